"""Thornton & Yin's incremental Mindlin-Deresiewicz (``md``) with the variant of Thornton, Cummins & Cleary
(2013): when the contact shrinks, T, T* and T** are first scaled by a / a_old."""
from . import md
from .md import PARAMETERS, STATE, SWAP_NEGATE, VECTOR_SLOTS  # noqa: F401

NAME, FAMILY = "md_rescale", "tangential"
SOURCE = "md with a_new/a_old scaling when the contact shrinks (Thornton, Cummins & Cleary 2013)"
planar, vector = md.forms(NAME, True)
