//! The numerical hard cases where fixed-point renderers fail: each renders with the fixed-point
//! type and with f32, compares with the f64 twin (on the same snapped positions where coverage is
//! concerned) and states its bound in its name or message. Worst errors are printed
//! (`cargo test --release --test hard_cases -- --nocapture`).

use crate::common;

use common::compare::HostProbe;
use common::{screen_camera, unlit, Frame};
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{color::TriangleId, probe::Probe, Stats};
use scanline3d_support::demo::deg;

type Q = Fx<I16F16>;

/// Prints a measurement and, when `HARD_CASES_REPORT` names a file, appends it there
/// (`scripts/hard-cases` collects them into `target/hard-cases.txt`).
fn report(line: String) {
    use std::io::Write as _;
    println!("{line}");
    if let Ok(path) = std::env::var("HARD_CASES_REPORT") {
        let mut f = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        writeln!(f, "{line}").unwrap_or_else(|e| panic!("{path}: {e}"));
    }
}

const W: usize = 64;
const H: usize = 64;
type R<S, C> = Renderer<S, C, W, H, 256, 256, 64>;

/// A triangle in screen pixels (x right, y down) at world depth z, with a colour.
#[derive(Copy, Clone, Debug)]
struct Tri {
    p: [[f64; 2]; 3],
    z: [f64; 3],
    color: [u8; 3],
}

/// A front-facing triangle (its vertices reordered if needed) at depth 0.
fn tri(p: [[f64; 2]; 3], color: [u8; 3]) -> Tri {
    let [a, b, c] = p;
    let area = (c[0] - a[0]) * (b[1] - a[1]) - (b[0] - a[0]) * (c[1] - a[1]);
    let p = if area >= 0.0 { p } else { [a, c, b] };
    Tri {
        p,
        z: [0.0; 3],
        color,
    }
}

/// A triangle exactly as given (it may be culled).
fn raw(p: [[f64; 2]; 3], color: [u8; 3]) -> Tri {
    Tri {
        p,
        z: [0.0; 3],
        color,
    }
}

/// Renders screen-space triangles (each its own object, unlit flat colour, orthographic screen
/// camera) with number type `S` into a `W × H` frame; `probe` sees the snapped vertices.
fn draw<S: Scalar, C: TargetColor, P: Probe>(
    tris: &[Tri],
    test: DepthTest,
    probe: &mut P,
) -> (Frame<C>, Stats) {
    let pos: Vec<[[S; 3]; 3]> = tris
        .iter()
        .map(|t| {
            [0, 1, 2].map(|k| common::at::<S>(W as u32, H as u32, t.p[k][0], t.p[k][1], t.z[k]))
        })
        .collect();
    static IDX: [[u16; 3]; 1] = [[0, 1, 2]];
    let objects: Vec<Object<S>> = tris
        .iter()
        .zip(pos.iter())
        .map(|(t, p)| Object {
            mesh: Mesh::new(p, &IDX).unwrap(),
            transform: Mat4::identity(),
            material: unlit(t.color, Shading::Flat),
        })
        .collect();
    let scene = Scene::new(
        &objects,
        screen_camera::<S>(H as u32),
        [Light::white([S::ZERO, S::ZERO, S::ONE])],
    );
    let mut r: Box<R<S, C>> = Box::default();
    r.set_depth_test(test);
    let mut f = Frame::new(W as u32, H as u32, C::from_channels([0; 3]));
    let stats = r
        .render_with(&scene, scanline3d::FrameOptions::new().probe(probe), &mut f)
        .unwrap();
    f.assert_each_written_once();
    (f, stats)
}

/// Asserts that `S`'s triangle ids equal f64's rendered on `S`'s snapped positions.
fn assert_same_ids<S: Scalar>(
    ids: &Frame<TriangleId>,
    ref_ids: &Frame<TriangleId>,
    diverged: u32,
    what: &str,
) {
    assert_eq!(diverged, 0, "{what} {}: geometry diverged", S::NAME);
    let diff = ids
        .px
        .iter()
        .zip(ref_ids.px.iter())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(diff, 0, "{what} {}: coverage differs from f64 on the same snapped positions at {diff} pixels (bound 0)", S::NAME);
}

/// Coverage (triangle ids) of `S` and of f64 on `S`'s snapped positions: must be identical.
fn same_coverage_as_f64<S: Scalar>(tris: &[Tri], what: &str) -> (Frame<TriangleId>, Stats) {
    let mut rec = HostProbe::record();
    let (ids, stats) = draw::<S, TriangleId, _>(tris, DepthTest::Less, &mut rec);
    let mut rp = HostProbe::replay(rec.recorded());
    let (ref_ids, _) = draw::<f64, TriangleId, _>(tris, DepthTest::Less, &mut rp);
    assert_same_ids::<S>(&ids, &ref_ids, rp.diverged(), what);
    (ids, stats)
}

/// Exact integer reference for the top-left rule: is the centre of pixel (px, py) covered by
/// the triangle with snapped vertices `v` (subpixels, y down, any winding)?
fn reference_covers(v: [(i64, i64); 3], px: i64, py: i64) -> bool {
    let (cx, cy) = (16 * px + 8, 16 * py + 8);
    let area = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[2].0 - v[0].0) * (v[1].1 - v[0].1);
    if area == 0 {
        return false;
    }
    // Orient clockwise on a y-down screen (interior to the right of each edge a→b).
    let v = if area > 0 { v } else { [v[0], v[2], v[1]] };
    (0..3).all(|k| {
        let (a, b) = (v[k], v[(k + 1) % 3]);
        let e = (b.0 - a.0) * (cy - a.1) - (b.1 - a.1) * (cx - a.0);
        // Top edge: horizontal, interior below (going right); left edge: going up.
        let top = a.1 == b.1 && b.0 > a.0;
        let left = b.1 < a.1;
        e > 0 || (e == 0 && (top || left))
    })
}

fn snap(p: [f64; 2]) -> (i64, i64) {
    ((p[0] * 16.0).round() as i64, (p[1] * 16.0).round() as i64)
}

// ---------------------------------------------------------------- 1. fill rule

fn tiny_triangles_match_the_integer_reference<S: Scalar>() {
    // Four 3/16-px triangles (one per direction) around the centre of pixel (20, 20), each
    // shifted by −1, 0, +1 sixteenths in x and y: 36 cases, compared pixel by pixel.
    let c = [20.5, 20.5];
    let s = 3.0 / 16.0;
    let shapes: [[[f64; 2]; 3]; 4] = [
        [[-s, -s], [s, -s], [0.0, s]],
        [[-s, s], [0.0, -s], [s, s]],
        [[-s, -s], [s, 0.0], [-s, s]],
        [[s, -s], [s, s], [-s, 0.0]],
    ];
    let mut cases = 0;
    for shape in shapes {
        for dx in -1..=1 {
            for dy in -1..=1 {
                let p = shape.map(|q| {
                    [
                        c[0] + q[0] + dx as f64 / 16.0,
                        c[1] + q[1] + dy as f64 / 16.0,
                    ]
                });
                let t = tri(p, [255, 255, 255]);
                let (ids, _) = same_coverage_as_f64::<S>(&[t], "3/16-px triangle");
                let v = p.map(snap);
                for py in 15..26 {
                    for px in 15..26 {
                        let got = ids.get(px, py).0 != 0;
                        assert_eq!(
                            got,
                            reference_covers(v, px as i64, py as i64),
                            "{} case {cases}: pixel ({px}, {py})",
                            S::NAME
                        );
                    }
                }
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 36);
}

fn random_triangles_match_the_integer_reference<S: Scalar>() {
    // Deterministic pseudo-random triangles on the 1/16-px grid: coverage equals the exact
    // edge-function reference at every pixel (bound: 0 differences).
    let mut seed = 0x2545_f491_u32;
    let mut next = |m: u32| {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed % m
    };
    for case in 0..400 {
        // Half the cases on a half-pixel grid, where pixel centres fall exactly on edges and
        // horizontal edges on centre rows: the fill rule's boundary cases.
        let step = if case % 2 == 0 { 16.0 } else { 2.0 };
        let n = (60.0 * step) as u32;
        let p = [0; 3].map(|_| [next(n) as f64 / step + 2.0, next(n) as f64 / step + 2.0]);
        let (ids, _) = same_coverage_as_f64::<S>(&[raw(p, [9, 9, 9])], "random triangle");
        let v = p.map(snap);
        for py in 0..H {
            for px in 0..W {
                let got = ids.get(px as u32, py as u32).0 != 0;
                // Back faces are culled: the reference counts only front-facing ones.
                let area =
                    (v[2].0 - v[0].0) * (v[1].1 - v[0].1) - (v[1].0 - v[0].0) * (v[2].1 - v[0].1);
                let want = area > 0 && reference_covers(v, px as i64, py as i64);
                assert_eq!(
                    got,
                    want,
                    "{} case {case} {p:?}: pixel ({px}, {py})",
                    S::NAME
                );
            }
        }
    }
}

// ---------------------------------------------------------------- 2. slivers and degenerates

fn slivers_and_degenerates<S: Scalar>() {
    // 0.1 × 60 px sliver strictly between the centre columns 3.5 and 4.5: nothing.
    let t = tri([[3.7, 1.0], [3.8, 61.0], [3.7, 61.0]], [1, 2, 3]);
    let (ids, s) = same_coverage_as_f64::<S>(&[t], "0.1-px sliver");
    assert!(
        ids.px.iter().all(|i| i.0 == 0),
        "{}: a sliver between centres drew pixels",
        S::NAME
    );
    assert_eq!(s.pixels_written, 0);
    // A long vertical edge exactly on the centres of column 10 (x = 10.5): drawn as a left edge,
    // not as a right edge.
    let left = tri([[10.5, 1.0], [10.5, 61.0], [20.0, 31.0]], [5, 5, 5]);
    let right = tri([[10.5, 1.0], [1.0, 31.0], [10.5, 61.0]], [5, 5, 5]);
    for (t, as_left) in [(left, true), (right, false)] {
        let (ids, _) = same_coverage_as_f64::<S>(&[t], "edge on a centre column");
        for y in 2..60 {
            assert_eq!(
                ids.get(10, y).0 != 0,
                as_left,
                "{}: row {y}, left edge {as_left}",
                S::NAME
            );
        }
    }
    // Zero area after snapping (all three vertices within 1/32 px of one grid point, and a
    // collinear one): nothing drawn, counted as degenerate, no panic.
    for p in [
        [[5.01, 5.01], [5.02, 5.0], [5.0, 5.02]],
        [[1.0, 1.0], [30.0, 30.0], [60.0, 60.0]],
    ] {
        let (ids, s) = same_coverage_as_f64::<S>(&[tri(p, [7, 7, 7])], "zero-area triangle");
        assert!(ids.px.iter().all(|i| i.0 == 0));
        assert_eq!((s.degenerate, s.drawn), (1, 0), "{}: {s:?}", S::NAME);
    }
}

// ---------------------------------------------------------------- 3. facing

fn facing_is_decided_on_snapped_positions<S: Scalar>() {
    // Float area (front-facing orientation) is +0.001 px²; snapped, the middle vertex moves to
    // the other side: culled.
    let p = [[0.5, 0.5], [10.5, 0.53], [20.5, 0.5599]];
    let float_area =
        (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]) - (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]);
    assert!(float_area > 0.0);
    let (_, s) = draw::<S, Rgb565, _>(&[raw(p, [1, 1, 1])], DepthTest::Less, &mut HostProbe::Plain);
    assert_eq!((s.culled, s.drawn), (1, 0), "{}: {s:?}", S::NAME);
}

// ---------------------------------------------------------------- 4 & 5. range

fn far_off_screen_vertices<S: Scalar>(reach: f64) {
    // A triangle whose vertices lie `reach` px off-screen covers the whole screen: every pixel
    // drawn, once, as by f64 on the same geometry.
    let t = tri(
        [
            [-reach, -reach],
            [3.0 * reach, -reach],
            [-reach, 3.0 * reach],
        ],
        [200, 100, 50],
    );
    let (ids, s) = same_coverage_as_f64::<S>(&[t], "far off-screen vertices");
    assert!(
        ids.px.iter().all(|i| i.0 != 0),
        "{} reach {reach}: {s:?}",
        S::NAME
    );
    assert_eq!(s.fragments as usize, W * H);
}

fn rotated_quad_with_corners_off_screen<S: Scalar>() {
    for k in 0..15 {
        let a = deg::<f64>(k as f64 * 6.0 + 1.0);
        let (sn, cs) = (a.sin(), a.cos());
        let r = 80.0;
        let c = [W as f64 / 2.0, H as f64 / 2.0];
        let corner = |u: f64, v: f64| [c[0] + r * (u * cs - v * sn), c[1] + r * (u * sn + v * cs)];
        let q = [
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
        ];
        let tris = [
            tri([q[0], q[1], q[2]], [1, 0, 0]),
            tri([q[0], q[2], q[3]], [0, 1, 0]),
        ];
        let (ids, s) = same_coverage_as_f64::<S>(&tris, "rotated quad");
        assert!(
            ids.px.iter().all(|i| i.0 != 0),
            "{} angle {k}: gap",
            S::NAME
        );
        assert_eq!(
            s.fragments as usize,
            W * H,
            "{} angle {k}: a pixel drawn twice",
            S::NAME
        );
    }
}

macro_rules! both {
    ($($name:ident),*) => {$(
        mod $name {
            use super::*;
            #[test]
            fn fixed_i16f16() {
                super::$name::<Q>();
            }
            #[test]
            fn float_f32() {
                super::$name::<f32>();
            }
        }
    )*};
}

both!(
    tiny_triangles_match_the_integer_reference,
    random_triangles_match_the_integer_reference,
    slivers_and_degenerates,
    facing_is_decided_on_snapped_positions,
    rotated_quad_with_corners_off_screen
);

#[test]
fn vertices_1000_and_100000_px_off_screen_equal_the_reference() {
    for reach in [1000.0, 100_000.0] {
        far_off_screen_vertices::<f32>(reach);
    }
    // In the screen camera one world unit is one pixel, so Q16.16 (±32768) reaches 1000 px;
    // 100 000 px is tested with a camera of 2 world units per screen below.
    far_off_screen_vertices::<Q>(1000.0);
}

// ---------------------------------------------------------------- world-space helpers

/// Renders world-space triangles (one object, flat or Gouraud with the given per-vertex colours
/// through an unlit material) seen by `camera`, into a `W × H` frame.
#[allow(clippy::too_many_arguments)]
fn draw_world<S: Scalar, C: TargetColor, P: Probe>(
    pos: &[[f64; 3]],
    idx: &[[u16; 3]],
    camera: Camera<S>,
    color: [u8; 3],
    test: DepthTest,
    dither: bool,
    probe: &mut P,
) -> (Frame<C>, Stats) {
    let p: Vec<[S; 3]> = pos.iter().map(|v| v.map(S::from_f64)).collect();
    let n: Vec<[S; 3]> = pos.iter().map(|_| [S::ZERO, S::ZERO, S::ONE]).collect();
    let objects = [Object {
        mesh: Mesh::new(&p, idx).unwrap().with_normals(&n).unwrap(),
        transform: Mat4::identity(),
        material: unlit(color, Shading::Gouraud),
    }];
    let scene = Scene::new(&objects, camera, [Light::white([S::ZERO, S::ZERO, S::ONE])]);
    let mut r: Box<Renderer<S, C, W, H, 4096, 4096, 256>> = Box::default();
    r.set_depth_test(test);
    r.set_dither(dither);
    let mut f = Frame::new(W as u32, H as u32, C::from_channels([0; 3]));
    let stats = r
        .render_with(&scene, scanline3d::FrameOptions::new().probe(probe), &mut f)
        .unwrap();
    f.assert_each_written_once();
    (f, stats)
}

fn perspective<S: Scalar>(
    eye: [f64; 3],
    target: [f64; 3],
    fov_deg: f64,
    near: f64,
    far: f64,
) -> Camera<S> {
    Camera::look_at(
        eye.map(S::from_f64),
        target.map(S::from_f64),
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(fov_deg),
            near: S::from_f64(near),
            far: S::from_f64(far),
        },
    )
    .unwrap()
}

/// Coverage of `S` equals f64's on `S`'s snapped positions; returns both id frames' coverage
/// count and stats.
fn world_same_coverage<S: Scalar>(
    pos: &[[f64; 3]],
    idx: &[[u16; 3]],
    camera: impl Fn() -> (Camera<S>, Camera<f64>),
    what: &str,
) -> (Frame<TriangleId>, Stats) {
    let (cs, cf) = camera();
    let mut rec = HostProbe::record();
    let (ids, stats) =
        draw_world::<S, TriangleId, _>(pos, idx, cs, [255; 3], DepthTest::Less, false, &mut rec);
    let mut rp = HostProbe::replay(rec.recorded());
    let (ref_ids, _) =
        draw_world::<f64, TriangleId, _>(pos, idx, cf, [255; 3], DepthTest::Less, false, &mut rp);
    assert_same_ids::<S>(&ids, &ref_ids, rp.diverged(), what);
    (ids, stats)
}

// ---------------------------------------------------------------- 6. near plane

fn near_plane_cases<S: Scalar>() {
    let cam = || {
        (
            perspective::<S>([0.0; 3], [0.0, 0.0, -1.0], 60.0, 0.1, 100.0),
            perspective::<f64>([0.0; 3], [0.0, 0.0, -1.0], 60.0, 0.1, 100.0),
        )
    };
    let floor = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        vec![[a[0], -1.0, a[1]], [b[0], -1.0, b[1]], [c[0], -1.0, c[1]]]
    };
    let idx = [[0u16, 1, 2]];
    // (vertices as (x, z); the eye is at z = 0 looking down −z; front-facing seen from above.)
    let cases: [(&str, Vec<[f64; 3]>, bool); 5] = [
        (
            "one vertex with w < 0",
            floor([-5.0, -10.0], [0.0, 5.0], [5.0, -10.0]),
            true,
        ),
        (
            "two vertices behind the eye",
            floor([0.0, -10.0], [-5.0, 5.0], [5.0, 5.0]),
            true,
        ),
        (
            "all three behind",
            floor([0.0, 10.0], [-5.0, 5.0], [5.0, 5.0]),
            false,
        ),
        (
            "a vertex exactly at w = 0",
            floor([-5.0, -10.0], [0.0, 0.0], [5.0, -10.0]),
            true,
        ),
        (
            "a vertex exactly on the near plane",
            floor([-5.0, -10.0], [0.0, -0.1], [5.0, -10.0]),
            true,
        ),
    ];
    for (what, pos, visible) in cases {
        let (ids, s) = world_same_coverage::<S>(&pos, &idx, cam, what);
        let covered = ids.px.iter().filter(|i| i.0 != 0).count();
        assert_eq!(covered > 0, visible, "{} {what}: {s:?}", S::NAME);
        // Nothing above the horizon: a triangle divided by a negative w would be mirrored there.
        for y in 0..H / 2 {
            for x in 0..W {
                assert_eq!(
                    ids.get(x as u32, y as u32).0,
                    0,
                    "{} {what}: pixel ({x}, {y}) above the horizon",
                    S::NAME
                );
            }
        }
    }
}

// ---------------------------------------------------------------- 7. varying w

fn varying_w_grid_has_no_overdraw_and_no_gaps<S: Scalar>() {
    // A 12 × 12 grid that projects to a regular grid on screen while every vertex has its own
    // depth w in [0.1, 4]: the surface never folds, so it must cover its screen rectangle
    // exactly once.
    let n = 12usize;
    let mut pos = Vec::new();
    let mut seed = 12345u32;
    let f = 1.0 / (30f64.to_radians()).tan(); // 60° field of view
    for j in 0..=n {
        for i in 0..=n {
            seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12345);
            let w = 0.1 + 3.9 * ((seed >> 8) as f64 / (1u32 << 24) as f64);
            let (nx, ny) = (
                -0.8 + 1.6 * i as f64 / n as f64,
                0.8 - 1.6 * j as f64 / n as f64,
            );
            pos.push([nx * w / f, ny * w / f, -w]);
        }
    }
    let mut idx = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let v = |i: usize, j: usize| (j * (n + 1) + i) as u16;
            idx.push([v(i, j), v(i, j + 1), v(i + 1, j)]);
            idx.push([v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)]);
        }
    }
    let cam = || {
        (
            perspective::<S>([0.0; 3], [0.0, 0.0, -1.0], 60.0, 0.05, 10.0),
            perspective::<f64>([0.0; 3], [0.0, 0.0, -1.0], 60.0, 0.05, 10.0),
        )
    };
    let (ids, s) = world_same_coverage::<S>(&pos, &idx, cam, "varying w");
    let covered = ids.px.iter().filter(|i| i.0 != 0).count();
    assert_eq!(
        s.fragments as usize,
        covered,
        "{}: a pixel was drawn twice",
        S::NAME
    );
    // The grid spans NDC ±0.8, i.e. pixels 6.4 .. 57.6: columns and rows 6..=57 have their
    // centres inside; every one must be covered.
    for y in 7..57 {
        for x in 7..57 {
            assert_ne!(ids.get(x, y).0, 0, "{}: gap at ({x}, {y})", S::NAME);
        }
    }
}

both!(near_plane_cases, varying_w_grid_has_no_overdraw_and_no_gaps);

// ---------------------------------------------------------------- 8. Gouraud and colour

/// A lit material whose vertex colours follow the normals: red × max(0, n·(0, 0, 1)).
fn lit_red<S: Scalar>() -> Material<S> {
    Material {
        color: [255, 0, 0],
        ambient: S::ZERO,
        diffuse: S::ONE,
        specular: S::ZERO,
        shininess: 1,
        shading: Shading::Gouraud,
        texture: None,
        alpha: 255,
    }
}

/// Renders a screen-space mesh whose vertex `k` has brightness `b[k]` (normal tilted so that
/// n·l = b) into a `WW × HH` frame.
fn ramp_frame<S: Scalar, const WW: usize, const HH: usize>(
    p: &[[f64; 2]],
    b: &[f64],
    idx: &[[u16; 3]],
    dither: bool,
) -> Frame<Rgb565> {
    let pos: Vec<[S; 3]> = p
        .iter()
        .map(|q| common::at::<S>(WW as u32, HH as u32, q[0], q[1], 0.0))
        .collect();
    let nor: Vec<[S; 3]> = b
        .iter()
        .map(|&v| {
            [
                S::from_f64((1.0 - v * v).max(0.0).sqrt()),
                S::ZERO,
                S::from_f64(v),
            ]
        })
        .collect();
    let objects = [Object {
        mesh: Mesh::new(&pos, idx).unwrap().with_normals(&nor).unwrap(),
        transform: Mat4::identity(),
        material: lit_red::<S>(),
    }];
    let scene = Scene::new(
        &objects,
        screen_camera::<S>(HH as u32),
        [Light::white([S::ZERO, S::ZERO, S::ONE])],
    );
    let mut r: Box<Renderer<S, Rgb565, WW, HH, 16, 16, 8>> = Box::default();
    r.set_dither(dither);
    let mut f = Frame::new(WW as u32, HH as u32, Rgb565::BLACK);
    r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    f
}

fn gouraud_ramp_and_vertex_colours<S: Scalar>() {
    // A 320-px ramp from black to full red: monotonic along every row, within 1 LSB of the
    // exact linear ramp, ending at ≥ 30.
    let p = [[0.0, 0.0], [320.0, 0.0], [320.0, 8.0], [0.0, 8.0]];
    // Counter-clockwise as the viewer sees it (clockwise on the y-down screen).
    let idx = [[0u16, 2, 1], [0, 3, 2]];
    let f = ramp_frame::<S, 320, 8>(&p, &[0.0, 1.0, 1.0, 0.0], &idx, false);
    let mut worst = 0.0f64;
    for y in 0..8 {
        let mut last = 0;
        for x in 0..320 {
            let r = f.get(x, y).r();
            assert!(r >= last, "{}: ramp not monotonic at ({x}, {y})", S::NAME);
            last = r;
            let exact = 31.0 * (x as f64 + 0.5) / 320.0;
            worst = worst.max((r as f64 - exact).abs());
        }
        assert!(last >= 30, "{}: ramp ends at {last}", S::NAME);
    }
    report(format!(
        "{}: 320-px ramp worst deviation {worst:.3} LSB (bound 1)",
        S::NAME
    ));
    assert!(worst <= 1.0, "{}: ramp deviates {worst} LSB", S::NAME);

    // A pixel centre exactly on a vertex gets that vertex's colour (the top-left vertex of a
    // triangle is on its top and left edges, so its pixel is covered).
    let p = [[10.5, 10.5], [10.5, 40.5], [40.5, 10.5]];
    for b0 in [0.3, 0.55, 0.8, 1.0] {
        let f = ramp_frame::<S, 64, 64>(&p, &[b0, 0.1, 0.95], &[[0u16, 1, 2]], false);
        let want = ((255.0 * b0).round() * 31.0 / 255.0).round() as u8;
        assert_eq!(
            f.get(10, 10).r(),
            want,
            "{}: vertex colour for brightness {b0}",
            S::NAME
        );
    }
}

fn dithering_keeps_tile_means<S: Scalar>() {
    // A constant, non-representable red (100/255 → 12.157 in 5 bits): dithered, every 4 × 4
    // tile averages to it within 1/16 LSB; undithered it rounds to 12 everywhere.
    let p = [[0.0, 0.0], [64.0, 0.0], [64.0, 64.0], [0.0, 64.0]];
    let idx = [[0u16, 2, 1], [0, 3, 2]];
    let b = 100.0 / 255.0;
    let plain = ramp_frame::<S, 64, 64>(&p, &[b; 4], &idx, false);
    assert!(
        plain.px.iter().all(|c| c.r() == 12),
        "{}: undithered constant",
        S::NAME
    );
    let f = ramp_frame::<S, 64, 64>(&p, &[b; 4], &idx, true);
    let exact = (255.0 * b).round() * 31.0 / 255.0;
    let mut worst = 0.0f64;
    for ty in 0..16 {
        for tx in 0..16 {
            let mut sum = 0.0;
            for y in 0..4 {
                for x in 0..4 {
                    sum += f.get(4 * tx + x, 4 * ty + y).r() as f64;
                }
            }
            worst = worst.max((sum / 16.0 - exact).abs());
        }
    }
    report(format!(
        "{}: dithered 4×4 tile mean worst deviation {worst:.4} LSB (bound 1/16)",
        S::NAME
    ));
    assert!(worst <= 1.0 / 16.0, "{}: tile mean off by {worst}", S::NAME);
}

// ---------------------------------------------------------------- 9. depth

fn depth_repeatability_and_ordering<S: Scalar>() {
    let big = |z: f64, rotate: usize, color: [u8; 3]| {
        let mut t = tri([[-10.0, -10.0], [200.0, -5.0], [-5.0, 200.0]], color);
        t.z = [z, z + 0.5, z - 0.7];
        let (p, zz) = (t.p, t.z);
        for k in 0..3 {
            t.p[k] = p[(k + rotate) % 3];
            t.z[k] = zz[(k + rotate) % 3];
        }
        t
    };
    // The same triangle twice, the second with its vertices rotated. Drawn in both orders under
    // LessEqual every fragment of the later copy passes, so each copy's depth is ≤ the other's
    // at every pixel: the depths are equal everywhere, i.e. an EQUAL test would pass everywhere.
    for rotate in 0..3 {
        for swap in [false, true] {
            let (a, b) = (big(0.0, 0, [1, 1, 1]), big(0.0, rotate, [2, 2, 2]));
            let tris = if swap { [b, a] } else { [a, b] };
            let (_, s) = draw::<S, Rgb565, _>(&tris, DepthTest::LessEqual, &mut HostProbe::Plain);
            assert_eq!(
                s.pixels_written,
                s.fragments,
                "{} rotation {rotate} swapped {swap}: depth not repeatable (EQUAL would fail)",
                S::NAME
            );
            assert_eq!(s.fragments as usize, 2 * W * H);
        }
    }
    // And the Equal test itself, in floats: a triangle exactly at the far plane stores 65535,
    // equal to the cleared value, at every pixel. (In Q16.16 the orthographic depth row is
    // exact only to a few steps at the far plane; see `Projection::matrix`.)
    if S::NAME != "I16F16" {
        let mut at_far_plane = big(0.0, 1, [3, 3, 3]);
        at_far_plane.z = [-9.0; 3];
        let (_, s) = draw::<S, Rgb565, _>(&[at_far_plane], DepthTest::Equal, &mut HostProbe::Plain);
        assert_eq!(
            s.pixels_written as usize,
            W * H,
            "{}: Equal against the cleared far plane",
            S::NAME
        );
    }
    // Two planes 3 depth steps apart (the screen camera maps 18 world units to 65535 steps):
    // the nearer one wins at every pixel, in either drawing order.
    let step = 18.0 / 65535.0;
    for order in [false, true] {
        let near = big(3.0 * step, 0, [0, 255, 0]);
        let far = big(0.0, 0, [255, 0, 0]);
        let tris = if order { [near, far] } else { [far, near] };
        let (ids, _) = draw::<S, TriangleId, _>(&tris, DepthTest::Less, &mut HostProbe::Plain);
        let near_id = if order { 1 } else { 2 };
        assert!(
            ids.px.iter().all(|i| i.0 == near_id),
            "{}: planes 3 depth steps apart misordered",
            S::NAME
        );
    }
    // Depth at the planes: the screen camera's near plane is world z = 9, its far plane z = −9.
    // A triangle at the near plane beats one in the middle; one at the far plane (stored 65535,
    // clamped, not wrapped to 0) loses to it and still passes LessEqual against the cleared line.
    let mid = big(0.0, 0, [5, 5, 5]);
    let mut at_near = tri([[-10.0, -10.0], [200.0, -5.0], [-5.0, 200.0]], [6, 6, 6]);
    at_near.z = [9.0; 3];
    let mut at_far = at_near;
    at_far.z = [-9.0; 3];
    let (ids, s) =
        draw::<S, TriangleId, _>(&[mid, at_near], DepthTest::LessEqual, &mut HostProbe::Plain);
    assert!(
        ids.px.iter().all(|i| i.0 == 2),
        "{}: near-plane triangle lost: {s:?}",
        S::NAME
    );
    let (ids, _) =
        draw::<S, TriangleId, _>(&[mid, at_far], DepthTest::LessEqual, &mut HostProbe::Plain);
    assert!(
        ids.px.iter().all(|i| i.0 == 1),
        "{}: far-plane triangle won (depth wrapped?)",
        S::NAME
    );
    let (ids, _) = draw::<S, TriangleId, _>(&[at_far], DepthTest::LessEqual, &mut HostProbe::Plain);
    assert!(
        ids.px.iter().all(|i| i.0 == 1),
        "{}: far-plane triangle not drawn under LessEqual",
        S::NAME
    );
}

both!(
    gouraud_ramp_and_vertex_colours,
    dithering_keeps_tile_means,
    depth_repeatability_and_ordering
);

// ---------------------------------------------------------------- 4 (cont.). extreme range

#[test]
fn vertices_100000_px_off_screen_in_fixed_point_and_f32_max() {
    // Camera of 2 world units per screen height: 100 000 px off-screen is 3125 units, inside
    // Q16.16's range; on-screen pixels equal f64's on the same snapped geometry.
    fn big<S: Scalar>(reach_px: f64) -> (Frame<TriangleId>, Stats) {
        let u = 2.0 / H as f64; // world units per pixel
        let r = reach_px * u;
        let pos = [[-r, -r, 0.0], [3.0 * r, -r, 0.0], [-r, 3.0 * r, 0.0]];
        let cam = || {
            let make = |s: f64| Projection::Orthographic {
                height: s,
                near: 1.0,
                far: 19.0,
            };
            let f =
                Camera::look_at([0.0, 0.0, 10.0], [0.0; 3], [0.0, 1.0, 0.0], make(2.0)).unwrap();
            let q = Camera::look_at(
                [S::ZERO, S::ZERO, S::from_f64(10.0)],
                [S::ZERO; 3],
                [S::ZERO, S::ONE, S::ZERO],
                Projection::Orthographic {
                    height: S::from_f64(2.0),
                    near: S::ONE,
                    far: S::from_f64(19.0),
                },
            )
            .unwrap();
            (q, f)
        };
        world_same_coverage::<S>(&pos, &[[0, 1, 2]], cam, "100 000 px off-screen")
    }
    for reach in [1000.0, 100_000.0] {
        let (ids, s) = big::<Q>(reach);
        assert!(
            ids.px.iter().all(|i| i.0 != 0),
            "I16F16 reach {reach}: {s:?}"
        );
        let (ids, s) = big::<f32>(reach);
        assert!(ids.px.iter().all(|i| i.0 != 0), "f32 reach {reach}: {s:?}");
    }
    // The largest finite f32 as a coordinate: f32 renders it like f64 (the orthographic scale
    // keeps every product finite) — no wrap, no panic.
    let m = f32::MAX as f64;
    let t = tri([[-m, -m], [m, -m], [-m, m]], [1, 2, 3]);
    let (_, s) = draw::<f32, Rgb565, _>(&[t], DepthTest::Less, &mut HostProbe::Plain);
    let (_, s64) = draw::<f64, Rgb565, _>(&[t], DepthTest::Less, &mut HostProbe::Plain);
    assert_eq!(
        s.pixels_written, s64.pixels_written,
        "f32::MAX: {s:?} vs {s64:?}"
    );
    // Q16.16 cannot hold it: the input saturates (a defined result), never wraps or panics.
    let (_, sq) = draw::<Q, Rgb565, _>(&[t], DepthTest::Less, &mut HostProbe::Plain);
    assert!(sq.drawn + sq.invalid + sq.culled + sq.outside + sq.degenerate + sq.empty >= 1);
}

// ---------------------------------------------------------------- 10. extreme cameras

fn cube_world(scale: f64) -> (Vec<[f64; 3]>, Vec<[u16; 3]>) {
    let c = Shape::<f64, 24, 12>::cube(scale).unwrap();
    let rot = Mat4::<f64>::rotate_y(0.6).then(&Mat4::rotate_x(0.4));
    let pos = c.positions.iter().map(|p| {
        let q = rot.transform_point(*p);
        [q[0], q[1], q[2]]
    });
    (pos.collect(), c.indices.to_vec())
}

fn extreme_fields_of_view<S: Scalar>() {
    // 1°: a cube 120 units away fills the view. 170°: the frustum is so wide that a unit cube
    // is a few pixels unless it surrounds the eye, so a 10 × 10 wall 1 unit away is used.
    let wall = (
        vec![
            [-5.0, -5.0, -1.0],
            [5.0, -5.0, -1.0],
            [5.0, 5.0, -1.0],
            [-5.0, 5.0, -1.0],
        ],
        vec![[0u16, 1, 2], [0, 2, 3]],
    );
    for (fov, dist, (pos, idx)) in [(1.0, 120.0, cube_world(1.0)), (170.0, 0.0, wall)] {
        let target = [0.0, 0.0, dist - 1.0];
        let cam = || {
            (
                perspective::<S>([0.0, 0.0, dist], target, fov, 0.01, 1000.0),
                perspective::<f64>([0.0, 0.0, dist], target, fov, 0.01, 1000.0),
            )
        };
        let (ids, s) = world_same_coverage::<S>(&pos, &idx, cam, "extreme field of view");
        let covered = ids.px.iter().filter(|i| i.0 != 0).count();
        report(format!(
            "{} fov {fov}°: {covered} pixels covered, {s:?}",
            S::NAME
        ));
        assert!(covered > 500, "{} fov {fov}°: {covered} pixels", S::NAME);
    }
}

fn near_1e_minus_3_far_1e3<S: Scalar>() {
    // Hyperbolic 16-bit depth with near 1e-3 and far 1e3 (far/near 10⁶, just under the
    // camera's limit `MAX_DEPTH_RATIO` = 2²⁰; 1e4 is refused since issue #21): the world
    // distance one depth step spans at distance d is about d²/(near·65535), ≈ 1.5 units at
    // d = 10. A cube at 9..11 and a larger one at 17..23 (several steps apart) must be
    // ordered exactly as f64 orders them; surfaces closer than a step apart tie, which no
    // 16-bit depth buffer can resolve.
    let (near, far) = (1e-3, 1e3);
    for d in [1.0, 10.0, 100.0] {
        report(format!(
            "{}: near {near} far {far}: one depth step ≈ {:.3e} world units at distance {d}",
            S::NAME,
            d * d / (near * 65535.0)
        ));
    }
    let (a, ia) = cube_world(1.0);
    let mut pos: Vec<[f64; 3]> = a.iter().map(|p| [p[0], p[1], p[2] - 10.0]).collect();
    pos.extend(
        a.iter()
            .map(|p| [p[0] * 3.0, p[1] * 3.0, p[2] * 3.0 - 20.0]),
    );
    let mut idx = ia.clone();
    idx.extend(ia.iter().map(|t| t.map(|i| i + 24)));
    let cam = || {
        (
            perspective::<S>([0.0; 3], [0.0, 0.0, -1.0], 60.0, near, far),
            perspective::<f64>([0.0; 3], [0.0, 0.0, -1.0], 60.0, near, far),
        )
    };
    let (ids, _) = world_same_coverage::<S>(&pos, &idx, cam, "near 1e-3 far 1e3");
    // The centre pixel sees the nearer, smaller cube (its triangles come first: ids 1..=12).
    let centre = ids.get(W as u32 / 2, H as u32 / 2).0;
    assert!(
        (1..=12).contains(&centre),
        "{}: centre shows triangle {centre}",
        S::NAME
    );
}

fn scene_scales<S: Scalar>() {
    // The same cube and camera scaled together by s: the image must not change (compared with
    // f64 at scale 1). Q16.16 keeps this within a few silhouette pixels for 1e-2 ≤ s ≤ 1e3;
    // smaller scenes lose position precision (documented: use I12F20 below 1e-2 units).
    let reference = {
        let (pos, idx) = cube_world(1.0);
        draw_world::<f64, TriangleId, _>(
            &pos,
            &idx,
            perspective::<f64>([0.0, 0.0, 5.0], [0.0; 3], 45.0, 0.1, 10.0),
            [255; 3],
            DepthTest::Less,
            false,
            &mut HostProbe::Plain,
        )
        .0
    };
    let scales: &[f64] = if S::NAME == "I16F16" {
        &[1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3]
    } else {
        &[1e-3, 1e-2, 1.0, 1e2, 1e3]
    };
    for &s in scales {
        let (pos, idx) = cube_world(s);
        let cam = perspective::<S>([0.0, 0.0, 5.0 * s], [0.0; 3], 45.0, 0.1 * s, 10.0 * s);
        let (ids, _) = draw_world::<S, TriangleId, _>(
            &pos,
            &idx,
            cam,
            [255; 3],
            DepthTest::Less,
            false,
            &mut HostProbe::Plain,
        );
        let diff = ids
            .px
            .iter()
            .zip(reference.px.iter())
            .filter(|(a, b)| (a.0 != 0) != (b.0 != 0))
            .count();
        report(format!(
            "{} scale {s:e}: {diff} coverage differences against f64 at scale 1",
            S::NAME
        ));
        assert!(
            diff <= 12,
            "{} scale {s}: {diff} pixels differ (bound 12)",
            S::NAME
        );
    }
}

both!(
    extreme_fields_of_view,
    near_1e_minus_3_far_1e3,
    scene_scales
);

// ---------------------------------------------------------------- 11. long runs

fn long_run<S: Scalar>() {
    // 36 000 frames of 1° steps. The angle is kept as whole degrees and the model matrix built
    // fresh each frame (the library keeps no state between frames), so nothing drifts: the
    // model's radius stays within 1e-4, and frame k equals a fresh render at the same angle.
    let (pos, idx) = cube_world(1.0);
    let p: Vec<[S; 3]> = pos.iter().map(|v| v.map(S::from_f64)).collect();
    let n: Vec<[S; 3]> = pos.iter().map(|_| [S::ZERO, S::ZERO, S::ONE]).collect();
    let radius = (3.0f64).sqrt();
    let cam = perspective::<S>([0.0, 0.0, 5.0], [0.0; 3], 45.0, 0.1, 10.0);
    let mut long: Box<Renderer<S, Rgb565, 32, 32, 32, 16, 16>> = Box::default();
    let mut worst = 0.0f64;
    for k in 0..36_000u32 {
        let m = Mat4::<S>::rotate_y(deg::<S>((k % 360) as f64));
        for v in &p {
            let q = m.transform_point(*v);
            let r = (q[0].to_f64().powi(2) + q[1].to_f64().powi(2) + q[2].to_f64().powi(2)).sqrt();
            worst = worst.max((r - radius).abs() / radius);
        }
        let objects = [Object {
            mesh: Mesh::new(&p, &idx).unwrap().with_normals(&n).unwrap(),
            transform: m,
            material: unlit([200, 100, 50], Shading::Flat),
        }];
        let scene = Scene::new(&objects, cam, [Light::white([S::ZERO, S::ZERO, S::ONE])]);
        let mut h = scanline3d_support::hash::HashTarget::<Rgb565>::new(32, 32);
        long.render(&scene, &mut h).unwrap();
        if k % 997 == 0 || k == 35_999 {
            let mut fresh: Box<Renderer<S, Rgb565, 32, 32, 32, 16, 16>> = Box::default();
            let mut h2 = scanline3d_support::hash::HashTarget::<Rgb565>::new(32, 32);
            fresh.render(&scene, &mut h2).unwrap();
            assert_eq!(
                h.hash(),
                h2.hash(),
                "{} frame {k} differs from a fresh render",
                S::NAME
            );
        }
    }
    report(format!(
        "{}: 36 000 frames, worst relative radius error {worst:.2e} (bound 1e-4)",
        S::NAME
    ));
    assert!(worst <= 1e-4, "{}: radius drifted {worst}", S::NAME);
}

both!(long_run);

// ---------------------------------------------------------------- 12. normalization and 1/w

fn normalization_and_reciprocals<S: Scalar>() {
    let mut worst_norm = 0.0f64;
    for e in -8..=8 {
        for (a, b, c) in [(0.6, 0.0, -0.8), (0.3, 0.4, 0.5), (-1.0, 1.0, 0.2)] {
            let k = 2f64.powi(e);
            let v = [S::from_f64(a * k), S::from_f64(b * k), S::from_f64(c * k)];
            let exact = {
                let f = v.map(|x| x.to_f64());
                let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
                f.map(|x| x / l)
            };
            let got = scanline3d::math::normalize(v);
            for i in 0..3 {
                worst_norm = worst_norm.max((got[i].to_f64() - exact[i]).abs());
            }
        }
    }
    assert_eq!(scanline3d::math::normalize([S::ZERO; 3]), [S::ZERO; 3]);
    // 1/w over the type's range (for Q16.16 every power of two from 2^-16 to 2^14), through
    // the perspective divide: v/w for v = w·0.75 must come back as 0.75.
    let mut worst_recip = 0.0f64;
    let range = if S::NAME == "I16F16" {
        -16..=14
    } else {
        -30..=30
    };
    for e in range {
        for m in [1.0, 1.37, 1.9999] {
            let w = S::from_f64(2f64.powi(e) * m);
            if w <= S::ZERO {
                continue;
            }
            let v = S::from_f64(w.to_f64() * 0.75);
            let q = S::ndc(v, S::recip(w)) as f64 / 4294967296.0;
            let exact = v.to_f64() / w.to_f64();
            worst_recip = worst_recip.max((q - exact).abs() / exact.abs().max(1e-300));
        }
    }
    report(format!("{}: normalize worst error {worst_norm:.2e} (bound 2^-12 = 2.4e-4); v/w worst relative error {worst_recip:.2e}", S::NAME));
    assert!(
        worst_norm <= 2f64.powi(-12),
        "{}: normalize {worst_norm}",
        S::NAME
    );
    assert!(
        worst_recip <= 4e-9 || (S::NAME == "f32" && worst_recip <= 2e-7),
        "{}: 1/w {worst_recip}",
        S::NAME
    );
}

both!(normalization_and_reciprocals);

#[test]
fn reciprocal_of_the_doubled_area_over_its_full_range() {
    // Triangle setup divides once, by the doubled area in subpixels² (1 … 2^47 on screen, up
    // to 2^62 in the guard band): 1/a = m · 2^-e from one 32-bit division and a Newton step.
    let mut worst = 0.0f64;
    let mut a = 1u64;
    while a < 1 << 62 {
        for v in [a, a + 1, a / 2 * 3 + 7, a / 4 * 5 + 3] {
            let (m, e) = scanline3d::internals::recip_norm(v);
            let got = m as f64 * 2f64.powi(-(e as i32));
            worst = worst.max((got * v as f64 - 1.0).abs());
        }
        a = a * 3 + 1;
    }
    report(format!(
        "1/area over 1 … 2^62: worst relative error {worst:.2e} (bound 2^-28 = 3.7e-9)"
    ));
    assert!(
        worst < 2f64.powi(-28),
        "1/area worst relative error {worst}"
    );
}
