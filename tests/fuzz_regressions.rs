//! Replays every committed fuzz input — the seed corpus (`fuzz/corpus/render`) and any crash the
//! fuzzer ever found (`fuzz/regressions`) — through the fuzz target's own decoding, so that
//! `cargo test` (debug, overflow checks on) guards them.

#[path = "../fuzz/fuzz_targets/render_input.rs"]
#[allow(dead_code)]
mod render_input;

#[test]
fn committed_fuzz_inputs_render_without_panicking() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut n = 0;
    for dir in ["corpus/render", "regressions"] {
        for entry in std::fs::read_dir(root.join(dir)).expect("fuzz input directory") {
            let path = entry.expect("entry").path();
            if path
                .file_name()
                .is_some_and(|f| f.to_string_lossy().starts_with('.'))
            {
                continue;
            }
            let data = std::fs::read(&path).expect("read input");
            render_input::render_all(&data);
            n += 1;
        }
    }
    assert!(
        n >= 8,
        "expected the committed seed corpus, found {n} inputs"
    );
}
