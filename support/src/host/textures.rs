//! Texture scenes and their exact reference (see `tests/textures.rs`).

use std::fmt;

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{Error, Texture, TextureMode, Wrap};

use super::Frame;

/// The floor scene's viewport.
pub const FLOOR_VIEW: (u32, u32) = (160, 120);
/// Texture size of [`coded_texture`].
pub const CODED: u32 = 32;

const EYE: [f64; 3] = [-0.5, 0.6, 0.8];
const TARGET: [f64; 3] = [0.6, 0.0, -1.5];
const FOV: f64 = 1.0;

/// A 32 × 32 texture whose texel (i, j) is red i, green j, blue 31: every texel its own colour.
pub fn coded_texture(s: Wrap, t: Wrap) -> &'static Texture {
    let texels: Vec<u16> = (0..CODED * CODED)
        .map(|k| (((k % CODED) << 11) | ((k / CODED) << 5) | 31) as u16)
        .collect();
    let texels: &'static [u16] = Box::leak(texels.into_boxed_slice());
    Box::leak(Box::new(
        Texture::new(texels, CODED, CODED).unwrap().with_wrap(s, t),
    ))
}

/// The floor: the quad x ∈ [−1, 1], z ∈ [−4, 0] at y = 0, facing up, with s = x + 1 and
/// t = −z (so s ∈ [0, 2], t ∈ [0, 4]).
pub struct Floor<S> {
    pub positions: [[S; 3]; 4],
    pub normals: [[S; 3]; 4],
    pub uvs: [[S; 2]; 4],
    pub indices: [[u16; 3]; 2],
}

impl<S: Scalar> Floor<S> {
    /// The mesh, with normals and texture coordinates.
    pub fn mesh(&self) -> Mesh<'_, S> {
        Mesh::new(&self.positions, &self.indices)
            .and_then(|m| m.with_normals(&self.normals))
            .and_then(|m| m.with_uvs(&self.uvs))
            .unwrap()
    }
}

pub fn floor<S: Scalar>() -> Floor<S> {
    floor_to::<S>(0.0)
}

/// The floor's near edge when it reaches behind the eye (crossing the near plane).
pub const BEHIND: f64 = 2.0;

/// The floor from z = −4 to `z_near` (0, or [`BEHIND`]).
pub fn floor_to<S: Scalar>(z_near: f64) -> Floor<S> {
    let p = |x: f64, z: f64| [S::from_f64(x), S::ZERO, S::from_f64(z)];
    let uv = |x: f64, z: f64| [S::from_f64(x + 1.0), S::from_f64(-z)];
    Floor {
        positions: [p(-1.0, z_near), p(1.0, z_near), p(1.0, -4.0), p(-1.0, -4.0)],
        normals: [[S::ZERO, S::ONE, S::ZERO]; 4],
        uvs: [
            uv(-1.0, z_near),
            uv(1.0, z_near),
            uv(1.0, -4.0),
            uv(-1.0, -4.0),
        ],
        indices: [[0, 1, 2], [0, 2, 3]],
    }
}

pub fn floor_camera<S: Scalar>() -> Camera<S> {
    let v = |p: [f64; 3]| p.map(S::from_f64);
    Camera::look_at(
        v(EYE),
        v(TARGET),
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: S::from_f64(FOV),
            near: S::from_f64(0.1),
            far: S::from_f64(10.0),
        },
    )
    .unwrap()
}

type TexRenderer<S> = Renderer<S, Rgb565, 160, 120, 64, 64, 16, 1, 64, 16>;

/// The floor with `tex` (unlit white material: the texels as they are) drawn in `mode`.
pub fn floor_scene<S: Scalar>(
    tex: &'static Texture,
    mode: TextureMode,
    key: Option<u16>,
) -> Frame<Rgb565> {
    floor_scene_to::<S>(tex, mode, key, 0.0)
}

/// [`floor_scene`] with the floor reaching to `z_near`.
pub fn floor_scene_to<S: Scalar>(
    tex: &'static Texture,
    mode: TextureMode,
    key: Option<u16>,
    z_near: f64,
) -> Frame<Rgb565> {
    let f = floor_to::<S>(z_near);
    let mesh = f.mesh();
    let mut material = Material::matte([255; 3], S::ONE, S::ZERO)
        .textured(tex)
        .texture_mode(mode);
    if let Some(k) = key {
        material = material.color_key(k);
    }
    let objects = [Object {
        mesh,
        transform: Mat4::identity(),
        material,
    }];
    let scene = Scene::new(
        &objects,
        floor_camera(),
        [Light::white([S::ZERO, S::ONE, S::ZERO])],
    );
    let mut r: Box<TexRenderer<S>> = Box::default();
    let (w, h) = FLOOR_VIEW;
    let mut frame = Frame::new(w, h, Rgb565::BLACK);
    r.render(&scene, &mut frame).unwrap();
    frame.assert_each_written_once();
    frame
}

/// The floor drawn by a renderer without attribute stores: its error.
pub fn render_without_stores<S: Scalar>(
    tex: &'static Texture,
) -> Option<Error<core::convert::Infallible>> {
    let f = floor::<S>();
    let mesh = f.mesh();
    let objects = [Object {
        mesh,
        transform: Mat4::identity(),
        material: Material::matte([255; 3], S::ONE, S::ZERO).textured(tex),
    }];
    let scene = Scene::new(
        &objects,
        floor_camera(),
        [Light::white([S::ZERO, S::ONE, S::ZERO])],
    );
    let mut r: Box<Renderer<S, Rgb565, 160, 120, 64, 64, 16>> = Box::default();
    let mut frame = Frame::new(160, 120, Rgb565::BLACK);
    r.render(&scene, &mut frame).err()
}

/// The exact texture coordinate (s, t) at the centre of pixel (x, y), or `None` off the floor.
pub fn exact_st(x: u32, y: u32, z_near: f64) -> Option<[f64; 2]> {
    let (w, h) = FLOOR_VIEW;
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let norm = |a: [f64; 3]| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        a.map(|v| v / l)
    };
    let f = norm(sub(TARGET, EYE));
    let r = norm(cross(f, [0.0, 1.0, 0.0]));
    let u = cross(r, f);
    let th = (FOV / 2.0).tan();
    let nx = (x as f64 + 0.5) / w as f64 * 2.0 - 1.0;
    let ny = 1.0 - (y as f64 + 0.5) / h as f64 * 2.0;
    let a = w as f64 / h as f64;
    let d: [f64; 3] = [0, 1, 2].map(|k| f[k] + nx * th * a * r[k] + ny * th * u[k]);
    if d[1] >= 0.0 {
        return None;
    }
    let k = -EYE[1] / d[1];
    let p = [EYE[0] + k * d[0], EYE[2] + k * d[2]];
    if p[0].abs() > 1.0 || p[1] > z_near || p[1] < -4.0 {
        return None;
    }
    Some([p[0] + 1.0, -p[1]])
}

/// The error figures of one rendering of the floor with [`coded_texture`].
#[derive(Clone, Debug, Default)]
pub struct TexError {
    /// Pixels showing a texel.
    pub drawn: u32,
    /// Of those, pixels whose exact texture coordinate lies in the texel drawn.
    pub exact: u32,
    /// Pixels neither background nor a texel of the coded texture.
    pub foreign: u32,
    /// Largest distance (texels) from the exact coordinate to the drawn texel's square.
    pub worst: f64,
    /// Mean of that distance over the drawn pixels.
    pub mean: f64,
}

impl fmt::Display for TexError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} px, {:.1} % exact texel, worst {:.3} texel, mean {:.4} texel",
            self.drawn,
            100.0 * self.exact as f64 / self.drawn.max(1) as f64,
            self.worst,
            self.mean
        )
    }
}

/// Circular distance from `u` (texels) to the texel interval [i, i+1) of a `n`-texel axis.
fn wrap_distance(u: f64, i: u32, n: u32) -> f64 {
    let x = (u - i as f64).rem_euclid(n as f64);
    if x < 1.0 {
        0.0
    } else {
        (x - 1.0).min(n as f64 - x)
    }
}

/// Renders the floor with `tex` (a [`coded_texture`]) in `mode` and measures every drawn pixel
/// whose centre's ray meets the floor.
pub fn floor_error<S: Scalar>(tex: &'static Texture, mode: TextureMode) -> TexError {
    let frame = floor_scene::<S>(tex, mode, None);
    measure_coded(&frame, 0.0)
}

/// [`floor_error`] with the floor reaching behind the eye: clipped at the near plane, so the
/// clipped vertices' texture coordinates are measured too.
pub fn clipped_floor_error<S: Scalar>(tex: &'static Texture, mode: TextureMode) -> TexError {
    let frame = floor_scene_to::<S>(tex, mode, None, BEHIND);
    measure_coded(&frame, BEHIND)
}

pub fn measure_coded(frame: &Frame<Rgb565>, z_near: f64) -> TexError {
    let (w, h) = FLOOR_VIEW;
    let mut e = TexError::default();
    let mut sum = 0.0;
    for y in 0..h {
        for x in 0..w {
            let c = frame.get(x, y);
            if c == Rgb565::BLACK {
                continue;
            }
            let raw = RawU16::from(c).into_inner();
            if raw & 31 != 31 || (raw >> 5) & 63 >= CODED as u16 {
                e.foreign += 1;
                continue;
            }
            let (i, j) = ((raw >> 11) as u32, ((raw >> 5) & 63) as u32);
            let Some([s, t]) = exact_st(x, y, z_near) else {
                continue;
            };
            let n = CODED as f64;
            let d = wrap_distance(s * n, i, CODED).max(wrap_distance(t * n, j, CODED));
            e.drawn += 1;
            e.exact += (d == 0.0) as u32;
            e.worst = e.worst.max(d);
            sum += d;
        }
    }
    e.mean = sum / e.drawn.max(1) as f64;
    e
}
