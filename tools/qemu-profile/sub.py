#!/usr/bin/env python3
# usage: sub.py ELF SYM ANCESTOR -> within symbol SYM, PCs whose inline chain contains ANCESTOR,
# grouped by the first function inlined below ANCESTOR (or by source line of ANCESTOR itself)
import sys, subprocess, pickle, collections, bisect
elf, target, anc = sys.argv[1], sys.argv[2], sys.argv[3]
pcs = pickle.load(open(elf+".pcs.pkl","rb"))
out=subprocess.run(["arm-none-eabi-nm","-S","-C",elf],capture_output=True,text=True).stdout
syms=[]
for l in out.splitlines():
    p=l.split(None,3)
    if len(p)==4 and p[2] in "tTW":
        a=int(p[0],16)&~1; syms.append((a,a+int(p[1],16),p[3]))
syms.sort(); starts=[s[0] for s in syms]
sel=[pc for pc in pcs if (lambda i: i>=0 and syms[i][0]<=pc<syms[i][1] and target in syms[i][2])(bisect.bisect_right(starts,pc)-1)]
sel.sort()
r=subprocess.run(["arm-none-eabi-addr2line","-a","-f","-i","-C","-e",elf]+["%x"%p for p in sel],capture_output=True,text=True).stdout
chains={}; cur=None; L=r.splitlines(); k=0
while k<len(L):
    if L[k].startswith("0x"): cur=int(L[k],16); chains[cur]=[]; k+=1; continue
    chains[cur].append((L[k],L[k+1])); k+=2
c=collections.Counter(); tot=0
for pc in sel:
    ch=chains[pc][::-1]
    idx=[i for i,(f,_) in enumerate(ch) if anc in f]
    if not idx: continue
    i=idx[-1]; n=pcs[pc]; tot+=n
    if i+1<len(ch): key=ch[i+1][0].replace("scanline3d::","")[:70]+"  @"+ch[i][1].split("/")[-1]
    else: key="(self) @"+ch[i][1].split("/")[-1]
    c[key]+=n
print("total",tot)
for k,n in c.most_common(int(sys.argv[4]) if len(sys.argv)>4 else 40): print("%8d  %s"%(n,k))
