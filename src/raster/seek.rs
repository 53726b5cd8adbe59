//! Starting a strip pass at any row with exactly the state a whole frame's pass has there, so
//! that the strips drawn from that row on are bit for bit those of the whole frame: the seam
//! that lets two renderers or cores split one prepared frame's rows.
//!
//! A whole frame's pass sets each triangle up at its first row and steps it down row by row
//! (the colour and depth rows by additions, whose roundings a setup at a later row would not
//! repeat), and its active list's order (which decides ties under the depth test) comes from
//! the pushes and swap-removals of every row above. The seek replays that history without
//! drawing: triangles that end above the row keep a place in the list only as long as they
//! would (a record with their last row; a textured one is set up and attached, so that the
//! attribute pool fills as it would), and those that cross the row are set up at their first
//! row and stepped to it (the steps between the rows where the short edge takes over jumped at
//! once, exactly: [`crate::raster::ActiveTri::advance_to`]). Costs one setup and a few jumps
//! for each triangle that crosses the row (and a setup for each textured one above it), and a
//! look at the vertices of every triangle that starts above it.

use crate::geometry::pool::{ActiveExtra, FREE};
use crate::geometry::vertex_extra::VertexExtra;
use crate::kernel::records::{first_pixel, ActiveList, ScreenVertex, TriRecord};
use crate::raster::depth_mode::{painter_insert, painter_key};
use crate::raster::kind::{enter, needs_pool};
use crate::raster::span_map::SpanMap;
use crate::raster::SpanMode;
use crate::scene::color::TargetColor;

/// What the seek reads of a prepared frame: the vertex store and its attribute store, the
/// triangles sorted by first row, the row buckets, the viewport's height.
#[derive(Clone, Copy)]
pub(crate) struct Rows<'a> {
    pub(crate) verts: &'a [ScreenVertex],
    pub(crate) xverts: &'a [VertexExtra],
    pub(crate) tris: &'a [TriRecord],
    pub(crate) heads: &'a [u16],
    pub(crate) vh: usize,
}

impl Rows<'_> {
    /// The triangles (indices into `tris`) whose first row is `row` (`row < vh`).
    fn bucket(&self, row: usize) -> core::ops::Range<usize> {
        let end = if row + 1 < self.vh {
            self.heads[row + 1] as usize
        } else {
            self.tris.len()
        };
        self.heads[row] as usize..end
    }
}

/// The first row triangle `t` does not cover (clamped to `height`), or `None` when a setup at
/// `row` would keep nothing ([`crate::raster::ActiveTri::setup`]'s two refusals: no row left
/// from `row` on, or a zero area).
fn row_end(t: &TriRecord, verts: &[ScreenVertex], row: i32, height: i32) -> Option<i32> {
    let [i, j, k] = t.indices();
    let (a, b, c) = (&verts[i], &verts[j], &verts[k]);
    let end = first_pixel(a.y.max(b.y).max(c.y) as i32).min(height);
    let (dx1, dy1) = (b.x as i32 - a.x as i32, b.y as i32 - a.y as i32);
    let (dx2, dy2) = (c.x as i32 - a.x as i32, c.y as i32 - a.y as i32);
    // |d| ≤ 32 766 each, as in the setup: 2·32 766² < 2³¹. Zero in any vertex order.
    (row < end && dx1 * dy2 != dx2 * dy1).then_some(end)
}

/// Fills `active` (empty; `pool` without triangle entries) with the strip pass's state at
/// `row` (`row < rows.vh`): the list a whole frame's pass holds when it reaches `row`, in the
/// same order, each triangle stepped to `row` exactly. `ord` is the painter's order's slot
/// list when the renderer keeps one ([`painter_insert`]); `painter` whether it keeps the
/// painter's order at all; `dither` whether the strip dithers (the rows left to the Cortex-M
/// row routine depend on it). Returns the triangles that cross `row` and found no room (only
/// under [`crate::OverflowPolicy::DrawWhatFits`]: the frame's needs were checked otherwise).
/// `XA`: the pool's capacity, as a constant, so that a renderer without attribute stores
/// compiles the seek without the textured and Phong set-up (the strip pass's rows do the same).
/// Always inlined, as it was into `StripPass::begin` when that method held it: there its caller's
/// constants (no depth lines, so no painter's order) drop what the frame cannot need; out of
/// line it kept 2.1 KB in the Pico firmware's RAM code.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn seek<C: TargetColor, const N: usize, const XA: usize, M: SpanMap>(
    active: &mut ActiveList<N>,
    pool: &mut [ActiveExtra],
    ord: Option<&mut [i16]>,
    rows: Rows<'_>,
    row: usize,
    mode: SpanMode,
    painter: bool,
    dither: bool,
    map: M,
) -> u32 {
    let h = rows.vh as i32;
    let target = row as i32;
    let mut skipped = 0u32;
    // The first row a listed triangle ends before (its `row_end`): rows above it remove
    // nothing, so the list is looked through only on rows where a triangle ends.
    let mut next_end = i32::MAX;
    for b in 0..row {
        for t in rows.bucket(b) {
            let rec = &rows.tris[t];
            let Some(end) = row_end(rec, rows.verts, b as i32, h) else {
                continue;
            };
            let crosses = end > target;
            let pooled = XA > 0 && !pool.is_empty() && needs_pool(rec, rows.xverts);
            let before = active.len();
            let kept = if crosses || pooled {
                enter::<C, N, M>(
                    pooled,
                    active,
                    pool,
                    rec,
                    rows.verts,
                    rows.xverts,
                    b as i32,
                    h,
                    mode,
                    map,
                    |a| {
                        if crosses {
                            a.advance_to(b as i32, target);
                            a.set_routine_rows(target, dither && C::can_dither());
                        }
                    },
                )
            } else {
                // Only its place in the list until its last row: nothing of it is drawn.
                active.push_with(|a| {
                    a.row_end = end as i16;
                    a.flags = 0;
                    true
                })
            };
            if active.len() > before {
                next_end = next_end.min(end);
            }
            if !kept {
                skipped += u32::from(crosses);
            } else if painter && active.len() > before {
                // Its submission order, for the painter's order below (no textured triangle
                // without depth lines, so `spare` is free).
                active.get_mut(before).spare = t as i16;
            }
        }
        // The row's end: the triangles whose last row it was leave the list as in the row
        // loop (a textured one frees its pool entry).
        if next_end > b as i32 + 1 {
            continue;
        }
        next_end = i32::MAX;
        let mut i = 0;
        while i < active.len() {
            let a = active.get_mut(i);
            if a.row_end as i32 > b as i32 + 1 {
                next_end = next_end.min(a.row_end as i32);
                i += 1;
                continue;
            }
            if a.has_pool_entry() {
                if let Some(e) = pool.get_mut(a.spare as usize) {
                    e.kind = FREE;
                }
            }
            active.swap_remove(i);
        }
    }
    if painter {
        order_painter(active, ord, rows);
    }
    skipped
}

/// Puts the list (each entry's `spare` its triangle's index) in the painter's order a whole
/// frame's pass has: farthest key first, equal keys in submission order, which is the
/// triangles' order (their insertions in [`painter_insert`] or `sort_in_last` keep exactly
/// this order, and removals keep the order of the rest).
fn order_painter<const N: usize>(
    active: &mut ActiveList<N>,
    ord: Option<&mut [i16]>,
    rows: Rows<'_>,
) {
    let n = active.len();
    // Submission order first (an insertion sort of the records: a seek's cost, not a row's).
    for k in 1..n {
        let mut at = k;
        while at > 0 && active.slots[at - 1].spare > active.slots[at].spare {
            active.slots.swap(at - 1, at);
            at -= 1;
        }
    }
    // Then each inserted as the pass inserts it.
    let mut ord = ord;
    for k in 0..n {
        let t = active.slots[k].spare as usize;
        let key = painter_key(&rows.tris[t], rows.verts);
        active.set_len(k + 1);
        match ord.as_deref_mut() {
            Some(o) => painter_insert(active, Some(o), key),
            None => active.sort_in_last(key),
        }
    }
    active.set_len(n);
}
