#!/usr/bin/env python3
# usage: annot.py ELF SYMSUBSTR [mincount] -> disassembly of hot symbols with per-instruction counts
import sys, subprocess, pickle, re
elf, target = sys.argv[1], sys.argv[2]
mn = int(sys.argv[3]) if len(sys.argv)>3 else 1
pcs = pickle.load(open(elf+".pcs.pkl","rb"))
d=subprocess.run(["arm-none-eabi-objdump","-d","--no-show-raw-insn","-C",elf],capture_output=True,text=True).stdout
on=False; tot=0
for l in d.splitlines():
    m=re.match(r"^([0-9a-f]+) <(.*)>:$",l)
    if m: on = target in m.group(2); 
    if m and on: print(l)
    if not on: continue
    m=re.match(r"^\s+([0-9a-f]+):\s+(.*)$",l)
    if m:
        n=pcs.get(int(m.group(1),16),0); tot+=n
        if n>=mn: print("%8d  %s  %s"%(n,m.group(1),m.group(2)))
print("total",tot)
