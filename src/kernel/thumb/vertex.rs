//! Thumb-1 assembly for the common case of an object's vertex loop with Q16.16 coordinates,
//! on ARMv6-M and on Thumb-2 cores (where the routines it calls are the Thumb-2 forms of
//! `xform_t2` and `project_t2`) (`kernel::project_run`): a run of vertices transformed
//! (`scanline3d_xform_q16`), given their outcode and projected (`scanline3d_project_q16`)
//! straight into the vertex store, without the loop's copies and checks in between.
//!
//! The routine stores exactly the records the renderer's vertex loop stores for those vertices
//! (the outcode with the guard band's saturated product, a zero record for a point to be
//! clipped or with w ≤ 0), and stops at the first vertex it does not handle, which the loop
//! then takes: a coordinate outside [−2³⁰, 2³⁰) (the transform's range), w = i32::MIN, and the
//! projection's own declines. The benchmark
//! scenes' hashes check it on every frame; the transform and the projection have their own
//! self-tests.
#![allow(unsafe_code)]

use crate::kernel::records::{
    ScreenVertex, BOTTOM, FAR, GUARD, LEFT, NEAR, NEEDS_CLIP, RIGHT, TOP,
};
use crate::kernel::wide::spread_bits;
use heapless::Vec;

/// The routine's argument block (`repr(C)`: it reads and updates the fields by offset).
#[repr(C)]
struct RunCtx {
    /// The next position (advanced by the routine) and the end of the run.
    pos: *const [i32; 3],
    end: *const [i32; 3],
    /// The model-view-projection matrix (16 words, row after row).
    m: *const i32,
    /// `sx | sy << 16` (8 × the viewport size) and the reciprocal's seed table.
    scales: u32,
    /// The guard band, an integer in 1..2¹⁵.
    gk: u32,
    seed: *const u16,
    /// The next record (advanced by the routine).
    out: *mut ScreenVertex,
    /// Scratch: the clip-space point and the screen words.
    clip: [i32; 4],
    words: [i32; 3],
}

/// Branches to label 12 when the clip-space word at byte `$k` of the scratch point (context
/// in r7) is i32::MIN or i32::MAX: then v ^ (v >> 31) is i32::MAX and adding 1 overflows.
/// Uses r1, r2.
#[cfg_attr(scanline3d_thumb2, allow(unused_macros))]
macro_rules! invalid_test {
    ($k:literal) => {
        concat!(
            "ldr r1, [r7, #{clip} + ",
            $k,
            "]\n",
            "asrs r2, r1, #31\n",
            "eors r2, r1\n",
            "adds r2, #1\n",
            "bvs 12f\n",
        )
    };
}

// Thumb-1; on Thumb-2 cores the Thumb-2 routine below.
#[cfg(not(scanline3d_thumb2))]
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_vertices_q16,\"ax\",%progbits",
    ".global scanline3d_vertices_q16",
    ".type scanline3d_vertices_q16,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = &mut RunCtx. Returns 0 (the run is done) or 1 (the vertex at `pos` is the loop's).
    // r4 = the position, r5 = the record, r7 = the context.
    "scanline3d_vertices_q16:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r7, r0",
    "ldr r4, [r7, #{pos}]",
    "ldr r5, [r7, #{out}]",
    "b 10f",
    "90:",
    "movs r0, #0",
    "b 99f",
    "91:",
    "movs r0, #1",
    "99:",
    "str r4, [r7, #{pos}]",
    "str r5, [r7, #{out}]",
    "pop {{r4, r5, r6, r7, pc}}",
    "10:",
    "ldr r0, [r7, #{end}]",
    "cmp r4, r0",
    "bhs 90b",
    // The point's coordinates in [−2³⁰, 2³⁰): v ^ (v >> 31) below 2³⁰ (the matrix was checked
    // for the run).
    "ldr r0, [r4, #0]",
    "asrs r3, r0, #31",
    "eors r0, r3",
    "ldr r1, [r4, #4]",
    "asrs r3, r1, #31",
    "eors r1, r3",
    "orrs r0, r1",
    "ldr r1, [r4, #8]",
    "asrs r3, r1, #31",
    "eors r1, r3",
    "orrs r0, r1",
    "lsrs r0, r0, #30",
    "bne 91b",
    // clip = m · (p, 1).
    "ldr r0, [r7, #{m}]",
    "mov r1, r4",
    "mov r2, r7",
    "adds r2, #{clip}",
    "movs r3, #4",
    "bl scanline3d_xform_q16",
    // The outcode (`clip::outcode`) in r0, w in r3; −w saturates only for w = i32::MIN,
    // which is the loop's.
    "ldr r3, [r7, #{clip} + 12]",
    "negs r6, r3",
    "bvs 91b",
    "movs r0, #0",
    "ldr r1, [r7, #{clip}]",
    "cmp r1, r6",
    "bge 1f",
    "adds r0, #{left}",
    "1:",
    "cmp r1, r3",
    "ble 1f",
    "adds r0, #{right}",
    "1:",
    "ldr r1, [r7, #{clip} + 4]",
    "cmp r1, r6",
    "bge 1f",
    "adds r0, #{bottom}",
    "1:",
    "cmp r1, r3",
    "ble 1f",
    "adds r0, #{top}",
    "1:",
    "ldr r1, [r7, #{clip} + 8]",
    "cmp r1, #0",
    "bge 1f",
    "adds r0, #{near}",
    "1:",
    "cmp r1, r3",
    "ble 1f",
    "adds r0, #{far}",
    "1:",
    // Outside an x/y plane: the guard band test with gw = sat(k·w) (g = k, an integer):
    // m = k·|w| from k·(|w| >> 16) and k·(|w| & 0xffff); m ≥ 2³¹ saturates.
    "lsls r1, r0, #28",
    "beq 4f",
    "asrs r1, r3, #31",
    "mov r6, r3",
    "eors r6, r1",
    "subs r6, r6, r1",
    "ldr r2, [r7, #{gk}]",
    "lsrs r1, r6, #16",
    "muls r1, r2, r1",
    "uxth r6, r6",
    "muls r6, r2, r6",
    "lsrs r2, r6, #16",
    "adds r2, r2, r1",
    "lsrs r2, r2, #15",
    "bne 5f",
    "lsls r1, r1, #16",
    "adds r6, r6, r1",
    // r6 = m (< 2³¹): gw = m for w ≥ 0, −m below.
    "cmp r3, #0",
    "bge 6f",
    "negs r6, r6",
    "b 6f",
    // Saturated: gw = i32::MAX for w ≥ 0, i32::MIN below.
    "5:",
    "movs r6, #1",
    "lsls r6, r6, #31",
    "cmp r3, #0",
    "blt 6f",
    "subs r6, #1",
    // r6 = gw, r2 = −gw (saturating: −i32::MIN = i32::MAX).
    "6:",
    "negs r2, r6",
    "bvc 7f",
    "subs r2, #1",
    "7:",
    "ldr r1, [r7, #{clip}]",
    "cmp r1, r2",
    "blt 8f",
    "cmp r1, r6",
    "bgt 8f",
    "ldr r1, [r7, #{clip} + 4]",
    "cmp r1, r2",
    "blt 8f",
    "cmp r1, r6",
    "ble 4f",
    "8:",
    "adds r0, #{guard}",
    // Invalid (a coordinate at i32::MIN or i32::MAX, as `Scalar::is_valid`): the outcode and
    // INVALID. Inside the planes only w can be (|x|, |y|, z ≤ w), else any coordinate.
    "4:",
    "mov r6, r0",
    "cmp r0, #0",
    "bne 11f",
    "adds r1, r3, #1",
    "bvs 12f",
    "b 13f",
    "11:",
    invalid_test!("0"),
    invalid_test!("4"),
    invalid_test!("8"),
    invalid_test!("12"),
    // To be clipped, or w ≤ 0 (no projection): a zero record with the flags.
    "movs r1, #{needs_clip}",
    "tst r0, r1",
    "bne 20f",
    "b 13f",
    "12:",
    "movs r1, #{invalid}",
    "orrs r6, r1",
    "b 20f",
    "13:",
    "cmp r3, #0",
    "ble 20f",
    // Projected: x, y, the depth (16.8) and no colour; flags = the outcode and PROJECTED.
    "mov r0, r7",
    "adds r0, #{clip}",
    "ldr r1, [r7, #{scales}]",
    "ldr r2, [r7, #{seed}]",
    "mov r3, r7",
    "adds r3, #{words}",
    "bl scanline3d_project_q16",
    "cmp r0, #0",
    "bne 1f",
    "b 91b",
    "1:",
    "ldr r0, [r7, #{words}]",
    "strh r0, [r5, #{vx}]",
    "ldr r0, [r7, #{words} + 4]",
    "strh r0, [r5, #{vy}]",
    "ldr r0, [r7, #{words} + 8]",
    "lsrs r1, r0, #8",
    "strh r1, [r5, #{vz}]",
    "strb r0, [r5, #{vzf}]",
    "movs r0, #0",
    "strb r0, [r5, #{vrgb}]",
    "strb r0, [r5, #{vrgb} + 1]",
    "strb r0, [r5, #{vrgb} + 2]",
    "movs r0, #1",
    "lsls r0, r0, #{projected_bit}",
    "orrs r0, r6",
    "strh r0, [r5, #{vflags}]",
    "b 30f",
    // To be clipped: a zero record with the outcode.
    "20:",
    "movs r0, #0",
    "strh r0, [r5, #{vx}]",
    "strh r0, [r5, #{vy}]",
    "strh r0, [r5, #{vz}]",
    "strb r0, [r5, #{vzf}]",
    "strb r0, [r5, #{vrgb}]",
    "strb r0, [r5, #{vrgb} + 1]",
    "strb r0, [r5, #{vrgb} + 2]",
    "strh r6, [r5, #{vflags}]",
    "30:",
    "adds r4, #12",
    "adds r5, #12",
    "b 10b",
    ".size scanline3d_vertices_q16, . - scanline3d_vertices_q16",
    pos = const core::mem::offset_of!(RunCtx, pos),
    end = const core::mem::offset_of!(RunCtx, end),
    m = const core::mem::offset_of!(RunCtx, m),
    scales = const core::mem::offset_of!(RunCtx, scales),
    seed = const core::mem::offset_of!(RunCtx, seed),
    out = const core::mem::offset_of!(RunCtx, out),
    clip = const core::mem::offset_of!(RunCtx, clip),
    words = const core::mem::offset_of!(RunCtx, words),
    vx = const core::mem::offset_of!(ScreenVertex, x),
    vy = const core::mem::offset_of!(ScreenVertex, y),
    vz = const core::mem::offset_of!(ScreenVertex, z),
    vzf = const core::mem::offset_of!(ScreenVertex, zf),
    vrgb = const crate::kernel::records::RGB_HI_OFFSET,
    vflags = const crate::kernel::records::FLAGS_OFFSET,
    left = const LEFT,
    right = const RIGHT,
    bottom = const BOTTOM,
    top = const TOP,
    near = const NEAR,
    far = const FAR,
    guard = const GUARD,
    needs_clip = const NEEDS_CLIP,
    invalid = const crate::kernel::records::INVALID,
    gk = const core::mem::offset_of!(RunCtx, gk),
    projected_bit = const crate::kernel::records::PROJECTED.trailing_zeros(),
);

/// Thumb-2 form of [`invalid_test`] for the clip-space word in `$r`: branches to label 12
/// when it is i32::MIN or i32::MAX. Uses r1.
#[cfg(scanline3d_thumb2)]
macro_rules! invalid_test_t2 {
    ($r:literal) => {
        concat!(
            "eor r1, ",
            $r,
            ", ",
            $r,
            ", asr #31\n",
            "adds r1, r1, #1\n",
            "bvs 12f\n",
        )
    };
}

// The Thumb-2 routine: the same records, outcodes and stops as the Thumb-1 one above, with
// the end in r8 and the clip-space point in r9–r11 and r3 after the transform, the outcode
// from `it` blocks, the guard band's product from one `umull` and each record stored as
// three words (`str`: the store is only 2-byte aligned, which `str` allows and `stm` does
// not).
#[cfg(scanline3d_thumb2)]
core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_vertices_q16,\"ax\",%progbits",
    ".global scanline3d_vertices_q16",
    ".type scanline3d_vertices_q16,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = &mut RunCtx. Returns 0 (the run is done) or 1 (the vertex at `pos` is the loop's).
    // r4 = the position, r5 = the record, r7 = the context, r8 = the end.
    "scanline3d_vertices_q16:",
    "push {{r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "sub sp, #4",
    "mov r7, r0",
    "ldr r4, [r7, #{pos}]",
    "ldr r5, [r7, #{out}]",
    "ldr r8, [r7, #{end}]",
    "b 10f",
    "90:",
    "movs r0, #0",
    "b 99f",
    "91:",
    "movs r0, #1",
    "99:",
    "str r4, [r7, #{pos}]",
    "str r5, [r7, #{out}]",
    "add sp, #4",
    "pop {{r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    "10:",
    "cmp r4, r8",
    "bhs 90b",
    // The point's coordinates in [−2³⁰, 2³⁰).
    "ldm r4, {{r0, r1, r2}}",
    "eor r0, r0, r0, asr #31",
    "eor r1, r1, r1, asr #31",
    "orrs r0, r0, r1",
    "eor r2, r2, r2, asr #31",
    "orrs r0, r0, r2",
    "lsrs r0, r0, #30",
    "bne 91b",
    // clip = m · (p, 1), then x, y, z, w in r9, r10, r11, r3.
    "ldr r0, [r7, #{m}]",
    "mov r1, r4",
    "add r2, r7, #{clip}",
    "movs r3, #4",
    "bl scanline3d_xform_q16",
    "ldrd r9, r10, [r7, #{clip}]",
    "ldrd r11, r3, [r7, #{clip} + 8]",
    // The outcode (`clip::outcode`) in r6; −w saturates only for w = i32::MIN: the loop's.
    "negs r12, r3",
    "bvs 91b",
    "movs r6, #0",
    "cmp r9, r12",
    "it lt",
    "orrlt r6, r6, #{left}",
    "cmp r9, r3",
    "it gt",
    "orrgt r6, r6, #{right}",
    "cmp r10, r12",
    "it lt",
    "orrlt r6, r6, #{bottom}",
    "cmp r10, r3",
    "it gt",
    "orrgt r6, r6, #{top}",
    "cmp r11, #0",
    "it lt",
    "orrlt r6, r6, #{near}",
    "cmp r11, r3",
    "it gt",
    "orrgt r6, r6, #{far}",
    // Outside an x/y plane: the guard band test with gw = sat(k·w) (g = k, an integer).
    "tst r6, #15",
    "beq 4f",
    "ldr r2, [r7, #{gk}]",
    "eor r1, r3, r3, asr #31",
    "sub r1, r1, r3, asr #31",
    "umull r1, r0, r1, r2",
    // m = k·|w| in r0:r1; m ≥ 2³¹ saturates.
    "cmp r0, #0",
    "bne 5f",
    "cmp r1, #0",
    "blt 5f",
    "cmp r3, #0",
    "it lt",
    "neglt r1, r1",
    "b 6f",
    // Saturated: gw = i32::MAX for w ≥ 0, i32::MIN below.
    "5:",
    "mov r1, #0x80000000",
    "cmp r3, #0",
    "it ge",
    "subge r1, r1, #1",
    // r1 = gw, r2 = −gw (saturating: −i32::MIN = i32::MAX).
    "6:",
    "negs r2, r1",
    "it vs",
    "subvs r2, r2, #1",
    "cmp r9, r2",
    "blt 8f",
    "cmp r9, r1",
    "bgt 8f",
    "cmp r10, r2",
    "blt 8f",
    "cmp r10, r1",
    "ble 4f",
    "8:",
    "orr r6, r6, #{guard}",
    // Invalid (a coordinate at i32::MIN or i32::MAX): inside the planes only w can be.
    "4:",
    "cmp r6, #0",
    "bne 11f",
    "adds r1, r3, #1",
    "bvs 12f",
    "b 13f",
    "11:",
    invalid_test_t2!("r9"),
    invalid_test_t2!("r10"),
    invalid_test_t2!("r11"),
    invalid_test_t2!("r3"),
    // To be clipped, or w ≤ 0 (no projection): a zero record with the flags.
    "tst r6, #{needs_clip}",
    "bne 20f",
    "b 13f",
    "12:",
    "orr r6, r6, #{invalid}",
    "b 20f",
    "13:",
    "cmp r3, #0",
    "ble 20f",
    // Projected: x | y << 16, z | zf << 16 (no colour), flags << 16 with PROJECTED.
    "add r0, r7, #{clip}",
    "ldr r1, [r7, #{scales}]",
    "ldr r2, [r7, #{seed}]",
    "add r3, r7, #{words}",
    "bl scanline3d_project_q16",
    "cmp r0, #0",
    "beq 91b",
    "add r0, r7, #{words}",
    "ldm r0, {{r0, r1, r2}}",
    "uxth r0, r0",
    "orr r0, r0, r1, lsl #16",
    "lsrs r1, r2, #8",
    "bfi r1, r2, #16, #8",
    "orr r2, r6, #{projected}",
    "lsls r2, r2, #16",
    "b 30f",
    // To be clipped: a zero record with the outcode.
    "20:",
    "movs r0, #0",
    "movs r1, #0",
    "lsls r2, r6, #16",
    "30:",
    "str r0, [r5, #0]",
    "str r1, [r5, #4]",
    "str r2, [r5, #8]",
    "adds r4, #12",
    "adds r5, #12",
    "b 10b",
    ".size scanline3d_vertices_q16, . - scanline3d_vertices_q16",
    pos = const core::mem::offset_of!(RunCtx, pos),
    end = const core::mem::offset_of!(RunCtx, end),
    m = const core::mem::offset_of!(RunCtx, m),
    scales = const core::mem::offset_of!(RunCtx, scales),
    seed = const core::mem::offset_of!(RunCtx, seed),
    out = const core::mem::offset_of!(RunCtx, out),
    clip = const core::mem::offset_of!(RunCtx, clip),
    words = const core::mem::offset_of!(RunCtx, words),
    gk = const core::mem::offset_of!(RunCtx, gk),
    left = const LEFT,
    right = const RIGHT,
    bottom = const BOTTOM,
    top = const TOP,
    near = const NEAR,
    far = const FAR,
    guard = const GUARD,
    needs_clip = const NEEDS_CLIP,
    invalid = const crate::kernel::records::INVALID,
    projected = const crate::kernel::records::PROJECTED,
);

// The Thumb-2 routine's record words: x, y, then z, zf, the three colour bytes and the flags,
// little-endian.
#[cfg(scanline3d_thumb2)]
const _: () = {
    assert!(core::mem::offset_of!(ScreenVertex, x) == 0);
    assert!(core::mem::offset_of!(ScreenVertex, y) == 2);
    assert!(core::mem::offset_of!(ScreenVertex, z) == 4);
    assert!(core::mem::offset_of!(ScreenVertex, zf) == 6);
    assert!(crate::kernel::records::RGB_HI_OFFSET == 7);
    assert!(crate::kernel::records::FLAGS_OFFSET == 10);
};

// `adds rN, #imm8` reaches the scratch words; a record is 12 bytes; the positions are three
// words.
const _: () = {
    assert!(core::mem::offset_of!(RunCtx, words) + 8 <= 124);
    assert!(core::mem::size_of::<ScreenVertex>() == 12);
};

// It calls `scanline3d_xform_q16` and `scanline3d_project_q16` (`xform`, `project`) itself.
extern "C" {
    fn scanline3d_vertices_q16(ctx: *mut RunCtx) -> u32;
}

/// `kernel::project_run` (Q16.16 words) on ARMv6-M: stores the records of the longest run of
/// `ps` (at most the store's room) that [`scanline3d_vertices_q16`] handles and returns its
/// length. Nothing when the guard band is not an integer of at least 1 (the renderer's is),
/// the scales are 2¹⁶ or more, or a matrix entry is outside [−2³⁰, 2³⁰).
#[inline(never)]
pub(crate) fn project_run<const V: usize>(
    m: &[[i32; 4]; 4],
    ps: &[[i32; 3]],
    g: i32,
    sx: u32,
    sy: u32,
    out: &mut Vec<ScreenVertex, V>,
) -> usize {
    let s = m.iter().flatten().fold(0, |s, &v| s | spread_bits(v));
    let gb = g;
    if gb < 1 << 16 || gb & 0xffff != 0 || (sx | sy) >> 16 != 0 || s >= 1 << 30 {
        return 0;
    }
    let n = ps.len().min(V - out.len());
    let run = ps[..n].as_ptr_range();
    let len = out.len();
    let seed: &'static [u16; 128] = &crate::kernel::wide::RECIP_SEED;
    let mut ctx = RunCtx {
        pos: run.start,
        end: run.end,
        m: m.as_ptr() as *const i32,
        scales: sx | sy << 16,
        gk: (gb >> 16) as u32,
        seed: seed.as_ptr(),
        // SAFETY: `len ≤ V`: one past the stored records, within or at the end of the buffer.
        out: unsafe { out.as_mut_ptr().add(len) },
        clip: [0; 4],
        words: [0; 3],
    };
    // SAFETY: the positions are three words each and the matrix 16 words. The routine reads positions in the run, the matrix
    // and the seed table, writes its scratch words and one 12-byte record per position it
    // passes, below the store's capacity (`n` ≤ the room), and each record completely.
    unsafe { scanline3d_vertices_q16(&mut ctx) };
    // SAFETY: the cursor stays within the run, at a whole position.
    let done = unsafe { ctx.pos.offset_from(run.start) } as usize;
    // SAFETY: the first `len + done` records are initialized (`done ≤ n ≤ V − len`).
    unsafe { out.set_len(len + done) };
    done
}
