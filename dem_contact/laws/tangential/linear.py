"""Cundall & Strack (1979) linear tangential spring: T += k_t dd, capped at mu N, with a constant
k_t = kappa k_n, k_n matched to the Hertz contact time at v_ref (``normal.linear.linear_stiffness``)."""
from ..normal.linear import linear_stiffness
from ..slots import P_KN, P_KT
from . import mindlin_incremental
from .mindlin_incremental import SWAP_NEGATE, VECTOR_SLOTS  # noqa: F401

NAME, FAMILY = "linear", "tangential"
SOURCE = "Cundall-Strack linear spring, k_t = kappa k_n(linear, matched at v_ref)"
PARAMETERS, STATE = ("k_t", "mu"), ("T",)
OPTIONS = ("v_ref",)
planar, vector = mindlin_incremental.forms("linear_tangential", False, True)


def configure(scene, p):
    linear_stiffness(scene, p, "the linear tangential law")


def describe(scene, p):
    return dict(k_n_linear=p[P_KN], k_t_linear=p[P_KT], v_ref=scene.v_ref)
