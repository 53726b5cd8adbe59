//! Thumb assembly for the common case of the lighting pass with Q16.16 values
//! (`kernel::light_run`), on ARMv6-M and, with Thumb-2 forms of its products (`smlal`, about
//! 105 instructions a lit vertex), on Thumb-2 cores: the vertices the triangle loop marked
//! (`NEEDS_LIGHT`), lit in the object's space by one grey directional light without a specular term, for RGB565
//! channels — what the pass computes for them (`shade::lit_diffuse`, `color::scale_channels`,
//! `project::pack_channels`), stored with the `LIT` flag as the pass stores it.
//!
//! Per vertex: the dot product N·L, the diffuse term `round(round(diffuse·N·L)·frac)`, the
//! ambient sum, and for each channel the clamped, rounded 8.8 value (`Scalar::lit_channel`),
//! its scaling to 0..=31 or 0..=63 (`color::scale_channels`) and its vertex format
//! (`project::pack_channels`), all in 32-bit arithmetic: it takes only the values for which
//! that arithmetic is exact (the same condition as `scalar::mul_q16_small` and
//! `scalar::dot3_q16_small`: normal components below 2²², products' factors below 2²³, an
//! ambient sum that does not saturate, a lit value below 2²³) and stops at any other vertex,
//! which the pass then lights itself. The benchmark firmware checks it against the portable
//! pass on 5 000 pseudo-random objects (`renderer::light_self_test`).
#![allow(unsafe_code)]

use crate::kernel::records::{ScreenVertex, FLAG_MASK, LIT, NEEDS_LIGHT};
use crate::kernel::wide::spread_bits;

/// The routine's argument block (`repr(C)`: it reads and updates the fields by offset). The
/// constant factors are split into 16-bit halves, the low one unsigned, the high one signed.
#[repr(C)]
struct LightCtx {
    /// The next vertex record (advanced by the routine) and the end of the run.
    v: *mut ScreenVertex,
    end: *mut ScreenVertex,
    /// The next normal (advanced with the record).
    n: *const [i32; 3],
    /// The material's colour (the fourth byte unused).
    color: [u8; 4],
    /// The light's direction in the object's space (components below 2²²).
    dir_lo: [u32; 3],
    dir_hi: [i32; 3],
    /// The material's diffuse coefficient and the light's colour fraction (below 2²³).
    diffuse_lo: u32,
    diffuse_hi: i32,
    frac_lo: u32,
    frac_hi: i32,
    /// The material's ambient coefficient (any value).
    ambient: i32,
    /// The direction, the diffuse coefficient and the colour fraction as whole words, for
    /// the Thumb-2 forms (`smlal`).
    dir: [i32; 3],
    diffuse: i32,
    frac: i32,
}

/// One component of the dot product N·L (the normal's component in r3, the direction's
/// halves at `$k` bytes into `dir_lo`/`dir_hi`): the low product's upper half is added to r6
/// and its lower half to ip (summed apart, so no carry is lost: see
/// `scalar::dot3_q16_small`), the cross products and the high product (shifted) to r6.
/// Uses r0–r5.
#[cfg(not(scanline3d_thumb2))]
macro_rules! dot_term {
    ($k:literal) => {
        concat!(
            "uxth r2, r3\n",
            "asrs r3, r3, #16\n",
            "ldr r1, [r7, #{dir_lo} + ",
            $k,
            "]\n",
            "ldr r0, [r7, #{dir_hi} + ",
            $k,
            "]\n",
            "movs r4, r2\n",
            "muls r4, r1\n",
            "lsrs r5, r4, #16\n",
            "adds r6, r6, r5\n",
            "uxth r4, r4\n",
            "add ip, r4\n",
            "muls r2, r0\n",
            "muls r1, r3\n",
            "muls r3, r0\n",
            "lsls r3, r3, #16\n",
            "adds r6, r6, r2\n",
            "adds r6, r6, r1\n",
            "adds r6, r6, r3\n",
        )
    };
}

/// r6 = `(a·r6 + 2¹⁵) >> 16` for the constant `a` whose halves are at `$lo`/`$hi` (both
/// factors below 2²³ in magnitude: `scalar::mul_q16_small`). The low product plus 2¹⁵
/// stays below 2³². Uses r0–r4.
#[cfg(not(scanline3d_thumb2))]
macro_rules! mul_q16 {
    ($lo:literal, $hi:literal, $w:literal) => {
        concat!(
            "@ whole word at ",
            $w,
            ", unused here\n",
            "uxth r1, r6\n",
            "asrs r0, r6, #16\n",
            "ldr r2, [r7, #",
            $lo,
            "]\n",
            "ldr r3, [r7, #",
            $hi,
            "]\n",
            "movs r4, r2\n",
            "muls r4, r1\n",
            "movs r6, #1\n",
            "lsls r6, r6, #15\n",
            "adds r4, r4, r6\n",
            "lsrs r6, r4, #16\n",
            "muls r2, r0\n",
            "muls r1, r3\n",
            "muls r3, r0\n",
            "lsls r3, r3, #16\n",
            "adds r6, r6, r2\n",
            "adds r6, r6, r1\n",
            "adds r6, r6, r3\n",
        )
    };
}

/// Channel `$k` (byte `$k` of `color`) of the lit value s in r5 (0 < s < 2²³) into
/// `$out`: `x = lit_channel(s, colour)` (the product below 2³¹, clamped to 255·2¹⁶, rounded to
/// 8.8), `y = (x·$max + 127) / 255` (`color::div255`'s shifts and adds: the dividend is below
/// 2²⁴) and the vertex format `(y + $half) >> $shift` (`pack_channels`; its upper limit,
/// 992 or 1008, is what x = 65280 gives, so it never clamps). Uses r0, r1.
#[cfg(not(scanline3d_thumb2))]
macro_rules! channel {
    ($k:literal, $max:literal, $half:literal, $shift:literal, $out:literal) => {
        concat!(
            "ldrb r0, [r7, #{color} + ",
            $k,
            "]\n",
            "muls r0, r5\n",
            "movs r1, #255\n",
            "lsls r1, r1, #16\n",
            "cmp r0, r1\n",
            "ble 1f\n",
            "mov r0, r1\n",
            "1:\n",
            "adds r0, #128\n",
            "lsrs r0, r0, #8\n",
            "movs r1, #",
            $max,
            "\n",
            "muls r0, r1\n",
            "adds r0, #127\n",
            "lsrs r1, r0, #8\n",
            "adds r1, r1, r0\n",
            "adds r1, #1\n",
            "lsrs r1, r1, #8\n",
            "adds r0, r0, r1\n",
            "adds r0, #1\n",
            "lsrs r0, r0, #8\n",
            "adds r0, #",
            $half,
            "\n",
            "lsrs ",
            $out,
            ", r0, #",
            $shift,
            "\n",
        )
    };
}

/// N·L into r6 (`dot3_q16_small`) for the normal in r3–r5: r6 and ip accumulate, ip from
/// the rounding's 2¹⁵. Uses r0–r5, r8, r9.
#[cfg(not(scanline3d_thumb2))]
macro_rules! dot3 {
    () => {
        concat!(
            "@ whole words at {dir}, unused here\n",
            "mov r8, r4\n",
            "mov r9, r5\n",
            "movs r6, #0\n",
            "movs r0, #1\n",
            "lsls r0, r0, #15\n",
            "mov ip, r0\n",
            dot_term!("0"),
            "mov r3, r8\n",
            dot_term!("4"),
            "mov r3, r9\n",
            dot_term!("8"),
            "mov r0, ip\n",
            "lsrs r0, r0, #16\n",
            "adds r6, r6, r0\n",
        )
    };
}

/// Thumb-2 form of [`dot3`] (the direction's whole words at `dir`): `dot3_q16_small`'s
/// `(Σ n·d + 2¹⁵) >> 16` from three `smlal` into r6 (the sum is far inside 64 bits). Uses
/// r0, r1.
#[cfg(scanline3d_thumb2)]
macro_rules! dot3 {
    () => {
        concat!(
            "@ halves at {dir_lo} and {dir_hi}, unused here\n",
            "ldr r0, [r7, #{dir}]\n",
            "mov r6, #0x8000\n",
            "movs r1, #0\n",
            "smlal r6, r1, r3, r0\n",
            "ldr r0, [r7, #{dir} + 4]\n",
            "smlal r6, r1, r4, r0\n",
            "ldr r0, [r7, #{dir} + 8]\n",
            "smlal r6, r1, r5, r0\n",
            "lsrs r6, r6, #16\n",
            "orr r6, r6, r1, lsl #16\n",
        )
    };
}

/// Thumb-2 form of [`mul_q16`]: r6 = `(a·r6 + 2¹⁵) >> 16` for the whole word `a` at `$w`
/// (`scalar::mul_q16_small`, one `smlal`; the halves `$lo`, `$hi` are the Thumb-1 form's).
/// Uses r0–r2.
#[cfg(scanline3d_thumb2)]
macro_rules! mul_q16 {
    ($lo:literal, $hi:literal, $w:literal) => {
        concat!(
            "@ halves at ",
            $lo,
            " and ",
            $hi,
            ", unused here\n",
            "ldr r2, [r7, #",
            $w,
            "]\n",
            "mov r0, #0x8000\n",
            "movs r1, #0\n",
            "smlal r0, r1, r6, r2\n",
            "lsrs r6, r0, #16\n",
            "orr r6, r6, r1, lsl #16\n",
        )
    };
}

/// Thumb-2 form of [`channel`]: the same values, the clamp by an `it` block and the
/// division's shifted adds as shifted operands.
#[cfg(scanline3d_thumb2)]
macro_rules! channel {
    ($k:literal, $max:literal, $half:literal, $shift:literal, $out:literal) => {
        concat!(
            "ldrb r0, [r7, #{color} + ",
            $k,
            "]\n",
            "muls r0, r5, r0\n",
            "cmp r0, #0xff0000\n",
            "it gt\n",
            "movgt r0, #0xff0000\n",
            "adds r0, #128\n",
            "lsrs r0, r0, #8\n",
            "movs r1, #",
            $max,
            "\n",
            "muls r0, r1, r0\n",
            "adds r0, #127\n",
            "add r1, r0, r0, lsr #8\n",
            "adds r1, #1\n",
            "add r0, r0, r1, lsr #8\n",
            "adds r0, #1\n",
            "lsrs r0, r0, #8\n",
            "adds r0, #",
            $half,
            "\n",
            "lsrs ",
            $out,
            ", r0, #",
            $shift,
            "\n",
        )
    };
}

core::arch::global_asm!(
    ".syntax unified",
    ".thumb",
    ".section .text.scanline3d_light565,\"ax\",%progbits",
    ".global scanline3d_light565",
    ".type scanline3d_light565,%function",
    ".p2align 2",
    ".thumb_func",
    // r0 = &mut LightCtx. Returns 0 (the run is done) or 1 (the vertex at `v` is the pass's).
    // r7 = the context; r8, r9 keep two normal components.
    "scanline3d_light565:",
    "push {{r4, r5, r6, r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "push {{r4, r5}}",
    "mov r7, r0",
    "b 10f",
    "90:",
    "movs r0, #0",
    "b 99f",
    "91:",
    "movs r0, #1",
    "99:",
    "pop {{r4, r5}}",
    "mov r8, r4",
    "mov r9, r5",
    "pop {{r4, r5, r6, r7, pc}}",
    // The next vertex and normal.
    "20:",
    "ldr r0, [r7, #{v}]",
    "adds r0, #12",
    "str r0, [r7, #{v}]",
    "ldr r0, [r7, #{n}]",
    "adds r0, #12",
    "str r0, [r7, #{n}]",
    "10:",
    "ldr r0, [r7, #{v}]",
    "ldr r1, [r7, #{end}]",
    "cmp r0, r1",
    "bhs 90b",
    // Only a marked vertex that is not lit yet: `LIT` clear, `NEEDS_LIGHT` (bit 15) set.
    "ldrh r1, [r0, #{vflags}]",
    "lsls r2, r1, #31 - {lit_bit}",
    "bmi 20b",
    "lsls r2, r1, #31 - {needs_bit}",
    "bpl 20b",
    // The normal, each component in [−2²², 2²²).
    "ldr r0, [r7, #{n}]",
    "ldm r0!, {{r3, r4, r5}}",
    "asrs r0, r3, #31",
    "eors r0, r3",
    "asrs r1, r4, #31",
    "eors r1, r4",
    "orrs r0, r1",
    "asrs r1, r5, #31",
    "eors r1, r5",
    "orrs r0, r1",
    "lsrs r0, r0, #22",
    "bne 91b",
    // r6 = N·L (`dot3_q16_small`).
    dot3!(),
    // r5 = s: the ambient term, plus the diffuse one where N·L > 0.
    "ldr r5, [r7, #{ambient}]",
    "cmp r6, #0",
    "ble 30f",
    "lsrs r0, r6, #23",
    "bne 91b",
    mul_q16!("{diffuse_lo}", "{diffuse_hi}", "{diffuse}"),
    "asrs r0, r6, #31",
    "eors r0, r6",
    "lsrs r0, r0, #23",
    "bne 91b",
    mul_q16!("{frac_lo}", "{frac_hi}", "{frac}"),
    "adds r5, r5, r6",
    "bvs 92f",
    // The channels: all zero for s ≤ 0, the pass's for s ≥ 2²³.
    "30:",
    "cmp r5, #0",
    "ble 40f",
    "lsrs r0, r5, #23",
    "bne 92f",
    channel!("0", "31", "4", "3", "r2"),
    channel!("1", "63", "8", "4", "r3"),
    channel!("2", "31", "4", "3", "r4"),
    "b 50f",
    // A decline from the code above, beyond a conditional branch's reach of label 91.
    "92:",
    "b 91b",
    "40:",
    "movs r2, #0",
    "movs r3, #0",
    "movs r4, #0",
    // Stored as `ScreenVertex::set_color` stores them (the upper 8 bits a byte, the lowest 2
    // in flag bits 10..=15, over `NEEDS_LIGHT`), with `LIT` set.
    "50:",
    "ldr r0, [r7, #{v}]",
    "lsrs r6, r2, #2",
    "strb r6, [r0, #{vrgb}]",
    "lsrs r6, r3, #2",
    "strb r6, [r0, #{vrgb} + 1]",
    "lsrs r6, r4, #2",
    "strb r6, [r0, #{vrgb} + 2]",
    "lsls r2, r2, #30",
    "lsrs r2, r2, #20",
    "lsls r3, r3, #30",
    "lsrs r3, r3, #18",
    "lsls r4, r4, #30",
    "lsrs r4, r4, #16",
    "orrs r2, r3",
    "orrs r2, r4",
    "ldrh r1, [r0, #{vflags}]",
    "lsls r1, r1, #22",
    "lsrs r1, r1, #22",
    "orrs r1, r2",
    "movs r3, #1",
    "lsls r3, r3, #{lit_bit}",
    "orrs r1, r3",
    "strh r1, [r0, #{vflags}]",
    "b 20b",
    ".size scanline3d_light565, . - scanline3d_light565",
    v = const core::mem::offset_of!(LightCtx, v),
    end = const core::mem::offset_of!(LightCtx, end),
    n = const core::mem::offset_of!(LightCtx, n),
    dir_lo = const core::mem::offset_of!(LightCtx, dir_lo),
    dir_hi = const core::mem::offset_of!(LightCtx, dir_hi),
    diffuse_lo = const core::mem::offset_of!(LightCtx, diffuse_lo),
    diffuse_hi = const core::mem::offset_of!(LightCtx, diffuse_hi),
    frac_lo = const core::mem::offset_of!(LightCtx, frac_lo),
    frac_hi = const core::mem::offset_of!(LightCtx, frac_hi),
    ambient = const core::mem::offset_of!(LightCtx, ambient),
    dir = const core::mem::offset_of!(LightCtx, dir),
    diffuse = const core::mem::offset_of!(LightCtx, diffuse),
    frac = const core::mem::offset_of!(LightCtx, frac),
    color = const core::mem::offset_of!(LightCtx, color),
    vrgb = const crate::kernel::records::RGB_HI_OFFSET,
    vflags = const crate::kernel::records::FLAGS_OFFSET,
    lit_bit = const LIT.trailing_zeros(),
    needs_bit = const NEEDS_LIGHT.trailing_zeros(),
);

// Word loads reach every field (offsets below 128), byte loads the colour (below 32); a record and a normal are 12 bytes; the
// colour bits the routine writes are those `set_color` writes (flags 10..=15, `LIT` below).
const _: () = {
    assert!(core::mem::offset_of!(LightCtx, color) + 2 < 32);
    assert!(core::mem::offset_of!(LightCtx, ambient) < 128);
    assert!(core::mem::size_of::<ScreenVertex>() == 12);
    assert!(FLAG_MASK == 0x3ff);
    assert!(LIT == 1 << 9 && NEEDS_LIGHT == 1 << 15);
};

extern "C" {
    fn scanline3d_light565(ctx: *mut LightCtx) -> u32;
}

/// `kernel::light_run` (Q16.16 words) on ARMv6-M: passes the vertices of `verts`
/// (with their normals, `normals[i]` for `verts[i]`) until the first marked one it does not
/// light, lighting the marked ones, and returns how many it passed; `None` when the light or
/// the material is outside the routine's range (a direction component of 2²² or more, a
/// diffuse coefficient or colour fraction of 2²³ or more), for the pass to light every vertex
/// itself.
pub(crate) fn light_run(
    verts: &mut [ScreenVertex],
    normals: &[[i32; 3]],
    dir: [i32; 3],
    frac: i32,
    ambient: i32,
    diffuse: i32,
    color: [u8; 3],
) -> Option<usize> {
    if dir.iter().fold(0, |s, &v| s | spread_bits(v)) >= 1 << 22
        || (spread_bits(frac) | spread_bits(diffuse)) >= 1 << 23
    {
        return None;
    }
    let n = verts.len().min(normals.len());
    let run = verts[..n].as_mut_ptr_range();
    let lo = |v: i32| (v & 0xffff) as u32;
    let mut ctx = LightCtx {
        v: run.start,
        end: run.end,
        n: normals.as_ptr(),
        dir_lo: dir.map(lo),
        dir_hi: dir.map(|v| v >> 16),
        diffuse_lo: lo(diffuse),
        diffuse_hi: diffuse >> 16,
        frac_lo: lo(frac),
        frac_hi: frac >> 16,
        ambient,
        color: [color[0], color[1], color[2], 0],
        dir,
        diffuse,
        frac,
    };
    // SAFETY: a normal is three words.
    // The routine reads the records and normals of the run (`n` of each, 12 bytes a record and
    // a normal), writes only the colour bytes and flags of records in the run and
    // its cursors, which it moves together one record (and normal) at a time up to the end.
    unsafe { scanline3d_light565(&mut ctx) };
    // SAFETY: the cursor stays within the run, at a whole record.
    Some(unsafe { ctx.v.offset_from(run.start) } as usize)
}
