//! Replays every committed fuzz input — the seed corpora (`fuzz/corpus/render`,
//! `fuzz/corpus/layered`) and any crash the fuzzer ever found (`fuzz/regressions`,
//! `fuzz/regressions/layered`) — through the fuzz targets' own decoding, so that `cargo test`
//! (debug, overflow checks on) guards them.

#[path = "../fuzz/fuzz_targets/render_input.rs"]
#[allow(dead_code)]
mod render_input;

#[path = "../fuzz/fuzz_targets/layered_input.rs"]
#[allow(dead_code)]
mod layered_input;

/// Runs `run` on every file of the directories `dirs` under `fuzz/` (not their
/// subdirectories, nor hidden files); returns how many.
fn replay(dirs: &[&str], run: fn(&[u8])) -> usize {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut n = 0;
    for dir in dirs {
        for entry in std::fs::read_dir(root.join(dir)).expect("fuzz input directory") {
            let path = entry.expect("entry").path();
            if path.is_dir()
                || path
                    .file_name()
                    .is_some_and(|f| f.to_string_lossy().starts_with('.'))
            {
                continue;
            }
            let data = std::fs::read(&path).expect("read input");
            eprintln!("{}", path.display());
            run(&data);
            n += 1;
        }
    }
    n
}

#[test]
fn committed_fuzz_inputs_render_without_panicking() {
    let n = replay(&["corpus/render", "regressions"], render_input::render_all);
    assert!(
        n >= 8,
        "expected the committed seed corpus, found {n} inputs"
    );
}

#[test]
fn committed_layered_fuzz_inputs_render_without_panicking() {
    // Each input's outcomes are printed (`--nocapture` shows them): what the seeds reach.
    let n = replay(&["corpus/layered", "regressions/layered"], |data| {
        for o in layered_input::outcomes(data) {
            eprintln!("  {o}");
        }
    });
    assert!(
        n >= 10,
        "expected the committed seed corpus, found {n} inputs"
    );
}

/// KNOWN DEFECT, open: a Phong (or fast Phong) object lit by a point light whose attenuation
/// `c + l·d + q·d²` is large at its pixels panics in debug ("attempt to shift right with
/// overflow" at src/phong.rs, `point_dir`, `am >> (ae - 32)`), in every number type, from
/// `render` and `render_layered` alike; e.g. a Phong cube at the origin and
/// `PointLight::new([1000, 1, 0], white).attenuation(1, 1, 1)`. Found by the `layered` fuzz
/// target; the fuzz targets avoid it until it is fixed (`avoid_known` in layered_input.rs).
/// When it is fixed: move the inputs up to fuzz/regressions/layered, drop `avoid_known`, and
/// remove this test.
#[test]
#[ignore = "open defect: Phong point-light attenuation overflows a shift (src/phong.rs point_dir)"]
fn open_defect_phong_point_light_attenuation() {
    let n = replay(
        &["regressions/layered/open_phong_point_attenuation"],
        layered_input::layered_all_unfiltered,
    );
    assert!(n >= 1);
}

/// KNOWN DEFECT, open: fog on a Phong object under an orthographic camera with a huge far
/// distance panics in debug ("attempt to multiply with overflow" at src/effects.rs,
/// `FogSpan::factor`, `d * self.ortho`), in f32 and f64, from `render` and `render_layered`
/// alike; e.g. f32, `Projection::Orthographic { height: 6, near: 0.5, far: 1e15 }` (1e12 is
/// fine), `Fog::linear(4, 9, ..)`, a Phong cube in view. Found by the `layered` fuzz target;
/// the fuzz targets avoid it until it is fixed (`avoid_known` in layered_input.rs). When it
/// is fixed: move the inputs up to fuzz/regressions/layered, drop that part of `avoid_known`,
/// and remove this test.
#[test]
#[ignore = "open defect: orthographic fog overflows a multiply (src/effects.rs FogSpan::factor)"]
fn open_defect_fog_orthographic_huge_far() {
    let n = replay(
        &["regressions/layered/open_fog_ortho_far"],
        layered_input::layered_all_unfiltered,
    );
    assert!(n >= 1);
}
