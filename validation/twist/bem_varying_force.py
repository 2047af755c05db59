"""Twist under a varying normal force: the deresiewicz law against the BEM with twist (steel on steel, mu 0.3).

A path of (overlap / 1 um, twist / beta_1) corners, 40 steps each: (1, 0) (1, 1) (2, 1) (2, -1.5) (1, -0.5)
(1.5, 1.5) (0.7, 0.5) (1, -1): twist, load at fixed twist, twist back, unload while twisting, ... Prints
the largest |M_law - M_BEM| / (mu N a) (N, a of the current step) for 32, 64 and 128 cells.

    python validation/twist/bem_varying_force.py 64      (elements across; needs the BEM with twist)
"""
import json, math, sys, time
import numpy as np
from dem_contact.reference import bem, paths
from dem_contact.laws.twist import deresiewicz as d
n_across = int(sys.argv[1])
E, nu, mu, R = 208e9, 0.3, 0.3, 5e-3
G = E / (2 * (1 + nu)); Gc = G / 2; Es = E / (2 * (1 - nu**2))
d0 = 1e-6
a0 = math.sqrt(R * d0); N0 = 4 / 3 * Es * math.sqrt(R) * d0**1.5
b1 = mu * N0 * a0 / (16 / 3 * Gc * a0**3)
k = 40
seg = lambda x0, x1: np.linspace(x0, x1, k + 1)[1:]
# (delta / d0, twist / b1) corners: twist at d0, load to 2 d0 at fixed twist, twist back, unload while twisting, ...
corners = [(1, 0), (1, 1.0), (2, 1.0), (2, -1.5), (1, -0.5), (1.5, 1.5), (0.7, 0.5), (1, -1.0)]
dl = [np.array([d0])]; tw = [np.array([0.0])]
for (a_, b_), (c_, e_) in zip(corners[:-1], corners[1:]):
    dl.append(d0 * seg(a_, c_)); tw.append(b1 * seg(b_, e_))
dl = np.concatenate(dl); tw = np.concatenate(tw)
t0 = time.time()
Nb, Tx, Ty, Mz = bem.bem_path(E, nu, E, nu, R, mu, dl, np.zeros_like(dl), np.zeros_like(dl), tw, n_across=n_across)
tb = time.time() - t0
N = 4 / 3 * Es * math.sqrt(R) * dl**1.5; a = np.sqrt(R * dl)
res = {}
for n in (32, 64, 128):
    bb = np.concatenate([[0.0], tw]); NN = np.concatenate([[N[0]], N]); aa = np.concatenate([[a[0]], a])
    M, W = d.twist_path(Gc, mu, R, NN, aa, bb, n)
    res[n] = float(np.max(np.abs(-M[1:] - Mz) / (mu * N * a)))
print(json.dumps({"n_across": n_across, "bem_s": tb, "max_err_over_muNa_local": res}))
