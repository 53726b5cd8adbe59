//! A strip pass of its own over a renderer's prepared frame, so that two cores (or two
//! tasks) draw different rows of the same frame at once: the renderer holds the frame's
//! geometry (vertex and attribute stores, triangles, row buckets), which the passes only read
//! through a shared `&Renderer`; each pass holds what a strip pass changes (its active list,
//! its attribute pool entries, its depth lines and colour lines, its row cursor and counts).
//! The rows a pass draws are bit for bit those of the whole frame (it starts at its first row
//! as [`crate::frame::Frame::seek_row`] does).

use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use crate::error::Error;
use crate::geometry::pool::{ActiveExtra, TRI};
use crate::kernel::records::ActiveList;
use crate::num::scalar::Scalar;
use crate::raster::seek::seek;
use crate::raster::strip::{strip_rows, PassMut};
use crate::renderer::Renderer;
use crate::scene::color::TargetColor;
use crate::stats::{NoProbe, Stats};

/// A strip pass over the frame a [`Renderer`] prepared, with its own state: for drawing some
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
    active: ActiveList<ACTIVE>,
    /// The frame's lights, materials and fog entries (copied at [`StripPass::begin`]) and the
    /// entries of this pass's textured and Phong triangles.
    pool: [ActiveExtra; XA],
    color: [[C; W]; LINES],
    /// 16-bit depth, 0 = nearest, 65535 = the far plane (cleared to 65535).
    depth: [[u16; W]; ZL],
    /// The next row this pass draws, and the row it stops before (`next_row ≥ end_row`: done).
    next_row: usize,
    end_row: usize,
    /// The renderer's frame this pass began on ([`Renderer`]'s `frame_id`, odd; 0: none).
    frame_id: u32,
    /// Whether the pass's triangles were given their Cortex-M routine rows for a dithered
    /// strip (the renderer's dithering may change between strips).
    dither: bool,
    stats: Stats,
    skipped: u32,
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

    /// Begins drawing rows `rows` (clamped to the viewport) of the frame `renderer` holds:
    /// the next strip starts at `rows.start`, exactly as the whole frame's rows (the triangles
    /// that cross it are set up at their first rows and stepped down, as
    /// [`crate::frame::Frame::seek_row`] does). May be called again for other rows of the same frame.
    ///
    /// # Errors
    ///
    /// [`Error::NoFrame`] when the renderer holds no frame a strip pass can draw (none
    /// prepared, the last geometry stage failed, or a layered frame).
    #[allow(clippy::type_complexity)]
    pub fn begin<
        S: Scalar,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const RL: usize,
        const XV: usize,
        const RZ: usize,
    >(
        &mut self,
        renderer: &Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, RL, XV, XA, RZ>,
        rows: Range<usize>,
    ) -> Result<(), Error<core::convert::Infallible>> {
        const {
            assert!(
                (RZ == 0) == (ZL == 0),
                "a pass has depth lines (ZL = LINES) exactly when its renderer has them"
            )
        };
        if renderer.frame_id & 1 == 0 {
            self.frame_id = 0;
            return Err(Error::NoFrame);
        }
        let frame = renderer.view();
        // The frame's own pool entries (lights, materials, fog); the renderer's triangle
        // entries are its own pass's.
        for (mine, theirs) in self.pool.iter_mut().zip(renderer.geo.xactive.iter()) {
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
        self.frame_id = renderer.frame_id;
        self.dither = frame.dither;
        self.stats = Stats::ZERO;
        self.skipped = 0;
        if start < self.end_row {
            self.skipped = seek::<C, ACTIVE>(
                &mut self.active,
                &mut self.pool,
                None,
                frame.rows,
                start,
                frame.mode,
                frame.painter,
                frame.dither,
            );
        }
        Ok(())
    }

    /// Draws the pass's next strip into `lines`, colour lines the caller owns (as
    /// [`crate::frame::Frame::strip_into`]: `min(N, LINES, rows left)` rows, each line cleared to
    /// the background first), and returns its rows, or `None` when the pass's rows are done.
    ///
    /// # Errors
    ///
    /// [`Error::FrameChanged`] when `renderer` holds another frame than the one the pass
    /// began on (nothing is drawn).
    #[allow(clippy::type_complexity)]
    pub fn render_strip_into<
        S: Scalar,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const RL: usize,
        const XV: usize,
        const RZ: usize,
        const N: usize,
    >(
        &mut self,
        renderer: &Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, RL, XV, XA, RZ>,
        lines: &mut [[C; W]; N],
    ) -> Result<Option<Range<usize>>, Error<core::convert::Infallible>> {
        const { assert!(N >= 1, "a strip buffer needs at least one line") };
        Ok(self
            .strip::<S, H, VERTS, TRIS, RL, XV, RZ>(renderer, Some(lines), N)?
            .map(|(y0, n)| y0..y0 + n))
    }

    /// Draws the pass's next strip into its own lines and sends it to `target` (rows `y0..`
    /// at their place in the frame, the viewport's width), returning its rows, or `None` when
    /// the pass's rows are done.
    ///
    /// # Errors
    ///
    /// [`Error::FrameChanged`] as [`StripPass::render_strip_into`];
    /// [`Error::TargetTooSmall`] when the target does not contain the viewport (nothing is
    /// drawn); [`Error::Target`] when the target fails (the pass's rows are then done).
    #[allow(clippy::type_complexity)]
    pub fn render_strip<
        S: Scalar,
        D: DrawTarget<Color = C>,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const RL: usize,
        const XV: usize,
        const RZ: usize,
    >(
        &mut self,
        renderer: &Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, RL, XV, XA, RZ>,
        target: &mut D,
    ) -> Result<Option<Range<usize>>, Error<D::Error>> {
        if renderer.frame_id != self.frame_id || self.frame_id == 0 {
            return Err(Error::FrameChanged);
        }
        if self.next_row >= self.end_row {
            return Ok(None);
        }
        renderer.check_target(target)?;
        let Some((y0, n)) = self
            .strip::<S, H, VERTS, TRIS, RL, XV, RZ>(renderer, None, LINES)
            .map_err(|_| Error::FrameChanged)?
        else {
            return Ok(None);
        };
        // The prepared frame's width (a viewport asked for since applies to the next frame).
        let vw = renderer.geo.vw;
        let area = Rectangle::new(Point::new(0, y0 as i32), Size::new(vw as u32, n as u32));
        let pixels = self.color[..n]
            .iter()
            .flat_map(|line| line[..vw].iter())
            .copied();
        if let Err(e) = target.fill_contiguous(&area, pixels) {
            self.next_row = self.end_row;
            return Err(Error::Target(e));
        }
        Ok(Some(y0..y0 + n))
    }

    /// The rows left to this pass (empty once done or before a [`StripPass::begin`]).
    #[must_use]
    pub fn rows_left(&self) -> Range<usize> {
        self.next_row..self.end_row.max(self.next_row)
    }

    /// This pass's counts since its [`StripPass::begin`]: the fragments tested and pixels
    /// written (the frame's other counts are the renderer's [`Renderer::stats`]).
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

    /// The next strip: its first row and height, or `None` when the pass's rows are done.
    #[allow(clippy::type_complexity)]
    fn strip<
        S: Scalar,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const RL: usize,
        const XV: usize,
        const RZ: usize,
    >(
        &mut self,
        renderer: &Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, RL, XV, XA, RZ>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
    ) -> Result<Option<(usize, usize)>, Error<core::convert::Infallible>> {
        if renderer.frame_id != self.frame_id || self.frame_id == 0 {
            return Err(Error::FrameChanged);
        }
        let frame = renderer.view();
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
        Ok(
            strip_rows::<C, NoProbe, W, ACTIVE, LINES, XV, XA, ZL, true>(
                frame,
                pass,
                lines,
                limit,
                &mut NoProbe,
            ),
        )
    }
}
