//! The renderer: geometry for every object, then one strip pass over the screen.

use core::marker::PhantomData;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::raw::ToBytes;
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::{Drawable, Pixel};
use heapless::Vec;

use crate::clip::{clip_triangle, outcode, ClipVertex, NEEDS_CLIP};
use crate::color::TargetColor;
use crate::cull::{facing, Facing};
use crate::math::{normalize, sub, Mat4, Vec3};
use crate::mesh::face_normal;
use crate::project::{
    pack_channels, pack_flat_channels, unpack_channels, ScreenVertex, Viewport, COORD_LIMIT,
    MAX_SCREEN,
};
use crate::raster::{first_pixel, ActiveList, ActiveTri, DepthTest, SpanMode, TriRecord, FLAT_BIT};
use crate::scalar::Scalar;
use crate::scene::{Object, Scene};
use crate::shade::{lit_color, lit_diffuse, PreparedLight, Shading};

/// [`ScreenVertex`] flag bits of the renderer (bits 0..=5 are the outcode of `clip`): a NaN,
/// infinite or overflowed position; projected; lit (its colour is set).
pub(crate) const INVALID: u16 = 1 << 7;
pub(crate) const PROJECTED: u16 = 1 << 8;
pub(crate) const LIT: u16 = 1 << 9;
/// Set by [`cull_push`] on an unlit vertex of a stored front face: it needs lighting (the
/// object's loop lights those after its triangles). A colour bit, free until the vertex is lit
/// ([`ScreenVertex::set_color`] overwrites it).
pub(crate) const NEEDS_LIGHT: u16 = 1 << 15;

/// The strip being rendered, as a draw target covering the whole `W × H` screen: pixels outside
/// the strip's rows are ignored. [`Renderer::render_overlaid`] hands it to an overlay
/// [`Drawable`] after the 3D content of each strip is drawn and before the strip is sent, so that
/// text or a HUD is composed into the lines instead of being drawn over the finished frame
/// (no flicker on a display without a framebuffer).
#[derive(Debug)]
pub struct StripCanvas<'a, C, const W: usize> {
    lines: &'a mut [[C; W]],
    y0: usize,
    height: u32,
}

impl<C, const W: usize> OriginDimensions for StripCanvas<'_, C, W> {
    fn size(&self) -> Size {
        Size::new(W as u32, self.height)
    }
}

impl<C: PixelColor, const W: usize> DrawTarget for StripCanvas<'_, C, W> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if p.x < 0 || p.y < self.y0 as i32 || p.x as usize >= W {
                continue;
            }
            if let Some(line) = self.lines.get_mut(p.y as usize - self.y0) {
                line[p.x as usize] = c;
            }
        }
        Ok(())
    }
}

/// One of the renderer's three compile-time capacities (see [`Needs`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Capacity {
    /// `VERTS`: mesh vertices of all objects plus vertices made by clipping.
    Vertices,
    /// `TRIS`: triangles that survive culling and clipping (a clipped triangle may become up
    /// to seven).
    Triangles,
    /// `ACTIVE`: triangles crossing one pixel row.
    ActiveTriangles,
}

/// Why a frame was not (completely) drawn.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error<E> {
    /// The draw target returned an error; the frame is drawn up to the failing strip.
    Target(E),
    /// The scene needs more room than the renderer was given in one capacity. No longer
    /// returned by the renderer: [`Error::Shortfall`] reports every capacity that is short at
    /// once.
    Capacity {
        /// The capacity.
        what: Capacity,
        /// Its compile-time value.
        capacity: usize,
        /// What this frame needed (for triangles: at least this many).
        needed: usize,
    },
    /// Object `object` asks for Gouraud shading but its mesh has no vertex normals. Nothing
    /// was drawn.
    MissingNormals {
        /// Index of the object in the scene.
        object: usize,
    },
    /// The scene's camera fails [`crate::Camera::validate`] (its fields are public and may
    /// have been changed after [`crate::Camera::look_at`]). Nothing was drawn.
    Camera(crate::CameraError),
    /// The frame needs more room than the renderer has, in one or more of its capacities:
    /// every capacity that is short, with what the frame needed, is in the [`Shortfall`]
    /// ([`Shortfall::iter`]). Returned under [`OverflowPolicy::Error`] (the default); nothing
    /// was drawn. This replaces [`Error::Capacity`], which the renderer no longer returns.
    Shortfall(Shortfall),
    /// The draw target does not contain the viewport: the renderer draws `viewport` pixels at
    /// the target's origin (`W × H` unless changed by [`Renderer::set_viewport`]) and the
    /// target's bounding box is `target`. Checked before anything is drawn (by
    /// [`Renderer::render`] and its variants once per frame, by [`Renderer::render_strip`] at
    /// each call); a larger target is fine (the rest of it is left as it was). Set the
    /// viewport to the target's size to draw into a smaller one.
    TargetTooSmall {
        /// The viewport, in pixels.
        viewport: Size,
        /// The target's bounding box.
        target: Rectangle,
    },
    /// [`Renderer::render_passes`] needs one strip over the whole viewport (the colour and
    /// depth lines keep every pass's pixels until the frame is sent): `LINES` is `lines`, the
    /// viewport is `height` rows high. Nothing was drawn.
    StripTooShort {
        /// The renderer's `LINES`.
        lines: usize,
        /// The viewport's height.
        height: usize,
    },
}

impl<E: core::fmt::Display> core::fmt::Display for Error<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::Target(e) => write!(f, "draw target error: {e}"),
            Error::Capacity {
                what,
                capacity,
                needed,
            } => {
                let (name, what) = match what {
                    Capacity::Vertices => ("VERTS", "vertices"),
                    Capacity::Triangles => ("TRIS", "triangles"),
                    Capacity::ActiveTriangles => ("ACTIVE", "triangles active on one row"),
                };
                write!(
                    f,
                    "scene needs {needed} {what} but the renderer's {name} capacity is \
                     {capacity}; nothing was drawn"
                )
            }
            Error::MissingNormals { object } => write!(
                f,
                "object {object} is Gouraud-shaded but its mesh has no vertex normals; nothing \
                 was drawn"
            ),
            Error::Camera(e) => write!(f, "{e}; nothing was drawn"),
            Error::Shortfall(s) => {
                write!(f, "frame does not fit the renderer: {s}; nothing was drawn")
            }
            Error::TargetTooSmall { viewport, target } => write!(
                f,
                "the draw target ({} × {} px at ({}, {})) does not contain the {} × {} px \
                 viewport; nothing was drawn",
                target.size.width,
                target.size.height,
                target.top_left.x,
                target.top_left.y,
                viewport.width,
                viewport.height
            ),
            Error::StripTooShort { lines, height } => write!(
                f,
                "drawing in passes needs one strip over the whole viewport, but the renderer's \
                 strip has {lines} lines for a viewport {height} rows high (LINES must be at \
                 least the viewport's height); nothing was drawn"
            ),
        }
    }
}

/// What a frame needs of the renderer's three capacities, or (as [`Renderer::CAPACITY`]) what
/// a renderer has.
///
/// | field | capacity | [`Stats`] field of a frame that fit |
/// |---|---|---|
/// | `vertices` | `VERTS` | [`Stats::vertices`] |
/// | `triangles` | `TRIS` | [`Stats::drawn`] |
/// | `active` | `ACTIVE` | [`Stats::max_active`] |
///
/// To size a renderer for an animation built in code, measure every frame on the host with a
/// renderer of generous capacities ([`Renderer::needs`]) and keep the largest figures
/// ([`Needs::max`]); then check the device's renderer with [`Needs::fits`]:
///
/// ```
/// # use embedded_graphics::pixelcolor::Rgb565;
/// # use scanline3d::prelude::*;
/// # use scanline3d::Needs;
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// let torus = scanline3d::demo::torus::<Q>().unwrap();
/// // The host's measuring renderer: the device's size, large capacities (in a `Box` or a
/// // `static`, see `Renderer::const_new`, when they are large).
/// let mut measure = Box::new(Renderer::<Q, Rgb565, 240, 240, 2048, 2048, 256>::new());
/// let mut worst = Needs::default();
/// for frame in 0..12 {
///     let objects = [Object {
///         mesh: torus.mesh(),
///         transform: Mat4::rotate_y(Q::lit(0.5 * frame as f64)),
///         material: scanline3d::demo::torus_material(),
///     }];
///     let scene = Scene::new(&objects, scanline3d::demo::camera().unwrap(), scanline3d::demo::lights());
///     worst = worst.max(measure.needs(&scene).unwrap());
/// }
/// type Device = Renderer<Q, Rgb565, 240, 240, 512, 480, 64>;
/// assert!(worst.fits(&Device::CAPACITY), "{worst:?}");
/// ```
///
/// `Needs`, [`Stats`] and [`Shortfall`] are `#[non_exhaustive]`: they may gain fields, so
/// outside this crate they are read, and built only by their functions ([`Needs::new`],
/// `Default`), not by struct expressions:
///
/// ```compile_fail
/// let n = scanline3d::Needs { vertices: 512, triangles: 480, active: 64 };
/// ```
///
/// ```compile_fail
/// let s = scanline3d::Stats { drawn: 1, ..Default::default() };
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct Needs {
    /// Vertices (`VERTS`): mesh vertices of every object, vertices made by clipping, and one
    /// face-colour vertex per drawn flat-shaded triangle.
    pub vertices: usize,
    /// Triangles stored for the row pass (`TRIS`): those that survive culling and clipping
    /// and cover a pixel (a clipped triangle may become up to seven).
    pub triangles: usize,
    /// Triangles crossing one pixel row at once, at the busiest row (`ACTIVE`).
    pub active: usize,
}

impl Needs {
    /// Needs (or capacities) of `vertices`, `triangles` and `active` triangles.
    #[must_use]
    pub const fn new(vertices: usize, triangles: usize, active: usize) -> Self {
        Needs {
            vertices,
            triangles,
            active,
        }
    }

    /// The needs of a frame that fit, from its statistics ([`Stats::vertices`],
    /// [`Stats::drawn`], [`Stats::max_active`]).
    #[must_use]
    pub const fn from_stats(stats: &Stats) -> Self {
        Needs {
            vertices: stats.vertices as usize,
            triangles: stats.drawn as usize,
            active: stats.max_active as usize,
        }
    }

    /// The larger of each figure: accumulates the needs of an animation's frames.
    #[must_use]
    pub const fn max(self, other: Needs) -> Self {
        const fn m(a: usize, b: usize) -> usize {
            if a > b {
                a
            } else {
                b
            }
        }
        Needs {
            vertices: m(self.vertices, other.vertices),
            triangles: m(self.triangles, other.triangles),
            active: m(self.active, other.active),
        }
    }

    /// Whether these needs fit `capacity` (e.g. a renderer's [`Renderer::CAPACITY`]).
    #[must_use]
    pub const fn fits(&self, capacity: &Needs) -> bool {
        self.vertices <= capacity.vertices
            && self.triangles <= capacity.triangles
            && self.active <= capacity.active
    }

    /// The figure for one capacity.
    #[must_use]
    pub const fn get(&self, what: Capacity) -> usize {
        match what {
            Capacity::Vertices => self.vertices,
            Capacity::Triangles => self.triangles,
            Capacity::ActiveTriangles => self.active,
        }
    }
}

impl<E: core::fmt::Debug + core::fmt::Display> core::error::Error for Error<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Error::Camera(e) => Some(e),
            _ => None,
        }
    }
}

/// A frame that did not fit the renderer: what it needed against what the renderer has, for
/// all three capacities at once ([`Error::Shortfall`], or [`Renderer::shortfall`] under
/// [`OverflowPolicy::DrawWhatFits`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct Shortfall {
    /// What the frame needed (see `exact`).
    pub needed: Needs,
    /// The renderer's capacities ([`Renderer::CAPACITY`]).
    pub capacity: Needs,
    /// Whether `needed` is exact. It is not when the vertex or the triangle store overflowed:
    /// the objects whose vertices did not fit are neither culled nor clipped, so all of their
    /// triangles count as needed and none of them toward `active`, and the triangles that did
    /// not fit the store do not count toward `active` either. Measure with larger capacities
    /// ([`Renderer::needs`]) for exact figures.
    pub exact: bool,
    /// Under [`OverflowPolicy::DrawWhatFits`], the triangles left out of the frame for lack of
    /// room (complete once the frame is drawn): the triangles counted in `needed.triangles`
    /// that were not stored (for an object whose vertices did not fit: all of its triangles),
    /// and each stored triangle dropped because the active list was full on its first row.
    /// 0 in an [`Error::Shortfall`] (nothing is drawn).
    pub skipped: usize,
}

impl Shortfall {
    /// Whether the frame needed more than `what`'s capacity.
    #[must_use]
    pub const fn is_short(&self, what: Capacity) -> bool {
        self.needed.get(what) > self.capacity.get(what)
    }

    /// Every capacity that is short: `(capacity, needed, available)`, in the order vertices,
    /// triangles, active triangles.
    pub fn iter(&self) -> impl Iterator<Item = (Capacity, usize, usize)> + '_ {
        [
            Capacity::Vertices,
            Capacity::Triangles,
            Capacity::ActiveTriangles,
        ]
        .into_iter()
        .filter(|&c| self.is_short(c))
        .map(|c| (c, self.needed.get(c), self.capacity.get(c)))
    }
}

impl core::fmt::Display for Shortfall {
    /// `vertices: needs 530, has 512; triangles active on one row: needs 66, has 64`, with
    /// `at least` before figures that are not exact.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        for (k, (what, needed, capacity)) in self.iter().enumerate() {
            let name = match what {
                Capacity::Vertices => "vertices (VERTS)",
                Capacity::Triangles => "triangles (TRIS)",
                Capacity::ActiveTriangles => "triangles active on one row (ACTIVE)",
            };
            let sep = if k > 0 { "; " } else { "" };
            let about = if self.exact { "" } else { "about " };
            write!(f, "{sep}{name}: needs {about}{needed}, has {capacity}")?;
        }
        if self.skipped > 0 {
            write!(f, "; {} triangles skipped", self.skipped)?;
        }
        Ok(())
    }
}

/// What the renderer does with a frame that does not fit its capacities
/// ([`Renderer::with_overflow`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum OverflowPolicy {
    /// The frame fails with [`Error::Shortfall`] before anything is drawn (the default): on a
    /// display without a framebuffer the previous image stays on the panel.
    #[default]
    Error,
    /// The frame is drawn without what does not fit, and [`Renderer::shortfall`] says what was
    /// needed and how many triangles were left out: objects whose vertices do not fit the
    /// vertex store (in scene order, the later ones), triangles that do not fit the triangle
    /// store (the later ones), and triangles that start on a row where the active list is
    /// full (each dropped as a whole, never drawn in part). The frame is never an error for
    /// its capacities and never panics; the image has holes where triangles were left out.
    DrawWhatFits,
}

/// A pipeline stage, as reported to a [`Probe`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Stage {
    /// Per-vertex transform, outcodes and projection.
    Vertices,
    /// Per-vertex (Gouraud) or per-face (flat) lighting.
    Lighting,
    /// Per-triangle culling, clipping and bucketing.
    Triangles,
    /// Per-triangle edge and gradient setup when a triangle becomes active.
    Setup,
    /// Line clears and spans.
    Raster,
    /// Handing finished strips to the draw target.
    Output,
    /// The frame is finished.
    Done,
}

/// Observes stage changes during a frame, e.g. to count instructions per stage on a
/// microcontroller. [`Renderer::render`] uses [`NoProbe`], which compiles to nothing.
pub trait Probe {
    /// Called when the renderer enters `stage`.
    fn enter(&mut self, stage: Stage);
    /// Called first thing in a frame, before any work.
    #[inline(always)]
    fn frame_start(&mut self) {}
    /// Called last thing in a frame, after the last strip was handed to the target.
    #[inline(always)]
    fn frame_end(&mut self) {}
    /// Called for every vertex as it is snapped to the subpixel grid, with its index in the
    /// frame's vertex store (mesh vertices in scene order, then clipper output in triangle
    /// order) and its position in subpixels; returns the position to use. The default keeps it.
    /// Comparison tools use this to run two number types on identical screen geometry.
    #[inline(always)]
    fn snap(&mut self, index: u32, x: i32, y: i32) -> (i32, i32) {
        let _ = index;
        (x, y)
    }
    /// Whether [`Probe::snap`] may move a vertex. A probe that keeps the default `snap` can
    /// say `false`, and the renderer then need not call it: on a Cortex-M0 the Q16.16 vertex
    /// loop stores runs of vertices in assembly and would otherwise pass over them again for
    /// the snapping (about 40 instructions a vertex). A probe that overrides `snap` must leave
    /// it `true`.
    const SNAPS: bool = true;
}

/// A probe that does nothing.
#[derive(Copy, Clone, Debug, Default)]
pub struct NoProbe;

impl Probe for NoProbe {
    #[inline(always)]
    fn enter(&mut self, _: Stage) {}
    const SNAPS: bool = false;
}

/// What happened to the triangles and pixels of a frame.
///
/// `repr(C)`: on Cortex-M0 the triangle loop's assembly counts into it by field offset.
/// `#[non_exhaustive]`: more counts may be added; start from `Stats::default()`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C)]
#[non_exhaustive]
pub struct Stats {
    /// Triangles in the scene's meshes.
    pub triangles_in: u32,
    /// Skipped: an index out of range, or a vertex that is NaN, infinite or overflowed (a
    /// fixed-point position at a saturation rail, where NaN and ±∞ inputs land, included);
    /// and every triangle of an object whose transform, material coefficients or scene light
    /// directions are not valid in the number type (NaN, infinite, or a fixed-point rail).
    /// The same for every number type.
    pub invalid: u32,
    /// Rejected: entirely outside the view volume or the screen, or clipped away.
    pub outside: u32,
    /// Back faces culled (negative snapped area).
    pub culled: u32,
    /// Zero snapped area (including slivers that collapse when snapped).
    pub degenerate: u32,
    /// Triangles that went through the near/far/guard-band clipper.
    pub clipped: u32,
    /// Triangles (after clipping) that cover no pixel centre.
    pub empty: u32,
    /// Triangles (after clipping) handed to the rasterizer.
    pub drawn: u32,
    /// Vertices needed (mesh vertices, clipper output, and one face-colour vertex per flat
    /// triangle).
    pub vertices: u32,
    /// Of those, the face-colour vertices of flat-shaded triangles (copies of a corner).
    pub color_vertices: u32,
    /// Pixels tested against the depth buffer (saturates at `u32::MAX`).
    pub fragments: u32,
    /// Pixels that passed the depth test and were written to the strip (saturates).
    pub pixels_written: u32,
    /// The largest number of triangles active on one row.
    pub max_active: u32,
}

impl Stats {
    /// Adds the counts of another pass of the same frame ([`Renderer::render_passes`]):
    /// `max_active` is the larger of the two, every other field the sum (saturating).
    fn add_pass(&mut self, p: &Stats) {
        let add = |a: &mut u32, b: u32| *a = a.saturating_add(b);
        add(&mut self.triangles_in, p.triangles_in);
        add(&mut self.invalid, p.invalid);
        add(&mut self.outside, p.outside);
        add(&mut self.culled, p.culled);
        add(&mut self.degenerate, p.degenerate);
        add(&mut self.clipped, p.clipped);
        add(&mut self.empty, p.empty);
        add(&mut self.drawn, p.drawn);
        add(&mut self.vertices, p.vertices);
        add(&mut self.color_vertices, p.color_vertices);
        add(&mut self.fragments, p.fragments);
        add(&mut self.pixels_written, p.pixels_written);
        self.max_active = self.max_active.max(p.max_active);
    }

    /// Counts one triangle-row's fragments and written pixels (saturating).
    fn add_row(&mut self, fragments: u32, written: u32) {
        self.fragments = self.fragments.saturating_add(fragments);
        self.pixels_written = self.pixels_written.saturating_add(written);
    }
}

/// A scanline Z-buffer renderer with a strip of `LINES` lines of `W` pixels.
///
/// * `S` — the number type of the geometry pipeline ([`crate::Fx`]`<I16F16>`, `f32`, `f64`).
/// * `C` — the target's pixel colour.
/// * `W`, `H` — the screen size in pixels (1..=1024), drawn at the target's origin; the
///   target must contain it ([`Error::TargetTooSmall`] otherwise).
/// * `VERTS` — vertex store (1..=32 768): all mesh vertices of a frame, those made by
///   clipping, and one per drawn flat-shaded triangle (a copy of a vertex carrying the face
///   colour). A frame's figure is [`Stats::vertices`].
/// * `TRIS` — triangles a frame can keep after culling (1..=32 767); [`Stats::drawn`].
/// * `ACTIVE` — triangles that may cross one row at once (1..=32 768); [`Stats::max_active`].
/// * `LINES` — rows per strip (default 1).
///
/// # Capacities
///
/// The limits above are checked at compile time, when [`Renderer::new`] or
/// [`Renderer::const_new`] is instantiated (a `cargo build`, not a `cargo check`): zero
/// capacities, for instance, do not compile.
///
/// ```compile_fail
/// # use embedded_graphics::pixelcolor::Rgb565;
/// # use scanline3d::Renderer;
/// // VERTS = 0: "VERTS must be 1..=32768"
/// let r = Renderer::<f32, Rgb565, 64, 64, 0, 16, 16>::new();
/// ```
///
/// A frame that needs more than the capacities fails with [`Error::Shortfall`], which names
/// every capacity that is short and what the frame needed, before anything is drawn; with
/// [`OverflowPolicy::DrawWhatFits`] ([`Renderer::with_overflow`]) it is drawn without what
/// does not fit instead, and [`Renderer::shortfall`] reports it. [`Renderer::needs`] measures
/// a frame's needs on the host, for sizing the device's renderer ([`Needs`] has an example).
///
/// # Placement
///
/// A renderer is large (its capacities are arrays inside it), so build it where it lives:
/// [`Renderer::const_new`] is a `const fn`, for a `static` (in firmware, e.g. behind a
/// critical-section mutex, a `StaticCell`, or `cortex_m::singleton!`):
///
/// ```
/// # use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// # use scanline3d::prelude::*;
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// use std::sync::Mutex; // on a device: critical_section::Mutex<RefCell<..>>, StaticCell, ...
/// type Big = Renderer<Q, Rgb565, 240, 240, 4096, 4096, 512>;
/// static RENDERER: Mutex<Big> = Mutex::new(Big::const_new(Rgb565::BLACK));
///
/// let mut renderer = RENDERER.lock().unwrap();
/// renderer.set_dither(true);
/// # let _ = renderer.viewport();
/// ```
///
/// `Renderer::new()` returns the renderer by value, which may go through the stack first (a
/// `Box::new(Renderer::new())` does in a debug build): fine for small renderers, not for one
/// near the stack's size. A `static` with a non-zero initial value is in `.data`: its initial
/// image ([`Renderer::RAM_BYTES`]) is also in flash.
///
/// # RAM
///
/// `size_of::<Renderer>()` ≈ `LINES·W·(size_of::<C>() + 2)` (colour and depth lines)
/// `+ 12·VERTS + 6·TRIS + 84·ACTIVE` (vertex store, triangle list, active list)
/// `+ 4·H` (row buckets and the active-count sweep) plus a few words; [`Renderer::RAM_BYTES`]
/// is the exact figure for a given instantiation. No framebuffer, no full-screen depth buffer.
#[derive(Debug)]
pub struct Renderer<
    S,
    C,
    const W: usize,
    const H: usize,
    const VERTS: usize,
    const TRIS: usize,
    const ACTIVE: usize,
    const LINES: usize = 1,
> {
    verts: Vec<ScreenVertex, VERTS>,
    tris: Vec<TriRecord, TRIS>,
    active: ActiveList<ACTIVE>,
    /// Per row: during geometry the number of triangles whose first row it is; then the index
    /// of the first of them in `tris` (sorted by first row).
    heads: [u16; H],
    /// Per row: during geometry the change of the active-triangle count (+1 for each triangle
    /// starting, −1 for each ending); then the insertion cursors of the bucket sort.
    starts: [i16; H],
    color: [[C; W]; LINES],
    depth: [[u16; W]; LINES],
    depth_test: DepthTest,
    dither: bool,
    /// Next row to rasterize (`vh` when no frame is prepared).
    next_row: usize,
    /// Viewport actually drawn, `vw ≤ W`, `vh ≤ H` (default `W × H`).
    vw: usize,
    vh: usize,
    background: C,
    stats: Stats,
    overflow: OverflowPolicy,
    /// Of the prepared frame, under [`OverflowPolicy::DrawWhatFits`]: the triangles needed but
    /// not stored (the frame needed `stats.drawn + store_skipped` triangles; its other needs
    /// are in `stats`), and those dropped from a full active list so far.
    store_skipped: u32,
    active_skipped: u32,
    _s: PhantomData<S>,
}

/// What the lighting routine ([`Scalar::light_run_565`]) needs of an object: its mesh's
/// normals, its one light's direction (in the object's space) and colour fraction.
type QuickLight<'n, S> = (&'n [Vec3<S>], Vec3<S>, S);

/// Per-object state of the geometry stage.
struct ObjectSetup<'o, 'a, S: Scalar, const L: usize> {
    obj: &'o Object<'a, S>,
    mvp: Mat4<S>,
    normal_matrix: Mat4<S>,
    similar: bool,
    /// The lights: in world space, or in the object's space when `in_object` holds
    /// ([`PreparedLight::in_object_space`]; then vertex normals are used as they are).
    lights: &'o [PreparedLight<S>; L],
    /// Gouraud shading (so no face normals, which are in world space), a normal matrix that
    /// is a rotation (`similar`) and no specular term (which would need the eye direction).
    in_object: bool,
    /// The transform mirrors (negative determinant): the triangle loop swaps each triangle's
    /// winding, so the outside stays the front.
    mirrored: bool,
    eye: Vec3<S>,
    base: usize,
}

impl<S: Scalar, const L: usize> ObjectSetup<'_, '_, S, L> {
    fn to_eye(&self, p: Vec3<S>) -> Vec3<S> {
        if self.obj.material.specular > S::ZERO {
            let w = self.obj.transform.transform_point(p);
            normalize(sub(self.eye, [w[0], w[1], w[2]]))
        } else {
            [S::ZERO; 3]
        }
    }

    fn world_normal(&self, n: Vec3<S>, force: bool) -> Vec3<S> {
        let n = self.normal_matrix.transform_dir(n);
        if self.similar && !force {
            n
        } else {
            normalize(n)
        }
    }

    /// What [`Scalar::light_run_565`] needs when it can light this object's vertices: the
    /// number type has the routine, the target is RGB565, the lights are in the object's space
    /// (no specular term), there is one light and it is grey, and the mesh has normals. Then
    /// the normals, the light's direction and its colour fraction.
    fn quick_light<C: TargetColor>(&self) -> Option<QuickLight<'_, S>> {
        if !(S::LIGHT_RUN && self.in_object && C::CHANNEL_MAX == [31, 63, 31]) {
            return None;
        }
        let [l] = self.lights.as_slice() else {
            return None;
        };
        let (dir, frac) = l.grey()?;
        Some((self.obj.mesh.normals()?, dir, frac))
    }

    /// Lights record `v` as mesh vertex `i` ([`Self::vertex_color`]) and marks it [`LIT`].
    #[inline(always)]
    fn light<C: TargetColor>(&self, v: &mut ScreenVertex, i: usize) {
        v.set_color(self.vertex_color::<C>(i));
        v.flags |= LIT;
    }

    /// Lit colour of mesh vertex `i`, in the vertex format ([`ScreenVertex::color`]).
    fn vertex_color<C: TargetColor>(&self, i: usize) -> [u16; 3] {
        let mesh = &self.obj.mesh;
        let p = mesh.positions()[i];
        let n = mesh.normals().map_or([S::ZERO; 3], |ns| ns[i]);
        let lit = if self.in_object {
            // The same dot products without a normal transform per vertex (and no specular
            // term: `in_object` requires none).
            lit_diffuse(&self.obj.material, self.lights, n)
        } else {
            lit_color(
                &self.obj.material,
                self.lights,
                self.world_normal(n, false),
                self.to_eye(p),
            )
        };
        pack_channels(C::vertex_channels(lit), C::CHANNEL_MAX)
    }

    /// Lit colour of a face, in the target's channel units (8.8).
    /// `tri` in screen winding (swapped for a mirrored object, whose mesh order is restored
    /// here for the face normal).
    fn face_color<C: TargetColor>(&self, tri: [u16; 3]) -> [u16; 3] {
        let [a, b, c] = tri.map(|i| self.obj.mesh.positions()[i as usize]);
        let (b, c) = if self.mirrored { (c, b) } else { (b, c) };
        let n = self.world_normal(face_normal(a, b, c), true);
        let k = S::from_f64(1.0 / 3.0);
        let centroid = [0, 1, 2].map(|j| (a[j] + b[j] + c[j]) * k);
        let lit = lit_color(&self.obj.material, self.lights, n, self.to_eye(centroid));
        C::vertex_channels(lit)
    }
}

impl<
        S: Scalar,
        C: TargetColor,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES>
{
    /// Exact RAM of this renderer in bytes.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// This renderer's capacities (`VERTS`, `TRIS`, `ACTIVE`), to compare a frame's
    /// [`Needs`] with.
    pub const CAPACITY: Needs = Needs::new(VERTS, TRIS, ACTIVE);

    const CHECK: () = {
        assert!(W >= 1 && W <= MAX_SCREEN, "W must be 1..=1024");
        assert!(H >= 1 && H <= MAX_SCREEN, "H must be 1..=1024");
        assert!(LINES >= 1, "LINES must be at least 1");
        assert!(
            VERTS >= 1 && VERTS <= FLAT_BIT as usize,
            "VERTS must be 1..=32768"
        );
        assert!(
            TRIS >= 1 && TRIS <= i16::MAX as usize,
            "TRIS must be 1..=32767"
        );
        assert!(
            ACTIVE >= 1 && ACTIVE <= ActiveList::<ACTIVE>::MAX,
            "ACTIVE must be 1..=32768"
        );
    };

    /// A renderer with the default options (depth test [`DepthTest::Less`], no dithering,
    /// [`OverflowPolicy::Error`]). Returned by value: for a large renderer, see
    /// [`Renderer::const_new`] (the type's docs, "Placement").
    #[must_use]
    pub fn new() -> Self {
        Self::const_new(C::from_channels([0; 3]))
    }

    /// [`Renderer::new`] as a `const fn`, for a `static` renderer (see the type's docs,
    /// "Placement"). `fill` is the colour the strip lines hold until the first frame (each line
    /// is cleared to the scene's background before it is drawn, so any colour does; a trait
    /// method cannot give a colour in a `const fn`): e.g. `Rgb565::BLACK`.
    #[must_use]
    pub const fn const_new(fill: C) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CHECK;
        Renderer {
            verts: Vec::new(),
            tris: Vec::new(),
            active: ActiveList::new(),
            heads: [0; H],
            starts: [0; H],
            color: [[fill; W]; LINES],
            depth: [[u16::MAX; W]; LINES],
            depth_test: DepthTest::Less,
            dither: false,
            next_row: H,
            vw: W,
            vh: H,
            background: fill,
            stats: Stats {
                triangles_in: 0,
                invalid: 0,
                outside: 0,
                culled: 0,
                degenerate: 0,
                clipped: 0,
                empty: 0,
                drawn: 0,
                vertices: 0,
                color_vertices: 0,
                fragments: 0,
                pixels_written: 0,
                max_active: 0,
            },
            overflow: OverflowPolicy::Error,
            store_skipped: 0,
            active_skipped: 0,
            _s: PhantomData,
        }
    }

    /// Sets what happens to a frame that does not fit the capacities ([`OverflowPolicy`];
    /// default [`OverflowPolicy::Error`]).
    #[must_use]
    pub fn with_overflow(mut self, policy: OverflowPolicy) -> Self {
        self.overflow = policy;
        self
    }

    /// Sets the overflow policy in place.
    pub fn set_overflow(&mut self, policy: OverflowPolicy) {
        self.overflow = policy;
    }

    /// The overflow policy.
    #[must_use]
    pub fn overflow(&self) -> OverflowPolicy {
        self.overflow
    }

    /// What the last prepared frame (the one being drawn, or drawn last) needed beyond the
    /// capacities, or `None` when it fit. Under [`OverflowPolicy::DrawWhatFits`] this is how a
    /// frame drawn in part says so: [`Shortfall::skipped`] counts the triangles left out
    /// (complete once the frame is drawn). A frame that failed with [`Error::Shortfall`] was
    /// not prepared: the error carries its shortfall.
    #[must_use]
    pub fn shortfall(&self) -> Option<Shortfall> {
        let s = &self.stats;
        let needed = Needs::new(
            s.vertices as usize,
            s.drawn as usize + self.store_skipped as usize,
            s.max_active as usize,
        );
        if needed.fits(&Self::CAPACITY) {
            return None;
        }
        Some(Shortfall {
            needed,
            capacity: Self::CAPACITY,
            exact: needed.vertices <= VERTS && needed.triangles <= TRIS,
            skipped: self.store_skipped as usize + self.active_skipped as usize,
        })
    }

    /// Measures what a frame of `scene` needs of each capacity ([`Needs`]): runs the geometry
    /// stage (as [`Renderer::prepare`] does, whatever the overflow policy) and leaves no frame
    /// prepared. For sizing a device's renderer on the host, with a renderer of the device's
    /// `W × H` (or viewport) and generous capacities; accumulate an animation's frames with
    /// [`Needs::max`].
    ///
    /// # Errors
    ///
    /// [`Error::MissingNormals`] as for a frame; [`Error::Shortfall`] when this renderer's
    /// vertex or triangle store is too small to measure the frame exactly (its figures are
    /// then estimates, [`Shortfall::exact`] is false). A frame whose only shortfall is the
    /// active list is measured exactly: `Ok`.
    pub fn needs<const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
    ) -> Result<Needs, Error<core::convert::Infallible>> {
        let policy = self.overflow;
        self.overflow = OverflowPolicy::DrawWhatFits;
        let result = self.geometry(scene, &mut NoProbe);
        self.overflow = policy;
        self.next_row = self.vh;
        let stats = result?;
        match self.shortfall() {
            None => Ok(Needs::from_stats(&stats)),
            Some(s) if s.exact => Ok(s.needed),
            Some(mut s) => {
                s.skipped = 0;
                Err(Error::Shortfall(s))
            }
        }
    }

    /// [`Error::TargetTooSmall`] unless `target` contains the viewport at its origin.
    fn check_target<D: Dimensions, E>(&self, target: &D) -> Result<(), Error<E>> {
        let bb = target.bounding_box();
        let (x0, y0) = (bb.top_left.x as i64, bb.top_left.y as i64);
        let (x1, y1) = (x0 + bb.size.width as i64, y0 + bb.size.height as i64);
        if x0 <= 0 && y0 <= 0 && x1 >= self.vw as i64 && y1 >= self.vh as i64 {
            Ok(())
        } else {
            Err(Error::TargetTooSmall {
                viewport: Size::new(self.vw as u32, self.vh as u32),
                target: bb,
            })
        }
    }

    /// Enables or disables 4×4 ordered dithering of Gouraud gradients (for targets with fewer
    /// than 8 bits per channel, such as RGB565).
    #[must_use]
    pub fn with_dither(mut self, on: bool) -> Self {
        self.set_dither(on);
        self
    }

    /// Sets the depth test.
    #[must_use]
    pub fn with_depth_test(mut self, test: DepthTest) -> Self {
        self.depth_test = test;
        self
    }

    /// Draws into a `width × height` viewport at the target's origin instead of the full
    /// `W × H` (clamped to 1..=W and 1..=H): one renderer type for several panel sizes, or a
    /// preview at any size. The projection's aspect ratio follows the viewport.
    pub fn set_viewport(&mut self, width: usize, height: usize) {
        self.vw = width.clamp(1, W);
        self.vh = height.clamp(1, H);
        self.next_row = self.vh;
    }

    /// The viewport size (`W × H` unless changed by [`Renderer::set_viewport`]).
    #[must_use]
    pub fn viewport(&self) -> (usize, usize) {
        (self.vw, self.vh)
    }

    /// Sets the depth test in place.
    pub fn set_depth_test(&mut self, test: DepthTest) {
        self.depth_test = test;
    }

    /// Enables or disables dithering in place (between strips too: the triangles already set
    /// up for the frame are drawn the new way from the next strip on).
    pub fn set_dither(&mut self, on: bool) {
        if on != self.dither {
            self.dither = on;
            // The dithered row routine draws only triangles checked for it at setup.
            self.active
                .refresh_routine_rows(self.next_row as i32, on && C::can_dither());
        }
    }

    /// Draws one frame of `scene` into `target`, at the target's origin, `W × H` pixels (the
    /// viewport).
    ///
    /// A target that does not contain the viewport ([`Error::TargetTooSmall`]), capacity
    /// shortfalls ([`Error::Shortfall`], unless the policy is
    /// [`OverflowPolicy::DrawWhatFits`]) and missing normals are found before anything is
    /// drawn. A target error stops the frame at the failing strip and is returned.
    pub fn render<D, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        self.render_probed(scene, target, &mut NoProbe)
    }

    /// [`Renderer::render`] with `overlay` (text, a HUD, any embedded-graphics [`Drawable`])
    /// composed into every strip after the 3D content and before the strip is sent. The
    /// overlay is drawn once per strip, clipped to it, so its cost grows with the number of
    /// strips: keep overlays small (a line of text) or use a taller strip. For a label on a
    /// microcontroller, [`crate::overlay::Glyphs`] composed into [`Renderer::render_strip_into`]'s
    /// lines does the font work once and touches only the strips the text crosses.
    pub fn render_overlaid<D, O, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        target: &mut D,
        overlay: &O,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
        O: Drawable<Color = C>,
    {
        let mut probe = NoProbe;
        self.check_target(target)?;
        self.geometry(scene, &mut probe)?;
        while self
            .strip(target, &mut probe, |canvas| {
                let _ = overlay.draw(canvas);
            })?
            .is_some()
        {}
        Ok(self.stats)
    }

    /// [`Renderer::render`], reporting each stage change to `probe`.
    pub fn render_probed<D, P, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        target: &mut D,
        probe: &mut P,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
        P: Probe,
    {
        probe.frame_start();
        let result = self
            .check_target(target)
            .and_then(|_| self.geometry(scene, probe))
            .and_then(|_| {
                probe.enter(Stage::Raster);
                while self.strip(target, probe, |_| {})?.is_some() {}
                Ok(self.stats)
            });
        probe.enter(Stage::Done);
        probe.frame_end();
        result
    }

    /// Draws the scenes of `passes` one after another into the same colour and depth lines, as
    /// one frame, and sends the frame to `target` once: a frame larger than the capacities,
    /// split between scenes (objects, or a mesh cut into pieces) that each fit, on a renderer
    /// whose strip holds the whole viewport (`LINES` ≥ the viewport's height, so a host's
    /// preview rather than a microcontroller's strip). Where two passes draw the same pixel the
    /// depth test decides, as within a pass, and a mesh cut between passes covers exactly the
    /// pixels it covers in one pass (the top-left rule decides a shared edge's pixels whatever
    /// the order), so the frame equals the one-pass frame wherever no two triangles have equal
    /// depth at a pixel (there the first one drawn stays under [`DepthTest::Less`], the last
    /// under [`DepthTest::LessEqual`]; under [`DepthTest::Always`] a later pass is drawn over
    /// an earlier one).
    ///
    /// The frame is cleared to the first scene's background; the other scenes' backgrounds are
    /// not used. An empty `passes` draws nothing and returns `Stats::default()`. The returned
    /// [`Stats`] add up the passes' counts except [`Stats::max_active`], the largest of any
    /// pass: `drawn` is what one renderer drawing the frame in one pass would store, while
    /// `vertices` counts a vertex once for each pass whose mesh has it. [`Renderer::stats`]
    /// and [`Renderer::shortfall`] are the last pass's. The overflow policy applies to each
    /// pass.
    ///
    /// # Errors
    ///
    /// [`Error::StripTooShort`] when `LINES` is less than the viewport's height,
    /// [`Error::TargetTooSmall`], and a pass's [`Error::Shortfall`], [`Error::MissingNormals`]
    /// or [`Error::Camera`]: all before anything is sent to the target (the passes before the
    /// failing one were drawn into the lines only). A target error is returned as
    /// [`Error::Target`].
    pub fn render_passes<D, const L: usize>(
        &mut self,
        passes: &[Scene<'_, S, L>],
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        let Some(first) = passes.first() else {
            return Ok(Stats::default());
        };
        let (vw, vh) = (self.vw, self.vh);
        if LINES < vh {
            return Err(Error::StripTooShort {
                lines: LINES,
                height: vh,
            });
        }
        self.check_target(target)?;
        let background = crate::color::quantize::<C>(first.background);
        for (c, d) in self.color[..vh].iter_mut().zip(&mut self.depth[..vh]) {
            c[..vw].fill(background);
            d[..vw].fill(u16::MAX);
        }
        let mut total = Stats::default();
        for scene in passes {
            self.geometry(scene, &mut NoProbe)?;
            // One strip: `LINES` ≥ `vh` rows from row 0.
            while self
                .draw_strip::<NoProbe, false>(None, LINES, &mut NoProbe)
                .is_some()
            {}
            total.add_pass(&self.stats);
        }
        let area = Rectangle::new(Point::zero(), Size::new(vw as u32, vh as u32));
        target
            .fill_contiguous(
                &area,
                self.color[..vh]
                    .iter()
                    .flat_map(|line| line[..vw].iter())
                    .copied(),
            )
            .map_err(Error::Target)?;
        Ok(total)
    }

    /// Runs the geometry stage (transform, light, clip, project, cull, bucket) for a frame of
    /// `scene` and reports what it needs; nothing is drawn yet. Then [`Renderer::render_strip`]
    /// draws the frame one strip at a time, which lets a caller interleave the strips with other
    /// work (a DMA transfer, or a second renderer for comparison).
    pub fn prepare<const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
    ) -> Result<Stats, Error<core::convert::Infallible>> {
        self.geometry(scene, &mut NoProbe)
    }

    /// [`Renderer::prepare`], reporting stages and snapped vertices to `probe`.
    pub fn prepare_probed<P: Probe, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Stats, Error<core::convert::Infallible>> {
        self.geometry(scene, probe)
    }

    /// Draws the next strip of the prepared frame into `target` and returns its rows, or
    /// `None` when the frame is complete (or nothing was prepared). A target that does not
    /// contain the viewport is [`Error::TargetTooSmall`] and nothing is drawn (the frame stays
    /// prepared).
    pub fn render_strip<D>(
        &mut self,
        target: &mut D,
    ) -> Result<Option<core::ops::Range<usize>>, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        self.render_strip_probed(target, &mut NoProbe)
    }

    /// Moves the strip pass of the prepared frame to `row` (clamped to the viewport's height):
    /// the next strip starts there; rows above it are not drawn. The triangles that cross
    /// `row` are set up at that row, so the strips from it on are those a whole frame has,
    /// within one step of a channel on a few pixels: a setup computes a triangle's colours at
    /// the seek row exactly, while the whole frame's row pass steps them down from the
    /// triangle's first row with a rounding drift. For splitting a frame's rows between
    /// renderers or cores that share its geometry (the Pico benchmark measures that split), or
    /// for redrawing part of the screen from the same geometry, also after the frame was drawn.
    ///
    /// Costs a look at the lowest vertex of each stored triangle that starts above `row`, and
    /// one triangle setup for each of those that cross it.
    pub fn seek_row(&mut self, row: usize) {
        let vh = self.vh;
        let row = row.min(vh);
        self.active.clear();
        self.next_row = row;
        if row >= vh {
            return;
        }
        let mode = SpanMode::new::<C>(self.depth_test, self.dither);
        let verts = &self.verts;
        for rec in &self.tris[..self.heads[row] as usize] {
            // A triangle that ends above the row needs no setup to be skipped: its lowest
            // vertex's first row (what setup would find) is at most `row`.
            let [i, j, k] = rec.indices();
            let y_max = verts[i].y.max(verts[j].y).max(verts[k].y);
            if first_pixel(y_max as i32) <= row as i32 {
                continue;
            }
            // Full only under `OverflowPolicy::DrawWhatFits` (the largest number of triangles
            // crossing one row was checked when the frame was prepared): the triangle is left
            // out and counted.
            if !self
                .active
                .push_with(|a| a.setup::<C>(rec, verts, row as i32, vh as i32, mode))
            {
                self.active_skipped = self.active_skipped.saturating_add(1);
            }
        }
    }

    /// The next row the strip pass draws (the viewport's height once the frame is complete or
    /// when nothing is prepared).
    #[must_use]
    pub fn next_row(&self) -> usize {
        self.next_row
    }

    /// The statistics of the frame being drawn (complete once the last strip is drawn).
    #[must_use]
    pub fn stats(&self) -> Stats {
        self.stats
    }

    fn geometry<E, P: Probe, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Stats, Error<E>> {
        self.verts.clear();
        self.tris.clear();
        self.active.clear();
        self.heads = [0; H];
        self.starts = [0; H];
        self.next_row = self.vh;
        let mut stats = Stats::default();
        for (i, o) in scene.objects.iter().enumerate() {
            if o.material.shading == Shading::Gouraud && o.mesh.normals().is_none() {
                return Err(Error::MissingNormals { object: i });
            }
        }
        let vp = Viewport {
            width: self.vw as u32,
            height: self.vh as u32,
        };
        let g = S::from_i32(vp.guard_band());
        // The camera's fields are public: checked every frame (a few dozen comparisons).
        scene.camera.validate().map_err(Error::Camera)?;
        let pv = scene
            .camera
            .projection
            .matrix(vp.aspect())
            .mul(&scene.camera.view);
        let mut need = (0usize, 0usize);
        // NaN, infinite or (fixed point) saturated inputs are skipped and counted per object,
        // the same for every number type (a float NaN would poison every vertex).
        let ok = |v: &S| v.is_valid();
        let lights_ok = scene.lights.iter().all(|l| l.direction.iter().all(ok));
        for obj in scene.objects {
            let m = &obj.material;
            if !(lights_ok
                && obj.transform.m.iter().all(|r| r.iter().all(ok))
                && [m.ambient, m.diffuse, m.specular].iter().all(ok))
            {
                let n = obj.mesh.indices().len() as u32;
                need.0 += obj.mesh.positions().len();
                stats.triangles_in = stats.triangles_in.wrapping_add(n);
                stats.invalid += n;
                continue;
            }
            let (normal_matrix, similar, mirrored) = obj.transform.normal_matrix_mirrored();
            let in_object = similar
                && obj.material.shading == Shading::Gouraud
                && obj.material.specular <= S::ZERO;
            // Prepared per object, in place (one array of lights on the stack: a 16 KB part
            // has no room for a second).
            let mut lights = scene.lights.map(|l| PreparedLight::new(&l));
            if in_object {
                for l in &mut lights {
                    *l = l.in_object_space(&normal_matrix);
                }
            }
            let setup = ObjectSetup {
                obj,
                mvp: pv.mul(&obj.transform),
                normal_matrix,
                similar,
                lights: &lights,
                in_object,
                mirrored,
                eye: scene.camera.eye,
                base: self.verts.len(),
            };
            self.object(&setup, &vp, g, &mut stats, &mut need, probe);
        }
        stats.vertices = need.0 as u32;
        let mut cur = 0i32;
        let mut max = 0i32;
        for &s in self.starts.iter() {
            cur += s as i32;
            max = max.max(cur);
        }
        stats.max_active = max as u32;
        // Triangles needed but not stored (only when the store or the vertices overflowed).
        let store_skipped = need.1.saturating_sub(self.tris.len());
        if need.0 > VERTS || need.1 > TRIS || max as usize > ACTIVE {
            // Every capacity at once: what the frame needed against all three.
            let needed = Needs::new(need.0, need.1, max as usize);
            if self.overflow == OverflowPolicy::Error {
                return Err(Error::Shortfall(Shortfall {
                    needed,
                    capacity: Self::CAPACITY,
                    exact: need.0 <= VERTS && need.1 <= TRIS,
                    skipped: 0,
                }));
            }
        }
        self.store_skipped = store_skipped.min(u32::MAX as usize) as u32;
        self.active_skipped = 0;
        self.sort_buckets();
        self.background = crate::color::quantize::<C>(scene.background);
        self.next_row = 0;
        self.stats = stats;
        Ok(stats)
    }

    /// The bucket of a stored triangle (see [`bucket_row`]).
    fn first_row(&self, t: &TriRecord) -> usize {
        // Element by element: on a Cortex-M0 `array::map` stays a call (`try_from_fn`).
        let [i, j, k] = t.indices();
        let (a, b, c) = (self.verts[i].y, self.verts[j].y, self.verts[k].y);
        let (a, b, c) = (a as i32, b as i32, c as i32);
        bucket_row(a.min(b).min(c))
    }

    /// Sorts the triangles by first row in place (an American-flag bucket sort: every record
    /// moves at most once), turning `heads` from counts into bucket starts. No list links are
    /// stored, which saves 2 bytes per triangle.
    fn sort_buckets(&mut self) {
        let vh = self.vh;
        let mut acc = 0u16;
        for r in 0..vh {
            let n = self.heads[r];
            self.heads[r] = acc;
            self.starts[r] = acc as i16;
            acc += n;
        }
        let len = self.tris.len();
        for b in 0..vh {
            let end = if b + 1 < vh {
                self.heads[b + 1] as usize
            } else {
                len
            };
            // The record at bucket b's cursor goes to its own bucket's cursor, and the record
            // it displaces is placed next, until one belongs to bucket b (as swapping the two
            // records each time would place them, with one read and one write a step).
            let mut i = self.starts[b] as usize;
            while i < end {
                let Some(&first) = self.tris.get(i) else {
                    break;
                };
                let mut t = first;
                let mut tb = self.first_row(&t);
                while tb != b {
                    // tb > b: every earlier bucket is complete.
                    let Some(j) = self.starts.get_mut(tb) else {
                        break;
                    };
                    let Some(slot) = self.tris.get_mut(*j as usize) else {
                        break;
                    };
                    *j += 1;
                    core::mem::swap(&mut t, slot);
                    tb = self.first_row(&t);
                }
                if let Some(slot) = self.tris.get_mut(i) {
                    *slot = t;
                }
                i += 1;
            }
            self.starts[b] = i as i16;
        }
    }

    /// Transforms, lights, clips, projects, culls and buckets one object.
    fn object<P: Probe, const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        vp: &Viewport,
        g: S,
        stats: &mut Stats,
        need: &mut (usize, usize),
        probe: &mut P,
    ) {
        let mesh = o.obj.mesh;
        let positions = mesh.positions();
        need.0 += positions.len();
        if o.base + positions.len() > VERTS {
            // Count what the object would need; nothing of it can be stored.
            stats.triangles_in += mesh.indices().len() as u32;
            need.1 += mesh.indices().len();
            return;
        }
        probe.enter(Stage::Vertices);
        if S::PROJECT_RUN && !mesh.has_invalid_positions() {
            let (sx, sy) = (8 * vp.width, 8 * vp.height);
            let mut i = 0;
            loop {
                // A run of vertices the number type stores itself (Q16.16 on a Cortex-M0),
                // then the probe's snapping for them (if it snaps); then one vertex here.
                let first = self.verts.len();
                let rest = positions.get(i..).unwrap_or(&[]);
                let run = S::project_run(&o.mvp.m, rest, g, sx, sy, &mut self.verts);
                let snaps = if P::SNAPS { run } else { 0 };
                for (k, v) in self.verts.iter_mut().enumerate().skip(first).take(snaps) {
                    if v.flags & PROJECTED != 0 {
                        let index = k - stats.color_vertices as usize;
                        (v.x, v.y) = snapped(probe, index, *v);
                    }
                }
                i += run;
                let Some(&p) = positions.get(i) else {
                    break;
                };
                i += 1;
                self.push_vertex(o, vp, g, p, stats, probe);
            }
        } else if !mesh.has_invalid_positions() {
            for &p in positions {
                self.push_vertex(o, vp, g, p, stats, probe);
            }
        } else {
            // A position NaN, infinite or at a fixed-point rail (known when the mesh was
            // built): its record is invalid, as a float NaN's clip coordinates make it.
            for &p in positions {
                self.push_vertex(o, vp, g, p, stats, probe);
                if !p.iter().all(|v| v.is_valid()) {
                    if let Some(v) = self.verts.last_mut() {
                        v.flags |= INVALID;
                    }
                }
            }
        }
        let flat = o.obj.material.shading == Shading::Flat;
        probe.enter(Stage::Triangles);
        // The triangles' ids follow on from the earlier objects' (counted once, not per
        // triangle through `stats`).
        let first_id = stats.triangles_in;
        let tris = mesh.indices();
        stats.triangles_in = first_id.wrapping_add(tris.len() as u32);
        let (base, n) = (o.base, positions.len());
        // Gouraud triangles of real colours go through `cull_push` (the common cases: cull,
        // count and bucket; vertices of stored front faces are marked for lighting), which
        // stops at a triangle that needs this loop's full path; flat ones and triangle ids
        // take the full path throughout.
        let fast = !flat && C::triangle_id(0).is_none() && !o.mirrored;
        let mut k = 0;
        loop {
            if fast {
                let view = (self.vw, self.vh);
                let (store, heads, starts) = (&mut self.tris, &mut self.heads, &mut self.starts);
                let Some(vs) = self.verts.get_mut(base..base + n) else {
                    break;
                };
                let bins = Bins {
                    store,
                    heads,
                    starts,
                    view,
                };
                if cull_push(tris, &mut k, vs, base as u16, bins, stats, &mut need.1)
                    == CullStop::Done
                {
                    break;
                }
            }
            let Some(&tri) = tris.get(k) else {
                break;
            };
            // A mirrored object's triangles in screen winding.
            let tri = &if o.mirrored {
                [tri[0], tri[2], tri[1]]
            } else {
                tri
            };
            let id = first_id.wrapping_add(k as u32) as u16;
            k += 1;
            // This object's vertices (all stored above; flat triangles' colour vertices
            // follow them): an index check against them is also the store's bounds check.
            let Some(vs) = self.verts.get(base..base + n) else {
                return;
            };
            // Element by element: on a Cortex-M0 `array::map` stays a call (`try_from_fn`).
            let (Some(a), Some(b), Some(c)) = (
                vs.get(tri[0] as usize),
                vs.get(tri[1] as usize),
                vs.get(tri[2] as usize),
            ) else {
                stats.invalid += 1;
                continue;
            };
            let vi = [
                base + tri[0] as usize,
                base + tri[1] as usize,
                base + tri[2] as usize,
            ];
            let f = [a.flags, b.flags, c.flags];
            if (f[0] | f[1] | f[2]) & INVALID != 0 {
                stats.invalid += 1;
                continue;
            }
            if f[0] & f[1] & f[2] & 0x3f != 0 {
                stats.outside += 1;
                continue;
            }
            if (f[0] | f[1] | f[2]) & NEEDS_CLIP as u16 == 0 {
                match facing(a, b, c) {
                    Facing::Degenerate => {
                        stats.degenerate += 1;
                        continue;
                    }
                    Facing::Back => {
                        stats.culled += 1;
                        continue;
                    }
                    Facing::Front => {}
                }
                probe.enter(Stage::Lighting);
                let color = if let Some(c) = C::triangle_id(id) {
                    Some(c)
                } else if flat {
                    Some(o.face_color::<C>(*tri))
                } else {
                    for (k, &v) in vi.iter().enumerate() {
                        if self.verts[v].flags & LIT == 0 {
                            o.light::<C>(&mut self.verts[v], tri[k] as usize);
                        }
                    }
                    None
                };
                probe.enter(Stage::Triangles);
                let mut v = [vi[0] as u16, vi[1] as u16, vi[2] as u16];
                if let Some(rgb) = color {
                    // A copy of the first vertex with the face colour carries it.
                    need.0 += 1;
                    let mut colour_vertex = self.verts[vi[0]];
                    colour_vertex.set_color(pack_flat_channels(rgb, C::CHANNEL_MAX));
                    v[0] = self.verts.len() as u16 | FLAT_BIT;
                    if self.verts.push(colour_vertex).is_err() {
                        need.1 += 1;
                        continue;
                    }
                    if !self.push_tri(v, stats, need) {
                        // Not stored (empty or off-screen): the colour vertex is not needed.
                        self.verts.pop();
                        need.0 -= 1;
                        continue;
                    }
                    stats.color_vertices += 1;
                    continue;
                }
                self.push_tri(v, stats, need);
            } else {
                self.clipped(o, tri, vi, flat, vp, g, id, stats, need, probe);
            }
        }
        if fast {
            // The vertices `cull_push` marked: lit once each, as the full path lights them;
            // runs of them by `Scalar::light_run_565` where it applies.
            probe.enter(Stage::Lighting);
            self.light_pass(o, n);
            probe.enter(Stage::Triangles);
        }
    }

    /// The lighting pass over the `n` vertices of object `o`: each vertex the triangle loop
    /// marked, lit once, by runs of [`Scalar::light_run_565`] where it applies. Out of line:
    /// its locals stay out of the frame of [`Self::object`], which is on the deepest stack of
    /// a frame (on a 16 KB part the stack has no room to spare).
    #[inline(never)]
    fn light_pass<const L: usize>(&mut self, o: &ObjectSetup<'_, '_, S, L>, n: usize) {
        let base = o.base;
        if let Some(quick) = o.quick_light::<C>() {
            let mut runs = true;
            let mut i = 0;
            while i < n {
                if runs {
                    match self.light_quick(o, i, n, quick) {
                        Some(j) => i = j,
                        None => runs = false,
                    }
                    if i >= n {
                        break;
                    }
                }
                if let Some(v) = self.verts.get_mut(base + i) {
                    if v.flags & (LIT | NEEDS_LIGHT) == NEEDS_LIGHT {
                        o.light::<C>(v, i);
                    }
                }
                i += 1;
            }
        } else {
            for (i, v) in self.verts.iter_mut().skip(base).take(n).enumerate() {
                if v.flags & (LIT | NEEDS_LIGHT) == NEEDS_LIGHT {
                    o.light::<C>(v, i);
                }
            }
        }
    }

    /// One run of [`Scalar::light_run_565`] over vertices `i..n` of object `o` (with `quick`
    /// from [`ObjectSetup::quick_light`]): the index of the first vertex it leaves to the
    /// lighting pass (`n` when none), or `None` when it takes none for this object's light and
    /// material. Out of line, and the pass lights the vertices a run leaves outside it: the
    /// deepest stack of a frame does not grow (on a 16 KB part it has no room).
    #[inline(never)]
    fn light_quick<const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        i: usize,
        n: usize,
        quick: QuickLight<'_, S>,
    ) -> Option<usize> {
        let (normals, dir, frac) = quick;
        let m = &o.obj.material;
        let vs = self.verts.get_mut(o.base + i..o.base + n)?;
        let ns = normals.get(i..)?;
        Some(i + S::light_run_565(vs, ns, dir, frac, m.ambient, m.diffuse, m.color)?)
    }

    /// The vertex loop's step: the record of position `p` of object `o` ([`vertex_record`]),
    /// with the probe's snapping, stored (room was checked).
    #[inline(always)]
    fn push_vertex<P: Probe, const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        vp: &Viewport,
        g: S,
        p: Vec3<S>,
        stats: &Stats,
        probe: &mut P,
    ) {
        let mut sv = vertex_record(&o.mvp, vp, g, p);
        if sv.flags & PROJECTED != 0 {
            let index = self.verts.len() - stats.color_vertices as usize;
            (sv.x, sv.y) = snapped(probe, index, sv);
        }
        // Cannot fail: room was checked.
        let _ = self.verts.push(sv);
    }

    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn clipped<P: Probe, const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        tri: &[u16; 3],
        vi: [usize; 3],
        flat: bool,
        vp: &Viewport,
        g: S,
        id: u16,
        stats: &mut Stats,
        need: &mut (usize, usize),
        probe: &mut P,
    ) {
        let positions = o.obj.mesh.positions();
        let face = if let Some(c) = C::triangle_id(id) {
            Some(c)
        } else if flat {
            Some(o.face_color::<C>(*tri))
        } else {
            None
        };
        let mut input = [ClipVertex {
            pos: [S::ZERO; 4],
            rgb: [0; 3],
        }; 3];
        for k in 0..3 {
            let v = vi[k];
            let rgb = match face {
                Some(c) => c,
                None => {
                    if self.verts[v].flags & LIT == 0 {
                        o.light::<C>(&mut self.verts[v], tri[k] as usize);
                    }
                    unpack_channels(self.verts[v].color(), C::CHANNEL_MAX)
                }
            };
            input[k] = ClipVertex {
                pos: o.mvp.transform_point(positions[tri[k] as usize]),
                rgb,
            };
        }
        let codes =
            (self.verts[vi[0]].flags | self.verts[vi[1]].flags | self.verts[vi[2]].flags) as u8;
        let poly = clip_triangle(input, codes, g);
        if poly.v.is_empty() {
            stats.outside += 1;
            return;
        }
        stats.clipped += 1;
        need.0 += poly.v.len();
        if self.verts.len() + poly.v.len() > VERTS {
            need.1 += poly.v.len() - 2;
            return;
        }
        let first = self.verts.len();
        for v in &poly.v {
            let rgb = if face.is_some() {
                pack_flat_channels(v.rgb, C::CHANNEL_MAX)
            } else {
                pack_channels(v.rgb, C::CHANNEL_MAX)
            };
            match vp.project_out_of_line(v.pos, rgb) {
                Some(mut sv) => {
                    sv.flags |= PROJECTED | LIT;
                    let index = self.verts.len() - stats.color_vertices as usize;
                    (sv.x, sv.y) = snapped(probe, index, sv);
                    let _ = self.verts.push(sv);
                }
                None => {
                    // w ≤ 0 after near clipping can only come from rounding at w ≈ 0 with a
                    // degenerate near plane; skip the polygon.
                    self.verts.truncate(first);
                    stats.invalid += 1;
                    return;
                }
            }
        }
        for k in 1..poly.v.len() - 1 {
            let t = [first, first + k, first + k + 1];
            match facing(&self.verts[t[0]], &self.verts[t[1]], &self.verts[t[2]]) {
                Facing::Degenerate => stats.degenerate += 1,
                Facing::Back => stats.culled += 1,
                Facing::Front => {
                    // Every polygon vertex has the face colour: the first one carries it.
                    let mut v = t.map(|v| v as u16);
                    if face.is_some() {
                        v[0] |= FLAT_BIT;
                    }
                    self.push_tri(v, stats, need);
                }
            }
        }
    }

    /// Buckets a triangle by its first covered row, or counts it as empty or off-screen.
    /// Returns whether the triangle is stored (or counted as needed when the store is full).
    fn push_tri(&mut self, v: [u16; 3], stats: &mut Stats, need: &mut (usize, usize)) -> bool {
        let t = TriRecord { v };
        // The three positions only (not 12-byte vertex copies through `array::map`, which
        // stays a call on a Cortex-M0).
        let [i, j, k] = t.indices();
        let (a, b, c) = (&self.verts[i], &self.verts[j], &self.verts[k]);
        let mut bins = Bins {
            store: &mut self.tris,
            heads: &mut self.heads,
            starts: &mut self.starts,
            view: (self.vw, self.vh),
        };
        bins.push(t, [a, b, c], stats, &mut need.1)
    }

    /// [`Renderer::render_strip`], reporting stage changes to `probe`.
    pub fn render_strip_probed<D, P>(
        &mut self,
        target: &mut D,
        probe: &mut P,
    ) -> Result<Option<core::ops::Range<usize>>, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
        P: Probe,
    {
        if self.next_row >= self.vh {
            return Ok(None);
        }
        self.check_target(target)?;
        self.strip(target, probe, |_| {})
    }

    fn strip<D, P, F>(
        &mut self,
        target: &mut D,
        probe: &mut P,
        mut overlay: F,
    ) -> Result<Option<core::ops::Range<usize>>, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
        P: Probe,
        F: FnMut(&mut StripCanvas<'_, C, W>),
    {
        let Some((y0, lines)) = self.draw_strip::<P, true>(None, LINES, probe) else {
            return Ok(None);
        };
        let (vw, vh) = (self.vw, self.vh);
        overlay(&mut StripCanvas {
            lines: &mut self.color[..lines],
            y0,
            height: vh as u32,
        });
        let area = Rectangle::new(Point::new(0, y0 as i32), Size::new(vw as u32, lines as u32));
        probe.enter(Stage::Output);
        let result = target.fill_contiguous(
            &area,
            self.color[..lines]
                .iter()
                .flat_map(|line| line[..vw].iter())
                .copied(),
        );
        probe.enter(Stage::Raster);
        if let Err(e) = result {
            // The frame is abandoned: a later render_strip draws nothing.
            self.next_row = vh;
            return Err(Error::Target(e));
        }
        Ok(Some(y0..y0 + lines))
    }

    /// Draws the next strip of the prepared frame into `lines`, colour lines that the caller
    /// owns, and returns its rows, or `None` when the frame is complete (or nothing was
    /// prepared). Nothing is sent anywhere: the caller hands the lines to a DMA channel, a
    /// display driver or another core, and may draw into them first (a label, a HUD).
    ///
    /// The strip is `min(N, LINES, rows left)` rows high (the depth lines are the renderer's
    /// own, `LINES` of them); row `y0 + i` is `lines[i][..vw]` for the returned `y0..y1`. Lines
    /// beyond the strip and columns beyond the viewport are left as they were. Each line is
    /// cleared to the background first, so a buffer can be reused without clearing it.
    ///
    /// For RGB565, a line is `W` native 16-bit words: an SPI display sends them in its own
    /// (big-endian) order when the SPI transfers 16-bit frames, which most microcontrollers'
    /// SPI and DMA units can do with no byte swapping at all (the Pico firmware does this). For
    /// a byte stream, [`Renderer::render_strip_be`] writes big-endian bytes instead.
    ///
    /// The pixels are exactly those [`Renderer::render`] draws into a target.
    pub fn render_strip_into<const N: usize>(
        &mut self,
        lines: &mut [[C; W]; N],
    ) -> Option<core::ops::Range<usize>> {
        const { assert!(N >= 1, "a strip buffer needs at least one line") };
        self.draw_strip::<NoProbe, true>(Some(lines), N, &mut NoProbe)
            .map(|(y0, n)| y0..y0 + n)
    }

    /// Draws the next strip of the prepared frame into the renderer's own lines and writes it
    /// to `out` as big-endian pixel bytes (for RGB565 the byte order of SPI panels such as the
    /// ST7789 and ILI9341: high byte first), row after row, `vw` pixels a row; returns its rows,
    /// or `None` when the frame is complete. The strip is as many rows as fit in `out`, at most
    /// `LINES`. For a driver that sends bytes (an 8-bit SPI DMA channel, a USB or network
    /// link); [`Renderer::render_strip_into`] avoids the copy.
    ///
    /// # Errors
    ///
    /// [`StripBufferTooSmall`] when `out` cannot hold one row (`vw · bytes per pixel`); nothing
    /// is drawn then.
    pub fn render_strip_be(
        &mut self,
        out: &mut [u8],
    ) -> Result<Option<core::ops::Range<usize>>, StripBufferTooSmall>
    where
        C: ToBytes,
        C::Bytes: AsRef<[u8]>,
    {
        let bpp = core::mem::size_of::<C::Bytes>();
        let row_bytes = self.vw * bpp;
        if self.next_row >= self.vh {
            return Ok(None);
        }
        if out.len() < row_bytes || bpp == 0 {
            return Err(StripBufferTooSmall {
                needed: row_bytes,
                given: out.len(),
            });
        }
        let fit = out.len() / row_bytes;
        let Some((y0, lines)) = self.draw_strip::<NoProbe, true>(None, fit, &mut NoProbe) else {
            return Ok(None);
        };
        for (line, dst) in self.color[..lines]
            .iter()
            .zip(out.chunks_exact_mut(row_bytes))
        {
            for (c, d) in line[..self.vw].iter().zip(dst.chunks_exact_mut(bpp)) {
                d.copy_from_slice(c.to_be_bytes().as_ref());
            }
        }
        Ok(Some(y0..y0 + lines))
    }

    /// Rasterizes the next strip of the prepared frame, at most `limit` rows, into `ext` (the
    /// caller's lines) or, for `None`, into the renderer's own lines. Returns its first row and
    /// height, or `None` when the frame is complete. `CLEAR`: each line is cleared to the
    /// background (colour) and the far plane (depth) first; without it the frame is drawn over
    /// what the lines hold ([`Renderer::render_passes`]; a constant, so the strip routines of
    /// a frame compile as they did without the option).
    fn draw_strip<P: Probe, const CLEAR: bool>(
        &mut self,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        let y0 = self.next_row;
        let (vw, vh) = (self.vw, self.vh);
        if y0 >= vh {
            return None;
        }
        let mode = SpanMode::new::<C>(self.depth_test, self.dither);
        let Renderer {
            verts,
            tris,
            active,
            heads,
            color: own,
            depth,
            depth_test,
            dither,
            background,
            stats,
            active_skipped: skipped,
            ..
        } = self;
        let color: &mut [[C; W]] = match ext {
            Some(lines) => lines,
            None => own.as_mut_slice(),
        };
        let lines = LINES.min(limit).min(color.len()).min(vh - y0);
        for l in 0..lines {
            if CLEAR {
                #[cfg(all(target_arch = "arm", target_os = "none"))]
                let cleared = crate::span_thumb::clear_line(
                    &mut color[l][..vw],
                    &mut depth[l][..vw],
                    *background,
                );
                #[cfg(not(all(target_arch = "arm", target_os = "none")))]
                let cleared = false;
                if !cleared {
                    color[l][..vw].fill(*background);
                    depth[l][..vw].fill(u16::MAX);
                }
            }
            let row = y0 + l;
            let end = if row + 1 < vh {
                heads[row + 1] as usize
            } else {
                tris.len()
            };
            let bucket = heads[row] as usize..end;
            if !bucket.is_empty() {
                probe.enter(Stage::Setup);
            }
            for t in bucket {
                let rec = tris[t];
                let (verts, h) = (&*verts, vh as i32);
                // Full only under `OverflowPolicy::DrawWhatFits` (the largest number of rows'
                // overlaps was checked): the triangle is left out and counted.
                if !active.push_with(|a| a.setup::<C>(&rec, verts, row as i32, h, mode)) {
                    *skipped = skipped.saturating_add(1);
                }
            }
            probe.enter(Stage::Raster);
            let mut i = 0;
            loop {
                #[cfg(all(target_arch = "arm", target_os = "none"))]
                if let Some((next, frag, written)) = crate::span_thumb::rows565(
                    active,
                    i,
                    &mut color[l][..vw],
                    &mut depth[l][..vw],
                    row,
                    *dither,
                ) {
                    stats.add_row(frag, written);
                    i = next;
                }
                if i >= active.len() {
                    break;
                }
                let (frag, written, done) = active.get_mut(i).draw_row(
                    row as i32,
                    &mut color[l][..vw],
                    &mut depth[l][..vw],
                    *depth_test,
                    *dither,
                );
                stats.add_row(frag, written);
                if done {
                    active.swap_remove(i);
                } else {
                    i += 1;
                }
            }
        }
        self.next_row = y0 + lines;
        Some((y0, lines))
    }
}

/// [`Renderer::render_strip_be`]'s error: the buffer cannot hold one row of the viewport.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct StripBufferTooSmall {
    /// Bytes one row needs.
    pub needed: usize,
    /// Bytes given.
    pub given: usize,
}

impl<
        S: Scalar,
        C: TargetColor,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
    > Default for Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES>
{
    fn default() -> Self {
        Self::new()
    }
}

/// The vertex store's record of position `p` transformed by `mvp`: its outcode (guard band
/// `g`) and flags, and, unless it is to be clipped, invalid or has w ≤ 0, its projection on
/// `vp` (before the probe's snapping) with no colour.
#[inline(always)]
fn vertex_record<S: Scalar>(mvp: &Mat4<S>, vp: &Viewport, g: S, p: Vec3<S>) -> ScreenVertex {
    let clip = mvp.transform_point(p);
    let mut flags = outcode(clip, g) as u16;
    let mut sv = ScreenVertex::default();
    if !clip.iter().all(|v| v.is_valid()) {
        flags |= INVALID;
    } else if flags & NEEDS_CLIP as u16 == 0 {
        if let Some(v) = vp.project(clip, [0; 3]) {
            sv = v;
            flags |= PROJECTED;
        }
    }
    sv.flags = flags;
    sv
}

/// ARMv6-M only, for the benchmark firmware: the assembly vertex run (`Scalar::project_run`
/// of `Fx<I16F16>`) against [`vertex_record`] on `n` pseudo-random objects of 16 positions:
/// matrices and positions from small to near the transform's range, w from negative to
/// large, points inside and outside the x/y planes, the guard band and the near and far
/// planes. Runs until every position is done, taking each declined one itself; returns the
/// first object with a differing record, as its seed.
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
#[doc(hidden)]
pub fn vertex_self_test(n: u32) -> Option<u32> {
    use crate::scalar::Fx;
    use fixed::types::I16F16;
    type Q = Fx<I16F16>;
    let q = |b: i32| Fx(I16F16::from_bits(b));
    let mut seeds = crate::raster::xorshift32(0xa54f_f53a);
    for _ in 0..n {
        let seed = seeds();
        let mut next = crate::raster::xorshift32(seed | 1);
        let mut val = |max_bits: u32| crate::raster::signed_bits(&mut next, max_bits);
        let mut m = Mat4::<Q>::identity();
        for row in m.m.iter_mut() {
            for e in row.iter_mut() {
                *e = q(val(if seed % 5 == 0 { 31 } else { 20 }));
            }
        }
        let size = [(240, 240), (64, 48), (1024, 1024), (320, 200)][(seed >> 8) as usize % 4];
        let vp = Viewport {
            width: size.0,
            height: size.1,
        };
        let g = Q::from_i32(vp.guard_band());
        let mut ps = [[Q::ZERO; 3]; 16];
        for p in &mut ps {
            *p = [0; 3].map(|_| q(val(if seed % 7 == 0 { 31 } else { 19 })));
        }
        let (sx, sy) = (8 * vp.width, 8 * vp.height);
        let mut out = Vec::<ScreenVertex, 16>::new();
        let mut i = 0;
        while i < ps.len() {
            let run = Q::project_run(&m.m, &ps[i..], g, sx, sy, &mut out);
            for k in 0..run {
                if out.get(i + k) != Some(&vertex_record(&m, &vp, g, ps[i + k])) {
                    return Some(seed);
                }
            }
            i += run;
            if let Some(&p) = ps.get(i) {
                let _ = out.push(vertex_record(&m, &vp, g, p));
                i += 1;
            }
        }
    }
    None
}

/// ARMv6-M only, for the benchmark firmware: the assembly lighting run
/// (`Scalar::light_run_565` of `Fx<I16F16>`) against the portable lighting of the pass
/// (`lit_diffuse`, RGB565 scaling and packing, `set_color`, `LIT`) on `n` pseudo-random
/// objects of 16 vertices: marked, lit and unmarked vertices with any other flag and colour
/// bits; normals and light directions from tiny to beyond the routine's range; diffuse
/// coefficients and colour fractions near and beyond it, ambient terms of every sign and size
/// (sums that saturate included), material colours 0..=255. Runs until every vertex is done,
/// lighting each declined one itself; returns the first object with a differing record, as its
/// seed.
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
#[doc(hidden)]
pub fn light_self_test(n: u32) -> Option<u32> {
    use crate::scalar::Fx;
    use crate::shade::Material;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use fixed::types::I16F16;
    type Q = Fx<I16F16>;
    let q = |b: i32| Fx(I16F16::from_bits(b));
    let max = <Rgb565 as TargetColor>::CHANNEL_MAX;
    let mut seeds = crate::raster::xorshift32(0x1d87_2b41);
    for _ in 0..n {
        let seed = seeds();
        let mut next = crate::raster::xorshift32(seed | 1);
        let mut val = |max_bits: u32| crate::raster::signed_bits(&mut next, max_bits);
        let big = seed % 7 == 0;
        let dir = [0; 3].map(|_| q(val(if big { 24 } else { 17 })));
        let frac = q(val(if big { 25 } else { 17 }));
        // Ambient terms next to either end of the range make the ambient sum saturate.
        let ambient = match seed % 11 {
            0 => i32::MAX - (val(24) & 0x7f_ffff),
            1 => i32::MIN + (val(24) & 0x7f_ffff),
            _ => val(if big { 31 } else { 18 }),
        };
        let mut m = Material::matte([0; 3], q(ambient), q(val(24)));
        m.color = [0; 3].map(|_| (val(8) & 0xff) as u8);
        let light = [PreparedLight::grey_raw(dir, frac)];
        let mut normals = [[Q::ZERO; 3]; 16];
        let mut verts = [ScreenVertex::default(); 16];
        for (nv, v) in normals.iter_mut().zip(verts.iter_mut()) {
            *nv = [0; 3].map(|_| q(val(if seed % 5 == 0 { 24 } else { 17 })));
            let r = val(16) as u16;
            v.rgb_hi = [r as u8, (r >> 8) as u8, r as u8 ^ 0x5a];
            v.flags = r;
        }
        // The pass's portable lighting of one vertex.
        let portable = |v: &mut ScreenVertex, nv: [Q; 3]| {
            if v.flags & (LIT | NEEDS_LIGHT) == NEEDS_LIGHT {
                v.set_color(pack_channels(
                    Rgb565::vertex_channels(lit_diffuse(&m, &light, nv)),
                    max,
                ));
                v.flags |= LIT;
            }
        };
        let mut want = verts;
        for (v, &nv) in want.iter_mut().zip(&normals) {
            portable(v, nv);
        }
        let mut i = 0;
        while i < verts.len() {
            let run = Q::light_run_565(
                &mut verts[i..],
                &normals[i..],
                dir,
                frac,
                m.ambient,
                m.diffuse,
                m.color,
            );
            i += run.unwrap_or(0);
            if let (Some(v), Some(&nv)) = (verts.get_mut(i), normals.get(i)) {
                portable(v, nv);
            }
            i += 1;
        }
        if verts != want {
            return Some(seed);
        }
    }
    None
}

/// Where a stored triangle goes: the triangle store and the per-row counts of the bucket sort
/// (see [`Renderer::sort_buckets`]), for a `view.0 × view.1` viewport (`view.1` ≤ the
/// counts' length).
pub(crate) struct Bins<'a, const T: usize> {
    pub store: &'a mut Vec<TriRecord, T>,
    pub heads: &'a mut [u16],
    pub starts: &'a mut [i16],
    pub view: (usize, usize),
}

impl<const T: usize> Bins<'_, T> {
    /// Stores triangle `t` (vertices `v`) under its first covered row, or counts it as empty or
    /// off-screen. Returns whether it is stored (or counted as needed when the store is full).
    /// `needed` counts the triangles stored or that would have been (full store).
    fn push(
        &mut self,
        t: TriRecord,
        v: [&ScreenVertex; 3],
        n: &mut Stats,
        needed: &mut usize,
    ) -> bool {
        let [a, b, c] = v;
        let (ax, bx, cx) = (a.x as i32, b.x as i32, c.x as i32);
        let (ay, by, cy) = (a.y as i32, b.y as i32, c.y as i32);
        let (x0, x1) = (ax.min(bx).min(cx), ax.max(bx).max(cx));
        let (y0, y1) = (ay.min(by).min(cy), ay.max(by).max(cy));
        let (px0, px1, py0, py1) = (
            first_pixel(x0),
            first_pixel(x1),
            first_pixel(y0),
            first_pixel(y1),
        );
        if px0 >= px1 || py0 >= py1 {
            n.empty += 1;
            return false;
        }
        let (vw, vh) = self.view;
        if px1 <= 0 || py1 <= 0 || px0 >= vw as i32 || py0 >= vh as i32 {
            n.outside += 1;
            return false;
        }
        *needed += 1;
        let row = bucket_row(y0);
        let end = py1.min(vh as i32) as usize;
        if self.store.push(t).is_err() {
            return true;
        }
        let (Some(h), Some(s)) = (self.heads.get_mut(row), self.starts.get_mut(row)) else {
            return true;
        };
        *h = h.wrapping_add(1);
        *s = s.wrapping_add(1);
        if end < vh {
            if let Some(e) = self.starts.get_mut(end) {
                *e = e.wrapping_sub(1);
            }
        }
        n.drawn += 1;
        true
    }
}

/// Why [`cull_push`] stopped.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum CullStop {
    /// Every triangle is done.
    Done,
    /// The triangle at the cursor needs the object loop's full path: an index out of range, an
    /// invalid vertex, or clipping.
    Portable,
}

/// The common cases of an object's triangle loop for Gouraud triangles of real colours, from
/// triangle `*k` on: each triangle whose vertices are valid and need no clipping is counted as
/// outside, degenerate or culled, or (a front face) stored by [`Bins::push`], exactly as the
/// full path does, and when stored its unlit vertices are marked [`NEEDS_LIGHT`]; `*k` moves
/// past it. Stops at a triangle that needs the full path. `verts` are the object's vertices,
/// `base` the store index of the first. On Cortex-M this is Thumb-1 assembly
/// (`cull_thumb::cull_push`); elsewhere [`cull_push_portable`].
#[inline(always)]
fn cull_push<const T: usize>(
    tris: &[[u16; 3]],
    k: &mut usize,
    verts: &mut [ScreenVertex],
    base: u16,
    bins: Bins<'_, T>,
    n: &mut Stats,
    needed: &mut usize,
) -> CullStop {
    #[cfg(all(target_arch = "arm", target_os = "none"))]
    return crate::cull_thumb::cull_push(tris, k, verts, base, bins, n, needed);
    #[cfg(not(all(target_arch = "arm", target_os = "none")))]
    return cull_push_portable(tris, k, verts, base, bins, n, needed);
}

/// [`cull_push`] in Rust.
pub(crate) fn cull_push_portable<const T: usize>(
    tris: &[[u16; 3]],
    k: &mut usize,
    verts: &mut [ScreenVertex],
    base: u16,
    mut bins: Bins<'_, T>,
    n: &mut Stats,
    needed: &mut usize,
) -> CullStop {
    while let Some(tri) = tris.get(*k) {
        let (Some(a), Some(b), Some(c)) = (
            verts.get(tri[0] as usize),
            verts.get(tri[1] as usize),
            verts.get(tri[2] as usize),
        ) else {
            return CullStop::Portable;
        };
        if (a.flags | b.flags | c.flags) & (INVALID | NEEDS_CLIP as u16) != 0 {
            return CullStop::Portable;
        }
        let all = a.flags & b.flags & c.flags;
        if all & 0x3f != 0 {
            n.outside += 1;
        } else {
            match facing(a, b, c) {
                Facing::Degenerate => n.degenerate += 1,
                Facing::Back => n.culled += 1,
                Facing::Front => {
                    let v = tri.map(|i| base.wrapping_add(i));
                    let stored = bins.push(TriRecord { v }, [a, b, c], n, needed);
                    if stored && all & LIT == 0 {
                        for &i in tri {
                            if let Some(v) = verts.get_mut(i as usize) {
                                if v.flags & LIT == 0 {
                                    v.flags |= NEEDS_LIGHT;
                                }
                            }
                        }
                    }
                }
            }
        }
        *k += 1;
    }
    CullStop::Done
}

/// Cortex-M only, for the benchmark firmware: the assembly triangle loop
/// (`cull_thumb::cull_push`) against [`cull_push_portable`] on `n` pseudo-random objects of
/// 24 triangles over 16 vertices (indices out of range, invalid, clipped, outside, unlit and
/// lit vertices; coordinates across the whole range and near one another; off-screen, empty
/// and degenerate triangles; a store that fills up; viewports of every height up to 64 rows).
/// Both are run to the end, skipping each triangle they stop at; returns the first object
/// whose stops, store, row counts, counts or vertex marks differ, as its seed.
#[cfg(all(target_arch = "arm", target_os = "none"))]
#[doc(hidden)]
pub fn cull_self_test(n: u32) -> Option<u32> {
    const ROWS: usize = 64;
    let mut seeds = crate::raster::xorshift32(0x3c6e_f372);
    for _ in 0..n {
        let seed = seeds();
        let mut next = crate::raster::xorshift32(seed | 1);
        let spread = [40, 400, 4000, 2 * crate::project::COORD_LIMIT as u32][(next() % 4) as usize];
        let mut verts = [ScreenVertex::default(); 16];
        for v in &mut verts {
            let r = next();
            let c = |h: u32| {
                let v = (h % spread) as i32 - spread as i32 / 2 + 1000;
                v.clamp(-crate::project::COORD_LIMIT, crate::project::COORD_LIMIT) as i16
            };
            v.x = c(r & 0xffff);
            v.y = c(r >> 16);
            let f = next();
            // Outcode bits now and then, the clipper's and invalid rarely, lit mostly.
            let mut flags = if f % 4 == 0 {
                (f >> 8) as u16 & 0x3f
            } else {
                0
            };
            if f % 23 == 0 {
                flags |= 1 << (4 + (f >> 16) % 4);
            }
            if f % 5 != 0 {
                // A lit vertex's colour bits are anything; an unlit one's are zero.
                flags |= LIT | (f >> 16) as u16 & !crate::project::FLAG_MASK;
            }
            v.flags = flags;
        }
        let mut tris = [[0u16; 3]; 24];
        for t in &mut tris {
            let r = next();
            *t = [r % 17, (r >> 8) % 17, (r >> 16) % 17].map(|i| i as u16);
        }
        let view = (
            1 + (next() % 300) as usize,
            1 + (next() % ROWS as u32) as usize,
        );
        let base = (next() % 1000) as u16;
        let mut runs = [(); 2].map(|_| {
            (
                verts,
                Vec::<TriRecord, 8>::new(),
                [0u16; ROWS],
                [0i16; ROWS],
                Stats::default(),
                0usize,
                0u32,
            )
        });
        for (which, (vs, store, heads, starts, counts, needed, stops)) in
            runs.iter_mut().enumerate()
        {
            let mut k = 0;
            for _ in 0..64 {
                let bins = Bins {
                    store,
                    heads,
                    starts,
                    view,
                };
                let stop = if which == 0 {
                    crate::cull_thumb::cull_push(&tris, &mut k, vs, base, bins, counts, needed)
                } else {
                    cull_push_portable(&tris, &mut k, vs, base, bins, counts, needed)
                };
                *stops = stops
                    .wrapping_mul(31)
                    .wrapping_add(stop as u32 * 32 + k as u32);
                if stop == CullStop::Done {
                    break;
                }
                k += 1;
            }
        }
        let [a, b] = &runs;
        let records = |s: &Vec<TriRecord, 8>| {
            let mut r = [[0u16; 3]; 8];
            for (d, t) in r.iter_mut().zip(s) {
                *d = t.v;
            }
            (s.len(), r)
        };
        let flags = |v: &[ScreenVertex; 16]| v.map(|v| v.flags);
        if (a.2, a.3, a.4, a.5, a.6) != (b.2, b.3, b.4, b.5, b.6)
            || records(&a.1) != records(&b.1)
            || flags(&a.0) != flags(&b.0)
        {
            return Some(seed);
        }
    }
    None
}

/// The row bucket of a triangle whose topmost vertex is at `y_min` subpixels: its first covered
/// row, clamped to the screen. [`Renderer::push_tri`] counts by it and the bucket sort places
/// by it, so both must agree.
fn bucket_row(y_min: i32) -> usize {
    first_pixel(y_min).max(0) as usize
}

/// The snapped position of a projected vertex, as the probe wants it, within the coordinate
/// range.
fn snapped<P: Probe>(probe: &mut P, index: usize, v: ScreenVertex) -> (i16, i16) {
    let (x, y) = probe.snap(index as u32, v.x as i32, v.y as i32);
    (
        x.clamp(-COORD_LIMIT, COORD_LIMIT) as i16,
        y.clamp(-COORD_LIMIT, COORD_LIMIT) as i16,
    )
}

/// Bytes per vertex in the vertex store (12).
pub const VERTEX_BYTES: usize = core::mem::size_of::<ScreenVertex>();
/// Bytes per stored triangle (6).
pub const TRIANGLE_BYTES: usize = core::mem::size_of::<TriRecord>();
/// Bytes per active triangle (84).
pub const ACTIVE_BYTES: usize = core::mem::size_of::<ActiveTri>();

/// The documented RAM formula (see the crate docs): colour and depth lines, vertex store,
/// triangle list, active list, row buckets; `extra` covers alignment and a few words of state.
#[must_use]
pub const fn ram_formula(
    w: usize,
    h: usize,
    color_bytes: usize,
    lines: usize,
    verts: usize,
    tris: usize,
    active: usize,
) -> usize {
    lines * w * (color_bytes + 2)
        + VERTEX_BYTES * verts
        + TRIANGLE_BYTES * tris
        + ACTIVE_BYTES * active
        + 4 * h
}

#[cfg(test)]
mod ram_tests {
    use super::*;
    use crate::scalar::Fx;
    use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
    use fixed::types::I16F16;

    #[test]
    fn record_sizes_are_the_documented_ones() {
        assert_eq!((VERTEX_BYTES, TRIANGLE_BYTES, ACTIVE_BYTES), (12, 6, 84));
        // The benchmark torus renderer meets the 16 KB budget; the demo one with a margin is
        // the figure the README quotes.
        let (v, t, a) = crate::demo::TORUS_CAPACITY;
        assert_eq!((v, t, a), (512, 466, 61));
        let bench = core::mem::size_of::<Renderer<Fx<I16F16>, Rgb565, 240, 240, 512, 466, 61>>();
        assert!(bench <= 16 * 1024, "{bench}");
        let demo = core::mem::size_of::<crate::demo::TorusRenderer<Fx<I16F16>, Rgb565>>();
        assert!(demo > bench && demo < 17 * 1024, "{demo}");
    }

    fn check<R>(formula: usize) {
        let real = core::mem::size_of::<R>();
        assert!(
            real >= formula && real <= formula + 128,
            "size {real}, formula {formula}"
        );
    }

    #[test]
    fn ram_formula_matches_size_of() {
        type Q = Fx<I16F16>;
        check::<Renderer<Q, Rgb565, 240, 240, 512, 512, 48>>(ram_formula(
            240, 240, 2, 1, 512, 512, 48,
        ));
        check::<Renderer<f32, Rgb888, 320, 200, 100, 300, 20, 4>>(ram_formula(
            320, 200, 4, 4, 100, 300, 20,
        ));
        check::<Renderer<f64, Rgb565, 16, 16, 8, 8, 8, 16>>(ram_formula(16, 16, 2, 16, 8, 8, 8));
    }
}
