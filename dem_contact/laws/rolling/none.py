"""No rolling resistance: the relative rolling of the bodies carries no torque (the contact laws of Hertz,
Mindlin and Deresiewicz treat a point contact)."""
from ..twist.none import EXAMPLE, PARAMETERS, STATE, VECTOR_SLOTS, lammps_keywords, max_torque, vector  # noqa: F401  (no torque: the same kernel)

NAME, FAMILY = "none", "rolling"
SOURCE = "no torque across the normal"
