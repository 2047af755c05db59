"""Law dispatch by id, generated from ``laws.table`` by ``python -m dem_contact.laws.generate``: do not
edit (a test fails when it is out of date). The ids are the places of the laws in ``table.FAMILIES``."""
from numba import njit

from .normal import hertz as n0
from .normal import thornton as n1
from .normal import hertz_damped as n2
from .normal import linear as n3
from .tangential import md as t0
from .tangential import md_rescale as t1
from .tangential import mindlin_total as t2
from .tangential import mindlin_incremental as t3
from .tangential import mindlin_rescale as t4
from .tangential import linear as t5
from .tangential import ddm as t6
from .tangential import mdr as t7
from .tangential import mdr_adaptive as t8
from .twist import none as q0
from .twist import marshall as q1
from .twist import sds as q2
from .twist import deresiewicz as q3
from .rolling import none as r0
from .rolling import sds as r1

NORMAL_NAMES = ('hertz', 'thornton', 'hertz_damped', 'linear',)
NORMAL_IDS = tuple(range(4))
TANGENTIAL_NAMES = ('md', 'md_rescale', 'mindlin_total', 'mindlin_incremental', 'mindlin_rescale', 'linear', 'ddm', 'mdr', 'mdr_adaptive',)
TANGENTIAL_IDS = tuple(range(9))
TWIST_NAMES = ('none', 'marshall', 'sds', 'deresiewicz',)
TWIST_IDS = tuple(range(4))
ROLLING_NAMES = ('none', 'sds',)
ROLLING_IDS = tuple(range(2))


@njit(inline="always", cache=True)
def normal_force(nid, p, h, delta, vel):
    return n0.planar(p, h, delta, vel) if nid == 0 else n1.planar(p, h, delta, vel) if nid == 1 else n2.planar(p, h, delta, vel) if nid == 2 else n3.planar(p, h, delta, vel)


@njit(inline="always", cache=True)
def normal_gap(nid, p, h, delta, vel):
    return n0.gap(p, h, delta, vel) if nid == 0 else n1.gap(p, h, delta, vel) if nid == 1 else n2.gap(p, h, delta, vel) if nid == 2 else n3.gap(p, h, delta, vel)


@njit(inline="always", cache=True)
def tangential_force(tid, p, h, N, dN, a, a_old, dd):
    return t0.planar(p, h, N, dN, a, a_old, dd) if tid == 0 else t1.planar(p, h, N, dN, a, a_old, dd) if tid == 1 else t2.planar(p, h, N, dN, a, a_old, dd) if tid == 2 else t3.planar(p, h, N, dN, a, a_old, dd) if tid == 3 else t4.planar(p, h, N, dN, a, a_old, dd) if tid == 4 else t5.planar(p, h, N, dN, a, a_old, dd) if tid == 5 else t6.planar(p, h, N, dN, a, a_old, dd) if tid == 6 else t7.planar(p, h, N, dN, a, a_old, dd) if tid == 7 else t8.planar(p, h, N, dN, a, a_old, dd)


@njit(inline="always", cache=True)
def normal_vector(nid, params, row, H, c, delta, vel):
    return n0.vector(params, row, H, c, delta, vel) if nid == 0 else n1.vector(params, row, H, c, delta, vel) if nid == 1 else n2.vector(params, row, H, c, delta, vel) if nid == 2 else n3.vector(params, row, H, c, delta, vel)


@njit(inline="always", cache=True)
def twist_torque(lid, params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    return q1.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt) if lid == 1 else q2.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt) if lid == 2 else q3.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt) if lid == 3 else q0.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt)


@njit(inline="always", cache=True)
def rolling_torque(lid, params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    return r1.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt) if lid == 1 else r0.vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt)


@njit(inline="always", cache=True)
def uses_rate(nid):
    """Whether the normal law's force depends on the overlap rate (``USES_RATE``)."""
    return nid == 2 or nid == 3


@njit(inline="always", cache=True)
def twist_base(nid):
    """First slot of the twist law's state in a 3D history row: after the normal law's state."""
    if nid == 1:
        return 7
    return 2


@njit(inline="always", cache=True)
def rolling_base(nid, qid):
    """First slot after the twist law's state (``laws.table``: the layout of a 3D row)."""
    return twist_base(nid) + (1 if qid == 1 else 1 if qid == 2 else 35 if qid == 3 else 0)


@njit(inline="always", cache=True)
def tangential_base(nid, qid, rid):
    """First slot after the rolling law's state (``laws.table``: the layout of a 3D row)."""
    return rolling_base(nid, qid) + (3 if rid == 1 else 0)


@njit(inline="always", cache=True)
def store_normal(nid, H, c, s0, s1, s2, s3, s4, N, tx, ty, tz):
    """The normal law's ``store`` (laws with a 3D state)."""
    if nid == 1:
        n1.store(H, c, s0, s1, s2, s3, s4, N, tx, ty, tz)
