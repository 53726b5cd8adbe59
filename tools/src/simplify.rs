//! Mesh simplification to a triangle or vertex budget (meshoptimizer) and the geometric error
//! it introduced (parry's point-to-surface distances): the `simplify` feature.

use crate::obj::{bounds, BigMesh, Simplified};

/// Simplifies `mesh` to at most `max_triangles` triangles and/or `max_vertices` vertices with
/// meshoptimizer (edge collapses that keep the topology, and where those cannot reach the
/// budget its vertex-clustering simplifier), drops the vertices no triangle uses, and orders
/// triangles and vertices with meshoptimizer's vertex-cache and vertex-fetch orders (the
/// triangles that share vertices come together and vertices are stored in order of first use:
/// reads of the vertex store and of the mesh in flash stay local). Normals, when the mesh has
/// the file's, follow their vertices; face-averaged ones are to be recomputed on the result.
/// Texture coordinates follow their vertices too: the topology-keeping simplifier only removes
/// vertices and keeps the seams (vertices that share a position, as the split ones at a
/// texture seam do) as seams. Its vertex-clustering fallback would join vertices across a
/// seam, so a mesh with texture coordinates that needs it is refused.
///
/// Chosen over a hand-written simplifier: meshoptimizer is maintained, widely used (glTF
/// tools, game engines) and reports its own error; the `meshopt` crate builds it from source.
pub fn simplify(
    mesh: &BigMesh,
    max_triangles: Option<usize>,
    max_vertices: Option<usize>,
) -> Result<Simplified, String> {
    let n_tris = mesh.indices.len();
    let n_verts = mesh.positions.len();
    if max_triangles == Some(0) || max_vertices.is_some_and(|v| v < 3) {
        return Err("the budget must allow at least one triangle (3 vertices)".into());
    }
    let flat: Vec<u32> = mesh.indices.iter().flatten().copied().collect();
    let pos32: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.map(|c| c as f32)).collect();
    let adapter = meshopt::VertexDataAdapter::new(meshopt::typed_to_bytes(&pos32), 12, 0)
        .map_err(|e| format!("meshoptimizer: {e}"))?;
    let scale = meshopt::simplify_scale(&adapter) as f64;
    let used = |idx: &[u32]| {
        let mut seen = vec![false; n_verts];
        idx.iter()
            .filter(|&&i| !std::mem::replace(&mut seen[i as usize], true))
            .count()
    };
    let tri_cap = max_triangles.unwrap_or(n_tris).min(n_tris);
    let mut target = match max_vertices {
        // A closed mesh has about two triangles per vertex.
        Some(v) => tri_cap.min(2 * v),
        None => tri_cap,
    };
    let mut result = None;
    for _ in 0..24 {
        let mut err = 0.0f32;
        let mut idx = meshopt::simplify(
            &flat,
            &adapter,
            3 * target,
            1.0,
            meshopt::SimplifyOptions::None,
            Some(&mut err),
        );
        let mut sloppy = false;
        if idx.len() / 3 > target {
            if mesh.uvs.is_some() {
                return Err(format!(
                    "meshoptimizer's topology-keeping simplifier stops at {} triangles, above the \
                     {target} asked for, and its vertex-clustering one would join texture \
                     coordinates across seams: allow more triangles or vertices, or remove the \
                     vt from the file",
                    idx.len() / 3
                ));
            }
            err = 0.0;
            idx = meshopt::simplify_sloppy(&flat, &adapter, 3 * target, 1.0, Some(&mut err));
            sloppy = true;
        }
        let verts = used(&idx);
        let fits = idx.len() / 3 <= tri_cap && max_vertices.is_none_or(|m| verts <= m);
        if fits && !idx.is_empty() {
            result = Some((idx, err as f64, sloppy));
            break;
        }
        if idx.is_empty() || target <= 1 {
            break;
        }
        // Too many vertices: aim lower in proportion.
        let ratio = max_vertices.map_or(0.9, |m| (m as f64 / verts as f64).min(0.95));
        target = ((target as f64 * ratio) as usize).max(1);
    }
    let Some((mut idx, rel, sloppy)) = result else {
        return Err(format!(
            "meshoptimizer could not bring {n_tris} triangles under {} triangles{}",
            tri_cap,
            max_vertices.map_or(String::new(), |v| format!(" and {v} vertices"))
        ));
    };
    meshopt::optimize_vertex_cache_in_place(&mut idx, n_verts);
    let order: Vec<u32> = (0..n_verts as u32).collect();
    // New vertex k is old vertex order[k]; `idx` is rewritten to the new numbering.
    let order = meshopt::optimize_vertex_fetch(&mut idx, &order);
    let out = BigMesh {
        positions: order.iter().map(|&i| mesh.positions[i as usize]).collect(),
        normals: mesh
            .normals
            .as_ref()
            .map(|ns| order.iter().map(|&i| ns[i as usize]).collect()),
        uvs: mesh
            .uvs
            .as_ref()
            .map(|us| order.iter().map(|&i| us[i as usize]).collect()),
        indices: idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    };
    let (lo, hi, _, _) = bounds(&mesh.positions);
    let diagonal =
        ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
    let samples = 20_000;
    let hausdorff = hausdorff(mesh, &out, samples)?;
    Ok(Simplified {
        mesh: out,
        meshopt_relative: rel,
        meshopt_absolute: rel * scale,
        sloppy,
        hausdorff,
        samples,
        diagonal,
    })
}

/// A symmetric Hausdorff estimate between the surfaces of `a` and `b`: the largest distance
/// from a point of one to the other surface, over every vertex of each and `samples`
/// area-weighted pseudo-random points on each (fixed seed: the same figure every run).
/// Distances by parry's triangle-mesh point queries (a bounding-volume hierarchy).
pub fn hausdorff(a: &BigMesh, b: &BigMesh, samples: usize) -> Result<f64, String> {
    Ok(one_sided(a, b, samples)?.max(one_sided(b, a, samples)?))
}

fn trimesh(m: &BigMesh) -> Result<parry3d_f64::shape::TriMesh, String> {
    let v = m
        .positions
        .iter()
        .map(|p| parry3d_f64::math::Vector::new(p[0], p[1], p[2]))
        .collect();
    parry3d_f64::shape::TriMesh::new(v, m.indices.clone()).map_err(|e| format!("parry: {e:?}"))
}

/// Largest distance from points of `from` (its vertices and `samples` points on its triangles)
/// to the surface of `to`.
fn one_sided(from: &BigMesh, to: &BigMesh, samples: usize) -> Result<f64, String> {
    use parry3d_f64::query::PointQuery;
    let target = trimesh(to)?;
    let dist = |p: [f64; 3]| {
        target.distance_to_local_point(parry3d_f64::math::Vector::new(p[0], p[1], p[2]), false)
    };
    let mut worst = 0.0f64;
    for &p in &from.positions {
        worst = worst.max(dist(p));
    }
    // Area-weighted triangle choice by a cumulative table, barycentric points by a fixed LCG.
    let mut cum = Vec::with_capacity(from.indices.len());
    let mut total = 0.0;
    for t in &from.indices {
        let [a, b, c] = t.map(|i| from.positions[i as usize]);
        let n = scanline3d::math::cross(scanline3d::math::sub(b, a), scanline3d::math::sub(c, a));
        total += scanline3d::math::length(n);
        cum.push(total);
    }
    if total <= 0.0 {
        return Ok(worst);
    }
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..samples {
        let r = next() * total;
        let k = cum.partition_point(|&c| c < r).min(cum.len() - 1);
        let [a, b, c] = from.indices[k].map(|i| from.positions[i as usize]);
        let (mut u, mut v) = (next(), next());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        let p = [0, 1, 2].map(|j| a[j] + u * (b[j] - a[j]) + v * (c[j] - a[j]));
        worst = worst.max(dist(p));
    }
    Ok(worst)
}
