"""Incremental Hertz-Mindlin force (Mindlin 1949; Yade, LAMMPS granular `mindlin/force`): T += 8 G* a dd,
capped at mu N. In 3D T is a vector of the tangent plane, carried into the current plane each step
(LAMMPS's arithmetic)."""
from numba import njit

from ..declare import GSTAR, MU
from ..slots import H_T, P_GSTAR, P_KT, P_MU
from ..vector import JIT, V_A, W_WORK, W_X, W_Y, W_Z, cap_vector, carry, renamed
from .common import cap, release

NAME, FAMILY = "mindlin_incremental", "tangential"
SOURCE = "incremental Hertz-Mindlin force (Yade, LAMMPS mindlin/force)"
PARAMETERS, STATE = (GSTAR, MU), ("T",)
#: scale T by a / a_old when the contact shrinks
RESCALE = False
#: k_t the constant parameter of the linear law (its variant in tangential/linear.py)
CONSTANT = False
#: fixed 3D slots (the work and the force T); swapping the bodies negates T
VECTOR_SLOTS = 4
SWAP_NEGATE = (W_X, W_Y, W_Z)


@njit(cache=True)
def incremental(p, h, N, a, a_old, dd, rescale, kt):
    """Incremental force laws (Mindlin 1949; Di Renzo & Di Maio 2004): T += kt dd, capped at mu N.
    Yade / LAMMPS `mindlin/force` (kt = 8 G* a); with ``rescale`` LAMMPS `mindlin_rescale/force` first
    scales T by a / a_old when the contact shrinks; Cundall-Strack linear spring (constant kt). Slot: H_T."""
    if N <= 0.0 or a <= 0.0:
        release(h)
        return 0.0
    T = h[H_T]
    if rescale and a < a_old:
        T *= a / a_old
    T = cap(T + kt * dd, p[P_MU] * N)
    h[H_T] = T
    return T


@njit(inline="always", **JIT)
def spring_incremental(kt, mu, N, a, a_old, x, y, z, nx, ny, nz, ddx, ddy, ddz, cs, sn, rescale):
    """Incremental force law as a vector spring (LAMMPS ``mindlin/force``, ``mindlin_rescale/force``;
    Cundall & Strack's linear spring with a constant kt): T = (x, y, z) carried into the plane, scaled by
    a / a_old when the contact shrinks (rescale), T += kt dd, scaled back to mu N if longer.
    Returns (T, work increment)."""
    if N <= 0.0 or a <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    x, y, z = carry(x, y, z, nx, ny, nz, cs, sn)
    if rescale and a < a_old:
        r = a / a_old
        x *= r
        y *= r
        z *= r
    w_old = x * ddx + y * ddy + z * ddz
    tx, ty, tz, slip = cap_vector(x + kt * ddx, y + kt * ddy, z + kt * ddz, mu * N)
    return tx, ty, tz, 0.5 * (w_old + tx * ddx + ty * ddy + tz * ddz)


def _vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """One 3D step: ``spring_incremental`` on the slots of the row, with k_t = 8 G* a or (the global
    CONSTANT) the parameter k_t of the linear law, and the global RESCALE (both bound by ``forms``).
    Returns T (tx, ty, tz)."""
    a_old = H[c, V_A]
    if CONSTANT:
        kt = params[row, P_KT]
        a_old = a
    else:
        kt = 8.0 * params[row, P_GSTAR] * a
    tx, ty, tz, dw = spring_incremental(kt, params[row, P_MU], N, a, a_old, H[c, b + W_X], H[c, b + W_Y],
                                        H[c, b + W_Z], nx, ny, nz, ddx, ddy, ddz, cs, sn, RESCALE)
    H[c, b + W_WORK] += dw
    H[c, b + W_X] = tx
    H[c, b + W_Y] = ty
    H[c, b + W_Z] = tz
    return tx, ty, tz


def _planar(p, h, N, dN, a, a_old, dd):
    if CONSTANT:
        return incremental(p, h, N, a, a, dd, False, p[P_KT])
    return incremental(p, h, N, a, a_old, dd, RESCALE, 8.0 * p[P_GSTAR] * a)


def forms(name, rescale, constant):
    """(planar, vector) kernels of the law with ``rescale`` or (``constant``) the linear law's constant k_t."""
    return (njit(inline="always", cache=True)(renamed(_planar, f"planar_{name}", RESCALE=rescale, CONSTANT=constant)),
            njit(inline="always", **JIT)(renamed(_vector, f"vector_{name}", RESCALE=rescale, CONSTANT=constant)))


_FORMS = forms(NAME, RESCALE, False)
planar = _FORMS[0]
"""The planar kernel, ``planar(p, h, N, dN, a, a_old, dd) -> T`` (``incremental`` with k_t = 8 G* a)."""
vector = _FORMS[1]
"""The 3D kernel, ``vector(params, row, H, c, b, N, a, F*, n, dd, cos, sin) -> T``."""
