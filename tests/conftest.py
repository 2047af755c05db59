"""Fixtures and helpers shared by the tests of several rooms (importable as ``conftest``: the tests' folder is on
the path)."""
import math

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.dem.contact3d import history_size, new_histories
from dem_contact.laws import table
from dem_contact.laws.model import Scene, reference_speed
from dem_contact.laws.slots import P_NSPRING
from dem_contact.materials import STEEL, Material, Sphere, Wall


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


def scene_history(sc, n=1):
    """Zeroed 3D histories of ``n`` contacts for the laws of Scene ``sc``."""
    return new_histories(n, history_size(sc.normal_id, sc.tangential_id, int(sc.params[P_NSPRING]), sc.twist_id,
                                         sc.rolling_id))


def _frame(rotated):
    if not rotated:
        return np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    q, _ = np.linalg.qr(np.random.default_rng(3).normal(size=(3, 3)))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    e1, m_wall = q[:, 0], q[:, 2]
    return np.ascontiguousarray(m_wall), np.ascontiguousarray(e1), np.cross(m_wall, e1)


def _law_scene(tangential, normal="hertz"):
    """A pair for every pair of laws, with their declared EXAMPLE settings (``laws.table``: a damped law's
    target e_n, a tangential law's own coefficients); a plastic normal law yields at the material's p_y."""
    mat = Material(E=70e9, nu=0.25, rho=2700.0, yield_pressure=1.2e9)
    law = table.law("normal", normal)
    return Scene(Sphere(5e-3, mat), Wall(STEEL), mu=0.35, normal=normal, tangential=tangential,
                 v_ref=reference_speed(1.5), **({} if law.PLASTIC else law.EXAMPLE),
                 **table.law("tangential", tangential).EXAMPLE)


def _have_lammps():
    try:
        from dem_contact.lammps import lammps_module
        lammps_module()
        return True
    except ImportError:
        return False
