//! `Frame::seek_row` is exact: a prepared frame's strips from any row on, after a seek to
//! that row, are bit for bit the whole frame's rows, for every kind of triangle (flat,
//! Gouraud, dithered, textured, Phong), every depth mode (Z-buffer with each test, no depth
//! lines in the painter's order kept as slots or as records, any order), with depth ties
//! decided by the active list's order, and with full active lists and attribute pools under
//! `OverflowPolicy::DrawWhatFits`. What splitting a frame's rows between two cores rests on.

use crate::common::Frame;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{DrawOrder, NoDepthRenderer, OverflowPolicy, Shape, StripPass, TexturedShape};

type Q = Fx<scanline3d::fixed::types::I16F16>;

const SENTINEL: Rgb565 = Rgb565::CSS_HOT_PINK;

/// Prepares `scene` in `$r`, draws the whole frame, then for every row `split` (and one past
/// the viewport) seeks to it, draws the strips left and checks them against the whole frame;
/// the rows above `split` must stay untouched. Returns the whole frame.
macro_rules! check_every_split {
    ($r:expr, $scene:expr, $what:expr) => {{
        let mut frame = $r.prepare($scene, FrameOptions::new()).unwrap();
        let (w, h) = frame.viewport();
        let mut whole = Frame::new(w as u32, h as u32, SENTINEL);
        while frame.strip_to(&mut whole).unwrap().is_some() {}
        for split in (0..=h).chain([h + 7]) {
            frame.seek_row(split);
            assert_eq!(frame.next_row(), split.min(h));
            let mut part = Frame::new(w as u32, h as u32, SENTINEL);
            while frame.strip_to(&mut part).unwrap().is_some() {}
            for y in 0..h as u32 {
                for x in 0..w as u32 {
                    let want = if (y as usize) < split {
                        SENTINEL
                    } else {
                        whole.get(x, y)
                    };
                    assert_eq!(
                        part.get(x, y),
                        want,
                        "{}: split {split}, pixel {x},{y}",
                        $what
                    );
                }
            }
        }
        whole
    }};
}

fn camera(eye: [f64; 3]) -> Camera<Q> {
    Camera::look_at(
        eye.map(Q::from_f64),
        [Q::ZERO; 3],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: Q::from_f64(0.9),
            near: Q::from_f64(0.1),
            far: Q::from_f64(10.0),
        },
    )
    .unwrap()
}

fn light() -> [Light<Q>; 1] {
    [Light::white([-Q::ONE, Q::ONE, Q::ONE])]
}

/// Drawn pixels, to show a case draws something.
fn drawn(f: &Frame<Rgb565>) -> usize {
    f.px.iter().filter(|&&c| c != SENTINEL).count()
}

#[test]
fn gouraud_flat_and_dithered_spheres() {
    let sphere = Shape::<Q, 642, 1280>::icosphere(1.0, 3).unwrap();
    for (shading, dither) in [
        (Shading::Gouraud, false),
        (Shading::Gouraud, true),
        (Shading::Flat, false),
    ] {
        let mut m = Material::matte([200, 60, 60], Q::from_f64(0.1), Q::from_f64(0.8));
        m.specular = Q::from_f64(0.6);
        m.shininess = 20;
        m.shading = shading;
        let objects = [Object {
            mesh: sphere.mesh(),
            transform: Mat4::rotate_y(Q::from_f64(0.4)),
            material: m,
        }];
        let scene = Scene::new(&objects, camera([0.0, 0.5, 3.0]), light());
        let mut r: Box<Renderer<Q, Rgb565, 120, 120, 1300, 1300, 96>> = Box::default();
        r.set_dither(dither);
        let f = check_every_split!(*r, &scene, format!("{shading:?}, dither {dither}"));
        assert!(drawn(&f) > 4000);
    }
}

/// Two coplanar quads over each other: every pixel of the overlap is a depth tie, decided by
/// which triangle the row draws first (`Less`: the first; `LessEqual`: the last).
#[test]
fn depth_ties_keep_the_whole_frames_order() {
    const QUAD: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    let p = |x: f64, y: f64| [Q::from_f64(x), Q::from_f64(y), Q::ZERO];
    let a = [p(-1.0, -1.0), p(0.6, -0.8), p(0.9, 1.0), p(-0.7, 0.7)];
    let b = [p(-0.4, -1.2), p(1.2, -0.5), p(0.3, 1.1), p(-1.1, 0.2)];
    let (ma, mb) = (
        scanline3d::Mesh::new(&a, &QUAD).unwrap(),
        scanline3d::Mesh::new(&b, &QUAD).unwrap(),
    );
    let flat = |c| {
        let mut m = Material::matte(c, Q::ONE, Q::ZERO);
        m.shading = Shading::Flat;
        m
    };
    let objects = [
        Object {
            mesh: ma,
            transform: Mat4::identity(),
            material: flat([250, 40, 40]),
        },
        Object {
            mesh: mb,
            transform: Mat4::identity(),
            material: flat([40, 40, 250]),
        },
    ];
    let scene = Scene::new(&objects, camera([0.0, 0.0, 3.0]), light());
    for test in [DepthTest::Less, DepthTest::LessEqual, DepthTest::Equal] {
        let mut r: Box<Renderer<Q, Rgb565, 96, 96, 16, 16, 8>> = Box::default();
        r.set_depth_test(test);
        let f = check_every_split!(*r, &scene, format!("{test:?}"));
        assert!(drawn(&f) > 2000);
    }
}

fn textured_cube_scene<'a>(
    shape: &'a TexturedShape<Q, 24, 12>,
    shading: Shading,
) -> [Object<'a, Q>; 1] {
    [Object {
        mesh: shape.mesh(),
        transform: Mat4::rotate_y(Q::from_f64(0.5)),
        material: Material::matte([255; 3], Q::from_f64(0.3), Q::from_f64(0.7))
            .textured(&scanline3d_support::demo::CHECKER)
            .shading(shading),
    }]
}

/// Textured and Phong triangles (the attribute pool), with a pool large enough and with one
/// of two entries, whose overflow leaves triangles out under `DrawWhatFits`: a seek fills
/// the pool as the whole frame's pass did.
#[test]
fn textured_and_phong_triangles_with_full_and_short_pools() {
    let shape = TexturedShape::<Q, 24, 12>::cube(1.0).unwrap();
    for shading in [Shading::Gouraud, Shading::Phong, Shading::FastPhong] {
        let objects = textured_cube_scene(&shape, shading);
        let scene = Scene::new(&objects, camera([0.0, 1.5, 3.0]), light());
        let mut big: Box<Renderer<Q, Rgb565, 96, 96, 64, 64, 16, 1, 64, 16>> = Box::default();
        let f = check_every_split!(*big, &scene, format!("{shading:?}, pool 16"));
        assert!(drawn(&f) > 1500);
        let mut short: Box<Renderer<Q, Rgb565, 96, 96, 64, 64, 16, 1, 64, 2>> =
            Box::new(Renderer::new().with_overflow(OverflowPolicy::DrawWhatFits));
        let g = check_every_split!(*short, &scene, format!("{shading:?}, pool 2"));
        assert!(
            drawn(&g) > 0 && g.px != f.px,
            "the short pool leaves triangles out"
        );
    }
}

/// An active list too short for the sphere's rows under `DrawWhatFits`: the triangles left
/// out are those the whole frame leaves out.
#[test]
fn a_full_active_list_leaves_out_what_the_whole_frame_does() {
    let sphere = Shape::<Q, 642, 1280>::icosphere(1.0, 3).unwrap();
    let objects = [Object {
        mesh: sphere.mesh(),
        transform: Mat4::identity(),
        material: Material::matte([60, 200, 90], Q::from_f64(0.2), Q::from_f64(0.8)),
    }];
    let scene = Scene::new(&objects, camera([0.0, 0.5, 3.0]), light());
    let mut r: Box<Renderer<Q, Rgb565, 120, 120, 1300, 1300, 12>> =
        Box::new(Renderer::new().with_overflow(OverflowPolicy::DrawWhatFits));
    let f = check_every_split!(*r, &scene, "active list of 12");
    assert!(r.shortfall().is_some_and(|s| s.skipped > 0));
    assert!(drawn(&f) > 1000);
}

/// Without depth lines: the painter's order as a slot list (`ACTIVE ≤ H`) and in the records
/// (`ACTIVE > H`), and any order, on two overlapping cubes.
#[test]
fn no_depth_lines_in_every_order() {
    let cube = Shape::<Q, 24, 12>::cube(1.0).unwrap();
    let m = |c| Material::matte(c, Q::from_f64(0.2), Q::from_f64(0.8));
    let objects = [
        Object {
            mesh: cube.mesh(),
            transform: Mat4::rotate_y(Q::from_f64(0.3))
                .then(&Mat4::translate([0.3, 0.0, 1.0].map(Q::from_f64))),
            material: m([220, 60, 60]),
        },
        Object {
            mesh: cube.mesh(),
            transform: Mat4::rotate_y(Q::from_f64(0.9))
                .then(&Mat4::translate([-0.4, 0.2, -1.5].map(Q::from_f64))),
            material: m([60, 200, 90]),
        },
    ];
    let scene = Scene::new(&objects, camera([0.3, 0.8, 4.0]), light());
    for order in [DrawOrder::FarToNear, DrawOrder::Any] {
        let mut slots: Box<NoDepthRenderer<Q, Rgb565, 96, 96, 64, 64, 32>> = Box::default();
        slots.set_order(order);
        let f = check_every_split!(*slots, &scene, format!("{order:?}, slots"));
        assert!(drawn(&f) > 1500);
        let mut records: Box<NoDepthRenderer<Q, Rgb565, 96, 96, 64, 64, 128>> = Box::default();
        records.set_order(order);
        let g = check_every_split!(*records, &scene, format!("{order:?}, records"));
        assert_eq!(f.px, g.px);
    }
}

/// Two [`StripPass`]es over one prepared frame, split at every row, their strips drawn in
/// turn as two cores would: the whole frame, bit for bit, with the passes' own lines
/// (`StripPass::render_strip`) and with the caller's (`StripPass::render_strip_into`).
macro_rules! check_passes {
    ($r:expr, $scene:expr, $pass:ty, $what:expr) => {{
        let mut frame = $r.prepare($scene, FrameOptions::new()).unwrap();
        let (w, h) = frame.viewport();
        let mut whole = Frame::new(w as u32, h as u32, SENTINEL);
        while frame.strip_to(&mut whole).unwrap().is_some() {}
        let shared = frame.share();
        let mut top: Box<$pass> = Box::default();
        let mut bottom: Box<$pass> = Box::default();
        for split in 0..=h {
            top.begin(shared, 0..split).unwrap();
            bottom.begin(shared, split..h + 3).unwrap();
            let mut got = Frame::new(w as u32, h as u32, SENTINEL);
            let mut lines = [[SENTINEL; 96]; 3];
            loop {
                let a = top.render_strip(shared, &mut got).unwrap();
                let b = bottom.render_strip_into(shared, &mut lines).unwrap();
                if let Some(rows) = &b {
                    assert!(rows.start >= split && rows.end <= h && rows.len() <= 3);
                    for (i, y) in rows.clone().enumerate() {
                        for x in 0..w {
                            got.px[y * w + x] = lines[i][x];
                        }
                    }
                }
                if let Some(rows) = &a {
                    assert!(rows.end <= split);
                }
                if a.is_none() && b.is_none() {
                    break;
                }
            }
            assert!(top.rows_left().is_empty() && bottom.rows_left().is_empty());
            assert_eq!(got.px, whole.px, "{}: split {split}", $what);
        }
        whole
    }};
}

#[test]
fn two_strip_passes_draw_the_whole_frame_at_every_split() {
    let sphere = Shape::<Q, 642, 1280>::icosphere(1.0, 3).unwrap();
    let objects = [Object {
        mesh: sphere.mesh(),
        transform: Mat4::rotate_y(Q::from_f64(0.4)),
        material: Material::matte([200, 60, 60], Q::from_f64(0.1), Q::from_f64(0.8)),
    }];
    let scene = Scene::new(&objects, camera([0.0, 0.5, 3.0]), light());
    for dither in [false, true] {
        let mut r: Box<Renderer<Q, Rgb565, 96, 96, 1300, 1300, 96>> = Box::default();
        r.set_dither(dither);
        let f = check_passes!(*r, &scene, StripPass<Rgb565, 96, 96, 4>, "sphere");
        assert!(drawn(&f) > 3000);
    }
    // Textured and Phong triangles: each pass copies the frame's lights and materials.
    let shape = TexturedShape::<Q, 24, 12>::cube(1.0).unwrap();
    for shading in [Shading::Gouraud, Shading::Phong] {
        let objects = textured_cube_scene(&shape, shading);
        let scene = Scene::new(&objects, camera([0.0, 1.5, 3.0]), light());
        let mut r: Box<Renderer<Q, Rgb565, 96, 96, 64, 64, 16, 1, 64, 16>> = Box::default();
        let f = check_passes!(*r, &scene, StripPass<Rgb565, 96, 16, 2, 16>, "textured");
        assert!(drawn(&f) > 1500);
    }
    // No depth lines, the painter's order (the renderer keeps slots; a pass, records).
    let cube = Shape::<Q, 24, 12>::cube(1.0).unwrap();
    let m = Material::matte([220, 60, 60], Q::from_f64(0.2), Q::from_f64(0.8));
    let objects = [
        Object {
            mesh: cube.mesh(),
            transform: Mat4::translate([0.3, 0.0, 1.0].map(Q::from_f64)),
            material: m,
        },
        Object {
            mesh: cube.mesh(),
            transform: Mat4::rotate_y(Q::from_f64(0.9))
                .then(&Mat4::translate([-0.4, 0.2, -1.5].map(Q::from_f64))),
            material: m,
        },
    ];
    let scene = Scene::new(&objects, camera([0.3, 0.8, 4.0]), light());
    let mut r: Box<NoDepthRenderer<Q, Rgb565, 96, 96, 64, 64, 32>> = Box::default();
    let f = check_passes!(*r, &scene, StripPass<Rgb565, 96, 32, 2, 0, 0>, "no depth");
    assert!(drawn(&f) > 1500);
}

/// A pass refuses a renderer without a frame, a frame prepared after it began, and a target
/// smaller than the viewport; a dithering change between strips is followed.
#[test]
fn a_strip_pass_refuses_a_stale_frame() {
    let sphere = Shape::<Q, 642, 1280>::icosphere(1.0, 2).unwrap();
    let objects = [Object {
        mesh: sphere.mesh(),
        transform: Mat4::identity(),
        material: Material::matte([60, 200, 90], Q::from_f64(0.2), Q::from_f64(0.8)),
    }];
    let scene = Scene::new(&objects, camera([0.0, 0.5, 3.0]), light());
    let mut r: Box<Renderer<Q, Rgb565, 96, 96, 700, 700, 64>> = Box::default();
    let mut pass: Box<StripPass<Rgb565, 96, 64, 4>> = Box::default();
    assert_eq!(pass.begin(&*r, 0..96), Err(scanline3d::Error::NoFrame));
    let mut lines = [[SENTINEL; 96]; 4];
    assert_eq!(
        pass.render_strip_into(&*r, &mut lines),
        Err(scanline3d::Error::FrameChanged)
    );
    let _ = r.prepare(&scene, FrameOptions::new()).unwrap();
    pass.begin(&*r, 10..50).unwrap();
    assert_eq!(pass.rows_left(), 10..50);
    let mut small = Frame::new(50, 50, SENTINEL);
    assert!(matches!(
        pass.render_strip(&*r, &mut small),
        Err(scanline3d::Error::TargetTooSmall { .. })
    ));
    assert_eq!(
        pass.render_strip_into(&*r, &mut lines).unwrap(),
        Some(10..14)
    );
    // A frame prepared after the pass began is refused.
    let _ = r.prepare(&scene, FrameOptions::new()).unwrap();
    assert_eq!(
        pass.render_strip_into(&*r, &mut lines),
        Err(scanline3d::Error::FrameChanged)
    );
    // Dithering switched on between strips: the pass follows as the renderer does.
    let mut want = Frame::new(96, 96, SENTINEL);
    let mut frame = r.prepare(&scene, FrameOptions::new()).unwrap();
    frame.seek_row(30);
    for _ in 0..4 {
        // The renderer's strips are one line (its `LINES`).
        assert!(frame.strip_into(&mut lines).is_some());
    }
    assert_eq!(frame.next_row(), 34);
    frame.set_dither(true);
    while frame.strip_to(&mut want).unwrap().is_some() {}
    frame.set_dither(false);
    pass.begin(&*r, 30..96).unwrap();
    assert_eq!(
        pass.render_strip_into(&*r, &mut lines).unwrap(),
        Some(30..34)
    );
    r.set_dither(true);
    let mut got = Frame::new(96, 96, SENTINEL);
    while pass.render_strip(&*r, &mut got).unwrap().is_some() {}
    assert_eq!(got.px[34 * 96..], want.px[34 * 96..]);
    assert!(got.px[34 * 96..].iter().all(|&c| c != SENTINEL) || drawn(&got) > 1000);
    assert!(pass.stats().fragments > 0);
}
