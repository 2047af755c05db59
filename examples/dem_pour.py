"""Pour spheres of two materials into a box: a small complete DEM code around dem_contact's 3D kernel.

Velocity Verlet for positions, velocities and spins; gravity; five walls (floor and four sides, each
with its own material); a cell-list neighbour search; contact histories kept per particle and carried
from step to step; every contact force from ``dem_contact.dem.contact3d.contact_force``.

Writes into --out: legacy VTK files ``pour_XXXX.vtk`` (open the series in ParaView: points with
radius, type, velocity, force), ``energy.csv`` (kinetic, potential, elastic and total energy over time),
and ``pour.png`` (side view of the final packing and the energy curves). Run ``--small`` for a quick test.

Usage: python examples/dem_pour.py [--n 800] [--time 0.3] [--small] [--out dem_pour_out]
"""
import argparse
import math
import os
import time

import numpy as np
from numba import njit

from dem_contact.dem.contact3d import contact_force, new_histories, reset_contact
from dem_contact.laws.slots import P_ESTAR, P_RSTAR
from dem_contact.materials import Material, Sphere, Wall
from dem_contact.dem.pairs import pair_table

GRAVITY = 9.81
MAX_CONTACTS = 16          # contact slots per particle (partners j > i)
N_WALLS = 5                # x = 0, x = L, y = 0, y = L, z = 0
WALL_NORMALS = np.array([[-1.0, 0, 0], [1.0, 0, 0], [0, -1.0, 0], [0, 1.0, 0], [0, 0, -1.0]])  # body 1 -> wall


@njit(cache=True)
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(cache=True)
def _build_cells(pos, cell, nc, head, nxt):
    head[:] = -1
    for i in range(pos.shape[0]):
        cx = min(max(int(pos[i, 0] / cell), 0), nc[0] - 1)
        cy = min(max(int(pos[i, 1] / cell), 0), nc[1] - 1)
        cz = min(max(int(pos[i, 2] / cell), 0), nc[2] - 1)
        k = (cx * nc[1] + cy) * nc[2] + cz
        nxt[i] = head[k]
        head[k] = i


@njit(cache=True)
def _forces(nid, tid, params, srow, wrow, typ, pos, vel, omg, rad, mass, L, dt, cell, nc, head, nxt,
            cj, cH, nj, nH, Hw, F, Tq):
    """Contact and gravity forces and torques. Old contact lists (cj, cH) -> new (nj, nH); the history of
    slot m of particle i is row i * MAX_CONTACTS + m of cH / nH, that of particle i on wall w row
    i * N_WALLS + w of Hw.
    Returns the elastic (Hertz) energy stored in the contacts."""
    n = pos.shape[0]
    F[:] = 0.0
    Tq[:] = 0.0
    nj[:] = -1
    eel = 0.0
    for i in range(n):
        F[i, 2] -= mass[i] * GRAVITY
    for i in range(n):
        cx = min(max(int(pos[i, 0] / cell), 0), nc[0] - 1)
        cy = min(max(int(pos[i, 1] / cell), 0), nc[1] - 1)
        cz = min(max(int(pos[i, 2] / cell), 0), nc[2] - 1)
        m = 0
        for ax in range(max(cx - 1, 0), min(cx + 2, nc[0])):
            for ay in range(max(cy - 1, 0), min(cy + 2, nc[1])):
                for az in range(max(cz - 1, 0), min(cz + 2, nc[2])):
                    j = head[(ax * nc[1] + ay) * nc[2] + az]
                    while j >= 0:
                        if j > i:
                            dx = pos[j, 0] - pos[i, 0]
                            dy = pos[j, 1] - pos[i, 1]
                            dz = pos[j, 2] - pos[i, 2]
                            dist = math.sqrt(dx * dx + dy * dy + dz * dz)
                            delta = rad[i] + rad[j] - dist
                            if delta > 0.0 and m < MAX_CONTACTS:
                                # carry the history of (i, j) over from the previous step
                                nj[i, m] = j
                                c = i * MAX_CONTACTS + m
                                nH[c, :] = 0.0
                                for q in range(MAX_CONTACTS):
                                    if cj[i, q] == j:
                                        nH[c, :] = cH[i * MAX_CONTACTS + q, :]
                                        break
                                nx, ny, nz = dx / dist, dy / dist, dz / dist
                                ri = rad[i] - 0.5 * delta          # centre -> contact point, along n
                                rj = rad[j] - 0.5 * delta          # along -n
                                wi = _cross(omg[i, 0], omg[i, 1], omg[i, 2], ri * nx, ri * ny, ri * nz)
                                wj = _cross(omg[j, 0], omg[j, 1], omg[j, 2], -rj * nx, -rj * ny, -rj * nz)
                                vx = vel[i, 0] + wi[0] - vel[j, 0] - wj[0]
                                vy = vel[i, 1] + wi[1] - vel[j, 1] - wj[1]
                                vz = vel[i, 2] + wi[2] - vel[j, 2] - wj[2]
                                # the contact frame turns with the mean spin about the normal
                                wn = 0.5 * ((omg[i, 0] + omg[j, 0]) * nx + (omg[i, 1] + omg[j, 1]) * ny
                                            + (omg[i, 2] + omg[j, 2]) * nz)
                                row = srow[typ[i], typ[j]]
                                fx, fy, fz, tx, ty, tz = contact_force(nid, tid, params, row, nH, c, nx, ny, nz,
                                                                       delta, vx, vy, vz, wn, dt)
                                F[i, 0] += fx
                                F[i, 1] += fy
                                F[i, 2] += fz
                                F[j, 0] -= fx
                                F[j, 1] -= fy
                                F[j, 2] -= fz
                                a = _cross(ri * nx, ri * ny, ri * nz, tx, ty, tz)
                                b = _cross(-rj * nx, -rj * ny, -rj * nz, -tx, -ty, -tz)
                                for k in range(3):
                                    Tq[i, k] += a[k]
                                    Tq[j, k] += b[k]
                                eel += (8.0 / 15.0 * params[row, P_ESTAR] * math.sqrt(params[row, P_RSTAR])
                                        * delta ** 2.5)
                                m += 1
                        j = nxt[j]
        for w in range(N_WALLS):
            ax = w // 2
            if w == 4:
                delta = rad[i] - pos[i, 2]
            elif w % 2 == 0:
                delta = rad[i] - pos[i, ax]
            else:
                delta = pos[i, ax] + rad[i] - L
            if delta <= 0.0:
                reset_contact(Hw, i * N_WALLS + w)
                continue
            nx = ny = nz = 0.0
            if w == 4:
                nz = -1.0
            elif ax == 0:
                nx = -1.0 if w % 2 == 0 else 1.0
            else:
                ny = -1.0 if w % 2 == 0 else 1.0
            ri = rad[i] - delta
            wi = _cross(omg[i, 0], omg[i, 1], omg[i, 2], ri * nx, ri * ny, ri * nz)
            row = wrow[typ[i], w]
            wn = 0.5 * (omg[i, 0] * nx + omg[i, 1] * ny + omg[i, 2] * nz)
            fx, fy, fz, tx, ty, tz = contact_force(nid, tid, params, row, Hw, i * N_WALLS + w, nx, ny, nz, delta,
                                                   vel[i, 0] + wi[0], vel[i, 1] + wi[1], vel[i, 2] + wi[2], wn, dt)
            F[i, 0] += fx
            F[i, 1] += fy
            F[i, 2] += fz
            a = _cross(ri * nx, ri * ny, ri * nz, tx, ty, tz)
            for k in range(3):
                Tq[i, k] += a[k]
            eel += 8.0 / 15.0 * params[row, P_ESTAR] * math.sqrt(params[row, P_RSTAR]) * delta ** 2.5
    return eel


@njit(cache=True)
def run_steps(nsteps, nid, tid, params, srow, wrow, typ, pos, vel, omg, rad, mass, inv_I, L, dt, cell, nc,
              head, nxt, cj, cH, nj, nH, Hw, F, Tq):
    """Advance ``nsteps`` velocity-Verlet steps. Returns the elastic energy at the last step."""
    eel = 0.0
    n = pos.shape[0]
    for s in range(nsteps):
        for i in range(n):
            for k in range(3):
                vel[i, k] += 0.5 * dt * F[i, k] / mass[i]
                omg[i, k] += 0.5 * dt * Tq[i, k] * inv_I[i]
                pos[i, k] += vel[i, k] * dt
        _build_cells(pos, cell, nc, head, nxt)
        eel = _forces(nid, tid, params, srow, wrow, typ, pos, vel, omg, rad, mass, L, dt, cell, nc, head, nxt,
                      cj, cH, nj, nH, Hw, F, Tq)
        cj[:] = nj
        cH[:] = nH
        for i in range(n):
            for k in range(3):
                vel[i, k] += 0.5 * dt * F[i, k] / mass[i]
                omg[i, k] += 0.5 * dt * Tq[i, k] * inv_I[i]
    return eel


def write_vtk(path, pos, vel, F, rad, typ):
    """Legacy ASCII VTK polydata: one vertex per sphere with radius, type, velocity and force."""
    n = pos.shape[0]
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\ndem_contact pour\nASCII\nDATASET POLYDATA\n")
        f.write(f"POINTS {n} double\n")
        np.savetxt(f, pos, fmt="%.9g")
        f.write(f"VERTICES {n} {2 * n}\n")
        np.savetxt(f, np.column_stack([np.ones(n, int), np.arange(n)]), fmt="%d")
        f.write(f"POINT_DATA {n}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
        np.savetxt(f, rad, fmt="%.9g")
        f.write("SCALARS type int 1\nLOOKUP_TABLE default\n")
        np.savetxt(f, typ, fmt="%d")
        f.write("VECTORS velocity double\n")
        np.savetxt(f, vel, fmt="%.9g")
        f.write("VECTORS force double\n")
        np.savetxt(f, F, fmt="%.9g")


def snapshot(path, pos, rad, typ, L, energy):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.5))
    for t, c in ((0, "tab:blue"), (1, "tab:orange")):
        s = typ == t
        a1.scatter(pos[s, 0] * 1e3, pos[s, 2] * 1e3, s=(rad[s] * 1e3 * 4) ** 2, c=c, alpha=0.7,
                   label=f"type {t}")
    a1.set(xlim=(0, L * 1e3), ylim=(0, None), aspect="equal", xlabel="x [mm]", ylabel="z [mm]",
           title="side view")
    a1.legend(loc="upper right")
    e = np.array(energy)
    for k, lab in ((1, "kinetic"), (2, "potential"), (3, "elastic"), (4, "total")):
        a2.plot(e[:, 0], e[:, k], label=lab)
    a2.set(xlabel="t [s]", ylabel="energy [J]", title="energy")
    a2.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=800, help="number of spheres (default 800)")
    ap.add_argument("--time", type=float, default=0.3, help="simulated time [s] (default 0.3)")
    ap.add_argument("--small", action="store_true", help="60 spheres, 0.05 s (for tests)")
    ap.add_argument("--frames", type=int, default=10, help="number of VTK frames")
    ap.add_argument("--tangential", default=None, help="tangential law (default: the library default)")
    ap.add_argument("--out", default="dem_pour_out", help="output directory")
    a = ap.parse_args(argv)
    if a.small:
        a.n, a.time, a.frames = 60, 0.05, 2
    if a.n < 1 or a.time <= 0 or a.frames < 1:
        ap.error("--n, --time and --frames must be positive")
    os.makedirs(a.out, exist_ok=True)
    # two materials (moduli reduced, as usual in DEM, to allow a larger time step); walls of a third one
    R = 2e-3
    glass = Material(E=5e7, nu=0.25, rho=2500.0)
    polymer = Material(E=1e7, nu=0.4, rho=1200.0)
    steel = Material(E=2e8, nu=0.3, rho=7800.0)
    types = [Sphere(R, glass), Sphere(1.25 * R, polymer)]
    tab = pair_table(types, [Wall(steel)] * N_WALLS, mu=0.4, normal="hertz_damped", e_n=0.6,
                     tangential=a.tangential)
    rmax = max(s.radius for s in types)
    per_side = max(2, int(math.ceil(math.sqrt(a.n / 12))))
    spacing = 2.2 * rmax
    L = per_side * spacing
    rng = np.random.default_rng(1)
    idx = np.arange(a.n)
    lay, rem = np.divmod(idx, per_side * per_side)
    pos = np.column_stack([(rem % per_side + 0.5) * spacing, (rem // per_side + 0.5) * spacing,
                           4 * rmax + lay * spacing]).astype(float)
    pos[:, :2] += rng.uniform(-0.1, 0.1, size=(a.n, 2)) * rmax
    typ = rng.integers(0, 2, size=a.n).astype(np.int64)
    rad = np.array([types[t].radius for t in typ])
    mass = np.array([types[t].mass for t in typ])
    inv_I = 1.0 / np.array([types[t].inertia for t in typ])
    vel = rng.normal(scale=0.05, size=(a.n, 3))
    omg = np.zeros((a.n, 3))
    # time step: 1/25 of the shortest Hertz contact time at the largest impact speed
    vmax = math.sqrt(2 * GRAVITY * pos[:, 2].max()) + 0.2
    tc = min(sc.contact_time(vmax) for sc in tab.scenes)
    dt = tc / 25
    cell = 2 * rmax
    nc = np.array([max(1, int(L / cell)), max(1, int(L / cell)), max(1, int(pos[:, 2].max() / cell) + 2)])
    cell = L / nc[0]
    head = np.full(nc.prod(), -1, dtype=np.int64)
    nxt = np.full(a.n, -1, dtype=np.int64)
    hs = tab.history_size
    cj, nj = (np.full((a.n, MAX_CONTACTS), -1, dtype=np.int64) for _ in range(2))
    cH, nH = (new_histories(a.n * MAX_CONTACTS, hs) for _ in range(2))
    Hw = new_histories(a.n * N_WALLS, hs)
    F, Tq = np.zeros((a.n, 3)), np.zeros((a.n, 3))
    state = (tab.normal_id, tab.tangential_id, tab.params, tab.sphere_row, tab.wall_row, typ, pos, vel, omg,
             rad, mass, inv_I, L, dt, cell, nc, head, nxt, cj, cH, nj, nH, Hw, F, Tq)
    nsteps = int(math.ceil(a.time / dt))
    chunk = max(1, nsteps // (5 * a.frames))
    energy = []
    t0 = time.perf_counter()
    print(f"{a.n} spheres, box {L * 1e3:.1f} mm, dt = {dt:.3g} s, {nsteps} steps, "
          f"laws: {tab.scenes[0].normal} x {tab.scenes[0].tangential}")
    print(f"{'t [s]':>8} {'kinetic [J]':>12} {'potential [J]':>14} {'elastic [J]':>12} {'total [J]':>12}")
    step, frame = 0, 0
    while step < nsteps:
        k = min(chunk, nsteps - step)
        eel = run_steps(k, *state)
        step += k
        ek = 0.5 * np.sum(mass * np.sum(vel**2, axis=1)) + 0.5 * np.sum(np.sum(omg**2, axis=1) / inv_I)
        ep = GRAVITY * np.sum(mass * pos[:, 2])
        energy.append((step * dt, ek, ep, eel, ek + ep + eel))
        if len(energy) % 5 == 0 or step == nsteps:
            print(f"{step * dt:8.4f} {ek:12.5g} {ep:14.6g} {eel:12.4g} {ek + ep + eel:12.6g}")
            write_vtk(os.path.join(a.out, f"pour_{frame:04d}.vtk"), pos, vel, F, rad, typ)
            frame += 1
    wall = time.perf_counter() - t0
    if not np.all(np.isfinite(pos)):
        raise SystemExit("non-finite positions")
    np.savetxt(os.path.join(a.out, "energy.csv"), np.array(energy), delimiter=",",
               header="t,kinetic,potential,elastic,total", comments="")
    snapshot(os.path.join(a.out, "pour.png"), pos, rad, typ, L, energy)
    print(f"wall time {wall:.1f} s ({nsteps / wall:.0f} steps/s); outputs in {a.out}/")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
