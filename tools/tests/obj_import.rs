//! OBJ import (issue #20, defect 3): a vertex is split only where the data the renderer uses
//! differs at that corner — a given `vn` — never at a texture seam (`vt`), and face-averaged
//! normals are averaged per position. Hard edges given by `vn` stay hard.

use scanline3d_tools as common;

use std::fmt::Write as _;
use std::path::PathBuf;

use common::obj::{load_obj, parse_obj, scan, vertex_normals, NormalSource, ObjMesh};
use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d_support::demo;

type Q = Fx<I16F16>;

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("obj_import");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// A UV sphere (`rings` × `segs`, one vertex per pole, no duplicated positions) as OBJ text.
/// With `vt`, faces carry texture coordinates the usual way: a column u = 1 repeating u = 0 at
/// the seam meridian and one coordinate per pole triangle, so the corners at the seam and at
/// the poles have several `vt`. With `vn`, one unit normal per position (smooth).
fn sphere_obj(rings: usize, segs: usize, with_vt: bool, with_vn: bool) -> String {
    use std::f64::consts::PI;
    let mut s = String::from("# UV sphere\n");
    let mut pos = vec![[0.0, 1.0, 0.0]];
    for i in 1..rings {
        let th = PI * i as f64 / rings as f64;
        for j in 0..segs {
            let ph = 2.0 * PI * j as f64 / segs as f64;
            pos.push([th.sin() * ph.cos(), th.cos(), -th.sin() * ph.sin()]);
        }
    }
    pos.push([0.0, -1.0, 0.0]);
    for p in &pos {
        writeln!(s, "v {} {} {}", p[0], p[1], p[2]).unwrap();
    }
    if with_vn {
        for p in &pos {
            writeln!(s, "vn {} {} {}", p[0], p[1], p[2]).unwrap();
        }
    }
    // vt grid (segs + 1) × (rings + 1), 1-based index of (column j, row i).
    if with_vt {
        for i in 0..=rings {
            for j in 0..=segs {
                writeln!(
                    s,
                    "vt {} {}",
                    j as f64 / segs as f64,
                    i as f64 / rings as f64
                )
                .unwrap();
            }
        }
    }
    let vt = |i: usize, j: usize| i * (segs + 1) + j + 1;
    // Position (1-based) of ring i (1..rings), column j (wrapping).
    let p = |i: usize, j: usize| -> usize {
        if i == 0 {
            1
        } else if i == rings {
            pos.len()
        } else {
            2 + (i - 1) * segs + j % segs
        }
    };
    let mut face = |c: [(usize, usize, usize); 3]| {
        // Counter-clockwise from outside: flip when the normal points inward.
        let [a, b, d] = c.map(|(v, _, _)| pos[v - 1]);
        let n = scanline3d::math::cross(scanline3d::math::sub(b, a), scanline3d::math::sub(d, a));
        let centre = [0, 1, 2].map(|k| a[k] + b[k] + d[k]);
        let c = if scanline3d::math::dot(n, centre) < 0.0 {
            [c[0], c[2], c[1]]
        } else {
            c
        };
        s.push('f');
        for (v, i, j) in c {
            match (with_vt, with_vn) {
                (true, true) => write!(s, " {v}/{}/{v}", vt(i, j)),
                (true, false) => write!(s, " {v}/{}", vt(i, j)),
                (false, true) => write!(s, " {v}//{v}"),
                (false, false) => write!(s, " {v}"),
            }
            .unwrap();
        }
        s.push('\n');
    };
    for i in 0..rings {
        for j in 0..segs {
            // Quad (i, j) .. (i + 1, j + 1); at the poles one triangle.
            let (a, b, c, d) = (
                (p(i, j), i, j),
                (p(i, j + 1), i, j + 1),
                (p(i + 1, j + 1), i + 1, j + 1),
                (p(i + 1, j), i + 1, j),
            );
            if i == 0 {
                face([a, c, d]);
            } else if i == rings - 1 {
                face([a, b, c]);
            } else {
                face([a, b, c]);
                face([a, c, d]);
            }
        }
    }
    s
}

fn write(name: &str, text: &str) -> PathBuf {
    let path = tmp(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// What the loader did before the fix: tobj with `single_index`, one vertex per distinct
/// `v/vt/vn` combination.
fn vertices_split_by_tobj(path: &std::path::Path) -> usize {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &opts).unwrap();
    models.iter().map(|m| m.mesh.positions.len() / 3).sum()
}

/// The sphere, Gouraud-shaded through the library at four turns about Y (the seam meridian
/// faces the camera in one of them).
fn render(mesh: &ObjMesh, normals: &[[f64; 3]]) -> Vec<Frame<Rgb565>> {
    let pos: Vec<[Q; 3]> = mesh.positions.iter().map(|p| p.map(Q::from_f64)).collect();
    let nor: Vec<[Q; 3]> = normals.iter().map(|n| n.map(Q::from_f64)).collect();
    let m = Mesh::new(&pos, &mesh.indices)
        .unwrap()
        .with_normals(&nor)
        .unwrap();
    (0..4)
        .map(|k| {
            let objects = [Object {
                mesh: m,
                transform: Mat4::rotate_x(demo::deg(20.0))
                    .then(&Mat4::rotate_y(demo::deg(90.0 * k as f64))),
                material: demo::torus_material(),
            }];
            let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
            let mut r: Box<demo::TorusRenderer<Q, Rgb565>> = Box::default();
            let mut f = Frame::new(240, 240, Rgb565::BLACK);
            r.render(&scene, &mut f).unwrap();
            f
        })
        .collect()
}

fn differing(a: &[Frame<Rgb565>], b: &[Frame<Rgb565>]) -> usize {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.px.iter().zip(&y.px).filter(|(p, q)| p != q).count())
        .sum()
}

#[test]
fn texture_seams_do_not_split_face_averaged_vertices() {
    let (rings, segs) = (8, 12);
    let positions = 2 + (rings - 1) * segs;
    let seamed = write("sphere_vt.obj", &sphere_obj(rings, segs, true, false));
    let plain = write("sphere.obj", &sphere_obj(rings, segs, false, false));
    let before = vertices_split_by_tobj(&seamed);
    let file = parse_obj(&seamed).unwrap();
    assert_eq!(file.default_normals(), NormalSource::FaceAverage);
    let mesh = file
        .mesh(NormalSource::FaceAverage)
        .unwrap()
        .to_u16("")
        .unwrap();
    println!(
        "sphere with vt seams: {positions} positions; split by v/vt (before): {before} vertices; now: {}",
        mesh.positions.len()
    );
    assert!(before > positions, "the test file has no seams");
    assert_eq!(mesh.positions.len(), positions);
    // The same mesh as the file without vt: same vertices, triangles, normals, pixels.
    let without_vt = load_obj(&plain).unwrap();
    assert_eq!(mesh, without_vt);
    assert_eq!(load_obj(&seamed).unwrap(), without_vt);
    let normals = vertex_normals(&mesh, false);
    let frames = render(&mesh, &normals);
    let reference = render(&without_vt, &vertex_normals(&without_vt, false));
    assert_eq!(differing(&frames, &reference), 0, "a seam line");
    let lit = frames[0].px.iter().filter(|&&c| c != Rgb565::BLACK).count();
    assert!(lit > 10_000, "the sphere covers {lit} pixels");
    // The old way (one vertex per v/vt combination, normals averaged per split vertex) gives a
    // different image: this test sees a seam when there is one.
    let old = {
        let opts = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        let (models, _) = tobj::load_obj(&seamed, &opts).unwrap();
        let m = &models[0].mesh;
        ObjMesh {
            positions: m
                .positions
                .chunks(3)
                .map(|p| [p[0] as f64, p[1] as f64, p[2] as f64])
                .collect(),
            normals: None,
            indices: m
                .indices
                .chunks(3)
                .map(|t| [t[0] as u16, t[1] as u16, t[2] as u16])
                .collect(),
        }
    };
    let old_frames = render(&old, &vertex_normals(&old, false));
    let seam_pixels = differing(&old_frames, &reference);
    println!("split by v/vt, the image differs in {seam_pixels} pixels (four views)");
    assert!(seam_pixels > 0);
}

#[test]
fn smooth_file_normals_do_not_split_at_texture_seams() {
    let (rings, segs) = (6, 10);
    let positions = 2 + (rings - 1) * segs;
    let path = write("sphere_vt_vn.obj", &sphere_obj(rings, segs, true, true));
    let file = parse_obj(&path).unwrap();
    assert!(file.all_corners_have_normals);
    assert_eq!(file.default_normals(), NormalSource::File);
    let mesh = load_obj(&path).unwrap();
    assert_eq!(mesh.positions.len(), positions);
    let ns = mesh.normals.as_ref().unwrap();
    for (p, n) in mesh.positions.iter().zip(ns) {
        assert_eq!(p, n, "the file's normal of each position");
    }
    assert!(vertices_split_by_tobj(&path) > positions);
}

/// A unit cube with one `vn` per face (hard edges), 8 positions, 6 normals.
fn hard_cube() -> String {
    let mut s = String::new();
    for k in 0..8 {
        let c = |b: usize| if k & b != 0 { 0.5 } else { -0.5 };
        writeln!(s, "v {} {} {}", c(1), c(2), c(4)).unwrap();
    }
    for n in ["1 0 0", "-1 0 0", "0 1 0", "0 -1 0", "0 0 1", "0 0 -1"] {
        writeln!(s, "vn {n}").unwrap();
    }
    // Quads, counter-clockwise from outside (1-based positions: bit 1 = x, 2 = y, 4 = z).
    for (q, n) in [
        ([2, 4, 8, 6], 1),
        ([1, 5, 7, 3], 2),
        ([3, 7, 8, 4], 3),
        ([1, 2, 6, 5], 4),
        ([5, 6, 8, 7], 5),
        ([1, 3, 4, 2], 6),
    ] {
        writeln!(s, "f {}", q.map(|v| format!("{v}//{n}")).join(" ")).unwrap();
    }
    s
}

#[test]
fn hard_edges_from_vn_stay_hard() {
    let path = write("hard_cube.obj", &hard_cube());
    let file = parse_obj(&path).unwrap();
    let hard = file.mesh(NormalSource::File).unwrap().to_u16("").unwrap();
    let smooth = file
        .mesh(NormalSource::FaceAverage)
        .unwrap()
        .to_u16("")
        .unwrap();
    println!(
        "cube with per-face vn: {} vertices with the file's normals, {} face-averaged",
        hard.positions.len(),
        smooth.positions.len()
    );
    assert_eq!(hard.positions.len(), 24);
    assert_eq!(smooth.positions.len(), 8);
    // Every corner's normal is its face's normal.
    let hard_normals = vertex_normals(&hard, true);
    for t in &hard.indices {
        let [a, b, c] = t.map(|i| hard.positions[i as usize]);
        let face = scanline3d::mesh::face_normal(a, b, c);
        for &i in t {
            let d = scanline3d::math::dot(face, hard_normals[i as usize]);
            assert!((d - 1.0).abs() < 1e-9, "corner normal off its face: {d}");
        }
    }
    // Rendered, a hard cube shows one colour per visible face; the averaged one shades across.
    let colours = |m: &ObjMesh, ns: &[[f64; 3]]| {
        let f = &render(m, ns)[0];
        let mut c: Vec<Rgb565> = f.px.clone();
        c.sort_by_key(|p| (p.r(), p.g(), p.b()));
        c.dedup();
        c.len()
    };
    let hard_colours = colours(&hard, &hard_normals);
    let smooth_colours = colours(&smooth, &vertex_normals(&smooth, false));
    println!("distinct colours: hard {hard_colours}, face-averaged {smooth_colours}");
    assert!(
        hard_colours <= 4,
        "background and three faces: {hard_colours}"
    );
    assert!(smooth_colours > 20, "{smooth_colours}");
}

#[test]
fn partial_normals_fall_back_to_face_averages() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n";
    let path = write("partial_vn.obj", text);
    let s = scan(text);
    assert_eq!((s.faces, s.corners_without_normal), (2, 3));
    let file = parse_obj(&path).unwrap();
    assert!(!file.all_corners_have_normals);
    assert_eq!(file.default_normals(), NormalSource::FaceAverage);
    let e = file.mesh(NormalSource::File).unwrap_err();
    assert!(e.contains("vn"), "{e}");
    assert_eq!(load_obj(&path).unwrap().positions.len(), 4);
}

#[test]
fn equal_positions_are_one_vertex_whatever_their_v_lines() {
    // An exporter that repeats a position for each face using it.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n";
    let path = write("repeated_v.obj", text);
    let mesh = load_obj(&path).unwrap();
    assert_eq!(mesh.positions.len(), 4);
    assert_eq!(mesh.indices, vec![[0, 1, 2], [1, 3, 2]]);
}
