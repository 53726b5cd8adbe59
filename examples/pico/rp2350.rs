//! What the Pico firmware (`examples/pico/firmware.rs`) needs that differs between chips: the
//! RP2350 of the Raspberry Pi Pico 2, its Cortex-M33 cores (rp235x-hal; no board crate).

pub use rp235x_hal as hal;
pub use rp235x_hal::entry;

use hal::clocks::{Clock, ClockSource, ClocksManager};
use hal::fugit::RateExtU32;
use hal::pac;
use hal::pll::{common_configs::PLL_SYS_150MHZ, setup_pll_blocking, PLLConfig};
use hal::xosc::setup_xosc_blocking;

/// The DMA request SPI1's transmit FIFO raises (the RP2350's DREQ table: DREQ_SPI1_TX = 26;
/// checked at start-up against the HAL's number).
pub const DREQ_SPI1_TX: u8 = 26;

/// The block the RP2350's boot ROM looks for in the first 4 KB of flash: a secure Arm
/// executable.
#[link_section = ".start_block"]
#[used]
pub static IMAGE_DEF: hal::block::ImageDef = hal::block::ImageDef::secure_exe();

/// The Pico 2's crystal.
const XOSC_HZ: u32 = 12_000_000;

/// PLL_USB at 125 MHz (VCO 1500 MHz / 6 / 2) to clock the peripherals: the firmware uses no
/// USB.
const PLL_PERI_125MHZ: PLLConfig = PLLConfig {
    vco_freq: hal::fugit::HertzU32::MHz(1500),
    refdiv: 1,
    post_div1: 6,
    post_div2: 2,
};

/// The hardware timer's driver.
pub type Timer = hal::Timer<hal::timer::CopyableTimer0>;

/// Core 1's stack: 2 040 words, so that with the HAL's flag beside them it fits SRAM8/9 (8 KB).
pub type Core1Stack = hal::multicore::Stack<2040>;

/// Starts `entry` on core 1 with `stack`.
pub fn spawn_core1<F: FnOnce() + Send + 'static>(
    core: &mut hal::multicore::Core,
    stack: &'static mut Core1Stack,
    entry: F,
) {
    core.spawn(stack.take().unwrap(), entry).ok().unwrap();
}

/// The clocks: clk_sys 150 MHz (the stock frequency) from PLL_SYS, and clk_peri 125 MHz from
/// PLL_USB. With clk_peri = clk_sys, as the HAL's default set-up leaves it, the SPI's divider
/// (an even prescale times 1 + SCR) cannot make 62.5 MHz from 150 MHz: a request for 62.5 MHz
/// comes out at 37.5 MHz (150 / 4). From 125 MHz it is 125 / 2 exactly.
pub fn clocks(
    xosc: pac::XOSC,
    clocks: pac::CLOCKS,
    pll_sys: pac::PLL_SYS,
    pll_usb: pac::PLL_USB,
    resets: &mut pac::RESETS,
    watchdog: &mut hal::Watchdog,
) -> ClocksManager {
    let xosc = setup_xosc_blocking(xosc, XOSC_HZ.Hz()).ok().unwrap();
    watchdog.enable_tick_generation((XOSC_HZ / 1_000_000) as u16);
    let mut manager = ClocksManager::new(clocks);
    let sys = setup_pll_blocking(
        pll_sys,
        xosc.operating_frequency(),
        PLL_SYS_150MHZ,
        &mut manager,
        resets,
    )
    .ok()
    .unwrap();
    let peri = setup_pll_blocking(
        pll_usb,
        xosc.operating_frequency(),
        PLL_PERI_125MHZ,
        &mut manager,
        resets,
    )
    .ok()
    .unwrap();
    manager
        .reference_clock
        .configure_clock(&xosc, xosc.get_freq())
        .ok()
        .unwrap();
    manager
        .system_clock
        .configure_clock(&sys, sys.get_freq())
        .ok()
        .unwrap();
    manager
        .peripheral_clock
        .configure_clock(&peri, peri.get_freq())
        .ok()
        .unwrap();
    manager
}

/// The timer (TIMER0; its peripheral is used by nothing else).
pub fn timer(resets: &mut pac::RESETS, clocks: &ClocksManager) -> Timer {
    // SAFETY: TIMER0 is not taken out of `Peripherals` anywhere else.
    hal::Timer::new_timer0(unsafe { pac::TIMER0::steal() }, resets, clocks)
}

/// The start-up self-test: none on the RP2350 (the interpolator row routine is the RP2040's;
/// the Cortex-M33 runs the Thumb-2 kernels, which the QEMU benchmark checks on an M33).
pub fn self_test_passes() -> bool {
    true
}

/// Makes the LED pin's pad drive: RP2350 pads start isolated (PADS_BANK0 ISO) until software
/// clears it.
pub fn led_pad_enable(pin: usize) {
    // SAFETY: only the LED pad's isolation bit changes.
    unsafe {
        (*pac::PADS_BANK0::ptr())
            .gpio(pin)
            .modify(|_, w| w.iso().clear_bit());
    }
}
