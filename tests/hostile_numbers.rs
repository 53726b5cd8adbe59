//! Hostile numbers through the public API (issue #21): NaN and infinite inputs, cameras whose
//! public fields were edited, a near plane too small for the 16-bit depth buffer, mirrored
//! transforms, and the errors that name what went wrong — for `Fx<I16F16>`, `f32` and `f64`,
//! into RGB565 and Gray8 targets. Each case says what `main` did before the fix. Every render
//! runs on a thread with a time limit, so a hang fails instead of stalling CI.

use crate::common;

use std::sync::mpsc;
use std::time::Duration;

use common::Frame;
use embedded_graphics::pixelcolor::{Gray8, GrayColor, Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use scanline3d::fixed::types::I16F16;
use scanline3d::limits::MAX_DEPTH_RATIO;
use scanline3d::prelude::*;
use scanline3d::{errors::CameraError, errors::MeshError, Error, Stats};

type Q = Fx<I16F16>;
type R<S, C> = Renderer<S, C, 48, 48, 64, 64, 32>;

/// Runs `f` on a thread and fails if it takes longer than 60 s (a hang) or panics.
fn limited<T: Send + 'static>(what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    match rx.recv_timeout(Duration::from_secs(60)) {
        Ok(v) => v,
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("{what}: no result within 60 s"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("{what}: panicked"),
    }
}

fn v3<S: Scalar>(a: [f64; 3]) -> [S; 3] {
    a.map(S::lit)
}

fn persp<S: Scalar>(near: f64, far: f64) -> Projection<S> {
    Projection::Perspective {
        fov_y: S::lit(0.9),
        near: S::lit(near),
        far: S::lit(far),
    }
}

fn camera<S: Scalar>(eye: [f64; 3], projection: Projection<S>) -> Result<Camera<S>, CameraError> {
    Camera::look_at(v3(eye), [S::ZERO; 3], v3([0.0, 1.0, 0.0]), projection)
}

/// What can be broken in a scene: which input gets `bad`.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Poison {
    None,
    Position,
    Transform,
    Light,
    Ambient,
    Diffuse,
}

/// The result of one frame: the stats (or the error, as text) and the non-background pixels.
type Outcome = Result<(Stats, usize), String>;

/// A 5-vertex, 4-triangle fan (vertex 3 used by two triangles) in front of the camera,
/// flat-shaded, into a `C` target, with `bad` put where `poison` says.
fn fan<S: Scalar, C>(poison: Poison, bad: f64, cam: Camera<S>) -> Outcome
where
    C: TargetColor + PixelColor + Default + std::fmt::Debug,
{
    let mut pos = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.7, 0.5, 0.0],
        [-1.0, -1.0, 0.0],
    ]
    .map(v3::<S>);
    if poison == Poison::Position {
        pos[3][0] = S::lit(bad);
    }
    let idx = [[0u16, 1, 2], [0, 3, 2], [1, 3, 4], [0, 4, 1]];
    let mesh = Mesh::new(&pos, &idx).map_err(|e| e.to_string())?;
    let mut material = Material::matte([200, 150, 100], S::lit(0.3), S::lit(0.7));
    material.shading = Shading::Flat;
    match poison {
        Poison::Ambient => material.ambient = S::lit(bad),
        Poison::Diffuse => material.diffuse = S::lit(bad),
        _ => {}
    }
    let mut transform = Mat4::identity();
    if poison == Poison::Transform {
        transform.m[1][2] = S::lit(bad);
    }
    let objects = [Object {
        mesh,
        transform,
        material,
    }];
    let mut dir = v3::<S>([0.3, 0.4, 1.0]);
    if poison == Poison::Light {
        dir[1] = S::lit(bad);
    }
    let scene = Scene::new(&objects, cam, [Light::white(dir)]);
    let mut r: Box<R<S, C>> = Box::default();
    let mut f = Frame::new(48, 48, C::default());
    let stats = r.render(&scene, &mut f).map_err(|e| e.to_string())?;
    let lit = f.px.iter().filter(|&&c| c != C::default()).count();
    Ok((stats, lit))
}

fn nan_inputs_for<S: Scalar, C>()
where
    C: TargetColor + PixelColor + Default + std::fmt::Debug,
{
    let cam = || camera::<S>([0.0, 0.0, 4.0], persp(0.1, 20.0)).unwrap();
    let (clean, clean_lit) = fan::<S, C>(Poison::None, 0.0, cam()).unwrap();
    assert_eq!(
        (clean.invalid, clean.drawn),
        (0, 4),
        "{}: {clean:?}",
        S::NAME
    );
    assert!(clean_lit > 100);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        // Position: main turned a Q16.16 NaN into 0 and drew all four triangles (f32/f64
        // skipped the two that use the vertex).
        let (s, _) = fan::<S, C>(Poison::Position, bad, cam()).unwrap();
        assert_eq!(
            (s.invalid, s.drawn),
            (2, 2),
            "{} position {bad}: {s:?}",
            S::NAME
        );
        // Transform, material coefficients: main drew the object in Q16.16 with the NaN read
        // as 0, and in f32/f64 drew it with a lost light (ambient only) or a NaN colour; now
        // every triangle of the object is skipped and counted, in every type.
        for poison in [Poison::Transform, Poison::Ambient, Poison::Diffuse] {
            let (s, lit) = fan::<S, C>(poison, bad, cam()).unwrap();
            assert_eq!(
                (s.triangles_in, s.invalid, s.drawn, s.pixels_written, lit),
                (4, 4, 0, 0, 0),
                "{} {poison:?} {bad}: {s:?}",
                S::NAME
            );
        }
        // A light direction: the scene's, not one object's. It too made every object a counted
        // skip (an empty frame that came back `Ok`); now the frame is refused, as for a fog or
        // a tone map with a NaN, in every type.
        let e = fan::<S, C>(Poison::Light, bad, cam()).unwrap_err();
        assert!(e.contains("light 0"), "{} light {bad}: {e}", S::NAME);
    }
}

#[test]
fn nan_and_infinite_inputs_are_counted_skips_in_every_number_type() {
    limited("nan inputs", || {
        nan_inputs_for::<Q, Rgb565>();
        nan_inputs_for::<f32, Rgb565>();
        nan_inputs_for::<f64, Rgb565>();
        nan_inputs_for::<Q, Gray8>();
        nan_inputs_for::<f32, Gray8>();
        nan_inputs_for::<f64, Gray8>();
    });
}

#[test]
fn fixed_point_nan_is_a_rail_not_zero() {
    // main: Q::from_f64(NaN) == 0, a valid value.
    assert!(!Q::lit(f64::NAN).is_valid());
    assert!(!Q::from_f64(f64::NAN).is_valid());
    assert!(!Q::from_f64(f64::INFINITY).is_valid());
    assert!(!Q::from_f64(f64::NEG_INFINITY).is_valid());
    let pos = [[Q::ZERO; 3], [Q::ONE, Q::ZERO, Q::lit(f64::NAN)]];
    assert!(Mesh::new(&pos, &[]).unwrap().has_invalid_positions());
    assert!(!Mesh::new(&pos[..1], &[]).unwrap().has_invalid_positions());
}

fn edited_cameras_for<S: Scalar, C>()
where
    C: TargetColor + PixelColor + Default + std::fmt::Debug,
{
    let good = camera::<S>([0.0, 0.0, 4.0], persp(0.1, 20.0)).unwrap();
    // Orthographic, height −1, near > far: main filled the whole screen with one colour.
    let mut cam = good;
    cam.projection = Projection::Orthographic {
        height: S::lit(-1.0),
        near: S::lit(5.0),
        far: S::lit(1.0),
    };
    let e = fan::<S, C>(Poison::None, 0.0, cam).unwrap_err();
    assert!(e.contains("height") && e.contains("-1"), "{}: {e}", S::NAME);
    cam.projection = Projection::Orthographic {
        height: S::lit(3.0),
        near: S::lit(5.0),
        far: S::lit(1.0),
    };
    let e = fan::<S, C>(Poison::None, 0.0, cam).unwrap_err();
    assert!(
        e.contains("far") && e.contains("> near"),
        "{}: {e}",
        S::NAME
    );
    // Perspective with near > far: main still drew.
    cam.projection = persp(5.0, 1.0);
    let e = fan::<S, C>(Poison::None, 0.0, cam).unwrap_err();
    assert!(
        e.contains("far = 1") && e.contains("> near"),
        "{}: {e}",
        S::NAME
    );
    // A NaN eye or view entry set by hand.
    let mut cam = good;
    cam.view.m[0][3] = S::lit(f64::NAN);
    let e = fan::<S, C>(Poison::None, 0.0, cam).unwrap_err();
    assert!(e.contains("view[0][3]"), "{}: {e}", S::NAME);
    // The error value itself, from `Renderer::render`.
    let mut cam = good;
    cam.projection = persp(5.0, 1.0);
    let objects: [Object<'_, S>; 0] = [];
    let scene = Scene::new(&objects, cam, [Light::white(v3([0.0, 0.0, 1.0]))]);
    let mut r: Box<R<S, C>> = Box::default();
    let mut f = Frame::new(48, 48, C::default());
    let err = r.render(&scene, &mut f).unwrap_err();
    assert_eq!(
        err,
        Error::Camera(CameraError::BadProjection {
            param: "far",
            value: 1.0,
            expected: "> near"
        })
    );
    assert!(f.writes.iter().all(|&n| n == 0), "nothing is drawn");
}

#[test]
fn render_revalidates_an_edited_camera() {
    limited("edited cameras", || {
        edited_cameras_for::<Q, Rgb565>();
        edited_cameras_for::<f32, Rgb565>();
        edited_cameras_for::<f64, Rgb565>();
        edited_cameras_for::<Q, Gray8>();
        edited_cameras_for::<f32, Gray8>();
        edited_cameras_for::<f64, Gray8>();
    });
}

fn tiny_near_for<S: Scalar, C>()
where
    C: TargetColor + PixelColor + Default + std::fmt::Debug,
{
    // near 1e-5, far 20: main accepted the camera, drew every triangle and wrote 0 pixels
    // (every depth rounded to the clear value and failed the Less test).
    let e = camera::<S>([0.0, 0.0, 4.0], persp(1e-5, 20.0)).unwrap_err();
    let CameraError::DepthPrecision {
        near,
        far,
        ratio,
        limit,
    } = e
    else {
        panic!("{}: {e:?}", S::NAME);
    };
    assert_eq!((far, limit), (20.0, MAX_DEPTH_RATIO), "{}", S::NAME);
    assert!(
        (near - 1e-5).abs() < 1e-5 && ratio > 1e6,
        "{}: {e:?}",
        S::NAME
    );
    let text = e.to_string();
    assert!(text.contains("1048576") && text.contains("depth"), "{text}");
    // The same camera set by hand is refused by `render`.
    let mut cam = camera::<S>([0.0, 0.0, 4.0], persp(0.1, 20.0)).unwrap();
    cam.projection = persp(1e-5, 20.0);
    let e = fan::<S, C>(Poison::None, 0.0, cam).unwrap_err();
    assert!(e.contains("depth"), "{e}");
    // Below the limit (the demo's near 0.01, far 1000; ratio 10⁵) the geometry is drawn.
    let cam = camera::<S>([0.0, 0.0, 4.0], persp(0.01, 1000.0)).unwrap();
    let (s, lit) = fan::<S, C>(Poison::None, 0.0, cam).unwrap();
    assert!(s.drawn == 4 && lit > 100, "{}: {s:?} {lit}", S::NAME);
}

#[test]
fn a_near_plane_too_small_for_the_depth_buffer_is_an_error() {
    limited("tiny near", || {
        tiny_near_for::<Q, Rgb565>();
        tiny_near_for::<f32, Rgb565>();
        tiny_near_for::<f64, Rgb565>();
        tiny_near_for::<Q, Gray8>();
        tiny_near_for::<f32, Gray8>();
        tiny_near_for::<f64, Gray8>();
    });
}

/// A unit cube rotated by `rot`, mirrored first in x when `mirror`, into a `C` frame; with a
/// light from the camera's side, so the faces toward the camera are the bright ones.
fn cube<S: Scalar, C>(mirror: bool, shading: Shading) -> (Stats, Frame<C>)
where
    C: TargetColor + PixelColor + Default,
{
    let shape = Shape::<S, 24, 12>::cube(1.0).unwrap();
    let rot = Mat4::rotate_y(S::lit(0.5)).then(&Mat4::rotate_x(S::lit(0.4)));
    let transform = if mirror {
        Mat4::scale(v3([-1.0, 1.0, 1.0])).then(&rot)
    } else {
        rot
    };
    let mut material = Material::matte([255, 200, 120], S::lit(0.2), S::lit(0.8));
    material.shading = shading;
    let objects = [Object {
        mesh: shape.mesh(),
        transform,
        material,
    }];
    let cam = camera::<S>([0.0, 0.0, 5.0], persp(0.1, 20.0)).unwrap();
    let scene = Scene::new(&objects, cam, [Light::white(v3([-0.3, 0.5, 1.0]))]);
    let mut r: Box<Renderer<S, C, 48, 48, 64, 64, 32>> = Box::default();
    let mut f = Frame::new(48, 48, C::default());
    let stats = r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    (stats, f)
}

fn mirrored_for<S: Scalar, C>(luma: impl Fn(C) -> u32)
where
    C: TargetColor + PixelColor + Default,
{
    for shading in [Shading::Flat, Shading::Gouraud] {
        // A cube mirrored in x is the same cube: the mirrored object must show the same faces,
        // lit the same, as the plain one. main drew it inside out: the far faces, lit from
        // behind (dark).
        let (plain, a) = cube::<S, C>(false, shading);
        let (mirrored, b) = cube::<S, C>(true, shading);
        assert_eq!(
            (mirrored.culled, mirrored.drawn),
            (plain.culled, plain.drawn),
            "{} {shading:?}",
            S::NAME
        );
        let sum = |f: &Frame<C>| f.px.iter().map(|&c| luma(c)).sum::<u32>();
        let (sa, sb) = (sum(&a), sum(&b));
        let differ =
            a.px.iter()
                .zip(&b.px)
                .filter(|(x, y)| luma(**x).abs_diff(luma(**y)) > 2)
                .count();
        let covered = a.px.iter().filter(|&&c| c != C::default()).count();
        assert!(covered > 300, "{}: {covered}", S::NAME);
        assert!(
            differ * 50 <= covered && sa.abs_diff(sb) * 50 <= sa,
            "{} {shading:?}: {differ} of {covered} pixels differ; brightness {sa} vs {sb}",
            S::NAME
        );
    }
}

#[test]
fn mirrored_transforms_show_the_outside() {
    limited("mirrored", || {
        let l565 = |c: Rgb565| c.r() as u32 * 2 + c.g() as u32 + c.b() as u32 * 2;
        let l8 = |c: Gray8| c.luma() as u32;
        mirrored_for::<Q, Rgb565>(l565);
        mirrored_for::<f32, Rgb565>(l565);
        mirrored_for::<f64, Rgb565>(l565);
        mirrored_for::<Q, Gray8>(l8);
        mirrored_for::<f32, Gray8>(l8);
        mirrored_for::<f64, Gray8>(l8);
    });
    assert!(Mat4::<Q>::scale(v3([1.0, -2.0, 1.0])).is_mirrored());
    assert!(!Mat4::<f32>::rotate_x(2.0).is_mirrored());
}

#[test]
fn look_at_errors_name_the_problem_and_the_value() {
    let up = |v: f64| [0.0, v, 0.0];
    let upf = |v: f32| [0.0, v, 0.0];
    // main: EyeAtTarget for all of these.
    // An eye beyond Q16.16's range saturates to the rail.
    let e = camera::<Q>([0.0, 0.0, 1e6], persp(0.1, 20.0)).unwrap_err();
    assert_eq!(
        e,
        CameraError::OutOfRange {
            param: "eye[2]",
            value: Q::lit(1e6).to_f64(),
            number_type: "I16F16"
        }
    );
    assert!(e.to_string().contains("I16F16") && e.to_string().contains("eye[2]"));
    // A NaN eye in Q16.16 (main: read as 0, a valid camera at the wrong place).
    let e = camera::<Q>([f64::NAN, 0.0, 4.0], persp(0.1, 20.0)).unwrap_err();
    assert!(
        matches!(
            e,
            CameraError::OutOfRange {
                param: "eye[0]",
                ..
            }
        ),
        "{e:?}"
    );
    // Non-finite float inputs.
    let e = camera::<f32>([0.0, 0.0, f64::INFINITY], persp(0.1, 20.0)).unwrap_err();
    assert_eq!(
        e,
        CameraError::NotFinite {
            param: "eye[2]",
            value: f64::INFINITY
        }
    );
    let e = Camera::<f64>::look_at(
        [0.0, 0.0, 4.0],
        [f64::NAN, 0.0, 0.0],
        up(1.0),
        persp(0.1, 2.0),
    )
    .unwrap_err();
    assert_eq!(
        e,
        CameraError::NotFinite {
            param: "target[0]",
            value: f64::NAN
        }
    );
    assert!(e.to_string().contains("target[0] is NaN"), "{e}");
    let e = Camera::<f64>::look_at(
        [0.0, 0.0, 4.0],
        [0.0; 3],
        [0.0, f64::NAN, 0.0],
        persp(0.1, 2.0),
    )
    .unwrap_err();
    assert!(matches!(e, CameraError::NotFinite { param: "up[1]", .. }));
    // Finite f32 inputs whose difference overflows.
    let e = Camera::<f32>::look_at(
        [3e38, 0.0, 0.0],
        [-3e38, 0.0, 0.0],
        upf(1.0),
        persp(0.1, 2.0),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            CameraError::OutOfRange {
                param: "eye[0] - target[0]",
                number_type: "f32",
                ..
            }
        ),
        "{e:?}"
    );
    // The real eye-at-target still says so.
    assert_eq!(
        camera::<Q>([0.0; 3], persp(0.1, 20.0)),
        Err(CameraError::EyeAtTarget)
    );
    // near 1e-6 rounds to 0 in Q16.16 (main: BadProjection, without saying so).
    let e = camera::<Q>([0.0, 0.0, 4.0], persp(1e-6, 20.0)).unwrap_err();
    assert_eq!(
        e,
        CameraError::RoundsToZero {
            param: "near",
            number_type: "I16F16",
            smallest: 1.0 / 65536.0
        }
    );
    let text = e.to_string();
    assert!(
        text.contains("near is 0 in I16F16") && text.contains("1.52587890625e-5"),
        "{text}"
    );
    // In f32, 1e-6 is representable: that camera fails on depth precision instead.
    assert!(matches!(
        camera::<f32>([0.0, 0.0, 4.0], persp(1e-6, 20.0)),
        Err(CameraError::DepthPrecision { .. })
    ));
    // Projection ranges name the parameter, its value and the valid range.
    let e = camera::<f64>(
        [0.0, 0.0, 4.0],
        Projection::Perspective {
            fov_y: 3.5,
            near: 0.1,
            far: 2.0,
        },
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "camera fov_y = 3.5: must be 0 < fov_y < π (radians)"
    );
}

fn lit_in_generic_code<S: Scalar>() -> S {
    S::lit(0.25) + S::lit(0.5)
}

#[test]
fn lit_is_on_the_number_trait() {
    // main: `Scalar` had no `lit` (only `Fx::lit`), so this did not compile.
    assert_eq!(lit_in_generic_code::<Q>(), Q::lit(0.75));
    assert_eq!(lit_in_generic_code::<f32>(), 0.75f32);
    assert_eq!(lit_in_generic_code::<f64>(), 0.75f64);
    assert_eq!(<Q as Scalar>::lit(0.5), Q::lit(0.5));
}

fn error_text<E: core::error::Error>(e: &E) -> String {
    e.to_string()
}

#[test]
fn errors_implement_display_and_error() {
    // main: none of these implemented `Display` or `core::error::Error`.
    let m = MeshError::IndexOutOfRange {
        triangle: 3,
        index: 9,
    };
    assert!(error_text(&m).contains("triangle 3") && error_text(&m).contains('9'));
    let g = scanline3d_support::overlay::GlyphError::TooManyChars { capacity: 4 };
    assert!(error_text(&g).contains('4'));
    let c: Error<core::convert::Infallible> = Error::Light {
        index: 1,
        point: true,
    };
    let t = error_text(&c);
    assert!(t.contains("point light 1") && t.contains("NaN"), "{t}");
    let cam: Error<core::convert::Infallible> = Error::Camera(CameraError::EyeAtTarget);
    assert!(core::error::Error::source(&cam).is_some());
    assert!(error_text(&cam).contains("eye equals target"));
    let b: scanline3d_support::demo::BenchError<core::convert::Infallible> =
        scanline3d_support::demo::BenchError::Render(Error::MissingNormals { object: 2 });
    assert!(error_text(&b).contains("object 2"));
    assert!(error_text(&CameraError::UpParallelToView).contains("parallel"));
}
