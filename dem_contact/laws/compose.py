"""One 3D contact step composed of the laws of the table: the kinematics of the contact, the normal law,
then the tangential law, writing the history row in place.

The step is compiled for each tangential law as a non-inlined leaf (``LEAVES``, for the single-contact
entry, whose switch on the id is ``dispatch3d``), each under a name of its own (``vector.renamed``): numba
names compiled code by the qualified name. The batch loops of ``dem.contact3d`` write the same step out
in their body (one level of inlining less, which the default law's loop repays); the law-contract tests
hold the two equal.
"""
from numba import njit

from . import table
from .dispatch import (normal_vector, rolling_base, rolling_torque, store_normal, tangential_base, twist_base,
                       twist_torque)
from .slots import P_ROLLING_LAW, P_TWIST_LAW
from .vector import JIT, V_A, V_N, renamed


@njit(inline="always", **JIT)
def kinematics(nx, ny, nz, vx, vy, vz, wn, dt):
    """Overlap rate v . n, slip increment dd = (v - (v . n) n) dt, and (cos, sin) of the turn of the contact
    frame about the normal, 2 atan(wn dt / 2) (Cayley form of the rotation by wn dt)."""
    vel = vx * nx + vy * ny + vz * nz
    cs = 1.0
    sn = 0.0
    if wn != 0.0:
        q = 0.5 * wn * dt
        inv = 1.0 / (1.0 + q * q)
        cs = (1.0 - q * q) * inv
        sn = 2.0 * q * inv
    return vel, (vx - vel * nx) * dt, (vy - vel * ny) * dt, (vz - vel * nz) * dt, cs, sn


@njit(_nrt=False, **JIT)
def torque_laws(nid, qid, rid, params, row, H, c, N, a, nx, ny, nz, wx, wy, wz, dt):
    """The torques on body 1 of the twist law ``qid`` and the rolling law ``rid`` (their states after the
    normal law's), not inlined: one compiled function that every step calls, only for rows that name such
    laws, so that neither the leaves nor the batch loops compile the twist and rolling laws into their body."""
    qx, qy, qz = twist_torque(qid, params, row, H, c, twist_base(nid), N, a, nx, ny, nz, wx, wy, wz, dt)
    mx, my, mz = rolling_torque(rid, params, row, H, c, rolling_base(nid, qid), N, a, nx, ny, nz, wx, wy, wz, dt)
    return qx, qy, qz, mx, my, mz


def _step(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt):
    """Template of the step of one tangential law (the global ``tangential``, bound per law by ``renamed``).
    (wx, wy, wz): relative spin w1 - w2 of the bodies [rad/s], for the twist and rolling laws (recorded in
    the parameter row). Returns the force on body 1, its tangential part and the torque on body 1 of the
    twist and rolling laws (Fx, Fy, Fz, Ftx, Fty, Ftz, Mx, My, Mz) [N, N m]."""
    qid = int(params[row, P_TWIST_LAW]) - 1
    rid = int(params[row, P_ROLLING_LAW]) - 1
    vel, ddx, ddy, ddz, cs, sn = kinematics(nx, ny, nz, vx, vy, vz, wn, dt)
    N, a, s0, s1, s2, s3, s4 = normal_vector(nid, params, row, H, c, delta, vel)
    b = tangential_base(nid, qid, rid)
    Np = N if N > 0.0 else 0.0
    # the twist and rolling laws before the tangential one (which writes the history row last)
    qx = qy = qz = mx = my = mz = 0.0
    if qid > 0 or rid > 0:
        qx, qy, qz, mx, my, mz = torque_laws(nid, qid, rid, params, row, H, c, Np, a, nx, ny, nz, wx, wy, wz, dt)
    tx, ty, tz = tangential(params, row, H, c, b, Np, a, s1, nx, ny, nz, ddx, ddy, ddz, cs, sn)  # noqa: F821
    store_normal(nid, H, c, s0, s1, s2, s3, s4, Np, tx, ty, tz)
    H[c, V_N] = Np
    H[c, V_A] = a
    return -N * nx - tx, -N * ny - ty, -N * nz - tz, -tx, -ty, -tz, qx + mx, qy + my, qz + mz


#: the step of each tangential law, in id order, not inlined (compiled from the template directly: each level
#: of inlining costs compile time)
LEAVES = tuple(njit(**JIT)(renamed(_step, f"leaf_{m.NAME}", tangential=m.vector)) for m in table.FAMILIES["tangential"])
