// Minimal ELF32 little-endian reader: the program headers (to load the firmware image) and the
// symbol table (to name the function the core is stuck in when a run fails).

const PT_LOAD = 1;
const SHT_SYMTAB = 2;

/**
 * Parses an ELF32 LE ARM executable.
 * @param {Buffer} buf the whole file
 * @returns {{entry:number, segments:Array<{paddr:number, vaddr:number, data:Buffer, memsz:number}>,
 *            symbols:Array<{name:string, addr:number, size:number}>}}
 */
export function parseElf(buf) {
  if (buf.length < 52 || buf.readUInt32BE(0) !== 0x7f454c46) {
    throw new Error('not an ELF file');
  }
  if (buf[4] !== 1 || buf[5] !== 1) {
    throw new Error('not a 32-bit little-endian ELF file');
  }
  const machine = buf.readUInt16LE(18);
  if (machine !== 40) {
    throw new Error(`ELF machine ${machine} is not ARM (40)`);
  }
  const entry = buf.readUInt32LE(24);
  const phoff = buf.readUInt32LE(28);
  const shoff = buf.readUInt32LE(32);
  const phentsize = buf.readUInt16LE(42);
  const phnum = buf.readUInt16LE(44);
  const shentsize = buf.readUInt16LE(46);
  const shnum = buf.readUInt16LE(48);

  const segments = [];
  for (let i = 0; i < phnum; i++) {
    const o = phoff + i * phentsize;
    if (buf.readUInt32LE(o) !== PT_LOAD) continue;
    const offset = buf.readUInt32LE(o + 4);
    const vaddr = buf.readUInt32LE(o + 8);
    const paddr = buf.readUInt32LE(o + 12);
    const filesz = buf.readUInt32LE(o + 16);
    const memsz = buf.readUInt32LE(o + 20);
    segments.push({ paddr, vaddr, memsz, data: buf.subarray(offset, offset + filesz) });
  }

  const symbols = [];
  for (let i = 0; i < shnum; i++) {
    const o = shoff + i * shentsize;
    if (buf.readUInt32LE(o + 4) !== SHT_SYMTAB) continue;
    const symOff = buf.readUInt32LE(o + 16);
    const symSize = buf.readUInt32LE(o + 20);
    const strIndex = buf.readUInt32LE(o + 24);
    const entsize = buf.readUInt32LE(o + 36) || 16;
    const strOff = buf.readUInt32LE(shoff + strIndex * shentsize + 16);
    for (let s = symOff; s + entsize <= symOff + symSize; s += entsize) {
      const nameOff = buf.readUInt32LE(s);
      const value = buf.readUInt32LE(s + 4);
      const size = buf.readUInt32LE(s + 8);
      const type = buf[s + 12] & 0xf;
      if (type !== 2 /* STT_FUNC */ || !nameOff) continue;
      const end = buf.indexOf(0, strOff + nameOff);
      symbols.push({ name: buf.toString('latin1', strOff + nameOff, end), addr: value & ~1, size });
    }
  }
  symbols.sort((a, b) => a.addr - b.addr);
  return { entry, segments, symbols };
}

/** The function symbol containing `addr` (or the nearest one below it), for messages. */
export function symbolAt(symbols, addr) {
  let best = null;
  for (const s of symbols) {
    if (s.addr <= addr) best = s;
    else break;
  }
  if (!best) return `0x${addr.toString(16)}`;
  const off = addr - best.addr;
  return `${best.name}+0x${off.toString(16)} (0x${addr.toString(16)})`;
}
