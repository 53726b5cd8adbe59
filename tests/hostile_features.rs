//! Hostile inputs to the newer features (issue #40): adjacency tables, volume casters and
//! outlined objects with bad indices or garbage tables, textured shapes with huge counts, an
//! overlay far larger than the screen, a volume reach far beyond the scene, invalid lights and
//! rotation angles, a viewport changed under a prepared frame, NaN vertex normals. Each case
//! was a panic, a hang or a silent wrong image before its fix; each runs in every number type
//! it concerns, under a time limit, in debug (overflow checks on) and release.

use std::sync::mpsc;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use scanline3d::prelude::*;
use scanline3d::{
    errors::AdjacencyError, errors::LayerError, errors::MeshError, errors::ShapeError,
    mesh::check_adjacency, mesh::mesh_adjacency, mesh::Adjacency, mesh::NO_NEIGHBOUR,
    shadow::Layering, shadow::Outline, shadow::ShadowLight, shadow::VolumeShadow, Effects, Error,
    Layers, PointLight, Stats, TexturedShape,
};

type Q = Fx<scanline3d::fixed::types::I16F16>;

/// Runs `f` on its own thread and fails if it panics or takes more than `secs` seconds.
fn limited<T: Send + 'static>(what: &str, secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    match rx.recv_timeout(Duration::from_secs(secs)) {
        Ok(v) => v,
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("{what}: no result within {secs} s"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("{what}: panicked"),
    }
}

/// A plain `W × H` target.
#[derive(Debug)]
struct Frame<C> {
    w: u32,
    h: u32,
    px: Vec<C>,
}

impl<C: PixelColor> Frame<C> {
    fn new(w: u32, h: u32, fill: C) -> Self {
        Frame {
            w,
            h,
            px: vec![fill; (w * h) as usize],
        }
    }
}

impl<C: PixelColor> OriginDimensions for Frame<C> {
    fn size(&self) -> Size {
        Size::new(self.w, self.h)
    }
}

impl<C: PixelColor> DrawTarget for Frame<C> {
    type Color = C;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, it: I) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.w && (p.y as u32) < self.h {
                self.px[(p.y as u32 * self.w + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

fn v<S: Scalar>(a: [f64; 3]) -> [S; 3] {
    a.map(S::from_f64)
}

fn camera<S: Scalar>(eye: &[f64; 3]) -> Camera<S> {
    Camera::look_at(
        v(*eye),
        v([0.0, 0.0, 0.0]),
        v([0.0, 1.0, 0.0]),
        Projection::Perspective {
            fov_y: S::from_f64(0.9),
            near: S::from_f64(0.1),
            far: S::from_f64(30.0),
        },
    )
    .unwrap()
}

// ---------------------------------------------------------------- adjacency tables

#[test]
fn mesh_adjacency_refuses_an_index_out_of_range() {
    // Was: index out of bounds at volume.rs:121.
    let pos: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let idx = [[0u16, 1, 9], [0, 2, 1]];
    let mesh = Mesh::new(&pos, &idx).unwrap();
    let mut out = [[0u16; 3]; 2];
    let e = mesh_adjacency(&mesh, &mut out).unwrap_err();
    assert_eq!(
        e,
        AdjacencyError::IndexOutOfRange {
            triangle: 0,
            index: 9
        }
    );
    assert!(e.to_string().contains("vertex 9"), "{e}");
    let q: Vec<[Q; 3]> = pos.iter().map(|p| p.map(Q::from_f32)).collect();
    let qmesh = Mesh::new(&q, &idx).unwrap();
    assert!(mesh_adjacency(&qmesh, &mut out).is_err());
}

/// Positions, triangles and adjacency table of a mesh.
type Parts<S> = (Vec<[S; 3]>, Vec<[u16; 3]>, Vec<[u16; 3]>);

/// A closed tetrahedron and its adjacency table.
fn tetra<S: Scalar>() -> Parts<S> {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]
    .map(|a| v::<S>([a[0] - 0.3, a[1] + 0.2, a[2] - 0.3]))
    .to_vec();
    let t = vec![[0u16, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut adj = vec![[0u16; 3]; 4];
    assert_eq!(
        mesh_adjacency(&Mesh::new(&p, &t).unwrap(), &mut adj).unwrap(),
        0
    );
    (p, t, adj)
}

/// A layered frame of a ground quad and a tetrahedron (`pos`, `tris`, its table `adj`),
/// shadowed by volumes or outlined.
fn layered<S: Scalar>(
    pos: &[[S; 3]],
    tris: &[[u16; 3]],
    adj: &[[u16; 3]],
    volume: bool,
    reach: f64,
) -> Result<(Stats, Frame<Rgb888>), String> {
    let caster = Mesh::new(pos, tris).unwrap();
    // The table is checked against its mesh once, here (it was checked by every frame, and
    // before that only its length was).
    let table = Adjacency::new(&caster, adj).map_err(|e| format!("adjacency: {e:?} ({e})"))?;
    let ground = [
        [-3.0, 0.0, 3.0],
        [3.0, 0.0, 3.0],
        [3.0, 0.0, -3.0],
        [-3.0, 0.0, -3.0],
    ]
    .map(|a| v::<S>([a[0], a[1] - 0.5, a[2]]));
    let quad = [[0u16, 1, 2], [0, 2, 3]];
    let objects = [
        Object {
            mesh: Mesh::new(&ground, &quad).unwrap(),
            transform: Mat4::identity(),
            material: Material::unlit([200, 200, 200]),
        },
        Object {
            mesh: caster,
            transform: Mat4::identity(),
            material: Material::unlit([220, 40, 40]),
        },
    ];
    let light = v::<S>([0.3, 1.0, 0.2]);
    let scene = Scene::new(&objects, camera(&[2.0, 3.0, 4.0]), [Light::white(light)]);
    let tables = [table];
    let layering = if volume {
        Layering::volumes(
            &[1],
            VolumeShadow {
                light: ShadowLight::Directional(light),
                reach: S::from_f64(reach),
                adjacency: &tables,
                color: [0; 3],
                alpha: 160,
            },
        )
    } else {
        Layering::none().with_outline(Outline::silhouette(&[1], &tables, [0, 0, 255]))
    };
    let mut r = Box::new(Renderer::<S, Rgb888, 64, 64, 256, 256, 64>::new());
    let mut layers = Box::new(Layers::<64, 1, 16, 64>::new());
    let mut f = Frame::new(64, 64, Rgb888::BLACK);
    let stats = r
        .render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(&layering, &mut layers),
            &mut f,
        )
        .map_err(|e| format!("render: {e:?}"))?;
    Ok((stats, f))
}

fn bad_tables_for<S: Scalar>() {
    let (p, t, adj) = tetra::<S>();
    for volume in [true, false] {
        let (s, _) = layered(&p, &t, &adj, volume, 8.0).unwrap();
        assert!(s.drawn > 0 && s.invalid == 0, "{s:?}");
        // An index out of range with a table of the right length: was index out of bounds at
        // volume.rs:348.
        let mut bad = t.clone();
        bad[2][1] = 40;
        let e = layered(&p, &bad, &adj, volume, 8.0).unwrap_err();
        assert!(
            e.starts_with("adjacency: IndexOutOfRange { triangle: 2, index: 40 }"),
            "{e}"
        );
        // Garbage tables of the right length: were accepted (wrong silhouettes, silently).
        let garbage: [Vec<[u16; 3]>; 4] = [
            vec![[7, 7, 7]; 4], // neighbours that do not exist
            vec![[1, 2, 3]; 4], // neighbours that are not across the edge
            {
                let mut a = adj.clone();
                a[0].swap(0, 1); // two edges' neighbours exchanged
                a
            },
            {
                let mut a = adj.clone();
                a[3][0] = 3; // a triangle its own neighbour
                a
            },
        ];
        for g in &garbage {
            let e = layered(&p, &t, g, volume, 8.0).unwrap_err();
            assert!(e.starts_with("adjacency: Mismatch"), "{g:?}: {e}");
            assert!(e.contains("mesh_adjacency"), "{e}");
        }
        // Open edges are taken as given.
        let open = vec![[NO_NEIGHBOUR; 3]; 4];
        assert!(check_adjacency(&Mesh::new(&p, &t).unwrap(), &open).is_ok());
    }
}

/// A table checked against one mesh, given for an object with another (equal in content, other
/// slices): refused by the frame, by name.
fn other_mesh_for<S: Scalar>() {
    let (p, t, adj) = tetra::<S>();
    let (p2, t2) = (p.clone(), t.clone());
    let table = Adjacency::new(&Mesh::new(&p, &t).unwrap(), &adj).unwrap();
    assert!(!table.is_for(&Mesh::new(&p2, &t2).unwrap()));
    let objects = [Object {
        mesh: Mesh::new(&p2, &t2).unwrap(),
        transform: Mat4::identity(),
        material: Material::unlit([220, 40, 40]),
    }];
    let light = v::<S>([0.3, 1.0, 0.2]);
    let scene = Scene::new(&objects, camera(&[2.0, 3.0, 4.0]), [Light::white(light)]);
    let tables = [table];
    let layering = Layering::none().with_outline(Outline::silhouette(&[0], &tables, [0, 0, 255]));
    let mut r = Box::new(Renderer::<S, Rgb888, 64, 64, 256, 256, 64>::new());
    let mut layers = Box::new(Layers::<64, 1, 16, 64>::new());
    let mut f = Frame::new(64, 64, Rgb888::BLACK);
    let e = r
        .render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(&layering, &mut layers),
            &mut f,
        )
        .unwrap_err();
    assert!(
        matches!(e, Error::Layers(LayerError::Adjacency { object: 0 })),
        "{e:?}"
    );
}

#[test]
fn bad_indices_and_garbage_adjacency_tables_are_named_errors() {
    limited("bad tables", 60, || {
        bad_tables_for::<Q>();
        bad_tables_for::<f32>();
        bad_tables_for::<f64>();
        other_mesh_for::<Q>();
        other_mesh_for::<f32>();
    });
}

#[test]
fn mesh_creases_refuses_a_table_that_is_not_the_meshs() {
    let (p, t, adj) = tetra::<f32>();
    let mesh = Mesh::new(&p, &t).unwrap();
    let mut bits = [0u8; 2];
    assert_eq!(
        scanline3d::mesh::mesh_creases(&mesh, &adj, 30.0, &mut bits),
        Ok(6)
    );
    let e = scanline3d::mesh::mesh_creases(&mesh, &[[9, 9, 9]; 4], 30.0, &mut bits).unwrap_err();
    assert!(matches!(e, AdjacencyError::Mismatch { .. }), "{e:?}");
}

// ---------------------------------------------------------------- textured shapes

#[test]
fn textured_torus_with_huge_counts_reports_an_overflowing_count() {
    // Was: add overflow at textured_shapes.rs:70 in debug, and in release
    // `Capacity { vertices: Some(0) }`, a wrong figure.
    for (nu, nv) in [(usize::MAX, 3), (3, usize::MAX), (usize::MAX, usize::MAX)] {
        let e = TexturedShape::<Q, 64, 64>::torus(1.0, 0.4, nu, nv).unwrap_err();
        assert!(
            matches!(e, ShapeError::Capacity { vertices: None, .. }),
            "{nu} {nv}: {e:?}"
        );
    }
}

// ---------------------------------------------------------------- overlays

fn lone_triangle<S: Scalar>() -> ([[S; 3]; 3], [[u16; 3]; 1]) {
    (
        [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.0, 0.5, 0.0]].map(v::<S>),
        [[0, 1, 2]],
    )
}

#[test]
fn an_overlay_far_larger_than_the_screen_costs_only_its_pixels_on_screen() {
    // Was: no end (time grew with the drawable's size: 10⁷ px took 8.5 s in release).
    let elapsed = limited("huge overlay", 30, || {
        let (p, t) = lone_triangle::<f32>();
        let objects = [Object {
            mesh: Mesh::new(&p, &t).unwrap(),
            transform: Mat4::identity(),
            material: Material::unlit([0, 200, 0]),
        }];
        let scene = Scene::new(
            &objects,
            camera(&[0.0, 0.0, 3.0]),
            [Light::white(v([0.0, 0.0, 1.0]))],
        );
        let mut r = Box::new(Renderer::<f32, Rgb565, 64, 64, 16, 16, 8>::new());
        let mut f = Frame::new(64, 64, Rgb565::BLACK);
        // A stroked rectangle 2·10⁹ px wide and 40 px high, centred on the screen.
        let huge = Rectangle::with_center(Point::new(32, 32), Size::new(2_000_000_000, 40))
            .into_styled(PrimitiveStyle::with_stroke(Rgb565::RED, 3));
        let start = Instant::now();
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().overlay(&huge),
            &mut f,
        )
        .unwrap();
        let took = start.elapsed();
        // The stroke's top and bottom edges (3 rows each) cross the whole screen; its left and
        // right edges are off screen; the triangle shows in the middle.
        let red_rows = (0..64)
            .filter(|y| (0..64).all(|x| f.px[y * 64 + x] == Rgb565::RED))
            .count();
        assert_eq!(red_rows, 6);
        let mid = f.px[32 * 64 + 32];
        assert!(f.px[32 * 64] != Rgb565::RED && mid != Rgb565::RED && mid != Rgb565::BLACK);
        // fill_contiguous on a strip: an area starting above, clipped on every side.
        let mut g = Frame::new(64, 64, Rgb565::BLACK);
        let grad = Gradient;
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().overlay(&grad),
            &mut g,
        )
        .unwrap();
        for (y, x) in [(0usize, 0usize), (5, 9), (63, 63), (20, 40)] {
            let want = ((x as i64 + 10) + (y as i64 + 7) * 1000) % 31;
            assert_eq!(
                g.px[y * 64 + x],
                Rgb565::new(want as u8, 0, 0),
                "({x}, {y})"
            );
        }
        took
    });
    assert!(elapsed < Duration::from_secs(5), "{elapsed:?}");
}

/// A drawable that fills a 1000 × 1000 area at (−10, −7) with colours by position through
/// `fill_contiguous`.
struct Gradient;

impl Drawable for Gradient {
    type Color = Rgb565;
    type Output = ();
    fn draw<D: DrawTarget<Color = Rgb565>>(&self, target: &mut D) -> Result<(), D::Error> {
        let area = Rectangle::new(Point::new(-10, -7), Size::new(1000, 1000));
        let colors = (0..1000i64 * 1000).map(|i| {
            let (x, y) = (i % 1000, i / 1000);
            Rgb565::new(((x + y * 1000) % 31) as u8, 0, 0)
        });
        target.fill_contiguous(&area, colors)
    }
}

// ---------------------------------------------------------------- volume reach

fn far_reach_for<S: Scalar>() -> usize {
    let (p, t, adj) = tetra::<S>();
    let (near, a) = layered(&p, &t, &adj, true, 8.0).unwrap();
    let (far, b) = layered(&p, &t, &adj, true, 30_000.0).unwrap();
    // Was, in Q16.16 from a reach of about 20 000: triangles counted invalid, the caster dark,
    // no ground shadow.
    assert_eq!((near.invalid, far.invalid), (0, 0), "{}", S::NAME);
    let shadowed = a.px.iter().filter(|c| c.r() < 150 && c.g() < 150).count();
    assert!(shadowed > 50, "{}: a shadow on the ground", S::NAME);
    let differ = a.px.iter().zip(&b.px).filter(|(x, y)| x != y).count();
    // The same closed volume around every visible point: only rounding along the shadow's
    // edge (the side faces' depths interpolated over larger triangles) may differ.
    assert!(
        differ * 50 <= shadowed,
        "{}: {differ} of {shadowed} shadow pixels differ between reach 8 and 30 000",
        S::NAME
    );
    differ
}

#[test]
fn a_volume_reach_far_beyond_the_scene_gives_the_same_shadow() {
    limited("far reach", 60, || {
        let differ = [
            far_reach_for::<Q>(),
            far_reach_for::<f32>(),
            far_reach_for::<f64>(),
        ];
        eprintln!("pixels that differ between reach 8 and 30 000 (Q16.16, f32, f64): {differ:?}");
    });
}

// ---------------------------------------------------------------- lights and angles

fn point_light_for<S: Scalar>(position: [f64; 3], attenuation: [f64; 3]) -> Result<Stats, String> {
    let (p, t) = lone_triangle::<S>();
    let n = [v::<S>([0.0, 0.0, 1.0]); 3];
    let objects = [Object {
        mesh: Mesh::new(&p, &t).unwrap().with_normals(&n).unwrap(),
        transform: Mat4::identity(),
        material: Material::matte([200, 200, 200], S::from_f64(0.2), S::from_f64(0.8)),
    }];
    let lamps = [PointLight {
        position: v(position),
        color: [255, 255, 255],
        attenuation: attenuation.map(S::from_f64),
    }];
    let effects = Effects {
        point_lights: &lamps,
        fog: None,
        tone: None,
    };
    let scene = Scene::new(
        &objects,
        camera(&[0.0, 0.0, 3.0]),
        [Light::white(v([0.0, 0.0, 1.0]))],
    )
    .with_effects(&effects);
    let mut r = Box::new(Renderer::<S, Gray8, 32, 32, 16, 16, 8>::new());
    let mut f = Frame::new(32, 32, Gray8::BLACK);
    r.render(&scene, &mut f).map_err(|e| e.to_string())
}

#[test]
fn an_invalid_point_light_is_refused() {
    // Was: every triangle counted invalid, the background only, `Ok`.
    fn each<S: Scalar>() {
        assert!(point_light_for::<S>([1.0, 1.0, 2.0], [1.0, 0.0, 0.0]).is_ok());
        for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e30] {
            for (pos, att) in [
                ([bad, 1.0, 1.0], [1.0, 0.0, 0.0]),
                ([1.0, 1.0, 1.0], [1.0, bad, 0.0]),
            ] {
                if S::NAME != "Q16.16" && bad == 1e30 {
                    continue; // a float holds 1e30
                }
                let e = point_light_for::<S>(pos, att).unwrap_err();
                assert!(e.contains("point light 0"), "{} {bad}: {e}", S::NAME);
            }
        }
    }
    each::<Q>();
    each::<f32>();
    each::<f64>();
}

#[test]
fn a_rotation_by_an_invalid_angle_is_an_invalid_transform() {
    // Was, in Q16.16: the object drawn at an arbitrary angle (f32 skipped it).
    fn each<S: Scalar>(angle: S) -> Stats {
        let (p, t) = lone_triangle::<S>();
        let objects = [Object {
            mesh: Mesh::new(&p, &t).unwrap(),
            transform: Mat4::rotate_y(angle),
            material: Material::unlit([255, 255, 255]),
        }];
        let scene = Scene::new(
            &objects,
            camera(&[0.0, 0.0, 3.0]),
            [Light::white(v([0.0, 0.0, 1.0]))],
        );
        let mut r = Box::new(Renderer::<S, Gray8, 32, 32, 16, 16, 8>::new());
        r.render(&scene, &mut Frame::new(32, 32, Gray8::BLACK))
            .unwrap()
    }
    for bad in [f64::NAN, f64::INFINITY, 1e30] {
        let s = each(Q::from_f64(bad));
        assert_eq!((s.invalid, s.drawn), (1, 0), "Q16.16 {bad}: {s:?}");
        for (x, y) in [
            (Mat4::<Q>::rotate_x(Q::from_f64(bad)), 1),
            (Mat4::<Q>::rotate_z(Q::from_f64(bad)), 0),
        ] {
            assert!(!x.m[y][y].is_valid(), "{bad}");
        }
    }
    let s = each(f32::NAN);
    assert_eq!((s.invalid, s.drawn), (1, 0), "f32: {s:?}");
    // A valid angle still draws.
    assert_eq!(each(Q::from_f64(0.3)).drawn, 1);
}

// ---------------------------------------------------------------- viewport and normals

#[test]
fn a_viewport_changed_under_a_prepared_frame_applies_to_the_next_one() {
    // Was: `render_strip` returned `Ok(None)` at once, the prepared frame dropped silently.
    // A prepared frame now holds the renderer, so the viewport changes between frames: a
    // frame left half drawn keeps its own, and the next one is prepared for the new one.
    let (p, t) = lone_triangle::<Q>();
    let objects = [Object {
        mesh: Mesh::new(&p, &t).unwrap(),
        transform: Mat4::identity(),
        material: Material::unlit([255, 255, 255]),
    }];
    let scene = Scene::new(
        &objects,
        camera(&[0.0, 0.0, 3.0]),
        [Light::white(v([0.0, 0.0, 1.0]))],
    );
    let mut whole = Box::new(Renderer::<Q, Gray8, 32, 32, 16, 16, 8>::new());
    let mut want = Frame::new(32, 32, Gray8::BLACK);
    whole.render(&scene, &mut want).unwrap();
    let mut r = Box::new(Renderer::<Q, Gray8, 32, 32, 16, 16, 8>::new());
    let mut f = Frame::new(32, 32, Gray8::BLACK);
    let mut frame = r.prepare(&scene, scanline3d::FrameOptions::new()).unwrap();
    let mut rows = 0;
    while let Some(strip) = frame.strip_to(&mut f).unwrap() {
        rows += strip.len();
        if rows == 16 {
            break;
        }
    }
    r.set_viewport(10, 10);
    assert_eq!(r.viewport(), (10, 10));
    // The half-drawn frame was prepared for 32 × 32: its geometry stays, drawable by strip
    // passes, whose rows are the whole frame's. (Was: a strip pass sent the strips at the
    // width asked for since, 10 columns of the frame's 32.)
    let mut pass: Box<scanline3d::StripPass<Gray8, 32, 8, 4>> = Box::default();
    pass.begin(&*r, 16..32).unwrap();
    while let Some(strip) = pass.render_strip(&*r, &mut f).unwrap() {
        rows += strip.len();
    }
    assert_eq!(rows, 32, "the prepared frame is drawn whole");
    assert!(f.px == want.px);
    // The next frame is 10 × 10.
    let mut small = Frame::new(32, 32, Gray8::new(7));
    r.render(&scene, &mut small).unwrap();
    assert!(small.px[11 * 32 + 11] == Gray8::new(7) && small.px[0] != Gray8::new(7));
}

#[test]
fn a_nan_vertex_normal_is_refused_when_the_mesh_is_built() {
    // Was: drawn, not counted invalid.
    let (p, t) = lone_triangle::<f32>();
    let mut n = [[0.0f32, 0.0, 1.0]; 3];
    n[1][2] = f32::NAN;
    let e = Mesh::new(&p, &t).unwrap().with_normals(&n).unwrap_err();
    assert_eq!(e, MeshError::InvalidNormal { vertex: 1 });
    assert!(e.to_string().contains("vertex 1"));
    let q = [[Q::ZERO, Q::ZERO, Q::from_f64(f64::INFINITY)]; 3];
    let (qp, qt) = lone_triangle::<Q>();
    assert!(Mesh::new(&qp, &qt).unwrap().with_normals(&q).is_err());
}

// ---------------------------------------------------------------- every type, every effect

/// One hostile number `bad` through each newer feature of a frame in `S` into `C`: a volume's
/// reach, a point light, a fog, a tone map's exposure, and the painter's renderer (no depth
/// lines) with a bad vertex. Each is `Ok` with every pixel written once, or a named error;
/// never a panic, a hang, or an `Ok` frame with nothing drawn but the background when the
/// geometry is valid.
fn sweep_for<S: Scalar, C>(bad: f64)
where
    C: scanline3d::TargetColor + PixelColor + Default + PartialEq + std::fmt::Debug,
{
    let label = format!("{} {bad}", S::NAME);
    let (p, t, adj) = tetra::<S>();
    let ground = [
        [-3.0, -0.5, 3.0],
        [3.0, -0.5, 3.0],
        [3.0, -0.5, -3.0],
        [-3.0, -0.5, -3.0],
    ]
    .map(v::<S>);
    let quad = [[0u16, 1, 2], [0, 2, 3]];
    let objects = [
        Object {
            mesh: Mesh::new(&ground, &quad).unwrap(),
            transform: Mat4::identity(),
            material: Material::matte([200, 200, 200], S::from_f64(0.3), S::from_f64(0.7)).flat(),
        },
        Object {
            mesh: Mesh::new(&p, &t).unwrap(),
            transform: Mat4::identity(),
            material: Material::matte([220, 40, 40], S::from_f64(0.3), S::from_f64(0.7)).flat(),
        },
    ];
    let light = v::<S>([0.3, 1.0, 0.2]);
    let base = Scene::new(&objects, camera(&[2.0, 3.0, 4.0]), [Light::white(light)]);
    let tables = [Adjacency::new(&objects[1].mesh, &adj).unwrap()];
    let mut r = Box::new(Renderer::<S, C, 48, 48, 256, 256, 64>::new());
    let mut layers = Box::new(Layers::<48, 1, 16, 64>::new());
    let drawn = |f: &Frame<C>| f.px.iter().any(|c| *c != C::default());
    // A volume's reach: refused (`LayerError::Reach`) or drawn whole.
    let layering = Layering::volumes(
        &[1],
        VolumeShadow {
            light: ShadowLight::Directional(light),
            reach: S::from_f64(bad),
            adjacency: &tables,
            color: [0; 3],
            alpha: 160,
        },
    );
    let mut f = Frame::new(48, 48, C::default());
    match r.render_with(
        &base,
        scanline3d::FrameOptions::new().layered(&layering, &mut layers),
        &mut f,
    ) {
        Ok(s) => assert!(s.invalid == 0 && drawn(&f), "{label} reach: {s:?}"),
        Err(e) => assert!(
            matches!(e, Error::Layers(LayerError::Reach)),
            "{label} reach: {e:?}"
        ),
    }
    // A point light, a fog and a tone map with the number: refused by name or drawn.
    let lamps = [PointLight {
        position: v([bad, 1.0, 1.0]),
        color: [255, 200, 100],
        attenuation: [1.0, 0.0, 0.0].map(S::from_f64),
    }];
    let cases: [(Effects<'_, S>, &str); 3] = [
        (
            Effects {
                point_lights: &lamps,
                fog: None,
                tone: None,
            },
            "point light",
        ),
        (
            Effects {
                point_lights: &[],
                fog: Some(scanline3d::Fog::linear(
                    S::from_f64(1.0),
                    S::from_f64(bad),
                    [9; 3],
                )),
                tone: None,
            },
            "fog",
        ),
        (
            Effects {
                point_lights: &[],
                fog: None,
                tone: Some(
                    scanline3d::ToneMap::new(scanline3d::tone::ToneCurve::Reinhard)
                        .with_exposure(S::from_f64(bad)),
                ),
            },
            "tone map",
        ),
    ];
    for (effects, what) in &cases {
        let mut f = Frame::new(48, 48, C::default());
        match r.render(&base.with_effects(effects), &mut f) {
            // (An exposure of 10⁻³⁰ draws every pixel black: written, the colour of nothing.)
            Ok(s) => assert!(
                s.invalid == 0 && s.pixels_written > 1000,
                "{label} {what}: {s:?}"
            ),
            Err(e) => assert!(
                matches!(e, Error::Light { .. } | Error::Fog | Error::Tone { .. }),
                "{label} {what}: {e:?}"
            ),
        }
    }
    // The painter's renderer (no depth lines) with the number in a vertex: that triangle
    // skipped and counted, the others drawn.
    let mut q = p.clone();
    q[3][0] = S::from_f64(bad);
    let objects = [Object {
        mesh: Mesh::new(&q, &t).unwrap(),
        transform: Mat4::identity(),
        material: Material::unlit([220, 40, 40]),
    }];
    let scene = Scene::new(&objects, camera(&[2.0, 3.0, 4.0]), [Light::white(light)]);
    let mut painter = Box::new(scanline3d::NoDepthRenderer::<S, C, 48, 48, 64, 64, 16>::new());
    let mut f = Frame::new(48, 48, C::default());
    let s = painter.render(&scene, &mut f).unwrap();
    if q[3][0].is_valid() {
        // (A Q16.16 vertex at 3·10⁴ overflows clip space: counted too, see the closing note of
        // issue #40.)
        assert!(
            s.invalid <= 3 && s.triangles_in == 4,
            "{label} painter: {s:?}"
        );
    } else {
        assert!(
            s.invalid == 3 && s.triangles_in == 4,
            "{label} painter: {s:?}"
        );
    }
}

#[test]
fn hostile_numbers_through_every_newer_feature_in_every_type() {
    limited("sweep", 120, || {
        for bad in [
            0.0,
            -1.0,
            1e-30,
            3e4,
            1e30,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
        ] {
            sweep_for::<Q, Rgb565>(bad);
            sweep_for::<Q, Rgb888>(bad);
            sweep_for::<Q, Gray8>(bad);
            sweep_for::<f32, Rgb565>(bad);
            sweep_for::<f32, Rgb888>(bad);
            sweep_for::<f32, Gray8>(bad);
            sweep_for::<f64, Rgb565>(bad);
            sweep_for::<f64, Gray8>(bad);
        }
    });
}
