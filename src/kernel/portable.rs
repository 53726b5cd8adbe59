//! The portable implementations of the kernels that have one of their own (the edge setup,
//! the cull loop, the line clear, the small floor division); the other kernels' portable
//! twins are the stages' generic code, which the kernel entry points leave the work to
//! (`kernel` lists each kernel with its twin).

use crate::kernel::records::{
    facing, Bins, CullCounts, CullStop, Edge, EdgeDda, Facing, ScreenVertex, TriRecord, C_BIAS,
    INVALID, LIT, NEEDS_CLIP, NEEDS_LIGHT, SUBPIXELS, SUBPIXEL_BITS,
};
use crate::kernel::udiv_small;
use crate::kernel::wide::div_floor;

impl Edge {
    /// [`Edge::new`] in portable code. Out of line where the edge kernel runs (ARMv6-M: it
    /// is the rare path there, and inlined its spills would grow the setup's frame).
    #[cfg_attr(scanline3d_no_divide, inline(never))]
    #[cfg_attr(not(scanline3d_no_divide), inline)]
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
            let q = t >> SUBPIXEL_BITS;
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

/// `(floor(n / d), n − d·floor(n / d))` for `d > 0`, by [`crate::kernel::udiv_small`]: for `n < 0`,
/// `floor(n/d) = −1 − floor((−n − 1)/d)`, and `−n − 1 = !n` has no overflow.
#[inline]
pub(crate) fn div_floor_small(n: i32, d: i32) -> (i32, i32) {
    if n < 0 {
        let (q, r) = udiv_small(!n as u32, d as u32);
        (!(q as i32), d - 1 - r as i32)
    } else {
        let (q, r) = udiv_small(n as u32, d as u32);
        (q as i32, r as i32)
    }
}

/// [`crate::kernel::cull_push`] in Rust: the portable implementation and the Thumb kernel's twin.
pub(crate) fn cull_push<const T: usize>(
    tris: &[[u16; 3]],
    k: &mut usize,
    verts: &mut [ScreenVertex],
    base: u16,
    mut bins: Bins<'_, T>,
    n: &mut CullCounts,
    needed: &mut usize,
) -> CullStop {
    while let Some(tri) = tris.get(*k) {
        let (Some(a), Some(b), Some(c)) = (
            verts.get(tri[0] as usize),
            verts.get(tri[1] as usize),
            verts.get(tri[2] as usize),
        ) else {
            return CullStop::Portable;
        };
        if (a.flags | b.flags | c.flags) & (INVALID | NEEDS_CLIP as u16) != 0 {
            return CullStop::Portable;
        }
        let all = a.flags & b.flags & c.flags;
        if all & 0x3f != 0 {
            n.outside += 1;
        } else {
            match facing(a, b, c) {
                Facing::Degenerate => n.degenerate += 1,
                Facing::Back => n.culled += 1,
                Facing::Front => {
                    let v = tri.map(|i| base.wrapping_add(i));
                    let stored = bins.push(TriRecord { v }, [a, b, c], n, needed);
                    if stored && all & LIT == 0 {
                        for &i in tri {
                            if let Some(v) = verts.get_mut(i as usize) {
                                if v.flags & LIT == 0 {
                                    v.flags |= NEEDS_LIGHT;
                                }
                            }
                        }
                    }
                }
            }
        }
        *k += 1;
    }
    CullStop::Done
}

/// Clears an RGB565 line: colour `background`, depth 65535.
#[cfg_attr(scanline3d_thumb, allow(dead_code))]
#[inline(always)]
pub(crate) fn clear_line(colors: &mut [u16], depth: &mut [u16], background: u16) {
    colors.fill(background);
    depth.fill(u16::MAX);
}
