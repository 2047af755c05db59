"""dem_contact's contact laws inside LAMMPS (optional extra ``lammps``), two ways:

- ``pair_style dem/contact``, a LAMMPS plugin for input scripts (``plugin_build``: its build; ``table_file``:
  the table file of ``pair_coeff``; ``pair_kernel`` and ``wall_kernel``: the steps it calls; ``aot``: the plugin
  with those steps compiled ahead of time, for an lmp with no Python; the C++ sources in ``plugin/``);
- ``LammpsContacts``, which adds the forces and torques of any normal x tangential law to a LAMMPS run through
  ``fix external``, on one or many MPI ranks, with walls. See ``bridge`` for the set-up and ``kernels`` for
  the per-step work; the walls are those of ``dem_contact.walls`` (``PlaneWall`` is re-exported here);
  ``session`` makes the LAMMPS instances and reduces over their ranks.

Both take the terms of one contact (its law's inputs, its parameter row for atoms of other sizes, its load on a
wall) from ``contact_terms``."""
from ..walls import PlaneWall
from .bridge import MIN_STEPS_PER_CONTACT, Census, LammpsContacts
from .session import lammps_module, lammps_warnings, library_path, new_lammps
from .native import native_commands

__all__ = ["Census", "LammpsContacts", "MIN_STEPS_PER_CONTACT", "PlaneWall", "lammps_module", "lammps_warnings",
           "library_path", "native_commands", "new_lammps"]
