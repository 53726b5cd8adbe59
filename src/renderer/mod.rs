//! The renderer: its type, its capacities and RAM, and the frame driver. The renderer owns the
//! geometry stage's stores ([`Stores`]) and the raster stage's state ([`Raster`]); a frame is
//! the geometry stage over every object ([`Renderer::geometry`], or the layered frame's in
//! `layered.rs`), then strip passes ([`Renderer::draw_strip`], [`crate::StripPass`] in
//! `pass.rs`). The stages' functions take what they read and write as arguments: this driver
//! is the one place that holds both.

pub(crate) mod layered;
pub(crate) mod mapped;
pub(crate) mod no_depth;
pub(crate) mod pass;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use crate::geometry::pool::ActiveExtra;
use crate::geometry::project::{ScreenVertex, MAX_SCREEN};
use crate::geometry::stores::Stores;
use crate::geometry::vertex_extra::VertexExtra;
use crate::num::scalar::Scalar;
use crate::raster::state::Raster;
use crate::raster::{ActiveList, ActiveTri, DepthTest, TriRecord, FLAT_BIT};
use crate::scene::color::TargetColor;
use crate::scene::Scene;

pub use crate::error::{Capacity, Error, Needs, OverflowPolicy, Shortfall, StripBufferTooSmall};
pub use crate::stats::{NoProbe, Probe, Stage, Stats};

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
/// * `XV`, `XA` — the texture attribute stores (default 0, 0: no textures, and no RAM or
///   instruction spent on them): texture coordinates for the first `XV` records of the
///   vertex store, and extra planes for `XA` textured triangles active at once (see
///   "Textures").
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
/// The texture stores add `XV·`[`VERTEX_EXTRA_BYTES`]` + XA·`[`ACTIVE_EXTRA_BYTES`] (20 and
/// 108 bytes on a 32-bit core).
///
/// # Textures
///
/// A scene with a textured material ([`crate::Material::textured`]) needs `XV` at least the
/// vertex-store index its last textured vertex gets (the vertices of the objects before it,
/// its own, and those its clipping and flat shading add: `XV = VERTS` always suffices) and
/// `XA ≥ 1`; otherwise the frame fails with [`Error::AttributeStore`] before anything is
/// drawn. Under [`OverflowPolicy::Error`] the frame also fails so when more triangles than
/// `XA` are active on one row ([`Stats::max_active`], a bound of the textured ones: the
/// renderer does not count those apart), so that no textured triangle is left out; under
/// [`OverflowPolicy::DrawWhatFits`] a textured triangle that finds all `XA` entries in use is
/// left out and counted in [`Renderer::shortfall`] (`skipped`).
///
/// ```
/// # use embedded_graphics::pixelcolor::Rgb565;
/// # use scanline3d::prelude::*;
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// // 240 × 240, 64 vertices, 64 triangles, 16 active, 1 line, textures for all 64
/// // vertices and 16 active triangles.
/// type Textured = Renderer<Q, Rgb565, 240, 240, 64, 64, 16, 1, 64, 16>;
/// assert_eq!(
///     Textured::RAM_BYTES,
///     Renderer::<Q, Rgb565, 240, 240, 64, 64, 16>::RAM_BYTES
///         + 64 * scanline3d::limits::VERTEX_EXTRA_BYTES
///         + 16 * scanline3d::limits::ACTIVE_EXTRA_BYTES
/// );
/// ```
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
    const XV: usize = 0,
    const XA: usize = 0,
    const ZL: usize = LINES,
> {
    /// The geometry stage's stores: vertices, triangles, attribute stores, row buckets and the
    /// prepared frame's viewport.
    pub(crate) geo: Stores<S, C, H, VERTS, TRIS, XV, XA>,
    /// The raster stage's state: the strip lines, the active list, the strip pass's settings
    /// and position.
    pub(crate) ras: Raster<C, W, LINES, ZL, ACTIVE>,
    /// The viewport [`Renderer::set_viewport`] asked for (1..=`W`, 1..=`H`, so that a u16
    /// holds it): taken by the next frame's geometry stage, or at once when no frame is being
    /// drawn.
    pub(crate) want_viewport: (u16, u16),
    /// Which frame the renderer holds, for the [`crate::StripPass`]es drawing it: advanced by
    /// every geometry stage; odd once a frame a strip pass can draw is prepared (by
    /// [`Renderer::prepare`] or a render), even while none is (before the first, during a
    /// geometry stage, after one that failed, and for a layered frame).
    pub(crate) frame_id: u32,
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
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>
{
    /// Exact RAM of this renderer in bytes.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// This renderer's capacities (`VERTS`, `TRIS`, `ACTIVE`, `XV`, `XA`; no layer lists:
    /// add a [`crate::Layers`]' with [`Needs::with_layers`]), to compare a frame's
    /// [`Needs`] with.
    pub const CAPACITY: Needs = Needs::new(VERTS, TRIS, ACTIVE).with_stores(XV, XA);

    const CHECK: () = {
        assert!(W >= 1 && W <= MAX_SCREEN, "W must be 1..=1024");
        assert!(H >= 1 && H <= MAX_SCREEN, "H must be 1..=1024");
        assert!(LINES >= 1, "LINES must be at least 1");
        assert!(
            ZL == LINES || ZL == 0,
            "ZL (depth lines) must be LINES (a Z-buffer) or 0 (no depth lines)"
        );
        assert!(
            ZL > 0 || (XV == 0 && XA == 0),
            "a renderer without depth lines (ZL = 0) draws flat and Gouraud triangles: XV and XA must be 0"
        );
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
            geo: Stores::new(W, H),
            ras: Raster::new(fill, H),
            want_viewport: (W as u16, H as u16),
            frame_id: 0,
        }
    }

    /// Sets what happens to a frame that does not fit the capacities ([`OverflowPolicy`];
    /// default [`OverflowPolicy::Error`]).
    #[must_use]
    pub fn with_overflow(mut self, policy: OverflowPolicy) -> Self {
        self.ras.overflow = policy;
        self
    }

    /// Sets the overflow policy in place.
    pub fn set_overflow(&mut self, policy: OverflowPolicy) {
        self.ras.overflow = policy;
    }

    /// The overflow policy.
    #[must_use]
    pub fn overflow(&self) -> OverflowPolicy {
        self.ras.overflow
    }

    /// What the last prepared frame (the one being drawn, or drawn last) needed beyond the
    /// capacities, or `None` when it fit. Under [`OverflowPolicy::DrawWhatFits`] this is how a
    /// frame drawn in part says so: [`Shortfall::skipped`] counts the triangles left out
    /// (complete once the frame is drawn). A frame that failed with [`Error::Shortfall`] was
    /// not prepared: the error carries its shortfall.
    #[must_use]
    pub fn shortfall(&self) -> Option<Shortfall> {
        let s = &self.ras.stats;
        let needed = Needs::new(
            s.vertices as usize,
            s.drawn as usize + self.geo.store_skipped as usize,
            s.max_active as usize,
        );
        // (A textured triangle left out for want of a pool entry is a shortfall too.)
        if needed.fits(&Self::CAPACITY) && self.ras.active_skipped == 0 {
            return None;
        }
        Some(Shortfall {
            needed,
            capacity: Self::CAPACITY,
            exact: needed.vertices <= VERTS && needed.triangles <= TRIS,
            skipped: self.geo.store_skipped as usize + self.ras.active_skipped as usize,
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
        let policy = self.ras.overflow;
        self.ras.overflow = OverflowPolicy::DrawWhatFits;
        let result = self.geometry(scene, &mut NoProbe);
        self.ras.overflow = policy;
        self.ras.next_row = self.geo.vh;
        result?;
        self.measured()
    }

    /// The needs of the frame just prepared under [`OverflowPolicy::DrawWhatFits`] (for
    /// [`Renderer::needs`] and [`Renderer::needs_layered`]).
    pub(crate) fn measured(&self) -> Result<Needs, Error<core::convert::Infallible>> {
        match self.shortfall() {
            None => Ok(Needs::from_stats(&self.ras.stats)),
            Some(s) if s.exact => Ok(Needs {
                triangles: s.needed.triangles,
                ..Needs::from_stats(&self.ras.stats)
            }),
            Some(mut s) => {
                s.skipped = 0;
                Err(Error::Shortfall(s))
            }
        }
    }

    /// For a call that draws a new frame: the viewport [`Renderer::set_viewport`] asked for
    /// taken (a prepared frame is given up, as the new frame replaces it), then
    /// [`Renderer::check_target`].
    pub(crate) fn begin_target<D: Dimensions, E>(&mut self, target: &D) -> Result<(), Error<E>> {
        self.take_viewport();
        self.check_target(target)
    }

    /// [`Error::TargetTooSmall`] unless `target` contains the viewport at its origin.
    pub(crate) fn check_target<D: Dimensions, E>(&self, target: &D) -> Result<(), Error<E>> {
        let bb = target.bounding_box();
        let (x0, y0) = (bb.top_left.x as i64, bb.top_left.y as i64);
        let (x1, y1) = (x0 + bb.size.width as i64, y0 + bb.size.height as i64);
        if x0 <= 0 && y0 <= 0 && x1 >= self.geo.vw as i64 && y1 >= self.geo.vh as i64 {
            Ok(())
        } else {
            Err(Error::TargetTooSmall {
                viewport: Size::new(self.geo.vw as u32, self.geo.vh as u32),
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
        self.ras.depth_test = test;
        self
    }

    /// Draws into a `width × height` viewport at the target's origin instead of the full
    /// `W × H` (clamped to 1..=W and 1..=H): one renderer type for several panel sizes, or a
    /// preview at any size. The projection's aspect ratio follows the viewport.
    ///
    /// A frame already prepared ([`Renderer::prepare`]) and not completely drawn keeps the
    /// viewport it was prepared for — its geometry was projected onto it — and its strips
    /// still come out; the new viewport applies from the next frame on. Between frames it
    /// applies at once.
    pub fn set_viewport(&mut self, width: usize, height: usize) {
        self.want_viewport = (width.clamp(1, W) as u16, height.clamp(1, H) as u16);
        if self.ras.next_row >= self.geo.vh {
            self.take_viewport();
        }
    }

    /// Makes the viewport [`Renderer::set_viewport`] asked for the one drawn (no frame is
    /// prepared afterwards).
    pub(crate) fn take_viewport(&mut self) {
        self.geo.vw = self.want_viewport.0 as usize;
        self.geo.vh = self.want_viewport.1 as usize;
        self.ras.next_row = self.geo.vh;
    }

    /// The viewport size (`W × H` unless changed by [`Renderer::set_viewport`]): the one the
    /// next frame is prepared for.
    #[must_use]
    pub fn viewport(&self) -> (usize, usize) {
        (self.want_viewport.0 as usize, self.want_viewport.1 as usize)
    }

    /// Sets the depth test in place.
    pub fn set_depth_test(&mut self, test: DepthTest) {
        self.ras.depth_test = test;
    }

    /// Enables or disables dithering in place (between strips too: the triangles already set
    /// up for the frame are drawn the new way from the next strip on).
    pub fn set_dither(&mut self, on: bool) {
        if on != self.ras.dither {
            self.ras.dither = on;
            // The dithered row routine draws only triangles checked for it at setup.
            self.ras
                .active
                .refresh_routine_rows(self.ras.next_row as i32, on && C::can_dither());
        }
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
        let (vw, vh) = (self.geo.vw, self.geo.vh);
        if LINES < vh {
            return Err(Error::StripTooShort {
                lines: LINES,
                height: vh,
            });
        }
        self.begin_target(target)?;
        let background = crate::scene::color::quantize::<C>(first.background);
        for c in &mut self.ras.color[..vh] {
            c[..vw].fill(background);
        }
        for d in self.ras.depth.iter_mut().take(vh) {
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
            total.add_pass(&self.ras.stats);
        }
        let area = Rectangle::new(Point::zero(), Size::new(vw as u32, vh as u32));
        target
            .fill_contiguous(
                &area,
                self.ras.color[..vh]
                    .iter()
                    .flat_map(|line| line[..vw].iter())
                    .copied(),
            )
            .map_err(Error::Target)?;
        Ok(total)
    }

    /// Moves the strip pass of the prepared frame to `row` ([`crate::frame::Frame::seek_row`]).
    pub(crate) fn seek_row(&mut self, row: usize) {
        let vh = self.geo.vh;
        let row = row.min(vh);
        self.clear_active();
        self.ras.next_row = row;
        if row >= vh {
            return;
        }
        let (mode, painter) = self.ras.setup_mode();
        let rows = crate::raster::seek::Rows {
            verts: &self.geo.verts,
            xverts: &self.geo.xverts,
            tris: &self.geo.tris,
            heads: &self.geo.heads,
            vh,
        };
        let ord = (ACTIVE <= H).then_some(&mut self.geo.starts[..]);
        let skipped = crate::raster::seek::seek::<C, ACTIVE, XA, _>(
            &mut self.ras.active,
            &mut self.geo.xactive,
            ord,
            rows,
            row,
            mode,
            painter,
            self.ras.dither,
            crate::raster::span_map::NoMap,
        );
        self.ras.active_skipped = self.ras.active_skipped.saturating_add(skipped);
    }

    /// The geometry stage of a frame one strip pass draws: [`Renderer::frame_start`], every
    /// object through the stage ([`Stores::frame_begin`], [`Stores::frame_object`],
    /// [`Stores::frame_end`]), then [`Renderer::frame_ready`].
    pub(crate) fn geometry<E, P: Probe, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Stats, Error<E>> {
        self.frame_start();
        let c = self.geo.frame_begin(scene, false)?;
        let mut f = crate::geometry::Frame::default();
        for (index, obj) in scene.objects.iter().enumerate() {
            self.geo
                .frame_object(&c, &mut f, scene, obj, index, probe)?;
        }
        let stats =
            self.geo
                .frame_end(scene, &c, &mut f, ACTIVE, self.ras.overflow, Self::CAPACITY)?;
        self.frame_ready(scene, stats);
        // A frame for strip passes too (odd).
        self.frame_id |= 1;
        Ok(stats)
    }

    /// The raster stage's next strip of the prepared frame ([`Raster::draw_strip`]: at most
    /// `limit` rows, into `ext` or the renderer's own lines; `CLEAR`: each line cleared first).
    pub(crate) fn draw_strip<P: Probe, const CLEAR: bool>(
        &mut self,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        self.ras
            .draw_strip::<S, H, VERTS, TRIS, XV, XA, P, CLEAR>(&mut self.geo, ext, limit, probe)
    }

    /// Before a frame's geometry stage: a new frame that no strip pass can draw yet (an even
    /// `frame_id`), the active list emptied, the viewport [`Renderer::set_viewport`] asked for
    /// taken.
    pub(crate) fn frame_start(&mut self) {
        self.frame_id = (self.frame_id | 1).wrapping_add(1);
        self.clear_active();
        self.take_viewport();
    }

    /// After a geometry stage that succeeded: the frame's statistics and background, and the
    /// strip pass at its first row.
    pub(crate) fn frame_ready<const L: usize>(&mut self, scene: &Scene<'_, S, L>, stats: Stats) {
        self.ras.active_skipped = 0;
        self.ras.background = crate::scene::color::quantize::<C>(scene.background);
        self.ras.next_row = 0;
        self.ras.stats = stats;
    }

    /// Empties the active list and frees the pool entries of its triangles (the frame's
    /// Phong lights and materials stay).
    pub(crate) fn clear_active(&mut self) {
        self.ras.active.clear();
        self.geo.free_triangle_entries();
    }

    /// The next row the strip pass draws (the viewport's height once the frame is complete or
    /// when nothing is prepared).
    #[must_use]
    pub fn next_row(&self) -> usize {
        self.ras.next_row
    }

    /// The statistics of the frame being drawn (complete once the last strip is drawn).
    #[must_use]
    pub fn stats(&self) -> Stats {
        self.ras.stats
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
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    > Default for Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>
{
    fn default() -> Self {
        Self::new()
    }
}

/// Bytes per vertex in the vertex store (12).
pub const VERTEX_BYTES: usize = core::mem::size_of::<ScreenVertex>();
/// Bytes per stored triangle (6).
pub const TRIANGLE_BYTES: usize = core::mem::size_of::<TriRecord>();
/// Bytes per active triangle (84).
pub const ACTIVE_BYTES: usize = core::mem::size_of::<ActiveTri>();
/// Bytes per vertex of the texture attribute store (`XV`): 20 on a 32-bit core, 24 on a
/// 64-bit host.
pub const VERTEX_EXTRA_BYTES: usize = core::mem::size_of::<VertexExtra>();
/// Bytes per entry of the textured triangles' pool (`XA`): 108 on a 32-bit core, 112 on a
/// 64-bit host.
pub const ACTIVE_EXTRA_BYTES: usize = core::mem::size_of::<ActiveExtra>();
/// [`VERTEX_EXTRA_BYTES`] on a 32-bit core (for sizing a device's renderer on the host;
/// checked at compile time on 32-bit targets).
pub const VERTEX_EXTRA_BYTES_32: usize = 20;
/// [`ACTIVE_EXTRA_BYTES`] on a 32-bit core.
pub const ACTIVE_EXTRA_BYTES_32: usize = 108;

// The documented record sizes on 32-bit cores.
#[cfg(target_pointer_width = "32")]
const _: () = assert!(
    VERTEX_EXTRA_BYTES == VERTEX_EXTRA_BYTES_32 && ACTIVE_EXTRA_BYTES == ACTIVE_EXTRA_BYTES_32
);

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
    use crate::num::scalar::Fx;
    use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
    use fixed::types::I16F16;

    #[test]
    pub(crate) fn record_sizes_are_the_documented_ones() {
        assert_eq!((VERTEX_BYTES, TRIANGLE_BYTES, ACTIVE_BYTES), (12, 6, 84));
        // The benchmark torus renderer (the support crate's `demo::TORUS_CAPACITY`, checked
        // there) meets the 16 KB budget.
        let bench = core::mem::size_of::<Renderer<Fx<I16F16>, Rgb565, 240, 240, 512, 466, 61>>();
        assert!(bench <= 16 * 1024, "{bench}");
    }

    pub(crate) fn check<R>(formula: usize) {
        let real = core::mem::size_of::<R>();
        assert!(
            real >= formula && real <= formula + 160,
            "size {real}, formula {formula}"
        );
    }

    #[test]
    pub(crate) fn ram_formula_matches_size_of() {
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

#[cfg(test)]
mod extra_size_tests {
    use super::*;

    #[test]
    fn attribute_store_records_are_the_documented_sizes() {
        let host = core::mem::size_of::<usize>() == 8;
        assert_eq!(
            (VERTEX_EXTRA_BYTES, ACTIVE_EXTRA_BYTES),
            if host { (24, 112) } else { (20, 108) }
        );
        assert_eq!(core::mem::align_of::<ActiveExtra>(), 4);
    }
}
