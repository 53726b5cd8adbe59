// Temporary profiler (lead's scratch): cycles per function over a cycle window.
import fs from 'node:fs';
import { parseElf } from './lib/elf.mjs';
import { Machine } from './lib/machine.mjs';
const [elfPath, romPath, fromC, toC] = process.argv.slice(2);
const elf = parseElf(fs.readFileSync(elfPath));
const rb = fs.readFileSync(romPath);
const bootrom = new Uint32Array(rb.buffer.slice(rb.byteOffset, rb.byteOffset + 16384));
const m = new Machine({ bootrom, elf, onByte: () => {} });
m.bootAtBoot2();
const from = Number(fromC), to = Number(toC);
m.run({ maxCycles: from + 1e9, done: () => m.cycles >= from });
const syms = elf.symbols.filter((s) => s.size > 0).sort((a, b) => a.addr - b.addr);
const addrs = syms.map((s) => s.addr);
function find(pc) {
  let lo = 0, hi = addrs.length - 1, r = -1;
  while (lo <= hi) { const mid = (lo + hi) >> 1; if (addrs[mid] <= pc) { r = mid; lo = mid + 1; } else hi = mid - 1; }
  if (r >= 0 && pc < syms[r].addr + syms[r].size) return syms[r].name;
  if (pc < 0x4000) return 'bootrom';
  return 'unknown';
}
const { core } = m.rp2040;
const acc = new Map();
let last = m.cycles;
m.run({ maxCycles: to + 1e9, done: () => {
  const c = m.cycles; const pc = core.PC;
  const k = find(pc); acc.set(k, (acc.get(k) || 0) + (c - last)); last = c;
  return c >= to;
} });
const tot = [...acc.values()].reduce((a, b) => a + b, 0);
for (const [k, v] of [...acc.entries()].sort((a, b) => b[1] - a[1]).slice(0, 30)) console.log(String(v).padStart(9), (100 * v / tot).toFixed(1).padStart(5) + '%', k);
