//! The preview tool: renders an OBJ file or a built-in scene with the library's own pipeline, as
//! the LCD will show it, and reports what the scene costs.
//!
//! `cargo run --release -p scanline3d-tools --bin render` renders the default scene (the benchmark torus) to
//! `scanline3d.png` and prints a one-line summary. `--help` lists every flag with its unit and
//! default. Every flag given is applied or refused (exit status 2, nothing written): the flags
//! each scene and mode does not use are listed in `tools/src/bin/render/rules.rs`. A frame in which
//! nothing could be drawn because every triangle was invalid is an error (exit status 1).

mod args;
mod budget;
use scanline3d_tools as common;
mod depth;
mod edges;
mod output;
mod rules;
mod shadow;
mod shadow_budget;
mod tone;

use std::path::Path;
use std::time::Instant;

use args::*;
use budget::{budget, capacity_name, short_capacities};
use clap::ValueEnum;
use common::compare::HostProbe;
use common::csg::load_csg;
use common::obj::{
    bounds, parse_obj, simplify, suggest_triangles, vertex_normals, NormalSource, ObjMesh,
};
use common::texture_io::load_png_texture;
use common::Frame;
use embedded_graphics::pixelcolor::{PixelColor, Rgb565, Rgb888, RgbColor};
use output::{compare, piece_mesh, plan, write_image};
use scanline3d::fixed::types::I16F16;
use scanline3d::internals::ram_formula;
use scanline3d::prelude::*;
use scanline3d::{
    errors::Capacity, Error, Needs, Stats, Texture, TextureMode, TexturedShape, Texturing,
};
use scanline3d_support::demo::{self, deg};
use scanline3d_support::metrics::Metrics;

/// Largest preview size and capacities (host only; `--budget` prints what a device needs): the
/// library's largest renderer (`Renderer`'s limits: 32 768 vertices, 32 767 triangles, 32 768
/// triangles active on one row).
const MAX_W: usize = 1024;
const MAX_H: usize = 1024;
/// With texture and Phong attribute stores for every vertex and 4 096 textured (or Phong)
/// triangles on one row.
type Big<S, C> = Renderer<S, C, MAX_W, MAX_H, 32768, 32767, 32768, 1, 32768, 4096>;
/// The same with one strip over the whole image, for a frame too large for one renderer: it is
/// drawn in passes ([`Renderer::render_passes`]), each a piece of the mesh that fits. Its lines
/// are 5 MB at 1024x1024 (made only when a frame needs them).
type Layered<S, C> = Renderer<S, C, MAX_W, MAX_H, 32768, 32767, 32768, MAX_H>;
/// The library's limits, the most any one renderer holds.
const LIMIT: Needs = Big::<f32, Rgb565>::CAPACITY;
/// Host time spent on the timing runs of one frame after which no more are made (the median
/// of fewer runs): a large model in a debug build takes seconds a frame.
const TIMING_BUDGET_S: f64 = 0.5;
/// Lights the tool supports (unused ones are zero vectors, which light nothing).
const LIGHTS: usize = 4;

/// The model in f64, before conversion to the pipeline's number type.
struct Model {
    name: String,
    positions: Vec<[f64; 3]>,
    normals: Vec<[f64; 3]>,
    indices: Vec<[u16; 3]>,
    /// Texture coordinates, one per vertex (with `--texture`).
    uvs: Option<Vec<[f64; 2]>>,
    /// What the simplification did (`--max-triangles`, `--max-vertices`).
    simplified: Option<String>,
}

fn model(args: &Args) -> Result<Model, String> {
    let file = match (&args.obj, &args.csg) {
        (Some(path), _) => Some((path, parse_obj(path)?)),
        (_, Some(path)) => Some((
            path,
            load_csg(path)?.to_obj_file(&path.display().to_string()),
        )),
        _ => None,
    };
    if let Some((path, file)) = file {
        let source = match args.normals {
            Some(NormalsArg::File) => {
                if !file.all_corners_have_normals {
                    return Err(format!(
                        "{}: --normals file, but the OBJ has no vn for every vertex",
                        path.display()
                    ));
                }
                NormalSource::File
            }
            Some(NormalsArg::FaceAverage) => NormalSource::FaceAverage,
            None => file.default_normals(),
        };
        let mut big = file
            .mesh_with(source, args.texture.is_some())
            .map_err(|e| {
                if args.texture.is_some() && !e.contains("only some") {
                    format!("{e} (--texture needs texture coordinates: vt on every face corner)")
                } else {
                    e
                }
            })?;
        let mut simplified = None;
        if args.max_triangles.is_some() || args.max_vertices.is_some() {
            let s = simplify(&big, args.max_triangles, args.max_vertices)
                .map_err(|e| format!("{}: {e}", file.name))?;
            simplified = Some(s.summary(&big));
            big = s.mesh;
        }
        let mesh: ObjMesh = big.to_u16(&file.name)?;
        let normals = vertex_normals(&mesh, source == NormalSource::File);
        return Ok(Model {
            name: path.display().to_string(),
            positions: mesh.positions,
            normals,
            indices: mesh.indices,
            uvs: big.uvs,
            simplified,
        });
    }
    fn from_shape<const V: usize, const T: usize>(
        name: &str,
        s: Shape<f64, V, T>,
        args: &Args,
    ) -> Model {
        let mesh = ObjMesh {
            positions: s.positions.to_vec(),
            normals: Some(s.normals.to_vec()),
            indices: s.indices.to_vec(),
        };
        let use_file = args.normals != Some(NormalsArg::FaceAverage);
        Model {
            name: name.into(),
            normals: vertex_normals(&mesh, use_file),
            positions: mesh.positions,
            indices: mesh.indices,
            uvs: None,
            simplified: None,
        }
    }
    let e = |e: scanline3d::errors::ShapeError| format!("shape: {e}");
    if args.texture.is_some() {
        // The textured shapes: the same geometry with texture coordinates (seams split).
        fn textured<const V: usize, const T: usize>(
            name: &str,
            s: TexturedShape<f64, V, T>,
            args: &Args,
        ) -> Model {
            let mut m = from_shape(name, s.shape, args);
            m.uvs = Some(s.uvs.to_vec());
            m
        }
        return Ok(match args.scene.unwrap_or(SceneArg::Torus) {
            SceneArg::Torus => textured(
                "torus",
                TexturedShape::<f64, 561, 1024>::torus(1.0, 0.4, 32, 16).map_err(e)?,
                args,
            ),
            SceneArg::Cube => textured(
                "cube",
                TexturedShape::<f64, 24, 12>::cube(1.0).map_err(e)?,
                args,
            ),
            SceneArg::Icosphere => textured(
                "icosphere",
                TexturedShape::<f64, 760, 1280>::icosphere(1.0, 3).map_err(e)?,
                args,
            ),
            SceneArg::Terrain => textured(
                "terrain",
                TexturedShape::<f64, 289, 512>::terrain(4.0, 16, 0.4).map_err(e)?,
                args,
            ),
            SceneArg::Shadow => return Err("--scene shadow takes no --texture".into()),
        });
    }
    Ok(match args.scene.unwrap_or(SceneArg::Torus) {
        SceneArg::Torus => from_shape("torus", demo::torus::<f64>().map_err(e)?, args),
        SceneArg::Cube => from_shape("cube", Shape::<f64, 24, 12>::cube(1.0).map_err(e)?, args),
        SceneArg::Icosphere => from_shape(
            "icosphere",
            Shape::<f64, 642, 1280>::icosphere(1.0, 3).map_err(e)?,
            args,
        ),
        SceneArg::Terrain => from_shape(
            "terrain",
            Shape::<f64, 289, 512>::terrain(4.0, 16, 0.4).map_err(e)?,
            args,
        ),
        // Drawn by `shadow::run` before a model is made.
        SceneArg::Shadow => return Err("--scene shadow is not a single model".into()),
    })
}

/// Camera, model placement and everything else a frame needs, in f64.
#[derive(Clone)]
struct Setup {
    /// The texture (`--texture`), loaded once.
    texture: Option<Texturing>,
    eye: [f64; 3],
    target: [f64; 3],
    up: [f64; 3],
    projection: Projection<f64>,
    /// Translation applied before the rotations (centres the model with --fit).
    centre: [f64; 3],
}

fn setup(args: &Args, m: &Model) -> Result<Setup, String> {
    let (w, h) = args.size;
    let texture = match &args.texture {
        None => None,
        Some(path) => {
            let png = load_png_texture(path)?;
            let texels: &'static [u16] = Box::leak(png.texels.into_boxed_slice());
            let texture = Texture::new(texels, png.width, png.height)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Some(
                Texturing::new(Box::leak(Box::new(texture)))
                    .with_mode(match args.texture_mode {
                        TexModeArg::Perspective => TextureMode::Subdivided16,
                        TexModeArg::Perspective8 => TextureMode::Subdivided8,
                        TexModeArg::Exact => TextureMode::PerPixel,
                        TexModeArg::Affine => TextureMode::Affine,
                    })
                    .with_key(png.key),
            )
        }
    };
    let mut s = Setup {
        texture,
        eye: args.eye,
        target: args.target,
        up: args.up,
        projection: match args.ortho {
            Some(height) => Projection::Orthographic {
                height,
                near: args.near,
                far: args.far,
            },
            None => Projection::Perspective {
                fov_y: args.fov_y.to_radians(),
                near: args.near,
                far: args.far,
            },
        },
        centre: [0.0; 3],
    };
    if args.fit {
        let (_, _, c, r) = bounds(&m.positions);
        let r = r.max(1e-9);
        s.centre = c;
        let dir = scanline3d::math::normalize(scanline3d::math::sub(args.eye, args.target));
        let dir = if dir == [0.0; 3] {
            [0.0, 0.0, 1.0]
        } else {
            dir
        };
        // The sphere fills the smaller of the two view angles.
        let half = (args.fov_y.to_radians() / 2.0)
            .min(((args.fov_y.to_radians() / 2.0).tan() * w as f64 / h as f64).atan());
        let dist = match args.ortho {
            Some(_) => 3.0 * r,
            None => r / half.sin(),
        };
        s.target = [0.0; 3];
        s.eye = dir.map(|d| d * dist);
        let (near, far) = ((dist - 1.05 * r).max(dist * 1e-3), dist + 1.05 * r);
        s.projection = match args.ortho {
            // `--ortho` is a factor on the fitted height.
            Some(factor) => Projection::Orthographic {
                height: 2.1 * r * (h as f64 / w.min(h) as f64) * factor,
                near,
                far,
            },
            None => Projection::Perspective {
                fov_y: args.fov_y.to_radians(),
                near,
                far,
            },
        };
    }
    Camera::look_at(s.eye, s.target, s.up, s.projection).map_err(|e| {
        format!("{e} (check --eye, --target, --up, --fov-y, --near, --far, --ortho)")
    })?;
    Ok(s)
}

/// The model transform of `frame`. Angles are reduced modulo 360° first (exact for floats, and
/// a no-op below 360°), so a large `--rotate-*` or `--spin` × frame stays within the
/// fixed-point range instead of saturating.
fn transform<S: Scalar>(args: &Args, s: &Setup, frame: usize) -> Mat4<S> {
    let c = s.centre.map(|v| S::from_f64(-v));
    Mat4::translate(c)
        .then(&Mat4::rotate_x(deg(args.rotate_x % 360.0)))
        .then(&Mat4::rotate_y(deg(args.rotate_y % 360.0)))
        .then(&Mat4::rotate_z(deg(args.rotate_z % 360.0)))
        .then(&Mat4::rotate_y(deg((args.spin * frame as f64) % 360.0)))
}

fn lights<S: Scalar>(args: &Args) -> [Light<S>; LIGHTS] {
    let mut l = [Light {
        direction: [S::ZERO; 3],
        color: [255; 3],
    }; LIGHTS];
    let dirs = if args.light.is_empty() {
        vec![[-1.0, 1.0, 1.0]]
    } else {
        args.light.clone()
    };
    for (k, d) in dirs.iter().take(LIGHTS).enumerate() {
        l[k].direction = rules::light_direction(*d).map(S::from_f64);
    }
    l
}

struct Run<C> {
    frames: Vec<Frame<C>>,
    /// Per frame; for a frame drawn in passes, the passes' counts added up
    /// ([`Renderer::render_passes`]).
    stats: Vec<Stats>,
    /// Per frame, what one renderer drawing it in one pass needs: for a frame drawn in passes,
    /// the mesh's vertices plus every pass's clipper and face-colour vertices, every pass's
    /// stored triangles, and (an upper bound) the passes' largest active counts added up.
    needs: Vec<Needs>,
    /// Per frame, the number of passes it was drawn in (1: one `render`).
    passes: Vec<usize>,
    ns_per_frame: f64,
    /// `--budget`: whether the frames need the depth lines.
    depth: Option<depth::Summary>,
}

/// What a frame's scenes share: the camera, lights and background, the model's transform and
/// material.
struct FrameSetup<'p, S: Scalar> {
    camera: Camera<S>,
    lights: [Light<S>; LIGHTS],
    effects: Effects<'p, S>,
    background: [u8; 3],
    transform: Mat4<S>,
    material: Material<S>,
}

impl<S: Scalar> FrameSetup<'_, S> {
    fn object<'a>(&self, mesh: Mesh<'a, S>) -> [Object<'a, S>; 1] {
        [Object {
            mesh,
            transform: self.transform,
            material: self.material,
        }]
    }

    fn scene<'a>(&'a self, objects: &'a [Object<'a, S>]) -> Scene<'a, S, LIGHTS>
    where
        Self: 'a,
    {
        let mut scene =
            Scene::new(objects, self.camera, self.lights).with_background(self.background);
        if !self.effects.point_lights.is_empty()
            || self.effects.fog.is_some()
            || self.effects.tone.is_some()
        {
            scene = scene.with_effects(&self.effects);
        }
        scene
    }
}

fn run<S: Scalar, C: TargetColor>(
    args: &Args,
    m: &Model,
    s: &Setup,
    timed_runs: usize,
) -> Result<Run<C>, String> {
    let (w, h) = args.size;
    let pos: Vec<[S; 3]> = m.positions.iter().map(|p| p.map(S::from_f64)).collect();
    let nor: Vec<[S; 3]> = m.normals.iter().map(|p| p.map(S::from_f64)).collect();
    let mesh = Mesh::new(&pos, &m.indices).map_err(|e| format!("{}: {e}", m.name))?;
    let mesh = mesh
        .with_normals(&nor)
        .map_err(|e| format!("{}: {e}", m.name))?;
    let uvs: Vec<[S; 2]> = m.uvs.iter().flatten().map(|t| t.map(S::from_f64)).collect();
    let mesh = if m.uvs.is_some() {
        mesh.with_uvs(&uvs)
            .map_err(|e| format!("{}: {e}", m.name))?
    } else {
        mesh
    };
    let projection = match s.projection {
        Projection::Perspective { fov_y, near, far } => Projection::Perspective {
            fov_y: S::from_f64(fov_y),
            near: S::from_f64(near),
            far: S::from_f64(far),
        },
        Projection::Orthographic { height, near, far } => Projection::Orthographic {
            height: S::from_f64(height),
            near: S::from_f64(near),
            far: S::from_f64(far),
        },
    };
    let camera = Camera::look_at(
        s.eye.map(S::from_f64),
        s.target.map(S::from_f64),
        s.up.map(S::from_f64),
        projection,
    )
    .map_err(|e| {
        format!(
            "in {}: {e} (the flags are valid in f64 but not in this number type: try --number f32 or f64)",
            S::NAME
        )
    })?;
    let material = Material {
        color: args.color,
        ambient: S::from_f64(args.ambient),
        diffuse: S::from_f64(args.diffuse),
        specular: S::from_f64(args.specular),
        shininess: args.shininess,
        shading: match args.shading {
            ShadingArg::Flat => Shading::Flat,
            ShadingArg::Gouraud => Shading::Gouraud,
            ShadingArg::Phong => Shading::Phong,
            ShadingArg::FastPhong => Shading::FastPhong,
            ShadingArg::Toon => Shading::Toon {
                bands: std::num::NonZeroU8::new(args.bands).unwrap_or(std::num::NonZeroU8::MIN),
            },
            ShadingArg::Wireframe => Shading::Flat,
        },
        texture: s.texture,
        alpha: 255,
    };
    let material = if args.shading == ShadingArg::Wireframe {
        Material::unlit(args.background)
    } else {
        material
    };
    let mut edge_frames = edges::EdgeFrames::new(args, &m.name, &mesh)?;
    let mut auto = tone::auto(args);
    let mut r: Box<Big<S, C>> = Box::default();
    r.set_viewport(w, h);
    r.set_dither(args.dither == OnOff::On);
    // Made when a frame does not fit `r`.
    let mut layered: Option<Box<Layered<S, C>>> = None;
    let mut out = Run {
        frames: Vec::new(),
        stats: Vec::new(),
        needs: Vec::new(),
        passes: Vec::new(),
        ns_per_frame: 0.0,
        depth: None,
    };
    let mut depth_check = depth::DepthCheck::<S, C>::new(args, s.texture.is_some());
    let mut times = Vec::new();
    let points: Vec<PointLight<S>> = args
        .point_light
        .iter()
        .map(|p| {
            let [c, l, q] = p.attenuation.map(S::from_f64);
            PointLight::new(p.position.map(S::from_f64), p.color).attenuation(c, l, q)
        })
        .collect();
    let frame_setup = |k: usize, auto: Option<&scanline3d::tone::AutoExposure>| FrameSetup {
        camera,
        lights: lights::<S>(args),
        effects: Effects {
            point_lights: &points,
            fog: args
                .fog
                .map(|f| Fog::linear(S::from_f64(f.near), S::from_f64(f.far), f.color)),
            tone: tone::tone_map(args, auto),
        },
        background: args.background,
        transform: transform::<S>(args, s, k),
        material,
    };
    for k in 0..args.frames {
        if let Some(a) = auto.as_mut() {
            // `--exposure auto`: adapted at the first pose first, then to each frame before.
            let (pose, n) = if k == 0 {
                (0, tone::AUTO_WARMUP)
            } else {
                (k - 1, 1)
            };
            for _ in 0..n {
                let fs = frame_setup(pose, Some(a));
                let objects = fs.object(mesh);
                tone::adapt(a, &mut r, &fs.scene(&objects), (w, h));
            }
        }
        let fs = frame_setup(k, auto.as_ref());
        let objects = fs.object(mesh);
        let scene = fs.scene(&objects);
        let mut f = Frame::new(w as u32, h as u32, C::from_channels([0; 3]));
        // Up to `timed_runs` runs, fewer once they took `TIMING_BUDGET_S`.
        let mut timed = |render: &mut dyn FnMut() -> f64| {
            let mut spent = 0.0;
            for _ in 0..timed_runs {
                let ns = render();
                times.push(ns);
                spent += ns / 1e9;
                if spent > TIMING_BUDGET_S {
                    break;
                }
            }
        };
        if let Some(e) = edge_frames.as_mut() {
            let stats = e
                .draw(&mut r, &scene, &mut f)
                .map_err(|msg| format!("{}: {msg}", m.name))?;
            timed(&mut || e.draw_timed(&mut r, &scene, (w, h)));
            out.needs.push(Needs::from_stats(&stats));
            out.stats.push(stats);
            out.passes.push(1);
            out.frames.push(f);
            continue;
        }
        let one_pass = match args.pass_triangles {
            None => r.render(&scene, &mut f).map(Some),
            Some(_) => Ok(None),
        };
        match one_pass {
            Ok(Some(mut stats)) => {
                if let Some(d) = depth_check.as_mut() {
                    if args.budget {
                        d.check(&scene, &f, args.background)
                            .map_err(|e| format!("{}: {e}", m.name))?;
                    }
                    if let Some(s) = d
                        .draw(args, &scene, &mut f)
                        .map_err(|e| format!("{}: {e}", m.name))?
                    {
                        stats = s;
                    }
                }
                let mut sink = scanline3d_support::hash::NullTarget::<C>::new(w as u32, h as u32);
                let mut t = HostProbe::timer();
                match depth_check.as_mut() {
                    Some(d) if args.depth != depth::DepthArg::Zbuffer => timed(&mut || {
                        t = HostProbe::timer();
                        let _ = d.renderer().render_with(
                            &scene,
                            scanline3d::FrameOptions::new().probe(&mut t),
                            &mut sink,
                        );
                        t.total().as_nanos() as f64
                    }),
                    _ => timed(&mut || {
                        t = HostProbe::timer();
                        let _ = r.render_with(
                            &scene,
                            scanline3d::FrameOptions::new().probe(&mut t),
                            &mut sink,
                        );
                        t.total().as_nanos() as f64
                    }),
                }
                out.needs.push(Needs::from_stats(&stats));
                out.stats.push(stats);
                out.passes.push(1);
            }
            // Textures and Phong need one renderer's attribute stores: no passes.
            Err(Error::Shortfall(sf)) if material.needs_attribute_stores() => {
                return Err(format!(
                    "{}: {sf}: a textured or Phong frame is drawn in one pass; simplify the \
                     model (--max-triangles)",
                    m.name
                ));
            }
            // More than one renderer holds: drawn in passes, each a piece of the mesh that fits.
            Ok(None) | Err(Error::Shortfall(_)) => {
                let lr = layered.get_or_insert_with(|| {
                    let mut l: Box<Layered<S, C>> = Box::default();
                    l.set_viewport(w, h);
                    l.set_dither(args.dither == OnOff::On);
                    l
                });
                let first = args.pass_triangles.unwrap_or(m.indices.len());
                let pieces = plan(lr, m, &pos, &nor, &fs, first)?;
                let objects = pieces
                    .iter()
                    .map(|(p, _)| piece_mesh(m, p).map(|mesh| fs.object(mesh)))
                    .collect::<Result<Vec<_>, _>>()?;
                let scenes: Vec<_> = objects.iter().map(|o| fs.scene(o)).collect();
                let stats = lr
                    .render_passes(&scenes, &mut f)
                    .map_err(|e| format!("{}: {e}", m.name))?;
                timed(&mut || {
                    let mut sink =
                        scanline3d_support::hash::NullTarget::<C>::new(w as u32, h as u32);
                    let t = Instant::now();
                    let _ = lr.render_passes(&scenes, &mut sink);
                    t.elapsed().as_nanos() as f64
                });
                // A vertex shared by pieces is in each piece's arrays: counted once here.
                let copies: usize = pieces.iter().map(|(p, _)| p.positions.len()).sum();
                let sum = |f: fn(&Needs) -> usize| pieces.iter().map(|(_, n)| f(n)).sum::<usize>();
                out.needs.push(Needs::new(
                    m.positions.len() + sum(|n| n.vertices) - copies,
                    sum(|n| n.triangles),
                    sum(|n| n.active),
                ));
                out.stats.push(stats);
                out.passes.push(pieces.len());
            }
            Err(e) => return Err(format!("{}: {e}", m.name)),
        }
        out.frames.push(f);
    }
    times.sort_by(|a, b| a.total_cmp(b));
    out.ns_per_frame = times.get(times.len() / 2).copied().unwrap_or(0.0);
    out.depth = depth_check.map(|d| d.summary);
    Ok(out)
}

fn main() {
    let args = Args::from_command_line();
    // The preview renderer is large (it accepts any OBJ up to 65 536 vertices): give it room.
    let worker = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || main2(args));
    let code = match worker.map(|h| h.join()) {
        Ok(Ok(Ok(()))) => 0,
        Ok(Ok(Err((msg, code)))) => {
            eprintln!("render: {msg}");
            code
        }
        _ => {
            eprintln!("render: internal error");
            3
        }
    };
    std::process::exit(code);
}

fn main2(args: Args) -> Result<(), (String, i32)> {
    check_flags(&args).map_err(|e| (e, 2))?;
    // Every flag given is applied or refused.
    rules::check(&args).map_err(|e| (e, 2))?;
    if args.scene == Some(SceneArg::Shadow) {
        return shadow::run(&args);
    }
    let m = model(&args).map_err(|e| (e, 2))?;
    let s = setup(&args, &m).map_err(|e| (e, 2))?;
    match args.format {
        FormatArg::Rgb565 => go::<Rgb565>(&args, &m, &s),
        FormatArg::Rgb888 => go::<Rgb888>(&args, &m, &s),
    }
}

fn go<C: TargetColor + RgbColor + Into<Rgb888>>(
    args: &Args,
    m: &Model,
    s: &Setup,
) -> Result<(), (String, i32)> {
    let timed = if args.budget {
        0
    } else {
        21.min(2 + 60 / args.frames)
    };
    let t0 = Instant::now();
    match args.number {
        NumberArg::Fixed => rules::check_numbers::<Fx<I16F16>>(args),
        NumberArg::F32 => rules::check_numbers::<f32>(args),
        NumberArg::F64 => rules::check_numbers::<f64>(args),
    }
    .map_err(|e| (e, 2))?;
    let tested = match args.number {
        NumberArg::Fixed => run::<Fx<I16F16>, C>(args, m, s, timed),
        NumberArg::F32 => run::<f32, C>(args, m, s, timed),
        NumberArg::F64 => run::<f64, C>(args, m, s, timed),
    }
    .map_err(|e| (e, 1))?;
    let name = match args.number {
        NumberArg::Fixed => "I16F16",
        NumberArg::F32 => "f32",
        NumberArg::F64 => "f64",
    };
    if args.budget {
        return budget::<C>(args, m, s, &tested, name);
    }
    if let Some((k, st)) = rules::nothing_drawn(&tested.stats) {
        return Err((
            format!(
                "{}: nothing drawn in frame {k} of {}: all {} triangle(s) left after culling \
                 were invalid in {name} (a vertex NaN, infinite or out of the number type's \
                 range after the model, view or projection transform{}); no image written: see \
                 `--budget` for the margins, scale the model down (--fit) or use --number f32",
                m.name,
                tested.stats.len(),
                st.invalid,
                if args.number == NumberArg::Fixed {
                    ": Q16.16 holds ±32768"
                } else {
                    ""
                }
            ),
            1,
        ));
    }
    let reference = run::<f64, C>(args, m, s, 0).map_err(|e| (e, 1))?;
    let metrics = compare(
        &tested.frames,
        &reference.frames,
        scanline3d::color::quantize::<C>(args.background),
    );
    write_image(&args.out, &tested.frames, 40).map_err(|e| (e, 1))?;
    if let Some(note) = &m.simplified {
        println!("{}: {note}", m.name);
    }
    let st = tested.stats[0];
    let (w, h) = args.size;
    let need = |f: fn(&Stats) -> u32| tested.stats.iter().map(f).max().unwrap_or(0) as usize;
    let needs = tested.needs.iter().fold(Needs::default(), |a, n| a.max(*n));
    let passes = tested.passes.iter().copied().max().unwrap_or(1);
    let short: Vec<String> = short_capacities(&needs, passes > 1)
        .iter()
        .map(|&(what, needed, limit, bound)| {
            format!(
                "{}{needed} {} (of {limit})",
                if bound { "up to " } else { "" },
                capacity_name(what)
            )
        })
        .collect();
    let ram = if !short.is_empty() {
        // Said on the note line below.
        format!("renderer RAM: no renderer holds this scene (drawn in {passes} passes here)")
    } else {
        format!(
            "renderer RAM {} B for this scene ({} lines)",
            ram_formula(
                w,
                h,
                core::mem::size_of::<C>(),
                args.strip,
                needs.vertices,
                needs.triangles,
                needs.active,
            ) - if args.depth == depth::DepthArg::Zbuffer {
                0
            } else {
                // No depth lines.
                args.strip * w * 2
            },
            args.strip
        )
    };
    if !short.is_empty() {
        println!(
            "{}: drawn in {passes} passes (pieces of the mesh, one depth buffer): one frame needs \
             {}, more than one renderer holds; `--budget` says what a device needs, \
             `--max-triangles N` previews it simplified",
            m.name,
            short.join(" and ")
        );
    } else if passes > 1 {
        println!("{}: drawn in {passes} passes (--pass-triangles)", m.name);
    }
    // Triangles skipped as invalid (a vertex out of the number type's range, NaN or infinite):
    // frame 0's count, as the other counts, and the largest of any frame when it differs.
    let invalid_max = need(|s| s.invalid);
    let invalid = if invalid_max > st.invalid as usize {
        format!("{} (up to {invalid_max} in a frame)", st.invalid)
    } else {
        st.invalid.to_string()
    };
    println!(
        "{}: {w}x{h} {name} {}{} | triangles in {} / culled {} / clipped {} / drawn {} / invalid {invalid} | pixels written {} | {:.3} ms/frame (host, median) | vs f64: max LSB r{} g{} b{}, PSNR {}, {} coverage mismatches | {ram} | {:.1} s",
        args.out.display(),
        m.name,
        if tested.frames.len() > 1 { format!(", {} frames", tested.frames.len()) } else { String::new() },
        st.triangles_in,
        st.culled,
        st.clipped,
        st.drawn,
        st.pixels_written,
        tested.ns_per_frame / 1e6,
        metrics.max_lsb[0],
        metrics.max_lsb[1],
        metrics.max_lsb[2],
        if metrics.psnr_db().is_finite() { format!("{:.1} dB", metrics.psnr_db()) } else { "∞ (identical)".into() },
        metrics.coverage_mismatch,
        t0.elapsed().as_secs_f64(),
    );
    if invalid_max > 0 {
        eprintln!(
            "render: warning: {}: {invalid_max} triangle(s) skipped as invalid in {name}: a vertex \
             NaN, infinite or out of the number type's range{}; see `--budget` for the margins, \
             scale the model down (--fit) or use --number f32",
            m.name,
            if args.number == NumberArg::Fixed { " (Q16.16 holds ±32768)" } else { "" }
        );
    }
    Ok(())
}
