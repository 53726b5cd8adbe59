//! Depth only where a scene needs it: a renderer without depth lines ([`crate::NoDepthRenderer`],
//! `ZL = 0`), which draws every fragment of the triangles left after back-face culling in one
//! of two orders ([`DrawOrder`]): any order (one closed convex object, whose front faces never
//! overlap) or the painter's, farthest first (objects that do not interpenetrate).
//!
//! Without depth lines the strip pass stores no depth, reads none and compares none: the RAM of
//! `LINES · W` 16-bit depths and the per-pixel test disappear. The painter's order costs a
//! sort instead, per triangle, not per pixel: a triangle is placed by its key among the row's
//! active triangles when it starts and taken out when it ends, so that every row draws its
//! triangles farthest first. The order is a list of active-list slots kept in the renderer's
//! row-count array (`starts`, free during the strip pass: no RAM of its own) when `ACTIVE ≤ H`;
//! otherwise the active records themselves are kept in order (a move of the records behind an
//! insertion or removal: dearer).

use crate::kernel::records::{ActiveList, ScreenVertex, TriRecord};
use crate::raster::kind::draw_row;
use crate::raster::span::NONE;
use crate::raster::span_map::NoMap;
use crate::raster::DepthTest;
use crate::scene::color::TargetColor;

/// The order in which a renderer without depth lines ([`crate::NoDepthRenderer`]) draws the
/// triangles that cross a row. Neither compares depths per pixel; where two front-facing
/// triangles overlap, the one drawn last is seen.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
pub enum DrawOrder {
    /// The painter's algorithm, per row: farthest triangle first, by its farthest vertex's
    /// depth (16-bit, ties in submission order). Right for triangles that do not
    /// interpenetrate and whose depth ranges do not interleave where they overlap; wrong for
    /// interpenetrating ones (the one whose far end is farther is drawn under the other
    /// entirely), which is why the Z-buffer is the default.
    #[default]
    FarToNear,
    /// Whatever order the rows hold them in: right only when no two drawn triangles overlap,
    /// i.e. one closed convex object after back-face culling. No sorting at all.
    Any,
}

/// Sets up a row's newly active triangle (slot `active.len() − 1`, just pushed) for the
/// painter's order: its key `key`, and its place in `ord` (the order of the slots, `ACTIVE ≤
/// H`) or, with `ord` `None`, among the records.
pub(crate) fn painter_insert<const N: usize>(
    active: &mut ActiveList<N>,
    ord: Option<&mut [i16]>,
    key: u16,
) {
    let Some(ord) = ord else {
        active.sort_in_last(key);
        return;
    };
    let n = active.len();
    active.get_mut(n - 1).spare = key as i16;
    // After every slot of key ≥ `key`: from the end, past the nearer ones.
    let mut at = n - 1;
    while at > 0 && (active.get_mut(ord[at - 1] as usize).spare as u16) < key {
        ord[at] = ord[at - 1];
        at -= 1;
    }
    ord[at] = (n - 1) as i16;
}

/// Draws row `row` of every active triangle into `colors` without depth lines, in the
/// painter's order (`ord`, or the records' order) or in the list's order, and takes out the
/// triangles whose last row it was. Returns (fragments, pixels written) added up.
pub(crate) fn draw_row_no_depth<C: TargetColor, const N: usize>(
    active: &mut ActiveList<N>,
    ord: Option<&mut [i16]>,
    painter: bool,
    row: usize,
    colors: &mut [C],
    dither: bool,
) -> (u32, u32) {
    let mut sum = (0, 0);
    let mut i = 0;
    match ord {
        Some(ord) if painter => {
            while i < active.len() {
                let slot = ord[i] as usize;
                let (f, w, done) = draw_row::<C, NONE, false, NoMap>(
                    active.get_mut(slot),
                    &mut [],
                    row as i32,
                    colors,
                    &mut [],
                    DepthTest::Always,
                    dither,
                    NoMap,
                );
                sum = (sum.0 + f, sum.1 + w);
                if !done {
                    i += 1;
                    continue;
                }
                // The last slot moves into the freed one: rename it in the order, then close
                // the order's gap.
                let last = active.len() - 1;
                active.swap_remove(slot);
                if slot != last {
                    if let Some(k) = ord[..=last].iter().position(|&s| s as usize == last) {
                        ord[k] = slot as i16;
                    }
                }
                ord.copy_within(i + 1..=last, i);
            }
        }
        _ => {
            while i < active.len() {
                let (f, w, done) = draw_row::<C, NONE, false, NoMap>(
                    active.get_mut(i),
                    &mut [],
                    row as i32,
                    colors,
                    &mut [],
                    DepthTest::Always,
                    dither,
                    NoMap,
                );
                sum = (sum.0 + f, sum.1 + w);
                match (done, painter) {
                    (false, _) => i += 1,
                    (true, true) => active.remove_in_order(i),
                    (true, false) => active.swap_remove(i),
                }
            }
        }
    }
    sum
}

/// A triangle's painter's key: the depth of its farthest vertex (16-bit, larger is farther).
#[inline]
pub(crate) fn painter_key(rec: &TriRecord, verts: &[ScreenVertex]) -> u16 {
    let [a, b, c] = rec.indices();
    verts[a].z.max(verts[b].z).max(verts[c].z)
}

impl<const N: usize> ActiveList<N> {
    /// Moves the last entry (just set up) among the others so that the list stays ordered by
    /// key, largest (farthest) first, after the entries of equal key; `key` is kept in its
    /// record's spare field.
    pub(crate) fn sort_in_last(&mut self, key: u16) {
        let n = self.len();
        let slots = &mut self.slots[..n];
        slots[n - 1].spare = key as i16;
        let mut at = n - 1;
        while at > 0 && (slots[at - 1].spare as u16) < key {
            at -= 1;
        }
        slots[at..].rotate_right(1);
    }
}
