//! The row routine: one row of every qualifying active triangle (span, edge steps, attribute
//! steps, the short edge's switch, removal after the last row), for RGB565 words, and its
//! macros (the dithered twins are in `rows_dither`).
#![allow(unsafe_code)]

#[cfg(not(scanline3d_thumb2))]
use super::offsets as o;
use crate::kernel::records::{ActiveList, ActiveTri, DITHER565};

extern "C" {
    fn scanline3d_rows565(ctx: *mut RowCtx) -> u32;
    #[cfg(not(feature = "rp2040"))]
    fn scanline3d_rows565_dither(ctx: *mut RowCtx, offsets: *const u32) -> u32;
    #[cfg(feature = "rp2040")]
    fn scanline3d_rows565_dither_interp(ctx: *mut RowCtx, offsets: *const u32) -> u32;
}
/// One row of the triangle in r3 (r5 = its left edge's `w << 16`, with `left.c ≥ 0`) for the
/// row routine: loads its three per-pixel steps into r8–r10 (kept after the span: the row step
/// reuses them), draws the span `left.c..min(right.c, width)` with [`pixel_loop`] (the stack
/// frame counts hidden pixels, lr twice the fragments, across the routine's call; r11 is
/// twice the width) and ends with
/// r0 = r12 = the triangle. Reads the stack frame of `scanline3d_rows565`. On a row it draws,
/// `right.c ≥ left.c ≥ 0`, so both biased columns (`raster::EdgeDda`) give twice the column
/// as `(w << 17) >> 16`.
#[cfg(not(scanline3d_thumb2))]
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
#[cfg(not(scanline3d_thumb2))]
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
pub(super) const INTERP0_LANE0: u32 = 16 | 15 << 10 | 1 << 17;
#[cfg(feature = "rp2040")]
pub(super) const INTERP0_LANE1: u32 = 31 << 10 | 1 << 16 | 1 << 18;
/// Interpolator 1, lane 0: bits 27–31 of the red-blue word at bits 11–15 (red); lane 1, from
/// the same accumulator: bits 11–15 at bits 0–4 (blue). The full result (BASE2 = 0) is both.
#[cfg(feature = "rp2040")]
pub(super) const INTERP1_LANE0: u32 = 16 | 11 << 5 | 15 << 10;
#[cfg(feature = "rp2040")]
pub(super) const INTERP1_LANE1: u32 = 11 | 4 << 10 | 1 << 16;

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

/// After a drawn row of the triangle in r0 = r12: both edges step (as `edge_step!`), loaded
/// and stored with one `ldm` and one `stm` (r1, r2 = left w, s; r3, r4 = right w, s), and the
/// packed rows with them: row += inc, and + gx (still in r8–r10) when the left edge carried;
/// one path for each. Label 17; each path ends with [`next_triangle`].
#[cfg(not(scanline3d_thumb2))]
macro_rules! both_edges_step {
    () => {
        concat!(
            "17:\n",
            "adds r5, r0, #{lw}\n",
            "ldm r5!, {{r1, r2, r3, r4}}\n",
            "adds r3, r3, r4\n",
            "bpl 7f\n",
            "ldrh r6, [r0, #{rdy}]\n",
            "lsls r6, r6, #16\n",
            "adds r6, #1\n",
            "adds r3, r3, r6\n",
            "7:\n",
            "adds r1, r1, r2\n",
            "bmi 9f\n",
            "subs r5, #16\n",
            "stm r5!, {{r1, r2, r3, r4}}\n",
            "adds r5, #{row_after_edges}\n",
            row_step_at!("r5", "r4", ""),
            next_triangle!(),
            "9:\n",
            "ldrh r6, [r0, #{ldy}]\n",
            "lsls r6, r6, #16\n",
            "adds r6, #1\n",
            "adds r1, r1, r6\n",
            "subs r5, #16\n",
            "stm r5!, {{r1, r2, r3, r4}}\n",
            "adds r5, #{row_after_edges}\n",
            row_step_at!("r5", "r4", "add r0, r8\nadd r1, r9\nadd r2, r10\n"),
            next_triangle!(),
        )
    };
}

/// The row routine's move to the next entry of the active list (slot address i += 84) and
/// back to its loop head, label 15. Repeated after each row step rather than branched to:
/// a branch fewer a row.
#[cfg(not(scanline3d_thumb2))]
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
    // Only a fast triangle's bit: a pool kind keeps a code there (`raster::kind`).
    "lsls r5, r4, #{fast_shift}",
    "bpl 12b",
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
    "lsls r5, r4, #{fast_shift}",
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
    // Both edges step (as `edge_step!`) and the packed rows with them (label 17).
    both_edges_step!(),
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
    fast_shift = const 31 - o::FAST.trailing_zeros(),
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

// On Thumb-2 the plain routine is `rows_t2`'s.
#[cfg(not(scanline3d_thumb2))]
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

/// The inverse of 21 modulo 2³²: a multiple of 84 bytes `b` is `(b >> 2)·INV21` slots
/// (mod 2³²). The row routine keeps slot addresses, not indices.
pub(super) const INV21: u32 = 0x3cf3_cf3d;
const _: () = assert!(21u32.wrapping_mul(INV21) == 1 && core::mem::size_of::<ActiveTri>() == 84);

/// What the row routine reads and updates (`#[repr(C)]`: the assembly uses the offsets).
#[repr(C)]
pub(super) struct RowCtx {
    /// The active list's records, in drawing order.
    pub(super) tris: *mut ActiveTri,
    pub(super) n: usize,
    pub(super) i: usize,
    pub(super) depth: *mut u16,
    pub(super) color_offset: isize,
    /// Twice the width (the routine's columns are byte offsets).
    pub(super) width_bytes: i32,
    pub(super) fragments: u32,
    pub(super) hidden: u32,
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
/// triangle that needs `draw_row`. `None` when it draws nothing from `start` (`dither`: RGB565 words change under
/// dithering).
#[inline(always)]
pub(crate) fn rows565<const N: usize>(
    active: &mut ActiveList<N>,
    start: usize,
    colors: &mut [u16],
    depth: &mut [u16],
    row: usize,
    dither: bool,
) -> Option<(usize, u32, u32)> {
    if start >= active.len() || !active.routine_may_draw(start) {
        return None;
    }
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
