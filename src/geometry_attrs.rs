//! The geometry stage's part of the attribute stores (textures, Phong): each vertex's
//! texture coordinates or normal, those of the vertices clipping and flat shading add, and
//! the pool's Phong entries of a frame.

use crate::attrs::{FREE, LIGHTS, MATERIAL};
use crate::color::TargetColor;
use crate::error::Error;
use crate::geometry::ObjectSetup;
use crate::math::{normalize, sub, Vec3};
use crate::phong::{PhongLight, PhongLights, PhongMaterial, MAX_PHONG_LIGHTS};
use crate::project::ScreenVertex;
use crate::renderer::Renderer;
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::shade::{PreparedLight, Shading};
use crate::textured::{q_from_depth, VertexExtra};

impl<
        S: Scalar,
        C: TargetColor,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XV: usize,
        const XA: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA>
{
    /// The texture attributes of object `o`'s mesh vertices (stored from `base`, `n` of them)
    /// when it is textured, none otherwise (where the store has room).
    #[inline(never)]
    pub(crate) fn vertex_extras<const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        base: usize,
        n: usize,
    ) {
        let mesh = &o.obj.mesh;
        let end = (base + n).min(XV).min(self.verts.len());
        let phong = o.obj.material.shading;
        for i in base..end {
            self.xverts[i] = match (&o.obj.material.texture, mesh.uvs(), mesh.normals()) {
                _ if C::triangle_id(0).is_some() => VertexExtra::NONE,
                (_, _, Some(ns)) if phong.is_phong() => VertexExtra::phong(
                    o.phong_normal(ns[i - base]),
                    o.phong_material(),
                    phong == Shading::FastPhong,
                ),
                (Some(map), Some(uvs), _) => {
                    let st = uvs[i - base].map(|c| c.to_fixed_i32(16));
                    let q = q_from_depth(self.verts[i].depth() as u32 >> 4, o.k24());
                    VertexExtra::new(map, st, q)
                }
                _ => VertexExtra::NONE,
            };
        }
    }

    /// Store entry `to` gets the texture attributes of entry `from` (a flat triangle's colour
    /// vertex), where the store has room.
    pub(crate) fn copy_extra(&mut self, from: usize, to: usize) {
        if to < XV {
            self.xverts[to] = self.xverts.get(from).copied().unwrap_or(VertexExtra::NONE);
        }
    }

    /// The texture attributes of a vertex a clip made on mesh triangle `tri` of object `o`,
    /// with barycentric weights `w` (of the triangle's vertices 1 and 2, in 2⁻¹⁶ units, as
    /// the clip interpolated them: 1 is 65535) and record `sv`, stored for the next vertex.
    pub(crate) fn clipped_extra<const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        tri: &[u16; 3],
        w: [u16; 3],
        sv: &ScreenVertex,
    ) {
        let at = self.verts.len();
        if at >= XV || C::triangle_id(0).is_some() {
            return;
        }
        let (w1, w2) = (w[0] as i64, w[1] as i64);
        // The weighted mix of three vertices' values (the weights in 2⁻¹⁶ units, 1 = 65535).
        let mix = |a: i64, b: i64, c: i64| {
            let d = (b - a) * w1 + (c - a) * w2;
            (a + (d + (1 << 15)).div_euclid(65535)) as i32
        };
        let material = &o.obj.material;
        if material.shading.is_phong() {
            let Some(ns) = o.obj.mesh.normals() else {
                return;
            };
            let n = [0, 1, 2].map(|k| o.phong_normal(ns[tri[k] as usize]).map(|v| v as i64));
            let n = [0, 1, 2].map(|j| mix(n[0][j], n[1][j], n[2][j]));
            let fast = material.shading == Shading::FastPhong;
            self.xverts[at] = VertexExtra::phong(n, o.phong_material(), fast);
            return;
        }
        let (Some(map), Some(uvs)) = (&material.texture, o.obj.mesh.uvs()) else {
            return;
        };
        let st = |k: usize| uvs[tri[k] as usize].map(|c| c.to_fixed_i32(16) as i64);
        let (a, b, c) = (st(0), st(1), st(2));
        let q = q_from_depth(sv.depth() as u32 >> 4, o.k24());
        self.xverts[at] = VertexExtra::new(map, [mix(a[0], b[0], c[0]), mix(a[1], b[1], c[1])], q);
    }

    /// Frees the pool and, when `scene` has Phong objects, gives its entry 0 the frame's
    /// lights and one entry after it to each Phong object's material, in scene order (see
    /// [`ObjectSetup::phong_material`]). Returns how many entries that takes.
    pub(crate) fn phong_entries<E, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
    ) -> Result<usize, Error<E>> {
        for e in self.xactive.iter_mut() {
            e.kind = FREE;
        }
        let phong: usize = scene
            .objects
            .iter()
            .filter(|o| o.material.shading.is_phong())
            .count();
        if phong == 0 || C::triangle_id(0).is_some() {
            return Ok(0);
        }
        if phong + 1 > XA {
            let object = scene
                .objects
                .iter()
                .position(|o| o.material.shading.is_phong());
            return Err(Error::AttributeStore {
                object: object.unwrap_or(0),
                vertices_needed: 0,
                vertex_capacity: XV,
                active_needed: phong + 2,
                active_capacity: XA,
            });
        }
        let q14 = |v: Vec3<S>| v.map(|c| c.to_fixed_i32(14));
        let mut lights = PhongLights::default();
        for (k, l) in scene.lights.iter().take(MAX_PHONG_LIGHTS).enumerate() {
            lights.lights[k] = PhongLight {
                dir: q14(PreparedLight::new(l).dir()),
                color: l.color,
            };
            lights.count = k as u8 + 1;
        }
        lights.store(&mut self.xactive[0]);
        self.xactive[0].kind = LIGHTS;
        let mut slot = 1;
        for o in scene
            .objects
            .iter()
            .filter(|o| o.material.shading.is_phong())
        {
            let m = &o.material;
            let origin = o.transform.transform_point([S::ZERO; 3]);
            let v = q14(normalize(sub(
                scene.camera.eye,
                [origin[0], origin[1], origin[2]],
            )));
            let k = |c: S| (c.max(S::ZERO).min(S::from_i32(255))).to_fixed_i32(14);
            let mut lv = [0; MAX_PHONG_LIGHTS];
            for (x, l) in lv.iter_mut().zip(&lights.lights) {
                let s: i64 = (0..3).map(|j| l.dir[j] as i64 * v[j] as i64).sum();
                *x = (s >> 14) as i32;
            }
            let pm = PhongMaterial {
                color: m.color,
                k: [k(m.ambient), k(m.diffuse), k(m.specular)],
                shininess: m.shininess,
                v,
                lv,
            };
            pm.store(&mut self.xactive[slot]);
            self.xactive[slot].kind = MATERIAL;
            slot += 1;
        }
        Ok(slot)
    }
}
