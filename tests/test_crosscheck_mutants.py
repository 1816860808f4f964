"""The integrator cross-check (``rocking.solver.crosscheck``) on what its other tests leave out.

``simulate_crosscheck`` re-integrates the compiled solver's hybrid model with SciPy's DOP853. Its
own code — a plain-Python twin of every floor-motion kind, the initial pivot, the breakpoint
crossings, the summary fields, the run's end, the saved rows — is only checked where a test
compares its output with something else. These tests do that for the parts the mutation run of
``crosscheck.py`` found unchecked (the surviving mutants each test kills are named in its
docstring as ``crosscheck.py:LINE (what the mutant does)``).

References: the compiled solver ``rocking.simulate`` (rtol 1e-10, atol 1e-12) and closed forms
(the uplift time of a ramp, Housner's release, the energy of a block launched from θ = 0). With
the cross-check at rtol 1e-12, atol 1e-13 the two integrators were measured to agree, on the
short runs below (≤ 2 s, a few impacts), to

* ≤ 3e-12 s on event times and ≤ 4e-12 on the velocities of an event row (rigid rocking),
  ≤ 2e-10 s and ≤ 3e-10 (m/s, rad/s) once the block slides and rocks at once;
* ≤ 1e-10 rad on θ and ≤ 1e-10 m on u on the saved grid.

The tolerances used are 1e-9 s on times, 1e-8 on event-row velocities and 1e-8 rad / 1e-8 m on the
grid: 5–100 times the measured differences, and still far below what any of the mutants changes
(a floor acceleration of the wrong shape moves an impact by milliseconds, a wrong pivot or a
wrong regime changes the run altogether).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import rocking as rk
from helpers import on_grid
from oracles import closed_forms as cf
from rocking.excitation.record import GroundMotion
from rocking.models.parameters import pack
from rocking.solver import crosscheck
from rocking.solver.crosscheck import integrate_crosscheck, simulate_crosscheck

COMPILED = {"rtol": 1e-10, "atol": 1e-12}
CROSSCHECK = {"rtol": 1e-12, "atol": 1e-13}
TIME_TOL = 1e-9  # s, event times (measured ≤ 2e-10)
ROW_TOL = 1e-8  # m/s, rad/s, J: the other fields of an event row (measured ≤ 3e-10)
THETA_TOL = 1e-8  # rad, θ on the grid (measured ≤ 1e-10)
U_TOL = 1e-8  # m, u on the grid
VELOCITY_TOL = 1e-7  # rad/s, m/s: θ̇ and u̇ on the grid (measured ≤ 1e-8; ≤ 1e-9 but in one test)

# b = 0.2 m, h = 1 m (tan α = 0.2), rigid, frictionless floor
BLOCK = rk.Statue(width=0.4, height=2.0, mass=1.0)
# the same block on a floor with friction: it slides once the floor pushes it hard enough
SLIPPY = rk.Statue(width=0.4, height=2.0, mass=1.0, friction=rk.Friction(static=0.12, kinetic=0.1))


def _both(system, motion, *, duration=None, save_dt=0.01, compiled=None, crosscheck_options=None, **initial):
    c = rk.simulate(system, motion, duration=duration,
                    options=rk.Options(save_dt=save_dt, **COMPILED, **(compiled or {})), **initial)
    r = simulate_crosscheck(system, motion, duration=duration,
                            options=rk.Options(**CROSSCHECK, **(crosscheck_options or compiled or {})),
                            save_dt=save_dt, **initial)
    return c, r


def _assert_rows_agree(c, r, *, row_tol=ROW_TOL):
    """The same event table: kinds and regimes exactly, times within TIME_TOL, the other fields
    (u̇, θ̇ before/after, energy lost, friction ratio) within ``row_tol``."""
    ec, er = c.event_table, r["event_table"]
    assert ec.shape == er.shape, (
        f"{len(ec)} compiled events {[rk.EventKind(int(k)).name for k in ec[:, 1]]} vs {len(er)} "
        f"cross-check events {[rk.EventKind(int(k)).name for k in er[:, 1]]}")
    for k, (a, b) in enumerate(zip(ec, er)):
        assert tuple(a[1:4]) == tuple(b[1:4]), f"event {k}: {a[:4]} vs {b[:4]}"
        assert abs(a[0] - b[0]) <= TIME_TOL, f"event {k} ({rk.EventKind(int(a[1])).name}): t {a[0]!r} vs {b[0]!r}"
        np.testing.assert_allclose(b[4:], a[4:], rtol=0, atol=row_tol, err_msg=f"event {k} row")


def _assert_grid_agrees(c, r, dt, *, skip=0):
    tc, thc, uc = on_grid(c, dt)
    tc, thc, uc = tc[skip:], thc[skip:], uc[skip:]
    assert tc.size == r["t"].size
    np.testing.assert_allclose(r["t"], tc, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r["theta"], thc, rtol=0, atol=THETA_TOL)
    np.testing.assert_allclose(r["u"], uc, rtol=0, atol=U_TOL)
    # the velocities of the same rows (on_grid keeps the first row at a grid time)
    rows = np.flatnonzero(np.isin(c.t, tc))
    _, first = np.unique(c.t[rows], return_index=True)
    rows = rows[first]
    np.testing.assert_allclose(r["theta_dot"], c.theta_dot[rows], rtol=0, atol=VELOCITY_TOL)
    np.testing.assert_allclose(r["u_dot"], c.u_dot[rows], rtol=0, atol=VELOCITY_TOL)


def _assert_summary_agrees(c, r):
    s = c.summary()
    assert r["status"] == c.status
    for key in ("first_rocking_time", "first_sliding_time", "overturn_time", "exceeded_alpha_time"):
        if s[key] is None:
            assert r[key] is None, key
        else:
            assert r[key] == pytest.approx(s[key], abs=TIME_TOL), key
    assert r["end_time"] == pytest.approx(c.end_time, abs=TIME_TOL)
    assert r["peak_rotation"] == pytest.approx(c.peak_rotation, abs=THETA_TOL)
    assert r["peak_sliding"] == pytest.approx(s["peak_sliding"], abs=U_TOL)
    assert r["residual_sliding"] == pytest.approx(s["residual_sliding"], abs=U_TOL)


def _assert_impacts_agree(c, r):
    assert len(r["impacts"]) == len(c.impacts)
    for a, b in zip(c.impacts, r["impacts"]):
        assert b.time == pytest.approx(a.time, abs=TIME_TOL)
        np.testing.assert_allclose(b[1:], a[1:], rtol=0, atol=ROW_TOL)


# ---------------------------------------------------------------------------------------------
# Floor motions: the cross-check's plain-Python twin of each signal kind
# ---------------------------------------------------------------------------------------------
def test_ricker_pulse_matches_compiled():
    """A Ricker pulse (0.4 g, 2 Hz) lifts the block at its main lobe; three impacts follow within
    2 s and the run ends while it still rocks. Events, grid, impacts and summary agree with the
    compiled solver (which evaluates the pulse with its own ``excitation.signal``).

    Kills crosscheck.py:179 (every arithmetic change of the Ricker formula: ``1 + 2x``, ``t + t0``,
    ``a/(…)``, ``2/(…)``, ``π/f``, ``/exp``, ``·2`` for ``**2``, ``**3`` in the polynomial or the
    exponent) — each moves the uplift by milliseconds or more; crosscheck.py:446/447 (first rocking
    time: set at a zero-length segment only, set while at rest, ``or``); crosscheck.py:599/600
    (impact rows: u̇ after read from θ̇ before, impacts picked by the regime code); crosscheck.py:507
    (status: ``still_moving`` here, ``completed`` with the mutants' inverted tests only at rest)."""
    c, r = _both(rk.System(statue=BLOCK), rk.RickerPulse(amplitude=0.4 * 9.81, frequency=2.0), duration=2.0)
    _assert_rows_agree(c, r)
    kinds = [e[1] for e in r["events"]]
    assert kinds[0] == rk.EventKind.UPLIFT and kinds.count(rk.EventKind.IMPACT) >= 3
    _assert_grid_agrees(c, r, 0.01)
    _assert_summary_agrees(c, r)
    _assert_impacts_agree(c, r)
    assert r["status"] == "still_moving" and r["first_rocking_time"] > 0.5


def test_ramp_uplift_time_closed_form():
    """Oracle O1: a ramp a_g = k·t lifts a block at rest when k·t reaches g·tan α, at
    t = g·(b/h)/k exactly (0.4904 s here); afterwards the block rocks on the ramp to α (EXCEED).
    The uplift time is compared with the closed form to 1e-12 s (rounding only: the guard is
    linear in t, Brent's method converges to a few ulp) and the whole run with the compiled solver.

    Kills crosscheck.py:181 (``a0/t``) and crosscheck.py:177 (``not kind == RICKER``: the ramp
    evaluated by the Ricker formula, a constant)."""
    k = 4.0
    c, r = _both(rk.System(statue=BLOCK), rk.Ramp(rate=k, end=1.0), duration=1.5)
    t_up = rk.g * (0.2 / 1.0) / k
    first = r["events"][0]
    assert first[1] == rk.EventKind.UPLIFT
    assert first[0] == pytest.approx(t_up, abs=1e-12)
    assert r["first_rocking_time"] == pytest.approx(t_up, abs=1e-12)
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.01)
    _assert_summary_agrees(c, r)
    _assert_impacts_agree(c, r)  # none: the EXCEED row (regime before ROCK) is not an impact


@pytest.mark.parametrize(
    "motion",
    [
        rk.Harmonic(amplitude=3.0, frequency=1.5, cycles=2),
        rk.Harmonic(amplitude=3.0, frequency=1.5, cycles=2, form="sin"),
        rk.SinePulse(amplitude=3.5, frequency=2.0),
        rk.CosinePulse(amplitude=3.0, frequency=2.0),
        rk.RectanglePulse(amplitude=2.5, width=0.3),
    ],
    ids=["harmonic-cos", "harmonic-sin", "sine-pulse", "cosine-pulse", "rectangle"],
)
def test_harmonic_and_pulse_shapes_match_compiled(motion):
    """Each of the other signal kinds the cross-check evaluates itself (harmonic cos and sin, the
    sine, cosine and rectangular pulses) on a block that rocks (from t = 0 when the motion starts
    above the threshold), 1.5 s: the same events, grid and summary as the compiled solver.
    (Coverage of the remaining plain-Python formulas; the harmonic ones are also exercised by the
    benchmark cases.)"""
    c, r = _both(rk.System(statue=BLOCK), motion, duration=1.5)
    assert r["first_rocking_time"] is not None
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.01)
    _assert_summary_agrees(c, r)


def _jump_record(vertical=True):
    """A record sampled every 0.05 s from t = 0.2 s to 1.2 s: zero before, then a jump to
    0.29 g (above the block's threshold 0.2 g), a 1.5 Hz sine of 0.35 g, and a 2 Hz vertical
    component of 0.3 g; the last interval [1.15, 1.2] s is far from zero."""
    tt = 0.2 + 0.05 * np.arange(21)
    h = 0.35 * 9.81 * np.sin(2 * np.pi * 1.5 * (tt - 0.2) + 1.0)
    v = 0.3 * 9.81 * np.cos(2 * np.pi * 2.0 * (tt - 0.2)) if vertical else None
    return GroundMotion(time=tt, values=h, vertical=v)


@pytest.mark.parametrize("vertical", [True, False], ids=["with-vertical", "horizontal-only"])
def test_sampled_record_with_a_jump_at_its_start(vertical):
    """A sampled record whose first sample is not at t = 0: the floor acceleration jumps from 0 to
    above the threshold at that breakpoint, where the regime is chosen again (a BREAKPOINT event
    REST → ROCK at exactly t = 0.2 s), then the block rocks (two impacts) through the last sample
    interval and past the end of the record. With and without a vertical component. Events
    (rows), grid and summary as the compiled solver.

    Kills crosscheck.py:161 (``times[n - 2]``: the last interval taken as outside the record),
    crosscheck.py:164 (``n - 3``: the last interval extrapolated from the one before),
    crosscheck.py:312 (the regime at a breakpoint chosen with the acceleration of the piece
    before it: no jump, an UPLIFT later), crosscheck.py:467 (``te > t_stop`` / ``te >= t_end``:
    breakpoints never crossed), crosscheck.py:318 (``y[4]`` in the BREAKPOINT row)."""
    c, r = _both(rk.System(statue=BLOCK), _jump_record(vertical), duration=1.5, save_dt=0.05)
    first = r["event_regimes"][0]
    assert first[1] == rk.EventKind.BREAKPOINT and first[0] == 0.2
    assert (first[2], first[3]) == (rk.Regime.REST, rk.Regime.ROCK)
    assert r["first_rocking_time"] == 0.2
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.05)
    _assert_summary_agrees(c, r)
    assert r["diagnostics"]["indeterminate"] == 0


def test_a_block_released_tilted_under_a_record_steps_to_its_first_sample():
    """A block released at θ0 = 0.05 rad rocks from t = 0 under a record sampled every 0.01 s: its
    first step must stop at the record's first sample, as every later one does (the other tests
    of records start at rest, where the rest path takes its own limit). Events, grid and summary
    as the cross-check, which steps sample by sample. (Written for compiled.py:491's mutant
    4992d5ed, which it does not kill: the loop sets the limit again before the first step, so that
    line's limit is a dead store and the mutant equivalent.)"""
    tt = np.arange(0.0, 1.5 + 1e-9, 0.01)
    motion = GroundMotion(time=tt, values=2.0 * np.sin(2.0 * np.pi * 1.5 * tt))
    c, r = _both(rk.System(statue=BLOCK), motion, duration=1.5, save_dt=0.05, initial_rotation=0.05)
    assert len(r["impacts"]) >= 2
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.05)
    _assert_summary_agrees(c, r)


def test_breakpoint_event_row_rocking_to_slide_rock():
    """Released from θ0 = 0.1 rad on a still floor, the block rocks; at t = 0.3 s a record starts
    with a jump to −4 m/s², which the floor friction (μ = 0.12) cannot transmit: the regime turns
    ROCK → SLIDE_ROCK at the breakpoint, with θ, θ̇ ≠ 0 and u̇ = 0. That BREAKPOINT row (u̇ and
    θ̇ before and after) and the following impacts agree with the compiled solver's rows; the first
    sliding time is the breakpoint.

    Kills crosscheck.py:318 (u̇ before or after of the BREAKPOINT row read from θ),
    crosscheck.py:449 (``sig != 1``: sliding counted from the first segment), crosscheck.py:497
    (the peak sliding fed with u̇ after an event), crosscheck.py:600 (impacts picked by the regime
    code: the impacts in SLIDE_ROCK are lost)."""
    motion = GroundMotion(time=np.array([0.3, 0.5, 0.7]), values=np.array([-4.0, -4.0, 0.0]))
    c, r = _both(rk.System(statue=SLIPPY), motion, duration=1.0, initial_rotation=0.1)
    first = r["event_table"][0]
    assert rk.EventKind(int(first[1])) == rk.EventKind.BREAKPOINT and first[0] == 0.3
    assert rk.Regime(int(first[3])) == rk.Regime.SLIDE_ROCK and first[6] != 0.0
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.01)
    # The peak rotation is the initial tilt θ0 = 0.1 rad in both (until 2026-11-24 the compiled
    # solver said 0.0999996 rad, |θ| after its first step: it started its peak from 0).
    _assert_summary_agrees(c, r)
    _assert_impacts_agree(c, r)
    assert r["peak_rotation"] == 0.1 and c.summary()["peak_rotation"] == 0.1
    assert r["first_sliding_time"] == 0.3 and r["first_rocking_time"] == 0.0


def test_sliver_before_the_first_breakpoint():
    """A record whose first sample is at t = 1e-16 s: the segment [0, 1e-16] is shorter than the
    cross-check's "event at the segment start" tolerance (64 ulp), so it is skipped and the
    breakpoint crossed at once (BREAKPOINT REST → ROCK at 1e-16 s); the run goes on to 1 s as in
    the compiled solver. (The grid point t = 0, inside the skipped sliver, is not saved by the
    cross-check — the compiled solver saves it — so the grids are compared from 0.01 s on.)

    Kills crosscheck.py:349 (``break`` after the sliver: the run ends at 1e-16 s)."""
    motion = GroundMotion(time=np.array([1e-16, 0.3, 0.6]), values=np.array([3.0, 3.0, 0.0]))
    c, r = _both(rk.System(statue=BLOCK), motion, duration=1.0)
    assert r["event_regimes"][0][1] == rk.EventKind.BREAKPOINT
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.01, skip=1)
    _assert_summary_agrees(c, r)
    assert r["end_time"] == 1.0


# ---------------------------------------------------------------------------------------------
# Initial states
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("theta0, omega0", [(-0.1, 0.0), (0.0, -0.4), (0.0, 1.0)])
def test_initial_pivot(theta0, omega0):
    """The pivot of an initial rocking state is the sign of θ0, or of θ̇0 when θ0 = 0. Free
    rocking of a squat block (b = 0.5 m, h = 1 m) on a still floor for 1.2 s, against the compiled
    solver and closed forms:

    * θ0 = −0.1 (released at rest): first impact at Housner's exact t1 with θ̇ = +ω1 (1e-9);
    * θ0 = 0, θ̇0 = −0.4 or +1 rad/s: the block climbs on the corner on the side of θ̇0 to the peak
      θmax = α − acos(cos α + θ̇0²/(2p²)) (energy; |θ| compared to 1e-9 rad relative, the
      cross-check locates θ̇ = 0 exactly), then returns and impacts.

    Kills crosscheck.py:328 (θ0 < 0 given pivot +1), crosscheck.py:330 (the pivot from θ̇: ``<=``,
    ``>=``, ``else 1``, ``else −2``), crosscheck.py:329 (``θ̇ != 1``: θ̇0 = 1 taken as at rest)."""
    b, h, g = 0.5, 1.0, rk.g
    quiet = rk.RectanglePulse(amplitude=0.0, width=3.0)
    c, r = _both(rk.System(statue=rk.Statue(width=2 * b, height=2 * h, mass=1.0)), quiet, duration=1.2,
                 initial_rotation=theta0, initial_angular_velocity=omega0)
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.01)
    _assert_summary_agrees(c, r)
    alpha, R = math.atan2(b, h), math.hypot(b, h)
    if theta0 != 0.0:
        first = r["impacts"][0]
        assert first.time == pytest.approx(cf.free_rocking_t1_exact(b, h, abs(theta0), g), abs=1e-9)
        assert first.theta_dot_before == pytest.approx(cf.free_rocking_impact_velocity(b, h, abs(theta0), g), rel=1e-9)
    else:
        p2 = 3.0 * g / (4.0 * R)
        theta_max = alpha - math.acos(math.cos(alpha) + omega0**2 / (2.0 * p2))
        assert r["peak_rotation"] == pytest.approx(theta_max, rel=1e-9)
        # the climb is on the side of θ̇0: θ keeps the sign of θ̇0 until the first impact
        before = r["t"] < r["impacts"][0].time
        assert np.all(np.sign(r["theta"][before][1:]) == math.copysign(1.0, omega0))


# ---------------------------------------------------------------------------------------------
# The run's end: status, settling, max_events, the last grid points
# ---------------------------------------------------------------------------------------------
def test_completed_at_rest_when_the_duration_runs_out():
    """A sine pulse below the rocking threshold (1 m/s² < 0.2 g) leaves the block at rest: with a
    given duration (0.8 s, shorter than 1 s) the run completes, status ``completed``, end 0.8 s,
    the grid k·0.01 s up to 0.8 s with θ = u = 0.

    Kills crosscheck.py:507 (``sig == 0`` / ``sig != 1``: ``still_moving`` at rest),
    crosscheck.py:584 (``t_end <= 1`` rejects a duration under 1 s)."""
    c, r = _both(rk.System(statue=BLOCK), rk.SinePulse(amplitude=1.0, frequency=2.0), duration=0.8)
    assert c.status == "completed" and r["status"] == "completed"
    assert r["end_time"] == 0.8 and r["events"] == []
    np.testing.assert_allclose(r["t"], 0.01 * np.arange(81), rtol=0, atol=1e-12)
    assert not np.any(r["theta"]) and not np.any(r["u"])


def test_settles_after_the_motion_like_compiled():
    """Without a duration the run follows the free motion after the floor stops (here a 0.5 s
    sine pulse of 3 m/s²) until the block is at rest: the rocking decays (restitution 0.6) and
    the rest_velocity rule ends it with a SETTLE event at ≈ 1.55 s, status ``completed``, as in
    the compiled solver (end time within 1e-9 s; measured 4e-11 s). The saved grid stops at the
    end, not at the free-motion limit (2 s after the pulse).

    Kills crosscheck.py:339 (``s != 0``: the run stopped at the end of the motion while the block
    still rocks), crosscheck.py:513 (``tg <= t + 1e-9``: the grid filled up to the limit with the
    final state)."""
    block = rk.Statue(width=0.4, height=2.0, mass=1.0, restitution=0.6)
    c, r = _both(rk.System(statue=block), rk.SinePulse(amplitude=3.0, frequency=2.0), compiled={"free_time_limit": 2.0})
    assert r["status"] == "completed" and r["events"][-1][1] == rk.EventKind.SETTLE
    assert 1.0 < r["end_time"] < 2.0
    _assert_rows_agree(c, r)
    _assert_summary_agrees(c, r)
    assert r["t"][-1] <= r["end_time"] and r["t"].size == math.floor(r["end_time"] / 0.01 + 1e-9) + 1
    _assert_grid_agrees(c, r, 0.01)


def test_run_ends_at_the_motion_end_when_nothing_moves():
    """Without a duration, a sub-threshold pulse (1 m/s² for 0.5 s) leaves everything at rest: the
    run ends at the end of the motion, t = 0.5 s exactly (the free motion of a still floor moves
    nothing), as in the compiled solver.

    Kills crosscheck.py:339 (``t > t_settle``: the run goes on to the free-motion limit)."""
    c, r = _both(rk.System(statue=BLOCK), rk.SinePulse(amplitude=1.0, frequency=2.0), compiled={"free_time_limit": 2.0})
    assert c.end_time == 0.5 and r["end_time"] == 0.5 and r["status"] == "completed"
    assert r["t"][-1] == pytest.approx(0.5, abs=1e-12)


def test_max_events_stops_like_compiled():
    """``Options.max_events = 3``: the run stops at the third event (UPLIFT, IMPACT, IMPACT) with
    status ``max_events``, as the compiled solver does (end time within 1e-9 s; measured 2e-11 s).

    Kills crosscheck.py:500 (``>``: one event more), crosscheck.py:502 (``continue``: the run goes
    on to the end)."""
    block = rk.Statue(width=0.4, height=2.0, mass=1.0, restitution=0.6)
    c, r = _both(rk.System(statue=block), rk.SinePulse(amplitude=3.0, frequency=2.0), duration=2.0,
                 compiled={"max_events": 3})
    assert r["status"] == "max_events" and len(r["events"]) == 3
    _assert_rows_agree(c, r)
    _assert_summary_agrees(c, r)
    assert r["t"][-1] <= r["end_time"] < 1.0


def test_a_run_that_starts_at_a_later_time_matches_compiled():
    """Both integrators take a start time t0 (``integrate_crosscheck`` and the compiled
    ``integrate``; ``simulate`` always starts at 0). The block, at rest, starts at t0 = 0.2 s, the
    first sample of a record that jumps there from 0 to 0.29 g (above the block's threshold,
    0.2 g) for one sample interval, is still from 0.3 s to 0.6 s and then shakes: it rocks from
    t0 on and impacts five times (0.368 s to 1.226 s) up to the run's end at 1.5 s. The grid
    t0 + k·0.01 s, the saved rows, their regimes and the event table are the compiled solver's
    (times within 1e-9 s, states within 1e-8).

    Kills, on today's source (ids of the session in bench/MUTATION.md, twenty-sixth round):
    crosscheck.py:270 (the grid t0 − k·dt), crosscheck.py:327 (the motion's piece for the initial
    regime taken at t0 − ½(t_stop − t0), before the record, or at t0 + ½(t_stop + t0), the still
    stretch: the block is said to be at rest at t0 and lifts off there at once, one UPLIFT row
    more). Breakpoints before and at t0 passed in too (0.05, 0.1 and 0.2 s) give the same run,
    in both (the compiled solver passes them over at compiled.py:468, which nothing else
    reaches: ``simulate`` starts at 0 and passes only later breakpoints): kills crosscheck.py:283 (``<=`` / ``>=`` / ``not`` / ``or`` in the loop that passes them over)
    and :284 (two passed at a time, which skips the one at 0.25 s)."""
    from rocking.results.response import split_saved_codes
    from rocking.solver.compiled import N_STATE, integrate

    # sampled every 0.05 s from 0.2 s: 0.29 g for one interval, still from 0.3 s to 0.6 s, then a
    # 1.5 Hz sine of 0.35 g
    tt = 0.2 + 0.05 * np.arange(21)
    values = np.where(tt < 0.27, 0.29 * 9.81, np.where(tt < 0.6, 0.0, 0.35 * 9.81 * np.sin(2 * np.pi * 1.5 * (tt - 0.6))))
    motion = GroundMotion(time=tt, values=values)
    o = rk.Options(**COMPILED)
    p = pack(rk.System(statue=BLOCK), gravity=o.gravity, normal_force=o.normal_force, impact=o.impact,
             rest_velocity=o.rest_velocity)
    t0, t_end = 0.2, 1.5
    bp = crosscheck._breakpoints(motion, t0, t_end)
    sh, sv = motion.signal(), motion.vertical_signal()
    _, tc, yc, rc, ec = integrate(p, (sh.kind, sh.params, sh.time, sh.values), (sv.kind, sv.params, sv.time, sv.values),
                                  bp, t0, t_end, np.zeros(N_STATE), o.rtol, o.atol, o.max_step, 0.01, True,
                                  o.max_events, math.inf, np.zeros(1, dtype=np.int64))
    x = rk.Options(**CROSSCHECK)
    r = integrate_crosscheck(p, sh, sv, bp, t0, t_end, np.zeros(4), x.rtol, x.atol, x.max_step, 0.01, True,
                             x.max_events)
    kinds = [rk.EventKind(int(k)) for k in r["event_table"][:, 1]]
    regime, _, _ = split_saved_codes(rc)
    assert r["regime"][0] == regime[0] == 1 and kinds == [rk.EventKind.IMPACT] * 5  # rocking from t0 on
    assert r["event_table"].shape == ec.shape
    np.testing.assert_array_equal(r["event_table"][:, 1:4], ec[:, 1:4])
    np.testing.assert_allclose(r["event_table"][:, 0], ec[:, 0], rtol=0, atol=TIME_TOL)
    np.testing.assert_allclose(r["event_table"][:, 4:], ec[:, 4:], rtol=0, atol=ROW_TOL)
    on = r["on_grid"]
    np.testing.assert_allclose(r["t"][on], t0 + 0.01 * np.arange(131), rtol=0, atol=1e-12)
    assert r["t"].shape == tc.shape
    np.testing.assert_allclose(r["t"], tc, rtol=0, atol=TIME_TOL)
    np.testing.assert_allclose(r["state"], yc[:, :4], rtol=0, atol=ROW_TOL)
    np.testing.assert_array_equal(r["regime"], regime)
    # breakpoints before and at t0 (the record's start) are passed over: the same run
    early = np.concatenate(([0.05, 0.1, t0], bp))
    again = integrate_crosscheck(p, sh, sv, early, t0, t_end, np.zeros(4), x.rtol, x.atol, x.max_step, 0.01, True,
                                 x.max_events)
    np.testing.assert_array_equal(again["event_table"], r["event_table"])
    np.testing.assert_array_equal(again["t"], r["t"])
    _, tc2, yc2, _, ec2 = integrate(p, (sh.kind, sh.params, sh.time, sh.values), (sv.kind, sv.params, sv.time, sv.values),
                                    early, t0, t_end, np.zeros(N_STATE), o.rtol, o.atol, o.max_step, 0.01, True,
                                    o.max_events, math.inf, np.zeros(1, dtype=np.int64))
    np.testing.assert_array_equal(ec2, ec)
    np.testing.assert_array_equal(tc2, tc)
    np.testing.assert_array_equal(yc2, yc)


def test_the_last_grid_point_after_a_last_segment_of_10_microseconds():
    """The grid's last point may lie past the run's end by rounding: 3 × 0.1 s is
    0.30000000000000004 s for a 0.3 s run. A segment's sampling takes a grid point up to
    1e-12 of its length past its end, so after a 10 µs last segment (a record sample at
    0.29999 s) that point falls to the end-of-run fill, which takes points up to 1e-9 s past the
    end. The block, lifted by a 2 Hz sine record of 0.3 g, still rocks at 0.3 s: four grid
    points, 0 to 0.3 s, the last one with the state at the end (the compiled solver's last row).

    Kills, on today's source (twenty-sixth round): crosscheck.py:512 (the fill skipped:
    ``status == "overturned"``, ``not (…)``), crosscheck.py:514 (``not …``), crosscheck.py:516
    (``tg > t − 1e-9``, ``tg <= t + 1e-9``, ``not …``; the point left out), crosscheck.py:518
    (the point not flagged as on the grid)."""
    tt = np.array([0.05, 0.1, 0.15, 0.2, 0.25, 0.29999])
    motion = GroundMotion(time=tt, values=0.3 * 9.81 * np.sin(2 * np.pi * 2.0 * tt))
    c, r = _both(rk.System(statue=BLOCK), motion, duration=0.3, save_dt=0.1)
    assert 3 * 0.1 > 0.3 and r["status"] == c.status == "still_moving"
    np.testing.assert_array_equal(r["t"], 0.1 * np.arange(4))
    # the compiled solver stamps that last row with the end time, 0.3 s
    assert c.t[-1] == 0.3 and c.t[-2] == 0.2
    for key, tol in (("theta", THETA_TOL), ("u", U_TOL), ("theta_dot", VELOCITY_TOL), ("u_dot", VELOCITY_TOL)):
        assert r[key][-1] == pytest.approx(getattr(c, key)[-1], abs=tol), key
    assert r["theta"][-1] != 0.0
    _assert_rows_agree(c, r)
    raw = _raw(rk.System(statue=BLOCK), motion, 0.3, (0.0, 0.0, 0.0, 0.0), save_dt=0.1)
    assert raw["t"][-1] == 0.1 * 3 and raw["on_grid"][-1]


# ---------------------------------------------------------------------------------------------
# Output contract: save_dt, the event rows of integrate_crosscheck, the diagnostics, arguments
# ---------------------------------------------------------------------------------------------
def test_save_dt_none_follows_simulate():
    """``save_dt=None``: the rule of ``simulate`` — the record's time step (0.05 s here), else
    ``Options.save_dt``, else 0.01 s — gives the same grid as the compiled solver's default.

    Kills crosscheck.py:590 (``and`` for ``or`` twice: 0.01 s instead of the record's step;
    ``1.01`` s for the 0.01 s default)."""
    rec = _jump_record(vertical=False)
    for motion, dt in ((rec, 0.05), (rk.SinePulse(amplitude=1.0, frequency=2.0), 0.01)):
        r = simulate_crosscheck(rk.System(statue=BLOCK), motion, duration=0.6, options=rk.Options(**CROSSCHECK),
                                save_dt=None)
        c = rk.simulate(rk.System(statue=BLOCK), motion, duration=0.6, options=rk.Options(**COMPILED))
        tc, _, _ = on_grid(c, dt)
        np.testing.assert_allclose(r["t"], tc, rtol=0, atol=1e-12)
        np.testing.assert_allclose(r["t"], dt * np.arange(round(0.6 / dt) + 1), rtol=0, atol=1e-12)
    r = simulate_crosscheck(rk.System(statue=BLOCK), rec, duration=0.6,
                            options=rk.Options(save_dt=0.1, **CROSSCHECK), save_dt=None)
    np.testing.assert_allclose(r["t"], 0.1 * np.arange(7), rtol=0, atol=1e-12)


def _raw(system, motion, duration, y0, *, save=True, save_dt=0.01):
    o = rk.Options(**CROSSCHECK)
    p = pack(system, gravity=o.gravity, normal_force=o.normal_force, impact=o.impact, rest_velocity=o.rest_velocity)
    bp = crosscheck._breakpoints(motion, 0.0, duration)
    return integrate_crosscheck(p, motion.signal(), motion.vertical_signal(), bp, 0.0, duration,
                                np.array(y0, dtype=float), o.rtol, o.atol, o.max_step, save_dt, save,
                                o.max_events)


def test_integrate_crosscheck_rows_match_compiled_output():
    """``integrate_crosscheck`` returns the grid rows and, at each event, the state just before
    and (except at EXCEED, where nothing jumps) just after, "as in the compiled output". Released
    from θ0 = 0.1 and pushed by a record from 0.3 s, the block impacts and then exceeds α: the
    rows (times, states, regimes) are those of the compiled ``Response`` (104 rows; times within
    1e-9 s, states within 1e-8). With ``save=False`` there are no rows at all.

    Kills crosscheck.py:495 (``not save``: no row after an event; ``save or``: a row after EXCEED
    too, and rows at events with ``save=False``; ``== EV_EXCEED``), crosscheck.py:477 (``not save``:
    no row before an event), crosscheck.py:489 (``not impact``: the impact count)."""
    motion = GroundMotion(time=np.array([0.3, 0.5, 0.7]), values=np.array([2.4, 2.4, 0.0]))
    system = rk.System(statue=BLOCK)
    c = rk.simulate(system, motion, duration=1.0, options=rk.Options(save_dt=0.01, **COMPILED), initial_rotation=0.1)
    assert [e.kind for e in c.events] == [rk.EventKind.IMPACT, rk.EventKind.EXCEED_ALPHA]
    raw = _raw(system, motion, 1.0, (0.0, 0.0, 0.1, 0.0))
    assert raw["t"].shape == c.t.shape
    np.testing.assert_allclose(raw["t"], c.t, rtol=0, atol=TIME_TOL)
    np.testing.assert_allclose(raw["state"], c.state[:, :4], rtol=0, atol=ROW_TOL)
    np.testing.assert_array_equal(raw["regime"], c.regime)
    assert int(np.count_nonzero(~raw["on_grid"])) == 3  # before/after the impact, before EXCEED
    assert raw["impacts"] == 1 and raw["status"] == c.status
    # the impact count of a run with more transitions than impacts (UPLIFT, then 3 IMPACTs)
    ricker = _raw(system, rk.RickerPulse(amplitude=0.4 * 9.81, frequency=2.0), 2.0, (0.0, 0.0, 0.0, 0.0), save=False)
    kinds = [rk.EventKind(int(k)) for k in ricker["event_table"][:, 1]]
    assert kinds.count(rk.EventKind.UPLIFT) == 1 and ricker["impacts"] == kinds.count(rk.EventKind.IMPACT) == 3
    quiet = _raw(system, motion, 1.0, (0.0, 0.0, 0.1, 0.0), save=False)
    assert quiet["t"].size == 0 and quiet["state"].shape == (0, 4)
    assert quiet["event_table"].shape == raw["event_table"].shape


def test_diagnostics_of_a_clean_run(monkeypatch):
    """On a run with breakpoints and events but no tie, grazing guard or inconsistent regime (the
    jump record: a breakpoint crossing every 0.05 s, a BREAKPOINT event, impacts), the
    diagnostics count nothing unusual, and ``rhs_evaluations`` / ``solve_ivp_calls`` are exactly
    SciPy's function evaluations (``nfev``) and the number of ``solve_ivp`` calls (counted by
    wrapping ``solve_ivp``).

    Kills crosscheck.py:261/262 (counters starting at 1: ``indeterminate``, ``sampled``, ``rhs``),
    crosscheck.py:315, 333, 481 (``if ok``: a consistent regime counted as indeterminate),
    crosscheck.py:430 (``==`` / ``not … !=``: a step-end event counted as found by sampling)."""
    calls = []
    real = crosscheck.solve_ivp

    def counting(*args, **kwargs):
        res = real(*args, **kwargs)
        calls.append(res.nfev)
        return res

    monkeypatch.setattr(crosscheck, "solve_ivp", counting)
    r = simulate_crosscheck(rk.System(statue=BLOCK), _jump_record(), duration=1.5,
                            options=rk.Options(**CROSSCHECK), save_dt=0.05)
    assert len(r["events"]) >= 3
    d = r["diagnostics"]
    assert d["solve_ivp_calls"] == len(calls) > 20
    assert d["rhs_evaluations"] == sum(calls)
    assert d["indeterminate"] == 0
    assert d["events_found_by_sampling"] == 0
    assert d["immediate_events"] == 0 and d["ignored_start_events"] == 0


def test_arguments_as_simulate():
    """The call forms and argument checks of ``simulate``: ``system`` and ``motion`` by keyword,
    ``duration`` keyword-only; a large initial tilt (θ0 = 0.3 rad < α = 0.38 rad, released at
    rest) is accepted and gives Housner's first impact time (1e-9 s); |θ0| ≥ π/2 and a
    non-positive duration are rejected as by ``simulate``.

    Kills crosscheck.py:549 (``/`` for ``*``: system/motion positional-only, duration positional),
    crosscheck.py:586 (``0.5/π`` = 0.16 rad as the tilt limit), crosscheck.py:584 (``t_end <= 1``),
    crosscheck.py:555 (the default ``save_dt`` 1.01 s)."""
    b, h = 0.4, 1.0
    block = rk.Statue(width=2 * b, height=2 * h, mass=1.0)
    quiet = rk.RectanglePulse(amplitude=0.0, width=3.0)
    r = simulate_crosscheck(system=rk.System(statue=block), motion=quiet, duration=0.9,
                            options=rk.Options(**CROSSCHECK), initial_rotation=0.3)
    assert r["impacts"][0].time == pytest.approx(cf.free_rocking_t1_exact(b, h, 0.3, rk.g), abs=1e-9)
    with pytest.raises(TypeError):
        simulate_crosscheck(rk.System(statue=block), quiet, 0.9)  # noqa: the point of the test
    with pytest.raises(TypeError):
        rk.simulate(rk.System(statue=block), quiet, 0.9)
    # the default grid is simulate's: every 0.01 s (91 points over 0.9 s)
    assert r["t"].size == 91 and r["t"][1] == 0.01
    for bad in ({"initial_rotation": 0.5 * math.pi}, {"initial_rotation": -2.0}, {"duration": 0.0}):
        kw = {"duration": 0.9, **bad}
        with pytest.raises(ValueError):
            rk.simulate(rk.System(statue=block), quiet, **kw)
        with pytest.raises(ValueError):
            simulate_crosscheck(rk.System(statue=block), quiet, **kw)


# ---------------------------------------------------------------------------------------------
# Guards that graze: found only by the cross-check's sampling of the dense output
# ---------------------------------------------------------------------------------------------
def test_grazing_uplifts_found_by_sampling():
    """A sine of amplitude 1.0001·g·tan α (1 Hz, one cycle) exceeds the rocking threshold for only
    4.5 ms around each peak: inside one DOP853 step, so SciPy's step-end sign test misses both
    uplifts and the cross-check finds them by sampling the guards on the dense output
    (``events_found_by_sampling`` = 2). Each uplift is at the closed-form instant
    sin(ωt) = 1/1.0001 (first peak t = asin(1/1.0001)/ω, second one half a period later; within
    1e-9 s, Brent's method on a guard of slope 0.17 m/s³ is good to ~1e-14 s), and each is followed
    by a chattering sequence of ~18 impacts that ends at rest; all 38 events and the grid agree
    with the compiled solver (measured ≤ 3e-13 s).

    Kills crosscheck.py:191-212 where the scan no longer finds an excursion inside a step, and
    crosscheck.py:425 (``guard_dt >= 0``: the scan run with a zero spacing)."""
    eps = 1e-4
    thr = rk.g * 0.2
    motion = rk.Harmonic(amplitude=thr * (1.0 + eps), frequency=1.0, cycles=1, form="sin")
    c, r = _both(rk.System(statue=BLOCK), motion, duration=1.0)
    ups = [e for e in r["event_regimes"] if e[1] == rk.EventKind.UPLIFT]
    t1 = math.asin(1.0 / (1.0 + eps)) / (2.0 * math.pi)
    assert len(ups) == 2
    assert ups[0][0] == pytest.approx(t1, abs=1e-9) and ups[1][0] == pytest.approx(t1 + 0.5, abs=1e-9)
    assert r["diagnostics"]["events_found_by_sampling"] == 2
    _assert_rows_agree(c, r)
    _assert_grid_agrees(c, r, 0.01)
    _assert_summary_agrees(c, r)
    assert r["status"] == "completed"
    # guard_dt = 0 turns the sampling off (integrate_crosscheck's documented switch): SciPy alone
    # then misses both 4.5 ms excursions and the block stays at rest.
    o = rk.Options(**CROSSCHECK)
    p = pack(rk.System(statue=BLOCK), gravity=o.gravity, normal_force=o.normal_force, impact=o.impact,
             rest_velocity=o.rest_velocity)
    off = integrate_crosscheck(p, motion.signal(), motion.vertical_signal(), crosscheck._breakpoints(motion, 0.0, 1.0),
                               0.0, 1.0, np.zeros(4), o.rtol, o.atol, o.max_step, 0.01, False, o.max_events,
                               guard_dt=0.0)
    assert off["event_table"].shape[0] == 0 and off["diagnostics"]["events_found_by_sampling"] == 0
