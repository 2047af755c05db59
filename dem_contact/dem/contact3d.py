"""Drop-in 3D contact force for DEM codes: any normal x tangential law of ``laws.contact``, in 3D.

    contact_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
        -> (Fx, Fy, Fz, Ftx, Fty, Ftz)

Conventions (SI units):

- ``params``: float64[n_rows, N_PARAMS] parameter table (``pairs.PairTable.params``), ``row`` the pair's row;
- ``H``: float64[n_contacts, history_size] the whole state of every contact, row ``c`` for this one
  (``pairs.PairTable.history_size``; layout in ``laws.vector``);
- ``n``: unit normal from body 1 to body 2; ``delta`` > 0: overlap [m];
- ``v``: relative velocity of body 1 with respect to body 2 at the contact point [m/s],
  v = (V1 + w1 x r1) - (V2 + w2 x r2) with r_i the vector from the centre of body i to the contact point;
  the overlap rate is d(delta)/dt = v . n (seen by dashpots) and the slip increment is
  dd = (v - (v . n) n) dt. In a velocity-Verlet loop pass the half-step velocities;
- ``wn``: rotation rate of the contact frame about the normal [rad/s], wn = 0.5 (w1 + w2) . n, the mean
  spin of the two bodies about the normal: the tangential history turns with it, so a pair turned
  rigidly sees its force turn with it (objectivity). 0.0 keeps the history fixed in space apart from the
  carry into the tangent plane (as LAMMPS's granular models do). Relative spin about the normal (torsion)
  is not a tangential load and does not act on the force;
- ``dt`` > 0 [s];
- returned: the force on body 1 (normal + tangential) and its tangential part (for the torques
  r1 x F_t on body 1 and -r2 x F_t on body 2). The force on body 2 is the opposite.

Each step the stored tangential history (a vector, an axis or a frame, see ``laws.vector``) is carried
into the current tangent plane keeping its magnitude and turned about the normal by the angle
2 atan(wn dt / 2) (the Cayley form of the rotation by wn dt: exactly orthogonal, wn dt (1 - (wn dt)^2 / 12)),
then the law acts on the slip increment (the 3D form of each law is in its file, ``laws.tangential``):
vector springs (the LAMMPS granular ``mindlin``, ``mindlin/force``, ``mindlin_rescale/force`` arithmetic),
Coulomb by scaling the force back to mu N; Thornton & Yin's law along the force axis, slip across the axis
turning the force; vector MDR, each cell a displacement in the tangent plane with its own Coulomb circle
(radial return).

Motion in one plane repeats the planar laws (``laws.contact``) to rounding error.

Checks: ``contact_force`` (and the helpers called from jitted code) check nothing and raise nothing, so a
user's ``prange`` loop around them runs in parallel (unknown law ids give NaN forces). Called from Python,
the helpers (``peek_force``, ``reset_contact``, ``swap_bodies``, ``rotate_history``, ``tangential_work``)
check their arguments; ``contact_forces_batch`` / ``contact_forces_serial`` check what could make the loop
write outside its arrays, race or compute in float32; ``check_contacts`` and ``contact_forces`` check
the values too (``debug=True``: a bounds-checked loop). Every parameter row records the laws it was built
for, and all of these refuse a table used with other law ids. Law ids always come first, (nid, tid).
"""
import math
import os
import threading

import numpy as np
from llvmlite import ir
from numba import njit, prange, types
from numba.core import cgutils
from numba.extending import intrinsic, overload

from ..errors import InputError, NumericalError
from ..laws import table
from ..laws.compose import kinematics, torque_laws
from ..laws.dispatch import (NORMAL_IDS, NORMAL_NAMES, ROLLING_IDS, TANGENTIAL_IDS, TANGENTIAL_NAMES, TWIST_IDS,
                             normal_vector, rolling_base, store_normal, tangential_base, twist_base)
from ..laws.dispatch3d import contact_leaf
from ..laws.slots import N_PARAMS, P_NORMAL_LAW, P_NSPRING, P_ROLLING_LAW, P_RSTAR, P_TANGENTIAL_LAW, P_TWIST_LAW
from ..laws.vector import JIT, V_A, V_N, W_WORK, W_X, renamed

__all__ = ["contact_force", "contact_force_torque", "peek_force", "reset_contact", "swap_bodies", "rotate_history", "tangential_work",
           "contact_forces_batch", "contact_forces_serial", "batch_loop", "contact_forces", "check_contacts",
           "new_histories", "history_size"]


# The kernels are flattened for speed: the step of each tangential law (``laws.compose``) alone reads and
# writes the arrays (H[c, j], params[row, j]) and calls only inlined functions of scalars. The batch loops
# are compiled per tangential law with its step inlined (numba then keeps the reference counting of the
# arrays out of the loop), and only the law that is used is compiled. ``contact_force`` calls one
# non-inlined leaf per law (``laws.dispatch3d``), to keep the cold compile of a user's loop short.

def history_size(nid: int, tid: int, n_cells: int = 0, qid: int = 0, rid: int = 0) -> int:
    """Length of a 3D history row for the normal law ``nid`` and the tangential law ``tid``; ``n_cells``:
    the MDR cell count (the largest params[:, P_NSPRING] of the table, >= 2) for the laws with cells,
    which have no default (``PairTable.history_size`` has it all); ``qid``, ``rid``: the twist and rolling
    laws (default 0, none), whose states come before the tangential one (layout: ``laws.table``)."""
    nid, tid = _valid_ids(nid, tid)
    qid, rid = _torque_ids(qid, rid)
    if table.FAMILIES["tangential"][tid].CELLS and not (isinstance(n_cells, (int, np.integer)) and n_cells >= 2):
        raise InputError(f"n_cells = {n_cells!r}: the {TANGENTIAL_NAMES[tid]} law needs its cell count (an integer "
                         f">= 2, the largest params[:, P_NSPRING] of the table; PairTable.history_size has it)")
    return table.vector_history_size(nid, tid, n_cells, qid, rid)


@njit(inline="always", **JIT)
def contact_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    """One contact step in 3D (see the module docstring). Updates H[c, :] in place.
    Returns (Fx, Fy, Fz, Ftx, Fty, Ftz): the total force on body 1 and its tangential part [N].
    Nothing is checked (``check_contacts``) and nothing raises, so that a user's ``prange`` loop around it
    runs in parallel: unknown law ids give NaN forces and leave H unchanged."""
    fx, fy, fz, tx, ty, tz, _, _, _ = contact_force_torque(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy,
                                                           vz, 0.0, 0.0, 0.0, wn, dt)
    return fx, fy, fz, tx, ty, tz


@njit(inline="always", **JIT)
def contact_force_torque(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt):
    """``contact_force`` with the relative spin of the bodies, w = w1 - w2 = (wx, wy, wz) [rad/s], for the
    twist and rolling laws of the table (``Scene(twist=..., rolling=...)``, recorded in its rows). Returns
    (Fx, Fy, Fz, Ftx, Fty, Ftz, Mx, My, Mz): the force on body 1, its tangential part [N] and the torque on
    body 1 of the twist and rolling laws [N m] (body 2 takes -M; the moment of the tangential force,
    r1 x Ft, is the caller's). Unknown law ids give NaN and leave H unchanged."""
    if nid < 0 or nid >= len(NORMAL_IDS) or tid < 0 or tid >= len(TANGENTIAL_IDS):
        return math.nan, math.nan, math.nan, math.nan, math.nan, math.nan, math.nan, math.nan, math.nan
    # int64 indices whatever the caller's (a prange index is uint64): the leaves compiled for serial loops
    # serve parallel ones too
    return contact_leaf(nid, tid, params, np.int64(row), H, np.int64(c), nx, ny, nz, delta, vx, vy, vz, wx, wy, wz,
                        wn, dt)


# The contact helpers: a jitted kernel each (``_peek_force`` ...), called unchecked from jitted code (the
# ``overload`` of the public name, indices as int64 so that serial and prange loops share one compilation),
# and a Python function of that name that checks its arguments first, so that a call from Python cannot
# write outside H.

@njit(**JIT)
def _peek_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    tmp = H[c:c + 1].copy()
    return contact_force(nid, tid, params, row, tmp, 0, nx, ny, nz, delta, vx, vy, vz, wn, dt)


@njit(**JIT)
def _reset_contact(H, c):
    for j in range(H.shape[1]):
        H[c, j] = 0.0


def _swap_rules():
    """The sign rules of the tangential laws for swapping the bodies (``SWAP_NEGATE``, ``SWAP_NEGATE_CELL``):
    the slots relative to the tangential base that change sign (-1 pads), and the first slot of the cell
    components that change sign (every second slot from there; -1: no cells)."""
    laws = table.FAMILIES["tangential"]
    negate = np.full((len(laws), max(len(m.SWAP_NEGATE) for m in laws)), -1, dtype=np.int64)
    cells = np.full(len(laws), -1, dtype=np.int64)
    for t, m in enumerate(laws):
        negate[t, :len(m.SWAP_NEGATE)] = m.SWAP_NEGATE
        if m.CELLS:
            cells[t] = m.VECTOR_SLOTS + m.SWAP_NEGATE_CELL
    return negate, cells


def _slot_rule(family, attr):
    """int64[laws, k]: the slots ``attr`` (``SWAP_NEGATE`` or ``VECTORS``, relative to the law's base) of each
    law of the twist or rolling family, -1 pads."""
    laws = table.FAMILIES[family]
    out = np.full((len(laws), max(1, max(len(getattr(m, attr)) for m in laws))), -1, dtype=np.int64)
    for i, m in enumerate(laws):
        out[i, :len(getattr(m, attr))] = getattr(m, attr)
    return out


_NEGATE, _CELL_NEGATE = _swap_rules()
_Q_NEGATE, _R_NEGATE = _slot_rule("twist", "SWAP_NEGATE"), _slot_rule("rolling", "SWAP_NEGATE")
_Q_VECTORS, _R_VECTORS = _slot_rule("twist", "VECTORS"), _slot_rule("rolling", "VECTORS")


@njit(inline="always", **JIT)
def _negate_slots(H, c, base, rule):
    for k in rule:
        if k >= 0:
            H[c, base + k] = -H[c, base + k]


@njit(inline="always", **JIT)
def _turn_vector(H, c, j, Q):
    x = H[c, j]
    y = H[c, j + 1]
    z = H[c, j + 2]
    for i in range(3):
        H[c, j + i] = Q[i, 0] * x + Q[i, 1] * y + Q[i, 2] * z


@njit(inline="always", **JIT)
def _torque_laws_of(params, row):
    """The twist and rolling law ids the parameter row records (0, none, where it records none)."""
    return max(int(params[row, P_TWIST_LAW]) - 1, 0), max(int(params[row, P_ROLLING_LAW]) - 1, 0)


@njit(**JIT)
def _swap_bodies(nid, tid, params, row, H, c):
    qid, rid = _torque_laws_of(params, row)
    b = tangential_base(nid, qid, rid)
    _negate_slots(H, c, b, _NEGATE[tid])
    if _CELL_NEGATE[tid] >= 0:
        for k in range(b + _CELL_NEGATE[tid], H.shape[1], 2):
            H[c, k] = -H[c, k]
    _negate_slots(H, c, twist_base(nid), _Q_NEGATE[qid])
    _negate_slots(H, c, rolling_base(nid, qid), _R_NEGATE[rid])


@njit(**JIT)
def _rotate_history(nid, tid, params, row, H, c, Q):
    qid, rid = _torque_laws_of(params, row)
    _turn_vector(H, c, tangential_base(nid, qid, rid) + W_X, Q)
    for k in _Q_VECTORS[qid]:
        if k >= 0:
            _turn_vector(H, c, twist_base(nid) + k, Q)
    for k in _R_VECTORS[rid]:
        if k >= 0:
            _turn_vector(H, c, rolling_base(nid, qid) + k, Q)


@njit(**JIT)
def _tangential_work(nid, tid, params, row, H, c):
    qid, rid = _torque_laws_of(params, row)
    return H[c, tangential_base(nid, qid, rid) + W_WORK]


def _check_row(H, c, writes, need=0):
    """H a float64 2D C array (writeable if the helper ``writes``) with rows of length >= ``need``, c one
    of its rows."""
    _array("H", H, 2, np.float64, writeable=writes)
    if isinstance(c, (bool, np.bool_)) or not isinstance(c, (int, np.integer)) or not 0 <= c < H.shape[0]:
        shown = repr(c) if isinstance(c, (int, float, np.number)) else f"a {type(c).__name__}"
        raise InputError(f"c = {shown} is not a row of H (valid: integers 0 to {H.shape[0] - 1})")
    if H.shape[1] < need:
        raise InputError(f"H has rows of length {H.shape[1]}; these laws need at least {need} "
                         f"(PairTable.history_size, contact3d.history_size)")


def _check_helper(nid, tid, params, row, H, c, writes):
    """The law ids, the table (built for them), ``row`` one of its rows, H and ``c`` (``InputError``)."""
    nid, tid = _valid_ids(nid, tid)
    need = _check_table(nid, tid, params)
    if isinstance(row, (bool, np.bool_)) or not isinstance(row, (int, np.integer)) or not 0 <= row < len(params):
        raise InputError(f"row = {row!r} is not a row of params (valid: 0 to {len(params) - 1})")
    _check_row(H, c, writes, need)
    return nid, tid


def peek_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    """``contact_force`` on a copy of the contact's history: H is left unchanged. Called from Python, the
    law ids, the table (built for them), ``row``, H and ``c`` are checked first (``InputError``)."""
    nid, tid = _check_helper(nid, tid, params, row, H, c, False)
    return _peek_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)


def reset_contact(H, c):
    """Zero the history of contact c (call on separation, before the row is reused)."""
    _check_row(H, c, True)
    _reset_contact(H, c)


def swap_bodies(nid, tid, params, row, H, c):
    """Exchange bodies 1 and 2 of contact c, whose parameter row is params[row]: the normal, the relative
    velocity, the displacement and the tangential force change sign. Swapping twice is the identity. The
    arguments are those of ``contact_force``: where the tangential slots start depends on the normal law
    (``thornton`` has a longer normal state) and on the twist and rolling laws that params[row] records
    (their states come before the tangential one, and change sign only where the law says so,
    ``SWAP_NEGATE``: a twist angle and a rolling displacement look the same from either body); the MDR laws
    hold a frame and cells."""
    nid, tid = _check_helper(nid, tid, params, row, H, c, True)
    _swap_bodies(nid, tid, params, row, H, c)


def rotate_history(nid, tid, params, row, H, c, Q):
    """Turn the history vectors of contact c (the tangential law's, and those of the twist and rolling laws
    that params[row] records) rigidly by the rotation matrix Q (float64[3, 3], proper orthogonal), e.g.
    for a pair whose frame is rotated by the caller. Its next step must get Q n. The arguments are those of
    ``contact_force`` (the turned slots do not depend on tid)."""
    nid, tid = _check_helper(nid, tid, params, row, H, c, True)
    _array("Q", Q, 2, np.float64, (3, 3))
    if not (np.allclose(Q @ Q.T, np.eye(3), rtol=0.0, atol=1e-9) and np.linalg.det(Q) > 0.0):
        raise InputError("Q must be a rotation matrix (Q Q^T = I within 1e-9, det Q = +1)")
    _rotate_history(nid, tid, params, row, H, c, Q)


def tangential_work(nid, tid, params, row, H, c):
    """Work absorbed by the tangential force of contact c since its history was zeroed [J]: the sum over
    steps of 0.5 (T_old + T) . dd. A passive contact keeps it >= 0; a negative value is energy created.
    The arguments are those of ``contact_force``: the slot depends on the normal law and on the twist and
    rolling laws that params[row] records, whose states come first."""
    nid, tid = _check_helper(nid, tid, params, row, H, c, False)
    return _tangential_work(nid, tid, params, row, H, c)


@overload(peek_force)
def _peek_force_jit(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    return lambda nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt: _peek_force(
        nid, tid, params, np.int64(row), H, np.int64(c), nx, ny, nz, delta, vx, vy, vz, wn, dt)


@overload(reset_contact)
def _reset_contact_jit(H, c):
    return lambda H, c: _reset_contact(H, np.int64(c))


@overload(swap_bodies)
def _swap_bodies_jit(nid, tid, params, row, H, c):
    return lambda nid, tid, params, row, H, c: _swap_bodies(nid, tid, params, np.int64(row), H, np.int64(c))


@overload(rotate_history)
def _rotate_history_jit(nid, tid, params, row, H, c, Q):
    return lambda nid, tid, params, row, H, c, Q: _rotate_history(nid, tid, params, np.int64(row), H, np.int64(c), Q)


@overload(tangential_work)
def _tangential_work_jit(nid, tid, params, row, H, c):
    return lambda nid, tid, params, row, H, c: _tangential_work(nid, tid, params, np.int64(row), H, np.int64(c))


@intrinsic
def _prefetch(typingctx, arr, row, col):
    """Ask the CPU to bring the cache line of arr[row, col] (a 2D C array) into its caches, for writing
    (``llvm.prefetch``); a hint only, it never faults."""
    if not (isinstance(arr, types.Array) and arr.ndim == 2 and isinstance(row, types.Integer)
            and isinstance(col, types.Integer)):
        return None

    def codegen(context, builder, signature, args):
        aryty = signature.args[0]
        ary = context.make_array(aryty)(context, builder, args[0])
        idx = [context.cast(builder, v, t, types.intp) for v, t in zip(args[1:], signature.args[1:])]
        ptr = cgutils.get_item_pointer(context, builder, aryty, ary, idx, wraparound=False)
        i8p = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        fnty = ir.FunctionType(ir.VoidType(), [i8p, i32, i32, i32])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.prefetch.p0")
        builder.call(fn, [builder.bitcast(ptr, i8p), i32(1), i32(3), i32(1)])   # write, keep, data
        return context.get_dummy_value()

    return types.void(arr, row, col), codegen


#: contacts ahead whose history rows the batch loops prefetch
AHEAD = 4


@njit(inline="always", **JIT)
def _prefetch_row(H, r):
    """Prefetch every cache line of row r of H."""
    for k in range(0, H.shape[1], 8):
        _prefetch(H, r, k)
    _prefetch(H, r, H.shape[1] - 1)


@njit(inline="always", **JIT)
def _prefetch_head(H, r):
    """Prefetch the first 16 values of row r of H (the normal law's state and, in a row of the default law
    without twist or rolling laws, the tangential law's header; an MDR row's cells follow, of which a step on a
    lasting contact reads the few at its edge)."""
    _prefetch(H, r, 0)
    _prefetch(H, r, min(8, H.shape[1] - 1))


# The batch loops of each tangential law, the law's step inlined: contact c has history row rows[c] of H,
# prefetched AHEAD contacts before it is used (scattered rows would otherwise stall the law on every
# contact); a row that follows the one before it in memory (rows in order, as a pool filled in the contacts'
# order) only its head: the CPU streams such rows by itself, and fetching all of an MDR row's cells, of which a
# step reads a few, would evict what the next steps read. One source, compiled serial and parallel (prange is
# range in a serial build).

def _loop(nid, tid, params, pair_rows, H, rows, normals, overlaps, velocities, spins, wn, dt, forces, tforces,
          torques):
    """Template of the batch loop of one tangential law (the global ``tangential``: the law's 3D kernel; the
    global ``loop_range``: ``range`` for the serial loop, ``prange`` for the parallel one, as numba's prange
    in a serial build costs the loop its optimisations). spins, torques: float64[n, 3], or [0, 3] for none
    (no relative spin; the torques of the twist and rolling laws not kept). The body is the step of
    ``laws.compose`` written out: one level of inlined functions that take the arrays less, which the
    default law's loop repays (about 10%); the twist and rolling laws are one call out of line
    (``laws.compose.torque_laws``), made only for rows that name such laws, so that the body of a loop over rows
    without them stays as small (and as fast) as the step without torques."""
    n = overlaps.shape[0]
    spun = spins.shape[0] > 0
    kept = torques.shape[0] > 0
    b0 = twist_base(nid)
    for k in loop_range(n):  # noqa: F821
        if k + AHEAD < n:
            r_ahead = rows[k + AHEAD]
            if r_ahead == rows[k + AHEAD - 1] + 1:
                _prefetch_head(H, r_ahead)
            else:
                _prefetch_row(H, r_ahead)
        row = pair_rows[k]
        c = rows[k]
        nx = normals[k, 0]
        ny = normals[k, 1]
        nz = normals[k, 2]
        qid = int(params[row, P_TWIST_LAW]) - 1
        rid = int(params[row, P_ROLLING_LAW]) - 1
        vel, ddx, ddy, ddz, cs, sn = kinematics(nx, ny, nz, velocities[k, 0], velocities[k, 1], velocities[k, 2],
                                                wn[k], dt)
        N, a, s0, s1, s2, s3, s4 = normal_vector(nid, params, row, H, c, overlaps[k], vel)
        Np = N if N > 0.0 else 0.0
        b = b0
        qx = qy = qz = mx = my = mz = 0.0
        if qid > 0 or rid > 0:
            # the twist and rolling laws (none: no state, no torque, the tangential state at b0)
            b = tangential_base(nid, qid, rid)
            wx = spins[k, 0] if spun else 0.0
            wy = spins[k, 1] if spun else 0.0
            wz = spins[k, 2] if spun else 0.0
            qx, qy, qz, mx, my, mz = torque_laws(nid, qid, rid, params, row, H, c, Np, a, nx, ny, nz, wx, wy, wz, dt)
        tx, ty, tz = tangential(params, row, H, c, b, Np, a, s1, nx, ny, nz, ddx, ddy, ddz, cs, sn)  # noqa: F821
        store_normal(nid, H, c, s0, s1, s2, s3, s4, Np, tx, ty, tz)
        H[c, V_N] = Np
        H[c, V_A] = a
        forces[k, 0] = -N * nx - tx
        forces[k, 1] = -N * ny - ty
        forces[k, 2] = -N * nz - tz
        tforces[k, 0] = -tx
        tforces[k, 1] = -ty
        tforces[k, 2] = -tz
        if kept:
            torques[k, 0] = qx + mx
            torques[k, 1] = qy + my
            torques[k, 2] = qz + mz


def _loops_of(tangential, name):
    return (njit(_nrt=False, **JIT)(renamed(_loop, f"serial_{name}", tangential=tangential, loop_range=range)),
            njit(parallel=True, **JIT)(renamed(_loop, f"parallel_{name}", tangential=tangential, loop_range=prange)))


#: the loops of each tangential law: (serial, parallel)
_LOOPS = tuple(_loops_of(m.vector, m.NAME) for m in table.FAMILIES["tangential"])
_IDENTITY = [np.arange(0)]
_SCRATCH = threading.local()


def _identity_rows(n):
    """int64[n] 0 ... n - 1 (one array kept and grown: a view of it, never written)."""
    if len(_IDENTITY[0]) < n:
        _IDENTITY[0] = np.arange(max(n, 2 * len(_IDENTITY[0])), dtype=np.int64)
    return _IDENTITY[0][:n]


@njit(cache=True)
def _first_shared_row(rows, stamp, epoch):
    """The first contact c whose history row rows[c] an earlier contact uses, or -1: each used row is
    stamped with ``epoch`` (rows checked to be in range before)."""
    for c in range(rows.shape[0]):
        r = rows[c]
        if stamp[r] == epoch:
            return c
        stamp[r] = epoch
    return -1


def _distinct(rows, n_rows):
    """True when the int64 ``rows`` (all in [0, n_rows)) are distinct: one O(n) pass over a stamp array
    of this thread, kept between calls (a new stamp value per call, so it is never cleared)."""
    st = _SCRATCH.__dict__
    stamp = st.get("stamp")
    epoch = st.get("epoch", 0) + 1
    if stamp is None or len(stamp) < n_rows or epoch >= 2**31 - 1:
        stamp = st["stamp"] = np.zeros(max(n_rows, 0 if stamp is None else len(stamp)), dtype=np.int32)
        epoch = 1
    st["epoch"] = epoch
    return _first_shared_row(rows, stamp, epoch) < 0


def _valid_ids(nid, tid):
    nid = _law_id("nid (normal law id)", nid, NORMAL_IDS, _NORMAL_NAMES)
    return nid, _law_id("tid (tangential law id)", tid, TANGENTIAL_IDS, _TANGENTIAL_NAMES)


def _torque_ids(qid, rid):
    return (_law_id("qid (twist law id)", qid, TWIST_IDS, _TWIST_NAMES),
            _law_id("rid (rolling law id)", rid, ROLLING_IDS, _ROLLING_NAMES))


def batch_loop(nid, tid, parallel=False):
    """The jitted batch loop of the tangential law ``tid`` (ids checked here, once):
    loop(nid, tid, params, pair_rows, H, history_rows, normals, overlaps, velocities, spins, wn, dt, forces,
    tforces, torques), the arguments of ``contact_forces_batch`` with history_rows required and spins,
    torques float64[n, 3] or [0, 3] (none), none checked. For a
    caller that steps the same laws many times and checked its arrays once (``check_contacts``): arrays
    that do not pass ``check_contacts`` can make it write outside them."""
    nid, tid = _valid_ids(nid, tid)
    return _LOOPS[tid][1 if parallel else 0]


#: spins or torques not given: no rows
NONE3 = np.zeros((0, 3))


def _run(parallel, nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
         history_rows, spins, torques):
    nid, tid = _check_layout(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces,
                             tforces, history_rows, spins, torques)
    rows = _identity_rows(len(overlaps)) if history_rows is None else history_rows
    _LOOPS[tid][1 if parallel else 0](nid, tid, params, pair_rows, H, rows, normals, overlaps, velocities,
                                      NONE3 if spins is None else spins, wn, float(dt), forces, tforces,
                                      NONE3 if torques is None else torques)


def contact_forces_batch(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
                         history_rows=None, *, spins=None, torques=None):
    """Advance every contact by one step, in parallel (numba prange over contacts), with the loop compiled
    for the law family of ``tid`` only.

    params: float64[n_rows, N_PARAMS] (``pairs.pair_table``, built for these law ids); pair_rows: int64[n]
    row of each contact; H: float64[n, history_size] (updated); normals, velocities: float64[n, 3];
    overlaps, wn: float64[n]; dt [s]; forces, tforces: float64[n, 3] receive the force on body 1 and its
    tangential part. history_rows: int64[n], distinct, the row of H that holds each contact's history (H
    then has any number of rows: a DEM code's own per-particle storage, advanced in place); default: row c
    for contact c. spins: float64[n, 3], the relative spin w1 - w2 of the bodies of each contact [rad/s],
    for the twist and rolling laws; torques: float64[n, 3] receives their torque on body 1 [N m] (the moment
    of the tangential force is the caller's). Both are required when a row of the table has a twist or
    rolling law, and may be left out (None) otherwise.

    Checked here (``InputError``), in O(1) per array and O(n) over the row indices: everything that could
    make the loop read or write outside the arrays, race, or compute in float32 (law ids, dtypes,
    shapes, C order, writeable H, forces and tforces, rows in range, distinct history rows, history rows
    long enough, a table built for these laws, spins and torques given for its twist and rolling laws,
    dt > 0). The values of the contacts (finite inputs, unit
    normals) are checked by ``check_contacts`` / ``contact_forces``."""
    _run(True, nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
         history_rows, spins, torques)


def contact_forces_serial(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
                          history_rows=None, *, spins=None, torques=None):
    """``contact_forces_batch`` on one thread."""
    _run(False, nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
         history_rows, spins, torques)


def new_histories(n_contacts: int, history_size: int) -> np.ndarray:
    """Zeroed histories of ``n_contacts`` contacts, float64[n_contacts, history_size];
    ``history_size`` is ``PairTable.history_size``."""
    return np.zeros((n_contacts, history_size))


# ------------------------------------------------------------------------------------------- checked entry

_NORMAL_NAMES = ", ".join(f"{i} {name}" for i, name in enumerate(NORMAL_NAMES))
_TANGENTIAL_NAMES = ", ".join(f"{i} {name}" for i, name in enumerate(TANGENTIAL_NAMES))
_TWIST_NAMES = ", ".join(f"{i} {m.NAME}" for i, m in enumerate(table.FAMILIES["twist"]))
_ROLLING_NAMES = ", ".join(f"{i} {m.NAME}" for i, m in enumerate(table.FAMILIES["rolling"]))
UNIT_TOL = 1e-6
#: the largest turn of a contact in one step that ``check_contacts`` takes [rad]
MAX_TURN = 1.0


def _law_id(name, value, valid, names):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or int(value) not in valid:
        shown = repr(value) if isinstance(value, (int, float, str, np.number)) else f"a {type(value).__name__}"
        raise InputError(f"{name} = {shown} is not a law id (valid: {names})")
    return int(value)


def _array(name, a, ndim, dtype, shape=None, writeable=False):
    if not isinstance(a, np.ndarray):
        raise InputError(f"{name} must be a numpy array of {np.dtype(dtype).name}, got {type(a).__name__}")
    if a.dtype != dtype:
        raise InputError(f"{name} must have dtype {np.dtype(dtype).name}, got {a.dtype}")
    if a.ndim != ndim:
        raise InputError(f"{name} must be {ndim}-dimensional, got shape {a.shape}")
    if shape is not None:
        for k, (got, want) in enumerate(zip(a.shape, shape)):
            if want is not None and got != want:
                want_text = ", ".join("any" if w is None else str(w) for w in shape)
                raise InputError(f"{name} must have shape ({want_text}) (any: any length), got {a.shape}")
    if not a.flags.c_contiguous:
        raise InputError(f"{name} must be C-contiguous (np.ascontiguousarray)")
    if writeable and not a.flags.writeable:
        raise InputError(f"{name} must be writeable (the kernels write it in place): pass a writeable copy")


def _first_bad(name, bad, what):
    """Raise for the first True of the boolean per-contact array ``bad``."""
    if np.any(bad):
        c = int(np.argmax(bad))
        raise InputError(f"{name}[{c}] {what(c)}")


def _law_names(nid, tid):
    known = 0 <= nid < len(NORMAL_NAMES) and 0 <= tid < len(TANGENTIAL_NAMES)
    return f"{NORMAL_NAMES[nid]} + {TANGENTIAL_NAMES[tid]}" if known else "unknown laws"


def _check_table(nid, tid, params):
    """The laws recorded in every row of ``params`` (P_NORMAL_LAW, P_TANGENTIAL_LAW) must be (nid, tid);
    MDR rows need a cell count (and width). Returns the history row length the table needs. O(rows)."""
    _array("params", params, 2, np.float64, (None, N_PARAMS))
    if params.shape[0] == 0:
        raise InputError("params must have at least one row (pairs.pair_table)")
    built_n = params[:, P_NORMAL_LAW]
    built_t = params[:, P_TANGENTIAL_LAW]
    if not (np.all(built_n == nid + 1) and np.all(built_t == tid + 1)):
        r = int(np.argmax((built_n != nid + 1) | (built_t != tid + 1)))
        if built_n[r] == 0.0 and built_t[r] == 0.0:
            raise InputError(f"params[{r}] records no laws (params[:, P_NORMAL_LAW], params[:, P_TANGENTIAL_LAW] "
                             f"are 0): build the table with pairs.pair_table or model.Scene")
        bn, bt = int(built_n[r]) - 1, int(built_t[r]) - 1
        raise InputError(f"params[{r}] was built for the laws nid = {bn}, tid = {bt} ({_law_names(bn, bt)}), "
                         f"not for nid = {nid}, tid = {tid} ({_law_names(nid, tid)}): pass the table's own "
                         f"PairTable.normal_id and tangential_id, or build a table for these laws")
    extra = _torque_slots(params)
    law = table.FAMILIES["tangential"][tid]
    if not law.CELLS:
        return history_size(nid, tid) + extra
    for bad, why in law.check_rows(params):
        _first_bad("params", bad, lambda r: why)
    return history_size(nid, tid, int(params[:, P_NSPRING].max())) + extra


def _torque_slots(params):
    """The most history slots the twist and rolling laws of a row of ``params`` take (P_TWIST_LAW,
    P_ROLLING_LAW: id + 1, 0 = none), checking that they are law ids."""
    for family, slot in (("twist", P_TWIST_LAW), ("rolling", P_ROLLING_LAW)):
        laws = table.FAMILIES[family]
        ids = params[:, slot]
        bad = ~((ids >= 0.0) & (ids <= len(laws)) & (ids == np.floor(ids)))
        _first_bad("params", bad, lambda r: f"records the {family} law {ids[r]!r}, not a law id + 1 (valid: 0 to "
                                            f"{len(laws)}; slot P_{family.upper()}_LAW)")
    q = np.maximum(params[:, P_TWIST_LAW].astype(np.int64) - 1, 0)
    r = np.maximum(params[:, P_ROLLING_LAW].astype(np.int64) - 1, 0)
    slots_q = np.array([m.VECTOR_SLOTS for m in table.FAMILIES["twist"]])
    slots_r = np.array([m.VECTOR_SLOTS for m in table.FAMILIES["rolling"]])
    return int((slots_q[q] + slots_r[r]).max())


def _check_torque_arrays(params, spins, torques):
    """A table with a twist or rolling law needs spins (without them the contact never turns) and torques
    (without them its moment is dropped)."""
    for family, slot in (("twist", P_TWIST_LAW), ("rolling", P_ROLLING_LAW)):
        used = params[:, slot] >= 2.0                       # id + 1; id 0 is none
        if not np.any(used):
            continue
        r = int(np.argmax(used))
        law = f"params[{r}] has the {family} law {table.FAMILIES[family][int(params[r, slot]) - 1].NAME}"
        if spins is None:
            raise InputError(f"spins is required: {law}, which acts on the relative spin w1 - w2 of the bodies "
                             f"(spins=float64[n, 3]); without it the contact never turns")
        if torques is None:
            raise InputError(f"torques is required: {law}, whose torque on body 1 it receives "
                             f"(torques=float64[n, 3]); without it the moment is dropped")


def _check_layout(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
                  history_rows, spins=None, torques=None):
    """What the loops need not to read or write outside the arrays, race or compute in float32:
    O(1) per array, O(rows of params), O(n) over the row indices. Returns the checked (nid, tid)."""
    nid, tid = _valid_ids(nid, tid)
    need = _check_table(nid, tid, params)
    _array("overlaps", overlaps, 1, np.float64)
    n = overlaps.shape[0]
    _array("pair_rows", pair_rows, 1, np.int64, (n,))
    if history_rows is None:
        _array("H", H, 2, np.float64, (n, None), writeable=True)
    else:
        _array("H", H, 2, np.float64, (None, None), writeable=True)
        _array("history_rows", history_rows, 1, np.int64, (n,))
    if H.shape[1] < need:
        raise InputError(f"H has rows of length {H.shape[1]}; these laws and params need {need} "
                         f"(PairTable.history_size, contact3d.history_size)")
    _array("normals", normals, 2, np.float64, (n, 3))
    _array("velocities", velocities, 2, np.float64, (n, 3))
    _array("wn", wn, 1, np.float64, (n,))
    for name, a in (("forces", forces), ("tforces", tforces), ("torques", torques)):
        if a is not None:
            _array(name, a, 2, np.float64, (n, 3), writeable=True)
    if spins is not None:
        _array("spins", spins, 2, np.float64, (n, 3))
    _check_torque_arrays(params, spins, torques)
    if not (isinstance(dt, (float, int, np.floating, np.integer)) and not isinstance(dt, (bool, np.bool_))
            and math.isfinite(dt) and dt > 0.0):
        raise InputError(f"dt = {dt!r} must be a finite time step > 0 [s]")
    if n == 0:
        return nid, tid
    rows = params.shape[0]
    if pair_rows.view(np.uint64).max() >= rows:               # (a negative row reads as a huge one)
        _first_bad("pair_rows", (pair_rows < 0) | (pair_rows >= rows),
                   lambda c: f"= {pair_rows[c]} is not a row of params (valid: 0 to {rows - 1})")
    if history_rows is not None:
        nh = H.shape[0]
        if history_rows.view(np.uint64).max() >= nh:
            _first_bad("history_rows", (history_rows < 0) | (history_rows >= nh),
                       lambda c: f"= {history_rows[c]} is not a row of H (valid: 0 to {nh - 1})")
        if not _distinct(history_rows, nh):
            raise InputError("history_rows must be distinct: two contacts cannot share one history row")
    return nid, tid


def _length(v):
    """The lengths of the rows of v float64[n, 3] (without overflowing their squares)."""
    return np.hypot(np.hypot(v[:, 0], v[:, 1]), v[:, 2])


def check_contacts(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces=None,
                   tforces=None, history_rows=None, *, spins=None, torques=None):
    """Check the arguments of ``contact_forces_batch`` / ``contact_forces_serial`` (and so of every
    ``contact_force`` call that uses the same arrays): law ids, a table built for them, dtypes, shapes,
    C-contiguity, writeable H (and forces, tforces), row indices in range (``history_rows`` distinct rows
    of H), history rows long enough for the laws, spins and torques given for the table's twist and
    rolling laws, unit normals (within 1e-6), dt > 0, finite inputs,
    overlaps and the distance the bodies move in one step (|v| dt) below the pair's R*, and turns in one step
    (|wn| dt, |spins| dt) below MAX_TURN.
    Raises ``InputError`` naming the first bad array and contact. Call it once per set of arrays (and
    again when they are reallocated); the jitted kernels themselves do not check."""
    _check_layout(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
                  history_rows, spins, torques)
    _first_bad("params", ~np.all(np.isfinite(params), axis=1), lambda r: "is not finite")
    if len(overlaps) == 0:
        return
    hist = H if history_rows is None else H[history_rows]
    _first_bad("H" if history_rows is None else "H[history_rows]", ~np.all(np.isfinite(hist), axis=1),
               lambda c: "(the history of the contact) is not finite")
    _first_bad("normals", ~np.all(np.isfinite(normals), axis=1), lambda c: "is not finite")
    length = np.sqrt(np.einsum("ij,ij->i", normals, normals))
    _first_bad("normals", np.abs(length - 1.0) > UNIT_TOL,
               lambda c: f"has length {length[c]:.9g} (a unit vector is needed, within {UNIT_TOL:g})")
    _first_bad("overlaps", ~np.isfinite(overlaps), lambda c: "is not finite")
    r_star = params[pair_rows, P_RSTAR]
    _first_bad("overlaps", ~(overlaps < r_star),
               lambda c: f"= {overlaps[c]:.6g} m is not below the pair's effective radius R* = {r_star[c]:.6g} m "
                         f"(the contact laws hold for overlaps far below it)")
    _first_bad("velocities", ~np.all(np.isfinite(velocities), axis=1), lambda c: "is not finite")
    # (a step that moves the bodies by more than R*, or turns them by a radian or more, resolves nothing of the
    # contact; beyond it the squares of the slip overflow, and the laws return no friction at all)
    moved = dt * _length(velocities)
    _first_bad("velocities", ~(moved < r_star),
               lambda c: f"moves the bodies {moved[c]:.6g} m in one step (|v| dt), not below the pair's effective "
                         f"radius R* = {r_star[c]:.6g} m: a time step too long for this speed")
    _first_bad("wn", ~np.isfinite(wn), lambda c: "is not finite")
    _first_bad("wn", ~(np.abs(wn) * dt < MAX_TURN),
               lambda c: f"turns the contact frame by {abs(wn[c]) * dt:.6g} rad in one step (|wn| dt), not below "
                         f"{MAX_TURN:g} rad: a time step too long for this spin")
    if spins is not None:
        _first_bad("spins", ~np.all(np.isfinite(spins), axis=1), lambda c: "is not finite")
        turned = dt * _length(spins)
        _first_bad("spins", ~(turned < MAX_TURN),
                   lambda c: f"turns the bodies by {turned[c]:.6g} rad against each other in one step (|w| dt), not "
                             f"below {MAX_TURN:g} rad: a time step too long for this spin")


@njit(boundscheck=True, **JIT)
def _serial_debug(nid, tid, params, pair_rows, H, hrows, normals, overlaps, velocities, spins, wn, dt, forces,
                  tforces, torques, need):
    """``contact_forces_serial`` with bounds checks and per-contact checks of what the kernel relies on;
    returns (-1, 0) or (first bad contact, reason: 1 row, 2 history row length, 3 normal, 4 non-finite
    input, 5 non-finite force)."""
    for c in range(overlaps.shape[0]):
        row = pair_rows[c]
        if row < 0 or row >= params.shape[0]:
            return c, 1
        if H.shape[1] < need:
            return c, 2
        nx = normals[c, 0]
        ny = normals[c, 1]
        nz = normals[c, 2]
        if not abs(math.sqrt(nx * nx + ny * ny + nz * nz) - 1.0) <= UNIT_TOL:
            return c, 3
        w = spins[c] if spins.shape[0] > 0 else np.zeros(3)
        s = overlaps[c] + velocities[c, 0] + velocities[c, 1] + velocities[c, 2] + wn[c] + w[0] + w[1] + w[2]
        if not math.isfinite(s):
            return c, 4
        fx, fy, fz, tx, ty, tz, mx, my, mz = contact_force_torque(
            nid, tid, params, row, H, hrows[c], nx, ny, nz, overlaps[c],
            velocities[c, 0], velocities[c, 1], velocities[c, 2], w[0], w[1], w[2], wn[c], dt)
        forces[c, 0], forces[c, 1], forces[c, 2], tforces[c, 0], tforces[c, 1], tforces[c, 2] = fx, fy, fz, tx, ty, tz
        if torques.shape[0] > 0:
            torques[c, 0], torques[c, 1], torques[c, 2] = mx, my, mz
        if not math.isfinite(fx + fy + fz + mx + my + mz):
            return c, 5
    return -1, 0


_DEBUG_REASONS = {1: "pair_rows[{c}] is not a row of params", 2: "H rows are too short for the laws",
                  3: "normals[{c}] is not a unit vector", 4: "an input of contact {c} is not finite"}


def _nonfinite_force(c, overlap, tid) -> NumericalError:
    hint = getattr(table.FAMILIES["tangential"][tid], "NAN_HINT", "")
    return NumericalError(f"contact {c}: the force is not finite (overlap {overlap:.6g} m{hint and ', ' + hint})")


def contact_forces(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces, *,
                   history_rows=None, parallel=True, debug=None, spins=None, torques=None):
    """Checked batch step: ``check_contacts``, then ``contact_forces_batch`` (``parallel``) or
    ``contact_forces_serial`` (``history_rows``, ``spins``, ``torques``: see ``contact_forces_batch``). ``debug`` (default: the
    environment variable DEM_CONTACT_DEBUG set to 1): run a serial loop compiled with numba's bounds
    checks that also checks every contact's inputs and force, and raises ``InputError`` /
    ``NumericalError`` naming the first bad contact."""
    check_contacts(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces,
                   history_rows, spins=spins, torques=torques)
    nid, tid = int(nid), int(tid)
    spins3 = NONE3 if spins is None else spins
    torques3 = NONE3 if torques is None else torques
    if debug is None:
        debug = os.environ.get("DEM_CONTACT_DEBUG", "") not in ("", "0")
    hrows = _identity_rows(len(overlaps)) if history_rows is None else history_rows
    if debug:
        need = H.shape[1]
        if not table.FAMILIES["tangential"][tid].CELLS:
            need = history_size(nid, tid) + _torque_slots(params)
        elif len(pair_rows):
            need = history_size(nid, tid, int(params[pair_rows, P_NSPRING].max())) + _torque_slots(params)
        c, reason = _serial_debug(nid, tid, params, pair_rows, H, hrows, normals, overlaps, velocities, spins3,
                                  wn, float(dt), forces, tforces, torques3, need)
        if reason == 5:
            raise _nonfinite_force(c, overlaps[c], tid)
        if reason:
            raise InputError(_DEBUG_REASONS[reason].format(c=c))
    else:
        _LOOPS[tid][1 if parallel else 0](nid, tid, params, pair_rows, H, hrows, normals, overlaps, velocities,
                                          spins3, wn, float(dt), forces, tforces, torques3)
        n = len(overlaps)
        bad = ~(np.all(np.isfinite(forces[:n]), axis=1) & np.all(np.isfinite(tforces[:n]), axis=1))
        if torques is not None:
            bad |= ~np.all(np.isfinite(torques[:n]), axis=1)
        if np.any(bad):
            c = int(np.argmax(bad))
            raise _nonfinite_force(c, overlaps[c], tid)
