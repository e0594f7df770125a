#!/usr/bin/env python3
# The cores' exact distance per step from pair_steps's vertices (/tmp/diag/out.txt), by a quadratic
# program over barycentric weights, beside grainflow's: /usr/bin/python3 tools/seed002/rocking_diagnosis/core_distance.py
import numpy as np, re, sys
from scipy.optimize import minimize
lines=open('/tmp/diag/out.txt').read().splitlines()
VA={};VB={};rad=None;rep={}
step=None
for l in lines:
    if l.startswith('step '): step=int(l.split()[1]); rep[step]=l
    elif l.startswith('VA '): p=l.split(); VA.setdefault(int(p[1]),[]).append([float(x) for x in p[2:]])
    elif l.startswith('VB '): p=l.split(); VB.setdefault(int(p[1]),[]).append([float(x) for x in p[2:]])
    elif l.startswith('radius'): rad=[float(x) for x in l.split()[1:]]
    elif l.startswith('core_distance'): rep[step]+= '  ' + l
def hull_dist(A,B):
    A=np.array(A);B=np.array(B);na=len(A);nb=len(B)
    def f(w): 
        d=w[:na]@A-w[na:]@B; return d@d
    cons=[{'type':'eq','fun':lambda w: w[:na].sum()-1},{'type':'eq','fun':lambda w: w[na:].sum()-1}]
    best=None
    for t in range(5):
        w0=np.random.dirichlet(np.ones(na)).tolist()+np.random.dirichlet(np.ones(nb)).tolist()
        r=minimize(f,w0,constraints=cons,bounds=[(0,1)]*(na+nb),method='SLSQP',options={'ftol':1e-16,'maxiter':500})
        if best is None or r.fun<best.fun: best=r
    return np.sqrt(max(best.fun,0))
for s in sorted(VA):
    d=hull_dist(VA[s],VB[s])
    print(s,'true core distance %.6g -> delta %.6g'%(d, sum(rad)-d),'|',rep[s][:200])
