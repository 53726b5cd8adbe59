//! A strip pass of its own over a renderer's prepared frame, so that two cores (or two
//! tasks) draw different rows of the same frame at once: the renderer holds the frame's
//! geometry (vertex and attribute stores, triangles, row buckets), which the passes only read
//! through a shared `&Renderer`; each pass holds what a strip pass changes (its active list,
//! its attribute pool entries, its depth lines and colour lines, its row cursor and counts).
//! The rows a pass draws are bit for bit those of the whole frame (it starts at its first row
//! as [`crate::frame::Frame::seek_row`] does).

use core::ops::Range;

use crate::error::Error;
use crate::geometry::pool::{ActiveExtra, TRI};
use crate::kernel::records::ActiveList;
use crate::raster::seek::seek;
use crate::raster::span_map::NoMap;
use crate::raster::strip::{strip_rows, FrameView, PassMut};
use crate::scene::color::TargetColor;
use crate::stats::{NoProbe, Stats};

/// A strip pass over the frame a [`crate::Renderer`] prepared, with its own state: for drawing some
/// of a frame's rows on one core while another core (with its own `StripPass`) draws others,
/// both reading the same `&Renderer`.
///
/// `C` and `W` are the renderer's colour and width; `ACTIVE` and `XA` its active list and
/// attribute pool capacities (the frame's needs were checked against them when it was
/// prepared); `LINES` the pass's own strip height (any); `ZL` its depth lines: `LINES`, or 0
/// for a renderer without depth lines.
///
/// ```
/// # use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// # use scanline3d::prelude::*;
/// # use scanline3d::StripPass;
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// # let shape = scanline3d::Shape::<Q, 24, 12>::cube(1.0).unwrap();
/// # let objects = [Object { mesh: shape.mesh(), transform: Mat4::identity(),
/// #     material: Material::matte([200, 80, 40], Q::from_f64(0.2), Q::from_f64(0.8)) }];
/// # let camera = Camera::look_at([0.0, 1.0, 3.0].map(Q::from_f64), [Q::ZERO; 3],
/// #     [Q::ZERO, Q::ONE, Q::ZERO], Projection::Perspective { fov_y: Q::from_f64(0.9),
/// #     near: Q::from_f64(0.1), far: Q::from_f64(10.0) }).unwrap();
/// # let scene = Scene::new(&objects, camera, [Light::white([Q::ONE; 3])]);
/// let mut renderer = Box::new(Renderer::<Q, Rgb565, 96, 96, 32, 16, 8>::new());
/// // The prepared frame's geometry, lent read-only to the passes.
/// let shared = renderer.prepare(&scene, FrameOptions::new()).unwrap().share();
/// // One pass per core: rows 0..48 and 48..96 of the same frame (here one after the other).
/// let (mut top, mut bottom) = (
///     StripPass::<Rgb565, 96, 8, 8>::new(),
///     StripPass::<Rgb565, 96, 8, 8>::new(),
/// );
/// top.begin(shared, 0..48).unwrap();
/// bottom.begin(shared, 48..96).unwrap();
/// let mut lines = [[Rgb565::BLACK; 96]; 8];
/// while let Some(rows) = bottom.render_strip_into(shared, &mut lines).unwrap() {
///     // send `lines[..rows.len()]` to rows `rows` of the display
/// #   assert!(rows.start >= 48);
/// }
/// while let Some(rows) = top.render_strip_into(shared, &mut lines).unwrap() {
/// #   assert!(rows.end <= 48);
/// }
/// ```
///
/// # RAM
///
/// [`StripPass::RAM_BYTES`] is the exact figure: about `84·ACTIVE + 108·XA` (active list,
/// pool) `+ LINES·W·(size_of::<C>() + 2)` (colour and depth lines) plus a few words. The
/// depth lines are as many as the strips are high (`LINES`); the colour lines are drawn into
/// by [`StripPass::render_strip`] only ([`StripPass::render_strip_into`] draws into the
/// caller's).
#[derive(Debug)]
pub struct StripPass<
    C,
    const W: usize,
    const ACTIVE: usize,
    const LINES: usize = 1,
    const XA: usize = 0,
    const ZL: usize = LINES,
> {
    pub(crate) active: ActiveList<ACTIVE>,
    /// The frame's lights, materials and fog entries (copied at [`StripPass::begin`]) and the
    /// entries of this pass's textured and Phong triangles.
    pub(crate) pool: [ActiveExtra; XA],
    pub(crate) color: [[C; W]; LINES],
    /// 16-bit depth, 0 = nearest, 65535 = the far plane (cleared to 65535).
    pub(crate) depth: [[u16; W]; ZL],
    /// The next row this pass draws, and the row it stops before (`next_row ≥ end_row`: done).
    pub(crate) next_row: usize,
    pub(crate) end_row: usize,
    /// The renderer's frame this pass began on ([`crate::Renderer`]'s `frame_id`, odd; 0: none).
    pub(crate) frame_id: u32,
    /// Whether the pass's triangles were given their Cortex-M routine rows for a dithered
    /// strip (the renderer's dithering may change between strips).
    pub(crate) dither: bool,
    pub(crate) stats: Stats,
    pub(crate) skipped: u32,
}

impl<
        C: TargetColor,
        const W: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XA: usize,
        const ZL: usize,
    > Default for StripPass<C, W, ACTIVE, LINES, XA, ZL>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<
        C: TargetColor,
        const W: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XA: usize,
        const ZL: usize,
    > StripPass<C, W, ACTIVE, LINES, XA, ZL>
{
    /// Exact RAM of this pass in bytes.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    const CHECK: () = {
        assert!(LINES >= 1, "LINES must be at least 1");
        assert!(
            ZL == LINES || ZL == 0,
            "ZL (depth lines) must be LINES (a Z-buffer) or 0 (no depth lines)"
        );
    };

    /// A pass that has begun no frame, its colour lines black. Returned by value: for a large
    /// pass, see [`StripPass::const_new`].
    #[must_use]
    pub fn new() -> Self {
        Self::const_new(C::from_channels([0; 3]))
    }

    /// [`StripPass::new`] as a `const fn`, its colour lines `fill` (for a `static`).
    #[must_use]
    pub const fn const_new(fill: C) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CHECK;
        StripPass {
            active: ActiveList::new(),
            pool: [ActiveExtra::EMPTY; XA],
            color: [[fill; W]; LINES],
            depth: [[u16::MAX; W]; ZL],
            next_row: 0,
            end_row: 0,
            frame_id: 0,
            dither: false,
            stats: Stats::ZERO,
            skipped: 0,
        }
    }

    /// The rows left to this pass (empty once done or before a [`StripPass::begin`]).
    #[must_use]
    pub fn rows_left(&self) -> Range<usize> {
        self.next_row..self.end_row.max(self.next_row)
    }

    /// This pass's counts since its [`StripPass::begin`]: the fragments tested and pixels
    /// written (the frame's other counts are the renderer's [`crate::Renderer::stats`]).
    #[must_use]
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Triangles this pass left out because its active list or pool was full (only under
    /// [`crate::OverflowPolicy::DrawWhatFits`]: a frame's needs are checked otherwise).
    #[must_use]
    pub fn skipped(&self) -> u32 {
        self.skipped
    }

    /// Begins drawing rows `rows` of `frame`, prepared with id `frame_id` and pool `pool`
    /// ([`crate::StripPass::begin`] with the renderer's parts). Inlined into that method, which
    /// knows the renderer's `XV`: out of line, the seek's textured set-up stayed in firmware
    /// without attribute stores (7.7 KB more of the Pico firmware's RAM code).
    #[inline(always)]
    pub(crate) fn begin_frame(
        &mut self,
        frame_id: u32,
        frame: FrameView<'_, C>,
        pool: &[ActiveExtra],
        rows: Range<usize>,
    ) -> Result<(), Error<core::convert::Infallible>> {
        if frame_id & 1 == 0 {
            self.frame_id = 0;
            return Err(Error::NoFrame);
        }
        // The frame's own pool entries (lights, materials, fog); the renderer's triangle
        // entries are its own pass's.
        for (mine, theirs) in self.pool.iter_mut().zip(pool.iter()) {
            *mine = if theirs.kind == TRI {
                ActiveExtra::EMPTY
            } else {
                *theirs
            };
        }
        self.active.clear();
        let vh = frame.rows.vh;
        let start = rows.start.min(vh);
        self.next_row = start;
        self.end_row = rows.end.min(vh);
        self.frame_id = frame_id;
        self.dither = frame.dither;
        self.stats = Stats::ZERO;
        self.skipped = 0;
        if start < self.end_row {
            self.skipped = seek::<C, ACTIVE, XA, NoMap>(
                &mut self.active,
                &mut self.pool,
                None,
                frame.rows,
                start,
                frame.mode,
                frame.painter,
                frame.dither,
                frame.map,
            );
        }
        Ok(())
    }

    /// The next strip of `frame` (prepared with id `frame_id`, with vertex attribute stores of
    /// `XV` vertices): its first row and height, or `None` when the pass's rows are done.
    #[inline(always)]
    pub(crate) fn strip_frame<const XV: usize>(
        &mut self,
        frame_id: u32,
        frame: FrameView<'_, C>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
    ) -> Result<Option<(usize, usize)>, Error<core::convert::Infallible>> {
        if frame_id != self.frame_id || self.frame_id == 0 {
            return Err(Error::FrameChanged);
        }
        if frame.dither != self.dither {
            // As the renderer does when its dithering changes between strips.
            self.dither = frame.dither;
            self.active
                .refresh_routine_rows(self.next_row as i32, frame.dither && C::can_dither());
        }
        let pass = PassMut {
            active: &mut self.active,
            pool: &mut self.pool,
            ord: None,
            depth: &mut self.depth,
            next_row: &mut self.next_row,
            end_row: self.end_row,
            stats: &mut self.stats,
            skipped: &mut self.skipped,
        };
        let lines = match ext {
            Some(lines) => lines,
            None => self.color.as_mut_slice(),
        };
        Ok(strip_rows::<
            C,
            NoProbe,
            W,
            ACTIVE,
            LINES,
            XV,
            XA,
            ZL,
            true,
            NoMap,
        >(frame, pass, lines, limit, &mut NoProbe))
    }
}
