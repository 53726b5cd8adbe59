//! The geometry stage's part of the attribute stores (textures, Phong): each vertex's
//! texture coordinates or normal, those of the vertices clipping and flat shading add, and
//! the pool's Phong entries of a frame.

use crate::error::Error;
use crate::geometry::fog::FogSpan;
use crate::geometry::object_setup::ObjectSetup;
use crate::geometry::phong_entries::{
    band_step, PhongLight, PhongLights, PhongMaterial, PhongPoint, PhongPoints, MAX_PHONG_LIGHTS,
    TONE_FILMIC, TONE_NONE, TONE_REINHARD,
};
use crate::geometry::pool::{lit_mode, FREE, LIGHTS, MATERIAL, MODE_PHONG};
use crate::geometry::project::ScreenVertex;
use crate::geometry::stores::Stores;
use crate::geometry::vertex_extra::{q_from_depth, VertexExtra};
use crate::num::math::{normalize, sub, Vec3};
use crate::num::scalar::Scalar;
use crate::scene::color::TargetColor;
use crate::scene::effects::{position_bits, MAX_PHONG_POINT_LIGHTS};
use crate::scene::shade::{PreparedLight, Shading};
use crate::scene::Scene;

impl<
        S: Scalar,
        C: TargetColor,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
    > Stores<S, C, H, VERTS, TRIS, XV, XA>
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
        // Positions only for point lights (Phong reads them for nothing else).
        let bits = if phong.is_phong() {
            o.phong_position_bits()
        } else {
            None
        };
        for i in base..end {
            self.xverts[i] = match (&o.obj.material.texture, mesh.uvs(), mesh.normals()) {
                _ if C::triangle_id(0).is_some() => VertexExtra::NONE,
                (_, _, Some(ns)) if phong.is_phong() => VertexExtra::phong(
                    o.phong_normal(ns[i - base]),
                    bits.map_or([0; 3], |b| o.phong_position(mesh.positions()[i - base], b)),
                    o.phong_material(),
                    lit_mode(phong).unwrap_or(MODE_PHONG),
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
            let bits = o.phong_position_bits();
            let ps = o.obj.mesh.positions();
            let n = [0, 1, 2].map(|k| o.phong_normal(ns[tri[k] as usize]).map(|v| v as i64));
            let x = [0, 1, 2]
                .map(|k| bits.map_or([0; 3], |b| o.phong_position(ps[tri[k] as usize], b)));
            let x = x.map(|v| v.map(|c| c.clamp(-32768, 32767) as i64));
            let n = [0, 1, 2].map(|j| mix(n[0][j], n[1][j], n[2][j]));
            let x = [0, 1, 2].map(|j| mix(x[0][j], x[1][j], x[2][j]));
            let mode = lit_mode(material.shading).unwrap_or(MODE_PHONG);
            self.xverts[at] = VertexExtra::phong(n, x, o.phong_material(), mode);
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

    /// Frees the pool and gives the frame's payloads their entries: entry 0 the fog (when
    /// the scene has fog and a Phong or textured object), then, when it has Phong objects,
    /// the directional lights, the point lights (when it has any) and one entry to each Phong
    /// object's material, in scene order (see [`ObjectSetup::phong_material`]). Returns how
    /// many entries that takes and the first material's.
    pub(crate) fn phong_entries<E, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
    ) -> Result<(usize, usize), Error<E>> {
        for e in self.xactive.iter_mut() {
            e.kind = FREE;
        }
        if C::triangle_id(0).is_some() {
            return Ok((0, 0));
        }
        let phong: usize = scene
            .objects
            .iter()
            .filter(|o| o.material.shading.is_phong())
            .count();
        let stores = scene
            .objects
            .iter()
            .position(|o| o.material.needs_attribute_stores());
        let fog = scene.fog().filter(|_| stores.is_some());
        let points = !scene.point_lights().is_empty() && phong > 0;
        let need = fog.is_some() as usize
            + if phong > 0 {
                phong + 1 + points as usize
            } else {
                0
            };
        if need == 0 {
            return Ok((0, 0));
        }
        if need > XA {
            return Err(Error::AttributeStore {
                object: stores.unwrap_or(0),
                vertices_needed: 0,
                vertex_capacity: XV,
                active_needed: need + 1,
                active_capacity: XA,
            });
        }
        let mut slot = 0;
        if let Some(f) = &fog {
            FogSpan::new(f, &scene.camera).store(&mut self.xactive[0]);
            slot = 1;
        }
        if phong == 0 {
            return Ok((slot, slot));
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
        lights.store(&mut self.xactive[slot]);
        self.xactive[slot].kind = LIGHTS;
        slot += 1;
        if points {
            let bits = position_bits(&scene.camera);
            let mut p = PhongPoints {
                bits: bits as u8,
                ..Default::default()
            };
            let eye = scene.camera.eye;
            let far = (1i64 << 30) as f64;
            for (k, l) in scene
                .point_lights()
                .iter()
                .take(MAX_PHONG_POINT_LIGHTS)
                .enumerate()
            {
                let d = sub(l.position, eye);
                p.lights[k] = PhongPoint {
                    // Through f64: a far light's position may exceed Q16.16's range here.
                    pos: d.map(|c| {
                        libm::round(c.to_f64() * (1u32 << bits) as f64).clamp(-far, far) as i32
                    }),
                    color: l.color,
                    att: l
                        .attenuation
                        .map(|c| c.max(S::ZERO).min(S::from_i32(31)).to_fixed_i32(16)),
                };
                p.count = k as u8 + 1;
            }
            p.store(&mut self.xactive[slot]);
            slot += 1;
        }
        let first = slot;
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
            // With a tone map the spans light in HDR: the coefficients carry the exposure
            // (and the lights' intensity, but for the ambient term) and the curve is read per
            // pixel (`phong::tone14`).
            let (scale_a, scale_l, tone) = match scene.tone() {
                Some(t) => (
                    t.exposure,
                    t.intensity * t.exposure,
                    match t.curve {
                        crate::scene::tone::ToneCurve::Clamp => TONE_NONE,
                        crate::scene::tone::ToneCurve::Reinhard => TONE_REINHARD,
                        crate::scene::tone::ToneCurve::Filmic => TONE_FILMIC,
                    },
                ),
                None => (S::ONE, S::ONE, TONE_NONE),
            };
            let mut lv = [0; MAX_PHONG_LIGHTS];
            for (x, l) in lv.iter_mut().zip(&lights.lights) {
                let s: i64 = (0..3).map(|j| l.dir[j] as i64 * v[j] as i64).sum();
                *x = (s >> 14) as i32;
            }
            let bands = match m.shading {
                Shading::Toon { bands } => bands.get(),
                _ => 0,
            };
            let pm = PhongMaterial {
                color: m.color,
                k: [
                    k(m.ambient * scale_a),
                    k(m.diffuse * scale_l),
                    k(m.specular * scale_l),
                ],
                shininess: m.shininess,
                v,
                lv,
                tone,
                bands,
                band_step: band_step(bands),
            };
            pm.store(&mut self.xactive[slot]);
            self.xactive[slot].kind = MATERIAL;
            slot += 1;
        }
        Ok((slot, first))
    }
}
