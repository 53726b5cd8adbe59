//! Decodes fuzzer bytes into a scene and renders it with every number type. Shared by the fuzz
//! target (`fuzz_targets/render.rs`) and the host regression test
//! (`tests/fuzz_regressions.rs`), which replays the committed corpus and crash inputs.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::Pixel;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{color::TriangleId, TargetColor};
use scanline3d_support::hash::HashTarget;

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    fn f32(&mut self) -> f32 {
        f32::from_bits(u32::from_le_bytes([
            self.u8(),
            self.u8(),
            self.u8(),
            self.u8(),
        ]))
    }
    fn v3(&mut self) -> [f32; 3] {
        [self.f32(), self.f32(), self.f32()]
    }
}

fn render<S: Scalar>(data: &[u8]) {
    let mut b = Bytes(data);
    let n = (b.u8() % 16) as usize + 1;
    let t = (b.u8() % 24) as usize + 1;
    let pos: Vec<[S; 3]> = (0..n).map(|_| b.v3().map(S::from_f32)).collect();
    let nor: Vec<[S; 3]> = (0..n).map(|_| b.v3().map(S::from_f32)).collect();
    let idx: Vec<[u16; 3]> = (0..t)
        .map(|_| [b.u16() % 20, b.u16() % 20, b.u16() % 20])
        .collect();
    let eye = b.v3().map(S::from_f32);
    let target = b.v3().map(S::from_f32);
    let up = b.v3().map(S::from_f32);
    let opts = b.u8();
    let projection = if opts & 1 == 0 {
        Projection::Perspective {
            fov_y: S::from_f32(b.f32()),
            near: S::from_f32(b.f32()),
            far: S::from_f32(b.f32()),
        }
    } else {
        Projection::Orthographic {
            height: S::from_f32(b.f32()),
            near: S::from_f32(b.f32()),
            far: S::from_f32(b.f32()),
        }
    };
    let Ok(camera) = Camera::look_at(eye, target, up, projection) else {
        return;
    };
    let mut material = Material::matte(
        [b.u8(), b.u8(), b.u8()],
        S::from_f32(b.f32()),
        S::from_f32(b.f32()),
    );
    material.specular = S::from_f32(b.f32());
    material.shininess = b.u8();
    material.shading = if opts & 2 == 0 {
        Shading::Gouraud
    } else {
        Shading::Flat
    };
    let rot = b.v3().map(S::from_f32);
    let transform = Mat4::rotate_x(rot[0])
        .then(&Mat4::rotate_y(rot[1]))
        .then(&Mat4::scale([rot[2]; 3]));
    let Ok(mesh) = Mesh::new(&pos, &idx) else {
        return;
    };
    let Ok(mesh) = mesh.with_normals(&nor) else {
        return;
    };
    let objects = [Object {
        mesh,
        transform,
        material,
    }];
    let scene = Scene::new(
        &objects,
        camera,
        [Light {
            direction: b.v3().map(S::from_f32),
            color: [b.u8(), b.u8(), b.u8()],
        }],
    );
    let mut r = Box::new(Renderer::<S, Rgb565, 40, 32, 128, 64, 32, 3>::new());
    r.set_dither(opts & 4 != 0);
    r.set_depth_test(match (opts >> 3) & 3 {
        0 => DepthTest::Less,
        1 => DepthTest::LessEqual,
        2 => DepthTest::Equal,
        _ => DepthTest::Always,
    });
    let mut h = HashTarget::<Rgb565>::new(40, 32);
    let _ = r.render(&scene, &mut h);
    // The colour-range invariant on the same geometry and camera, with vertex colours taken
    // from the normals' bytes.
    let cols: Vec<[u8; 3]> = nor_bytes(&nor);
    if let Err(v) = colour_range_violation(&pos, &idx, &cols, camera, opts & 4 != 0) {
        panic!("{v}");
    }
}

/// Vertex colours from normals (their components' magnitudes scaled to bytes).
fn nor_bytes<S: Scalar>(nor: &[[S; 3]]) -> Vec<[u8; 3]> {
    nor.iter()
        .map(|n| n.map(|c| (c.to_f64().abs().min(1.0) * 255.0) as u8))
        .collect()
}

/// A frame in memory for the invariant's two renders.
struct Buf<C> {
    px: Vec<C>,
}

impl<C: TargetColor> OriginDimensions for Buf<C> {
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl<C: TargetColor> DrawTarget for Buf<C> {
    type Color = C;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if (0..W as i32).contains(&p.x) && (0..H as i32).contains(&p.y) {
                self.px[p.y as usize * W + p.x as usize] = c;
            }
        }
        Ok(())
    }
}

const W: usize = 40;
const H: usize = 32;

/// The issue #20 invariant: every pixel's colour lies within the range of its triangle's
/// vertex colours, per RGB565 channel, ±1 LSB. The scene is lit so that each vertex's colour
/// is known: a white material (ambient 0, diffuse 1, Gouraud) under three lights along the
/// axes, red, green and blue, lights a vertex with normal `(r, g, b)/255` (identity transform,
/// so the normal is not rotated) to `(r, g, b)`. A second render into [`TriangleId`] says
/// which triangle each pixel shows; clipped triangles keep their id and interpolate within the
/// same range. Returns the number of pixels checked (0 where the mesh or the render is
/// refused: an error is a defined result), or the first violation, described.
pub fn colour_range_violation<S: Scalar>(
    pos: &[[S; 3]],
    idx: &[[u16; 3]],
    cols: &[[u8; 3]],
    camera: Camera<S>,
    dither: bool,
) -> Result<usize, String> {
    let nor: Vec<[S; 3]> = cols
        .iter()
        .map(|c| c.map(|v| S::from_f64(v as f64 / 255.0)))
        .collect();
    let Some(mesh) = Mesh::new(pos, idx)
        .ok()
        .and_then(|m| m.with_normals(&nor).ok())
    else {
        return Ok(0);
    };
    let objects = [Object {
        mesh,
        transform: Mat4::identity(),
        material: Material {
            color: [255; 3],
            ambient: S::from_f64(0.0),
            diffuse: S::from_f64(1.0),
            specular: S::from_f64(0.0),
            shininess: 1,
            shading: Shading::Gouraud,
            texture: None,
            alpha: 255,
        },
    }];
    let axis = |k: usize| {
        let mut d = [S::from_f64(0.0); 3];
        d[k] = S::from_f64(1.0);
        let mut c = [0u8; 3];
        c[k] = 255;
        Light {
            direction: d,
            color: c,
        }
    };
    let scene = Scene::new(&objects, camera, [axis(0), axis(1), axis(2)]);
    let mut colours = Buf {
        px: vec![Rgb565::BLACK; W * H],
    };
    let mut r = Box::new(Renderer::<S, Rgb565, W, H, 128, 64, 32, 3>::new());
    r.set_dither(dither);
    if r.render(&scene, &mut colours).is_err() {
        return Ok(0);
    }
    let mut ids = Buf {
        px: vec![TriangleId(0); W * H],
    };
    let mut r = Box::new(Renderer::<S, TriangleId, W, H, 128, 64, 32, 3>::new());
    if r.render(&scene, &mut ids).is_err() {
        return Ok(0);
    }
    let mut checked = 0;
    for (i, (&c, &id)) in colours.px.iter().zip(&ids.px).enumerate() {
        let Some(t) = (id.0 as usize).checked_sub(1).and_then(|t| idx.get(t)) else {
            continue;
        };
        checked += 1;
        let got = [c.r(), c.g(), c.b()];
        for (k, max) in [31u8, 63, 31].into_iter().enumerate() {
            let unit = |v: u8| v as f64 * max as f64 / 255.0;
            let vs = t.map(|v| unit(cols[v as usize][k]));
            let lo = vs.iter().cloned().fold(f64::MAX, f64::min).floor() - 1.0;
            let hi = vs.iter().cloned().fold(f64::MIN, f64::max).ceil() + 1.0;
            let g = got[k] as f64;
            if g < lo || g > hi {
                return Err(format!(
                    "pixel ({}, {}) of triangle {t:?}: channel {k} is {g}, outside {lo}..={hi} \
                     (vertex colours {:?})",
                    i % W,
                    i / W,
                    t.map(|v| cols[v as usize])
                ));
            }
        }
    }
    Ok(checked)
}

/// Renders the scene encoded in `data` with I16F16, f32 and f64.
pub fn render_all(data: &[u8]) {
    render::<Fx<I16F16>>(data);
    render::<f32>(data);
    render::<f64>(data);
}
