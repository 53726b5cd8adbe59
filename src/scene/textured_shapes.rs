//! The built-in shapes with texture coordinates: each a [`Shape`] plus one `(s, t)` per
//! vertex, with a vertex split wherever two faces need different coordinates (a UV seam) and
//! only there.

use core::f64::consts::PI;

use heapless::Vec;

use crate::num::scalar::Scalar;
use crate::scene::mesh::Mesh;
use crate::scene::shapes::{Shape, ShapeError};

/// A [`Shape`] with texture coordinates (see [`crate::Texture`] for their orientation).
#[derive(Clone, Debug)]
pub struct TexturedShape<S, const V: usize, const T: usize> {
    /// Positions, normals and triangles.
    pub shape: Shape<S, V, T>,
    /// `(s, t)` of each vertex (rounded once from `f64`).
    pub uvs: Vec<[S; 2], V>,
}

impl<S: Scalar, const V: usize, const T: usize> TexturedShape<S, V, T> {
    /// The mesh, with normals and texture coordinates.
    #[must_use]
    pub fn mesh(&self) -> Mesh<'_, S> {
        let m = self.shape.mesh();
        // One coordinate per vertex, each within [0, 2] (checked by construction).
        m.with_uvs(&self.uvs).unwrap_or(m)
    }

    fn push_uv(&mut self, st: [f64; 2]) {
        // Capacity was checked with the shape's.
        let _ = self.uvs.push(st.map(S::from_f64));
    }

    /// [`Shape::cube`] with each face showing the whole texture, upright on the four side
    /// faces (24 vertices, as the cube has: its faces share no vertex).
    ///
    /// # Errors
    ///
    /// As [`Shape::cube`].
    pub fn cube(h: f64) -> Result<Self, ShapeError> {
        let shape = Shape::cube(h)?;
        let mut s = TexturedShape {
            shape,
            uvs: Vec::new(),
        };
        // The cube's corners in each face's (u, v) axes, in its vertex order.
        for _ in 0..6 {
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                s.push_uv([(a + 1.0) * 0.5, (1.0 - b) * 0.5]);
            }
        }
        Ok(s)
    }

    /// A torus as [`Shape::torus`] but with the seams split: `(nu + 1)·(nv + 1)` vertices,
    /// vertex `(i, j)` at index `i·(nv + 1) + j` with `s = i/nu`, `t = j/nv` (the texture once
    /// around each circle), `2·nu·nv` triangles.
    ///
    /// # Errors
    ///
    /// As [`Shape::torus`], with the vertex count above.
    pub fn torus(big_r: f64, r: f64, nu: usize, nv: usize) -> Result<Self, ShapeError> {
        // The parameter and range checks of the plain torus (which has no room to be built).
        match Shape::<S, 0, 0>::torus(big_r, r, nu, nv) {
            Err(ShapeError::Capacity { .. }) | Ok(_) => {}
            Err(e) => return Err(e),
        }
        // Checked: `nu + 1` itself overflows for `nu = usize::MAX` (reported as `None`).
        let vertices = nu
            .checked_add(1)
            .zip(nv.checked_add(1))
            .and_then(|(a, b)| a.checked_mul(b));
        let triangles = nu.checked_mul(nv).and_then(|n| n.checked_mul(2));
        let shape = Shape::with_capacity_for(vertices, triangles)?;
        let mut s = TexturedShape {
            shape,
            uvs: Vec::new(),
        };
        for i in 0..=nu {
            let (su, cu) = libm::sincos(2.0 * PI * (i % nu) as f64 / nu as f64);
            for j in 0..=nv {
                let (sv, cv) = libm::sincos(2.0 * PI * (j % nv) as f64 / nv as f64);
                s.shape.vertex(
                    [(big_r + r * cv) * cu, (big_r + r * cv) * su, r * sv],
                    [cv * cu, cv * su, sv],
                );
                s.push_uv([i as f64 / nu as f64, j as f64 / nv as f64]);
            }
        }
        let id = |i: usize, j: usize| i * (nv + 1) + j;
        for i in 0..nu {
            for j in 0..nv {
                s.shape.tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
                s.shape.tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
            }
        }
        Ok(s)
    }

    /// [`Shape::terrain`] with the texture once over the whole square: vertex `(i, k)` has
    /// `s = i/cells`, `t = k/cells` (no seams).
    ///
    /// # Errors
    ///
    /// As [`Shape::terrain`].
    pub fn terrain(size: f64, cells: usize, amplitude: f64) -> Result<Self, ShapeError> {
        let shape = Shape::terrain(size, cells, amplitude)?;
        let mut s = TexturedShape {
            shape,
            uvs: Vec::new(),
        };
        for i in 0..=cells {
            for k in 0..=cells {
                s.push_uv([i as f64 / cells as f64, k as f64 / cells as f64]);
            }
        }
        Ok(s)
    }

    /// [`Shape::icosphere`] with the equirectangular mapping `s = ½ + atan2(z, x)/2π`,
    /// `t = ½ − asin(y)/π` (north pole at the top of the image): a triangle that crosses the
    /// seam (`s` jumps by more than ½) uses copies of its vertices with `s + 1` (shared with
    /// its neighbours across the seam), and every triangle at a pole its own copy of the pole
    /// with the mean `s` of its other two vertices. The copies follow the icosphere's own
    /// vertices (fewer than 100 more at every subdivision count). Without subdivisions the
    /// icosahedron has edges through the poles, which no such mapping can follow: use at
    /// least one subdivision for a textured sphere.
    ///
    /// # Errors
    ///
    /// As [`Shape::icosphere`]; [`ShapeError::Capacity`] with the vertex count after the
    /// copies when `V` cannot hold them.
    pub fn icosphere(radius: f64, subdivisions: u32) -> Result<Self, ShapeError> {
        let shape = Shape::<S, V, T>::icosphere(radius, subdivisions)?;
        let mut s = TexturedShape {
            shape,
            uvs: Vec::new(),
        };
        let unit = |n: &[S; 3]| n.map(|v| v.to_f64());
        let pole = |p: [f64; 3]| p[0].abs() < 1e-9 && p[2].abs() < 1e-9;
        let uv = |p: [f64; 3]| {
            [
                0.5 + libm::atan2(p[2], p[0]) / (2.0 * PI),
                0.5 - libm::asin(p[1].clamp(-1.0, 1.0)) / PI,
            ]
        };
        let mut st: Vec<[f64; 2], V> = Vec::new();
        for n in &s.shape.normals {
            let _ = st.push(uv(unit(n)));
        }
        // Seam copies as (original, copy), so that neighbours across the seam share one.
        let mut seam: Vec<(u16, u16), 256> = Vec::new();
        let mut needed = s.shape.positions.len();
        let mut copy = |s: &mut Self, st: &mut Vec<[f64; 2], V>, i: u16, c: [f64; 2]| -> u16 {
            needed += 1;
            let (p, n) = (s.shape.positions[i as usize], s.shape.normals[i as usize]);
            if s.shape.positions.push(p).is_err() || st.push(c).is_err() {
                return i;
            }
            let _ = s.shape.normals.push(n);
            (s.shape.positions.len() - 1) as u16
        };
        for ti in 0..s.shape.indices.len() {
            let mut t = s.shape.indices[ti];
            let at_pole = t.map(|i| pole(unit(&s.shape.normals[i as usize])));
            let ss = [0, 1, 2].map(|k| st[t[k] as usize][0]);
            let (mut lo, mut hi) = (f64::MAX, f64::MIN);
            for k in (0..3).filter(|&k| !at_pole[k]) {
                lo = lo.min(ss[k]);
                hi = hi.max(ss[k]);
            }
            if hi - lo > 0.5 {
                for k in (0..3).filter(|&k| !at_pole[k] && ss[k] < 0.5) {
                    let i = t[k];
                    t[k] = match seam.iter().find(|(o, _)| *o == i) {
                        Some(&(_, c)) => c,
                        None => {
                            let tk = st[i as usize][1];
                            let c = copy(&mut s, &mut st, i, [ss[k] + 1.0, tk]);
                            let _ = seam.push((i, c));
                            c
                        }
                    };
                }
            }
            for k in (0..3).filter(|&k| at_pole[k]) {
                let (a, b) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                let mean = 0.5 * (st[a][0] + st[b][0]);
                let tk = st[t[k] as usize][1];
                t[k] = copy(&mut s, &mut st, t[k], [mean, tk]);
            }
            s.shape.indices[ti] = t;
        }
        if needed > s.shape.positions.len() || seam.is_full() {
            return Err(ShapeError::Capacity {
                vertices: Some(needed),
                triangles: Some(s.shape.indices.len()),
                vertex_capacity: V.min(1 << 16),
                triangle_capacity: T,
            });
        }
        for c in &st {
            s.push_uv(*c);
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Largest difference of `s` within a triangle: no triangle may cross the seam.
    fn widest<const V: usize, const T: usize>(s: &TexturedShape<f64, V, T>) -> f64 {
        s.shape
            .indices
            .iter()
            .map(|t| {
                let ss = t.map(|i| s.uvs[i as usize][0]);
                ss.iter().copied().fold(f64::MIN, f64::max)
                    - ss.iter().copied().fold(f64::MAX, f64::min)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn every_vertex_has_coordinates_and_no_triangle_crosses_a_seam() {
        let c = TexturedShape::<f64, 24, 12>::cube(1.0).unwrap();
        assert_eq!(c.uvs.len(), 24);
        assert!(widest(&c) <= 1.0);
        let t = TexturedShape::<f64, 400, 640>::torus(1.0, 0.4, 16, 20).unwrap();
        assert_eq!((t.uvs.len(), t.shape.indices.len()), (17 * 21, 640));
        assert!(widest(&t) <= 1.0 / 16.0 + 1e-12);
        let g = TexturedShape::<f64, 81, 128>::terrain(4.0, 8, 0.5).unwrap();
        assert_eq!(g.uvs.len(), 81);
        // The largest shapes are some 300 KB each, built by value: an unoptimized test build
        // keeps several copies on the stack, more than a test thread's 2 MB.
        std::thread::Builder::new()
            .stack_size(32 << 20)
            .spawn(|| {
                for (n, verts) in [(0u32, 12usize), (1, 42), (2, 162), (3, 642), (4, 2562)] {
                    let s = TexturedShape::<f64, 2700, 5120>::icosphere(1.0, n).unwrap();
                    let extra = s.uvs.len() - verts;
                    assert_eq!(s.uvs.len(), s.shape.positions.len());
                    if n > 0 {
                        assert!(widest(&s) < 0.5, "subdivisions {n}: {}", widest(&s));
                    }
                    assert!(extra < 100, "{extra}");
                    for uv in &s.uvs {
                        assert!((0.0..=1.5).contains(&uv[0]) && (0.0..=1.0).contains(&uv[1]));
                    }
                }
                assert!(matches!(
                    TexturedShape::<f64, 2562, 5120>::icosphere(1.0, 4),
                    Err(ShapeError::Capacity { .. })
                ));
            })
            .unwrap()
            .join()
            .unwrap();
        assert!(matches!(
            TexturedShape::<f64, 10, 10>::torus(1.0, 2.0, 3, 3),
            Err(ShapeError::BadParameter { name: "r", .. })
        ));
    }
}
