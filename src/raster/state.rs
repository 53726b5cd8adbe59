//! The raster stage's state: the strip's colour and depth lines, the active triangles, the
//! settings a strip pass reads (depth test, draw order, dithering), and where the pass is in
//! the prepared frame. The renderer owns one beside the geometry stage's stores; the raster
//! stage's functions are methods of it, and take those stores as an argument.

use crate::error::OverflowPolicy;
use crate::kernel::records::ActiveList;
use crate::raster::depth_mode::DrawOrder;
use crate::raster::{DepthTest, SpanMode};
use crate::scene::color::TargetColor;
use crate::stats::Stats;

/// The raster state of a renderer `W` pixels wide with `LINES` colour lines, `ZL` depth lines
/// (`LINES`, or 0 without a depth buffer) and `ACTIVE` active triangles, in colour type `C`.
///
/// `repr(C)`, fields in this order. Built by [`Raster::new`] inside the renderer's `const_new`,
/// the default layout (the lines first) made LLVM build the colour and depth lines in a
/// temporary and copy them (256 B more stack in the 16 KB part's torus frame at 64 × 64, whose
/// stack has 16 B to spare at 112 × 112); with the active list first it writes them in place.
/// Instruction counts move with this order (`scripts/mcu-bench`): the small fields first made
/// the rv32imac torus 1.4 % and the M33 shadow volumes 1.4 % dearer; the statistics and row
/// cursor right after the active list, the M0 and M33 shadow volumes 1.3–1.6 % dearer.
#[derive(Debug)]
#[repr(C)]
pub(crate) struct Raster<
    C,
    const W: usize,
    const LINES: usize,
    const ZL: usize,
    const ACTIVE: usize,
> {
    /// The triangles crossing the current row, set up (edges, planes, span kind).
    pub(crate) active: ActiveList<ACTIVE>,
    /// The strip's colour lines.
    pub(crate) color: [[C; W]; LINES],
    /// The depth lines, one per strip line (16-bit depth, 0 = nearest, 65535 = the far plane;
    /// cleared to 65535): `ZL = LINES`, or none (`ZL = 0`, [`crate::NoDepthRenderer`]).
    pub(crate) depth: [[u16; W]; ZL],
    pub(crate) depth_test: DepthTest,
    /// How a renderer without depth lines orders a row's triangles (unused with depth lines).
    pub(crate) order: DrawOrder,
    pub(crate) dither: bool,
    /// The renderer's overflow policy. The strip pass does not read it (the driver and the
    /// geometry stage do): here it takes the byte the three settings above leave before
    /// `next_row`, where in the renderer it made a padded tail of its own (4 B more on a
    /// 32-bit core).
    pub(crate) overflow: OverflowPolicy,
    /// Next row to rasterize (the viewport's height when no frame is prepared).
    pub(crate) next_row: usize,
    /// The prepared frame's background, quantized to `C`.
    pub(crate) background: C,
    /// The prepared frame's statistics: the geometry stage's counts, then each strip's.
    pub(crate) stats: Stats,
    /// Under [`crate::OverflowPolicy::DrawWhatFits`]: the triangles dropped from a full active
    /// list so far in the prepared frame (0..=`u32::MAX`, saturating).
    pub(crate) active_skipped: u32,
}

impl<C: Copy, const W: usize, const LINES: usize, const ZL: usize, const ACTIVE: usize>
    Raster<C, W, LINES, ZL, ACTIVE>
{
    /// The lines filled with `fill`, no frame prepared (`next_row` = `rows`, the viewport's
    /// height), default settings.
    pub(crate) const fn new(fill: C, rows: usize) -> Self {
        Raster {
            active: ActiveList::new(),
            color: [[fill; W]; LINES],
            depth: [[u16::MAX; W]; ZL],
            depth_test: DepthTest::Less,
            order: DrawOrder::FarToNear,
            dither: false,
            overflow: OverflowPolicy::Error,
            next_row: rows,
            background: fill,
            stats: Stats::ZERO,
            active_skipped: 0,
        }
    }
}

impl<C: TargetColor, const W: usize, const LINES: usize, const ZL: usize, const ACTIVE: usize>
    Raster<C, W, LINES, ZL, ACTIVE>
{
    /// How the strip pass (and [`crate::frame::Frame::seek_row`]) sets up a triangle, and
    /// whether it keeps the painter's order. Without depth lines every triangle is set up as
    /// for `Less` (its fast spans then skip the test).
    pub(crate) fn setup_mode(&self) -> (SpanMode, bool) {
        let test = if ZL == 0 {
            DepthTest::Less
        } else {
            self.depth_test
        };
        let painter = ZL == 0 && self.order == DrawOrder::FarToNear;
        (SpanMode::new::<C>(test, self.dither), painter)
    }
}
