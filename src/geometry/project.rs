//! Perspective division and the viewport transform: clip space → snapped screen space.
//!
//! One reciprocal of w per vertex ([`Scalar::recip`]); x/w, y/w, z/w come back as signed
//! Q31.32 integers ([`Scalar::ndc`]) and everything after that is integer arithmetic shared by
//! every number type.
//!
//! Screen space: pixel (0, 0) is the top-left pixel, its centre is at (0.5, 0.5); x grows right
//! and y grows **down**. Positions are snapped to a grid of 2⁻⁴ px ([`SUBPIXEL_BITS`]).

use crate::kernel;
use crate::num::scalar::{mul_q32, Scalar, NDC_FRAC_BITS};

pub(crate) use crate::kernel::records::FLAG_MASK;
pub use crate::kernel::records::{
    ScreenVertex, COORD_LIMIT, DEPTH_FRAC_BITS, DEPTH_MAX, MAX_SCREEN, SUBPIXELS, SUBPIXEL_BITS,
};

/// Significant bits of a channel maximum (31 → 5, 63 → 6, 255 → 8, 0 → 0).
#[must_use]
pub const fn channel_bits(max: u8) -> u32 {
    8 - max.leading_zeros()
}

/// Fraction bits a channel with maximum `max` keeps in a vertex's 10-bit channel:
/// `10 − bits` (≤ 9; a channel of 0 bits is always 0).
#[must_use]
pub const fn vertex_frac_bits(max: u8) -> u32 {
    let b = channel_bits(max);
    if b == 0 {
        9
    } else {
        10 - b
    }
}

/// Channels in channel units, 8.8 (0..=`max`·256), to the vertex's 10-bit format (see
/// [`ScreenVertex::color`]), rounding to nearest: the result is at most
/// `max`·2^(10 − bits) ≤ 1020.
#[must_use]
pub fn pack_channels(rgb: [u16; 3], max: [u8; 3]) -> [u16; 3] {
    let mut out = [0u16; 3];
    for k in 0..3 {
        if max[k] == 0 {
            continue;
        }
        let bits = channel_bits(max[k]);
        let limit = (max[k] as u32) << (10 - bits);
        // 8.8 → 10 − bits fraction bits: a right shift for 2 bits and more, a left shift for a
        // 1-bit channel (BinaryColor), which keeps 9.
        let v = if bits >= 2 {
            let s = bits - 2;
            (rgb[k] as u32 + (1 << s >> 1)) >> s
        } else {
            (rgb[k] as u32) << (2 - bits)
        };
        out[k] = v.min(limit) as u16;
    }
    out
}

/// A flat (face) colour in channel units, 8.8, rounded to whole channel values and stored in
/// the vertex byte format, so that the rasterizer's rounding of the byte gives back exactly
/// the face colour rounded once.
#[must_use]
pub fn pack_flat_channels(rgb: [u16; 3], max: [u8; 3]) -> [u16; 3] {
    let mut out = [0u16; 3];
    for k in 0..3 {
        let whole = ((rgb[k] as u32 + 128) >> 8).min(max[k] as u32);
        out[k] = (whole << vertex_frac_bits(max[k])) as u16;
    }
    out
}

/// The inverse of [`pack_channels`]: vertex bytes back to channel units, 8.8 (exact).
#[must_use]
pub fn unpack_channels(rgb: [u16; 3], max: [u8; 3]) -> [u16; 3] {
    let mut out = [0u16; 3];
    for k in 0..3 {
        if max[k] != 0 {
            // A 1-bit channel (BinaryColor) was shifted left by one: shift it back.
            let bits = channel_bits(max[k]);
            out[k] = if bits >= 2 {
                rgb[k] << (bits - 2)
            } else {
                rgb[k] >> (2 - bits)
            };
        }
    }
    out
}

/// The viewport: screen size and the guard band that follows from it.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Viewport {
    /// Width in pixels (1..=[`MAX_SCREEN`]).
    pub width: u32,
    /// Height in pixels (1..=[`MAX_SCREEN`]).
    pub height: u32,
}

impl Viewport {
    /// The guard band factor G ≥ 1: vertices with `|x|, |y| ≤ G·w` project inside
    /// ±[`COORD_LIMIT`] subpixels. For 240×240, G = 7 (the band reaches 7 half-screens to each
    /// side of the centre; farther vertices are clipped). At 1024 px, G = 1.
    #[must_use]
    pub fn guard_band(&self) -> i32 {
        let m = self.width.max(self.height).max(1) as i32;
        (COORD_LIMIT / (8 * m) - 1).max(1)
    }

    /// Width / height.
    #[must_use]
    pub fn aspect<S: Scalar>(&self) -> S {
        S::from_f64(self.width as f64 / self.height.max(1) as f64)
    }

    /// Projects a clip-space point with `w > 0` inside the guard band and the near/far planes.
    /// Returns `None` when `w` is not positive (such a point must have been clipped).
    #[must_use]
    #[inline(always)]
    pub fn project<S: Scalar>(&self, p: [S; 4], rgb: [u16; 3]) -> Option<ScreenVertex> {
        if p[3].partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        let (sx, sy) = (8 * self.width, 8 * self.height);
        // The Q16.16 projection kernel where there is one, else (or where it declines) here.
        let fast = S::q16_words(&[p]).and_then(|w| kernel::project_q16(&w[0], sx, sy));
        let [x, y, z] = match fast {
            Some(words) => words,
            None => self.screen_words(p),
        };
        let mut v = ScreenVertex {
            x: x as i16,
            y: y as i16,
            z: (z >> 8) as u16,
            zf: z as u8,
            rgb_hi: [0; 3],
            flags: 0,
        };
        v.set_color(rgb);
        Some(v)
    }

    /// [`Viewport::project`] out of line, for the clipped-polygon path of the geometry stage
    /// (inlined there, it would grow that stage's deepest frame, which on a 16 KB part has no
    /// room to spare).
    #[must_use]
    #[inline(never)]
    pub(crate) fn project_out_of_line<S: Scalar>(
        &self,
        p: [S; 4],
        rgb: [u16; 3],
    ) -> Option<ScreenVertex> {
        self.project(p, rgb)
    }

    /// [`Viewport::project`]'s screen words for `w > 0`: x and y in subpixels, clamped to
    /// ±[`COORD_LIMIT`], and the depth as unsigned 16.8 (0..=65535·2⁸).
    pub(crate) fn screen_words<S: Scalar>(&self, p: [S; 4]) -> [i32; 3] {
        let [x, y, z, w] = p;
        let r = S::recip(w);
        // x_sub = (ndc_x + 1) · width/2 · 16 = ndc_x · 8·width + 8·width.
        let (sx, sy) = (8 * self.width as i64, 8 * self.height as i64);
        let nz = S::ndc(z, r);
        let lim = COORD_LIMIT as i64;
        let px = S::ndc_scaled(x, r, sx as u32, false) + sx;
        let py = S::ndc_scaled(y, r, sy as u32, true) + sy;
        let dz = (DEPTH_MAX as i64) << DEPTH_FRAC_BITS;
        let pz = mul_q32(nz.clamp(0, 1 << NDC_FRAC_BITS), dz as u32);
        // 16.12 to 16.8, rounded (at most 65535·2⁸).
        let z = (pz.clamp(0, dz) + 8) >> 4;
        [
            px.clamp(-lim, lim) as i32,
            py.clamp(-lim, lim) as i32,
            z as i32,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    fn centre_maps_to_screen_centre<S: Scalar>() {
        let vp = Viewport {
            width: 240,
            height: 160,
        };
        let o = S::ZERO;
        let v = vp
            .project([o, o, S::from_f64(0.5), S::ONE], [0; 3])
            .unwrap();
        assert_eq!((v.x, v.y), (120 * 16, 80 * 16));
        assert_eq!(v.depth(), 65535 << 11);
        // Top-left corner of the view volume is (0, 0); +y is up in clip space, down on screen.
        let v = vp.project([-S::ONE, S::ONE, o, S::ONE], [0; 3]).unwrap();
        assert_eq!((v.x, v.y, v.depth()), (0, 0, 0));
        let v = vp
            .project([S::ONE, -S::ONE, S::ONE, S::ONE], [0; 3])
            .unwrap();
        assert_eq!((v.x, v.y, v.depth()), (240 * 16, 160 * 16, 65535 << 12));
        assert!(vp.project([o, o, o, -S::ONE], [0; 3]).is_none());
    }

    #[test]
    fn viewport_mapping() {
        centre_maps_to_screen_centre::<f64>();
        centre_maps_to_screen_centre::<f32>();
        centre_maps_to_screen_centre::<Fx<I16F16>>();
    }

    #[test]
    fn guard_band_keeps_coordinates_in_range() {
        let vp = Viewport {
            width: 240,
            height: 240,
        };
        let g = vp.guard_band() as f64;
        assert_eq!(g, 7.0);
        let v = vp.project([g, -g, 0.0, 1.0f64], [0; 3]).unwrap();
        assert!(v.x as i32 <= COORD_LIMIT && v.y as i32 >= -COORD_LIMIT);
        assert_eq!((v.x, v.y), (8 * 8 * 240, 8 * 8 * 240));
        // The largest screen still has a guard band of one screen.
        let big = Viewport {
            width: 1024,
            height: 1024,
        };
        assert_eq!(big.guard_band(), 1);
        let v = big.project([-1.0, -1.0, 0.0, 1.0f64], [0; 3]).unwrap();
        assert_eq!((v.x, v.y), (0, COORD_LIMIT as i16));
        assert_eq!(core::mem::size_of::<ScreenVertex>(), 12);
    }

    #[test]
    fn channel_bytes_round_trip() {
        let max = [31, 63, 255];
        for v in [0u16, 1, 127, 128, 4000, 31 * 256] {
            let p = pack_channels([v, v.min(63 * 256), v.min(255 * 256)], max);
            let u = unpack_channels(p, max);
            assert!((u[0] as i32 - v as i32).abs() <= 4, "{v} {p:?} {u:?}");
        }
        assert_eq!(
            pack_channels([31 * 256, 63 * 256, 255 * 256], max),
            [992, 1008, 1020]
        );
        assert_eq!(pack_channels([65535; 3], max), [992, 1008, 1020]);
        let mut v = ScreenVertex {
            flags: 0x3ff,
            ..Default::default()
        };
        v.set_color([1023, 2, 513]);
        assert_eq!((v.color(), v.flags & FLAG_MASK), ([1023, 2, 513], 0x3ff));
    }
}
