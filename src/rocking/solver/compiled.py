"""The compiled event-driven solver: smooth segments by Dormand–Prince 8(5,3) (DOP853), events
located on its dense output, regime switches and impacts applied, and a restart.

This is where physics (``models``, ``contact``) meets numerics (``integrators``). Steps never
cross a breakpoint of the floor motion (a sample time of a record, the end of a pulse), so the
Runge–Kutta step always sees a smooth right-hand side. What keeps it fast without giving up
accuracy (measured by ``bench/run.py``):

* a step cut short by a record sample is a Dormand–Prince 5(4) step (7 stages, not 12);
* the state at an event comes from a step to the event (8th order), not from the interpolant,
  but locating the event interpolates only the state variables its guard needs;
* rest is crossed without integrating: between record samples when the guards are positive at
  both ends (they are linear in time there), and under a harmonic motion up to the closed-form
  time where the floor acceleration leaves the band where rest holds;
* the event loop runs without Numba's runtime (no reference counting of arrays), on arrays
  allocated once per run by :func:`integrate`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, types

from ..excitation.signal import (
    LOCAL_COSINE,
    LOCAL_LINEAR,
    LOCAL_SIZE,
    LOCAL_ZERO,
    cosine_band_exit,
    crest_inside,
    local_value,
    localise,
    next_crest,
    floor_end,
)
from ..integrators import dop853, dopri5
from ..models.dynamics import (
    evaluate_all,
    mechanical_energy,
    overturning_barrier,
    pedestal_half_width,
    pressure_centre,
    pressure_moment,
)
from ..models.transitions import (
    EV_BREAKPOINT,
    EV_EXCEED,
    apply_transition,
)
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
    angle_guard,
    evaluate_guards,
    guards_from_forces,
    rest_band,
    select_regime,
    track_threshold_guards,
)
from ..models.parameters import ALPHA, B, CAN_SLIDE, G, H, IMPACT_COULOMB, M, M2, MU_S, MU_TOP

# Runs the Python-level signal handlers (C API; needs the GIL, which compiled code holds). In a
# thread other than the main one it does nothing. See rocking.solver.signals for why the
# handlers must only record the signal while compiled code runs.
_check_signals = types.ExternalFunction("PyErr_CheckSignals", types.int32())

# Layout of the summary vector returned by `integrate` (NaN = did not happen).
(S_STATUS, S_OVERTURN_TIME, S_EXCEED_TIME, S_PEAK_ROTATION, S_PEAK_SLIDING, S_RESIDUAL_SLIDING, S_IMPACTS,
 S_FIRST_ROCK, S_FIRST_SLIDE, S_TOP_RATIO, S_BALANCE, S_STEPS, S_EVENTS, S_T_END, S_N_NONPOSITIVE,
 S_PY_NONPOSITIVE, S_TOP_SLIP, S_UPLIFT, S_IMPACT_FLOOR_RATIO, S_IMPACT_FLOOR_SHORT, S_INDETERMINATE,
 S_D_IMPACT, S_D_FRICTION, S_W_INPUT, S_ENERGY_SCALE, S_REJECTED, S_HELD_IMPACT, S_SETTLED) = range(28)
N_SUMMARY = 28

(STATUS_COMPLETED, STATUS_OVERTURNED, STATUS_MAX_EVENTS, STATUS_SINGULAR, STATUS_STEP_FAILED, STATUS_STILL_MOVING,
 STATUS_INTERRUPTED) = range(7)
# The event loop hands pending signals (Ctrl-C, SIGTERM) to Python's handlers every this many
# iterations: often enough to stop within milliseconds, rarely enough to cost nothing.
SIGNAL_POLL_INTERVAL = 2000

N_EVENT_FIELDS = 10  # t, kind, regime before, regime after, u̇⁻, u̇⁺, θ̇⁻, θ̇⁺, energy lost, friction ratio

N_STATE = 6  # u, u̇, θ, θ̇, input work W, friction dissipation D
FSAL5 = 6  # row of K holding rhs(t + h, y_new) after a Dormand–Prince 5(4) step
N_DIAG = 7  # extra right-hand-side outputs: a_g, a_v, F, N, P_x, P_y, ok (not integrated)
# An event is read off the dense output of a DOP853 step whose scaled error is below this: the
# step is then ≥ 4× shorter than the tolerance needs, and the interpolant's error (∝ h⁸) is
# 1e-5 of what it would be at the tolerance. Longer steps take a step to the event instead.
DENSE_EVENT_ERROR = 1e-5
# The four checks of the model's assumptions behind the run's warnings, in the order of their
# slots in ``gmin`` (after the guards and the top-face ratio): the statue would
# slip on the pedestal, the pedestal would uplift, the floor's normal force N ≤ 0, the statue's
# base force P_y ≤ 0. Their summary entries hold the first instant each fails.
N_CHECKS = 4
CHECK_SLOTS = (S_TOP_SLIP, S_UPLIFT, S_N_NONPOSITIVE, S_PY_NONPOSITIVE)


@njit(cache=True)
def _piece_table(sig_h, sig_v, breakpoints, t0, t_end):
    """The floor motion localised on every piece between breakpoints, once per run: row ``i``
    holds the horizontal and vertical formulas (see signal.localise) valid from breakpoint
    i − 1 (or t0) to breakpoint i (or t_end). A record sample is then crossed by reading a row,
    not by a search in the record."""
    table = np.empty((breakpoints.shape[0] + 1, 2 * LOCAL_SIZE))
    _fill_piece_table(table, sig_h[0], sig_h[1], sig_h[2], sig_h[3], 0, breakpoints, t0, t_end)
    _fill_piece_table(table, sig_v[0], sig_v[1], sig_v[2], sig_v[3], LOCAL_SIZE, breakpoints, t0, t_end)
    return table


@njit(cache=True, _nrt=False)
def _fill_piece_table(table, kind, params, times, values, column, breakpoints, t0, t_end):
    nb = breakpoints.shape[0]
    for i in range(nb + 1):
        lo = breakpoints[i - 1] if i > 0 else t0
        hi = breakpoints[i] if i < nb else t_end
        row = localise(kind, params, times, values, 0.5 * (lo + hi))
        for k in range(LOCAL_SIZE):
            table[i, column + k] = row[k]


@njit(cache=True, inline="always")
def _piece(table, i):
    """Row ``i`` of the piece table as a tuple (passed around without reference counting)."""
    return (table[i, 0], table[i, 1], table[i, 2], table[i, 3], table[i, 4],
            table[i, 5], table[i, 6], table[i, 7], table[i, 8], table[i, 9])


@njit(cache=True, inline="always")
def _all_positive(g):
    for i in range(N_GUARDS):
        if not g[i] > 0.0:
            return False
    return True


@njit(cache=True, inline="always")
def _ground(loc, t):
    """(a_g, a_v) at time t, m/s²."""
    return local_value(loc, 0, t), local_value(loc, LOCAL_SIZE, t)


@njit(cache=True, _nrt=False)
def rhs(t, y, p, sig, s, loc, out):
    """dy/dt into ``out``; out[6:] receives (a_g, a_v, F, N, P_x, P_y, ok) for guards and checks."""
    a, av = _ground(loc, t)
    udd, thdd, ok, f, n, px, py, p_in, p_fric = evaluate_all(p, sig, s, y[1], y[2], y[3], a, av)
    out[12] = 1.0 if ok else 0.0
    out[6] = a
    out[7] = av
    out[8] = f
    out[9] = n
    out[10] = px
    out[11] = py
    out[0] = y[1]
    out[1] = udd
    out[2] = y[3]
    out[3] = thdd
    out[4] = p_in
    out[5] = p_fric


@njit(cache=True, inline="always")
def _check_margin(p, s, a, udd, n_full, px, py, which):
    """How far check ``which`` (see N_CHECKS) is from failing at a state whose floor
    acceleration a, ü and forces (N, P_x, P_y) are known, in the check's own units:
    μs,top·P_y − |P_x| (N), b₁ − |x_N| (m; derivation §3.5), N and P_y (N). +inf where the
    check cannot fail: no top friction given, no pedestal width and height. Where N ≤ 0 the
    uplift has happened if the pedestal carries a moment (−inf): x_N = moment/N leaves the base
    as N falls to zero, so the pressure centre crosses b₁ just before the floor force vanishes
    (until 2026-12-03 the margin was +inf there, and an uplift 0.3 ms before a jump, in a step
    that ended past the jump, was warned 0.24 s late, at a later crossing)."""
    if which == 0:
        return p[MU_TOP] * py - abs(px) if p[MU_TOP] >= 0.0 else math.inf
    if which == 1:
        b1 = pedestal_half_width(p)
        if b1 <= 0.0:
            return math.inf
        xn = pressure_centre(p, s, a, udd, px, py, n_full)
        if math.isfinite(xn):
            return b1 - abs(xn)
        return -math.inf if n_full <= 0.0 and pressure_moment(p, s, a, udd, px, py) != 0.0 else math.inf
    if which == 2:
        return n_full
    return py


@njit(cache=True, inline="always")
def _failed(margin, which):
    """Whether a check whose margin is ``margin`` fails: the statue slips if |P_x| > μs,top·P_y,
    the pedestal uplifts if |x_N| > b₁, the bodies jump if N ≤ 0 or P_y ≤ 0."""
    return margin < 0.0 if which < 2 else margin <= 0.0


@njit(cache=True, inline="always")
def _margin_scale(p, which):
    """The size against which a check's margin is near zero: the statue's weight, b₁, or the
    weight of both bodies."""
    if which == 1:
        return pedestal_half_width(p)
    return (p[M] if which == 2 else p[M2]) * p[G]


@njit(cache=True, inline="always")
def _need(p, theta, px, py):
    """|P_x|/P_y, the friction the statue's base needs; 0 where P_y ≤ 0 or |θ| > α (toppling:
    no design quantity there)."""
    return abs(px) / py if py > 0.0 and abs(theta) <= p[ALPHA] else 0.0


@njit(cache=True)
def _need_rate(p, sig, s, y, dy, here, t, loc, h):
    """The rate (1/s) at which the friction the statue's base needs changes at (t, y), where it
    is ``here`` and the derivatives are ``dy`` (a row of K), by a difference over 1e-3 of the
    step h along the tangent (its error, ~1e-3 of the rate, only matters where the rate is near
    zero: then the peak it points to is at the point itself). Only its sign and size are used."""
    d = 1e-3 * h
    a, av = _ground(loc, t + d)
    _, _, _, _, _, px, py, _, _ = evaluate_all(p, sig, s, y[1] + d * dy[1], y[2] + d * dy[2], y[3] + d * dy[3], a,
                                               av)
    return (_need(p, y[2] + d * dy[2], px, py) - here) / d


#: Of a step, the widest stretch between two samples of the need next to an end (DOP853's first
#: interior stage is at c = 0.053 and its last at 0.857; the 5(4) pair's at 0.2 and 0.889).
END_GAP = 0.25


@njit(cache=True, inline="always")
def _watched(p, summ, which):
    """Whether check ``which`` can still raise its warning: not raised yet, and not off (no top
    friction given; no pedestal width and height)."""
    if not math.isnan(summ[CHECK_SLOTS[which]]):
        return False
    if which == 0:
        return p[MU_TOP] >= 0.0
    if which == 1:
        return pedestal_half_width(p) > 0.0
    return True


@njit(cache=True, inline="always")
def _stages(t, y, h, K, work, p, sig, s, loc, gmin, summ, c, a_tab, n_stages):
    """Stages 1…n_stages−1 of an explicit Runge–Kutta step (tableau c, a_tab) into K, with the
    threshold guards and the top-face friction ratio tracked at every stage into ``gmin``, and
    each check's smallest margin at a stage (gmin[N_GUARDS + 1 + check]; +inf if none) with
    the fraction c of the step at that stage (gmin[N_GUARDS + 1 + N_CHECKS + check])."""
    for i in range(N_GUARDS):
        gmin[i] = np.inf
    gmin[N_GUARDS] = 0.0
    for w in range(N_CHECKS):
        gmin[N_GUARDS + 1 + w] = np.inf
        gmin[N_GUARDS + 1 + N_CHECKS + w] = 0.0
    n = N_STATE  # a constant: the stage sums unroll
    for stage in range(1, n_stages):
        for j in range(n):
            acc = 0.0
            for k in range(stage):
                acc += a_tab[stage, k] * K[k, j]
            work[j] = y[j] + h * acc
        ts = t + c[stage] * h
        # The right-hand side written out here rather than called: in this innermost loop a
        # function call per stage costs as much as the physics itself.
        a = local_value(loc, 0, ts)
        av = local_value(loc, LOCAL_SIZE, ts)
        udd, thdd, ok, f, nn, px, py, p_in, p_fric = evaluate_all(p, sig, s, work[1], work[2], work[3], a, av)
        K[stage, 0] = work[1]
        K[stage, 1] = udd
        K[stage, 2] = work[3]
        K[stage, 3] = thdd
        K[stage, 4] = p_in
        K[stage, 5] = p_fric
        track_threshold_guards(p, sig, s, work, a, av, udd, f, nn, gmin)
        # The friction the statue's base needs peaks between step ends: sample it at the stages
        # (while |θ| ≤ α: beyond, the statue is toppling and the ratio is no design quantity).
        gmin[N_GUARDS] = max(gmin[N_GUARDS], _need(p, work[2], px, py))
        # The warnings' first instants: each check's smallest margin at the stages, and where,
        # so that a failure, or a near miss, that starts and ends inside a step shows here
        # (_failure_bound). Written out: no loop in this innermost one.
        cs = c[stage]
        if nn < gmin[N_GUARDS + 3]:
            gmin[N_GUARDS + 3], gmin[N_GUARDS + 3 + N_CHECKS] = nn, cs
        if py < gmin[N_GUARDS + 4]:
            gmin[N_GUARDS + 4], gmin[N_GUARDS + 4 + N_CHECKS] = py, cs
        m = _check_margin(p, s, a, udd, nn, px, py, 0)
        if m < gmin[N_GUARDS + 1]:
            gmin[N_GUARDS + 1], gmin[N_GUARDS + 1 + N_CHECKS] = m, cs
        if _watched(p, summ, 1):  # (the pressure centre only while its warning can come)
            m = _check_margin(p, s, a, udd, nn, px, py, 1)
            if m < gmin[N_GUARDS + 2]:
                gmin[N_GUARDS + 2], gmin[N_GUARDS + 2 + N_CHECKS] = m, cs


@njit(cache=True, _nrt=False)
def _step(t, y, h, K, work, y_new, p, sig, s, loc, gmin, summ, fsal):
    """One DOP853 step; K[0] = rhs(t, y) on entry, K[FSAL] = rhs(t + h, y_new) on exit if
    ``fsal`` (a step to an event skips it: the regime changes there). ``gmin`` receives the
    smallest values of the threshold guards at the interior stages."""
    _stages(t, y, h, K, work, p, sig, s, loc, gmin, summ, dop853.C, dop853.A, dop853.N_STAGES)
    dop853.advance(y, K, h, y_new)
    if fsal:
        rhs(t + h, y_new, p, sig, s, loc, K[dop853.FSAL])


@njit(cache=True, _nrt=False)
def _step5(t, y, h, K, work, y_new, p, sig, s, loc, gmin, summ):
    """One Dormand–Prince 5(4) step (FSAL row 6): for steps cut short by a sample of a record,
    where 12 stages would buy accuracy the short step already has."""
    _stages(t, y, h, K, work, p, sig, s, loc, gmin, summ, dopri5.C, dopri5.A, 6)
    dopri5.advance(y, K, h, y_new)
    rhs(t + h, y_new, p, sig, s, loc, K[FSAL5])


@njit(cache=True, _nrt=False)
def _prepare_dense(t, y, y_new, h, K, work, F, p, sig, s, loc):
    """7th-order dense output of the accepted step (three more right-hand sides) into F."""
    for j in range(dop853.N_EXTRA):
        dop853.extra_stage_input(y, K, h, j, work)
        rhs(t + dop853.C_EXTRA[j] * h, work, p, sig, s, loc, K[dop853.FSAL + 1 + j])
    dop853.prepare_dense(y, y_new, K, h, F)


@njit(cache=True, _nrt=False)
def _prepare_step_dense(t, y, y_new, h, K, work, F, p, sig, s, loc, low_order):
    """The accepted step's dense output into F: the nested one of a 5(4) step, DOP853's 7th-order
    one otherwise. Returns True (for the caller's flag that it is built)."""
    if low_order:
        dopri5.prepare_dense_nested(y, K, h, F)
    else:
        _prepare_dense(t, y, y_new, h, K, work, F, p, sig, s, loc)
    return True


@njit(cache=True)
def _regime(sig, s):
    return (1 if s != 0 else 0) + (2 if sig != 0 else 0)


#: Added to a saved sample's regime code when the statue rocks on its negative pivot (s = −1),
#: and when the body on the floor slides in the negative direction (σ = −1). Neither sign can be
#: read back from the state: at the onset of rocking θ = θ̇ = 0 and at that of sliding u̇ = 0, and
#: at the sample saved just before an impact θ may have crossed zero by rounding.
SAVED_NEGATIVE_PIVOT = 4
SAVED_NEGATIVE_SLIP = 8


@njit(cache=True)
def _saved_code(sig, s):
    """The regime code of a saved sample, with the signs of the regime (see above)."""
    return _regime(sig, s) + (SAVED_NEGATIVE_PIVOT if s < 0 else 0) + (SAVED_NEGATIVE_SLIP if sig < 0 else 0)


@njit(cache=True, _nrt=False)
def _guard_at(p, sig, s, y0, F, h, x, loc, t0, exceeded, work, gbuf, index):
    if s != 0 and index >= IMPACT:  # a guard of θ alone: interpolate θ only
        return angle_guard(p, s, index, dop853.dense_component(y0, F, x, 2), exceeded)
    dop853.dense(y0, F, x, work)
    a, av = _ground(loc, t0 + x * h)
    evaluate_guards(p, sig, s, work, a, av, exceeded, gbuf)
    return gbuf[index]


@njit(cache=True, _nrt=False)
def _locate(p, sig, s, y0, F, h, loc, t0, exceeded, work, gbuf, index, g_lo, g_hi, x0, x1):
    """Fraction of the step where guard ``index`` first reaches zero in [x0, x1], given
    g(x0) = g_lo > 0 ≥ g_hi = g(x1) (Illinois method on the dense output)."""
    lo, hi = x0, x1
    flo, fhi = g_lo, g_hi
    side = 0
    for _ in range(200):
        x = (lo * fhi - hi * flo) / (fhi - flo)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        fx = _guard_at(p, sig, s, y0, F, h, x, loc, t0, exceeded, work, gbuf, index)
        if fx <= 0.0:
            hi, fhi = x, fx
            if side == -1:
                flo *= 0.5
            side = -1
        else:
            lo, flo = x, fx
            if side == 1:
                fhi *= 0.5
            side = 1
        if (hi - lo) * h <= 1e-15 * max(1.0, abs(t0)) + 1e-300:
            break
    return hi


@njit(cache=True, _nrt=False)
def _minimum(p, sig, s, y0, F, h, loc, t0, exceeded, work, gbuf, index):
    """Golden-section search for the minimum of guard ``index`` over the step; returns its
    position if the minimum is ≤ 0, else −1 (a grazing dip between the 64 samples)."""
    ratio = 0.6180339887498949
    lo, hi = 0.0, 1.0
    x1 = hi - ratio * (hi - lo)
    x2 = lo + ratio * (hi - lo)
    f1 = _guard_at(p, sig, s, y0, F, h, x1, loc, t0, exceeded, work, gbuf, index)
    f2 = _guard_at(p, sig, s, y0, F, h, x2, loc, t0, exceeded, work, gbuf, index)
    for _ in range(60):
        if min(f1, f2) <= 0.0:
            break
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - ratio * (hi - lo)
            f1 = _guard_at(p, sig, s, y0, F, h, x1, loc, t0, exceeded, work, gbuf, index)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + ratio * (hi - lo)
            f2 = _guard_at(p, sig, s, y0, F, h, x2, loc, t0, exceeded, work, gbuf, index)
        if hi - lo < 1e-7:
            break
    if f1 <= 0.0:
        return x1
    if f2 <= 0.0:
        return x2
    return -1.0


@njit(cache=True, _nrt=False)
def _positive_inside(p, sig, s, y0, F, h, loc, t0, exceeded, work, gbuf, index, x_turn):
    """A fraction x of the step where guard ``index`` is positive, or −1. For the impact guard
    the best candidate is the turning point of θ, ``x_turn`` (−1 if none); otherwise 32
    samples are tried."""
    if index == IMPACT and x_turn >= 0.0:
        if _guard_at(p, sig, s, y0, F, h, x_turn, loc, t0, exceeded, work, gbuf, index) > 0.0:
            return x_turn
    x_best = -1.0
    for k in range(1, 32):
        x = k / 32.0
        if _guard_at(p, sig, s, y0, F, h, x, loc, t0, exceeded, work, gbuf, index) > 0.0:
            x_best = x
    return x_best


@njit(cache=True, _nrt=False)
def _theta_dot_root(y0, F, f_lo, f_hi, x_hi):
    """Fraction of the step in [0, x_hi] where θ̇ changes sign, given θ̇ = f_lo at 0 and f_hi at
    x_hi (the Illinois method on the dense output, to 1e-10 of the step: θ at a turning point is
    insensitive to its position to first order, and θ̇ is smooth inside a step)."""
    return dop853.dense_sum_root(y0, F, 3, 1, 1, f_lo, f_hi, x_hi)


#: _value_at's code for the friction the statue's base needs (after the checks' codes).
NEED = N_CHECKS


@njit(cache=True, _nrt=False)
def _value_at(p, sig, s, y0, F, h, x, loc, t0, work, which):
    """On the dense output of the step at fraction x: the margin of check ``which``
    (_check_margin), or for ``which`` = NEED the friction the statue's base needs, negated
    (_lowest looks for the lowest value of either)."""
    dop853.dense(y0, F, x, work)
    a, av = _ground(loc, t0 + x * h)
    udd, _, _, _, n_full, px, py, _, _ = evaluate_all(p, sig, s, work[1], work[2], work[3], a, av)
    if which == NEED:
        return -_need(p, work[2], px, py)
    return _check_margin(p, s, a, udd, n_full, px, py, which)


@njit(cache=True, _nrt=False)
def _check_at(p, sig, s, y0, F, h, x, loc, t0, work, which):
    """Whether check ``which`` fails on the dense output of the step, at fraction x."""
    return _failed(_value_at(p, sig, s, y0, F, h, x, loc, t0, work, which), which)


@njit(cache=True, _nrt=False)
def _lowest(p, sig, s, y0, F, h, x_end, x_hint, loc, t0, work, which):
    """The lowest value of _value_at over [0, x_end] of the step, and where (a fraction): the
    lowest of 17 samples and of x_hint (ignored outside (0, x_end)), then a golden-section
    search between its neighbours to 1e-6 of the step (the values are flat to ~1e-12 of
    themselves there). For the peak of the friction the statue's base needs (the stages alone,
    up to a quarter of a step apart, read it low: 0.27499 for 0.27501 on a statue rocking under
    a sine, until 2026-12-02), and for a check's margin the stages saw dip near zero between the
    step's ends (a dip below zero narrower than their spacing passed unseen until 2026-12-02:
    P_y ≤ 0 for 3.5 ms, to −0.33 N, under a 100 kg statue)."""
    best, xb = math.inf, 0.0
    for k in range(17):
        x = x_end * k / 16.0
        v = _value_at(p, sig, s, y0, F, h, x, loc, t0, work, which)
        if v < best:
            best, xb = v, x
    if 0.0 < x_hint < x_end:
        v = _value_at(p, sig, s, y0, F, h, x_hint, loc, t0, work, which)
        if v < best:
            best, xb = v, x_hint
    lo, hi = max(0.0, xb - x_end / 16.0), min(x_end, xb + x_end / 16.0)
    g = 0.6180339887498949
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1 = _value_at(p, sig, s, y0, F, h, x1, loc, t0, work, which)
    f2 = _value_at(p, sig, s, y0, F, h, x2, loc, t0, work, which)
    for _ in range(60):
        if hi - lo < 1e-6 * x_end:
            break
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = _value_at(p, sig, s, y0, F, h, x1, loc, t0, work, which)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = _value_at(p, sig, s, y0, F, h, x2, loc, t0, work, which)
    if f1 < best:
        best, xb = f1, x1
    if f2 < best:
        best, xb = f2, x2
    return best, xb


@njit(cache=True, _nrt=False)
def _first_check_failure(p, sig, s, y0, F, h, t0, x_hi, loc, work, which):
    """The first instant (s) in the step from t0 at which check ``which`` fails, given it holds
    at t0 and fails at fraction x_hi of the step (its end, or where it came nearest to failing:
    _warning_time): on the dense output, the first of 16 samples up to x_hi that fails, then the
    crossing before it bisected to the last bit of max(t, 1 s). NaN when the dense output holds
    at x_hi (a failure within the step's error; the next point checked decides). Until
    2026-12-02 a warning took the time of the first step end at which its check failed: up to a
    step late (ms while rocking)."""
    if not _check_at(p, sig, s, y0, F, h, x_hi, loc, t0, work, which):
        return math.nan
    if _check_at(p, sig, s, y0, F, h, 0.0, loc, t0, work, which):
        return t0  # (the run's start, which no check precedes)
    lo, hi = 0.0, x_hi
    for k in range(1, 16):
        x = x_hi * k / 16.0
        if _check_at(p, sig, s, y0, F, h, x, loc, t0, work, which):
            hi = x
            break
        lo = x
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi or (hi - lo) * h <= 2.3e-16 * max(abs(t0), 1.0):
            break
        if _check_at(p, sig, s, y0, F, h, mid, loc, t0, work, which):
            hi = mid
        else:
            lo = mid
    return t0 + hi * h


#: A check's margin counts as near zero below this fraction of its scale (_margin_scale): a stage
#: margin that low, and lower than at both ends of the step, has the dense output searched for
#: a failure between the stages (_lowest). Steps whose stages stay farther from failing cost
#: nothing more.
NEAR_MISS = 0.02
#: _failure_bound's answer for such a near miss.
SEARCH_DIP = -1.0


@njit(cache=True, inline="always")
def _failure_bound(p, s, gmin, summ, which, at_rest, x_end, K, a, udd, n_full, px, py):
    """Where in a step that ends at fraction x_end (the step's end, or an event) check ``which``
    first failed: x_end if it fails at the end (a, ü and the forces there given); SEARCH_DIP
    if a stage before x_end failed it, or came near zero (NEAR_MISS) lower than both ends (the
    start's from the step's first row of K, only then); +inf if neither, if its warning is
    already raised, or, at rest, for the top slip and the uplift (_rest_checks finds those
    exactly)."""
    if (which < 2 and at_rest) or not _watched(p, summ, which):
        return math.inf
    m_end = _check_margin(p, s, a, udd, n_full, px, py, which)
    if _failed(m_end, which):
        return x_end
    m = gmin[N_GUARDS + 1 + which]
    if m < NEAR_MISS * _margin_scale(p, which) and m < m_end:
        if m < _check_margin(p, s, K[0, 6], K[0, 1], K[0, 9], K[0, 10], K[0, 11], which):
            return SEARCH_DIP
    return math.inf


@njit(cache=True, _nrt=False)
def _warning_time(p, sig, s, y0, F, h, t0, x_end, x_hi, gmin, loc, work, which):
    """The first instant (s) at which check ``which`` fails in the step from t0, up to fraction
    x_end, given _failure_bound's answer x_hi (the end, or SEARCH_DIP); NaN if it holds there."""
    if x_hi == SEARCH_DIP:
        v, x_hi = _lowest(p, sig, s, y0, F, h, x_end, gmin[N_GUARDS + 1 + N_CHECKS + which], loc, t0, work, which)
        if not _failed(v, which):
            return math.nan
    return _first_check_failure(p, sig, s, y0, F, h, t0, x_hi, loc, work, which)


@njit(cache=True, inline="always")
def _cross_breakpoint(p, y, sig, s, t, t_end, ib, breakpoints, pieces, loc, events, n_ev, max_events,
                      indeterminate):
    """At a breakpoint of the floor motion — a sample time of a record (continuous) or a jump
    (pulse start or end) — move to the next piece and re-select the regime.
    Returns (ib, t_stop, sig, s, fresh, n_ev, indeterminate, loc)."""
    nb = breakpoints.shape[0]
    ib += 1
    t_stop = min(breakpoints[ib], t_end) if ib < nb else t_end
    loc_next = _piece(pieces, ib)
    a, av = _ground(loc_next, t)
    a_old, av_old = _ground(loc, t)
    if abs(a - a_old) + abs(av - av_old) <= 1e-12 * (abs(a) + abs(av) + p[G]):
        # Continuous here (a sample of a record): every guard is continuous too, so the regime
        # holds and the last stage of the previous step serves as the first of the next.
        return ib, t_stop, sig, s, False, n_ev, indeterminate, loc_next
    sig2, s2, ok = select_regime(p, y, s, a, av, False, False)
    if not ok:
        indeterminate += 1
    if sig2 != sig or s2 != s:
        if n_ev < max_events:
            events[n_ev, 0] = t
            events[n_ev, 1] = EV_BREAKPOINT
            events[n_ev, 2] = _regime(sig, s)
            events[n_ev, 3] = _regime(sig2, s2)
            events[n_ev, 4] = y[1]
            events[n_ev, 5] = y[1]
            events[n_ev, 6] = y[3]
            events[n_ev, 7] = y[3]
            events[n_ev, 8] = 0.0
            events[n_ev, 9] = 0.0
            n_ev += 1
    return ib, t_stop, sig2, s2, True, n_ev, indeterminate, loc_next


@njit(cache=True, _nrt=False)
def _save_row(y_out, n, y):
    """Saved sample n ← (u, u̇, θ, θ̇) of y."""
    for j in range(4):
        y_out[n, j] = y[j]


@njit(cache=True, _nrt=False)
def _rest_point(p, y, loc, t):
    """At rest at time t, the three things the loop checks that depend on the floor motion alone
    (derivation §3.5): the ratio |P_x|/P_y the statue's base needs (0 where P_y ≤ 0 or |θ| > α,
    as in the loop), and by how much the model's assumptions fail there: |P_x| − μs,top·P_y (the
    statue slips on the pedestal if > 0) and |x_N| − b₁ (the pedestal uplifts if > 0), each −inf
    when its check is off (no top friction given; no pedestal width or height); and −N and −P_y
    (the floor's normal force and the statue's base force, N: the bodies would jump if ≥ 0)."""
    a, av = _ground(loc, t)
    _, _, _, _, n_full, px, py, _, _ = evaluate_all(p, 0, 0, y[1], y[2], y[3], a, av)
    ratio = _need(p, y[2], px, py)
    slip = abs(px) - p[MU_TOP] * py if p[MU_TOP] >= 0.0 else -math.inf
    uplift = -math.inf
    b1 = pedestal_half_width(p)
    if b1 > 0.0:
        xn = pressure_centre(p, 0, a, 0.0, px, py, n_full)
        if math.isfinite(xn):
            uplift = abs(xn) - b1
        elif n_full <= 0.0 and pressure_moment(p, 0, a, 0.0, px, py) != 0.0:
            uplift = math.inf  # (x_N left the base as N fell to zero: _check_margin)
    return ratio, slip, uplift, -n_full, -py


@njit(cache=True, _nrt=False)
def _rest_checks(p, y, loc, t_a, t_b, summ):
    """The largest |P_x|/P_y the statue's base needs while everything rests from t_a to t_b, and
    the first instants there of the top-slip and uplift warnings, if not set yet. For a stretch
    the rest crossing passes without a step (so without the loop's checks), and for a step at
    rest (whose stages straddle a crest of |a_g|: a Ricker pulse's peak fell 0.4 % short of
    |a_p|/g before 2026-12-02). At rest the bodies move with the floor: P_x = m₂·a_g,
    P_y = m₂·(g + a_v), x_N ∝ a_g/(g + a_v), all functions of |a_g|/(g + a_v). On a
    piecewise-linear piece that ratio of two linear functions is largest at an end; on a
    harmonic or a pulse (no vertical part) at an end or at a crest of |a_g| (crest_inside).
    Until 2026-12-02 neither warning was checked at rest (a tall, narrow pedestal tipping under
    a resting statue went unflagged)."""
    ratio, slip, uplift, jump, lift = _rest_point(p, y, loc, t_a)
    r_b, slip_b, uplift_b, jump_b, lift_b = _rest_point(p, y, loc, t_b)
    ratio, slip, uplift = max(ratio, r_b), max(slip, slip_b), max(uplift, uplift_b)
    jump, lift = max(jump, jump_b), max(lift, lift_b)
    tau = crest_inside(loc, t_a, t_b)
    if tau == tau:
        r_c, slip_c, uplift_c, _, _ = _rest_point(p, y, loc, tau)
        ratio, slip, uplift = max(ratio, r_c), max(slip, slip_c), max(uplift, uplift_c)
    if slip > 0.0 and math.isnan(summ[S_TOP_SLIP]):
        summ[S_TOP_SLIP] = _first_failure(p, y, loc, t_a, t_b, 1)
    if uplift > 0.0 and math.isnan(summ[S_UPLIFT]):
        summ[S_UPLIFT] = _first_failure(p, y, loc, t_a, t_b, 2)
    # N and P_y at rest are ∝ g + a_v: linear on a record's piece, constant on the others (a
    # vertical floor motion is a record's), so an end shows a failure and bisection finds it
    if jump >= 0.0 and math.isnan(summ[S_N_NONPOSITIVE]):
        summ[S_N_NONPOSITIVE] = _first_failure(p, y, loc, t_a, t_b, 3)
    if lift >= 0.0 and math.isnan(summ[S_PY_NONPOSITIVE]):
        summ[S_PY_NONPOSITIVE] = _first_failure(p, y, loc, t_a, t_b, 4)
    return ratio


@njit(cache=True, _nrt=False)
def _fails(p, y, loc, t, which):
    """Whether check ``which`` of _rest_point (1: top slip, 2: uplift, 3: N ≤ 0, 4: P_y ≤ 0)
    fails at rest at t."""
    v = _rest_point(p, y, loc, t)[which]
    return v > 0.0 if which <= 2 else v >= 0.0


@njit(cache=True, _nrt=False)
def _first_failure(p, y, loc, t_a, t_b, which):
    """The first time in [t_a, t_b] (s) at which check ``which`` of _rest_point fails at rest, or
    NaN if it never does there. For the warning's time. Checks 1 and 2 grow with
    |a_g|/(g + a_v), and 3 and 4 with −(g + a_v) (only a record's linear pieces have a vertical
    part), so between two crests of |a_g| (next_crest) a failure shows at an end: the crests are
    visited in order from t_a, and the crossing before the first failing one (or t_b) is then
    bisected to the last bit, the only one between it and the crest before."""
    if _fails(p, y, loc, t_a, which):
        return t_a
    lo = t_a
    while True:
        hi = min(next_crest(loc, lo), t_b)
        if _fails(p, y, loc, hi, which):
            break
        if hi >= t_b:
            return math.nan
        lo = hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        if _fails(p, y, loc, mid, which):
            hi = mid
        else:
            lo = mid
    return hi


@njit(cache=True, _nrt=False)
def _hold(t_out, y_out, r_out, n_out, cap, next_grid, n_grid, t0, save_dt, t_limit, y, regime, t_fixed):
    """Save the grid points up to ``t_limit`` while the state ``y`` does not change (at rest, or
    the last point reached only up to rounding), stamped with their grid times, or with
    ``t_fixed`` when it is not NaN. Returns (n_out, next_grid)."""
    while next_grid < n_grid and n_out < cap:
        tg = t0 + next_grid * save_dt
        if tg > t_limit:
            break
        t_out[n_out] = tg if math.isnan(t_fixed) else t_fixed
        _save_row(y_out, n_out, y)
        r_out[n_out] = regime
        n_out += 1
        next_grid += 1
    return n_out, next_grid


@njit(cache=True)
def integrate(p, sig_h, sig_v, breakpoints, t0, t_end, y_init, rtol, atol, max_step, save_dt, save, max_events,
              t_settle, stop_flag):
    """Integrate the hybrid system from t0 to t_end.

    From ``t_settle`` on (s; the end of the floor motion, or +inf) the run also ends as soon as
    every body is at rest: the pedestal stuck and the statue at rest (θ = θ̇ = 0), with the
    floor still, nothing can move again. A run that reaches ``t_end`` while anything still
    moves ends with status STILL_MOVING. ``stop_flag`` (int64[1]) is set by the signal handlers
    of :func:`rocking.solver.signals.deferred_signals`; the loop polls the handlers every
    SIGNAL_POLL_INTERVAL iterations and ends with status INTERRUPTED when it is non-zero.

    Returns (summary, t_out, y_out, regime_out, events): the summary vector (layout above), the
    saved samples (a uniform grid of step ``save_dt`` merged with the event instants; empty when
    ``save`` is False; a sample's regime code carries the signs of the regime, see
    ``SAVED_NEGATIVE_PIVOT``) and the event table (one row per event, N_EVENT_FIELDS columns).
    """
    n_grid = int(math.floor((t_end - t0) / save_dt + 1e-9)) + 1 if save else 0
    cap = n_grid + 2 * max_events + 4 if save else 0
    summ = np.full(N_SUMMARY, np.nan)
    t_out = np.empty(cap)
    y_out = np.empty((cap, 4))
    r_out = np.empty(cap, dtype=np.int8)
    events = np.empty((max_events + 2, N_EVENT_FIELDS))
    scratch = (
        y_init.copy(),
        np.empty(N_STATE),  # y_new
        np.empty(N_STATE),  # work
        np.empty(N_STATE),  # ye: state at an event
        np.empty((dop853.N_K, N_STATE + N_DIAG)),  # K: stages of the step
        np.empty((dop853.N_K, N_STATE + N_DIAG)),  # Ke: stages of the step to an event
        np.empty((dop853.INTERPOLATOR_POWER, N_STATE)),  # F: dense output
        np.empty(N_GUARDS),  # g0: guards at the step start
        np.empty(N_GUARDS),  # g1: guards at the step end
        np.empty(N_GUARDS),  # gbuf
        np.empty(N_GUARDS + 1 + 2 * N_CHECKS),  # gmin: + the largest top-face ratio, the checks' margins and where
        np.empty(N_GUARDS),  # near
        np.ones(N_GUARDS, dtype=np.bool_),  # armed
        np.empty(2 * N_GUARDS),  # gband: scratch of rest_band
    )
    pieces = _piece_table(sig_h, sig_v, breakpoints, t0, t_end)
    n_out, n_ev = _integrate(p, pieces, breakpoints, t0, t_end, rtol, atol, max_step, save_dt, save, n_grid, cap,
                             max_events, t_settle, stop_flag, summ, t_out, y_out, r_out, events, *scratch)
    summ[S_SETTLED] = 1.0 if _cannot_overturn(p, summ, scratch[0], floor_end(sig_h, sig_v)) else 0.0
    return summ, t_out[:n_out], y_out[:n_out], r_out[:n_out], events[:n_ev]


# Compiled without Numba's runtime (``_nrt=False``): the loop never allocates, so it can take
# its arrays without the atomic reference counting Numba otherwise performs at every use of an
# array passed to, or inlined into, a function — a fifth to two fifths of the run time (perf).
@njit(cache=True, _nrt=False)
def _integrate(p, pieces, breakpoints, t0, t_end, rtol, atol, max_step, save_dt, save, n_grid, cap, max_events,
               t_settle, stop_flag, summ, t_out, y_out, r_out, events, y, y_new, work, ye, K, Ke, F, g0, g1, gbuf, gmin, near, armed, gband):
    """The event-driven loop of :func:`integrate` on preallocated arrays; returns the numbers of
    saved samples and of events."""
    for i in range(N_SUMMARY):
        summ[i] = math.nan
    # An interior minimum of a threshold guard is searched for a sign change only when it comes
    # this close to zero (3 % of the guard's natural scale): the cost stays with grazing steps.
    for i in range(N_GUARDS):
        near[i] = -math.inf
    if p[CAN_SLIDE] > 0.5:
        near[SLIP_TO_NEGATIVE] = near[SLIP_TO_POSITIVE] = 0.03 * p[MU_S] * p[M] * p[G]
        near[STOP] = 1e-3
    near[ROCK_TO_NEGATIVE] = near[ROCK_TO_POSITIVE] = 0.03 * p[G] * math.tan(p[ALPHA])
    n_out = 0
    next_grid = 0
    n_ev = 0

    nb = breakpoints.shape[0]
    ib = 0
    t = t0
    status = STATUS_COMPLETED
    exceeded = False
    impacts = 0
    indeterminate = 0
    d_impact = 0.0
    steps = 0
    rejected = 0
    peak_theta = abs(y[2])  # a statue released tilted: its start counts (the first step may turn away)
    peak_u = abs(y[0])
    top_ratio = 0.0
    impact_floor_ratio = 0.0
    energy_scale = 0.0
    balance = 0.0
    impact_short = 0

    # Piece of the floor motion the first step sees, then the initial regime.
    while ib < nb and breakpoints[ib] <= t:
        ib += 1
    t_stop = min(breakpoints[ib], t_end) if ib < nb else t_end
    loc = _piece(pieces, ib)
    a, av = _ground(loc, t)
    s_init = 0
    if y[2] != 0.0:
        s_init = 1 if y[2] > 0.0 else -1
    elif y[3] != 0.0:
        s_init = 1 if y[3] > 0.0 else -1
    sig, s, ok = select_regime(p, y, s_init, a, av, False, False)
    if not ok:
        indeterminate += 1
    e0 = mechanical_energy(p, s, y[1], y[2], y[3])
    energy_scale = max(abs(e0), p[M] * p[G] * 1e-6 * (p[B] + p[H]))
    h = min(max_step, 1e-3, t_end - t0)
    fresh = True  # K[0] and the guards at t must be recomputed (start, event or breakpoint)
    since_poll = 0

    while t < t_end:
        since_poll += 1
        if since_poll >= SIGNAL_POLL_INTERVAL:
            since_poll = 0
            _check_signals()
            if stop_flag[0] != 0:
                status = STATUS_INTERRUPTED
                break
        if sig == 0 and s == 0 and t >= t_settle:
            # At rest on a still floor: nothing can move again (the rest detection of impacts
            # has closed any Zeno sequence), so the run is over.
            break
        if fresh:
            while ib < nb and breakpoints[ib] <= t:
                ib += 1
            t_stop = min(breakpoints[ib], t_end) if ib < nb else t_end
            loc = _piece(pieces, ib)
            rhs(t, y, p, sig, s, loc, K[0])
            a, av = _ground(loc, t)
            evaluate_guards(p, sig, s, y, a, av, exceeded, g0)
            for i in range(N_GUARDS):
                armed[i] = g0[i] > 0.0
            fresh = False
        if sig == 0 and s == 0 and _all_positive(g0):
            # At rest nothing changes until a guard reaches zero, and at rest the guards depend
            # on the floor motion alone: the time up to t_quiet, where rest surely still holds,
            # is crossed without integrating. The step that follows locates the event as any
            # other.
            t_quiet = t
            if loc[0] <= LOCAL_LINEAR and loc[LOCAL_SIZE] <= LOCAL_LINEAR:
                # Piecewise-linear motion (a record between two samples): the guards are linear
                # in time, so positive at both ends means positive in between.
                a1, av1 = _ground(loc, t_stop)
                evaluate_guards(p, 0, 0, y, a1, av1, exceeded, g1)
                if _all_positive(g1):
                    t_quiet = t_stop
            elif loc[0] == LOCAL_COSINE and loc[LOCAL_SIZE] == LOCAL_ZERO:
                # Harmonic motion: rest holds while a_g stays in the rest band; its exit is
                # found in closed form.
                a_lo, a_hi = rest_band(p, y, 0.0, gband)
                t_quiet = cosine_band_exit(loc[1], loc[2], loc[3], t, t_stop, a_lo, a_hi)
                if t_quiet >= t_stop:
                    a1, av1 = _ground(loc, t_stop)
                    evaluate_guards(p, 0, 0, y, a1, av1, exceeded, g1)
            if t_quiet > t:
                top_ratio = max(top_ratio, _rest_checks(p, y, loc, t, t_quiet, summ))
                if save:
                    n_out, next_grid = _hold(t_out, y_out, r_out, n_out, cap, next_grid, n_grid, t0, save_dt,
                                             t_quiet + 1e-12, y, 0, math.nan)
                t = t_quiet
                if t < t_stop:
                    fresh = True
                else:
                    for i in range(N_GUARDS):
                        g0[i] = g1[i]
                    if t < t_end:
                        ib, t_stop, sig, s, fresh, n_ev, indeterminate, loc = _cross_breakpoint(
                            p, y, sig, s, t, t_end, ib, breakpoints, pieces, loc, events, n_ev, max_events,
                            indeterminate,
                        )
                continue
        if s != 0 and s * K[0, 3] < 0.0 and s * y[2] >= 0.0:
            # Rocking back towards the impact: on a parabola s·θ reaches 0 after τ. A step
            # ending soon after that (1.5 τ) still contains the impact but is short enough, in
            # a chattering sequence, for the impact to be read off its dense output (below).
            qa = -0.5 * s * K[0, 3]
            qb = s * y[3]
            tau = (qb + math.sqrt(qb * qb + 4.0 * qa * s * y[2])) / (2.0 * qa)
            if tau > 1e-9:  # (an impact due at once is left to the event location)
                h = min(h, 1.5 * tau)
        if not h > 0.0:  # no step-size rule may stall the loop
            status = STATUS_STEP_FAILED
            break
        h_wanted = min(h, max_step)
        h = min(h_wanted, t_stop - t)
        # Avoid a sliver of a step before a breakpoint.
        if t_stop - (t + h) < 1e-3 * h:
            h = t_stop - t
        # A step cut well short by a breakpoint (a record sample) needs far less than DOP853's
        # 12 stages for the same accuracy: take a 5th-order step there.
        low_order = h < h_wanted
        if low_order:
            _step5(t, y, h, K, work, y_new, p, sig, s, loc, gmin, summ)
            err = dopri5.error_norm(y, y_new, K, h, rtol, atol, 4)
            exponent = 0.2
            fs = FSAL5
        else:
            _step(t, y, h, K, work, y_new, p, sig, s, loc, gmin, summ, True)
            err = dop853.error_norm(y, y_new, K, h, rtol, atol, 4)
            exponent = dop853.ERROR_EXPONENT
            fs = dop853.FSAL
        if not (err <= 1.0):
            rejected += 1
            if not math.isfinite(err):
                h *= 0.1
            else:
                h *= max(0.2, 0.9 * err ** (-exponent))
            if h < 1e-14 * max(1.0, abs(t)):
                status = STATUS_STEP_FAILED
                break
            continue
        steps += 1
        t1 = t + h
        if abs(t1 - t_stop) <= 4e-16 * max(1.0, abs(t_stop)) * 4:
            t1 = t_stop

        # Guards at the end of the step (same piece of the motion as the step).
        # K[fs] is the right-hand side at (t1, y_new), with its forces
        guards_from_forces(p, sig, s, y_new, K[fs, 6], K[fs, 7], K[fs, 1], K[fs, 8], K[fs, 9], exceeded, g1)
        # The dense output costs three more right-hand sides: build it only when this step
        # holds an event candidate, a turning point of θ or a saved sample.
        need_dense = s != 0 and (y[3] > 0.0) != (y_new[3] > 0.0)
        for i in range(N_GUARDS):
            if g1[i] <= 0.0 or (armed[i] and g0[i] > 0.0 and gmin[i] < min(g0[i], g1[i]) and gmin[i] < near[i]):
                need_dense = True
        if save and next_grid < n_grid and t0 + next_grid * save_dt <= t1 + 1e-12 * h:
            need_dense = True
        x_turn = -1.0  # where θ̇ changes sign in the step (a peak of |θ|), if it does
        if need_dense:
            _prepare_step_dense(t, y, y_new, h, K, work, F, p, sig, s, loc, low_order)
            if s != 0 and (y[3] > 0.0) != (y_new[3] > 0.0):
                x_turn = _theta_dot_root(y, F, y[3], y_new[3], 1.0)
        first = -1
        x_first = 2.0
        for i in range(N_GUARDS):
            if g1[i] > 0.0:
                if armed[i] and g0[i] > 0.0 and gmin[i] < min(g0[i], g1[i]) and gmin[i] < near[i]:
                    # The guard has an interior minimum (seen at a stage): it may dip below
                    # zero and come back inside this step. Find the minimum on the dense output
                    # and the first crossing before it.
                    x_neg = _minimum(p, sig, s, y, F, h, loc, t, exceeded, work, gbuf, i)
                    if x_neg > 0.0:
                        g_neg = _guard_at(p, sig, s, y, F, h, x_neg, loc, t, exceeded, work, gbuf, i)
                        x = _locate(p, sig, s, y, F, h, loc, t, exceeded, work, gbuf, i, g0[i], g_neg, 0.0, x_neg)
                        if x < x_first:
                            x_first, first = x, i
                continue
            if armed[i] and g0[i] > 0.0:
                x = _locate(p, sig, s, y, F, h, loc, t, exceeded, work, gbuf, i, g0[i], g1[i], 0.0, 1.0)
            else:
                # A guard that started on zero (just after an event) may have gone positive and
                # back within this step: find an interior point where it is positive.
                x_lo = _positive_inside(p, sig, s, y, F, h, loc, t, exceeded, work, gbuf, i, x_turn)
                if x_lo < 0.0:
                    # A friction or rocking threshold exactly tied when the regime was chosen
                    # (e.g. a pulse whose phase starts rocking at t = 0) and crossed right away:
                    # the regime ends at the start of the step.
                    if i in (SLIP_TO_NEGATIVE, SLIP_TO_POSITIVE):
                        if g1[i] < 0.0:
                            x_first, first = 0.0, i
                    elif i in (ROCK_TO_NEGATIVE, ROCK_TO_POSITIVE):
                        # A rocking threshold that stays tied (a block sliding on the floor with
                        # μk = tan α exactly: its base's acceleration is the threshold for as long
                        # as it slides) is not crossed: it only wobbles by rounding (1e-16 g),
                        # and an uplift there would settle at once, again and again.
                        if g1[i] < -1e-12 * p[G]:
                            x_first, first = 0.0, i
                    elif i == IMPACT and g1[i] < 0.0:
                        # Rocking began at a tangency of the threshold (the floor acceleration
                        # touched g·tan α and turned back): θ went the wrong way from the start.
                        # The uplift did not happen; the statue stays at rest.
                        x_first, first = 0.0, i
                    elif i == EXCEED and g1[i] < 0.0:
                        # Released exactly at θ = α and turning outwards: α is exceeded at
                        # the start (without this, a statue that falls would report that it
                        # never passed α).
                        x_first, first = 0.0, i
                    continue
                g_lo = _guard_at(p, sig, s, y, F, h, x_lo, loc, t, exceeded, work, gbuf, i)
                x = _locate(p, sig, s, y, F, h, loc, t, exceeded, work, gbuf, i, g_lo, g1[i], x_lo, 1.0)
            if x < x_first:
                x_first, first = x, i
        x_end = x_first if first >= 0 else 1.0
        # A regime counts as entered once it lasts: a tie resolved at the same instant does not.
        if x_end > 0.0:
            if s != 0 and math.isnan(summ[S_FIRST_ROCK]):
                summ[S_FIRST_ROCK] = t
            if sig != 0 and math.isnan(summ[S_FIRST_SLIDE]):
                summ[S_FIRST_SLIDE] = t

        # Peak rotation inside the step (θ̇ changes sign).
        if s != 0 and need_dense and x_turn < 0.0 and x_end < 1.0:
            # No net sign change over the whole step, but maybe up to an event inside it.
            thd_end = dop853.dense_component(y, F, x_end, 3)
            if (y[3] > 0.0) != (thd_end > 0.0):
                x_turn = _theta_dot_root(y, F, y[3], thd_end, x_end)
        if 0.0 <= x_turn <= x_end:
            peak_theta = max(peak_theta, abs(dop853.dense_component(y, F, x_turn, 2)))

        # Samples on the output grid up to the end of the (possibly shortened) step.
        if save:
            while next_grid < n_grid:
                tg = t0 + next_grid * save_dt
                if tg > t + x_end * h + 1e-12 * h:
                    break
                if tg >= t:
                    dop853.dense(y, F, (tg - t) / h, work)
                    t_out[n_out] = tg
                    _save_row(y_out, n_out, work)
                    r_out[n_out] = _saved_code(sig, s)
                    n_out += 1
                next_grid += 1

        if first < 0:
            # The friction the statue's base needs: its values at the step's ends are exact, those
            # at the stages (states off the trajectory, of lower order) only hint where it peaks:
            # until 2026-12-03 they were taken as values, and one run read 0.0779872 where its
            # own saved forces peak at 0.0779869. The peak is searched on the dense output when
            # it may lie inside the step above the run's largest so far: a stage above both
            # ends, or an end whose need falls towards it (a peak between it and the stage next
            # to it, which one run read 5e-6 low). A parabola through an end with rate q that
            # peaks within END_GAP of it rises at most |q|·END_GAP·h/2 above it.
            n0 = _need(p, y[2], K[0, 10], K[0, 11])
            n1 = _need(p, y_new[2], K[fs, 10], K[fs, 11])
            top_ratio = max(top_ratio, n1)
            m = gmin[N_GUARDS]
            search = m > top_ratio and m > max(n0, n1)
            if not search and max(m, n1, n0) > top_ratio - (max(m, n0, n1) - min(m, n0, n1)):
                q = _need_rate(p, sig, s, y_new, K[fs], n1, t1, loc, -h)
                search = q < 0.0 and n1 - q * END_GAP * h / 2 > top_ratio
                if not search:
                    q = _need_rate(p, sig, s, y, K[0], n0, t, loc, h)
                    search = q > 0.0 and n0 + q * END_GAP * h / 2 > top_ratio
            if search:
                if not need_dense:
                    need_dense = _prepare_step_dense(t, y, y_new, h, K, work, F, p, sig, s, loc, low_order)
                top_ratio = max(top_ratio, -_lowest(p, sig, s, y, F, h, 1.0, -1.0, loc, t, work, NEED)[0])
            at_rest = sig == 0 and s == 0
            if at_rest:
                top_ratio = max(top_ratio, _rest_checks(p, y, loc, t, t1, summ))
            for w in range(N_CHECKS):
                x_hi = _failure_bound(p, s, gmin, summ, w, at_rest, 1.0, K, K[fs, 6], K[fs, 1], K[fs, 9], K[fs, 10],
                                      K[fs, 11])
                if x_hi <= 1.0:
                    if not need_dense:
                        need_dense = _prepare_step_dense(t, y, y_new, h, K, work, F, p, sig, s, loc, low_order)
                    summ[CHECK_SLOTS[w]] = _warning_time(p, sig, s, y, F, h, t, 1.0, x_hi, gmin, loc, work, w)
            for j in range(N_STATE):
                y[j] = y_new[j]
            t = t1
            for i in range(N_GUARDS):
                g0[i] = g1[i]
                if g1[i] > 0.0:
                    armed[i] = True
            # FSAL: the whole row, the floor accelerations, forces and ok flag with the derivatives
            # (the checks at the step's end read them; copying only the derivatives left them at
            # the last event, and the warnings judged a state long gone)
            for j in range(K.shape[1]):
                K[0, j] = K[fs, j]
            if low_order:
                h = h_wanted  # the cut was the breakpoint's, not the accuracy's
            else:
                h = h * min(10.0, max(0.2, 0.9 * err ** (-exponent))) if err > 0 else 10.0 * h
            if t >= t_stop and t < t_end:
                ib, t_stop, sig, s, fresh, n_ev, indeterminate, loc = _cross_breakpoint(
                    p, y, sig, s, t, t_end, ib, breakpoints, pieces, loc, events, n_ev, max_events,
                    indeterminate,
                )
        else:
            # Event: the state there, then the transition.
            te = t + x_first * h
            top_before = top_ratio
            if not low_order and err <= DENSE_EVENT_ERROR:
                # The step is far shorter than its accuracy allows (its error is that fraction
                # of the tolerance, and the interpolant's scales with it): read the event state
                # off the 7th-order dense output.
                dop853.dense(y, F, x_first, ye)
            else:
                # Otherwise a step to the event (8th order), not the interpolant.
                for j in range(K.shape[1]):
                    Ke[0, j] = K[0, j]
                _step(t, y, te - t, Ke, work, ye, p, sig, s, loc, gmin, summ, False)
                for w in range(N_CHECKS):  # (as fractions of the step the dense output is of)
                    gmin[N_GUARDS + 1 + N_CHECKS + w] *= x_first
            # The forces just before the event: the need there (the stages up to it only hint
            # where the need peaks, as above) and the warnings' checks below.
            a, av = _ground(loc, te)
            udd_e, _, _, _, n_e, px_e, py_e, _, _ = evaluate_all(p, sig, s, ye[1], ye[2], ye[3], a, av)
            top_ratio = max(top_ratio, _need(p, ye[2], px_e, py_e))
            at_rest = sig == 0 and s == 0
            if at_rest:
                top_ratio = max(top_ratio, _rest_checks(p, y, loc, t, te, summ))
            elif x_first > 0.0 and (gmin[N_GUARDS] > top_before or top_ratio > top_before):
                # (the stages of the step, or of the step to the event: a peak up to the event
                # may lie between them, as in an accepted step above. Compared with the largest
                # need before this step: until 2026-12-02 it was compared after the stages had
                # raised it, so the search never ran, and a need peaking 3 ms before an impact
                # read 0.215422 for the 0.215442 its own saved forces show)
                top_ratio = max(top_ratio, -_lowest(p, sig, s, y, F, h, x_first, -1.0, loc, t, work, NEED)[0])
            if x_first > 0.0:
                # The warnings' failures up to the event (F holds the step's dense output: the
                # event was located on it), the state just before the event included.
                for w in range(N_CHECKS):
                    x_hi = _failure_bound(p, s, gmin, summ, w, at_rest, x_first, K, a, udd_e, n_e, px_e, py_e)
                    if x_hi <= x_first:
                        summ[CHECK_SLOTS[w]] = _warning_time(p, sig, s, y, F, h, t, x_first, x_hi, gmin, loc, work,
                                                             w)
            for j in range(N_STATE):
                y[j] = ye[j]
            t = te
            fresh = True
            regime_before = _regime(sig, s)
            ud_before, thd_before = y[1], y[3]
            lost = 0.0
            ratio = 0.0
            kind = 0
            if save and n_out < cap:
                t_out[n_out] = t
                _save_row(y_out, n_out, y)
                r_out[n_out] = _saved_code(sig, s)
                n_out += 1
            a, av = _ground(loc, t)
            sig2, s2, kind, ok, impact, lost, ratio, top, short = apply_transition(
                p, first, x_first == 0.0, y, sig, s, a, av
            )
            if not ok:
                indeterminate += 1
            if first == FALL:
                summ[S_OVERTURN_TIME] = t
                status = STATUS_OVERTURNED
            elif first == EXCEED:
                exceeded = True
                summ[S_EXCEED_TIME] = t
            elif impact:
                impacts += 1
                impact_floor_ratio = max(impact_floor_ratio, ratio)
                impact_short += 1 if short else 0
                if short and p[IMPACT_COULOMB] > 0.5 and math.isnan(summ[S_HELD_IMPACT]):
                    # the Coulomb law found no outcome within friction and held the body anyway:
                    # the two-body model's result ends here (results.response.status_of)
                    summ[S_HELD_IMPACT] = t
                top_ratio = max(top_ratio, top)
                if p[MU_TOP] >= 0.0 and top > p[MU_TOP] and math.isnan(summ[S_TOP_SLIP]):
                    summ[S_TOP_SLIP] = t
            d_impact += lost
            sig, s = sig2, s2
            if n_ev < max_events + 2:
                events[n_ev, 0] = t
                events[n_ev, 1] = kind
                events[n_ev, 2] = regime_before
                events[n_ev, 3] = _regime(sig, s)
                events[n_ev, 4] = ud_before
                events[n_ev, 5] = y[1]
                events[n_ev, 6] = thd_before
                events[n_ev, 7] = y[3]
                events[n_ev, 8] = lost
                events[n_ev, 9] = ratio
                n_ev += 1
            if save and n_out < cap and kind != EV_EXCEED:
                t_out[n_out] = t
                _save_row(y_out, n_out, y)
                r_out[n_out] = _saved_code(sig, s)
                n_out += 1
            if status == STATUS_OVERTURNED:
                peak_theta = max(peak_theta, abs(y[2]))
                peak_u = max(peak_u, abs(y[0]))
                break
            if n_ev >= max_events:
                status = STATUS_MAX_EVENTS
                break

        # Checks at the new point: extremes, energy balance, the model's assumptions.
        peak_theta = max(peak_theta, abs(y[2]))
        peak_u = max(peak_u, abs(y[0]))
        if fresh:
            a, av = _ground(loc, t)
            udd, thdd, ok, _, n_full, px, py, _, _ = evaluate_all(p, sig, s, y[1], y[2], y[3], a, av)
        else:  # K[0] already holds the right-hand side at (t, y) (FSAL)
            a, udd, ok, n_full, px, py = K[0, 6], K[0, 1], K[0, 12] > 0.5, K[0, 9], K[0, 10], K[0, 11]
        if not ok:
            status = STATUS_SINGULAR
            break
        e = mechanical_energy(p, s, y[1], y[2], y[3])
        energy_scale = max(energy_scale, abs(e), abs(y[4]), abs(y[5]))
        balance = max(balance, abs(e - e0 - y[4] + y[5] + d_impact))
        top_ratio = max(top_ratio, _need(p, y[2], px, py))
        # The four checks at the point itself, in every regime (until 2026-12-02 the top slip
        # and the uplift only while the statue rocked, N and P_y too: a tall, narrow pedestal
        # tipping under a resting statue, or a floor falling faster than g under a sliding one,
        # went unflagged). At rest the stretch checks above find their first instants, while
        # moving the stages and the dense output do; this is the event's new state.
        for w in range(N_CHECKS):
            if math.isnan(summ[CHECK_SLOTS[w]]) and _failed(_check_margin(p, s, a, udd, n_full, px, py, w), w):
                summ[CHECK_SLOTS[w]] = t

    if status == STATUS_COMPLETED and (sig != 0 or s != 0):
        status = STATUS_STILL_MOVING  # the time ran out, not the motion
    if save and status != STATUS_OVERTURNED:
        # Last grid point(s) reached exactly at t_end.
        n_out, next_grid = _hold(t_out, y_out, r_out, n_out, cap, next_grid, n_grid, t0, save_dt, t + 1e-9, y,
                                 _saved_code(sig, s), t)
        if n_out < cap and (n_out == 0 or t_out[n_out - 1] < t):
            # The state where the run ended, between grid points: the one its verdict judges
            # (still moving, settled or not, when the time ran out; or where it stopped).
            t_out[n_out] = t
            _save_row(y_out, n_out, y)
            r_out[n_out] = _saved_code(sig, s)
            n_out += 1

    summ[S_STATUS] = status
    summ[S_PEAK_ROTATION] = peak_theta
    summ[S_PEAK_SLIDING] = peak_u
    summ[S_RESIDUAL_SLIDING] = y[0]
    summ[S_IMPACTS] = impacts
    summ[S_TOP_RATIO] = top_ratio
    summ[S_BALANCE] = balance
    summ[S_STEPS] = steps
    summ[S_EVENTS] = n_ev
    summ[S_T_END] = t
    summ[S_IMPACT_FLOOR_RATIO] = impact_floor_ratio
    summ[S_IMPACT_FLOOR_SHORT] = impact_short
    summ[S_INDETERMINATE] = indeterminate
    summ[S_D_IMPACT] = d_impact
    summ[S_D_FRICTION] = y[5]
    summ[S_W_INPUT] = y[4]
    summ[S_ENERGY_SCALE] = energy_scale
    summ[S_REJECTED] = rejected
    return n_out, n_ev


@njit(cache=True)
def _cannot_overturn(p, summ, y, t_floor_end):
    """Whether a run that ended still moving (summary ``summ``, state ``y``) can no longer
    overturn its statue. Once the floor has stopped for good (the run ended at or after
    ``t_floor_end``, s, where both components of its motion end), no energy comes in: friction
    takes energy, and so does every impact of the Coulomb law (derivation §7). So a statue inside
    ±α whose energy, with the ledger's largest error added, is below :func:`overturning_barrier`
    never reaches ±α again. The paper's impact law (Eq. 1) keeps u̇ and can add energy where the
    pedestal slides: no such claim there. (T + V is the same about either corner at θ = 0, and
    at rest on the base, so the pivot is read from the sign of θ.)"""
    if summ[S_STATUS] != STATUS_STILL_MOVING or summ[S_T_END] < t_floor_end:
        return False
    if p[IMPACT_COULOMB] < 0.5 and p[CAN_SLIDE] > 0.5:
        return False
    s = 1 if y[2] >= 0.0 else -1
    energy = mechanical_energy(p, s, y[1], y[2], y[3]) + summ[S_BALANCE]
    return abs(y[2]) < p[ALPHA] and energy < overturning_barrier(p)
