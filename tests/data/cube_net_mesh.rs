// Baked by `cargo run --release -p scanline3d-tools --bin bake` from cube_net.obj. Do not edit.
//
// 14 vertices, 12 triangles, 520 bytes of flash.
// Positions are normalized: model = stored * SCALE + OFFSET (stored within ±1, Q16.16).
// Largest position error after baking: 5.2011477199485406e-6 model units.
// Texture coordinates (s, t) = (u, 1 - v) of the OBJ's vt (t down), Q16.16.

use scanline3d::fixed::types::I16F16;
use scanline3d::Fx;

const fn q(bits: i32) -> Fx<I16F16> {
    Fx(I16F16::from_bits(bits))
}

/// Multiply stored positions by this (model units) ...
pub const SCALE: f64 = 0.8660254037844386;
/// ... and add this to get model coordinates.
pub const OFFSET: [f64; 3] = [0.0, 0.0, 0.0];
/// Bounding box in model units (min, max).
pub const BOUNDING_BOX: ([f64; 3], [f64; 3]) = ([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]);
/// Bounding sphere in model units (centre, radius).
pub const BOUNDING_SPHERE: ([f64; 3], f64) = ([0.0, 0.0, 0.0], 0.8660254037844386);

/// Normalized positions, Q16.16.
pub static POSITIONS: [[Fx<I16F16>; 3]; 14] = [
    [q(-37837), q(-37837), q(37837)],
    [q(37837), q(-37837), q(37837)],
    [q(37837), q(37837), q(37837)],
    [q(-37837), q(37837), q(37837)],
    [q(37837), q(-37837), q(-37837)],
    [q(37837), q(37837), q(-37837)],
    [q(-37837), q(-37837), q(-37837)],
    [q(-37837), q(37837), q(-37837)],
    [q(-37837), q(-37837), q(-37837)],
    [q(-37837), q(37837), q(-37837)],
    [q(37837), q(37837), q(-37837)],
    [q(-37837), q(37837), q(-37837)],
    [q(-37837), q(-37837), q(-37837)],
    [q(37837), q(-37837), q(-37837)],
];

/// Unit vertex normals, Q16.16.
pub static NORMALS: [[Fx<I16F16>; 3]; 14] = [
    [q(-26755), q(-26755), q(53510)],
    [q(43691), q(-43691), q(21845)],
    [q(26755), q(26755), q(53510)],
    [q(-43691), q(43691), q(21845)],
    [q(26755), q(-26755), q(-53510)],
    [q(43691), q(43691), q(-21845)],
    [q(-43691), q(-43691), q(-21845)],
    [q(-26755), q(26755), q(-53510)],
    [q(-43691), q(-43691), q(-21845)],
    [q(-26755), q(26755), q(-53510)],
    [q(43691), q(43691), q(-21845)],
    [q(-26755), q(26755), q(-53510)],
    [q(-43691), q(-43691), q(-21845)],
    [q(26755), q(-26755), q(-53510)],
];

/// Counter-clockwise triangles.
pub static INDICES: [[u16; 3]; 12] = [
    [0, 1, 2],
    [0, 2, 3],
    [1, 4, 5],
    [1, 5, 2],
    [4, 6, 7],
    [4, 7, 5],
    [8, 0, 3],
    [8, 3, 9],
    [3, 2, 10],
    [3, 10, 11],
    [12, 13, 1],
    [12, 1, 0],
];

/// Texture coordinates (s, t), Q16.16: (0, 0) is the top-left corner of the image.
pub static UVS: [[Fx<I16F16>; 2]; 14] = [
    [q(16384), q(49152)],
    [q(32768), q(49152)],
    [q(32768), q(32768)],
    [q(16384), q(32768)],
    [q(49152), q(49152)],
    [q(49152), q(32768)],
    [q(65536), q(49152)],
    [q(65536), q(32768)],
    [q(0), q(49152)],
    [q(0), q(32768)],
    [q(32768), q(16384)],
    [q(16384), q(16384)],
    [q(16384), q(65536)],
    [q(32768), q(65536)],
];
