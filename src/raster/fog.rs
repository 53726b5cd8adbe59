//! Fog in the spans: the scene's [`Fog`] as the Phong and textured spans apply it per lit pixel
//! or per segment end, from the depth value, kept in the attribute pool's entry 0 ([`FOG`]).

use crate::num::scalar::{mul_wide, recip_norm, Scalar};
use crate::raster::attrs::{ActiveExtra, FOG};
use crate::scene::camera::{Camera, Projection};
use crate::scene::effects::Fog;

/// The fog as spans see it (Phong and textured spans fog per lit pixel or per segment end,
/// from the depth value): the pool's entry 0 ([`FOG`]) while a frame with fog has Phong or
/// textured objects.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct FogSpan {
    /// The camera's near distance, Q16.16 world units.
    near: i32,
    /// Perspective: `(1 − near/far)·2⁵⁶/(65535·2⁸)` (the depth's step in `near/w`, Q0.24, per
    /// 16.8 depth unit, with 32 more fraction bits); 0 for an orthographic camera.
    kq: i64,
    /// Orthographic: `(far − near)` in Q16.16 per depth unit of 16.8 with 24 fraction bits
    /// (`(far − near)·2²⁴/(65535·2⁸)`), at most 2³⁸ (a depth unit times it stays within i64;
    /// beyond that, about 4·10⁶ world units, the view depth is past Q16.16 anyway); 0 for a
    /// perspective camera.
    ortho: i64,
    /// The fog's start, Q16.16 view depth.
    start: i32,
    /// `1/(fog far − fog near)` (Q16.16 units) as a normalized reciprocal: `m·2^-e`.
    inv: (i32, u32),
    color: [u8; 3],
}

impl FogSpan {
    /// From the scene's fog and camera (Q16.16 numbers saturate).
    pub(crate) fn new<S: Scalar>(fog: &Fog<S>, camera: &Camera<S>) -> Self {
        let q16 = |v: f64| libm::round(v * 65536.0).clamp(i32::MIN as f64, i32::MAX as f64);
        const D: f64 = 65535.0 * 256.0;
        let (near, far) = camera.projection.near_far();
        let (near, far) = (near.to_f64(), far.to_f64());
        let persp = matches!(camera.projection, Projection::Perspective { .. });
        let (kq, ortho) = if persp {
            (
                libm::round((1.0 - near / far) * (1u64 << 56) as f64 / D) as i64,
                0,
            )
        } else {
            (
                0,
                libm::round((far - near) * 65536.0 * (1u64 << 24) as f64 / D)
                    .min((1u64 << 38) as f64) as i64,
            )
        };
        let range = (q16(fog.far.to_f64()) - q16(fog.near.to_f64())).max(1.0);
        let (m, e) = recip_norm(range as u64);
        FogSpan {
            near: q16(near) as i32,
            kq,
            ortho,
            start: q16(fog.near.to_f64()) as i32,
            inv: (m, e),
            color: fog.color,
        }
    }

    pub(crate) fn store(&self, e: &mut ActiveExtra) {
        let c = self.color;
        e.set_words([
            self.near as i64,
            self.kq,
            self.ortho,
            self.start as i64,
            self.inv.0 as i64,
            self.inv.1 as i64,
            c[0] as i64 | (c[1] as i64) << 8 | (c[2] as i64) << 16,
            0,
            0,
        ]);
        e.kind = FOG;
    }

    /// The fog in pool entry 0, if the frame has one.
    #[inline]
    pub(crate) fn load(pool: &[ActiveExtra]) -> Option<Self> {
        Self::entry(pool).map(Self::from_entry)
    }

    /// The pool's fog entry (entry 0), if the frame has fog.
    #[inline]
    pub(crate) fn entry(pool: &[ActiveExtra]) -> Option<&ActiveExtra> {
        pool.first().filter(|e| e.kind == FOG)
    }

    /// The fog stored in entry `e` (a [`FOG`] entry).
    pub(crate) fn from_entry(e: &ActiveExtra) -> Self {
        let w = e.words();
        FogSpan {
            near: w[0] as i32,
            kq: w[1],
            ortho: w[2],
            start: w[3] as i32,
            inv: (w[4] as i32, w[5] as u32),
            color: [w[6] as u8, (w[6] >> 8) as u8, (w[6] >> 16) as u8],
        }
    }

    /// The fog colour's channel `k` (0..=255).
    pub(crate) fn channel(&self, k: usize) -> i32 {
        self.color[k] as i32
    }

    /// The fog factor (Q0.16, 0..=65536) at depth `z` (16.12, the spans' depth with its
    /// rounding bias): the view depth from the depth value (perspective: `near/(near/w)`
    /// with `near/w = 1 − d·(1 − near/far)`, one normalized reciprocal; orthographic: linear),
    /// then linear between the fog's near and far. No division.
    pub(crate) fn factor(&self, z: i32) -> i32 {
        let d = (z.max(0) >> 4) as i64; // 16.8
        let w = if self.kq != 0 {
            // near/w in Q0.24, at least 1.
            let q = ((1i64 << 24) - ((d * self.kq) >> 32)).max(1);
            let (m, e) = recip_norm(q as u64);
            // near·2^24/q in Q16.16.
            (mul_wide(self.near, m) >> (e - 24)).min(i32::MAX as i64)
        } else {
            self.near as i64 + ((d * self.ortho) >> 24)
        };
        let x = (w - self.start as i64).clamp(0, i32::MAX as i64) as i32;
        let (m, e) = self.inv;
        (mul_wide(x, m) >> (e - 16)).clamp(0, 1 << 16) as i32
    }
}
