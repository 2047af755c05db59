"""Scene options shared by the subcommands (sphere, wall, laws, time step), parsed into the presets of
``impacts.presets``."""
from __future__ import annotations

import json
import math
import os

import numpy as np

from ..errors import InputError
from ..impacts.presets import CASES, DEFAULT_TANGENTIAL, preset_scene
from ..laws import table
from ..laws.dispatch import ROLLING_NAMES as ROLLING_LAWS, TWIST_NAMES as TWIST_LAWS
from ..laws.model import MODELS, NORMAL_LAWS, TANGENTIAL_LAWS, Scene
from ..materials import STEEL


def add_command(sub, module):
    """The subparser of a command module: its name (the module's, with hyphens for underscores), ``HELP``,
    ``DESCRIPTION``, the options of ``add_options(p)`` and ``run``."""
    name = module.__name__.rsplit(".", 1)[-1].replace("_", "-")
    p = sub.add_parser(name, help=module.HELP, description=module.DESCRIPTION)
    module.add_options(p)
    p.set_defaults(run=module.run)
    return p


def add_out_dir(p, default: str):
    """The option --out: the directory a command writes its files to (checked by ``check_output_dir``)."""
    p.add_argument("--out", default=default, help=f"output directory (default ./{default})")


def _option(flag, **kwargs):
    """One row of an option table: (flag, argparse keyword arguments)."""
    return flag, kwargs


def law_options(*families) -> tuple:
    """The option table rows of the settings that the laws of ``families`` take (``declare.Option`` with a
    ``cli``), from their declarations: flag, default, choices, and a help naming the laws that take them."""
    rows = []
    for o in table.options():
        laws = [m for f in families for m in table.FAMILIES[f] if o in m.OPTIONS]
        if o.cli is None or not laws or any(o.flag == r[0] for r in rows):
            continue
        kw = dict(default=o.default, help=f"{o.describe()} ({', '.join(m.NAME for m in laws)})")
        if o.choices is not None:
            kw["choices"] = list(o.choices)
        elif o.parse is None:
            kw["type"] = float
        rows.append(_option(o.flag, **{**kw, **o.cli}))
    return tuple(rows)


#: The scene options, spelled once: the argparse options of ``add_scene_options`` and, by their names, the
#: arguments of ``impacts.presets.preset_scene`` that ``scene_from_args`` passes (--case and --vn
#: positionally, every other by keyword).
SCENE_OPTIONS = (
    _option("--case", choices=CASES, default="EE",
            help="preset scene: RE rigid sphere on elastic steel (takes --nu), EE steel on steel, "
                 "PE plastic steel sphere (Y = 1.85 GPa) on elastic steel with the thornton law "
                 "(default EE)"),
    _option("--radius", type=float, default=0.01, help="sphere radius [m] (default 0.01)"),
    _option("--density", type=float, default=STEEL.rho, help="sphere density [kg/m^3] (default 7850)"),
    _option("--E", type=float, default=None, help="sphere Young's modulus [Pa] (default 208e9)"),
    _option("--nu", type=float, default=None, help="sphere Poisson ratio (-1, 0.5] (default 0.3); "
            "for --case RE the Poisson ratio of the elastic wall"),
    _option("--wall-E", type=float, default=None, help="wall Young's modulus [Pa] (default: steel)"),
    _option("--wall-nu", type=float, default=None, help="wall Poisson ratio (default: steel, 0.3)"),
    _option("--rigid-wall", action="store_true", help="the wall is rigid"),
    _option("--rigid-sphere", action="store_true", help="the sphere is rigid"),
    _option("--mu", type=float, default=0.3, help="friction coefficient >= 0 (default 0.3)"),
    _option("--normal", choices=list(NORMAL_LAWS), default=None,
            help="normal law (default hertz; thornton for --case PE)"),
    _option("--tangential", choices=list(TANGENTIAL_LAWS), default=None,
            help=f"tangential law (default {DEFAULT_TANGENTIAL}, the library default)"),
    _option("--yield-pressure", type=float, default=None,
            help="sphere's limiting contact pressure p_y [Pa] (thornton)"),
    _option("--yield-stress", type=float, default=None,
            help="sphere's uniaxial yield stress Y [Pa], p_y = 1.6 Y (thornton)"),
    _option("--model", choices=list(MODELS), default=None,
            help="named model that sets the laws and the time step: thornton2001 = Thornton et al. "
                 "(2001), thornton normal law (hertz if nothing yields) + md, 1000 steps per contact"),
    *law_options("normal", "tangential"),
    _option("--vn", type=float, default=5.0,
            help="normal impact speed towards the wall [m/s] (default {vn:g})"),
)

#: The time-step options (group "time step"): the keyword arguments of an impact (``time_options``).
TIME_OPTIONS = (
    _option("--steps-per-contact", type=float, default=None,
            help="steps per elastic contact time (default: the library default)"),
    _option("--dt", type=float, default=None, help="explicit time step [s] (instead of steps per contact)"),
    _option("--scheme", choices=["located", "standard"], default="located",
            help="located: separation located inside the last step (default); standard: the contact "
                 "ends at the first step without overlap, as in LIGGGHTS and LAMMPS"),
)


def dest(flag: str) -> str:
    """The attribute of the parsed options that ``flag`` sets (``--wall-E`` -> ``wall_E``)."""
    return flag.lstrip("-").replace("-", "_")


def default(kwargs: dict):
    """The value that the option of a table row (its argparse keyword arguments) takes when not given."""
    return kwargs.get("default", False if kwargs.get("action") == "store_true" else None)


#: The arguments of ``preset_scene`` that the scene options give by keyword.
SCENE_KEYWORDS = tuple(dest(flag) for flag, _ in SCENE_OPTIONS if flag not in ("--case", "--vn"))


def add_scene_options(p, vn_default=5.0):
    """The options of SCENE_OPTIONS (group "scene") and TIME_OPTIONS (group "time step"); vn_default: the
    default of --vn."""
    g = p.add_argument_group("scene (SI units; defaults: the EE steel scene of Wu et al. 2009; the laws' reference "
                                 "speed v_ref is --vn)")
    for flag, kwargs in SCENE_OPTIONS:
        if flag == "--vn":
            kwargs = dict(kwargs, default=vn_default, help=kwargs["help"].format(vn=vn_default))
        g.add_argument(flag, **kwargs)
    t = p.add_argument_group("time step")
    for flag, kwargs in TIME_OPTIONS:
        t.add_argument(flag, **kwargs)


def scene_from_args(args, v_ref: float | None = None) -> Scene:
    """Build the Scene that the options describe (validated); v_ref: the largest normal speed of the run
    (default --vn), which places the mdr springs and the calibrations."""
    return preset_scene(args.case, args.vn if v_ref is None else v_ref,
                        **{k: getattr(args, k) for k in SCENE_KEYWORDS})


#: The twist and rolling options (group "twist and rolling"), each a ``Scene`` argument of its name: the
#: laws (default: the library's, 'none') and the coefficients of LAMMPS's engine models.
TORQUE_OPTIONS = (
    _option("--twist", choices=list(TWIST_LAWS), default=None,
            help="twist law, the moment about the normal: deresiewicz (exact for Hertz contacts: Lubkin "
                 "1951, Deresiewicz 1954), LAMMPS's marshall or sds (default none: no moment)"),
    *law_options("twist"),
    _option("--rolling", choices=list(ROLLING_LAWS), default=None,
            help="rolling resistance, LAMMPS's engine model sds (a calibration of shape and roughness, not "
                 "contact mechanics of smooth spheres; default none)"),
    *law_options("rolling"),
)


def add_torque_options(p):
    """The options of TORQUE_OPTIONS (group "twist and rolling")."""
    g = p.add_argument_group("twist and rolling (the moment about the normal; rolling resistance)")
    for flag, kwargs in TORQUE_OPTIONS:
        g.add_argument(flag, **kwargs)


def torque_laws(args) -> dict:
    """The Scene arguments that the twist and rolling options given set (none: {})."""
    return {dest(flag): getattr(args, dest(flag)) for flag, _ in TORQUE_OPTIONS
            if getattr(args, dest(flag), None) is not None}


def time_options(args) -> dict:
    """The keyword arguments of an impact that the time-step options give."""
    return {dest(flag): getattr(args, dest(flag)) for flag, _ in TIME_OPTIONS}


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
    torque = "".join(f", {k} {m[f'{k}_law']}" for k in ("twist", "rolling") if m.get(f"{k}_law", "none") != "none")
    return (f"model: normal {m['normal_law']}, tangential {m['tangential_law']}{torque}, mu = {m['mu']:g}, "
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
