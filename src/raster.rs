//! Scan conversion: exact integer edge stepping, attribute setup, and the span loop.
//!
//! Coverage rule: pixel `(px, py)` is covered when its centre `(16·px + 8, 16·py + 8)` (in
//! subpixels) lies inside the triangle, with the **top-left rule** on the boundary: a centre
//! exactly on a left or top edge is covered, one on a right or bottom edge is not. Rows are the
//! half-open range `Ytop ≤ Ys < Ybottom`; in a row the span is `x_left ≤ Xs < x_right`, so both
//! ends are `ceil((x − 8) / 16)` of the exact edge crossing `x`.
//!
//! Each edge keeps that ceiling as an integer plus an exact remainder (a Bresenham-style DDA):
//! stepping one row is two additions and a compare, and the value is exact at every row, so an
//! edge shared by two triangles yields the same pixel boundary in both — no gaps, no pixel twice.
//!
//! Depth and colour are planes `A(x, y) = A₀ + gx·(x − x₀) + gy·(y − y₀)`.
//!
//! Cost per triangle: one division for a normalized reciprocal of its area (every gradient is
//! then a multiply), and one division-with-remainder per edge for its start and one for its
//! step (32-bit whenever the values fit, which is the case for on-screen triangles below
//! ~1000 px), i.e. at most seven divisions. Per row: one or two additions per edge and one
//! per attribute. Per pixel: one addition per attribute, a shift, a compare and stores.

use crate::color::{TargetColor, BAYER};
use crate::project::{ScreenVertex, DEPTH_FRAC_BITS, DEPTH_MAX, SUBPIXELS};

/// Fraction bits of interpolated colour channels (channel units, so 0..=255·2²⁰ < 2²⁸ fits an
/// `i32`; step 2⁻²⁰ of a channel unit).
pub const COLOR_FRAC_BITS: u32 = 20;
/// Vertex colours are stored with 8 fraction bits; this shift brings them to
/// [`COLOR_FRAC_BITS`].
const COLOR_SHIFT: u32 = COLOR_FRAC_BITS - 8;
/// Largest magnitude of a gradient (per pixel), to keep spans in `i32`.
const GRAD_LIMIT: i64 = 1 << 30;

/// The comparison a fragment's depth must pass against the stored depth (0 = nearest).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
pub enum DepthTest {
    /// Nearer than what is stored (the first of equal depths wins). Lines are cleared to the
    /// far plane (65535), so a fragment exactly at the far plane is not drawn, as in OpenGL.
    #[default]
    Less,
    /// Nearer or equal (the last of equal depths wins).
    LessEqual,
    /// Exactly equal (for repeatability tests and decals).
    Equal,
    /// Always pass (painter's order).
    Always,
}

/// `ceil(n / d)` for `d > 0`.
#[inline]
pub(crate) fn ceil_div(n: i64, d: i64) -> i64 {
    let q = n.div_euclid(d);
    if q * d == n {
        q
    } else {
        q + 1
    }
}

/// First pixel index whose centre is at or right of (below) the subpixel coordinate `v`:
/// `ceil((v − 8) / 16)`, which for a power of two is `(v − 8 + 15) >> 4` (arithmetic shift =
/// floor), exact for every `v` in the coordinate range.
#[inline(always)]
pub(crate) fn first_pixel(v: i32) -> i32 {
    (v - SUBPIXELS / 2 + (SUBPIXELS - 1)) >> crate::project::SUBPIXEL_BITS
}

/// A normalized reciprocal `1/d ≈ ±m · 2^-e` with `m` in (2³⁰, 2³¹]: computed with **one**
/// division per triangle, after which every attribute gradient is a multiply.
#[derive(Copy, Clone, Debug)]
struct Reciprocal {
    m: i64,
    e: u32,
    neg: bool,
}

impl Reciprocal {
    /// `d ≠ 0`, `|d| < 2⁶²`.
    fn new(d: i64) -> Self {
        let a = d.unsigned_abs().max(1);
        let s = 64 - a.leading_zeros(); // a in [2^(s-1), 2^s)
        let sh = s.saturating_sub(32); // keep 32 significant bits of d
        let a2 = a >> sh;
        let s2 = s - sh;
        // 2^(s2+30) / a2 in (2^30, 2^31]; s2 + 30 ≤ 62.
        let m = (1u64 << (s2 + 30)) / a2;
        Reciprocal {
            m: m as i64,
            e: s2 + 30 + sh,
            neg: d < 0,
        }
    }

    /// `round(n / d)` to within 2⁻²⁹ relative, clamped to ±[`GRAD_LIMIT`].
    fn div(&self, n: i64) -> i64 {
        let a = n.unsigned_abs();
        let nb = 64 - a.leading_zeros();
        let shn = nb.saturating_sub(31); // keep 31 significant bits of n
        let p = (a >> shn) as i64 * self.m; // < 2^62
        let e = self.e as i64 - shn as i64;
        let q = if e <= 0 {
            GRAD_LIMIT
        } else if e >= 63 {
            0
        } else {
            ((p >> (e - 1)) + 1) >> 1
        };
        let q = q.min(GRAD_LIMIT);
        if (n < 0) != self.neg {
            -q
        } else {
            q
        }
    }
}

/// `(floor(n / d), n mod d)` for `d > 0`, in 32 bits when both fit (the usual case on screen).
#[inline]
fn div_floor(n: i64, d: i64) -> (i64, i64) {
    if let (Ok(n32), Ok(d32)) = (i32::try_from(n), i32::try_from(d)) {
        let (q, r) = (n32.div_euclid(d32), n32.rem_euclid(d32));
        (q as i64, r as i64)
    } else {
        (n.div_euclid(d), n.rem_euclid(d))
    }
}

/// One edge from its upper vertex `a` to its lower vertex `b`, positioned on a pixel row:
/// `c` is the first pixel whose centre is at or right of the edge; the exact crossing is
/// `c − e/d` (in pixels, relative to centres), with `0 ≤ e < d`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Edge {
    /// Current pixel boundary (column index).
    pub c: i32,
    /// Remainder, `0 ≤ e < d`.
    e: i32,
    /// Whole pixels the boundary moves per row (floor).
    pub sq: i32,
    /// Remainder of the move per row, `0 ≤ sr < d`.
    sr: i32,
    /// `16 · (yb − ya)`, ≤ 2²⁷.
    d: i32,
}

impl Edge {
    /// The edge `a → b` (`a.y < b.y`) at pixel row `row`. Coordinates must be within
    /// ±[`crate::project::COORD_LIMIT`] subpixels.
    pub(crate) fn new(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> Edge {
        let dy = (yb as i64 - ya as i64).max(1);
        let dx = xb as i64 - xa as i64;
        let d = SUBPIXELS as i64 * dy;
        let ys = SUBPIXELS as i64 * row as i64 + (SUBPIXELS / 2) as i64;
        // x − 8 at the sample row, times dy: |n| < 2^47.
        let n = (xa as i64 - (SUBPIXELS / 2) as i64) * dy + (ys - ya as i64) * dx;
        // c = ceil(n/d), e = c·d − n.
        let (q, r) = div_floor(n, d);
        let (c, e) = if r == 0 { (q, 0) } else { (q + 1, d - r) };
        let (sq, sr) = div_floor(SUBPIXELS as i64 * dx, d);
        Edge {
            c: c as i32,
            e: e as i32,
            sq: sq as i32,
            sr: sr as i32,
            d: d as i32,
        }
    }

    /// Moves to the next row; returns true when the boundary moved by `sq + 1` instead of `sq`.
    #[inline(always)]
    pub(crate) fn step(&mut self) -> bool {
        self.e -= self.sr;
        self.c += self.sq;
        if self.e < 0 {
            self.e += self.d;
            self.c += 1;
            true
        } else {
            false
        }
    }
}

/// One interpolated attribute of a triangle being drawn.
#[derive(Copy, Clone, Debug, Default)]
struct Attr {
    /// Value at the vertex the plane is anchored on.
    a0: i32,
    /// Per-pixel gradients, |g| ≤ 2³⁰.
    gx: i32,
    gy: i32,
    /// Value at the centre of the current row's first pixel (column `left.c`).
    row: i64,
    /// Change of `row` per row when the left edge moves by `sq` columns: `gy + gx·sq`.
    inc: i64,
}

/// A triangle as stored between geometry and rasterization (12 bytes).
#[derive(Copy, Clone, Debug)]
pub(crate) struct TriRecord {
    /// Indices into the renderer's vertex store.
    pub v: [u16; 3],
    /// Flat colour (channel units, 8.8) or `None` for Gouraud.
    pub flat: Option<[u16; 3]>,
    /// Next triangle in the same first-row bucket, or `u16::MAX`.
    pub next: u16,
}

/// A triangle on the active list.
#[derive(Clone, Debug)]
pub(crate) struct ActiveTri {
    left: Edge,
    right: Edge,
    /// Row where the short edge changes from v0→v1 to v1→v2.
    row_mid: i32,
    /// First row not covered.
    row_end: i32,
    /// v1 is left of the long edge.
    mid_left: bool,
    /// Sorted (top to bottom) vertices, kept for the switch at `row_mid`.
    v1: (i32, i32),
    v2: (i32, i32),
    x0: i32,
    y0: i32,
    /// z, r, g, b (only z for flat).
    attrs: [Attr; 4],
    n_attrs: u8,
    flat: Option<[u16; 3]>,
}

impl ActiveTri {
    /// Sets up triangle `t` starting at `row` (its first covered row, clamped to the screen).
    /// Returns `None` if it covers no row from `row` on.
    pub(crate) fn new(
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
    ) -> Option<Self> {
        let mut p = [
            verts[t.v[0] as usize],
            verts[t.v[1] as usize],
            verts[t.v[2] as usize],
        ];
        // Sort by y (stable for equal y: order does not matter, horizontal edges are unused).
        if p[1].y < p[0].y {
            p.swap(0, 1);
        }
        if p[2].y < p[1].y {
            p.swap(1, 2);
        }
        if p[1].y < p[0].y {
            p.swap(0, 1);
        }
        let [a, b, c] = p;
        let row_end = first_pixel(c.y).min(height);
        let row_mid = first_pixel(b.y);
        if row >= row_end {
            return None;
        }
        let (dx1, dy1) = (b.x as i64 - a.x as i64, b.y as i64 - a.y as i64);
        let (dx2, dy2) = (c.x as i64 - a.x as i64, c.y as i64 - a.y as i64);
        let det = dx1 * dy2 - dx2 * dy1;
        if det == 0 {
            return None;
        }
        let mid_left = det < 0;
        let long = Edge::new(a.x, a.y, c.x, c.y, row);
        let short = if row < row_mid {
            Edge::new(a.x, a.y, b.x, b.y, row)
        } else {
            Edge::new(b.x, b.y, c.x, c.y, row)
        };
        let (left, right) = if mid_left {
            (short, long)
        } else {
            (long, short)
        };

        let mut attrs = [Attr::default(); 4];
        let n_attrs = if t.flat.is_some() { 1 } else { 4 };
        let val = |v: &ScreenVertex, k: usize| -> i32 {
            if k == 0 {
                v.z
            } else {
                (v.rgb[k - 1] as i32) << COLOR_SHIFT
            }
        };
        let s = SUBPIXELS as i64;
        let inv = Reciprocal::new(det);
        for (k, at) in attrs.iter_mut().enumerate().take(n_attrs) {
            let (a0, a1, a2) = (val(&a, k), val(&b, k), val(&c, k));
            let (da1, da2) = (a1 as i64 - a0 as i64, a2 as i64 - a0 as i64);
            at.a0 = a0;
            // |da| < 2^29, |d·| < 2^24: each numerator < 2^58.
            at.gx = inv.div(s * (da1 * dy2 - da2 * dy1)) as i32;
            at.gy = inv.div(s * (dx1 * da2 - dx2 * da1)) as i32;
        }
        let mut tri = ActiveTri {
            left,
            right,
            row_mid,
            row_end,
            mid_left,
            v1: (b.x, b.y),
            v2: (c.x, c.y),
            x0: a.x,
            y0: a.y,
            attrs,
            n_attrs: n_attrs as u8,
            flat: t.flat,
        };
        tri.anchor_attrs(row);
        Some(tri)
    }

    /// Evaluates every attribute plane at the centre of pixel (`left.c`, `row`).
    fn anchor_attrs(&mut self, row: i32) {
        let s = SUBPIXELS as i64;
        let dx = s * self.left.c as i64 + s / 2 - self.x0 as i64;
        let dy = s * row as i64 + s / 2 - self.y0 as i64;
        let sq = self.left.sq as i64;
        for at in self.attrs.iter_mut().take(self.n_attrs as usize) {
            let (gx, gy) = (at.gx as i64, at.gy as i64);
            at.row = at.a0 as i64 + ((gx * dx + gy * dy) >> 4);
            at.inc = gy + gx * sq;
        }
    }

    /// Moves to `next_row` (the row after the one just drawn).
    fn advance(&mut self, next_row: i32) {
        let (long, short) = if self.mid_left {
            (&mut self.right, &mut self.left)
        } else {
            (&mut self.left, &mut self.right)
        };
        let long_carry = long.step();
        if next_row == self.row_mid {
            *short = Edge::new(self.v1.0, self.v1.1, self.v2.0, self.v2.1, next_row);
            if self.mid_left {
                self.anchor_attrs(next_row);
            } else {
                self.step_attrs(long_carry);
            }
        } else {
            let short_carry = short.step();
            self.step_attrs(if self.mid_left {
                short_carry
            } else {
                long_carry
            });
        }
    }

    #[inline(always)]
    fn step_attrs(&mut self, carry: bool) {
        for at in self.attrs.iter_mut().take(self.n_attrs as usize) {
            at.row += at.inc;
            if carry {
                at.row += at.gx as i64;
            }
        }
    }

    /// Draws this triangle's span on `row` into one line of the strip and moves to the next
    /// row. Returns `(fragments tested, pixels written, finished)`.
    pub(crate) fn draw_row<C: TargetColor>(
        &mut self,
        row: i32,
        colors: &mut [C],
        depth: &mut [u16],
        test: DepthTest,
        dither: bool,
    ) -> (u32, u32, bool) {
        let width = colors.len().min(depth.len()) as i32;
        let xs = self.left.c.max(0);
        let xe = self.right.c.min(width);
        let mut counts = (0, 0);
        if xs < xe {
            let skip = (xs - self.left.c) as i64;
            let mut start = [0i32; 4];
            let zmax = (DEPTH_MAX as i64) << DEPTH_FRAC_BITS;
            for k in 0..self.n_attrs as usize {
                let at = &self.attrs[k];
                let max = if k == 0 {
                    zmax
                } else {
                    (C::CHANNEL_MAX[k - 1] as i64) << COLOR_FRAC_BITS
                };
                let v = if skip == 0 { at.row } else { at.row + at.gx as i64 * skip };
                start[k] = v.clamp(0, max) as i32;
            }
            let span = Span {
                x0: xs as usize,
                x1: xe as usize,
                row,
                start,
                gx: [
                    self.attrs[0].gx,
                    self.attrs[1].gx,
                    self.attrs[2].gx,
                    self.attrs[3].gx,
                ],
            };
            let dither = dither && C::can_dither();
            let written = match (self.flat, test) {
                (Some(rgb), t) => {
                    let c = C::vertex_channels_done(rgb);
                    match t {
                        DepthTest::Less => span.fill_flat::<C, LESS>(colors, depth, c),
                        DepthTest::LessEqual => span.fill_flat::<C, LESS_EQUAL>(colors, depth, c),
                        DepthTest::Equal => span.fill_flat::<C, EQUAL>(colors, depth, c),
                        DepthTest::Always => span.fill_flat::<C, ALWAYS>(colors, depth, c),
                    }
                }
                (None, DepthTest::Less) => span.fill_gouraud::<C, LESS>(colors, depth, dither),
                (None, DepthTest::LessEqual) => span.fill_gouraud::<C, LESS_EQUAL>(colors, depth, dither),
                (None, DepthTest::Equal) => span.fill_gouraud::<C, EQUAL>(colors, depth, dither),
                (None, DepthTest::Always) => span.fill_gouraud::<C, ALWAYS>(colors, depth, dither),
            };
            counts = ((xe - xs) as u32, written);
        }
        let next = row + 1;
        if next >= self.row_end {
            return (counts.0, counts.1, true);
        }
        self.advance(next);
        (counts.0, counts.1, false)
    }
}

/// Extension used by the span loop: a flat colour (channel units, 8.8) rounded to a pixel.
trait FlatPixel: TargetColor {
    fn vertex_channels_done(rgb: [u16; 3]) -> Self {
        Self::from_channels([
            ((rgb[0] as u32 + 128) >> 8) as u8,
            ((rgb[1] as u32 + 128) >> 8) as u8,
            ((rgb[2] as u32 + 128) >> 8) as u8,
        ])
    }
}
impl<C: TargetColor> FlatPixel for C {}

/// One span: pixels `x0..x1` of a row, with attribute values at `x0` and per-pixel gradients.
struct Span {
    x0: usize,
    x1: usize,
    row: i32,
    /// z (16.12, clamped to 0..=65535·2¹²) and r, g, b (channel units, 20 fraction bits).
    start: [i32; 4],
    gx: [i32; 4],
}

const LESS: u8 = 0;
const LESS_EQUAL: u8 = 1;
const EQUAL: u8 = 2;
const ALWAYS: u8 = 3;

/// The depth test, resolved at compile time in each monomorphized span loop.
#[inline(always)]
fn passes<const T: u8>(z: u16, stored: u16) -> bool {
    match T {
        LESS => z < stored,
        LESS_EQUAL => z <= stored,
        EQUAL => z == stored,
        _ => true,
    }
}

impl Span {
    /// Depth with a half-step bias so that the shift rounds to nearest. Gradient rounding can
    /// overshoot the clamped range by at most ½ per pixel (< 2¹¹ over a 2048-px span), which
    /// the bias absorbs, so the shift never leaves 0..=65535.
    #[inline(always)]
    fn z_start(&self) -> i32 {
        self.start[0] + (1 << (DEPTH_FRAC_BITS - 1))
    }

    fn fill_flat<C: TargetColor, const T: u8>(&self, colors: &mut [C], depth: &mut [u16], color: C) -> u32 {
        let mut z = self.z_start();
        let gz = self.gx[0];
        let mut written = 0;
        let (zs, cs) = (&mut depth[self.x0..self.x1], &mut colors[self.x0..self.x1]);
        for (zb, cb) in zs.iter_mut().zip(cs.iter_mut()) {
            let z16 = (z >> DEPTH_FRAC_BITS) as u16;
            if passes::<T>(z16, *zb) {
                *zb = z16;
                *cb = color;
                written += 1;
            }
            z = z.wrapping_add(gz);
        }
        written
    }

    fn fill_gouraud<C: TargetColor, const T: u8>(&self, colors: &mut [C], depth: &mut [u16], dither: bool) -> u32 {
        if dither {
            self.fill_gouraud_dither::<C, T>(colors, depth)
        } else {
            self.fill_gouraud_round::<C, T>(colors, depth)
        }
    }

    /// Gouraud span, rounding to nearest: the half is folded into the start values.
    fn fill_gouraud_round<C: TargetColor, const T: u8>(&self, colors: &mut [C], depth: &mut [u16]) -> u32 {
        let half = 1i32 << (COLOR_FRAC_BITS - 1);
        let mut z = self.z_start();
        let [_, r0, g0, b0] = self.start;
        let (mut r, mut g, mut b) = (r0 + half, g0 + half, b0 + half);
        let [gz, gr, gg, gb] = self.gx;
        let mut written = 0;
        let (zs, cs) = (&mut depth[self.x0..self.x1], &mut colors[self.x0..self.x1]);
        for (zb, cb) in zs.iter_mut().zip(cs.iter_mut()) {
            let z16 = (z >> DEPTH_FRAC_BITS) as u16;
            if passes::<T>(z16, *zb) {
                *zb = z16;
                *cb = C::from_channels([
                    (r >> COLOR_FRAC_BITS) as u8,
                    (g >> COLOR_FRAC_BITS) as u8,
                    (b >> COLOR_FRAC_BITS) as u8,
                ]);
                written += 1;
            }
            z = z.wrapping_add(gz);
            r = r.wrapping_add(gr);
            g = g.wrapping_add(gg);
            b = b.wrapping_add(gb);
        }
        written
    }

    /// Gouraud span with 4×4 ordered dithering: the rounding bias is the Bayer threshold
    /// (2·B + 1)/32 of a channel unit for the pixel's column phase.
    fn fill_gouraud_dither<C: TargetColor, const T: u8>(&self, colors: &mut [C], depth: &mut [u16]) -> u32 {
        let mut bias = [0i32; 4];
        let row = &BAYER[(self.row & 3) as usize];
        for (k, t) in bias.iter_mut().enumerate() {
            *t = (2 * row[k] as i32 + 1) << (COLOR_FRAC_BITS - 5);
        }
        let mut z = self.z_start();
        let [_, mut r, mut g, mut b] = self.start;
        let [gz, gr, gg, gb] = self.gx;
        let mut written = 0;
        let (zs, cs) = (&mut depth[self.x0..self.x1], &mut colors[self.x0..self.x1]);
        for (x, (zb, cb)) in (self.x0..).zip(zs.iter_mut().zip(cs.iter_mut())) {
            let z16 = (z >> DEPTH_FRAC_BITS) as u16;
            if passes::<T>(z16, *zb) {
                let t = bias[x & 3];
                *zb = z16;
                *cb = C::from_channels([
                    ((r + t) >> COLOR_FRAC_BITS) as u8,
                    ((g + t) >> COLOR_FRAC_BITS) as u8,
                    ((b + t) >> COLOR_FRAC_BITS) as u8,
                ]);
                written += 1;
            }
            z = z.wrapping_add(gz);
            r = r.wrapping_add(gr);
            g = g.wrapping_add(gg);
            b = b.wrapping_add(gb);
        }
        written
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact reference: first pixel whose centre is at or right of the edge at `row`.
    fn reference(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> i32 {
        // x(ys) − 8 = ((xa − 8)(yb − ya) + (ys − ya)(xb − xa)) / (yb − ya); ceil of that / 16.
        let ys = 16 * row as i64 + 8;
        let n = (xa as i64 - 8) * (yb - ya) as i64 + (ys - ya as i64) * (xb - xa) as i64;
        let d = 16 * (yb - ya) as i64;
        ceil_div(n, d) as i32
    }

    #[test]
    fn edge_dda_is_exact_on_every_row() {
        let cases = [
            (0, 0, 160, 320),
            (37, 5, -501, 777),
            (8, 8, 8, 400),
            (-3000, -20, 4000, 3),
            (123, 17, 124, 1000),
            (-(1 << 21), -(1 << 21), 1 << 21, 1 << 21),
        ];
        for (xa, ya, xb, yb) in cases {
            let first = first_pixel(ya);
            let end = first_pixel(yb);
            let mut e = Edge::new(xa, ya, xb, yb, first);
            for row in first..end.min(first + 3000) {
                assert_eq!(
                    e.c,
                    reference(xa, ya, xb, yb, row),
                    "edge {xa},{ya}->{xb},{yb} row {row}"
                );
                e.step();
            }
            // Starting anywhere gives the same value.
            let mid = (first + end) / 2;
            assert_eq!(
                Edge::new(xa, ya, xb, yb, mid).c,
                reference(xa, ya, xb, yb, mid)
            );
        }
    }

    #[test]
    fn pixel_centres_on_the_boundary() {
        // Centre of pixel 3 is at 56 subpixels: an edge exactly there starts the span at 3.
        assert_eq!(first_pixel(56), 3);
        assert_eq!(first_pixel(57), 4);
        assert_eq!(first_pixel(55), 3);
        assert_eq!(first_pixel(-8), -1);
        assert_eq!(first_pixel(-7), 0);
        // Pixel −1 has its centre at −8 subpixels, pixel −2 at −24.
        assert_eq!(first_pixel(-9), -1);
        assert_eq!(first_pixel(-24), -2);
        assert_eq!(first_pixel(-23), -1);
    }

    #[test]
    fn reciprocal_division_matches_exact_rounding() {
        let dens = [
            1i64,
            -1,
            3,
            7,
            -255,
            4096,
            123_456_789,
            -(1 << 40) + 12345,
            (1 << 47) - 1,
        ];
        let nums = [
            0i64,
            1,
            -1,
            7,
            1000,
            -99_999,
            1 << 30,
            -(1 << 45) + 3,
            (1 << 57) + 12_345,
        ];
        for &d in &dens {
            let r = Reciprocal::new(d);
            for &n in &nums {
                let exact = n as f64 / d as f64;
                let got = r.div(n) as f64;
                if exact.abs() < GRAD_LIMIT as f64 {
                    let bound = 0.5 + exact.abs() * 2f64.powi(-29);
                    assert!((got - exact).abs() <= bound, "{n}/{d}: {got} vs {exact}");
                } else {
                    assert_eq!(got.abs(), GRAD_LIMIT as f64, "{n}/{d} clamps");
                }
            }
        }
    }

    #[test]
    fn floor_division_both_paths() {
        for (n, d) in [
            (7i64, 2i64),
            (-7, 2),
            (0, 5),
            (-(1 << 40), 3),
            ((1 << 40) + 1, 1 << 20),
        ] {
            assert_eq!(div_floor(n, d), (n.div_euclid(d), n.rem_euclid(d)));
        }
    }
}
