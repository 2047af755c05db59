"""The contact work of ``pair_style dem/contact`` (the LAMMPS plugin) for one step, compiled by numba and
called by the plugin's C++ pair style through a C function pointer (a numba ``cfunc``), once per step.

The pair style walks LAMMPS's neighbour list, finds the touching pairs and their history rows, and hands them
over in one canonical order (the atom with the lower id is body 1) with the law's inputs it gathered for each
pair (the normal, the overlap, the slip velocity with the full radii, the relative spin, the spin of the contact
frame). This kernel gives atoms not of their type's size their per-contact R* and m*, runs the tangential
family's batch loop (``dem.contact3d.batch_loop``, every law of the table inlined), and returns per contact the
force on body 1, the torques on both bodies (arm R - delta/2, as LAMMPS's granular models), the overlap, the
tangential force, the normal and the friction coefficient (and with ``energy yes`` the work of the contact's
forces, ``account_work``), or adds the forces and torques to LAMMPS's itself, with the virial.

``attach`` is what the plugin calls (from its embedded or the running Python interpreter) when a table file is
named by ``pair_coeff``: it reads the table (``dem.pairs.PairTable.load``), compiles the step for the table's
tangential family, and writes the addresses the pair style needs into the C structure the pair style passes.
"""
from __future__ import annotations

import ctypes
import math
import traceback

import numpy as np
from numba import carray, cfunc, njit, types

from ..dem.contact3d import _LOOPS, _torque_laws_of as torque_laws_of
from ..laws.dispatch import tangential_base, uses_rate
from ..laws.slots import N_PARAMS, P_MU, P_NORMAL_LAW, P_ROLLING_LAW, P_TANGENTIAL_LAW, P_TWIST_LAW
from ..laws.vector import V_N, W_WORK, renamed
from . import contact_terms as T

#: the layout version of ``Attach`` (the plugin refuses another)
ABI = 8

#: columns of the per-contact output: force on body 1 (3), torque on body 1 (3), torque on body 2 (3), overlap,
#: tangential force on body 1 (3), unit normal from body 1 to body 2 (3), friction coefficient, the work the
#: normal force and the tangential force have done on the contact since it began [J] (``X_WORK_N``, the law's
#: ``W_WORK``), the torque of the twist and rolling laws on body 1 (3)
OUT_F = 0
OUT_TA = 3
OUT_TB = 6
OUT_DELTA = 9
OUT_FT = 10
OUT_N = 13
OUT_MU = 16
OUT_WORK_N = 17
OUT_WORK_T = 18
OUT_Q = 19
N_OUT = 22

#: values the plugin keeps after the law's history in each contact row where it accounts the work of the
#: contact forces (then a row is history_size + N_EXTRA long):
#: the work the normal force has done on the contact since it began, the trapezoid sum of N d(delta) [J]; the
#: overlap at the last step [m]; the work of the normal and tangential forces together [J] (the law's W_WORK
#: added): what the contact absorbed, stored elastically while it lasts, and at its end the energy it
#: dissipated; the normal force at the last step [N]
X_WORK_N = 0
X_DELTA = 1
X_WORK = 2
X_N_LAST = 3
N_EXTRA = 4

#: what the pair style asks of a step (its flags argument, bits): the per-contact output, the forces and
#: torques added to LAMMPS's, the global virial, the work of the contact forces (``pair_style ... energy yes``:
#: its rows carry N_EXTRA values more)
WRITE_OUT = 1
SCATTER = 2
VIRIAL = 4
ENERGY = 8


@njit(inline="always", cache=True)
def account_work(H, r, w_col, delta, vx, vy, vz, nx, ny, nz, dt):
    """After the law's step of the contact of row r of H (whose last N_EXTRA values are the plugin's), with
    overlap delta, slip velocity v and normal n (the law's inputs; w_col: the column of the tangential law's
    running work W_WORK, ``work_column``): the normal force's work advanced by the trapezoid rule, 0.5 (N_last
    + N) (delta - delta_last), as the law's W_WORK is, and the total with W_WORK; the overlap and the normal
    force kept for the next step. A contact that begins (X_DELTA still 0) starts from its overlap at the last
    step, a gap, delta - dt (v . n), as the time integration moved the bodies, and no force: so the work of its
    forces is what the integration gave them (the kinetic energy the bodies lose)."""
    x0 = H.shape[1] - N_EXTRA
    last = H[r, x0 + X_DELTA]
    if last == 0.0:
        last = delta - dt * (vx * nx + vy * ny + vz * nz)
    n_now = H[r, V_N]
    wn = H[r, x0 + X_WORK_N] + 0.5 * (H[r, x0 + X_N_LAST] + n_now) * (delta - last)
    H[r, x0 + X_WORK_N] = wn
    H[r, x0 + X_DELTA] = delta
    H[r, x0 + X_N_LAST] = n_now
    H[r, x0 + X_WORK] = wn + H[r, w_col]


@njit(inline="always", cache=True)
def work_column(nid, params, row):
    """The column of the tangential law's running work W_WORK in a history row of parameter row ``row`` (after
    the normal, twist and rolling laws' states: ``laws.dispatch.tangential_base``)."""
    qid, rid = torque_laws_of(params, row)
    return tangential_base(nid, qid, rid) + W_WORK


@njit(inline="always", cache=True)
def work_columns(nid, params):
    """int64[n_rows]: ``work_column`` of every parameter row."""
    cols = np.empty(params.shape[0], dtype=np.int64)
    for row in range(params.shape[0]):
        cols[row] = work_column(nid, params, row)
    return cols


@njit(inline="always", cache=True)
def ended_work(H, r, delta_end):
    """The work done on the contact of row r of H that ended: X_WORK, with the last part of the normal work, from
    the last step's overlap and normal force to the overlap now, delta_end (a gap), and no force, by the
    trapezoid rule (as the plugin's C++, PairDemContact::ended_work)."""
    x0 = H.shape[1] - N_EXTRA
    return H[r, x0 + X_WORK] + 0.5 * H[r, V_N] * (delta_end - H[r, x0 + X_DELTA])


def _step(n, pairs, hrow, H, normals, overlaps, velocities, spins, wn, x, radius, rmass, typ, params, rowinfo,
          type_size, sized, dt, out, forces, tforces, torques, prow, pc, to, f, torque, write_out, scatter,
          with_virial, virial, energy):
    """The n contacts of the pairs ``pairs`` (int64[n, 2], body 1 the lower atom id) with the H rows ``hrow``
    (advanced in place; the caller passes copies where nothing may advance), and the law's inputs the pair style
    gathered: normals, velocities float64[n, 3], overlaps, wn float64[n] (the unit normal from body 1 to body 2,
    the overlap, the slip velocity with the full radii, the mean spin about the normal), spins float64[n, 3] (the
    relative spins, where the table has twist or rolling laws; else [0, 3]) and prow int64[n] (each pair's
    parameter row). The tangential family's loop (``loop``, bound per family), then what the pair style asks:
    ``out`` float64[n, N_OUT] (``write_out``), and (``scatter``) the forces and torques added to f, torque
    float64[nall, 3] of the local atoms to[k] (int64[n, 2], per body: the local atom that takes its force, the
    atom itself or, for a periodic image of a local atom evaluated once, that atom; -1: none), with the virial's
    six components added to ``virial`` (``with_virial``). forces, tforces float64[n, 3], torques float64[n, 3]
    (where spins has n rows, else [0, 3]): scratch for the law's outputs; pc float64[n_rows + n, N_PARAMS] (only
    where ``sized``: atoms not of their type's size get their own rows there, prow pointing at them);
    ``energy``: the rows carry N_EXTRA values after the law's history, the work of the contact's forces
    (``account_work``). Returns the number of contacts whose force or torques are not finite. (Nothing here
    allocates: it is compiled without numba's runtime, so that no reference counting runs in its loops, and it
    also runs compiled ahead of time, ``aot``.)"""
    nid = int(params[0, P_NORMAL_LAW]) - 1
    tid = int(params[0, P_TANGENTIAL_LAW]) - 1
    turning = spins.shape[0] > 0
    nr = params.shape[0]
    rows = params
    if sized:
        for r in range(nr):
            for q in range(params.shape[1]):
                pc[r, q] = params[r, q]
        rows = pc
        for k in range(n):
            a = pairs[k, 0]
            b = pairs[k, 1]
            if T.resized(radius, rmass, typ, type_size, a) or T.resized(radius, rmass, typ, type_size, b):
                rs, ms = T.effective(radius, rmass, a, b, rowinfo, prow[k])
                T.contact_row(params, prow[k], pc, nr + k, rowinfo, rs, ms)
                prow[k] = nr + k
    if uses_rate(nid):
        # dashpots see the normal velocity predicted at the end of the step (as the impact integrator)
        for k in range(n):
            a = pairs[k, 0]
            b = pairs[k, 1]
            kick = 0.5 * dt * H[hrow[k], V_N] * (1.0 / rmass[a] + 1.0 / rmass[b])
            for d in range(3):
                velocities[k, d] -= kick * normals[k, d]
    loop(nid, tid, rows, prow, H, hrow, normals, overlaps, velocities, spins, wn, dt, forces, tforces,  # noqa: F821
         torques)
    if energy:
        for k in range(n):
            account_work(H, hrow[k], work_column(nid, rows, prow[k]), overlaps[k], velocities[k, 0],
                         velocities[k, 1], velocities[k, 2], normals[k, 0], normals[k, 1], normals[k, 2], dt)
    # (one sum of every force and torque: not finite where any is)
    check = 0.0
    for k in range(n):
        a = pairs[k, 0]
        b = pairs[k, 1]
        cx, cy, cz = T.normal_cross(normals, tforces, k)
        delta = overlaps[k]
        # torque on a sphere: (R - delta/2) n x Ft on both bodies of the pair, and the twist and rolling laws'
        arm_a = radius[a] - 0.5 * delta
        arm_b = radius[b] - 0.5 * delta
        qx = qy = qz = 0.0
        if turning:
            qx = torques[k, 0]
            qy = torques[k, 1]
            qz = torques[k, 2]
        fx = forces[k, 0]
        fy = forces[k, 1]
        fz = forces[k, 2]
        tax = arm_a * cx + qx
        tay = arm_a * cy + qy
        taz = arm_a * cz + qz
        tbx = arm_b * cx - qx
        tby = arm_b * cy - qy
        tbz = arm_b * cz - qz
        check += (fx + fy + fz) + (tax + tay + taz) + (tbx + tby + tbz)
        if write_out:
            out[k, OUT_F] = fx
            out[k, OUT_F + 1] = fy
            out[k, OUT_F + 2] = fz
            out[k, OUT_TA] = tax
            out[k, OUT_TA + 1] = tay
            out[k, OUT_TA + 2] = taz
            out[k, OUT_TB] = tbx
            out[k, OUT_TB + 1] = tby
            out[k, OUT_TB + 2] = tbz
            out[k, OUT_DELTA] = delta
            for d in range(3):
                out[k, OUT_FT + d] = tforces[k, d]
                out[k, OUT_N + d] = normals[k, d]
            out[k, OUT_MU] = rows[prow[k], P_MU]
            out[k, OUT_Q] = qx
            out[k, OUT_Q + 1] = qy
            out[k, OUT_Q + 2] = qz
            if energy:
                x0 = H.shape[1] - N_EXTRA
                out[k, OUT_WORK_N] = H[hrow[k], x0 + X_WORK_N]
                out[k, OUT_WORK_T] = H[hrow[k], x0 + X_WORK] - H[hrow[k], x0 + X_WORK_N]
        if scatter:
            # LAMMPS's forces and torques of the local atoms (each summed over its contacts in their order)
            ta = to[k, 0]
            tb = to[k, 1]
            if ta >= 0:
                f[ta, 0] += fx
                f[ta, 1] += fy
                f[ta, 2] += fz
                torque[ta, 0] += tax
                torque[ta, 1] += tay
                torque[ta, 2] += taz
            if tb >= 0:
                f[tb, 0] -= fx
                f[tb, 1] -= fy
                f[tb, 2] -= fz
                torque[tb, 0] += tbx
                torque[tb, 1] += tby
                torque[tb, 2] += tbz
            if with_virial:
                # (as LAMMPS's ev_tally_xyz with newton off: half for each local atom of the pair)
                h = 0.5 * ((1.0 if ta >= 0 else 0.0) + (1.0 if tb >= 0 else 0.0))
                dx = x[a, 0] - x[b, 0]
                dy = x[a, 1] - x[b, 1]
                dz = x[a, 2] - x[b, 2]
                virial[0] += h * dx * fx
                virial[1] += h * dy * fy
                virial[2] += h * dz * fz
                virial[3] += h * dx * fy
                virial[4] += h * dx * fz
                virial[5] += h * dy * fz
    return 0 if math.isfinite(check) else _not_finite(n, forces, tforces, torques)


@njit(cache=True)
def _not_finite(n, forces, tforces, torques):
    """The number of contacts whose force, tangential force or twist and rolling torques are not finite."""
    bad = 0
    for k in range(n):
        ok = True
        for d in range(3):
            ok = ok and math.isfinite(forces[k, d]) and math.isfinite(tforces[k, d])
            if torques.shape[0] > 0:
                ok = ok and math.isfinite(torques[k, d])
        bad += 0 if ok else 1
    return max(bad, 1)


def _entry(n, pairs, hrow, H, h_rows, hs, normals, overlaps, velocities, spins, wn, turning, x, radius, rmass, typ,
           nall, params, n_rows, rowinfo, type_size, n_types, sized, dt, out, forces, tforces, torques, prow, pc, to,
           f, torque, flags, virial):
    """The C entry of ``_step``: raw pointers of the pair style's buffers and LAMMPS's per-atom arrays."""
    m = n if turning else 0
    n_pc = n_rows + (n if sized else 0)
    return step(n, carray(pairs, (n, 2)), carray(hrow, (n,)), carray(H, (h_rows, hs)),  # noqa: F821
                carray(normals, (n, 3)), carray(overlaps, (n,)), carray(velocities, (n, 3)),
                carray(spins, (m, 3)), carray(wn, (n,)), carray(x, (nall, 3)),
                carray(radius, (nall,)), carray(rmass, (nall,)), carray(typ, (nall,)),
                carray(params, (n_rows, N_PARAMS)), carray(rowinfo, (n_rows, T.N_ROWINFO)),
                carray(type_size, (n_types, 2)), sized != 0, dt, carray(out, (n, N_OUT)),
                carray(forces, (n, 3)), carray(tforces, (n, 3)), carray(torques, (m, 3)),
                carray(prow, (n,)), carray(pc, (n_pc, N_PARAMS)),
                carray(to, (n, 2)), carray(f, (nall, 3)), carray(torque, (nall, 3)), (flags & WRITE_OUT) != 0,
                (flags & SCATTER) != 0, (flags & VIRIAL) != 0, carray(virial, (6,)), (flags & ENERGY) != 0)


_I64P = types.CPointer(types.int64)
_F64P = types.CPointer(types.float64)
#: the C signature of the step (``pair_dem_contact.cpp``, ``StepFn``)
SIGNATURE = types.int64(types.int64, _I64P, _I64P, _F64P, types.int64, types.int64, _F64P, _F64P, _F64P, _F64P,
                        _F64P, types.int64, _F64P, _F64P, _F64P, types.CPointer(types.int32), types.int64, _F64P,
                        types.int64, _F64P, _F64P, types.int64, types.int64, types.float64, _F64P, _F64P, _F64P,
                        _F64P, _I64P, _F64P, _I64P, _F64P, _F64P, types.int64, _F64P)

_CFUNCS = {}


def step_function(tid: int):
    """The compiled C entry of the step for tangential family ``tid`` (a numba cfunc; compiled once per
    process, cached on disk as the package's kernels)."""
    if tid not in _CFUNCS:
        name = f"lammps_step_{tid}"
        step = njit(cache=True, _nrt=False)(renamed(_step, name, loop=_LOOPS[tid][0]))
        _CFUNCS[tid] = cfunc(SIGNATURE, cache=True)(renamed(_entry, f"{name}_entry", step=step))
    return _CFUNCS[tid]


class Attach(ctypes.Structure):
    """What the pair style reads after ``attach`` (the C struct ``DemContactAttach`` of
    ``pair_dem_contact.h``, field for field)."""

    _fields_ = [
        ("abi", ctypes.c_int64),
        ("error", ctypes.c_char * 2048),
        ("step", ctypes.c_void_p),
        ("params", ctypes.c_void_p),
        ("n_rows", ctypes.c_int64),
        ("sphere_row", ctypes.c_void_p),
        ("n_types", ctypes.c_int64),
        ("rowinfo", ctypes.c_void_p),
        ("type_size", ctypes.c_void_p),
        ("size_free", ctypes.c_int64),
        ("history_size", ctypes.c_int64),
        ("turning", ctypes.c_int64),
        ("tc_unit", ctypes.c_void_p),
        ("alpha", ctypes.c_void_p),
        ("laws", ctypes.c_char * 512),
    ]


#: the arrays the pair styles of this process read, by the address of their Attach (kept alive here; a pair
#: style made later at the same address replaces them)
_KEPT = {}


def attach(path: str, n_types: int, address: int) -> None:
    """Read the table file ``path`` for a LAMMPS run with ``n_types`` atom types and fill the Attach at
    ``address``; any failure is written to its ``error`` field (the pair style stops with it)."""
    out = Attach.from_address(address)
    try:
        _attach(path, n_types, out, address)
    except Exception as e:      # (every failure reaches LAMMPS as its error message)
        from ..errors import InputError
        text = str(e) if isinstance(e, InputError) else f"{type(e).__name__}: {e}\n{traceback.format_exc()}"
        out.error = text.encode()[:2047]


def _attach(path, n_types, out, address):
    from ..errors import InputError
    from . import table_file

    if out.abi != ABI:
        raise InputError(f"the plugin was built for another version of dem_contact (interface {out.abi}, this "
                         f"package's is {ABI}): build it again with `dem-contact lammps-plugin --rebuild`")
    saved = table_file.load(path)
    table = saved.table
    nt = table.sphere_row.shape[0]
    if nt != n_types:
        raise InputError(f"the table file {path} is for {nt} atom types, the LAMMPS box has {n_types}: write "
                         f"it for the box's types (PairTable.save)")
    arrays = dict(params=table.params, sphere_row=table.sphere_row, rowinfo=np.ascontiguousarray(saved.rowinfo),
                  type_size=np.ascontiguousarray(saved.type_size), tc_unit=np.ascontiguousarray(saved.tc_unit),
                  alpha=np.ascontiguousarray(saved.alpha))
    fn = step_function(table.tangential_id)
    _KEPT[address] = (arrays, fn)
    out.step = fn.address
    for name, a in arrays.items():
        setattr(out, name, a.ctypes.data)
    out.n_rows = table.params.shape[0]
    out.n_types = nt
    out.size_free = int(saved.size_free)
    out.history_size = table.history_size
    out.turning = int(bool(np.any(table.params[:, P_TWIST_LAW] > 1) or np.any(table.params[:, P_ROLLING_LAW] > 1)))
    out.laws = saved.laws.encode()[:511]
    out.error = b""

