# Tests of the source-aware invariant fix (rfix_src.py) and the wet fraction on a bed (bedvof.py).
#   TEST=ritter|runup|lake  MODES=plain,src,vof+src,...  CELLS=100,200,400  EPS=1e-9
#   /usr/bin/python3 tests_src.py
# MODES: plain, rfix, src, vof, vof+rfix, vof+src (vof = wet fraction; rfix = flat-bed invariant
# fix of rfix.py; src = rfix_src.py). runup: NMAN=0,0.012; REFEPS (1e-5), reference cached in ref_*.npy.
import os; os.environ.setdefault("KAP","0.5")   # rfix.py and rfix_src.py both at KAP=0.5 (as vof_best.py)
import numpy as np, sys, time
from ritter import g, exact_h
import bedvof
E=float(os.environ.get("EPS","1e-9"))
CELLS=tuple(int(c) for c in os.environ.get("CELLS","100,200,400").split(','))
MODES=os.environ.get("MODES","plain,rfix,src,vof,vof+rfix,vof+src").split(',')
def opts(m): return dict(vof=m.startswith('vof'),fix=('rfix' if m.endswith('rfix') else 'src' if m.endswith('src') else 'none'))
def ritter():
    for h0,te in ((0.005,6.0),(0.02,3.0)):
        c0=np.sqrt(g*h0); xf=5+2*c0*te-te*np.sqrt(9*g*5e-7)
        for m in MODES:
            prev=None; row=[]
            for nx in CELLS:
                dx=10.0/nx; x=(np.arange(nx)+.5)*dx; h=np.where(x<5,h0,0.0); z=np.zeros(nx)
                h,q,al,negs=bedvof.run(x,h,z,te,eps=E,**opts(m))
                wet=np.nonzero(h>5e-7)[0]; front=(wet[-1]+1)*dx
                xs=(np.arange(nx*20)+.5)*dx/20; he=exact_h(xs,h0,te).reshape(nx,20).mean(1)
                l1=np.sum(np.abs(h-he))*dx; o='' if prev is None else ' (%.2f)'%np.log2(prev/l1); prev=l1
                row.append(f'{(xf-front)/dx:5.1f} L1={l1:.2e}{o} dm={h.sum()*dx-h0*5:.0e} neg={negs}')
            print(f'ritter {h0*1e3:g}mm {m:9s} lag: '+' | '.join(row),flush=True)
THR=1e-4
def shoreline(x,h,z,dx):
    # right-most crossing of the h = THR contour of the piecewise linear interpolant of the cell depths
    w=np.nonzero(h>THR)[0]
    if len(w)==0: return x[0]
    k=w[-1]
    if k==len(h)-1: return x[-1]
    return x[k]+dx*(h[k]-THR)/(h[k]-h[k+1])
def runup_run(nx,m,nman,eps,cfl=0.45):
    dx=10.0/nx; x=(np.arange(nx)+.5)*dx
    z=np.where(x>5,0.1*(x-5),0.0); h=np.where(x<3,0.02,0.0)
    st=dict(q=0.0,xs=0.0,m0=h.sum()*dx,dm=0.0)
    def mon(t,h,q):
        w=np.nonzero(h>THR)[0]
        if len(w): st['q']=max(st['q'],z[w[-1]])
        st['xs']=max(st['xs'],shoreline(x,h,z,dx))
        st['dm']=max(st['dm'],abs(h.sum()*dx-st['m0']))
    h,q,al,negs=bedvof.run(x,h,z,8.0,n_manning=nman,eps=eps,cfl=cfl,monitor=mon,**opts(m))
    return 0.1*(st['xs']-5)*1e3, st['q']*1e3, st['dm'], negs
def runup():
    REFN=int(os.environ.get("REFN","3200")); REFEPS=float(os.environ.get("REFEPS","1e-5"))
    for nman in (float(v) for v in os.environ.get("NMAN","0,0.012").split(',')):
        fn=f'ref_runup_n{nman}_N{REFN}_e{REFEPS:g}.npy'
        if os.path.exists(fn): ref=np.load(fn)
        else:
            t0=time.time(); ref=np.array(runup_run(REFN,'plain',nman,REFEPS)); np.save(fn,ref)
            print(f'  (reference {REFN} cells took {time.time()-t0:.0f} s)')
        print(f'runup n={nman}: reference plain {REFN} cells eps={REFEPS:g}: interpolated {ref[0]:.2f} mm, cell-quantised {ref[1]:.2f} mm',flush=True)
        for m in MODES:
            row=[]
            for nx in CELLS:
                r,qq,dm,negs=runup_run(nx,m,nman,E)
                row.append(f'{r:6.2f} ({r-ref[0]:+5.2f}) [q {qq:5.2f}] dm={dm:.0e} neg={negs}')
            print(f'  {m:9s} '+' | '.join(row),flush=True)
def lake():
    for m in MODES:
        for nman in (0.0,0.012):
            row=[]
            for nx in CELLS:
                dx=10.0/nx; x=(np.arange(nx)+.5)*dx
                z=np.where(x>5,0.1*(x-5),0.0); eta0=0.1*(7.03-5)       # shoreline inside a cell
                h=np.maximum(eta0-z,0.0); m0=h.sum()*dx
                st=dict(u=0.0)
                def mon(t,h,q): st['u']=max(st['u'],np.max(np.abs(q[h>E]/h[h>E])) if (h>E).any() else 0)
                h,q,al,negs=bedvof.run(x,h,z,10.0,n_manning=nman,eps=E,cfl=0.45,monitor=mon,**opts(m))
                row.append(f'max|u|={st["u"]:.1e} max|h-h0|={np.max(np.abs(h-np.maximum(eta0-z,0))):.1e} dm={h.sum()*dx-m0:.0e} neg={negs}')
            print(f'lake {m:9s} n={nman}: '+' | '.join(row),flush=True)
def frfront():
    # friction-bound front: 5 mm dam break at x<5 onto a dry flat bed, Manning n, t = 6 s; front =
    # right-most crossing of the h = THRF contour (linear interpolation of cell depths), in cells of the
    # run vs the plain scheme at REFN cells (cached)
    REFN=int(os.environ.get("REFN","3200")); thr=float(os.environ.get("THRF","5e-7"))
    def front(nx,m,nman):
        dx=10.0/nx; x=(np.arange(nx)+.5)*dx; h=np.where(x<5,0.005,0.0); z=np.zeros(nx)
        h,q,al,negs=bedvof.run(x,h,z,6.0,n_manning=nman,eps=E,**opts(m))
        w=np.nonzero(h>thr)[0]; k=w[-1]
        return x[k]+dx*(h[k]-thr)/(h[k]-h[k+1]), h.sum()*dx-0.025, negs
    for nman in (float(v) for v in os.environ.get("NMAN","0.012,0.03").split(',')):
        fn=f'ref_front_n{nman}_N{REFN}_t{thr:g}.npy'
        if os.path.exists(fn): ref=float(np.load(fn))
        else: ref=front(REFN,'plain',nman)[0]; np.save(fn,ref)
        print(f'front n={nman} thr={thr:g}: reference plain {REFN} cells x={ref:.4f} m; (x-ref)/dx:',flush=True)
        for m in MODES:
            row=[]
            for nx in CELLS:
                xf,dm,negs=front(nx,m,nman); row.append(f'{(xf-ref)/(10.0/nx):+6.2f} dm={dm:.0e} neg={negs}')
            print(f'  {m:9s} '+' | '.join(row),flush=True)

if __name__=='__main__':
    dict(ritter=ritter,runup=runup,lake=lake,frfront=frfront)[os.environ.get("TEST","ritter")]()
