//! The accuracy contract of the fixed-point pipeline, asserted for every benchmark scene:
//! against the f64 twin on the same snapped screen geometry (reference (a), which isolates
//! arithmetic error), every fixed-point and f32 frame is within 1 LSB per RGB565 channel with no
//! coverage mismatch. A regression in accuracy fails CI.

mod common;

use common::compare::compare;
use scanline3d::demo::Bench;
use scanline3d::fixed::types::I16F16;
use scanline3d::{Fx, Scalar};

fn check<S: Scalar>() {
    for b in Bench::ALL {
        let [a, _] = compare::<S>(b, 0);
        let m = &a.metrics;
        println!(
            "{} {}: max LSB {:?}, coverage {}, depth order {}, diverged {}, PSNR {:.1}",
            b.name(),
            S::NAME,
            m.max_lsb,
            m.coverage_mismatch,
            m.depth_mismatch,
            a.diverged,
            m.psnr_db()
        );
        assert_eq!(
            a.diverged,
            0,
            "{} {}: snapped geometry could not be replayed",
            b.name(),
            S::NAME
        );
        assert!(
            m.max_lsb.iter().all(|&x| x <= 1),
            "{} {}: max LSB {:?} > 1 against f64 on the same geometry",
            b.name(),
            S::NAME,
            m.max_lsb
        );
        assert_eq!(
            m.coverage_mismatch,
            0,
            "{} {}: coverage differs on the same geometry",
            b.name(),
            S::NAME
        );
    }
}

#[test]
fn fixed_i16f16_within_one_lsb_of_f64_on_same_geometry() {
    check::<Fx<I16F16>>();
}

#[test]
fn f32_within_one_lsb_of_f64_on_same_geometry() {
    check::<f32>();
}
