//! Unit tests of the raster stages (`raster`, `setup`, `span`).

use super::*;
use crate::kernel::records::ScreenVertex;
use crate::kernel::wide::{div_floor, mul_shr_16, udiv_shift_subtract};
use crate::kernel::{portable::div_floor_small, udiv_small};
use crate::raster::setup::*;
use crate::selftest::xorshift32;
use heapless::Vec;

/// The dithered Cortex-M row routine draws every triangle with routine rows; so in a
/// dithered strip only `DITHER_OK` ones may have them, including triangles set up before
/// dithering was switched on mid-frame (`ActiveList::refresh_routine_rows`).
#[test]
fn routine_rows_in_a_dithered_strip_need_dither_ok() {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut v = [ScreenVertex::default(); 3];
    for (p, (x, y)) in v.iter_mut().zip([(80, 16), (400, 300), (40, 600)]) {
        (p.x, p.y) = (x, y);
        p.set_color([400, 500, 300]);
    }
    let t = TriRecord { v: [0, 1, 2] };
    let plain = SpanMode::new::<Rgb565>(DepthTest::Less, false);
    let mut list = ActiveList::<4>::new();
    assert!(list.push_with(|r| r.setup::<Rgb565>(&t, &v, 1, 240, plain)));
    let rows = list.slots[0].routine_rows;
    assert!(rows > 0 && list.slots[0].flags & (FAST | DITHER_OK) == FAST);
    list.refresh_routine_rows(1, true);
    assert_eq!(list.slots[0].routine_rows, 0);
    assert_eq!(
        list.slots[0].flags & (LAST_IN_ROUTINE | SWITCH_IN_ROUTINE),
        0
    );
    list.refresh_routine_rows(1, false);
    assert_eq!(list.slots[0].routine_rows, rows);
    // Set up while dithering: checked, so it keeps its rows in a dithered strip.
    let dithered = SpanMode::new::<Rgb565>(DepthTest::Less, true);
    let mut list = ActiveList::<4>::new();
    assert!(list.push_with(|r| r.setup::<Rgb565>(&t, &v, 1, 240, dithered)));
    assert!(list.slots[0].flags & DITHER_OK != 0);
    list.refresh_routine_rows(1, true);
    assert_eq!(list.slots[0].routine_rows, rows);
}

#[test]
fn green_fits_equals_its_64_bit_specification() {
    let mut rnd = xorshift32(0x9e37_79b9);
    let edges = [
        0,
        1,
        -1,
        i32::MAX,
        i32::MIN,
        1 << 16,
        -(1 << 16),
        0xffff,
        -0xffff,
    ];
    let mut agree = [0u32; 2];
    for k in 0..400_000u32 {
        let (gx, gy) = if k % 4 == 0 {
            (edges[rnd() as usize % 9], edges[rnd() as usize % 9])
        } else {
            // Mostly a real triangle's small gradients, some anywhere.
            let g = |r: u32, s: u32| {
                if s % 3 == 0 {
                    r as i32
                } else {
                    (r as i32) >> (8 + s % 16)
                }
            };
            (g(rnd(), rnd()), g(rnd(), rnd()))
        };
        let a = if k % 8 == 0 {
            [0, u32::MAX, 1 << 31, 15 << 21][rnd() as usize % 4]
        } else {
            rnd()
        };
        let r = rnd();
        let v = |r: u32| {
            if r % 7 == 0 {
                [16_400, -16_400, 0][r as usize % 3]
            } else {
                (r % 32_801) as i32 - 16_400
            }
        };
        let (dx, dy) = (v(r), v(r.rotate_left(16)));
        let (frac, vf) = [(26, 4), (24, 2), (25, 3)][k as usize % 3];
        // Half the cases: the colour the field itself rounds to (±1), so many pass; and
        // exactly at the distance bound now and then.
        let c = if k % 2 == 0 {
            let f = 16 * a as i64 + gx as i64 * dx as i64 + gy as i64 * dy as i64;
            let unit = 16i64 << (frac - vf);
            ((f - (16i64 << (frac - 1)) + unit / 2).div_euclid(unit) + (rnd() % 3) as i64 - 1)
                .clamp(0, 1023) as u16
        } else {
            rnd() as u16 % 1024
        };
        let fast = green_fits_split(a, gx, gy, dx, dy, c, frac, vf);
        assert_eq!(
            fast,
            green_fits_wide(a, gx, gy, dx, dy, c, frac, vf),
            "a {a:#x} gx {gx} gy {gy} d ({dx}, {dy}) c {c} frac {frac}"
        );
        agree[fast as usize] += 1;
    }
    // At the distance bound exactly (16·F = 16·ideal ± 16·e), both sides.
    for (frac, vf) in [(26u32, 4u32), (24, 2)] {
        for c in [0u16, 1, 512, 1023] {
            let ideal = 16 * (((c as i64) << (frac - vf)) + (1i64 << (frac - 1)));
            for target in [ideal + (16i64 << (frac - 2)), ideal - (16i64 << (frac - 2))] {
                for nudge in [-1i64, 0, 1] {
                    // 16·a = target + nudge with dx = 1, gx = the remainder.
                    let t = target + nudge;
                    let a = (t.div_euclid(16)).clamp(0, u32::MAX as i64) as u32;
                    let gx = (t - 16 * a as i64) as i32;
                    assert_eq!(
                        green_fits_split(a, gx, 0, 1, 0, c, frac, vf),
                        green_fits_wide(a, gx, 0, 1, 0, c, frac, vf),
                        "bound c {c} frac {frac} nudge {nudge}"
                    );
                }
            }
        }
    }
    assert!(agree[0] > 10_000 && agree[1] > 10_000, "{agree:?}");
}

/// Exact reference: first pixel whose centre is at or right of the edge at `row`.
fn reference(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> i32 {
    // x(ys) − 8 = ((xa − 8)(yb − ya) + (ys − ya)(xb − xa)) / (yb − ya); ceil of that / 16.
    let ys = 16 * row as i64 + 8;
    let n = (xa as i64 - 8) * (yb - ya) as i64 + (ys - ya as i64) * (xb - xa) as i64;
    let d = 16 * (yb - ya) as i64;
    ceil_div(n, d) as i32
}

#[test]
fn edge_dda_is_exact_on_every_row() {
    let cases = [
        (0, 0, 160, 320),
        (37, 5, -501, 777),
        (8, 8, 8, 400),
        (-3000, -20, 4000, 3),
        (123, 17, 124, 1000),
        (-16383, -16383, 16383, 16383),
        (16383, -16383, -16383, 16383),
        (-16383, 100, 16383, 101),
    ];
    for (xa, ya, xb, yb) in cases {
        let first = first_pixel(ya);
        let end = first_pixel(yb);
        let (mut e, dy) = Edge::new(xa, ya, xb, yb, first).dda();
        for row in first..end.min(first + 3000) {
            assert_eq!(
                e.c(),
                reference(xa, ya, xb, yb, row),
                "edge {xa},{ya}->{xb},{yb} row {row}"
            );
            let (c, carry) = e.peek();
            assert_eq!(e.step(dy), carry);
            if row + 1 < end {
                assert_eq!(e.c(), c);
            }
        }
        // Starting anywhere gives the same value.
        let mid = (first + end) / 2;
        assert_eq!(
            Edge::new(xa, ya, xb, yb, mid).c as i32,
            reference(xa, ya, xb, yb, mid)
        );
    }
}

#[test]
fn pixel_centres_on_the_boundary() {
    // Centre of pixel 3 is at 56 subpixels: an edge exactly there starts the span at 3.
    assert_eq!(first_pixel(56), 3);
    assert_eq!(first_pixel(57), 4);
    assert_eq!(first_pixel(55), 3);
    assert_eq!(first_pixel(-8), -1);
    assert_eq!(first_pixel(-7), 0);
    // Pixel −1 has its centre at −8 subpixels, pixel −2 at −24.
    assert_eq!(first_pixel(-9), -1);
    assert_eq!(first_pixel(-24), -2);
    assert_eq!(first_pixel(-23), -1);
}

#[test]
fn reciprocal_is_accurate_to_28_bits_over_the_full_range() {
    let mut worst = 0.0f64;
    let mut d = 1i64;
    while d < 1 << 60 {
        for k in [d, d + 1, d / 2 * 3 + 7, -d, -(d / 4 * 5) - 3] {
            let r = Reciprocal::new(k);
            let sign = if r.neg { -1.0 } else { 1.0 };
            let got = sign * r.m as f64 * 2f64.powi(-(r.e as i32));
            worst = worst.max((got * k as f64 - 1.0).abs());
        }
        d = d * 3 + 1;
    }
    assert!(worst < 2f64.powi(-28), "worst relative error {worst:e}");
}

#[test]
fn active_list_keeps_vector_order() {
    // The same pushes and removals on the list and on a plain vector of ids.
    let mut list = ActiveList::<40>::new();
    let mut ids: Vec<i16, 40> = Vec::new();
    let mut next = 0i16;
    for step in 0..400u32 {
        if step % 3 != 2 && list.len() < 40 {
            assert!(list.push_with(|t| {
                t.row_end = next;
                true
            }));
            ids.push(next).unwrap();
            next += 1;
        } else if list.len() > 0 {
            let i = (step as usize * 7) % list.len();
            list.swap_remove(i);
            ids.swap_remove(i);
        }
        assert!(!list.push_with(|_| false) || list.len() < 40);
        for (i, &id) in ids.iter().enumerate() {
            assert_eq!(list.get_mut(i).row_end, id, "step {step} entry {i}");
        }
    }
    let mut full = ActiveList::<2>::new();
    assert!(full.push_with(|_| true) && full.push_with(|_| true));
    assert!(!full.push_with(|_| true));
    assert_eq!(ActiveList::<2>::MAX, 32768);
}

#[test]
fn coefficient_products_match_64_bits() {
    // Every shift, the extreme and a spread of mantissas, and every v at the edges of
    // its range and a stride through it.
    let ms = [
        1i32,
        2,
        0x7fff,
        0x8000,
        (1 << 29) + 1,
        0x2aaa_aaab,
        0x3fff_ffff,
        1 << 30,
    ];
    for l in 1..=16u32 {
        let lim = 1i32 << l;
        let step = (lim / 97).max(1);
        let vs = (-lim + 1..lim)
            .step_by(step as usize)
            .chain([-lim + 1, -1, 0, 1, lim - 1]);
        for v in vs {
            for &m in &ms {
                let want = (m as i64 * v as i64) >> l;
                assert_eq!(mul_shr_16(m, v, l) as i64, want, "{m} {v} {l}");
            }
        }
    }
}

#[test]
fn small_divisions_match_the_library() {
    let ns = [
        0i32,
        1,
        2,
        7,
        15,
        16,
        17,
        255,
        1000,
        32766,
        65535,
        1 << 30,
        i32::MAX,
    ];
    let ds = [1i32, 2, 3, 16, 17, 1000, 32766, 1 << 20, i32::MAX];
    for &n in &ns {
        for &d in &ds {
            let want = (n as u32 / d as u32, n as u32 % d as u32);
            assert_eq!(udiv_small(n as u32, d as u32), want);
            assert_eq!(udiv_shift_subtract(n as u32, d as u32), want);
            for m in [n, -n, -n - 1] {
                let want = (m.div_euclid(d), m.rem_euclid(d));
                assert_eq!(div_floor_small(m, d), want, "{m} / {d}");
            }
        }
    }
}

/// Dithered Gouraud triangles (RGB565) on pseudo-random triangles that take the fast path
/// without dithering, small to the fast path's largest, with colours over the whole range
/// (channels at 0 and at the maximum included, and changes across the whole range): row by
/// row through `draw_row`,
/// - a triangle is either fast with [`DITHER_OK`] or not fast at all;
/// - a [`DITHER_OK`] triangle's spans ([`span_packed_dither`]) equal those of the same
///   record drawn by the clamped span, which reads each field separately: no carry
///   between fields and no field leaving its range, at any pixel;
/// - every pixel of a fast triangle is within 1 LSB per channel of the exact dithered
///   quantization of the plane through the vertex colours at its centre,
///   `floor(v + (2·B + 1)/32)`.
#[test]
fn dithered_fast_span_is_exact_and_within_one_lsb() {
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
    let mut next = xorshift32(0x2468_ace1);
    let mode = SpanMode::new::<Rgb565>(DepthTest::Less, true);
    assert!(mode.fast_gouraud && mode.dither);
    const W: usize = 1100;
    let (mut ok, mut slow, mut pixels, mut worst) = (0u32, 0u32, 0u64, [0i32; 3]);
    for i in 0..6000u32 {
        let size = [24i32, 160, 1200, 8000][(i % 4) as usize];
        let mut v = [ScreenVertex::default(); 3];
        for p in &mut v {
            let r = next();
            p.x = (400 + (r % size as u32) as i32) as i16;
            p.y = (300 + ((r >> 16) % size as u32) as i32) as i16;
            p.z = 1000 + (next() % 5000) as u16;
            let c = next();
            let pick = |k: u32, max: u16| match (c >> (k * 8)) & 3 {
                0 => 0,
                1 => max,
                _ => ((c >> (k * 8 + 2)) % (max as u32 + 1)) as u16,
            };
            p.set_color([pick(0, 992), pick(1, 1008), pick(2, 992)]);
        }
        let t = TriRecord { v: [0, 1, 2] };
        let row0 = v.iter().map(|p| first_pixel(p.y as i32)).min().unwrap();
        let mut rec = ActiveTri::EMPTY;
        let plain = SpanMode {
            dither: false,
            ..mode
        };
        if !rec.setup::<Rgb565>(&t, &v, row0, 1024, plain) || rec.flags & FAST == 0 {
            continue;
        }
        assert!(rec.setup::<Rgb565>(&t, &v, row0, 1024, mode));
        let safe = rec.flags & DITHER_OK != 0;
        if safe {
            ok += 1;
        } else {
            assert_eq!(rec.flags & FAST, 0, "a fast triangle without DITHER_OK");
            slow += 1;
        }
        let mut other = rec.clone();
        other.flags &= !DITHER_OK;
        // The exact plane through the vertex colours (channel units).
        let [a, b, c] = v.map(|p| (p.x as f64 / 16.0, p.y as f64 / 16.0, p.color()));
        let det = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
        let scale = [32.0, 16.0, 32.0];
        let mut row = row0.max(0);
        loop {
            let mut cs = [Rgb565::BLACK; W];
            let mut zs = [u16::MAX; W];
            let (mut cs2, mut zs2) = (cs, zs);
            let (_, _, done) = rec.draw_row(row, &mut cs, &mut zs, DepthTest::Less, true);
            let _ = other.draw_row(row, &mut cs2, &mut zs2, DepthTest::Less, true);
            if safe {
                assert_eq!(
                    cs, cs2,
                    "triangle {i} row {row}: fast and clamped spans differ"
                );
            }
            let yc = row as f64 + 0.5;
            for x in 0..W {
                // Triangles set up without the fast path are drawn by the dithered span
                // of before (the same code): only the fast ones are compared here.
                if zs[x] == u16::MAX || !safe {
                    continue;
                }
                pixels += 1;
                let xc = x as f64 + 0.5;
                let l1 = ((xc - a.0) * (c.1 - a.1) - (c.0 - a.0) * (yc - a.1)) / det;
                let l2 = ((b.0 - a.0) * (yc - a.1) - (xc - a.0) * (b.1 - a.1)) / det;
                let th = (2.0 * BAYER[(row & 3) as usize][x & 3] as f64 + 1.0) / 32.0;
                let got = [cs[x].r(), cs[x].g(), cs[x].b()];
                for k in 0..3 {
                    let val = (a.2[k] as f64
                        + l1 * (b.2[k] as f64 - a.2[k] as f64)
                        + l2 * (c.2[k] as f64 - a.2[k] as f64))
                        / scale[k];
                    let max = [31.0, 63.0, 31.0][k];
                    let want = (val + th).floor().clamp(0.0, max) as i32;
                    let e = (got[k] as i32 - want).abs();
                    worst[k] = worst[k].max(e);
                    assert!(e <= 1, "triangle {i} (DITHER_OK {safe}, {v:?}) pixel ({x}, {row}) channel {k}: {} vs exact {want} ({val})", got[k]);
                }
            }
            if done {
                break;
            }
            row += 1;
        }
    }
    extern crate std;
    std::println!(
        "triangles fast without dithering: {ok} fast and DITHER_OK with it, {slow} set up without the fast path; {pixels} pixels, worst |Δ| per channel against the exact dithered value {worst:?} LSB"
    );
    assert!(ok > 1000 && slow > 0);
}

#[test]
fn dither_words_are_the_thresholds() {
    use embedded_graphics_core::pixelcolor::Rgb565;
    for row in 0..4 {
        for (p, [rb, g]) in dither_words::<Rgb565>(row).into_iter().enumerate() {
            let d = 2 * BAYER[row as usize][p] as i32 - 15;
            // ½ (the start values' bias) + d = (2·B + 1)/32 of a unit.
            assert_eq!((rb & 0xffff) as i16 as i32, d * 64);
            assert_eq!(
                (rb.wrapping_sub(rb as i16 as i32 as u32) as i32) >> 16,
                d * 64
            );
            assert_eq!(g as i32, d << 21);
            assert_eq!(1024 + d * 64, (2 * BAYER[row as usize][p] as i32 + 1) * 64);
        }
    }
}

#[test]
fn floor_division_both_paths() {
    // Quotients are pixel columns: always within i32, numerators up to 2^47.
    for (n, d) in [
        (7i64, 2i32),
        (-7, 2),
        (0, 5),
        (-(1 << 40), 1 << 20),
        ((1 << 46) + 1, 1 << 27),
    ] {
        let (q, r) = div_floor(n, d);
        let dd = d as i64;
        assert_eq!((q as i64, r as i64), (n.div_euclid(dd), n.rem_euclid(dd)));
    }
}

/// `EdgeDda::jump` against `n` calls of `EdgeDda::step` on pseudo-random edges: the same words
/// and the same number of carries, for every distance within the edge's rows.
#[test]
fn edge_jump_equals_steps() {
    let mut rnd = xorshift32(0x5eed_1234);
    for _ in 0..2_000 {
        let ya = (rnd() % 4_000) as i32;
        let yb = ya + 1 + (rnd() % 4_000) as i32;
        let xa = (rnd() % 8_000) as i32 - 2_000;
        let xb = (rnd() % 8_000) as i32 - 2_000;
        let first = (ya + 8) >> 4;
        let last = (yb - 1 + 8) >> 4;
        if last <= first {
            continue;
        }
        let (start, dy) = Edge::new(xa, ya, xb, yb, first).dda();
        let mut stepped = start;
        let mut carries = 0u32;
        for n in 1..=(last - first) as u32 {
            carries += u32::from(stepped.step(dy));
            let mut jumped = start;
            let k = jumped.jump(n, dy);
            assert_eq!(
                (jumped.w, k),
                (stepped.w, carries),
                "edge ({xa}, {ya}) → ({xb}, {yb}), {n} rows"
            );
        }
    }
}

/// `ActiveTri::advance_to` against `advance` row by row on pseudo-random triangles (Gouraud,
/// flat and the fast path, across the short edge's switch): the same state on every row.
#[test]
fn advance_to_equals_row_steps() {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut rnd = xorshift32(0x0fac_e0ff);
    let mut checked = 0;
    for case in 0..400 {
        let mut v = [ScreenVertex::default(); 3];
        for p in v.iter_mut() {
            p.x = (rnd() % 4_400) as i16 - 200;
            p.y = (rnd() % 3_900) as i16;
            p.set_color([0; 3].map(|_: u16| (rnd() % 1024) as u16));
        }
        let flat = if case % 3 == 0 { FLAT_BIT } else { 0 };
        let t = TriRecord { v: [flat, 1, 2] };
        let mode = SpanMode::new::<Rgb565>(DepthTest::Less, case % 2 == 0);
        let mut base = ActiveList::<1>::new();
        let top = (v.iter().map(|p| p.y).min().unwrap() as i32 + 8) >> 4;
        if !base.push_with(|a| a.setup::<Rgb565>(&t, &v, top, 240, mode)) {
            continue;
        }
        let a0 = base.slots[0].clone();
        let mut stepped = a0.clone();
        for target in top + 1..a0.row_end as i32 {
            stepped.advance(target);
            let mut jumped = a0.clone();
            jumped.advance_to(top, target);
            assert!(
                jumped.edges == stepped.edges
                    && jumped.row == stepped.row
                    && jumped.inc == stepped.inc,
                "case {case}, row {target}"
            );
            checked += 1;
        }
    }
    assert!(checked > 1_000, "{checked} rows checked");
}
