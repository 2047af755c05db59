"""Incremental Hertz-Mindlin force with a / a_old rescaling (LAMMPS granular `mindlin_rescale/force`): T is
first scaled by a / a_old when the contact shrinks, then T += 8 G* a dd, capped at mu N."""
from . import mindlin_incremental
from .mindlin_incremental import PARAMETERS, STATE, SWAP_NEGATE, VECTOR_SLOTS  # noqa: F401

NAME, FAMILY = "mindlin_rescale", "tangential"
SOURCE = "incremental Hertz-Mindlin with a/a_old rescaling (LAMMPS mindlin_rescale/force)"
planar, vector = mindlin_incremental.forms(NAME, True, False)
