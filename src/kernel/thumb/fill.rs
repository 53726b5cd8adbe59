//! The strip-line clear: 16 bytes a store.
#![allow(unsafe_code)]

extern "C" {
    fn scanline3d_fill128(start: *mut [u32; 4], end: *mut [u32; 4], word: u32);
}

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

/// Clears a strip line: colour `background` (an RGB565 word) and depth 65535.
#[inline(always)]
pub(crate) fn clear_line(colors: &mut [u16], depth: &mut [u16], background: u16) {
    fill16(colors, background);
    fill16(depth, u16::MAX);
}
