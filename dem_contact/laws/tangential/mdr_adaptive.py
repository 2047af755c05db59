"""Method of dimensionality reduction with few cells on a grid that follows the contact (Popov & Hess 2015,
chapter 6): the cells of ``mdr`` (n cells, n = mdr_springs, even) whose width is set at first contact and
halved or doubled as the contact shrinks or grows, so that no grid is set up and few cells suffice.
The default tangential law."""
import numpy as np
from numba import njit

from ...errors import InputError
from ..slots import H_T, H_TANG_EXTRA, P_NSPRING, P_RSTAR
from .mdr import (CONVERGED_STEPS, PARAMETERS, PROFILE, SPRINGS, SWAP_NEGATE_ADAPTIVE, SWAP_NEGATE_CELL, VECTOR_SLOTS_ADAPTIVE, _advance, _cells,  # noqa: F401
                  _merge, _release, _split, initial_width, set_profile, shrink_edge, vector_form)

NAME, FAMILY = "mdr_adaptive", "tangential"
SOURCE = "method of dimensionality reduction with few cells on a grid that follows the contact"
STATE = ("T", "cell width", "cells")
OPTIONS = (SPRINGS, PROFILE)
CELLS = True
#: planar slots before the cells: the cell width
CELL_HEADER = 1
#: Default cell count (even).
CELLS_DEFAULT = 16
#: fixed 3D slots (the sticking zone of ``mdr._vector`` included) and those negated when the bodies are swapped
VECTOR_SLOTS = VECTOR_SLOTS_ADAPTIVE
SWAP_NEGATE = SWAP_NEGATE_ADAPTIVE


def configure(scene, p):
    set_profile(scene, p)
    springs = scene.arguments["mdr_springs"]
    n = CELLS_DEFAULT if springs is None else springs
    if isinstance(n, bool) or int(n) != n or n % 2 or not 2 <= n <= 1024:
        raise InputError(f"mdr_springs = {n!r} must be an even integer in [2, 1024] for {NAME}")
    scene.mdr_springs = int(n)
    p[P_NSPRING] = int(n)


def describe(scene, p):
    return dict(mdr_profile=scene.mdr_profile)

def check_rows(params):
    """(bad rows, why) of a parameter table that this law cannot run (the checked 3D entries)."""
    cells = params[:, P_NSPRING]
    return [(~((cells >= 2) & (cells <= 10**6) & (cells == np.floor(cells))),
             f"has no MDR cell count (params[:, P_NSPRING] in [2, 1e6]), which the {NAME} law needs"),
            (cells % 2 != 0, f"has an odd MDR cell count: {NAME} needs an even one")]


@njit(inline="always", cache=True)
def adaptive(p, h, N, a, a_old, dd):
    """The planar law (module docstring).

    Same cells as ``mdr`` (n = P_NSPRING, even), but the cell width dx, stored in h[H_TANG_EXTRA], is set
    at first contact to R* times the power of 2 in (a / n, 2 a / n] (scale-free: problems with the same
    dimensionless groups get the same grid in units of R*, and the grid does not depend on the time step)
    and halved or doubled as the contact shrinks or grows, so the contact always spans between n/4 and n
    cells (n/2 to n while it grows): when a > n dx, pairs of cells merge into their length-weighted mean
    (exact for the integral of u, and cells at the Coulomb limit stay at it); when both a and
    a_old < n dx / 4, every cell splits in two halves (``_split``: mean kept, cells at the Coulomb limit
    stay at it); when the contact shrinks, the cell cut by the new edge keeps the mean of its remaining
    part (``shrink_edge``). Cell displacements: h[H_TANG_EXTRA + 1 + i].
    With n = 16, f/mu of an oblique impact is within about 1e-3 of the converged MDR value."""
    n = int(p[P_NSPRING])
    k0 = H_TANG_EXTRA + 1
    dx = h[H_TANG_EXTRA]
    if N <= 0.0 or a * a * a <= 0.0:      # (a^3 underflows at the touch overlap 1e-300 m: no contact)
        if dx > 0.0:
            _release(h, k0, max(_cells(a, dx, n), _cells(a_old, dx, n)))
        h[H_TANG_EXTRA] = 0.0
        h[H_T] = 0.0
        return 0.0
    if dx <= 0.0 or a_old <= 0.0:
        _release(h, k0, n)
        a_old = 0.0
        dx = initial_width(a, n, p[P_RSTAR])
    while a > n * dx:
        _merge(h, k0, n, dx, a_old)
        dx *= 2.0
    while 4.0 * a < n * dx and 4.0 * a_old < n * dx:
        _split(h, k0, n, dx, a_old)
        dx *= 0.5
    h[H_TANG_EXTRA] = dx
    if a < a_old:
        i, f = shrink_edge(n, dx, a, a_old)
        if i >= 0:
            h[k0 + i] *= f
    return _advance(p, h, k0, n, dx, N, a, a_old, dd)


@njit(inline="always", cache=True)
def planar(p, h, N, dN, a, a_old, dd):
    return adaptive(p, h, N, a, a_old, dd)


vector = vector_form(NAME, True)
