# Trial: a sub-cell wedge in the front cell (c = sqrt(g h) linear to zero inside it, its
# length from the cell's mass, R = u + 2c from the wet neighbour; no outflow until the wedge
# reaches the dry face). EPS=1e-9 /usr/bin/python3 wedge.py
import os
import numpy as np
import ritter
from ritter import g, recon_default
def recon_wedge(h,u,eps,th):
    hW,hE,uW,uE=(a.copy() for a in recon_default(h,u,eps,th))
    dx=ritter.DX; c=np.sqrt(g*h)
    for k in range(1,len(h)-1):
        if h[k]<=eps: continue
        for side in (1,-1):   # side=+1: neighbour k+1 dry
            if h[k+side]<=eps and h[k-side]>eps and side*u[k]>0:
                R=side*u[k-side]+2*c[k-side]
                cmax=(2/3)*(R-side*u[k])
                if cmax<=0: continue
                L=3*g*h[k]*dx/cmax**2
                if L<dx: hf=0.0; uf=0.0
                else:
                    cr=cmax*(1-dx/L); hf=cr*cr/g; uf=side*(R-2*cr)
                if side==1: hE[k-1]=hf; uE[k-1]=uf
                else: hW[k-1]=hf; uW[k-1]=uf
    return hW,hE,uW,uE
if __name__=="__main__":
    ritter.RECON=recon_wedge
    E=float(os.environ.get("EPS","1e-5")); cells=tuple(int(c) for c in os.environ.get("CELLS","100,200,400,800").split(','))
    ritter.report(0.005,6.0,cells,eps=E); ritter.report(0.02,3.0,cells,eps=E)
