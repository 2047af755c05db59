"""Scene options shared by the subcommands (sphere, wall, laws, time step) and the published presets."""
from __future__ import annotations

import inspect
import json
import math

from ..errors import InputError
from ..materials import STEEL, Material, Sphere, Wall, check_finite
from ..model import NORMAL_LAWS, TANGENTIAL_LAWS, Scene

#: The library's default tangential law (the default of Scene).
DEFAULT_TANGENTIAL = inspect.signature(Scene).parameters["tangential"].default

#: Scenes of Wu, Thornton & Li (2009) (physics.md section 6): steel sphere R = 10 mm, mu = 0.3.
#: RE: rigid sphere on an elastic half-space (nu set by --nu); EE: elastic steel on elastic steel;
#: PE: elastic-perfectly plastic sphere (Y = 1.85 GPa, p_y = 1.6 Y) on elastic steel, thornton law.
CASES = ("RE", "EE", "PE")
PE_YIELD_STRESS = 1.85e9


def add_scene_options(p, vn_default=5.0):
    g = p.add_argument_group("scene (SI units; defaults: the EE steel scene of Wu et al. 2009)")
    g.add_argument("--case", choices=CASES, default="EE",
                   help="preset scene: RE rigid sphere on elastic steel (takes --nu), EE steel on steel, "
                        "PE plastic steel sphere (Y = 1.85 GPa) on elastic steel with the thornton law "
                        "(default EE)")
    g.add_argument("--radius", type=float, default=0.01, help="sphere radius [m] (default 0.01)")
    g.add_argument("--density", type=float, default=STEEL.rho, help="sphere density [kg/m^3] (default 7850)")
    g.add_argument("--E", type=float, default=None, help="sphere Young's modulus [Pa] (default 208e9)")
    g.add_argument("--nu", type=float, default=None, help="sphere Poisson ratio (-1, 0.5] (default 0.3); "
                   "for --case RE the Poisson ratio of the elastic wall")
    g.add_argument("--wall-E", type=float, default=None, help="wall Young's modulus [Pa] (default: steel)")
    g.add_argument("--wall-nu", type=float, default=None, help="wall Poisson ratio (default: steel, 0.3)")
    g.add_argument("--rigid-wall", action="store_true", help="the wall is rigid")
    g.add_argument("--rigid-sphere", action="store_true", help="the sphere is rigid")
    g.add_argument("--mu", type=float, default=0.3, help="friction coefficient >= 0 (default 0.3)")
    g.add_argument("--normal", choices=list(NORMAL_LAWS), default=None,
                   help="normal law (default hertz; thornton for --case PE)")
    g.add_argument("--tangential", choices=list(TANGENTIAL_LAWS), default=None,
                   help=f"tangential law (default {DEFAULT_TANGENTIAL}, the library default)")
    g.add_argument("--yield-pressure", type=float, default=None,
                   help="sphere's limiting contact pressure p_y [Pa] (thornton)")
    g.add_argument("--yield-stress", type=float, default=None,
                   help="sphere's uniaxial yield stress Y [Pa], p_y = 1.6 Y (thornton)")
    g.add_argument("--e-n", type=float, default=None,
                   help="target normal restitution: sets the dashpot of hertz_damped and linear, or "
                        "calibrates p_y of thornton at --vn")
    g.add_argument("--vn", type=float, default=vn_default,
                   help=f"normal impact speed towards the wall [m/s] (default {vn_default:g})")
    t = p.add_argument_group("time step")
    t.add_argument("--steps-per-contact", type=float, default=None,
                   help="steps per elastic contact time (default: the library default)")
    t.add_argument("--dt", type=float, default=None, help="explicit time step [s] (instead of steps per contact)")
    t.add_argument("--scheme", choices=["located", "standard"], default="located",
                   help="located: separation located inside the last step (default); standard: the contact "
                        "ends at the first step without overlap, as in LIGGGHTS and LAMMPS")


def scene_from_args(args) -> Scene:
    """Build the Scene that the options describe (validated)."""
    check_finite("vn (normal impact speed towards the wall, m/s)", args.vn, lo=0.0)
    E = 208e9 if args.E is None else args.E
    nu = 0.3 if args.nu is None else args.nu
    wall_E = STEEL.E if args.wall_E is None else args.wall_E
    wall_nu = STEEL.nu if args.wall_nu is None else args.wall_nu
    yield_pressure, yield_stress = args.yield_pressure, args.yield_stress
    normal = args.normal
    rigid_sphere, rigid_wall = args.rigid_sphere, args.rigid_wall
    if args.case == "RE":
        rigid_sphere = True
        if args.nu is not None and args.wall_nu is None:
            wall_nu, nu = args.nu, 0.3
    elif args.case == "PE":
        normal = normal or "thornton"
        if yield_pressure is None and yield_stress is None and args.e_n is None:
            yield_stress = PE_YIELD_STRESS
    normal = normal or "hertz"
    if rigid_sphere:
        sphere_mat = Material.rigid(rho=args.density)
    else:
        sphere_mat = Material(E=E, nu=nu, rho=args.density, yield_pressure=yield_pressure, yield_stress=yield_stress)
    wall = Wall.rigid() if rigid_wall else Wall(Material(E=wall_E, nu=wall_nu, rho=STEEL.rho))
    laws = {} if args.tangential is None else {"tangential": args.tangential}
    return Scene(Sphere(args.radius, sphere_mat), wall, mu=args.mu, normal=normal, e_n=args.e_n, v_ref=args.vn,
                 **laws)


def time_options(args) -> dict:
    return {"steps_per_contact": args.steps_per_contact, "dt": args.dt, "scheme": args.scheme}


def dump_json(obj) -> str:
    return json.dumps(obj, indent=2, allow_nan=False)


def angle_to_vt(vn: float, angle_deg: float) -> float:
    if not -90.0 < angle_deg < 90.0:
        raise InputError(f"angle = {angle_deg:g} deg is outside the valid range (-90, 90)")
    return vn * math.tan(math.radians(angle_deg))


def preset_scene(case: str = "EE", vn: float = 5.0, **options) -> Scene:
    """The Scene of a --case preset at normal speed ``vn``, as the CLI builds it; ``options`` are other
    scene options by their argument names (nu, mu, tangential, normal, ...)."""
    import argparse

    p = argparse.ArgumentParser()
    add_scene_options(p)
    args = p.parse_args([])
    args.case, args.vn = case, vn
    for k, v in options.items():
        if not hasattr(args, k):
            raise InputError(f"unknown scene option {k!r}")
        setattr(args, k, v)
    return scene_from_args(args)
