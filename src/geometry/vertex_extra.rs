//! A vertex's attributes beyond its screen record ([`VertexExtra`], the attribute store's
//! entry, indexed as the vertex store): a textured vertex's texture coordinates and mode, a
//! Phong vertex's normal and position. The geometry stage writes them (`attrs`), the
//! rasterizer's setup reads them.

use crate::scene::texture::{Texture, TextureMode, Texturing};

/// A vertex's texture attributes, indexed as the vertex store.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct VertexExtra {
    /// `(s, t)`, signed Q16.16 texture units (|·| < 16, step 2⁻¹⁶).
    pub(crate) st: [i32; 2],
    /// `near/w` from the vertex's depth, unsigned Q0.24 (0..=2²⁴, step 2⁻²⁴; 2²⁴ at the near
    /// plane and in orthographic projection).
    pub(crate) q: u32,
    /// The texture (`None`: the vertex is not textured).
    pub(crate) texture: Option<&'static Texture>,
    /// The colour key, and whether there is one.
    pub(crate) key: u16,
    pub(crate) has_key: bool,
    /// [`TextureMode`] as its index.
    pub(crate) mode: u8,
}

impl VertexExtra {
    pub(crate) const NONE: VertexExtra = VertexExtra {
        st: [0; 2],
        q: 0,
        texture: None,
        key: 0,
        has_key: false,
        mode: 0,
    };

    /// The attributes of a vertex of a Phong object: its unit normal (world space, Q1.14)
    /// and its position less the eye's (world space, 2^-bits units, `effects::position_bits`),
    /// packed as six `i16` in `st` and `q`; the pool entry of its object's material, and its
    /// lighting mode ([`lit_mode`](crate::geometry::pool::lit_mode)).
    pub(crate) fn phong(n: [i32; 3], pos: [i32; 3], material: u16, mode: u8) -> Self {
        let h = |v: i32| (v.clamp(-32768, 32767) as u16) as u32;
        VertexExtra {
            st: [
                (h(n[0]) | h(n[1]) << 16) as i32,
                (h(n[2]) | h(pos[0]) << 16) as i32,
            ],
            q: h(pos[1]) | h(pos[2]) << 16,
            texture: None,
            key: material,
            has_key: false,
            mode,
        }
    }

    /// A Phong vertex's normal and position ([`VertexExtra::phong`]).
    pub(crate) fn phong_attributes(&self) -> ([i32; 3], [i32; 3]) {
        let lo = |v: u32| v as u16 as i16 as i32;
        let hi = |v: u32| (v >> 16) as u16 as i16 as i32;
        let (a, b) = (self.st[0] as u32, self.st[1] as u32);
        ([lo(a), hi(a), lo(b)], [hi(b), lo(self.q), hi(self.q)])
    }

    /// The attributes of a vertex of an object textured by `map`.
    pub(crate) fn new(map: &Texturing, st: [i32; 2], q: u32) -> Self {
        VertexExtra {
            st,
            q,
            texture: Some(map.texture()),
            key: map.key().unwrap_or(0),
            has_key: map.key().is_some(),
            mode: mode_index(map.mode()),
        }
    }
}

fn mode_index(m: TextureMode) -> u8 {
    match m {
        TextureMode::PerPixel => 0,
        TextureMode::Subdivided16 => 1,
        TextureMode::Subdivided8 => 2,
        TextureMode::Affine => 3,
    }
}

pub(crate) fn mode_of(i: u8) -> TextureMode {
    match i {
        0 => TextureMode::PerPixel,
        1 => TextureMode::Subdivided16,
        2 => TextureMode::Subdivided8,
        _ => TextureMode::Affine,
    }
}

/// `near/w` in Q0.24 of a vertex with depth `depth` (unsigned 16.8, [`ScreenVertex::depth`](crate::geometry::project::ScreenVertex::depth)
/// without its 4 extra bits) for the perspective constant `k = 1 − near/far` in Q0.24
/// (0 for an orthographic projection): the depth is `d = (1 − near/w)/k` of the far plane's,
/// so `near/w = 1 − d·k`. Exact to a step of the depth.
pub(crate) fn q_from_depth(depth: u32, k24: u32) -> u32 {
    const D_MAX: u64 = 65535 << 8;
    let dk = (depth.min(D_MAX as u32) as u64 * k24 as u64 + D_MAX / 2) / D_MAX;
    ((1u64 << 24) - dk.min(1 << 24)) as u32
}
