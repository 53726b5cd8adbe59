#!/usr/bin/env node
// Where the Pico firmware's cycles go: runs it in the emulator as pico-emu.mjs does (same machine,
// same timed SPI and DMA) and charges each instruction's cycles to the function it is in, per
// core, from the end of frame 0 to the end of frame N. Writes target/pico-emu/profile.json and
// prints core 0's top functions with their share of a frame. Cycles spent polling (a busy loop on
// the DMA queue) are charged to the function that polls, so a firmware that waits for the SPI
// shows it; cycles a core sleeps (WFE/WFI) or is held in reset are a row of their own, idle.
//
//   node tools/pico-emu/profile.mjs [--frames N] [--elf PATH] [--bootrom PATH] [--out DIR] [--top K]
import fs from 'node:fs';
import path from 'node:path';
import { parseElf } from './lib/elf.mjs';
import { Machine } from './lib/machine.mjs';
import { St7789 } from './lib/st7789.mjs';
import { writeAtomic } from './lib/image.mjs';

function parseArgs(argv) {
  const o = {
    frames: 3,
    top: 25,
    elf: 'target/thumbv6m-none-eabi/release/examples/pico_st7789',
    bootrom: 'target/pico-emu/bootrom.bin',
    out: 'target/pico-emu',
  };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const v = argv[++i];
    if (v === undefined) throw new Error(`${a} needs a value`);
    if (a === '--frames' || a === '--top') {
      const n = Number(v);
      if (!Number.isInteger(n) || n < 1) throw new Error(`${a} needs an integer >= 1`);
      o[a.slice(2)] = n;
    } else if (a === '--elf' || a === '--bootrom' || a === '--out') {
      o[a.slice(2)] = v;
    } else {
      throw new Error(`unknown argument ${a}`);
    }
  }
  return o;
}

/** Sorted function symbols and a lookup from an address to the function that contains it. */
function functionIndex(symbols) {
  const fns = symbols.filter((s) => s.size > 0).sort((a, b) => a.addr - b.addr);
  const starts = fns.map((s) => s.addr);
  return (pc) => {
    let lo = 0;
    let hi = starts.length - 1;
    let r = -1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (starts[mid] <= pc) {
        r = mid;
        lo = mid + 1;
      } else hi = mid - 1;
    }
    if (r >= 0 && pc < fns[r].addr + fns[r].size) return fns[r].name;
    return pc < 0x4000 ? '(boot ROM)' : '(no symbol)';
  };
}

/** A readable name: the Rust path without hashes and generic arguments. */
function shortName(name) {
  // Rust v0 symbols (the standard library's): the length-prefixed identifiers after the
  // crate's disambiguator.
  const v0 = /^_R[A-Za-z]*C[A-Za-z0-9]*_(.*)$/.exec(name);
  if (v0) {
    const parts = [];
    let s = v0[1];
    for (;;) {
      const n = /^[A-Za-z]*?(\d+)/.exec(s);
      if (!n) break;
      const len = Number(n[1]);
      parts.push(s.slice(n[0].length, n[0].length + len));
      s = s.slice(n[0].length + len);
    }
    return parts.length ? parts.join('::') : name;
  }
  const m = /^_ZN(.*)E$/.exec(name);
  if (!m) return name;
  const parts = [];
  let s = m[1];
  while (s.length) {
    const n = /^(\d+)/.exec(s);
    if (!n) break;
    const len = Number(n[1]);
    parts.push(s.slice(n[1].length, n[1].length + len));
    s = s.slice(n[1].length + len);
  }
  if (parts.length && /^h[0-9a-f]{16}$/.test(parts[parts.length - 1])) parts.pop();
  return parts
    .join('::')
    .replace(/\$LT\$.*\$GT\$/g, '<..>')
    .replace(/\$u20\$/g, ' ')
    .replace(/\.\./g, '..');
}

/**
 * Runs the firmware `elf` (parsed) with `bootrom` and returns the cycles charged to each
 * function over `frames` frames after frame 0: `{ frames, cycles_per_frame, functions, cores }`.
 * `functions` is core 0's (sorted by cycles, each `{ function, cycles_per_frame, share }`, the
 * share of all cycles); `cores` has, per core, its busy cycles per frame and its functions.
 */
export function profileFrames(elf, bootrom, frames) {
  const o = { frames };
  const done = [];
  let machine = null;
  const display = new St7789({ onFrame: () => done.push(machine.cycles) });
  machine = new Machine({
    bootrom,
    elf,
    onByte: (v, dc, start, end) => display.byte(v, dc, start, end),
    onDisplayReset: () => display.reset('RST pin'),
  });
  machine.bootAtBoot2();
  const limit = 100e6 + 60e6 * (o.frames + 1);
  machine.run({ maxCycles: limit, done: () => done.length >= 1 });
  const fnAt = functionIndex(elf.symbols);
  const perCore = [new Map(), new Map()];
  const from = machine.cycles;
  machine.run({
    maxCycles: limit,
    done: () => done.length >= 1 + o.frames,
    onStep: (core, pc, cycles) => {
      const m = perCore[core];
      const name = fnAt(pc);
      m.set(name, (m.get(name) || 0) + cycles);
    },
  });
  const total = machine.cycles - from;
  const perFrame = total / o.frames;
  const table = (cycles) => {
    const busy = [...cycles.values()].reduce((a, b) => a + b, 0);
    const rows = [...cycles.entries()];
    if (total > busy) rows.push(['(idle: asleep in WFE/WFI or in reset)', total - busy]);
    return {
      busy,
      rows: rows
        .sort((a, b) => b[1] - a[1])
        .map(([name, c]) => ({ function: shortName(name), cycles_per_frame: Math.round(c / o.frames), share: c / total })),
    };
  };
  const tables = perCore.map(table);
  return {
    frames: o.frames,
    cycles_per_frame: Math.round(perFrame),
    note:
      'Emulated cycles of each instruction charged to the function it is in (polling loops ' +
      'included), per core, mean over the frames after frame 0; a core asleep (WFE/WFI) or in ' +
      'reset is idle. rp2040js timings, no XIP cache or bus contention.',
    functions: tables[0].rows,
    cores: tables.map((t, i) => ({
      core: i,
      busy_cycles_per_frame: Math.round(t.busy / o.frames),
      busy_share: t.busy / total,
      functions: i === 0 ? undefined : t.rows,
    })),
  };
}

function main() {
  const o = parseArgs(process.argv.slice(2));
  const elf = parseElf(fs.readFileSync(o.elf));
  const rom = fs.readFileSync(o.bootrom);
  const bootrom = new Uint32Array(rom.buffer.slice(rom.byteOffset, rom.byteOffset + 16384));
  const report = profileFrames(elf, bootrom, o.frames);
  const rows = report.functions;
  const perFrame = report.cycles_per_frame;
  fs.mkdirSync(o.out, { recursive: true });
  writeAtomic(path.join(o.out, 'profile.json'), JSON.stringify(report, null, 2) + '\n');
  console.log(`profile: ${o.frames} frame(s), ${Math.round(perFrame)} cycles per frame`);
  for (const r of rows.slice(0, o.top)) {
    console.log(
      `${String(r.cycles_per_frame).padStart(9)} ${(100 * r.share).toFixed(1).padStart(5)}%  ${r.function}`,
    );
  }
  console.log(`profile: ${path.join(o.out, 'profile.json')}`);
}

if (import.meta.url === `file://${process.argv[1]}` || process.argv[1]?.endsWith('profile.mjs')) {
  try {
    main();
  } catch (e) {
    console.error(`profile: ${e.message}`);
    process.exit(1);
  }
}
