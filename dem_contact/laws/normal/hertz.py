"""Hertz elastic contact (Johnson 1985, Contact Mechanics, eq. 4.23): a = sqrt(R* delta), N = (4/3) E* a delta."""
import math

from numba import njit

from .. import closed_forms as cf
from ..declare import ESTAR, RSTAR
from ..slots import P_ESTAR, P_RSTAR
from ..vector import JIT

NAME, FAMILY = "hertz", "normal"
SOURCE = "Hertz (Johnson 1985), elastic"
PARAMETERS, STATE = (ESTAR, RSTAR), ()
USES_RATE, PLASTIC = False, False
#: LAMMPS's equivalent normal model (``pair granular``; see ``lammps.native``)
LAMMPS = "hertz/material"


def contact_time(scene, vn):
    """Hertz's elastic contact time at normal speed vn [s] (Johnson 1985, section 11.4)."""
    pr = scene.pair
    return cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, vn)


@njit(inline="always", cache=True)
def hertz_vector(E, R, delta):
    """Hertz (Johnson 1985, eq. 4.23) on scalars: a = sqrt(R delta), N = (4/3) E a delta. Returns (N, a).
    Every kernel's Hertz force (this law, hertz_damped, thornton's elastic branches) is this one,
    inlined into each kernel."""
    if delta <= 0.0:
        return 0.0, 0.0
    a = math.sqrt(R * delta)
    return 4.0 / 3.0 * E * a * delta, a


@njit(inline="always", cache=True)
def hertz(p, delta):
    """``hertz_vector`` with E* and R* of the planar parameter row."""
    return hertz_vector(p[P_ESTAR], p[P_RSTAR], delta)


@njit(inline="always", cache=True)
def planar(p, h, delta, vel):
    return hertz(p, delta)


@njit(inline="always", cache=True)
def gap(p, h, delta, vel):
    return delta


@njit(inline="always", **JIT)
def vector(params, row, H, c, delta, vel):
    """The 3D form: (N, a) and no state."""
    N, a = hertz_vector(params[row, P_ESTAR], params[row, P_RSTAR], delta)
    return N, a, 0.0, 0.0, 0.0, 0.0, 0.0
