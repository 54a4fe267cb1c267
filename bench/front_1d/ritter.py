# A 1D copy of the finite-volume scheme of hydro/swe_kernels.hpp on a flat bed (desingularised
# velocities, generalised minmod on h and u, first order next to a cell at most eps deep, HLL
# with the exact dry-bed flux at a face with one dry side, Heun at cfl 0.8 with the redo at
# 0.45, a 0.05 s step cap, walls), for trying front treatments on Ritter's dam break quickly
# (docs/hydro.md, "Wet/dry fronts"). Not part of the build. Debian's numpy:
#   /usr/bin/python3 ritter.py      lag of the 5e-7 m front [cells] and L1 of h at 100-800 cells
# It reproduces the solver's lags (3.2, 6.4 cells at 100, 200 cells; 10.7 at 400 as at cfl 0.45).
import numpy as np, sys
g=9.81
def minmod(dl,dr,th):
    c=0.5*(dl+dr); lo=np.minimum(np.minimum(th*dl,c),th*dr); hi=np.maximum(np.maximum(th*dl,c),th*dr)
    return np.where(lo>0,lo,np.where(hi<0,hi,0.0))
def invd(h,eps): return 2*h/(h*h+np.maximum(h*h,eps*eps))
def flux(hL,uL,hR,uR,eps):
    cL=np.sqrt(g*hL); cR=np.sqrt(g*hR)
    sL=np.minimum(np.minimum(uL-cL,uR-cR),0); sR=np.maximum(np.maximum(uL+cL,uR+cR),0)
    qL=hL*uL; qR=hR*uR; pL=.5*g*hL*hL; pR=.5*g*hR*hR
    span=sR-sL; inv=np.where(span>1e-12,1/np.where(span>1e-12,span,1),0)
    hm=(sR*qL-sL*qR+sL*sR*(hR-hL))*inv
    hn=(sR*(qL*uL+pL)-sL*(qR*uR+pR)+sL*sR*(qR-qL))*inv
    dryL=hL<=eps; dryR=hR<=eps; s=np.where(dryR,1.0,-1.0)
    unw=np.where(dryR,uL,uR); cw=np.where(dryR,cL,cR); qw=np.where(dryR,qL,qR); pw=np.where(dryR,pL,pR)
    cs=np.maximum(0,(s*unw+2*cw)/3); hs=cs*cs/g
    away=s*unw>=cw
    dm=np.where(away,qw,s*hs*cs); dn=np.where(away,qw*unw+pw,1.5*hs*cs*cs)
    one=dryL!=dryR
    return np.where(one,dm,hm), np.where(one,dn,hn), np.maximum(-sL,sR)
def recon_default(h,u,eps,th):
    # cells padded with 1 ghost each side (walls). returns left/right face states of faces between cells
    wet=(h[:-2]>eps)&(h[1:-1]>eps)&(h[2:]>eps)
    sh=np.where(wet,minmod(h[1:-1]-h[:-2],h[2:]-h[1:-1],th),0)
    su=np.where(wet,minmod(u[1:-1]-u[:-2],u[2:]-u[1:-1],th),0)
    # interior cells 1..n ; faces between cell k and k+1 for k=0..n
    hW=h[1:-1]-.5*sh; hE=h[1:-1]+.5*sh; uW=u[1:-1]-.5*su; uE=u[1:-1]+.5*su
    return hW,hE,uW,uE
RECON=recon_default  # the reconstruction hook: (h, u, eps, theta) of the padded cells -> face values
POST=None            # an optional hook after each step: q = POST(h, q, eps)
DX=None              # the cell size of the run in progress [m], for hooks that need it
def rates(h,q,dx,eps,th):
    n=len(h)
    hp=np.concatenate([[h[0]],h,[h[-1]]]); qp=np.concatenate([[-q[0]],q,[-q[-1]]])
    up=qp*invd(hp,eps)
    hW,hE,uW,uE=RECON(hp,up,eps,th)
    # ghosts: face states of ghost cells: first order mirror
    hEg=np.concatenate([[hp[0]],hE]); uEg=np.concatenate([[up[0]],uE])
    hWg=np.concatenate([hW,[hp[-1]]]); uWg=np.concatenate([uW,[up[-1]]])
    fm,fn,a=flux(hEg,uEg,hWg,uWg,eps)
    return -(fm[1:]-fm[:-1])/dx, -(fn[1:]-fn[:-1])/dx, a
def run(nx,h0,t_end,cfl=0.8,eps=1e-5,th=1.3,order=2,dtcap=0.05):
    global DX
    dx=10.0/nx; x=(np.arange(nx)+.5)*dx; DX=dx
    h=np.where(x<5,h0,0.0); q=np.zeros(nx); t=0
    while t<t_end-1e-12:
        u=q*invd(h,eps); c=np.sqrt(g*h); a=np.max((np.abs(u)+c)/dx)
        dt=min(cfl/a,dtcap,t_end-t)
        for attempt in range(2):
            dh,dq,_=rates(h,q,dx,eps,th)
            h1=h+dt*dh; q1=q+dt*dq
            if order==2:
                h1c=np.maximum(h1,0); q1c=np.where(h1c>0,q1,0)
                dh2,dq2,_=rates(h1c,q1c,dx,eps,th)
                h2=.5*h+.5*(h1c+dt*dh2); q2=.5*q+.5*(q1c+dt*dq2)
            else: h2,q2=h1,q1
            if ((h1<0).any() or (h2<0).any()) and attempt==0 and dt*a>0.45+1e-9:
                dt=0.45/a; continue
            break
        h=np.maximum(h2,0); q=np.where(h>0,q2,0); t+=dt
        if POST: q=POST(h,q,eps)
    return x,h,q,dx
def exact_h(x,h0,t):
    c0=np.sqrt(g*h0); xi=(x-5)/t
    return np.where(xi<-c0,h0,np.where(xi<2*c0,(2*c0-xi)**2/(9*g),0))
def report(h0,t_end,cells=(100,200,400,800),label='',**kw):
    prev=None
    c0=np.sqrt(g*h0); xf=5+2*c0*t_end-t_end*np.sqrt(9*g*5e-7)
    for nx in cells:
        x,h,q,dx=run(nx,h0,t_end,**kw)
        wet=np.nonzero(h>5e-7)[0]; front=(wet[-1]+1)*dx
        # L1 with cell averages of exact via fine sampling
        xs=(np.arange(nx*20)+.5)*dx/20; he=exact_h(xs,h0,t_end).reshape(nx,20).mean(1)
        l1=np.sum(np.abs(h-he))*dx
        o='' if prev is None else '%.2f'%np.log2(prev/l1); prev=l1
        print(f'{label}{h0*1e3:g}mm nx={nx} front={front:.4f} xf={xf:.4f} lag={(xf-front)/dx:.1f} cells L1={l1:.3e} {o}')
if __name__=='__main__':
    import os
    E=float(os.environ.get("EPS","1e-5")); cells=tuple(int(c) for c in os.environ.get("CELLS","100,200,400,800").split(','))
    report(0.005,6.0,cells,eps=E); report(0.02,3.0,cells,eps=E)
