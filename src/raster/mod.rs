//! Scan conversion: the coverage rule, the depth test and the number formats the raster stages
//! share (the packed span formats, the strip's span mode). The stages themselves are
//! `setup.rs` (a triangle's edges and attribute planes when it becomes active) and `span.rs`
//! (a row of an active triangle: edge steps, attribute steps and the span loops).
//!
//! Coverage rule: pixel `(px, py)` is covered when its centre `(16·px + 8, 16·py + 8)` (in
//! subpixels) lies inside the triangle, with the **top-left rule** on the boundary: a centre
//! exactly on a left or top edge is covered, one on a right or bottom edge is not. Rows are the
//! half-open range `Ytop ≤ Ys < Ybottom`; in a row the span is `x_left ≤ Xs < x_right`, so both
//! ends are `ceil((x − 8) / 16)` of the exact edge crossing `x`.
//!
//! Each edge keeps that ceiling as an integer plus an exact remainder (a Bresenham-style DDA):
//! stepping one row is two additions and a compare, and the value is exact at every row, so an
//! edge shared by two triangles yields the same pixel boundary in both — no gaps, no pixel twice.
//!
//! Depth and colour are planes `A(x, y) = A₀ + gx·(x − x₀) + gy·(y − y₀)`.
//!
//! Cost per triangle: one division for a normalized reciprocal of its area (every gradient is
//! then a multiply), and one division-with-remainder per edge for its start and one for its
//! step (32-bit whenever the values fit, which is the case for on-screen triangles below
//! ~1000 px), i.e. at most seven divisions. Per row: one or two additions per edge and one
//! per attribute. Per pixel: one addition per attribute, a shift, a compare and stores.

pub(crate) mod depth_mode;
pub(crate) mod fog;
pub(crate) mod kind;
pub(crate) mod layer_rows;
pub(crate) mod layers;
pub(crate) mod pass;
pub(crate) mod phong;
pub(crate) mod seek;
pub(crate) mod setup;
pub(crate) mod shadow;
pub(crate) mod shadow_map;
pub(crate) mod shadow_span;
pub(crate) mod span;
pub(crate) mod span_map;
pub(crate) mod state;
pub(crate) mod strip;
pub(crate) mod textured;
pub(crate) mod volume;

use crate::geometry::project::{channel_bits, DEPTH_FRAC_BITS};
pub(crate) use crate::kernel::records::{
    first_pixel, ActiveList, ActiveTri, Edge, EdgeDda, Sorted, TriRecord, COARSE_MIN, DITHER_OK,
    FAST, FLAT, FLAT_BIT, LAST_IN_ROUTINE, MID_LEFT, SWITCH_IN_ROUTINE,
};
use crate::scene::color::{TargetColor, BAYER};

/// Fraction bits of interpolated colour channels (channel units, so 0..=255·2²⁰ < 2²⁸ fits an
/// `i32`; step 2⁻²⁰ of a channel unit).
pub const COLOR_FRAC_BITS: u32 = 20;

/// The comparison a fragment's depth must pass against the stored depth (0 = nearest).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum DepthTest {
    /// Nearer than what is stored (the first of equal depths wins). Lines are cleared to the
    /// far plane (65535), so a fragment exactly at the far plane is not drawn, as in OpenGL.
    #[default]
    Less,
    /// Nearer or equal (the last of equal depths wins).
    LessEqual,
    /// Exactly equal (for repeatability tests and decals).
    Equal,
    /// Always pass (painter's order).
    Always,
}

#[cfg(test)]
/// `ceil(n / d)` for `d > 0`.
#[inline]
pub(crate) fn ceil_div(n: i64, d: i64) -> i64 {
    let q = n.div_euclid(d);
    if q * d == n {
        q
    } else {
        q + 1
    }
}

/// Which fast span loops a strip may use, decided once per strip from the colour type, the
/// depth test and dithering (see [`FAST`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct SpanMode {
    /// Flat triangles: the depth test is [`DepthTest::Less`].
    pub fast_flat: bool,
    /// Gouraud triangles: also channels of at most 6 bits.
    pub fast_gouraud: bool,
    /// Dithering changes the colour (so fast Gouraud triangles are checked for
    /// [`DITHER_OK`] at setup).
    pub dither: bool,
}

impl SpanMode {
    pub(crate) fn new<C: TargetColor>(test: DepthTest, dither: bool) -> Self {
        let less = test == DepthTest::Less;
        SpanMode {
            fast_flat: less,
            fast_gouraud: less && packable::<C>(),
            dither: dither && C::can_dither(),
        }
    }
}

/// The pixel of a packed red-blue word and a packed green word ([`pack_zrgb`]): the whole bits
/// of each field. The shifts are constants of the colour type (immediates, no registers), so
/// [`span_packed`] and its dithered twin share this without cost.
#[inline(always)]
pub(crate) fn packed_color<C: TargetColor>(rb: u32, g: u32) -> C {
    let (fr, fb) = packed_frac_bits::<C>();
    C::from_channels([
        (rb >> (16 + fr)) as u8,
        shr_or_zero(g, 32 - channel_bits(C::CHANNEL_MAX[1])) as u8,
        ((rb & 0xffff) >> fb) as u8,
    ])
}

/// `v >> s`, and 0 for `s ≥ 32` (a green word's channel bits for a colour type without green:
/// `s` is a constant of the colour type, so this folds to one shift or to 0).
#[inline(always)]
pub(crate) fn shr_or_zero(v: u32, s: u32) -> u32 {
    v.checked_shr(s).unwrap_or(0)
}

/// Whether red and blue of `C` fit the packed red-blue word (at most 6 bits each).
#[inline(always)]
pub(crate) fn packable<C: TargetColor>() -> bool {
    C::CHANNEL_MAX[0] <= 63 && C::CHANNEL_MAX[2] <= 63 && C::CHANNEL_MAX[0] > 0
}

/// Fraction bits of red and blue in a packed red-blue word: `16 − bits` of each channel.
#[inline(always)]
pub(crate) fn packed_frac_bits<C: TargetColor>() -> (u32, u32) {
    (
        16 - channel_bits(C::CHANNEL_MAX[0]),
        16 - channel_bits(C::CHANNEL_MAX[2]),
    )
}

/// The packed red-blue word of red `r` and blue `b` (20 fraction bits each, values or
/// gradients): each rounded to `16 − bits` fraction bits, red in the high half, added with
/// wrapping (so the word is `R·2¹⁶ + B mod 2³²`, whatever the signs).
#[inline(always)]
pub(crate) fn pack_rb<C: TargetColor>(r: i64, b: i64) -> u32 {
    let (fr, fb) = packed_frac_bits::<C>();
    let conv = |v: i64, s: u32| (v.wrapping_add(1 << (s - 1)) >> s) as u32;
    (conv(r, COLOR_FRAC_BITS - fr) << 16).wrapping_add(conv(b, COLOR_FRAC_BITS - fb))
}

/// Half a unit of red and of blue in a packed red-blue word: the rounding bias of a start value.
#[inline(always)]
pub(crate) fn packed_rb_half<C: TargetColor>() -> u32 {
    let (fr, fb) = packed_frac_bits::<C>();
    ((1u32 << (fr - 1)) << 16) + (1 << (fb - 1))
}

/// The dithered fast span's offsets for pixel row `row` ([`span_packed_dither`]): for each
/// column phase `p = x & 3`, the word to add to a packed red-blue value and the word to add
/// to a packed green value. The packed start values already carry the ½-unit rounding bias
/// of the non-dithered path ([`attribute_words`]); the Bayer threshold (2·B + 1)/32 of a unit
/// (B = `BAYER[row & 3][p]`) is that bias plus `d = (2·B − 15)/32`, from −15/32 to +15/32 of a
/// unit in steps of 1/16. `d` is exact in every packed format (channels of at most 6 bits
/// have at least 10 fraction bits): `d·2^(frac − 5)` in the red half and in the blue half
/// (added as one wrapping word, so red gets `d` and blue gets `d` — no carry crosses the
/// halves when both fields stay in `0..2¹⁶`, see [`DITHER_OK`]), and `d·2^(32 − bits − 5)`
/// in the green word.
#[inline(always)]
pub(crate) fn dither_words<C: TargetColor>(row: i32) -> [[u32; 2]; 4] {
    let (fr, fb) = packed_frac_bits::<C>();
    let gs = 32 - channel_bits(C::CHANNEL_MAX[1]) - 5;
    let b = &BAYER[(row & 3) as usize];
    let mut out = [[0u32; 2]; 4];
    for (o, &bv) in out.iter_mut().zip(b) {
        let d = 2 * bv as i32 - 15;
        o[0] = ((d << (fr - 5)) as u32)
            .wrapping_shl(16)
            .wrapping_add((d << (fb - 5)) as u32);
        o[1] = (d as u32).wrapping_shl(gs);
    }
    out
}

/// Left shift of a packed depth word: depth (16.12) times 2⁴, so that the stored depth is the
/// high half (the shifted value wraps exactly as the unshifted one, modulo 2³²).
pub(crate) const PACKED_Z_SHIFT: u32 = 32 - 16 - DEPTH_FRAC_BITS;

/// Left shift of a packed green word: green (20 fraction bits) times `2^(12 − bits)`, so that
/// its `bits` whole bits are the word's top bits.
#[inline(always)]
pub(crate) fn packed_g_shift<C: TargetColor>() -> u32 {
    32 - COLOR_FRAC_BITS - channel_bits(C::CHANNEL_MAX[1])
}

/// A depth, red-blue and green triple (values or steps, 16.12 depth and 20-bit channels with
/// any biases added) in the packed span formats: depth and green shifted to the top of their
/// words, red and blue in one word ([`pack_rb`]). All wrapping, so stepping the packed words
/// gives exactly the packed stepped values.
#[inline(always)]
pub(crate) fn pack_zrgb<C: TargetColor>(z: i64, r: i64, g: i64, b: i64) -> [i32; 3] {
    [
        (z as i32) << PACKED_Z_SHIFT,
        pack_rb::<C>(r, b) as i32,
        (g as i32) << packed_g_shift::<C>(),
    ]
}

#[cfg(test)]
#[path = "raster_tests.rs"]
mod tests;
