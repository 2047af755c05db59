"""Walls: one module per kind of wall behind one contract (``contract``: the signed distance and the normal
at the contact point, the wall's velocity there, its curvature for R*, a history key per wall and element),
and one table of kinds (``table``: the kind ids, the packing of a list of walls into the rows the kernels
read, and the dispatch of the kernels on the kind). Used by the LAMMPS bridge (``lammps``) and the 3D batch
face (``dem.walls``). Kinds today: ``plane`` (``PlaneWall``). Uses ``errors`` only."""
from .plane import PlaneWall
from .table import KINDS, ROW_SIZE, pack

__all__ = ["KINDS", "PlaneWall", "ROW_SIZE", "pack"]
