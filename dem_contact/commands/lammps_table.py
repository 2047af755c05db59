"""``dem-contact lammps-table``: write the table file of ``pair_style dem/contact`` (``pair_coeff * * FILE``)."""
from __future__ import annotations

ORDER = 80
HELP = "write the table file of the LAMMPS plugin (pair_coeff * * FILE)"
DESCRIPTION = ("Write the parameter table of a LAMMPS run with pair_style dem/contact: one row per pair of atom "
               "types, from their materials and radii, the friction coefficient and the laws (JSON, for "
               "`pair_coeff * * FILE`). Atom type k is the k-th --sphere. The atoms' masses must be their "
               "type's density times their volume (LAMMPS's `set type k density RHO`); laws whose parameters "
               "depend on the sizes through R* and m* only take atoms of any radius. All quantities SI.")


def add_options(p):
    from .common import add_torque_options, law_options
    from ..laws.model import NORMAL_LAWS, TANGENTIAL_LAWS

    p.add_argument("--out", required=True, help="the table file to write (.json)")
    p.add_argument("--sphere", nargs=4, action="append", required=True, metavar=("RADIUS", "E", "NU", "RHO"),
                   help="an atom type: radius [m], Young's modulus [Pa], Poisson ratio, density [kg/m^3] "
                        "(repeat for types 1, 2, ...)")
    p.add_argument("--wall", nargs="+", action="append", default=[], metavar="E NU [CURVATURE]",
                   help="a wall material for fix dem/contact/wall: Young's modulus [Pa], Poisson ratio, and the "
                        "curvature 1/R2 [1/m] of its contacts (default 0, flat; a cylinder of radius RC: -1/(2 RC) "
                        "inside, 1/(2 RC) outside); the fix's `wall W` is the W-th, from 0 (repeat for more)")
    p.add_argument("--mu", type=float, default=0.5, help="friction coefficient of every pair (default 0.5)")
    p.add_argument("--normal", choices=list(NORMAL_LAWS), default="hertz", help="normal law (default hertz)")
    p.add_argument("--tangential", choices=list(TANGENTIAL_LAWS), default=None,
                   help="tangential law (default: the library's default)")
    p.add_argument("--v-ref", type=float, default=None,
                   help="reference normal speed [m/s] of the calibrations and the mdr springs (default: the laws')")
    for flag, kwargs in law_options("normal", "tangential"):
        if flag != "--v-ref":
            p.add_argument(flag, **kwargs)
    add_torque_options(p)


def run(args) -> int:
    from .common import check_output_file, dest, law_options, torque_laws
    from ..dem.pairs import pair_table
    from ..errors import InputError
    from ..lammps import table_file
    from ..materials import Material, Sphere, Wall

    check_output_file("--out", args.out, (".json",))
    spheres = []
    for k, words in enumerate(args.sphere, start=1):
        try:
            radius, E, nu, rho = (float(w) for w in words)
        except ValueError:
            raise InputError(f"--sphere (type {k}): RADIUS E NU RHO must be numbers, got {' '.join(words)}") from None
        try:
            spheres.append(Sphere(radius, Material(E=E, nu=nu, rho=rho)))
        except InputError as e:
            raise InputError(f"--sphere (type {k}): {e}") from None
    options = {dest(flag): getattr(args, dest(flag)) for flag, _ in law_options("normal", "tangential")
               if flag != "--v-ref" and getattr(args, dest(flag), None) is not None}
    laws = dict(normal=args.normal, v_ref=args.v_ref, **options, **torque_laws(args))
    if args.tangential is not None:
        laws["tangential"] = args.tangential
    walls = []
    for k, words in enumerate(args.wall):
        try:
            if len(words) not in (2, 3):
                raise ValueError
            E, nu, *curvature = (float(w) for w in words)
        except ValueError:
            raise InputError(f"--wall (wall {k}): E NU [CURVATURE] must be two or three numbers, got "
                             f"{' '.join(words)}") from None
        try:
            # (a wall's density does not enter its contacts: 1/m2 = 0)
            walls.append(Wall(Material(E=E, nu=nu, rho=1.0), curvature=curvature[0] if curvature else 0.0))
        except InputError as e:
            raise InputError(f"--wall (wall {k}): {e}") from None
    table = pair_table(spheres, walls, mu=args.mu, **laws)
    path = table_file.save(table, args.out)
    print(f"{path}: {len(spheres)} atom type(s), {len(walls)} wall(s), {len(table.params)} rows, "
          f"{table_file.load(path).laws}; in the input script: pair_coeff * * {path}")
    return 0
