// The RP2040's second Cortex-M0+ core, added to rp2040js 1.4.1 (which builds one) at run time.
//
// Each core reaches the bus through its own view of the RP2040 object: core 0 uses rp2040js's
// RP2040 itself, core 1 an object whose prototype is that RP2040 (so memory and peripherals are
// the very same objects) with three properties of its own: `core` (its CortexM0Core), `ppb` (its
// NVIC, SysTick, VTOR, SCR and MPU) and `sio` (its view of the SIO, lib/sio.mjs). rp2040js's
// memory map code reads `this.ppb` and `this.sio`, and its PPB reads `this.rp2040.core`, so an
// access made by core 1 lands in core 1's private blocks without any change to rp2040js.
//
// Also here: peripheral IRQ lines raised on both cores' NVICs, the SIO IRQs on their own core's,
// SEV between the cores, and core 1's reset through PSM FRCE_OFF.PROC1 (Multicore::spawn).

import { HarnessError } from './errors.mjs';
import { SioShared, CoreSio, SIO_IRQ_PROC0 } from './sio.mjs';

/** Thumb WFE and WFI. */
const WFE = 0xbf20;
const WFI = 0xbf30;

// PSM (0x40010000) FRCE_OFF and its PROC1 bit.
const PSM_FRCE_OFF = 0x04;
const PSM_PROC1 = 1 << 16;

/**
 * Cycles from the write that clears FRCE_OFF.PROC1 to core 1's first instruction. On the chip the
 * PSM powers the domain up and the core leaves reset: that takes time the datasheet does not give.
 * It matters for the launch handshake: if core 1 started at once it would drain its FIFO and push
 * its 0 at the very moment core 0 sends its first 0, the two zeros cross, and with the cores in
 * lockstep the exchange repeats forever (rp2040-hal gives up after 16 tries). With core 1 a little
 * late, core 0's first 0 is in core 1's FIFO before the ROM drains it, and the handshake completes
 * as on the chip. An assumption, not a measurement (see README.md).
 */
export const CORE1_RELEASE_CYCLES = 1000;

// PPB offsets (from 0xe000e000) that rp2040js's RPPPB implements.
const PPB_RPPPB = new Set([
  0x010, 0x014, 0x018, 0x01c, // SysTick CSR, RVR, CVR, CALIB
  0x100, 0x180, 0x200, 0x280, // NVIC ISER, ICER, ISPR, ICPR
  0x400, 0x404, 0x408, 0x40c, 0x410, 0x414, 0x418, 0x41c, // NVIC IPR0..7
  0xd00, 0xd04, 0xd08, 0xd1c, 0xd20, // CPUID, ICSR, VTOR, SHPR2, SHPR3
]);
// Added here (per core): SCR and the MPU's registers.
const SCR = 0xd10;
const SCR_SLEEPDEEP = 1 << 2;
const MPU_TYPE = 0xd90;
const MPU_CTRL = 0xd94;
const MPU_RNR = 0xd98;
const MPU_RBAR = 0xd9c;
const MPU_RASR = 0xda0;
const MPU_REGIONS = 8;

const hex = (v) => `0x${(v >>> 0).toString(16)}`;

/** One core: its CortexM0Core, its bus view, and its own time (in cycles). */
export class CoreSlot {
  constructor(index, core, bus) {
    this.index = index;
    this.core = core;
    this.bus = bus;
    /** The cycle at which this core's next instruction starts (its local time). */
    this.time = 0;
    /** Cycles spent executing instructions (WFE/WFI's own 2 included, the sleep after not). */
    this.busy = 0;
    /** Held in reset (PSM FRCE_OFF.PROC1, or no boot ROM to run): not stepped. */
    this.held = false;
    /** 'wfe' or 'wfi' while the core sleeps (rp2040js's `waiting` does not say which). */
    this.waitKind = null;
    /** Times the core was released from reset. */
    this.launches = 0;
  }
}

/**
 * SCR and the MPU on a core's PPB. rp2040js has neither (reads give 0xffffffff, which makes
 * rp2040-hal's core-1 stack guard trap: it checks that MPU_CTRL reads 0). They are plain
 * registers: SLEEPDEEP is accepted (it changes nothing here); SLEEPONEXIT and SEVONPEND, which
 * would change when a core sleeps or wakes, are not modelled and fail. The MPU's regions are
 * stored, not enforced. With `strict`, any other PPB register rp2040js lacks fails too (core 1);
 * core 0 keeps rp2040js's behaviour (a warning and 0xffffffff) so the one-core path is unchanged.
 */
function extendPpb(ppb, index, strict) {
  const read = ppb.readUint32.bind(ppb);
  const write = ppb.writeUint32.bind(ppb);
  const regs = { scr: 0, mpuCtrl: 0, rnr: 0, rbar: new Uint32Array(MPU_REGIONS), rasr: new Uint32Array(MPU_REGIONS) };
  ppb.coreRegs = regs;
  const unmodelled = (what, offset) =>
    new HarnessError(`core ${index} ${what} PPB register ${hex(0xe000_e000 + offset)}, which the harness does not model`);
  ppb.readUint32 = (offset) => {
    switch (offset) {
      case SCR:
        return regs.scr;
      case MPU_TYPE:
        return MPU_REGIONS << 8;
      case MPU_CTRL:
        return regs.mpuCtrl;
      case MPU_RNR:
        return regs.rnr;
      case MPU_RBAR:
        return (regs.rbar[regs.rnr] | regs.rnr) >>> 0;
      case MPU_RASR:
        return regs.rasr[regs.rnr];
      default:
        if (strict && !PPB_RPPPB.has(offset)) throw unmodelled('read', offset);
        return read(offset);
    }
  };
  ppb.writeUint32 = (offset, value) => {
    switch (offset) {
      case SCR:
        if (value & ~SCR_SLEEPDEEP) {
          throw new HarnessError(`core ${index} set SCR to ${hex(value)}: only SLEEPDEEP is modelled (no SLEEPONEXIT, SEVONPEND)`);
        }
        regs.scr = value & SCR_SLEEPDEEP;
        return;
      case MPU_CTRL:
        regs.mpuCtrl = value & 7;
        return;
      case MPU_RNR:
        regs.rnr = value & (MPU_REGIONS - 1);
        return;
      case MPU_RBAR:
        if (value & 0x10) regs.rnr = value & (MPU_REGIONS - 1); // VALID: REGION selects
        regs.rbar[regs.rnr] = value & 0xffffff00;
        return;
      case MPU_RASR:
        regs.rasr[regs.rnr] = value;
        return;
      default:
        if (strict && !PPB_RPPPB.has(offset)) throw unmodelled('wrote to', offset);
        write(offset, value);
    }
  };
  ppb.resetCoreRegs = () => {
    regs.scr = 0;
    regs.mpuCtrl = 0;
    regs.rnr = 0;
    regs.rbar.fill(0);
    regs.rasr.fill(0);
  };
}

/** The RP2040 B1 boot ROM starts with its header: 'M', 'u', 1 at 0x10. */
export function hasRp2040RomHeader(bootrom) {
  return (bootrom[4] & 0x00ff_ffff) === 0x01_754d;
}

/**
 * Adds core 1 to machine `m` (lib/machine.mjs) and returns the two CoreSlots. `core1Boot`: core
 * 1 leaves reset with core 0 and runs the boot ROM's reset handler (which parks it in the ROM's
 * launch wait loop); otherwise it is held in reset until the firmware cycles PSM FRCE_OFF.PROC1.
 */
export function installCores(m, { core1Boot }) {
  const { rp2040 } = m;
  const originalSio = rp2040.sio;
  const shared = new SioShared(originalSio, (c, level) => m.setCoreIrq(c, SIO_IRQ_PROC0 + c, level));
  m.sioShared = shared;

  // Core 1's bus view.
  const bus = Object.create(rp2040);
  const RPSIO = originalSio.constructor;
  bus.sio = new CoreSio(1, shared, new RPSIO(bus));
  bus.ppb = new rp2040.ppb.constructor(bus, 'PPB1');
  rp2040.addClockListener((hz) => {
    bus.ppb.systickTimer.frequency = hz;
  });
  extendPpb(rp2040.ppb, 0, false);
  extendPpb(bus.ppb, 1, true);
  const Core = rp2040.core.constructor;
  bus.core = new Core(bus);
  bus.onBreak = (code) => m.noteBreak(1, code);
  rp2040.onBreak = (code) => m.noteBreak(0, code);

  // Core 0's view: rp2040js's own, with its SIO decoded per core.
  const sio0 = new CoreSio(0, shared, originalSio);
  // rp2040js's GPIO pins read these two fields of `rp2040.sio`.
  Object.defineProperties(sio0, {
    gpioValue: { get: () => originalSio.gpioValue },
    gpioOutputEnable: { get: () => originalSio.gpioOutputEnable },
  });
  rp2040.sio = sio0;

  const slots = [new CoreSlot(0, rp2040.core, rp2040), new CoreSlot(1, bus.core, bus)];

  // Peripheral IRQ lines reach both NVICs; each core's enable bits decide which takes them.
  rp2040.setInterrupt = (irq, value) => {
    m.setCoreIrq(0, irq, value);
    m.setCoreIrq(1, irq, value);
  };

  const slot1 = slots[1];
  /**
   * Core 1 starts from the boot ROM's vector table (VTOR 0), with fresh NVIC and SysTick, its
   * first instruction `delay` cycles from now.
   */
  const resetCore1 = (delay) => {
    const core = new Core(bus);
    bus.core = core;
    slot1.core = core;
    bus.ppb.reset();
    bus.ppb.resetCoreRegs();
    core.reset(); // SP and PC from 0x00000000 and 0x00000004
    slot1.held = false;
    slot1.waitKind = null;
    slot1.time = Math.max(slot1.time, m.cycles + delay);
    slot1.launches++;
    // Its SIO IRQ line may already be high (data in its RX FIFO): raise it on the new NVIC.
    shared.irqLevel[1] = false;
    shared.updateIrqs();
  };
  if (core1Boot) resetCore1(0); // at power-on both cores leave reset together
  else slot1.held = true;

  // PSM FRCE_OFF.PROC1: set holds core 1 in reset, clear releases it (rp2040-hal's
  // Multicore::spawn and the SDK's multicore_reset_core1 do both before the launch handshake).
  const psm = rp2040.peripherals[0x40010];
  const psmWrite = psm.writeUint32.bind(psm);
  psm.writeUint32 = (offset, value) => {
    psmWrite(offset, value);
    if (offset !== PSM_FRCE_OFF) return;
    const off = (psm.frceOff & PSM_PROC1) !== 0;
    if (off && !slot1.held) {
      slot1.held = true;
      slot1.waitKind = null;
    } else if (!off && slot1.held) {
      resetCore1(CORE1_RELEASE_CYCLES);
    }
  };
  return slots;
}

/** After a step of `slot` left its core waiting: was that a WFE or a WFI? */
export function noteWait(slot, pc) {
  const op = slot.bus.readUint16(pc);
  slot.waitKind = op === WFE ? 'wfe' : op === WFI ? 'wfi' : 'wfe';
}
