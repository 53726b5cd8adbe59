//! The Raspberry Pi Pico firmware of `examples/pico_st7789.rs` on one core: core 0 prepares each
//! frame and draws all its rows; core 1 stays in the boot ROM. For tools and parts that do not
//! run the second core, and as the reference the two-core build is measured against.
//!
//! Build: `cargo build --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789_one_core`
//!
//! Checked in CI in the RP2040 emulator (`scripts/pico-emu --example pico_st7789_one_core`).
#![cfg_attr(target_os = "none", no_std, no_main)]

/// Cores that render: core 0 only.
#[cfg(target_os = "none")]
const CORES: usize = 1;

#[cfg(target_os = "none")]
#[path = "pico/rp2040.rs"]
mod chip;

#[cfg(target_os = "none")]
#[path = "pico/firmware.rs"]
mod firmware;

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "pico_st7789_one_core is firmware for the Raspberry Pi Pico: cargo build --release \
         --target thumbv6m-none-eabi --features rp2040 --example pico_st7789_one_core"
    );
}
