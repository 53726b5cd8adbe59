//! Built-in procedural meshes for tests, benchmarks and demos: cube, torus, icosphere and a
//! height-field terrain grid.
//!
//! Shapes are generated in `f64` (libm, pure software, so bit-identical on every target) and
//! rounded once to `S`. Their storage is sized at compile time: `V` vertices and `T` triangles;
//! a shape that does not fit returns [`ShapeError`] with the counts it needs.

use core::f64::consts::PI;

use heapless::Vec;

use crate::math::Vec3;
use crate::mesh::{vertex_normals, Mesh};
use crate::scalar::Scalar;

/// A generated mesh with its own storage: `V` vertices (positions and unit normals) and `T`
/// triangles.
#[derive(Clone, Debug)]
pub struct Shape<S, const V: usize, const T: usize> {
    /// Positions.
    pub positions: Vec<Vec3<S>, V>,
    /// Unit vertex normals.
    pub normals: Vec<Vec3<S>, V>,
    /// Counter-clockwise triangles.
    pub indices: Vec<[u16; 3], T>,
}

/// The shape does not fit its compile-time capacity (or its parameters are out of range).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ShapeError {
    /// Vertices the shape needs.
    pub vertices: usize,
    /// Triangles the shape needs.
    pub triangles: usize,
}

impl<S: Scalar, const V: usize, const T: usize> Shape<S, V, T> {
    fn with_capacity_for(vertices: usize, triangles: usize) -> Result<Self, ShapeError> {
        if vertices > V || triangles > T || vertices > 1 << 16 {
            return Err(ShapeError {
                vertices,
                triangles,
            });
        }
        Ok(Shape {
            positions: Vec::new(),
            normals: Vec::new(),
            indices: Vec::new(),
        })
    }

    fn vertex(&mut self, p: [f64; 3], n: [f64; 3]) {
        // Capacity was checked up front.
        let _ = self.positions.push(p.map(S::from_f64));
        let _ = self.normals.push(n.map(S::from_f64));
    }

    fn tri(&mut self, a: usize, b: usize, c: usize) {
        let _ = self.indices.push([a as u16, b as u16, c as u16]);
    }

    /// The mesh, with normals.
    #[must_use]
    pub fn mesh(&self) -> Mesh<'_, S> {
        // At most 65 536 vertices (checked on creation) and one normal per position.
        Mesh::from_parts(&self.positions, &self.indices, Some(&self.normals))
    }

    /// An axis-aligned cube of half-size `h` centred at the origin: 24 vertices (4 per face, with
    /// the face's normal) and 12 triangles.
    pub fn cube(h: f64) -> Result<Self, ShapeError> {
        let mut s = Self::with_capacity_for(24, 12)?;
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
    pub fn torus(big_r: f64, r: f64, nu: usize, nv: usize) -> Result<Self, ShapeError> {
        if nu < 3 || nv < 3 {
            return Err(ShapeError {
                vertices: nu * nv,
                triangles: 2 * nu * nv,
            });
        }
        let mut s = Self::with_capacity_for(nu * nv, 2 * nu * nv)?;
        for i in 0..nu {
            let (su, cu) = libm::sincos(2.0 * PI * i as f64 / nu as f64);
            for j in 0..nv {
                let (sv, cv) = libm::sincos(2.0 * PI * j as f64 / nv as f64);
                s.vertex(
                    [(big_r + r * cv) * cu, (big_r + r * cv) * su, r * sv],
                    [cv * cu, cv * su, sv],
                );
            }
        }
        for i in 0..nu {
            for j in 0..nv {
                let id = |i: usize, j: usize| (i % nu) * nv + (j % nv);
                s.tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
                s.tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
            }
        }
        Ok(s)
    }

    /// A sphere of `radius` made by subdividing an icosahedron `subdivisions` times:
    /// `10·4ⁿ + 2` vertices and `20·4ⁿ` triangles (n = 0..=4).
    pub fn icosphere(radius: f64, subdivisions: u32) -> Result<Self, ShapeError> {
        let n4 = 1usize << (2 * subdivisions.min(8));
        let (nv, nt) = (10 * n4 + 2, 20 * n4);
        if subdivisions > 4 {
            return Err(ShapeError {
                vertices: nv,
                triangles: nt,
            });
        }
        let mut s = Self::with_capacity_for(nv, nt)?;
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

    /// A height-field terrain in the XZ plane, `size × size` world units centred at the origin,
    /// `cells × cells` quads, height `amplitude · sin(2.1x)·cos(1.7z)`-style rolling hills
    /// (amplitude 0 gives a flat ground plane). Faces up (+Y); normals are face averages.
    /// `(cells+1)²` vertices, `2·cells²` triangles.
    pub fn terrain(size: f64, cells: usize, amplitude: f64) -> Result<Self, ShapeError> {
        let n = cells + 1;
        if cells == 0 {
            return Err(ShapeError {
                vertices: 1,
                triangles: 0,
            });
        }
        let mut s = Self::with_capacity_for(n * n, 2 * cells * cells)?;
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
    use crate::math::{cross, dot, sub};

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
    fn too_small_capacity_is_an_error_with_counts() {
        let e = Shape::<f32, 100, 100>::torus(1.0, 0.4, 32, 16).unwrap_err();
        assert_eq!(
            e,
            ShapeError {
                vertices: 512,
                triangles: 1024
            }
        );
    }
}
