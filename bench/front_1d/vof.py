# Trial: sub-cell front tracking, a wet fraction alpha per cell carried at the tip speed, the
# tip cell's back face set to a wedge state, no outflow through its dry face (TIPFACE=1);
# RFIX=1 adds rfix.py after each step. See vof_best.py for the combination that meets the
# 2-cell target in 1D.
import numpy as np, os, sys
from ritter import g, minmod, invd, flux, exact_h
from rfix import rfix
RFIX=int(os.environ.get('RFIX','0'))
K=float(os.environ.get("K","2.598"))      # tip speed s = u + K*sqrt(g*h/alpha)  (2.598=3*sqrt(3)/2 wedge, 2 = plain R+)
UPMAX=int(os.environ.get("UPMAX","0"))    # also take max with upstream cell R+ (face state)
TIPFACE=int(os.environ.get("TIPFACE","0"))
HWMODE=os.environ.get("HWMODE","hw")      # back-face state of tip cell: 'h' cell avg, 'hw' wet-part mean, 'wedge' 3*hw
def stage(h,q,al,dx,eps,th):
    n=len(h)
    hp=np.concatenate([[h[0]],h,[h[-1]]]); qp=np.concatenate([[-q[0]],q,[-q[-1]]])
    ap=np.concatenate([[al[0]],al,[al[-1]]])
    up=qp*invd(hp,eps); wet=hp>eps
    # tip cells (interior index k=1..n in padded arrays)
    k=np.arange(1,n+1)
    tipE=(ap[k]<1)&wet[k-1]&~wet[k+1]&(ap[k-1]>=1)        # front moving east, water against west face
    tipW=(ap[k]<1)&wet[k+1]&~wet[k-1]&(ap[k+1]>=1)
    tipE&=~tipW
    # wet-part depth
    aa=np.where(tipE|tipW,np.maximum(ap[k],1e-300),1.0)
    hw=np.where(wet[k],hp[k]/aa,hp[k])
    # reconstruction on (hw,u): first order near dry like baseline
    hq=hp.copy(); hq[1:-1]=hw
    w3=wet[:-2]&wet[1:-1]&wet[2:]&~np.concatenate([[False],tipE|tipW,[False]])[1:-1]
    # also first order in neighbours of tip cells (stencil contains a tip cell)
    T=np.concatenate([[False],tipE|tipW,[False]])
    w3&=~T[:-2]&~T[2:]
    sh=np.where(w3,minmod(hq[1:-1]-hq[:-2],hq[2:]-hq[1:-1],th),0)
    su=np.where(w3,minmod(up[1:-1]-up[:-2],up[2:]-up[1:-1],th),0)
    hW=hq[1:-1]-.5*sh; hE=hq[1:-1]+.5*sh; uW=up[1:-1]-.5*su; uE=up[1:-1]+.5*su
    cw=np.sqrt(g*hw)
    if HWMODE=='wedge':
        cb=np.sqrt(3.0)*cw
        hE=np.where(tipW,3*hw,hE); uE=np.where(tipW,up[k]+.5*cb,uE)
        hW=np.where(tipE,3*hw,hW); uW=np.where(tipE,up[k]-.5*cb,uW)
    elif HWMODE=='h':
        hE=np.where(tipW,hp[k],hE); hW=np.where(tipE,hp[k],hW)
    if TIPFACE:
        # tip moving east in cell k: back face = west face of k; last full cell = k-1
        ell=np.clip(ap[k],0,1)*dx
        mE=(hp[k-1]*dx+hp[k]*dx); kE=np.sqrt(3*g*mE/(dx+ell)**3)
        mW=(hp[k+1]*dx+hp[k]*dx); kW=np.sqrt(3*g*mW/(dx+ell)**3)
        RE=up[k-1]+2*np.sqrt(g*hp[k-1]); RW=-up[k+1]+2*np.sqrt(g*hp[k+1])
        if TIPFACE==2:
            RE=np.where(wet[k],np.maximum(RE,up[k]+K*cw),RE); RW=np.where(wet[k],np.maximum(RW,-up[k]+K*cw),RW)
        cfE=kE*ell; cfW=kW*ell
        # set both sides of back face to tip state
        hfE=cfE**2/g; ufE=RE-2*cfE; hfW=cfW**2/g; ufW=-(RW-2*cfW)
        hW=np.where(tipE,hfE,hW); uW=np.where(tipE,ufE,uW); hE=np.where(tipW,hfW,hE); uE=np.where(tipW,ufW,uE)
        km=np.arange(n)
        # east state of cell k-1 (index km-1 in hE) for tipE cells
        iE=np.nonzero(tipE)[0]; iE=iE[iE>0]; hE[iE-1]=hfE[iE]; uE[iE-1]=ufE[iE]
        iW=np.nonzero(tipW)[0]; iW=iW[iW<n-1]; hW[iW+1]=hfW[iW]; uW[iW+1]=ufW[iW]
        TIPS=(RE,RW)
    hEg=np.concatenate([[hp[0]],hE]); uEg=np.concatenate([[up[0]],uE])
    hWg=np.concatenate([hW,[hp[-1]]]); uWg=np.concatenate([uW,[up[-1]]])
    fm,fn,a=flux(hEg,uEg,hWg,uWg,eps)
    # block outflow through the dry side of a tip cell (faces j=0..n, face j between cell j-1 and j (0-based))
    blk=np.zeros(n+1,bool); blk[1:]|=tipE; blk[:-1]|=tipW
    fm=np.where(blk,0,fm); fn=np.where(blk,0,fn)
    # tip speeds
    sown_E=up[k]+K*cw; sown_W=-up[k]+K*cw
    # upstream face state R+: east-moving tip: west neighbour's east face state
    RupE=hEg[:-1]; RupE=uEg[:-1]+2*np.sqrt(g*hEg[:-1])   # face k-1 left state = east state of cell k-1
    RupW=-uWg[1:]+2*np.sqrt(g*hWg[1:])                    # right state at face k = west state of cell k+1
    sE=np.where(wet[k],sown_E,RupE); sW=np.where(wet[k],sown_W,RupW)
    if UPMAX: sE=np.where(wet[k],np.maximum(sown_E,RupE),RupE); sW=np.where(wet[k],np.maximum(sown_W,RupW),RupW)
    if TIPFACE: sE,sW=TIPS
    dal=np.where(tipE,np.maximum(sE,0),0)+np.where(tipW,np.maximum(sW,0),0)
    amax=np.max(np.concatenate([a,dal]))
    return -(fm[1:]-fm[:-1])/dx, -(fn[1:]-fn[:-1])/dx, dal/dx, tipE, tipW, amax/dx
def alpha_heun(al,da,da2,tE,tW,tE2,tW2,dt):
    # Heun: the wet fraction moves with the mean of the two stages' speeds of the same tip
    # (followed into the next cell if it moved one cell in the first stage).
    s2E=np.where(tE2,da2,np.where(np.concatenate([tE2[1:],[False]]),np.concatenate([da2[1:],[0]]),da))
    s2W=np.where(tW2,da2,np.where(np.concatenate([[False],tW2[:-1]]),np.concatenate([[0],da2[:-1]]),da))
    return al+dt*0.5*(da+np.where(tE,s2E,np.where(tW,s2W,0)))
def fix_alpha(h,al,tipE,tipW,eps):
    n=len(h)
    al=al.copy()
    ovE=np.where(tipE,np.maximum(al-1,0),0); ovW=np.where(tipW,np.maximum(al-1,0),0)
    al=np.minimum(al,1.0)
    al[1:]=np.where(ovE[:-1]>0,np.maximum(al[1:],0)+ovE[:-1],al[1:])
    al[:-1]=np.where(ovW[1:]>0,np.maximum(al[:-1],0)+ovW[1:],al[:-1])
    al=np.minimum(al,1.0)
    wet=h>eps
    # lower bound: wet part no deeper than the deeper neighbour
    hn=np.maximum(np.concatenate([[h[0]],h[:-1]]),np.concatenate([h[1:],[h[-1]]]))
    lo=np.where(hn>0,h/np.where(hn>0,hn,1),1.0)
    al=np.where(wet,np.clip(al,np.minimum(lo,1.0),1.0),al)
    # cells with no dry neighbour are full
    wl=np.concatenate([[True],wet[:-1]]); wr=np.concatenate([wet[1:],[True]])
    al=np.where(wet&wl&wr,1.0,al)
    # dry cells with no wet neighbour: reset
    al=np.where(~wet&~wl&~wr,0.0,al)
    return al
def run(nx,h0,t_end,cfl=0.8,eps=float(os.environ.get("EPS","1e-5")),th=1.3,dtcap=0.05,h_init=None):
    dx=10.0/nx; x=(np.arange(nx)+.5)*dx
    h=np.where(x<5,h0,0.0) if h_init is None else h_init(x); q=np.zeros(nx); t=0
    al=np.where(h>eps,1.0,0.0); negs=0
    while t<t_end-1e-12:
        dh,dq,da,tE,tW,a=stage(h,q,al,dx,eps,th)
        dt=min(cfl/a,dtcap,t_end-t)
        for attempt in range(2):
            h1=h+dt*dh; q1=q+dt*dq; a1=al+dt*da
            h1c=np.maximum(h1,0); q1c=np.where(h1c>0,q1,0); a1=fix_alpha(h1c,a1,tE,tW,eps)
            dh2,dq2,da2,tE2,tW2,_=stage(h1c,q1c,a1,dx,eps,th)
            h2=.5*h+.5*(h1c+dt*dh2); q2=.5*q+.5*(q1c+dt*dq2)
            a2=alpha_heun(al,da,da2,tE,tW,tE2,tW2,dt)
            if ((h1<0).any() or (h2<0).any()) and attempt==0 and dt*a>0.45+1e-9:
                dt=0.45/a; continue
            break
        negs+=(h1<0).sum()+(h2<0).sum()
        a2=fix_alpha(np.maximum(h2,0),a2,tE,tW,eps)
        h=np.maximum(h2,0); q=np.where(h>0,q2,0); al=a2; t+=dt
        if RFIX: q=rfix(h,q,eps)
    return x,h,q,dx,al,negs
def report(h0,t_end,cells=(100,200,400,800),**kw):
    prev=None; out=[]
    c0=np.sqrt(g*h0); xf=5+2*c0*t_end-t_end*np.sqrt(9*g*5e-7)
    for nx in cells:
        x,h,q,dx,al,negs=run(nx,h0,t_end,**kw)
        wet=np.nonzero(h>5e-7)[0]; front=(wet[-1]+1)*dx
        xs=(np.arange(nx*20)+.5)*dx/20; he=exact_h(xs,h0,t_end).reshape(nx,20).mean(1)
        l1=np.sum(np.abs(h-he))*dx
        o='' if prev is None else '%.2f'%np.log2(prev/l1); prev=l1
        merr=h.sum()*dx-h0*5
        print(f'{h0*1e3:g}mm nx={nx} lag={(xf-front)/dx:.1f} L1={l1:.3e} {o} mass_err={merr:.1e} negs={negs}',flush=True)
if __name__=='__main__':
    E=float(os.environ.get("EPS","1e-5")); cells=tuple(int(c) for c in os.environ.get("CELLS","100,200,400").split(','))
    report(0.005,6.0,cells,eps=E); report(0.02,3.0,cells,eps=E)
