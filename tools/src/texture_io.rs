//! PNG textures for the host tools (`tools/src/bin/bake.rs --texture`) and their tests: a PNG of any
//! colour type and bit depth (the png crate decodes and expands it), quantized to RGB565 by
//! rounding, its transparent pixels made one colour key, and the Rust source of a `static`
//! [`scanline3d::Texture`] for `include!`.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::Path;

use scanline3d::{limits::MAX_TEXTURE_SIZE, Wrap};

use crate::atomic::write_atomic;

/// The colour key chosen when no opaque texel has it: magenta (red 31, green 0, blue 31).
pub const PREFERRED_KEY: u16 = 0xF81F;

/// A PNG image as RGB565 texels.
#[derive(Clone, Debug, PartialEq)]
pub struct PngTexture {
    pub width: u32,
    pub height: u32,
    /// Row-major, top row first; a transparent pixel is [`Self::key`].
    pub texels: Vec<u16>,
    /// The value of every transparent pixel (alpha below one half), used by no opaque texel:
    /// [`PREFERRED_KEY`] when free, else the lowest free value; `None` when no pixel is
    /// transparent.
    pub key: Option<u16>,
    /// The largest and the mean quantization error, in 8-bit units (0..=255 a channel), over
    /// every channel of the opaque pixels: |value − its RGB565 level|, both on the 8-bit scale
    /// (a 5-bit level k is k·255/31, a 6-bit one k·255/63; a 16-bit value v is v·255/65535).
    pub quantization: (f64, f64),
    /// How many pixels are transparent.
    pub transparent: usize,
    /// The file's name (without its directory) and format, for the source's header.
    pub file: String,
    pub format: String,
}

/// The level `0..=levels` nearest to `v` on a `0..=max` scale: round(v·levels/max), in integers
/// (never a tie: `max` is odd and `2·v·levels` even).
fn level(v: u32, max: u32, levels: u32) -> u32 {
    (2 * v * levels + max) / (2 * max)
}

/// Reads a PNG file of any colour type (grey, grey with alpha, RGB, RGBA, palette, with or
/// without a `tRNS` chunk) and bit depth (1 to 16) as RGB565 texels. 16-bit samples are rounded
/// from their 16 bits (not cut to 8 first). An error names the file unless it is a PNG image
/// whose width and height are powers of two up to [`MAX_TEXTURE_SIZE`].
pub fn load_png_texture(path: &Path) -> Result<PngTexture, String> {
    let name = path.display();
    if path.is_dir() {
        return Err(format!("{name}: is a directory, not a PNG file"));
    }
    let file = std::fs::File::open(path).map_err(|e| format!("{name}: cannot read: {e}"))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    // Palette to RGB(A), grey of 1, 2 or 4 bits to 8, tRNS to an alpha channel; 16-bit
    // samples stay 16-bit (png's STRIP_16 would cut them to their high byte, not round).
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder
        .read_info()
        .map_err(|e| format!("{name}: not a PNG image the png crate can read: {e}"))?;
    let (width, height) = reader.info().size();
    let format = format!(
        "{:?}, {} bits per sample",
        reader.info().color_type,
        reader.info().bit_depth as u8
    );
    let fits = |n: u32| n.is_power_of_two() && n <= MAX_TEXTURE_SIZE;
    if !fits(width) || !fits(height) {
        return Err(format!(
            "{name}: {width}x{height} pixels: a texture's width and height must be powers of \
             two from 1 to {MAX_TEXTURE_SIZE}"
        ));
    }
    let mut buf = vec![0; reader.output_buffer_size()];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("{name}: cannot decode the image: {e}"))?;
    let (color, depth) = reader.output_color_type();
    let (bytes, max) = match depth {
        png::BitDepth::Eight => (1, 255u32),
        png::BitDepth::Sixteen => (2, 65535),
        d => {
            return Err(format!(
                "{name}: unexpected bit depth {d:?} after expansion"
            ))
        }
    };
    let channels = color.samples();
    let sample = |row: &[u8], k: usize| -> u32 {
        if bytes == 1 {
            row[k] as u32
        } else {
            u16::from_be_bytes([row[2 * k], row[2 * k + 1]]) as u32
        }
    };
    let mut texels = Vec::with_capacity((width * height) as usize);
    // Where the transparent pixels go, once the key is known; the values opaque texels use.
    let mut transparent = Vec::new();
    let mut used = vec![false; 1 << 16];
    let (mut worst, mut sum, mut opaque) = (0.0f64, 0.0f64, 0usize);
    for y in 0..height as usize {
        let row = &buf[y * frame.line_size..][..frame.line_size];
        for x in 0..width as usize {
            let s = |c: usize| sample(row, x * channels + c);
            let (rgb, alpha) = match color {
                png::ColorType::Grayscale => ([s(0); 3], max),
                png::ColorType::GrayscaleAlpha => ([s(0); 3], s(1)),
                png::ColorType::Rgb => ([s(0), s(1), s(2)], max),
                png::ColorType::Rgba => ([s(0), s(1), s(2)], s(3)),
                png::ColorType::Indexed => {
                    return Err(format!("{name}: the palette was not expanded"))
                }
            };
            // Transparent: alpha below one half (below 128 of 255).
            if alpha * 255 < 128 * max {
                transparent.push(texels.len());
                texels.push(0);
                continue;
            }
            let mut word = 0u16;
            for (c, (shift, levels)) in rgb.into_iter().zip([(11, 31), (5, 63), (0, 31)]) {
                let k = level(c, max, levels);
                word |= (k << shift) as u16;
                let e = (c as f64 * 255.0 / max as f64 - k as f64 * 255.0 / levels as f64).abs();
                worst = worst.max(e);
                sum += e;
            }
            opaque += 1;
            used[word as usize] = true;
            texels.push(word);
        }
    }
    let key = if transparent.is_empty() {
        None
    } else {
        let free = std::iter::once(PREFERRED_KEY)
            .chain(0..=u16::MAX)
            .find(|&v| !used[v as usize])
            .ok_or_else(|| {
                format!(
                    "{name}: its opaque pixels use every one of the 65536 RGB565 values: no \
                     colour key is left for its {} transparent pixels",
                    transparent.len()
                )
            })?;
        for &k in &transparent {
            texels[k] = free;
        }
        Some(free)
    };
    let file = path
        .file_name()
        .map_or_else(|| name.to_string(), |n| n.to_string_lossy().into_owned());
    Ok(PngTexture {
        width,
        height,
        texels,
        key,
        quantization: (worst, sum / (3 * opaque).max(1) as f64),
        transparent: transparent.len(),
        file,
        format,
    })
}

/// An upper-case Rust identifier from `raw` (a `--name` or a file stem): ASCII letters and
/// digits upper-cased, every run of other characters one `_`, none at either end, `TEX_` before
/// a leading digit. An error when nothing is left.
pub fn texture_ident(raw: &str) -> Result<String, String> {
    let mut s = String::new();
    for ch in raw.chars() {
        if ch.is_ascii_alphanumeric() {
            s.push(ch.to_ascii_uppercase());
        } else if !s.is_empty() && !s.ends_with('_') {
            s.push('_');
        }
    }
    let s = s.trim_end_matches('_');
    match s.chars().next() {
        None => Err(format!(
            "{raw:?} has no ASCII letter or digit to make the texture's Rust name of: give one \
             with --name"
        )),
        Some(c) if c.is_ascii_digit() => Ok(format!("TEX_{s}")),
        Some(_) => Ok(s.to_string()),
    }
}

/// Rust source for `include!`: `{name}_TEXELS` (the RGB565 words), the `static` texture `name`
/// with `wrap` on both axes, and `{name}_KEY` when the image has transparent pixels. `name`
/// must be what [`texture_ident`] makes.
pub fn texture_rust_source(name: &str, tex: &PngTexture, wrap: Wrap) -> String {
    assert_eq!(
        texture_ident(name).as_deref(),
        Ok(name),
        "not a texture name"
    );
    let (w, h, n) = (tex.width, tex.height, tex.texels.len());
    let wrap_flag = format!("{wrap:?}").to_lowercase();
    let mut s = format!(
        "// Baked by `cargo run --release -p scanline3d-tools --bin bake -- --texture {file} --name {name} --wrap {wrap_flag}`
// from {file} ({format}). Do not edit.
//
// {w} x {h} texels, RGB565 (red bits 11..15, green 5..10, blue 0..4), {bytes} bytes of flash.
// Quantized by rounding: largest error {worst:.3}, mean {mean:.3} (8-bit units, every channel of
// the {opaque} opaque pixels).
",
        file = tex.file,
        format = tex.format,
        bytes = 2 * n,
        worst = tex.quantization.0,
        mean = tex.quantization.1,
        opaque = n - tex.transparent,
    );
    if let Some(key) = tex.key {
        let _ = writeln!(
            s,
            "// {} transparent pixels (alpha below one half) are the colour key {key:#06X}, the value of no\n\
             // opaque texel: `Material::color_key({name}_KEY)` leaves them undrawn.",
            tex.transparent
        );
    }
    let _ = write!(
        s,
        "
/// The texels, row-major, top row first.
pub static {name}_TEXELS: [u16; {n}] = ["
    );
    let per_line = w.min(16) as usize;
    for (k, t) in tex.texels.iter().enumerate() {
        s.push_str(if k % per_line == 0 { "\n    " } else { " " });
        let _ = write!(s, "{t:#06X},");
    }
    let _ = write!(
        s,
        "
];

/// The {w} x {h} texture, wrap {wrap_flag} across (s) and down (t).
pub static {name}: scanline3d::Texture =
    match scanline3d::Texture::new(&{name}_TEXELS, {w}, {h}) {{
        Ok(t) => t.with_wrap(scanline3d::Wrap::{wrap:?}, scanline3d::Wrap::{wrap:?}),
        Err(_) => panic!(\"{name}: not a texture size\"),
    }};
"
    );
    if let Some(key) = tex.key {
        let _ = write!(
            s,
            "
/// The value of the transparent texels, for `Material::color_key`.
pub const {name}_KEY: u16 = {key:#06X};
"
        );
    }
    s
}

/// `bake --texture`: reads `png`, writes the Rust source of its texture to `out` atomically,
/// and returns the line the tool prints (size, flash, quantization error, key).
pub fn bake_texture(
    png: &Path,
    out: &Path,
    name: Option<&str>,
    wrap: Wrap,
) -> Result<String, String> {
    let tex = load_png_texture(png)?;
    let raw = match name {
        Some(n) => n.to_string(),
        None => png
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
    };
    let ident = texture_ident(&raw).map_err(|e| format!("{}: {e}", png.display()))?;
    write_atomic(out, &texture_rust_source(&ident, &tex, wrap))?;
    let key = match tex.key {
        Some(k) => format!(
            ", {} transparent pixels as the colour key {k:#06X} ({ident}_KEY)",
            tex.transparent
        ),
        None => String::new(),
    };
    Ok(format!(
        "{}: {ident}, {}x{} texels, {} bytes of flash, quantization error max {:.3} mean {:.3} \
         (8-bit units){key}",
        out.display(),
        tex.width,
        tex.height,
        2 * tex.texels.len(),
        tex.quantization.0,
        tex.quantization.1,
    ))
}
