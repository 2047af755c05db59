"""f/mu against Theta for an oblique-impact sweep (Wu, Thornton & Li 2009, figure 5 style).

Usage: python examples/sweep.py [--n 30] [--tangential md] [--steps 500] [--png sweep.png]
"""
import argparse

import numpy as np

from dem_contact import STEEL, Scene, Sphere, Wall, reference_speed
from dem_contact.impacts.sweep import sweep_theta


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=30, help="number of impacts")
    ap.add_argument("--vn", type=float, default=5.0, help="normal speed [m/s]")
    ap.add_argument("--tangential", default=None, help="tangential law (default: the library default)")
    ap.add_argument("--steps", type=float, default=500, help="steps per contact time")
    ap.add_argument("--png", default=None, help="write the sweep figure here")
    a = ap.parse_args(argv)
    laws = {} if a.tangential is None else {"tangential": a.tangential}
    scene = Scene(Sphere(0.01, STEEL), Wall(STEEL), mu=0.3, v_ref=reference_speed(a.vn), **laws)
    Theta = np.linspace(0.2, 8.0, a.n)
    res = sweep_theta(scene, Theta, vn=a.vn, steps_per_contact=a.steps)
    print(f"laws: {scene.normal} x {scene.tangential}")
    print(f"{'Theta':>8} {'f/mu':>8} {'Psi_r':>8} {'e_t':>8}")
    for p in res.points:
        print(f"{p.Theta:8.3f} {p.f_over_mu:8.4f} {p.Psi_r:8.4f} {p.e_t:8.4f}")
    if a.png:
        from dem_contact.plots import sweep_figure

        sweep_figure(res, a.png, kappa=scene.pair.kappa)
        print(f"figure: {a.png}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
