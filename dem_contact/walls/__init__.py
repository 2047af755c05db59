"""Walls: one module per kind of wall behind one contract (``contract``: the distance and the normal at the
contact point, the wall's velocity there from its rigid motion, its curvature for R*, a history key per
wall and patch), and one table of kinds (``table``: the kind ids, the packing of a list of walls into the
rows the kernels read, and the dispatch of the kernels on the kind). Used by the LAMMPS bridge
(``lammps``) and the 3D batch face (``dem.walls``). Kinds: ``plane`` (``PlaneWall``), ``cylinder``
(``CylinderWall``), ``mesh`` (``MeshWall``, from STL files: ``stl``). Uses ``errors`` only."""
from .cylinder import CylinderWall
from .mesh import MeshWall
from .plane import PlaneWall
from .stl import read_stl, write_stl
from .table import KINDS, ROW_SIZE, pack

__all__ = ["KINDS", "CylinderWall", "MeshWall", "PlaneWall", "ROW_SIZE", "pack", "read_stl", "write_stl"]
