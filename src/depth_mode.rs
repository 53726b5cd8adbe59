//! Depth only where a scene needs it: a renderer without depth lines ([`NoDepthRenderer`],
//! `ZL = 0`), which draws every fragment of the triangles left after back-face culling in one
//! of two orders ([`DrawOrder`]): any order (one closed convex object, whose front faces never
//! overlap) or the painter's, farthest first (objects that do not interpenetrate).
//!
//! Without depth lines the strip pass stores no depth, reads none and compares none: the RAM of
//! `LINES · W` 16-bit depths and the per-pixel test disappear. The painter's order costs a
//! sort instead: a triangle is placed among the row's active triangles by its key when it
//! starts (a move of the records behind it) and taken out in place when it ends, so that every
//! row draws its triangles farthest first; per triangle, not per pixel.

use crate::kernel::records::{ActiveList, ScreenVertex, TriRecord};
use crate::renderer::Renderer;
use crate::scalar::Scalar;
use crate::TargetColor;

/// The order in which a renderer without depth lines ([`NoDepthRenderer`]) draws the
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

/// A [`Renderer`] without depth lines: `LINES · W · 2` bytes less RAM and no per-pixel depth
/// test, for scenes that do not need one ([`DrawOrder`]). It draws flat and Gouraud
/// triangles (no texture or Phong stores: `XV = XA = 0`) and no layered effects (shadows,
/// outlines, translucency need the depth lines: [`crate::Error::NoDepthLines`]).
///
/// ```
/// # use embedded_graphics::pixelcolor::Rgb565;
/// # use scanline3d::prelude::*;
/// # use scanline3d::{DrawOrder, NoDepthRenderer};
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// type Z = Renderer<Q, Rgb565, 240, 240, 64, 64, 16>;
/// type P = NoDepthRenderer<Q, Rgb565, 240, 240, 64, 64, 16>;
/// assert_eq!(P::RAM_BYTES, Z::RAM_BYTES - 240 * 2);
/// let mut painter = P::new();
/// assert_eq!(painter.order(), DrawOrder::FarToNear);
/// painter.set_order(DrawOrder::Any); // one closed convex object
/// ```
pub type NoDepthRenderer<
    S,
    C,
    const W: usize,
    const H: usize,
    const VERTS: usize,
    const TRIS: usize,
    const ACTIVE: usize,
    const LINES: usize = 1,
> = Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, 0, 0, 0>;

impl<
        S: Scalar,
        C: TargetColor,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, 0, 0, 0>
{
    /// The order of the triangles of a row (default [`DrawOrder::FarToNear`]).
    #[must_use]
    pub fn order(&self) -> DrawOrder {
        self.order
    }

    /// Sets the order of the triangles of a row; it applies from the next prepared frame.
    pub fn set_order(&mut self, order: DrawOrder) {
        self.order = order;
    }

    /// [`Self::set_order`] on a renderer by value.
    #[must_use]
    pub fn with_order(mut self, order: DrawOrder) -> Self {
        self.order = order;
        self
    }
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
