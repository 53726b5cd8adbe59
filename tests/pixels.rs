//! Tiny pixel-exact cases in embedded-graphics' MockDisplay (its overdraw check is on: the
//! renderer must write every pixel of the screen exactly once). Each case runs for the fixed-
//! point type, f32 and f64.

use crate::common;

use common::{at, screen_camera, unlit};
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use scanline3d::color::quantize;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::Stats;

const W: u32 = 16;
const H: u32 = 16;
static ONE_TRI: [[u16; 3]; 1] = [[0, 1, 2]];

/// Orders three screen points (y down) so the triangle faces the viewer.
fn front(p: [[f64; 2]; 3]) -> [[f64; 2]; 3] {
    let [a, b, c] = p;
    let area = (c[0] - a[0]) * (b[1] - a[1]) - (b[0] - a[0]) * (c[1] - a[1]);
    if area >= 0.0 {
        p
    } else {
        [a, c, b]
    }
}

/// Renders screen-space triangles (each its own object with an unlit colour) at world z
/// `depth` into a 16×16 MockDisplay.
fn render<S: Scalar, C: TargetColor>(
    tris: &[([[f64; 2]; 3], [u8; 3])],
    shading: Shading,
    dither: bool,
) -> (MockDisplay<C>, Stats) {
    let positions: Vec<[[S; 3]; 3]> = tris
        .iter()
        .map(|(p, _)| front(*p).map(|q| at::<S>(W, H, q[0], q[1], 0.0)))
        .collect();
    let normals = [[S::ZERO, S::ZERO, S::ONE]; 3];
    let objects: Vec<Object<S>> = tris
        .iter()
        .zip(positions.iter())
        .map(|((_, color), pos)| Object {
            mesh: Mesh::new(pos, &ONE_TRI)
                .unwrap()
                .with_normals(&normals)
                .unwrap(),
            transform: Mat4::identity(),
            material: unlit(*color, shading),
        })
        .collect();
    let scene = Scene::new(
        &objects,
        screen_camera::<S>(H),
        [Light::white([S::ZERO, S::ZERO, S::ONE])],
    );
    let mut r = Renderer::<S, C, 16, 16, 64, 64, 16>::new().with_dither(dither);
    let mut d = MockDisplay::new();
    let stats = r.render(&scene, &mut d).unwrap();
    (d, stats)
}

fn count<C: PixelColor>(d: &MockDisplay<C>, c: C) -> usize {
    let mut n = 0;
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            if d.get_pixel(Point::new(x, y)) == Some(c) {
                n += 1;
            }
        }
    }
    n
}

fn split_square<S: Scalar>() {
    // A 5×5 px square with corners on pixel boundaries, split along the diagonal: the diagonal
    // is the right edge of the upper-left triangle and the left edge of the lower-right one.
    let (a, b, c, d) = ([2.0, 2.0], [7.0, 2.0], [7.0, 7.0], [2.0, 7.0]);
    let (red, blue) = ([255, 0, 0], [0, 0, 255]);
    let (disp, stats) =
        render::<S, Rgb888>(&[([a, b, d], red), ([b, c, d], blue)], Shading::Flat, false);
    assert_eq!(
        count(&disp, Rgb888::RED),
        10,
        "{}: upper-left triangle",
        S::NAME
    );
    assert_eq!(
        count(&disp, Rgb888::BLUE),
        15,
        "{}: lower-right triangle",
        S::NAME
    );
    // 25 fragments for 25 pixels: no pixel rasterized twice.
    assert_eq!(
        (stats.fragments, stats.pixels_written),
        (25, 25),
        "{}",
        S::NAME
    );
}

fn quad_on_centre_lines<S: Scalar>() {
    let (a, b, c, d) = ([2.5, 2.5], [6.5, 2.5], [6.5, 6.5], [2.5, 6.5]);
    let (disp, stats) = render::<S, Rgb888>(
        &[([a, b, c], [0, 255, 0]), ([a, c, d], [0, 255, 0])],
        Shading::Flat,
        false,
    );
    assert_eq!(count(&disp, Rgb888::GREEN), 16, "{}", S::NAME);
    assert_eq!(stats.fragments, 16, "{}", S::NAME);
    // Top-left rule: the centres on the top and left edges are in, bottom and right out.
    assert_eq!(disp.get_pixel(Point::new(2, 2)), Some(Rgb888::GREEN));
    assert_eq!(disp.get_pixel(Point::new(6, 6)), Some(Rgb888::BLACK));
}

fn fan_around_a_centre<S: Scalar>() {
    let c = [8.5, 8.5];
    let mut tris = Vec::new();
    for k in 0..8 {
        let a0 = k as f64 * std::f64::consts::FRAC_PI_4 + 0.1;
        let a1 = a0 + std::f64::consts::FRAC_PI_4;
        let p = |a: f64| [c[0] + 5.0 * a.cos(), c[1] + 5.0 * a.sin()];
        tris.push(([c, p(a0), p(a1)], [(30 * k) as u8, 200, 100]));
    }
    let (disp, stats) = render::<S, Rgb888>(&tris, Shading::Flat, false);
    let covered = (W * H) as usize - count(&disp, Rgb888::BLACK);
    assert_eq!(
        stats.fragments as usize,
        covered,
        "{}: a pixel was rasterized twice",
        S::NAME
    );
    assert_ne!(disp.get_pixel(Point::new(8, 8)), Some(Rgb888::BLACK));
}

fn constant_gouraud<S: Scalar>() {
    let tri = [
        ([1.0, 1.0], [255, 160, 64]),
        ([14.0, 3.0], [0; 3]),
        ([5.0, 15.0], [0; 3]),
    ];
    let p = [tri[0].0, tri[1].0, tri[2].0];
    let want: Rgb565 = quantize([255, 160, 64]);
    let (disp, stats) = render::<S, Rgb565>(&[(p, [255, 160, 64])], Shading::Gouraud, false);
    assert_eq!(
        count(&disp, want),
        stats.pixels_written as usize,
        "{}",
        S::NAME
    );
    assert!(stats.pixels_written > 60);
    // Dithering leaves a representable colour unchanged.
    let (disp, stats) = render::<S, Rgb565>(&[(p, [255, 255, 255])], Shading::Gouraud, true);
    assert_eq!(
        count(&disp, Rgb565::WHITE),
        stats.pixels_written as usize,
        "{}",
        S::NAME
    );
}

fn whole_pixel_translation<S: Scalar>() {
    let base = [[2.3, 1.7], [9.9, 4.1], [4.2, 10.6]];
    let (d0, _) = render::<S, Rgb888>(&[(base, [255, 255, 255])], Shading::Flat, false);
    let moved = base.map(|p| [p[0] + 3.0, p[1] + 2.0]);
    let (d1, _) = render::<S, Rgb888>(&[(moved, [255, 255, 255])], Shading::Flat, false);
    for y in 0..(H as i32 - 2) {
        for x in 0..(W as i32 - 3) {
            assert_eq!(
                d0.get_pixel(Point::new(x, y)),
                d1.get_pixel(Point::new(x + 3, y + 2)),
                "{} at ({x}, {y})",
                S::NAME
            );
        }
    }
}

macro_rules! for_each_type {
    ($($name:ident),*) => {$(
        mod $name {
            use super::*;
            #[test]
            fn fixed_i16f16() {
                super::$name::<Fx<I16F16>>();
            }
            #[test]
            fn float_f32() {
                super::$name::<f32>();
            }
            #[test]
            fn float_f64() {
                super::$name::<f64>();
            }
        }
    )*};
}

for_each_type!(
    split_square,
    quad_on_centre_lines,
    fan_around_a_centre,
    constant_gouraud,
    whole_pixel_translation
);

/// A user's own colour type: `From<Rgb888>` plus an empty `impl TargetColor` is enough.
#[derive(Copy, Clone, PartialEq, Eq, Debug)]
struct Rgb332(u8);
impl PixelColor for Rgb332 {
    type Raw = embedded_graphics::pixelcolor::raw::RawU8;
}
impl From<Rgb888> for Rgb332 {
    fn from(c: Rgb888) -> Self {
        Rgb332((c.r() & 0xe0) | ((c.g() >> 3) & 0x1c) | (c.b() >> 6))
    }
}
impl TargetColor for Rgb332 {}

#[test]
fn custom_colour_type_through_rgb888() {
    let pos = [
        at::<f32>(W, H, 1.0, 1.0, 0.0),
        at(W, H, 1.0, 15.0, 0.0),
        at(W, H, 15.0, 8.0, 0.0),
    ];
    let idx = [[0u16, 1, 2]];
    let objects = [Object {
        mesh: Mesh::new(&pos, &idx).unwrap(),
        transform: Mat4::identity(),
        material: unlit([255, 128, 255], Shading::Flat),
    }];
    let scene = Scene::new(
        &objects,
        screen_camera::<f32>(H),
        [Light::white([0.0, 0.0, 1.0])],
    );
    let mut r = Renderer::<f32, Rgb332, 16, 16, 8, 8, 4>::new();
    let mut f = common::Frame::new(W, H, Rgb332(0));
    let stats = r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    let want = Rgb332::from(Rgb888::new(255, 128, 255));
    assert_eq!(
        f.px.iter().filter(|&&c| c == want).count(),
        stats.pixels_written as usize
    );
    assert!(stats.pixels_written > 40);
}
