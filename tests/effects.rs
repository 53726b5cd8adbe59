//! Point lights and fog against their exact models: a point-lit sphere against a ray-cast one
//! lit per pixel in f64, a distant point light against the directional light it becomes, and
//! fog on a floor against the view depth of each pixel's floor point, ray cast. `cargo test
//! --test effects -- --nocapture` prints the figures.

use crate::common;

use common::textures::{floor, floor_camera, FLOOR_VIEW};
use common::Frame;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use scanline3d::prelude::*;
use scanline3d::{
    limits::MAX_TONE_SCALE, tone::AutoExposure, tone::Metered, tone::ToneCurve, Error, Texture,
    TextureMode, ToneMap,
};

type Q = Fx<scanline3d::fixed::types::I16F16>;

const SIZE: u32 = 160;
const EYE: f64 = 3.0;
const FOV: f64 = 0.8;
const COLOR: [u8; 3] = [220, 160, 90];
const AMBIENT: f64 = 0.1;
const DIFFUSE: f64 = 0.9;
const SPECULAR: f64 = 0.4;
const SHININESS: u8 = 12;
/// The point light: position, colour, attenuation.
const LAMP: [f64; 3] = [1.1, 0.9, 1.4];
const LAMP_COLOR: [u8; 3] = [255, 240, 200];
const ATT: [f64; 3] = [0.6, 0.3, 0.25];

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    v.map(|c| c / l)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sphere_camera<S: Scalar>() -> Camera<S> {
    Camera::look_at(
        [S::ZERO, S::ZERO, S::from_f64(EYE)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: S::from_f64(FOV),
            near: S::from_f64(0.1),
            far: S::from_f64(10.0),
        },
    )
    .unwrap()
}

type SphereRenderer<S> = Renderer<S, Rgb565, 160, 160, 1400, 1400, 64, 1, 1400, 72>;

/// The icosphere (subdivided 3 times: 642 vertices) under the scene's `lights` and `points`.
fn sphere<S: Scalar, const L: usize>(
    shading: Shading,
    lights: [Light<S>; L],
    points: &[PointLight<S>],
) -> Frame<Rgb565> {
    toned_sphere(shading, lights, points, None, COLOR)
}

/// [`sphere`] with a tone map and a material colour.
fn toned_sphere<S: Scalar, const L: usize>(
    shading: Shading,
    lights: [Light<S>; L],
    points: &[PointLight<S>],
    tone: Option<ToneMap<S>>,
    color: [u8; 3],
) -> Frame<Rgb565> {
    let shape = Shape::<S, 642, 1280>::icosphere(1.0, 3).unwrap();
    let objects = [Object {
        mesh: shape.mesh(),
        transform: Mat4::identity(),
        material: Material::matte(color, S::from_f64(AMBIENT), S::from_f64(DIFFUSE))
            .specular(S::from_f64(SPECULAR), SHININESS)
            .shading(shading),
    }];
    let effects = Effects {
        point_lights: points,
        fog: None,
        tone,
    };
    let scene = Scene::new(&objects, sphere_camera(), lights).with_effects(&effects);
    let mut r: Box<SphereRenderer<S>> = Box::default();
    let mut f = Frame::new(SIZE, SIZE, Rgb565::BLACK);
    r.render(&scene, &mut f).unwrap();
    f.assert_each_written_once();
    f
}

fn lamp<S: Scalar>() -> PointLight<S> {
    let [c, l, q] = ATT.map(S::from_f64);
    PointLight::new(LAMP.map(S::from_f64), LAMP_COLOR).attenuation(c, l, q)
}

/// The exact model on the unit sphere at the centre of pixel (x, y) with the point light,
/// 8-bit channels, or `None` off the sphere. The view direction is the object origin's (as
/// Phong's).
fn reference(x: u32, y: u32) -> Option<[f64; 3]> {
    reference_toned(x, y, None)
}

/// [`reference`] in HDR: every light `intensity` times as bright, the radiance times
/// `exposure`, then `curve` (as `ToneMap` defines them), or plainly clamped for `None`.
fn reference_toned(x: u32, y: u32, tone: Option<(ToneCurve, f64, f64)>) -> Option<[f64; 3]> {
    let p = common::ray_sphere(x, y, SIZE, FOV, EYE)?;
    let n = unit(p);
    let to = [0, 1, 2].map(|k| LAMP[k] - p[k]);
    let dist = dot(to, to).sqrt();
    let l = unit(to);
    let att = 1.0 / (ATT[0] + ATT[1] * dist + ATT[2] * dist * dist).max(1.0);
    let v = [0.0, 0.0, 1.0];
    let nl = dot(n, l);
    let rv = 2.0 * nl * dot(n, v) - dot(l, v);
    let (curve, intensity, exposure) = tone.unwrap_or((ToneCurve::Clamp, 1.0, 1.0));
    Some([0, 1, 2].map(|c| {
        let lc = LAMP_COLOR[c] as f64;
        let diffuse = intensity * DIFFUSE * att * lc / 255.0 * nl.max(0.0);
        let mut s = COLOR[c] as f64 * (AMBIENT + diffuse);
        if nl > 0.0 && rv > 0.0 {
            s += intensity * SPECULAR * att * lc * rv.powi(SHININESS as i32);
        }
        let x = (exposure * s / 255.0).max(0.0);
        255.0
            * match curve {
                ToneCurve::Clamp => x.min(1.0),
                ToneCurve::Reinhard => x / (1.0 + x),
                ToneCurve::Filmic => {
                    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).min(1.0)
                }
                other => panic!("no float reference for the tone curve {other:?}"),
            }
    }))
}

/// The red channel (5 bits) as 8-bit units.
fn red8(c: Rgb565) -> f64 {
    c.r() as f64 * 255.0 / 31.0
}

/// Worst and mean red difference (8-bit units) against [`reference`] over the pixels 2 px
/// inside the sphere's outline.
fn sphere_error(f: &Frame<Rgb565>) -> (f64, f64) {
    sphere_error_toned(f, None)
}

/// [`sphere_error`] against [`reference_toned`].
fn sphere_error_toned(f: &Frame<Rgb565>, tone: Option<(ToneCurve, f64, f64)>) -> (f64, f64) {
    let (mut worst, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in 2..SIZE - 2 {
        for x in 2..SIZE - 2 {
            let inside =
                [(0i32, 0i32), (-2, 0), (2, 0), (0, -2), (0, 2)]
                    .iter()
                    .all(|&(dx, dy)| {
                        reference((x as i32 + dx) as u32, (y as i32 + dy) as u32).is_some()
                    });
            if !inside || f.get(x, y) == Rgb565::BLACK {
                continue;
            }
            let e = (red8(f.get(x, y)) - reference_toned(x, y, tone).unwrap()[0]).abs();
            worst = worst.max(e);
            sum += e;
            n += 1;
        }
    }
    assert!(n > 5000, "{n}");
    (worst, sum / n as f64)
}

fn point_lit<S: Scalar>(shading: Shading) -> Frame<Rgb565> {
    sphere::<S, 0>(shading, [], &[lamp()])
}

#[test]
fn a_point_lit_sphere_matches_the_ray_cast_one() {
    for ty in ["I16F16", "f32", "f64"] {
        let r = |s: Shading| match ty {
            "I16F16" => point_lit::<Q>(s),
            "f32" => point_lit::<f32>(s),
            _ => point_lit::<f64>(s),
        };
        let (g, p, fp) = (
            sphere_error(&r(Shading::Gouraud)),
            sphere_error(&r(Shading::Phong)),
            sphere_error(&r(Shading::FastPhong)),
        );
        println!(
            "{ty}: red error against the ray-cast sphere (8-bit units), worst / mean: \
             gouraud {:.1} / {:.2}, phong {:.1} / {:.2}, fast phong {:.1} / {:.2}",
            g.0, g.1, p.0, p.1, fp.0, fp.1
        );
        // Phong: within a few RGB565 steps everywhere (the mesh's facets move the
        // silhouette and the highlight a little), about one step on average.
        assert!(p.0 < 40.0 && p.1 < 4.5, "phong {p:?}");
        assert!(fp.1 < 4.5, "fast phong {fp:?}");
        // Gouraud is close on the diffuse part; its local viewer moves the highlight.
        assert!(g.1 < 8.0, "gouraud {g:?}");
    }
}

/// A point light very far away in direction `d`, without attenuation, lights as the
/// directional light toward `d`: the same pixels within one RGB565 step.
#[test]
fn a_distant_point_light_is_a_directional_light() {
    fn check<S: Scalar>(name: &str) {
        let d = unit([-0.6, 0.7, 1.0]);
        let far = PointLight::new(d.map(|c| S::from_f64(c * 2000.0)), [255; 3]);
        for shading in [Shading::Gouraud, Shading::Phong, Shading::Flat] {
            let point = sphere::<S, 0>(shading, [], &[far]);
            let directional = sphere::<S, 1>(shading, [Light::white(d.map(S::from_f64))], &[]);
            let (worst, differing, _) = common::compare565(&point, &directional, Rgb565::BLACK);
            println!("{name} {shading:?}: worst {worst:?}, {differing} px differ");
            assert!(
                worst.iter().all(|&w| w <= 1),
                "{name} {shading:?}: {worst:?}"
            );
            assert!(differing < 2000, "{name} {shading:?}: {differing}");
        }
    }
    check::<Q>("I16F16");
    check::<f32>("f32");
    check::<f64>("f64");
}

/// Nearer than the lamp's reach, brighter: the pixel of the sphere nearest the lamp is
/// brighter than with the lamp twice as far, by about the attenuation's ratio.
#[test]
fn attenuation_dims_with_distance() {
    let at = |k: f64| {
        let p = PointLight::new(LAMP.map(|c| c * k), [255; 3]).attenuation(0.0, 0.0, 1.0);
        let f = sphere::<f64, 0>(Shading::Phong, [], &[p]);
        // The brightest red over the frame.
        (0..SIZE)
            .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
            .map(|(x, y)| red8(f.get(x, y)))
            .fold(0.0, f64::max)
    };
    let (near, far) = (at(1.0), at(2.0));
    println!("brightest red: lamp at 1× {near:.0}, at 2× {far:.0}");
    assert!(near > 1.5 * far, "{near} {far}");
}

// ---- Fog ----

const FOG: [u8; 3] = [170, 190, 220];
const FOG_NEAR: f64 = 1.5;
const FOG_FAR: f64 = 3.5;

/// The view depth of the floor's point at the centre of pixel (x, y) of the floor scene, or
/// `None` off the floor.
fn floor_depth(x: u32, y: u32) -> Option<f64> {
    let (eye, target) = ([-0.5, 0.6, 0.8], [0.6, 0.0, -1.5]);
    let fwd = unit([0, 1, 2].map(|k| target[k] - eye[k]));
    let right = unit([-fwd[2], 0.0, fwd[0]]);
    let up = [
        right[1] * fwd[2] - right[2] * fwd[1],
        right[2] * fwd[0] - right[0] * fwd[2],
        right[0] * fwd[1] - right[1] * fwd[0],
    ];
    let (w, h) = (FLOOR_VIEW.0 as f64, FLOOR_VIEW.1 as f64);
    let th = (1.0f64 / 2.0).tan();
    let sx = ((x as f64 + 0.5) / w * 2.0 - 1.0) * th * w / h;
    let sy = (1.0 - (y as f64 + 0.5) / h * 2.0) * th;
    let d = [0, 1, 2].map(|k| fwd[k] + sx * right[k] + sy * up[k]);
    if d[1] >= 0.0 {
        return None;
    }
    let t = -eye[1] / d[1];
    let p = [0, 1, 2].map(|k| eye[k] + t * d[k]);
    (p[0].abs() < 0.98 && p[2] < -0.02 && p[2] > -3.98).then_some(t)
}

/// A white 2 × 2 texture: a textured floor that shows its lighting.
fn white_texture() -> &'static Texture {
    static WHITE: [u16; 4] = [0xffff; 4];
    static T: std::sync::OnceLock<Texture> = std::sync::OnceLock::new();
    T.get_or_init(|| Texture::new(&WHITE, 2, 2).unwrap())
}

type FloorRenderer<S> = Renderer<S, Rgb565, 160, 120, 64, 64, 16, 1, 64, 16>;

/// The floor (unlit: ambient 1, colour [`FLOOR`]), with or without fog, in a given style.
fn fog_floor<S: Scalar>(
    style: &str,
    fog: bool,
) -> Result<Frame<Rgb565>, Error<core::convert::Infallible>> {
    let f = floor::<S>();
    let mut material = Material::matte(FLOOR, S::ONE, S::ZERO);
    material = match style {
        "gouraud" => material,
        "phong" => material.phong(),
        "fast phong" => material.shading(Shading::FastPhong),
        "textured" => material.textured(white_texture()),
        "textured affine" => material
            .textured(white_texture())
            .texture_mode(TextureMode::Affine),
        _ => material.flat(),
    };
    let objects = [Object {
        mesh: f.mesh(),
        transform: Mat4::identity(),
        material,
    }];
    let effects = Effects {
        point_lights: &[],
        fog: Some(Fog::linear(
            S::from_f64(FOG_NEAR),
            S::from_f64(FOG_FAR),
            FOG,
        )),
        tone: None,
    };
    let mut scene = Scene::new(
        &objects,
        floor_camera(),
        [Light::white([S::ZERO, S::ONE, S::ZERO])],
    );
    if fog {
        scene = scene.with_effects(&effects);
    }
    let mut r: Box<FloorRenderer<S>> = Box::default();
    let (w, h) = FLOOR_VIEW;
    let mut frame = Frame::new(w, h, Rgb565::BLACK);
    r.render(&scene, &mut frame)?;
    frame.assert_each_written_once();
    Ok(frame)
}

const FLOOR: [u8; 3] = [60, 120, 40];

/// Worst and mean error (RGB565 steps, over the channels) of the fogged floor against the
/// exact mix of the floor colour and the fog colour at each pixel's view depth.
fn fog_error(f: &Frame<Rgb565>) -> (f64, f64) {
    let (mut worst, mut sum, mut n) = (0.0f64, 0.0, 0);
    for y in 0..FLOOR_VIEW.1 {
        for x in 0..FLOOR_VIEW.0 {
            let Some(z) = floor_depth(x, y) else {
                continue;
            };
            let t = ((z - FOG_NEAR) / (FOG_FAR - FOG_NEAR)).clamp(0.0, 1.0);
            let c = f.get(x, y);
            let got = [c.r() as f64, c.g() as f64, c.b() as f64];
            for k in 0..3 {
                let max = [31.0, 63.0, 31.0][k];
                let want = (FLOOR[k] as f64 * (1.0 - t) + FOG[k] as f64 * t) * max / 255.0;
                let e = (got[k] - want).abs();
                worst = worst.max(e);
                sum += e;
                n += 1;
            }
        }
    }
    assert!(n > 3000, "{n}");
    (worst, sum / n as f64)
}

#[test]
fn fog_follows_the_view_depth() {
    for ty in ["I16F16", "f32", "f64"] {
        for style in [
            "phong",
            "fast phong",
            "textured",
            "textured affine",
            "gouraud",
            "flat",
        ] {
            let f = match ty {
                "I16F16" => fog_floor::<Q>(style, true),
                "f32" => fog_floor::<f32>(style, true),
                _ => fog_floor::<f64>(style, true),
            }
            .unwrap();
            let (worst, mean) = fog_error(&f);
            println!("{ty} {style}: fog error worst {worst:.2}, mean {mean:.3} RGB565 steps");
            match style {
                // Per lit pixel or per 8- or 16-pixel segment: within a step and a half.
                "phong" | "fast phong" | "textured" => assert!(worst < 1.5 && mean < 0.5),
                // One segment a span: the fog is linear across the whole span.
                "textured affine" => assert!(worst < 3.0 && mean < 0.6),
                // Per vertex (two triangles here: the fog is linear across each) and per
                // face (one factor each): only its average follows.
                "gouraud" => assert!(mean < 6.0),
                _ => assert!(mean < 8.0),
            }
        }
    }
}

/// Before the fog's near depth nothing changes; beyond its far depth only fog shows.
#[test]
fn fog_starts_at_near_and_hides_everything_beyond_far() {
    let fog565 = Rgb565::new(
        ((FOG[0] as u32 * 31 * 2 + 255) / 510) as u8,
        ((FOG[1] as u32 * 63 * 2 + 255) / 510) as u8,
        ((FOG[2] as u32 * 31 * 2 + 255) / 510) as u8,
    );
    for style in ["phong", "fast phong", "textured", "gouraud"] {
        let (with, without) = (
            fog_floor::<Q>(style, true).unwrap(),
            fog_floor::<Q>(style, false).unwrap(),
        );
        let (mut near, mut far) = (0, 0);
        for y in 0..FLOOR_VIEW.1 {
            for x in 0..FLOOR_VIEW.0 {
                match floor_depth(x, y) {
                    Some(z) if z < FOG_NEAR - 0.1 && style != "gouraud" => {
                        assert_eq!(with.get(x, y), without.get(x, y), "{style} ({x}, {y})");
                        near += 1;
                    }
                    Some(z) if z > FOG_FAR + 0.1 && style != "gouraud" => {
                        assert_eq!(with.get(x, y), fog565, "{style} ({x}, {y})");
                        far += 1;
                    }
                    _ => {}
                }
            }
        }
        if style != "gouraud" {
            assert!(near > 1000 && far > 100, "{style}: {near} {far}");
        }
    }
}

#[test]
fn bad_fog_and_bad_point_lights_are_reported() {
    let f = floor::<f32>();
    let objects = [Object {
        mesh: f.mesh(),
        transform: Mat4::identity(),
        material: Material::matte(FLOOR, 1.0, 0.0),
    }];
    let scene = Scene::new(&objects, floor_camera(), [Light::white([0.0, 1.0, 0.0])]);
    let mut r: Box<FloorRenderer<f32>> = Box::default();
    let mut frame = Frame::new(FLOOR_VIEW.0, FLOOR_VIEW.1, Rgb565::BLACK);
    for fog in [
        Fog::linear(2.0, 2.0, [0; 3]),
        Fog::linear(3.0, 1.0, [0; 3]),
        Fog::linear(f32::NAN, 1.0, [0; 3]),
    ] {
        let effects = Effects {
            point_lights: &[],
            fog: Some(fog),
            tone: None,
        };
        let e = r
            .render(&scene.with_effects(&effects), &mut frame)
            .unwrap_err();
        assert_eq!(e, Error::Fog);
        assert!(e.to_string().contains("near < far"), "{e}");
    }
    // A point light with a NaN: refused, as a fog (it once made every object a counted skip,
    // an empty frame that came back `Ok`).
    let bad = [PointLight::new([f32::NAN, 1.0, 0.0], [255; 3])];
    let effects = Effects {
        point_lights: &bad,
        fog: None,
        tone: None,
    };
    let e = r
        .render(&scene.with_effects(&effects), &mut frame)
        .unwrap_err();
    assert_eq!(
        e,
        Error::Light {
            index: 0,
            point: true
        }
    );
}

/// The point-light and fog benchmark frames in each number type, against golden images
/// (looked at).
#[test]
fn effects_frames_match_their_golden_images() {
    use scanline3d_support::demo::Bench;
    fn one<S: Scalar>(b: Bench, ty: &str) {
        common::compare::check_bench_golden::<S>(b, ty);
    }
    for b in [
        Bench::PointPhong,
        Bench::PointPhongFast,
        Bench::PointGouraud,
        Bench::FogGouraud,
        Bench::TexturedFog,
        Bench::HdrGouraud,
        Bench::HdrPhong,
    ] {
        one::<Q>(b, "I16F16");
        one::<f32>(b, "f32");
        one::<f64>(b, "f64");
    }
}

#[test]
fn tone_curves_are_monotone_and_bounded() {
    fn go<S: Scalar>() {
        for curve in [ToneCurve::Clamp, ToneCurve::Reinhard, ToneCurve::Filmic] {
            let mut last = S::ZERO;
            assert_eq!(curve.apply(S::ZERO), S::ZERO, "{curve:?}");
            assert_eq!(curve.apply(S::from_f64(-3.0)), S::ZERO, "{curve:?}");
            // Finely near 0 (where rounding could turn a curve down), then to 20 × white.
            for k in 1..=2048 {
                let y = curve.apply(S::from_f64(k as f64 / 8192.0));
                assert!(
                    y >= last && y <= S::ONE,
                    "{curve:?} {} at {k}/8192",
                    S::NAME
                );
                last = y;
            }
            for k in 6..=400 {
                let y = curve.apply(S::from_f64(k as f64 * 0.05));
                assert!(y >= last && y <= S::ONE, "{curve:?} {} at {}", S::NAME, k);
                last = y;
            }
        }
        let near = |a: S, b: f64| (a.to_f64() - b).abs() < 1e-4;
        assert!(near(ToneCurve::Reinhard.apply(S::ONE), 0.5));
        assert!(near(ToneCurve::Clamp.apply(S::from_f64(0.3)), 0.3));
        assert_eq!(ToneCurve::Clamp.apply(S::from_f64(7.0)), S::ONE);
        assert_eq!(ToneCurve::Filmic.apply(S::from_f64(20.0)), S::ONE);
        // The filmic toe: darker than the clamp below about 0.05, brighter above.
        assert!(ToneCurve::Filmic.apply(S::from_f64(0.02)) < S::from_f64(0.02));
        assert!(ToneCurve::Filmic.apply(S::from_f64(0.5)) > S::from_f64(0.5));
    }
    go::<Q>();
    go::<f32>();
    go::<f64>();
}

/// The sphere under its directional light and lamp, with `tone`.
fn hdr_sphere<S: Scalar>(tone: Option<ToneMap<S>>, color: [u8; 3]) -> Frame<Rgb565> {
    let light = [Light::white([-0.6, 0.8, 1.0].map(S::from_f64))];
    toned_sphere(Shading::Gouraud, light, &[lamp()], tone, color)
}

#[test]
fn a_clamp_tone_map_at_exposure_one_is_the_plain_image() {
    fn go<S: Scalar>() {
        let plain = hdr_sphere::<S>(None, COLOR);
        let clamp = hdr_sphere(Some(ToneMap::<S>::new(ToneCurve::Clamp)), COLOR);
        assert!(plain.px == clamp.px, "{}", S::NAME);
        // The curves change it.
        let filmic = hdr_sphere(Some(ToneMap::<S>::new(ToneCurve::Filmic)), COLOR);
        assert!(plain.px != filmic.px, "{}", S::NAME);
    }
    go::<Q>();
    go::<f32>();
    go::<f64>();
}

/// Mean luma (0..=255) of the sphere's pixels (not the black background).
fn sphere_luma(f: &Frame<Rgb565>) -> f64 {
    let lit: Vec<f64> =
        f.px.iter()
            .filter(|c| **c != Rgb565::BLACK)
            .map(|c| {
                let (r, g, b) = (
                    c.r() as f64 * 255.0 / 31.0,
                    c.g() as f64 * 255.0 / 63.0,
                    c.b() as f64 * 255.0 / 31.0,
                );
                // BT.601 (embedded-graphics' weights), as `Metered` measures.
                (77.0 * r + 150.0 * g + 29.0 * b) / 256.0
            })
            .collect();
    lit.iter().sum::<f64>() / lit.len().max(1) as f64
}

#[test]
fn a_dark_material_under_a_bright_light_looks_like_a_normal_colour() {
    fn go<S: Scalar>() {
        let dark = [40, 40, 40];
        // Clamped, at ordinary brightness: dim.
        let dim = sphere_luma(&hdr_sphere::<S>(None, dark));
        // Six times as bright, Reinhard: a mid grey, with highlights that do not clip.
        let bright = ToneMap::<S>::new(ToneCurve::Reinhard).with_intensity(S::from_f64(6.0));
        let f = hdr_sphere(Some(bright), dark);
        let mid = sphere_luma(&f);
        assert!(dim < 40.0, "{} {dim}", S::NAME);
        assert!((60.0..200.0).contains(&mid), "{} {mid}", S::NAME);
        // The same light clamped saturates more of the sphere than Reinhard does.
        let clamped = hdr_sphere(
            Some(ToneMap::<S>::new(ToneCurve::Clamp).with_intensity(S::from_f64(6.0))),
            COLOR,
        );
        let reinhard = hdr_sphere(Some(bright), COLOR);
        let white = |f: &Frame<Rgb565>| -> usize { f.px.iter().filter(|c| c.r() == 31).count() };
        assert!(white(&clamped) > 2 * white(&reinhard) + 10, "{}", S::NAME);
    }
    go::<Q>();
    go::<f32>();
    go::<f64>();
}

#[test]
fn automatic_exposure_adapts_to_bright_and_dark_scenes() {
    fn go<S: Scalar>(intensity: f64) -> (f64, f64) {
        let mut auto = AutoExposure::new(50, 128);
        let mut first = 0.0;
        for k in 0..24 {
            let tone = ToneMap::<S>::new(ToneCurve::Reinhard)
                .with_intensity(S::from_f64(intensity))
                .with_exposure(auto.exposure::<S>());
            let f = hdr_sphere(Some(tone), COLOR);
            // Measured as the strips go out (here the frame in one call to a target that
            // discards it), sphere and background alike.
            let mut sink = scanline3d_support::hash::NullTarget::<Rgb565>::new(SIZE, SIZE);
            let mut m = Metered::new(&mut sink);
            let all = Rectangle::new(Point::zero(), Size::new(SIZE, SIZE));
            m.fill_contiguous(&all, f.px.iter().copied()).unwrap();
            let mean = m.mean();
            if k == 0 {
                first = mean as f64;
            }
            auto.adapt(mean);
            if k == 23 {
                return (first, mean as f64);
            }
        }
        unreachable!()
    }
    for (bright, dark) in [
        (go::<Q>(8.0), go::<Q>(0.25)),
        (go::<f64>(8.0), go::<f64>(0.25)),
    ] {
        // Too bright, then near the target; too dark, then near it.
        assert!(
            bright.0 > 70.0 && (bright.1 - 50.0).abs() < 6.0,
            "{bright:?}"
        );
        assert!(dark.0 < 35.0 && (dark.1 - 50.0).abs() < 6.0, "{dark:?}");
    }
    // The exposure stays within its range whatever is measured.
    // Leaving the background out: the sphere's own mean.
    let f = hdr_sphere::<f64>(None, COLOR);
    let mut sink = scanline3d_support::hash::NullTarget::<Rgb565>::new(SIZE, SIZE);
    let mut m = Metered::new(&mut sink).excluding(Rgb565::BLACK);
    let all = Rectangle::new(Point::zero(), Size::new(SIZE, SIZE));
    m.fill_contiguous(&all, f.px.iter().copied()).unwrap();
    assert_eq!(m.mean() as f64, sphere_luma(&f).floor());
    m.reset();
    assert_eq!(m.mean(), 0);
    let mut a = AutoExposure::new(200, 256);
    for _ in 0..40 {
        a.adapt(0);
    }
    assert_eq!(a.exposure_bits(), (MAX_TONE_SCALE as u32) << 16);
    for _ in 0..40 {
        a.adapt(255);
    }
    assert!(a.exposure_bits() >= 1 << 8);
}

#[test]
fn bad_tone_maps_are_named_errors() {
    fn go<S: Scalar>(
        tone: ToneMap<S>,
        shading: Shading,
    ) -> Option<Error<core::convert::Infallible>> {
        let shape = Shape::<S, 42, 80>::icosphere(1.0, 1).unwrap();
        let objects = [Object {
            mesh: shape.mesh(),
            transform: Mat4::identity(),
            material: Material::matte(COLOR, S::ONE, S::ZERO).shading(shading),
        }];
        let effects = Effects {
            point_lights: &[],
            fog: None,
            tone: Some(tone),
        };
        let light = [Light::white([S::ZERO, S::ZERO, S::ONE])];
        let scene = Scene::new(&objects, sphere_camera(), light).with_effects(&effects);
        let mut r: Box<SphereRenderer<S>> = Box::default();
        let mut f = Frame::new(SIZE, SIZE, Rgb565::BLACK);
        r.render(&scene, &mut f).err()
    }
    let numbers = Some(Error::Tone { object: None });
    let t = ToneMap::<f32>::new(ToneCurve::Reinhard);
    assert_eq!(go(t.with_exposure(0.0), Shading::Gouraud), numbers);
    assert_eq!(go(t.with_exposure(f32::NAN), Shading::Gouraud), numbers);
    assert_eq!(go(t.with_intensity(17.0), Shading::Gouraud), numbers);
    assert_eq!(go(t.with_intensity(-1.0), Shading::Flat), numbers);
    assert_eq!(go(t, Shading::Phong), None);
    assert_eq!(go(t, Shading::Gouraud), None);
    let q = ToneMap::<Q>::new(ToneCurve::Filmic);
    assert_eq!(
        go(q.with_exposure(Q::from_f64(16.5)), Shading::Gouraud),
        numbers
    );
    assert_eq!(
        go(q.with_intensity(Q::from_f64(16.0)), Shading::Gouraud),
        None
    );
}

/// Phong and fast Phong are tone-mapped per pixel: with the clamp at intensity and exposure 1
/// they are the plain images bit for bit, and in HDR they match the ray-cast sphere lit,
/// exposed and mapped by the same curve as closely as the plain Phong sphere matches the plain
/// one.
#[test]
fn phong_is_tone_mapped_per_pixel() {
    fn go<S: Scalar>() {
        for shading in [Shading::Phong, Shading::FastPhong] {
            let plain = toned_sphere::<S, 0>(shading, [], &[lamp()], None, COLOR);
            let clamp = toned_sphere::<S, 0>(
                shading,
                [],
                &[lamp()],
                Some(ToneMap::new(ToneCurve::Clamp)),
                COLOR,
            );
            assert!(plain.px == clamp.px, "{} {shading:?}", S::NAME);
            for curve in [ToneCurve::Clamp, ToneCurve::Reinhard, ToneCurve::Filmic] {
                let (i, e) = (3.0, 0.7);
                let tone = ToneMap::new(curve)
                    .with_intensity(S::from_f64(i))
                    .with_exposure(S::from_f64(e));
                let f = toned_sphere::<S, 0>(shading, [], &[lamp()], Some(tone), COLOR);
                let (worst, mean) = sphere_error_toned(&f, Some((curve, i, e)));
                println!(
                    "{} {shading:?} {curve:?}: red error {worst:.1} worst, {mean:.2} mean",
                    S::NAME
                );
                assert!(
                    worst < 24.0 && mean < 2.5,
                    "{} {shading:?} {curve:?}",
                    S::NAME
                );
                if curve != ToneCurve::Clamp {
                    assert!(f.px != plain.px);
                }
            }
        }
    }
    go::<Q>();
    go::<f32>();
    go::<f64>();
}
