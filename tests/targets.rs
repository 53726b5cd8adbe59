//! Gouraud shading into targets with few bits per channel (BinaryColor, Gray2, Gray4) and
//! Gray8: no panic in debug (overflow checks on) or release, with or without dithering, for
//! every number type, and images that agree with the 8-bit grey render (issue #21: a Gouraud
//! BinaryColor frame panicked in `pack_channels` and came out all Off in release; Gray2/Gray4
//! without dithering panicked on a 32-bit shift of the missing green channel).

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::{BinaryColor, Gray2, Gray4, Gray8, GrayColor};
use embedded_graphics::prelude::*;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d_support::demo::deg;

/// A lit white icosphere, Gouraud, 64 × 64, into a `C` frame.
fn sphere<S: Scalar, C: TargetColor + PixelColor>(dither: bool, bg: C) -> Frame<C> {
    let shape = Shape::<S, 162, 320>::icosphere(1.0, 2).unwrap();
    let objects = [Object {
        mesh: shape.mesh(),
        transform: Mat4::identity(),
        material: Material::matte([255, 255, 255], S::from_f64(0.1), S::from_f64(0.9)),
    }];
    let camera = Camera::look_at(
        [S::ZERO, S::ZERO, S::from_f64(3.0)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(50.0),
            near: S::from_f64(0.1),
            far: S::from_f64(10.0),
        },
    )
    .unwrap();
    let scene = Scene::new(&objects, camera, [Light::white([-S::ONE, S::ONE, S::ONE])]);
    let mut r = Box::new(Renderer::<S, C, 64, 64, 162, 320, 64>::new().with_dither(dither));
    let mut f = Frame::new(64, 64, bg);
    r.render(&scene, &mut f).unwrap();
    f
}

fn check<S: Scalar>() {
    for dither in [false, true] {
        let g8 = sphere::<S, Gray8>(dither, Gray8::BLACK);
        let lit = g8.px.iter().filter(|c| c.luma() > 0).count();
        assert!(lit > 1000, "{} grey: {lit} lit pixels", S::NAME);
        // Gray4 and Gray2 within one of their steps (plus the dither's) of the 8-bit grey.
        for (bits, frame) in [
            (
                4u32,
                sphere::<S, Gray4>(dither, Gray4::BLACK)
                    .px
                    .iter()
                    .map(|c| c.luma())
                    .collect::<Vec<_>>(),
            ),
            (
                2,
                sphere::<S, Gray2>(dither, Gray2::BLACK)
                    .px
                    .iter()
                    .map(|c| c.luma())
                    .collect(),
            ),
        ] {
            let max = (1u32 << bits) - 1;
            let tolerance = if dither { 2.0 } else { 1.0 };
            for (i, (&g, want)) in frame.iter().zip(&g8.px).enumerate() {
                let got = g as f64 * 255.0 / max as f64;
                let step = 255.0 / max as f64;
                assert!(
                    (got - want.luma() as f64).abs() <= tolerance * step,
                    "{} Gray{bits} dither {dither} pixel {i}: {g} against grey {}",
                    S::NAME,
                    want.luma()
                );
            }
        }
        // BinaryColor: On where the grey is clearly light, Off where clearly dark.
        let bin = sphere::<S, BinaryColor>(dither, BinaryColor::Off);
        let on = bin.px.iter().filter(|&&c| c == BinaryColor::On).count();
        assert!(
            on > 500,
            "{} binary dither {dither}: {on} pixels On",
            S::NAME
        );
        if !dither {
            for (i, (&b, g)) in bin.px.iter().zip(&g8.px).enumerate() {
                if g.luma() > 160 {
                    assert_eq!(
                        b,
                        BinaryColor::On,
                        "{} pixel {i}: grey {}",
                        S::NAME,
                        g.luma()
                    );
                }
                if g.luma() < 96 {
                    assert_eq!(
                        b,
                        BinaryColor::Off,
                        "{} pixel {i}: grey {}",
                        S::NAME,
                        g.luma()
                    );
                }
            }
        }
    }
}

#[test]
fn few_bit_targets_with_gouraud_fixed() {
    check::<Fx<I16F16>>();
}

#[test]
fn few_bit_targets_with_gouraud_f32() {
    check::<f32>();
}

#[test]
fn few_bit_targets_with_gouraud_f64() {
    check::<f64>();
}
