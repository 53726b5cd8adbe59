//! An external user's program (issue #21): written against the public API only (`scanline3d::`
//! paths, as a crate depending on scanline3d by path sees it; an integration test cannot reach
//! the crate's internals), the way the README and the crate docs teach it.
//!
//! The scene: a ground plane ([`Shape::plane`]) with two objects on it — a flat-shaded torus
//! and a smooth, shiny octahedron built by hand with [`vertex_normals`] — lit by a white sun
//! and a warm fill light that is switched off for some frames ([`Light::switched_off`]), seen
//! by a camera orbiting the scene. Materials come from the builder
//! (`Material::matte(..).flat()`, `.specular(..)`), transforms from the `*` operator.
//!
//! The device renderer's capacities were sized with [`Renderer::needs`] over the whole
//! animation ([`Needs::max`], [`Needs::fits`]) and are named in a [`Capacities`] constant that
//! [`renderer_type!`] turns into the renderer type; the firmware's renderer is a `static` built by
//! [`Renderer::const_new`] behind a mutex (`critical_section::Mutex<RefCell<..>>` on a device,
//! `std::sync::Mutex` here). Frames go to RGB565, RGB888 and Gray8 frame buffers, to a custom
//! `DrawTarget` that records what a panel driver would receive (and can fail like a bus), and
//! to embedded-graphics' `MockDisplay` (which panics on a pixel drawn twice).

use std::convert::Infallible;
use std::sync::Mutex;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Gray8, GrayColor, PixelColor, Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::{DrawTarget, OriginDimensions, Pixel, Point, PointsIter, Size};
use embedded_graphics::primitives::Rectangle;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{errors::Capacity, Error, TexturedShape};

type Q = Fx<I16F16>;

/// The panel.
const W: usize = 96;
const H: usize = 96;
/// One orbit of the camera.
const FRAMES: usize = 24;

/// The device renderer's size and capacities: the panel, and the largest needs over the
/// animation, as `the_device_renderer_is_sized_for_the_whole_animation` measures them with
/// [`Renderer::needs`] (vertices 341, triangles 220, active 43; frame 0 alone needs less), plus
/// a small margin.
const CAPS: Capacities = Capacities {
    width: W,
    height: H,
    vertices: 360,
    triangles: 240,
    active: 48,
    lines: 1,
    attr_vertices: 0,
    attr_active: 0,
};

/// The firmware's renderer type.
type Device<C> = renderer_type!(Q, C, CAPS);
/// The host's measuring renderer: the device's size, generous capacities.
const MEASURE: Capacities = Capacities {
    vertices: 4096,
    triangles: 4096,
    active: 512,
    ..CAPS
};
type Measure = renderer_type!(Q, Rgb565, MEASURE);

/// The firmware's renderer, in a `static`: no stack copy, placed by the linker.
static DEVICE: Mutex<Device<Rgb565>> = Mutex::new(Device::const_new(Rgb565::BLACK));

// ---------------------------------------------------------------------------------------------
// The scene.

/// The octahedron's corners: ±X, ±Y, ±Z.
const GEM_INDICES: [[u16; 3]; 8] = [
    [0, 2, 4],
    [2, 1, 4],
    [1, 3, 4],
    [3, 0, 4],
    [2, 0, 5],
    [1, 2, 5],
    [3, 1, 5],
    [0, 3, 5],
];

/// The meshes: built once (in firmware: at start-up, or baked into flash).
struct World {
    ground: Shape<Q, 81, 128>,
    torus: Shape<Q, 128, 256>,
    gem_positions: [[Q; 3]; 6],
    gem_normals: [[Q; 3]; 6],
}

impl World {
    fn new() -> Self {
        let r = Q::lit(0.6);
        let (o, z) = (-r, Q::ZERO);
        let gem_positions = [
            [r, z, z],
            [o, z, z],
            [z, r, z],
            [z, o, z],
            [z, z, r],
            [z, z, o],
        ];
        let mut gem_normals = [[Q::ZERO; 3]; 6];
        vertex_normals(&gem_positions, &GEM_INDICES, &mut gem_normals).unwrap();
        World {
            ground: Shape::plane(6.0, 6.0, 8, 8).unwrap(),
            torus: Shape::torus(0.5, 0.2, 16, 8).unwrap(),
            gem_positions,
            gem_normals,
        }
    }

    /// The objects of `frame`: the torus and the octahedron turn as the camera orbits.
    fn objects(&self, frame: usize) -> [Object<'_, Q>; 3] {
        let spin = Q::lit(0.4) * Q::from_i32(frame as i32);
        let gem = Mesh::new(&self.gem_positions, &GEM_INDICES)
            .unwrap()
            .with_normals(&self.gem_normals)
            .unwrap();
        [
            Object {
                mesh: self.ground.mesh(),
                transform: Mat4::identity(),
                material: Material::matte([110, 180, 90], Q::lit(0.2), Q::lit(0.8)),
            },
            Object {
                mesh: self.torus.mesh(),
                transform: Mat4::translate([Q::lit(-1.1), Q::lit(0.75), Q::lit(0.2)])
                    * Mat4::rotate_y(spin),
                material: Material::matte([255, 160, 64], Q::lit(0.15), Q::lit(0.85)).flat(),
            },
            Object {
                mesh: gem,
                transform: Mat4::translate([Q::lit(1.1), Q::lit(0.65), Q::lit(-0.3)])
                    * Mat4::rotate_y(-spin)
                    * Mat4::rotate_x(Q::lit(0.3)),
                material: Material::matte([90, 160, 255], Q::lit(0.1), Q::lit(0.7))
                    .specular(Q::lit(0.6), 16),
            },
        ]
    }
}

/// The camera orbits the scene once in `FRAMES` frames, above the ground.
fn camera(frame: usize) -> Camera<Q> {
    let a = 2.0 * std::f64::consts::PI * frame as f64 / FRAMES as f64;
    Camera::look_at(
        [Q::lit(3.6 * a.cos()), Q::lit(1.8), Q::lit(3.6 * a.sin())],
        [Q::ZERO, Q::lit(0.4), Q::ZERO],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: Q::lit(0.9),
            near: Q::lit(0.3),
            far: Q::lit(12.0),
        },
    )
    .unwrap()
}

fn sun() -> Light<Q> {
    Light::white([-Q::ONE, Q::lit(2.0), Q::ONE])
}

fn fill() -> Light<Q> {
    Light {
        direction: [Q::lit(1.5), Q::ONE, -Q::ONE],
        color: [255, 190, 140],
    }
}

/// The fill light is off in every fourth frame.
fn fill_is_off(frame: usize) -> bool {
    frame % 4 == 3
}

fn lights(frame: usize) -> [Light<Q>; 2] {
    let fill = if fill_is_off(frame) {
        fill().switched_off()
    } else {
        fill()
    };
    [sun(), fill]
}

fn scene<'a, const L: usize>(
    objects: &'a [Object<'a, Q>],
    frame: usize,
    lights: [Light<Q>; L],
) -> Scene<'a, Q, L> {
    let mut s = Scene::new(objects, camera(frame), lights);
    s.background = [16, 24, 48];
    s
}

// ---------------------------------------------------------------------------------------------
// Targets.

/// A frame buffer: a user's own `DrawTarget` for any colour type.
#[derive(Clone, PartialEq)]
struct Frame<C> {
    w: usize,
    h: usize,
    px: Vec<C>,
}

impl<C: PixelColor> Frame<C> {
    fn new(w: usize, h: usize, fill: C) -> Self {
        Frame {
            w,
            h,
            px: vec![fill; w * h],
        }
    }
}

impl<C: PixelColor> OriginDimensions for Frame<C> {
    fn size(&self) -> Size {
        Size::new(self.w as u32, self.h as u32)
    }
}

impl<C: PixelColor> DrawTarget for Frame<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            if (0..self.w as i32).contains(&p.x) && (0..self.h as i32).contains(&p.y) {
                self.px[p.y as usize * self.w + p.x as usize] = c;
            }
        }
        Ok(())
    }
}

/// What an SPI panel driver receives: an address window and a stream of pixels per
/// `fill_contiguous`, as raw RGB565 words. It can fail like a bus does.
struct Panel {
    raw: Vec<u16>,
    windows: Vec<Rectangle>,
    single_pixels: usize,
    fail_at_window: Option<usize>,
}

#[derive(Debug, PartialEq)]
struct BusError;

impl Panel {
    fn new() -> Self {
        Panel {
            raw: vec![0xdead; W * H],
            windows: Vec::new(),
            single_pixels: 0,
            fail_at_window: None,
        }
    }
}

impl OriginDimensions for Panel {
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl DrawTarget for Panel {
    type Color = Rgb565;
    type Error = BusError;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), BusError> {
        for Pixel(p, c) in pixels {
            self.single_pixels += 1;
            self.raw[p.y as usize * W + p.x as usize] = raw565(c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), BusError> {
        if self.fail_at_window == Some(self.windows.len()) {
            return Err(BusError);
        }
        self.windows.push(*area);
        let mut n = 0;
        for (p, c) in area.points().zip(colors) {
            self.raw[p.y as usize * W + p.x as usize] = raw565(c);
            n += 1;
        }
        assert_eq!(
            n,
            area.size.width * area.size.height,
            "a short pixel stream"
        );
        Ok(())
    }
}

fn raw565(c: Rgb565) -> u16 {
    (u16::from(c.r()) << 11) | (u16::from(c.g()) << 5) | u16::from(c.b())
}

fn rgb(c: Rgb888) -> [u8; 3] {
    [c.r(), c.g(), c.b()]
}

// ---------------------------------------------------------------------------------------------
// Tests.

/// The host-side sizing the docs teach: measure every frame with a generous renderer, keep the
/// largest figures, check the device's renderer; then render every frame on the device's
/// renderer with the default policy (an error if a frame does not fit): none fails.
#[test]
fn the_device_renderer_is_sized_for_the_whole_animation() {
    let world = World::new();
    let mut measure = Box::new(Measure::new());
    let mut worst = Needs::default();
    let mut per_frame = Vec::new();
    for frame in 0..FRAMES {
        let objects = world.objects(frame);
        let needs = measure
            .needs(&scene(&objects, frame, lights(frame)))
            .unwrap();
        per_frame.push(needs);
        worst = worst.max(needs);
    }
    println!("worst needs over {FRAMES} frames: {worst:?}");
    assert!(worst.fits(&CAPS.capacity()), "{worst:?}");
    // The type is the one the constant names, and the positional spelling is the same type.
    assert_eq!(Device::<Rgb565>::CAPACITIES, CAPS);
    assert_eq!(Device::<Rgb565>::CAPACITY, CAPS.capacity());
    let positional: Box<Renderer<Q, Rgb565, W, H, 360, 240, 48, 1>> = Box::new(Device::new());
    assert_eq!(positional.viewport(), (W, H));
    // Sized from the measurement, not guessed: at most a small margin above it.
    for what in [
        Capacity::Vertices,
        Capacity::Triangles,
        Capacity::ActiveTriangles,
    ] {
        let (need, cap) = (worst.get(what), Device::<Rgb565>::CAPACITY.get(what));
        assert!(cap <= need + need / 5 + 8, "{what:?}: {cap} for {need}");
    }
    // The animation's needs vary: frame 0 alone would have sized it wrong.
    assert!(per_frame.iter().any(|n| !n.fits(&per_frame[0])));

    let mut device = Box::new(Device::<Rgb565>::new().with_dither(true));
    let mut frame_buf = Frame::new(W, H, Rgb565::BLACK);
    for (frame, needs) in per_frame.iter().enumerate() {
        let objects = world.objects(frame);
        let stats = device
            .render(&scene(&objects, frame, lights(frame)), &mut frame_buf)
            .unwrap_or_else(|e| panic!("frame {frame}: {e}"));
        assert!(stats.pixels_written > 0);
        assert_eq!(Needs::from_stats(&stats), *needs, "frame {frame}");
        assert!(device.shortfall().is_none());
    }
}

/// Every frame renders into RGB565, RGB888 and Gray8 frame buffers; the three agree on what
/// was drawn, their colours agree with each other, and the image changes as the camera
/// orbits.
#[test]
fn every_frame_renders_into_every_colour_type_and_the_orbit_moves_the_image() {
    let world = World::new();
    let mut r565 = Box::new(Device::<Rgb565>::new());
    let mut r888 = Box::new(Device::<Rgb888>::new());
    let mut rgray = Box::new(Device::<Gray8>::new());
    let mut frames888: Vec<Frame<Rgb888>> = Vec::new();
    let mut worst_565 = 0u32;
    let mut worst_gray = 0u32;
    for frame in 0..FRAMES {
        let objects = world.objects(frame);
        let s = scene(&objects, frame, lights(frame));
        let mut f565 = Frame::new(W, H, Rgb565::MAGENTA);
        let mut f888 = Frame::new(W, H, Rgb888::MAGENTA);
        let mut fgray = Frame::new(W, H, Gray8::new(7));
        let a = r565.render(&s, &mut f565).unwrap();
        let b = r888.render(&s, &mut f888).unwrap();
        let c = rgray.render(&s, &mut fgray).unwrap();
        // The same geometry whatever the colour type.
        assert_eq!((a.drawn, a.pixels_written), (b.drawn, b.pixels_written));
        assert_eq!((a.drawn, a.pixels_written), (c.drawn, c.pixels_written));
        // A sizeable part of the screen is the scene, the rest background: every pixel drawn.
        assert!(
            b.pixels_written as usize > W * H / 4,
            "frame {frame}: {b:?}"
        );
        assert!(f888.px.iter().all(|&p| p != Rgb888::MAGENTA));
        let background = Rgb888::new(16, 24, 48);
        let scene_px = f888.px.iter().filter(|&&p| p != background).count();
        assert!(
            scene_px > W * H / 4,
            "frame {frame}: {scene_px} scene pixels"
        );
        // The colour types agree: RGB565 to within a 5/6-bit step (each rounds once from the
        // same lighting), Gray8 to the BT.601 luma of the RGB888 pixel.
        for i in 0..W * H {
            let (p565, p888, pg) = (f565.px[i], f888.px[i], fgray.px[i]);
            let up = [
                u32::from(p565.r()) * 255 / 31,
                u32::from(p565.g()) * 255 / 63,
                u32::from(p565.b()) * 255 / 31,
            ];
            for (k, &v) in rgb(p888).iter().enumerate() {
                worst_565 = worst_565.max(up[k].abs_diff(u32::from(v)));
            }
            let luma = Gray8::from(p888).luma();
            worst_gray = worst_gray.max(u32::from(pg.luma().abs_diff(luma)));
        }
        frames888.push(f888);
    }
    assert!(worst_565 <= 8, "RGB565 against RGB888: {worst_565}");
    assert!(worst_gray <= 1, "Gray8 against RGB888's luma: {worst_gray}");
    // The orbit moves the image: every frame differs from every other, and neighbouring frames
    // in many pixels.
    for i in 0..FRAMES {
        for j in 0..i {
            assert!(frames888[i] != frames888[j], "frames {j} and {i} are equal");
        }
        let next = &frames888[(i + 1) % FRAMES];
        let changed = (0..W * H)
            .filter(|&k| frames888[i].px[k] != next.px[k])
            .count();
        assert!(
            changed > W * H / 10,
            "frame {i}: only {changed} pixels change"
        );
    }
}

/// A switched-off light lights nothing: the image is darker (no pixel brighter, many darker)
/// than with it on, and exactly the image of a scene without that light.
#[test]
fn a_switched_off_light_darkens_the_image() {
    let world = World::new();
    let mut r = Box::new(Device::<Rgb888>::new());
    let mut r1 = Box::new(Device::<Rgb888>::new());
    let mut off_frames = 0;
    for frame in (0..FRAMES).filter(|&f| fill_is_off(f)) {
        off_frames += 1;
        let objects = world.objects(frame);
        let render = |r: &mut Device<Rgb888>, s: &Scene<'_, Q, 2>| {
            let mut f = Frame::new(W, H, Rgb888::BLACK);
            r.render(s, &mut f).unwrap();
            f
        };
        let off = render(&mut r, &scene(&objects, frame, lights(frame)));
        let on = render(&mut r, &scene(&objects, frame, [sun(), fill()]));
        assert!(lights(frame)[1].is_off() && !fill().is_off());
        let (mut darker, mut sum_on, mut sum_off) = (0, 0u64, 0u64);
        for (a, b) in off.px.iter().zip(&on.px) {
            let (a, b) = (rgb(*a), rgb(*b));
            assert!(
                (0..3).all(|k| a[k] <= b[k]),
                "frame {frame}: {a:?} brighter than {b:?}"
            );
            darker += usize::from(a != b);
            sum_off += a.iter().map(|&v| u64::from(v)).sum::<u64>();
            sum_on += b.iter().map(|&v| u64::from(v)).sum::<u64>();
        }
        assert!(darker > W * H / 10, "frame {frame}: {darker} pixels darker");
        assert!(
            sum_off * 10 < sum_on * 9,
            "frame {frame}: {sum_off} vs {sum_on}"
        );
        // Off is off: the same pixels as the sun alone, and as `Light::off()`.
        let mut alone = Frame::new(W, H, Rgb888::BLACK);
        r1.render(&scene(&objects, frame, [sun()]), &mut alone)
            .unwrap();
        assert!(
            off == alone,
            "frame {frame}: an off light changed the image"
        );
        let other_off = render(&mut r, &scene(&objects, frame, [sun(), Light::off()]));
        assert!(other_off == alone, "frame {frame}");
    }
    assert_eq!(off_frames, FRAMES / 4);
}

/// The firmware's `static` renderer (built by `const_new`, behind a mutex) draws exactly what
/// a boxed `Renderer::new()` draws, and what the measuring renderer with larger capacities
/// draws, frame after frame.
#[test]
fn the_static_renderer_draws_what_a_boxed_one_draws() {
    let world = World::new();
    let mut device = DEVICE.lock().unwrap();
    device.set_dither(true);
    let mut boxed = Box::new(Device::<Rgb565>::new().with_dither(true));
    let mut big = Box::new(Measure::new().with_dither(true));
    for frame in 0..FRAMES {
        let objects = world.objects(frame);
        let s = scene(&objects, frame, lights(frame));
        let mut a = Frame::new(W, H, Rgb565::BLACK);
        let mut b = Frame::new(W, H, Rgb565::WHITE);
        let mut c = Frame::new(W, H, Rgb565::RED);
        let sa = device.render(&s, &mut a).unwrap();
        let sb = boxed.render(&s, &mut b).unwrap();
        let sc = big.render(&s, &mut c).unwrap();
        assert_eq!(sa, sb, "frame {frame}");
        assert_eq!(sa, sc, "frame {frame}");
        assert!(a == b && a == c, "frame {frame}: the pixels differ");
    }
}

/// A custom panel target receives one address window per row, top to bottom, each pixel once
/// and nothing pixel by pixel; a bus error comes back as `Error::Target` with the rows before
/// it drawn, and the renderer draws the next frame normally.
#[test]
fn a_custom_panel_gets_one_window_per_row_and_its_errors_come_back() {
    let world = World::new();
    let mut device = Box::new(Device::<Rgb565>::new().with_dither(true));
    let objects = world.objects(5);
    let s = scene(&objects, 5, lights(5));

    let mut reference = Frame::new(W, H, Rgb565::BLACK);
    device.render(&s, &mut reference).unwrap();

    let mut panel = Panel::new();
    device.render(&s, &mut panel).unwrap();
    let rows: Vec<Rectangle> = (0..H as i32)
        .map(|y| Rectangle::new(Point::new(0, y), Size::new(W as u32, 1)))
        .collect();
    assert_eq!(panel.windows, rows);
    assert_eq!(panel.single_pixels, 0);
    let expected: Vec<u16> = reference.px.iter().map(|&c| raw565(c)).collect();
    assert_eq!(panel.raw, expected);

    // The bus fails at row 40: the error comes back, rows 0..40 are on the panel.
    let mut failing = Panel::new();
    failing.fail_at_window = Some(40);
    match device.render(&s, &mut failing) {
        Err(Error::Target(BusError)) => {}
        other => panic!("expected the bus error, got {other:?}"),
    }
    assert_eq!(failing.windows.len(), 40);
    assert_eq!(failing.raw[..40 * W], expected[..40 * W]);
    assert!(failing.raw[40 * W..].iter().all(|&p| p == 0xdead));
    // The renderer is reusable after the error.
    failing.fail_at_window = None;
    failing.windows.clear();
    device.render(&s, &mut failing).unwrap();
    assert_eq!(failing.raw, expected);
}

/// The README's target: embedded-graphics' `MockDisplay` (64 × 64 at most, panics on a pixel
/// drawn twice), with the viewport set to its size.
#[test]
fn mock_display_sees_each_pixel_drawn_once() {
    let world = World::new();
    let mut device = Box::new(Device::<Rgb565>::new());
    device.set_viewport(64, 64);
    for frame in [0, 7, 15] {
        let objects = world.objects(frame);
        let mut display = MockDisplay::<Rgb565>::new();
        let stats = device
            .render(&scene(&objects, frame, lights(frame)), &mut display)
            .unwrap();
        assert!(stats.pixels_written > 0);
        assert_eq!(display.affected_area().size, Size::new(64, 64));
    }
}

/// The mistakes a user makes are reported before anything is drawn: a target smaller than the
/// renderer, a renderer too small for a frame (every short capacity named), a Gouraud object
/// without normals. `OverflowPolicy::DrawWhatFits` draws what fits and says what it skipped.
#[test]
fn mistakes_are_reported_before_anything_is_drawn() {
    let world = World::new();
    let objects = world.objects(0);
    let s = scene(&objects, 0, lights(0));

    let mut device = Box::new(Device::<Rgb565>::new());
    let mut small = Frame::new(64, 64, Rgb565::MAGENTA);
    match device.render(&s, &mut small) {
        Err(Error::TargetTooSmall { viewport, target }) => {
            assert_eq!(viewport, Size::new(W as u32, H as u32));
            assert_eq!(target.size, Size::new(64, 64));
        }
        other => panic!("{other:?}"),
    }
    assert!(small.px.iter().all(|&p| p == Rgb565::MAGENTA));

    // Too few active triangles, enough of the rest.
    const TIGHT: Capacities = Capacities { active: 8, ..CAPS };
    type Tight = renderer_type!(Q, Rgb565, TIGHT);
    let mut tight = Box::new(Tight::new());
    let mut f = Frame::new(W, H, Rgb565::MAGENTA);
    match tight.render(&s, &mut f) {
        Err(Error::Shortfall(short)) => {
            assert!(short.is_short(Capacity::ActiveTriangles));
            assert!(!short.is_short(Capacity::Vertices) && !short.is_short(Capacity::Triangles));
            assert!(short.needed.active > 8 && short.needed.active <= CAPS.active);
        }
        other => panic!("{other:?}"),
    }
    assert!(f.px.iter().all(|&p| p == Rgb565::MAGENTA));
    // On the device, drawing what fits may be better than a black frame.
    tight.set_overflow(OverflowPolicy::DrawWhatFits);
    let stats = tight.render(&s, &mut f).unwrap();
    assert!(stats.pixels_written > 0);
    let short = tight.shortfall().expect("a frame drawn in part says so");
    assert!(short.skipped > 0);

    // Gouraud without normals.
    let bare = Mesh::new(&world.gem_positions, &GEM_INDICES).unwrap();
    let mut objects = world.objects(0);
    objects[2].mesh = bare;
    let mut f = Frame::new(W, H, Rgb565::MAGENTA);
    match device.render(&scene(&objects, 0, lights(0)), &mut f) {
        Err(Error::MissingNormals { object: 2 }) => {}
        other => panic!("{other:?}"),
    }
    assert!(f.px.iter().all(|&p| p == Rgb565::MAGENTA));
    // The same mesh flat-shaded needs no normals.
    objects[2].material = objects[2].material.flat();
    device
        .render(&scene(&objects, 0, lights(0)), &mut f)
        .unwrap();
}

// ---------------------------------------------------------------------------------------------
// A layered, fogged, textured orbit, sized exactly (issue #40): the sizing recipe of the
// README for every kind of frame. `Renderer::needs_layered` measures the vertices the shadow
// polygons add, the attribute stores (`XV`, `XA`: the fog takes a pool entry for the whole
// frame) and the `Layers` lists (`RA`, `PA`); a renderer and layers with exactly those
// figures draw every frame, and one less in any of the seven fails a frame with an error that
// names it.

/// An 8 × 8 RGB565 checker in flash.
static CHECKER: [u16; 64] = {
    let mut t = [0u16; 64];
    let mut i = 0;
    while i < 64 {
        t[i] = if (i / 8 + i % 8) % 2 == 0 {
            0xffff
        } else {
            0x3186
        };
        i += 1;
    }
    t
};
static CHECKER_TEXTURE: scanline3d::Texture = match scanline3d::Texture::new(&CHECKER, 8, 8) {
    Ok(t) => t,
    Err(_) => panic!("an 8 × 8 texture"),
};

/// The layered device's capacities: exactly the largest needs over the orbit (the test
/// `the_layered_orbit_is_sized_exactly` measures them and fails, naming the new figures, if
/// they change).
const LAYERED: Capacities = Capacities {
    width: W,
    height: H,
    vertices: LAYERED_NEEDS[0],
    triangles: LAYERED_NEEDS[1],
    active: LAYERED_NEEDS[2],
    lines: 1,
    attr_vertices: LAYERED_NEEDS[3],
    attr_active: LAYERED_NEEDS[4],
};
/// Vertices, triangles, active, XV, XA, RA, PA.
const LAYERED_NEEDS: [usize; 7] = [611, 345, 30, 359, 70, 20, 39];

/// The objects of the layered orbit's frame `frame`: the ground (the shadow's receiver), the
/// flat torus (its caster) and a textured cube.
fn layered_objects<'a>(
    world: &'a World,
    cube: &'a TexturedShape<Q, 24, 12>,
    frame: usize,
) -> [Object<'a, Q>; 3] {
    let [ground, torus, _] = world.objects(frame);
    let spin = Q::lit(0.3) * Q::from_i32(frame as i32);
    [
        ground,
        torus,
        Object {
            mesh: cube.mesh(),
            transform: Mat4::translate([Q::lit(-1.2), Q::lit(0.45), Q::lit(0.6)])
                * Mat4::rotate_y(spin),
            material: Material::matte([255, 255, 255], Q::lit(0.3), Q::lit(0.7))
                .textured(&CHECKER_TEXTURE),
        },
    ]
}

/// The layered orbit's fog (no point lights, no tone map).
fn orbit_effects() -> scanline3d::Effects<'static, Q> {
    scanline3d::Effects {
        point_lights: &[],
        fog: Some(scanline3d::Fog::linear(
            Q::lit(3.0),
            Q::lit(9.0),
            [16, 24, 48],
        )),
        tone: None,
    }
}

/// The layered orbit's layering: the torus (object 1) shadows the ground (object 0) along the
/// sun.
fn orbit_layering() -> scanline3d::shadow::Layering<'static, Q> {
    scanline3d::shadow::Layering::projected(
        &[0],
        &[1],
        scanline3d::shadow::PlanarShadow::new(
            [Q::ZERO, Q::ONE, Q::ZERO, Q::ZERO],
            scanline3d::shadow::ShadowLight::Directional(sun().direction),
            140,
        ),
    )
}

/// Draws every frame of the layered orbit with a renderer and layers of the given
/// capacities; the first error, as text, or `Ok`.
fn layered_orbit<
    const V: usize,
    const T: usize,
    const A: usize,
    const XV: usize,
    const XA: usize,
    const RA: usize,
    const PA: usize,
>() -> Result<(), String> {
    let world = World::new();
    let cube = TexturedShape::<Q, 24, 12>::cube(0.35).unwrap();
    let effects = orbit_effects();
    let mut renderer = Box::new(Renderer::<Q, Rgb565, W, H, V, T, A, 1, XV, XA>::new());
    let mut layers = Box::new(scanline3d::Layers::<W, 1, RA, PA>::new());
    let mut frame = Frame::new(W, H, Rgb565::BLACK);
    for k in 0..FRAMES {
        let objects = layered_objects(&world, &cube, k);
        let scene = scene(&objects, k, lights(k)).with_effects(&effects);
        let layering = orbit_layering();
        renderer
            .render_with(
                &scene,
                scanline3d::FrameOptions::new().layered(&layering, &mut layers),
                &mut frame,
            )
            .map_err(|e| format!("frame {k}: {e}"))?;
    }
    Ok(())
}

#[test]
fn the_layered_orbit_is_sized_exactly() {
    // Measured with generous capacities, attribute stores and lists.
    let world = World::new();
    let cube = TexturedShape::<Q, 24, 12>::cube(0.35).unwrap();
    let effects = orbit_effects();
    type Big = renderer_type!(Q, Rgb565, width: W, height: H, vertices: 4096,
        triangles: 4096, active: 512, attr_vertices: 4096, attr_active: 512);
    let mut measure = Box::new(Big::new());
    let mut layers = Box::new(scanline3d::Layers::<W, 1, 512, 512>::new());
    let mut worst = Needs::default();
    for k in 0..FRAMES {
        let objects = layered_objects(&world, &cube, k);
        let scene = scene(&objects, k, lights(k)).with_effects(&effects);
        let layering = orbit_layering();
        worst = worst.max(
            measure
                .needs_layered(&scene, &layering, &mut layers)
                .unwrap(),
        );
    }
    let [v, t, a, xv, xa, ra, pa] = LAYERED_NEEDS;
    let measured = [
        worst.vertices,
        worst.triangles,
        worst.active,
        worst.attr_vertices as usize,
        worst.attr_active as usize,
        worst.receivers as usize,
        worst.overlays as usize,
    ];
    assert_eq!(
        measured, LAYERED_NEEDS,
        "the orbit's needs changed: {worst:?}"
    );
    assert_eq!(worst, LAYERED.capacity().with_layers(ra, pa));
    type Exact = renderer_type!(Q, Rgb565, LAYERED);
    assert!(worst.fits(&Exact::CAPACITY.with_layers(ra, pa)));
    // Exactly sized: every frame draws.
    const N: [usize; 7] = LAYERED_NEEDS;
    layered_orbit::<{ N[0] }, { N[1] }, { N[2] }, { N[3] }, { N[4] }, { N[5] }, { N[6] }>()
        .unwrap();
    // One less in any capacity: a frame fails, and the error names what was short.
    let short = [
        (
            layered_orbit::<{ N[0] - 1 }, { N[1] }, { N[2] }, { N[3] }, { N[4] }, { N[5] }, { N[6] }>(
            ),
            "VERTS",
        ),
        (
            layered_orbit::<{ N[0] }, { N[1] - 1 }, { N[2] }, { N[3] }, { N[4] }, { N[5] }, { N[6] }>(
            ),
            "TRIS",
        ),
        (
            layered_orbit::<{ N[0] }, { N[1] }, { N[2] - 1 }, { N[3] }, { N[4] }, { N[5] }, { N[6] }>(
            ),
            "ACTIVE",
        ),
        (
            layered_orbit::<{ N[0] }, { N[1] }, { N[2] }, { N[3] - 1 }, { N[4] }, { N[5] }, { N[6] }>(
            ),
            "XV needs",
        ),
        (
            layered_orbit::<{ N[0] }, { N[1] }, { N[2] }, { N[3] }, { N[4] - 1 }, { N[5] }, { N[6] }>(
            ),
            "XA needs",
        ),
        (
            layered_orbit::<{ N[0] }, { N[1] }, { N[2] }, { N[3] }, { N[4] }, { N[5] - 1 }, { N[6] }>(
            ),
            "RA",
        ),
        (
            layered_orbit::<{ N[0] }, { N[1] }, { N[2] }, { N[3] }, { N[4] }, { N[5] }, { N[6] - 1 }>(
            ),
            "PA",
        ),
    ];
    for (result, name) in short {
        let e = result.expect_err(name);
        assert!(e.contains(name), "{name}: {e}");
    }
    let _ = (v, t, a, xv, xa);
}
