//! Perspective division and the viewport transform: clip space → snapped screen space.
//!
//! One reciprocal of w per vertex ([`Scalar::recip`]); x/w, y/w, z/w come back as signed
//! Q31.32 integers ([`Scalar::ndc`]) and everything after that is integer arithmetic shared by
//! every number type.
//!
//! Screen space: pixel (0, 0) is the top-left pixel, its centre is at (0.5, 0.5); x grows right
//! and y grows **down**. Positions are snapped to a grid of 2⁻⁴ px ([`SUBPIXEL_BITS`]).

use crate::scalar::{mul_q32, Scalar, NDC_FRAC_BITS};

/// Fraction bits of snapped screen positions: 4, i.e. 1/16 px.
pub const SUBPIXEL_BITS: u32 = 4;
/// Subpixels per pixel.
pub const SUBPIXELS: i32 = 1 << SUBPIXEL_BITS;
/// Fraction bits of interpolated depth (unsigned 16.12 fixed point in an `i32`; range
/// 0..=65535·2¹² plus a half-step bias; step 2⁻¹² depth units).
pub const DEPTH_FRAC_BITS: u32 = 12;
/// Largest stored depth (the far plane).
pub const DEPTH_MAX: i32 = 65535;
/// Largest magnitude of a snapped screen coordinate, in subpixels (2²² = 262 144 px): the guard
/// band is chosen so that every projected vertex stays within it, which keeps all edge setup in
/// 32-bit integers.
pub const COORD_LIMIT: i32 = 1 << 22;
/// Largest supported screen width or height in pixels.
pub const MAX_SCREEN: usize = 2048;

/// A vertex after projection: snapped position, depth and colour.
///
/// Size: 20 bytes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct ScreenVertex {
    /// x in subpixels (signed 28.4 fixed point; |x| ≤ [`COORD_LIMIT`]).
    pub x: i32,
    /// y in subpixels, downwards (signed 28.4; |y| ≤ [`COORD_LIMIT`]).
    pub y: i32,
    /// Depth, unsigned 16.12 in an `i32`: 0 at the near plane, 65535·2¹² at the far plane.
    pub z: i32,
    /// Colour channels in the target's channel units, unsigned 8.8 (0..=65280, step 1/256).
    pub rgb: [u16; 3],
    /// Renderer bookkeeping (outcode and state bits).
    pub(crate) flags: u16,
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
    /// The guard band factor G: vertices with `|x|, |y| ≤ G·w` project inside
    /// ±[`COORD_LIMIT`] subpixels. For 240×240, G = 2183.
    #[must_use]
    pub fn guard_band(&self) -> i32 {
        let m = self.width.max(self.height).max(1) as i32;
        COORD_LIMIT / (8 * m) - 1
    }

    /// Width / height.
    #[must_use]
    pub fn aspect<S: Scalar>(&self) -> S {
        S::from_f64(self.width as f64 / self.height.max(1) as f64)
    }

    /// Projects a clip-space point with `w > 0` inside the guard band and the near/far planes.
    /// Returns `None` when `w` is not positive (such a point must have been clipped).
    #[must_use]
    pub fn project<S: Scalar>(&self, p: [S; 4], rgb: [u16; 3]) -> Option<ScreenVertex> {
        let [x, y, z, w] = p;
        if w.partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        let r = S::recip(w);
        // x_sub = (ndc_x + 1) · width/2 · 16 = ndc_x · 8·width + 8·width.
        let (sx, sy) = (8 * self.width as i64, 8 * self.height as i64);
        let nx = S::ndc(x, r);
        let ny = S::ndc(y, r);
        let nz = S::ndc(z, r);
        let lim = COORD_LIMIT as i64 + sx.max(sy);
        let px = mul_q32(nx, sx as u32) + sx;
        let py = mul_q32(-ny, sy as u32) + sy;
        let dz = (DEPTH_MAX as i64) << DEPTH_FRAC_BITS;
        let pz = mul_q32(nz.clamp(0, 1 << NDC_FRAC_BITS), dz as u32);
        Some(ScreenVertex {
            x: px.clamp(-lim, lim) as i32,
            y: py.clamp(-lim, lim) as i32,
            z: pz.clamp(0, dz) as i32,
            rgb,
            flags: 0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fx;
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
        assert_eq!(v.z, 65535 << 11);
        // Top-left corner of the view volume is (0, 0); +y is up in clip space, down on screen.
        let v = vp.project([-S::ONE, S::ONE, o, S::ONE], [0; 3]).unwrap();
        assert_eq!((v.x, v.y, v.z), (0, 0, 0));
        let v = vp
            .project([S::ONE, -S::ONE, S::ONE, S::ONE], [0; 3])
            .unwrap();
        assert_eq!((v.x, v.y, v.z), (240 * 16, 160 * 16, 65535 << 12));
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
        assert_eq!(g, 2183.0);
        let v = vp.project([g, -g, 0.0, 1.0f64], [0; 3]).unwrap();
        assert!(v.x.abs() <= COORD_LIMIT && v.y.abs() <= COORD_LIMIT);
    }
}
