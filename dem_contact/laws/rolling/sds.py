"""LAMMPS's ``rolling sds`` engine model: a spring-dashpot-slider on the rolling displacement (Luding 2008;
the rolling velocity of Wang et al. 2015, Particuology 23, 49, eq. 31), with LAMMPS's arithmetic and
history (22 Jul 2025 release, GRANULAR package, ``GranSubModRollingSDS``).

Rolling resistance is not contact mechanics of smooth spheres: two smooth elastic spheres roll on each
other without a resisting moment (apart from hysteresis, which no such spring models). This is the
optional, named engine model that DEM users expect (for non-spherical or rough grains), offered for
comparison with LAMMPS and for moving a simulation between the two.

With the rolling velocity v = R* (w x n), w = w1 - w2, and the rolling displacement h (three history
slots, a vector in global axes), each step

    if |h . n| k_roll > 1e-10 mu_roll N:  h turned into the tangent plane keeping its length
    h += v dt;  F = -k_roll h - gamma_roll v
    if |F| > mu_roll N:  h = -(mu_roll N / (k_roll |F|)) F - (gamma_roll / k_roll) v,  F scaled to mu_roll N
                         (if h = 0: F = 0 and h kept)

and the torque on body 1 is R* (n x F) (body 2 takes the opposite); the largest is mu_roll R* N. N is the
normal force of the step (LAMMPS's F_ncrit; see ``laws.twist.sds``). LAMMPS writes n from body 2 to body
1; here n points from body 1 to body 2, so v, h and F are LAMMPS's negated (exactly) and the torque is the
same. The rolling displacement looks the same from either body: it keeps its sign when the bodies are
swapped, and ``rotate_history`` turns it.
"""
import math

from numba import njit

from ..declare import RSTAR, Param, non_negative, positive
from ..slots import P_GAMMA_ROLL, P_K_ROLL, P_MU_ROLL, P_RSTAR
from ..twist.sds import configure_sds
from ..vector import JIT

NAME, FAMILY = "sds", "rolling"
SOURCE = "LAMMPS rolling sds: spring-dashpot-slider on the rolling displacement (Wang et al. 2015, eq. 31)"
PARAMETERS = (Param("k_roll", "P_K_ROLL", "rolling spring k_roll", "N/m"),
              Param("gamma_roll", "P_GAMMA_ROLL", "rolling dashpot gamma_roll", "N s/m"),
              Param("mu_roll", "P_MU_ROLL", "rolling slider mu_roll (the limit of the pseudo-force is mu_roll N)", "-"),
              RSTAR)
STATE = ("h_x", "h_y", "h_z")
#: LAMMPS's rolling sds coefficients (all required)
OPTIONS = (positive("k_roll", "rolling sds: spring", "N/m", short="rolling spring"),
           non_negative("gamma_roll", "rolling sds: dashpot", "N s/m", short="rolling dashpot"),
           non_negative("mu_roll", "rolling sds: Coulomb limit per unit normal force", "", short="rolling slider"))
VECTOR_SLOTS = 3
VECTORS = (0,)
#: LAMMPS's EPSILON of gran_sub_mod_rolling.cpp (the history is turned into the tangent plane only above it)
EPSILON = 1e-10
#: the Scene settings of a typical contact of this law (a 2 mm steel sphere; the contract tests use them)
EXAMPLE = {"k_roll": 5e5, "gamma_roll": 1e-3, "mu_roll": 0.1}


def lammps_keywords(p):
    """LAMMPS's ``rolling sds`` keywords on the parameter row p."""
    return f"rolling sds {float(p[P_K_ROLL])!r} {float(p[P_GAMMA_ROLL])!r} {float(p[P_MU_ROLL])!r}"


def max_torque(p, N, a):
    """The slider's limit mu_roll R* N [N m] (parameter row p, normal force N [N])."""
    return p[P_MU_ROLL] * p[P_RSTAR] * N


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    """Torque on body 1 (x, y, z) [N m] from the relative spin w = w1 - w2 [rad/s]: R* (n x F)."""
    k = params[row, P_K_ROLL]
    gamma = params[row, P_GAMMA_ROLL]
    R = params[row, P_RSTAR]
    crit = params[row, P_MU_ROLL] * N
    vx = R * (wy * nz - wz * ny)
    vy = R * (wz * nx - wx * nz)
    vz = R * (wx * ny - wy * nx)
    hx = H[c, b]
    hy = H[c, b + 1]
    hz = H[c, b + 2]
    hn = hx * nx + hy * ny + hz * nz
    if math.fabs(hn) * k > EPSILON * crit:
        # LAMMPS's rotate_rescale_vec: into the tangent plane, length kept
        mag = math.sqrt(hx * hx + hy * hy + hz * hz)
        hx -= hn * nx
        hy -= hn * ny
        hz -= hn * nz
        prj = math.sqrt(hx * hx + hy * hy + hz * hz)
        s = mag / prj if prj > 0.0 else 0.0
        hx *= s
        hy *= s
        hz *= s
    hx += dt * vx
    hy += dt * vy
    hz += dt * vz
    fx = -k * hx + -gamma * vx
    fy = -k * hy + -gamma * vy
    fz = -k * hz + -gamma * vz
    mag_f = math.sqrt(fx * fx + fy * fy + fz * fz)
    if mag_f > crit:
        if math.sqrt(hx * hx + hy * hy + hz * hz) != 0.0:
            k_inv = 1.0 / k
            f_inv = 1.0 / mag_f
            s = -crit * k_inv * f_inv
            g = -gamma * k_inv
            hx = s * fx + g * vx
            hy = s * fy + g * vy
            hz = s * fz + g * vz
            s = crit * f_inv
            fx *= s
            fy *= s
            fz *= s
        else:
            fx = fy = fz = 0.0
    H[c, b] = hx
    H[c, b + 1] = hy
    H[c, b + 2] = hz
    return R * (ny * fz - nz * fy), R * (nz * fx - nx * fz), R * (nx * fy - ny * fx)


def configure(scene, p):
    configure_sds(scene, p, "rolling='sds'", "LAMMPS's rolling sds coefficients", OPTIONS, (P_K_ROLL, P_GAMMA_ROLL,
                                                                                        P_MU_ROLL))


def describe(scene, p):
    return dict(k_roll=p[P_K_ROLL], gamma_roll=p[P_GAMMA_ROLL], mu_roll=p[P_MU_ROLL])
