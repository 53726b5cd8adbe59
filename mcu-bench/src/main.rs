//! Benchmark firmware: renders every benchmark scene with the fixed-point type and with f32 into
//! a line-hashing target and prints, over semihosting, exact instruction counts (QEMU with
//! `-icount shift=7`: every instruction advances the virtual clock by 128 ns, so a board timer
//! counts instructions), per-stage counts, the image hash, and memory figures. On RISC-V (QEMU
//! `virt` and `sifive_e`, machine mode) the count is the `minstret` CSR read directly, QEMU run
//! with `-icount shift=0`.
//!
//! Output lines (parsed by `tools/src/bin/mcu_report.rs`):
//! `BENCH scene=.. number=.. instructions=.. vertices=.. lighting=.. triangles=.. setup=..
//!  raster=.. output=.. hash=.. pixels=.. renderer_ram=.. drawn=..`, then
//! `SPLIT frame=.. split=.. geometry=.. top=.. bottom=..` (the Pico firmware's frame
//! split between two cores at each strip boundary, `demo::board::split_frame`),
//! `MEM static=.. stack=.. flash=..` and `DONE`.
#![no_std]
#![no_main]

use core::panic::PanicInfo;

#[cfg(target_arch = "arm")]
use cortex_m_rt::entry;
#[cfg(target_arch = "arm")]
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics_core::pixelcolor::Rgb565;
#[cfg(target_arch = "riscv32")]
use riscv_rt::entry;
#[cfg(target_arch = "riscv32")]
use riscv_semihosting::{debug, hprintln};
use scanline3d::fixed::types::I16F16;
use scanline3d::{probe::Probe, probe::Stage, Fx, Scalar};
use scanline3d_support::demo::{render_bench, Bench};
// The 16 KB parts run the cube scenes only: their build compiles only those scenes' renderers
// (`render_bench_cube`), not every scene's.
#[cfg(small_part)]
use scanline3d_support::demo::render_bench_cube as render_scene;
#[cfg(not(small_part))]
use scanline3d_support::demo::render_bench as render_scene;
use scanline3d_support::hash::{HashTarget, NullTarget};

#[cfg(all(target_arch = "arm", not(feature = "microbit")))]
mod timer {
    //! CMSDK APB TIMER0 of the mps2 boards: a 32-bit down-counter at the board's clock
    //! (mps2-an385/an386: 25 MHz; mps2-an505: the IoTKit's, at 20 MHz).
    #[cfg(not(feature = "an505"))]
    const BASE: usize = 0x4000_0000;
    /// The IoTKit's TIMER0 through its secure alias (0x4000_0000 non-secure): the core runs
    /// secure.
    #[cfg(feature = "an505")]
    const BASE: usize = 0x5000_0000;
    pub fn start() {
        // SAFETY: MMIO registers of the emulated board's timer, used by nothing else.
        unsafe {
            core::ptr::write_volatile((BASE + 0x8) as *mut u32, u32::MAX); // RELOAD
            core::ptr::write_volatile((BASE + 0x4) as *mut u32, u32::MAX); // VALUE
            core::ptr::write_volatile(BASE as *mut u32, 1); // CTRL: enable
        }
    }
    /// Ticks since start (counting up).
    #[inline(always)]
    pub fn now() -> u32 {
        // SAFETY: reading the timer's VALUE register.
        u32::MAX - unsafe { core::ptr::read_volatile((BASE + 0x4) as *const u32) }
    }
    /// Instructions in `ticks`: 25 MHz ticks of 40 ns, 128 ns per instruction.
    #[cfg(not(feature = "an505"))]
    pub fn instructions(ticks: u64) -> u64 {
        (ticks * 5 + 8) / 16
    }
    /// Instructions in `ticks`: 20 MHz ticks of 50 ns, 128 ns per instruction.
    #[cfg(feature = "an505")]
    pub fn instructions(ticks: u64) -> u64 {
        (ticks * 25 + 32) / 64
    }
}

#[cfg(all(target_arch = "arm", feature = "microbit"))]
mod timer {
    //! nRF51 TIMER0: 32-bit timer at 16 MHz, read by a capture task.
    const BASE: usize = 0x4000_8000;
    pub fn start() {
        // SAFETY: MMIO registers of the emulated board's timer, used by nothing else.
        unsafe {
            core::ptr::write_volatile((BASE + 0x504) as *mut u32, 0); // MODE: timer
            core::ptr::write_volatile((BASE + 0x508) as *mut u32, 3); // BITMODE: 32 bit
            core::ptr::write_volatile((BASE + 0x510) as *mut u32, 0); // PRESCALER: 16 MHz
            core::ptr::write_volatile((BASE + 0x00C) as *mut u32, 1); // TASKS_CLEAR
            core::ptr::write_volatile(BASE as *mut u32, 1); // TASKS_START (+0x000)
        }
    }
    #[inline(always)]
    pub fn now() -> u32 {
        // SAFETY: trigger CAPTURE[0], read CC[0].
        unsafe {
            core::ptr::write_volatile((BASE + 0x040) as *mut u32, 1);
            core::ptr::read_volatile((BASE + 0x540) as *const u32)
        }
    }
    /// Instructions in `ticks`: 16 MHz ticks of 62.5 ns, 128 ns per instruction.
    pub fn instructions(ticks: u64) -> u64 {
        (ticks * 125 + 128) / 256
    }
}

#[cfg(target_arch = "riscv32")]
mod timer {
    //! The hart's `minstret` CSR (machine mode): instructions retired. In QEMU it reads the
    //! virtual clock, which with `-icount shift=0,align=off,sleep=off` advances exactly 1 ns per
    //! instruction executed: the count is exact and the same on every run (without `-icount`
    //! QEMU returns host time instead, and the script always passes it). The low 32 bits: one
    //! frame stays far below 2^32 instructions.
    pub fn start() {}
    #[inline(always)]
    pub fn now() -> u32 {
        riscv::register::minstret::read() as u32
    }
    /// Instructions in `ticks`: one tick per instruction.
    pub fn instructions(ticks: u64) -> u64 {
        ticks
    }
    /// What `minstret` counts from one read to the next across a known run: 32 full-size
    /// `nop`s and 32 compressed ones, then the second read (the first read's own retirement
    /// falls before its value). The firmware stops unless it is exactly
    /// [`CALIBRATION_EXPECTED`]: a counter that is not one per executed instruction (QEMU run
    /// without `-icount`, where it reads host time) fails the run instead of giving figures.
    #[inline(never)]
    pub fn calibration() -> u32 {
        let (a, b): (u32, u32);
        // SAFETY: reads a CSR twice around no-op instructions; no memory or stack is touched.
        unsafe {
            core::arch::asm!(
                "csrr {a}, minstret",
                ".rept 32",
                "nop",
                "c.nop",
                ".endr",
                "csrr {b}, minstret",
                a = out(reg) a,
                b = out(reg) b,
                options(nomem, nostack),
            )
        };
        b.wrapping_sub(a)
    }
    /// The instructions between the two reads of [`calibration`] and the second read.
    pub const CALIBRATION_EXPECTED: u32 = 65;
}

/// A no-op instruction, for the trace markers.
#[inline(always)]
fn nop() {
    #[cfg(target_arch = "arm")]
    cortex_m::asm::nop();
    #[cfg(target_arch = "riscv32")]
    riscv::asm::nop();
}

/// The current stack pointer.
#[inline(always)]
fn stack_pointer() -> usize {
    #[cfg(target_arch = "arm")]
    return cortex_m::register::msp::read() as usize;
    #[cfg(target_arch = "riscv32")]
    {
        let sp: usize;
        // SAFETY: copies the stack pointer into a register; no memory is touched.
        unsafe { core::arch::asm!("mv {}, sp", out(reg) sp, options(nomem, nostack)) };
        sp
    }
}

/// Times exactly one `render` call (mesh generation and renderer construction excluded).
struct FrameTimer {
    start: u32,
    ticks: u32,
}

impl Probe for FrameTimer {
    // Keeps the default `snap`.
    const SNAPS: bool = false;
    #[inline(always)]
    fn enter(&mut self, _: Stage) {}
    #[inline(always)]
    fn frame_start(&mut self) {
        self.start = timer::now();
    }
    #[inline(always)]
    fn frame_end(&mut self) {
        self.ticks = timer::now().wrapping_sub(self.start);
    }
}

/// Calls two never-inlined marker functions around the frame, so that an instruction trace can
/// be cut to exactly one `render` call.
struct Markers;

#[inline(never)]
fn frame_start_marker() {
    nop();
}

#[inline(never)]
fn frame_end_marker() {
    // Different from the start marker, so the two are never merged.
    nop();
    nop();
}

impl Probe for Markers {
    // Keeps the default `snap`.
    const SNAPS: bool = false;
    #[inline(always)]
    fn enter(&mut self, _: Stage) {}
    fn frame_start(&mut self) {
        frame_start_marker();
    }
    fn frame_end(&mut self) {
        frame_end_marker();
    }
}

/// Accumulates timer ticks per stage.
struct StageProbe {
    last: u32,
    current: Option<Stage>,
    ticks: [u64; 7],
}

fn stage_index(s: Stage) -> usize {
    match s {
        Stage::Vertices => 0,
        Stage::Lighting => 1,
        Stage::Triangles => 2,
        Stage::Setup => 3,
        Stage::Raster => 4,
        Stage::Output => 5,
        _ => 6,
    }
}

impl Probe for StageProbe {
    // Keeps the default `snap`.
    const SNAPS: bool = false;
    #[inline(never)]
    fn enter(&mut self, stage: Stage) {
        let now = timer::now();
        if let Some(c) = self.current {
            self.ticks[stage_index(c)] += now.wrapping_sub(self.last) as u64;
        }
        self.current = Some(stage);
        self.last = timer::now();
    }
}

const PAINT: u32 = 0x5ca1_ab1e;

extern "C" {
    /// The start of flash: the vector table on Cortex-M, the start of .text (riscv-rt's
    /// `_start` first) on RISC-V.
    #[cfg(target_arch = "arm")]
    static __vector_table: u32;
    #[cfg(target_arch = "riscv32")]
    #[link_name = "__stext"]
    static __vector_table: u32;
    static mut __sheap: u32;
    static _stack_start: u32;
    static mut __sdata: u32;
    static mut __edata: u32;
    static mut __sbss: u32;
    static mut __ebss: u32;
    static __sidata: u32;
}

/// Fills the free RAM between the end of .bss and the current stack pointer with a pattern.
fn paint_stack() {
    let sp = stack_pointer();
    // SAFETY: the words between the end of .bss (`__sheap`) and 64 bytes below the live stack
    // pointer are unused: there is no heap, and the stack grows down toward them.
    unsafe {
        let mut p = core::ptr::addr_of_mut!(__sheap) as usize;
        while p + 64 < sp {
            core::ptr::write_volatile(p as *mut u32, PAINT);
            p += 4;
        }
    }
}

/// Bytes of stack ever used: from the top of RAM down to the lowest word no longer painted.
fn stack_high_water() -> usize {
    // SAFETY: reads the painted region, see `paint_stack`.
    unsafe {
        let top = core::ptr::addr_of!(_stack_start) as usize;
        let mut p = core::ptr::addr_of_mut!(__sheap) as usize;
        while p < top && core::ptr::read_volatile(p as *const u32) == PAINT {
            p += 4;
        }
        top - p
    }
}

/// Bytes of RAM: from its start (`__sdata`) to the initial stack pointer (its end).
#[cfg_attr(not(small_part), allow(dead_code))]
fn ram_size() -> usize {
    // Only the addresses of linker symbols are taken.
    core::ptr::addr_of!(_stack_start) as usize - core::ptr::addr_of!(__sdata) as usize
}

fn static_ram() -> usize {
    // Only the addresses of linker symbols are taken.
    let a = |p: *const u32| p as usize;
    (a(core::ptr::addr_of!(__edata)) - a(core::ptr::addr_of!(__sdata)))
        + (a(core::ptr::addr_of!(__ebss)) - a(core::ptr::addr_of!(__sbss)))
}

fn flash_used() -> usize {
    // Flash holds vectors, .text and .rodata from the vector table (the start of flash: 0, or
    // 0x1000_0000 on mps2-an505) up to __sidata, then the initial values of .data.
    let data = core::ptr::addr_of!(__edata) as usize - core::ptr::addr_of!(__sdata) as usize;
    core::ptr::addr_of!(__sidata) as usize - core::ptr::addr_of!(__vector_table) as usize + data
}

#[cfg(all(feature = "profile-torus", not(feature = "profile-phong-fast")))]
const SCENES: &[Bench] = &[Bench::Torus];
#[cfg(feature = "profile-phong-fast")]
const SCENES: &[Bench] = &[Bench::PhongFast];
#[cfg(all(not(small_part), not(feature = "profile-torus")))]
const SCENES: &[Bench] = &Bench::ALL;
#[cfg(small_part)]
const SCENES: &[Bench] = &[Bench::Cube];

/// The torus mesh in flash (generated by build.rs from the library's torus, bit-identical).
#[cfg(small_part)]
mod flash_torus {
    use scanline3d::fixed::types::I16F16;
    use scanline3d::Fx;
    include!(concat!(env!("OUT_DIR"), "/torus_mesh.rs"));
}

/// Side of the square frame the torus is rendered at on the 16 KB part: the largest multiple
/// of 8 pixels that fits (the firmware prints what the next size would need).
#[cfg(small_part)]
pub const MICROBIT_TORUS_SIZE: usize = scanline3d_support::demo::SMALL_PART_TORUS.0;
/// Triangle and active capacities of that renderer: what the frame needs.
#[cfg(small_part)]
const MICROBIT_CAPACITY: (usize, usize) = (
    scanline3d_support::demo::SMALL_PART_TORUS.1,
    scanline3d_support::demo::SMALL_PART_TORUS.2,
);

/// The default torus frame at `W × W` on the 16 KB part, from the flash mesh.
#[cfg(small_part)]
#[inline(never)]
fn torus_sized<const W: usize>() {
    use scanline3d_support::demo::render_torus_sized;
    const T: usize = MICROBIT_CAPACITY.0;
    const A: usize = MICROBIT_CAPACITY.1;
    let mesh = match scanline3d::Mesh::new(&flash_torus::POSITIONS, &flash_torus::INDICES)
        .and_then(|m| m.with_normals(&flash_torus::NORMALS))
    {
        Ok(m) => m,
        Err(e) => {
            hprintln!("ERROR torus mesh {:?}", e);
            return;
        }
    };
    let mut target = HashTarget::<Rgb565>::new(W as u32, W as u32);
    let mut ft = FrameTimer { start: 0, ticks: 0 };
    let r = render_torus_sized::<Fx<I16F16>, Rgb565, _, _, W, T, A>(mesh, &mut target, &mut ft);
    match r {
        Ok(f) => report_sized(
            W,
            ft.ticks as u64,
            target.hash(),
            f.renderer_ram_bytes,
            f.stats.drawn,
            f.stats.pixels_written,
        ),
        Err(e) => hprintln!("ERROR torus size={} {}", W, bench_error(&e)),
    }
}

/// The `SIZED` line of [`torus_sized`]. Out of line: the formatting's arguments stay off the
/// 16 KB part's deepest frame (the renderer's).
#[cfg(small_part)]
#[inline(never)]
fn report_sized(w: usize, ticks: u64, hash: u64, ram: usize, drawn: u32, written: u32) {
    hprintln!(
        "SIZED scene=torus number=I16F16 size={} instructions={} hash={:016x} renderer_ram={} drawn={} written={}",
        w,
        timer::instructions(ticks),
        hash,
        ram,
        drawn,
        written
    );
}

/// One benchmark scene, dithering on or off (`DITHER`, a constant as it is in firmware that
/// never changes it): with dithering the line's scene name gets the suffix `_dithered`
/// (`tools/src/bin/mcu_report.rs` renders the host's frame the same way).
// Not inlined: inlined into `main` (as LLVM chose once), its 5 KB frame stayed under the
// 16 KB part's largest frame (`torus_sized`) and overflowed its RAM.
#[inline(never)]
fn bench<S: Scalar, const DITHER: bool>(scene: Bench) {
    let dither = DITHER;
    // The renderer alone: one `render` call into a target that does nothing.
    let mut null = NullTarget::<Rgb565>::new(240, 240);
    let mut ft = FrameTimer { start: 0, ticks: 0 };
    let r = render_scene::<S, Rgb565, _, _>(scene, 0.0, dither, &mut null, &mut ft);
    let ticks = ft.ticks as u64;
    let suffix = if dither { "_dithered" } else { "" };
    let frame = match r {
        Ok(f) => f,
        Err(e) => {
            hprintln!(
                "ERROR scene={} number={} {}",
                scene.name(),
                S::NAME,
                bench_error(&e)
            );
            return;
        }
    };
    // Per stage, with the probe (its own cost lands in the stages), and the image hash: one
    // run for both. A probe that keeps the default `snap` cannot change a pixel, and the hash
    // is compared with the host's frame (drawn without a probe) by `mcu_report`. One run
    // rather than a hash run without the probe and a probed one: each (target, probe) pair is
    // a copy of every scene's renderer in the firmware, which the firmware build compiles and
    // optimizes as one unit (see CHANGELOG for the build times).
    let mut probe = StageProbe {
        last: 0,
        current: None,
        ticks: [0; 7],
    };
    let mut target = HashTarget::<Rgb565>::new(240, 240);
    let _ = render_scene::<S, Rgb565, _, _>(scene, 0.0, dither, &mut target, &mut probe);
    let i = |k: usize| timer::instructions(probe.ticks[k]);
    hprintln!(
        "BENCH scene={}{} number={} instructions={} vertices={} lighting={} triangles={} setup={} raster={} output={} hash={:016x} pixels={} renderer_ram={} drawn={} written={}",
        scene.name(),
        suffix,
        S::NAME,
        timer::instructions(ticks),
        i(0),
        i(1),
        i(2),
        i(3),
        i(4),
        i(5),
        target.hash(),
        target.pixels(),
        frame.renderer_ram_bytes,
        frame.stats.drawn,
        frame.stats.pixels_written
    );
}

/// The torus frame (I16F16) with a strip of `LINES` lines: its renderer instructions, RAM and
/// hash (`scripts/mcu-bench` checks that the hash equals the one-line frame's).
#[cfg(not(any(small_part, feature = "profile-torus")))]
fn strip_bench<const LINES: usize>() {
    use scanline3d_support::demo::render_torus_strip;
    let mut null = NullTarget::<Rgb565>::new(240, 240);
    let mut ft = FrameTimer { start: 0, ticks: 0 };
    let r = render_torus_strip::<Fx<I16F16>, Rgb565, _, _, LINES>(0.0, false, &mut null, &mut ft);
    let mut target = HashTarget::<Rgb565>::new(240, 240);
    let _ = render_torus_strip::<Fx<I16F16>, Rgb565, _, _, LINES>(
        0.0,
        false,
        &mut target,
        &mut scanline3d::probe::NoProbe,
    );
    match r {
        Ok(f) => hprintln!(
            "STRIP scene=torus number={} lines={} instructions={} renderer_ram={} hash={:016x}",
            <Fx<I16F16> as Scalar>::NAME,
            LINES,
            timer::instructions(ft.ticks as u64),
            f.renderer_ram_bytes,
            target.hash()
        ),
        Err(e) => hprintln!("ERROR strip lines={} {}", LINES, bench_error(&e)),
    }
}

/// A renderer error's name, printed without its fields: a camera error holds `f64` values,
/// and formatting one would link the `f64` formatter (about 8 KB), for which the 16 KB part's
/// 256 KB of flash has no room. (A capacity shortfall's figures are in the renderer's
/// `Stats`; the host's `render --budget` prints them.)
fn render_error<E>(e: &scanline3d::Error<E>) -> &'static str {
    match e {
        scanline3d::Error::Target(_) => "target",
        scanline3d::Error::Shortfall(_) => "capacity shortfall",
        scanline3d::Error::MissingNormals { .. } => "missing normals",
        scanline3d::Error::Camera(_) => "camera",
        scanline3d::Error::TargetTooSmall { .. } => "target too small",
        _ => "other",
    }
}

/// [`render_error`] of a benchmark's error.
fn bench_error<E>(e: &scanline3d_support::demo::BenchError<E>) -> &'static str {
    match e {
        scanline3d_support::demo::BenchError::Render(e) => render_error(e),
        _ => "scene",
    }
}

/// The Pico firmware's frame `frame` (`demo::board`: the dithered torus, 8-line strips) split
/// between two cores at every strip boundary: the instructions of the shared geometry, of the
/// rows above the split (the first core's strip pass) and of the rows below (the second
/// core's, begun at the split), run one after the other here (`demo::board::split_frame`; the
/// host tests check that a frame split by two strip passes is the whole frame bit for bit).
#[cfg(not(any(small_part, feature = "profile-torus")))]
fn split_bench(frame: u32) {
    use embedded_graphics_core::pixelcolor::RgbColor;
    use scanline3d_support::demo::board::{self, SplitPart};
    let Ok(shape) = scanline3d_support::demo::torus::<Fx<I16F16>>() else {
        hprintln!("ERROR split: torus");
        return;
    };
    let Ok(scene) = board::BoardScene::new(&shape) else {
        hprintln!("ERROR split: scene");
        return;
    };
    let mut renderer = board::renderer::<Fx<I16F16>>();
    let mut buffer = [[Rgb565::BLACK; board::SIZE]; board::STRIP_LINES];
    // The two cores' passes (on the stack here: 4 MB of RAM).
    let (mut top, mut bottom) = (board::BoardPass::new(), board::BoardPass::new());
    for split in (0..=board::SIZE).step_by(board::STRIP_LINES) {
        let mut marks = [0u32; 3];
        let start = timer::now();
        let r = board::split_frame(
            &scene,
            &mut renderer,
            [&mut top, &mut bottom],
            frame,
            split,
            &mut buffer,
            |p| {
                let i = match p {
                    SplitPart::Geometry => 0,
                    SplitPart::Top => 1,
                    SplitPart::Bottom => 2,
                };
                marks[i] = timer::now();
            },
        );
        let ins = |a: u32, b: u32| timer::instructions(b.wrapping_sub(a) as u64);
        match r {
            Ok(_) => hprintln!(
                "SPLIT frame={} split={} geometry={} top={} bottom={}",
                frame,
                split,
                ins(start, marks[0]),
                ins(marks[0], marks[1]),
                ins(marks[1], marks[2])
            ),
            Err(e) => hprintln!(
                "ERROR split frame={} split={} {}",
                frame,
                split,
                render_error(&e)
            ),
        }
    }
}

#[entry]
fn main() -> ! {
    if !cfg!(feature = "profile-torus") {
        paint_stack();
    }
    if !cfg!(feature = "profile-torus") && !transform_matches_rows() {
        debug::exit(debug::EXIT_FAILURE);
    }
    if !cfg!(feature = "profile-torus") && !assembly_matches_portable() {
        debug::exit(debug::EXIT_FAILURE);
    }
    #[cfg(target_arch = "riscv32")]
    {
        let counted = timer::calibration();
        if counted != timer::CALIBRATION_EXPECTED {
            hprintln!(
                "ERROR minstret counted {} over a run of {} instructions: not an exact instruction counter (QEMU needs -icount)",
                counted,
                timer::CALIBRATION_EXPECTED
            );
            debug::exit(debug::EXIT_FAILURE);
        }
    }
    timer::start();
    for &scene in SCENES {
        if cfg!(feature = "profile-torus") {
            let mut null = NullTarget::<Rgb565>::new(240, 240);
            let _ = render_bench::<Fx<I16F16>, Rgb565, _, _>(
                scene,
                0.0,
                false,
                &mut null,
                &mut Markers,
            );
            continue;
        }
        bench::<Fx<I16F16>, false>(scene);
        bench::<f32, false>(scene);
    }
    // The default torus with 4×4 ordered dithering (as the Pico firmware renders it).
    #[cfg(not(any(small_part, feature = "profile-torus")))]
    bench::<Fx<I16F16>, true>(Bench::Torus);
    #[cfg(not(any(small_part, feature = "profile-torus")))]
    strip_bench::<8>();
    #[cfg(not(any(small_part, feature = "profile-torus")))]
    for frame in [0, 15] {
        split_bench(frame);
    }
    #[cfg(small_part)]
    {
        torus_sized::<MICROBIT_TORUS_SIZE>();
        // What the next size (8 px more) would need, from the measured stack use.
        const NEXT: usize = MICROBIT_TORUS_SIZE + 8;
        let this = core::mem::size_of::<
            scanline3d::Renderer<
                Fx<I16F16>,
                Rgb565,
                MICROBIT_TORUS_SIZE,
                MICROBIT_TORUS_SIZE,
                512,
                { MICROBIT_CAPACITY.0 },
                { MICROBIT_CAPACITY.1 },
            >,
        >();
        let next = core::mem::size_of::<
            scanline3d::Renderer<
                Fx<I16F16>,
                Rgb565,
                NEXT,
                NEXT,
                512,
                { MICROBIT_CAPACITY.0 },
                { MICROBIT_CAPACITY.1 },
            >,
        >();
        hprintln!(
            "FIT size={} stack={} next_size={} next_stack={} ram={}",
            MICROBIT_TORUS_SIZE,
            stack_high_water(),
            NEXT,
            stack_high_water() - this + next,
            ram_size()
        );
    }
    hprintln!(
        "MEM static={} stack={} flash={}",
        static_ram(),
        stack_high_water(),
        flash_used()
    );
    hprintln!("DONE");
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        nop();
    }
}

/// The point and direction transforms (the Q16.16 transform kernel where it runs) give exactly
/// `dot3_add` of each row on 4096 pseudo-random cases (`selftest::transform_self_test`).
/// Prints the first mismatch. Not inlined, so that its locals are not part of `main`'s frame
/// during the renders.
#[inline(never)]
fn transform_matches_rows() -> bool {
    if let Some(case) = scanline3d::selftest::transform_self_test(4096) {
        hprintln!("TRANSFORM MISMATCH case={}", case);
        return false;
    }
    true
}

/// Every kernel against its portable twin (`scanline3d::selftest`): the plain and flat span
/// kernels and the line clear on 20 000 pseudo-random spans, the row kernel without dithering
/// on 2 000 strips; the assembly edge setup gives the portable one's edges on 20 000
/// pseudo-random edges, the
/// assembly projection the portable one's screen words on 20 000 pseudo-random points, and the
/// assembly Gouraud setup the portable attribute words on 20 000 pseudo-random triangles, and
/// the assembly dithered span the portable one on 20 000 pseudo-random spans and the
/// dithered row routine the portable rows on 2 000 strips of four triangles, and
/// the assembly triangle loop the portable one on 5 000 objects of 24 triangles, the assembly
/// vertex loop and lighting run the portable ones on 5 000 objects each, the assembly
/// triangle setup the portable one on 20 000 more and the assembly dither check the portable
/// one on 20 000 fast triangles (the
/// benchmark scenes' hashes check them too, but only on the cases they have). Prints the first
/// mismatch. Not inlined, so that its locals are not part of `main`'s frame during the
/// renders (on the 16 KB part every byte of it counts).
#[inline(never)]
fn assembly_matches_portable() -> bool {
    if let Some(e) = scanline3d::selftest::span_self_test(20_000) {
        hprintln!("SPAN MISMATCH {:?}", e);
        return false;
    }
    if let Some(case) = scanline3d::selftest::rows_self_test(2_000) {
        hprintln!("ROWS MISMATCH case {}", case);
        return false;
    }
    if let Some(e) = scanline3d::selftest::edge_setup_self_test(20_000) {
        hprintln!("EDGE MISMATCH {:?}", e);
        return false;
    }
    if let Some(e) = scanline3d::selftest::projection_self_test(20_000) {
        hprintln!("PROJECTION MISMATCH {:?}", e);
        return false;
    }
    if let Some(e) = scanline3d::selftest::gouraud_setup_self_test(20_000) {
        hprintln!("SETUP MISMATCH {:?}", e);
        return false;
    }
    if let Some(e) = scanline3d::selftest::triangle_setup_self_test(20_000) {
        hprintln!("TRIANGLE SETUP MISMATCH {:?}", e);
        return false;
    }
    if let Some(e) = scanline3d::selftest::dither_fits_self_test(20_000) {
        hprintln!("DITHER CHECK MISMATCH {:?}", e);
        return false;
    }
    if let Some(e) = scanline3d::selftest::dither_span_self_test(20_000) {
        hprintln!("DITHERED SPAN MISMATCH {:?}", e);
        return false;
    }
    if let Some(case) = scanline3d::selftest::dither_rows_self_test(2_000) {
        hprintln!("DITHERED ROWS MISMATCH case {}", case);
        return false;
    }
    if let Some(seed) = scanline3d::selftest::cull_self_test(5_000) {
        hprintln!("TRIANGLE LOOP MISMATCH seed {:#x}", seed);
        return false;
    }
    if let Some(seed) = scanline3d::selftest::vertex_self_test(5_000) {
        hprintln!("VERTEX LOOP MISMATCH seed {:#x}", seed);
        return false;
    }
    if let Some(seed) = scanline3d::selftest::light_self_test(5_000) {
        hprintln!("LIGHTING MISMATCH seed {:#x}", seed);
        return false;
    }
    true
}

/// A fault (on the 16 KB part: the stack running out of RAM) ends the run with a failure
/// instead of hanging.
#[cfg(target_arch = "arm")]
#[cortex_m_rt::exception]
unsafe fn HardFault(_frame: &cortex_m_rt::ExceptionFrame) -> ! {
    hprintln!("HARDFAULT");
    debug::exit(debug::EXIT_FAILURE);
    loop {
        nop();
    }
}

/// The same on RISC-V: any exception (an access fault when the 16 KB part's stack runs below
/// its RAM, an illegal instruction) prints its cause and address and ends the run.
#[cfg(target_arch = "riscv32")]
#[export_name = "ExceptionHandler"]
fn exception_handler(_frame: &riscv_rt::TrapFrame) -> ! {
    hprintln!(
        "HARDFAULT mcause={:#x} mepc={:#x} mtval={:#x}",
        riscv::register::mcause::read().bits(),
        riscv::register::mepc::read(),
        riscv::register::mtval::read()
    );
    debug::exit(debug::EXIT_FAILURE);
    loop {
        nop();
    }
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    hprintln!("PANIC {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        nop();
    }
}
