//! Firmware for a Raspberry Pi Pico (RP2040) with a Waveshare Pico-LCD-1.3 (ST7789, 240 × 240):
//! the default torus spinning about Y, Gouraud-shaded in fixed point with dithering, the frame
//! rate of the previous frame as a label, no framebuffer.
//!
//! How a frame goes out: mipidsi initialises the panel and sets the address window through this
//! file's SPI interface (`firmware::PanelBus`, which implements mipidsi's `Interface`); then the
//! renderer draws 8-line strips (`scanline3d_support::demo::board`) into a ring of strip buffers in SRAM
//! while DMA channel 0 sends the finished ones to the panel, with the SPI in 16-bit frames so each
//! native RGB565 word goes out high byte first, as the ST7789 expects, with no byte swapping. The
//! DMA's completion interrupt starts the next finished strip, so the SPI keeps sending while the
//! CPU runs ahead through cheap strips (empty rows) and through the next frame's geometry. The
//! label is composed into the strips it crosses from glyphs rasterized once.
//!
//! Build: `cargo build --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789`
//! Flash: `cargo run --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789` (BOOTSEL mode;
//! the runner is elf2uf2-rs, see `.cargo/config.toml`).
//!
//! Checked in CI in the RP2040 emulator (`scripts/pico-emu`: boot, panel commands, every pixel
//! of the frames, cycles per frame); not yet run on a real board. On the host this file
//! compiles to a program that only says so.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "pico_st7789 is firmware for the Raspberry Pi Pico: \
         cargo build --release --target thumbv6m-none-eabi --features rp2040 --example pico_st7789"
    );
}

#[cfg(target_os = "none")]
mod firmware {
    use core::convert::Infallible;
    use core::sync::atomic::{AtomicU32, Ordering};

    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;
    use embedded_hal::digital::OutputPin;
    use embedded_hal::spi::SpiBus;
    use mipidsi::interface::Interface;
    use mipidsi::models::ST7789;
    use mipidsi::options::ColorInversion;
    use mipidsi::Builder;
    use panic_halt as _;
    use rp_pico::entry;
    use rp_pico::hal::fugit::RateExtU32;
    use rp_pico::hal::pac::interrupt;
    use rp_pico::hal::{self, gpio, pac, Clock};
    use scanline3d::fixed::types::I16F16;
    use scanline3d::{renderer_type, Capacities, Fx};
    use scanline3d_support::demo::board;
    use scanline3d_support::overlay::Glyphs;

    // Wiring of the Waveshare Pico-LCD-1.3 (SPI1). Another board: change these lines.
    type ClkPin = gpio::Pin<gpio::bank0::Gpio10, gpio::FunctionSpi, gpio::PullNone>;
    type MosiPin = gpio::Pin<gpio::bank0::Gpio11, gpio::FunctionSpi, gpio::PullNone>;
    type DcPin = gpio::Pin<gpio::bank0::Gpio8, gpio::FunctionSioOutput, gpio::PullDown>;
    type CsPin = gpio::Pin<gpio::bank0::Gpio9, gpio::FunctionSioOutput, gpio::PullDown>;
    type Spi1 = hal::spi::Spi<hal::spi::Enabled, pac::SPI1, (MosiPin, ClkPin), 8>;
    /// SPI clock: the RP2040's peripheral clock (125 MHz) divided by 2, the fastest it allows.
    const SPI_HZ: u32 = 62_500_000;
    /// DMA channel that sends the strips, and the SPI1 TX data request it is paced by.
    const DMA_CH: usize = 0;
    const DREQ_SPI1_TX: u8 = 18;

    type Q = Fx<I16F16>;

    /// The renderer's size and capacities, by name: the panel; the default torus's needs over
    /// a full turn (`scanline3d_support::demo::TORUS_CAPACITY`: 512 vertices, 466 triangles, 61 active)
    /// with a margin; strips of `board::STRIP_LINES` rows. The host tool that renders the
    /// reference frames uses `board::BoardRenderer`: `Device` must be that type, and the
    /// compiler checks it is (`board::draw_strip` takes a `BoardRenderer`).
    const CAPS: Capacities = Capacities {
        width: board::SIZE,
        height: board::SIZE,
        vertices: 512,
        triangles: 480,
        active: 64,
        lines: board::STRIP_LINES,
        attr_vertices: 0,
        attr_active: 0,
    };
    type Device = renderer_type!(Q, Rgb565, CAPS);

    /// Strip buffers in the ring (10 × 3 840 B in SRAM): enough for the renderer to run ahead
    /// through the empty rows above and below the torus while the SPI catches up.
    const RING: usize = 10;

    /// The ring of strip buffers, shared by the renderer (main) and the DMA (started from main
    /// or from the DMA interrupt). Buffer `k % RING` holds strip `k`; the counters below say
    /// which buffers the renderer may write: those not between `DONE` and `READY`.
    struct Ring(core::cell::UnsafeCell<[board::StripBuffer; RING]>);
    // SAFETY: access is arbitrated by the counters (see `Ring`).
    unsafe impl Sync for Ring {}
    static BUFFERS: Ring = Ring(core::cell::UnsafeCell::new(
        [[[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES]; RING],
    ));
    /// Rows of each buffer's strip.
    static ROWS: [AtomicU32; RING] = [const { AtomicU32::new(0) }; RING];
    /// Strips rendered (written by main only), handed to the DMA, and sent (both written with
    /// interrupts off or from the interrupt), all counted since start-up, wrapping.
    static READY: AtomicU32 = AtomicU32::new(0);
    static STARTED: AtomicU32 = AtomicU32::new(0);
    static DONE: AtomicU32 = AtomicU32::new(0);

    fn dma() -> &'static pac::dma::CH {
        // SAFETY: channel DMA_CH is used by this file's strip queue only.
        unsafe { (*pac::DMA::ptr()).ch(DMA_CH) }
    }

    /// Starts the DMA on the next finished strip if it is idle; interrupts must be off (or this
    /// is the DMA interrupt).
    fn start_next() {
        let started = STARTED.load(Ordering::Relaxed);
        if started == READY.load(Ordering::Acquire) || started != DONE.load(Ordering::Relaxed) {
            return; // nothing ready, or a transfer is running
        }
        let k = started as usize % RING;
        let words = ROWS[k].load(Ordering::Relaxed) * board::SIZE as u32;
        let ch = dma();
        // SAFETY: buffer k holds a finished strip that the renderer does not touch until DONE
        // passes it; SPI1's data register paces the transfer with its TX request.
        unsafe {
            let buffer = (*BUFFERS.0.get())[k].as_ptr();
            ch.ch_read_addr().write(|w| w.bits(buffer as u32));
            ch.ch_write_addr()
                .write(|w| w.bits((*pac::SPI1::ptr()).sspdr().as_ptr() as u32));
            ch.ch_trans_count().write(|w| w.bits(words));
            ch.ch_ctrl_trig().write(|w| {
                w.data_size()
                    .size_halfword()
                    .incr_read()
                    .set_bit()
                    .incr_write()
                    .clear_bit()
                    .treq_sel()
                    .bits(DREQ_SPI1_TX)
                    .chain_to()
                    .bits(DMA_CH as u8)
                    .en()
                    .set_bit()
            });
        }
        STARTED.store(started.wrapping_add(1), Ordering::Relaxed);
    }

    /// A strip is out: its buffer is free; the next finished one goes.
    #[interrupt]
    fn DMA_IRQ_0() {
        // SAFETY: acknowledging channel DMA_CH's interrupt (write 1 to clear).
        unsafe { (*pac::DMA::ptr()).ints0().write(|w| w.bits(1 << DMA_CH)) };
        DONE.store(
            DONE.load(Ordering::Relaxed).wrapping_add(1),
            Ordering::Release,
        );
        start_next();
    }

    /// Renders the prepared frame's strips into the ring, each queued for the DMA as soon as it
    /// is drawn; returns once the last one is queued (it is sent while the caller goes on).
    fn stream_frame(renderer: &mut Device, glyphs: &Glyphs<16>, label: &str) {
        loop {
            let k = READY.load(Ordering::Relaxed);
            // A free buffer: fewer than RING strips rendered and not yet sent.
            while k.wrapping_sub(DONE.load(Ordering::Acquire)) as usize >= RING {}
            // SAFETY: buffer k % RING is not being sent (see above) and only main writes it.
            let buffer = unsafe { &mut (*BUFFERS.0.get())[k as usize % RING] };
            let Some(rows) = board::draw_strip(renderer, glyphs, label, buffer) else {
                return;
            };
            ROWS[k as usize % RING].store(rows.len() as u32, Ordering::Relaxed);
            READY.store(k.wrapping_add(1), Ordering::Release);
            cortex_m::interrupt::free(|_| start_next());
        }
    }

    /// SPI1 with the panel's DC and CS lines: mipidsi's interface for commands (blocking
    /// byte writes, 8-bit frames); pixels go through the strip queue (16-bit frames).
    pub struct PanelBus {
        spi: Spi1,
        dc: DcPin,
        cs: CsPin,
        /// Pixels were streamed since the last command (the SPI is in 16-bit frames).
        streaming: bool,
    }

    impl PanelBus {
        fn regs() -> &'static pac::spi0::RegisterBlock {
            // SAFETY: SPI1 is owned by `self.spi`; these accesses only change the frame size
            // and read the status while no other code uses the peripheral.
            unsafe { &*pac::SPI1::ptr() }
        }

        /// Data size of the SPI's frames (8 or 16 bits), changed with the SPI disabled.
        fn frame_bits(bits: u8) {
            let spi = Self::regs();
            spi.sspcr1().modify(|_, w| w.sse().clear_bit());
            // SAFETY: DSS takes 3..=15 (frame bits − 1).
            spi.sspcr0()
                .modify(|_, w| unsafe { w.dss().bits(bits - 1) });
            spi.sspcr1().modify(|_, w| w.sse().set_bit());
        }

        /// Waits until every queued strip is sent and the SPI is idle, empties the receive
        /// FIFO (the panel sends nothing back) and returns to 8-bit frames for commands.
        fn finish_pixels(&mut self) {
            if !self.streaming {
                return;
            }
            while DONE.load(Ordering::Acquire) != READY.load(Ordering::Relaxed) {}
            let spi = Self::regs();
            while spi.sspsr().read().bsy().bit_is_set() || spi.sspsr().read().tfe().bit_is_clear() {
            }
            while spi.sspsr().read().rne().bit_is_set() {
                let _ = spi.sspdr().read();
            }
            Self::frame_bits(8);
            self.streaming = false;
        }

        /// After `RAMWR`: data mode, 16-bit frames, ready for the strip queue.
        fn begin_pixels(&mut self) {
            let _ = self.spi.flush();
            let _ = self.dc.set_high();
            Self::frame_bits(16);
            self.streaming = true;
        }
    }

    impl Interface for PanelBus {
        type Word = u8;
        type Error = Infallible;

        fn send_command(&mut self, command: u8, args: &[u8]) -> Result<(), Infallible> {
            self.finish_pixels();
            self.cs.set_low()?;
            self.dc.set_low()?;
            self.spi.write(&[command])?;
            self.spi.flush()?;
            self.dc.set_high()?;
            self.spi.write(args)?;
            self.spi.flush()
        }

        fn send_pixels<const N: usize>(
            &mut self,
            pixels: impl IntoIterator<Item = [u8; N]>,
        ) -> Result<(), Infallible> {
            for p in pixels {
                self.spi.write(&p)?;
            }
            self.spi.flush()
        }

        fn send_repeated_pixel<const N: usize>(
            &mut self,
            pixel: [u8; N],
            count: u32,
        ) -> Result<(), Infallible> {
            for _ in 0..count {
                self.spi.write(&pixel)?;
            }
            self.spi.flush()
        }
    }

    extern "C" {
        // `.ram_code` (memory.x): its SRAM range and its load address in flash.
        static mut __sram_code: u32;
        static mut __eram_code: u32;
        static __siram_code: u32;
    }

    /// Copies the renderer's code from flash to SRAM (`.ram_code` in memory.x), word by word
    /// with volatile accesses (no call into code that is not there yet).
    fn load_ram_code() {
        // SAFETY: the linker script defines the symbols as the word-aligned bounds of
        // `.ram_code` in SRAM and its load image in flash; nothing runs from that SRAM yet.
        unsafe {
            let mut dst = core::ptr::addr_of_mut!(__sram_code);
            let end = core::ptr::addr_of_mut!(__eram_code);
            let mut src = core::ptr::addr_of!(__siram_code);
            while dst < end {
                core::ptr::write_volatile(dst, core::ptr::read_volatile(src));
                dst = dst.add(1);
                src = src.add(1);
            }
        }
    }

    #[entry]
    fn main() -> ! {
        // The renderer (`Device::RAM_BYTES`, 23 KB) is a static, never built on the stack: its
        // initial value is a constant (`const_new`), in `.data`, which the reset handler copies
        // from flash before `main` (the image takes as much flash; `.bss` would need a zero
        // initial value, and the depth lines start at u16::MAX). cortex-m-rt's `#[entry]` (which rp-pico's wraps, keeping
        // the statics first) turns a `static mut` declared first in the entry function into a
        // `&'static mut` — safe, as the entry function runs once — so no flag, lock, unsafe
        // block or extra crate is needed.
        static mut RENDERER: Device = Device::const_new(Rgb565::BLACK);
        // First: the HAL's clock set-up below already divides (hardware-divider helpers).
        load_ram_code();
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
        // The DMA block out of reset; channel DMA_CH's completion raises DMA_IRQ_0.
        pac.RESETS.reset().modify(|_, w| w.dma().clear_bit());
        while pac.RESETS.reset_done().read().dma().bit_is_clear() {}
        // SAFETY: enables the channel's interrupt; the handler only touches the strip queue.
        unsafe {
            pac.DMA.inte0().write(|w| w.bits(1 << DMA_CH));
            cortex_m::peripheral::NVIC::unmask(pac::Interrupt::DMA_IRQ_0);
        }

        // SPI1: CLK GP10, MOSI GP11; CS GP9, DC GP8, RST GP12, backlight GP13.
        let clk: ClkPin = pins.gpio10.reconfigure();
        let mosi: MosiPin = pins.gpio11.reconfigure();
        let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, clk)).init(
            &mut pac.RESETS,
            clocks.peripheral_clock.freq(),
            SPI_HZ.Hz(),
            embedded_hal::spi::MODE_0,
        );
        let mut cs: CsPin = pins.gpio9.into_push_pull_output();
        let _ = cs.set_high();
        let bus = PanelBus {
            spi,
            dc: pins.gpio8.into_push_pull_output(),
            cs,
            streaming: false,
        };
        let rst = pins.gpio12.into_push_pull_output();
        let mut backlight = pins.gpio13.into_push_pull_output();
        let mut display = Builder::new(ST7789, bus)
            .display_size(board::SIZE as u16, board::SIZE as u16)
            .invert_colors(ColorInversion::Inverted)
            .reset_pin(rst)
            .init(&mut timer)
            .unwrap();
        backlight.set_high().unwrap();

        // The DMA sends the strip buffers as 16-bit words: they must be RGB565 words.
        let probe = [Rgb565::new(31, 0, 1)];
        // SAFETY: reads the first two bytes of a one-element array.
        let word = unsafe { *(probe.as_ptr() as *const u16) };
        assert!(core::mem::size_of::<Rgb565>() == 2 && word == RawU16::from(probe[0]).into_inner());

        // The scene: the default torus, generated once into RAM (18 KB), on `main`'s stack; the
        // renderer (`RENDERER`) and the strip buffers (the ring `BUFFERS`) are statics.
        // The dithered row routine with the interpolators (feature `rp2040`) against the
        // portable rows on 25 random strips of four triangles: it can only run on an RP2040
        // (the QEMU benchmark's Cortex-M0 has no SIO). A mismatch stops the firmware before
        // its first frame.
        assert!(scanline3d::selftest::dither_rows_self_test(25).is_none());
        let scene = board::BoardScene::<Q>::new().unwrap();
        let glyphs = board::glyphs().unwrap();
        // `board::renderer()`'s options, which the host's reference frames are drawn with.
        let renderer: &'static mut Device = RENDERER;
        renderer.set_dither(true);
        let last_pixel = board::SIZE as u16 - 1;

        // The timer is read once per frame, before the frame is drawn (the emulator check
        // computes the label each frame must show from these reads).
        let mut last = timer.get_counter();
        let mut frame_us = 0u64;
        let mut frame = 0u32;
        loop {
            let label = board::fps_label(frame_us);
            // Geometry first: the previous frame's last strips are still going out meanwhile.
            // A frame that does not fit (it always does: the capacities hold for a full turn)
            // leaves the previous image on the panel.
            if scene.prepare(renderer, frame).is_ok() {
                // The address window and RAMWR through mipidsi (once the queue is empty).
                let _ = display.set_pixels(0, 0, last_pixel, last_pixel, core::iter::empty());
                // SAFETY: only data is sent until the next mipidsi call, which ends the stream
                // (`finish_pixels`) before its command.
                unsafe { display.dcs() }.begin_pixels();
                stream_frame(renderer, &glyphs, &label);
            }
            let now = timer.get_counter();
            frame_us = (now - last).to_micros();
            last = now;
            frame = frame.wrapping_add(1);
        }
    }
}
