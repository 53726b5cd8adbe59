//! The edge setup (`kernel::edge_new`): an edge's column and remainders on a row by shift
//! and subtract (no divide instruction on ARMv6-M), and the edge macros the triangle setup
//! reuses.
#![allow(unsafe_code)]

use super::offsets as o;
use crate::kernel::records::Edge;

extern "C" {
    fn scanline3d_edge_new(a: u32, b: u32, row: i32, out: *mut Edge) -> u32;
}

/// `(n / d, n % d)` for `0 ≤ n < 2³¹`, `d ≥ 1` by shift and subtract, one step per quotient
/// bit, as `raster::udiv_small`: `$q` = quotient, `$n` = remainder. Uses `$dd`, `$bit` and
/// `$half`; labels 6–9.
macro_rules! udiv_small {
    ($n:literal, $d:literal, $q:literal, $dd:literal, $bit:literal, $half:literal) => {
        concat!(
            "movs ", $q, ", #0\n", "cmp ", $n, ", ", $d, "\n", "bcc 9f\n", "movs ", $bit, ", #1\n",
            "mov ", $dd, ", ", $d, "\n", "lsrs ", $half, ", ", $n, ", #1\n",
            // dd = d·bit ≤ n < 2·dd.
            "8:\n", "cmp ", $dd, ", ", $half, "\n", "bhi 7f\n", "lsls ", $dd, ", ", $dd, ", #1\n",
            "lsls ", $bit, ", ", $bit, ", #1\n", "b 8b\n", "7:\n", "cmp ", $n, ", ", $dd, "\n",
            "bcc 6f\n", "subs ", $n, ", ", $n, ", ", $dd, "\n", "orrs ", $q, ", ", $bit, "\n",
            "6:\n", "lsrs ", $dd, ", ", $dd, ", #1\n", "lsrs ", $bit, ", ", $bit, ", #1\n",
            "bne 7b\n", "9:\n",
        )
    };
}

/// The steps of `raster::Edge::new_portable` for [`scanline3d_edge_new`] and the triangle
/// setup's edges ([`edge_dda_inline`]): from r0 = xa | ya << 16, r1 = xb | yb << 16,
/// r2 = row, with r4–r7 and lr saved, to `$q` with r0 = sq, r6 = sr, r7 = dy (r3 untouched so far), then to `$c`
/// with r1 = c, r5 = e; a row outside 0 ≤ k ≤ dy + 16 (k = 16·row + 8 − ya) branches to
/// label 2.
macro_rules! edge_steps {
    ($q:expr, $c:expr) => {
        concat!(
            "push {{r4, r5, r6, r7, lr}}\n",
            edge_body!("bhi 2f\n", $q, $c)
        )
    };
}

/// The body of [`edge_steps`] (without saving registers; r12 and lr are free): `$out` is
/// where a row outside the edge's goes, branching on `hi` after the row test.
macro_rules! edge_body {
    ($out:expr, $q:expr, $c:expr) => {
        concat!(
            "sxth r4, r0\n",
            "asrs r5, r0, #16\n",
            "sxth r6, r1\n",
            "asrs r7, r1, #16\n",
            // dy = max(1, yb − ya), dx = xb − xa.
            "subs r7, r7, r5\n",
            "bgt 1f\n",
            "movs r7, #1\n",
            "1:\n",
            "subs r6, r6, r4\n",
            // k = 16·row + 8 − ya, in 0..=dy + 16 (unsigned, so k < 0 fails too).
            "lsls r2, r2, #4\n",
            "adds r2, #8\n",
            "subs r2, r2, r5\n",
            "movs r5, r7\n",
            "adds r5, #16\n",
            "cmp r2, r5\n",
            $out,
            // r12 = k, lr = xa, r3 = the edge (no stack beyond the saved registers: this runs at
            // the deepest point of a frame, which on a 16 KB part sets the largest frame size).
            "mov r12, r2\n",
            "mov lr, r4\n",
            // (sq, sr) = floor division of dx by dy: for dx < 0 (mask r5 = −1) from !dx:
            // sq = !q, sr = dy − 1 − r. Stored at once with dy.
            "asrs r5, r6, #31\n",
            "eors r6, r5\n",
            udiv_small!("r6", "r7", "r0", "r1", "r2", "r4"),
            "eors r0, r5\n",
            "cmp r5, #0\n",
            "beq 3f\n",
            "subs r6, r7, r6\n",
            "subs r6, #1\n",
            "3:\n",
            $q,
            // lr = xa − 8 + k·sq; (qb, rb) = (k·sr) / dy.
            "mov r1, r12\n",
            "muls r0, r1\n",
            "mov r2, lr\n",
            "adds r0, r0, r2\n",
            "subs r0, #8\n",
            "mov lr, r0\n",
            "mov r4, r12\n",
            "muls r4, r6\n",
            udiv_small!("r4", "r7", "r0", "r1", "r2", "r5"),
            // t = xa − 8 + k·sq + qb; r = dy·(t & 15) + rb; q = t >> 4.
            "mov r1, lr\n",
            "adds r1, r1, r0\n",
            "movs r2, #15\n",
            "ands r2, r1\n",
            "muls r2, r7\n",
            "adds r2, r2, r4\n",
            "asrs r1, r1, #4\n",
            // r = 0: (c, e) = (q, 0); else (q + 1, (16·dy − r) >> 4).
            "movs r5, #0\n",
            "cmp r2, #0\n",
            "beq 4f\n",
            "adds r1, #1\n",
            "lsls r5, r7, #4\n",
            "subs r5, r5, r2\n",
            "asrs r5, r5, #4\n",
            "4:\n",
            $c,
        )
    };
}

/// For [`edge_body`] in the row loops' form (`raster::Edge::dda`): r3 = s = sq − sr·2¹⁶.
macro_rules! dda_q {
    () => {
        "lsls r3, r6, #16\nsubs r3, r0, r3\n"
    };
}

/// For [`edge_body`] in the row loops' form (`raster::Edge::dda`): r1 = w = e·2¹⁶ + c + 2¹⁵, r2 = s,
/// r3 = dy.
macro_rules! dda_c {
    () => {
        concat!(
            "lsls r5, r5, #16\n",
            "adds r1, r1, r5\n",
            "movs r2, #128\n",
            "lsls r2, r2, #8\n",
            "adds r1, r1, r2\n",
            "mov r2, r3\n",
            "mov r3, r7\n",
        )
    };
}

/// For [`scanline3d_setup565`]: [`scanline3d_edge_new`]'s steps in line, with the edge in the row
/// loops' form (the setup has saved r4–r7 and lr and keeps nothing in r4–r7, r12 or lr across
/// it; in line, it saves a call, a return and the saving of five registers per edge): from r0 = a, r1 = b, r2 = row to r1 = w,
/// r2 = s, r3 = dy; a row outside the edge's declines (`.Lsu_decline`).
macro_rules! edge_dda_inline {
    () => {
        edge_body!("bls 5f\nb .Lsu_decline\n5:\n", dda_q!(), dda_c!())
    };
}

/// For [`scanline3d_setup565`]: the edge that [`edge_dda_inline`] computed (r1 = w,
/// r2 = s, r3 = dy) into slot r6 (0 = left, 1 = right) of the record; the left edge's column
/// (`(w & 0xffff) − 2¹⁵`) and step (`s` as an `i16`) also into the frame's `raster::Sorted`.
/// Uses r4, r5, r7.
macro_rules! edge_to_record {
    () => {
        concat!(
            "cmp r6, #0\n",
            "bne 1f\n",
            "uxth r4, r1\n",
            "movs r5, #128\n",
            "lsls r5, r5, #8\n",
            "subs r4, r4, r5\n",
            "str r4, [sp, #su_lc]\n",
            "sxth r4, r2\n",
            "str r4, [sp, #su_lsq]\n",
            "1:\n",
            "ldr r7, [sp, #su_rec]\n",
            "lsls r5, r6, #1\n",
            "adds r5, r7, r5\n",
            "strh r3, [r5, #{left_dy}]\n",
            "lsls r5, r6, #3\n",
            "adds r5, r7, r5\n",
            "str r1, [r5, #{left_w}]\n",
            "str r2, [r5, #{left_s}]\n",
        )
    };
}

/// For [`scanline3d_setup565`]: `raster::first_pixel(v)` = `(v + 7) >> 4` of `$v` into `$d`.
macro_rules! first_pixel {
    ($d:literal, $v:literal) => {
        concat!("adds ", $d, ", ", $v, ", #7\n", "asrs ", $d, ", ", $d, ", #4\n")
    };
}

/// For [`scanline3d_setup565`]: if the vertex at `$q` is above the one at `$p` (a smaller y,
/// the halfword at offset 2), swaps the pointers. Uses r3, r4.
macro_rules! sort_step {
    ($p:literal, $q:literal) => {
        concat!(
            "ldrh r3, [",
            $p,
            ", #2]\n",
            "sxth r3, r3\n",
            "ldrh r4, [",
            $q,
            ", #2]\n",
            "sxth r4, r4\n",
            "cmp r4, r3\n",
            "bge 1f\n",
            "mov r3, ",
            $p,
            "\n",
            "mov ",
            $p,
            ", ",
            $q,
            "\n",
            "mov ",
            $q,
            ", r3\n",
            "1:\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_edge_new,\"ax\",%progbits",
    ".global scanline3d_edge_new",
    ".type scanline3d_edge_new,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = xa | ya << 16, r1 = xb | yb << 16 (16-bit halves), r2 = row, r3 = the `Edge` to
    // write. `raster::Edge::new_portable`'s steps for 0 ≤ k ≤ dy + 16 (k = 16·row + 8 − ya):
    // returns 1 having written the edge, or 0 (nothing written) for any other row.
    "scanline3d_edge_new:",
    edge_steps!(
        "strh r0, [r3, #{sq}]\nstrh r6, [r3, #{sr}]\nstrh r7, [r3, #{dy}]\n",
        "strh r1, [r3, #{c}]\nstrh r5, [r3, #{e}]\nmovs r0, #1\npop {{r4, r5, r6, r7, pc}}\n"
    ),
    "2:",
    "movs r0, #0",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_edge_new, . - scanline3d_edge_new",
    c = const o::EDGE_C,
    sq = const o::EDGE_SQ,
    e = const o::EDGE_E,
    sr = const o::EDGE_SR,
    dy = const o::EDGE_DY,
);

/// `raster::Edge::new` for a row from the edge's first sample on (`0 ≤ k ≤ dy + 16`, the
/// rows the renderer sets edges up on) by [`scanline3d_edge_new`], for coordinates that fit
/// 16 bits (snapped ones always do); `None` otherwise.
#[inline(always)]
pub(crate) fn edge_new(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> Option<Edge> {
    if [xa, ya, xb, yb].iter().any(|&v| v != v as i16 as i32) {
        return None;
    }
    let pack = |x: i32, y: i32| (x as u16 as u32) | (y as u32) << 16;
    let mut e = core::mem::MaybeUninit::<Edge>::uninit();
    // SAFETY: the routine reads nothing but its arguments and, when it returns 1, has written
    // all five 16-bit fields of `e` (at the offsets given to it, `#[repr(C)]`; the struct has
    // no padding), so `e` is then initialized.
    unsafe {
        if scanline3d_edge_new(pack(xa, ya), pack(xb, yb), row, e.as_mut_ptr()) != 0 {
            Some(e.assume_init())
        } else {
            None
        }
    }
}
