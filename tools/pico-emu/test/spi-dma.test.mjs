// The timed SPI1 and DMA feeding it, driven from register writes (no firmware): each byte takes 16
// cycles at 62.5 MHz, 16-bit frames 32, and a DMA channel paced by DREQ_SPI1_TX is held back by
// the 8-deep TX FIFO.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Machine, NS_PER_CYCLE } from '../lib/machine.mjs';

const SPI1 = 0x4004_0000;
const DMA = 0x5000_0000;
const SIO = 0xd000_0000;
const IO_BANK0 = 0x4001_4000;

function machine() {
  const bytes = [];
  // A firmware image is needed to construct the machine; it is never run here.
  const elf = { segments: [{ paddr: 0x1000_0000, data: Buffer.from([0xfe, 0xe7]) }] };
  const m = new Machine({
    bootrom: new Uint32Array(4096),
    elf,
    onByte: (value, dc, start, end) => bytes.push({ value, dc, start, end }),
  });
  const w = (a, v) => m.rp2040.writeUint32(a, v);
  // GP8 (DC), GP9 (CS), GP12 (RST): SIO outputs; DC high, CS low, RST high.
  for (const p of [8, 9, 12]) w(IO_BANK0 + p * 8 + 4, 5);
  w(SIO + 0x24, (1 << 8) | (1 << 9) | (1 << 12)); // GPIO_OE_SET
  w(SIO + 0x14, (1 << 8) | (1 << 12)); // GPIO_OUT_SET
  return { m, w, bytes };
}

function spiOn(w, dss) {
  w(SPI1 + 0x10, 2); // CPSDVSR 2: 62.5 MHz
  w(SPI1 + 0x00, dss); // SCR 0, Motorola SPI mode 0, DSS
  w(SPI1 + 0x04, 2); // SSE
  w(SPI1 + 0x24, 2); // TXDMAE
}

const run = (m, cycles) => {
  for (let i = 0; i < cycles; i++) m.clock.tick(NS_PER_CYCLE);
};

/** DMA channel `ch`: `count` transfers of `size` (0 = byte, 1 = halfword) from `src` to SPI1. */
function dmaToSpi(w, ch, src, count, size, chainTo = ch, trigger = true) {
  const base = DMA + ch * 0x40;
  w(base + 0x00, src);
  w(base + 0x04, SPI1 + 0x08);
  w(base + 0x08, count);
  const ctrl = 1 | (size << 2) | (1 << 4) | (chainTo << 11) | (18 << 15); // EN, INCR_READ, DREQ_SPI1_TX
  w(base + (trigger ? 0x0c : 0x10), ctrl);
}

test('CPU writes: one byte per 16 cycles, FIFO full after 8 + 1 in the shifter', () => {
  const { m, w, bytes } = machine();
  spiOn(w, 7);
  for (let i = 0; i < 12; i++) w(SPI1 + 0x08, 0x10 + i); // writes to a full FIFO are lost
  assert.equal(m.spi.txFIFO.itemCount, 8);
  const sr = m.rp2040.readUint32(SPI1 + 0x0c);
  assert.equal(sr & 0x12, 0x10); // BSY set, TNF clear
  run(m, 200);
  assert.deepEqual(bytes.map((b) => b.value), [0x10, 0x11, 0x12, 0x13, 0x14, 0x15, 0x16, 0x17, 0x18]);
  assert.deepEqual(bytes.map((b) => b.end), bytes.map((_, i) => 16 * (i + 1)));
  assert.equal(m.rp2040.readUint32(SPI1 + 0x0c) & 0x11, 0x01); // idle: TFE, not BSY
  assert.equal(m.stats.spiBusyCycles, 9 * 16);
});

test('DMA 8-bit, paced by the FIFO: back-to-back bytes, 16 cycles each', () => {
  const { m, w, bytes } = machine();
  spiOn(w, 7);
  const data = Array.from({ length: 40 }, (_, i) => (i * 37) & 0xff);
  m.rp2040.sram.set(data, 0);
  dmaToSpi(w, 0, 0x2000_0000, data.length, 0);
  run(m, 1);
  // One in the shifter, eight in the FIFO: the channel waits for room.
  assert.equal(m.rp2040.dma.channels[0].transCount, data.length - 9);
  run(m, 16 * 10);
  assert.equal(m.rp2040.dma.channels[0].transCount, data.length - 19);
  run(m, 16 * 40);
  assert.deepEqual(bytes.map((b) => b.value), data);
  assert.deepEqual(bytes.map((b) => b.end - b.start), data.map(() => 16));
  for (let i = 1; i < bytes.length; i++) assert.equal(bytes[i].start, bytes[i - 1].end);
});

test('DMA 16-bit frames (DSS 15): two bytes each, most significant first, 32 cycles', () => {
  const { m, w, bytes } = machine();
  spiOn(w, 15);
  const px = [0xf800, 0x07e0, 0x001f, 0x1234];
  px.forEach((p, i) => m.rp2040.sramView.setUint16(i * 2, p, true));
  dmaToSpi(w, 1, 0x2000_0000, px.length, 1);
  run(m, 200);
  assert.deepEqual(bytes.map((b) => b.value), [0xf8, 0x00, 0x07, 0xe0, 0x00, 0x1f, 0x12, 0x34]);
  // Triggered at cycle 0, the channel fills the FIFO at once: frame k ends at 32 (k + 1).
  assert.deepEqual(bytes.filter((_, i) => i % 2).map((b) => b.end), [32, 64, 96, 128]);
});

test('chained channels and a re-triggered channel send in order', () => {
  const { m, w, bytes } = machine();
  spiOn(w, 7);
  m.rp2040.sram.set([1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12], 0);
  dmaToSpi(w, 3, 0x2000_0006, 6, 0, 3, false); // configured, not started
  dmaToSpi(w, 2, 0x2000_0000, 6, 0, 3); // chains to channel 3 when done
  run(m, 16 * 14);
  assert.deepEqual(bytes.map((b) => b.value), [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]);
  // Re-trigger channel 2 from a new address (the strip pattern), no chaining this time.
  m.rp2040.sram.set([0xaa, 0xbb], 0x100);
  dmaToSpi(w, 2, 0x2000_0100, 2, 0, 2, false);
  w(DMA + 2 * 0x40 + 0x1c, 2); // AL1_TRANS_COUNT_TRIG: starts the channel
  run(m, 16 * 6);
  assert.deepEqual(bytes.slice(12).map((b) => b.value), [0xaa, 0xbb]);
});

test('no DMA request without TXDMAE', () => {
  const { m, w, bytes } = machine();
  w(SPI1 + 0x10, 2);
  w(SPI1 + 0x00, 7);
  w(SPI1 + 0x04, 2);
  m.rp2040.sram.set([1, 2, 3], 0);
  dmaToSpi(w, 0, 0x2000_0000, 3, 0);
  run(m, 100);
  assert.equal(bytes.length, 0);
  w(SPI1 + 0x24, 2);
  run(m, 100);
  assert.deepEqual(bytes.map((b) => b.value), [1, 2, 3]);
});

test('DC changing while a byte is shifted out is a failure', () => {
  const { w } = machine();
  spiOn(w, 7);
  w(SPI1 + 0x08, 0x2c);
  assert.throws(() => w(SIO + 0x18, 1 << 8), /DC \(GP8\) changed .* still shifting out 0x2c/);
});

test('CHAN_ABORT reads 0, and setting one bit aborts that channel only', () => {
  const { m, w, bytes } = machine();
  spiOn(w, 7);
  m.rp2040.sram.set([1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20], 0);
  dmaToSpi(w, 1, 0x2000_0000, 20, 0);
  run(m, 16);
  // embassy-rp's Transfer::drop: CHAN_ABORT |= 1 << channel, here for the idle channel 0.
  assert.equal(m.rp2040.readUint32(DMA + 0x444), 0);
  w(DMA + 0x444, m.rp2040.readUint32(DMA + 0x444) | 1);
  run(m, 16 * 25);
  assert.deepEqual(bytes.map((b) => b.value), [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20]);
  assert.ok(!m.logger.summary().some((s) => /0x444/.test(s)), m.logger.summary().join('; '));
});
