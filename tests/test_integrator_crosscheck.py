"""Integrator cross-check: the compiled solver against the same physics integrated by SciPy.

``rocking.solver.crosscheck.simulate_crosscheck`` imports the compiled solver's own equations,
guards, regime selection, transitions and impact laws and integrates them with SciPy's
``solve_ivp`` (DOP853, Brent event location on its dense output, one call per smooth segment).
So these tests check the *integrator and the event location* only (steps, dense output, grazing
guards, chattering impacts, ties at a segment start, breakpoints, bookkeeping): a mistake in the
shared physics is made by both solvers and passes here. The physics is checked against an
independent solver built from the sympy derivation, in ``test_independent_solver.py``.

Both must give the same rotation history (θ within 1e-7 rad) and the same events (kind,
regimes, time within 1e-7 s) over the first 5 s, and the same overturning verdict over the whole
run. Beyond a few seconds the rocking response is chaotic (differences grow by orders of
magnitude per impact), so only the verdict is compared.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import rocking as rk

from helpers import on_grid
from oracles import closed_forms as cf
from rocking.io.records import read_record
from rocking.solver.crosscheck import simulate_crosscheck

COMPILED = {"rtol": 1e-10, "atol": 1e-12}
CROSSCHECK = {"rtol": 1e-12, "atol": 1e-13}
THETA_TOL = 1e-7  # rad
U_TOL = 1e-7  # m
TIME_TOL = 1e-7  # s
WINDOW = 5.0  # s

STATUE = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)  # paper Table 1, fig. 10a
PEDESTAL = rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3))
PAPER_MOTION = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30)


def _both(system, motion, *, duration=None, save_dt=0.01, impact="coulomb", gravity=rk.g, **initial):
    c = rk.simulate(system, motion, duration=duration,
                    options=rk.Options(impact=impact, gravity=gravity, save_dt=save_dt, **COMPILED), **initial)
    r = simulate_crosscheck(system, motion, duration=duration,
                           options=rk.Options(impact=impact, gravity=gravity, **CROSSCHECK), save_dt=save_dt, **initial)
    return c, r


def _events(c, r, window):
    ec = [(e.time, e.kind, e.before, e.after) for e in c.events if e.time <= window]
    er = [e for e in r["event_regimes"] if e[0] <= window]
    return ec, er


def _assert_agree(c, r, *, dt=0.01, window=WINDOW):
    tc, thc, uc = on_grid(c, dt)
    n = min(tc.size, r["t"].size)
    assert n > 0
    np.testing.assert_array_equal(tc[:n], r["t"][:n])
    keep = r["t"][:n] <= window + 1e-9
    d_theta = np.abs(thc[:n] - r["theta"][:n])[keep]
    d_u = np.abs(uc[:n] - r["u"][:n])[keep]
    worst = int(np.argmax(d_theta))
    assert d_theta.max() <= THETA_TOL, f"θ differs by {d_theta.max():.3e} rad at t = {r['t'][worst]:.4f} s"
    assert d_u.max() <= U_TOL, f"u differs by {d_u.max():.3e} m"
    ec, er = _events(c, r, window)
    for k, (a, b) in enumerate(zip(ec, er)):
        assert a[1:] == tuple(b[1:]) and abs(a[0] - b[0]) <= TIME_TOL, (
            f"event {k}: compiled {a[1].name} {a[2].name}->{a[3].name} at t = {a[0]!r}, "
            f"cross-check {b[1].name} {b[2].name}->{b[3].name} at t = {b[0]!r}"
        )
    assert len(ec) == len(er), f"{len(ec)} compiled events vs {len(er)} cross-check events up to {window} s"
    return ec


def _assert_no_workarounds(r):
    """The cross-check did not have to resolve a tie or an inconsistent regime."""
    d = r["diagnostics"]
    assert d["ignored_start_events"] == 0 and d["immediate_events"] == 0, d


# ---------------------------------------------------------------------------------------------
# (a)-(d): the four benchmark cases (bench/README.md)
# ---------------------------------------------------------------------------------------------
def test_a_single_block_harmonic():
    c, r = _both(rk.System(statue=STATUE), PAPER_MOTION)
    events = _assert_agree(c, r)
    assert sum(e[1] == rk.EventKind.IMPACT for e in events) >= 3
    assert r["overturned"] and c.overturned  # the paper's fig. 10a: the lone statue falls
    _assert_no_workarounds(r)


@pytest.mark.parametrize("impact", ["coulomb", "paper"])
def test_b_statue_on_pedestal(impact):
    c, r = _both(rk.System(statue=STATUE, pedestal=PEDESTAL), PAPER_MOTION, impact=impact)
    events = _assert_agree(c, r)
    kinds = {e[1] for e in events}
    assert {rk.EventKind.IMPACT, rk.EventKind.STOP} <= kinds
    assert not r["overturned"] and not c.overturned  # the pedestal saves it (paper fig. 10a)
    assert r["peak_rotation"] == pytest.approx(c.peak_rotation, abs=THETA_TOL)
    _assert_no_workarounds(r)


def test_c_slender_block_under_a_record():
    rec = read_record("Northridge1994_RinaldiReceivingSta_228")
    block = rk.Statue(width=0.3, height=1.2, mass=1.0)
    c, r = _both(rk.System(statue=block), rec, save_dt=rec.dt)
    events = _assert_agree(c, r, dt=rec.dt)
    assert any(e[1] == rk.EventKind.UPLIFT for e in events)
    assert c.overturned == r["overturned"]
    if c.overturned:
        assert r["overturn_time"] == pytest.approx(c.overturn_time, abs=TIME_TOL)
    _assert_no_workarounds(r)


def test_d_single_block_slide_rock():
    block = rk.Statue(width=1.0, height=2.0, mass=1.0, friction=rk.Friction(static=0.6, kinetic=0.5))
    pulse = rk.SinePulse(amplitude=12.0, frequency=2.0)
    c, r = _both(rk.System(statue=block), pulse, duration=5.0)
    events = _assert_agree(c, r)
    assert rk.Regime.SLIDE_ROCK in set(r["regime"])
    assert {rk.EventKind.SLIP, rk.EventKind.STOP, rk.EventKind.UPLIFT} <= {e[1] for e in events}
    assert r["residual_sliding"] == pytest.approx(c.summary()["residual_sliding"], abs=U_TOL)
    assert r["peak_sliding"] == pytest.approx(c.summary()["peak_sliding"], abs=U_TOL)
    _assert_no_workarounds(r)


def test_squat_block_sliding_only():
    """Pure sliding (SLIP/STOP) of a squat block that never rocks."""
    block = rk.Statue(width=1.0, height=1.0, mass=1.0, friction=rk.Friction(static=0.5, kinetic=0.4))
    motion = rk.Harmonic(amplitude=6.0, frequency=1.5, cycles=4, form="sin")
    c, r = _both(rk.System(statue=block), motion)
    events = _assert_agree(c, r)
    assert {e[1] for e in events} == {rk.EventKind.SLIP, rk.EventKind.STOP}
    assert r["residual_sliding"] == pytest.approx(c.summary()["residual_sliding"], abs=U_TOL)
    _assert_no_workarounds(r)


# ---------------------------------------------------------------------------------------------
# Whole runs: the same overturning verdicts
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "height, pedestal, expected",
    [(4.0, None, True), (4.0, PEDESTAL, False), (2.0, None, False), (5.0, PEDESTAL, None)],
)
def test_whole_run_verdicts(height, pedestal, expected):
    statue = rk.Statue(width=1.0, height=height, mass=1.0, restitution=0.8)
    c, r = _both(rk.System(statue=statue, pedestal=pedestal), PAPER_MOTION)
    assert c.overturned == r["overturned"]
    if expected is not None:
        assert r["overturned"] is expected


# ---------------------------------------------------------------------------------------------
# The cross-check itself against closed forms, and its output contract
# ---------------------------------------------------------------------------------------------
def test_crosscheck_free_rocking_closed_form():
    """Release at rest from θ0 (O3): time and velocity of the first impact, Housner's η (O2)."""
    b, h, g = 0.2, 1.0, 9.81
    block = rk.Statue(width=2 * b, height=2 * h, mass=1.0)
    alpha = math.atan2(b, h)
    theta0 = 0.5 * alpha
    quiet = rk.RectanglePulse(amplitude=0.0, width=3.0)
    c, r = _both(rk.System(statue=block), quiet, gravity=g, initial_rotation=theta0)
    t1 = cf.free_rocking_t1_exact(b, h, theta0, g)
    w1 = cf.free_rocking_impact_velocity(b, h, theta0, g)
    first = r["impacts"][0]
    assert first.time == pytest.approx(t1, abs=1e-9)
    assert first.theta_dot_before == pytest.approx(-w1, rel=1e-9)
    assert first.theta_dot_after / first.theta_dot_before == pytest.approx(cf.housner_eta(b, h), rel=1e-12)
    assert c.impacts[0].time == pytest.approx(t1, abs=1e-9)
    peaks = cf.amplitude_sequence_exact(alpha, cf.housner_eta(b, h), theta0, 1)
    # Peak after the first impact, from the cross-check's grid (θ̇ = 0 lies between samples).
    after = (r["t"] > first.time) & (r["t"] < r["impacts"][1].time)
    assert np.max(np.abs(r["theta"][after])) == pytest.approx(peaks[0], rel=1e-4)
    assert r["peak_rotation"] == pytest.approx(theta0, rel=1e-12)


def test_crosscheck_tie_at_start():
    """A type-A sine pulse starts rocking exactly at t = 0 (threshold tied): both solvers lift
    the block at once and then agree."""
    b, h = 0.2, 1.0
    block = rk.Statue(width=2 * b, height=2 * h, mass=1.0)
    ap = 3.0 * rk.g * b / h
    pulse = rk.SinePulse(amplitude=ap, frequency=1.0, phase=math.asin(rk.g * (b / h) / ap))
    c, r = _both(rk.System(statue=block), pulse, duration=3.0)
    events = _assert_agree(c, r, window=3.0)
    assert events[0][1] == rk.EventKind.UPLIFT and events[0][0] == pytest.approx(0.0, abs=1e-12)


def test_crosscheck_output_contract():
    r = simulate_crosscheck(rk.System(statue=STATUE), PAPER_MOTION, duration=2.0, save_dt=0.05)
    for key in ("t", "u", "u_dot", "theta", "theta_dot", "events", "impacts", "overturned", "overturn_time",
                "exceeded_alpha_time", "peak_rotation", "peak_sliding", "residual_sliding"):
        assert key in r
    np.testing.assert_allclose(r["t"], 0.05 * np.arange(41), rtol=0, atol=1e-12)
    for name in ("u", "u_dot", "theta", "theta_dot"):
        assert r[name].shape == r["t"].shape
    assert all(isinstance(t, float) and isinstance(k, rk.EventKind) for t, k in r["events"])
    assert len(r["impacts"]) == sum(k in (rk.EventKind.IMPACT, rk.EventKind.SETTLE) for _, k in r["events"])
    assert r["overturned"] is False and r["overturn_time"] is None


def test_chattering_block_settles_like_the_crosscheck():
    """Just above its threshold the block lifts off every half cycle and settles through ~50
    ever shorter flights (a Zeno sequence ended at rest_velocity). The compiled solver shortens
    its steps to the predicted flights and reads those impacts off the dense output; every one
    of them must still agree with the cross-check in time and order."""
    st = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
    c, r = _both(rk.System(statue=st), rk.Harmonic(amplitude=2.6154, frequency=0.5, cycles=30), duration=3.0)
    events = _assert_agree(c, r, window=3.0)
    impacts = sum(e[1] == rk.EventKind.IMPACT for e in events)
    settles = sum(e[1] == rk.EventKind.SETTLE for e in events)
    assert impacts >= 80 and settles >= 2
