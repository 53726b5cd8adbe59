//! Picks the memory layout of the emulated machine by feature and puts it on the linker path
//! as `memory.x` (the repository root's `memory.x` is the Pico's and is never seen here).
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR"));
    let layout = if env::var_os("CARGO_FEATURE_MICROBIT").is_some() {
        "layouts/microbit.x"
    } else {
        "layouts/mps2.x"
    };
    fs::copy(layout, out.join("memory.x")).expect("copy memory layout");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=layouts");
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("TARGET").is_ok_and(|t| t.starts_with("thumb")) {
        println!("cargo:rustc-link-arg=-Tlink.x");
    }
}
