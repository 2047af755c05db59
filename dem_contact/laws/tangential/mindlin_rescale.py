"""Incremental Hertz-Mindlin force with a / a_old rescaling (LAMMPS granular `mindlin_rescale/force`): T is
first scaled by a / a_old when the contact shrinks, then T += 8 G* a dd, capped at mu N."""
from numba import njit

from ..slots import P_GSTAR
from ..vector import JIT
from .mindlin_incremental import (CELLS, OPTIONS, PARAMETERS, STATE, SWAP_NEGATE, VECTOR_SLOTS,  # noqa: F401
                                  configure, describe, incremental, incremental_vector)

NAME = "mindlin_rescale"
FAMILY = "tangential"
SOURCE = "incremental Hertz-Mindlin with a/a_old rescaling (LAMMPS mindlin_rescale/force)"
RESCALE = True


@njit(inline="always", cache=True)
def planar(p, h, N, dN, a, a_old, dd):
    return incremental(p, h, N, a, a_old, dd, RESCALE, 8.0 * p[P_GSTAR] * a)


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    return incremental_vector(params, row, H, c, b, N, a, nx, ny, nz, ddx, ddy, ddz, cs, sn, RESCALE, False)
