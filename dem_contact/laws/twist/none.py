"""No twisting resistance: the relative spin of the bodies about the normal carries no torque (the contact
laws of Hertz, Mindlin and Deresiewicz treat a point contact)."""
from numba import njit

from ..vector import JIT

NAME, FAMILY = "none", "twist"
SOURCE = "no torque about the normal"
PARAMETERS, STATE = (), ()
VECTOR_SLOTS = 0
#: the Scene settings of a typical contact of this law (the contract tests use them)
EXAMPLE = {}


def lammps_keywords(p):
    """The keywords of LAMMPS's equivalent model on the parameter row p (``pair granular``): none."""
    return ""


def max_torque(p, N, a):
    """The largest torque [N m] of the law on a parameter row p at normal force N [N], contact radius a [m]."""
    return 0.0


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    """Torque on body 1 (x, y, z) [N m] from the relative spin w = w1 - w2 [rad/s]: none."""
    return 0.0, 0.0, 0.0
