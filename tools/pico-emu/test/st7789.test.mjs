// The ST7789 decoder on hand-made byte streams.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { St7789, DecodeError, GRAM_W } from '../lib/st7789.mjs';

/** Feeds [dc, byte] pairs; returns the frames produced. */
function feed(d, items) {
  let cycle = 0;
  for (const [dc, v] of items) {
    d.byte(v, dc, cycle, cycle + 16);
    cycle += 16;
  }
}
const cmd = (c, ...params) => [[false, c], ...params.map((p) => [true, p])];
const window = (xs, xe, ys, ye) => [
  ...cmd(0x2a, xs >> 8, xs & 0xff, xe >> 8, xe & 0xff),
  ...cmd(0x2b, ys >> 8, ys & 0xff, ye >> 8, ye & 0xff),
];
const pixels = (list) => list.flatMap((p) => [[true, p >> 8], [true, p & 0xff]]);
const init = [...cmd(0x11), ...cmd(0x36, 0), ...cmd(0x21), ...cmd(0x3a, 0x55), ...cmd(0x13), ...cmd(0x29)];

test('a full 240x240 write is one frame, RGB565 big-endian, row-major', () => {
  const frames = [];
  const d = new St7789({ onFrame: (f) => frames.push(f) });
  const px = Array.from({ length: 240 * 240 }, (_, i) => (i * 7919) & 0xffff);
  feed(d, [...init, ...window(0, 239, 0, 239), ...cmd(0x2c), ...pixels(px)]);
  d.end();
  assert.equal(frames.length, 1);
  assert.deepEqual(Array.from(frames[0].pixels), px);
  assert.equal(frames[0].inverted, true);
  assert.equal(frames[0].displayOn, true);
  // The first pixel byte starts the frame; the last byte of the last pixel ends it.
  const n = init.length + 10 + 1;
  assert.equal(frames[0].firstByteCycle, n * 16);
  assert.equal(frames[0].doneCycle, (n + px.length * 2) * 16);
});

test('line by line, one window per line, as mipidsi draws; RAMWRC continues', () => {
  const frames = [];
  const d = new St7789({ onFrame: (f) => frames.push(f) });
  feed(d, init);
  for (let y = 0; y < 240; y++) {
    const line = Array.from({ length: 240 }, (_, x) => x + y);
    if (y % 2) {
      feed(d, [...window(0, 239, y, y), ...cmd(0x2c), ...pixels(line)]);
    } else {
      feed(d, [...window(0, 239, y, y), ...cmd(0x2c), ...pixels(line.slice(0, 100))]);
      feed(d, [...cmd(0x3c), ...pixels(line.slice(100))]);
    }
  }
  assert.equal(frames.length, 1);
  assert.equal(frames[0].pixels[239 * 240 + 5], 244);
});

test('an unknown command byte fails, naming the byte', () => {
  const d = new St7789();
  assert.throws(() => feed(d, cmd(0x99)), (e) => e instanceof DecodeError && /0x99/.test(e.message));
});

test('pixel data past the window fails, saying how many bytes over', () => {
  const d = new St7789();
  feed(d, [...init, ...window(0, 1, 0, 0), ...cmd(0x2c), ...pixels([1, 2, 3, 4])]);
  assert.throws(() => d.end(), (e) => e instanceof DecodeError && /4 byte\(s\) past/.test(e.message));
  const d2 = new St7789();
  feed(d2, [...init, ...window(0, 1, 0, 0), ...cmd(0x2c), ...pixels([1, 2, 3])]);
  assert.throws(() => feed(d2, cmd(0x29)), /2 byte\(s\) past/);
});

test('pixels need 16-bit COLMOD', () => {
  const d = new St7789();
  assert.throws(() => feed(d, [...window(0, 0, 0, 0), ...cmd(0x2c), ...pixels([1])]), /COLMOD is 0x66/);
});

test('MADCTL: MV exchanges the counters, then MX / MY mirror the physical column / row', () => {
  const d = new St7789();
  feed(d, [...cmd(0x3a, 0x55), ...cmd(0x36, 0x20), ...window(300, 300, 5, 5), ...cmd(0x2c), ...pixels([0xabcd])]);
  assert.equal(d.gram[300 * GRAM_W + 5], 0xabcd);
  feed(d, [...cmd(0x36, 0x60), ...window(300, 300, 5, 5), ...cmd(0x2c), ...pixels([0x1234])]);
  assert.equal(d.gram[300 * GRAM_W + 234], 0x1234);
  feed(d, [...cmd(0x36, 0x80), ...window(7, 7, 0, 0), ...cmd(0x2c), ...pixels([0x5678])]);
  assert.equal(d.gram[319 * GRAM_W + 7], 0x5678);
  // MV: CASET may address up to 319, RASET only up to 239.
  assert.throws(() => feed(d, [...cmd(0x36, 0x20), ...window(0, 0, 0, 240)]), /RASET window 0..240/);
});

test('a hardware reset forgets the pixel format; GRAM is kept', () => {
  const d = new St7789();
  feed(d, [...init, ...window(0, 0, 0, 0), ...cmd(0x2c), ...pixels([0x4242])]);
  d.reset('RST pin');
  assert.equal(d.colmod, 0x66);
  assert.equal(d.gram[0], 0x4242);
});
