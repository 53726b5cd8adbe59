//! Shadow volumes and outlines: the triangles a layered frame adds for them, built in the
//! geometry stage from each mesh's adjacency ([`crate::mesh::mesh_adjacency`]).
//!
//! - A **shadow volume** is a caster's faces turned away from the light (the near cap), the
//!   same faces moved away from the light (the far cap) and one quad per silhouette edge
//!   (an edge between a face turned away from the light and one turned toward it, or an open
//!   edge) joining the two. The strip pass counts, per pixel, the volume faces behind the
//!   visible surface (+1 seen from behind, −1 seen from the front: z-fail), and a non-zero
//!   count is a shadow.
//! - An **outline** is a 1 px line along each contour edge (between a face turned toward the
//!   eye and one turned away, or an open edge of a face turned toward it), drawn as a quad one
//!   pixel across on the minor axis, so that each column (or row) it crosses gets one pixel.
//!
//! Which way each face turns is found in the object's own space (the light and the eye moved
//! there once per object, in f64): one cross and one dot product per face, marked in the stencil
//! lines' bits (free during the geometry stage). Volume faces are neither culled nor sorted:
//! each is stored turned toward the eye, and which way it was turned is kept in the order of its
//! vertex indices (see [`volume_sign`]).

use crate::geometry::clip::{clip_triangle, ClipVertex, FAR, GUARD, NEAR, NEEDS_CLIP};
use crate::geometry::project::{pack_flat_channels, COORD_LIMIT};
use crate::geometry::stores::Stores;
use crate::geometry::{snapped, vertex_record_keep, Frame, FrameConst, INVALID, PROJECTED};
use crate::kernel::records::{facing, Facing, ScreenVertex, TriRecord};
use crate::num::math::{cross, dot, normalize, scale, sub, Mat4, Vec3};
use crate::num::scalar::Scalar;
use crate::raster::shadow::{ShadowLight, VolumeShadow};
use crate::raster::FLAT_BIT;
use crate::scene::adjacency::NO_NEIGHBOUR;
use crate::scene::color::TargetColor;
use crate::scene::mesh::Mesh;
use crate::scene::Object;
use crate::stats::Probe;

/// One object's outline: its adjacency table, which edges, whether hidden ones show, the
/// colour (8 bits per channel) and the eye in world space (a point, or a direction toward the
/// eye when `.1`: an orthographic camera).
pub(crate) struct Lines<'a, S> {
    pub(crate) adjacency: &'a [[u16; 3]],
    pub(crate) pick: Pick<'a>,
    pub(crate) see_through: bool,
    pub(crate) color: [u8; 3],
    pub(crate) eye: (Vec3<S>, bool),
}

/// Which edges an outline draws for one object ([`crate::shadow::Edges`] with the object's crease
/// table).
#[derive(Copy, Clone)]
pub(crate) enum Pick<'a> {
    Silhouette,
    Crease(&'a [u8]),
    All,
}

impl Pick<'_> {
    /// Whether edge `e` of triangle `t` (turned toward the eye when `front`) is drawn from `t`,
    /// with `across` the neighbour across it and whether that one is turned toward the eye
    /// (`None`: an open edge). Each edge is drawn once: a contour edge from its face turned
    /// toward the eye, an edge between two faces turned the same way from the lower index.
    /// Without `see_through`, only edges of faces turned toward the eye.
    pub(crate) fn draws(
        self,
        t: usize,
        e: usize,
        front: bool,
        across: Option<(usize, bool)>,
        see_through: bool,
    ) -> bool {
        let contour = front && across.is_none_or(|(_, f)| !f);
        let inner = match across {
            Some((u, f)) => f == front && t < u && (front || see_through),
            // An open edge of a face turned away (the contour has the other open edges).
            None => !front && see_through,
        };
        match self {
            Pick::Silhouette => contour,
            Pick::Crease(bits) => contour || (inner && crease_bit(bits, t, e)),
            Pick::All => contour || inner,
        }
    }
}

/// Whether bit `3·t + e` of crease table `bits` is set (false past its end).
#[inline]
pub(crate) fn crease_bit(bits: &[u8], t: usize, e: usize) -> bool {
    let bit = 3 * t + e;
    bits.get(bit / 8).is_some_and(|b| b & (1 << (bit % 8)) != 0)
}

/// A volume triangle's sign from its stored vertex order: −1 (255) when the first index is
/// the largest (stored turned around: the face was seen from behind), else +1.
#[inline(always)]
pub(crate) fn volume_sign(t: &TriRecord) -> u8 {
    let [a, b, c] = t.indices();
    if a > b && a > c {
        255
    } else {
        1
    }
}

/// The point or direction faces are tested against (toward it: "turned toward").
#[derive(Copy, Clone)]
enum Toward<S> {
    Direction(Vec3<S>),
    Point(Vec3<S>),
}

/// `toward` (in world space) moved into the space of the object with transform `m` (its upper
/// 3×3 inverted in f64, once per object), and whether `m` mirrors. `None` for a transform
/// that cannot be inverted.
fn into_object<S: Scalar>(m: &Mat4<S>, toward: Toward<S>) -> Option<(Toward<S>, bool)> {
    let a = m.m.map(|r| r.map(|v| v.to_f64()));
    let c = |i: usize, j: usize| {
        let (i1, i2, j1, j2) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
        a[j1][i1] * a[j2][i2] - a[j1][i2] * a[j2][i1]
    };
    // inv[i][j] = cofactor(j, i) / det.
    let det = a[0][0] * c(0, 0) + a[0][1] * c(1, 0) + a[0][2] * c(2, 0);
    if !det.is_finite() || det.abs() < 1e-12 {
        return None;
    }
    let apply = |v: [f64; 3]| -> Vec3<S> {
        core::array::from_fn(|i| S::from_f64((0..3).map(|j| c(i, j) * v[j]).sum::<f64>() / det))
    };
    let f = |v: Vec3<S>| v.map(|x| x.to_f64());
    let moved = match toward {
        Toward::Direction(d) => Toward::Direction(apply(f(d))),
        Toward::Point(p) => {
            let p = f(p);
            Toward::Point(apply([p[0] - a[0][3], p[1] - a[1][3], p[2] - a[2][3]]))
        }
    };
    Some((moved, det < 0.0))
}

/// How far `obj`'s shadow volume is extruded: `reach`, or less where less still passes every
/// point the camera can see (the volume is then closed beyond every visible receiver, so the
/// image is the same), so that a reach far beyond the scene (30 000 units) does not carry the
/// far cap out of the number type's range (Q16.16 clip coordinates saturate near 32 768).
///
/// Every visible point lies within `R` of the eye (the far plane's corner distance, `vw/vh`
/// the aspect), and a caster vertex `w` shadows only points along one ray from it, so a reach
/// of `|w − eye| + R` suffices; bounded over the object by its transformed centre and radius.
/// In f64, once per caster, and only when `reach > R` (no scan of the mesh otherwise).
pub(crate) fn volume_reach<S: Scalar>(
    camera: &crate::Camera<S>,
    (vw, vh): (usize, usize),
    obj: &Object<'_, S>,
    reach: S,
) -> S {
    // Every visible point is within the far distance along the view axis and R ≥ far: a reach
    // up to `far` needs nothing more (one comparison in S, no f64 work: the usual case).
    let far = camera.projection.near_far().1;
    if reach <= far {
        return reach;
    }
    let aspect = vw as f64 / vh.max(1) as f64;
    let r = reach.to_f64();
    let sq = |v: f64| v * v;
    let view = match camera.projection {
        crate::Projection::Perspective { fov_y, far, .. } => {
            let t = libm::tan(0.5 * fov_y.to_f64());
            far.to_f64() * libm::sqrt(1.0 + sq(t) * (1.0 + sq(aspect)))
        }
        crate::Projection::Orthographic { height, near, far } => {
            let h = 0.5 * height.to_f64();
            let z = near.to_f64().abs().max(far.to_f64().abs());
            libm::sqrt(sq(z) + sq(h) * (1.0 + sq(aspect)))
        }
    };
    if r <= view || !view.is_finite() {
        return reach;
    }
    let m = &obj.transform.m;
    // The largest column norm of the linear part bounds how far it moves a unit vector.
    let stretch = (0..3)
        .map(|c| libm::sqrt((0..3).map(|k| sq(m[k][c].to_f64())).sum::<f64>()))
        .fold(0.0, f64::max);
    let radius = obj
        .mesh
        .positions()
        .iter()
        .map(|p| libm::sqrt(p.iter().map(|v| sq(v.to_f64())).sum::<f64>()))
        .fold(0.0, f64::max);
    let centre = libm::sqrt(
        (0..3)
            .map(|k| sq(m[k][3].to_f64() - camera.eye[k].to_f64()))
            .sum(),
    );
    // A margin over the rounding of the bound into `S`.
    let bound = (centre + stretch * radius + view) * (1.0 + 1e-3) + 1e-3;
    if bound.is_finite() && bound < r {
        S::from_f64(bound)
    } else {
        reach
    }
}

/// Marks in `marks` (bit `t` per triangle `t`) the faces of `mesh` turned toward `toward`
/// (object space; `flip` for a mirroring transform). One cross and one dot product per face.
fn mark_faces<S: Scalar>(mesh: &Mesh<'_, S>, toward: Toward<S>, flip: bool, marks: &mut [u8]) {
    let p = mesh.positions();
    for (t, tri) in mesh.indices().iter().enumerate() {
        let [a, b, c] = tri.map(|i| p[i as usize]);
        let n = cross(sub(b, a), sub(c, a));
        let d = match toward {
            Toward::Direction(l) => dot(n, l),
            Toward::Point(q) => dot(n, sub(q, a)),
        };
        let on = (d > S::ZERO) != flip;
        let (byte, bit) = (t / 8, 1u8 << (t % 8));
        if on {
            marks[byte] |= bit;
        } else {
            marks[byte] &= !bit;
        }
    }
}

#[inline(always)]
fn marked(marks: &[u8], t: usize) -> bool {
    marks[t / 8] & (1 << (t % 8)) != 0
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
    /// The shadow volume of `obj` from `v`'s light, extruded by `reach` (checked valid and
    /// positive; [`volume_reach`] of `v.reach`): its vertices (each mesh vertex and its extruded copy, side by side) and its
    /// triangles, stored turned toward the eye. `marks` holds a bit per triangle (checked).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn volume_object<P: Probe>(
        &mut self,
        c: &FrameConst<S>,
        f: &mut Frame,
        obj: &Object<'_, S>,
        adjacency: &[[u16; 3]],
        v: &VolumeShadow<'_, S>,
        reach: S,
        marks: &mut [u8],
        probe: &mut P,
    ) {
        let light = &v.light;
        let mesh = obj.mesh;
        let (positions, tris) = (mesh.positions(), mesh.indices());
        let toward = match *light {
            ShadowLight::Directional(d) => Toward::Direction(d),
            ShadowLight::Point(p) => Toward::Point(p),
        };
        let Some((local, flip)) = into_object(&obj.transform, toward) else {
            f.stats.invalid += tris.len() as u32;
            return;
        };
        mark_faces(&mesh, local, flip, marks);
        let n = positions.len();
        let base = self.verts.len();
        f.need.0 += 2 * n;
        if base + 2 * n > VERTS {
            // Counted (the frame's shortfall names it); nothing of it is stored.
            f.need.1 += tris.len();
            return;
        }
        let away = match *light {
            ShadowLight::Directional(d) => Some(scale(normalize(d), -reach)),
            ShadowLight::Point(_) => None,
        };
        let extrude = |w: Vec3<S>| match (away, *light) {
            (Some(a), _) => [w[0] + a[0], w[1] + a[1], w[2] + a[2]],
            (None, ShadowLight::Point(q)) => {
                let d = scale(normalize(sub(w, q)), reach);
                [w[0] + d[0], w[1] + d[1], w[2] + d[2]]
            }
            (None, ShadowLight::Directional(_)) => w,
        };
        let world = |p: Vec3<S>| {
            let w = obj.transform.transform_point(p);
            [w[0], w[1], w[2]]
        };
        let keep = !FAR;
        // The near cap's vertices through the object's own transform (as its triangles are
        // drawn: the same records, so the cap meets the object's pixels exactly).
        let mvp = c.pv.mul(&obj.transform);
        for &p in positions {
            let w = world(p);
            let near = vertex_record_keep(&mvp, &c.vp, c.g, p, keep);
            self.push_snapped(near, f, probe);
            let far = vertex_record_keep(&c.pv, &c.vp, c.g, extrude(w), keep);
            self.push_snapped(far, f, probe);
        }
        // The clip-space position of volume vertex record `r`, for the clipped path.
        let clip_of = |r: usize| {
            let k = r - base;
            let p = positions[k / 2];
            if k % 2 == 1 {
                c.pv.transform_point(extrude(world(p)))
            } else {
                mvp.transform_point(p)
            }
        };
        let at = |i: u16, extruded: usize| base + 2 * i as usize + extruded;
        for (t, tri) in tris.iter().enumerate() {
            if marked(marks, t) {
                continue;
            }
            let [a, b, cc] = *tri;
            // Near cap (turned toward the light: the volume's outside there faces it), far cap.
            self.volume_tri(c, f, [at(a, 0), at(cc, 0), at(b, 0)], &clip_of, probe);
            self.volume_tri(c, f, [at(a, 1), at(b, 1), at(cc, 1)], &clip_of, probe);
            let adj = adjacency.get(t).copied().unwrap_or([NO_NEIGHBOUR; 3]);
            for e in 0..3 {
                let u = adj[e] as usize;
                if u < tris.len() && !marked(marks, u) {
                    continue;
                }
                let (i, j) = (tri[e], tri[(e + 1) % 3]);
                self.volume_tri(c, f, [at(i, 0), at(j, 0), at(j, 1)], &clip_of, probe);
                self.volume_tri(c, f, [at(i, 0), at(j, 1), at(i, 1)], &clip_of, probe);
            }
        }
    }

    /// Stores volume triangle `v` (vertex records, in the volume's outward winding), clipped
    /// at the near plane and the guard band where it crosses them (not at the far plane:
    /// depth there is flattened onto it), each part turned toward the eye with its sign kept.
    fn volume_tri<P: Probe>(
        &mut self,
        c: &FrameConst<S>,
        f: &mut Frame,
        v: [usize; 3],
        clip_of: &impl Fn(usize) -> [S; 4],
        probe: &mut P,
    ) {
        let fl = v.map(|i| self.verts[i].flags);
        if (fl[0] | fl[1] | fl[2]) & INVALID != 0 {
            f.stats.invalid += 1;
            return;
        }
        if fl[0] & fl[1] & fl[2] & 0x3f != 0 {
            f.stats.outside += 1;
            return;
        }
        if (fl[0] | fl[1] | fl[2]) & NEEDS_CLIP as u16 == 0 {
            self.push_signed(v, f);
            return;
        }
        let input = v.map(|i| ClipVertex {
            pos: clip_of(i),
            rgb: [0; 3],
        });
        let codes = (fl[0] | fl[1] | fl[2]) as u8 & (NEAR | GUARD);
        let poly = clip_triangle(input, codes, c.g);
        if poly.v.is_empty() {
            f.stats.outside += 1;
            return;
        }
        f.need.0 += poly.v.len();
        if self.verts.len() + poly.v.len() > VERTS {
            f.need.1 += poly.v.len() - 2;
            return;
        }
        let first = self.verts.len();
        for p in &poly.v {
            match c.vp.project_out_of_line(p.pos, [0; 3]) {
                Some(mut sv) => {
                    sv.flags |= PROJECTED;
                    self.push_snapped(sv, f, probe);
                }
                None => {
                    self.verts.truncate(first);
                    f.stats.invalid += 1;
                    return;
                }
            }
        }
        for k in 1..poly.v.len() - 1 {
            self.push_signed([first, first + k, first + k + 1], f);
        }
    }

    /// Stores vertex record `v` (room was checked), a projected one at the position the probe
    /// snaps it to (as every vertex of the frame: comparison tools replay one number type's
    /// screen geometry in another).
    fn push_snapped<P: Probe>(&mut self, mut v: ScreenVertex, f: &Frame, probe: &mut P) {
        if v.flags & PROJECTED != 0 {
            let index = self.verts.len() - f.stats.color_vertices as usize;
            (v.x, v.y) = snapped(probe, index, v);
        }
        let _ = self.verts.push(v);
    }

    /// Stores triangle `v` turned toward the eye: as it is (first index the smallest) when it
    /// faces the eye, else reversed (first index the largest), so that [`volume_sign`] reads
    /// which. Flat (its first vertex's colour, unused: only coverage and depth count).
    fn push_signed(&mut self, v: [usize; 3], f: &mut Frame) {
        let [a, b, cc] = v.map(|i| &self.verts[i]);
        let (mut v, back) = match facing(a, b, cc) {
            Facing::Degenerate => {
                f.stats.degenerate += 1;
                return;
            }
            Facing::Front => (v, false),
            Facing::Back => ([v[0], v[2], v[1]], true),
        };
        // Rotate (keeps the winding): the smallest index first when front, the largest when
        // back.
        let pick = if back {
            (0..3).max_by_key(|&k| v[k]).unwrap_or(0)
        } else {
            (0..3).min_by_key(|&k| v[k]).unwrap_or(0)
        };
        v.rotate_left(pick);
        let rec = [v[0] as u16 | FLAT_BIT, v[1] as u16, v[2] as u16];
        self.push_tri(rec, &mut f.stats, &mut f.need);
    }

    /// The outline of `obj` in `lines`: the edges its pick chooses ([`Pick::draws`]), two
    /// triangles per edge, one pixel across. `marks` holds a bit per triangle (checked).
    pub(crate) fn outline_object<P: Probe>(
        &mut self,
        c: &FrameConst<S>,
        f: &mut Frame,
        obj: &Object<'_, S>,
        lines: Lines<'_, S>,
        marks: &mut [u8],
        probe: &mut P,
    ) {
        let Lines {
            adjacency,
            pick,
            see_through,
            color,
            eye,
        } = lines;
        let mesh = obj.mesh;
        let (positions, tris) = (mesh.positions(), mesh.indices());
        let toward = if eye.1 {
            Toward::Direction(eye.0)
        } else {
            Toward::Point(eye.0)
        };
        let Some((local, flip)) = into_object(&obj.transform, toward) else {
            f.stats.invalid += tris.len() as u32;
            return;
        };
        mark_faces(&mesh, local, flip, marks);
        let mvp = c.pv.mul(&obj.transform);
        let rgb = pack_flat_channels(
            C::vertex_channels(color.map(|v| (v as u16) << 8)),
            C::CHANNEL_MAX,
        );
        for (t, tri) in tris.iter().enumerate() {
            let front = marked(marks, t);
            if !front && !see_through {
                continue;
            }
            let adj = adjacency.get(t).copied().unwrap_or([NO_NEIGHBOUR; 3]);
            for e in 0..3 {
                let u = adj[e] as usize;
                let across = (u < tris.len()).then(|| (u, marked(marks, u)));
                if !pick.draws(t, e, front, across, see_through) {
                    continue;
                }
                let (i, j) = (tri[e] as usize, tri[(e + 1) % 3] as usize);
                let ends = [i, j].map(|k| mvp.transform_point(positions[k]));
                self.outline_edge(c, f, ends, rgb, probe);
            }
        }
    }

    /// One outline edge between clip-space points `ends`: clipped to the near plane and the
    /// guard band, projected, and stored as a quad one pixel across its minor axis.
    fn outline_edge<P: Probe>(
        &mut self,
        c: &FrameConst<S>,
        f: &mut Frame,
        ends: [[S; 4]; 2],
        rgb: [u16; 3],
        probe: &mut P,
    ) {
        let [p, q] = ends;
        if !p.iter().chain(q.iter()).all(|v| v.is_valid()) {
            f.stats.invalid += 1;
            return;
        }
        // Liang–Barsky against z ≥ 0 and |x|, |y| ≤ g·w: the distances of both ends.
        let d = |v: &[S; 4]| {
            let gw = c.g * v[3];
            [v[2], gw + v[0], gw - v[0], gw + v[1], gw - v[1]]
        };
        let (dp, dq) = (d(&p), d(&q));
        let (mut t0, mut t1) = (S::ZERO, S::ONE);
        for k in 0..5 {
            let (a, b) = (dp[k], dq[k]);
            if a < S::ZERO && b < S::ZERO {
                f.stats.outside += 1;
                return;
            }
            if a < S::ZERO {
                t0 = t0.max(a / (a - b));
            } else if b < S::ZERO {
                t1 = t1.min(a / (a - b));
            }
        }
        if t0 >= t1 {
            f.stats.outside += 1;
            return;
        }
        let lerp = |t: S| core::array::from_fn(|k| p[k] + t * (q[k] - p[k]));
        let (Some(mut a), Some(mut b)) = (
            c.vp.project_out_of_line(lerp(t0), [0; 3]),
            c.vp.project_out_of_line(lerp(t1), [0; 3]),
        ) else {
            f.stats.invalid += 1;
            return;
        };
        // Snapped as the quad's first two vertices (their offsets follow the snapped ends).
        let index = self.verts.len() - f.stats.color_vertices as usize;
        (a.x, a.y) = snapped(probe, index, a);
        (b.x, b.y) = snapped(probe, index + 1, b);
        let (dx, dy) = (b.x as i32 - a.x as i32, b.y as i32 - a.y as i32);
        // Half a pixel (8 subpixels) each side across the minor axis.
        let (ox, oy) = if dx.abs() >= dy.abs() { (0, 8) } else { (8, 0) };
        let shift = |v: &ScreenVertex, s: i32| {
            let mut v = *v;
            v.x = (v.x as i32 + s * ox).clamp(-COORD_LIMIT, COORD_LIMIT) as i16;
            v.y = (v.y as i32 + s * oy).clamp(-COORD_LIMIT, COORD_LIMIT) as i16;
            v.set_color(rgb);
            v.flags |= PROJECTED;
            v
        };
        let quad = [shift(&a, -1), shift(&b, -1), shift(&b, 1), shift(&a, 1)];
        f.need.0 += 4;
        if self.verts.len() + 4 > VERTS {
            f.need.1 += 2;
            return;
        }
        let first = self.verts.len();
        for v in quad {
            let _ = self.verts.push(v);
        }
        for t in [[0, 1, 2], [0, 2, 3]] {
            let v = t.map(|k| first + k);
            let (a, b, cc) = (&self.verts[v[0]], &self.verts[v[1]], &self.verts[v[2]]);
            let v = match facing(a, b, cc) {
                Facing::Degenerate => continue,
                Facing::Front => v,
                Facing::Back => [v[0], v[2], v[1]],
            };
            self.push_tri(
                [v[0] as u16 | FLAT_BIT, v[1] as u16, v[2] as u16],
                &mut f.stats,
                &mut f.need,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::adjacency::{mesh_adjacency, AdjacencyError};

    /// A tetrahedron's corners and its four faces, wound counter-clockwise from outside.
    const CORNERS: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    const TET: [[u16; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

    #[test]
    fn a_tetrahedron_is_closed_and_a_square_has_four_open_edges() {
        let p = CORNERS;
        let tet = TET;
        let mesh = Mesh::new(&p, &tet).unwrap();
        let mut adj = [[0u16; 3]; 4];
        assert_eq!(mesh_adjacency(&mesh, &mut adj), Ok(0));
        // Symmetric: t's neighbour across e has t as a neighbour.
        for (t, a) in adj.iter().enumerate() {
            for &u in a {
                assert!(adj[u as usize].contains(&(t as u16)));
            }
        }
        let square = [[0u16, 1, 2], [0, 2, 3]];
        let mesh = Mesh::new(&p, &square).unwrap();
        let mut adj = [[0u16; 3]; 2];
        assert_eq!(mesh_adjacency(&mesh, &mut adj), Ok(4));
        assert_eq!(adj[0][2], 1);
        assert_eq!(adj[1][0], 0);
    }

    #[test]
    fn bad_meshes_are_named() {
        let p = CORNERS;
        let flipped = [[0u16, 1, 2], [0, 1, 3]];
        let mesh = Mesh::new(&p, &flipped).unwrap();
        let mut adj = [[0u16; 3]; 2];
        assert_eq!(
            mesh_adjacency(&mesh, &mut adj),
            Err(AdjacencyError::NotOriented {
                triangle: 1,
                edge: 0
            })
        );
        let fin = [[0u16, 1, 2], [1, 0, 3], [1, 0, 2]];
        let mesh = Mesh::new(&p, &fin).unwrap();
        let mut adj = [[0u16; 3]; 3];
        assert!(matches!(
            mesh_adjacency(&mesh, &mut adj),
            Err(AdjacencyError::NonManifold { .. } | AdjacencyError::NotOriented { .. })
        ));
        let mut short = [[0u16; 3]; 1];
        assert_eq!(
            mesh_adjacency(&mesh, &mut short),
            Err(AdjacencyError::BufferTooSmall { needed: 3 })
        );
    }

    #[test]
    fn each_chosen_edge_is_drawn_once() {
        let p = CORNERS;
        let tet = TET;
        let mesh = Mesh::new(&p, &tet).unwrap();
        let mut adj = [[0u16; 3]; 4];
        mesh_adjacency(&mesh, &mut adj).unwrap();
        let all_creases = [0xffu8; 2];
        // Faces 0 and 1 toward the eye: every pair of a tetrahedron's faces shares an edge, so
        // 4 contour edges, 1 between the two front faces, 1 between the two back ones.
        let front = |t: usize| t < 2;
        let count = |pick: Pick<'_>, see: bool| {
            let mut n = 0;
            for t in 0..4 {
                for e in 0..3 {
                    let u = adj[t][e] as usize;
                    n += pick.draws(t, e, front(t), Some((u, front(u))), see) as u32;
                }
            }
            n
        };
        assert_eq!(count(Pick::Silhouette, false), 4);
        assert_eq!(count(Pick::Silhouette, true), 4);
        assert_eq!(count(Pick::All, false), 5);
        assert_eq!(count(Pick::All, true), 6);
        assert_eq!(count(Pick::Crease(&all_creases), false), 5);
        assert_eq!(count(Pick::Crease(&[0; 2]), true), 4);
        // Open edges: drawn from a front face always, from a back face only seen through.
        assert!(Pick::All.draws(0, 0, true, None, false));
        assert!(!Pick::All.draws(0, 0, false, None, false));
        assert!(Pick::All.draws(0, 0, false, None, true));
        assert!(!Pick::Silhouette.draws(0, 0, false, None, true));
    }

    #[test]
    fn the_sign_survives_in_the_index_order() {
        assert_eq!(volume_sign(&TriRecord { v: [3, 5, 9] }), 1);
        assert_eq!(
            volume_sign(&TriRecord {
                v: [9 | FLAT_BIT, 3, 5]
            }),
            255
        );
        assert_eq!(
            volume_sign(&TriRecord {
                v: [5 | FLAT_BIT, 9, 3]
            }),
            1
        );
    }
}
