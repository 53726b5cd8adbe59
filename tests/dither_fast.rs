//! Dithered Gouraud triangles take the fast packed path (`DepthTest::Less`, RGB565): every
//! pixel stays within 1 LSB per channel of the dithered path of before. The reference is the
//! same frame rendered with `DepthTest::LessEqual`, which never takes a fast path, so every
//! Gouraud span there is the portable `fill_gouraud_dither` from the 20-bit values. The two
//! depth tests differ only where two fragments have exactly equal depth, which these scenes
//! (one closed or open object each, or random triangles at distinct depths) do not have; the
//! comparison counts coverage mismatches too and requires none.

use crate::common;

use common::{compare565, screen_camera, Frame};
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d_support::demo::{self, deg};

type Q = Fx<I16F16>;
type R = Renderer<Q, Rgb565, 240, 240, 1024, 2048, 192>;

fn render<const L: usize>(scene: &Scene<'_, Q, L>, test: DepthTest) -> Frame<Rgb565> {
    let mut r: Box<R> = Box::default();
    r.set_dither(true);
    r.set_depth_test(test);
    let mut f = Frame::new(240, 240, Rgb565::BLACK);
    r.render(scene, &mut f).unwrap();
    f.assert_each_written_once();
    f
}

/// Renders `scene` dithered with the fast path and with the reference; returns the worst
/// difference per channel and the pixels that differ, after checking the bound.
fn check<const L: usize>(name: &str, scene: &Scene<'_, Q, L>) -> ([u8; 3], usize) {
    let fast = render(scene, DepthTest::Less);
    let reference = render(scene, DepthTest::LessEqual);
    let (max, differ, coverage) = compare565(&fast, &reference, Rgb565::BLACK);
    println!("{name}: worst |Δ| per channel {max:?} LSB, {differ} pixels differ");
    assert_eq!(coverage, 0, "{name}: coverage differs");
    assert!(max.iter().all(|&m| m <= 1), "{name}: {max:?}");
    (max, differ)
}

#[test]
fn dithered_torus_within_one_lsb_at_several_angles() {
    let shape = demo::torus::<Q>().unwrap();
    let mut total = 0;
    for spin in [0.0, 25.0, 70.0, 140.0, 222.0] {
        let objects = [Object {
            mesh: shape.mesh(),
            transform: demo::torus_transform(spin),
            material: demo::torus_material(),
        }];
        let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
        total += check(&format!("torus spin {spin}"), &scene).1;
    }
    // The packed values are rounded differently from the 20-bit ones: some pixels move.
    assert!(total > 0);
}

#[test]
fn dithered_icosphere_and_terrain_within_one_lsb() {
    let ico = Shape::<Q, 642, 1280>::icosphere(1.0, 3).unwrap();
    for (spin, specular) in [(0.0, 0.6), (40.0, 0.0)] {
        let mut m = Material::matte([200, 60, 60], Q::from_f64(0.1), Q::from_f64(0.8));
        m.specular = Q::from_f64(specular);
        m.shininess = 20;
        let objects = [Object {
            mesh: ico.mesh(),
            transform: Mat4::rotate_y(deg(spin)),
            material: m,
        }];
        let cam = Camera::look_at(
            [Q::ZERO, Q::from_f64(0.5), Q::from_f64(3.0)],
            [Q::ZERO; 3],
            [Q::ZERO, Q::ONE, Q::ZERO],
            Projection::Perspective {
                fov_y: deg(45.0),
                near: Q::from_f64(0.1),
                far: Q::from_f64(10.0),
            },
        )
        .unwrap();
        let scene = Scene::new(&objects, cam, [Light::white([-Q::ONE, Q::ONE, Q::ONE])]);
        check(
            &format!("icosphere spin {spin} specular {specular}"),
            &scene,
        );
    }
    let terrain = Shape::<Q, 289, 512>::terrain(8.0, 16, 0.5).unwrap();
    let objects = [Object {
        mesh: terrain.mesh(),
        transform: Mat4::identity(),
        material: Material::matte([110, 180, 90], Q::from_f64(0.25), Q::from_f64(0.75)),
    }];
    let cam = Camera::look_at(
        [Q::ZERO, Q::from_f64(0.6), Q::from_f64(3.5)],
        [Q::ZERO, Q::from_f64(-0.3), Q::ZERO],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: deg(60.0),
            near: Q::from_f64(0.1),
            far: Q::from_f64(20.0),
        },
    )
    .unwrap();
    let scene = Scene::new(
        &objects,
        cam,
        [Light::white([Q::ONE, Q::from_f64(2.0), Q::ONE])],
    );
    check("terrain", &scene);
}

/// Random triangles in screen space, each at its own depth, lit by a white light through
/// random vertex normals (so channels run over their whole range, 0 and the maximum
/// included, within a triangle), sizes from a few pixels to most of the screen.
#[test]
fn dithered_random_triangles_within_one_lsb() {
    let mut state = 0x9e37_79b9u32;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    };
    let mut unit = move || (next() % 2001) as f64 / 1000.0 - 1.0;
    for frame in 0..12 {
        let n = 40;
        let mut pos = Vec::new();
        let mut nrm = Vec::new();
        let mut idx = Vec::new();
        for t in 0..n {
            let size = [8.0, 30.0, 90.0, 200.0][(t + frame) % 4];
            let (cx, cy) = (unit() * 100.0, unit() * 100.0);
            let z = -(t as f64) * 0.2;
            for _ in 0..3 {
                pos.push([cx + unit() * size, cy + unit() * size, z].map(Q::from_f64));
                let (a, b) = (unit(), unit());
                nrm.push([a, b, 1.0 + unit()].map(Q::from_f64));
            }
            let k = 3 * t as u16;
            idx.push([k, k + 1, k + 2]);
            // Both windings: back faces are culled.
            idx.push([k, k + 2, k + 1]);
        }
        let mesh = Mesh::new(&pos, &idx).unwrap().with_normals(&nrm).unwrap();
        let color = [[255, 255, 255], [255, 128, 16], [40, 220, 250]][frame % 3];
        let objects = [Object {
            mesh,
            transform: Mat4::identity(),
            material: Material::matte(color, Q::from_f64(0.0), Q::from_f64(1.2)),
        }];
        let light = Light::white([Q::from_f64(0.3), Q::from_f64(-0.2), Q::ONE]);
        let scene = Scene::new(&objects, screen_camera::<Q>(240), [light]);
        check(&format!("random triangles {frame}"), &scene);
    }
}
