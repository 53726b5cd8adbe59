//! What the Pico firmware (`examples/pico/firmware.rs`) needs that differs between chips: the
//! RP2040 of the Raspberry Pi Pico (rp2040-hal through the rp-pico board crate).

pub use rp_pico::entry;
pub use rp_pico::hal;

use hal::pac;

/// The DMA request SPI1's transmit FIFO raises (RP2040 datasheet 2.5.3.1: DREQ_SPI1_TX = 18;
/// checked at start-up against the HAL's number).
pub const DREQ_SPI1_TX: u8 = 18;

/// The hardware timer's driver.
pub type Timer = hal::Timer;

/// Core 1's stack (8 KB).
pub type Core1Stack = hal::multicore::Stack<2048>;

/// Starts `entry` on core 1 with `stack`.
pub fn spawn_core1<F: FnOnce() + Send + 'static>(
    core: &mut hal::multicore::Core,
    stack: &'static mut Core1Stack,
    entry: F,
) {
    core.spawn(&mut stack.mem, entry).ok().unwrap();
}

/// The clocks: clk_sys 125 MHz from the 12 MHz crystal through PLL_SYS, clk_peri = clk_sys (the
/// SPI's 62.5 MHz is clk_peri / 2).
pub fn clocks(
    xosc: pac::XOSC,
    clocks: pac::CLOCKS,
    pll_sys: pac::PLL_SYS,
    pll_usb: pac::PLL_USB,
    resets: &mut pac::RESETS,
    watchdog: &mut hal::Watchdog,
) -> hal::clocks::ClocksManager {
    hal::clocks::init_clocks_and_plls(
        rp_pico::XOSC_CRYSTAL_FREQ,
        xosc,
        clocks,
        pll_sys,
        pll_usb,
        resets,
        watchdog,
    )
    .ok()
    .unwrap()
}

/// The timer (its peripheral is used by nothing else).
pub fn timer(resets: &mut pac::RESETS, clocks: &hal::clocks::ClocksManager) -> Timer {
    // SAFETY: TIMER is not taken out of `Peripherals` anywhere else.
    hal::Timer::new(unsafe { pac::TIMER::steal() }, resets, clocks)
}

/// The start-up self-test: the dithered row routine with the interpolators (feature `rp2040`)
/// against the portable rows on 25 random strips of four triangles. It can only run on an
/// RP2040 (the QEMU benchmark's Cortex-M0 has no SIO).
pub fn self_test_passes() -> bool {
    scanline3d::selftest::dither_rows_self_test(25).is_none()
}

/// Makes the LED pin's pad drive (nothing to do on the RP2040: its pads are not isolated).
pub fn led_pad_enable(_pin: usize) {}
