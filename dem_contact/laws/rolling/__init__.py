"""Rolling laws: a torque across the normal from the relative rolling of the bodies; one file each (see
``laws.table`` for what a law file declares)."""
