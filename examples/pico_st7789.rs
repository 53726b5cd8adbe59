//! Firmware for a Raspberry Pi Pico (RP2040) with a Waveshare Pico-LCD-1.3 (ST7789, 240 × 240),
//! both cores rendering: the default torus spinning about Y, Gouraud-shaded in fixed point with
//! dithering, the frame rate of the previous frame as a label, no framebuffer.
//!
//! Core 0 prepares each frame's geometry into one of two renderers while core 1 still draws the
//! previous frame from the other; then core 0 draws the frame's top rows and core 1 its bottom
//! rows, each through its own strip pass over the same prepared frame, into one ring of strip
//! buffers that DMA sends to the panel in row order. The split moves by a strip per frame
//! towards equal work on both cores. How it all goes: `examples/pico/firmware.rs`.
//!
//! Build: `cargo build --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789`
//! Flash: `cargo run --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789`
//! (BOOTSEL mode; the runner is elf2uf2-rs, see `.cargo/config.toml`). The one-core build of the
//! same firmware is `--example pico_st7789_one_core`.
//!
//! Checked in CI in the RP2040 emulator (`scripts/pico-emu`: boot, both cores, panel commands,
//! every pixel of the frames, cycles per frame); not yet run on a real board. On the host this
//! file compiles to a program that only says so.
#![cfg_attr(target_os = "none", no_std, no_main)]

/// Cores that render: core 1 draws the bottom rows of every frame.
#[cfg(target_os = "none")]
const CORES: usize = 2;

#[cfg(target_os = "none")]
#[path = "pico/rp2040.rs"]
mod chip;

#[cfg(target_os = "none")]
#[path = "pico/firmware.rs"]
mod firmware;

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "pico_st7789 is firmware for the Raspberry Pi Pico: \
         cargo build --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789"
    );
}
