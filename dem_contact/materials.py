"""Materials, bodies and the effective properties of a contacting pair (Johnson, *Contact Mechanics*, 1985,
section 4.2; the Mindlin tangential compliance as in Wu, Thornton & Li 2009, eq. 2.9).

All quantities are SI: Pa, kg/m^3, m, kg. A rigid material has ``E = inf``; its compliance terms are 0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import InputError

#: Default conversion from uniaxial yield stress Y to Thornton's limiting contact pressure, p_y = 1.6 Y.
#: With it the yield velocity equals Johnson's first-yield velocity (Johnson 1985, eq. 11.24; Thornton 1997).
YIELD_PRESSURE_PER_YIELD_STRESS = 1.6


def check_finite(name: str, value, lo=None, hi=None, lo_open=True, hi_open=False, allow_inf=False) -> float:
    """Return ``float(value)`` or raise InputError naming ``name`` and the valid range."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if ((math.isfinite(x) or (allow_inf and not math.isnan(x)))
            and (lo is None or x > lo or (not lo_open and x == lo))
            and (hi is None or x < hi or (not hi_open and x == hi))):
        return x
    lo_s = "-inf" if lo is None else f"{lo:g}"
    hi_s = "inf" if hi is None else f"{hi:g}"
    rng = f"{'(' if lo_open else '['}{lo_s}, {hi_s}{')' if hi_open or hi is None else ']'}"
    if math.isnan(x):
        raise InputError(f"{name} is NaN; valid range {rng}")
    if math.isinf(x) and not allow_inf:
        raise InputError(f"{name} must be finite, got {x}; valid range {rng}")
    if lo is not None and (x < lo or (lo_open and x == lo)):
        raise InputError(f"{name} = {x:g} is outside the valid range {rng}")
    if hi is not None and (x > hi or (hi_open and x == hi)):
        raise InputError(f"{name} = {x:g} is outside the valid range {rng}")
    return x


#: Range of moduli, densities and yield pressures [SI] accepted: far wider than any material, narrow enough
#: that the contact quantities built from them stay ordinary double-precision numbers.
MATERIAL_RANGE = (1e-30, 1e30)


@dataclass(frozen=True)
class Material:
    """An isotropic material.

    E: Young's modulus [Pa] (``math.inf`` for a rigid body); nu: Poisson ratio in (-1, 0.5];
    rho: density [kg/m^3]; yield_pressure: Thornton's limiting contact pressure p_y [Pa], or
    yield_stress: uniaxial yield stress Y [Pa], converted as p_y = 1.6 Y. Both optional.
    """

    E: float
    nu: float
    rho: float
    yield_pressure: float | None = None
    yield_stress: float | None = None

    def __post_init__(self):
        E = check_finite("E (Young's modulus, Pa)", self.E, lo=0.0, allow_inf=True)
        if not math.isinf(E):
            check_finite("E (Young's modulus, Pa)", E, lo=MATERIAL_RANGE[0], hi=MATERIAL_RANGE[1], lo_open=False)
        nu = check_finite("nu (Poisson ratio)", self.nu, lo=-1.0, hi=0.5)
        rho = check_finite("rho (density, kg/m^3)", self.rho, lo=MATERIAL_RANGE[0], hi=MATERIAL_RANGE[1],
                           lo_open=False)
        object.__setattr__(self, "E", E)
        object.__setattr__(self, "nu", nu)
        object.__setattr__(self, "rho", rho)
        if self.yield_pressure is not None and self.yield_stress is not None:
            raise InputError("give either yield_pressure or yield_stress, not both")
        if self.yield_pressure is not None:
            object.__setattr__(self, "yield_pressure", check_finite("yield_pressure (Pa)", self.yield_pressure,
                                                                    lo=MATERIAL_RANGE[0], hi=MATERIAL_RANGE[1],
                                                                    lo_open=False))
        if self.yield_stress is not None:
            object.__setattr__(self, "yield_stress", check_finite("yield_stress (Pa)", self.yield_stress,
                                                                  lo=MATERIAL_RANGE[0], hi=MATERIAL_RANGE[1],
                                                                  lo_open=False))

    @classmethod
    def rigid(cls, rho: float = 7850.0) -> "Material":
        """A rigid material (infinite modulus) of density ``rho``."""
        return cls(E=math.inf, nu=0.0, rho=rho)

    @property
    def is_rigid(self) -> bool:
        return math.isinf(self.E)

    @property
    def G(self) -> float:
        """Shear modulus G = E / (2 (1 + nu)) [Pa]."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def p_y(self) -> float | None:
        """Limiting contact pressure [Pa]: given directly, or 1.6 Y."""
        if self.yield_pressure is not None:
            return self.yield_pressure
        if self.yield_stress is not None:
            return YIELD_PRESSURE_PER_YIELD_STRESS * self.yield_stress
        return None


#: The steel of Wu, Thornton & Li (2009): E = 208 GPa, nu = 0.3, rho = 7850 kg/m^3.
STEEL = Material(E=208e9, nu=0.3, rho=7850.0)


#: Range of the magnitudes (SI) that bodies may have (mass, moment of inertia): inside it products and
#: powers of the impact quantities stay ordinary double-precision numbers.
BODY_RANGE = (1e-100, 1e100)


@dataclass(frozen=True)
class Sphere:
    """A sphere of ``radius`` [m] made of ``material``."""

    radius: float
    material: Material

    def __post_init__(self):
        r = check_finite("radius (m)", self.radius, lo=0.0)
        object.__setattr__(self, "radius", r)
        if not isinstance(self.material, Material):
            raise InputError(f"material of a Sphere must be a Material, got {self.material!r}")
        # mass and moment of inertia must be ordinary floats (no overflow, no underflow to 0)
        cm = 4.0 / 3.0 * math.pi * self.material.rho          # m = cm R^3, I = 0.4 cm R^5
        lo = max((BODY_RANGE[0] / cm) ** (1 / 3), (BODY_RANGE[0] / (0.4 * cm)) ** 0.2)
        hi = min((BODY_RANGE[1] / cm) ** (1 / 3), (BODY_RANGE[1] / (0.4 * cm)) ** 0.2)
        if not lo <= r <= hi:
            raise InputError(f"radius = {r:g} m with density {self.material.rho:g} kg/m^3 gives a mass or moment "
                             f"of inertia outside [{BODY_RANGE[0]:g}, {BODY_RANGE[1]:g}] (SI): radius must be in "
                             f"[{lo:.3g}, {hi:.3g}] m for this density")

    @property
    def mass(self) -> float:
        return 4.0 / 3.0 * math.pi * self.radius**3 * self.material.rho

    @property
    def inertia(self) -> float:
        """Moment of inertia 2/5 m R^2 [kg m^2]."""
        return 0.4 * self.mass * self.radius**2


@dataclass(frozen=True)
class Wall:
    """A wall of infinite mass, with its own ``material`` (``Material.rigid()`` for a rigid wall), flat
    (default) or with the ``curvature`` k = 1/R2 [1/m] at its contacts (> 0 convex, < 0 concave): the
    effective radius of a sphere on it is R* = 1 / (1/R1 + k) (Johnson 1985, Contact Mechanics, section
    4.2). A curved wall of ``dem_contact.walls`` states the k its material must carry (``CylinderWall``:
    ``curvature_for_rstar``)."""

    material: Material
    curvature: float = 0.0

    def __post_init__(self):
        if not isinstance(self.material, Material):
            raise InputError(f"material of a Wall must be a Material, got {self.material!r}")
        object.__setattr__(self, "curvature", check_finite("curvature (1/m)", self.curvature))

    @classmethod
    def rigid(cls) -> "Wall":
        return cls(Material.rigid())


@dataclass(frozen=True)
class PairProperties:
    """Effective properties of a contacting pair (Johnson 1985; Wu, Thornton & Li 2009, section 2).

    E_star, G_star [Pa]; R_star [m]; m_star [kg]; kappa = 4 G*/E* (ratio of tangential to normal
    stiffness); p_y the limiting contact pressure of the softer yielding body [Pa] or None.
    """

    E_star: float
    G_star: float
    R_star: float
    m_star: float
    kappa: float
    p_y: float | None


def _compliance_E(m: Material) -> float:
    return 0.0 if m.is_rigid else (1.0 - m.nu**2) / m.E


def _compliance_G(m: Material) -> float:
    return 0.0 if m.is_rigid else (2.0 - m.nu) / m.G


def pair_properties(body1: Sphere, body2: Sphere | Wall) -> PairProperties:
    """Effective E*, G*, R*, m*, kappa of sphere ``body1`` against a sphere or a wall ``body2``.

    1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2,  1/G* = (2-nu1)/G1 + (2-nu2)/G2,  1/R* = 1/R1 + 1/R2,
    1/m* = 1/m1 + 1/m2 (a wall has 1/R2 = its curvature, 0 if flat, and 1/m2 = 0), kappa = 4 G*/E*  (Johnson 1985; Wu et al. 2009).
    """
    m1, m2 = body1.material, body2.material
    cE = _compliance_E(m1) + _compliance_E(m2)
    cG = _compliance_G(m1) + _compliance_G(m2)
    if cE == 0.0:
        raise InputError("both bodies are rigid: at least one of sphere and wall must have a finite E")
    if isinstance(body2, Sphere):
        R_star = 1.0 / (1.0 / body1.radius + 1.0 / body2.radius)
        m_star = 1.0 / (1.0 / body1.mass + 1.0 / body2.mass)
    else:
        if not 1.0 / body1.radius + body2.curvature > 0.0:
            raise InputError(f"a sphere of radius {body1.radius:g} m does not fit a wall of curvature "
                             f"{body2.curvature:g} 1/m: 1/R1 + curvature must be > 0")
        R_star = body1.radius if body2.curvature == 0.0 else 1.0 / (1.0 / body1.radius + body2.curvature)
        m_star = body1.mass
    E_star = 1.0 / cE
    G_star = 1.0 / cG
    # p_y: the yielding body's limiting pressure; if both yield, the lower one governs.
    pys = [p for p in (m1.p_y, m2.p_y) if p is not None]
    p_y = min(pys) if pys else None
    return PairProperties(E_star=E_star, G_star=G_star, R_star=R_star, m_star=m_star,
                          kappa=4.0 * G_star / E_star, p_y=p_y)
