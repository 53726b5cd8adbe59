// Core 1 running programs next to core 0: the launch handshake (through a stand-in boot ROM and,
// when scripts/pico-emu has fetched it, the real B1 ROM), spinlock contention, an interrupt that
// reaches only the core that enabled it, idle accounting and determinism. The programs are
// hand-assembled Thumb; each array's comment is its source (llvm-mc, thumbv6m).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { Machine } from '../lib/machine.mjs';
import { CORE1_RELEASE_CYCLES } from '../lib/cores.mjs';

const RAM = 0x2000_0000;

/** An ELF segment holding Thumb halfwords at `paddr`. */
function seg(paddr, halfwords) {
  const data = Buffer.alloc(halfwords.length * 2);
  halfwords.forEach((h, i) => data.writeUInt16LE(h, i * 2));
  return { paddr, data };
}
/** Word `value` at `paddr` (a vector-table entry). */
const word = (paddr, value) => {
  const data = Buffer.alloc(4);
  data.writeUInt32LE(value >>> 0);
  return { paddr, data };
};

/** A stand-in boot ROM: SP 0x20041f00, reset vector `reset`, `code` at ROM address 0x100. */
function standInRom(reset, code = []) {
  const rom = new Uint32Array(4096);
  rom[0] = 0x2004_1f00;
  rom[1] = reset;
  const v = new DataView(rom.buffer);
  code.forEach((h, i) => v.setUint16(0x100 + 2 * i, h, true));
  return rom;
}

function machine(rom, segments, core1Boot) {
  const m = new Machine({ bootrom: rom, elf: { segments }, onByte: () => {}, core1Boot });
  m.bootAtBoot2(); // core 0 starts at 0x10000000
  return m;
}
const read = (m, a) => m.rp2040.readUint32(a);

// Core 0 at 0x10000000: rp2040-hal's Multicore::spawn, minus the stack set-up. Resets core 1
// (PSM FRCE_OFF.PROC1 set, read back, cleared), then sends 0, 0, 1, vector table 0x10000400,
// SP 0x20001000, entry 0x10000201, each echoed by core 1 (a mismatch starts over); drains its RX
// FIFO and SEVs before each 0, SEVs after each write, WFEs while waiting for the echo.
//      ldr r0, =0x40012004 ; ldr r1, =0x10000 ; str r1, [r0]      @ FRCE_OFF set alias: PROC1
//      ldr r2, =0x40010004
// 1:   ldr r3, [r2] ; tst r3, r1 ; beq 1b
//      ldr r0, =0x40013004 ; str r1, [r0]                        @ clear alias: release core 1
//      ldr r4, =0xd0000000 ; adr r5, cmds ; movs r6, #0
// next: lsls r0, r6, #2 ; ldr r7, [r5, r0] ; cmp r7, #0 ; bne send
// drain: ldr r0, [r4, #0x50] ; lsrs r0, r0, #1 ; bcc drained ; ldr r0, [r4, #0x58] ; b drain
// drained: sev
// send: ldr r0, [r4, #0x50] ; lsrs r0, r0, #2 ; bcc send ; str r7, [r4, #0x54] ; sev
// recv: ldr r0, [r4, #0x50] ; lsrs r0, r0, #1 ; bcs got ; wfe ; b recv
// got:  ldr r0, [r4, #0x58] ; cmp r0, r7 ; bne restart ; adds r6, #1 ; cmp r6, #6 ; bne next
// done: nop ; b done                                             @ 0x1000004c
// restart: movs r6, #0 ; b next
// cmds: .word 0, 0, 1, 0x10000400, 0x20001000, 0x10000201 ; literal pool
const LAUNCH_CORE0 = [
  0x481a, 0x491b, 0x6001, 0x4a1b, 0x6813, 0x420b, 0xd0fc, 0x481a, 0x6001, 0x4c1a, 0xa50f, 0x2600,
  0x00b0, 0x582f, 0x2f00, 0xd105, 0x6d20, 0x0840, 0xd301, 0x6da0, 0xe7fa, 0xbf40, 0x6d20, 0x0880,
  0xd3fc, 0x6567, 0xbf40, 0x6d20, 0x0840, 0xd201, 0xbf20, 0xe7fa, 0x6da0, 0x42b8, 0xd104, 0x3601,
  0x2e06, 0xd1e5, 0xbf00, 0xe7fd, 0x2600, 0xe7e1, 0x0000, 0x0000, 0x0000, 0x0000, 0x0001, 0x0000,
  0x0400, 0x1000, 0x1000, 0x2000, 0x0201, 0x1000, 0x2004, 0x4001, 0x0000, 0x0001, 0x0004, 0x4001,
  0x3004, 0x4001, 0x0000, 0xd000,
];
const LAUNCH_DONE = 0x1000_004c;

// Core 1's entry at 0x10000200: writes CPUID, SP and VTOR to 0x20000100.. and 0xab as a flag,
// then sleeps.
//      ldr r0, =0xd0000000 ; ldr r1, [r0] ; ldr r2, =0x20000100 ; str r1, [r2]
//      mov r3, sp ; str r3, [r2, #4]
//      ldr r0, =0xe000ed08 ; ldr r3, [r0] ; str r3, [r2, #8]
//      movs r3, #0xab ; str r3, [r2, #12]
// 1:   wfe ; b 1b
const CORE1_ENTRY = [
  0x4806, 0x6801, 0x4a06, 0x6011, 0x466b, 0x6053, 0x4805, 0x6803, 0x6093, 0x23ab, 0x60d3, 0xbf20,
  0xe7fd, 0x0000, 0x0000, 0xd000, 0x0100, 0x2000, 0xed08, 0xe000,
];

// The stand-in ROM's core-1 side of the handshake (written for these tests from the datasheet's
// description, not the ROM's code), at ROM 0x100: pop a word (WFE while none), echo it (SEV);
// words 0 and 1 must be 0 and word 2 must be 1, else start over; after six words set VTOR and
// MSP from words 3 and 4 and branch to word 5. Words are kept at 0x20040000.
//      ldr r4, =0xd0000000 ; ldr r5, =0x20040000
// restart: movs r6, #0
// pop:  ldr r0, [r4, #0x50] ; lsrs r0, r0, #1 ; bcs got ; wfe ; b pop
// got:  ldr r7, [r4, #0x58]
// push: ldr r0, [r4, #0x50] ; lsrs r0, r0, #2 ; bcc push ; str r7, [r4, #0x54] ; sev
//      cmp r6, #2 ; bhi keep ; movs r0, #0 ; cmp r6, #2 ; bne check ; movs r0, #1
// check: cmp r7, r0 ; bne restart
// keep: lsls r0, r6, #2 ; str r7, [r5, r0] ; adds r6, #1 ; cmp r6, #6 ; bne pop
//      ldr r0, [r5, #12] ; ldr r1, =0xe000ed08 ; str r0, [r1]
//      ldr r0, [r5, #16] ; msr msp, r0 ; ldr r0, [r5, #20] ; bx r0
const STAND_IN_ROM_CORE1 = [
  0x4c11, 0x4d12, 0x2600, 0x6d20, 0x0840, 0xd201, 0xbf20, 0xe7fa, 0x6da7, 0x6d20, 0x0880, 0xd3fc,
  0x6567, 0xbf40, 0x2e02, 0xd805, 0x2000, 0x2e02, 0xd100, 0x2001, 0x4287, 0xd1eb, 0x00b0, 0x502f,
  0x3601, 0x2e06, 0xd1e7, 0x68e8, 0x4905, 0x6008, 0x6928, 0xf380, 0x8808, 0x6968, 0x4700, 0x0000,
  0x0000, 0xd000, 0x0000, 0x2004, 0xed08, 0xe000,
];

/** The real B1 boot ROM, if scripts/pico-emu has fetched it (it is never committed). */
function realRom() {
  const file = new URL('../../../target/pico-emu/bootrom.bin', import.meta.url);
  if (!fs.existsSync(file)) return null;
  const b = fs.readFileSync(file);
  return b.length === 16384 ? new Uint32Array(b.buffer.slice(b.byteOffset, b.byteOffset + 16384)) : null;
}

/** Runs the launch program until core 1 has set its flag and core 0 sits in its done loop. */
function launch(rom) {
  const m = machine(rom, [seg(0x1000_0000, LAUNCH_CORE0), seg(0x1000_0200, CORE1_ENTRY)]);
  const atDone = (pc) => pc === LAUNCH_DONE || pc === LAUNCH_DONE + 2;
  m.run({ maxCycles: 100_000, done: () => read(m, RAM + 0x10c) === 0xab && atDone(m.core(0).PC) });
  return m;
}

function checkLaunched(m) {
  assert.equal(read(m, RAM + 0x100), 1, 'the entry ran on core 1 (CPUID 1)');
  assert.equal(read(m, RAM + 0x104), 0x2000_1000, 'with the stack pointer sent');
  assert.equal(read(m, RAM + 0x108), 0x1000_0400, 'and VTOR set to the vector table sent');
  assert.equal(m.slots[1].launches >= 1, true);
  // Core 0 slept in WFE while it waited for the echoes: those cycles are not busy ones.
  const [s0] = m.slots;
  assert.ok(s0.busy < m.cycles, `core 0 busy ${s0.busy} of ${m.cycles} cycles`);
  assert.ok(m.cycles > CORE1_RELEASE_CYCLES);
}

test('launch through a stand-in ROM: PSM reset, the six-word handshake, entry on core 1', () => {
  const rom = standInRom(0x101, STAND_IN_ROM_CORE1);
  const m = launch(rom);
  checkLaunched(m);
  assert.equal(m.slots[1].launches, 1); // held in reset until the PSM write (no ROM header)
});

test('launch through the real B1 boot ROM (core 1 parked in the ROM since power-on)', (t) => {
  const rom = realRom();
  if (!rom) {
    t.skip('target/pico-emu/bootrom.bin is absent (scripts/pico-emu fetches it)');
    return;
  }
  const m = launch(rom);
  checkLaunched(m);
  assert.equal(m.slots[1].launches, 2); // at power-on, then after the PSM reset
  // The ROM sets SCR.SLEEPDEEP while it waits and clears it before the jump.
  assert.equal(m.slots[1].bus.ppb.coreRegs.scr, 0);
});

test('a core asleep in WFE is idle: its busy count stands still while time goes on', () => {
  const m = launch(standInRom(0x101, STAND_IN_ROM_CORE1));
  const [s0, s1] = m.slots;
  m.run({ maxCycles: 200_000, done: () => m.coreStats()[1].state === 'asleep (wfe)' });
  const busy0 = s0.busy;
  const busy1 = s1.busy;
  const t = m.cycles;
  m.run({ maxCycles: t + 5000, done: () => m.cycles >= t + 4000 });
  assert.equal(s1.busy, busy1, 'core 1 slept');
  assert.equal(s0.busy - busy0, m.cycles - t, 'core 0 ran (its done loop) all the time');
  assert.equal(m.coreStats()[1].state, 'asleep (wfe)');
});

// Both cores run this from 0x10000000 (core 1 from the stand-in ROM's reset vector): 200 times
// claim spinlock 7 (counting failed claims per core), add 1 to the shared counter at 0x20000000
// with a load and a store, release; then set a per-core done flag.
//      ldr r0, =0xd000011c ; ldr r1, =0x20000000 ; ldr r5, =0xd0000000 ; ldr r5, [r5]
//      lsls r5, r5, #2 ; adds r5, r1, r5 ; movs r2, #200            @ r5 = 0x20000000 + 4 * CPUID
// loop: ldr r3, [r0] ; cmp r3, #0 ; bne locked
//      ldr r3, [r5, #4] ; adds r3, #1 ; str r3, [r5, #4] ; b loop   @ failed claims at 0x20000004 + 4 * CPUID
// locked: ldr r3, [r1] ; adds r3, #1 ; str r3, [r1] ; str r3, [r0] ; subs r2, #1 ; bne loop
//      movs r3, #1 ; str r3, [r5, #12]                              @ done flag at 0x2000000c + 4 * CPUID
// end: nop ; b end
const SPIN = [
  0x480b, 0x490c, 0x4d0c, 0x682d, 0x00ad, 0x194d, 0x22c8, 0x6803, 0x2b00, 0xd103, 0x686b, 0x3301,
  0x606b, 0xe7f8, 0x680b, 0x3301, 0x600b, 0x6003, 0x3a01, 0xd1f2, 0x2301, 0x60eb, 0xbf00, 0xe7fd,
  0x011c, 0xd000, 0x0000, 0x2000, 0x0000, 0xd000,
];

function spin() {
  const m = machine(standInRom(0x1000_0001), [seg(0x1000_0000, SPIN)], true);
  m.run({ maxCycles: 100_000, done: () => read(m, RAM + 0xc) === 1 && read(m, RAM + 0x10) === 1 });
  return m;
}

test('spinlock contention: two cores, 200 locked increments each, none lost', () => {
  const m = spin();
  assert.equal(read(m, RAM), 400);
  const failed = [read(m, RAM + 4), read(m, RAM + 8)];
  assert.ok(failed[0] + failed[1] > 0, `the cores contended (failed claims ${failed})`);
  assert.ok(m.slots[0].busy > 0 && m.slots[1].busy > 0);
});

// Core 0 (0x10000000) points VTOR at its table (0x10000300, IRQ 0 -> handler0) and loops; core 1
// (0x10000100, from the stand-in ROM's reset vector) points VTOR at its table (0x10000380, IRQ 0
// -> handler1), enables IRQ 0 (TIMER alarm 0) in its own NVIC, arms alarm 0 for 5 us on, WFIs.
// Each handler clears the alarm's interrupt and counts: handler0 at 0x20000010, handler1 at
// 0x20000014.
//   core0:    ldr r0, =0xe000ed08 ; ldr r1, =0x10000300 ; str r1, [r0] ; 1: nop ; b 1b
//   core1:    ldr r0, =0xe000ed08 ; ldr r1, =0x10000380 ; str r1, [r0]
//             ldr r0, =0xe000e100 ; movs r1, #1 ; str r1, [r0]           @ NVIC_ISER: IRQ 0
//             ldr r0, =0x40054000 ; str r1, [r0, #0x38]                   @ TIMER INTE: alarm 0
//             ldr r2, [r0, #0x28] ; adds r2, #5 ; str r2, [r0, #0x10]     @ ALARM0 = TIMERAWL + 5
//             1: wfi ; b 1b
//   handler1: ldr r0, =0x40054000 ; movs r1, #1 ; str r1, [r0, #0x34]     @ INTR: clear alarm 0
//             ldr r0, =0x20000014 ; ldr r1, [r0] ; adds r1, #1 ; str r1, [r0] ; bx lr
//   handler0: ldr r0, =0x20000010 ; ldr r1, [r0] ; adds r1, #1 ; str r1, [r0] ; bx lr
const IRQ_CORE0 = [0x4802, 0x4903, 0x6001, 0xbf00, 0xe7fd, 0x0000, 0xed08, 0xe000, 0x0300, 0x1000];
const IRQ_CORE1 = [
  0x4806, 0x4907, 0x6001, 0x4807, 0x2101, 0x6001, 0x4806, 0x6381, 0x6a82, 0x3205, 0x6102, 0xbf30,
  0xe7fd, 0x0000, 0xed08, 0xe000, 0x0380, 0x1000, 0xe100, 0xe000, 0x4000, 0x4005,
];
const HANDLER1 = [0x4803, 0x2101, 0x6341, 0x4803, 0x6801, 0x3101, 0x6001, 0x4770, 0x4000, 0x4005, 0x0014, 0x2000];
const HANDLER0 = [0x4802, 0x6801, 0x3101, 0x6001, 0x4770, 0x0000, 0x0010, 0x2000];

test('a peripheral interrupt reaches both NVICs but only the core that enabled it takes it', () => {
  const m = machine(
    standInRom(0x1000_0101),
    [
      seg(0x1000_0000, IRQ_CORE0),
      seg(0x1000_0100, IRQ_CORE1),
      seg(0x1000_0200, HANDLER1),
      seg(0x1000_0240, HANDLER0),
      word(0x1000_0300 + 4 * 16, 0x1000_0241),
      word(0x1000_0380 + 4 * 16, 0x1000_0201),
    ],
    true,
  );
  let core0InHandler = false;
  let sawPendingOnCore0 = false;
  m.run({
    maxCycles: 10_000,
    done: () => read(m, RAM + 0x14) === 1 && m.cycles > 2000,
    onStep: (core, pc) => {
      if (core === 0 && pc >= 0x1000_0240 && pc < 0x1000_0250) core0InHandler = true;
      if (m.core(0).pendingInterrupts & 1) sawPendingOnCore0 = true;
    },
  });
  assert.equal(read(m, RAM + 0x14), 1, 'core 1 took the alarm interrupt once');
  assert.equal(read(m, RAM + 0x10), 0, 'core 0 did not');
  assert.equal(core0InHandler, false);
  assert.equal(sawPendingOnCore0, true, 'the line was pending on core 0 too, not enabled there');
  assert.equal(m.core(0).enabledInterrupts, 0);
  assert.equal(m.coreStats()[1].state, 'asleep (wfi)');
});

test('a firmware that leaves core 1 alone runs to the same cycle whether core 1 sleeps in the ROM or is in reset', () => {
  // Core 1's reset code in the stand-in ROM: wfe ; b .-2 (where the real ROM's wait loop is).
  const rom = standInRom(0x101, [0xbf20, 0xe7fd]);
  const runOnce = (core1Boot) => {
    const m = machine(rom, [seg(0x1000_0000, SPIN)], core1Boot);
    m.run({ maxCycles: 100_000, done: () => read(m, RAM + 0xc) === 1 });
    return [m.cycles, m.slots[0].busy, read(m, RAM), m.coreStats()[1].state];
  };
  const asleep = runOnce(true);
  const reset = runOnce(false);
  assert.equal(asleep[3], 'asleep (wfe)');
  assert.equal(reset[3], 'reset');
  assert.deepEqual(asleep.slice(0, 3), reset.slice(0, 3));
  assert.equal(asleep[2], 200);
});

test('determinism: two runs give the same cycles, per core, to the cycle', () => {
  const fingerprint = (m) => [m.cycles, ...m.slots.map((s) => s.busy), read(m, RAM + 4), read(m, RAM + 8)];
  assert.deepEqual(fingerprint(spin()), fingerprint(spin()));
  const rom = standInRom(0x101, STAND_IN_ROM_CORE1);
  const a = launch(rom);
  const b = launch(rom);
  assert.deepEqual([a.cycles, a.slots[0].busy, a.slots[1].busy], [b.cycles, b.slots[0].busy, b.slots[1].busy]);
});

test('SEV from core 0 wakes core 1 from WFE, not from WFI (which keeps the event for its next WFE)', () => {
  // Core 0: nop x 4 ; sev ; 1: nop ; b 1b. Core 1 (the stand-in ROM's reset code): wfe (or wfi) ; b .-2
  const core0 = [0xbf00, 0xbf00, 0xbf00, 0xbf00, 0xbf40, 0xbf00, 0xe7fd];
  const run = (sleep) => {
    const m = machine(standInRom(0x101, [sleep, 0xe7fd]), [seg(0x1000_0000, core0)], true);
    m.run({ maxCycles: 1000, done: () => m.cycles >= 100 });
    return m;
  };
  const wfe = run(0xbf20);
  // Asleep from cycle 2, woken by the SEV at cycle 4 (the event is consumed), then b and wfe: asleep.
  assert.equal(wfe.slots[1].busy, 2 + 2 + 2);
  assert.equal(wfe.coreStats()[1].state, 'asleep (wfe)');
  const wfi = run(0xbf30);
  assert.equal(wfi.slots[1].busy, 2);
  assert.equal(wfi.coreStats()[1].state, 'asleep (wfi)');
  assert.equal(wfi.core(1).eventRegistered, true);
});
