"""Thornton & Yin's incremental Mindlin-Deresiewicz (``md``) with the variant of Thornton, Cummins & Cleary
(2013): when the contact shrinks, T, T* and T** are first scaled by a / a_old."""
from numba import njit

from ..vector import JIT
from .md import CELLS, OPTIONS, PARAMETERS, STATE, SWAP_NEGATE, VECTOR_SLOTS, configure, describe, md, md_vector  # noqa: F401

NAME = "md_rescale"
FAMILY = "tangential"
SOURCE = "md with a_new/a_old scaling when the contact shrinks (Thornton, Cummins & Cleary 2013)"
RESCALE = True


@njit(inline="always", cache=True)
def planar(p, h, N, dN, a, a_old, dd):
    return md(p, h, N, dN, a, a_old, dd, RESCALE)


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    return md_vector(params, row, H, c, b, N, a, nx, ny, nz, ddx, ddy, ddz, cs, sn, RESCALE)
