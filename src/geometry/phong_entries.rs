//! The Phong pool entries: a frame's directional and point lights and an object's material
//! as the geometry stage stores them in the attribute pool ([`ActiveExtra`]'s payloads) and
//! the Phong spans load them ([`crate::raster::phong`]), with their formats.

use crate::geometry::pool::{ActiveExtra, POINTS};
use crate::scene::effects::MAX_PHONG_POINT_LIGHTS;

/// The most directional lights Phong shading takes (more are left out of it).
pub const MAX_PHONG_LIGHTS: usize = 4;

/// One light as Phong spans see it.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct PhongLight {
    /// Unit direction toward the light, world space, Q1.14.
    pub(crate) dir: [i32; 3],
    /// Light colour (0..=255 per channel).
    pub(crate) color: [u8; 3],
}

/// `c/255` in Q0.16 (0..=65536), rounded: a light channel as a fraction.
pub(crate) fn fraction(c: u8) -> i64 {
    (c as i64 * 65536 + 127) / 255
}

/// The lights of a frame for Phong spans (world space).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct PhongLights {
    pub(crate) lights: [PhongLight; MAX_PHONG_LIGHTS],
    pub(crate) count: u8,
}

/// An object's material and view direction as Phong spans see them.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct PhongMaterial {
    pub(crate) color: [u8; 3],
    /// Ambient, diffuse and specular coefficients, Q8.14 (0..=255·2¹⁴).
    pub(crate) k: [i32; 3],
    pub(crate) shininess: u8,
    /// Unit direction from the object's origin toward the eye, Q1.14.
    pub(crate) v: [i32; 3],
    /// `L·V` of each light, Q1.14.
    pub(crate) lv: [i32; MAX_PHONG_LIGHTS],
    /// The scene's tone curve ([`TONE_NONE`], [`TONE_REINHARD`], [`TONE_FILMIC`]); with a tone
    /// map, `k` holds the coefficients times the exposure (ambient) or times the intensity and
    /// the exposure (diffuse, specular).
    pub(crate) tone: u8,
    /// [`crate::Shading::Toon`]'s bands (1..=255), 0 for Phong.
    pub(crate) bands: u8,
    /// One band's step of `N·L`, [`band_step`]`(bands)`: Q1.14, 64..=2¹⁴ (step 2⁻¹⁴), worked out
    /// once per object, so that a toon span does not divide.
    pub(crate) band_step: u16,
}

/// One of `bands` equal steps of `N·L`, `⌊1/bands⌋` in Q1.14 (64..=2¹⁴; a whole step for 0 or
/// 1 band). A division: for the per-object setup ([`PhongMaterial`]), not a span.
pub(crate) const fn band_step(bands: u8) -> u16 {
    // Unsigned: a signed division would keep a panic path for `i32::MIN / -1`.
    ((ONE as u32) / if bands == 0 { 1 } else { bands as u32 }) as u16
}

/// [`PhongMaterial::tone`]: the lit channel clamped to 255 (no tone map, or the clamp curve).
pub(crate) const TONE_NONE: u8 = 0;
/// [`PhongMaterial::tone`]: Reinhard's curve on the exposed radiance.
pub(crate) const TONE_REINHARD: u8 = 1;
/// [`PhongMaterial::tone`]: the filmic curve on the exposed radiance.
pub(crate) const TONE_FILMIC: u8 = 2;

/// A point light as Phong spans see it.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct PhongPoint {
    /// Position less the eye's, world space, in units of 2^-`bits` ([`PhongPoints::bits`];
    /// clamped to ±2³⁰).
    pub(crate) pos: [i32; 3],
    /// Light colour (0..=255 per channel).
    pub(crate) color: [u8; 3],
    /// Attenuation coefficients (constant, linear, quadratic; world units), Q5.16
    /// (0..2²¹, step 2⁻¹⁶).
    pub(crate) att: [i32; 3],
}

/// The point lights of a frame for Phong spans.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct PhongPoints {
    pub(crate) lights: [PhongPoint; MAX_PHONG_POINT_LIGHTS],
    pub(crate) count: u8,
    /// Fraction bits of the positions (theirs and the vertices', `effects::position_bits`).
    pub(crate) bits: u8,
}

impl PhongPoints {
    /// Stored in pool entry `e` (see [`ActiveExtra`]'s payloads).
    pub(crate) fn store(&self, e: &mut ActiveExtra) {
        let mut w = [0i64; 9];
        let lo = |v: i32| v as u32 as i64;
        for (k, l) in self.lights.iter().enumerate() {
            let c = l.color;
            w[3 * k] = lo(l.pos[0]) | (l.pos[1] as i64) << 32;
            w[3 * k + 1] =
                lo(l.pos[2]) | (c[0] as i64) << 32 | (c[1] as i64) << 40 | (c[2] as i64) << 48;
            let a = l.att.map(|v| v.clamp(0, (1 << 21) - 1) as i64);
            w[3 * k + 2] = a[0] | a[1] << 21 | a[2] << 42;
        }
        w[8] = self.count as i64 | (self.bits as i64) << 8;
        e.set_words(w);
        e.kind = POINTS;
    }

    pub(crate) fn load(e: &ActiveExtra) -> Self {
        let w = e.words();
        let mut lights = [PhongPoint::default(); MAX_PHONG_POINT_LIGHTS];
        for (k, l) in lights.iter_mut().enumerate() {
            let (a, b, c) = (w[3 * k], w[3 * k + 1], w[3 * k + 2]);
            l.pos = [a as i32, (a >> 32) as i32, b as i32];
            l.color = [(b >> 32) as u8, (b >> 40) as u8, (b >> 48) as u8];
            l.att = [0, 21, 42].map(|s| ((c >> s) & ((1 << 21) - 1)) as i32);
        }
        PhongPoints {
            lights,
            count: (w[8] as u8).min(MAX_PHONG_POINT_LIGHTS as u8),
            bits: (w[8] >> 8) as u8,
        }
    }
}

/// Q1.14 one.
pub(crate) const ONE: i32 = 1 << 14;

pub(crate) fn pack3(v: [i32; 3]) -> i64 {
    let h = |x: i32| (x as i16 as u16) as i64;
    h(v[0]) | h(v[1]) << 16 | h(v[2]) << 32
}

pub(crate) fn unpack3(w: i64) -> [i32; 3] {
    [0, 16, 32].map(|s| (w >> s) as i16 as i32)
}

impl PhongLights {
    /// Stored in pool entry `e` (see [`ActiveExtra`]'s payloads).
    pub(crate) fn store(&self, e: &mut ActiveExtra) {
        let mut words = [0i64; 9];
        for (k, l) in self.lights.iter().enumerate() {
            words[k] = pack3(l.dir) | (l.color[0] as i64) << 48 | (l.color[1] as i64) << 56;
            // The fractions (17 bits each), computed once a frame, and the third colour.
            let f = l.color.map(fraction);
            words[4 + k] = f[0] | f[1] << 17 | f[2] << 34 | (l.color[2] as i64) << 51;
        }
        words[8] = self.count as i64;
        e.set_words(words);
    }

    /// The lights stored in `e` (the spans read them with
    /// [`crate::raster::phong::ShadeCtx::from_entries`]).
    #[cfg(test)]
    pub(crate) fn load(e: &ActiveExtra) -> Self {
        let w = e.words();
        let mut lights = [PhongLight::default(); MAX_PHONG_LIGHTS];
        for (k, l) in lights.iter_mut().enumerate() {
            l.dir = unpack3(w[k]);
            l.color = [
                (w[k] >> 48) as u8,
                (w[k] >> 56) as u8,
                (w[4 + k] >> 51) as u8,
            ];
        }
        PhongLights {
            lights,
            count: (w[8] as u8).min(MAX_PHONG_LIGHTS as u8),
        }
    }
}

impl PhongMaterial {
    pub(crate) fn store(&self, e: &mut ActiveExtra) {
        let mut words = [0i64; 9];
        words[0] = self.k[0] as i64;
        words[1] = self.k[1] as i64;
        words[2] = self.k[2] as i64;
        words[3] = self.color[0] as i64
            | (self.color[1] as i64) << 8
            | (self.color[2] as i64) << 16
            | (self.shininess as i64) << 24
            | (self.tone as i64) << 32
            | (self.bands as i64) << 40
            | (self.band_step as i64) << 48;
        words[4] = pack3(self.v);
        for k in 0..MAX_PHONG_LIGHTS {
            words[5 + k] = self.lv[k] as i64;
        }
        e.set_words(words);
    }

    pub(crate) fn load(e: &ActiveExtra) -> Self {
        let w = e.words();
        PhongMaterial {
            k: [w[0] as i32, w[1] as i32, w[2] as i32],
            color: [0, 8, 16].map(|s| (w[3] >> s) as u8),
            shininess: (w[3] >> 24) as u8,
            v: unpack3(w[4]),
            lv: [w[5] as i32, w[6] as i32, w[7] as i32, w[8] as i32],
            tone: (w[3] >> 32) as u8,
            bands: (w[3] >> 40) as u8,
            band_step: (w[3] >> 48) as u16,
        }
    }
}
