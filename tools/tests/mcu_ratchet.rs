//! The performance ratchet's comparison (`tools/src/ratchet.rs`, run by
//! `scripts/mcu-bench`), tested on the host: `cargo test` does not run the tests of examples,
//! so the module is included here.

use scanline3d_tools::ratchet;

use ratchet::{compare, exceeds, format, lowered, parse, Key, BASELINE_PATH};
use scanline3d_tools::atomic::write_atomic;

fn row(scene: &str, number: &str, core: &str, n: u64) -> (Key, u64) {
    (Key::new(scene, number, core), n)
}

fn torus(n: u64) -> Vec<(Key, u64)> {
    vec![row("torus, dithered", "I16F16", "m0", n)]
}

#[test]
fn equal_counts_pass() {
    let base = vec![
        row("cube", "I16F16", "m0", 618_390),
        row("torus, dithered", "I16F16", "m4f", 2_682_788),
    ];
    let c = compare(&base, &base);
    assert!(c.passed());
    assert_eq!(c.unchanged, 2);
    assert!(c.failure("b").is_none());
    assert!(c.improved.is_empty() && c.grew.is_empty() && c.regressed.is_empty());
}

#[test]
fn growth_of_0_9_percent_passes() {
    let c = compare(&torus(1_000_000), &torus(1_009_000));
    assert!(c.passed(), "{:?}", c.failure("b"));
    assert_eq!(c.grew.len(), 1);
    assert!(c.summary("b").contains("+0.90 %"), "{}", c.summary("b"));
}

#[test]
fn growth_of_exactly_1_percent_passes_and_one_more_fails() {
    assert!(!exceeds(1_000_000, 1_010_000));
    assert!(exceeds(1_000_000, 1_010_001));
    assert!(!exceeds(0, 0));
    assert!(exceeds(0, 1));
    assert!(!exceeds(u64::MAX, u64::MAX));
}

#[test]
fn growth_of_1_1_percent_fails_and_names_the_row() {
    let base = vec![
        row("cube", "I16F16", "m0", 618_390),
        row("torus, dithered", "I16F16", "m0", 1_000_000),
    ];
    let now = vec![
        row("cube", "I16F16", "m0", 618_390),
        row("torus, dithered", "I16F16", "m0", 1_011_000),
    ];
    let c = compare(&base, &now);
    assert!(!c.passed());
    assert_eq!(c.regressed.len(), 1);
    assert_eq!(
        c.regressed[0].key,
        Key::new("torus, dithered", "I16F16", "m0")
    );
    let msg = c.failure(BASELINE_PATH).unwrap();
    assert!(
        msg.contains(
            "torus, dithered | I16F16 | m0: baseline 1000000, measured 1011000 (+11000, +1.10 %)"
        ),
        "{msg}"
    );
    assert!(!msg.contains("cube"), "{msg}");
    assert!(msg.contains("scripts/mcu-bench --update-baseline"), "{msg}");
}

#[test]
fn every_regressed_row_is_listed() {
    let base = vec![
        row("torus", "I16F16", "m0", 100),
        row("torus", "I16F16", "m4f", 100),
        row("torus", "I16F16", "m33", 100),
        row("torus", "I16F16", "microbit", 100),
    ];
    let now = vec![
        row("torus", "I16F16", "m0", 102),
        row("torus", "I16F16", "m4f", 101),
        row("torus", "I16F16", "m33", 103),
        row("torus", "I16F16", "microbit", 150),
    ];
    let c = compare(&base, &now);
    let msg = c.failure("b").unwrap();
    assert!(msg.contains("3 row(s) cost more"), "{msg}");
    assert!(
        msg.contains("torus | I16F16 | m33: baseline 100, measured 103"),
        "{msg}"
    );
    assert!(
        msg.contains("torus | I16F16 | m0: baseline 100, measured 102"),
        "{msg}"
    );
    assert!(
        msg.contains("torus | I16F16 | microbit: baseline 100, measured 150"),
        "{msg}"
    );
    assert!(!msg.contains("m4f"), "{msg}");
}

#[test]
fn measured_row_without_baseline_fails_with_the_update_command() {
    let base = torus(1_000);
    let mut now = torus(1_000);
    now.push(row("cube", "I16F16", "microbit", 620_036));
    let c = compare(&base, &now);
    assert!(!c.passed());
    assert_eq!(c.new, vec![row("cube", "I16F16", "microbit", 620_036)]);
    let msg = c.failure(BASELINE_PATH).unwrap();
    assert!(msg.contains("have no baseline"), "{msg}");
    assert!(
        msg.contains("cube | I16F16 | microbit: measured 620036"),
        "{msg}"
    );
    assert!(msg.contains("scripts/mcu-bench --update-baseline"), "{msg}");
}

#[test]
fn baseline_row_no_longer_measured_fails() {
    let mut base = torus(1_000);
    base.push(row("deep", "f32", "m4f", 904_077));
    let c = compare(&base, &torus(1_000));
    assert!(!c.passed());
    assert_eq!(c.missing, vec![row("deep", "f32", "m4f", 904_077)]);
    let msg = c.failure(BASELINE_PATH).unwrap();
    assert!(msg.contains("were not measured"), "{msg}");
    assert!(msg.contains("deep | f32 | m4f: baseline 904077"), "{msg}");
}

#[test]
fn improvement_passes_and_is_reported() {
    let c = compare(&torus(2_682_121), &torus(2_500_000));
    assert!(c.passed());
    assert!(c.failure("b").is_none());
    assert_eq!(c.improved.len(), 1);
    let s = c.summary("b");
    assert!(
        s.contains("cheaper: torus, dithered | I16F16 | m0: baseline 2682121, measured 2500000 (-182121, -6.79 %)"),
        "{s}"
    );
    assert!(s.contains("--lower-baseline"), "{s}");
}

#[test]
fn format_and_parse_round_trip_keeping_the_order() {
    let rows = vec![
        row("torus", "I16F16", "m0", 2_335_141),
        row("torus, dithered", "I16F16", "m0", 2_682_121),
        row("cube", "f32", "microbit", 818_363),
        row("torus, 120 × 120", "I16F16", "microbit", 2_243_536),
    ];
    let text = format(&rows);
    assert!(text
        .lines()
        .all(|l| l.starts_with('#') || l.contains(" | ")));
    assert_eq!(parse(&text).unwrap(), rows);
}

#[test]
fn malformed_baselines_are_refused() {
    assert!(parse("torus | I16F16 | m0").is_err());
    assert!(parse("torus | I16F16 | m0 | many").is_err());
    assert!(parse("torus | I16F16 | m0 | -1").is_err());
    assert!(parse(" | I16F16 | m0 | 1").is_err());
    let dup = parse("torus | I16F16 | m0 | 1\ntorus | I16F16 | m0 | 2\n").unwrap_err();
    assert!(dup.contains("line 2"), "{dup}");
    assert_eq!(parse("# only a comment\n\n").unwrap(), vec![]);
}

#[test]
fn atomic_write_replaces_the_file_and_leaves_no_temporary() {
    let dir = std::env::temp_dir().join(format!("scanline3d-ratchet-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("baseline.txt");
    std::fs::write(&path, "old").unwrap();
    let rows = torus(42);
    write_atomic(&path, &format(&rows)).unwrap();
    assert_eq!(
        parse(&std::fs::read_to_string(&path).unwrap()).unwrap(),
        rows
    );
    assert!(!dir.join("baseline.txt.tmp").exists());
    assert!(write_atomic(&dir.join("no/such/dir/baseline.txt"), "x").is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_committed_baseline_parses_and_covers_every_fixed_point_scene() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../mcu-bench/baseline.txt");
    let rows = parse(&std::fs::read_to_string(path).unwrap()).unwrap();
    let scenes = scanline3d_support::demo::Bench::ALL.map(|b| b.name());
    // Cortex-M0 (mps2-an385), Cortex-M4F (mps2-an386), Cortex-M33 (mps2-an505) and RISC-V
    // rv32imac (virt): every scene, the dithered torus and the torus with a strip of 8 lines.
    for core in ["m0", "m4f", "m33", "rv32imac"] {
        for scene in scenes
            .iter()
            .copied()
            .chain(["torus, dithered", "torus, strip of 8 lines"])
        {
            let k = Key::new(scene, "I16F16", core);
            assert!(rows.iter().any(|(r, _)| *r == k), "{k} missing from {path}");
        }
    }
    // The 16 KB parts: the microbit (Cortex-M0) and the FE310 (sifive_e, RISC-V), each with
    // its cube and its sized torus.
    for core in ["microbit", "fe310"] {
        assert!(rows
            .iter()
            .any(|(k, _)| k.core == core && k.scene == "cube" && k.number == "I16F16"));
        assert!(rows.iter().any(|(k, _)| k.core == core
            && k.scene.starts_with("torus, ")
            && k.scene.contains(" × ")));
    }
}

#[test]
fn lowering_takes_the_cheaper_rows_only_and_refuses_a_failed_comparison() {
    let base = vec![
        row("cube", "I16F16", "m0", 1_000_000),
        row("torus", "I16F16", "m0", 2_000_000),
        row("phong", "I16F16", "m0", 3_000_000),
    ];
    // Cheaper, dearer within the tolerance, unchanged.
    let now = vec![
        row("cube", "I16F16", "m0", 900_000),
        row("torus", "I16F16", "m0", 2_010_000),
        row("phong", "I16F16", "m0", 3_000_000),
    ];
    assert_eq!(
        lowered(&base, &now).unwrap(),
        vec![
            row("cube", "I16F16", "m0", 900_000),
            row("torus", "I16F16", "m0", 2_000_000),
            row("phong", "I16F16", "m0", 3_000_000),
        ]
    );
    // A new row (a new scene's) is added after the others at its measured count.
    let mut new = now.clone();
    new.insert(1, row("deep", "I16F16", "m0", 1));
    assert_eq!(
        lowered(&base, &new).unwrap(),
        vec![
            row("cube", "I16F16", "m0", 900_000),
            row("torus", "I16F16", "m0", 2_000_000),
            row("phong", "I16F16", "m0", 3_000_000),
            row("deep", "I16F16", "m0", 1),
        ]
    );
    // A regressed row, a missing row: refused, with the counts named.
    let mut regressed = now.clone();
    regressed[1].1 = 2_030_000;
    assert!(lowered(&base, &regressed)
        .unwrap_err()
        .contains("1 regressed"));
    assert!(lowered(&base, &now[..2]).unwrap_err().contains("1 missing"));
}
