"""Closed-form results used to set up and to check simulations (Johnson 1985, section 11.4; Thornton 1997; Tsuji, Tanaka & Ishida 1992).

Plain Python functions of SI quantities; none of them integrates anything.
"""
import math

from ..errors import InputError

#: Smallest V_y / V_i of a thornton calibration from e_n (e_n ~ 0.003 there).
THORNTON_MIN_VELOCITY_RATIO = 1e-12
#: t_c = HERTZ_TC_FACTOR * delta_max / V  (Johnson 1985, section 11.4)
HERTZ_TC_FACTOR = 2.9433


def hertz_overlap_coefficients(E_star, R_star, m_star):
    """(c1, c2) = (15 m*, 16 E* sqrt(R*)) of delta_max = (c1 V^2 / c2)^(2/5)."""
    return 15.0 * m_star, 16.0 * E_star * math.sqrt(R_star)


def hertz_max_overlap(E_star, R_star, m_star, v):
    """delta_max = (15 m* V^2 / (16 E* sqrt(R*)))^(2/5) [m] for an elastic impact at normal speed v."""
    c1, c2 = hertz_overlap_coefficients(E_star, R_star, m_star)
    return (c1 * v * v / c2) ** 0.4


def hertz_contact_time(E_star, R_star, m_star, v):
    """t_c = 2.9433 delta_max / V [s] (Johnson 1985)."""
    return HERTZ_TC_FACTOR * hertz_max_overlap(E_star, R_star, m_star, v) / v


def hertz_force(E_star, R_star, delta):
    """Hertz's normal force N = (4/3) E* sqrt(R*) delta^(3/2) [N] at the overlap delta [m] (a number or an
    array, delta >= 0; Johnson 1985, eq. 4.23)."""
    return 4.0 / 3.0 * E_star * math.sqrt(R_star) * delta**1.5


def hertz_max_force(E_star, R_star, m_star, v):
    """F_max = (4/3) E* sqrt(R*) delta_max^(3/2) [N]."""
    return hertz_force(E_star, R_star, hertz_max_overlap(E_star, R_star, m_star, v))


def thornton_yield_overlap(E_star, R_star, p_y):
    """delta_y = R* (pi p_y / (2 E*))^2 [m] (Thornton 1997, J. Appl. Mech. 64:383)."""
    return R_star * (math.pi * p_y / (2.0 * E_star)) ** 2


def thornton_yield_force(E_star, R_star, p_y):
    """F_y = pi^3 p_y^3 R*^2 / (6 E*^2) [N]."""
    return math.pi**3 * p_y**3 * R_star**2 / (6.0 * E_star**2)


def thornton_yield_velocity(E_star, R_star, m_star, p_y):
    """V_y = sqrt(pi^5 p_y^5 R*^3 / (30 E*^4 m*)) [m/s]: normal speed at which yield starts."""
    return math.sqrt(math.pi**5 * p_y**5 * R_star**3 / (30.0 * E_star**4 * m_star))


def thornton_yield_pressure_for_velocity(E_star, R_star, m_star, v_y):
    """Inverse of ``thornton_yield_velocity``: p_y [Pa] giving yield velocity v_y."""
    return (30.0 * E_star**4 * m_star * v_y * v_y / (math.pi**5 * R_star**3)) ** 0.2


def thornton_restitution_ratio(r):
    """Thornton (1997) e_n as a function of r = V_y / V_i (e_n = 1 for r >= 1)."""
    if r >= 1.0:
        return 1.0
    return (math.sqrt(6.0 * math.sqrt(3.0) / 5.0 * (1.0 - r * r / 6.0))
            * (r / (r + 2.0 * math.sqrt(6.0 / 5.0 - r * r / 5.0))) ** 0.25)


def thornton_restitution(E_star, R_star, m_star, p_y, v):
    """Thornton's closed-form e_n [-] at normal impact speed v [m/s]."""
    return thornton_restitution_ratio(thornton_yield_velocity(E_star, R_star, m_star, p_y) / v)


def thornton_yield_pressure_for_restitution(E_star, R_star, m_star, e_n, v):
    """Calibrate p_y [Pa] so that Thornton's law gives restitution ``e_n`` at normal speed ``v``
    (inverts the closed form; 0 < e_n < 1)."""
    if not 0.0 < e_n < 1.0:
        raise InputError(f"e_n = {e_n:g} cannot be calibrated with the thornton law: valid range (0, 1)")
    e_min = thornton_restitution_ratio(THORNTON_MIN_VELOCITY_RATIO)
    if e_n < e_min:
        raise InputError(f"e_n = {e_n:g} cannot be calibrated with the thornton law: valid range [{e_min:.3g}, 1)")
    from scipy.optimize import brentq

    r = brentq(lambda r: thornton_restitution_ratio(r) - e_n, THORNTON_MIN_VELOCITY_RATIO, 1.0, xtol=1e-15,
               rtol=1e-15)
    return thornton_yield_pressure_for_velocity(E_star, R_star, m_star, r * v)


def linear_damping_ratio(e_n):
    """gamma of the unclamped linear spring-dashpot for restitution e_n: e_n = exp(-gamma pi / sqrt(1-gamma^2))."""
    if e_n >= 1.0:
        return 0.0
    if e_n <= 0.0:
        return 1.0
    L = math.log(e_n)
    return -L / math.sqrt(math.pi**2 + L * L)


def linear_restitution(gamma):
    """e_n of the unclamped linear spring-dashpot with damping ratio gamma < 1."""
    return math.exp(-gamma * math.pi / math.sqrt(1.0 - gamma * gamma))


def linear_contact_time(k_n, m_star, gamma=0.0):
    """Contact duration pi / (omega0 sqrt(1 - gamma^2)) of the linear spring-dashpot [s]."""
    return math.pi / (math.sqrt(k_n / m_star) * math.sqrt(1.0 - gamma * gamma))


def thornton_max_overlap(E_star, R_star, m_star, p_y, v):
    """Largest overlap delta* [m] of a Thornton impact at normal speed v, from the energy balance
    m* V^2 / 2 = (2/5) F_y delta_y + F_y x + pi p_y R* x^2 / 2 with x = delta* - delta_y (Hertz below V_y)."""
    d_y = thornton_yield_overlap(E_star, R_star, p_y)
    F_y = thornton_yield_force(E_star, R_star, p_y)
    if v <= thornton_yield_velocity(E_star, R_star, m_star, p_y):
        return hertz_max_overlap(E_star, R_star, m_star, v)
    A = 0.5 * math.pi * p_y * R_star
    C = 0.4 * F_y * d_y - 0.5 * m_star * v * v
    return d_y + (-F_y + math.sqrt(F_y * F_y - 4.0 * A * C)) / (2.0 * A)


def thornton_unloading(E_star, R_star, p_y, delta_star):
    """(F*, R_p, delta_p) of Thornton's unloading curve from the largest overlap delta* > delta_y:
    F* = F_y + pi p_y R* (delta* - delta_y), R_p = (4 E*/(3 F*)) ((2 F* + F_y)/(2 pi p_y))^(3/2),
    delta_p = delta* - (3 F* / (4 E* sqrt(R_p)))^(2/3)."""
    d_y = thornton_yield_overlap(E_star, R_star, p_y)
    F_y = thornton_yield_force(E_star, R_star, p_y)
    F = F_y + math.pi * p_y * R_star * (delta_star - d_y)
    R_p = 4.0 * E_star / (3.0 * F) * ((2.0 * F + F_y) / (2.0 * math.pi * p_y)) ** 1.5
    d_p = delta_star - (3.0 * F / (4.0 * E_star * math.sqrt(R_p))) ** (2.0 / 3.0)
    return F, R_p, d_p


def truncated_line_load(x, a, R_star, E_star, p_t):
    """MDR line load q(x) [N/m] of the Hertz pressure of contact radius a [m] truncated at p_t [Pa],
    p(r) = min(p0 sqrt(1 - r^2/a^2), p_t) with p0 = 2 E* a / (pi R*) (Thornton 1997, plastic loading).

    q is the Abel transform 2 int_x^a r p(r) / sqrt(r^2 - x^2) dr (Popov & Hess 2015): Hertz's
    (E*/R*)(a^2 - x^2) less, for |x| < c = a sqrt(1 - k^2), k = p_t/p0, the part cut off,
    (p0 / a) (a^2 - x^2) arctan(sqrt(c^2 - x^2) / (k a)) - p_t sqrt(c^2 - x^2).
    2 int_0^a q dx = pi a^2 p_t (1 - k^2/3), Thornton's force at the overlap a^2/R*."""
    import numpy as np

    x = np.abs(np.asarray(x, dtype=float))
    p0 = 2.0 * E_star * a / (math.pi * R_star)
    q = np.where(x < a, E_star / R_star * (a * a - x * x), 0.0)
    k = p_t / p0
    if k >= 1.0:
        return q
    c2 = a * a * (1.0 - k * k)
    r = np.sqrt(np.maximum(c2 - x * x, 0.0))
    cut = p0 / a * (a * a - x * x) * np.arctan2(r, k * a) - p_t * r
    return q - np.where(x * x < c2, cut, 0.0)


def twist_no_slip_moment(G_c, a, beta):
    """M = (16/3) G_c a^3 beta [N m]: the twist of a contact of radius a with no slip, 1/G_c = 1/G1 + 1/G2
    (Johnson 1985, eq. 7.43; the rigid flat punch of Reissner & Sagoci 1944 with both compliances)."""
    return 16.0 / 3.0 * G_c * a**3 * beta


def twist_full_slip_moment(mu, N, a):
    """M = (3 pi / 16) mu N a [N m]: the circumferential traction mu p of a Hertz contact (Lubkin 1951)."""
    return 3.0 * math.pi / 16.0 * mu * N * a


def _lubkin_J(u):
    """int_0^u t^2 (K - E)(1 - t^2) dt (complete elliptic integrals of parameter m)."""
    from scipy.integrate import quad
    from scipy.special import ellipe, ellipk
    return quad(lambda t: t * t * (ellipk(1.0 - t * t) - ellipe(1.0 - t * t)), 0.0, u, limit=200,
                epsabs=1e-14, epsrel=1e-12)[0]


def lubkin_twist(c_over_a, G_c, mu, N, a):
    """(beta [rad], M [N m]) of a Hertz contact twisted monotonically from rest at constant N until its
    stick radius is c (Lubkin 1951): beta = 3 mu N (K - E) / (4 pi a^2 G_c) at the parameter
    m = 1 - c^2/a^2, and M = (16/3) G_c beta c^3 + (12/pi) mu N a (pi^2/64 - J(c/a)) with
    J(u) = int_0^u t^2 (K - E)(1 - t^2) dt: the stick disc twisted rigidly, the annulus at mu p
    (superposition of flat punches, Jaeger 1995)."""
    from scipy.special import ellipe, ellipk
    if not 0.0 < c_over_a <= 1.0:
        raise InputError(f"c_over_a = {c_over_a!r} (stick radius / contact radius) must be in (0, 1]")
    m = 1.0 - c_over_a**2
    beta = 3.0 * mu * N * (ellipk(m) - ellipe(m)) / (4.0 * math.pi * a * a * G_c)
    M = 16.0 / 3.0 * G_c * beta * (c_over_a * a) ** 3 + 12.0 / math.pi * mu * N * a * (
        math.pi**2 / 64.0 - _lubkin_J(c_over_a))
    return beta, M


def lubkin_moment(beta, G_c, mu, N, a):
    """M [N m] of Lubkin's loading curve at the twist beta >= 0 (``lubkin_twist`` solved for c)."""
    from scipy.optimize import brentq
    if beta <= 0.0:
        return 0.0
    c = brentq(lambda u: lubkin_twist(u, G_c, mu, N, a)[0] - beta, 1e-300, 1.0, xtol=1e-15, rtol=1e-14)
    return lubkin_twist(c, G_c, mu, N, a)[1]
