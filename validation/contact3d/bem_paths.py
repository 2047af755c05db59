"""The 3D tangential laws (dem_contact.dem.contact3d) against the boundary-element reference on curved
tangential paths at constant overlap, steel sphere (R = 5 mm) on a steel wall, mu = 0.3, delta = 1 um.

Paths, in units of the slip displacement 3 mu N / (16 G* a), from the unloaded contact: a circle through the
origin of radius 0.3; a load to 0.5 then a circle around the origin; an L-turn (1.5 along x, then 1.5
along y); a figure-eight of size 0.6; a circle through the origin of radius 0.6. Prints, per path and law,
the largest |T_law - T_BEM| / (mu N) over the path (JSON with --json).

Needs ``dem_contact.reference.bem`` (the boundary-element reference).
Usage: python validation/contact3d/bem_paths.py [--n-across 128] [--steps 480] [--json out.json]
"""
import argparse
import json
import math

import numpy as np

from dem_contact.dem.contact3d import contact_force, history_size, new_histories
from dem_contact.laws.model import TANGENTIAL_LAWS, Scene, reference_speed
from dem_contact.laws.slots import P_NSPRING
from dem_contact.materials import STEEL, Sphere, Wall
from dem_contact.reference.bem import bem_path

R, MU, DELTA = 5e-3, 0.3, 1e-6
PATHS = ["circle 0.3", "load 0.5 + circle", "L-turn 1.5", "figure-eight 0.6", "circle 0.6"]


def path(name, steps, s_slip):
    th = np.linspace(0, 2 * np.pi, steps + 1)[1:]
    if name.startswith("circle"):
        r = float(name.split()[1])
        u = np.column_stack([r - r * np.cos(th), r * np.sin(th)])
    elif name.startswith("load"):
        k = steps // 4
        u = np.vstack([np.column_stack([np.linspace(0, 0.5, k + 1)[1:], np.zeros(k)]),
                       0.5 * np.column_stack([np.cos(th), np.sin(th)])])
    elif name.startswith("L-turn"):
        k = steps // 2
        ramp = np.linspace(0, 1.5, k + 1)[1:]
        u = np.vstack([np.column_stack([ramp, np.zeros(k)]), np.column_stack([np.full(k, 1.5), ramp])])
    else:
        u = 0.6 * np.column_stack([np.sin(th), np.sin(th) * np.cos(th)])
    return np.vstack([[0.0, 0.0], u]) * s_slip


def law_forces(law, u, a):
    sc = Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU, tangential=law, v_ref=reference_speed(1.0),
               **({"mdr_max_radius": 1.5 * a} if law == "mdr" else {}))
    P = sc.params[None, :]
    H = new_histories(1, history_size(sc.normal_id, sc.tangential_id, int(sc.params[P_NSPRING])))
    dt = 1e-6
    T = np.zeros((len(u), 2))
    for k in range(1, len(u)):
        v = (u[k] - u[k - 1]) / dt
        f = contact_force(sc.normal_id, sc.tangential_id, P, 0, H, 0, 0.0, 0.0, 1.0, DELTA, v[0], v[1], 0.0, 0.0,
                          dt)
        T[k] = f[3], f[4]
    return T


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n-across", type=int, default=128, help="BEM elements across the contact (default 128)")
    ap.add_argument("--steps", type=int, default=480, help="steps per turn of a path (default 480)")
    ap.add_argument("--json", help="write the errors to this JSON file")
    a = ap.parse_args()
    sc = Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU)
    Es, Gs = sc.pair.E_star, sc.pair.G_star
    radius = math.sqrt(R * DELTA)
    N0 = 4.0 / 3.0 * Es * radius * DELTA
    s_slip = 3.0 * MU * N0 / (16.0 * Gs * radius)
    out = {}
    for name in PATHS:
        u = path(name, a.steps, s_slip)
        N, Tx, Ty = bem_path(STEEL.E, STEEL.nu, STEEL.E, STEEL.nu, R, MU, np.full(len(u), DELTA), u[:, 0], u[:, 1],
                             n_across=a.n_across)
        muN = MU * N.max()
        out[name] = {}
        for law in TANGENTIAL_LAWS:
            T = law_forces(law, u, radius)
            out[name][law] = float(np.max(np.hypot(T[:, 0] - Tx, T[:, 1] - Ty)) / muN)
        print(f"{name:18s} " + " ".join(f"{k} {v:.4f}" for k, v in out[name].items()), flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
