"""Walls: one module per kind of wall behind one contract (``contract``: the distance and the normal at the
contact point, the wall's velocity there from its rigid motion, its curvature for R*, a history key per
wall and patch), and one table of kinds (``table``: the kind ids, the packing of a list of walls into the
rows the kernels read, and the dispatch of the kernels on the kind). Used by the LAMMPS plugin's wall step
(``lammps.wall_kernel``), ``Census`` (``lammps.census``) and the 3D batch face (``dem.walls``). Kinds:
``plane`` (``PlaneWall``), ``cylinder`` (``CylinderWall``), ``mesh`` (``MeshWall``, from STL files: ``stl``);
the user class of every kind of the table is exported here. Uses ``errors`` only."""
from .stl import read_stl, write_stl
from .table import CLASSES, KINDS, ROW_SIZE, pack

globals().update({c.__name__: c for c in CLASSES})
__all__ = ["KINDS", "ROW_SIZE", "pack", "read_stl", "write_stl", *(c.__name__ for c in CLASSES)]
