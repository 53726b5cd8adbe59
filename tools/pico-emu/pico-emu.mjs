#!/usr/bin/env node
// Runs the scanline3d Pico firmware in rp2040js, captures the ST7789 frames it sends on SPI1,
// writes them as PNG, compares them with the host's render and reports timing figures.
// Normally started by scripts/pico-emu, which builds what this needs; run from the repository root.
//
//   node tools/pico-emu/pico-emu.mjs [--frames N] [--max-cycles N] [--min-fps X]
//        [--host-tool PATH | --no-host] [--elf PATH] [--bootrom PATH] [--out DIR]
//        [--benchmarks PATH | --no-benchmarks]
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { parseElf, symbolAt } from './lib/elf.mjs';
import { Machine, HarnessError, CLOCK_HZ } from './lib/machine.mjs';
import { St7789, DecodeError } from './lib/st7789.mjs';
import { writeFramePng, writeDiffPng, writeAtomic } from './lib/image.mjs';
import {
  labelMicrosPerFrame,
  readHostFrame,
  compareFrames,
  hex565,
  FRAME_W,
  FRAME_H,
} from './lib/frames.mjs';
import { benchmarksBlock, updateBenchmarks } from './lib/report.mjs';
import { profileFrames } from './profile.mjs';

const USAGE = `usage: pico-emu.mjs [--frames N] [--max-cycles N] [--min-fps X]
       [--host-tool PATH | --no-host] [--elf PATH] [--bootrom PATH] [--out DIR]
       [--benchmarks PATH | --no-benchmarks] [--one-core-report PATH] [--profile-frames N]`;

function parseArgs(argv) {
  const o = {
    frames: 6,
    maxCycles: null,
    minFps: null,
    hostTool: null,
    noHost: false,
    elf: 'target/thumbv6m-none-eabi/release/examples/pico_st7789',
    bootrom: 'target/pico-emu/bootrom.bin',
    out: 'target/pico-emu',
    benchmarks: 'BENCHMARKS.md',
    oneCoreReport: null,
    profileFrames: 2,
  };
  const num = (name, v) => {
    const n = Number(v);
    if (v === undefined || !Number.isFinite(n) || n < 0) throw new Error(`${name} needs a number`);
    return n;
  };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    switch (a) {
      case '--frames':
        o.frames = num(a, argv[++i]);
        if (!Number.isInteger(o.frames) || o.frames < 1) throw new Error('--frames needs an integer >= 1');
        break;
      case '--max-cycles':
        o.maxCycles = num(a, argv[++i]);
        break;
      case '--min-fps':
        o.minFps = num(a, argv[++i]);
        break;
      case '--host-tool':
        o.hostTool = argv[++i];
        break;
      case '--no-host':
        o.noHost = true;
        break;
      case '--elf':
        o.elf = argv[++i];
        break;
      case '--bootrom':
        o.bootrom = argv[++i];
        break;
      case '--out':
        o.out = argv[++i];
        break;
      case '--benchmarks':
        o.benchmarks = argv[++i];
        break;
      case '--no-benchmarks':
        o.benchmarks = null;
        break;
      case '--one-core-report':
        o.oneCoreReport = argv[++i];
        break;
      case '--profile-frames':
        o.profileFrames = num(a, argv[++i]);
        break;
      case '-h':
      case '--help':
        console.log(USAGE);
        process.exit(0);
        break;
      default:
        throw new Error(`unknown argument ${a}\n${USAGE}`);
    }
  }
  // Generous by default: 100 M cycles of boot (0.8 s) and 60 M per frame (0.48 s).
  if (o.maxCycles === null) o.maxCycles = 100e6 + 60e6 * o.frames;
  return o;
}

const pad4 = (k) => String(k).padStart(4, '0');

function main() {
  const wallStart = process.hrtime.bigint();
  const opts = parseArgs(process.argv.slice(2));
  fs.mkdirSync(opts.out, { recursive: true });
  for (const f of fs.readdirSync(opts.out)) {
    if (/^(frame|diff)-\d{4}\.png$/.test(f)) fs.unlinkSync(path.join(opts.out, f));
  }
  // rp2040js's package.json is not exported: read it from node_modules directly.
  const rp2040jsVersion = JSON.parse(
    fs.readFileSync(new URL('./node_modules/rp2040js/package.json', import.meta.url), 'utf8'),
  ).version;

  const elf = parseElf(fs.readFileSync(opts.elf));
  const romBytes = fs.readFileSync(opts.bootrom);
  if (romBytes.length !== 16384) {
    throw new HarnessError(`${opts.bootrom}: ${romBytes.length} bytes, the boot ROM is 16384`);
  }
  const bootrom = new Uint32Array(romBytes.buffer.slice(romBytes.byteOffset, romBytes.byteOffset + 16384));

  const warnings = [];
  const warn = (msg) => {
    if (warnings.length < 100) warnings.push(msg);
  };
  const frames = [];
  let machine = null;
  // Timer reads since boot, kept short: the last few with their cycle.
  const display = new St7789({
    warn,
    onFrame: (f) => {
      f.spiBusyAtDone = machine.stats.spiBusyCycles;
      f.coreBusyAtDone = machine.slots.map((s) => s.busy);
      frames.push(f);
    },
  });
  let frameStartSeen = null; // the open frame's first pixel byte, to note the timer before it
  machine = new Machine({
    bootrom,
    elf,
    onByte: (value, dc, start, end) => {
      display.byte(value, dc, start, end);
      // The decoder opened a new frame with this byte: note the timer read that belongs to it
      // (the firmware's rule, see `labelMicrosPerFrame`): for frame 0 the last read before its
      // first pixel byte, for frame K the K-th read after that byte (the firmware reads the
      // timer once per frame; drawing runs ahead of the SPI, so a later frame's read may come
      // before this frame's first byte).
      if (display.frameStart && display.frameStart !== frameStartSeen) {
        frameStartSeen = display.frameStart;
        const k = frames.length;
        let t = null;
        if (k === 0) {
          t = machine.lastTimerRead && machine.lastTimerRead.cycle <= start ? machine.lastTimerRead : null;
          machine.timerLog = [];
        } else {
          t = machine.timerLog?.[k - 1] ?? null;
        }
        display.frameStart.timerBefore = t ? { ...t } : null;
        display.frameStart.timerReads = machine.stats.timerReads;
        display.frameStart.spiBusy = machine.stats.spiBusyCycles;
      }
    },
    onDisplayReset: () => display.reset('RST pin'),
  });

  // Where a run must not go: fault and panic handlers, by symbol.
  const traps = new Map();
  for (const s of elf.symbols) {
    if (/^(HardFault|HardFault_|DefaultHandler_|rust_begin_unwind|__rustc::rust_begin_unwind)$/.test(s.name)) {
      traps.set(s.addr, `${s.name} (0x${s.addr.toString(16)})`);
    }
  }

  machine.bootAtBoot2();
  let failure = null;
  try {
    machine.run({ maxCycles: opts.maxCycles, done: () => frames.length >= opts.frames, traps });
    display.end();
  } catch (e) {
    if (!(e instanceof HarnessError || e instanceof DecodeError)) throw e;
    const failedCore = machine.failedCore ?? 0;
    const pc = machine.core(failedCore).PC;
    failure =
      `${e.message} (cycle ${machine.cycles}, core ${failedCore}'s PC in ${symbolAt(elf.symbols, pc)}; ` +
      `${frames.length} frame(s) captured, ${machine.stats.spiBytes} SPI bytes)`;
    if (frames.length === 0) {
      failure +=
        machine.stats.spiBytes === 0
          ? ': the firmware never reached the display'
          : ': the firmware talked to the display but completed no frame';
    }
  }
  const emulatedCycles = machine.cycles;

  // Frames as PNG; each frame's data for the report.
  const framesOut = frames.map((f) => {
    const png = path.join(opts.out, `frame-${pad4(f.index)}.png`);
    writeFramePng(png, f.pixels, FRAME_W, FRAME_H);
    if (!f.displayOn || f.sleeping) {
      warn(`frame ${f.index} was drawn while the display was ${f.sleeping ? 'asleep' : 'off'}`);
    }
    return {
      index: f.index,
      first_pixel_cycle: f.firstByteCycle,
      done_cycle: f.doneCycle,
      timer_before_us: f.timerBefore?.value ?? null,
      png,
    };
  });
  // Timer reads between consecutive frames' first pixel bytes (information only: the label rule
  // counts reads from frame 0's first byte on, see `labelMicrosPerFrame`).
  for (let k = 1; k < frames.length; k++) {
    framesOut[k - 1].timer_reads_until_next_frame = frames[k].timerReads - frames[k - 1].timerReads;
  }

  // Label times and the host comparison.
  let labels = null;
  let matchesHost = null;
  const compareFailures = [];
  if (frames.length) {
    try {
      labels = labelMicrosPerFrame(frames);
      labels.forEach((us, k) => (framesOut[k].label_us = us));
    } catch (e) {
      compareFailures.push(`label times: ${e.message}`);
    }
  }
  if (!opts.noHost && frames.length) {
    if (!opts.hostTool || !fs.existsSync(opts.hostTool)) {
      compareFailures.push(
        `the host reference tool is missing (${opts.hostTool ?? 'no --host-tool given'}): ` +
          'tools/src/bin/board_frames.rs builds it; --no-host runs without the comparison',
      );
    } else if (labels) {
      const hostDir = path.join(opts.out, 'host');
      fs.rmSync(hostDir, { recursive: true, force: true });
      fs.mkdirSync(hostDir, { recursive: true });
      const args = ['--out', hostDir];
      labels.forEach((us, k) => args.push('--frame', `${k}:${us}`));
      const r = spawnSync(opts.hostTool, args, { encoding: 'utf8' });
      if (r.status !== 0) {
        compareFailures.push(
          `${opts.hostTool} ${args.join(' ')} failed (${r.error?.message ?? `exit ${r.status}`}): ${(r.stderr ?? '').trim()}`,
        );
      } else {
        for (const f of frames) {
          const file = path.join(hostDir, `host-${pad4(f.index)}.bin`);
          let host;
          try {
            host = readHostFrame(file);
          } catch (e) {
            compareFailures.push(`frame ${f.index}: ${e.message}`);
            continue;
          }
          const c = compareFrames(f.pixels, host);
          framesOut[f.index].differing_pixels = c.differing;
          if (c.differing) {
            const diff = path.join(opts.out, `diff-${pad4(f.index)}.png`);
            writeDiffPng(diff, f.pixels, host, FRAME_W, FRAME_H);
            framesOut[f.index].diff_png = diff;
            compareFailures.push(
              `frame ${f.index} differs from the host in ${c.differing} pixel(s); first at ` +
                `(x ${c.first.x}, y ${c.first.y}): emulator ${hex565(c.first.emulator)}, host ` +
                `${hex565(c.first.host)} (label ${labels[f.index]} us; see ${diff})`,
            );
          }
        }
      }
    }
    matchesHost = compareFailures.length === 0;
  } else if (!opts.noHost) {
    matchesHost = false;
  }

  // Figures.
  const n = frames.length;
  const frameCycles = frames.slice(1).map((f, i) => f.doneCycle - frames[i].doneCycle);
  const cyclesPerFrame = frameCycles.length
    ? frameCycles.reduce((a, b) => a + b, 0) / frameCycles.length
    : null;
  let busyFraction = null;
  if (n >= 2) {
    busyFraction =
      (frames[n - 1].spiBusyAtDone - frames[0].spiBusyAtDone) /
      (frames[n - 1].doneCycle - frames[0].doneCycle);
  } else if (n === 1) {
    busyFraction =
      (frames[0].spiBusyAtDone - frames[0].frameStartBusy) /
      (frames[0].doneCycle - frames[0].firstByteCycle);
  }
  // Per core: cycles spent executing (not asleep in WFE/WFI, not in reset), over the frames after
  // frame 0 when there are two or more, else since reset.
  const cores = machine.coreStats().map((c, i) => {
    const o = { ...c };
    if (n >= 2) {
      const busy = frames[n - 1].coreBusyAtDone[i] - frames[0].coreBusyAtDone[i];
      o.busy_cycles_per_frame = busy / (n - 1);
      o.busy_fraction = busy / (frames[n - 1].doneCycle - frames[0].doneCycle);
    }
    return o;
  });
  const perBit = machine.stats.spiCyclesPerBit;
  const wallSeconds = Number(process.hrtime.bigint() - wallStart) / 1e9;
  const report = {
    frames: n,
    cycles_per_frame: cyclesPerFrame,
    frame_cycles: frameCycles,
    fps: cyclesPerFrame ? CLOCK_HZ / cyclesPerFrame : null,
    matches_host: matchesHost,
    boot_cycles: n ? frames[0].firstByteCycle : null,
    spi_busy_fraction: busyFraction,
    clock_hz: CLOCK_HZ,
    spi_cycles_per_byte: perBit === null ? null : perBit * 8,
    spi_frame_bits: [...machine.stats.spiFrameBits],
    spi_bytes: machine.stats.spiBytes,
    spi_bytes_ignored: machine.stats.bytesIgnored,
    emulated_cycles: emulatedCycles,
    cores,
    firmware_clk_sys_hz: machine.rp2040.clkSys,
    frames_detail: framesOut,
    display_commands: Object.fromEntries(display.commandCounts),
    failure,
    comparison_failures: compareFailures,
    protocol_warnings: warnings,
    emulator_messages: machine.logger.summary().slice(0, 20),
    rp2040js_version: rp2040jsVersion,
    elf: opts.elf,
    wall_seconds: Number(wallSeconds.toFixed(2)),
  };
  if (machine.rp2040.clkSys !== CLOCK_HZ) {
    warn(
      `the firmware set clk_sys to ${machine.rp2040.clkSys} Hz; the harness counts time at ${CLOCK_HZ} Hz`,
    );
  }
  let fpsFailure = null;
  if (opts.minFps !== null && (report.fps === null || report.fps < opts.minFps)) {
    fpsFailure = `frame rate ${report.fps === null ? 'unknown' : report.fps.toFixed(2)} fps is below --min-fps ${opts.minFps}`;
  }
  // Where the cycles go (a second run of the same firmware, cycles charged to functions).
  let profile = null;
  if (n >= 2 && !failure && opts.profileFrames > 0) {
    profile = profileFrames(elf, bootrom, opts.profileFrames);
    writeAtomic(path.join(opts.out, 'profile.json'), `${JSON.stringify(profile, null, 2)}\n`);
  }
  // The one-core build's run (its report.json), for the BENCHMARKS.md section.
  let oneCore = null;
  if (opts.oneCoreReport && fs.existsSync(opts.oneCoreReport)) {
    oneCore = JSON.parse(fs.readFileSync(opts.oneCoreReport, 'utf8'));
  }
  report.profile_top = profile ? profile.functions.slice(0, 12) : null;
  writeAtomic(path.join(opts.out, 'report.json'), `${JSON.stringify(report, null, 2)}\n`);
  if (opts.benchmarks && n && !failure) {
    updateBenchmarks(
      opts.benchmarks,
      benchmarksBlock({ ...report, rp2040js_version: rp2040jsVersion }, profile, oneCore),
    );
  }

  // Summary.
  const fmt = (v, d = 0) => (v === null || v === undefined ? 'n/a' : Number(v).toFixed(d));
  console.log(`pico-emu: ${n} frame(s) in ${fmt(emulatedCycles)} emulated cycles, ${fmt(wallSeconds, 1)} s`);
  for (const f of framesOut) {
    console.log(
      `  frame ${f.index}: first pixel byte at cycle ${f.first_pixel_cycle}, done at ${f.done_cycle}` +
        `, label ${fmt(f.label_us)} us` +
        (f.differing_pixels !== undefined ? `, ${f.differing_pixels} pixel(s) differ from the host` : ''),
    );
  }
  console.log(`  boot_cycles        ${fmt(report.boot_cycles)}`);
  console.log(`  cycles_per_frame   ${fmt(report.cycles_per_frame)}  [${frameCycles.join(', ')}]`);
  console.log(`  fps                ${fmt(report.fps, 2)} (at ${CLOCK_HZ / 1e6} MHz)`);
  if (frameCycles.length) {
    const worst = Math.max(...frameCycles);
    console.log(`  worst_frame        ${worst} cycles (${(CLOCK_HZ / worst).toFixed(2)} fps)`);
  }
  console.log(`  spi_busy_fraction  ${fmt(report.spi_busy_fraction, 3)}`);
  console.log(`  spi_cycles_per_byte ${fmt(report.spi_cycles_per_byte)}`);
  for (const c of cores) {
    console.log(
      `  core ${c.core}             ${c.state}; busy ${fmt(c.busy_cycles_per_frame)} cycles per frame` +
        ` (${c.busy_fraction === undefined ? 'n/a' : (100 * c.busy_fraction).toFixed(1) + ' %'})`,
    );
  }
  console.log(`  matches_host       ${matchesHost === null ? 'not compared (--no-host)' : matchesHost}`);
  if (profile) {
    console.log(`  profile (cycles per frame, share; ${path.join(opts.out, 'profile.json')}):`);
    for (const f of profile.functions.slice(0, 12)) {
      console.log(`    ${String(f.cycles_per_frame).padStart(9)} ${(100 * f.share).toFixed(1).padStart(5)}%  ${f.function}`);
    }
  }
  for (const w of warnings.slice(0, 10)) console.log(`  warning: ${w}`);
  console.log(`  report: ${path.join(opts.out, 'report.json')}`);

  const problems = [];
  if (failure) problems.push(failure);
  if (!n && !failure) problems.push('no frame was captured');
  problems.push(...compareFailures);
  if (fpsFailure) problems.push(fpsFailure);
  if (problems.length) {
    for (const p of problems) console.error(`pico-emu: FAILED: ${p}`);
    return 1;
  }
  return 0;
}

try {
  process.exitCode = main();
} catch (e) {
  console.error(`pico-emu: FAILED: ${e instanceof HarnessError ? e.message : e.stack}`);
  process.exitCode = 1;
}
