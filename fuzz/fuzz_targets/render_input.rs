//! Decodes fuzzer bytes into a scene and renders it with every number type. Shared by the fuzz
//! target (`fuzz_targets/render.rs`) and the host regression test
//! (`tests/fuzz_regressions.rs`), which replays the committed corpus and crash inputs.

use embedded_graphics_core::pixelcolor::Rgb565;
use scanline3d::fixed::types::I16F16;
use scanline3d::hash::HashTarget;
use scanline3d::prelude::*;

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
}

/// Renders the scene encoded in `data` with I16F16, f32 and f64.
pub fn render_all(data: &[u8]) {
    render::<Fx<I16F16>>(data);
    render::<f32>(data);
    render::<f64>(data);
}
