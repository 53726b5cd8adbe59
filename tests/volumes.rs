//! Shadow volumes and outlines: the camera inside a volume gives the image the planar
//! projection predicts, an object shadows itself and others, outlines are 1 px and hidden
//! behind nearer surfaces, bad layerings are named errors, and every pixel is written once.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{
    errors::AdjacencyError, errors::LayerError, mesh::mesh_adjacency, mesh::Adjacency,
    shadow::Layering, shadow::Outline, shadow::PlanarShadow, shadow::ShadowLight,
    shadow::VolumeShadow, Error, Layers,
};

type Q = Fx<scanline3d::fixed::types::I16F16>;

const N: u32 = 96;
const SHADOW: u8 = 160;
const GROUND: [u8; 3] = [200, 200, 200];

/// A closed box (8 corners, 12 counter-clockwise triangles seen from outside), centred at `c`
/// with half-sizes `h`, appended to `p` and `t`.
fn boxed(c: [f64; 3], h: [f64; 3], p: &mut Vec<[f64; 3]>, t: &mut Vec<[u16; 3]>) {
    let b = p.len() as u16;
    for k in 0..8 {
        let s = |bit: usize| if k & (1 << bit) != 0 { 1.0 } else { -1.0 };
        p.push([c[0] + s(0) * h[0], c[1] + s(1) * h[1], c[2] + s(2) * h[2]]);
    }
    // Faces as corner quads (outward normal by the right-hand rule).
    for q in [
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
    ] {
        t.push([b + q[0], b + q[1], b + q[2]]);
        t.push([b + q[0], b + q[2], b + q[3]]);
    }
}

struct World<S> {
    ground: Vec<[S; 3]>,
    caster: Vec<[S; 3]>,
    caster_tris: Vec<[u16; 3]>,
    adjacency: Vec<[u16; 3]>,
}

/// An 8 × 8 ground square at y = 0 and, above it, the boxes of `boxes` as one mesh (centre,
/// half-sizes).
fn world<S: Scalar>(boxes: &[([f64; 3], [f64; 3])]) -> World<S> {
    let (mut p, mut t) = (Vec::new(), Vec::new());
    for &(c, h) in boxes {
        boxed(c, h, &mut p, &mut t);
    }
    let caster: Vec<[S; 3]> = p.iter().map(|v| v.map(S::from_f64)).collect();
    let mut adjacency = vec![[0u16; 3]; t.len()];
    let open = mesh_adjacency(&Mesh::new(&caster, &t).unwrap(), &mut adjacency).unwrap();
    assert_eq!(open, 0, "the boxes are closed");
    let g = 4.0;
    let ground = [[-g, 0.0, g], [g, 0.0, g], [g, 0.0, -g], [-g, 0.0, -g]]
        .map(|v| v.map(S::from_f64))
        .to_vec();
    World {
        ground,
        caster,
        caster_tris: t,
        adjacency,
    }
}

const QUAD: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

fn unlit<S: Scalar>(c: [u8; 3]) -> Material<S> {
    Material::unlit(c)
}

/// How a frame's shadow is drawn.
#[derive(Copy, Clone, PartialEq)]
enum How {
    Planar,
    Volume,
}

/// `w` seen by `camera`, its boxes (unlit red) shadowing along `light` by `how`.
fn draw<S: Scalar>(w: &World<S>, camera: Camera<S>, light: [f64; 3], how: How) -> Frame<Rgb888> {
    let objects = [
        Object {
            mesh: Mesh::new(&w.ground, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit(GROUND),
        },
        Object {
            mesh: Mesh::new(&w.caster, &w.caster_tris).unwrap(),
            transform: Mat4::identity(),
            material: unlit([220, 40, 40]),
        },
    ];
    let l = light.map(S::from_f64);
    let scene = Scene::new(&objects, camera, [Light::white(l)]).with_background([0, 0, 60]);
    let adjacency = [Adjacency::new(&objects[1].mesh, &w.adjacency).unwrap()];
    let layering = match how {
        How::Planar => Layering::projected(
            &[0],
            &[1],
            PlanarShadow::new(
                [0.0, 1.0, 0.0, 0.0].map(S::from_f64),
                ShadowLight::Directional(l),
                SHADOW,
            ),
        ),
        How::Volume => Layering::volumes(
            &[1],
            VolumeShadow {
                light: ShadowLight::Directional(l),
                reach: S::from_f64(8.0),
                adjacency: &adjacency,
                color: [0; 3],
                alpha: SHADOW,
            },
        ),
    };
    let mut r = Renderer::<S, Rgb888, { N as usize }, { N as usize }, 256, 256, 64>::new();
    let mut layers = Layers::<{ N as usize }, 1, 4, 128>::new();
    let mut f = Frame::new(N, N, Rgb888::BLACK);
    r.render_with(
        &scene,
        scanline3d::FrameOptions::new().layered(&layering, &mut layers),
        &mut f,
    )
    .unwrap();
    f.assert_each_written_once();
    f
}

fn camera<S: Scalar>(eye: [f64; 3], target: [f64; 3]) -> Camera<S> {
    Camera::look_at(
        eye.map(S::from_f64),
        target.map(S::from_f64),
        [0.0, 1.0, 0.0].map(S::from_f64),
        Projection::Perspective {
            fov_y: S::from_f64(80f64.to_radians()),
            near: S::from_f64(0.05),
            far: S::from_f64(30.0),
        },
    )
    .unwrap()
}

/// An orthographic camera at `eye` looking at the origin, 1 unit = 8 px.
fn ortho<S: Scalar>(eye: [f64; 3], up: [f64; 3]) -> Camera<S> {
    common::ortho8(eye, up, N, 20.0)
}

/// The ground's colour darkened by the shadow, as the target shows it.
fn shadowed_ground() -> Rgb888 {
    let c = |v: u8| ((v as u32 * (255 - SHADOW as u32) + 127) / 255) as u8;
    Rgb888::new(c(GROUND[0]), c(GROUND[1]), c(GROUND[2]))
}

fn count(f: &Frame<Rgb888>, c: Rgb888) -> usize {
    f.px.iter().filter(|&&p| p == c).count()
}

/// The ground pixels where two frames differ, and those of them off the rims of `a`'s
/// shadow (no pixel within one step whose shadowed state differs from theirs in `a`). (The
/// planar projection predicts nothing about the casters' own pixels.)
fn differ(a: &Frame<Rgb888>, b: &Frame<Rgb888>) -> (usize, usize) {
    let dark = shadowed_ground();
    let (mut all, mut off_rim) = (0, 0);
    for y in 0..N {
        for x in 0..N {
            if a.get(x, y) == b.get(x, y) || a.get(x, y) == Rgb888::new(220, 40, 40) {
                continue;
            }
            all += 1;
            let here = a.get(x, y) == dark;
            let rim = (y.saturating_sub(1)..(y + 2).min(N)).any(|v| {
                (x.saturating_sub(1)..(x + 2).min(N)).any(|u| (a.get(u, v) == dark) != here)
            });
            if !rim {
                off_rim += 1;
            }
        }
    }
    (all, off_rim)
}

/// One box at height 2 over the ground, the light nearly overhead: the camera at `eye`.
fn inside_or_outside<S: Scalar>(eye: [f64; 3], target: [f64; 3]) -> ((usize, usize), usize, usize) {
    let w = world::<S>(&[([0.0, 2.0, 0.0], [0.6, 0.3, 0.6])]);
    let light = [-0.15, 1.0, -0.1];
    let planar = draw(&w, camera(eye, target), light, How::Planar);
    let volume = draw(&w, camera(eye, target), light, How::Volume);
    let dark = shadowed_ground();
    if let Ok(dir) = std::env::var("VOLUME_DEBUG") {
        let tag = format!("{}_{}", S::NAME, eye[1]);
        std::fs::write(
            format!("{dir}/planar_{tag}.png"),
            common::png_bytes(&planar),
        )
        .unwrap();
        std::fs::write(
            format!("{dir}/volume_{tag}.png"),
            common::png_bytes(&volume),
        )
        .unwrap();
    }
    (
        differ(&planar, &volume),
        count(&volume, dark),
        count(&planar, dark),
    )
}

fn camera_inside_a_volume<S: Scalar>() {
    // Under the box, inside its shadow volume (the near plane cuts the volume): the ground
    // around the camera is in shadow, the ground farther off is lit, exactly as the planar
    // projection of the same box predicts (up to a pixel's rounding along the rim).
    let ((diff, off_rim), dark, dark_planar) =
        inside_or_outside::<S>([0.1, 1.0, 0.0], [1.5, 0.0, 0.3]);
    assert!(dark > 500, "{} shadowed pixels", dark);
    assert!(dark_planar > 500);
    // (A count that missed the camera's own volume would invert the shadow: most pixels.)
    assert_eq!(
        off_rim, 0,
        "{diff} pixels differ, {off_rim} off the shadow's rim"
    );
    assert!(
        diff * 10 <= dark,
        "{diff} pixels differ of {dark} in shadow"
    );
    // The same from outside the volume.
    let ((diff, off_rim), dark, _) = inside_or_outside::<S>([1.5, 2.5, 2.0], [0.0, 0.2, 0.0]);
    assert!(dark > 200, "{dark}");
    assert_eq!(
        off_rim, 0,
        "{diff} pixels differ, {off_rim} off the shadow's rim"
    );
}

#[test]
fn the_camera_inside_a_volume_sees_what_the_projection_predicts() {
    camera_inside_a_volume::<Q>();
    camera_inside_a_volume::<f32>();
    camera_inside_a_volume::<f64>();
}

/// The two boxes under a slanted light: the small box's shadow falls on the large box's top
/// (one mesh shadows itself) and the large box's on the ground.
fn slanted<S: Scalar>() -> Frame<Rgb888> {
    let w = world::<S>(&[
        ([0.0, 3.0, 0.0], [0.5, 0.2, 0.5]),
        ([0.0, 0.5, 0.0], [2.0, 0.5, 2.0]),
    ]);
    // From above (up = −z).
    let cam = ortho([0.0, 10.0, 0.0], [0.0, 0.0, -1.0]);
    // Toward the light: up and toward −x, so shadows move +x by 0.5 per unit of drop.
    draw(&w, cam, [-0.5, 1.0, 0.0], How::Volume)
}

fn slanted_self_shadow<S: Scalar>() {
    let f = slanted::<S>();
    let red = Rgb888::new(220, 40, 40);
    let c = |v: u8| ((v as u32 * (255 - SHADOW as u32) + 127) / 255) as u8;
    let dark_red = Rgb888::new(c(220), c(40), c(40));
    let px = |wx: f64, wz: f64| f.get((48.0 + 8.0 * wx) as u32, (48.0 + 8.0 * wz) as u32);
    // The small box (top at y 3.2, bottom 2.8) over the large box's top (y 1): its shadow is
    // moved +x by 0.5·(2.8 − 1) = 0.9 to 0.5·(3.2 − 1) = 1.1: x from −0.5 + 0.9 to 0.5 + 1.1.
    assert_eq!(px(0.0, 0.0), red, "the small box's top is lit");
    assert_eq!(px(1.25, 0.0), dark_red, "its shadow on the large box");
    assert_eq!(px(1.25, 0.8), red, "beside the shadow, lit");
    assert_eq!(
        px(-1.5, 0.0),
        red,
        "the large box's top on the light's side, lit"
    );
    // The large box's shadow on the ground: +x by 0.5 per unit: up to x = 2 + 0.5.
    assert_eq!(
        px(2.25, 0.0),
        shadowed_ground(),
        "the large box's shadow on the ground"
    );
    assert_eq!(
        px(2.25, 2.5),
        Rgb888::new(GROUND[0], GROUND[1], GROUND[2]),
        "ground beside it, lit"
    );
    assert_eq!(
        px(-2.5, 0.0),
        Rgb888::new(GROUND[0], GROUND[1], GROUND[2]),
        "ground on the light's side, lit"
    );
}

#[test]
fn an_object_shadows_itself_and_the_ground() {
    slanted_self_shadow::<Q>();
    slanted_self_shadow::<f32>();
    slanted_self_shadow::<f64>();
}

/// A unit-coloured square facing the camera (an open mesh: its rim is its outline) at depth
/// `z`, half-size `h`, centred at (`cx`, `cy`).
fn facing_square<S: Scalar>(cx: f64, cy: f64, z: f64, h: f64) -> Vec<[S; 3]> {
    [
        [cx - h, cy - h, z],
        [cx + h, cy - h, z],
        [cx + h, cy + h, z],
        [cx - h, cy + h, z],
    ]
    .map(|p| p.map(S::from_f64))
    .to_vec()
}

const INK: [u8; 3] = [255, 255, 0];

/// A square (object 0) outlined in [`INK`], and in front of its right half, when `cover`, a
/// second square (object 1), from an orthographic camera down −z (1 unit = 8 px).
fn outlined<S: Scalar>(cover: bool) -> Frame<Rgb888> {
    let back = facing_square::<S>(0.0, 0.0, 0.0, 3.0);
    let front = facing_square::<S>(3.0, 0.0, 1.0, 2.0);
    let mut objects = vec![Object {
        mesh: Mesh::new(&back, &QUAD).unwrap(),
        transform: Mat4::identity(),
        material: unlit([0, 120, 0]),
    }];
    if cover {
        objects.push(Object {
            mesh: Mesh::new(&front, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit([0, 0, 200]),
        });
    }
    let cam = ortho([0.0, 0.0, 10.0], [0.0, 1.0, 0.0]);
    let scene = Scene::new(&objects, cam, [Light::white([S::ZERO, S::ZERO, S::ONE])]);
    let mut adjacency = [[0u16; 3]; 2];
    mesh_adjacency(&objects[0].mesh, &mut adjacency).unwrap();
    let adj = [Adjacency::new(&objects[0].mesh, &adjacency).unwrap()];
    let layering = Layering::<S>::none().with_outline(Outline::silhouette(&[0], &adj, INK));
    let mut r = Renderer::<S, Rgb888, { N as usize }, { N as usize }, 64, 64, 16>::new();
    let mut layers = Layers::<{ N as usize }, 1, 4, 16>::new();
    let mut f = Frame::new(N, N, Rgb888::BLACK);
    r.render_with(
        &scene,
        scanline3d::FrameOptions::new().layered(&layering, &mut layers),
        &mut f,
    )
    .unwrap();
    f.assert_each_written_once();
    f
}

fn outlines_are_one_pixel_and_hidden_behind_nearer_surfaces<S: Scalar>() {
    let ink = Rgb888::new(INK[0], INK[1], INK[2]);
    let f = outlined::<S>(false);
    // The square spans x, y in [−3, 3]: pixels 24..72. Each column crossed by the top and
    // bottom edges has exactly one ink pixel per edge, each row crossed by the left and
    // right edges one per edge.
    for x in 28..68 {
        let n = (0..N).filter(|&y| f.get(x, y) == ink).count();
        assert_eq!(n, 2, "column {x}");
    }
    for y in 28..68 {
        let n = (0..N).filter(|&x| f.get(x, y) == ink).count();
        assert_eq!(n, 2, "row {y}");
    }
    // Behind the second square (x from 1 to 5, y from −2 to 2: pixels 56..88 and 32..64), no
    // ink; above and below it, the outline as before.
    let g = outlined::<S>(true);
    for y in 33..63 {
        for x in 57..N {
            assert_ne!(
                g.get(x, y),
                ink,
                "({x}, {y}) shows an outline through a nearer square"
            );
        }
    }
    // Left of it, and above and below it, the same as without it.
    for y in 0..N {
        for x in 0..N {
            if x < 55 || !(31..65).contains(&y) {
                assert_eq!(g.get(x, y), f.get(x, y), "({x}, {y})");
            }
        }
    }
}

#[test]
fn outlines_are_one_pixel_wide_and_depth_correct() {
    outlines_are_one_pixel_and_hidden_behind_nearer_surfaces::<Q>();
    outlines_are_one_pixel_and_hidden_behind_nearer_surfaces::<f32>();
    outlines_are_one_pixel_and_hidden_behind_nearer_surfaces::<f64>();
}

#[test]
fn bad_volume_and_outline_layerings_are_named_errors() {
    let w = world::<f32>(&[([0.0, 2.0, 0.0], [0.6, 0.3, 0.6])]);
    let objects = [Object {
        mesh: Mesh::new(&w.caster, &w.caster_tris).unwrap(),
        transform: Mat4::identity(),
        material: unlit([220, 40, 40]),
    }];
    let scene = Scene::new(
        &objects,
        camera([3.0, 3.0, 3.0], [0.0, 0.0, 0.0]),
        [Light::white([0.0, 1.0, 0.0])],
    );
    let good = [Adjacency::new(&objects[0].mesh, &w.adjacency).unwrap()];
    // A table too short for its mesh is refused when it is checked; one checked against
    // another mesh (equal in content, other slices) by the frame.
    assert_eq!(
        Adjacency::new(&objects[0].mesh, &w.adjacency[1..]),
        Err(AdjacencyError::BufferTooSmall { needed: 12 })
    );
    let copy = w.caster.clone();
    let short = [Adjacency::new(&Mesh::new(&copy, &w.caster_tris).unwrap(), &w.adjacency).unwrap()];
    let volume = |adjacency, reach| VolumeShadow {
        light: ShadowLight::Directional([0.0, 1.0, 0.0]),
        reach,
        adjacency,
        color: [0; 3],
        alpha: 100,
    };
    let planar = PlanarShadow::new(
        [0.0, 1.0, 0.0, 0.0],
        ShadowLight::Directional([0.0, 1.0, 0.0]),
        100,
    );
    let run = |l: &Layering<'_, f32>| {
        let mut r = Renderer::<f32, Rgb888, { N as usize }, { N as usize }, 256, 256, 64>::new();
        let mut layers = Layers::<{ N as usize }, 1, 4, 128>::new();
        let mut f = Frame::new(N, N, Rgb888::BLACK);
        let e = r.render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(l, &mut layers),
            &mut f,
        );
        assert!(f.writes.iter().all(|&n| n == 0), "nothing drawn");
        e.err()
    };
    let both = Layering {
        shadow: Some(planar),
        ..Layering::volumes(&[0], volume(&good[..], 4.0))
    };
    assert_eq!(run(&both), Some(Error::Layers(LayerError::TwoShadows)));
    assert_eq!(
        run(&Layering::volumes(&[0], volume(&short[..], 4.0))),
        Some(Error::Layers(LayerError::Adjacency { object: 0 }))
    );
    assert_eq!(
        run(&Layering::volumes(&[0], volume(&[][..], 4.0))),
        Some(Error::Layers(LayerError::Adjacency { object: 0 }))
    );
    for reach in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(
            run(&Layering::volumes(&[0], volume(&good[..], reach))),
            Some(Error::Layers(LayerError::Reach))
        );
    }
    let dark = VolumeShadow {
        light: ShadowLight::Directional([0.0, 0.0, 0.0]),
        ..volume(&good[..], 4.0)
    };
    assert_eq!(
        run(&Layering::volumes(&[0], dark)),
        Some(Error::Layers(LayerError::Shadow))
    );
    assert_eq!(
        run(&Layering::volumes(&[3], volume(&good[..], 4.0))),
        Some(Error::Layers(LayerError::NoSuchObject { index: 3 }))
    );
    let outline = |objects| Outline::silhouette(objects, &good, INK);
    assert_eq!(
        run(&Layering::none().with_outline(outline(&[5]))),
        Some(Error::Layers(LayerError::NoSuchObject { index: 5 }))
    );
    assert_eq!(
        run(&Layering::none().with_outline(outline(&[0, 0]))),
        Some(Error::Layers(LayerError::Adjacency { object: 0 }))
    );
    // More triangles than the stencil line's bits (8 per pixel of a 1-line strip).
    let mut r = Renderer::<f32, Rgb888, 1, 1, 256, 256, 64>::new();
    let mut layers = Layers::<1, 1, 4, 128>::new();
    let mut f = Frame::new(1, 1, Rgb888::BLACK);
    assert_eq!(
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(
                &Layering::volumes(&[0], volume(&good[..], 4.0)),
                &mut layers
            ),
            &mut f
        )
        .err(),
        Some(Error::Layers(LayerError::TooManyTriangles {
            object: 0,
            triangles: 12,
            capacity: 8
        }))
    );
}

/// Shadow volumes, outlines and a translucent box in one frame, into embedded-graphics'
/// `MockDisplay` (its overdraw check on): every pixel is written exactly once.
fn every_pixel_once<S: Scalar>() {
    use embedded_graphics::mock_display::MockDisplay;
    let w = world::<S>(&[
        ([0.0, 3.0, 0.0], [0.5, 0.2, 0.5]),
        ([0.0, 0.5, 0.0], [2.0, 0.5, 2.0]),
    ]);
    let glass = world::<S>(&[([1.5, 2.0, 1.5], [0.4, 0.4, 0.4])]);
    let objects = [
        Object {
            mesh: Mesh::new(&w.ground, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: unlit(GROUND),
        },
        Object {
            mesh: Mesh::new(&w.caster, &w.caster_tris).unwrap(),
            transform: Mat4::identity(),
            material: unlit([220, 40, 40]),
        },
        Object {
            mesh: Mesh::new(&glass.caster, &glass.caster_tris).unwrap(),
            transform: Mat4::identity(),
            material: unlit::<S>([40, 40, 220]).translucent(120),
        },
    ];
    let cam = camera([4.0, 5.0, 6.0], [0.0, 0.5, 0.0]);
    let scene = Scene::new(
        &objects,
        cam,
        [Light::white([-0.5, 1.0, 0.3].map(S::from_f64))],
    );
    let adjacency = [Adjacency::new(&objects[1].mesh, &w.adjacency).unwrap()];
    let layering = Layering::volumes(
        &[1],
        VolumeShadow {
            light: ShadowLight::Directional([-0.5, 1.0, 0.3].map(S::from_f64)),
            reach: S::from_f64(8.0),
            adjacency: &adjacency,
            color: [0; 3],
            alpha: SHADOW,
        },
    )
    .with_outline(Outline::silhouette(&[1], &adjacency, INK));
    let mut r = Renderer::<S, Rgb888, 64, 64, 256, 256, 64>::new();
    let mut layers = Layers::<64, 1, 4, 128>::new();
    let mut display = MockDisplay::<Rgb888>::new();
    let stats = r
        .render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(&layering, &mut layers),
            &mut display,
        )
        .unwrap();
    assert!(stats.drawn > 0);
    let ink = Rgb888::new(INK[0], INK[1], INK[2]);
    let (mut inked, mut dark) = (0, 0);
    for y in 0..64 {
        for x in 0..64 {
            let p = display.get_pixel(Point::new(x, y));
            assert!(p.is_some(), "({x}, {y}) not written");
            inked += (p == Some(ink)) as u32;
            dark += (p == Some(shadowed_ground())) as u32;
        }
    }
    assert!(
        inked > 20 && dark > 20,
        "{inked} outline, {dark} shadowed pixels"
    );
}

#[test]
fn every_pixel_is_written_once_with_volumes_outlines_and_translucency() {
    every_pixel_once::<Q>();
    every_pixel_once::<f32>();
    every_pixel_once::<f64>();
}
