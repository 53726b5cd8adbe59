//! The textured benchmark scenes' assets (`demo::Bench::Textured` and its variants): the
//! checkerboard texture in flash and the floor mesh.

use crate::scalar::Scalar;

/// The textured benchmark's 64 × 64 texture: a two-tone checkerboard of 8 × 8-texel squares
/// with a dark line along each square's top and left edge (the lines show a perspective
/// error as bent or broken lines).
pub static CHECKER_TEXELS: [u16; 64 * 64] = {
    let mut t = [0u16; 64 * 64];
    let mut i = 0;
    while i < 64 * 64 {
        let (x, y) = (i % 64, i / 64);
        let light = ((x / 8) + (y / 8)) % 2 == 0;
        t[i] = if x % 8 == 0 || y % 8 == 0 {
            0x2104 // dark grey (4, 8, 4)
        } else if light {
            0xffff
        } else {
            0xc618 // grey (24, 48, 24)
        };
        i += 1;
    }
    t
};

/// [`CHECKER_TEXELS`] as a texture (repeating).
pub static CHECKER: crate::Texture = match crate::Texture::new(&CHECKER_TEXELS, 64, 64) {
    Ok(t) => t,
    Err(_) => panic!("the checkerboard is 64 x 64"),
};

/// The textured benchmark's floor: x ∈ [−3, 3], z ∈ [−10, 4] at y = 0 (reaching behind the
/// eye, so it is clipped at the near plane), facing up, the checkerboard repeated 3 × 7 times.
pub(crate) struct Floor<S> {
    pub(crate) positions: [[S; 3]; 4],
    pub(crate) normals: [[S; 3]; 4],
    pub(crate) uvs: [[S; 2]; 4],
    pub(crate) indices: [[u16; 3]; 2],
}

impl<S: Scalar> Floor<S> {
    pub(crate) fn new() -> Self {
        let p = |x: f64, z: f64| [S::from_f64(x), S::ZERO, S::from_f64(z)];
        let uv = |x: f64, z: f64| [S::from_f64((x + 3.0) * 0.5), S::from_f64((4.0 - z) * 0.5)];
        Floor {
            positions: [p(-3.0, 4.0), p(3.0, 4.0), p(3.0, -10.0), p(-3.0, -10.0)],
            normals: [[S::ZERO, S::ONE, S::ZERO]; 4],
            uvs: [uv(-3.0, 4.0), uv(3.0, 4.0), uv(3.0, -10.0), uv(-3.0, -10.0)],
            indices: [[0, 1, 2], [0, 2, 3]],
        }
    }
}
