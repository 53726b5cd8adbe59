//! HDR lighting and tone mapping ([`ToneMap`], attached with [`crate::Effects::tone`]): the
//! lights may be brighter than white and add up beyond it; the lit value is scaled by an
//! exposure and mapped to the display by a tone curve instead of being clamped. Per vertex for
//! flat and Gouraud shading, in the number type, before the colour is stored: nothing per
//! pixel. Per pixel for Phong shading, in integers (the Phong spans' lit channel, Q8.14,
//! exposed and mapped by the same curves with a normalized reciprocal instead of a division,
//! read up to 128 × white as Q16.16 reads the per-vertex radiance).
//!
//! [`AutoExposure`] adapts the exposure over frames, as the eye adapts, from the brightness of
//! the previous frame's pixels, measured as the strips reach the display ([`Metered`]: no
//! framebuffer).

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, Point};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

use crate::num::scalar::{channel_8_8, Scalar};
use crate::scene::color::TargetColor;
use crate::scene::shade::Material;

/// Largest [`ToneMap::intensity`] and [`ToneMap::exposure`].
///
/// Range of the HDR values: the exposed radiance of a channel is computed in the number type
/// in channel units (255 = white). In Q16.16 (step 2⁻¹⁶) that holds up to 32 767, 128.5 ×
/// white: beyond it the value saturates (every operation of `Fx` does) and the curve reads
/// 128.5 × white (Reinhard 0.992, filmic 1, the clamp 1). [`ToneMap::peak`] bounds the
/// radiance of a material under a number of lights; `render --budget` checks it against this
/// range.
pub const MAX_TONE_SCALE: f64 = 16.0;

/// How radiance (in units of white, `x ≥ 0`) becomes a display value in 0..=1.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum ToneCurve {
    /// `min(x, 1)`: today's clamp (with exposure and intensity 1, exactly the image without
    /// a tone map).
    #[default]
    Clamp,
    /// Reinhard's `x / (1 + x)`: never saturates, compresses highlights.
    Reinhard,
    /// A filmic curve (Narkowicz's fit of the ACES reference curve):
    /// `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`, clamped to 1: a toe that deepens shadows
    /// and a shoulder that rolls highlights off to white.
    Filmic,
}

impl ToneCurve {
    /// The curve at `x` (units of white; negative is 0), in the number type.
    #[must_use]
    pub fn apply<S: Scalar>(self, x: S) -> S {
        let x = x.max(S::ZERO);
        let y = match self {
            ToneCurve::Clamp => x,
            ToneCurve::Reinhard => x / (S::ONE + x),
            ToneCurve::Filmic => {
                // As `x · g(x)`: the ratio `g` of two terms at least 0.03 and 0.14 keeps its
                // relative precision in fixed point where `x(2.51x + 0.03)` would be a few
                // steps of 2⁻¹⁶ (rounded that way, the curve turned down near 0).
                let k = S::from_f64;
                let g = (k(2.51) * x + k(0.03)) / (x * (k(2.43) * x + k(0.59)) + k(0.14));
                x * g
            }
        };
        y.max(S::ZERO).min(S::ONE)
    }
}

/// A scene's HDR lighting: every light (directional and point) times `intensity`, the lit
/// radiance times `exposure`, then `curve` (see [`MAX_TONE_SCALE`] for the values' range).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ToneMap<S> {
    /// Every light's brightness factor (1: as its colour says; up to [`MAX_TONE_SCALE`]).
    pub intensity: S,
    /// The exposure (radiance factor before the curve, above 0, up to [`MAX_TONE_SCALE`]).
    pub exposure: S,
    /// The tone curve.
    pub curve: ToneCurve,
}

impl<S: Scalar> ToneMap<S> {
    /// `curve` with intensity and exposure 1.
    #[must_use]
    pub const fn new(curve: ToneCurve) -> Self {
        ToneMap {
            intensity: S::ONE,
            exposure: S::ONE,
            curve,
        }
    }

    /// This tone map with exposure `e`.
    #[must_use]
    pub const fn with_exposure(self, e: S) -> Self {
        ToneMap {
            exposure: e,
            ..self
        }
    }

    /// This tone map with light intensity `i`.
    #[must_use]
    pub const fn with_intensity(self, i: S) -> Self {
        ToneMap {
            intensity: i,
            ..self
        }
    }

    /// Whether intensity and exposure are valid numbers within range (exposure above 0).
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let max = S::from_f64(MAX_TONE_SCALE);
        self.intensity.is_valid()
            && self.exposure.is_valid()
            && self.intensity >= S::ZERO
            && self.intensity <= max
            && self.exposure > S::ZERO
            && self.exposure <= max
    }

    /// An upper bound of any channel's radiance under `lights` lights of material `m`, in units
    /// of white (before the exposure): `ambient + intensity·lights·(diffuse + specular)`. What
    /// `render --budget` checks against the number type's range.
    #[must_use]
    pub fn peak(&self, m: &Material<S>, lights: usize) -> f64 {
        let f = |v: S| v.to_f64().max(0.0);
        f(m.ambient) + f(self.intensity) * lights as f64 * (f(m.diffuse) + f(m.specular))
    }

    /// The display colour (8.8 per channel) of material `m` from the lit sums: `light`
    /// (Σ diffuse·N·L·light per channel) and `spec` (Σ specular
    /// terms per channel, in channel units 0..=255): `curve(exposure · (color·(ambient +
    /// intensity·light) + intensity·spec)/255)`.
    pub(crate) fn map(&self, m: &Material<S>, light: [S; 3], spec: [S; 3]) -> [u16; 3] {
        let ambient = m.ambient;
        let mut out = [0u16; 3];
        for c in 0..3 {
            let coef = (ambient + self.intensity * light[c]) * self.exposure;
            let v = coef.mul_int(m.color[c] as i32) + self.intensity * self.exposure * spec[c];
            out[c] = match self.curve {
                // Exactly the clamp of the plain lighting (`shade::finish`).
                ToneCurve::Clamp => channel_8_8(v),
                curve => {
                    let y = curve.apply(v / S::from_i32(255));
                    channel_8_8(y.mul_int(255))
                }
            };
        }
        out
    }
}

/// Automatic exposure: after each frame, the exposure moves toward the one that would bring the
/// frame's mean luma (0..=255, measured by [`Metered`]) to `target`, by `rate` of the way. In
/// integers (Q16.16 exposure, step 2⁻¹⁶), so every core adapts alike.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct AutoExposure {
    /// The exposure, Q16.16 (1/256 to [`MAX_TONE_SCALE`]).
    exposure: u32,
    /// The mean luma aimed at, 1..=254.
    target: u8,
    /// The fraction of the way moved per frame, in 256ths (1..=256).
    rate: u16,
}

impl AutoExposure {
    /// Starts at exposure 1, aiming at mean luma `target` (clamped to 1..=254), moving `rate`
    /// 256ths of the way per frame (clamped to 1..=256).
    #[must_use]
    pub const fn new(target: u8, rate: u16) -> Self {
        let target = if target < 1 {
            1
        } else if target > 254 {
            254
        } else {
            target
        };
        let rate = if rate < 1 {
            1
        } else if rate > 256 {
            256
        } else {
            rate
        };
        AutoExposure {
            exposure: 1 << 16,
            target,
            rate,
        }
    }

    /// The exposure for the next frame, Q16.16.
    #[must_use]
    pub const fn exposure_bits(&self) -> u32 {
        self.exposure
    }

    /// The exposure for the next frame in the number type.
    #[must_use]
    pub fn exposure<S: Scalar>(&self) -> S {
        S::from_f64(self.exposure as f64 / 65536.0)
    }

    /// Adapts to a frame whose pixels had mean luma `mean` (0..=255; see [`Metered::mean`]):
    /// the exposure that would give `target` (assuming luma grows with exposure, at most 4×
    /// per frame either way) is approached by `rate`/256 of the way.
    pub fn adapt(&mut self, mean: u8) {
        let e = self.exposure as u64;
        let mean = (mean as u64).max(1);
        let goal = (e * self.target as u64 / mean).clamp(e / 4, e * 4);
        let next = if goal >= e {
            e + (goal - e) * self.rate as u64 / 256
        } else {
            e - (e - goal) * self.rate as u64 / 256
        };
        self.exposure = next.clamp(1 << 8, (MAX_TONE_SCALE as u64) << 16) as u32;
    }
}

/// A draw target that measures the luma of what passes through it to `target`: the strips of
/// a frame as the renderer hands them over (no framebuffer). Luma is BT.601's
/// ([`crate::color::luma`]) of the 8-bit channels; [`Metered::mean`] is the mean since [`Metered::reset`], of every pixel or
/// of those not in an excluded colour ([`Metered::excluding`]: the background, so that the
/// exposure follows the objects, not how much of the screen they cover).
#[derive(Debug)]
pub struct Metered<'a, D: DrawTarget> {
    target: &'a mut D,
    skip: Option<D::Color>,
    sum: u64,
    count: u64,
}

impl<'a, D: DrawTarget> Metered<'a, D> {
    /// Measures what is drawn to `target`.
    pub fn new(target: &'a mut D) -> Self {
        Metered {
            target,
            skip: None,
            sum: 0,
            count: 0,
        }
    }

    /// This meter, leaving pixels of colour `c` out of the mean.
    #[must_use]
    pub fn excluding(self, c: D::Color) -> Self {
        Metered {
            skip: Some(c),
            ..self
        }
    }

    /// The mean luma (0..=255) of the pixels drawn since the last reset (0 for none).
    #[must_use]
    pub fn mean(&self) -> u8 {
        self.sum
            .checked_div(self.count)
            .map_or(0, |m| m.min(255) as u8)
    }

    /// Starts a new measurement.
    pub fn reset(&mut self) {
        self.sum = 0;
        self.count = 0;
    }
}

/// The luma (0..=255) of `c`: [`crate::color::luma`] (BT.601, embedded-graphics' weights) of its
/// channels scaled to 8 bits, rounded (`None` for a colour without channels).
fn luma<C: TargetColor>(c: C) -> Option<u64> {
    let max = C::CHANNEL_MAX;
    let ch = c.channels()?;
    let v = |k: usize| (ch[k] as u64 * 255 + max[k] as u64 / 2) / (max[k] as u64).max(1);
    // A grey colour has one channel (`CHANNEL_MAX` `[max, 0, 0]`).
    if max[1] == 0 {
        return Some(v(0));
    }
    let l = crate::scene::color::luma([0, 1, 2].map(|k| (v(k) << 8) as u16));
    Some((l as u64 + 128) >> 8)
}

/// Adds `c`'s luma to `(sum, count)` unless it is `skip`.
fn add<C: TargetColor>(sum: &mut u64, count: &mut u64, skip: Option<C>, c: C) {
    if skip != Some(c) {
        if let Some(l) = luma(c) {
            *sum += l;
            *count += 1;
        }
    }
}

impl<D: DrawTarget> Dimensions for Metered<'_, D> {
    fn bounding_box(&self) -> Rectangle {
        self.target.bounding_box()
    }
}

impl<D: DrawTarget> DrawTarget for Metered<'_, D>
where
    D::Color: TargetColor,
{
    type Color = D::Color;
    type Error = D::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        // Measured one at a time, then forwarded in one call.
        let mut err = Ok(());
        let mut batch = [Pixel(
            Point::zero(),
            <D::Color as TargetColor>::from_channels([0; 3]),
        ); 32];
        let mut n = 0;
        for p in pixels {
            add(&mut self.sum, &mut self.count, self.skip, p.1);
            batch[n] = p;
            n += 1;
            if n == batch.len() {
                err = err.and(self.target.draw_iter(batch));
                n = 0;
            }
        }
        err.and(self.target.draw_iter(batch.into_iter().take(n)))
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        let (sum, count, skip) = (&mut self.sum, &mut self.count, self.skip);
        let mut metered = colors.into_iter().inspect(|&c| add(sum, count, skip, c));
        let r = self.target.fill_contiguous(area, metered.by_ref());
        // What the target did not read (one that discards its pixels reads none) is measured
        // too.
        metered.for_each(drop);
        r
    }
}
