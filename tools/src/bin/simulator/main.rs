//! The simulator front end: the renderer drawing into an embedded-graphics-simulator display,
//! as a firmware draws into its panel's driver.
//!
//! `cargo run --release -p scanline3d-tools --features simulator --bin simulator` opens a
//! window with the default scene (the benchmark torus); the arrow keys and a drag with the
//! left mouse button orbit it, Home resets the view, Esc or Q quits; the host's time per frame
//! is drawn in the top-left corner. `--scene NAME` shows another built-in scene, `--obj FILE`
//! an OBJ model. `--headless --out FILE.png` draws one frame into the simulator's display
//! without a window and writes the simulator's output image (what the window shows) as PNG:
//! that needs only the `simulator-headless` feature, which builds no SDL2.
//!
//! Exit status: 0, 1 when a frame, the window or the output failed, 2 for bad arguments (a
//! missing or bad OBJ, an unknown scene: the message says which).

// The window uses all of it; a headless build leaves the orbit's steps and the error
// screen unused.
#[cfg_attr(not(feature = "simulator"), allow(dead_code))]
mod scene;
#[cfg(feature = "simulator")]
mod window;

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Parser;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettings, OutputSettingsBuilder, SimulatorDisplay};
use scene::{draw_label, frame_time_text, View, Viewer, SIZE};

/// Draws a built-in scene or an OBJ model with scanline3d into an embedded-graphics-simulator
/// display (240×240 RGB565): in a window (arrow keys or a left-button drag orbit, Home resets,
/// Esc or Q quits), or headless into a PNG.
#[derive(Parser, Debug)]
#[command(name = "simulator")]
struct Args {
    /// Built-in scene: a benchmark scene of the support crate (torus, cube, icosphere, terrain,
    /// shadow, textured, phong, …; a wrong name lists them all) [default: torus]. Only the
    /// torus and OBJ models pitch; the other scenes turn about the vertical axis only
    #[arg(long, value_name = "NAME", value_parser = scene::bench_named, conflicts_with = "obj")]
    scene: Option<scanline3d_support::demo::Bench>,
    /// OBJ model, centred, scaled and framed as `render --obj FILE --fit` frames it
    #[arg(long, value_name = "FILE")]
    obj: Option<PathBuf>,
    /// Initial yaw, whole degrees about the vertical axis
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0
    )]
    yaw: i32,
    /// Initial pitch, whole degrees about the horizontal axis, −90 to 90 (the torus and OBJ
    /// models only)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = 0,
          value_parser = clap::value_parser!(i32).range(-90..=90))]
    pitch: i32,
    /// Output pixels per display pixel (the window's and the PNG's)
    #[arg(long, value_name = "N", default_value_t = 2,
          value_parser = clap::value_parser!(u32).range(1..=8))]
    scale: u32,
    /// No window: draw one frame (the frame time measured over 5 renders) and write it to
    /// --out
    #[arg(long, requires = "out")]
    headless: bool,
    /// The PNG --headless writes (through a temporary file: never half-written)
    #[arg(long, value_name = "FILE.png", requires = "headless")]
    out: Option<PathBuf>,
}

/// Renders timed for the headless frame's label (the median is shown).
const HEADLESS_RUNS: usize = 5;

fn main() {
    let code = match run(Args::parse()) {
        Ok(()) => 0,
        Err((msg, code)) => {
            eprintln!("simulator: {msg}");
            code
        }
    };
    std::process::exit(code);
}

fn run(args: Args) -> Result<(), (String, i32)> {
    if let Some(out) = &args.out {
        let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !ext.eq_ignore_ascii_case("png") {
            return Err((format!("{}: --out must end in .png", out.display()), 2));
        }
    }
    let mut viewer = match (&args.obj, args.scene) {
        (Some(path), _) => Viewer::obj(path),
        (None, Some(bench)) => Viewer::bench(bench),
        (None, None) => Viewer::torus(),
    }
    .map_err(|e| (e, 2))?;
    if args.pitch != 0 && !viewer.pitches() {
        return Err((
            format!(
                "--pitch: scene {} turns about the vertical axis only (the support crate's \
                 render_bench takes one spin angle); the torus and OBJ models pitch",
                viewer.name
            ),
            2,
        ));
    }
    let view = View::new(args.yaw, args.pitch);
    let settings = OutputSettingsBuilder::new().scale(args.scale).build();
    match &args.out {
        Some(out) => headless(&mut viewer, view, &settings, out).map_err(|e| (e, 1)),
        None => window_or_refuse(&mut viewer, view, &settings),
    }
}

/// The display the renderer draws into.
fn display() -> SimulatorDisplay<Rgb565> {
    SimulatorDisplay::new(Size::new(SIZE, SIZE))
}

/// One frame into the simulator's display, its label over it, written through the simulator's
/// output image (PNG) to a temporary file, then renamed to `out`.
fn headless(
    viewer: &mut Viewer,
    view: View,
    settings: &OutputSettings,
    out: &Path,
) -> Result<(), String> {
    let mut display = display();
    let mut times = Vec::new();
    let mut st = scanline3d::Stats::default();
    for _ in 0..HEADLESS_RUNS {
        let t = Instant::now();
        st = viewer.draw(view, &mut display)?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    let ms = times[times.len() / 2];
    let Ok(_) = draw_label(&mut display, &frame_time_text(ms));
    let tmp = out.with_extension("partial");
    let written = display
        .to_rgb_output_image(settings)
        .save_png(&tmp)
        .map_err(|e| e.to_string())
        .and_then(|()| std::fs::rename(&tmp, out).map_err(|e| e.to_string()));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(format!("{}: {e}", out.display()));
    }
    println!(
        "{}: {} yaw {}° pitch {}° | triangles in {} / drawn {} | pixels written {} | {ms:.3} \
         ms/frame (host, median of {HEADLESS_RUNS}, into the simulator's display)",
        out.display(),
        viewer.name,
        view.yaw,
        view.pitch,
        st.triangles_in,
        st.drawn,
        st.pixels_written,
    );
    Ok(())
}

#[cfg(not(feature = "simulator"))]
fn window_or_refuse(_: &mut Viewer, _: View, _: &OutputSettings) -> Result<(), (String, i32)> {
    Err((
        "this build has no window (built with `simulator-headless` only): rebuild with \
         `--features simulator` (SDL2: apt-get install libsdl2-dev), or pass --headless --out \
         FILE.png"
            .into(),
        2,
    ))
}

#[cfg(feature = "simulator")]
fn window_or_refuse(
    viewer: &mut Viewer,
    view: View,
    settings: &OutputSettings,
) -> Result<(), (String, i32)> {
    window::run(viewer, view, settings)
}
