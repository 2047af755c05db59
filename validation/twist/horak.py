"""Horak's spinning impact: a steel sphere spinning about the vertical at w0, dropped at vn on a steel plane
(no tangential velocity), with the exact twist law (deresiewicz), LAMMPS's engine models (marshall; sds with the Hertz values at the
largest force) and with no twist law; and an oblique impact
with spin about the normal.

The spin lost in the impact, 1 - w_r / w0, against Psi = w0 t_c / beta_1, the twist over the contact time in
units of the no-slip twist at unit moment at the largest force (beta_1 = mu N a / ((16/3) G_c a^3)). Small
Psi: the contact sticks and acts as a torsional spring (a loss independent of w0, set by the contact time
and the torsional stiffness against the inertia); large Psi: full slip, the angular impulse of Lubkin's
moment (3 pi/16) mu int N a dt, so 1 - w_r / w0 = (3 pi/16) mu int N a dt / (I w0) (drawn).

    python validation/twist/horak.py

Writes validation/twist/horak.png and horak.json.
"""
import json
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from dem_contact.impacts.impact3d import impact3d  # noqa: E402
from dem_contact.laws.model import Scene  # noqa: E402
from dem_contact.laws.twist import deresiewicz as d  # noqa: E402
from dem_contact.materials import STEEL, Sphere, Wall  # noqa: E402

HERE = pathlib.Path(__file__).parent
R, MU = 5e-3, 0.3


def main():
    out = {"sphere": "steel R 5 mm on a steel plane", "mu": MU, "runs": []}
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    for vn, mark in ((0.2, "o"), (2.0, "s")):
        sc = Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU, twist="deresiewicz")
        base = impact3d(sc, vn, series=True)
        s = base.series
        a = np.sqrt(sc.pair.R_star * np.clip(s["overlap"], 0.0, None))
        Na = np.trapezoid(np.clip(s["normal_force"], 0, None) * a, s["t"])
        I = 0.4 * sc.sphere.mass * R * R
        dw_slip = 3 * math.pi / 16 * MU * Na / I          # the spin lost in full slip
        Gc = d.twist_modulus(sc.sphere, sc.body2)
        Nmax, amax = base.max_force, math.sqrt(sc.pair.R_star * base.max_overlap)
        beta1 = MU * Nmax * amax / (16 / 3 * Gc * amax**3)
        tc = base.contact_time
        # the engine models: marshall as LAMMPS derives it; sds with the Hertz values at the largest force
        # (Lubkin's no-slip stiffness and full-slip moment per unit N), no dashpot
        engines = {"marshall": sc.replace(twist="marshall"),
                   "sds (Hertz values at F_max)": sc.replace(twist="sds", k_twist=16 / 3 * Gc * amax**3,
                                                             gamma_twist=0.0, mu_twist=3 * math.pi / 16 * MU * amax)}
        rows = []
        for Psi in np.geomspace(0.01, 1000.0, 21):
            w0 = Psi * beta1 / tc
            r = impact3d(sc, vn, (0.0, 0.0), (0.0, 0.0, w0))
            r0 = impact3d(sc.replace(twist="none"), vn, (0.0, 0.0), (0.0, 0.0, w0))
            rows.append(dict(Psi=Psi, w0=w0, lost=1 - r.spin_r[2] / w0, lost_none=1 - r0.spin_r[2] / w0,
                             lost_full_slip=dw_slip / w0, energy_error=r.energy.error / r.energy.initial,
                             twist_work=r.energy.friction,
                             **{f"lost {k}": 1 - impact3d(e, vn, (0.0, 0.0), (0.0, 0.0, w0)).spin_r[2] / w0
                                for k, e in engines.items()}))
        out["runs"].append({"vn": vn, "int_N_a_dt": Na, "full_slip_spin_loss": dw_slip, "beta_1_at_max_force": beta1,
                            "contact_time": tc, "rows": rows})
        P = np.array([x["Psi"] for x in rows])
        axs[0].loglog(P, [x["lost"] for x in rows], mark, label=f"deresiewicz, vn = {vn} m/s")
        axs[0].loglog(P, [x["lost_full_slip"] for x in rows], "-", lw=0.8,
                      label=f"full slip throughout, vn = {vn} m/s")
        for k, st in zip(engines, ("x", "+")):
            axs[0].loglog(P, [x[f"lost {k}"] for x in rows], st, ms=5, label=f"{k}, vn = {vn} m/s")
    axs[0].set_xlabel("Psi = w0 t_c / beta_1 (beta_1 at the largest force)")
    axs[0].set_ylabel("1 - w_r / w0 (spin about the normal lost)")
    axs[0].set_title("Horak: a spinning sphere dropped on a plane (no twist law: no loss)")
    axs[0].legend(fontsize=7)
    # oblique impact with spin about the normal: the spin plane turns
    sc = Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU, twist="deresiewicz")
    obl = {}
    for tw in ("none", "deresiewicz"):
        r = impact3d(sc.replace(twist=tw), 1.0, (0.5, 0.0), (0.0, 0.0, 2000.0), series=True)
        s = r.series
        ang = np.degrees(np.arctan2(s["tangential_force_y"], s["tangential_force_x"]))
        axs[1].plot(s["t"] * 1e6, s["spin_z"], label=f"spin about the normal, {tw}")
        obl[tw] = {"spin_r": r.spin_r, "vt_r": r.vt_r, "out_of_plane_angle_deg": r.out_of_plane_angle_deg,
                   "force_angle_deg_at_end": float(ang[len(ang) // 2]), "energy_error": r.energy.error / r.energy.initial}
    axs[1].set_xlabel("t [us]")
    axs[1].set_ylabel("w_z [rad/s]")
    axs[1].set_title("oblique impact, vt 0.5 m/s, vn 1 m/s, w_z 2000 rad/s")
    axs[1].legend(fontsize=7)
    out["oblique"] = obl
    fig.tight_layout()
    fig.savefig(HERE / "horak.png", dpi=120)
    (HERE / "horak.json").write_text(json.dumps(out, indent=1, default=float))
    print(json.dumps(out, indent=1, default=float))


if __name__ == "__main__":
    main()
