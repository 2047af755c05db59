"""dem_contact: validated, fast contact laws for spheres (Hertz, Thornton, Mindlin-Deresiewicz) and
the oblique sphere-wall impact they govern."""
from . import kernel_cache  # noqa: F401  (first: numba's cache locators for the package's kernels)
from .errors import InputError, NumericalError
from .impacts.impact import DEFAULT_STEPS_PER_CONTACT, EnergyBudget, ImpactResult, impact
from .materials import STEEL, Material, PairProperties, Sphere, Wall, pair_properties
from .laws.model import NORMAL_LAWS, TANGENTIAL_LAWS, Scene, reference_speed

from .version import __version__

__all__ = [
    "DEFAULT_STEPS_PER_CONTACT", "EnergyBudget", "ImpactResult", "InputError", "Material",
    "NORMAL_LAWS", "NumericalError", "PairProperties", "STEEL", "Scene", "Sphere", "TANGENTIAL_LAWS",
    "Wall", "impact", "pair_properties", "reference_speed",
]
