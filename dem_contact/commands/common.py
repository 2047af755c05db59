"""Scene options shared by the subcommands (sphere, wall, laws, time step), parsed into the presets of
``impacts.presets``."""
from __future__ import annotations

import json
import math
import os

import numpy as np

from ..errors import InputError
from ..impacts.presets import CASES, DEFAULT_TANGENTIAL, preset_scene
from ..laws.model import MDR_PROFILES, MODELS, NORMAL_LAWS, TANGENTIAL_LAWS, Scene
from ..materials import STEEL


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
    g.add_argument("--model", choices=list(MODELS), default=None,
                   help="named model that sets the laws and the time step: thornton2001 = Thornton et al. "
                        "(2001), thornton normal law (hertz if nothing yields) + md, 1000 steps per contact")
    g.add_argument("--traction-yield", action="store_true",
                   help="thornton: the limiting pressure falls with the traction |T|/N the contact carries, "
                        "as the first-yield pressure of a Hertz contact under sliding traction (Hamilton 1983)")
    g.add_argument("--mdr-profile", choices=list(MDR_PROFILES), default="truncated",
                   help="Coulomb limit of mdr/mdr_adaptive in Thornton's plastic loading: truncated = Hertz "
                        "pressure truncated at p_y (default), scaled = Hertz shape scaled to the force")
    g.add_argument("--vn", type=float, default=vn_default,
                   help=f"normal impact speed towards the wall [m/s] (default {vn_default:g})")
    t = p.add_argument_group("time step")
    t.add_argument("--steps-per-contact", type=float, default=None,
                   help="steps per elastic contact time (default: the library default)")
    t.add_argument("--dt", type=float, default=None, help="explicit time step [s] (instead of steps per contact)")
    t.add_argument("--scheme", choices=["located", "standard"], default="located",
                   help="located: separation located inside the last step (default); standard: the contact "
                        "ends at the first step without overlap, as in LIGGGHTS and LAMMPS")


def scene_from_args(args, v_ref: float | None = None) -> Scene:
    """Build the Scene that the options describe (validated); v_ref: the largest normal speed of the run
    (default --vn), which places the mdr springs and the calibrations."""
    return preset_scene(args.case, args.vn if v_ref is None else v_ref, radius=args.radius, density=args.density, E=args.E, nu=args.nu,
                        wall_E=args.wall_E, wall_nu=args.wall_nu, rigid_sphere=args.rigid_sphere,
                        rigid_wall=args.rigid_wall, mu=args.mu, normal=args.normal, tangential=args.tangential,
                        yield_pressure=args.yield_pressure, yield_stress=args.yield_stress, e_n=args.e_n,
                        model=args.model, traction_yield=args.traction_yield, mdr_profile=args.mdr_profile)


def time_options(args) -> dict:
    return {"steps_per_contact": args.steps_per_contact, "dt": args.dt, "scheme": args.scheme}


def strict_json(obj, nulls: dict | None = None, path: str = ""):
    """``obj`` as strict JSON data: numpy scalars and arrays become Python numbers and lists, and every NaN
    or infinity becomes None, its path (``points[3].e_t``) and value recorded in ``nulls``."""
    if isinstance(obj, dict):
        return {k: strict_json(v, nulls, f"{path}.{k}" if path else str(k)) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, np.ndarray)):
        return [strict_json(v, nulls, f"{path}[{i}]") for i, v in enumerate(obj)]
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        if math.isfinite(x):
            return x
        if nulls is not None:
            nulls[path] = x
        return None
    return obj


def _nodes(x, path=""):
    """(path, value) of JSON data ``x`` and of every value inside it, outside the ``null_values`` entries."""
    yield path, x
    if isinstance(x, dict):
        for k, v in x.items():
            if k != "null_values":
                yield from _nodes(v, f"{path}.{k}" if path else k)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from _nodes(v, f"{path}[{i}]")


def null_paths(x) -> list:
    """Paths of the nulls in JSON data ``x`` (outside the ``null_values`` entries)."""
    return [p for p, v in _nodes(x) if v is None]


def explained_paths(x) -> set:
    """Paths that a ``null_values`` entry explains (of the object at that path or of one inside it)."""
    return {f"{p}.{k}" if p else k for p, v in _nodes(x) if isinstance(v, dict) for k in v.get("null_values", {})}


def dump_json(obj) -> str:
    """Strict JSON text of ``obj``: no NaN or Infinity, and every null has its reason in a ``null_values``
    object (of the output, or of each object of an output that is a list). The producers give the reasons
    they know (an undefined quantity, a step not run); any other null is explained here: a number that is
    not finite, or a setting with no value."""
    nonfinite = {}
    data = strict_json(obj, nonfinite)
    targets = [(data, "")] if isinstance(data, dict) else [
        (d, f"[{i}]") for i, d in enumerate(data) if isinstance(d, dict)] if isinstance(data, list) else []
    for d, prefix in targets:
        explained = explained_paths(d)
        for p in null_paths(d):
            if p not in explained:
                full = f"{prefix}.{p}" if prefix else p
                d.setdefault("null_values", {})[p] = (f"not a finite number ({nonfinite[full]})" if full in nonfinite
                                                      else "no value: not set for this output")
    return json.dumps(data, indent=2, allow_nan=False)


def model_line(r) -> str:
    """The first line of an impact's text report: laws, friction, scheme and time step of result ``r``."""
    m = r.model
    return (f"model: normal {m['normal_law']}, tangential {m['tangential_law']}, mu = {m['mu']:g}, "
            f"kappa = {m['kappa']:.4f}; {r.settings['scheme']} scheme, {r.settings['steps_per_contact']:.4g} "
            f"steps per contact (dt = {r.dt:.4g} s)")


def print_energy_and_warnings(r) -> None:
    """The last lines of an impact's text report: the energy budget of result ``r`` and its warnings."""
    e = r.energy
    print(f"energy [J]: initial {e.initial:.6g}, final {e.final:.6g}, friction {e.friction:.6g}, "
          f"normal {e.normal:.6g}, balance error {e.error:.3g}")
    for w in r.warnings:
        print(f"warning: {w}")


def angle_to_vt(vn: float, angle_deg: float) -> float:
    if not -90.0 < angle_deg < 90.0:
        raise InputError(f"angle = {angle_deg:g} deg is outside the valid range (-90, 90)")
    return vn * math.tan(math.radians(angle_deg))


def check_output_file(option: str, path: str, suffixes: tuple | None = None) -> str:
    """Check, before any computation, that ``path`` can be written (its directory exists and accepts a
    file) and ends in one of ``suffixes``; raise InputError naming ``option`` otherwise."""
    if suffixes and os.path.splitext(path)[1].lower() not in suffixes:
        raise InputError(f"{option} {path!r}: the file name must end in {' or '.join(suffixes)}")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise InputError(f"{option} {path!r}: the directory {parent} does not exist")
    if os.path.isdir(path):
        raise InputError(f"{option} {path!r} is a directory, not a file")
    existed = os.path.exists(path)
    try:
        with open(path, "a"):
            pass
    except OSError as e:
        raise InputError(f"{option} {path!r} cannot be written: {e.strerror}") from None
    if not existed:
        os.remove(path)
    return path


def check_output_dir(option: str, path: str) -> str:
    """Check, before any computation, that directory ``path`` exists or can be created and accepts files."""
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as e:
        raise InputError(f"{option} {path!r}: the directory cannot be created: {e.strerror}") from None
    probe = os.path.join(path, ".dem_contact_write_test")
    try:
        with open(probe, "w"):
            pass
        os.remove(probe)
    except OSError as e:
        raise InputError(f"{option} {path!r}: the directory does not accept files: {e.strerror}") from None
    return path
