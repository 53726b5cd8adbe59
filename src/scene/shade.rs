//! Lighting: ambient + Lambert diffuse + optional Phong specular, for directional lights.
//!
//! For each channel `c` (0..=255):
//!
//! `colour_c = material_c · (ambient + Σ diffuse · light_c/255 · max(0, N·L))
//!           + Σ specular · light_c · max(0, R·V)^shininess`, clamped to 0..=255,
//!
//! with `L` the unit direction toward the light, `R = 2(N·L)N − L` its mirror about the unit
//! normal `N`, and `V` the unit direction from the point toward the eye (a local viewer). No
//! gamma. Flat shading evaluates this once per face with the face normal, Gouraud once per
//! vertex with the vertex normal; Gouraud colours are then interpolated linearly in screen space.

use crate::num::math::{dot, normalize, scale, sub, Mat4, Vec3};
use crate::num::scalar::{channel_8_8, Scalar};
use crate::scene::texture::{Texture, TextureMode, Texturing};

/// How a surface is shaded.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Shading {
    /// One colour per face, from the face normal.
    Flat,
    /// Per-vertex lighting from vertex normals, interpolated across the face.
    #[default]
    Gouraud,
    /// Per-pixel lighting: the vertex normals interpolated across the face and lit at every
    /// pixel (the seeds' model, directional lights, up to [`crate::limits::MAX_PHONG_LIGHTS`]; the
    /// view direction is the object origin's, one per object). Needs the renderer's attribute
    /// stores, as a texture does ([`crate::Renderer`], "Textures"); not combined with a
    /// texture (the texture is not drawn).
    Phong,
    /// [`Shading::Phong`] lit at every 8th pixel of a span, the colour linear in between:
    /// most of Phong's highlights for additions per pixel.
    FastPhong,
    /// Toon (cel) shading: [`Shading::Phong`] with hard edges, per pixel. Each light's `N·L`
    /// on the lit side is rounded up to the next of `bands` equal steps (`⌈N·L·bands⌉/bands`,
    /// so the lit side shows `bands` flat tones and the side turned away the ambient colour),
    /// and the specular term is all or nothing (full where `max(0, R·V)^shininess ≥ ½`). With
    /// the renderer's dithering on, the colour is dithered into the target's channels as
    /// Gouraud colours are. Needs the attribute stores, as Phong does.
    Toon {
        /// Lit tones (1: one tone for the whole lit side).
        bands: core::num::NonZeroU8,
    },
}

impl Shading {
    /// Whether the shading lights per pixel ([`Shading::Phong`], [`Shading::FastPhong`],
    /// [`Shading::Toon`]).
    #[must_use]
    pub const fn is_phong(self) -> bool {
        matches!(
            self,
            Shading::Phong | Shading::FastPhong | Shading::Toon { .. }
        )
    }
}

/// A directional light.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Light<S> {
    /// Direction **toward** the light, world space; need not be unit length (it is normalized
    /// once per frame; a zero vector makes the light contribute nothing).
    pub direction: Vec3<S>,
    /// Light colour, 8 bits per channel (255 = full intensity).
    pub color: [u8; 3],
}

impl<S: Scalar> Light<S> {
    /// A white light toward `direction`.
    #[must_use]
    pub const fn white(direction: Vec3<S>) -> Self {
        Light {
            direction,
            color: [255; 3],
        }
    }

    /// A light that is switched off: black, with a zero direction. It lights nothing, so a
    /// scene keeps its number of lights `L` (a type parameter) while a light is off: a frame
    /// with `[sun, Light::off()]` has exactly the pixels of a frame with `[sun]` alone, for
    /// every number type. It costs what a lit light costs per lit vertex or face (a dot
    /// product; the per-pixel work does not depend on the lights). To switch off a light but
    /// keep its direction, use [`Light::switched_off`].
    #[must_use]
    pub const fn off() -> Self {
        Light {
            direction: [S::ZERO; 3],
            color: [0; 3],
        }
    }

    /// This light with its colour set to black, which switches it off (see [`Light::off`]);
    /// its direction is kept. Switch it back on by setting [`Light::color`] again.
    #[must_use]
    pub const fn switched_off(self) -> Self {
        Light {
            direction: self.direction,
            color: [0; 3],
        }
    }

    /// Whether the light is off (black): it contributes nothing to any colour.
    #[must_use]
    pub const fn is_off(&self) -> bool {
        matches!(self.color, [0, 0, 0])
    }
}

/// Surface properties.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Material<S> {
    /// Base colour, 8 bits per channel.
    pub color: [u8; 3],
    /// Ambient coefficient (typically 0..=1).
    pub ambient: S,
    /// Diffuse coefficient (typically 0..=1).
    pub diffuse: S,
    /// Specular coefficient; zero skips the specular term and its per-vertex cost.
    pub specular: S,
    /// Phong exponent.
    pub shininess: u8,
    /// Flat or Gouraud.
    pub shading: Shading,
    /// A texture that multiplies the lit colour ([`Material::textured`]); `None` for a plain
    /// colour. Drawing a textured material needs a renderer with attribute stores (its `XV`
    /// and `XA` capacities; see [`crate::Renderer`]).
    pub texture: Option<Texturing>,
    /// Opacity, 0..=255 (255, the default: opaque). A translucent material (below 255) is
    /// blended over what is behind it, `C = Csrc·α + Cdst·(1 − α)` with `α = alpha/255`, by
    /// [`crate::FrameOptions::layered`]; [`crate::Renderer::render`] refuses it
    /// ([`crate::Error::NeedsLayers`]).
    pub alpha: u8,
}

/// Building a material: start from [`Material::matte`] and chain the builder methods, e.g.
///
/// ```
/// # use scanline3d::prelude::*;
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// let shiny = Material::matte([90, 160, 255], Q::lit(0.1), Q::lit(0.7))
///     .flat()
///     .specular(Q::lit(0.5), 16);
/// assert_eq!(shiny.shading, Shading::Flat);
/// assert_eq!((shiny.specular, shiny.shininess), (Q::lit(0.5), 16));
/// ```
///
/// The builder methods are `const fn`, so a material can be a `const` or a `static`:
///
/// ```
/// # use scanline3d::prelude::*;
/// const RED: Material<f32> = Material::matte([255, 0, 0], 0.2, 0.8).specular(0.4, 8);
/// # assert_eq!(RED.shading, Shading::Gouraud);
/// ```
impl<S: Scalar> Material<S> {
    /// A matte material: the given colour, ambient and diffuse, no specular, Gouraud.
    #[must_use]
    pub const fn matte(color: [u8; 3], ambient: S, diffuse: S) -> Self {
        Material {
            color,
            ambient,
            diffuse,
            specular: S::ZERO,
            shininess: 1,
            shading: Shading::Gouraud,
            texture: None,
            alpha: 255,
        }
    }

    /// `color` exactly, whatever the lights: flat, ambient 1, no diffuse or specular term. In
    /// the background colour it hides what is behind it and shows nothing of itself — the
    /// surfaces of a wireframe with its hidden lines removed ([`crate::shadow::Outline`] with
    /// [`crate::shadow::Edges::All`]).
    #[must_use]
    pub const fn unlit(color: [u8; 3]) -> Self {
        Material::matte(color, S::ONE, S::ZERO).flat()
    }

    /// This material with [`Shading::Flat`]: one colour per face.
    #[must_use]
    pub const fn flat(self) -> Self {
        self.shading(Shading::Flat)
    }

    /// This material with [`Shading::Gouraud`] (the default of [`Material::matte`]).
    #[must_use]
    pub const fn gouraud(self) -> Self {
        self.shading(Shading::Gouraud)
    }

    /// This material with the given shading mode.
    #[must_use]
    pub const fn shading(self, shading: Shading) -> Self {
        Material { shading, ..self }
    }

    /// This material with `texture` ([`TextureMode::Subdivided16`], no colour key): each pixel
    /// is its texel times the lit colour / 255 (a white material shows the texels as they are
    /// under full light).
    #[must_use]
    pub const fn textured(self, texture: &'static Texture) -> Self {
        Material {
            texture: Some(Texturing::new(texture)),
            ..self
        }
    }

    /// This material with its texture's span mode set to `mode` (no effect without a texture).
    #[must_use]
    pub const fn texture_mode(self, mode: TextureMode) -> Self {
        match self.texture {
            Some(t) => Material {
                texture: Some(t.with_mode(mode)),
                ..self
            },
            None => self,
        }
    }

    /// This material with texels equal to `key` not drawn (no effect without a texture).
    #[must_use]
    pub const fn color_key(self, key: u16) -> Self {
        match self.texture {
            Some(t) => Material {
                texture: Some(t.with_key(Some(key))),
                ..self
            },
            None => self,
        }
    }

    /// This material with opacity `alpha` (0..=255; see [`Material::alpha`]).
    #[must_use]
    pub const fn translucent(self, alpha: u8) -> Self {
        Material { alpha, ..self }
    }

    /// This material with [`Shading::Phong`].
    #[must_use]
    pub const fn phong(self) -> Self {
        self.shading(Shading::Phong)
    }

    /// Whether drawing this material needs the renderer's attribute stores (a texture, or
    /// Phong shading).
    #[must_use]
    pub const fn needs_attribute_stores(&self) -> bool {
        self.texture.is_some() || self.shading.is_phong()
    }

    /// This material with a Phong specular term: coefficient `k` (zero, or below, removes the
    /// term and its per-vertex cost) and exponent `shininess`.
    #[must_use]
    pub const fn specular(self, k: S, shininess: u8) -> Self {
        Material {
            specular: k,
            shininess,
            ..self
        }
    }
}

/// A light prepared for one frame: unit direction and colour as fractions.
#[derive(Copy, Clone, Debug)]
pub(crate) struct PreparedLight<S> {
    dir: Vec3<S>,
    /// light_c / 255, step of `S`.
    frac: [S; 3],
    /// light_c (0..=255).
    full: [S; 3],
    /// Whether the three `frac` are equal (a grey light, white included): the diffuse term
    /// then takes one product instead of three, with the same values.
    grey: bool,
}

impl<S: Scalar> PreparedLight<S> {
    /// The light as seen in an object's space, for normals that are transformed by a normal
    /// matrix `n` with orthonormal columns: `(N·n)·l = n·(Nᵀ·l)`, so the per-vertex normal
    /// transform can go. `Nᵀ·l` is renormalized (the columns are unit length only to 2⁻¹⁰),
    /// by one Newton step for `1/|d|` from 1 (relative error about the square of 2⁻¹⁰, far
    /// below a Q16.16 step) — products only: a division's library call would be the deepest
    /// stack of a frame on a 16 KB part.
    pub(crate) fn in_object_space(&self, n: &Mat4<S>) -> Self {
        let col = |j: usize| [n.m[0][j], n.m[1][j], n.m[2][j]];
        let d = [0, 1, 2].map(|j| dot(col(j), self.dir));
        let r = (S::from_i32(3) - dot(d, d)) * S::from_f64(0.5);
        PreparedLight {
            dir: d.map(|v| v * r),
            ..*self
        }
    }

    /// The unit direction toward the light.
    pub(crate) fn dir(&self) -> Vec3<S> {
        self.dir
    }

    /// The direction and colour fraction of a grey light (equal channels), else `None`.
    pub(crate) fn grey(&self) -> Option<(Vec3<S>, S)> {
        self.grey.then_some((self.dir, self.frac[0]))
    }

    /// A grey light with the given direction (as it is, not normalized) and colour fraction,
    /// for the lighting routine's self-test.
    pub(crate) fn grey_raw(dir: Vec3<S>, frac: S) -> Self {
        PreparedLight {
            dir,
            frac: [frac; 3],
            full: [S::from_i32(255); 3],
            grey: true,
        }
    }

    /// A light toward unit direction `dir` with colour `color` scaled by `att` (a point
    /// light at one point, [`crate::PointLight`]).
    pub(crate) fn scaled(dir: Vec3<S>, color: [u8; 3], att: S) -> Self {
        let k = S::from_f64(1.0 / 255.0) * att;
        let c = |i: usize| S::from_i32(color[i] as i32);
        let [r, g, b] = color;
        PreparedLight {
            dir,
            frac: [c(0) * k, c(1) * k, c(2) * k],
            full: [c(0) * att, c(1) * att, c(2) * att],
            grey: r == g && g == b,
        }
    }

    /// Channel `k`'s colour fraction (`light/255`, times the attenuation of a point light).
    #[cfg(test)]
    pub(crate) fn frac_of(&self, k: usize) -> S {
        self.frac[k]
    }

    /// Directional light `l`: its unit direction and full colour (a product by one is exact
    /// in every number type).
    pub(crate) fn new(l: &Light<S>) -> Self {
        Self::scaled(normalize(l.direction), l.color, S::ONE)
    }
}

fn powi<S: Scalar>(mut b: S, mut e: u8) -> S {
    let mut r = S::ONE;
    while e > 0 {
        if e & 1 == 1 {
            r = r * b;
        }
        b = b * b;
        e >>= 1;
    }
    r
}

/// The lit colour of a point with unit normal `n` (world space), as 8.8 fixed point per channel
/// (0..=65280). `to_eye` is the unit direction toward the eye; it is only read when the material
/// has a specular term.
pub(crate) fn lit_color<S: Scalar>(
    m: &Material<S>,
    lights: &[PreparedLight<S>],
    n: Vec3<S>,
    to_eye: Vec3<S>,
) -> [u16; 3] {
    let mut sums = ([m.ambient; 3], [S::ZERO; 3]);
    for l in lights {
        add_light(&mut sums, m, l, n, to_eye);
    }
    finish(m, sums)
}

/// The (diffuse coefficient, specular) sums of [`lit_color`].
pub(crate) type Sums<S> = ([S; 3], [S; 3]);

/// Adds light `l`'s diffuse and specular terms for unit normal `n` to `sums`.
#[inline(always)]
pub(crate) fn add_light<S: Scalar>(
    sums: &mut Sums<S>,
    m: &Material<S>,
    l: &PreparedLight<S>,
    n: Vec3<S>,
    to_eye: Vec3<S>,
) {
    let two = S::ONE + S::ONE;
    let ndl = dot(n, l.dir);
    add_diffuse(&mut sums.0, m, l, ndl);
    if m.specular > S::ZERO {
        // R·V = 2(N·L)(N·V) − L·V.
        let r = sub(scale(n, two * ndl), l.dir);
        let rv = dot(r, to_eye);
        if rv > S::ZERO && ndl > S::ZERO {
            let p = m.specular * powi(rv, m.shininess);
            for c in 0..3 {
                sums.1[c] = sums.1[c] + p * l.full[c];
            }
        }
    }
}

/// The lit colour from the sums of [`add_light`], 8.8 per channel.
#[inline(always)]
pub(crate) fn finish<S: Scalar>(m: &Material<S>, (diffuse, spec): Sums<S>) -> [u16; 3] {
    let mut out = [0u16; 3];
    for c in 0..3 {
        out[c] = channel_8_8(diffuse[c].mul_int(m.color[c] as i32) + spec[c]);
    }
    out
}

/// [`lit_color`] for a material without a specular term (`m.specular ≤ 0`): the same values,
/// without the specular sums (fewer live values: on a Cortex-M0 the general version keeps
/// them on the stack).
pub(crate) fn lit_diffuse<S: Scalar>(
    m: &Material<S>,
    lights: &[PreparedLight<S>],
    n: Vec3<S>,
) -> [u16; 3] {
    let mut diffuse = [m.ambient; 3];
    for l in lights {
        add_diffuse(&mut diffuse, m, l, dot(n, l.dir));
    }
    let mut out = [0u16; 3];
    for c in 0..3 {
        // `lit_color` adds a zero specular sum here, which changes nothing.
        out[c] = diffuse[c].lit_channel(m.color[c]);
    }
    out
}

/// Adds light `l`'s diffuse term for `ndl = N·L` (nothing when it is not positive).
#[inline(always)]
fn add_diffuse<S: Scalar>(diffuse: &mut [S; 3], m: &Material<S>, l: &PreparedLight<S>, ndl: S) {
    if ndl > S::ZERO {
        let d = m.diffuse * ndl;
        if l.grey {
            let v = d * l.frac[0];
            for c in diffuse.iter_mut() {
                *c = *c + v;
            }
        } else {
            for c in 0..3 {
                diffuse[c] = diffuse[c] + d * l.frac[c];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    fn lambert<S: Scalar>() {
        let m = Material::matte([200, 100, 50], S::from_f64(0.2), S::from_f64(0.8));
        let l = [PreparedLight::new(&Light::white([
            S::ZERO,
            S::ZERO,
            S::from_f64(5.0),
        ]))];
        let z = [S::ZERO; 3];
        // Facing the light: full.
        let c = lit_color(&m, &l, [S::ZERO, S::ZERO, S::ONE], z);
        assert_eq!(c.map(|v| (v + 128) >> 8), [200, 100, 50]);
        // Facing away: ambient only.
        let c = lit_color(&m, &l, [S::ZERO, S::ZERO, -S::ONE], z);
        assert_eq!(c.map(|v| (v + 128) >> 8), [40, 20, 10]);
        // 60°: 0.2 + 0.8·0.5 = 0.6.
        let h = S::from_f64(libm::sqrt(0.75));
        let c = lit_color(&m, &l, [h, S::ZERO, S::from_f64(0.5)], z);
        assert_eq!(c.map(|v| (v + 128) >> 8), [120, 60, 30]);
    }

    /// Lighting an object-space normal with the light brought into object space gives the
    /// colour of the world-space normal with the world light: to a tie's rounding for f64,
    /// to a few 2⁻⁸ of a channel unit for Q16.16 (both paths round; 2 measured), over a sphere
    /// of normals and a rotated object. A wrong light direction is off by thousands.
    fn object_space_matches_world<S: Scalar>(tol: u16) {
        let m = Material::matte([200, 150, 90], S::from_f64(0.15), S::from_f64(0.85));
        let l = [PreparedLight::new(&Light::white([
            S::from_f64(-1.0),
            S::from_f64(2.0),
            S::from_f64(1.5),
        ]))];
        let t = Mat4::rotate_x(S::from_f64(0.9))
            .then(&Mat4::rotate_y(S::from_f64(-2.3)))
            .then(&Mat4::rotate_z(S::from_f64(0.4)));
        let (nm, similar) = t.normal_matrix();
        assert!(similar, "{:?}", nm.m.map(|r| r.map(|v| v.to_f64())));
        let lo = [l[0].in_object_space(&nm)];
        let z = [S::ZERO; 3];
        let mut worst = 0;
        for i in 0..24 {
            for j in 0..12 {
                let (a, b) = (i as f64 * 0.2618, j as f64 * 0.2618 + 0.05);
                let n = [a.cos() * b.sin(), a.sin() * b.sin(), b.cos()].map(S::from_f64);
                let world = lit_color(&m, &l, nm.transform_dir(n), z);
                let object = lit_color(&m, &lo, n, z);
                for c in 0..3 {
                    worst = worst.max(world[c].abs_diff(object[c]));
                }
            }
        }
        assert!(
            worst <= tol,
            "largest difference {worst} (8.8 channel units)"
        );
    }

    #[test]
    fn lighting_in_object_space_matches_world_space() {
        object_space_matches_world::<f64>(1);
        object_space_matches_world::<Fx<I16F16>>(4);
    }

    #[test]
    fn lambert_for_every_type() {
        lambert::<f64>();
        lambert::<f32>();
        lambert::<Fx<I16F16>>();
    }

    #[test]
    fn specular_peaks_at_the_mirror_direction_and_clamps() {
        let mut m = Material::matte([100, 100, 100], 0.0f64, 0.5);
        m.specular = 1.0;
        m.shininess = 8;
        let l = [PreparedLight::new(&Light::white([0.0, 0.0, 1.0]))];
        let n = [0.0, 0.0, 1.0];
        let c = lit_color(&m, &l, n, [0.0, 0.0, 1.0]);
        assert_eq!(c, [255 << 8; 3]);
        let v = normalize([1.0, 0.0, 1.0]);
        let c = lit_color(&m, &l, n, v);
        // 50 + 255·(0.7071^8 = 0.0625) = 65.94
        assert_eq!((c[0] + 128) >> 8, 66);
    }

    #[test]
    fn material_builder_sets_the_fields_it_names() {
        type Q = Fx<I16F16>;
        let m = Material::matte([10, 20, 30], Q::lit(0.25), Q::lit(0.5))
            .flat()
            .specular(Q::lit(0.75), 12);
        assert_eq!(
            m,
            Material {
                color: [10, 20, 30],
                ambient: Q::lit(0.25),
                diffuse: Q::lit(0.5),
                specular: Q::lit(0.75),
                shininess: 12,
                shading: Shading::Flat,
                texture: None,
                alpha: 255,
            }
        );
        assert_eq!(m.gouraud().shading, Shading::Gouraud);
        assert_eq!(m.gouraud().shading(Shading::Flat), m);
        const M: Material<f32> = Material::matte([1, 2, 3], 0.5, 0.5).flat();
        assert_eq!(M.shading, Shading::Flat);
    }

    /// A switched-off light adds exactly nothing, whatever the normal, material and type.
    fn off_light_adds_nothing<S: Scalar>() {
        let sun = Light::white([-1.0, 2.0, 1.5].map(S::from_f64));
        let dim = Light {
            direction: [0.5, -1.0, 2.0].map(S::from_f64),
            color: [200, 120, 40],
        };
        assert!(Light::<S>::off().is_off() && dim.switched_off().is_off() && !dim.is_off());
        assert_eq!(dim.switched_off().direction, dim.direction);
        let one = [PreparedLight::new(&sun)];
        for off in [Light::off(), dim.switched_off()] {
            let two = [PreparedLight::new(&sun), PreparedLight::new(&off)];
            for spec in [0.0, 0.6] {
                let m = Material::matte([200, 150, 90], S::from_f64(0.15), S::from_f64(0.85))
                    .specular(S::from_f64(spec), 9);
                for i in 0..24 {
                    let a = i as f64 * 0.2618;
                    let n = [a.cos() * 0.6, a.sin() * 0.6, 0.8].map(S::from_f64);
                    let v = [0.0, a.sin() * 0.6, 0.8].map(S::from_f64);
                    assert_eq!(lit_color(&m, &one, n, v), lit_color(&m, &two, n, v));
                    assert_eq!(lit_diffuse(&m, &one, n), lit_diffuse(&m, &two, n));
                }
            }
        }
    }

    #[test]
    fn a_switched_off_light_adds_nothing() {
        off_light_adds_nothing::<f64>();
        off_light_adds_nothing::<f32>();
        off_light_adds_nothing::<Fx<I16F16>>();
    }

    #[test]
    fn coloured_light_tints_diffuse() {
        let m = Material::matte([255, 255, 255], 0.0f32, 1.0);
        let l = [PreparedLight::new(&Light {
            direction: [0.0, 1.0, 0.0],
            color: [255, 0, 128],
        })];
        let c = lit_color(&m, &l, [0.0, 1.0, 0.0], [0.0; 3]);
        assert_eq!(c.map(|v| (v + 128) >> 8), [255, 0, 128]);
    }
}
