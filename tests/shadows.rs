//! Layered frames: projected planar shadows (stencilled: overlaps darken once, nothing outside
//! the receivers) and translucent materials (the same image in any submission order), in every
//! number type, and the shadow benchmark scenes' golden images.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{
    errors::LayerError, shadow::Layering, shadow::PlanarShadow, shadow::ShadowLight, Error, Layers,
};
use scanline3d_support::demo::Bench;

type Q = Fx<scanline3d::fixed::types::I16F16>;

const N: u32 = 64;

/// A unit square in the plane y = `y`, centred at (`cx`, `cz`), half-size `h`, facing up.
fn square<S: Scalar>(cx: f64, cz: f64, y: f64, h: f64) -> [[S; 3]; 4] {
    [
        [cx - h, y, cz + h],
        [cx + h, y, cz + h],
        [cx + h, y, cz - h],
        [cx - h, y, cz - h],
    ]
    .map(|p| p.map(S::from_f64))
}

const QUAD: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

fn top_camera<S: Scalar>() -> Camera<S> {
    // Straight down onto the ground (up = −z), orthographic: 1 world unit = 16 px.
    Camera::look_at(
        [0.0, 10.0, 0.0].map(S::from_f64),
        [S::ZERO; 3],
        [0.0, 0.0, -1.0].map(S::from_f64),
        Projection::Orthographic {
            height: S::from_f64(N as f64 / 16.0),
            near: S::from_f64(1.0),
            far: S::from_f64(20.0),
        },
    )
    .unwrap()
}

fn unlit<S: Scalar>(c: [u8; 3]) -> Material<S> {
    Material::matte(c, S::ONE, S::ZERO).flat()
}

/// The ground (object 0, half-size `g`) and two small squares floating above it (objects 1 and
/// 2) whose straight-down shadows overlap, drawn from above with a shadow of opacity `alpha`;
/// the casters are drawn only if `show_casters`.
fn shadow_frame<S: Scalar>(g: f64, alpha: u8, show_casters: bool) -> Frame<Rgb888> {
    let ground = square::<S>(0.0, 0.0, 0.0, g);
    // Hidden casters are fully transparent (opacity 0): only their shadows show.
    let a = square::<S>(-0.5, 0.0, 1.0, 0.5);
    let b = square::<S>(0.25, 0.25, 2.0, 0.5);
    let gs: &[[S; 3]] = &ground;
    let (as_, bs): (&[[S; 3]], &[[S; 3]]) = (&a, &b);
    let hidden = if show_casters { 255 } else { 0 };
    let objects = [
        Object {
            mesh: Mesh::new(gs, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit([200, 200, 200]),
        },
        Object {
            mesh: Mesh::new(as_, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit::<S>([255, 0, 0]).translucent(hidden),
        },
        Object {
            mesh: Mesh::new(bs, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit::<S>([0, 0, 255]).translucent(hidden),
        },
    ];
    let scene = Scene::new(
        &objects,
        top_camera(),
        [Light::white([S::ZERO, S::ONE, S::ZERO])],
    )
    .with_background([10, 20, 30]);
    let plane = [S::ZERO, S::ONE, S::ZERO, S::ZERO];
    let light = ShadowLight::Directional([S::ZERO, S::ONE, S::ZERO]);
    let layering = Layering::projected(&[0], &[1, 2], PlanarShadow::new(plane, light, alpha));
    let mut r = Renderer::<S, Rgb888, 64, 64, 64, 64, 16>::new();
    let mut layers = Layers::<64, 1, 4, 16>::new();
    let mut f = Frame::new(N, N, Rgb888::BLACK);
    r.render_with(
        &scene,
        scanline3d::FrameOptions::new().layered(&layering, &mut layers),
        &mut f,
    )
    .unwrap();
    f.assert_each_written_once();
    f
}

fn count(f: &Frame<Rgb888>, c: Rgb888) -> usize {
    (0..N)
        .flat_map(|y| (0..N).map(move |x| (x, y)))
        .filter(|&(x, y)| f.get(x, y) == c)
        .count()
}

fn overlapping_shadows_darken_once<S: Scalar>() {
    let f = shadow_frame::<S>(1.5, 128, false);
    let ground = Rgb888::new(200, 200, 200);
    // 200·(255 − 128)/255 = 99.6 → 100.
    let shadow = Rgb888::new(100, 100, 100);
    // The two shadows, 16 × 16 px each: a at x ∈ [−1, 0], z ∈ [−0.5, 0.5]; b at
    // x ∈ [−0.25, 0.75], z ∈ [−0.25, 0.75]; they overlap on 0.25 × 0.75 units.
    let union_area = 1.0 + 1.0 - 0.25 * 0.75;
    let px = (union_area * 256.0) as usize;
    let dark = count(&f, shadow);
    assert_eq!(dark, px, "shadowed pixels");
    // Nothing darker than one shadow (the overlap darkened once).
    for y in 0..N {
        for x in 0..N {
            let c = f.get(x, y);
            assert!(
                c == shadow || c == ground || c == Rgb888::new(10, 20, 30),
                "({x}, {y}): {c:?}"
            );
        }
    }
}

#[test]
fn overlapping_shadows_darken_once_in_every_number_type() {
    overlapping_shadows_darken_once::<Q>();
    overlapping_shadows_darken_once::<f32>();
    overlapping_shadows_darken_once::<f64>();
}

fn no_shadow_outside_the_receiver<S: Scalar>() {
    // A ground of half-size 0.5: the shadows reach beyond it, onto the background.
    let with = shadow_frame::<S>(0.5, 200, false);
    let bg = Rgb888::new(10, 20, 30);
    let ground_px = count(&with, Rgb888::new(200, 200, 200)) + count(&with, shadow_of(200, 200));
    assert_eq!(ground_px, 16 * 16, "the ground square");
    assert_eq!(
        count(&with, bg) as u32,
        N * N - 256,
        "the background is untouched"
    );
}

fn shadow_of(c: u32, a: u32) -> Rgb888 {
    let v = ((c * (255 - a) + 127) / 255) as u8;
    Rgb888::new(v, v, v)
}

#[test]
fn a_shadow_never_appears_outside_its_receiver() {
    no_shadow_outside_the_receiver::<Q>();
    no_shadow_outside_the_receiver::<f32>();
    no_shadow_outside_the_receiver::<f64>();
}

#[test]
fn a_shadow_does_not_fall_on_the_casters_in_front_of_the_receiver() {
    // Opaque casters: where they are seen, they show their own colour, undarkened.
    let f = shadow_frame::<f64>(1.5, 128, true);
    let (red, blue) = (Rgb888::new(255, 0, 0), Rgb888::new(0, 0, 255));
    // b is above a (nearer the camera) and covers 0.25 × 0.75 units of it.
    assert_eq!(count(&f, blue), 256);
    assert_eq!(count(&f, red), 256 - (0.25 * 0.75 * 256.0) as usize);
}

/// Two overlapping translucent squares over an opaque ground, given in either order.
fn translucent_frame<S: Scalar>(swap: bool) -> Frame<Rgb565> {
    let ground = square::<S>(0.0, 0.0, 0.0, 1.5);
    let a = square::<S>(-0.4, 0.0, 1.0, 0.6);
    let b = square::<S>(0.3, 0.2, 2.0, 0.6);
    let gs: &[[S; 3]] = &ground;
    let (as_, bs): (&[[S; 3]], &[[S; 3]]) = (&a, &b);
    fn mk<'a, S: Scalar>(m: &'a [[S; 3]], c: [u8; 3], alpha: u8) -> Object<'a, S> {
        Object {
            mesh: Mesh::new(m, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit::<S>(c).translucent(alpha),
        }
    }
    let g = mk(gs, [200, 200, 200], 255);
    let (ta, tb) = (mk(as_, [255, 0, 0], 120), mk(bs, [0, 0, 255], 180));
    let objects = if swap { [tb, g, ta] } else { [g, ta, tb] };
    let scene = Scene::new(
        &objects,
        top_camera(),
        [Light::white([S::ZERO, S::ONE, S::ZERO])],
    );
    let mut r = Renderer::<S, Rgb565, 64, 64, 64, 64, 16>::new();
    let mut layers = Layers::<64, 1, 1, 16>::new();
    let mut f = Frame::new(N, N, Rgb565::BLACK);
    r.render_with(
        &scene,
        scanline3d::FrameOptions::new().layered(&Layering::none(), &mut layers),
        &mut f,
    )
    .unwrap();
    f.assert_each_written_once();
    f
}

fn translucent_any_order<S: Scalar>() {
    let (a, b) = (translucent_frame::<S>(false), translucent_frame::<S>(true));
    assert!(a.px == b.px, "the submission order changed the image");
    // Where only the red square is over the ground: round((255·120 + 200·135)/255) in 8
    // bits, then RGB565 (5 bits: round(v·31/255)).
    let at = |f: &Frame<Rgb565>, x: f64, z: f64| {
        let px = ((x * 16.0) + 32.0) as u32;
        let py = ((z * 16.0) + 32.0) as u32;
        f.get(px, py)
    };
    let red_only = at(&a, -0.8, -0.3);
    let r5 = |v8: u32| ((v8 * 31 + 127) / 255) as u8;
    let r6 = |v8: u32| ((v8 * 63 + 127) / 255) as u8;
    // Blended in the target's units: ground 200 → (25, 49, 25), red 255 → 31.
    let blend = |d: u32, s: u32, a: u32| ((d * (255 - a) + s * a + 127) / 255) as u8;
    let (gr, gg) = (r5(200) as u32, r6(200) as u32);
    let want = Rgb565::new(blend(gr, 31, 120), blend(gg, 0, 120), blend(gr, 0, 120));
    assert_eq!(red_only, want);
}

#[test]
fn translucent_triangles_give_the_same_image_in_any_order() {
    translucent_any_order::<Q>();
    translucent_any_order::<f32>();
    translucent_any_order::<f64>();
}

#[test]
fn plain_render_refuses_translucent_materials_and_bad_layerings_are_errors() {
    let ground = square::<f64>(0.0, 0.0, 0.0, 1.0);
    let gs: &[[f64; 3]] = &ground;
    let objects = [Object {
        mesh: Mesh::new(gs, &QUAD).unwrap(),
        transform: Mat4::identity(),
        material: unlit::<f64>([9, 9, 9]).translucent(100),
    }];
    let scene = Scene::new(&objects, top_camera(), [Light::white([0.0, 1.0, 0.0])]);
    let mut r = Renderer::<f64, Rgb565, 64, 64, 64, 64, 16>::new();
    let mut f = Frame::new(N, N, Rgb565::BLACK);
    assert_eq!(
        r.render(&scene, &mut f).unwrap_err(),
        Error::NeedsLayers { object: 0 }
    );
    let opaque = [Object {
        material: unlit::<f64>([9, 9, 9]),
        ..objects[0]
    }];
    let scene = Scene::new(&opaque, top_camera(), [Light::white([0.0, 1.0, 0.0])]);
    let mut layers = Layers::<64, 1, 1, 4>::new();
    let up = ShadowLight::Directional([0.0, 1.0, 0.0]);
    let plane = [0.0, 1.0, 0.0, 0.0];
    let cases = [
        (
            Layering::projected(&[3], &[0], PlanarShadow::new(plane, up, 1)),
            LayerError::NoSuchObject { index: 3 },
        ),
        (
            Layering::projected(
                &[0],
                &[0],
                PlanarShadow::new(plane, ShadowLight::Directional([1.0, 0.0, 0.0]), 1),
            ),
            LayerError::Shadow,
        ),
        (
            Layering::projected(&[0], &[0], PlanarShadow::new([f64::NAN; 4], up, 1)),
            LayerError::Shadow,
        ),
        (
            // The ground is at y = 0, the plane at y = 0.5.
            Layering::projected(&[0], &[0], PlanarShadow::new([0.0, 1.0, 0.0, -0.5], up, 1)),
            LayerError::OffPlane { object: 0 },
        ),
    ];
    for (layering, want) in cases {
        let mut f = Frame::new(N, N, Rgb565::BLACK);
        assert_eq!(
            r.render_with(
                &scene,
                scanline3d::FrameOptions::new().layered(&layering, &mut layers),
                &mut f
            )
            .unwrap_err(),
            Error::Layers(want)
        );
        assert!(f.writes.iter().all(|&n| n == 0), "nothing drawn");
    }
}

#[test]
fn shadow_benchmark_scenes_match_their_golden_images() {
    fn go<S: Scalar>(ty: &str) {
        for b in [
            Bench::ShadowNone,
            Bench::Shadow,
            Bench::ShadowBlob,
            Bench::Translucent,
            Bench::ShadowVolume,
            Bench::Outline,
            Bench::Edges,
            Bench::Wireframe,
            Bench::ShadowMap,
            Bench::ShadowMapPcf,
            Bench::ShadowImageBlur,
        ] {
            common::compare::check_bench_golden::<S>(b, ty);
        }
    }
    go::<Q>("i16f16");
    go::<f32>("f32");
    go::<f64>("f64");
}
