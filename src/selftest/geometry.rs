//! The geometry kernels against their portable twins: the vertex run, the lighting run, the
//! cull loop and the projection.

use super::*;

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly vertex run (`kernel::project_run`) against [`vertex_record`] on `n` pseudo-random objects of 16 positions:
/// matrices and positions from small to near the transform's range, w from negative to
/// large, points inside and outside the x/y planes, the guard band and the near and far
/// planes. Runs until every position is done, taking each declined one itself; returns the
/// first object with a differing record, as its seed.
#[doc(hidden)]
pub fn vertex_self_test(n: u32) -> Option<u32> {
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;
    type Q = Fx<I16F16>;
    let q = |b: i32| Fx(I16F16::from_bits(b));
    let mut seeds = xorshift32(0xa54f_f53a);
    for _ in 0..n {
        let seed = seeds();
        let mut next = xorshift32(seed | 1);
        let mut val = |max_bits: u32| signed_bits(&mut next, max_bits);
        let mut m = Mat4::<Q>::identity();
        for row in m.m.iter_mut() {
            for e in row.iter_mut() {
                *e = q(val(if seed % 5 == 0 { 31 } else { 20 }));
            }
        }
        let size = [(240, 240), (64, 48), (1024, 1024), (320, 200)][(seed >> 8) as usize % 4];
        let vp = Viewport {
            width: size.0,
            height: size.1,
        };
        let g = Q::from_i32(vp.guard_band());
        let mut ps = [[Q::ZERO; 3]; 16];
        for p in &mut ps {
            *p = [0; 3].map(|_| q(val(if seed % 7 == 0 { 31 } else { 19 })));
        }
        let (sx, sy) = (8 * vp.width, 8 * vp.height);
        let mut out = Vec::<ScreenVertex, 16>::new();
        let mut i = 0;
        while i < ps.len() {
            let words = |v: &[[Q; 3]]| {
                v.iter()
                    .map(|p| p.map(|c| c.to_bits()))
                    .collect::<Vec<_, 16>>()
            };
            let mw = m.m.map(|r| r.map(|c| c.to_bits()));
            let run = kernel::project_run(&mw, &words(&ps[i..]), g.to_bits(), sx, sy, &mut out);
            for k in 0..run {
                if out.get(i + k) != Some(&vertex_record(&m, &vp, g, ps[i + k])) {
                    return Some(seed);
                }
            }
            i += run;
            if let Some(&p) = ps.get(i) {
                let _ = out.push(vertex_record(&m, &vp, g, p));
                i += 1;
            }
        }
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly lighting run
/// (`kernel::light_run`) against the portable lighting of the pass
/// (`lit_diffuse`, RGB565 scaling and packing, `set_color`, `LIT`) on `n` pseudo-random
/// objects of 16 vertices: marked, lit and unmarked vertices with any other flag and colour
/// bits; normals and light directions from tiny to beyond the routine's range; diffuse
/// coefficients and colour fractions near and beyond it, ambient terms of every sign and size
/// (sums that saturate included), material colours 0..=255. Runs until every vertex is done,
/// lighting each declined one itself; returns the first object with a differing record, as its
/// seed.
#[doc(hidden)]
pub fn light_self_test(n: u32) -> Option<u32> {
    use crate::num::scalar::Fx;
    use crate::scene::shade::Material;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use fixed::types::I16F16;
    type Q = Fx<I16F16>;
    let q = |b: i32| Fx(I16F16::from_bits(b));
    let max = <Rgb565 as TargetColor>::CHANNEL_MAX;
    let mut seeds = xorshift32(0x1d87_2b41);
    for _ in 0..n {
        let seed = seeds();
        let mut next = xorshift32(seed | 1);
        let mut val = |max_bits: u32| signed_bits(&mut next, max_bits);
        let big = seed % 7 == 0;
        let dir = [0; 3].map(|_| q(val(if big { 24 } else { 17 })));
        let frac = q(val(if big { 25 } else { 17 }));
        // Ambient terms next to either end of the range make the ambient sum saturate.
        let ambient = match seed % 11 {
            0 => i32::MAX - (val(24) & 0x7f_ffff),
            1 => i32::MIN + (val(24) & 0x7f_ffff),
            _ => val(if big { 31 } else { 18 }),
        };
        let mut m = Material::matte([0; 3], q(ambient), q(val(24)));
        m.color = [0; 3].map(|_| (val(8) & 0xff) as u8);
        let light = [PreparedLight::grey_raw(dir, frac)];
        let mut normals = [[Q::ZERO; 3]; 16];
        let mut verts = [ScreenVertex::default(); 16];
        for (nv, v) in normals.iter_mut().zip(verts.iter_mut()) {
            *nv = [0; 3].map(|_| q(val(if seed % 5 == 0 { 24 } else { 17 })));
            let r = val(16) as u16;
            v.rgb_hi = [r as u8, (r >> 8) as u8, r as u8 ^ 0x5a];
            v.flags = r;
        }
        // The pass's portable lighting of one vertex.
        let portable = |v: &mut ScreenVertex, nv: [Q; 3]| {
            if v.flags & (LIT | NEEDS_LIGHT) == NEEDS_LIGHT {
                v.set_color(pack_channels(
                    Rgb565::vertex_channels(lit_diffuse(&m, &light, nv)),
                    max,
                ));
                v.flags |= LIT;
            }
        };
        let mut want = verts;
        for (v, &nv) in want.iter_mut().zip(&normals) {
            portable(v, nv);
        }
        let mut i = 0;
        while i < verts.len() {
            let nw: Vec<[i32; 3], 16> = normals[i..]
                .iter()
                .map(|n| n.map(|c| c.to_bits()))
                .collect();
            let run = kernel::light_run(
                &mut verts[i..],
                &nw,
                dir.map(|c| c.to_bits()),
                frac.to_bits(),
                m.ambient.to_bits(),
                m.diffuse.to_bits(),
                m.color,
            );
            i += run.unwrap_or(0);
            if let (Some(v), Some(&nv)) = (verts.get_mut(i), normals.get(i)) {
                portable(v, nv);
            }
            i += 1;
        }
        if verts != want {
            return Some(seed);
        }
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly triangle loop
/// (`kernel::cull_push`) against the portable `kernel::portable::cull_push` on `n` pseudo-random objects of
/// 24 triangles over 16 vertices (indices out of range, invalid, clipped, outside, unlit and
/// lit vertices; coordinates across the whole range and near one another; off-screen, empty
/// and degenerate triangles; a store that fills up; viewports of every height up to 64 rows).
/// Both are run to the end, skipping each triangle they stop at; returns the first object
/// whose stops, store, row counts, counts or vertex marks differ, as its seed.
#[doc(hidden)]
pub fn cull_self_test(n: u32) -> Option<u32> {
    const ROWS: usize = 64;
    let mut seeds = xorshift32(0x3c6e_f372);
    for _ in 0..n {
        let seed = seeds();
        let mut next = xorshift32(seed | 1);
        let spread = [
            40,
            400,
            4000,
            2 * crate::geometry::project::COORD_LIMIT as u32,
        ][(next() % 4) as usize];
        let mut verts = [ScreenVertex::default(); 16];
        for v in &mut verts {
            let r = next();
            let c = |h: u32| {
                let v = (h % spread) as i32 - spread as i32 / 2 + 1000;
                v.clamp(
                    -crate::geometry::project::COORD_LIMIT,
                    crate::geometry::project::COORD_LIMIT,
                ) as i16
            };
            v.x = c(r & 0xffff);
            v.y = c(r >> 16);
            let f = next();
            // Outcode bits now and then, the clipper's and invalid rarely, lit mostly.
            let mut flags = if f % 4 == 0 {
                (f >> 8) as u16 & 0x3f
            } else {
                0
            };
            if f % 23 == 0 {
                flags |= 1 << (4 + (f >> 16) % 4);
            }
            if f % 5 != 0 {
                // A lit vertex's colour bits are anything; an unlit one's are zero.
                flags |= LIT | (f >> 16) as u16 & !crate::geometry::project::FLAG_MASK;
            }
            v.flags = flags;
        }
        let mut tris = [[0u16; 3]; 24];
        for t in &mut tris {
            let r = next();
            *t = [r % 17, (r >> 8) % 17, (r >> 16) % 17].map(|i| i as u16);
        }
        let view = (
            1 + (next() % 300) as usize,
            1 + (next() % ROWS as u32) as usize,
        );
        let base = (next() % 1000) as u16;
        let mut runs = [(); 2].map(|_| {
            (
                verts,
                Vec::<TriRecord, 8>::new(),
                [0u16; ROWS],
                [0i16; ROWS],
                CullCounts::default(),
                0usize,
                0u32,
            )
        });
        for (which, (vs, store, heads, starts, counts, needed, stops)) in
            runs.iter_mut().enumerate()
        {
            let mut k = 0;
            for _ in 0..64 {
                let bins = Bins {
                    store,
                    heads,
                    starts,
                    view,
                };
                let stop = if which == 0 {
                    kernel::cull_push(&tris, &mut k, vs, base, bins, counts, needed)
                } else {
                    kernel::portable::cull_push(&tris, &mut k, vs, base, bins, counts, needed)
                };
                *stops = stops
                    .wrapping_mul(31)
                    .wrapping_add(stop as u32 * 32 + k as u32);
                if stop == CullStop::Done {
                    break;
                }
                k += 1;
            }
        }
        let [a, b] = &runs;
        let records = |s: &Vec<TriRecord, 8>| {
            let mut r = [[0u16; 3]; 8];
            for (d, t) in r.iter_mut().zip(s) {
                *d = t.v;
            }
            (s.len(), r)
        };
        let flags = |v: &[ScreenVertex; 16]| v.map(|v| v.flags);
        if (a.2, a.3, a.4, a.5, a.6) != (b.2, b.3, b.4, b.5, b.6)
            || records(&a.1) != records(&b.1)
            || flags(&a.0) != flags(&b.0)
        {
            return Some(seed);
        }
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): [`Viewport::project`]'s screen words from
/// the Q16.16 assembly routine against the portable ones, on `n` pseudo-random clip-space
/// points (w from 2⁻¹⁶ to 2¹⁵, coordinates up to 16·w and beyond the guard band, depths
/// in front of, inside and behind the depth range) and a few screen sizes. Returns the
/// first point `[x, y, z, w]` (Q16.16 bits) and width whose words differ.
#[doc(hidden)]
#[must_use]
pub fn projection_self_test(n: u32) -> Option<([i32; 4], u32)> {
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;
    let mut next = xorshift32(0x2545_f491);
    for i in 0..n {
        let (r1, r2, r3) = (next(), next(), next());
        let w = ((r1 >> 1) >> (r1 % 31)).max(1) as i32;
        // Coordinates up to 2^k·w, every sign: mostly inside the guard band (k ≤ 3).
        let coord = |r: u32| {
            let k = [0u32, 1, 2, 3, 3, 4, 5, 8][(r >> 29) as usize];
            let m = (w as i64) << k;
            ((r as i64 % (2 * m + 1)) - m).clamp(i32::MIN as i64, i32::MAX as i64) as i32
        };
        let (x, y) = (coord(r2), coord(r3));
        let z = coord(r1.rotate_left(7) ^ r3);
        let width = [240u32, 320, 128, 1024][(i % 4) as usize];
        let vp = Viewport {
            width,
            height: [240u32, 240, 160, 1024][(i % 4) as usize],
        };
        let p = [x, y, z, w].map(|b| Fx(I16F16::from_bits(b)));
        let want = vp.screen_words(p);
        if let Some(got) = crate::kernel::project_q16(&[x, y, z, w], 8 * vp.width, 8 * vp.height) {
            if got != want {
                return Some(([x, y, z, w], width));
            }
        }
    }
    None
}

/// The Q16.16 point and direction transform kernels (`kernel::transform_q16`,
/// `kernel::transform_dir_q16`, reached through `Mat4::transform_point` and
/// `Mat4::transform_dir`) against `Scalar::dot3_add` of each row, on `n` pseudo-random
/// matrices and points of every magnitude up to the saturation rails. Returns the first
/// mismatching case.
pub fn transform_self_test(n: u32) -> Option<u32> {
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;
    type Q = Fx<I16F16>;
    let mut next = xorshift32(0x2545_f491);
    let mut value = || {
        // A random magnitude: from a few bits to the whole word.
        let r = next();
        let bits = r % 33;
        let v = (r.rotate_left(7) as i32) >> (32 - bits.max(1));
        Fx(I16F16::from_bits(if bits == 32 { r as i32 } else { v }))
    };
    for case in 0..n {
        let m = Mat4::<Q> {
            m: core::array::from_fn(|_| core::array::from_fn(|_| value())),
        };
        let p = [value(), value(), value()];
        let want: [Q; 4] = core::array::from_fn(|i| {
            let r = m.m[i];
            Q::dot3_add([r[0], r[1], r[2]], p, r[3])
        });
        let want_dir: [Q; 3] = core::array::from_fn(|i| {
            let r = m.m[i];
            Q::dot3_add([r[0], r[1], r[2]], p, Q::ZERO)
        });
        if m.transform_point(p) != want || m.transform_dir(p) != want_dir {
            return Some(case);
        }
    }
    None
}
