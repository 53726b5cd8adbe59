//! CSG modelling on the host (tools/src/csg.rs): parser errors that name the line and the
//! problem, and meshes that are closed, wound counter-clockwise outward, of the right volume and
//! free of slivers.

use scanline3d_tools as common;
mod shared;

use common::csg::{check_closed, mesh_csg_text, min_angle, signed_volume, CsgMesh};
use std::f64::consts::PI;

const PART: &str = include_str!("../../tests/data/part.csg");

fn mesh(text: &str) -> CsgMesh {
    mesh_csg_text(text).unwrap_or_else(|e| panic!("{e}"))
}

/// Area of the regular n-gon inscribed in a circle of radius r (the meshed cylinder's section).
fn ngon(n: usize, r: f64) -> f64 {
    n as f64 / 2.0 * r * r * (2.0 * PI / n as f64).sin()
}

#[test]
fn malformed_trees_are_rejected_with_their_line_and_problem() {
    let cases: &[(&str, usize, &str)] = &[
        ("a = box 1 1\n", 1, "`box` takes 3 numbers, found 2"),
        ("\n# c\na = sphere x\n", 3, "`x` is not a number"),
        ("a = sphere 1\nb = union a c\n", 2, "`c` is not defined"),
        ("a = sphere 1\na = sphere 2\n", 2, "`a` is already defined"),
        ("a = torus 1 2\n", 1, "unknown operation `torus`"),
        ("a = box 1 1 -1\n", 1, "sizes above zero"),
        ("a = box 1 1 1 rotate w 30\n", 1, "`w` is not an axis"),
        ("a = box 1 1 1 scale 0\n", 1, "`scale` by zero"),
        (
            "a = box 1 1 1 translate 1 2\n",
            1,
            "`translate` takes 3 numbers",
        ),
        (
            "a = sphere 1\nb = difference a\n",
            2,
            "needs two or more names",
        ),
        ("segments 2\n", 1, "not in 3..=256"),
        ("box 1 1 1\n", 1, "expected `NAME = OPERATION"),
        ("# only a comment\n", 0, "no definitions"),
        (
            "a = box 1 1 1\nb = box 1 1 1 translate 5 0 0\nc = intersection a b\n",
            3,
            "is empty",
        ),
    ];
    for (text, line, words) in cases {
        let e = mesh_csg_text(text).expect_err(text);
        assert_eq!(e.line, *line, "{text:?}: {e}");
        assert!(e.message.contains(words), "{text:?}: {e}");
    }
}

#[test]
fn primitives_are_closed_outward_and_of_their_volume() {
    let n = 24;
    let cases = [
        ("a = box 2 3 4", 24.0),
        ("a = cylinder 0.5 2", ngon(n, 0.5) * 2.0),
        ("a = cone 0.5 3", ngon(n, 0.5) * 3.0 / 3.0),
        ("a = box 1 1 1 scale -1 2 1", 2.0),
    ];
    for (text, volume) in cases {
        let m = mesh(text);
        check_closed(&m).unwrap_or_else(|e| panic!("{text}: {e}"));
        let v = signed_volume(&m);
        assert!((v - volume).abs() < 1e-9, "{text}: {v} against {volume}");
    }
    // The latitude-longitude sphere lies inside the true one and approaches it.
    let m = mesh("segments 64\na = sphere 1");
    check_closed(&m).unwrap();
    let v = signed_volume(&m);
    assert!(v < 4.0 / 3.0 * PI && v > 0.98 * 4.0 / 3.0 * PI, "{v}");
}

#[test]
fn booleans_keep_flat_faces_exact() {
    // A prism drilled through a box: the volume removed is exactly the polygon's area × length.
    let m = mesh(
        "segments 12\nb = box 2 2 1\nd = cylinder 0.5 3 translate 0 0 -1.5\nr = difference b d\n",
    );
    check_closed(&m).unwrap();
    let v = signed_volume(&m);
    let want = 4.0 - ngon(12, 0.5);
    assert!((v - want).abs() < 1e-6, "{v} against {want}");
    // Union of two overlapping boxes and their intersection.
    let u = mesh("a = box 2 2 2\nb = box 2 2 2 translate 1 1 1\nc = union a b\n");
    check_closed(&u).unwrap();
    assert!((signed_volume(&u) - 15.0).abs() < 1e-6);
    let i = mesh("a = box 2 2 2\nb = box 2 2 2 translate 1 1 1\nc = intersection a b\n");
    check_closed(&i).unwrap();
    assert!((signed_volume(&i) - 1.0).abs() < 1e-6);
}

#[test]
fn the_example_part_is_closed_outward_of_its_volume_and_without_slivers() {
    let m = mesh(PART);
    check_closed(&m).unwrap();
    // Block 2 × 1.4 × 1, minus a half ball of radius 0.6, minus a hole of radius 0.2 through
    // 1.4: the meshed part is within 2 % of the smooth one (facets lie inside the round surfaces,
    // so the meshed holes are smaller and the part a little larger).
    let smooth = 2.8 - 2.0 / 3.0 * PI * 0.6f64.powi(3) - PI * 0.04 * 1.4;
    let v = signed_volume(&m);
    assert!(v > smooth && v < smooth * 1.02, "{v} against {smooth}");
    assert!(m.triangles.len() < 600, "{} triangles", m.triangles.len());
    let worst = m
        .triangles
        .iter()
        .map(|t| min_angle(&m.positions, *t))
        .fold(180.0, f64::min);
    let thin = m
        .triangles
        .iter()
        .filter(|t| min_angle(&m.positions, **t) < 10.0)
        .count();
    println!("{thin} triangles with an angle under 10°");
    println!(
        "{} triangles, {} vertices, smallest angle {worst:.2}°",
        m.triangles.len(),
        m.positions.len()
    );
    assert!(worst > MIN_ANGLE, "smallest angle {worst}°");
}

/// The smallest interior angle the example part may have, in degrees.
const MIN_ANGLE: f64 = 1.0;

fn tmp(name: &str) -> std::path::PathBuf {
    shared::tmp("csg", name)
}

fn run(tool: &str, args: &[&str]) -> (i32, String, String) {
    shared::run(tool, args)
}

#[test]
fn render_and_bake_take_a_csg_file() {
    let part = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/part.csg");
    let m = mesh(PART);
    let png = tmp("part.png");
    let (code, out, err) = run(
        "render",
        &["--csg", part, "--fit", "--out", png.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains(&format!("triangles in {}", m.triangles.len())),
        "{out}"
    );
    let (w, h, rgb) = common::read_png(&png).expect("a PNG");
    assert_eq!((w, h), (240, 240));
    let lit = rgb.chunks(3).filter(|p| p.iter().any(|c| *c > 0)).count();
    assert!(lit > 10_000, "{lit} lit pixels");

    let rs = tmp("part_mesh.rs");
    let (code, out, err) = run("bake", &["--csg", part, "--out", rs.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains(&format!("{} triangles", m.triangles.len())),
        "{out}"
    );
    let src = std::fs::read_to_string(&rs).unwrap();
    assert!(src.contains("from part.csg"), "{src}");
}

#[test]
fn the_tools_name_the_file_and_line_of_a_malformed_tree() {
    let bad = tmp("bad.csg");
    std::fs::write(&bad, "a = box 1 1 1\nb = difference a c\n").unwrap();
    let png = tmp("bad.png");
    for (tool, args) in [
        (
            "render",
            vec![
                "--csg",
                bad.to_str().unwrap(),
                "--out",
                png.to_str().unwrap(),
            ],
        ),
        (
            "bake",
            vec![
                "--csg",
                bad.to_str().unwrap(),
                "--out",
                tmp("bad.rs").to_str().unwrap(),
            ],
        ),
    ] {
        let (code, out, err) = run(tool, &args);
        assert_ne!(code, 0, "{tool}: {out}{err}");
        let text = format!("{out}{err}");
        assert!(
            text.contains("bad.csg: csg line 2: `c` is not defined"),
            "{tool}: {text}"
        );
    }
    assert!(!png.exists());
}

/// The smallest interior angle over a mesh, in degrees.
fn smallest_angle(m: &CsgMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| min_angle(&m.positions, *t))
        .fold(180.0, f64::min)
}

#[test]
fn planes_cut_boxes_exactly() {
    let cases = [
        // x + y + z ≤ 1.5 keeps the cube [-1, 1]³ less the corner simplex of side 1.5.
        ("b = box 2 2 2\np = plane 1 1 1 -1.5\nr = intersection b p\n", 8.0 - 0.5625),
        // The difference keeps that corner simplex.
        ("b = box 2 2 2\np = plane 1 1 1 -1.5\nr = difference b p\n", 0.5625),
        // z ≤ 0 turned about x by 90° is y ≥ 0, moved to y ≥ 0.5; the plane may come first.
        (
            "p = plane 0 0 1 0 rotate x 90 translate 0 0.5 0\nb = box 2 2 2\nr = intersection p b\n",
            2.0,
        ),
        // Scaling the plane by 2 moves x ≤ 0.25 to x ≤ 0.5.
        ("b = box 2 2 2\np = plane 4 0 0 -1 scale 2\nr = intersection b p\n", 6.0),
        // A plane that holds the whole box changes nothing.
        ("b = box 2 2 2\np = plane 1 0 0 -5\nr = intersection b p\n", 8.0),
    ];
    for (text, volume) in cases {
        let m = mesh(text);
        check_closed(&m).unwrap_or_else(|e| panic!("{text}: {e}"));
        let v = signed_volume(&m);
        assert!((v - volume).abs() < 1e-6, "{text}: {v} against {volume}");
        let worst = smallest_angle(&m);
        println!(
            "{text:?}: {} triangles, smallest angle {worst:.2}°",
            m.triangles.len()
        );
        assert!(worst > 10.0, "{text}: smallest angle {worst}°");
    }
}

#[test]
fn quadrics_match_the_volume_of_their_solids() {
    // (text, exact volume of the smooth solid)
    let cases = [
        // The unit sphere written as a quadric.
        (
            "b = box 3 3 3\nq = quadric 1 1 1 0 0 0 0 0 0 -1\nr = intersection b q\n",
            4.0 / 3.0 * PI,
        ),
        // An ellipsoid x² + y²/0.49 + z²/0.25 ≤ 1, moved: 4/3 π · 1 · 0.7 · 0.5.
        (
            "b = box 3 3 3\nq = quadric 1 2.0408163265306123 4 0 0 0 0 0 0 -1 translate 0.2 0 -0.3\nr = intersection q b\n",
            4.0 / 3.0 * PI * 0.7 * 0.5,
        ),
        // pᵀ A p ≤ 1 with a cross term, A = [[1, .3, 0], [.3, 1, 0], [0, 0, 2]]:
        // 4/3 π / √det A, det A = 1.82; turned about z.
        (
            "b = box 3 3 3\nq = quadric 1 1 2 0.6 0 0 0 0 0 -1 rotate z 30\nr = intersection b q\n",
            4.0 / 3.0 * PI / 1.82f64.sqrt(),
        ),
        // A paraboloid bowl z ≥ x² + y² inside a box reaching z = 1 (the cylinder of radius 1.2
        // holds the bowl's rim): ∫ (1 − r²) 2πr dr = π/2.
        (
            "segments 32\nb = cylinder 1.2 1\nq = quadric 1 1 0 0 0 0 0 0 -1 0\nr = intersection b q\n",
            PI / 2.0,
        ),
        // The unit ball less the part of the ellipsoid above: difference with a half-space
        // x² + y² + z² − 1 ≤ 0 taken away from a box leaves the box less the ball.
        (
            "b = box 3 3 3\nq = quadric 1 1 1 0 0 0 0 0 0 -1\nr = difference b q\n",
            27.0 - 4.0 / 3.0 * PI,
        ),
    ];
    for (text, volume) in cases {
        let m = mesh(text);
        check_closed(&m).unwrap_or_else(|e| panic!("{text}: {e}"));
        let v = signed_volume(&m);
        let worst = smallest_angle(&m);
        println!(
            "{text:?}: volume {v:.5} against {volume:.5} ({:+.3} %), {} triangles, smallest angle {worst:.2}°",
            (v / volume - 1.0) * 100.0,
            m.triangles.len()
        );
        assert!(
            (v / volume - 1.0).abs() < QUADRIC_VOLUME_TOLERANCE,
            "{text}: {v} against {volume}"
        );
        // Measured smallest angles: 8.9° to 29° for most of these, 2.9° from surface nets alone
        // (the ellipsoid with a cross term, which no boolean cuts) and 0.54° where the booleans
        // cut the paraboloid along the cylinder's faces. A floor against degenerate output, not a
        // quality claim.
        assert!(worst > 0.25, "{text}: smallest angle {worst}°");
    }
}

/// The relative volume error allowed for a meshed quadric at the default 24 segments (24 grid
/// cells along the longest side of the bound): surface-net vertices average the edge crossings of
/// their cell and so sit a little inside a convex surface.
const QUADRIC_VOLUME_TOLERANCE: f64 = 0.025;

#[test]
fn malformed_half_spaces_are_rejected_with_their_line_and_problem() {
    let cases: &[(&str, usize, &str)] = &[
        ("a = plane 1 2 3\n", 1, "`plane` takes 4 numbers, found 3"),
        (
            "a = quadric 1 1 1 0 0 0 0 0 0\n",
            1,
            "`quadric` takes 10 numbers, found 9",
        ),
        ("\na = quadric 1 1 1 0 0 0 0 0 y 1\n", 2, "`y` is not a number"),
        ("a = plane 0 0 0 1\n", 1, "`plane` has no term in x, y or z"),
        (
            "a = quadric 0 0 0 0 0 0 0 0 0 -1\n",
            1,
            "`quadric` has no term in x, y or z",
        ),
        ("a = plane 1 0 0 0\n", 1, "`a` is an unbounded half-space"),
        (
            "a = plane 1 0 0 0\nb = box 1 1 1\nc = union a b\n",
            3,
            "`a` is an unbounded half-space and cannot be part of a `union`",
        ),
        (
            "a = plane 1 0 0 0\nb = box 1 1 1\nc = difference a b\n",
            3,
            "cannot be the first operand of a `difference`",
        ),
        (
            "a = plane 1 0 0 0\nb = quadric 1 1 1 0 0 0 0 0 0 -1\nc = intersection a b\n",
            3,
            "half-spaces alone is unbounded",
        ),
        (
            "a = plane 1 0 0 5\nb = box 1 1 1\nc = intersection a b\n",
            3,
            "`c` is empty",
        ),
        (
            "a = quadric 1 1 1 0 0 0 0 0 0 -1 translate 9 0 0\nb = box 1 1 1\nc = intersection a b\n",
            3,
            "`c` is empty",
        ),
        ("a = plane 1 0 0 0 rotate q 3\n", 1, "`q` is not an axis"),
    ];
    for (text, line, words) in cases {
        let e = mesh_csg_text(text).expect_err(text);
        assert_eq!(e.line, *line, "{text:?}: {e}");
        assert!(e.message.contains(words), "{text:?}: {e}");
    }
}

#[test]
fn hostile_half_space_numbers_give_a_mesh_or_a_line_numbered_error() {
    for hs in [
        "plane 1e300 1e300 1e300 0",
        "plane 1e-300 0 0 0",
        "plane 1 0 0 -1e300",
        "quadric 1e300 1e300 1e300 0 0 0 0 0 0 -1",
        "quadric 1e-300 1e-300 1e-300 0 0 0 0 0 0 -1e-300",
        "quadric -1e300 1e300 0 0 0 0 0 0 0 1e300",
        "quadric 1 1 -1 0 0 0 0 0 0 0",
        "quadric 1 1 1 0 0 0 0 0 0 -1 scale 1e-200",
    ] {
        let text = format!("b = box 2 2 2\nh = {hs}\nr = intersection b h\n");
        match mesh_csg_text(&text) {
            Ok(m) => {
                check_closed(&m).unwrap_or_else(|e| panic!("{hs}: {e}"));
                println!("{hs}: {} triangles", m.triangles.len());
            }
            Err(e) => {
                assert!(e.line == 2 || e.line == 3, "{hs}: {e}");
                println!("{hs}: {e}");
            }
        }
    }
}

/// `support/src/demo_csg_mesh.rs` (the `csg` benchmark scene's mesh) is exactly what `bake`
/// writes for `tests/data/part.csg` today, so the scene cannot drift from the CSG modeller (or
/// the modeller change the part unnoticed).
#[test]
fn the_baked_csg_part_is_what_bake_writes() {
    let root = shared::root();
    let out = tmp("demo_csg_mesh.rs");
    let part = shared::data("part.csg");
    let (code, _, err) = run(
        "bake",
        &[
            "--csg",
            part.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    let want = std::fs::read(root.join("support/src/demo_csg_mesh.rs")).unwrap();
    let got = std::fs::read(&out).unwrap();
    assert!(
        got == want,
        "support/src/demo_csg_mesh.rs differs from a fresh `cargo run --release -p scanline3d-tools --bin bake -- --csg \
         tests/data/part.csg --out support/src/demo_csg_mesh.rs`"
    );
}
