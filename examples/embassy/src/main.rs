//! The Raspberry Pi Pico firmware on Embassy (embassy-rp): the default torus of
//! `examples/pico_st7789_one_core.rs` on the Waveshare Pico-LCD-1.3 (ST7789, 240 × 240, SPI1),
//! with the same renderer type, the same frames and the same frame-rate label, drawn on core 0.
//!
//! How a frame goes out: mipidsi initialises the panel and sets the address window through
//! [`PanelBus`] (embassy-rp's blocking SPI, 8-bit frames); then the SPI runs in 16-bit frames,
//! so each native RGB565 word goes out high byte first as the ST7789 expects, and embassy-rp's
//! async DMA ([`Pixels::send`], DMA channel 0 paced by SPI1's transmit request) sends the
//! strips. Two strip buffers: while the DMA sends strip k from one, the core draws strip k + 1
//! into the other ([`board::BoardPass`], [`board::STRIP_LINES`] rows a strip): the transfer's
//! future is pinned and polled once, which starts the DMA, the next strip is drawn, then the
//! future is awaited (the executor sleeps in WFE until the DMA's interrupt wakes it). While a
//! frame's last strip goes out the core reads the timer, prepares the next frame's geometry
//! and draws its first strip; then `RAMWR` (the address counter back to the window's start,
//! with the SPI idle) and the next frame's strips follow.
//!
//! Build and check: `scripts/embassy-firmware` (size, emulator run, frame check against the
//! host's render). Versions and why Embassy: `Cargo.toml` and `README.md` beside this folder.
#![no_std]
#![no_main]

use core::ops::Range;
use core::pin::pin;

use embassy_executor::Executor;
use embassy_futures::poll_once;
use embassy_rp::dma::{self, Channel};
use embassy_rp::gpio::{Level, Output};
use embassy_rp::pac;
use embassy_rp::pac::dma::vals::TreqSel;
use embassy_rp::peripherals::{DMA_CH0, SPI1};
use embassy_rp::spi::{self, Blocking, Spi};
use embassy_rp::{bind_interrupts, Peripherals};
use embassy_time::{Delay, Instant};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use mipidsi::interface::Interface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use scanline3d::fixed::types::I16F16;
use scanline3d::{renderer_type, Capacities, Fx};
use scanline3d_support::demo::{self, board, TorusShape};
use scanline3d_support::overlay::Glyphs;
use static_cell::{ConstStaticCell, StaticCell};

type Q = Fx<I16F16>;

/// The renderer of the rp2040-hal firmware (`examples/pico/firmware.rs`, its `CAPS`): the panel;
/// the default torus's needs over a full turn with a margin; one strip line of its own, since
/// its rows are drawn by the strip pass ([`board::BoardPass`], 8 rows a strip) into this file's
/// buffers. `board::BoardScene::prepare` takes only the board's renderer with some number of
/// lines, so the compiler checks the other figures.
const CAPS: Capacities = Capacities {
    width: board::SIZE,
    height: board::SIZE,
    vertices: 512,
    triangles: 480,
    active: 64,
    lines: 1,
    attr_vertices: 0,
    attr_active: 0,
};
type Device = renderer_type!(Q, Rgb565, CAPS);

/// SPI clock: clk_peri (embassy-rp's default clocks: clk_sys 125 MHz from the 12 MHz crystal,
/// clk_peri = clk_sys) divided by 2, the fastest the PL022 allows and the ST7789's rated write
/// clock.
const SPI_HZ: u32 = 62_500_000;
/// ST7789 memory write: the address counter back to the window's start, pixels follow.
const RAMWR: u8 = 0x2c;
/// The Pico's LED (GP25): it blinks a failure code when the firmware stops.
const LED_PIN: usize = 25;

bind_interrupts!(struct Irqs {
    DMA_IRQ_0 => dma::InterruptHandler<DMA_CH0>;
});

// The big state lives in statics, built in place (`ConstStaticCell::take` hands out the
// static itself; nothing passes through the stack). The renderer and the pass start from
// `const_new` (in `.data`: their depth lines start at `u16::MAX`).
/// The renderer (`Device::RAM_BYTES`, 16 KB): the prepared frame.
static RENDERER: ConstStaticCell<Device> = ConstStaticCell::new(Device::const_new(Rgb565::BLACK));
/// The strip pass (its active list and depth lines, 13 KB).
static PASS: ConstStaticCell<board::BoardPass> =
    ConstStaticCell::new(board::BoardPass::const_new(Rgb565::BLACK));
/// The torus mesh (18 KB), built in place at start-up (`demo::build_torus`).
static SHAPE: ConstStaticCell<TorusShape<Q>> = ConstStaticCell::new(TorusShape::new());
/// The two strip buffers (2 × 3 840 B): one being sent, one being drawn.
static STRIPS: ConstStaticCell<[board::StripBuffer; 2]> =
    ConstStaticCell::new([[[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES]; 2]);
static EXECUTOR: StaticCell<Executor> = StaticCell::new();

/// Why the firmware stopped, as the LED blinks it (the codes of the rp2040-hal firmware): that
/// many short flashes, then a pause, repeated.
#[derive(Clone, Copy, Debug)]
enum Failure {
    /// A panic: a failed `unwrap` or assertion (one flash).
    Panic = 1,
    /// The start-up self-test of the interpolator row routine found a mismatch (two flashes).
    SelfTest = 2,
}

/// Any panic: the LED blinks [`Failure::Panic`]. (Under the emulator the harness stops at this
/// handler, `rust_begin_unwind`, and reports where.)
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    blink(Failure::Panic)
}

/// Stops the core and blinks `failure` on the LED forever. Works at any point of the start-up:
/// it takes the GPIO blocks out of reset itself and drives the pin through the SIO.
fn blink(failure: Failure) -> ! {
    cortex_m::interrupt::disable();
    pac::RESETS.reset().modify(|w| {
        w.set_io_bank0(false);
        w.set_pads_bank0(false);
    });
    while !pac::RESETS.reset_done().read().io_bank0()
        || !pac::RESETS.reset_done().read().pads_bank0()
    {}
    // FUNCSEL 5: the SIO drives the pin.
    pac::IO_BANK0
        .gpio(LED_PIN)
        .ctrl()
        .write(|w| w.set_funcsel(5));
    pac::SIO.gpio_oe(0).value_set().write_value(1 << LED_PIN);
    // Cycle counts at 125 MHz (slower before the clocks are set up: still readable).
    loop {
        for _ in 0..failure as u32 {
            pac::SIO.gpio_out(0).value_set().write_value(1 << LED_PIN);
            cortex_m::asm::delay(25_000_000);
            pac::SIO.gpio_out(0).value_clr().write_value(1 << LED_PIN);
            cortex_m::asm::delay(25_000_000);
        }
        cortex_m::asm::delay(125_000_000);
    }
}

/// SPI1 with the panel's DC and CS lines: mipidsi's interface for the start-up commands
/// (embassy-rp's blocking writes, which return once the SPI is idle; 8-bit frames). Pixels go through [`Pixels`] afterwards.
struct PanelBus {
    spi: Spi<'static, SPI1, Blocking>,
    dc: Output<'static>,
    cs: Output<'static>,
}

impl Interface for PanelBus {
    type Word = u8;
    type Error = spi::Error;

    fn send_command(&mut self, command: u8, args: &[u8]) -> Result<(), spi::Error> {
        self.cs.set_low();
        self.dc.set_low();
        self.spi.blocking_write(&[command])?;
        self.dc.set_high();
        self.spi.blocking_write(args)
    }

    fn send_pixels<const N: usize>(
        &mut self,
        pixels: impl IntoIterator<Item = [u8; N]>,
    ) -> Result<(), spi::Error> {
        for p in pixels {
            self.spi.blocking_write(&p)?;
        }
        Ok(())
    }

    fn send_repeated_pixel<const N: usize>(
        &mut self,
        pixel: [u8; N],
        count: u32,
    ) -> Result<(), spi::Error> {
        for _ in 0..count {
            self.spi.blocking_write(&pixel)?;
        }
        Ok(())
    }
}

/// The pixel path after mipidsi's commands: SPI1 in 16-bit frames, fed by DMA channel 0.
struct Pixels {
    /// Owns SPI1 and the DC and CS lines; only this path uses them from now on.
    bus: PanelBus,
    dma: Channel<'static>,
}

impl Pixels {
    /// After mipidsi's last command (`RAMWR` of the whole window): data mode, 16-bit frames.
    fn new(mut bus: PanelBus, dma: Channel<'static>) -> Self {
        bus.dc.set_high();
        spi_drain();
        frame_bits(16);
        Pixels { bus, dma }
    }

    /// `RAMWR` between two frames' pixels (no transfer running): the command byte with DC low
    /// in an 8-bit frame, then DC high and 16-bit frames again.
    fn ramwr(&mut self) {
        spi_drain();
        frame_bits(8);
        self.bus.dc.set_low();
        pac::SPI1.dr().write(|w| w.set_data(RAMWR as u16));
        spi_drain();
        self.bus.dc.set_high();
        frame_bits(16);
    }

    /// Sends `words` (RGB565, one 16-bit SPI frame each) through the DMA; ready once the DMA has
    /// handed the last word to the SPI's FIFO (the SPI may still be shifting: [`Pixels::ramwr`]
    /// waits for it). Nothing happens until the future is first polled.
    async fn send(&mut self, words: &[u16]) {
        // SAFETY: `words` stays borrowed while the transfer lives (dropping it aborts the
        // channel and waits until it stops); SSPDR is SPI1's data register, which only this
        // path writes, and the request SPI1_TX paces the channel by its transmit FIFO.
        let transfer = unsafe {
            self.dma.write(
                words,
                pac::SPI1.dr().as_ptr() as *mut u16,
                TreqSel::SPI1_TX,
                false,
            )
        };
        transfer.await;
    }
}

/// Data size of SPI1's frames (8 or 16 bits), changed with the SPI disabled.
fn frame_bits(bits: u8) {
    pac::SPI1.cr1().modify(|w| w.set_sse(false));
    pac::SPI1.cr0().modify(|w| w.set_dss(bits - 1));
    pac::SPI1.cr1().modify(|w| w.set_sse(true));
}

/// Waits until SPI1 has shifted out everything queued, then empties its receive FIFO (the
/// panel sends nothing back).
fn spi_drain() {
    let spi = pac::SPI1;
    while spi.sr().read().bsy() || !spi.sr().read().tfe() {}
    while spi.sr().read().rne() {
        let _ = spi.dr().read();
    }
}

/// The first `lines` lines of a strip buffer as the 16-bit words the DMA sends.
fn words(buffer: &board::StripBuffer, lines: usize) -> &[u16] {
    let n = lines.min(board::STRIP_LINES) * board::SIZE;
    // SAFETY: an RGB565 colour is one native 16-bit word (checked in `run` before any strip is
    // sent), so the buffer's first `n` of its `STRIP_LINES · SIZE` colours are `n` `u16`s.
    unsafe { core::slice::from_raw_parts(buffer.as_ptr().cast::<u16>(), n) }
}

/// One frame's drawing state.
struct Frame {
    /// Its number in the animation (the spin).
    number: u32,
    /// The frame-rate label drawn into it.
    label: heapless::String<16>,
    /// The pass was begun on the prepared frame (false: the frame did not fit; its strips are
    /// drawn black).
    begun: bool,
}

/// Prepares frame `number` (its geometry) and begins the pass on all its rows.
fn start_frame(
    scene: &board::BoardScene<'_, Q>,
    renderer: &mut Device,
    pass: &mut board::BoardPass,
    number: u32,
) -> bool {
    // A frame that does not fit (it always does: the capacities hold for a full turn) is
    // drawn black rather than left half drawn.
    scene
        .prepare(renderer, number)
        .is_ok_and(|frame| pass.begin(frame.share(), 0..board::SIZE).is_ok())
}

/// Draws the strip of the frame starting at row `row` into `buffer`, with the label composed
/// into it; returns its rows.
fn draw_strip(
    pass: &mut board::BoardPass,
    renderer: &Device,
    buffer: &mut board::StripBuffer,
    row: usize,
    begun: bool,
    glyphs: &Glyphs<16>,
    label: &str,
) -> Range<usize> {
    let rows = match begun.then(|| pass.render_strip_into(renderer, buffer)) {
        Some(Ok(Some(rows))) => rows,
        _ => {
            // No strip where one was due: black rows keep the stream's order.
            *buffer = [[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES];
            row..(row + board::STRIP_LINES).min(board::SIZE)
        }
    };
    let n = rows.len();
    glyphs.draw(
        label,
        board::LABEL_AT,
        Rgb565::WHITE,
        rows.start,
        &mut buffer[..n],
    );
    rows
}

extern "C" {
    // `.ram_code` (memory.x): its SRAM range and its load address in flash.
    static mut __sram_code: u32;
    static mut __eram_code: u32;
    static __siram_code: u32;
}

/// Copies the renderer's code from flash to SRAM (`.ram_code` in memory.x), word by word with
/// volatile accesses (no call into code that is not there yet). `main`'s first statement:
/// `.ram_code` holds `mem*` and the compiler's helpers, which the executor and embassy-rp's
/// clock set-up may call.
fn load_ram_code() {
    // SAFETY: the linker script defines the symbols as the word-aligned bounds of `.ram_code`
    // in SRAM and its load image in flash; nothing runs from that SRAM yet.
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

#[cortex_m_rt::entry]
fn main() -> ! {
    load_ram_code();
    let p = embassy_rp::init(Default::default());
    let executor = EXECUTOR.init(Executor::new());
    executor.run(|spawner| spawner.spawn(run(p).unwrap()))
}

/// The firmware: the panel's start-up, then frames forever.
#[embassy_executor::task]
async fn run(p: Peripherals) -> ! {
    // The chip's start-up self-test: the dithered row routine with the interpolators against
    // the portable rows on 25 random strips. A failure stops the firmware before its first
    // frame, the LED blinking `Failure::SelfTest`.
    if scanline3d::selftest::dither_rows_self_test(25).is_some() {
        blink(Failure::SelfTest);
    }

    // SPI1: CLK GP10, MOSI GP11; CS GP9, DC GP8, RST GP12, backlight GP13 (off until the first
    // frame is on the panel). The wiring of the Waveshare Pico-LCD-1.3, as in
    // examples/pico/firmware.rs.
    let mut config = spi::Config::default();
    config.frequency = SPI_HZ;
    let spi = Spi::new_blocking_txonly(p.SPI1, p.PIN_10, p.PIN_11, config);
    let mut backlight = Output::new(p.PIN_13, Level::Low);
    let bus = PanelBus {
        spi,
        dc: Output::new(p.PIN_8, Level::Low),
        cs: Output::new(p.PIN_9, Level::High),
    };
    let rst = Output::new(p.PIN_12, Level::Low);
    let mut display = Builder::new(ST7789, bus)
        .display_size(board::SIZE as u16, board::SIZE as u16)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut Delay)
        .unwrap();
    // The address window and RAMWR through mipidsi; then the pixel path for good.
    let last_pixel = board::SIZE as u16 - 1;
    display
        .set_pixels(0, 0, last_pixel, last_pixel, core::iter::empty())
        .unwrap();
    let (bus, _, _) = display.release();
    let mut pixels = Pixels::new(bus, Channel::new(p.DMA_CH0, Irqs));

    // The DMA sends the strip buffers as 16-bit words: they must be RGB565 words.
    let probe = [Rgb565::new(31, 0, 1)];
    // SAFETY: reads the first two bytes of a one-element array of a two-byte type.
    let word = unsafe { *(probe.as_ptr() as *const u16) };
    assert!(core::mem::size_of::<Rgb565>() == 2 && word == RawU16::from(probe[0]).into_inner());

    // The scene: the default torus, generated once in place; the renderer, pass and strip
    // buffers are statics too.
    let shape = SHAPE.take();
    demo::build_torus(shape).unwrap();
    let shape: &TorusShape<Q> = shape;
    let scene = board::BoardScene::new(shape).unwrap();
    let glyphs = board::glyphs().unwrap();
    let renderer = RENDERER.take();
    // `board::renderer()`'s options, which the host's reference frames are drawn with.
    renderer.set_dither(true);
    let pass = PASS.take();
    let [ready, spare] = STRIPS.take();
    let (mut ready, mut spare) = (ready, spare);

    // The timer is read once before the first frame's geometry and once after drawing each
    // frame's rows, before the next frame's geometry; frame K's label shows T_K − T_{K−1} (the
    // emulator check computes the label each frame must show from these reads). Nothing else
    // reads the timer while frames are drawn (no embassy-time timer is armed).
    let mut last = Instant::now();
    let mut frame = Frame {
        number: 0,
        label: board::fps_label(0),
        begun: start_frame(&scene, renderer, pass, 0),
    };
    let mut rows = draw_strip(pass, renderer, ready, 0, frame.begun, &glyphs, &frame.label);
    let mut lit = false;
    loop {
        if rows.start == 0 {
            // The frame's first strip: the address counter back to the window's start.
            pixels.ramwr();
        }
        let next = {
            let mut tx = pin!(pixels.send(words(ready, rows.len())));
            // The first poll starts the DMA; the strip goes out while the core draws the next.
            let sent = poll_once(tx.as_mut()).is_ready();
            let next = if rows.end < board::SIZE {
                draw_strip(
                    pass,
                    renderer,
                    spare,
                    rows.end,
                    frame.begun,
                    &glyphs,
                    &frame.label,
                )
            } else {
                // The frame's last strip is going out: the next frame's label, geometry and
                // first strip.
                let now = Instant::now();
                let number = frame.number.wrapping_add(1);
                frame = Frame {
                    number,
                    label: board::fps_label((now - last).as_micros()),
                    begun: start_frame(&scene, renderer, pass, number),
                };
                last = now;
                draw_strip(pass, renderer, spare, 0, frame.begun, &glyphs, &frame.label)
            };
            if !sent {
                tx.await;
            }
            next
        };
        if !lit && rows.end == board::SIZE {
            // The first frame is on the panel: the backlight comes on.
            backlight.set_high();
            lit = true;
        }
        core::mem::swap(&mut ready, &mut spare);
        rows = next;
    }
}
