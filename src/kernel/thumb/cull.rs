//! Thumb assembly for the common cases of an object's triangle loop on Cortex-M
//! (`kernel::cull_push`; a Thumb-1 routine on ARMv6-M, a Thumb-2 one with the same results
//! on Thumb-2 cores): index checks, the flag
//! tests, the back-face test and, for a front face, its bounding box, the empty and off-screen
//! tests, its record and bucket counts, and the lighting marks of its unlit vertices.
//!
//! Why assembly: LLVM keeps the loop's vertex pointers, counters and the store's state on the
//! stack (eight low registers on ARMv6-M), with bounds checks and a call to `push_tri` per
//! front face. With this routine the default torus frame takes about 110 k fewer instructions
//! on a Cortex-M0 and 39 k fewer on a Cortex-M4F (`scripts/mcu-bench`, the lighting marks
//! included).
//!
//! The routine computes exactly what the portable `kernel::portable::cull_push` computes: the same
//! tests in the same order, the same stops, records, counts and marks, so the triangle store
//! (and so every image) is identical. The benchmark firmware compares the two on pseudo-random
//! objects before it measures (`selftest::cull`).
#![allow(unsafe_code)]

use crate::kernel::records::{
    Bins, CullCounts, CullStop, ScreenVertex, TriRecord, FLAGS_OFFSET, INVALID, LIT, NEEDS_CLIP,
    NEEDS_LIGHT,
};

/// The routine's argument block (`repr(C)`: it reads and updates the fields by offset).
#[repr(C)]
struct CullCtx {
    /// The triangle at the cursor (advanced by the routine).
    tri: *const [u16; 3],
    /// One past the last triangle.
    end: *const [u16; 3],
    /// The object's first vertex.
    verts: *mut ScreenVertex,
    /// The object's vertex count.
    n: u32,
    /// The triangle store's buffer, its length (updated) and its capacity.
    store: *mut TriRecord,
    len: u32,
    cap: u32,
    /// The per-row counts (at least `vh` entries each).
    heads: *mut u16,
    starts: *mut i16,
    vw: i32,
    vh: i32,
    /// The store index of the object's first vertex.
    base: u32,
    /// The counts and the count of triangles needed.
    stats: *mut CullCounts,
    needed: *mut usize,
}

/// Increments the [`CullCounts`] field at byte offset `$off` (the context in r7). Uses r0, r1.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! count {
    ($off:literal) => {
        concat!(
            "ldr r0, [r7, #{stats}]\n",
            "ldr r1, [r0, #{",
            $off,
            "}]\n",
            "adds r1, #1\n",
            "str r1, [r0, #{",
            $off,
            "}]\n"
        )
    };
}

/// `$p` = the object's vertex `$p` (an index < n) as an address, with the vertices at r4 and
/// 12 (their size) in r6.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! vertex_address {
    ($p:literal) => {
        concat!("muls ", $p, ", r6\n", "adds ", $p, ", r4, ", $p, "\n")
    };
}

/// `$lo` = min and `$hi` = max of `$lo`, `$hi`, `$c` (signed), then both through
/// `raster::first_pixel` ((v + 7) >> 4). Uses r0.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! pixel_range {
    ($lo:literal, $hi:literal, $c:literal) => {
        concat!(
            "cmp ", $lo, ", ", $hi, "\n", "ble 1f\n", "mov r0, ", $lo, "\n", "mov ", $lo, ", ",
            $hi, "\n", "mov ", $hi, ", r0\n", "1:\n", "cmp ", $c, ", ", $lo, "\n", "bge 2f\n",
            "mov ", $lo, ", ", $c, "\n", "b 3f\n", "2:\n", "cmp ", $c, ", ", $hi, "\n", "ble 3f\n",
            "mov ", $hi, ", ", $c, "\n", "3:\n", "adds ", $lo, ", #7\n", "asrs ", $lo, ", ", $lo,
            ", #4\n", "adds ", $hi, ", #7\n", "asrs ", $hi, ", ", $hi, ", #4\n",
        )
    };
}

/// Sets `NEEDS_LIGHT` (in r3) on the vertex of triangle r0's index at byte offset `$i`
/// (vertices at r6) unless it is lit. Uses r1, r2, r4.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! mark_unlit {
    ($i:literal) => {
        concat!(
            "ldrh r1, [r0, #",
            $i,
            "]\n",
            "lsls r2, r1, #1\n",
            "adds r1, r1, r2\n",
            "lsls r1, r1, #2\n",
            "adds r1, r6, r1\n",
            "ldrh r2, [r1, #{flags}]\n",
            "lsls r4, r2, #{lit_shift}\n",
            "bmi 1f\n",
            "orrs r2, r3\n",
            "strh r2, [r1, #{flags}]\n",
            "1:\n",
        )
    };
}

// Thumb-1; on Thumb-2 cores the Thumb-2 routine below.
#[cfg(not(scanline3d_thumb2))]
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_cull_push,\"ax\",%progbits",
    ".global scanline3d_cull_push",
    ".type scanline3d_cull_push,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = &mut CullCtx. Returns 0 (done) or 1 (the triangle at the cursor needs the full
    // path). r7 = the context throughout, r8 = the AND of the three vertices' flags.
    "scanline3d_cull_push:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r4, r8",
    "push {{r4}}",
    "mov r7, r0",
    "ldr r0, [r7, #{tri}]",
    "b 10f",
    // The next triangle.
    "20:",
    "ldr r0, [r7, #{tri}]",
    "adds r0, #6",
    "str r0, [r7, #{tri}]",
    "10:",
    "ldr r1, [r7, #{end}]",
    "cmp r0, r1",
    "bhs 90f",
    // Indices below n, else the full path.
    "ldrh r1, [r0, #0]",
    "ldrh r2, [r0, #2]",
    "ldrh r3, [r0, #4]",
    "ldr r4, [r7, #{n}]",
    "cmp r1, r4",
    "bhs 91f",
    "cmp r2, r4",
    "bhs 91f",
    "cmp r3, r4",
    "bhs 91f",
    "ldr r4, [r7, #{verts}]",
    "movs r6, #12",
    vertex_address!("r1"),
    vertex_address!("r2"),
    vertex_address!("r3"),
    "ldrh r4, [r1, #{flags}]",
    "ldrh r5, [r2, #{flags}]",
    "ldrh r6, [r3, #{flags}]",
    // Any vertex invalid or needing the clipper (bits 4..=7): the full path.
    "mov r0, r4",
    "orrs r0, r5",
    "orrs r0, r6",
    "lsls r0, r0, #24",
    "lsrs r0, r0, #28",
    "bne 91f",
    // All three outside one plane (a common outcode bit 0..=5): outside.
    "ands r4, r5",
    "ands r4, r6",
    "lsls r0, r4, #26",
    "bne 30f",
    "mov r8, r4",
    // Twice the signed area from the words y·2¹⁶ + x (`cull::signed_area2`; coordinates
    // within ±(2¹⁴ − 1), so the halves of a word difference are exact):
    // (cx − ax)·(by − ay) − (bx − ax)·(cy − ay).
    "ldr r1, [r1]",
    "ldr r2, [r2]",
    "ldr r3, [r3]",
    "asrs r4, r1, #16",
    "asrs r5, r2, #16",
    "subs r5, r5, r4",
    "asrs r6, r3, #16",
    "subs r6, r6, r4",
    "subs r0, r3, r1",
    "sxth r0, r0",
    "muls r5, r0, r5",
    "subs r0, r2, r1",
    "sxth r0, r0",
    "muls r6, r0, r6",
    "subs r5, r5, r6",
    "bgt 50f",
    "beq 31f",
    count!("culled"),
    "b 20b",
    "31:",
    count!("degenerate"),
    "b 20b",
    "30:",
    count!("outside"),
    "b 20b",
    "40:",
    count!("empty"),
    "b 20b",
    "90:",
    "movs r0, #0",
    "b 99f",
    "91:",
    "movs r0, #1",
    "99:",
    "pop {{r4}}",
    "mov r8, r4",
    "pop {{r4, r5, r6, r7, pc}}",
    // A front face: `Bins::push`: x range r4..r5, then y range r1..r2 in pixels.
    "50:",
    "sxth r4, r1",
    "sxth r5, r2",
    "sxth r6, r3",
    pixel_range!("r4", "r5", "r6"),
    "cmp r4, r5",
    "bge 40b",
    "asrs r1, r1, #16",
    "asrs r2, r2, #16",
    "asrs r3, r3, #16",
    pixel_range!("r1", "r2", "r3"),
    "cmp r1, r2",
    "bge 40b",
    "cmp r5, #0",
    "ble 30b",
    "cmp r2, #0",
    "ble 30b",
    "ldr r0, [r7, #{vw}]",
    "cmp r4, r0",
    "bge 30b",
    "ldr r3, [r7, #{vh}]",
    "cmp r1, r3",
    "bge 30b",
    "ldr r0, [r7, #{needed}]",
    "ldr r4, [r0]",
    "adds r4, #1",
    "str r4, [r0]",
    // r1 = the bucket row max(py0, 0), r2 = the end row min(py1, vh).
    "cmp r1, #0",
    "bge 1f",
    "movs r1, #0",
    "1:",
    "cmp r2, r3",
    "ble 1f",
    "mov r2, r3",
    "1:",
    // A full store: counted as needed only.
    "ldr r4, [r7, #{len}]",
    "ldr r5, [r7, #{cap}]",
    "cmp r4, r5",
    "blo 1f",
    "b 60f",
    "1:",
    // The record (store indices base + i) at store + 6·len.
    "lsls r5, r4, #1",
    "adds r5, r5, r4",
    "lsls r5, r5, #1",
    "ldr r6, [r7, #{store}]",
    "adds r6, r6, r5",
    "adds r4, #1",
    "str r4, [r7, #{len}]",
    "ldr r0, [r7, #{tri}]",
    "ldr r5, [r7, #{base}]",
    "ldrh r4, [r0, #0]",
    "adds r4, r4, r5",
    "strh r4, [r6, #0]",
    "ldrh r4, [r0, #2]",
    "adds r4, r4, r5",
    "strh r4, [r6, #2]",
    "ldrh r4, [r0, #4]",
    "adds r4, r4, r5",
    "strh r4, [r6, #4]",
    // heads[row] += 1, starts[row] += 1, and starts[end] −= 1 when end < vh.
    "lsls r1, r1, #1",
    "ldr r4, [r7, #{heads}]",
    "ldrh r5, [r4, r1]",
    "adds r5, #1",
    "strh r5, [r4, r1]",
    "ldr r4, [r7, #{starts}]",
    "ldrh r5, [r4, r1]",
    "adds r5, #1",
    "strh r5, [r4, r1]",
    "cmp r2, r3",
    "bge 1f",
    "lsls r2, r2, #1",
    "ldrh r5, [r4, r2]",
    "subs r5, #1",
    "strh r5, [r4, r2]",
    "1:",
    count!("drawn"),
    // The unlit vertices of a stored (or needed) front face: marked NEEDS_LIGHT.
    "60:",
    "mov r0, r8",
    "lsls r0, r0, #{lit_shift}",
    "bmi 2f",
    "ldr r0, [r7, #{tri}]",
    "ldr r6, [r7, #{verts}]",
    "movs r3, #1",
    "lsls r3, r3, #{needs_light_bit}",
    mark_unlit!("0"),
    mark_unlit!("2"),
    mark_unlit!("4"),
    "2:",
    "b 20b",
    ".size scanline3d_cull_push, . - scanline3d_cull_push",
    tri = const core::mem::offset_of!(CullCtx, tri),
    end = const core::mem::offset_of!(CullCtx, end),
    verts = const core::mem::offset_of!(CullCtx, verts),
    n = const core::mem::offset_of!(CullCtx, n),
    store = const core::mem::offset_of!(CullCtx, store),
    len = const core::mem::offset_of!(CullCtx, len),
    cap = const core::mem::offset_of!(CullCtx, cap),
    heads = const core::mem::offset_of!(CullCtx, heads),
    starts = const core::mem::offset_of!(CullCtx, starts),
    vw = const core::mem::offset_of!(CullCtx, vw),
    vh = const core::mem::offset_of!(CullCtx, vh),
    base = const core::mem::offset_of!(CullCtx, base),
    stats = const core::mem::offset_of!(CullCtx, stats),
    needed = const core::mem::offset_of!(CullCtx, needed),
    outside = const core::mem::offset_of!(CullCounts, outside),
    culled = const core::mem::offset_of!(CullCounts, culled),
    degenerate = const core::mem::offset_of!(CullCounts, degenerate),
    empty = const core::mem::offset_of!(CullCounts, empty),
    drawn = const core::mem::offset_of!(CullCounts, drawn),
    flags = const FLAGS_OFFSET,
    lit_shift = const 31 - LIT.trailing_zeros(),
    needs_light_bit = const NEEDS_LIGHT.trailing_zeros(),
);

/// Thumb-2 form of [`count`]: increments the [`CullCounts`] field at byte offset `$off`.
/// Uses r12, lr.
#[cfg(scanline3d_thumb2)]
macro_rules! count_t2 {
    ($off:literal) => {
        concat!(
            "ldr r12, [r7, #{stats}]\n",
            "ldr lr, [r12, #{",
            $off,
            "}]\n",
            "add lr, lr, #1\n",
            "str lr, [r12, #{",
            $off,
            "}]\n",
        )
    };
}

/// Thumb-2 form of [`vertex_address`]: `$p` = the address of vertex `$p` (vertices at r10).
#[cfg(scanline3d_thumb2)]
macro_rules! vertex_address_t2 {
    ($p:literal) => {
        concat!(
            "add ",
            $p,
            ", ",
            $p,
            ", ",
            $p,
            ", lsl #1\n",
            "add ",
            $p,
            ", r10, ",
            $p,
            ", lsl #2\n",
        )
    };
}

/// Thumb-2 form of [`pixel_range`] (`it` blocks instead of branches). Uses r12.
#[cfg(scanline3d_thumb2)]
macro_rules! pixel_range_t2 {
    ($lo:literal, $hi:literal, $c:literal) => {
        concat!(
            "cmp ",
            $lo,
            ", ",
            $hi,
            "\n",
            "ittt gt\n",
            "movgt r12, ",
            $lo,
            "\n",
            "movgt ",
            $lo,
            ", ",
            $hi,
            "\n",
            "movgt ",
            $hi,
            ", r12\n",
            "cmp ",
            $c,
            ", ",
            $lo,
            "\n",
            "it lt\n",
            "movlt ",
            $lo,
            ", ",
            $c,
            "\n",
            "cmp ",
            $c,
            ", ",
            $hi,
            "\n",
            "it gt\n",
            "movgt ",
            $hi,
            ", ",
            $c,
            "\n",
            "adds ",
            $lo,
            ", #7\n",
            "asrs ",
            $lo,
            ", ",
            $lo,
            ", #4\n",
            "adds ",
            $hi,
            ", #7\n",
            "asrs ",
            $hi,
            ", ",
            $hi,
            ", #4\n",
        )
    };
}

/// Thumb-2 form of [`mark_unlit`] (triangle in r0, vertices at r10, `NEEDS_LIGHT` in r3).
/// Uses r1, r2.
#[cfg(scanline3d_thumb2)]
macro_rules! mark_unlit_t2 {
    ($i:literal) => {
        concat!(
            "ldrh r1, [r0, #",
            $i,
            "]\n",
            "add r1, r1, r1, lsl #1\n",
            "add r1, r10, r1, lsl #2\n",
            "ldrh r2, [r1, #{flags}]\n",
            "tst r2, #{lit}\n",
            "itt eq\n",
            "orreq r2, r2, r3\n",
            "strheq r2, [r1, #{flags}]\n",
        )
    };
}

// The Thumb-2 routine: the same tests, stops, records, counts and marks as the Thumb-1 one
// above, with the cursor, the end, the vertex count and the vertices in registers, the
// vertex addresses and row counts from shifted operands and the ranges from `it` blocks.
// r0 = the cursor, r7 = the context, r8 = the AND of the three vertices' flags, r9 = n,
// r10 = the vertices, r11 = the end.
#[cfg(scanline3d_thumb2)]
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_cull_push,\"ax\",%progbits",
    ".global scanline3d_cull_push",
    ".type scanline3d_cull_push,%function",
    ".p2align 2",
    ".thumb_func",
    "scanline3d_cull_push:",
    "push {{r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "mov r7, r0",
    "ldr r0, [r7, #{tri}]",
    "ldr r11, [r7, #{end}]",
    "ldr r10, [r7, #{verts}]",
    "ldr r9, [r7, #{n}]",
    "b 10f",
    "20:",
    "adds r0, #6",
    "10:",
    "cmp r0, r11",
    "bhs 90f",
    "ldrh r1, [r0, #0]",
    "ldrh r2, [r0, #2]",
    "ldrh r3, [r0, #4]",
    "cmp r1, r9",
    "bhs 91f",
    "cmp r2, r9",
    "bhs 91f",
    "cmp r3, r9",
    "bhs 91f",
    vertex_address_t2!("r1"),
    vertex_address_t2!("r2"),
    vertex_address_t2!("r3"),
    "ldrh r4, [r1, #{flags}]",
    "ldrh r5, [r2, #{flags}]",
    "ldrh r6, [r3, #{flags}]",
    "orr r12, r4, r5",
    "orr r12, r12, r6",
    "tst r12, #0xf0",
    "bne 91f",
    "ands r4, r4, r5",
    "ands r4, r4, r6",
    "tst r4, #0x3f",
    "bne 30f",
    "mov r8, r4",
    "ldr r1, [r1]",
    "ldr r2, [r2]",
    "ldr r3, [r3]",
    "asrs r4, r1, #16",
    "rsb r5, r4, r2, asr #16",
    "rsb r6, r4, r3, asr #16",
    "subs r12, r3, r1",
    "sxth r12, r12",
    "mul r5, r12, r5",
    "subs r12, r2, r1",
    "sxth r12, r12",
    "mul r6, r12, r6",
    "subs r5, r5, r6",
    "bgt 50f",
    "beq 31f",
    count_t2!("culled"),
    "b 20b",
    "31:",
    count_t2!("degenerate"),
    "b 20b",
    "30:",
    count_t2!("outside"),
    "b 20b",
    "40:",
    count_t2!("empty"),
    "b 20b",
    "90:",
    "movs r1, #0",
    "b 99f",
    "91:",
    "movs r1, #1",
    "99:",
    "str r0, [r7, #{tri}]",
    "mov r0, r1",
    "pop {{r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    // A front face: `Bins::push`.
    "50:",
    "sxth r4, r1",
    "sxth r5, r2",
    "sxth r6, r3",
    pixel_range_t2!("r4", "r5", "r6"),
    "cmp r4, r5",
    "bge 40b",
    "asrs r1, r1, #16",
    "asrs r2, r2, #16",
    "asrs r3, r3, #16",
    pixel_range_t2!("r1", "r2", "r3"),
    "cmp r1, r2",
    "bge 40b",
    "cmp r5, #0",
    "ble 30b",
    "cmp r2, #0",
    "ble 30b",
    "ldr r12, [r7, #{vw}]",
    "cmp r4, r12",
    "bge 30b",
    "ldr r3, [r7, #{vh}]",
    "cmp r1, r3",
    "bge 30b",
    "ldr r12, [r7, #{needed}]",
    "ldr r4, [r12]",
    "adds r4, #1",
    "str r4, [r12]",
    // r1 = the bucket row max(py0, 0), r2 = the end row min(py1, vh).
    "bic r1, r1, r1, asr #31",
    "cmp r2, r3",
    "it gt",
    "movgt r2, r3",
    // A full store: counted as needed only.
    "ldr r4, [r7, #{len}]",
    "ldr r5, [r7, #{cap}]",
    "cmp r4, r5",
    "bhs 60f",
    "add r5, r4, r4, lsl #1",
    "ldr r6, [r7, #{store}]",
    "add r6, r6, r5, lsl #1",
    "adds r4, #1",
    "str r4, [r7, #{len}]",
    "ldr r5, [r7, #{base}]",
    "ldrh r4, [r0, #0]",
    "add r4, r4, r5",
    "strh r4, [r6, #0]",
    "ldrh r4, [r0, #2]",
    "add r4, r4, r5",
    "strh r4, [r6, #2]",
    "ldrh r4, [r0, #4]",
    "add r4, r4, r5",
    "strh r4, [r6, #4]",
    "ldr r4, [r7, #{heads}]",
    "ldrh r5, [r4, r1, lsl #1]",
    "adds r5, #1",
    "strh r5, [r4, r1, lsl #1]",
    "ldr r4, [r7, #{starts}]",
    "ldrh r5, [r4, r1, lsl #1]",
    "adds r5, #1",
    "strh r5, [r4, r1, lsl #1]",
    "cmp r2, r3",
    "bge 1f",
    "ldrh r5, [r4, r2, lsl #1]",
    "subs r5, #1",
    "strh r5, [r4, r2, lsl #1]",
    "1:",
    count_t2!("drawn"),
    "60:",
    "tst r8, #{lit}",
    "bne 20b",
    "mov r3, #{needs_light}",
    mark_unlit_t2!("0"),
    mark_unlit_t2!("2"),
    mark_unlit_t2!("4"),
    "b 20b",
    ".size scanline3d_cull_push, . - scanline3d_cull_push",
    tri = const core::mem::offset_of!(CullCtx, tri),
    end = const core::mem::offset_of!(CullCtx, end),
    verts = const core::mem::offset_of!(CullCtx, verts),
    n = const core::mem::offset_of!(CullCtx, n),
    store = const core::mem::offset_of!(CullCtx, store),
    len = const core::mem::offset_of!(CullCtx, len),
    cap = const core::mem::offset_of!(CullCtx, cap),
    heads = const core::mem::offset_of!(CullCtx, heads),
    starts = const core::mem::offset_of!(CullCtx, starts),
    vw = const core::mem::offset_of!(CullCtx, vw),
    vh = const core::mem::offset_of!(CullCtx, vh),
    base = const core::mem::offset_of!(CullCtx, base),
    stats = const core::mem::offset_of!(CullCtx, stats),
    needed = const core::mem::offset_of!(CullCtx, needed),
    outside = const core::mem::offset_of!(CullCounts, outside),
    culled = const core::mem::offset_of!(CullCounts, culled),
    degenerate = const core::mem::offset_of!(CullCounts, degenerate),
    empty = const core::mem::offset_of!(CullCounts, empty),
    drawn = const core::mem::offset_of!(CullCounts, drawn),
    flags = const FLAGS_OFFSET,
    lit = const LIT,
    needs_light = const NEEDS_LIGHT,
);

// The flag tests above: invalid and the clipper's planes are bits 4..=7, the outcode bits
// 0..=5; a record is three 16-bit indices; x and y are a vertex's first word.
const _: () = {
    assert!(INVALID as u32 | NEEDS_CLIP as u32 == 0xf0);
    assert!(core::mem::size_of::<TriRecord>() == 6 && core::mem::size_of::<ScreenVertex>() == 12);
    assert!(core::mem::offset_of!(ScreenVertex, x) == 0);
    assert!(core::mem::offset_of!(ScreenVertex, y) == 2);
    assert!(FLAGS_OFFSET <= 62 && FLAGS_OFFSET % 2 == 0);
    assert!(core::mem::size_of::<CullCtx>() <= 124 && core::mem::size_of::<CullCounts>() <= 124);
};

extern "C" {
    fn scanline3d_cull_push(ctx: *mut CullCtx) -> u32;
}

/// `kernel::cull_push` by [`scanline3d_cull_push`]; the same arguments and results as the
/// portable twin.
#[inline(always)]
pub(crate) fn cull_push<const T: usize>(
    tris: &[[u16; 3]],
    k: &mut usize,
    verts: &mut [ScreenVertex],
    base: u16,
    bins: Bins<'_, T>,
    stats: &mut CullCounts,
    needed: &mut usize,
) -> CullStop {
    let Some(rest) = tris.get(*k..) else {
        return CullStop::Done;
    };
    // The routine indexes the counts by rows below vh and by vh itself only through `end <
    // vh`: both within the slices.
    let vh = bins.view.1.min(bins.heads.len()).min(bins.starts.len());
    let range = rest.as_ptr_range();
    let mut ctx = CullCtx {
        tri: range.start,
        end: range.end,
        verts: verts.as_mut_ptr(),
        n: verts.len() as u32,
        store: bins.store.as_mut_ptr(),
        len: bins.store.len() as u32,
        cap: T as u32,
        heads: bins.heads.as_mut_ptr(),
        starts: bins.starts.as_mut_ptr(),
        vw: bins.view.0 as i32,
        vh: vh as i32,
        base: base as u32,
        stats,
        needed,
    };
    // SAFETY: the routine reads triangles in `rest`, vertices whose indices it checked against
    // `verts.len()`, writes records below the store's capacity (and only then raises the
    // length, which is what `set_len` gets), and counts at rows below `vh`, in the five
    // `CullCounts` fields and in `needed`.
    let r = unsafe { scanline3d_cull_push(&mut ctx) };
    unsafe { bins.store.set_len(ctx.len as usize) };
    // SAFETY: the cursor stays within `rest` (or at its end), at a whole triangle.
    *k += unsafe { ctx.tri.offset_from(range.start) } as usize;
    if r == 0 {
        CullStop::Done
    } else {
        CullStop::Portable
    }
}
