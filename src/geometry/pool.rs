//! The attribute stores' pool entry: the extra planes of an active textured or Phong
//! triangle, or a Phong payload (the frame's lights, an object's material), shared by
//! `textured` and `phong`.

use crate::scene::texture::Texture;

/// The extra planes of an active textured triangle: values at the centre of pixel `(px0,
/// py0)` and per-pixel gradients, all with 16 fraction bits and in wrapping 64-bit
/// arithmetic (exact modulo 2⁶⁴ up to the gradients' rounding, ½ of 2⁻¹⁶ per pixel).
/// `U`, `V`: texel offsets from the first vertex in units of 2^-`f` texel, times `Q`
/// (|U| < 2³⁰ at the vertices); `Q`: `near/w` normalized so that its largest vertex value is
/// in [2¹⁴, 2¹⁵) (or 2¹⁴ everywhere for [`crate::TextureMode::Affine`]).
///
/// `packed(4)`: 4-byte aligned on every target, so that an empty pool (`[ActiveExtra; 0]`)
/// does not change the renderer's alignment.
#[derive(Copy, Clone, Debug)]
#[repr(C, packed(4))]
pub(crate) struct ActiveExtra {
    pub(crate) val: [i64; 3],
    pub(crate) gx: [i64; 3],
    pub(crate) gy: [i64; 3],
    pub(crate) px0: i16,
    pub(crate) py0: i16,
    /// Texel coordinates of the first vertex, Q16.16 texels (a Phong triangle: the pool
    /// index of the frame's lights entry, −1 for none).
    pub(crate) base: [i32; 2],
    /// The lit colour of a flat triangle, channel units with [`COLOR_FRAC_BITS`](crate::raster::COLOR_FRAC_BITS).
    pub(crate) flat: [i32; 3],
    pub(crate) texture: Option<&'static Texture>,
    /// The colour key (a Phong triangle: the pool index of its material entry).
    pub(crate) key: u16,
    pub(crate) has_key: bool,
    /// [`VertexExtra::mode`](crate::geometry::vertex_extra::VertexExtra::mode).
    pub(crate) mode: u8,
    /// Fraction bits of `U`/`Q` and `V`/`Q` (0..=15).
    pub(crate) f: u8,
    /// What the entry holds: [`FREE`], a triangle's planes ([`TRI`]), or, in the plane
    /// words, a frame's Phong lights ([`LIGHTS`], `phong::PhongLights`) or an object's Phong
    /// material ([`MATERIAL`], `phong::PhongMaterial`).
    pub(crate) kind: u8,
}

/// [`ActiveExtra::kind`]: free.
pub(crate) const FREE: u8 = 0;
/// [`ActiveExtra::kind`]: an active triangle's planes.
pub(crate) const TRI: u8 = 1;
/// [`ActiveExtra::kind`]: the frame's Phong lights.
pub(crate) const LIGHTS: u8 = 2;
/// [`ActiveExtra::kind`]: an object's Phong material.
pub(crate) const MATERIAL: u8 = 3;

/// [`ActiveExtra::kind`]: the frame's fog for the spans (`fog::FogSpan`), always entry 0.
pub(crate) const FOG: u8 = 4;
/// [`ActiveExtra::kind`]: the frame's point lights for Phong spans (`phong::PhongPoints`),
/// right after the [`LIGHTS`] entry.
pub(crate) const POINTS: u8 = 5;

/// [`VertexExtra::mode`](crate::geometry::vertex_extra::VertexExtra::mode) of a vertex of a [`crate::Shading::Phong`] object (after the
/// texture modes' indices).
pub(crate) const MODE_PHONG: u8 = 4;
/// [`VertexExtra::mode`](crate::geometry::vertex_extra::VertexExtra::mode) of a vertex of a [`crate::Shading::FastPhong`] object.
pub(crate) const MODE_FAST_PHONG: u8 = 5;
/// [`VertexExtra::mode`](crate::geometry::vertex_extra::VertexExtra::mode) of a vertex of a [`crate::Shading::Toon`] object.
pub(crate) const MODE_TOON: u8 = 6;

/// [`VertexExtra::mode`](crate::geometry::vertex_extra::VertexExtra::mode) of a vertex of an object lit per pixel with `shading` (the pool kind
/// its triangles get, `kind::enter`); `None` for a shading lit per vertex or face.
pub(crate) fn lit_mode(shading: crate::Shading) -> Option<u8> {
    match shading {
        crate::Shading::Phong => Some(MODE_PHONG),
        crate::Shading::FastPhong => Some(MODE_FAST_PHONG),
        crate::Shading::Toon { .. } => Some(MODE_TOON),
        _ => None,
    }
}

impl ActiveExtra {
    pub(crate) const EMPTY: ActiveExtra = ActiveExtra {
        val: [0; 3],
        gx: [0; 3],
        gy: [0; 3],
        px0: 0,
        py0: 0,
        base: [0; 2],
        flat: [0; 3],
        texture: None,
        key: 0,
        has_key: false,
        mode: 0,
        f: 0,
        kind: FREE,
    };

    /// The nine plane words, for a payload.
    pub(crate) fn words(&self) -> [i64; 9] {
        let (v, x, y) = (self.val, self.gx, self.gy);
        [v[0], v[1], v[2], x[0], x[1], x[2], y[0], y[1], y[2]]
    }

    /// Stores a payload in the nine plane words.
    pub(crate) fn set_words(&mut self, w: [i64; 9]) {
        self.val = [w[0], w[1], w[2]];
        self.gx = [w[3], w[4], w[5]];
        self.gy = [w[6], w[7], w[8]];
    }

    /// Plane `j` (0..6) of a Phong triangle's entry, whose words hold six planes of 32 bits
    /// (the low halves planes 0..3, the high halves 3..6: [`ActiveExtra::set_planes32`]) at the
    /// centre of pixel `(x, y)`, in wrapping 32-bit arithmetic (16 fraction bits).
    #[inline]
    pub(crate) fn plane32(&self, j: usize, x: i32, y: i32) -> i32 {
        let (dx, dy) = (x - self.px0 as i32, y - self.py0 as i32);
        let h = |w: [i64; 3]| (w[j % 3] >> (32 * (j / 3))) as i32;
        let (val, gx, gy) = (self.val, self.gx, self.gy);
        h(val)
            .wrapping_add(h(gx).wrapping_mul(dx))
            .wrapping_add(h(gy).wrapping_mul(dy))
    }

    /// Plane `j`'s step per pixel along a row (see [`ActiveExtra::plane32`]).
    pub(crate) fn step32(&self, j: usize) -> i32 {
        let gx = self.gx;
        (gx[j % 3] >> (32 * (j / 3))) as i32
    }

    /// Packs the low 32 bits of the planes of `a` (planes 0..3) and `b` (planes 3..6) into
    /// this entry's words; `a`'s pixel origin (which `b`'s must equal).
    pub(crate) fn set_planes32(&mut self, a: &ActiveExtra, b: &ActiveExtra) {
        let pack =
            |x: [i64; 3], y: [i64; 3]| [0, 1, 2].map(|k| (x[k] as u32 as i64) | (y[k] << 32));
        let (av, ax, ay, bv, bx, by) = (a.val, a.gx, a.gy, b.val, b.gx, b.gy);
        self.val = pack(av, bv);
        self.gx = pack(ax, bx);
        self.gy = pack(ay, by);
        self.px0 = a.px0;
        self.py0 = a.py0;
        self.kind = a.kind;
    }
}
