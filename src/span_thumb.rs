//! Thumb-1 assembly for the renderer's hot path on Cortex-M cores: for RGB565 words, the
//! Gouraud span loop, a routine that draws one row of every qualifying active triangle (span,
//! edge steps, attribute steps, the short edge's switch, removal after the last row) and the
//! strip-line clear; and the Q16.16 point and direction transforms. The span loop alone was
//! about 40 % of a frame's instructions on a Cortex-M0 before it was written here.
//!
//! Why assembly: on `thumbv6m` only r0–r7 are general registers for most instructions and r7 is
//! the frame pointer, so LLVM spills the span's accumulators to the stack and unrolls the loop
//! four times, which comes to about 47 instructions per pixel. Written by hand the loop keeps
//! the three accumulators, the index and both line ends in low registers and the three steps
//! in r8–r10: 19 instructions per written pixel and 12 per hidden one.
//!
//! With 4×4 ordered dithering the span and the row routine have dithered twins
//! (`scanline3d_span565_less_dither`, `scanline3d_rows565_dither`; the plain loops are
//! unchanged): the row's eight Bayer offsets (`raster::dither_words`) sit on the stack, the
//! pixel loop is unrolled over the four column phases so that each loads its two offsets with
//! an immediate sp offset, and a written pixel adds them to copies of the red-blue and green
//! words before reading the channels: 23 instructions per written pixel, 12 per hidden one.
//! The row routine draws its common row's span with a copy of the unrolled loop in line and
//! the rarer rows' spans through a subroutine (two copies instead of five), and only
//! triangles with `DITHER_OK` (the only ones with routine rows in a dithered strip). With the
//! `rp2040` feature its twin `scanline3d_rows565_dither_interp` draws the same pixels with the
//! RP2040's SIO interpolators (depth stepping and the red-blue placement: 19 instructions and
//! 24 cycles per written pixel); the Pico firmware compares it with the portable rows at
//! start-up, since the QEMU benchmark has no SIO.
//!
//! On ARMv6-M the triangle setup (`scanline3d_setup565`, with `scanline3d_gouraud_setup`) also
//! makes the dither check of `raster::ActiveTri::dither_fits` (`scanline3d_dither_fits565`),
//! compared with the portable check on random triangles by the benchmark firmware.
//!
//! The routines compute exactly what the portable code in [`crate::raster`] computes
//! (`span_packed` for `DepthTest::Less` and 5-6-5 channels, `ActiveTri::draw_row` for a fast
//! Gouraud row: same truncations, same wrapping additions), so the image is bit-identical;
//! `scripts/mcu-bench` checks the image hashes of every benchmark scene on Cortex-M0 and
//! Cortex-M4F against the host's, which runs the portable code, and the benchmark firmware
//! checks the transforms against `dot3_add` on 4096 cases before it measures.
//!
//! Safety: every entry point checks that the colour type is a plain 16-bit RGB565 word
//! ([`rgb565_words`]) and passes runs within the lines it was given.
#![allow(unsafe_code)]

use crate::color::TargetColor;
use crate::project::ScreenVertex;
use crate::raster::{offsets as o, ActiveList, ActiveTri, Edge, Sorted, DITHER565};
use crate::scalar::Fx;
use fixed::types::I16F16;

/// AAPCS entry of both routines: saves r4–r11 and the return address (r8–r11 through low
/// registers: Thumb-1 `push` takes only r0–r7 and lr).
macro_rules! save_registers {
    () => {
        concat!(
            "push {{r4, r5, r6, r7, lr}}\n",
            "mov r4, r8\n",
            "mov r5, r9\n",
            "mov r6, r10\n",
            "mov r7, r11\n",
            "push {{r4, r5, r6, r7}}\n",
        )
    };
}

/// The matching exit: restores r8–r11 and r4–r7 and returns.
macro_rules! restore_registers_and_return {
    () => {
        concat!(
            "pop {{r4, r5, r6, r7}}\n",
            "mov r8, r4\n",
            "mov r9, r5\n",
            "mov r10, r6\n",
            "mov r11, r7\n",
            "pop {{r4, r5, r6, r7, pc}}\n",
        )
    };
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

/// One row of the triangle in r3 (r5 = its left edge's `w << 16`, with `left.c ≥ 0`) for the
/// row routine: loads its three per-pixel steps into r8–r10 (kept after the span: the row step
/// reuses them), draws the span `left.c..min(right.c, width)` with [`pixel_loop`] (the stack
/// frame counts hidden pixels, lr twice the fragments, across the routine's call; r11 is
/// twice the width) and ends with
/// r0 = r12 = the triangle. Reads the stack frame of `scanline3d_rows565`. On a row it draws,
/// `right.c ≥ left.c ≥ 0`, so both biased columns (`raster::EdgeDda`) give twice the column
/// as `(w << 17) >> 16`.
macro_rules! row_span {
    ($run:ident) => {
        concat!(
            "mov r12, r3\n",
            "lsls r4, r5, #1\n",
            "lsrs r4, r4, #16\n",
            "adds r3, #{gx0}\n",
            "ldm r3!, {{r0, r1, r2}}\n",
            "mov r8, r0\n",
            "mov r9, r1\n",
            "mov r10, r2\n",
            "mov r3, r12\n",
            // In bytes: xe = min(right.c, width); an empty span draws nothing.
            "ldr r5, [r3, #{rw}]\n",
            "lsls r5, r5, #17\n",
            "lsrs r5, r5, #16\n",
            clamp_right!(),
            "subs r6, r5, r4\n",
            "ble 5f\n",
            "adds r3, #{row0}\n",
            "ldm r3, {{r2, r3, r4}}\n",
            $run!(),
        )
    };
}

/// The end of [`row_span`]: the run of r6 bytes ending at byte column r5 of both lines, with
/// r2–r4 and r8–r10 loaded; counts the fragments (lr) and ends with r0 = r12.
macro_rules! span_run {
    () => {
        concat!(
            "add lr, r6\n",
            "ldr r1, [sp, #12]\n",
            "adds r7, r1, r5\n",
            "ldr r1, [sp, #16]\n",
            "adds r1, r1, r5\n",
            "negs r0, r6\n",
            pixel_loop!(),
            "b 5f\n",
            hidden_pixel!(count_on_stack!(), gouraud_steps!()),
            "5:\n",
            "mov r0, r12\n",
        )
    };
}

/// [`span_run`] for the dithered row routine: the same run, drawn by its [`dither_loop`]
/// subroutine (label 40; lr, the fragment count, is kept on the stack across the call, so the
/// subroutine's frame words are 4 bytes further from sp). Ends with r0 = r12.
macro_rules! span_run_dither {
    () => {
        concat!(
            "add lr, r6\n",
            "ldr r1, [sp, #12]\n",
            "adds r7, r1, r5\n",
            "ldr r1, [sp, #16]\n",
            "adds r1, r1, r5\n",
            "negs r0, r6\n",
            "subs r5, r5, r6\n",
            "mov r6, lr\n",
            "push {{r6}}\n",
            "bl 40f\n",
            "pop {{r6}}\n",
            "mov lr, r6\n",
            "5:\n",
            "mov r0, r12\n",
        )
    };
}

/// The lane controls of the interpolators for [`dither_pixel_interp`] (RP2040 datasheet,
/// `INTERPn_CTRL_LANEm`: SHIFT bits 0–4, MASK_LSB 5–9, MASK_MSB 10–14, CROSS_INPUT 16,
/// CROSS_RESULT 17, ADD_RAW 18). Interpolator 0, lane 0: the accumulator's high half (the
/// depth word's stored depth), and on a pop the accumulator takes lane 1's result; lane 1:
/// lane 0's accumulator plus BASE1 unshifted (the depth word plus its step).
#[cfg(feature = "rp2040")]
const INTERP0_LANE0: u32 = 16 | 15 << 10 | 1 << 17;
#[cfg(feature = "rp2040")]
const INTERP0_LANE1: u32 = 31 << 10 | 1 << 16 | 1 << 18;
/// Interpolator 1, lane 0: bits 27–31 of the red-blue word at bits 11–15 (red); lane 1, from
/// the same accumulator: bits 11–15 at bits 0–4 (blue). The full result (BASE2 = 0) is both.
#[cfg(feature = "rp2040")]
const INTERP1_LANE0: u32 = 16 | 11 << 5 | 15 << 10;
#[cfg(feature = "rp2040")]
const INTERP1_LANE1: u32 = 11 | 4 << 10 | 1 << 16;

/// The interpolators' register base, 0xd000_0080, into low register `$r`.
#[cfg(feature = "rp2040")]
macro_rules! interp_base {
    ($r:literal) => {
        concat!(
            "movs ",
            $r,
            ", #0xd0\n",
            "lsls ",
            $r,
            ", ",
            $r,
            ", #24\n",
            "adds ",
            $r,
            ", #0x80\n",
        )
    };
}

/// For [`dither_pixel_interp`]'s spans: the depth word (r2) and its step (r8) into interpolator
/// 0, then r2 = the interpolators' base. Uses low register `$t`.
#[cfg(feature = "rp2040")]
macro_rules! interp_take_depth {
    ($t:literal) => {
        concat!(
            interp_base!($t),
            "str r2, [",
            $t,
            ", #{i0_accum0}]\n",
            "mov r2, r8\n",
            "str r2, [",
            $t,
            ", #{i0_base1}]\n",
            "mov r2, ",
            $t,
            "\n",
        )
    };
}

/// For [`scanline3d_rows565_dither_interp`]'s entry: both interpolators of the calling core
/// set up for [`dither_pixel_interp`] (lane controls, interpolator 0's BASE0 and interpolator
/// 1's BASE2 zero). Uses r2 and r3.
#[cfg(feature = "rp2040")]
macro_rules! interp_config {
    () => {
        concat!(
            interp_base!("r2"),
            "movs r3, #0\n",
            "str r3, [r2, #{i0_base0}]\n",
            "str r3, [r2, #{i1_base2}]\n",
            "ldr r3, ={i0_lane0}\n",
            "str r3, [r2, #{i0_ctrl0}]\n",
            "ldr r3, ={i0_lane1}\n",
            "str r3, [r2, #{i0_ctrl1}]\n",
            "ldr r3, ={i1_lane0}\n",
            "str r3, [r2, #{i1_ctrl0}]\n",
            "ldr r3, ={i1_lane1}\n",
            "str r3, [r2, #{i1_ctrl1}]\n",
        )
    };
}

/// [`row_span`] with [`span_run_dither`]'s run drawn by a copy of [`dither_loop`] in line,
/// for the dithered row routine's common row (its frame words `{itrb0}` … `{itg3}` and the
/// hidden count at [sp, #20], as the routine sees them). An empty span leaves through the stub
/// at label 27 before the loop head (to label 37 here: the loop is too long for a conditional
/// branch over it), and a span past the line's end is clamped by the stub at label 26 (so
/// that the common case is a branch not taken). Ends with r0 = r12 = the triangle.
macro_rules! row_span_dither_inline {
    // `$setup` runs once the row's start words are in r2–r4 (the interpolator variant hands
    // the depth word to interpolator 0 there); `$loop` is the pixel loop.
    ($setup:expr, $loop:expr) => {
        concat!(
            "mov r12, r3\n",
            "lsls r4, r5, #1\n",
            "lsrs r4, r4, #16\n",
            "adds r3, #{gx0}\n",
            "ldm r3!, {{r0, r1, r2}}\n",
            "mov r8, r0\n",
            "mov r9, r1\n",
            "mov r10, r2\n",
            "mov r3, r12\n",
            "ldr r5, [r3, #{rw}]\n",
            "lsls r5, r5, #17\n",
            "lsrs r5, r5, #16\n",
            // min(r5, r11) through the stub at label 26 (rarely taken).
            "cmp r5, r11\n",
            "bgt 26b\n",
            "36:\n",
            "subs r6, r5, r4\n",
            "ble 27b\n",
            "adds r3, #{row0}\n",
            "ldm r3, {{r2, r3, r4}}\n",
            $setup,
            "add lr, r6\n",
            "ldr r1, [sp, #12]\n",
            "adds r7, r1, r5\n",
            "ldr r1, [sp, #16]\n",
            "adds r1, r1, r5\n",
            "negs r0, r6\n",
            "subs r5, r5, r6\n",
            $loop,
            "37:\n",
            "mov r0, r12\n",
        )
    };
}

/// [`row_span`] for a row with `left.c < 0` (r5 = the left edge's `w << 16`): the span
/// `0..min(right.c, width)`, its attributes at column 0 as `ActiveTri::draw_row` has them,
/// `row + gx·(−left.c)` (wrapping). Same registers in and out.
macro_rules! row_span_left_clamped {
    ($run:ident) => {
        concat!(
            "mov r12, r3\n",
            // r4 = −left.c = 2¹⁵ − biased column.
            "lsrs r5, r5, #16\n",
            "movs r4, #1\n",
            "lsls r4, r4, #15\n",
            "subs r4, r4, r5\n",
            "adds r3, #{gx0}\n",
            "ldm r3!, {{r0, r1, r2}}\n",
            "mov r8, r0\n",
            "mov r9, r1\n",
            "mov r10, r2\n",
            "muls r0, r4, r0\n",
            "muls r1, r4, r1\n",
            "muls r2, r4, r2\n",
            "mov r3, r12\n",
            "adds r3, #{row0}\n",
            "ldm r3!, {{r5, r6, r7}}\n",
            "adds r5, r5, r0\n",
            "adds r6, r6, r1\n",
            "adds r7, r7, r2\n",
            "mov r2, r5\n",
            "mov r3, r6\n",
            "mov r4, r7\n",
            // In bytes: xe = min(2·right.c, twice the width), signed (right.c may be < 0 too);
            // an empty span draws nothing.
            "mov r0, r12\n",
            "ldr r5, [r0, #{rw}]\n",
            "lsls r5, r5, #16\n",
            "lsrs r5, r5, #15\n",
            "movs r1, #1\n",
            "lsls r1, r1, #16\n",
            "subs r5, r5, r1\n",
            "ble 5f\n",
            clamp_right!(),
            "movs r6, r5\n",
            $run!(),
        )
    };
}

/// For [`row_span`]: r5 = min(r5, r11 = twice the width) (signed).
macro_rules! clamp_right {
    () => {
        concat!("cmp r5, r11\n", "ble 4f\n", "mov r5, r11\n", "4:\n",)
    };
}

/// The packed attribute rows of the triangle in r0 step by one row: row += inc, then
/// `$carry` (adds r0–r2 the steps in r8–r10 when the left edge carried). Uses r0–r7.
macro_rules! row_step {
    ($carry:literal) => {
        concat!(
            "movs r4, #{row0}\n",
            "adds r4, r0, r4\n",
            row_step_at!("r4", "r5", $carry),
        )
    };
}

/// [`row_step`] with the record's `row` address in `$p` (r4 or r5; `$t` is the other one):
/// one `ldm` of the three rows, the pending edge's word between them and the increments
/// (row in r0–r2, increments in `$t`, r6, r7), the sums, one `stm`.
macro_rules! row_step_at {
    ($p:literal, $t:literal, $carry:literal) => {
        concat!(
            "ldm ",
            $p,
            "!, {{r0, r1, r2, r3, ",
            $t,
            ", r6, r7}}\n",
            "adds r0, r0, ",
            $t,
            "\n",
            "adds r1, r1, r6\n",
            "adds r2, r2, r7\n",
            $carry,
            "subs ",
            $p,
            ", #28\n",
            "stm ",
            $p,
            "!, {{r0, r1, r2}}\n",
        )
    };
}

/// The row routine's move to the next entry of the active list (slot address i += 84) and
/// back to its loop head, label 15. Repeated after each row step rather than branched to:
/// a branch fewer a row.
macro_rules! next_triangle {
    () => {
        concat!(
            "ldr r3, [sp, #8]\n",
            "adds r3, #{size}\n",
            "str r3, [sp, #8]\n",
            "b 15b\n",
        )
    };
}

/// The row routine's step of the right (`$x` = `r`) edge of the triangle in r0
/// (`raster::EdgeDda`): w += s; when that is negative, w += dy·2¹⁶ + 1. Uses r1 and r2. (The
/// left edge's step is spelled out in the routine, where each outcome has its own row step.)
macro_rules! edge_step {
    ($x:literal) => {
        concat!(
            "ldr r1, [r0, #{",
            $x,
            "w}]\n",
            "ldr r2, [r0, #{",
            $x,
            "s}]\n",
            "adds r1, r1, r2\n",
            "bpl 7f\n",
            "ldrh r2, [r0, #{",
            $x,
            "dy}]\n",
            "lsls r2, r2, #16\n",
            "adds r2, #1\n",
            "adds r1, r1, r2\n",
            "7:\n",
            "str r1, [r0, #{",
            $x,
            "w}]\n",
        )
    };
}

/// Copies the pending short edge of the triangle in r0 (`ActiveTri::set_pending`) over its
/// left (`l`) or right (`r`) edge. Uses r1.
macro_rules! take_pending {
    ($x:literal) => {
        concat!(
            "ldr r1, [r0, #{pend_w}]\n",
            "str r1, [r0, #{",
            $x,
            "w}]\n",
            "ldr r1, [r0, #{pend_s}]\n",
            "str r1, [r0, #{",
            $x,
            "s}]\n",
            "ldr r1, [r0, #{pend_dy}]\n",
            "strh r1, [r0, #{",
            $x,
            "dy}]\n",
        )
    };
}

/// After a switch with the middle vertex left (r0 = the triangle, r4 = dc + carry, r3 = dsq,
/// see `ActiveTri::advance`), attribute `$k` (its step in `$g`): row += inc + gx·(dc + carry),
/// then inc += gx·dsq. Uses r1, r2, r5.
macro_rules! carry_attr {
    ($k:literal, $g:literal) => {
        concat!(
            "ldr r1, [r0, #{row",
            $k,
            "}]\n",
            "ldr r2, [r0, #{inc",
            $k,
            "}]\n",
            "adds r1, r1, r2\n",
            "mov r5, ",
            $g,
            "\n",
            "muls r5, r3, r5\n",
            "adds r2, r2, r5\n",
            "str r2, [r0, #{inc",
            $k,
            "}]\n",
            "mov r5, ",
            $g,
            "\n",
            "muls r5, r4, r5\n",
            "adds r1, r1, r5\n",
            "str r1, [r0, #{row",
            $k,
            "}]\n",
        )
    };
}

/// The row routine `$name` (`scanline3d_rows565`, or its dithered twin): `$table` runs first
/// (the dithered routine copies its eight offsets to the top of its frame there), `$qualify`
/// is an extra test of a triangle at the loop head (leaving with 1 when it fails), `$run`
/// draws a span, `$frame` is the frame's size in bytes, `$tail` code after the routine (the
/// dithered span's subroutine) and `$extra` more operands.
macro_rules! rows565_routine {
    ($name:literal, $table:expr, $main:expr, $run:ident, $stubs:expr, $frame:literal, $tail:expr,
     [$($extra:tt)*]) => {
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    concat!(".section .text.", $name, ",\"ax\",%progbits"),
    concat!(".global ", $name),
    concat!(".type ", $name, ",%function"),
    ".p2align 2",
    ".thumb_func",
    // r0 = &mut RowCtx. Draws the row of active triangles i, i+1, … while they qualify (see
    // `rows565`); returns 0 when it reached n, 1 when triangle i needs the portable path.
    concat!($name, ":"),
    save_registers!(),
    $table,
    // The context's first six words are copied to the stack, each a single load away, with
    // the indices as slot addresses and the colour offset as the colour line: [sp] = tris,
    // [sp, #4] = slot n, [sp, #8] = slot i, [sp, #12] = the depth line, [sp, #16] = the
    // colour line, [sp, #20] = the count of hidden pixels (where the context has twice the
    // width, which goes to r11); [sp, #24] = the context. lr counts twice the fragments for
    // the whole call (the return address is on the stack).
    "push {{r0}}",
    "ldm r0!, {{r1, r2, r3, r4, r5, r6}}",
    "movs r7, #{size}",
    "muls r2, r7, r2",
    "adds r2, r1, r2",
    "muls r3, r7, r3",
    "adds r3, r1, r3",
    "adds r5, r5, r4",
    "mov r11, r6",
    "movs r6, #0",
    "push {{r1, r2, r3, r4, r5, r6}}",
    "mov lr, r6",
    "b 10f",
    ".p2align 2",
    ".ltorg",
    // Exits within reach of the conditional branches of the sections below them.
    "12:",
    "movs r0, #1",
    "b 13f",
    // The count is used up. The row before the short edge's switch, if it is marked so:
    // drawn here, then the edges and attribute rows move as `ActiveTri::advance` moves them
    // at the switch, and the count starts again for the rows after it (as
    // `ActiveTri::set_routine_rows`). The triangle's last row, if it is marked so: drawn here
    // and the triangle leaves the list as `ActiveList::swap_remove` does. Either needs
    // left.c ≥ 0.
    "20:",
    "ldrb r4, [r3, #{flags}]",
    "lsls r5, r4, #{last_shift}",
    "bpl 26f",
    "ldr r5, [r3, #{lw}]",
    "lsls r5, r5, #16",
    "bpl 12b",
    row_span!($run),
    // The last record (slot n − 1) moves into slot i, as `ActiveList::swap_remove`: 21 words
    // through r0 and r3–r7.
    "ldr r1, [sp, #8]",
    "ldr r2, [sp, #4]",
    "subs r2, #{size}",
    "str r2, [sp, #4]",
    "cmp r1, r2",
    "bne 27f",
    "b 10f",
    "27:",
    "ldm r2!, {{r0, r3, r4, r5, r6, r7}}",
    "stm r1!, {{r0, r3, r4, r5, r6, r7}}",
    "ldm r2!, {{r0, r3, r4, r5, r6, r7}}",
    "stm r1!, {{r0, r3, r4, r5, r6, r7}}",
    "ldm r2!, {{r0, r3, r4, r5, r6, r7}}",
    "stm r1!, {{r0, r3, r4, r5, r6, r7}}",
    "ldm r2!, {{r0, r3, r4}}",
    "stm r1!, {{r0, r3, r4}}",
    "b 10f",
    "12:",
    "movs r0, #1",
    "b 13f",
    "26:",
    "lsls r5, r4, #{switch_shift}",
    "bpl 12b",
    "ldr r5, [r3, #{lw}]",
    "lsls r5, r5, #16",
    "bpl 12b",
    row_span!($run),
    // Count and flags for the rows from the switch on: row_end − 1 − row_mid, last row flag
    // when it is at most 255.
    "ldrh r1, [r0, #{row_end}]",
    "ldrh r2, [r0, #{row_mid}]",
    "subs r1, r1, r2",
    "subs r1, #1",
    "ldrb r2, [r0, #{flags}]",
    "movs r3, #{switch_flag}",
    "bics r2, r3",
    "cmp r1, #255",
    "bls 22f",
    "movs r1, #255",
    "b 23f",
    "22:",
    "adds r2, #{last_flag}",
    "23:",
    "strb r2, [r0, #{flags}]",
    "strb r1, [r0, #{rrows}]",
    "lsls r2, r2, #{mid_left_shift}",
    "bmi 24f",
    // The middle vertex is right: the right edge becomes the pending one; the left edge is
    // the long one and steps with the attributes as on any row.
    take_pending!("r"),
    "b 29f",
    // The middle vertex is left: the right edge steps; the left one becomes the pending
    // one, and the attributes move along the old left edge by one row (with its carry),
    // then by dc = new c − old stepped c columns, and their row step changes by
    // dsq = new sq − old sq columns.
    "24:",
    edge_step!("r"),
    // In 32 bits (one row past its end the old edge's column may leave the packed half):
    // biased c + sq + carry, with carry = e < sr, e = w >> 16 and sr = (sq − s) >> 16.
    "ldr r1, [r0, #{lw}]",
    "uxth r4, r1",
    "ldr r2, [r0, #{ls}]",
    "sxth r5, r2",
    "adds r4, r4, r5",
    "subs r2, r5, r2",
    "lsrs r1, r1, #16",
    "lsrs r2, r2, #16",
    "movs r6, #0",
    "cmp r1, r2",
    "bhs 25f",
    "movs r6, #1",
    "25:",
    "adds r1, r4, r6",
    // dc + carry = (new biased c − that) + carry; dsq = new sq − old sq.
    "ldr r3, [r0, #{pend_w}]",
    "uxth r4, r3",
    "subs r4, r4, r1",
    "adds r4, r4, r6",
    "ldr r3, [r0, #{pend_s}]",
    "sxth r3, r3",
    "subs r3, r3, r5",
    take_pending!("l"),
    carry_attr!("0", "r8"),
    carry_attr!("1", "r9"),
    carry_attr!("2", "r10"),
    "b 31f",
    "11:",
    "movs r0, #0",
    "b 13f",
    // Ways out of the loop head below, within reach of its conditional branches (the main
    // path falls through them untaken).
    "19:",
    "b 20b",
    "28:",
    "b 18f",
    $stubs,
    "10:",
    "ldr r3, [sp, #8]",
    "15:",
    "ldr r2, [sp, #4]",
    "cmp r3, r2",
    "bhs 11b",
    // Entry i's record is slot i (`ActiveList`), in r3. Qualifies: rows left on the
    // triangle's routine count (a fast Gouraud row that neither switches its short edge nor
    // ends it; in a dithered strip only a `DITHER_OK` triangle has them, see
    // `ActiveTri::set_routine_rows`); left.c < 0 goes to 18. The count goes down by one.
    "ldrb r4, [r3, #{rrows}]",
    "subs r4, #1",
    "bcc 19b",
    "ldr r5, [r3, #{lw}]",
    "lsls r5, r5, #16",
    "bpl 28b",
    "strb r4, [r3, #{rrows}]",
    $main,
    // Both edges step (as `edge_step!`), loaded and stored with one `ldm` and one `stm`
    // (r1, r2 = left w, s; r3, r4 = right w, s), and the packed rows with them: row += inc,
    // and + gx (still in r8–r10) when the left edge carried; one path for each.
    "17:",
    "adds r5, r0, #{lw}",
    "ldm r5!, {{r1, r2, r3, r4}}",
    "adds r3, r3, r4",
    "bpl 7f",
    "ldrh r6, [r0, #{rdy}]",
    "lsls r6, r6, #16",
    "adds r6, #1",
    "adds r3, r3, r6",
    "7:",
    "adds r1, r1, r2",
    "bmi 9f",
    "subs r5, #16",
    "stm r5!, {{r1, r2, r3, r4}}",
    "adds r5, #{row_after_edges}",
    row_step_at!("r5", "r4", ""),
    next_triangle!(),
    "9:",
    "ldrh r6, [r0, #{ldy}]",
    "lsls r6, r6, #16",
    "adds r6, #1",
    "adds r1, r1, r6",
    "subs r5, #16",
    "stm r5!, {{r1, r2, r3, r4}}",
    "adds r5, #{row_after_edges}",
    row_step_at!("r5", "r4", "add r0, r8\nadd r1, r9\nadd r2, r10\n"),
    next_triangle!(),
    // After the switch with the middle vertex right (the right edge is the new one, not
    // stepped): the left edge steps, and the rows with it.
    "29:",
    "ldr r1, [r0, #{lw}]",
    "ldr r2, [r0, #{ls}]",
    "adds r1, r1, r2",
    "bmi 8f",
    "str r1, [r0, #{lw}]",
    row_step!(""),
    // The next triangle.
    "31:",
    next_triangle!(),
    "8:",
    "ldrh r2, [r0, #{ldy}]",
    "lsls r2, r2, #16",
    "adds r2, #1",
    "adds r1, r1, r2",
    "str r1, [r0, #{lw}]",
    row_step!("add r0, r8\nadd r1, r9\nadd r2, r10\n"),
    next_triangle!(),
    // A counted row with left.c < 0 (a triangle across the left border): as `draw_row`, the
    // span starts at column 0 with the attributes moved by gx·(−left.c), then the row steps
    // as any other.
    "18:",
    "strb r4, [r3, #{rrows}]",
    row_span_left_clamped!($run),
    "b 17b",
    // Slot addresses back to indices (exact divisions by 84, as above).
    "13:",
    "ldr r1, [sp, #24]",
    "ldr r3, [sp]",
    "ldr r4, ={inv21}",
    "ldr r2, [sp, #4]",
    "subs r2, r2, r3",
    "lsrs r2, r2, #2",
    "muls r2, r4, r2",
    "str r2, [r1, #{cn}]",
    "ldr r2, [sp, #8]",
    "subs r2, r2, r3",
    "lsrs r2, r2, #2",
    "muls r2, r4, r2",
    "str r2, [r1, #{ci}]",
    "mov r2, lr",
    "lsrs r2, r2, #1",
    "str r2, [r1, #{cfrag}]",
    "ldr r2, [sp, #20]",
    "str r2, [r1, #{chidden}]",
    concat!("add sp, #", $frame),
    restore_registers_and_return!(),
    $tail,
    concat!(".size ", $name, ", . - ", $name),
    ci = const core::mem::offset_of!(RowCtx, i),
    cn = const core::mem::offset_of!(RowCtx, n),
    cfrag = const core::mem::offset_of!(RowCtx, fragments),
    chidden = const core::mem::offset_of!(RowCtx, hidden),
    size = const core::mem::size_of::<ActiveTri>(),
    inv21 = const INV21,
    rrows = const o::ROUTINE_ROWS,
    flags = const o::FLAGS,
    last_shift = const 31 - o::LAST_BIT,
    switch_shift = const 31 - o::SWITCH_BIT,
    mid_left_shift = const 31 - o::MID_LEFT.trailing_zeros(),
    switch_flag = const o::SWITCH,
    last_flag = const o::LAST,
    row_mid = const o::ROW_MID,
    row_end = const o::ROW_END,
    pend_w = const o::PEND_W,
    pend_s = const o::PEND_S,
    pend_dy = const o::PEND_DY,
    row1 = const o::ROW + 4,
    row2 = const o::ROW + 8,
    inc0 = const o::INC,
    inc1 = const o::INC + 4,
    inc2 = const o::INC + 8,
    lw = const o::LEFT + o::W,
    ls = const o::LEFT + o::S,
    ldy = const o::LEFT_DY,
    rw = const o::RIGHT + o::W,
    rs = const o::RIGHT + o::S,
    rdy = const o::RIGHT_DY,
    gx0 = const o::GX,
    row0 = const o::ROW,
    row_after_edges = const o::ROW - (o::RIGHT + o::S + 4),
    $($extra)*
);
    };
}

rows565_routine!(
    "scanline3d_rows565",
    "",
    row_span!(span_run),
    span_run,
    "",
    "28",
    "",
    []
);

/// A dithered row routine `$name` (r1 = the eight offsets of the row's Bayer row in
/// `raster::DITHER565`): before the context's six words, the offsets go on the stack ([sp, #28]
/// to [sp, #56] in the routine, the `itrb`/`itg` words; the span subroutine of the rarer paths
/// sees them 4 bytes further, after the saved fragment count: the `strb`/`stg` words). The
/// common row draws its span with a copy of the dithered loop in line (no call), the rarer
/// rows through the subroutine at label 40. Only `DITHER_OK` triangles have routine rows in a
/// dithered strip (`ActiveTri::set_routine_rows`), so the routine needs no test of its own for
/// them. `$entry` runs first; `$take_depth` (common row) and `$sub_take_depth` (subroutine)
/// run once a span's start words are in r2–r4; `$pixel` and `$steps` are the loop's written
/// pixel and a hidden pixel's steps ([`dither_loop`]); `$extra` more operands.
macro_rules! rows565_dither_routine {
    ($name:literal, $entry:expr, $take_depth:expr, $sub_take_depth:expr, $pixel:ident,
     $steps:expr, [$($extra:tt)*]) => {
        rows565_routine!(
            $name,
            concat!(
                $entry,
                "adds r1, #16\n",
                "ldm r1!, {{r2, r3, r4, r5}}\n",
                "push {{r2, r3, r4, r5}}\n",
                "subs r1, #32\n",
                "ldm r1!, {{r2, r3, r4, r5}}\n",
                "push {{r2, r3, r4, r5}}\n",
            ),
            row_span_dither_inline!(
                $take_depth,
                dither_loop!("i", count_on_stack!(), $pixel, $steps)
            ),
            span_run_dither,
            "26:\nmov r5, r11\nb 36f\n27:\nb 37f\n",
            "60",
            concat!(
                "40:\n",
                $sub_take_depth,
                dither_loop!(
                    "s",
                    "ldr r5, [sp, #24]\nadds r5, #1\nstr r5, [sp, #24]\n",
                    $pixel,
                    $steps
                ),
                "bx lr\n",
            ),
            [
                strb0 = const 32,
                stg0 = const 36,
                strb1 = const 40,
                stg1 = const 44,
                strb2 = const 48,
                stg2 = const 52,
                strb3 = const 56,
                stg3 = const 60,
                itrb0 = const 28,
                itg0 = const 32,
                itrb1 = const 36,
                itg1 = const 40,
                itrb2 = const 44,
                itg2 = const 48,
                itrb3 = const 52,
                itg3 = const 56,
                $($extra)*
            ]
        );
    };
}

rows565_dither_routine!(
    "scanline3d_rows565_dither",
    "",
    "",
    "",
    dither_pixel,
    gouraud_steps!(),
    []
);

// The dithered row routine with the RP2040's SIO interpolators (feature `rp2040`, where the
// Pico firmware runs: the SIO exists only on an RP2040, so other ARMv6-M parts keep
// `scanline3d_rows565_dither`). The same routine with [`dither_pixel_interp`]'s pixels; it sets
// up both interpolators of the calling core on entry ([`interp_config`]) and leaves them
// changed (the renderer owns them while it draws: an interrupt handler that uses them must
// save and restore them). Its register offsets are from the interpolators' base 0xd000_0080
// (RP2040 datasheet 2.3.1.6, SIO registers INTERP0_ACCUM0 … INTERP1_BASE_1AND0).
#[cfg(feature = "rp2040")]
rows565_dither_routine!(
    "scanline3d_rows565_dither_interp",
    interp_config!(),
    interp_take_depth!("r0"),
    interp_take_depth!("r6"),
    dither_pixel_interp,
    "add r3, r9\nadd r4, r10\n",
    [
        i0_accum0 = const 0x00,
        i0_base0 = const 0x08,
        i0_base1 = const 0x0c,
        i0_pop0 = const 0x14,
        i0_ctrl0 = const 0x2c,
        i0_ctrl1 = const 0x30,
        i1_accum0 = const 0x40,
        i1_base2 = const 0x50,
        i1_peek_full = const 0x68,
        i1_ctrl0 = const 0x6c,
        i1_ctrl1 = const 0x70,
        i0_lane0 = const INTERP0_LANE0,
        i0_lane1 = const INTERP0_LANE1,
        i1_lane0 = const INTERP1_LANE0,
        i1_lane1 = const INTERP1_LANE1,
    ]
);

// The immediate offsets above must be encodable in 16-bit Thumb loads and stores (some are 0
// today, which clippy finds absurd to compare; the layout may change).
#[allow(clippy::absurd_extreme_comparisons)]
const _: () = {
    assert!(o::LEFT % 4 == 0 && o::RIGHT % 4 == 0 && o::RIGHT + o::S <= 124);
    assert!(o::W == 0 && o::S == 4 && o::LEFT_DY % 2 == 0 && o::RIGHT_DY <= 62);
    assert!(o::GX % 4 == 0 && o::ROW == o::GX + 16 && o::INC == o::ROW + 16);
    // The row routine loads and stores both edges' words with one `ldm` and `stm` from
    // `adds r5, r0, #LEFT` (an immediate of 3 bits).
    assert!(o::LEFT <= 7 && o::RIGHT == o::LEFT + 8 && o::S == 4);
    assert!(o::ROW >= o::RIGHT + o::S + 4 && o::ROW - (o::RIGHT + o::S + 4) <= 255);
    assert!(o::INC + 12 <= 255);
    assert!(core::mem::size_of::<ActiveTri>() <= 255);
    assert!(o::ROUTINE_ROWS <= 31 && o::FLAGS <= 31);
};

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_fill128,\"ax\",%progbits",
    ".global scanline3d_fill128",
    ".type scanline3d_fill128,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = start, r1 = end (a multiple of 16 bytes after r0, word-aligned), r2 = the word.
    // 64 bytes per iteration in three stores of six, six and four words (3 instructions per
    // 64 bytes and 22 cycles, where two-block stores took 26 and the library fill about 8
    // instructions per 16 bytes); a block count that is not a multiple of four is stored
    // first, one and two blocks at a time.
    "scanline3d_fill128:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r3, r2",
    "mov r4, r2",
    "mov r5, r2",
    "mov r6, r2",
    "mov r7, r2",
    // r1 = blocks of 16 bytes; its bit 0 (into carry): one block, bit 1: two blocks.
    "subs r1, r1, r0",
    "lsrs r1, r1, #5",
    "bcc 1f",
    "stm r0!, {{r2, r3, r4, r5}}",
    "1:",
    "lsrs r1, r1, #1",
    "bcc 2f",
    "stm r0!, {{r2, r3, r4, r5, r6, r7}}",
    "stm r0!, {{r2, r3}}",
    "2:",
    "beq 3f",
    "4:",
    "stm r0!, {{r2, r3, r4, r5, r6, r7}}",
    "stm r0!, {{r2, r3, r4, r5, r6, r7}}",
    "stm r0!, {{r2, r3, r4, r5}}",
    "subs r1, #1",
    "bne 4b",
    "3:",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_fill128, . - scanline3d_fill128",
);

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

/// `scalar::recip_norm(a)` for `0 < a < 2³¹` in r4, with `scalar::RECIP_SEED` in r2: r6 = the
/// mantissa m in [1, 2³⁰], r5 = s, the bit length of `a` (1/a = m·2^-(29 + s)). A table seed,
/// one Newton step in 32-bit products and one in 64-bit ones, as the portable code. Uses
/// r0–r3 and r7; about 75 instructions.
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
    vrgb = const crate::project::RGB_HI_OFFSET,
    vfl = const crate::project::FLAGS_OFFSET,
    gx = const o::GX,
    row = const o::ROW,
    inc = const o::INC,
    coarse_min = const crate::raster::COARSE_MIN,
);

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
    ".section .text.scanline3d_setup565,\"ax\",%progbits",
    ".global scanline3d_setup565",
    ".type scanline3d_setup565,%function",
    ".p2align 2",
    ".thumb_func",
    ".equ su_det, 12",
    ".equ su_row, 16",
    ".equ su_lc, 20",
    ".equ su_lsq, 24",
    ".equ su_rec, 28",
    ".equ su_h, 32",
    ".equ su_a, 36",
    ".equ su_b, 40",
    ".equ su_c, 44",
    ".equ su_mid, 48",
    ".equ su_end, 52",
    ".equ su_seed, 56",
    ".equ su_left, 60",
    ".equ su_frame, 64",
    // r0 = the record, r1 = the arguments (`SetupArgs`: the vertex store and its length, the
    // triangle's indices v0 | v1 << 16 and v2, the row, the screen height, the reciprocal
    // seed). `raster::ActiveTri::setup` for a Gouraud triangle (no `FLAT_BIT`) whose setup is
    // fast, with RGB565 channels and `DepthTest::Less`: returns 1 (set up, kept) or 2 (no row
    // to draw from `row` on: not kept), or 0 for what the portable setup handles (a flat or
    // large triangle, an edge or attribute setup the assembly declines); the record is then
    // unspecified. Frame (the `su_` offsets): `raster::Sorted` (words 0–6), the record, the
    // height, the sorted vertices' packed x | y << 16, row_mid, row_end, the seed, mid_left.
    "scanline3d_setup565:",
    "push {{r4, r5, r6, r7, lr}}",
    "sub sp, #su_frame",
    "str r0, [sp, #su_rec]",
    "ldm r1!, {{r2, r3, r4, r5, r6, r7}}",
    "str r6, [sp, #su_row]",
    "str r7, [sp, #su_h]",
    // The seed table's address with the dither flag in bit 0 (the table is 2-aligned).
    "ldr r6, [r1]",
    "str r6, [sp, #su_seed]",
    // The vertex pointers (indices checked against the store's length).
    "lsls r0, r4, #16",
    "bpl 1f",
    "b .Lsu_decline",
    "1:",
    "lsrs r0, r0, #16",
    "lsrs r1, r4, #16",
    "cmp r0, r3",
    "bhs 7f",
    "cmp r1, r3",
    "bhs 7f",
    "cmp r5, r3",
    "blo 1f",
    "7:",
    "b .Lsu_decline",
    "1:",
    "movs r6, #12",
    "muls r0, r6, r0",
    "adds r0, r0, r2",
    "muls r1, r6, r1",
    "adds r1, r1, r2",
    "muls r5, r6, r5",
    "adds r2, r2, r5",
    // Sorted by y as the portable setup sorts them (the same swaps for equal ys).
    sort_step!("r0", "r1"),
    sort_step!("r1", "r2"),
    sort_step!("r0", "r1"),
    "mov r3, sp",
    "stm r3!, {{r0, r1, r2}}",
    "ldr r3, [r0]",
    "ldr r4, [r1]",
    "ldr r5, [r2]",
    "add r0, sp, #su_a",
    "stm r0!, {{r3, r4, r5}}",
    "asrs r0, r3, #16",
    "asrs r1, r4, #16",
    "asrs r2, r5, #16",
    // row_end = min(first_pixel(cy), height) > row, row_mid = first_pixel(by).
    first_pixel!("r6", "r2"),
    "ldr r7, [sp, #su_h]",
    "cmp r6, r7",
    "ble 1f",
    "mov r6, r7",
    "1:",
    "ldr r7, [sp, #su_row]",
    "cmp r7, r6",
    "blt 1f",
    "b .Lsu_empty",
    "1:",
    "str r6, [sp, #su_end]",
    first_pixel!("r6", "r1"),
    "str r6, [sp, #su_mid]",
    // det = dx1·dy2 − dx2·dy1 ≠ 0 (32-bit: |d| ≤ 32 766).
    "subs r1, r1, r0",
    "subs r2, r2, r0",
    "sxth r3, r3",
    "sxth r4, r4",
    "sxth r5, r5",
    "subs r4, r4, r3",
    "subs r5, r5, r3",
    "mov r6, r4",
    "muls r6, r2, r6",
    "mov r7, r5",
    "muls r7, r1, r7",
    "subs r6, r6, r7",
    "bne 1f",
    "b .Lsu_empty",
    "1:",
    "str r6, [sp, #su_det]",
    // Fast only when (x_hi − x_lo) + (cy − ay) ≤ 1024 px.
    "movs r0, #0",
    "movs r3, #0",
    "cmp r4, r3",
    "ble 1f",
    "mov r3, r4",
    "1:",
    "cmp r4, r0",
    "bge 1f",
    "mov r0, r4",
    "1:",
    "cmp r5, r3",
    "ble 1f",
    "mov r3, r5",
    "1:",
    "cmp r5, r0",
    "bge 1f",
    "mov r0, r5",
    "1:",
    "subs r3, r3, r0",
    "adds r3, r3, r2",
    "movs r0, #1",
    "lsls r0, r0, #14",
    "cmp r3, r0",
    "ble 1f",
    "b .Lsu_decline",
    "1:",
    // mid_left = det < 0: the long edge is the right one (slot 1), else the left (slot 0).
    "lsrs r6, r6, #31",
    "str r6, [sp, #su_left]",
    "ldr r0, [sp, #su_a]",
    "ldr r1, [sp, #su_c]",
    "ldr r2, [sp, #su_row]",
    edge_dda_inline!(),
    "ldr r6, [sp, #su_left]",
    edge_to_record!(),
    // The short edge: a → b before row_mid, b → c from it; the other slot.
    "ldr r2, [sp, #su_row]",
    "ldr r1, [sp, #su_mid]",
    "cmp r2, r1",
    "bge 2f",
    "ldr r0, [sp, #su_a]",
    "ldr r1, [sp, #su_b]",
    "b 3f",
    "2:",
    "ldr r0, [sp, #su_b]",
    "ldr r1, [sp, #su_c]",
    "3:",
    edge_dda_inline!(),
    "ldr r6, [sp, #su_left]",
    "movs r0, #1",
    "eors r6, r0",
    edge_to_record!(),
    // The attribute words.
    "mov r0, sp",
    "ldr r1, [sp, #su_rec]",
    "ldr r2, [sp, #su_seed]",
    "lsrs r2, r2, #1",
    "lsls r2, r2, #1",
    "bl scanline3d_gouraud_setup",
    "cmp r0, #0",
    "bne 1f",
    "b .Lsu_decline",
    "1:",
    // The pending short edge b → c at row_mid, when row < row_mid < row_end
    // (`ActiveTri::set_pending`: w, s and dy in the fourth words of gx, row and inc).
    "ldr r2, [sp, #su_row]",
    "ldr r1, [sp, #su_mid]",
    "cmp r2, r1",
    "bge .Lsu_nopend",
    "ldr r0, [sp, #su_end]",
    "cmp r1, r0",
    "bge .Lsu_nopend",
    "ldr r0, [sp, #su_b]",
    "ldr r1, [sp, #su_c]",
    "ldr r2, [sp, #su_mid]",
    edge_dda_inline!(),
    "ldr r7, [sp, #su_rec]",
    "str r1, [r7, #{pend_w}]",
    "str r2, [r7, #{pend_s}]",
    "str r3, [r7, #{pend_dy}]",
    ".Lsu_nopend:",
    // bx, by and cx, cy as the packed words; row_mid and row_end.
    "ldr r7, [sp, #su_rec]",
    "ldr r0, [sp, #su_b]",
    "str r0, [r7, #{bx}]",
    "ldr r0, [sp, #su_c]",
    "str r0, [r7, #{cx}]",
    "ldr r0, [sp, #su_mid]",
    "ldr r1, [sp, #su_end]",
    "lsls r2, r1, #16",
    "uxth r3, r0",
    "orrs r2, r3",
    "str r2, [r7, #{row_mid}]",
    // `ActiveTri::set_routine_rows`: rows up to stop = row_mid − 1 when row ≤ it < row_end − 1,
    // else row_end − 1; the count (at most 255) and LAST or SWITCH when it reaches stop.
    "subs r1, #1",
    "subs r0, #1",
    "ldr r2, [sp, #su_row]",
    "mov r3, r1",
    "cmp r0, r2",
    "blt 1f",
    "cmp r0, r1",
    "bge 1f",
    "mov r3, r0",
    "1:",
    "ldr r4, [sp, #su_left]",
    "adds r4, #{fast}",
    "subs r5, r3, r2",
    "cmp r5, #255",
    "bls 2f",
    "movs r5, #255",
    "b 3f",
    "2:",
    "cmp r3, r1",
    "bne 5f",
    "adds r4, #{last}",
    "b 3f",
    "5:",
    "adds r4, #{switch}",
    "3:",
    "strb r4, [r7, #{flags}]",
    "strb r5, [r7, #{rows}]",
    // While dithering: `raster::ActiveTri::dither_fits` (the sorted vertex pointers are the
    // frame's first three words) sets `DITHER_OK`, or the result is 3. r4 and r7 survive the
    // call.
    "ldr r0, [sp, #su_seed]",
    "lsls r0, r0, #31",
    "beq 6f",
    "mov r0, r7",
    "mov r1, sp",
    "ldr r2, [sp, #su_row]",
    "bl scanline3d_dither_fits565",
    "cmp r0, #0",
    "beq .Lsu_undithered",
    "adds r4, #{dither_ok}",
    "strb r4, [r7, #{flags}]",
    "6:",
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
    "add sp, #su_frame",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_setup565, . - scanline3d_setup565",
    left_dy = const o::LEFT_DY,
    left_w = const o::LEFT + o::W,
    left_s = const o::LEFT + o::S,
    pend_w = const o::PEND_W,
    pend_s = const o::PEND_S,
    pend_dy = const o::PEND_DY,
    bx = const o::BX,
    cx = const o::CX,
    row_mid = const o::ROW_MID,
    fast = const o::FAST,
    last = const o::LAST,
    switch = const o::SWITCH,
    flags = const o::FLAGS,
    rows = const o::ROUTINE_ROWS,
    dither_ok = const o::DITHER_OK,
);

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

/// `v ^ (v >> 31)`: `v` for `v ≥ 0`, `|v| − 1` below, so an OR of these is below 2³⁰ exactly
/// when every value is in [−2³⁰, 2³⁰).
#[inline(always)]
pub(crate) fn spread(v: Fx<I16F16>) -> i32 {
    crate::scalar::spread_bits(v.0.to_bits())
}

/// The first `R` rows of `m` times `(p, 1)` for `R = 4` (a point) or times `(p, 0)` for
/// `R = 3` (a direction: the upper 3 × 3 block), in Q16.16 by [`scanline3d_xform_q16`] when
/// every entry it uses is in [−2³⁰, 2³⁰) — the condition under which the portable `dot3_add`
/// takes its plain 64-bit sum, whose result this is, bit for bit. `None` otherwise (the
/// portable code then saturates where it must).
#[inline(always)]
fn transform_q16<const R: usize>(
    m: &[[Fx<I16F16>; 4]; 4],
    p: [Fx<I16F16>; 3],
) -> Option<[Fx<I16F16>; R]> {
    const { assert!(R == 3 || R == 4) };
    let mut s = spread(p[0]) | spread(p[1]) | spread(p[2]);
    for row in &m[..R] {
        s |= spread(row[0]) | spread(row[1]) | spread(row[2]);
        if R == 4 {
            s |= spread(row[3]);
        }
    }
    if s >= 1 << 30 {
        return None;
    }
    let pb = p.map(|v| v.0.to_bits());
    let mut out = [0i32; R];
    // SAFETY: `Fx<I16F16>` is `repr(transparent)` over `FixedI32`, which is `repr(transparent)`
    // over `i32`, so the matrix is 16 `i32` words, row after row; the routine reads the first
    // `R` rows (the last word of each only for R = 4) and the three words of `pb`, and writes
    // the `R` words of `out`.
    unsafe {
        scanline3d_xform_q16(
            m.as_ptr() as *const i32,
            pb.as_ptr(),
            out.as_mut_ptr(),
            R as u32,
        )
    };
    Some(out.map(|b| Fx(I16F16::from_bits(b))))
}

/// `m · (p, 1)` (see [`transform_q16`]): about 360 instructions on a Cortex-M0, where LLVM's
/// version of the four rows takes about 600.
#[inline(always)]
pub(crate) fn transform_i16f16(
    m: &[[Fx<I16F16>; 4]; 4],
    p: [Fx<I16F16>; 3],
) -> Option<[Fx<I16F16>; 4]> {
    transform_q16::<4>(m, p)
}

/// The upper 3 × 3 block of `m` times the direction `v` (see [`transform_q16`]).
#[inline(always)]
pub(crate) fn transform_dir_i16f16(
    m: &[[Fx<I16F16>; 4]; 4],
    v: [Fx<I16F16>; 3],
) -> Option<[Fx<I16F16>; 3]> {
    transform_q16::<3>(m, v)
}

/// `Viewport::project`'s screen words (x and y in subpixels, clamped to ±`COORD_LIMIT`, and
/// the depth as unsigned 16.8) of a Q16.16 clip-space point by [`scanline3d_project_q16`],
/// for the scales `sx`, `sy` < 2¹⁶; `None` where it declines (w ≤ 2⁻¹³, or a quotient
/// beyond the guard band: points that are clipped before they are projected), and the
/// portable code computes them.
#[inline(always)]
pub(crate) fn project_i16f16(p: &[Fx<I16F16>; 4], sx: u32, sy: u32) -> Option<[i32; 3]> {
    if (sx | sy) >> 16 != 0 {
        return None;
    }
    let mut out = [0i32; 3];
    // SAFETY: `Fx<I16F16>` is `repr(transparent)` over an `i32` (see `transform_q16`), so the
    // point is four words; the routine reads them and the 128-entry seed table, and writes
    // only the three words of `out`.
    let seed: &'static [u16; 128] = &crate::scalar::RECIP_SEED;
    let ok = unsafe {
        scanline3d_project_q16(
            p.as_ptr() as *const i32,
            sx | sy << 16,
            seed.as_ptr(),
            out.as_mut_ptr(),
        )
    };
    (ok != 0).then_some(out)
}

/// `raster::attribute_words` of a fast Gouraud triangle with RGB565 channels
/// (`C::CHANNEL_MAX == [31, 63, 31]`), written into `rec`'s `gx`, `row` and `inc` by
/// [`scanline3d_gouraud_setup`]; false (nothing written) where it declines and the portable
/// code computes them.
#[inline(always)]
pub(crate) fn gouraud_setup(rec: &mut ActiveTri, tri: &Sorted<'_>) -> bool {
    const {
        assert!(o::ROW == o::GX + 16 && o::INC == o::ROW + 16);
        assert!(core::mem::size_of::<Sorted<'_>>() == 28);
    };
    let seed: &'static [u16; 128] = &crate::scalar::RECIP_SEED;
    // SAFETY: `Sorted` is `repr(C)`, seven words (three vertex pointers, four `i32`), which the
    // routine reads along with the three vertices (at the field offsets given to it) and the
    // 128-entry seed table; it writes only the twelve words of `rec` from `gx` on (`gx`, `row`
    // and `inc`, contiguous, as asserted above).
    unsafe { scanline3d_gouraud_setup(tri as *const Sorted as *const u32, rec, seed.as_ptr()) != 0 }
}

/// The arguments of [`scanline3d_setup565`] (seven words).
#[cfg(not(target_has_atomic = "32"))]
#[repr(C)]
struct SetupArgs {
    verts: *const u32,
    len: u32,
    v01: u32,
    v2: u32,
    row: i32,
    height: i32,
    /// The reciprocal seed table's address, plus 1 while dithering (the routine then checks
    /// the triangle for `DITHER_OK`): the table is 2-aligned, so bit 0 is free.
    seed_dither: usize,
}

/// What [`setup565`] did.
#[cfg(not(target_has_atomic = "32"))]
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Setup565 {
    /// Set up and kept (while dithering: with `DITHER_OK`).
    Kept,
    /// No row to draw from the given row on.
    Empty,
    /// Set up, but while dithering its packed fields failed `ActiveTri::dither_fits`: the
    /// triangle must be set up again without the fast path.
    NotDitherable,
}

/// `raster::ActiveTri::setup` by [`scanline3d_setup565`] for a Gouraud triangle on a strip
/// whose mode is fast Gouraud (`DepthTest::Less`) with RGB565 channels, and with `dither` the
/// check of `raster::ActiveTri::setup_dither` too ([`scanline3d_dither_fits565`]): what it
/// did, or `None` (the record unspecified) for what the portable setup handles.
#[cfg(not(target_has_atomic = "32"))]
#[inline(always)]
pub(crate) fn setup565(
    rec: &mut ActiveTri,
    t: &crate::raster::TriRecord,
    verts: &[ScreenVertex],
    row: i32,
    height: i32,
    dither: bool,
) -> Option<Setup565> {
    const {
        assert!(core::mem::offset_of!(ScreenVertex, x) == 0);
        assert!(core::mem::offset_of!(ScreenVertex, y) == 2);
        assert!(core::mem::size_of::<ScreenVertex>() == 12);
        assert!(o::CX == o::BX + 4 && o::BX % 4 == 0 && o::ROW_END == o::ROW_MID + 2);
        assert!(o::ROW_MID % 4 == 0 && o::RIGHT == o::LEFT + 8 && o::RIGHT_DY == o::LEFT_DY + 2);
    };
    let seed: &'static [u16; 128] = &crate::scalar::RECIP_SEED;
    let args = SetupArgs {
        verts: verts.as_ptr() as *const u32,
        len: verts.len() as u32,
        v01: t.v[0] as u32 | (t.v[1] as u32) << 16,
        v2: t.v[2] as u32,
        row,
        height,
        seed_dither: seed.as_ptr() as usize | dither as usize,
    };
    // SAFETY: the routine reads the arguments, the three vertices whose indices it has checked
    // against the store's length (12-byte `repr(C)` records, x and y the first word, as
    // asserted above) and the seed table; it writes the record's fields at the offsets given
    // to it (not `ord`), and sets up its edges in line and calls `scanline3d_gouraud_setup` with
    // buffers in its own frame (and `scanline3d_dither_fits565` with the vertex pointers it
    // checked and the record it wrote).
    match unsafe { scanline3d_setup565(rec, &args) } {
        1 => Some(Setup565::Kept),
        2 => Some(Setup565::Empty),
        3 => Some(Setup565::NotDitherable),
        _ => None,
    }
}

/// For [`scanline3d_dither_fits565`]: vertex `$k` (its pointer at word `$k` of the array in
/// frame word `df_vp`) passes the three field tests of `raster::ActiveTri::dither_fits`, or
/// the routine leaves through `.Ldf_fail`. r4 = dx, r5 = dy (subpixels from the first pixel's
/// centre), r6 = the vertex, r2 = its flags half (the low two bits of each 10-bit channel in
/// bits 10–15), r0, r1, r3, r7 scratch.
#[cfg(not(target_has_atomic = "32"))]
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
#[cfg(not(target_has_atomic = "32"))]
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

#[cfg(not(target_has_atomic = "32"))]
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
    vrgb = const crate::project::RGB_HI_OFFSET,
    vfl = const crate::project::FLAGS_OFFSET,
);

/// `raster::ActiveTri::dither_fits` for RGB565 by [`scanline3d_dither_fits565`]: `rec` is a
/// fast Gouraud triangle just set up on `row` from the vertices `p` (so its first pixel and
/// every vertex are within the 1024-pixel box the fast path requires: the routine's sums stay
/// within 32 bits).
#[cfg(not(target_has_atomic = "32"))]
#[inline(always)]
pub(crate) fn dither_fits565(rec: &ActiveTri, p: [&ScreenVertex; 3], row: i32) -> bool {
    const {
        assert!(crate::project::FLAGS_OFFSET == 10 && crate::project::RGB_HI_OFFSET + 2 < 10);
        assert!(o::INC + 8 <= 124 && o::LEFT + o::S <= 124);
    };
    let ptrs = p.map(|v| v as *const ScreenVertex);
    // SAFETY: the routine reads the record's left edge, `gx`, `row` and `inc` words (at the
    // offsets given to it) and the three vertices' first word, colour bytes and flags half
    // (12-byte `repr(C)` records, offsets asserted above and by `setup565`); it writes only its
    // own frame.
    unsafe { scanline3d_dither_fits565(rec, ptrs.as_ptr(), row) != 0 }
}

extern "C" {
    fn scanline3d_edge_new(a: u32, b: u32, row: i32, out: *mut Edge) -> u32;
    fn scanline3d_xform_q16(m: *const i32, p: *const i32, out: *mut i32, rows: u32);
    fn scanline3d_project_q16(p: *const i32, scales: u32, seed: *const u16, out: *mut i32) -> u32;
    fn scanline3d_gouraud_setup(tri: *const u32, rec: *mut ActiveTri, seed: *const u16) -> u32;
    #[cfg(not(target_has_atomic = "32"))]
    fn scanline3d_setup565(rec: *mut ActiveTri, args: *const SetupArgs) -> u32;
    #[cfg(not(target_has_atomic = "32"))]
    fn scanline3d_dither_fits565(
        rec: *const ActiveTri,
        p: *const *const ScreenVertex,
        row: i32,
    ) -> u32;
    fn scanline3d_fill128(start: *mut [u32; 4], end: *mut [u32; 4], word: u32);
    fn scanline3d_rows565(ctx: *mut RowCtx) -> u32;
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
    #[cfg(not(feature = "rp2040"))]
    fn scanline3d_rows565_dither(ctx: *mut RowCtx, offsets: *const u32) -> u32;
    #[cfg(feature = "rp2040")]
    fn scanline3d_rows565_dither_interp(ctx: *mut RowCtx, offsets: *const u32) -> u32;
    #[cfg(not(target_has_atomic = "32"))]
    fn scanline3d_span565_flat_less(
        z: *mut u16,
        color_offset: isize,
        end: *mut u16,
        acc: *const [u32; 3],
    ) -> u32;
}

/// Whether `C` is stored as one 16-bit word `r << 11 | g << 5 | b` (embedded-graphics'
/// `Rgb565`): its size is two bytes, it says so ([`TargetColor::RGB565_WORD`]), and the three
/// channel maxima land on the expected bits. For a concrete type this folds to a constant.
#[inline(always)]
pub(crate) fn rgb565_words<C: TargetColor>() -> bool {
    if !C::RGB565_WORD || core::mem::size_of::<C>() != 2 || core::mem::align_of::<C>() > 2 {
        return false;
    }
    let bits = |c: [u8; 3]| word(&C::from_channels(c));
    bits([31, 0, 0]) == 0xF800 && bits([0, 63, 0]) == 0x07E0 && bits([0, 0, 31]) == 0x001F
}

/// The bytes of a two-byte colour as a `u16`; only called once `size_of::<C>() == 2` holds.
#[inline(always)]
fn word<C: TargetColor>(c: &C) -> u16 {
    debug_assert_eq!(core::mem::size_of::<C>(), 2);
    // SAFETY: `C` is two bytes without padding (a `u16` wrapper), so its bytes are a `u16`.
    unsafe { core::mem::transmute_copy::<C, u16>(c) }
}

/// The `DepthTest::Less` Gouraud span for RGB565 words; the same arguments as the portable
/// loop. `zs` and `cs` have the same length ≥ 1 and `rgb565_words::<C>()` holds.
#[inline(always)]
pub(crate) fn span565_less<C: TargetColor>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
) -> u32 {
    let n = zs.len().min(cs.len());
    if n == 0 || !rgb565_words::<C>() {
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
    // `cs` (reached as `zp + offset`), both exclusively borrowed; a colour is written as one
    // aligned `u16`, which `rgb565_words` showed is the representation of `C`.
    unsafe { scanline3d_span565_less(zp, offset, zp.add(n), &acc) }
}

/// The dithered `DepthTest::Less` Gouraud span for RGB565 words (`raster::span_packed_dither`):
/// the same arguments as the portable loop, `x0` the first pixel's column and `row` the pixel
/// row. `zs` and `cs` have the same length ≥ 1 and `rgb565_words::<C>()` holds.
#[inline(always)]
pub(crate) fn span565_less_dither<C: TargetColor>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    let n = zs.len().min(cs.len());
    if n == 0 || !rgb565_words::<C>() {
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
    // both exclusively borrowed, colours stored as the `u16` that `rgb565_words` showed is the
    // representation of `C`; the routine also reads the eight words of `offsets` (static).
    unsafe { scanline3d_span565_less_dither(zp, offset, zp.add(n), &acc) }
}

#[cfg(not(target_has_atomic = "32"))]
/// The `DepthTest::Less` flat span for RGB565 words; the same arguments as the portable
/// loop (`z` 16.12 with its rounding bias, `gz` its step), whose truncation `(z >> 12) as u16`
/// is the high half of `z << 4` (both wrap alike).
#[inline(always)]
pub(crate) fn span565_flat_less<C: TargetColor>(
    zs: &mut [u16],
    cs: &mut [C],
    z: i32,
    gz: i32,
    color: C,
) -> u32 {
    let n = zs.len().min(cs.len());
    if n == 0 || !rgb565_words::<C>() {
        return 0;
    }
    let acc = [(z as u32) << 4, (gz as u32) << 4, word(&color) as u32];
    let zp = zs.as_mut_ptr();
    let offset = (cs.as_mut_ptr() as isize).wrapping_sub(zp as isize);
    // SAFETY: as in `span565_less`: `n ≥ 1` pixels at `zp[0..n]` and the same indices of `cs`,
    // both exclusively borrowed; the colour is stored as the `u16` that `rgb565_words` showed
    // is the representation of `C`.
    unsafe { scanline3d_span565_flat_less(zp, offset, zp.add(n), &acc) }
}

/// The inverse of 21 modulo 2³²: a multiple of 84 bytes `b` is `(b >> 2)·INV21` slots
/// (mod 2³²). The row routine keeps slot addresses, not indices.
const INV21: u32 = 0x3cf3_cf3d;
const _: () = assert!(21u32.wrapping_mul(INV21) == 1 && core::mem::size_of::<ActiveTri>() == 84);

/// What the row routine reads and updates (`#[repr(C)]`: the assembly uses the offsets).
#[repr(C)]
struct RowCtx {
    /// The active list's records, in drawing order.
    tris: *mut ActiveTri,
    n: usize,
    i: usize,
    depth: *mut u16,
    color_offset: isize,
    /// Twice the width (the routine's columns are byte offsets).
    width_bytes: i32,
    fragments: u32,
    hidden: u32,
}

// The routine copies the first six words to its stack frame with one `ldm`.
const _: () = {
    use core::mem::offset_of;
    assert!(offset_of!(RowCtx, tris) == 0 && offset_of!(RowCtx, n) == 4);
    assert!(offset_of!(RowCtx, i) == 8 && offset_of!(RowCtx, depth) == 12);
    assert!(offset_of!(RowCtx, color_offset) == 16 && offset_of!(RowCtx, width_bytes) == 20);
};

/// Draws one row of the active triangles `start..` for as long as they are fast Gouraud
/// triangles with their left edge on screen (the rows that make up most of a frame; the
/// triangle's routine row count and its last-row and switch flags say so,
/// `ActiveTri::set_routine_rows`), each exactly as `ActiveTri::draw_row` would: the span into
/// RGB565 words, then both edges and the packed attribute rows step — or, on the row before
/// the short edge's switch, the edges and rows move as `ActiveTri::advance` moves them there,
/// to the edge setup kept — or, on a triangle's last row, the triangle leaves the list as
/// `ActiveList::swap_remove` does. With `dither` (for a colour it changes), the spans are
/// `raster::span_packed_dither`'s for pixel row `row`, and only triangles with `DITHER_OK`
/// are drawn.
/// Returns `(index reached, fragments, written)`: the index is `active.len()` or the first
/// triangle that needs `draw_row`. `None` when `C` is not an RGB565 word.
#[inline(always)]
pub(crate) fn rows565<C: TargetColor, const N: usize>(
    active: &mut ActiveList<N>,
    start: usize,
    colors: &mut [C],
    depth: &mut [u16],
    row: usize,
    dither: bool,
) -> Option<(usize, u32, u32)> {
    if !rgb565_words::<C>() || start >= active.len() || !active.routine_may_draw(start) {
        return None;
    }
    let dither = dither && C::can_dither();
    let (tris, n) = active.raw_parts();
    let zp = depth.as_mut_ptr();
    let mut ctx = RowCtx {
        tris,
        n,
        i: start,
        depth: zp,
        color_offset: (colors.as_mut_ptr() as isize).wrapping_sub(zp as isize),
        width_bytes: 2 * colors.len().min(depth.len()).min(1024) as i32,
        fragments: 0,
        hidden: 0,
    };
    // SAFETY: the routine reads and writes the records of slots `start..n` (below `N`) and
    // moves the last of them into a removed one's slot, at the field offsets asserted above
    // (`#[repr(C)]`), and pixels `left.c..min(right.c, width)` of both lines only for records
    // it checked to have `left.c ≥ 0`, with `width` at most both lengths; colours are written
    // as `u16` words, which `rgb565_words` showed is the representation of `C`. It never goes
    // past `n`.
    // With dithering (which changes an RGB565 colour), the dithered routine: the same, with
    // the row's offsets (eight static words), and only for triangles with `DITHER_OK`; it
    // also reads those eight words.
    unsafe {
        if dither {
            #[cfg(feature = "rp2040")]
            {
                scanline3d_rows565_dither_interp(&mut ctx, DITHER565[row & 3].as_ptr())
            }
            #[cfg(not(feature = "rp2040"))]
            {
                scanline3d_rows565_dither(&mut ctx, DITHER565[row & 3].as_ptr())
            }
        } else {
            scanline3d_rows565(&mut ctx)
        }
    };
    active.set_len_after_routine(ctx.n);
    Some((
        ctx.i,
        ctx.fragments,
        ctx.fragments.saturating_sub(ctx.hidden),
    ))
}

/// Fills a run of 16-bit words four 32-bit words at a time (the library `fill` of a colour
/// line is a loop of 16-bit stores; each strip clears one colour and one depth line per row).
#[inline(always)]
fn fill16(line: &mut [u16], v: u16) {
    let w = (v as u32) << 16 | v as u32;
    // SAFETY: every bit pattern is a valid `u16` and `[u32; 4]`; `align_to_mut` returns the
    // aligned middle and the unaligned ends, which are filled as `u16`.
    let (head, mid, tail) = unsafe { line.align_to_mut::<[u32; 4]>() };
    head.fill(v);
    let p = mid.as_mut_ptr();
    // SAFETY: the routine stores 16 bytes at a time from `p` up to `p + mid.len()`, the
    // exclusively borrowed, word-aligned middle.
    unsafe { scanline3d_fill128(p, p.add(mid.len()), w) };
    tail.fill(v);
}

/// Clears a strip line: colour `background` (RGB565 words, as [`rgb565_words`] checks) and
/// depth 65535. Returns false, having done nothing, when `C` is not an RGB565 word.
#[inline(always)]
pub(crate) fn clear_line<C: TargetColor>(
    colors: &mut [C],
    depth: &mut [u16],
    background: C,
) -> bool {
    if !rgb565_words::<C>() {
        return false;
    }
    // SAFETY: `C` is a two-byte, two-aligned `u16` wrapper (checked above), so its bytes are a
    // `u16` and every `u16` is a `C`.
    let words =
        unsafe { core::slice::from_raw_parts_mut(colors.as_mut_ptr() as *mut u16, colors.len()) };
    fill16(words, word(&background));
    fill16(depth, u16::MAX);
    true
}
