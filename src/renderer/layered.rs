//! The layered frame's geometry stage ([`crate::FrameOptions::layered`]): its checks, its
//! object groups in the order the strip pass tells them apart by (receivers, other opaque
//! objects, shadow polygons or volumes, outlines, translucent objects), and its lists' needs.
//! The layered rows themselves are the raster stage's (`raster::layers`).

use crate::error::{LayerError, MAX_TRANSLUCENT};
use crate::kernel::records::first_pixel;
use crate::num::scalar::Scalar;
use crate::raster::layers::{check_adjacency, check_creases, check_volume, set_blend, Layers};
use crate::raster::shadow::{blob_disc, Edges, Layering, ShadowMethod, BLOB_FAN};
use crate::raster::volume::{Lines, Pick};
use crate::renderer::*;
use crate::scene::color::TargetColor;
use crate::scene::shade::Material;
use crate::scene::{Object, Scene};

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
        const ZL: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>
{
    /// Measures what a layered frame of `scene` needs ([`Needs`], with the `layers`' lists:
    /// [`Needs::receivers`] for `RA`, [`Needs::overlays`] for `PA`, and the vertices the
    /// shadow polygons, volumes and outlines add): runs the layered frame's geometry stage
    /// (as [`crate::FrameOptions::layered`] does, whatever the overflow policy) and leaves no
    /// frame prepared. For sizing a device's renderer and layers on the host, as
    /// [`Renderer::needs`] for a plain frame; check with
    /// `worst.fits(&Device::CAPACITY.with_layers(RA, PA))`.
    ///
    /// # Errors
    ///
    /// As [`crate::FrameOptions::layered`] for a layering that cannot be drawn, and as
    /// [`Renderer::needs`] when this renderer's stores are too small to measure the frame
    /// exactly.
    pub fn needs_layered<const L: usize, const RA: usize, const PA: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        layering: &Layering<'_, S>,
        layers: &mut Layers<W, LINES, RA, PA>,
    ) -> Result<Needs, Error<core::convert::Infallible>> {
        let policy = self.ras.overflow;
        self.ras.overflow = OverflowPolicy::DrawWhatFits;
        let result = self.geometry_layered(scene, layering, layers, &mut NoProbe);
        self.ras.overflow = policy;
        self.ras.next_row = self.geo.vh;
        result?;
        self.measured()
    }

    /// The geometry stage of a layered frame: the receivers' objects first, then the other
    /// opaque ones, the casters' shadow polygons and the translucent objects, each group's
    /// vertices contiguous in the store (which is how the strip pass tells them apart).
    pub(crate) fn geometry_layered<
        E,
        P: Probe,
        const L: usize,
        const RA: usize,
        const PA: usize,
    >(
        &mut self,
        scene: &Scene<'_, S, L>,
        layering: &Layering<'_, S>,
        layers: &mut Layers<W, LINES, RA, PA>,
        probe: &mut P,
    ) -> Result<Stats, Error<E>> {
        if ZL == 0 {
            return Err(Error::NoDepthLines);
        }
        let n = scene.objects.len();
        let bad = |index: usize| Error::Layers(LayerError::NoSuchObject { index });
        let outlined = layering.outline.map_or(&[][..], |o| o.objects);
        for &i in layering
            .receivers
            .iter()
            .chain(layering.casters)
            .chain(outlined)
        {
            if i >= n {
                return Err(bad(i));
            }
        }
        let shadow = match &layering.shadow {
            Some(s) => Some((s.matrix().ok_or(Error::Layers(LayerError::Shadow))?, s)),
            None => None,
        };
        if let Some(v) = &layering.volume {
            if shadow.is_some() {
                return Err(Error::Layers(LayerError::TwoShadows));
            }
            check_volume(scene, layering.casters, v, 8 * W * LINES)?;
        }
        if let Some(o) = &layering.outline {
            check_adjacency(scene, o.objects, o.adjacency, 8 * W * LINES)?;
            check_creases(scene, o)?;
        }
        let translucent = scene.objects.iter().any(|o| o.material.alpha < 255);
        // (A [`crate::color::TriangleId`] target records the opaque triangles only: nothing blends.)
        if (shadow.is_some() || layering.volume.is_some() || translucent)
            && C::from_channels([0; 3]).channels().is_none()
            && C::triangle_id(0).is_none()
        {
            return Err(Error::Layers(LayerError::Blending));
        }
        if let Some(i) = scene
            .objects
            .iter()
            .position(|o| o.material.alpha < 255 && o.material.needs_attribute_stores())
        {
            return Err(Error::Layers(LayerError::Translucent { object: i }));
        }
        if scene
            .objects
            .iter()
            .filter(|o| o.material.alpha < 255)
            .count()
            > MAX_TRANSLUCENT
        {
            return Err(Error::Layers(LayerError::TooManyTranslucent));
        }
        if let Some((_, s)) = &shadow {
            for &i in layering.receivers {
                if scene.objects[i].material.alpha == 255 && !s.holds(&scene.objects[i]) {
                    return Err(Error::Layers(LayerError::OffPlane { object: i }));
                }
            }
        }
        let receiver = |i: usize| {
            shadow.is_some()
                && scene.objects[i].material.alpha == 255
                && layering.receivers.contains(&i)
        };
        self.frame_start();
        let c = self.geo.frame_begin(scene, true)?;
        let mut f = crate::geometry::Frame::default();
        for (i, o) in scene.objects.iter().enumerate() {
            if receiver(i) {
                self.geo.frame_object(&c, &mut f, scene, o, i, probe)?;
            }
        }
        let end = |r: &Self| r.geo.verts.len().min(u16::MAX as usize) as u16;
        layers.bounds[0] = end(self);
        for (i, o) in scene.objects.iter().enumerate() {
            if !receiver(i) && o.material.alpha == 255 {
                self.geo.frame_object(&c, &mut f, scene, o, i, probe)?;
            }
        }
        layers.bounds[1] = end(self);
        layers.shadow = ([0; 3], 0);
        layers.blob = false;
        layers.volume = false;
        let marks = layers.stencil.as_flattened_mut();
        if let Some(v) = &layering.volume {
            for (k, &i) in layering.casters.iter().enumerate() {
                let adjacency = v.adjacency[k].table();
                let o = &scene.objects[i];
                let reach = crate::raster::volume::volume_reach(
                    &scene.camera,
                    (self.geo.vw, self.geo.vh),
                    o,
                    v.reach,
                );
                self.geo
                    .volume_object(&c, &mut f, o, adjacency, v, reach, marks, probe);
            }
            layers.volume = true;
            set_blend::<C, W, LINES, RA, PA>(layers, v.color, v.alpha);
        }
        if let Some((m, s)) = shadow {
            // Flat and unlit: only the coverage of these triangles is used.
            let material = Material::matte(s.color, S::ONE, S::ZERO).flat();
            let disc = blob_disc::<S>();
            let blob = s.method == ShadowMethod::Blob;
            for (i, o) in scene.objects.iter().enumerate() {
                if !layering.casters.contains(&i) {
                    continue;
                }
                if !blob {
                    // The caster's triangles flattened onto the plane.
                    let flat = Object {
                        mesh: o.mesh,
                        transform: m.mul(&o.transform),
                        material,
                    };
                    self.geo.frame_object(&c, &mut f, scene, &flat, i, probe)?;
                } else if let Some(rings) = s.blob_rings(&m, o) {
                    let mesh = crate::Mesh::new(&disc, &BLOB_FAN)
                        .map_err(|_| Error::Layers(LayerError::Shadow))?;
                    for transform in rings {
                        let ring = Object {
                            mesh,
                            transform,
                            material,
                        };
                        self.geo.frame_object(&c, &mut f, scene, &ring, i, probe)?;
                    }
                }
            }
            let alpha = if blob { s.blob_ring_alpha() } else { s.alpha };
            set_blend::<C, W, LINES, RA, PA>(layers, s.color, alpha);
            layers.blob = blob;
        }
        layers.bounds[2] = end(self);
        if let Some(o) = &layering.outline {
            let cam = &scene.camera;
            let eye = match cam.projection {
                crate::Projection::Orthographic { .. } => {
                    let r = cam.view.m[2];
                    ([r[0], r[1], r[2]], true)
                }
                _ => (cam.eye, false),
            };
            layers.see_through = o.see_through;
            let marks = layers.stencil.as_flattened_mut();
            for (k, &i) in o.objects.iter().enumerate() {
                let obj = &scene.objects[i];
                let pick = match o.edges {
                    Edges::Silhouette => Pick::Silhouette,
                    Edges::Crease(tables) => Pick::Crease(tables[k]),
                    Edges::All => Pick::All,
                };
                let lines = Lines {
                    adjacency: o.adjacency[k].table(),
                    pick,
                    see_through: o.see_through,
                    color: o.color,
                    eye,
                };
                self.geo
                    .outline_object(&c, &mut f, obj, lines, marks, probe);
            }
        }
        layers.bounds[3] = end(self);
        layers.translucent.clear();
        for (i, o) in scene.objects.iter().enumerate() {
            if o.material.alpha < 255 {
                self.geo.frame_object(&c, &mut f, scene, o, i, probe)?;
                // Cannot fail: counted above.
                let _ = layers.translucent.push((end(self), o.material.alpha));
            }
        }
        let overflow = self.ras.overflow;
        let stats = self
            .geo
            .frame_end(scene, &c, &mut f, usize::MAX, overflow, Self::CAPACITY)?;
        self.frame_ready(scene, stats);
        // Each list's most triangles on one row, against its capacity: all three at once.
        let [receivers, overlays, opaque] =
            [0u8, 1, 2].map(|list| self.layer_overlap(&layers.bounds, list));
        self.ras.stats.max_receivers = receivers as u32;
        self.ras.stats.max_overlays = overlays as u32;
        self.ras.stats.max_active = opaque as u32;
        let needed = Needs::from_stats(&self.ras.stats);
        let capacity = Self::CAPACITY.with_layers(RA, PA);
        if self.ras.overflow == OverflowPolicy::Error
            && (receivers > RA || overlays > PA || opaque > ACTIVE)
        {
            self.ras.next_row = self.geo.vh;
            return Err(Error::Shortfall(Shortfall {
                needed,
                capacity,
                exact: true,
                skipped: 0,
            }));
        }
        layers.receivers.clear();
        layers.post.clear();
        layers.skipped = 0;
        Ok(self.ras.stats)
    }

    /// The most triangles of list `list` (0: receivers, 1: shadow, outline and translucent
    /// triangles, 2: the other opaque ones) covering one row, by a sweep over the row-change counts (in `starts`, free
    /// once the buckets are sorted).
    fn layer_overlap(&mut self, bounds: &[u16; 4], list: u8) -> usize {
        let vh = self.geo.vh;
        self.geo.starts[..vh].fill(0);
        for t in self.geo.tris.iter() {
            let i = t.v[1] as usize;
            let group = if i < bounds[0] as usize {
                0
            } else if i < bounds[1] as usize {
                2
            } else {
                1
            };
            if group != list {
                continue;
            }
            let [a, b, c] = t.indices().map(|k| self.geo.verts[k].y as i32);
            let first = first_pixel(a.min(b).min(c)).clamp(0, vh as i32) as usize;
            let end = first_pixel(a.max(b).max(c)).clamp(0, vh as i32) as usize;
            if first < end {
                self.geo.starts[first] += 1;
                if end < vh {
                    self.geo.starts[end] -= 1;
                }
            }
        }
        let (mut cur, mut max) = (0i32, 0i32);
        for &s in &self.geo.starts[..vh] {
            cur += s as i32;
            max = max.max(cur);
        }
        max as usize
    }
}
