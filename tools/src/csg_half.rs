//! Plane and general quadric half-spaces for the CSG format (tools/src/csg.rs).
//!
//! A half-space `f(x, y, z) ≤ 0` is kept symbolically, as the symmetric 4 × 4 matrix `Q` with
//! `f(p) = [p 1] Q [p 1]ᵀ` (f64), so transforms are exact on the coefficients
//! (`f'(p) = f(T⁻¹ p)`, `Q' = T⁻ᵀ Q T⁻¹`). It is unbounded in general, so it only becomes a mesh
//! once an `intersection` or `difference` gives it a bounded operand to meet, and then only over
//! that operand's bounding box (enlarged by a margin):
//!
//! - a plane (no second-degree term) becomes a box with one face exactly on the plane, large
//!   enough to hold the bound: flat cuts stay exact, like the boxes' faces;
//! - any other quadric is meshed as an implicit surface with naive surface nets
//!   (`fast-surface-nets`, a maintained crates.io mesher) on a grid over the enlarged bound, the
//!   grid's outer layer forced outside so the surface closes there. The closing caps lie in the
//!   margin, outside the bounded operand, and the mesh booleans cut them away, so what is left is
//!   the quadric's surface inside the operand and the operand's own exact faces. Surface nets were
//!   chosen over a parametric construction because one path then serves every quadric (ellipsoids,
//!   paraboloids, hyperboloids, elliptic cylinders and cones, in any orientation) without
//!   classifying it, and over marching cubes because their vertices sit inside the cells rather
//!   than on cell edges, which as a rule gives fewer slivers (not compared here). The price: the
//!   surface is an approximation (each vertex averages the linear interpolations of `f / |∇f|`
//!   along its cell's crossed edges, so it sits a little inside a convex surface: volumes −1.4 %
//!   to +0.3 % in tests/csg.rs at 24 segments), and a singular point (a cone's apex) may come out
//!   non-manifold, which is then reported as an error.

use super::{box_mesh, check_closed, signed_volume, CsgMesh};

/// A half-space `[p 1] q [p 1]ᵀ ≤ 0`; `q` is symmetric.
#[derive(Clone, Debug)]
pub struct HalfSpace {
    pub q: [[f64; 4]; 4],
}

/// Grid cells along the longest side of the enlarged bound for each `segments` step: with the
/// default 24 segments, 24 cells.
const CELLS_PER_SEGMENT: usize = 1;

/// The smallest bound a quadric is meshed in, in model units: 2⁻¹², 4 096 steps of the 2⁻²⁴
/// grid the booleans snap to.
const MIN_SIZE: f64 = 1.0 / 4096.0;

/// Cells of margin around the bound (the grid's closing caps round off within two cells).
const MARGIN_CELLS: f64 = 3.0;

impl HalfSpace {
    /// `a x + b y + c z + d ≤ 0`.
    pub fn plane(a: f64, b: f64, c: f64, d: f64) -> Self {
        Self::quadric([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, a, b, c, d])
    }

    /// `A x² + B y² + C z² + D xy + E yz + F xz + G x + H y + I z + J ≤ 0`, coefficients in that
    /// order.
    pub fn quadric(k: [f64; 10]) -> Self {
        let [a, b, c, d, e, f, g, h, i, j] = k;
        let mut hs = HalfSpace {
            q: [
                [a, d / 2.0, f / 2.0, g / 2.0],
                [d / 2.0, b, e / 2.0, h / 2.0],
                [f / 2.0, e / 2.0, c, i / 2.0],
                [g / 2.0, h / 2.0, i / 2.0, j],
            ],
        };
        hs.normalize();
        hs
    }

    /// Divides every coefficient by the largest magnitude (a positive factor: the same
    /// half-space), so that sums and products of coefficients stay far from overflow and
    /// underflow whatever the scale the text gave.
    fn normalize(&mut self) {
        let m = self.q.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        if m > 0.0 && m.is_finite() {
            self.q = self.q.map(|r| r.map(|x| x / m));
        }
    }

    /// Every coefficient finite.
    pub fn is_finite(&self) -> bool {
        self.q.iter().flatten().all(|x| x.is_finite())
    }

    /// No second-degree term: a plane.
    pub fn is_plane(&self) -> bool {
        (0..3).all(|i| (0..3).all(|j| self.q[i][j] == 0.0))
    }

    /// No term in x, y or z at all (the whole space or nothing).
    pub fn is_constant(&self) -> bool {
        (0..3).all(|i| (0..4).all(|j| self.q[i][j] == 0.0))
    }

    /// The complement `f ≥ 0`, as `−f ≤ 0` (the boundary belongs to both).
    pub fn complement(&self) -> Self {
        HalfSpace {
            q: self.q.map(|r| r.map(|x| -x)),
        }
    }

    /// Applies a transform given by its inverse `inv` (an affine 4 × 4 matrix, last row 0 0 0 1).
    pub fn transform_by_inverse(&mut self, inv: [[f64; 4]; 4]) {
        // Scaling the inverse by a positive factor scales f by its square: the same half-space,
        // and no overflow from a large inverse (a tiny `scale`).
        let m = inv.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let inv = inv.map(|r| r.map(|x| x / m));
        let mut t = [[0.0; 4]; 4];
        for (i, row) in t.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (0..4)
                    .flat_map(|k| (0..4).map(move |l| (k, l)))
                    .map(|(k, l)| inv[k][i] * self.q[k][l] * inv[l][j])
                    .sum();
            }
        }
        self.q = t;
        self.normalize();
    }

    /// `f(p)`.
    pub fn value(&self, p: [f64; 3]) -> f64 {
        let x = [p[0], p[1], p[2], 1.0];
        (0..4)
            .map(|i| (0..4).map(|j| x[i] * self.q[i][j] * x[j]).sum::<f64>())
            .sum()
    }

    /// `∇f(p)`.
    pub fn gradient(&self, p: [f64; 3]) -> [f64; 3] {
        let x = [p[0], p[1], p[2], 1.0];
        [0, 1, 2].map(|i| 2.0 * (0..4).map(|j| self.q[i][j] * x[j]).sum::<f64>())
    }

    /// The half-space as a closed solid over the box `lo..hi` enlarged by a margin: the solid
    /// agrees with the half-space inside `lo..hi`. `Ok(None)` when the half-space holds the whole
    /// box (nothing to cut), `Err` when it misses the box or cannot be meshed.
    pub fn bounded_mesh(
        &self,
        lo: [f64; 3],
        hi: [f64; 3],
        segments: usize,
    ) -> Result<Option<CsgMesh>, String> {
        if !self.is_finite() || self.is_constant() {
            return Err("its coefficients are out of range after the transforms".into());
        }
        if self.is_plane() {
            return self.plane_mesh(lo, hi);
        }
        // An ellipsoid is bounded itself: the grid then covers only the common part of both
        // boxes, so its cells follow the ellipsoid's size rather than the operand's.
        let (lo, hi) = match self.ellipsoid_bounds() {
            Some((elo, ehi)) => {
                let lo = [0, 1, 2].map(|k| lo[k].max(elo[k]));
                let hi = [0, 1, 2].map(|k| hi[k].min(ehi[k]));
                if (0..3).any(|k| lo[k] >= hi[k]) {
                    return Err(
                        "the quadric does not reach its bounded operand (nothing is inside)".into(),
                    );
                }
                (lo, hi)
            }
            None => (lo, hi),
        };
        let longest = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        // The booleans snap to a 2⁻²⁴ grid: a surface much smaller would collapse.
        if longest.is_nan() || longest < MIN_SIZE {
            return Err(format!(
                "the quadric's part inside its operand is too small to mesh (under {MIN_SIZE:e} across)"
            ));
        }
        let inner = (segments * CELLS_PER_SEGMENT) as f64;
        let h = longest / inner;
        let origin = [0, 1, 2].map(|k| lo[k] - MARGIN_CELLS * h);
        let n = [0, 1, 2].map(|k| ((hi[k] - lo[k]) / h + 2.0 * MARGIN_CELLS).ceil() as u32 + 1);
        let at = |x: u32, y: u32, z: u32| {
            [x, y, z]
                .iter()
                .enumerate()
                .map(|(k, &c)| origin[k] + c as f64 * h)
                .collect::<Vec<_>>()
        };
        let mut sdf = Vec::with_capacity((n[0] * n[1] * n[2]) as usize);
        let (mut inside, mut outside) = (0usize, 0usize);
        for z in 0..n[2] {
            for y in 0..n[1] {
                for x in 0..n[0] {
                    let p = at(x, y, z);
                    let p = [p[0], p[1], p[2]];
                    let g = self.gradient(p);
                    // f / |∇f| is close to a distance near the surface (so edges interpolate
                    // well); the floor keeps the sign where the gradient vanishes (a centre).
                    let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt().max(1e-12);
                    // Two layers on the high sides: surface nets make no face in the last cell there.
                    let border = [x, y, z].iter().zip(n).any(|(&c, m)| c == 0 || c + 2 >= m);
                    let d = (self.value(p) / len).clamp(-1e30, 1e30) as f32;
                    let within = (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k]);
                    if within {
                        if d < 0.0 {
                            inside += 1;
                        } else {
                            outside += 1;
                        }
                    }
                    sdf.push(if border { h as f32 } else { d });
                }
            }
        }
        if inside == 0 {
            return Err(
                "the quadric does not reach its bounded operand (nothing is inside)".into(),
            );
        }
        if outside == 0 {
            return Ok(None);
        }
        let shape = fast_surface_nets::ndshape::RuntimeShape::<u32, 3>::new(n);
        let mut buf = fast_surface_nets::SurfaceNetsBuffer::default();
        fast_surface_nets::surface_nets(
            &sdf,
            &shape,
            [0; 3],
            [n[0] - 1, n[1] - 1, n[2] - 1],
            &mut buf,
        );
        let mut mesh = CsgMesh {
            positions: buf
                .positions
                .iter()
                .map(|p| [0, 1, 2].map(|k| origin[k] + f64::from(p[k]) * h))
                .collect(),
            triangles: buf.indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect(),
        };
        check_closed(&mesh).map_err(|e| {
            format!("the quadric's surface mesh is not closed ({e}); try other `segments`")
        })?;
        // Surface nets wind by the sign change; turn the whole closed mesh outward if needed.
        if signed_volume(&mesh) < 0.0 {
            for t in &mut mesh.triangles {
                t.swap(1, 2);
            }
        }
        Ok(Some(mesh))
    }

    /// The bounding box of an ellipsoid (a positive definite second-degree part `A`): centre
    /// `c = −A⁻¹ b` (with `b` the half-gradient at the origin), half-extent along axis k
    /// `√(−f(c) · (A⁻¹)ₖₖ)`. `None` for any other quadric (or an empty ellipsoid).
    fn ellipsoid_bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let q = &self.q;
        let a = |i: usize, j: usize| q[i][j];
        let m1 = a(0, 0);
        let m2 = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
        let det = a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1))
            - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0))
            + a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
        if !(m1 > 0.0 && m2 > 0.0 && det > 0.0) {
            return None;
        }
        // The inverse by cofactors (A is symmetric).
        let cof = |i: usize, j: usize| {
            let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
            let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
            a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0)
        };
        let inv = [0, 1, 2].map(|i| [0, 1, 2].map(|j| cof(j, i) / det));
        let b = [q[0][3], q[1][3], q[2][3]];
        let c = [0, 1, 2].map(|i| -(0..3).map(|j| inv[i][j] * b[j]).sum::<f64>());
        let r = -self.value(c);
        if r <= 0.0 {
            return None;
        }
        let e = [0, 1, 2].map(|k| (r * inv[k][k]).sqrt());
        let (lo, hi) = (
            [0, 1, 2].map(|k| c[k] - e[k]),
            [0, 1, 2].map(|k| c[k] + e[k]),
        );
        lo.iter()
            .chain(&hi)
            .all(|x| x.is_finite())
            .then_some((lo, hi))
    }

    /// A box with its top face on the plane, holding `lo..hi` (enlarged) below it.
    fn plane_mesh(&self, lo: [f64; 3], hi: [f64; 3]) -> Result<Option<CsgMesh>, String> {
        let q = &self.q;
        let g = [2.0 * q[0][3], 2.0 * q[1][3], 2.0 * q[2][3]];
        let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        let nrm = g.map(|x| x / len);
        let centre = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
        let half_diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt() / 2.0;
        // The signed distance of the centre from the plane.
        let s = self.value(centre) / len;
        if s <= -half_diagonal {
            return Ok(None);
        }
        if s >= half_diagonal {
            return Err("the plane leaves nothing of its bounded operand".into());
        }
        let r = half_diagonal * 1.5 + 1e-3;
        // A right-handed frame (u, v, n): u × v = n keeps the winding.
        let a = if nrm[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = super::cross(a, nrm);
        let ul = super::dot(u, u).sqrt();
        let u = u.map(|x| x / ul);
        let v = super::cross(nrm, u);
        let foot = [0, 1, 2].map(|k| centre[k] - s * nrm[k]);
        let mut mesh = box_mesh(2.0 * r, 2.0 * r, 2.0 * r);
        for p in &mut mesh.positions {
            let (x, y, z) = (p[0], p[1], p[2] - r);
            *p = [0, 1, 2].map(|k| foot[k] + x * u[k] + y * v[k] + z * nrm[k]);
        }
        Ok(Some(mesh))
    }
}
