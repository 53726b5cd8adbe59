//! CSG trees on the host: a small line-based text format, primitives meshed as closed,
//! counter-clockwise-outward triangle meshes, and the tree evaluated with mesh booleans.
//!
//! The booleans come from `boolmesh` (a pure-Rust rewrite of Manifold's algorithm, depending only
//! on glam): its output is closed and consistently wound, and flat faces and sharp edges stay
//! exact, which an implicit-surface mesher would round off. Its ear-clipped fans leave thin
//! triangles on flat faces, so the result goes through an edge-flip pass (`improve`) that only
//! flips edges between coplanar triangles and only when the smaller angle grows.
//!
//! # The format
//!
//! One definition a line; `#` starts a comment; blank lines are ignored.
//!
//! ```text
//! segments 24                        # tessellation of round primitives (3..=256), optional
//! block = box 2 1.2 1                # sizes along x, y, z, centred on the origin
//! ball  = sphere 0.7                 # radius, centred on the origin
//! drill = cylinder 0.25 3 translate 0 0 -1.5   # x²+y² ≤ r², 0 ≤ z ≤ h
//! tip   = cone 0.5 1                 # base radius r at z = 0, apex at z = h
//! part  = difference block ball drill          # first minus every other
//! ```
//!
//! Primitives: `box SX SY SZ`, `sphere R`, `cylinder R H`, `cone R H`. Combinations:
//! `union A B ...`, `intersection A B ...`, `difference A B ...` (two or more names defined on
//! earlier lines). Any definition may end with transforms, applied left to right:
//! `translate X Y Z`, `rotate x|y|z DEGREES`, `scale S` or `scale SX SY SZ` (non-zero factors).
//! The last definition is the result.
//!
//! Half-spaces (tools/src/csg_half.rs says how they are meshed):
//!
//! ```text
//! cut  = plane A B C D                   # A x + B y + C z + D ≤ 0
//! bowl = quadric A B C D E F G H I J     # A x² + B y² + C z² + D xy + E yz + F xz
//!                                        #   + G x + H y + I z + J ≤ 0
//! part = intersection block cut bowl     # each half-space meets a bounded operand
//! ```
//!
//! A half-space is unbounded, so it may only be an operand of an `intersection` that has at
//! least one bounded operand, or a second or later operand of a `difference` (whose first operand
//! is bounded); in a `union`, as the first operand of a `difference`, or as the result it is
//! refused with its line. It is meshed over the bounding box of what it meets, so it can take
//! transforms like any primitive.

use boolmesh::prelude::{compute_boolean, Manifold, OpType};
use std::collections::HashMap;

#[path = "csg_half.rs"]
mod half;
pub use half::HalfSpace;

/// A definition: a closed mesh, or a half-space kept as its equation until it meets a bounded
/// operand.
#[derive(Clone, Debug)]
enum Node {
    Solid(CsgMesh),
    Half(HalfSpace),
}

/// A closed triangle mesh: f64 positions (the model's units), counter-clockwise outward.
#[derive(Clone, Debug)]
pub struct CsgMesh {
    pub positions: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// A parse or meshing error; `line` is 1-based (0 when the problem is not on one line).
#[derive(Clone, Debug, PartialEq)]
pub struct CsgError {
    pub line: usize,
    pub message: String,
}

impl std::fmt::Display for CsgError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            write!(f, "csg: {}", self.message)
        } else {
            write!(f, "csg line {}: {}", self.line, self.message)
        }
    }
}

fn err<T>(line: usize, message: impl Into<String>) -> Result<T, CsgError> {
    Err(CsgError {
        line,
        message: message.into(),
    })
}

/// Parses a CSG text and meshes its last definition.
pub fn mesh_csg_text(text: &str) -> Result<CsgMesh, CsgError> {
    let mut segments = 24usize;
    let mut defs: HashMap<String, Node> = HashMap::new();
    let mut last: Option<(usize, String)> = None;
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        if words[0] == "segments" {
            if words.len() != 2 {
                return err(n, "`segments` takes one whole number");
            }
            segments = match words[1].parse::<usize>() {
                Ok(s) if (3..=256).contains(&s) => s,
                _ => return err(n, format!("segments `{}` is not in 3..=256", words[1])),
            };
            continue;
        }
        if words.len() < 3 || words[1] != "=" {
            return err(n, "expected `NAME = OPERATION ARGUMENTS...`");
        }
        let name = words[0];
        if !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return err(n, format!("`{name}` is not a name (letters, digits and _)"));
        }
        if defs.contains_key(name) {
            return err(n, format!("`{name}` is already defined"));
        }
        let rest = &words[2..];
        // The operation's own arguments run up to the first transform keyword.
        let split = rest[1..]
            .iter()
            .position(|w| matches!(*w, "translate" | "rotate" | "scale"))
            .map_or(rest.len(), |p| p + 1);
        let (op, args, transforms) = (rest[0], &rest[1..split], &rest[split..]);
        let mut node = match op {
            "box" | "sphere" | "cylinder" | "cone" => {
                let want = if op == "box" {
                    3
                } else if op == "sphere" {
                    1
                } else {
                    2
                };
                if args.len() != want {
                    return err(n, format!("`{op}` takes {want} numbers, found {}", args.len()));
                }
                let v = numbers(n, args)?;
                if let Some(bad) = v.iter().find(|x| **x <= 0.0) {
                    return err(n, format!("`{op}` needs sizes above zero, found {bad}"));
                }
                Node::Solid(match op {
                    "box" => box_mesh(v[0], v[1], v[2]),
                    "sphere" => sphere_mesh(v[0], segments),
                    "cylinder" => cylinder_mesh(v[0], v[1], segments),
                    _ => cone_mesh(v[0], v[1], segments),
                })
            }
            "plane" | "quadric" => {
                let want = if op == "plane" { 4 } else { 10 };
                if args.len() != want {
                    return err(n, format!("`{op}` takes {want} numbers, found {}", args.len()));
                }
                let v = numbers(n, args)?;
                let h = if op == "plane" {
                    HalfSpace::plane(v[0], v[1], v[2], v[3])
                } else {
                    let mut k = [0.0; 10];
                    k.copy_from_slice(&v);
                    HalfSpace::quadric(k)
                };
                if h.is_constant() {
                    return err(n, format!("`{op}` has no term in x, y or z"));
                }
                Node::Half(h)
            }
            "union" | "intersection" | "difference" => {
                if args.len() < 2 {
                    return err(n, format!("`{op}` needs two or more names"));
                }
                let mut operands = Vec::new();
                for a in args {
                    let Some(m) = defs.get(*a) else {
                        return err(n, format!("`{a}` is not defined on an earlier line"));
                    };
                    operands.push((*a, m));
                }
                Node::Solid(combine(n, name, op, &operands, segments)?)
            }
            other => {
                return err(
                    n,
                    format!("unknown operation `{other}` (box, sphere, cylinder, cone, plane, quadric, union, intersection, difference)"),
                )
            }
        };
        apply_transforms(n, transforms, &mut node)?;
        if let Node::Solid(mesh) = &node {
            if mesh.triangles.is_empty() {
                return err(n, format!("`{name}` is empty"));
            }
        }
        defs.insert(name.to_string(), node);
        last = Some((n, name.to_string()));
    }
    let Some((n, name)) = last else {
        return err(0, "no definitions");
    };
    let mut mesh = match defs.remove(&name).expect("defined") {
        Node::Solid(m) => m,
        Node::Half(_) => {
            return err(
                n,
                format!("`{name}` is an unbounded half-space: intersect it with a bounded solid"),
            )
        }
    };
    improve(&mut mesh);
    if let Err(e) = check_closed(&mesh) {
        return err(n, format!("the result is not a closed mesh: {e}"));
    }
    Ok(mesh)
}

/// `op` over the operands of line `n` (defining `name`). Bounded operands are combined with the
/// mesh booleans; half-spaces are meshed over the bounding box of the bounded result so far.
fn combine(
    n: usize,
    name: &str,
    op: &str,
    operands: &[(&str, &Node)],
    segments: usize,
) -> Result<CsgMesh, CsgError> {
    let unbounded = |a: &str, why: &str| {
        err(
            n,
            format!("`{a}` is an unbounded half-space and cannot be {why} (intersect it with a bounded solid)"),
        )
    };
    // OpType is neither Copy nor Clone: made afresh for each step.
    let kind = || match op {
        "union" => OpType::Add,
        "intersection" => OpType::Intersect,
        _ => OpType::Subtract,
    };
    let boolean = |p: &Manifold, m: &Manifold, k: OpType| {
        // boolmesh reports an empty result as an error ("empty pos matrix").
        compute_boolean(p, m, k).map_err(|e| CsgError {
            line: n,
            message: if e.contains("empty") {
                format!("`{name}` is empty (`{op}` left nothing: {e})")
            } else {
                format!("`{op}` failed: {e}")
            },
        })
    };
    let to_manifold = |a: &str, m: &CsgMesh| {
        manifold(m).map_err(|e| CsgError {
            line: n,
            message: format!("`{a}`: {e}"),
        })
    };
    // Bounded operands first (in order), then the half-spaces: an intersection is the same in
    // any order, and a difference keeps its first operand first.
    let mut acc: Option<Manifold> = None;
    for (i, (a, node)) in operands.iter().enumerate() {
        let Node::Solid(m) = node else {
            match op {
                "union" => return unbounded(a, "part of a `union`"),
                "difference" if i == 0 => {
                    return unbounded(a, "the first operand of a `difference`")
                }
                _ => continue,
            }
        };
        let m = to_manifold(a, m)?;
        acc = Some(match acc {
            None => m,
            Some(p) => boolean(&p, &m, kind())?,
        });
    }
    let Some(mut acc) = acc else {
        return err(
            n,
            format!("`{op}` of half-spaces alone is unbounded: add a bounded operand"),
        );
    };
    for (a, node) in operands {
        let Node::Half(h) = node else { continue };
        let h = if op == "difference" {
            h.complement()
        } else {
            h.clone()
        };
        let now = from_manifold(&acc);
        let (lo, hi) = bounds(&now);
        match h.bounded_mesh(lo, hi, segments) {
            Ok(None) => {}
            Ok(Some(m)) => acc = boolean(&acc, &to_manifold(a, &m)?, OpType::Intersect)?,
            Err(e) if e.contains("nothing") => {
                return err(n, format!("`{name}` is empty (`{a}`: {e})"))
            }
            Err(e) => return err(n, format!("`{a}`: {e}")),
        }
    }
    Ok(from_manifold(&acc))
}

/// The axis-aligned bounding box of a mesh's vertices.
fn bounds(m: &CsgMesh) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &m.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

fn numbers(n: usize, words: &[&str]) -> Result<Vec<f64>, CsgError> {
    words
        .iter()
        .map(|w| match w.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => err(n, format!("`{w}` is not a number")),
        })
        .collect()
}

fn apply_transforms(n: usize, words: &[&str], node: &mut Node) -> Result<(), CsgError> {
    let mut i = 0;
    while i < words.len() {
        let key = words[i];
        // Arguments run to the next keyword.
        let end = words[i + 1..]
            .iter()
            .position(|w| matches!(*w, "translate" | "rotate" | "scale"))
            .map_or(words.len(), |p| p + i + 1);
        let args = &words[i + 1..end];
        match key {
            "translate" => {
                if args.len() != 3 {
                    return err(n, "`translate` takes 3 numbers");
                }
                let t = numbers(n, args)?;
                match node {
                    Node::Solid(mesh) => {
                        for p in &mut mesh.positions {
                            for k in 0..3 {
                                p[k] += t[k];
                            }
                        }
                    }
                    Node::Half(h) => {
                        let mut inv = IDENTITY;
                        for k in 0..3 {
                            inv[k][3] = -t[k];
                        }
                        h.transform_by_inverse(inv);
                    }
                }
            }
            "rotate" => {
                if args.len() != 2 {
                    return err(n, "`rotate` takes an axis (x, y or z) and degrees");
                }
                let axis = match args[0] {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    a => return err(n, format!("`{a}` is not an axis (x, y or z)")),
                };
                let (s, c) = numbers(n, &args[1..])?[0].to_radians().sin_cos();
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                match node {
                    Node::Solid(mesh) => {
                        for p in &mut mesh.positions {
                            let (a, b) = (p[u], p[v]);
                            p[u] = c * a - s * b;
                            p[v] = s * a + c * b;
                        }
                    }
                    Node::Half(h) => {
                        // The inverse: the rotation by minus the angle.
                        let mut inv = IDENTITY;
                        (inv[u][u], inv[u][v], inv[v][u], inv[v][v]) = (c, s, -s, c);
                        h.transform_by_inverse(inv);
                    }
                }
            }
            "scale" => {
                let f = match args.len() {
                    1 => vec![numbers(n, args)?[0]; 3],
                    3 => numbers(n, args)?,
                    _ => return err(n, "`scale` takes 1 or 3 numbers"),
                };
                if f.contains(&0.0) {
                    return err(n, "`scale` by zero flattens the shape");
                }
                match node {
                    Node::Solid(mesh) => {
                        for p in &mut mesh.positions {
                            for k in 0..3 {
                                p[k] *= f[k];
                            }
                        }
                        // A mirror (odd number of negative factors) turns the winding inside out.
                        if f.iter().filter(|x| **x < 0.0).count() % 2 == 1 {
                            for t in &mut mesh.triangles {
                                t.swap(1, 2);
                            }
                        }
                    }
                    Node::Half(h) => {
                        let mut inv = IDENTITY;
                        for k in 0..3 {
                            inv[k][k] = 1.0 / f[k];
                        }
                        h.transform_by_inverse(inv);
                    }
                }
            }
            other => return err(n, format!("unexpected `{other}` after the arguments")),
        }
        i = end;
    }
    Ok(())
}

const IDENTITY: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// Vertices snapped to a 2⁻²⁴ grid before the booleans: nearly coincident inputs (a limitation
/// boolmesh's own tests document) become exactly coincident.
fn manifold(m: &CsgMesh) -> Result<Manifold, String> {
    let grid = (1u64 << 24) as f64;
    let pos: Vec<f64> = m
        .positions
        .iter()
        .flat_map(|p| p.map(|c| (c * grid).round() / grid))
        .collect();
    let idx: Vec<usize> = m.triangles.iter().flatten().map(|&i| i as usize).collect();
    Manifold::new(&pos, &idx)
}

fn from_manifold(m: &Manifold) -> CsgMesh {
    CsgMesh {
        positions: m.ps.iter().map(|p| [p.x, p.y, p.z]).collect(),
        triangles: m
            .hs
            .chunks(3)
            .map(|h| [h[0].tail as u32, h[1].tail as u32, h[2].tail as u32])
            .collect(),
    }
}

fn box_mesh(sx: f64, sy: f64, sz: f64) -> CsgMesh {
    let (x, y, z) = (sx / 2.0, sy / 2.0, sz / 2.0);
    let positions = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -x } else { x },
                if i & 2 == 0 { -y } else { y },
                if i & 4 == 0 { -z } else { z },
            ]
        })
        .collect();
    // Each face as a quad, counter-clockwise seen from outside.
    let quads = [
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    CsgMesh {
        positions,
        triangles,
    }
}

/// A latitude-longitude sphere: `segments` around, `segments / 2` (at least 2) rings.
fn sphere_mesh(r: f64, segments: usize) -> CsgMesh {
    let rings = (segments / 2).max(2);
    let mut positions = vec![[0.0, 0.0, -r]];
    for j in 1..rings {
        let phi = std::f64::consts::PI * j as f64 / rings as f64;
        let (s, c) = phi.sin_cos();
        for i in 0..segments {
            let t = std::f64::consts::TAU * i as f64 / segments as f64;
            positions.push([r * s * t.cos(), r * s * t.sin(), -r * c]);
        }
    }
    positions.push([0.0, 0.0, r]);
    let top = (positions.len() - 1) as u32;
    let at = |j: usize, i: usize| (1 + (j - 1) * segments + i % segments) as u32;
    let mut triangles = Vec::new();
    for i in 0..segments {
        triangles.push([0, at(1, i + 1), at(1, i)]);
        for j in 1..rings - 1 {
            triangles.push([at(j, i), at(j, i + 1), at(j + 1, i + 1)]);
            triangles.push([at(j, i), at(j + 1, i + 1), at(j + 1, i)]);
        }
        triangles.push([at(rings - 1, i), at(rings - 1, i + 1), top]);
    }
    CsgMesh {
        positions,
        triangles,
    }
}

/// A ring of `segments` points of radius `r` at height z for each entry of `zs` (radius 0 gives
/// one apex point), closed by fans at both ends.
fn lathe(r: &[f64], zs: &[f64], segments: usize) -> CsgMesh {
    let mut positions = vec![[0.0, 0.0, zs[0]]];
    let mut rings = Vec::new();
    for (&rr, &z) in r.iter().zip(zs) {
        let start = positions.len() as u32;
        if rr == 0.0 {
            positions.push([0.0, 0.0, z]);
            rings.push((start, 1u32));
        } else {
            for i in 0..segments {
                let t = std::f64::consts::TAU * i as f64 / segments as f64;
                positions.push([rr * t.cos(), rr * t.sin(), z]);
            }
            rings.push((start, segments as u32));
        }
    }
    let s = segments as u32;
    let at = |(start, len): (u32, u32), i: u32| start + i % s % len;
    let mut triangles = Vec::new();
    // Bottom cap, seen from below (−z) counter-clockwise.
    for i in 0..s {
        triangles.push([0, at(rings[0], i + 1), at(rings[0], i)]);
    }
    for w in rings.windows(2) {
        for i in 0..s {
            let (a, b, c, d) = (at(w[0], i), at(w[0], i + 1), at(w[1], i + 1), at(w[1], i));
            if w[0].1 > 1 {
                triangles.push([a, b, c]);
            }
            if w[1].1 > 1 {
                triangles.push([a, c, d]);
            }
        }
    }
    let last = *rings.last().expect("rings");
    if last.1 > 1 {
        let top = positions.len() as u32;
        positions.push([0.0, 0.0, *zs.last().expect("zs")]);
        for i in 0..s {
            triangles.push([at(last, i), at(last, i + 1), top]);
        }
    }
    CsgMesh {
        positions,
        triangles,
    }
}

fn cylinder_mesh(r: f64, h: f64, segments: usize) -> CsgMesh {
    lathe(&[r, r], &[0.0, h], segments)
}

fn cone_mesh(r: f64, h: f64, segments: usize) -> CsgMesh {
    lathe(&[r, 0.0], &[0.0, h], segments)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit_normal(p: &[[f64; 3]], t: [u32; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|i| p[i as usize]);
    let n = cross(sub(b, a), sub(c, a));
    let l = dot(n, n).sqrt();
    if l == 0.0 {
        n
    } else {
        n.map(|x| x / l)
    }
}

/// The smallest interior angle of a triangle, in degrees.
pub fn min_angle(p: &[[f64; 3]], t: [u32; 3]) -> f64 {
    let v = t.map(|i| p[i as usize]);
    (0..3)
        .map(|k| {
            let (e1, e2) = (sub(v[(k + 1) % 3], v[k]), sub(v[(k + 2) % 3], v[k]));
            let c = dot(e1, e2) / (dot(e1, e1) * dot(e2, e2)).sqrt();
            c.clamp(-1.0, 1.0).acos().to_degrees()
        })
        .fold(180.0, f64::min)
}

/// Edge flips between coplanar neighbours (normals within 1e-9) whenever the flip raises the
/// smaller of the two triangles' minimum angles; stops when no flip helps (at most 64 passes).
pub fn improve(m: &mut CsgMesh) {
    for _ in 0..64 {
        let mut edges: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
        for (ti, t) in m.triangles.iter().enumerate() {
            for k in 0..3 {
                edges.insert((t[k], t[(k + 1) % 3]), (ti, k));
            }
        }
        let mut touched = vec![false; m.triangles.len()];
        let mut flipped = 0;
        let mut keys: Vec<_> = edges.keys().copied().filter(|(a, b)| a < b).collect();
        keys.sort_unstable();
        for (a, b) in keys {
            let (Some(&(t0, k0)), Some(&(t1, k1))) = (edges.get(&(a, b)), edges.get(&(b, a)))
            else {
                continue;
            };
            if touched[t0] || touched[t1] {
                continue;
            }
            let (x, y) = (m.triangles[t0], m.triangles[t1]);
            let c = x[(k0 + 2) % 3];
            let d = y[(k1 + 2) % 3];
            if c == d || edges.contains_key(&(c, d)) || edges.contains_key(&(d, c)) {
                continue;
            }
            let p = &m.positions;
            let (n0, n1) = (unit_normal(p, x), unit_normal(p, y));
            if dot(n0, n1) < 1.0 - 1e-9 {
                continue;
            }
            // (a, b, c) and (b, a, d) share a-b; the quad a, d, b, c is split along d-c instead.
            let (u, v) = ([a, d, c], [d, b, c]);
            let (nu, nv) = (unit_normal(p, u), unit_normal(p, v));
            // The quad must be convex: both new triangles face the old way.
            if dot(nu, n0) < 1.0 - 1e-9 || dot(nv, n0) < 1.0 - 1e-9 {
                continue;
            }
            let before = min_angle(p, x).min(min_angle(p, y));
            let after = min_angle(p, u).min(min_angle(p, v));
            if after > before + 1e-6 {
                m.triangles[t0] = u;
                m.triangles[t1] = v;
                touched[t0] = true;
                touched[t1] = true;
                flipped += 1;
            }
        }
        if flipped == 0 {
            break;
        }
    }
}

/// Every directed edge used once and its reverse used once: closed and consistently oriented.
pub fn check_closed(m: &CsgMesh) -> Result<(), String> {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.triangles {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Err(format!("degenerate triangle {t:?}"));
        }
        for k in 0..3 {
            *count.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &c) in &count {
        if c != 1 || count.get(&(b, a)) != Some(&1) {
            return Err(format!(
                "edge {a}-{b} is not shared by exactly two triangles in opposite directions"
            ));
        }
    }
    Ok(())
}

/// Signed volume (positive when the triangles wind counter-clockwise seen from outside).
pub fn signed_volume(m: &CsgMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            dot(a, cross(b, c)) / 6.0
        })
        .sum()
}

/// Corners whose faces meet at more than this angle get separate normals (a hard edge), in
/// degrees: a machined part's edges stay sharp while the 16-segment sphere and cylinder (22.5°
/// between neighbouring facets) are shaded smooth.
pub const CREASE_DEGREES: f64 = 40.0;

impl CsgMesh {
    /// The mesh as a parsed OBJ file with one normal per corner: the normalized sum of the
    /// area-weighted normals of the faces around the corner's position that lie within
    /// [`CREASE_DEGREES`] of the corner's own face. `bake` and `render` then treat it like an
    /// OBJ with `vn` (a vertex is split where its corners' normals differ).
    pub fn to_obj_file(&self, name: &str) -> super::obj::ObjFile {
        use super::obj::{Corner, ObjFile, Texcoords};
        let p = &self.positions;
        let area_normals: Vec<[f64; 3]> = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| p[i as usize]);
                cross(sub(b, a), sub(c, a))
            })
            .collect();
        let units: Vec<[f64; 3]> = self.triangles.iter().map(|t| unit_normal(p, *t)).collect();
        let mut around: Vec<Vec<usize>> = vec![Vec::new(); p.len()];
        for (ti, t) in self.triangles.iter().enumerate() {
            for &v in t {
                around[v as usize].push(ti);
            }
        }
        let cos = CREASE_DEGREES.to_radians().cos();
        let mut normals: Vec<[f64; 3]> = Vec::new();
        let mut index: HashMap<[u64; 3], u32> = HashMap::new();
        let mut triangles = Vec::with_capacity(self.triangles.len());
        for (ti, t) in self.triangles.iter().enumerate() {
            triangles.push(t.map(|v| {
                let mut s = [0.0; 3];
                for &f in &around[v as usize] {
                    if dot(units[f], units[ti]) >= cos {
                        s = [0, 1, 2].map(|k| s[k] + area_normals[f][k]);
                    }
                }
                let l = dot(s, s).sqrt();
                let n = s.map(|x| x / l);
                let key = n.map(f64::to_bits);
                let next = normals.len() as u32;
                let ni = *index.entry(key).or_insert(next);
                if ni == next {
                    normals.push(n);
                }
                Corner {
                    position: v,
                    normal: Some(ni),
                    uv: None,
                }
            }));
        }
        ObjFile {
            name: name.to_string(),
            positions: self.positions.clone(),
            normals,
            uvs: Vec::new(),
            triangles,
            all_corners_have_normals: true,
            texcoords: Texcoords::None,
        }
    }
}

/// Reads and meshes a CSG file; errors carry the path and line.
pub fn load_csg(path: &std::path::Path) -> Result<CsgMesh, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    mesh_csg_text(&text).map_err(|e| format!("{}: {e}", path.display()))
}
