//! Textured triangles: their per-vertex attributes (the vertex store's twin), their extra
//! planes while active (a pool beside the active list), and their span loop. A renderer
//! without attribute stores (`XV = XA = 0`, the default) compiles none of this into its frame
//! (every call is behind a test of those constants), so its RAM and instructions are those of
//! a renderer without textures.
//!
//! A textured triangle is set up as an ordinary (not [`FAST`]) triangle for its edges, depth
//! and lit colour, and gets three more planes in its pool entry: `Q`, proportional to `1/w`,
//! and `U = Δs·Q`, `V = Δt·Q` (the texel offsets from its first vertex), which are linear in
//! screen space. A span finds the exact texture coordinate `(U/Q, V/Q)` at the ends of each
//! segment of [`TextureMode::segment`] pixels (one normalized reciprocal, no division) and
//! steps linearly in between; [`TextureMode::Affine`] uses `Q = 1`. The cost per pixel is
//! additions, shifts and masks for the texel's address, a load, the depth test and one
//! product per channel for the lighting (a 32-bit `muls`, one cycle on a Cortex-M0+).

use crate::geometry::pool::*;
use crate::geometry::project::{
    vertex_frac_bits, ScreenVertex, DEPTH_FRAC_BITS, DEPTH_MAX, SUBPIXELS,
};
use crate::geometry::vertex_extra::{mode_of, VertexExtra};
use crate::kernel::{div_segment, TEXTURED_PIXELS_SLICED};
use crate::num::scalar::{mul_wide, recip_norm};
use crate::raster::fog::FogSpan;
use crate::raster::span::{by_depth_test, passes};
use crate::raster::*;
use crate::scene::color::TargetColor;
use crate::scene::texture::TextureMode;

/// Gives triangle `t`, just set up in `rec` (as an ordinary triangle, with the default
/// [`SpanMode`]), its planes in a free entry of `pool`: a textured triangle's texture planes,
/// a per-pixel lit one's normal and position planes. Returns the entry's index, or `None` when
/// the pool is full or the vertices' attributes are missing (the entry is then left free).
pub(crate) fn attach_textured<C: TargetColor>(
    rec: &ActiveTri,
    pool: &mut [ActiveExtra],
    t: &TriRecord,
    verts: &[ScreenVertex],
    xverts: &[VertexExtra],
) -> Option<usize> {
    let slot = pool.iter().position(|e| e.kind == FREE)?;
    let [i0, i1, i2] = t.indices();
    let x0 = xverts[(t.v[0] & !FLAT_BIT) as usize];
    let (x1, x2) = (xverts.get(i1)?, xverts.get(i2)?);
    let p = [&verts[i0], &verts[i1], &verts[i2]];
    let e = &mut pool[slot];
    *e = ActiveExtra::EMPTY;
    if x0.mode >= MODE_PHONG {
        // The normals' and positions' planes, 32 bits each; the material entry's index in
        // `key`.
        let [a, b, c] = [&x0, x1, x2].map(|x| x.phong_attributes());
        let planes = |j: usize| {
            let at = |v: &([i32; 3], [i32; 3]), k: usize| [v.0, v.1][j][k] as i64;
            [0, 1, 2].map(|k| [at(&a, k), at(&b, k), at(&c, k)])
        };
        let (mut normals, mut positions) = (ActiveExtra::EMPTY, ActiveExtra::EMPTY);
        if !set_planes(&mut normals, p, planes(0)) || !set_planes(&mut positions, p, planes(1)) {
            return None;
        }
        e.set_planes32(&normals, &positions);
        e.mode = x0.mode;
        e.key = x0.key;
        // The frame's lights entry and the point lights' right after it.
        let lights = pool.iter().position(|e| e.kind == LIGHTS);
        let points = lights
            .map(|i| i + 1)
            .filter(|&i| pool.get(i).is_some_and(|e| e.kind == POINTS));
        let e = &mut pool[slot];
        let index = |i: Option<usize>| i.map_or(-1, |i| i as i32);
        e.base = [index(lights), index(points)];
        return Some(slot);
    }
    let texture = x0.texture?;
    e.texture = Some(texture);
    e.key = x0.key;
    e.has_key = x0.has_key;
    e.mode = x0.mode;
    if rec.flags & FLAT != 0 {
        let c = p[0].color();
        for k in 0..3 {
            let f = vertex_frac_bits(C::CHANNEL_MAX[k]);
            e.flat[k] = (c[k] as i32) << (COLOR_FRAC_BITS - f);
        }
    }
    let xs = [&x0, x1, x2];
    let (wl, hl) = texture.logs();
    // Texel coordinates (Q16.16 texels, in 64 bits: |s·width| < 2³⁰·2¹⁰) and their offsets
    // from the first vertex.
    let tc = |x: &VertexExtra, k: usize| (x.st[k] as i64) << [wl, hl][k];
    let base = [tc(&x0, 0), tc(&x0, 1)];
    let d = |k: usize| [0, 1, 2].map(|i| tc(xs[i], k) - base[k]);
    let (du, dv) = (d(0), d(1));
    // Fraction bits f: the offsets in 2^-f texels below 2¹⁵ (|Δ| < 2^15 texels: UV_LIMIT).
    let m = du
        .iter()
        .chain(dv.iter())
        .map(|v| v.unsigned_abs())
        .max()
        .unwrap_or(0);
    let mut f = 15u32;
    while f > 0 && (m >> (16 - f)) >= 1 << 15 {
        f -= 1;
    }
    e.f = f as u8;
    e.base = [base[0] as i32, base[1] as i32];
    let affine = mode_of(x0.mode) == TextureMode::Affine;
    let qs = [x0.q, x1.q, x2.q].map(|q| q.max(1));
    let qmax = qs.iter().copied().max().unwrap_or(1);
    let shift = (32 - qmax.leading_zeros()).saturating_sub(15);
    let qn = qs.map(|q| {
        if affine {
            1 << 14
        } else {
            ((q >> shift).max(1)) as i64
        }
    });
    let vals = |d: [i64; 3]| [0, 1, 2].map(|i| (d[i] >> (16 - f)) * qn[i]);
    if !set_planes(e, p, [vals(du), vals(dv), qn]) {
        *e = ActiveExtra::EMPTY;
        return None;
    }
    Some(slot)
}

/// Sets `e`'s planes through the values `planes[k]` at the vertices `p` (|values| < 2³¹),
/// and marks it a triangle's entry; false for a triangle of no area.
pub(crate) fn set_planes(
    e: &mut ActiveExtra,
    p: [&ScreenVertex; 3],
    planes: [[i64; 3]; 3],
) -> bool {
    // Plane gradients per subpixel are N/det; per pixel, with 16 fraction bits,
    // 2⁴·2¹⁶·N/det, from N/det's quotient and remainder (N < 2⁴⁷, det < 2³¹: no overflow).
    let (ax, ay) = (p[0].x as i64, p[0].y as i64);
    let (dx1, dy1) = (p[1].x as i64 - ax, p[1].y as i64 - ay);
    let (dx2, dy2) = (p[2].x as i64 - ax, p[2].y as i64 - ay);
    let det = dx1 * dy2 - dx2 * dy1;
    if det == 0 {
        return false;
    }
    let (px0, py0) = (
        ax.div_euclid(SUBPIXELS as i64),
        ay.div_euclid(SUBPIXELS as i64),
    );
    // The first vertex's offset from that pixel's centre, in subpixels (|·| ≤ 8).
    let (ox, oy) = (
        SUBPIXELS as i64 * px0 + SUBPIXELS as i64 / 2 - ax,
        SUBPIXELS as i64 * py0 + SUBPIXELS as i64 / 2 - ay,
    );
    for k in 0..3 {
        let [a, b, c] = planes[k];
        let (d1, d2) = (b - a, c - a);
        let nx = d1 * dy2 - d2 * dy1;
        let ny = d2 * dx1 - d1 * dx2;
        e.gx[k] = scaled_div(nx, det, 20);
        e.gy[k] = scaled_div(ny, det, 20);
        // The value at the pixel centre: a + (nx·ox + ny·oy)/det, with 16 fraction bits.
        e.val[k] = (a << 16).wrapping_add(scaled_div(nx * ox + ny * oy, det, 16));
    }
    e.px0 = px0 as i16;
    e.py0 = py0 as i16;
    e.kind = TRI;
    true
}

/// [`span`] in a function of its own, for the cores where the pooled kinds' row calls it out of
/// line ([`kernel::TEXTURED_SPAN_OUT_OF_LINE`](crate::kernel::TEXTURED_SPAN_OUT_OF_LINE)).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn span_out_of_line<C: TargetColor>(
    rec: &ActiveTri,
    pool: &[ActiveExtra],
    lc: i32,
    xs: i32,
    row: i32,
    zs: &mut [u16],
    cs: &mut [C],
    test: DepthTest,
) -> u32 {
    span_inlined::<C>(rec, pool, lc, xs, row, zs, cs, test)
}

/// The span of the [`TEXTURED`](crate::raster::kind::TEXTURED) kind (with or without
/// [`FLAT`]): triangle `rec`'s pixels from column `xs` of `row` (`lc`: its left edge's column),
/// `zs` and `cs` the span's depth and colours, its planes in its pool entry. Returns the pixels
/// written. Where it is not called out of line (`span_out_of_line`), the compiler chooses whether
/// to inline it into the pooled kinds' row, as before that function existed (forcing it inline
/// there cost rv32imac's textured rows 1.1-3.7 %).
#[allow(clippy::too_many_arguments)]
pub(crate) fn span<C: TargetColor>(
    rec: &ActiveTri,
    pool: &[ActiveExtra],
    lc: i32,
    xs: i32,
    row: i32,
    zs: &mut [u16],
    cs: &mut [C],
    test: DepthTest,
) -> u32 {
    span_inlined::<C>(rec, pool, lc, xs, row, zs, cs, test)
}

/// [`span`]'s body, always inlined into its two callers: the out-of-line function's code is
/// then the span's as if it were marked out of line itself (through a plain call instead, the
/// Cortex-M4F's `textured_fog` row was 3.5 % dearer).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn span_inlined<C: TargetColor>(
    rec: &ActiveTri,
    pool: &[ActiveExtra],
    lc: i32,
    xs: i32,
    row: i32,
    zs: &mut [u16],
    cs: &mut [C],
    test: DepthTest,
) -> u32 {
    let Some(e) = pool.get(rec.spare as usize) else {
        return 0;
    };
    let e = *e;
    let skip = xs - lc;
    let flat = rec.flags & FLAT != 0;
    let at = |k: usize| rec.row[k].wrapping_add(rec.gx[k].wrapping_mul(skip));
    let z = at(0).clamp(0, DEPTH_MAX << DEPTH_FRAC_BITS) + (1 << (DEPTH_FRAC_BITS - 1));
    let mut light = [[0i32; 2]; 3];
    for k in 0..3 {
        let (v, g) = if flat {
            (e.flat[k], 0)
        } else {
            (at(k + 1), rec.gx[k + 1])
        };
        light[k] = modulation::<C>(k, v, g);
    }
    let fog = FogSpan::entry(pool);
    let span = TexSpan {
        e: &e,
        x0: xs,
        row,
        z: [z, rec.gx[0]],
        light,
        fog,
    };
    if fog.is_some() {
        by_depth_test!(test, T => span.fill::<C, T, true>(zs, cs))
    } else {
        by_depth_test!(test, T => span.fill::<C, T, false>(zs, cs))
    }
}

/// Texel maxima of the RGB565 channels.
const TEXEL_MAX: [i32; 3] = [31, 63, 31];

/// The modulation factor of channel `k` and its per-pixel step, from the lit value `v` and
/// gradient `g` (channel units of `C`, [`COLOR_FRAC_BITS`]): `P = 2·L/texel max` (L clamped
/// to the channel's range), so that the output channel is `(texel·P + 2²⁰) >> 21`
/// (`texel·P < 2³⁰`).
fn modulation<C: TargetColor>(k: usize, v: i32, g: i32) -> [i32; 2] {
    let max = (C::CHANNEL_MAX[k] as i32) << COLOR_FRAC_BITS;
    let t = TEXEL_MAX[k];
    [2 * v.clamp(0, max) / t, 2 * g / t]
}

struct TexSpan<'e> {
    e: &'e ActiveExtra,
    /// First pixel's column and the row.
    x0: i32,
    row: i32,
    /// Depth (16.12 with the rounding bias) and its step.
    z: [i32; 2],
    /// Modulation factors ([`modulation`]).
    light: [[i32; 2]; 3],
    /// The frame's fog entry (read by `fill::<_, _, true>` only).
    fog: Option<&'e ActiveExtra>,
}

impl TexSpan<'_> {
    /// The texture coordinates (Q16.16 texels) at the centre of pixel `x` of the row.
    #[inline]
    fn uv_at(&self, x: i32) -> [i32; 2] {
        let e = self.e;
        let (dx, dy) = ((x - e.px0 as i32) as i64, (self.row - e.py0 as i32) as i64);
        let (val, gx, gy) = (e.val, e.gx, e.gy);
        let plane = |k: usize| {
            val[k]
                .wrapping_add(gx[k].wrapping_mul(dx))
                .wrapping_add(gy[k].wrapping_mul(dy))
        };
        // Q > 0 inside the triangle; a segment end half a pixel outside stays near it.
        let q = plane(2).max(1 << 16);
        let (m, ex) = recip_norm(q as u64);
        // U/Q = (U >> 16)·m·2^(16 − ex), in Q16.16 texels: shifted by ex + f − 32 ≥ 14.
        let sh = ex + e.f as u32 - 32;
        let uv = |k: usize| {
            let h = (plane(k) >> 16).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
            (mul_wide(h, m) >> sh) as i32
        };
        [e.base[0].wrapping_add(uv(0)), e.base[1].wrapping_add(uv(1))]
    }

    /// Tests and writes the span's pixels; returns how many it wrote. With `FOG`, each
    /// pixel is mixed toward the fog colour by the fog factor, exact at the ends of each
    /// segment (from the depth) and linear between.
    fn fill<C: TargetColor, const T: u8, const FOG: bool>(
        &self,
        zs: &mut [u16],
        cs: &mut [C],
    ) -> u32 {
        let e = self.e;
        let Some(tex) = e.texture else {
            return 0;
        };
        let texels = tex.texels();
        let (wl, hl) = tex.logs();
        let key = if e.has_key { e.key as u32 } else { 1 << 16 };
        let n = zs.len().min(cs.len()) as i32;
        let seg = mode_of(e.mode).segment().unwrap_or(n.max(1));
        let fog = if FOG {
            self.fog.map(FogSpan::from_entry).unwrap_or_default()
        } else {
            FogSpan::default()
        };
        // The fog colour in the target's channel units.
        let fogc = if FOG {
            [0, 1, 2].map(|c| (fog.channel(c) * C::CHANNEL_MAX[c] as i32 * 2 + 255) / 510)
        } else {
            [0; 3]
        };
        let [mut z, gz] = self.z;
        let mut l = self.light.map(|c| c[0]);
        let gl = self.light.map(|c| c[1]);
        let mut written = 0;
        let mut i = 0;
        let mut uv = self.uv_at(self.x0);
        // Both lines cut to the span once where the pixel loop slices them: each segment's
        // slices then need no bounds check of their own. (Elsewhere left as they were: on
        // rv32imac the indexed loop over the cut lines was 5-9 % dearer.)
        let (zs, cs) = if TEXTURED_PIXELS_SLICED {
            (&mut zs[..n as usize], &mut cs[..n as usize])
        } else {
            (zs, cs)
        };
        while i < n {
            let len = seg.min(n - i);
            let end = if seg == 1 {
                uv
            } else {
                self.uv_at(self.x0 + i + len)
            };
            // A whole segment's step by a shift (16 or 8 px), a shorter one by a division.
            let step = if len == seg && seg.count_ones() == 1 {
                let sh = seg.trailing_zeros();
                [
                    end[0].wrapping_sub(uv[0]) >> sh,
                    end[1].wrapping_sub(uv[1]) >> sh,
                ]
            } else if len > 1 {
                [
                    div_segment(end[0].wrapping_sub(uv[0]), len),
                    div_segment(end[1].wrapping_sub(uv[1]), len),
                ]
            } else {
                [0, 0]
            };
            let [mut u, mut v] = uv;
            // With fog, the modulation times `1 − f` and the fog colour times `f` (`f` the fog
            // factor, Q0.16, exact at the segment's ends from the depth), each linear across
            // the segment: additions per pixel.
            let by = |a: i32, b: i32| {
                if len == seg && seg.count_ones() == 1 {
                    b.wrapping_sub(a) >> seg.trailing_zeros()
                } else if len > 1 {
                    div_segment(b.wrapping_sub(a), len)
                } else {
                    0
                }
            };
            let (mut lf, mut fa, mut dlf, mut dfa) = ([0i32; 3], [0i32; 3], [0i32; 3], [0i32; 3]);
            let l_end = [0, 1, 2].map(|c| l[c].wrapping_add(gl[c].wrapping_mul(len)));
            if FOG {
                let f0 = fog.factor(z);
                let f1 = fog.factor(z.wrapping_add(gz.wrapping_mul(len)));
                let keep = |lv: i32, f: i32| (mul_wide(lv, (1 << 16) - f) >> 16) as i32;
                for c in 0..3 {
                    lf[c] = keep(l[c], f0);
                    dlf[c] = by(lf[c], keep(l_end[c], f1));
                    // fogc·f/2¹⁶ in the output's 2²¹ units (below 2²⁷).
                    fa[c] = (fogc[c] * f0) << 5;
                    dfa[c] = by(fa[c], (fogc[c] * f1) << 5);
                }
            }
            // One pixel, its depth and colour at the places `$zk` and `$ck`: tested, written,
            // and the interpolants stepped.
            macro_rules! pixel {
                ($zk:expr, $ck:expr) => {{
                    let z16 = (z >> DEPTH_FRAC_BITS) as u16;
                    if passes::<T>(z16, $zk) {
                        let col = tex.col_index(u >> 16, wl, 0);
                        let rw = tex.col_index(v >> 16, hl, 1);
                        let texel = texels[(rw << wl) | col];
                        if texel as u32 != key {
                            let t = [
                                (texel >> 11) as i32,
                                ((texel >> 5) & 63) as i32,
                                (texel & 31) as i32,
                            ];
                            let (m, a) = if FOG { (lf, fa) } else { (l, [0; 3]) };
                            let ch = [0, 1, 2].map(|c| {
                                ((t[c] * m[c] + a[c] + (1 << 20)) >> 21)
                                    .clamp(0, C::CHANNEL_MAX[c] as i32) as u8
                            });
                            $zk = z16;
                            $ck = C::from_channels(ch);
                            written += 1;
                        }
                    }
                    z = z.wrapping_add(gz);
                    for c in 0..3 {
                        if FOG {
                            lf[c] = lf[c].wrapping_add(dlf[c]);
                            fa[c] += dfa[c];
                        } else {
                            l[c] = l[c].wrapping_add(gl[c]);
                        }
                    }
                    u = u.wrapping_add(step[0]);
                    v = v.wrapping_add(step[1]);
                }};
            }
            let (a, b) = (i as usize, (i + len) as usize);
            if TEXTURED_PIXELS_SLICED {
                // The segment's pixels as slices of both lines: no index or bounds check in
                // the loop (indexed, its index and modulation spilled on the M0: two
                // instructions more a written pixel).
                for (zk, ck) in zs[a..b].iter_mut().zip(cs[a..b].iter_mut()) {
                    pixel!(*zk, *ck);
                }
            } else {
                for x in i..i + len {
                    let k = x as usize;
                    pixel!(zs[k], cs[k]);
                }
            }
            if FOG {
                l = l_end;
            }
            i += len;
            uv = if seg == 1 && i < n {
                self.uv_at(self.x0 + i)
            } else {
                end
            };
        }
        written
    }
}

/// `n/d` rounded to nearest (halves away from zero), `d ≠ 0`.
fn round_div(n: i64, d: i64) -> i64 {
    let (q, r) = (n / d, n % d);
    if 2 * r.unsigned_abs() >= d.unsigned_abs() {
        q + if (n < 0) == (d < 0) { 1 } else { -1 }
    } else {
        q
    }
}

/// `n·2^s/det` rounded, for `|n| < 2⁵²`, `0 < |det| < 2³²` and `s ≤ 20`, without overflow:
/// the quotient shifted plus the rounded remainder's share (wrapping: a sliver's gradient may
/// exceed 2⁶³, and only its low bits are used, see [`ActiveExtra`]).
fn scaled_div(n: i64, det: i64, s: u32) -> i64 {
    let (q, r) = (n / det, n % det);
    q.wrapping_shl(s).wrapping_add(round_div(r << s, det))
}
