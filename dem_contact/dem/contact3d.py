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
then the law acts on the slip increment:

- ``mindlin_total``, ``ddm``, ``mindlin_incremental``, ``mindlin_rescale``, ``linear``: vector springs
  (the LAMMPS granular ``mindlin``, ``mindlin/force``, ``mindlin_rescale/force`` arithmetic), Coulomb by
  scaling the force back to mu N;
- ``md``, ``md_rescale``: the planar law along the force axis; slip across the axis turns the force;
- ``mdr``, ``mdr_adaptive``: vector MDR, each cell a displacement in the tangent plane with its own
  Coulomb circle (radial return).

Motion in one plane repeats the planar laws (``laws.contact``) to rounding error. The kernels do not check
their arguments: call ``check_contacts`` once per set of arrays, or ``contact_forces(..., debug=True)``.
"""
import math
import os

import numpy as np
from numba import njit, prange

from ..errors import InputError, NumericalError
from ..laws import vector as V
from ..laws.contact import (DDM, HERTZ, HERTZ_DAMPED, LINEAR_NORMAL, LINEAR_TANGENTIAL, MD, MD_RESCALE,
                            MDR, MDR_ADAPTIVE, MINDLIN_INCREMENTAL, MINDLIN_RESCALE, MINDLIN_TOTAL, THORNTON)
from ..laws.slots import N_PARAMS, P_DX, P_GSTAR, P_KT, P_NSPRING
from ..laws.vector import JIT, V_A, V_N, W_WORK, W_X, history_size, tangential_base

__all__ = ["contact_force", "peek_force", "reset_contact", "swap_bodies", "rotate_history", "tangential_work",
           "contact_forces_batch", "contact_forces_serial", "contact_forces", "check_contacts",
           "new_histories", "history_size"]


@njit(**JIT)
def _normal(nid, params, row, H, c, delta, vel):
    if nid == HERTZ:
        return V.hertz(params, row, delta)
    if nid == THORNTON:
        return V.thornton(params, row, H, c, delta)
    if nid == HERTZ_DAMPED:
        return V.hertz_damped(params, row, delta, vel)
    if nid == LINEAR_NORMAL:
        return V.linear_normal(params, row, delta, vel)
    raise InputError("unknown normal law id (valid: 0 hertz, 1 thornton, 2 hertz_damped, 3 linear)")


@njit(**JIT)
def _tangential(tid, params, row, H, c, b, N, dN, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    if tid == MD or tid == MD_RESCALE:
        return V.md_axis(params, row, H, c, b, N, dN, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn,
                         tid == MD_RESCALE)
    if tid == MDR_ADAPTIVE or tid == MDR:
        return V.mdr_vector(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn,
                            tid == MDR_ADAPTIVE)
    if tid == MINDLIN_TOTAL:
        return V.spring_total(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn, 1.0)
    if tid == DDM:
        return V.spring_total(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn,
                              2.0 / 3.0)
    if tid == MINDLIN_INCREMENTAL or tid == MINDLIN_RESCALE:
        return V.spring_incremental(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn,
                                    8.0 * params[row, P_GSTAR] * a, tid == MINDLIN_RESCALE)
    if tid == LINEAR_TANGENTIAL:
        return V.spring_incremental(params, row, H, c, b, N, a, a, nx, ny, nz, ddx, ddy, ddz, cs, sn,
                                    params[row, P_KT], False)
    raise InputError("unknown tangential law id (valid: 0 to 8, see laws.contact)")


@njit(**JIT)
def contact_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    """One contact step in 3D (see the module docstring). Updates H[c, :] in place.
    Returns (Fx, Fy, Fz, Ftx, Fty, Ftz): the total force on body 1 and its tangential part [N]."""
    vel = vx * nx + vy * ny + vz * nz
    ddx = (vx - vel * nx) * dt
    ddy = (vy - vel * ny) * dt
    ddz = (vz - vel * nz) * dt
    cs = 1.0
    sn = 0.0
    if wn != 0.0:
        q = 0.5 * wn * dt
        inv = 1.0 / (1.0 + q * q)
        cs = (1.0 - q * q) * inv
        sn = 2.0 * q * inv
    N, a = _normal(nid, params, row, H, c, delta, vel)
    Np = N if N > 0.0 else 0.0
    tx, ty, tz = _tangential(tid, params, row, H, c, tangential_base(nid), Np, Np - H[c, V_N], a,
                             H[c, V_A], nx, ny, nz, ddx, ddy, ddz, cs, sn)
    H[c, V_N] = Np
    H[c, V_A] = a
    return -N * nx - tx, -N * ny - ty, -N * nz - tz, -tx, -ty, -tz


@njit(**JIT)
def peek_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    """``contact_force`` on a copy of the contact's history: H is left unchanged."""
    tmp = H[c:c + 1].copy()
    return contact_force(nid, tid, params, row, tmp, 0, nx, ny, nz, delta, vx, vy, vz, wn, dt)


@njit(**JIT)
def reset_contact(H, c):
    """Zero the history of contact c (call on separation, before the row is reused)."""
    for j in range(H.shape[1]):
        H[c, j] = 0.0


@njit(**JIT)
def swap_bodies(nid, tid, params, row, H, c):
    """Exchange bodies 1 and 2 of contact c: the normal, the relative velocity, the displacement and the
    tangential force change sign. Swapping twice is the identity."""
    b = tangential_base(nid)
    for j in range(W_X, W_X + 3):
        H[c, b + j] = -H[c, b + j]
    if tid == MDR or tid == MDR_ADAPTIVE:
        # e1 -> -e1 and n -> -n keep e2 = n x e1: the second components change sign
        H[c, b + V.R_T2] = -H[c, b + V.R_T2]
        for i in range(int(params[row, P_NSPRING])):
            H[c, b + V.R_CELLS + 2 * i + 1] = -H[c, b + V.R_CELLS + 2 * i + 1]


@njit(**JIT)
def rotate_history(nid, H, c, Q):
    """Turn the tangential history of contact c rigidly by the rotation matrix Q (float64[3, 3], proper
    orthogonal), e.g. for a pair whose frame is rotated by the caller. Its next step must get Q n."""
    b = tangential_base(nid)
    x = H[c, b + W_X]
    y = H[c, b + W_X + 1]
    z = H[c, b + W_X + 2]
    for i in range(3):
        H[c, b + W_X + i] = Q[i, 0] * x + Q[i, 1] * y + Q[i, 2] * z


@njit(**JIT)
def tangential_work(nid, H, c):
    """Work absorbed by the tangential force of contact c since its history was zeroed [J]: the sum over
    steps of 0.5 (T_old + T) . dd. A passive contact keeps it >= 0; a negative value is energy created."""
    return H[c, tangential_base(nid) + W_WORK]


@njit(inline="always", **JIT)
def _one(c, nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces):
    fx, fy, fz, tx, ty, tz = contact_force(
        nid, tid, params, pair_rows[c], H, c, normals[c, 0], normals[c, 1], normals[c, 2], overlaps[c],
        velocities[c, 0], velocities[c, 1], velocities[c, 2], wn[c], dt)
    forces[c, 0] = fx
    forces[c, 1] = fy
    forces[c, 2] = fz
    tforces[c, 0] = tx
    tforces[c, 1] = ty
    tforces[c, 2] = tz


@njit(parallel=True, **JIT)
def contact_forces_batch(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces,
                         tforces):
    """Advance every contact by one step, in parallel (prange over contacts); no argument checks.

    params: float64[n_rows, N_PARAMS]; pair_rows: int64[n] row of each contact; H: float64[n, history_size]
    (updated); normals, velocities: float64[n, 3]; overlaps, wn: float64[n]; dt [s]; forces, tforces:
    float64[n, 3] receive the force on body 1 and its tangential part."""
    for c in prange(overlaps.shape[0]):
        _one(c, nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces)


@njit(**JIT)
def contact_forces_serial(nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces,
                          tforces):
    """``contact_forces_batch`` on one thread."""
    for c in range(overlaps.shape[0]):
        _one(c, nid, tid, params, pair_rows, H, normals, overlaps, velocities, wn, dt, forces, tforces)


def new_histories(n_contacts: int, history_size: int) -> np.ndarray:
    """Zeroed histories of ``n_contacts`` contacts, float64[n_contacts, history_size];
    ``history_size`` is ``PairTable.history_size``."""
    return np.zeros((n_contacts, history_size))
