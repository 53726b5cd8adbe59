//! The simulator front end without a window (the `simulator-headless` feature: no SDL2): its
//! scenes drawn into embedded-graphics-simulator's `SimulatorDisplay` equal the host's render
//! of the same scenes into the support crate's `Frame` pixel for pixel (same renderer, same
//! scene, only the target differs); its default frame is the benchmark torus's golden image;
//! and the `simulator` binary's `--headless --out` screenshot (the simulator's own output image)
//! is that frame with the frame-time label over it. Bad arguments exit non-zero with a message.

#[allow(dead_code)]
#[path = "../src/bin/simulator/scene.rs"]
mod scene;
mod shared;

use std::path::{Path, PathBuf};
use std::process::Command;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_simulator::SimulatorDisplay;
use scanline3d::probe::NoProbe;
use scanline3d_support::demo::{render_bench, Bench};
use scanline3d_tools::obj::to_obj;
use scanline3d_tools::{golden_dir, read_png, Frame};
use scene::{View, Viewer, SIZE};

fn frame() -> Frame<Rgb565> {
    Frame::new(SIZE, SIZE, Rgb565::new(1, 2, 3))
}

fn display() -> SimulatorDisplay<Rgb565> {
    SimulatorDisplay::new(Size::new(SIZE, SIZE))
}

/// Draws `viewer` from `view` into a simulator display and into a `Frame`; asserts they are
/// equal pixel for pixel and that the frame's pixels were each written once; returns the frame.
fn both(viewer: &mut Viewer, view: View) -> Frame<Rgb565> {
    let mut d = display();
    let mut f = frame();
    let sd = viewer.draw(view, &mut d).expect("draw into the simulator");
    let sf = viewer.draw(view, &mut f).expect("draw into the frame");
    assert_eq!(sd, sf, "{} {view:?}: stats", viewer.name);
    f.assert_each_written_once();
    let differ = (0..SIZE)
        .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
        .filter(|&(x, y)| d.get_pixel(Point::new(x as i32, y as i32)) != f.get(x, y))
        .count();
    assert_eq!(differ, 0, "{} {view:?}: pixels differ", viewer.name);
    assert!(sf.pixels_written > 1000, "{} {view:?}: {sf:?}", viewer.name);
    f
}

/// The support crate's benchmark frame of `bench` at spin `yaw`, into a `Frame`.
fn bench_frame(bench: Bench, yaw: i32) -> Frame<Rgb565> {
    let mut f = frame();
    render_bench::<scene::Q, Rgb565, _, _>(bench, f64::from(yaw), false, &mut f, &mut NoProbe)
        .unwrap_or_else(|e| panic!("{bench:?} at {yaw}°: {e}"));
    f
}

fn golden_torus() -> Vec<u8> {
    let path = golden_dir().join("torus_gouraud_I16F16.png");
    let (w, h, rgb) = read_png(&path).unwrap_or_else(|| panic!("{}", path.display()));
    assert_eq!((w, h), (SIZE, SIZE));
    rgb
}

#[test]
fn default_scene_in_the_simulator_is_the_host_frame_and_the_golden_torus() {
    let mut torus = Viewer::torus().unwrap();
    let f = both(&mut torus, View::default());
    assert!(f.px == bench_frame(Bench::Torus, 0).px, "not Bench::Torus");
    assert!(f.rgb888_bytes() == golden_torus(), "not the torus golden");
}

#[test]
fn the_torus_orbits_about_both_axes() {
    let mut torus = Viewer::torus().unwrap();
    assert!(torus.pitches());
    // Yaw alone is the benchmark torus's spin.
    for yaw in [37, 90, 211, 359] {
        let f = both(&mut torus, View::new(yaw, 0));
        assert!(f.px == bench_frame(Bench::Torus, yaw).px, "yaw {yaw}");
    }
    // Pitch turns it too: every pitch a different image, each the same on both targets.
    let level = both(&mut torus, View::default()).px;
    let mut seen = vec![level];
    for pitch in [-90, -30, 15, 60, 90] {
        let f = both(&mut torus, View::new(0, pitch)).px;
        assert!(
            !seen.contains(&f),
            "pitch {pitch} draws an image seen before"
        );
        seen.push(f);
    }
}

#[test]
fn views_wrap_and_clamp() {
    assert_eq!(View::new(-5, 0), View { yaw: 355, pitch: 0 });
    assert_eq!(View::new(725, 0).yaw, 5);
    assert_eq!(View::new(0, 120).pitch, 90);
    assert_eq!(View::default().turned(-1, -200), View::new(359, -90));
    assert_eq!(
        View::new(i32::MAX, 0).turned(i32::MAX, 0).yaw,
        i32::MAX.rem_euclid(360)
    );
}

#[test]
fn every_builtin_scene_draws_the_same_in_the_simulator() {
    for name in scene::scene_names() {
        let bench = scene::bench_named(name).unwrap();
        let mut v = Viewer::bench(bench).unwrap();
        assert_eq!(v.pitches(), name == "torus", "{name}");
        for yaw in [0, 45] {
            let f = both(&mut v, View::new(yaw, 0));
            assert!(f.px == bench_frame(bench, yaw).px, "{name} at {yaw}°");
        }
    }
    let e = scene::bench_named("teapot").err().unwrap();
    assert!(e.contains("\"teapot\"") && e.contains("torus, ") && e.contains("shadow_volume"));
}

fn tmp(name: &str) -> PathBuf {
    let p = shared::tmp("simulator", name);
    let _ = std::fs::remove_file(&p);
    p
}

#[test]
fn an_obj_model_is_fitted_and_orbits() {
    // The torus scaled up 1 000 and moved: fitted into the unit sphere before Q16.16, so it
    // draws as the torus of any size would.
    let torus = scanline3d_support::demo::torus::<f64>().unwrap();
    let moved: Vec<[f64; 3]> = torus
        .positions
        .iter()
        .map(|p| [p[0] * 1000.0 + 5000.0, p[1] * 1000.0 - 70.0, p[2] * 1000.0])
        .collect();
    let path = tmp("big_torus.obj");
    std::fs::write(&path, to_obj(&moved, Some(&torus.normals), &torus.indices)).unwrap();
    let mut v = Viewer::obj(&path).unwrap();
    assert!(v.pitches());
    let a = both(&mut v, View::default());
    let b = both(&mut v, View::new(30, -20));
    assert!(a.px != b.px);
    // The model fills the view: its drawn pixels reach near all four edges' margins.
    let drawn: Vec<(u32, u32)> = (0..SIZE)
        .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
        .filter(|&(x, y)| a.get(x, y) != Rgb565::BLACK)
        .collect();
    let (x0, x1) = (
        drawn.iter().map(|p| p.0).min(),
        drawn.iter().map(|p| p.0).max(),
    );
    assert!(x0 < Some(40) && x1 > Some(200), "{x0:?}..{x1:?}");
}

#[test]
fn bad_models_are_messages() {
    let missing = Path::new("/nonexistent/model.obj");
    let e = Viewer::obj(missing).err().unwrap();
    assert!(e.contains("/nonexistent/model.obj"), "{e}");
    let flat = tmp("point.obj");
    std::fs::write(&flat, "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n").unwrap();
    assert!(Viewer::obj(&flat).is_err());
}

#[test]
fn the_label_stays_in_its_rectangle() {
    let mut torus = Viewer::torus().unwrap();
    let mut d = display();
    torus.draw(View::default(), &mut d).unwrap();
    let before = d.clone();
    let Ok(area) = scene::draw_label(&mut d, &scene::frame_time_text(12.345));
    assert_eq!(scene::frame_time_text(12.345), "12.35 ms/frame");
    assert_eq!(area, Rectangle::new(scene::LABEL_AT, Size::new(6 * 14, 10)));
    let mut lit = 0;
    for p in Rectangle::new(Point::zero(), Size::new(SIZE, SIZE)).points() {
        if area.contains(p) {
            lit += usize::from(d.get_pixel(p) == scene::LABEL_COLOR);
        } else {
            assert_eq!(d.get_pixel(p), before.get_pixel(p), "{p:?}");
        }
    }
    assert!(lit > 50, "{lit} label pixels");
}

/// Runs the simulator binary: exit status, stdout, stderr.
fn run(args: &[&str]) -> (i32, String, String) {
    run_env(args, &[])
}

fn run_env(args: &[&str], env: &[(&str, &str)]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_simulator"))
        .args(args)
        .envs(env.iter().copied())
        .output()
        .expect("run the simulator binary");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The label's rectangle at `scale`, with the widest label a frame of under 10 s gives.
fn label_area(scale: u32) -> Rectangle {
    let r = Rectangle::new(scene::LABEL_AT, Size::new(6 * 16, 10));
    Rectangle::new(r.top_left * scale as i32, r.size * scale)
}

#[test]
fn headless_screenshot_is_the_default_frame_with_its_label() {
    let golden = golden_torus();
    for scale in [1u32, 2] {
        let out = tmp(&format!("shot{scale}.png"));
        let s = scale.to_string();
        let (code, stdout, stderr) =
            run(&["--headless", "--out", out.to_str().unwrap(), "--scale", &s]);
        assert_eq!(code, 0, "{stderr}");
        assert!(stdout.contains("torus yaw 0° pitch 0°") && stdout.contains("ms/frame"));
        assert!(!out.with_extension("partial").exists());
        let (w, h, rgb) = read_png(&out).expect("a PNG");
        assert_eq!((w, h), (SIZE * scale, SIZE * scale));
        let label = label_area(scale);
        let mut lit = 0;
        for y in 0..h {
            for x in 0..w {
                let i = 3 * (y * w + x) as usize;
                let got = &rgb[i..i + 3];
                if label.contains(Point::new(x as i32, y as i32)) {
                    let white: Rgb888 = scene::LABEL_COLOR.into();
                    lit += usize::from(got == [white.r(), white.g(), white.b()]);
                    continue;
                }
                let j = 3 * ((y / scale) * SIZE + x / scale) as usize;
                assert_eq!(got, &golden[j..j + 3], "scale {scale}: ({x}, {y})");
            }
        }
        assert!(lit > 50 * (scale * scale) as usize, "no label: {lit}");
    }
}

#[test]
fn headless_other_scenes_and_views() {
    let out = tmp("shadow.png");
    let (code, stdout, stderr) = run(&[
        "--headless",
        "--out",
        out.to_str().unwrap(),
        "--scene",
        "shadow",
        "--yaw",
        "-30",
        "--scale",
        "1",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("shadow yaw 330°"), "{stdout}");
    let (_, _, rgb) = read_png(&out).unwrap();
    let want = bench_frame(Bench::Shadow, 330);
    let label = label_area(1);
    let want_rgb = want.rgb888_bytes();
    for (k, (a, b)) in rgb.chunks(3).zip(want_rgb.chunks(3)).enumerate() {
        let p = Point::new((k as u32 % SIZE) as i32, (k as u32 / SIZE) as i32);
        assert!(label.contains(p) || a == b, "{p:?}");
    }
}

#[test]
fn bad_arguments_exit_non_zero_with_a_message_and_no_file() {
    let out = tmp("never.png");
    let o = out.to_str().unwrap();
    let cases: &[(&[&str], i32, &[&str])] = &[
        (
            &["--headless", "--out", o, "--scene", "teapot"],
            2,
            &["teapot", "cube, torus, icosphere"],
        ),
        (
            &["--headless", "--out", o, "--obj", "/nonexistent/m.obj"],
            2,
            &["/nonexistent/m.obj"],
        ),
        (
            &["--headless", "--out", o, "--scene", "cube", "--pitch", "10"],
            2,
            &["--pitch", "cube"],
        ),
        (&["--headless", "--out", o, "--pitch", "91"], 2, &["91"]),
        (&["--headless", "--out", o, "--scale", "0"], 2, &["--scale"]),
        (&["--headless"], 2, &["--out"]),
        (&["--out", o], 2, &["--headless"]),
        (&["--headless", "--out", "/tmp/x.bmp"], 2, &[".png"]),
        (
            &["--headless", "--out", "/nonexistent/dir/x.png"],
            1,
            &["/nonexistent/dir/x.png"],
        ),
    ];
    for (args, want, parts) in cases {
        let (code, _, stderr) = run(args);
        assert_eq!(code, *want, "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        for p in *parts {
            assert!(stderr.contains(p), "{args:?}: {p:?} not in {stderr}");
        }
        assert!(!out.exists(), "{args:?} wrote a file");
    }
}

/// Without the window feature the window is refused with a message; with it, a machine whose
/// SDL has no video device, or only its offscreen one (an invisible window), gets a message,
/// not the simulator's panic or a window nobody sees.
#[test]
fn no_window_is_a_message() {
    for driver in ["no-such-driver", "offscreen"] {
        let (code, _, stderr) = run_env(&[], &[("SDL_VIDEODRIVER", driver)]);
        assert!(!stderr.contains("panicked"), "{stderr}");
        if cfg!(feature = "simulator") {
            assert_eq!(code, 1, "{driver}: {stderr}");
            assert!(stderr.contains("cannot open a window"), "{stderr}");
            assert!(stderr.contains("--headless --out"), "{stderr}");
        } else {
            assert_eq!(code, 2, "{stderr}");
            assert!(stderr.contains("--features simulator"), "{stderr}");
        }
    }
}
