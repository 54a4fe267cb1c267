# One 1D solver for the front trials with a bed: Audusse hydrostatic reconstruction (eta, h, u
# reconstructed, first order next to a cell <= eps deep), HLL with the exact dry-bed flux,
# implicit Manning friction after each Heun stage (as slope.py), optional wet-fraction tracking
# (VOF: vof.py with TIPFACE=1, extended to a bed) and an optional post-step fix:
#   FIX = none | rfix (rfix.py, flat-bed invariant, KAP=0.5) | src (rfix_src.py, source aware)
# With z = 0, n = 0, eps = 1e-9: vof=True, fix=src or rfix reproduces vof_best.py digit for digit;
# vof=False, fix=none is ritter.py/slope.py except the walls (mirrored face states, see stage()).
# Tip cell on a bed (VOF): the wedge state (h_f, u_f) of vof.py is a depth at the back face; its
# level is eta_f = z_f + h_f with z_f = (z_{k-1}+z_k)/2 (TIPZ=mid) or max(z_{k-1},z_k) (TIPZ=max: rejected,
# it gives negative depths and mass errors up to 1e-3 on the runup test),
# and both face sides are reconstructed hydrostatically from that level (h_side = max(eta_f - z_side, 0),
# then the usual Audusse step). The tip speed and the back-face invariant are R+ of the upstream cell
# plus the same source drop D as in rfix_src.py over the distance dx/2 + ell (TIPSRC=1).
# A dry tip cell with alpha = 0 is only started if the upstream level is above its bed
# (hydrostatically reconstructed face depth > eps), so a shoreline at rest never starts a tip.
import numpy as np, os
from ritter import g, minmod, invd, flux
from vof import fix_alpha, alpha_heun
from rfix import rfix
from rfix_src import rfix_src, _minv43
TIPZ=os.environ.get("TIPZ","mid")
TIPSRC=int(os.environ.get("TIPSRC","1"))
def src_drop(uk,ck,R,hk,ht,dzdist,dist,n_manning,eps):
    # drop of R+ from cell centre (uk, ck) to a point `dist` downstream (bed rise dzdist), <= 0
    lam=np.maximum(.5*(uk+ck+np.maximum(R,0)),1e-12); ub=.5*(uk+np.maximum(R,0))
    a=g*n_manning**2*_minv43(np.maximum(hk,eps),np.maximum(np.minimum(ht,hk),eps))
    x=a*(dist/lam)*np.abs(ub)
    # at most stop the tip (R + D >= 0 when R > 0; no drop when R <= 0: no C+ reaches the tip)
    return np.maximum(np.minimum(0,-g*dzdist/lam-ub*x/(1+x)),-np.maximum(R,0))
def stage(h,q,al,z,dx,eps,th,vof,n_manning):
    n=len(h)
    hp=np.concatenate([[h[0]],h,[h[-1]]]); qp=np.concatenate([[-q[0]],q,[-q[-1]]])
    zp=np.concatenate([[z[0]],z,[z[-1]]]); ap=np.concatenate([[al[0]],al,[al[-1]]])
    up=qp*invd(hp,eps); ep=hp+zp; wet=hp>eps
    k=np.arange(1,n+1)
    if vof:
        tipE=(ap[k]<1)&wet[k-1]&~wet[k+1]&(ap[k-1]>=1)
        tipW=(ap[k]<1)&wet[k+1]&~wet[k-1]&(ap[k+1]>=1)
        tipE&=~tipW
        # start a dry, empty tip cell only if the upstream water stands above the face bed
        startE=ep[k-1]-np.maximum(zp[k-1],zp[k])>eps; startW=ep[k+1]-np.maximum(zp[k+1],zp[k])>eps
        tipE&=wet[k]|(ap[k]>0)|startE; tipW&=wet[k]|(ap[k]>0)|startW
    else:
        tipE=np.zeros(n,bool); tipW=np.zeros(n,bool)
    T=np.concatenate([[False],tipE|tipW,[False]])
    w3=wet[:-2]&wet[1:-1]&wet[2:]&~T[1:-1]&~T[:-2]&~T[2:]
    se=np.where(w3,minmod(ep[1:-1]-ep[:-2],ep[2:]-ep[1:-1],th),0)
    sh=np.where(w3,minmod(hp[1:-1]-hp[:-2],hp[2:]-hp[1:-1],th),0)
    su=np.where(w3,minmod(up[1:-1]-up[:-2],up[2:]-up[1:-1],th),0)
    eW=ep[1:-1]-.5*se; eE=ep[1:-1]+.5*se; hW=hp[1:-1]-.5*sh; hE=hp[1:-1]+.5*sh; uW=up[1:-1]-.5*su; uE=up[1:-1]+.5*su
    sE=sW=None
    if vof and (tipE.any() or tipW.any()):
        ell=np.clip(ap[k],0,1)*dx
        kE=np.sqrt(3*g*(hp[k-1]+hp[k])*dx/(dx+ell)**3); kW=np.sqrt(3*g*(hp[k+1]+hp[k])*dx/(dx+ell)**3)
        RE=up[k-1]+2*np.sqrt(g*hp[k-1]); RW=-up[k+1]+2*np.sqrt(g*hp[k+1])
        cfE=kE*ell; cfW=kW*ell
        if TIPSRC:
            hwk=hp[k]/np.maximum(ap[k],1e-300)
            dist=.5*dx+ell
            DE=src_drop(up[k-1],np.sqrt(g*hp[k-1]),RE,hp[k-1],hwk,(zp[k]-zp[k-1])*dist/dx,dist,n_manning,eps)
            DW=src_drop(-up[k+1],np.sqrt(g*hp[k+1]),RW,hp[k+1],hwk,(zp[k]-zp[k+1])*dist/dx,dist,n_manning,eps)
            fb=.5*dx/dist                       # the drop up to the back face
            RbE=RE+fb*DE; RbW=RW+fb*DW; RE=RE+DE; RW=RW+DW
        else: RbE=RE; RbW=RW
        hfE=cfE**2/g; ufE=RbE-2*cfE; hfW=cfW**2/g; ufW=-(RbW-2*cfW)
        # levels of the tip states at the back faces
        zfE=np.maximum(zp[k-1],zp[k]) if TIPZ=='max' else .5*(zp[k-1]+zp[k])
        zfW=np.maximum(zp[k+1],zp[k]) if TIPZ=='max' else .5*(zp[k+1]+zp[k])
        efE=zfE+hfE; efW=zfW+hfW
        # tipE: back face = west face of cell i (0-based), sides: east of i-1, west of i
        i=np.nonzero(tipE)[0]; i=i[i>0]
        hW[i]=np.maximum(efE[i]-z[i],0); eW[i]=z[i]+hW[i]; uW[i]=ufE[i]
        hE[i-1]=np.maximum(efE[i]-z[i-1],0); eE[i-1]=z[i-1]+hE[i-1]; uE[i-1]=ufE[i]
        i=np.nonzero(tipW)[0]; i=i[i<n-1]
        hE[i]=np.maximum(efW[i]-z[i],0); eE[i]=z[i]+hE[i]; uE[i]=ufW[i]
        hW[i+1]=np.maximum(efW[i]-z[i+1],0); eW[i+1]=z[i+1]+hW[i+1]; uW[i+1]=ufW[i]
        sE=RE; sW=RW
    eL=np.concatenate([[ep[0]],eE]); hL=np.concatenate([[hp[0]],hE]); uL=np.concatenate([[up[0]],uE])
    eR=np.concatenate([eW,[ep[-1]]]); hR=np.concatenate([hW,[hp[-1]]]); uR=np.concatenate([uW,[up[-1]]])
    # walls: the outer state is the mirror of the inner face state (ritter.py/slope.py mirror the
    # cell average instead, which lets mass through a wall next to a second-order cell)
    eL[0]=eW[0]; hL[0]=hW[0]; uL[0]=-uW[0]; eR[-1]=eE[-1]; hR[-1]=hE[-1]; uR[-1]=-uE[-1]
    zs=np.maximum(eL-hL,eR-hR); hsL=np.maximum(0,eL-zs); hsR=np.maximum(0,eR-zs)
    fm,fn,a=flux(hsL,uL,hsR,uR,eps)
    # shut the dry face of a tip cell (faces j=0..n; face j between cells j-1 and j): no mass or
    # momentum flux (as vof.py), only the hydrostatic bed reaction of the Audusse step remains
    blk=np.zeros(n+1,bool); blk[1:]|=tipE; blk[:-1]|=tipW
    fm=np.where(blk,0,fm); fn=np.where(blk,0,fn)
    nL=fn+.5*g*(hL**2-hsL**2); nR=fn+.5*g*(hR**2-hsR**2)
    zW=eW-hW; zE=eE-hE
    dh=-(fm[1:]-fm[:-1])/dx
    dq=-(nL[1:]-nR[:-1])/dx-g*.5*(hW+hE)*(zE-zW)/dx
    if sE is not None:
        dal=np.where(tipE,np.maximum(sE,0),0)+np.where(tipW,np.maximum(sW,0),0)
    else: dal=np.zeros(n)
    amax=np.max(np.concatenate([a,dal]))
    return dh,dq,dal/dx,tipE,tipW,amax/dx
def run(x,h,z,t_end,vof=False,fix='none',n_manning=0.0,eps=1e-9,cfl=0.8,th=1.3,dtcap=0.05,monitor=None):
    nx=len(x); dx=x[1]-x[0]; q=np.zeros(nx); t=0
    al=np.where(h>eps,1.0,0.0); negs=0
    def fric(h,q,dt):
        if n_manning==0: return q
        hs=np.maximum(h,eps); a=dt*g*n_manning**2/hs**(7/3)
        return q*2/(1+np.sqrt(1+4*a*np.abs(q)))
    while t<t_end-1e-12:
        dh,dq,da,tE,tW,a=stage(h,q,al,z,dx,eps,th,vof,n_manning)
        dt=min(cfl/a,dtcap,t_end-t)
        for attempt in range(2):
            h1=h+dt*dh; q1=q+dt*dq; a1=al+dt*da
            h1c=np.maximum(h1,0); q1c=np.where(h1c>0,fric(h1c,q1,dt),0)
            if vof: a1=fix_alpha(h1c,a1,tE,tW,eps)
            dh2,dq2,da2,tE2,tW2,_=stage(h1c,q1c,a1,z,dx,eps,th,vof,n_manning)
            h2=h1c+dt*dh2; q2=fric(np.maximum(h2,0),q1c+dt*dq2,dt)
            h2=.5*h+.5*h2; q2=.5*q+.5*q2
            if vof: a2=alpha_heun(al,da,da2,tE,tW,tE2,tW2,dt)
            if ((h1<0).any() or (h2<0).any()) and attempt==0 and dt*a>0.45+1e-9:
                dt=0.45/a; continue
            break
        negs+=(h1<0).sum()+(h2<0).sum()
        h=np.maximum(h2,0); q=np.where(h>0,q2,0); t+=dt
        if vof: al=fix_alpha(h,a2,tE,tW,eps)
        if fix=='rfix': q=rfix(h,q,eps)
        elif fix=='src': q=rfix_src(h,q,eps,z,dx,n_manning)
        if monitor: monitor(t,h,q)
    return h,q,al,negs
