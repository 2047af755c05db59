"""Drop-in 3D contact force for DEM codes: any normal x tangential law of ``laws.contact``, in 3D.

Conventions (SI units):

- ``n``: unit normal from body 1 to body 2; ``delta`` > 0: overlap [m];
- ``v``: relative velocity of body 1 with respect to body 2 at the contact point [m/s],
  v = (V1 + w1 x r1) - (V2 + w2 x r2) with r_i the vector from the centre of body i to the contact point;
  the overlap rate is d(delta)/dt = v . n (seen by dashpots) and the slip increment is
  dd = (v - (v . n) n) dt. In a velocity-Verlet loop pass the half-step velocities (the slip over the step);
  ``integrator.integrate_impact`` additionally gives dashpots the normal velocity predicted at the end of
  the step, v . n - (dt / 2) N / m* (the 3D test loop does the same);
- returned: the force on body 1 (normal + tangential) and its tangential part (for the torques
  r1 x F_t on body 1 and -r2 x F_t on body 2). The force on body 2 is the opposite.

State of one contact: the planar history row ``h`` (``laws.slots``, its length is the law's history size)
and a separate row ``h3`` of ``N_HIST3D`` floats holding the unit axis u of the planar law, so that the
tangential force on body 1 is F_t = -h[H_T] u (physics.md 5.3 sign: T acts along the displacement,
the force on body 1 is -T). Slots H_TANG_EXTRA and later of ``h`` stay the planar law's own.

3D extension of the planar (scalar) tangential laws, every step:

1. u is carried into the current tangent plane, u <- (u - (u.n) n) / |u - (u.n) n|, which keeps |T|
   (physics.md 5.4). When h[H_T] = 0 (new or released contact) u is the slip direction dd / |dd|.
2. The slip increment is split into d_par = dd . u and d_perp = dd - d_par u. d_par drives the planar law
   (``laws.contact.contact_step``) along u: loading / unloading / reloading of Mindlin-Deresiewicz, the
   reversal points T*, T**, the mu dN terms and Coulomb slip are those of the planar law for the
   displacement component along the force axis. A reversal means d_par changing sign.
3. d_perp turns the force about the normal, keeping the planar law's |T|: the force takes the direction
   of w = T u + k_0 d_perp, with the elastic stiffness k_0 = 8 G* a (P_KT for the linear tangential law),
   and the axis follows it, u <- sign(T) w / |w|. The law's own state (T, T*, T**, regime, xi, MDR cells)
   is not touched, so |T| <= mu N holds as in the planar law; the magnitude change that d_perp would
   add is of second order in the step and is left out.

When the motion stays in one plane, d_perp is exactly zero and the kernel performs exactly the planar
law's operations (the planar reduction is tested against ``integrator.integrate_impact``).
"""
import math

import numpy as np
from numba import njit, prange

from ..laws.contact import LINEAR_TANGENTIAL, contact_step
from ..laws.slots import H_T, P_GSTAR, P_KT

# slots of the per-contact 3D row h3
H3_UX = 0      # axis of the planar tangential law, unit vector in the tangent plane (0 when unset)
H3_UY = 1
H3_UZ = 2
N_HIST3D = 3


@njit(cache=True)
def elastic_tangential_stiffness(tid, p, a):
    """Stiffness that turns the tangential force for slip across its axis [N/m]: the Mindlin stiffness
    8 G* a (physics.md section 1), or the constant k_t of the linear (Cundall-Strack) law."""
    if tid == LINEAR_TANGENTIAL:
        return p[P_KT]
    return 8.0 * p[P_GSTAR] * a


@njit(cache=True)
def contact_force_xyz(nid, tid, p, h, h3, nx, ny, nz, delta, vx, vy, vz, dt):
    """One contact step in 3D, scalar arguments (see the module docstring for conventions and the
    3D extension of the planar laws).

    nid, tid: law ids (``laws.contact``); p: parameter row; h: history row, h3: float64[N_HIST3D], both
    updated in place; (nx, ny, nz): unit normal from body 1 to body 2; delta: overlap [m];
    (vx, vy, vz): relative velocity of body 1 w.r.t. body 2 at the contact point [m/s]; dt [s].
    Returns (Fx, Fy, Fz, Ftx, Fty, Ftz): the total force on body 1 and its tangential part [N].
    """
    vel = vx * nx + vy * ny + vz * nz
    ddx = (vx - vel * nx) * dt
    ddy = (vy - vel * ny) * dt
    ddz = (vz - vel * nz) * dt
    ux = h3[H3_UX]
    uy = h3[H3_UY]
    uz = h3[H3_UZ]
    axis = False
    if h[H_T] != 0.0:
        # carry the axis into the current tangent plane, keeping |T| (physics.md 5.4)
        un = ux * nx + uy * ny + uz * nz
        ux -= un * nx
        uy -= un * ny
        uz -= un * nz
        norm = math.sqrt(ux * ux + uy * uy + uz * uz)
        if norm > 0.0:
            ux /= norm
            uy /= norm
            uz /= norm
            axis = True
    if not axis:
        dmag = math.sqrt(ddx * ddx + ddy * ddy + ddz * ddz)
        if dmag > 0.0:
            ux = ddx / dmag
            uy = ddy / dmag
            uz = ddz / dmag
        else:
            ux = 0.0
            uy = 0.0
            uz = 0.0
    d_par = ddx * ux + ddy * uy + ddz * uz
    px = ddx - d_par * ux
    py = ddy - d_par * uy
    pz = ddz - d_par * uz
    N, a, T = contact_step(nid, tid, p, h, delta, vel, d_par)
    tx = T * ux
    ty = T * uy
    tz = T * uz
    if T != 0.0 and (px != 0.0 or py != 0.0 or pz != 0.0):
        # slip across the axis turns the force about the normal; its magnitude is the planar law's |T|
        k0 = elastic_tangential_stiffness(tid, p, a)
        wx = tx + k0 * px
        wy = ty + k0 * py
        wz = tz + k0 * pz
        inv = 1.0 / math.sqrt(wx * wx + wy * wy + wz * wz)
        if T < 0.0:
            inv = -inv
        ux = wx * inv          # T u = |T| w / |w|
        uy = wy * inv
        uz = wz * inv
        tx = T * ux
        ty = T * uy
        tz = T * uz
    h3[H3_UX] = ux
    h3[H3_UY] = uy
    h3[H3_UZ] = uz
    return -N * nx - tx, -N * ny - ty, -N * nz - tz, -tx, -ty, -tz


@njit(cache=True)
def contact_force(nid, tid, p, h, h3, n, delta, v, dt, out):
    """``contact_force_xyz`` with vectors: n, v float64[3]; out float64[6] receives the force on body 1
    (out[0:3]) and its tangential part (out[3:6]). h, h3 are updated in place."""
    fx, fy, fz, tx, ty, tz = contact_force_xyz(nid, tid, p, h, h3, n[0], n[1], n[2], delta, v[0], v[1], v[2], dt)
    out[0] = fx
    out[1] = fy
    out[2] = fz
    out[3] = tx
    out[4] = ty
    out[5] = tz


@njit(cache=True)
def peek_force(nid, tid, p, h, h3, n, delta, v, dt, out):
    """``contact_force`` evaluated on copies of the history: h and h3 are left unchanged."""
    contact_force(nid, tid, p, h.copy(), h3.copy(), n, delta, v, dt, out)


@njit(cache=True)
def reset_contact(h, h3):
    """Zero the history of a contact (call on separation, before the slots are reused)."""
    h[:] = 0.0
    h3[:] = 0.0


@njit(cache=True)
def swap_bodies(h, h3):
    """Exchange bodies 1 and 2 of a contact: the normal, the relative velocity, the displacement and the
    tangential force all change sign, which is the sign of the axis u (the scalar state along u is
    unchanged). Swapping twice is the identity."""
    h3[H3_UX] = -h3[H3_UX]
    h3[H3_UY] = -h3[H3_UY]
    h3[H3_UZ] = -h3[H3_UZ]


@njit(cache=True)
def _one(c, nid, tid, params, pair, H, H3, normals, overlaps, velocities, dt, forces, tforces):
    fx, fy, fz, tx, ty, tz = contact_force_xyz(
        nid, tid, params[pair[c]], H[c], H3[c], normals[c, 0], normals[c, 1], normals[c, 2], overlaps[c],
        velocities[c, 0], velocities[c, 1], velocities[c, 2], dt)
    forces[c, 0] = fx
    forces[c, 1] = fy
    forces[c, 2] = fz
    tforces[c, 0] = tx
    tforces[c, 1] = ty
    tforces[c, 2] = tz


@njit(parallel=True, cache=True)
def contact_forces_batch(nid, tid, params, pair, H, H3, normals, overlaps, velocities, dt, forces, tforces):
    """Advance many contacts by one step in parallel (prange over contacts).

    params: float64[n_rows, N_PARAMS] pair table (``pairs.pair_table``); pair: int64[n] row of each contact;
    H: float64[n, n_hist], H3: float64[n, N_HIST3D] histories (updated); normals, velocities:
    float64[n, 3]; overlaps: float64[n]; dt [s]; forces, tforces: float64[n, 3] receive the force on
    body 1 and its tangential part."""
    for c in prange(overlaps.shape[0]):
        _one(c, nid, tid, params, pair, H, H3, normals, overlaps, velocities, dt, forces, tforces)


@njit(cache=True)
def contact_forces_serial(nid, tid, params, pair, H, H3, normals, overlaps, velocities, dt, forces, tforces):
    """``contact_forces_batch`` on one thread."""
    for c in range(overlaps.shape[0]):
        _one(c, nid, tid, params, pair, H, H3, normals, overlaps, velocities, dt, forces, tforces)


def new_histories(n_contacts: int, history_size: int):
    """Zeroed histories of ``n_contacts`` contacts: (H float64[n, history_size], H3 float64[n, N_HIST3D]).
    ``history_size`` is ``Scene.history_size`` or ``PairTable.history_size``."""
    return np.zeros((n_contacts, history_size)), np.zeros((n_contacts, N_HIST3D))
