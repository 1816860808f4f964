"""The solver's shortcuts against what they shortcut: rest crossed in closed form under a
harmonic floor motion, the rest band read off the guards, one-component dense output."""

import math

import numpy as np
import pytest
from helpers import G, alone, block

import rocking as rk
from rocking.excitation.record import GroundMotion
from rocking.excitation.signal import cosine_band_exit
from rocking.integrators import dop853
from rocking.models.modes import N_GUARDS, rest_band
from rocking.models.parameters import pack
from rocking.solver.compiled import S_STEPS

MARGIN = 1e-6  # rad of phase kept before a cosine leaves its band (signal._PHASE_MARGIN)


def _first_exit(amplitude, omega, phase, t, t_stop, lo, hi):
    """First time in [t, t_stop] where A cos(ωτ + φ) leaves (lo, hi), by dense sampling and
    bisection (independent of the closed form); inf if it stays inside."""
    tau = np.linspace(t, t_stop, 200_001)
    a = amplitude * np.cos(omega * tau + phase)
    out = np.nonzero((a >= hi) | (a <= lo))[0]
    if out.size == 0:
        return math.inf
    k = out[0]
    if k == 0:
        return t
    left, right = tau[k - 1], tau[k]
    for _ in range(80):
        mid = 0.5 * (left + right)
        v = amplitude * math.cos(omega * mid + phase)
        if v >= hi or v <= lo:
            right = mid
        else:
            left = mid
    return right


@pytest.mark.parametrize("seed", range(40))
def test_cosine_band_exit_stops_just_short_of_the_first_exit(seed):
    rng = np.random.default_rng(seed)
    amplitude = rng.uniform(-5.0, 5.0)
    omega = rng.uniform(0.5, 20.0)
    phase = rng.uniform(-10.0, 10.0)
    t = rng.uniform(0.0, 3.0)
    t_stop = t + rng.uniform(0.01, 3.0)
    level = rng.uniform(0.5, 6.0)
    lo, hi = (-level, level) if seed % 3 else (-rng.uniform(0.5, 6.0), level)
    got = cosine_band_exit(amplitude, omega, phase, t, t_stop, lo, hi)
    exact = _first_exit(amplitude, omega, phase, t, t_stop, lo, hi)
    if exact == t:  # already outside the band: nothing may be skipped
        assert got == t
        return
    assert t <= got <= t_stop
    # Inside the band all the way to the returned time (sampled densely)...
    tau = np.linspace(t, got, 20_001)
    a = amplitude * np.cos(omega * tau + phase)
    assert np.all((a > lo) & (a < hi))
    # ...which is the end of the interval, or the exit less the phase margin. The exit found by
    # bisection is good to ~1e-12 s; the closed form's arccos loses ~1e-8 rad near tangency.
    if math.isinf(exact):
        assert got == t_stop
    else:
        assert got == pytest.approx(min(t_stop, exact - MARGIN / omega), abs=2e-8 / omega + 1e-11)


def test_cosine_band_exit_never_skips_past_a_grazing_peak():
    # The amplitude touches the band's edge within rounding: the exit is at the crest.
    omega, level = 2.0, 3.0
    for amplitude in (level * (1 + 1e-15), level * (1 + 1e-9), level * (1 + 1e-4)):
        got = cosine_band_exit(amplitude, omega, 1.0, 0.0, 10.0, -2 * level, level)
        crest = (2 * math.pi - 1.0) / omega  # ωt + 1 = 2π
        assert got < crest


@pytest.mark.parametrize("mu_s", [None, 0.1, 0.4])
@pytest.mark.parametrize("av", [0.0, -2.0, 3.0])
def test_rest_band_is_the_rocking_and_friction_thresholds(mu_s, av):
    st = block(0.25, 1.0)
    if mu_s is None:
        system = alone(st)
        level = (G + av) * math.tan(st.slenderness)
    else:
        system = rk.System(statue=st, pedestal=rk.Pedestal(mass=2.0, friction=rk.Friction(static=mu_s, kinetic=0.8 * mu_s)))
        level = (G + av) * min(mu_s, math.tan(st.slenderness))
    p = pack(system, gravity=G, normal_force="full", impact="coulomb", rest_velocity=1e-6)
    lo, hi = rest_band(p, np.zeros(6), av, np.empty(2 * N_GUARDS))
    assert hi == pytest.approx(level, rel=1e-14)
    assert lo == pytest.approx(-level, rel=1e-14)


def test_dense_component_equals_the_full_dense_output():
    rng = np.random.default_rng(1)
    y = rng.normal(size=6)
    F = rng.normal(size=(dop853.INTERPOLATOR_POWER, 6))
    out = np.empty(6)
    for x in (0.0, 0.3, 0.77, 1.0):
        dop853.dense(y, F, x, out)
        for j in range(6):
            assert dop853.dense_component(y, F, x, j) == out[j]


def test_uplifts_after_settling_under_a_harmonic_motion_are_at_the_threshold_crossings():
    # A block just above its threshold lifts off, chatters to rest, and waits there (crossed in
    # closed form) until |a_g| = g tan α again, on the rising edge: ωt = kπ − arccos(g tan α / A).
    st = block(0.125, 0.5, restitution=0.8)
    level = G * math.tan(st.slenderness)
    amplitude, f = 1.07 * level, 1.3
    r = rk.simulate(alone(st), rk.Harmonic(amplitude=amplitude, frequency=f, cycles=6),
                    options=rk.Options(gravity=G))
    uplifts = [e.time for e in r.events if e.kind == rk.EventKind.UPLIFT]
    assert len(uplifts) >= 10
    omega, beta = 2 * math.pi * f, math.acos(level / amplitude)
    for t in uplifts:
        k = round((omega * t + beta) / math.pi)
        assert t == pytest.approx((k * math.pi - beta) / omega, abs=1e-9)


def test_a_block_below_its_threshold_is_never_integrated():
    st = block(0.25, 1.0)
    amplitude = 0.9 * G * math.tan(st.slenderness)
    r = rk.simulate(alone(st), rk.Harmonic(amplitude=amplitude, frequency=2.0, cycles=30),
                    options=rk.Options(gravity=G))
    assert r.raw_summary[S_STEPS] == 0
    assert not r.events
    assert np.all(r.theta == 0.0) and r.t[-1] == pytest.approx(15.0, abs=1e-12)
    assert len(r.t) == 1501  # the whole output grid, held at rest


@pytest.mark.parametrize("with_friction", [False, True])
def test_a_block_below_its_thresholds_under_a_record_is_never_integrated(with_friction):
    # The same under a record: between two samples the floor acceleration is linear in time, so
    # are the guards of rest, and rest positive at both samples holds in between. Fails if
    # compiled.py:541 evaluates those guards at the next sample as if sliding (`sig = 1`: the
    # sliding-stops guard u̇ = 0 is then never positive, and every sample interval is integrated).
    # with friction, μs·g above the record's peak too, so the friction guards are watched
    st = block(0.25, 1.0, friction=rk.Friction(static=0.5, kinetic=0.4) if with_friction else None)
    level = G * math.tan(st.slenderness)
    t = np.round(np.arange(0.0, 8.0, 0.01), 10)
    record = GroundMotion(time=t, values=0.9 * level * np.sin(2 * np.pi * 1.7 * t) * np.exp(-0.2 * t))
    r = rk.simulate(alone(st), record, options=rk.Options(gravity=G))
    assert r.raw_summary[S_STEPS] == 0
    assert not r.events
    assert np.all(r.theta == 0.0) and np.all(r.u == 0.0)


def test_rocking_from_a_tie_is_not_held_up_by_the_impact_step_limit():
    # A sine pulse phased so that rocking starts at t = 0 (the spectra's "onset" phase), with
    # the amplitude 1 % above the threshold: θ = θ̇ = 0 and θ̈ ≈ 0 at the start, where the
    # predicted time to impact is zero. (Without a floor on that prediction the solver stalled.)
    from rocking.analyses.spectra import spectrum_motion

    st = block(0.2, 1.0)
    gta, p = G * math.tan(st.slenderness), st.frequency_parameter(G)
    for ratio in (1.01, 1.5):
        motion = spectrum_motion("sine", ratio, 1.0, g_tan_alpha=gta, p=p)
        r = rk.simulate(alone(st), motion, duration=3.0, options=rk.Options(gravity=G), save=False)
        summary = r.summary()
        assert r.status in ("completed", "overturned")
        assert summary["end_time"] == pytest.approx(3.0 if r.status == "completed" else summary["overturn_time"])
        assert summary["first_rocking_time"] == pytest.approx(0.0, abs=1e-12)
