//! `Renderer::render_passes` (issue #20, part 4): a frame drawn in passes, each a piece of the
//! scene, into one strip over the whole viewport, is the frame `render` draws in one pass, and
//! its statistics add up; the preview uses it for models larger than any one renderer.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{Error, Stats};
use scanline3d_support::demo;

type Q = Fx<I16F16>;

/// One strip over 240 × 240 for the passes, a one-line strip for the reference (the image of a
/// frame is the same for every strip height).
type Layered<S, C> = Renderer<S, C, 240, 240, 1024, 1024, 128, 240>;
type OneLine<S, C> = Renderer<S, C, 240, 240, 1024, 1024, 128>;

/// A mesh's arrays, owned.
struct Piece<S> {
    positions: Vec<[S; 3]>,
    normals: Vec<[S; 3]>,
    indices: Vec<[u16; 3]>,
}

impl<S: Scalar> Piece<S> {
    fn mesh(&self) -> Mesh<'_, S> {
        Mesh::new(&self.positions, &self.indices)
            .unwrap()
            .with_normals(&self.normals)
            .unwrap()
    }
}

/// `mesh` cut into `k` pieces of consecutive triangles, each with only the vertices it uses.
fn pieces<S: Scalar>(mesh: &Mesh<'_, S>, k: usize) -> Vec<Piece<S>> {
    let (pos, nor, idx) = (mesh.positions(), mesh.normals().unwrap(), mesh.indices());
    let per = idx.len().div_ceil(k);
    idx.chunks(per)
        .map(|tris| {
            let mut map = vec![u16::MAX; pos.len()];
            let mut p = Piece {
                positions: Vec::new(),
                normals: Vec::new(),
                indices: Vec::new(),
            };
            for t in tris {
                p.indices.push(t.map(|i| {
                    let i = i as usize;
                    if map[i] == u16::MAX {
                        map[i] = p.positions.len() as u16;
                        p.positions.push(pos[i]);
                        p.normals.push(nor[i]);
                    }
                    map[i]
                }));
            }
            p
        })
        .collect()
}

fn scene<'a, S: Scalar>(objects: &'a [Object<'a, S>]) -> Scene<'a, S, 1> {
    let mut s = Scene::new(objects, demo::camera().unwrap(), demo::lights());
    s.background = [20, 30, 40];
    s
}

/// The torus in one pass and in `k` passes, with the given material, number type and colour:
/// the same pixels, and the passes' counts add up to the one pass's.
fn torus_in_passes<S: Scalar, C: TargetColor>(material: Material<S>, dither: bool, k: usize) {
    let shape = demo::torus::<S>().unwrap();
    let mesh = shape.mesh();
    for spin in [0.0, 37.0, 200.0] {
        let transform = demo::torus_transform(spin);
        let whole = [Object {
            mesh,
            transform,
            material,
        }];
        let mut one = Box::new(OneLine::<S, C>::new().with_dither(dither));
        let mut want = Frame::new(240, 240, C::from_channels([0; 3]));
        let st1 = one.render(&scene(&whole), &mut want).unwrap();

        let ps = pieces(&mesh, k);
        let objects: Vec<[Object<'_, S>; 1]> = ps
            .iter()
            .map(|p| {
                [Object {
                    mesh: p.mesh(),
                    transform,
                    material,
                }]
            })
            .collect();
        let scenes: Vec<_> = objects.iter().map(|o| scene(o)).collect();
        let mut r = Box::new(Layered::<S, C>::new().with_dither(dither));
        let mut got = Frame::new(240, 240, C::from_channels([0; 3]));
        let st = r.render_passes(&scenes, &mut got).unwrap();
        got.assert_each_written_once();
        let what = format!("{} {k} passes, spin {spin}, dither {dither}", S::NAME);
        assert!(got.px == want.px, "{what}: the pixels differ");
        for (name, f) in [
            (
                "triangles_in",
                (|s: &Stats| s.triangles_in) as fn(&Stats) -> u32,
            ),
            ("culled", |s| s.culled),
            ("outside", |s| s.outside),
            ("clipped", |s| s.clipped),
            ("degenerate", |s| s.degenerate),
            ("empty", |s| s.empty),
            ("drawn", |s| s.drawn),
            ("color_vertices", |s| s.color_vertices),
            ("fragments", |s| s.fragments),
        ] {
            assert_eq!(f(&st), f(&st1), "{what}: {name}");
        }
        // Each piece has its own copy of a vertex it shares with another.
        let copies: usize = ps.iter().map(|p| p.positions.len()).sum();
        assert_eq!(
            st.vertices as usize,
            st1.vertices as usize + copies - mesh.positions().len(),
            "{what}"
        );
        assert!(
            st.max_active <= st1.max_active && st.max_active > 0,
            "{what}"
        );
        // `stats()` is the last pass's.
        assert_eq!(
            r.stats().triangles_in as usize,
            ps.last().unwrap().indices.len()
        );
    }
}

#[test]
fn a_mesh_in_pieces_draws_the_pixels_of_one_pass() {
    let gouraud = demo::torus_material::<Q>();
    for k in [1, 2, 3, 7] {
        torus_in_passes::<Q, Rgb565>(gouraud, false, k);
    }
    torus_in_passes::<Q, Rgb565>(gouraud, true, 5);
    torus_in_passes::<Q, Rgb565>(gouraud.flat(), false, 4);
    torus_in_passes::<Q, Rgb565>(gouraud.specular(Q::from_f64(0.5), 20), true, 3);
    torus_in_passes::<f32, Rgb888>(demo::torus_material(), false, 6);
    torus_in_passes::<f64, Rgb565>(demo::torus_material::<f64>().flat(), true, 2);
}

/// Objects that hide each other, one per pass, in either order: the depth buffer is shared,
/// so the frame is the one-pass frame.
#[test]
fn objects_in_separate_passes_hide_each_other_as_in_one_pass() {
    let ball = Shape::<Q, 642, 1280>::icosphere(0.6, 3).unwrap();
    let ground = Shape::<Q, 289, 512>::terrain(4.0, 16, 0.4).unwrap();
    let objects = [
        Object {
            mesh: ground.mesh(),
            transform: Mat4::translate([0.0, -0.3, 0.0].map(Q::from_f64)),
            material: Material::matte([110, 180, 90], Q::from_f64(0.2), Q::from_f64(0.8)),
        },
        Object {
            mesh: ball.mesh(),
            transform: Mat4::translate([0.2, 0.1, 0.4].map(Q::from_f64)),
            material: Material::matte([200, 80, 80], Q::from_f64(0.2), Q::from_f64(0.8))
                .specular(Q::from_f64(0.4), 16),
        },
    ];
    let mut want = Frame::new(240, 240, Rgb565::BLACK);
    let mut one = Box::new(OneLine::<Q, Rgb565>::new());
    let st1 = one.render(&scene(&objects), &mut want).unwrap();
    let mut r = Box::new(Layered::<Q, Rgb565>::new());
    for order in [[0, 1], [1, 0]] {
        let singles = order.map(|i| [objects[i]]);
        let scenes = singles.each_ref().map(|o| scene(o));
        let mut got = Frame::new(240, 240, Rgb565::BLACK);
        let st = r.render_passes(&scenes, &mut got).unwrap();
        assert!(got.px == want.px, "order {order:?}: the pixels differ");
        assert_eq!((st.drawn, st.fragments), (st1.drawn, st1.fragments));
        // The ball hides part of the ground: drawn after it, it overwrites those pixels;
        // drawn first, the ground fails the depth test there.
        if order == [0, 1] {
            assert!(st.pixels_written >= st1.pixels_written, "{order:?}");
        } else {
            assert!(st.pixels_written < st1.pixels_written, "{order:?}");
        }
    }
}

/// The frame is cleared to the first scene's background; a viewport smaller than the renderer
/// is drawn at the origin and nothing beyond it is touched.
#[test]
fn background_and_viewport() {
    let shape = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let mut a = scene(&objects);
    let mut b = a;
    a.background = [255, 0, 0];
    b.background = [0, 0, 255];
    let mut r = Box::new(Layered::<Q, Rgb565>::new());
    r.set_viewport(120, 90);
    let mut got = Frame::new(240, 240, Rgb565::CSS_HOT_PINK);
    r.render_passes(&[a, b], &mut got).unwrap();
    assert_eq!(got.get(0, 0), Rgb565::RED);
    assert_eq!(got.get(119, 89), Rgb565::RED);
    assert_eq!(got.get(120, 0), Rgb565::CSS_HOT_PINK);
    assert_eq!(got.get(0, 90), Rgb565::CSS_HOT_PINK);
    let mut one = Box::new(OneLine::<Q, Rgb565>::new());
    one.set_viewport(120, 90);
    let mut want = Frame::new(240, 240, Rgb565::CSS_HOT_PINK);
    one.render(&a, &mut want).unwrap();
    // The same scene twice: the second pass draws nothing new (equal depths fail `Less`).
    assert!(got.px == want.px);
}

/// Errors come before anything is sent to the target, which is left as it was.
#[test]
fn errors_leave_the_target_untouched() {
    let shape = demo::torus::<Q>().unwrap();
    let objects = [demo::torus_object(&shape)];
    let s = scene(&objects);
    let untouched = |f: &Frame<Rgb565>| f.writes.iter().all(|&n| n == 0);

    // A strip shorter than the viewport: a clear error, unless the viewport is made to fit.
    let mut short = Box::new(Renderer::<Q, Rgb565, 240, 240, 1024, 1024, 128, 60>::new());
    let mut f = Frame::new(240, 240, Rgb565::BLACK);
    let e = short.render_passes(&[s, s], &mut f).unwrap_err();
    assert_eq!(
        e,
        Error::StripTooShort {
            lines: 60,
            height: 240
        }
    );
    let msg = e.to_string();
    for part in ["60 lines", "240 rows", "LINES", "nothing was drawn"] {
        assert!(msg.contains(part), "{msg:?} lacks {part:?}");
    }
    assert!(untouched(&f));
    short.set_viewport(240, 60);
    assert!(short.render_passes(&[s], &mut f).is_ok());

    // No passes: nothing drawn.
    let mut r = Box::new(Layered::<Q, Rgb565>::new());
    let mut f = Frame::new(240, 240, Rgb565::BLACK);
    assert_eq!(r.render_passes::<_, 1>(&[], &mut f), Ok(Stats::default()));
    assert!(untouched(&f));

    // A target smaller than the viewport.
    let mut small = Frame::new(100, 240, Rgb565::BLACK);
    assert!(matches!(
        r.render_passes(&[s], &mut small),
        Err(Error::TargetTooSmall { .. })
    ));
    assert!(untouched(&small));

    // A pass that does not fit: the first pass fits, the second (the torus twice) does not.
    let twice = [objects[0], objects[0]];
    let too_big = scene(&twice);
    let mut tiny = Box::new(Renderer::<Q, Rgb565, 240, 240, 600, 600, 64, 240>::new());
    let mut f = Frame::new(240, 240, Rgb565::BLACK);
    assert!(matches!(
        tiny.render_passes(&[s, too_big], &mut f),
        Err(Error::Shortfall(_))
    ));
    assert!(untouched(&f));
    // Missing normals in a pass.
    let bare = Mesh::new(shape.positions.as_slice(), shape.indices.as_slice()).unwrap();
    let no_normals = [Object {
        mesh: bare,
        ..objects[0]
    }];
    assert!(matches!(
        tiny.render_passes(&[s, scene(&no_normals)], &mut f),
        Err(Error::MissingNormals { object: 0 })
    ));
    assert!(untouched(&f));
}
