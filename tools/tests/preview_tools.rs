//! The preview tools on large models (issue #20, defect 4) and on bad inputs: `render` draws a
//! model no renderer can hold in passes and its `--budget` refuses it with a message that says
//! what to do, a model beyond u16 indices is refused with that message, `--max-triangles`
//! previews it simplified, and `bake --max-triangles` simplifies it to a budget and reports the
//! error. Large models are made here, never committed.

use scanline3d_tools as common;
mod shared;

use std::fmt::Write as _;
use std::path::PathBuf;

use common::obj::{load_obj, parse_obj, NormalSource};

fn tmp(name: &str) -> PathBuf {
    shared::tmp("preview_tools", name)
}

fn run(tool: &str, args: &[&str]) -> (i32, String, String) {
    shared::run(tool, args)
}

/// A closed torus of `nu × nv` vertices and twice as many triangles (no normals).
fn torus_obj(nu: usize, nv: usize) -> String {
    use std::f64::consts::TAU;
    let mut s = String::new();
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            let (x, y, z) = (
                (1.0 + 0.35 * v.cos()) * u.cos(),
                0.35 * v.sin(),
                (1.0 + 0.35 * v.cos()) * u.sin(),
            );
            writeln!(s, "v {x} {y} {z}").unwrap();
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + j % nv + 1;
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            writeln!(s, "f {a} {d} {c}\nf {a} {c} {b}").unwrap();
        }
    }
    s
}

/// "error X model units = Y % of the bounding-box diagonal": (X, Y).
fn reported_error(stdout: &str) -> (f64, f64) {
    let rest = stdout
        .split("error ")
        .nth(1)
        .unwrap_or_else(|| panic!("no error reported: {stdout}"));
    let words: Vec<&str> = rest.split_whitespace().collect();
    assert_eq!(&words[1..4], &["model", "units", "="], "{stdout}");
    (words[0].parse().unwrap(), words[4].parse().unwrap())
}

/// A UV sphere of radius 1: `rings` bands of `segs` segments, `(rings − 1)·segs + 2` vertices
/// and `2·segs·(rings − 1)` triangles, outward winding, no normals.
fn sphere_obj(rings: usize, segs: usize) -> String {
    use std::f64::consts::{PI, TAU};
    let mut s = String::from("v 0 1 0\n");
    for i in 1..rings {
        let th = PI * i as f64 / rings as f64;
        for j in 0..segs {
            let ph = TAU * j as f64 / segs as f64;
            let (x, y, z) = (th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin());
            writeln!(s, "v {x} {y} {z}").unwrap();
        }
    }
    s.push_str("v 0 -1 0\n");
    let v = |i: usize, j: usize| 2 + (i - 1) * segs + j % segs;
    let bottom = 2 + (rings - 1) * segs;
    for j in 0..segs {
        writeln!(s, "f 1 {} {}", v(1, j + 1), v(1, j)).unwrap();
        writeln!(s, "f {bottom} {} {}", v(rings - 1, j), v(rings - 1, j + 1)).unwrap();
    }
    for i in 1..rings - 1 {
        for j in 0..segs {
            let (a, b, c, d) = (v(i, j), v(i, j + 1), v(i + 1, j + 1), v(i + 1, j));
            writeln!(s, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    s
}

/// The number after `key` in `text` ("pixels written 41023" → 41023).
fn number_after(text: &str, key: &str) -> usize {
    let rest = text
        .split(key)
        .nth(1)
        .unwrap_or_else(|| panic!("{key:?} not in {text}"));
    rest.split_whitespace()
        .next()
        .unwrap()
        .trim_matches([',', '`'])
        .parse()
        .unwrap()
}

/// Pixels of an RGB image that are not black (the background).
fn lit_pixels(rgb: &[u8]) -> usize {
    rgb.chunks_exact(3).filter(|p| p != &[0, 0, 0]).count()
}

#[test]
#[cfg_attr(not(feature = "simplify"), ignore = "needs the simplify feature")]
fn a_69k_triangle_scan_previews_on_the_host_in_passes() {
    // 34 562 vertices, 69 120 triangles: within u16 indices, beyond any one renderer (32 768
    // vertices).
    let obj = tmp("big_sphere.obj");
    std::fs::write(&obj, sphere_obj(145, 240)).unwrap();
    let o = obj.to_str().unwrap();
    let png = tmp("big_sphere.png");
    let forced = tmp("big_sphere_forced.png");
    let _ = std::fs::remove_file(&png);
    // Orthographic and fitted: the sphere's outline is a disc of radius 240 / 2.1 px.
    let args = ["--obj", o, "--fit", "--ortho", "1", "--out"];
    let (code, stdout, stderr) = run("render", &[&args[..], &[png.to_str().unwrap()]].concat());
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
    println!("{stdout}");
    assert!(stdout.contains("triangles in 69120"), "{stdout}");
    assert!(stdout.contains("drawn in 2 passes"), "{stdout}");
    assert!(stdout.contains("34562 vertices (of 32768)"), "{stdout}");
    assert!(stdout.contains("no renderer holds this scene"), "{stdout}");
    // Half the sphere faces the camera: the back half is culled, every piece's share added up.
    let culled = number_after(&stdout, "culled ");
    assert!((34_000..=35_100).contains(&culled), "{stdout}");
    let (w, h, rgb) = common::read_png(&png).expect("a PNG");
    assert_eq!((w, h), (240, 240));
    let covered = lit_pixels(&rgb);
    // A closed convex object after culling: no pixel is written twice, whatever the pass.
    assert_eq!(
        covered,
        number_after(&stdout, "pixels written "),
        "{stdout}"
    );
    let r = 240.0 / 2.1;
    let disc = std::f64::consts::PI * r * r;
    assert!(
        (covered as f64 - disc).abs() < 2.0 * std::f64::consts::PI * r * 0.5,
        "{covered} pixels covered, the disc has {disc:.0}"
    );
    // Passes of at most 10 000 triangles (7 or more): the same image.
    let (code, stdout, stderr) = run(
        "render",
        &[
            &args[..],
            &[forced.to_str().unwrap(), "--pass-triangles", "10000"],
        ]
        .concat(),
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(number_after(&stdout, "drawn in ") >= 7, "{stdout}");
    assert_eq!(common::read_png(&forced), common::read_png(&png));

    // The budget says what a device would need and what to do; nothing is written.
    let (code, stdout, stderr) = run("render", &["--obj", o, "--fit", "--budget"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        stdout.contains("vertices stored (mesh + clipping): 34562"),
        "{stdout}"
    );
    assert!(stdout.contains("of 69120 in the mesh"), "{stdout}");
    for part in [
        "big_sphere.obj",
        "34562 vertices",
        "32768",
        "--max-triangles",
        "--features simplify --bin bake",
    ] {
        assert!(stderr.contains(part), "{stderr:?} lacks {part:?}");
    }
    // What it suggests fits a renderer: the budget of the simplified model passes.
    let n = number_after(&stderr, "--max-triangles ").to_string();
    let (code, stdout, stderr) = run(
        "render",
        &["--obj", o, "--fit", "--budget", "--max-triangles", &n],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("renderer type:"), "{stdout}");
}

#[test]
#[cfg_attr(not(feature = "simplify"), ignore = "needs the simplify feature")]
fn a_model_too_large_for_one_renderer_is_drawn_in_passes_and_can_be_simplified() {
    // 36 000 vertices, 72 000 triangles: within u16 indices, beyond any renderer's frame.
    let obj = tmp("big_torus.obj");
    std::fs::write(&obj, torus_obj(300, 120)).unwrap();
    let o = obj.to_str().unwrap();
    let png = tmp("big_torus.png");
    let _ = std::fs::remove_file(&png);
    let (code, stdout, stderr) = run(
        "render",
        &["--obj", o, "--fit", "--out", png.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("triangles in 72000"), "{stdout}");
    assert!(stdout.contains("36000 vertices (of 32768)"), "{stdout}");
    assert_eq!(common::read_png(&png).map(|p| (p.0, p.1)), Some((240, 240)));
    let (code, _, stderr) = run("render", &["--obj", o, "--fit", "--budget"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for part in [
        "big_torus.obj",
        "36000 vertices",
        "32768",
        "--max-triangles",
        "--features simplify --bin bake",
    ] {
        assert!(stderr.contains(part), "{stderr:?} lacks {part:?}");
    }
    // Previewed simplified, with the error in the summary and in the budget.
    let (code, stdout, stderr) = run(
        "render",
        &[
            "--obj",
            o,
            "--fit",
            "--max-triangles",
            "20000",
            "--out",
            png.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("72000 -> 20000 triangles"), "{stdout}");
    assert!(stdout.contains("triangles in 20000"), "{stdout}");
    assert_eq!(common::read_png(&png).map(|p| (p.0, p.1)), Some((240, 240)));
    let (code, stdout, stderr) = run(
        "render",
        &["--obj", o, "--fit", "--max-triangles", "20000", "--budget"],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("simplified 72000 -> 20000"), "{stdout}");
    assert!(stdout.contains("renderer type:"), "{stdout}");
    let (_, rel) = reported_error(&stdout);
    assert!(rel < 0.2, "{stdout}");

    // bake to 4000 triangles: Rust source and OBJ, a small reported error.
    let rs = tmp("big_torus_mesh.rs");
    let small = tmp("big_torus_4k.obj");
    let (code, stdout, stderr) = run(
        "bake",
        &[
            o,
            "--max-triangles",
            "4000",
            "--out",
            rs.to_str().unwrap(),
            "--obj-out",
            small.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    println!("{stdout}");
    let (abs, rel) = reported_error(&stdout);
    // A 4000-triangle torus of radii 1 and 0.35 is within a few thousandths of the original
    // (its chords alone sag about 2e-3); the diagonal is 3.88.
    assert!(abs > 0.0 && abs < 0.02, "{stdout}");
    assert!(rel < 0.5, "{stdout}");
    let mesh = load_obj(&small).unwrap();
    assert!(mesh.indices.len() <= 4000 && mesh.indices.len() > 3000);
    // The baked source: array lengths as declared, every index in range, no vertex unused.
    let src = std::fs::read_to_string(&rs).unwrap();
    let section = |name: &str| -> Vec<Vec<i64>> {
        let start = src.find(&format!("pub static {name}")).unwrap();
        let body = &src[start..];
        let body = &body[body.find("= [\n").unwrap() + 4..body.find("\n];").unwrap()];
        body.lines()
            .map(|l| {
                l.trim()
                    .trim_end_matches(',')
                    .trim_matches(['[', ']'])
                    .split(',')
                    .map(|w| {
                        w.trim()
                            .trim_start_matches("q(")
                            .trim_end_matches(')')
                            .parse()
                            .unwrap()
                    })
                    .collect()
            })
            .collect()
    };
    let (pos, nor, idx) = (section("POSITIONS"), section("NORMALS"), section("INDICES"));
    assert!(src.contains(&format!("[[Fx<I16F16>; 3]; {}]", pos.len())));
    assert!(src.contains(&format!("[[u16; 3]; {}]", idx.len())));
    assert_eq!(pos.len(), nor.len());
    assert_eq!(idx.len(), mesh.indices.len());
    let mut used = vec![false; pos.len()];
    for t in &idx {
        assert_eq!(t.len(), 3);
        for &i in t {
            assert!(
                (0..pos.len() as i64).contains(&i),
                "index {i} of {}",
                pos.len()
            );
            used[i as usize] = true;
        }
    }
    assert!(
        used.iter().all(|&u| u),
        "the baked mesh keeps unused vertices"
    );
    assert!(
        src.contains("simplified 72000 -> "),
        "the source says it was simplified"
    );
}

#[test]
#[cfg_attr(not(feature = "simplify"), ignore = "needs the simplify feature")]
fn beyond_u16_indices_the_message_says_what_to_do_and_bake_can_simplify() {
    // 70 000 vertices in a strip of two rows: more than u16 indices address.
    let n = 35_000;
    let mut s = String::new();
    for row in 0..2 {
        for k in 0..n {
            writeln!(s, "v {} {row} 0", k as f64 * 0.01).unwrap();
        }
    }
    for k in 1..n {
        let (a, b, c, d) = (k, k + 1, n + k + 1, n + k);
        writeln!(s, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
    }
    let obj = tmp("strip70k.obj");
    std::fs::write(&obj, s).unwrap();
    let o = obj.to_str().unwrap();
    let png = tmp("strip70k.png");
    let _ = std::fs::remove_file(&png);
    let (code, _, stderr) = run("render", &["--obj", o, "--out", png.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(!stderr.contains("panicked"), "{stderr}");
    for part in ["strip70k.obj", "70000 vertices", "65536", "--max-triangles"] {
        assert!(stderr.contains(part), "{stderr:?} lacks {part:?}");
    }
    assert!(!png.exists());
    // The preview of the model simplified as the message suggests.
    let n = number_after(&stderr, "--max-triangles ").to_string();
    let (code, stdout, stderr) = run(
        "render",
        &[
            "--obj",
            o,
            "--fit",
            "--max-triangles",
            &n,
            "--out",
            png.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains(&format!("69998 -> {n} triangles")),
        "{stdout}"
    );
    assert!(png.exists());
    // What the message suggests works.
    let small = tmp("strip_small.obj");
    let (code, stdout, stderr) = run(
        "bake",
        &[
            o,
            "--max-triangles",
            "1000",
            "--obj-out",
            small.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("69998 -> "), "{stdout}");
    let mesh = load_obj(&small).unwrap();
    assert!(mesh.indices.len() <= 1000);
    // The strip is flat, so nothing leaves its plane, but meshoptimizer may cut a corner of the
    // outline (its own estimate does not count that; the sampled distance does): small
    // against the 350-unit strip all the same.
    let (abs, rel) = reported_error(&stdout);
    assert!(abs < 0.2 && rel < 0.1, "{stdout}");
}

#[test]
#[cfg_attr(not(feature = "simplify"), ignore = "needs the simplify feature")]
fn max_vertices_is_a_vertex_budget() {
    let obj = tmp("torus_mid.obj");
    std::fs::write(&obj, torus_obj(60, 30)).unwrap();
    let out = tmp("torus_mid_500.obj");
    let (code, stdout, stderr) = run(
        "bake",
        &[
            obj.to_str().unwrap(),
            "--max-vertices",
            "500",
            "--obj-out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    let file = parse_obj(&out).unwrap();
    let mesh = file.mesh(NormalSource::FaceAverage).unwrap();
    assert!(
        mesh.positions.len() <= 500 && mesh.positions.len() > 300,
        "{} vertices: {stdout}",
        mesh.positions.len()
    );
}

/// A bad input: non-zero exit, no panic, a message naming the file and the problem, no output.
fn bad(tool: &str, path: &std::path::Path, expect: &[&str]) {
    let out = tmp("bad_out.png");
    let rs = tmp("bad_out.rs");
    let _ = std::fs::remove_file(&out);
    let _ = std::fs::remove_file(&rs);
    let p = path.to_str().unwrap();
    let (code, _, stderr) = match tool {
        "render" => run("render", &["--obj", p, "--out", out.to_str().unwrap()]),
        _ => run("bake", &[p, "--out", rs.to_str().unwrap()]),
    };
    let name = path.file_name().unwrap().to_str().unwrap();
    assert_ne!(code, 0, "{tool} {name}: exit status 0");
    assert!(!stderr.contains("panicked"), "{tool} {name}: {stderr}");
    assert!(
        stderr.contains(name),
        "{tool} {name}: the message does not name the file: {stderr}"
    );
    for e in expect {
        assert!(stderr.contains(e), "{tool} {name}: {stderr:?} lacks {e:?}");
    }
    for f in [&out, &rs] {
        assert!(
            !f.exists() && !f.with_extension("partial").exists(),
            "{tool} {name}: output written"
        );
    }
}

#[test]
fn bad_inputs_are_clear_errors() {
    let dir = tmp("a_directory.obj");
    std::fs::create_dir_all(&dir).unwrap();
    let file = |name: &str, text: &str| {
        let p = tmp(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let empty = file("empty.obj", "");
    let only_v = file("only_v.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    let zero = file("index_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    let nan = file("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    for tool in ["render", "bake"] {
        bad(tool, &dir, &["is a directory"]);
        bad(tool, &empty, &["no triangles"]);
        bad(tool, &only_v, &["no triangles", "3 `v` lines"]);
        bad(tool, &zero, &[":4:", "vertex 0", "start at 1"]);
        bad(tool, &nan, &[":3:", "finite"]);
    }
}

/// A bad flag: exit status 2 (a usage error, as clap's own), no panic, every `expect` part in
/// the message, no image written.
fn bad_flags(args: &[&str], expect: &[&str]) {
    let out = tmp("bad_flag.png");
    let _ = std::fs::remove_file(&out);
    let mut all = args.to_vec();
    all.extend(["--out", out.to_str().unwrap()]);
    let (code, stdout, stderr) = run("render", &all);
    assert_eq!(code, 2, "render {args:?}: {stdout}{stderr}");
    assert!(!stderr.contains("panicked"), "render {args:?}: {stderr}");
    for e in expect {
        assert!(
            stderr.contains(e),
            "render {args:?}: {stderr:?} lacks {e:?}"
        );
    }
    assert!(!out.exists(), "render {args:?}: image written");
}

#[test]
fn camera_flags_name_the_flag_and_its_range() {
    // Main printed only "camera: BadProjection { … }" (or `RoundsToZero` for --near 0), in the
    // library's parameter names (fov_y in radians, height), never the flag.
    bad_flags(
        &["--fov-y", "0"],
        &["--fov-y must be in (0, 180) degrees, got 0"],
    );
    bad_flags(
        &["--fov-y", "180"],
        &["--fov-y must be in (0, 180) degrees, got 180"],
    );
    bad_flags(
        &["--near", "5", "--far", "1"],
        &["--far must be greater than --near (5), got 1"],
    );
    bad_flags(
        &["--near", "0"],
        &["--near must be greater than 0", "got 0"],
    );
    bad_flags(&["--ortho", "0"], &["--ortho", "greater than 0", "got 0"]);
    // Main: clap's "unexpected argument '-1'" (no negative numbers accepted at all).
    bad_flags(
        &["--near", "-1"],
        &["--near must be greater than 0", "got -1"],
    );
    // Main: `camera: EyeAtTarget` (Debug); now the library's Display and the flags to check.
    bad_flags(&["--eye", "0,0,0"], &["eye equals target", "--eye"]);
}

#[test]
fn non_finite_and_zero_flags_are_refused() {
    // Main accepted each of these and exited 0: --light 0,0,0 lit nothing, --frames 0 rendered
    // one frame, --spin/--rotate-* NaN drew a different image in fixed point than in f64, and
    // NaN/∞ material coefficients drew nothing (every triangle invalid).
    bad_flags(&["--light", "0,0,0"], &["--light 0,0,0", "zero vector"]);
    bad_flags(
        &["--frames", "0"],
        &["--frames must be in [1, 1000], got 0"],
    );
    bad_flags(&["--spin", "nan"], &["--spin must be a finite number"]);
    bad_flags(
        &["--ambient", "nan"],
        &["--ambient must be a finite number"],
    );
    bad_flags(
        &["--diffuse", "inf"],
        &["--diffuse must be a finite number"],
    );
    bad_flags(
        &["--specular", "nan"],
        &["--specular must be a finite number"],
    );
    for axis in ["x", "y", "z"] {
        let flag = format!("--rotate-{axis}");
        bad_flags(
            &[&flag, "nan"],
            &[&format!("{flag} must be a finite number")],
        );
    }
    bad_flags(&["--fov-y", "nan"], &["--fov-y must be a finite number"]);
    bad_flags(&["--far", "inf"], &["--far must be a finite number"]);
    bad_flags(&["--ortho", "nan"], &["--ortho must be a finite number"]);
}

#[test]
fn other_numeric_flags_are_checked_against_their_range() {
    // Main: negative coefficients were a clap error ("unexpected argument"), or with `=`
    // accepted; --shininess 0 silently became 1; --strip beyond the image height was accepted
    // and `--strip 18446744073709551615` panicked (multiply overflow, exit 3) in debug.
    bad_flags(
        &["--specular=-1"],
        &["--specular must be in [0, 255], got -1"],
    );
    bad_flags(
        &["--ambient", "300"],
        &["--ambient must be in [0, 255], got 300"],
    );
    bad_flags(
        &["--shininess", "0"],
        &["--shininess must be in [1, 255], got 0"],
    );
    bad_flags(
        &["--strip", "241"],
        &["--strip must be in [1, 240]", "got 241"],
    );
    bad_flags(
        &["--strip", "18446744073709551615"],
        &["--strip must be in [1, 240]"],
    );
    // Negative angles are valid (main refused `--rotate-y -30` as an unexpected argument).
    let out = tmp("negative_rotation.png");
    let (code, _, stderr) = run(
        "render",
        &["--rotate-y", "-30", "--out", out.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn frames_are_bounded() {
    // Main rendered all of them, keeping every frame in memory: unbounded time and memory.
    bad_flags(
        &["--frames", "1000000"],
        &["--frames must be in [1, 1000], got 1000000"],
    );
    // Also bounded in pixels over all frames (main: 100 frames of 1024x1024 in memory twice).
    bad_flags(
        &["--frames", "100", "--size", "1024x1024"],
        &["--frames 100 at 1024x1024", "at most 64 frames"],
    );
}

#[test]
fn obj_vertices_beyond_f32_or_with_a_nan_w_are_refused() {
    // Main: tobj reads coordinates as f32, so `1e39` became +∞, and a NaN fourth value (w)
    // made the triangle invalid: both rendered an empty image with exit status 0.
    let file = |name: &str, text: &str| {
        let p = tmp(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let big = file("beyond_f32.obj", "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n");
    let w_nan = file("w_nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0 nan\nf 1 2 3\n");
    for tool in ["render", "bake"] {
        bad(tool, &big, &[":3:", "finite", "f32"]);
        bad(tool, &w_nan, &[":3:", "finite"]);
    }
}

#[test]
fn the_summary_counts_triangles_skipped_as_invalid() {
    // A triangle with a vertex beyond Q16.16 (±32768) is skipped. Main's summary said only
    // "triangles in 2 / … / drawn 1", with no count and no warning.
    let obj = tmp("beyond_q16.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 40000 0\nv 1 40000 0\nf 1 2 3\nf 1 4 5\n",
    )
    .unwrap();
    let out = tmp("beyond_q16.png");
    let (code, stdout, stderr) = run(
        "render",
        &[
            "--obj",
            obj.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("drawn 1 / invalid 1 |"), "{stdout}");
    assert!(
        stderr.contains("1 triangle(s) skipped as invalid") && stderr.contains("Q16.16"),
        "{stderr}"
    );
    // In f64 the same triangle is valid: nothing skipped, no warning.
    let (code, stdout, stderr) = run(
        "render",
        &[
            "--obj",
            obj.to_str().unwrap(),
            "--number",
            "f64",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("/ invalid 0 |"), "{stdout}");
    assert!(!stderr.contains("skipped"), "{stderr}");
}

#[test]
fn edges_and_wireframes_render_and_their_flags_are_checked() {
    // A hidden-line wireframe of the torus (exact colours: RGB888): only the background and
    // the lines, in the model's colour.
    let png = tmp("wireframe.png");
    let _ = std::fs::remove_file(&png);
    let (code, stdout, stderr) = run(
        "render",
        &[
            "--shading",
            "wireframe",
            "--format",
            "rgb888",
            "--background",
            "10,20,30",
            "--out",
            png.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    let (_, _, rgb) = common::read_png(&png).expect("a PNG");
    let lines = rgb.chunks_exact(3).filter(|p| p == &[255, 160, 64]).count();
    let bg = rgb.chunks_exact(3).filter(|p| p == &[10, 20, 30]).count();
    assert_eq!(lines + bg, 240 * 240, "{stdout}");
    // Seen through, the hidden lines add to it.
    let through = tmp("wireframe_through.png");
    let (code, _, stderr) = run(
        "render",
        &[
            "--shading",
            "wireframe",
            "--see-through",
            "--format",
            "rgb888",
            "--background",
            "10,20,30",
            "--out",
            through.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    let (_, _, rgb2) = common::read_png(&through).expect("a PNG");
    let lines2 = rgb2
        .chunks_exact(3)
        .filter(|p| p == &[255, 160, 64])
        .count();
    assert!(lines2 > lines + lines / 4, "{lines2} vs {lines}");
    // Edges over the shaded model and over the shadow scene.
    for args in [
        &["--edges", "crease", "--crease-angle", "10"][..],
        &["--scene", "shadow", "--shadow", "none", "--edges", "all"][..],
        &[
            "--scene",
            "shadow",
            "--shading",
            "wireframe",
            "--see-through",
        ][..],
    ] {
        let out = tmp("edges.png");
        let _ = std::fs::remove_file(&out);
        let mut all = args.to_vec();
        all.extend(["--out", out.to_str().unwrap()]);
        let (code, _, stderr) = run("render", &all);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        assert!(out.exists(), "{args:?}");
    }
    bad_flags(
        &["--edges", "crease", "--crease-angle", "200"],
        &["--crease-angle must be in [0, 180] degrees, got 200"],
    );
    bad_flags(
        &["--edge-color", "1,2,3"],
        &["--edge-color", "need --edges"],
    );
    bad_flags(&["--see-through"], &["--see-through", "need --edges"]);
    bad_flags(
        &["--shading", "wireframe", "--edges", "none"],
        &["--shading wireframe draws edges"],
    );
    bad_flags(
        &["--edges", "all", "--pass-triangles", "100"],
        &["one layered frame"],
    );
}

#[test]
fn tone_mapping_flags_render_and_are_checked() {
    // Automatic exposure brings a dim and a bright sphere to about the same brightness.
    let mean = |intensity: &str| {
        let out = tmp(&format!("tone_{intensity}.png"));
        let (code, _, stderr) = run(
            "render",
            &[
                "--scene",
                "icosphere",
                "--format",
                "rgb888",
                "--tone",
                "filmic",
                "--exposure",
                "auto",
                "--light-intensity",
                intensity,
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert_eq!(code, 0, "{stderr}");
        let (_, _, rgb) = common::read_png(&out).expect("a PNG");
        let lit: Vec<f64> = rgb
            .chunks_exact(3)
            .filter(|p| p != &[0, 0, 0])
            .map(|p| (2.0 * p[0] as f64 + 5.0 * p[1] as f64 + p[2] as f64) / 8.0)
            .collect();
        lit.iter().sum::<f64>() / lit.len() as f64
    };
    let (dim, bright) = (mean("0.3"), mean("4"));
    assert!((dim - bright).abs() < 12.0, "{dim} vs {bright}");
    // The budget states the HDR range and refuses what overflows Q16.16.
    let (code, stdout, _) = run(
        "render",
        &["--light-intensity", "3", "--tone", "reinhard", "--budget"],
    );
    assert_eq!(code, 0);
    assert!(stdout.contains("HDR lighting: radiance up to"), "{stdout}");
    let (code, _, stderr) = run(
        "render",
        &[
            "--light-intensity",
            "16",
            "--exposure",
            "16",
            "--diffuse",
            "1",
            "--budget",
        ],
    );
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("overflows Q16.16"), "{stderr}");
    bad_flags(&["--exposure", "0"], &["--exposure", "above 0"]);
    bad_flags(&["--exposure", "bright"], &["auto"]);
    bad_flags(
        &["--light-intensity", "17"],
        &["--light-intensity must be in [0, 16], got 17"],
    );
    // Phong is tone-mapped per pixel.
    let (code, _, stderr) = run(
        "render",
        &[
            "--tone",
            "filmic",
            "--light-intensity",
            "2",
            "--shading",
            "phong",
            "--out",
            tmp("hdr_phong.png").to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    bad_flags(
        &["--scene", "shadow", "--tone", "filmic"],
        &["not --scene shadow"],
    );
}

#[test]
fn budget_measures_whether_a_scene_needs_depth() {
    let pick = |args: &[&str]| {
        let (code, stdout, stderr) = run("render", args);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        stdout
            .lines()
            .find(|l| l.contains("pick:") || l.contains("depth:"))
            .unwrap_or_else(|| panic!("{args:?}: no depth line in\n{stdout}"))
            .to_string()
    };
    let frames = ["--budget", "--frames", "6", "--spin", "60"];
    // One convex object: nothing overlaps after culling, any order does.
    let cube = pick(&[&["--scene", "cube"][..], &frames].concat());
    assert!(
        cube.contains("NoDepthRenderer with DrawOrder::Any"),
        "{cube}"
    );
    // The torus overlaps itself without interpenetrating: the painter's order draws it.
    let torus = pick(&[&["--scene", "torus"][..], &frames].concat());
    assert!(torus.contains("DrawOrder::FarToNear"), "{torus}");
    // The CSG part's pocket: triangles the painter's order cannot sort.
    let part = pick(&[&["--csg", "../tests/data/part.csg", "--fit"][..], &frames].concat());
    assert!(part.contains("the Z-buffer"), "{part}");
    // Phong needs the attribute stores, which a renderer without depth lines has not.
    let phong = pick(&[&["--scene", "icosphere", "--shading", "phong"][..], &frames].concat());
    assert!(
        phong.contains("Phong shading needs the attribute stores"),
        "{phong}"
    );
}

#[test]
fn depth_flag_draws_without_depth_lines() {
    let image = |depth: &str| {
        let out = tmp(&format!("depth_{depth}.png"));
        let (code, stdout, stderr) = run(
            "render",
            &[
                "--scene",
                "torus",
                "--rotate-x",
                "70",
                "--depth",
                depth,
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert_eq!(code, 0, "{stderr}");
        (common::read_png(&out).expect("a PNG").2, stdout)
    };
    let (z, zs) = image("zbuffer");
    let (p, ps) = image("painter");
    let (a, _) = image("any");
    // The torus seen from low: it overlaps itself, which the painter's order sorts out.
    assert_eq!(z, p, "painter's differs from the Z-buffer");
    let differ = z.chunks(3).zip(a.chunks(3)).filter(|(x, y)| x != y).count();
    assert!(
        differ > 500,
        "any order should show hidden faces: {differ} px"
    );
    // Without depth lines the renderer is one depth line (240 · 2 bytes) smaller.
    let ram = |s: &str| -> usize {
        let i = s.find("renderer RAM ").expect("RAM figure") + "renderer RAM ".len();
        s[i..].split(' ').next().unwrap().parse().unwrap()
    };
    assert_eq!(ram(&zs) - ram(&ps), 480);
    bad_flags(
        &["--depth", "any", "--shading", "phong"],
        &["without depth lines", "Phong"],
    );
    bad_flags(
        &["--depth", "painter", "--edges", "all"],
        &["edges are tested against the depth lines"],
    );
    bad_flags(&["--depth", "none"], &["zbuffer", "painter", "any"]);
}
