"""Di Renzo & Di Maio (2005): the total-displacement spring of ``mindlin_total`` with k_t = (2/3) 8 G* a."""
from . import mindlin_total
from .mindlin_total import PARAMETERS, STATE, SWAP_NEGATE, VECTOR_SLOTS  # noqa: F401

NAME, FAMILY = "ddm", "tangential"
SOURCE = "Di Renzo & Di Maio (2005): total displacement, k_t = (2/3) 8 G* a"
planar, vector = mindlin_total.forms(NAME, 2.0 / 3.0)
