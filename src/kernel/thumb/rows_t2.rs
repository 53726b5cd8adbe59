//! Thumb-2 forms (ARMv7-M and later: the `scanline3d_thumb2` cfg) of the row routine's hot
//! path macros (`rows`): the same registers, results and stack frame as their Thumb-1 twins,
//! in fewer instructions — `ldm`/`stm` without write-back into high registers, loads at
//! offsets from r12 and sp with `ldrd`, shifted operands and `ubfx`. The routine around them
//! is the same source; the Thumb-1 forms stay on ARMv6-M (and ARMv8-M Baseline), unchanged.

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

/// [`span_run`] (Thumb-2): both line ends from one `ldrd` of the frame's line words.
macro_rules! span_run {
    () => {
        concat!(
            "add lr, r6\n",
            "ldrd r7, r1, [sp, #12]\n",
            "add r7, r5\n",
            "add r1, r5\n",
            "negs r0, r6\n",
            pixel_loop!(),
            "b 5f\n",
            hidden_pixel!(count_on_stack!(), gouraud_steps!()),
            "5:\n",
            "mov r0, r12\n",
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
