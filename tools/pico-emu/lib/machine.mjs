// The emulated Raspberry Pi Pico: rp2040js 1.4.1's RP2040 with the harness's patches, a second
// core (lib/cores.mjs, lib/sio.mjs), a deterministic stepping loop driven by the cores' cycle
// counts, and a cycle-timed SPI1 whose bytes (with the DC and CS pin levels) go to a callback.
//
// Time: one clock, rp2040js's SimulationClock, advanced by the harness only, by 8 ns per core
// cycle (clk_sys = 125 MHz, the firmware's PLL setting). Everything that rp2040js schedules (DMA
// transfers, timer alarms, the watchdog tick) and everything the harness schedules (SPI shifting)
// runs from that clock, so a run is exactly repeatable: no wall-clock time is read anywhere.
//
// Two cores: each has its own time (the cycle its next instruction starts at). The loop always
// steps the running core whose time is lower (core 0 on a tie), one whole instruction, then
// moves the clock to the lower time of the running cores. So every instruction executes with
// the clock at its own start cycle, as in the one-core loop, and peripherals see the two cores'
// accesses in time order. A sleeping (WFE/WFI) or reset core is not stepped and does not hold the
// clock back; when it wakes, its time moves up to the clock. With core 1 asleep or in reset this
// is exactly the one-core loop: one instruction of core 0, then the clock moves by its cycles.
//
// What each patch of rp2040js does, and why, is said where it is made (patch* functions below).
// rp2040js itself is not modified on disk: the objects are patched after construction.

import { RP2040, GPIOPinState, BasePeripheral } from 'rp2040js';
import { HarnessError } from './errors.mjs';
import { installCores, noteWait, hasRp2040RomHeader } from './cores.mjs';

export { HarnessError };

/** clk_sys: the firmware sets the PLLs to 125 MHz (rp2040-hal init_clocks_and_plls). */
export const CLOCK_HZ = 125_000_000;
/** Nanoseconds per core cycle at 125 MHz (exact). */
export const NS_PER_CYCLE = 8;
/** Core cycles per microsecond: the TIMER counts one per 125 cycles. */
export const CYCLES_PER_US = 125;

export const FLASH_BASE = 0x1000_0000;
export const FLASH_SIZE = 16 * 1024 * 1024; // rp2040js's flash array (the Pico has 2 MiB)

// DMA request numbers (RP2040 datasheet 2.5.3.1).
const DREQ_SPI_TX = [16, 18];
const DREQ_SPI_RX = [17, 19];

// SPI (PL022) register offsets and bits.
const SSPCR0 = 0x000;
const SSPCR1 = 0x004;
const SSPCPSR = 0x010;
const SSPDMACR = 0x024;
const SSE = 1 << 1;
const TXDMAE = 1 << 1;
const RXDMAE = 1 << 0;

// DMA register offsets.
const DMA_CHAN_ABORT = 0x444;

// TIMER register offsets.
const TIMEHR = 0x08;
const TIMELR = 0x0c;
const ALARM0 = 0x10;
const ALARM3 = 0x1c;
const TIMERAWH = 0x24;
const TIMERAWL = 0x28;

/**
 * A block of plain read/write registers, for peripherals rp2040js leaves unimplemented (an
 * unimplemented one reads 0xffffffff, which the boot ROM misreads).
 */
class RegisterBlock extends BasePeripheral {
  constructor(rp2040, name, resetValues = {}) {
    super(rp2040, name);
    this.regs = new Map(Object.entries(resetValues).map(([k, v]) => [Number(k), v >>> 0]));
  }
  readUint32(offset) {
    return this.regs.get(offset) ?? 0;
  }
  writeUint32(offset, value) {
    this.regs.set(offset, value >>> 0);
  }
}

/**
 * Collects rp2040js's log messages instead of printing each (the firmware touches a few
 * unimplemented registers thousands of times). Messages that mean the program did something the
 * chip would fault on are failures: a read or write outside every memory region (a bus fault, a
 * HardFault on the chip), an instruction rp2040js does not implement, and rp2040js's own errors.
 */
class HarnessLogger {
  constructor() {
    this.counts = new Map();
    this.onFatal = (msg) => {
      throw new HarnessError(msg);
    };
    /** Called when a core executes SEV (rp2040js only logs it). */
    this.onSev = () => {};
  }
  note(level, component, message) {
    // Group messages that differ only in their numbers.
    const key = `${level} [${component}] ${message.replace(/0x[0-9a-f]+|\b[0-9a-f]{5,}\b/gi, 'N')}`;
    const entry = this.counts.get(key);
    if (entry) entry.count++;
    else this.counts.set(key, { count: 1, first: `[${component}] ${message}` });
  }
  debug() {}
  info(component, message) {
    if (message === 'SEV' && component === 'CortexM0Core') this.onSev();
    this.note('info', component, message);
  }
  warn(component, message) {
    if (
      /Read from invalid memory address|Write to undefined address/.test(message) ||
      /is not implemented yet|Opcode:/.test(message)
    ) {
      this.onFatal(`[${component}] ${message}`);
    }
    this.note('warn', component, message);
  }
  error(component, message) {
    this.note('error', component, message);
    this.onFatal(`[${component}] ${message}`);
  }
  summary() {
    return [...this.counts.entries()]
      .sort((a, b) => b[1].count - a[1].count)
      .map(([, v]) => `${v.count} x ${v.first}`);
  }
}

/** The level a pin drives: true high, false low, null when it is not an output. */
function driven(pin) {
  const v = pin.value;
  if (v === GPIOPinState.High) return true;
  if (v === GPIOPinState.Low) return false;
  return null;
}

export class Machine {
  /**
   * @param {object} o
   * @param {Uint32Array} o.bootrom the RP2040 B1 boot ROM, 4096 words
   * @param {{segments:Array}} o.elf parsed firmware (lib/elf.mjs)
   * @param {number} [o.spi] SPI block the display is on (1)
   * @param {{dc:number, cs:number, rst:number}} [o.pins] display pins (GP8, GP9, GP12)
   * @param {(value:number, dc:boolean, start:number, end:number)=>void} o.onByte
   *        each byte the display receives (CS low, RST high), with its start and end cycle
   * @param {()=>void} [o.onDisplayReset] the display's RST pin went low
   * @param {boolean} [o.core1Boot] core 1 leaves reset with core 0 and runs the boot ROM's reset
   *        handler, which parks it in the ROM's launch wait loop. Default: when `bootrom` is the
   *        RP2040's (its header at 0x10); a stand-in ROM (the unit tests') keeps core 1 in reset
   *        until the firmware cycles PSM FRCE_OFF.PROC1, as Multicore::spawn does.
   */
  constructor(o) {
    this.rp2040 = new RP2040();
    this.clock = this.rp2040.clock;
    this.logger = new HarnessLogger();
    this.rp2040.logger = this.logger;
    this.spiIndex = o.spi ?? 1;
    this.pins = o.pins ?? { dc: 8, cs: 9, rst: 12 };
    this.onByte = o.onByte;
    this.onDisplayReset = o.onDisplayReset ?? (() => {});
    this.stats = {
      spiBytes: 0, // bytes shifted out on the display's SPI
      spiBusyCycles: 0, // cycles the display's SPI spent shifting
      bytesIgnored: 0, // shifted while CS was high or RST low
      spiCyclesPerBit: null, // from the SPI's clock registers
      spiFrameBits: new Set(),
      timerReads: 0,
    };
    /** The last value the firmware read from the timer's low word, when, and on which core. */
    this.lastTimerRead = null;
    /** When an array: every timer read from then on is appended to it ({cycle, value, core}). */
    this.timerLog = null;
    this.breakCode = null;
    this.breakCore = null;
    /** The core being stepped (SEV, timer reads); the core a failure happened on. */
    this.current = 0;
    this.failedCore = null;

    this.rp2040.loadBootrom(o.bootrom);
    this.loadFirmware(o.elf);
    this.patchChipResetBlock();
    this.patchQspiSsPad();
    this.patchTimer();
    this.patchSpi();
    this.patchDmaAbort();
    this.watchDisplayPins();
    // Core 1, the per-core SIO (with the exact divider) and PPB, SEV between the cores.
    this.slots = installCores(this, { core1Boot: o.core1Boot ?? hasRp2040RomHeader(o.bootrom) });
    this.logger.onSev = () => this.sev();
  }

  /** Core `index`'s CortexM0Core. */
  core(index) {
    return this.slots[index].core;
  }

  noteBreak(index, code) {
    this.breakCode = code;
    this.breakCore = index;
  }

  /** Drives IRQ line `irq` of core `index`'s NVIC; notes the wake of a core that was sleeping. */
  setCoreIrq(index, irq, level) {
    const slot = this.slots[index];
    const { core } = slot;
    const was = core.waiting;
    core.setInterrupt(irq, level);
    if (was && !core.waiting) this.woke(slot);
  }

  /** A sleeping core woke up: its next instruction starts no earlier than now. */
  woke(slot) {
    slot.waitKind = null;
    slot.time = Math.max(slot.time, Math.ceil(this.clock.nanos / NS_PER_CYCLE));
  }

  /**
   * SEV on the current core: an event for every core (the RP2040 wires each core's TXEV to the
   * other's RXEV, and SEV also sets the local event register). A core sleeping in WFE wakes and
   * the event is consumed; any other core (running, or in WFI) keeps it in its event register,
   * so its next WFE does not sleep. A core held in reset ignores it.
   */
  sev() {
    for (const slot of this.slots) {
      if (slot.held) continue;
      const { core } = slot;
      if (core.waiting && slot.waitKind === 'wfe') {
        core.waiting = false;
        this.woke(slot);
      } else {
        core.eventRegistered = true;
      }
    }
  }

  /** Cycles since reset (the clock runs 8 ns per cycle). */
  get cycles() {
    return this.clock.nanos / NS_PER_CYCLE;
  }

  /**
   * Copies the ELF's PT_LOAD segments to flash at their physical (load) addresses. A segment that
   * loads outside flash with bytes in the file is an error (a flash image has none); RAM-only
   * segments (.bss, .uninit; .data's run address) are the firmware's own start-up code's job.
   */
  loadFirmware(elf) {
    const { flash } = this.rp2040;
    // rp2040js's reset() erased flash (0xff) before loadBootrom returned.
    let bytes = 0;
    for (const seg of elf.segments) {
      if (seg.data.length === 0) continue;
      const a = seg.paddr >>> 0;
      if (a < FLASH_BASE || a + seg.data.length > FLASH_BASE + FLASH_SIZE) {
        throw new HarnessError(
          `ELF segment at physical address 0x${a.toString(16)} (${seg.data.length} bytes) is ` +
            'not in flash (0x10000000..): cannot load it',
        );
      }
      flash.set(seg.data, a - FLASH_BASE);
      bytes += seg.data.length;
    }
    if (!bytes) throw new HarnessError('the ELF has nothing to load into flash');
    this.flashBytes = bytes;
  }

  /**
   * Patch (a): VREG_AND_CHIP_RESET (0x40064000) is unimplemented in rp2040js and reads 0xffffffff,
   * so the boot ROM sees CHIP_RESET's "had PSM restart" flag and parks in a WFI loop. Map a plain
   * register block with the chip's reset values (VREG 0xb1, BOD 0x91, CHIP_RESET 0).
   */
  patchChipResetBlock() {
    this.rp2040.peripherals[0x40064] = new RegisterBlock(this.rp2040, 'VREG_AND_CHIP_RESET', {
      0x0: 0xb1,
      0x4: 0x91,
      0x8: 0,
    });
  }

  /**
   * Patch (b): the QSPI SS pad's reset value in rp2040js lacks input-enable, so SS reads low and
   * the boot ROM takes that for the BOOTSEL button and enters USB boot. Give the pad input-enable
   * and drive the pin high (the flash's CS has a pull-up on the Pico; BOOTSEL not pressed).
   */
  patchQspiSsPad() {
    const ss = this.rp2040.qspi[1];
    ss.padValue |= 0x40; // IE
    ss.setInputValue(true);
  }

  /**
   * TIMER: the microsecond counter is floor(cycles / 125), from the core's cycle count (rp2040js
   * derives it from the same clock, but as a fraction; alarms compared against a fraction can
   * fire up to 1 us early). Reads of the low word are logged: the harness derives the frame time
   * the firmware shows from them (see lib/frames.mjs).
   */
  patchTimer() {
    const timer = this.rp2040.peripherals[0x40054];
    const m = this;
    const micros = () => Math.floor(m.cycles / CYCLES_PER_US);
    const origRead = timer.readUint32.bind(timer);
    const origWrite = timer.writeUint32.bind(timer);
    timer.readUint32 = (offset) => {
      switch (offset) {
        case TIMELR:
        case TIMERAWL: {
          const us = micros();
          if (offset === TIMELR) timer.latchedTimeHigh = Math.floor(us / 2 ** 32);
          m.lastTimerRead = { cycle: m.cycles, value: us, core: m.current };
          m.stats.timerReads++;
          if (m.timerLog) m.timerLog.push(m.lastTimerRead);
          return us >>> 0;
        }
        case TIMERAWH:
          return Math.floor(micros() / 2 ** 32) >>> 0;
        case TIMEHR:
          return timer.latchedTimeHigh >>> 0;
        default:
          return origRead(offset);
      }
    };
    timer.writeUint32 = (offset, value) => {
      if (offset >= ALARM0 && offset <= ALARM3 && (offset & 3) === 0) {
        // The alarm fires when the counter's low word equals the value.
        const alarm = timer.alarms[(offset - ALARM0) / 4];
        const deltaUs = ((value >>> 0) - (micros() >>> 0)) >>> 0;
        const fireNs = (Math.floor(m.cycles / CYCLES_PER_US) + deltaUs) * 1000;
        alarm.armed = true;
        alarm.targetMicros = value >>> 0;
        alarm.clockAlarm.schedule(Math.max(0, fireNs - m.clock.nanos));
        return;
      }
      origWrite(offset, value);
    };
  }

  /**
   * SPI timing. rp2040js's RPSPI keeps the PL022's 8-deep TX and RX FIFOs and moves a frame from
   * the TX FIFO into a shifter (`busy`) when the shifter is free, but by default completes the
   * transfer at once (`onTransmit` calls `completeTransmit` immediately). Here the display's SPI
   * completes each frame after (frame bits) x (cycles per bit) core cycles, scheduled on the
   * clock: 16 cycles for a byte at 62.5 MHz (CPSDVSR 2, SCR 0), 32 for a 16-bit frame. BSY, TNF,
   * TFE (SSPSR) and the TX DMA request follow the FIFO as rp2040js computes them, so a DMA
   * channel paced by DREQ_SPIx_TX is throttled by the FIFO as on the chip.
   *
   * Two more differences from the PL022 are fixed: rp2040js raises the DMA requests whatever
   * SSPDMACR says (the chip only with TXDMAE / RXDMAE set), and shifts frames out while the SPI
   * is disabled (SSE clear).
   */
  patchSpi() {
    const m = this;
    const spi = this.rp2040.spi[this.spiIndex];
    const dma = this.rp2040.dma;
    const txDreq = DREQ_SPI_TX[this.spiIndex];
    const rxDreq = DREQ_SPI_RX[this.spiIndex];
    this.spi = spi;

    spi.updateDMATx = function () {
      if (this.txFIFO.full || !(this.dmaControl & TXDMAE)) dma.clearDREQ(txDreq);
      else dma.setDREQ(txDreq);
    };
    spi.updateDMARx = function () {
      if (this.rxFIFO.empty || !(this.dmaControl & RXDMAE)) dma.clearDREQ(rxDreq);
      else dma.setDREQ(rxDreq);
    };
    const origDoTX = spi.doTX.bind(spi);
    spi.doTX = () => {
      if (spi.control1 & SSE) origDoTX();
    };
    const origWrite = spi.writeUint32.bind(spi);
    spi.writeUint32 = (offset, value) => {
      origWrite(offset, value);
      if (offset === SSPDMACR) {
        spi.updateDMATx();
        spi.updateDMARx();
      } else if (offset === SSPCR1) {
        spi.doTX();
      }
    };
    spi.updateDMATx();
    spi.updateDMARx();

    // The frame being shifted out.
    this.shifting = null;
    const completeAlarm = this.clock.createAlarm(() => {
      const f = m.shifting;
      m.shifting = null;
      m.stats.spiBusyCycles += f.cycles;
      m.deliverFrame(f, m.cycles);
      spi.completeTransmit(0); // the receive side of a write-only display reads zeros
    });

    spi.onTransmit = (value) => {
      const bits = spi.dataBits;
      const cpsdvsr = spi.readUint32(SSPCPSR) & 0xfe;
      const scr = (spi.readUint32(SSPCR0) >> 8) & 0xff;
      if (!cpsdvsr) {
        throw new HarnessError(`SPI${m.spiIndex} transmits with CPSDVSR 0 (no clock)`);
      }
      // clk_peri = clk_sys in the firmware (CLK_PERI_CTRL source clk_sys).
      const perBit = cpsdvsr * (1 + scr);
      m.stats.spiCyclesPerBit = perBit;
      m.stats.spiFrameBits.add(bits);
      if (bits !== 8 && bits !== 16) {
        throw new HarnessError(
          `SPI${m.spiIndex} sends a ${bits}-bit frame: the harness decodes 8- and 16-bit frames only`,
        );
      }
      m.shifting = {
        value,
        bits,
        cycles: bits * perBit,
        start: m.cycles,
        dc: driven(m.rp2040.gpio[m.pins.dc]),
        cs: driven(m.rp2040.gpio[m.pins.cs]),
        rst: driven(m.rp2040.gpio[m.pins.rst]),
      };
      completeAlarm.schedule(bits * perBit * NS_PER_CYCLE);
    };
  }

  /**
   * DMA CHAN_ABORT (0x50000444) reads 0. rp2040js implements only its write (which aborts the
   * channels at once) and reads it as an unimplemented register, 0xffffffff. On the chip a bit
   * reads 1 while that channel's abort is still flushing, so an idle DMA reads 0; embassy-rp
   * drops every transfer with a read-modify-write of the register (set its channel's bit), which
   * with 0xffffffff aborted every channel.
   */
  patchDmaAbort() {
    const { dma } = this.rp2040;
    const origRead = dma.readUint32.bind(dma);
    dma.readUint32 = (offset) => (offset === DMA_CHAN_ABORT ? 0 : origRead(offset));
  }

  /** A frame finished shifting: hand its byte(s) to the display if it was selected. */
  deliverFrame(f, end) {
    const n = f.bits / 8;
    this.stats.spiBytes += n;
    // CS low (selected) and RST not low: the display receives the frame.
    if (f.cs !== false || f.rst === false) {
      this.stats.bytesIgnored += n;
      return;
    }
    if (f.dc === null) {
      throw new HarnessError(
        `SPI${this.spiIndex} byte 0x${f.value.toString(16)} sent to the display (cycle ${f.start}) ` +
          `while DC (GP${this.pins.dc}) is not an output`,
      );
    }
    if (n === 1) {
      this.onByte(f.value & 0xff, f.dc, f.start, end);
    } else {
      // A 16-bit frame is two bytes on the wire, most significant first.
      const mid = f.start + f.cycles / 2;
      this.onByte((f.value >> 8) & 0xff, f.dc, f.start, mid);
      this.onByte(f.value & 0xff, f.dc, mid, end);
    }
  }

  /**
   * DC and CS must not change while a frame is being shifted out (the display samples DC with a
   * byte's last bit and drops a byte cut by CS): firmware that toggles them before the SPI is idle
   * has a race, which is a failure here. RST low resets the display controller.
   */
  watchDisplayPins() {
    const { gpio } = this.rp2040;
    const names = { [this.pins.dc]: 'DC', [this.pins.cs]: 'CS' };
    for (const index of [this.pins.dc, this.pins.cs]) {
      gpio[index].addListener((value, old) => {
        const f = this.shifting;
        if (f && f.cs === false) {
          throw new HarnessError(
            `${names[index]} (GP${index}) changed (${GPIOPinState[old]} -> ${GPIOPinState[value]}) ` +
              `at cycle ${this.cycles} while SPI${this.spiIndex} was still shifting out ` +
              `0x${f.value.toString(16)} (cycles ${f.start}..${f.start + f.cycles}): ` +
              'the firmware must wait for the SPI to be idle (SSPSR.BSY clear) first',
          );
        }
      });
    }
    gpio[this.pins.rst].addListener((value) => {
      if (value === GPIOPinState.Low) this.onDisplayReset();
    });
  }

  /**
   * Starts the firmware. The boot ROM runs first on the chip: it checks the chip-reset and BOOTSEL
   * state, reads the 256-byte boot2 from flash through the SSI, checks its CRC and runs it. The
   * SSI in rp2040js has no flash chip behind it, so here the core starts at boot2 in flash
   * (0x10000000), as rp2040js's own demos do, with the boot ROM's initial stack pointer
   * (0x20041f00) and LR = 0 so boot2 then enters the firmware through its vector table at
   * 0x10000100. The boot ROM stays mapped: rp2040-hal calls its functions (memset4, memcpy44,
   * clz32, the float and divide tables). boot2's SSI set-up is accepted by rp2040js's SSI model
   * and XIP reads come straight from the flash array.
   */
  bootAtBoot2() {
    const { core } = this.rp2040;
    core.SP = this.rp2040.readUint32(0); // 0x20041f00 from the ROM's vector table
    core.LR = 0;
    core.PC = FLASH_BASE;
  }

  /**
   * Runs until `done()` says so, checked after every instruction (of either core). Fails
   * (HarnessError; `failedCore` says which core) past `maxCycles`, at a BKPT/UDF, when a core
   * enters a fault or panic handler (`traps`: address -> description), when it branches to itself
   * (a `loop {}` such as panic-halt's), or when every core that is not in reset waits for an
   * interrupt that nothing can raise. `onStep(core, pc, cycles)`, if given, is called after each
   * instruction with the core's index, the instruction's address and its cycles.
   */
  run({ maxCycles, done, traps = new Map(), onStep = null }) {
    const { clock, slots } = this;
    const [s0, s1] = slots;
    const maxNs = maxCycles * NS_PER_CYCLE;
    while (!done()) {
      if (clock.nanos >= maxNs) {
        throw new HarnessError(`cycle limit reached (${maxCycles} cycles)`);
      }
      // The running core with the lower time; core 0 on a tie.
      const r0 = !s0.held && !s0.core.waiting;
      const r1 = !s1.held && !s1.core.waiting;
      let slot;
      if (r0 && (!r1 || s0.time <= s1.time)) slot = s0;
      else if (r1) slot = s1;
      else {
        this.sleepUntilNextEvent();
        continue;
      }
      this.step(slot, traps, onStep);
    }
  }

  /** Executes one instruction on `slot`'s core and moves the clock on. */
  step(slot, traps, onStep) {
    const { core, index } = slot;
    const { clock } = this;
    const now = clock.nanos / NS_PER_CYCLE;
    if (slot.time < now) slot.time = now; // it woke up during the other core's instruction
    const pc = core.PC;
    const trap = traps.get(pc);
    if (trap !== undefined) {
      this.failedCore = index;
      throw new HarnessError(`core ${index} entered ${trap}`);
    }
    this.current = index;
    const delta = core.executeInstruction();
    slot.time += delta;
    slot.busy += delta;
    if (core.waiting) noteWait(slot, pc);
    // The clock moves to the lower time of the running cores (this one if none other runs).
    let target = slot.time;
    const other = this.slots[1 - index];
    if (!other.held && !other.core.waiting && other.time < target) target = other.time;
    const dn = target * NS_PER_CYCLE - clock.nanos;
    if (dn > 0) clock.tick(dn);
    if (onStep) onStep(index, pc, delta);
    if (core.PC === pc) {
      this.failedCore = index;
      throw new HarnessError(`core ${index} is stuck in a branch to itself at 0x${pc.toString(16)}`);
    }
    if (this.breakCode !== null) {
      this.failedCore = this.breakCore;
      throw new HarnessError(
        `core ${this.breakCore} hit a breakpoint or undefined instruction (code ${this.breakCode}) at 0x${pc.toString(16)}`,
      );
    }
  }

  /** No core runs: skip to the next scheduled event (in whole cycles), which may wake one. */
  sleepUntilNextEvent() {
    const { clock } = this;
    if (!clock.nextAlarm) {
      const waiting = this.slots
        .filter((s) => !s.held)
        .map((s) => `core ${s.index} (${(s.waitKind ?? 'WFI/WFE').toUpperCase()} at 0x${(s.core.PC - 2).toString(16)})`);
      this.failedCore = this.slots.find((s) => !s.held)?.index ?? 0;
      throw new HarnessError(
        `${waiting.join(' and ')} ${waiting.length > 1 ? 'wait' : 'waits'} for an interrupt ` +
          'and nothing is scheduled that could raise one',
      );
    }
    const dn = Math.max(clock.nanosToNextAlarm, 0);
    clock.tick(Math.ceil(dn / NS_PER_CYCLE) * NS_PER_CYCLE || NS_PER_CYCLE);
  }

  /** Per core: busy cycles, whether it was ever released from reset, and its state now. */
  coreStats() {
    return this.slots.map((s) => ({
      core: s.index,
      busy_cycles: s.busy,
      launches: s.launches,
      state: s.held ? 'reset' : s.core.waiting ? `asleep (${s.waitKind})` : 'running',
    }));
  }
}
