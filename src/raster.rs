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
use crate::project::{
    channel_bits, vertex_frac_bits, ScreenVertex, DEPTH_FRAC_BITS, DEPTH_MAX, SUBPIXELS,
};
use crate::scalar::{mul_wide, mul_wide16, recip_norm, round_shr64};
use heapless::Vec;

/// Fraction bits of interpolated colour channels (channel units, so 0..=255·2²⁰ < 2²⁸ fits an
/// `i32`; step 2⁻²⁰ of a channel unit).
pub const COLOR_FRAC_BITS: u32 = 20;

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

#[cfg(test)]
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

/// `1/d` for a triangle's doubled area `d ≠ 0` (|d| < 2⁶²), as `±m · 2^-e` with `m` in
/// (2²⁹, 2³⁰] (see [`crate::scalar::recip_norm`]).
#[derive(Copy, Clone, Debug)]
struct Reciprocal {
    m: i32,
    e: u32,
    neg: bool,
}

impl Reciprocal {
    fn new(d: i64) -> Self {
        let (m, e) = recip_norm(d.unsigned_abs());
        Reciprocal { m, e, neg: d < 0 }
    }
}

/// `(floor(n / d), n − d·floor(n / d))` for `d > 0` and a quotient that fits in `i32`: one
/// 32-bit division when `n` fits.
#[inline]
fn div_floor(n: i64, d: i32) -> (i32, i32) {
    if let Ok(n32) = i32::try_from(n) {
        let (mut q, mut r) = (n32 / d, n32 % d);
        if r < 0 {
            q -= 1;
            r += d;
        }
        (q, r)
    } else {
        let d = d as i64;
        (n.div_euclid(d) as i32, n.rem_euclid(d) as i32)
    }
}

/// `(n / d, n % d)` for `d > 0`. On ARMv6-M by shift and subtract, one step per quotient
/// bit: an edge's quotients are a few bits, where the library division of a Cortex-M0 (no
/// divide instruction) costs over a hundred instructions whatever the quotient. Cores with a
/// divide instruction (ARMv7-M, the host) use it. (ARMv6-M is the Arm profile without 32-bit
/// atomics, the one property stable Rust exposes to `cfg`.)
#[inline]
fn udiv_small(n: u32, d: u32) -> (u32, u32) {
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "32"))))]
    {
        (n / d, n % d)
    }
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "32")))]
    udiv_shift_subtract(n, d)
}

/// [`udiv_small`] by shift and subtract (tested on the host too).
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "32"))))]
#[inline]
fn udiv_shift_subtract(n: u32, d: u32) -> (u32, u32) {
    if n < d {
        return (0, n);
    }
    let (mut dd, mut bit) = (d, 1u32);
    let half = n >> 1;
    while dd <= half {
        dd <<= 1;
        bit <<= 1;
    }
    // d·bit ≤ n < 2·d·bit.
    let (mut q, mut r) = (0, n);
    loop {
        if r >= dd {
            r -= dd;
            q |= bit;
        }
        if bit == 1 {
            return (q, r);
        }
        bit >>= 1;
        dd >>= 1;
    }
}

/// `(floor(n / d), n − d·floor(n / d))` for `d > 0`, by [`udiv_small`]: for `n < 0`,
/// `floor(n/d) = −1 − floor((−n − 1)/d)`, and `−n − 1 = !n` has no overflow.
#[inline]
fn div_floor_small(n: i32, d: i32) -> (i32, i32) {
    if n < 0 {
        let (q, r) = udiv_small(!n as u32, d as u32);
        (!(q as i32), d - 1 - r as i32)
    } else {
        let (q, r) = udiv_small(n as u32, d as u32);
        (q as i32, r as i32)
    }
}

/// `(m·v) >> l` (floor) for `0 < m ≤ 2³⁰`, `1 ≤ l ≤ 16` and `|v| < 2^l`, in 32-bit
/// products: with `m = mh·2¹⁵ + ml`, both `mh·v` and `ml·v` are below 2³¹; for `l ≤ 15` the
/// first term shifted is a whole multiple of `2^l`, and for `l = 16` the two floors nest. The
/// result, below 2³⁰ in magnitude, is that of the 64-bit product (a triangle's gradient
/// coefficients: about 20 instructions fewer each on a Cortex-M0).
#[inline(always)]
fn mul_shr_16(m: i32, v: i32, l: u32) -> i32 {
    let (mh, ml) = (m >> 15, m & 0x7fff);
    if l <= 15 {
        ((mh * v) << (15 - l)) + ((ml * v) >> l)
    } else {
        ((mh * v) + ((ml * v) >> 15)) >> 1
    }
}

/// A gradient `S · 2^-shift` (see [`ActiveTri::setup`]) rounded half up, for `shift ≥ 1`
/// (a triangle's setup has `shift ≥ 10`) and `|S| < 2⁶²`: exact, not clamped. A sliver's
/// gradient can exceed the `i32` range; the planes are stepped in wrapping arithmetic (see
/// [`ActiveTri`]), so only its low bits matter where it is used, but those must be exact.
#[inline]
fn scale_gradient(s: i64, shift: i32) -> i64 {
    if shift >= 63 {
        // |S| < 2⁶², so S / 2^shift rounds to 0.
        0
    } else {
        round_shr64(s, shift.max(1) as u32)
    }
}

/// A colour channel's x and y gradients from the exact 64-bit sums, for the triangles whose
/// 20-bit coefficients are not precise enough (see [`attribute_words`]). Out of line and
/// cold: inlined, LLVM computed parts of it for every triangle and spilled them.
#[cold]
#[inline(never)]
fn exact_color_gradients(b: [i32; 4], d1: i32, d2: i32, sh: u32, shift: i32) -> [i64; 2] {
    let [bx1, bx2, by1, by2] = b;
    // |b| ≤ 2³⁰ and |d| < 2¹⁰, so each sum is below 2⁴¹ and, shifted by sh ≤ 18, below 2⁵⁹.
    [
        scale_gradient((mul_wide16(bx1, d1) - mul_wide16(bx2, d2)) << sh, shift),
        scale_gradient((mul_wide16(by1, d2) - mul_wide16(by2, d1)) << sh, shift),
    ]
}

/// One edge from its upper vertex `a` to its lower vertex `b`, positioned on a pixel row:
/// `c` is the first pixel whose centre is at or right of the edge; the exact crossing is
/// `c − (16·e + k)/(16·dy)` pixels (relative to centres) with `0 ≤ e < dy` and a constant
/// `0 ≤ k < 16`. Every row step changes the numerator by a multiple of 16, so the DDA keeps
/// `e = floor(numerator / 16)` exactly and the test `numerator < 0` is `e < 0`: all five
/// fields fit 16 bits. Rows step it in the packed form [`EdgeDda`] ([`Edge::dda`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C)] // field offsets are used by the Cortex-M edge setup (`span_thumb`)
pub(crate) struct Edge {
    /// Current pixel boundary (column index; |c| ≤ 1025 on every row the edge is used).
    pub c: i16,
    /// Whole pixels the boundary moves per row (floor; |sq| ≤ 32 766).
    pub sq: i16,
    /// Remainder in sixteenths, `0 ≤ e < dy`.
    e: i16,
    /// Remainder of the move per row in sixteenths, `0 ≤ sr < dy`.
    sr: u16,
    /// `max(1, yb − ya)` in subpixels (≤ 32 766).
    dy: u16,
}

impl Edge {
    /// The edge `a → b` (`a.y < b.y`) at pixel row `row` (on the screen, 0..=1024), for
    /// coordinates within ±[`crate::project::COORD_LIMIT`]: every product below is under 2³⁰
    /// and the sum under 2³¹, so the setup is 32-bit (two divisions). On ARMv6-M (no divide
    /// instruction) the rows the renderer uses (the edge's own) take the assembly version of
    /// the same steps (`span_thumb::edge_new`).
    #[inline(always)]
    pub(crate) fn new(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> Edge {
        #[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
        if let Some(e) = crate::span_thumb::edge_new(xa, ya, xb, yb, row) {
            return e;
        }
        Edge::new_portable(xa, ya, xb, yb, row)
    }

    /// [`Edge::new`] in portable code.
    #[inline(never)]
    pub(crate) fn new_portable(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> Edge {
        let dy = (yb - ya).max(1);
        let dx = xb - xa;
        let d = SUBPIXELS * dy;
        let ys = SUBPIXELS * row + SUBPIXELS / 2;
        // 16·dx = sq·16·dy + sr with sr a multiple of 16.
        let (sq, sr) = div_floor_small(dx, dy);
        // The crossing numerator n = (x − 8 at the sample row)·dy = (xa − 8)·dy + k·dx, k the
        // rows' distance in subpixels; c = ceil(n/d), e = c·d − n. With dx = sq·dy + sr:
        // n = dy·(xa − 8 + k·sq) + k·sr, and k·sr = qb·dy + rb needs only a division with a
        // quotient below k (< 16 on a triangle's first row), so n = dy·t + rb.
        let k = ys - ya;
        let (c, e) = if (0..=dy + SUBPIXELS).contains(&k) {
            // |k·sq| ≤ (dy + 16)·|dx|/dy + k ≤ 17·2¹⁵ and k·sr < (dy + 16)·dy < 2³¹.
            let (qb, rb) = udiv_small((k * sr) as u32, dy as u32);
            let t = xa - SUBPIXELS / 2 + k * sq + qb as i32;
            // n = 16·dy·(t >> 4) + dy·(t & 15) + rb, the last two in 0..16·dy.
            let r = dy * (t & (SUBPIXELS - 1)) + rb as i32;
            let q = t >> crate::project::SUBPIXEL_BITS;
            if r == 0 {
                (q, 0)
            } else {
                (q + 1, d - r)
            }
        } else {
            // Not reached by the renderer (it starts edges at or below their upper vertex,
            // within their rows); kept exact for any row.
            let n = (xa - SUBPIXELS / 2) as i64 * dy as i64 + k as i64 * dx as i64;
            let (q, r) = div_floor(n, d);
            if r == 0 {
                (q, 0)
            } else {
                (q + 1, d - r)
            }
        };
        Edge {
            c: c as i16,
            sq: sq as i16,
            e: (e >> 4) as i16,
            sr: sr as u16,
            dy: dy as u16,
        }
    }

    /// The row loops' form of this edge: its two words and `dy`.
    #[inline(always)]
    pub(crate) fn dda(&self) -> (EdgeDda, u16) {
        let w = ((self.e as u32) << 16) + (self.c as i32 + C_BIAS) as u32;
        let s = (self.sq as i32 as u32).wrapping_sub((self.sr as u32) << 16);
        (EdgeDda { w, s }, self.dy)
    }
}

/// ARMv6-M only, for the benchmark firmware's self-tests: a signed value of 1 to `max_bits`
/// bits (the count from `next`'s top bits, the sign from its lowest) from the generator `next`.
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
pub(crate) fn signed_bits(next: &mut impl FnMut() -> u32, max_bits: u32) -> i32 {
    let r = next();
    let bits = (r >> 27) % max_bits + 1;
    let v = (next() >> (32 - bits)) as i32;
    if r & 1 == 0 {
        -v
    } else {
        v
    }
}

/// For the benchmark firmware's self-tests (Cortex-M) and the unit tests: a xorshift32
/// generator from `seed` (nonzero), the same sequence on every core.
#[cfg(any(test, all(target_arch = "arm", target_os = "none")))]
pub(crate) fn xorshift32(seed: u32) -> impl FnMut() -> u32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    }
}

/// For the self-tests: any depth and any 10-bit colour channels for `p`.
#[cfg(all(target_arch = "arm", target_os = "none"))]
fn random_depth_and_colour(p: &mut ScreenVertex, next: &mut impl FnMut() -> u32) {
    let d = next();
    p.z = d as u16;
    p.zf = (d >> 16) as u8;
    let c = next();
    p.set_color([
        (c & 1023) as u16,
        (c >> 10 & 1023) as u16,
        (c >> 20 & 1023) as u16,
    ]);
}

/// Cortex-M only, for the benchmark firmware: the assembly edge setup against the portable
/// one on `n` pseudo-random edges (coordinates over the whole snapped range, rows at and past
/// the upper vertex). Returns the inputs `[xa, ya, xb, yb, row]` of the first mismatch.
#[cfg(all(target_arch = "arm", target_os = "none"))]
#[doc(hidden)]
pub fn edge_setup_self_test(n: u32) -> Option<[i32; 5]> {
    let mut next = xorshift32(0x9e37_79b9u32);
    let lim = crate::project::COORD_LIMIT;
    for i in 0..n {
        let (r1, r2, r3) = (next(), next(), next());
        // Short and long edges, steep and flat, every sign.
        let span = [15, 255, 4095, 2 * lim][(r3 >> 30) as usize];
        let xa = (r1 % (2 * lim as u32 + 1)) as i32 - lim;
        let ya = ((r1 >> 16) % (2 * lim as u32 + 1)) as i32 - lim;
        let xb = (xa + (r2 % (2 * span as u32 + 1)) as i32 - span).clamp(-lim, lim);
        let yb = (ya + ((r2 >> 16) % (span as u32 + 1)) as i32).min(lim);
        // The row of the upper vertex's first sample or a later one of the edge (some
        // beyond it, which the assembly declines).
        let first = first_pixel(ya);
        let row = (first + (r3 % 8) as i32 * (i % 3) as i32).clamp(0, 1024);
        let want = Edge::new_portable(xa, ya, xb, yb, row);
        if let Some(got) = crate::span_thumb::edge_new(xa, ya, xb, yb, row) {
            if got != want {
                return Some([xa, ya, xb, yb, row]);
            }
        }
    }
    None
}

/// Cortex-M only, for the benchmark firmware: the assembly Gouraud setup
/// (`span_thumb::gouraud_setup`) against the portable [`attribute_words`] for RGB565 on `n`
/// pseudo-random triangles (small and large, every orientation, any depths and colours,
/// first rows and left edges at and around the first vertex). Returns the first mismatching
/// triangle's vertices `[x, y, depth, colour]` (the colour's three 10-bit channels packed)
/// and `[row, left column, left step]`.
#[cfg(all(target_arch = "arm", target_os = "none"))]
#[doc(hidden)]
#[allow(clippy::type_complexity)]
pub fn gouraud_setup_self_test(n: u32) -> Option<([[i32; 4]; 3], [i32; 3])> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x6a09_e667u32);
    let lim = crate::project::COORD_LIMIT;
    for i in 0..n {
        let size = [64u32, 512, 4096, 2 * lim as u32][(i % 4) as usize];
        let (ox, oy) = ((next() % 4096) as i32 - 2048, (next() % 4096) as i32 - 2048);
        let mut v = [ScreenVertex::default(); 3];
        for p in &mut v {
            let r = next();
            p.x = (ox + (r % (size + 1)) as i32 - size as i32 / 2).clamp(-lim, lim) as i16;
            p.y = (oy + ((r >> 16) % (size + 1)) as i32 - size as i32 / 2).clamp(-lim, lim) as i16;
            random_depth_and_colour(p, &mut next);
        }
        v.sort_unstable_by_key(|p| p.y);
        let [a, b, c] = &v;
        let det = (b.x as i32 - a.x as i32) * (c.y as i32 - a.y as i32)
            - (c.x as i32 - a.x as i32) * (b.y as i32 - a.y as i32);
        if det == 0 {
            continue;
        }
        let r = next();
        let row = first_pixel(a.y as i32) + (r % 16) as i32;
        let left_c = (a.x as i32 >> 4) + ((r >> 8) % 64) as i32 - 32;
        let left_sq = ((r >> 16) % 512) as i32 - 256;
        let tri = Sorted {
            v: [a, b, c],
            det,
            row,
            left_c,
            left_sq,
        };
        // The routine's precondition, which a first pixel of the left edge (within a pixel of
        // the triangle) meets: every colour plane at the first pixel within ±2³⁰ (20
        // fraction bits), so that its 32-bit value has not wrapped. Random first pixels far
        // from a small triangle can break it.
        let (dx, dy) = (16 * left_c + 8 - a.x as i32, 16 * row + 8 - a.y as i32);
        let (dx1, dy1) = (b.x as i32 - a.x as i32, b.y as i32 - a.y as i32);
        let (dx2, dy2) = (c.x as i32 - a.x as i32, c.y as i32 - a.y as i32);
        let l1 = dy2 as i64 * dx as i64 - dx2 as i64 * dy as i64;
        let l2 = dx1 as i64 * dy as i64 - dy1 as i64 * dx as i64;
        let in_range = (0..3).all(|k| {
            let c0 = a.color()[k] as i64;
            let (d1, d2) = (b.color()[k] as i64 - c0, c.color()[k] as i64 - c0);
            let n = (c0 * det as i64 + d1 * l1 + d2 * l2) << 16;
            n.unsigned_abs() < (det.unsigned_abs() as u64) << 30
        });
        if !in_range {
            continue;
        }
        let want = attribute_words::<Rgb565>(&tri, false, true, [0; 3]);
        let mut rec = ActiveTri::EMPTY;
        if crate::span_thumb::gouraud_setup(&mut rec, &tri) && [rec.gx, rec.row, rec.inc] != want {
            let word = |p: &ScreenVertex| {
                let c = p.color();
                [
                    p.x as i32,
                    p.y as i32,
                    p.depth(),
                    c[0] as i32 | (c[1] as i32) << 10 | (c[2] as i32) << 20,
                ]
            };
            return Some(([word(a), word(b), word(c)], [row, left_c, left_sq]));
        }
    }
    None
}

/// For the triangle setup self-tests: case `i`'s three random vertices within a box of 48,
/// 400, 4000 or 16 000 subpixels (by `i mod 4`) around (120, 120) px, any depths and colours,
/// each then changed by `tweak`.
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
fn random_triangle(
    i: u32,
    next: &mut impl FnMut() -> u32,
    tweak: impl Fn(&mut ScreenVertex),
) -> [ScreenVertex; 3] {
    let size = [48u32, 400, 4000, 16000][(i % 4) as usize];
    let mut v = [ScreenVertex::default(); 3];
    for p in &mut v {
        let r = next();
        p.x = ((r % size) as i32 - size as i32 / 2 + 1920) as i16;
        p.y = (((r >> 16) % size) as i32 - size as i32 / 2 + 1920) as i16;
        random_depth_and_colour(p, next);
        tweak(p);
    }
    v
}

/// Cortex-M0 only, for the benchmark firmware: the assembly triangle setup
/// (`span_thumb::setup565`) against [`ActiveTri::setup_portable`] for RGB565 on `n`
/// pseudo-random Gouraud triangles (small, tall and wide ones, equal ys, first rows before,
/// at and after the middle vertex, short screens), without and with the dither check. Returns
/// the first mismatch's vertices `[x, y]` and `[row, height]` (height negated when the
/// mismatch is with the check).
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
#[doc(hidden)]
pub fn triangle_setup_self_test(n: u32) -> Option<([[i16; 2]; 3], [i32; 2])> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0xbb67_ae85u32);
    let mode = SpanMode::new::<Rgb565>(crate::DepthTest::Less, false);
    let same = |a: &ActiveTri, b: &ActiveTri| {
        (a.flags, a.routine_rows, a.dy, a.row_mid, a.row_end)
            == (b.flags, b.routine_rows, b.dy, b.row_mid, b.row_end)
            && (a.bx, a.by, a.cx, a.cy) == (b.bx, b.by, b.cx, b.cy)
            && a.edges
                .iter()
                .zip(&b.edges)
                .all(|(p, q)| (p.w, p.s) == (q.w, q.s))
            && (a.gx, a.row, a.inc) == (b.gx, b.row, b.inc)
    };
    for i in 0..n {
        let v = random_triangle(i, &mut next, |p| {
            if i % 7 == 0 {
                // Equal ys.
                p.y &= !63;
            }
        });
        let t = TriRecord { v: [0, 1, 2] };
        let y_min = v.iter().map(|p| p.y as i32).min().unwrap_or(0);
        let r = next();
        let row = (first_pixel(y_min) + (r % 64) as i32 - 2).max(0);
        let height = [240, 60, 1024, 128][(r >> 8) as usize % 4];
        let mut want = ActiveTri::EMPTY;
        let kept = want.setup_portable::<Rgb565>(&t, &v, row, height, mode);
        let mut got = ActiveTri::EMPTY;
        if let Some(k) = crate::span_thumb::setup565(&mut got, &t, &v, row, height, false) {
            let k = k == crate::span_thumb::Setup565::Kept;
            if k != kept || (kept && !same(&got, &want)) {
                return Some((v.map(|p| [p.x, p.y]), [row, height]));
            }
            // With the dither check: `DITHER_OK` added to the same record, or the answer that
            // the triangle needs the slow path, as the portable check decides.
            use crate::span_thumb::Setup565;
            let mut dithered = ActiveTri::EMPTY;
            let d = crate::span_thumb::setup565(&mut dithered, &t, &v, row, height, true);
            let expect = if !kept {
                Setup565::Empty
            } else if want.dither_fits::<Rgb565>([&v[0], &v[1], &v[2]], row) {
                want.flags |= DITHER_OK;
                Setup565::Kept
            } else {
                Setup565::NotDitherable
            };
            if d != Some(expect) || (expect == Setup565::Kept && !same(&dithered, &want)) {
                return Some((v.map(|p| [p.x, p.y]), [row, -height]));
            }
        }
    }
    None
}

/// ARMv6-M only, for the benchmark firmware: the assembly dither check
/// (`span_thumb::dither_fits565`) against the portable [`ActiveTri::dither_fits`] for RGB565
/// on `n` pseudo-random fast Gouraud triangles (small to the largest fast size, so that the
/// packed rows drift; colours anywhere in half the cases and inside the RGB565 range in the
/// other half, so that both answers occur; first rows at and below the first vertex). Returns
/// the first mismatching triangle's vertices `[x, y]` and `[row, portable answer]`.
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
#[doc(hidden)]
pub fn dither_fits_self_test(n: u32) -> Option<([[i16; 2]; 3], [i32; 2])> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x510e_527fu32);
    let mode = SpanMode::new::<Rgb565>(DepthTest::Less, true);
    let (mut tested, mut fits) = (0u32, 0u32);
    let mut i = 0u32;
    while tested < n && i < 8 * n {
        i += 1;
        let v = random_triangle(i, &mut next, |p| {
            if i % 2 == 0 {
                let c = p.color();
                p.set_color([c[0] % 993, c[1] % 1009, c[2] % 993]);
            }
        });
        let t = TriRecord { v: [0, 1, 2] };
        let y_min = v.iter().map(|p| p.y as i32).min().unwrap_or(0);
        let row = (first_pixel(y_min) + (next() % 16) as i32 - 2).max(0);
        let mut rec = ActiveTri::EMPTY;
        if !rec.setup_portable::<Rgb565>(&t, &v, row, 1024, mode)
            || rec.flags & (FAST | FLAT) != FAST
        {
            continue;
        }
        tested += 1;
        let p = [&v[0], &v[1], &v[2]];
        let want = rec.dither_fits::<Rgb565>(p, row);
        fits += want as u32;
        if crate::span_thumb::dither_fits565(&rec, p, row) != want {
            return Some((v.map(|p| [p.x, p.y]), [row, want as i32]));
        }
    }
    // Both answers must have been compared (and enough triangles found).
    if tested < n || fits == 0 || fits == tested {
        return Some(([[0; 2]; 3], [tested as i32, fits as i32]));
    }
    None
}

/// Cortex-M only, for the benchmark firmware: the assembly dithered span
/// (`span_thumb::span565_less_dither`) against [`span_packed_dither_portable`] (RGB565,
/// `DepthTest::Less`) on `n` pseudo-random spans: any start words and steps (small and large),
/// lengths 1 to 40, every column phase and Bayer row, depth lines that hide about half the
/// pixels. Returns the first mismatch's `[case, length, x0, row]`.
#[cfg(all(target_arch = "arm", target_os = "none"))]
#[doc(hidden)]
pub fn dither_span_self_test(n: u32) -> Option<[u32; 4]> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x3c6e_f372u32);
    for case in 0..n {
        let len = 1 + (next() % 40) as usize;
        let x0 = (next() % 1024) as usize;
        let row = (next() % 1024) as i32;
        let mut word_and_step = || {
            let (v, s, k) = (next(), next(), next() % 32);
            [v, s >> k]
        };
        let [z0, gz] = word_and_step();
        let rb = word_and_step();
        let [g0, gg] = word_and_step();
        let (z, g) = ([z0 as i32, gz as i32], [g0 as i32, gg as i32]);
        let mut za = [0u16; 40];
        let mut ca = [Rgb565::new(0, 0, 0); 40];
        for (zp, cp) in za.iter_mut().zip(ca.iter_mut()) {
            let r = next();
            *zp = r as u16;
            *cp = Rgb565::new((r >> 16) as u8 & 31, (r >> 21) as u8 & 63, (r >> 27) as u8);
        }
        let (mut zb, mut cb) = (za, ca);
        let wa = crate::span_thumb::span565_less_dither(
            &mut za[..len],
            &mut ca[..len],
            z,
            rb,
            g,
            x0,
            row,
        );
        let wb = span_packed_dither_portable::<Rgb565, LESS>(
            &mut zb[..len],
            &mut cb[..len],
            z,
            rb,
            g,
            x0,
            row,
        );
        if wa != wb || za != zb || ca != cb {
            return Some([case, len as u32, x0 as u32, row as u32]);
        }
    }
    None
}

/// Cortex-M only, for the benchmark firmware: the dithered row routine
/// (`span_thumb::rows565` with dithering, the renderer's path) against `draw_row` alone on `n`
/// pseudo-random strips of four Gouraud triangles (RGB565, 96 × 48 px, some across the left
/// border, any depths and colours, set up while dithering as the renderer sets them up: on
/// their first row), row by row. Returns the first mismatching case.
#[cfg(all(target_arch = "arm", target_os = "none"))]
#[doc(hidden)]
pub fn dither_rows_self_test(n: u32) -> Option<u32> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    const W: usize = 96;
    const H: i32 = 48;
    let mut next = xorshift32(0xa54f_f53au32);
    let mode = SpanMode::new::<Rgb565>(DepthTest::Less, true);
    for case in 0..n {
        let mut v = [ScreenVertex::default(); 12];
        for p in &mut v {
            let r = next();
            p.x = ((r % (W as u32 * 16 + 320)) as i32 - 160) as i16;
            p.y = ((r >> 16) % (H as u32 * 16)) as i16;
            random_depth_and_colour(p, &mut next);
            if case % 2 == 0 {
                // Colours inside the RGB565 range (most of these triangles are DITHER_OK).
                let c = p.color();
                p.set_color([c[0] % 993, c[1] % 1009, c[2] % 993]);
            }
        }
        let tris = [[0u16, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]].map(|v| TriRecord { v });
        let first = |t: &TriRecord| {
            let [i0, i1, i2] = t.indices();
            first_pixel(v[i0].y.min(v[i1].y).min(v[i2].y) as i32).max(0)
        };
        let mut a = ActiveList::<4>::new();
        let mut b = ActiveList::<4>::new();
        for row in 0..H {
            for t in tris.iter().filter(|t| first(t) == row) {
                a.push_with(|r| r.setup::<Rgb565>(t, &v, row, H, mode));
                b.push_with(|r| r.setup::<Rgb565>(t, &v, row, H, mode));
            }
            let (mut ca, mut za) = ([Rgb565::new(0, 0, 0); W], [u16::MAX; W]);
            let (mut cb, mut zb) = (ca, za);
            let mut i = 0;
            loop {
                if let Some((next_i, _, _)) =
                    crate::span_thumb::rows565(&mut a, i, &mut ca, &mut za, row as usize, true)
                {
                    i = next_i;
                }
                if i >= a.len() {
                    break;
                }
                let (_, _, done) =
                    a.get_mut(i)
                        .draw_row(row, &mut ca, &mut za, DepthTest::Less, true);
                if done {
                    a.swap_remove(i);
                } else {
                    i += 1;
                }
            }
            let mut i = 0;
            while i < b.len() {
                let (_, _, done) =
                    b.get_mut(i)
                        .draw_row(row, &mut cb, &mut zb, DepthTest::Less, true);
                if done {
                    b.swap_remove(i);
                } else {
                    i += 1;
                }
            }
            if ca != cb || za != zb || a.len() != b.len() {
                return Some(case);
            }
        }
    }
    None
}

/// Bias of the column in [`EdgeDda::w`]: every column an edge takes on a row where it is used
/// (|c| ≤ 1025), and every sum `c + sq` on the way to the next such row, is in
/// `−2¹⁵..2¹⁵`, so the biased column is a 16-bit unsigned half that never carries into `e`.
const C_BIAS: i32 = 1 << 15;

/// An edge as the row loops step it: [`Edge`]'s fields in two words, so that one addition
/// steps both the column and the remainder and its sign is the carry test.
///
/// - `w = e·2¹⁶ + (c + 2¹⁵)`: remainder `0 ≤ e < dy` (< 2¹⁵) in the high half, the biased
///   column (0..2¹⁶) in the low half.
/// - `s = sq − sr·2¹⁶` (modulo 2³²): the low half is `sq` (as an `i16`), the high half is
///   the remainder's step.
///
/// `w + s = (e − sr)·2¹⁶ + (c + sq + 2¹⁵)` exactly, whose sign is that of `e − sr`; when it is
/// negative, adding `dy·2¹⁶ + 1` gives `e − sr + dy` and `c + sq + 1`, as [`Edge`]'s step.
/// `dy` (≤ 32 766) is kept beside the words ([`ActiveTri::dy`]). Size: 8 bytes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C)] // field offsets are used by the Cortex-M row loop (`span_thumb`)
pub(crate) struct EdgeDda {
    w: u32,
    s: u32,
}

impl EdgeDda {
    /// The current pixel boundary.
    #[inline(always)]
    pub(crate) fn c(&self) -> i32 {
        (self.w & 0xffff) as i32 - C_BIAS
    }

    /// Whole pixels the boundary moves per row (floor).
    #[inline(always)]
    pub(crate) fn sq(&self) -> i32 {
        self.s as i16 as i32
    }

    /// Moves to the next row (`dy` is this edge's); returns true when the boundary moved by
    /// `sq + 1` instead of `sq`.
    #[inline(always)]
    pub(crate) fn step(&mut self, dy: u16) -> bool {
        let w = self.w.wrapping_add(self.s);
        if (w as i32) < 0 {
            self.w = w.wrapping_add((dy as u32) << 16 | 1);
            true
        } else {
            self.w = w;
            false
        }
    }

    /// The column and carry [`EdgeDda::step`] would give, in 32 bits, without moving (one row
    /// past the edge's end the column may leave the range of the packed half).
    #[inline(always)]
    fn peek(&self) -> (i32, bool) {
        let e = self.w >> 16;
        let sr = (self.sq() as u32).wrapping_sub(self.s) >> 16;
        let carry = e < sr;
        (self.c() + self.sq() + carry as i32, carry)
    }
}

/// Bit of [`TriRecord::v`]`[0]` that marks a flat-shaded triangle: its colour is the colour of
/// vertex `v[0] & !FLAT_BIT` (the renderer stores a copy of a vertex with the face colour).
pub(crate) const FLAT_BIT: u16 = 1 << 15;

/// A triangle as stored between geometry and rasterization (6 bytes): three indices into the
/// vertex store, the first one carrying [`FLAT_BIT`]. Records are sorted by first covered row
/// after the geometry stage, so no list link is stored.
#[derive(Copy, Clone, Debug)]
#[repr(C)]
pub(crate) struct TriRecord {
    /// Indices into the renderer's vertex store (below 2¹⁵); [`FLAT_BIT`] in `v[0]`.
    pub v: [u16; 3],
}

impl TriRecord {
    /// The three vertex indices without the flag.
    #[inline(always)]
    pub(crate) fn indices(&self) -> [usize; 3] {
        [
            (self.v[0] & !FLAT_BIT) as usize,
            self.v[1] as usize,
            self.v[2] as usize,
        ]
    }
}

/// [`ActiveTri::flags`]: the middle vertex is left of the long edge.
const MID_LEFT: u8 = 1;
/// [`ActiveTri::flags`]: flat shaded (one attribute; `gx[1]` holds the colour).
const FLAT: u8 = 2;
/// [`ActiveTri::flags`]: drawn by the fast span loops. The width + height of the bounding box
/// is ≤ 1024 px, so the rounding drift of the attribute rows (≤ ½ unit per pixel of distance
/// from the anchor) stays far inside the depth bias and the colour fields' headroom and span
/// starts need no clamping; the depth test is [`DepthTest::Less`] and, for Gouraud triangles,
/// the colour has channels of at most 6 bits. A fast Gouraud triangle keeps its rows *packed*
/// (see [`ActiveTri::row`]), ready for [`span_packed`] (or, dithered, [`span_packed_dither`]
/// when it has [`DITHER_OK`]).
const FAST: u8 = 4;
/// [`ActiveTri::flags`]: the row where [`ActiveTri::routine_rows`] runs out is the triangle's
/// last, which the Cortex-M row routine draws too (and then removes the triangle).
const LAST_IN_ROUTINE: u8 = 8;
/// [`ActiveTri::flags`]: the row where [`ActiveTri::routine_rows`] runs out is the one before
/// the short edge's switch, which the Cortex-M row routine draws too, switching to the edge
/// kept by [`ActiveTri::set_pending`] (a fast Gouraud triangle only).
const SWITCH_IN_ROUTINE: u8 = 16;

/// [`ActiveTri::flags`]: a [`FAST`] Gouraud triangle set up while dithering whose packed
/// fields are within ¼ unit of the exact colour plane and keep 15/32 of a channel unit of
/// headroom at both ends of their ranges at every point of the triangle
/// ([`ActiveTri::dither_fits`]), so the dithered fast span ([`span_packed_dither`]) may add any
/// Bayer offset without a carry between fields. (A triangle that fails is set up without the
/// fast path; a fast triangle set up while dithering was off is dithered by
/// [`span_packed_dither_clamped`].)
const DITHER_OK: u8 = 32;

/// Which fast span loops a strip may use, decided once per strip from the colour type, the
/// depth test and dithering (see [`FAST`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct SpanMode {
    /// Flat triangles: the depth test is [`DepthTest::Less`].
    pub fast_flat: bool,
    /// Gouraud triangles: also channels of at most 6 bits.
    pub fast_gouraud: bool,
    /// Dithering changes the colour (so fast Gouraud triangles are checked for
    /// [`DITHER_OK`] at setup).
    pub dither: bool,
}

impl SpanMode {
    pub(crate) fn new<C: TargetColor>(test: DepthTest, dither: bool) -> Self {
        let less = test == DepthTest::Less;
        SpanMode {
            fast_flat: less,
            fast_gouraud: less && packable::<C>(),
            dither: dither && C::can_dither(),
        }
    }
}

/// The pixel of a packed red-blue word and a packed green word ([`pack_zrgb`]): the whole bits
/// of each field. The shifts are constants of the colour type (immediates, no registers), so
/// [`span_packed`] and its dithered twin share this without cost.
#[inline(always)]
fn packed_color<C: TargetColor>(rb: u32, g: u32) -> C {
    let (fr, fb) = packed_frac_bits::<C>();
    C::from_channels([
        (rb >> (16 + fr)) as u8,
        shr_or_zero(g, 32 - channel_bits(C::CHANNEL_MAX[1])) as u8,
        ((rb & 0xffff) >> fb) as u8,
    ])
}

/// `v >> s`, and 0 for `s ≥ 32` (a green word's channel bits for a colour type without green:
/// `s` is a constant of the colour type, so this folds to one shift or to 0).
#[inline(always)]
fn shr_or_zero(v: u32, s: u32) -> u32 {
    v.checked_shr(s).unwrap_or(0)
}

/// Whether red and blue of `C` fit the packed red-blue word (at most 6 bits each).
#[inline(always)]
fn packable<C: TargetColor>() -> bool {
    C::CHANNEL_MAX[0] <= 63 && C::CHANNEL_MAX[2] <= 63 && C::CHANNEL_MAX[0] > 0
}

/// Fraction bits of red and blue in a packed red-blue word: `16 − bits` of each channel.
#[inline(always)]
fn packed_frac_bits<C: TargetColor>() -> (u32, u32) {
    (
        16 - channel_bits(C::CHANNEL_MAX[0]),
        16 - channel_bits(C::CHANNEL_MAX[2]),
    )
}

/// The packed red-blue word of red `r` and blue `b` (20 fraction bits each, values or
/// gradients): each rounded to `16 − bits` fraction bits, red in the high half, added with
/// wrapping (so the word is `R·2¹⁶ + B mod 2³²`, whatever the signs).
#[inline(always)]
fn pack_rb<C: TargetColor>(r: i64, b: i64) -> u32 {
    let (fr, fb) = packed_frac_bits::<C>();
    let conv = |v: i64, s: u32| (v.wrapping_add(1 << (s - 1)) >> s) as u32;
    (conv(r, COLOR_FRAC_BITS - fr) << 16).wrapping_add(conv(b, COLOR_FRAC_BITS - fb))
}

/// Half a unit of red and of blue in a packed red-blue word: the rounding bias of a start value.
#[inline(always)]
fn packed_rb_half<C: TargetColor>() -> u32 {
    let (fr, fb) = packed_frac_bits::<C>();
    ((1u32 << (fr - 1)) << 16) + (1 << (fb - 1))
}

/// The dithered fast span's offsets for pixel row `row` ([`span_packed_dither`]): for each
/// column phase `p = x & 3`, the word to add to a packed red-blue value and the word to add
/// to a packed green value. The packed start values already carry the ½-unit rounding bias
/// of the non-dithered path ([`attribute_words`]); the Bayer threshold (2·B + 1)/32 of a unit
/// (B = `BAYER[row & 3][p]`) is that bias plus `d = (2·B − 15)/32`, from −15/32 to +15/32 of a
/// unit in steps of 1/16. `d` is exact in every packed format (channels of at most 6 bits
/// have at least 10 fraction bits): `d·2^(frac − 5)` in the red half and in the blue half
/// (added as one wrapping word, so red gets `d` and blue gets `d` — no carry crosses the
/// halves when both fields stay in `0..2¹⁶`, see [`DITHER_OK`]), and `d·2^(32 − bits − 5)`
/// in the green word.
#[inline(always)]
pub(crate) fn dither_words<C: TargetColor>(row: i32) -> [[u32; 2]; 4] {
    let (fr, fb) = packed_frac_bits::<C>();
    let gs = 32 - channel_bits(C::CHANNEL_MAX[1]) - 5;
    let b = &BAYER[(row & 3) as usize];
    let mut out = [[0u32; 2]; 4];
    for (o, &bv) in out.iter_mut().zip(b) {
        let d = 2 * bv as i32 - 15;
        o[0] = ((d << (fr - 5)) as u32)
            .wrapping_shl(16)
            .wrapping_add((d << (fb - 5)) as u32);
        o[1] = (d as u32).wrapping_shl(gs);
    }
    out
}

/// [`dither_words`] of RGB565 (red and blue with 11 fraction bits, green with 26) for the
/// four Bayer rows, as the Cortex-M routines read them: per row, eight words, the red-blue
/// and green offsets of column phases 0, 1, 2, 3 in turn.
#[cfg(all(target_arch = "arm", target_os = "none"))]
pub(crate) static DITHER565: [[u32; 8]; 4] = {
    let mut t = [[0u32; 8]; 4];
    let mut r = 0;
    while r < 4 {
        let mut p = 0;
        while p < 4 {
            let d = 2 * BAYER[r][p] as i32 - 15;
            t[r][2 * p] = ((d << 6) as u32).wrapping_mul(0x1_0001);
            t[r][2 * p + 1] = (d as u32).wrapping_shl(21);
            p += 1;
        }
        r += 1;
    }
    t
};

/// Left shift of a packed depth word: depth (16.12) times 2⁴, so that the stored depth is the
/// high half (the shifted value wraps exactly as the unshifted one, modulo 2³²).
const PACKED_Z_SHIFT: u32 = 32 - 16 - DEPTH_FRAC_BITS;

/// Left shift of a packed green word: green (20 fraction bits) times `2^(12 − bits)`, so that
/// its `bits` whole bits are the word's top bits.
#[inline(always)]
fn packed_g_shift<C: TargetColor>() -> u32 {
    32 - COLOR_FRAC_BITS - channel_bits(C::CHANNEL_MAX[1])
}

/// A depth, red-blue and green triple (values or steps, 16.12 depth and 20-bit channels with
/// any biases added) in the packed span formats: depth and green shifted to the top of their
/// words, red and blue in one word ([`pack_rb`]). All wrapping, so stepping the packed words
/// gives exactly the packed stepped values.
#[inline(always)]
fn pack_zrgb<C: TargetColor>(z: i64, r: i64, g: i64, b: i64) -> [i32; 3] {
    [
        (z as i32) << PACKED_Z_SHIFT,
        pack_rb::<C>(r, b) as i32,
        (g as i32) << packed_g_shift::<C>(),
    ]
}

/// A triangle on the active list (84 bytes).
///
/// Attribute values are 32-bit and updated with wrapping arithmetic: every value that is
/// *used* is the plane at a pixel centre inside the triangle, which lies within the attribute's
/// range, and two's-complement arithmetic is exact modulo 2³², so intermediate wrap-arounds
/// (far outside the triangle) cannot change it.
#[derive(Clone, Debug)]
#[repr(C)] // field offsets are used by the Cortex-M row loop (`span_thumb`)
pub(crate) struct ActiveTri {
    /// [`MID_LEFT`], [`FLAT`], [`FAST`], [`LAST_IN_ROUTINE`], [`SWITCH_IN_ROUTINE`],
    /// [`DITHER_OK`].
    flags: u8,
    /// Rows from the current one on that the Cortex-M row routine may draw without asking:
    /// a fast Gouraud triangle's rows before the one that switches its short edge or ends it
    /// (0..=255; 0 for every other triangle). Set at setup and after every portable row
    /// ([`ActiveTri::set_routine_rows`]); the routine counts it down.
    routine_rows: u8,
    /// Unused (explicit padding, so that the record has no implicit padding bytes).
    spare: i16,
    /// The left and right edges.
    edges: [EdgeDda; 2],
    /// `dy` of the left and right edges (see [`EdgeDda`]).
    dy: [u16; 2],
    /// Row where the short edge changes from a→b to b→c (|·| ≤ 1025).
    row_mid: i16,
    /// First row not covered (≤ 1024).
    row_end: i16,
    /// x and y of the middle and bottom vertices (sorted by y), in subpixels (12.4), for the
    /// short edge's switch.
    bx: i16,
    by: i16,
    cx: i16,
    cy: i16,
    /// Per-pixel x gradients, the low 32 bits of the exact ones (a sliver's can exceed the
    /// `i32` range; every value used is exact modulo 2³², see above): depth (16.12 per pixel)
    /// and r, g, b (channel units, 20 fraction bits per pixel). Flat triangles keep their final channel bytes in `gx[1]`.
    /// (The y gradient lives on in `inc`, and the values at the first vertex in `row`, so
    /// neither is stored.)
    gx: [i32; 4],
    /// Values at the centre of the current row's first pixel (column `left.c`), same formats.
    /// A [`FAST`] Gouraud triangle keeps three *packed* values here, in `gx` and in `inc`
    /// instead ([`pack_zrgb`]): depth with its ½-step rounding bias, times 2⁴ (16.16, the
    /// depth is the high half); red and blue in one word, red in the high half and blue in the
    /// low half, each with `16 − bits` fraction bits, rounded from the 20-bit values at setup,
    /// plus ½ unit each; green plus ½ unit, shifted so that its `bits` whole bits are the
    /// word's top bits (`32 − bits` fraction bits). All steps are wrapping additions, so the
    /// packed word is exactly `R·2¹⁶ + B (mod 2³²)` of the stepped red and blue, and its
    /// halves read back as the channels whenever `B` is in `0..2¹⁶`, which holds at every
    /// pixel centre inside the triangle (the ½-unit bias leaves ½ unit of headroom at both
    /// ends, and the stepping of values rounded to `16 − bits` fraction bits drifts by under
    /// 2⁻¹² unit per row and per pixel).
    row: [i32; 4],
    /// Change of `row` when the left edge moves by `sq` columns: `gy + gx·sq`.
    inc: [i32; 4],
}

// The routine's row count and a spare halfword fill what was padding: an active triangle stays
// 84 bytes.
const _: () = assert!(core::mem::size_of::<ActiveTri>() == 84);
// Five 16-bit fields and no padding (the Cortex-M edge setup writes all of them).
const _: () = assert!(core::mem::size_of::<Edge>() == 10);

/// The active triangles of the current row: up to `N` records in drawing order. Removal is
/// `swap_remove` (the last record moves into the removed one's slot: on a Cortex-M0 the row
/// routine does it with six `ldm`/`stm` pairs, once per triangle, where an order kept apart
/// from the records cost a lookup on every row). Slots are added when the list first grows
/// past them and then reused, frame after frame.
#[derive(Debug)]
pub(crate) struct ActiveList<const N: usize> {
    /// The slots used so far (never shrinks; a vector, so a new list is built without
    /// writing, or copying, `N` records on the stack).
    slots: Vec<ActiveTri, N>,
    /// Triangles on the list (≤ `slots.len()`).
    len: usize,
}

impl<const N: usize> ActiveList<N> {
    /// Sets every active triangle's routine row count again for `row` (the next row to draw)
    /// after dithering was switched to `dithered` between strips ([`ActiveTri::set_routine_rows`]).
    pub(crate) fn refresh_routine_rows(&mut self, row: i32, dithered: bool) {
        for t in &mut self.slots[..self.len] {
            t.set_routine_rows(row, dithered);
        }
    }

    pub(crate) const fn new() -> Self {
        ActiveList {
            slots: Vec::new(),
            len: 0,
        }
    }

    #[inline(always)]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    /// Most slots (the renderer's limit on `ACTIVE`).
    pub(crate) const MAX: usize = 1 << 15;

    /// Entry `i` of the list (`i < len`).
    #[inline(always)]
    pub(crate) fn get_mut(&mut self, i: usize) -> &mut ActiveTri {
        &mut self.slots[i]
    }

    /// Sets up a triangle in the next free slot with `f`, which returns whether it is kept.
    /// Returns false when the list is full.
    #[inline(always)]
    pub(crate) fn push_with(&mut self, f: impl FnOnce(&mut ActiveTri) -> bool) -> bool {
        if self.len >= N {
            return false;
        }
        if self.len == self.slots.len() {
            let _ = self.slots.push(ActiveTri::EMPTY);
        }
        if f(&mut self.slots[self.len]) {
            self.len += 1;
        }
        true
    }

    /// Removes entry `i` (`i < len`); the last entry takes its place.
    #[inline(always)]
    pub(crate) fn swap_remove(&mut self, i: usize) {
        let last = self.len - 1;
        if i != last {
            self.slots[i] = self.slots[last].clone();
        }
        self.len = last;
    }

    /// The list length after the Cortex-M row routine removed finished triangles (as
    /// [`ActiveList::swap_remove`] does); `n ≤ len`.
    #[cfg(all(target_arch = "arm", target_os = "none"))]
    #[inline(always)]
    pub(crate) fn set_len_after_routine(&mut self, n: usize) {
        self.len = n.min(self.len);
    }

    /// Whether the Cortex-M row routine would draw entry `i` (`i < len`) on this row (given
    /// its left edge on screen): entering it for one that it declines costs about 60
    /// instructions, which a frame of flat or clipped triangles pays on every row.
    #[cfg(all(target_arch = "arm", target_os = "none"))]
    #[inline(always)]
    pub(crate) fn routine_may_draw(&self, i: usize) -> bool {
        let t = &self.slots[i];
        t.routine_rows != 0 || t.flags & (LAST_IN_ROUTINE | SWITCH_IN_ROUTINE) != 0
    }

    /// The slot records (for the Cortex-M row routine) and the list length.
    #[cfg(all(target_arch = "arm", target_os = "none"))]
    #[inline(always)]
    pub(crate) fn raw_parts(&mut self) -> (*mut ActiveTri, usize) {
        (self.slots.as_mut_ptr(), self.len)
    }
}

/// Byte offsets of the fields the Cortex-M row loop reads and writes.
#[cfg(all(target_arch = "arm", target_os = "none"))]
pub(crate) mod offsets {
    use super::{ActiveTri, EdgeDda};
    use core::mem::{offset_of, size_of};
    pub const LEFT: usize = offset_of!(ActiveTri, edges);
    pub const RIGHT: usize = LEFT + size_of::<EdgeDda>();
    pub const W: usize = offset_of!(EdgeDda, w);
    pub const S: usize = offset_of!(EdgeDda, s);
    pub const LEFT_DY: usize = offset_of!(ActiveTri, dy);
    pub const RIGHT_DY: usize = LEFT_DY + 2;
    pub const GX: usize = offset_of!(ActiveTri, gx);
    pub const ROW: usize = offset_of!(ActiveTri, row);
    pub const INC: usize = offset_of!(ActiveTri, inc);
    pub const ROUTINE_ROWS: usize = offset_of!(ActiveTri, routine_rows);
    pub const FLAGS: usize = offset_of!(ActiveTri, flags);
    pub const LAST_BIT: u32 = super::LAST_IN_ROUTINE.trailing_zeros();
    pub const SWITCH_BIT: u32 = super::SWITCH_IN_ROUTINE.trailing_zeros();
    pub const SWITCH: u8 = super::SWITCH_IN_ROUTINE;
    pub const LAST: u8 = super::LAST_IN_ROUTINE;
    pub const MID_LEFT: u8 = super::MID_LEFT;
    pub const ROW_MID: usize = offset_of!(ActiveTri, row_mid);
    pub const ROW_END: usize = offset_of!(ActiveTri, row_end);
    pub const BX: usize = offset_of!(ActiveTri, bx);
    pub const CX: usize = offset_of!(ActiveTri, cx);
    pub const FAST: u8 = super::FAST;
    pub const DITHER_OK: u8 = super::DITHER_OK;
    /// The pending short edge of a fast Gouraud triangle ([`ActiveTri::set_pending`]): its
    /// `w` word in the fourth `gx` word, `s` in the fourth `row` word, `dy` in the fourth
    /// `inc` word.
    pub const PEND_W: usize = GX + 12;
    pub const PEND_S: usize = ROW + 12;
    pub const PEND_DY: usize = INC + 12;
    pub const EDGE_C: usize = offset_of!(super::Edge, c);
    pub const EDGE_SQ: usize = offset_of!(super::Edge, sq);
    pub const EDGE_E: usize = offset_of!(super::Edge, e);
    pub const EDGE_SR: usize = offset_of!(super::Edge, sr);
    pub const EDGE_DY: usize = offset_of!(super::Edge, dy);
}

/// A triangle's vertices sorted by y, with what [`attribute_words`] needs of its setup
/// (seven words in this order: the Cortex-M0 setup, `span_thumb::gouraud_setup`, reads them).
#[repr(C)]
pub(crate) struct Sorted<'v> {
    /// The vertices, top to bottom.
    pub v: [&'v ScreenVertex; 3],
    /// Twice the signed area, `(b − a) × (c − a)` in subpixels² (nonzero, |·| < 2³¹).
    pub det: i32,
    /// The first row to draw.
    pub row: i32,
    /// The left edge's column on that row.
    pub left_c: i32,
    /// The left edge's whole step in columns per row.
    pub left_sq: i32,
}

/// The attribute words of a triangle set up on `tri.row` ([`ActiveTri::gx`], `row` and
/// `inc`): the planes of depth and colour, their gradients, their values at the centre of the
/// first pixel of the first row and their steps from row to row along the left edge; packed
/// for the span loops when `fast` and not `flat`.
#[inline(always)]
fn attribute_words<C: TargetColor>(
    tri: &Sorted<'_>,
    flat: bool,
    fast: bool,
    flat_rgb: [u16; 3],
) -> [[i32; 4]; 3] {
    let [a, b, c] = tri.v;
    let (ax, ay, bx, by, cx, cy) = (
        a.x as i32, a.y as i32, b.x as i32, b.y as i32, c.x as i32, c.y as i32,
    );
    let (dx1, dy1) = (bx - ax, by - ay);
    let (dx2, dy2) = (cx - ax, cy - ay);
    // Barycentric gradient coefficients, 16·(dy2, dy1, dx2, dx1)/det, with a shared
    // exponent: gx = da1·bx1 − da2·bx2, gy = da2·by1 − da1·by2.
    let inv = Reciprocal::new(tri.det as i64);
    let vmax = dy2
        .unsigned_abs()
        .max(dy1.unsigned_abs())
        .max(dx1.unsigned_abs())
        .max(dx2.unsigned_abs());
    let l = crate::scalar::bitlen32(vmax); // ≤ 16
    let coef = |v: i32| -> i32 {
        let q = mul_shr_16(inv.m, v, l);
        if inv.neg {
            -q
        } else {
            q
        }
    };
    let (bx1, bx2, by1, by2) = (coef(dy2), coef(dy1), coef(dx1), coef(dx2));
    // g = S · 2^(l + 4 − e), S = Σ da·b.
    let shift = inv.e as i32 - (l as i32 + 4);
    // The 20-bit coefficients below move a colour anywhere in the triangle by at most
    // (|d1| + |d2|)·2^(2l − bitlen(det) − 18) channel units (10-bit): each is within 2¹⁰ of
    // its coefficient (≤ 2³⁰, so 2⁻²⁰ of the largest), that error in a gradient is
    // (|d1| + |d2|)·2^(l − 15 − bitlen(det)) per pixel, and no pixel is more than 2^(l − 3)
    // pixels (x plus y) from the first vertex. With |d| < 2¹⁰ that is at most 1/8 of a 5-bit
    // unit when 2l − bitlen(det) ≤ 9, i.e. shift − l ≥ 16 (a triangle at most about 500 times
    // longer than it is thick). Thinner ones take the exact sums.
    let coarse_ok = shift - l as i32 >= COARSE_MIN;

    let n_attrs = if flat { 1 } else { 4 };
    // The coefficients rounded to 20 bits (|c| ≤ 2^19) for the colour gradients.
    let c20 = [bx1, bx2, by1, by2].map(|v| (v + (1 << 10)) >> 11);
    let (ca, cb, cc) = (a.color(), b.color(), c.color());
    // Values at the first vertex, and the gradients per pixel: exact, in 64 bits (a sliver's
    // gradients may exceed the i32 range; see [`scale_gradient`]).
    let mut a0 = [0i32; 4];
    let mut gx = [0i64; 4];
    let mut gy = [0i64; 4];
    {
        let (v0, v1, v2) = (a.depth(), b.depth(), c.depth());
        let (da1, da2) = (v1 - v0, v2 - v0); // |da| < 2^28
        a0[0] = v0;
        gx[0] = scale_gradient(mul_wide(da1, bx1) - mul_wide(da2, bx2), shift);
        gy[0] = scale_gradient(mul_wide(da2, by1) - mul_wide(da1, by2), shift);
    }
    // Constant trip counts (with a break), so that the channels are unrolled: with a
    // variable count LLVM kept the arrays in memory and the loop cost about twice as much.
    for k in 1..4 {
        if flat {
            break;
        }
        // Colours are 10-bit channels scaled by a constant power of two: the products are
        // 32 × 16-bit, shifted afterwards (the same values).
        let sh = COLOR_FRAC_BITS - vertex_frac_bits(C::CHANNEL_MAX[k - 1]);
        let c0 = ca[k - 1] as i32;
        let (d1, d2) = (cb[k - 1] as i32 - c0, cc[k - 1] as i32 - c0); // |d| < 2^10
        a0[k] = c0 << sh;
        // The gradients from the coefficients rounded to 20 bits: sums of single 32-bit
        // products (|d·c| < 2^29), rounded once by a 32-bit shift (see `coarse_ok`).
        // Triangles thin enough to need a shift of less than 1 keep the exact 64-bit sums.
        let r = shift - 11 - sh as i32;
        if r >= 1 && coarse_ok {
            // v / 2^r rounded half up, as `round_shr64` (r ≤ 62).
            let round = |v: i32| -> i64 { (((v >> (r - 1).min(31)) + 1) >> 1) as i64 };
            gx[k] = round(c20[0] * d1 - c20[1] * d2);
            gy[k] = round(c20[2] * d2 - c20[3] * d1);
        } else {
            [gx[k], gy[k]] = exact_color_gradients([bx1, bx2, by1, by2], d1, d2, sh, shift);
        }
    }
    // Evaluate every attribute plane at the centre of pixel (left.c, row), modulo 2⁶⁴ (the
    // exact value where it is used: see [`ActiveTri`]).
    let dx = SUBPIXELS * tri.left_c + SUBPIXELS / 2 - ax;
    let dy = SUBPIXELS * tri.row + SUBPIXELS / 2 - ay;
    let mut row64 = [0i64; 4];
    for k in 0..4 {
        if k == n_attrs {
            break;
        }
        let p = wide_plane(gx[k], dx).wrapping_add(wide_plane(gy[k], dy));
        row64[k] = (a0[k] as i64).wrapping_add(p >> crate::project::SUBPIXEL_BITS);
    }
    let sq = tri.left_sq;
    if fast && !flat {
        // Pack once here, so that rows and spans step three words and convert nothing. Red
        // and blue are packed from the 64-bit values (a wrapped 32-bit blue would put a wrong
        // borrow into red), and the row step from the packed gradients, `Gy + Gx·sq`, so that
        // stepping rows adds no error beyond the packed gradients' own (see
        // [`ActiveTri::dither_fits`]).
        let [z, rb, g] = pack_zrgb::<C>(
            row64[0].wrapping_add(1 << (DEPTH_FRAC_BITS - 1)),
            row64[1],
            row64[2].wrapping_add(1 << (COLOR_FRAC_BITS - 1)),
            row64[3],
        );
        let row_v = [z, rb.wrapping_add(packed_rb_half::<C>() as i32), g, 0];
        let px = pack_zrgb::<C>(gx[0], gx[1], gx[2], gx[3]);
        let py = pack_zrgb::<C>(gy[0], gy[1], gy[2], gy[3]);
        let inc = [0, 1, 2].map(|k| py[k].wrapping_add(px[k].wrapping_mul(sq)));
        return [[px[0], px[1], px[2], 0], row_v, [inc[0], inc[1], inc[2], 0]];
    }
    let mut out_gx = gx.map(|g| g as i32);
    let mut row_v = row64.map(|v| v as i32);
    let inc = [0, 1, 2, 3].map(|k| (gy[k] as i32).wrapping_add((gx[k] as i32).wrapping_mul(sq)));
    if flat {
        // Final channel values, rounded from the vertex bytes.
        let mut ch = [0u8; 3];
        for k in 0..3 {
            let f = vertex_frac_bits(C::CHANNEL_MAX[k]);
            ch[k] = ((flat_rgb[k] as u32 + (1 << (f - 1))) >> f) as u8;
        }
        out_gx[1] = i32::from_le_bytes([ch[0], ch[1], ch[2], 0]);
    }
    if fast {
        row_v[0] = row_v[0].wrapping_add(1 << (DEPTH_FRAC_BITS - 1));
    }
    [out_gx, row_v, inc]
}

/// The smallest `shift − l` (see [`attribute_words`]) for which a triangle's colour gradients
/// come from the 20-bit coefficients.
pub(crate) const COARSE_MIN: i32 = 16;

/// `g·d` modulo 2⁶⁴ for a gradient `g` and a subpixel offset `|d| < 2¹⁵` ([`mul_wide16`]'s
/// range) or any `d` (a 64-bit multiply).
#[inline(always)]
fn wide_plane(g: i64, d: i32) -> i64 {
    if g == g as i32 as i64 && d == d as i16 as i32 {
        mul_wide16(g as i32, d)
    } else {
        g.wrapping_mul(d as i64)
    }
}

/// [`attribute_words`] into `rec`, out of line, on ARMv6-M: there the assembly
/// (`span_thumb::setup565`) takes the common case, and inlined the portable words and their
/// spills would grow the frame of [`ActiveTri::setup`] (on a 16 KB part the stack has no
/// room).
#[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
#[inline(never)]
fn set_attribute_words<C: TargetColor>(
    rec: &mut ActiveTri,
    tri: &Sorted<'_>,
    flat: bool,
    fast: bool,
    flat_rgb: [u16; 3],
) {
    [rec.gx, rec.row, rec.inc] = attribute_words::<C>(tri, flat, fast, flat_rgb);
}

impl ActiveTri {
    /// An inactive record to set up in place (see [`ActiveTri::setup`]).
    pub(crate) const EMPTY: ActiveTri = ActiveTri {
        flags: 0,
        routine_rows: 0,
        spare: 0,
        edges: [EdgeDda { w: 0, s: 0 }; 2],
        dy: [1; 2],
        row_mid: 0,
        row_end: 0,
        bx: 0,
        by: 0,
        cx: 0,
        cy: 0,
        gx: [0; 4],
        row: [0; 4],
        inc: [0; 4],
    };

    /// Sets up triangle `t` starting at `row` (its first covered row, clamped to the screen)
    /// in place — the record is 84 bytes, and building it elsewhere to copy it into the
    /// active list cost two block copies per triangle on a Cortex-M0. `mode` is the strip's
    /// [`SpanMode`]. Returns false (leaving `self` unspecified) if the triangle covers no row
    /// from `row` on.
    pub(crate) fn setup<C: TargetColor>(
        &mut self,
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
        mode: SpanMode,
    ) -> bool {
        // On ARMv6-M the assembly setup also makes the dither check of `setup_dither`.
        #[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
        if mode.fast_gouraud && C::CHANNEL_MAX == [31, 63, 31] {
            use crate::span_thumb::Setup565;
            match crate::span_thumb::setup565(self, t, verts, row, height, mode.dither) {
                Some(Setup565::Kept) => return true,
                Some(Setup565::Empty) => return false,
                Some(Setup565::NotDitherable) => {
                    let slow = SpanMode {
                        fast_gouraud: false,
                        ..mode
                    };
                    return self.setup_portable::<C>(t, verts, row, height, slow);
                }
                None => {}
            }
        }
        if mode.dither {
            return self.setup_dither::<C>(t, verts, row, height, mode);
        }
        self.setup_portable::<C>(t, verts, row, height, mode)
    }

    /// [`ActiveTri::setup`] while dithering: a fast Gouraud triangle gets [`DITHER_OK`] if
    /// [`ActiveTri::dither_fits`] holds, and otherwise is set up again without the fast path
    /// (its rows are then dithered from the 20-bit values by `Span::fill_gouraud_dither`, as
    /// every dithered triangle was before). Out of line, so that the undithered setup is the
    /// same code as before.
    #[inline(never)]
    fn setup_dither<C: TargetColor>(
        &mut self,
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
        mode: SpanMode,
    ) -> bool {
        // (On ARMv6-M, `setup` came here only if the assembly setup declined.)
        let kept = self.setup_portable::<C>(t, verts, row, height, mode);
        if !kept || self.flags & (FAST | FLAT) != FAST {
            return kept;
        }
        let [i0, i1, i2] = t.indices();
        let p = [&verts[i0], &verts[i1], &verts[i2]];
        #[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
        let fits = if C::CHANNEL_MAX == [31, 63, 31] {
            crate::span_thumb::dither_fits565(self, p, row)
        } else {
            self.dither_fits::<C>(p, row)
        };
        #[cfg(not(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32"))))]
        let fits = self.dither_fits::<C>(p, row);
        if fits {
            self.flags |= DITHER_OK;
            return true;
        }
        let slow = SpanMode {
            fast_gouraud: false,
            ..mode
        };
        self.setup_portable::<C>(t, verts, row, height, slow)
    }

    /// Whether the packed fields of this fast Gouraud triangle (just set up on `row`, `p` its
    /// vertices) are fit for the dithered fast span: at every pixel centre of the triangle,
    /// each field is within ¼ unit of the exact plane through the vertex colours (plus the
    /// ½-unit bias), and at least 15/32 of a unit inside its range, so that adding any offset
    /// of [`dither_words`] (|d| ≤ 15/32 of a unit) neither carries from blue into red nor
    /// leaves the red half or the green word.
    ///
    /// Why this is checked per triangle: the packed fields hold the value plus ½ unit, and the
    /// values the packed rows produce are not exactly within the channel's range. The colour
    /// gradients come from coefficients rounded to 20 bits (a few 2⁻¹⁸ of the channel's change
    /// across the triangle), and the packed steps are rounded to `16 − bits` fraction bits:
    /// 2⁻¹² unit per pixel, and per row 2⁻¹² unit times `1 + |sq|` (the row step is
    /// `inc = gy + gx·sq`, and after the short edge's switch `inc` changes by the *packed*
    /// `gx·dsq`, so the rounding of `gx` comes back `|sq|` times per row): a steep left edge
    /// across a tall triangle drifts by units. Rounding to nearest tolerates ½ unit (less in
    /// such triangles); the thresholds 1/32 and 31/32 leave 1/32 unit, so a field near 0 or
    /// the channel's maximum would borrow or carry between fields (blue 0 would read as 31).
    /// Neither bound holds in general, so both are checked, exactly:
    ///
    /// The packed rows are stepped with wrapping additions of constant words, so every packed
    /// field is an exact linear function of the pixel: `F(c, r) = F₀ + Gx·(c − c₀) +
    /// Gy·(r − r₀)` with `F₀` the field at the first pixel `(c₀, r₀)` (the left edge's column
    /// on `row`), `Gx` the field of `gx` and `Gy = inc − gx·sq` (the left edge's `sq`). The
    /// row step `inc + carry·gx` and the column move `sq + carry` keep `Gy` constant, and so
    /// does the switch to the short edge b → c (`inc` changes by `gx·dsq` when `sq` changes by
    /// `dsq`; `row` moves by `gx·dc`). The exact plane is linear too, so the extremes of `F`
    /// and of `F` minus the exact plane over the triangle are at its vertices: checking `16·F`
    /// at the three vertices (in subpixels, so in integers) bounds both at every pixel centre
    /// inside. Reading the word as fields (blue the low half, red the high half minus blue's
    /// borrow, gradients as signed halves) picks one of the decompositions `R·2¹⁶ + B
    /// (mod 2³²)`; any other one differs by a multiple of 2¹⁶ in `B` everywhere and fails the
    /// range check, so a pass proves that the word's halves are these fields at every pixel.
    /// Range: the fields are below 2¹⁶, their gradient halves below 2¹⁵ and the vertices
    /// within 16 400 subpixels of the first pixel (width + height ≤ 1024 px), so each sum is
    /// below 2³¹; green is summed in 64 bits.
    fn dither_fits<C: TargetColor>(&self, p: [&ScreenVertex; 3], row: i32) -> bool {
        let c0 = self.edges[0].c();
        let sq = self.edges[0].sq() as u32;
        let (ox, oy) = (
            SUBPIXELS * c0 + SUBPIXELS / 2,
            SUBPIXELS * row + SUBPIXELS / 2,
        );
        // Red and blue: the halves of the packed word (F₀, Gx, Gy of each).
        let (a, gx) = (self.row[1] as u32, self.gx[1] as u32);
        let gy = (self.inc[1] as u32).wrapping_sub(gx.wrapping_mul(sq));
        let (bx, by) = (gx as i16 as i32, gy as i16 as i32);
        let (rx, ry) = (
            (gx.wrapping_sub(bx as u32) as i32) >> 16,
            (gy.wrapping_sub(by as u32) as i32) >> 16,
        );
        let (b0, r0) = ((a & 0xffff) as i32, (a >> 16) as i32);
        // Green: the whole word.
        let (ga, ggx) = (self.row[2] as u32, self.gx[2]);
        let ggy = (self.inc[2] as u32).wrapping_sub((ggx as u32).wrapping_mul(sq)) as i32;
        // Vertex by vertex, leaving at the first field that does not fit (fewer live values
        // than field by field: this runs once per dithered fast triangle).
        p.iter().all(|v| {
            let (dx, dy) = (v.x as i32 - ox, v.y as i32 - oy);
            let c = v.color();
            field16_fits::<C, 2>(b0, bx, by, dx, dy, c[2])
                && field16_fits::<C, 0>(r0, rx, ry, dx, dy, c[0])
                && green_fits::<C>(ga, ggx, ggy, dx, dy, c[1])
        })
    }

    /// [`ActiveTri::setup`] in portable code (on ARMv6-M, for what `span_thumb::setup565`
    /// declines).
    #[inline]
    fn setup_portable<C: TargetColor>(
        &mut self,
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
        mode: SpanMode,
    ) -> bool {
        let [i0, i1, i2] = t.indices();
        let flat = t.v[0] & FLAT_BIT != 0;
        let (v0, v1, v2) = (&verts[i0], &verts[i1], &verts[i2]);
        let flat_rgb = v0.color();
        // Sort by y (for equal y the order does not matter: horizontal edges are unused),
        // moving references rather than 12-byte vertices.
        let mut p = [v0, v1, v2];
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
        let (ax, ay, bx, by, cx, cy) = (
            a.x as i32, a.y as i32, b.x as i32, b.y as i32, c.x as i32, c.y as i32,
        );
        let row_end = first_pixel(cy).min(height);
        let row_mid = first_pixel(by);
        if row >= row_end {
            return false;
        }
        let (dx1, dy1) = (bx - ax, by - ay);
        let (dx2, dy2) = (cx - ax, cy - ay);
        // |d| ≤ 32 766 each: 2·32 766² < 2³¹.
        let det = dx1 * dy2 - dx2 * dy1;
        if det == 0 {
            return false;
        }
        let mid_left = det < 0;
        let long = Edge::new(ax, ay, cx, cy, row);
        let short = if row < row_mid {
            Edge::new(ax, ay, bx, by, row)
        } else {
            Edge::new(bx, by, cx, cy, row)
        };
        let (left, right) = if mid_left {
            (short, long)
        } else {
            (long, short)
        };

        let (x_lo, x_hi) = (ax.min(bx).min(cx), ax.max(bx).max(cx));
        let small = (x_hi - x_lo) + (cy - ay) <= 1024 * SUBPIXELS;
        let fast = small
            && if flat {
                mode.fast_flat
            } else {
                mode.fast_gouraud
            };
        let tri = Sorted {
            v: [a, b, c],
            det,
            row,
            left_c: left.c as i32,
            left_sq: left.sq as i32,
        };
        #[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
        let done = fast
            && !flat
            && C::CHANNEL_MAX == [31, 63, 31]
            && crate::span_thumb::gouraud_setup(self, &tri);
        #[cfg(not(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32"))))]
        let done = false;
        if !done {
            #[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
            set_attribute_words::<C>(self, &tri, flat, fast, flat_rgb);
            #[cfg(not(all(
                target_arch = "arm",
                target_os = "none",
                not(target_has_atomic = "32")
            )))]
            {
                [self.gx, self.row, self.inc] = attribute_words::<C>(&tri, flat, fast, flat_rgb);
            }
        }
        let flags = (mid_left as u8 * MID_LEFT) | (flat as u8 * FLAT) | (fast as u8 * FAST);
        let ((lw, ldy), (rw, rdy)) = (left.dda(), right.dda());
        self.edges = [lw, rw];
        self.dy = [ldy, rdy];
        self.row_mid = row_mid as i16;
        self.row_end = row_end as i16;
        self.bx = bx as i16;
        self.by = by as i16;
        self.cx = cx as i16;
        self.cy = cy as i16;
        self.flags = flags;
        if fast && !flat && row < row_mid && row_mid < row_end {
            self.set_pending(Edge::new(bx, by, cx, cy, row_mid));
        }
        self.set_routine_rows(row, false);
        true
    }

    /// Keeps the short edge `b → c` at row `row_mid` for a fast Gouraud triangle, in the
    /// fourth words of `gx`, `row` and `inc`, which its packed attributes leave unused (the
    /// Cortex-M row routine and the portable [`ActiveTri::advance`] switch to it).
    fn set_pending(&mut self, e: Edge) {
        let (d, dy) = e.dda();
        self.gx[3] = d.w as i32;
        self.row[3] = d.s as i32;
        self.inc[3] = dy as i32;
    }

    /// The edge kept by [`ActiveTri::set_pending`].
    fn pending(&self) -> (EdgeDda, u16) {
        (
            EdgeDda {
                w: self.gx[3] as u32,
                s: self.row[3] as u32,
            },
            self.inc[3] as u16,
        )
    }

    /// Sets [`ActiveTri::routine_rows`] for `row`, the next row to draw: rows `x` from `row`
    /// on with `x + 1 < row_end` and `x + 1 ≠ row_mid`, up to the first that fails; and
    /// [`LAST_IN_ROUTINE`] when that one is the last row (`x + 1 = row_end`), or
    /// [`SWITCH_IN_ROUTINE`] when it is the row before the short edge's switch
    /// (`x + 1 = row_mid`), if the count reaches it.
    ///
    /// With `dithered` (the strip dithers its colour), a triangle without [`DITHER_OK`] gets
    /// no routine rows: the dithered Cortex-M row routine draws only `DITHER_OK` triangles
    /// and, so that it need not test the flag on every row, relies on this. A setup passes
    /// false: a fast Gouraud triangle set up while dithering has `DITHER_OK` or is set up again
    /// without the fast path ([`ActiveTri::setup_dither`]); a triangle set up while dithering
    /// was off gets its count again when dithering is switched on
    /// ([`ActiveList::refresh_routine_rows`]).
    #[inline(always)]
    fn set_routine_rows(&mut self, row: i32, dithered: bool) {
        let mut k = 0;
        self.flags &= !(LAST_IN_ROUTINE | SWITCH_IN_ROUTINE);
        if self.flags & (FAST | FLAT) == FAST && (!dithered || self.flags & DITHER_OK != 0) {
            let last = self.row_end as i32 - 1;
            let mid = self.row_mid as i32 - 1;
            let stop = if mid >= row && mid < last { mid } else { last };
            k = (stop - row).clamp(0, 255);
            if stop - row <= 255 {
                self.flags |= if stop == last {
                    LAST_IN_ROUTINE
                } else {
                    SWITCH_IN_ROUTINE
                };
            }
        }
        self.routine_rows = k as u8;
    }

    #[inline(always)]
    fn n_attrs(&self) -> usize {
        if self.flags & FLAT != 0 {
            1
        } else if self.flags & FAST != 0 {
            3
        } else {
            4
        }
    }

    /// The final channel bytes of a flat triangle.
    #[inline(always)]
    fn flat_channels(&self) -> [u8; 3] {
        let b = self.gx[1].to_le_bytes();
        [b[0], b[1], b[2]]
    }

    /// Moves to `next_row` (the row after the one just drawn).
    #[inline]
    fn advance(&mut self, next_row: i32) {
        let mid_left = self.flags & MID_LEFT != 0;
        // The short edge b → c from the switch on: a fast Gouraud triangle has it from setup
        // ([`ActiveTri::set_pending`], the one the Cortex-M row routine switches to).
        let switch = (next_row == self.row_mid as i32).then(|| {
            if self.flags & (FAST | FLAT) == FAST {
                self.pending()
            } else {
                Edge::new(
                    self.bx as i32,
                    self.by as i32,
                    self.cx as i32,
                    self.cy as i32,
                    next_row,
                )
                .dda()
            }
        });
        let [left, right] = &mut self.edges;
        let [left_dy, right_dy] = &mut self.dy;
        let (long, long_dy, short, short_dy) = if mid_left {
            (right, *right_dy, left, left_dy)
        } else {
            (left, *left_dy, right, right_dy)
        };
        let long_carry = long.step(long_dy);
        if let Some((new_short, new_dy)) = switch {
            if mid_left {
                // Carry the attribute rows over exactly: step along the old left edge's line
                // to the new row (`EdgeDda::peek`, in 32 bits: extrapolated past its lower end,
                // that column may leave the packed half), then move by whole pixels to the new
                // edge's first column, and change the row increment for the new edge's slope.
                let (c_old, carry) = short.peek();
                let dc = new_short.c() - c_old;
                let dsq = new_short.sq() - short.sq();
                *short = new_short;
                *short_dy = new_dy;
                self.step_attrs(carry);
                for k in 0..self.n_attrs() {
                    let g = self.gx[k];
                    self.row[k] = self.row[k].wrapping_add(g.wrapping_mul(dc));
                    self.inc[k] = self.inc[k].wrapping_add(g.wrapping_mul(dsq));
                }
                return;
            }
            *short = new_short;
            *short_dy = new_dy;
            self.step_attrs(long_carry);
        } else {
            let short_carry = short.step(*short_dy);
            self.step_attrs(if mid_left { short_carry } else { long_carry });
        }
    }

    #[inline(always)]
    fn step_attrs(&mut self, carry: bool) {
        // Unrolled for the three attribute counts.
        if self.flags & FLAT != 0 {
            self.step_first::<1>(carry);
        } else if self.flags & FAST != 0 {
            self.step_first::<3>(carry);
        } else {
            self.step_first::<4>(carry);
        }
    }

    #[inline(always)]
    fn step_first<const N: usize>(&mut self, carry: bool) {
        for k in 0..N {
            let mut v = self.row[k].wrapping_add(self.inc[k]);
            if carry {
                v = v.wrapping_add(self.gx[k]);
            }
            self.row[k] = v;
        }
    }

    /// Draws this triangle's span on `row` into one line of the strip and moves to the next
    /// row. Returns `(fragments tested, pixels written, finished)`.
    #[inline(never)]
    pub(crate) fn draw_row<C: TargetColor>(
        &mut self,
        row: i32,
        colors: &mut [C],
        depth: &mut [u16],
        test: DepthTest,
        dither: bool,
    ) -> (u32, u32, bool) {
        let width = colors.len().min(depth.len()) as i32;
        let (lc, rc) = (self.edges[0].c(), self.edges[1].c());
        let xs = lc.max(0);
        let xe = rc.min(width);
        let flat = self.flags & FLAT != 0;
        let mut counts = (0, 0);
        if self.flags & FAST != 0 {
            if xs < xe {
                // The common case, without clamps, dispatch or a span record.
                let (x0, x1) = (xs as usize, xe as usize);
                let skip = xs - lc;
                let mut v = [self.row[0], self.row[1], self.row[2]];
                if skip != 0 {
                    for k in 0..3 {
                        v[k] = v[k].wrapping_add(self.gx[k].wrapping_mul(skip));
                    }
                }
                let (zs, cs) = (&mut depth[x0..x1], &mut colors[x0..x1]);
                let written = if flat {
                    let c = C::from_channels(self.flat_channels());
                    span_flat::<C, LESS>(zs, cs, v[0], self.gx[0], c)
                } else if dither && C::can_dither() {
                    let (z, rb, g) = (
                        [v[0], self.gx[0]],
                        [v[1] as u32, self.gx[1] as u32],
                        [v[2], self.gx[2]],
                    );
                    if self.flags & DITHER_OK != 0 {
                        span_packed_dither::<C, LESS>(zs, cs, z, rb, g, x0, row)
                    } else {
                        span_packed_dither_clamped::<C>(zs, cs, z, rb, g, x0, row)
                    }
                } else {
                    span_packed::<C, LESS>(
                        zs,
                        cs,
                        [v[0], self.gx[0]],
                        [v[1] as u32, self.gx[1] as u32],
                        [v[2], self.gx[2]],
                    )
                };
                counts = ((xe - xs) as u32, written);
            }
        } else if xs < xe {
            let skip = xs - lc;
            let mut start = [0i32; 4];
            for k in 0..self.n_attrs() {
                let max = if k == 0 {
                    DEPTH_MAX << DEPTH_FRAC_BITS
                } else {
                    (C::CHANNEL_MAX[k - 1] as i32) << COLOR_FRAC_BITS
                };
                let v = if skip == 0 {
                    self.row[k]
                } else {
                    self.row[k].wrapping_add(self.gx[k].wrapping_mul(skip))
                };
                start[k] = v.clamp(0, max);
            }
            let span = Span {
                x0: xs as usize,
                x1: xe as usize,
                row,
                start,
                gx: self.gx,
            };
            let dither = dither && C::can_dither();
            let written = if flat {
                let c = C::from_channels(self.flat_channels());
                match test {
                    DepthTest::Less => span.fill_flat::<C, LESS>(colors, depth, c),
                    DepthTest::LessEqual => span.fill_flat::<C, LESS_EQUAL>(colors, depth, c),
                    DepthTest::Equal => span.fill_flat::<C, EQUAL>(colors, depth, c),
                    DepthTest::Always => span.fill_flat::<C, ALWAYS>(colors, depth, c),
                }
            } else {
                match test {
                    DepthTest::Less => span.fill_gouraud::<C, LESS>(colors, depth, dither),
                    DepthTest::LessEqual => {
                        span.fill_gouraud::<C, LESS_EQUAL>(colors, depth, dither)
                    }
                    DepthTest::Equal => span.fill_gouraud::<C, EQUAL>(colors, depth, dither),
                    DepthTest::Always => span.fill_gouraud::<C, ALWAYS>(colors, depth, dither),
                }
            };
            counts = ((xe - xs) as u32, written);
        }
        let next = row + 1;
        if next >= self.row_end as i32 {
            return (counts.0, counts.1, true);
        }
        self.advance(next);
        self.set_routine_rows(next, dither && C::can_dither());
        (counts.0, counts.1, false)
    }
}

/// Flat span: depth test `T`, constant colour. `z` carries the half-step rounding bias.
// A function of its own: inlined into the row loop, the pixel loop inherits that loop's
// register pressure and spills its accumulators on a Cortex-M0.
#[inline(never)]
fn span_flat<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    mut z: i32,
    gz: i32,
    color: C,
) -> u32 {
    // ARMv6-M only (the Arm profile without 32-bit atomics): on Thumb-2 cores LLVM's loop,
    // with post-indexed loads and conditional stores, measured faster than this routine.
    #[cfg(all(target_arch = "arm", target_os = "none", not(target_has_atomic = "32")))]
    if T == LESS && crate::span_thumb::rgb565_words::<C>() {
        return crate::span_thumb::span565_flat_less(zs, cs, z, gz, color);
    }
    let mut written = 0;
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

/// Gouraud span with red and blue packed in one accumulator (see
/// [`Span::fill_gouraud_packed`] for why that is exact), depth test `T`: `z`, `rb`, `g` are
/// `[start, per-pixel step]` in the packed formats ([`pack_zrgb`]) with their rounding biases
/// already added.
#[inline(never)]
fn span_packed<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
) -> u32 {
    #[cfg(all(target_arch = "arm", target_os = "none"))]
    if T == LESS && crate::span_thumb::rgb565_words::<C>() {
        return crate::span_thumb::span565_less(zs, cs, z, rb, g);
    }
    let ([mut z, gz], [mut rb, grb], [mut g, gg]) = (z, rb, g);
    let mut written = 0;
    for (zb, cb) in zs.iter_mut().zip(cs.iter_mut()) {
        let z16 = (z as u32 >> 16) as u16;
        if passes::<T>(z16, *zb) {
            *zb = z16;
            *cb = packed_color::<C>(rb, g as u32);
            written += 1;
        }
        z = z.wrapping_add(gz);
        rb = rb.wrapping_add(grb);
        g = g.wrapping_add(gg);
    }
    written
}

/// [`span_packed`] with 4×4 ordered dithering, for a [`DITHER_OK`] triangle: the pixels are
/// columns `x0..` of pixel row `row`, and each written pixel's packed red-blue and green
/// values get the offset of its column phase from [`dither_words`] before the channels are
/// read, so each channel is `floor(v + (2·B + 1)/32)` of the packed value `v` (the ½ bias
/// the start values carry and the offset `d` add up to the threshold). The accumulators step
/// as in [`span_packed`]. This is the definition the Cortex-M routine
/// (`span_thumb::span565_less_dither`, and the row routine's dithered variant) equals bit
/// for bit.
#[inline(never)]
fn span_packed_dither<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    #[cfg(all(target_arch = "arm", target_os = "none"))]
    if T == LESS && crate::span_thumb::rgb565_words::<C>() {
        return crate::span_thumb::span565_less_dither(zs, cs, z, rb, g, x0, row);
    }
    span_packed_dither_portable::<C, T>(zs, cs, z, rb, g, x0, row)
}

/// [`span_packed_dither`] in portable code (the twin of the Cortex-M routines).
#[inline(always)]
pub(crate) fn span_packed_dither_portable<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    let offsets = dither_words::<C>(row);
    let ([mut z, gz], [mut rb, grb], [mut g, gg]) = (z, rb, g);
    let mut written = 0;
    for (x, (zb, cb)) in (x0..).zip(zs.iter_mut().zip(cs.iter_mut())) {
        let z16 = (z as u32 >> 16) as u16;
        if passes::<T>(z16, *zb) {
            let [drb, dg] = offsets[x & 3];
            *zb = z16;
            *cb = packed_color::<C>(rb.wrapping_add(drb), (g as u32).wrapping_add(dg));
            written += 1;
        }
        z = z.wrapping_add(gz);
        rb = rb.wrapping_add(grb);
        g = g.wrapping_add(gg);
    }
    written
}

/// The dithered fast span (`DepthTest::Less`) for a fast triangle without [`DITHER_OK`] (its
/// packed values may come within 15/32 of a unit of a field's end, or it was set up while
/// dithering was off): each field is read out of the packed words (exact: the ½ bias keeps
/// every field inside `0..2¹⁶` at pixel centres of the triangle, see [`ActiveTri::row`]),
/// the offset `d` is added in an `i32` and the channel is clamped to its range. Portable on
/// every core (rare).
#[inline(never)]
fn span_packed_dither_clamped<C: TargetColor>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    let (fr, fb) = packed_frac_bits::<C>();
    let gbits = channel_bits(C::CHANNEL_MAX[1]);
    let bayer = &BAYER[(row & 3) as usize];
    let ([mut z, gz], [mut rb, grb], [mut g, gg]) = (z, rb, g);
    let q = |v: i64, frac: u32, max: u8| (v >> frac).clamp(0, max as i64) as u8;
    let mut written = 0;
    for (x, (zb, cb)) in (x0..).zip(zs.iter_mut().zip(cs.iter_mut())) {
        let z16 = (z as u32 >> 16) as u16;
        if z16 < *zb {
            let d = 2 * bayer[x & 3] as i64 - 15;
            *zb = z16;
            *cb = C::from_channels([
                q((rb >> 16) as i64 + (d << (fr - 5)), fr, C::CHANNEL_MAX[0]),
                q(
                    g as u32 as i64 + (d << (32 - gbits - 5)),
                    32 - gbits,
                    C::CHANNEL_MAX[1],
                ),
                q(
                    (rb & 0xffff) as i64 + (d << (fb - 5)),
                    fb,
                    C::CHANNEL_MAX[2],
                ),
            ]);
            written += 1;
        }
        z = z.wrapping_add(gz);
        rb = rb.wrapping_add(grb);
        g = g.wrapping_add(gg);
    }
    written
}

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

    fn fill_flat<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
        color: C,
    ) -> u32 {
        span_flat::<C, T>(
            &mut depth[self.x0..self.x1],
            &mut colors[self.x0..self.x1],
            self.z_start(),
            self.gx[0],
            color,
        )
    }

    fn fill_gouraud<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
        dither: bool,
    ) -> u32 {
        if dither {
            self.fill_gouraud_dither::<C, T>(colors, depth)
        } else if packable::<C>() && self.x1 - self.x0 <= 1024 {
            self.fill_gouraud_packed::<C, T>(colors, depth)
        } else {
            self.fill_gouraud_round::<C, T>(colors, depth)
        }
    }

    /// Gouraud span for channels of at most 6 bits (RGB565, RGB555, RGB666), rounding to
    /// nearest. Red and blue share one 32-bit accumulator as two 16-bit fields with
    /// `16 − bits` fraction bits each (red in the high half): `P = R·2¹⁶ + B` is exact as long
    /// as `B` stays in `0..2¹⁶`, which holds because the clamped start plus the half-step bias
    /// leaves `2^(15 − bits)` of headroom and rounding of the gradient drifts by at most ½ unit
    /// per pixel over at most 1024 pixels. Fewer live values keep the loop in registers on a
    /// Cortex-M0.
    // A function of its own: inlined into the row loop, the span loop inherits that loop's
    // register pressure and spills its accumulators on a Cortex-M0.
    fn fill_gouraud_packed<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
    ) -> u32 {
        // The stored gradients are the low 32 bits of the exact ones, which are the exact ones
        // whenever the span has two pixels or more: two pixel centres of one row inside the
        // triangle differ by less than a channel's range, so |gx| < 2⁸ units per pixel. (With
        // one pixel the gradient is never added.)
        let [s, g] = [self.start, self.gx].map(|w| w.map(|v| v as i64));
        let [z, rb, g0] = pack_zrgb::<C>(
            self.z_start() as i64,
            s[1],
            s[2] + (1 << (COLOR_FRAC_BITS - 1)),
            s[3],
        );
        let rb = (rb as u32).wrapping_add(packed_rb_half::<C>());
        let [gz, grb, gg] = pack_zrgb::<C>(g[0], g[1], g[2], g[3]);
        let (zs, cs) = (&mut depth[self.x0..self.x1], &mut colors[self.x0..self.x1]);
        span_packed::<C, T>(zs, cs, [z, gz], [rb, grb as u32], [g0, gg])
    }

    /// Gouraud span, rounding to nearest: the half is folded into the start values.
    // A function of its own: inlined into the row loop, the span loop inherits that loop's
    // register pressure and spills its accumulators on a Cortex-M0.
    #[inline(never)]
    fn fill_gouraud_round<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
    ) -> u32 {
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
    // A function of its own: inlined into the row loop, the span loop inherits that loop's
    // register pressure and spills its accumulators on a Cortex-M0.
    #[inline(never)]
    fn fill_gouraud_dither<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
    ) -> u32 {
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

/// For [`ActiveTri::dither_fits`]: whether a 16-bit field of the packed red-blue word (channel
/// `K`, `16 − bits` fraction bits), `F = f0 + (gx·dx + gy·dy)/16` at a vertex `(dx, dy)`
/// subpixels from the first pixel's centre with vertex colour `c`, is at least 15/32 of a unit
/// inside `0..2¹⁶` and within ¼ unit of the exact value plus the ½-unit bias. Each sum is below
/// 2³¹ (see `dither_fits`).
#[inline(always)]
fn field16_fits<C: TargetColor, const K: usize>(
    f0: i32,
    gx: i32,
    gy: i32,
    dx: i32,
    dy: i32,
    c: u16,
) -> bool {
    let frac = 16 - channel_bits(C::CHANNEL_MAX[K]);
    let vf = vertex_frac_bits(C::CHANNEL_MAX[K]);
    let (lo, e) = (15 << (frac - 5), 1 << (frac - 2));
    let v = 16 * f0 + gx * dx + gy * dy;
    let ideal = 16 * (((c as i32) << (frac - vf)) + (1 << (frac - 1)));
    // One unsigned comparison per interval: 16·lo ≤ v < 16·(2¹⁶ − lo), |v − ideal| ≤ 16·e.
    (v.wrapping_sub(16 * lo) as u32) < (16 * ((1 << 16) - 2 * lo)) as u32
        && (v.wrapping_sub(ideal).wrapping_add(16 * e) as u32) <= (32 * e) as u32
}

/// For [`ActiveTri::dither_fits`]: the same test for the green word (`32 − bits` fraction
/// bits, unsigned `a`): `16·F = 16·a + gx·dx + gy·dy` (a 64-bit value in principle) at least
/// `16·lo` and below `16·(2³² − lo)`, and within `16·e` of `16·ideal` ([`green_fits_wide`]
/// states it in 64 bits). A Cortex-M0 has no 64-bit arithmetic, so here `16·F` is formed as
/// `T·2¹⁶ + L` (`0 ≤ L < 2¹⁶`) in 32-bit operations: `T = 16·a_hi + gx_hi·dx + gy_hi·dy` plus
/// the carries of the low products `16·a_lo`, `gx_lo·dx`, `gy_lo·dy` (each |·| < 2³¹: |dx|,
/// |dy| ≤ 16 400). Every bound is a multiple of 2¹⁶ (`frac ≥ 24`, `frac − vf = 22` for the
/// packable colour types), so the comparisons need `T` alone, and `L` only for equality at
/// the upper bound of the distance. The same decisions (tested on random and extreme cases).
#[inline(always)]
fn green_fits<C: TargetColor>(a: u32, gx: i32, gy: i32, dx: i32, dy: i32, c: u16) -> bool {
    let frac = 32 - channel_bits(C::CHANNEL_MAX[1]);
    let vf = vertex_frac_bits(C::CHANNEL_MAX[1]);
    green_fits_split(a, gx, gy, dx, dy, c, frac, vf)
}

/// [`green_fits`] for `frac` and `vf` given (`frac ≥ 17`, `frac − vf ≥ 12`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn green_fits_split(
    a: u32,
    gx: i32,
    gy: i32,
    dx: i32,
    dy: i32,
    c: u16,
    frac: u32,
    vf: u32,
) -> bool {
    // The bounds over 2¹⁶: 16·lo, 16·(2³² − lo), 16·ideal and 16·e.
    let floor = 15 << (frac - 17);
    let ceil = (1 << 20) - floor;
    let ideal = ((c as i32) << (frac - vf - 12)) + (1 << (frac - 13));
    let e = 1 << (frac - 14);
    let (ah, al) = ((a >> 16) as i32, (a & 0xffff) as i32);
    let (p1, p2) = ((gx & 0xffff) * dx, (gy & 0xffff) * dy);
    let low = ((al << 4) & 0xffff) + (p1 & 0xffff) + (p2 & 0xffff);
    let t = 16 * ah
        + (gx >> 16) * dx
        + (gy >> 16) * dy
        + (al >> 12)
        + (p1 >> 16)
        + (p2 >> 16)
        + (low >> 16);
    let upper = ideal + e;
    t >= floor.max(ideal - e) && t < ceil && (t < upper || (t == upper && low & 0xffff == 0))
}

/// [`green_fits`] as it is specified, in 64-bit arithmetic (the reference of its test).
#[cfg(test)]
#[allow(clippy::too_many_arguments)]
fn green_fits_wide(a: u32, gx: i32, gy: i32, dx: i32, dy: i32, c: u16, frac: u32, vf: u32) -> bool {
    let (lo, e) = (15i64 << (frac - 5), 1i64 << (frac - 2));
    let v = 16 * a as i64 + gx as i64 * dx as i64 + gy as i64 * dy as i64;
    let ideal = 16 * (((c as i64) << (frac - vf)) + (1i64 << (frac - 1)));
    v >= 16 * lo && v < 16 * ((1i64 << 32) - lo) && (v - ideal).abs() <= 16 * e
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dithered Cortex-M row routine draws every triangle with routine rows; so in a
    /// dithered strip only `DITHER_OK` ones may have them, including triangles set up before
    /// dithering was switched on mid-frame (`ActiveList::refresh_routine_rows`).
    #[test]
    fn routine_rows_in_a_dithered_strip_need_dither_ok() {
        use embedded_graphics_core::pixelcolor::Rgb565;
        let mut v = [ScreenVertex::default(); 3];
        for (p, (x, y)) in v.iter_mut().zip([(80, 16), (400, 300), (40, 600)]) {
            (p.x, p.y) = (x, y);
            p.set_color([400, 500, 300]);
        }
        let t = TriRecord { v: [0, 1, 2] };
        let plain = SpanMode::new::<Rgb565>(DepthTest::Less, false);
        let mut list = ActiveList::<4>::new();
        assert!(list.push_with(|r| r.setup::<Rgb565>(&t, &v, 1, 240, plain)));
        let rows = list.slots[0].routine_rows;
        assert!(rows > 0 && list.slots[0].flags & (FAST | DITHER_OK) == FAST);
        list.refresh_routine_rows(1, true);
        assert_eq!(list.slots[0].routine_rows, 0);
        assert_eq!(
            list.slots[0].flags & (LAST_IN_ROUTINE | SWITCH_IN_ROUTINE),
            0
        );
        list.refresh_routine_rows(1, false);
        assert_eq!(list.slots[0].routine_rows, rows);
        // Set up while dithering: checked, so it keeps its rows in a dithered strip.
        let dithered = SpanMode::new::<Rgb565>(DepthTest::Less, true);
        let mut list = ActiveList::<4>::new();
        assert!(list.push_with(|r| r.setup::<Rgb565>(&t, &v, 1, 240, dithered)));
        assert!(list.slots[0].flags & DITHER_OK != 0);
        list.refresh_routine_rows(1, true);
        assert_eq!(list.slots[0].routine_rows, rows);
    }

    #[test]
    fn green_fits_equals_its_64_bit_specification() {
        let mut rnd = xorshift32(0x9e37_79b9);
        let edges = [
            0,
            1,
            -1,
            i32::MAX,
            i32::MIN,
            1 << 16,
            -(1 << 16),
            0xffff,
            -0xffff,
        ];
        let mut agree = [0u32; 2];
        for k in 0..400_000u32 {
            let (gx, gy) = if k % 4 == 0 {
                (edges[rnd() as usize % 9], edges[rnd() as usize % 9])
            } else {
                // Mostly a real triangle's small gradients, some anywhere.
                let g = |r: u32, s: u32| {
                    if s % 3 == 0 {
                        r as i32
                    } else {
                        (r as i32) >> (8 + s % 16)
                    }
                };
                (g(rnd(), rnd()), g(rnd(), rnd()))
            };
            let a = if k % 8 == 0 {
                [0, u32::MAX, 1 << 31, 15 << 21][rnd() as usize % 4]
            } else {
                rnd()
            };
            let r = rnd();
            let v = |r: u32| {
                if r % 7 == 0 {
                    [16_400, -16_400, 0][r as usize % 3]
                } else {
                    (r % 32_801) as i32 - 16_400
                }
            };
            let (dx, dy) = (v(r), v(r.rotate_left(16)));
            let (frac, vf) = [(26, 4), (24, 2), (25, 3)][k as usize % 3];
            // Half the cases: the colour the field itself rounds to (±1), so many pass; and
            // exactly at the distance bound now and then.
            let c = if k % 2 == 0 {
                let f = 16 * a as i64 + gx as i64 * dx as i64 + gy as i64 * dy as i64;
                let unit = 16i64 << (frac - vf);
                ((f - (16i64 << (frac - 1)) + unit / 2).div_euclid(unit) + (rnd() % 3) as i64 - 1)
                    .clamp(0, 1023) as u16
            } else {
                rnd() as u16 % 1024
            };
            let fast = green_fits_split(a, gx, gy, dx, dy, c, frac, vf);
            assert_eq!(
                fast,
                green_fits_wide(a, gx, gy, dx, dy, c, frac, vf),
                "a {a:#x} gx {gx} gy {gy} d ({dx}, {dy}) c {c} frac {frac}"
            );
            agree[fast as usize] += 1;
        }
        // At the distance bound exactly (16·F = 16·ideal ± 16·e), both sides.
        for (frac, vf) in [(26u32, 4u32), (24, 2)] {
            for c in [0u16, 1, 512, 1023] {
                let ideal = 16 * (((c as i64) << (frac - vf)) + (1i64 << (frac - 1)));
                for target in [ideal + (16i64 << (frac - 2)), ideal - (16i64 << (frac - 2))] {
                    for nudge in [-1i64, 0, 1] {
                        // 16·a = target + nudge with dx = 1, gx = the remainder.
                        let t = target + nudge;
                        let a = (t.div_euclid(16)).clamp(0, u32::MAX as i64) as u32;
                        let gx = (t - 16 * a as i64) as i32;
                        assert_eq!(
                            green_fits_split(a, gx, 0, 1, 0, c, frac, vf),
                            green_fits_wide(a, gx, 0, 1, 0, c, frac, vf),
                            "bound c {c} frac {frac} nudge {nudge}"
                        );
                    }
                }
            }
        }
        assert!(agree[0] > 10_000 && agree[1] > 10_000, "{agree:?}");
    }

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
            (-16383, -16383, 16383, 16383),
            (16383, -16383, -16383, 16383),
            (-16383, 100, 16383, 101),
        ];
        for (xa, ya, xb, yb) in cases {
            let first = first_pixel(ya);
            let end = first_pixel(yb);
            let (mut e, dy) = Edge::new(xa, ya, xb, yb, first).dda();
            for row in first..end.min(first + 3000) {
                assert_eq!(
                    e.c(),
                    reference(xa, ya, xb, yb, row),
                    "edge {xa},{ya}->{xb},{yb} row {row}"
                );
                let (c, carry) = e.peek();
                assert_eq!(e.step(dy), carry);
                if row + 1 < end {
                    assert_eq!(e.c(), c);
                }
            }
            // Starting anywhere gives the same value.
            let mid = (first + end) / 2;
            assert_eq!(
                Edge::new(xa, ya, xb, yb, mid).c as i32,
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
    fn reciprocal_is_accurate_to_28_bits_over_the_full_range() {
        let mut worst = 0.0f64;
        let mut d = 1i64;
        while d < 1 << 60 {
            for k in [d, d + 1, d / 2 * 3 + 7, -d, -(d / 4 * 5) - 3] {
                let r = Reciprocal::new(k);
                let sign = if r.neg { -1.0 } else { 1.0 };
                let got = sign * r.m as f64 * 2f64.powi(-(r.e as i32));
                worst = worst.max((got * k as f64 - 1.0).abs());
            }
            d = d * 3 + 1;
        }
        assert!(worst < 2f64.powi(-28), "worst relative error {worst:e}");
    }

    #[test]
    fn active_list_keeps_vector_order() {
        // The same pushes and removals on the list and on a plain vector of ids.
        let mut list = ActiveList::<40>::new();
        let mut ids: Vec<i16, 40> = Vec::new();
        let mut next = 0i16;
        for step in 0..400u32 {
            if step % 3 != 2 && list.len() < 40 {
                assert!(list.push_with(|t| {
                    t.row_end = next;
                    true
                }));
                ids.push(next).unwrap();
                next += 1;
            } else if list.len() > 0 {
                let i = (step as usize * 7) % list.len();
                list.swap_remove(i);
                ids.swap_remove(i);
            }
            assert!(!list.push_with(|_| false) || list.len() < 40);
            for (i, &id) in ids.iter().enumerate() {
                assert_eq!(list.get_mut(i).row_end, id, "step {step} entry {i}");
            }
        }
        let mut full = ActiveList::<2>::new();
        assert!(full.push_with(|_| true) && full.push_with(|_| true));
        assert!(!full.push_with(|_| true));
        assert_eq!(ActiveList::<2>::MAX, 32768);
    }

    #[test]
    fn coefficient_products_match_64_bits() {
        // Every shift, the extreme and a spread of mantissas, and every v at the edges of
        // its range and a stride through it.
        let ms = [
            1i32,
            2,
            0x7fff,
            0x8000,
            (1 << 29) + 1,
            0x2aaa_aaab,
            0x3fff_ffff,
            1 << 30,
        ];
        for l in 1..=16u32 {
            let lim = 1i32 << l;
            let step = (lim / 97).max(1);
            let vs = (-lim + 1..lim)
                .step_by(step as usize)
                .chain([-lim + 1, -1, 0, 1, lim - 1]);
            for v in vs {
                for &m in &ms {
                    let want = (m as i64 * v as i64) >> l;
                    assert_eq!(mul_shr_16(m, v, l) as i64, want, "{m} {v} {l}");
                }
            }
        }
    }

    #[test]
    fn small_divisions_match_the_library() {
        let ns = [
            0i32,
            1,
            2,
            7,
            15,
            16,
            17,
            255,
            1000,
            32766,
            65535,
            1 << 30,
            i32::MAX,
        ];
        let ds = [1i32, 2, 3, 16, 17, 1000, 32766, 1 << 20, i32::MAX];
        for &n in &ns {
            for &d in &ds {
                let want = (n as u32 / d as u32, n as u32 % d as u32);
                assert_eq!(udiv_small(n as u32, d as u32), want);
                assert_eq!(udiv_shift_subtract(n as u32, d as u32), want);
                for m in [n, -n, -n - 1] {
                    let want = (m.div_euclid(d), m.rem_euclid(d));
                    assert_eq!(div_floor_small(m, d), want, "{m} / {d}");
                }
            }
        }
    }

    /// Dithered Gouraud triangles (RGB565) on pseudo-random triangles that take the fast path
    /// without dithering, small to the fast path's largest, with colours over the whole range
    /// (channels at 0 and at the maximum included, and changes across the whole range): row by
    /// row through `draw_row`,
    /// - a triangle is either fast with [`DITHER_OK`] or not fast at all;
    /// - a [`DITHER_OK`] triangle's spans ([`span_packed_dither`]) equal those of the same
    ///   record drawn by the clamped span, which reads each field separately: no carry
    ///   between fields and no field leaving its range, at any pixel;
    /// - every pixel of a fast triangle is within 1 LSB per channel of the exact dithered
    ///   quantization of the plane through the vertex colours at its centre,
    ///   `floor(v + (2·B + 1)/32)`.
    #[test]
    fn dithered_fast_span_is_exact_and_within_one_lsb() {
        use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
        let mut next = xorshift32(0x2468_ace1);
        let mode = SpanMode::new::<Rgb565>(DepthTest::Less, true);
        assert!(mode.fast_gouraud && mode.dither);
        const W: usize = 1100;
        let (mut ok, mut slow, mut pixels, mut worst) = (0u32, 0u32, 0u64, [0i32; 3]);
        for i in 0..6000u32 {
            let size = [24i32, 160, 1200, 8000][(i % 4) as usize];
            let mut v = [ScreenVertex::default(); 3];
            for p in &mut v {
                let r = next();
                p.x = (400 + (r % size as u32) as i32) as i16;
                p.y = (300 + ((r >> 16) % size as u32) as i32) as i16;
                p.z = 1000 + (next() % 5000) as u16;
                let c = next();
                let pick = |k: u32, max: u16| match (c >> (k * 8)) & 3 {
                    0 => 0,
                    1 => max,
                    _ => ((c >> (k * 8 + 2)) % (max as u32 + 1)) as u16,
                };
                p.set_color([pick(0, 992), pick(1, 1008), pick(2, 992)]);
            }
            let t = TriRecord { v: [0, 1, 2] };
            let row0 = v.iter().map(|p| first_pixel(p.y as i32)).min().unwrap();
            let mut rec = ActiveTri::EMPTY;
            let plain = SpanMode {
                dither: false,
                ..mode
            };
            if !rec.setup::<Rgb565>(&t, &v, row0, 1024, plain) || rec.flags & FAST == 0 {
                continue;
            }
            assert!(rec.setup::<Rgb565>(&t, &v, row0, 1024, mode));
            let safe = rec.flags & DITHER_OK != 0;
            if safe {
                ok += 1;
            } else {
                assert_eq!(rec.flags & FAST, 0, "a fast triangle without DITHER_OK");
                slow += 1;
            }
            let mut other = rec.clone();
            other.flags &= !DITHER_OK;
            // The exact plane through the vertex colours (channel units).
            let [a, b, c] = v.map(|p| (p.x as f64 / 16.0, p.y as f64 / 16.0, p.color()));
            let det = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
            let scale = [32.0, 16.0, 32.0];
            let mut row = row0.max(0);
            loop {
                let mut cs = [Rgb565::BLACK; W];
                let mut zs = [u16::MAX; W];
                let (mut cs2, mut zs2) = (cs, zs);
                let (_, _, done) = rec.draw_row(row, &mut cs, &mut zs, DepthTest::Less, true);
                let _ = other.draw_row(row, &mut cs2, &mut zs2, DepthTest::Less, true);
                if safe {
                    assert_eq!(
                        cs, cs2,
                        "triangle {i} row {row}: fast and clamped spans differ"
                    );
                }
                let yc = row as f64 + 0.5;
                for x in 0..W {
                    // Triangles set up without the fast path are drawn by the dithered span
                    // of before (the same code): only the fast ones are compared here.
                    if zs[x] == u16::MAX || !safe {
                        continue;
                    }
                    pixels += 1;
                    let xc = x as f64 + 0.5;
                    let l1 = ((xc - a.0) * (c.1 - a.1) - (c.0 - a.0) * (yc - a.1)) / det;
                    let l2 = ((b.0 - a.0) * (yc - a.1) - (xc - a.0) * (b.1 - a.1)) / det;
                    let th = (2.0 * BAYER[(row & 3) as usize][x & 3] as f64 + 1.0) / 32.0;
                    let got = [cs[x].r(), cs[x].g(), cs[x].b()];
                    for k in 0..3 {
                        let val = (a.2[k] as f64
                            + l1 * (b.2[k] as f64 - a.2[k] as f64)
                            + l2 * (c.2[k] as f64 - a.2[k] as f64))
                            / scale[k];
                        let max = [31.0, 63.0, 31.0][k];
                        let want = (val + th).floor().clamp(0.0, max) as i32;
                        let e = (got[k] as i32 - want).abs();
                        worst[k] = worst[k].max(e);
                        assert!(e <= 1, "triangle {i} (DITHER_OK {safe}, {v:?}) pixel ({x}, {row}) channel {k}: {} vs exact {want} ({val})", got[k]);
                    }
                }
                if done {
                    break;
                }
                row += 1;
            }
        }
        extern crate std;
        std::println!(
            "triangles fast without dithering: {ok} fast and DITHER_OK with it, {slow} set up without the fast path; {pixels} pixels, worst |Δ| per channel against the exact dithered value {worst:?} LSB"
        );
        assert!(ok > 1000 && slow > 0);
    }

    #[test]
    fn dither_words_are_the_thresholds() {
        use embedded_graphics_core::pixelcolor::Rgb565;
        for row in 0..4 {
            for (p, [rb, g]) in dither_words::<Rgb565>(row).into_iter().enumerate() {
                let d = 2 * BAYER[row as usize][p] as i32 - 15;
                // ½ (the start values' bias) + d = (2·B + 1)/32 of a unit.
                assert_eq!((rb & 0xffff) as i16 as i32, d * 64);
                assert_eq!(
                    (rb.wrapping_sub(rb as i16 as i32 as u32) as i32) >> 16,
                    d * 64
                );
                assert_eq!(g as i32, d << 21);
                assert_eq!(1024 + d * 64, (2 * BAYER[row as usize][p] as i32 + 1) * 64);
            }
        }
    }

    #[test]
    fn floor_division_both_paths() {
        // Quotients are pixel columns: always within i32, numerators up to 2^47.
        for (n, d) in [
            (7i64, 2i32),
            (-7, 2),
            (0, 5),
            (-(1 << 40), 1 << 20),
            ((1 << 46) + 1, 1 << 27),
        ] {
            let (q, r) = div_floor(n, d);
            let dd = d as i64;
            assert_eq!((q as i64, r as i64), (n.div_euclid(dd), n.rem_euclid(dd)));
        }
    }
}
