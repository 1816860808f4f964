"""Independent closed-form oracles for the test suite (O1-O20, as re-derived for this project).

Pure functions on numpy/scipy only.  This module never imports ``rocking``: the library is
tested *against* it.

Conventions:

* SI units, angles in radians.
* b, h: half-width and half-height of a uniform rectangle; R = sqrt(b^2 + h^2);
  alpha = atan(b/h); I_O = (4/3) m R^2 (about a base corner); p = sqrt(3 g / (4 R)).
* eta = theta_dot+ / theta_dot- (velocity ratio); eta^2 is Housner's energy ratio.
* theta > 0 means the block pivots on its +x corner and leans to +x.
* g defaults to 9.81 m/s^2, the value of every table these oracles were checked against.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import integrate, optimize

G_TABLES = 9.81  #: gravity used in all oracle tables, m/s^2


# ---------------------------------------------------------------------------------------------
# O2: block constants
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BlockConstants:
    """Housner constants of a uniform rectangular block (O2).  Units: m, rad, s^-1."""

    b: float  #: half-width, m
    h: float  #: half-height, m
    g: float  #: gravity, m/s^2
    R: float  #: half-diagonal, m
    alpha: float  #: slenderness atan(b/h), rad
    tan_alpha: float  #: b/h, -
    g_tan_alpha: float  #: static rocking threshold g tan(alpha), m/s^2
    p: float  #: frequency parameter sqrt(3g/(4R)), 1/s
    eta: float  #: Housner velocity ratio 1 - 1.5 sin^2(alpha), -
    eta2: float  #: Housner energy ratio eta^2, -
    I_O_per_mass: float  #: I_O/m = (4/3) R^2, m^2
    J_G_per_mass: float  #: J_G/m = R^2/3, m^2

    def I_O(self, m: float) -> float:
        """Moment of inertia about a base corner, (4/3) m R^2 (O2).  kg m^2."""
        return m * self.I_O_per_mass


def block_constants(b: float, h: float, g: float = G_TABLES) -> BlockConstants:
    """O2 - Housner constants of a uniform rectangle with half-width b and half-height h.

    Returns R (m), alpha (rad), tan(alpha), g tan(alpha) (m/s^2), p = sqrt(3g/(4R)) (1/s),
    eta = 1 - 1.5 sin^2(alpha), eta^2, I_O/m = 4/3 R^2 and J_G/m = R^2/3 (m^2).
    """
    R = math.hypot(b, h)
    alpha = math.atan2(b, h)
    eta = 1.0 - 1.5 * math.sin(alpha) ** 2
    return BlockConstants(
        b=b, h=h, g=g, R=R, alpha=alpha, tan_alpha=b / h, g_tan_alpha=g * b / h,
        p=math.sqrt(3.0 * g / (4.0 * R)), eta=eta, eta2=eta * eta,
        I_O_per_mass=4.0 / 3.0 * R * R, J_G_per_mass=R * R / 3.0,
    )


def housner_eta(b: float, h: float) -> float:
    """O2 - Housner's angular-velocity ratio eta = 1 - 1.5 sin^2(alpha) (dimensionless).

    Equivalent to (I_O - 2 m b^2)/I_O for a uniform rectangle.
    """
    return 1.0 - 1.5 * b * b / (b * b + h * h)


# ---------------------------------------------------------------------------------------------
# O1: onset thresholds
# ---------------------------------------------------------------------------------------------
def rocking_onset_acceleration(b: float, h: float, g: float = G_TABLES, a_v: float = 0.0) -> float:
    """O1 - base acceleration (m/s^2) above which a block at rest on a stuck base starts rocking:
    (g + a_v) tan(alpha).  The pivot is s = -sign(a_g)."""
    return (g + a_v) * b / h


def sliding_onset_acceleration(mu_s: float, g: float = G_TABLES, a_v: float = 0.0) -> float:
    """O1/O12 - base acceleration (m/s^2) above which a block at rest slips: mu_s (g + a_v)."""
    return mu_s * (g + a_v)


# ---------------------------------------------------------------------------------------------
# O3: free rocking, time to first impact
# ---------------------------------------------------------------------------------------------
def _release_integral(alpha: float, theta0: float, inertia_ratio) -> float:
    """int_0^theta0 sqrt(inertia_ratio(theta) / (2 [cos(alpha-theta0) - cos(alpha-theta)])) dtheta.

    The integrand has an integrable 1/sqrt singularity at theta = theta0.  With
    theta = theta0 sin(psi), psi in [0, pi/2], it becomes smooth:
      cos(alpha-theta0) - cos(alpha-theta) = 2 sin(alpha - (theta0+theta)/2) sin((theta0-theta)/2),
      theta0 - theta = 2 theta0 sin^2(pi/4 - psi/2),
    and cos(psi) / sqrt(theta0 - theta) stays finite.
    """
    if not 0.0 < theta0 < math.pi:
        raise ValueError("theta0 must be positive")

    def integrand(psi: float) -> float:
        th = theta0 * math.sin(psi)
        gap = 2.0 * theta0 * math.sin(math.pi / 4.0 - psi / 2.0) ** 2  # theta0 - theta >= 0
        if gap == 0.0:
            # limit psi -> pi/2: cos(psi) ~ sqrt(2 gap/theta0)
            # D ~ 2 sin(alpha - theta0) gap/2 = sin(alpha-theta0) gap
            return theta0 * math.sqrt(2.0 / theta0) * math.sqrt(
                inertia_ratio(theta0) / (2.0 * math.sin(alpha - theta0)))
        D = 2.0 * math.sin(alpha - 0.5 * (theta0 + th)) * math.sin(0.5 * gap)
        return theta0 * math.cos(psi) * math.sqrt(inertia_ratio(th) / (2.0 * D))

    val, _err = integrate.quad(integrand, 0.0, math.pi / 2.0, epsabs=1e-14, epsrel=1e-13, limit=200)
    return val


def free_rocking_t1_linearised(b: float, h: float, theta0: float, g: float = G_TABLES) -> float:
    """O3 [lin] - Housner's time (s) from release at rest at theta0 (0 < theta0 < alpha) to the
    first impact: t1 = (1/p) arccosh(1/(1 - theta0/alpha)).  The linearised period is 4 t1."""
    c = block_constants(b, h, g)
    return math.acosh(1.0 / (1.0 - theta0 / c.alpha)) / c.p


def free_rocking_t1_exact(b: float, h: float, theta0: float, g: float = G_TABLES) -> float:
    """O3 [exact] - time (s) from release at rest at theta0 to the first impact of the nonlinear
    Housner block: t1 = int_0^theta0 dtheta / sqrt(2 p^2 [cos(alpha-theta0) - cos(alpha-theta)]),
    evaluated by scipy.integrate.quad after the substitution theta = theta0 sin(psi)."""
    c = block_constants(b, h, g)
    return _release_integral(c.alpha, theta0, lambda th: 1.0 / c.p ** 2)


def free_rocking_impact_velocity(b: float, h: float, theta0: float, g: float = G_TABLES) -> float:
    """O3/O5 [exact] - |theta_dot| (rad/s) at the first impact after release at rest at theta0:
    sqrt(2 p^2 [cos(alpha - theta0) - cos(alpha)])."""
    c = block_constants(b, h, g)
    return math.sqrt(2.0 * c.p ** 2 * (math.cos(c.alpha - theta0) - math.cos(c.alpha)))


# ---------------------------------------------------------------------------------------------
# O4: amplitude decay
# ---------------------------------------------------------------------------------------------
def amplitude_sequence_exact(alpha: float, eta: float, theta0: float, n: int) -> np.ndarray:
    """O4 [exact] - peak rotations theta_1..theta_n (rad) of free rocking released at theta0,
    from the energy recursion cos(alpha - theta_{k+1}) - cos(alpha) = eta^2 [cos(alpha - theta_k)
    - cos(alpha)] (kinetic energy times eta^2 at each impact, energy conserved in between)."""
    out = np.empty(n)
    th = theta0
    ca = math.cos(alpha)
    for k in range(n):
        th = alpha - math.acos(ca + eta * eta * (math.cos(alpha - th) - ca))
        out[k] = th
    return out


def amplitude_sequence_linearised(alpha: float, eta: float, theta0: float, n: int) -> np.ndarray:
    """O4 [lin] - Housner's linearised peaks theta_1..theta_n (rad):
    theta_k/alpha = 1 - sqrt(1 - eta^(2k) [1 - (1 - theta0/alpha)^2])."""
    k = np.arange(1, n + 1)
    x0 = 1.0 - theta0 / alpha
    return alpha * (1.0 - np.sqrt(1.0 - eta ** (2 * k) * (1.0 - x0 * x0)))


# ---------------------------------------------------------------------------------------------
# O6 / O7: velocity steps
# ---------------------------------------------------------------------------------------------
def vcrit_exact(b: float, h: float, g: float = G_TABLES) -> float:
    """O6 [exact] - ground-velocity step V (m/s) that just overturns a block at rest without an
    impact: I_O theta_dot0 = m V h and (1/2) I_O theta_dot0^2 = m g R (1 - cos alpha) give
    V_crit = sqrt((8/3) g R (1 - cos alpha)) / cos alpha."""
    c = block_constants(b, h, g)
    return math.sqrt(8.0 / 3.0 * g * c.R * (1.0 - math.cos(c.alpha))) / math.cos(c.alpha)


def vcrit_linearised(b: float, h: float, g: float = G_TABLES) -> float:
    """O6 [lin] - linearised critical velocity step g alpha / p (m/s)."""
    c = block_constants(b, h, g)
    return g * c.alpha / c.p


def vcrit_double(b: float, h: float, g: float = G_TABLES, eta: float | None = None) -> float:
    """O7 [exact] - double impulse (+V, then -V right at the first impact): V_crit/(1 + eta)
    (m/s).  eta defaults to Housner's."""
    if eta is None:
        eta = housner_eta(b, h)
    return vcrit_exact(b, h, g) / (1.0 + eta)


# ---------------------------------------------------------------------------------------------
# O8 / O9 / O9b: pulse thresholds (linearised, mode 1 = overturning without impact)
# ---------------------------------------------------------------------------------------------
def rect_pulse_threshold(p_td: float) -> float:
    """O8 [lin] - minimum a/(g alpha) of a one-sided rectangular acceleration pulse of duration
    t_d that overturns without impact: 1/(1 - exp(-p t_d)).  Argument: p*t_d (dimensionless)."""
    return 1.0 / (1.0 - math.exp(-p_td))


def one_sine_psi(beta: float) -> float:
    """O9 [lin] - phase psi (rad) of the critical one-sine pulse a_p sin(w_p t + psi),
    0 <= t <= (2 pi - psi)/w_p, beta = w_p/p: the root of
    (cos psi - beta sin psi) exp((2 pi - psi)/beta) = 1 on 0 < psi < atan(1/beta) (unique, the
    left side decreases from exp(2 pi/beta) > 1 to 0)."""
    f = lambda psi: (math.cos(psi) - beta * math.sin(psi)) * math.exp((2.0 * math.pi - psi) / beta) - 1.0
    hi = math.atan(1.0 / beta)
    return optimize.brentq(f, 1e-300, hi, xtol=1e-16, rtol=4 * np.finfo(float).eps, maxiter=500)


def one_sine_threshold(beta: float) -> float:
    """O9 [lin] - minimum a_p/(g alpha) for mode-1 overturning under the one-sine pulse:
    1/sin(psi) with psi from :func:`one_sine_psi`.  beta = w_p/p."""
    return 1.0 / math.sin(one_sine_psi(beta))


def one_cosine_threshold(beta: float) -> float:
    """O9b [lin] - minimum a_p/(g alpha) for mode-1 overturning (no impact) under
    a_g = a_p cos(w_p t), 0 <= t <= 2 pi/w_p: (1 + beta^2)/(1 - exp(-2 pi/beta))."""
    return (1.0 + beta * beta) / (1.0 - math.exp(-2.0 * math.pi / beta))


# ---------------------------------------------------------------------------------------------
# O11: harmonic (1,1) symmetric orbit, linearised
# ---------------------------------------------------------------------------------------------
def _o11_consts(beta: float, eta: float):
    lam = math.pi / beta
    P = math.tanh(lam / 2.0)
    Q = 1.0 / P
    amp = math.hypot(Q * (1.0 + eta), beta * (1.0 - eta))
    return P, Q, amp


def harmonic_11_amin(beta: float, eta: float) -> float:
    """O11 [lin] - minimum A = a/(g alpha) for which the symmetric one-impact-per-half-period
    orbit exists under a_g = a sin(w t + tau), beta = w/p:
    A_min = (1 + beta^2) P (1 - eta) / sqrt(Q^2 (1+eta)^2 + beta^2 (1-eta)^2),
    with P = tanh(pi/(2 beta)), Q = 1/P."""
    P, Q, amp = _o11_consts(beta, eta)
    return (1.0 + beta * beta) * P * (1.0 - eta) / amp


def harmonic_11_orbits(beta: float, eta: float, A: float) -> list[tuple[float, float]]:
    """O11 [lin] - the (1,1) orbits for A = a/(g alpha) >= A_min.

    Returns [(tau, phidot0_over_p), ...] sorted by tau in [0, 2 pi): tau solves
    K [Q (1+eta) sin tau + beta (1-eta) cos tau] = -P (1 - eta) with K = A/(1 + beta^2), and
    phidot0/p = P + Q K sin tau + beta K cos tau is the post-impact velocity of phi = theta/alpha
    divided by p (dimensionless).  Empty list if A < A_min.
    """
    P, Q, amp = _o11_consts(beta, eta)
    K = A / (1.0 + beta * beta)
    c = -P * (1.0 - eta) / (K * amp)
    if abs(c) > 1.0:
        return []
    delta = math.atan2(beta * (1.0 - eta), Q * (1.0 + eta))  # Q(1+eta) sin + beta(1-eta) cos = amp sin(tau + delta)
    out = []
    for x in {math.asin(c), math.pi - math.asin(c)}:
        tau = (x - delta) % (2.0 * math.pi)
        v = P + Q * K * math.sin(tau) + beta * K * math.cos(tau)
        out.append((tau, v))
    return sorted(out)


# ---------------------------------------------------------------------------------------------
# O12 / O13 / O14: sliding block
# ---------------------------------------------------------------------------------------------
def newmark_rect_pulse(A_over_g: float, N_over_g: float, t0: float, g: float = G_TABLES) -> float:
    """O12 [exact] - Newmark (1965): sliding displacement (m) of a block with friction resistance
    N*g under a rectangular base pulse A*g of duration t0 (s): u = V^2/(2 g N) (1 - N/A),
    V = A g t0.  Requires A > N."""
    V = A_over_g * g * t0
    return V * V / (2.0 * g * N_over_g) * (1.0 - N_over_g / A_over_g)


@dataclass(frozen=True)
class HalfSineSliding:
    """O13 result: slip start t1 (s), stop t2 (s), final relative displacement u (m, magnitude)."""

    t1: float
    t2: float
    u: float


def half_sine_sliding(A_p: float, mu: float, T_p: float, g: float = G_TABLES) -> HalfSineSliding:
    """O13 [exact] - block with mu_s = mu_k = mu under a_g = A_p sin(pi t/T_p) on [0, T_p].

    Slip starts at t1 = (T_p/pi) asin(mu g/A_p); the (magnitude of the) relative velocity is
    v = (A_p/w)(cos w t1 - cos w t) - mu g (t - t1) during the pulse (w = pi/T_p) and decreases at
    mu g after it; t2 is the root of v(t2) = 0 (brentq) and u = int_{t1}^{t2} v dt (quad).
    A_p in m/s^2, T_p in s.
    """
    w = math.pi / T_p
    mg = mu * g
    if A_p <= mg:
        return HalfSineSliding(float("nan"), float("nan"), 0.0)
    t1 = math.asin(mg / A_p) / w

    def v(t: float) -> float:
        if t <= T_p:
            return A_p / w * (math.cos(w * t1) - math.cos(w * t)) - mg * (t - t1)
        vT = A_p / w * (math.cos(w * t1) - math.cos(w * T_p)) - mg * (T_p - t1)
        return vT - mg * (t - T_p)

    vT = v(T_p)
    if vT > 0.0:
        t2 = T_p + vT / mg
    else:
        # v rises then falls back to zero inside the pulse: bracket the zero after the maximum
        tm = T_p - t1  # symmetric point: dv/dt = A_p sin(w t) - mg vanishes at t1 and T_p - t1
        t2 = optimize.brentq(v, tm, T_p, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    pts = [T_p] if t1 < T_p < t2 else None
    u, _ = integrate.quad(v, t1, t2, points=pts, epsabs=1e-14, epsrel=1e-13, limit=200)
    return HalfSineSliding(t1=t1, t2=t2, u=u)


def harmonic_nonstop_threshold(mu_s: float, mu_k: float | None = None, g: float = G_TABLES) -> float:
    """O14 [exact] - amplitude A (m/s^2) of a_g = A sin(w t) above which a sliding block never
    sticks in steady state: sqrt((mu_s g)^2 + (pi mu_k g/2)^2); = mu g sqrt(1 + pi^2/4) for
    mu_s = mu_k = mu."""
    if mu_k is None:
        mu_k = mu_s
    return math.hypot(mu_s * g, math.pi * mu_k * g / 2.0)


def harmonic_sliding_peak_to_peak(A: float, omega: float, mu_k: float, g: float = G_TABLES) -> float:
    """O14 [exact] - steady-state peak-to-peak relative displacement (m) of non-stop sliding under
    a_g = A sin(w t) (A in m/s^2, w in rad/s): (2A/w^2) sqrt(1 - (pi mu_k g/(2A))^2)."""
    return 2.0 * A / omega ** 2 * math.sqrt(1.0 - (math.pi * mu_k * g / (2.0 * A)) ** 2)


# ---------------------------------------------------------------------------------------------
# O15: Shenton map under a constant base acceleration lambda*g
# ---------------------------------------------------------------------------------------------
def shenton_mu_req(b: float, h: float, lam: float) -> float:
    """O15 - floor friction (dimensionless) needed for pure rocking to start from rest under a
    constant base acceleration lam*g (uniform rectangle):
    mu_req = [lam (4b^2 + h^2) + 3 b h] / [(b^2 + 4 h^2) + 3 lam b h].
    Equals b/h at lam = b/h and tends to (4b^2 + h^2)/(3bh) as lam -> inf."""
    if math.isinf(lam):
        return (4 * b * b + h * h) / (3 * b * h)
    return (lam * (4 * b * b + h * h) + 3 * b * h) / ((b * b + 4 * h * h) + 3 * lam * b * h)


def shenton_regime(b: float, h: float, mu_s: float, lam: float, mu_k: float | None = None) -> str:
    """O15 - regime ("rest" | "slide" | "rock" | "slide-rock") of a block at rest when a
    constant base acceleration lam*g (lam >= 0) is applied.

    The first consistent regime in the order rest, rock (stuck base), slide (block upright),
    slide-rock is returned (fewest moving degrees of freedom; stick before slide):
      rest        lam <= mu_s and lam <= b/h;
      rock        lam > b/h and mu_req(lam) <= mu_s;
      slide       lam > mu_s and mu_k <= b/h (a sliding block accelerates at mu_k g);
      slide-rock  otherwise.
    With mu_k = mu_s (the default) this is exactly Shenton's rule (O15).
    """
    if mu_k is None:
        mu_k = mu_s
    lam = abs(lam)
    tan_a = b / h
    if lam <= mu_s and lam <= tan_a:
        return "rest"
    if lam > tan_a and shenton_mu_req(b, h, lam) <= mu_s:
        return "rock"
    if lam > mu_s and mu_k <= tan_a:
        return "slide"
    return "slide-rock"


# ---------------------------------------------------------------------------------------------
# O17: statue that can never rock
# ---------------------------------------------------------------------------------------------
def statue_never_rocks(b: float, h: float, mu_s: float, mu_k: float) -> bool:
    """O17 [exact] - True if tan(alpha) >= mu_s >= mu_k: under any horizontal excitation starting
    from rest, the statue on a Coulomb pedestal can never start rocking."""
    return b / h >= mu_s >= mu_k


# ---------------------------------------------------------------------------------------------
# O18 / O19: two-block stack
# ---------------------------------------------------------------------------------------------
def eta_stack_frictionless(b: float, h: float, m1: float, m2: float) -> float:
    """O18 [exact] - theta_dot+/theta_dot- of a statue impact on a pedestal sliding on a
    frictionless floor (zero horizontal floor impulse):
    (I_O - 2 m2 b^2 - m2^2 h^2/M) / (I_O - m2^2 h^2/M), M = m1 + m2, I_O = (4/3) m2 R^2."""
    M = m1 + m2
    I_O = 4.0 / 3.0 * m2 * (b * b + h * h)
    k = m2 * m2 * h * h / M
    return (I_O - 2.0 * m2 * b * b - k) / (I_O - k)


@dataclass(frozen=True)
class FrictionlessRelease:
    """O18 result (statue released at rest at theta0 > 0, pedestal on a frictionless floor)."""

    t1: float  #: time to first impact, s
    theta_dot: float  #: statue angular velocity just before impact, rad/s (negative)
    u: float  #: pedestal displacement at impact, m
    u_dot: float  #: pedestal velocity just before impact, m/s
    eta_stack: float  #: impact velocity ratio with a frictionless floor
    eta_housner: float  #: Housner's ratio for comparison
    p_eff: float  #: linearised frequency sqrt(m2 g R/(I_O - m2^2 R^2 cos^2 alpha/M)), 1/s


def frictionless_release(b: float, h: float, m1: float, m2: float, theta0: float,
                         g: float = G_TABLES) -> FrictionlessRelease:
    """O18 [exact] - statue on a pedestal, frictionless floor, no ground motion, released at rest
    at 0 < theta0 < alpha (pivot +x).

    Horizontal momentum M u_dot + m2 R cos(phi) theta_dot = 0 (phi = alpha - theta) keeps the
    centre of mass fixed; energy (1/2) I_eff theta_dot^2 + m2 g R cos(phi) = const with
    I_eff = I_O - m2^2 R^2 cos^2(phi)/M.  t1 by quadrature; at impact
    theta_dot = -sqrt(2 m2 g R (cos(alpha - theta0) - cos alpha)/I_eff(0)),
    u = (m2/M) (b - R sin(alpha - theta0)), u_dot = -(m2 h/M) theta_dot.
    """
    M = m1 + m2
    R = math.hypot(b, h)
    alpha = math.atan2(b, h)
    I_O = 4.0 / 3.0 * m2 * R * R

    def I_eff(th: float) -> float:
        return I_O - (m2 * R * math.cos(alpha - th)) ** 2 / M

    K = m2 * g * R
    t1 = _release_integral(alpha, theta0, lambda th: I_eff(th) / K)
    thd = -math.sqrt(2.0 * K * (math.cos(alpha - theta0) - math.cos(alpha)) / I_eff(0.0))
    u = m2 / M * (b - R * math.sin(alpha - theta0))
    ud = -m2 * h / M * thd
    p_eff = math.sqrt(K / (I_O - (m2 * h) ** 2 / M))
    return FrictionlessRelease(t1=t1, theta_dot=thd, u=u, u_dot=ud,
                               eta_stack=eta_stack_frictionless(b, h, m1, m2),
                               eta_housner=housner_eta(b, h), p_eff=p_eff)


def impact_friction_needed(b: float, h: float, r: float | None = None) -> float:
    """O19 [exact] - |Fx|/Fy (dimensionless) that the floor (and the statue-pedestal interface)
    must supply for an impact theta_dot+ = r theta_dot- with the pedestal held still:
    (h/b)(1 - r)/(1 + r); with Housner's r = eta this is 1.5 sin(a) cos(a)/(2 - 1.5 sin^2(a))."""
    if r is None:
        r = housner_eta(b, h)
    return h / b * (1.0 - r) / (1.0 + r)


# ---------------------------------------------------------------------------------------------
# O20: rocking frame (bonus)
# ---------------------------------------------------------------------------------------------
def rocking_frame(b: float, h: float, gamma: float) -> tuple[float, float]:
    """O20 - rocking frame with cap-beam mass ratio gamma: (p_hat/p, eta_hat) with
    p_hat/p = sqrt((1+2 gamma)/(1+3 gamma)) and
    eta_hat = (1 - 1.5 sin^2 alpha + 3 gamma cos 2 alpha)/(1 + 3 gamma)."""
    a = math.atan2(b, h)
    return (math.sqrt((1 + 2 * gamma) / (1 + 3 * gamma)),
            (1 - 1.5 * math.sin(a) ** 2 + 3 * gamma * math.cos(2 * a)) / (1 + 3 * gamma))


# ---------------------------------------------------------------------------------------------
# Seed cases 9a/9b (derivation.md, "What a test may assert", items 1-2)
# ---------------------------------------------------------------------------------------------
def seed_first_stop_phase(A: float, mu_k: float, g: float = G_TABLES) -> float:
    """Seed 9a/9b - phase w*t (rad) at which a pedestal that starts sliding at t = 0+ under
    a_g = A cos(w t) (statue at rest) first stops: the positive root of mu_k g (w t) = A sin(w t)
    (relative velocity u_dot = -(A/w) sin(w t) + mu_k g t).  Valid if mu_k g < A."""
    f = lambda x: A * math.sin(x) - mu_k * g * x
    return optimize.brentq(f, 1e-6, math.pi, xtol=1e-15, rtol=4 * np.finfo(float).eps)


def seed_reslip_phase(A: float, mu_s: float, g: float = G_TABLES) -> float:
    """Seed 9a - phase w*t (rad) after the first stop at which the stuck pedestal (statue at rest)
    slips again under A cos(w t): acos(-mu_s g/A)."""
    return math.acos(-mu_s * g / A)


def seed_rock_onset_phase(A: float, b: float, h: float, g: float = G_TABLES) -> float:
    """Seed 9b - phase w*t (rad) after the first stop at which the statue on the stuck pedestal
    starts rocking under A cos(w t): acos(-g tan(alpha)/A)."""
    return math.acos(-g * (b / h) / A)
