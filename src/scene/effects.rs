//! Point lights and depth fog: the scene-wide effects beyond directional lights, lit per
//! vertex (flat and Gouraud shading, in the scene's number type, so that the f64 pipeline is
//! their reference) and per pixel for Phong shading (in integers, [`crate::raster::phong`]).
//!
//! A scene without them ([`crate::Scene::effects`] `None`, or empty) takes none of this code: its vertices keep the object-space lighting and the lighting
//! kernels, and its images and instruction counts do not change.

use crate::num::math::{dot, normalize, sub, Vec3};
use crate::num::scalar::Scalar;
use crate::scene::camera::Camera;
use crate::scene::shade::{add_light, finish, Material, PreparedLight};
use crate::scene::tone::ToneMap;

/// What a scene adds to its directional lights: point lights and fog, borrowed by
/// [`crate::Scene::effects`] (one pointer in the scene: a scene without them pays nothing
/// else, and its frames keep the object-space lighting and the lighting kernels).
///
/// ```
/// # use scanline3d::prelude::*;
/// # use scanline3d::Effects;
/// let lamps = [PointLight::new([1.0f32, 2.0, 1.0], [255, 220, 180]).attenuation(1.0, 0.2, 0.1)];
/// let effects = Effects {
///     point_lights: &lamps,
///     fog: Some(Fog::linear(4.0, 9.0, [150, 170, 200])),
///     tone: None,
/// };
/// # let objects: [Object<'_, f32>; 0] = [];
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0],
/// #     Projection::Perspective { fov_y: 0.8, near: 0.1, far: 10.0 }).unwrap();
/// let scene = Scene::new(&objects, camera, [Light::white([-1.0, 1.0, 1.0])]).with_effects(&effects);
/// assert_eq!(scene.point_lights().len(), 1);
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Default)]
pub struct Effects<'a, S> {
    /// The point lights (any number for flat and Gouraud shading; Phong takes the first
    /// [`MAX_PHONG_POINT_LIGHTS`]).
    pub point_lights: &'a [PointLight<S>],
    /// Linear depth fog.
    pub fog: Option<Fog<S>>,
    /// HDR lighting and tone mapping ([`crate::ToneMap`]; `None`: colours are clamped).
    pub tone: Option<crate::ToneMap<S>>,
}

/// A point light: a position in world space, a colour and a distance attenuation.
///
/// At a point at distance `d` from the light, the light's colour is scaled by
/// `1 / max(1, c + l·d + q·d²)` with `[c, l, q]` = [`PointLight::attenuation`], and its
/// direction is the unit vector toward [`PointLight::position`]. The `max(1, ·)` keeps the
/// factor at most 1: a light is never brighter than its colour, and a light close to a
/// surface (or coefficients that sum to less than 1) cannot overflow a channel's range.
/// Negative coefficients are used as zero.
///
/// Flat and Gouraud shading light per face or per vertex (any number of point lights);
/// Phong shading per pixel, up to [`MAX_PHONG_POINT_LIGHTS`] (more are left out of Phong
/// objects, lit as if absent). A point light is about three times the cost of a directional
/// light per lit vertex (a normalization, a square root and a division): see `BENCHMARKS.md`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct PointLight<S> {
    /// World-space position.
    pub position: Vec3<S>,
    /// Light colour, 8 bits per channel (255 = full intensity).
    pub color: [u8; 3],
    /// Attenuation coefficients `[constant, linear, quadratic]` (world units; `[1, 0, 0]`:
    /// no attenuation).
    pub attenuation: [S; 3],
}

/// The most point lights a Phong object is lit by (the first ones of the scene's list).
pub const MAX_PHONG_POINT_LIGHTS: usize = 2;

impl<S: Scalar> PointLight<S> {
    /// A light of colour `color` at `position`, without attenuation.
    #[must_use]
    pub fn new(position: Vec3<S>, color: [u8; 3]) -> Self {
        PointLight {
            position,
            color,
            attenuation: [S::ONE, S::ZERO, S::ZERO],
        }
    }

    /// This light with attenuation `1 / max(1, constant + linear·d + quadratic·d²)`.
    #[must_use]
    pub fn attenuation(self, constant: S, linear: S, quadratic: S) -> Self {
        PointLight {
            attenuation: [constant, linear, quadratic],
            ..self
        }
    }

    /// Whether every number of the light is valid (not NaN, infinite or at a fixed-point
    /// rail): a frame skips and counts every object when one is not, as for a directional
    /// light.
    pub(crate) fn is_valid(&self) -> bool {
        self.position
            .iter()
            .chain(self.attenuation.iter())
            .all(|v| v.is_valid())
    }

    /// The light as a directional one at world point `p`: the unit direction toward it and
    /// its colour scaled by the attenuation at its distance.
    pub(crate) fn at(&self, p: Vec3<S>) -> PreparedLight<S> {
        let l = sub(self.position, p);
        let dir = normalize(l);
        // |l| from the unit direction (no square of |l|, which would saturate Q16.16 beyond
        // 181 units).
        let d = dot(l, dir).max(S::ZERO);
        let [c, k1, k2] = self.attenuation.map(|v| v.max(S::ZERO));
        let den = (c + k1 * d + k2 * d * d).max(S::ONE);
        PreparedLight::scaled(dir, self.color, S::ONE / den)
    }
}

/// Linear depth fog: a point at view depth `z` (distance along the camera's view direction)
/// is mixed toward [`Fog::color`] by `f = clamp((z − near)/(far − near), 0, 1)`:
/// `colour·(1 − f) + fog·f`. No fog before `near`, only fog beyond `far`.
///
/// Flat shading fogs each face at its centroid, Gouraud each vertex (the colours are then
/// interpolated: no per-pixel cost); Phong and textured spans fog at the pixels they light
/// or at the ends of their segments, from the depth buffer's value.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Fog<S> {
    /// View depth where the fog starts (world units).
    pub near: S,
    /// View depth where the fog hides everything (world units; above `near`).
    pub far: S,
    /// Fog colour, 8 bits per channel.
    pub color: [u8; 3],
}

impl<S: Scalar> Fog<S> {
    /// Fog from view depth `near` to `far`, toward `color`.
    #[must_use]
    pub fn linear(near: S, far: S, color: [u8; 3]) -> Self {
        Fog { near, far, color }
    }

    /// Whether the fog's numbers are valid and `near < far`.
    pub(crate) fn is_valid(&self) -> bool {
        self.near.is_valid() && self.far.is_valid() && self.near < self.far
    }

    /// The fog factor at view depth `z`, Q0.16 (0..=65536).
    pub(crate) fn factor(&self, z: S) -> i32 {
        let f = (z - self.near) / (self.far - self.near);
        f.max(S::ZERO)
            .min(S::ONE)
            .to_fixed_i32(16)
            .clamp(0, 1 << 16)
    }

    /// Colour `c` (8.8 per channel, 0..=65280) fogged at view depth `z`.
    pub(crate) fn apply(&self, c: [u16; 3], z: S) -> [u16; 3] {
        mix_8_8(c, self.color, self.factor(z))
    }
}

/// `c·(1 − f) + fog·f` for a colour `c` in 8.8 per channel and `f` in Q0.16, rounded.
pub(crate) fn mix_8_8(c: [u16; 3], fog: [u8; 3], f: i32) -> [u16; 3] {
    let f = f.clamp(0, 1 << 16) as i64;
    [0, 1, 2].map(|k| {
        let (a, b) = (c[k] as i64, (fog[k] as i64) << 8);
        (a + (((b - a) * f + (1 << 15)) >> 16)) as u16
    })
}

/// The fraction bits of the positions Phong spans interpolate for point lights (world
/// position less the eye's, as `i16`): the most for which a point twice the camera's far
/// distance from the eye fits (0..=14).
pub(crate) fn position_bits<S: Scalar>(camera: &Camera<S>) -> u32 {
    let far = camera.projection.near_far().1.to_f64();
    let mut e = 14;
    while e > 0 && 2.0 * far * (1u32 << e) as f64 > 32767.0 {
        e -= 1;
    }
    e
}

/// [`lit_color`](crate::scene::shade::lit_color) with point lights too, at world point `p`
/// ([`PointLight::at`]), and the scene's tone map. Here, with the effects it combines, so that
/// the shading of a material imports no effect (no shade ↔ effects ↔ tone cycle).
pub(crate) fn lit_color_points<S: Scalar>(
    m: &Material<S>,
    lights: &[PreparedLight<S>],
    points: &[PointLight<S>],
    n: Vec3<S>,
    p: Vec3<S>,
    to_eye: Vec3<S>,
    tone: Option<&ToneMap<S>>,
) -> [u16; 3] {
    // With a tone map the lights' sums start at zero: the ambient term is not scaled by the
    // lights' intensity.
    let start = if tone.is_some() { S::ZERO } else { m.ambient };
    let mut sums = ([start; 3], [S::ZERO; 3]);
    for l in lights {
        add_light(&mut sums, m, l, n, to_eye);
    }
    for pl in points {
        add_light(&mut sums, m, &pl.at(p), n, to_eye);
    }
    match tone {
        Some(t) => t.map(m, sums.0, sums.1),
        None => finish(m, sums),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    fn attenuates<S: Scalar>() {
        let l = PointLight::new([0.0, 0.0, 4.0].map(S::from_f64), [200, 100, 50]).attenuation(
            S::ONE,
            S::from_f64(0.5),
            S::from_f64(0.25),
        );
        // d = 4: 1 + 2 + 4 = 7.
        let p = l.at([S::ZERO; 3]);
        assert!((p.dir()[2].to_f64() - 1.0).abs() < 1e-3);
        let want = 200.0 / 255.0 / 7.0;
        assert!(
            (p.frac_of(0).to_f64() - want).abs() < 1e-3,
            "{}",
            p.frac_of(0).to_f64()
        );
        // Where the denominator is below 1 the factor stops at 1.
        let near = l.attenuation(S::from_f64(0.25), S::from_f64(0.1), S::ZERO);
        let q = near.at([0.0, 0.0, 3.5].map(S::from_f64));
        assert!((q.frac_of(0).to_f64() - 200.0 / 255.0).abs() < 1e-3);
        // Far away (beyond Q16.16's range of d²) it fades to nothing, without overflow.
        let far = l.at([0.0, 0.0, -3000.0].map(S::from_f64));
        assert!(far.frac_of(0).to_f64() < 1e-4);
    }

    #[test]
    fn attenuation_for_every_type() {
        attenuates::<f64>();
        attenuates::<f32>();
        attenuates::<Fx<I16F16>>();
    }

    #[test]
    fn fog_mixes_linearly_between_near_and_far() {
        let f = Fog::linear(2.0f64, 6.0, [255, 0, 128]);
        let c = [100 << 8, 200 << 8, 0];
        assert_eq!(f.apply(c, 1.0), c);
        assert_eq!(f.apply(c, 7.0), [255 << 8, 0, 128 << 8]);
        // A quarter of the way: 100 + 155/4 = 138.75, 200 − 50, 32 (8.8).
        assert_eq!(f.apply(c, 3.0), [35520, 38400, 8192]);
        type Q = Fx<I16F16>;
        let q = Fog::linear(Q::lit(2.0), Q::lit(6.0), [255, 0, 128]);
        assert_eq!(q.apply(c, Q::lit(3.0)), [35520, 38400, 8192]);
        assert!(!Fog::linear(2.0f64, 2.0, [0; 3]).is_valid());
    }
}
