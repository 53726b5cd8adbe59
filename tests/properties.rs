//! Property tests (proptest) over random meshes, cameras and lights.

use crate::common;

use common::{at, screen_camera, unlit, Frame};
use embedded_graphics::pixelcolor::Rgb565;
use proptest::prelude::*;
use scanline3d::color::TriangleId;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d_support::hash::NullTarget;

type Q = Fx<I16F16>;

/// Any f32, including NaN, infinities, huge and tiny values, weighted toward ordinary ones.
fn any_coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => -20.0f32..20.0,
        1 => proptest::num::f32::ANY,
        1 => prop_oneof![Just(0.0f32), Just(f32::NAN), Just(f32::INFINITY), Just(f32::MAX), Just(-1e-30)],
    ]
}

#[derive(Clone, Debug)]
struct World {
    pos: Vec<[f32; 3]>,
    nor: Vec<[f32; 3]>,
    idx: Vec<[u16; 3]>,
    eye: [f32; 3],
    target: [f32; 3],
    up: [f32; 3],
    fov: f32,
    near: f32,
    far: f32,
    light: [f32; 3],
    flat: bool,
}

fn world() -> impl Strategy<Value = World> {
    (1usize..24).prop_flat_map(|n| {
        (
            proptest::collection::vec([any_coord(), any_coord(), any_coord()], n),
            proptest::collection::vec([any_coord(), any_coord(), any_coord()], n),
            proptest::collection::vec(
                [
                    0u16..(n as u16 + 2),
                    0u16..(n as u16 + 2),
                    0u16..(n as u16 + 2),
                ],
                1..40,
            ),
            (
                [any_coord(), any_coord(), any_coord()],
                [any_coord(), any_coord(), any_coord()],
                [any_coord(), any_coord(), any_coord()],
            ),
            (0.001f32..3.1, 0.0001f32..10.0, 0.0f32..1000.0),
            [any_coord(), any_coord(), any_coord()],
            any::<bool>(),
        )
            .prop_map(
                |(pos, nor, idx, (eye, target, up), (fov, near, far_extra), light, flat)| World {
                    pos,
                    nor,
                    idx,
                    eye,
                    target,
                    up,
                    fov,
                    near,
                    far: near + far_extra + 0.001,
                    light,
                    flat,
                },
            )
    })
}

fn render_world<S: Scalar>(w: &World) {
    let v = |a: [f32; 3]| a.map(S::from_f32);
    let pos: Vec<[S; 3]> = w.pos.iter().map(|&p| v(p)).collect();
    let nor: Vec<[S; 3]> = w.nor.iter().map(|&p| v(p)).collect();
    let Ok(camera) = Camera::look_at(
        v(w.eye),
        v(w.target),
        v(w.up),
        Projection::Perspective {
            fov_y: S::from_f32(w.fov),
            near: S::from_f32(w.near),
            far: S::from_f32(w.far),
        },
    ) else {
        return; // a bad camera is an error, which is a defined result
    };
    let mut m = Material::matte([200, 100, 50], S::from_f64(0.2), S::from_f64(0.8));
    m.specular = S::from_f64(0.5);
    m.shininess = 8;
    m.shading = if w.flat {
        Shading::Flat
    } else {
        Shading::Gouraud
    };
    // Normals that are not valid numbers are refused when the mesh is built.
    let Ok(mesh) = Mesh::new(&pos, &w.idx).unwrap().with_normals(&nor) else {
        assert!(nor.iter().flatten().any(|c| !c.is_valid()));
        return;
    };
    let objects = [Object {
        mesh,
        transform: Mat4::rotate_y(S::from_f64(0.3)),
        material: m,
    }];
    let scene = Scene::new(&objects, camera, [Light::white(v(w.light))]);
    let mut r: Box<Renderer<S, Rgb565, 48, 40, 256, 256, 64>> = Box::default();
    let mut t = NullTarget::<Rgb565>::new(48, 40);
    // Ok or a named error; a panic fails the property.
    let _ = r.render(&scene, &mut t);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// No input — NaN, infinities, f32::MAX, out-of-range indices, degenerate cameras — makes
    /// the renderer panic, in any number type (debug builds check every overflow).
    #[test]
    fn never_panics(w in world()) {
        render_world::<Q>(&w);
        render_world::<f32>(&w);
        render_world::<f64>(&w);
    }
}

/// Random screen-space triangles at random depths, as objects in the given order.
fn ids_of<S: Scalar>(tris: &[([[f64; 2]; 3], [f64; 3])], test: DepthTest) -> Frame<TriangleId> {
    let pos: Vec<[[S; 3]; 3]> = tris
        .iter()
        .map(|(p, z)| [0, 1, 2].map(|k| at::<S>(64, 64, p[k][0], p[k][1], z[k])))
        .collect();
    static IDX: [[u16; 3]; 1] = [[0, 1, 2]];
    let objects: Vec<Object<S>> = pos
        .iter()
        .map(|p| Object {
            mesh: Mesh::new(p, &IDX).unwrap(),
            transform: Mat4::identity(),
            material: unlit([1, 1, 1], Shading::Flat),
        })
        .collect();
    let scene = Scene::new(
        &objects,
        screen_camera::<S>(64),
        [Light::white([S::ZERO, S::ZERO, S::ONE])],
    );
    let mut r: Box<Renderer<S, TriangleId, 64, 64, 256, 256, 64>> = Box::default();
    r.set_depth_test(test);
    let mut f = Frame::new(64, 64, TriangleId(0));
    r.render(&scene, &mut f).unwrap();
    f
}

fn tri_strategy() -> impl Strategy<Value = Vec<([[f64; 2]; 3], [f64; 3])>> {
    proptest::collection::vec(
        (
            [
                [-10.0f64..74.0, -10.0f64..74.0],
                [-10.0f64..74.0, -10.0f64..74.0],
                [-10.0f64..74.0, -10.0f64..74.0],
            ],
            [-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0],
        )
            .prop_map(|(p, z)| {
                // Front-facing.
                let area = (p[2][0] - p[0][0]) * (p[1][1] - p[0][1])
                    - (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]);
                if area >= 0.0 {
                    (p, z)
                } else {
                    ([p[0], p[2], p[1]], [z[0], z[2], z[1]])
                }
            }),
        2..12,
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// The image does not depend on triangle order, except at exact depth ties — the pixels
    /// where `Less` (first wins) and `LessEqual` (last wins) disagree.
    #[test]
    fn order_independent_except_at_ties(tris in tri_strategy()) {
        fn check<S: Scalar>(tris: &[([[f64; 2]; 3], [f64; 3])]) -> Result<(), TestCaseError> {
            let n = tris.len() as u32;
            let fwd = ids_of::<S>(tris, DepthTest::Less);
            let fwd_le = ids_of::<S>(tris, DepthTest::LessEqual);
            let rev: Vec<_> = tris.iter().rev().cloned().collect();
            let back = ids_of::<S>(&rev, DepthTest::Less);
            for (k, ((a, b), tie)) in fwd.px.iter().zip(back.px.iter()).zip(fwd_le.px.iter()).enumerate() {
                // Map the reversed order's ids back to the original triangles.
                let b = if b.0 == 0 { 0 } else { n + 1 - b.0 };
                let is_tie = fwd.px[k] != *tie;
                prop_assert!(a.0 == b || is_tie, "{}: pixel {k}: {} vs {} (no tie)", S::NAME, a.0, b);
            }
            Ok(())
        }
        check::<Q>(&tris)?;
        check::<f32>(&tris)?;
    }

    /// Fixed-point coverage (its own snapped geometry) differs from f64's only at pixels whose
    /// centre lies within 0.1 px of an edge of the exact triangles (snapping moves a vertex by
    /// at most 1/32 px per axis).
    #[test]
    fn fixed_coverage_differs_from_f64_only_near_edges(tris in tri_strategy()) {
        let q = ids_of::<Q>(&tris, DepthTest::Less);
        let f = ids_of::<f64>(&tris, DepthTest::Less);
        for y in 0..64u32 {
            for x in 0..64u32 {
                if (q.get(x, y).0 != 0) == (f.get(x, y).0 != 0) {
                    continue;
                }
                let c = [x as f64 + 0.5, y as f64 + 0.5];
                let near_edge = tris.iter().any(|(p, _)| {
                    (0..3).any(|k| {
                        let (a, b) = (p[k], p[(k + 1) % 3]);
                        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                        let len2 = dx * dx + dy * dy;
                        let t = if len2 == 0.0 { 0.0 } else { (((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / len2).clamp(0.0, 1.0) };
                        let (px, py) = (a[0] + t * dx - c[0], a[1] + t * dy - c[1]);
                        (px * px + py * py).sqrt() <= 0.1
                    })
                });
                prop_assert!(near_edge, "coverage differs at ({x}, {y}), more than 0.1 px from every edge");
            }
        }
    }
}

use crate::render_input;

/// Random meshes with slivers (a vertex near the line through two others) and strongly
/// different vertex colours, seen by a perspective camera; `(positions, indices, colours)`.
/// Positions, indices and vertex colours.
type ColouredMesh = (Vec<[f64; 3]>, Vec<[u16; 3]>, Vec<[u8; 3]>);

fn coloured_mesh() -> impl Strategy<Value = ColouredMesh> {
    let v = || [-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0];
    (1usize..8).prop_flat_map(move |n| {
        (
            proptest::collection::vec((v(), v(), 0.0f64..1.0, -1e-3f64..1e-3, any::<bool>()), n),
            proptest::collection::vec(any::<[u8; 3]>(), 3 * n),
        )
            .prop_map(|(tris, cols)| {
                let mut pos = Vec::new();
                for (a, b, t, e, sliver) in tris {
                    // The third vertex: on the segment a–b, off by e (a sliver), or anywhere.
                    let c = if sliver {
                        [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]) + e * (k as f64 + 1.0))
                    } else {
                        [0, 1, 2].map(|k| a[k] * t - b[k] * (1.0 - t) + e * 1e3)
                    };
                    pos.extend([a, b, c]);
                }
                let idx = (0..pos.len() as u16 / 3)
                    .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                    .collect();
                (pos, idx, cols)
            })
    })
}

fn colour_range_holds<S: Scalar>(
    pos: &[[f64; 3]],
    idx: &[[u16; 3]],
    cols: &[[u8; 3]],
    dither: bool,
) -> Result<usize, TestCaseError> {
    let camera = Camera::look_at(
        [S::from_f64(0.3), S::from_f64(0.2), S::from_f64(8.0)],
        [S::from_f64(0.0); 3],
        [S::from_f64(0.0), S::from_f64(1.0), S::from_f64(0.0)],
        Projection::Perspective {
            fov_y: S::from_f64(0.9),
            near: S::from_f64(0.5),
            far: S::from_f64(30.0),
        },
    )
    .unwrap();
    let p: Vec<[S; 3]> = pos.iter().map(|a| a.map(S::from_f64)).collect();
    // Both windings, so that back faces show too.
    let flipped: Vec<[u16; 3]> = idx.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let mut checked = 0;
    for idx in [idx, &flipped[..]] {
        checked += render_input::colour_range_violation(&p, idx, cols, camera, dither)
            .map_err(TestCaseError::fail)?;
    }
    Ok(checked)
}

/// Pixels the invariant property checked (summed over its cases), to show it is not vacuous.
static CHECKED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Issue #20's invariant: every pixel's colour lies within its triangle's vertex colours
    /// (per RGB565 channel, ±1 LSB), slivers included, in every number type, with and without
    /// dithering. (The fuzz target checks the same on its inputs.)
    #[test]
    fn colour_stays_within_the_vertex_colours((pos, idx, cols) in coloured_mesh(), dither in any::<bool>()) {
        let n = colour_range_holds::<Q>(&pos, &idx, &cols, dither)?
            + colour_range_holds::<f32>(&pos, &idx, &cols, dither)?
            + colour_range_holds::<f64>(&pos, &idx, &cols, dither)?;
        CHECKED.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    }
}

#[test]
fn the_colour_range_property_checks_pixels() {
    // Runs the property's cases itself when the harness runs this test first.
    colour_stays_within_the_vertex_colours();
    let n = CHECKED.load(std::sync::atomic::Ordering::Relaxed);
    assert!(n > 100_000, "only {n} pixels checked");
}
