//! OBJ import and mesh baking for the host tools (`examples/render.rs`, `examples/bake.rs`) and
//! their tests. Parsing is tobj's; this module turns its output into one indexed triangle mesh
//! and its failures into messages that name the file and, where possible, the line.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::Path;

/// A triangle mesh in f64 model units.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjMesh {
    pub positions: Vec<[f64; 3]>,
    /// The file's `vn` normals, one per position, when every corner had one.
    pub normals: Option<Vec<[f64; 3]>>,
    pub indices: Vec<[u16; 3]>,
}

/// Loads an OBJ file: polygons triangulated, `v/vt/vn` forms and negative indices accepted,
/// all objects merged into one mesh.
pub fn load_obj(path: &Path) -> Result<ObjMesh, String> {
    let name = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    // The remaining options exist only with some tobj features: keep the update.
    #[allow(clippy::needless_update)]
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let mut reader = std::io::BufReader::new(text.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &opts, |_| {
        Err(tobj::LoadError::MaterialParseError)
    })
    .map_err(|e| match find_bad_line(&text) {
        Some((line, why)) => format!("{name}:{line}: {why} ({e})"),
        None => format!("{name}: {e}"),
    })?;
    // Indices out of range are not always reported by tobj: check them ourselves.
    if let Some((line, why)) = find_bad_line(&text) {
        return Err(format!("{name}:{line}: {why}"));
    }
    let mut mesh = ObjMesh {
        positions: Vec::new(),
        normals: Some(Vec::new()),
        indices: Vec::new(),
    };
    for m in &models {
        let base = mesh.positions.len();
        let m = &m.mesh;
        let n = m.positions.len() / 3;
        for k in 0..n {
            mesh.positions.push([
                m.positions[3 * k] as f64,
                m.positions[3 * k + 1] as f64,
                m.positions[3 * k + 2] as f64,
            ]);
        }
        match (&mut mesh.normals, m.normals.len() == m.positions.len()) {
            (Some(ns), true) => {
                for k in 0..n {
                    ns.push([
                        m.normals[3 * k] as f64,
                        m.normals[3 * k + 1] as f64,
                        m.normals[3 * k + 2] as f64,
                    ]);
                }
            }
            (normals, _) => *normals = None,
        }
        if mesh.positions.len() > 65536 {
            return Err(format!(
                "{name}: {} vertices after splitting by normals; u16 indices address at most 65536",
                mesh.positions.len()
            ));
        }
        for t in m.indices.chunks_exact(3) {
            mesh.indices
                .push([0, 1, 2].map(|k| (base + t[k] as usize) as u16));
        }
    }
    if mesh.indices.is_empty() {
        return Err(format!(
            "{name}: no triangles (no `f` lines with three or more vertices)"
        ));
    }
    Ok(mesh)
}

/// The first line of an OBJ text that tobj would reject or that refers to a vertex that does
/// not exist: (1-based line number, reason).
pub fn find_bad_line(text: &str) -> Option<(usize, String)> {
    let (mut nv, mut nt, mut nn) = (0i64, 0i64, 0i64);
    for (k, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let Some(kind) = words.next() else { continue };
        let rest: Vec<&str> = words.collect();
        let floats = |need: usize| {
            rest.len() >= need && rest.iter().take(need).all(|w| w.parse::<f64>().is_ok())
        };
        let bad = match kind {
            "v" if !floats(3) => Some("a vertex needs three numbers".to_string()),
            "vn" if !floats(3) => Some("a normal needs three numbers".to_string()),
            "vt" if !floats(1) => Some("a texture coordinate needs numbers".to_string()),
            "f" => {
                if rest.len() < 3 {
                    Some("a face needs at least three vertices".to_string())
                } else {
                    rest.iter().find_map(|corner| {
                        for (i, part) in corner.split('/').enumerate() {
                            if part.is_empty() {
                                if i == 0 {
                                    return Some(format!("face corner {corner:?} has no vertex index"));
                                }
                                continue;
                            }
                            let Ok(v) = part.parse::<i64>() else {
                                return Some(format!("face corner {corner:?} is not of the form v, v/vt, v//vn or v/vt/vn"));
                            };
                            let count = [nv, nt, nn][i.min(2)];
                            let what = ["vertex", "texture coordinate", "normal"][i.min(2)];
                            let ok = if v > 0 { v <= count } else { v < 0 && -v <= count };
                            if !ok {
                                return Some(format!("face refers to {what} {v}, but only {count} are defined so far"));
                            }
                        }
                        None
                    })
                }
            }
            _ => None,
        };
        if let Some(why) = bad {
            return Some((k + 1, why));
        }
        match kind {
            "v" => nv += 1,
            "vt" => nt += 1,
            "vn" => nn += 1,
            _ => {}
        }
    }
    None
}

/// Writes an indexed mesh as an OBJ text (with normals when given).
pub fn to_obj(
    positions: &[[f64; 3]],
    normals: Option<&[[f64; 3]]>,
    indices: &[[u16; 3]],
) -> String {
    let mut s = String::from("# written by scanline3d\n");
    for p in positions {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    if let Some(ns) = normals {
        for n in ns {
            let _ = writeln!(s, "vn {} {} {}", n[0], n[1], n[2]);
        }
    }
    for t in indices {
        let [a, b, c] = t.map(|i| i as usize + 1);
        if normals.is_some() {
            let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
        } else {
            let _ = writeln!(s, "f {a} {b} {c}");
        }
    }
    s
}

/// Bounding box and sphere (centre of the box, radius to the farthest vertex).
pub fn bounds(positions: &[[f64; 3]]) -> ([f64; 3], [f64; 3], [f64; 3], f64) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let r = positions
        .iter()
        .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt())
        .fold(0.0, f64::max);
    (lo, hi, c, r)
}

/// Unit vertex normals: the file's, or the normalized average of the unit face normals.
pub fn vertex_normals(mesh: &ObjMesh, use_file: bool) -> Vec<[f64; 3]> {
    if use_file {
        if let Some(ns) = &mesh.normals {
            return ns.iter().map(|n| scanline3d::math::normalize(*n)).collect();
        }
    }
    let mut out = vec![[0.0; 3]; mesh.positions.len()];
    // The library's own averaging, in f64.
    let _ = scanline3d::mesh::vertex_normals(&mesh.positions, &mesh.indices, &mut out);
    out
}

/// A baked mesh: positions normalized into ±1 (`model = stored · scale + offset`) and stored
/// as Q16.16 bits, unit normals as Q16.16 bits, indices.
pub struct Baked {
    pub source: String,
    pub flash_bytes: usize,
    /// Largest distance between an original vertex and its baked, de-normalized position
    /// (model units).
    pub quantization_error: f64,
    pub scale: f64,
    pub offset: [f64; 3],
}

fn q16(v: f64) -> i32 {
    (v * 65536.0)
        .round()
        .clamp(i32::MIN as f64, i32::MAX as f64) as i32
}

/// Bakes `mesh` into Rust source for `include!`.
pub fn bake(mesh: &ObjMesh, use_file_normals: bool, name: &str) -> Baked {
    let (lo, hi, c, r) = bounds(&mesh.positions);
    let scale = if r > 0.0 { r } else { 1.0 };
    let normals = vertex_normals(mesh, use_file_normals);
    let mut err = 0.0f64;
    let mut pos_src = String::new();
    for p in &mesh.positions {
        let q = [0, 1, 2].map(|k| q16((p[k] - c[k]) / scale));
        let back = [0, 1, 2].map(|k| q[k] as f64 / 65536.0 * scale + c[k]);
        err = err.max(
            ((back[0] - p[0]).powi(2) + (back[1] - p[1]).powi(2) + (back[2] - p[2]).powi(2)).sqrt(),
        );
        let _ = writeln!(pos_src, "    [q({}), q({}), q({})],", q[0], q[1], q[2]);
    }
    let mut nor_src = String::new();
    for n in &normals {
        let q = n.map(q16);
        let _ = writeln!(nor_src, "    [q({}), q({}), q({})],", q[0], q[1], q[2]);
    }
    let mut idx_src = String::new();
    for t in &mesh.indices {
        let _ = writeln!(idx_src, "    [{}, {}, {}],", t[0], t[1], t[2]);
    }
    let (nv, nt) = (mesh.positions.len(), mesh.indices.len());
    let flash_bytes = 12 * nv + 12 * nv + 6 * nt;
    let source = format!(
        "// Baked by `cargo run --release --example bake` from {name}. Do not edit.
//
// {nv} vertices, {nt} triangles, {flash_bytes} bytes of flash.
// Positions are normalized: model = stored * SCALE + OFFSET (stored within ±1, Q16.16).
// Largest position error after baking: {err:e} model units.

use scanline3d::fixed::types::I16F16;
use scanline3d::Fx;

const fn q(bits: i32) -> Fx<I16F16> {{
    Fx(I16F16::from_bits(bits))
}}

/// Multiply stored positions by this (model units) ...
pub const SCALE: f64 = {scale:?};
/// ... and add this to get model coordinates.
pub const OFFSET: [f64; 3] = {c:?};
/// Bounding box in model units (min, max).
pub const BOUNDING_BOX: ([f64; 3], [f64; 3]) = ({lo:?}, {hi:?});
/// Bounding sphere in model units (centre, radius).
pub const BOUNDING_SPHERE: ([f64; 3], f64) = ({c:?}, {r:?});

/// Normalized positions, Q16.16.
pub static POSITIONS: [[Fx<I16F16>; 3]; {nv}] = [
{pos_src}];

/// Unit vertex normals, Q16.16.
pub static NORMALS: [[Fx<I16F16>; 3]; {nv}] = [
{nor_src}];

/// Counter-clockwise triangles.
pub static INDICES: [[u16; 3]; {nt}] = [
{idx_src}];
"
    );
    Baked {
        source,
        flash_bytes,
        quantization_error: err,
        scale,
        offset: c,
    }
}
