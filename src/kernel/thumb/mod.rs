//! The Thumb kernels: hand-written Thumb-1 assembly for the renderer's hot path on Cortex-M
//! cores, one file per kernel (`span`, `rows` with `rows_t2`, `rows_dither`, `fill`, `xform`, `project`,
//! `gouraud`, `edge`, `setup`, `setup_t2`, `dither_fits`, `cull`, `light`, `vertex`). The span file holds for RGB565 words, the
//! Gouraud span loop, a routine that draws one row of every qualifying active triangle (span,
//! edge steps, attribute steps, the short edge's switch, removal after the last row) and the
//! strip-line clear; and the Q16.16 point and direction transforms. The span loop alone was
//! about 40 % of a frame's instructions on a Cortex-M0 before it was written here.
//!
//! Why assembly: on `thumbv6m` only r0–r7 are general registers for most instructions and r7 is
//! the frame pointer, so LLVM spills the span's accumulators to the stack and unrolls the loop
//! four times, which comes to about 47 instructions per pixel. Written by hand the loop keeps
//! the three accumulators, the index and both line ends in low registers and the three steps
//! in r8–r10: 19 instructions per written pixel and 12 per hidden one.
//!
//! With 4×4 ordered dithering the span and the row routine have dithered twins
//! (`scanline3d_span565_less_dither`, `scanline3d_rows565_dither`; the plain loops are
//! unchanged): the row's eight Bayer offsets (`raster::dither_words`) sit on the stack, the
//! pixel loop is unrolled over the four column phases so that each loads its two offsets with
//! an immediate sp offset, and a written pixel adds them to copies of the red-blue and green
//! words before reading the channels: 23 instructions per written pixel, 12 per hidden one.
//! The row routine draws its common row's span with a copy of the unrolled loop in line and
//! the rarer rows' spans through a subroutine (two copies instead of five), and only
//! triangles with `DITHER_OK` (the only ones with routine rows in a dithered strip). With the
//! `rp2040` feature its twin `scanline3d_rows565_dither_interp` draws the same pixels with the
//! RP2040's SIO interpolators (depth stepping and the red-blue placement: 19 instructions and
//! 24 cycles per written pixel); the Pico firmware compares it with the portable rows at
//! start-up, since the QEMU benchmark has no SIO.
//!
//! The triangle setup (`scanline3d_setup565`, with `scanline3d_gouraud_setup`) also makes the
//! dither check of `raster::ActiveTri::dither_fits` (`scanline3d_dither_fits565`), compared
//! with the portable check on random triangles by the benchmark firmware. It runs on every
//! Cortex-M core: in Thumb-1 (`setup`, `gouraud`, with `edge`'s edge macros and `project`'s
//! reciprocal) on ARMv6-M, and in Thumb-2 (`setup_t2`: `smull`/`umull`, `clz`, `udiv`, `mla`,
//! shifted operands; about 230 instructions per triangle for the setup and 270 for the
//! attributes on a Cortex-M4F, where the portable setup took about 935) elsewhere.
//!
//! The routines compute exactly what the portable code in [`crate::raster`] computes
//! (`span_packed` for `DepthTest::Less` and 5-6-5 channels, `ActiveTri::draw_row` for a fast
//! Gouraud row: same truncations, same wrapping additions), so the image is bit-identical;
//! `scripts/mcu-bench` checks the image hashes of every benchmark scene on Cortex-M0 and
//! Cortex-M4F against the host's, which runs the portable code, and the benchmark firmware
//! checks the transforms against `dot3_add` on 4096 cases before it measures.
//!
//! On cores with Thumb-2 (`scanline3d_thumb2`: ARMv7-M, ARMv7E-M, ARMv8-M Mainline) the span
//! loops' pixel loop (`span`) and the row routine's hot path (`rows_t2`: span head, line
//! ends, edge and row steps, next triangle) take Thumb-2 forms: the plain row routine is a
//! Thumb-2 source of its own (`rows_t2`), 16 instructions per written pixel and about 36
//! around each drawn row instead of 19 and about 49; the triangle setup and the Gouraud
//! attribute setup too (`setup_t2`: `udiv`/`mls` edges, `clz`/`umull` reciprocal,
//! `smull`/`smlal` planes). The vertex
//! run (`vertex`) runs there too, calling Thumb-2 forms of the transform and the projection
//! (`xform_t2`, `project_t2`: `smlal`, `smull`, `umull`, `clz`; about 60 and 115 instructions
//! a vertex where LLVM's code takes about 140 and 175), and so does the lighting run (`light`,
//! with Thumb-2 forms of its products). The single transforms (`transform_q16`) and the edge
//! kernel (`edge`) stay on ARMv6-M only: elsewhere the portable code, with the long multiply
//! and the divide, is as fast or faster.
//!
//! Safety: the entry points take RGB565 words (`u16` lines) and pass runs within the lines
//! they were given; `kernel` chooses these routines only on Cortex-M targets (the
//! `scanline3d_thumb` cfg of `build.rs`) and, for the routines that only pay off without
//! Thumb-2's multiplies and divides, only on ARMv6-M (`scanline3d_thumb_v6m`); the Thumb-2
//! forms only where `scanline3d_thumb2`.
#![allow(unsafe_code)]

/// AAPCS entry of both routines: saves r4–r11 and the return address (r8–r11 through low
/// registers: Thumb-1 `push` takes only r0–r7 and lr).
macro_rules! save_registers {
    () => {
        concat!(
            "push {{r4, r5, r6, r7, lr}}\n",
            "mov r4, r8\n",
            "mov r5, r9\n",
            "mov r6, r10\n",
            "mov r7, r11\n",
            "push {{r4, r5, r6, r7}}\n",
        )
    };
}

/// The matching exit: restores r8–r11 and r4–r7 and returns.
macro_rules! restore_registers_and_return {
    () => {
        concat!(
            "pop {{r4, r5, r6, r7}}\n",
            "mov r8, r4\n",
            "mov r9, r5\n",
            "mov r10, r6\n",
            "mov r11, r7\n",
            "pop {{r4, r5, r6, r7, pc}}\n",
        )
    };
}

// Modules that define assembly macros their successors use come first (`macro_use`).
#[macro_use]
mod span;
#[cfg(scanline3d_thumb2)]
#[macro_use]
mod rows_t2;
#[macro_use]
mod rows;
mod fill;
mod rows_dither;
#[cfg(scanline3d_thumb_v6m)]
#[macro_use]
mod xform;
#[cfg(scanline3d_thumb2)]
mod xform_t2;
// The projection (Thumb-1 here, `project_t2` on Thumb-2 cores) and `recip_norm!` for the
// Thumb-1 attribute setup.
#[macro_use]
mod project;
#[cfg(scanline3d_thumb2)]
#[macro_use]
mod project_t2;
#[cfg(scanline3d_thumb2)]
#[macro_use]
mod setup_t2;
#[macro_use]
mod gouraud;
// The edge kernel and the Thumb-1 triangle setup's edge macros; on Thumb-2 cores the setup
// has its own (`setup_t2`) and the edges set up elsewhere stay portable.
#[cfg(not(scanline3d_thumb2))]
#[macro_use]
mod edge;
mod cull;
mod dither_fits;
#[cfg(scanline3d_thumb_geometry)]
mod light;
mod setup;
#[cfg(scanline3d_thumb_geometry)]
mod vertex;

pub(crate) use cull::cull_push;
pub(crate) use dither_fits::dither_fits565;
#[cfg(scanline3d_thumb_v6m)]
pub(crate) use edge::edge_new;
pub(crate) use fill::clear_line;
pub(crate) use gouraud::gouraud_setup;
#[cfg(scanline3d_thumb_geometry)]
pub(crate) use light::light_run;
#[cfg(scanline3d_thumb_geometry)]
pub(crate) use project::project_q16;
pub(crate) use rows::rows565;
pub(crate) use setup::setup565;
#[cfg(scanline3d_thumb_v6m)]
pub(crate) use span::span565_flat_less;
pub(crate) use span::{span565_less, span565_less_dither};
#[cfg(scanline3d_thumb_geometry)]
pub(crate) use vertex::project_run;
#[cfg(scanline3d_thumb_v6m)]
pub(crate) use xform::{transform_dir_q16, transform_q16};

/// Byte offsets of the fields the Thumb kernels read and write (some only on ARMv6-M).
#[allow(dead_code)]
pub(crate) mod offsets {
    use crate::kernel::records::{ActiveTri, EdgeDda};
    use core::mem::{offset_of, size_of};
    pub const LEFT: usize = offset_of!(ActiveTri, edges);
    pub const RIGHT: usize = LEFT + size_of::<EdgeDda>();
    pub const W: usize = offset_of!(EdgeDda, w);
    pub const S: usize = offset_of!(EdgeDda, s);
    pub const LEFT_DY: usize = offset_of!(ActiveTri, dy);
    pub const RIGHT_DY: usize = LEFT_DY + 2;
    pub const GX: usize = offset_of!(ActiveTri, gx);
    pub const ROW: usize = offset_of!(ActiveTri, row);
    pub const INC: usize = offset_of!(ActiveTri, inc);
    pub const ROUTINE_ROWS: usize = offset_of!(ActiveTri, routine_rows);
    pub const FLAGS: usize = offset_of!(ActiveTri, flags);
    pub const LAST_BIT: u32 = crate::kernel::records::LAST_IN_ROUTINE.trailing_zeros();
    pub const SWITCH_BIT: u32 = crate::kernel::records::SWITCH_IN_ROUTINE.trailing_zeros();
    pub const SWITCH: u8 = crate::kernel::records::SWITCH_IN_ROUTINE;
    pub const LAST: u8 = crate::kernel::records::LAST_IN_ROUTINE;
    pub const MID_LEFT: u8 = crate::kernel::records::MID_LEFT;
    pub const ROW_MID: usize = offset_of!(ActiveTri, row_mid);
    pub const ROW_END: usize = offset_of!(ActiveTri, row_end);
    pub const BX: usize = offset_of!(ActiveTri, bx);
    pub const CX: usize = offset_of!(ActiveTri, cx);
    pub const FAST: u8 = crate::kernel::records::FAST;
    pub const DITHER_OK: u8 = crate::kernel::records::DITHER_OK;
    /// The pending short edge of a fast Gouraud triangle ([`ActiveTri::set_pending`]): its
    /// `w` word in the fourth `gx` word, `s` in the fourth `row` word, `dy` in the fourth
    /// `inc` word.
    pub const PEND_W: usize = GX + 12;
    pub const PEND_S: usize = ROW + 12;
    pub const PEND_DY: usize = INC + 12;
    pub const EDGE_C: usize = offset_of!(crate::kernel::records::Edge, c);
    pub const EDGE_SQ: usize = offset_of!(crate::kernel::records::Edge, sq);
    pub const EDGE_E: usize = offset_of!(crate::kernel::records::Edge, e);
    pub const EDGE_SR: usize = offset_of!(crate::kernel::records::Edge, sr);
    pub const EDGE_DY: usize = offset_of!(crate::kernel::records::Edge, dy);
}
