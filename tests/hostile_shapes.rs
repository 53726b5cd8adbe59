//! Hostile inputs to the shape constructors (issue #21): huge segment and cell counts, NaN,
//! infinite, zero and negative lengths, shapes too large or too small for the number type, and
//! the error they must give instead. Every case runs with `Fx<I16F16>`, `f32` and `f64`, in a
//! thread with a time limit, so a hang is a failure and not a stalled test run.
//!
//! What main did before (ab51637), measured in debug and release:
//! - `torus(1, 0.4, usize::MAX, 2 or 3)`, `torus(.., 2³², 2³²)` and `terrain(4, usize::MAX
//!   or 2³², 0)` panicked ("attempt to multiply/add with overflow") in debug. In release
//!   `torus(.., 2³², 2³²)` and `terrain(4, usize::MAX, 0)` hung (the count wrapped to a value
//!   that passed the capacity check and the loops ran 2⁶⁴ or more times); the others returned
//!   `ShapeError` with wrapped counts (e.g. 18446744073709551614 vertices for `usize::MAX · 2`).
//! - `cube(-1 | 0 | NaN | inf)`, `torus(NaN, ..)`, `torus(1, -0.4 | 1.5, ..)`,
//!   `icosphere(NaN | -1, ..)`, `terrain(NaN | -4, ..)` and `terrain(.., inf)` returned `Ok`
//!   with NaN, infinite, collapsed, inside-out or self-intersecting geometry.
//! - `Fx<I16F16>` `torus(30000, 5000)` returned `Ok` with every vertex saturated at the rail
//!   (which the renderer then skips as invalid), `cube(1e-6)` `Ok` with every vertex at 0;
//!   `f32` `cube(1e39)` `Ok` with infinite vertices.
//! - `torus(1, 0.4, 2, 2)` gave `ShapeError { vertices: 4, triangles: 8 }` (reads as a
//!   capacity error), `icosphere(1, 99)` the counts of 8 subdivisions, `terrain(4, 0, 0)`
//!   `{ vertices: 1, triangles: 0 }`; `ShapeError` had no `Display` and no `Error` impl.

use std::sync::mpsc;
use std::time::Duration;

use scanline3d::fixed::types::{I12F20, I16F16};
use scanline3d::mesh::ParamValue;
use scanline3d::{errors::ShapeError, Fx, Scalar, Shape};

type Q = Fx<I16F16>;

/// The capacities of the shapes under test: small, so a constructor that loops past its checks
/// only wastes time, which the limit below turns into a failure.
type Small<S> = Shape<S, 64, 128>;

/// Runs `f` in its own thread and returns its result, failing if it panics or takes longer than
/// the time limit (a hung thread is left behind; the test process ends with the run).
fn within_limit<R: Send + 'static>(what: &str, f: impl FnOnce() -> R + Send + 'static) -> R {
    let (tx, rx) = mpsc::channel();
    std::thread::Builder::new()
        .name(what.into())
        .spawn(move || {
            let _ = tx.send(f());
        })
        .expect("spawn");
    match rx.recv_timeout(Duration::from_secs(10)) {
        Ok(r) => r,
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("{what}: still running after 10 s"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("{what}: panicked"),
    }
}

/// The constructor's result without the shape (which need not be `Debug`-printed).
fn outcome<S: Scalar, const V: usize, const T: usize>(
    r: Result<Shape<S, V, T>, ShapeError>,
) -> Result<(usize, usize), ShapeError> {
    r.map(|s| (s.positions.len(), s.indices.len()))
}

/// A count computed exactly in `u128`, as `ShapeError::Capacity` reports it.
fn count(n: u128) -> Option<usize> {
    usize::try_from(n).ok()
}

fn capacity(vertices: u128, triangles: u128) -> ShapeError {
    ShapeError::Capacity {
        vertices: count(vertices),
        triangles: count(triangles),
        vertex_capacity: 64,
        triangle_capacity: 128,
    }
}

fn bad_count(name: &'static str, n: u64) -> ShapeError {
    let expected = match name {
        "subdivisions" => "0..=4",
        "cells" => ">= 1",
        _ => ">= 3",
    };
    ShapeError::BadParameter {
        name,
        value: ParamValue::Count(n),
        expected,
    }
}

/// Asserts `e` is `BadParameter` naming `name` with the value `v` (bit for bit, so NaN counts).
fn assert_bad_real(e: Result<(usize, usize), ShapeError>, name: &str, v: f64, case: &str) {
    match e {
        Err(ShapeError::BadParameter {
            name: n,
            value: ParamValue::Real(got),
            ..
        }) if n == name && got.to_bits() == v.to_bits() => {}
        other => panic!("{case}: expected BadParameter {name} = {v}, got {other:?}"),
    }
}

/// `1 << (usize::BITS / 2)`: 2³² on a 64-bit host, 65 536 on a 32-bit microcontroller. Its
/// square is exactly 2^usize::BITS, which wraps to 0.
const HALF: usize = 1 << (usize::BITS / 2);

fn huge_torus_counts<S: Scalar + Send>() {
    let name = S::NAME;
    // (nu, nv, what main did in release). usize::MAX·2 and ·3 wrapped; HALF² wrapped to 0 and
    // hung; 2·HALF · (HALF/2 + 1) wrapped to 2·HALF; HALF · 2 wrapped nowhere but nv = 2 < 3.
    let cases = [
        (usize::MAX, 3),
        (3, usize::MAX),
        (HALF, HALF),
        (2 * HALF, HALF / 2 + 1),
        (usize::MAX, usize::MAX),
        (65_536, 65_536),
        (257, 256),
    ];
    for (nu, nv) in cases {
        let case = format!("{name} torus(1, 0.4, {nu}, {nv})");
        let got = within_limit(&case, move || outcome(Small::<S>::torus(1.0, 0.4, nu, nv)));
        let n = nu as u128 * nv as u128;
        assert_eq!(got, Err(capacity(n, n.saturating_mul(2))), "{case}");
    }
    // A parameter below 3 is named, whatever the other count (main: overflow panic in debug, a
    // wrapped count in release).
    for (nu, nv, bad, value) in [
        (usize::MAX, 2, "nv", 2),
        (2, usize::MAX, "nu", 2),
        (0, HALF, "nu", 0),
        (2, 2, "nu", 2),
    ] {
        let case = format!("{name} torus(1, 0.4, {nu}, {nv})");
        let got = within_limit(&case, move || outcome(Small::<S>::torus(1.0, 0.4, nu, nv)));
        assert_eq!(got, Err(bad_count(bad, value)), "{case}");
    }
}

#[test]
fn huge_torus_segment_counts_are_refused_without_overflow_or_hang() {
    huge_torus_counts::<Q>();
    huge_torus_counts::<f32>();
    huge_torus_counts::<f64>();
}

fn huge_terrain_counts<S: Scalar + Send>() {
    let name = S::NAME;
    for cells in [
        usize::MAX,
        usize::MAX - 1,
        HALF,
        HALF - 1,
        HALF + 1,
        255,
        256,
    ] {
        let case = format!("{name} terrain(4, {cells}, 0)");
        let got = within_limit(&case, move || outcome(Small::<S>::terrain(4.0, cells, 0.0)));
        let c = cells as u128;
        assert_eq!(
            got,
            Err(capacity(
                (c + 1).saturating_mul(c + 1),
                (c * c).saturating_mul(2)
            )),
            "{case}"
        );
    }
    let got = within_limit("terrain(4, 0, 0)", || {
        outcome(Small::<S>::terrain(4.0, 0, 0.0))
    });
    assert_eq!(got, Err(bad_count("cells", 0)), "{name} terrain(4, 0, 0)");
}

#[test]
fn huge_terrain_cell_counts_are_refused_without_overflow_or_hang() {
    huge_terrain_counts::<Q>();
    huge_terrain_counts::<f32>();
    huge_terrain_counts::<f64>();
}

/// Counts past 65 536 vertices are refused even when `V` is larger: `u16` indices cannot
/// address them, and the error says the capacity is 65 536.
#[test]
fn vertex_counts_beyond_u16_indices_are_refused() {
    let got = std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| {
            // 65 538 vertices and 131 076 triangles: both fit V and T, not u16 indices.
            let torus = outcome(Shape::<f32, 70_000, 140_000>::torus(1.0, 0.4, 3, 21_846));
            // 257² = 66 049 vertices.
            let terrain = outcome(Shape::<f32, 70_000, 140_000>::terrain(4.0, 256, 0.0));
            (torus, terrain)
        })
        .expect("spawn")
        .join()
        .expect("no panic");
    let cap = |v, t| ShapeError::Capacity {
        vertices: Some(v),
        triangles: Some(t),
        vertex_capacity: 65_536,
        triangle_capacity: 140_000,
    };
    assert_eq!(got.0, Err(cap(65_538, 131_076)));
    assert_eq!(got.1, Err(cap(66_049, 131_072)));
}

fn bad_lengths<S: Scalar + Send>() {
    let name = S::NAME;
    let bad = [
        -1.0,
        0.0,
        -0.0,
        f64::NAN,
        -f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        -f64::MIN_POSITIVE,
    ];
    for v in bad {
        let got = within_limit("cube", move || outcome(Shape::<S, 24, 12>::cube(v)));
        assert_bad_real(got, "h", v, &format!("{name} cube({v})"));

        let got = within_limit("torus R", move || outcome(Small::<S>::torus(v, 0.4, 4, 4)));
        assert_bad_real(got, "big_r", v, &format!("{name} torus({v}, 0.4)"));
        let got = within_limit("torus r", move || outcome(Small::<S>::torus(1.0, v, 4, 4)));
        assert_bad_real(got, "r", v, &format!("{name} torus(1, {v})"));

        let got = within_limit("icosphere", move || outcome(Small::<S>::icosphere(v, 1)));
        assert_bad_real(got, "radius", v, &format!("{name} icosphere({v}, 1)"));

        let got = within_limit("terrain", move || outcome(Small::<S>::terrain(v, 2, 0.0)));
        assert_bad_real(got, "size", v, &format!("{name} terrain({v}, 2, 0)"));
    }
    // The amplitude may be any finite value, of either sign, but not NaN or infinite.
    for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let got = within_limit("terrain amplitude", move || {
            outcome(Small::<S>::terrain(4.0, 2, v))
        });
        assert_bad_real(got, "amplitude", v, &format!("{name} terrain(4, 2, {v})"));
    }
    for v in [-0.5, 0.0, 0.5] {
        let t = Small::<S>::terrain(4.0, 2, v).unwrap();
        assert!(t.positions.iter().flatten().all(|c| c.is_valid()));
    }
    // A minor radius above the major one makes a spindle torus whose inner triangles face
    // inward: refused, naming r. Equal radii (a horn torus) are accepted.
    let got = within_limit("torus r > R", || outcome(Small::<S>::torus(1.0, 1.5, 4, 4)));
    assert_bad_real(got, "r", 1.5, &format!("{name} torus(1, 1.5)"));
    assert_eq!(outcome(Small::<S>::torus(1.0, 1.0, 4, 4)), Ok((16, 32)));
    // The check runs before the count checks: the parameter is named even if nothing fits.
    let got = within_limit("torus NaN huge", || {
        outcome(Small::<S>::torus(f64::NAN, 0.4, HALF, HALF))
    });
    assert_bad_real(
        got,
        "big_r",
        f64::NAN,
        &format!("{name} torus(NaN, 0.4, HALF, HALF)"),
    );
}

#[test]
fn nan_infinite_zero_and_negative_lengths_are_bad_parameters() {
    bad_lengths::<Q>();
    bad_lengths::<f32>();
    bad_lengths::<f64>();
}

fn subdivisions<S: Scalar + Send>() {
    for n in [5, 8, 99, u32::MAX] {
        let got = within_limit("icosphere", move || outcome(Small::<S>::icosphere(1.0, n)));
        assert_eq!(
            got,
            Err(bad_count("subdivisions", n.into())),
            "{} icosphere(1, {n})",
            S::NAME
        );
    }
    // Four subdivisions are valid: too little room is a capacity error with the right counts.
    assert_eq!(
        outcome(Small::<S>::icosphere(1.0, 4)),
        Err(capacity(2562, 5120))
    );
    assert_eq!(outcome(Small::<S>::icosphere(1.0, 1)), Ok((42, 80)));
}

#[test]
fn too_many_subdivisions_is_a_bad_parameter_not_a_capacity() {
    subdivisions::<Q>();
    subdivisions::<f32>();
    subdivisions::<f64>();
}

#[test]
fn shapes_outside_the_number_range_are_refused() {
    let too_large = |extent: f64, ty: &'static str| ShapeError::OutOfRange {
        extent,
        number_type: ty,
        rounds_to_zero: false,
    };
    // Q16.16 holds ±32768 and treats the rails as invalid: a torus reaching 35 000 would have
    // saturated vertices (main: Ok, every outer vertex at 32767.99998).
    assert_eq!(
        outcome(Small::<Q>::torus(30_000.0, 5_000.0, 4, 4)),
        Err(too_large(35_000.0, "I16F16"))
    );
    assert_eq!(
        outcome(Shape::<Q, 24, 12>::cube(32_767.999_99)),
        Err(too_large(32_767.999_99, "I16F16"))
    );
    assert_eq!(
        outcome(Small::<Fx<I12F20>>::torus(2_000.0, 100.0, 4, 4)),
        Err(too_large(2_100.0, "I12F20"))
    );
    // The terrain's normals are computed in S from differences between vertices, up to
    // max(size, 2·|amplitude|), which must not saturate either.
    assert_eq!(
        outcome(Small::<Q>::terrain(4.0, 2, -20_000.0)),
        Err(too_large(40_000.0, "I16F16"))
    );
    assert_eq!(
        outcome(Small::<Q>::terrain(40_000.0, 2, 0.0)),
        Err(too_large(40_000.0, "I16F16"))
    );
    let t = Small::<Q>::terrain(30_000.0, 4, 1_000.0).unwrap();
    assert!(t
        .positions
        .iter()
        .chain(&t.normals)
        .flatten()
        .all(|v| v.is_valid()));
    assert!(
        t.normals.iter().all(|n| n[1].to_f64() > 0.9),
        "{:?}",
        t.normals
    );
    // f64 holds any finite size whose hills' phase 2π·x/size stays finite (found by the fuzz
    // target: main gave NaN heights for size f64::MAX).
    let got = outcome(Small::<f64>::terrain(f64::MAX, 5, 0.0));
    assert_bad_real(got, "size", f64::MAX, "f64 terrain(f64::MAX, 5, 0)");
    let t = Small::<f64>::terrain(1e300, 5, -3.6e284).unwrap();
    assert!(t
        .positions
        .iter()
        .chain(&t.normals)
        .flatten()
        .all(|v| v.is_finite()));
    // The floats hold them.
    assert_eq!(
        outcome(Small::<f32>::torus(30_000.0, 5_000.0, 4, 4)),
        Ok((16, 32))
    );
    assert_eq!(
        outcome(Small::<f64>::torus(30_000.0, 5_000.0, 4, 4)),
        Ok((16, 32))
    );
    // f32 overflows at 3.4e38 (main: Ok with infinite vertices); f64's R + r overflows too.
    assert_eq!(
        outcome(Shape::<f32, 24, 12>::cube(1e39)),
        Err(too_large(1e39, "f32"))
    );
    assert_eq!(outcome(Shape::<f64, 24, 12>::cube(1e39)), Ok((24, 12)));
    assert_eq!(
        outcome(Small::<f64>::torus(f64::MAX, f64::MAX, 4, 4)),
        Err(too_large(f64::INFINITY, "f64"))
    );
    // A shape that rounds to 0 would be a single point (main: Ok, every vertex at 0).
    assert_eq!(
        outcome(Shape::<Q, 24, 12>::cube(1e-6)),
        Err(ShapeError::OutOfRange {
            extent: 1e-6,
            number_type: "I16F16",
            rounds_to_zero: true
        })
    );
    assert_eq!(outcome(Shape::<f32, 24, 12>::cube(1e-6)), Ok((24, 12)));
    // Just inside the range is accepted and every vertex is valid.
    let c = Shape::<Q, 24, 12>::cube(32_000.0).unwrap();
    assert!(c.positions.iter().flatten().all(|v| v.is_valid()));
}

#[test]
fn capacity_errors_name_needed_and_available_counts() {
    fn check<S: Scalar>() {
        assert_eq!(
            outcome(Shape::<S, 100, 100>::torus(1.0, 0.4, 32, 16)),
            Err(ShapeError::Capacity {
                vertices: Some(512),
                triangles: Some(1024),
                vertex_capacity: 100,
                triangle_capacity: 100,
            })
        );
        assert_eq!(
            outcome(Shape::<S, 23, 12>::cube(1.0)),
            Err(ShapeError::Capacity {
                vertices: Some(24),
                triangles: Some(12),
                vertex_capacity: 23,
                triangle_capacity: 12,
            })
        );
    }
    check::<Q>();
    check::<f32>();
    check::<f64>();
}

#[test]
fn errors_display_what_is_wrong() {
    let e = Small::<f32>::torus(1.0, 0.4, 2, 2).unwrap_err();
    assert_eq!(e.to_string(), "bad shape parameter: nu = 2, expected >= 3");
    let e = Shape::<f32, 24, 12>::cube(f64::NAN).unwrap_err();
    assert_eq!(
        e.to_string(),
        "bad shape parameter: h = NaN, expected finite and > 0"
    );
    let e = Small::<f32>::icosphere(1.0, 99).unwrap_err();
    assert_eq!(
        e.to_string(),
        "bad shape parameter: subdivisions = 99, expected 0..=4"
    );
    let e = Small::<f32>::torus(1.0, 0.4, 32, 16).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shape capacity too small: it needs 512 vertices and 1024 triangles, the shape holds \
         64 vertices and 128 triangles"
    );
    let e = Small::<f32>::torus(1.0, 0.4, HALF, HALF).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "shape capacity too small: it needs more than {m} vertices and more than {m} \
             triangles, the shape holds 64 vertices and 128 triangles",
            m = usize::MAX
        )
    );
    let e = Small::<Q>::torus(30_000.0, 5_000.0, 4, 4).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shape too large for I16F16: its extent 35000 is beyond the type's valid range"
    );
    let e = Shape::<Q, 24, 12>::cube(1e-6).unwrap_err();
    assert_eq!(
        e.to_string(),
        "shape too small for I16F16: its extent 0.000001 rounds to 0"
    );
    // A standard error: boxes into `dyn Error`, no underlying cause.
    let boxed: Box<dyn std::error::Error> = Box::new(e);
    assert!(boxed.source().is_none());
}

#[path = "../fuzz/fuzz_targets/shapes_input.rs"]
#[allow(dead_code)]
mod shapes_input;

/// Replays the committed seed corpus of the `shapes` fuzz target through its own decoding and
/// checks (so `cargo test` guards them in debug and release), each input with a time limit.
#[test]
fn committed_shape_fuzz_inputs_pass_their_checks() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/shapes");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).expect("fuzz/corpus/shapes") {
        let path = entry.expect("entry").path();
        let data = std::fs::read(&path).expect("read input");
        within_limit(&path.display().to_string(), move || {
            shapes_input::shapes_all(&data)
        });
        n += 1;
    }
    assert!(
        n >= 10,
        "expected the committed seed corpus, found {n} inputs"
    );
}
