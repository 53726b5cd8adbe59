//! Renders frames of the Raspberry Pi Pico firmware (`examples/pico_st7789.rs`) on the host,
//! with the library code the firmware runs (`scanline3d_support::demo::board`), for the emulator check
//! in `scripts/pico-emu`: the emulator's captured frames must equal these bit for bit.
//!
//! ```sh
//! cargo run --release -p scanline3d-tools --bin board_frames -- --out DIR --frame 0:0 --frame 1:28571 --png
//! ```
//!
//! Each `--frame K:US` writes `DIR/host-KKKK.bin`: frame number `K` (spin `3·K` degrees) with
//! the fps label the firmware shows after a previous frame of `US` microseconds (0: no label),
//! 240 × 240 RGB565 big-endian, row-major, 115 200 bytes. `--png` also writes
//! `DIR/host-KKKK.png`. Files are written atomically (a temporary file, then a rename).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use embedded_graphics::pixelcolor::raw::ToBytes;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::fixed::types::I16F16;
use scanline3d::Fx;
use scanline3d_support::demo::board;
use scanline3d_tools::atomic::write_atomic;

type Q = Fx<I16F16>;

#[derive(Parser, Debug)]
#[command(about = "Renders Pico firmware frames on the host (RGB565 big-endian, 240 x 240)")]
struct Args {
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// A frame to render, as FRAME:MICROSECONDS (frame number; the previous frame's time that
    /// its label shows, 0 for no label). Repeatable.
    #[arg(long = "frame", value_parser = parse_frame, required = true)]
    frames: Vec<(u32, u64)>,
    /// Also write each frame as PNG.
    #[arg(long)]
    png: bool,
}

fn parse_frame(s: &str) -> Result<(u32, u64), String> {
    let (k, us) = s
        .split_once(':')
        .ok_or_else(|| format!("`{s}`: expected FRAME:MICROSECONDS, e.g. 3:28571"))?;
    let k = k
        .parse()
        .map_err(|e| format!("`{s}`: frame number `{k}`: {e}"))?;
    let us = us
        .parse()
        .map_err(|e| format!("`{s}`: microseconds `{us}`: {e}"))?;
    Ok((k, us))
}

/// Frame `frame` with the label for `us`, as big-endian RGB565 bytes.
fn render(frame: u32, us: u64) -> Result<Vec<u8>, String> {
    let shape = scanline3d_support::demo::torus::<Q>().map_err(|e| format!("torus: {e}"))?;
    let scene = board::BoardScene::new(&shape)?;
    let glyphs = board::glyphs().map_err(|e| format!("glyphs: {e:?}"))?;
    let mut renderer = Box::new(board::renderer::<Q>());
    let mut prepared = scene
        .prepare(&mut renderer, frame)
        .map_err(|e| format!("frame {frame}: {e:?}"))?;
    let label = board::fps_label(us);
    let mut buffer: board::StripBuffer = [[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES];
    let mut out = vec![0u8; board::SIZE * board::SIZE * 2];
    while let Some(rows) = board::draw_strip(&mut prepared, &glyphs, &label, &mut buffer) {
        for (i, row) in rows.enumerate() {
            let dst = &mut out[row * board::SIZE * 2..(row + 1) * board::SIZE * 2];
            for (c, d) in buffer[i].iter().zip(dst.chunks_exact_mut(2)) {
                d.copy_from_slice(&c.to_be_bytes());
            }
        }
    }
    Ok(out)
}

fn png_bytes(be565: &[u8]) -> Result<Vec<u8>, String> {
    let mut rgb = Vec::with_capacity(board::SIZE * board::SIZE * 3);
    for p in be565.chunks_exact(2) {
        let v = u16::from_be_bytes([p[0], p[1]]) as u32;
        let (r, g, b) = (v >> 11, (v >> 5) & 63, v & 31);
        rgb.extend(
            [
                (r * 255 + 15) / 31,
                (g * 255 + 31) / 63,
                (b * 255 + 15) / 31,
            ]
            .map(|c| c as u8),
        );
    }
    let mut png = Vec::new();
    let mut enc = png::Encoder::new(&mut png, board::SIZE as u32, board::SIZE as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().map_err(|e| e.to_string())?;
    w.write_image_data(&rgb).map_err(|e| e.to_string())?;
    drop(w);
    Ok(png)
}

fn run(args: &Args) -> Result<(), String> {
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    for &(k, us) in &args.frames {
        let bytes = render(k, us)?;
        write_atomic(&args.out.join(format!("host-{k:04}.bin")), &bytes)?;
        if args.png {
            write_atomic(
                &args.out.join(format!("host-{k:04}.png")),
                &png_bytes(&bytes)?,
            )?;
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("board_frames: {e}");
            ExitCode::FAILURE
        }
    }
}
