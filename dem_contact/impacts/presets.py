"""The impact scenes of Wu, Thornton & Li (2009, Proc. R. Soc. A 465:937, section 3): a steel sphere,
R = 10 mm, against a steel wall, mu = 0.3.

RE: rigid sphere on an elastic half-space (the wall's Poisson ratio set by ``nu``); EE: elastic steel on
elastic steel; PE: elastic-perfectly plastic sphere (Y = 1.85 GPa, p_y = 1.6 Y) on elastic steel, with the
thornton normal law.
"""
from __future__ import annotations

import inspect

from ..laws.model import NORMAL_LAWS, Scene, law_of, reference_speed
from ..materials import STEEL, Material, Sphere, Wall, check_finite

CASES = ("RE", "EE", "PE")
#: Uniaxial yield stress of the PE sphere [Pa].
PE_YIELD_STRESS = 1.85e9
#: The library's default tangential law (the default of Scene).
DEFAULT_TANGENTIAL = inspect.signature(Scene).parameters["tangential"].default


def preset_scene(case: str = "EE", vn: float = 5.0, *, radius: float = 0.01, density: float = STEEL.rho,
                 E: float | None = None, nu: float | None = None, wall_E: float | None = None,
                 wall_nu: float | None = None, rigid_sphere: bool = False, rigid_wall: bool = False,
                 mu: float = 0.3, normal: str | None = None, tangential: str | None = None,
                 yield_pressure: float | None = None, yield_stress: float | None = None,
                 model: str | None = None, twist: str | None = None, rolling: str | None = None, **options) -> Scene:
    """The Scene of preset ``case`` (one of CASES) at normal speed ``vn`` [m/s] (the reference speed of
    calibrations and of the mdr grid), with any option changed. Defaults: the EE steel scene (E = 208 GPa,
    nu = 0.3, rho = 7850), hertz (thornton for PE) and the library's default tangential law. For RE,
    ``nu`` is the Poisson ratio of the elastic wall. ``model``, ``twist``, ``rolling`` and ``options`` (the
    settings the laws take, ``Scene``'s ``**options``: e_n, traction_yield, mdr_profile, ...) are passed to
    ``Scene``; v_ref is ``vn``."""
    from ..errors import InputError

    if case not in CASES:
        raise InputError(f"case = {case!r} is unknown; choose one of: {', '.join(CASES)}")
    check_finite("vn (normal impact speed towards the wall, m/s)", vn, lo=0.0)
    rigid_sphere = rigid_sphere or case == "RE"
    if rigid_sphere:
        given = [n for n, v in (("E", E), ("yield_pressure", yield_pressure), ("yield_stress", yield_stress))
                 if v is not None]
        if nu is not None and (case != "RE" or wall_nu is not None):
            given.append("nu")
        if given:
            raise InputError(f"{', '.join(given)} cannot act on a rigid sphere (case {case}"
                             f"{', rigid_sphere' if case != 'RE' else ''})")
    if rigid_wall:
        given = [n for n, v in (("wall_E", wall_E), ("wall_nu", wall_nu)) if v is not None]
        if case == "RE" and nu is not None:
            given.append("nu (the wall's Poisson ratio for case RE)")
        if given:
            raise InputError(f"{', '.join(given)} cannot act on a rigid wall")
    case_normal = normal or ("thornton" if case == "PE" else "hertz")
    if (yield_pressure is not None or yield_stress is not None) and not law_of("normal", case_normal).PLASTIC:
        raise InputError(f"yield_pressure and yield_stress act on the plastic normal laws only "
                         f"({', '.join(n for n in NORMAL_LAWS if law_of('normal', n).PLASTIC)}), not on "
                         f"{case_normal!r}")
    sphere_E = STEEL.E if E is None else E
    sphere_nu = STEEL.nu if nu is None else nu
    wall_E = STEEL.E if wall_E is None else wall_E
    wall_nu_used = STEEL.nu if wall_nu is None else wall_nu
    if case == "RE":
        rigid_sphere = True
        if nu is not None and wall_nu is None:
            wall_nu_used, sphere_nu = nu, STEEL.nu
    elif case == "PE":
        normal = normal or "thornton"
        if (law_of("normal", normal).PLASTIC and yield_pressure is None and yield_stress is None
                and options.get("e_n") is None):
            yield_stress = PE_YIELD_STRESS
    normal = normal or "hertz"
    if rigid_sphere:
        sphere_mat = Material.rigid(rho=density)
    else:
        sphere_mat = Material(E=sphere_E, nu=sphere_nu, rho=density, yield_pressure=yield_pressure,
                              yield_stress=yield_stress)
    wall = Wall.rigid() if rigid_wall else Wall(Material(E=wall_E, nu=wall_nu_used, rho=STEEL.rho))
    laws = {k: v for k, v in (("tangential", tangential), ("twist", twist), ("rolling", rolling)) if v is not None}
    if "v_ref" in options:
        raise InputError("v_ref is the preset's vn: give vn")
    return Scene(Sphere(radius, sphere_mat), wall, mu=mu, normal=normal, v_ref=reference_speed(vn), model=model,
                 **laws, **options)
