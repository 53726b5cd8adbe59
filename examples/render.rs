//! The preview tool: renders an OBJ file or a built-in scene with the library's own pipeline, as
//! the LCD will show it, and reports what the scene costs.
//!
//! `cargo run --release --example render` renders the default scene (the benchmark torus) to
//! `scanline3d.png` and prints a one-line summary. `--help` lists every flag.

#[path = "../tests/common/mod.rs"]
mod common;
#[path = "render_parts/depth.rs"]
mod depth;
#[path = "render_parts/edges.rs"]
mod edges;
#[path = "render_parts/shadow.rs"]
mod shadow;
#[path = "render_parts/tone.rs"]
mod tone;

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Parser, ValueEnum};
use common::compare::Timer;
use common::csg::load_csg;
use common::obj::{
    bounds, parse_obj, simplify, suggest_triangles, vertex_normals, NormalSource, ObjMesh,
};
use common::texture_io::load_png_texture;
use common::Frame;
use embedded_graphics::pixelcolor::{PixelColor, Rgb565, Rgb888, RgbColor};
use scanline3d::demo::{self, deg};
use scanline3d::fixed::types::I16F16;
use scanline3d::internals::ram_formula;
use scanline3d::metrics::Metrics;
use scanline3d::prelude::*;
use scanline3d::{Capacity, Error, Needs, Stats, Texture, TextureMode, TexturedShape, Texturing};

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
/// Most frames one run renders. Every frame is kept in memory twice (the tested number type
/// and the f64 reference) until the animated image is written, and each is rendered up to
/// three times (timing): 1 000 frames is 40 s of animation at the image's 25 frames/s, a full
/// turn even at a 0.36° `--spin`, and about 230 MB and a few seconds (release) at 240x240.
const MAX_FRAMES: usize = 1000;
/// Most pixels over all frames (frames × width × height, 64 Mi): bounds the memory of a large
/// animation (about 400 MB in Rgb888 for both copies) — 1 000 frames at 240x240, 64 at 1024x1024.
const MAX_FRAME_PIXELS: usize = 1 << 26;
/// Largest material coefficient: with a material channel ≥ 1 (of 255), a coefficient of 255
/// already saturates the channel, so larger ones change nothing but the fixed-point headroom.
const MAX_COEFFICIENT: f64 = 255.0;

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum SceneArg {
    Torus,
    Cube,
    Icosphere,
    Terrain,
    /// A torus and a cube above a ground square (the `shadow` benchmark scene): --shadow,
    /// --shadow-plane, --alpha and --outline apply to it
    Shadow,
}

/// How `--scene shadow` draws its shadow.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum ShadowArg {
    /// No shadow
    None,
    /// The models' triangles projected onto the shadow plane along the light, stencilled (each
    /// ground pixel darkened once)
    Projected,
    /// A soft round blob under each model (nested discs; the seeds' cheapest method)
    Blob,
    /// Shadow volumes of the models (stencil counting, z-fail): on the ground, on each other
    /// and on themselves
    Volume,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum ShadingArg {
    Flat,
    Gouraud,
    /// Lit at every pixel
    Phong,
    /// Phong lit every 8 pixels, linear between
    FastPhong,
    /// Lines along the edges (--edges, default all) over surfaces unlit in the background
    /// colour, which hide the lines behind them (unless --see-through)
    Wireframe,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum TexModeArg {
    /// Perspective-correct every 16 pixels (TextureMode::Subdivided16)
    Perspective,
    /// Perspective-correct every 8 pixels (TextureMode::Subdivided8)
    Perspective8,
    /// Perspective-correct at every pixel (TextureMode::PerPixel)
    Exact,
    /// Linear in screen space (TextureMode::Affine)
    Affine,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum NormalsArg {
    FaceAverage,
    File,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum NumberArg {
    Fixed,
    F32,
    F64,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum FormatArg {
    Rgb565,
    Rgb888,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum OnOff {
    On,
    Off,
}

fn v3(s: &str) -> Result<[f64; 3], String> {
    match numbers(s)?[..] {
        [x, y, z] => Ok([x, y, z]),
        _ => Err(format!("{s:?}: expected three finite numbers x,y,z")),
    }
}

/// `--point-light`: position, colour, attenuation.
#[derive(Copy, Clone, Debug, PartialEq)]
struct PointArg {
    position: [f64; 3],
    color: [u8; 3],
    attenuation: [f64; 3],
}

/// `--fog`: view depths and colour.
#[derive(Copy, Clone, Debug, PartialEq)]
struct FogArg {
    near: f64,
    far: f64,
    color: [u8; 3],
}

/// Comma-separated finite numbers.
pub(crate) fn numbers(s: &str) -> Result<Vec<f64>, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{s:?}: {e}"))?;
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        return Err(format!("{s:?}: {x} is not a finite number"));
    }
    Ok(v)
}

/// A colour channel 0-255 given as a number.
fn channel(s: &str, v: f64) -> Result<u8, String> {
    if v.fract() != 0.0 || !(0.0..=255.0).contains(&v) {
        return Err(format!(
            "{s:?}: colour channels are integers 0-255, got {v}"
        ));
    }
    Ok(v as u8)
}

fn point_light(s: &str) -> Result<PointArg, String> {
    let v = numbers(s)?;
    if ![3, 6, 9].contains(&v.len()) {
        return Err(format!(
            "{s:?}: expected x,y,z or x,y,z,r,g,b or x,y,z,r,g,b,c,l,q ({} numbers given)",
            v.len()
        ));
    }
    let color = if v.len() >= 6 {
        [channel(s, v[3])?, channel(s, v[4])?, channel(s, v[5])?]
    } else {
        [255; 3]
    };
    let attenuation = if v.len() == 9 {
        [v[6], v[7], v[8]]
    } else {
        [1.0, 0.0, 0.0]
    };
    if attenuation
        .iter()
        .any(|&a| !(0.0..=MAX_ATTENUATION).contains(&a))
    {
        return Err(format!(
            "{s:?}: attenuation coefficients must be in [0, {MAX_ATTENUATION}]"
        ));
    }
    Ok(PointArg {
        position: [v[0], v[1], v[2]],
        color,
        attenuation,
    })
}

fn fog(s: &str) -> Result<FogArg, String> {
    let v = numbers(s)?;
    let [near, far, r, g, b] = v[..] else {
        return Err(format!(
            "{s:?}: expected near,far,r,g,b ({} numbers given)",
            v.len()
        ));
    };
    if near >= far {
        return Err(format!(
            "{s:?}: the fog's near depth must be below its far depth"
        ));
    }
    Ok(FogArg {
        near,
        far,
        color: [channel(s, r)?, channel(s, g)?, channel(s, b)?],
    })
}

/// The largest attenuation coefficient (what Phong spans store, Q5.16).
const MAX_ATTENUATION: f64 = 31.0;

fn rgb(s: &str) -> Result<[u8; 3], String> {
    let v: Vec<u8> = s
        .split(',')
        .map(|x| x.trim().parse::<u8>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{s:?}: {e} (channels are 0-255)"))?;
    match v[..] {
        [r, g, b] => Ok([r, g, b]),
        _ => Err(format!("{s:?}: expected r,g,b")),
    }
}

fn size(s: &str) -> Result<(usize, usize), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("{s:?}: expected WxH, e.g. 240x240"))?;
    let (w, h) = (
        w.parse::<usize>().map_err(|e| format!("{s:?}: {e}"))?,
        h.parse::<usize>().map_err(|e| format!("{s:?}: {e}"))?,
    );
    if !(1..=MAX_W).contains(&w) || !(1..=MAX_H).contains(&h) {
        return Err(format!("{s:?}: width and height must be 1-{MAX_W}"));
    }
    Ok((w, h))
}

/// Renders an OBJ file or a built-in scene as a 240×240 RGB565 LCD would show it (through the
/// library's own pipeline), and reports what the scene costs.
#[derive(Parser, Debug, Clone)]
#[command(name = "render", version)]
struct Args {
    /// OBJ file to render (triangulated; v/vt/vn and negative indices accepted)
    #[arg(long, value_name = "FILE", conflicts_with = "scene")]
    obj: Option<PathBuf>,
    /// CSG tree to mesh and render (format: tests/common/csg.rs; e.g. examples/csg/part.csg);
    /// corners get crease-angle normals (edges sharper than 40° stay hard)
    #[arg(long, value_name = "FILE", conflicts_with_all = ["scene", "obj"])]
    csg: Option<PathBuf>,
    /// Built-in scene [default: torus]
    #[arg(long, value_enum)]
    scene: Option<SceneArg>,
    /// Centre the model and place the camera so that its bounding sphere fills the view
    #[arg(long)]
    fit: bool,
    /// Image size in pixels, WxH (up to 1024x1024)
    #[arg(long, value_parser = size, default_value = "240x240")]
    size: (usize, usize),
    /// Camera position, world units
    #[arg(long, allow_hyphen_values = true, value_parser = v3, default_value = "0,1.2,3")]
    eye: [f64; 3],
    /// Point the camera looks at, world units
    #[arg(long, allow_hyphen_values = true, value_parser = v3, default_value = "0,0,0")]
    target: [f64; 3],
    /// Camera up direction
    #[arg(long, allow_hyphen_values = true, value_parser = v3, default_value = "0,1,0")]
    up: [f64; 3],
    /// Vertical field of view, degrees, in (0, 180)
    #[arg(long = "fov-y", allow_hyphen_values = true, default_value_t = 45.0)]
    fov_y: f64,
    /// Near plane distance, world units, > 0
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.1)]
    near: f64,
    /// Far plane distance, world units, > --near
    #[arg(long, allow_hyphen_values = true, default_value_t = 10.0)]
    far: f64,
    /// Parallel projection with this view height (world units, > 0) instead of perspective
    #[arg(long, value_name = "HEIGHT", allow_hyphen_values = true)]
    ortho: Option<f64>,
    /// Model rotation about X, degrees (applied first)
    #[arg(long = "rotate-x", allow_hyphen_values = true, default_value_t = 30.0)]
    rotate_x: f64,
    /// Model rotation about Y, degrees (applied second)
    #[arg(long = "rotate-y", allow_hyphen_values = true, default_value_t = 20.0)]
    rotate_y: f64,
    /// Model rotation about Z, degrees (applied third)
    #[arg(long = "rotate-z", allow_hyphen_values = true, default_value_t = 0.0)]
    rotate_z: f64,
    /// Direction toward a light, world space (not 0,0,0); repeat for up to 4 lights [default: -1,1,1]
    #[arg(long, allow_hyphen_values = true, value_parser = v3)]
    light: Vec<[f64; 3]>,
    /// A point light: position x,y,z (world units), then optionally its colour r,g,b (0-255,
    /// default white) and attenuation constant,linear,quadratic (default 1,0,0): the light is
    /// scaled by 1/max(1, c + l·d + q·d²) at distance d; repeat for more (Phong objects use the
    /// first 2)
    #[arg(long = "point-light", value_name = "X,Y,Z[,R,G,B[,C,L,Q]]", allow_hyphen_values = true, value_parser = point_light)]
    point_light: Vec<PointArg>,
    /// Linear depth fog: none before view depth NEAR, only fog colour r,g,b beyond FAR
    #[arg(long, value_name = "NEAR,FAR,R,G,B", allow_hyphen_values = true, value_parser = fog)]
    fog: Option<FogArg>,
    /// Ambient coefficient, 0-255
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.15)]
    ambient: f64,
    /// Diffuse coefficient, 0-255
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.85)]
    diffuse: f64,
    /// Specular coefficient, 0-255 (0 = none)
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    specular: f64,
    /// Phong exponent (1-255)
    #[arg(long, default_value_t = 16)]
    shininess: u8,
    /// Model colour r,g,b (0-255)
    #[arg(long, value_parser = rgb, default_value = "255,160,64")]
    color: [u8; 3],
    /// Background colour r,g,b (0-255)
    #[arg(long, value_parser = rgb, default_value = "0,0,0")]
    background: [u8; 3],
    /// Shading mode
    #[arg(long, value_enum, default_value = "gouraud")]
    shading: ShadingArg,
    /// Texture image (PNG, power-of-two sides up to 1024): multiplies the lit colour (use
    /// --color 255,255,255 for the image's own colours); the OBJ needs vt, the built-in scenes
    /// have texture coordinates; transparent pixels are not drawn
    #[arg(long, value_name = "FILE.png")]
    texture: Option<PathBuf>,
    /// How textured spans find their texture coordinates
    #[arg(long, value_enum, default_value = "perspective", requires = "texture")]
    texture_mode: TexModeArg,
    /// Vertex normals: averaged from the faces, or the OBJ's own vn [default: file when the OBJ has them]
    #[arg(long, value_enum)]
    normals: Option<NormalsArg>,
    /// Number type of the geometry pipeline
    #[arg(long, value_enum, default_value = "fixed")]
    number: NumberArg,
    /// Pixel format of the simulated display
    #[arg(long, value_enum, default_value = "rgb565")]
    format: FormatArg,
    /// 4×4 ordered dithering of Gouraud gradients
    #[arg(long, value_enum, default_value = "off")]
    dither: OnOff,
    /// Lines per strip for the RAM figures, 1 to the image height (the image is the same for
    /// every strip height)
    #[arg(long, value_name = "LINES", default_value_t = 1)]
    strip: usize,
    /// The shadow of `--scene shadow` (default: projected; none with --shading wireframe)
    #[arg(long, value_enum)]
    shadow: Option<ShadowArg>,
    /// The plane `--scene shadow`'s shadow falls on, a·x + b·y + c·z + d = 0 (default 0,1,0,0:
    /// the ground; the ground receives it only where it lies in that plane)
    #[arg(long = "shadow-plane", value_name = "A,B,C,D", allow_hyphen_values = true, value_parser = shadow::plane)]
    shadow_plane: Option<[f64; 4]>,
    /// Opacity of `--scene shadow`'s torus, 0-255 (default 255: opaque): below 255 it is
    /// blended over what is behind it
    #[arg(long, value_name = "A")]
    alpha: Option<u8>,
    /// Outlines of `--scene shadow`'s models (their contour edges from the eye), 1 px, in this
    /// colour
    #[arg(long, value_name = "R,G,B", value_parser = rgb)]
    outline: Option<[u8; 3]>,
    /// How depth is resolved: the Z-buffer, or without depth lines in the painter's order or in
    /// any order (flat and Gouraud models without edges; `--budget` says which one a scene
    /// needs)
    #[arg(long, value_enum, default_value = "zbuffer")]
    depth: depth::DepthArg,
    /// Edges drawn over the model (1 px, hidden behind nearer surfaces unless --see-through)
    /// [default: none; all with --shading wireframe]
    #[arg(long, value_enum)]
    edges: Option<edges::EdgesArg>,
    /// The edges' colour [default: black; the model's --color with --shading wireframe]
    #[arg(long = "edge-color", value_name = "R,G,B", value_parser = rgb)]
    edge_color: Option<[u8; 3]>,
    /// `--edges crease`: an edge whose two faces meet at more than this angle, degrees
    #[arg(long = "crease-angle", value_name = "DEG", default_value_t = 40.0)]
    crease_angle: f64,
    /// Edges hidden behind surfaces are drawn too (and those of faces turned away)
    #[arg(long = "see-through")]
    see_through: bool,
    /// HDR: the tone curve mapping the lit radiance to the display [default: clamp when
    /// --exposure or --light-intensity is given]
    #[arg(long, value_enum)]
    tone: Option<tone::ToneArg>,
    /// HDR: the radiance's factor before the tone curve (above 0, at most 16), or `auto`: adapted
    /// frame by frame toward a mean luma of 96 from the previous frame's pixels (first over 16
    /// frames at the first frame's pose)
    #[arg(long, value_name = "E|auto", value_parser = tone::exposure)]
    exposure: Option<tone::ExposureArg>,
    /// HDR: every light's brightness factor (0 to 16; 1 = as its colour says)
    #[arg(long = "light-intensity", value_name = "X")]
    light_intensity: Option<f64>,
    /// Output image (.png; with --frames > 1 an animated .png or .gif)
    #[arg(long, value_name = "FILE", default_value = "scanline3d.png")]
    out: PathBuf,
    /// Number of frames (an animation about the Y axis), 1-1000, and at most 64 Mi pixels over
    /// all frames (e.g. 64 frames at 1024x1024)
    #[arg(long, default_value_t = 1)]
    frames: usize,
    /// Rotation about Y between frames, degrees
    #[arg(long, allow_hyphen_values = true, default_value_t = 10.0)]
    spin: f64,
    /// Report what the scene needs (capacities, fixed-point headroom, RAM) over every frame,
    /// print the renderer type for firmware, and fail if a format or capacity overflows
    #[arg(long)]
    budget: bool,
    /// Simplify the OBJ to at most this many triangles first (meshoptimizer; as `bake
    /// --max-triangles`), e.g. to see a model too large for one renderer (drawn in passes
    /// here) as a device can hold it
    #[arg(long, value_name = "N", requires = "obj")]
    max_triangles: Option<usize>,
    /// Simplify the OBJ to at most this many vertices first (meshoptimizer)
    #[arg(long, value_name = "N", requires = "obj")]
    max_vertices: Option<usize>,
    /// Testing: draw every frame in passes of at most N triangles of the mesh, as a frame too
    /// large for one renderer is drawn (the image must be the same as in one pass). The active
    /// count of `--budget` and of the RAM figure is then an upper bound.
    #[arg(long, value_name = "N", hide = true)]
    pass_triangles: Option<usize>,
}

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
    let e = |e: scanline3d::ShapeError| format!("shape: {e}");
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
        let dir = scanline3d::normalize(scanline3d::sub(args.eye, args.target));
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
            Some(_) => Projection::Orthographic {
                height: 2.1 * r * (h as f64 / w.min(h) as f64),
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
        l[k].direction = d.map(S::from_f64);
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

/// A piece of the mesh for one pass: consecutive triangles, with their own vertex arrays.
struct Piece<S> {
    positions: Vec<[S; 3]>,
    normals: Vec<[S; 3]>,
    indices: Vec<[u16; 3]>,
}

/// The triangles `tris` with only the vertices they use, renumbered in order of first use.
/// `map` (one entry per mesh vertex, all `u32::MAX`) is left as it was found.
fn piece<S: Copy>(
    positions: &[[S; 3]],
    normals: &[[S; 3]],
    tris: &[[u16; 3]],
    map: &mut [u32],
) -> Piece<S> {
    let mut p = Piece {
        positions: Vec::new(),
        normals: Vec::new(),
        indices: Vec::with_capacity(tris.len()),
    };
    for t in tris {
        p.indices.push(t.map(|i| {
            let slot = &mut map[i as usize];
            if *slot == u32::MAX {
                *slot = p.positions.len() as u32;
                p.positions.push(positions[i as usize]);
                p.normals.push(normals[i as usize]);
            }
            *slot as u16
        }));
    }
    for t in tris {
        for &i in t {
            map[i as usize] = u32::MAX;
        }
    }
    p
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

fn piece_mesh<'a, S: Scalar>(m: &Model, p: &'a Piece<S>) -> Result<Mesh<'a, S>, String> {
    Mesh::new(&p.positions, &p.indices)
        .and_then(|mesh| mesh.with_normals(&p.normals))
        .map_err(|e| format!("{}: {e}", m.name))
}

/// Splits the mesh into pieces of consecutive triangles that each fit one renderer in this
/// frame (pieces of `first_pieces` triangles, each halved until it fits), in mesh order, with
/// each piece's needs.
fn plan<S: Scalar, C: TargetColor>(
    r: &mut Layered<S, C>,
    m: &Model,
    pos: &[[S; 3]],
    nor: &[[S; 3]],
    fs: &FrameSetup<'_, S>,
    first_pieces: usize,
) -> Result<Vec<(Piece<S>, Needs)>, String> {
    let mut map = vec![u32::MAX; pos.len()];
    let n = m.indices.len();
    let step = first_pieces.clamp(1, n.max(1));
    // Pieces of `step` triangles, the first on top of the stack.
    let mut todo: Vec<_> = (0..n.div_ceil(step))
        .rev()
        .map(|k| k * step..n.min((k + 1) * step))
        .collect();
    let mut out = Vec::new();
    while let Some(range) = todo.pop() {
        let p = piece(pos, nor, &m.indices[range.clone()], &mut map);
        let objects = fs.object(piece_mesh(m, &p)?);
        let measured = match r.needs(&fs.scene(&objects)) {
            Ok(n) => n,
            // Not measured exactly: the piece is too large, and is split.
            Err(Error::Shortfall(_)) => Needs::new(usize::MAX, usize::MAX, usize::MAX),
            Err(e) => return Err(format!("{}: {e}", m.name)),
        };
        if measured.fits(&LIMIT) {
            out.push((p, measured));
        } else if range.len() > 1 {
            let mid = range.start + range.len() / 2;
            // A stack: the first half is taken next, so the pieces stay in mesh order.
            todo.push(mid..range.end);
            todo.push(range.start..mid);
        } else {
            return Err(format!(
                "{}: triangle {} alone does not fit a renderer ({measured:?})",
                m.name, range.start
            ));
        }
    }
    Ok(out)
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
    let frame_setup = |k: usize, auto: Option<&scanline3d::AutoExposure>| FrameSetup {
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
                let mut sink = scanline3d::hash::NullTarget::<C>::new(w as u32, h as u32);
                let mut t = Timer::default();
                match depth_check.as_mut() {
                    Some(d) if args.depth != depth::DepthArg::Zbuffer => timed(&mut || {
                        t = Timer::default();
                        let _ = d.renderer().render_probed(&scene, &mut sink, &mut t);
                        t.total.as_nanos() as f64
                    }),
                    _ => timed(&mut || {
                        t = Timer::default();
                        let _ = r.render_probed(&scene, &mut sink, &mut t);
                        t.total.as_nanos() as f64
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
                    let mut sink = scanline3d::hash::NullTarget::<C>::new(w as u32, h as u32);
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

/// The capacities `needs` exceeds the library's limits in: (capacity, needed, limit, whether
/// `needed` is an upper bound). A frame drawn in passes (`multi_pass`) has an upper bound of
/// its active count (the passes' largest counts added up), named only when its vertices and
/// triangles are within the limits.
fn short_capacities(needs: &Needs, multi_pass: bool) -> Vec<(Capacity, usize, usize, bool)> {
    let mut out: Vec<_> = [Capacity::Vertices, Capacity::Triangles]
        .into_iter()
        .filter(|&c| needs.get(c) > LIMIT.get(c))
        .map(|c| (c, needs.get(c), LIMIT.get(c), false))
        .collect();
    let active = Capacity::ActiveTriangles;
    if (out.is_empty() || !multi_pass) && needs.active > LIMIT.active {
        out.push((active, needs.active, LIMIT.active, multi_pass));
    }
    out
}

/// A capacity no renderer has, with what to do about it.
fn capacity_message(m: &Model, what: Capacity, needed: usize, limit: usize, bound: bool) -> String {
    let name = &m.name;
    let n = suggest_triangles(m.indices.len(), needed, limit);
    format!(
        "{name}: one frame needs {}{needed} {}, more than any renderer holds ({limit}, the \
         library's limit): the preview draws it in passes, a device cannot; simplify the model, \
         e.g. preview and budget it with `--max-triangles {n}`, or bake a smaller mesh with \
         `cargo run --release --example bake -- {name} --max-triangles {n} --obj-out smaller.obj`",
        if bound { "up to " } else { "" },
        capacity_name(what),
    )
}

fn capacity_name(c: Capacity) -> &'static str {
    match c {
        Capacity::Vertices => "vertices",
        Capacity::Triangles => "triangles",
        Capacity::ActiveTriangles => "triangles active on one row",
        _ => "of a capacity",
    }
}

/// Writes PNG, animated PNG or GIF to a temporary name, then renames: never a half-written file.
fn write_image<C: PixelColor + Into<Rgb888>>(
    path: &Path,
    frames: &[Frame<C>],
    delay_ms: u16,
) -> Result<(), String> {
    let name = path.display();
    let tmp = path.with_extension("partial");
    let result = (|| -> Result<(), String> {
        let file = std::fs::File::create(&tmp).map_err(|e| format!("{name}: {e}"))?;
        let (w, h) = (frames[0].w, frames[0].h);
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        match ext.as_str() {
            "gif" => {
                let mut enc = gif::Encoder::new(file, w as u16, h as u16, &[])
                    .map_err(|e| format!("{name}: {e}"))?;
                enc.set_repeat(gif::Repeat::Infinite)
                    .map_err(|e| format!("{name}: {e}"))?;
                for f in frames {
                    let mut fr =
                        gif::Frame::from_rgb_speed(w as u16, h as u16, &f.rgb888_bytes(), 10);
                    fr.delay = delay_ms / 10;
                    enc.write_frame(&fr).map_err(|e| format!("{name}: {e}"))?;
                }
            }
            "png" => {
                let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
                enc.set_color(png::ColorType::Rgb);
                enc.set_depth(png::BitDepth::Eight);
                if frames.len() > 1 {
                    enc.set_animated(frames.len() as u32, 0)
                        .map_err(|e| format!("{name}: {e}"))?;
                    enc.set_frame_delay(delay_ms, 1000)
                        .map_err(|e| format!("{name}: {e}"))?;
                }
                let mut wr = enc.write_header().map_err(|e| format!("{name}: {e}"))?;
                for f in frames {
                    wr.write_image_data(&f.rgb888_bytes())
                        .map_err(|e| format!("{name}: {e}"))?;
                }
                wr.finish().map_err(|e| format!("{name}: {e}"))?;
            }
            _ => return Err(format!("{name}: the output must end in .png or .gif")),
        }
        Ok(())
    })();
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| format!("{name}: {e}")),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

fn compare<C: RgbColor>(a: &[Frame<C>], b: &[Frame<C>], background: C) -> Metrics {
    let mut m = Metrics::new([C::MAX_R, C::MAX_G, C::MAX_B]);
    for (fa, fb) in a.iter().zip(b.iter()) {
        for y in 0..fa.h as usize {
            let r = y * fa.w as usize..(y + 1) * fa.w as usize;
            m.add_line(&fa.px[r.clone()], &fb.px[r], background);
        }
    }
    m
}

fn main() {
    let args = Args::parse();
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
    let shadow_flags = args.shadow.is_some()
        || args.shadow_plane.is_some()
        || args.alpha.is_some()
        || args.outline.is_some();
    if args.scene == Some(SceneArg::Shadow) {
        return shadow::run(&args);
    }
    if shadow_flags {
        return Err((
            "--shadow, --shadow-plane, --alpha and --outline apply to --scene shadow only".into(),
            2,
        ));
    }
    let m = model(&args).map_err(|e| (e, 2))?;
    let s = setup(&args, &m).map_err(|e| (e, 2))?;
    match args.format {
        FormatArg::Rgb565 => go::<Rgb565>(&args, &m, &s),
        FormatArg::Rgb888 => go::<Rgb888>(&args, &m, &s),
    }
}

/// Every numeric flag against its valid range, named as the user typed it (usage errors: exit
/// status 2, like clap's). `--size`, `--eye`, `--target`, `--up`, `--light`, `--color` and
/// `--background` are checked by their parsers (finite, in range); the camera as a whole (eye
/// at the target, up along the view, depth precision) by `Camera::look_at` in [`setup`].
fn check_flags(args: &Args) -> Result<(), String> {
    let (w, h) = args.size;
    let finite = |flag: &str, v: f64| {
        if v.is_finite() {
            Ok(())
        } else {
            Err(format!("{flag} must be a finite number, got {v}"))
        }
    };
    finite("--fov-y", args.fov_y)?;
    if !(args.fov_y > 0.0 && args.fov_y < 180.0) {
        return Err(format!(
            "--fov-y must be in (0, 180) degrees, got {}",
            args.fov_y
        ));
    }
    finite("--near", args.near)?;
    if args.near <= 0.0 {
        return Err(format!(
            "--near must be greater than 0 (world units), got {}",
            args.near
        ));
    }
    finite("--far", args.far)?;
    if args.far <= args.near {
        return Err(format!(
            "--far must be greater than --near ({}), got {}",
            args.near, args.far
        ));
    }
    finite("--crease-angle", args.crease_angle)?;
    edges::check(args)?;
    tone::check(args)?;
    depth::check(args)?;
    if let Some(height) = args.ortho {
        finite("--ortho", height)?;
        if height <= 0.0 {
            return Err(format!(
                "--ortho (the view height) must be greater than 0 (world units), got {height}"
            ));
        }
    }
    for (flag, v) in [
        ("--rotate-x", args.rotate_x),
        ("--rotate-y", args.rotate_y),
        ("--rotate-z", args.rotate_z),
        ("--spin", args.spin),
    ] {
        finite(flag, v)?;
    }
    if args.light.len() > LIGHTS {
        return Err(format!(
            "at most {LIGHTS} --light flags, got {}",
            args.light.len()
        ));
    }
    if let Some(l) = args.light.iter().find(|l| **l == [0.0; 3]) {
        return Err(format!(
            "--light {},{},{} is a zero vector: a light needs a direction",
            l[0], l[1], l[2]
        ));
    }
    for (flag, v) in [
        ("--ambient", args.ambient),
        ("--diffuse", args.diffuse),
        ("--specular", args.specular),
    ] {
        finite(flag, v)?;
        if !(0.0..=MAX_COEFFICIENT).contains(&v) {
            return Err(format!("{flag} must be in [0, {MAX_COEFFICIENT}], got {v}"));
        }
    }
    if args.shininess == 0 {
        return Err("--shininess must be in [1, 255], got 0".into());
    }
    if !(1..=h).contains(&args.strip) {
        return Err(format!(
            "--strip must be in [1, {h}] lines (the image height), got {}",
            args.strip
        ));
    }
    if !(1..=MAX_FRAMES).contains(&args.frames) {
        return Err(format!(
            "--frames must be in [1, {MAX_FRAMES}], got {} (every frame is kept in memory \
             until the animation is written)",
            args.frames
        ));
    }
    let pixels = args.frames.saturating_mul(w * h);
    if pixels > MAX_FRAME_PIXELS {
        return Err(format!(
            "--frames {} at {w}x{h} is {pixels} pixels, more than the {MAX_FRAME_PIXELS} \
             (frames × width × height) kept in memory: at most {} frames at this --size",
            args.frames,
            MAX_FRAME_PIXELS / (w * h)
        ));
    }
    Ok(())
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
    let reference = run::<f64, C>(args, m, s, 0).map_err(|e| (e, 1))?;
    let metrics = compare(
        &tested.frames,
        &reference.frames,
        scanline3d::quantize::<C>(args.background),
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

/// `--budget`: what the scene needs over every frame.
fn budget<C: TargetColor>(
    args: &Args,
    m: &Model,
    s: &Setup,
    run: &Run<C>,
    number: &str,
) -> Result<(), (String, i32)> {
    let (w, h) = args.size;
    let max = |f: fn(&Stats) -> u32| run.stats.iter().map(f).max().unwrap_or(0) as usize;
    // What one renderer needs for every frame (for a frame drawn in passes, its whole mesh's).
    let needs = run.needs.iter().fold(Needs::default(), |a, n| a.max(*n));
    let (verts, tris, active) = (needs.vertices, needs.triangles, needs.active);
    let passes = run.passes.iter().copied().max().unwrap_or(1);
    let invalid = max(|s| s.invalid);
    // Fixed-point headroom: the largest magnitudes each stage reaches, in f64, against Q16.16.
    let cam = Camera::look_at(s.eye, s.target, s.up, s.projection)
        .map_err(|e| (format!("camera: {e}"), 2))?;
    let pv = cam.projection.matrix(w as f64 / h as f64).mul(&cam.view);
    let (mut model_max, mut world_max, mut clip_max) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..args.frames {
        let t = transform::<f64>(args, s, k);
        let mvp = pv.mul(&t);
        for p in &m.positions {
            model_max = model_max.max(p.iter().fold(0.0, |a, v| a.max(v.abs())));
            world_max = world_max.max(
                t.transform_point(*p)
                    .iter()
                    .take(3)
                    .fold(0.0, |a, v| a.max(v.abs())),
            );
            clip_max = clip_max.max(
                mvp.transform_point(*p)
                    .iter()
                    .fold(0.0, |a, v| a.max(v.abs())),
            );
        }
    }
    let matrix_max = pv.m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let range = 32768.0;
    let lines = args.strip;
    let color = if core::mem::size_of::<C>() == 2 {
        "Rgb565"
    } else {
        "Rgb888"
    };
    println!(
        "budget for {} over {} frame(s) at {w}x{h} ({number}):",
        m.name,
        run.stats.len()
    );
    if let Some(s) = &m.simplified {
        println!("  {s}");
    }
    println!("  vertices stored (mesh + clipping): {verts}");
    println!(
        "  triangles after culling and clipping: {tris} (of {} in the mesh)",
        m.indices.len()
    );
    if passes > 1 {
        println!(
            "  triangles active on one row (max): at most {active} (the preview drew a frame in \
             {passes} passes; this adds up their largest counts)"
        );
    } else {
        println!("  triangles active on one row (max): {active}");
    }
    println!("  invalid triangles skipped: {invalid}");
    println!("  fixed-point headroom (Q16.16 range ±32768; margin = range / largest magnitude):");
    for (stage, v) in [
        ("model positions", model_max),
        ("world positions", world_max),
        ("view-projection matrix", matrix_max),
        ("clip coordinates", clip_max),
    ] {
        println!(
            "    {stage:24} largest {v:>12.4}  margin {:>10.1}x",
            range / v.max(1e-30)
        );
    }
    tone::budget(args, args.ambient, args.diffuse, args.specular).map_err(|e| (e, 1))?;
    let short = short_capacities(&needs, passes > 1);
    if !short.is_empty() {
        // No renderer holds a frame: no RAM figure or renderer type, but what to do.
        return Err((
            short
                .iter()
                .map(|&(what, needed, limit, bound)| {
                    capacity_message(m, what, needed, limit, bound)
                })
                .collect::<Vec<_>>()
                .join("\n"),
            1,
        ));
    }
    let ram = ram_formula(w, h, core::mem::size_of::<C>(), lines, verts, tris, active);
    println!(
        "  renderer RAM: {ram} bytes = {lines}·{w}·({} + 2) + {}·{verts} + {}·{tris} + {}·{active} + 4·{h} (+ ≤ 128 state)",
        core::mem::size_of::<C>(),
        scanline3d::internals::VERTEX_BYTES,
        scanline3d::internals::TRIANGLE_BYTES,
        scanline3d::internals::ACTIVE_BYTES
    );
    if s.texture.is_some() || matches!(args.shading, ShadingArg::Phong | ShadingArg::FastPhong) {
        // The attribute stores: every vertex, and every active triangle plus the Phong lights'
        // and material's entries.
        let reserved = if matches!(args.shading, ShadingArg::Phong | ShadingArg::FastPhong) {
            2
        } else {
            0
        };
        let (xv, xa) = (verts, active + reserved);
        println!(
            "  attribute stores (texture, Phong): XV = {xv}, XA = {xa}: + {} bytes on a 32-bit core \
             ({xv}·{} + {xa}·{})",
            xv * scanline3d::VERTEX_EXTRA_BYTES_32 + xa * scanline3d::ACTIVE_EXTRA_BYTES_32,
            scanline3d::VERTEX_EXTRA_BYTES_32,
            scanline3d::ACTIVE_EXTRA_BYTES_32
        );
        println!("  renderer type: Renderer<Fx<I16F16>, {color}, {w}, {h}, {verts}, {tris}, {active}, {lines}, {xv}, {xa}>");
    } else {
        println!("  renderer type: Renderer<Fx<I16F16>, {color}, {w}, {h}, {verts}, {tris}, {active}, {lines}>");
    }
    // Work the scene does not need.
    if let Some(d) = &run.depth {
        d.report(run.stats.len(), lines, w);
    }
    if is_closed_convex(m) {
        println!(
            "  (the mesh is one closed convex object: after back-face culling nothing overlaps)"
        );
    }
    if args.shading == ShadingArg::Flat {
        println!("  hint: flat shading lights faces, not vertices: the mesh needs no vertex normals (saves {} bytes of flash)", 12 * m.positions.len());
    }
    let overflow = [model_max, world_max, matrix_max, clip_max]
        .iter()
        .any(|&v| v >= range);
    if overflow || invalid > 0 {
        return Err((format!("{}: the scene overflows Q16.16 (see the margins above); scale it down or use Fx<I20F12>", m.name), 1));
    }
    Ok(())
}

/// Every edge shared by exactly two triangles (vertices welded by position, since OBJ corners
/// with different texture coordinates or normals are separate vertices), and every vertex on or
/// behind every face's plane.
fn is_closed_convex(m: &Model) -> bool {
    use std::collections::HashMap;
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let id: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            let n = weld.len() as u32;
            *weld.entry(p.map(f64::to_bits)).or_insert(n)
        })
        .collect();
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.indices {
        for k in 0..3 {
            let (a, b) = (id[t[k] as usize], id[t[(k + 1) % 3] as usize]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    if edges.values().any(|&n| n != 2) {
        return false;
    }
    let (_, _, _, r) = bounds(&m.positions);
    m.indices.iter().all(|t| {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let n = scanline3d::cross(scanline3d::sub(b, a), scanline3d::sub(c, a));
        let len = scanline3d::length(n);
        len == 0.0
            || m.positions
                .iter()
                .all(|p| scanline3d::dot(n, scanline3d::sub(*p, a)) / len <= 1e-9 * r.max(1.0))
    })
}
