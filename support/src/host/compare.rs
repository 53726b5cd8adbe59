//! The fixed-point-against-float comparison, shared by `tools/src/bin/compare.rs` and
//! `tests/accuracy.rs`: every benchmark scene, every number type, against the f64 twin twice —
//! (a) on the tested type's own snapped screen geometry (arithmetic error only) and (b) with f64's
//! own geometry (the whole error a user sees).
#![allow(dead_code)]

use std::time::{Duration, Instant};

use crate::demo::{render_bench, Bench};
use crate::metrics::Metrics;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::{color::TriangleId, probe::Probe, probe::Stage, Scalar, TargetColor};

use super::Frame;

/// The host's one probe: records snapped vertex positions, replays them onto another number
/// type's frame, times the render call, or does nothing. One type rather than one per job, so
/// that each benchmark scene's renderer is compiled once per number type and colour for all
/// four jobs (`compare` and the integration tests instantiate every scene in six number types:
/// with four probe types the comparison held about 340 copies of the renderer's frame driver).
/// Its checks cost a branch per stage change and per snapped vertex, nothing per pixel.
pub enum HostProbe<'a> {
    /// Nothing recorded, nothing changed.
    Plain,
    /// Records every snapped vertex position by its index in the vertex store (vertices that
    /// are clipped instead of projected have none).
    Record(Vec<Option<(i32, i32)>>),
    /// Replays recorded snapped positions onto another number type's frame. A vertex whose
    /// own position is further from the recorded one than 4 px plus 1/1024 of its distance
    /// from the origin (the two pipelines' vertex stores diverged, e.g. by a different clipping
    /// decision, rather than rounded differently) keeps its own and is counted in `diverged`.
    Replay {
        snaps: &'a [Option<(i32, i32)>],
        diverged: u32,
    },
    /// Times exactly the render call (from the frame's start to its end), summed over frames.
    Timer {
        start: Option<Instant>,
        total: Duration,
    },
}

impl<'a> HostProbe<'a> {
    /// A probe that records snapped positions.
    #[must_use]
    pub fn record() -> Self {
        HostProbe::Record(Vec::new())
    }

    /// A probe that replays `snaps` (a [`HostProbe::recorded`]).
    #[must_use]
    pub fn replay(snaps: &'a [Option<(i32, i32)>]) -> Self {
        HostProbe::Replay { snaps, diverged: 0 }
    }

    /// A probe that times frames.
    #[must_use]
    pub fn timer() -> Self {
        HostProbe::Timer {
            start: None,
            total: Duration::ZERO,
        }
    }

    /// The recorded positions (empty unless recording).
    #[must_use]
    pub fn recorded(&self) -> &[Option<(i32, i32)>] {
        match self {
            HostProbe::Record(v) => v,
            _ => &[],
        }
    }

    /// Vertices whose recorded position could not be replayed (0 unless replaying).
    #[must_use]
    pub fn diverged(&self) -> u32 {
        match self {
            HostProbe::Replay { diverged, .. } => *diverged,
            _ => 0,
        }
    }

    /// The time the timed frames took (zero unless timing).
    #[must_use]
    pub fn total(&self) -> Duration {
        match self {
            HostProbe::Timer { total, .. } => *total,
            _ => Duration::ZERO,
        }
    }
}

impl Probe for HostProbe<'_> {
    fn enter(&mut self, _: Stage) {}
    fn frame_start(&mut self) {
        if let HostProbe::Timer { start, .. } = self {
            *start = Some(Instant::now());
        }
    }
    fn frame_end(&mut self) {
        if let HostProbe::Timer { start, total } = self {
            if let Some(s) = start.take() {
                *total += s.elapsed();
            }
        }
    }
    fn snap(&mut self, index: u32, x: i32, y: i32) -> (i32, i32) {
        match self {
            HostProbe::Plain | HostProbe::Timer { .. } => (x, y),
            HostProbe::Record(v) => {
                let i = index as usize;
                if v.len() <= i {
                    v.resize(i + 1, None);
                }
                v[i] = Some((x, y));
                (x, y)
            }
            HostProbe::Replay { snaps, diverged } => match snaps.get(index as usize) {
                Some(&Some((sx, sy)))
                    if {
                        let tol = 64 + sx.abs().max(sy.abs()) / 1024;
                        (sx - x).abs() <= tol && (sy - y).abs() <= tol
                    } =>
                {
                    (sx, sy)
                }
                _ => {
                    *diverged += 1;
                    (x, y)
                }
            },
        }
    }
}

/// Benchmark scene `b`'s frame (spin 0, no dithering) in number type `S` and colour `C`.
pub fn frame<S: Scalar, C: TargetColor>(b: Bench, probe: &mut HostProbe<'_>) -> Frame<C> {
    let mut f = Frame::new(240, 240, C::from_channels([0; 3]));
    render_bench::<S, C, _, _>(b, 0.0, false, &mut f, probe)
        .unwrap_or_else(|e| panic!("{} {}: {e:?}", b.name(), S::NAME));
    f
}

/// Benchmark scene `b`'s frame ([`frame`], RGB565) checked against its golden image
/// `<scene>_<ty>.png`, every pixel of the frame written exactly once.
pub fn check_bench_golden<S: Scalar>(b: Bench, ty: &str) {
    let f = frame::<S, Rgb565>(b, &mut HostProbe::Plain);
    f.assert_each_written_once();
    super::check_golden(&format!("{}_{ty}", b.name()), &f);
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
            let mut t = HostProbe::timer();
            let mut f = Frame::new(240, 240, Rgb565::BLACK);
            render_bench::<S, Rgb565, _, _>(b, 0.0, false, &mut f, &mut t).expect("render");
            t.total().as_nanos() as f64
        })
        .collect();
    times.sort_by(|x, y| x.total_cmp(y));
    times[times.len() / 2]
}

/// Both comparisons of number type `S` on scene `b`; `runs` timed frames (0: no timing).
pub fn compare<S: Scalar>(b: Bench, runs: usize) -> [Row; 2] {
    let mut rec = HostProbe::record();
    let img = frame::<S, Rgb565>(b, &mut rec);
    let ids = frame::<S, TriangleId>(b, &mut HostProbe::Plain);
    // (a): f64 on S's snapped geometry.
    let mut rp = HostProbe::replay(rec.recorded());
    let ref_a = frame::<f64, Rgb565>(b, &mut rp);
    let mut rp_ids = HostProbe::replay(rec.recorded());
    let ref_a_ids = frame::<f64, TriangleId>(b, &mut rp_ids);
    // (b): f64 with its own geometry.
    let ref_b = frame::<f64, Rgb565>(b, &mut HostProbe::Plain);
    let ref_b_ids = frame::<f64, TriangleId>(b, &mut HostProbe::Plain);
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
            diverged: rp.diverged().max(rp_ids.diverged()),
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
    let img = frame::<S, Rgb565>(b, &mut HostProbe::Plain);
    let ids = frame::<S, TriangleId>(b, &mut HostProbe::Plain);
    let r = frame::<f64, Rgb565>(reference, &mut HostProbe::Plain);
    let r_ids = frame::<f64, TriangleId>(reference, &mut HostProbe::Plain);
    metrics(&img, &r, &ids, &r_ids)
}
