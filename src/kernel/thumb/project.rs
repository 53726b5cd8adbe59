//! The Q16.16 perspective divide and viewport transform of one clip-space point (with the
//! normalized reciprocal), and the reciprocal macro the triangle setup reuses.
#![allow(unsafe_code)]

#[cfg(scanline3d_thumb_geometry)]
extern "C" {
    fn scanline3d_project_q16(p: *const i32, scales: u32, seed: *const u16, out: *mut i32) -> u32;
}

/// `scalar::recip_norm(a)` for `0 < a < 2³¹` in r4, with `scalar::RECIP_SEED` in r2: r6 = the
/// mantissa m in [1, 2³⁰], r5 = s, the bit length of `a` (1/a = m·2^-(29 + s)). A table seed,
/// one Newton step in 32-bit products and one in 64-bit ones, as the portable code. Uses
/// r0–r3 and r7; about 75 instructions.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! recip_norm {
    () => {
        concat!(
            // `scalar::recip_norm(w)`. r4 = w normalized (bit 31 set), r5 = s = its bit length.
            "movs r5, #32\n",
            "lsrs r6, r4, #16\n",
            "bne 1f\n",
            "lsls r4, r4, #16\n",
            "subs r5, #16\n",
            "1:\n",
            "lsrs r6, r4, #24\n",
            "bne 1f\n",
            "lsls r4, r4, #8\n",
            "subs r5, #8\n",
            "1:\n",
            "lsrs r6, r4, #28\n",
            "bne 1f\n",
            "lsls r4, r4, #4\n",
            "subs r5, #4\n",
            "1:\n",
            "lsrs r6, r4, #30\n",
            "bne 1f\n",
            "lsls r4, r4, #2\n",
            "subs r5, #2\n",
            "1:\n",
            "cmp r4, #0\n",
            "blt 1f\n",
            "lsls r4, r4, #1\n",
            "subs r5, #1\n",
            "1:\n",
            // x0 = seed[(a32 >> 24) & 127] + 2¹⁶; e = −d·x0 (d = a32 >> 16);
            // x1 = x0 + ((x0 >> 1)·(e >> 10) >> 21); m0 = x1 << 13 (r6).
            "lsrs r6, r4, #23\n",
            "movs r7, #254\n",
            "ands r6, r7\n",
            "ldrh r6, [r2, r6]\n",
            "movs r7, #1\n",
            "lsls r7, r7, #16\n",
            "adds r6, r6, r7\n",
            "lsrs r7, r4, #16\n",
            "muls r7, r6, r7\n",
            "negs r7, r7\n",
            "asrs r7, r7, #10\n",
            "lsrs r3, r6, #1\n",
            "muls r7, r3, r7\n",
            "asrs r7, r7, #21\n",
            "adds r6, r6, r7\n",
            "lsls r6, r6, #13\n",
            // r1:r7 = a32·m0 (unsigned): al·bl, al·bh (< 2³⁰) and ah·bl (< 2³², their sum may
            // carry), ah·bh.
            "uxth r0, r4\n",
            "lsrs r1, r4, #16\n",
            "uxth r2, r6\n",
            "lsrs r3, r6, #16\n",
            "mov r7, r0\n",
            "muls r7, r2, r7\n",
            "muls r0, r3, r0\n",
            "muls r2, r1, r2\n",
            "muls r1, r3, r1\n",
            "adds r0, r0, r2\n",
            "movs r2, #0\n",
            "adcs r2, r2\n",
            "lsls r2, r2, #16\n",
            "adds r1, r1, r2\n",
            "lsls r2, r0, #16\n",
            "lsrs r0, r0, #16\n",
            "adds r7, r7, r2\n",
            "adcs r1, r0\n",
            // err = 2⁶¹ − a32·m0 (|err| < 2⁴⁷); t = err >> 30 (r2).
            "movs r2, #1\n",
            "lsls r2, r2, #29\n",
            "negs r7, r7\n",
            "sbcs r2, r1\n",
            "lsls r2, r2, #2\n",
            "lsrs r7, r7, #30\n",
            "orrs r2, r7\n",
            // m1 = m0 + (m0·t >> 31) (the signed product from four halves), clamped to [1, 2³⁰].
            "uxth r0, r6\n",
            "lsrs r1, r6, #16\n",
            "uxth r3, r2\n",
            "asrs r2, r2, #16\n",
            "mov r4, r0\n",
            "muls r4, r3, r4\n",
            "muls r3, r1, r3\n",
            "muls r1, r2, r1\n",
            "muls r0, r2, r0\n",
            "adds r0, r0, r3\n",
            "lsls r3, r0, #16\n",
            "asrs r0, r0, #16\n",
            "adds r4, r4, r3\n",
            "adcs r1, r0\n",
            "lsls r1, r1, #1\n",
            "lsrs r4, r4, #31\n",
            "orrs r1, r4\n",
            "adds r6, r6, r1\n",
            "cmp r6, #1\n",
            "bge 1f\n",
            "movs r6, #1\n",
            "1:\n",
            "movs r0, #1\n",
            "lsls r0, r0, #30\n",
            "cmp r6, r0\n",
            "ble 1f\n",
            "mov r6, r0\n",
            "1:\n",
        )
    };
}

/// For [`scanline3d_project_q16`]: `v·m`, rounded to `ns` fraction bits fewer, as
/// `scalar::round_shr_words(mul_wide(v, m), ns)` — the Q16.16 `ndc` of `v` — for the word
/// at byte offset `$off` of the point (frame word 0) and the reciprocal's mantissa `m` in r6
/// (0 < m ≤ 2³⁰). r5 = ns, r12 = 2^(ns − 1), lr = 32 − ns. Out: r0 = high word (signed),
/// r4 = low word. Uses r1–r3. With v = vh·2¹⁶ + vl and m likewise (mh ≤ 2¹⁴): vl·ml is
/// added unsigned, vl·mh (< 2³⁰) unsigned and vh·ml (|·| < 2³¹) signed, each shifted by 16,
/// and vh·mh to the high word. 29 instructions, four of them `muls`.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! ndc_words {
    ($off:literal) => {
        concat!(
            "ldr r0, [sp, #0]\n",
            "ldr r0, [r0, #",
            $off,
            "]\n",
            "uxth r1, r0\n",
            "asrs r0, r0, #16\n",
            "uxth r2, r6\n",
            "lsrs r3, r6, #16\n",
            "mov r4, r1\n",
            "muls r4, r2, r4\n",
            "muls r1, r3, r1\n",
            "muls r2, r0, r2\n",
            "muls r0, r3, r0\n",
            "lsls r3, r1, #16\n",
            "lsrs r1, r1, #16\n",
            "adds r4, r4, r3\n",
            "adcs r0, r1\n",
            "lsls r3, r2, #16\n",
            "asrs r2, r2, #16\n",
            "adds r4, r4, r3\n",
            "adcs r0, r2\n",
            // + 2^(ns − 1), then the 64-bit arithmetic shift by ns in 32-bit shifts.
            "mov r1, r12\n",
            "adds r4, r4, r1\n",
            "movs r1, #0\n",
            "adcs r0, r1\n",
            "lsrs r4, r4, r5\n",
            "mov r1, lr\n",
            "mov r2, r0\n",
            "lsls r2, r2, r1\n",
            "orrs r4, r2\n",
            "asrs r0, r0, r5\n",
        )
    };
}

/// For [`scanline3d_project_q16`]: the screen coordinate of the quotient r0:r4 (high, low
/// word) for the scale `k` that `$k` extracts from frame word 1 into r1, stored at byte
/// offset `$out` of the result (frame word 2): `clamp(hi·k + ((lo·k + 2³¹) >> 32) + k,
/// ±COORD_LIMIT)` (the limit in frame word 3), as `Viewport::project` computes it through `scalar::mul_q32_short`; a high word
/// beyond the `i16` range branches to label 9 (declined). Uses r1–r3.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! screen_coordinate {
    ($k:literal, $out:literal) => {
        concat!(
            "sxth r2, r0\n",
            "cmp r2, r0\n",
            "beq 1f\n",
            "b 9f\n",
            "1:\n",
            "ldr r1, [sp, #4]\n",
            $k,
            // t = (lo >> 16)·k + ((lo & 0xffff)·k >> 16); (lo·k + 2³¹) >> 32 = (t + 2¹⁵) >> 16.
            "lsrs r2, r4, #16\n",
            "muls r2, r1, r2\n",
            "uxth r3, r4\n",
            "muls r3, r1, r3\n",
            "lsrs r3, r3, #16\n",
            "adds r2, r2, r3\n",
            "lsrs r2, r2, #15\n",
            "adds r2, #1\n",
            "lsrs r2, r2, #1\n",
            "muls r0, r1, r0\n",
            "adds r0, r0, r2\n",
            "adds r0, r0, r1\n",
            "ldr r2, [sp, #12]\n",
            "cmp r0, r2\n",
            "ble 1f\n",
            "mov r0, r2\n",
            "1:\n",
            "negs r2, r2\n",
            "cmp r0, r2\n",
            "bge 1f\n",
            "mov r0, r2\n",
            "1:\n",
            "ldr r1, [sp, #8]\n",
            "str r0, [r1, #",
            $out,
            "]\n",
        )
    };
}

// Thumb-1; on Thumb-2 cores `project_t2` assembles the same routine from Thumb-2 forms.
#[cfg(not(scanline3d_thumb2))]
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_project_q16,\"ax\",%progbits",
    ".global scanline3d_project_q16",
    ".type scanline3d_project_q16,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = the clip-space point (x, y, z, w: four Q16.16 words), r1 = sx | sy << 16 (the
    // screen scales 8·width and 8·height), r2 = `scalar::RECIP_SEED`, r3 = the result (three
    // words: x and y in subpixels, clamped to ±COORD_LIMIT, and the depth as unsigned 16.8).
    // Returns 1, or 0 (nothing written but maybe some of the words) for the cases the
    // portable code handles: w ≤ 2⁻¹³ and quotients beyond the guard band.
    "scanline3d_project_q16:",
    "push {{r4, r5, r6, r7, lr}}",
    "sub sp, #16",
    "str r0, [sp, #0]",
    "str r1, [sp, #4]",
    "str r3, [sp, #8]",
    "ldr r4, [r0, #12]",
    "cmp r4, #0",
    "bgt 1f",
    "b 9f",
    "1:",
    recip_norm!(),
    // The quotients' shift is ns = 29 + s − 32; the portable code handles ns ≤ 0.
    "cmp r5, #4",
    "bge 1f",
    "b 9f",
    "1:",
    // r5 = ns, r12 = 2^(ns − 1), lr = 32 − ns, frame word 3 = COORD_LIMIT.
    "subs r5, #3",
    "movs r1, #1",
    "subs r0, r5, #1",
    "lsls r1, r1, r0",
    "mov r12, r1",
    "movs r1, #32",
    "subs r1, r1, r5",
    "mov lr, r1",
    "movs r1, #{lim_bits}",
    "movs r0, #1",
    "lsls r0, r0, r1",
    "subs r0, #1",
    "str r0, [sp, #12]",
    // x: + ndc·sx + sx.
    ndc_words!("0"),
    screen_coordinate!("uxth r1, r1\n", "0"),
    // y: − ndc·sy + sy (the negation in words, as `ndc_scaled`).
    ndc_words!("4"),
    "mvns r0, r0",
    "negs r4, r4",
    "movs r1, #0",
    "adcs r0, r1",
    screen_coordinate!("lsrs r1, r1, #16\n", "4"),
    // z: the quotient nz clamped to [0, 2³²], then ((nz·65535·2¹² + 2³¹) >> 32 + 8) >> 4,
    // where (lo·65535·2¹² + 2³¹) >> 32 = (A + (B >> 16) + 8) >> 4 for A = (lo >> 16)·65535
    // and B = (lo & 0xffff)·65535 (2¹⁹ is 8·2¹⁶: it adds 8 to B >> 16 and cannot overflow).
    ndc_words!("8"),
    "cmp r0, #0",
    "bne 2f",
    "lsrs r1, r4, #16",
    "lsls r2, r1, #16",
    "subs r2, r2, r1",
    "uxth r1, r4",
    "lsls r3, r1, #16",
    "subs r3, r3, r1",
    "lsrs r3, r3, #16",
    "adds r3, #8",
    "adds r2, r2, r3",
    "lsrs r2, r2, #4",
    "adds r2, #8",
    "lsrs r2, r2, #4",
    "b 3f",
    // nz < 0: depth 0; nz ≥ 2³²: the far plane, 65535·2⁸.
    "2:",
    "movs r2, #0",
    "cmp r0, #0",
    "blt 3f",
    "movs r2, #255",
    "lsls r2, r2, #8",
    "adds r2, #255",
    "lsls r2, r2, #8",
    "3:",
    "ldr r1, [sp, #8]",
    "str r2, [r1, #8]",
    "movs r0, #1",
    "add sp, #16",
    "pop {{r4, r5, r6, r7, pc}}",
    "9:",
    "movs r0, #0",
    "add sp, #16",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_project_q16, . - scanline3d_project_q16",
    lim_bits = const 14,
);

/// `Viewport::project`'s screen words (x and y in subpixels, clamped to ±`COORD_LIMIT`, and
/// the depth as unsigned 16.8) of a Q16.16 clip-space point by [`scanline3d_project_q16`],
/// for the scales `sx`, `sy` < 2¹⁶; `None` where it declines (w ≤ 2⁻¹³, or a quotient
/// beyond the guard band: points that are clipped before they are projected), and the
/// portable code computes them.
#[inline(always)]
#[cfg(scanline3d_thumb_geometry)]
pub(crate) fn project_q16(p: &[i32; 4], sx: u32, sy: u32) -> Option<[i32; 3]> {
    if (sx | sy) >> 16 != 0 {
        return None;
    }
    let mut out = [0i32; 3];
    // SAFETY: the routine reads the point's four words and the 128-entry seed table, and writes
    // only the three words of `out`.
    let seed: &'static [u16; 128] = &crate::kernel::wide::RECIP_SEED;
    let ok = unsafe {
        scanline3d_project_q16(p.as_ptr(), sx | sy << 16, seed.as_ptr(), out.as_mut_ptr())
    };
    (ok != 0).then_some(out)
}
