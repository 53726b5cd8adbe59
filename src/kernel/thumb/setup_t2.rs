//! The triangle setup of a fast Gouraud triangle with RGB565 channels in Thumb-2 (ARMv7-M and
//! later: the `scanline3d_thumb2` cfg): `scanline3d_setup565` and `scanline3d_gouraud_setup`
//! with the same interfaces and results as their Thumb-1 forms (`setup`, `gouraud`), written
//! for the long multiplies (`smull`, `smlal`, `umull`), `clz`, the divide instructions, `mla`
//! and `mls`, shifted operands, `ubfx` and conditional execution, with r8–r12 as ordinary
//! registers. The Thumb-1 forms stay on ARMv6-M, unchanged.
//!
//! Both entry points share one attribute routine (`scanline3d_gouraud_t2`, an internal
//! interface in registers); the triangle setup computes the edges in line ([`edge_t2`]).
#![allow(unsafe_code)]

use super::offsets as o;
use crate::kernel::records::ScreenVertex;

// `channel_g_t2`'s word: green's byte and the flags (its low bits at flag bits 12–13) in one
// aligned word of a 4-aligned vertex.
const _: () = {
    use crate::kernel::records::{FLAGS_OFFSET, RGB_HI_OFFSET};
    assert!((RGB_HI_OFFSET + 1) % 4 == 0 && FLAGS_OFFSET == RGB_HI_OFFSET + 3);
    assert!(core::mem::align_of::<ScreenVertex>() >= 4);
};

/// `raster::Edge::new_portable`'s steps, then the row loops' form (`raster::Edge::dda`), for
/// [`scanline3d_setup565`]: from r0 = xa, r1 = ya, r2 = xb, r3 = yb (`ya ≤ yb`) and the row in
/// `$row` (not r0–r6) to r5 = w, r6 = s, r3 = dy, with r0 = c and r2 = sq. The floor division
/// of dx by dy is the unsigned one of dx + 2¹⁵·dy (positive: |dx| < 2¹⁵); a row outside
/// 0 ≤ k ≤ dy + 16 (k = 16·row + 8 − ya) declines. The column and its remainder (the portable
/// t = xa − 8 + k·sq + (k·sr) / dy, q = t >> 4, r = dy·(t & 15) + (k·sr) % dy) are those of
/// one floor division of N = dy·(xa − 8) + k·dx (= dy·t + (k·sr) % dy) by 16·dy; here of −N
/// (|N| < 2³⁰: dy, |dx| ≤ 2¹⁴, |xa| < 2¹⁴ and k ≤ dy + 16 in a fast triangle), `sdiv` made a
/// floor division: −N = 16·dy·q′ + r′ (0 ≤ r′ < 16·dy) gives c = −q′ and e = r′ >> 4 (the
/// portable r = 0: c = q, e = 0; else c = q + 1, e = (16·dy − r) >> 4). Uses r1, r4.
/// 28 instructions, and `$k` (k in r4) after the row's check.
macro_rules! edge_t2 {
    ($row:literal, $k:literal) => {
        concat!(
            "subs r3, r3, r1\n",
            "it le\n",
            "movle r3, #1\n",
            "subs r2, r2, r0\n",
            "rsb r4, r1, ",
            $row,
            ", lsl #4\n",
            "adds r4, r4, #8\n",
            "add r1, r3, #16\n",
            "cmp r4, r1\n",
            "bhi .Lsu_decline\n",
            $k,
            // −N = dy·(8 − xa) − k·dx (r5).
            "rsb r0, r0, #8\n",
            "mul r0, r0, r3\n",
            "mls r5, r4, r2, r0\n",
            // (sq, sr) = floor division of dx by dy.
            "add r1, r2, r3, lsl #15\n",
            "udiv r2, r1, r3\n",
            "mls r1, r2, r3, r1\n",
            "sub r2, r2, #32768\n",
            // (q′, r′) = floor division of −N by 16·dy (r4).
            "lsls r4, r3, #4\n",
            "sdiv r0, r5, r4\n",
            "mls r5, r0, r4, r5\n",
            "cmp r5, #0\n",
            "itt lt\n",
            "sublt r0, r0, #1\n",
            "addlt r5, r5, r4\n",
            // c = −q′, w = e·2¹⁶ + c + 2¹⁵, s = sq − sr·2¹⁶.
            "rsb r0, r0, #0\n",
            "lsrs r5, r5, #4\n",
            "add r4, r0, #32768\n",
            "add r5, r4, r5, lsl #16\n",
            "sub r6, r2, r1, lsl #16\n",
        )
    };
}

/// For [`scanline3d_gouraud_t2`]: colour channel `$byte` (its high byte's offset in a vertex,
/// its low two bits at `$bit` of the flags) of the three vertices (frame words 8, 12, 16):
/// r0 = the first vertex's, then r3 = gx = round(c0·d1 − c1·d2) and r5 = gy = round(c2·d2 −
/// c3·d1) (d1, d2 the others' differences from it) as the portable setup rounds a colour
/// gradient, `((v >> (r − 1)) + 1) >> 1`, here `(v + 2^(r − 1)) >> r` (the same floor) with
/// r1 = 2^(r − 1), r2 = r ([`coarse_t2`] as `$tail`), or exactly ([`exact_t2`]). Uses r4.
macro_rules! channel_t2 {
    ($byte:literal, $bit:literal, $tail:ident) => {
        concat!(
            "ldr r3, [sp, #8]\n",
            "ldrb r0, [r3, #",
            $byte,
            "]\n",
            "ldrh r3, [r3, #{vfl}]\n",
            "ubfx r3, r3, #",
            $bit,
            ", #2\n",
            "orr r0, r3, r0, lsl #2\n",
            "ldr r3, [sp, #12]\n",
            "ldrb r4, [r3, #",
            $byte,
            "]\n",
            "ldrh r3, [r3, #{vfl}]\n",
            "ubfx r3, r3, #",
            $bit,
            ", #2\n",
            "orr r4, r3, r4, lsl #2\n",
            "subs r4, r4, r0\n",
            "ldr r3, [sp, #16]\n",
            "ldrb r5, [r3, #",
            $byte,
            "]\n",
            "ldrh r3, [r3, #{vfl}]\n",
            "ubfx r3, r3, #",
            $bit,
            ", #2\n",
            "orr r5, r3, r5, lsl #2\n",
            "subs r5, r5, r0\n",
            $tail!(),
        )
    };
}

/// [`channel_t2`] for green, whose high byte and low two bits are in one word of a vertex
/// (`{vrgb} + 1`: the byte at bits 0–7, the low bits at 28–29): per vertex one load, the low
/// bits (with blue's above them) shifted down and the byte inserted above them by `bfi`.
macro_rules! channel_g_t2 {
    ($tail:ident) => {
        concat!(
            "ldr r3, [sp, #8]\n",
            "ldr r3, [r3, #{vrgb} + 1]\n",
            "lsrs r0, r3, #28\n",
            "bfi r0, r3, #2, #8\n",
            "ldr r3, [sp, #12]\n",
            "ldr r3, [r3, #{vrgb} + 1]\n",
            "lsrs r4, r3, #28\n",
            "bfi r4, r3, #2, #8\n",
            "subs r4, r4, r0\n",
            "ldr r3, [sp, #16]\n",
            "ldr r3, [r3, #{vrgb} + 1]\n",
            "lsrs r5, r3, #28\n",
            "bfi r5, r3, #2, #8\n",
            "subs r5, r5, r0\n",
            $tail!(),
        )
    };
}

/// For [`scanline3d_gouraud_t2`]: the gradient coefficient `±raster::mul_shr_16(m, v, l)` of
/// the coordinate difference v in `$r`, in place: `(m·(v << (16 − l))) >> 16` (the same floor),
/// with r3 = m, r0 = 16 − l, r7 = 0 or −1 (det < 0: negated). Uses r1.
macro_rules! coefficient_t2 {
    ($r:literal) => {
        concat!(
            "lsl ",
            $r,
            ", ",
            $r,
            ", r0\n",
            "smull r1, ",
            $r,
            ", r3, ",
            $r,
            "\n",
            "lsrs r1, r1, #16\n",
            "orr ",
            $r,
            ", r1, ",
            $r,
            ", lsl #16\n",
            "eor ",
            $r,
            ", ",
            $r,
            ", r7\n",
            "sub ",
            $r,
            ", ",
            $r,
            ", r7\n",
        )
    };
}

/// For [`scanline3d_gouraud_t2`]: the depth (`ScreenVertex::depth`, 16.12) of the vertex whose
/// pointer is in frame word `$v`, into `$r`. Uses r1.
macro_rules! depth_t2 {
    ($v:literal, $r:literal) => {
        concat!(
            "ldr r1, [sp, #",
            $v,
            "]\n",
            "ldrh ",
            $r,
            ", [r1, #{vz}]\n",
            "ldrb r1, [r1, #{vzf}]\n",
            "lsls ",
            $r,
            ", ",
            $r,
            ", #12\n",
            "orr ",
            $r,
            ", ",
            $r,
            ", r1, lsl #4\n",
        )
    };
}

/// The four gradient coefficients in r12, r10, r9, r11 rounded to 20 bits in place,
/// `(c + 2¹⁰) >> 11` (`raster::attribute_words`' `c20`).
macro_rules! round_coefficients_t2 {
    () => {
        concat!(
            "add r12, r12, #1024\n",
            "asr r12, r12, #11\n",
            "add r10, r10, #1024\n",
            "asr r10, r10, #11\n",
            "add r9, r9, #1024\n",
            "asr r9, r9, #11\n",
            "add r11, r11, #1024\n",
            "asr r11, r11, #11\n",
        )
    };
}

/// For [`scanline3d_gouraud_t2`]: the four coefficients and the depth sums.
macro_rules! coef_depth_t2 {
    () => {
        concat!(
            // The coefficients bx1 (r12, from dy2), bx2 (r10, dy1), by1 (r9, dx1), by2 (r11, dx2).
            "sub r0, r0, #16\n",
            coefficient_t2!("r12"),
            coefficient_t2!("r10"),
            coefficient_t2!("r9"),
            coefficient_t2!("r11"),
            // Depth (16.12): a0 (frame word 4), da1 (r4), da2 (r5); Sx = da1·bx1 − da2·bx2 (r3:r1),
            // Sy = da2·by1 − da1·by2 (r7:r5).
            depth_t2!("8", "r0"),
            "str r0, [sp, #4]\n",
            depth_t2!("12", "r4"),
            "subs r4, r4, r0\n",
            depth_t2!("16", "r5"),
            "subs r5, r5, r0\n",
            "smull r1, r3, r4, r12\n",
            "negs r0, r5\n",
            "smlal r1, r3, r0, r10\n",
            "smull r5, r7, r5, r9\n",
            "negs r4, r4\n",
            "smlal r5, r7, r4, r11\n",
        )
    };
}

/// For [`scanline3d_gouraud_t2`]: the depth gradients scaled, packed and written.
macro_rules! depth_words_t2 {
    () => {
        concat!(
            // `raster::scale_gradient(S, shift)`: t = S >> k (k = shift − 1, 10..=54), declined where
            // |t| ≥ 2³¹ (a gradient beyond 2³⁰), then (t >> 1) + (t & 1).
            "sub r4, r2, #1\n",
            "cmp r4, #32\n",
            "bge 5f\n",
            "rsb lr, r4, #32\n",
            "lsrs r1, r1, r4\n",
            "lsl r0, r3, lr\n",
            "orr r1, r1, r0\n",
            "asrs r3, r3, r4\n",
            "cmp r3, r1, asr #31\n",
            "bne .Lgt_decline\n",
            "lsrs r5, r5, r4\n",
            "lsl r0, r7, lr\n",
            "orr r5, r5, r0\n",
            "asrs r7, r7, r4\n",
            "cmp r7, r5, asr #31\n",
            "bne .Lgt_decline\n",
            "b 6f\n",
            "5:\n",
            "sub lr, r4, #32\n",
            "asr r1, r3, lr\n",
            "asr r5, r7, lr\n",
            "6:\n",
            "asrs r1, r1, #1\n",
            "adc r1, r1, #0\n",
            "asrs r5, r5, #1\n",
            "adc r5, r5, #0\n",
            // Depth packed (`raster::pack_zrgb`: << 4): gx, the first pixel's value
            // (a0 + (gx·dx + gy·dy) >> 4, of which the low 28 bits count) with its ½-unit bias, and
            // the row step gy + gx·sq.
            "ldr r0, [sp, #20]\n",
            "mla r3, r1, r0, r5\n",
            "lsls r3, r3, #4\n",
            "mul r7, r1, r6\n",
            "mla r7, r5, r8, r7\n",
            "lsls r1, r1, #4\n",
            "ldr r0, [sp, #4]\n",
            "add r7, r0, r7, asr #4\n",
            "lsls r7, r7, #4\n",
            "add r7, r7, #0x8000\n",
            "ldr r0, [sp, #0]\n",
            "str r1, [r0, #{gx}]\n",
            "str r7, [r0, #{row}]\n",
            "str r3, [r0, #{inc}]\n",
        )
    };
}

/// For [`scanline3d_gouraud_t2`]: the three colour channels (their gradients by `$tail`),
/// written, and the return.
macro_rules! channels_t2 {
    ($tail:ident) => {
        concat!(
            blue_red_t2!($tail),
            green_t2!($tail),
            "movs r0, #1\n",
            "pop {{r1, r2, r3, r4, r5, r7, pc}}\n",
        )
    };
}

/// For [`channels_t2`]: blue and red (r2 = shift on entry, then shift − 26).
macro_rules! blue_red_t2 {
    ($tail:ident) => {
        concat!(
            // Blue (5.5 vertex channels, 15 bits to 20 fraction bits, packed with 11): gx and gy
            // packed (v + 2⁸) >> 9 into r7 and lr; the first pixel's value (exact in 64 bits: all of
            // its 32-bit word counts, as the borrow into red) packed the same into frame word 4.
            "sub r2, r2, #26\n",
            "sub r1, r2, #1\n",
            "movs r4, #1\n",
            "lsl r1, r4, r1\n",
            channel_t2!("{vrgb} + 2", "14", $tail),
            "add r7, r3, #256\n",
            "asr r7, r7, #9\n",
            "add lr, r5, #256\n",
            "asr lr, lr, #9\n",
            "lsls r0, r0, #19\n",
            "add r0, r0, #4096\n",
            "movs r4, #0\n",
            "smlal r0, r4, r3, r6\n",
            "smlal r0, r4, r5, r8\n",
            "lsrs r0, r0, #13\n",
            "orr r0, r0, r4, lsl #19\n",
            "str r0, [sp, #4]\n",
            // Red: its halves added (the first pixel's value mod 2²⁸ is enough for its half), with
            // both halves' ½-unit biases; the row step gy + gx·sq of the packed words.
            channel_t2!("{vrgb}", "10", $tail),
            "add r4, r3, #256\n",
            "asr r4, r4, #9\n",
            "add r7, r7, r4, lsl #16\n",
            "add r4, r5, #256\n",
            "asr r4, r4, #9\n",
            "add lr, lr, r4, lsl #16\n",
            "lsls r0, r0, #19\n",
            "add r0, r0, #4096\n",
            "mla r0, r3, r6, r0\n",
            "mla r0, r5, r8, r0\n",
            "lsrs r0, r0, #13\n",
            "ldr r4, [sp, #4]\n",
            "add r4, r4, r0, lsl #16\n",
            "add r4, r4, #0x04000400\n",
            "ldr r0, [sp, #0]\n",
            "ldr r3, [sp, #20]\n",
            "mla r3, r7, r3, lr\n",
            "str r7, [r0, #{gx} + 4]\n",
            "str r4, [r0, #{row} + 4]\n",
            "str r3, [r0, #{inc} + 4]\n",
        )
    };
}

/// For [`channels_t2`]: green (r2 = shift − 26 on entry, then shift − 27).
macro_rules! green_t2 {
    ($tail:ident) => {
        concat!(
            // Green (6.4, 16 bits to 20, packed with 26: << 6; its rounding one bit less): the first
            // pixel's value with its ½-unit bias 2¹⁹, mod 2²⁶.
            "sub r2, r2, #1\n",
            "lsr r1, r1, #1\n",
            channel_g_t2!($tail),
            "lsls r0, r0, #20\n",
            "add r0, r0, #0x800000\n",
            "mla r0, r3, r6, r0\n",
            "mla r0, r5, r8, r0\n",
            "bic r0, r0, #15\n",
            "lsls r0, r0, #2\n",
            "lsls r3, r3, #6\n",
            "lsls r5, r5, #6\n",
            "ldr r1, [sp, #0]\n",
            "ldr r4, [sp, #20]\n",
            "mla r5, r3, r4, r5\n",
            "str r3, [r1, #{gx} + 8]\n",
            "str r0, [r1, #{row} + 8]\n",
            "str r5, [r1, #{inc} + 8]\n",
        )
    };
}

/// [`channel_t2`]'s gradients for a triangle whose 20-bit coefficients are too coarse (or
/// whose rounding r would be below 1), as `setup::exact_color_gradients` computes them: from
/// the full coefficients (r12, r10, r9, r11), S = c0·d1 − c1·d2 and c2·d2 − c3·d1 in 64 bits
/// (smull, smlal), `scale_gradient(S << sh, shift)` = (S + 2^(n − 1)) >> n with n = shift − sh
/// = r2 + 11 (1 ≤ n ≤ 31: checked on entry), declined unless |gradient| < 2²⁹ (the coarse
/// gradients' bound, which the packing below assumes). Uses r1 and, saved, r6–r8.
macro_rules! exact_t2 {
    () => {
        concat!(
            "push {{r6, r7, r8}}\n",
            "smull r1, r3, r12, r4\n",
            "rsb r6, r5, #0\n",
            "smlal r1, r3, r10, r6\n",
            round64_t2!(),
            "mov r7, r1\n",
            "smull r1, r3, r9, r5\n",
            "rsb r6, r4, #0\n",
            "smlal r1, r3, r11, r6\n",
            round64_t2!(),
            "mov r5, r1\n",
            "mov r3, r7\n",
            "pop {{r6, r7, r8}}\n",
        )
    };
}

/// For [`exact_t2`]: r1 = (r3:r1 + 2^(n − 1)) >> n (n = r2 + 11), declined (the three saved
/// words dropped) unless it is within ±2²⁹. Uses r3, r6, r8.
macro_rules! round64_t2 {
    () => {
        concat!(
            "rsb r6, r2, #21\n",
            "mov r8, #0x80000000\n",
            "lsr r8, r8, r6\n",
            "adds r1, r1, r8\n",
            "adc r3, r3, #0\n",
            "lsl r8, r3, r6\n",
            "rsb r6, r6, #32\n",
            "lsr r1, r1, r6\n",
            "orr r1, r1, r8\n",
            "asr r3, r3, r6\n",
            "cmp r3, r1, asr #31\n",
            "bne .Lgt_decline3\n",
            "add r8, r1, #0x20000000\n",
            "lsrs r8, r8, #30\n",
            "bne .Lgt_decline3\n",
        )
    };
}

/// [`channel_t2`]'s gradients from the 20-bit coefficients (r12, r10, r9, r11), rounded once.
macro_rules! coarse_t2 {
    () => {
        concat!(
            "mla r3, r12, r4, r1\n",
            "mls r3, r10, r5, r3\n",
            "asrs r3, r3, r2\n",
            "mul r4, r4, r11\n",
            "mla r5, r5, r9, r1\n",
            "subs r5, r5, r4\n",
            "asrs r5, r5, r2\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_gouraud_t2,\"ax\",%progbits",
    ".global scanline3d_gouraud_t2",
    ".type scanline3d_gouraud_t2,%function",
    ".p2align 2",
    ".thumb_func",
    // `raster::attribute_words` of a fast Gouraud triangle with RGB565 channels, as the
    // Thumb-1 `scanline3d_gouraud_setup` computes it (the same declines), for the two entry
    // points below: r0 = the record, r1 = `scalar::RECIP_SEED`, r2 = det, r3–r5 = the sorted
    // vertices, r6 = the left edge's column, r7 = its step, r8 = dy = 16·row + 8 − ay (the
    // first row's centre from the first vertex, subpixels), r9 = dx1, r10 = dy1, r11 = dx2,
    // r12 = dy2 (b − a and c − a; dy1, dy2 ≥ 0: sorted by y). Writes the first three words of
    // the record's `gx`, `row` and `inc` (not the fourth) and returns r0 = 1, or 0 (having
    // written nothing, except where a sliver's exact gradient is beyond 2²⁹: then some of
    // those words; every caller has the portable code write all of them after a 0).
    // Clobbers r1–r12. Frame: the record, a scratch word, the vertices, the step, lr.
    "scanline3d_gouraud_t2:",
    "push {{r0, r1, r3, r4, r5, r7, lr}}",
    // dx = 16·left.c + 8 − ax (r6); it and dy (r8) within the i16 range.
    "ldrsh r0, [r3]",
    "rsb r6, r0, r6, lsl #4",
    "adds r6, r6, #8",
    "add r0, r6, #0x8000",
    "add r3, r8, #0x8000",
    "orr r0, r0, r3",
    "cmp r0, #0x10000",
    "bhs .Lgt_decline",
    // r0 = 32 − l, l the bit length of the largest |difference| (of their OR; dy1 and dy2
    // are not negative).
    "eor r0, r9, r9, asr #31",
    "sub r0, r0, r9, asr #31",
    "eor r3, r11, r11, asr #31",
    "sub r3, r3, r11, asr #31",
    "orr r0, r0, r3",
    "orr r0, r0, r10",
    "orr r0, r0, r12",
    "clz r0, r0",
    // `scalar::recip_norm(|det|)`: r3 = m, r2 = 32 − s (r7 = det's sign mask). A table seed,
    // one Newton step in 32-bit products and one in 64-bit ones, as the portable code.
    "asr r7, r2, #31",
    "eor r4, r2, r7",
    "sub r4, r4, r7",
    "clz r2, r4",
    "lsls r4, r4, r2",
    // (Before the reciprocal, which it does not need:) shift = 29 + s − (l + 4) (r2); where
    // shift − l < `raster::COARSE_MIN` (r5 < 0) or green's rounding r = shift − 27 is below 1,
    // the portable code keeps exact sums (`.Lgt_sliver`).
    "sub r2, r0, r2",
    "add r2, r2, #25",
    "add r5, r2, r0",
    "subs r5, r5, #(32 + {coarse_min})",
    "bmi .Lgt_sliver",
    "cmp r2, #28",
    "blt .Lgt_sliver",
    recip_mantissa_t2!("r4", "r1", "r3", "r5", "lr"),
    coef_depth_t2!(),
    round_coefficients_t2!(),
    depth_words_t2!(),
    channels_t2!(coarse_t2),
    // A sliver: the exact colour sums of every channel (`exact_t2`), for shift ≥ 17 (n ≥ 1);
    // where shift = 27 and the coefficients are fine, red and blue (r = 1) take the coarse
    // sums and green the exact ones (`.Lgt_mixed`).
    ".Lgt_sliver:",
    "cmp r2, #17",
    "blt .Lgt_decline",
    "cmp r2, #27",
    "bne 1f",
    "cmp r5, #0",
    "bge .Lgt_mixed",
    "1:",
    recip_mantissa_t2!("r4", "r1", "r3", "r5", "lr"),
    coef_depth_t2!(),
    depth_words_t2!(),
    channels_t2!(exact_t2),
    // Green first from the full coefficients, then blue and red from the rounded ones.
    ".Lgt_mixed:",
    recip_mantissa_t2!("r4", "r1", "r3", "r5", "lr"),
    coef_depth_t2!(),
    depth_words_t2!(),
    "sub r2, r2, #26",
    green_t2!(exact_t2),
    "add r2, r2, #27",
    round_coefficients_t2!(),
    blue_red_t2!(coarse_t2),
    "movs r0, #1",
    "pop {{r1, r2, r3, r4, r5, r7, pc}}",
    ".Lgt_decline3:",
    "add sp, #12",
    ".Lgt_decline:",
    "movs r0, #0",
    "pop {{r1, r2, r3, r4, r5, r7, pc}}",
    ".size scanline3d_gouraud_t2, . - scanline3d_gouraud_t2",
    vz = const core::mem::offset_of!(ScreenVertex, z),
    vzf = const core::mem::offset_of!(ScreenVertex, zf),
    vrgb = const crate::kernel::records::RGB_HI_OFFSET,
    vfl = const crate::kernel::records::FLAGS_OFFSET,
    gx = const o::GX,
    row = const o::ROW,
    inc = const o::INC,
    coarse_min = const crate::kernel::records::COARSE_MIN,
);

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_gouraud_setup,\"ax\",%progbits",
    ".global scanline3d_gouraud_setup",
    ".type scanline3d_gouraud_setup,%function",
    ".p2align 2",
    ".thumb_func",
    // The Thumb-1 routine's interface (r0 = `raster::Sorted`, r1 = the record, r2 = the seed
    // table): `scanline3d_gouraud_t2`'s registers from the seven words, and the fourth words
    // of `gx`, `row` and `inc` zeroed when it has written the others.
    "scanline3d_gouraud_setup:",
    "push {{r1, r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "mov lr, r0",
    "mov r0, r1",
    "mov r1, r2",
    "ldm lr, {{r3, r4, r5}}",
    "ldrd r2, r8, [lr, #12]",
    "ldrd r6, r7, [lr, #20]",
    "ldr lr, [r3]",
    "ldr r9, [r4]",
    "ldr r11, [r5]",
    "lsl r8, r8, #4",
    "add r8, r8, #8",
    "sub r8, r8, lr, asr #16",
    "asr r10, r9, #16",
    "sub r10, r10, lr, asr #16",
    "asr r12, r11, #16",
    "sub r12, r12, lr, asr #16",
    "sxth lr, lr",
    "sxth r9, r9",
    "sub r9, r9, lr",
    "sxth r11, r11",
    "sub r11, r11, lr",
    "bl scanline3d_gouraud_t2",
    "cbz r0, 1f",
    "ldr r1, [sp]",
    "movs r2, #0",
    "str r2, [r1, #{gx} + 12]",
    "str r2, [r1, #{row} + 12]",
    "str r2, [r1, #{inc} + 12]",
    "1:",
    "pop {{r1, r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    ".size scanline3d_gouraud_setup, . - scanline3d_gouraud_setup",
    gx = const o::GX,
    row = const o::ROW,
    inc = const o::INC,
);

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_setup565,\"ax\",%progbits",
    ".global scanline3d_setup565",
    ".type scanline3d_setup565,%function",
    ".p2align 2",
    ".thumb_func",
    // The Thumb-1 routine's interface and results (r0 = the record, r1 = `SetupArgs`): 1 kept,
    // 2 no row to draw, 3 kept but not ditherable, 0 declined. Frame: the registers of
    // `scanline3d_gouraud_t2` (words 0–12: the record, the seed, det, the sorted vertices, the
    // left edge's column and step, dy = 16·row + 8 − ay, dx1, dy1, dx2, dy2), row_end (52),
    // the right edge's column and step (56, 60: unused), the seed with the dither flag (68),
    // the row (72).
    "scanline3d_setup565:",
    "push {{r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "sub sp, #76",
    "ldm r1, {{r2, r3, r4, r5, r7, r8, r9}}",
    "bic r1, r9, #1",
    "strd r0, r1, [sp, #0]",
    "strd r9, r7, [sp, #68]",
    "mov lr, r0",
    // The vertex pointers (a flat triangle declines; indices checked against the length).
    "tst r4, #0x8000",
    "bne .Lsu_decline",
    "uxth r1, r4",
    "lsrs r4, r4, #16",
    "cmp r1, r3",
    "bhs .Lsu_decline",
    "cmp r4, r3",
    "bhs .Lsu_decline",
    "cmp r5, r3",
    "bhs .Lsu_decline",
    "movs r6, #12",
    "mla r3, r1, r6, r2",
    "mla r4, r4, r6, r2",
    "mla r5, r5, r6, r2",
    // Sorted by y as the portable setup sorts them (the same swaps for equal ys).
    "ldrsh r9, [r3, #2]",
    "ldrsh r10, [r4, #2]",
    "ldrsh r11, [r5, #2]",
    "cmp r10, r9",
    "bge 1f",
    "mov r1, r3",
    "mov r3, r4",
    "mov r4, r1",
    "ldrsh r9, [r3, #2]",
    "ldrsh r10, [r4, #2]",
    "1:",
    "cmp r11, r10",
    "bge 1f",
    "mov r1, r4",
    "mov r4, r5",
    "mov r5, r1",
    "mov r10, r11",
    "1:",
    "cmp r10, r9",
    "bge 1f",
    "mov r1, r3",
    "mov r3, r4",
    "mov r4, r1",
    "1:",
    "strd r3, r4, [sp, #12]",
    "str r5, [sp, #20]",
    // The packed x | y << 16 of a, b, c (r9–r11); bx, by, cx, cy into the record.
    "ldr r9, [r3]",
    "ldr r10, [r4]",
    "ldr r11, [r5]",
    "strd r10, r11, [lr, #{bx}]",
    // row_end = min(first_pixel(cy), height) > row (r6), row_mid = first_pixel(by) (r12).
    "asr r1, r9, #16",
    "asr r2, r10, #16",
    "asr r3, r11, #16",
    "add r6, r3, #7",
    "asr r6, r6, #4",
    "cmp r6, r8",
    "it gt",
    "movgt r6, r8",
    "cmp r7, r6",
    "bge .Lsu_empty",
    "str r6, [sp, #52]",
    "add r12, r2, #7",
    "asr r12, r12, #4",
    "uxth r4, r12",
    "orr r4, r4, r6, lsl #16",
    "str r4, [lr, #{row_mid}]",
    // det = dx1·dy2 − dx2·dy1 ≠ 0 (r0).
    "subs r2, r2, r1",
    "subs r3, r3, r1",
    "sxth r1, r9",
    "sxth r4, r10",
    "subs r4, r4, r1",
    "sxth r5, r11",
    "subs r5, r5, r1",
    "strd r4, r2, [sp, #36]",
    "strd r5, r3, [sp, #44]",
    "mul r0, r4, r3",
    "mls r0, r5, r2, r0",
    "cmp r0, #0",
    "beq .Lsu_empty",
    "str r0, [sp, #8]",
    // Fast only when (x_hi − x_lo) + (cy − ay) ≤ 1024 px.
    "cmp r4, r5",
    "ite lt",
    "movlt r1, r4",
    "movge r1, r5",
    "add r2, r4, r5",
    "sub r2, r2, r1",
    "bic r2, r2, r2, asr #31",
    "and r1, r1, r1, asr #31",
    "sub r2, r2, r1",
    "add r2, r2, r3",
    "cmp r2, #16384",
    "bgt .Lsu_decline",
    // mid_left = det < 0 (r8: the long edge's slot, 1 = right).
    "lsrs r8, r0, #31",
    // `ActiveTri::set_routine_rows`: rows up to stop = row_mid − 1 when row ≤ it < row_end − 1,
    // else row_end − 1; the count (at most 255) and LAST or SWITCH when it reaches stop.
    "sub r1, r6, #1",
    "sub r3, r12, #1",
    "cmp r3, r7",
    "it ge",
    "cmpge r1, r3",
    "ite gt",
    "movgt r2, r3",
    "movle r2, r1",
    "cmp r2, r1",
    "ite eq",
    "orreq r5, r8, #({fast} | {last})",
    "orrne r5, r8, #({fast} | {switch})",
    "subs r3, r2, r7",
    "cmp r3, #255",
    "itt hi",
    "movhi r3, #255",
    "orrhi r5, r8, #{fast}",
    "strb r5, [lr, #{flags}]",
    "strb r3, [lr, #{rows}]",
    // The long edge a → c into slot r8 (its column and step into frame words 6–7 when it is
    // the left edge, else 14–15).
    "sxth r0, r9",
    "asr r1, r9, #16",
    "sxth r2, r11",
    "asr r3, r11, #16",
    edge_t2!("r7", "str r4, [sp, #32]\n"),
    "add r1, lr, r8, lsl #3",
    "strd r5, r6, [r1, #{left_w}]",
    "add r1, lr, r8, lsl #1",
    "strh r3, [r1, #{left_dy}]",
    "add r1, sp, r8, lsl #5",
    "strd r0, r2, [r1, #24]",
    // The short edge: a → b before row_mid, b → c from it; the other slot.
    "cmp r7, r12",
    "itete lt",
    "movlt r4, r9",
    "movge r4, r10",
    "movlt r5, r10",
    "movge r5, r11",
    "sxth r0, r4",
    "asr r1, r4, #16",
    "sxth r2, r5",
    "asr r3, r5, #16",
    edge_t2!("r7", ""),
    "eor r8, r8, #1",
    "add r1, lr, r8, lsl #3",
    "strd r5, r6, [r1, #{left_w}]",
    "add r1, lr, r8, lsl #1",
    "strh r3, [r1, #{left_dy}]",
    "add r1, sp, r8, lsl #5",
    "strd r0, r2, [r1, #24]",
    // The pending short edge b → c at row_mid when row < row_mid < row_end
    // (`ActiveTri::set_pending`: w, s and dy in the fourth words of gx, row and inc), else
    // zeros there.
    "cmp r7, r12",
    "bge 2f",
    "ldr r0, [sp, #52]",
    "cmp r12, r0",
    "bge 2f",
    "sxth r0, r10",
    "asr r1, r10, #16",
    "sxth r2, r11",
    "asr r3, r11, #16",
    edge_t2!("r12", ""),
    "b 3f",
    "2:",
    "movs r5, #0",
    "movs r6, #0",
    "movs r3, #0",
    "3:",
    "str r5, [lr, #{pend_w}]",
    "str r6, [lr, #{pend_s}]",
    "str r3, [lr, #{pend_dy}]",
    // The attribute words.
    "ldm sp, {{r0, r1, r2, r3, r4, r5, r6, r7, r8, r9, r10, r11, r12}}",
    "bl scanline3d_gouraud_t2",
    "cbz r0, .Lsu_decline",
    // While dithering: `raster::ActiveTri::dither_fits` (the sorted vertex pointers are frame
    // words 3–5) sets `DITHER_OK`, or the result is 3; else it is 1 (r0).
    "ldr r1, [sp, #68]",
    "lsls r1, r1, #31",
    "beq .Lsu_done",
    "ldr r0, [sp, #0]",
    "add r1, sp, #12",
    "ldr r2, [sp, #72]",
    "bl scanline3d_dither_fits565",
    "cbz r0, .Lsu_undithered",
    "ldr r1, [sp, #0]",
    "ldrb r2, [r1, #{flags}]",
    "orr r2, r2, #{dither_ok}",
    "strb r2, [r1, #{flags}]",
    "movs r0, #1",
    "b .Lsu_done",
    ".Lsu_undithered:",
    "movs r0, #3",
    "b .Lsu_done",
    ".Lsu_empty:",
    "movs r0, #2",
    "b .Lsu_done",
    ".Lsu_decline:",
    "movs r0, #0",
    ".Lsu_done:",
    "add sp, #76",
    "pop {{r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    ".size scanline3d_setup565, . - scanline3d_setup565",
    left_dy = const o::LEFT_DY,
    left_w = const o::LEFT + o::W,
    pend_w = const o::PEND_W,
    pend_s = const o::PEND_S,
    pend_dy = const o::PEND_DY,
    bx = const o::BX,
    row_mid = const o::ROW_MID,
    fast = const o::FAST,
    last = const o::LAST,
    switch = const o::SWITCH,
    flags = const o::FLAGS,
    rows = const o::ROUTINE_ROWS,
    dither_ok = const o::DITHER_OK,
);
