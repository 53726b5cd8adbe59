//! The row routines on Thumb-2 (ARMv7-M and later: the `scanline3d_thumb2` cfg).
//!
//! The plain routine `scanline3d_rows565` is its own Thumb-2 source here (below): the slot in
//! r12, one `ldm` of the record's first six words and one `stm` of five, edges and attribute
//! rows stepped before the span, high registers as working registers and a pixel loop that
//! indexes both lines in pixels. Outside the 16 instructions per written pixel, a drawn row
//! of the common path takes 32 instructions, 3 more when its right edge carries and 6 more
//! when its left edge does (about 36 on average; the Thumb-1 routine's Thumb-2 build took
//! about 49): the torus frame's rows565 count went from 926 403 to 827 553 instructions.
//!
//! The dithered routine (`rows_dither`) keeps the shared `rows565_routine` source with the
//! Thumb-2 forms of its hot path macros below (`row_span`, `both_edges_step`,
//! `next_triangle`): the same registers, results and stack frame as their Thumb-1 twins, in
//! fewer instructions — `ldm`/`stm` without write-back into high registers, loads at offsets
//! from r12 and sp with `ldrd`, shifted operands and `ubfx`. The Thumb-1 forms stay on ARMv6-M
//! (and ARMv8-M Baseline), unchanged.
#![allow(unsafe_code)]

use super::offsets as o;
use super::rows::RowCtx;
use crate::kernel::records::ActiveTri;

/// [`row_span`] (Thumb-2): the steps loaded straight into r8–r10 and the left column by `ubfx`
/// (4 instructions instead of 9).
macro_rules! row_span {
    ($run:ident) => {
        concat!(
            "mov r12, r3\n",
            "ubfx r4, r5, #15, #16\n",
            "add r0, r3, #{gx0}\n",
            "ldm r0, {{r8, r9, r10}}\n",
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

/// [`both_edges_step`] (Thumb-2): the record addressed from r12 (the triangle, as r0), the
/// edge and row words loaded and stored without write-back, the carries added with a shifted
/// operand. 4 instructions fewer a row.
macro_rules! both_edges_step {
    () => {
        concat!(
            "17:\n",
            "add r5, r12, #{lw}\n",
            "ldm r5, {{r1, r2, r3, r4}}\n",
            "adds r3, r3, r4\n",
            "bpl 7f\n",
            "ldrh r6, [r12, #{rdy}]\n",
            "add.w r3, r3, r6, lsl #16\n",
            "adds r3, #1\n",
            "7:\n",
            "adds r1, r1, r2\n",
            "bmi 9f\n",
            "stm r5, {{r1, r2, r3, r4}}\n",
            "adds r5, #({row_after_edges} + 16)\n",
            "ldm r5, {{r0, r1, r2, r3, r4, r6, r7}}\n",
            "adds r0, r0, r4\n",
            "adds r1, r1, r6\n",
            "adds r2, r2, r7\n",
            "stm r5, {{r0, r1, r2}}\n",
            next_triangle!(),
            "9:\n",
            "ldrh r6, [r12, #{ldy}]\n",
            "add.w r1, r1, r6, lsl #16\n",
            "adds r1, #1\n",
            "stm r5, {{r1, r2, r3, r4}}\n",
            "adds r5, #({row_after_edges} + 16)\n",
            "ldm r5, {{r0, r1, r2, r3, r4, r6, r7}}\n",
            "adds r0, r0, r4\n",
            "adds r1, r1, r6\n",
            "adds r2, r2, r7\n",
            "add r0, r8\n",
            "add r1, r9\n",
            "add r2, r10\n",
            "stm r5, {{r0, r1, r2}}\n",
            next_triangle!(),
        )
    };
}

/// [`next_triangle`] (Thumb-2): the next slot from r12 (the triangle just drawn) rather than
/// from the frame.
macro_rules! next_triangle {
    () => {
        concat!("add r3, r12, #{size}\n", "str r3, [sp, #8]\n", "b 15b\n",)
    };
}

// The plain row routine in Thumb-2 (`scanline3d_rows565` on ARMv7-M and later; ARMv6-M keeps
// the Thumb-1 routine of `rows`). The same rows, pixels and record updates, with its own
// registers and frame: the slot address i lives in r12 and the fragment count (in pixels) in
// lr for the whole call; a row loads its record's first six words (flags and count, both
// edges, both `dy`) with one `ldm`, steps both edges and the packed attribute rows *before*
// drawing (the edges and the decremented count go back with one `stm`, the rows with one
// `ldm`/`stm` that also leaves the row's start values in the pixel loop's accumulators), then
// draws the span with [`t2_pixel_loop`]. Frame: [sp] = slot n, [sp, #4] = the width (pixels),
// [sp, #8] = colour line − depth line (bytes), [sp, #12] = the depth line, [sp, #16] = the
// hidden count, [sp, #20] = the records, [sp, #24] = the context, [sp, #28] = scratch.

/// The Thumb-2 row routine's pixel loop: [`pixel_loop`] with its own registers — r7 = end of the
/// depth run, r4 = end of the colour run, r10 = minus the run's length in *pixels* (the lines
/// addressed with `lsl #1`), r0, r1, r2 = z, rb, g and r3, r9, r11 their steps; uses r5, r6.
/// Falls through to label 2 after its last pixel; a hidden pixel goes to label 3
/// ([`t2_hidden_pixel`], placed after the code that follows the loop). 16 instructions per
/// written pixel, 12 per hidden one.
macro_rules! t2_pixel_loop {
    () => {
        concat!(
            "1:\n",
            "ldrh r5, [r7, r10, lsl #1]\n",
            "lsrs r6, r0, #16\n",
            "cmp r6, r5\n",
            "bhs 3f\n",
            "strh r6, [r7, r10, lsl #1]\n",
            "lsrs r5, r1, #27\n",
            "lsrs r6, r2, #26\n",
            "orr.w r5, r6, r5, lsl #6\n",
            "ubfx r6, r1, #11, #5\n",
            "orr.w r5, r6, r5, lsl #5\n",
            "strh r5, [r4, r10, lsl #1]\n",
            "add r0, r3\n",
            "add r1, r9\n",
            "add r2, r11\n",
            "adds r10, #1\n",
            "bne 1b\n",
            "2:\n",
        )
    };
}

/// [`t2_pixel_loop`]'s hidden pixel (label 3): counted in the frame, stepped, and back to the
/// loop, or on to label 2 after the last pixel. Placed after an unconditional branch.
macro_rules! t2_hidden_pixel {
    () => {
        concat!(
            "3:\n",
            "ldr r5, [sp, #16]\n",
            "adds r5, #1\n",
            "str r5, [sp, #16]\n",
            "add r0, r3\n",
            "add r1, r9\n",
            "add r2, r11\n",
            "adds r10, #1\n",
            "bne 1b\n",
            "b 2b\n",
        )
    };
}

/// Before [`t2_pixel_loop`] (r7 = end of the depth run, r10 = minus its length, r8 = colour
/// line − depth line): the colour run's end into r4 and the fragments counted (lr).
macro_rules! t2_loop_setup {
    () => {
        concat!("add r4, r7, r8\n", "sub lr, lr, r10\n")
    };
}

/// Both edges of the row's record step (r1, r2 = left w, s; r3, r4 = right w, s; r5 = both
/// `dy`, left in the low half; as `edge_step!`): the right one here, the left one too when it
/// does not carry, and all five words (r0 = flags and count) are stored; a carry of the left
/// edge goes to `$carry` ([`t2_left_carry`]). Uses r6.
macro_rules! t2_edges {
    ($carry:expr) => {
        concat!(
            "adds r3, r3, r4\n",
            "bpl 7f\n",
            "lsrs r6, r5, #16\n",
            "add.w r3, r3, r6, lsl #16\n",
            "adds r3, #1\n",
            "7:\n",
            "adds r1, r1, r2\n",
            "bmi ",
            $carry,
            "\n",
            "stm r12, {{r0, r1, r2, r3, r4}}\n",
        )
    };
}

/// [`t2_edges`] when the left edge carries: w += dy·2¹⁶ + 1, and the five words stored.
macro_rules! t2_left_carry {
    () => {
        concat!(
            "add.w r1, r1, r5, lsl #16\n",
            "adds r1, #1\n",
            "stm r12, {{r0, r1, r2, r3, r4}}\n",
        )
    };
}

/// The packed attribute rows step (row += inc, and + gx when `$carry` is
/// "add r4, r3\nadd r5, r9\nadd r6, r11\n"), leaving the row's start values in r0–r2 and the
/// per-pixel steps gx in r3, r9, r11. Uses r4–r6.
macro_rules! t2_rows {
    ("") => {
        concat!(
            "add r9, r12, #{row0}\n",
            "ldm r9, {{r0, r1, r2, r3, r4, r5, r6}}\n",
            "add r4, r0\n",
            "add r5, r1\n",
            "add r6, r2\n",
            "stm r9, {{r4, r5, r6}}\n",
            "add r11, r12, #{gx0}\n",
            "ldm r11, {{r3, r9, r11}}\n",
        )
    };
    ($carry:expr) => {
        concat!(
            "add r6, r12, #{row0}\n",
            "ldm r6, {{r0, r1, r2, r3, r4, r5, r6}}\n",
            "add r11, r12, #{gx0}\n",
            "ldm r11, {{r3, r9, r11}}\n",
            "add r4, r0\n",
            "add r5, r1\n",
            "add r6, r2\n",
            $carry,
            "strd r4, r5, [r12, #{row0}]\n",
            "str r6, [r12, #({row0} + 8)]\n",
        )
    };
}

/// The gx additions of a carried row for [`t2_rows`].
macro_rules! t2_gx {
    () => {
        "add r4, r3\nadd r5, r9\nadd r6, r11\n"
    };
}

/// The next slot (i += 84) and the loop test: back to the row head (label 16) with r7 = the
/// width, r8 = colour line − depth line and r11 = the depth line while i < n, else out with 0
/// (label 11).
macro_rules! t2_next {
    () => {
        concat!(
            "add r12, r12, #{size}\n",
            "ldm sp, {{r6, r7, r8, r11}}\n",
            "cmp r12, r6\n",
            "blo 16b\n",
            "b 11b\n",
        )
    };
}

/// For a row with `left.c < 0` ([`row_span_left_clamped`]): the start values at column 0,
/// row + gx·(−left.c) (wrapping), with −left.c in the frame's scratch word.
macro_rules! t2_left_clamped_start {
    () => {
        concat!(
            "ldr r5, [sp, #28]\n",
            "mla r0, r3, r5, r0\n",
            "mla r1, r9, r5, r1\n",
            "mla r2, r11, r5, r2\n",
        )
    };
}

/// A drawn row of the main path after the span's checks (r7 = end of the depth run, r10 = minus
/// its length): edges, rows (`$start` then moves the start values), the span, the next slot;
/// the left edge's carry at label `$c`.
macro_rules! t2_row {
    ($c:literal, $start:expr) => {
        concat!(
            t2_edges!(concat!($c, "f")),
            t2_rows!(""),
            $start,
            t2_loop_setup!(),
            t2_pixel_loop!(),
            t2_next!(),
            t2_hidden_pixel!(),
            $c,
            ":\n",
            t2_left_carry!(),
            t2_rows!(t2_gx!()),
            $start,
            t2_loop_setup!(),
            t2_pixel_loop!(),
            t2_next!(),
            t2_hidden_pixel!(),
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_rows565,\"ax\",%progbits",
    ".global scanline3d_rows565",
    ".type scanline3d_rows565,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = &mut RowCtx; returns 0 when it reached n, 1 when triangle i needs the portable path.
    "scanline3d_rows565:",
    "push {{r4-r11, lr}}",
    "mov r7, r0",
    "ldm r0, {{r0, r1, r2, r3, r4, r5}}",
    "movs r6, #{size}",
    "mla r12, r2, r6, r0",
    "mla r1, r1, r6, r0",
    "lsrs r2, r5, #1",
    "mov r5, r3",
    "mov r3, r4",
    "mov r4, r5",
    "movs r5, #0",
    "mov r6, r0",
    "push {{r1, r2, r3, r4, r5, r6, r7, r8}}",
    "mov lr, r5",
    "ldm sp, {{r6, r7, r8, r11}}",
    "cmp r12, r6",
    "blo 16f",
    "11:",
    "movs r0, #0",
    "b 13f",
    "12:",
    "movs r0, #1",
    "b 13f",
    // Slot i (r12) qualifies: rows left on its routine count (else label 19) and left.c ≥ 0
    // (else label 18). r7 = the width, r8 = colour line − depth line, r11 = the depth line.
    "16:",
    "ldm r12, {{r0, r1, r2, r3, r4, r5}}",
    "tst r0, #0xff00",
    "beq 19f",
    "sub r0, r0, #0x100",
    "tst r1, #0x8000",
    "beq 18f",
    // The span left.c..min(right.c, width) (as `row_span`: both columns ≥ 0 on a drawn row);
    // an empty one only steps (label 30).
    "ubfx r6, r1, #0, #15",
    "ubfx r9, r3, #0, #15",
    "cmp r9, r7",
    "bgt 5f",
    "6:",
    "subs r10, r6, r9",
    "bge 30f",
    "add r7, r11, r9, lsl #1",
    t2_row!("9", ""),
    "5:",
    "mov r9, r7",
    "b 6b",
    // An empty span: the steps only.
    "30:",
    t2_edges!("31f"),
    "add r9, r12, #{row0}",
    "ldm r9, {{r0, r1, r2, r3, r4, r5, r6}}",
    "add r4, r0",
    "add r5, r1",
    "add r6, r2",
    "stm r9, {{r4, r5, r6}}",
    t2_next!(),
    "31:",
    t2_left_carry!(),
    t2_rows!(t2_gx!()),
    t2_next!(),
    // left.c < 0: the span 0..min(right.c, width) (right.c may be < 0 too: then empty), its
    // start values at column 0.
    "18:",
    "uxth r9, r3",
    "subs r9, r9, #0x8000",
    "ble 30b",
    "cmp r9, r7",
    "bgt 45f",
    "46:",
    "add r7, r11, r9, lsl #1",
    "rsb r10, r9, #0",
    "uxth r6, r1",
    "rsb r6, r6, #0x8000",
    "str r6, [sp, #28]",
    t2_row!("41", t2_left_clamped_start!()),
    "45:",
    "mov r9, r7",
    "b 46b",
    // The count is used up (r0 = flags): the triangle's last row or the row before its short
    // edge's switch, if it is marked so and left.c ≥ 0 (else out with 1).
    "19:",
    "tst r1, #0x8000",
    "beq 12b",
    "tst r0, #{last_flag}",
    "beq 26f",
    // Only a fast triangle's bit: a pool kind keeps a code there (`raster::kind`).
    "tst r0, #{fast}",
    "beq 12b",
    // The last row: drawn, then the last record (slot n − 1) moves into slot i, as
    // `ActiveList::swap_remove`.
    "ubfx r6, r1, #0, #15",
    "ubfx r9, r3, #0, #15",
    "cmp r9, r7",
    "bgt 55f",
    "56:",
    "subs r10, r6, r9",
    "bge 21f",
    "add r7, r11, r9, lsl #1",
    "add r4, r12, #{row0}",
    "ldm r4, {{r0, r1, r2}}",
    "add r11, r12, #{gx0}",
    "ldm r11, {{r3, r9, r11}}",
    t2_loop_setup!(),
    t2_pixel_loop!(),
    "21:",
    "ldr r2, [sp]",
    "subs r2, #{size}",
    "str r2, [sp]",
    "cmp r12, r2",
    "beq 11b",
    "ldm r2, {{r0, r1, r3, r4, r5, r6, r7, r8, r9, r10, r11}}",
    "stm r12, {{r0, r1, r3, r4, r5, r6, r7, r8, r9, r10, r11}}",
    "add r2, #44",
    "ldm r2, {{r0, r1, r2, r3, r4, r5, r6, r7, r8, r9}}",
    "add r11, r12, #44",
    "stm r11, {{r0, r1, r2, r3, r4, r5, r6, r7, r8, r9}}",
    "ldm sp, {{r6, r7, r8, r11}}",
    "b 16b",
    t2_hidden_pixel!(),
    "55:",
    "mov r9, r7",
    "b 56b",
    // The row before the switch: drawn, then the edges and rows move as
    // `ActiveTri::advance` moves them at the switch (gx stays in r3, r9, r11).
    "26:",
    "tst r0, #{switch_flag}",
    "beq 12b",
    "tst r0, #{fast}",
    "beq 12b",
    "ubfx r6, r1, #0, #15",
    "ubfx r9, r3, #0, #15",
    "cmp r9, r7",
    "bgt 57f",
    "58:",
    "subs r10, r6, r9",
    "add r7, r11, r9, lsl #1",
    "add r11, r12, #{gx0}",
    "ldm r11, {{r3, r9, r11}}",
    "bge 27f",
    "add r4, r12, #{row0}",
    "ldm r4, {{r0, r1, r2}}",
    t2_loop_setup!(),
    t2_pixel_loop!(),
    // Count and flags for the rows from the switch on: row_end − 1 − row_mid, last row flag
    // when it is at most 255.
    "27:",
    "ldrh r1, [r12, #{row_end}]",
    "ldrh r2, [r12, #{row_mid}]",
    "subs r1, r1, r2",
    "subs r1, #1",
    "ldrb r2, [r12, #{flags}]",
    "bic r2, r2, #{switch_flag}",
    "cmp r1, #255",
    "bls 22f",
    "movs r1, #255",
    "b 23f",
    "22:",
    "adds r2, #{last_flag}",
    "23:",
    "strb r2, [r12, #{flags}]",
    "strb r1, [r12, #{rrows}]",
    "tst r2, #{mid_left}",
    "bne 24f",
    // The middle vertex is right: the right edge becomes the pending one; the left edge steps
    // with the rows as on any row.
    "ldr r1, [r12, #{pend_w}]",
    "str r1, [r12, #{rw}]",
    "ldr r1, [r12, #{pend_s}]",
    "str r1, [r12, #{rs}]",
    "ldr r1, [r12, #{pend_dy}]",
    "strh r1, [r12, #{rdy}]",
    "ldrd r1, r2, [r12, #{lw}]",
    "adds r1, r1, r2",
    "bmi 8f",
    "str r1, [r12, #{lw}]",
    "add r8, r12, #{row0}",
    "ldm r8, {{r0, r1, r2, r4, r5, r6, r7}}",
    "add r5, r0",
    "add r6, r1",
    "add r7, r2",
    "stm r8, {{r5, r6, r7}}",
    t2_next!(),
    "8:",
    "ldrh r2, [r12, #{ldy}]",
    "add.w r1, r1, r2, lsl #16",
    "adds r1, #1",
    "str r1, [r12, #{lw}]",
    "add r8, r12, #{row0}",
    "ldm r8, {{r0, r1, r2, r4, r5, r6, r7}}",
    "add r5, r0",
    "add r6, r1",
    "add r7, r2",
    "add r5, r3",
    "add r6, r9",
    "add r7, r11",
    "stm r8, {{r5, r6, r7}}",
    t2_next!(),
    // The middle vertex is left: the right edge steps; the left one becomes the pending one,
    // and the attributes move along the old left edge by one row (with its carry), then by
    // dc = new c − old stepped c columns, and their row step changes by dsq = new sq − old sq
    // columns (see the Thumb-1 routine).
    "24:",
    "ldrd r1, r2, [r12, #{rw}]",
    "adds r1, r1, r2",
    "bpl 7f",
    "ldrh r2, [r12, #{rdy}]",
    "add.w r1, r1, r2, lsl #16",
    "adds r1, #1",
    "7:",
    "str r1, [r12, #{rw}]",
    "ldrd r1, r2, [r12, #{lw}]",
    "uxth r4, r1",
    "sxth r5, r2",
    "add r4, r4, r5",
    "sub r2, r5, r2",
    "lsrs r1, r1, #16",
    "lsrs r2, r2, #16",
    // r6 = −carry (carry: e < sr).
    "cmp r1, r2",
    "sbc r6, r6, r6",
    "sub r1, r4, r6",
    "ldr r7, [r12, #{pend_w}]",
    "uxth r4, r7",
    "sub r4, r4, r1",
    "sub r4, r4, r6",
    "ldr r8, [r12, #{pend_s}]",
    "sxth r10, r8",
    "sub r10, r10, r5",
    "str r7, [r12, #{lw}]",
    "str r8, [r12, #{ls}]",
    "ldr r1, [r12, #{pend_dy}]",
    "strh r1, [r12, #{ldy}]",
    // row += inc + gx·(dc + carry); inc += gx·dsq.
    "add r8, r12, #{row0}",
    "ldm r8, {{r0, r1, r2, r5, r6, r7, r8}}",
    "add r0, r6",
    "mla r0, r3, r4, r0",
    "add r1, r7",
    "mla r1, r9, r4, r1",
    "add r2, r8",
    "mla r2, r11, r4, r2",
    "mla r6, r3, r10, r6",
    "mla r7, r9, r10, r7",
    "mla r8, r11, r10, r8",
    "add r5, r12, #{row0}",
    "stm r5, {{r0, r1, r2}}",
    "add r5, r12, #{inc0}",
    "stm r5, {{r6, r7, r8}}",
    t2_next!(),
    t2_hidden_pixel!(),
    "57:",
    "mov r9, r7",
    "b 58b",
    // Slot addresses back to indices.
    "13:",
    "ldr r1, [sp, #24]",
    "ldr r3, [sp, #20]",
    "movs r5, #{size}",
    "ldr r2, [sp]",
    "subs r2, r2, r3",
    "udiv r2, r2, r5",
    "str r2, [r1, #{cn}]",
    "sub r2, r12, r3",
    "udiv r2, r2, r5",
    "str r2, [r1, #{ci}]",
    "str lr, [r1, #{cfrag}]",
    "ldr r2, [sp, #16]",
    "str r2, [r1, #{chidden}]",
    "add sp, #32",
    "pop {{r4-r11, pc}}",
    ".size scanline3d_rows565, . - scanline3d_rows565",
    ci = const core::mem::offset_of!(RowCtx, i),
    cn = const core::mem::offset_of!(RowCtx, n),
    cfrag = const core::mem::offset_of!(RowCtx, fragments),
    chidden = const core::mem::offset_of!(RowCtx, hidden),
    size = const core::mem::size_of::<ActiveTri>(),
    rrows = const o::ROUTINE_ROWS,
    flags = const o::FLAGS,
    switch_flag = const o::SWITCH,
    last_flag = const o::LAST,
    fast = const o::FAST,
    mid_left = const o::MID_LEFT,
    row_mid = const o::ROW_MID,
    row_end = const o::ROW_END,
    pend_w = const o::PEND_W,
    pend_s = const o::PEND_S,
    pend_dy = const o::PEND_DY,
    inc0 = const o::INC,
    lw = const o::LEFT + o::W,
    ls = const o::LEFT + o::S,
    ldy = const o::LEFT_DY,
    rw = const o::RIGHT + o::W,
    rs = const o::RIGHT + o::S,
    rdy = const o::RIGHT_DY,
    gx0 = const o::GX,
    row0 = const o::ROW,
);

// The record layout the routine's `ldm`s assume: flags and count in the first word, then both
// edges' words and both `dy` (six words), `row` (with the pending `s`) right before `inc`.
const _: () = {
    assert!(o::FLAGS == 0 && o::ROUTINE_ROWS == 1 && o::LEFT == 4 && o::W == 0 && o::S == 4);
    assert!(o::RIGHT == 12 && o::LEFT_DY == 20 && o::RIGHT_DY == 22);
    assert!(o::ROW == o::GX + 16 && o::INC == o::ROW + 16 && o::PEND_S == o::ROW + 12);
    assert!(core::mem::size_of::<ActiveTri>() == 84);
};
