"""``dem-contact path``: the forces of a contact law along a prescribed loading path."""
from __future__ import annotations

import math
import sys

import numpy as np

from ..errors import InputError
from ..laws import table
from ..laws.model import TANGENTIAL_LAWS, law_of
from ..materials import STEEL
from .common import check_output_file, dump_json

ORDER = 6
HELP = "forces of a contact law along a prescribed path of overlap, tangential displacement and twist"
DESCRIPTION = ("Drive one contact (the 3D per-contact kernel, normal along z) along a path and print, per "
               "row, the normal force N and the tangential force (Tx, Ty) on body 1 [N] (it opposes the "
               "displacement) and the moment Mz on body 1 about the normal [N m] (it opposes the twist). "
               "The path is a CSV with the header delta,ux,uy[,twist] and one row per step: overlap [m] "
               "(<= 0: no contact, the history is released), the tangential displacement of body 1 relative "
               "to body 2 at the contact point, components in the tangent plane [m], and optionally the "
               "twist: the rotation of body 1 relative to body 2 about the normal (from body 1 to body 2, "
               "right-handed) [rad]; the contact starts unloaded before the first row. Or a named path at "
               "constant overlap (--shape), sizes in units of the slip displacement mu delta / kappa and "
               "twists in units of beta_1 = 3 mu N / (16 G_c a^2) (1/G_c = 1/G1 + 1/G2), the twist at "
               "which the no-slip moment would be mu N a. A path that twists needs a twist law (--twist) or "
               "--reference: the law 'none' ignores the twist (Mz = 0) and is refused for it unless named. "
               "SI units.")


#: the normal laws a path can run: those whose force is a function of the overlap (no rate, which a path has not)
PATH_NORMAL_LAWS = [m.NAME for m in table.FAMILIES["normal"] if not m.USES_RATE]
#: the tangential laws a path can set up: those that take no reference speed (a path has none), or whose springs
#: are placed from the path's largest overlap instead (they take mdr_max_radius)
PATH_TANGENTIAL_LAWS = [t for t in TANGENTIAL_LAWS if "v_ref" not in law_of("tangential", t).OPTIONS
                        or "mdr_max_radius" in law_of("tangential", t).OPTIONS]
#: the settings of the twist laws
TWIST_SETTINGS = tuple(dict.fromkeys(o.name for m in table.FAMILIES["twist"] for o in m.OPTIONS))

def add_options(p):
    from ..reference.paths import DEFAULT_SIZES, SHAPES, TWIST_SHAPES

    shapes = ("circle: the circle through the origin of radius SIZE, centre (SIZE, 0); load-circle: along x "
              "to SIZE, then once round the circle of radius SIZE about the origin; l-turn: along x to SIZE, "
              "then along y by SIZE; figure-eight: u = SIZE (sin t, sin t cos t), t from 0 to 2 pi; "
              "load-unload: along x to SIZE, back to -SIZE and again to SIZE; with a twist (twists in "
              "beta_1): twist-cycle: twist to SIZE, back to -SIZE and again to SIZE, no displacement; "
              "shear-twist: along x to SIZE, then a twist to 1 and back to 0; circle-twist: the circle of "
              "radius SIZE with the twist SIZE sin 2t (twice per turn)")
    defaults = "; ".join(f"{k} {v:g}" for k, v in DEFAULT_SIZES.items())
    p.add_argument("path_csv", nargs="?", default=None, metavar="PATH.csv",
                   help="the path (header delta,ux,uy and optionally twist); or use --shape")
    g = p.add_argument_group("named path (instead of PATH.csv)")
    g.add_argument("--shape", choices=SHAPES + TWIST_SHAPES, default=None, help=shapes)
    g.add_argument("--size", type=float, default=None,
                   help=f"size of the named path in units of the slip displacement mu delta / kappa, or of "
                        f"beta_1 for twist-cycle (defaults: {defaults})")
    g.add_argument("--overlap", type=float, default=1e-5, help="constant overlap of the named path [m] (default 1e-5)")
    g.add_argument("--steps", type=int, default=400,
                   help="steps of the named path after its first row (the loaded contact at u = 0; default 400)")
    s = p.add_argument_group("contact (SI units; defaults: steel sphere of radius 10 mm on a steel wall)")
    s.add_argument("--radius", type=float, default=0.01, help="sphere radius [m] (default 0.01)")
    s.add_argument("--E", type=float, default=None, help="sphere Young's modulus [Pa] (default 208e9)")
    s.add_argument("--nu", type=float, default=None, help="sphere Poisson ratio (default 0.3)")
    s.add_argument("--wall-E", type=float, default=None, help="wall Young's modulus [Pa] (default 208e9)")
    s.add_argument("--wall-nu", type=float, default=None, help="wall Poisson ratio (default 0.3)")
    s.add_argument("--rigid-wall", action="store_true", help="the wall is rigid")
    s.add_argument("--rigid-sphere", action="store_true", help="the sphere is rigid")
    s.add_argument("--mu", type=float, default=0.3, help="friction coefficient >= 0 (default 0.3)")
    s.add_argument("--normal", choices=PATH_NORMAL_LAWS, default="hertz",
                   help="normal law (default hertz; dashpot laws need a rate, which a path does not have)")
    s.add_argument("--yield-stress", type=float, default=None, help="sphere's yield stress Y [Pa] (thornton)")
    s.add_argument("--tangential", choices=PATH_TANGENTIAL_LAWS, default=None,
                   help="tangential law (default: the library default; mdr places its springs for the path's "
                        "largest overlap)")
    twist_laws = list(table.ids("twist"))
    s.add_argument("--twist", choices=twist_laws, default=None,
                   help=f"twist law: the moment about the normal from the twist (default: the library's, "
                        f"{table.DEFAULTS['twist']!r}; 'none' ignores the twist, Mz = 0: a path that twists is "
                        f"refused unless a law is named)")
    from .common import law_options

    for flag, kwargs in law_options("twist"):
        s.add_argument(flag, **kwargs)
    s.add_argument("--coupled", action="store_true",
                   help="twist and shear from one local state (laws.twist_shear: the cells of the default "
                        "tangential law and of deresiewicz sharing the Coulomb limit at points of each ring; "
                        "Hertz only; the overlap may vary: the Hertz normal force and contact radius of each row)")
    s.add_argument("--reference", action="store_true",
                   help="use the boundary-element reference (exact 3D Cattaneo-Mindlin with the twist, slow) "
                        "instead of a law")
    s.add_argument("--n-across", type=int, default=64,
                   help="with --reference: boundary elements across the largest contact (default 64)")
    o = p.add_argument_group("output")
    o.add_argument("--json", action="store_true",
                   help="print one JSON object with the lists N, Tx, Ty [N] and Mz [N m]")
    o.add_argument("--csv", default=None, metavar="FILE",
                   help="write delta, ux, uy [m], twist [rad], N, Tx, Ty [N], Mz [N m] per row to FILE")
    o.add_argument("--plot", default=None, metavar="FILE.png",
                   help="draw the path and the force (T/(mu N), both components and magnitude; Mz/(mu N a) "
                        "when the path twists) to a PNG")


def _scene(args, delta_max: float):
    """The contact of the options; delta_max [m]: the path's largest overlap (places the mdr springs)."""
    from ..laws.model import Scene
    from ..materials import Material, Sphere, Wall, pair_properties

    plastic = law_of("normal", args.normal).PLASTIC
    if args.yield_stress is not None and not plastic:
        raise InputError(f"--yield-stress applies to a plastic --normal law only, not {args.normal}")
    if plastic and args.yield_stress is None:
        raise InputError(f"--normal {args.normal} needs --yield-stress (the sphere's yield stress Y [Pa])")
    for rigid, flag, opts in ((args.rigid_sphere, "--rigid-sphere", (("--E", args.E), ("--nu", args.nu),
                                                                     ("--yield-stress", args.yield_stress))),
                              (args.rigid_wall, "--rigid-wall", (("--wall-E", args.wall_E),
                                                                 ("--wall-nu", args.wall_nu)))):
        given = [name for name, v in opts if v is not None]
        if rigid and given:
            raise InputError(f"{', '.join(given)} cannot act on a rigid body ({flag})")
    pick = lambda v, default: default if v is None else v  # noqa: E731
    sphere_mat = (Material.rigid(rho=STEEL.rho) if args.rigid_sphere else
                  Material(E=pick(args.E, STEEL.E), nu=pick(args.nu, STEEL.nu), rho=STEEL.rho,
                           yield_stress=args.yield_stress))
    wall = Wall.rigid() if args.rigid_wall else Wall(Material(E=pick(args.wall_E, STEEL.E),
                                                              nu=pick(args.wall_nu, STEEL.nu), rho=STEEL.rho))
    sphere = Sphere(args.radius, sphere_mat)
    laws = {} if args.tangential is None else {"tangential": args.tangential}
    if args.twist is not None:
        laws["twist"] = args.twist
    laws.update({k: getattr(args, k) for k in TWIST_SETTINGS if getattr(args, k) is not None})
    if args.tangential is not None and "mdr_max_radius" in law_of("tangential", args.tangential).OPTIONS:
        # a path has no impact speed to place the springs by: they cover the contact radius of its largest
        # overlap (as studies.paths.path_scene does)
        R_star = pair_properties(sphere, wall).R_star
        laws["mdr_max_radius"] = 1.05 * math.sqrt(R_star * max(delta_max, 1e-12 * R_star))
    return Scene(sphere, wall, mu=args.mu, normal=args.normal, **laws)


def run(args) -> int:
    from ..reference.paths import DEFAULT_SIZES, scene_path
    from ..studies.paths import coupled_path, read_path_csv, reference_path, run_path, write_path_csv

    # output paths first: nothing is computed for a file that cannot be written
    if args.csv:
        check_output_file("--csv", args.csv)
    if args.plot:
        check_output_file("--plot", args.plot, (".png",))
    coefficients = [table.option(k).flag for k in TWIST_SETTINGS if getattr(args, k) is not None]
    if args.coupled and (args.reference or args.tangential is not None or args.twist is not None or coefficients):
        raise InputError("--coupled is a law of its own (the default tangential law and deresiewicz coupled): "
                         "give it without --reference, --tangential, --twist and the twist coefficients")
    if args.reference and coefficients:
        raise InputError(f"{', '.join(coefficients)} cannot act on --reference (it solves the twist exactly)")
    if args.reference and args.tangential is not None:
        raise InputError("give either --reference or --tangential, not both")
    if args.reference and args.twist is not None:
        raise InputError("give either --reference or --twist, not both (the reference solves the twist exactly)")
    if args.reference and args.normal != "hertz":
        raise InputError("--reference solves the Hertz contact: it takes --normal hertz only")
    if args.n_across != 64 and not args.reference:
        raise InputError("--n-across applies to --reference only")
    if (args.path_csv is None) == (args.shape is None):
        raise InputError("give either a path CSV (PATH.csv) or --shape")
    named = args.shape is not None
    if not named and (args.size is not None or args.overlap != 1e-5 or args.steps != 400):
        raise InputError("--size, --overlap and --steps apply to --shape only")
    if named:
        size = args.size if args.size is not None else DEFAULT_SIZES[args.shape]
        if not args.overlap > 0:
            raise InputError(f"--overlap = {args.overlap:g} must be > 0 [m]")
        scene = _scene(args, args.overlap)
        path = scene_path(args.shape, size, args.steps, scene, args.overlap)
    else:
        path = read_path_csv(args.path_csv)
        scene = _scene(args, float(path[0].max()))
    delta, ux, uy = path[:3]
    twist = path[3] if len(path) == 4 else np.zeros(delta.size)
    twists = bool(np.any(twist != 0.0))
    if twists and not (args.reference or args.coupled) and scene.twist == "none" and args.twist is None:
        source = f"the {args.shape} path" if named else f"the twist column of {args.path_csv}"
        raise InputError(f"{source} twists the contact, but the twist law is 'none' (no moment: Mz = 0); "
                         f"choose --twist LAW (one of: {', '.join(table.ids('twist'))}; --twist none to accept "
                         f"Mz = 0) or --reference")
    if args.reference:
        N, Tx, Ty, Mz = reference_path(scene, delta, ux, uy, twist, n_across=args.n_across)
        law = f"boundary-element reference ({args.n_across} elements across)"
    elif args.coupled:
        N, Tx, Ty, Mz = coupled_path(scene, delta, ux, uy, twist)
        law = f"{scene.normal} / twist and shear coupled (laws.twist_shear)"
    else:
        from ..impacts.sweep import compile_notice

        with compile_notice(sys.stderr.isatty()):      # (the notice: in a terminal only)
            N, Tx, Ty, Mz = run_path(scene, delta, ux, uy, twist)
        law = f"{scene.normal} / {scene.tangential} / twist {scene.twist}"
    if args.csv:
        write_path_csv(args.csv, delta, ux, uy, N, Tx, Ty, twist=twist, Mz=Mz)
    if args.plot:
        from ..plots import path_figure
        title = (f"{args.shape} path" if named else args.path_csv) + f": {law}, mu = {scene.mu:g}"
        moment = None
        if twists:
            a = np.sqrt(scene.pair.R_star * np.clip(delta, 0.0, None))
            moment = np.where(N > 0, Mz / np.where(N > 0, scene.mu * N * a, 1.0), np.nan)
        path_figure(delta, ux, uy, N, Tx, Ty, scene.mu, args.plot, title=title, moment=moment)
    model = scene.describe()
    if args.coupled:
        model = dict(model, twist_law="deresiewicz", coupling="laws.twist_shear: the tangential and twist cells "
                     "share the Coulomb limit at points of each ring")
    if args.json:
        print(dump_json({"N": [float(x) + 0.0 for x in N], "Tx": [float(x) + 0.0 for x in Tx],
                         "Ty": [float(x) + 0.0 for x in Ty], "Mz": [float(x) + 0.0 for x in Mz], "law": law,
                         "model": model}))
        return 0
    print(f"# {law}; mu = {scene.mu:g}, kappa = {scene.pair.kappa:.4f}; {len(N)} rows; forces [N] and moment "
          f"about the normal [N m] on body 1")
    print("N,Tx,Ty,Mz")
    for n, tx, ty, mz in zip(N, Tx, Ty, Mz):
        print(f"{n + 0.0:.10g},{tx + 0.0:.10g},{ty + 0.0:.10g},{mz + 0.0:.10g}")      # + 0.0: no negative zeros
    return 0
