"""The 3D contact step by tangential law id, generated from ``laws.table`` by
``python -m dem_contact.laws.generate``: do not edit."""
from numba import njit

from .compose import LEAVES
from .vector import JIT

(_0, _1, _2, _3, _4, _5, _6, _7, _8,) = LEAVES


@njit(inline="always", **JIT)
def contact_leaf(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    """``compose.LEAVES[tid]`` (tid assumed valid)."""
    if tid == 0:
        return _0(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 1:
        return _1(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 2:
        return _2(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 3:
        return _3(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 4:
        return _4(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 5:
        return _5(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 6:
        return _6(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    if tid == 7:
        return _7(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
    return _8(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)
