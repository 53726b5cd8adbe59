//! The Pico firmware shared by `examples/pico_st7789.rs` (two cores) and
//! `examples/pico_st7789_one_core.rs` (one core): the including file sets `CORES`.
//!
//! How a frame goes out: mipidsi initialises the panel and sets the address window through this
//! file's SPI interface ([`PanelBus`], which implements mipidsi's `Interface`); then the strip
//! passes ([`board::BoardPass`], one per core) draw 8-line strips into a ring of [`RING`] strip
//! buffers in SRAM, and DMA channel [`DMA_CH`] sends the finished ones to the panel in row
//! order, with the SPI in 16-bit frames so each native RGB565 word goes out high byte first, as
//! the ST7789 expects, with no byte swapping. The DMA's completion interrupt starts the next
//! finished strip; before a frame's first strip it sends `RAMWR` itself (the address counter
//! back to the window's start), so the SPI never waits for the CPU between frames.
//!
//! Two cores: frame `f`'s geometry goes into renderer `f % 2` while core 1 may still draw frame
//! `f − 1` from the other one. Core 0 then draws rows `0..split` and core 1 rows `split..240`
//! of frame `f`, both from the same prepared frame (`&Renderer`), each strip into the ring slot
//! of its place in the stream. The split moves by one strip per frame towards equal work
//! (each core times its own work with its SysTick, waits excluded). The label is drawn into the
//! strips it crosses (rows 4..14, always core 0's: the split stays at or below row 16).
//!
//! The cores talk through the SIO FIFOs: core 0 sends a frame's job (renderer, split, first
//! strip's number in the stream), core 1 answers with its work time once it has drawn its rows
//! (the renderer is free again). The ring's counters change inside `critical_section` (on
//! the RP2040 the HAL's implementation takes spinlock 31 and masks the core's interrupts, so it
//! excludes the other core too).

use core::cell::UnsafeCell;
use core::convert::Infallible;
use core::ops::Range;
use core::sync::atomic::{AtomicU32, Ordering};

use super::chip::{self, entry, hal};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use hal::fugit::RateExtU32;
use hal::multicore::Multicore;
use hal::pac::interrupt;
use hal::{gpio, pac, Clock};
use mipidsi::interface::Interface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use scanline3d::fixed::types::I16F16;
use scanline3d::{renderer_type, Capacities, Fx};
use scanline3d_support::demo::{self, board, TorusShape};
use scanline3d_support::overlay::Glyphs;

use super::CORES;

// Wiring of the Waveshare Pico-LCD-1.3 (SPI1). Another board: change these lines.
type ClkPin = gpio::Pin<gpio::bank0::Gpio10, gpio::FunctionSpi, gpio::PullNone>;
type MosiPin = gpio::Pin<gpio::bank0::Gpio11, gpio::FunctionSpi, gpio::PullNone>;
type DcPin = gpio::Pin<gpio::bank0::Gpio8, gpio::FunctionSioOutput, gpio::PullDown>;
type CsPin = gpio::Pin<gpio::bank0::Gpio9, gpio::FunctionSioOutput, gpio::PullDown>;
type Spi1 = hal::spi::Spi<hal::spi::Enabled, pac::SPI1, (MosiPin, ClkPin), 8>;
/// The panel's data/command line, GPIO 8 (`DcPin`), as a bit of the SIO's GPIO registers: the
/// DMA interrupt sets it for `RAMWR` between frames.
const DC_BIT: u32 = 1 << 8;
/// SPI clock: the peripheral clock (125 MHz on both chips, see `chip::clocks`) divided by 2,
/// the fastest the PL022 allows and the ST7789's rated write clock.
const SPI_HZ: u32 = 62_500_000;
/// DMA channel that sends the strips (its completion raises `DMA_IRQ_0` on core 0).
pub const DMA_CH: usize = 0;
/// The DMA request the channel is paced by: SPI1's transmit FIFO (the chip's constant: 18 on
/// the RP2040, 26 on the RP2350; checked against the HAL's number at start-up).
pub use chip::DREQ_SPI1_TX;
/// ST7789 memory write: the address counter back to the window's start, pixels follow.
const RAMWR: u32 = 0x2c;

type Q = Fx<I16F16>;

/// The renderer's size and capacities, by name: the panel; the default torus's needs over
/// a full turn (`scanline3d_support::demo::TORUS_CAPACITY`: 512 vertices, 466 triangles, 61
/// active) with a margin. One strip line of its own: its rows are drawn by the cores' strip
/// passes ([`board::BoardPass`], `board::STRIP_LINES` rows a strip), never by the renderer's
/// own pass, so its lines would be 2 × 6.7 KB of unused SRAM. The host tool that renders the
/// reference frames uses `board::BoardRenderer`, the same renderer with 8 lines (a frame's
/// pixels do not depend on the strip height); `board::BoardScene::prepare` takes either, and
/// the compiler checks that `Device` is one of them.
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

/// Strip buffers in the ring (14 × 3 840 B = 52.5 KB of SRAM). Enough that the core drawing the
/// bottom rows runs ahead while the top rows go out, and that the SPI still has strips to send
/// while core 0 prepares the next frame.
const RING: usize = 14;
/// Strips are numbered in the stream modulo `WRAP`, a multiple of `RING` (so that strip `g`'s
/// slot, `g % RING`, does not jump when the count wraps) and of the strips per frame.
const WRAP: u32 = (RING as u32 * STRIPS) << 20;
const _: () = assert!((RING as u64 * STRIPS as u64) << 20 < 1 << 32);
/// Strips per frame.
const STRIPS: u32 = (board::SIZE / board::STRIP_LINES) as u32;
/// The split's bounds: the label (rows 4..14) is always in core 0's rows.
const SPLIT_MIN: usize = 2 * board::STRIP_LINES;
const SPLIT_MAX: usize = board::SIZE - board::STRIP_LINES;

/// Data shared between the cores and the DMA interrupt, its accesses arbitrated by the
/// protocol its users describe.
struct Shared<T>(UnsafeCell<T>);
// SAFETY: every access goes through the ring's counters or the cores' FIFO messages (see the
// users of each static).
unsafe impl<T> Sync for Shared<T> {}

/// The ring: strip `g` of the stream (counted from start-up, wrapping) is drawn into buffer
/// `g % RING` once the DMA has sent strip `g − RING` (`DONE` passed it), by the core that draws
/// its rows, which then writes `ROWS` and `FILLED` of the slot.
static BUFFERS: Shared<[board::StripBuffer; RING]> = Shared(UnsafeCell::new(
    [[[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES]; RING],
));
/// Each slot's strip: first row (bits 16..) and row count (bits 0..16).
static ROWS: [AtomicU32; RING] = [const { AtomicU32::new(0) }; RING];
/// Each slot's strip number plus one once it is drawn (0: never drawn; `1..=WRAP`).
static FILLED: [AtomicU32; RING] = [const { AtomicU32::new(0) }; RING];
/// Strips handed to the DMA and strips sent, counted since start-up modulo `WRAP`; changed only
/// inside `critical_section` (from either core, or the DMA interrupt).
static STARTED: AtomicU32 = AtomicU32::new(0);
static DONE: AtomicU32 = AtomicU32::new(0);

/// The renderers (`Device::RAM_BYTES`, 16 KB each), one per core: frame `f` is prepared in renderer
/// `f % CORES`. Core 0 writes a renderer only after core 1 said it is done with it; core 1
/// reads it only between the job message and its answer. Initialised by `const_new` (in
/// `.data`: the reset handler copies them from flash; the depth lines start at `u16::MAX`, so
/// `.bss` would not do).
static FRAMES: Shared<[Device; CORES]> = Shared(UnsafeCell::new(
    [const { Device::const_new(Rgb565::BLACK) }; CORES],
));
/// Each core's strip pass (its active list and depth lines, 13 KB): pass `i` is core `i`'s.
static PASSES: Shared<[board::BoardPass; CORES]> = Shared(UnsafeCell::new(
    [const { board::BoardPass::const_new(Rgb565::BLACK) }; CORES],
));
/// Core 1's stack (8 KB; its strip pass is the static above).
/// The torus mesh (18 KB), built in place at start-up (`demo::build_torus`): a shape returned
/// by value would pass through the stack, which does not have room for it beside the statics.
static SHAPE: Shared<TorusShape<Q>> = Shared(UnsafeCell::new(TorusShape::new()));
/// In SRAM4/5 on the RP2040, SRAM8/9 on the RP2350 (`.core1_stack` in the chip's layout,
/// memory-rp2040.x or memory-rp2350.x), apart from the statics and core 0's stack.
#[link_section = ".core1_stack"]
static CORE1_STACK: Shared<chip::Core1Stack> = Shared(UnsafeCell::new(chip::Core1Stack::new()));

/// `g + n` in the stream's numbering (`g < WRAP`, `n < WRAP`).
fn later(g: u32, n: u32) -> u32 {
    let s = g + n;
    if s >= WRAP {
        s - WRAP
    } else {
        s
    }
}

/// Strips from `from` to `to` in the stream's numbering (both `< WRAP`).
fn strips_between(from: u32, to: u32) -> u32 {
    if to >= from {
        to - from
    } else {
        to + WRAP - from
    }
}

/// The Pico's LED (GP25): it blinks a failure code when the firmware stops.
pub const LED_PIN: usize = 25;

/// Why the firmware stopped, as the LED blinks it: that many short flashes, then a pause,
/// repeated (the backlight may be off: the LED is what shows it).
#[derive(Clone, Copy, Debug)]
pub enum Failure {
    /// A panic: a failed `unwrap` or assertion, on either core (one flash).
    Panic = 1,
    /// The start-up self-test of the interpolator row routine found a mismatch (two flashes).
    SelfTest = 2,
}

/// Any panic, on either core: the LED blinks [`Failure::Panic`]. (Under the emulator the
/// harness stops at this handler, `rust_begin_unwind`, and reports where.)
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    blink(Failure::Panic)
}

/// Stops the calling core and blinks `failure` on the LED forever. Works at any point of the
/// start-up: it takes the GPIO blocks out of reset itself and drives the pin through the SIO.
fn blink(failure: Failure) -> ! {
    cortex_m::interrupt::disable();
    // SAFETY: the core stops here; these writes only make GP25 an SIO output and drive it.
    unsafe {
        let resets = &*pac::RESETS::ptr();
        resets
            .reset()
            .modify(|_, w| w.io_bank0().clear_bit().pads_bank0().clear_bit());
        while resets.reset_done().read().io_bank0().bit_is_clear()
            || resets.reset_done().read().pads_bank0().bit_is_clear()
        {}
        // FUNCSEL 5: the SIO drives the pin.
        chip::led_pad_enable(LED_PIN);
        (*pac::IO_BANK0::ptr())
            .gpio(LED_PIN)
            .gpio_ctrl()
            .write(|w| w.bits(5));
        let sio = &*pac::SIO::ptr();
        sio.gpio_oe_set().write(|w| w.bits(1 << LED_PIN));
        // Cycle counts at 125 MHz (slower before the clocks are set up: still readable).
        loop {
            for _ in 0..failure as u32 {
                sio.gpio_out_set().write(|w| w.bits(1 << LED_PIN));
                cortex_m::asm::delay(25_000_000);
                sio.gpio_out_clr().write(|w| w.bits(1 << LED_PIN));
                cortex_m::asm::delay(25_000_000);
            }
            cortex_m::asm::delay(125_000_000);
        }
    }
}

fn dma() -> &'static pac::dma::CH {
    // SAFETY: channel DMA_CH is used by this file's strip queue only.
    unsafe { (*pac::DMA::ptr()).ch(DMA_CH) }
}

fn spi_regs() -> &'static pac::spi0::RegisterBlock {
    // SAFETY: SPI1 belongs to the panel; outside mipidsi's commands (before the first strip)
    // only the strip queue uses it, inside `critical_section` or with the DMA idle.
    unsafe { &*pac::SPI1::ptr() }
}

/// Data size of the SPI's frames (8 or 16 bits), changed with the SPI disabled.
fn frame_bits(bits: u8) {
    let spi = spi_regs();
    spi.sspcr1().modify(|_, w| w.sse().clear_bit());
    // SAFETY: DSS takes 3..=15 (frame bits − 1).
    spi.sspcr0()
        .modify(|_, w| unsafe { w.dss().bits(bits - 1) });
    spi.sspcr1().modify(|_, w| w.sse().set_bit());
}

/// Waits until the SPI has shifted out everything queued, then empties its receive FIFO (the
/// panel sends nothing back).
fn spi_drain() {
    let spi = spi_regs();
    while spi.sspsr().read().bsy().bit_is_set() || spi.sspsr().read().tfe().bit_is_clear() {}
    while spi.sspsr().read().rne().bit_is_set() {
        let _ = spi.sspdr().read();
    }
}

/// `RAMWR` between two frames' pixels (the DMA is idle): the command byte with DC low in an
/// 8-bit frame, then DC high and 16-bit frames again.
fn ramwr() {
    // SAFETY: the SIO's GPIO set/clear registers change only the DC line's bit (core 0
    // configured the pin as an SIO output; no other code drives it while pixels stream).
    let sio = unsafe { &*pac::SIO::ptr() };
    spi_drain();
    frame_bits(8);
    sio.gpio_out_clr().write(|w| unsafe { w.bits(DC_BIT) });
    // SAFETY: a data register write of one byte.
    spi_regs()
        .sspdr()
        .write(|w| unsafe { w.data().bits(RAMWR as u16) });
    spi_drain();
    sio.gpio_out_set().write(|w| unsafe { w.bits(DC_BIT) });
    frame_bits(16);
}

/// Starts the DMA on the next strip of the stream if it is drawn and the DMA idle. Only inside
/// `critical_section` (from either core or the DMA interrupt).
fn start_next() {
    let started = STARTED.load(Ordering::Relaxed);
    if started != DONE.load(Ordering::Relaxed) {
        return; // a transfer is running
    }
    let k = started as usize % RING;
    if FILLED[k].load(Ordering::Acquire) != started + 1 {
        return; // not drawn yet
    }
    let rows = ROWS[k].load(Ordering::Relaxed);
    if rows >> 16 == 0 {
        ramwr(); // the frame's first strip
    }
    let words = (rows & 0xffff) * board::SIZE as u32;
    let ch = dma();
    // SAFETY: buffer k holds a finished strip that no core touches until DONE passes it;
    // SPI1's data register paces the transfer with its TX request.
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
    STARTED.store(later(started, 1), Ordering::Relaxed);
}

/// A strip is out: its buffer is free (a core waiting for it is woken by the event); the next
/// drawn one goes.
#[interrupt]
fn DMA_IRQ_0() {
    // SAFETY: acknowledging channel DMA_CH's interrupt (write 1 to clear).
    unsafe { (*pac::DMA::ptr()).ints0().write(|w| w.bits(1 << DMA_CH)) };
    critical_section::with(|_| {
        DONE.store(later(DONE.load(Ordering::Relaxed), 1), Ordering::Release);
        start_next();
    });
    cortex_m::asm::sev();
}

/// The calling core's SysTick as a free-running 24-bit down-counter at the core's clock.
fn systick_start(syst: &mut SYST) {
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00ff_ffff);
    syst.clear_current();
    syst.enable_counter();
}

/// Cycles since `then` (a `SYST::get_current()` value), for spans under 2²⁴ cycles (134 ms).
fn since(then: u32) -> u32 {
    then.wrapping_sub(SYST::get_current()) & 0x00ff_ffff
}

/// Draws rows `rows` of the frame `renderer` holds through `pass` into the ring (strip `y / 8`
/// of the frame is strip `first + y / 8` of the stream), with the label composed into the
/// strips it crosses. Returns the cycles spent drawing (waits for a free buffer excluded).
fn draw_rows(
    pass: &mut board::BoardPass,
    renderer: &Device,
    rows: Range<usize>,
    first: u32,
    label: Option<(&Glyphs<16>, &str)>,
) -> u32 {
    let t = SYST::get_current();
    // Never fails for a prepared frame; if it did, the strips below are drawn black.
    let begun = pass.begin(renderer, rows.clone()).is_ok();
    let mut work = since(t);
    let mut y = rows.start;
    while y < rows.end {
        let g = later(first, (y / board::STRIP_LINES) as u32);
        // A free buffer: strip g − RING is sent.
        while strips_between(DONE.load(Ordering::Acquire), g) as usize >= RING {
            cortex_m::asm::wfe();
        }
        let k = g as usize % RING;
        // SAFETY: buffer k is not being sent (see above), and strip g is this core's alone.
        let buffer = unsafe { &mut (*BUFFERS.0.get())[k] };
        let t = SYST::get_current();
        let strip = match begun.then(|| pass.render_strip_into(renderer, buffer)) {
            Some(Ok(Some(strip))) => strip,
            _ => {
                // No strip where one was due: black rows keep the stream's order.
                *buffer = [[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES];
                y..(y + board::STRIP_LINES).min(rows.end)
            }
        };
        if let Some((glyphs, text)) = label {
            let n = strip.len();
            glyphs.draw(
                text,
                board::LABEL_AT,
                Rgb565::WHITE,
                strip.start,
                &mut buffer[..n],
            );
        }
        work = work.wrapping_add(since(t));
        ROWS[k].store(
            ((strip.start as u32) << 16) | strip.len() as u32,
            Ordering::Relaxed,
        );
        FILLED[k].store(g + 1, Ordering::Release);
        critical_section::with(|_| start_next());
        y = strip.end;
    }
    work
}

/// Core 1: waits for a frame's job (renderer, split, the frame's first strip in the stream),
/// draws the rows below the split, answers with its work time.
fn core1_main(pass: &'static mut board::BoardPass) {
    // SAFETY: core 1's own SIO FIFO end and SysTick; core 0 uses its own.
    let pac = unsafe { pac::Peripherals::steal() };
    let mut sio = hal::Sio::new(pac.SIO);
    let mut syst = unsafe { cortex_m::Peripherals::steal() }.SYST;
    systick_start(&mut syst);
    loop {
        let job = sio.fifo.read_blocking();
        let first = sio.fifo.read_blocking();
        let (slot, split) = ((job & 1) as usize, (job >> 8) as usize);
        // SAFETY: core 0 does not write renderer `slot` until this core's answer below.
        let renderer = unsafe { &(*FRAMES.0.get())[slot] };
        let work = draw_rows(pass, renderer, split..board::SIZE, first, None);
        sio.fifo.write_blocking(work);
    }
}

/// The next frame's split from one frame's work times (core 0's geometry and top rows, core
/// 1's bottom rows): one strip towards the core that had less to do, when the difference is
/// more than an average strip's work.
fn balance(split: usize, work0: u32, work1: u32) -> usize {
    let strip = (work0 / 2 + work1 / 2) / (STRIPS / 2);
    let next = if work0 > work1.saturating_add(strip) {
        split - board::STRIP_LINES
    } else if work1 > work0.saturating_add(strip) {
        split + board::STRIP_LINES
    } else {
        split
    };
    next.clamp(SPLIT_MIN, SPLIT_MAX)
}

/// SPI1 with the panel's DC and CS lines: mipidsi's interface for the start-up commands
/// (blocking byte writes, 8-bit frames). Pixels go through the strip queue afterwards.
pub struct PanelBus {
    spi: Spi1,
    dc: DcPin,
    cs: CsPin,
}

impl PanelBus {
    /// After mipidsi's last command: data mode, 16-bit frames, ready for the strip queue
    /// (whose DMA interrupt sends each frame's `RAMWR` from then on).
    fn begin_pixels(&mut self) {
        let _ = self.spi.flush();
        let _ = self.dc.set_high();
        spi_drain();
        frame_bits(16);
    }
}

impl Interface for PanelBus {
    type Word = u8;
    type Error = Infallible;

    fn send_command(&mut self, command: u8, args: &[u8]) -> Result<(), Infallible> {
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
    // `.ram_code` (the chip's layout, memory-rp2040.x or memory-rp2350.x): its SRAM range and
    // its load address in flash.
    static mut __sram_code: u32;
    static mut __eram_code: u32;
    static __siram_code: u32;
}

/// Copies the renderer's code from flash to SRAM (`.ram_code` in the chip's layout), word by word with
/// volatile accesses (no call into code that is not there yet). Must run before anything
/// calls into that code: the HAL's clock set-up divides through the hardware-divider
/// helpers, which `.ram_code` holds, so this is `main`'s first statement.
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

#[entry]
fn main() -> ! {
    load_ram_code();
    let mut pac = pac::Peripherals::take().unwrap();
    let mut core = cortex_m::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = chip::clocks(
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    );
    let mut sio = hal::Sio::new(pac.SIO);
    let pins = gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut timer = chip::timer(&mut pac.RESETS, &clocks);
    // The DMA request number above is the HAL's.
    assert!(DREQ_SPI1_TX == <pac::SPI1 as hal::spi::SpiDevice>::tx_dreq());
    systick_start(&mut core.SYST);
    // The DMA block out of reset; channel DMA_CH's completion raises DMA_IRQ_0 (core 0).
    pac.RESETS.reset().modify(|_, w| w.dma().clear_bit());
    while pac.RESETS.reset_done().read().dma().bit_is_clear() {}
    // SAFETY: enables the channel's interrupt; the handler only touches the strip queue.
    unsafe {
        pac.DMA.inte0().write(|w| w.bits(1 << DMA_CH));
        cortex_m::peripheral::NVIC::unmask(pac::Interrupt::DMA_IRQ_0);
    }

    // SPI1: CLK GP10, MOSI GP11; CS GP9, DC GP8, RST GP12, backlight GP13 (off until the first
    // frame is on the panel).
    let clk: ClkPin = pins.gpio10.reconfigure();
    let mosi: MosiPin = pins.gpio11.reconfigure();
    let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, clk)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let mut backlight = pins.gpio13.into_push_pull_output();
    let _ = backlight.set_low();
    let mut cs: CsPin = pins.gpio9.into_push_pull_output();
    let _ = cs.set_high();
    let bus = PanelBus {
        spi,
        dc: pins.gpio8.into_push_pull_output(),
        cs,
    };
    let rst = pins.gpio12.into_push_pull_output();
    let mut display = Builder::new(ST7789, bus)
        .display_size(board::SIZE as u16, board::SIZE as u16)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut timer)
        .unwrap();

    // The DMA sends the strip buffers as 16-bit words: they must be RGB565 words.
    let probe = [Rgb565::new(31, 0, 1)];
    // SAFETY: reads the first two bytes of a one-element array.
    let word = unsafe { *(probe.as_ptr() as *const u16) };
    assert!(core::mem::size_of::<Rgb565>() == 2 && word == RawU16::from(probe[0]).into_inner());

    // The scene: the default torus, generated once into RAM (`SHAPE`, 18 KB, in place); the
    // renderers, strip passes and strip buffers are statics too.
    // The chip's start-up self-test (`chip::self_test_passes`): a failure stops the firmware
    // before its first frame, the LED blinking `Failure::SelfTest`.
    if !chip::self_test_passes() {
        blink(Failure::SelfTest);
    }
    // SAFETY: the only reference to SHAPE ever made mutable, before any shared one.
    let shape = unsafe { &mut *SHAPE.0.get() };
    demo::build_torus(shape).unwrap();
    let shape: &TorusShape<Q> = shape;
    let scene = board::BoardScene::new(shape).unwrap();
    let glyphs = board::glyphs().unwrap();

    // SAFETY: the renderers and passes are not used yet; core 1 gets its pass (and nothing
    // else of PASSES) below, and renderers only through the job protocol.
    let passes = unsafe { &mut *PASSES.0.get() };
    let (pass0, pass1) = passes.split_at_mut(1);
    let pass0 = &mut pass0[0];
    for slot in 0..CORES {
        // `board::renderer()`'s options, which the host's reference frames are drawn with.
        // SAFETY: core 1 is not running yet.
        unsafe { (*FRAMES.0.get())[slot].set_dither(true) };
    }
    if CORES == 2 {
        let mut mc = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
        let cores = mc.cores();
        // SAFETY: the stack is given to core 1 once, here.
        let stack = unsafe { &mut *CORE1_STACK.0.get() };
        chip::spawn_core1(&mut cores[1], stack, move || core1_main(&mut pass1[0]));
    }

    // The address window and RAMWR through mipidsi, then the SPI in 16-bit data mode for good.
    let last_pixel = board::SIZE as u16 - 1;
    let _ = display.set_pixels(0, 0, last_pixel, last_pixel, core::iter::empty());
    // SAFETY: only data is sent from now on; mipidsi is never called again.
    unsafe { display.dcs() }.begin_pixels();

    // The timer is read once per frame, before its geometry (the emulator check computes the
    // label each frame must show from these reads: frame K shows T_K − T_{K−1}).
    let mut last = timer.get_counter();
    let mut frame_us = 0u64;
    let mut frame = 0u32;
    // The first strip of the next frame drawn, in the stream.
    let mut first = 0u32;
    // The first frames' split: about where the balance settles for this torus (the QEMU
    // benchmark's best split, BENCHMARKS.md), so that they do not wait for it.
    let mut split = if CORES == 2 { 96 } else { board::SIZE };
    // Per renderer: core 1 has a job on it, and core 0's work on that frame.
    let mut busy = [false; 2];
    let mut work0 = [0u32; 2];
    let mut lit = false;
    loop {
        let label = board::fps_label(frame_us);
        let slot = if CORES == 2 { (frame & 1) as usize } else { 0 };
        if busy[slot] {
            // The frame drawn from this renderer two frames ago: core 1's answer frees it
            // and says how long its rows took.
            let work1 = sio.fifo.read_blocking();
            busy[slot] = false;
            split = balance(split, work0[slot], work1);
        }
        let t = SYST::get_current();
        // SAFETY: core 1 has no job on this renderer (see `busy`).
        let renderer = unsafe { &mut (*FRAMES.0.get())[slot] };
        // A frame that does not fit (it always does: the capacities hold for a full turn)
        // sends no strips: the previous image stays on the panel.
        if let Ok(prepared) = scene.prepare(renderer, frame) {
            let renderer: &Device = prepared.share();
            let mut work = since(t);
            if CORES == 2 {
                sio.fifo.write_blocking(slot as u32 | (split as u32) << 8);
                sio.fifo.write_blocking(first);
                busy[slot] = true;
            }
            work = work.wrapping_add(draw_rows(
                pass0,
                renderer,
                0..split,
                first,
                Some((&glyphs, &label)),
            ));
            work0[slot] = work;
            first = later(first, STRIPS);
        }
        if !lit && DONE.load(Ordering::Acquire) >= STRIPS {
            // The first frame is on the panel: the backlight comes on.
            let _ = backlight.set_high();
            lit = true;
        }
        let now = timer.get_counter();
        frame_us = (now - last).to_micros();
        last = now;
        frame = frame.wrapping_add(1);
    }
}
