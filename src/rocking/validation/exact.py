"""Independent references for the manual: the published closed forms evaluated, and an exact
integration of Housner's nonlinear rocking equation with SciPy.

Nothing here imports the library's solver or its models: the integrator below is a separate,
plain implementation (``scipy.integrate.solve_ivp`` with event location, an impact map and an
energy argument after the motion ends), so that a fault in the library cannot hide in both.

Conventions (those of ``docs/theory/derivation.md``): b, h are the half-width and half-height
(m); R = √(b² + h²) (m); α = atan(b/h) (rad); p = √(3g/4R) (1/s); θ > 0 leans the block towards
+x about its +x corner; a floor acceleration towards +x (a_g > 0, m/s²) starts rocking with
θ < 0. Housner's equation about the active corner s = ±1 is

    θ̈ = −p² [ sin(sα − θ) + (a_g/g)·cos(sα − θ) ].
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import integrate, optimize

#: gravity of every table in the manual, m/s² (the oracle tables of tests/oracles/closed_forms.py)
G = 9.81


@dataclass(frozen=True)
class Block:
    """A uniform rectangular block. b, h: half-width and half-height, m; g: gravity, m/s²."""

    b: float
    h: float
    g: float = G

    @property
    def R(self) -> float:
        """Half-diagonal, m."""
        return math.hypot(self.b, self.h)

    @property
    def alpha(self) -> float:
        """Slenderness atan(b/h), rad."""
        return math.atan2(self.b, self.h)

    @property
    def tan_alpha(self) -> float:
        return self.b / self.h

    @property
    def p(self) -> float:
        """Frequency parameter √(3g/4R), 1/s."""
        return math.sqrt(3.0 * self.g / (4.0 * self.R))

    @property
    def eta(self) -> float:
        """Housner's ratio θ̇⁺/θ̇⁻ = 1 − 1.5 sin²α (angular momentum about the new corner)."""
        return 1.0 - 1.5 * math.sin(self.alpha) ** 2

    @property
    def io_per_mass(self) -> float:
        """I_O/m = (4/3)R², m²."""
        return 4.0 / 3.0 * self.R**2


def slender(alpha: float, h: float = 1.0, g: float = G) -> Block:
    """The block of slenderness α (rad) and half-height h (m)."""
    return Block(h * math.tan(alpha), h, g)


# ------------------------------------------------------------------ published closed forms
def uplift_acceleration(block: Block, a_v: float = 0.0) -> float:
    """Floor acceleration at which rocking starts, (g + a_v)·tan α, m/s² (Housner 1963 for
    a_v = 0)."""
    return (block.g + a_v) * block.tan_alpha


def quarter_period_linear(block: Block, theta0: float) -> float:
    """Housner's small-angle time (s) from release at rest at θ0 to the first impact:
    (1/p)·arccosh(1/(1 − θ0/α)); the period is four times this."""
    return math.acosh(1.0 / (1.0 - theta0 / block.alpha)) / block.p


def quarter_period_exact(block: Block, theta0: float) -> float:
    """The same time (s) for the nonlinear equation, by quadrature of the energy integral

        t1 = ∫₀^θ0 dθ / √(2p²[cos(α − θ0) − cos(α − θ)]).

    With θ = θ0 − w² the integrand becomes 2w/√(4p² sin(α − θ0 + w²/2)·sin(w²/2)), which is
    bounded at w = 0 (it tends to 2/(p·√(2 sin(α − θ0)))), so plain Gauss–Kronrod converges.
    """
    a, p = block.alpha, block.p

    def f(w: float) -> float:
        if w == 0.0:
            return 2.0 / (p * math.sqrt(2.0 * math.sin(a - theta0)))
        return 2.0 * w / (p * math.sqrt(4.0 * math.sin(a - theta0 + 0.5 * w * w) * math.sin(0.5 * w * w)))

    val, _ = integrate.quad(f, 0.0, math.sqrt(theta0), epsabs=0.0, epsrel=1e-13, limit=200)
    return val


def peaks_exact(block: Block, theta0: float, n: int, eta: float | None = None) -> list[float]:
    """Peak rotations θ1..θn (rad) of free rocking from rest at θ0: energy is conserved in flight
    and the kinetic energy is multiplied by η² at each impact."""
    eta = block.eta if eta is None else eta
    ca, out, th = math.cos(block.alpha), [], theta0
    for _ in range(n):
        th = block.alpha - math.acos(ca + eta * eta * (math.cos(block.alpha - th) - ca))
        out.append(th)
    return out


def peaks_linear(block: Block, theta0: float, n: int, eta: float | None = None) -> list[float]:
    """Housner's small-angle peaks (rad): θn/α = 1 − √(1 − η^(2n)·[1 − (1 − θ0/α)²])."""
    eta = block.eta if eta is None else eta
    x0 = 1.0 - theta0 / block.alpha
    return [block.alpha * (1.0 - math.sqrt(1.0 - eta ** (2 * k) * (1.0 - x0 * x0))) for k in range(1, n + 1)]


def velocity_step_exact(block: Block) -> float:
    """Floor velocity step (m/s) that just overturns a block at rest: angular momentum about the
    corner gives I_O·θ̇0 = m·V·h, and θ̇0 must lift the centre of mass over the corner,
    ½ I_O θ̇0² = m g R (1 − cos α). Hence V = √((8/3) g R (1 − cos α)) / cos α."""
    a = block.alpha
    return math.sqrt(8.0 / 3.0 * block.g * block.R * (1.0 - math.cos(a))) / math.cos(a)


def velocity_step_linear(block: Block) -> float:
    """The small-angle form of the same limit, g·α/p (m/s)."""
    return block.g * block.alpha / block.p


def double_impulse_exact(block: Block, eta: float | None = None) -> float:
    """Velocity amplitude V (m/s) of the double impulse (+V, then −V just after the first impact)
    that just overturns: the block returns to the impact with the kick's angular velocity, the
    impact multiplies it by η and the second kick adds the same again, so V = V_step/(1 + η)."""
    eta = block.eta if eta is None else eta
    return velocity_step_exact(block) / (1.0 + eta)


def rectangle_threshold_linear(p_td: float) -> float:
    """Smallest a/(g α) of a rectangular pulse of duration t_d that overturns without an impact,
    for the small-angle equation: 1/(1 − e^(−p t_d)). Argument: p·t_d."""
    return 1.0 / (1.0 - math.exp(-p_td))


def one_sine_mode1_linear(beta: float) -> float:
    """Smallest a_p/(g α) of the one-sine pulse a_p·sin(ω_p t + ψ), sin ψ = gα/a_p, that
    overturns without an impact (mode 1), small-angle equation: 1/sin ψ with ψ the root of
    (cos ψ − β sin ψ)·exp((2π − ψ)/β) = 1 on 0 < ψ < atan(1/β), β = ω_p/p."""
    def f(psi: float) -> float:
        return (math.cos(psi) - beta * math.sin(psi)) * math.exp((2.0 * math.pi - psi) / beta) - 1.0

    psi = optimize.brentq(f, 1e-300, math.atan(1.0 / beta), xtol=1e-17, rtol=1e-15, maxiter=400)
    return 1.0 / math.sin(psi)


def one_cosine_mode1_linear(beta: float) -> float:
    """Smallest a_p/(g α) of the one-cosine pulse a_p·cos(ω_p t), 0 ≤ t ≤ 2π/ω_p, that overturns
    without an impact, small-angle equation: (1 + β²)/(1 − e^(−2π/β))."""
    return (1.0 + beta * beta) / (1.0 - math.exp(-2.0 * math.pi / beta))


def one_sine_linear_response(A: float, beta: float) -> tuple[float, float]:
    """Closed-form solution of the small-angle equation x'' = x − 1 + A·sin(βτ + ψ) (x = |θ|/α,
    τ = p·t, sin ψ = 1/A so that rocking starts at τ = 0; free motion x'' = x − 1 after the pulse
    ends at τ_e = (2π − ψ)/β). Returns (peak x before the first impact, τ of the first impact);
    τ = inf if x never returns to 0 (the block overturns)."""
    psi = math.asin(1.0 / A)
    k = 1.0 / (1.0 + beta * beta)
    c1, c2 = -1.0 + A * math.sin(psi) * k, A * beta * math.cos(psi) * k
    te = (2.0 * math.pi - psi) / beta

    def x(t: float) -> float:
        if t <= te:
            return 1.0 - A * k * math.sin(beta * t + psi) + c1 * math.cosh(t) + c2 * math.sinh(t)
        xe, ve = x(te), dx(te)
        return 1.0 + (xe - 1.0) * math.cosh(t - te) + ve * math.sinh(t - te)

    def dx(t: float) -> float:
        if t <= te:
            return -A * k * beta * math.cos(beta * t + psi) + c1 * math.sinh(t) + c2 * math.cosh(t)
        xe, ve = x(te), dx(te)
        return (xe - 1.0) * math.sinh(t - te) + ve * math.cosh(t - te)

    grid = np.linspace(1e-9, te + 20.0, 200001)
    vel = np.array([dx(t) for t in grid])
    turn = np.flatnonzero((vel[:-1] > 0) & (vel[1:] <= 0))
    if turn.size == 0:
        return math.inf, math.inf
    t_peak = optimize.brentq(dx, grid[turn[0]], grid[turn[0] + 1], xtol=1e-15, rtol=1e-15)
    peak = x(t_peak)
    if peak >= 1.0:
        return peak, math.inf
    pos = np.array([x(t) for t in grid])
    after = np.flatnonzero((grid[:-1] > t_peak) & (pos[:-1] > 0) & (pos[1:] <= 0))
    if after.size == 0:
        return peak, math.inf
    t1 = optimize.brentq(x, grid[after[0]], grid[after[0] + 1], xtol=1e-15, rtol=1e-15)
    return peak, t1


def newmark_rectangle(A_over_g: float, N_over_g: float, t0: float, g: float = G) -> float:
    """Newmark (1965): sliding (m) of a block with resistance N·g under a rectangular floor pulse
    A·g lasting t0 (s): u = V²/(2gN)·(1 − N/A), V = A·g·t0. Requires A > N."""
    V = A_over_g * g * t0
    return V * V / (2.0 * g * N_over_g) * (1.0 - N_over_g / A_over_g)


def shenton_mu_rock(b: float, h: float, lam: float) -> float:
    """Friction (–) a uniform rectangle needs for pure rocking (rather than slide-rock) to start
    under a constant floor acceleration λ·g above its uplift threshold b/h: the ratio of the
    corner's horizontal to vertical reaction at the onset of rocking,
    [λ(4b² + h²) + 3bh] / [(b² + 4h²) + 3λbh]."""
    return (lam * (4 * b * b + h * h) + 3 * b * h) / ((b * b + 4 * h * h) + 3 * lam * b * h)


def shenton_mode(b: float, h: float, mu: float, lam: float) -> str:
    """Shenton's initiation mode under a constant λ·g from rest: "rest", "slide", "rock" or
    "slide-rock" (μ = μs = μk)."""
    t = b / h
    if lam <= min(mu, t):
        return "rest"
    if mu < t:
        return "slide"  # the sliding block passes on μg < g·b/h: it cannot also start to rock
    return "rock" if mu >= shenton_mu_rock(b, h, lam) else "slide-rock"


# ----------------------------------------------------------- exact integration (nonlinear)
@dataclass(frozen=True)
class Motion:
    """A floor acceleration a_g(t) (m/s²) on [0, end] (s), zero afterwards."""

    accel: Callable[[float], float]
    end: float


def sine_pulse(a_p: float, omega: float, psi: float) -> Motion:
    """a_p·sin(ω t + ψ) on 0 ≤ t ≤ (2π − ψ)/ω (m/s², rad/s, rad)."""
    return Motion(lambda t: a_p * math.sin(omega * t + psi), (2.0 * math.pi - psi) / omega)


def cosine_pulse(a_p: float, omega: float) -> Motion:
    """a_p·cos(ω t) on 0 ≤ t ≤ 2π/ω."""
    return Motion(lambda t: a_p * math.cos(omega * t), 2.0 * math.pi / omega)


def rectangle(a: float, width: float) -> Motion:
    """a on 0 ≤ t < width."""
    return Motion(lambda t: a, width)


@dataclass
class Outcome:
    """Result of :func:`rock`: did the block overturn (|θ| reach π/2), after how many impacts,
    at which times (s), and the turning-point amplitudes |θ| (rad) met on the way."""

    overturned: bool
    impacts: int
    impact_times: list[float] = field(default_factory=list)
    turns: list[float] = field(default_factory=list)


def rock(block: Block, motion: Motion, *, eta: float | None = None, theta0: float = 0.0,
         theta_dot0: float = 0.0, stop_after_impacts: int | None = None, rest_velocity: float = 1e-6,
         free_time: float | None = None, rtol: float = 1e-11, atol: float = 1e-13) -> Outcome:
    """Integrate Housner's nonlinear equation from (θ0, θ̇0) at t = 0 under ``motion``.

    * At rest, rocking starts when |a_g| exceeds g·tan α, about the corner s = −sgn(a_g).
    * An impact (θ back to 0) multiplies θ̇ by η (Housner's by default) and switches the corner;
      below ``rest_velocity`` (rad/s) the block is back at rest.
    * Once the motion has ended the floor is still and the energy per unit mass
      E = ½(I_O/m)θ̇² + gR·cos(α − |θ|) can only fall, at impacts. Below gR (the energy of the
      balance point |θ| = α) the block stays on its side of that point: it settles if inside,
      falls if outside. Above it, it falls if it moves outwards; moving inwards it reaches an
      impact, keeps η² of its kinetic energy, and the test repeats. That decides the outcome
      without integrating the free motion.

    ``stop_after_impacts``: stop (not overturned) once that many impacts have happened.
    ``free_time`` (s): integrate the free motion for that long instead of deciding it by energy
    (to time the impacts after the motion); the outcome is then that seen within it.
    """
    eta = block.eta if eta is None else eta
    g, a, p2 = block.g, block.alpha, block.p**2
    thr = g * block.tan_alpha
    t, th, thd = 0.0, float(theta0), float(theta_dot0)
    s = 0 if (th == 0.0 and thd == 0.0) else int(math.copysign(1, th if th != 0.0 else thd))
    out = Outcome(False, 0)

    def impact() -> bool:
        """Apply the impact map at θ = 0; True when the caller must stop."""
        nonlocal s, thd
        out.impacts += 1
        thd *= eta
        s = -s
        if abs(thd) < rest_velocity:
            s, thd = 0, 0.0
        return stop_after_impacts is not None and out.impacts >= stop_after_impacts

    t_stop = motion.end if free_time is None else motion.end + free_time
    while True:
        if t >= motion.end and free_time is None:
            return _free_outcome(block, th, thd, s, eta, out, stop_after_impacts)
        if t >= t_stop:
            return out
        if s == 0:
            if t >= motion.end:
                return out  # at rest on a still floor
            t_up = _uplift_time(motion, t, thr)
            if t_up is None:
                return out
            t, th, thd = t_up, 0.0, 0.0
            s = -1 if motion.accel(min(t_up + 1e-12, motion.end)) > 0 else 1
        sgn = s
        free = t >= motion.end  # the floor is still: a_g = 0
        seg_end = t_stop if free else motion.end

        def rhs(_t, y, sgn=sgn, free=free):
            phi = sgn * a - y[0]
            return (y[1], -p2 * (math.sin(phi) + (0.0 if free else motion.accel(_t) / g) * math.cos(phi)))

        def ev_impact(_t, y, sgn=sgn):
            return sgn * y[0]

        def ev_fall(_t, y, sgn=sgn):
            return sgn * y[0] - 0.5 * math.pi

        def ev_turn(_t, y):
            return y[1]

        ev_impact.terminal, ev_impact.direction = True, -1
        ev_fall.terminal, ev_fall.direction = True, 1
        sol = integrate.solve_ivp(rhs, (t, seg_end), (th, thd), method="DOP853", rtol=rtol, atol=atol,
                                  events=(ev_impact, ev_fall, ev_turn))
        # a start from rest (θ̇ = 0) is not a turning point
        out.turns.extend(abs(float(y[0])) for tt, y in zip(sol.t_events[2], sol.y_events[2]) if tt > t)
        if sol.t_events[1].size:
            out.overturned = True
            return out
        if sol.t_events[0].size:
            t = float(sol.t_events[0][0])
            th, thd = 0.0, float(sol.y_events[0][0][1])
            out.impact_times.append(t)
            if impact():
                return out
            continue
        t, th, thd = seg_end, float(sol.y[0, -1]), float(sol.y[1, -1])


def _free_outcome(block: Block, th: float, thd: float, s: int, eta: float, out: Outcome,
                  stop_after_impacts: int | None) -> Outcome:
    """Outcome of the free motion on a still floor, by the energy argument of :func:`rock`."""
    if s == 0:
        return out
    gR, a, k = block.g * block.R, block.alpha, 0.5 * block.io_per_mass
    kin = k * thd * thd
    pot = gR * math.cos(a - abs(th))
    outside = abs(th) > a  # beyond the balance point |θ| = α, where gravity pulls outwards
    while True:
        if kin + pot < gR:
            # cannot cross the balance point: trapped inside (rocks and settles) or outside (falls)
            out.overturned = outside
            return out
        if s * thd >= 0.0:
            out.overturned = True
            return out
        outside = False
        # moving back to θ = 0 with energy to spare: the impact keeps η² of the kinetic energy
        kin = eta * eta * (kin + pot - gR * math.cos(a))
        pot = gR * math.cos(a)
        out.impacts += 1
        s = -s  # θ̇ keeps its sign through the impact: now moving outwards about the new corner
        if stop_after_impacts is not None and out.impacts >= stop_after_impacts:
            return out


def composite_rocking(mass: float, io: float, b: float, h_c: float, a: float, width: float,
                      g: float = G) -> tuple[float, float]:
    """Any rigid body rocking about a floor corner, set rocking from rest by a rectangular pulse.

    ``mass`` (kg) and ``io``, its moment of inertia about the corner (kg·m²); its centre of mass
    ``b`` (m) sideways from the corner and ``h_c`` (m) above it; the floor accelerates by ``a``
    (m/s², away from the corner, a > g·b/h_c) for ``width`` s, then stops. Housner's equation for
    a general body, θ ≥ 0 the tilt, R_c = √(b² + h_c²), α_c = atan(b/h_c):

        I_O θ̈ = m R_c [a_g cos(α_c − θ) − g sin(α_c − θ)],   a_g = a for t < width, else 0.

    Returns (the time θ is back at 0, s; the largest θ on the way, rad)."""
    if not a * h_c > g * b:
        raise ValueError(f"a = {a!r} m/s² does not lift the body (g·b/h_c = {g * b / h_c!r})")
    r_c, a_c = math.hypot(b, h_c), math.atan2(b, h_c)

    def rhs(t, y, ag):
        return (y[1], mass * r_c * (ag * math.cos(a_c - y[0]) - g * math.sin(a_c - y[0])) / io)

    def back(_t, y, _ag):
        return y[0]

    back.terminal, back.direction = True, -1
    kw = dict(method="DOP853", rtol=1e-12, atol=1e-14)
    # the pulse's end is a kink of θ̈: integrate the two pieces separately
    during = integrate.solve_ivp(rhs, (0.0, width), (0.0, 0.0), args=(a,), **kw)
    after = integrate.solve_ivp(rhs, (width, width + 1e3), during.y[:, -1], args=(0.0,), events=back,
                                dense_output=True, **kw)
    if not after.t_events[0].size:
        raise ValueError("the body does not come back to θ = 0 (it overturns)")
    t_back = float(after.t_events[0][0])
    # the peak is where θ̇ changes sign after the pulse (θ̇ > 0 at its end)
    turn = optimize.brentq(lambda t: after.sol(t)[1], width, t_back)
    return t_back, float(after.sol(turn)[0])


def _uplift_time(motion: Motion, t_from: float, threshold: float) -> float | None:
    """First t ≥ t_from (s) in the motion where |a_g| exceeds ``threshold`` (m/s²), or None."""
    n = 4000
    ts = np.linspace(t_from, motion.end, n + 1)
    over = np.array([abs(motion.accel(x)) - threshold for x in ts])
    idx = np.flatnonzero(over > 0.0)
    if idx.size == 0:
        return None
    i = int(idx[0])
    if i == 0:
        return t_from
    return optimize.brentq(lambda x: abs(motion.accel(x)) - threshold, ts[i - 1], ts[i], xtol=1e-15)


# ------------------------------------------------------------------------------- bisection
def threshold(fails: Callable[[float], bool], guess: float, *, rtol: float = 1e-7, step: float = 1.02,
              max_expand: int = 200) -> tuple[float, float]:
    """The bracket [lo, hi] (hi − lo ≤ rtol·hi) around the smallest x near ``guess`` where
    ``fails`` turns true: expand geometrically from the guess until the outcome changes, then
    bisect. Raises RuntimeError when no change is found."""
    lo = hi = guess
    f = fails(guess)
    for _ in range(max_expand):
        if f:
            lo = lo / step
            if not fails(lo):
                break
            hi = lo
        else:
            hi = hi * step
            if fails(hi):
                break
            lo = hi
    else:
        raise RuntimeError(f"no change of outcome found near {guess!r}")
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        if fails(mid):
            hi = mid
        else:
            lo = mid
    return lo, hi


def midpoint(bracket: tuple[float, float]) -> float:
    return 0.5 * (bracket[0] + bracket[1])


def find(fails: Callable[[float], bool], guess: float, *, fallback: float | None = None, **kw) -> float:
    """Midpoint of :func:`threshold` from ``guess`` (or ``fallback`` when the guess is not a
    finite number); NaN when no change of outcome is found, so that the row that shows it
    turns red instead of the whole manual stopping."""
    if not math.isfinite(guess):
        if fallback is None or not math.isfinite(fallback):
            return math.nan
        guess = fallback
    try:
        return midpoint(threshold(fails, guess, **kw))
    except RuntimeError:
        return math.nan
