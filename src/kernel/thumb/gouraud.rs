//! The attribute setup of a fast Gouraud triangle with RGB565 channels: depth and colour
//! planes, gradients, first-pixel values and row steps (`raster::attribute_words`).
#![allow(unsafe_code)]
#![cfg_attr(scanline3d_thumb2, allow(unused_macros, unused_imports))]

use super::offsets as o;
use crate::kernel::records::{ActiveTri, ScreenVertex, Sorted};

extern "C" {
    fn scanline3d_gouraud_setup(tri: *const u32, rec: *mut ActiveTri, seed: *const u16) -> u32;
}

/// For [`scanline3d_gouraud_setup`]: r0:r4 (high, low word) = r0·r1, signed, for
/// `|r0| < 2²⁸` and `|r1| ≤ 2³⁰` (a depth difference and a gradient coefficient): then
/// ah·bl + al·bh is below 2³¹ in magnitude and is added once. Uses r1–r3. 17 instructions.
macro_rules! mul_depth {
    () => {
        concat!(
            "uxth r2, r0\n",
            "asrs r0, r0, #16\n",
            "uxth r3, r1\n",
            "asrs r1, r1, #16\n",
            "mov r4, r2\n",
            "muls r4, r3, r4\n",
            "muls r3, r0, r3\n",
            "muls r0, r1, r0\n",
            "muls r1, r2, r1\n",
            "adds r1, r1, r3\n",
            "lsls r2, r1, #16\n",
            "asrs r1, r1, #16\n",
            "adds r4, r4, r2\n",
            "adcs r0, r1\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: the depth gradient
/// `raster::scale_gradient(a·b − c·d, shift)` for the frame words at `$a`, `$b`, `$c`, `$d`,
/// stored at `$out`: the difference of two [`mul_depth`] products, rounded half up by
/// `shift − 1` (in `gs_k`, 10..=54) then 1, or the routine declines (label 8) where that
/// exceeds ±2³⁰. Uses r0–r7.
macro_rules! depth_gradient {
    ($a:literal, $b:literal, $c:literal, $d:literal, $out:literal) => {
        concat!(
            "ldr r0, [sp, #", $a, "]\n",
            "ldr r1, [sp, #", $b, "]\n",
            mul_depth!(),
            "mov r6, r0\n",
            "mov r5, r4\n",
            "ldr r0, [sp, #", $c, "]\n",
            "ldr r1, [sp, #", $d, "]\n",
            mul_depth!(),
            "subs r5, r5, r4\n",
            "sbcs r6, r0\n",
            // t = the difference >> k (r6 = high, r5 = low word).
            "ldr r7, [sp, #gs_k]\n",
            "cmp r7, #32\n",
            "bge 1f\n",
            "lsrs r5, r5, r7\n",
            "movs r0, #32\n",
            "subs r0, r0, r7\n",
            "mov r1, r6\n",
            "lsls r1, r1, r0\n",
            "orrs r5, r1\n",
            "asrs r6, r6, r7\n",
            "b 2f\n",
            "1:\n",
            "mov r0, r7\n",
            "subs r0, #32\n",
            "asrs r6, r6, r0\n",
            "mov r5, r6\n",
            "asrs r6, r6, #31\n",
            // |t| ≥ 2³¹: a gradient beyond 2³⁰ (a sliver's), which the portable code keeps in
            // 64 bits: declined. Else (t >> 1) + (t & 1) (the carry of the shift), within ±2³⁰.
            "2:\n",
            "asrs r0, r5, #31\n",
            "cmp r0, r6\n",
            "beq 3f\n",
            "b 8f\n",
            "3:\n",
            "asrs r5, r5, #1\n",
            "movs r0, #0\n",
            "adcs r5, r0\n",
            "str r5, [sp, #", $out, "]\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: the depth of the vertex whose pointer is in frame word
/// `$v`, as `ScreenVertex::depth` (16.12: `z << 12 | zf << 4`), into `$r`. Uses r2, r4.
macro_rules! vertex_depth {
    ($v:literal, $r:literal) => {
        concat!(
            "ldr r4, [sp, #",
            $v,
            "]\n",
            "ldrh ",
            $r,
            ", [r4, #{vz}]\n",
            "lsls ",
            $r,
            ", ",
            $r,
            ", #12\n",
            "ldrb r2, [r4, #{vzf}]\n",
            "lsls r2, r2, #4\n",
            "orrs ",
            $r,
            ", r2\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: the 10-bit colour channel `$k` of the vertex in r4
/// (`ScreenVertex::color`: the byte's 8 bits, then 2 bits of the flags) into `$r`. Uses r3.
macro_rules! vertex_channel {
    ($r:literal, $rgb:literal, $fl:literal) => {
        concat!(
            "ldrb ",
            $r,
            ", [r4, #",
            $rgb,
            "]\n",
            "lsls ",
            $r,
            ", ",
            $r,
            ", #2\n",
            "ldrh r3, [r4, #{vfl}]\n",
            "lsls r3, r3, #",
            $fl,
            "\n",
            "lsrs r3, r3, #30\n",
            "orrs ",
            $r,
            ", r3\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: r0 (|r0| < 2³⁰) rounded by the channel's shift `r ≥ 1`
/// as the portable setup rounds a colour gradient, `((v >> (r − 1)) + 1) >> 1`. `gs_r` holds
/// r − 1 for red and blue; `$green` subtracts one for green. Uses r2.
macro_rules! round_channel {
    ($green:literal) => {
        concat!(
            "ldr r2, [sp, #gs_r]\n",
            $green,
            "asrs r0, r0, r2\n",
            "adds r0, #1\n",
            "asrs r0, r0, #1\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: `(gx·dx + gy·dy) >> 4` (the low word of the exact
/// shifted sum) for r0 = gx, r3 = gy, into r0 — the offset of an attribute's value at the
/// first pixel from its value at the first vertex. With g = gh·2¹⁶ + gl and gl the signed low
/// half: |gl·dx| ≤ 2³⁰, and dy > −2¹⁵ (rows are on the screen, ay ≤ 2¹⁴), so the low
/// products' sum fits an `i32` and the sum is `(Σ gh·d)·2¹⁶ + Σ gl·d`. Uses r1, r2, r4.
macro_rules! prestep {
    () => {
        concat!(
            "ldr r1, [sp, #gs_dx]\n",
            "sxth r2, r0\n",
            "subs r0, r0, r2\n",
            "asrs r0, r0, #16\n",
            "muls r2, r1, r2\n",
            "muls r0, r1, r0\n",
            "ldr r1, [sp, #gs_dy]\n",
            "sxth r4, r3\n",
            "subs r3, r3, r4\n",
            "asrs r3, r3, #16\n",
            "muls r4, r1, r4\n",
            "muls r3, r1, r3\n",
            "adds r0, r0, r3\n",
            "adds r2, r2, r4\n",
            "lsls r0, r0, #12\n",
            "asrs r2, r2, #4\n",
            "adds r0, r0, r2\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: colour channel `$rgb` (its byte's offset in a vertex;
/// `$fl` = the left shift that brings its two low bits to the top of the flags, `$sh` = its
/// shift to 20 fraction bits, `$less` = [`round_channel`]'s adjustment for green), from its
/// value at the first vertex `c0 << sh` and its gradients from the 20-bit coefficients,
/// `gx = round(c0·d1 − c1·d2)` and `gy = round(c2·d2 − c3·d1)`, to its value at the first
/// pixel (`+ `[`prestep`]) and `gy` (the row step's first part: the routine adds `Gx·sq` of
/// the packed gradient at the end), all three packed into the record (r7) by `$gx`, `$inc`
/// and `$row` ([`pack_blue`], [`pack_red`], [`pack_green`]: each
/// stores the word in the register it names, with r6 = 2⁸). Nothing goes through the frame
/// but the constants. Uses r0–r7.
macro_rules! channel {
    ($rgb:literal, $fl:literal, $sh:literal, $less:literal, $gx:expr, $inc:expr, $row:expr) => {
        concat!(
            "ldr r4, [sp, #gs_va]\n",
            vertex_channel!("r5", $rgb, $fl),
            "ldr r4, [sp, #gs_vb]\n",
            vertex_channel!("r6", $rgb, $fl),
            "subs r6, r6, r5\n",
            "ldr r4, [sp, #gs_vc]\n",
            vertex_channel!("r7", $rgb, $fl),
            "subs r7, r7, r5\n",
            "lsls r5, r5, #",
            $sh,
            "\n",
            // r0 = gx, r3 = gy.
            "ldr r0, [sp, #gs_c20]\n",
            "muls r0, r6, r0\n",
            "ldr r1, [sp, #gs_c20 + 4]\n",
            "muls r1, r7, r1\n",
            "subs r0, r0, r1\n",
            round_channel!($less),
            "ldr r3, [sp, #gs_c20 + 8]\n",
            "muls r3, r7, r3\n",
            "ldr r1, [sp, #gs_c20 + 12]\n",
            "muls r1, r6, r1\n",
            "subs r3, r3, r1\n",
            // Rounded as r0 was, by the shift left in r2.
            "asrs r3, r3, r2\n",
            "adds r3, #1\n",
            "asrs r3, r3, #1\n",
            // r1 = gy; the packed gx and gy (the row step `Gy + Gx·sq` is completed from the
            // packed words once all channels are in).
            "ldr r7, [sp, #gs_rec]\n",
            "mov r1, r3\n",
            "movs r6, #1\n",
            "lsls r6, r6, #8\n",
            "mov r2, r0\n",
            $gx,
            $inc,
            // r0 = the value at the first pixel.
            prestep!(),
            "adds r0, r0, r5\n",
            $row,
        )
    };
}

/// For [`channel`]: blue's packed word `(r$v + 2⁸) >> 9` (`$bias`: the start value's
/// ½-unit bias, or nothing) into the record at `$off` (red adds its half later).
macro_rules! pack_blue {
    ($v:literal, $off:literal, $bias:literal) => {
        concat!(
            "adds ", $v, ", ", $v, ", r6\n", "asrs ", $v, ", ", $v, ", #9\n", $bias, "str ", $v,
            ", [r7, #", $off, "]\n",
        )
    };
}

/// For [`channel`]: red's half `(r$v + 2⁸) >> 9` (`$bias` as [`pack_blue`]) shifted to the
/// high half and added to blue's word at `$off` (wrapping: `R·2¹⁶ + B mod 2³²`). Uses r4.
macro_rules! pack_red {
    ($v:literal, $off:literal, $bias:literal) => {
        concat!(
            "adds ",
            $v,
            ", ",
            $v,
            ", r6\n",
            "asrs ",
            $v,
            ", ",
            $v,
            ", #9\n",
            $bias,
            "lsls ",
            $v,
            ", ",
            $v,
            ", #16\n",
            "ldr r4, [r7, #",
            $off,
            "]\n",
            "adds ",
            $v,
            ", ",
            $v,
            ", r4\n",
            "str ",
            $v,
            ", [r7, #",
            $off,
            "]\n",
        )
    };
}

/// For [`channel`]: green's packed word `r$v << 6` into the record at `$off`.
macro_rules! pack_green {
    ($v:literal, $off:literal) => {
        concat!("lsls ", $v, ", ", $v, ", #6\n", "str ", $v, ", [r7, #", $off, "]\n")
    };
}

/// For [`scanline3d_gouraud_setup`]: a bit length of a value below 2¹⁶ in r0 into r1. Uses r2.
macro_rules! bitlen16 {
    () => {
        concat!(
            "movs r1, #0\n",
            "lsrs r2, r0, #8\n",
            "beq 1f\n",
            "movs r1, #8\n",
            "mov r0, r2\n",
            "1:\n",
            "lsrs r2, r0, #4\n",
            "beq 1f\n",
            "adds r1, #4\n",
            "mov r0, r2\n",
            "1:\n",
            "lsrs r2, r0, #2\n",
            "beq 1f\n",
            "adds r1, #2\n",
            "mov r0, r2\n",
            "1:\n",
            "lsrs r2, r0, #1\n",
            "beq 1f\n",
            "adds r1, #1\n",
            "mov r0, r2\n",
            "1:\n",
            "adds r1, r1, r0\n",
        )
    };
}

/// For [`scanline3d_gouraud_setup`]: the gradient coefficient in frame word `$f` (a
/// coordinate difference v on entry): `±raster::mul_shr_16(m, v, l)` with r0 = m >> 15,
/// r1 = m & 0x7fff, r2 = l, r3 = 15 − l, r4 = 0 or −1 (det < 0: negated), and its 20-bit
/// rounding `(q + 2¹⁰) >> 11` (r5 = 2¹⁰) into `$c20`. Uses r6, r7.
macro_rules! coefficient {
    ($f:literal, $c20:literal) => {
        concat!(
            "ldr r6, [sp, #",
            $f,
            "]\n",
            "mov r7, r6\n",
            "muls r6, r0, r6\n",
            "lsls r6, r6, r3\n",
            "muls r7, r1, r7\n",
            "asrs r7, r7, r2\n",
            "adds r6, r6, r7\n",
            "eors r6, r4\n",
            "subs r6, r6, r4\n",
            "str r6, [sp, #",
            $f,
            "]\n",
            "adds r6, r6, r5\n",
            "asrs r6, r6, #11\n",
            "str r6, [sp, #",
            $c20,
            "]\n",
        )
    };
}

// The Thumb-1 form (ARMv6-M); Thumb-2 cores assemble `setup_t2`'s.
#[cfg(not(scanline3d_thumb2))]
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_gouraud_setup,\"ax\",%progbits",
    ".global scanline3d_gouraud_setup",
    ".type scanline3d_gouraud_setup,%function",
    ".p2align 2",
    ".thumb_func",
    // The frame (byte offsets from sp).
    ".equ gs_bx1, 0",
    ".equ gs_bx2, 4",
    ".equ gs_by1, 8",
    ".equ gs_by2, 12",
    ".equ gs_gx, 16",
    ".equ gs_gy, 32",
    ".equ gs_a0, 48",
    ".equ gs_va, 64",
    ".equ gs_vb, 68",
    ".equ gs_vc, 72",
    ".equ gs_det, 76",
    ".equ gs_row, 80",
    ".equ gs_lc, 84",
    ".equ gs_lsq, 88",
    ".equ gs_rec, 92",
    ".equ gs_k, 96",
    ".equ gs_r, 100",
    ".equ gs_dx, 104",
    ".equ gs_dy, 108",
    ".equ gs_da1, 112",
    ".equ gs_da2, 116",
    ".equ gs_c20, 120",
    ".equ gs_frame, 136",
    // r0 = `raster::Sorted` (seven words: the three vertices top to bottom, det, the row,
    // the left edge's column and step), r1 = the record, r2 = `scalar::RECIP_SEED`. Writes
    // the record's packed attribute words (`gx`, `row`, `inc`, twelve words from `gx` on) as
    // `raster::attribute_words` computes them for a fast Gouraud triangle with RGB565
    // channels and returns 1; or returns 0 with the record unchanged for what the portable
    // code handles: a first pixel 2¹⁵ subpixels or more from the first vertex, slivers whose
    // colour gradients need the exact sums and those whose depth gradient exceeds 2³⁰. The
    // first pixel is the left edge's (within a pixel of the triangle), so every colour value
    // there is within ±2³⁰ and its 32-bit word has not wrapped: red and blue are packed from
    // it as the portable code packs them from 64 bits.
    "scanline3d_gouraud_setup:",
    "push {{r4, r5, r6, r7, lr}}",
    "sub sp, #gs_frame",
    "str r1, [sp, #gs_rec]",
    "mov r12, r2",
    "ldm r0!, {{r1, r2, r3, r4, r5, r6, r7}}",
    "add r0, sp, #gs_va",
    "stm r0!, {{r1, r2, r3, r4, r5, r6, r7}}",
    // dx = 16·left.c + 8 − ax, dy = 16·row + 8 − ay, both within the i16 range.
    "ldrh r2, [r1, #{vx}]",
    "sxth r2, r2",
    "ldrh r3, [r1, #{vy}]",
    "sxth r3, r3",
    "lsls r6, r6, #4",
    "adds r6, #8",
    "subs r6, r6, r2",
    "sxth r0, r6",
    "cmp r0, r6",
    "beq 1f",
    "b 8f",
    "1:",
    "str r6, [sp, #gs_dx]",
    "lsls r5, r5, #4",
    "adds r5, #8",
    "subs r5, r5, r3",
    "sxth r0, r5",
    "cmp r0, r5",
    "beq 1f",
    "b 8f",
    "1:",
    "str r5, [sp, #gs_dy]",
    // The coordinate differences into the coefficient words (bx1 ← dy2, bx2 ← dy1,
    // by1 ← dx1, by2 ← dx2) and l = the bit length of the largest magnitude (of their OR).
    "ldr r4, [sp, #gs_vb]",
    "ldrh r0, [r4, #{vx}]",
    "sxth r0, r0",
    "subs r0, r0, r2",
    "str r0, [sp, #gs_by1]",
    "asrs r7, r0, #31",
    "eors r0, r7",
    "subs r0, r0, r7",
    "mov r5, r0",
    "ldrh r0, [r4, #{vy}]",
    "sxth r0, r0",
    "subs r0, r0, r3",
    "str r0, [sp, #gs_bx2]",
    "asrs r7, r0, #31",
    "eors r0, r7",
    "subs r0, r0, r7",
    "orrs r5, r0",
    "ldr r4, [sp, #gs_vc]",
    "ldrh r0, [r4, #{vx}]",
    "sxth r0, r0",
    "subs r0, r0, r2",
    "str r0, [sp, #gs_by2]",
    "asrs r7, r0, #31",
    "eors r0, r7",
    "subs r0, r0, r7",
    "orrs r5, r0",
    "ldrh r0, [r4, #{vy}]",
    "sxth r0, r0",
    "subs r0, r0, r3",
    "str r0, [sp, #gs_bx1]",
    "asrs r7, r0, #31",
    "eors r0, r7",
    "subs r0, r0, r7",
    "orrs r0, r5",
    bitlen16!(),
    "str r1, [sp, #gs_k]",
    // 1/|det| = m·2^-(29 + s).
    "ldr r4, [sp, #gs_det]",
    "asrs r0, r4, #31",
    "eors r4, r0",
    "subs r4, r4, r0",
    "mov r2, r12",
    recip_norm!(),
    // shift = 29 + s − (l + 4); k = shift − 1 (10..=54); the red and blue rounding
    // r = shift − 11 − 15 (gs_r = r − 1), green's one less: below 1 the portable code keeps
    // exact sums, and so it does where shift − l < `raster::COARSE_MIN` (a triangle too thin
    // for the 20-bit coefficients).
    "ldr r2, [sp, #gs_k]",
    "adds r5, #25",
    "subs r5, r5, r2",
    "subs r0, r5, r2",
    "subs r0, #{coarse_min}",
    "bpl 1f",
    "b 8f",
    "1:",
    "subs r0, r5, #1",
    "str r0, [sp, #gs_k]",
    "subs r5, #27",
    "str r5, [sp, #gs_r]",
    "subs r5, #1",
    "bpl 1f",
    "b 8f",
    "1:",
    // The coefficients and their 20-bit roundings.
    "lsrs r0, r6, #15",
    "movs r1, #0x7f",
    "lsls r1, r1, #8",
    "adds r1, #0xff",
    "ands r1, r6",
    "movs r3, #15",
    "subs r3, r3, r2",
    "ldr r4, [sp, #gs_det]",
    "asrs r4, r4, #31",
    "movs r5, #1",
    "lsls r5, r5, #10",
    coefficient!("gs_bx1", "gs_c20"),
    coefficient!("gs_bx2", "gs_c20 + 4"),
    coefficient!("gs_by1", "gs_c20 + 8"),
    coefficient!("gs_by2", "gs_c20 + 12"),
    // Depth (16.12): a0 = the first vertex's, da1 and da2 the others' differences from it.
    vertex_depth!("gs_va", "r1"),
    "str r1, [sp, #gs_a0]",
    vertex_depth!("gs_vb", "r0"),
    "subs r0, r0, r1",
    "str r0, [sp, #gs_da1]",
    vertex_depth!("gs_vc", "r0"),
    "subs r0, r0, r1",
    "str r0, [sp, #gs_da2]",
    depth_gradient!("gs_da1", "gs_bx1", "gs_da2", "gs_bx2", "gs_gx"),
    depth_gradient!("gs_da2", "gs_by1", "gs_da1", "gs_by2", "gs_gy"),
    // Packed (`raster::pack_zrgb`) into the record (r7) as each attribute is done: its
    // gradient, its value at the first pixel with its rounding bias, and its row step
    // `Gy + Gx·sq` of the packed gradients (for the colours completed at the end); each word
    // of the record is [depth << 4, red << 16 + blue (rounded to 11 fraction bits),
    // green << 6, 0]. Depth: gy is in r5.
    "ldr r7, [sp, #gs_rec]",
    "ldr r0, [sp, #gs_gx]",
    "mov r3, r5",
    "ldr r1, [sp, #gs_lsq]",
    "muls r1, r0, r1",
    "adds r1, r1, r3",
    "lsls r1, r1, #4",
    "str r1, [r7, #{inc}]",
    "lsls r2, r0, #4",
    "str r2, [r7, #{gx}]",
    prestep!(),
    "ldr r1, [sp, #gs_a0]",
    "adds r0, r0, r1",
    "lsls r0, r0, #4",
    "movs r1, #1",
    "lsls r1, r1, #15",
    "adds r0, r0, r1",
    "str r0, [r7, #{row}]",
    "movs r0, #0",
    "str r0, [r7, #{gx} + 12]",
    "str r0, [r7, #{row} + 12]",
    "str r0, [r7, #{inc} + 12]",
    // Blue, red, green: 10-bit channels with 5, 4, 5 fraction bits, to 20.
    channel!(
        "{vrgb} + 2", "16", "15", "",
        pack_blue!("r2", "{gx} + 4", ""),
        pack_blue!("r1", "{inc} + 4", ""),
        pack_blue!("r0", "{row} + 4", "lsls r4, r6, #2\nadds r0, r0, r4\n")
    ),
    channel!(
        "{vrgb}", "20", "15", "",
        pack_red!("r2", "{gx} + 4", ""),
        pack_red!("r1", "{inc} + 4", ""),
        pack_red!("r0", "{row} + 4", "lsls r4, r6, #2\nadds r0, r0, r4\n")
    ),
    channel!(
        "{vrgb} + 1", "18", "16", "subs r2, #1\n",
        pack_green!("r2", "{gx} + 8"),
        pack_green!("r1", "{inc} + 8"),
        concat!("lsls r4, r6, #11\nadds r0, r0, r4\n", pack_green!("r0", "{row} + 8"))
    ),
    // The red-blue and green row steps: Gy + Gx·sq from the packed words (r7 = the record).
    "ldr r1, [sp, #gs_lsq]",
    "ldr r0, [r7, #{gx} + 4]",
    "muls r0, r1, r0",
    "ldr r2, [r7, #{inc} + 4]",
    "adds r0, r0, r2",
    "str r0, [r7, #{inc} + 4]",
    "ldr r0, [r7, #{gx} + 8]",
    "muls r0, r1, r0",
    "ldr r2, [r7, #{inc} + 8]",
    "adds r0, r0, r2",
    "str r0, [r7, #{inc} + 8]",
    "movs r0, #1",
    "add sp, #gs_frame",
    "pop {{r4, r5, r6, r7, pc}}",
    "8:",
    "movs r0, #0",
    "add sp, #gs_frame",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_gouraud_setup, . - scanline3d_gouraud_setup",
    vx = const core::mem::offset_of!(ScreenVertex, x),
    vy = const core::mem::offset_of!(ScreenVertex, y),
    vz = const core::mem::offset_of!(ScreenVertex, z),
    vzf = const core::mem::offset_of!(ScreenVertex, zf),
    vrgb = const crate::kernel::records::RGB_HI_OFFSET,
    vfl = const crate::kernel::records::FLAGS_OFFSET,
    gx = const o::GX,
    row = const o::ROW,
    inc = const o::INC,
    coarse_min = const crate::kernel::records::COARSE_MIN,
);

/// `raster::attribute_words` of a fast Gouraud triangle with RGB565 channels
/// (`C::CHANNEL_MAX == [31, 63, 31]`), written into `rec`'s `gx`, `row` and `inc` by
/// [`scanline3d_gouraud_setup`]; false where it declines and the portable code computes them
/// (nothing written, but for the Thumb-2 form's rare late decline of a sliver, after which
/// some of those words are written: the portable code overwrites them all).
#[inline(always)]
pub(crate) fn gouraud_setup(rec: &mut ActiveTri, tri: &Sorted<'_>) -> bool {
    const {
        assert!(o::ROW == o::GX + 16 && o::INC == o::ROW + 16);
        assert!(core::mem::size_of::<Sorted<'_>>() == 28);
    };
    let seed: &'static [u16; 128] = &crate::kernel::wide::RECIP_SEED;
    // SAFETY: `Sorted` is `repr(C)`, seven words (three vertex pointers, four `i32`), which the
    // routine reads along with the three vertices (at the field offsets given to it) and the
    // 128-entry seed table; it writes only the twelve words of `rec` from `gx` on (`gx`, `row`
    // and `inc`, contiguous, as asserted above).
    unsafe { scanline3d_gouraud_setup(tri as *const Sorted as *const u32, rec, seed.as_ptr()) != 0 }
}
