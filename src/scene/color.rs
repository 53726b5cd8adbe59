//! Output colours: how lit 8-bit colours become the target's pixel colour.
//!
//! Lighting produces 8-bit channels (0..=255, as 8.8 fixed point). Per **vertex** they are
//! scaled to the target's channel range with rounding — `c·31/255` for the 5-bit channels of
//! RGB565, `c·63/255` for its 6-bit green, not a shift — and kept as 8.8 fixed point, so per
//! **pixel** only an add and a shift remain: `(c + bias) >> frac`, where `bias` is one half
//! (round to nearest) or, with dithering, a 4×4 ordered (Bayer) threshold.

use core::any::TypeId;

use embedded_graphics_core::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, BinaryColor, Gray2, Gray4, Gray8, GrayColor, IntoStorage,
    PixelColor, Rgb555, Rgb565, Rgb666, Rgb888, RgbColor,
};

/// A pixel colour the renderer can write.
///
/// Implemented for the embedded-graphics RGB, BGR, grey and binary colours. For another colour
/// type that converts from [`Rgb888`], an empty `impl TargetColor for MyColor {}` works: the
/// defaults quantize to 8 bits per channel and convert through `Rgb888`.
pub trait TargetColor: PixelColor + From<Rgb888> + 'static {
    /// The largest value of each channel (R, G, B) in this colour's own units.
    const CHANNEL_MAX: [u8; 3] = [255, 255, 255];

    /// Builds a pixel from channels already in this colour's units (≤ [`Self::CHANNEL_MAX`]).
    #[must_use]
    fn from_channels(c: [u8; 3]) -> Self {
        Rgb888::new(c[0], c[1], c[2]).into()
    }

    /// Converts lit 8-bit channels (8.8 fixed point, 0..=65280) to this colour's channel units,
    /// also 8.8 fixed point, rounding to nearest. Called once per vertex (or per flat face).
    #[must_use]
    fn vertex_channels(rgb: [u16; 3]) -> [u16; 3] {
        scale_channels(rgb, Self::CHANNEL_MAX)
    }

    /// For colour types that stand for triangles rather than colours ([`TriangleId`]): the
    /// flat "colour" of input triangle `id`, in channel units (8.8). `None` for real colours.
    #[must_use]
    fn triangle_id(id: u16) -> Option<[u16; 3]> {
        let _ = id;
        None
    }

    /// This pixel's channels in this colour's own units (≤ [`Self::CHANNEL_MAX`]), for
    /// blending over it (shadows and translucent materials,
    /// [`crate::FrameOptions::layered`]); `None` for a type that cannot say (the default,
    /// and [`TriangleId`]): such a target is drawn without blending.
    #[must_use]
    fn channels(self) -> Option<[u8; 3]> {
        None
    }

    /// Whether 4×4 ordered dithering can change this colour's output (fewer than 8 bits in a
    /// channel).
    #[must_use]
    fn can_dither() -> bool {
        Self::CHANNEL_MAX.iter().any(|&m| m != 0 && m < 255)
    }
}

/// Whether `C` is embedded-graphics' [`Rgb565`], whose raw storage ([`IntoStorage`]) is the
/// 16-bit word `r << 11 | g << 5 | b`, laid out in memory as that `u16` (checked, not
/// assumed: a size, an alignment and a probe value). The RGB565 kernels write such words, so
/// they are chosen by this, a property of the type itself (no trait constant a user could set
/// wrongly). Folds to a constant for every concrete `C`.
#[inline(always)]
pub(crate) fn is_rgb565<C: TargetColor>() -> bool {
    TypeId::of::<C>() == TypeId::of::<Rgb565>() && rgb565_is_its_storage()
}

/// `Rgb565` is two bytes, at most 2-aligned, and its bytes are its raw storage word.
#[inline(always)]
#[allow(unsafe_code)]
fn rgb565_is_its_storage() -> bool {
    if core::mem::size_of::<Rgb565>() != 2 || core::mem::align_of::<Rgb565>() > 2 {
        return false;
    }
    let probe = Rgb565::new(0b10110, 0b011001, 0b01101);
    // SAFETY: `Rgb565` is two bytes (checked above) without padding (a `u16` wrapper), so its
    // bytes are a valid `u16`.
    let bytes = unsafe { core::mem::transmute_copy::<Rgb565, u16>(&probe) };
    bytes == probe.into_storage()
}

/// A line of `C` as RGB565 words when [`is_rgb565`] holds, else `None`.
#[inline(always)]
#[allow(unsafe_code)]
pub(crate) fn rgb565_words_mut<C: TargetColor>(cs: &mut [C]) -> Option<&mut [u16]> {
    if !is_rgb565::<C>() {
        return None;
    }
    // SAFETY: `C` is `Rgb565` (same `TypeId`), which is two bytes, 2-aligned at most, with its
    // raw storage word as its bytes (checked by `is_rgb565`); every `u16` is a valid `Rgb565`.
    // The slice is exclusively borrowed for the lifetime of the result.
    Some(unsafe { core::slice::from_raw_parts_mut(cs.as_mut_ptr() as *mut u16, cs.len()) })
}

/// A colour's RGB565 word when [`is_rgb565`] holds, else `None`.
#[inline(always)]
pub(crate) fn rgb565_word<C: TargetColor>(c: C) -> Option<u16> {
    if !is_rgb565::<C>() {
        return None;
    }
    let mut one = [c];
    rgb565_words_mut(&mut one).map(|w| w[0])
}

/// `c · max / 255`, rounded to nearest, for each channel (all 8.8 fixed point).
#[must_use]
pub fn scale_channels(rgb: [u16; 3], max: [u8; 3]) -> [u16; 3] {
    let mut out = [0u16; 3];
    for k in 0..3 {
        out[k] = div255(rgb[k] as u32 * max[k] as u32 + 127) as u16;
    }
    out
}

/// `x / 255` for any `u32`, as a multiply by 2³⁹/255 rounded up (0x8080_8081) and a shift — the
/// constant compilers use — with the 64-bit product from four 16-bit multiplies: a Cortex-M0 has
/// no divide instruction, and the library division costs about a hundred instructions.
#[inline(always)]
fn div255(x: u32) -> u32 {
    if x < 0xff_ffff {
        // Below 2²⁴ − 1 (every scaled channel): x/255 = x/256 · (1 + 1/255), twice refined,
        // in shifts and adds (checked against the division over the whole range).
        let q0 = (x + (x >> 8) + 1) >> 8;
        return (x + q0 + 1) >> 8;
    }
    (crate::kernel::wide::mul_wide_u(x, 0x8080_8081) >> 39) as u32
}

/// ITU-R BT.601 luma of 8.8 channels, with the weights embedded-graphics uses (77, 150, 29)/256.
#[must_use]
pub fn luma(rgb: [u16; 3]) -> u16 {
    ((rgb[0] as u32 * 77 + rgb[1] as u32 * 150 + rgb[2] as u32 * 29 + 128) >> 8) as u16
}

macro_rules! rgb_target {
    ($($t:ident),*) => {$(
        impl TargetColor for $t {
            const CHANNEL_MAX: [u8; 3] = [$t::MAX_R, $t::MAX_G, $t::MAX_B];
            #[inline(always)]
            fn from_channels(c: [u8; 3]) -> Self {
                $t::new(c[0], c[1], c[2])
            }
            #[inline(always)]
            fn channels(self) -> Option<[u8; 3]> {
                Some([self.r(), self.g(), self.b()])
            }
        }
    )*};
}
rgb_target!(Rgb555, Bgr555, Bgr565, Rgb666, Bgr666, Rgb888, Bgr888);

impl TargetColor for Rgb565 {
    const CHANNEL_MAX: [u8; 3] = [Rgb565::MAX_R, Rgb565::MAX_G, Rgb565::MAX_B];
    #[inline(always)]
    fn from_channels(c: [u8; 3]) -> Self {
        Rgb565::new(c[0], c[1], c[2])
    }
    #[inline(always)]
    fn channels(self) -> Option<[u8; 3]> {
        Some([self.r(), self.g(), self.b()])
    }
}

macro_rules! gray_target {
    ($($t:ident = $max:expr),*) => {$(
        impl TargetColor for $t {
            const CHANNEL_MAX: [u8; 3] = [$max, 0, 0];
            #[inline(always)]
            fn from_channels(c: [u8; 3]) -> Self {
                $t::new(c[0])
            }
            #[inline(always)]
            fn channels(self) -> Option<[u8; 3]> {
                Some([self.luma(), 0, 0])
            }
            fn vertex_channels(rgb: [u16; 3]) -> [u16; 3] {
                scale_channels([luma(rgb), 0, 0], Self::CHANNEL_MAX)
            }
        }
    )*};
}
gray_target!(Gray8 = 255, Gray4 = 15, Gray2 = 3);

impl TargetColor for BinaryColor {
    const CHANNEL_MAX: [u8; 3] = [1, 0, 0];
    #[inline(always)]
    fn from_channels(c: [u8; 3]) -> Self {
        if c[0] != 0 {
            BinaryColor::On
        } else {
            BinaryColor::Off
        }
    }
    fn vertex_channels(rgb: [u16; 3]) -> [u16; 3] {
        scale_channels([luma(rgb), 0, 0], Self::CHANNEL_MAX)
    }
    fn channels(self) -> Option<[u8; 3]> {
        Some([self.is_on() as u8, 0, 0])
    }
}

/// A "colour" that records which input triangle covers a pixel: `id + 1` of the triangle
/// (counted over the scene's objects in order, wrapping at 2¹⁶), 0 for the background. Rendering
/// into it answers "which triangle won the depth test here", for comparing pipelines.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct TriangleId(pub u32);

impl embedded_graphics_core::pixelcolor::PixelColor for TriangleId {
    type Raw = embedded_graphics_core::pixelcolor::raw::RawU32;
}

impl From<Rgb888> for TriangleId {
    fn from(c: Rgb888) -> Self {
        use embedded_graphics_core::pixelcolor::RgbColor;
        TriangleId((c.r() as u32) << 16 | (c.g() as u32) << 8 | c.b() as u32)
    }
}

impl TargetColor for TriangleId {
    fn from_channels(c: [u8; 3]) -> Self {
        TriangleId((c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32)
    }
    fn triangle_id(id: u16) -> Option<[u16; 3]> {
        let v = id as u32 + 1;
        Some([
            ((v >> 16) as u16) << 8,
            ((v >> 8) as u16 & 0xff) << 8,
            ((v & 0xff) as u16) << 8,
        ])
    }
    fn vertex_channels(rgb: [u16; 3]) -> [u16; 3] {
        rgb
    }
    fn can_dither() -> bool {
        false
    }
}

/// Converts a colour to what the target will show (through the same quantization as
/// rendering, rounding to nearest).
#[must_use]
pub fn quantize<C: TargetColor>(rgb8: [u8; 3]) -> C {
    let q = C::vertex_channels([
        (rgb8[0] as u16) << 8,
        (rgb8[1] as u16) << 8,
        (rgb8[2] as u16) << 8,
    ]);
    C::from_channels([
        ((q[0] + 128) >> 8) as u8,
        ((q[1] + 128) >> 8) as u8,
        ((q[2] + 128) >> 8) as u8,
    ])
}

pub use crate::kernel::records::BAYER;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn div255_is_exact() {
        let mut x = 0u32;
        loop {
            for v in [x, x.wrapping_add(1), x.wrapping_sub(1), x.wrapping_add(254)] {
                assert_eq!(div255(v), v / 255, "{v}");
            }
            // Every value the channel scaling uses, then a stride over the rest of u32.
            let step = if x < 65280 * 255 + 128 { 1 } else { 65_521 };
            match x.checked_add(step) {
                Some(n) => x = n,
                None => break,
            }
        }
        assert_eq!(div255(u32::MAX), u32::MAX / 255);
        // Both sides of the shift-and-add range's end, and all of its last block.
        for v in 0xff_0000..=0x100_00ffu32 {
            assert_eq!(div255(v), v / 255, "{v}");
        }
    }
    use embedded_graphics_core::pixelcolor::GrayColor;

    #[test]
    fn rgb565_rounds_not_shifts() {
        // 255·31/255 = 31; 132·31/255 = 16.05 → 16 while 132 >> 3 = 16; 140·31/255 = 17.02
        // → 17 while 140 >> 3 = 17; 4·31/255 = 0.49 → 0; 5·31/255 = 0.61 → 1 (shift gives 0).
        let c: Rgb565 = quantize([5, 255, 0]);
        assert_eq!((c.r(), c.g(), c.b()), (1, 63, 0));
        let c: Rgb565 = quantize([4, 2, 255]);
        assert_eq!((c.r(), c.g(), c.b()), (0, 0, 31));
        for v in 0..=255u8 {
            let c: Rgb565 = quantize([v, v, v]);
            let want = (v as u32 * 31 + 127) / 255;
            assert_eq!(c.r() as u32, want, "{v}");
        }
    }

    #[test]
    fn gray_uses_bt601_luma() {
        let c: Gray8 = quantize([255, 0, 0]);
        assert_eq!(c.luma(), Gray8::from(Rgb888::RED).luma());
        let c: Gray8 = quantize([10, 200, 30]);
        assert_eq!(c.luma(), Gray8::from(Rgb888::new(10, 200, 30)).luma());
    }

    #[test]
    fn rgb888_is_exact() {
        let c: Rgb888 = quantize([1, 128, 254]);
        assert_eq!(c, Rgb888::new(1, 128, 254));
        assert!(!Rgb888::can_dither());
        assert!(Rgb565::can_dither());
    }

    #[test]
    fn bayer_is_a_permutation() {
        let mut seen = [false; 16];
        for row in BAYER {
            for v in row {
                seen[v as usize] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }
}
