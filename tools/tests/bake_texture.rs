//! `bake --texture` and OBJ texture coordinates: PNG images of every colour type and bit depth
//! quantized to RGB565 by rounding, transparent pixels as a colour key no opaque texel uses,
//! clear errors for bad images, the committed baked texture and textured mesh compiled,
//! rendered and still what the generators produce; `vt` baked as `UVS` (t = 1 − v), split at
//! seams, carried through simplification, refused when only some faces have it or out of range.

use scanline3d_tools as common;

#[allow(dead_code)]
mod baked_texture {
    include!("../../tests/data/baked_checker.rs");
}

#[allow(dead_code)]
mod baked_cube {
    include!("../../tests/data/cube_net_mesh.rs");
}

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use common::obj::{bake_with_uvs, normals_per_position, parse_obj, simplify, NormalSource};
use common::texture_io::{
    bake_texture, load_png_texture, texture_ident, texture_rust_source, PREFERRED_KEY,
};
use common::textures::coded_texture;
use common::{at, screen_camera, Frame};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::RawData;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{Texture, Wrap};

type Q = Fx<I16F16>;
type TexRenderer = Renderer<Q, Rgb565, 160, 120, 64, 64, 16, 1, 64, 16>;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data")
        .join(name)
}

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bake_texture");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// Writes a PNG of the given format into the test's temporary folder.
fn write_png(
    name: &str,
    (w, h): (u32, u32),
    color: png::ColorType,
    depth: png::BitDepth,
    pixels: &[u8],
    palette: Option<(&[u8], &[u8])>,
) -> PathBuf {
    let path = tmp(name);
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        if let Some((rgb, trns)) = palette {
            enc.set_palette(rgb.to_vec());
            if !trns.is_empty() {
                enc.set_trns(trns.to_vec());
            }
        }
        let mut wr = enc.write_header().unwrap();
        wr.write_image_data(pixels).unwrap();
    }
    std::fs::write(&path, bytes).unwrap();
    path
}

// tests/data/checker8.png (8 x 8 RGBA): a checkerboard of A = (132, 64, 200) and
// B = (10, 250, 3), with red at (0, 0), white at (7, 0), grey 128 at (0, 7); at (3, 3) an A of
// alpha 128 (opaque), at (4, 4) an A of alpha 127 and at (7, 7) alpha 0 (both transparent).
// Hand-computed RGB565 by rounding (c·31/255, c·63/255):
//   A: red round(132·31/255 = 16.05) = 16, green round(64·63/255 = 15.81) = 16,
//      blue round(200·31/255 = 24.31) = 24 (cutting 200 >> 3 would give 25): 0x8218.
//   B: red round(1.22) = 1, green round(250·63/255 = 61.76) = 62, blue round(0.36) = 0: 0x0FC0.
//   grey 128: red and blue round(15.56) = 16, green round(31.62) = 32: 0x8410.
const A: u16 = 0x8218;
const B: u16 = 0x0FC0;
const RED: u16 = 0xF800;
const WHITE: u16 = 0xFFFF;
const GREY: u16 = 0x8410;

/// The texel the checker should have at (x, y), `None` for the transparent ones.
fn checker_texel(x: usize, y: usize) -> Option<u16> {
    match (x, y) {
        (0, 0) => Some(RED),
        (7, 0) => Some(WHITE),
        (0, 7) => Some(GREY),
        (4, 4) | (7, 7) => None,
        _ if (x + y).is_multiple_of(2) => Some(A),
        _ => Some(B),
    }
}

/// The checker's 8-bit RGBA pixels, as the PNG should hold them.
fn checker_rgba(x: usize, y: usize) -> [u8; 4] {
    match (x, y) {
        (0, 0) => [255, 0, 0, 255],
        (7, 0) => [255, 255, 255, 255],
        (0, 7) => [128, 128, 128, 255],
        (3, 3) => [132, 64, 200, 128],
        (4, 4) => [132, 64, 200, 127],
        (7, 7) => [0, 0, 0, 0],
        _ if (x + y).is_multiple_of(2) => [132, 64, 200, 255],
        _ => [10, 250, 3, 255],
    }
}

#[test]
fn the_committed_checker_is_the_image_described_here() {
    let (w, h, rgba) = {
        let dec = png::Decoder::new(std::fs::File::open(data("checker8.png")).unwrap());
        let mut r = dec.read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size()];
        let info = r.next_frame(&mut buf).unwrap();
        assert_eq!(
            (info.color_type, info.bit_depth),
            (png::ColorType::Rgba, png::BitDepth::Eight)
        );
        (info.width, info.height, buf)
    };
    assert_eq!((w, h), (8, 8));
    for y in 0..8 {
        for x in 0..8 {
            assert_eq!(
                rgba[4 * (8 * y + x)..][..4],
                checker_rgba(x, y),
                "({x}, {y})"
            );
        }
    }
}

#[test]
fn checker_png_quantizes_by_rounding_with_a_free_key() {
    let t = load_png_texture(&data("checker8.png")).unwrap();
    assert_eq!((t.width, t.height, t.texels.len()), (8, 8, 64));
    assert_eq!(t.key, Some(PREFERRED_KEY), "magenta is free in the checker");
    assert_eq!(t.transparent, 2);
    for y in 0..8 {
        for x in 0..8 {
            let want = checker_texel(x, y).unwrap_or(PREFERRED_KEY);
            assert_eq!(
                t.texels[8 * y + x],
                want,
                "texel ({x}, {y}): {:#06X}",
                t.texels[8 * y + x]
            );
        }
    }
    // Blue 200 rounds to 24, not 25.
    assert_eq!(t.texels[2] & 31, 24);
    // Largest error: grey 128 against the 5-bit level 16 = 16·255/31 = 131.61.
    let worst = 16.0 * 255.0 / 31.0 - 128.0;
    assert!(
        (t.quantization.0 - worst).abs() < 1e-9,
        "{:?}",
        t.quantization
    );
    // Mean: over the 62 opaque pixels' channels, by f64 rounding here.
    let mut sum = 0.0;
    for y in 0..8 {
        for x in 0..8 {
            let p = checker_rgba(x, y);
            if p[3] < 128 {
                continue;
            }
            for (c, levels) in [(p[0], 31.0), (p[1], 63.0), (p[2], 31.0)] {
                let c = c as f64;
                let k = (c * levels / 255.0).round();
                sum += (c - k * 255.0 / levels).abs();
            }
        }
    }
    let mean = sum / (3.0 * 62.0);
    assert!(
        (t.quantization.1 - mean).abs() < 1e-9,
        "{:?}",
        t.quantization
    );
}

/// 16-bit samples as PNG stores them (big-endian).
fn be16(samples: &[u16]) -> Vec<u8> {
    samples.iter().flat_map(|v| v.to_be_bytes()).collect()
}

#[test]
fn every_colour_type_and_bit_depth_is_read() {
    use png::{BitDepth as D, ColorType as C};
    // Red, B, magenta (opaque), and an entry that tRNS makes transparent.
    let pal: &[u8] = &[255, 0, 0, 10, 250, 3, 255, 0, 255, 1, 2, 3];
    let trns: &[u8] = &[255, 255, 255, 0];
    let k = PREFERRED_KEY;
    // (name, size, colour type, bit depth, samples, palette and tRNS, texels, key)
    #[allow(clippy::type_complexity)]
    #[rustfmt::skip]
    let cases: [(&str, (u32, u32), C, D, Vec<u8>, Option<(&[u8], &[u8])>, &[u16], Option<u16>); 8] = [
        // 132: red and blue 16, green round(32.61) = 33; 7: 1, round(1.73) = 2, 1.
        ("grey8", (2, 2), C::Grayscale, D::Eight, vec![0, 132, 255, 7], None,
         &[0x0000, 0x8430, 0xFFFF, 0x0841], None),
        // Rounded from all 16 bits: 1058·31/65535 = 0.5005 -> 1, 1058·63/65535 = 1.017 -> 1
        // (0x0821), where cutting to the high byte (4) would give 0, 1, 0 (0x0020).
        // 32896 = 128·257 is 8-bit 128.
        ("grey16", (2, 2), C::Grayscale, D::Sixteen, be16(&[1058, 65535, 0, 32896]), None,
         &[0x0821, 0xFFFF, 0x0000, GREY], None),
        // 1 0 / 0 1, each row padded to a byte.
        ("grey1", (2, 2), C::Grayscale, D::One, vec![0b1000_0000, 0b0100_0000], None,
         &[0xFFFF, 0x0000, 0x0000, 0xFFFF], None),
        // An opaque 132 and a transparent pixel.
        ("greya8", (2, 1), C::GrayscaleAlpha, D::Eight, vec![132, 255, 9, 0], None,
         &[0x8430, k], Some(k)),
        ("rgb8", (2, 1), C::Rgb, D::Eight, vec![132, 64, 200, 10, 250, 3], None,
         &[A, B], None),
        // Alpha 32896 (128·257) is opaque, 32895 transparent.
        ("rgba16", (2, 1), C::Rgba, D::Sixteen, be16(&[65535, 0, 1058, 32896, 1, 2, 3, 32895]),
         None, &[0xF801, k], Some(k)),
        // Without tRNS a palette is opaque: magenta is a texel, not a key.
        ("palette8", (2, 1), C::Indexed, D::Eight, vec![2, 1], Some((pal, &[])),
         &[k, B], None),
        // Magenta is taken: the key is the lowest value no opaque texel has, 0.
        ("palette2", (4, 1), C::Indexed, D::Two, vec![0b00_01_10_11], Some((pal, trns)),
         &[RED, B, k, 0x0000], Some(0x0000)),
    ];
    for (name, size, color, depth, px, palette, texels, key) in cases {
        let path = write_png(&format!("{name}.png"), size, color, depth, &px, palette);
        let t = load_png_texture(&path).unwrap();
        assert_eq!((t.texels.as_slice(), t.key), (texels, key), "{name}");
        assert_eq!(t.transparent, key.map_or(0, |_| 1), "{name}");
    }
}

/// The 8-bit value whose rounding gives the `levels`-level `k` back exactly.
fn expand(k: u32, levels: u32) -> u8 {
    ((k * 255 * 2 + levels) / (2 * levels)) as u8
}

/// A 512 x 256 RGBA image: pixel i has the colour of RGB565 value i mod 65536 (or of
/// `replace(i)`), the last pixel transparent.
fn all_values_png(name: &str, replace: impl Fn(u32) -> u32) -> PathBuf {
    let mut px = Vec::with_capacity(512 * 256 * 4);
    for i in 0..512 * 256u32 {
        let v = replace(i % 65536);
        px.extend([
            expand(v >> 11, 31),
            expand((v >> 5) & 63, 63),
            expand(v & 31, 31),
            255,
        ]);
    }
    let n = px.len();
    px[n - 1] = 0;
    write_png(
        name,
        (512, 256),
        png::ColorType::Rgba,
        png::BitDepth::Eight,
        &px,
        None,
    )
}

#[test]
fn the_key_is_searched_when_magenta_is_taken_and_refused_when_none_is_free() {
    // Every value but 0x1234 (magenta among them): the key is 0x1234.
    let path = all_values_png("all_but_one.png", |v| if v == 0x1234 { 0 } else { v });
    let t = load_png_texture(&path).unwrap();
    assert_eq!(t.key, Some(0x1234));
    assert_eq!(
        t.texels.iter().filter(|&&v| v == 0x1234).count(),
        1,
        "only the transparent pixel"
    );
    // The expansion round-trips: no quantization error beyond the 8-bit rounding.
    assert!(t.quantization.0 <= 0.5, "{:?}", t.quantization);
    // Every value taken: an error, not a key that an opaque texel shares.
    let path = all_values_png("all_values.png", |v| v);
    let e = load_png_texture(&path).unwrap_err();
    assert!(
        e.contains("all_values.png") && e.contains("no colour key"),
        "{e}"
    );
}

#[test]
fn bad_images_are_clear_errors_and_write_nothing() {
    let out = tmp("bad_out.rs");
    let check = |path: &Path, expect: &[&str]| {
        let _ = std::fs::remove_file(&out);
        let e = bake_texture(path, &out, None, Wrap::Repeat).unwrap_err();
        let name = path.file_name().unwrap().to_str().unwrap();
        assert!(e.contains(name), "the message does not name the file: {e}");
        for x in expect {
            assert!(e.contains(x), "{e:?} lacks {x:?}");
        }
        assert!(!out.exists() && !out.with_extension("partial").exists());
    };
    let grey = |name: &str, w: u32, h: u32| {
        write_png(
            name,
            (w, h),
            png::ColorType::Grayscale,
            png::BitDepth::Eight,
            &vec![7; (w * h) as usize],
            None,
        )
    };
    check(&grey("six_by_eight.png", 6, 8), &["6x8", "powers of two"]);
    check(&grey("eight_by_three.png", 8, 3), &["8x3", "powers of two"]);
    check(&grey("too_wide.png", 2048, 1), &["2048x1", "1024"]);
    let text = tmp("not_a_png.png");
    std::fs::write(&text, "P3\n2 2\n255\n").unwrap();
    check(&text, &["not a PNG"]);
    let cut = tmp("truncated.png");
    let bytes = std::fs::read(data("checker8.png")).unwrap();
    std::fs::write(&cut, &bytes[..bytes.len() - 30]).unwrap();
    check(&cut, &[]);
    check(&tmp("missing.png"), &["cannot read"]);
    let dir = tmp("a_directory.png");
    std::fs::create_dir_all(&dir).unwrap();
    check(&dir, &["is a directory"]);
    // A file stem with nothing to name the texture by, and no --name.
    let nameless = tmp("-.png");
    std::fs::copy(data("checker8.png"), &nameless).unwrap();
    check(&nameless, &["--name"]);
    let _ = std::fs::remove_file(&out);
    assert!(bake_texture(&nameless, &out, Some("--"), Wrap::Repeat).is_err());
    assert!(!out.exists());
    bake_texture(&nameless, &out, Some("dash"), Wrap::Repeat).unwrap();
    assert!(std::fs::read_to_string(&out)
        .unwrap()
        .contains("pub static DASH: scanline3d::Texture"));
}

#[test]
fn texture_names_are_upper_case_identifiers() {
    assert_eq!(texture_ident("checker8").unwrap(), "CHECKER8");
    assert_eq!(texture_ident("my-tex.v2").unwrap(), "MY_TEX_V2");
    assert_eq!(texture_ident("  bricks__wall ").unwrap(), "BRICKS_WALL");
    assert_eq!(texture_ident("8x8").unwrap(), "TEX_8X8");
    assert_eq!(texture_ident("héllo wörld").unwrap(), "H_LLO_W_RLD");
    assert_eq!(texture_ident("TEX_8X8").unwrap(), "TEX_8X8");
    for bad in ["", "-", "__", "ééé"] {
        assert!(texture_ident(bad).is_err(), "{bad:?}");
    }
}

#[test]
fn the_committed_texture_is_what_bake_produces_now() {
    let out = tmp("baked_checker.rs");
    let line = bake_texture(&data("checker8.png"), &out, None, Wrap::Repeat).unwrap();
    println!("{line}");
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        include_str!("../../tests/data/baked_checker.rs"),
        "tests/data/baked_checker.rs is stale: rerun \
         `cargo run -p scanline3d-tools --bin bake -- --texture tests/data/checker8.png --out tests/data/baked_checker.rs`"
    );
    for part in [
        "CHECKER8",
        "8x8 texels",
        "128 bytes of flash",
        "max 3.613",
        "0xF81F",
    ] {
        assert!(line.contains(part), "{line:?} lacks {part:?}");
    }
    // The compiled statics are the image's texels.
    let t = load_png_texture(&data("checker8.png")).unwrap();
    assert_eq!(
        baked_texture::CHECKER8_TEXELS.as_slice(),
        t.texels.as_slice()
    );
    assert_eq!(baked_texture::CHECKER8_KEY, PREFERRED_KEY);
    let tex = &baked_texture::CHECKER8;
    assert_eq!((tex.width(), tex.height()), (8, 8));
    assert_eq!(tex.wrap(), [Wrap::Repeat; 2]);
    assert_eq!(tex.texel(0, 0), RED);
    // --wrap clamp and --name reach the source; an image without transparency has no key.
    let mut opaque = t.clone();
    opaque.key = None;
    opaque.transparent = 0;
    let src = texture_rust_source("BRICKS", &opaque, Wrap::Clamp);
    assert!(src.contains("Ok(t) => t.with_wrap(scanline3d::Wrap::Clamp, scanline3d::Wrap::Clamp)"));
    assert!(src.contains("pub static BRICKS_TEXELS: [u16; 64] = ["));
    assert!(!src.contains("_KEY"), "{src}");
}

/// A `64 x 64`-pixel quad at the centre of a 160 x 120 screen, (s, t) from (0, 0) at its
/// top-left to (1, 1) at its bottom-right, with `tex` (white, unlit: the texels as they are).
fn quad_frame(tex: &'static Texture, key: Option<u16>, bg: Rgb565) -> Frame<Rgb565> {
    let positions = [
        at::<Q>(160, 120, 48.0, 28.0, 0.0),
        at(160, 120, 48.0, 92.0, 0.0),
        at(160, 120, 112.0, 92.0, 0.0),
        at(160, 120, 112.0, 28.0, 0.0),
    ];
    let normals = [[Q::ZERO, Q::ZERO, Q::ONE]; 4];
    let uvs = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]].map(|uv| uv.map(Q::from_f64));
    let indices = [[0, 1, 2], [0, 2, 3]];
    let mesh = Mesh::new(&positions, &indices)
        .unwrap()
        .with_normals(&normals)
        .unwrap()
        .with_uvs(&uvs)
        .unwrap();
    let mut material = Material::matte([255; 3], Q::ONE, Q::ZERO).textured(tex);
    if let Some(k) = key {
        material = material.color_key(k);
    }
    render_one(mesh, Mat4::identity(), material, bg)
}

fn render_one(
    mesh: Mesh<'_, Q>,
    transform: Mat4<Q>,
    material: Material<Q>,
    bg: Rgb565,
) -> Frame<Rgb565> {
    let objects = [Object {
        mesh,
        transform,
        material,
    }];
    let mut scene = Scene::new(
        &objects,
        screen_camera(120),
        [Light::white([Q::ZERO, Q::ZERO, Q::ONE])],
    );
    // The renderer clears to the scene's background: `bg` as 8-bit channels.
    let c = raw(bg) as u32;
    scene.background = [
        (c >> 11) * 255 / 31,
        ((c >> 5) & 63) * 255 / 63,
        (c & 31) * 255 / 31,
    ]
    .map(|v| v as u8);
    let mut r: Box<TexRenderer> = Box::default();
    let mut frame = Frame::new(160, 120, bg);
    r.render(&scene, &mut frame).unwrap();
    frame.assert_each_written_once();
    frame
}

fn raw(c: Rgb565) -> u16 {
    RawU16::from(c).into_inner()
}

#[test]
fn the_baked_texture_renders_texel_for_texel_with_its_key() {
    // Green: no texel of the checker.
    let bg = Rgb565::new(0, 63, 0);
    let f = quad_frame(
        &baked_texture::CHECKER8,
        Some(baked_texture::CHECKER8_KEY),
        bg,
    );
    // Each texel is 8 x 8 pixels: its centre shows it, or the background where it is the key.
    for j in 0..8 {
        for i in 0..8 {
            let got = raw(f.get(48 + 8 * i as u32 + 4, 28 + 8 * j as u32 + 4));
            let want = checker_texel(i, j).unwrap_or(raw(bg));
            assert_eq!(got, want, "texel ({i}, {j}): {got:#06X}");
        }
    }
    assert_eq!(f.get(20, 20), bg);
    // Without the key the transparent texels show as magenta.
    let f = quad_frame(&baked_texture::CHECKER8, None, bg);
    assert_eq!(raw(f.get(48 + 7 * 8 + 4, 28 + 7 * 8 + 4)), PREFERRED_KEY);
}

// ---- OBJ texture coordinates ----

fn write(name: &str, text: &str) -> PathBuf {
    let path = tmp(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn the_cube_net_splits_only_at_its_cuts() {
    let file = parse_obj(&data("cube_net.obj")).unwrap();
    assert_eq!(file.uvs_present(), Ok(true));
    let plain = file.mesh(NormalSource::FaceAverage).unwrap();
    assert_eq!(plain.positions.len(), 8);
    assert_eq!(plain.uvs, None);
    // Without texture coordinates, exactly the mesh the loader made before.
    assert_eq!(file.mesh_with(NormalSource::FaceAverage, false), Ok(plain));
    let big = file.mesh_with(NormalSource::FaceAverage, true).unwrap();
    let uvs = big.uvs.as_ref().unwrap();
    println!(
        "cube net: {} vertices, {} texture coordinates, {} triangles",
        big.positions.len(),
        uvs.len(),
        big.indices.len()
    );
    assert_eq!(
        (big.positions.len(), uvs.len(), big.indices.len()),
        (14, 14, 12)
    );
    // (s, t) = (u, 1 − v): the +Z face's corner (−0.5, −0.5, 0.5) is vt 0.25 0.25.
    let k = big
        .positions
        .iter()
        .zip(uvs)
        .position(|(p, uv)| *p == [-0.5, -0.5, 0.5] && uv[0] == 0.25)
        .unwrap();
    assert_eq!(uvs[k], [0.25, 0.75]);
    // Every triangle lies in one square of the 4 x 4 grid.
    for t in &big.indices {
        let [a, b, c] = t.map(|i| uvs[i as usize]);
        for k in 0..2 {
            let span = [a[k], b[k], c[k]];
            let (lo, hi) = span
                .iter()
                .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
            assert_eq!(hi - lo, 0.25, "{a:?} {b:?} {c:?}");
        }
    }
    // Face-averaged normals are per position: each split copy of a corner has the normal the
    // mesh without texture coordinates has there, where averaging per vertex would give a seam.
    let mesh = big.to_u16("").unwrap();
    let ns = normals_per_position(&mesh);
    let plain = file
        .mesh(NormalSource::FaceAverage)
        .unwrap()
        .to_u16("")
        .unwrap();
    let plain_normals = common::obj::vertex_normals(&plain, false);
    for (p, n) in mesh.positions.iter().zip(&ns) {
        let k = plain.positions.iter().position(|q| q == p).unwrap();
        assert_eq!(*n, plain_normals[k], "{p:?}");
    }
    let per_vertex = common::obj::vertex_normals(&mesh, false);
    assert!(per_vertex.iter().zip(&ns).any(|(a, b)| a != b));
}

#[test]
fn the_committed_cube_is_what_bake_produces_now_and_renders_upright() {
    let file = parse_obj(&data("cube_net.obj")).unwrap();
    let big = file.mesh_with(file.default_normals(), true).unwrap();
    let mesh = big.to_u16(&file.name).unwrap();
    let b = bake_with_uvs(&mesh, big.uvs.as_deref(), false, "cube_net.obj");
    assert_eq!(
        b.source,
        include_str!("../../tests/data/cube_net_mesh.rs"),
        "tests/data/cube_net_mesh.rs is stale: rerun \
         `cargo run -p scanline3d-tools --bin bake -- tests/data/cube_net.obj --out tests/data/cube_net_mesh.rs`"
    );
    assert_eq!(b.flash_bytes, 14 * (12 + 12 + 8) + 12 * 6);
    assert_eq!(baked_cube::UVS.len(), 14);
    // Front view (orthographic, down −Z), the cube 64 px wide and flattened in depth: only the
    // +Z face shows, s ∈ [0.25, 0.5], t ∈ [0.5, 0.75]. With a 32 x 32 texture whose texel
    // (i, j) is red i, green j, that is texels i 8..16, j 16..24, 8 x 8 pixels each, i across and
    // j down (t = 1 − v: the image upright).
    let s = baked_cube::SCALE * 64.0;
    let place = Mat4::scale([s, s, 1.0].map(Q::from_f64));
    let mesh = Mesh::new(&baked_cube::POSITIONS, &baked_cube::INDICES)
        .unwrap()
        .with_normals(&baked_cube::NORMALS)
        .unwrap()
        .with_uvs(&baked_cube::UVS)
        .unwrap();
    let tex = coded_texture(Wrap::Repeat, Wrap::Repeat);
    let material = Material::matte([255; 3], Q::ONE, Q::ZERO).textured(tex);
    let f = render_one(mesh, place, material, Rgb565::new(0, 63, 0));
    for j in 0..8 {
        for i in 0..8 {
            let got = raw(f.get(48 + 8 * i + 4, 28 + 8 * j + 4));
            let want = (((8 + i) << 11) | ((16 + j) << 5) | 31) as u16;
            assert_eq!(got, want, "({i}, {j}): {got:#06X}");
        }
    }
}

/// A UV sphere with `vt` (a column u = 1 repeating u = 0 at the seam, one `vt` per pole
/// triangle): OBJ text, faces counter-clockwise from outside.
fn uv_sphere(rings: usize, segs: usize) -> String {
    use std::f64::consts::PI;
    let mut s = String::new();
    let mut pos = vec![[0.0, 1.0, 0.0]];
    for i in 1..rings {
        let th = PI * i as f64 / rings as f64;
        for j in 0..segs {
            let ph = 2.0 * PI * j as f64 / segs as f64;
            pos.push([th.sin() * ph.cos(), th.cos(), -th.sin() * ph.sin()]);
        }
    }
    pos.push([0.0, -1.0, 0.0]);
    for p in &pos {
        writeln!(s, "v {} {} {}", p[0], p[1], p[2]).unwrap();
    }
    for i in 0..=rings {
        for j in 0..=segs {
            let (u, v) = (j as f64 / segs as f64, 1.0 - i as f64 / rings as f64);
            writeln!(s, "vt {u} {v}").unwrap();
        }
    }
    let p = |i: usize, j: usize| match i {
        0 => 1,
        _ if i == rings => pos.len(),
        _ => 2 + (i - 1) * segs + j % segs,
    };
    let vt = |i: usize, j: usize| i * (segs + 1) + j + 1;
    for i in 0..rings {
        for j in 0..segs {
            let quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let tris: &[[usize; 3]] = match i {
                0 => &[[0, 1, 2]],
                _ if i == rings - 1 => &[[0, 1, 3]],
                _ => &[[0, 1, 2], [0, 2, 3]],
            };
            for t in tris {
                s.push('f');
                for k in t {
                    let (a, b) = quad[*k];
                    write!(s, " {}/{}", p(a, b), vt(a, b)).unwrap();
                }
                s.push('\n');
            }
        }
    }
    s
}

#[test]
#[cfg_attr(not(feature = "simplify"), ignore = "needs the simplify feature")]
fn texture_coordinates_follow_simplification_and_sloppy_is_refused() {
    use std::f64::consts::PI;
    let (rings, segs) = (16, 32);
    let file = parse_obj(&write("uv_sphere.obj", &uv_sphere(rings, segs))).unwrap();
    let big = file.mesh_with(NormalSource::FaceAverage, true).unwrap();
    // Positions 2 + 15·32 = 482; the seam column doubles 15 of them and each pole is one
    // vertex per pole triangle: 482 − 2 + 15 + 2·32 = 559.
    assert_eq!(big.positions.len(), 559);
    // The faces wind outward (the renderer culls the others).
    for t in &big.indices {
        let [a, b, c] = t.map(|i| big.positions[i as usize]);
        let n = scanline3d::math::cross(scanline3d::math::sub(b, a), scanline3d::math::sub(c, a));
        assert!(scanline3d::math::dot(n, a) > 0.0);
    }
    let s = simplify(&big, Some(200), None).unwrap();
    let out = &s.mesh;
    let uvs = out.uvs.as_ref().unwrap();
    println!("{}", s.summary(&big));
    assert!(out.indices.len() <= 200 && out.indices.len() > 100);
    assert_eq!(uvs.len(), out.positions.len());
    // Each vertex keeps the (s, t) of its position: t the latitude, s the longitude (0 or 1 on
    // the seam, anything at a pole).
    for (p, uv) in out.positions.iter().zip(uvs) {
        let t = p[1].clamp(-1.0, 1.0).acos() / PI;
        assert!((uv[1] - t).abs() < 1e-5, "{p:?} {uv:?}");
        if p[1].abs() < 0.999 {
            let s = (-p[2]).atan2(p[0]).rem_euclid(2.0 * PI) / (2.0 * PI);
            let d = (uv[0] - s).rem_euclid(1.0);
            assert!(d.min(1.0 - d) < 1e-5, "{p:?} {uv:?} (s {s})");
        }
    }
    // No triangle spans the seam: its s range stays small.
    for t in &out.indices {
        let s = t.map(|i| uvs[i as usize][0]);
        let span =
            s.iter().cloned().fold(f64::MIN, f64::max) - s.iter().cloned().fold(f64::MAX, f64::min);
        assert!(span < 0.5, "a triangle across the seam: {s:?}");
    }
    // A budget only vertex clustering reaches: refused with texture coordinates, done without.
    let e = simplify(&big, Some(8), None).err().unwrap();
    assert!(e.contains("seams"), "{e}");
    let plain = file.mesh(NormalSource::FaceAverage).unwrap();
    assert!(simplify(&plain, Some(8), None).is_ok());
}

#[test]
fn texture_coordinates_on_only_some_faces_are_an_error() {
    let text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2 4 3\n";
    let file = parse_obj(&write("partial_vt.obj", text)).unwrap();
    let e = file.uvs_present().unwrap_err();
    for part in [
        "partial_vt.obj",
        "only some faces",
        "3 face corners have a vt",
        "line 8",
        "line 9",
    ] {
        assert!(e.contains(part), "{e:?} lacks {part:?}");
    }
    assert!(file.mesh_with(NormalSource::FaceAverage, true).is_err());
    // The mesh without them still loads (render ignores vt).
    assert_eq!(
        file.mesh(NormalSource::FaceAverage)
            .unwrap()
            .positions
            .len(),
        4
    );
    // No vt on any face (vt lines unused): no texture coordinates, no error.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n";
    let file = parse_obj(&write("unused_vt.obj", text)).unwrap();
    assert_eq!(file.uvs_present(), Ok(false));
    // A vt with one number: the line.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nf 1 2 3\n";
    let e = parse_obj(&write("short_vt.obj", text)).unwrap_err();
    assert!(e.contains(":4:") && e.contains("two numbers"), "{e}");
}

#[test]
fn texture_coordinates_beyond_the_renderers_range_are_an_error() {
    let tri =
        |vt: &str| format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n{vt}\nf 1/1 2/2 3/3\n");
    // Within ±16 once rounded to Q16.16 (t = 1 − v): accepted, and the renderer takes them.
    for (k, ok) in ["vt 15.99 1", "vt -15.99 -14.99", "vt 0 16.99"]
        .iter()
        .enumerate()
    {
        let file = parse_obj(&write(&format!("ok_vt{k}.obj"), &tri(ok))).unwrap();
        let big = file.mesh_with(NormalSource::FaceAverage, true).unwrap();
        let uvs: Vec<[Q; 2]> = big
            .uvs
            .unwrap()
            .iter()
            .map(|uv| uv.map(Q::from_f64))
            .collect();
        let pos = [[Q::ZERO; 3]; 3];
        assert!(
            Mesh::new(&pos, &[[0, 1, 2]])
                .unwrap()
                .with_uvs(&uvs)
                .is_ok(),
            "{ok}"
        );
    }
    // 16, beyond, 15.999999 (16 once rounded to Q16.16), v = −15.5 (t = 16.5), infinite.
    for (k, bad) in [
        "vt 16 0",
        "vt 0.5 -15.5",
        "vt 15.999999 0",
        "vt -17 0",
        "vt 1e39 0",
    ]
    .iter()
    .enumerate()
    {
        let name = format!("bad_vt{k}.obj");
        let file = parse_obj(&write(&name, &tri(bad))).unwrap();
        let e = file.mesh_with(NormalSource::FaceAverage, true).unwrap_err();
        assert!(e.contains(&name) && e.contains("UV_LIMIT"), "{bad}: {e}");
        // Only where they are used: the mesh without them loads.
        assert!(file.mesh(NormalSource::FaceAverage).is_ok());
    }
}
