// The frame comparison, the label-time rule and the BENCHMARKS.md block.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { compareFrames, labelMicrosPerFrame, readHostFrame, FRAME_BYTES } from '../lib/frames.mjs';
import { rgb565ToRgb888 } from '../lib/image.mjs';
import { updateBenchmarks, START_MARKER, END_MARKER } from '../lib/report.mjs';

const frame = () => Uint16Array.from({ length: 240 * 240 }, (_, i) => (i * 2654435761) >>> 16);

test('a frame equals itself', () => {
  const f = frame();
  assert.deepEqual(compareFrames(f, f.slice()), { differing: 0, first: null });
});

test('an altered copy differs: count and first pixel', () => {
  const f = frame();
  const g = f.slice();
  g[240 * 17 + 3] ^= 1;
  g[240 * 200 + 100] = ~g[240 * 200 + 100] & 0xffff;
  const c = compareFrames(g, f);
  assert.equal(c.differing, 2);
  assert.deepEqual(c.first, { x: 3, y: 17, emulator: g[240 * 17 + 3], host: f[240 * 17 + 3] });
});

test('host frames are read big-endian and must be exactly 115200 bytes', () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'pico-emu-'));
  const buf = Buffer.alloc(FRAME_BYTES);
  buf.writeUInt16BE(0xf800, 0);
  buf.writeUInt16BE(0x001f, FRAME_BYTES - 2);
  fs.writeFileSync(path.join(dir, 'a.bin'), buf);
  const f = readHostFrame(path.join(dir, 'a.bin'));
  assert.equal(f[0], 0xf800);
  assert.equal(f[240 * 240 - 1], 0x001f);
  fs.writeFileSync(path.join(dir, 'b.bin'), buf.subarray(1));
  assert.throws(() => readHostFrame(path.join(dir, 'b.bin')), /115199 bytes/);
});

test('label times: frame 0 none, frame K the difference of the reads before frames K and K-1', () => {
  const frames = [1000, 25_000, 49_500].map((value) => ({ timerBefore: { value } }));
  assert.deepEqual(labelMicrosPerFrame(frames), [0, 24_000, 24_500]);
  assert.throws(() => labelMicrosPerFrame([{ timerBefore: null }, { timerBefore: { value: 1 } }]));
});

test('RGB565 to RGB888 rounds c*255/31 and c*255/63', () => {
  assert.deepEqual(rgb565ToRgb888(0xffff), [255, 255, 255]);
  assert.deepEqual(rgb565ToRgb888(0x0000), [0, 0, 0]);
  assert.deepEqual(rgb565ToRgb888((1 << 11) | (1 << 5) | 16), [8, 4, 132]);
});

test('BENCHMARKS.md: the block is appended once, then replaced in place', () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'pico-emu-'));
  const p = path.join(dir, 'B.md');
  fs.writeFileSync(p, '# Benchmarks\n\ntext\n');
  const block = (x) => `${START_MARKER}\n${x}\n${END_MARKER}`;
  updateBenchmarks(p, block('one'));
  assert.equal(fs.readFileSync(p, 'utf8'), `# Benchmarks\n\ntext\n\n${block('one')}\n`);
  updateBenchmarks(p, block('two'));
  assert.equal(fs.readFileSync(p, 'utf8'), `# Benchmarks\n\ntext\n\n${block('two')}\n`);
});

test('a block with markers of its own goes after another block, then is replaced in place', () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'pico-emu-'));
  const p = path.join(dir, 'B.md');
  const pico = `${START_MARKER}\npico\n${END_MARKER}`;
  fs.writeFileSync(p, `# Benchmarks\n\n${pico}\n\n## Later\n`);
  const markers = { start: '<!-- e:start -->', end: '<!-- e:end -->', after: END_MARKER };
  const block = (x) => `${markers.start}\n${x}\n${markers.end}`;
  updateBenchmarks(p, block('one'), markers);
  assert.equal(fs.readFileSync(p, 'utf8'), `# Benchmarks\n\n${pico}\n\n${block('one')}\n\n## Later\n`);
  updateBenchmarks(p, block('two'), markers);
  assert.equal(fs.readFileSync(p, 'utf8'), `# Benchmarks\n\n${pico}\n\n${block('two')}\n\n## Later\n`);
  // The pico-emu block is still found and replaced by the default markers.
  updateBenchmarks(p, `${START_MARKER}\nnew\n${END_MARKER}`);
  assert.match(fs.readFileSync(p, 'utf8'), /pico-emu:start -->\nnew\n.*\n\n<!-- e:start -->\ntwo/s);
});
