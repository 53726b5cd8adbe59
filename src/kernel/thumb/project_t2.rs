//! Thumb-2 form (ARMv7-M and later: the `scanline3d_thumb2` cfg) of the Q16.16 perspective
//! divide and viewport transform, `scanline3d_project_q16` (`project`): the same arguments,
//! results and declines as the Thumb-1 routine, with `clz` for the reciprocal's
//! normalization and `smull`/`umull`/`mla` for its products — about 95 instructions a
//! vertex where the Thumb-1 routine takes about 250 and LLVM's `Viewport::screen_words`
//! about 175 on a Cortex-M4F.

/// `wide::recip_norm`'s mantissa for `$a`, the value normalized (bit 31 set), into `$m`: a
/// table seed (`wide::RECIP_SEED` at `$seed`), one Newton step in 32-bit products and one in
/// 64-bit ones, clamped to [1, 2³⁰]. `$a` is kept; `$seed`, `$t1`, `$t2` are clobbered (all
/// low registers but `$t2`). The projection and the triangle setup (`setup_t2`) share it.
/// (One instruction a line: rustfmt would put every operand on a line of its own.)
#[rustfmt::skip]
macro_rules! recip_mantissa_t2 {
    ($a:literal, $seed:literal, $m:literal, $t1:literal, $t2:literal) => {
        concat!(
            // x0 = seed[(a32 >> 24) & 127] + 2¹⁶; e = −d·x0 (d = a32 >> 16, wrapping);
            // x1 = x0 + ((x0 >> 1)·(e >> 10) >> 21); m0 = x1 << 13.
            "ubfx ", $m, ", ", $a, ", #24, #7\n",
            "ldrh ", $m, ", [", $seed, ", ", $m, ", lsl #1]\n",
            "add ", $m, ", ", $m, ", #65536\n",
            "lsrs ", $t1, ", ", $a, ", #16\n",
            "muls ", $t1, ", ", $m, ", ", $t1, "\n",
            "negs ", $t1, ", ", $t1, "\n",
            "asrs ", $t1, ", ", $t1, ", #10\n",
            "lsrs ", $seed, ", ", $m, ", #1\n",
            "muls ", $t1, ", ", $seed, ", ", $t1, "\n",
            "add ", $m, ", ", $m, ", ", $t1, ", asr #21\n",
            "lsls ", $m, ", ", $m, ", #13\n",
            // err = 2⁶¹ − a32·m0 (|err| < 2⁴⁷), t = err >> 30 (its low word, in $t2).
            "umull ", $t1, ", ", $seed, ", ", $a, ", ", $m, "\n",
            "mov ", $t2, ", #0x20000000\n",
            "negs ", $t1, ", ", $t1, "\n",
            "sbc ", $t2, ", ", $t2, ", ", $seed, "\n",
            "lsrs ", $t1, ", ", $t1, ", #30\n",
            "orr ", $t2, ", ", $t1, ", ", $t2, ", lsl #2\n",
            // m1 = m0 + (m0·t >> 31), clamped to [1, 2³⁰].
            "smull ", $t1, ", ", $seed, ", ", $m, ", ", $t2, "\n",
            "lsrs ", $t1, ", ", $t1, ", #31\n",
            "orr ", $seed, ", ", $t1, ", ", $seed, ", lsl #1\n",
            "adds ", $m, ", ", $m, ", ", $seed, "\n",
            "cmp ", $m, ", #1\n",
            "it lt\n",
            "movlt ", $m, ", #1\n",
            "cmp ", $m, ", #0x40000000\n",
            "it gt\n",
            "movgt ", $m, ", #0x40000000\n",
        )
    };
}

/// [`scanline3d_project_q16`]'s quotient `v·m` rounded to `ns` fraction bits fewer
/// (`wide::round_shr_words(mul_wide(v, m), ns)`, the Q16.16 `ndc` of `v`) for the word at
/// byte offset `$off` of the point (r8) and the reciprocal's mantissa in r6. r5 = ns (1..=28),
/// r12 = 2^(ns − 1), lr = 32 − ns. Out: r0 = high word (signed), r4 = low word. Uses r1.
macro_rules! ndc_words_t2 {
    ($off:literal) => {
        concat!(
            "ldr r0, [r8, #",
            $off,
            "]\n",
            "smull r4, r0, r0, r6\n",
            "adds r4, r4, r12\n",
            "adc r0, r0, #0\n",
            "lsr r4, r4, r5\n",
            "lsl r1, r0, lr\n",
            "orr r4, r4, r1\n",
            "asr r0, r0, r5\n",
        )
    };
}

/// [`scanline3d_project_q16`]'s screen coordinate of the quotient r0:r4 (high, low word) for
/// the scale `k` in r1, stored at byte offset `$out` of the result (r10): `clamp(hi·k +
/// ((lo·k + 2³¹) >> 32) + k, ±COORD_LIMIT)` (the limit in r7), as `wide::mul_q32_short`
/// computes it (its two 16-bit products give the same rounded high word as this `umull`); a
/// high word beyond the `i16` range branches to label 9 (declined). Uses r2, r3.
macro_rules! screen_coordinate_t2 {
    ($out:literal) => {
        concat!(
            "sxth r2, r0\n",
            "cmp r2, r0\n",
            "bne 9f\n",
            "umull r3, r2, r4, r1\n",
            "adds r3, r3, #0x80000000\n",
            "adc r2, r2, #0\n",
            "mla r0, r0, r1, r2\n",
            "add r0, r0, r1\n",
            "cmp r0, r7\n",
            "it gt\n",
            "movgt r0, r7\n",
            "cmn r0, r7\n",
            "it lt\n",
            "rsblt r0, r7, #0\n",
            "str r0, [r10, #",
            $out,
            "]\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_project_q16,\"ax\",%progbits",
    ".global scanline3d_project_q16",
    ".type scanline3d_project_q16,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = the clip-space point (x, y, z, w: four Q16.16 words), r1 = sx | sy << 16 (the
    // screen scales 8·width and 8·height), r2 = `wide::RECIP_SEED`, r3 = the result (three
    // words: x and y in subpixels, clamped to ±COORD_LIMIT, and the depth as unsigned 16.8).
    // Returns 1, or 0 (nothing written but maybe some of the words) for the cases the
    // portable code handles: w ≤ 2⁻¹³ and quotients beyond the guard band.
    // r8 = the point, r9 = the scales, r10 = the result.
    "scanline3d_project_q16:",
    "push {{r4, r5, r6, r7, r8, r9, r10, lr}}",
    "ldr r4, [r0, #12]",
    "cmp r4, #0",
    "ble 9f",
    "mov r8, r0",
    "mov r9, r1",
    "mov r10, r3",
    // `wide::recip_norm(w)`: r4 = w normalized (bit 31 set), r5 = s, its bit length.
    "clz r5, r4",
    "lsls r4, r4, r5",
    "rsb r5, r5, #32",
    // m1 (r6), as `wide::recip_norm`.
    recip_mantissa_t2!("r4", "r2", "r6", "r7", "r3"),
    // The quotients' shift is ns = 29 + s − 32; the portable code handles ns ≤ 0.
    "subs r5, r5, #3",
    "ble 9f",
    // r12 = 2^(ns − 1), lr = 32 − ns, r7 = COORD_LIMIT.
    "subs r0, r5, #1",
    "mov r12, #1",
    "lsl r12, r12, r0",
    "rsb lr, r5, #32",
    "movw r7, #{lim}",
    // x: + ndc·sx + sx.
    ndc_words_t2!("0"),
    "uxth r1, r9",
    screen_coordinate_t2!("0"),
    // y: − ndc·sy + sy (the negation in words, as `ndc_scaled`).
    ndc_words_t2!("4"),
    "mvns r0, r0",
    "negs r4, r4",
    "adc r0, r0, #0",
    "lsrs r1, r9, #16",
    screen_coordinate_t2!("4"),
    // z: the quotient nz clamped to [0, 2³²], then ((nz·65535·2¹² + 2³¹) >> 32 + 8) >> 4.
    ndc_words_t2!("8"),
    "cbnz r0, 2f",
    "movw r1, #0xf000",
    "movt r1, #0x0fff",
    "umull r3, r2, r4, r1",
    "adds r3, r3, #0x80000000",
    "adc r2, r2, #0",
    "adds r2, #8",
    "lsrs r2, r2, #4",
    "b 3f",
    // nz < 0: depth 0; nz ≥ 2³²: the far plane, 65535·2⁸.
    "2:",
    "movw r2, #0xff00",
    "movt r2, #0x00ff",
    "cmp r0, #0",
    "it lt",
    "movlt r2, #0",
    "3:",
    "str r2, [r10, #8]",
    "movs r0, #1",
    "pop {{r4, r5, r6, r7, r8, r9, r10, pc}}",
    "9:",
    "movs r0, #0",
    "pop {{r4, r5, r6, r7, r8, r9, r10, pc}}",
    ".size scanline3d_project_q16, . - scanline3d_project_q16",
    lim = const crate::kernel::records::COORD_LIMIT,
);
