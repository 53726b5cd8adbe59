//! The dither check of a fast Gouraud triangle with RGB565 channels
//! (`raster::ActiveTri::dither_fits`): whether every packed field keeps its headroom for any
//! Bayer offset at every point of the triangle.
#![allow(unsafe_code)]

use super::offsets as o;
use crate::kernel::records::{ActiveTri, ScreenVertex};

extern "C" {
    fn scanline3d_dither_fits565(
        rec: *const ActiveTri,
        p: *const *const ScreenVertex,
        row: i32,
    ) -> u32;
}

/// For [`scanline3d_dither_fits565`]: vertex `$k` (its pointer at word `$k` of the array in
/// frame word `df_vp`) passes the three field tests of `raster::ActiveTri::dither_fits`, or
/// the routine leaves through `.Ldf_fail`. r4 = dx, r5 = dy (subpixels from the first pixel's
/// centre), r6 = the vertex, r2 = its flags half (the low two bits of each 10-bit channel in
/// bits 10–15), r0, r1, r3, r7 scratch.
macro_rules! dither_fits_vertex {
    ($k:literal) => {
        concat!(
            "ldr r6, [sp, #df_vp]\n",
            "ldr r6, [r6, #4 * ", $k, "]\n",
            "ldr r0, [r6]\n",
            "sxth r4, r0\n",
            "asrs r5, r0, #16\n",
            "ldr r1, [sp, #df_ox]\n",
            "subs r4, r4, r1\n",
            "ldr r1, [sp, #df_oy]\n",
            "subs r5, r5, r1\n",
            "ldrh r2, [r6, #{vfl}]\n",
            // Blue, then red: U = K + gx·dx + gy·dy (= 16·F − 16·lo), in range when U < 16·(2¹⁶ −
            // 2·lo); then U − 2¹⁰·c + 7168 ≤ 2¹⁴ (|16·F − 16·ideal| ≤ 16·e).
            field16_fits_asm!("df_bx", "df_by", "df_kb", "2", "lsrs r1, r2, #14\n"),
            field16_fits_asm!("df_rx", "df_ry", "df_kr", "0", "lsls r1, r2, #20\nlsrs r1, r1, #30\n"),
            // Green: X = L0 + gxl·dx + gyl·dy (the low products, |X| < 2³¹), T' = T0' + gxh·dx +
            // gyh·dy + (X >> 16) = ⌊16·F / 2¹⁶⌋ − 7680; in range when T' < 1 033 216; then u =
            // T' + 3584 − 2¹⁰·c within 0..=8192, and 8192 only with X's low half 0.
            "ldr r0, [sp, #df_gxl]\n",
            "muls r0, r4, r0\n",
            "ldr r1, [sp, #df_gyl]\n",
            "muls r1, r5, r1\n",
            "adds r0, r0, r1\n",
            "ldr r1, [sp, #df_l0]\n",
            "adds r0, r0, r1\n",
            "ldr r1, [sp, #df_gxh]\n",
            "muls r1, r4, r1\n",
            "ldr r3, [sp, #df_gyh]\n",
            "muls r3, r5, r3\n",
            "adds r1, r1, r3\n",
            "ldr r3, [sp, #df_t0]\n",
            "adds r1, r1, r3\n",
            "asrs r3, r0, #16\n",
            "adds r1, r1, r3\n",
            "cmp r1, r9\n",
            "bhs 9f\n",
            "ldrb r3, [r6, #{vrgb} + 1]\n",
            "lsls r3, r3, #12\n",
            "lsls r7, r2, #18\n",
            "lsrs r7, r7, #30\n",
            "lsls r7, r7, #10\n",
            "adds r3, r3, r7\n",
            "subs r1, r1, r3\n",
            "add r1, r12\n",
            "cmp r1, lr\n",
            "bhi 9f\n",
            "bne 1f\n",
            "lsls r0, r0, #16\n",
            "bne 9f\n",
            "1:\n",
            // Out of reach of the conditional branches above: their way out.
            "b 8f\n",
            "9:\n",
            "b .Ldf_fail\n",
            "8:\n",
        )
    };
}

/// For [`dither_fits_vertex`]: one 16-bit field of the packed red-blue word (gradient halves in
/// frame words `$gx`, `$gy`, the constant in `$k`; the vertex colour's high byte at
/// `rgb_hi[$c]`, its low two bits from r2 by `$lo`, which leaves them in bits 0–1 of r1).
macro_rules! field16_fits_asm {
    ($gx:literal, $gy:literal, $k:literal, $c:literal, $lo:expr) => {
        concat!(
            "ldr r0, [sp, #",
            $gx,
            "]\n",
            "muls r0, r4, r0\n",
            "ldr r1, [sp, #",
            $gy,
            "]\n",
            "muls r1, r5, r1\n",
            "adds r0, r0, r1\n",
            "ldr r1, [sp, #",
            $k,
            "]\n",
            "adds r0, r0, r1\n",
            "cmp r0, r8\n",
            "bhs 9f\n",
            "ldrb r3, [r6, #{vrgb} + ",
            $c,
            "]\n",
            "lsls r3, r3, #12\n",
            $lo,
            "lsls r1, r1, #10\n",
            "adds r3, r3, r1\n",
            "subs r0, r0, r3\n",
            "add r0, r10\n",
            "cmp r0, r11\n",
            "bhi 9f\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_dither_fits565,\"ax\",%progbits",
    ".global scanline3d_dither_fits565",
    ".type scanline3d_dither_fits565,%function",
    ".p2align 2",
    ".thumb_func",
    ".equ df_vp, 0",
    ".equ df_ox, 4",
    ".equ df_oy, 8",
    ".equ df_bx, 12",
    ".equ df_by, 16",
    ".equ df_kb, 20",
    ".equ df_rx, 24",
    ".equ df_ry, 28",
    ".equ df_kr, 32",
    ".equ df_gxl, 36",
    ".equ df_gyl, 40",
    ".equ df_gxh, 44",
    ".equ df_gyh, 48",
    ".equ df_l0, 52",
    ".equ df_t0, 56",
    ".equ df_frame, 60",
    // r0 = the record of a fast Gouraud triangle just set up on row r2 with RGB565 channels,
    // r1 = its three vertices (pointers). `raster::ActiveTri::dither_fits` for RGB565
    // (red and blue with 11 fraction bits in the packed word, green with 26; vertex channels
    // 5.5, 6.4, 5.5): returns 1 when every field fits at every vertex, else 0. The frame holds
    // the per-triangle terms (the `df_` words), the vertex loop is unrolled.
    "scanline3d_dither_fits565:",
    save_registers!(),
    // The tests' bounds in high registers: r8 = 16·(2¹⁶ − 2·lo) = 1 017 856 and r11 = 2¹⁴ (red
    // and blue), r10 = 7168 (their distance bias), r9 = 1 033 216 (green's range), r12 = 3584
    // (its distance bias) and lr = 8192 (its bound); the return address is on the stack.
    "ldr r4, =1017856",
    "mov r8, r4",
    "ldr r4, =1033216",
    "mov r9, r4",
    "movs r4, #7",
    "lsls r4, r4, #10",
    "mov r10, r4",
    "lsrs r4, r4, #1",
    "mov r12, r4",
    "movs r4, #1",
    "lsls r4, r4, #14",
    "mov r11, r4",
    "lsrs r4, r4, #1",
    "mov lr, r4",
    "sub sp, #df_frame",
    "str r1, [sp, #df_vp]",
    // The first pixel's centre in subpixels: ox = 16·c + 8 (c = the left edge's biased
    // column − 2¹⁵: the half's top bit flipped, then sign-extended), oy = 16·row + 8.
    "lsls r2, r2, #4",
    "adds r2, #8",
    "str r2, [sp, #df_oy]",
    "ldr r3, [r0, #{lw}]",
    "lsls r3, r3, #16",
    "movs r4, #1",
    "lsls r4, r4, #31",
    "eors r3, r4",
    "asrs r3, r3, #12",
    "adds r3, #8",
    "str r3, [sp, #df_ox]",
    // r5 = the left edge's sq; gy = inc − gx·sq for each word.
    "ldr r5, [r0, #{ls}]",
    "sxth r5, r5",
    // Red and blue: gradient halves (blue the signed low half, red the rest) and
    // K = 16·field − 15 360 of the start word's halves.
    "ldr r1, [r0, #{gx1}]",
    "ldr r2, [r0, #{inc1}]",
    "mov r4, r1",
    "muls r4, r5, r4",
    "subs r2, r2, r4",
    "sxth r3, r1",
    "str r3, [sp, #df_bx]",
    "subs r1, r1, r3",
    "asrs r1, r1, #16",
    "str r1, [sp, #df_rx]",
    "sxth r3, r2",
    "str r3, [sp, #df_by]",
    "subs r2, r2, r3",
    "asrs r2, r2, #16",
    "str r2, [sp, #df_ry]",
    "ldr r1, [r0, #{row1}]",
    "uxth r2, r1",
    "lsls r2, r2, #4",
    "ldr r3, =15360",
    "subs r2, r2, r3",
    "str r2, [sp, #df_kb]",
    "lsrs r1, r1, #16",
    "lsls r1, r1, #4",
    "subs r1, r1, r3",
    "str r1, [sp, #df_kr]",
    // Green: the gradients' low halves (unsigned) and high halves (signed), L0 = the low half
    // of 16·a and T0' = (16·a >> 16) − 7680.
    "ldr r1, [r0, #{gx2}]",
    "ldr r2, [r0, #{inc2}]",
    "mov r4, r1",
    "muls r4, r5, r4",
    "subs r2, r2, r4",
    "uxth r3, r1",
    "str r3, [sp, #df_gxl]",
    "asrs r1, r1, #16",
    "str r1, [sp, #df_gxh]",
    "uxth r3, r2",
    "str r3, [sp, #df_gyl]",
    "asrs r2, r2, #16",
    "str r2, [sp, #df_gyh]",
    "ldr r1, [r0, #{row2}]",
    "lsls r2, r1, #4",
    "uxth r2, r2",
    "str r2, [sp, #df_l0]",
    "lsrs r1, r1, #12",
    "ldr r3, =7680",
    "subs r1, r1, r3",
    "str r1, [sp, #df_t0]",
    dither_fits_vertex!("0"),
    dither_fits_vertex!("1"),
    dither_fits_vertex!("2"),
    "movs r0, #1",
    "b .Ldf_out",
    ".Ldf_fail:",
    "movs r0, #0",
    ".Ldf_out:",
    "add sp, #df_frame",
    restore_registers_and_return!(),
    ".ltorg",
    ".size scanline3d_dither_fits565, . - scanline3d_dither_fits565",
    lw = const o::LEFT + o::W,
    ls = const o::LEFT + o::S,
    gx1 = const o::GX + 4,
    gx2 = const o::GX + 8,
    row1 = const o::ROW + 4,
    row2 = const o::ROW + 8,
    inc1 = const o::INC + 4,
    inc2 = const o::INC + 8,
    vrgb = const crate::kernel::records::RGB_HI_OFFSET,
    vfl = const crate::kernel::records::FLAGS_OFFSET,
);

/// `raster::ActiveTri::dither_fits` for RGB565 by [`scanline3d_dither_fits565`]: `rec` is a
/// fast Gouraud triangle just set up on `row` from the vertices `p` (so its first pixel and
/// every vertex are within the 1024-pixel box the fast path requires: the routine's sums stay
/// within 32 bits).
#[inline(always)]
pub(crate) fn dither_fits565(rec: &ActiveTri, p: [&ScreenVertex; 3], row: i32) -> bool {
    const {
        assert!(
            crate::kernel::records::FLAGS_OFFSET == 10
                && crate::kernel::records::RGB_HI_OFFSET + 2 < 10
        );
        assert!(o::INC + 8 <= 124 && o::LEFT + o::S <= 124);
    };
    let ptrs = p.map(|v| v as *const ScreenVertex);
    // SAFETY: the routine reads the record's left edge, `gx`, `row` and `inc` words (at the
    // offsets given to it) and the three vertices' first word, colour bytes and flags half
    // (12-byte `repr(C)` records, offsets asserted above and by `setup565`); it writes only its
    // own frame.
    unsafe { scanline3d_dither_fits565(rec, ptrs.as_ptr(), row) != 0 }
}
