//! Triangle meshes borrowed from slices (so a mesh can live in flash as `static` arrays).
//!
//! Triangles are counter-clockwise when seen from their front. Vertex normals are optional;
//! [`vertex_normals`] computes them as the seeds do: the normalized, unweighted average of the
//! unit normals of the faces that share the vertex.

use crate::num::math::{add, cross, normalize, sub, Vec3};
use crate::num::scalar::Scalar;

/// A mesh: positions, triangles as `u16` indices, and optional unit vertex normals.
#[derive(Copy, Clone, Debug)]
pub struct Mesh<'a, S> {
    positions: &'a [Vec3<S>],
    indices: &'a [[u16; 3]],
    normals: Option<&'a [Vec3<S>]>,
    /// Texture coordinates `(s, t)`, one per position ([`Mesh::with_uvs`]).
    uvs: Option<&'a [[S; 2]]>,
    /// Whether a position has a coordinate that is not valid in `S` ([`Scalar::is_valid`]:
    /// NaN, infinite, or a fixed-point rail, where a NaN input lands): found once when the
    /// mesh is built, so that the renderer checks positions one by one only for such a mesh.
    bad_positions: bool,
}

/// Whether any coordinate of `positions` is not valid in `S`.
fn any_invalid<S: Scalar>(positions: &[Vec3<S>]) -> bool {
    positions.iter().any(|p| !p.iter().all(|v| v.is_valid()))
}

/// Why a mesh could not be built.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum MeshError {
    /// More than 65 536 positions: `u16` indices cannot address them.
    TooManyVertices {
        /// The number of positions given.
        count: usize,
    },
    /// The normals slice is not as long as the positions slice.
    NormalCount {
        /// Number of positions.
        positions: usize,
        /// Number of normals.
        normals: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The bad index.
        index: u16,
    },
    /// An output buffer is shorter than needed.
    BufferTooSmall {
        /// The length needed.
        needed: usize,
    },
    /// A vertex normal has a coordinate that is NaN, infinite or (fixed point) at a
    /// saturation rail ([`Scalar::is_valid`]): it would light its triangles with garbage.
    InvalidNormal {
        /// The vertex.
        vertex: usize,
    },
    /// The texture-coordinate slice is not as long as the positions slice.
    UvCount {
        /// Number of positions.
        positions: usize,
        /// Number of texture coordinates.
        uvs: usize,
    },
    /// A texture coordinate is not valid in the number type or not within ±[`UV_LIMIT`].
    UvOutOfRange {
        /// The vertex.
        vertex: usize,
    },
}

/// The largest magnitude of a texture coordinate (exclusive): 16 texture widths, so that a
/// triangle spans fewer than 2¹⁵ texels of a 1024-texel texture (the span formats' range).
pub const UV_LIMIT: f64 = 16.0;

impl<'a, S: Scalar> Mesh<'a, S> {
    /// A mesh without normals (enough for flat shading; Gouraud needs [`Mesh::with_normals`]).
    ///
    /// Indices are checked when rendering: a triangle with an index out of range is skipped and
    /// counted in [`crate::Stats::invalid`].
    pub fn new(positions: &'a [Vec3<S>], indices: &'a [[u16; 3]]) -> Result<Self, MeshError> {
        if positions.len() > 1 << 16 {
            return Err(MeshError::TooManyVertices {
                count: positions.len(),
            });
        }
        Ok(Mesh {
            positions,
            indices,
            normals: None,
            uvs: None,
            bad_positions: any_invalid(positions),
        })
    }

    /// A mesh of positions already known to be valid in `S` (a [`crate::Shape`]'s: its
    /// constructors refuse a shape whose coordinates are not), so that building it — once per
    /// frame in a firmware's loop — does not scan them again.
    pub(crate) fn from_valid_parts(
        positions: &'a [Vec3<S>],
        indices: &'a [[u16; 3]],
        normals: Option<&'a [Vec3<S>]>,
    ) -> Self {
        debug_assert!(!any_invalid(positions));
        Mesh {
            positions,
            indices,
            normals,
            uvs: None,
            bad_positions: false,
        }
    }

    /// Adds unit vertex normals, one per position.
    ///
    /// # Errors
    ///
    /// [`MeshError::NormalCount`] unless there is one per position;
    /// [`MeshError::InvalidNormal`] for a normal with a coordinate that is not valid in `S`
    /// (NaN, infinite, or a fixed-point rail).
    pub fn with_normals(mut self, normals: &'a [Vec3<S>]) -> Result<Self, MeshError> {
        if normals.len() != self.positions.len() {
            return Err(MeshError::NormalCount {
                positions: self.positions.len(),
                normals: normals.len(),
            });
        }
        if let Some(vertex) = normals.iter().position(|n| !n.iter().all(|c| c.is_valid())) {
            return Err(MeshError::InvalidNormal { vertex });
        }
        self.normals = Some(normals);
        Ok(self)
    }

    /// Adds texture coordinates `(s, t)`, one per position (see [`crate::Texture`] for their
    /// orientation). A vertex where two faces need different coordinates (a UV seam) must be
    /// two vertices.
    ///
    /// # Errors
    ///
    /// [`MeshError::UvCount`] unless there is one per position; [`MeshError::UvOutOfRange`]
    /// for a coordinate that is not valid in `S` or not within ±[`UV_LIMIT`].
    pub fn with_uvs(mut self, uvs: &'a [[S; 2]]) -> Result<Self, MeshError> {
        if uvs.len() != self.positions.len() {
            return Err(MeshError::UvCount {
                positions: self.positions.len(),
                uvs: uvs.len(),
            });
        }
        let (lo, hi) = (S::from_f64(-UV_LIMIT), S::from_f64(UV_LIMIT));
        if let Some(vertex) = uvs
            .iter()
            .position(|uv| !uv.iter().all(|&c| c.is_valid() && c > lo && c < hi))
        {
            return Err(MeshError::UvOutOfRange { vertex });
        }
        self.uvs = Some(uvs);
        Ok(self)
    }

    /// The texture coordinates, if any.
    #[must_use]
    pub fn uvs(&self) -> Option<&'a [[S; 2]]> {
        self.uvs
    }

    /// The positions.
    #[must_use]
    pub fn positions(&self) -> &'a [Vec3<S>] {
        self.positions
    }

    /// The triangles.
    #[must_use]
    pub fn indices(&self) -> &'a [[u16; 3]] {
        self.indices
    }

    /// The vertex normals, if any.
    #[must_use]
    pub fn normals(&self) -> Option<&'a [Vec3<S>]> {
        self.normals
    }

    /// Whether a position has a coordinate that is NaN, infinite or (fixed point) at a
    /// saturation rail — where [`Scalar::from_f64`] puts NaN, ±∞ and out-of-range inputs. The
    /// renderer skips the triangles that use such a vertex and counts them in
    /// [`crate::Stats::invalid`], for every number type. Checked once, when the mesh is built.
    #[must_use]
    pub fn has_invalid_positions(&self) -> bool {
        self.bad_positions
    }

    /// Checks every index against the number of positions.
    pub fn validate(&self) -> Result<(), MeshError> {
        for (t, tri) in self.indices.iter().enumerate() {
            for &i in tri {
                if i as usize >= self.positions.len() {
                    return Err(MeshError::IndexOutOfRange {
                        triangle: t,
                        index: i,
                    });
                }
            }
        }
        Ok(())
    }
}

impl core::fmt::Display for MeshError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            MeshError::TooManyVertices { count } => write!(
                f,
                "mesh has {count} positions; u16 indices address at most 65536"
            ),
            MeshError::NormalCount { positions, normals } => write!(
                f,
                "mesh has {positions} positions but {normals} normals (one per position needed)"
            ),
            MeshError::IndexOutOfRange { triangle, index } => write!(
                f,
                "mesh triangle {triangle} refers to vertex {index}, which does not exist"
            ),
            MeshError::InvalidNormal { vertex } => write!(
                f,
                "normal of vertex {vertex} is NaN, infinite or out of the number type's range"
            ),
            MeshError::BufferTooSmall { needed } => {
                write!(f, "output buffer too small: {needed} entries needed")
            }
            MeshError::UvCount { positions, uvs } => write!(
                f,
                "mesh has {positions} positions but {uvs} texture coordinates (one per \
                 position needed)"
            ),
            MeshError::UvOutOfRange { vertex } => write!(
                f,
                "texture coordinate of vertex {vertex} is not a number within ±{UV_LIMIT}"
            ),
        }
    }
}

impl core::error::Error for MeshError {}

/// The unit normal of the counter-clockwise triangle `a, b, c` (zero for a degenerate one).
///
/// The edges are normalized before the cross product so that small triangles keep their
/// precision in fixed point.
#[must_use]
pub fn face_normal<S: Scalar>(a: Vec3<S>, b: Vec3<S>, c: Vec3<S>) -> Vec3<S> {
    normalize(cross(normalize(sub(b, a)), normalize(sub(c, a))))
}

/// Computes vertex normals into `out` (at least as long as `positions`): for each vertex, the
/// normalized sum of the unit normals of the faces using it. Vertices used by no face (or only
/// by degenerate ones) get the zero vector, which lights as ambient only.
pub fn vertex_normals<S: Scalar>(
    positions: &[Vec3<S>],
    indices: &[[u16; 3]],
    out: &mut [Vec3<S>],
) -> Result<(), MeshError> {
    if out.len() < positions.len() {
        return Err(MeshError::BufferTooSmall {
            needed: positions.len(),
        });
    }
    Mesh::new(positions, indices)?.validate()?;
    for n in out.iter_mut() {
        *n = [S::ZERO; 3];
    }
    for tri in indices {
        let [a, b, c] = tri.map(|i| positions[i as usize]);
        let n = face_normal(a, b, c);
        for &i in tri {
            out[i as usize] = add(out[i as usize], n);
        }
    }
    for n in out.iter_mut().take(positions.len()) {
        *n = normalize(*n);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    #[test]
    fn face_normal_follows_counter_clockwise_order() {
        let n = face_normal::<f32>([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(n, [0.0, 0.0, 1.0]);
        type Q = Fx<I16F16>;
        let p = |x: f64, y: f64| [Q::lit(x * 0.001), Q::lit(y * 0.001), Q::ZERO];
        let n = face_normal(p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0));
        assert!((n[2].to_f64() - 1.0).abs() < 1e-3, "{n:?}");
    }

    #[test]
    fn vertex_normal_is_unweighted_average_of_face_normals() {
        // Vertex 1 is shared by one face with normal +Z and two (of different areas) with
        // normal +Y: the unweighted average is (0, 2, 1)/√5, not area-weighted.
        let pos = [
            [0.0f64, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [5.0, 0.0, 5.0],
        ];
        let idx = [[0u16, 1, 2], [0, 3, 1], [3, 4, 1]];
        let mut out = [[0.0; 3]; 5];
        vertex_normals(&pos, &idx, &mut out).unwrap();
        let k = 1.0 / libm::sqrt(1.0 + 4.0);
        assert!((out[1][1] - 2.0 * k).abs() < 1e-12 && (out[1][2] - k).abs() < 1e-12);
        assert_eq!(out[0], normalize([0.0, 1.0, 1.0]));
    }

    #[test]
    fn bad_meshes_are_errors() {
        let pos = [[0.0f32; 3]; 3];
        let idx = [[0u16, 1, 3]];
        let m = Mesh::new(&pos, &idx).unwrap();
        assert_eq!(
            m.validate(),
            Err(MeshError::IndexOutOfRange {
                triangle: 0,
                index: 3
            })
        );
        let n = [[0.0f32; 3]; 2];
        assert!(matches!(
            m.with_normals(&n),
            Err(MeshError::NormalCount { .. })
        ));
        let mut out = [[0.0f32; 3]; 3];
        assert!(vertex_normals(&pos, &idx, &mut out).is_err());
    }
}
