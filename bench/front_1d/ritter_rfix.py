# Trial: the scheme of ritter.py with rfix.py after each step. KAP=0.5 EPS=1e-9 /usr/bin/python3 ritter_rfix.py
import os
import ritter
from rfix import rfix
if __name__=='__main__':
    ritter.POST=rfix
    E=float(os.environ.get("EPS","1e-5")); cells=tuple(int(c) for c in os.environ.get("CELLS","100,200,400").split(','))
    ritter.report(0.005,6.0,cells,eps=E); ritter.report(0.02,3.0,cells,eps=E)
