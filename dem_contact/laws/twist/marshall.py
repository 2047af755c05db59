"""LAMMPS's ``twisting marshall`` engine model: the spring-dashpot-slider of ``twisting sds`` with its
coefficients scaled from the tangential model at each step (Marshall 2009, J. Comput. Phys. 228, 1541,
eq. 32), with LAMMPS's arithmetic and history (22 Jul 2025 release, GRANULAR package,
``GranSubModTwistingMarshall``):

    k_twist = 0.5 k_t a^2,  gamma_twist = 0.5 gamma_t a^2,  mu_twist = (2/3) mu a

with a the contact radius, mu the friction coefficient and k_t, gamma_t the coefficients of LAMMPS's
tangential model: for ``tangential mindlin`` with k_t NULL, k_t = 8 G*, the per-radius coefficient, used
unscaled, so that k_twist = 4 G* a^2 (not 4 G* a^3: about 1/a times stiffer than the Mindlin-scaled
form, a nearly rigid slider at M = (2/3) mu N a); for the ``linear`` tangential law here, its k_t [N/m].
The tangential laws here have no dashpot (LAMMPS's x_gamma,t = 0), so gamma_twist = 0.

Twisting resistance of this kind is not contact mechanics of smooth spheres: the twist of a Hertz contact
is Lubkin's (no-slip stiffness (16/3) G_c a^3, full-slip moment (3 pi/16) mu N a); this is the optional,
named engine model that DEM users expect, for comparison with LAMMPS and for moving between the two. The
step, its quirks and the sign convention are those of ``laws.twist.sds``.
"""
from numba import njit

from ..declare import MU
from ..slots import P_GAMMA_TWIST, P_K_TWIST, P_MU
from ..vector import JIT
from .sds import GAMMA, K, VECTOR_SLOTS, spring_dashpot_slider  # noqa: F401

NAME, FAMILY = "marshall", "twist"
SOURCE = "LAMMPS twisting marshall: sds with k = 0.5 k_t a^2, mu = (2/3) mu a (Marshall 2009, eq. 32)"
PARAMETERS, STATE = (K, GAMMA, MU), ("xi",)

#: LAMMPS's TWOTHIRDS (math_const.h)
TWOTHIRDS = 2.0 / 3.0
#: the Scene settings of a typical contact of this law (the contract tests use them)
EXAMPLE = {}


def lammps_keywords(p):
    """LAMMPS's ``twisting marshall`` keywords (its coefficients come from the tangential model)."""
    return "twisting marshall"


def max_torque(p, N, a):
    """The slider's limit (2/3) mu a N [N m] (parameter row p, normal force N [N], contact radius a [m])."""
    return TWOTHIRDS * p[P_MU] * a * N


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    """Torque on body 1 (x, y, z) [N m] from the relative spin w = w1 - w2 [rad/s]: M n."""
    k = 0.5 * params[row, P_K_TWIST] * a * a
    damp = 0.5 * params[row, P_GAMMA_TWIST] * a * a
    mu = TWOTHIRDS * params[row, P_MU] * a
    W = wx * nx + wy * ny + wz * nz
    M = spring_dashpot_slider(H, c, b, k, damp, mu, W, dt, N)
    return M * nx, M * ny, M * nz


def configure(scene, p):
    """k_t of LAMMPS's tangential model (the tangential law's ``lammps_k_t``: Mindlin's 8 G* of ``tangential
    mindlin NULL``, or the linear law's k_t)."""
    p[P_K_TWIST] = scene.tangential_law.lammps_k_t(p)
    p[P_GAMMA_TWIST] = 0.0


def describe(scene, p):
    return dict(twist_k_t=p[P_K_TWIST])
