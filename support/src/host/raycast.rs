//! An f64 ray-cast reference for shadow maps: each texel's ray through the light's view,
//! intersected with the casters' triangles (Möller–Trumbore, both faces), gives the depth the
//! map should hold there. [`map_against_raycast`] compares a drawn map with it.

use scanline3d::prelude::*;

/// A world-space triangle in f64.
pub type Tri = [[f64; 3]; 3];

/// The triangles of `objects[i]` for each `i` in `indices`, in world space (each vertex through
/// the object's transform, in f64 from the number type's values).
pub fn world_triangles<S: Scalar>(objects: &[Object<'_, S>], indices: &[usize]) -> Vec<Tri> {
    let mut out = Vec::new();
    for &i in indices {
        let o = &objects[i];
        let m = o.transform.m.map(|r| r.map(|v| v.to_f64()));
        let p = o.mesh.positions();
        let world = |k: u16| {
            let q = p[k as usize].map(|v| v.to_f64());
            let h: [f64; 4] =
                std::array::from_fn(|r| m[r][0] * q[0] + m[r][1] * q[1] + m[r][2] * q[2] + m[r][3]);
            [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
        };
        for t in o.mesh.indices() {
            out.push([world(t[0]), world(t[1]), world(t[2])]);
        }
    }
    out
}

/// The parameter `t` in (0, 1] where the segment `a + t·(b − a)` first meets a triangle of
/// `tris` (either face), and that triangle's index, or `None`.
pub fn first_hit(tris: &[Tri], a: [f64; 3], b: [f64; 3]) -> Option<(f64, usize)> {
    let d = sub(b, a);
    let mut best: Option<(f64, usize)> = None;
    for (i, t) in tris.iter().enumerate() {
        let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let p = cross(d, e2);
        let det = dot(e1, p);
        if det.abs() < 1e-300 {
            continue;
        }
        let inv = 1.0 / det;
        let s = sub(a, t[0]);
        let u = dot(s, p) * inv;
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let q = cross(s, e1);
        let v = dot(d, q) * inv;
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let h = dot(e2, q) * inv;
        if h > 0.0 && h <= 1.0 && best.is_none_or(|b| h < b.0) {
            best = Some((h, i));
        }
    }
    best
}

/// A drawn map against the ray cast of its casters.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapAccuracy {
    /// Texels of the map.
    pub texels: usize,
    /// Texels the ray cast finds a caster at.
    pub covered: usize,
    /// Texels covered in one and not the other (a caster's edge through the texel centre's
    /// neighbourhood: the fill rule against the exact centre ray).
    pub coverage_mismatch: usize,
    /// Of those, texels that are not next to a texel covered in both (not an edge texel: a
    /// hole or a spill of the map).
    pub isolated_mismatch: usize,
    /// The largest depth difference (depth steps) over texels covered in both.
    pub max_depth_error: f64,
    /// Texels covered in both whose depth differs by more than the snapping of the map's
    /// vertices explains (the hit triangle's depth change over 1/32 texel in each direction: a
    /// vertex is snapped to 1/16 texel; plus 2 steps) next to a depth edge (a neighbour's ray
    /// misses, or meets a surface more than twice the hit triangle's depth change per texel
    /// plus 64 steps away): the texel centre's ray and the map's snapped edge fall on either
    /// side of a nearer surface's edge.
    pub depth_edge: usize,
    /// Such texels not next to a depth edge: an error of the map's depth itself.
    pub beyond_snapping: usize,
    /// The mean depth difference (steps) over texels covered in both.
    pub mean_depth_error: f64,
}

/// Compares `depth` (an `n × n` map, row by row, 65535 = no caster) drawn with the world →
/// map matrix `to_map` (homogeneous `(x, y, d, w)`: texel `x/w`, `y/w`, depth `d/w`) with the
/// ray cast of `tris` through each texel's centre.
pub fn map_against_raycast(
    depth: &[u16],
    n: usize,
    to_map: [[f64; 4]; 4],
    tris: &[Tri],
) -> MapAccuracy {
    let inv = invert(to_map).expect("the light's matrix is invertible");
    let world = |x: f64, y: f64, d: f64| {
        let h: [f64; 4] =
            std::array::from_fn(|r| inv[r][0] * x + inv[r][1] * y + inv[r][2] * d + inv[r][3]);
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    };
    let map_depth = |p: [f64; 3]| {
        let h: [f64; 4] = std::array::from_fn(|r| {
            to_map[r][0] * p[0] + to_map[r][1] * p[1] + to_map[r][2] * p[2] + to_map[r][3]
        });
        h[2] / h[3]
    };
    // Each triangle's depth change per texel in the map, |∂d/∂x| + |∂d/∂y|.
    let slope = |t: &Tri| {
        let p = t.map(|v| {
            let h: [f64; 4] = std::array::from_fn(|r| {
                to_map[r][0] * v[0] + to_map[r][1] * v[1] + to_map[r][2] * v[2] + to_map[r][3]
            });
            [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
        });
        let (e1, e2) = (sub(p[1], p[0]), sub(p[2], p[0]));
        let det = e1[0] * e2[1] - e2[0] * e1[1];
        if det.abs() < 1e-12 {
            return f64::INFINITY;
        }
        let gx = (e1[2] * e2[1] - e2[2] * e1[1]) / det;
        let gy = (e2[2] * e1[0] - e1[2] * e2[0]) / det;
        gx.abs() + gy.abs()
    };
    let mut reference = vec![None; n * n];
    for r in 0..n {
        for c in 0..n {
            let (x, y) = (c as f64 + 0.5, r as f64 + 0.5);
            let (a, b) = (world(x, y, 0.0), world(x, y, 65535.0));
            reference[r * n + c] = first_hit(tris, a, b)
                .map(|(t, i)| (map_depth(add(a, sub(b, a).map(|v| v * t))), slope(&tris[i])));
        }
    }
    let mut acc = MapAccuracy {
        texels: n * n,
        ..MapAccuracy::default()
    };
    let both = |k: usize| depth[k] != u16::MAX && reference[k].is_some();
    let neighbours = |k: usize| {
        let (r, c) = ((k / n) as i64, (k % n) as i64);
        (-1..=1)
            .flat_map(move |dr| (-1..=1).map(move |dc| (r + dr, c + dc)))
            .filter_map(move |(rr, cc)| {
                (rr >= 0 && cc >= 0 && rr < n as i64 && cc < n as i64 && (rr, cc) != (r, c))
                    .then_some((rr * n as i64 + cc) as usize)
            })
    };
    let (mut sum, mut count) = (0.0, 0usize);
    for k in 0..n * n {
        let drawn = depth[k] != u16::MAX;
        acc.covered += reference[k].is_some() as usize;
        if drawn != reference[k].is_some() {
            acc.coverage_mismatch += 1;
            acc.isolated_mismatch += !neighbours(k).any(both) as usize;
        } else if let Some((d, g)) = reference[k] {
            let e = (depth[k] as f64 - d).abs();
            if e > g / 32.0 + 2.0 {
                let jump =
                    |j: usize| reference[j].is_none_or(|(dj, _)| (dj - d).abs() > 2.0 * g + 64.0);
                if neighbours(k).any(jump) {
                    acc.depth_edge += 1;
                } else {
                    acc.beyond_snapping += 1;
                }
            }
            acc.max_depth_error = acc.max_depth_error.max(e);
            sum += e;
            count += 1;
        }
    }
    acc.mean_depth_error = if count > 0 { sum / count as f64 } else { 0.0 };
    acc
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The inverse of a 4 × 4 matrix (Gauss–Jordan with partial pivoting), or `None` when it is
/// singular.
pub fn invert(m: [[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let mut a = m;
    let mut inv = [[0.0; 4]; 4];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for col in 0..4 {
        let pivot = (col..4).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        for j in 0..4 {
            a[col][j] /= p;
            inv[col][j] /= p;
        }
        for r in 0..4 {
            if r != col {
                let f = a[r][col];
                for j in 0..4 {
                    a[r][j] -= f * a[col][j];
                    inv[r][j] -= f * inv[col][j];
                }
            }
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_and_misses() {
        let t = [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]];
        let (h, _) = first_hit(&t, [0.25, 0.25, 1.0], [0.25, 0.25, -1.0]).unwrap();
        assert!((h - 0.5).abs() < 1e-12);
        assert!(first_hit(&t, [0.75, 0.75, 1.0], [0.75, 0.75, -1.0]).is_none());
        assert!(first_hit(&t, [0.25, 0.25, 2.0], [0.25, 0.25, 1.0]).is_none());
        let m = [
            [2.0, 0.0, 0.0, 1.0],
            [0.0, 3.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 5.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let i = invert(m).unwrap();
        for r in 0..4 {
            for c in 0..4 {
                let v: f64 = (0..4).map(|k| m[r][k] * i[k][c]).sum();
                assert!((v - (r == c) as u8 as f64).abs() < 1e-12);
            }
        }
        assert!(invert([[0.0; 4]; 4]).is_none());
    }
}
