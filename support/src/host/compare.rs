//! The fixed-point-against-float comparison, shared by `tools/src/bin/compare.rs` and
//! `tests/accuracy.rs`: every benchmark scene, every number type, against the f64 twin twice —
//! (a) on the tested type's own snapped screen geometry (arithmetic error only) and (b) with f64's
//! own geometry (the whole error a user sees).
#![allow(dead_code)]

use std::time::{Duration, Instant};

use crate::demo::{render_bench, Bench};
use crate::metrics::Metrics;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::{Probe, Scalar, Stage, TargetColor, TriangleId};

use super::Frame;

/// Records every snapped vertex position of a frame by its index in the vertex store
/// (vertices that are clipped instead of projected have none).
#[derive(Default)]
pub struct Record(pub Vec<Option<(i32, i32)>>);

impl Probe for Record {
    fn enter(&mut self, _: Stage) {}
    fn snap(&mut self, index: u32, x: i32, y: i32) -> (i32, i32) {
        let i = index as usize;
        if self.0.len() <= i {
            self.0.resize(i + 1, None);
        }
        self.0[i] = Some((x, y));
        (x, y)
    }
}

/// Replays recorded snapped positions onto another number type's frame. A vertex whose own
/// position is further from the recorded one than 4 px plus 1/1024 of its distance from the
/// origin (the two pipelines' vertex stores diverged, e.g. by a different clipping decision,
/// rather than rounded differently) keeps its own and is counted.
pub struct Replay<'a> {
    pub snaps: &'a [Option<(i32, i32)>],
    pub diverged: u32,
}

impl Probe for Replay<'_> {
    fn enter(&mut self, _: Stage) {}
    fn snap(&mut self, index: u32, x: i32, y: i32) -> (i32, i32) {
        match self.snaps.get(index as usize) {
            Some(&Some((sx, sy)))
                if {
                    let tol = 64 + sx.abs().max(sy.abs()) / 1024;
                    (sx - x).abs() <= tol && (sy - y).abs() <= tol
                } =>
            {
                (sx, sy)
            }
            _ => {
                self.diverged += 1;
                (x, y)
            }
        }
    }
}

/// Times exactly the `render` call.
#[derive(Default)]
pub struct Timer {
    start: Option<Instant>,
    pub total: Duration,
}

impl Probe for Timer {
    fn enter(&mut self, _: Stage) {}
    fn frame_start(&mut self) {
        self.start = Some(Instant::now());
    }
    fn frame_end(&mut self) {
        if let Some(s) = self.start.take() {
            self.total += s.elapsed();
        }
    }
}

pub fn frame<S: Scalar, C: TargetColor, P: Probe>(b: Bench, probe: &mut P) -> Frame<C> {
    let mut f = Frame::new(240, 240, C::from_channels([0; 3]));
    render_bench::<S, C, _, _>(b, 0.0, false, &mut f, probe)
        .unwrap_or_else(|e| panic!("{} {}: {e:?}", b.name(), S::NAME));
    f
}

/// One row of the comparison.
#[derive(Clone, Debug)]
pub struct Row {
    pub scene: &'static str,
    pub number: &'static str,
    pub reference: &'static str,
    pub metrics: Metrics,
    pub host_ns_per_frame: f64,
    /// Vertices whose recorded snap could not be replayed (reference (a) only).
    pub diverged: u32,
}

fn metrics(
    a: &Frame<Rgb565>,
    b: &Frame<Rgb565>,
    ia: &Frame<TriangleId>,
    ib: &Frame<TriangleId>,
) -> Metrics {
    let mut m = Metrics::new([Rgb565::MAX_R, Rgb565::MAX_G, Rgb565::MAX_B]);
    let w = a.w as usize;
    for y in 0..a.h as usize {
        let r = y * w..(y + 1) * w;
        m.add_line_ids(
            &a.px[r.clone()],
            &b.px[r.clone()],
            &ia.px[r.clone()],
            &ib.px[r],
        );
    }
    m
}

/// Median host time of `runs` frames of `b` with number type `S`, in ns.
pub fn time_frame<S: Scalar>(b: Bench, runs: usize) -> f64 {
    let mut times: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let mut t = Timer::default();
            let mut f = Frame::new(240, 240, Rgb565::BLACK);
            render_bench::<S, Rgb565, _, _>(b, 0.0, false, &mut f, &mut t).expect("render");
            t.total.as_nanos() as f64
        })
        .collect();
    times.sort_by(|x, y| x.total_cmp(y));
    times[times.len() / 2]
}

/// Both comparisons of number type `S` on scene `b`; `runs` timed frames (0: no timing).
pub fn compare<S: Scalar>(b: Bench, runs: usize) -> [Row; 2] {
    let mut rec = Record::default();
    let img = frame::<S, Rgb565, _>(b, &mut rec);
    let ids = frame::<S, TriangleId, _>(b, &mut Record::default());
    // (a): f64 on S's snapped geometry.
    let mut rp = Replay {
        snaps: &rec.0,
        diverged: 0,
    };
    let ref_a = frame::<f64, Rgb565, _>(b, &mut rp);
    let mut rp_ids = Replay {
        snaps: &rec.0,
        diverged: 0,
    };
    let ref_a_ids = frame::<f64, TriangleId, _>(b, &mut rp_ids);
    // (b): f64 with its own geometry.
    let ref_b = frame::<f64, Rgb565, _>(b, &mut scanline3d::NoProbe);
    let ref_b_ids = frame::<f64, TriangleId, _>(b, &mut scanline3d::NoProbe);
    let ns = if runs > 0 {
        time_frame::<S>(b, runs)
    } else {
        0.0
    };
    [
        Row {
            scene: b.name(),
            number: S::NAME,
            reference: "f64-same-geometry",
            metrics: metrics(&img, &ref_a, &ids, &ref_a_ids),
            host_ns_per_frame: ns,
            diverged: rp.diverged.max(rp_ids.diverged),
        },
        Row {
            scene: b.name(),
            number: S::NAME,
            reference: "f64",
            metrics: metrics(&img, &ref_b, &ids, &ref_b_ids),
            host_ns_per_frame: ns,
            diverged: 0,
        },
    ]
}

/// The error of scene `b` in number type `S` against scene `reference` in f64 (both with their
/// own geometry): for a span mode against the exact one, the whole error a user sees.
pub fn compare_with<S: Scalar>(b: Bench, reference: Bench) -> Metrics {
    let img = frame::<S, Rgb565, _>(b, &mut scanline3d::NoProbe);
    let ids = frame::<S, TriangleId, _>(b, &mut scanline3d::NoProbe);
    let r = frame::<f64, Rgb565, _>(reference, &mut scanline3d::NoProbe);
    let r_ids = frame::<f64, TriangleId, _>(reference, &mut scanline3d::NoProbe);
    metrics(&img, &r, &ids, &r_ids)
}
