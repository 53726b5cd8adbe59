// The SIO block (0xd0000000) as each core sees it. rp2040js 1.4.1 has one RPSIO for its one core:
// CPUID always 0, no inter-core FIFOs, one divider and one pair of interpolators. On the chip
// some SIO registers are per core and some are shared:
//
//   per core  CPUID (0 or 1), the divider, INTERP0 and INTERP1, which end of each FIFO it sees,
//             the FIFO_ST sticky flags (WOF, ROE) and the SIO IRQ (IRQ 15 for core 0, 16 for core 1)
//   shared    the GPIO registers, the two FIFOs' contents, the 32 spinlocks
//
// Here each core gets a CoreSio that decodes the offset itself: CPUID, FIFOs, spinlocks and the
// divider are implemented here; the interpolator registers go to an RPSIO of that core (core 0
// keeps rp2040js's original one, core 1 gets a second instance) and the GPIO registers to the
// original RPSIO, which both cores share. Any other offset is a HarnessError: it is not modelled.

import { HarnessError } from './errors.mjs';

const CPUID = 0x000;
const FIFO_ST = 0x050;
const FIFO_WR = 0x054;
const FIFO_RD = 0x058;
const SPINLOCK_ST = 0x05c;
const DIV_UDIVIDEND = 0x060;
const DIV_UDIVISOR = 0x064;
const DIV_SDIVIDEND = 0x068;
const DIV_SDIVISOR = 0x06c;
const DIV_QUOTIENT = 0x070;
const DIV_REMAINDER = 0x074;
const DIV_CSR = 0x078;
const INTERP_FIRST = 0x080; // INTERP0_ACCUM0
const INTERP_LAST = 0x0fc; // INTERP1_BASE_1AND0
const SPINLOCK0 = 0x100;
const SPINLOCK31 = 0x17c;
const GPIO_FIRST = 0x004; // GPIO_IN
const GPIO_LAST = 0x04c; // GPIO_HI_OE_XOR
const GPIO_RESERVED = 0x00c;

/** FIFO_ST bits. */
export const FIFO_VLD = 1 << 0; // this core's RX FIFO holds data
export const FIFO_RDY = 1 << 1; // this core's TX FIFO has room
export const FIFO_WOF = 1 << 2; // sticky: this core wrote to its full TX FIFO
export const FIFO_ROE = 1 << 3; // sticky: this core read its empty RX FIFO

/** Entries in each inter-core FIFO. */
export const FIFO_DEPTH = 8;
/** The SIO IRQ of core 0 (SIO_IRQ_PROC0); core 1's is the next one. */
export const SIO_IRQ_PROC0 = 15;

const hex = (v) => `0x${(v >>> 0).toString(16)}`;

/**
 * What the two cores share: the FIFOs (fifo[0] carries core 0 -> core 1, fifo[1] core 1 -> core
 * 0), each core's sticky flags, the spinlocks, and the GPIO part of rp2040js's RPSIO.
 */
export class SioShared {
  /**
   * @param {object} gpioSio rp2040js's RPSIO, used for the GPIO registers
   * @param {(core:number, level:boolean)=>void} setIrq drives core `core`'s SIO IRQ line
   */
  constructor(gpioSio, setIrq) {
    this.gpioSio = gpioSio;
    this.setIrq = setIrq;
    this.fifo = [[], []];
    this.wof = [false, false];
    this.roe = [false, false];
    this.spinlocks = 0;
    this.irqLevel = [false, false];
  }

  /** FIFO_ST as core `c` reads it. */
  status(c) {
    return (
      (this.fifo[1 - c].length ? FIFO_VLD : 0) |
      (this.fifo[c].length < FIFO_DEPTH ? FIFO_RDY : 0) |
      (this.wof[c] ? FIFO_WOF : 0) |
      (this.roe[c] ? FIFO_ROE : 0)
    );
  }

  /** Each core's SIO IRQ is the OR of VLD, WOF and ROE in its FIFO_ST (datasheet 2.3.1.4). */
  updateIrqs() {
    for (let c = 0; c < 2; c++) {
      const level = (this.status(c) & (FIFO_VLD | FIFO_WOF | FIFO_ROE)) !== 0;
      if (level !== this.irqLevel[c]) {
        this.irqLevel[c] = level;
        this.setIrq(c, level);
      }
    }
  }

  push(c, value) {
    const tx = this.fifo[c];
    if (tx.length >= FIFO_DEPTH) this.wof[c] = true; // the word is lost
    else tx.push(value >>> 0);
    this.updateIrqs();
  }

  pop(c) {
    const rx = this.fifo[1 - c];
    let value = 0; // the chip's value for a read of an empty FIFO is not documented: 0 here
    if (rx.length) value = rx.shift();
    else this.roe[c] = true;
    this.updateIrqs();
    return value;
  }

  /** A write to FIFO_ST: a 1 in WOF or ROE clears that flag (the other bits are read-only). */
  clearFlags(c, value) {
    if (value & FIFO_WOF) this.wof[c] = false;
    if (value & FIFO_ROE) this.roe[c] = false;
    this.updateIrqs();
  }

  /** Reading SPINLOCKn claims lock n: 1 << n if it was free, 0 if it is held (by either core). */
  claim(n) {
    const bit = 1 << n;
    if (this.spinlocks & bit) return 0;
    this.spinlocks = (this.spinlocks | bit) >>> 0;
    return bit >>> 0;
  }

  /** Any write to SPINLOCKn releases lock n. */
  release(n) {
    this.spinlocks = (this.spinlocks & ~(1 << n)) >>> 0;
  }
}

/** The SIO seen from core `index`: replaces rp2040js's `rp2040.sio` on that core's bus. */
export class CoreSio {
  /**
   * @param {number} index 0 or 1
   * @param {SioShared} shared
   * @param {object} localSio an RPSIO holding this core's interpolators
   */
  constructor(index, shared, localSio) {
    this.index = index;
    this.shared = shared;
    this.local = localSio;
    // The divider (each core has its own); the values rp2040js starts with.
    this.dividend = 0;
    this.divisor = 1;
    this.quotient = 0;
    this.remainder = 0;
    this.csr = 0; // bit 0 READY, bit 1 DIRTY
  }

  unmodelled(what, offset) {
    return new HarnessError(`core ${this.index} ${what} SIO register ${hex(0xd000_0000 + offset)}, which the harness does not model`);
  }

  readUint32(offset) {
    const { shared } = this;
    if (offset >= GPIO_FIRST && offset <= GPIO_LAST && offset !== GPIO_RESERVED) {
      return shared.gpioSio.readUint32(offset);
    }
    if (offset >= INTERP_FIRST && offset <= INTERP_LAST) return this.local.readUint32(offset);
    if (offset >= SPINLOCK0 && offset <= SPINLOCK31) return shared.claim((offset - SPINLOCK0) >> 2);
    switch (offset) {
      case CPUID:
        return this.index;
      case FIFO_ST:
        return shared.status(this.index);
      case FIFO_RD:
        return shared.pop(this.index);
      case FIFO_WR:
        return 0; // write-only
      case SPINLOCK_ST:
        return shared.spinlocks;
      case DIV_UDIVIDEND:
      case DIV_SDIVIDEND:
        return this.dividend;
      case DIV_UDIVISOR:
      case DIV_SDIVISOR:
        return this.divisor;
      case DIV_QUOTIENT:
        this.csr &= ~0b10; // reading the quotient clears DIRTY
        return this.quotient;
      case DIV_REMAINDER:
        return this.remainder;
      case DIV_CSR:
        return this.csr;
      default:
        throw this.unmodelled('read', offset);
    }
  }

  writeUint32(offset, value) {
    const { shared } = this;
    if (offset >= GPIO_FIRST && offset <= GPIO_LAST && offset !== GPIO_RESERVED) {
      shared.gpioSio.writeUint32(offset, value);
      return;
    }
    if (offset >= INTERP_FIRST && offset <= INTERP_LAST) {
      this.local.writeUint32(offset, value);
      return;
    }
    if (offset >= SPINLOCK0 && offset <= SPINLOCK31) {
      shared.release((offset - SPINLOCK0) >> 2);
      return;
    }
    switch (offset) {
      case FIFO_ST:
        shared.clearFlags(this.index, value);
        return;
      case FIFO_WR:
        shared.push(this.index, value);
        return;
      case DIV_UDIVIDEND:
        this.dividend = value >>> 0;
        this.divide(false);
        return;
      case DIV_SDIVIDEND:
        this.dividend = value >>> 0;
        this.divide(true);
        return;
      case DIV_UDIVISOR:
        this.divisor = value >>> 0;
        this.divide(false);
        return;
      case DIV_SDIVISOR:
        this.divisor = value >>> 0;
        this.divide(true);
        return;
      case DIV_QUOTIENT: // a context restore (rp2040-hal's save_divider)
        this.quotient = value >>> 0;
        this.csr = 0b11;
        return;
      case DIV_REMAINDER:
        this.remainder = value >>> 0;
        this.csr = 0b11;
        return;
      default:
        // CPUID, FIFO_RD, SPINLOCK_ST and DIV_CSR are read-only: a write is a firmware bug.
        throw this.unmodelled('wrote to', offset);
    }
  }

  /**
   * The hardware divider. The chip takes 8 cycles, in parallel with the core; software waits for
   * it with instructions that are counted anyway, so the result is available at once here (and
   * no cycles are added: rp2040js's own divider adds 8 to core.cycles, which the harness's time
   * does not use). Results are exact integers; division by zero gives the datasheet's values
   * (quotient -1 for a non-negative signed dividend, else 1; 0xffffffff unsigned; remainder =
   * dividend). -2^31 / -1 overflows to -2^31, as on the chip.
   */
  divide(signed) {
    const n = this.dividend;
    const d = this.divisor;
    if (signed) {
      const sn = n | 0;
      const sd = d | 0;
      if (sd === 0) {
        this.quotient = sn >= 0 ? 0xffffffff : 1;
        this.remainder = sn >>> 0;
      } else {
        this.quotient = Math.trunc(sn / sd) >>> 0;
        this.remainder = (sn % sd) >>> 0;
      }
    } else if (d === 0) {
      this.quotient = 0xffffffff;
      this.remainder = n;
    } else {
      this.quotient = Math.floor(n / d) >>> 0;
      this.remainder = n % d >>> 0;
    }
    this.csr = 0b11; // READY | DIRTY
  }
}
