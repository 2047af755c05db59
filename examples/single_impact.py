"""One oblique impact of a steel sphere on a steel wall (the EE scene of Wu, Thornton & Li 2009).

Usage: python examples/single_impact.py [--vn 5] [--angle 30] [--tangential md] [--steps 1000]
Prints the rebound quantities and checks the momentum identity Omega_r = Omega_i - f/mu (Wu, Thornton & Li 2009, eq. 2.22).
"""
import argparse
import math

from dem_contact import STEEL, Scene, Sphere, Wall, impact, reference_speed


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--vn", type=float, default=5.0, help="normal speed [m/s]")
    ap.add_argument("--angle", type=float, default=30.0, help="impact angle from the normal [deg]")
    ap.add_argument("--tangential", default=None, help="tangential law (default: the library default)")
    ap.add_argument("--steps", type=float, default=None, help="steps per contact time")
    a = ap.parse_args(argv)
    laws = {} if a.tangential is None else {"tangential": a.tangential}
    scene = Scene(Sphere(0.01, STEEL), Wall(STEEL), mu=0.3, v_ref=reference_speed(a.vn), **laws)
    r = impact(scene, a.vn, a.vn * math.tan(math.radians(a.angle)), steps_per_contact=a.steps)
    print(f"laws: {scene.normal} x {scene.tangential}, vn = {a.vn} m/s, angle = {a.angle} deg")
    for k in ("e_n", "e_t", "f_over_mu", "Theta", "Psi_r", "Omega_r", "contact_time", "max_force"):
        print(f"  {k:14s} {getattr(r, k):.6g}")
    err = abs(r.Omega_r - (r.Omega_i - r.f_over_mu))
    print(f"  |Omega_r - (Omega_i - f/mu)| = {err:.2e}")
    return 0 if err < 1e-9 else 1


if __name__ == "__main__":
    raise SystemExit(main())
