//! What the simulator draws, into any `DrawTarget<Color = Rgb565>` (the simulator's display, or
//! the support crate's `Frame` in `tools/tests/simulator.rs`, which includes this file): a
//! benchmark scene of the support crate, or a model (the default torus, an OBJ file) seen from
//! an orbit, and the frame-time label drawn over it. No window and no SDL here.

use std::path::Path;

use embedded_graphics::mono_font::ascii::FONT_6X10;
use embedded_graphics::mono_font::MonoTextStyleBuilder;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::text::{Baseline, Text};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{probe::NoProbe, Error, Stats};
use scanline3d_support::demo::{self, deg, Bench};
use scanline3d_tools::obj::{bounds, parse_obj, suggest_triangles, vertex_normals, NormalSource};

/// The device's number type, as on the board.
pub type Q = Fx<I16F16>;

/// The panel: 240 × 240 RGB565, the size every benchmark scene is drawn at.
pub const SIZE: u32 = 240;

/// Vertices and triangles the model renderer holds: the renderer's limits (32 768 vertices,
/// 32 767 triangles), so that any OBJ `render` previews in one pass is shown here too.
pub const MODEL_VERTICES: usize = 32768;
pub const MODEL_TRIANGLES: usize = 32767;
/// Triangles active on one row: 4 096 (a 240-pixel row of a dense model; the default torus
/// needs 61). 344 KB of the renderer's 0.9 MB (84 bytes each).
pub const MODEL_ACTIVE: usize = 4096;

/// The renderer of the model scenes (on the heap: 0.9 MB).
pub type ModelRenderer = Renderer<
    Q,
    Rgb565,
    { SIZE as usize },
    { SIZE as usize },
    MODEL_VERTICES,
    MODEL_TRIANGLES,
    MODEL_ACTIVE,
>;

/// Where the scene is seen from, in whole degrees: `yaw` turns it about the world's vertical
/// axis, `pitch` then about the world's x axis (the camera's horizontal axis: every scene's
/// camera looks along −z). Whole degrees keep the benchmark scenes on the angles their
/// capacities were measured at (every degree of a turn for the torus).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct View {
    /// In [0, 360).
    pub yaw: i32,
    /// In [−90, 90].
    pub pitch: i32,
}

/// Largest pitch either way: the model seen from straight above or below.
pub const MAX_PITCH: i32 = 90;

impl View {
    /// `yaw` wrapped into [0, 360), `pitch` clamped to ±[`MAX_PITCH`].
    #[must_use]
    pub fn new(yaw: i32, pitch: i32) -> Self {
        View {
            yaw: yaw.rem_euclid(360),
            pitch: pitch.clamp(-MAX_PITCH, MAX_PITCH),
        }
    }

    /// This view turned by `d_yaw` and `d_pitch` degrees.
    #[must_use]
    pub fn turned(self, d_yaw: i32, d_pitch: i32) -> Self {
        View::new(
            self.yaw.saturating_add(d_yaw),
            self.pitch.saturating_add(d_pitch),
        )
    }
}

/// A mesh shown with the default scene's material (colour (255, 160, 64), ambient 0.15,
/// diffuse 0.85, Gouraud), light and background: the default torus with its camera and tilt,
/// or an OBJ model.
struct Model {
    positions: Vec<[Q; 3]>,
    normals: Vec<[Q; 3]>,
    indices: Vec<[u16; 3]>,
    /// The model's own placement, before the orbit.
    placement: Mat4<Q>,
    camera: Camera<Q>,
    renderer: Box<ModelRenderer>,
}

enum Content {
    Model(Box<Model>),
    /// A benchmark scene drawn by the support crate's `render_bench`: its own meshes, camera,
    /// lights and renderer. It takes one spin angle about Y, so these scenes have no pitch.
    Bench(Bench),
}

/// A scene the simulator shows.
pub struct Viewer {
    /// For messages and the window's title.
    pub name: String,
    content: Content,
}

/// The scene names `--scene` accepts: every benchmark scene of the support crate
/// ([`Bench::ALL`]; `render --scene`'s names are among them).
#[must_use]
pub fn scene_names() -> Vec<&'static str> {
    Bench::ALL.iter().map(|b| b.name()).collect()
}

/// The benchmark scene called `name`, or a message listing the names.
pub fn bench_named(name: &str) -> Result<Bench, String> {
    Bench::ALL
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| {
            format!(
                "no built-in scene {name:?}; the scenes are: {}",
                scene_names().join(", ")
            )
        })
}

impl Viewer {
    /// The default scene: the benchmark torus (R = 1.0, r = 0.4, 32 × 16 segments), as
    /// `render` draws it by default and as [`Bench::Torus`] at spin `yaw` when the pitch is 0.
    pub fn torus() -> Result<Self, String> {
        let shape = demo::torus::<Q>().map_err(|e| format!("torus: {e}"))?;
        Ok(Viewer {
            name: "torus".into(),
            content: Content::Model(Box::new(Model {
                positions: shape.positions.to_vec(),
                normals: shape.normals.to_vec(),
                indices: shape.indices.to_vec(),
                placement: demo::torus_tilt(),
                camera: demo::camera().map_err(|e| format!("torus camera: {e}"))?,
                renderer: Box::default(),
            })),
        })
    }

    /// A benchmark scene; [`Bench::Torus`] is [`Viewer::torus`], which can also pitch.
    pub fn bench(bench: Bench) -> Result<Self, String> {
        match bench {
            Bench::Torus => Self::torus(),
            bench => Ok(Viewer {
                name: bench.name().into(),
                content: Content::Bench(bench),
            }),
        }
    }

    /// An OBJ file (read by `scanline3d_tools::obj` as `render --obj` reads it: normals from
    /// the file when every corner has one, else face-averaged), centred and scaled into the
    /// unit sphere in f64 before it is rounded to Q16.16 (any model's units fit the number
    /// type), tilted as `render` tilts a model (30° about X, then 20° about Y) and framed as
    /// `render --fit` frames it with the default camera direction and 45° field of view.
    pub fn obj(path: &Path) -> Result<Self, String> {
        let file = parse_obj(path)?;
        let source = file.default_normals();
        let big = file.mesh(source)?;
        let (verts, tris) = (big.positions.len(), big.indices.len());
        if verts > MODEL_VERTICES || tris > MODEL_TRIANGLES {
            let target = suggest_triangles(tris, verts, MODEL_VERTICES).min(MODEL_TRIANGLES);
            return Err(format!(
                "{}: {verts} vertices and {tris} triangles, more than the simulator's renderer \
                 holds ({MODEL_VERTICES} vertices, {MODEL_TRIANGLES} triangles): simplify it, \
                 e.g. `cargo run --release -p scanline3d-tools --features simplify --bin bake \
                 -- {} --max-triangles {target} --obj-out smaller.obj`",
                file.name, file.name
            ));
        }
        let mesh = big.to_u16(&file.name)?;
        let normals = vertex_normals(&mesh, source == NormalSource::File);
        let (_, _, centre, radius) = bounds(&mesh.positions);
        if !(radius.is_finite() && radius > 0.0) {
            return Err(format!(
                "{}: the model has no extent (every vertex at one point)",
                file.name
            ));
        }
        let positions = mesh
            .positions
            .iter()
            .map(|p| [0, 1, 2].map(|k| Q::from_f64((p[k] - centre[k]) / radius)))
            .collect();
        let normals = normals.iter().map(|n| n.map(Q::from_f64)).collect();
        // `render --fit`: the unit sphere fills the 45° view from along (0, 1.2, 3).
        let fov = 45.0f64.to_radians();
        let distance = 1.0 / (fov / 2.0).sin();
        let dir = scanline3d::math::normalize([0.0, 1.2, 3.0]);
        let camera = Camera::look_at(
            dir.map(|d| Q::from_f64(d * distance)),
            [Q::ZERO; 3],
            [Q::ZERO, Q::ONE, Q::ZERO],
            Projection::Perspective {
                fov_y: Q::from_f64(fov),
                near: Q::from_f64(distance - 1.05),
                far: Q::from_f64(distance + 1.05),
            },
        )
        .map_err(|e| format!("{}: camera: {e}", file.name))?;
        Ok(Viewer {
            name: file.name.clone(),
            content: Content::Model(Box::new(Model {
                positions,
                normals,
                indices: mesh.indices,
                placement: demo::torus_tilt(),
                camera,
                renderer: Box::default(),
            })),
        })
    }

    /// Whether the view's pitch turns this scene (the benchmark scenes other than the torus
    /// turn about Y only).
    #[must_use]
    pub fn pitches(&self) -> bool {
        matches!(self.content, Content::Model(_))
    }

    /// Draws the scene from `view` into `target` (its top-left 240 × 240 pixels, each written
    /// once): the frame's statistics, or a message.
    pub fn draw<D>(&mut self, view: View, target: &mut D) -> Result<Stats, String>
    where
        D: DrawTarget<Color = Rgb565>,
        D::Error: core::fmt::Debug + core::fmt::Display,
    {
        match &mut self.content {
            Content::Bench(bench) => demo::render_bench::<Q, Rgb565, D, NoProbe>(
                *bench,
                f64::from(view.yaw),
                false,
                target,
                &mut NoProbe,
            )
            .map(|frame| frame.stats)
            .map_err(|e| format!("{}: {e}", self.name)),
            Content::Model(m) => {
                let mesh = Mesh::new(&m.positions, &m.indices)
                    .and_then(|mesh| mesh.with_normals(&m.normals))
                    .map_err(|e| format!("{}: {e}", self.name))?;
                // As `demo::torus_transform`: the placement, then the spin about Y.
                let transform = m
                    .placement
                    .then(&Mat4::rotate_y(deg(f64::from(view.yaw))))
                    .then(&Mat4::rotate_x(deg(f64::from(view.pitch))));
                let objects = [Object {
                    mesh,
                    transform,
                    material: demo::torus_material(),
                }];
                let scene = Scene::new(&objects, m.camera, demo::lights());
                m.renderer.render(&scene, target).map_err(|e| match e {
                    Error::Shortfall(sf) => format!(
                        "{}: {sf} at yaw {}° pitch {}° (the simulator's renderer holds \
                         {MODEL_ACTIVE} triangles on one row): simplify the model",
                        self.name, view.yaw, view.pitch
                    ),
                    e => format!("{}: {e}", self.name),
                })
            }
        }
    }
}

/// The label's text colour (white: the benchmark scenes' backgrounds are dark).
pub const LABEL_COLOR: Rgb565 = Rgb565::WHITE;
/// Its top-left corner, as the board firmware's frame-rate label.
pub const LABEL_AT: Point = Point::new(4, 4);

/// The frame-time label, e.g. `3.41 ms/frame`.
#[must_use]
pub fn frame_time_text(ms: f64) -> String {
    format!("{ms:.2} ms/frame")
}

/// Draws `text` at [`LABEL_AT`] in embedded-graphics' 6 × 10 font, white on black; returns
/// the rectangle it covered (nothing outside it is touched).
pub fn draw_label<D: DrawTarget<Color = Rgb565>>(
    target: &mut D,
    text: &str,
) -> Result<Rectangle, D::Error> {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(LABEL_COLOR)
        .background_color(Rgb565::BLACK)
        .build();
    let text = Text::with_baseline(text, LABEL_AT, style, Baseline::Top);
    text.draw(target)?;
    Ok(text.bounding_box())
}

/// A message over a cleared screen, one line per 38 characters (the window shows a frame that
/// could not be drawn this way instead of closing).
pub fn draw_message<D: DrawTarget<Color = Rgb565>>(
    target: &mut D,
    message: &str,
) -> Result<(), D::Error> {
    target.clear(Rgb565::BLACK)?;
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb565::RED)
        .build();
    let chars: Vec<char> = message.chars().collect();
    for (k, line) in chars.chunks(38).enumerate() {
        let line: String = line.iter().collect();
        let at = Point::new(4, 4 + 11 * k as i32);
        Text::with_baseline(&line, at, style, Baseline::Top).draw(target)?;
    }
    Ok(())
}
