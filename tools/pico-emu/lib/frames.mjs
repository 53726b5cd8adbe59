// Frame bookkeeping that depends on the firmware's conventions: the frame time its fps label
// shows, and the comparison with the host's render of the same frame.
import fs from 'node:fs';

export const FRAME_W = 240;
export const FRAME_H = 240;
export const FRAME_BYTES = FRAME_W * FRAME_H * 2;

/**
 * The frame time (us) the firmware's on-screen label shows in each frame, from the timer values
 * the firmware read. The firmware's rule (examples/pico/firmware.rs): it reads the 64-bit timer
 * once before its first frame's geometry and once after drawing each frame's rows (so before the
 * next frame's geometry); frame K's label shows T_K - T_{K-1}; frame 0 shows no label (0).
 *
 * The caller gives each frame its T_K as `timerBefore`: for frame 0 the last read before its first
 * pixel byte, for frame K >= 1 the K-th read after that byte (pico-emu.mjs). Counting reads, not
 * "the last read before frame K's first byte", because the cores draw ahead of the SPI: the read
 * after frame K's rows may come before frame K's first byte goes out. Adapt this function and that
 * assignment together if the rule changes.
 *
 * @param {Array<{timerBefore: {value:number}|null}>} frames in order, from frame 0
 * @returns {number[]} us per frame
 */
export function labelMicrosPerFrame(frames) {
  return frames.map((f, k) => {
    if (k === 0) return 0;
    const a = frames[k - 1].timerBefore;
    const b = f.timerBefore;
    if (!a || !b) {
      throw new Error(`frame ${k}: no timer read before its first pixel byte (or frame ${k - 1}'s)`);
    }
    return b.value - a.value;
  });
}

/** Reads a host reference frame: 240x240 RGB565 big-endian, row-major, exactly 115200 bytes. */
export function readHostFrame(path) {
  const buf = fs.readFileSync(path);
  if (buf.length !== FRAME_BYTES) {
    throw new Error(`${path}: ${buf.length} bytes, a frame is ${FRAME_BYTES}`);
  }
  const out = new Uint16Array(FRAME_W * FRAME_H);
  for (let i = 0; i < out.length; i++) out[i] = buf.readUInt16BE(i * 2);
  return out;
}

/**
 * Pixel-for-pixel comparison of two RGB565 frames.
 * @returns {{differing:number, first:null|{x:number, y:number, emulator:number, host:number}}}
 */
export function compareFrames(emu, host, width = FRAME_W) {
  if (emu.length !== host.length) throw new Error('frames of different sizes');
  let differing = 0;
  let first = null;
  for (let i = 0; i < emu.length; i++) {
    if (emu[i] !== host[i]) {
      if (!first) first = { x: i % width, y: Math.floor(i / width), emulator: emu[i], host: host[i] };
      differing++;
    }
  }
  return { differing, first };
}

export const hex565 = (v) => `0x${v.toString(16).padStart(4, '0')}`;
