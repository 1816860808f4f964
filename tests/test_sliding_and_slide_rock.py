"""Sliding (paper §2.2, Eq. 14) and slide-rock of one block: oracles O12–O15."""

import math

import numpy as np
import pytest
from helpers import G, OPTS, alone, block
from oracles import closed_forms as cf
from oracles import energy

import rocking as rk
from rocking.models import dynamics
from rocking.models.parameters import pack
from rocking.models.regimes import EventKind, Regime


def squat(mu_s, mu_k=None):
    """A block too squat to rock at the accelerations used (b/h = 10)."""
    return block(5.0, 0.5, friction=rk.Friction(static=mu_s, kinetic=mu_k))


@pytest.mark.parametrize("a_g,mu,t0,u_expected", [(0.5, 0.2, 0.5, 0.919687), (1.0, 0.1, 0.2, 1.765800)])
def test_o12_newmark_rectangular_pulse(a_g, mu, t0, u_expected):
    r = rk.simulate(alone(squat(mu)), rk.RectanglePulse(amplitude=a_g * G, width=t0), duration=5.0, options=OPTS)
    v = a_g * G * t0
    assert v**2 / (2 * G * mu) * (1 - mu / a_g) == pytest.approx(u_expected, rel=1e-6)
    # The floor moves towards +x, so the block lags behind: u < 0.
    assert r.summary()["residual_sliding"] == pytest.approx(-u_expected, rel=1e-6)
    assert r.summary()["peak_rotation"] == 0.0


@pytest.mark.parametrize("a_p,mu,tp,u_expected", [(0.5, 0.2, 0.5, 0.280945), (0.4, 0.1, 1.0, 2.031287)])
def test_o13_half_sine_pulse(a_p, mu, tp, u_expected):
    half_sine = rk.Harmonic(amplitude=a_p * G, frequency=0.5 / tp, cycles=0.5, form="sin")
    r = rk.simulate(alone(squat(mu)), half_sine, duration=6.0, options=OPTS)
    s = r.summary()
    assert s["first_sliding_time"] == pytest.approx(tp / math.pi * math.asin(mu / a_p), abs=1e-9)
    exact = cf.half_sine_sliding(a_p * G, mu, tp, g=G)  # root-find and quadrature (O13)
    assert exact.u == pytest.approx(u_expected, abs=5e-7)  # the table's rounding
    assert abs(s["residual_sliding"]) == pytest.approx(exact.u, rel=1e-8)
    stop = [e for e in r.events if e.kind == EventKind.STOP][0]
    assert stop.time == pytest.approx(exact.t2, abs=1e-9)


def test_o14_harmonic_sliding_steady_peak_to_peak():
    amplitude, omega, mu_k = 6.75, 2 * math.pi * 1.2, 0.3
    motion = rk.Harmonic(amplitude=amplitude, frequency=1.2, cycles=30, form="sin")
    r = rk.simulate(alone(squat(0.4, mu_k)), motion, options=OPTS)
    late = (r.t > 15.0) & (r.t <= motion.duration)  # the steady state under the motion, not the free slide after
    ptp = r.u[late].max() - r.u[late].min()
    expected = 2 * amplitude / omega**2 * math.sqrt(1 - (math.pi * mu_k * G / (2 * amplitude)) ** 2)
    assert expected == pytest.approx(0.173038, abs=5e-7)
    assert ptp == pytest.approx(expected, rel=1e-5)


@pytest.mark.parametrize("factor,sticks", [(0.95, True), (1.05, False)])
def test_o14_non_stop_sliding_threshold(factor, sticks):
    mu = 0.3
    amplitude = factor * mu * G * math.sqrt(1 + math.pi**2 / 4)
    motion = rk.Harmonic(amplitude=amplitude, frequency=1.0, cycles=12, form="sin")
    r = rk.simulate(alone(squat(mu)), motion, options=OPTS)
    stops = [e for e in r.events if e.kind == EventKind.STOP and 6.0 <= e.time <= 12.0 and e.after == Regime.REST]
    assert bool(stops) is sticks


def mu_req(b, h, lam):
    """Friction needed for pure rocking to start under a constant λg (O15, uniform rectangle)."""
    return (lam * (4 * b * b + h * h) + 3 * b * h) / ((b * b + 4 * h * h) + 3 * lam * b * h)


def start_regime(b, h, mu_s, lam):
    st = block(b, h, friction=rk.Friction(static=mu_s, kinetic=mu_s))
    r = rk.simulate(alone(st), rk.RectanglePulse(amplitude=lam * G, width=0.05), duration=0.05, options=OPTS)
    return Regime(int(r.regime[1]))  # just after t = 0


def library_friction_demand(b, h, lam):
    """|F|/N the library's equations need from the floor when a block held by friction starts
    to rock under a constant floor acceleration λg towards +x (θ = θ̇ = 0, pivot s = −1)."""
    st = block(b, h, friction=rk.Friction(static=10.0, kinetic=10.0))
    p = pack(alone(st), gravity=G, normal_force="full", impact="coulomb", rest_velocity=1e-6)
    udd, thdd, ok = dynamics.accelerations(p, 0, -1, 0.0, 0.0, 0.0, lam * G, 0.0)
    assert ok and udd == 0.0 and thdd < 1e-12  # held, and tipping towards −x (θ̈ = 0 at λ = b/h)
    f, n = dynamics.floor_forces(p, -1, 0.0, 0.0, lam * G, 0.0, udd, thdd)
    return abs(f) / n


def test_o15_mu_req_table():
    table = {0.2: (0.2000, 0.2246, 0.2486, 0.3793), 0.25: (0.2500, 0.2806, 0.3099, 0.4156),
             1 / 3: (0.3333, 0.3735, 0.4109, 0.4783), 0.5: (0.5000, 0.5581, 0.6087, 0.6087)}
    for ratio, values in table.items():
        lams = (ratio, 1.5 * ratio, 2 * ratio, 1.0)
        np.testing.assert_allclose([mu_req(ratio, 1.0, lam) for lam in lams], values, atol=5e-5)  # the table's rounding
        got = [library_friction_demand(ratio, 1.0, lam) for lam in lams]
        np.testing.assert_allclose(got, values, atol=5e-5)
        np.testing.assert_allclose(got, [mu_req(ratio, 1.0, lam) for lam in lams], rtol=1e-12)


@pytest.mark.parametrize("ratio", [0.2, 0.25, 1 / 3, 0.5])
def test_o15_shenton_map(ratio):
    b, h = ratio, 1.0
    lam = 1.5 * ratio
    boundary = mu_req(b, h, lam)
    # Rest below both thresholds; slide when μs < b/h < λ.
    assert start_regime(b, h, 1.2 * ratio, 0.9 * ratio) == Regime.REST
    assert start_regime(b, h, 0.8 * ratio, 0.9 * ratio) == Regime.SLIDE
    assert start_regime(b, h, 0.8 * ratio, lam) == Regime.SLIDE
    # Above b/h: pure rock if μs ≥ μ_req(λ), slide-rock just below it — to 1e-9.
    assert start_regime(b, h, boundary * (1 + 1e-9), lam) == Regime.ROCK
    assert start_regime(b, h, boundary * (1 - 1e-9), lam) == Regime.SLIDE_ROCK


def test_slide_rock_energy_ledger_balances():
    st = block(0.5, 1.0, restitution=0.9, friction=rk.Friction(static=0.55, kinetic=0.45))
    from rocking.io.records import read_record

    motion = read_record("Northridge1994_RinaldiReceivingSta_228").trimmed(8.0)
    # Saved every 0.25 ms, on the record's sample times (every 0.01 s): the chattering flights
    # between impacts last a few ms, and those of fewer than 4 samples are integrated by trapezoids.
    r = rk.simulate(alone(st), motion, duration=motion.duration, options=rk.Options(gravity=G, save_dt=2.5e-4))
    regimes = set(np.unique(r.regime))
    assert {Regime.ROCK, Regime.SLIDE_ROCK} <= regimes or {Regime.SLIDE, Regime.SLIDE_ROCK} <= regimes
    # The ledger from the samples, with the sympy derivation's energy and forces and the record's
    # own interpolation: a_g has a kink at every sample, so the quadrature stops at each one.
    led = energy.ledger(r.t, r.state, r.regime, energy.lagrange_params(r.system, G), motion.acceleration,
                        motion.vertical_acceleration, motion.breakpoints)
    assert led.friction[-1] > 0.5 * led.scale and led.jumps[-1] > 1e-3 * led.scale
    assert np.max(np.abs(led.residual)) <= 1e-8 * led.scale  # 1.6e-9 measured
    # No event creates energy, but one: a statue settling (|θ̇⁺| below rest_velocity after an
    # impact) on a sliding block has its θ̇⁺ zeroed at constant u̇, which drops the coupling term
    # m2·h·u̇·θ̇⁺ of the kinetic energy: a gain of at most m2·h·|u̇|·rest_velocity (~1e-8 J here).
    settle = {e.time for e in r.events if e.kind == EventKind.SETTLE}
    v_rest = r.options.rest_velocity
    for t, loss in led.losses:
        i = np.flatnonzero(r.t == t)[0]
        allowed = st.mass * st.h * abs(r.u_dot[i]) * v_rest if t in settle else 0.0
        assert loss >= -allowed - 1e-12 * led.scale, (t, loss)
    lost = {imp.time: imp.energy_lost for imp in r.impacts}
    assert len(lost) > 100
    for t, loss in led.losses:
        if t in lost:
            assert loss == pytest.approx(lost[t], rel=1e-9, abs=1e-12 * led.scale)
    e = r.energy
    np.testing.assert_allclose([e["input_work"], e["friction_dissipation"], e["impact_dissipation"]],
                               [led.input_work[-1], led.friction[-1], led.jumps[-1]], rtol=1e-8)
    assert e["relative_balance_error"] < 1e-8


def test_record_kinks_are_stepped_on_exactly():
    """A sampled triangular pulse (kinks at 0.3 s and 0.8 s) under a sliding block: the
    displacement by quadrature of the exact piecewise-linear acceleration agrees to 1e-9 m. A step
    across a kink would lose the Runge–Kutta order and miss by ~1e-6 m or more."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    from rocking.excitation.record import GroundMotion

    mu, peak = 0.1, 4.0
    t_s = np.array([0.0, 0.3, 0.8, 1.0])
    a_s = np.array([0.0, peak, 0.0, 0.0])
    motion = GroundMotion.from_arrays(t_s, a_s)
    r = rk.simulate(alone(squat(mu)), motion, duration=3.0, options=OPTS)

    slopes = np.diff(a_s) / np.diff(t_s)
    cum = np.concatenate([[0.0], np.cumsum(np.diff(t_s) * (a_s[:-1] + a_s[1:]) / 2)])

    def a_integral(t):  # ∫0^t a, exact for the piecewise-linear record (zero after its end)
        i = min(np.searchsorted(t_s, t, side="right") - 1, t_s.size - 2)
        d = min(t, t_s[-1]) - t_s[i]
        return cum[i] + a_s[i] * d + 0.5 * slopes[i] * d * d

    mg = mu * G
    t1 = 0.3 * mg / peak  # a(t1) = μg: the block starts to slide back (u < 0)

    def v(t):  # velocity of the floor relative to the block, m/s (the block lags: u̇ = −v)
        return a_integral(t) - a_integral(t1) - mg * (t - t1)

    t2 = brentq(v, 0.8, 3.0, xtol=1e-15)
    u = -quad(v, t1, t2, points=[0.3, 0.8], epsabs=1e-14, epsrel=1e-13, limit=200)[0]
    assert r.summary()["first_sliding_time"] == pytest.approx(t1, abs=1e-10)
    stop = [e for e in r.events if e.kind == EventKind.STOP][0]
    assert stop.time == pytest.approx(t2, abs=1e-9)
    assert r.summary()["residual_sliding"] == pytest.approx(u, abs=1e-9)
