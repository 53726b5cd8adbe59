//! The Gouraud RGB565 span loop in Thumb-1 assembly, for Cortex-M cores (the hot loop of the
//! renderer: about 40 % of a frame's instructions on a Cortex-M0 before it was written here).
//!
//! Why assembly: on `thumbv6m` only r0–r7 are general registers for most instructions and r7 is
//! the frame pointer, so LLVM spills the span's accumulators to the stack and unrolls the loop
//! four times, which comes to about 47 instructions per pixel. Written by hand the loop keeps
//! the three accumulators and the pointer in low registers and the three steps and the end
//! pointer in r8–r11: 23 instructions per written pixel and 11 per hidden one.
//!
//! The loop computes exactly what [`crate::raster`]'s portable `span_packed` computes for
//! `DepthTest::Less` and 5-6-5 channels (same truncations, same wrapping additions), so the
//! image is bit-identical; `scripts/mcu-bench` checks the image hashes of every benchmark scene
//! on Cortex-M0 and Cortex-M4F against the host's, which runs the portable loop.
//!
//! Safety: the caller passes a depth run and a colour run of the same length `n ≥ 1`, with the
//! colour type a plain 16-bit RGB565 word (checked by [`rgb565_words`]).
#![allow(unsafe_code)]

use crate::color::TargetColor;

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
    "push {{r4, r5, r6, r7, lr}}",
    "mov r4, r8",
    "mov r5, r9",
    "mov r6, r10",
    "mov r7, r11",
    "push {{r4, r5, r6, r7}}",
    "mov r11, r2",
    "ldr r4, [r3, #4]",
    "mov r8, r4",
    "ldr r4, [r3, #12]",
    "mov r9, r4",
    "ldr r4, [r3, #20]",
    "mov r10, r4",
    "ldr r2, [r3, #0]",
    "ldr r4, [r3, #16]",
    "ldr r3, [r3, #8]",
    "movs r7, #0",
    // r2 = z (16.12 + ½ bias), r3 = rb (red << 16 + blue, 11 fraction bits each, + ½ bias),
    // r4 = g (20 fraction bits + ½ bias); r8, r9, r10 = their per-pixel steps.
    "1:",
    "ldrh r5, [r0]",
    "lsrs r6, r2, #12",
    "uxth r6, r6",
    "cmp r6, r5",
    "bhs 2f",
    "strh r6, [r0]",
    "lsrs r5, r3, #27",
    "lsls r5, r5, #11",
    "lsls r6, r4, #6",
    "lsrs r6, r6, #26",
    "lsls r6, r6, #5",
    "orrs r5, r6",
    "lsls r6, r3, #16",
    "lsrs r6, r6, #27",
    "orrs r5, r6",
    "strh r5, [r0, r1]",
    "adds r7, #1",
    "2:",
    "add r2, r8",
    "add r3, r9",
    "add r4, r10",
    "adds r0, #2",
    "cmp r0, r11",
    "bne 1b",
    "mov r0, r7",
    "pop {{r4, r5, r6, r7}}",
    "mov r8, r4",
    "mov r9, r5",
    "mov r10, r6",
    "mov r11, r7",
    "pop {{r4, r5, r6, r7, pc}}",
    ".size scanline3d_span565_less, . - scanline3d_span565_less",
);

extern "C" {
    fn scanline3d_span565_less(
        z: *mut u16,
        color_offset: isize,
        end: *mut u16,
        acc: *const [u32; 6],
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
    let bits = |c: [u8; 3]| -> u16 {
        let v = C::from_channels(c);
        // SAFETY: `C` is two bytes without padding (a `u16` wrapper), so its bytes are a `u16`.
        unsafe { core::mem::transmute_copy::<C, u16>(&v) }
    };
    bits([31, 0, 0]) == 0xF800 && bits([0, 63, 0]) == 0x07E0 && bits([0, 0, 31]) == 0x001F
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
