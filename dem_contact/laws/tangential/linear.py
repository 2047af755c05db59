"""Cundall & Strack (1979) linear tangential spring: T += k_t dd, capped at mu N, with a constant
k_t = kappa k_n, k_n matched to the Hertz contact time at v_ref (``normal.linear.linear_stiffness``)."""
from numba import njit

from ..slots import P_KN, P_KT
from ..vector import JIT
from ..normal.linear import linear_stiffness
from .mindlin_incremental import SWAP_NEGATE, VECTOR_SLOTS, incremental, incremental_vector  # noqa: F401

NAME = "linear"
FAMILY = "tangential"
SOURCE = "Cundall-Strack linear spring, k_t = kappa k_n(linear, matched at v_ref)"
PARAMETERS = ("k_t", "mu")
STATE = ("T",)
OPTIONS = ()
CELLS = False


def configure(scene, p):
    linear_stiffness(scene, p, "the linear tangential law")


def describe(scene, p):
    return dict(k_n_linear=p[P_KN], k_t_linear=p[P_KT], v_ref=scene.v_ref)


@njit(inline="always", cache=True)
def planar(p, h, N, dN, a, a_old, dd):
    return incremental(p, h, N, a, a, dd, False, p[P_KT])


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    return incremental_vector(params, row, H, c, b, N, a, nx, ny, nz, ddx, ddy, ddz, cs, sn, False, True)
