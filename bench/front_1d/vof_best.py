# The one combination found that meets issue 14's 2-cell target in 1D: vof.py tracking
# (TIPFACE=1) + rfix.py (KAP=0.5) at a dry tolerance of 1e-9 m. /usr/bin/python3 vof_best.py
import os
for k,v in dict(RFIX="1",KAP="0.5",TIPFACE="1",EPS="1e-9").items(): os.environ.setdefault(k,v)
import vof
if __name__=='__main__':
    cells=tuple(int(c) for c in os.environ.get("CELLS","100,200,400").split(','))
    vof.report(0.005,6.0,cells); vof.report(0.02,3.0,cells)
