//! Whole scenes rendered into a simulated display buffer and compared with golden PNGs under
//! `tests/golden/` (regenerate with `UPDATE_GOLDEN=1 cargo test --test scenes`, then look at
//! every image before committing). Each scene runs for I16F16, f32 and f64; the fixed-point and
//! f32 images are also compared with the f64 twin.

use crate::common;

use common::{at, check_golden, compare565, screen_camera, unlit, Frame};
use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanline3d::color::quantize;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::Stats;
use scanline3d_support::demo::{self, deg};

type Q = Fx<I16F16>;

fn frame<C: TargetColor>(w: usize, h: usize) -> Frame<C> {
    Frame::new(w as u32, h as u32, C::from_channels([0; 3]))
}

fn render<S: Scalar, const W: usize, const H: usize, const L: usize>(
    scene: &Scene<'_, S, L>,
) -> (Frame<Rgb565>, Stats) {
    let mut r: Box<Renderer<S, Rgb565, W, H, 2048, 2048, 256>> = Box::default();
    let mut f = frame(W, H);
    let stats = r.render(scene, &mut f).expect("render");
    f.assert_each_written_once();
    (f, stats)
}

/// Renders a scene for all three types; checks goldens and bounds against f64.
fn all_types<const W: usize, const H: usize>(
    name: &str,
    build: impl Fn(&mut dyn FnMut(&str, &dyn Fn() -> (Frame<Rgb565>, Stats))),
    max_lsb: u8,
    max_coverage: usize,
) {
    let mut frames = Vec::new();
    build(&mut |ty: &str, f: &dyn Fn() -> (Frame<Rgb565>, Stats)| {
        let (img, stats) = f();
        check_golden(&format!("{name}_{ty}"), &img);
        frames.push((ty.to_string(), img, stats));
    });
    let reference = frames.iter().find(|f| f.0 == "f64").expect("f64 run");
    for (ty, img, _) in &frames {
        let (max, _, coverage) = compare565(img, &reference.1, Rgb565::BLACK);
        assert!(
            max.iter().all(|&m| m <= max_lsb) && coverage <= max_coverage,
            "{name} {ty} vs f64: max LSB {max:?} (bound {max_lsb}), coverage mismatches {coverage} (bound {max_coverage})"
        );
    }
}

macro_rules! three {
    ($run:ident, $name:expr, $w:expr, $h:expr, $lsb:expr, $cov:expr) => {
        all_types::<$w, $h>(
            $name,
            |emit| {
                emit("I16F16", &|| $run::<Q>());
                emit("f32", &|| $run::<f32>());
                emit("f64", &|| $run::<f64>());
            },
            $lsb,
            $cov,
        )
    };
}

fn torus<S: Scalar>() -> (Frame<Rgb565>, Stats) {
    let shape = demo::torus::<S>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let (f, stats) = render::<S, 240, 240, 1>(&scene);
    assert_eq!(stats.triangles_in, 1024);
    assert!(
        (36_000..37_000).contains(&stats.pixels_written),
        "{}",
        stats.pixels_written
    );
    (f, stats)
}

#[test]
fn gouraud_torus_default_scene() {
    three!(torus, "torus_gouraud", 240, 240, 1, 12);
}

fn cube<S: Scalar>() -> (Frame<Rgb565>, Stats) {
    let shape = Shape::<S, 24, 12>::cube(1.0).unwrap();
    let mut material = Material::matte([90, 160, 255], S::from_f64(0.2), S::from_f64(0.8));
    material.shading = Shading::Flat;
    let objects = [Object {
        mesh: shape.mesh(),
        transform: Mat4::rotate_y(deg(35.0)).then(&Mat4::rotate_x(deg(25.0))),
        material,
    }];
    let camera = Camera::look_at(
        [S::ZERO, S::ZERO, S::from_f64(4.5)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(45.0),
            near: S::from_f64(0.1),
            far: S::from_f64(10.0),
        },
    )
    .unwrap();
    let scene = Scene::new(
        &objects,
        camera,
        [Light::white([-S::ONE, S::from_f64(2.0), S::from_f64(3.0)])],
    );
    let (f, stats) = render::<S, 128, 128, 1>(&scene);
    // Three faces visible: 6 triangles drawn, 6 culled.
    assert_eq!((stats.drawn, stats.culled), (6, 6));
    // Flat shading: exactly three distinct non-background colours.
    let mut colours: Vec<Rgb565> =
        f.px.iter()
            .copied()
            .filter(|&c| c != Rgb565::BLACK)
            .collect();
    colours.sort_by_key(|c| (c.r(), c.g(), c.b()));
    colours.dedup();
    assert_eq!(colours.len(), 3, "{colours:?}");
    (f, stats)
}

#[test]
fn flat_cube() {
    three!(cube, "cube_flat", 128, 128, 1, 8);
}

/// A floor triangle at y = −1 seen from the origin looking down −Z, with `behind` of its
/// vertices behind the eye (z > 0).
fn floor<S: Scalar>(behind: usize) -> (Frame<Rgb565>, Stats) {
    let p = |x: f64, z: f64| [S::from_f64(x), S::from_f64(-1.0), S::from_f64(z)];
    let pos = match behind {
        1 => [p(-5.0, -10.0), p(0.0, 5.0), p(5.0, -10.0)],
        _ => [p(0.0, -10.0), p(-5.0, 5.0), p(5.0, 5.0)],
    };
    let idx = [[0u16, 1, 2]];
    let mesh = Mesh::new(&pos, &idx).unwrap();
    let objects = [Object {
        mesh,
        transform: Mat4::identity(),
        material: unlit([255, 255, 255], Shading::Flat),
    }];
    let camera = Camera::look_at(
        [S::ZERO; 3],
        [S::ZERO, S::ZERO, -S::ONE],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(60.0),
            near: S::from_f64(0.1),
            far: S::from_f64(100.0),
        },
    )
    .unwrap();
    let scene = Scene::new(&objects, camera, [Light::white([S::ZERO, S::ONE, S::ZERO])]);
    let (f, stats) = render::<S, 96, 96, 1>(&scene);
    assert_eq!(stats.clipped, 1, "{stats:?}");
    // Nothing may appear above the horizon (row 48): a triangle divided by a negative w would
    // be mirrored up there.
    for y in 0..48 {
        for x in 0..96 {
            assert_eq!(
                f.get(x, y),
                Rgb565::BLACK,
                "{}: pixel ({x}, {y}) above the horizon",
                S::NAME
            );
        }
    }
    // The floor under the camera reaches the bottom row.
    assert_eq!(f.get(48, 95), Rgb565::WHITE, "{}", S::NAME);
    (f, stats)
}

fn floor_one_behind<S: Scalar>() -> (Frame<Rgb565>, Stats) {
    floor::<S>(1)
}

fn floor_two_behind<S: Scalar>() -> (Frame<Rgb565>, Stats) {
    let (f, stats) = floor::<S>(2);
    // The far vertex is a point ahead: the covered region narrows toward the horizon.
    assert_eq!(f.get(2, 50), Rgb565::BLACK);
    (f, stats)
}

#[test]
fn near_plane_one_vertex_behind_the_eye() {
    three!(floor_one_behind, "near_one_behind", 96, 96, 0, 6);
}

#[test]
fn near_plane_two_vertices_behind_the_eye() {
    three!(floor_two_behind, "near_two_behind", 96, 96, 0, 6);
}

/// A red triangle at depth 0 pierced by a blue one that goes from z = −3 (left, farther) to
/// z = +3 (right, nearer); orthographic screen camera.
fn interpenetrating<S: Scalar>() -> (Frame<Rgb565>, Stats) {
    let (w, h) = (64, 64);
    let p = |x: f64, y: f64, z: f64| at::<S>(w, h, x, y, z);
    let red = [p(8.0, 8.0, 0.0), p(8.0, 56.0, 0.0), p(56.0, 32.0, 0.0)];
    let blue = [p(8.0, 30.0, -3.0), p(56.0, 54.0, 3.0), p(56.0, 10.0, 3.0)];
    let idx = [[0u16, 1, 2]];
    let objects = [
        Object {
            mesh: Mesh::new(&red, &idx).unwrap(),
            transform: Mat4::identity(),
            material: unlit([255, 0, 0], Shading::Flat),
        },
        Object {
            mesh: Mesh::new(&blue, &idx).unwrap(),
            transform: Mat4::identity(),
            material: unlit([0, 0, 255], Shading::Flat),
        },
    ];
    let scene = Scene::new(
        &objects,
        screen_camera::<S>(h),
        [Light::white([S::ZERO, S::ZERO, S::ONE])],
    );
    let (f, stats) = render::<S, 64, 64, 1>(&scene);
    // The blue plane crosses z = 0 at x = 32: red in front on the left, blue on the right.
    assert_eq!(f.get(22, 32), Rgb565::RED, "{}", S::NAME);
    assert_eq!(f.get(42, 32), Rgb565::BLUE, "{}", S::NAME);
    // Where only one of them covers, it shows.
    assert_eq!(f.get(10, 12), Rgb565::RED);
    assert_eq!(f.get(54, 14), Rgb565::BLUE);
    // The intersection column, row by row, is within one pixel of x = 32.
    for y in 24..40 {
        let first_blue = (0..64).find(|&x| f.get(x, y) == Rgb565::BLUE).unwrap();
        assert!(
            (31..=33).contains(&first_blue),
            "{}: row {y} switches at {first_blue}",
            S::NAME
        );
    }
    (f, stats)
}

#[test]
fn interpenetrating_triangles() {
    three!(interpenetrating, "interpenetrating", 64, 64, 0, 4);
}

/// The smallest real scene: a flat ground plane and a torus standing on it, two objects with
/// their own transforms and materials, one strip pass, several lights.
fn ground_and_model<S: Scalar>() -> (Frame<Rgb565>, Stats) {
    let ground = Shape::<S, 81, 128>::terrain(6.0, 8, 0.0).unwrap();
    let torus = demo::torus::<S>().unwrap();
    let mut ground_mat = Material::matte([120, 200, 120], S::from_f64(0.3), S::from_f64(0.7));
    ground_mat.shading = Shading::Flat;
    let mut torus_mat = demo::torus_material::<S>();
    torus_mat.specular = S::from_f64(0.5);
    torus_mat.shininess = 16;
    let objects = [
        Object {
            mesh: ground.mesh(),
            transform: Mat4::translate([S::ZERO, S::from_f64(-1.4), S::ZERO]),
            material: ground_mat,
        },
        Object {
            mesh: torus.mesh(),
            transform: Mat4::rotate_y(deg(30.0)).then(&Mat4::translate([
                S::ZERO,
                S::from_f64(0.05),
                S::ZERO,
            ])),
            material: torus_mat,
        },
    ];
    let camera = Camera::look_at(
        [S::ZERO, S::from_f64(1.5), S::from_f64(4.0)],
        [S::ZERO, S::from_f64(-0.5), S::ZERO],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(50.0),
            near: S::from_f64(0.1),
            far: S::from_f64(20.0),
        },
    )
    .unwrap();
    let lights = [
        Light::white([-S::ONE, S::from_f64(2.0), S::ONE]),
        Light {
            direction: [S::ONE, S::from_f64(0.5), -S::ONE],
            color: [80, 80, 160],
        },
    ];
    let scene = Scene::new(&objects, camera, lights);
    let (f, stats) = render::<S, 160, 120, 2>(&scene);
    // The torus hides part of the ground: the ground colour is not at the torus centre's
    // bottom, and the torus is drawn over it.
    let ground_px = f.px.iter().filter(|&&c| c.g() > c.r() + 5).count();
    assert!(ground_px > 3000, "ground pixels {ground_px}");
    assert_eq!(stats.triangles_in, 128 + 1024);
    (f, stats)
}

#[test]
fn ground_plane_and_model() {
    three!(ground_and_model, "ground_and_torus", 160, 120, 2, 24);
}

#[test]
fn rgb888_and_gray8_targets() {
    use embedded_graphics::pixelcolor::{Gray8, GrayColor};
    let shape = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut r888: Box<Renderer<Q, Rgb888, 240, 240, 512, 512, 64>> = Box::default();
    let mut f888 = frame::<Rgb888>(240, 240);
    r888.render(&scene, &mut f888).unwrap();
    let mut rg: Box<Renderer<Q, Gray8, 240, 240, 512, 512, 64>> = Box::default();
    let mut fg = frame::<Gray8>(240, 240);
    rg.render(&scene, &mut fg).unwrap();
    f888.assert_each_written_once();
    fg.assert_each_written_once();
    // Grey is the BT.601 luma of the colour image, within one step of interpolation rounding.
    let mut worst = 0;
    for (c, g) in f888.px.iter().zip(fg.px.iter()) {
        let want = Gray8::from(*c).luma();
        worst = worst.max(want.abs_diff(g.luma()));
    }
    assert!(worst <= 1, "grey differs from luma of colour by {worst}");
    // The brightest lit pixel is the material colour at full diffuse.
    let full: Rgb888 = quantize([255, 160, 64]);
    assert!(f888.px.iter().any(|&c| c.r() == full.r()));
}

/// A closed convex mesh after back-face culling covers its silhouette exactly once: every
/// fragment is a distinct pixel (no pixel twice) and the silhouette has no holes (no gaps).
fn watertight_sphere<S: Scalar>() {
    let ico = Shape::<S, 642, 1280>::icosphere(1.0, 3).unwrap();
    let mut m = Material::matte([200, 200, 200], S::from_f64(0.3), S::from_f64(0.7));
    m.shading = Shading::Flat;
    let objects = [Object {
        mesh: ico.mesh(),
        transform: Mat4::rotate_y(deg(17.0)).then(&Mat4::rotate_x(deg(11.0))),
        material: m,
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
    let scene = Scene::new(&objects, camera, [Light::white([S::ONE, S::ONE, S::ONE])]);
    let mut r: Box<Renderer<S, Rgb565, 128, 128, 1400, 1300, 128>> = Box::default();
    r.set_depth_test(DepthTest::Always);
    let mut f = frame(128, 128);
    let stats = r.render(&scene, &mut f).unwrap();
    let covered = f.px.iter().filter(|&&c| c != Rgb565::BLACK).count();
    assert_eq!(
        stats.fragments as usize,
        covered,
        "{}: a pixel was rasterized twice",
        S::NAME
    );
    // No holes: every row's covered pixels are one contiguous run.
    for y in 0..128 {
        let xs: Vec<u32> = (0..128).filter(|&x| f.get(x, y) != Rgb565::BLACK).collect();
        if let (Some(a), Some(b)) = (xs.first(), xs.last()) {
            assert_eq!(xs.len() as u32, b - a + 1, "{}: gap in row {y}", S::NAME);
        }
    }
    assert!(covered > 4000);
}

#[test]
fn closed_mesh_is_watertight() {
    watertight_sphere::<Q>();
    watertight_sphere::<f32>();
    watertight_sphere::<f64>();
}

fn torus_with_lines<const LINES: usize>(dither: bool) -> Frame<Rgb565> {
    let shape = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut r: Box<Renderer<Q, Rgb565, 240, 240, 512, 512, 64, LINES>> = Box::default();
    r.set_dither(dither);
    let mut f = frame(240, 240);
    r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    f
}

#[test]
fn strip_height_does_not_change_the_image() {
    let one = torus_with_lines::<1>(false);
    assert_eq!(one.px, torus_with_lines::<4>(false).px);
    // 240 = 34·7 + 2: the last strip is partial.
    assert_eq!(one.px, torus_with_lines::<7>(false).px);
    assert_eq!(
        torus_with_lines::<1>(true).px,
        torus_with_lines::<16>(true).px
    );
}

#[test]
fn dithering_stays_within_one_lsb_and_breaks_up_bands() {
    let plain = torus_with_lines::<1>(false);
    let dith = torus_with_lines::<1>(true);
    check_golden("torus_gouraud_dithered_I16F16", &dith);
    let (max, differ, coverage) = compare565(&dith, &plain, Rgb565::BLACK);
    assert_eq!(coverage, 0);
    assert!(max.iter().all(|&m| m <= 1), "{max:?}");
    assert!(differ > 5000, "dithering changed only {differ} pixels");
}

fn overlay_matches_text_drawn_on_top<const LINES: usize>() {
    use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
    use embedded_graphics::prelude::*;
    use embedded_graphics::text::Text;
    let shape = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
    // Straddles strip boundaries for every strip height.
    let text = Text::new("60.0 fps  1024 tris", Point::new(4, 13), style);
    let mut r: Box<Renderer<Q, Rgb565, 240, 240, 512, 512, 64, LINES>> = Box::default();
    let mut plain = frame::<Rgb565>(240, 240);
    r.render(&scene, &mut plain).unwrap();
    text.draw(&mut plain).unwrap();
    let mut overlaid = frame::<Rgb565>(240, 240);
    r.render_with(
        &scene,
        scanline3d::FrameOptions::new().overlay(&text),
        &mut overlaid,
    )
    .unwrap();
    overlaid.assert_each_written_once();
    assert_eq!(overlaid.px, plain.px, "LINES = {LINES}");
    assert!(overlaid.px.iter().filter(|&&c| c == Rgb565::WHITE).count() > 50);
}

#[test]
fn overlay_is_composed_into_the_strips() {
    overlay_matches_text_drawn_on_top::<1>();
    overlay_matches_text_drawn_on_top::<4>();
    overlay_matches_text_drawn_on_top::<7>();
}

#[test]
fn a_smaller_viewport_renders_like_a_renderer_of_that_size() {
    let shape = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut exact: Box<Renderer<Q, Rgb565, 160, 100, 512, 512, 64>> = Box::default();
    let mut a = frame::<Rgb565>(160, 100);
    exact.render(&scene, &mut a).unwrap();
    let mut big: Box<Renderer<Q, Rgb565, 240, 240, 512, 512, 64, 3>> = Box::default();
    big.set_viewport(160, 100);
    assert_eq!(big.viewport(), (160, 100));
    let mut b = frame::<Rgb565>(160, 100);
    big.render(&scene, &mut b).unwrap();
    b.assert_each_written_once();
    assert_eq!(a.px, b.px);
}
