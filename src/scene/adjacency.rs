//! Mesh adjacency: each triangle's neighbours across its edges ([`mesh_adjacency`]), the check
//! that a table is its mesh's ([`check_adjacency`]), a table bound to its mesh once checked
//! ([`Adjacency`], what shadow volumes and outlines read), and the crease edges
//! ([`mesh_creases`]).

use crate::num::math::Vec3;
use crate::num::scalar::Scalar;
use crate::scene::mesh::{Mesh, MeshError};

/// An adjacency table checked against its mesh ([`check_adjacency`]) once, when it is made, and
/// bound to that mesh's slices: what [`crate::shadow::VolumeShadow`] and [`crate::shadow::Outline`] take. A
/// layered frame checks only that each object's mesh is the one its table was checked against
/// (the same index and position slices, two pointer comparisons), so a table costs nothing per
/// frame. The table and the mesh's slices stay borrowed while it exists, so neither can change
/// under it.
///
/// ```
/// use scanline3d::{mesh::mesh_adjacency, mesh::Adjacency, Shape};
///
/// let cube = Shape::<f32, 24, 12>::cube(1.0).unwrap();
/// let mut table = [[0u16; 3]; 12];
/// mesh_adjacency(&cube.mesh(), &mut table).unwrap(); // a mesh's setup: O(T²)
/// let adjacency = Adjacency::new(&cube.mesh(), &table).unwrap(); // O(T), once
/// assert!(adjacency.is_for(&cube.mesh()));
/// // A table that is not the mesh's is refused:
/// assert!(Adjacency::new(&cube.mesh(), &[[7, 7, 7]; 12]).is_err());
/// ```
#[derive(Copy, Clone, Debug)]
pub struct Adjacency<'a, S> {
    table: &'a [[u16; 3]],
    indices: &'a [[u16; 3]],
    positions: &'a [Vec3<S>],
}

impl<'a, S: Scalar> Adjacency<'a, S> {
    /// `table` checked against `mesh` ([`check_adjacency`]: every index of the mesh in range,
    /// every neighbour a triangle along the same edge that names the first back).
    ///
    /// # Errors
    ///
    /// As [`check_adjacency`].
    pub fn new(mesh: &Mesh<'a, S>, table: &'a [[u16; 3]]) -> Result<Self, AdjacencyError> {
        check_adjacency(mesh, table)?;
        Ok(Adjacency {
            table: &table[..mesh.indices().len()],
            indices: mesh.indices(),
            positions: mesh.positions(),
        })
    }

    /// The table: one entry per triangle of the mesh.
    #[must_use]
    pub fn table(&self) -> &'a [[u16; 3]] {
        self.table
    }

    /// Whether `mesh` is the mesh the table was checked against: the same index and position
    /// slices (addresses and lengths).
    #[must_use]
    pub fn is_for(&self, mesh: &Mesh<'_, S>) -> bool {
        core::ptr::eq(self.indices, mesh.indices())
            && core::ptr::eq(self.positions, mesh.positions())
    }
}

/// Tables are equal when they are the same table of the same mesh (the same slices).
impl<S> PartialEq for Adjacency<'_, S> {
    fn eq(&self, o: &Self) -> bool {
        core::ptr::eq(self.table, o.table)
            && core::ptr::eq(self.indices, o.indices)
            && core::ptr::eq(self.positions, o.positions)
    }
}

impl<S> Eq for Adjacency<'_, S> {}

/// An [`mesh_adjacency`] entry: no neighbour across this edge (an open edge).
pub const NO_NEIGHBOUR: u16 = u16::MAX;

/// Why [`mesh_adjacency`] could not build a table.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
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

/// Whether two vertex positions are equal (the same corner of a mesh), with [`Scalar::same`].
#[inline]
fn same_position<S: Scalar>(p: Vec3<S>, q: Vec3<S>) -> bool {
    p[0].same(q[0]) && p[1].same(q[1]) && p[2].same(q[2])
}

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
    let same = |a: u16, b: u16| a == b || same_position(pos[a as usize], pos[b as usize]);
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
/// [`Adjacency::new`] runs it once per table; a few comparisons per edge.
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
    let same = |a: u16, b: u16| a == b || same_position(pos[a as usize], pos[b as usize]);
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
/// The table is what [`crate::shadow::Edges::Crease`] draws; both sides of an edge carry the same bit.
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
