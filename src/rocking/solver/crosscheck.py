"""Integrator cross-check: the compiled solver's own hybrid equations, integrated by SciPy.

This is *not* an independent check of the physics. ``simulate_crosscheck`` integrates exactly
the model of :mod:`rocking.solver.compiled` — it imports the same equations of motion
(``models.dynamics.accelerations``), the same guards (``models.modes.evaluate_guards``), the same
regime selection (``models.modes.select_regime``), the same transitions
(``models.transitions.apply_transition``) and so the same impact laws (``contact.impact``) — so a
mistake there is made twice and the two solvers still agree. What it checks is the numerics of
the compiled solver: its Runge–Kutta steps, its event location (grazing guards, chattering
impacts, ties at a segment start), its breakpoints, fast paths and bookkeeping. The physics is
checked against an independent solver written from the sympy derivation
(``tests/oracles/independent_solver.py``, ``tests/test_independent_solver.py``). (This module
was ``rocking.solver.reference``, ``simulate_reference``.)

The numerics that differ from the compiled solver's:

* smooth segments by :func:`scipy.integrate.solve_ivp` with its ``DOP853`` (Hairer's 8(5,3)
  Dormand–Prince pair, SciPy's step-size control and 7th-order dense output), not the compiled
  solver's own Runge–Kutta code;
* events located by SciPy: every guard that can end the current regime is a separate event
  function (terminal, direction −1); SciPy brackets its sign change over a step and solves it
  with Brent's method on the dense output. The compiled solver uses its own root finder and
  its own tests for grazing guards. Here, in addition, the guards are sampled on the dense
  output inside every step (spacing ≤ ``GUARD_DT`` = 1 ms, at least 4 samples per step), so that
  a guard that dips below zero and comes back within one step — SciPy only compares the signs
  at the two ends of a step — is not missed (``diagnostics["events_found_by_sampling"]``);
* the floor acceleration is evaluated by a plain-Python version of each signal kind (the
  compiled ``excitation.signal.evaluate`` is only a fallback for kinds not listed here);
* |θ| peaks from a non-terminal θ̇ = 0 event.

The *model* rules are the compiled solver's, applied at the same instants: the guards of
``evaluate_guards``, ``select_regime`` at t0, after every event (with ``forbid_stick`` after a
slip and ``forbid_rest`` after an uplift) and at every breakpoint, the impact laws, the
``rest_velocity`` settle rule, the EXCEED/FALL bookkeeping, and a regime counting as "entered"
(first rocking/sliding time) only once it lasts a positive time.

It is slow (a Python call per right-hand-side evaluation, one ``solve_ivp`` call per segment)
and meant for cross-checking the compiled core in tests and benchmarks, not for production runs.

Segments
--------
An integration segment never crosses a breakpoint of the floor motion (a sample time of a
record, the end of a pulse or of a harmonic): ``solve_ivp`` is called on ``[t, t_stop]`` with
``t_stop`` the next breakpoint (or the end of the run), so DOP853 only ever sees a smooth
right-hand side. Which side of a jump applies is decided, as in the compiled solver, by a
"piece" time strictly inside the segment. At a breakpoint the regime is selected again
(``select_regime``) and a BREAKPOINT event is recorded if it changes. A terminal event ends the
``solve_ivp`` call early; the transition is applied and a new call starts at the event time.

Guards that start on zero
-------------------------
Right after a switch, the guard that ends the new regime is often exactly zero at the start of
the segment (θ = 0 just after an impact or an uplift, u̇ = 0 just after a slip starts). SciPy
decides that an event happened in a step from the signs of g at the two ends of the step, and
``g(t_old) = 0, g(t_new) ≤ 0`` counts as a crossing whose root Brent's method puts at ``t_old``:
the same event would fire again at the segment start, forever. And a guard that starts on zero,
goes positive and comes back to zero within the first step would be missed by a test that just
ignores roots at the start.

What is done here: ``select_regime`` only returns a regime whose guards are non-negative and
*leave zero upwards* (it checks the sign of the first non-vanishing derivative: σ·ü > 0 for a
slip that starts, S·θ̈ > 0 for a rocking that starts, S·θ̇ > 0 after an impact). So for each guard
that is exactly 0 at the segment start (mode ZERO), its value *at exactly the start time* is
replaced by a tiny positive number (its right-hand limit's sign). Then a guard that rises and
falls back within the first step is bracketed and located properly (g > 0 at the start, ≤ 0 at
the step end), and one that stays positive never fires. The other cases:

* a guard that "fires" within 64 ulp of the start although it was ZERO (a tie that
  ``select_regime`` resolved with a tolerance, or no consistent regime): a friction-cone or
  rocking-threshold guard then ends its regime at once, at the start (an immediate SLIP or
  UPLIFT event, as the compiled solver does for such a guard that stays negative over its first
  step), and so does α − |θ| (a statue released at α turning outwards has exceeded α at the
  start); any other guard (STOP, IMPACT) is ignored until it has come back above zero — it is
  then watched as a direction +1 "arming" event, and the integration restarts there with the
  guard armed. Counted in ``diagnostics["ignored_start_events"]``;
* a guard that is < 0 at the start (the selected regime is not consistent, or a statue released
  beyond α): a threshold guard or α − |θ| ends its regime at once (``diagnostics["immediate_events"]``; if several, the last in guard
  order, as in the compiled loop); any other guard is armed only once it comes back up.

Peaks
-----
|θ| peaks are found exactly: θ̇ = 0 is a non-terminal event while the statue rocks; |u| peaks
are at segment ends and events (|u| is monotone while u̇ keeps its sign, and u̇ = 0 only at a STOP
event or while stuck).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..excitation.base import (
    KIND_HARMONIC,
    KIND_RAMP,
    KIND_RECTANGLE,
    KIND_RICKER,
    KIND_SAMPLED,
    KIND_SINE_PULSE,
    KIND_ZERO,
    signal_breakpoints,
)
from ..excitation.signal import evaluate
from ..models.dynamics import accelerations
from ..models.modes import (
    EXCEED,
    FALL,
    IMPACT,
    N_GUARDS,
    ROCK_TO_NEGATIVE,
    ROCK_TO_POSITIVE,
    SLIP_TO_NEGATIVE,
    SLIP_TO_POSITIVE,
    STOP,
    evaluate_guards,
    select_regime,
)
from ..models.parameters import CAN_SLIDE, pack
from ..models.regimes import EventKind, Regime
from ..results.response import Impact
from ..simulation import Options
from ..models.transitions import EV_BREAKPOINT, EV_EXCEED, EV_IMPACT, EV_SETTLE, apply_transition
from .compiled import (
    N_EVENT_FIELDS,
)

__all__ = ["simulate_crosscheck", "integrate_crosscheck"]

_EPS = float(np.finfo(float).eps)
GUARD_DT = 1e-3  # s: largest spacing of the extra guard samples inside a DOP853 step
_START_TOL = 64.0 * _EPS  # relative: "an event at the segment start"
_SENTINEL = 1e-300  # |value| standing for a guard's right-hand limit sign at the segment start
# How a guard is watched during one solve_ivp call: positive at the start (ARMED); exactly zero
# and known to leave zero upwards (ZERO); negative, waiting to come back up (DISARMED); a
# threshold tie resolved the wrong way (IMMEDIATE: its regime ends at once).
ARMED, ZERO, DISARMED, IMMEDIATE = 0, 1, 2, 3
_THRESHOLDS = (SLIP_TO_NEGATIVE, SLIP_TO_POSITIVE, ROCK_TO_NEGATIVE, ROCK_TO_POSITIVE)  # cone, rocking threshold
# ... and α − |θ| for a statue released at or beyond α, turning outwards: α is exceeded at the start
_AT_ONCE = _THRESHOLDS + (EXCEED,)


class _Singular(Exception):
    """The slide-rock system is singular at some (t, y)."""

    def __init__(self, t):
        super().__init__(f"singular slide-rock equations at t = {t!r}")
        self.t = t


def _regime(sig, s):
    return (1 if s != 0 else 0) + (2 if sig != 0 else 0)


def _piece_function(signal, piece):
    """The acceleration (m/s²) of ``signal`` as a plain Python function of t on the piece of the
    motion containing ``piece`` (the twin of ``excitation.signal.evaluate``)."""
    kind, params, times, values = signal
    kind = int(kind)
    if kind == KIND_ZERO:
        return None
    if kind == KIND_SAMPLED:
        n = times.shape[0]
        if piece < times[0] or piece > times[n - 1]:
            return None
        i = int(np.searchsorted(times, piece, side="right")) - 1
        i = min(i, n - 2)
        t_i, dt_i = float(times[i]), float(times[i + 1] - times[i])
        v_i, dv_i = float(values[i]), float(values[i + 1] - values[i])
        return lambda t: v_i + (t - t_i) / dt_i * dv_i
    known = (KIND_HARMONIC, KIND_SINE_PULSE, KIND_RECTANGLE, KIND_RICKER, KIND_RAMP)
    if kind in known and (piece < 0.0 or piece > params[3]):
        return None
    a0, a1, a2 = float(params[0]), float(params[1]), float(params[2])
    if kind in (KIND_HARMONIC, KIND_SINE_PULSE):
        cos = math.cos
        return lambda t: a0 * cos(a1 * t + a2)
    if kind == KIND_RECTANGLE:
        return lambda t: a0
    if kind == KIND_RICKER:
        exp, pi = math.exp, math.pi
        return lambda t: a0 * (1.0 - 2.0 * (pi * a1 * (t - a2)) ** 2) * exp(-((pi * a1 * (t - a2)) ** 2))
    if kind == KIND_RAMP:
        return lambda t: a0 * t
    # A kind this module does not know: the compiled evaluator.
    return lambda t: float(evaluate(kind, params, times, values, t, piece))


def _scan_guards(sol, t_start, t_end, ev_funcs, guard_dt):
    """Earliest sign change of the event functions ``ev_funcs`` (in their own direction) on the
    dense output ``sol`` over [t_start, t_end], sampled inside every step at a spacing of at most
    ``guard_dt`` (and at least 4 points per step). Returns (index, root time) or None."""
    ts = sol.ts
    ts = ts[(ts > t_start) & (ts < t_end)]
    nodes = np.concatenate(([t_start], ts, [t_end]))
    pieces = [nodes[:1]]
    for ta, tb in zip(nodes[:-1], nodes[1:]):
        n = max(4, int(math.ceil((tb - ta) / guard_dt)))
        pieces.append(ta + (tb - ta) * np.arange(1, n + 1) / n)
    times = np.concatenate(pieces)
    times[-1] = t_end
    ys = sol(times)
    n_ev = len(ev_funcs)
    best = None
    prev = [ev_funcs[k](times[0], ys[:, 0]) for k in range(n_ev)]
    for j in range(1, times.size):
        tj = times[j]
        yj = np.ascontiguousarray(ys[:, j])
        for k in range(n_ev):
            g = ev_funcs[k](tj, yj)
            d = ev_funcs[k].direction
            if (d < 0 and prev[k] > 0.0 and g <= 0.0) or (d > 0 and prev[k] < 0.0 and g >= 0.0):
                ev = ev_funcs[k]
                root = brentq(lambda tt: ev(tt, sol(tt)), times[j - 1], tj, xtol=4 * _EPS, rtol=4 * _EPS)
                if best is None or root < best[1]:
                    best = (k, root)
            prev[k] = g
        if best is not None:
            return best
    return None


def _breakpoints(motion, t0, t_end):
    """The motion's breakpoints and its two signals' own jumps and kinks inside (t0, t_end)."""
    bp = np.concatenate([np.asarray(motion.breakpoints, dtype=float),
                         signal_breakpoints(motion.signal()), signal_breakpoints(motion.vertical_signal())])
    return np.unique(bp[(bp > t0) & (bp < t_end)])


def _active_guards(p, sig, s, exceeded):
    """Indices of the guards that can end the regime (sig, s); the others are constant +1."""
    out = []
    if sig == 0:
        if p[CAN_SLIDE] > 0.5:
            out += [SLIP_TO_NEGATIVE, SLIP_TO_POSITIVE]
    else:
        out.append(STOP)
    if s == 0:
        out += [ROCK_TO_NEGATIVE, ROCK_TO_POSITIVE]
    else:
        out.append(IMPACT)
        if not exceeded:
            out.append(EXCEED)
        out.append(FALL)
    return out


def integrate_crosscheck(p, sig_h, sig_v, breakpoints, t0, t_end, y_init, rtol, atol, max_step, save_dt, save,
                        max_events, guard_dt=GUARD_DT, t_settle=math.inf):
    """Integrate the hybrid system from ``t0`` to ``t_end`` with SciPy's DOP853.

    Arguments as :func:`rocking.solver.compiled.integrate` (``sig_h``/``sig_v`` are
    ``excitation.base.Signal`` tuples, ``y_init`` holds at least (u, u̇, θ, θ̇)); ``guard_dt`` is
    the largest spacing of the extra guard samples inside a step (0 turns them off); from
    ``t_settle`` on, the run ends once everything is at rest (a still floor moves nothing). Returns a
    dict: ``t``, ``state`` (n×4), ``regime``, ``on_grid`` (True for the uniform-grid rows; the
    other rows are the states just before and after each event, as in the compiled output),
    ``event_table`` (compiled layout), ``status`` and the scalar results.
    """
    sig_h = tuple(sig_h)
    sig_v = tuple(sig_v)
    t0 = float(t0)
    t_end = float(t_end)
    st = {  # the mutable state of the run (closures below update it)
        "t": t0, "y": np.array(np.asarray(y_init, dtype=float)[:4]), "sig": 0, "s": 0, "ib": 0,
        "exceeded": False, "impacts": 0, "indeterminate": 0, "ignored_start": 0, "sampled": 0,
        "immediate": 0, "rhs": 0, "calls": 0, "peak_theta": 0.0, "peak_u": 0.0,
        "first_rock": math.nan, "first_slide": math.nan, "next_grid": 0,
    }
    nb = breakpoints.shape[0]
    n_grid = int(math.floor((t_end - t0) / save_dt + 1e-9)) + 1 if save else 0
    grid = t0 + np.arange(n_grid) * save_dt
    t_out, y_out, r_out, g_out = [], [], [], []
    events = []  # rows in the layout of the compiled event table
    status = "completed"
    overturn_time = math.nan
    exceed_time = math.nan
    gbuf = np.empty(N_GUARDS)

    def stop_time():
        ib = st["ib"]
        return min(float(breakpoints[ib]), t_end) if ib < nb else t_end

    def skip_passed_breakpoints():
        while st["ib"] < nb and breakpoints[st["ib"]] <= st["t"]:
            st["ib"] += 1

    def ground_on(piece):
        fh, fv = _piece_function(sig_h, piece), _piece_function(sig_v, piece)

        def accel(tt):
            return (fh(tt) if fh else 0.0), (fv(tt) if fv else 0.0)

        return accel

    def record(tt, yy, regime, on_grid):
        t_out.append(tt)
        y_out.append(np.array(yy[:4], dtype=float))
        r_out.append(regime)
        g_out.append(on_grid)

    def sample_grid(t_a, t_b, evaluate_at, regime):
        """Grid points in [t_a, t_b] (the state before any event at t_b)."""
        while st["next_grid"] < n_grid:
            tg = grid[st["next_grid"]]
            if tg > t_b + 1e-12 * (t_b - t_a):
                break
            if tg >= t_a:
                record(tg, evaluate_at(min(tg, t_b)), regime, True)
            st["next_grid"] += 1

    def cross_breakpoint():
        """At a breakpoint of the floor motion (t = t_stop < t_end) the regime may change."""
        t, y, sig, s = st["t"], st["y"], st["sig"], st["s"]
        st["ib"] += 1
        t_next = stop_time()
        a2, av2 = ground_on(t + 0.5 * (t_next - t))(t)
        sig2, s2, ok2 = select_regime(p, y, s, a2, av2, False, False)
        sig2, s2 = int(sig2), int(s2)
        if not ok2:
            st["indeterminate"] += 1
        if (sig2 != sig or s2 != s) and len(events) < max_events:
            events.append((t, EV_BREAKPOINT, _regime(sig, s), _regime(sig2, s2), y[1], y[1], y[3], y[3], 0.0, 0.0))
        st["sig"], st["s"] = sig2, s2

    # Initial regime.
    skip_passed_breakpoints()
    t_stop = stop_time()
    a, av = ground_on(t0 + 0.5 * (t_stop - t0))(t0)
    y = st["y"]
    s_init = 0
    if y[2] != 0.0:
        s_init = 1 if y[2] > 0.0 else -1
    elif y[3] != 0.0:
        s_init = 1 if y[3] > 0.0 else -1
    sig, s, ok = select_regime(p, y, s_init, a, av, False, False)
    st["sig"], st["s"] = int(sig), int(s)
    if not ok:
        st["indeterminate"] += 1

    override = {}  # guard index -> how to watch it at the next restart (same instant)
    try:
        while st["t"] < t_end:
            if st["sig"] == 0 and st["s"] == 0 and st["t"] >= t_settle:
                break
            skip_passed_breakpoints()
            t_stop = stop_time()
            t_start, y = st["t"], st["y"]
            sig_c, s_c, exc_c = st["sig"], st["s"], st["exceeded"]
            if t_stop - t_start <= _START_TOL * max(1.0, abs(t_start)):
                st["t"] = t_stop  # a sliver before a breakpoint: nothing moves measurably
                if t_stop < t_end:
                    cross_breakpoint()
                continue
            accel = ground_on(t_start + 0.5 * (t_stop - t_start))
            a0, av0 = accel(t_start)
            g_start = np.empty(N_GUARDS)
            evaluate_guards(p, sig_c, s_c, y, a0, av0, exc_c, g_start)
            active = _active_guards(p, sig_c, s_c, exc_c)
            modes = {}
            for i in active:
                g = g_start[i]
                modes[i] = override.get(i, ARMED if g > 0.0 else (ZERO if g == 0.0 else DISARMED))
            override = {}

            # A held/at-rest regime whose threshold is already exceeded ends at once (the compiled
            # solver: an unarmed threshold guard that stays negative fires at the step start; of
            # several, the last in guard order is taken).
            immediate = [i for i in active if i in _AT_ONCE and modes[i] in (DISARMED, IMMEDIATE)]
            sol = None
            if immediate:
                fired, te = max(immediate), t_start
                st["immediate"] += 1
            else:
                def rhs(tt, yy):
                    st["rhs"] += 1
                    ag, avg = accel(tt)
                    udd, thdd, okk = accelerations(p, sig_c, s_c, yy[1], yy[2], yy[3], ag, avg)
                    if not okk:
                        raise _Singular(tt)
                    return np.array([yy[1], udd, yy[3], thdd])

                cache_key = [None]

                def guards(tt, yy):
                    key = (tt, yy[0], yy[1], yy[2], yy[3])
                    if cache_key[0] != key:
                        ag, avg = accel(tt)
                        evaluate_guards(p, sig_c, s_c, np.ascontiguousarray(yy, dtype=float), ag, avg, exc_c, gbuf)
                        cache_key[0] = key
                    return gbuf

                def make_event(i, mode):
                    at_start = _SENTINEL if mode == ZERO else -_SENTINEL
                    replace = mode != ARMED and g_start[i] == 0.0

                    def ev(tt, yy):
                        if replace and tt == t_start:
                            return at_start
                        return float(guards(tt, yy)[i])

                    ev.terminal = True
                    ev.direction = 1 if mode == DISARMED else -1
                    return ev

                ev_funcs = [make_event(i, modes[i]) for i in active]
                turning = s_c != 0
                if turning:
                    def ev_turn(tt, yy):
                        return yy[3]

                    ev_turn.terminal = False
                    ev_turn.direction = 0
                    ev_funcs.append(ev_turn)

                st["calls"] += 1
                res = solve_ivp(rhs, (t_start, t_stop), y, method="DOP853", rtol=rtol, atol=atol,
                                max_step=max_step, events=ev_funcs, dense_output=True)
                if res.status == -1:
                    status = "step_failed"
                    break
                sol = res.sol
                fired, te = -1, t_stop
                if res.status == 1:
                    best = math.inf
                    for k, i in enumerate(active):
                        if len(res.t_events[k]) and res.t_events[k][0] < best:
                            fired, best = i, float(res.t_events[k][0])
                    te = best
                if guard_dt > 0.0:
                    # Guards that dip through zero and back within one DOP853 step (SciPy only
                    # compares the signs at the step ends): sample the dense output inside steps.
                    found = _scan_guards(sol, t_start, te, ev_funcs[:len(active)], guard_dt)
                    if found is not None and (found[1] < te or fired < 0):
                        if active[found[0]] != fired or te - found[1] > 1e-12 * max(1.0, abs(te)):
                            st["sampled"] += 1  # an excursion SciPy's step-end test did not see
                        fired, te = active[found[0]], min(found[1], te)
                if fired >= 0 and modes[fired] == ZERO and te - t_start <= _START_TOL * max(1.0, abs(t_start)):
                    # The guard does not leave zero upwards after all (a tie resolved the other way):
                    # a threshold guard ends its regime at once; any other guard is ignored until it
                    # has been positive (as the compiled solver does). Restart at the same instant.
                    st["ignored_start"] += 1
                    override = {fired: IMMEDIATE if fired in _AT_ONCE else DISARMED}
                    continue
                if turning:
                    for tk, yk in zip(res.t_events[-1], res.y_events[-1]):
                        if tk <= te:
                            st["peak_theta"] = max(st["peak_theta"], abs(float(yk[2])))

            # A regime counts as entered once it lasts (as in the compiled solver).
            if te > t_start:
                if s_c != 0 and math.isnan(st["first_rock"]):
                    st["first_rock"] = t_start
                if sig_c != 0 and math.isnan(st["first_slide"]):
                    st["first_slide"] = t_start
            if save:
                y_const = y
                sample_grid(t_start, te, sol if sol is not None else (lambda tt: y_const), _regime(sig_c, s_c))
            if sol is not None:
                y = np.array(sol(te), dtype=float)
            else:
                y = y.copy()
            st["t"], st["y"] = te, y
            st["peak_theta"] = max(st["peak_theta"], abs(y[2]))
            st["peak_u"] = max(st["peak_u"], abs(y[0]))

            if fired >= 0 and sol is not None and modes[fired] == DISARMED:
                # A disarmed guard came back up through zero: restart here with it watched.
                override = {fired: ZERO}
                continue
            if fired < 0:
                if te >= t_stop and te < t_end:
                    cross_breakpoint()
                continue

            # ---- transition at an event (as in the compiled loop) ----
            t = te
            sig, s = sig_c, s_c
            a, av = accel(t)
            regime_before = _regime(sig, s)
            ud_before, thd_before = float(y[1]), float(y[3])
            if save:
                record(t, y, regime_before, False)
            # The transition itself is shared with the compiled solver (models.transitions).
            sig2, s2, kind, ok, impact, lost, ratio, _, _ = apply_transition(p, fired, False, y, sig, s, a, av)
            if not ok:
                st["indeterminate"] += 1
            if fired == FALL:
                overturn_time = t
                status = "overturned"
            elif fired == EXCEED:
                st["exceeded"] = True
                exceed_time = t
            if impact:
                st["impacts"] += 1
            sig, s = int(sig2), int(s2)
            st["sig"], st["s"] = sig, s
            events.append((t, kind, regime_before, _regime(sig, s), ud_before, float(y[1]), thd_before,
                           float(y[3]), lost, ratio))
            if save and kind != EV_EXCEED:
                record(t, y, _regime(sig, s), False)
            st["peak_u"] = max(st["peak_u"], abs(y[0]))
            if status == "overturned":
                break
            if len(events) >= max_events:
                status = "max_events"
                break
    except _Singular:
        status = "singular"

    t, y = st["t"], st["y"]
    if status == "completed" and (st["sig"] != 0 or st["s"] != 0):
        status = "still_moving"
    if save and status != "overturned":
        # Last grid point(s) reached exactly at t_end (the grid may overshoot it by 1e-9·save_dt).
        while st["next_grid"] < n_grid:
            tg = grid[st["next_grid"]]
            if tg > t + 1e-9:
                break
            record(tg, y, _regime(st["sig"], st["s"]), True)
            st["next_grid"] += 1
        if not t_out or t_out[-1] < t:
            record(t, y, _regime(st["sig"], st["s"]), False)  # the end, between grid points

    return {
        "t": np.array(t_out, dtype=float),
        "state": np.array(y_out, dtype=float).reshape(-1, 4),
        "regime": np.array(r_out, dtype=np.int8),
        "on_grid": np.array(g_out, dtype=bool),
        "event_table": np.array(events, dtype=float).reshape(-1, N_EVENT_FIELDS),
        "status": status,
        "overturn_time": overturn_time,
        "exceeded_alpha_time": exceed_time,
        "peak_rotation": st["peak_theta"],
        "peak_sliding": st["peak_u"],
        "residual_sliding": float(y[0]),
        "impacts": st["impacts"],
        "first_rocking_time": st["first_rock"],
        "first_sliding_time": st["first_slide"],
        "final_state": y.copy(),
        "end_time": t,
        "diagnostics": {
            "immediate_events": st["immediate"],
            "ignored_start_events": st["ignored_start"],
            "events_found_by_sampling": st["sampled"],
            "indeterminate": st["indeterminate"],
            "rhs_evaluations": st["rhs"],
            "solve_ivp_calls": st["calls"],
        },
    }


def simulate_crosscheck(
    system,
    motion,
    *,
    duration: float | None = None,
    options: Options = Options(),
    initial_rotation: float = 0.0,
    initial_angular_velocity: float = 0.0,
    initial_sliding_velocity: float = 0.0,
    save_dt: float | None = 0.01,
    save: bool = True,
) -> dict:
    """Simulate ``system`` on ``motion`` with the SciPy integrator cross-check (same physics as
    the compiled solver, other numerics; see the module docstring).

    Same model, options and run length as :func:`rocking.simulate` (without ``duration``: the
    motion, then free motion until at rest, at most ``options.free_time_limit``; ``options.rtol``/``atol``/``max_step``
    are passed to ``solve_ivp``; ``options.save_dt`` is ignored in favour of ``save_dt``; with
    ``save_dt=None`` the rule of ``simulate`` applies: the record's time step, else 0.01 s).

    Returns
    -------
    dict
        ``t`` (s, the uniform grid ``k·save_dt`` up to the end or the overturn), ``u``, ``u_dot``,
        ``theta``, ``theta_dot``, ``regime`` (int codes of :class:`~rocking.Regime`) on that grid;
        ``events``: list of ``(time, EventKind)``; ``event_regimes``: list of
        ``(time, EventKind, Regime before, Regime after)``; ``event_table``: the same rows in the
        layout of the compiled solver; ``impacts``: list of :class:`rocking.results.response.Impact`;
        ``overturned`` (bool), ``overturn_time``, ``exceeded_alpha_time`` (s or None),
        ``peak_rotation`` (rad), ``peak_sliding``, ``residual_sliding`` (m), ``status``,
        ``first_rocking_time``, ``first_sliding_time``, ``end_time``, ``diagnostics``.
        With ``save=False`` the time series are empty (for timing runs).
    """
    if duration is None:
        t_settle = float(motion.duration)
        t_end = t_settle + float(options.free_time_limit)
    else:
        t_end, t_settle = float(duration), math.inf
    if not math.isfinite(t_end) or t_end <= 0:
        raise ValueError(f"duration must be a positive number, got {duration!r}")
    if abs(initial_rotation) >= 0.5 * math.pi:
        raise ValueError(f"initial_rotation must satisfy |θ0| < π/2, got {initial_rotation!r}")
    if save_dt is None:
        dt = getattr(motion, "dt", None)
        save_dt = float(options.save_dt or dt or 0.01)
    p = pack(system, gravity=options.gravity, normal_force=options.normal_force, impact=options.impact,
             rest_velocity=options.rest_velocity)
    y0 = np.array([0.0, initial_sliding_velocity, initial_rotation, initial_angular_velocity], dtype=float)
    raw = integrate_crosscheck(p, motion.signal(), motion.vertical_signal(), _breakpoints(motion, 0.0, t_end), 0.0,
                              t_end, y0, options.rtol, options.atol, options.max_step, float(save_dt), bool(save),
                              int(options.max_events), t_settle=t_settle)
    table = raw["event_table"]
    rows = [(float(r[0]), EventKind(int(r[1])), Regime(int(r[2])), Regime(int(r[3]))) for r in table]
    impacts = [Impact(*(float(v) for v in (r[0], r[4], r[5], r[6], r[7], r[8], r[9])))
               for r in table if int(r[1]) in (EV_IMPACT, EV_SETTLE)]

    def opt(x):
        return None if math.isnan(x) else float(x)

    # The uniform grid only: the rows at event instants (before/after) are left out.
    keep = raw["on_grid"]
    t = raw["t"]
    state = raw["state"]
    return {
        "t": t[keep],
        "u": state[keep, 0],
        "u_dot": state[keep, 1],
        "theta": state[keep, 2],
        "theta_dot": state[keep, 3],
        "regime": raw["regime"][keep].astype(int),
        "events": [(r[0], r[1]) for r in rows],
        "event_regimes": rows,
        "event_table": table,
        "impacts": impacts,
        "overturned": raw["status"] == "overturned",
        "overturn_time": opt(raw["overturn_time"]),
        "exceeded_alpha_time": opt(raw["exceeded_alpha_time"]),
        "peak_rotation": float(raw["peak_rotation"]),
        "peak_sliding": float(raw["peak_sliding"]),
        "residual_sliding": float(raw["residual_sliding"]),
        "status": raw["status"],
        "first_rocking_time": opt(raw["first_rocking_time"]),
        "first_sliding_time": opt(raw["first_sliding_time"]),
        "end_time": float(raw["end_time"]),
        "diagnostics": raw["diagnostics"],
    }
