//! Firmware for a Raspberry Pi Pico 2 (RP2350, two Cortex-M33 cores at 150 MHz) with a Waveshare
//! Pico-LCD-1.3 (ST7789, 240 × 240), wired as for the Pico: the firmware of
//! `examples/pico_st7789.rs` (both cores render the dithered torus into a ring of strips that DMA
//! sends to the panel) on the RP2350, with the library's Thumb-2 kernels. The peripheral clock
//! comes from PLL_USB at 125 MHz so that the SPI really runs at 62.5 MHz (`examples/pico/rp2350.rs`
//! says why).
//!
//! Build: `cargo build --release --target thumbv8m.main-none-eabihf --example pico2_st7789`
//! (the RP2350's memory layout is `memory-rp2350.x`, which build.rs hands to the linker for this
//! target's examples). Flash: `picotool load -x` on the ELF, or convert it to UF2 for the
//! RP2350 (family `rp2350-arm-s`).
//!
//! Built and sized in CI (`scripts/firmware-size`); its frame's instructions on a Cortex-M33 are
//! the QEMU benchmark's board rows (`scripts/mcu-bench`, mps2-an505). Not run: the project's
//! emulator models the RP2040 only, and no board has run it.
#![cfg_attr(target_os = "none", no_std, no_main)]

/// Cores that render: core 1 draws the bottom rows of every frame.
#[cfg(target_os = "none")]
const CORES: usize = 2;

#[cfg(target_os = "none")]
#[path = "pico/rp2350.rs"]
mod chip;

#[cfg(target_os = "none")]
#[path = "pico/firmware.rs"]
mod firmware;

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "pico2_st7789 is firmware for the Raspberry Pi Pico 2: \
         cargo build --release --target thumbv8m.main-none-eabihf --example pico2_st7789"
    );
}
