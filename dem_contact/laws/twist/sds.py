"""LAMMPS's ``twisting sds`` engine model: a spring-dashpot-slider on the relative spin about the normal
(Marshall 2009, J. Comput. Phys. 228, 1541, eqs. 30, 34, 44), with LAMMPS's arithmetic and history (22 Jul
2025 release, GRANULAR package, ``GranSubModTwistingSDS``).

Twisting resistance of this kind is not contact mechanics of smooth spheres: Hertz, Mindlin and
Deresiewicz give no such spring (the torsion of a Hertz contact is Lubkin's, with a slip annulus). This
is the optional, named engine model that DEM users expect, offered for comparison with LAMMPS and for
moving a simulation between the two.

With W = (w1 - w2) . n the twist rate and xi the twist angle (one history slot), each step

    xi += W dt;  M = -k_twist xi - gamma_twist W;  Mc = mu_twist N
    if |M| > Mc:  xi = (Mc s - gamma_twist W) / k_twist,  M = -Mc s,   s = sign(W)

and the torque on body 1 is M n (body 2 takes -M n). N is the normal force of the step (LAMMPS's F_ncrit,
the magnitude of the elastic plus damping normal force; here the normal force clamped at 0, which is the
same for undamped laws). LAMMPS's quirks are kept, as its results are to be reproduced: the slider takes
the sign of the spin rate, not of the trial moment (a spin that reverses while the spring is past the
limit flips the moment), and W = 0 past the limit erases the spring. LAMMPS writes n from body 2 to body
1; here n points from body 1 to body 2, so W, xi and M are LAMMPS's negated (exactly) and the torque is
the same. The twist angle looks the same from either body: it keeps its sign when the bodies are swapped.
"""
import math

from numba import njit

from ...errors import InputError
from ..declare import Param, non_negative, positive
from ..slots import P_GAMMA_TWIST, P_K_TWIST, P_MU_TWIST
from ..vector import JIT

NAME, FAMILY = "sds", "twist"
SOURCE = "LAMMPS twisting sds: spring-dashpot-slider (Marshall 2009, eqs. 30, 34, 44)"
#: the spring and the dashpot, whose slots the marshall twist sets from the tangential law
K = Param("k_twist", "P_K_TWIST", "twist spring k_twist (marshall: the tangential coefficient k_t it is scaled from)",
          "N m/rad")
GAMMA = Param("gamma_twist", "P_GAMMA_TWIST", "twist dashpot gamma_twist (marshall: the tangential damping it is "
              "scaled from)", "N m s/rad")
PARAMETERS = (K, GAMMA, Param("mu_twist", "P_MU_TWIST", "twist slider mu_twist (the limit is mu_twist N)", "m"))
STATE = ("xi",)
#: LAMMPS's twisting sds coefficients (all required)
OPTIONS = (positive("k_twist", "twist sds: spring", "N m/rad", short="twist spring"),
           non_negative("gamma_twist", "twist sds: dashpot", "N m s/rad", short="twist dashpot"),
           non_negative("mu_twist", "twist sds: Coulomb limit per unit normal force", "m", short="twist slider"))
VECTOR_SLOTS = 1
#: the Scene settings of a typical contact of this law (a 2 mm steel sphere; the contract tests use them)
EXAMPLE = {"k_twist": 1.0, "gamma_twist": 1e-6, "mu_twist": 1e-4}


def lammps_keywords(p):
    """LAMMPS's ``twisting sds`` keywords on the parameter row p."""
    return f"twisting sds {float(p[P_K_TWIST])!r} {float(p[P_GAMMA_TWIST])!r} {float(p[P_MU_TWIST])!r}"


def max_torque(p, N, a):
    """The slider's limit mu_twist N [N m] (parameter row p, normal force N [N])."""
    return p[P_MU_TWIST] * N


@njit(inline="always", **JIT)
def spring_dashpot_slider(H, c, b, k, damp, mu, W, dt, N):
    """The twist moment M of LAMMPS's ``gran_twisting`` core (Marshall 2009, eqs. 30, 34, 44) on the twist
    angle in H[c, b], updated in place."""
    xi = H[c, b] + W * dt
    M = -k * xi - damp * W
    s = 1.0 if W > 0.0 else (-1.0 if W < 0.0 else 0.0)
    Mc = mu * N
    if math.fabs(M) > Mc:
        xi = (Mc * s - damp * W) / k
        M = -Mc * s
    H[c, b] = xi
    return M


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    """Torque on body 1 (x, y, z) [N m] from the relative spin w = w1 - w2 [rad/s]: M n."""
    W = wx * nx + wy * ny + wz * nz
    M = spring_dashpot_slider(H, c, b, params[row, P_K_TWIST], params[row, P_GAMMA_TWIST],
                              params[row, P_MU_TWIST], W, dt, N)
    return M * nx, M * ny, M * nz


def configure(scene, p):
    configure_sds(scene, p, "twist='sds'", "LAMMPS's twisting sds coefficients", OPTIONS, (P_K_TWIST, P_GAMMA_TWIST,
                                                                                       P_MU_TWIST))


def configure_sds(scene, p, law, source, options, slots):
    """Store the spring, dashpot and slider coefficients of a spring-dashpot-slider engine model (LAMMPS's
    twisting and rolling sds; the Options, checked by Scene, and their slots), InputError naming those
    missing."""
    missing = [o for o in options if getattr(scene, o) is None]
    if missing:
        raise InputError(f"{law} needs {', '.join(missing)} ({'; '.join(f'{o}: {o.describe()}' for o in options)}: "
                         f"{source})")
    for o, slot in zip(options, slots):
        p[slot] = getattr(scene, o)


def describe(scene, p):
    return dict(k_twist=p[P_K_TWIST], gamma_twist=p[P_GAMMA_TWIST], mu_twist=p[P_MU_TWIST])
