//! The [`StripPass`] methods that take the renderer holding the frame: each hands the raster
//! stage's pass (`raster::pass`) the prepared frame's parts (its id, its view, its pool).

use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use crate::error::Error;
use crate::num::scalar::Scalar;
use crate::raster::pass::StripPass;
use crate::renderer::Renderer;
use crate::scene::color::TargetColor;

impl<
        C: TargetColor,
        const W: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XA: usize,
        const ZL: usize,
    > StripPass<C, W, ACTIVE, LINES, XA, ZL>
{
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
        self.begin_frame(
            renderer.frame_id,
            renderer.ras.view(&renderer.geo),
            &renderer.geo.xactive,
            rows,
        )
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
        self.strip_frame::<XV>(
            renderer.frame_id,
            renderer.ras.view(&renderer.geo),
            ext,
            limit,
        )
    }
}
