// RGB565 frames to PNG.
//
// PNG writing uses pngjs (pinned in package.json): pure JavaScript with no dependencies and no
// native build step (so `npm ci` works on any machine CI runs on), a synchronous encoder, and
// one of the most widely used and maintained PNG packages on npm.
import fs from 'node:fs';
import pngjs from 'pngjs';

const { PNG } = pngjs;

/** RGB565 to 8-bit RGB: each channel c expanded as round(c * 255 / 31) (green: / 63). */
export function rgb565ToRgb888(c) {
  const r = (c >> 11) & 0x1f;
  const g = (c >> 5) & 0x3f;
  const b = c & 0x1f;
  return [Math.round((r * 255) / 31), Math.round((g * 255) / 63), Math.round((b * 255) / 31)];
}

function encode(width, height, fill) {
  const png = new PNG({ width, height, colorType: 2, inputColorType: 6, inputHasAlpha: true });
  fill(png.data);
  return PNG.sync.write(png, { colorType: 2, inputColorType: 6, inputHasAlpha: true });
}

/** Writes a row-major RGB565 frame as an 8-bit RGB PNG, atomically (temp file, rename). */
export function writeFramePng(path, pixels, width, height) {
  writeAtomic(
    path,
    encode(width, height, (data) => {
      for (let i = 0; i < width * height; i++) {
        const [r, g, b] = rgb565ToRgb888(pixels[i]);
        data.set([r, g, b, 255], i * 4);
      }
    }),
  );
}

/**
 * A diff picture, three panels side by side: the emulator's frame, the host's, and the
 * differences (differing pixels white, equal ones a dim copy of the frame).
 */
export function writeDiffPng(path, emu, host, width, height) {
  writeAtomic(
    path,
    encode(width * 3, height, (data) => {
      for (let y = 0; y < height; y++) {
        for (let x = 0; x < width; x++) {
          const i = y * width + x;
          const a = rgb565ToRgb888(emu[i]);
          const b = rgb565ToRgb888(host[i]);
          const d = emu[i] === host[i] ? a.map((v) => v >> 2) : [255, 255, 255];
          const row = y * width * 3;
          data.set([...a, 255], (row + x) * 4);
          data.set([...b, 255], (row + width + x) * 4);
          data.set([...d, 255], (row + 2 * width + x) * 4);
        }
      }
    }),
  );
}

/** Writes a file through a temporary name and a rename, so a reader never sees half of it. */
export function writeAtomic(path, contents) {
  const tmp = `${path}.tmp-${process.pid}`;
  fs.writeFileSync(tmp, contents);
  fs.renameSync(tmp, path);
}
