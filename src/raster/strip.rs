//! The strip pass and its output: each strip of `LINES` lines cleared, the triangles that
//! start on its rows set up, every active triangle's row drawn (the row kernel where it runs),
//! an overlay composed, and the finished lines handed to the target with one
//! `fill_contiguous` (or written as big-endian bytes for a DMA buffer).

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

use crate::raster::depth_mode::{draw_row_no_depth, painter_insert, painter_key};
use crate::raster::kind::{draw_row, enter};
use crate::raster::seek::Rows;
use crate::raster::span::LESS;
use crate::raster::span_map::{NoMap, SpanMap};
use crate::raster::{ActiveList, SpanMode};
use crate::scene::color::{rgb565_word, rgb565_words_mut, TargetColor};

use crate::geometry::stores::Stores;
use crate::kernel;
use crate::raster::state::Raster;
use crate::stats::*;

/// The strip being rendered, as a draw target covering the whole `W × H` screen: pixels outside
/// the strip's rows are ignored. A frame's overlay ([`crate::FrameOptions::overlay`]) draws into
/// it after the 3D content of each strip is drawn and before the strip goes to its sink, so
/// that text or a HUD is composed into the lines instead of being drawn over the finished
/// frame (no flicker on a display without a framebuffer).
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

    /// Clipped to the strip first: a rectangle of any size (a stroke two billion pixels wide)
    /// costs only the pixels it has on the strip's rows.
    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        if let Some((rows, cols)) = self.clip(area) {
            for line in &mut self.lines[rows] {
                line[cols.clone()].fill(color);
            }
        }
        Ok(())
    }

    /// Clipped to the strip first: the colours of the rows above the strip are skipped with
    /// `nth`, the rows below are never read, and an area that misses the strip reads none.
    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = C>,
    {
        let Some((rows, cols)) = self.clip(area) else {
            return Ok(());
        };
        // Offsets within `area`, in u64: the area may be up to 2³² px on a side.
        let (ax, ay) = (i64::from(area.top_left.x), i64::from(area.top_left.y));
        let width = u64::from(area.size.width);
        let mut colors = colors.into_iter();
        // The colour index `colors` is at.
        let mut at = 0u64;
        for r in rows {
            let y = (self.y0 + r) as i64;
            let row_start = (y - ay) as u64 * width;
            let first = row_start + (cols.start as i64 - ax) as u64;
            // Skip to the row's first visible colour (usize steps: a skip longer than
            // usize::MAX on a 32-bit core is done in pieces).
            let mut skip = first - at;
            while skip > 0 {
                let step = skip.min(usize::MAX as u64);
                if step > 0 && colors.nth(step as usize - 1).is_none() {
                    return Ok(());
                }
                skip -= step;
            }
            at = first;
            for x in cols.clone() {
                let Some(c) = colors.next() else {
                    return Ok(());
                };
                self.lines[r][x] = c;
                at += 1;
            }
        }
        Ok(())
    }
}

impl<'a, C, const W: usize> StripCanvas<'a, C, W> {
    /// The strip `lines`, whose first row is screen row `y0`, on a screen `height` rows high.
    pub(crate) fn new(lines: &'a mut [[C; W]], y0: usize, height: u32) -> Self {
        StripCanvas { lines, y0, height }
    }

    /// The strip's lines and columns `area` covers, or `None` if it covers none of them.
    fn clip(&self, area: &Rectangle) -> Option<(core::ops::Range<usize>, core::ops::Range<usize>)> {
        let (x0, y0) = (i64::from(area.top_left.x), i64::from(area.top_left.y));
        let (x1, y1) = (
            x0 + i64::from(area.size.width),
            y0 + i64::from(area.size.height),
        );
        let (sy0, sy1) = (self.y0 as i64, (self.y0 + self.lines.len()) as i64);
        let (cx0, cx1) = (x0.max(0), x1.min(W as i64));
        let (cy0, cy1) = (y0.max(sy0), y1.min(sy1));
        if cx0 >= cx1 || cy0 >= cy1 {
            return None;
        }
        Some((
            (cy0 - sy0) as usize..(cy1 - sy0) as usize,
            cx0 as usize..cx1 as usize,
        ))
    }
}

impl<C: TargetColor, const W: usize, const LINES: usize, const ZL: usize, const ACTIVE: usize>
    Raster<C, W, LINES, ZL, ACTIVE>
{
    /// Rasterizes the next strip of the prepared frame, at most `limit` rows, into `ext` (the
    /// caller's lines) or, for `None`, into the renderer's own lines. Returns its first row and
    /// height, or `None` when the frame is complete. `CLEAR`: each line is cleared to the
    /// background (colour) and the far plane (depth) first; without it the frame is drawn over
    /// what the lines hold ([`crate::Renderer::render_passes`]; a constant, so the strip routines of
    /// a frame compile as they did without the option).
    #[allow(clippy::type_complexity)]
    pub(crate) fn draw_strip<
        S,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
        P: Probe,
        const CLEAR: bool,
    >(
        &mut self,
        geo: &mut Stores<S, C, H, VERTS, TRIS, XV, XA>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        self.draw_strip_with::<S, H, VERTS, TRIS, XV, XA, P, CLEAR, NoMap>(
            geo, ext, limit, probe, NoMap,
        )
    }

    /// [`Raster::draw_strip`] with the frame's shadow map context `map` ([`SpanMap`]).
    #[allow(clippy::type_complexity)]
    #[inline(always)]
    pub(crate) fn draw_strip_with<
        S,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
        P: Probe,
        const CLEAR: bool,
        M: SpanMap,
    >(
        &mut self,
        geo: &mut Stores<S, C, H, VERTS, TRIS, XV, XA>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
        map: M,
    ) -> Option<(usize, usize)> {
        if self.next_row >= geo.vh {
            return None;
        }
        let (mode, painter) = self.setup_mode();
        let Raster {
            active,
            color,
            depth,
            depth_test,
            dither,
            background,
            stats,
            active_skipped,
            next_row,
            ..
        } = self;
        let Stores {
            verts,
            xverts,
            xactive,
            tris,
            heads,
            starts,
            vw,
            vh,
            ..
        } = geo;
        let frame = FrameView {
            rows: Rows {
                verts,
                xverts,
                tris,
                heads,
                vh: *vh,
            },
            vw: *vw,
            background: *background,
            depth_test: *depth_test,
            dither: *dither,
            mode,
            painter,
            map,
        };
        let pass = PassMut {
            active,
            pool: xactive,
            ord: (ACTIVE <= H).then_some(&mut starts[..]),
            depth,
            next_row,
            end_row: usize::MAX,
            stats,
            skipped: active_skipped,
        };
        let lines = match ext {
            Some(lines) => lines,
            None => color.as_mut_slice(),
        };
        strip_rows::<C, P, W, ACTIVE, LINES, XV, XA, ZL, CLEAR, M>(frame, pass, lines, limit, probe)
    }

    /// What a strip pass reads of the frame prepared in `geo`.
    pub(crate) fn view<
        'a,
        S,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
    >(
        &self,
        geo: &'a Stores<S, C, H, VERTS, TRIS, XV, XA>,
    ) -> FrameView<'a, C> {
        let (mode, painter) = self.setup_mode();
        FrameView {
            rows: Rows {
                verts: &geo.verts,
                xverts: &geo.xverts,
                tris: &geo.tris,
                heads: &geo.heads,
                vh: geo.vh,
            },
            vw: geo.vw,
            background: self.background,
            depth_test: self.depth_test,
            dither: self.dither,
            mode,
            painter,
            map: NoMap,
        }
    }
}

/// What a strip pass reads of a prepared frame (shared by every pass of it): its rows (the
/// vertex and attribute stores, triangles and buckets), the viewport's width, the background,
/// how triangles are set up and drawn, and its shadow map context ([`SpanMap`]; [`NoMap`]
/// for a frame without one).
#[derive(Clone, Copy)]
pub(crate) struct FrameView<'a, C, M: SpanMap = NoMap> {
    pub(crate) rows: Rows<'a>,
    pub(crate) vw: usize,
    pub(crate) background: C,
    pub(crate) depth_test: crate::raster::DepthTest,
    pub(crate) dither: bool,
    pub(crate) mode: SpanMode,
    pub(crate) painter: bool,
    pub(crate) map: M,
}

/// A strip pass's own state, borrowed from a renderer or a [`crate::StripPass`]: the active
/// list, the attribute pool (the frame's lights and materials and the triangles' entries),
/// the painter's slot order where it is kept (`ord`), the depth lines, the next row and the
/// row it stops before, and its counts.
pub(crate) struct PassMut<'a, const W: usize, const ACTIVE: usize, const ZL: usize> {
    pub(crate) active: &'a mut ActiveList<ACTIVE>,
    pub(crate) pool: &'a mut [crate::geometry::pool::ActiveExtra],
    pub(crate) ord: Option<&'a mut [i16]>,
    /// The depth lines as an array, as the renderer held them before the pass had this type
    /// (a constant length for the row loop's indexing; whether a slice would cost more was
    /// not measured apart: the torus row on rv32imac was the same either way).
    pub(crate) depth: &'a mut [[u16; W]; ZL],
    pub(crate) next_row: &'a mut usize,
    pub(crate) end_row: usize,
    pub(crate) stats: &'a mut Stats,
    pub(crate) skipped: &'a mut u32,
}

/// The strip pass: rasterizes the next strip of `frame` for `pass`, at most `limit` rows and
/// as many as `color` has lines (at most `LINES`), stopping before `pass.end_row`. Returns its
/// first row and height, or `None` when no row is left. `CLEAR`: see
/// [`crate::Renderer::draw_strip`]. (`XV`, `XA`, `ZL`: the renderer's stores and depth lines, as
/// constants, so that a renderer without them compiles the pass without their tests.)
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn strip_rows<
    C: TargetColor,
    P: Probe,
    const W: usize,
    const ACTIVE: usize,
    const LINES: usize,
    const XV: usize,
    const XA: usize,
    const ZL: usize,
    const CLEAR: bool,
    M: SpanMap,
>(
    frame: FrameView<'_, C, M>,
    pass: PassMut<'_, W, ACTIVE, ZL>,
    color: &mut [[C; W]],
    limit: usize,
    probe: &mut P,
) -> Option<(usize, usize)> {
    let PassMut {
        active,
        pool: xactive,
        mut ord,
        depth,
        next_row,
        end_row,
        stats,
        skipped,
    } = pass;
    let FrameView {
        rows:
            Rows {
                verts,
                xverts,
                tris,
                heads,
                vh,
            },
        vw,
        background,
        depth_test,
        dither,
        mode,
        painter,
        map,
    } = frame;
    let y0 = *next_row;
    let stop = vh.min(end_row);
    if y0 >= stop {
        return None;
    }
    let lines = LINES.min(limit).min(color.len()).min(stop - y0);
    for l in 0..lines {
        if CLEAR && ZL == 0 {
            color[l][..vw].fill(background);
        } else if CLEAR {
            match (
                rgb565_words_mut(&mut color[l][..vw]),
                rgb565_word(background),
            ) {
                (Some(words), Some(bg)) => kernel::clear_line565(words, &mut depth[l][..vw], bg),
                _ => {
                    color[l][..vw].fill(background);
                    depth[l][..vw].fill(u16::MAX);
                }
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
            let before = active.len();
            // Full only under `OverflowPolicy::DrawWhatFits` (the largest number of rows'
            // overlaps was checked): the triangle is left out and counted. (`XV`, `XA`:
            // constant tests, so that a renderer without attribute stores compiles the
            // setup without the pool.)
            let h = vh as i32;
            if !enter::<C, ACTIVE, M>(
                XV > 0 && XA > 0,
                active,
                xactive,
                &rec,
                verts,
                xverts,
                row as i32,
                h,
                mode,
                map,
                |_| {},
            ) {
                *skipped = skipped.saturating_add(1);
            } else if painter && active.len() > before {
                painter_insert(active, ord.as_deref_mut(), painter_key(&rec, verts));
            }
        }
        probe.enter(Stage::Raster);
        if ZL == 0 {
            // No depth lines: every fragment written, in the painter's or the list's order.
            let (frag, written) = draw_row_no_depth(
                active,
                ord.as_deref_mut(),
                painter,
                row,
                &mut color[l][..vw],
                dither,
            );
            stats.add_row(frag, written);
            continue;
        }
        draw_list_row::<C, ACTIVE, XA, M>(
            active,
            xactive,
            row,
            &mut color[l][..vw],
            &mut depth[l][..vw],
            depth_test,
            dither,
            stats,
            map,
        );
    }
    *next_row = y0 + lines;
    Some((y0, lines))
}

/// Draws one row of every triangle of `active` into a strip line ([`row_loop`]), with the pool
/// kinds' arms only when the renderer has a pool (`XA > 0`), out of line then, so that the
/// strip pass of a renderer without the pool stays as small as it was. Removes the triangles
/// whose last row this was. The one row loop of every strip pass with depth lines (opaque,
/// layered).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn draw_list_row<C: TargetColor, const N: usize, const XA: usize, M: SpanMap>(
    active: &mut crate::raster::ActiveList<N>,
    pool: &mut [crate::geometry::pool::ActiveExtra],
    row: usize,
    colors: &mut [C],
    depth: &mut [u16],
    test: crate::raster::DepthTest,
    dither: bool,
    stats: &mut Stats,
    map: M,
) {
    if XA > 0 {
        draw_row_pooled(active, pool, row, colors, depth, test, dither, stats, map);
    } else {
        row_loop::<C, N, false, M>(active, pool, row, colors, depth, test, dither, stats, map);
    }
}

/// [`draw_list_row`] for a renderer with the attribute pool.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn draw_row_pooled<C: TargetColor, const N: usize, M: SpanMap>(
    active: &mut crate::raster::ActiveList<N>,
    pool: &mut [crate::geometry::pool::ActiveExtra],
    row: usize,
    colors: &mut [C],
    depth: &mut [u16],
    test: crate::raster::DepthTest,
    dither: bool,
    stats: &mut Stats,
    map: M,
) {
    row_loop::<C, N, true, M>(active, pool, row, colors, depth, test, dither, stats, map);
}

/// The row loop: the row kernel, then each active triangle's row by its kind
/// ([`draw_row`]; `POOLED`: with the pool kinds' arms).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn row_loop<C: TargetColor, const N: usize, const POOLED: bool, M: SpanMap>(
    active: &mut crate::raster::ActiveList<N>,
    pool: &mut [crate::geometry::pool::ActiveExtra],
    row: usize,
    colors: &mut [C],
    depth: &mut [u16],
    test: crate::raster::DepthTest,
    dither: bool,
    stats: &mut Stats,
    map: M,
) {
    let mut i = 0;
    loop {
        if let Some(words) = rgb565_words_mut(colors) {
            if let Some((next, frag, written)) =
                kernel::rows565(active, i, words, depth, row, dither)
            {
                stats.add_row(frag, written);
                i = next;
            }
        }
        if i >= active.len() {
            break;
        }
        let (frag, written, done) = draw_row::<C, LESS, POOLED, M>(
            active.get_mut(i),
            pool,
            row as i32,
            colors,
            depth,
            test,
            dither,
            map,
        );
        stats.add_row(frag, written);
        if done {
            active.swap_remove(i);
        } else {
            i += 1;
        }
    }
}
