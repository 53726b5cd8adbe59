//! Depth only where a scene needs it: a renderer without depth lines (`NoDepthRenderer`) in
//! either order draws a convex object exactly as the Z-buffer does; the painter's order draws
//! objects that do not interpenetrate exactly as the Z-buffer does, and fails on
//! interpenetrating triangles (why the Z-buffer is the default); the depth lines' RAM is gone;
//! layered effects are refused.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{
    shadow::Layering, DrawOrder, Error, Layers, NoDepthRenderer, Shape, Stats, TargetColor,
};

type Q = Fx<scanline3d::fixed::types::I16F16>;

const N: usize = 96;

/// Which renderer draws the frame.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Mode {
    ZBuffer,
    /// The painter's order kept as a list of slots (`ACTIVE ≤ H`).
    Painter,
    /// The painter's order kept in the active records themselves (`ACTIVE > H`).
    PainterRecords,
    Any,
}

fn camera<S: Scalar>() -> Camera<S> {
    Camera::look_at(
        [0.3, 0.8, 4.0].map(S::from_f64),
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: S::from_f64(45f64.to_radians()),
            near: S::from_f64(0.5),
            far: S::from_f64(20.0),
        },
    )
    .unwrap()
}

fn lights<S: Scalar>() -> [Light<S>; 1] {
    [Light::white([-S::ONE, S::from_f64(1.5), S::from_f64(2.0)])]
}

/// `objects` drawn in `mode` into an `N × N` frame of colour `C`, with `dither`; the frame and
/// the renderer's statistics.
fn draw<S: Scalar, C: TargetColor + Into<Rgb888>>(
    objects: &[Object<'_, S>],
    mode: Mode,
    dither: bool,
) -> (Frame<C>, Stats) {
    let scene = Scene::new(objects, camera(), lights()).with_background([20, 30, 40]);
    let mut f = Frame::new(N as u32, N as u32, C::from_channels([0; 3]));
    let stats = match mode {
        Mode::ZBuffer => {
            let mut r = Renderer::<S, C, N, N, 1024, 1024, 128>::new();
            r.set_dither(dither);
            r.render(&scene, &mut f).unwrap()
        }
        Mode::Painter => {
            let mut r = NoDepthRenderer::<S, C, N, N, 1024, 1024, 64>::new();
            r.set_dither(dither);
            r.render(&scene, &mut f).unwrap()
        }
        Mode::PainterRecords | Mode::Any => {
            let mut r = NoDepthRenderer::<S, C, N, N, 1024, 1024, 128>::new();
            r.set_dither(dither);
            if mode == Mode::Any {
                r.set_order(DrawOrder::Any);
            }
            r.render(&scene, &mut f).unwrap()
        }
    };
    f.assert_each_written_once();
    (f, stats)
}

/// Pixels that differ between two frames.
fn differing<C: PartialEq>(a: &Frame<C>, b: &Frame<C>) -> usize {
    a.px.iter().zip(&b.px).filter(|(x, y)| x != y).count()
}

fn material<S: Scalar>(color: [u8; 3], shading: Shading) -> Material<S> {
    let mut m = Material::matte(color, S::from_f64(0.2), S::from_f64(0.8));
    m.shading = shading;
    m
}

fn turned<S: Scalar>(deg: f64) -> Mat4<S> {
    Mat4::rotate_y(S::from_f64(deg.to_radians())).then(&Mat4::rotate_x(S::from_f64(0.4)))
}

/// Every mode, colour type and dithering draws a convex object's frame as the Z-buffer does.
fn convex_case<S: Scalar>() {
    let cube = Shape::<S, 24, 12>::cube(1.4).unwrap();
    let ico = Shape::<S, 162, 320>::icosphere(1.2, 2).unwrap();
    for (mesh, shading) in [
        (cube.mesh(), Shading::Flat),
        (ico.mesh(), Shading::Gouraud),
        (ico.mesh(), Shading::Flat),
    ] {
        for deg in [0.0, 33.0, 171.0] {
            let objects = [Object {
                mesh,
                transform: turned(deg),
                material: material([200, 120, 60], shading),
            }];
            for dither in [false, true] {
                let (z, zs) = draw::<S, Rgb565>(&objects, Mode::ZBuffer, dither);
                for mode in [Mode::Painter, Mode::PainterRecords, Mode::Any] {
                    let (f, s) = draw::<S, Rgb565>(&objects, mode, dither);
                    assert_eq!(differing(&z, &f), 0, "{mode:?} {shading:?} {deg}° {dither}");
                    // The same fragments, every one written (nothing to hide).
                    assert_eq!(s.fragments, zs.fragments);
                    assert_eq!(s.pixels_written, s.fragments);
                }
            }
            let (z, _) = draw::<S, Rgb888>(&objects, Mode::ZBuffer, false);
            let (f, _) = draw::<S, Rgb888>(&objects, Mode::Any, false);
            assert_eq!(differing(&z, &f), 0, "Rgb888 {shading:?} {deg}°");
        }
    }
}

#[test]
fn a_convex_object_needs_no_depth_fixed() {
    convex_case::<Q>();
}

#[test]
fn a_convex_object_needs_no_depth_f32() {
    convex_case::<f32>();
}

#[test]
fn a_convex_object_needs_no_depth_f64() {
    convex_case::<f64>();
}

/// Two cubes, the near one submitted first and overlapping the far one on screen: the
/// painter's order draws the Z-buffer's frame, any order draws the far cube over the near one.
fn separate_objects_case<S: Scalar>() {
    let cube = Shape::<S, 24, 12>::cube(1.0).unwrap();
    let objects = [
        Object {
            mesh: cube.mesh(),
            transform: turned::<S>(20.0).then(&Mat4::translate([0.3, 0.0, 1.0].map(S::from_f64))),
            material: material([220, 60, 60], Shading::Flat),
        },
        Object {
            mesh: cube.mesh(),
            transform: turned::<S>(50.0).then(&Mat4::translate([-0.4, 0.2, -1.5].map(S::from_f64))),
            material: material([60, 200, 90], Shading::Gouraud),
        },
    ];
    let (z, _) = draw::<S, Rgb565>(&objects, Mode::ZBuffer, false);
    let (p, _) = draw::<S, Rgb565>(&objects, Mode::Painter, false);
    let (pr, _) = draw::<S, Rgb565>(&objects, Mode::PainterRecords, false);
    let (a, _) = draw::<S, Rgb565>(&objects, Mode::Any, false);
    assert_eq!(differing(&z, &p), 0, "painter's differs from the Z-buffer");
    assert_eq!(
        differing(&z, &pr),
        0,
        "painter's (records) differs from the Z-buffer"
    );
    // From the middle row on (`seek_row`), the painter's order is kept too.
    let scene = Scene::new(&objects, camera(), lights()).with_background([20, 30, 40]);
    let mut r = NoDepthRenderer::<S, Rgb565, N, N, 1024, 1024, 64>::new();
    let mut frame = r.prepare(&scene, scanline3d::FrameOptions::new()).unwrap();
    frame.seek_row(N / 2);
    let mut g = Frame::new(N as u32, N as u32, Rgb565::BLACK);
    while frame.strip_to(&mut g).unwrap().is_some() {}
    let half = N * N / 2;
    assert_eq!(g.px[half..], p.px[half..], "painter's from seek_row");
    assert!(
        differing(&z, &a) > 50,
        "any order should show the far cube over the near one: {} pixels differ",
        differing(&z, &a)
    );
}

#[test]
fn painter_draws_separate_objects_as_the_zbuffer_fixed() {
    separate_objects_case::<Q>();
}

#[test]
fn painter_draws_separate_objects_as_the_zbuffer_f32() {
    separate_objects_case::<f32>();
}

#[test]
fn painter_draws_separate_objects_as_the_zbuffer_f64() {
    separate_objects_case::<f64>();
}

/// Two triangles crossing each other in depth (an X seen from the side): the Z-buffer shows
/// each in front on its own side of the crossing line; the painter's order shows one of them
/// over the other everywhere they overlap.
fn interpenetrating_case<S: Scalar>() {
    let positions: [[S; 3]; 6] = [
        [-1.2, -1.0, -0.8],
        [1.2, -1.0, 0.8],
        [0.0, 1.2, 0.0],
        [-1.2, -0.9, 0.8],
        [1.2, -0.9, -0.8],
        [0.0, 1.1, 0.0],
    ]
    .map(|p| p.map(S::from_f64));
    let red: Material<S> = common::unlit([255, 0, 0], Shading::Flat);
    let blue: Material<S> = common::unlit([0, 0, 255], Shading::Flat);
    let objects = [
        Object {
            mesh: Mesh::new(&positions[..3], &[[0u16, 1, 2]]).unwrap(),
            transform: Mat4::identity(),
            material: red,
        },
        Object {
            mesh: Mesh::new(&positions[3..], &[[0u16, 1, 2]]).unwrap(),
            transform: Mat4::identity(),
            material: blue,
        },
    ];
    let count = |f: &Frame<Rgb565>, c: Rgb565, left: bool| {
        (0..N as u32)
            .flat_map(|y| (0..N as u32).map(move |x| (x, y)))
            .filter(|&(x, y)| (x < N as u32 / 2) == left && f.get(x, y) == c)
            .count()
    };
    let (z, _) = draw::<S, Rgb565>(&objects, Mode::ZBuffer, false);
    let (p, _) = draw::<S, Rgb565>(&objects, Mode::Painter, false);
    let (red, blue) = (Rgb565::RED, Rgb565::BLUE);
    // The Z-buffer: red nearer on the right half, blue on the left.
    assert!(count(&z, blue, true) > 200 && count(&z, red, false) > 200);
    assert!(count(&z, red, true) < count(&z, blue, true) / 4);
    // The painter's order: one triangle drawn over the other on both sides.
    let wrong = differing(&z, &p);
    assert!(
        wrong > 200,
        "painter's should fail here: {wrong} pixels differ"
    );
    // Either side of the crossing line, inside both triangles: the Z-buffer shows each in
    // front on its own side, the painter's order the same one on both.
    let (y, l, r) = (N as u32 / 2 + 5, N as u32 / 2 - 10, N as u32 / 2 + 10);
    assert_eq!((z.get(l, y), z.get(r, y)), (blue, red));
    assert_eq!(p.get(l, y), p.get(r, y));
}

#[test]
fn painter_fails_on_interpenetrating_triangles_fixed() {
    interpenetrating_case::<Q>();
}

#[test]
fn painter_fails_on_interpenetrating_triangles_f32() {
    interpenetrating_case::<f32>();
}

#[test]
fn painter_fails_on_interpenetrating_triangles_f64() {
    interpenetrating_case::<f64>();
}

#[test]
fn no_depth_lines_no_depth_ram() {
    type Z4 = Renderer<Q, Rgb565, 240, 240, 64, 64, 16, 4>;
    type P4 = NoDepthRenderer<Q, Rgb565, 240, 240, 64, 64, 16, 4>;
    assert_eq!(Z4::RAM_BYTES - P4::RAM_BYTES, 4 * 240 * 2);
    // The explicit parameter: `ZL = LINES` is the default.
    type Z4b = Renderer<Q, Rgb565, 240, 240, 64, 64, 16, 4, 0, 0, 4>;
    assert_eq!(Z4b::RAM_BYTES, Z4::RAM_BYTES);
}

#[test]
fn layered_frames_need_depth_lines() {
    let cube = Shape::<f32, 24, 12>::cube(1.0).unwrap();
    let objects = [Object {
        mesh: cube.mesh(),
        transform: Mat4::identity(),
        material: material([200, 200, 200], Shading::Flat),
    }];
    let scene = Scene::new(&objects, camera(), lights());
    let mut r = NoDepthRenderer::<f32, Rgb565, N, N, 64, 64, 16>::new();
    let mut layers = Layers::<N, 1, 4, 16>::new();
    let mut f = Frame::new(N as u32, N as u32, Rgb565::BLACK);
    let e = r
        .render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(&Layering::none(), &mut layers),
            &mut f,
        )
        .unwrap_err();
    assert_eq!(e, Error::NoDepthLines);
    assert!(e.to_string().contains("depth lines"));
    assert!(f.writes.iter().all(|&n| n == 0), "nothing is drawn");
}

/// The benchmark's depth-mode scenes draw their Z-buffer scene's pixels at every angle, with
/// less renderer RAM.
fn bench_case<S: Scalar>() {
    use scanline3d_support::demo::{render_bench, Bench};
    for (b, zbuffer) in [
        (Bench::CubePainter, Bench::Cube),
        (Bench::CubeNoDepth, Bench::Cube),
        (Bench::IcospherePainter, Bench::Icosphere),
        (Bench::IcosphereNoDepth, Bench::Icosphere),
    ] {
        assert!(b.depth_order().is_some() && zbuffer.depth_order().is_none());
        for spin in (0..360).step_by(30) {
            for dither in [false, true] {
                let frame = |scene| {
                    let mut f = Frame::new(240, 240, Rgb565::BLACK);
                    let r = render_bench::<S, Rgb565, _, _>(
                        scene,
                        spin as f64,
                        dither,
                        &mut f,
                        &mut common::compare::HostProbe::Plain,
                    )
                    .unwrap();
                    (f, r)
                };
                let ((f, r), (z, rz)) = (frame(b), frame(zbuffer));
                assert_eq!(differing(&f, &z), 0, "{b:?} at {spin}°, dither {dither}");
                assert_eq!(rz.renderer_ram_bytes - r.renderer_ram_bytes, 240 * 2);
            }
        }
    }
}

#[test]
fn bench_depth_modes_fixed() {
    bench_case::<Q>();
}

#[test]
fn bench_depth_modes_f32() {
    bench_case::<f32>();
}

#[test]
fn bench_depth_modes_f64() {
    bench_case::<f64>();
}
