"""One planar contact evaluation: the normal law, then the tangential law, chosen by integer ids (the places
of the laws in ``laws.table``; the switch on them is ``laws.dispatch``)."""
from numba import njit

from .dispatch import normal_force, normal_gap, tangential_force  # noqa: F401  (the planar entries)
from .slots import H_A, H_N


@njit(inline="always", cache=True)
def contact_step(nid, tid, p, h, delta, vel, dd):
    """Advance one contact by one step to overlap ``delta`` [m] (rate ``vel`` [m/s]) with tangential
    displacement increment ``dd`` [m]. Returns (N, a, T); N is the law's force (tension only for the
    linear law), the tangential law sees max(N, 0). Writes H_N, H_A and the law's own slots."""
    N, a = normal_force(nid, p, h, delta, vel)
    Np = N if N > 0.0 else 0.0
    T = tangential_force(tid, p, h, Np, Np - h[H_N], a, h[H_A], dd)
    h[H_N] = Np
    h[H_A] = a
    return N, a, T
