//! Shadow maps (issue #42): the map pass against an f64 ray cast of its casters, per map size
//! and number type, for a directional and a point light over the shadow benchmark's models (a
//! torus and a cube above a ground square).

use embedded_graphics::pixelcolor::Rgb565;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::shadow::{ShadowLight, ShadowMap, ShadowMapping};
use scanline3d_support::demo::SHADOW_LIGHT;
use scanline3d_support::host::raycast::{map_against_raycast, world_triangles, MapAccuracy};

type Q = Fx<I16F16>;

/// The ground (object 0), the torus (1) and the cube (2), placed as the shadow benchmark
/// places them.
fn with_models<S: Scalar, R>(f: impl FnOnce(&[Object<'_, S>]) -> R) -> R {
    let ground = Shape::<S, 4, 2>::plane(5.0, 5.0, 1, 1).unwrap();
    let torus = Shape::<S, 288, 576>::torus(0.7, 0.25, 24, 12).unwrap();
    let cube = Shape::<S, 24, 12>::cube(0.35).unwrap();
    let s = S::from_f64;
    let m = Material::matte([200, 200, 200], s(0.25), s(0.75));
    let deg = |d: f64| s(d.to_radians());
    let objects = [
        Object {
            mesh: ground.mesh(),
            transform: Mat4::identity(),
            material: m.flat(),
        },
        Object {
            mesh: torus.mesh(),
            transform: Mat4::rotate_x(deg(35.0)).then(&Mat4::translate([s(-0.4), s(1.2), s(-0.2)])),
            material: m,
        },
        Object {
            mesh: cube.mesh(),
            transform: Mat4::rotate_y(deg(30.0)).then(&Mat4::translate([s(0.55), s(0.5), s(0.7)])),
            material: m.flat(),
        },
    ];
    f(&objects)
}

/// The map of `N` texels a side of the torus and the cube, fitted to the ground, against the
/// ray cast.
fn accuracy<S: Scalar, const N: usize>(light: ShadowLight<S>) -> MapAccuracy {
    with_models::<S, _>(|objects| {
        let camera = Camera::look_at(
            [0.0, 3.8, 4.6].map(S::from_f64),
            [0.0, 0.3, 0.0].map(S::from_f64),
            [0.0, 1.0, 0.0].map(S::from_f64),
            Projection::Perspective {
                fov_y: S::from_f64(0.8),
                near: S::from_f64(0.5),
                far: S::from_f64(20.0),
            },
        )
        .unwrap();
        let scene = Scene::new(
            objects,
            camera,
            [Light::white(SHADOW_LIGHT.map(S::from_f64))],
        );
        let mapping = ShadowMapping::new(light, &[1, 2], &[0]);
        let mut renderer = Renderer::<S, Rgb565, 128, 128, 1024, 1024, 64, 8>::new();
        let mut map = Box::new(ShadowMap::<N>::new());
        renderer
            .shadow_map_pass(&scene, &mapping, &mut map)
            .unwrap();
        let depth: Vec<u16> = map.depth().iter().flatten().copied().collect();
        let tris = world_triangles(objects, &[1, 2]);
        map_against_raycast(&depth, N, map.world_to_map().unwrap(), &tris)
    })
}

fn lights<S: Scalar>() -> [(&'static str, ShadowLight<S>); 2] {
    [
        (
            "directional",
            ShadowLight::Directional(SHADOW_LIGHT.map(S::from_f64)),
        ),
        (
            "point",
            ShadowLight::Point([-2.4, 3.5, 1.2].map(S::from_f64)),
        ),
    ]
}

fn check<S: Scalar>() {
    for (name, light) in lights::<S>() {
        let results = [
            (32, accuracy::<S, 32>(light)),
            (64, accuracy::<S, 64>(light)),
            (128, accuracy::<S, 128>(light)),
        ];
        for (n, a) in results {
            println!(
                "shadow map {n}x{n} {name} {}: {} of {} texels covered, coverage differs at {} ({} not at an edge), depth error max {:.2} mean {:.3} steps, beyond the snapping at {} depth-edge texels and {} others",
                S::NAME,
                a.covered,
                a.texels,
                a.coverage_mismatch,
                a.isolated_mismatch,
                a.max_depth_error,
                a.mean_depth_error,
                a.depth_edge,
                a.beyond_snapping
            );
            assert!(
                a.covered > a.texels / 50,
                "{name} {n}: the casters cover too little of the map"
            );
            assert_eq!(
                a.isolated_mismatch,
                0,
                "{name} {n} {}: a hole or spill in the map",
                S::NAME
            );
            // Only texels whose centre is within the snapping of an edge differ.
            assert!(
                a.coverage_mismatch * 50 <= a.covered,
                "{name} {n} {}: {} texels' coverage differs",
                S::NAME,
                a.coverage_mismatch
            );
            assert_eq!(
                a.beyond_snapping,
                0,
                "{name} {n} {}: depth beyond the snapping",
                S::NAME
            );
        }
    }
}

#[test]
fn map_against_raycast_f64() {
    check::<f64>();
}

#[test]
fn map_against_raycast_f32() {
    check::<f32>();
}

#[test]
fn map_against_raycast_i16f16() {
    check::<Q>();
}
