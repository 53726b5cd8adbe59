//! Strips into buffers the caller owns (`Frame::strip_into`, `Frame::strip_be`) and
//! the board firmware's frames (`demo::board`): the same pixels as `Renderer::render`.
// Pixel coordinates index the frame and the lines in lockstep.
#![allow(clippy::needless_range_loop)]

use crate::common;

use common::Frame;
use embedded_graphics::mono_font::ascii::FONT_6X10;
use embedded_graphics::mono_font::MonoTextStyle;
use embedded_graphics::pixelcolor::raw::ToBytes;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use scanline3d::errors::StripBufferTooSmall;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d_support::demo::{self, board};

type Q = Fx<I16F16>;

fn torus_scene_render(frame: u32, dither: bool) -> Frame<Rgb565> {
    let shape = demo::torus::<Q>().unwrap();
    let objects = [Object {
        mesh: shape.mesh(),
        transform: demo::torus_transform(board::spin(frame)),
        material: demo::torus_material(),
    }];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut r = Box::new(demo::TorusRenderer::<Q, Rgb565>::new().with_dither(dither));
    let mut f = Frame::new(240, 240, Rgb565::CSS_HOT_PINK);
    r.render(&scene, &mut f).unwrap();
    f
}

/// The caller's strip buffers, of any height, give exactly `render`'s pixels; lines and columns
/// outside the strip keep what they held.
#[test]
fn strips_into_caller_lines_equal_render() {
    for (frame, dither) in [(0, false), (7, true), (50, true)] {
        let want = torus_scene_render(frame, dither);
        let shape = scanline3d_support::demo::torus::<Q>().unwrap();
        let scene = board::BoardScene::new(&shape).unwrap();
        let mut r = Box::new(board::renderer::<Q>());
        r.set_dither(dither);
        let mut prepared = scene.prepare(&mut r, frame).unwrap();
        // 3 lines of caller buffer against 8 depth lines: strips of 3 rows.
        let mut lines = [[Rgb565::CSS_HOT_PINK; 240]; 3];
        let mut next = 0;
        while let Some(rows) = prepared.strip_into(&mut lines) {
            assert_eq!(rows.start, next);
            assert!(rows.len() <= 3);
            for (i, y) in rows.clone().enumerate() {
                for x in 0..240 {
                    assert_eq!(
                        lines[i][x],
                        want.get(x as u32, y as u32),
                        "frame {frame} at {x},{y}"
                    );
                }
            }
            next = rows.end;
        }
        assert_eq!(next, 240);
        // A viewport narrower than the buffer leaves the columns beyond it alone.
        r.set_viewport(100, 50);
        let mut prepared = scene.prepare(&mut r, frame).unwrap();
        let mut wide = [[Rgb565::CSS_HOT_PINK; 240]; 8];
        let rows = prepared.strip_into(&mut wide).unwrap();
        assert_eq!(rows, 0..8);
        assert!(wide
            .iter()
            .all(|l| l[100..].iter().all(|&c| c == Rgb565::CSS_HOT_PINK)));
    }
}

/// Big-endian bytes: the same pixels, as many rows as fit, a clear error for a buffer that
/// cannot hold one row, and `None` once the frame is done.
#[test]
fn strips_as_big_endian_bytes_equal_render() {
    let want = torus_scene_render(3, true);
    let shape = scanline3d_support::demo::torus::<Q>().unwrap();
    let scene = board::BoardScene::new(&shape).unwrap();
    let mut r = Box::new(board::renderer::<Q>());
    assert!(r.prepared().is_none(), "nothing prepared");
    let mut prepared = scene.prepare(&mut r, 3).unwrap();
    assert_eq!(
        prepared.strip_be(&mut [0u8; 479]),
        Err(StripBufferTooSmall {
            needed: 480,
            given: 479
        })
    );
    // 2.5 rows of bytes: strips of 2 rows.
    let mut out = vec![0u8; 1200];
    let mut next = 0;
    while let Some(rows) = prepared.strip_be(&mut out).unwrap() {
        assert_eq!(rows.start, next);
        assert_eq!(rows.len(), 2);
        for (i, y) in rows.clone().enumerate() {
            for x in 0..240 {
                let c = want.get(x as u32, y as u32).to_be_bytes();
                let at = (i * 240 + x) * 2;
                assert_eq!(&out[at..at + 2], &c[..], "at {x},{y}");
            }
        }
        next = rows.end;
    }
    assert_eq!(next, 240);
    assert_eq!(prepared.strip_be(&mut out), Ok(None), "the frame is done");
}

/// The board firmware's frame: the render plus the label as embedded-graphics draws it.
#[test]
fn board_frame_is_render_plus_label() {
    let mut want = torus_scene_render(9, true);
    let label = board::fps_label(27_777);
    assert_eq!(label.as_str(), "36.0 fps");
    Text::with_baseline(
        &label,
        Point::new(board::LABEL_AT.0, board::LABEL_AT.1),
        MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE),
        Baseline::Top,
    )
    .draw(&mut want)
    .unwrap();
    let shape = scanline3d_support::demo::torus::<Q>().unwrap();
    let scene = board::BoardScene::new(&shape).unwrap();
    let glyphs = board::glyphs().unwrap();
    let mut r = Box::new(board::renderer::<Q>());
    let mut prepared = scene.prepare(&mut r, 9).unwrap();
    let mut buffer = [[Rgb565::BLACK; 240]; board::STRIP_LINES];
    let mut next = 0;
    while let Some(rows) = board::draw_strip(&mut prepared, &glyphs, &label, &mut buffer) {
        for (i, y) in rows.clone().enumerate() {
            for x in 0..240 {
                assert_eq!(buffer[i][x], want.get(x as u32, y as u32), "at {x},{y}");
            }
        }
        next = rows.end;
    }
    assert_eq!(next, 240);
}

/// A frame split at every row, the halves drawn after `seek_row` (the bottom first), is the
/// whole frame bit for bit; seeking back redraws rows from the same geometry.
#[test]
fn seek_row_splits_a_frame_exactly_at_every_row() {
    for (frame, dither) in [(0, false), (11, true), (40, false), (77, true)] {
        let want = torus_scene_render(frame, dither);
        let shape = scanline3d_support::demo::torus::<Q>().unwrap();
        let scene = board::BoardScene::new(&shape).unwrap();
        let mut r = Box::new(board::renderer::<Q>());
        r.set_dither(dither);
        for split in (0usize..=240).chain([500]) {
            let mut prepared = scene.prepare(&mut r, frame).unwrap();
            let mut got = vec![[Rgb565::CSS_HOT_PINK; 240]; 240];
            let mut line = [[Rgb565::CSS_HOT_PINK; 240]; 1];
            // Bottom part first, then the top: the order does not matter.
            prepared.seek_row(split);
            while let Some(rows) = prepared.strip_into(&mut line) {
                got[rows.start] = line[0];
            }
            prepared.seek_row(0);
            while let Some(rows) = prepared.strip_into(&mut line) {
                if rows.start >= split {
                    break;
                }
                got[rows.start] = line[0];
            }
            for (y, l) in got.iter().enumerate() {
                for (x, &c) in l.iter().enumerate() {
                    let w = want.get(x as u32, y as u32);
                    assert_eq!(c, w, "frame {frame} split {split} at {x},{y}");
                }
            }
        }
    }
}
