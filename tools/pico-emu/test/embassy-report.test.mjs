// The Embassy firmware's BENCHMARKS.md block (embassy-report.mjs): sizes parsing and the table.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { embassyBlock, readSizes, EMBASSY_START, EMBASSY_END } from '../embassy-report.mjs';

const report = (fps, cycles) => ({
  frames: 3,
  fps,
  cycles_per_frame: cycles,
  frame_cycles: [cycles - 10, cycles + 10],
  clock_hz: 125_000_000,
  cores: [{ busy_fraction: 0.5 }],
  spi_busy_fraction: 0.25,
  boot_cycles: 1000,
  matches_host: true,
});

test('sizes: two "flash ram" lines, anything else refused', () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'pico-emu-'));
  const p = path.join(dir, 's');
  fs.writeFileSync(p, '100 200\n300 400\n');
  assert.deepEqual(readSizes(p), [{ flash: 100, ram: 200 }, { flash: 300, ram: 400 }]);
  fs.writeFileSync(p, '100 200\n');
  assert.throws(() => readSizes(p), /1 lines, expected 2/);
  fs.writeFileSync(p, '100 x\n300 400\n');
  assert.throws(() => readSizes(p), /is not "flash ram"/);
});

test('the block: both columns, or "not run" without the one-core report', () => {
  const sizes = [{ flash: 100, ram: 200 }, { flash: 300, ram: 400 }];
  const b = embassyBlock(report(33.88, 3689702), report(35.21, 3549784), sizes);
  assert.ok(b.startsWith(EMBASSY_START) && b.endsWith(EMBASSY_END));
  assert.match(b, /\| frame rate at 125 MHz \(mean of frames 1..n\) \| \*\*33.88 fps\*\* \| 35.21 fps \|/);
  assert.match(b, /\| cycles per frame \(mean\) \| 3689702 \| 3549784 \|/);
  assert.match(b, /\| worst frame \| 3689712 cycles \(33.88 fps\) \| 3549794 cycles/);
  assert.match(b, /\| flash \(bytes\) \| 100 \| 300 \|/);
  assert.match(b, /\| static SRAM \(bytes\) \| 200 \| 400 \|/);
  const bad = { ...report(35.21, 3549784), matches_host: false };
  assert.match(embassyBlock(report(33.88, 3689702), bad, sizes), /\| 3 \| 3 \(not all equal to the host's\) \|/);
  const alone = embassyBlock(report(33.88, 3689702), null, sizes);
  assert.match(alone, /\| cycles per frame \(mean\) \| 3689702 \| not run \|/);
  assert.match(alone, /\| flash \(bytes\) \| 100 \| 300 \|/);
});
