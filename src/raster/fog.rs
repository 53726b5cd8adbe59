//! Fog in the spans: the fog entry ([`FogSpan`], made by the geometry stage) as the Phong and
//! textured spans apply it per lit pixel or per segment end, from the depth value.

pub(crate) use crate::geometry::fog::FogSpan;
use crate::num::scalar::{mul_wide, recip_norm};

impl FogSpan {
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
