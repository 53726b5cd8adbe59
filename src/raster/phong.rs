//! Phong shading: the seeds' lighting model evaluated per pixel from the vertex normals
//! interpolated across the triangle, in integers (so the image is the same for every number
//! type and on every core). [`Shading::Phong`](crate::Shading::Phong) lights every pixel;
//! [`Shading::FastPhong`](crate::Shading::FastPhong) lights every 8th pixel of a span and
//! interpolates the colour linearly in between (Gouraud within 8-pixel segments): per pixel
//! additions only.
//!
//! Model (as the Gouraud path's, [`crate::Material`]): per channel
//! `c = material·(ambient + Σ diffuse·light/255·max(0, N·L)) + Σ specular·light·max(0, R·V)^n`,
//! clamped to 0..=255, with `N` the interpolated normal normalized per lit pixel, `L` each
//! directional light's unit direction, `R·V = 2(N·L)(N·V) − L·V`, and `V` the unit direction
//! from the object's origin toward the eye (one per object: a viewer distant compared with
//! the object; Gouraud uses the exact direction at each vertex).
//!
//! Formats: directions and normals Q1.14 (`i32`, step 2⁻¹⁴); coefficients Q8.14 (ambient,
//! diffuse and specular up to 255); the lit channel Q8.14 (0..=255·2¹⁴).

use crate::geometry::phong_entries::{
    fraction, unpack3, PhongLights, PhongMaterial, PhongPoints, MAX_PHONG_LIGHTS, ONE, TONE_NONE,
    TONE_REINHARD,
};
use crate::geometry::pool::{ActiveExtra, POINTS};
use crate::geometry::project::{DEPTH_FRAC_BITS, DEPTH_MAX};
use crate::kernel::div_segment;
use crate::num::scalar::{bitlen32, mul_wide, recip_norm};
use crate::raster::fog::FogSpan;
use crate::raster::span::{by_depth_test, passes};
use crate::raster::{ActiveTri, DepthTest, COLOR_FRAC_BITS};
use crate::scene::color::TargetColor;
use crate::scene::color::BAYER;
use crate::scene::effects::MAX_PHONG_POINT_LIGHTS;

/// White in the lit channel's format (Q8.14 channel units).
const WHITE14: i64 = 255 << 14;
/// The largest exposed radiance a tone curve reads, 128 × white (Q8.14 channel units, below
/// 2²⁹): as `Fx<I16F16>`'s per-vertex radiance, which saturates at 128.5 × white.
const HDR_MAX14: i64 = 128 * WHITE14;

/// `num/den` in Q2.30 for `0 ≤ num ≤ 1.1·den`, `den ≥ 1`, without division: both are brought
/// below 2³² together and `1/den` is a normalized reciprocal ([`recip_norm`]).
fn ratio_q30(num: u64, den: u64) -> u64 {
    let k = crate::kernel::wide::bitlen64(den.max(1)).saturating_sub(32);
    let (n, d) = (num >> k, (den >> k).max(1));
    let (m, e) = recip_norm(d);
    // n < 2^32.2 and m ≤ 2^30: the product fits; e = 29 + bitlen(d) ≥ 30.
    (n * m as u64) >> (e - 30)
}

/// The tone curve `tone` on an exposed radiance `v` (Q8.14 channel units, 255·2¹⁴ = white):
/// the display channel, Q8.14 in 0..=255·2¹⁴. Reinhard `x/(1 + x)` and the filmic
/// `x(2.51x + 0.03)/(x(2.43x + 0.59) + 0.14)` (clamped to 1) as [`crate::tone::ToneCurve`]
/// defines them, in integers: the filmic polynomials on `v/2¹⁰` (steps of 1/16 channel unit,
/// constants Q2.14).
fn tone14(v: i64, tone: u8) -> i32 {
    let v = v.clamp(0, HDR_MAX14) as u64;
    let q = if tone == TONE_REINHARD {
        ratio_q30(v, v + WHITE14 as u64)
    } else {
        let (t, w) = (v >> 10, (WHITE14 >> 10) as u64);
        // 2.51, 0.03, 2.43, 0.59, 0.14 in Q2.14; t ≤ 2^19, w = 4080: every product below 2^55.
        let num = t * (41124 * t + 492 * w);
        let den = t * (39813 * t + 9667 * w) + 2294 * w * w;
        ratio_q30(num, den)
    };
    ((q.min(1 << 30) * WHITE14 as u64) >> 30) as i32
}

/// `⌊√x⌋`, bit by bit (16 steps).
fn isqrt(x: u32) -> u32 {
    let (mut r, mut rem, mut bit) = (0u32, x, 1u32 << 30);
    while bit > rem {
        bit >>= 2;
    }
    while bit != 0 {
        if rem >= r + bit {
            rem -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    r
}

/// `b^e` for `b` in Q1.14 (0..=1), by squaring.
fn pow14(mut b: i32, mut e: u8) -> i32 {
    let mut r = ONE;
    while e > 0 {
        if e & 1 == 1 {
            r = (r * b) >> 14;
        }
        b = (b * b) >> 14;
        e >>= 1;
    }
    r
}

/// The lights and material of a span in the forms [`shade`] uses (built once per row).
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct ShadeCtx {
    /// Directions (Q1.14) and colours as fractions `light/255` (Q0.16, 0..=65536).
    dir: [[i32; 3]; MAX_PHONG_LIGHTS],
    frac: [[i32; 3]; MAX_PHONG_LIGHTS],
    /// `light` (0..=255) per channel, for the specular term.
    full: [[i32; 3]; MAX_PHONG_LIGHTS],
    lv: [i32; MAX_PHONG_LIGHTS],
    count: usize,
    v: [i32; 3],
    color: [i32; 3],
    /// Ambient, diffuse, specular (Q8.14).
    k: [i32; 3],
    shininess: u8,
    /// [`PhongMaterial::tone`].
    tone: u8,
    /// Where the specular sums saturate (Q8.14): white, or with a tone curve
    /// [`HDR_MAX14`].
    spec_cap: i32,
    /// Toon: the bands (0 for Phong) and one band's step of `N·L`, `⌊1/bands⌋` in Q1.14.
    bands: i32,
    band_step: i32,
}

/// The point lights of a span in the forms [`shade`] uses ([`PhongPoints`]), their count
/// and the positions' fraction bits.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct PointsCtx {
    points: [PointCtx; MAX_PHONG_POINT_LIGHTS],
    count: usize,
    bits: u32,
}

/// A point light in the forms [`shade`] uses.
#[derive(Copy, Clone, Debug, Default)]
struct PointCtx {
    pos: [i32; 3],
    frac: [i32; 3],
    full: [i32; 3],
    /// Q5.16.
    att: [i32; 3],
}

impl ShadeCtx {
    /// From the pool's lights entry `lights` (or none) and material entry `m`, without
    /// unpacking the lights' structure: the fractions were computed when they were stored.
    /// With toon's bands for `TOON` only: a Phong span leaves them 0 (they are read by
    /// [`band`]`::<true>` alone), so that its context costs what it did before toon (their
    /// division, now worked out per object in [`PhongMaterial::band_step`], was a library call
    /// of about 70 instructions per span on the M0: 1.4 % of fast Phong's raster stage there).
    pub(crate) fn from_entries<const TOON: bool>(
        lights: Option<&ActiveExtra>,
        m: &PhongMaterial,
    ) -> Self {
        let mut c = Self::without_bands(&PhongLights::default(), m);
        if TOON {
            c.set_bands(m);
        }
        if let Some(e) = lights {
            let w = e.words();
            c.count = (w[8] as usize).min(MAX_PHONG_LIGHTS);
            // The stored lights only ([`shade`] reads no more): a scene with one light
            // unpacks one, per span.
            for k in 0..c.count {
                c.dir[k] = unpack3(w[k]);
                c.full[k] = [
                    (w[k] >> 48) as u8,
                    (w[k] >> 56) as u8,
                    (w[4 + k] >> 51) as u8,
                ]
                .map(|x| x as i32);
                c.frac[k] = [0, 17, 34].map(|s| ((w[4 + k] >> s) & 0x1_ffff) as i32);
            }
        }
        c
    }

    /// From the lights `l` and material `m` (the unit tests'; the spans use
    /// [`ShadeCtx::from_entries`]).
    #[cfg(test)]
    pub(crate) fn new(l: &PhongLights, m: &PhongMaterial) -> Self {
        let mut c = Self::without_bands(l, m);
        c.set_bands(m);
        c
    }

    /// Toon's bands (0 for Phong) and one band's step of `N·L`, as material `m` holds them.
    #[inline(always)]
    fn set_bands(&mut self, m: &PhongMaterial) {
        self.bands = m.bands as i32;
        self.band_step = m.band_step as i32;
    }

    /// The context of the lights `l` and material `m`, toon's bands left 0. Inlined: with no
    /// lights (as [`ShadeCtx::from_entries`] calls it) its loop is constant.
    #[inline(always)]
    fn without_bands(l: &PhongLights, m: &PhongMaterial) -> Self {
        let mut c = ShadeCtx {
            count: l.count as usize,
            v: m.v,
            color: m.color.map(|x| x as i32),
            k: m.k,
            shininess: m.shininess,
            lv: m.lv,
            tone: m.tone,
            spec_cap: if m.tone == TONE_NONE {
                WHITE14
            } else {
                HDR_MAX14
            } as i32,
            ..Default::default()
        };
        for (k, pl) in l.lights.iter().enumerate() {
            c.dir[k] = pl.dir;
            c.full[k] = pl.color.map(|x| x as i32);
            c.frac[k] = pl.color.map(|x| fraction(x) as i32);
        }
        c
    }
}

impl PointsCtx {
    /// No point lights (a constant: a span without them builds nothing).
    pub(crate) const NONE: PointsCtx = PointsCtx {
        points: [PointCtx {
            pos: [0; 3],
            frac: [0; 3],
            full: [0; 3],
            att: [0; 3],
        }; MAX_PHONG_POINT_LIGHTS],
        count: 0,
        bits: 0,
    };

    /// The point lights of pool entry `e` (none when it holds none).
    pub(crate) fn load(e: Option<&ActiveExtra>) -> Self {
        let mut c = PointsCtx::default();
        if let Some(e) = e.filter(|e| e.kind == POINTS) {
            let p = PhongPoints::load(e);
            c.count = p.count as usize;
            c.bits = (p.bits as u32).min(14);
            for (x, l) in c.points.iter_mut().zip(&p.lights) {
                *x = PointCtx {
                    pos: l.pos,
                    frac: l.color.map(|v| fraction(v) as i32),
                    full: l.color.map(|v| v as i32),
                    att: l.att,
                };
            }
        }
        c
    }
}

/// The unit direction (Q1.14) toward point light `p` from position `x` (units of
/// 2^-`bits`) and the light's attenuation there (Q0.16, 0..=65536), `None` at the light.
/// No division: the direction by a normalized reciprocal of `⌊√(l·l)⌋` after scaling `l`
/// below 2¹⁴ a component, the attenuation by one of `c + l·d + q·d²` (Q16.16, at least 1).
// Inlined: with toon shading its caller has two instances, and as a function of its own it
// made the point-light Phong frames 3–6 % dearer (M0, M4F, M33).
#[inline(always)]
fn point_dir(p: &PointCtx, x: [i32; 3], bits: u32) -> Option<([i32; 3], i32)> {
    let l = [0, 1, 2].map(|k| p.pos[k].wrapping_sub(x[k]));
    let m = l.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
    if m == 0 {
        return None;
    }
    let s = bitlen32(m).saturating_sub(14);
    let ls = l.map(|v| v >> s);
    let len = isqrt((ls[0] * ls[0] + ls[1] * ls[1] + ls[2] * ls[2]) as u32).max(1);
    let (mm, ee) = recip_norm(len as u64);
    let dir = ls.map(|v| (mul_wide(v, mm) >> (ee - 14)) as i32);
    // The distance in Q16.16 world units (2^-bits units: shifted by 16 − bits).
    let d = (((len as i64) << s) << (16 - bits)).min(i32::MAX as i64) as i32;
    let [c0, c1, c2] = p.att;
    let q = (mul_wide(c2, d) >> 16).min(i32::MAX as i64) as i32;
    let den = c0 as i64 + (mul_wide(c1, d) >> 16) + (mul_wide(q, d) >> 16);
    let (am, ae) = recip_norm(den.max(1 << 16) as u64);
    // 2³²/den: `den` is at least 2¹⁶ (ae ≥ 46), and past 2⁴⁷ or so (a light far away with a
    // large attenuation) the shift passes 31 and the attenuation is 0.
    let att = am.checked_shr(ae - 32).unwrap_or(0);
    Some((dir, att.min(1 << 16)))
}

/// `N·L` (Q1.14, > 0) as the diffuse term takes it: as it is for Phong; for toon (`TOON`)
/// rounded up to the next of `c.bands` equal steps, `⌈N·L·bands⌉/bands` (the top step exactly
/// 1, the others `i·⌊1/bands⌋`, below 2⁻¹⁴ under `i/bands`).
#[inline(always)]
fn band<const TOON: bool>(nl: i32, c: &ShadeCtx) -> i32 {
    if !TOON {
        return nl;
    }
    // nl ≤ 2^14 + 2^10 and bands ≤ 255: the product fits.
    let i = (nl * c.bands + ONE - 1) >> 14;
    if i >= c.bands {
        ONE
    } else {
        i * c.band_step
    }
}

/// The specular power `p` (Q1.14, 0..=1) as the specular term takes it: as it is for Phong;
/// for toon (`TOON`) all or nothing, 1 from ½ on.
#[inline(always)]
fn hard<const TOON: bool>(p: i32) -> i32 {
    match (TOON, p >= ONE / 2) {
        (false, _) => p,
        (true, true) => ONE,
        (true, false) => 0,
    }
}

/// The lit colour (Q8.14 per channel, clamped to 0..=255) of a point with the interpolated
/// normal `n` (Q1.14, each component within ±[`NORMAL_MAX`]: at most unit length plus the
/// planes' rounding inside a triangle, [`outside`] where the point may lie outside; zero lights
/// ambient only) at position `x` (read for point lights only: `POINTS`, [`PointsCtx`]). No division: `1/|n|`
/// is a normalized reciprocal ([`recip_norm`]) of `⌊√(n·n)⌋`; 64-bit products are 32 × 32-bit
/// ones ([`mul_wide`]). `TONE`: the context's tone curve is not [`TONE_NONE`] (the span
/// chooses once which loop it runs, so that scenes without HDR test nothing per pixel).
pub(crate) fn shade<const POINTS: bool, const TOON: bool, const TONE: bool>(
    n: [i32; 3],
    x: [i32; 3],
    c: &ShadeCtx,
    pts: &PointsCtx,
) -> [i32; 3] {
    // Each component within ±NORMAL_MAX (the caller's part): each dot product with a unit
    // direction, and n·n, stays below 2^30.
    let dot = |x: [i32; 3]| n[0] * x[0] + n[1] * x[1] + n[2] * x[2];
    let len = isqrt(dot(n).max(0) as u32) as i32; // Q1.14
    let [ambient, diffuse, specular] = c.k;
    let mut light = [ambient; 3]; // Q8.14 coefficient sums
    let mut spec = [0i32; 3]; // Q8.14 channel sums
    if len > 0 {
        // N̂·X = (n·X)/|n| in Q1.14: (n·X)·m·2^-e with 1/|n| = m·2^-e.
        let (m, e) = recip_norm(len as u64);
        let unit = |s: i32| (mul_wide(s, m) >> e) as i32;
        let nv = unit(dot(c.v));
        for k in 0..c.count.min(MAX_PHONG_LIGHTS) {
            let nl = unit(dot(c.dir[k]));
            if nl <= 0 {
                continue;
            }
            // diffuse · light/255 · N·L (Q8.14; below 2^22 · 4 lights · 1).
            let d = (mul_wide(diffuse, band::<TOON>(nl, c)) >> 14) as i32;
            for ch in 0..3 {
                light[ch] += (mul_wide(d, c.frac[k][ch]) >> 16) as i32;
            }
            if specular > 0 {
                let rv = ((2 * mul_wide(nl, nv)) >> 14) as i32 - c.lv[k];
                if rv > 0 {
                    let p = hard::<TOON>(pow14(rv.min(ONE), c.shininess));
                    let p = (mul_wide(specular, p) >> 14) as i32;
                    for ch in 0..3 {
                        // Saturating: the channel is clamped at 255 (the tone curves read
                        // at most 128 × white) anyway.
                        spec[ch] = (spec[ch] + p * c.full[k][ch]).min(c.spec_cap);
                    }
                }
            }
        }
        if POINTS {
            add_points::<TOON>(&mut light, &mut spec, c, pts, x, n, (m, e), nv);
        }
    }
    debug_assert_eq!(TONE, c.tone != TONE_NONE);
    if TONE {
        return toned(c, &light, &spec);
    }
    let mut out = [0i32; 3];
    for ch in 0..3 {
        // material · (Σ), Q8.14, plus the specular sum.
        let v = mul_wide(c.color[ch], light[ch]) + spec[ch] as i64;
        out[ch] = v.clamp(0, WHITE14) as i32;
    }
    out
}

/// The largest normal component [`shade`] takes (Q1.14): 2¹⁴ + 2¹⁰.
const NORMAL_MAX: i32 = ONE + 1024;

/// A normal (Q1.14) interpolated at a point that may lie outside its triangle, clamped for
/// [`shade`]: a fast-Phong segment's end may lie a pixel past the span, where a sliver's planes
/// take any value. Inside the triangle the planes stay within a unit plus their rounding, so
/// the per-pixel loops pass their normals as they are.
#[inline(always)]
fn outside(n: [i32; 3]) -> [i32; 3] {
    n.map(|v| v.clamp(-NORMAL_MAX, NORMAL_MAX))
}

/// [`shade`]'s channels with a tone curve: `material · (Σ) + specular` exposed radiance
/// mapped by [`tone14`]. Out of line, so that the loops of scenes without a tone map compile as
/// they did.
#[inline(never)]
fn toned(c: &ShadeCtx, light: &[i32; 3], spec: &[i32; 3]) -> [i32; 3] {
    [0, 1, 2].map(|ch| tone14(mul_wide(c.color[ch], light[ch]) + spec[ch] as i64, c.tone))
}

/// Adds the point lights' terms to [`shade`]'s sums (`light`: coefficients, `spec`:
/// channels, Q8.14) for the normal `n` (clamped) with `1/|n| = m·2^-e`, `N̂·V = nv`, at
/// position `x`: as a directional light's, toward each light and scaled by its attenuation.
// Always inlined into [`shade`]: as a call (once the toned loops had their own copies of
// `shade`, LLVM stopped inlining it) point_phong cost +5.9 % on the M4F, +3.8 % on the M0.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn add_points<const TOON: bool>(
    light: &mut [i32; 3],
    spec: &mut [i32; 3],
    c: &ShadeCtx,
    pts: &PointsCtx,
    x: [i32; 3],
    n: [i32; 3],
    (m, e): (i32, u32),
    nv: i32,
) {
    let dot = |a: [i32; 3], b: [i32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let [_, diffuse, specular] = c.k;
    for p in pts.points.iter().take(pts.count) {
        let Some((dir, att)) = point_dir(p, x, pts.bits) else {
            continue;
        };
        let nl = (mul_wide(dot(n, dir), m) >> e) as i32;
        if nl <= 0 {
            continue;
        }
        let d = (mul_wide(diffuse, band::<TOON>(nl, c)) >> 14) as i32;
        let d = (mul_wide(d, att) >> 16) as i32;
        for ch in 0..3 {
            light[ch] += (mul_wide(d, p.frac[ch]) >> 16) as i32;
        }
        if specular > 0 {
            let lv = dot(dir, c.v) >> 14;
            let rv = ((2 * mul_wide(nl, nv)) >> 14) as i32 - lv;
            if rv > 0 {
                let q = hard::<TOON>(pow14(rv.min(ONE), c.shininess));
                let q = (mul_wide(specular, q) >> 14) as i32;
                let q = (mul_wide(q, att) >> 16) as i32;
                for ch in 0..3 {
                    spec[ch] = (spec[ch] + q * p.full[ch]).min(c.spec_cap);
                }
            }
        }
    }
}

/// Pixels per segment of [`crate::Shading::FastPhong`] (lit at both ends, linear between).
pub(crate) const FAST_SEGMENT: i32 = 8;

/// The factors of [`channels`]: `max·2²²/255` rounded, per channel of `C`.
fn channel_factors<C: TargetColor>() -> [i32; 3] {
    C::CHANNEL_MAX.map(|m| ((((m as u32) << 22) + 127) / 255) as i32)
}

/// The lit colour of `shade` (Q8.14, ≤ 255·2¹⁴) in the channel units of `C` with
/// [`COLOR_FRAC_BITS`]: `v·max/255·2⁶` as `v·factor/2¹⁶` (no division; the factor's rounding
/// is below 2⁻¹⁵ of a unit).
#[inline]
fn channels(v: [i32; 3], f: &[i32; 3]) -> [i32; 3] {
    [0, 1, 2].map(|c| (mul_wide(v[c], f[c]) >> 16) as i32)
}

/// The span of the Phong kinds (`raster::kind`): `kind` is one of them, and the kind's codes
/// for fast Phong (lit every [`FAST_SEGMENT`] pixels) and toon shading (dithered with
/// `dither`) come as `FAST` and `TOON` (the caller owns the codes; comparing the code here, not
/// in the caller, keeps the caller's code as measured by the ratchet). Draws triangle `rec`'s
/// pixels from column `xs` of `row` (`lc`: its left edge's column), `zs` and `cs` the span's
/// depth and colours, its planes and material in its pool entries. Returns the pixels written.
// Out of line: inlined into the pool kinds' row (`kind::pool_row`), it changed the textured
// span's code there (textured +5 % on rv32imac, with fog +1 % on the M4F).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn span<C: TargetColor, const FAST: u8, const TOON: u8>(
    rec: &ActiveTri,
    kind: u8,
    pool: &[ActiveExtra],
    lc: i32,
    xs: i32,
    row: i32,
    zs: &mut [u16],
    cs: &mut [C],
    test: DepthTest,
    dither: bool,
) -> u32 {
    let z = rec.row[0].wrapping_add(rec.gx[0].wrapping_mul(xs - lc));
    let z = z.clamp(0, DEPTH_MAX << DEPTH_FRAC_BITS) + (1 << (DEPTH_FRAC_BITS - 1));
    let seg = if kind == FAST { FAST_SEGMENT } else { 1 };
    let slot = rec.spare as usize;
    let z = [z, rec.gx[0]];
    if kind == TOON {
        return toon_span::<C>(pool, slot, dither, xs, row, z, zs, cs, test);
    }
    by_depth_test!(test, T => fill_t::<C, T, false>(pool, slot, seg, false, xs, row, z, zs, cs))
}

/// [`span`] for toon shading: out of line, so that the Phong kinds' spans compile as they did
/// before toon (inlined there, its loops changed their register allocation: in a profile of the
/// M0's fast-Phong frame, 3 more instructions a pixel in its pixel loop).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn toon_span<C: TargetColor>(
    pool: &[ActiveExtra],
    slot: usize,
    dither: bool,
    xs: i32,
    row: i32,
    z: [i32; 2],
    zs: &mut [u16],
    cs: &mut [C],
    test: DepthTest,
) -> u32 {
    let dither = dither && C::can_dither();
    by_depth_test!(test, T => fill_t::<C, T, true>(pool, slot, 1, dither, xs, row, z, zs, cs))
}

#[allow(clippy::too_many_arguments)]
fn fill_t<C: TargetColor, const T: u8, const TOON: bool>(
    pool: &[ActiveExtra],
    slot: usize,
    seg: i32,
    dither: bool,
    x0: i32,
    row: i32,
    z: [i32; 2],
    zs: &mut [u16],
    cs: &mut [C],
) -> u32 {
    let Some(e) = pool.get(slot) else {
        return 0;
    };
    let entry = |i: i32| usize::try_from(i).ok().and_then(|i| pool.get(i));
    let Some(m) = pool.get(e.key as usize).map(PhongMaterial::load) else {
        return 0;
    };
    let ctx = ShadeCtx::from_entries::<TOON>(entry(e.base[0]), &m);
    let span = Span {
        e,
        seg,
        dither,
        x0,
        row,
        z,
        ctx: &ctx,
    };
    if ctx.tone != TONE_NONE {
        return toned_fill::<C, T, TOON>(&span, pool, zs, cs);
    }
    span.fill_lit::<C, T, TOON, false>(pool, zs, cs)
}

/// [`fill_t`] for a scene with a tone curve (HDR): out of line, so that the loops of scenes
/// without one neither test the curve per pixel nor change their register allocation.
#[inline(never)]
fn toned_fill<C: TargetColor, const T: u8, const TOON: bool>(
    span: &Span,
    pool: &[ActiveExtra],
    zs: &mut [u16],
    cs: &mut [C],
) -> u32 {
    span.fill_lit::<C, T, TOON, true>(pool, zs, cs)
}

/// A Phong span's triangle entry, first pixel, row, depth (16.12 with its bias, and its step)
/// and lighting.
struct Span<'a> {
    e: &'a ActiveExtra,
    /// Pixels per lit segment: 1, or [`FAST_SEGMENT`] for fast Phong.
    seg: i32,
    /// Toon only: dither the colour into the target's channels.
    dither: bool,
    x0: i32,
    row: i32,
    z: [i32; 2],
    ctx: &'a ShadeCtx,
}

impl Span<'_> {
    /// [`Self::fill`] with the frame's point lights and fog: a frame with either takes the
    /// loop that reads the positions' planes and the fog; the others keep the loop without
    /// them.
    #[inline(always)]
    fn fill_lit<C: TargetColor, const T: u8, const TOON: bool, const TONE: bool>(
        &self,
        pool: &[ActiveExtra],
        zs: &mut [u16],
        cs: &mut [C],
    ) -> u32 {
        let e = self.e;
        let fog = FogSpan::load(pool);
        if fog.is_some() || e.base[1] >= 0 {
            let entry = usize::try_from(e.base[1]).ok().and_then(|i| pool.get(i));
            let pts = PointsCtx::load(entry);
            self.fill::<C, T, true, TOON, TONE>(&pts, fog.as_ref(), zs, cs)
        } else {
            self.fill::<C, T, false, TOON, TONE>(&PointsCtx::NONE, None, zs, cs)
        }
    }

    /// Tests and writes the span's pixels; returns how many it wrote. With `FX`, lit with the
    /// point lights `pts` at the interpolated position, and fogged by `fog`.
    fn fill<C: TargetColor, const T: u8, const FX: bool, const TOON: bool, const TONE: bool>(
        &self,
        pts: &PointsCtx,
        fog: Option<&FogSpan>,
        zs: &mut [u16],
        cs: &mut [C],
    ) -> u32 {
        let e = self.e;
        let n = zs.len().min(cs.len()) as i32;
        let seg = self.seg;
        // The planes stepped: the normal's, and with `FX` the position's (integer parts: Q1.14
        // and 2^-bits units), from the span's first pixel.
        let planes = if FX { 6 } else { 3 };
        let mut nv = [0i32; 6];
        let mut step = [0i32; 6];
        for k in 0..planes {
            nv[k] = e.plane32(k, self.x0, self.row);
            step[k] = e.step32(k);
        }
        let factors = channel_factors::<C>();
        // `ends`: a fast-Phong segment's end, which may lie past the span (see [`outside`]).
        let lit = |nv: &[i32; 6], z: i32, ends: bool| {
            let n = [nv[0] >> 16, nv[1] >> 16, nv[2] >> 16];
            let n = if ends { outside(n) } else { n };
            if !FX {
                return channels(
                    shade::<false, TOON, TONE>(n, [0; 3], self.ctx, pts),
                    &factors,
                );
            }
            let x = [nv[3] >> 16, nv[4] >> 16, nv[5] >> 16];
            let c = shade::<true, TOON, TONE>(n, x, self.ctx, pts);
            let c = match fog {
                // Toward the fog colour (Q8.14) by the factor at this depth.
                Some(f) => {
                    let t = f.factor(z) as i64;
                    [0, 1, 2].map(|k| {
                        let d = ((f.channel(k) << 14) - c[k]) as i64;
                        c[k] + ((d * t) >> 16) as i32
                    })
                }
                None => c,
            };
            channels(c, &factors)
        };
        let half = 1 << (COLOR_FRAC_BITS - 1);
        // The channels rounded (`t` = ½ unit) or dithered (toon with dithering: `t` =
        // (2·b + 1)/32 of a unit, b the pixel's Bayer entry, as the dithered Gouraud spans).
        let out =
            |c: [i32; 3], t: i32| {
                C::from_channels([0, 1, 2].map(|k| {
                    ((c[k] + t) >> COLOR_FRAC_BITS).clamp(0, C::CHANNEL_MAX[k] as i32) as u8
                }))
            };
        let bayer = &BAYER[(self.row & 3) as usize];
        let [mut z, gz] = self.z;
        let mut written = 0;
        let mut i = 0;
        if seg == 1 {
            while i < n {
                let k = i as usize;
                let z16 = (z >> DEPTH_FRAC_BITS) as u16;
                if passes::<T>(z16, zs[k]) {
                    zs[k] = z16;
                    let t = if TOON && self.dither {
                        (2 * bayer[((self.x0 + i) & 3) as usize] as i32 + 1)
                            << (COLOR_FRAC_BITS - 5)
                    } else {
                        half
                    };
                    cs[k] = out(lit(&nv, z, false), t);
                    written += 1;
                }
                z = z.wrapping_add(gz);
                for k in 0..planes {
                    nv[k] = nv[k].wrapping_add(step[k]);
                }
                i += 1;
            }
            return written;
        }
        let mut c0 = lit(&nv, z, false);
        while i < n {
            let len = seg.min(n - i);
            for k in 0..planes {
                nv[k] = nv[k].wrapping_add(step[k].wrapping_mul(len));
            }
            let c1 = lit(&nv, z.wrapping_add(gz.wrapping_mul(len)), true);
            // A whole segment's step by a shift (8 px), a shorter last one by a division
            // ([`div_segment`]: shifts and adds where the core has no divide instruction).
            let dc = [0, 1, 2].map(|k| {
                if len == FAST_SEGMENT {
                    (c1[k] - c0[k]) >> 3
                } else {
                    div_segment(c1[k] - c0[k], len)
                }
            });
            let mut c = c0;
            for x in i..i + len {
                let k = x as usize;
                let z16 = (z >> DEPTH_FRAC_BITS) as u16;
                if passes::<T>(z16, zs[k]) {
                    zs[k] = z16;
                    cs[k] = out(c, half);
                    written += 1;
                }
                z = z.wrapping_add(gz);
                for k in 0..3 {
                    c[k] += dc[k];
                }
            }
            c0 = c1;
            i += len;
        }
        written
    }
}

#[cfg(test)]
#[path = "phong_tests.rs"]
mod tests;
