// The SIO as each core sees it (lib/sio.mjs), driven by register accesses made on each core's bus:
// CPUID, the two inter-core FIFOs with their status bits and IRQs, the spinlocks, and the
// per-core divider and interpolators. No program runs here (test/core1.test.mjs runs programs).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Machine, HarnessError } from '../lib/machine.mjs';

const SIO = 0xd000_0000;
const CPUID = SIO + 0x000;
const FIFO_ST = SIO + 0x050;
const FIFO_WR = SIO + 0x054;
const FIFO_RD = SIO + 0x058;
const SPINLOCK_ST = SIO + 0x05c;
const SPINLOCK = (n) => SIO + 0x100 + 4 * n;
const VLD = 1;
const RDY = 2;
const WOF = 4;
const ROE = 8;

/** A machine (never run) and read/write functions for each core's bus. */
function machine() {
  const elf = { segments: [{ paddr: 0x1000_0000, data: Buffer.from([0xfe, 0xe7]) }] };
  const m = new Machine({ bootrom: new Uint32Array(4096), elf, onByte: () => {} });
  const bus = (c) => ({
    r: (a) => m.slots[c].bus.readUint32(a),
    w: (a, v) => m.slots[c].bus.writeUint32(a, v),
  });
  return { m, c0: bus(0), c1: bus(1) };
}
const pending = (m, c, irq) => (m.core(c).pendingInterrupts >>> irq) & 1;

test('CPUID is 0 on core 0 and 1 on core 1', () => {
  const { c0, c1 } = machine();
  assert.equal(c0.r(CPUID), 0);
  assert.equal(c1.r(CPUID), 1);
});

test('FIFOs: 8 words each way, VLD/RDY, WOF on a write to a full FIFO, ROE on a read of an empty one', () => {
  const { m, c0, c1 } = machine();
  assert.equal(c0.r(FIFO_ST), RDY); // empty RX, room in TX
  assert.equal(c1.r(FIFO_ST), RDY);
  for (let i = 0; i < 8; i++) {
    assert.equal(c0.r(FIFO_ST) & RDY, RDY);
    c0.w(FIFO_WR, 0x100 + i);
  }
  assert.equal(c0.r(FIFO_ST), 0); // full: no RDY; its own RX still empty
  assert.equal(c1.r(FIFO_ST), VLD | RDY);
  c0.w(FIFO_WR, 0xdead); // lost
  assert.equal(c0.r(FIFO_ST), WOF);
  // The other direction is independent.
  c1.w(FIFO_WR, 0x77);
  assert.equal(c0.r(FIFO_ST), WOF | VLD);
  assert.equal(c0.r(FIFO_RD), 0x77);
  // Core 1 reads the eight words in order; a ninth read finds the FIFO empty.
  const got = [];
  while (c1.r(FIFO_ST) & VLD) got.push(c1.r(FIFO_RD));
  assert.deepEqual(got, [0x100, 0x101, 0x102, 0x103, 0x104, 0x105, 0x106, 0x107]);
  assert.equal(c1.r(FIFO_ST), RDY);
  assert.equal(c1.r(FIFO_RD), 0);
  assert.equal(c1.r(FIFO_ST), RDY | ROE);
  assert.equal(c0.r(FIFO_ST), WOF | RDY); // the sticky flags are per core
  // Write 1 to clear: a 0 in the bit leaves it, each core clears only its own flags.
  c1.w(FIFO_ST, WOF);
  assert.equal(c1.r(FIFO_ST), RDY | ROE);
  c1.w(FIFO_ST, ROE);
  assert.equal(c1.r(FIFO_ST), RDY);
  assert.equal(c0.r(FIFO_ST), WOF | RDY);
  c0.w(FIFO_ST, 0xff);
  assert.equal(c0.r(FIFO_ST), RDY);
  // FIFO_ST's other bits are read-only: writing them changes nothing.
  c0.w(FIFO_ST, VLD | RDY);
  assert.equal(c0.r(FIFO_ST), RDY);
  assert.equal(m.sioShared.fifo[0].length + m.sioShared.fifo[1].length, 0);
});

test('SIO IRQs: IRQ 15 on core 0 and IRQ 16 on core 1, each the OR of that core\'s VLD, WOF and ROE', () => {
  const { m, c0, c1 } = machine();
  const state = () => [pending(m, 0, 15), pending(m, 0, 16), pending(m, 1, 15), pending(m, 1, 16)];
  assert.deepEqual(state(), [0, 0, 0, 0]);
  c0.w(FIFO_WR, 1); // data for core 1
  assert.deepEqual(state(), [0, 0, 0, 1]);
  c1.r(FIFO_RD);
  assert.deepEqual(state(), [0, 0, 0, 0]);
  c1.r(FIFO_RD); // ROE on core 1
  assert.deepEqual(state(), [0, 0, 0, 1]);
  c1.w(FIFO_ST, ROE);
  assert.deepEqual(state(), [0, 0, 0, 0]);
  c1.w(FIFO_WR, 2); // data for core 0
  assert.deepEqual(state(), [1, 0, 0, 0]);
  c0.r(FIFO_RD);
  for (let i = 0; i < 9; i++) c0.w(FIFO_WR, i); // WOF on core 0, VLD on core 1
  assert.deepEqual(state(), [1, 0, 0, 1]);
  c0.w(FIFO_ST, WOF);
  assert.deepEqual(state(), [0, 0, 0, 1]);
});

test('spinlocks: shared by the cores, a read claims (0 while held), a write releases', () => {
  const { c0, c1 } = machine();
  assert.equal(c0.r(SPINLOCK(5)), 1 << 5);
  assert.equal(c1.r(SPINLOCK(5)), 0); // held by core 0
  assert.equal(c0.r(SPINLOCK(5)), 0); // a second claim fails too, on either core
  assert.equal(c1.r(SPINLOCK(31)), 0x8000_0000);
  assert.equal(c0.r(SPINLOCK_ST), (0x8000_0020 >>> 0));
  assert.equal(c1.r(SPINLOCK_ST), (0x8000_0020 >>> 0));
  c0.w(SPINLOCK(5), 0); // any value releases
  assert.equal(c1.r(SPINLOCK_ST), 0x8000_0000);
  assert.equal(c1.r(SPINLOCK(5)), 1 << 5);
  c1.w(SPINLOCK(5), 1);
  c0.w(SPINLOCK(31), 0); // a core may release a lock the other claimed
  assert.equal(c0.r(SPINLOCK_ST), 0);
});

test('each core has its own divider: exact quotients, the datasheet values for division by zero', () => {
  const { c0, c1 } = machine();
  const start = (c, signed, n, d) => {
    c.w(SIO + (signed ? 0x68 : 0x60), n);
    c.w(SIO + (signed ? 0x6c : 0x64), d);
  };
  const result = (c) => [c.r(SIO + 0x74), c.r(SIO + 0x70)]; // remainder first, quotient last
  start(c0, false, 100, 7);
  start(c1, true, -9 >>> 0, 2);
  assert.equal(c0.r(SIO + 0x78), 3); // READY | DIRTY
  assert.deepEqual(result(c0), [2, 14]);
  assert.equal(c0.r(SIO + 0x78), 1); // reading the quotient cleared DIRTY
  assert.equal(c1.r(SIO + 0x78), 3); // core 1's divider is untouched by core 0's reads
  assert.deepEqual(result(c1), [-1 >>> 0, -4 >>> 0]);
  start(c0, true, 0x8000_0000, -1 >>> 0);
  assert.deepEqual(result(c0), [0, 0x8000_0000]);
  start(c1, true, 5, 0);
  assert.deepEqual(result(c1), [5, 0xffff_ffff]);
  start(c1, true, -5 >>> 0, 0);
  assert.deepEqual(result(c1), [-5 >>> 0, 1]);
  start(c0, false, 0, 0);
  assert.deepEqual(result(c0), [0, 0xffff_ffff]);
  // A context restore (rp2040-hal's save_divider) writes the results back.
  c1.w(SIO + 0x74, 11);
  c1.w(SIO + 0x70, 22);
  assert.deepEqual(result(c1), [11, 22]);
  assert.deepEqual(result(c0), [0, 0xffff_ffff]);
});

test('each core has its own INTERP0 and INTERP1', () => {
  const { c0, c1 } = machine();
  const ACCUM0 = 0x80;
  const BASE0 = 0x88;
  const PEEK_LANE0 = 0xa0;
  const CTRL_LANE0 = 0xac;
  for (const [c, k] of [[c0, 1], [c1, 2]]) {
    for (const interp of [0, 0x40]) {
      c.w(SIO + interp + CTRL_LANE0, 0x1f << 10); // MASK_MSB 31, no shift
      c.w(SIO + interp + ACCUM0, 100 * k + interp);
      c.w(SIO + interp + BASE0, 7 * k);
    }
  }
  assert.equal(c0.r(SIO + PEEK_LANE0), 100 + 7);
  assert.equal(c0.r(SIO + 0x40 + PEEK_LANE0), 100 + 0x40 + 7);
  assert.equal(c1.r(SIO + PEEK_LANE0), 200 + 14);
  assert.equal(c1.r(SIO + 0x40 + PEEK_LANE0), 200 + 0x40 + 14);
  assert.equal(c0.r(SIO + ACCUM0), 100);
  assert.equal(c1.r(SIO + ACCUM0), 200);
});

test('an SIO or PPB register the harness does not model is a HarnessError, not a silent value', () => {
  const { c0, c1 } = machine();
  const fails = (f, re) => assert.throws(f, (e) => e instanceof HarnessError && re.test(e.message));
  fails(() => c1.r(SIO + 0x07c), /core 1 read SIO register 0xd000007c/);
  fails(() => c0.r(SIO + 0x180), /core 0 read SIO register 0xd0000180/);
  fails(() => c1.w(CPUID, 1), /core 1 wrote to SIO register 0xd0000000/);
  fails(() => c1.r(0xe000_ed0c), /core 1 read PPB register 0xe000ed0c/); // AIRCR
  fails(() => c1.w(0xe000_ed10, 0x10), /SEVONPEND/);
  // SCR.SLEEPDEEP and the MPU (rp2040-hal's stack guard) are plain registers on both cores.
  for (const c of [c0, c1]) {
    c.w(0xe000_ed10, 4);
    assert.equal(c.r(0xe000_ed10), 4);
    assert.equal(c.r(0xe000_ed94), 0); // MPU_CTRL: rp2040-hal traps unless it reads 0
    c.w(0xe000_ed94, 5);
    c.w(0xe000_ed9c, 0x2000_1000 | 0x10 | 3); // RBAR with VALID: region 3
    assert.equal(c.r(0xe000_ed98), 3);
    assert.equal(c.r(0xe000_ed9c), 0x2000_1003);
  }
});
