"""dem_contact's contact laws inside LAMMPS (optional extra ``lammps``): ``pair_style dem/contact`` and ``fix
dem/contact/wall``, a LAMMPS plugin, for input scripts and for LAMMPS driven from Python.

- ``plugin_build``: its build; ``table_file``: the table file of ``pair_coeff``; ``mesh_file``: the packed mesh
  file of a mesh wall; ``pair_kernel`` and ``wall_kernel``: the steps it calls; ``aot``: the plugin with those
  steps compiled ahead of time, for an lmp with no Python; the C++ sources in ``plugin/``;
- ``LammpsContacts`` (``contacts``): its Python face, which writes those files and issues those commands for a
  ``PairTable`` and a list of walls of ``dem_contact.walls`` (``PlaneWall`` is re-exported here), and reads back
  the contacts, the wall loads and the counts;
- ``Census`` (``census``): the contacts of a run with any pair style, from the positions;
- ``native``: LAMMPS's own granular commands for a table, where they compute the same;
- ``session`` makes the LAMMPS instances and reduces over their ranks.

The steps take the terms of one contact (its law's inputs, its parameter row for atoms of other sizes, its load
on a wall) from ``contact_terms``."""
from ..walls import PlaneWall
from .census import Census
from .contacts import LammpsContacts
from .session import lammps_module, lammps_warnings, library_path, new_lammps
from .native import native_commands

__all__ = ["Census", "LammpsContacts", "PlaneWall", "lammps_module", "lammps_warnings", "library_path",
           "native_commands", "new_lammps"]
