import math

import pytest

import dem_contact as dc


@pytest.fixture(scope="session")
def steel_sphere():
    return dc.Sphere(0.01, dc.STEEL)


@pytest.fixture(scope="session")
def steel_wall():
    return dc.Wall(dc.STEEL)


def vt_for_Theta(Theta, mu, vn, e_n=1.0):
    """Tangential speed giving Theta = 2 vt / ((1 + e_n) mu vn) (no spin)."""
    return Theta * (1.0 + e_n) * mu * vn / 2.0


def angle_vt(vn, deg):
    return vn * math.tan(math.radians(deg))
