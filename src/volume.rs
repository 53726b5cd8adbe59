//! Shadow volumes and outlines: the triangles a layered frame adds for them, built in the
//! geometry stage from each mesh's adjacency ([`mesh_adjacency`]).
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

use crate::clip::{clip_triangle, ClipVertex, FAR, GUARD, NEAR, NEEDS_CLIP};
use crate::color::TargetColor;
use crate::geometry::{snapped, vertex_record_keep, Frame, FrameConst, INVALID, PROJECTED};
use crate::kernel::records::{facing, Facing, ScreenVertex, TriRecord};
use crate::math::{cross, dot, normalize, scale, sub, Mat4, Vec3};
use crate::mesh::{Mesh, MeshError};
use crate::project::{pack_flat_channels, COORD_LIMIT};
use crate::raster::FLAT_BIT;
use crate::renderer::{Probe, Renderer};
use crate::scalar::Scalar;
use crate::scene::Object;
use crate::shadow::{ShadowLight, VolumeShadow};

/// An [`mesh_adjacency`] entry: no neighbour across this edge (an open edge).
pub const NO_NEIGHBOUR: u16 = u16::MAX;

/// Why [`mesh_adjacency`] could not build a table.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum AdjacencyError {
    /// The output holds fewer entries than the mesh's triangles.
    BufferTooSmall {
        /// The mesh's triangles.
        needed: usize,
    },
    /// The mesh has 65 535 triangles or more (the table stores `u16` indices).
    TooManyTriangles {
        /// The mesh's triangles.
        triangles: usize,
    },
    /// An edge is shared by more than two triangles.
    NonManifold {
        /// A triangle with the edge.
        triangle: usize,
        /// Its edge (0: vertices 0→1, 1: 1→2, 2: 2→0).
        edge: usize,
    },
    /// Two triangles run along their shared edge the same way: one of them is turned inside
    /// out, and no side of the mesh is its outside.
    NotOriented {
        /// The second triangle with the edge.
        triangle: usize,
        /// Its edge.
        edge: usize,
    },
    /// The crease table ([`mesh_creases`]) holds fewer than 3 bits per triangle.
    CreaseTableTooSmall {
        /// The bytes it needs.
        bytes: usize,
    },
    /// The crease angle is not within 0..=180 degrees.
    Angle,
    /// An adjacency table that is not its mesh's: the neighbour it gives across edge `edge`
    /// of triangle `triangle` is not a triangle of the mesh, does not share that edge (its
    /// ends, run the other way), or does not name `triangle` back.
    Mismatch {
        /// The triangle.
        triangle: usize,
        /// Its edge.
        edge: usize,
    },
    /// Triangle `triangle` of the mesh refers to vertex `index`, which does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The bad index.
        index: u16,
    },
}

impl core::fmt::Display for AdjacencyError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AdjacencyError::BufferTooSmall { needed } => {
                write!(f, "the adjacency table needs {needed} entries")
            }
            AdjacencyError::TooManyTriangles { triangles } => {
                write!(f, "{triangles} triangles: an adjacency table holds at most 65 534")
            }
            AdjacencyError::NonManifold { triangle, edge } => write!(
                f,
                "edge {edge} of triangle {triangle} is shared by more than two triangles"
            ),
            AdjacencyError::NotOriented { triangle, edge } => write!(
                f,
                "triangle {triangle} runs along its edge {edge} the same way as its neighbour (not consistently wound)"
            ),
            AdjacencyError::CreaseTableTooSmall { bytes } => {
                write!(f, "the crease table needs {bytes} bytes (3 bits per triangle)")
            }
            AdjacencyError::Angle => write!(f, "the crease angle is not within 0 to 180 degrees"),
            AdjacencyError::Mismatch { triangle, edge } => write!(
                f,
                "the adjacency table is not the mesh's: the neighbour across edge {edge} of \
                 triangle {triangle} does not share that edge (build it with mesh_adjacency)"
            ),
            AdjacencyError::IndexOutOfRange { triangle, index } => write!(
                f,
                "mesh triangle {triangle} refers to vertex {index}, which does not exist"
            ),
        }
    }
}

impl core::error::Error for AdjacencyError {}

/// Each triangle's neighbours, into `out[..triangles]`: `out[t][e]` is the triangle across edge
/// `e` of triangle `t` (edge 0 joins its vertices 0 and 1, edge 1 vertices 1 and 2, edge 2
/// vertices 2 and 0), or [`NO_NEIGHBOUR`]. Edges are matched by their ends' positions, so a
/// mesh whose faces have their own vertices (a cube with flat normals, a texture seam) is
/// joined across them. Returns the number of open edges.
///
/// For a mesh's setup, not per frame: O(triangles²) comparisons, no memory besides `out`.
///
/// # Errors
///
/// [`AdjacencyError`]: `out` too short, too many triangles, an edge of three or more
/// triangles, or two neighbours wound opposite ways.
pub fn mesh_adjacency<S: Scalar>(
    mesh: &Mesh<'_, S>,
    out: &mut [[u16; 3]],
) -> Result<usize, AdjacencyError> {
    let (tris, pos) = (mesh.indices(), mesh.positions());
    let n = tris.len();
    if let Err(MeshError::IndexOutOfRange { triangle, index }) = mesh.validate() {
        return Err(AdjacencyError::IndexOutOfRange { triangle, index });
    }
    // Vertices are the same corner when their positions are equal (a mesh with split normals
    // or texture seams has several records per corner).
    let same = |a: u16, b: u16| a == b || pos[a as usize] == pos[b as usize];
    if n >= NO_NEIGHBOUR as usize {
        return Err(AdjacencyError::TooManyTriangles { triangles: n });
    }
    let out = out
        .get_mut(..n)
        .ok_or(AdjacencyError::BufferTooSmall { needed: n })?;
    out.fill([NO_NEIGHBOUR; 3]);
    for t in 0..n {
        for e in 0..3 {
            let (a, b) = (tris[t][e], tris[t][(e + 1) % 3]);
            if same(a, b) {
                continue;
            }
            for (u, other) in tris.iter().enumerate().skip(t + 1) {
                for f in 0..3 {
                    let (c, d) = (other[f], other[(f + 1) % 3]);
                    if same(c, a) && same(d, b) {
                        return Err(AdjacencyError::NotOriented {
                            triangle: u,
                            edge: f,
                        });
                    }
                    if same(c, b) && same(d, a) {
                        if out[t][e] != NO_NEIGHBOUR || out[u][f] != NO_NEIGHBOUR {
                            return Err(AdjacencyError::NonManifold {
                                triangle: u,
                                edge: f,
                            });
                        }
                        out[t][e] = u as u16;
                        out[u][f] = t as u16;
                    }
                }
            }
        }
    }
    Ok(out.iter().flatten().filter(|&&v| v == NO_NEIGHBOUR).count())
}

/// Checks that `table` is an adjacency table of `mesh` (as [`mesh_adjacency`] makes one): every
/// index of the mesh in range, and each neighbour the table names a triangle of the mesh that
/// runs along the same edge the other way and names the first back. An open edge
/// ([`NO_NEIGHBOUR`]) is taken as given (proving it open would cost a search of the mesh).
/// Run by every layered frame on its volume casters' and outlined objects' tables: a few
/// comparisons per edge.
///
/// # Errors
///
/// [`AdjacencyError::IndexOutOfRange`], [`AdjacencyError::BufferTooSmall`] (a table shorter
/// than the mesh's triangles) or [`AdjacencyError::Mismatch`].
pub fn check_adjacency<S: Scalar>(
    mesh: &Mesh<'_, S>,
    table: &[[u16; 3]],
) -> Result<(), AdjacencyError> {
    let (tris, pos) = (mesh.indices(), mesh.positions());
    let n = tris.len();
    if let Err(MeshError::IndexOutOfRange { triangle, index }) = mesh.validate() {
        return Err(AdjacencyError::IndexOutOfRange { triangle, index });
    }
    let table = table
        .get(..n)
        .ok_or(AdjacencyError::BufferTooSmall { needed: n })?;
    let same = |a: u16, b: u16| a == b || pos[a as usize] == pos[b as usize];
    for (t, adj) in table.iter().enumerate() {
        for (e, &u) in adj.iter().enumerate() {
            if u == NO_NEIGHBOUR {
                continue;
            }
            let (a, b) = (tris[t][e], tris[t][(e + 1) % 3]);
            let back = |f: usize| {
                let other = tris[u as usize];
                let (c, d) = (other[f], other[(f + 1) % 3]);
                table[u as usize][f] == t as u16 && same(c, b) && same(d, a)
            };
            if (u as usize) >= n || u as usize == t || !(0..3).any(back) {
                return Err(AdjacencyError::Mismatch {
                    triangle: t,
                    edge: e,
                });
            }
        }
    }
    Ok(())
}

/// Which edges of a mesh are creases, into `out` (bit `3·t + e` of the bytes, least
/// significant first, for edge `e` of triangle `t`, numbered as in [`mesh_adjacency`]): an
/// edge whose two faces meet at more than `angle_deg` degrees (between their normals: 0 for a
/// flat surface), or an open edge. A face of zero area makes no crease with its neighbours.
/// The table is what [`crate::Edges::Crease`] draws; both sides of an edge carry the same bit.
/// Returns the number of crease edges (an edge between two faces counted once).
///
/// For a mesh's setup, not per frame: one face normal per triangle, in f64 (the same table
/// for every number type).
///
/// # Errors
///
/// [`AdjacencyError::BufferTooSmall`] when `adjacency` is shorter than the mesh's triangles,
/// [`AdjacencyError::CreaseTableTooSmall`] when `out` holds fewer than `3·T` bits, and
/// [`AdjacencyError::Angle`] for an angle outside 0..=180 degrees, and the errors of
/// [`check_adjacency`] for a table that is not the mesh's.
pub fn mesh_creases<S: Scalar>(
    mesh: &Mesh<'_, S>,
    adjacency: &[[u16; 3]],
    angle_deg: f64,
    out: &mut [u8],
) -> Result<usize, AdjacencyError> {
    let (tris, pos) = (mesh.indices(), mesh.positions());
    let n = tris.len();
    if !(0.0..=180.0).contains(&angle_deg) {
        return Err(AdjacencyError::Angle);
    }
    check_adjacency(mesh, adjacency)?;
    let adjacency = &adjacency[..n];
    let bytes = (3 * n).div_ceil(8);
    let out = out
        .get_mut(..bytes)
        .ok_or(AdjacencyError::CreaseTableTooSmall { bytes })?;
    out.fill(0);
    // The unit normal of face `t` in f64 (zero for a face of zero area).
    let normal = |t: usize| -> [f64; 3] {
        let [a, b, c] = tris[t].map(|i| pos[i as usize].map(|v| v.to_f64()));
        let (u, v) = (
            [0, 1, 2].map(|k| b[k] - a[k]),
            [0, 1, 2].map(|k| c[k] - a[k]),
        );
        let m = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let len = libm::sqrt(m.iter().map(|x| x * x).sum::<f64>());
        if len > 0.0 && len.is_finite() {
            m.map(|x| x / len)
        } else {
            [0.0; 3]
        }
    };
    // Faces whose normals' dot product is within this of the limit are not a crease: rounding
    // leaves a flat pair's at 1 − 1e-16 or so, which would make it a crease at 0°.
    const FLAT: f64 = 1e-9;
    let limit = libm::cos(angle_deg.to_radians());
    let mut count = 0;
    for (t, adj) in adjacency.iter().enumerate() {
        for (e, &u) in adj.iter().enumerate() {
            let u = u as usize;
            let crease = if u >= n {
                true
            } else {
                let (p, q) = (normal(t), normal(u));
                let zero = |v: [f64; 3]| v == [0.0; 3];
                !zero(p) && !zero(q) && p[0] * q[0] + p[1] * q[1] + p[2] * q[2] < limit - FLAT
            };
            if crease {
                let bit = 3 * t + e;
                out[bit / 8] |= 1 << (bit % 8);
                if u >= n || t < u {
                    count += 1;
                }
            }
        }
    }
    Ok(count)
}

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

/// Which edges an outline draws for one object ([`crate::Edges`] with the object's crease
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
    aspect: f64,
    obj: &Object<'_, S>,
    reach: S,
) -> S {
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
