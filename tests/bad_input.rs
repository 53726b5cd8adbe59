//! Bad input gets a defined result — a counted skip or an error naming the problem — never a
//! panic. These run in debug (overflow checks on) and release in CI.

use crate::common;

use common::{at, screen_camera, unlit, Frame};
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::prelude::*;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{errors::Capacity, Error, Stats};
use scanline3d_support::demo::deg;

type Q = Fx<I16F16>;
type Small<S> = Renderer<S, Rgb565, 32, 32, 64, 64, 16>;

fn perspective<S: Scalar>(eye: [f64; 3]) -> Camera<S> {
    Camera::look_at(
        eye.map(S::from_f64),
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(60.0),
            near: S::from_f64(0.1),
            far: S::from_f64(50.0),
        },
    )
    .unwrap()
}

fn draw<S: Scalar>(
    pos: &[[S; 3]],
    idx: &[[u16; 3]],
    normals: Option<&[[S; 3]]>,
    cam: Camera<S>,
) -> (Frame<Rgb565>, Stats) {
    let mut mesh = Mesh::new(pos, idx).unwrap();
    let shading = if let Some(n) = normals {
        mesh = mesh.with_normals(n).unwrap();
        Shading::Gouraud
    } else {
        Shading::Flat
    };
    let mut material = unlit([200, 100, 50], shading);
    material.diffuse = S::from_f64(0.5);
    let objects = [Object {
        mesh,
        transform: Mat4::identity(),
        material,
    }];
    let scene = Scene::new(&objects, cam, [Light::white([S::ONE, S::ONE, S::ONE])]);
    let mut r: Box<Small<S>> = Box::default();
    let mut f = Frame::new(32, 32, Rgb565::BLACK);
    let stats = r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    (f, stats)
}

fn p<S: Scalar>(x: f64, y: f64, z: f64) -> [S; 3] {
    [S::from_f64(x), S::from_f64(y), S::from_f64(z)]
}

fn non_finite_floats<S: Scalar>(bad: f64) {
    let pos = [
        p::<S>(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.0),
        p(0.0, 1.0, 0.0),
        p(bad, 0.5, 0.0),
        p(-1.0, -1.0, 0.0),
    ];
    let idx = [[0u16, 1, 2], [0, 3, 2], [1, 3, 4], [0, 4, 1]];
    let (_, s) = draw(&pos, &idx, None, perspective([0.0, 0.0, 3.0]));
    assert_eq!(s.invalid, 2, "{} {bad}: {s:?}", S::NAME);
    assert_eq!(s.drawn, 2);
}

#[test]
fn nan_and_infinite_coordinates_are_counted_skips() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        non_finite_floats::<f32>(bad);
        non_finite_floats::<f64>(bad);
    }
    // f32::MAX survives as a finite f32 input but overflows the transform.
    non_finite_floats::<f32>(f32::MAX as f64);
}

#[test]
fn fixed_point_overflow_is_a_counted_skip() {
    // 30 000 is representable in Q16.16, but the projection overflows it: the vertex hits the
    // saturation rail and its triangles are skipped, never drawn wrapped.
    let pos = [
        p::<Q>(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.0),
        p(0.0, 1.0, 0.0),
        p(30000.0, 0.5, 0.0),
    ];
    let idx = [[0u16, 1, 2], [0, 3, 2]];
    let (_, s) = draw(&pos, &idx, None, perspective([0.0, 0.0, 0.2]));
    assert_eq!((s.invalid, s.drawn), (1, 1), "{s:?}");
    // Saturating input conversion is defined too.
    assert_eq!(Q::from_f64(1e300), Q::from_f64(32767.99999));
}

fn zero_normals_light_as_ambient<S: Scalar>() {
    let pos = [p::<S>(-1.0, -1.0, 0.0), p(1.0, -1.0, 0.0), p(0.0, 1.0, 0.0)];
    let n = [[S::ZERO; 3]; 3];
    let (f, s) = draw(&pos, &[[0, 1, 2]], Some(&n), perspective([0.0, 0.0, 3.0]));
    assert!(s.pixels_written > 50);
    // Ambient only: material colour × 1.0 (ambient 1, the diffuse term sees N = 0).
    let want: Rgb565 = scanline3d::color::quantize([200, 100, 50]);
    assert_eq!(f.get(16, 16), want, "{}", S::NAME);
}

#[test]
fn zero_length_normals() {
    zero_normals_light_as_ambient::<Q>();
    zero_normals_light_as_ambient::<f32>();
    zero_normals_light_as_ambient::<f64>();
}

fn degenerate_and_bad_indices<S: Scalar>() {
    let pos = [
        p::<S>(0.0, 0.0, 0.0),
        p(1.0, 1.0, 0.0),
        p(2.0, 2.0, 0.0),
        p(0.0, 1.0, 0.0),
    ];
    let idx = [[0u16, 1, 2], [1, 1, 1], [0, 1, 9], [65535, 0, 1], [0, 3, 2]];
    let (_, s) = draw(&pos, &idx, None, perspective([0.0, 0.0, 3.0]));
    assert_eq!(s.degenerate, 2, "{}: {s:?}", S::NAME);
    assert_eq!(s.invalid, 2, "{}: {s:?}", S::NAME);
    assert_eq!(s.triangles_in, 5);
}

#[test]
fn degenerate_triangles_and_out_of_range_indices() {
    degenerate_and_bad_indices::<Q>();
    degenerate_and_bad_indices::<f32>();
    degenerate_and_bad_indices::<f64>();
}

fn all_behind<S: Scalar>() {
    // The camera at z = 3 looks toward −Z; everything at z = 5..6 is behind the eye, including
    // a vertex exactly at the eye plane (w = 0).
    let pos = [
        p::<S>(-1.0, -1.0, 5.0),
        p(1.0, -1.0, 6.0),
        p(0.0, 1.0, 5.0),
        p(0.0, 0.0, 3.0),
    ];
    let idx = [[0u16, 1, 2], [0, 2, 1], [0, 1, 3]];
    let (f, s) = draw(&pos, &idx, None, perspective([0.0, 0.0, 3.0]));
    assert_eq!(s.drawn, 0, "{}: {s:?}", S::NAME);
    assert_eq!(s.outside, 3, "{}: {s:?}", S::NAME);
    assert!(f.px.iter().all(|&c| c == Rgb565::BLACK));
}

#[test]
fn every_vertex_behind_the_eye() {
    all_behind::<Q>();
    all_behind::<f32>();
    all_behind::<f64>();
}

fn camera_inside_a_cube<S: Scalar>() {
    let cube = Shape::<S, 24, 12>::cube(1.0).unwrap();
    let mut m = unlit([255, 255, 255], Shading::Flat);
    m.diffuse = S::from_f64(0.5);
    // Turn the cube inside out (reversed winding) so the faces around the eye face it. (A
    // mirroring transform no longer does that: the renderer keeps a mirrored object's outside
    // in front, issue #21.)
    let inside_out: Vec<[u16; 3]> = cube
        .mesh()
        .indices()
        .iter()
        .map(|t| [t[0], t[2], t[1]])
        .collect();
    let objects = [Object {
        mesh: Mesh::new(cube.mesh().positions(), &inside_out).unwrap(),
        transform: Mat4::identity(),
        material: m,
    }];
    let cam = Camera::look_at(
        [S::from_f64(0.2), S::from_f64(0.1), S::from_f64(0.3)],
        [S::from_f64(1.0), S::from_f64(0.3), S::from_f64(-1.0)],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(90.0),
            near: S::from_f64(0.05),
            far: S::from_f64(10.0),
        },
    )
    .unwrap();
    let scene = Scene::new(&objects, cam, [Light::white([S::ONE, S::ONE, S::ONE])]);
    let mut r: Box<Small<S>> = Box::default();
    let mut f = Frame::new(32, 32, Rgb565::BLACK);
    let s = r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    // Inside a closed box every pixel sees a wall.
    assert!(
        f.px.iter().all(|&c| c != Rgb565::BLACK),
        "{}: {s:?}",
        S::NAME
    );
    assert!(s.clipped > 0);
}

#[test]
fn camera_inside_a_closed_mesh() {
    camera_inside_a_cube::<Q>();
    camera_inside_a_cube::<f32>();
    camera_inside_a_cube::<f64>();
}

#[test]
fn capacity_errors_name_the_capacity_and_draw_nothing() {
    let torus = scanline3d_support::demo::torus::<Q>().unwrap();
    let objects = [scanline3d_support::demo::torus_object(&torus)];
    let scene = Scene::new(
        &objects,
        scanline3d_support::demo::camera().unwrap(),
        scanline3d_support::demo::lights(),
    );
    // Too few vertices: the one error names every capacity that is short.
    let mut r: Box<Renderer<Q, Rgb565, 64, 64, 100, 2000, 200>> = Box::default();
    let mut d = MockDisplay::<Rgb565>::new();
    match r.render(&scene, &mut d) {
        Err(Error::Shortfall(s)) => {
            assert_eq!(s.needed.vertices, 512);
            assert_eq!(s.capacity.vertices, 100);
            assert!(s.is_short(Capacity::Vertices) && !s.exact);
            assert_eq!(s.iter().next(), Some((Capacity::Vertices, 512, 100)));
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(d, MockDisplay::new(), "nothing drawn");
    // Too few triangles.
    let mut r: Box<Renderer<Q, Rgb565, 64, 64, 512, 100, 200>> = Box::default();
    match r.render(&scene, &mut d) {
        Err(Error::Shortfall(s)) => {
            assert!(s.is_short(Capacity::Triangles) && !s.is_short(Capacity::Vertices));
            assert_eq!(s.capacity.triangles, 100);
            assert!(s.needed.triangles > 400, "{s:?}");
        }
        other => panic!("{other:?}"),
    }
    // Too few active triangles.
    let mut r: Box<Renderer<Q, Rgb565, 64, 64, 512, 600, 4>> = Box::default();
    match r.render(&scene, &mut d) {
        Err(Error::Shortfall(s)) => {
            assert_eq!(
                s.iter().map(|(c, _, _)| c).collect::<Vec<_>>(),
                [Capacity::ActiveTriangles]
            );
            assert!(s.needed.active > 4 && s.exact);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(d, MockDisplay::new(), "nothing drawn");
    // Enough: renders, and the renderer can be reused after errors.
    let mut r: Box<Renderer<Q, Rgb565, 64, 64, 512, 600, 64>> = Box::default();
    let s = r.render(&scene, &mut d).unwrap();
    assert!(s.max_active <= 64 && s.drawn > 0);
}

#[test]
fn gouraud_without_normals_is_an_error() {
    let pos = [p::<f32>(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
    let idx = [[0u16, 1, 2]];
    let objects = [Object {
        mesh: Mesh::new(&pos, &idx).unwrap(),
        transform: Mat4::identity(),
        material: unlit([1, 2, 3], Shading::Gouraud),
    }];
    let scene = Scene::new(
        &objects,
        screen_camera::<f32>(32),
        [Light::white([0.0, 0.0, 1.0])],
    );
    let mut r: Box<Small<f32>> = Box::default();
    let mut d = MockDisplay::<Rgb565>::new();
    assert_eq!(
        r.render(&scene, &mut d),
        Err(Error::MissingNormals { object: 0 })
    );
}

/// A display that fails after accepting `ok` strips.
struct Failing {
    ok: usize,
    strips: usize,
}
impl OriginDimensions for Failing {
    fn size(&self) -> Size {
        Size::new(32, 32)
    }
}
impl DrawTarget for Failing {
    type Color = Rgb565;
    type Error = &'static str;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        Ok(())
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        _: &embedded_graphics::primitives::Rectangle,
        _: I,
    ) -> Result<(), Self::Error> {
        self.strips += 1;
        if self.strips > self.ok {
            Err("spi bus error")
        } else {
            Ok(())
        }
    }
}

#[test]
fn draw_target_errors_propagate() {
    let pos = [
        at::<f32>(32, 32, 2.0, 2.0, 0.0),
        at(32, 32, 2.0, 30.0, 0.0),
        at(32, 32, 30.0, 16.0, 0.0),
    ];
    let idx = [[0u16, 1, 2]];
    let objects = [Object {
        mesh: Mesh::new(&pos, &idx).unwrap(),
        transform: Mat4::identity(),
        material: unlit([9, 9, 9], Shading::Flat),
    }];
    let scene = Scene::new(
        &objects,
        screen_camera::<f32>(32),
        [Light::white([0.0, 0.0, 1.0])],
    );
    let mut r: Box<Small<f32>> = Box::default();
    let mut t = Failing { ok: 5, strips: 0 };
    assert_eq!(
        r.render(&scene, &mut t),
        Err(Error::Target("spi bus error"))
    );
    assert_eq!(t.strips, 6, "stops at the first failing strip");
}
