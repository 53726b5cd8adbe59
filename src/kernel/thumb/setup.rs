//! The whole setup of a fast Gouraud triangle with RGB565 channels on ARMv6-M: sorting,
//! edges, the record, the attribute words (`scanline3d_gouraud_setup`) and, while dithering,
//! the dither check (`scanline3d_dither_fits565`).
#![allow(unsafe_code)]
#![cfg_attr(scanline3d_thumb2, allow(unused_macros, unused_imports))]

use super::offsets as o;
use crate::kernel::records::{ActiveTri, ScreenVertex};
use crate::kernel::Setup565;

extern "C" {
    fn scanline3d_setup565(rec: *mut ActiveTri, args: *const SetupArgs) -> u32;
}

// The Thumb-1 form (ARMv6-M); Thumb-2 cores assemble `setup_t2`'s.
#[cfg(not(scanline3d_thumb2))]
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

/// The arguments of [`scanline3d_setup565`] (seven words).
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

/// `raster::ActiveTri::setup` by [`scanline3d_setup565`] for a Gouraud triangle on a strip
/// whose mode is fast Gouraud (`DepthTest::Less`) with RGB565 channels, and with `dither` the
/// check of `raster::ActiveTri::setup_dither` too ([`scanline3d_dither_fits565`]): what it
/// did, or `None` (the record unspecified) for what the portable setup handles.
#[inline(always)]
pub(crate) fn setup565(
    rec: &mut ActiveTri,
    t: &crate::kernel::records::TriRecord,
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
    let seed: &'static [u16; 128] = &crate::kernel::wide::RECIP_SEED;
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
