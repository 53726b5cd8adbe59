//! Shadow maps (issue #42): the map pass against an f64 ray cast of its casters, per map size
//! and number type, for a directional and a point light over the shadow benchmark's models (a
//! torus and a cube above a ground square).

use embedded_graphics::pixelcolor::Rgb565;
use scanline3d::errors::LayerError;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::shadow::{ShadowFilter, ShadowLight, ShadowMap, ShadowMapping};
use scanline3d_support::demo::SHADOW_LIGHT;
use scanline3d_support::host::raycast::{map_against_raycast, world_triangles, MapAccuracy};

type Q = Fx<I16F16>;

/// The ground (object 0), the torus (1) and the cube (2), placed as the shadow benchmark
/// places them.
fn with_models<S: Scalar, R>(f: impl FnOnce(&[Object<'_, S>]) -> R) -> R {
    let ground = Shape::<S, 4, 2>::plane(5.0, 5.0, 1, 1).unwrap();
    let torus = Shape::<S, 288, 576>::torus(0.7, 0.25, 24, 12).unwrap();
    let cube = Shape::<S, 24, 12>::cube(0.35).unwrap();
    let s = S::from_f64;
    let m = Material::matte([200, 200, 200], s(0.25), s(0.75));
    let deg = |d: f64| s(d.to_radians());
    let objects = [
        Object {
            mesh: ground.mesh(),
            transform: Mat4::identity(),
            material: m.flat(),
        },
        Object {
            mesh: torus.mesh(),
            transform: Mat4::rotate_x(deg(35.0)).then(&Mat4::translate([s(-0.4), s(1.2), s(-0.2)])),
            material: m,
        },
        Object {
            mesh: cube.mesh(),
            transform: Mat4::rotate_y(deg(30.0)).then(&Mat4::translate([s(0.55), s(0.5), s(0.7)])),
            material: m.flat(),
        },
    ];
    f(&objects)
}

/// The map of `N` texels a side of the torus and the cube, fitted to the ground, against the
/// ray cast.
fn accuracy<S: Scalar, const N: usize>(light: ShadowLight<S>) -> MapAccuracy {
    with_models::<S, _>(|objects| {
        let camera = Camera::look_at(
            [0.0, 3.8, 4.6].map(S::from_f64),
            [0.0, 0.3, 0.0].map(S::from_f64),
            [0.0, 1.0, 0.0].map(S::from_f64),
            Projection::Perspective {
                fov_y: S::from_f64(0.8),
                near: S::from_f64(0.5),
                far: S::from_f64(20.0),
            },
        )
        .unwrap();
        let scene = Scene::new(
            objects,
            camera,
            [Light::white(SHADOW_LIGHT.map(S::from_f64))],
        );
        let mapping = ShadowMapping::new(light, &[1, 2], &[0]);
        let mut renderer = Renderer::<S, Rgb565, 128, 128, 1024, 1024, 64, 8>::new();
        let mut map = Box::new(ShadowMap::<N>::new());
        renderer
            .shadow_map_pass(&scene, &mapping, &mut *map)
            .unwrap();
        let depth: Vec<u16> = map.depth().iter().flatten().copied().collect();
        let tris = world_triangles(objects, &[1, 2]);
        map_against_raycast(&depth, N, map.world_to_map().unwrap(), &tris)
    })
}

fn lights<S: Scalar>() -> [(&'static str, ShadowLight<S>); 2] {
    [
        (
            "directional",
            ShadowLight::Directional(SHADOW_LIGHT.map(S::from_f64)),
        ),
        (
            "point",
            ShadowLight::Point([-2.4, 3.5, 1.2].map(S::from_f64)),
        ),
    ]
}

fn check<S: Scalar>() {
    for (name, light) in lights::<S>() {
        let results = [
            (32, accuracy::<S, 32>(light)),
            (64, accuracy::<S, 64>(light)),
            (128, accuracy::<S, 128>(light)),
        ];
        for (n, a) in results {
            println!(
                "shadow map {n}x{n} {name} {}: {} of {} texels covered, coverage differs at {} ({} not at an edge), depth error max {:.2} mean {:.3} steps, beyond the snapping at {} depth-edge texels and {} others",
                S::NAME,
                a.covered,
                a.texels,
                a.coverage_mismatch,
                a.isolated_mismatch,
                a.max_depth_error,
                a.mean_depth_error,
                a.depth_edge,
                a.beyond_snapping
            );
            assert!(
                a.covered > a.texels / 50,
                "{name} {n}: the casters cover too little of the map"
            );
            assert_eq!(
                a.isolated_mismatch,
                0,
                "{name} {n} {}: a hole or spill in the map",
                S::NAME
            );
            // Only texels whose centre is within the snapping of an edge differ.
            assert!(
                a.coverage_mismatch * 50 <= a.covered,
                "{name} {n} {}: {} texels' coverage differs",
                S::NAME,
                a.coverage_mismatch
            );
            assert_eq!(
                a.beyond_snapping,
                0,
                "{name} {n} {}: depth beyond the snapping",
                S::NAME
            );
        }
    }
}

#[test]
fn map_against_raycast_f64() {
    check::<f64>();
}

#[test]
fn map_against_raycast_f32() {
    check::<f32>();
}

#[test]
fn map_against_raycast_i16f16() {
    check::<Q>();
}

/// The shadow benchmark's view of its models.
fn camera<S: Scalar>() -> Camera<S> {
    Camera::look_at(
        [0.0, 3.8, 4.6].map(S::from_f64),
        [0.0, 0.3, 0.0].map(S::from_f64),
        [0.0, 1.0, 0.0].map(S::from_f64),
        Projection::Perspective {
            fov_y: S::from_f64(0.8),
            near: S::from_f64(0.5),
            far: S::from_f64(20.0),
        },
    )
    .unwrap()
}

/// What a mapped frame of the models looks like against the ray cast.
#[derive(Debug)]
struct Lookup {
    /// Pixels whose eye ray meets a face turned toward the light.
    lit_facing: usize,
    /// Of those, pixels in shadow by the ray cast.
    in_shadow: usize,
    /// Pixels darkened by the map where the ray cast says lit, and the other way round.
    false_shadow: usize,
    missed_shadow: usize,
    /// Pixels of the torus that the map and the ray cast both put in shadow: its own inner
    /// ring, which only the map (of the planar, blob and volume methods, the volumes too) can
    /// shadow on a curved receiver.
    torus_shadowed: usize,
}

impl Lookup {
    fn mismatch(&self) -> f64 {
        (self.false_shadow + self.missed_shadow) as f64 / self.lit_facing as f64
    }
}

/// The models at 240 × 240 drawn plainly and with a map of `N` texels (every object receives,
/// the torus and the cube cast), compared pixel by pixel with an f64 ray cast: each pixel's
/// eye ray through its centre meets the nearest triangle of the scene; on a face turned
/// toward the light, a shadow ray toward the light meets a caster or not. A pixel the map
/// darkened differs between the two frames.
fn lookup_against_raycast<S: Scalar, const N: usize>(
    light: ShadowLight<S>,
    png: Option<&str>,
) -> Lookup {
    use scanline3d_support::host::raycast::{first_hit, invert};
    use scanline3d_support::host::Frame;
    with_models::<S, _>(|objects| {
        let cam = camera::<S>();
        let scene = Scene::new(objects, cam, [Light::white(SHADOW_LIGHT.map(S::from_f64))])
            .with_background([24, 28, 40]);
        let mapping = ShadowMapping::new(light, &[1, 2], &[]);
        let mut renderer =
            Box::new(Renderer::<S, Rgb565, 240, 240, 1024, 1024, 64, 8, 0, 64>::new());
        let mut map = Box::new(ShadowMap::<N>::new());
        let mut lit = Frame::new(240, 240, Rgb565::new(0, 0, 0));
        renderer.render(&scene, &mut lit).unwrap();
        let mut shadowed = Frame::new(240, 240, Rgb565::new(0, 0, 0));
        renderer
            .prepare(&scene, FrameOptions::new().shadow_map(&mapping, &mut *map))
            .unwrap()
            .draw_to(&mut shadowed)
            .unwrap();
        if let Some(name) = png {
            let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
            std::fs::write(
                dir.join(name),
                scanline3d_support::host::png_bytes(&shadowed),
            )
            .unwrap();
        }
        let all = world_triangles(objects, &[0, 1, 2]);
        let casters = world_triangles(objects, &[1, 2]);
        let f = |m: Mat4<S>| m.m.map(|r| r.map(|v| v.to_f64()));
        let (p, v) = (f(cam.projection.matrix(S::ONE)), f(cam.view));
        let clip: [[f64; 4]; 4] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..4).map(|k| p[i][k] * v[k][j]).sum())
        });
        let inv = invert(clip).unwrap();
        let unproject = |x: f64, y: f64, z: f64| {
            let h: [f64; 4] =
                std::array::from_fn(|r| inv[r][0] * x + inv[r][1] * y + inv[r][2] * z + inv[r][3]);
            [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
        };
        let (sub, dot) = (
            |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]],
            |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
        );
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let mut out = Lookup {
            lit_facing: 0,
            in_shadow: 0,
            false_shadow: 0,
            missed_shadow: 0,
            torus_shadowed: 0,
        };
        // Every other pixel each way (a quarter of the frame: the ray cast is the test's cost).
        for y in (0..240u32).step_by(2) {
            for x in (0..240u32).step_by(2) {
                let (nx, ny) = (
                    (x as f64 + 0.5) / 120.0 - 1.0,
                    1.0 - (y as f64 + 0.5) / 120.0,
                );
                let (a, b) = (unproject(nx, ny, 0.0), unproject(nx, ny, 1.0));
                let Some((t, i)) = first_hit(&all, a, b) else {
                    continue;
                };
                let hit: [f64; 3] = std::array::from_fn(|k| a[k] + (b[k] - a[k]) * t);
                let tri = all[i];
                let n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]));
                let to_light = match light {
                    ShadowLight::Directional(d) => d.map(|v| v.to_f64()),
                    ShadowLight::Point(q) => sub(q.map(|v| v.to_f64()), hit),
                };
                if dot(n, to_light) <= 0.0 {
                    continue;
                }
                out.lit_facing += 1;
                let len = dot(to_light, to_light).sqrt();
                let dir = to_light.map(|v| v / len);
                let start: [f64; 3] = std::array::from_fn(|k| hit[k] + dir[k] * 1e-6);
                let end: [f64; 3] = match light {
                    ShadowLight::Directional(_) => std::array::from_fn(|k| hit[k] + dir[k] * 100.0),
                    ShadowLight::Point(q) => q.map(|v| v.to_f64()),
                };
                let blocked = first_hit(&casters, start, end).is_some();
                let darkened = lit.get(x, y) != shadowed.get(x, y);
                out.in_shadow += blocked as usize;
                out.false_shadow += (darkened && !blocked) as usize;
                out.missed_shadow += (!darkened && blocked) as usize;
                // The ground's 2 triangles, then the torus's 576.
                out.torus_shadowed += (darkened && blocked && (2..578).contains(&i)) as usize;
            }
        }
        out
    })
}

fn check_lookup<S: Scalar>() {
    for (name, light) in lights::<S>() {
        let png = |n: usize| format!("shadow_map_{name}_{n}_{}.png", S::NAME);
        let results = [
            (32, lookup_against_raycast::<S, 32>(light, Some(&png(32)))),
            (64, lookup_against_raycast::<S, 64>(light, Some(&png(64)))),
            (
                128,
                lookup_against_raycast::<S, 128>(light, Some(&png(128))),
            ),
        ];
        for (n, r) in &results {
            println!(
                "shadow map lookup {n}x{n} {name} {}: {} lit-facing pixels (of a quarter of the frame), {} in shadow by the ray cast ({} on the torus itself); darkened but lit {}, lit but shadowed {}: {:.2} % differ",
                S::NAME,
                r.lit_facing,
                r.in_shadow,
                r.torus_shadowed,
                r.false_shadow,
                r.missed_shadow,
                100.0 * r.mismatch()
            );
            assert!(
                r.in_shadow * 20 > r.lit_facing,
                "{name} {n}: too little shadow to measure"
            );
            assert!(
                r.torus_shadowed > 20,
                "{name} {n}: the torus does not shadow itself"
            );
        }
        // A finer map errs less, and every size keeps the mismatch small.
        assert!(
            results[2].1.mismatch() <= results[0].1.mismatch(),
            "{name}: 128 worse than 32"
        );
        // Locked at about 1.5 times the first measured values (a quarter of the frame, f64:
        // directional 0.97 %, 0.31 %, 0.21 %; point 1.43 %, 0.66 %, 0.33 %).
        for (n, r) in &results {
            let limit = match (name, n) {
                ("directional", 32) => 0.015,
                ("directional", 64) => 0.005,
                ("directional", _) => 0.0035,
                (_, 32) => 0.022,
                (_, 64) => 0.01,
                _ => 0.005,
            };
            assert!(
                r.mismatch() <= limit,
                "{name} {n} {}: {:.2} % differ",
                S::NAME,
                100.0 * r.mismatch()
            );
        }
    }
}

#[test]
fn lookup_against_raycast_f64() {
    check_lookup::<f64>();
}

#[test]
fn lookup_against_raycast_f32() {
    check_lookup::<f32>();
}

#[test]
fn lookup_against_raycast_i16f16() {
    check_lookup::<Q>();
}

/// The models in I16F16 seen by the benchmark's camera under its light, and that light as a
/// shadow map's.
fn lit_models<R>(f: impl FnOnce(&Scene<'_, Q, 1>, ShadowLight<Q>) -> R) -> R {
    with_models::<Q, _>(|objects| {
        let scene = Scene::new(
            objects,
            camera(),
            [Light::white(SHADOW_LIGHT.map(Q::from_f64))],
        );
        f(
            &scene,
            ShadowLight::Directional(SHADOW_LIGHT.map(Q::from_f64)),
        )
    })
}

/// The models drawn plainly and with a 64-texel map into a `C` target; the two frames.
fn frames_in<C: scanline3d::TargetColor>(
    fill: C,
) -> (
    scanline3d_support::host::Frame<C>,
    scanline3d_support::host::Frame<C>,
) {
    frames_filtered(fill, ShadowFilter::Nearest)
}

/// The models drawn plainly and with a 64-texel map read through `filter` into a `C` target;
/// the two frames.
fn frames_filtered<C: scanline3d::TargetColor>(
    fill: C,
    filter: ShadowFilter,
) -> (
    scanline3d_support::host::Frame<C>,
    scanline3d_support::host::Frame<C>,
) {
    use scanline3d_support::host::Frame;
    lit_models(|scene, light| {
        let mapping = ShadowMapping::new(light, &[1, 2], &[]).with_filter(filter);
        let mut renderer = Box::new(Renderer::<Q, C, 240, 240, 2048, 1024, 64, 8, 0, 64>::new());
        let mut map = Box::new(ShadowMap::<64>::new());
        let mut lit = Frame::new(240, 240, fill);
        renderer.render(scene, &mut lit).unwrap();
        let mut shadowed = Frame::new(240, 240, fill);
        renderer
            .prepare(scene, FrameOptions::new().shadow_map(&mapping, &mut *map))
            .unwrap()
            .draw_to(&mut shadowed)
            .unwrap();
        shadowed.assert_each_written_once();
        (lit, shadowed)
    })
}

/// Every colour type that can blend is shadowed, each pixel darkened or left as the plain
/// frame has it; a triangle-id target records the plain frame's triangles.
#[test]
fn every_colour_type() {
    use embedded_graphics::pixelcolor::{BinaryColor, Gray8, Rgb888};
    fn differing<C: scanline3d::TargetColor + PartialEq>(fill: C) -> usize {
        let (lit, shadowed) = frames_in(fill);
        lit.px
            .iter()
            .zip(&shadowed.px)
            .filter(|(a, b)| a != b)
            .count()
    }
    let n565 = differing(Rgb565::new(0, 0, 0));
    let n888 = differing(Rgb888::new(0, 0, 0));
    let ngray = differing(Gray8::new(0));
    println!("shadowed pixels: Rgb565 {n565}, Rgb888 {n888}, Gray8 {ngray}");
    for n in [n565, n888, ngray] {
        assert!(n > 2000, "{n} pixels shadowed");
    }
    // A pixel's shadow does not depend on the colour type: within the blend's rounding.
    assert!(n565.abs_diff(n888) * 50 < n888 && ngray.abs_diff(n888) * 20 < n888);
    // BinaryColor: the blend toward black turns lit pixels off where the map shadows them.
    let (lit, shadowed) = frames_in(BinaryColor::Off);
    let on = |f: &scanline3d_support::host::Frame<BinaryColor>| {
        f.px.iter().filter(|&&c| c == BinaryColor::On).count()
    };
    assert!(
        on(&shadowed) < on(&lit),
        "{} of {} on",
        on(&shadowed),
        on(&lit)
    );
    // A triangle-id target records the triangles, none darkened: the plain frame's ids.
    let (lit, shadowed) = frames_in(scanline3d::color::TriangleId(0));
    assert!(lit.px == shadowed.px);
}

/// Percentage-closer filtering (2 × 2 and 3 × 3) against the nearest read: a filtered pixel
/// differs from the nearest one only near the nearest shadow's edges (the interiors are
/// equal), every filtered pixel lies between the lit and the fully shadowed colour, and the
/// edges take intermediate levels (more of them with 3 × 3 taps than with 2 × 2).
#[test]
fn pcf_softens_the_edges_only() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    let (lit, nearest) = frames_filtered(Rgb888::BLACK, ShadowFilter::Nearest);
    let ch = |c: Rgb888| [c.r(), c.g(), c.b()];
    let shadowed: Vec<bool> = lit
        .px
        .iter()
        .zip(&nearest.px)
        .map(|(a, b)| a != b)
        .collect();
    // Chebyshev distance of each pixel to the nearest read's shadow edge (a shadowed pixel
    // next to a lit one, on the same surface or not).
    let (w, h) = (240usize, 240usize);
    let mut dist = vec![usize::MAX; w * h];
    let mut queue = std::collections::VecDeque::new();
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let edge = shadowed[i]
                && [(0i32, 1i32), (1, 0), (0, -1), (-1, 0)]
                    .iter()
                    .any(|&(dx, dy)| {
                        let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                        (0..w as i32).contains(&nx)
                            && (0..h as i32).contains(&ny)
                            && !shadowed[ny as usize * w + nx as usize]
                    });
            if edge {
                dist[i] = 0;
                queue.push_back(i);
            }
        }
    }
    while let Some(i) = queue.pop_front() {
        let (x, y) = ((i % w) as i32, (i / w) as i32);
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (nx, ny) = (x + dx, y + dy);
                if (0..w as i32).contains(&nx) && (0..h as i32).contains(&ny) {
                    let j = ny as usize * w + nx as usize;
                    if dist[j] == usize::MAX {
                        dist[j] = dist[i] + 1;
                        queue.push_back(j);
                    }
                }
            }
        }
    }
    let mut soft = [0usize; 2];
    for (k, filter) in [ShadowFilter::Pcf2, ShadowFilter::Pcf3]
        .into_iter()
        .enumerate()
    {
        let (lit2, filtered) = frames_filtered(Rgb888::BLACK, filter);
        assert!(lit2.px == lit.px);
        let (mut differs, mut far, mut intermediate, mut out_of_range) = (0, 0, 0, 0);
        let mut farthest = 0;
        for i in 0..w * h {
            let (l, n, f) = (ch(lit.px[i]), ch(nearest.px[i]), ch(filtered.px[i]));
            // The shadow is black: a filtered pixel is no brighter than the lit one, and no
            // darker than the fully shadowed one (the nearest read's, where it shadows).
            if (0..3).any(|c| f[c] > l[c] || (shadowed[i] && f[c] < n[c])) {
                out_of_range += 1;
            }
            if f != n {
                differs += 1;
                farthest = farthest.max(dist[i]);
                // A 64-texel map's texel covers up to about 4 pixels of this frame; the taps
                // reach 1.5 texels.
                if dist[i] > 6 {
                    far += 1;
                }
                if f != l && !(shadowed[i] && f == n) {
                    intermediate += 1;
                }
            }
        }
        println!(
            "{filter:?}: {differs} pixels differ from the nearest read, at most {farthest} \
             pixels from its edges ({far} beyond 6); {intermediate} at an intermediate level; \
             {out_of_range} outside the lit..shadowed range"
        );
        assert_eq!(out_of_range, 0, "{filter:?}");
        assert!(differs > 300, "{filter:?}: {differs} pixels soft");
        assert_eq!(far, 0, "{filter:?}: {far} of {differs} beyond 6 pixels");
        assert!(
            intermediate * 2 > differs,
            "{filter:?}: {intermediate} of {differs}"
        );
        soft[k] = intermediate;
    }
    assert!(soft[1] > soft[0], "3 × 3 {} <= 2 × 2 {}", soft[1], soft[0]);
}

/// The models drawn with the light-view image of `N` texels (`image`) or the depth map, read
/// through `filter`, into an Rgb888 target, receivers `receivers` (empty: every opaque object;
/// an image leaves the casters out).
fn image_or_map<const N: usize>(
    image: bool,
    filter: ShadowFilter,
    receivers: &[usize],
) -> scanline3d_support::host::Frame<embedded_graphics::pixelcolor::Rgb888> {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    use scanline3d::shadow::ShadowImage;
    use scanline3d_support::host::Frame;
    lit_models(|scene, light| {
        let mapping = ShadowMapping::new(light, &[1, 2], receivers).with_filter(filter);
        let mut renderer =
            Box::new(Renderer::<Q, Rgb888, 240, 240, 2048, 1024, 64, 8, 0, 64>::new());
        let mut f = Frame::new(240, 240, Rgb888::BLACK);
        let frame = if image {
            let mut m = Box::new(ShadowImage::<N>::new());
            renderer
                .prepare(scene, FrameOptions::new().shadow_map(&mapping, &mut *m))
                .unwrap()
                .draw_to(&mut f)
        } else {
            let mut m = Box::new(ShadowMap::<N>::new());
            renderer
                .prepare(scene, FrameOptions::new().shadow_map(&mapping, &mut *m))
                .unwrap()
                .draw_to(&mut f)
        };
        frame.unwrap();
        f.assert_each_written_once();
        f
    })
}

/// The light-view image without depth (the seeds' first kind): it shadows the receivers that
/// are not casters only (no self-shadowing: the casters are left out of the receivers), and on
/// the ground, below both casters, it darkens the pixels the depth map darkens; pre-blurred
/// (`Pcf3`), it softens the same edges.
#[test]
fn image_shadows_the_ground_as_the_depth_map() {
    use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
    let plain = frames_filtered(Rgb888::BLACK, ShadowFilter::Nearest).0;
    let dark = |f: &scanline3d_support::host::Frame<Rgb888>| -> Vec<bool> {
        plain.px.iter().zip(&f.px).map(|(a, b)| a != b).collect()
    };
    let map_ground = dark(&image_or_map::<64>(false, ShadowFilter::Nearest, &[0]));
    let map_all = dark(&image_or_map::<64>(false, ShadowFilter::Nearest, &[]));
    let image_ground = dark(&image_or_map::<64>(true, ShadowFilter::Nearest, &[0]));
    let image_all = dark(&image_or_map::<64>(true, ShadowFilter::Nearest, &[]));
    let count = |v: &[bool]| v.iter().filter(|&&b| b).count();
    let differ = |a: &[bool], b: &[bool]| a.iter().zip(b).filter(|(x, y)| x != y).count();
    println!(
        "image 64: {} ground pixels shadowed, the depth map {} ({} differ); every receiver: \
         image {}, depth map {} (the models on themselves and each other)",
        count(&image_ground),
        count(&map_ground),
        differ(&image_ground, &map_ground),
        count(&image_all),
        count(&map_all)
    );
    assert!(count(&map_ground) > 2000);
    // The same texels, the same coverage: at most a few pixels apart where the depth map's
    // bias lets a texel's edge through.
    assert!(differ(&image_ground, &map_ground) * 100 <= count(&map_ground));
    // Every receiver but the casters: the ground alone, exactly.
    assert!(
        image_all == image_ground,
        "{}",
        differ(&image_all, &image_ground)
    );
    // The depth map shadows the models too (the torus its inner ring, the torus the cube).
    assert!(count(&map_all) > count(&map_ground) + 200);
    // Pre-blurred: only pixels near the hard image's edges change, to levels between.
    let blurred = image_or_map::<64>(true, ShadowFilter::Pcf3, &[]);
    let hard = image_or_map::<64>(true, ShadowFilter::Nearest, &[]);
    let changed = blurred
        .px
        .iter()
        .zip(&hard.px)
        .filter(|(a, b)| a != b)
        .count();
    let between = (0..240 * 240)
        .filter(|&i| {
            let c = |p: Rgb888| [p.r(), p.g(), p.b()];
            let (l, h, b) = (c(plain.px[i]), c(hard.px[i]), c(blurred.px[i]));
            b != l && b != h && (0..3).all(|k| b[k] <= l[k])
        })
        .count();
    println!(
        "image 64 pre-blurred 3 × 3: {changed} pixels changed, {between} between lit and shadowed"
    );
    assert!(
        changed > 200 && between * 2 > changed,
        "{changed} {between}"
    );
}

/// A cube over an icosphere: the map shadows the curved receiver, which the planar method
/// refuses (the sphere is not in a plane).
#[test]
fn cube_shadows_a_sphere() {
    use scanline3d::shadow::{Layering, PlanarShadow};
    use scanline3d::Layers;
    use scanline3d_support::host::Frame;
    let s = Q::from_f64;
    let sphere = Shape::<Q, 642, 1280>::icosphere(1.0, 3).unwrap();
    let cube = Shape::<Q, 24, 12>::cube(0.3).unwrap();
    let m = Material::matte([200, 200, 200], s(0.25), s(0.75));
    let objects = [
        Object {
            mesh: sphere.mesh(),
            transform: Mat4::identity(),
            material: m,
        },
        Object {
            mesh: cube.mesh(),
            transform: Mat4::translate([s(0.2), s(1.8), s(0.3)]),
            material: m.flat(),
        },
    ];
    let up = [0.3, 1.0, 0.2].map(s);
    let scene = Scene::new(&objects, camera(), [Light::white(up)]);
    let mut renderer = Box::new(Renderer::<Q, Rgb565, 240, 240, 2048, 2048, 96, 8, 0, 96>::new());
    let mut lit = Frame::new(240, 240, Rgb565::new(0, 0, 0));
    renderer.render(&scene, &mut lit).unwrap();
    let mapping = ShadowMapping::new(ShadowLight::Directional(up), &[1], &[0]);
    let mut map = Box::new(ShadowMap::<64>::new());
    let mut shadowed = Frame::new(240, 240, Rgb565::new(0, 0, 0));
    renderer
        .prepare(&scene, FrameOptions::new().shadow_map(&mapping, &mut *map))
        .unwrap()
        .draw_to(&mut shadowed)
        .unwrap();
    let darkened = lit
        .px
        .iter()
        .zip(&shadowed.px)
        .filter(|(a, b)| a != b)
        .count();
    println!("cube over icosphere: {darkened} pixels of the sphere shadowed");
    assert!(darkened > 500, "{darkened}");
    let planar = Layering::projected(
        &[0],
        &[1],
        PlanarShadow::new(
            [s(0.0), s(1.0), s(0.0), s(0.0)],
            ShadowLight::Directional(up),
            140,
        ),
    );
    let mut layers = Box::new(Layers::<240, 8, 96, 96>::new());
    let e = renderer
        .prepare(&scene, FrameOptions::new().layered(&planar, &mut layers))
        .err();
    assert_eq!(
        e,
        Some(scanline3d::Error::Layers(LayerError::OffPlane {
            object: 0
        }))
    );
}

/// What a mapped frame refuses, before drawing anything.
#[test]
fn mapped_frame_errors() {
    use scanline3d::Error;
    with_models::<f32, _>(|objects| {
        let scene = Scene::new(
            objects,
            camera(),
            [Light::white(SHADOW_LIGHT.map(|v| v as f32))],
        );
        let light = ShadowLight::Directional(SHADOW_LIGHT.map(|v| v as f32));
        let mapping = ShadowMapping::new(light, &[1, 2], &[]);
        let mut map = Box::new(ShadowMap::<64>::new());
        // No pool.
        let mut r = Box::new(Renderer::<f32, Rgb565, 240, 240, 1024, 1024, 64, 8>::new());
        let e = r
            .prepare(&scene, FrameOptions::new().shadow_map(&mapping, &mut *map))
            .err();
        assert!(
            matches!(
                e,
                Some(Error::AttributeStore {
                    object: 0,
                    active_capacity: 0,
                    ..
                })
            ),
            "{e:?}"
        );
        // No depth lines.
        let mut r = Box::new(Renderer::<f32, Rgb565, 240, 240, 1024, 1024, 64, 8, 0, 0, 0>::new());
        let e = r
            .prepare(&scene, FrameOptions::new().shadow_map(&mapping, &mut *map))
            .err();
        assert_eq!(e, Some(Error::NoDepthLines));
        let mut r = Box::new(Renderer::<f32, Rgb565, 240, 240, 1024, 1024, 64, 8, 0, 64>::new());
        // A map larger than the renderer.
        let mut big = Box::new(ShadowMap::<256>::new());
        let e = r
            .prepare(&scene, FrameOptions::new().shadow_map(&mapping, &mut *big))
            .err();
        assert_eq!(
            e,
            Some(Error::Layers(LayerError::MapLargerThanViewport {
                size: 256,
                width: 240,
                height: 240
            }))
        );
        // An object lit per pixel.
        let mut phong = objects.to_vec();
        phong[0].material.shading = Shading::Phong;
        let scene2 = Scene {
            objects: &phong,
            ..scene
        };
        let e = r
            .prepare(&scene2, FrameOptions::new().shadow_map(&mapping, &mut *map))
            .err();
        assert_eq!(e, Some(Error::Layers(LayerError::MapShading { object: 0 })));
        // An index that is not an object.
        let bad = ShadowMapping::new(light, &[1, 7], &[]);
        let e = r
            .prepare(&scene, FrameOptions::new().shadow_map(&bad, &mut *map))
            .err();
        assert_eq!(
            e,
            Some(Error::Layers(LayerError::NoSuchObject { index: 7 }))
        );
        // After the errors, the frame is drawn.
        let mut f = scanline3d_support::host::Frame::new(240, 240, Rgb565::new(0, 0, 0));
        r.prepare(&scene, FrameOptions::new().shadow_map(&mapping, &mut *map))
            .unwrap()
            .draw_to(&mut f)
            .unwrap();
    });
}
