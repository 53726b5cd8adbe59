//! Firmware for a Raspberry Pi Pico (RP2040) with a Waveshare Pico-LCD-1.3 (ST7789, 240 × 240):
//! the default torus spinning about Y, Gouraud-shaded in fixed point with dithering, drawn line
//! by line through mipidsi (no framebuffer), with the frame rate composed into the lines as text.
//!
//! Build: `cargo build --release --target thumbv6m-none-eabi --example pico_st7789`
//! Flash: `cargo run --release --target thumbv6m-none-eabi --example pico_st7789` (BOOTSEL mode;
//! the runner is elf2uf2-rs, see `.cargo/config.toml`).
//!
//! Not yet verified on hardware: it builds and links in CI. On the host this file compiles to a
//! program that only says so.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "pico_st7789 is firmware for the Raspberry Pi Pico: \
         cargo build --release --target thumbv6m-none-eabi --example pico_st7789"
    );
}

#[cfg(target_os = "none")]
mod firmware {
    use core::fmt::Write as _;

    use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;
    use embedded_graphics::text::Text;
    use embedded_hal::digital::OutputPin;
    use embedded_hal_bus::spi::ExclusiveDevice;
    use mipidsi::interface::SpiInterface;
    use mipidsi::models::ST7789;
    use mipidsi::options::ColorInversion;
    use mipidsi::Builder;
    use panic_halt as _;
    use rp_pico::entry;
    use rp_pico::hal::fugit::RateExtU32;
    use rp_pico::hal::{self, gpio, pac, Clock};
    use scanline3d::demo::{self, TorusRenderer};
    use scanline3d::fixed::types::I16F16;
    use scanline3d::{Fx, Object, Scene};

    // Wiring of the Waveshare Pico-LCD-1.3 (SPI1). Another board: change these lines.
    type ClkPin = gpio::bank0::Gpio10;
    type MosiPin = gpio::bank0::Gpio11;
    /// SPI clock: the RP2040's peripheral clock (125 MHz) divided by 2, the fastest it allows.
    const SPI_HZ: u32 = 62_500_000;
    /// Degrees the torus turns per frame.
    const SPIN_DEG: f64 = 3.0;

    type Q = Fx<I16F16>;

    #[entry]
    fn main() -> ! {
        let mut pac = pac::Peripherals::take().unwrap();
        let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
        let clocks = hal::clocks::init_clocks_and_plls(
            rp_pico::XOSC_CRYSTAL_FREQ,
            pac.XOSC,
            pac.CLOCKS,
            pac.PLL_SYS,
            pac.PLL_USB,
            &mut pac.RESETS,
            &mut watchdog,
        )
        .ok()
        .unwrap();
        let sio = hal::Sio::new(pac.SIO);
        let pins = rp_pico::Pins::new(
            pac.IO_BANK0,
            pac.PADS_BANK0,
            sio.gpio_bank0,
            &mut pac.RESETS,
        );
        let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

        // SPI1: CLK GP10, MOSI GP11; CS GP9, DC GP8, RST GP12, backlight GP13.
        let clk: gpio::Pin<ClkPin, gpio::FunctionSpi, gpio::PullNone> = pins.gpio10.reconfigure();
        let mosi: gpio::Pin<MosiPin, gpio::FunctionSpi, gpio::PullNone> = pins.gpio11.reconfigure();
        let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, clk)).init(
            &mut pac.RESETS,
            clocks.peripheral_clock.freq(),
            SPI_HZ.Hz(),
            embedded_hal::spi::MODE_0,
        );
        let cs = pins.gpio9.into_push_pull_output();
        let dc = pins.gpio8.into_push_pull_output();
        let rst = pins.gpio12.into_push_pull_output();
        let mut backlight = pins.gpio13.into_push_pull_output();
        let spi = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
        let mut buffer = [0u8; 512];
        let di = SpiInterface::new(spi, dc, &mut buffer);
        let mut display = Builder::new(ST7789, di)
            .display_size(240, 240)
            .invert_colors(ColorInversion::Inverted)
            .reset_pin(rst)
            .init(&mut timer)
            .unwrap();
        backlight.set_high().unwrap();

        // The scene: the default torus, generated once into RAM (18 KB), and a renderer with a
        // one-line strip (its RAM is printed by `cargo run --example render` on the host).
        let shape = demo::torus::<Q>().unwrap();
        let camera = demo::camera::<Q>().unwrap();
        let mut renderer = TorusRenderer::<Q, Rgb565>::new().with_dither(true);
        let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
        let mut label: heapless::String<32> = heapless::String::new();
        let mut spin = 0.0f64;
        let mut last = timer.get_counter();
        loop {
            let objects = [Object {
                mesh: shape.mesh(),
                transform: demo::torus_transform(spin),
                material: demo::torus_material(),
            }];
            let scene = Scene::new(&objects, camera, demo::lights());
            let text = Text::new(&label, Point::new(4, 12), style);
            // A frame that cannot be drawn is skipped; the next one is tried.
            let _ = renderer.render_overlaid(&scene, &mut display, &text);
            let now = timer.get_counter();
            let us = (now - last).to_micros().max(1);
            last = now;
            label.clear();
            let _ = write!(label, "{}.{} fps", 1_000_000 / us, (10_000_000 / us) % 10);
            spin += SPIN_DEG;
            if spin >= 360.0 {
                spin -= 360.0;
            }
        }
    }
}
