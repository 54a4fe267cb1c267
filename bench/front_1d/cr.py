# Trial: reconstruct c = sqrt(g h) and both Riemann invariants u +- 2c instead of h and u
# (MODE=cr), or that with the wedge of wedge.py (MODE=both). MODE=cr EPS=1e-5 /usr/bin/python3 cr.py
import os
import numpy as np
import ritter
from ritter import g, minmod, recon_default
from wedge import recon_wedge
def recon_cr(h,u,eps,th):
    c=np.sqrt(g*h); Rp=u+2*c; Rm=u-2*c
    wet=(h[:-2]>eps)&(h[1:-1]>eps)&(h[2:]>eps)
    sc=np.where(wet,minmod(c[1:-1]-c[:-2],c[2:]-c[1:-1],th),0)
    sp=np.where(wet,minmod(Rp[1:-1]-Rp[:-2],Rp[2:]-Rp[1:-1],th),0)
    sm=np.where(wet,minmod(Rm[1:-1]-Rm[:-2],Rm[2:]-Rm[1:-1],th),0)
    cW=np.maximum(c[1:-1]-.5*sc,0); cE=np.maximum(c[1:-1]+.5*sc,0)
    uW=.5*(Rp[1:-1]-.5*sp+Rm[1:-1]-.5*sm); uE=.5*(Rp[1:-1]+.5*sp+Rm[1:-1]+.5*sm)
    return cW**2/g, cE**2/g, uW, uE
def recon_both(h,u,eps,th):
    # the wedge's face values where it changed the scheme's, the invariants' elsewhere
    hW,hE,uW,uE=recon_cr(h,u,eps,th)
    w=recon_wedge(h,u,eps,th); d=recon_default(h,u,eps,th)
    mW=(w[0]!=d[0])|(w[2]!=d[2]); mE=(w[1]!=d[1])|(w[3]!=d[3])
    return np.where(mW,w[0],hW),np.where(mE,w[1],hE),np.where(mW,w[2],uW),np.where(mE,w[3],uE)
if __name__=="__main__":
    MODE=os.environ.get("MODE","cr")
    ritter.RECON=recon_cr if MODE=="cr" else recon_both
    E=float(os.environ.get("EPS","1e-5")); cells=tuple(int(c) for c in os.environ.get("CELLS","100,200,400,800").split(','))
    ritter.report(0.005,6.0,cells,label=f'{MODE} eps={E} ',eps=E); ritter.report(0.02,3.0,cells,label=f'{MODE} eps={E} ',eps=E)
