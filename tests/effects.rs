//! Point lights and fog against their exact models: a point-lit sphere against a ray-cast one
//! lit per pixel in f64, a distant point light against the directional light it becomes, and
//! fog on a floor against the view depth of each pixel's floor point, ray cast. `cargo test
//! --test effects -- --nocapture` prints the figures.

mod common;

use common::textures::{floor, floor_camera, FLOOR_VIEW};
use common::Frame;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{Error, Texture, TextureMode};

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
    let shape = Shape::<S, 642, 1280>::icosphere(1.0, 3).unwrap();
    let objects = [Object {
        mesh: shape.mesh(),
        transform: Mat4::identity(),
        material: Material::matte(COLOR, S::from_f64(AMBIENT), S::from_f64(DIFFUSE))
            .specular(S::from_f64(SPECULAR), SHININESS)
            .shading(shading),
    }];
    let effects = Effects {
        point_lights: points,
        fog: None,
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
    let p = common::ray_sphere(x, y, SIZE, FOV, EYE)?;
    let n = unit(p);
    let to = [0, 1, 2].map(|k| LAMP[k] - p[k]);
    let dist = dot(to, to).sqrt();
    let l = unit(to);
    let att = 1.0 / (ATT[0] + ATT[1] * dist + ATT[2] * dist * dist).max(1.0);
    let v = [0.0, 0.0, 1.0];
    let nl = dot(n, l);
    let rv = 2.0 * nl * dot(n, v) - dot(l, v);
    Some([0, 1, 2].map(|c| {
        let lc = LAMP_COLOR[c] as f64;
        let mut s = COLOR[c] as f64 * (AMBIENT + DIFFUSE * att * lc / 255.0 * nl.max(0.0));
        if nl > 0.0 && rv > 0.0 {
            s += SPECULAR * att * lc * rv.powi(SHININESS as i32);
        }
        s.clamp(0.0, 255.0)
    }))
}

/// The red channel (5 bits) as 8-bit units.
fn red8(c: Rgb565) -> f64 {
    c.r() as f64 * 255.0 / 31.0
}

/// Worst and mean red difference (8-bit units) against [`reference`] over the pixels 2 px
/// inside the sphere's outline.
fn sphere_error(f: &Frame<Rgb565>) -> (f64, f64) {
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
            let e = (red8(f.get(x, y)) - reference(x, y).unwrap()[0]).abs();
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
        };
        let e = r
            .render(&scene.with_effects(&effects), &mut frame)
            .unwrap_err();
        assert_eq!(e, Error::Fog);
        assert!(e.to_string().contains("near < far"), "{e}");
    }
    // A point light with a NaN: every object is skipped and counted, as for a directional
    // light.
    let bad = [PointLight::new([f32::NAN, 1.0, 0.0], [255; 3])];
    let effects = Effects {
        point_lights: &bad,
        fog: None,
    };
    let stats = r.render(&scene.with_effects(&effects), &mut frame).unwrap();
    assert_eq!(stats.invalid, 2);
    assert_eq!(stats.drawn, 0);
}

/// The point-light and fog benchmark frames in each number type, against golden images
/// (looked at).
#[test]
fn effects_frames_match_their_golden_images() {
    use scanline3d::demo::{render_bench, Bench};
    fn one<S: Scalar>(b: Bench, ty: &str) {
        let mut f = Frame::new(240, 240, Rgb565::BLACK);
        render_bench::<S, Rgb565, _, _>(b, 0.0, false, &mut f, &mut scanline3d::NoProbe).unwrap();
        f.assert_each_written_once();
        common::check_golden(&format!("{}_{ty}", b.name()), &f);
    }
    for b in [
        Bench::PointPhong,
        Bench::PointPhongFast,
        Bench::PointGouraud,
        Bench::FogGouraud,
        Bench::TexturedFog,
    ] {
        one::<Q>(b, "I16F16");
        one::<f32>(b, "f32");
        one::<f64>(b, "f64");
    }
}
