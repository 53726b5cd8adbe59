#!/usr/bin/env python3
# usage: inl.py ELF FUNCSUBSTR -> break down PCs inside a symbol by inline chain (addr2line -i)
import sys, subprocess, pickle, collections, bisect
elf, target = sys.argv[1], sys.argv[2]
pcs = pickle.load(open(elf+".pcs.pkl","rb"))
out=subprocess.run(["arm-none-eabi-nm","-S","-C",elf],capture_output=True,text=True).stdout
syms=[]
for l in out.splitlines():
    p=l.split(None,3)
    if len(p)==4 and p[2] in "tTW":
        a=int(p[0],16)&~1; syms.append((a,a+int(p[1],16),p[3]))
syms.sort(); starts=[s[0] for s in syms]
sel=[]
for pc,n in pcs.items():
    i=bisect.bisect_right(starts,pc)-1
    if i>=0 and syms[i][0]<=pc<syms[i][1] and target in syms[i][2]: sel.append(pc)
sel.sort()
r=subprocess.run(["arm-none-eabi-addr2line","-f","-i","-C","-e",elf]+["%x"%p for p in sel]+["0"],capture_output=True,text=True).stdout
# addr2line -i output: for each address, pairs of (func, file:line) lines; the terminator "0" gives ?? 
lines=r.splitlines()
# use --addresses to split
r=subprocess.run(["arm-none-eabi-addr2line","-a","-f","-i","-C","-e",elf]+["%x"%p for p in sel],capture_output=True,text=True).stdout
chains={}; cur=None
L=r.splitlines(); k=0
while k<len(L):
    if L[k].startswith("0x"):
        cur=int(L[k],16); chains[cur]=[]; k+=1; continue
    fn=L[k]; loc=L[k+1] if k+1<len(L) else ""; chains[cur].append((fn,loc)); k+=2
depth=int(sys.argv[3]) if len(sys.argv)>3 else 1
c=collections.Counter(); cl=collections.Counter()
tot=0
for pc in sel:
    ch=chains.get(pc,[])[::-1]  # outermost first
    n=pcs[pc]; tot+=n
    key=" > ".join(f.split("(")[0].replace("scanline3d::","")[:60] for f,_ in ch[1:1+depth]) or "(self)"
    c[key]+=n
    if ch: cl[ch[-1][1].split("/")[-1]]+=n
print("total in",target,tot)
for k,n in c.most_common(40): print("%9d  %s"%(n,k))
print("--- innermost source lines")
for k,n in cl.most_common(25): print("%9d  %s"%(n,k))
print("--- inclusive per function (anywhere in inline chain)")
inc=collections.Counter()
for pc in sel:
    seen=set()
    for f,_ in chains.get(pc,[]):
        f=f.replace("scanline3d::","")
        if f in seen: continue
        seen.add(f); inc[f]+=pcs[pc]
for k,n in inc.most_common(70): print("%9d  %s"%(n,k[:130]))
