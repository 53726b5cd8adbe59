//! What the tools' integration tests share: the tools' binaries (cargo builds a package's
//! binaries before its integration tests, with the same profile) and the repository's data.
#![allow(dead_code)]

use std::path::PathBuf;

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
