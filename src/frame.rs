//! The frame API: [`Renderer::prepare`] runs a frame's geometry stage with its
//! [`FrameOptions`] and returns a [`Frame`], whose strips then go to one of three sinks —
//! an embedded-graphics [`DrawTarget`] ([`Frame::strip_to`], or [`Frame::draw_to`] for all of
//! them), colour lines the caller owns ([`Frame::strip_into`]), or big-endian bytes
//! ([`Frame::strip_be`]). A plain frame's geometry can be shared read-only
//! ([`Frame::share`]) with [`crate::StripPass`]es, one per core.
//!
//! The options are types, not flags: a frame without a probe, layers or overlay compiles to
//! the code it had before they existed (a scene pays only for what it uses).

use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::raw::ToBytes;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Drawable;

use crate::error::{Error, StripBufferTooSmall};
use crate::num::scalar::Scalar;
use crate::raster::layers::Layers;
use crate::raster::shadow::Layering;
use crate::raster::strip::StripCanvas;
use crate::renderer::Renderer;
use crate::scene::color::TargetColor;
use crate::scene::Scene;
use crate::stats::{NoProbe, Probe, Stage, Stats};

mod mapped;
pub use mapped::{Mapped, MappedStrips};

/// What a frame is prepared with besides its scene: a probe ([`FrameOptions::probe`]), layers
/// ([`FrameOptions::layered`]: shadows, outlines, translucency) and an overlay composed into
/// every strip ([`FrameOptions::overlay`]). [`FrameOptions::new`] has none of them.
///
/// ```
/// # use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565, prelude::*};
/// # use scanline3d::prelude::*;
/// # let cube = Shape::<f32, 24, 12>::cube(1.0).unwrap();
/// # let objects = [Object { mesh: cube.mesh(), transform: Mat4::translate([0.0, 0.0, -4.0]),
/// #     material: Material::matte([255, 160, 64], 0.15, 0.85) }];
/// # let camera = Camera::look_at([0.0; 3], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0],
/// #     Projection::Perspective { fov_y: 0.8, near: 0.1, far: 10.0 }).unwrap();
/// # let scene = Scene::new(&objects, camera, [Light::white([-1.0, 1.0, 1.0])]);
/// let mut renderer = Renderer::<f32, Rgb565, 32, 32, 64, 64, 16, 4>::new();
/// let mut display = MockDisplay::<Rgb565>::new();
/// let mut frame = renderer.prepare(&scene, FrameOptions::new()).unwrap();
/// while let Some(rows) = frame.strip_to(&mut display).unwrap() {
///     // rows.start..rows.end of the frame are on the display now.
///     assert!(rows.len() <= 4);
/// }
/// ```
#[derive(Debug, Default)]
#[must_use]
pub struct FrameOptions<P = NoProbe, K = Plain, O = NoOverlay> {
    probe: P,
    kind: K,
    overlay: O,
}

impl FrameOptions {
    /// No probe, no layers, no overlay.
    pub const fn new() -> Self {
        FrameOptions {
            probe: NoProbe,
            kind: Plain,
            overlay: NoOverlay,
        }
    }
}

impl<P, K, O> FrameOptions<P, K, O> {
    /// Reports the frame's stage changes (and snapped vertices) to `probe`: a probe, or
    /// `&mut` one to read it afterwards. [`Probe::frame_start`] is called first thing in
    /// [`Renderer::prepare`]; [`Probe::frame_end`] when the frame's last strip has gone to
    /// its sink (or the frame failed).
    pub fn probe<Q: Probe>(self, probe: Q) -> FrameOptions<Q, K, O> {
        FrameOptions {
            probe,
            kind: self.kind,
            overlay: self.overlay,
        }
    }

    /// Composes `overlay` into every strip after the 3D content and before the strip goes to
    /// its sink, whichever sink it is: a `&` embedded-graphics [`Drawable`] (text, a HUD), or
    /// any [`StripOverlay`]. A `Drawable` is drawn once per strip, clipped to it, so its cost
    /// grows with the number of strips: keep it small (a line of text) or use a taller strip.
    pub fn overlay<Q>(self, overlay: Q) -> FrameOptions<P, K, Q> {
        FrameOptions {
            probe: self.probe,
            kind: self.kind,
            overlay,
        }
    }
}

impl<P, O> FrameOptions<P, Plain, O> {
    /// A layered frame, drawn with the lists of `layers`: each row of each strip draws the
    /// `layering`'s receivers, then its projected shadow (each receiver pixel darkened at most
    /// once, the stencil of `layers` keeping count), then the other opaque objects, then the
    /// translucent triangles ([`crate::Material::alpha`]) back to front, depth-tested against
    /// the opaque ones and not writing depth. With [`Layering::volumes`] the shadow is
    /// counted instead, after the opaque objects of each row (see
    /// [`crate::shadow::VolumeShadow`]); [`Layering::with_outline`] adds outlines before the
    /// translucent triangles. The shadow and the translucent triangles blend onto the strip's
    /// pixels (`C = Csrc·α + Cdst·(1 − α)`): one product per channel and pixel (the only
    /// per-pixel products of the renderer), a table lookup for the shadow on a target of at
    /// most 6 bits per channel (RGB565).
    ///
    /// Translucent triangles are sorted per row by the sum of their vertices' depths (then by
    /// their screen positions), so the image does not depend on the order they are given in;
    /// triangles that cross in depth are not split.
    ///
    /// [`Renderer::prepare`] fails with [`Error::Layers`] for a layering that cannot be drawn
    /// ([`crate::errors::LayerError`]) and [`Error::NoDepthLines`] on a renderer without
    /// depth lines (the layers test against them).
    pub fn layered<
        'l,
        's,
        S,
        const W: usize,
        const LINES: usize,
        const RA: usize,
        const PA: usize,
    >(
        self,
        layering: &'l Layering<'s, S>,
        layers: &'l mut Layers<W, LINES, RA, PA>,
    ) -> FrameOptions<P, Layered<'l, 's, S, W, LINES, RA, PA>, O> {
        FrameOptions {
            probe: self.probe,
            kind: Layered { layering, layers },
            overlay: self.overlay,
        }
    }
}

/// A frame without layers ([`FrameOptions::new`]'s kind).
#[derive(Copy, Clone, Debug, Default)]
pub struct Plain;

/// A layered frame's options ([`FrameOptions::layered`]).
#[derive(Debug)]
pub struct Layered<'l, 's, S, const W: usize, const LINES: usize, const RA: usize, const PA: usize>
{
    layering: &'l Layering<'s, S>,
    layers: &'l mut Layers<W, LINES, RA, PA>,
}

/// A layered frame's lists, which its strips draw with (what [`Layered`] becomes once the
/// frame is prepared: the [`Layering`] is only read by the geometry stage).
#[derive(Debug)]
pub struct LayeredStrips<'l, const W: usize, const LINES: usize, const RA: usize, const PA: usize> {
    layers: &'l mut Layers<W, LINES, RA, PA>,
}

/// No overlay ([`FrameOptions::new`]'s).
#[derive(Copy, Clone, Debug, Default)]
pub struct NoOverlay;

/// Something composed into every strip of a frame before the strip goes to its sink
/// ([`FrameOptions::overlay`]). A `&D` for any embedded-graphics [`Drawable`] `D` is one; an
/// overlay of its own can skip the strips it does not reach (as the support crate's glyph
/// labels do).
pub trait StripOverlay<C> {
    /// Draws into `canvas`, the strip's lines (a [`DrawTarget`] covering the whole screen,
    /// clipped to the strip's rows).
    fn compose<const W: usize>(&self, canvas: &mut StripCanvas<'_, C, W>);
}

impl<C> StripOverlay<C> for NoOverlay {
    #[inline(always)]
    fn compose<const W: usize>(&self, _canvas: &mut StripCanvas<'_, C, W>) {}
}

impl<C: TargetColor, D: Drawable<Color = C>> StripOverlay<C> for &D {
    fn compose<const W: usize>(&self, canvas: &mut StripCanvas<'_, C, W>) {
        // The canvas cannot fail.
        let _ = (*self).draw(canvas);
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Plain {}
    impl<S, const W: usize, const LINES: usize, const RA: usize, const PA: usize> Sealed
        for super::Layered<'_, '_, S, W, LINES, RA, PA>
    {
    }
    impl<const W: usize, const LINES: usize, const RA: usize, const PA: usize> Sealed
        for super::LayeredStrips<'_, W, LINES, RA, PA>
    {
    }
}

/// A frame's kind as its options give it ([`Plain`] or [`Layered`]): how its geometry stage
/// runs and what its strips draw with. Sealed: the renderer's own kinds only.
pub trait FrameKind<S, const W: usize, const LINES: usize>: sealed::Sealed {
    /// What the prepared frame's strips draw with.
    type Strips: StripSource<W, LINES>;
    #[doc(hidden)]
    #[allow(clippy::type_complexity)]
    fn geometry<
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
        const L: usize,
    >(
        self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Self::Strips, Error<core::convert::Infallible>>
    where
        S: Scalar;
}

/// What a prepared frame's strips draw with ([`Plain`] or [`LayeredStrips`]). Sealed.
pub trait StripSource<const W: usize, const LINES: usize>: sealed::Sealed {
    /// Whether [`Frame::draw_to`]'s loop is inlined into its caller.
    #[doc(hidden)]
    const INLINE_LOOP: bool;
    #[doc(hidden)]
    #[allow(clippy::type_complexity)]
    fn draw<
        S: Scalar,
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    >(
        &mut self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)>;
}

impl<S, const W: usize, const LINES: usize> FrameKind<S, W, LINES> for Plain {
    type Strips = Plain;
    #[inline(always)]
    fn geometry<
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
        const L: usize,
    >(
        self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Plain, Error<core::convert::Infallible>>
    where
        S: Scalar,
    {
        renderer.geometry(scene, probe).map(|_| Plain)
    }
}

impl<const W: usize, const LINES: usize> StripSource<W, LINES> for Plain {
    const INLINE_LOOP: bool = false;
    #[inline(always)]
    fn draw<
        S: Scalar,
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    >(
        &mut self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        renderer.draw_strip::<P, true>(ext, limit, probe)
    }
}

impl<'l, S, const W: usize, const LINES: usize, const RA: usize, const PA: usize>
    FrameKind<S, W, LINES> for Layered<'l, '_, S, W, LINES, RA, PA>
{
    type Strips = LayeredStrips<'l, W, LINES, RA, PA>;
    #[inline(always)]
    fn geometry<
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
        const L: usize,
    >(
        self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Self::Strips, Error<core::convert::Infallible>>
    where
        S: Scalar,
    {
        let Layered { layering, layers } = self;
        renderer.geometry_layered(scene, layering, layers, probe)?;
        Ok(LayeredStrips { layers })
    }
}

impl<const W: usize, const LINES: usize, const RA: usize, const PA: usize> StripSource<W, LINES>
    for LayeredStrips<'_, W, LINES, RA, PA>
{
    const INLINE_LOOP: bool = true;
    #[inline(always)]
    fn draw<
        S: Scalar,
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    >(
        &mut self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        // The layered strip is drawn in the renderer's lines (the layers' stencil and lists
        // are per renderer line); caller's lines get a copy.
        let (y0, n) =
            renderer
                .ras
                .draw_strip_layered(&mut renderer.geo, self.layers, limit, probe)?;
        if let Some(ext) = ext {
            let vw = renderer.geo.vw;
            for (dst, src) in ext.iter_mut().zip(&renderer.ras.color[..n]) {
                dst[..vw].copy_from_slice(&src[..vw]);
            }
        }
        Some((y0, n))
    }
}

/// A prepared frame ([`Renderer::prepare`]): its strips, top to bottom, go to one of three
/// sinks — [`Frame::strip_to`] (a [`DrawTarget`]; [`Frame::draw_to`] sends all of them),
/// [`Frame::strip_into`] (the caller's colour lines) or [`Frame::strip_be`] (big-endian
/// bytes). The sinks can be mixed within a frame; each strip's pixels are the same whichever
/// sink it goes to.
///
/// The frame borrows the renderer mutably; dropping it leaves the prepared geometry in the
/// renderer, unchanged. A plain frame's [`Frame::share`] hands the renderer out read-only for
/// [`crate::StripPass`]es.
#[derive(Debug)]
#[must_use = "a prepared frame draws nothing until its strips go to a sink"]
pub struct Frame<'r, R, P = NoProbe, K = Plain, O = NoOverlay> {
    renderer: &'r mut R,
    probe: P,
    strips: K,
    overlay: O,
    /// The probe was told the frame ended ([`Probe::frame_end`]).
    ended: bool,
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
    /// Draws one frame of `scene` into `target`, at the target's origin, `W × H` pixels (the
    /// viewport): [`Renderer::render_with`] with [`FrameOptions::new`].
    ///
    /// A target that does not contain the viewport ([`Error::TargetTooSmall`]), capacity
    /// shortfalls ([`Error::Shortfall`], unless the policy is
    /// [`crate::OverflowPolicy::DrawWhatFits`]) and missing normals are found before anything is
    /// drawn (the target first). A target error stops the frame at the failing strip and is
    /// returned.
    pub fn render<D, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        self.render_with(scene, FrameOptions::new(), target)
    }

    /// Draws one frame of `scene` with `options` (a probe, layers, an overlay) into `target`:
    /// [`Renderer::prepare`], then [`Frame::draw_to`]. The target is checked first: one that
    /// does not contain the viewport is [`Error::TargetTooSmall`] before anything is prepared
    /// (the probe hears nothing of such a frame). Then as [`Renderer::render`], and the
    /// errors of [`Renderer::prepare`].
    #[allow(clippy::type_complexity)]
    pub fn render_with<D, P, K, O, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        options: FrameOptions<P, K, O>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
        P: Probe,
        K: FrameKind<S, W, LINES>,
        O: StripOverlay<C>,
    {
        self.begin_target(target)?;
        self.prepare(scene, options)
            .map_err(Error::widen)?
            .draw_to(target)
    }

    /// Prepares a frame of `scene`: runs its geometry stage (transform, light, clip, project,
    /// cull, bucket; and for a layered frame its shadows, outlines and translucent triangles)
    /// and returns the [`Frame`], whose strips are drawn by its sinks. Nothing is drawn yet.
    /// The frame's viewport is the one asked for last ([`Renderer::set_viewport`]).
    ///
    /// # Errors
    ///
    /// Capacity shortfalls ([`Error::Shortfall`], unless the policy is
    /// [`crate::OverflowPolicy::DrawWhatFits`]), missing normals or texture coordinates, a
    /// translucent object in a frame without layers ([`Error::NeedsLayers`]), a layering that
    /// cannot be drawn ([`Error::Layers`], [`Error::NoDepthLines`]): all before anything is
    /// drawn, and no frame is left prepared. The error's target type is
    /// [`core::convert::Infallible`]: [`Error::widen`] gives it any other.
    #[allow(clippy::type_complexity)]
    pub fn prepare<P, K, O, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        options: FrameOptions<P, K, O>,
    ) -> Result<Frame<'_, Self, P, K::Strips, O>, Error<core::convert::Infallible>>
    where
        P: Probe,
        K: FrameKind<S, W, LINES>,
        O: StripOverlay<C>,
    {
        let FrameOptions {
            mut probe,
            kind,
            overlay,
        } = options;
        probe.frame_start();
        match kind.geometry(self, scene, &mut probe) {
            Ok(strips) => {
                probe.enter(Stage::Raster);
                Ok(Frame {
                    renderer: self,
                    probe,
                    strips,
                    overlay,
                    ended: false,
                })
            }
            Err(e) => {
                probe.enter(Stage::Done);
                probe.frame_end();
                Err(e)
            }
        }
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
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>
{
    /// The plain frame this renderer holds, prepared earlier and its [`Frame`] dropped, picked
    /// up where its strips stopped (without the probe or overlay it was prepared with): for
    /// code that prepares a frame in one place and sends its strips from another (a DMA
    /// interrupt, a task), where holding the `Frame` borrow between them does not fit. `None`
    /// when no plain frame is prepared: none yet, the last [`Renderer::prepare`] failed, or
    /// it was layered (a layered frame needs its [`Layers`]).
    pub fn prepared(&mut self) -> Option<Frame<'_, Self>> {
        if self.frame_id & 1 == 0 {
            return None;
        }
        Some(Frame {
            renderer: self,
            probe: NoProbe,
            strips: Plain,
            overlay: NoOverlay,
            ended: false,
        })
    }
}

impl<
        'r,
        S: Scalar,
        C: TargetColor,
        P: Probe,
        K: StripSource<W, LINES>,
        O: StripOverlay<C>,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    > Frame<'r, Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>, P, K, O>
{
    /// Draws the next strip (up to `LINES` rows) and sends it to `target` (rows `y0..` at
    /// their place on the screen, the viewport's width) with one `fill_contiguous`; returns
    /// its rows, or `None` when the frame is complete.
    ///
    /// # Errors
    ///
    /// [`Error::TargetTooSmall`] when `target` does not contain the viewport at its origin
    /// (nothing is drawn; the frame stays where it was). A target error is returned as
    /// [`Error::Target`], and the frame is then abandoned (later strips are `None`).
    pub fn strip_to<D>(&mut self, target: &mut D) -> Result<Option<Range<usize>>, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        if self.is_complete() {
            return Ok(None);
        }
        self.renderer.check_target(target)?;
        self.send(target)
    }

    /// Sends every strip left to `target` ([`Frame::strip_to`] until `None`) and returns the
    /// frame's [`Stats`].
    ///
    /// # Errors
    ///
    /// As [`Frame::strip_to`]; the target is checked once, before the first strip.
    // Inlined, and its loop chosen by kind (the shapes the benchmark firmware measured
    // cheapest, scripts/mcu-bench): a layered frame's rows are inlined into its loop, and
    // behind an outlined `draw_to` they were up to 4 % dearer on the Cortex-M4F; a plain
    // frame's strips are drawn by out-of-line code anyway and its loop stays out of line.
    // `prepare` is not inlined: that took the 16 KB part's last bytes of stack.
    #[inline(always)]
    pub fn draw_to<D>(self, target: &mut D) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        if K::INLINE_LOOP {
            self.draw_all_inlined(target)
        } else {
            self.draw_all(target)
        }
    }

    /// [`Frame::draw_to`]'s loop for a plain frame, not inlined; the probe is told of the
    /// end by the last strip's `send` (measured cheaper here than once after the loop: 1.1 %
    /// on the 16 KB RISC-V part's torus).
    fn draw_all<D>(mut self, target: &mut D) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        if !self.is_complete() {
            if let Err(e) = self.renderer.check_target(target) {
                self.end();
                return Err(e);
            }
            while self.send(target)?.is_some() {}
        }
        self.end();
        Ok(self.renderer.ras.stats)
    }

    /// [`Frame::draw_to`]'s loop for a layered frame.
    #[inline(always)]
    fn draw_all_inlined<D>(mut self, target: &mut D) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        if !self.is_complete() {
            if let Err(e) = self.renderer.check_target(target) {
                self.end();
                return Err(e);
            }
            // The probe hears of the end once, after the loop (not checked per strip).
            loop {
                match self.send_strip(target) {
                    Ok(Some(_)) => {}
                    Ok(None) => break,
                    Err(e) => {
                        self.end();
                        return Err(e);
                    }
                }
            }
        }
        self.end();
        Ok(self.renderer.ras.stats)
    }

    /// Draws the next strip into `lines`, colour lines that the caller owns, and returns its
    /// rows, or `None` when the frame is complete. Nothing is sent anywhere: the caller hands
    /// the lines to a DMA channel, a display driver or another core, and may draw into them
    /// first (a label, a HUD).
    ///
    /// The strip is `min(N, LINES, rows left)` rows high (the depth lines are the
    /// renderer's); row `y0 + i` is `lines[i][..vw]` for the returned `y0..y1`. Lines beyond
    /// the strip and columns beyond the viewport are left as they were. Each line is cleared
    /// to the background first, so a buffer can be reused without clearing it. (A layered
    /// frame's strip is drawn in the renderer's lines and copied: one more store a pixel.)
    ///
    /// For RGB565, a line is `W` native 16-bit words: an SPI display sends them in its own
    /// (big-endian) order when the SPI transfers 16-bit frames, which most microcontrollers'
    /// SPI and DMA units can do with no byte swapping at all (the Pico firmware does this).
    /// For a byte stream, [`Frame::strip_be`] writes big-endian bytes instead.
    pub fn strip_into<const N: usize>(&mut self, lines: &mut [[C; W]; N]) -> Option<Range<usize>> {
        const { assert!(N >= 1, "a strip buffer needs at least one line") };
        let (y0, n) = self
            .strips
            .draw(self.renderer, Some(lines), N, &mut self.probe)?;
        self.overlay.compose(&mut StripCanvas::new(
            &mut lines[..n],
            y0,
            self.renderer.geo.vh as u32,
        ));
        self.after_strip();
        Some(y0..y0 + n)
    }

    /// Draws the next strip in the renderer's lines and writes it to `out` as big-endian
    /// pixel bytes (for RGB565 the byte order of SPI panels such as the ST7789 and ILI9341:
    /// high byte first), row after row, `vw` pixels a row; returns its rows, or `None` when
    /// the frame is complete. The strip is as many rows as fit in `out`, at most `LINES`.
    /// For a driver that sends bytes (an 8-bit SPI DMA channel, a USB or network link);
    /// [`Frame::strip_into`] avoids the copy.
    ///
    /// # Errors
    ///
    /// [`StripBufferTooSmall`] when `out` cannot hold one row (`vw · bytes per pixel`);
    /// nothing is drawn then.
    pub fn strip_be(&mut self, out: &mut [u8]) -> Result<Option<Range<usize>>, StripBufferTooSmall>
    where
        C: ToBytes,
        C::Bytes: AsRef<[u8]>,
    {
        let bpp = core::mem::size_of::<C::Bytes>();
        let vw = self.renderer.geo.vw;
        let row_bytes = vw * bpp;
        if self.is_complete() {
            return Ok(None);
        }
        if out.len() < row_bytes || bpp == 0 {
            return Err(StripBufferTooSmall {
                needed: row_bytes,
                given: out.len(),
            });
        }
        let fit = out.len() / row_bytes;
        let Some((y0, n)) = self.strips.draw(self.renderer, None, fit, &mut self.probe) else {
            return Ok(None);
        };
        let r = &mut *self.renderer;
        self.overlay.compose(&mut StripCanvas::new(
            &mut r.ras.color[..n],
            y0,
            r.geo.vh as u32,
        ));
        for (line, dst) in r.ras.color[..n].iter().zip(out.chunks_exact_mut(row_bytes)) {
            for (c, d) in line[..vw].iter().zip(dst.chunks_exact_mut(bpp)) {
                d.copy_from_slice(c.to_be_bytes().as_ref());
            }
        }
        self.after_strip();
        Ok(Some(y0..y0 + n))
    }

    /// Enables or disables dithering from the next strip on ([`Renderer::set_dither`]: the
    /// triangles already set up are drawn the new way).
    pub fn set_dither(&mut self, on: bool) {
        self.renderer.set_dither(on);
    }

    /// The next row the frame's strips start at (the viewport's height once it is complete).
    #[must_use]
    pub fn next_row(&self) -> usize {
        self.renderer.ras.next_row
    }

    /// Whether every strip of the frame has been drawn (or the frame was abandoned after a
    /// target error).
    #[must_use]
    pub fn is_complete(&self) -> bool {
        self.renderer.ras.next_row >= self.renderer.geo.vh
    }

    /// The frame's statistics: the geometry stage's, and the strips' counts so far (complete
    /// once the last strip is drawn).
    #[must_use]
    pub fn stats(&self) -> Stats {
        self.renderer.ras.stats
    }

    /// The viewport the frame was prepared for (width, height).
    #[must_use]
    pub fn viewport(&self) -> (usize, usize) {
        (self.renderer.geo.vw, self.renderer.geo.vh)
    }

    /// Draws the next strip in the renderer's lines, composes the overlay and sends the strip
    /// to `target` (already checked); tells the probe when the frame is complete.
    fn send<D>(&mut self, target: &mut D) -> Result<Option<Range<usize>>, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        let sent = self.send_strip(target);
        match &sent {
            Ok(_) => self.after_strip(),
            Err(_) => self.end(),
        }
        sent
    }

    /// [`Frame::send`] without telling the probe anything.
    #[inline(always)]
    fn send_strip<D>(&mut self, target: &mut D) -> Result<Option<Range<usize>>, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        let Some((y0, n)) = self
            .strips
            .draw(self.renderer, None, LINES, &mut self.probe)
        else {
            return Ok(None);
        };
        let r = &mut *self.renderer;
        let (vw, vh) = (r.geo.vw, r.geo.vh);
        self.overlay
            .compose(&mut StripCanvas::new(&mut r.ras.color[..n], y0, vh as u32));
        let area = Rectangle::new(Point::new(0, y0 as i32), Size::new(vw as u32, n as u32));
        self.probe.enter(Stage::Output);
        let sent = target.fill_contiguous(
            &area,
            r.ras.color[..n]
                .iter()
                .flat_map(|line| line[..vw].iter())
                .copied(),
        );
        self.probe.enter(Stage::Raster);
        if let Err(e) = sent {
            // The frame is abandoned: its later strips are `None`.
            self.renderer.ras.next_row = vh;
            return Err(Error::Target(e));
        }
        Ok(Some(y0..y0 + n))
    }

    /// Tells the probe the frame ended once its last strip is drawn.
    #[inline(always)]
    fn after_strip(&mut self) {
        if self.is_complete() {
            self.end();
        }
    }

    fn end(&mut self) {
        if !self.ended {
            self.ended = true;
            self.probe.enter(Stage::Done);
            self.probe.frame_end();
        }
    }
}

impl<
        'r,
        S: Scalar,
        C: TargetColor,
        P: Probe,
        O: StripOverlay<C>,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    > Frame<'r, Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>, P, Plain, O>
{
    /// Moves the frame's strips to `row` (clamped to the viewport's height): the next strip
    /// starts there; rows above it are not drawn. The strips from `row` on are bit for bit
    /// those of the whole frame: each triangle that crosses `row` is set up at its first row
    /// and stepped down to `row` as the whole frame's pass steps it, and the active list's
    /// order (which decides depth ties) is replayed. For splitting a frame's rows between
    /// renderers, or for redrawing part of the screen from the same geometry, also after the
    /// frame was drawn. (Plain frames only: a layered frame's lists are built strip by strip.)
    ///
    /// Costs one triangle setup for each triangle that crosses `row` (and each textured one
    /// above it), its row steps down to `row`, and a look at the vertices of every triangle
    /// that starts above `row`.
    pub fn seek_row(&mut self, row: usize) {
        self.renderer.seek_row(row);
    }

    /// The prepared frame's renderer, read-only, for the rest of its borrow: for
    /// [`crate::StripPass`]es that draw the frame's rows, one per core or in any split
    /// ([`crate::StripPass::begin`]). The renderer keeps the frame until it is prepared
    /// again.
    #[must_use]
    pub fn share(self) -> &'r Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL> {
        self.renderer
    }
}
