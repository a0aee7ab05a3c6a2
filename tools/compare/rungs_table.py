"""Table of a compare.py ladder from its <out>-rungs.jsonl (usable when the ladder was interrupted).

Usage: python tools/compare/rungs_table.py docs/images/perf-fog-cube-llvm-rungs.jsonl
Specific to the fog-cube run of docs/performance.md: it corrects Mitsuba's errors for the seed
overlap of that restarted ladder (reference seeds 2..835, 834 chunks of 4 spp; see below).
"""
import json, sys, math
import numpy as np
rows=[json.loads(l) for l in open(sys.argv[1])]
out={}
# The restarted ladder's Mitsuba chunks reused the reference's seeds (2..835, 834 chunks of
# 4 spp): chunk seeds ran 2, 3, ... after one warm-up chunk (seed 1). With k of an image's n
# chunks inside the reference, E[MSE vs ref] = var (1/n + 1/N - 2k/(nN)), so the image's own
# variance is MSE / (1 + n/N - 2k/N) (k = 0: the harness's 1 / (1 + n/N)).
N=834; seed=2
for r in rows:
    n=r['mitsuba_spp']//4; seeds=range(seed, seed+n); seed+=n
    k=sum(1 for x in seeds if 2<=x<=835)
    r['mitsuba_own_share']=1.0/(1+n/N-2*k/N); r['k']=k; r['n']=n
for r in rows:
    b=r['brume_mse_own']; m=r['mitsuba_mse_own_ref']; f=r['mitsuba_own_share']
    e=out.setdefault(r['budget_s'],{'bs':[],'ms':[],'b':[],'b4':[],'m':[],'m4':[],'spp':[]})
    e['bs'].append(r['brume_s']); e['ms'].append(r['mitsuba_s']); e['spp'].append(r['mitsuba_spp'])
    e['b'].append(math.sqrt(b[0])/r['brume_ref_mean']); e['b4'].append(math.sqrt(b[3])/r['brume_ref_mean'])
    e['m'].append(math.sqrt(m[0]*f)/r['mitsuba_ref_mean']); e['m4'].append(math.sqrt(m[3]*f)/r['mitsuba_ref_mean'])
def ms(v): 
    return f"{np.mean(v):.4f} ± {np.std(v,ddof=1):.4f}" if len(v)>1 else f"{v[0]:.4f}"
print("| budget CPU s | runs | brume CPU s | brume rel. RMSE | brume 4x4 | Mitsuba CPU s | Mitsuba spp | Mitsuba rel. RMSE | Mitsuba 4x4 | ratio | ratio 4x4 | ratio at equal time |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
allb=[];allm=[]
for t,e in sorted(out.items()):
    rb=np.mean(e['b']); rm=np.mean(e['m'])
    # equal time: scale each by sqrt(measured/budget) (error ~ t^-1/2)
    eq=np.mean([x*math.sqrt(s/t) for x,s in zip(e['b'],e['bs'])])/np.mean([x*math.sqrt(s/t) for x,s in zip(e['m'],e['ms'])])
    print(f"| {t:g} | {len(e['b'])} | {np.mean(e['bs']):.1f} | {ms(e['b'])} | {ms(e['b4'])} | {np.mean(e['ms']):.1f} | {np.mean(e['spp']):.0f} | {ms(e['m'])} | {ms(e['m4'])} | {rb/rm:.2f} | {np.mean(e['b4'])/np.mean(e['m4']):.2f} | {eq:.2f} |")
    allb+= list(zip(e['bs'],e['b'],e['b4'])); allm+=list(zip(e['ms'],e['m'],e['m4']))
for name,pts in (('brume',allb),('mitsuba',allm)):
    if len({round(p[0]) for p in pts})>1:
        lt=np.log([p[0] for p in pts])
        print(name,'slope rel_rmse',round(np.polyfit(lt,np.log([p[1] for p in pts]),1)[0],3),'bin4',round(np.polyfit(lt,np.log([p[2] for p in pts]),1)[0],3))
