//! The dithered row routines (`scanline3d_rows565_dither`, and with the `rp2040` feature
//! `scanline3d_rows565_dither_interp` on the RP2040's SIO interpolators).
#![allow(unsafe_code)]

use super::offsets as o;
use super::rows::{RowCtx, INV21};
#[cfg(feature = "rp2040")]
use super::rows::{INTERP0_LANE0, INTERP0_LANE1, INTERP1_LANE0, INTERP1_LANE1};
use crate::kernel::records::ActiveTri;

/// A dithered row routine `$name` (r1 = the eight offsets of the row's Bayer row in
/// `raster::DITHER565`): before the context's six words, the offsets go on the stack ([sp, #28]
/// to [sp, #56] in the routine, the `itrb`/`itg` words; the span subroutine of the rarer paths
/// sees them 4 bytes further, after the saved fragment count: the `strb`/`stg` words). The
/// common row draws its span with a copy of the dithered loop in line (no call), the rarer
/// rows through the subroutine at label 40. Only `DITHER_OK` triangles have routine rows in a
/// dithered strip (`ActiveTri::set_routine_rows`), so the routine needs no test of its own for
/// them. `$entry` runs first; `$take_depth` (common row) and `$sub_take_depth` (subroutine)
/// run once a span's start words are in r2–r4; `$pixel` and `$steps` are the loop's written
/// pixel and a hidden pixel's steps ([`dither_loop`]); `$extra` more operands.
macro_rules! rows565_dither_routine {
    ($name:literal, $entry:expr, $take_depth:expr, $sub_take_depth:expr, $pixel:ident,
     $steps:expr, [$($extra:tt)*]) => {
        rows565_routine!(
            $name,
            concat!(
                $entry,
                "adds r1, #16\n",
                "ldm r1!, {{r2, r3, r4, r5}}\n",
                "push {{r2, r3, r4, r5}}\n",
                "subs r1, #32\n",
                "ldm r1!, {{r2, r3, r4, r5}}\n",
                "push {{r2, r3, r4, r5}}\n",
            ),
            row_span_dither_inline!(
                $take_depth,
                dither_loop!("i", count_on_stack!(), $pixel, $steps)
            ),
            span_run_dither,
            "26:\nmov r5, r11\nb 36f\n27:\nb 37f\n",
            "60",
            concat!(
                "40:\n",
                $sub_take_depth,
                dither_loop!(
                    "s",
                    "ldr r5, [sp, #24]\nadds r5, #1\nstr r5, [sp, #24]\n",
                    $pixel,
                    $steps
                ),
                "bx lr\n",
            ),
            [
                strb0 = const 32,
                stg0 = const 36,
                strb1 = const 40,
                stg1 = const 44,
                strb2 = const 48,
                stg2 = const 52,
                strb3 = const 56,
                stg3 = const 60,
                itrb0 = const 28,
                itg0 = const 32,
                itrb1 = const 36,
                itg1 = const 40,
                itrb2 = const 44,
                itg2 = const 48,
                itrb3 = const 52,
                itg3 = const 56,
                $($extra)*
            ]
        );
    };
}

rows565_dither_routine!(
    "scanline3d_rows565_dither",
    "",
    "",
    "",
    dither_pixel,
    gouraud_steps!(),
    []
);

// The dithered row routine with the RP2040's SIO interpolators (feature `rp2040`, where the
// Pico firmware runs: the SIO exists only on an RP2040, so other ARMv6-M parts keep
// `scanline3d_rows565_dither`). The same routine with [`dither_pixel_interp`]'s pixels; it sets
// up both interpolators of the calling core on entry ([`interp_config`]) and leaves them
// changed (the renderer owns them while it draws: an interrupt handler that uses them must
// save and restore them). Its register offsets are from the interpolators' base 0xd000_0080
// (RP2040 datasheet 2.3.1.6, SIO registers INTERP0_ACCUM0 … INTERP1_BASE_1AND0).
#[cfg(feature = "rp2040")]
rows565_dither_routine!(
    "scanline3d_rows565_dither_interp",
    interp_config!(),
    interp_take_depth!("r0"),
    interp_take_depth!("r6"),
    dither_pixel_interp,
    "add r3, r9\nadd r4, r10\n",
    [
        i0_accum0 = const 0x00,
        i0_base0 = const 0x08,
        i0_base1 = const 0x0c,
        i0_pop0 = const 0x14,
        i0_ctrl0 = const 0x2c,
        i0_ctrl1 = const 0x30,
        i1_accum0 = const 0x40,
        i1_base2 = const 0x50,
        i1_peek_full = const 0x68,
        i1_ctrl0 = const 0x6c,
        i1_ctrl1 = const 0x70,
        i0_lane0 = const INTERP0_LANE0,
        i0_lane1 = const INTERP0_LANE1,
        i1_lane0 = const INTERP1_LANE0,
        i1_lane1 = const INTERP1_LANE1,
    ]
);

// The immediate offsets above must be encodable in 16-bit Thumb loads and stores (some are 0
// today, which clippy finds absurd to compare; the layout may change).
#[allow(clippy::absurd_extreme_comparisons)]
const _: () = {
    assert!(o::LEFT % 4 == 0 && o::RIGHT % 4 == 0 && o::RIGHT + o::S <= 124);
    assert!(o::W == 0 && o::S == 4 && o::LEFT_DY % 2 == 0 && o::RIGHT_DY <= 62);
    assert!(o::GX % 4 == 0 && o::ROW == o::GX + 16 && o::INC == o::ROW + 16);
    // The row routine loads and stores both edges' words with one `ldm` and `stm` from
    // `adds r5, r0, #LEFT` (an immediate of 3 bits).
    assert!(o::LEFT <= 7 && o::RIGHT == o::LEFT + 8 && o::S == 4);
    assert!(o::ROW >= o::RIGHT + o::S + 4 && o::ROW - (o::RIGHT + o::S + 4) <= 255);
    assert!(o::INC + 12 <= 255);
    assert!(core::mem::size_of::<ActiveTri>() <= 255);
    assert!(o::ROUTINE_ROWS <= 31 && o::FLAGS <= 31);
};
