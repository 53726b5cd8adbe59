//! Unit tests of the number types (`scalar`) and the integer helpers (`wide`).

use super::*;
use crate::kernel::wide::bitlen64;
use crate::kernel::wide::{mul_wide_u, round_shr_sat, shr_to_i32};

type Q = Fx<I16F16>;

#[test]
fn reciprocal_seed_and_steps_over_every_leading_word() {
    // Every 16-bit leading word d (the table index and the 32-bit Newton step see only
    // d), with the low word at both ends and in the middle: the 32-bit step's product
    // stays in i32 (debug builds check) and the result is within 2^-28 relative.
    let mut worst = 0.0f64;
    for d in 1u64 << 15..1 << 16 {
        for low in [0u64, 0x8000, 0xffff] {
            for shift in [0, 20] {
                let a = ((d << 16) | low) << shift;
                let (m, e) = recip_norm(a);
                assert!((1 << 29..=1 << 30).contains(&m), "{a}: m = {m}");
                let got = m as f64 * 2f64.powi(-(e as i32));
                worst = worst.max((got * a as f64 - 1.0).abs());
            }
        }
    }
    assert!(worst < 2f64.powi(-28), "worst relative error {worst:e}");
}

#[test]
fn fixed_saturates_instead_of_overflowing() {
    let big = Q::lit(30000.0);
    assert!(!(big + big).is_valid());
    assert!(!(big * big).is_valid());
    assert!(!(Q::ONE / Q::ZERO).is_valid());
    assert_eq!((-Q::lit(2.0)).sqrt(), Q::ZERO);
    assert!(Q::lit(1.5).is_valid());
}

#[test]
fn from_f64_rounds_to_nearest_step() {
    // 2^-17 is half a step: rounds away from zero in f64's round().
    assert_eq!(Q::lit(1.0 / 131072.0).to_bits(), 1);
    assert_eq!(Q::lit(0.4 / 65536.0).to_bits(), 0);
    // NaN lands on the negative rail, which `is_valid` rejects (it used to become 0).
    assert_eq!(Q::lit(f64::NAN).to_bits(), i32::MIN);
    assert_eq!(Q::lit(1e30).to_bits(), i32::MAX);
}

fn ndc_matches_f64<S: Scalar>(tol_q32: f64) {
    let mut worst = 0.0f64;
    for wi in 1..400 {
        let w = 0.01 * wi as f64 * wi as f64 / 4.0 + 0.05;
        for vi in -20..=20 {
            let v = w * vi as f64 / 10.0;
            let (vs, ws) = (S::from_f64(v), S::from_f64(w));
            let exact = vs.to_f64() / ws.to_f64() * 4294967296.0;
            let got = S::ndc(vs, S::recip(ws)) as f64;
            worst = worst.max((got - exact).abs() / exact.abs().max(4294967296.0));
        }
    }
    assert!(
        worst <= tol_q32,
        "{}: worst relative error {worst:e}",
        S::NAME
    );
}

#[test]
fn ndc_relative_error_within_bounds() {
    // The fixed-point reciprocal is good to 2^-28 relative (3.7e-9).
    ndc_matches_f64::<Q>(4.0e-9);
    ndc_matches_f64::<Fx<I20F12>>(4.0e-9);
    ndc_matches_f64::<f32>(2.0e-7);
    ndc_matches_f64::<f64>(1.0e-9);
    ndc_matches_f64::<micromath::F32>(2.0e-7);
}

#[test]
fn micromath_candidate_is_approximate_but_bounded() {
    // micromath documents ~5 % *average* deviation; the worst case over [1, 4] is ~6.1 %.
    let mut worst = 0.0f32;
    for i in 0..300 {
        let x = 1.0 + i as f32 * 0.01;
        let got = Scalar::sqrt(micromath::F32(x)).0;
        worst = worst.max((got - libm::sqrtf(x)).abs() / libm::sqrtf(x));
    }
    assert!(
        worst > 0.01 && worst < 0.065,
        "worst relative sqrt error {worst}"
    );
    let (s, c) = micromath::F32(0.5).sin_cos();
    assert!((s.0 - libm::sinf(0.5)).abs() < 0.002 && (c.0 - libm::cosf(0.5)).abs() < 0.002);
    assert_eq!(Scalar::sqrt(micromath::F32(-1.0)), micromath::F32(0.0));
}

#[test]
fn unsigned_wide_multiply_is_exact() {
    for &a in &[0u32, 1, 0xffff, 0x1_0000, 0xdead_beef, u32::MAX] {
        for &b in &[0u32, 3, 0xffff, 0x8000_0000, u32::MAX] {
            assert_eq!(mul_wide_u(a, b), a as u64 * b as u64);
        }
    }
}

#[test]
fn q32_scaling_rounds_like_wide_arithmetic() {
    for &n in &[
        0i64,
        1,
        -1,
        1 << 31,
        (1 << 43) - 12345,
        -(1 << 43) + 999,
        0x1_2345_6789,
        -0x7_6543_2101,
    ] {
        for &k in &[1u32, 1920, 16384, 65535 << 12] {
            let exact = ((n as i128 * k as i128 + (1 << 31)) >> 32) as i64;
            assert_eq!(mul_q32(n, k), exact, "{n} * {k}");
        }
    }
}

#[test]
fn variable_shifts_match_64_bit_shifts() {
    let xs = [
        0i64,
        1,
        -1,
        5,
        -5,
        (1 << 31) - 1,
        -(1 << 31),
        1 << 40,
        -(1 << 40) - 3,
        (1 << 62) - 1,
        -(1 << 62),
        i64::MAX,
        i64::MIN,
        0x1234_5678_9abc_def0,
        -0x0fed_cba9_8765_4321,
    ];
    for &x in &xs {
        for s in 0..32 {
            let want = x >> s;
            if i32::try_from(want).is_ok() {
                assert_eq!(shr_to_i32(x, s) as i64, want, "{x} >> {s}");
            }
        }
        for s in 1..=62u32 {
            if x.unsigned_abs() < 1 << 62 {
                assert_eq!(
                    round_shr64(x, s),
                    (x + (1i64 << (s - 1))) >> s,
                    "{x} / 2^{s}"
                );
            }
        }
        for s in 1..=63u32 {
            for limit in [1 << 30, 1000] {
                let want = (((x >> (s - 1)) >> 1) + ((x >> (s - 1)) & 1))
                    .clamp(-limit as i64, limit as i64);
                assert_eq!(round_shr_sat(x, s, limit) as i64, want, "{x} / 2^{s}");
            }
        }
    }
}

/// The Q16.16 `ndc_scaled` shortcut equals the trait's definition (`mul_q32` of the
/// rounded, possibly negated quotient) for every kind of w, numerator and scale: small and
/// large w, numerators far outside the guard band (the fallback), exact ties and both signs.
#[test]
fn ndc_scaled_matches_its_definition() {
    type F = Fx<I16F16>;
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    for i in 0..200_000 {
        let a = next();
        let w = match i % 4 {
            0 => (a as u32 >> (a >> 59)) as i32 & i32::MAX,
            1 => 1 + (a as u32 & 15) as i32,
            2 => 1 << (a as u32 % 31),
            _ => (a as i32 & 0x7f_ffff) + 0x1_0000,
        }
        .max(1);
        let b = next();
        let v = match i % 3 {
            0 => (b as i32) >> (b >> 59),
            1 => ((w as i64 * ((b as i32 >> 8) % 8) as i64) as i32).wrapping_add(b as i32 % 3),
            _ => -(w >> (b as u32 & 7)),
        };
        let k = [1u32, 1920, 8192, 65535, 65536, 1 << 20][(b >> 40) as usize % 6];
        let (fv, fw) = (Fx(I16F16::from_bits(v)), Fx(I16F16::from_bits(w)));
        let r = F::recip(fw);
        for negate in [false, true] {
            let n = F::ndc(fv, r);
            let want = mul_q32(if negate { -n } else { n }, k);
            assert_eq!(
                F::ndc_scaled(fv, r, k, negate),
                want,
                "{v} / {w} · {k} {negate}"
            );
        }
    }
}

#[test]
fn mul_q32_rounds_and_saturates() {
    for n in [
        0i64,
        1,
        -1,
        1 << 32,
        -(1 << 32) + 5,
        123_456_789_012,
        -(1 << 47) - 1,
        (1 << 61) + 3,
    ] {
        for k in [0u32, 1, 1920, 65535 << 4, (1 << 31) - 1] {
            let want = ((n as i128 * k as i128 + (1 << 31)) >> 32)
                .clamp(i64::MIN as i128, i64::MAX as i128) as i64;
            assert_eq!(mul_q32(n, k), want, "{n} · {k}");
        }
    }
    // The 16-bit scale path: every low word pattern class, high words in the i16 range.
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    for _ in 0..20_000 {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let hi = ((x >> 48) as i16) as i64;
        let lo = (x as u32 ^ (x >> 29) as u32) as i64;
        let n = (hi << 32) | lo;
        for k in [1u32, 1920, 8191, 32768, 65535] {
            let want = (n as i128 * k as i128 + (1 << 31)) >> 32;
            assert_eq!(mul_q32(n, k) as i128, want, "{n} · {k}");
        }
    }
    for n in [
        u32::MAX as i64,
        (1 << 32) - 1,
        -1,
        i16::MIN as i64 * (1 << 32),
    ] {
        assert_eq!(
            mul_q32(n, 65535) as i128,
            (n as i128 * 65535 + (1 << 31)) >> 32
        );
    }
}

#[test]
fn small_q16_products_equal_the_64_bit_ones() {
    // mul_q16_small and dot3_q16_small against the exact 64-bit rounding, at the ends of
    // their ranges and on pseudo-random values of every magnitude within them.
    let exact = |p: i64| ((p + (1 << 15)) >> 16) as i32;
    let ends = [
        -(1 << 23),
        -(1 << 23) + 1,
        -65537,
        -65536,
        -32769,
        -32768,
        -1,
        0,
        1,
    ];
    let ends = ends
        .iter()
        .chain(&[32767, 32768, 65535, 65536, (1 << 23) - 1]);
    for &a in ends.clone() {
        for &b in ends.clone() {
            assert_eq!(mul_q16_small(a, b), exact(a as i64 * b as i64), "{a} · {b}");
        }
    }
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |bits: u32| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        ((x as i32) >> (x >> 59)) >> (32 - bits)
    };
    for _ in 0..200_000 {
        let (a, b) = (next(24), next(24));
        assert_eq!(mul_q16_small(a, b), exact(a as i64 * b as i64), "{a} · {b}");
        let (u, v) = (
            [next(23), next(23), next(23)],
            [next(23), next(23), next(23)],
        );
        let p: i64 = (0..3).map(|k| u[k] as i64 * v[k] as i64).sum();
        assert_eq!(dot3_q16_small(u, v), exact(p), "{u:?} · {v:?}");
    }
    let m = (1 << 22) - 1;
    for (u, v) in [
        ([m; 3], [m; 3]),
        ([-m - 1; 3], [m; 3]),
        ([-m - 1; 3], [-m - 1; 3]),
    ] {
        let p: i64 = (0..3).map(|k| u[k] as i64 * v[k] as i64).sum();
        assert_eq!(dot3_q16_small(u, v), exact(p), "{u:?} · {v:?}");
    }
}

#[test]
fn lit_channel_equals_the_clamped_rounded_product() {
    // Each Fx type's fast `lit_channel` against the trait's default composition, on every
    // raw value near the fast path's bounds and on pseudo-random ones, with every k.
    fn reference<S: Scalar>(x: S, k: u8) -> u16 {
        channel_8_8(x.mul_int(k as i32))
    }
    fn check<T>()
    where
        Fx<T>: Scalar,
        T: fixed::traits::Fixed<Bits = i32>,
    {
        let one = |b: i32| {
            let v = Fx(T::from_bits(b));
            for k in 0..=255u8 {
                assert_eq!(v.lit_channel(k), reference(v, k), "{b:#x} · {k}");
            }
        };
        for b in [i32::MIN, i32::MAX, -1, 0, 1, 127, 128, 129] {
            one(b);
        }
        for b in [
            1 << 23,
            255 << 12,
            255 << 16,
            255 << 20,
            1 << 16,
            1 << 12,
            1 << 20,
        ] {
            for d in -3..=3 {
                one(b + d);
            }
        }
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..2_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            one((x as i32) >> (x >> 59));
        }
    }
    check::<I16F16>();
    check::<I20F12>();
    check::<I12F20>();
}

#[test]
fn mul_int_is_the_product_with_the_integer() {
    fn check<S: Scalar + core::fmt::Debug + PartialEq>(vals: &[f64]) {
        for &v in vals {
            for k in [
                -2048,
                -255,
                -3,
                -1,
                0,
                1,
                2,
                31,
                63,
                255,
                2047,
                4096,
                1 << 20,
            ] {
                let x = S::from_f64(v);
                assert_eq!(x.mul_int(k), x * S::from_i32(k), "{v} · {k}");
            }
        }
    }
    let vals = [
        0.0, 1.0, -1.0, 0.3, -0.7, 1.999, 13.25, -32767.5, 32767.99, 1e-5, 2047.9,
    ];
    check::<Fx<I16F16>>(&vals);
    check::<Fx<I20F12>>(&vals);
    check::<Fx<I12F20>>(&vals);
    check::<f32>(&vals);
    check::<f64>(&vals);
}

#[test]
fn bitlen_matches_leading_zeros() {
    // Every power of two, its neighbours and a pseudo-random sweep.
    let mut x = 0x2545_f491u32;
    let edges = (0..32).flat_map(|k| {
        let p = 1u32 << k;
        [p, p - 1, p.wrapping_add(1), p | (p >> 1)]
    });
    let sweep = (0..100_000).map(|_| {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        x >> (x & 31)
    });
    for v in [0u32, 1, u32::MAX].into_iter().chain(edges).chain(sweep) {
        assert_eq!(bitlen32(v), 32 - v.leading_zeros(), "{v:#x}");
        let w = (v as u64) << (v & 31) | v as u64;
        assert_eq!(bitlen64(w), 64 - w.leading_zeros(), "{w:#x}");
    }
}

#[test]
fn mul_wide16_is_exact() {
    for a in [
        0i32,
        1,
        -1,
        65535,
        65536,
        -65536,
        i32::MAX,
        i32::MIN,
        0x1234_5678,
        -0x0765_4321,
    ] {
        for b in [0i32, 1, -1, 32767, -32768, 12345, -2047] {
            assert_eq!(mul_wide16(a, b), a as i64 * b as i64, "{a} · {b}");
        }
    }
}

#[test]
fn mul_wide_is_exact() {
    let vals = [
        0,
        1,
        -1,
        2,
        65535,
        65536,
        -65536,
        123_456_789,
        -987_654_321,
        i32::MAX,
        i32::MIN,
        0x7fff_0001,
        -0x8000,
    ];
    for &a in &vals {
        for &b in &vals {
            assert_eq!(mul_wide(a, b), a as i64 * b as i64, "{a} * {b}");
        }
    }
}

#[test]
fn fixed_mul_rounds_to_nearest_and_dot_rounds_once() {
    let q = |v: f64| Q::lit(v);
    assert_eq!((q(1.5) * q(-2.25)).to_f64(), -3.375);
    // 3·2^-16 · 0.5 = 1.5 steps → rounds to 2 steps.
    assert_eq!((Fx(I16F16::from_bits(3)) * q(0.5)).to_bits(), 2);
    let a = [q(0.1), q(0.2), q(0.3)];
    let b = [q(0.7), q(-0.4), q(0.9)];
    let exact: f64 = (0..3).map(|k| a[k].to_f64() * b[k].to_f64()).sum::<f64>() + 0.25;
    let got = Q::dot3_add(a, b, q(0.25)).to_f64();
    assert!((got - exact).abs() <= 0.5 / 65536.0, "{got} vs {exact}");
    assert!(!Q::dot3_add([q(30000.0); 3], [q(30000.0); 3], Q::ZERO).is_valid());
}

#[test]
fn to_fixed_rounds() {
    assert_eq!(Q::lit(1.5).to_fixed_i32(8), 384);
    assert_eq!(Q::lit(-1.5).to_fixed_i32(20), -(3 << 19));
    assert_eq!(1.5f32.to_fixed_i32(8), 384);
    assert_eq!(f64::NAN.to_fixed_i32(8), 0);
}

#[test]
fn sin_cos_within_one_step() {
    for i in 0..64 {
        let a = i as f64 * 0.1 - 3.2;
        let (s, c) = Q::lit(a).sin_cos();
        let a_q = Q::lit(a).to_f64();
        assert!((s.to_f64() - libm::sin(a_q)).abs() <= 1.0 / 65536.0);
        assert!((c.to_f64() - libm::cos(a_q)).abs() <= 1.0 / 65536.0);
    }
}

#[test]
fn same_is_equality() {
    // `Scalar::same` (the fixed-point types' bit comparison) against `==`, on equal raw values,
    // neighbours and pseudo-random pairs; the floats keep `==`'s answers (0.0 is -0.0, NaN is
    // not NaN).
    fn check<T>()
    where
        Fx<T>: Scalar,
        T: fixed::traits::Fixed<Bits = i32>,
    {
        let mut x = 0x1234_5678u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x as i32
        };
        for _ in 0..2000 {
            let a = next();
            for b in [
                a,
                a.wrapping_add(1),
                a.wrapping_sub(1),
                next(),
                i32::MIN,
                i32::MAX,
            ] {
                let (p, q) = (Fx(T::from_bits(a)), Fx(T::from_bits(b)));
                assert_eq!(p.same(q), p == q, "{a:#x} {b:#x}");
            }
        }
    }
    check::<fixed::types::I16F16>();
    check::<fixed::types::I20F12>();
    check::<fixed::types::I12F20>();
    assert!(0.0f32.same(-0.0) && 0.0f64.same(-0.0));
    assert!(!f32::NAN.same(f32::NAN) && !f64::NAN.same(f64::NAN));
    assert!(1.5f32.same(1.5) && !1.5f64.same(1.25));
}
