//! The Q16.16 point and direction transforms (a 4 × 4 matrix times a point or a direction).
#![allow(unsafe_code)]

use crate::kernel::wide::spread_bits;

extern "C" {
    fn scanline3d_xform_q16(m: *const i32, p: *const i32, out: *mut i32, rows: u32);
}

/// One signed 32 × 32-bit product `a·b` of a transform row added to the 64-bit accumulator
/// r7:r6, for `|a|, |b| < 2³⁰`. In: r5 = the row, `a` at byte offset `$a`; the low (unsigned)
/// and high (signed) 16-bit halves of `b` in the high registers `$bl` and `$bh`. Uses r0–r4.
/// With a = ah·2¹⁶ + al and b likewise: al·bl (< 2³²) is added unsigned, ah·bh (< 2²⁸) to
/// the high word, and ah·bl + al·bh (each below 2³⁰ in magnitude, so their sum fits) shifted
/// by 16. 20 instructions, four of them `muls`.
macro_rules! q16_product {
    ($a:literal, $bl:literal, $bh:literal) => {
        concat!(
            "ldr r0, [r5, #",
            $a,
            "]\n",
            "uxth r1, r0\n",
            "asrs r0, r0, #16\n",
            "mov r2, ",
            $bl,
            "\n",
            "mov r3, ",
            $bh,
            "\n",
            "mov r4, r1\n",
            "muls r4, r2, r4\n",
            "adds r6, r6, r4\n",
            "movs r4, #0\n",
            "adcs r7, r4\n",
            "mov r4, r0\n",
            "muls r4, r3, r4\n",
            "adds r7, r7, r4\n",
            "muls r0, r2, r0\n",
            "muls r1, r3, r1\n",
            "adds r0, r0, r1\n",
            "lsls r4, r0, #16\n",
            "asrs r0, r0, #16\n",
            "adds r6, r6, r4\n",
            "adcs r7, r0\n",
        )
    };
}

/// One row of [`scanline3d_xform_q16`] (r5 = the row), its result stored at byte offset
/// `$out` of the result: `sat32((Σ a·b + (c << 16) + 2¹⁵) >> 16)`, c the row's last entry
/// masked by [sp, #4] (zero for a direction). Uses r0–r4, r6, r7.
macro_rules! xform_row {
    ($out:literal) => {
        concat!(
            // r7:r6 = (c << 16) + 2^15.
            "ldr r0, [r5, #12]\n",
            "ldr r1, [sp, #4]\n",
            "ands r0, r1\n",
            "lsls r6, r0, #16\n",
            "asrs r7, r0, #16\n",
            "movs r4, #1\n",
            "lsls r4, r4, #15\n",
            "adds r6, r6, r4\n",
            "movs r4, #0\n",
            "adcs r7, r4\n",
            q16_product!("0", "r8", "r9"),
            q16_product!("4", "r10", "r11"),
            q16_product!("8", "r12", "lr"),
            // r6 = the sum >> 16 when it fits an i32, else i32::MIN or i32::MAX by its sign.
            "lsrs r6, r6, #16\n",
            "lsls r0, r7, #16\n",
            "orrs r6, r0\n",
            "asrs r7, r7, #16\n",
            "asrs r0, r6, #31\n",
            "cmp r0, r7\n",
            "beq 2f\n",
            "movs r6, #1\n",
            "lsls r6, r6, #31\n",
            "cmp r7, #0\n",
            "blt 2f\n",
            "subs r6, #1\n",
            "2:\n",
            "ldr r0, [sp, #8]\n",
            "str r6, [r0, #",
            $out,
            "]\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_xform_q16,\"ax\",%progbits",
    ".global scanline3d_xform_q16",
    ".type scanline3d_xform_q16,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = the matrix (16 words, row after row), r1 = the point (3 words), r2 = the result
    // (r3 words), r3 = 4 for a point (w = 1: the last column counts) or 3 for a direction
    // (w = 0: the first three rows, last column ignored). Every entry used in [−2³⁰, 2³⁰).
    // Per row: sat32((Σ a·b + (c << 16) + 2¹⁵) >> 16). The point's halves live in r8–r12
    // and lr, so the stack holds only the saved registers, the result pointer, a mask and the
    // row count (48 bytes: this runs inside the geometry stage, where a 16 KB part has little
    // to spare).
    "scanline3d_xform_q16:",
    save_registers!(),
    // [sp, #8] = the result pointer, [sp, #4] = the mask of the last column (all ones for a
    // point, zero for a direction), [sp] = the number of rows. The rows are unrolled.
    "push {{r2}}",
    "subs r4, r3, #4",
    "mvns r4, r4",
    "push {{r4}}",
    "push {{r3}}",
    "ldr r3, [r1, #0]",
    "uxth r4, r3",
    "asrs r3, r3, #16",
    "mov r8, r4",
    "mov r9, r3",
    "ldr r3, [r1, #4]",
    "uxth r4, r3",
    "asrs r3, r3, #16",
    "mov r10, r4",
    "mov r11, r3",
    "ldr r3, [r1, #8]",
    "uxth r4, r3",
    "asrs r3, r3, #16",
    "mov r12, r4",
    "mov lr, r3",
    "mov r5, r0",
    xform_row!("0"),
    "adds r5, #16",
    xform_row!("4"),
    "adds r5, #16",
    xform_row!("8"),
    "ldr r0, [sp, #0]",
    "cmp r0, #4",
    "bne 3f",
    "adds r5, #16",
    xform_row!("12"),
    "3:",
    "add sp, #12",
    restore_registers_and_return!(),
    ".size scanline3d_xform_q16, . - scanline3d_xform_q16",
);

/// The first `R` rows of `m` times `(p, 1)` for `R = 4` (a point) or times `(p, 0)` for
/// `R = 3` (a direction: the upper 3 × 3 block), Q16.16 words, by [`scanline3d_xform_q16`]
/// when every entry it uses is in [−2³⁰, 2³⁰) — the condition under which the portable
/// `dot3_add` takes its plain 64-bit sum, whose result this is, bit for bit. `None` otherwise
/// (the portable code then saturates where it must). About 360 instructions for a point on a
/// Cortex-M0, where LLVM's version of the four rows takes about 600.
#[inline(always)]
pub(crate) fn transform_rows<const R: usize>(m: &[[i32; 4]; 4], p: [i32; 3]) -> Option<[i32; R]> {
    const { assert!(R == 3 || R == 4) };
    let mut s = spread_bits(p[0]) | spread_bits(p[1]) | spread_bits(p[2]);
    for row in &m[..R] {
        s |= spread_bits(row[0]) | spread_bits(row[1]) | spread_bits(row[2]);
        if R == 4 {
            s |= spread_bits(row[3]);
        }
    }
    if s >= 1 << 30 {
        return None;
    }
    let mut out = [0i32; R];
    // SAFETY: the matrix is 16 `i32` words, row after row; the routine reads the first `R`
    // rows (the last word of each only for R = 4) and the three words of `p`, and writes the
    // `R` words of `out`.
    unsafe {
        scanline3d_xform_q16(
            m.as_ptr() as *const i32,
            p.as_ptr(),
            out.as_mut_ptr(),
            R as u32,
        )
    };
    Some(out)
}

/// `m · (p, 1)` in Q16.16 words (see [`transform_rows`]).
#[inline(always)]
pub(crate) fn transform_q16(m: &[[i32; 4]; 4], p: [i32; 3]) -> Option<[i32; 4]> {
    transform_rows::<4>(m, p)
}

/// The upper 3 × 3 block of `m` times the direction `v`, Q16.16 words (see
/// [`transform_rows`]).
#[inline(always)]
pub(crate) fn transform_dir_q16(m: &[[i32; 4]; 4], v: [i32; 3]) -> Option<[i32; 3]> {
    transform_rows::<3>(m, v)
}
