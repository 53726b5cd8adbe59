//! Texture mapping against an exact reference: a floor receding in perspective, textured with
//! an image whose every texel has its own colour (red = column, green = row, blue = 31), so
//! that each drawn pixel says which texel it shows. The reference casts the ray through the
//! pixel centre onto the floor in `f64` and finds the exact texture coordinate; the error of a
//! pixel is the distance, in texels, from that coordinate to the square of the texel drawn
//! (0 when it is inside). `cargo test --test textures -- --nocapture` prints the figures.

use crate::common;

use common::textures::{coded_texture, floor_error, floor_scene, TexError, FLOOR_VIEW};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{OverflowPolicy, Renderer, Texture, TextureMode, Wrap};

type Q = Fx<scanline3d::fixed::types::I16F16>;

fn measure<S: Scalar>(mode: TextureMode) -> TexError {
    let tex = coded_texture(Wrap::Repeat, Wrap::Repeat);
    floor_error::<S>(tex, mode)
}

#[test]
fn perspective_modes_are_within_their_bounds_and_affine_is_not() {
    for (name, m) in [
        ("Q16.16", measure::<Q> as fn(TextureMode) -> TexError),
        ("f32", measure::<f32>),
        ("f64", measure::<f64>),
    ] {
        let exact = m(TextureMode::PerPixel);
        let s16 = m(TextureMode::Subdivided16);
        let s8 = m(TextureMode::Subdivided8);
        let affine = m(TextureMode::Affine);
        println!(
            "{name}: per-pixel {exact}; subdivided 16 {s16}; subdivided 8 {s8}; affine {affine}"
        );
        for e in [&exact, &s16, &s8, &affine] {
            assert!(e.drawn > 5_000, "{name}: {e}");
            assert_eq!(e.foreign, 0, "{name}: pixels that are not texels: {e}");
        }
        // Exact perspective: only the snapping of the vertices to 1/16 px and the depth's
        // quantization stand between the drawn texel and the exact point.
        assert!(exact.worst < 0.1, "{name}: {exact}");
        assert!(s8.worst < 0.25 && s16.worst < 0.5, "{name}: {s8} / {s16}");
        assert!(s8.worst <= s16.worst + 0.01, "{name}");
        assert!(
            affine.worst > 2.0,
            "{name}: affine should be visibly wrong: {affine}"
        );
    }
}

#[test]
fn clipped_texture_coordinates_are_exact() {
    // The floor reaches behind the eye: the near plane cuts it, and the new vertices' texture
    // coordinates come from the clip (barycentric weights carried through it).
    for (name, e) in [
        (
            "Q16.16",
            common::textures::clipped_floor_error::<Q>
                as fn(&'static Texture, TextureMode) -> TexError,
        ),
        ("f32", common::textures::clipped_floor_error::<f32>),
        ("f64", common::textures::clipped_floor_error::<f64>),
    ] {
        let e = e(
            coded_texture(Wrap::Repeat, Wrap::Repeat),
            TextureMode::PerPixel,
        );
        println!("{name}, clipped floor, per pixel: {e}");
        assert!(e.drawn > 5_000 && e.foreign == 0, "{name}: {e}");
        assert!(e.worst < 0.1, "{name}: {e}");
    }
}

#[test]
fn colour_key_leaves_the_background_and_depth_alone() {
    // Every texel with an even column is see-through: those pixels keep the background.
    static TEXELS: std::sync::OnceLock<Vec<u16>> = std::sync::OnceLock::new();
    let texels = TEXELS.get_or_init(|| {
        (0..32 * 32)
            .map(|i| if (i % 32) % 2 == 0 { 0x07e0 } else { 0xf800 })
            .collect()
    });
    let tex: &'static Texture = Box::leak(Box::new(
        Texture::new(Box::leak(texels.clone().into_boxed_slice()), 32, 32).unwrap(),
    ));
    let frame = floor_scene::<f32>(tex, TextureMode::Subdivided16, Some(0x07e0));
    let (w, h) = FLOOR_VIEW;
    let mut red = 0;
    for y in 0..h {
        for x in 0..w {
            let c = frame.get(x, y);
            assert_ne!(c, Rgb565::GREEN, "keyed texel drawn at ({x}, {y})");
            red += (c == Rgb565::RED) as u32;
        }
    }
    assert!(red > 2_000, "{red}");
}

#[test]
fn clamp_and_repeat_differ_only_outside_the_unit_square() {
    let rep = floor_error::<Q>(
        coded_texture(Wrap::Repeat, Wrap::Repeat),
        TextureMode::PerPixel,
    );
    let clamp = floor_error::<Q>(
        coded_texture(Wrap::Clamp, Wrap::Clamp),
        TextureMode::PerPixel,
    );
    // The floor spans s in [0, 2) and t in [0, 4): clamped, everything past s = 1 or t = 1 is
    // the edge texel, which the reference (wrapping) calls wrong.
    assert!(rep.worst < 0.1, "{rep}");
    assert!(clamp.worst > 10.0, "{clamp}");
    assert_eq!(rep.drawn, clamp.drawn);
}

#[test]
fn textured_scene_without_attribute_stores_is_a_clear_error() {
    let tex = coded_texture(Wrap::Repeat, Wrap::Repeat);
    let err = common::textures::render_without_stores::<f32>(tex);
    assert!(
        matches!(
            err,
            Some(scanline3d::Error::AttributeStore { object: 0, .. })
        ),
        "{err:?}"
    );
}

#[test]
fn attribute_stores_cost_exactly_their_records() {
    // A renderer pays for the stores exactly their records, so one without them (XV = XA = 0,
    // the default) pays nothing (`ram_formula` itself is checked against `size_of` in the
    // library's tests).
    type Plain = Renderer<Q, Rgb565, 240, 240, 512, 466, 61>;
    type Stores = Renderer<Q, Rgb565, 240, 240, 512, 466, 61, 1, 512, 61>;
    assert_eq!(
        std::mem::size_of::<Stores>(),
        std::mem::size_of::<Plain>()
            + 512 * scanline3d::limits::VERTEX_EXTRA_BYTES
            + 61 * scanline3d::limits::ACTIVE_EXTRA_BYTES
    );
    assert_eq!(
        std::mem::align_of::<Plain>(),
        std::mem::align_of::<Stores>()
    );
}

/// The textured benchmark frame in every span mode and number type, against golden images
/// (looked at): the checkerboard floor crossing the near plane and the textured cube.
#[test]
fn textured_frames_match_their_golden_images() {
    use scanline3d_support::demo::Bench;
    fn one<S: Scalar>(b: Bench, ty: &str) {
        common::compare::check_bench_golden::<S>(b, ty);
    }
    for b in [Bench::Textured, Bench::TexturedAffine, Bench::TexturedExact] {
        one::<Q>(b, "I16F16");
        one::<f32>(b, "f32");
        one::<f64>(b, "f64");
    }
}

/// A textured floor with `XA` pool entries, under `policy`: the frame, its stats and its
/// shortfall.
fn floor_with_pool<const XA: usize>(
    policy: OverflowPolicy,
    shading: Shading,
) -> (
    common::Frame<Rgb565>,
    Result<scanline3d::Stats, scanline3d::Error<core::convert::Infallible>>,
    Option<scanline3d::Shortfall>,
) {
    let f = common::textures::floor::<f32>();
    let mesh = f.mesh();
    let tex = coded_texture(Wrap::Repeat, Wrap::Repeat);
    let objects = [Object {
        mesh,
        transform: Mat4::identity(),
        material: Material::matte([255; 3], 1.0, 0.0)
            .shading(shading)
            .textured(tex)
            .texture_mode(TextureMode::PerPixel),
    }];
    let scene = Scene::new(
        &objects,
        common::textures::floor_camera(),
        [Light::white([0.0, 1.0, 0.0])],
    );
    let mut r: Box<Renderer<f32, Rgb565, 160, 120, 64, 64, 16, 1, 64, XA>> = Box::default();
    r.set_overflow(policy);
    let mut frame = common::Frame::new(160, 120, Rgb565::BLACK);
    let res = r.render(&scene, &mut frame);
    (frame, res, r.shortfall())
}

#[test]
fn a_full_pool_leaves_triangles_out_and_counts_them() {
    // Both floor triangles are active on the same rows: one pool entry cannot hold them.
    let (full, ok, none) = floor_with_pool::<2>(OverflowPolicy::Error, Shading::Gouraud);
    assert!(ok.is_ok() && none.is_none());
    let (part, _, short) = floor_with_pool::<1>(OverflowPolicy::DrawWhatFits, Shading::Gouraud);
    let short = short.expect("a triangle was left out");
    // Under the default policy the frame is refused instead, before anything is drawn.
    let (_, err, _) = floor_with_pool::<1>(OverflowPolicy::Error, Shading::Gouraud);
    assert!(
        matches!(
            err,
            Err(scanline3d::Error::AttributeStore {
                active_needed: 2,
                active_capacity: 1,
                ..
            })
        ),
        "{err:?}"
    );
    assert!(short.skipped >= 1, "{short:?}");
    let lit = |f: &common::Frame<Rgb565>| f.px.iter().filter(|&&c| c != Rgb565::BLACK).count();
    assert!(lit(&part) < lit(&full) && lit(&part) > 0);
}

#[test]
fn flat_textured_triangles_are_the_same_unlit() {
    // Unlit (ambient 1, no diffuse), flat and Gouraud textured triangles show the same texels.
    let (g, _, _) = floor_with_pool::<4>(OverflowPolicy::Error, Shading::Gouraud);
    let (f, _, _) = floor_with_pool::<4>(OverflowPolicy::Error, Shading::Flat);
    assert_eq!(g.px, f.px);
    f.assert_each_written_once();
}

#[test]
fn seeking_a_row_gives_the_rows_of_the_whole_frame() {
    // The whole frame, then the same frame from row 100 on after a seek: the texture planes
    // are evaluated per row (no drift), the lighting within one step as for any triangle.
    let shape = scanline3d::TexturedShape::<Q, 24, 12>::cube(1.0).unwrap();
    let objects = [Object {
        mesh: shape.mesh(),
        transform: Mat4::rotate_y(Q::lit(0.5)),
        material: Material::matte([255; 3], Q::lit(0.3), Q::lit(0.7))
            .textured(&scanline3d_support::demo::CHECKER),
    }];
    let cam = Camera::look_at(
        [Q::lit(0.0), Q::lit(1.5), Q::lit(3.0)],
        [Q::ZERO; 3],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: Q::lit(0.9),
            near: Q::lit(0.1),
            far: Q::lit(10.0),
        },
    )
    .unwrap();
    let scene = Scene::new(&objects, cam, [Light::white([-Q::ONE, Q::ONE, Q::ONE])]);
    type R = Renderer<Q, Rgb565, 240, 240, 64, 64, 16, 1, 64, 16>;
    let mut a: Box<R> = Box::default();
    let mut full = common::Frame::new(240, 240, Rgb565::BLACK);
    a.render(&scene, &mut full).unwrap();
    let mut b: Box<R> = Box::default();
    let mut frame = b.prepare(&scene, scanline3d::FrameOptions::new()).unwrap();
    frame.seek_row(100);
    let mut tail = common::Frame::new(240, 240, Rgb565::BLACK);
    while frame.strip_to(&mut tail).unwrap().is_some() {}
    let mut worst = 0;
    for y in 100..240 {
        for x in 0..240 {
            let (p, q) = (full.get(x, y), tail.get(x, y));
            let d = (p.r() as i32 - q.r() as i32)
                .abs()
                .max((p.g() as i32 - q.g() as i32).abs())
                .max((p.b() as i32 - q.b() as i32).abs());
            worst = worst.max(d);
        }
    }
    assert!(worst <= 1, "{worst}");
    assert!(full.px.iter().filter(|&&c| c != Rgb565::BLACK).count() > 5000);
}

mod random {
    use super::*;
    use proptest::prelude::*;

    /// Random triangles (slivers and near-plane crossings included) with random texture
    /// coordinates and normals, textured in every mode or lit by Phong: no panic (debug
    /// builds check every overflow), every pixel written once.
    fn draw(tris: &[([f32; 3], [f32; 3], [f32; 3])], uv: &[[f32; 2]], mode: u8) {
        let mut pos = Vec::new();
        let mut idx = Vec::new();
        for (k, (a, b, c)) in tris.iter().enumerate() {
            pos.extend([*a, *b, *c]);
            let i = 3 * k as u16;
            idx.push([i, i + 1, i + 2]);
        }
        let uvs: Vec<[f32; 2]> = (0..pos.len()).map(|i| uv[i % uv.len()]).collect();
        let normals: Vec<[f32; 3]> = pos
            .iter()
            .map(|p| {
                let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt().max(1e-3);
                [p[0] / l, p[1] / l, p[2] / l]
            })
            .collect();
        let mesh = Mesh::new(&pos, &idx)
            .unwrap()
            .with_normals(&normals)
            .unwrap()
            .with_uvs(&uvs)
            .unwrap();
        let tex = coded_texture(Wrap::Repeat, Wrap::Clamp);
        let material = match mode {
            0 => Material::matte([255; 3], 0.3, 0.7).textured(tex),
            1 => Material::matte([255; 3], 0.3, 0.7)
                .textured(tex)
                .texture_mode(TextureMode::Affine),
            2 => Material::matte([255; 3], 0.3, 0.7)
                .textured(tex)
                .texture_mode(TextureMode::PerPixel)
                .color_key(0x001f),
            3 => Material::matte([200, 100, 50], 0.1, 0.8)
                .specular(0.9, 60)
                .phong(),
            _ => Material::matte([200, 100, 50], 0.1, 0.8)
                .specular(0.9, 60)
                .shading(Shading::FastPhong),
        };
        let objects = [Object {
            mesh,
            transform: Mat4::identity(),
            material,
        }];
        let cam = Camera::look_at(
            [0.0, 0.0, 2.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            Projection::Perspective {
                fov_y: 1.0,
                near: 0.05,
                far: 20.0,
            },
        )
        .unwrap();
        let scene = Scene::new(&objects, cam, [Light::white([-1.0, 1.0, 1.0])]);
        let mut r: Box<Renderer<f32, Rgb565, 48, 40, 256, 128, 64, 1, 256, 66>> = Box::default();
        let mut f = common::Frame::new(48, 40, Rgb565::BLACK);
        r.render(&scene, &mut f).unwrap();
        f.assert_each_written_once();
    }

    fn point() -> impl Strategy<Value = [f32; 3]> {
        [-3.0f32..3.0, -3.0f32..3.0, -4.0f32..2.5]
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
        #[test]
        fn random_textured_and_phong_triangles(
            tris in proptest::collection::vec((point(), point(), point()), 1..12),
            uv in proptest::collection::vec([-15.9f32..15.9, -15.9f32..15.9], 3..9),
            mode in 0u8..5,
        ) {
            draw(&tris, &uv, mode);
        }
    }
}

/// The reference rasterizer's approach (`tests/reference_raster.rs`) extended to texture
/// coordinates: random screen-space triangles with their vertices imposed on the subpixel
/// grid (a probe snaps them) and random texture coordinates, in an orthographic view (where
/// every span mode is exact: `1/w` is constant). At every drawn pixel whose centre is inside
/// the triangle, the texel must be the one the f64 barycentric interpolation of the vertex
/// coordinates at the centre falls in, except within 2⁻⁶ texel of a texel's edge.
mod reference {
    use super::*;
    use crate::common::Snap;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

    const SIZE: u32 = 64;
    const SEED: [u8; 32] = *b"scanline3d issue 23 texel refs 1";

    /// Mismatching texels over the drawn pixels inside the triangle, and those pixels.
    fn check(p: [[i32; 2]; 3], uv: [[f64; 2]; 3], mode: TextureMode) -> (u32, u32) {
        // Counter-clockwise on screen as the renderer's front (y down: negative area).
        let area = |p: &[[i32; 2]; 3]| {
            let [a, b, c] = p.map(|q| q.map(i64::from));
            (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        };
        let (mut p, mut uv) = (p, uv);
        if area(&p) > 0 {
            p.swap(1, 2);
            uv.swap(1, 2);
        }
        let det = area(&p);
        if det == 0 {
            return (0, 0);
        }
        let pos: Vec<[f32; 3]> = p
            .iter()
            .map(|q| common::at(SIZE, SIZE, q[0] as f64 / 16.0, q[1] as f64 / 16.0, 0.0))
            .collect();
        let uvs: Vec<[f32; 2]> = uv.iter().map(|t| t.map(|c| c as f32)).collect();
        let normals = [[0.0f32, 0.0, 1.0]; 3];
        let idx = [[0u16, 1, 2]];
        let mesh = Mesh::new(&pos, &idx)
            .and_then(|m| m.with_normals(&normals))
            .and_then(|m| m.with_uvs(&uvs))
            .unwrap();
        let objects = [Object {
            mesh,
            transform: Mat4::identity(),
            material: Material::matte([255; 3], 1.0, 0.0)
                .textured(coded_texture(Wrap::Repeat, Wrap::Repeat))
                .texture_mode(mode),
        }];
        let scene = Scene::new(
            &objects,
            common::screen_camera(SIZE),
            [Light::white([0.0, 0.0, 1.0])],
        );
        let mut r: Box<Renderer<f32, Rgb565, 64, 64, 8, 8, 8, 1, 8, 8>> = Box::default();
        let mut f = common::Frame::new(SIZE, SIZE, Rgb565::BLACK);
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().probe(&mut Snap(&p)),
            &mut f,
        )
        .unwrap();
        let n = common::textures::CODED as f64;
        let (mut bad, mut seen) = (0, 0);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let c = f.get(x, y);
                if c == Rgb565::BLACK {
                    continue;
                }
                // Barycentric weights of the centre (in subpixels), from exact integers.
                let (cx, cy) = (16 * x as i64 + 8, 16 * y as i64 + 8);
                let [a, b, d] = p.map(|q| q.map(i64::from));
                let w1 = (cx - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (cy - a[1]);
                let w2 = (b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1]);
                let (l1, l2) = (w1 as f64 / det as f64, w2 as f64 / det as f64);
                if l1 <= 0.0 || l2 <= 0.0 || l1 + l2 >= 1.0 {
                    continue; // on an edge (the coverage rule is tested elsewhere)
                }
                let at =
                    |k: usize| uv[0][k] + l1 * (uv[1][k] - uv[0][k]) + l2 * (uv[2][k] - uv[0][k]);
                let (u, v) = (at(0) * n, at(1) * n);
                let near_edge = |t: f64| (t - t.round()).abs() < 1.0 / 64.0;
                if near_edge(u) || near_edge(v) {
                    continue;
                }
                let raw = embedded_graphics::pixelcolor::raw::RawU16::from(c).into_inner();
                let (i, j) = ((raw >> 11) as i64, ((raw >> 5) & 63) as i64);
                let want = (
                    u.floor().rem_euclid(n) as i64,
                    v.floor().rem_euclid(n) as i64,
                );
                seen += 1;
                bad += u32::from((i, j) != want);
            }
        }
        (bad, seen)
    }

    #[test]
    fn texels_match_the_f64_interpolation_in_every_mode() {
        let coord = -16..(SIZE as i32 * 16 + 16);
        let tri = [
            [coord.clone(), coord.clone()],
            [coord.clone(), coord.clone()],
            [coord.clone(), coord],
        ];
        let t = || [-3.0f64..3.0, -3.0f64..3.0];
        let uv = [t(), t(), t()];
        let mut runner = TestRunner::new_with_rng(
            Config {
                cases: 200,
                ..Config::default()
            },
            TestRng::from_seed(RngAlgorithm::ChaCha, &SEED),
        );
        let total = std::cell::Cell::new([0u32; 3]);
        runner
            .run(&(tri, uv), |(p, uv)| {
                for (k, mode) in [
                    TextureMode::PerPixel,
                    TextureMode::Subdivided16,
                    TextureMode::Affine,
                ]
                .into_iter()
                .enumerate()
                {
                    let (bad, seen) = check(p, uv, mode);
                    let mut t = total.get();
                    t[k] += seen;
                    total.set(t);
                    prop_assert_eq!(bad, 0, "{:?}: {} of {} texels differ", mode, bad, seen);
                }
                Ok(())
            })
            .unwrap();
        let total = total.get();
        println!("texels checked per mode: {total:?}");
        assert!(total.iter().all(|&t| t > 20_000), "{total:?}");
    }
}
