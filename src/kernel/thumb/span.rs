//! The Gouraud span loops for RGB565 words (`DepthTest::Less`): plain, dithered (4×4 Bayer)
//! and, on ARMv6-M, flat; and the pixel-loop macros the row routines reuse.
#![allow(unsafe_code)]

use crate::kernel::records::DITHER565;

extern "C" {
    fn scanline3d_span565_less(
        z: *mut u16,
        color_offset: isize,
        end: *mut u16,
        acc: *const [u32; 6],
    ) -> u32;
    fn scanline3d_span565_less_dither(
        z: *mut u16,
        color_offset: isize,
        end: *mut u16,
        acc: *const [u32; 8],
    ) -> u32;
    #[cfg(scanline3d_thumb_v6m)]
    fn scanline3d_span565_flat_less(
        z: *mut u16,
        color_offset: isize,
        end: *mut u16,
        acc: *const [u32; 3],
    ) -> u32;
}

/// The pixel loop shared by both routines. In: r7 = end of the depth run, r1 = end of the
/// colour run, r0 = minus the run's length in bytes (< 0: the loop counts it up to zero and
/// addresses both lines from their ends, so the end test is the sign of that addition),
/// r2 = z, r3 = rb, r4 = g in the packed formats of a fast triangle
/// (`raster::pack_zrgb`: the depth is the high half of z, red and blue are the halves of rb
/// with 11 fraction bits each, green is the top 6 bits of g; rounding biases added), r8, r9,
/// r10 = their per-pixel steps (all wrapping, so these are the bits the portable loop
/// extracts). *Hidden* pixels are counted by the hidden path (`hidden_pixel!`: fewer than the
/// written ones in a typical frame — the torus has a few dozen — so the count costs the rare
/// path). Uses r5, r6. A hidden pixel branches to label 3, which must be placed (with
/// `hidden_pixel!`) after an unconditional branch within 256 bytes of the loop, right before
/// the code that follows the loop. 19 instructions per written pixel, 12 per hidden one.
#[cfg(not(scanline3d_thumb2))]
macro_rules! pixel_loop {
    () => {
        concat!(
            "1:\n",
            "ldrh r5, [r7, r0]\n",
            "lsrs r6, r2, #16\n",
            "cmp r6, r5\n",
            "bhs 3f\n",
            "strh r6, [r7, r0]\n",
            "lsrs r5, r3, #27\n",
            "lsls r5, r5, #11\n",
            "lsrs r6, r4, #26\n",
            "lsls r6, r6, #5\n",
            "orrs r5, r6\n",
            "lsls r6, r3, #16\n",
            "lsrs r6, r6, #27\n",
            "orrs r5, r6\n",
            "strh r5, [r1, r0]\n",
            gouraud_steps!(),
            "adds r0, #2\n",
            "bne 1b\n",
        )
    };
}

/// [`pixel_loop`] in Thumb-2 (ARMv7-M and later): the same registers and results; the colour
/// word in five instructions (`orr` with a shifted operand, `ubfx`) instead of eight. 16
/// instructions per written pixel, 12 per hidden one.
#[cfg(scanline3d_thumb2)]
macro_rules! pixel_loop {
    () => {
        concat!(
            "1:\n",
            "ldrh r5, [r7, r0]\n",
            "lsrs r6, r2, #16\n",
            "cmp r6, r5\n",
            "bhs 3f\n",
            "strh r6, [r7, r0]\n",
            "lsrs r5, r3, #27\n",
            "lsrs r6, r4, #26\n",
            "orr.w r5, r6, r5, lsl #6\n",
            "ubfx r6, r3, #11, #5\n",
            "orr.w r5, r6, r5, lsl #5\n",
            "strh r5, [r1, r0]\n",
            gouraud_steps!(),
            "adds r0, #2\n",
            "bne 1b\n",
        )
    };
}

/// The pixel loop's hidden-pixel path: counts it with `$count` (three instructions that add
/// one to the count, using r5), then the loop's own steps `$steps` and end test (repeated
/// here rather than branched back to), so that its last pixel falls through to what follows.
macro_rules! hidden_pixel {
    ($count:expr, $steps:expr) => {
        concat!("3:\n", $count, $steps, "adds r0, #2\n", "bne 1b\n",)
    };
}

/// For [`hidden_pixel`]: adds one to the count in the high register `$r`. Uses r5.
macro_rules! count_in {
    ($r:literal) => {
        concat!("mov r5, ", $r, "\n", "adds r5, #1\n", "mov ", $r, ", r5\n")
    };
}

/// For [`hidden_pixel`] in the row routine: adds one to the hidden count in its stack frame.
/// Uses r5.
macro_rules! count_on_stack {
    () => {
        "ldr r5, [sp, #20]\nadds r5, #1\nstr r5, [sp, #20]\n"
    };
}

/// The per-pixel steps of [`pixel_loop`] (for [`hidden_pixel`]).
macro_rules! gouraud_steps {
    () => {
        "add r2, r8\nadd r3, r9\nadd r4, r10\n"
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_span565_less,\"ax\",%progbits",
    ".global scanline3d_span565_less",
    ".type scanline3d_span565_less,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = depth pointer, r1 = colour pointer − depth pointer (bytes), r2 = end of the depth
    // run, r3 = &[z, gz, rb, grb, g, gg]. Returns the number of pixels written.
    "scanline3d_span565_less:",
    save_registers!(),
    // r0 = −(run bytes), r1 = colour end, r7 = depth end; r12 keeps r0 for the count.
    "subs r0, r0, r2",
    "adds r1, r1, r2",
    "mov r7, r2",
    "mov r12, r0",
    "ldr r4, [r3, #4]",
    "mov r8, r4",
    "ldr r4, [r3, #12]",
    "mov r9, r4",
    "ldr r4, [r3, #20]",
    "mov r10, r4",
    "ldr r2, [r3, #0]",
    "ldr r4, [r3, #16]",
    "ldr r3, [r3, #8]",
    "movs r5, #0",
    "mov r11, r5",
    pixel_loop!(),
    "b 4f",
    hidden_pixel!(count_in!("r11"), gouraud_steps!()),
    // Written = run length − hidden.
    "4:",
    "mov r0, r12",
    "negs r0, r0",
    "lsrs r0, r0, #1",
    "mov r1, r11",
    "subs r0, r0, r1",
    restore_registers_and_return!(),
    ".size scanline3d_span565_less, . - scanline3d_span565_less",
);

/// One pixel of the dithered loop ([`dither_loop`]) for column phase `$p` (0..=3): as
/// [`pixel_loop`], but the red-blue and green values get the phase's offsets (the frame words
/// `{$pre trb$p}` and `{$pre tg$p}` above sp, `raster::dither_words`; `$pre` tells the copies of
/// the loop in one routine apart) before the channels are read; the
/// accumulators themselves step as in the plain loop. A hidden pixel branches to `$hidden`;
/// `$end` is the end test after the index step. 23 instructions per written pixel (the plain
/// loop's 19 and two loads and two additions), 12 per hidden one.
macro_rules! dither_pixel {
    ($pre:literal, $p:literal, $hidden:literal, $end:literal) => {
        concat!(
            "ldrh r5, [r7, r0]\n",
            "lsrs r6, r2, #16\n",
            "cmp r6, r5\n",
            "bhs ",
            $hidden,
            "\n",
            "strh r6, [r7, r0]\n",
            "ldr r6, [sp, #{",
            $pre,
            "trb",
            $p,
            "}]\n",
            "adds r6, r6, r3\n",
            "lsrs r5, r6, #27\n",
            "lsls r5, r5, #11\n",
            "lsls r6, r6, #16\n",
            "lsrs r6, r6, #27\n",
            "orrs r5, r6\n",
            "ldr r6, [sp, #{",
            $pre,
            "tg",
            $p,
            "}]\n",
            "adds r6, r6, r4\n",
            "lsrs r6, r6, #26\n",
            "lsls r6, r6, #5\n",
            "orrs r5, r6\n",
            "strh r5, [r1, r0]\n",
            gouraud_steps!(),
            "adds r0, #2\n",
            $end,
            "\n",
        )
    };
}

/// The hidden pixel of [`dither_loop`] for the phase whose written pixel continues with
/// `$next` (the next phase's loop label): counts it with `$count` (using r5), steps, and goes
/// on with the next phase, or leaves through label 49.
macro_rules! dither_hidden {
    ($count:expr, $next:literal, $steps:expr) => {
        concat!(
            $count,
            $steps,
            "adds r0, #2\n",
            "bne ",
            $next,
            "\n",
            "b 49f\n",
        )
    };
}

/// [`dither_pixel`] with the RP2040's SIO interpolators (feature `rp2040`; r2 = the base of the
/// interpolator registers, see [`scanline3d_rows565_dither_interp`]): interpolator 0 holds the
/// depth word and its step, one read gives the depth (the word's high half, as `lsrs r6, r2,
/// #16`) and steps it; the dithered red-blue word goes into interpolator 1, whose full result
/// is red and blue at their RGB565 places (the two shifts and masks of `packed_color`). 19
/// instructions per written pixel and 24 cycles, where the plain dithered pixel takes 23 and 28;
/// 10 per hidden one.
#[cfg(feature = "rp2040")]
macro_rules! dither_pixel_interp {
    ($pre:literal, $p:literal, $hidden:literal, $end:literal) => {
        concat!(
            "ldrh r5, [r7, r0]\n",
            "ldr r6, [r2, #{i0_pop0}]\n",
            "cmp r6, r5\n",
            "bhs ",
            $hidden,
            "\n",
            "strh r6, [r7, r0]\n",
            "ldr r6, [sp, #{",
            $pre,
            "trb",
            $p,
            "}]\n",
            "adds r6, r6, r3\n",
            "str r6, [r2, #{i1_accum0}]\n",
            "ldr r5, [r2, #{i1_peek_full}]\n",
            "ldr r6, [sp, #{",
            $pre,
            "tg",
            $p,
            "}]\n",
            "adds r6, r6, r4\n",
            "lsrs r6, r6, #26\n",
            "lsls r6, r6, #5\n",
            "orrs r5, r6\n",
            "strh r5, [r1, r0]\n",
            "add r3, r9\n",
            "add r4, r10\n",
            "adds r0, #2\n",
            $end,
            "\n",
        )
    };
}

/// The pixel loop with 4×4 ordered dithering, unrolled over the four column phases so that
/// each phase loads its offsets with an immediate sp offset. In: as [`pixel_loop`], and r5 =
/// the first pixel's column times two (its bits 1 and 2 are the column phase); the offsets of
/// the row's Bayer row in the frame words `{$pre trb0}`, `{$pre tg0}`, … `{$pre tg3}` above sp. Hidden
/// pixels are counted by `$count` (using r5). Ends at label 49, placed after the loop. The
/// hidden paths come first, so that every branch is within the 256 bytes of Thumb-1's
/// conditional branches. `$pixel` is the written pixel's macro ([`dither_pixel`], or
/// [`dither_pixel_interp`] whose depth steps in an interpolator) and `$steps` the hidden
/// pixel's steps (defaults: the plain loop's).
macro_rules! dither_loop {
    ($pre:literal, $count:expr) => {
        dither_loop!($pre, $count, dither_pixel, gouraud_steps!())
    };
    ($pre:literal, $count:expr, $pixel:ident, $steps:expr) => {
        concat!(
            // Phase = bits 1 (into N) and 2 (into C) of r5.
            "lsls r5, r5, #30\n",
            "bcs 45f\n",
            "bmi 51f\n",
            "b 50f\n",
            "45:\n",
            "bmi 53f\n",
            "b 52f\n",
            "60:\n",
            dither_hidden!($count, "51f", $steps),
            "61:\n",
            dither_hidden!($count, "52f", $steps),
            "62:\n",
            dither_hidden!($count, "53f", $steps),
            "63:\n",
            dither_hidden!($count, "50f", $steps),
            "50:\n",
            $pixel!($pre, "0", "60b", "beq 49f"),
            "51:\n",
            $pixel!($pre, "1", "61b", "beq 49f"),
            "52:\n",
            $pixel!($pre, "2", "62b", "beq 49f"),
            "53:\n",
            $pixel!($pre, "3", "63b", "bne 50b"),
            "49:\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_span565_less_dither,\"ax\",%progbits",
    ".global scanline3d_span565_less_dither",
    ".type scanline3d_span565_less_dither,%function",
    ".p2align 2",
    ".thumb_func",
    // As `scanline3d_span565_less`, with r3 = &[z, gz, rb, grb, g, gg, offsets, 2·x0]:
    // `offsets` points to the eight words of the row's `raster::DITHER565` row, copied to
    // the bottom of the frame; x0 is the first pixel's column.
    "scanline3d_span565_less_dither:",
    save_registers!(),
    "ldr r4, [r3, #24]",
    "adds r4, #16",
    "ldm r4, {{r4, r5, r6, r7}}",
    "push {{r4, r5, r6, r7}}",
    "ldr r4, [r3, #24]",
    "ldm r4, {{r4, r5, r6, r7}}",
    "push {{r4, r5, r6, r7}}",
    "subs r0, r0, r2",
    "adds r1, r1, r2",
    "mov r7, r2",
    "mov r12, r0",
    "ldr r4, [r3, #4]",
    "mov r8, r4",
    "ldr r4, [r3, #12]",
    "mov r9, r4",
    "ldr r4, [r3, #20]",
    "mov r10, r4",
    "movs r5, #0",
    "mov r11, r5",
    "ldr r2, [r3, #0]",
    "ldr r4, [r3, #16]",
    "ldr r5, [r3, #28]",
    "ldr r3, [r3, #8]",
    dither_loop!("", count_in!("r11")),
    // Written = run length − hidden.
    "mov r0, r12",
    "negs r0, r0",
    "lsrs r0, r0, #1",
    "mov r1, r11",
    "subs r0, r0, r1",
    "add sp, #32",
    restore_registers_and_return!(),
    ".size scanline3d_span565_less_dither, . - scanline3d_span565_less_dither",
    trb0 = const 0,
    tg0 = const 4,
    trb1 = const 8,
    tg1 = const 12,
    trb2 = const 16,
    tg2 = const 20,
    trb3 = const 24,
    tg3 = const 28,
);

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_span565_flat_less,\"ax\",%progbits",
    ".global scanline3d_span565_flat_less",
    ".type scanline3d_span565_flat_less,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = depth pointer, r1 = colour pointer − depth pointer (bytes), r2 = end of the depth
    // run (> r0), r3 = &[z, gz, colour]: the depth 16.12 times 2⁴ (the stored depth is the
    // high half, as in `pixel_loop`) and its step, and the RGB565 word. Returns the number
    // of pixels written. 9 instructions per written pixel and 10 per hidden one (counted in
    // lr, saved on entry). As in `pixel_loop`: r0 counts minus the run's bytes up to zero,
    // r7 and r1 are the ends of the depth and colour runs.
    "scanline3d_span565_flat_less:",
    "push {{r4, r5, r6, r7, lr}}",
    "subs r0, r0, r2",
    "adds r1, r1, r2",
    "mov r7, r2",
    "mov r12, r0",
    "ldm r3, {{r2, r3, r4}}",
    "movs r5, #0",
    "mov lr, r5",
    "1:",
    "ldrh r5, [r7, r0]",
    "lsrs r6, r2, #16",
    "cmp r6, r5",
    "bhs 3f",
    "strh r6, [r7, r0]",
    "strh r4, [r1, r0]",
    "adds r2, r2, r3",
    "adds r0, #2",
    "bne 1b",
    "b 4f",
    hidden_pixel!(count_in!("lr"), "adds r2, r2, r3\n"),
    // Written = run length − hidden.
    "4:",
    "mov r0, r12",
    "negs r0, r0",
    "lsrs r0, r0, #1",
    "mov r1, lr",
    "subs r0, r0, r1",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_span565_flat_less, . - scanline3d_span565_flat_less",
);

/// The `DepthTest::Less` Gouraud span for RGB565 words; the same arguments as the portable
/// loop. `zs` and `cs` have the same length ≥ 1 and `cs` holds RGB565 words.
#[inline(always)]
pub(crate) fn span565_less(
    zs: &mut [u16],
    cs: &mut [u16],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
) -> u32 {
    let n = zs.len().min(cs.len());
    if n == 0 {
        return 0;
    }
    // Already shifted as the loop wants them (see `pixel_loop`).
    let acc = [
        z[0] as u32,
        z[1] as u32,
        rb[0],
        rb[1],
        g[0] as u32,
        g[1] as u32,
    ];
    let zp = zs.as_mut_ptr();
    let offset = (cs.as_mut_ptr() as isize).wrapping_sub(zp as isize);
    // SAFETY: `n ≥ 1` pixels are read and written at `zp[0..n]` and at the same indices of
    // `cs` (reached as `zp + offset`), both exclusively borrowed.
    unsafe { scanline3d_span565_less(zp, offset, zp.add(n), &acc) }
}

/// The dithered `DepthTest::Less` Gouraud span for RGB565 words (`raster::span_packed_dither`):
/// the same arguments as the portable loop, `x0` the first pixel's column and `row` the pixel
/// row. `zs` and `cs` have the same length ≥ 1 and `cs` holds RGB565 words.
#[inline(always)]
pub(crate) fn span565_less_dither(
    zs: &mut [u16],
    cs: &mut [u16],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    let n = zs.len().min(cs.len());
    if n == 0 {
        return 0;
    }
    let offsets: &'static [u32; 8] = &DITHER565[(row & 3) as usize];
    let acc = [
        z[0] as u32,
        z[1] as u32,
        rb[0],
        rb[1],
        g[0] as u32,
        g[1] as u32,
        offsets.as_ptr() as u32,
        (x0 as u32) << 1,
    ];
    let zp = zs.as_mut_ptr();
    let offset = (cs.as_mut_ptr() as isize).wrapping_sub(zp as isize);
    // SAFETY: as in `span565_less`: `n ≥ 1` pixels at `zp[0..n]` and the same indices of `cs`,
    // both exclusively borrowed; the routine also reads the eight words of `offsets` (static).
    unsafe { scanline3d_span565_less_dither(zp, offset, zp.add(n), &acc) }
}

#[cfg(scanline3d_thumb_v6m)]
/// The `DepthTest::Less` flat span for RGB565 words; the same arguments as the portable
/// loop (`z` 16.12 with its rounding bias, `gz` its step), whose truncation `(z >> 12) as u16`
/// is the high half of `z << 4` (both wrap alike).
#[inline(always)]
pub(crate) fn span565_flat_less(
    zs: &mut [u16],
    cs: &mut [u16],
    z: i32,
    gz: i32,
    color: u16,
) -> u32 {
    let n = zs.len().min(cs.len());
    if n == 0 {
        return 0;
    }
    let acc = [(z as u32) << 4, (gz as u32) << 4, color as u32];
    let zp = zs.as_mut_ptr();
    let offset = (cs.as_mut_ptr() as isize).wrapping_sub(zp as isize);
    // SAFETY: as in `span565_less`: `n ≥ 1` pixels at `zp[0..n]` and the same indices of `cs`,
    // both exclusively borrowed.
    unsafe { scanline3d_span565_flat_less(zp, offset, zp.add(n), &acc) }
}
