"""Total-displacement no-slip Hertz-Mindlin (Mindlin 1949; LIGGGHTS `tangential history`, EDEM, LAMMPS
granular `mindlin`): a spring displacement xi takes every increment, T = 8 G* a xi, and Coulomb slip scales T
back to mu N with xi = T / (8 G* a). In 3D xi is a vector of the tangent plane (LAMMPS's arithmetic)."""
from numba import njit

from ..declare import GSTAR, MU
from ..slots import H_T, H_XI, P_GSTAR, P_MU
from ..vector import JIT, V_A, W_WORK, W_X, W_Y, W_Z, at, cap_vector, carry, put, renamed
from .common import cap, release

NAME, FAMILY = "mindlin_total", "tangential"
SOURCE = "total-displacement no-slip Hertz-Mindlin (LIGGGHTS tangential history, EDEM, LAMMPS mindlin)"
PARAMETERS, STATE = (GSTAR, MU), ("xi", "T")
#: LAMMPS's equivalent tangential model (``pair granular ... tangential``; see ``lammps.native``)
LAMMPS = "mindlin"
#: stiffness factor on 8 G* a
FACTOR = 1.0
#: fixed 3D slots (the work and the spring displacement xi); swapping the bodies negates xi
VECTOR_SLOTS = 4
SWAP_NEGATE = (W_X, W_Y, W_Z)


@njit(cache=True)
def total(p, h, N, a, dd, factor):
    """Total-displacement no-slip Hertz-Mindlin (LIGGGHTS `tangential history`, EDEM, LAMMPS `mindlin`;
    Mindlin 1949; Di Renzo & Di Maio 2004): xi += dd, T = factor 8 G* a xi, capped at mu N with xi = T / (factor 8 G* a).
    factor = 1; factor = 2/3 is Di Renzo & Di Maio (2005). Slots: H_XI, H_T."""
    muN = p[P_MU] * N
    if N <= 0.0 or a <= 0.0:
        release(h)
        return 0.0
    kt = factor * 8.0 * p[P_GSTAR] * a
    xi = h[H_XI] + dd
    T = kt * xi
    if abs(T) > muN:
        T = cap(T, muN)
        xi = T / kt
    h[H_XI] = xi
    h[H_T] = T
    return T


@njit(inline="always", **JIT)
def spring_total(g8, mu, N, a, a_old, x, y, z, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """Total-displacement Hertz-Mindlin as a vector spring (LAMMPS ``tangential mindlin``; with
    g8 = (2/3) 8 G*: Di Renzo & Di Maio 2005): the spring displacement xi = (x, y, z) is carried into the
    plane, xi += dd, T = g8 a xi, and if |T| > mu N, T is scaled to mu N and xi = T / (g8 a).
    Returns (T, new xi, work increment 0.5 (T_old + T) . dd)."""
    if N <= 0.0 or a <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    x, y, z = carry(x, y, z, nx, ny, nz, cs, sn)
    w_old = g8 * a_old * (x * ddx + y * ddy + z * ddz)
    kt = g8 * a
    x += ddx
    y += ddy
    z += ddz
    tx, ty, tz, slip = cap_vector(kt * x, kt * y, kt * z, mu * N)
    if slip:
        x = tx / kt
        y = ty / kt
        z = tz / kt
    return tx, ty, tz, x, y, z, 0.5 * (w_old + tx * ddx + ty * ddy + tz * ddz)


def _vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """One 3D step: ``spring_total`` on the slots of the row, with the global FACTOR bound by ``forms``.
    Returns T (tx, ty, tz)."""
    a_old = at(H, c, V_A)
    g8 = 8.0 * params[row, P_GSTAR]
    if FACTOR != 1.0:
        g8 *= FACTOR
    tx, ty, tz, x, y, z, dw = spring_total(g8, params[row, P_MU], N, a, a_old, at(H, c, b + W_X), at(H, c, b + W_Y),
                                           at(H, c, b + W_Z), nx, ny, nz, ddx, ddy, ddz, cs, sn)
    put(H, c, b + W_WORK, at(H, c, b + W_WORK) + dw)
    put(H, c, b + W_X, x)
    put(H, c, b + W_Y, y)
    put(H, c, b + W_Z, z)
    return tx, ty, tz


def _planar(p, h, N, dN, a, a_old, dd):
    return total(p, h, N, a, dd, FACTOR)


def forms(name, factor):
    """(planar, vector) kernels of the law with the stiffness ``factor`` (this law or its variant)."""
    return (njit(inline="always", cache=True)(renamed(_planar, f"planar_{name}", FACTOR=factor)),
            njit(inline="always", **JIT)(renamed(_vector, f"vector_{name}", FACTOR=factor)))


_FORMS = forms(NAME, FACTOR)
planar = _FORMS[0]
"""The planar kernel, ``planar(p, h, N, dN, a, a_old, dd) -> T`` (``total`` with FACTOR = 1)."""
vector = _FORMS[1]
"""The 3D kernel, ``vector(params, row, H, c, b, N, a, F*, n, dd, cos, sin) -> T``."""
