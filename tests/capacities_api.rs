//! Issue #21, API points 1–4: capacities reported all at once, measured on the host, and what a
//! frame that does not fit does on the device; a renderer built in a `static`; the target's
//! size checked at render time; `#[non_exhaustive]` statistics.
//!
//! None of these tests compiles on the code before this file was added (no `Needs`,
//! `Shortfall`, `OverflowPolicy`, `Error::Shortfall`, `Error::TargetTooSmall`,
//! `Renderer::needs`, `Renderer::const_new`, `Renderer::shortfall`); each also checks behaviour
//! the old code did not have (see each test's comment). Zero capacities and the
//! `#[non_exhaustive]` structs are compile-time properties: `compile_fail` doctests on
//! `Renderer` and `Needs` check them (`cargo test --doc`).

use crate::common;

use std::sync::Mutex;

use common::Frame;
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{errors::Capacity, Error, Shortfall, Stats};
use scanline3d_support::demo::{self, deg, TorusShape};

type Q = Fx<I16F16>;

/// The default torus and, beside it, a cube, seen by a camera orbiting them at `angle_deg`
/// (the "orbiting camera" scene, built in code).
fn orbit<'a>(torus: &'a TorusShape<Q>, cube: &'a Shape<Q, 24, 12>) -> [Object<'a, Q>; 2] {
    [
        demo::torus_object(torus),
        Object {
            mesh: cube.mesh(),
            transform: Mat4::translate([Q::lit(1.2), Q::lit(-0.3), Q::lit(0.2)]),
            material: Material::matte([90, 160, 255], Q::lit(0.2), Q::lit(0.8)),
        },
    ]
}

fn orbit_camera(angle_deg: f64) -> Camera<Q> {
    let a: f64 = angle_deg.to_radians();
    Camera::look_at(
        [Q::lit(3.2 * a.sin()), Q::lit(1.4), Q::lit(3.2 * a.cos())],
        [Q::ZERO; 3],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: deg(50.0),
            near: Q::lit(0.1),
            far: Q::lit(12.0),
        },
    )
    .unwrap()
}

fn cube() -> Shape<Q, 24, 12> {
    Shape::cube(0.7).unwrap()
}

/// A renderer of generous capacities for measuring, 64 × 64.
type Measure = Renderer<Q, Rgb565, 64, 64, 4096, 4096, 1024>;

/// Point 1 (a): a frame short of all three capacities gets one error naming all three, with
/// what was needed and what the renderer has. (The old code returned only the first shortfall,
/// `Error::Capacity { what: Vertices, .. }`.)
#[test]
fn every_shortfall_in_one_error() {
    let torus = demo::torus::<Q>().unwrap();
    let cube = cube();
    let objects = orbit(&torus, &cube);
    let scene = Scene::new(&objects, orbit_camera(0.0), demo::lights());
    // The torus's 512 vertices fit, the cube's 24 do not; the torus alone needs more than 100
    // triangles, and more than 2 of those cross one row.
    let mut small: Box<Renderer<Q, Rgb565, 64, 64, 520, 100, 2>> = Box::default();
    let mut display = MockDisplay::<Rgb565>::new();
    let short = match small.render(&scene, &mut display) {
        Err(Error::Shortfall(s)) => s,
        other => panic!("{other:?}"),
    };
    assert_eq!(display, MockDisplay::new(), "nothing drawn");
    let listed: Vec<(Capacity, usize, usize)> = short.iter().collect();
    assert_eq!(listed.len(), 3, "{short:?}");
    assert_eq!(listed[0], (Capacity::Vertices, 536, 520));
    assert_eq!(listed[1].0, Capacity::Triangles);
    assert_eq!(listed[2].0, Capacity::ActiveTriangles);
    for (what, needed, capacity) in listed {
        assert!(needed > capacity, "{what:?}: {needed} ≤ {capacity}");
        assert!(short.is_short(what));
    }
    assert_eq!(short.capacity, Needs::new(520, 100, 2));
    assert_eq!(
        short.capacity,
        Renderer::<Q, Rgb565, 64, 64, 520, 100, 2>::CAPACITY
    );
    assert!(!short.exact, "the vertex store overflowed: estimates");
    assert_eq!(short.skipped, 0, "an error skips nothing: nothing is drawn");
    let text = short.to_string();
    for part in [
        "vertices (VERTS): needs about 536, has 520",
        "(TRIS)",
        "(ACTIVE)",
    ] {
        assert!(text.contains(part), "{text}");
    }
    // The failed frame was not prepared: the error carries its shortfall.
    assert_eq!(small.shortfall(), None);

    // Short of the active list only: the figures are exact, and equal what a renderer with
    // room measures.
    let exact = Box::<Measure>::default().needs(&scene).unwrap();
    let mut narrow: Box<Renderer<Q, Rgb565, 64, 64, 4096, 4096, 3>> = Box::default();
    match narrow.render(&scene, &mut display) {
        Err(Error::Shortfall(s)) => {
            assert!(s.exact);
            assert_eq!(s.needed, exact);
            assert_eq!(
                s.iter().collect::<Vec<_>>(),
                [(Capacity::ActiveTriangles, exact.active, 3)]
            );
        }
        other => panic!("{other:?}"),
    }
}

/// Point 1 (b): the needs of a code-built animation, measured on the host over every frame,
/// size a renderer that draws every frame, and one less of any capacity fails a frame with
/// exactly the measured figure. (The old code had no way to measure a scene built in code.)
#[test]
fn needs_measured_over_an_animation_size_the_renderer() {
    let torus = demo::torus::<Q>().unwrap();
    let cube = cube();
    let objects = orbit(&torus, &cube);
    let frames: Vec<Scene<'_, Q, 1>> = (0..36)
        .map(|k| Scene::new(&objects, orbit_camera(10.0 * k as f64), demo::lights()))
        .collect();
    let mut measure: Box<Measure> = Box::default();
    let mut worst = Needs::default();
    let mut per_frame = Vec::new();
    for scene in &frames {
        let needs = measure.needs(scene).unwrap();
        per_frame.push(needs);
        worst = worst.max(needs);
    }
    // The figures vary over the orbit (so one frame is not enough to size the renderer).
    assert!(
        per_frame.iter().any(|n| n.active != worst.active),
        "{per_frame:?}"
    );
    assert!(worst.fits(&Measure::CAPACITY));
    assert_eq!(measure.next_row(), 64, "needs leaves no frame prepared");

    // A frame that fit reports the same figures in its statistics (the documented mapping:
    // vertices → VERTS, drawn → TRIS, max_active → ACTIVE).
    let mut display = Frame::new(64, 64, Rgb565::BLACK);
    let stats: Stats = measure.render(&frames[0], &mut display).unwrap();
    assert_eq!(Needs::from_stats(&stats), per_frame[0]);
    assert_eq!(
        (
            stats.vertices as usize,
            stats.drawn as usize,
            stats.max_active as usize
        ),
        (
            per_frame[0].vertices,
            per_frame[0].triangles,
            per_frame[0].active
        )
    );

    // The measured maxima (fixed point: the same on every host), then a renderer with exactly
    // those capacities draws every frame, and one with one less of a capacity fails exactly
    // the frames that needed it, naming the measured figure.
    const V: usize = 536;
    const T: usize = 475;
    const A: usize = 67;
    assert_eq!(worst, Needs::new(V, T, A));
    fn failing<const TT: usize, const AA: usize>(
        frames: &[Scene<'_, Q, 1>],
        per_frame: &[Needs],
    ) -> Vec<usize> {
        let mut r: Box<Renderer<Q, Rgb565, 64, 64, V, TT, AA>> = Box::default();
        let mut failed = Vec::new();
        for (k, scene) in frames.iter().enumerate() {
            let mut display = Frame::new(64, 64, Rgb565::BLACK);
            match r.render(scene, &mut display) {
                Ok(_) => {}
                Err(Error::Shortfall(s)) => {
                    // Exact unless the triangle store overflowed (then the active figure
                    // counts only the stored triangles); vertices and triangles always.
                    let n = per_frame[k];
                    assert_eq!(s.exact, s.needed.triangles <= TT, "frame {k}");
                    assert_eq!(
                        (s.needed.vertices, s.needed.triangles),
                        (n.vertices, n.triangles)
                    );
                    if s.exact {
                        assert_eq!(s.needed, n, "frame {k}");
                    }
                    failed.push(k);
                }
                Err(e) => panic!("{e:?}"),
            }
        }
        failed
    }
    let needing = |f: fn(&Needs) -> usize, max: usize| -> Vec<usize> {
        (0..frames.len())
            .filter(|&k| f(&per_frame[k]) == max)
            .collect()
    };
    assert_eq!(failing::<T, A>(&frames, &per_frame), Vec::<usize>::new());
    assert_eq!(
        failing::<{ T - 1 }, A>(&frames, &per_frame),
        needing(|n| n.triangles, T)
    );
    assert_eq!(
        failing::<T, { A - 1 }>(&frames, &per_frame),
        needing(|n| n.active, A)
    );

    // A measuring renderer too small to measure says so instead of returning estimates.
    let mut tiny: Box<Renderer<Q, Rgb565, 64, 64, 100, 100, 100>> = Box::default();
    match tiny.needs(&frames[0]) {
        Err(Error::Shortfall(s)) => assert!(!s.exact && s.is_short(Capacity::Vertices)),
        other => panic!("{other:?}"),
    }
}

/// Point 1 (c), the default: a frame that does not fit is an error and draws nothing.
/// (The old code had no policy and no `shortfall()`.)
#[test]
fn overflow_policy_error_is_the_default() {
    let torus = demo::torus::<Q>().unwrap();
    let cube = cube();
    let objects = orbit(&torus, &cube);
    let scene = Scene::new(&objects, orbit_camera(30.0), demo::lights());
    let mut r: Box<Renderer<Q, Rgb565, 64, 64, 4096, 4096, 4>> = Box::default();
    assert_eq!(r.overflow(), OverflowPolicy::Error);
    assert_eq!(OverflowPolicy::default(), OverflowPolicy::Error);
    let mut display = MockDisplay::<Rgb565>::new();
    assert!(matches!(
        r.render(&scene, &mut display),
        Err(Error::Shortfall(_))
    ));
    assert_eq!(display, MockDisplay::new());
    assert!(matches!(
        r.prepare(&scene, scanline3d::FrameOptions::new()),
        Err(Error::Shortfall(_))
    ));
    assert!(r.prepared().is_none(), "nothing prepared");
}

/// Renders `scene` with `r` into a fresh 64 × 64 frame; panics on a pixel written twice.
fn draw<const V: usize, const T: usize, const A: usize>(
    r: &mut Renderer<Q, Rgb565, 64, 64, V, T, A>,
    scene: &Scene<'_, Q, 1>,
) -> (Frame<Rgb565>, Stats) {
    let mut f = Frame::new(64, 64, Rgb565::new(1, 2, 3));
    let stats = r.render(scene, &mut f).unwrap();
    f.assert_each_written_once();
    (f, stats)
}

/// Point 1 (c), draw what fits, active list short mid-frame: the frame is drawn without the
/// triangles that found the list full, which are counted; no panic; every drawn pixel is one
/// the full frame covers. (The old code returned `Error::Capacity` and drew nothing.)
#[test]
fn draw_what_fits_skips_what_the_active_list_cannot_hold() {
    let torus = demo::torus::<Q>().unwrap();
    let cube = cube();
    let objects = orbit(&torus, &cube);
    let bg = Rgb565::new(1, 2, 3);
    for k in 0..12 {
        let scene = Scene::new(&objects, orbit_camera(30.0 * k as f64), demo::lights());
        let mut full: Box<Measure> = Box::default();
        let (reference, full_stats) = draw(&mut full, &scene);
        assert!(full.shortfall().is_none());
        let mut r: Box<Renderer<Q, Rgb565, 64, 64, 4096, 4096, 6>> = Box::default();
        r.set_overflow(OverflowPolicy::DrawWhatFits);
        let (partial, stats) = draw(&mut r, &scene);
        let short: Shortfall = r.shortfall().expect("the active list overflowed");
        assert!(short.exact);
        assert_eq!(short.needed.active, full_stats.max_active as usize);
        assert_eq!(short.iter().count(), 1, "{short:?}");
        // At the busiest row at most 6 of the triangles crossing it can be on the list.
        assert!(short.skipped >= short.needed.active - 6, "{short:?}");
        assert!(short.skipped < full_stats.drawn as usize);
        assert!(stats.pixels_written > 0 && stats.pixels_written < full_stats.pixels_written);
        let mut drawn = 0;
        for (i, (&a, &b)) in partial.px.iter().zip(&reference.px).enumerate() {
            if a != bg {
                drawn += 1;
                assert_ne!(b, bg, "frame {k}: pixel {i} drawn outside the full frame");
            }
        }
        assert!(drawn > 0);
        // The next frame that fits clears the report.
        let (_, _) = draw(&mut full, &scene);
        r.set_overflow(OverflowPolicy::Error);
        assert!(matches!(
            r.prepare(&scene, scanline3d::FrameOptions::new()),
            Err(Error::Shortfall(_))
        ));
    }
}

/// Point 1 (c), draw what fits, vertex and triangle stores short: the objects (in scene order)
/// and triangles that fit are drawn exactly as they are without the rest, the rest counted.
#[test]
fn draw_what_fits_with_short_stores() {
    let torus = demo::torus::<Q>().unwrap();
    let cube = cube();
    let objects = orbit(&torus, &cube);
    let scene = Scene::new(&objects, orbit_camera(40.0), demo::lights());
    let torus_only = Scene::new(&objects[..1], orbit_camera(40.0), demo::lights());
    let (reference, torus_stats) = draw(&mut Box::<Measure>::default(), &torus_only);

    // The cube's vertices do not fit: the frame is the torus alone; the cube's 12 triangles
    // are skipped.
    let mut r = Box::new(
        Renderer::<Q, Rgb565, 64, 64, 520, 4096, 1024>::new()
            .with_overflow(OverflowPolicy::DrawWhatFits),
    );
    let (f, stats) = draw(&mut r, &scene);
    assert_eq!(f.px, reference.px);
    assert_eq!(stats.drawn, torus_stats.drawn);
    let short = r.shortfall().unwrap();
    assert_eq!(short.skipped, 12);
    assert_eq!(
        short.iter().collect::<Vec<_>>(),
        [(Capacity::Vertices, 536, 520)]
    );

    // Room for 100 triangles: 100 are drawn, the rest counted.
    let mut r = Box::new(
        Renderer::<Q, Rgb565, 64, 64, 4096, 100, 1024>::new()
            .with_overflow(OverflowPolicy::DrawWhatFits),
    );
    let (f, stats) = draw(&mut r, &scene);
    assert_eq!(stats.drawn, 100);
    let short = r.shortfall().unwrap();
    assert!(short.is_short(Capacity::Triangles) && !short.is_short(Capacity::Vertices));
    assert!(
        !short.exact,
        "the active figure counts only the stored triangles"
    );
    assert_eq!(short.skipped, short.needed.triangles - 100);
    let bg = Rgb565::new(1, 2, 3);
    assert!(f.px.iter().any(|&c| c != bg));
}

/// Point 2: a 1.29 MB renderer (the 1024 × 1024 Rgb888 one with large capacities)
/// built as a `static` by the `const fn`, and used from a thread with a 256 KB stack: never on
/// the stack. (The old `new()` is not `const`, and built it on the stack first.)
#[test]
fn large_renderer_as_a_static() {
    type Big = Renderer<f32, Rgb888, 1024, 1024, 32768, 32767, 8192>;
    static BIG: Mutex<Big> = Mutex::new(Big::const_new(Rgb888::BLACK));
    // Also evaluated at compile time.
    const _SMALL: Renderer<Q, Rgb565, 240, 240, 512, 480, 64> = Renderer::const_new(Rgb565::BLACK);
    const { assert!(Big::RAM_BYTES > 1_280_000) };
    let pixels = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(|| {
            let torus = demo::torus::<f32>().unwrap();
            let objects = [demo::torus_object(&torus)];
            let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
            let mut r = BIG.lock().unwrap();
            r.set_dither(true);
            let mut target = scanline3d_support::hash::NullTarget::<Rgb888>::new(1024, 1024);
            let stats = r.render(&scene, &mut target).unwrap();
            assert!(r.shortfall().is_none());
            stats.pixels_written
        })
        .unwrap()
        .join()
        .unwrap();
    assert!(pixels > 100_000, "{pixels}");
    // `const_new` is `new`: same pixels.
    let torus = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&torus)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut a: Box<Renderer<Q, Rgb565, 64, 64, 512, 480, 64>> =
        Box::new(Renderer::const_new(Rgb565::WHITE));
    let mut b: Box<Renderer<Q, Rgb565, 64, 64, 512, 480, 64>> = Box::default();
    let (fa, sa) = draw(&mut a, &scene);
    let (fb, sb) = draw(&mut b, &scene);
    assert_eq!((fa.px, sa), (fb.px, sb));
}

/// Point 3: a target smaller than the viewport is an error naming both sizes, before anything
/// is drawn (the old code panicked inside `MockDisplay` for 64 × 64, and sent 1024 full rows to
/// a 2 × 2 target); a larger one gets the frame at its origin and the rest untouched.
#[test]
fn target_size_is_checked() {
    let torus = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&torus)];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut r: Box<Renderer<Q, Rgb565, 240, 240, 512, 480, 64>> = Box::default();
    let mut mock = MockDisplay::<Rgb565>::new();
    let want = Size::new(240, 240);
    assert_eq!(
        r.render(&scene, &mut mock),
        Err(Error::TargetTooSmall {
            viewport: want,
            target: Rectangle::new(Point::zero(), Size::new(64, 64)),
        })
    );
    assert_eq!(mock, MockDisplay::new(), "nothing drawn");
    let mut two = Frame::new(2, 2, Rgb565::BLACK);
    let err = r.render(&scene, &mut two).unwrap_err();
    assert!(matches!(err, Error::TargetTooSmall { target, .. } if target.size == Size::new(2, 2)));
    assert!(two.writes.iter().all(|&n| n == 0));
    // One row short, and the overlaid and strip paths.
    let mut short = Frame::new(240, 239, Rgb565::BLACK);
    assert!(matches!(
        r.render(&scene, &mut short),
        Err(Error::TargetTooSmall { .. })
    ));
    let label = embedded_graphics::primitives::Rectangle::new(Point::zero(), Size::new(1, 1));
    let style = embedded_graphics::primitives::PrimitiveStyle::with_fill(Rgb565::WHITE);
    let overlay = embedded_graphics::primitives::Primitive::into_styled(label, style);
    assert!(matches!(
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().overlay(&overlay),
            &mut short
        ),
        Err(Error::TargetTooSmall { .. })
    ));
    let mut frame = r.prepare(&scene, scanline3d::FrameOptions::new()).unwrap();
    assert!(matches!(
        frame.strip_to(&mut short),
        Err(Error::TargetTooSmall { .. })
    ));
    assert!(short.writes.iter().all(|&n| n == 0));
    assert_eq!(frame.next_row(), 0, "the frame stays prepared");
    // A target whose bounding box does not start at the origin.
    let mut big = Frame::new(300, 300, Rgb565::BLACK);
    let mut moved = big.translated(Point::new(100, 0));
    assert!(matches!(
        r.render(&scene, &mut moved),
        Err(Error::TargetTooSmall { .. })
    ));
    // The viewport set to the target's size draws into it.
    r.set_viewport(64, 64);
    let mut mock = MockDisplay::<Rgb565>::new();
    assert!(r.render(&scene, &mut mock).unwrap().pixels_written > 0);
    r.set_viewport(240, 240);

    // A larger target: the frame at its origin, every other pixel untouched.
    let mut exact = Frame::new(240, 240, Rgb565::BLACK);
    r.render(&scene, &mut exact).unwrap();
    exact.assert_each_written_once();
    let mut large = Frame::new(300, 260, Rgb565::new(1, 1, 1));
    r.render(&scene, &mut large).unwrap();
    for y in 0..260 {
        for x in 0..300 {
            let i = (y * 300 + x) as usize;
            if x < 240 && y < 240 {
                assert_eq!(large.writes[i], 1);
                assert_eq!(large.get(x, y), exact.get(x, y));
            } else {
                assert_eq!(large.writes[i], 0, "({x}, {y})");
            }
        }
    }
}

/// Point 4: `Stats` is `#[non_exhaustive]`, so it is read, never built, outside the crate;
/// `Needs` is built with `Needs::new`. (That a struct literal no longer compiles is checked by
/// the `compile_fail` doctest on `Needs`; here, the ways that remain.)
#[test]
fn statistics_and_needs_are_read_not_built() {
    let s = Stats::default();
    assert_eq!(Needs::from_stats(&s), Needs::default());
    let n = Needs::new(1, 2, 3).max(Needs::new(3, 2, 1));
    assert_eq!((n.vertices, n.triangles, n.active), (3, 2, 3));
    assert!(n.fits(&Needs::new(3, 2, 3)) && !n.fits(&Needs::new(3, 1, 3)));
}
