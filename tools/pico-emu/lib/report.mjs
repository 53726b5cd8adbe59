// report.json figures and the generated section of BENCHMARKS.md.
import fs from 'node:fs';
import { writeAtomic } from './image.mjs';

export const START_MARKER = '<!-- pico-emu:start -->';
export const END_MARKER = '<!-- pico-emu:end -->';

const grouped = (n) => String(n);

/**
 * What a second core would bring, from the QEMU benchmark's split-frame rows (`kind: "split"`
 * in target/mcu-bench/report.json: the board frame's geometry, its rows above a split row and,
 * after `Renderer::seek_row`, the rows below, in Cortex-M0 instructions, for every split row on
 * a strip boundary). For each measured frame the best split is the one with the least work on
 * the busier core, where the first core prepares the geometry and draws the top and the second
 * draws the bottom once the geometry is ready: frame = geometry + max(top, bottom). The
 * estimate scales the emulator's measured one-core cycles by that frame's instructions over the
 * one-core instructions (geometry + every row), and cannot beat the panel's own limit (the SPI
 * time of a frame). An estimate, not a measurement: the emulator runs one core.
 */
export function twoCoreEstimate(r, mcu) {
  const panelCycles = r.spi_cycles_per_byte * 240 * 240 * 2;
  const panelFps = r.clock_hz / panelCycles;
  const rows = Array.isArray(mcu) ? mcu.filter((x) => x.kind === 'split' && x.core === 'm0') : [];
  if (!rows.length || !r.cycles_per_frame) {
    return { measured: false, why: 'not estimated: run scripts/mcu-bench first (split-frame rows)', panel_fps: panelFps };
  }
  const frames = [...new Set(rows.map((x) => x.frame))];
  let worst = null;
  for (const f of frames) {
    const fr = rows.filter((x) => x.frame === f);
    const whole = fr.find((x) => x.split === 240);
    if (!whole) continue;
    const oneCore = whole.geometry + whole.top + whole.bottom;
    let best = null;
    for (const x of fr) {
      const two = x.geometry + Math.max(x.top, x.bottom);
      if (!best || two < best.two) best = { split: x.split, two, geometry: x.geometry, top: x.top, bottom: x.bottom };
    }
    const ratio = best.two / oneCore;
    if (!worst || ratio > worst.ratio) worst = { frame: f, oneCore, ratio, ...best };
  }
  if (!worst) return { measured: false, why: 'no whole-frame split row (split = 240)', panel_fps: panelFps };
  const cycles = Math.round(r.cycles_per_frame * worst.ratio);
  const limited = Math.max(cycles, panelCycles);
  return {
    measured: true,
    frame: worst.frame,
    split: worst.split,
    one_core_instructions: worst.oneCore,
    core0_instructions: worst.geometry + worst.top,
    core1_instructions: worst.geometry + worst.bottom,
    geometry_instructions: worst.geometry,
    frame_instructions: worst.two,
    cycles_per_frame: limited,
    fps: r.clock_hz / limited,
    panel_cycles_per_frame: panelCycles,
    panel_fps: panelFps,
  };
}

/** The markdown block (markers included) for BENCHMARKS.md. */
export function benchmarksBlock(r, profile = null) {
  const ms = (c) => ((c / r.clock_hz) * 1e3).toFixed(1);
  const rows = [
    ['frames captured', String(r.frames)],
    ['boot: reset to the first pixel byte', `${grouped(r.boot_cycles)} cycles (${ms(r.boot_cycles)} ms)`],
    [
      'cycles per frame (mean of frames 1..n, completion to completion)',
      r.cycles_per_frame === null ? 'n/a (one frame)' : `${grouped(Math.round(r.cycles_per_frame))} (${ms(r.cycles_per_frame)} ms)`,
    ],
    ['frame rate at 125 MHz', r.fps === null ? 'n/a' : `${r.fps.toFixed(2)} fps`],
    ['SPI busy (share of the frame time)', `${(r.spi_busy_fraction * 100).toFixed(1)} %`],
    ['SPI cycles per byte', String(r.spi_cycles_per_byte)],
    [
      'every frame equal to the host render',
      r.matches_host === null ? 'not compared' : r.matches_host ? 'yes' : 'NO',
    ],
  ];
  const prof = [];
  if (profile) {
    const label = profile.functions
      .filter((f) => /Glyphs/.test(f.function))
      .reduce((a, f) => a + f.cycles_per_frame, 0);
    prof.push(
      '',
      `Where the cycles of a frame go (\`tools/pico-emu/profile.mjs\`, ${profile.frames} frames after frame 0; each`,
      'emulated cycle charged to the function the core was in, waiting loops included):',
      '',
      '| function | cycles per frame | share |',
      '|---|---:|---:|',
      ...profile.functions
        .slice(0, 12)
        .map((f) => `| \`${f.function}\` | ${f.cycles_per_frame} | ${(100 * f.share).toFixed(1)} % |`),
      '',
      `The fps label (\`overlay::Glyphs::draw\`): ${label} cycles per frame, ` +
        `${((100 * label) / profile.cycles_per_frame).toFixed(2)} % of a frame.`,
    );
  }
  const tc = r.two_core;
  const two = [];
  if (tc && tc.measured) {
    two.push(
      '',
      `The panel's own limit, the SPI time of one frame (${240 * 240 * 2} bytes): ${tc.panel_cycles_per_frame} cycles, ` +
        `${tc.panel_fps.toFixed(1)} fps; the one-core firmware above reaches ${((100 * tc.panel_cycles_per_frame) / r.cycles_per_frame).toFixed(0)} % of that frame rate.`,
      '',
      '**Two cores (estimate, not measured: the firmware runs on one core; the emulator models both).** The QEMU benchmark',
      `measures the board frame split at each strip boundary (\`demo::board::split_frame\`). For the`,
      `least favourable measured frame (frame ${tc.frame}), the best split is at row ${tc.split}: the first core prepares the`,
      `geometry (${tc.geometry_instructions} instructions) and draws the rows above (${tc.core0_instructions - tc.geometry_instructions}), the second`,
      `core draws the rows below with its own strip pass begun at the split (${tc.core1_instructions - tc.geometry_instructions}); a frame takes ${tc.frame_instructions} Cortex-M0 instructions`,
      `instead of ${tc.one_core_instructions}. Scaled to the measured cycles: **${tc.cycles_per_frame} cycles per frame, ${tc.fps.toFixed(1)} fps**`,
      '(the larger of that and the panel\'s limit). Overlapping the next frame\'s geometry with the',
      'second core\'s rows (a second vertex store and triangle list) would shorten it further.',
    );
  } else if (tc) {
    two.push('', `Two cores: ${tc.why}.`);
  }
  return [
    START_MARKER,
    '## Raspberry Pi Pico firmware in an emulator',
    '',
    'Generated by `scripts/pico-emu`: `examples/pico_st7789.rs` built for thumbv6m with the',
    '`rp2040` feature (the SIO interpolators in the dithered row routine; the boot includes its',
    'start-up self-test) and run in',
    `rp2040js ${r.rp2040js_version} at ${r.clock_hz / 1e6} MHz, time from the core's cycle count, SPI1 shifting one`,
    `byte per ${r.spi_cycles_per_byte} cycles, the ST7789 byte stream decoded into frames and compared with the host.`,
    '',
    '| figure | value |',
    '|---|---:|',
    ...rows.map(([a, b]) => `| ${a} | ${b} |`),
    ...prof,
    ...two,
    '',
    'Not modelled: core 1, the XIP flash cache (every flash access costs what an SRAM access',
    'does, so code running from flash is faster than on the chip after a cache miss) and bus',
    'contention between the core and DMA: the cycle counts are optimistic (a lower bound).',
    END_MARKER,
  ].join('\n');
}

/**
 * Puts `block` between the markers in `path`, or appends it at the end of the file when the
 * markers are absent. Written atomically.
 */
export function updateBenchmarks(path, block) {
  const old = fs.existsSync(path) ? fs.readFileSync(path, 'utf8') : '';
  const s = old.indexOf(START_MARKER);
  const e = old.indexOf(END_MARKER);
  let text;
  if (s >= 0 && e > s) {
    text = old.slice(0, s) + block + old.slice(e + END_MARKER.length);
  } else {
    text = `${old}${old && !old.endsWith('\n') ? '\n' : ''}${old ? '\n' : ''}${block}\n`;
  }
  if (text !== old) writeAtomic(path, text);
}
