//! The geometry stage's per-object state ([`ObjectSetup`]): the object's transforms, its
//! prepared lights and how its vertices and faces are lit.

use crate::geometry::project::{pack_channels, ScreenVertex};
use crate::kernel;
use crate::kernel::records::LIT;
use crate::num::math::{normalize, sub, Mat4, Vec3};
use crate::num::scalar::Scalar;
use crate::scene::color::TargetColor;
use crate::scene::mesh::face_normal;
use crate::scene::shade::{lit_color, lit_diffuse, PreparedLight};
use crate::scene::{Object, Scene};

/// What the lighting routine ([`kernel::light_run`]) needs of an object: its mesh's
/// normals, its one light's direction (in the object's space) and colour fraction.
pub(crate) type QuickLight<'n, S> = (&'n [Vec3<S>], Vec3<S>, S);

/// Per-object state of the geometry stage.
pub(crate) struct ObjectSetup<'o, 'a, S: Scalar, const L: usize> {
    pub(crate) obj: &'o Object<'a, S>,
    /// The scene (its point lights, fog and camera; the object-space path and the lighting
    /// kernels are for scenes without point lights and fog).
    pub(crate) scene: &'o Scene<'a, S, L>,
    pub(crate) mvp: Mat4<S>,
    pub(crate) normal_matrix: Mat4<S>,
    pub(crate) similar: bool,
    /// The lights: in world space, or in the object's space when `in_object` holds
    /// ([`PreparedLight::in_object_space`]; then vertex normals are used as they are).
    pub(crate) lights: &'o [PreparedLight<S>; L],
    /// Gouraud shading (so no face normals, which are in world space), a normal matrix that
    /// is a rotation (`similar`) and no specular term (which would need the eye direction).
    pub(crate) in_object: bool,
    /// The transform mirrors (negative determinant): the triangle loop swaps each triangle's
    /// winding, so the outside stays the front.
    pub(crate) mirrored: bool,
    pub(crate) base: usize,
    /// For the attribute stores, in one word (the deepest stack of a frame, on a 16 KB part,
    /// has no room for two): bits 0..=24, `1 − near/far` in Q0.24 for a perspective camera,
    /// 0 for an orthographic one (the textured vertices' `near/w` from their depth,
    /// [`q_from_depth`](crate::geometry::vertex_extra::q_from_depth)); bits 25..=31, a Phong object's material entry in the pool (0: not
    /// Phong; at most 127 Phong objects).
    pub(crate) extra: u32,
}

impl<S: Scalar, const L: usize> ObjectSetup<'_, '_, S, L> {
    /// `1 − near/far` in Q0.24 (see [`Self::extra`]).
    pub(crate) fn k24(&self) -> u32 {
        self.extra & ((1 << 25) - 1)
    }

    /// A Phong object's material entry in the pool (see [`Self::extra`]).
    pub(crate) fn phong_material(&self) -> u16 {
        (self.extra >> 25) as u16
    }

    /// Mesh normal `n` in world space, unit, Q1.14 (a Phong vertex's attribute).
    pub(crate) fn phong_normal(&self, n: Vec3<S>) -> [i32; 3] {
        self.world_normal(n, true).map(|c| c.to_fixed_i32(14))
    }

    /// The fraction bits of Phong vertices' positions when the scene has point lights (which
    /// alone read them), else `None` (computed once per object: f64 arithmetic).
    pub(crate) fn phong_position_bits(&self) -> Option<u32> {
        (!self.scene.point_lights().is_empty())
            .then(|| crate::scene::effects::position_bits(&self.scene.camera))
    }

    /// Object point `p` in world space less the eye, in 2^-`bits` units (a Phong vertex's
    /// attribute, for point lights).
    pub(crate) fn phong_position(&self, p: Vec3<S>, bits: u32) -> [i32; 3] {
        let w = self.obj.transform.transform_point(p);
        let d = sub([w[0], w[1], w[2]], self.scene.camera.eye);
        d.map(|c| c.to_fixed_i32(bits))
    }

    pub(crate) fn to_eye(&self, p: Vec3<S>) -> Vec3<S> {
        if self.obj.material.specular > S::ZERO {
            let w = self.obj.transform.transform_point(p);
            normalize(sub(self.scene.camera.eye, [w[0], w[1], w[2]]))
        } else {
            [S::ZERO; 3]
        }
    }

    pub(crate) fn world_normal(&self, n: Vec3<S>, force: bool) -> Vec3<S> {
        let n = self.normal_matrix.transform_dir(n);
        if self.similar && !force {
            n
        } else {
            normalize(n)
        }
    }

    /// What [`kernel::light_run`] needs when it can light this object's vertices: the
    /// number type has the routine, the target is RGB565, the lights are in the object's space
    /// (no specular term), there is one light and it is grey, and the mesh has normals. Then
    /// the normals, the light's direction and its colour fraction.
    pub(crate) fn quick_light<C: TargetColor>(&self) -> Option<QuickLight<'_, S>> {
        if !(kernel::LIGHT_RUN && self.in_object && C::CHANNEL_MAX == [31, 63, 31]) {
            return None;
        }
        let [l] = self.lights.as_slice() else {
            return None;
        };
        let (dir, frac) = l.grey()?;
        Some((self.obj.mesh.normals()?, dir, frac))
    }

    /// Whether the scene has point lights or fog (lit by [`Self::lit_fx`]).
    #[inline(always)]
    pub(crate) fn has_fx(&self) -> bool {
        self.scene.effects.is_some()
    }

    /// The lit and fogged colour (8.8 per channel) at object point `p` with unit world normal
    /// `n`, with the scene's point lights and fog: the world point's direction to the eye and
    /// view depth. Out of line: the deepest stack of a frame without them does not grow.
    #[inline(never)]
    pub(crate) fn lit_fx(&self, p: Vec3<S>, n: Vec3<S>) -> [u16; 3] {
        let w = self.obj.transform.transform_point(p);
        let w = [w[0], w[1], w[2]];
        let m = &self.obj.material;
        let to_eye = if m.specular > S::ZERO {
            normalize(sub(self.scene.camera.eye, w))
        } else {
            [S::ZERO; 3]
        };
        let lit = crate::scene::effects::lit_color_points(
            m,
            self.lights,
            self.scene.point_lights(),
            n,
            w,
            to_eye,
            self.scene.tone(),
        );
        match &self.scene.fog() {
            // A textured material's spans fog its pixels (texel × light, then fog).
            Some(f) if m.texture.is_none() => {
                let r = self.scene.camera.view.m[2];
                f.apply(lit, -S::dot3_add([r[0], r[1], r[2]], w, r[3]))
            }
            _ => lit,
        }
    }

    /// Lights record `v` as mesh vertex `i` ([`Self::vertex_color`]) and marks it [`LIT`].
    #[inline(always)]
    pub(crate) fn light<C: TargetColor>(&self, v: &mut ScreenVertex, i: usize) {
        v.set_color(self.vertex_color::<C>(i));
        v.flags |= LIT;
    }

    /// Lit colour of mesh vertex `i`, in the vertex format ([`ScreenVertex::color`]).
    pub(crate) fn vertex_color<C: TargetColor>(&self, i: usize) -> [u16; 3] {
        let mesh = &self.obj.mesh;
        let p = mesh.positions()[i];
        let n = mesh.normals().map_or([S::ZERO; 3], |ns| ns[i]);
        let lit = if self.has_fx() {
            self.lit_fx(p, self.world_normal(n, false))
        } else if self.in_object {
            // The same dot products without a normal transform per vertex (and no specular
            // term: `in_object` requires none).
            lit_diffuse(&self.obj.material, self.lights, n)
        } else {
            lit_color(
                &self.obj.material,
                self.lights,
                self.world_normal(n, false),
                self.to_eye(p),
            )
        };
        pack_channels(C::vertex_channels(lit), C::CHANNEL_MAX)
    }

    /// Lit colour of a face, in the target's channel units (8.8).
    /// `tri` in screen winding (swapped for a mirrored object, whose mesh order is restored
    /// here for the face normal).
    pub(crate) fn face_color<C: TargetColor>(&self, tri: [u16; 3]) -> [u16; 3] {
        let m = &self.obj.material;
        if m.diffuse == S::ZERO && m.specular <= S::ZERO && !self.has_fx() {
            // Unlit (the ambient term only): no face normal (the same value: the diffuse
            // term is a product by zero). Shadow polygons are such faces.
            return C::vertex_channels(lit_color(m, self.lights, [S::ZERO; 3], [S::ZERO; 3]));
        }
        let [a, b, c] = tri.map(|i| self.obj.mesh.positions()[i as usize]);
        let (b, c) = if self.mirrored { (c, b) } else { (b, c) };
        let n = self.world_normal(face_normal(a, b, c), true);
        let k = S::from_f64(1.0 / 3.0);
        let centroid = [0, 1, 2].map(|j| (a[j] + b[j] + c[j]) * k);
        if self.has_fx() {
            return C::vertex_channels(self.lit_fx(centroid, n));
        }
        let lit = lit_color(&self.obj.material, self.lights, n, self.to_eye(centroid));
        C::vertex_channels(lit)
    }
}
