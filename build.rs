//! Chooses the kernels (`src/kernel`): sets the cfg aliases `scanline3d_thumb` (a Cortex-M
//! target: `target_arch = "arm"` and `target_os = "none"`) and `scanline3d_thumb_v6m` (the
//! same without 32-bit atomics, i.e. ARMv6-M: Cortex-M0/M0+) and `scanline3d_thumb2` (the same
//! on a core with the full Thumb-2 instruction set: ARMv7-M, ARMv7E-M, ARMv8-M Mainline) and
//! `scanline3d_thumb_geometry` (either of the last two: where the vertex-run, projection and
//! lighting kernels run; not on ARMv8-M Baseline, where they were never measured), all
//! unless the `portable` feature is on; and the capability cfgs `scanline3d_no_divide` (no
//! divide instruction), `scanline3d_no_mul64` (no 32 × 32 → 64-bit multiply) and
//! `scanline3d_no_clz` (no count-leading-zeros instruction), all three ARMv6-M whatever the
//! features. This is the one place the target's architecture is looked at.
//!
//! Also puts the firmware examples' memory layout on the linker path as `memory-chip.x` (which
//! the root `memory.x` includes) — only for this package's examples and only for the two chips'
//! targets: `memory-rp2040.x` for the Raspberry Pi Pico's RP2040 (`thumbv6m-none-eabi`:
//! `pico_st7789`, `pico_st7789_one_core`) and `memory-rp2350.x` for the Pico 2's RP2350
//! (`thumbv8m.main-none-eabihf`: `pico2_st7789`). The library itself links nothing, and crates
//! that depend on it (such as the QEMU benchmark firmware with its own memory layouts) never see
//! these files.
use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=memory-rp2040.x");
    println!("cargo:rerun-if-changed=memory-rp2350.x");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_thumb)");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_thumb_v6m)");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_no_divide)");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_no_mul64)");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_no_clz)");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_thumb2)");
    println!("cargo::rustc-check-cfg=cfg(scanline3d_thumb_geometry)");
    let cfg = |k: &str| env::var(k).unwrap_or_default();
    let cortex_m = cfg("CARGO_CFG_TARGET_ARCH") == "arm" && cfg("CARGO_CFG_TARGET_OS") == "none";
    let atomics32 = cfg("CARGO_CFG_TARGET_HAS_ATOMIC")
        .split(',')
        .any(|w| w == "32");
    let portable = env::var_os("CARGO_FEATURE_PORTABLE").is_some();
    let target = env::var("TARGET").unwrap_or_default();
    // The full Thumb-2 instruction set (ARMv7-M, ARMv7E-M, ARMv8-M Mainline; not ARMv8-M
    // Baseline, which has 32-bit atomics but only a few 32-bit instructions).
    let thumb2 = target.starts_with("thumbv7") || target.starts_with("thumbv8m.main");
    if cortex_m && !atomics32 {
        println!("cargo::rustc-cfg=scanline3d_no_divide");
        println!("cargo::rustc-cfg=scanline3d_no_mul64");
        println!("cargo::rustc-cfg=scanline3d_no_clz");
    }
    if cortex_m && !portable {
        println!("cargo::rustc-cfg=scanline3d_thumb");
        if !atomics32 {
            println!("cargo::rustc-cfg=scanline3d_thumb_v6m");
        }
        if thumb2 {
            println!("cargo::rustc-cfg=scanline3d_thumb2");
        }
        if !atomics32 || thumb2 {
            println!("cargo::rustc-cfg=scanline3d_thumb_geometry");
        }
    }
    // The firmware examples' memory layouts: the Pico's RP2040 (thumbv6m) and the Pico 2's
    // RP2350 (thumbv8m.main), each copied as memory-chip.x, which memory.x includes.
    let layout = match target.as_str() {
        "thumbv6m-none-eabi" => "memory-rp2040.x",
        "thumbv8m.main-none-eabihf" => "memory-rp2350.x",
        _ => return,
    };
    let out = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR"));
    fs::copy(layout, out.join("memory-chip.x")).expect("copy the memory layout");
    println!("cargo:rustc-link-arg-examples=-L{}", out.display());
    println!("cargo:rustc-link-arg-examples=--nmagic");
    println!("cargo:rustc-link-arg-examples=-Tlink.x");
}
