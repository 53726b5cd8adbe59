//! The frame API (`Renderer::prepare`, `FrameOptions`, `Frame`): the three sinks give the same
//! pixels for plain and layered frames, with and without an overlay; a probe lent to a frame
//! hears the frame start and end once each, also when the frame fails; a dropped frame is
//! picked up again where it stopped (`Renderer::prepared`), a layered one is not.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use scanline3d::prelude::*;
use scanline3d::probe::{Probe, Stage};
use scanline3d::{shadow::Layering, shadow::PlanarShadow, shadow::ShadowLight, Error, Layers};

type Q = Fx<scanline3d::fixed::types::I16F16>;
type R = Renderer<Q, Rgb565, 64, 64, 64, 64, 16, 4>;
type L = Layers<64, 4, 4, 16>;

const GROUND: [[f64; 3]; 4] = [
    [-2.0, 0.0, 2.0],
    [2.0, 0.0, 2.0],
    [2.0, 0.0, -2.0],
    [-2.0, 0.0, -2.0],
];
const CASTER: [[f64; 3]; 4] = [
    [-1.0, 1.0, 0.5],
    [0.5, 1.0, 0.5],
    [0.5, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
];
const QUAD: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// Calls `f` with a renderer, a scene of the ground (a shadow receiver) and a square of
/// opacity `alpha` above it, seen from above at an angle, and a layering that shadows the
/// ground with the square.
fn with_scene<T>(alpha: u8, f: impl FnOnce(&mut R, &Scene<'_, Q, 1>, &Layering<'_, Q>) -> T) -> T {
    let ground = GROUND.map(|p| p.map(Q::from_f64));
    let caster = CASTER.map(|p| p.map(Q::from_f64));
    let objects = [
        Object {
            mesh: Mesh::new(&ground, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: Material::matte([200, 200, 200], Q::lit(0.3), Q::lit(0.7)).flat(),
        },
        Object {
            mesh: Mesh::new(&caster, &QUAD).unwrap(),
            transform: Mat4::identity(),
            material: Material::matte([220, 40, 40], Q::lit(0.3), Q::lit(0.7))
                .flat()
                .translucent(alpha),
        },
    ];
    let camera = Camera::look_at(
        [0.0, 5.0, 3.0].map(Q::from_f64),
        [Q::ZERO; 3],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: Q::lit(0.9),
            near: Q::lit(0.5),
            far: Q::lit(20.0),
        },
    )
    .unwrap();
    let light = [0.3, 1.0, 0.2].map(Q::from_f64);
    let scene = Scene::new(&objects, camera, [Light::white(light)]).with_background([10, 20, 30]);
    let plane = [Q::ZERO, Q::ONE, Q::ZERO, Q::ZERO];
    let shadow = PlanarShadow::new(plane, ShadowLight::Directional(light), 140);
    let layering = Layering::projected(&[0], &[1], shadow);
    let mut r: Box<R> = Box::default();
    f(&mut r, &scene, &layering)
}

/// A white bar across rows 30..34: an overlay every sink must compose.
fn bar() -> embedded_graphics::primitives::Styled<Rectangle, PrimitiveStyle<Rgb565>> {
    Rectangle::new(Point::new(5, 30), Size::new(40, 4))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::WHITE))
}

/// The frame through each sink: `draw_to`, `strip_into` (3 lines against the renderer's 4) and
/// `strip_be` (2.5 rows of bytes); returns the three images.
macro_rules! three_sinks {
    ($r:expr, $scene:expr, $options:expr) => {{
        let mut a = Frame::new(64, 64, Rgb565::CSS_HOT_PINK);
        $r.render_with($scene, $options, &mut a).unwrap();
        let mut b = Frame::new(64, 64, Rgb565::CSS_HOT_PINK);
        let mut frame = $r.prepare($scene, $options).unwrap();
        let mut lines = [[Rgb565::CSS_HOT_PINK; 64]; 3];
        let mut next = 0;
        while let Some(rows) = frame.strip_into(&mut lines) {
            assert_eq!(rows.start, next);
            assert!(rows.len() <= 3);
            for (i, y) in rows.clone().enumerate() {
                b.px[y * 64..(y + 1) * 64].copy_from_slice(&lines[i]);
            }
            next = rows.end;
        }
        assert_eq!(next, 64);
        assert!(frame.is_complete());
        let mut c = Frame::new(64, 64, Rgb565::CSS_HOT_PINK);
        let mut frame = $r.prepare($scene, $options).unwrap();
        let mut bytes = [0u8; 64 * 2 * 5 / 2];
        while let Some(rows) = frame.strip_be(&mut bytes).unwrap() {
            assert!(rows.len() <= 2);
            for (i, y) in rows.enumerate() {
                for x in 0..64 {
                    let at = (i * 64 + x) * 2;
                    let raw = u16::from_be_bytes([bytes[at], bytes[at + 1]]);
                    c.px[y * 64 + x] = embedded_graphics::pixelcolor::raw::RawU16::new(raw).into();
                }
            }
        }
        (a, b, c)
    }};
}

#[test]
fn the_three_sinks_draw_the_same_plain_and_layered_frames() {
    let overlay = bar();
    let plain = with_scene(255, |r, scene, _| {
        let (a, b, c) = three_sinks!(r, scene, FrameOptions::new().overlay(&overlay));
        assert!(a.px.iter().all(|&p| p != Rgb565::CSS_HOT_PINK));
        assert!(
            a.px == b.px && a.px == c.px,
            "plain frame: the sinks differ"
        );
        assert_eq!(a.get(10, 31), Rgb565::WHITE, "the overlay is composed");
        a
    });
    // Layered: the shadow and a half-transparent square.
    with_scene(128, |r, scene, layering| {
        let mut layers: Box<L> = Box::default();
        let (a, b, c) = three_sinks!(
            r,
            scene,
            FrameOptions::new()
                .overlay(&overlay)
                .layered(layering, &mut layers)
        );
        assert!(
            a.px == b.px && a.px == c.px,
            "layered frame: the sinks differ"
        );
        assert_eq!(a.get(10, 31), Rgb565::WHITE, "the overlay is composed");
        // The layers drew something: the shadow, and the square see-through.
        let differ = a.px.iter().zip(&plain.px).filter(|(p, q)| p != q).count();
        assert!(differ > 200, "{differ} pixels differ from the plain frame");
    });
}

/// Records what a frame tells its probe.
#[derive(Default)]
struct Log {
    starts: u32,
    ends: u32,
    /// The stage entered last, and whether `frame_end` came after `Stage::Done`.
    last: Option<Stage>,
    done_before_end: bool,
}

impl Probe for Log {
    fn enter(&mut self, stage: Stage) {
        self.last = Some(stage);
    }
    fn frame_start(&mut self) {
        self.starts += 1;
    }
    fn frame_end(&mut self) {
        self.ends += 1;
        self.done_before_end = self.last == Some(Stage::Done);
    }
}

#[test]
fn a_lent_probe_hears_one_start_and_one_end() {
    with_scene(255, |r, scene, _| {
        let mut log = Log::default();
        let mut frame = r
            .prepare(scene, FrameOptions::new().probe(&mut log))
            .unwrap();
        let mut f = Frame::new(64, 64, Rgb565::BLACK);
        let mut strips = 0;
        while frame.strip_to(&mut f).unwrap().is_some() {
            strips += 1;
        }
        // More calls after the end change nothing.
        assert_eq!(frame.strip_to(&mut f).unwrap(), None);
        assert_eq!(strips, 16);
        assert_eq!((log.starts, log.ends), (1, 1));
        assert!(log.done_before_end);
        // A frame that fails (4 vertices of capacity for 8) ends too, once.
        let mut log = Log::default();
        let mut small: Box<Renderer<Q, Rgb565, 64, 64, 4, 64, 16, 4>> = Box::default();
        assert!(small
            .prepare(scene, FrameOptions::new().probe(&mut log))
            .is_err());
        assert_eq!((log.starts, log.ends), (1, 1));
    });
}

#[test]
fn a_dropped_plain_frame_is_picked_up_where_it_stopped() {
    with_scene(255, |r, scene, layering| {
        assert!(r.prepared().is_none(), "nothing prepared yet");
        let mut want = Frame::new(64, 64, Rgb565::BLACK);
        r.render(scene, &mut want).unwrap();
        let mut got = Frame::new(64, 64, Rgb565::BLACK);
        let mut frame = r.prepare(scene, FrameOptions::new()).unwrap();
        assert_eq!(frame.strip_to(&mut got).unwrap(), Some(0..4));
        drop(frame);
        let mut frame = r.prepared().expect("the frame is still prepared");
        assert_eq!(frame.next_row(), 4);
        while frame.strip_to(&mut got).unwrap().is_some() {}
        assert!(got.px == want.px);
        // A layered frame needs its layers: it is not picked up without them.
        let mut layers: Box<L> = Box::default();
        let _ = r
            .prepare(scene, FrameOptions::new().layered(layering, &mut layers))
            .unwrap();
        assert!(r.prepared().is_none());
    });
}

#[test]
fn a_prepare_error_widens_to_any_target_error() {
    with_scene(255, |_, scene, _| {
        let mut small: Box<Renderer<Q, Rgb565, 64, 64, 4, 64, 16, 4>> = Box::default();
        let e = small.prepare(scene, FrameOptions::new()).err().unwrap();
        let wide: Error<std::fmt::Error> = e.widen();
        assert_eq!(wide.to_string(), e.to_string());
        assert!(matches!(wide, Error::Shortfall(_)));
    });
}
