//! Renders the default scene (the benchmark torus) with the fixed-point pipeline into
//! `scanline3d.png` and prints one summary line: triangles in / culled / clipped / drawn, pixels
//! written, host time per frame (median), and the error against the f64 twin of the pipeline.
//!
//! `cargo run --release --example render [-- --out FILE.png]`

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::demo;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::Stats;

const W: usize = 240;
const H: usize = 240;
type R<S> = demo::TorusRenderer<S, Rgb565>;

fn render<S: Scalar>(runs: usize) -> Result<(Frame<Rgb565>, Stats, f64), String> {
    let shape = demo::torus::<S>().map_err(|e| format!("torus: {e:?}"))?;
    let objects = [demo::torus_object(&shape)];
    let camera = demo::camera::<S>().map_err(|e| format!("camera: {e:?}"))?;
    let scene = Scene::new(&objects, camera, demo::lights());
    let mut r: Box<R<S>> = Box::default();
    let mut frame = Frame::new(W as u32, H as u32, Rgb565::BLACK);
    let mut times = Vec::new();
    let mut stats = Stats::default();
    for _ in 0..runs.max(1) {
        frame = Frame::new(W as u32, H as u32, Rgb565::BLACK);
        let t = Instant::now();
        stats = r
            .render(&scene, &mut frame)
            .map_err(|e| format!("render: {e:?}"))?;
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(|a, b| a.total_cmp(b));
    Ok((frame, stats, times[times.len() / 2]))
}

/// PSNR over all RGB565 channels, each normalized to its own range.
fn psnr(a: &Frame<Rgb565>, b: &Frame<Rgb565>) -> f64 {
    let mut se = 0.0;
    for (x, y) in a.px.iter().zip(b.px.iter()) {
        se += ((x.r() as f64 - y.r() as f64) / 31.0).powi(2);
        se += ((x.g() as f64 - y.g() as f64) / 63.0).powi(2);
        se += ((x.b() as f64 - y.b() as f64) / 31.0).powi(2);
    }
    let mse = se / (3.0 * a.px.len() as f64);
    if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (1.0 / mse).log10()
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut out = "scanline3d.png".to_string();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--out" => match it.next() {
                Some(f) => out = f.clone(),
                None => fail("--out needs a file name"),
            },
            "--help" | "-h" => {
                println!("usage: render [--out FILE.png]   (default: scanline3d.png)");
                return;
            }
            other => fail(&format!("unknown argument {other:?} (see --help)")),
        }
    }
    let (frame, stats, secs) = render::<Fx<I16F16>>(21).unwrap_or_else(|e| fail(&e));
    let (reference, _, _) = render::<f64>(1).unwrap_or_else(|e| fail(&e));
    let (max, differ, coverage) = common::compare565(&frame, &reference, Rgb565::BLACK);
    let bytes = common::png_bytes(&frame);
    // Write to a temporary name first so a failure never leaves a half-written image.
    let tmp = format!("{out}.tmp");
    if let Err(e) = std::fs::write(&tmp, &bytes).and_then(|_| std::fs::rename(&tmp, &out)) {
        let _ = std::fs::remove_file(&tmp);
        fail(&format!("{out}: {e}"));
    }
    println!(
        "{out}: {W}x{H} I16F16 | triangles in {} / culled {} / clipped {} / drawn {} | pixels written {} | {:.3} ms/frame (host, median of 21) | vs f64: max LSB r{} g{} b{}, PSNR {:.1} dB, {} pixels differ, {} coverage mismatches | max active {} | renderer RAM {} B (W={W} H={H} LINES=1 VERTS=512 TRIS=512 ACTIVE=64)",
        stats.triangles_in,
        stats.culled,
        stats.clipped,
        stats.drawn,
        stats.pixels_written,
        secs * 1e3,
        max[0],
        max[1],
        max[2],
        psnr(&frame, &reference),
        differ,
        coverage,
        stats.max_active,
        R::<Fx<I16F16>>::RAM_BYTES,
    );
}

fn fail(msg: &str) -> ! {
    eprintln!("render: {msg}");
    std::process::exit(2);
}
