"""The contact work of ``fix dem/contact/wall`` (the LAMMPS plugin's walls) for one step, compiled by numba and
called by the fix's C++ code through a C function pointer (a numba ``cfunc``), once per step.

A fix is one wall of the walls room (``dem_contact.walls``: a plane, a cylinder or an STL mesh, with a rigid
motion) and its words in the input script are read here (``parse``):

    fix ID GROUP dem/contact/wall KIND ARGS [wall W] [velocity VX VY VZ] [angular_velocity WX WY WZ]
        [centre CX CY CZ] [slots N]

    plane PX PY PZ NX NY NZ             a point and the unit normal into the spheres' side
    cylinder PX PY PZ AX AY AZ RC SIDE  a point on the axis, the axis, the radius, SIDE in (spheres inside) or
                                        out (outside); curved contacts (R* with -+ 1/(2 RC)); flat: SIDE
                                        followed by the word flat
    mesh FILE [scale S]                 an STL file (ASCII or binary), its coordinates times S [m], or a packed
                                        mesh file (``mesh_file``: the only mesh the plugin compiled ahead of
                                        time reads)

``wall W``: the wall's material, the W-th wall of the table file (0, 1, ...: ``dem-contact lammps-table --wall``);
the rigid motion (``walls.contract``): the velocity of the centre [m/s] and the angular velocity about it
[rad/s] (the centre by default the plane's point, the cylinder's axis point, the mean of the mesh's triangles'
corners); ``slots``: history rows per atom (default: 1 for a plane or a cylinder, 6 for a mesh: the patches an
atom touches at once).

The step: the wall placed at the time now, the elements near each atom of the group
(``walls.search.near_elements``), the law's inputs of each touching element (``contact_terms.wall_slip``),
its history row found by the contact's key (``walls.table.history_key``) among the atom's rows (kept by the
fix, which moves them with the atom), the tangential family's batch loop (every law of the table inlined),
and the force and torque (arm R, as LAMMPS's ``fix wall/gran``) added to the atom, with the wall's load
summed (``contact_terms.add_wall_load``).
"""
from __future__ import annotations

import ctypes
import math
import traceback

import numpy as np
from numba import carray, cfunc, njit, types

from ..dem.contact3d import _LOOPS
from ..laws.dispatch import uses_rate
from ..laws.slots import N_PARAMS, P_MU, P_NORMAL_LAW, P_TANGENTIAL_LAW
from ..laws.vector import V_N, renamed
from ..walls import search as WS
from ..walls import table as W
from . import contact_terms as T
from . import pair_kernel as PK

#: the layout version of ``WallAttach`` (the plugin refuses another)
ABI = 6

#: what the fix asks of a step (its flags argument, bits): advance the histories (not a run's set-up), save
#: the atoms' wall forces with their state (a run's last step), reapply the saved forces of the atoms whose
#: state is that saved (a run's set-up), pass the spin of the contact frame to the law, account the work of the
#: contact forces (its rows carry pair_kernel.N_EXTRA values more: ``pair_style ... energy yes``)
ADVANCE = 1
SAVE = 2
REAPPLY = 4
FRAME_SPIN = 8
ENERGY = 16

#: columns of the per-atom saved forces (the history fix's ``saved``: FixDemContactHistory::SF_...)
SF_F, SF_T, SF_X, SF_V, SF_W, SF_R, SF_M, SF_STEP, SF_ID, N_SAVED = 0, 3, 6, 9, 12, 15, 16, 17, 18, 19

#: the values a step reports (float64[N_REPORT]): the wall's load on this rank (force 3 [N], torque about its
#: centre 3 [N m], power given to the spheres [W]), the number of contacts, of contacts whose force is not
#: finite, the local index + 1 of an atom with more contacts than rows, of an atom whose centre is behind an
#: unbounded wall, the largest normal speed a contact began at above v_max [m/s], the fewest steps per
#: contact time at it and the local index + 1 of its atom
R_LOAD = 0
R_CONTACTS = 7
R_BAD = 8
R_OVERFLOW = 9
R_BEHIND = 10
R_FAST_V = 11
R_FAST_STEPS = 12
R_FAST_ATOM = 13
N_REPORT = 14

#: the box facts a step takes (float64[N_BOX]): the periods (3), whether periodic (3), v_max [m/s]
N_BOX = 7


@njit(inline="always", cache=True)
def _release(keys, i, r):
    """Free slot r of atom i: its key zeroed (taking a slot zeroes its row: an atom from another rank brings only
    its filled rows)."""
    keys[i, r] = 0.0


def _find_row(keys, i, key):
    """The row of atom i keyed ``key``, else -1."""
    for s in range(keys.shape[1]):
        if keys[i, s] == key:
            return s
    return -1


def _unchanged(saved, i, x, v, omega, radius, rmass, step_no, box):
    """Whether atom i's forces saved at step ``step_no`` are those of its state now (positions up to a period
    of the box, which LAMMPS wraps atoms into at a run's set-up)."""
    if saved[i, SF_STEP] != step_no or saved[i, SF_R] != radius[i] or saved[i, SF_M] != rmass[i]:
        return False
    for d in range(3):
        dx = x[i, d] - saved[i, SF_X + d]
        if box[3 + d] != 0.0:
            dx -= box[d] * np.rint(dx / box[d])
        if not (abs(dx) <= 1e-13 * (box[d] + abs(x[i, d])) and saved[i, SF_V + d] == v[i, d]
                and saved[i, SF_W + d] == omega[i, d]):
            return False
    return True


def _wall_step(nlocal, x, v, omega, radius, rmass, typ, mask, groupbit, walls, t, mat, params, wall_row, rowinfo,
               type_size, size_free, keys, H, saved, dissipated, dt, flags, step_no, box, f, torque, report, out,
               out_atoms):
    """One step of the wall ``walls`` (packed rows of one wall, placed here at time t [s]) on the local atoms
    of the group (mask & groupbit): see the module's docstring. keys float64[nlocal, slots] and H
    float64[nlocal * slots, history_size (+ pair_kernel.N_EXTRA where ``ENERGY``)]: the atoms' rows (key 0: free;
    advanced in place where ``ADVANCE``, else the law works on copies with no time passing); saved
    float64[nlocal, N_SAVED]; dissipated float64[nlocal]: the energy of the atoms' ended contacts [J], added to
    as rows are freed (``ENERGY``); f, torque
    float64[nlocal, 3]: LAMMPS's, added to; report float64[N_REPORT]; out float64[cap, pair_kernel.N_OUT] and
    out_atoms int64[cap]: the first cap contacts (cap may be 0), as the pair style's (no torque on body 2: the
    wall), and their atoms. Returns the number of contacts."""
    advance = (flags & ADVANCE) != 0
    save = (flags & SAVE) != 0
    reapply = (flags & REAPPLY) != 0
    frame_spin = (flags & FRAME_SPIN) != 0
    energy = (flags & ENERGY) != 0
    nid = int(params[0, P_NORMAL_LAW]) - 1
    tid = int(params[0, P_TANGENTIAL_LAW]) - 1
    v_max = box[6]
    for q in range(N_REPORT):
        report[q] = 0.0
    report[R_FAST_STEPS] = math.inf
    W.place_walls(walls, t)
    unbounded = not math.isfinite(W.bounds(walls, 0, 0)[0])
    slots = keys.shape[1]
    hits = WS.near_elements(nlocal, x, radius, walls, 0.0)
    n = hits.shape[0]
    body = np.empty(n, dtype=np.int64)
    hrow = np.empty(n, dtype=np.int64)
    prow = np.empty(n, dtype=np.int64)
    normals = np.empty((n, 3))
    velocities = np.empty((n, 3))
    spins = np.empty((n, 3))
    overlaps = np.empty(n)
    wn = np.empty(n)
    w_cols = PK.work_columns(nid, params) if energy else np.empty(0, dtype=np.int64)
    forces = np.empty((n, 3))
    tforces = np.empty((n, 3))
    torques = np.zeros((n, 3))
    pc = np.empty((params.shape[0] + n, N_PARAMS))
    pc[:params.shape[0]] = params
    used = np.zeros((nlocal, slots), dtype=np.bool_)
    Hl = H if advance else np.zeros((n, H.shape[1]))
    m = 0
    for c in range(n):
        i = hits[c, 0]
        e = hits[c, 2]
        if (mask[i] & groupbit) == 0:
            continue
        gap, nx, ny, nz = W.contact_of(walls, 0, e, x[i, 0], x[i, 1], x[i, 2], radius[i])
        delta = radius[i] - gap
        if not delta > 0.0:
            continue
        if unbounded and gap < 0.0:
            report[R_BEHIND] = i + 1
            continue
        key = W.key_of(walls, 0, e, x[i, 0], x[i, 1], x[i, 2])
        s = _find_row(keys, i, key)
        fresh = s < 0
        if advance:
            if fresh:
                s = _find_row(keys, i, 0.0)
                if s < 0:
                    report[R_OVERFLOW] = i + 1
                    continue
                keys[i, s] = key
                for q in range(H.shape[1]):
                    H[i * slots + s, q] = 0.0
            used[i, s] = True
            hrow[m] = i * slots + s
        else:
            if not fresh:
                for q in range(H.shape[1]):
                    Hl[m, q] = H[i * slots + s, q]
            hrow[m] = m
        vx, vy, vz, wn[m] = T.wall_slip(x, v, omega, radius, walls, i, 0, gap, nx, ny, nz, frame_spin)
        row = wall_row[typ[i] - 1, mat]
        prow[m] = row
        if size_free and T.resized(radius, rmass, typ, type_size, i):
            rs, ms = T.effective(radius, rmass, i, -1, rowinfo, row)
            prow[m] = params.shape[0] + m
            T.contact_row(params, row, pc, prow[m], rowinfo, rs, ms)
        if advance and fresh:
            vn = vx * nx + vy * ny + vz * nz
            if vn > v_max:
                rs, ms = T.effective(radius, rmass, i, -1, rowinfo, row)
                tc = rowinfo[row, T.RI_TC] * T.size_factor(rowinfo, row, rs, ms) * vn ** -rowinfo[row, T.RI_ALPHA]
                if vn > report[R_FAST_V]:
                    report[R_FAST_V] = vn
                    report[R_FAST_ATOM] = i + 1
                report[R_FAST_STEPS] = min(report[R_FAST_STEPS], tc / dt)
        body[m] = i
        T.put_contact(normals, overlaps, velocities, m, nx, ny, nz, delta, vx, vy, vz)
        for d in range(3):
            spins[m, d] = omega[i, d] - (walls[0, W.OMEGA + d] if frame_spin else 0.0)
        m += 1
    if advance:
        # the rows of the group's atoms that no contact used at this step: freed
        for i in range(nlocal):
            if (mask[i] & groupbit) != 0:
                for s in range(slots):
                    if keys[i, s] != 0.0 and not used[i, s]:
                        if energy:
                            # (the overlap now, a gap, where the wall is one element: a plane, a cylinder)
                            delta_end = 0.0
                            if unbounded:
                                gap = W.contact_of(walls, 0, 0, x[i, 0], x[i, 1], x[i, 2], radius[i])[0]
                                delta_end = min(radius[i] - gap, 0.0)
                            dissipated[i] += PK.ended_work(H, i * slots + s, delta_end)
                        _release(keys, i, s)
    if uses_rate(nid):
        # dashpots see the normal velocity predicted at the end of the step (as the impact integrator)
        for k in range(m):
            kick = 0.5 * dt * Hl[hrow[k], V_N] / rmass[body[k]]
            for d in range(3):
                velocities[k, d] -= kick * normals[k, d]
    loop(nid, tid, pc, prow[:m], Hl, hrow[:m], normals[:m], overlaps[:m], velocities[:m], spins[:m],  # noqa: F821
         wn[:m], dt, forces[:m], tforces[:m], torques[:m])

    acc = np.zeros((nlocal, 6))
    load = report[R_LOAD:R_LOAD + 7]
    for k in range(m):
        i = body[k]
        if energy:
            PK.account_work(Hl, hrow[k], w_cols[wall_row[typ[i] - 1, mat]], overlaps[k], velocities[k, 0],
                            velocities[k, 1], velocities[k, 2], normals[k, 0], normals[k, 1], normals[k, 2], dt)
        cx, cy, cz = T.normal_cross(normals, tforces, k)
        # torque on the sphere: R n x Ft (the arm against a wall: the full radius) and the twist and rolling torques
        r = radius[i]
        tx = r * cx + torques[k, 0]
        ty = r * cy + torques[k, 1]
        tz = r * cz + torques[k, 2]
        acc[i, 0] += forces[k, 0]
        acc[i, 1] += forces[k, 1]
        acc[i, 2] += forces[k, 2]
        acc[i, 3] += tx
        acc[i, 4] += ty
        acc[i, 5] += tz
        T.add_wall_load(x, radius, walls, 0, i, overlaps[k], normals, forces, torques, k, load)
        if k < out.shape[0]:
            out_atoms[k] = i
            out[k, PK.OUT_TA] = tx
            out[k, PK.OUT_TA + 1] = ty
            out[k, PK.OUT_TA + 2] = tz
            for d in range(3):
                out[k, PK.OUT_F + d] = forces[k, d]
                out[k, PK.OUT_TB + d] = 0.0
                out[k, PK.OUT_FT + d] = tforces[k, d]
                out[k, PK.OUT_N + d] = normals[k, d]
                out[k, PK.OUT_Q + d] = torques[k, d]
            out[k, PK.OUT_DELTA] = overlaps[k]
            out[k, PK.OUT_MU] = pc[prow[k], P_MU]
            if energy:
                x0 = Hl.shape[1] - PK.N_EXTRA
                out[k, PK.OUT_WORK_N] = Hl[hrow[k], x0 + PK.X_WORK_N]
                out[k, PK.OUT_WORK_T] = Hl[hrow[k], x0 + PK.X_WORK] - Hl[hrow[k], x0 + PK.X_WORK_N]
    report[R_CONTACTS] = m
    for i in range(nlocal):
        if (mask[i] & groupbit) == 0:
            continue
        if reapply and _unchanged(saved, i, x, v, omega, radius, rmass, step_no, box):
            for d in range(6):
                acc[i, d] = saved[i, d]
        finite = True
        for d in range(6):
            finite = finite and math.isfinite(acc[i, d])
        if not finite:
            report[R_BAD] += 1.0
            continue
        for d in range(3):
            f[i, d] += acc[i, d]
            torque[i, d] += acc[i, 3 + d]
        if save:
            for d in range(6):
                saved[i, d] = acc[i, d]
            for d in range(3):
                saved[i, SF_X + d] = x[i, d]
                saved[i, SF_V + d] = v[i, d]
                saved[i, SF_W + d] = omega[i, d]
            saved[i, SF_R] = radius[i]
            saved[i, SF_M] = rmass[i]
            saved[i, SF_STEP] = step_no
    return m


def _entry(nlocal, x, v, omega, radius, rmass, typ, mask, groupbit, walls, wall_rows, t, mat, params, n_rows,
           wall_row, n_types, n_mats, rowinfo, type_size, size_free, keys, H, slots, hs, saved, dissipated, dt, flags,
           step_no, box, f, torque, report, out, out_atoms, out_cap):
    """The C entry of ``_wall_step``: raw pointers of the fix's buffers and LAMMPS's per-atom arrays."""
    return step(nlocal, carray(x, (nlocal, 3)), carray(v, (nlocal, 3)), carray(omega, (nlocal, 3)),  # noqa: F821
                carray(radius, (nlocal,)), carray(rmass, (nlocal,)), carray(typ, (nlocal,)), carray(mask, (nlocal,)),
                groupbit, carray(walls, (wall_rows, W.ROW_SIZE)), t, mat, carray(params, (n_rows, N_PARAMS)),
                carray(wall_row, (n_types, n_mats)), carray(rowinfo, (n_rows, T.N_ROWINFO)),
                carray(type_size, (n_types, 2)), size_free != 0, carray(keys, (nlocal, slots)),
                carray(H, (nlocal * slots, hs)), carray(saved, (nlocal, N_SAVED)), carray(dissipated, (nlocal,)), dt,
                flags, step_no,
                carray(box, (N_BOX,)), carray(f, (nlocal, 3)), carray(torque, (nlocal, 3)), carray(report, (N_REPORT,)),
                carray(out, (out_cap, PK.N_OUT)), carray(out_atoms, (out_cap,)))


_I64P = types.CPointer(types.int64)
_F64P = types.CPointer(types.float64)
_I32P = types.CPointer(types.int32)
_I64 = types.int64
#: the C signature of the step (``fix_dem_contact_wall.cpp``, ``WallStepFn``)
SIGNATURE = types.int64(_I64, _F64P, _F64P, _F64P, _F64P, _F64P, _I32P, _I32P, _I64, _F64P, _I64, types.float64, _I64,
                        _F64P, _I64, _I64P, _I64, _I64, _F64P, _F64P, _I64, _F64P, _F64P, _I64, _I64, _F64P, _F64P,
                        types.float64, _I64, types.float64, _F64P, _F64P, _F64P, _F64P, _F64P, _I64P, _I64)

_CFUNCS = {}


def step_function(tid: int):
    """The compiled C entry of the wall step for tangential family ``tid`` (a numba cfunc; compiled once per
    process, cached on disk as the package's kernels)."""
    if tid not in _CFUNCS:
        name = f"lammps_wall_step_{tid}"
        step = njit(cache=True)(renamed(_wall_step, name, loop=_LOOPS[tid][0]))
        _CFUNCS[tid] = cfunc(SIGNATURE, cache=True)(renamed(_entry, f"{name}_entry", step=step))
    return _CFUNCS[tid]


_find_row = njit(inline="always", cache=True)(_find_row)
_unchanged = njit(inline="always", cache=True)(_unchanged)


class WallAttach(ctypes.Structure):
    """What the fix reads after ``attach`` (the C struct ``DemContactWallAttach`` of ``fix_dem_contact_wall.h``,
    field for field)."""

    _fields_ = [
        ("abi", ctypes.c_int64),
        ("error", ctypes.c_char * 2048),
        ("step", ctypes.c_void_p),
        ("walls", ctypes.c_void_p),
        ("wall_rows", ctypes.c_int64),
        ("mat", ctypes.c_int64),
        ("params", ctypes.c_void_p),
        ("n_rows", ctypes.c_int64),
        ("wall_row", ctypes.c_void_p),
        ("n_types", ctypes.c_int64),
        ("n_mats", ctypes.c_int64),
        ("rowinfo", ctypes.c_void_p),
        ("type_size", ctypes.c_void_p),
        ("size_free", ctypes.c_int64),
        ("history_size", ctypes.c_int64),
        ("slots", ctypes.c_int64),
        ("unbounded", ctypes.c_int64),
        ("describe", ctypes.c_char * 512),
    ]


#: the arrays the fixes of this process read, by the address of their WallAttach (kept alive here)
_KEPT = {}

#: the words of each kind, after its name
_KIND_WORDS = {"plane": "PX PY PZ NX NY NZ", "cylinder": "PX PY PZ AX AY AZ RC in|out [flat]",
               "mesh": "FILE [scale S]"}
_SYNTAX = ("fix ID GROUP dem/contact/wall KIND ARGS [wall W] [velocity VX VY VZ] [angular_velocity WX WY WZ] "
           "[centre CX CY CZ] [slots N], KIND one of: " + "; ".join(f"{k} {w}" for k, w in _KIND_WORDS.items()))


def parse(words: list):
    """(the wall, slots or None) of the words of ``fix ... dem/contact/wall`` after the style
    (InputError naming the word and the syntax)."""
    from ..errors import InputError
    from ..walls import CylinderWall, MeshWall, PlaneWall
    from . import mesh_file

    def numbers(at, count, what):
        got = words[at:at + count]
        try:
            if len(got) < count:
                raise ValueError
            return tuple(float(w) for w in got)
        except ValueError:
            raise InputError(f"{what} needs {count} numbers, got {' '.join(got) or 'none'} "
                             f"(syntax: {_SYNTAX})") from None

    if not words or words[0] not in _KIND_WORDS:
        raise InputError(f"unknown wall kind {words[0] if words else '(none)'!r} "
                         f"(syntax: {_SYNTAX})")
    kind = words[0]
    k = 1
    if kind == "plane":
        a = numbers(k, 6, "plane")
        shape = dict(point=a[:3], normal=a[3:])
        k += 6
    elif kind == "cylinder":
        a = numbers(k, 7, "cylinder")
        k += 7
        side = words[k] if k < len(words) else None
        if side not in ("in", "out"):
            raise InputError(f"cylinder needs its side after the radius, in or out, got "
                             f"{side!r} (syntax: {_SYNTAX})")
        k += 1
        curved = True
        if k < len(words) and words[k] == "flat":
            curved = False
            k += 1
        shape = dict(point=a[:3], axis=a[3:6], radius=a[6], inside=side == "in", curved=curved)
    else:
        if k >= len(words):
            raise InputError(f"mesh needs an STL file (syntax: {_SYNTAX})")
        shape = dict(path=words[k])
        k += 1
        if k < len(words) and words[k] == "scale":
            shape["scale"] = numbers(k + 1, 1, "scale")[0]
            k += 2
    motion = {}
    slots = None
    mat = 0
    while k < len(words):
        key = words[k]
        if key in ("velocity", "angular_velocity", "centre"):
            motion[key] = numbers(k + 1, 3, key)
            k += 4
        elif key in ("wall", "slots"):
            got = words[k + 1] if k + 1 < len(words) else ""
            try:
                value = int(got)
            except ValueError:
                raise InputError(f"{key} needs a whole number, got {got or 'none'!r}") from None
            if key == "wall":
                mat = value
            else:
                if not 1 <= value <= 1000:
                    raise InputError(f"slots (history rows per atom) must be in [1, 1000], "
                                     f"got {value}")
                slots = value
            k += 2
        else:
            raise InputError(f"unknown keyword {key!r} (syntax: {_SYNTAX})")
    if kind == "plane":
        wall = PlaneWall(wall=mat, **shape, **motion)
    elif kind == "cylinder":
        wall = CylinderWall(wall=mat, **shape, **motion)
    elif mesh_file.is_packed(shape["path"]):
        if "scale" in shape:
            raise InputError(f"scale applies to an STL file: {shape['path']} is a packed mesh, whose coordinates "
                             f"were scaled when it was written (dem-contact lammps-mesh --scale)")
        wall = mesh_file.read(shape["path"], wall=mat, **motion)
    else:
        try:
            wall = MeshWall.from_stl(shape["path"], scale=shape.get("scale", 1.0), wall=mat, **motion)
        except OSError as e:
            raise InputError(f"the STL file {shape['path']} cannot be read ({e})") from None
    return wall, slots


def fix_words(wall, mesh=None, slots=None) -> str:
    """The words of ``fix ... dem/contact/wall`` after the style for a PlaneWall, a CylinderWall or a MeshWall
    (``mesh``: the path of its packed mesh file, ``mesh_file.write``; ``slots``: history rows per atom, None for
    the fix's default), which ``parse`` reads back as the wall and the slots."""
    from ..errors import InputError
    from ..walls import CylinderWall, MeshWall, PlaneWall

    def num(v):
        return " ".join(repr(float(c)) for c in v)

    if isinstance(wall, MeshWall):
        if mesh is None:
            raise InputError("a MeshWall's fix names its packed mesh file (mesh_file.write): give its path")
        words = f'mesh "{mesh}"'
    elif isinstance(wall, PlaneWall):
        words = f"plane {num(wall.point)} {num(wall.normal)}"
    elif isinstance(wall, CylinderWall):
        words = (f"cylinder {num(wall.point)} {num(wall.axis)} {float(wall.radius)!r} "
                 f"{'in' if wall.inside else 'out'}{'' if wall.curved else ' flat'}")
    else:
        raise InputError(f"a wall of fix dem/contact/wall is a PlaneWall, a CylinderWall or a MeshWall, got "
                         f"{type(wall).__name__}")
    words += f" wall {int(wall.wall)} velocity {num(wall.velocity)} angular_velocity {num(wall.angular_velocity)}"
    return (words + (f" centre {num(wall.centre)}" if wall.centre is not None else "")
            + (f" slots {int(slots)}" if slots is not None else ""))


def attach(words: str, path: str, n_types: int, address: int) -> None:
    """Read the wall of a fix (``words``: its words after the style, separated by newlines) and the table file
    ``path`` of the pair style for a run with ``n_types`` atom types, and fill the WallAttach at ``address``;
    any failure is written to its ``error`` field (the fix stops with it)."""
    out = WallAttach.from_address(address)
    try:
        _attach(words.split("\n") if words else [], path, n_types, out, address)
    except Exception as e:      # (every failure reaches LAMMPS as its error message)
        from ..errors import InputError
        text = str(e) if isinstance(e, InputError) else f"{type(e).__name__}: {e}\n{traceback.format_exc()}"
        out.error = text.encode()[:2047]


def _attach(words, path, n_types, out, address):
    from ..errors import InputError
    from ..walls import pack
    from . import table_file

    if out.abi != ABI:
        raise InputError(f"the plugin was built for another version of dem_contact (wall interface {out.abi}, "
                         f"this package's is {ABI}): build it again with `dem-contact lammps-plugin --rebuild`")
    wall, slots = parse(words)
    saved = table_file.load(path)
    table = saved.table
    if table.wall_row.shape[0] != n_types:
        raise InputError(f"the table file {path} is for {table.wall_row.shape[0]} atom types, the LAMMPS box has "
                         f"{n_types}")
    n_mats = table.wall_row.shape[1]
    if n_mats == 0:
        raise InputError(f"the table file {path} has no walls: write it with the walls' materials "
                         f"(`dem-contact lammps-table ... --wall E NU`, or pair_table(spheres, walls))")
    if not 0 <= wall.wall < n_mats:
        raise InputError(f"wall {wall.wall} is not a wall of the table file {path} (it has "
                         f"walls 0 ... {n_mats - 1})")
    try:
        rows, mats = pack([wall], n_mats)
    except InputError as e:
        # (the walls room names the wall walls[0]: here it is the fix's)
        raise InputError(str(e).replace("walls[0].", "the wall's ")) from None
    want = float(getattr(wall, "curvature_for_rstar", 0.0))
    have = float(saved.rowinfo[table.wall_row[0, wall.wall], T.RI_CURV])
    if have != want:
        raise InputError(f"the wall has curvature {want!r} 1/m at its contacts, but its "
                         f"material (wall {wall.wall} of {path}) has curvature {have!r}: write the table with that "
                         f"curvature for it (--wall E NU {want!r}), or give the cylinder the word flat (R* = R1)")
    unbounded = not math.isfinite(W.bounds(rows, 0, 0)[0])
    if slots is None:
        # (a plane or a cylinder: one contact per atom; a mesh: one per patch it touches)
        slots = 1 if unbounded else 6
    fn = step_function(table.tangential_id)
    arrays = dict(walls=rows, params=table.params, wall_row=np.ascontiguousarray(table.wall_row),
                  rowinfo=np.ascontiguousarray(saved.rowinfo), type_size=np.ascontiguousarray(saved.type_size))
    _KEPT[address] = (arrays, fn)
    out.step = fn.address
    for name, a in arrays.items():
        setattr(out, name, a.ctypes.data)
    out.wall_rows = rows.shape[0]
    out.mat = wall.wall
    out.n_rows = table.params.shape[0]
    out.n_types = table.wall_row.shape[0]
    out.n_mats = n_mats
    out.size_free = int(saved.size_free)
    out.history_size = table.history_size
    out.slots = slots
    out.unbounded = int(unbounded)
    out.describe = f"{type(wall).__name__} (table wall {wall.wall}), {saved.laws}".encode()[:511]
    out.error = b""
