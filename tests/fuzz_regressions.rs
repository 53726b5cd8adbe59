//! Replays every committed fuzz input — the seed corpora (`fuzz/corpus/render`,
//! `fuzz/corpus/layered`) and any crash the fuzzer ever found (`fuzz/regressions`,
//! `fuzz/regressions/layered`) — through the fuzz targets' own decoding, so that `cargo test`
//! (debug, overflow checks on) guards them.

use crate::render_input;

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
