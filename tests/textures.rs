//! Texture mapping against an exact reference: a floor receding in perspective, textured with
//! an image whose every texel has its own colour (red = column, green = row, blue = 31), so
//! that each drawn pixel says which texel it shows. The reference casts the ray through the
//! pixel centre onto the floor in `f64` and finds the exact texture coordinate; the error of a
//! pixel is the distance, in texels, from that coordinate to the square of the texel drawn
//! (0 when it is inside). `cargo test --test textures -- --nocapture` prints the figures.

mod common;

use common::textures::{coded_texture, floor_error, floor_scene, TexError, FLOOR_VIEW};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{Texture, TextureMode, Wrap};

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
fn renderer_without_textures_is_the_same_size() {
    use scanline3d::Renderer;
    type Plain = Renderer<Q, Rgb565, 240, 240, 512, 466, 61>;
    type Zero = Renderer<Q, Rgb565, 240, 240, 512, 466, 61, 1, 0, 0>;
    assert_eq!(std::mem::size_of::<Plain>(), std::mem::size_of::<Zero>());
    assert_eq!(std::mem::align_of::<Plain>(), std::mem::align_of::<Zero>());
}

/// The textured benchmark frame in every span mode and number type, against golden images
/// (looked at): the checkerboard floor crossing the near plane and the textured cube.
#[test]
fn textured_frames_match_their_golden_images() {
    use scanline3d::demo::{render_bench, Bench};
    fn one<S: Scalar>(b: Bench, ty: &str) {
        let mut f = common::Frame::new(240, 240, Rgb565::BLACK);
        render_bench::<S, Rgb565, _, _>(b, 0.0, false, &mut f, &mut scanline3d::NoProbe).unwrap();
        f.assert_each_written_once();
        common::check_golden(&format!("{}_{ty}", b.name()), &f);
    }
    for b in [Bench::Textured, Bench::TexturedAffine, Bench::TexturedExact] {
        one::<Q>(b, "I16F16");
        one::<f32>(b, "f32");
        one::<f64>(b, "f64");
    }
}
