//! The fog's pool entry: the scene's [`Fog`] in the numbers the Phong and textured spans read
//! (`raster::fog` evaluates it per lit pixel or segment end), made by the geometry stage and
//! kept in the attribute pool's entry 0 ([`FOG`]).

use crate::geometry::pool::{ActiveExtra, FOG};
use crate::num::scalar::{recip_norm, Scalar};
use crate::scene::camera::{Camera, Projection};
use crate::scene::effects::Fog;

/// The fog as spans see it (Phong and textured spans fog per lit pixel or per segment end,
/// from the depth value): the pool's entry 0 ([`FOG`]) while a frame with fog has Phong or
/// textured objects.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct FogSpan {
    /// The camera's near distance, Q16.16 world units.
    pub(crate) near: i32,
    /// Perspective: `(1 − near/far)·2⁵⁶/(65535·2⁸)` (the depth's step in `near/w`, Q0.24, per
    /// 16.8 depth unit, with 32 more fraction bits); 0 for an orthographic camera.
    pub(crate) kq: i64,
    /// Orthographic: `(far − near)` in Q16.16 per depth unit of 16.8 with 24 fraction bits
    /// (`(far − near)·2²⁴/(65535·2⁸)`), at most 2³⁸ (a depth unit times it stays within i64;
    /// beyond that, about 4·10⁶ world units, the view depth is past Q16.16 anyway); 0 for a
    /// perspective camera.
    pub(crate) ortho: i64,
    /// The fog's start, Q16.16 view depth.
    pub(crate) start: i32,
    /// `1/(fog far − fog near)` (Q16.16 units) as a normalized reciprocal: `m·2^-e`.
    pub(crate) inv: (i32, u32),
    pub(crate) color: [u8; 3],
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
}
