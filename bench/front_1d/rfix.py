# Trial: after each step, at a face where the right cell is thinner than KAP times the left and
# the flow expands to the right (u_R > u_L, u_R > 0), move momentum from left to right until
# u + 2c is equal on both sides (mirrored for the left); conservative, but it assumes a simple
# wave on a flat bed without friction (there u + 2c is constant), which a slope or friction breaks.
import numpy as np, os
from ritter import g, invd
KAP=float(os.environ.get("KAP","1.0"))   # apply only if h_thin < KAP*h_thick
def rfix(h,q,eps,z=None):
    u=q*invd(h,eps); c=np.sqrt(g*h); wet=h>eps
    hL,hR,uL,uR,cL,cR=h[:-1],h[1:],u[:-1],u[1:],c[:-1],c[1:]
    both=wet[:-1]&wet[1:]
    # thin on right, flow to right, expanding: R+ of right should not be below left
    mR=both&(hR<KAP*hL)&(uR>uL)&(uR>0)
    dR=np.where(mR,np.maximum((uL+2*cL)-(uR+2*cR),0)*hL*hR/np.maximum(hL+hR,1e-300),0)
    # thin on left, flow to left, expanding: R- of left should not exceed right
    mL=both&(hL<KAP*hR)&(uR>uL)&(uL<0)
    dL=np.where(mL,np.maximum((uL-2*cL)-(uR-2*cR),0)*hL*hR/np.maximum(hL+hR,1e-300),0)
    # momentum flux F across face (positive = moved from left to right)
    F=dR+dL
    q=q.copy(); q[1:]+=F; q[:-1]-=F
    return q
