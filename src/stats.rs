//! The frame's statistics and the probe that reports the pipeline's stages.

use crate::kernel::records::CullCounts;

/// A pipeline stage, as reported to a [`Probe`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
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
/// microcontroller. [`Renderer::render`](crate::Renderer::render) uses [`NoProbe`], which compiles to nothing.
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

/// A probe lent to a frame ([`crate::FrameOptions::probe`]`(&mut probe)`), to be read after it.
impl<P: Probe + ?Sized> Probe for &mut P {
    #[inline(always)]
    fn enter(&mut self, stage: Stage) {
        (**self).enter(stage);
    }
    #[inline(always)]
    fn frame_start(&mut self) {
        (**self).frame_start();
    }
    #[inline(always)]
    fn frame_end(&mut self) {
        (**self).frame_end();
    }
    #[inline(always)]
    fn snap(&mut self, index: u32, x: i32, y: i32) -> (i32, i32) {
        (**self).snap(index, x, y)
    }
    const SNAPS: bool = P::SNAPS;
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
/// `#[non_exhaustive]`: more counts may be added; start from `Stats::default()`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
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
    /// The largest number of triangles active on one row. In a layered frame
    /// ([`FrameOptions::layered`](crate::FrameOptions::layered)), those of the
    /// renderer's own active list (`ACTIVE`): the opaque triangles that do not receive a
    /// planar shadow.
    pub max_active: u32,
    /// Of a frame with textured or Phong objects: the vertex-store index where the last such
    /// object's vertices end, which the renderer's `XV` must reach (0 without such objects).
    pub attr_vertices: u32,
    /// Of a frame with textured or Phong objects: the attribute pool entries the frame
    /// needs, `XA` — the frame's fog, Phong lights and materials, which take entries for the
    /// whole frame, plus [`Stats::max_active`] (a bound of the textured and Phong triangles
    /// on one row). 0 without such objects.
    pub attr_active: u32,
    /// Of a layered frame: the most receiver triangles (of a planar shadow) on one row, the
    /// [`crate::Layers`]' `RA`.
    pub max_receivers: u32,
    /// Of a layered frame: the most shadow, outline and translucent triangles on one row,
    /// the [`crate::Layers`]' `PA`.
    pub max_overlays: u32,
}

impl Stats {
    /// Every count zero (a frame not yet prepared).
    pub(crate) const ZERO: Stats = Stats {
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
        attr_vertices: 0,
        attr_active: 0,
        max_receivers: 0,
        max_overlays: 0,
    };

    /// Adds the cull loop's counts (the kernels count into their own record).
    #[inline(always)]
    pub(crate) fn add_culling(&mut self, c: &CullCounts) {
        self.outside = self.outside.wrapping_add(c.outside);
        self.culled = self.culled.wrapping_add(c.culled);
        self.degenerate = self.degenerate.wrapping_add(c.degenerate);
        self.empty = self.empty.wrapping_add(c.empty);
        self.drawn = self.drawn.wrapping_add(c.drawn);
    }

    /// Adds the counts of another pass of the same frame ([`Renderer::render_passes`]):
    /// the `max_*` and `attr_*` figures are the larger of the two, every other field the sum
    /// (saturating).
    pub(crate) fn add_pass(&mut self, p: &Stats) {
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
        self.attr_vertices = self.attr_vertices.max(p.attr_vertices);
        self.attr_active = self.attr_active.max(p.attr_active);
        self.max_receivers = self.max_receivers.max(p.max_receivers);
        self.max_overlays = self.max_overlays.max(p.max_overlays);
    }

    /// Counts one triangle-row's fragments and written pixels (saturating).
    pub(crate) fn add_row(&mut self, fragments: u32, written: u32) {
        self.fragments = self.fragments.saturating_add(fragments);
        self.pixels_written = self.pixels_written.saturating_add(written);
    }
}
