"""The 3D contact step by tangential law id, generated from ``laws.table`` by
``python -m dem_contact.laws.generate``: do not edit."""
from numba import njit

from .compose import LEAVES
from .vector import JIT

(_0, _1, _2, _3, _4, _5, _6, _7, _8,) = LEAVES


@njit(inline="always", **JIT)
def contact_leaf(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt):
    """``compose.LEAVES[tid]`` (tid assumed valid)."""
    return _0(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 0 else _1(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 1 else _2(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 2 else _3(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 3 else _4(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 4 else _5(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 5 else _6(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 6 else _7(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt) if tid == 7 else _8(nid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wx, wy, wz, wn, dt)
