//! The geometry stage: for every object, its vertices transformed, tested against the view
//! volume and projected (runs of them by the vertex kernel where it runs), its triangles culled
//! and binned (the cull kernel), clipped where they cross the near or far plane or the guard
//! band, and its vertices lit (runs of them by the lighting kernel).

pub(crate) mod attrs;
pub(crate) mod bin;
pub(crate) mod clip;
pub(crate) mod cull;
pub(crate) mod fog;
pub(crate) mod object_setup;
pub(crate) mod phong_entries;
pub(crate) mod pool;
pub(crate) mod project;
pub(crate) mod stores;
pub(crate) mod vertex_extra;

use heapless::Vec;

use crate::geometry::clip::{clip_triangle, outcode, ClipVertex, NEEDS_CLIP};
use crate::geometry::cull::{facing, Facing};
use crate::geometry::project::{
    pack_channels, pack_flat_channels, unpack_channels, ScreenVertex, Viewport, COORD_LIMIT,
};
use crate::geometry::vertex_extra::VertexExtra;
use crate::kernel::records::{TriRecord, FLAT_BIT};
use crate::num::math::{Mat4, Vec3};
use crate::num::scalar::Scalar;
use crate::scene::camera::Projection;
use crate::scene::color::TargetColor;
use crate::scene::shade::{PreparedLight, Shading};
use crate::scene::{Object, Scene};

use crate::error::*;
use crate::geometry::stores::Stores;
use crate::kernel;
use crate::kernel::records::{Bins, CullCounts, CullStop};
pub(crate) use crate::kernel::records::{INVALID, LIT, NEEDS_LIGHT, PROJECTED};
use crate::stats::*;

pub(crate) use crate::geometry::object_setup::{ObjectSetup, QuickLight};

/// The geometry stage's constants over a frame's objects ([`Stores::frame_begin`]).
#[derive(Copy, Clone)]
pub(crate) struct FrameConst<S> {
    pub(crate) vp: Viewport,
    /// The guard band, in the number type.
    pub(crate) g: S,
    /// Projection × view.
    pub(crate) pv: Mat4<S>,
    /// The pool entries the Phong lights, point lights and fog reserve.
    reserved: usize,
    /// The first Phong material's pool entry.
    first_material: usize,
    /// `1 − near/far` in Q0.24 ([`ObjectSetup::k24`]).
    k24: u32,
}

/// The geometry stage's counts over a frame's objects.
#[derive(Default)]
pub(crate) struct Frame {
    /// Vertices and triangles the frame needs so far.
    pub(crate) need: (usize, usize),
    pub(crate) stats: Stats,
}

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
    /// The geometry stage's start: the stores emptied, every object checked for what its
    /// material needs (normals, texture coordinates, attribute stores; with `layered` false, an
    /// opaque material: a translucent one needs [`crate::FrameOptions::layered`]), the camera
    /// validated and the frame's constants computed.
    #[inline(always)]
    pub(crate) fn frame_begin<E, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        layered: bool,
    ) -> Result<FrameConst<S>, Error<E>> {
        self.verts.clear();
        self.tris.clear();
        self.heads = [0; H];
        self.starts = [0; H];
        for (i, o) in scene.objects.iter().enumerate() {
            if o.material.shading != Shading::Flat && o.mesh.normals().is_none() {
                return Err(Error::MissingNormals { object: i });
            }
            if !layered && o.material.alpha < 255 {
                return Err(Error::NeedsLayers { object: i });
            }
            if o.material.needs_attribute_stores() {
                if o.material.texture.is_some()
                    && !o.material.shading.is_phong()
                    && o.mesh.uvs().is_none()
                {
                    return Err(Error::MissingUvs { object: i });
                }
                if XV == 0 || XA == 0 {
                    return Err(Error::AttributeStore {
                        object: i,
                        vertices_needed: self.verts.len() + o.mesh.positions().len(),
                        vertex_capacity: XV,
                        active_needed: 1,
                        active_capacity: XA,
                    });
                }
            }
        }
        let vp = Viewport {
            width: self.vw as u32,
            height: self.vh as u32,
        };
        let g = S::from_i32(vp.guard_band());
        // The camera's fields are public: checked every frame (a few dozen comparisons).
        scene.camera.validate().map_err(Error::Camera)?;
        let pv = scene
            .camera
            .projection
            .matrix(vp.aspect())
            .mul(&scene.camera.view);
        // The pool's Phong entries (the frame's lights, each Phong object's material).
        let (reserved, first_material) = if XV > 0 {
            self.phong_entries(scene)?
        } else {
            (0, 0)
        };
        let k24 = match scene.camera.projection {
            _ if XV == 0 => 0,
            Projection::Perspective { near, far, .. } => {
                let k = 1.0 - near.to_f64() / far.to_f64();
                libm::round(k.clamp(0.0, 1.0) * (1u32 << 24) as f64) as u32
            }
            Projection::Orthographic { .. } => 0,
        };
        lights_valid(scene)?;
        Ok(FrameConst {
            vp,
            g,
            pv,
            reserved,
            first_material,
            k24,
        })
    }

    /// The geometry stage for object `obj` (scene object `index`, or drawn for it: a shadow
    /// polygon set is its caster's mesh under another transform and material).
    #[inline(always)]
    pub(crate) fn frame_object<E, P: Probe, const L: usize>(
        &mut self,
        c: &FrameConst<S>,
        f: &mut Frame,
        scene: &Scene<'_, S, L>,
        obj: &Object<'_, S>,
        index: usize,
        probe: &mut P,
    ) -> Result<(), Error<E>> {
        // NaN, infinite or (fixed point) saturated inputs are skipped and counted per object,
        // the same for every number type (a float NaN would poison every vertex).
        let ok = |v: &S| v.is_valid();
        let m = &obj.material;
        if !(obj.transform.m.iter().all(|r| r.iter().all(ok))
            && [m.ambient, m.diffuse, m.specular].iter().all(ok))
        {
            let n = obj.mesh.indices().len() as u32;
            f.need.0 += obj.mesh.positions().len();
            f.stats.triangles_in = f.stats.triangles_in.wrapping_add(n);
            f.stats.invalid += n;
            return Ok(());
        }
        let (normal_matrix, similar, mirrored) = obj.transform.normal_matrix_mirrored();
        let in_object = similar
            && scene.effects.is_none()
            && obj.material.shading == Shading::Gouraud
            && obj.material.specular <= S::ZERO;
        // Prepared per object, in place (one array of lights on the stack: a 16 KB part has
        // no room for a second).
        let mut lights = scene.lights.map(|l| PreparedLight::new(&l));
        if in_object {
            for l in &mut lights {
                *l = l.in_object_space(&normal_matrix);
            }
        }
        let setup = ObjectSetup {
            obj,
            scene,
            mvp: c.pv.mul(&obj.transform),
            normal_matrix,
            similar,
            lights: &lights,
            in_object,
            mirrored,
            base: self.verts.len(),
            // The material's pool entry (after the lights' entries): the Phong objects are
            // numbered in the scene's order.
            extra: c.k24
                | if XV > 0 && obj.material.shading.is_phong() {
                    let rank = scene.objects[..index.min(scene.objects.len())]
                        .iter()
                        .filter(|o| o.material.shading.is_phong())
                        .count();
                    ((c.first_material + rank) as u32) << 25
                } else {
                    0
                },
        };
        self.object(&setup, &c.vp, c.g, &mut f.stats, &mut f.need, probe);
        if XV > 0 {
            let end = self.verts.len();
            if obj.material.needs_attribute_stores() {
                f.stats.attr_vertices = f.stats.attr_vertices.max(end as u32);
            }
            if obj.material.needs_attribute_stores() && end > XV {
                return Err(Error::AttributeStore {
                    object: index,
                    vertices_needed: end,
                    vertex_capacity: XV,
                    active_needed: 0,
                    active_capacity: XA,
                });
            }
            if !obj.material.needs_attribute_stores() {
                for x in self.xverts.iter_mut().take(end).skip(setup.base) {
                    *x = VertexExtra::NONE;
                }
            }
        }
        Ok(())
    }

    /// The geometry stage's end: the capacities checked (`active`: the most triangles one row
    /// may hold, the renderer's `ACTIVE` for a plain frame; a layered frame checks each of its lists), the
    /// buckets sorted and the frame prepared for the strip pass.
    #[inline(always)]
    pub(crate) fn frame_end<E, const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        c: &FrameConst<S>,
        f: &mut Frame,
        active: usize,
        overflow: OverflowPolicy,
        capacity: Needs,
    ) -> Result<Stats, Error<E>> {
        // In place (no copy of the statistics on the deepest stack).
        let (stats, need, reserved) = (&mut f.stats, f.need, c.reserved);
        stats.vertices = need.0 as u32;
        let mut cur = 0i32;
        let mut max = 0i32;
        for &s in self.starts.iter() {
            cur += s as i32;
            max = max.max(cur);
        }
        stats.max_active = max as u32;
        // The attribute pool's entries the frame needs: its fog, Phong lights and materials,
        // and the most triangles on a row (a bound of the textured and Phong ones among them).
        let pool = max as usize + reserved;
        // The first object that needs the attribute stores (a frame with one on a renderer
        // without stores was refused by `frame_begin`).
        let stores = if XV > 0 {
            scene
                .objects
                .iter()
                .position(|o| o.material.needs_attribute_stores())
        } else {
            None
        };
        stats.attr_active = if stores.is_some() { pool as u32 } else { 0 };
        // Under `OverflowPolicy::Error` the pool must hold that bound, so that no textured
        // triangle is left out.
        if let Some(object) = stores {
            if XA > 0 && overflow == OverflowPolicy::Error && pool > XA {
                return Err(Error::AttributeStore {
                    object,
                    vertices_needed: stats.attr_vertices as usize,
                    vertex_capacity: XV,
                    active_needed: pool,
                    active_capacity: XA,
                });
            }
        }
        // Triangles needed but not stored (only when the store or the vertices overflowed).
        let store_skipped = need.1.saturating_sub(self.tris.len());
        if need.0 > VERTS || need.1 > TRIS || max as usize > active {
            // Every capacity at once: what the frame needed against all three.
            let needed = Needs::new(need.0, need.1, max as usize);
            if overflow == OverflowPolicy::Error {
                return Err(Error::Shortfall(Shortfall {
                    needed,
                    capacity,
                    exact: need.0 <= VERTS && need.1 <= TRIS,
                    skipped: 0,
                }));
            }
        }
        self.store_skipped = store_skipped.min(u32::MAX as usize) as u32;
        self.sort_buckets();
        Ok(*stats)
    }

    /// Transforms, lights, clips, projects, culls and buckets one object.
    pub(crate) fn object<P: Probe, const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        vp: &Viewport,
        g: S,
        stats: &mut Stats,
        need: &mut (usize, usize),
        probe: &mut P,
    ) {
        let mesh = o.obj.mesh;
        let positions = mesh.positions();
        need.0 += positions.len();
        if o.base + positions.len() > VERTS {
            // Count what the object would need; nothing of it can be stored.
            stats.triangles_in += mesh.indices().len() as u32;
            need.1 += mesh.indices().len();
            return;
        }
        probe.enter(Stage::Vertices);
        if kernel::PROJECT_RUN && S::q16_words(positions).is_some() && !mesh.has_invalid_positions()
        {
            let (sx, sy) = (8 * vp.width, 8 * vp.height);
            let mut i = 0;
            loop {
                // A run of vertices the number type stores itself (Q16.16 on a Cortex-M0),
                // then the probe's snapping for them (if it snaps); then one vertex here.
                let first = self.verts.len();
                let rest = positions.get(i..).unwrap_or(&[]);
                let run = project_run(&o.mvp.m, rest, g, sx, sy, &mut self.verts);
                let snaps = if P::SNAPS { run } else { 0 };
                for (k, v) in self.verts.iter_mut().enumerate().skip(first).take(snaps) {
                    if v.flags & PROJECTED != 0 {
                        let index = k - stats.color_vertices as usize;
                        (v.x, v.y) = snapped(probe, index, *v);
                    }
                }
                i += run;
                let Some(&p) = positions.get(i) else {
                    break;
                };
                i += 1;
                self.push_vertex(o, vp, g, p, stats, probe);
            }
        } else if !mesh.has_invalid_positions() {
            for &p in positions {
                self.push_vertex(o, vp, g, p, stats, probe);
            }
        } else {
            // A position NaN, infinite or at a fixed-point rail (known when the mesh was
            // built): its record is invalid, as a float NaN's clip coordinates make it.
            for &p in positions {
                self.push_vertex(o, vp, g, p, stats, probe);
                if !p.iter().all(|v| v.is_valid()) {
                    if let Some(v) = self.verts.last_mut() {
                        v.flags |= INVALID;
                    }
                }
            }
        }
        if XV > 0 {
            self.vertex_extras(o, o.base, positions.len());
        }
        let flat = o.obj.material.shading == Shading::Flat;
        probe.enter(Stage::Triangles);
        // The triangles' ids follow on from the earlier objects' (counted once, not per
        // triangle through `stats`).
        let first_id = stats.triangles_in;
        let tris = mesh.indices();
        stats.triangles_in = first_id.wrapping_add(tris.len() as u32);
        let (base, n) = (o.base, positions.len());
        // Gouraud triangles of real colours go through `cull_push` (the common cases: cull,
        // count and bucket; vertices of stored front faces are marked for lighting), which
        // stops at a triangle that needs this loop's full path; flat ones and triangle ids
        // take the full path throughout.
        let fast = !flat && C::triangle_id(0).is_none() && !o.mirrored;
        let mut k = 0;
        loop {
            if fast {
                let view = (self.vw, self.vh);
                let (store, heads, starts) = (&mut self.tris, &mut self.heads, &mut self.starts);
                let Some(vs) = self.verts.get_mut(base..base + n) else {
                    break;
                };
                let bins = Bins {
                    store,
                    heads,
                    starts,
                    view,
                };
                let mut counts = CullCounts::default();
                let stop = kernel::cull_push(
                    tris,
                    &mut k,
                    vs,
                    base as u16,
                    bins,
                    &mut counts,
                    &mut need.1,
                );
                stats.add_culling(&counts);
                if stop == CullStop::Done {
                    break;
                }
            }
            let Some(&tri) = tris.get(k) else {
                break;
            };
            // A mirrored object's triangles in screen winding.
            let tri = &if o.mirrored {
                [tri[0], tri[2], tri[1]]
            } else {
                tri
            };
            let id = first_id.wrapping_add(k as u32) as u16;
            k += 1;
            // This object's vertices (all stored above; flat triangles' colour vertices
            // follow them): an index check against them is also the store's bounds check.
            let Some(vs) = self.verts.get(base..base + n) else {
                return;
            };
            // Element by element: on a Cortex-M0 `array::map` stays a call (`try_from_fn`).
            let (Some(a), Some(b), Some(c)) = (
                vs.get(tri[0] as usize),
                vs.get(tri[1] as usize),
                vs.get(tri[2] as usize),
            ) else {
                stats.invalid += 1;
                continue;
            };
            let vi = [
                base + tri[0] as usize,
                base + tri[1] as usize,
                base + tri[2] as usize,
            ];
            let f = [a.flags, b.flags, c.flags];
            if (f[0] | f[1] | f[2]) & INVALID != 0 {
                stats.invalid += 1;
                continue;
            }
            if f[0] & f[1] & f[2] & 0x3f != 0 {
                stats.outside += 1;
                continue;
            }
            if (f[0] | f[1] | f[2]) & NEEDS_CLIP as u16 == 0 {
                match facing(a, b, c) {
                    Facing::Degenerate => {
                        stats.degenerate += 1;
                        continue;
                    }
                    Facing::Back => {
                        stats.culled += 1;
                        continue;
                    }
                    Facing::Front => {}
                }
                probe.enter(Stage::Lighting);
                let color = if let Some(c) = C::triangle_id(id) {
                    Some(c)
                } else if flat {
                    Some(o.face_color::<C>(*tri))
                } else {
                    for (k, &v) in vi.iter().enumerate() {
                        if self.verts[v].flags & LIT == 0 {
                            o.light::<C>(&mut self.verts[v], tri[k] as usize);
                        }
                    }
                    None
                };
                probe.enter(Stage::Triangles);
                let mut v = [vi[0] as u16, vi[1] as u16, vi[2] as u16];
                if let Some(rgb) = color {
                    // A copy of the first vertex with the face colour carries it.
                    need.0 += 1;
                    let mut colour_vertex = self.verts[vi[0]];
                    colour_vertex.set_color(pack_flat_channels(rgb, C::CHANNEL_MAX));
                    v[0] = self.verts.len() as u16 | FLAT_BIT;
                    if XV > 0 {
                        self.copy_extra(vi[0], self.verts.len());
                    }
                    if self.verts.push(colour_vertex).is_err() {
                        need.1 += 1;
                        continue;
                    }
                    if !self.push_tri(v, stats, need) {
                        // Not stored (empty or off-screen): the colour vertex is not needed.
                        self.verts.pop();
                        need.0 -= 1;
                        continue;
                    }
                    stats.color_vertices += 1;
                    continue;
                }
                self.push_tri(v, stats, need);
            } else {
                self.clipped(o, tri, vi, flat, vp, g, id, stats, need, probe);
            }
        }
        if fast {
            // The vertices `cull_push` marked: lit once each, as the full path lights them;
            // runs of them by `kernel::light_run` where it applies.
            probe.enter(Stage::Lighting);
            self.light_pass(o, n);
            probe.enter(Stage::Triangles);
        }
    }

    /// The lighting pass over the `n` vertices of object `o`: each vertex the triangle loop
    /// marked, lit once, by runs of [`kernel::light_run`] where it applies. Out of line:
    /// its locals stay out of the frame of [`Self::object`], which is on the deepest stack of
    /// a frame (on a 16 KB part the stack has no room to spare).
    #[inline(never)]
    pub(crate) fn light_pass<const L: usize>(&mut self, o: &ObjectSetup<'_, '_, S, L>, n: usize) {
        let base = o.base;
        if let Some(quick) = o.quick_light::<C>() {
            let mut runs = true;
            let mut i = 0;
            while i < n {
                if runs {
                    match self.light_quick(o, i, n, quick) {
                        Some(j) => i = j,
                        None => runs = false,
                    }
                    if i >= n {
                        break;
                    }
                }
                if let Some(v) = self.verts.get_mut(base + i) {
                    if v.flags & (LIT | NEEDS_LIGHT) == NEEDS_LIGHT {
                        o.light::<C>(v, i);
                    }
                }
                i += 1;
            }
        } else {
            for (i, v) in self.verts.iter_mut().skip(base).take(n).enumerate() {
                if v.flags & (LIT | NEEDS_LIGHT) == NEEDS_LIGHT {
                    o.light::<C>(v, i);
                }
            }
        }
    }

    /// One run of [`kernel::light_run`] over vertices `i..n` of object `o` (with `quick`
    /// from [`ObjectSetup::quick_light`]): the index of the first vertex it leaves to the
    /// lighting pass (`n` when none), or `None` when it takes none for this object's light and
    /// material. Out of line, and the pass lights the vertices a run leaves outside it: the
    /// deepest stack of a frame does not grow (on a 16 KB part it has no room).
    #[inline(never)]
    pub(crate) fn light_quick<const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        i: usize,
        n: usize,
        quick: QuickLight<'_, S>,
    ) -> Option<usize> {
        let (normals, dir, frac) = quick;
        let m = &o.obj.material;
        let vs = self.verts.get_mut(o.base + i..o.base + n)?;
        let ns = normals.get(i..)?;
        let w = |v: S| v.q16_bits();
        let (ns, dir) = (S::q16_words(ns)?, S::q16_words(&[dir])?[0]);
        let (frac, ambient, diffuse) = (w(frac)?, w(m.ambient)?, w(m.diffuse)?);
        Some(i + kernel::light_run(vs, ns, dir, frac, ambient, diffuse, m.color)?)
    }

    /// The vertex loop's step: the record of position `p` of object `o` ([`vertex_record`]),
    /// with the probe's snapping, stored (room was checked).
    #[inline(always)]
    pub(crate) fn push_vertex<P: Probe, const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        vp: &Viewport,
        g: S,
        p: Vec3<S>,
        stats: &Stats,
        probe: &mut P,
    ) {
        let mut sv = vertex_record(&o.mvp, vp, g, p);
        if sv.flags & PROJECTED != 0 {
            let index = self.verts.len() - stats.color_vertices as usize;
            (sv.x, sv.y) = snapped(probe, index, sv);
        }
        // Cannot fail: room was checked.
        let _ = self.verts.push(sv);
    }

    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    pub(crate) fn clipped<P: Probe, const L: usize>(
        &mut self,
        o: &ObjectSetup<'_, '_, S, L>,
        tri: &[u16; 3],
        vi: [usize; 3],
        flat: bool,
        vp: &Viewport,
        g: S,
        id: u16,
        stats: &mut Stats,
        need: &mut (usize, usize),
        probe: &mut P,
    ) {
        let positions = o.obj.mesh.positions();
        let face = if let Some(c) = C::triangle_id(id) {
            Some(c)
        } else if flat {
            Some(o.face_color::<C>(*tri))
        } else {
            None
        };
        let mut input = [ClipVertex {
            pos: [S::ZERO; 4],
            rgb: [0; 3],
        }; 3];
        for k in 0..3 {
            let v = vi[k];
            let rgb = match face {
                Some(c) => c,
                None => {
                    if self.verts[v].flags & LIT == 0 {
                        o.light::<C>(&mut self.verts[v], tri[k] as usize);
                    }
                    unpack_channels(self.verts[v].color(), C::CHANNEL_MAX)
                }
            };
            input[k] = ClipVertex {
                pos: o.mvp.transform_point(positions[tri[k] as usize]),
                rgb,
            };
        }
        let codes =
            (self.verts[vi[0]].flags | self.verts[vi[1]].flags | self.verts[vi[2]].flags) as u8;
        let poly = clip_triangle(input, codes, g);
        // A textured triangle's polygon once more, with the barycentric weights of its
        // vertices 1 and 2 in place of the colour: the new vertices' texture coordinates.
        let weights = (XV > 0 && o.obj.material.needs_attribute_stores()).then(|| {
            let mut tagged = input;
            for (k, v) in tagged.iter_mut().enumerate() {
                v.rgb = [(k == 1) as u16 * u16::MAX, (k == 2) as u16 * u16::MAX, 0];
            }
            clip_triangle(tagged, codes, g)
        });
        if poly.v.is_empty() {
            stats.outside += 1;
            return;
        }
        stats.clipped += 1;
        need.0 += poly.v.len();
        if self.verts.len() + poly.v.len() > VERTS {
            need.1 += poly.v.len() - 2;
            return;
        }
        let first = self.verts.len();
        for (pi, v) in poly.v.iter().enumerate() {
            let rgb = if face.is_some() {
                pack_flat_channels(v.rgb, C::CHANNEL_MAX)
            } else {
                pack_channels(v.rgb, C::CHANNEL_MAX)
            };
            match vp.project_out_of_line(v.pos, rgb) {
                Some(mut sv) => {
                    sv.flags |= PROJECTED | LIT;
                    let index = self.verts.len() - stats.color_vertices as usize;
                    (sv.x, sv.y) = snapped(probe, index, sv);
                    if let Some(w) = weights.as_ref().and_then(|w| w.v.get(pi)) {
                        self.clipped_extra(o, tri, w.rgb, &sv);
                    }
                    let _ = self.verts.push(sv);
                }
                None => {
                    // w ≤ 0 after near clipping can only come from rounding at w ≈ 0 with a
                    // degenerate near plane; skip the polygon.
                    self.verts.truncate(first);
                    stats.invalid += 1;
                    return;
                }
            }
        }
        for k in 1..poly.v.len() - 1 {
            let t = [first, first + k, first + k + 1];
            match facing(&self.verts[t[0]], &self.verts[t[1]], &self.verts[t[2]]) {
                Facing::Degenerate => stats.degenerate += 1,
                Facing::Back => stats.culled += 1,
                Facing::Front => {
                    // Every polygon vertex has the face colour: the first one carries it.
                    let mut v = t.map(|v| v as u16);
                    if face.is_some() {
                        v[0] |= FLAT_BIT;
                    }
                    self.push_tri(v, stats, need);
                }
            }
        }
    }

    /// Buckets a triangle by its first covered row, or counts it as empty or off-screen.
    /// Returns whether the triangle is stored (or counted as needed when the store is full).
    pub(crate) fn push_tri(
        &mut self,
        v: [u16; 3],
        stats: &mut Stats,
        need: &mut (usize, usize),
    ) -> bool {
        let t = TriRecord { v };
        // The three positions only (not 12-byte vertex copies through `array::map`, which
        // stays a call on a Cortex-M0).
        let [i, j, k] = t.indices();
        let (a, b, c) = (&self.verts[i], &self.verts[j], &self.verts[k]);
        let mut bins = Bins {
            store: &mut self.tris,
            heads: &mut self.heads,
            starts: &mut self.starts,
            view: (self.vw, self.vh),
        };
        let mut counts = CullCounts::default();
        let stored = bins.push(t, [a, b, c], &mut counts, &mut need.1);
        stats.add_culling(&counts);
        stored
    }
}

/// [`Error::Light`] for a light with an invalid number, [`Error::Fog`] for a fog without
/// valid numbers and `near < far`, [`Error::Tone`] for an invalid tone map. Out of line: the
/// deepest stack of a frame (on a 16 KB part) does not hold its locals.
#[inline(never)]
fn lights_valid<S: Scalar, E, const L: usize>(scene: &Scene<'_, S, L>) -> Result<(), Error<E>> {
    if scene.fog().is_some_and(|f| !f.is_valid()) {
        return Err(Error::Fog);
    }
    if let Some(t) = scene.tone() {
        if !t.is_valid() {
            return Err(Error::Tone { object: None });
        }
    }
    // A light is the whole scene's: one that is not a valid number is refused like a fog or
    // a tone map (it once made every object a counted skip, an empty frame that looked `Ok`).
    if let Some(index) = scene
        .lights
        .iter()
        .position(|l| !l.direction.iter().all(|v| v.is_valid()))
    {
        return Err(Error::Light {
            index,
            point: false,
        });
    }
    if let Some(index) = scene.point_lights().iter().position(|l| !l.is_valid()) {
        return Err(Error::Light { index, point: true });
    }
    Ok(())
}

/// The vertex store's record of position `p` transformed by `mvp`: its outcode (guard band
/// `g`) and flags, and, unless it is to be clipped, invalid or has w ≤ 0, its projection on
/// `vp` (before the probe's snapping) with no colour.
#[inline(always)]
pub(crate) fn vertex_record<S: Scalar>(
    mvp: &Mat4<S>,
    vp: &Viewport,
    g: S,
    p: Vec3<S>,
) -> ScreenVertex {
    vertex_record_keep(mvp, vp, g, p, u8::MAX)
}

/// [`vertex_record`] with only the outcode bits in `keep` (a shadow volume's vertices leave out
/// [`crate::geometry::clip::FAR`]: beyond the far plane they are projected, their depth flattened onto
/// it).
#[inline(always)]
pub(crate) fn vertex_record_keep<S: Scalar>(
    mvp: &Mat4<S>,
    vp: &Viewport,
    g: S,
    p: Vec3<S>,
    keep: u8,
) -> ScreenVertex {
    let clip = mvp.transform_point(p);
    let mut flags = (outcode(clip, g) & keep) as u16;
    let mut sv = ScreenVertex::default();
    if !clip.iter().all(|v| v.is_valid()) {
        flags |= INVALID;
    } else if flags & NEEDS_CLIP as u16 == 0 {
        if let Some(v) = vp.project(clip, [0; 3]) {
            sv = v;
            flags |= PROJECTED;
        }
    }
    sv.flags = flags;
    sv
}

/// The snapped position of a projected vertex, as the probe wants it, within the coordinate
/// range.
pub(crate) fn snapped<P: Probe>(probe: &mut P, index: usize, v: ScreenVertex) -> (i16, i16) {
    let (x, y) = probe.snap(index as u32, v.x as i32, v.y as i32);
    (
        x.clamp(-COORD_LIMIT, COORD_LIMIT) as i16,
        y.clamp(-COORD_LIMIT, COORD_LIMIT) as i16,
    )
}

/// The vertex kernel ([`kernel::project_run`]) over the Q16.16 words of `m`, `ps` and `g`: the
/// length of the run it stored, 0 for a number type that is not Q16.16.
#[inline(always)]
pub(crate) fn project_run<S: Scalar, const V: usize>(
    m: &[[S; 4]; 4],
    ps: &[[S; 3]],
    g: S,
    sx: u32,
    sy: u32,
    out: &mut Vec<ScreenVertex, V>,
) -> usize {
    let (Some(mw), Some(pw), Some(gw)) = (S::q16_words(&m[..]), S::q16_words(ps), g.q16_bits())
    else {
        return 0;
    };
    match <&[[i32; 4]; 4]>::try_from(mw) {
        Ok(mw) => kernel::project_run(mw, pw, gw, sx, sy, out),
        Err(_) => 0,
    }
}
