//! Host helpers (the `host` feature, with `std`) shared by the library's integration tests and
//! the host tools: a simulated display buffer that counts how often each pixel is written, PNG
//! encoding and the golden files (`tests/golden` of the repository), scenes placed in screen
//! coordinates, fixed point against float ([`compare`]) and the texture test scenes
//! ([`textures`]).
#![allow(missing_docs)]

pub mod compare;
pub mod raycast;
pub mod textures;

use std::path::PathBuf;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;

/// A simulated display: every pixel stored, every write counted.
pub struct Frame<C> {
    pub w: u32,
    pub h: u32,
    pub px: Vec<C>,
    pub writes: Vec<u32>,
}

impl<C: PixelColor> Frame<C> {
    pub fn new(w: u32, h: u32, fill: C) -> Self {
        Frame {
            w,
            h,
            px: vec![fill; (w * h) as usize],
            writes: vec![0; (w * h) as usize],
        }
    }

    pub fn get(&self, x: u32, y: u32) -> C {
        self.px[(y * self.w + x) as usize]
    }

    /// Panics unless every pixel was written exactly once.
    pub fn assert_each_written_once(&self) {
        for (i, &n) in self.writes.iter().enumerate() {
            assert_eq!(
                n,
                1,
                "pixel ({}, {}) written {n} times",
                i as u32 % self.w,
                i as u32 / self.w
            );
        }
    }
}

impl<C: PixelColor + Into<Rgb888>> Frame<C> {
    /// The pixels as packed 8-bit RGB bytes, row by row (embedded-graphics' rounding
    /// conversion from the frame's colour type).
    pub fn rgb888_bytes(&self) -> Vec<u8> {
        self.px
            .iter()
            .flat_map(|&c| {
                let c: Rgb888 = c.into();
                [c.r(), c.g(), c.b()]
            })
            .collect()
    }
}

impl<C: PixelColor> OriginDimensions for Frame<C> {
    fn size(&self) -> Size {
        Size::new(self.w, self.h)
    }
}

impl<C: PixelColor> DrawTarget for Frame<C> {
    type Color = C;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.w && (p.y as u32) < self.h {
                let i = (p.y as u32 * self.w + p.x as u32) as usize;
                self.px[i] = c;
                self.writes[i] += 1;
            }
        }
        Ok(())
    }
}

pub fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/golden")
}

/// Encodes a frame as 8-bit RGB PNG (RGB565 expanded by embedded-graphics' rounding conversion).
pub fn png_bytes<C: PixelColor + Into<Rgb888>>(f: &Frame<C>) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, f.w, f.h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().unwrap();
        w.write_image_data(&f.rgb888_bytes()).unwrap();
    }
    out
}

/// Decodes an 8-bit RGB PNG into (width, height, rgb bytes).
pub fn read_png(path: &std::path::Path) -> Option<(u32, u32, Vec<u8>)> {
    let file = std::fs::File::open(path).ok()?;
    let dec = png::Decoder::new(file);
    let mut r = dec.read_info().ok()?;
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).ok()?;
    buf.truncate(info.buffer_size());
    Some((info.width, info.height, buf))
}

/// Compares a frame with `tests/golden/<name>.png` pixel for pixel. With `UPDATE_GOLDEN=1` the
/// golden file is (re)written instead; a missing golden file is an error, never a silent pass.
pub fn check_golden<C: PixelColor + Into<Rgb888>>(name: &str, f: &Frame<C>) {
    let path = golden_dir().join(format!("{name}.png"));
    let bytes = png_bytes(f);
    if std::env::var("UPDATE_GOLDEN").is_ok() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        std::fs::write(&path, &bytes).unwrap();
        return;
    }
    let (w, h, want) = read_png(&path).unwrap_or_else(|| {
        panic!(
            "missing golden image {} (run with UPDATE_GOLDEN=1 and look at it)",
            path.display()
        )
    });
    assert_eq!((w, h), (f.w, f.h), "{name}: size");
    let got = f.rgb888_bytes();
    let diff = got
        .chunks(3)
        .zip(want.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    if diff != 0 {
        let out =
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("target/{name}.actual.png"));
        std::fs::write(&out, &bytes).unwrap();
        panic!(
            "{name}: {diff} pixels differ from the golden image; actual written to {}",
            out.display()
        );
    }
}

/// Per-channel comparison of two RGB565 frames: (max |Δ| in LSB per channel, pixels differing,
/// coverage mismatches against the background).
pub fn compare565(a: &Frame<Rgb565>, b: &Frame<Rgb565>, bg: Rgb565) -> ([u8; 3], usize, usize) {
    let mut max = [0u8; 3];
    let mut differ = 0;
    let mut coverage = 0;
    for (x, y) in a.px.iter().zip(b.px.iter()) {
        if x != y {
            differ += 1;
        }
        if (*x == bg) != (*y == bg) {
            coverage += 1;
            continue;
        }
        max[0] = max[0].max(x.r().abs_diff(y.r()));
        max[1] = max[1].max(x.g().abs_diff(y.g()));
        max[2] = max[2].max(x.b().abs_diff(y.b()));
    }
    (max, differ, coverage)
}

/// An orthographic camera that maps world (x, y) to screen pixels: world x = px − w/2,
/// world y = h/2 − py, looking down −Z from z = 10 with near 1 and far 19 (so world z = 0 has
/// depth 0.5).
pub fn screen_camera<S: Scalar>(h: u32) -> Camera<S> {
    Camera::look_at(
        [S::ZERO, S::ZERO, S::from_f64(10.0)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Orthographic {
            height: S::from_f64(h as f64),
            near: S::ONE,
            far: S::from_f64(19.0),
        },
    )
    .unwrap()
}

/// An orthographic camera at `eye` looking at the origin with `up` up, 1 world unit = 8 px on a
/// frame `h` pixels high, near 1 and far `far` (`tests/edges.rs`, `tests/volumes.rs`).
pub fn ortho8<S: Scalar>(eye: [f64; 3], up: [f64; 3], h: u32, far: f64) -> Camera<S> {
    Camera::look_at(
        eye.map(S::from_f64),
        [S::ZERO; 3],
        up.map(S::from_f64),
        Projection::Orthographic {
            height: S::from_f64(h as f64 / 8.0),
            near: S::ONE,
            far: S::from_f64(far),
        },
    )
    .unwrap()
}

/// World position of screen point (sx, sy) (in pixels, y down) at world depth z, for a
/// `screen_camera(h)` on a `w`-wide screen.
pub fn at<S: Scalar>(w: u32, h: u32, sx: f64, sy: f64, z: f64) -> [S; 3] {
    [
        S::from_f64(sx - w as f64 / 2.0),
        S::from_f64(h as f64 / 2.0 - sy),
        S::from_f64(z),
    ]
}

/// A material that shows exactly `color` whatever the normal: ambient 1, no diffuse.
pub fn unlit<S: Scalar>(color: [u8; 3], shading: Shading) -> Material<S> {
    Material {
        color,
        ambient: S::ONE,
        diffuse: S::ZERO,
        specular: S::ZERO,
        shininess: 1,
        shading,
        texture: None,
        alpha: 255,
    }
}

/// A probe that imposes the vertices' snapped positions (subpixels), by vertex index: the
/// reference-rasterizer tests draw triangles exactly on the grid they choose.
pub struct Snap<'a>(pub &'a [[i32; 2]]);

impl scanline3d::probe::Probe for Snap<'_> {
    fn enter(&mut self, _: scanline3d::probe::Stage) {}
    fn snap(&mut self, index: u32, x: i32, y: i32) -> (i32, i32) {
        self.0.get(index as usize).map_or((x, y), |q| (q[0], q[1]))
    }
}

/// The point of the unit sphere at the origin seen at the centre of pixel (x, y) of a
/// `size` × `size` view from (0, 0, `eye`) looking down −Z with vertical field of view `fov`
/// (radians), or `None` off the sphere.
pub fn ray_sphere(x: u32, y: u32, size: u32, fov: f64, eye: f64) -> Option<[f64; 3]> {
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / l)
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let th = (fov / 2.0).tan();
    let nx = ((x as f64 + 0.5) / size as f64 * 2.0 - 1.0) * th;
    let ny = (1.0 - (y as f64 + 0.5) / size as f64 * 2.0) * th;
    let d = unit([nx, ny, -1.0]);
    let o = [0.0, 0.0, eye];
    // |o + t·d| = 1.
    let b = dot(o, d);
    let disc = b * b - (dot(o, o) - 1.0);
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    Some([0, 1, 2].map(|k| o[k] + t * d[k]))
}
