"""Twist laws: a torque about the normal from the relative spin of the bodies about it; one file each (see
``laws.table`` for what a law file declares)."""
