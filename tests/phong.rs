//! Phong shading against the model evaluated exactly: a coarse icosphere whose specular
//! highlight falls in the middle of a triangle (where Gouraud, which lights only the vertices,
//! loses it), against a ray-cast sphere lit per pixel in f64 with the same light, view
//! direction and material. `cargo test --test phong -- --nocapture` prints the figures.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{Error, TexturedShape};

type Q = Fx<scanline3d::fixed::types::I16F16>;

const SIZE: u32 = 160;
const EYE: f64 = 3.0;
const FOV: f64 = 0.8;
const COLOR: [u8; 3] = [60, 110, 210];
const AMBIENT: f64 = 0.1;
const DIFFUSE: f64 = 0.7;
const SPECULAR: f64 = 0.8;
const SHININESS: u8 = 40;

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The light direction that puts the highlight (the mirror direction of the view) at the
/// centre of the icosphere's face nearest the viewer: for a face centre direction `c` and the
/// view direction `v`, `L = 2(c·v)c − v`.
fn light_into_a_face() -> [f64; 3] {
    let s = Shape::<f64, 42, 80>::icosphere(1.0, 1).unwrap();
    let v = [0.0, 0.0, 1.0];
    let c = s
        .indices
        .iter()
        .map(|t| unit([0, 1, 2].map(|j| t.iter().map(|&i| s.positions[i as usize][j]).sum())))
        // A face a little off the centre, so that the highlight is not on the axis.
        .filter(|c| c[2] < 0.95)
        .max_by(|a, b| a[2].total_cmp(&b[2]))
        .unwrap();
    unit([0, 1, 2].map(|k| 2.0 * dot(c, v) * c[k] - v[k]))
}

fn render<S: Scalar>(shading: Shading, light: [f64; 3]) -> Frame<Rgb565> {
    let shape = Shape::<S, 42, 80>::icosphere(1.0, 1).unwrap();
    let objects = [Object {
        mesh: shape.mesh(),
        transform: Mat4::identity(),
        material: Material::matte(COLOR, S::from_f64(AMBIENT), S::from_f64(DIFFUSE))
            .specular(S::from_f64(SPECULAR), SHININESS)
            .shading(shading),
    }];
    let cam = Camera::look_at(
        [S::ZERO, S::ZERO, S::from_f64(EYE)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: S::from_f64(FOV),
            near: S::from_f64(0.1),
            far: S::from_f64(10.0),
        },
    )
    .unwrap();
    let scene = Scene::new(&objects, cam, [Light::white(light.map(S::from_f64))]);
    let mut r: Box<Renderer<S, Rgb565, 160, 160, 64, 96, 16, 1, 64, 18>> = Box::default();
    let mut f = Frame::new(SIZE, SIZE, Rgb565::BLACK);
    r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    f
}

/// The exact model on the unit sphere at the centre of pixel (x, y): 8-bit channels, or
/// `None` off the sphere. The view direction is the object origin's (as Phong's).
fn reference(x: u32, y: u32, light: [f64; 3]) -> Option<[f64; 3]> {
    let n = unit(common::ray_sphere(x, y, SIZE, FOV, EYE)?);
    let (l, v) = (light, [0.0, 0.0, 1.0]);
    let nl = dot(n, l);
    let rv = 2.0 * nl * dot(n, v) - dot(l, v);
    Some([0, 1, 2].map(|c| {
        let mut s = COLOR[c] as f64 * (AMBIENT + DIFFUSE * nl.max(0.0));
        if nl > 0.0 && rv > 0.0 {
            s += SPECULAR * 255.0 * rv.powi(SHININESS as i32);
        }
        s.clamp(0.0, 255.0)
    }))
}

/// Blue channel (5 bits) of a pixel, as 8-bit units.
fn blue8(c: Rgb565) -> f64 {
    c.b() as f64 * 255.0 / 31.0
}

/// Figures of one rendering against the reference, over the pixels the mesh covers at least
/// 3 px inside the sphere's outline: the brightest blue (the highlight), and the largest and
/// mean blue difference in 8-bit units.
fn figures(f: &Frame<Rgb565>, light: [f64; 3]) -> (f64, f64, f64, f64) {
    let (mut peak, mut ref_peak, mut worst, mut sum, mut n) = (0.0f64, 0.0f64, 0.0f64, 0.0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let inside = (-3i32..=3).all(|dy| {
                (-3i32..=3).all(|dx| {
                    reference((x as i32 + dx) as u32, (y as i32 + dy) as u32, light).is_some()
                })
            });
            // (The coarse mesh lies inside the sphere: its outline is a few pixels in.)
            if !inside || f.get(x, y) == Rgb565::BLACK {
                continue;
            }
            let want = reference(x, y, light).unwrap()[2];
            let got = blue8(f.get(x, y));
            peak = peak.max(got);
            ref_peak = ref_peak.max(want);
            worst = worst.max((got - want).abs());
            sum += (got - want).abs();
            n += 1;
        }
    }
    (peak, ref_peak, worst, sum / n as f64)
}

#[test]
fn a_highlight_inside_a_triangle_appears_under_phong_and_not_under_gouraud() {
    let light = light_into_a_face();
    let show = |name: &str, f: &(f64, f64, f64, f64)| {
        println!(
            "{name}: highlight {:.0} (exact {:.0}), blue error worst {:.1}, mean {:.2} (8-bit units)",
            f.0, f.1, f.2, f.3
        );
    };
    for ty in ["I16F16", "f32", "f64"] {
        let r = |s: Shading| match ty {
            "I16F16" => render::<Q>(s, light),
            "f32" => render::<f32>(s, light),
            _ => render::<f64>(s, light),
        };
        let (g, p, fp) = (
            figures(&r(Shading::Gouraud), light),
            figures(&r(Shading::Phong), light),
            figures(&r(Shading::FastPhong), light),
        );
        println!("{ty}:");
        show("  gouraud", &g);
        show("  phong", &p);
        show("  fast phong", &fp);
        // The exact highlight saturates blue; Phong reaches it, Gouraud stays far below.
        assert!(p.1 > 250.0, "{p:?}");
        assert!(p.0 > 240.0, "phong loses the highlight: {p:?}");
        assert!(fp.0 > 230.0, "fast phong loses the highlight: {fp:?}");
        assert!(
            g.0 < 200.0,
            "the highlight should vanish under gouraud: {g:?}"
        );
        // Phong is closer to the exact shading on average (the worst pixel, for every mode,
        // is where the coarse mesh's interpolated normals put the highlight a few pixels
        // away from the sphere's).
        assert!(p.3 < 0.7 * g.3 && p.2 < g.2, "{p:?} {g:?}");
        assert!(fp.3 < 0.7 * g.3, "{fp:?} {g:?}");
    }
}

/// An f32 camera on the +Z axis, 3 units out, looking at the origin.
fn camera3() -> Camera<f32> {
    Camera::look_at(
        [0.0, 0.0, 3.0],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        Projection::Perspective {
            fov_y: 0.8,
            near: 0.1,
            far: 10.0,
        },
    )
    .unwrap()
}

#[test]
fn without_a_specular_term_phong_is_gouraud_on_a_flat_quad() {
    // Every normal the same: Gouraud's vertex colours and Phong's per-pixel colour are the
    // same lighting (rounded differently: within one RGB565 step).
    let quad = [
        [-1.0f32, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    let n = unit([0.3, 0.2, 1.0]);
    let normals = [n.map(|c| c as f32); 4];
    let idx = [[0u16, 1, 2], [0, 2, 3]];
    let draw = |s: Shading| {
        let mesh = Mesh::new(&quad, &idx)
            .unwrap()
            .with_normals(&normals)
            .unwrap();
        let objects = [Object {
            mesh,
            transform: Mat4::identity(),
            material: Material::matte([200, 150, 90], 0.2, 0.8).shading(s),
        }];
        let cam = camera3();
        let lights = [
            Light::white([-1.0, 1.0, 1.0]),
            Light {
                direction: [1.0, 0.0, 0.5],
                color: [255, 60, 0],
            },
        ];
        let scene = Scene::new(&objects, cam, lights);
        let mut r: Box<Renderer<f32, Rgb565, 64, 64, 8, 8, 8, 1, 8, 8>> = Box::default();
        let mut f = Frame::new(64, 64, Rgb565::BLACK);
        r.render(&scene, &mut f).unwrap();
        f
    };
    let (g, p) = (draw(Shading::Gouraud), draw(Shading::Phong));
    let (max, differing, _) = common::compare565(&g, &p, Rgb565::BLACK);
    assert!(max.iter().all(|&d| d <= 1), "{max:?} over {differing} px");
    assert!(g.px.iter().filter(|&&c| c != Rgb565::BLACK).count() > 1000);
}

#[test]
fn phong_needs_the_attribute_stores() {
    let shape = TexturedShape::<f32, 64, 96>::icosphere(1.0, 1).unwrap();
    let objects = [Object {
        mesh: shape.shape.mesh(),
        transform: Mat4::identity(),
        material: Material::matte([255; 3], 0.2, 0.8).phong(),
    }];
    let cam = camera3();
    let scene = Scene::new(&objects, cam, [Light::white([0.0, 0.0, 1.0])]);
    let mut plain: Box<Renderer<f32, Rgb565, 64, 64, 64, 96, 16>> = Box::default();
    let mut f = Frame::new(64, 64, Rgb565::BLACK);
    assert!(matches!(
        plain.render(&scene, &mut f),
        Err(Error::AttributeStore { object: 0, .. })
    ));
    // One pool entry is the lights', one the material's: one more is not enough for the
    // triangles of a row.
    let mut small: Box<Renderer<f32, Rgb565, 64, 64, 64, 96, 16, 1, 64, 3>> = Box::default();
    assert!(matches!(
        small.render(&scene, &mut f),
        Err(Error::AttributeStore { .. })
    ));
    let mut enough: Box<Renderer<f32, Rgb565, 64, 64, 64, 96, 16, 1, 64, 18>> = Box::default();
    let mut f = Frame::new(64, 64, Rgb565::BLACK);
    enough.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
}

/// The Phong benchmark frames in each variant and number type, against golden images
/// (looked at).
#[test]
fn phong_frames_match_their_golden_images() {
    use scanline3d_support::demo::Bench;
    fn one<S: Scalar>(b: Bench, ty: &str) {
        common::compare::check_bench_golden::<S>(b, ty);
    }
    for b in [
        Bench::Phong,
        Bench::PhongFast,
        Bench::PhongGouraud,
        Bench::Toon,
    ] {
        one::<Q>(b, "I16F16");
        one::<f32>(b, "f32");
        one::<f64>(b, "f64");
    }
}

/// The toon frame with the renderer's dithering on: its golden image (looked at), and the
/// dithering changes pixels within a tone only, by at most one RGB565 step a channel.
#[test]
fn toon_with_dithering_matches_its_golden_image() {
    use scanline3d_support::demo::{render_bench, Bench};
    let frame = |dither: bool| {
        let mut f = Frame::new(240, 240, Rgb565::BLACK);
        render_bench::<Q, Rgb565, _, _>(
            Bench::Toon,
            0.0,
            dither,
            &mut f,
            &mut common::compare::HostProbe::Plain,
        )
        .unwrap();
        f.assert_each_written_once();
        f
    };
    let (plain, dithered) = (frame(false), frame(true));
    common::check_golden("toon_dithered_I16F16", &dithered);
    let mut changed = 0;
    for (a, b) in plain.px.iter().zip(&dithered.px) {
        let d = [
            a.r().abs_diff(b.r()),
            a.g().abs_diff(b.g()),
            a.b().abs_diff(b.b()),
        ];
        assert!(d.iter().all(|&d| d <= 1), "{a:?} {b:?}");
        changed += usize::from(a != b);
    }
    assert!(changed > 1000, "dithering changed {changed} pixels");
}

/// The reference rasterizer's approach (`tests/reference_raster.rs`) extended to normals:
/// random screen-space triangles with their vertices imposed on the subpixel grid (a probe
/// snaps them) and random unit normals, lit per pixel by one directional light (diffuse
/// only). At every drawn pixel whose centre is inside the triangle, the colour must be, within
/// 3/4 of an RGB565 step (0.51 measured), `255·max(0, N̂·L)` for `N̂` the f64 barycentric interpolation of the
/// vertex normals at the centre, normalized.
mod reference {
    use super::*;
    use crate::common::Snap;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

    const SIZE: u32 = 64;
    const SEED: [u8; 32] = *b"scanline3d issue 23 normal refs1";
    const L: [f64; 3] = [0.36, 0.48, 0.8];

    /// The largest difference (RGB565 steps, red and green) over the drawn pixels inside the
    /// triangle, and those pixels.
    fn check(p: [[i32; 2]; 3], normals: [[f64; 3]; 3]) -> (f64, u32) {
        check_shading(p, normals, None).0
    }

    /// [`check`] for Phong (`bands` `None`) or toon shading in `bands` tones, whose reference
    /// is `255·⌈N̂·L·bands⌉/bands`; returns also the pixels left out because `N̂·L·bands` is
    /// within 0.002 of a whole number (a band's edge, where the Q1.14 normal may fall either
    /// side).
    fn check_shading(
        p: [[i32; 2]; 3],
        normals: [[f64; 3]; 3],
        bands: Option<u8>,
    ) -> ((f64, u32), u32) {
        let area = |p: &[[i32; 2]; 3]| {
            let [a, b, c] = p.map(|q| q.map(i64::from));
            (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        };
        let (mut p, mut ns) = (p, normals.map(unit));
        if area(&p) > 0 {
            p.swap(1, 2);
            ns.swap(1, 2);
        }
        let det = area(&p);
        if det == 0 {
            return ((0.0, 0), 0);
        }
        let pos: Vec<[f32; 3]> = p
            .iter()
            .map(|q| common::at(SIZE, SIZE, q[0] as f64 / 16.0, q[1] as f64 / 16.0, 0.0))
            .collect();
        let nf: Vec<[f32; 3]> = ns.iter().map(|n| n.map(|c| c as f32)).collect();
        let idx = [[0u16, 1, 2]];
        let mesh = Mesh::new(&pos, &idx)
            .and_then(|m| m.with_normals(&nf))
            .unwrap();
        let objects = [Object {
            mesh,
            transform: Mat4::identity(),
            material: Material::matte([255; 3], 0.0, 1.0).shading(match bands {
                None => Shading::Phong,
                Some(b) => Shading::Toon {
                    bands: core::num::NonZeroU8::new(b).unwrap(),
                },
            }),
        }];
        let scene = Scene::new(
            &objects,
            common::screen_camera(SIZE),
            [Light::white(L.map(|c| c as f32))],
        );
        let mut r: Box<Renderer<f32, Rgb565, 64, 64, 8, 8, 8, 1, 8, 8>> = Box::default();
        let mut f = Frame::new(SIZE, SIZE, Rgb565::BLACK);
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().probe(&mut Snap(&p)),
            &mut f,
        )
        .unwrap();
        let (mut worst, mut seen, mut edges) = (0.0f64, 0, 0);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let (cx, cy) = (16 * x as i64 + 8, 16 * y as i64 + 8);
                let [a, b, d] = p.map(|q| q.map(i64::from));
                let w1 = (cx - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (cy - a[1]);
                let w2 = (b[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (b[1] - a[1]);
                let (l1, l2) = (w1 as f64 / det as f64, w2 as f64 / det as f64);
                if l1 <= 0.0 || l2 <= 0.0 || l1 + l2 >= 1.0 {
                    continue;
                }
                let n = [0, 1, 2]
                    .map(|k| ns[0][k] + l1 * (ns[1][k] - ns[0][k]) + l2 * (ns[2][k] - ns[0][k]));
                if dot(n, n) < 1e-4 {
                    continue; // opposite normals cancel: no direction to compare
                }
                let d = dot(unit(n), L).max(0.0);
                let want = match bands {
                    None => 255.0 * d,
                    Some(b) => {
                        let t = d * b as f64;
                        if d > 0.0 && (t - t.round()).abs() < 0.002 * b as f64 {
                            edges += 1;
                            continue;
                        }
                        255.0 * t.ceil() / b as f64
                    }
                };
                let c = f.get(x, y);
                let e = (c.r() as f64 - want * 31.0 / 255.0)
                    .abs()
                    .max((c.g() as f64 - want * 63.0 / 255.0).abs());
                worst = worst.max(e);
                seen += 1;
            }
        }
        ((worst, seen), edges)
    }

    #[test]
    fn phong_colours_match_the_f64_normal_interpolation() {
        let coord = -16..(SIZE as i32 * 16 + 16);
        let tri = [
            [coord.clone(), coord.clone()],
            [coord.clone(), coord.clone()],
            [coord.clone(), coord],
        ];
        let n = || [-1.0f64..1.0, -1.0f64..1.0, 0.05f64..1.0];
        let mut runner = TestRunner::new_with_rng(
            Config {
                cases: 200,
                ..Config::default()
            },
            TestRng::from_seed(RngAlgorithm::ChaCha, &SEED),
        );
        let total = std::cell::Cell::new(0u32);
        let worst = std::cell::Cell::new(0.0f64);
        runner
            .run(&(tri, [n(), n(), n()]), |(p, ns)| {
                let (w, seen) = check(p, ns);
                total.set(total.get() + seen);
                worst.set(worst.get().max(w));
                // The 5/6-bit rounding (half a step) and a little more: Q1.14 normals.
                prop_assert!(w <= 0.75, "{} RGB565 steps off", w);
                Ok(())
            })
            .unwrap();
        println!(
            "Phong against the f64 normal interpolation: {} pixels, worst {:.2} RGB565 steps",
            total.get(),
            worst.get()
        );
        assert!(total.get() > 20_000, "{}", total.get());
    }

    /// Toon shading against the same reference, banded: every pixel off a band's edge has its
    /// band's colour (within the 5/6-bit rounding).
    #[test]
    fn toon_bands_match_the_f64_normal_interpolation() {
        let coord = -16..(SIZE as i32 * 16 + 16);
        let tri = [
            [coord.clone(), coord.clone()],
            [coord.clone(), coord.clone()],
            [coord.clone(), coord],
        ];
        let n = || [-1.0f64..1.0, -1.0f64..1.0, 0.05f64..1.0];
        let mut runner = TestRunner::new_with_rng(
            Config {
                cases: 120,
                ..Config::default()
            },
            TestRng::from_seed(RngAlgorithm::ChaCha, &SEED),
        );
        let (total, edges) = (std::cell::Cell::new(0u32), std::cell::Cell::new(0u32));
        runner
            .run(&(tri, [n(), n(), n()], 1u8..9), |(p, ns, bands)| {
                let ((w, seen), e) = check_shading(p, ns, Some(bands));
                total.set(total.get() + seen);
                edges.set(edges.get() + e);
                prop_assert!(w <= 0.75, "{bands} bands: {w} RGB565 steps off");
                Ok(())
            })
            .unwrap();
        println!(
            "toon against the f64 normal interpolation: {} pixels, {} at a band's edge left out",
            total.get(),
            edges.get()
        );
        assert!(total.get() > 10_000 && edges.get() < total.get() / 50);
    }
}
