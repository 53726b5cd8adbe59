//! OBJ import and mesh baking for the host tools (`tools/src/bin/render/main.rs`, `tools/src/bin/bake.rs`) and
//! their tests. Parsing is tobj's; this module turns its output into one indexed triangle mesh
//! and its failures into messages that name the file and, where possible, the line.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::Path;

/// A triangle mesh in f64 model units, with the renderer's u16 indices.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjMesh {
    pub positions: Vec<[f64; 3]>,
    /// The file's `vn` normals, one per vertex, when the mesh was built with
    /// [`NormalSource::File`]; `None` when normals are to be averaged ([`vertex_normals`]).
    pub normals: Option<Vec<[f64; 3]>>,
    pub indices: Vec<[u16; 3]>,
}

/// The same with u32 indices: any size an OBJ file can have, before simplification; and
/// texture coordinates when asked for ([`ObjFile::mesh_with`]).
#[derive(Clone, Debug, PartialEq)]
pub struct BigMesh {
    pub positions: Vec<[f64; 3]>,
    pub normals: Option<Vec<[f64; 3]>>,
    /// Texture coordinates `(s, t)` in the renderer's convention (`t` down: `t = 1 − v` of the
    /// file's `vt`), one per vertex; `None` unless asked for.
    pub uvs: Option<Vec<[f64; 2]>>,
    pub indices: Vec<[u32; 3]>,
}

/// Where vertex normals come from.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum NormalSource {
    /// The file's `vn`: a vertex is split where the `vn` of its corners differ (hard edges).
    File,
    /// The normalized sum of the unit normals of the faces sharing a position: one vertex per
    /// position.
    FaceAverage,
}

/// One corner of a triangle as the file gives it: indices into [`ObjFile::positions`],
/// [`ObjFile::normals`] and [`ObjFile::uvs`]. An attribute is a part of
/// [`ObjFile::split_key`] when it is used.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Corner {
    pub position: u32,
    pub normal: Option<u32>,
    pub uv: Option<u32>,
}

/// Which face corners of an OBJ file have a texture coordinate (`v/vt` or `v/vt/vn`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Texcoords {
    /// None has.
    None,
    /// Every corner has.
    All,
    /// Some have, some not: how many of each, and the first line of a face with a corner of
    /// each kind.
    Some {
        with: usize,
        without: usize,
        line_with: usize,
        line_without: usize,
    },
}

/// An OBJ file's triangles with their corners' attributes, positions welded: equal
/// coordinates are one position, whatever `v` lines, `vt` or objects they came from.
#[derive(Clone, Debug)]
pub struct ObjFile {
    /// The path, for messages.
    pub name: String,
    /// Distinct positions, in order of first use by a face.
    pub positions: Vec<[f64; 3]>,
    /// Distinct `vn` values (as given, not normalized), in order of first use.
    pub normals: Vec<[f64; 3]>,
    /// Distinct `vt` values `(u, v)` as given (`v` up), in order of first use; read only when
    /// every face corner has one.
    pub uvs: Vec<[f64; 2]>,
    pub triangles: Vec<[Corner; 3]>,
    /// Whether every face corner has a `vn`.
    pub all_corners_have_normals: bool,
    /// Which face corners have a `vt`.
    pub texcoords: Texcoords,
}

impl ObjFile {
    /// The file's normals when every corner has one, else face-averaged.
    pub fn default_normals(&self) -> NormalSource {
        if self.all_corners_have_normals {
            NormalSource::File
        } else {
            NormalSource::FaceAverage
        }
    }

    /// Whether the mesh is to have texture coordinates: every face corner has a `vt` (true),
    /// none has (false), or an error when only some have.
    pub fn uvs_present(&self) -> Result<bool, String> {
        match self.texcoords {
            Texcoords::None => Ok(false),
            Texcoords::All => Ok(true),
            Texcoords::Some {
                with,
                without,
                line_with,
                line_without,
            } => Err(format!(
                "{}: texture coordinates on only some faces: {with} face corners have a vt \
                 (first on line {line_with}), {without} have none (first on line \
                 {line_without}); give every face corner a vt, or none",
                self.name
            )),
        }
    }

    /// What must be equal for two corners to be one vertex: the position, the normal when the
    /// file's normals are used, and the texture coordinate when texture coordinates are used
    /// (a seam: faces that meet at a position with different `vt`).
    fn split_key(c: &Corner, normals: NormalSource, uvs: bool) -> (u32, Option<u32>, Option<u32>) {
        let normal = match normals {
            NormalSource::File => c.normal,
            NormalSource::FaceAverage => None,
        };
        (c.position, normal, if uvs { c.uv } else { None })
    }

    /// The indexed mesh without texture coordinates ([`Self::mesh_with`]).
    pub fn mesh(&self, normals: NormalSource) -> Result<BigMesh, String> {
        self.mesh_with(normals, false)
    }

    /// The indexed mesh: one vertex per distinct [`Self::split_key`], in order of first use;
    /// with `uvs`, texture coordinates `(s, t) = (u, 1 − v)` (an error unless every corner has
    /// a `vt` and every one is within ±[`scanline3d::limits::UV_LIMIT`] once stored in Q16.16).
    pub fn mesh_with(&self, normals: NormalSource, uvs: bool) -> Result<BigMesh, String> {
        use std::collections::HashMap;
        if normals == NormalSource::File && !self.all_corners_have_normals {
            return Err(format!(
                "{}: the file's normals were asked for, but not every face corner has a vn",
                self.name
            ));
        }
        let st = if uvs {
            if !self.uvs_present()? {
                return Err(format!(
                    "{}: texture coordinates were asked for, but no face has a vt",
                    self.name
                ));
            }
            self.uvs
                .iter()
                .map(|&uv| self.texture_coordinate(uv))
                .collect::<Result<Vec<_>, _>>()?
        } else {
            Vec::new()
        };
        let mut ids: HashMap<(u32, Option<u32>, Option<u32>), u32> = HashMap::new();
        let mut out = BigMesh {
            positions: Vec::new(),
            normals: (normals == NormalSource::File).then(Vec::new),
            uvs: uvs.then(Vec::new),
            indices: Vec::with_capacity(self.triangles.len()),
        };
        for t in &self.triangles {
            out.indices.push(t.map(|c| {
                let key = Self::split_key(&c, normals, uvs);
                *ids.entry(key).or_insert_with(|| {
                    out.positions.push(self.positions[c.position as usize]);
                    if let (Some(ns), Some(n)) = (&mut out.normals, key.1) {
                        ns.push(self.normals[n as usize]);
                    }
                    if let (Some(us), Some(u)) = (&mut out.uvs, key.2) {
                        us.push(st[u as usize]);
                    }
                    (out.positions.len() - 1) as u32
                })
            }));
        }
        Ok(out)
    }

    /// The renderer's `(s, t)` of a `vt` `(u, v)`: `(u, 1 − v)` (OBJ's `v` goes up, the
    /// renderer's `t` down from the top row), or an error naming the `vt` when a coordinate,
    /// rounded to Q16.16 as baked, is not strictly within ±[`scanline3d::limits::UV_LIMIT`].
    fn texture_coordinate(&self, [u, v]: [f64; 2]) -> Result<[f64; 2], String> {
        let st = [u, 1.0 - v];
        let limit = (scanline3d::limits::UV_LIMIT * 65536.0) as i64;
        if st
            .iter()
            .all(|&c| c.is_finite() && (q16(c) as i64).abs() < limit)
        {
            Ok(st)
        } else {
            Err(format!(
                "{}: texture coordinate `vt {u} {v}` gives (s, t) = ({}, {}) (t = 1 − v): \
                 the renderer takes coordinates strictly within ±{} (scanline3d::limits::UV_LIMIT)",
                self.name,
                st[0],
                st[1],
                scanline3d::limits::UV_LIMIT
            ))
        }
    }
}

/// Largest number of vertices u16 indices address.
pub const U16_VERTICES: usize = 65536;

impl BigMesh {
    /// The mesh with u16 indices, or a message that says what to do when it has too many
    /// vertices.
    pub fn to_u16(&self, name: &str) -> Result<ObjMesh, String> {
        let n = self.positions.len();
        if n > U16_VERTICES {
            let target = suggest_triangles(self.indices.len(), n, 32768);
            return Err(format!(
                "{name}: {n} vertices, more than the 65536 that u16 indices address: simplify it, \
                 e.g. `--max-triangles {target}` (render) or \
                 `cargo run --release -p scanline3d-tools --features simplify --bin bake -- {name} --max-triangles {target} --obj-out smaller.obj`"
            ));
        }
        // Texture coordinates, if any, stay in `self.uvs`: an `ObjMesh` has none.
        Ok(ObjMesh {
            positions: self.positions.clone(),
            normals: self.normals.clone(),
            indices: self.indices.iter().map(|t| t.map(|i| i as u16)).collect(),
        })
    }
}

/// A triangle budget that should bring a mesh of `tris` triangles and `verts` vertices under
/// `cap` vertices (90 % of the proportional share, rounded down to a thousand when that large).
pub fn suggest_triangles(tris: usize, verts: usize, cap: usize) -> usize {
    let t = (tris as f64 * 0.9 * cap as f64 / verts.max(1) as f64) as usize;
    if t >= 2000 {
        t / 1000 * 1000
    } else {
        t.max(1)
    }
}

/// Reads and parses an OBJ file (tobj parses; polygons triangulated, `v/vt/vn` forms and
/// negative indices accepted, all objects merged, equal positions welded; equal `vn` and,
/// when every corner has one, equal `vt` values too).
pub fn parse_obj(path: &Path) -> Result<ObjFile, String> {
    use std::collections::HashMap;
    let name = path.display();
    if path.is_dir() {
        return Err(format!("{name}: is a directory, not an OBJ file"));
    }
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    // Lines tobj would reject and indices out of range, with their line numbers.
    let scan = scan(&text);
    if let Some((line, why)) = scan.bad {
        return Err(format!("{name}:{line}: {why}"));
    }
    if scan.faces == 0 {
        return Err(format!(
            "{name}: no triangles (no `f` lines with three or more vertices; {} `v` lines)",
            scan.vertices
        ));
    }
    // The remaining options exist only with some tobj features: keep the update.
    // `single_index: false`: corners keep their own position, normal and texture-coordinate
    // indices; vertices are made here, split only where the attributes used differ
    // ([`ObjFile::mesh_with`]).
    #[allow(clippy::needless_update)]
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let mut reader = std::io::BufReader::new(text.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &opts, |_| {
        Err(tobj::LoadError::MaterialParseError)
    })
    .map_err(|e| format!("{name}: {e}"))?;
    let texcoords = match (
        scan.first_face_with_texcoord,
        scan.first_face_without_texcoord,
    ) {
        (None, _) => Texcoords::None,
        (Some(_), None) => Texcoords::All,
        (Some(line_with), Some(line_without)) => Texcoords::Some {
            with: scan.corners_with_texcoord,
            without: scan.corners_without_texcoord,
            line_with,
            line_without,
        },
    };
    let mut file = ObjFile {
        name: name.to_string(),
        positions: Vec::new(),
        normals: Vec::new(),
        uvs: Vec::new(),
        triangles: Vec::new(),
        all_corners_have_normals: scan.corners_without_normal == 0,
        texcoords,
    };
    // -0.0 and 0.0 are one coordinate.
    let key = |v: [f64; 3]| v.map(|c| (c + 0.0).to_bits());
    let mut pos_ids: HashMap<[u64; 3], u32> = HashMap::new();
    let mut nor_ids: HashMap<[u64; 3], u32> = HashMap::new();
    let mut uv_ids: HashMap<[u64; 2], u32> = HashMap::new();
    for m in &models {
        let m = &m.mesh;
        let read3 = |v: &[f32], i: u32| -> Option<[f64; 3]> {
            let i = 3 * i as usize;
            Some([
                *v.get(i)? as f64,
                *v.get(i + 1)? as f64,
                *v.get(i + 2)? as f64,
            ])
        };
        let use_normals =
            file.all_corners_have_normals && m.normal_indices.len() == m.indices.len();
        let use_uvs = file.texcoords == Texcoords::All;
        if use_uvs && m.texcoord_indices.len() != m.indices.len() {
            return Err(format!(
                "{name}: tobj gave {} texture-coordinate indices for {} face corners",
                m.texcoord_indices.len(),
                m.indices.len()
            ));
        }
        for (k, t) in m.indices.chunks_exact(3).enumerate() {
            let mut tri = [Corner {
                position: 0,
                normal: None,
                uv: None,
            }; 3];
            for j in 0..3 {
                let p = read3(&m.positions, t[j])
                    .ok_or_else(|| format!("{name}: a face refers to a missing vertex"))?;
                let n = pos_ids.len() as u32;
                tri[j].position = *pos_ids.entry(key(p)).or_insert_with(|| {
                    file.positions.push(p);
                    n
                });
                if use_normals {
                    let v = read3(&m.normals, m.normal_indices[3 * k + j])
                        .ok_or_else(|| format!("{name}: a face refers to a missing normal"))?;
                    let n = nor_ids.len() as u32;
                    tri[j].normal = Some(*nor_ids.entry(key(v)).or_insert_with(|| {
                        file.normals.push(v);
                        n
                    }));
                }
                if use_uvs {
                    let i = 2 * m.texcoord_indices[3 * k + j] as usize;
                    let uv = m
                        .texcoords
                        .get(i..i + 2)
                        .map(|c| [c[0] as f64, c[1] as f64])
                        .ok_or_else(|| {
                            format!("{name}: a face refers to a missing texture coordinate")
                        })?;
                    let n = uv_ids.len() as u32;
                    let bits = uv.map(|c| (c + 0.0).to_bits());
                    tri[j].uv = Some(*uv_ids.entry(bits).or_insert_with(|| {
                        file.uvs.push(uv);
                        n
                    }));
                }
            }
            file.triangles.push(tri);
        }
        if !use_normals {
            file.all_corners_have_normals = false;
        }
    }
    if file.triangles.is_empty() {
        return Err(format!("{name}: no triangles"));
    }
    Ok(file)
}

/// Loads an OBJ file as one mesh with u16 indices, normals from the file when every corner has
/// a `vn` ([`ObjFile::default_normals`]).
pub fn load_obj(path: &Path) -> Result<ObjMesh, String> {
    let file = parse_obj(path)?;
    file.mesh(file.default_normals())?.to_u16(&file.name)
}

/// What [`scan`] finds in an OBJ text.
#[derive(Debug, Default)]
pub struct Scan {
    /// The first line tobj would reject or that refers to something not defined:
    /// (1-based line number, reason).
    pub bad: Option<(usize, String)>,
    pub vertices: usize,
    pub faces: usize,
    /// Face corners without a `vn` index.
    pub corners_without_normal: usize,
    /// Face corners with and without a `vt` index, and the first line of a face with a corner
    /// of each kind.
    pub corners_with_texcoord: usize,
    pub corners_without_texcoord: usize,
    pub first_face_with_texcoord: Option<usize>,
    pub first_face_without_texcoord: Option<usize>,
}

/// The first line of an OBJ text that tobj would reject or that refers to a vertex that does
/// not exist: (1-based line number, reason).
pub fn find_bad_line(text: &str) -> Option<(usize, String)> {
    scan(text).bad
}

/// Checks every line of an OBJ text and counts what the faces have.
pub fn scan(text: &str) -> Scan {
    let mut out = Scan::default();
    let (mut nv, mut nt, mut nn) = (0i64, 0i64, 0i64);
    for (k, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let Some(kind) = words.next() else { continue };
        let rest: Vec<&str> = words.collect();
        // tobj reads coordinates as f32: a value beyond its range (±3.4e38) is infinite there.
        let finite = |w: &&str| w.parse::<f32>().is_ok_and(f32::is_finite);
        let floats = |need: usize| rest.len() >= need && rest.iter().take(need).all(finite);
        // Words after x y z (w, or a vertex colour) that are numbers must be finite too: tobj
        // reads them, and a NaN there made the triangle invalid without a word.
        let extras_finite = || {
            rest.iter()
                .skip(3)
                .all(|w| w.parse::<f64>().is_err() || finite(w))
        };
        let bad = match kind {
            "v" if !floats(3) || !extras_finite() => Some(
                "a vertex needs three numbers, all finite (and within ±3.4e38, the f32 range \
                 the OBJ is read in); so must any w or colour after them"
                    .to_string(),
            ),
            "vn" if !floats(3) => {
                Some("a normal needs three numbers, all finite (and within ±3.4e38)".to_string())
            }
            // tobj needs u and v; their range matters only where they are used
            // (`ObjFile::mesh_with`).
            "vt" if rest.len() < 2 || !rest.iter().take(2).all(|w| w.parse::<f32>().is_ok()) => {
                Some("a texture coordinate needs two numbers (u v)".to_string())
            }
            "f" => {
                if rest.len() < 3 {
                    Some("a face needs at least three vertices".to_string())
                } else {
                    rest.iter().find_map(|corner| {
                        if corner.split('/').nth(2).is_none_or(str::is_empty) {
                            out.corners_without_normal += 1;
                        }
                        if corner.split('/').nth(1).is_none_or(str::is_empty) {
                            out.corners_without_texcoord += 1;
                            out.first_face_without_texcoord.get_or_insert(k + 1);
                        } else {
                            out.corners_with_texcoord += 1;
                            out.first_face_with_texcoord.get_or_insert(k + 1);
                        }
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
                            if v == 0 {
                                return Some(format!("face corner {corner:?} refers to {what} 0, but OBJ indices start at 1"));
                            }
                            let ok = if v > 0 { v <= count } else { -v <= count };
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
            out.bad = Some((k + 1, why));
            return out;
        }
        match kind {
            "v" => nv += 1,
            "vt" => nt += 1,
            "vn" => nn += 1,
            "f" => out.faces += 1,
            _ => {}
        }
    }
    out.vertices = nv as usize;
    out
}

/// Writes an indexed mesh as an OBJ text (with normals when given).
pub fn to_obj<I: Copy + Into<u64>>(
    positions: &[[f64; 3]],
    normals: Option<&[[f64; 3]]>,
    indices: &[[I; 3]],
) -> String {
    to_obj_with_uvs(positions, normals, None, indices)
}

/// The same with texture coordinates `(s, t)` when given, written as `vt s 1−t` (OBJ's `v` up).
pub fn to_obj_with_uvs<I: Copy + Into<u64>>(
    positions: &[[f64; 3]],
    normals: Option<&[[f64; 3]]>,
    uvs: Option<&[[f64; 2]]>,
    indices: &[[I; 3]],
) -> String {
    let mut s = String::from("# written by scanline3d\n");
    for p in positions {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    for uv in uvs.into_iter().flatten() {
        let _ = writeln!(s, "vt {} {}", uv[0], 1.0 - uv[1]);
    }
    if let Some(ns) = normals {
        for n in ns {
            let _ = writeln!(s, "vn {} {} {}", n[0], n[1], n[2]);
        }
    }
    for t in indices {
        let [a, b, c] = t.map(|i| i.into() + 1);
        let _ = match (uvs.is_some(), normals.is_some()) {
            (false, false) => writeln!(s, "f {a} {b} {c}"),
            (false, true) => writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}"),
            (true, false) => writeln!(s, "f {a}/{a} {b}/{b} {c}/{c}"),
            (true, true) => writeln!(s, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}"),
        };
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

/// Face-averaged unit normals per position: vertices at the same position (split at a texture
/// seam) get the same normal, the average over all the faces around the position.
pub fn normals_per_position(mesh: &ObjMesh) -> Vec<[f64; 3]> {
    use std::collections::HashMap;
    let mut first: HashMap<[u64; 3], u16> = HashMap::new();
    let mut welded = ObjMesh {
        positions: Vec::new(),
        normals: None,
        indices: Vec::new(),
    };
    // Vertex i is welded vertex weld[i].
    let weld: Vec<u16> = mesh
        .positions
        .iter()
        .map(|p| {
            *first
                .entry(p.map(|c| (c + 0.0).to_bits()))
                .or_insert_with(|| {
                    welded.positions.push(*p);
                    (welded.positions.len() - 1) as u16
                })
        })
        .collect();
    welded.indices = mesh
        .indices
        .iter()
        .map(|t| t.map(|i| weld[i as usize]))
        .collect();
    let normals = vertex_normals(&welded, false);
    weld.iter().map(|&w| normals[w as usize]).collect()
}

/// Bakes `mesh` into Rust source for `include!`.
pub fn bake(mesh: &ObjMesh, use_file_normals: bool, name: &str) -> Baked {
    bake_with_uvs(mesh, None, use_file_normals, name)
}

/// The same with texture coordinates `(s, t)`, one per vertex, when given: a `UVS` array
/// (Q16.16), and face-averaged normals averaged per position ([`normals_per_position`]) so that
/// a texture seam is not a shading seam. Without them, the source is [`bake`]'s.
pub fn bake_with_uvs(
    mesh: &ObjMesh,
    uvs: Option<&[[f64; 2]]>,
    use_file_normals: bool,
    name: &str,
) -> Baked {
    let (lo, hi, c, r) = bounds(&mesh.positions);
    let scale = if r > 0.0 { r } else { 1.0 };
    let normals = if uvs.is_some() && !use_file_normals {
        normals_per_position(mesh)
    } else {
        vertex_normals(mesh, use_file_normals)
    };
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
    let mut flash_bytes = 12 * nv + 12 * nv + 6 * nt;
    // The texture-coordinate parts of the source: a header line and the array.
    let (mut uv_note, mut uv_src) = (String::new(), String::new());
    if let Some(uvs) = uvs {
        assert_eq!(uvs.len(), nv, "one texture coordinate per vertex");
        flash_bytes += 8 * nv;
        let _ = writeln!(
            uv_note,
            "// Texture coordinates (s, t) = (u, 1 - v) of the OBJ's vt (t down), Q16.16."
        );
        let _ = writeln!(
            uv_src,
            "\n/// Texture coordinates (s, t), Q16.16: (0, 0) is the top-left corner of the \
             image.\npub static UVS: [[Fx<I16F16>; 2]; {nv}] = ["
        );
        for uv in uvs {
            let _ = writeln!(uv_src, "    [q({}), q({})],", q16(uv[0]), q16(uv[1]));
        }
        uv_src.push_str("];\n");
    }
    let source = format!(
        "// Baked by `cargo run --release -p scanline3d-tools --bin bake` from {name}. Do not edit.
//
// {nv} vertices, {nt} triangles, {flash_bytes} bytes of flash.
// Positions are normalized: model = stored * SCALE + OFFSET (stored within ±1, Q16.16).
// Largest position error after baking: {err:e} model units.
{uv_note}
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
{uv_src}"
    );
    Baked {
        source,
        flash_bytes,
        quantization_error: err,
        scale,
        offset: c,
    }
}

/// A simplified mesh and the geometric error the simplification introduced.
pub struct Simplified {
    pub mesh: BigMesh,
    /// meshoptimizer's own error estimate, relative to the mesh extents, and in model units.
    pub meshopt_relative: f64,
    pub meshopt_absolute: f64,
    /// Whether meshoptimizer's topology-keeping simplifier could not reach the budget and its
    /// "sloppy" one (vertex clustering) was used.
    pub sloppy: bool,
    /// The largest distance, in model units, from points sampled on either surface to the
    /// other surface (a symmetric Hausdorff estimate), and the number of points each way.
    pub hausdorff: f64,
    pub samples: usize,
    /// The bounding-box diagonal of the original, model units.
    pub diagonal: f64,
}

impl Simplified {
    /// One line for the tools' output.
    pub fn summary(&self, before: &BigMesh) -> String {
        format!(
            "simplified {} -> {} triangles, {} -> {} vertices{}: error {:.3e} model units = {:.3} % of the bounding-box diagonal ({:.4e}) \
             (largest distance between the two surfaces, {} points sampled on each); meshoptimizer's estimate {:.3e} ({:.3} % of its extent)",
            before.indices.len(),
            self.mesh.indices.len(),
            before.positions.len(),
            self.mesh.positions.len(),
            if self.sloppy { " (meshoptimizer's sloppy simplifier: the topology-keeping one could not reach the budget)" } else { "" },
            self.hausdorff,
            100.0 * self.hausdorff / self.diagonal.max(1e-300),
            self.diagonal,
            self.samples,
            self.meshopt_absolute,
            100.0 * self.meshopt_relative,
        )
    }
}

/// Simplification is the `simplify` feature's (meshoptimizer and parry: 30 more crates and a
/// C++ build that the default tools build leaves out); without it `--max-triangles` and
/// `--max-vertices` are refused with this message.
#[cfg(not(feature = "simplify"))]
pub fn simplify(
    _mesh: &BigMesh,
    _max_triangles: Option<usize>,
    _max_vertices: Option<usize>,
) -> Result<Simplified, String> {
    Err("this build of the tools has no mesh simplifier: add `-p scanline3d-tools --features simplify` \
         to the cargo command (`--max-triangles`/`--max-vertices` need meshoptimizer)"
        .into())
}

#[cfg(feature = "simplify")]
pub use crate::simplify::{hausdorff, simplify};
