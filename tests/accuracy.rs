//! The accuracy contract of the fixed-point pipeline, asserted for every benchmark scene:
//! against the f64 twin on the same snapped screen geometry (reference (a), which isolates
//! arithmetic error), every fixed-point and f32 frame is within 1 LSB per RGB565 channel with no
//! coverage mismatch (a textured frame: fewer than 10 % of the pixels show another texel). A
//! regression in accuracy fails CI.

use crate::common;

use common::compare::compare;
use scanline3d::fixed::types::I16F16;
use scanline3d::{Fx, Scalar};
use scanline3d_support::demo::Bench;

fn check<S: Scalar>() {
    for b in Bench::ALL {
        let [a, _] = compare::<S>(b, 0);
        let m = &a.metrics;
        println!(
            "{} {}: max LSB {:?}, differing {} of {} px, coverage {}, depth order {}, diverged {}, PSNR {:.1}",
            b.name(),
            S::NAME,
            m.max_lsb,
            m.differing,
            m.pixels,
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
        if matches!(
            b,
            Bench::Textured | Bench::TexturedAffine | Bench::TexturedExact | Bench::TexturedFog
        ) {
            // A texel is a step of any size: where the exact texture coordinate lies within a
            // rounding of a texel's edge, two number types may pick neighbouring texels (the
            // coordinates of clipped vertices and the depth come from `S`), and where the
            // floor is minified (several texels to a pixel, far away) nearly any difference
            // picks another texel. The texture coordinates' own bound is in texels, against a
            // ray-cast reference, clipped floor included (`tests/textures.rs`); here, a bound
            // on the pixels (I16F16 measures 2 % for `textured` and 8 % for
            // `textured_affine`, whose long affine spans carry a vertex's difference far).
            assert!(
                m.differing * 10 < m.pixels,
                "{} {}: {} of {} pixels differ from f64 on the same geometry",
                b.name(),
                S::NAME,
                m.differing,
                m.pixels
            );
        } else if b == Bench::Toon {
            // A toon tone is a step too: where a pixel's N·L lies within a rounding of a band's
            // edge, the normals of two number types (each type's own vertex normals, in Q1.14)
            // may put it in neighbouring bands (I16F16 measures 3 such pixels of 57 600).
            assert!(
                m.differing * 1000 < m.pixels,
                "{} {}: {} of {} pixels differ from f64 on the same geometry",
                b.name(),
                S::NAME,
                m.differing,
                m.pixels
            );
        } else if b == Bench::ShadowVolume
            || b.name().starts_with("shadow_map")
            || b.name().starts_with("shadow_image")
        {
            // (A shadow map's texel is a step the same way: where a receiver's light depth
            // lies within a rounding of the map's, or a pixel's texel within a rounding of a
            // texel's edge, two number types' maps and light planes may disagree; I16F16
            // measures 2 such pixels of 57 600.)
            // A pixel is in a shadow volume or not: a step. Where a volume face passes within
            // a rounding of the visible surface's depth (the rim of a shadow on the ground, the
            // terminator of a curved caster), two number types may count it differently: the
            // screen positions are replayed here, the depths are each type's own (I16F16
            // measures 7 such pixels of 57 600).
            assert!(
                m.differing * 1000 < m.pixels,
                "{} {}: {} of {} pixels differ from f64 on the same geometry",
                b.name(),
                S::NAME,
                m.differing,
                m.pixels
            );
        } else {
            assert!(
                m.max_lsb.iter().all(|&x| x <= 1),
                "{} {}: max LSB {:?} > 1 against f64 on the same geometry",
                b.name(),
                S::NAME,
                m.max_lsb
            );
        }
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

/// The device path: two renderers (fixed point and f64) prepared on the same scene and drawn
/// strip by strip, side by side, into two one-strip captures; the line-by-line metrics equal the
/// whole-frame comparison.
#[test]
fn strip_by_strip_comparison_in_o_width_memory() {
    use common::Frame;
    use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    use scanline3d::{Renderer, Scene};
    use scanline3d_support::demo;
    use scanline3d_support::metrics::{Metrics, StripCapture};
    type Q = Fx<I16F16>;
    let sq = demo::torus::<Q>().unwrap();
    let sf = demo::torus::<f64>().unwrap();
    let oq = [demo::torus_object(&sq)];
    let of = [demo::torus_object(&sf)];
    let scene_q = Scene::new(&oq, demo::camera().unwrap(), demo::lights());
    let scene_f = Scene::new(&of, demo::camera().unwrap(), demo::lights());
    let mut rq: Box<Renderer<Q, Rgb565, 240, 240, 512, 512, 64, 3>> = Box::default();
    let mut rf: Box<Renderer<f64, Rgb565, 240, 240, 512, 512, 64, 3>> = Box::default();
    let mut q = rq
        .prepare(&scene_q, scanline3d::FrameOptions::new())
        .unwrap();
    let mut f = rf
        .prepare(&scene_f, scanline3d::FrameOptions::new())
        .unwrap();
    let mut cq = StripCapture::<Rgb565, 240, 3>::new(240, Rgb565::BLACK);
    let mut cf = StripCapture::<Rgb565, 240, 3>::new(240, Rgb565::BLACK);
    let mut m = Metrics::new([31, 63, 31]);
    while let Some(rows) = q.strip_to(&mut cq).unwrap() {
        assert_eq!(f.strip_to(&mut cf).unwrap(), Some(rows.clone()));
        for k in 0..rows.len() {
            m.add_line(cq.line(k), cf.line(k), Rgb565::BLACK);
        }
    }
    assert_eq!(f.strip_to(&mut cf).unwrap(), None);
    // The same comparison on whole frames.
    let mut fq = Frame::new(240, 240, Rgb565::BLACK);
    let mut ff = Frame::new(240, 240, Rgb565::BLACK);
    rq.render(&scene_q, &mut fq).unwrap();
    rf.render(&scene_f, &mut ff).unwrap();
    let mut whole = Metrics::new([31, 63, 31]);
    for y in 0..240 {
        whole.add_line(
            &fq.px[y * 240..(y + 1) * 240],
            &ff.px[y * 240..(y + 1) * 240],
            Rgb565::BLACK,
        );
    }
    assert_eq!(m, whole);
    assert_eq!(m.pixels, 240 * 240);
    assert!(m.max_lsb.iter().all(|&x| x <= 2), "{:?}", m.max_lsb);
}
