"""Compose a normal law, a tangential law and mu, and compare the compositions on the same impact.

Usage: python examples/custom_composition.py [--normal hertz thornton] [--tangential md mindlin_total]
       [--mu 0.1 0.3] [--angle 20] [--steps 500]
"""
import argparse
import math
import warnings

from dem_contact import NORMAL_LAWS, TANGENTIAL_LAWS, Material, Scene, Sphere, Wall, impact, reference_speed
from dem_contact.materials import STEEL

# a steel sphere that yields (p_y = 1.6 Y, Y = 1.85 GPa, the PE scene) so that thornton can be composed too
SPHERE = Sphere(0.01, Material(E=208e9, nu=0.3, rho=7850.0, yield_stress=1.85e9))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--normal", nargs="+", default=["hertz", "thornton"], choices=list(NORMAL_LAWS))
    ap.add_argument("--tangential", nargs="+", default=["md", "mindlin_total", "mindlin_incremental"],
                    choices=list(TANGENTIAL_LAWS))
    ap.add_argument("--mu", nargs="+", type=float, default=[0.3])
    ap.add_argument("--vn", type=float, default=5.0, help="normal speed [m/s]")
    ap.add_argument("--angle", type=float, default=20.0, help="impact angle [deg]")
    ap.add_argument("--steps", type=float, default=500, help="steps per contact time")
    a = ap.parse_args(argv)
    vt = a.vn * math.tan(math.radians(a.angle))
    print(f"{'normal':>12} {'tangential':>20} {'mu':>5} {'e_n':>8} {'e_t':>8} {'f/mu':>8} {'energy err':>11} {'creates energy':>15}")
    for normal in a.normal:
        for tangential in a.tangential:
            for mu in a.mu:
                # e_n sets the dashpots; thornton takes p_y from the sphere's yield stress, hertz is elastic
                scene = Scene(SPHERE, Wall(STEEL), mu=mu, normal=normal, tangential=tangential,
                              e_n=0.8 if normal in ("hertz_damped", "linear") else None, v_ref=reference_speed(a.vn))
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")          # reported in the last column
                    r = impact(scene, a.vn, vt, steps_per_contact=a.steps)
                print(f"{normal:>12} {tangential:>20} {mu:5.2f} {r.e_n:8.4f} {r.e_t:8.4f} {r.f_over_mu:8.4f} "
                      f"{r.energy.error / r.energy.initial:11.2e} {str(bool(r.energy_created)):>15}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
