//! The shadow map's span kinds ([`SHADOW`](crate::raster::kind::SHADOW) and its flat twin): a
//! receiver's triangle, drawn as a Gouraud or flat triangle whose pixels are darkened where
//! the map holds a caster nearer the light.
//!
//! At [`attach_shadow`] each vertex's screen point `s = (x, y, d, 1)` goes through the frame's
//! screen → map matrix ([`MapLookup::m`]) to `(X, Y, Z, W)`, homogeneous light-view
//! coordinates that are affine in the screen point, so `X`, `Y` and `Z` are screen-space
//! planes over the triangle (its pool entry's three planes, as a textured triangle's) and `W`
//! follows from a pixel's own position and depth. The four are affine along a row (the depth
//! is): a span evaluates them at its first pixel (ten 64-bit products) and reaches each
//! segment's end by additions. It finds the texel `(X/W, Y/W)` and the light depth `Z/W`
//! exactly at the ends of each segment of [`SEGMENT`] pixels (one normalized reciprocal, no
//! division) and steps them linearly between, as textured spans step their texture
//! coordinates. Per pixel that passes the depth test: three additions,
//! the texel's index (shifts and an OR), one bound test, one load, one compare, and for a
//! shadowed pixel the shadow blend's table lookups (products on a target wider than 6 bits
//! per channel, as every shadow method blends).

use crate::geometry::pool::ActiveExtra;
use crate::geometry::project::{DEPTH_FRAC_BITS, DEPTH_MAX};
use crate::kernel::div_segment;
use crate::kernel::records::SUBPIXELS;
use crate::kernel::wide::{bitlen64, mul_wide, recip_norm};
use crate::raster::layer_rows::blend;
use crate::raster::span::{by_depth_test, passes};
use crate::raster::span_map::{MapLookup, MapView, ShadowFilter, LEVEL9, MAX_BIAS};
use crate::raster::textured::set_planes;
use crate::raster::*;
use crate::scene::color::TargetColor;

/// Pixels per segment: the light coordinates are exact at each segment's ends.
pub(crate) const SEGMENT: i32 = 16;

/// Fraction bits of the light depth a span steps (Q16.14: 0..=65535 below 2³⁰).
const Z_FRAC: i32 = 14;

/// What [`attach_shadow`] did with a receiver's triangle.
pub(crate) enum Attach {
    /// Its planes are in this pool entry: it is drawn as a shadow kind.
    Slot(usize),
    /// It faces away from the light, crosses the light's plane or has no area in the map: drawn
    /// as its plain kind (a face turned away from the light is lit by ambient light only, and
    /// is not darkened again).
    Plain,
    /// The pool has no free entry: the triangle is left out and counted.
    Full,
}

/// `1/w` (`w > 0`) as `recip_norm` gives it, for [`ratio`]: one per denominator, shared by
/// the coordinates divided by it.
#[inline]
fn recip(w: i64) -> (i32, u32) {
    recip_norm(w as u64)
}

/// `num·2^frac/w` from `w`'s reciprocal `(m, e)` ([`recip`]) and one 32 × 32-bit product:
/// `num` is cut to its 31 leading bits (a relative error below 2⁻³⁰), the result saturated to
/// the `i32` range.
#[inline]
fn ratio(num: i64, (m, e): (i32, u32), frac: i32) -> i32 {
    let k = bitlen64(num.unsigned_abs()).saturating_sub(31);
    let n = (num >> k) as i32;
    let p = mul_wide(n, m);
    let sh = e as i32 - k as i32 - frac;
    let q = if sh >= 63 {
        p >> 63
    } else if sh >= 0 {
        p >> sh
    } else if sh > -32 && p.unsigned_abs() < 1u64 << (62 + sh) {
        p << -sh
    } else {
        p.signum() * i64::MAX
    };
    q.clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

/// `g·n` for `0 <= n < 16` by additions (no 64-bit product: a library call on a Cortex-M0).
#[inline]
fn times(g: i64, n: i32) -> i64 {
    let mut r = 0i64;
    for b in 0..4 {
        if n & (1 << b) != 0 {
            r = r.wrapping_add(g.wrapping_shl(b));
        }
    }
    r
}

/// Row `row` of [`MapLookup::m`] at screen point `s`: exact (each product is below 2⁶⁰ by the
/// matrix's scale, the sum below 2⁶²).
#[inline]
fn light_row(row: &[i64; 4], s: [i64; 4]) -> i64 {
    row[0] * s[0] + row[1] * s[1] + row[2] * s[2] + row[3] * s[3]
}

/// `(X, Y, Z, W)` of screen point `s` (see [`MapLookup::m`]).
#[inline]
fn light_point(m: &[[i64; 4]; 4], s: [i64; 4]) -> [i64; 4] {
    m.map(|row| light_row(&row, s))
}

/// Gives receiver triangle `t` (set up as an ordinary triangle, with the default
/// [`SpanMode`]) its light planes in a free entry of `pool`, and its depth bias:
/// [`MapLookup::bias`]'s constant plus its slope factor times the triangle's light depth
/// change across one texel (`|∂z/∂u| + |∂z/∂v|`, from its three vertices in the map), at most
/// [`MAX_BIAS`] steps.
pub(crate) fn attach_shadow(
    pool: &mut [ActiveExtra],
    t: &TriRecord,
    verts: &[crate::geometry::project::ScreenVertex],
    look: &MapLookup,
) -> Attach {
    let Some(slot) = pool
        .iter()
        .position(|e| e.kind == crate::geometry::pool::FREE)
    else {
        return Attach::Full;
    };
    let [i0, i1, i2] = t.indices();
    let p = [&verts[i0], &verts[i1], &verts[i2]];
    let l = p.map(|v| {
        let d = ((v.z as i64) << 12) | ((v.zf as i64) << 4);
        light_point(&look.m, [v.x as i64, v.y as i64, d, 1])
    });
    if l.iter().any(|l| l[3] <= 0) {
        return Attach::Plain;
    }
    // Texel coordinates (Q16.16) and light depth (Q16.14) of the vertices.
    let uvz = l.map(|l| {
        let r = recip(l[3]);
        [
            ratio(l[0], r, 16) as i128,
            ratio(l[1], r, 16) as i128,
            ratio(l[2], r, Z_FRAC) as i128,
        ]
    });
    let d = |k: usize, c: usize| uvz[k][c] - uvz[0][c];
    let det = d(1, 0) * d(2, 1) - d(2, 0) * d(1, 1);
    // Facing the light: the same turn in the map as on the screen (both drawn by the same
    // rasterizer, the map's front faces are the light's).
    let (ax, ay) = (p[0].x as i64, p[0].y as i64);
    let screen =
        (p[1].x as i64 - ax) * (p[2].y as i64 - ay) - (p[2].x as i64 - ax) * (p[1].y as i64 - ay);
    if det == 0 || screen == 0 || (det > 0) != (screen > 0) {
        return Attach::Plain;
    }
    // Light depth change per texel, |∂z/∂u| + |∂z/∂v| (Q16.14 per texel): the two numerators
    // over the one determinant, (Q14·Q16 << 16) / Q32, in one 64-bit division after both are
    // cut to the numerator's 47 leading bits.
    let sum = (d(1, 2) * d(2, 1) - d(2, 2) * d(1, 1)).unsigned_abs()
        + (d(1, 0) * d(2, 2) - d(2, 0) * d(1, 2)).unsigned_abs();
    let cut = (128 - sum.leading_zeros()).saturating_sub(47);
    let (num, den) = ((sum >> cut) as u64, (det.unsigned_abs() >> cut) as u64);
    let slope = (num << 16).checked_div(den).unwrap_or(1 << 40).min(1 << 40);
    let [b0, b1] = look.bias.map(|b| b as u64);
    let reach = look.filter.reach() as u64;
    let bias = ((b0 << Z_FRAC) + ((slope * b1 * reach) >> 8)).min((MAX_BIAS as u64) << Z_FRAC);
    // The planes of X, Y, Z, cut to 30 bits by a shift common to the three.
    let big = l
        .iter()
        .flat_map(|l| l[..3].iter())
        .map(|v| v.unsigned_abs())
        .max()
        .unwrap_or(0);
    let shift = bitlen64(big).saturating_sub(30);
    let vals = |r: usize| [l[0][r] >> shift, l[1][r] >> shift, l[2][r] >> shift];
    let e = &mut pool[slot];
    *e = ActiveExtra::EMPTY;
    if !set_planes(e, p, [vals(0), vals(1), vals(2)]) {
        *e = ActiveExtra::EMPTY;
        return Attach::Plain;
    }
    e.f = shift as u8;
    e.flat[0] = bias as i32;
    Attach::Slot(slot)
}

/// The span of a shadow kind: triangle `rec`'s pixels from column `xs` of `row` (`lc`: its left
/// edge's column), `zs` and `cs` the span's depth and colours, its planes in its pool entry,
/// the map in `map`. Returns the pixels written.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn span<C: TargetColor>(
    rec: &ActiveTri,
    pool: &[ActiveExtra],
    lc: i32,
    xs: i32,
    row: i32,
    zs: &mut [u16],
    cs: &mut [C],
    test: DepthTest,
    map: MapView<'_>,
) -> u32 {
    let Some(e) = pool.get(rec.spare as usize) else {
        return 0;
    };
    let skip = xs - lc;
    let at = |k: usize| rec.row[k].wrapping_add(rec.gx[k].wrapping_mul(skip));
    let z = at(0).clamp(0, DEPTH_MAX << DEPTH_FRAC_BITS) + (1 << (DEPTH_FRAC_BITS - 1));
    let half = 1i32 << (COLOR_FRAC_BITS - 1);
    let flat = rec.flags & FLAT != 0;
    let mut light = [[0i32; 2]; 3];
    if !flat {
        for (k, l) in light.iter_mut().enumerate() {
            let max = (C::CHANNEL_MAX[k] as i32) << COLOR_FRAC_BITS;
            *l = [at(k + 1).clamp(0, max) + half, rec.gx[k + 1]];
        }
    }
    let s = ShadowSpan {
        e,
        map,
        x0: xs,
        row,
        z: [z, rec.gx[0]],
        light,
        flat: flat.then(|| rec.flat_channels()),
    };
    // A flat triangle's loop steps no colour (on a Cortex-M0, three fewer registers).
    macro_rules! read {
        ($f:expr) => {
            if flat {
                by_depth_test!(test, T => s.fill::<C, T, $f, true>(zs, cs))
            } else {
                by_depth_test!(test, T => s.fill::<C, T, $f, false>(zs, cs))
            }
        };
    }
    if map.look.image {
        return read!(IMAGE);
    }
    match map.look.filter {
        ShadowFilter::Nearest => read!(NEAREST),
        ShadowFilter::Pcf2 => read!(PCF2),
        ShadowFilter::Pcf3 => read!(PCF3),
    }
}

/// [`ShadowSpan::fill`]'s reads of the map: [`ShadowFilter`]'s kinds as constants.
const NEAREST: u8 = 0;
const PCF2: u8 = 1;
const PCF3: u8 = 2;
/// An image's cover level (no depth).
const IMAGE: u8 = 3;

struct ShadowSpan<'a> {
    e: &'a ActiveExtra,
    map: MapView<'a>,
    /// First pixel's column and the row.
    x0: i32,
    row: i32,
    /// Depth (16.12 with the rounding bias) and its step.
    z: [i32; 2],
    /// The Gouraud channels (with the rounding half) and their steps.
    light: [[i32; 2]; 3],
    /// A flat triangle's channels.
    flat: Option<[u8; 3]>,
}

impl ShadowSpan<'_> {
    /// The light-space values at the centre of the span's first pixel, whose eye depth is `z`
    /// (16.12), and their change per pixel along the row, `gz` being the depth's: the
    /// triangle's X, Y and Z planes and the matrix's W, all affine along a row (the depth is),
    /// so that a segment's end is reached by additions. Exact: 64-bit products, ten per span.
    #[inline]
    fn light_start(&self, z: i32, gz: i32) -> ([i64; 4], [i64; 4]) {
        let e = self.e;
        let (dx, dy) = (
            (self.x0 - e.px0 as i32) as i64,
            (self.row - e.py0 as i32) as i64,
        );
        let w = &self.map.look.m[3];
        let s = [
            (self.x0 as i64) * SUBPIXELS as i64 + SUBPIXELS as i64 / 2,
            (self.row as i64) * SUBPIXELS as i64 + SUBPIXELS as i64 / 2,
            z as i64,
            1,
        ];
        let plane = |k: usize| {
            e.val[k]
                .wrapping_add(e.gx[k].wrapping_mul(dx))
                .wrapping_add(e.gy[k].wrapping_mul(dy))
        };
        (
            [plane(0), plane(1), plane(2), light_row(w, s)],
            [
                e.gx[0],
                e.gx[1],
                e.gx[2],
                w[0] * SUBPIXELS as i64 + w[2] * gz as i64,
            ],
        )
    }

    /// The light-space values `walk.0` moved `len` pixels along the row (`walk.1` per pixel),
    /// and their texel and light depth ([`ShadowSpan::light_of`]).
    #[inline(never)]
    fn advance(&self, walk: &mut ([i64; 4], [i64; 4]), len: i32) -> [i32; 3] {
        let (p, g) = walk;
        for k in 0..4 {
            p[k] = p[k].wrapping_add(if len == SEGMENT {
                g[k].wrapping_mul(SEGMENT as i64)
            } else {
                times(g[k], len)
            });
        }
        self.light_of(*p)
    }

    /// Texel coordinates (Q16.16) and light depth less the bias (Q16.14) from the light-space
    /// values `p` ([`ShadowSpan::light_start`]); a point behind the light's plane gets a texel
    /// outside the map (lit).
    #[inline]
    fn light_of(&self, p: [i64; 4]) -> [i32; 3] {
        let e = self.e;
        if p[3] <= 0 {
            return [-1 << 16, -1 << 16, 0];
        }
        let r = recip(p[3]);
        // A plane is X·2^(16 − f) (its 16 fraction bits over the values cut by f bits).
        let f = e.f as i32;
        [
            ratio(p[0], r, f),
            ratio(p[1], r, f),
            ratio(p[2], r, f - 2).saturating_sub(e.flat[0]),
        ]
    }

    /// Tests and writes the span's pixels, reading the map as `F` says ([`NEAREST`], [`PCF2`]
    /// or [`PCF3`]); returns how many it wrote.
    fn fill<C: TargetColor, const T: u8, const F: u8, const FL: bool>(
        &self,
        zs: &mut [u16],
        cs: &mut [C],
    ) -> u32 {
        let look = self.map.look;
        let texels = self.map.depth;
        let cover = self.map.cover;
        let log2n = look.log2n as u32;
        let small = C::CHANNEL_MAX.iter().all(|&m| m <= 63);
        let (sc, _) = look.shadow;
        // Channels `ch` darkened to level 1..=4.
        let dark = |ch: [u8; 3], level: usize| -> [u8; 3] {
            core::array::from_fn(|c| {
                if small {
                    look.lut[level - 1][c][ch[c] as usize & 63]
                } else {
                    blend(ch[c] as u32, sc[c] as u32, look.alphas[level] as u32) as u8
                }
            })
        };
        // A flat triangle's colour at each level (`FL`).
        let ch = self.flat.unwrap_or([0; 3]);
        let mut flat = [C::from_channels(ch); 5];
        if FL {
            for (level, c) in flat.iter_mut().enumerate().skip(1) {
                *c = C::from_channels(dark(ch, level));
            }
        }
        let n = zs.len().min(cs.len()) as i32;
        let [mut z, gz] = self.z;
        let mut l = self.light.map(|c| c[0]);
        let gl = self.light.map(|c| c[1]);
        let mut written = 0;
        let mut i = 0;
        // (In memory, advanced out of line: held in registers, the eight 64-bit values would
        // crowd the pixel loop's.)
        let mut walk = self.light_start(z, gz);
        let mut at = self.light_of(walk.0);
        while i < n {
            let len = SEGMENT.min(n - i);
            let end = self.advance(&mut walk, len);
            let step: [i32; 3] = core::array::from_fn(|k| {
                let d = end[k].wrapping_sub(at[k]);
                if len == SEGMENT {
                    d >> SEGMENT.trailing_zeros()
                } else if len > 1 {
                    div_segment(d, len)
                } else {
                    0
                }
            });
            let [mut u, mut v, mut lz] = at;
            for k in i as usize..(i + len) as usize {
                let z16 = (z >> DEPTH_FRAC_BITS) as u16;
                if passes::<T>(z16, zs[k]) {
                    let d = lz >> Z_FRAC;
                    // Whether texel (iu, iv) hides the pixel: inside the map and nearer the
                    // light (a texel outside the map is lit).
                    let hides = |iu: i32, iv: i32| -> usize {
                        (((iu | iv) as u32) >> log2n == 0
                            && d > texels[((iv as u32) << log2n | iu as u32) as usize] as i32)
                            as usize
                    };
                    let level = match F {
                        NEAREST => hides(u >> 16, v >> 16) * 4,
                        IMAGE => {
                            let (iu, iv) = (u >> 16, v >> 16);
                            if ((iu | iv) as u32) >> log2n == 0 {
                                cover[((iv as u32) << log2n | iu as u32) as usize] as usize
                            } else {
                                0
                            }
                        }
                        PCF2 => {
                            let (iu, iv) = ((u - (1 << 15)) >> 16, (v - (1 << 15)) >> 16);
                            hides(iu, iv)
                                + hides(iu + 1, iv)
                                + hides(iu, iv + 1)
                                + hides(iu + 1, iv + 1)
                        }
                        _ => {
                            let (iu, iv) = (u >> 16, v >> 16);
                            let mut count = 0;
                            for dv in -1..=1 {
                                for du in -1..=1 {
                                    count += hides(iu + du, iv + dv);
                                }
                            }
                            LEVEL9[count] as usize
                        }
                    };
                    cs[k] = if FL {
                        flat[level]
                    } else {
                        let ch = l.map(|c| (c >> COLOR_FRAC_BITS) as u8);
                        C::from_channels(if level == 0 { ch } else { dark(ch, level) })
                    };
                    zs[k] = z16;
                    written += 1;
                }
                z = z.wrapping_add(gz);
                if !FL {
                    for c in 0..3 {
                        l[c] = l[c].wrapping_add(gl[c]);
                    }
                }
                u = u.wrapping_add(step[0]);
                v = v.wrapping_add(step[1]);
                lz = lz.wrapping_add(step[2]);
            }
            i += len;
            at = end;
        }
        written
    }
}
