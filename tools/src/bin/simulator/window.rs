//! The simulator's window (the `simulator` feature: SDL2): the scene drawn every pass of the
//! loop with its frame time, orbited by the arrow keys and a left-button drag.

use std::collections::VecDeque;
use std::time::Instant;

use embedded_graphics::prelude::*;
use embedded_graphics_simulator::sdl2::{Keycode, MouseButton};
use embedded_graphics_simulator::{OutputSettings, SimulatorEvent, Window};

use crate::scene::{self, draw_label, frame_time_text, View, Viewer};

/// Frames the label averages over.
const AVERAGE: usize = 15;
/// Degrees an arrow key turns.
const KEY_STEP: i32 = 5;

/// The window: a frame drawn every pass of the loop (the label is the mean of the last
/// [`AVERAGE`] frame times), the events read after it.
pub(crate) fn run(
    viewer: &mut Viewer,
    mut view: View,
    settings: &OutputSettings,
) -> Result<(), (String, i32)> {
    // The simulator's window unwraps SDL's errors (it panics without a display): ask SDL
    // first, and let go of it before the window initialises it again (one context at a time).
    // Without a display SDL may still start its offscreen driver: an invisible window.
    let driver = sdl2::init()
        .and_then(|sdl| sdl.video().map(|v| v.current_video_driver().to_owned()))
        .map_err(|e| format!("SDL: {e}"))
        .and_then(|driver| match driver.as_str() {
            "offscreen" | "dummy" => {
                Err(format!("SDL found no display (only its {driver} driver)"))
            }
            _ => Ok(()),
        });
    if let Err(e) = driver {
        return Err((
            format!("cannot open a window: {e}; without a display use --headless --out FILE.png"),
            1,
        ));
    }
    let start = view;
    let mut window = Window::new(&format!("scanline3d: {}", viewer.name), settings);
    let mut display = crate::display();
    let mut times: VecDeque<f64> = VecDeque::with_capacity(AVERAGE);
    let mut drag: Option<Point> = None;
    println!(
        "simulator: {}: arrow keys or a left-button drag orbit{}, Home resets, Esc or Q quits",
        viewer.name,
        if viewer.pitches() {
            ""
        } else {
            " (about the vertical axis only)"
        }
    );
    loop {
        let t = Instant::now();
        match viewer.draw(view, &mut display) {
            Ok(_) => {
                if times.len() == AVERAGE {
                    times.pop_front();
                }
                times.push_back(t.elapsed().as_secs_f64() * 1e3);
                let ms = times.iter().sum::<f64>() / times.len() as f64;
                let Ok(_) = draw_label(&mut display, &frame_time_text(ms));
            }
            // Shown in the window; the next view is drawn again.
            Err(msg) => {
                let Ok(()) = scene::draw_message(&mut display, &msg);
            }
        }
        window.update(&display);
        let pitch = i32::from(viewer.pitches());
        for event in window.events() {
            match event {
                SimulatorEvent::Quit => return Ok(()),
                SimulatorEvent::KeyDown { keycode, .. } => match keycode {
                    Keycode::Q => return Ok(()),
                    Keycode::Left => view = view.turned(-KEY_STEP, 0),
                    Keycode::Right => view = view.turned(KEY_STEP, 0),
                    Keycode::Up => view = view.turned(0, -KEY_STEP * pitch),
                    Keycode::Down => view = view.turned(0, KEY_STEP * pitch),
                    Keycode::Home => view = start,
                    _ => {}
                },
                SimulatorEvent::MouseButtonDown {
                    mouse_btn: MouseButton::Left,
                    point,
                } => drag = Some(point),
                SimulatorEvent::MouseButtonUp {
                    mouse_btn: MouseButton::Left,
                    ..
                } => drag = None,
                // One degree per display pixel dragged.
                SimulatorEvent::MouseMove { point } => {
                    if let Some(from) = drag {
                        view = view.turned(point.x - from.x, (point.y - from.y) * pitch);
                        drag = Some(point);
                    }
                }
                _ => {}
            }
        }
    }
}
