//! Thumb-2 form (ARMv7-M and later: the `scanline3d_thumb2` cfg) of the Q16.16 transform
//! `scanline3d_xform_q16` (`xform`): the same arguments and results as the Thumb-1 routine,
//! each row's three products accumulated by `smlal` (about 15 instructions a row where the
//! Thumb-1 routine takes about 80). The vertex kernel (`vertex`) calls it.

/// One row of [`scanline3d_xform_q16`]: the row's four words loaded from r0 (advanced), the
/// point in r4–r6, the last column's mask in lr; `sat32((Σ a·b + (c << 16) + 2¹⁵) >> 16)`
/// stored at r2 (advanced). Every entry is in [−2³⁰, 2³⁰), so the sum is far inside 64 bits.
/// Uses r1, r3, r7–r10.
macro_rules! xform_row_t2 {
    () => {
        concat!(
            "ldm r0!, {{r7, r8, r9, r10}}\n",
            "and r10, r10, lr\n",
            // r3:r1 = (c << 16) + 2¹⁵ (the low half of c << 16 is zero: no carry).
            "lsls r1, r10, #16\n",
            "add r1, r1, #0x8000\n",
            "asr r3, r10, #16\n",
            "smlal r1, r3, r7, r4\n",
            "smlal r1, r3, r8, r5\n",
            "smlal r1, r3, r9, r6\n",
            // The sum >> 16 when it fits an i32, else i32::MAX or i32::MIN by its sign.
            "lsrs r1, r1, #16\n",
            "orr r1, r1, r3, lsl #16\n",
            "asr r7, r3, #16\n",
            "cmp r7, r1, asr #31\n",
            "beq 1f\n",
            "mvn r1, #0x80000000\n",
            "eor r1, r1, r3, asr #31\n",
            "1:\n",
            "str r1, [r2], #4\n",
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
    "scanline3d_xform_q16:",
    "push {{r4, r5, r6, r7, r8, r9, r10, lr}}",
    "ldm r1, {{r4, r5, r6}}",
    "mov r12, r3",
    // lr = the last column's mask: all ones for a point (r3 = 4), zero for a direction.
    "subs r3, r3, #4",
    "mvn lr, r3",
    xform_row_t2!(),
    xform_row_t2!(),
    xform_row_t2!(),
    "cmp r12, #4",
    "bne 3f",
    xform_row_t2!(),
    "3:",
    "pop {{r4, r5, r6, r7, r8, r9, r10, pc}}",
    ".size scanline3d_xform_q16, . - scanline3d_xform_q16",
);
