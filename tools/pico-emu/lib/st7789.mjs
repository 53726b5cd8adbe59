// ST7789 command-stream decoder: turns the bytes the firmware shifted out on SPI1 (with the level of
// the DC pin when each byte completed) into the controller's GRAM, and snapshots the visible
// 240x240 area each time a pixel lands on its last pixel (a completed frame).
//
// Model of the controller (ST7789V datasheet, 4-line serial interface):
// - a byte with DC low is a command; bytes with DC high are its parameters, or pixel data after
//   RAMWR / RAMWRC;
// - the controller keeps its state (current command, parameter count, address counter) across
//   chip-select pulses: CS high only resets the serial interface's bit counter, which the harness
//   models by dropping a byte during which CS changed (the caller reports that as a failure);
// - GRAM is 240 columns x 320 rows of RGB565, written high byte first (COLMOD 16 bit/pixel);
// - the address counter runs over the CASET columns, then to the next RASET row; MADCTL's MV
//   exchanges the counters' roles, then MX mirrors the physical column and MY the physical row
//   (the same convention as mipidsi's MemoryMapping).

export class DecodeError extends Error {}

export const GRAM_W = 240;
export const GRAM_H = 320;

/**
 * Commands the decoder accepts: every command mipidsi 0.9 sends for
 * `Builder::new(ST7789, di).display_size(240, 240).invert_colors(Inverted).reset_pin(rst)`
 * (SLPOUT, MADCTL, INVON, COLMOD, NORON, DISPON, then CASET, RASET, RAMWR) plus the usual
 * ST7789 initialisation and control commands. `params` is [min, max] parameter bytes; 'pixels'
 * marks the memory writes. Any other command byte is a decoding failure.
 */
export const COMMANDS = new Map([
  [0x01, { name: 'SWRESET', params: [0, 0] }],
  [0x10, { name: 'SLPIN', params: [0, 0] }],
  [0x11, { name: 'SLPOUT', params: [0, 0] }],
  [0x13, { name: 'NORON', params: [0, 0] }],
  [0x20, { name: 'INVOFF', params: [0, 0] }],
  [0x21, { name: 'INVON', params: [0, 0] }],
  [0x28, { name: 'DISPOFF', params: [0, 0] }],
  [0x29, { name: 'DISPON', params: [0, 0] }],
  [0x2a, { name: 'CASET', params: [4, 4] }],
  [0x2b, { name: 'RASET', params: [4, 4] }],
  [0x2c, { name: 'RAMWR', params: 'pixels' }],
  [0x33, { name: 'VSCRDEF', params: [6, 6] }],
  [0x34, { name: 'TEOFF', params: [0, 0] }],
  [0x35, { name: 'TEON', params: [1, 1] }],
  [0x36, { name: 'MADCTL', params: [1, 1] }],
  [0x37, { name: 'VSCSAD', params: [2, 2] }],
  [0x3a, { name: 'COLMOD', params: [1, 1] }],
  [0x3c, { name: 'RAMWRC', params: 'pixels' }],
  [0xb2, { name: 'PORCTRL', params: [5, 5] }],
  [0xb7, { name: 'GCTRL', params: [1, 1] }],
  [0xbb, { name: 'VCOMS', params: [1, 1] }],
  [0xc0, { name: 'LCMCTRL', params: [1, 1] }],
  [0xc2, { name: 'VDVVRHEN', params: [1, 2] }],
  [0xc3, { name: 'VRHS', params: [1, 1] }],
  [0xc4, { name: 'VDVS', params: [1, 1] }],
  [0xc6, { name: 'FRCTRL2', params: [1, 1] }],
  [0xd0, { name: 'PWCTRL1', params: [2, 2] }],
  [0xe0, { name: 'PVGAMCTRL', params: [14, 14] }],
  [0xe1, { name: 'NVGAMCTRL', params: [14, 14] }],
]);

const hex = (v) => `0x${v.toString(16).padStart(2, '0')}`;

export class St7789 {
  /**
   * @param {object} opts
   * @param {{x:number, y:number, w:number, h:number}} [opts.visible] the GRAM area the panel shows
   * @param {(frame:object)=>void} [opts.onFrame] called with each completed frame
   * @param {(msg:string)=>void} [opts.warn] protocol oddities that are not failures
   */
  constructor(opts = {}) {
    this.visible = opts.visible ?? { x: 0, y: 0, w: 240, h: 240 };
    this.onFrame = opts.onFrame ?? (() => {});
    this.warn = opts.warn ?? (() => {});
    this.gram = new Uint16Array(GRAM_W * GRAM_H);
    this.frames = 0;
    this.commandCounts = new Map();
    this.reset('power-on');
  }

  /** Hardware reset (RST low) or SWRESET: registers to their reset values; GRAM is kept. */
  reset(why) {
    this.finishCommand();
    this.resetReason = why;
    this.command = null; // current command code
    this.params = [];
    this.sleeping = true;
    this.displayOn = false;
    this.inverted = false;
    this.madctl = 0;
    this.colmod = 0x66; // reset value: 18 bit/pixel
    this.xs = 0;
    this.xe = GRAM_W - 1;
    this.ys = 0;
    this.ye = GRAM_H - 1;
    this.col = 0;
    this.row = 0;
    this.pixelHigh = -1; // first byte of a pixel, waiting for its second
    this.overBytes = 0; // pixel bytes past the end of the window
    this.frameStart = null; // the current frame's first pixel byte {start, end}
  }

  /** One byte received with DC `dc` (true = data); `start`/`end` are its cycle numbers. */
  byte(value, dc, start, end) {
    if (!dc) {
      this.finishCommand();
      const cmd = COMMANDS.get(value);
      if (!cmd) {
        throw new DecodeError(
          `unknown ST7789 command byte ${hex(value)} at cycle ${end} (the decoder accepts ${[
            ...COMMANDS.values(),
          ]
            .map((c) => c.name)
            .join(', ')})`,
        );
      }
      this.command = value;
      this.params = [];
      this.commandCounts.set(cmd.name, (this.commandCounts.get(cmd.name) ?? 0) + 1);
      this.startCommand(value, end);
      return;
    }
    if (this.command === null) {
      this.warn(`data byte ${hex(value)} with no command before it (cycle ${end}); ignored`);
      return;
    }
    const cmd = COMMANDS.get(this.command);
    if (cmd.params === 'pixels') {
      this.pixelByte(value, start, end);
      return;
    }
    this.params.push(value);
    if (this.params.length === cmd.params[1]) {
      this.applyParams(this.command, this.params, end);
    } else if (this.params.length > cmd.params[1]) {
      this.warn(
        `${cmd.name} got parameter byte ${this.params.length} (${hex(value)}), it takes ${
          cmd.params[1]
        }; ignored (cycle ${end})`,
      );
    }
  }

  /** Called before a new command and at the end of the stream: checks the one that ends. */
  finishCommand(atEnd = false) {
    if (this.overBytes) {
      const n = this.overBytes;
      this.overBytes = 0;
      throw new DecodeError(
        `pixel data ran ${n} byte(s) past the end of the CASET/RASET window ` +
          `(columns ${this.xs}..${this.xe}, rows ${this.ys}..${this.ye})` +
          (atEnd ? ' before the run ended' : ''),
      );
    }
    if (this.command === null || this.command === undefined) return;
    const cmd = COMMANDS.get(this.command);
    if (cmd.params === 'pixels') {
      if (this.pixelHigh >= 0) {
        this.warn(`${cmd.name} ended with half a pixel (odd number of data bytes)`);
        this.pixelHigh = -1;
      }
    } else if (this.params.length < cmd.params[0]) {
      this.warn(
        `${cmd.name} ended after ${this.params.length} parameter byte(s), it takes ${cmd.params[0]}`,
      );
    } else if (this.params.length < cmd.params[1] && this.params.length > 0) {
      this.applyParams(this.command, this.params);
    }
  }

  startCommand(code, cycle) {
    switch (code) {
      case 0x01:
        this.reset('SWRESET');
        this.command = code;
        break;
      case 0x10:
        this.sleeping = true;
        break;
      case 0x11:
        this.sleeping = false;
        break;
      case 0x20:
        this.inverted = false;
        break;
      case 0x21:
        this.inverted = true;
        break;
      case 0x28:
        this.displayOn = false;
        break;
      case 0x29:
        this.displayOn = true;
        break;
      case 0x2c:
        // RAMWR: the address counter goes back to the window's start.
        this.col = this.xs;
        this.row = this.ys;
        this.pixelHigh = -1;
        break;
      case 0x3c:
        // RAMWRC: continues where the last memory write stopped.
        this.pixelHigh = -1;
        break;
      default:
        break;
    }
    void cycle;
  }

  applyParams(code, p) {
    switch (code) {
      case 0x2a:
        this.xs = (p[0] << 8) | p[1];
        this.xe = (p[2] << 8) | p[3];
        this.checkWindow('CASET', this.xs, this.xe, this.counterLimits()[0]);
        break;
      case 0x2b:
        this.ys = (p[0] << 8) | p[1];
        this.ye = (p[2] << 8) | p[3];
        this.checkWindow('RASET', this.ys, this.ye, this.counterLimits()[1]);
        break;
      case 0x36:
        this.madctl = p[0];
        break;
      case 0x3a:
        this.colmod = p[0];
        break;
      default:
        break; // power, gamma, porch, scrolling, tearing: no effect on the picture model
    }
  }

  /** Sizes of the column and row counters: MV exchanges them. */
  counterLimits() {
    return this.madctl & 0x20 ? [GRAM_H, GRAM_W] : [GRAM_W, GRAM_H];
  }

  checkWindow(name, s, e, limit) {
    if (s > e || e >= limit) {
      throw new DecodeError(
        `${name} window ${s}..${e} is empty or outside the controller's ${limit} addresses ` +
          `(MADCTL ${hex(this.madctl)})`,
      );
    }
  }

  pixelByte(value, start, end) {
    if (this.frameStart === null) {
      this.frameStart = { start, end };
    }
    if (this.pixelHigh < 0) {
      this.pixelHigh = value;
      return;
    }
    const pixel = (this.pixelHigh << 8) | value;
    this.pixelHigh = -1;
    if ((this.colmod & 0x07) !== 0x05) {
      throw new DecodeError(
        `pixel data while COLMOD is ${hex(this.colmod)}: the harness decodes 16 bit/pixel ` +
          `(COLMOD 0x55 or 0x05) only`,
      );
    }
    if (this.row > this.ye) {
      this.overBytes += 2;
      return;
    }
    const { madctl } = this;
    let x = this.col;
    let y = this.row;
    if (madctl & 0x20) [x, y] = [y, x]; // MV: exchange
    if (madctl & 0x40) x = GRAM_W - 1 - x; // MX: mirror the physical column
    if (madctl & 0x80) y = GRAM_H - 1 - y; // MY: mirror the physical row
    this.gram[y * GRAM_W + x] = pixel;
    // Advance: column, then row, within the window.
    if (this.col < this.xe) {
      this.col++;
    } else {
      this.col = this.xs;
      this.row++;
    }
    const v = this.visible;
    if (x === v.x + v.w - 1 && y === v.y + v.h - 1) {
      this.completeFrame(end);
    }
  }

  /** The visible area as a row-major Uint16Array of RGB565 values. */
  visiblePixels() {
    const { x, y, w, h } = this.visible;
    const out = new Uint16Array(w * h);
    for (let r = 0; r < h; r++) {
      out.set(this.gram.subarray((y + r) * GRAM_W + x, (y + r) * GRAM_W + x + w), r * w);
    }
    return out;
  }

  completeFrame(cycle) {
    const frame = {
      index: this.frames++,
      pixels: this.visiblePixels(),
      firstByteCycle: this.frameStart.start,
      firstByteEndCycle: this.frameStart.end,
      // What the caller noted when the frame's first pixel byte arrived.
      timerBefore: this.frameStart.timerBefore ?? null,
      timerReads: this.frameStart.timerReads ?? null,
      frameStartBusy: this.frameStart.spiBusy ?? null,
      doneCycle: cycle,
      displayOn: this.displayOn,
      sleeping: this.sleeping,
      inverted: this.inverted,
      madctl: this.madctl,
    };
    this.frameStart = null;
    this.onFrame(frame);
  }

  /** End of the stream: reports a pending overflow. */
  end() {
    this.finishCommand(true);
  }
}
