//! Dumps the benchmark frames as raw RGB565 and compares two such dumps, for
//! `scripts/frame-diff` (which frames changed between two revisions, and by how much).
//!
//! ```sh
//! cargo run --release --example bench_frames -- render DIR
//! cargo run --release --example bench_frames -- compare OLD_DIR NEW_DIR
//! ```
//!
//! `render` writes `DIR/NAME.bin` for every frame in [`FRAMES`]: each scene of
//! [`demo::Bench`] at spin 0 in `Fx<I16F16>` (`render_bench`, undithered), the dithered torus,
//! and two Pico firmware frames (`demo::board`, as `tools/src/bin/board_frames.rs` renders them);
//! 240 × 240 RGB565 big-endian, row-major, written atomically. `compare` prints, per frame, the
//! pixels that differ and the largest difference per channel in RGB565 steps (red and blue
//! 0..31, green 0..63).
//!
//! `scripts/frame-diff` copies this file into an older revision to build it there, so it uses
//! only APIs that already existed in commit 3431c8b.

use std::path::Path;
use std::process::ExitCode;

use embedded_graphics::pixelcolor::raw::ToBytes;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use scanline3d::fixed::types::I16F16;
use scanline3d::{probe::NoProbe, Fx};
use scanline3d_support::demo::{self, board, Bench};

type Q = Fx<I16F16>;

const SIZE: usize = 240;

/// What a frame is.
#[derive(Copy, Clone)]
enum Kind {
    /// A benchmark scene, dithered or not.
    Bench(Bench, bool),
    /// A Pico firmware frame: frame number and the microseconds its fps label shows (0: none).
    Board(u32, u64),
}

/// Every frame, in report order.
const FRAMES: [(&str, Kind); 9] = [
    ("cube", Kind::Bench(Bench::Cube, false)),
    ("torus", Kind::Bench(Bench::Torus, false)),
    ("torus-dither", Kind::Bench(Bench::Torus, true)),
    ("icosphere", Kind::Bench(Bench::Icosphere, false)),
    ("terrain", Kind::Bench(Bench::Terrain, false)),
    ("overdraw", Kind::Bench(Bench::Overdraw, false)),
    ("deep", Kind::Bench(Bench::Deep, false)),
    ("board-0000", Kind::Board(0, 0)),
    ("board-0007", Kind::Board(7, 28_571)),
];

/// A 240 × 240 RGB565 frame buffer.
struct Buffer(Vec<Rgb565>);

impl OriginDimensions for Buffer {
    fn size(&self) -> Size {
        Size::new(SIZE as u32, SIZE as u32)
    }
}

impl DrawTarget for Buffer {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(p, c) in pixels {
            if (0..SIZE as i32).contains(&p.x) && (0..SIZE as i32).contains(&p.y) {
                self.0[p.y as usize * SIZE + p.x as usize] = c;
            }
        }
        Ok(())
    }
}

fn render(kind: Kind) -> Result<Vec<u8>, String> {
    let px = match kind {
        Kind::Bench(b, dither) => {
            let mut f = Buffer(vec![Rgb565::BLACK; SIZE * SIZE]);
            demo::render_bench::<Q, Rgb565, _, _>(b, 0.0, dither, &mut f, &mut NoProbe)
                .map_err(|e| format!("{}: {e}", b.name()))?;
            f.0
        }
        Kind::Board(frame, us) => {
            let shape =
                scanline3d_support::demo::torus::<Q>().map_err(|e| format!("torus: {e}"))?;
            let scene = board::BoardScene::new(&shape)?;
            let glyphs = board::glyphs().map_err(|e| format!("glyphs: {e:?}"))?;
            let mut renderer = Box::new(board::renderer::<Q>());
            let mut prepared = scene
                .prepare(&mut renderer, frame)
                .map_err(|e| format!("board frame {frame}: {e:?}"))?;
            let label = board::fps_label(us);
            let mut buffer: board::StripBuffer = [[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES];
            let mut px = vec![Rgb565::BLACK; SIZE * SIZE];
            while let Some(rows) = board::draw_strip(&mut prepared, &glyphs, &label, &mut buffer) {
                for (i, row) in rows.enumerate() {
                    px[row * SIZE..(row + 1) * SIZE].copy_from_slice(&buffer[i]);
                }
            }
            px
        }
    };
    Ok(px.iter().flat_map(|c| c.to_be_bytes()).collect())
}

fn render_all(dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (name, kind) in FRAMES {
        let bytes = render(kind)?;
        let path = dir.join(format!("{name}.bin"));
        let tmp = path.with_extension("tmp");
        std::fs::write(&tmp, &bytes).map_err(|e| format!("{}: {e}", tmp.display()))?;
        std::fs::rename(&tmp, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

/// Red, green and blue of a big-endian RGB565 pixel.
fn channels(p: &[u8]) -> [i32; 3] {
    let v = i32::from(u16::from_be_bytes([p[0], p[1]]));
    [v >> 11, (v >> 5) & 63, v & 31]
}

fn compare(old: &Path, new: &Path) -> Result<(), String> {
    let read = |dir: &Path, name: &str| {
        let path = dir.join(format!("{name}.bin"));
        std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))
    };
    println!(
        "{:<14} {:>8} {:>8} {:>8}  max step (R/31 G/63 B/31)",
        "frame", "differ", "pixels", "share"
    );
    let (mut changed, mut total_diff) = (0, 0);
    for (name, _) in FRAMES {
        let (a, b) = (read(old, name)?, read(new, name)?);
        if a.len() != b.len() || a.len() != SIZE * SIZE * 2 {
            return Err(format!(
                "{name}: frames of {} and {} bytes",
                a.len(),
                b.len()
            ));
        }
        let mut differ = 0;
        let mut max = [0; 3];
        for (p, q) in a.chunks_exact(2).zip(b.chunks_exact(2)) {
            if p != q {
                differ += 1;
                let (p, q) = (channels(p), channels(q));
                for k in 0..3 {
                    max[k] = max[k].max((p[k] - q[k]).abs());
                }
            }
        }
        let pixels = SIZE * SIZE;
        println!(
            "{name:<14} {differ:>8} {pixels:>8} {:>7.3}%  {} / {} / {}",
            100.0 * differ as f64 / pixels as f64,
            max[0],
            max[1],
            max[2]
        );
        changed += usize::from(differ > 0);
        total_diff += differ;
    }
    println!(
        "{changed} of {} frames changed, {total_diff} pixels in all",
        FRAMES.len()
    );
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["render", dir] => render_all(Path::new(dir)),
        ["compare", old, new] => compare(Path::new(old), Path::new(new)),
        _ => {
            eprintln!("usage: bench_frames render DIR | bench_frames compare OLD_DIR NEW_DIR");
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bench_frames: {e}");
            ExitCode::FAILURE
        }
    }
}
