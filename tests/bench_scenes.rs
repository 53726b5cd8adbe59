//! The benchmark scenes render for every number type, over a full turn, within their renderers'
//! capacities, each exercising what it is meant to (clipping, overdraw, depth range).

use crate::common;

use common::compare::HostProbe;
use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::probe::NoProbe;
use scanline3d_support::demo::{render_bench, Bench};
use scanline3d_support::hash::HashTarget;

type Q = Fx<I16F16>;

fn frame<S: Scalar>(b: Bench, spin: f64) -> (Frame<Rgb565>, scanline3d_support::demo::BenchFrame) {
    let mut f = Frame::new(240, 240, Rgb565::BLACK);
    let r = render_bench::<S, Rgb565, _, _>(b, spin, false, &mut f, &mut HostProbe::Plain)
        .unwrap_or_else(|e| panic!("{b:?} {} at {spin}°: {e:?}", S::NAME));
    f.assert_each_written_once();
    (f, r)
}

/// The full turn of every scene in four tests (a quarter of `Bench::ALL` each): the debug test
/// run's longest test was this one as a whole (44 s unoptimized), which the test threads could
/// not share.
#[test]
fn every_scene_renders_over_a_full_turn_1_of_4() {
    full_turn(0);
}
#[test]
fn every_scene_renders_over_a_full_turn_2_of_4() {
    full_turn(1);
}
#[test]
fn every_scene_renders_over_a_full_turn_3_of_4() {
    full_turn(2);
}
#[test]
fn every_scene_renders_over_a_full_turn_4_of_4() {
    full_turn(3);
}

/// The scenes of quarter `part` (0..4) of `Bench::ALL` over a full turn: every fourth scene from
/// the `part`-th, so that the costly neighbours in the list (the shadow and outline scenes
/// build their adjacency every frame) fall into different quarters.
fn full_turn(part: usize) {
    for &b in Bench::ALL.iter().skip(part).step_by(4) {
        for spin in (0..360).step_by(15) {
            frame::<Q>(b, spin as f64);
            frame::<f32>(b, spin as f64);
        }
        let (f, r) = frame::<Q>(b, 0.0);
        std::fs::create_dir_all("target/bench-scenes").unwrap();
        std::fs::write(
            format!("target/bench-scenes/{}.png", b.name()),
            common::png_bytes(&f),
        )
        .unwrap();
        let s = r.stats;
        assert!(s.drawn > 0 && s.pixels_written > 1000, "{b:?}: {s:?}");
        match b {
            Bench::Terrain => assert!(s.clipped > 0, "terrain must cross the near plane: {s:?}"),
            Bench::Overdraw => {
                assert!(s.fragments > 7 * 240 * 240, "overdraw: {s:?}");
                assert!(s.pixels_written > 2 * 240 * 240, "overdraw: {s:?}");
            }
            Bench::Deep => assert!(s.drawn >= 12, "deep: {s:?}"),
            Bench::Phong | Bench::PhongFast | Bench::PhongGouraud => {
                assert!(s.drawn > 100, "{b:?}: {s:?}")
            }
            Bench::Textured | Bench::TexturedAffine | Bench::TexturedExact => {
                assert!(s.clipped > 0, "the floor must cross the near plane: {s:?}");
            }
            _ => {}
        }
    }
}

#[test]
fn hash_target_sees_the_same_frame_as_a_buffer() {
    for b in Bench::ALL {
        let (f, _) = frame::<Q>(b, 0.0);
        let mut h = HashTarget::<Rgb565>::new(240, 240);
        render_bench::<Q, Rgb565, _, _>(b, 0.0, false, &mut h, &mut NoProbe).unwrap();
        let mut h2 = HashTarget::<Rgb565>::new(240, 240);
        use embedded_graphics::prelude::*;
        h2.fill_contiguous(
            &embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(240, 240)),
            f.px.iter().copied(),
        )
        .unwrap();
        assert_eq!(h.hash(), h2.hash(), "{b:?}");
        assert_eq!(h.pixels(), 240 * 240);
    }
}

#[test]
fn a_taller_strip_gives_the_same_torus() {
    // `render_torus_strip` is what `scripts/mcu-bench` measures against the one-line strip.
    for spin in [0.0, 37.0] {
        let (f, one) = frame::<Q>(Bench::Torus, spin);
        let mut g = Frame::new(240, 240, Rgb565::BLACK);
        let eight = scanline3d_support::demo::render_torus_strip::<Q, Rgb565, _, _, 8>(
            spin,
            false,
            &mut g,
            &mut NoProbe,
        )
        .unwrap();
        g.assert_each_written_once();
        assert!(f.px == g.px, "spin {spin}");
        assert_eq!(one.stats, eight.stats);
        // Seven more lines of RGB565 colour and 16-bit depth.
        assert_eq!(
            eight.renderer_ram_bytes,
            one.renderer_ram_bytes + 7 * 240 * 4
        );
    }
}

/// The 16 KB part's capacities (`demo::SMALL_PART_TORUS`) are exactly what its frame needs:
/// its stack has no room for more, and one less of either fails the frame.
#[test]
fn small_part_capacities_are_exactly_the_frame_s_needs() {
    use scanline3d::Error;
    use scanline3d_support::demo::{render_torus_sized, SMALL_PART_TORUS};
    const W: usize = SMALL_PART_TORUS.0;
    const T: usize = SMALL_PART_TORUS.1;
    const A: usize = SMALL_PART_TORUS.2;
    let shape = scanline3d_support::demo::torus::<Q>().unwrap();
    let mut t = HashTarget::<Rgb565>::new(W as u32, W as u32);
    let f =
        render_torus_sized::<Q, Rgb565, _, _, W, T, A>(shape.mesh(), &mut t, &mut NoProbe).unwrap();
    assert_eq!(
        (f.stats.drawn as usize, f.stats.max_active as usize),
        (T, A)
    );
    // On the host the support crate draws the frame with a larger renderer and checks the
    // frame's needs against the scene's capacities after it (`BenchError::Capacity`).
    let short = |r: Result<_, scanline3d_support::demo::BenchError<_>>, t: usize, a: usize| {
        matches!(
            r,
            Err(scanline3d_support::demo::BenchError::Capacity { needed, capacity })
                if needed.triangles == T && needed.active == A
                    && capacity.triangles == t && capacity.active == a
        )
    };
    let mut t = HashTarget::<Rgb565>::new(W as u32, W as u32);
    assert!(short(
        render_torus_sized::<Q, Rgb565, _, _, W, { T - 1 }, A>(shape.mesh(), &mut t, &mut NoProbe),
        T - 1,
        A
    ));
    assert!(short(
        render_torus_sized::<Q, Rgb565, _, _, W, T, { A - 1 }>(shape.mesh(), &mut t, &mut NoProbe),
        T,
        A - 1
    ));
    // The 16 KB part's own renderer type (as its firmware builds it) fails the frame with a
    // shortfall before drawing anything when one capacity is one less.
    let objects = [scanline3d_support::demo::torus_object(&shape)];
    let camera = scanline3d_support::demo::camera::<Q>().unwrap();
    let scene = Scene::new(&objects, camera, scanline3d_support::demo::lights());
    let mut r = Renderer::<Q, Rgb565, W, W, 512, T, { A - 1 }>::new();
    let e = r.render(&scene, &mut t).unwrap_err();
    assert!(matches!(e, Error::Shortfall(s) if s.needed.active == A && s.capacity.active == A - 1));
    let mut r = Renderer::<Q, Rgb565, W, W, 512, { T - 1 }, A>::new();
    let e = r.render(&scene, &mut t).unwrap_err();
    assert!(
        matches!(e, Error::Shortfall(s) if s.capacity.triangles == T - 1 && s.needed.triangles >= T)
    );
}

/// The `csg` scene (the example CSG part baked into flash) against its golden images (looked
/// at), and its renderer's capacities (`demo::CSG_TRIS`, `demo::CSG_ACTIVE`) exactly the most its
/// frames need over a full turn: a drawn count or active list above them would have failed the
/// frame with a shortfall.
#[test]
fn csg_scene_matches_its_golden_images_and_its_capacities() {
    use scanline3d_support::demo::{CSG_ACTIVE, CSG_TRIS};
    fn most<S: Scalar>() -> (usize, usize) {
        (0..360)
            .step_by(5)
            .map(|spin| frame::<S>(Bench::Csg, spin as f64).1.stats)
            .fold((0, 0), |(d, a), s| {
                (d.max(s.drawn as usize), a.max(s.max_active as usize))
            })
    }
    let (q, f32s, f64s) = (most::<Q>(), most::<f32>(), most::<f64>());
    println!("csg over a turn (drawn, active): I16F16 {q:?}, f32 {f32s:?}, f64 {f64s:?}");
    let need = (q.0.max(f32s.0).max(f64s.0), q.1.max(f32s.1).max(f64s.1));
    assert_eq!(need, (CSG_TRIS, CSG_ACTIVE));
    common::check_golden("csg_I16F16", &frame::<Q>(Bench::Csg, 0.0).0);
    common::check_golden("csg_f32", &frame::<f32>(Bench::Csg, 0.0).0);
    common::check_golden("csg_f64", &frame::<f64>(Bench::Csg, 0.0).0);
}
