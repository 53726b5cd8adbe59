//! Built-in procedural meshes for tests, benchmarks and demos: cube, torus, icosphere, a flat
//! plane (a ground or a quad) and a height-field terrain grid.
//!
//! Shapes are generated in `f64` (libm, pure software, so bit-identical on every target) and
//! rounded once to `S`. Their storage is sized at compile time: `V` vertices and `T` triangles.
//!
//! Every constructor checks its inputs before it generates anything, in this order, and returns
//! the first [`ShapeError`] that applies:
//!
//! 1. [`ShapeError::BadParameter`]: a parameter no number type or capacity could make valid —
//!    a NaN or infinite length, a length ≤ 0, a minor radius above the major one, fewer than 3
//!    segments, 0 terrain or plane cells, more than 4 icosphere subdivisions.
//! 2. [`ShapeError::OutOfRange`]: the shape's extent (its largest coordinate; for the terrain,
//!    the largest difference between coordinates) does not fit `S` (it would saturate a
//!    fixed-point type, which the renderer then treats as invalid, or overflow `f32`) or rounds
//!    to zero in `S` (every vertex would coincide).
//! 3. [`ShapeError::Capacity`]: the shape needs more than `V` vertices or `T` triangles, or more
//!    than the 65 536 vertices `u16` indices address. The counts are computed with checked
//!    arithmetic and never wrap; a count beyond `usize::MAX` is reported as `None`.
//!
//! So a constructor never panics, never loops over more than the capacity it checked, and never
//! returns `Ok` with a shape other than the one its documentation describes.

use core::f64::consts::PI;
use core::fmt;

use heapless::Vec;

use crate::num::math::Vec3;
use crate::num::scalar::Scalar;
use crate::scene::mesh::{vertex_normals, Mesh};

/// The most vertices `u16` indices can address.
const MAX_INDEXED: usize = 1 << 16;

/// A generated mesh with its own storage: `V` vertices (positions and unit normals) and `T`
/// triangles.
#[derive(Clone, Debug)]
pub struct Shape<S, const V: usize, const T: usize> {
    /// Positions. Every coordinate is at most the shape's extent in magnitude (the constructor
    /// checked that the extent is a valid, non-zero value of `S`); rounded once from `f64`.
    pub positions: Vec<Vec3<S>, V>,
    /// Unit vertex normals (rounded once from `f64`, or computed in `S` for the terrain).
    pub normals: Vec<Vec3<S>, V>,
    /// Counter-clockwise triangles; every index is below `positions.len()` (≤ 65 536).
    pub indices: Vec<[u16; 3], T>,
}

/// Why a shape could not be built: a bad parameter, a shape the number type cannot hold, or too
/// little storage.
#[derive(Copy, Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ShapeError {
    /// A parameter is outside the range the constructor accepts, whatever the number type and
    /// the capacities.
    BadParameter {
        /// The parameter's name in the constructor's signature (`"h"`, `"big_r"`, `"nu"`, ...).
        name: &'static str,
        /// The value given.
        value: ParamValue,
        /// What the constructor accepts, in words (`"finite and > 0"`, `">= 3"`, ...).
        expected: &'static str,
    },
    /// The parameters are valid, but the shape's extent — its largest coordinate in magnitude,
    /// or for the terrain, whose normals are computed in `S`, the largest difference between two
    /// vertices' coordinates — does not fit the number type `S`: it saturates or overflows
    /// there (the renderer would skip every triangle touching such a vertex as invalid, or the
    /// shape would be squashed), or, when `rounds_to_zero`, it rounds to 0 (every vertex would
    /// coincide).
    OutOfRange {
        /// The shape's extent, computed in `f64` from the parameters (see each constructor).
        extent: f64,
        /// [`Scalar::NAME`] of the number type.
        number_type: &'static str,
        /// `true` when `extent` rounds to zero in `S`, `false` when it is too large for `S`.
        rounds_to_zero: bool,
    },
    /// The parameters are valid but the shape does not fit its storage.
    Capacity {
        /// Vertices the shape needs; `None` when the count exceeds `usize::MAX`.
        vertices: Option<usize>,
        /// Triangles the shape needs; `None` when the count exceeds `usize::MAX`.
        triangles: Option<usize>,
        /// Vertices the shape can hold: `V`, or 65 536 (what `u16` indices address) if smaller.
        vertex_capacity: usize,
        /// Triangles the shape can hold: `T`.
        triangle_capacity: usize,
    },
}

/// The value of a rejected parameter ([`ShapeError::BadParameter`]).
#[derive(Copy, Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ParamValue {
    /// A length or amplitude, exactly as given (NaN and infinities included).
    Real(f64),
    /// A segment, cell or subdivision count, exactly as given.
    Count(u64),
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Real(v) => write!(f, "{v}"),
            ParamValue::Count(n) => write!(f, "{n}"),
        }
    }
}

/// Writes a count, or that it exceeds `usize::MAX`.
struct CountText(Option<usize>);

impl fmt::Display for CountText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(n) => write!(f, "{n}"),
            None => write!(f, "more than {}", usize::MAX),
        }
    }
}

impl fmt::Display for ShapeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ShapeError::BadParameter {
                name,
                value,
                expected,
            } => write!(
                f,
                "bad shape parameter: {name} = {value}, expected {expected}"
            ),
            ShapeError::OutOfRange {
                extent,
                number_type,
                rounds_to_zero: true,
            } => write!(
                f,
                "shape too small for {number_type}: its extent {extent} rounds to 0"
            ),
            ShapeError::OutOfRange {
                extent,
                number_type,
                rounds_to_zero: false,
            } => write!(
                f,
                "shape too large for {number_type}: its extent {extent} is beyond the type's \
                 valid range"
            ),
            ShapeError::Capacity {
                vertices,
                triangles,
                vertex_capacity,
                triangle_capacity,
            } => write!(
                f,
                "shape capacity too small: it needs {} vertices and {} triangles, the shape \
                 holds {vertex_capacity} vertices and {triangle_capacity} triangles",
                CountText(vertices),
                CountText(triangles),
            ),
        }
    }
}

impl core::error::Error for ShapeError {}

/// `Ok` when `v` is finite and positive, else [`ShapeError::BadParameter`] naming it.
pub(crate) fn positive(name: &'static str, v: f64) -> Result<(), ShapeError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(ShapeError::BadParameter {
            name,
            value: ParamValue::Real(v),
            expected: "finite and > 0",
        })
    }
}

/// `Ok` when the count `n` is at least `min`, else [`ShapeError::BadParameter`] naming it.
pub(crate) fn at_least(
    name: &'static str,
    n: usize,
    min: usize,
    expected: &'static str,
) -> Result<(), ShapeError> {
    if n >= min {
        Ok(())
    } else {
        Err(ShapeError::BadParameter {
            name,
            // usize is at most 64 bits on every Rust target; saturate rather than assume it.
            value: ParamValue::Count(u64::try_from(n).unwrap_or(u64::MAX)),
            expected,
        })
    }
}

impl<S: Scalar, const V: usize, const T: usize> Default for Shape<S, V, T> {
    /// [`Shape::new`]: an empty shape.
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Scalar, const V: usize, const T: usize> Shape<S, V, T> {
    /// Checks that the shape's largest coordinate in magnitude, `extent` (finite and > 0, from
    /// already checked parameters), and its negation are valid values of `S` and that `extent`
    /// does not round to zero.
    pub(crate) fn check_extent(extent: f64) -> Result<(), ShapeError> {
        let (hi, lo) = (S::from_f64(extent), S::from_f64(-extent));
        if !(extent.is_finite() && hi.is_valid() && lo.is_valid()) {
            return Err(ShapeError::OutOfRange {
                extent,
                number_type: S::NAME,
                rounds_to_zero: false,
            });
        }
        if hi <= S::ZERO {
            return Err(ShapeError::OutOfRange {
                extent,
                number_type: S::NAME,
                rounds_to_zero: true,
            });
        }
        Ok(())
    }

    /// Empty storage for a shape of `vertices` vertices and `triangles` triangles (`None`: more
    /// than `usize::MAX`), or [`ShapeError::Capacity`] if it does not fit `V`, `T` and `u16`
    /// indices. After `Ok`, pushing that many vertices and triangles cannot fail.
    pub(crate) fn with_capacity_for(
        vertices: Option<usize>,
        triangles: Option<usize>,
    ) -> Result<Self, ShapeError> {
        Self::check_capacity(vertices, triangles)?;
        Ok(Self::new())
    }

    /// `Ok` when `vertices` vertices and `triangles` triangles (`None`: more than
    /// `usize::MAX`) fit `V`, `T` and `u16` indices, else [`ShapeError::Capacity`].
    fn check_capacity(vertices: Option<usize>, triangles: Option<usize>) -> Result<(), ShapeError> {
        let vertex_capacity = V.min(MAX_INDEXED);
        match (vertices, triangles) {
            (Some(v), Some(t)) if v <= vertex_capacity && t <= T => Ok(()),
            _ => Err(ShapeError::Capacity {
                vertices,
                triangles,
                vertex_capacity,
                triangle_capacity: T,
            }),
        }
    }

    pub(crate) fn vertex(&mut self, p: [f64; 3], n: [f64; 3]) {
        // Capacity was checked up front.
        let _ = self.positions.push(p.map(S::from_f64));
        let _ = self.normals.push(n.map(S::from_f64));
    }

    pub(crate) fn tri(&mut self, a: usize, b: usize, c: usize) {
        // Indices are below the vertex count, checked ≤ 65 536 up front: `as u16` is exact.
        let _ = self.indices.push([a as u16, b as u16, c as u16]);
    }

    /// The mesh, with normals.
    #[must_use]
    pub fn mesh(&self) -> Mesh<'_, S> {
        // At most 65 536 vertices, every coordinate valid in `S` (both checked on creation),
        // and one normal per position.
        Mesh::from_valid_parts(&self.positions, &self.indices, Some(&self.normals))
    }

    /// An axis-aligned cube of half-size `h` centred at the origin: 24 vertices (4 per face, with
    /// the face's normal) and 12 triangles.
    ///
    /// # Errors
    ///
    /// [`ShapeError::BadParameter`] unless `h` is finite and > 0; [`ShapeError::OutOfRange`] if
    /// ±`h` is not a valid value of `S` or `h` rounds to 0 there; [`ShapeError::Capacity`] if
    /// `V < 24` or `T < 12`.
    pub fn cube(h: f64) -> Result<Self, ShapeError> {
        positive("h", h)?;
        Self::check_extent(h)?;
        let mut s = Self::with_capacity_for(Some(24), Some(12))?;
        // For each face: normal and two in-plane axes (u, v) with u × v = normal.
        let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        for (f, (n, u, v)) in faces.iter().enumerate() {
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let p = [0, 1, 2].map(|k| h * (n[k] + a * u[k] + b * v[k]));
                s.vertex(p, *n);
            }
            let o = 4 * f;
            s.tri(o, o + 1, o + 2);
            s.tri(o, o + 2, o + 3);
        }
        Ok(s)
    }

    /// A torus around the Z axis in the XY plane: major radius `big_r`, minor radius `r`, `nu`
    /// segments around the major circle and `nv` around the minor one. Vertex `(i, j)` has index
    /// `i·nv + j`, `u = 2πi/nu`, `v = 2πj/nv`,
    /// `P = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v)`,
    /// `N = (cos v cos u, cos v sin u, sin v)`; each quad gives triangles
    /// `(i,j),(i+1,j),(i+1,j+1)` and `(i,j),(i+1,j+1),(i,j+1)` (indices wrap), counter-clockwise
    /// seen from outside: `nu·nv` vertices, `2·nu·nv` triangles.
    ///
    /// # Errors
    ///
    /// [`ShapeError::BadParameter`] unless `big_r` is finite and > 0, `r` is finite and in
    /// (0, `big_r`] (a larger minor radius makes a self-intersecting spindle torus whose inner
    /// triangles face inward), and `nu`, `nv` ≥ 3; [`ShapeError::OutOfRange`] if the extent
    /// `big_r + r` is not a valid value of `S` or rounds to 0 there; [`ShapeError::Capacity`] if
    /// `nu·nv` exceeds `V` or 65 536, or `2·nu·nv` exceeds `T`.
    pub fn torus(big_r: f64, r: f64, nu: usize, nv: usize) -> Result<Self, ShapeError> {
        let mut s = Self::new();
        s.set_torus(big_r, r, nu, nv)?;
        Ok(s)
    }

    /// An empty shape (no vertex, no triangle), as a `const fn`: storage for a shape that is
    /// then built in place ([`Shape::set_torus`]), e.g. in a `static` on a part whose stack
    /// cannot hold a shape returned by value.
    #[must_use]
    pub const fn new() -> Self {
        Shape {
            positions: Vec::new(),
            normals: Vec::new(),
            indices: Vec::new(),
        }
    }

    /// Makes this shape [`Shape::torus`]`(big_r, r, nu, nv)` in place: the same vertices and
    /// triangles, with no copy of the shape on the stack.
    ///
    /// # Errors
    ///
    /// As [`Shape::torus`]; the shape is then left unchanged.
    pub fn set_torus(
        &mut self,
        big_r: f64,
        r: f64,
        nu: usize,
        nv: usize,
    ) -> Result<(), ShapeError> {
        positive("big_r", big_r)?;
        positive("r", r)?;
        if r > big_r {
            return Err(ShapeError::BadParameter {
                name: "r",
                value: ParamValue::Real(r),
                expected: "<= big_r",
            });
        }
        at_least("nu", nu, 3, ">= 3")?;
        at_least("nv", nv, 3, ">= 3")?;
        Self::check_extent(big_r + r)?;
        let vertices = nu.checked_mul(nv);
        let triangles = vertices.and_then(|n| n.checked_mul(2));
        // After this, nu·nv ≤ 65 536: the loops below are bounded by the capacity.
        Self::check_capacity(vertices, triangles)?;
        // Emptied in place (a new shape assigned here would be built on the stack first).
        self.positions.clear();
        self.normals.clear();
        self.indices.clear();
        for i in 0..nu {
            let (su, cu) = libm::sincos(2.0 * PI * i as f64 / nu as f64);
            for j in 0..nv {
                let (sv, cv) = libm::sincos(2.0 * PI * j as f64 / nv as f64);
                self.vertex(
                    [(big_r + r * cv) * cu, (big_r + r * cv) * su, r * sv],
                    [cv * cu, cv * su, sv],
                );
            }
        }
        for i in 0..nu {
            for j in 0..nv {
                let id = |i: usize, j: usize| (i % nu) * nv + (j % nv);
                self.tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
                self.tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
            }
        }
        Ok(())
    }

    /// A sphere of `radius` made by subdividing an icosahedron `subdivisions` times:
    /// `10·4ⁿ + 2` vertices and `20·4ⁿ` triangles (n = 0..=4).
    ///
    /// # Errors
    ///
    /// [`ShapeError::BadParameter`] unless `radius` is finite and > 0 and `subdivisions` ≤ 4;
    /// [`ShapeError::OutOfRange`] if ±`radius` is not a valid value of `S` or rounds to 0
    /// there; [`ShapeError::Capacity`] if `V` or `T` is below the counts above.
    pub fn icosphere(radius: f64, subdivisions: u32) -> Result<Self, ShapeError> {
        positive("radius", radius)?;
        if subdivisions > 4 {
            return Err(ShapeError::BadParameter {
                name: "subdivisions",
                value: ParamValue::Count(u64::from(subdivisions)),
                expected: "0..=4",
            });
        }
        Self::check_extent(radius)?;
        // 4ⁿ ≤ 256: the counts are at most 2 562 and 5 120.
        let n4 = 1usize << (2 * subdivisions);
        let (nv, nt) = (10 * n4 + 2, 20 * n4);
        let mut s = Self::with_capacity_for(Some(nv), Some(nt))?;
        // Unit-sphere positions in f64 while subdividing; converted at the end.
        let mut pos: Vec<[f64; 3], 2562> = Vec::new();
        let mut tris: Vec<[u16; 3], 5120> = Vec::new();
        let t = (1.0 + libm::sqrt(5.0)) / 2.0;
        let base = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ];
        let unit = |p: [f64; 3]| {
            let l = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            [p[0] / l, p[1] / l, p[2] / l]
        };
        for p in base {
            let _ = pos.push(unit(p));
        }
        let faces: [[u16; 3]; 20] = [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for f in faces {
            let _ = tris.push(f);
        }
        for _ in 0..subdivisions {
            let old: Vec<[u16; 3], 5120> = tris.clone();
            let first_new = pos.len();
            tris.clear();
            for [a, b, c] in old {
                let mut mid = |i: u16, j: u16| -> u16 {
                    let (pi, pj) = (pos[i as usize], pos[j as usize]);
                    let m = unit([
                        (pi[0] + pj[0]) * 0.5,
                        (pi[1] + pj[1]) * 0.5,
                        (pi[2] + pj[2]) * 0.5,
                    ]);
                    // The same edge from the neighbouring face computes the same bits.
                    if let Some(k) = pos[first_new..].iter().position(|q| *q == m) {
                        return (first_new + k) as u16;
                    }
                    let _ = pos.push(m);
                    (pos.len() - 1) as u16
                };
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                for t in [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]] {
                    let _ = tris.push(t);
                }
            }
        }
        for p in &pos {
            s.vertex(p.map(|v| v * radius), *p);
        }
        for t in &tris {
            s.tri(t[0] as usize, t[1] as usize, t[2] as usize);
        }
        Ok(s)
    }

    /// A flat rectangle in the XZ plane (y = 0) centred at the origin, facing up (+Y): a
    /// ground plane, or with one cell a quad of 4 vertices and 2 triangles. It is `size_x`
    /// world units along X and `size_z` along Z, divided into `cells_x × cells_z` equal cells
    /// (more cells follow a specular highlight more closely and split a large ground into
    /// smaller triangles; a directional light lights a flat plane evenly with any number).
    /// Vertex `(i, k)` (i = 0..=cells_x along X, k = 0..=cells_z along Z) has index
    /// `i·(cells_z+1) + k`, position `(size_x·(i/cells_x − ½), 0, size_z·(k/cells_z − ½))` and
    /// normal `(0, 1, 0)`; each cell gives triangles `(i,k),(i,k+1),(i+1,k)` and
    /// `(i+1,k),(i,k+1),(i+1,k+1)`, counter-clockwise seen from above:
    /// `(cells_x+1)·(cells_z+1)` vertices, `2·cells_x·cells_z` triangles. Seen from below it is
    /// back-facing and culled (flip it with a rotation of π about X for a ceiling).
    ///
    /// # Errors
    ///
    /// [`ShapeError::BadParameter`] unless `size_x` and `size_z` are finite and > 0 and
    /// `cells_x`, `cells_z` ≥ 1; [`ShapeError::OutOfRange`] if the extent `max(size_x,
    /// size_z)` (the largest difference between two vertices' coordinates, which flat shading
    /// takes in `S`) is not a valid value of `S`, or if half the smaller size (the smallest
    /// coordinate of a corner) rounds to 0 there; [`ShapeError::Capacity`] if
    /// `(cells_x+1)·(cells_z+1)` exceeds `V` or 65 536, or `2·cells_x·cells_z` exceeds `T`.
    pub fn plane(
        size_x: f64,
        size_z: f64,
        cells_x: usize,
        cells_z: usize,
    ) -> Result<Self, ShapeError> {
        positive("size_x", size_x)?;
        positive("size_z", size_z)?;
        at_least("cells_x", cells_x, 1, ">= 1")?;
        at_least("cells_z", cells_z, 1, ">= 1")?;
        Self::check_extent(size_x.max(size_z))?;
        // Smaller than the checked extent, so only its rounding to 0 can fail.
        Self::check_extent(size_x.min(size_z) * 0.5)?;
        let vertices = cells_x
            .checked_add(1)
            .zip(cells_z.checked_add(1))
            .and_then(|(a, b)| a.checked_mul(b));
        let triangles = cells_x.checked_mul(cells_z).and_then(|c| c.checked_mul(2));
        // After this, (cells_x+1)·(cells_z+1) ≤ 65 536: the loops below are bounded by the
        // capacity.
        let mut s = Self::with_capacity_for(vertices, triangles)?;
        let n = cells_z + 1;
        for i in 0..=cells_x {
            let x = size_x * (i as f64 / cells_x as f64 - 0.5);
            for k in 0..=cells_z {
                let z = size_z * (k as f64 / cells_z as f64 - 0.5);
                s.vertex([x, 0.0, z], [0.0, 1.0, 0.0]);
            }
        }
        for i in 0..cells_x {
            for k in 0..cells_z {
                let id = |i: usize, k: usize| i * n + k;
                s.tri(id(i, k), id(i, k + 1), id(i + 1, k));
                s.tri(id(i + 1, k), id(i, k + 1), id(i + 1, k + 1));
            }
        }
        Ok(s)
    }

    /// A height-field terrain in the XZ plane, `size × size` world units centred at the origin,
    /// `cells × cells` quads, height `amplitude · sin(2.1x)·cos(1.7z)`-style rolling hills
    /// (amplitude 0 gives a flat ground plane). Faces up (+Y); normals are face averages.
    /// `(cells+1)²` vertices, `2·cells²` triangles.
    ///
    /// # Errors
    ///
    /// [`ShapeError::BadParameter`] unless `size` is finite, > 0 and at most `f64::MAX / π`,
    /// `cells` ≥ 1 and `amplitude` is finite (any sign; negative turns hills into valleys);
    /// [`ShapeError::OutOfRange`] if the extent `max(size, 2·|amplitude|)` (the largest
    /// difference between two vertices' coordinates, from which the normals are computed in
    /// `S`) is not a valid value of `S` or rounds to 0 there; [`ShapeError::Capacity`] if
    /// `(cells+1)²` exceeds `V` or 65 536, or `2·cells²` exceeds `T`.
    pub fn terrain(size: f64, cells: usize, amplitude: f64) -> Result<Self, ShapeError> {
        positive("size", size)?;
        at_least("cells", cells, 1, ">= 1")?;
        if !amplitude.is_finite() {
            return Err(ShapeError::BadParameter {
                name: "amplitude",
                value: ParamValue::Real(amplitude),
                expected: "finite",
            });
        }
        // The hills' phase 2π·x/size, with |x| ≤ size/2, must not overflow f64.
        if !(2.0 * PI * (size * 0.5)).is_finite() {
            return Err(ShapeError::BadParameter {
                name: "size",
                value: ParamValue::Real(size),
                expected: "finite, > 0 and at most f64::MAX / π",
            });
        }
        // |x|, |z| ≤ size/2 and |y| ≤ |amplitude|·(0.6 + 0.4), so two vertices differ by at
        // most size or 2·|amplitude| in a coordinate: the normals are computed in S from those
        // differences, which must not saturate.
        Self::check_extent(size.max(2.0 * amplitude.abs()))?;
        let n = cells.checked_add(1);
        let vertices = n.and_then(|n| n.checked_mul(n));
        let triangles = cells.checked_mul(cells).and_then(|c| c.checked_mul(2));
        // After this, (cells+1)² ≤ 65 536: the loops below are bounded by the capacity.
        let mut s = Self::with_capacity_for(vertices, triangles)?;
        let n = cells + 1;
        for i in 0..n {
            for k in 0..n {
                let x = size * (i as f64 / cells as f64 - 0.5);
                let z = size * (k as f64 / cells as f64 - 0.5);
                let fx = 2.0 * PI * x / size;
                let fz = 2.0 * PI * z / size;
                let y = amplitude
                    * (0.6 * libm::sin(2.0 * fx + 0.3) * libm::cos(1.5 * fz)
                        + 0.4 * libm::sin(3.0 * fz + fx));
                s.vertex([x, y, z], [0.0, 1.0, 0.0]);
            }
        }
        for i in 0..cells {
            for k in 0..cells {
                let id = |i: usize, k: usize| i * n + k;
                s.tri(id(i, k), id(i, k + 1), id(i + 1, k));
                s.tri(id(i + 1, k), id(i, k + 1), id(i + 1, k + 1));
            }
        }
        let mut normals = s.normals.clone();
        // Cannot fail: same lengths, indices in range by construction.
        let _ = vertex_normals(&s.positions, &s.indices, &mut normals);
        s.normals = normals;
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::math::{cross, dot, sub};
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    fn outward<const V: usize, const T: usize>(s: &Shape<f64, V, T>) {
        for t in &s.indices {
            let [a, b, c] = t.map(|i| s.positions[i as usize]);
            let n = cross(sub(b, a), sub(c, a));
            let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
            let vn = s.normals[t[0] as usize];
            assert!(dot(n, vn) > 0.0, "triangle {t:?} faces inward");
            let _ = centroid;
        }
    }

    #[test]
    fn torus_matches_the_spec() {
        let s = Shape::<f64, 512, 1024>::torus(1.0, 0.4, 32, 16).unwrap();
        assert_eq!((s.positions.len(), s.indices.len()), (512, 1024));
        assert_eq!(s.indices[0], [0, 16, 17]);
        assert_eq!(s.indices[1], [0, 17, 1]);
        assert!((s.positions[0][0] - 1.4).abs() < 1e-12);
        outward(&s);
    }

    #[test]
    fn cube_and_icosphere_face_outward() {
        outward(&Shape::<f64, 24, 12>::cube(1.0).unwrap());
        let ico = Shape::<f64, 642, 1280>::icosphere(1.0, 3).unwrap();
        assert_eq!((ico.positions.len(), ico.indices.len()), (642, 1280));
        outward(&ico);
    }

    #[test]
    fn terrain_faces_up() {
        let t = Shape::<f64, 81, 128>::terrain(4.0, 8, 0.3).unwrap();
        for tri in &t.indices {
            let [a, b, c] = tri.map(|i| t.positions[i as usize]);
            assert!(cross(sub(b, a), sub(c, a))[1] > 0.0);
        }
    }

    #[test]
    fn plane_matches_the_spec_and_faces_up() {
        let p = Shape::<f64, 12, 12>::plane(4.0, 2.0, 3, 2).unwrap();
        assert_eq!((p.positions.len(), p.indices.len()), (12, 12));
        assert_eq!(p.positions[0], [-2.0, 0.0, -1.0]);
        assert_eq!(p.positions[11], [2.0, 0.0, 1.0]);
        assert_eq!(p.indices[0], [0, 1, 3]);
        assert_eq!(p.indices[1], [3, 1, 4]);
        outward(&p);
        for tri in &p.indices {
            let [a, b, c] = tri.map(|i| p.positions[i as usize]);
            assert!(cross(sub(b, a), sub(c, a))[1] > 0.0);
        }
        assert!(p.normals.iter().all(|n| *n == [0.0, 1.0, 0.0]));
        let quad = Shape::<Fx<I16F16>, 4, 2>::plane(1.0, 1.0, 1, 1).unwrap();
        assert_eq!((quad.positions.len(), quad.indices.len()), (4, 2));
        quad.mesh().validate().unwrap();
    }

    #[test]
    fn plane_checks_parameters_range_and_capacity_in_order() {
        type P = Shape<Fx<I16F16>, 16, 18>;
        let bad = |name, value, expected| ShapeError::BadParameter {
            name,
            value,
            expected,
        };
        let real = ParamValue::Real;
        assert!(matches!(
            P::plane(f64::NAN, 1.0, 1, 1).unwrap_err(),
            ShapeError::BadParameter { name: "size_x", value: ParamValue::Real(v), .. } if v.is_nan()
        ));
        for (sx, sz, name, v) in [
            (0.0, 1.0, "size_x", 0.0),
            (-1.0, 1.0, "size_x", -1.0),
            (f64::INFINITY, 1.0, "size_x", f64::INFINITY),
            (1.0, 0.0, "size_z", 0.0),
            (1.0, f64::NEG_INFINITY, "size_z", f64::NEG_INFINITY),
        ] {
            assert_eq!(
                P::plane(sx, sz, 0, 0).unwrap_err(),
                bad(name, real(v), "finite and > 0")
            );
        }
        assert_eq!(
            P::plane(1.0, 1.0, 0, 5).unwrap_err(),
            bad("cells_x", ParamValue::Count(0), ">= 1")
        );
        assert_eq!(
            P::plane(1.0, 1.0, 5, 0).unwrap_err(),
            bad("cells_z", ParamValue::Count(0), ">= 1")
        );
        // Q16.16 holds up to 32 768: a side of 40 000 saturates the edge vectors.
        assert_eq!(
            P::plane(40_000.0, 1.0, 1, 1).unwrap_err(),
            ShapeError::OutOfRange {
                extent: 40_000.0,
                number_type: Fx::<I16F16>::NAME,
                rounds_to_zero: false,
            }
        );
        assert!(matches!(
            P::plane(1.0, 1e-7, 1, 1).unwrap_err(),
            ShapeError::OutOfRange {
                rounds_to_zero: true,
                ..
            }
        ));
        assert!(Shape::<f64, 16, 18>::plane(1.0, 1e-7, 1, 1).is_ok());
        assert_eq!(
            P::plane(1.0, 1.0, 3, 4).unwrap_err(),
            ShapeError::Capacity {
                vertices: Some(20),
                triangles: Some(24),
                vertex_capacity: 16,
                triangle_capacity: 18,
            }
        );
        assert_eq!(
            P::plane(1.0, 1.0, usize::MAX, usize::MAX).unwrap_err(),
            ShapeError::Capacity {
                vertices: None,
                triangles: None,
                vertex_capacity: 16,
                triangle_capacity: 18,
            }
        );
        assert!(P::plane(1.0, 1.0, 3, 3).is_ok());
    }

    #[test]
    fn too_small_capacity_is_an_error_with_counts() {
        let e = Shape::<f32, 100, 100>::torus(1.0, 0.4, 32, 16).unwrap_err();
        assert_eq!(
            e,
            ShapeError::Capacity {
                vertices: Some(512),
                triangles: Some(1024),
                vertex_capacity: 100,
                triangle_capacity: 100,
            }
        );
    }
}
