//! Unit tests of `raster::phong`: the integer square root, the lighting model against f64, the
//! pool payloads, the tone curves and the toon bands.

use super::*;
use crate::geometry::phong_entries::{band_step, PhongLight, TONE_FILMIC};

#[test]
fn integer_square_root() {
    for x in [
        0u32,
        1,
        2,
        3,
        4,
        15,
        16,
        17,
        1 << 28,
        (1 << 28) + 12345,
        u32::MAX,
    ] {
        let r = isqrt(x) as u64;
        assert!(r * r <= x as u64 && (r + 1) * (r + 1) > x as u64, "{x}");
    }
}

#[test]
fn shade_matches_the_model_in_floating_point() {
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    let q = |v: [f64; 3]| v.map(|c| (c * ONE as f64).round() as i32);
    let (ld, vd) = (unit([-1.0, 1.0, 1.0]), unit([0.2, 0.3, 1.0]));
    let lv = ld[0] * vd[0] + ld[1] * vd[1] + ld[2] * vd[2];
    let mut lights = PhongLights {
        count: 1,
        ..Default::default()
    };
    lights.lights[0] = PhongLight {
        dir: q(ld),
        color: [255, 200, 100],
    };
    let m = PhongMaterial {
        color: [200, 60, 60],
        k: [0.1, 0.8, 0.6].map(|c: f64| (c * ONE as f64).round() as i32),
        shininess: 20,
        v: q(vd),
        lv: [(lv * ONE as f64).round() as i32, 0, 0, 0],
        tone: TONE_NONE,
        bands: 0,
        band_step: band_step(0),
    };
    let mut worst = 0.0f64;
    for i in 0..200 {
        let a = i as f64 * 0.1;
        let n = unit([a.sin(), (a * 0.7).cos(), 0.5 + (a * 1.3).sin().abs()]);
        // A shorter normal (as interpolation gives) must light the same.
        let got = shade::<false, false, false>(
            q(n.map(|c| c * 0.8)),
            [0; 3],
            &ShadeCtx::new(&lights, &m),
            &PointsCtx::default(),
        );
        let nl = n[0] * ld[0] + n[1] * ld[1] + n[2] * ld[2];
        let nv = n[0] * vd[0] + n[1] * vd[1] + n[2] * vd[2];
        for c in 0..3 {
            let lc = lights.lights[0].color[c] as f64;
            let mut v = m.color[c] as f64 * (0.1 + 0.8 * lc / 255.0 * nl.max(0.0));
            let rv = 2.0 * nl * nv - lv;
            if nl > 0.0 && rv > 0.0 {
                v += 0.6 * lc * rv.powi(20);
            }
            let want = v.clamp(0.0, 255.0);
            worst = worst.max((got[c] as f64 / ONE as f64 - want).abs());
        }
    }
    // Within 3/4 of an 8-bit step (a tenth of an RGB565 step): Q1.14 directions, whose
    // 2⁻¹⁴ rounding the specular power multiplies (20·2⁻¹⁴·0.6·255 ≈ 0.2 a step, from each
    // of the products in R·V), and the power's truncated squarings.
    assert!(worst < 0.75, "{worst}");
}

#[test]
fn pool_payloads_round_trip() {
    let mut e = ActiveExtra::EMPTY;
    let mut l = PhongLights {
        count: 3,
        ..Default::default()
    };
    l.lights[2] = PhongLight {
        dir: [1, -2, 3],
        color: [255, 0, 7],
    };
    l.store(&mut e);
    assert_eq!(PhongLights::load(&e), l);
    let m0 = PhongMaterial::default();
    let (a, b) = (
        ShadeCtx::from_entries::<true>(Some(&e), &m0),
        ShadeCtx::new(&l, &m0),
    );
    assert_eq!(
        (a.dir, a.frac, a.full, a.count),
        (b.dir, b.frac, b.full, b.count)
    );
    let m = PhongMaterial {
        color: [1, 2, 3],
        k: [255 << 14, 0, 12345],
        shininess: 255,
        v: [-16384, 5, 16383],
        lv: [-12000, 16384, 0, -1],
        tone: TONE_FILMIC,
        bands: 255,
        band_step: band_step(255),
    };
    m.store(&mut e);
    assert_eq!(PhongMaterial::load(&e), m);
}

/// Toon's diffuse steps against `⌈N·L·bands⌉/bands` in f64: the same step for every `N·L`
/// of the lit side, its value within `bands` units of 2⁻¹⁴ below (exact at the top), never
/// decreasing; Phong's `N·L` unchanged. The specular term is 0 below ½ and 1 from ½ on.
#[test]
fn toon_bands_follow_the_definition() {
    for bands in [1u8, 2, 3, 4, 5, 7, 16, 255] {
        let m = PhongMaterial {
            bands,
            band_step: band_step(bands),
            ..PhongMaterial::default()
        };
        let c = ShadeCtx::new(&PhongLights::default(), &m);
        let mut last = 0;
        for nl in 1..=ONE + 1024 {
            let got = band::<true>(nl, &c);
            let x = nl.min(ONE) as f64 / ONE as f64;
            let want = (x * bands as f64).ceil() / bands as f64;
            let err = want * ONE as f64 - got as f64;
            assert!(
                (0.0..=bands as f64).contains(&err),
                "{bands} {nl}: {got} {want}"
            );
            assert!(got >= last, "{bands} {nl}");
            last = got;
            assert_eq!(band::<false>(nl, &c), nl);
        }
        assert_eq!(last, ONE);
    }
    assert_eq!((hard::<true>(ONE / 2 - 1), hard::<true>(ONE / 2)), (0, ONE));
    assert_eq!(hard::<false>(123), 123);
}

/// The integer tone curves against the f64 ones: within 1/8 of a channel unit (the filmic
/// constants rounded to Q2.14), monotone,
/// and white at the top of their range.
#[test]
fn tone14_follows_the_curves() {
    let f64_curve = |tone: u8, x: f64| match tone {
        TONE_REINHARD => x / (1.0 + x),
        _ => (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).min(1.0),
    };
    for tone in [TONE_REINHARD, TONE_FILMIC] {
        let mut last = 0;
        let mut worst = 0.0f64;
        // Finely from 0 to 2 × white, then coarsely to past the top of the range.
        let fine = (0..=2 * 255 * 64).map(|k| (k as i64) << 8);
        let coarse = (3..=140).map(|k| k as i64 * WHITE14);
        for v in fine.chain(coarse) {
            let got = tone14(v, tone);
            assert!(got >= last, "{tone} not monotone at {v}");
            last = got;
            let x = v.min(HDR_MAX14) as f64 / WHITE14 as f64;
            let want = 255.0 * f64_curve(tone, x);
            worst = worst.max((got as f64 / 16384.0 - want).abs());
        }
        assert!(worst < 1.0 / 8.0, "{tone}: {worst}");
        assert_eq!(tone14(-5, tone), 0);
        assert_eq!(tone14(i64::MAX / 4, tone), tone14(HDR_MAX14, tone));
    }
    assert_eq!(tone14(HDR_MAX14, TONE_FILMIC), WHITE14 as i32);
}
