"""``dem-contact lammps-mesh``: write the packed mesh file of ``fix dem/contact/wall ... mesh FILE``."""
from __future__ import annotations

ORDER = 82
HELP = "write a packed mesh file for fix dem/contact/wall (from an STL file)"
DESCRIPTION = ("Read an STL file (ASCII or binary) and write the mesh wall as dem_contact's walls room packs it "
               "(the conforming triangles, their neighbours, flat patches and history keys) to a packed mesh file, "
               "for `fix ID GROUP dem/contact/wall mesh FILE ...`. The plugin compiled ahead of time (lammps-plugin "
               "--ahead-of-time), which runs no Python, reads meshes only so; the plugin that reaches dem_contact "
               "through Python reads either file. The wall's material and motion are the fix's words, not the "
               "file's. Coordinates in metres (after --scale).")


def add_options(p):
    p.add_argument("stl", metavar="STL", help="the STL file of the mesh")
    p.add_argument("--out", required=True, help="the packed mesh file to write (.mesh)")
    p.add_argument("--scale", type=float, default=1.0,
                   help="the STL's coordinates times this give metres (default 1; e.g. 0.001 for millimetres)")


def run(args) -> int:
    import math

    from .common import check_output_file
    from ..errors import InputError
    from ..lammps import mesh_file

    check_output_file("--out", args.out, (".mesh",))
    if not (math.isfinite(args.scale) and args.scale > 0.0):
        raise InputError(f"--scale must be finite and > 0, got {args.scale!r}")
    wall = mesh_file.from_stl(args.stl, args.out, scale=args.scale)
    print(f"{args.out}: {len(wall.triangles)} triangles (conforming), {len(wall.vertices)} vertices; in the input "
          f"script: fix ID GROUP dem/contact/wall mesh {args.out} [wall W] [velocity ...] [angular_velocity ...]")
    return 0
