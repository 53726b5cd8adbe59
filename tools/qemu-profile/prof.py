#!/usr/bin/env python3
# usage: prof.py ELF -> runs QEMU (one instruction per TB, exec log streamed through a FIFO),
# histograms PCs between frame_start_marker and frame_end_marker, prints per-function counts.
import sys, subprocess, re, collections, os, bisect, pickle, signal
elf = sys.argv[1]
fifo = "/tmp/m4f-prof-%d.fifo" % os.getpid()
if os.path.exists(fifo): os.remove(fifo)
os.mkfifo(fifo)
syms=[]
out=subprocess.run(["arm-none-eabi-nm","-S","-C",elf],capture_output=True,text=True).stdout
for l in out.splitlines():
    p=l.split(None,3)
    if len(p)==4 and p[2] in "tTW":
        a=int(p[0],16)&~1; syms.append((a,a+int(p[1],16),p[3]))
syms.sort()
start=[s[0] for s in syms if "frame_start_marker" in s[2]][0]
end=[s[0] for s in syms if "frame_end_marker" in s[2]][0]
q=subprocess.Popen(["timeout","600","qemu-system-arm","-machine",os.environ.get("QEMU_MACHINE","mps2-an386"),"-nographic","-monitor","none",
    "-serial","null","-semihosting-config","enable=on,target=native","-icount","shift=7,align=off,sleep=off",
    "-singlestep","-d","exec,nochain","-D",fifo,"-kernel",elf], stdout=subprocess.DEVNULL,
    # A session of its own: the kill below reaches QEMU, not only `timeout` (killing `timeout`
    # alone left QEMU running, a core busy, after the script had ended).
    start_new_session=True)
pcs=collections.Counter(); on=False; total=0
rx=re.compile(r"Trace \d+: \S+ \[[0-9a-f]+/([0-9a-f]+)/")
with open(fifo) as fh:
    for line in fh:
        m=rx.search(line)
        if not m: continue
        pc=int(m.group(1),16)
        if pc==start: on=True; continue
        if pc==end: break
        if on: pcs[pc]+=1; total+=1
os.killpg(q.pid, signal.SIGKILL); q.wait(); os.remove(fifo)
starts=[s[0] for s in syms]
f=collections.Counter()
for pc,n in pcs.items():
    i=bisect.bisect_right(starts,pc)-1
    name = syms[i][2] if i>=0 and syms[i][0]<=pc<syms[i][1] else "?"
    f[name]+=n
print("total", total)
for name,n in f.most_common(int(sys.argv[2]) if len(sys.argv)>2 else 30):
    print("%9d %5.1f%%  %s"%(n,100*n/total,name[:140]))
pickle.dump(pcs,open(elf+".pcs.pkl","wb"))
