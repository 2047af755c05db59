"""The contract of every wall kind (``walls.contract``), over the table of kinds (``walls.table.KINDS``), on the
example wall each kind declares (``example``, with ``sample``: points covering its surface and sphere centres
near it), so that a new kind gets these tests unedited:

- the distance and the normal of ``contact`` are those of the closest point of the surface, found by brute
  force over the surface points;
- under a rigid motion (translation and rotation about a centre off the wall), ``place`` keeps the distance of
  a point carried with the wall and turns its normal with the wall, and ``contract.velocity`` at the contact
  point is the time derivative of that point of the wall;
- ``search.near_elements`` lists the same (sphere, wall, element) as a brute-force loop over ``distance``.
"""
import numpy as np
import pytest

from dem_contact.walls import contract, search
from dem_contact.walls import table as W

KINDS = [mod for _, mod in W.KINDS]
MOTION = dict(velocity=(0.3, -0.1, 0.2), angular_velocity=(0.5, 0.2, -0.4), centre=(0.2, 0.1, -0.1))


def _closest(walls, x, r=1.0):
    """(s, n) of the element of wall 0 nearest to the centre x that reports a contact: the smallest s."""
    best = (np.inf, None)
    for e in range(contract.elements(walls, 0)):
        s, nx, ny, nz = W.contact(walls, 0, e, x[0], x[1], x[2], r)
        if s < best[0]:
            best = (s, np.array([nx, ny, nz]))
    return best


def _rotation(omega, t):
    """Rot(omega t) (Rodrigues), float[3, 3]."""
    om = np.linalg.norm(omega)
    if om == 0.0:
        return np.eye(3)
    k = np.asarray(omega) / om
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(om * t) * K + (1.0 - np.cos(om * t)) * K @ K


@pytest.mark.parametrize("kind", KINDS, ids=lambda m: m.__name__.rsplit(".", 1)[1])
def test_distance_and_normal_are_those_of_the_closest_point(kind):
    rng = np.random.default_rng(1)
    wall = kind.example()
    surface, centres = kind.sample(wall, 40, rng)
    walls, _ = W.pack([wall])
    for x in centres:
        s, n = _closest(walls, x)
        d = np.linalg.norm(surface - x, axis=1)
        k = np.argmin(d)
        towards = (surface[k] - x) / d[k]
        assert abs(s - d[k]) < 2e-3 * max(d[k], 1.0), (x, s, d[k])
        assert n @ towards > 0.99, (x, n, towards)
        assert abs(np.linalg.norm(n) - 1.0) < 1e-12


@pytest.mark.parametrize("kind", KINDS, ids=lambda m: m.__name__.rsplit(".", 1)[1])
def test_rigid_motion_carries_the_surface_and_gives_its_velocity(kind):
    rng = np.random.default_rng(2)
    wall = kind.example(**MOTION)
    _, centres = kind.sample(wall, 10, rng)
    walls, _ = W.pack([wall])
    V, Om, C0 = (np.array(MOTION[k]) for k in ("velocity", "angular_velocity", "centre"))

    def carried(p, t):          # a point of the wall at time 0, where the motion takes it at time t
        return C0 + V * t + _rotation(Om, t) @ (p - C0)

    t, h = 0.37, 1e-6
    for x in centres:
        W.place_walls(walls, 0.0)
        s0, n0 = _closest(walls, x)
        W.place_walls(walls, t)
        s, n = _closest(walls, carried(x, t))
        assert abs(s - s0) < 1e-12 * max(1.0, abs(s0)) + 1e-13
        assert np.allclose(n, _rotation(Om, t) @ n0, rtol=0.0, atol=1e-12)
        c0 = x + s0 * n0
        c = carried(c0, t)
        v = np.array(contract.velocity(walls, 0, c[0], c[1], c[2]))
        assert np.allclose(v, (carried(c0, t + h) - carried(c0, t - h)) / (2.0 * h), rtol=0.0, atol=1e-8)


def test_the_wall_list_is_that_of_brute_force():
    rng = np.random.default_rng(3)
    walls, _ = W.pack([kind.example() for kind in KINDS])
    n = 300
    x = rng.uniform(-1.5, 1.5, (n, 3))
    radius = rng.uniform(0.01, 0.2, n)
    skin = 0.05
    found = {tuple(row) for row in search.near_elements(n, x, radius, walls, skin)}
    brute = {(i, w, e) for i in range(n) for w in range(contract.count(walls))
             for e in range(contract.elements(walls, w))
             if W.distance(walls, w, e, x[i, 0], x[i, 1], x[i, 2]) < radius[i] + skin}
    assert found == brute and len(brute) > 30
