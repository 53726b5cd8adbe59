//! Puts the Raspberry Pi Pico's `memory.x` on the linker path — only for this package's
//! examples (the firmware example `pico_st7789`) and only when building for the RP2040's target,
//! `thumbv6m-none-eabi`. The library itself links nothing, and crates that depend on it (such as
//! the QEMU benchmark firmware with its own memory layouts) never see this file.
use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    let target = env::var("TARGET").unwrap_or_default();
    if target != "thumbv6m-none-eabi" {
        return;
    }
    let out = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-arg-examples=-L{}", out.display());
    println!("cargo:rustc-link-arg-examples=--nmagic");
    println!("cargo:rustc-link-arg-examples=-Tlink.x");
}
