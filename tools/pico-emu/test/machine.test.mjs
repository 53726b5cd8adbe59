// A run always ends: stuck loops, breakpoints, faults, waits with nothing scheduled and the cycle
// bound are failures with a message, never a hang.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Machine, HarnessError } from '../lib/machine.mjs';

/** A machine whose flash holds `code` (Thumb halfwords) at 0x10000000, started there. */
function machineWith(code) {
  const data = Buffer.alloc(code.length * 2);
  code.forEach((h, i) => data.writeUInt16LE(h, i * 2));
  const rom = new Uint32Array(4096);
  rom[0] = 0x2004_1f00;
  const m = new Machine({ bootrom: rom, elf: { segments: [{ paddr: 0x1000_0000, data }] }, onByte: () => {} });
  m.bootAtBoot2();
  return m;
}
const fails = (m, re, opts = {}) =>
  assert.throws(
    () => m.run({ maxCycles: 1e6, done: () => false, ...opts }),
    (e) => e instanceof HarnessError && re.test(e.message),
  );

test('a branch to itself (panic-halt, loop {}) is a failure', () => {
  fails(machineWith([0x46c0, 0xe7fe]), /stuck in a branch to itself at 0x10000002/);
});

test('BKPT is a failure', () => {
  fails(machineWith([0x46c0, 0xbe01]), /breakpoint.*\(code 1\)/);
});

test('entering a trap address (fault or panic handler) is a failure', () => {
  // nop; nop; b 0x10000000 -- loops without ever branching to itself
  const m = machineWith([0x46c0, 0x46c0, 0xe7fc]);
  fails(m, /entered HardFault/, { traps: new Map([[0x1000_0002, 'HardFault']]) });
});

test('the cycle bound ends a loop', () => {
  fails(machineWith([0x46c0, 0xe7fd]), /cycle limit reached \(1000000 cycles\)/);
});

test('WFI with nothing scheduled is a failure', () => {
  fails(machineWith([0xbf30, 0xe7fd]), /waits for an interrupt/);
});

test('a read outside every memory region (a bus fault on the chip) is a failure', () => {
  // movs r0, #0x30; lsls r0, r0, #24 (0x30000000); ldr r1, [r0]
  fails(machineWith([0x2030, 0x0600, 0x6801, 0xe7fe]), /invalid memory address: 30000000/);
});

test('the hardware divider: exact quotients, and the datasheet values for division by zero', () => {
  const m = machineWith([0xe7fe]);
  const sio = 0xd000_0000;
  const div = (u, n, d) => {
    m.rp2040.writeUint32(sio + (u ? 0x60 : 0x68), n);
    m.rp2040.writeUint32(sio + (u ? 0x64 : 0x6c), d);
    return [m.rp2040.readUint32(sio + 0x70), m.rp2040.readUint32(sio + 0x74)];
  };
  assert.deepEqual(div(true, 7, 2), [3, 1]);
  assert.deepEqual(div(false, -7 >>> 0, 2), [-3 >>> 0, -1 >>> 0]);
  assert.deepEqual(div(true, 0xffff_ffff, 16), [0x0fff_ffff, 15]);
  assert.deepEqual(div(false, 0x8000_0000, 0xffff_ffff), [0x8000_0000, 0]);
  assert.deepEqual(div(true, 5, 0), [0xffff_ffff, 5]);
  assert.deepEqual(div(false, 0, 0), [0xffff_ffff, 0]);
  assert.deepEqual(div(false, -5 >>> 0, 0), [1, -5 >>> 0]);
});
