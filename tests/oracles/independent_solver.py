"""An independent hybrid solver of the statue-on-pedestal model (oracle for the compiled solver).

Nothing of the library's physics is used here. From ``rocking`` this module only *reads its
inputs*, by attribute, without importing anything:

* the system: ``statue.width/height/mass/restitution/friction``, ``pedestal.mass/friction``,
  ``friction.mu_s/mu_k``;
* the floor motion: ``acceleration(t)``, ``vertical_acceleration(t)``, ``duration``,
  ``breakpoints``;
* the options: ``gravity``, ``normal_force``, ``impact``, ``rtol``, ``atol``, ``max_step``,
  ``rest_velocity``, ``free_time_limit``, ``max_events``.

Everything else comes from elsewhere:

* the right-hand sides, the floor forces F and N of every regime: the sympy derivation
  ``oracles.lagrange.accelerations`` (Euler–Lagrange equations built from positions and energies);
* the impacts: the sympy impact maps ``lagrange.impact_coulomb`` / ``lagrange.impact_paper``;
* the guards, the regime selection, the transitions and the run length: written here from
  ``docs/theory/derivation.md`` §4–§6 and ``docs/verdicts.md`` (below);
* the numerics: SciPy's ``DOP853`` stepper (Hairer's 8(5,3) pair with its 7th-order dense
  output), driven step by step, and ``brentq`` on the dense output to locate events.

So a mistake in ``rocking.models`` (equations, forces, guards, mode selection) or in
``rocking.contact`` (impact laws) shows up as a disagreement with this solver, which the
integrator cross-check (``rocking.solver.crosscheck``, same physics, other numerics) cannot see.

Units: SI throughout (m, kg, s, rad; accelerations in m/s², forces in N, impulses in N·s).

The rules implemented
---------------------
State y = (u, u̇, θ, θ̇): pedestal displacement and velocity relative to the floor, statue
rotation and angular velocity. The regime is (σ, s): σ ∈ {0 stuck, ±1 sliding towards ±x},
s ∈ {0 statue at rest, ±1 rocking about its ±x corner}; names REST (0, 0), ROCK (0, ±1),
SLIDE (±1, 0), SLIDE_ROCK (±1, ±1), i.e. lagrange's stick-rest, stick-rock, slide-rest,
slide-rock.

Guards (derivation §4), each positive while its regime holds; the event is the first time one
reaches zero from above:

=============  ==========================  ==================  =========================
guard          value                       while               event
=============  ==========================  ==================  =========================
friction cone  μs·N − |F_req|               pedestal stuck      SLIP
stop           σ·u̇                          pedestal sliding    STOP
rocking onset  (g + a_v)·tan α − |a_g + ü|  statue at rest      UPLIFT
impact         s·θ                          statue rocking      IMPACT (or SETTLE)
exceed α       α − |θ|                      rocking, once       EXCEED_ALPHA (recorded only)
fall           π/2 − |θ|                    statue rocking      FALL (the run ends)
=============  ==========================  ==================  =========================

F_req and N are lagrange's F and N of the current regime (for "paper" normal force N = M·G).

Regime selection (derivation §5), at t = 0, after every event and at every breakpoint of the
floor motion. A body that moves keeps moving (a sliding pedestal keeps σ = sgn u̇, a rocking
statue keeps its pivot); for a body that does not move every option is a candidate: pedestal
σ ∈ {0, +1, −1} (only 0 if the floor has no friction), statue s ∈ {0, +1, −1}. Candidates are
tried in the order stick-rest, stick-rock, slide-rest, slide-rock (fewest moving degrees of
freedom, stick before slide, rest before rock) and the first *consistent* class is taken:

* stuck pedestal:          |F| ≤ μs·N;
* pedestal starting to slide: σ·ü > 0;
* statue at rest:          |a_g + ü| ≤ (g + a_v)·tan α;
* statue starting to rock: s·θ̈ > 0;
* always N > 0 (and a regular slide-rock matrix: lagrange raises on a Painlevé case).

Ties: the two "held" tests (stick, rest) accept a value within a relative 1e-12 of their bound,
and the held regime's guard then decides, from the dense output right after the instant, whether
the regime ends at once: a tie then shows as an event at that same instant (e.g. a type-A pulse
lifts the block at t = 0: REST, then UPLIFT at t = 0). The "starting" tests (σ·ü > 0, s·θ̈ > 0)
are strict. If two candidates of the first consistent class pass (both σ, or both s), which has
never been seen, the direction of derivation §4 is taken (σ = −sgn F_req of the stuck pedestal,
s = −sgn(a_g + ü)) and ``diagnostics["ambiguous"]`` counts it. If no candidate passes,
``diagnostics["inconsistent"]`` counts it and the first candidate in the order is taken (its
guard then ends it at once if it really is violated).

Transitions (derivation §4, §6):

* SLIP: the cone was left, so the pedestal slides with σ = −sgn(F_req) (no σ·ü test: it is 0 at
  the crossing when μk = μs); the statue is selected as above;
* UPLIFT: the onset threshold was crossed: the statue rocks with s = −sgn(a_g + ü) (no s·θ̈ test,
  s·θ̈ = 0 at the crossing); a stuck pedestal is selected again;
* STOP: u̇ = 0; the pedestal is selected again (stick, or a slip the other way at once: P12);
* IMPACT at θ = 0: θ := 0 and the impact map of ``options.impact`` gives u̇⁺ and θ̇⁺ and the new
  pivot; if |θ̇⁺| < ``rest_velocity`` the statue is at rest (SETTLE: θ̇ := 0; u̇ takes the map's
  u̇⁺, or 0 if |u̇⁺| < rest_velocity·(b + h), see below); then the pedestal (if u̇⁺ = 0) and the
  statue (if settled) are selected again. If θ goes the wrong way
  right after an UPLIFT (a tangency of the threshold), the impact guard fires at once with
  θ̇ ≈ 0: the map then leaves |θ̇⁺| < rest_velocity and the statue is back at rest (SETTLE);
* SETTLE closes a Zeno sequence of ever smaller impacts at its accumulation point, where θ̇ = 0.
  The kick the last impact would give the pedestal is then O(θ̇⁻) like the rest of the sequence,
  and a slide slower than rest_velocity·(b + h) is dropped with it (u̇⁺ := 0). Kept, it can start
  an endless cycle: the pedestal slides at ~1e-7 m/s, a statue at rest on a sliding pedestal
  must rock when μk > tan α, the pedestal stops, the statue falls back and settles, and again.
  A faster u̇⁺ stands: an impact that leaves |θ̇⁺| ≈ 0 on a pedestal sliding fast (a nearly
  plastic sliding impact) changes its slide for real;
* EXCEED_ALPHA: recorded once; FALL: the run ends, status "overturned";
* BREAKPOINT: at a breakpoint of the floor motion (a record sample, the end of a pulse or of
  the harmonic) the regime is selected again with the acceleration of the next piece; an event
  is recorded if it changes.

Run length (docs/verdicts.md): with ``duration`` the run lasts exactly that long; without it,
the motion plus at most ``free_time_limit`` of free motion, and it ends as soon as everything is
at rest (REST) at or after the end of the motion. A run that ends while anything moves has
status "still_moving".

Numerics: every smooth segment (between events and breakpoints) is integrated by SciPy's DOP853
stepper; the floor acceleration on a segment is evaluated strictly inside it (one ulp in from
each end), so a jump at a breakpoint is seen on the correct side. After each accepted step the
guards are sampled on the dense output (at least 8 points, at most ``guard_dt`` apart, plus
points at 10⁻³ and 10⁻² of the first step of a segment), so that a guard dipping below zero and
back within one step is seen; a crossing is located by ``brentq`` on the dense output. After an
event the first step is 10 µs, so the short flights of a chattering sequence fall inside the
sampled points. |θ| peaks are located where θ̇ changes sign between samples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import DOP853
from scipy.optimize import brentq

from . import lagrange

__all__ = ["simulate_independent", "IndependentEvent", "IndependentRun", "regime_name"]

TIE = 1e-12  # relative width of a tie in the held tests (stick, rest) and in the guards
GUARD_DT = 1e-3  # s: largest spacing of the guard samples inside a step
MIN_SAMPLES = 8  # guard samples per step, at least
FIRST_STEP_AFTER_EVENT = 1e-5  # s
_EPS = float(np.finfo(float).eps)

_NAMES = {(False, False): "REST", (False, True): "ROCK", (True, False): "SLIDE", (True, True): "SLIDE_ROCK"}
_KIND_OF_GUARD = {"cone": "SLIP", "stop": "STOP", "onset": "UPLIFT", "impact": "IMPACT",
                  "exceed": "EXCEED_ALPHA", "fall": "FALL"}


def regime_name(sig: int, s: int) -> str:
    """REST, ROCK, SLIDE or SLIDE_ROCK for pedestal σ and statue pivot s (the names of
    ``rocking.Regime``)."""
    return _NAMES[(sig != 0, s != 0)]


def _lagrange_regime(sig: int, s: int) -> str:
    return ("slide" if sig else "stick") + ("-rock" if s else "-rest")


def _sign(x: float) -> int:
    return 1 if x > 0.0 else (-1 if x < 0.0 else 0)


@dataclass
class IndependentEvent:
    """One event: time (s), kind (a name of ``rocking.EventKind``), regimes before and after
    (names of ``rocking.Regime``), u̇ (m/s) and θ̇ (rad/s) before and after."""

    time: float
    kind: str
    before: str
    after: str
    u_dot_before: float
    u_dot_after: float
    theta_dot_before: float
    theta_dot_after: float


@dataclass
class IndependentRun:
    """The result of :func:`simulate_independent`. Series on the grid k·save_dt (s): ``t`` (s),
    ``u`` (m), ``u_dot`` (m/s), ``theta`` (rad), ``theta_dot`` (rad/s), ``regime`` (names)."""

    t: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    regime: list
    events: list
    status: str
    overturn_time: float | None
    exceeded_alpha_time: float | None
    peak_rotation: float
    peak_sliding: float
    residual_sliding: float
    end_time: float
    diagnostics: dict = field(default_factory=dict)

    @property
    def overturned(self) -> bool:
        return self.status == "overturned"


class _Singular(Exception):
    """lagrange found the slide-rock system singular (Painlevé-type) at a state."""


class _Model:
    """The numbers of the system, and the physics, all through lagrange."""

    def __init__(self, system, options):
        statue, pedestal = system.statue, system.pedestal
        self.b, self.h = 0.5 * float(statue.width), 0.5 * float(statue.height)
        self.m2 = float(statue.mass)
        self.m1 = float(pedestal.mass) if pedestal is not None else 0.0
        friction = pedestal.friction if pedestal is not None else statue.friction
        self.can_slide = friction is not None
        self.mu_s = float(friction.mu_s) if self.can_slide else math.inf
        self.mu_k = float(friction.mu_k) if self.can_slide else 0.0
        self.g = float(options.gravity)
        self.alpha = math.atan2(self.b, self.h)
        self.tan_alpha = self.b / self.h
        self.restitution = None if statue.restitution is None else float(statue.restitution)
        self.impact = options.impact
        self.rest_velocity = float(options.rest_velocity)
        self.params = dict(b=self.b, h=self.h, m1=self.m1, m2=self.m2, g=self.g, mu_s=self.mu_s,
                           mu_k=self.mu_k, normal_force=options.normal_force)
        m = self.m1 + self.m2
        # Tie widths: a guard within its tie of zero at a segment start is "tied", and its sign
        # right after decides. Threshold guards: TIE times their natural scale (N, m/s²);
        # velocity and angle guards start on an exact 0, so a rounding-level width.
        self.tie = {
            "cone": TIE * (self.mu_s * m * self.g if self.can_slide else 1.0),
            "onset": TIE * self.g * self.tan_alpha,
            "stop": 1e-15,  # m/s; u̇ is set to exactly 0 where this guard starts on zero
            "impact": 1e-14 * self.alpha,  # θ is set to exactly 0; values below this are rounding
            "exceed": 0.0,
            "fall": 0.0,
        }

    def forces(self, sig, s, y, a, av):
        """(ü, θ̈, N, F) in regime (σ, s) at state y under floor accelerations (a, av), from the
        sympy derivation."""
        try:
            udd, thdd, n, f, _, _ = lagrange.accelerations(
                _lagrange_regime(sig, s), self.params, y, a, av, s=s if s else None, sigma=sig if sig else None)
        except ValueError as exc:
            raise _Singular(str(exc)) from None
        return udd, thdd, n, f

    def onset_margin(self, a, av, udd):
        """(g + a_v)·tan α − |a_g + ü|: positive while a statue at rest stays at rest."""
        return (self.g + av) * self.tan_alpha - abs(a + udd)

    def guard_names(self, sig, s, exceeded):
        names = []
        if sig == 0:
            if self.can_slide:
                names.append("cone")
        else:
            names.append("stop")
        if s == 0:
            names.append("onset")
        else:
            names.append("impact")
            if not exceeded:
                names.append("exceed")
            names.append("fall")
        return names

    def guards(self, sig, s, y, a, av, names):
        """Values of the guards ``names`` of regime (σ, s) at one state."""
        out = []
        need_forces = ("cone" in names) or ("onset" in names)
        if need_forces:
            udd, _, n, f = self.forces(sig, s, y, a, av)
        for name in names:
            if name == "cone":
                out.append(self.mu_s * n - abs(f))
            elif name == "stop":
                out.append(sig * y[1])
            elif name == "onset":
                out.append(self.onset_margin(a, av, udd))
            elif name == "impact":
                out.append(s * y[2])
            elif name == "exceed":
                out.append(self.alpha - abs(y[2]))
            else:
                out.append(0.5 * math.pi - abs(y[2]))
        return out

    # ---------------------------------------------------------------- regime selection (§5)
    def select(self, y, s_now, a, av, forced_sig=0, forced_s=0):
        """(σ, s, status) for state y; ``s_now`` is the pivot of a rocking statue (0 at rest);
        ``forced_sig``/``forced_s``: the direction an event has just imposed (SLIP, UPLIFT).
        status: "ok", "ambiguous" or "inconsistent"."""
        ud = y[1]
        if forced_sig:
            ped = [(forced_sig, False)]  # (σ, must pass the slip test)
        elif ud != 0.0:
            ped = [(_sign(ud), False)]
        elif not self.can_slide:
            ped = [(0, False)]
        else:
            ped = [(0, True), (1, True), (-1, True)]
        if forced_s:
            sta = [(forced_s, False)]
        elif s_now != 0:
            sta = [(s_now, False)]
        else:
            sta = [(0, True), (1, True), (-1, True)]
        first = None
        for slide_class in (False, True):
            for rock_class in (False, True):
                passing = []
                for sig, test_sig in ped:
                    if (sig != 0) != slide_class:
                        continue
                    for s, test_s in sta:
                        if (s != 0) != rock_class:
                            continue
                        if first is None:
                            first = (sig, s)
                        if self._consistent(y, sig, s, test_sig, test_s, a, av):
                            passing.append((sig, s))
                if len(passing) == 1:
                    return passing[0][0], passing[0][1], "ok"
                if passing:
                    return self._prefer(y, passing, a, av) + ("ambiguous",)
        return first[0], first[1], "inconsistent"

    def _consistent(self, y, sig, s, test_sig, test_s, a, av):
        try:
            udd, thdd, n, f = self.forces(sig, s, y, a, av)
        except _Singular:
            return False
        if not n > 0.0:
            return False
        if test_sig:
            if sig == 0:
                if self.can_slide and abs(f) - self.mu_s * n > self.tie["cone"]:
                    return False
            elif not sig * udd > 0.0:
                return False
        if test_s:
            if s == 0:
                if self.onset_margin(a, av, udd) < -self.tie["onset"]:
                    return False
            elif not s * thdd > 0.0:
                return False
        return True

    def _prefer(self, y, passing, a, av):
        """Of several consistent candidates of one class, the directions of derivation §4."""
        sig0, s0 = passing[0]
        s_ref = s0 if len({s for _, s in passing}) == 1 else 0
        if len({sig for sig, _ in passing}) > 1:
            _, _, _, f = self.forces(0, s_ref, y, a, av)
            want = -_sign(f)
            passing = [c for c in passing if c[0] == want] or passing
        if len({s for _, s in passing}) > 1:
            udd, _, _, _ = self.forces(passing[0][0], 0, y, a, av)
            want = -_sign(a + udd)
            passing = [c for c in passing if c[1] == want] or passing
        return passing[0]

    # ---------------------------------------------------------------- impact (§6)
    def impact_map(self, y, s):
        """(u̇⁺, θ̇⁺, new pivot, consistent) at θ = 0 for the pivot s before the impact."""
        state = (y[0], y[1], 0.0, y[3])
        if self.impact == "paper":
            res = lagrange.impact_paper(self.params, state, r=self.restitution, s_before=s)
        else:
            res = lagrange.impact_coulomb(self.params, state, r=self.restitution, s_before=s)
        return res.u_dot, res.theta_dot, res.s_after, res.consistent


class _Floor:
    """The floor motion on one smooth piece [lo, hi]: evaluated strictly inside it, so that the
    side of a jump at a breakpoint is the piece's own."""

    def __init__(self, motion, lo, hi):
        self.motion = motion
        self.lo, self.hi = float(np.nextafter(lo, math.inf)), float(np.nextafter(hi, -math.inf))
        if self.hi < self.lo:  # a sliver of two ulps or less
            self.lo = self.hi = 0.5 * (lo + hi)

    def __call__(self, t):
        tt = min(max(t, self.lo), self.hi)
        return float(self.motion.acceleration(tt)), float(self.motion.vertical_acceleration(tt))

    def many(self, ts):
        tt = np.clip(ts, self.lo, self.hi)
        return (np.asarray(self.motion.acceleration(tt), dtype=float),
                np.asarray(self.motion.vertical_acceleration(tt), dtype=float))


def simulate_independent(system, motion, *, duration=None, options, initial_rotation=0.0,
                         initial_angular_velocity=0.0, initial_sliding_velocity=0.0, save_dt=0.01,
                         guard_dt=GUARD_DT) -> IndependentRun:
    """Simulate ``system`` on the floor ``motion`` with the rules of this module.

    ``options`` supplies gravity (m/s²), normal_force, impact, rtol, atol, max_step (s),
    rest_velocity (rad/s), free_time_limit (s) and max_events. ``duration`` (s): the run length;
    None: the motion, then free motion until at rest, for at most ``free_time_limit``.
    Initial state: θ0 (rad), θ̇0 (rad/s), u̇0 (m/s), u0 = 0. ``save_dt`` (s): the output grid.
    """
    return _Run(system, motion, duration, options, initial_rotation, initial_angular_velocity,
                initial_sliding_velocity, save_dt, guard_dt).run()


class _Run:
    def __init__(self, system, motion, duration, options, th0, thd0, ud0, save_dt, guard_dt):
        self.model = _Model(system, options)
        self.motion = motion
        if duration is None:
            self.t_settle = float(motion.duration)
            self.t_end = self.t_settle + float(options.free_time_limit)
        else:
            self.t_end, self.t_settle = float(duration), math.inf
        self.rtol, self.atol = float(options.rtol), float(options.atol)
        self.max_step = float(options.max_step)
        self.max_events = int(options.max_events)
        self.save_dt = float(save_dt)
        self.guard_dt = float(guard_dt)
        bp = np.asarray(motion.breakpoints, dtype=float)
        self.breakpoints = np.unique(bp[(bp > 0.0) & (bp < self.t_end)])
        self.y = np.array([0.0, float(ud0), float(th0), float(thd0)])
        self.t = 0.0
        self.n_grid = int(math.floor(self.t_end / self.save_dt + 1e-9)) + 1
        self.next_grid = 0
        self.out_t, self.out_y, self.out_r = [], [], []
        self.events = []
        self.exceeded = False
        self.peak_theta = abs(self.y[2])
        self.peak_u = 0.0
        self.diag = {"ambiguous": 0, "inconsistent": 0, "immediate": 0, "impact_inconsistent": 0,
                     "steps": 0, "segments": 0}

    # ---------------------------------------------------------------- helpers
    def _note(self, status):
        if status != "ok":
            self.diag[status] += 1

    def _next_stop(self, t):
        i = int(np.searchsorted(self.breakpoints, t, side="right"))
        return float(self.breakpoints[i]) if i < self.breakpoints.size else self.t_end

    def _grid_upto(self, t_cut, value_at, regime):
        """Output the grid points k·save_dt ≤ t_cut; ``value_at(ts)`` gives the states (4 × n)."""
        k0 = self.next_grid
        k1 = k0
        while k1 < self.n_grid and k1 * self.save_dt <= t_cut + 1e-12 * max(1.0, t_cut):
            k1 += 1
        if k1 == k0:
            return
        ts = np.arange(k0, k1) * self.save_dt
        ys = value_at(ts)
        for j in range(k1 - k0):
            self.out_t.append(ts[j])
            self.out_y.append(np.array(ys[:, j], dtype=float))
            self.out_r.append(regime)
        self.next_grid = k1

    def _event(self, t, kind, before, after, ud0, ud1, thd0, thd1):
        self.events.append(IndependentEvent(float(t), kind, before, after, float(ud0), float(ud1),
                                            float(thd0), float(thd1)))

    # ---------------------------------------------------------------- the run
    def run(self):
        m = self.model
        t_stop = self._next_stop(0.0)
        a, av = _Floor(self.motion, 0.0, t_stop)(0.0)
        s_init = _sign(self.y[2]) or _sign(self.y[3])
        sig, s, st = m.select(self.y, s_init, a, av)
        self._note(st)
        status = "completed"
        overturn_time = exceed_time = None
        first_step = None
        try:
            while self.t < self.t_end:
                if sig == 0 and s == 0 and self.t >= self.t_settle:
                    break  # at rest on a still floor: nothing can move again
                t_stop = self._next_stop(self.t)
                out = self._segment(self.t, t_stop, sig, s, first_step)
                self.diag["segments"] += 1
                if out is None:  # reached t_stop without an event
                    first_step = self._last_h
                    if self.t < self.t_end:
                        floor = _Floor(self.motion, self.t, self._next_stop(self.t))
                        a, av = floor(self.t)
                        sig2, s2, st = m.select(self.y, s, a, av)
                        self._note(st)
                        if (sig2, s2) != (sig, s):
                            self._event(self.t, "BREAKPOINT", regime_name(sig, s), regime_name(sig2, s2),
                                        self.y[1], self.y[1], self.y[3], self.y[3])
                            first_step = FIRST_STEP_AFTER_EVENT
                        sig, s = sig2, s2
                    continue
                name, floor = out
                t, y = self.t, self.y
                a, av = floor(t)
                before = regime_name(sig, s)
                ud0, thd0 = y[1], y[3]
                first_step = FIRST_STEP_AFTER_EVENT
                kind = _KIND_OF_GUARD[name]
                if name == "fall":
                    self._event(t, kind, before, before, ud0, ud0, thd0, thd0)
                    status, overturn_time = "overturned", t
                    break
                if name == "exceed":
                    self.exceeded, exceed_time = True, t
                    self._event(t, kind, before, before, ud0, ud0, thd0, thd0)
                    first_step = self._last_h
                    continue
                if name == "cone":
                    _, _, _, f = m.forces(0, s, y, a, av)
                    sig, s, st = m.select(y, s, a, av, forced_sig=-_sign(f) or 1)
                elif name == "onset":
                    udd, _, _, _ = m.forces(sig, 0, y, a, av)
                    sig, s, st = m.select(y, 0, a, av, forced_s=-_sign(a + udd) or 1)
                elif name == "stop":
                    y[1] = 0.0
                    sig, s, st = m.select(y, s, a, av)
                else:  # impact at θ = 0
                    y[2] = 0.0
                    ud1, thd1, s_after, ok = m.impact_map(y, s)
                    if not ok:
                        self.diag["impact_inconsistent"] += 1
                    s = s_after
                    if abs(thd1) < m.rest_velocity:
                        # The Zeno sequence is closed at its accumulation point: θ̇ = 0. The map's
                        # u̇⁺ stands, unless slower than rest_velocity·(b + h): that kick is
                        # O(θ̇⁻), like the rest of the sequence, and is dropped (kept, it can
                        # restart a sequence that never ends when μk > tan α: slide, rock, stop,
                        # settle, slide…).
                        thd1, s, kind = 0.0, 0, "SETTLE"
                        if abs(ud1) < m.rest_velocity * (m.b + m.h):
                            ud1 = 0.0
                    y[1], y[3] = ud1, thd1
                    sig, s, st = m.select(y, s, a, av)
                self._note(st)
                self._event(t, kind, before, regime_name(sig, s), ud0, y[1], thd0, y[3])
                self.peak_u = max(self.peak_u, abs(y[0]))
                if len(self.events) >= self.max_events:
                    status = "max_events"
                    break
        except _Singular:
            status = "singular"
        if status == "completed" and (sig != 0 or s != 0):
            status = "still_moving"
        if status != "overturned":
            y_end = self.y.copy()
            self._grid_upto(self.t + 1e-9, lambda ts: np.repeat(y_end[:, None], ts.size, axis=1),
                            regime_name(sig, s))
        ys = np.array(self.out_y).reshape(-1, 4)
        return IndependentRun(
            t=np.array(self.out_t), u=ys[:, 0], u_dot=ys[:, 1], theta=ys[:, 2], theta_dot=ys[:, 3],
            regime=self.out_r, events=self.events, status=status, overturn_time=overturn_time,
            exceeded_alpha_time=exceed_time, peak_rotation=self.peak_theta, peak_sliding=self.peak_u,
            residual_sliding=float(self.y[0]), end_time=float(self.t), diagnostics=dict(self.diag))

    # ---------------------------------------------------------------- one smooth segment
    def _segment(self, t0, t1, sig, s, first_step):
        """Integrate regime (σ, s) from (t0, self.y) towards t1. Returns None if t1 is reached
        (self.t, self.y updated), else (guard name, floor) with self.t, self.y at the event."""
        m = self.model
        floor = _Floor(self.motion, t0, t1)
        regime = regime_name(sig, s)
        names = m.guard_names(sig, s, self.exceeded)
        ties = [m.tie[n] for n in names]
        y0 = self.y.copy()
        a0, av0 = floor(t0)
        g0 = m.guards(sig, s, y0, a0, av0, names)
        # Per guard: "armed" (last sample positive, at time last[k]) or "tied" (undecided).
        armed = [g > tie for g, tie in zip(g0, ties)]
        tied = [(-tie <= g <= tie) for g, tie in zip(g0, ties)]
        last = [t0] * len(names)
        self._last_h = first_step
        for k, g in enumerate(g0):
            if not armed[k] and not tied[k]:
                # The selected regime is already violated: it ends at once.
                self.diag["immediate"] += 1
                return names[k], floor

        def rhs(t, y):
            a, av = floor(t)
            udd, thdd, _, _ = m.forces(sig, s, y, a, av)
            return np.array([y[1], udd, y[3], thdd])

        h_max = min(self.max_step, t1 - t0)
        fs = None if first_step is None else min(first_step, t1 - t0)
        solver = DOP853(rhs, t0, y0, t1, rtol=self.rtol, atol=self.atol, max_step=h_max, first_step=fs)
        first = True
        while True:
            solver.step()
            if solver.status == "failed":
                raise _Singular(f"step failed at t = {solver.t!r}")
            self.diag["steps"] += 1
            ta, tb = solver.t_old, solver.t
            h = tb - ta
            for k in range(len(names)):
                if tied[k]:
                    last[k] = max(last[k], ta)  # a tie resolved in this step ends the regime in it
            self._last_h = h
            sol = solver.dense_output()
            n = max(MIN_SAMPLES, int(math.ceil(h / self.guard_dt)))
            xs = np.arange(1, n + 1) / n
            if first:
                xs = np.concatenate(([1e-3, 1e-2], xs))
            ts = ta + h * xs
            ts[-1] = tb
            ys = sol(ts)
            ys[:, -1] = solver.y
            a_s, av_s = floor.many(ts)
            hit, t_hit = -1, math.inf
            for j in range(ts.size):
                yj = ys[:, j]
                gj = m.guards(sig, s, yj, a_s[j], av_s[j], names)
                for k, g in enumerate(gj):
                    if tied[k]:
                        if abs(g) <= ties[k]:
                            last[k] = ts[j]  # still tied here
                            continue
                        tied[k] = False
                        if g < 0.0:
                            # A tie resolved against the regime: it ends where the tie was seen.
                            if last[k] < t_hit:
                                hit, t_hit = k, last[k]
                        else:
                            armed[k], last[k] = True, ts[j]
                        continue
                    if armed[k]:
                        if g <= 0.0:
                            root = self._root(sol, floor, sig, s, names[k], last[k], ts[j])
                            if root < t_hit:
                                hit, t_hit = k, root
                        else:
                            last[k] = ts[j]
                    elif g > 0.0:
                        armed[k], last[k] = True, ts[j]
                if hit >= 0:
                    break
            first = False
            t_cut = t_hit if hit >= 0 else tb
            if s != 0:
                self._peaks(sol, ta, t_cut, ts, ys)
            self._grid_upto(t_cut, sol, regime)
            if hit >= 0:
                y_e = y0.copy() if t_hit == t0 else np.array(sol(t_hit), dtype=float)
                self.t, self.y = float(t_hit), y_e
                self.peak_theta = max(self.peak_theta, abs(y_e[2]))
                self.peak_u = max(self.peak_u, abs(y_e[0]))
                return names[hit], floor
            self.peak_u = max(self.peak_u, float(np.max(np.abs(ys[0]))))
            if solver.status == "finished":
                self.t, self.y = float(t1), np.array(solver.y, dtype=float)
                return None

    def _root(self, sol, floor, sig, s, name, t_lo, t_hi):
        """Where guard ``name`` reaches zero between t_lo (positive) and t_hi (≤ 0), s."""
        m = self.model

        def g(t):
            a, av = floor(t)
            return m.guards(sig, s, sol(t), a, av, (name,))[0]

        if g(t_hi) == 0.0:
            return t_hi
        return brentq(g, t_lo, t_hi, xtol=1e-15, rtol=4 * _EPS, maxiter=200)

    def _peaks(self, sol, ta, t_cut, ts, ys):
        """|θ| maxima up to t_cut: at the samples and where θ̇ changes sign between them."""
        keep = ts <= t_cut
        th, thd = ys[2][keep], ys[3][keep]
        if th.size:
            self.peak_theta = max(self.peak_theta, float(np.max(np.abs(th))))
        prev_t, prev_w = ta, float(sol(ta)[3])
        for tj, wj in zip(ts[keep], thd):
            if (prev_w > 0.0) != (wj > 0.0) and prev_w != 0.0 and wj != 0.0:
                tr = brentq(lambda tt: sol(tt)[3], prev_t, tj, xtol=1e-15, rtol=4 * _EPS)
                self.peak_theta = max(self.peak_theta, abs(float(sol(tr)[2])))
            prev_t, prev_w = tj, wj
