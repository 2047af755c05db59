"""Cundall & Strack (1979) linear tangential spring: T += k_t dd, capped at mu N, with a constant
k_t = kappa k_n, k_n matched to the Hertz contact time at v_ref (``normal.linear.linear_stiffness``)."""
from ..declare import MU, V_REF
from ..normal.linear import KN, KT, linear_stiffness
from ..slots import P_KN, P_KT
from . import mindlin_incremental
from .mindlin_incremental import SWAP_NEGATE, VECTOR_SLOTS  # noqa: F401

NAME, FAMILY = "linear", "tangential"
SOURCE = "Cundall-Strack linear spring, k_t = kappa k_n(linear, matched at v_ref)"
PARAMETERS, STATE = (KT, KN, MU), ("T",)
OPTIONS = (V_REF,)
planar, vector = mindlin_incremental.forms("linear_tangential", False, True)


def lammps_k_t(p):
    """The stiffness of LAMMPS's ``tangential linear_history`` equivalent: k_t [N/m]."""
    return p[P_KT]


def configure(scene, p):
    linear_stiffness(scene, p, "the linear tangential law")


def describe(scene, p):
    return dict(k_n_linear=p[P_KN], k_t_linear=p[P_KT], v_ref=scene.v_ref)
