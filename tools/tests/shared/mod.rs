//! What the tools' integration tests share: the tools' binaries (cargo builds a package's
//! binaries before its integration tests, with the same profile) and the repository's data.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;

/// The binary of tool `name` (`render`, `bake` or `board_frames`).
pub fn tool(name: &str) -> PathBuf {
    PathBuf::from(match name {
        "render" => env!("CARGO_BIN_EXE_render"),
        "bake" => env!("CARGO_BIN_EXE_bake"),
        "board_frames" => env!("CARGO_BIN_EXE_board_frames"),
        _ => panic!("no tool {name}"),
    })
}

/// The repository's root (the workspace's).
pub fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// A file of the repository's test data (`tests/data`).
pub fn data(name: &str) -> PathBuf {
    root().join("tests/data").join(name)
}

/// A fresh path `name` in this test binary's scratch folder `group` (under cargo's
/// `CARGO_TARGET_TMPDIR`).
pub fn tmp(group: &str, name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(group);
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// Runs tool `name` with `args`: its exit status (-1 when killed by a signal), stdout, stderr.
pub fn run(name: &str, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(tool(name))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("run the {name} tool (cargo builds it before the tests): {e}"));
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}
