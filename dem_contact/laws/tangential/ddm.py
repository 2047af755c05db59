"""Di Renzo & Di Maio (2005): the total-displacement spring of ``mindlin_total`` with k_t = (2/3) 8 G* a."""
from numba import njit

from ..vector import JIT
from .mindlin_total import (CELLS, OPTIONS, PARAMETERS, STATE, SWAP_NEGATE, VECTOR_SLOTS, configure,  # noqa: F401
                            describe, total, total_vector)

NAME = "ddm"
FAMILY = "tangential"
SOURCE = "Di Renzo & Di Maio (2005): total displacement, k_t = (2/3) 8 G* a"
FACTOR = 2.0 / 3.0


@njit(inline="always", cache=True)
def planar(p, h, N, dN, a, a_old, dd):
    return total(p, h, N, a, dd, FACTOR)


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    return total_vector(params, row, H, c, b, N, a, nx, ny, nz, ddx, ddy, ddz, cs, sn, FACTOR)
