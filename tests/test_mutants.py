"""Tests written to kill the mutants that survived the rest of the suite (bench/MUTATION.md).

Each test names, in its docstring, the mutants it kills (the file:line and the change, as listed
in bench/MUTATION.md). They check behaviour the suite left open, not the mutation itself.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
import sys

import numpy as np
import pytest

import rocking as rk
from rocking.io.records import (
    RECORD_LIMIT_ENV,
    RecordError,
    UnitsConflictError,
    bundled_records,
    read_record,
    record_size_limit,
    resolve_record,
)

# ------------------------------------------------------------------------------------------------
# contact/friction.py
# ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs",
    [
        {"static": -0.1},
        {"static": math.nan},
        {"static": "0.4"},
        {"static": 0.4, "kinetic": -0.1},
        {"static": 0.4, "kinetic": math.nan},
    ],
    ids=["negative", "nan", "text", "negative kinetic", "nan kinetic"],
)
def test_friction_refuses_a_negative_nan_or_non_numeric_coefficient(kwargs):
    """friction.py:25 `for name in []` (no check at all); friction.py:29 `or` → `and` in either
    place (NaN, a negative value or a text slips through, or a text raises TypeError)."""
    with pytest.raises(ValueError, match="must be a number ≥ 0"):
        rk.Friction(**kwargs)


def test_friction_checks_the_kinetic_coefficient_after_a_missing_static_one():
    """friction.py:28 `continue` → `break`: an absent coefficient must not end the checks of the
    ones after it (with the mutant, -1 is compared with None: a TypeError, not this ValueError)."""
    with pytest.raises(ValueError):
        rk.Friction(static=None, kinetic=-1.0)


def test_friction_is_a_frozen_keyword_only_slotted_value():
    """friction.py:9 frozen/kw_only/slots=True → False. Friction is a value: one instance may be
    shared by several systems, so it must not change under them (frozen); its two coefficients
    are too easily swapped by position (keyword-only); it carries no other attribute (slots)."""
    f = rk.Friction(static=0.4, kinetic=0.3)
    with pytest.raises(dataclasses.FrozenInstanceError):
        f.static = 0.5
    with pytest.raises(TypeError):
        rk.Friction(0.4, 0.3)
    assert not hasattr(f, "__dict__")


# ------------------------------------------------------------------------------------------------
# excitation/pulses.py
# ------------------------------------------------------------------------------------------------

PULSES = {
    "sine": (rk.SinePulse, {"amplitude": 2.0, "frequency": 1.0, "phase": 0.5}),
    "cosine": (rk.CosinePulse, {"amplitude": 2.0, "frequency": 1.0}),
    "rectangle": (rk.RectanglePulse, {"amplitude": 2.0, "width": 0.5}),
    "ricker": (rk.RickerPulse, {"amplitude": 2.0, "frequency": 1.0}),
    "ramp": (rk.Ramp, {"rate": 2.0, "end": 0.5}),
}


@pytest.mark.parametrize("name", sorted(PULSES))
def test_pulses_are_frozen_and_keyword_only(name):
    """pulses.py:28/76/109/137/177 frozen or kw_only=True → False, for each pulse class. A motion
    may be reused by many runs (frozen), and (amplitude, frequency) against (amplitude, width) or
    (rate, end) are easily swapped by position (keyword-only)."""
    cls, kwargs = PULSES[name]
    pulse = cls(**kwargs)
    first = next(iter(kwargs))
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(pulse, first, 1.0)
    with pytest.raises(TypeError):
        cls(*kwargs.values())


def test_sine_pulse_phase_must_lie_below_two_pi():
    """pulses.py:50 `phase < 2π` → `≤ 2π`, and 2.0 → 3.0 in its bound."""
    with pytest.raises(ValueError, match="phase must lie in"):
        rk.SinePulse(amplitude=1.0, frequency=1.0, phase=2.0 * math.pi)


def _formula(name, pulse, t):
    """Each pulse's closed form, written out here (oracle O9, O9b, O8, Ricker, O1)."""
    if name == "sine":
        return pulse.amplitude * math.sin(pulse.omega * t + pulse.phase)
    if name == "cosine":
        return pulse.amplitude * math.cos(pulse.omega * t)
    if name == "rectangle":
        return pulse.amplitude
    if name == "ricker":
        x = (math.pi * pulse.frequency * (t - pulse.t0)) ** 2
        return pulse.amplitude * (1.0 - 2.0 * x) * math.exp(-x)
    return pulse.rate * t


@pytest.mark.parametrize("name", ["sine", "cosine", "rectangle", "ricker"])
def test_a_pulse_is_on_at_its_start(name):
    """pulses.py:63/97/126/165 `t >= 0` → `t > 0`: the pulse's first instant belongs to it (its
    value there is a_p·sin ψ, a_p, a and the Ricker's tail, none of them zero). The ramp starts at
    k·0 = 0, so its twin mutant at :194 is equivalent (bench/MUTATION.md)."""
    cls, kwargs = PULSES[name]
    pulse = cls(**kwargs)
    expected = _formula(name, pulse, 0.0)
    assert expected != 0.0
    assert float(pulse.acceleration(0.0)) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("name", ["cosine", "ricker", "ramp"])
def test_a_closed_pulse_is_on_at_its_end(name):
    """pulses.py:97/165/194 `t <= end` → `t < end`: the cosine pulse (a_p at t = 1/f), the Ricker
    wavelet (its tail at 2 t_0) and the ramp (k·t_end) include their last instant. The sine
    pulse's last value is sin 2π = 0, so its twin at :63 is equivalent (bench/MUTATION.md)."""
    cls, kwargs = PULSES[name]
    pulse = cls(**kwargs)
    expected = _formula(name, pulse, pulse.duration)
    assert expected != 0.0
    assert float(pulse.acceleration(pulse.duration)) == pytest.approx(expected, rel=1e-12)


def test_a_rectangle_pulse_is_off_at_its_width():
    """pulses.py:126 `t < width` → `t <= width`: the rectangle is [0, t_d), as its docstring and
    the compiled evaluator have it."""
    pulse = rk.RectanglePulse(amplitude=2.0, width=0.5)
    assert float(pulse.acceleration(0.5)) == 0.0
    assert float(pulse.acceleration(np.nextafter(0.5, 0.0))) == 2.0


def test_ricker_pulse_lasts_twice_its_centre_time():
    """pulses.py:160 `2.0 * t0` → `2.0 / t0` or `3.0 * t0`: the wavelet spans [0, 2 t_0],
    symmetric about its centre, and is zero after it."""
    pulse = rk.RickerPulse(amplitude=2.0, frequency=1.0)
    assert pulse.t0 == 1.5
    assert pulse.duration == 3.0
    assert float(pulse.acceleration(3.5)) == 0.0
    assert float(pulse.acceleration(2.5)) == pytest.approx(_formula("ricker", pulse, 2.5), rel=1e-12)


# ------------------------------------------------------------------------------------------------
# contact/impact.py (its two impact laws are checked against the oracle in tests/test_impact_maps.py)
# ------------------------------------------------------------------------------------------------


def test_coulomb_impact_with_no_consistent_sliding_direction_falls_back_to_the_held_pedestal():
    """impact.py:75 `return 0.0, ...` → `1.0`: when neither sliding direction solves the balances
    (a squat statue on a light pedestal sliding into the impact), the law returns the held-pedestal
    outcome (u̇⁺ = 0, θ̇⁺ from the angular momentum about the new pivot) and flags it (ok False)."""
    from rocking.contact.impact import impact_coulomb

    b, h, m1, m2, u_dot, theta_dot = 0.8, 1.0, 0.3, 1.0, -0.6, 0.3
    i_o = 4.0 / 3.0 * m2 * (b * b + h * h)
    eta = 1.0 - 1.5 * b * b / (b * b + h * h)
    v, w, fx, fy, ok = impact_coulomb(i_o, m1 + m2, m2, b, h, eta, 0.4, 0.3, 1.0, u_dot, theta_dot)
    w_held = (eta * i_o * theta_dot + m2 * h * u_dot) / i_o
    assert not ok
    assert v == 0.0
    assert w == pytest.approx(w_held, rel=1e-12)
    assert fx == pytest.approx((m1 + m2) * (0.0 - u_dot) + m2 * h * (w_held - theta_dot), rel=1e-12)
    assert fy == pytest.approx(m2 * b * (abs(w_held) + abs(theta_dot)), rel=1e-12)
    assert abs(fx) > 0.4 * fy  # the held pedestal needs more than μs: this is the sliding branch's fallback


def test_coulomb_impact_on_the_friction_cone_boundary_holds_the_pedestal():
    """impact.py:55 `abs(fx) <= mu_s * fy` → `<`: Coulomb's inequality is not strict. When the
    held-pedestal impulse needs exactly μs, the floor holds the pedestal (u̇⁺ = 0, consistent)."""
    from rocking.contact.impact import impact_coulomb

    b, h, m1, m2, u_dot, theta_dot = 0.25, 1.0, 1.0, 1.0, 0.0, -0.8
    i_o = 4.0 / 3.0 * m2 * (b * b + h * h)
    eta = 1.0 - 1.5 * b * b / (b * b + h * h)
    _, w_held, fx, fy, _ = impact_coulomb(i_o, m1 + m2, m2, b, h, eta, 0.0, 0.0, 0.0, u_dot, theta_dot)
    # the μs (among the neighbours of |Fx|/Fy) for which μs·Fy equals |Fx| in floating point
    mu_s = abs(fx) / fy
    for _ in range(4):
        if mu_s * fy == abs(fx):
            break
        mu_s = np.nextafter(mu_s, math.inf if mu_s * fy < abs(fx) else 0.0)
    assert mu_s * fy == abs(fx)
    v, w, *_, ok = impact_coulomb(i_o, m1 + m2, m2, b, h, eta, mu_s, 0.5 * mu_s, 1.0, u_dot, theta_dot)
    assert ok and v == 0.0 and w == w_held


def test_friction_without_a_static_coefficient_is_refused_at_once():
    """Found by the mutation run: static=None used to pass and fail later, in mu_s."""
    with pytest.raises(ValueError, match=r"friction\.static must be a number ≥ 0, got None"):
        rk.Friction(static=None)


# ------------------------------------------------------------------------------------------------
# models/transitions.py
# ------------------------------------------------------------------------------------------------

_SLENDER = rk.Statue(width=0.2, height=1.2, mass=50.0, restitution=0.8)


def _top_ratio_of(impact, h=0.6, b=0.1):
    """|Fx|/Fy of the impulse on the statue's base at one impact, from its momentum balance:
    Fx = m2 (Δu̇ + h Δθ̇), Fy = m2 b (|θ̇⁺| + |θ̇⁻|) (the centre goes from −b|θ̇⁻| to +b|θ̇⁺|)."""
    fx = (impact.u_dot_after - impact.u_dot_before) + h * (impact.theta_dot_after - impact.theta_dot_before)
    return abs(fx) / (b * (abs(impact.theta_dot_after) + abs(impact.theta_dot_before)))


@pytest.mark.parametrize("law", ["coulomb", "paper"])
def test_top_friction_needed_at_an_impact_on_a_held_pedestal(law):
    """On a pedestal the floor holds, the impulse on the statue's base needs
    |Fx|/Fy = (h/b)(1 − r)/(1 + r) (oracle O19): here 6·0.2/1.8 = 2/3, more than rocking needs,
    so it is the run's required_top_friction. Kills transitions.py:58-59 (the base impulse
    lx = m2((u̇⁺ − u̇⁻) + h(θ̇⁺ − θ̇⁻)), ly = m2 b(|θ̇⁺| + |θ̇⁻|): + for −, × for /, y[4] for y[3])."""
    pedestal = rk.Pedestal(mass=200.0, friction=rk.Friction(static=5.0, kinetic=5.0))
    r = rk.simulate(rk.System(statue=_SLENDER, pedestal=pedestal), rk.SinePulse(amplitude=2.5, frequency=1.5),
                    options=rk.Options(impact=law))
    assert len(r.impacts) == 1
    assert _top_ratio_of(r.impacts[0]) == pytest.approx(6 * 0.2 / 1.8, rel=1e-12)
    assert r.summary()["required_top_friction"] == pytest.approx(6 * 0.2 / 1.8, rel=1e-12)


def test_top_friction_needed_at_an_impact_that_sets_the_pedestal_sliding():
    """The Coulomb law lets the floor impulse set a light pedestal sliding (u̇⁺ ≠ u̇⁻): the base
    impulse then includes m2 Δu̇. Kills the sign mutants of transitions.py:58 that the held
    pedestal cannot see (the h·Δθ̇ term alone would give 2/3)."""
    pedestal = rk.Pedestal(mass=20.0, friction=rk.Friction(static=0.25, kinetic=0.2))
    r = rk.simulate(rk.System(statue=_SLENDER, pedestal=pedestal), rk.SinePulse(amplitude=3.5, frequency=1.5))
    (impact,) = r.impacts
    assert impact.u_dot_after != impact.u_dot_before
    assert r.summary()["required_top_friction"] == pytest.approx(_top_ratio_of(impact), rel=1e-12)
    assert _top_ratio_of(impact) < 6 * 0.2 / 1.8 - 0.1


def test_floor_friction_short_at_an_impact_is_reported_for_the_paper_law_only():
    """The paper's law keeps a stuck pedestal stuck through the impact whatever floor impulse
    that needs; when that exceeds μs the run says so. The Coulomb law lets the pedestal slide
    instead, and says nothing. Kills transitions.py:56 (``and`` → ``or`` in floor_short) and
    checks the count and the ratio the warning gives."""
    pedestal = rk.Pedestal(mass=20.0, friction=rk.Friction(static=0.25, kinetic=0.2))
    system, motion = rk.System(statue=_SLENDER, pedestal=pedestal), rk.SinePulse(amplitude=3.5, frequency=1.5)
    paper = rk.simulate(system, motion, options=rk.Options(impact="paper"))
    (impact,) = paper.impacts
    assert impact.u_dot_before == impact.u_dot_after == 0.0 and impact.friction_needed > 0.25
    short = [w for w in paper.warnings if "needed more floor friction" in w]
    assert short == [f"1 impact(s) needed more floor friction than μs (up to {impact.friction_needed:.3f}); "
                     "the paper's impact law ignores this"]
    coulomb = rk.simulate(system, motion)
    assert not [w for w in coulomb.warnings if "needed more floor friction" in w]


def test_ordinary_events_are_consistent():
    """Uplift, impact, exceeding α and the fall of a plain run all leave a strictly consistent
    regime: no 'no regime was strictly consistent' warning. Kills transitions.py:32
    (``ok = False`` as the default of the events that select no regime)."""
    for system in (rk.System(statue=_SLENDER),
                   rk.System(statue=_SLENDER, pedestal=rk.Pedestal(mass=20.0, friction=rk.Friction(static=0.2)))):
        r = rk.simulate(system, rk.SinePulse(amplitude=3.5, frequency=1.5))
        assert r.overturned
        assert not [w for w in r.warnings if "strictly consistent" in w]


def test_friction_ratio_of_a_zero_normal_impulse_is_infinite():
    """|Fx|/Fy with Fy = 0 needs infinite friction (no division). Kills impact.py:81
    (``fy <= 0.0`` → ``fy < 0.0``, which divides by zero)."""
    from rocking.contact.impact import friction_ratio

    assert friction_ratio(1.0, 0.0) == math.inf
    assert friction_ratio(0.0, 0.0) == math.inf
    assert friction_ratio(-0.3, 1.0) == pytest.approx(0.3, rel=1e-15)


def test_a_plastic_impact_on_a_held_pedestal_is_consistent():
    """r = 0 on a pedestal the floor holds: the Coulomb law stops the statue dead (θ̇⁺ = 0
    exactly), which is consistent, not a reversal. Kills impact.py:58 (``w_stick * θ̇⁻ >= 0`` →
    ``> 0``, which flags the stop as inconsistent)."""
    from rocking.contact.impact import impact_coulomb

    statue = rk.Statue(width=0.2, height=1.2, mass=50.0, restitution=0.0)
    m2, m_tot, b, h = 50.0, 250.0, 0.1, 0.6
    u1, w1, fx, fy, ok = impact_coulomb(statue.inertia_about_corner, m_tot, m2, b, h, 0.0, 10.0, 10.0, 1.0, 0.0, 0.44)
    assert (u1, w1, ok) == (0.0, 0.0, True)
    assert fx == pytest.approx(-m2 * h * 0.44, rel=1e-14) and fy == pytest.approx(m2 * b * 0.44, rel=1e-14)


# ------------------------------------------------------------------------------------------------
# models/parameters.py: the "not given" sentinels of the statue–pedestal checks
# ------------------------------------------------------------------------------------------------


def _statue_thrown_up_on_a_held_pedestal(top_friction):
    """A 0.3 × 1.5 m statue rocking on a pedestal that cannot slide (μ = 3), while the floor
    drops at 9 m/s² for 0.4 s: its base force nearly vanishes, so the friction it needs from the
    pedestal's top face exceeds 1 (measured 1.17), without lift-off."""
    from rocking.excitation.record import GroundMotion

    t = np.arange(0.0, 4.0, 0.005)
    horizontal = np.where(t < 1.0, 3.0 * np.sin(2 * np.pi * 1.5 * t), 0.0)
    vertical = np.where((t > 0.5) & (t < 0.9), -9.0, 0.0)
    statue = rk.Statue(width=0.3, height=1.5, mass=100.0, friction=top_friction)
    pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=3.0, kinetic=3.0))
    return rk.simulate(rk.System(statue=statue, pedestal=pedestal), GroundMotion(time=t, values=horizontal, vertical=vertical))


def test_no_top_face_slip_warning_without_a_top_face_friction():
    """parameters.py:37 `p[MU_TOP] = 1.0` for −1.0 when no top friction is given: a statue that
    needs more than μ = 1 from the top face would be said to slip on a face whose friction nobody
    gave. With μs = 0.9 given, the warning is due."""
    slip = "the statue would slip on the pedestal"
    free = _statue_thrown_up_on_a_held_pedestal(None)
    assert free.summary()["required_top_friction"] > 1.0
    assert not any(slip in w for w in free.warnings), free.warnings
    given = _statue_thrown_up_on_a_held_pedestal(rk.Friction(static=0.9))
    assert any(slip in w for w in given.warnings), given.warnings


@pytest.mark.parametrize(("width", "height", "uplift"), [(None, 3.0, False), (0.4, None, False), (0.5, 3.0, True)],
                         ids=["no width", "no height", "both"])
def test_the_pedestal_uplift_check_needs_both_its_width_and_height(width, height, uplift):
    """parameters.py:39/40 `else 1.0` for −1.0: a pedestal whose width (or height) was not given
    would be checked for uplift as if it were 2 m wide (or 1 m tall). Under 0.8 g a pedestal 3 m
    tall and 0.5 m wide uplifts at once; without both sizes nothing can be said."""
    statue = rk.Statue(width=0.3, height=1.5, mass=100.0)
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=3.0, kinetic=3.0), width=width, height=height)
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=0.8 * 9.81, frequency=1.5, cycles=3))
    assert any("pedestal would uplift" in w for w in r.warnings) is uplift, r.warnings


def test_only_impacts_on_a_held_pedestal_count_as_short_of_floor_friction():
    """Under the paper's law the paper's case 10a has 116 impacts: 115 on a pedestal the floor
    holds, which need more than μs = 0.4 from the floor, and one on a sliding pedestal (whose
    floor impulse ratio also exceeds μs, but a sliding face is not "held" by it). The warning
    counts the 115. Kills transitions.py:56 (`… and u̇⁺ == 0 or ratio > μs`, which counts the
    sliding one too)."""
    statue = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
    pedestal = rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30),
                    options=rk.Options(impact="paper"))
    held = [i for i in r.impacts if i.u_dot_before == i.u_dot_after == 0.0 and i.friction_needed > 0.4]
    sliding = [i for i in r.impacts if i.u_dot_before != 0.0 and i.friction_needed > 0.4]
    assert sliding, "the case lost its impact on a sliding pedestal"
    top = max(i.friction_needed for i in held)
    assert [w for w in r.warnings if "needed more floor friction" in w] == [
        f"{len(held)} impact(s) needed more floor friction than μs (up to {top:.3f}); the paper's impact law ignores this"]


def test_a_statue_held_by_an_upward_floor_acceleration_stays_at_rest():
    """Under a floor accelerating upwards at a_v = 5 m/s², a statue (tan α = 0.25) starts to rock
    only past (g + a_v)·tan α = 3.70 m/s²; a horizontal 3 m/s² from t = 0, above g·tan α and
    (g − a_v)·tan α, must leave it at rest. Kills models/modes.py:108 (`g − a_v` in the regime
    selection, which starts it rocking at t = 0)."""
    from rocking.excitation.record import GroundMotion

    t = np.arange(0.0, 1.0, 0.01)
    motion = GroundMotion(time=t, values=np.full(t.size, 3.0), vertical=np.full(t.size, 5.0))
    statue = rk.Statue(width=0.5, height=2.0, mass=100.0)
    assert 9.81 * 0.25 < 3.0 < (9.81 + 5.0) * 0.25
    r = rk.simulate(rk.System(statue=statue), motion)
    assert r.peak_rotation == 0.0 and r.summary()["first_rocking_time"] is None, r.verdict
    assert not [w for w in r.warnings if "strictly consistent" in w]


# ------------------------------------------------------------------------------------------------
# models/transitions.py and models/modes.py: a grazing touch of the rocking threshold, a jump
# ------------------------------------------------------------------------------------------------


def test_a_grazing_touch_of_the_rocking_threshold_leaves_the_statue_at_rest():
    """A statue (tan α = 1/6, r = 0.5) set rocking at 0.3 rad/s settles at 0.69 s; the floor then
    peaks (Ricker crest, 0.75 s) at g·tan α·(1 + 1e-10). The rocking threshold is reached and
    left again inside one step, at rest: the onset is found only by tracking the threshold guard
    at the step's stages, and at once θ goes the wrong way. There was no uplift: the statue
    stays at rest (θ = θ̇ = 0 after), the settling is no impact and loses no energy, and the input
    work of the earlier rocking stays in the energy ledger. Kills transitions.py:43 (the
    tangency reported as an impact), transitions.py:41 (`y[4] = 0` for `y[3] = 0`: the input
    work dropped), modes.py:171 (`+1e-9·g/R` for `−1e-9·g/R`: an onset at the crest is flagged
    inconsistent) and modes.py:86 (`s == 1`, `not s == 0`: the threshold not tracked at rest)."""
    from rocking.models.regimes import EventKind, Regime

    statue = rk.Statue(width=0.2, height=1.2, mass=50.0, restitution=0.5)
    crest = rk.g * (0.2 / 1.2) * (1.0 + 1e-10)
    r = rk.simulate(rk.System(statue=statue), rk.RickerPulse(amplitude=crest, frequency=2.0),
                    initial_angular_velocity=0.3)
    *rocking, uplift, settle = r.events
    assert (uplift.kind, uplift.before, uplift.after) == (EventKind.UPLIFT, Regime.REST, Regime.ROCK)
    assert uplift.time == pytest.approx(0.75, abs=1e-5)
    assert (settle.kind, settle.time, settle.after) == (EventKind.SETTLE, uplift.time, Regime.REST)
    assert rocking[-1].kind == EventKind.SETTLE and rocking[-1].time < 0.7
    assert r.summary()["impacts"] == sum(e.kind in (EventKind.IMPACT, EventKind.SETTLE) for e in rocking)
    assert list(r.event_table[-1, 6:9]) == [0.0, 0.0, 0.0]  # θ̇ before and after, energy lost
    after = r.t >= uplift.time
    assert after.sum() > 10 and not np.any(r.theta[after]) and not np.any(r.theta_dot[after])
    energy = r.energy
    assert abs(energy["input_work"]) > 0.01 * energy["impact_dissipation"]
    assert energy["relative_balance_error"] < 1e-8
    assert not [w for w in r.warnings if "strictly consistent" in w]


def test_a_crest_at_the_threshold_to_an_ulp_at_the_start_settles_once():
    """A cos harmonic whose crest, at t = 0, is g·tan α·(1 + 1e-15): rounding makes rocking the
    regime chosen at t = 0 and θ goes the wrong way at once. Before the fix, the settling chose
    rocking again at the same instant: 100 000 SETTLE events at t = 0 and status "max_events",
    so no verdict. Now one SETTLE (rock → rest) at t = 0, the statue stays at rest until the
    last crest (t = 2 s), and the run matches the one with a crest 1e-12 above the threshold,
    which rocks for 0.4 µs and settles (the onset at the last crest to 1e-6 s)."""
    from rocking.models.regimes import EventKind, Regime

    runs = [rk.simulate(rk.System(statue=_SLENDER),
                        rk.Harmonic(amplitude=rk.g * (0.2 / 1.2) * (1.0 + f), frequency=1.5, cycles=3))
            for f in (1e-15, 1e-12)]
    tied, above = runs
    assert tied.status == "completed" and len(tied.events) == 3
    assert tied.events[0] == (0.0, EventKind.SETTLE, Regime.ROCK, Regime.REST)
    before_last_crest = tied.t < 1.99
    assert before_last_crest.sum() > 100 and not np.any(tied.theta[before_last_crest])
    assert tied.summary()["first_rocking_time"] == pytest.approx(2.0, abs=1e-6)
    assert [e.kind for e in tied.events] == [e.kind for e in above.events]
    assert tied.events[1].time == pytest.approx(above.events[1].time, abs=1e-6)
    assert tied.summary()["peak_rotation"] < 1e-20 and not tied.overturned


def test_a_block_sliding_with_its_friction_at_tan_alpha_slides_upright_to_a_verdict():
    """A 0.4 × 2.0 m block (tan α = 0.2) sliding on the floor with μk = 0.2: while it slides, the
    floor pushes its base at μk·g = g·tan α, its rocking threshold, to the last bit. Before, the
    threshold guard, tied to rounding, fired at the start of each step: uplift, then θ went the
    wrong way at once and the block settled, 100 000 times at one instant, status "max_events" and
    no verdict (found by the seventh round of mutation). A tie is no uplift: the run ends at rest,
    the rotation stays at rounding level, and the sliding is that of μk 1e-9 below the tie (to
    1e-9 m)."""
    def run(mu_k):
        statue = rk.Statue(width=0.4, height=2.0, mass=50.0, friction=rk.Friction(static=0.2, kinetic=mu_k))
        return rk.simulate(rk.System(statue=statue), rk.Harmonic(amplitude=2.5 * 0.2 * 9.81, frequency=2.0),
                           throw=False)

    tied, below = run(0.2), run(0.2 * (1.0 - 1e-9))
    assert tied.status == below.status == "completed" and len(tied.events) < 50
    s, ref = tied.summary(), below.summary()
    assert not s["overturned"] and s["peak_rotation"] < 1e-12
    assert abs(s["peak_sliding"] - ref["peak_sliding"]) < 1e-9
    assert abs(s["residual_sliding"] - ref["residual_sliding"]) < 1e-9


def test_a_jump_of_the_floor_motion_that_starts_the_rocking_is_an_event():
    """A record that begins at t = 1 s (zero before) jumps from 0 to 3 m/s², above g·tan α =
    1.63 m/s²: the statue starts to rock at the jump, which the events list as a BREAKPOINT
    (rest → rock). Kills transitions.py:18 (`EV_BREAKPOINT = 9`, a kind no EventKind has)."""
    from rocking.excitation.record import GroundMotion
    from rocking.models.regimes import EventKind, Regime

    t = np.linspace(1.0, 1.5, 51)
    r = rk.simulate(rk.System(statue=_SLENDER), GroundMotion(time=t, values=np.full(t.size, 3.0)))
    assert r.events[0] == (1.0, EventKind.BREAKPOINT, Regime.REST, Regime.ROCK)
    assert r.summary()["first_rocking_time"] == 1.0
    assert r.overturned


def test_a_record_touching_the_rocking_threshold_at_a_sample_leaves_the_statue_at_rest():
    """A record rises linearly to g·tan α exactly at its sample t = 0.2 s and turns back: the
    threshold guard reaches zero at the end of a step cut by that sample, so the uplift is located
    on the sample itself, and θ goes the wrong way at once: UPLIFT and SETTLE at 0.2 s, no
    rocking (a regime counts as entered only once it lasts). The same record rising on past the
    threshold starts the rocking on that sample. Kills compiled.py's piece lookup after an
    event that skips breakpoints only while `< t` (ac02c7f0 of the fourteenth round): the
    event then sits on the old piece, a zero-length step follows, and the tie counts as
    rocking begun at 0.2 s."""
    from rocking.excitation.record import GroundMotion
    from rocking.models.regimes import EventKind, Regime

    statue = rk.Statue(width=0.3, height=1.2, mass=1.0)
    a_uplift = rk.g * 0.25
    t = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]
    touch = rk.simulate(rk.System(statue=statue),
                        GroundMotion(time=np.array(t), values=a_uplift * np.array([0, 0.5, 1, 0.5, 0.5, 0])),
                        duration=2.0)
    assert touch.events == [(0.2, EventKind.UPLIFT, Regime.REST, Regime.ROCK),
                            (0.2, EventKind.SETTLE, Regime.ROCK, Regime.REST)]
    assert touch.summary()["first_rocking_time"] is None
    assert touch.peak_rotation == 0.0 and touch.status == "completed"
    cross = rk.simulate(rk.System(statue=statue),
                        GroundMotion(time=np.array(t), values=a_uplift * np.array([0, 0.5, 1, 1.5, 0.5, 0])),
                        duration=2.0, throw=False)
    assert cross.events[0] == (0.2, EventKind.UPLIFT, Regime.REST, Regime.ROCK)
    assert cross.summary()["first_rocking_time"] == 0.2 and cross.peak_rotation > 1e-3


def test_top_friction_needed_at_impacts_on_a_sliding_pedestal():
    """On a light pedestal (20 kg under the 50 kg statue, μs = 0.18) that slides under a 2.5 m/s²
    sine pulse, every impact of the statue happens while the pedestal slides (u̇⁻ ≈ ±0.01 m/s),
    and the largest friction the statue's base needs in the run is that of those impacts,
    |Fx|/Fy with Fx = m2 (Δu̇ + h Δθ̇): only the change of the pedestal's velocity enters, not the
    velocity itself. Kills transitions.py:58 (`u̇⁺ + u̇⁻` and `u̇⁺ − θ` for `u̇⁺ − u̇⁻`, which
    make the demand ~10⁵ here, where θ̇ is small)."""
    from rocking.models.regimes import EventKind

    pedestal = rk.Pedestal(mass=20.0, friction=rk.Friction(static=0.18, kinetic=0.144))
    r = rk.simulate(rk.System(statue=_SLENDER, pedestal=pedestal), rk.SinePulse(amplitude=2.5, frequency=1.5))
    impact_times = {e.time for e in r.events if e.kind == EventKind.IMPACT}
    impacts = [i for i in r.impacts if i.time in impact_times]
    assert len(impacts) >= 20
    assert all(abs(i.u_dot_before) > 0.005 and i.u_dot_after != i.u_dot_before for i in impacts)
    assert r.summary()["required_top_friction"] == pytest.approx(max(_top_ratio_of(i) for i in impacts), rel=1e-9)


def _light_statue_rocking_on_a_pedestal(mu_s, **kwargs):
    """A 50 g statue on a 20 g pedestal (floor friction μs, μk = 0.8·μs) under a one-sine pulse,
    0.3 s: the statue rocks, and the friction demand on the floor peaks at 0.2062 (the two tests
    below)."""
    statue = rk.Statue(width=0.2, height=1.2, mass=0.05, restitution=0.8)
    pedestal = rk.Pedestal(mass=0.02, friction=rk.Friction(static=mu_s, kinetic=0.8 * mu_s))
    return rk.simulate(rk.System(statue=statue, pedestal=pedestal),
                       rk.SinePulse(amplitude=2.5, frequency=1.5, phase=math.pi), duration=0.3, **kwargs)


def test_a_friction_demand_that_exceeds_mus_for_a_fraction_of_a_step_starts_the_slide():
    """A light statue (50 g) rocks on a 20 g pedestal the floor holds (μs = 10). The friction
    demand |F|/N peaks at 0.2062 (F < 0) at 0.163 s, while the statue rocks, with N below 1 N.
    With μs a millionth below that peak the demand exceeds μs for well under a millisecond,
    inside one step of ~0.02 s whose ends both see the pedestal held: the slide must start there,
    found by tracking the friction guards at the step's stages. Kills modes.py:83 (`cap − F` for
    `cap + F`: the negative direction not tracked) and modes.py:81 (`μs / N` for `μs·N`, which
    with N < 1 N overstates the margin)."""
    from rocking.models.regimes import EventKind, Regime

    held = _light_statue_rocking_on_a_pedestal(10.0, options=rk.Options(save_dt=1e-5))
    forces = held.contact_forces()
    demand = np.where((held.t > 0.1) & (held.t < 0.25), forces["F"] / forces["N"], 0.0)
    i = int(np.argmax(np.abs(demand)))
    t_peak, peak = held.t[i], abs(demand[i])
    assert demand[i] < 0.0 and held.regime[i] == Regime.ROCK and forces["N"].max() < 1.0
    assert not [e for e in held.events if e.kind == EventKind.SLIP]

    slips = [e for e in _light_statue_rocking_on_a_pedestal(peak * (1.0 - 1e-6)).events if e.kind == EventKind.SLIP]
    assert slips, "the slide was missed"
    slip = slips[0]
    assert (slip.before, slip.after) == (Regime.ROCK, Regime.SLIDE_ROCK)
    assert t_peak - 1e-3 < slip.time <= t_peak + 1e-5


# ------------------------------------------------------------------------------------------------
# models/bodies.py: the validation and the value contracts of Statue, Pedestal and System
# ------------------------------------------------------------------------------------------------

_BODIES = {
    "statue": (rk.Statue, {"width": 0.3, "height": 1.2, "mass": 100.0}, "width"),
    "pedestal": (rk.Pedestal, {"mass": 50.0, "friction": rk.Friction(static=0.3)}, "mass"),
    "system": (rk.System, {"statue": rk.Statue(width=0.3, height=1.2, mass=100.0)}, "statue"),
}


@pytest.mark.parametrize("name", sorted(_BODIES))
def test_bodies_are_frozen_hashable_keyword_only_slotted_values(name):
    """bodies.py:20/93/123 frozen, kw_only or slots=True → False, for Statue, Pedestal and
    System. A body is a value: one statue may stand in several systems of a study and serve as a
    key (frozen, hence hashable: eq without frozen sets __hash__ to None); width and height, or
    a pedestal's mass and friction, are too easily swapped by position (keyword-only); it carries
    no attribute besides its fields (slots)."""
    cls, kwargs, field = _BODIES[name]
    body = cls(**kwargs)
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(body, field, getattr(body, field))
    assert hash(body) == hash(cls(**kwargs)) and {body, cls(**kwargs)} == {body}
    with pytest.raises(TypeError):
        cls(*kwargs.values())
    assert not hasattr(body, "__dict__")


@pytest.mark.parametrize("field", ["width", "height", "mass"])
@pytest.mark.parametrize("value", [0.0, -0.5, math.nan, math.inf, "1.0", None], ids=repr)
def test_a_statue_refuses_a_size_or_mass_that_is_not_a_positive_finite_number(field, value):
    """bodies.py:16, the check of B, H and m: `value < 0` (a zero size or mass accepted),
    `not isinstance(..) and not isfinite(..)` (a text or None fails with a TypeError of
    math.isfinite, naming nothing), `not isfinite(..) and value <= 0` (NaN and +inf accepted)."""
    kwargs = {"width": 0.3, "height": 1.2, "mass": 100.0, field: value}
    message = f"statue.{field} must be a positive finite number, got {value!r}"
    with pytest.raises(ValueError, match=re.escape(message)):
        rk.Statue(**kwargs)


@pytest.mark.parametrize("value", [-0.1, 1.5, math.nan, "0.5"], ids=repr)
def test_a_statue_refuses_a_restitution_outside_zero_to_one(value):
    """bodies.py:49: `and` for the first `or` (1.5 accepted; a text fails with a TypeError of the
    comparison) and the upper bound 2.0 for 1.0 (1.5 accepted)."""
    with pytest.raises(ValueError, match=re.escape(f"statue.restitution must lie in [0, 1], got {value!r}")):
        rk.Statue(width=0.3, height=1.2, mass=100.0, restitution=value)


@pytest.mark.parametrize("value", [0.0, 1.0])
def test_a_statue_takes_a_plastic_or_a_perfectly_elastic_restitution(value):
    """bodies.py:49 `0.0 < r` and `r < 1.0`: both ends of [0, 1] are allowed (a plastic impact,
    r = 0, stops the statue dead; r = 1 loses no energy) and used as given, not Housner's value."""
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0, restitution=value)
    assert statue.effective_restitution == value
    assert statue.housner_restitution == pytest.approx(1.0 - 1.5 * 0.15**2 / (0.15**2 + 0.6**2), rel=1e-14)


@pytest.mark.parametrize("value", [-1.0, math.nan, math.inf, "50"], ids=repr)
def test_a_pedestal_refuses_a_mass_that_is_not_a_finite_number_at_least_zero(value):
    """bodies.py:114: `not isinstance(..) and not isfinite(..)` (a text fails with a TypeError of
    math.isfinite) and `not isfinite(..) and m < 0` (NaN and +inf accepted). A massless
    pedestal (m1 = 0, a single block that slides and rocks) stays allowed."""
    friction = rk.Friction(static=0.3)
    with pytest.raises(ValueError, match=re.escape(f"pedestal.mass must be a finite number ≥ 0, got {value!r}")):
        rk.Pedestal(mass=value, friction=friction)
    assert rk.Pedestal(mass=0.0, friction=friction).mass == 0.0


@pytest.mark.parametrize("field", ["width", "height"])
@pytest.mark.parametrize("value", [0.0, -0.5, math.nan, "0.5"], ids=repr)
def test_a_pedestal_refuses_a_width_or_height_that_is_not_a_positive_finite_number(field, value):
    """bodies.py:118 `for name in []`: the optional sizes of the pedestal (its drawing and the
    uplift check) were not checked at all. Not given (None) they are allowed."""
    friction = rk.Friction(static=0.3)
    message = f"pedestal.{field} must be a positive finite number, got {value!r}"
    with pytest.raises(ValueError, match=re.escape(message)):
        rk.Pedestal(mass=50.0, friction=friction, **{field: value})
    assert getattr(rk.Pedestal(mass=50.0, friction=friction, **{field: None}), field) is None


# ------------------------------------------------------------------------------------------------
# excitation/harmonic.py
# ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("form", ["cos", "sin"])
def test_harmonic_follows_its_closed_form_from_start_to_end(form):
    """a_g(t) = A·cos 2πft ("cos") or A·sin 2πft ("sin") on [0, cycles/f], both ends included
    (the cos form is A at t = 0 and at its end), and 0 outside. Kills harmonic.py:73
    (`ω t − φ`), :64 (`−0.5/π`, `+0.5·π`, `−1.5·π` for the sin form's phase −π/2), :72
    (`t > 0`, `t < duration`) and :73 (`1.0` for 0 outside the motion)."""
    amplitude, frequency, cycles = 2.5, 1.25, 3
    motion = rk.Harmonic(amplitude=amplitude, frequency=frequency, cycles=cycles, form=form)
    assert motion.duration == pytest.approx(cycles / frequency, rel=1e-15)
    t = np.linspace(0.0, motion.duration, 241)
    wave = np.cos if form == "cos" else np.sin
    expected = amplitude * wave(2.0 * math.pi * frequency * t)
    np.testing.assert_allclose(motion.acceleration(t), expected, rtol=0.0, atol=1e-12 * amplitude)
    if form == "cos":
        assert float(motion.acceleration(0.0)) == amplitude
        assert float(motion.acceleration(motion.duration)) == pytest.approx(amplitude, rel=1e-12)
    outside = np.array([-0.5, np.nextafter(0.0, -1.0), np.nextafter(motion.duration, math.inf), motion.duration + 0.5])
    assert np.array_equal(motion.acceleration(outside), np.zeros(4))


@pytest.mark.parametrize("value", [math.nan, math.inf, "2.0", None], ids=repr)
def test_harmonic_refuses_an_amplitude_that_is_not_a_finite_number(value):
    """Found by the mutants of harmonic.py: a text or None amplitude raised a TypeError of
    math.isfinite that named neither the field nor the value; it now gets the same one-line
    error as every pulse."""
    with pytest.raises(ValueError, match=re.escape(f"amplitude must be a finite number, got {value!r}")):
        rk.Harmonic(amplitude=value, frequency=1.0)


def test_harmonic_lasts_one_cycle_unless_told():
    """harmonic.py:41 `cycles = 2.0` as the default: without ``cycles`` the motion is one cycle."""
    motion = rk.Harmonic(amplitude=1.0, frequency=2.0)
    assert motion.cycles == 1.0
    assert motion.duration == 0.5


def test_harmonic_is_frozen_and_keyword_only():
    """harmonic.py:14 frozen or kw_only=True → False. A motion may be reused by many runs
    (frozen), and amplitude and frequency are easily swapped by position (keyword-only)."""
    motion = rk.Harmonic(amplitude=2.0, frequency=1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        motion.amplitude = 3.0
    with pytest.raises(TypeError):
        rk.Harmonic(2.0, 1.0)


# ------------------------------------------------------------------------------------------------
# models/regimes.py: the names of the codes the compiled solver writes
# ------------------------------------------------------------------------------------------------


def test_regime_of_names_the_motion_pattern_of_the_slip_and_pivot_signs():
    """Regime.of(σ, s): REST when nothing moves, ROCK when the statue rocks on a held body (either
    pivot), SLIDE when the body on the floor slides (either way) and the statue does not rock,
    SLIDE_ROCK for both, as the compiled solver encodes them (compiled._regime). Kills every
    mutant of regimes.py:21 (`−` for `+`, `==` for `!=`, `not`, `s != 1`, `sig != 1`, 2 or 3
    for 1 or 2, `else 1`) and regimes.py:16 (`SLIDE = 3`, which leaves no member for code 2)."""
    from rocking.models.regimes import Regime
    from rocking.solver.compiled import _regime

    expected = {(0, 0): Regime.REST, (0, 1): Regime.ROCK, (0, -1): Regime.ROCK,
                (1, 0): Regime.SLIDE, (-1, 0): Regime.SLIDE}
    expected.update({(sig, s): Regime.SLIDE_ROCK for sig in (1, -1) for s in (1, -1)})
    for (sig, s), regime in expected.items():
        assert Regime.of(sig, s) is regime, (sig, s)
        assert Regime(_regime(sig, s)) is regime, (sig, s)


def test_event_kinds_are_the_codes_the_compiled_transitions_write():
    """Each EventKind has the code models/transitions.py writes for that event, and a block
    sliding on the floor reports its slip and its stop by name. Kills regimes.py:28 (`SLIP = 3`:
    STOP becomes an alias and code 2 has no name) and regimes.py:34 (`BREAKPOINT = 9`)."""
    from rocking.models import transitions as tr
    from rocking.models.regimes import EventKind, Regime

    codes = {"IMPACT": tr.EV_IMPACT, "SLIP": tr.EV_SLIP, "STOP": tr.EV_STOP, "UPLIFT": tr.EV_UPLIFT,
             "EXCEED_ALPHA": tr.EV_EXCEED, "FALL": tr.EV_FALL, "SETTLE": tr.EV_SETTLE, "BREAKPOINT": tr.EV_BREAKPOINT}
    assert {kind.name: int(kind) for kind in EventKind} == codes

    # a square block (rocks only past g) with μs = 0.2 under a 3 m/s² sine: it slides, never rocks
    block = rk.Statue(width=1.0, height=1.0, mass=10.0, friction=rk.Friction(static=0.2, kinetic=0.15))
    r = rk.simulate(rk.System(statue=block), rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=1, form="sin"))
    slip, stop = r.events[0], r.events[1]
    assert (slip.kind, slip.before, slip.after) == (EventKind.SLIP, Regime.REST, Regime.SLIDE)
    assert (stop.kind, stop.before, stop.after) == (EventKind.STOP, Regime.SLIDE, Regime.REST)
    assert math.sin(2.0 * math.pi * 2.0 * slip.time) == pytest.approx(0.2 * rk.g / 3.0, rel=1e-9)
    assert set(np.unique(r.regime)) == {Regime.REST, Regime.SLIDE}


# ------------------------------------------------------------------------------------------------
# excitation/_checks.py: the checks every floor motion shares
# ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("value", [0, -1.0, math.nan, math.inf, "1.5", None], ids=repr)
def test_a_motion_refuses_a_frequency_or_width_that_is_not_a_positive_finite_number(value):
    """_checks.py:7 (`positive`): `value < 0` (0 Hz accepted), `and` for any of the first two
    `or` (a text fails with a TypeError of math.isfinite, naming nothing), `not isfinite(..) and
    value <= 0` (NaN and +inf accepted)."""
    with pytest.raises(ValueError, match=re.escape(f"frequency must be a positive finite number, got {value!r}")):
        rk.Harmonic(amplitude=1.0, frequency=value)
    with pytest.raises(ValueError, match=re.escape(f"width must be a positive finite number, got {value!r}")):
        rk.RectanglePulse(amplitude=1.0, width=value)


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, "2.0", None], ids=repr)
def test_a_pulse_refuses_an_amplitude_or_rate_that_is_not_a_finite_number(value):
    """_checks.py:12 (`finite`): `and` for either `or` (a text fails with a TypeError of
    math.isfinite instead of naming the field). Zero and negative values stay allowed."""
    with pytest.raises(ValueError, match=re.escape(f"amplitude must be a finite number, got {value!r}")):
        rk.SinePulse(amplitude=value, frequency=1.0)
    with pytest.raises(ValueError, match=re.escape(f"rate must be a finite number, got {value!r}")):
        rk.Ramp(rate=value, end=1.0)
    assert rk.SinePulse(amplitude=-2.0, frequency=1.0).amplitude == -2.0


# ------------------------------------------------------------------------------------------------
# solver/signals.py: SIGTERM in a study's worker process (SIGINT ignored, SIGTERM default)
# ------------------------------------------------------------------------------------------------

_WORKER_GETS_SIGTERM = """\
import os, signal, time
signal.signal(signal.SIGINT, signal.SIG_IGN)    # as analyses/executors.py sets up a worker
signal.signal(signal.SIGTERM, signal.SIG_DFL)
from rocking.solver.signals import deferred_signals
with deferred_signals() as flag:
    os.kill(os.getpid(), signal.SIGTERM)
    for _ in range(1000):
        if flag[0]:
            break
        time.sleep(0.001)
    print("deferred", int(flag[0]), signal.getsignal(signal.SIGINT) == signal.SIG_IGN, flush=True)
print("still alive", flush=True)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_sigterm_in_a_worker_that_ignores_ctrl_c_is_deferred_then_ends_the_process():
    """A study's worker ignores SIGINT and keeps SIGTERM's default action. A SIGTERM while it
    simulates is recorded (the solver returns early), SIGINT stays ignored, and when the block
    ends the process dies of that SIGTERM, as it would have without the deferral. Kills
    signals.py:51 (`break` for `continue`: after the ignored SIGINT, SIGTERM is not deferred and
    kills the process inside the compiled loop), :62 (`not callable`: SIG_DFL is called and
    raises TypeError) and :65 (`!=` for `==`, or `not ==`: the SIGTERM is swallowed and the
    worker lives on)."""
    import os
    import signal
    import subprocess
    from pathlib import Path

    src = str(Path(rk.__file__).resolve().parents[1])  # the rocking under test (the mutated copy in `try`)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [src, os.environ.get("PYTHONPATH")]))}
    proc = subprocess.run([sys.executable, "-c", _WORKER_GETS_SIGTERM], env=env, capture_output=True, text=True,
                          timeout=120)
    assert proc.stdout == f"deferred {int(signal.SIGTERM)} True\n", (proc.stdout, proc.stderr)
    assert proc.returncode == -signal.SIGTERM, (proc.returncode, proc.stderr)
    assert "Traceback" not in proc.stderr, proc.stderr


# ------------------------------------------------------------------------------------------------
# excitation/record.py: GroundMotion's trimming, repr, metadata, identity and vertical record
# ------------------------------------------------------------------------------------------------


def _record(**kw):
    """A record that starts at 0.5 s, not 0 (so time[0] and time[1] are told apart): horizontal
    2, −4, 1 m/s² and vertical 1, 3, 0 m/s² at 0.5, 1.0, 1.5 s."""
    from rocking.excitation.record import GroundMotion

    kw = {"name": "s", "vertical": [1.0, 3.0, 0.0], **kw}
    return GroundMotion.from_arrays([0.5, 1.0, 1.5], [2.0, -4.0, 1.0], **kw)


def test_a_record_trimmed_at_its_last_sample_is_the_record_itself():
    """Cutting a record where it ends cuts nothing: the record comes back as it is, and its
    metadata does not claim a trim. Kills record.py:303 `t_end > time[-1]` (a new motion with
    `trimmed_at` in its metadata)."""
    gm = _record()
    assert gm.trimmed(gm.duration) is gm
    assert "trimmed_at" not in gm.trimmed(1.5).meta


def test_a_record_can_be_trimmed_inside_its_first_interval():
    """A cut between the first two samples keeps the first sample and adds one interpolated at
    the cut (the history up to it unchanged); a cut on the second sample keeps two samples.
    Kills record.py:298 `t_end <= time[1]` (both cuts refused)."""
    cut = _record().trimmed(0.75)
    assert cut.time.tolist() == [0.5, 0.75]
    assert cut.values.tolist() == [2.0, -1.0]  # halfway from 2 to −4
    assert cut.vertical.tolist() == [1.0, 2.0]  # halfway from 1 to 3
    assert cut.duration == 0.75 and cut.meta["trimmed_at"] == 0.75
    on_sample = _record().trimmed(1.0)
    assert on_sample.time.tolist() == [0.5, 1.0] and on_sample.values.tolist() == [2.0, -4.0]


@pytest.mark.parametrize("t_end", [0.5, 0.25, math.nan], ids=repr)
def test_a_cut_at_or_before_the_first_sample_is_refused_naming_the_first_time(t_end):
    """The error states the first sample's time (0.5 s here) and the cut asked for. Kills
    record.py:301 `time[1]` (the message quoted the second sample's time, 1.0)."""
    message = f"GroundMotion.trimmed: t_end must be finite and > time[0] = 0.5, got {t_end!r}"
    with pytest.raises(ValueError, match=re.escape(message)):
        _record().trimmed(t_end)


def test_the_repr_of_a_record_says_whether_it_has_a_vertical_component():
    """Kills record.py:323 `is None` for `is not None`, and `not … is not None` (yes and no
    swapped)."""
    assert repr(_record()) == ("GroundMotion(name='s', n=3, dt=0.5 s, duration=1.5 s, pga=4 m/s², "
                               "vertical=yes)")
    assert repr(_record(vertical=None)).endswith(", vertical=no)")


@pytest.mark.parametrize(
    ("meta", "kind"),
    [(5, "int"), ([("station", "TAK", "extra")], "list"), ([1.0], "list")],
    ids=["a number", "a triple", "a list of numbers"],
)
def test_metadata_that_is_neither_a_mapping_nor_pairs_is_refused_naming_the_field(meta, kind):
    """`dict(meta)` of a number raises TypeError, of a triple ValueError: both become the
    one-line error naming `GroundMotion.meta` and the type given. Pairs and mappings are taken
    (as a read-only copy). Kills record.py:116 `isinstance(meta, Mapping)` and `not not
    isinstance(..)` (a non-mapping is not converted: a raw TypeError or ValueError of `dict`),
    record.py:119 `TypeError` or `ValueError` no longer caught."""
    message = f"GroundMotion.meta must be a mapping or (key, value) pairs, got {kind} ("
    with pytest.raises(ValueError, match=re.escape(message)):
        _record(meta=meta)
    assert dict(_record(meta=[("station", "TAK")]).meta) == {"station": "TAK"}
    given = {"station": "TAK"}
    gm = _record(meta=given)
    given["station"] = "other"
    assert dict(gm.meta) == {"station": "TAK"}
    with pytest.raises(TypeError):
        gm.meta["station"] = "other"  # type: ignore[index]


def test_ground_motions_compare_and_hash_by_identity():
    """Two records with the same samples are two motions: `==` is identity, and a motion can be
    a dict key or a set member, and `motion in motions` works. Kills record.py:49
    `eq=True` (a hash of the fields fails on the arrays, and `==` compares arrays element-wise:
    `in` raises)."""
    a, b = _record(), _record()
    assert a == a and a != b
    assert len({a, b}) == 2 and {a: "first", b: "second"}[b] == "second"
    assert b in [a, b] and hash(a) == hash(a)


@pytest.mark.parametrize(("name", "shown"), [("quiet", "'quiet'"), ("", "'the record'")])
def test_scaling_a_silent_record_to_a_pga_names_the_record(name, shown):
    """A record that is zero everywhere cannot be scaled to a PGA: the error names it, or says
    'the record' if it has no name. Kills record.py:275 `name and 'the record'`."""
    from rocking.excitation.record import GroundMotion

    silent = GroundMotion.from_arrays([0.0, 0.01, 0.02], [0.0, 0.0, 0.0], name=name)
    message = f"GroundMotion.scaled: cannot scale {shown} to a target PGA because it is identically zero"
    with pytest.raises(ValueError, match=re.escape(message)):
        silent.scaled(pga=1.0)


def test_the_vertical_record_is_zero_before_its_first_sample_and_after_its_last():
    """The floor is still before a record starts (here at 0.5 s), vertically as horizontally,
    and linear between samples. Kills record.py:215 `left=1.0` (1 m/s² upwards before the
    record)."""
    gm = _record()
    t = np.array([0.0, 0.49, 0.5, 0.75, 1.25, 1.5, 1.51, 3.0])
    assert gm.vertical_acceleration(t).tolist() == [0.0, 0.0, 1.0, 2.0, 1.5, 0.0, 0.0, 0.0]
    assert gm.acceleration(t).tolist() == [0.0, 0.0, 2.0, -1.0, -1.5, 1.0, 0.0, 0.0]


# ------------------------------------------------------------------------------------------------
# io/records.py: record files (PEER AT2, ESM ASCII, two-column), their errors, the size limit
# ------------------------------------------------------------------------------------------------

_G = 9.80665  # m/s² per g, the conversion the reader documents
_PEER_TOP = "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Nowhere, 0\n"
_TWO_COLUMN_TOP = "Castaic record\nSource: a test\nTime[s] Accel[g]\n"  # rows start on line 4


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _record_error(path) -> str:
    """The message of the RecordError that reading ``path`` raises."""
    with pytest.raises(RecordError) as info:
        read_record(path)
    return str(info.value)


def _sparse(tmp_path, size):
    """A file of `size` bytes that takes no disk space (the size check only stats the file)."""
    path = tmp_path / "big.AT2"
    with open(path, "wb") as f:
        f.truncate(size)
    return path


def test_a_two_column_time_that_does_not_parse_is_reported_at_its_line(tmp_path):
    """The error for a garbled time names its line (rows on lines 4 and 5). Kills records.py:414
    `idx - 1` and `idx + 2` (the time's line given as 3 or 6)."""
    path = _write(tmp_path, "rows.dat", _TWO_COLUMN_TOP + "0.00 0.1\n0.0l 0.2\n")
    with pytest.raises(RecordError) as info:
        read_record(path)
    assert str(info.value) == f"{path}: line 5: cannot parse '0.0l' as a number"


def test_an_unsorted_time_is_reported_with_the_time_before_it(tmp_path):
    """0.015 s after 0.02 s: the error quotes both times and both lines. Kills records.py:427
    `times[i + 1]` and `times[i - 2]` (the previous time quoted as 0.03 or 0.01)."""
    rows = "0.00 0.1\n0.01 0.2\n0.02 0.3\n0.015 0.4\n0.03 0.5\n"  # lines 4 to 8
    path = _write(tmp_path, "unsorted.dat", _TWO_COLUMN_TOP + rows)
    assert _record_error(path) == (f"{path}: line 7: time 0.015 is not greater than the previous time "
                                   "0.02 (line 6); times must be strictly increasing")


@pytest.mark.parametrize(
    "header",
    [
        "Castaic record\nSource: a test\nTime[s] Accel[g]\n",
        "Castaic record\nSource: a test, units: g\ntime accel\n",
        "Castaic record\nSource: a test\nTIME SERIES IN UNITS OF G\n",
    ],
    ids=["Accel[g]", "units: g", "UNITS OF G"],
)
def test_a_two_column_header_states_its_units_in_any_of_three_ways(tmp_path, header):
    """The units come from the header line that states them; units that contradict them are
    refused, naming that line (line 3 here, or 2). Kills records.py:438 `j - 1` and `j + 2` (the
    wrong line named), records.py:435 `_UNITS_OF_RE.search(..) and _UNITS_KEY_RE.search(..)` (a
    `units: g` line no longer read)."""
    path = _write(tmp_path, "castaic.dat", header + "0.00 0.1\n0.01 -0.2\n")
    gm = read_record(path)
    assert gm.units == "g" and gm.values.tolist() == [0.1 * _G, -0.2 * _G]
    with pytest.raises(UnitsConflictError) as info:
        read_record(path, units="m/s2")
    line = 2 if "units:" in header else 3
    assert info.value.line == line and str(info.value).startswith(f"{path}: line {line}: ")


def test_the_first_statement_of_units_in_a_header_is_the_one_used(tmp_path):
    """A later 'units' in the header (of the time column) does not replace the acceleration's:
    PEER reads `UNITS OF G` on line 3, not `UNITS OF SEC` on line 4; two-column reads `Accel[g]`,
    not `time units: s`. Kills records.py:307 and 439 `break` → `continue` (the last statement
    wins: 'SEC' and 's' are refused as unknown units)."""
    peer = _write(tmp_path, "two_units.AT2", _PEER_TOP + "ACCELERATION TIME SERIES IN UNITS OF G\n"
                  "NPTS= 3, DT= .0100 SEC (TIME IN UNITS OF SEC)\n 0.1 0.2 -0.3\n")
    gm = read_record(peer)
    assert gm.meta["header_units"] == "G"
    np.testing.assert_allclose(gm.values, [0.1 * _G, 0.2 * _G, -0.3 * _G], rtol=1e-15)
    columns = _write(tmp_path, "two_units.dat", "Time[s] Accel[g]\ntime units: s\n0 0.1\n0.01 0.2\n")
    assert read_record(columns).meta["header_units"] == "g"


def test_a_value_that_overflows_in_si_units_is_named_by_its_position(tmp_path):
    """1e308 g is finite in the file but not in m/s²: the error counts the values from 1.
    Kills records.py:574 `bad[0] - 1`, `bad[0] + 2`."""
    path = _write(tmp_path, "huge.AT2", _PEER_TOP + "ACCELERATION IN UNITS OF G\n"
                  "NPTS= 3, DT= .01 SEC\n0.1 0.2 1e308\n")
    with pytest.raises(RecordError) as info:
        read_record(path)
    assert str(info.value) == f"{path}: value #3 (1e+308 g) overflows when converted to m/s²"


def test_read_record_takes_its_options_by_keyword_only(tmp_path):
    """`read_record(path, "peer")` is refused: format, units and the override are easily
    swapped by position. Kills records.py:476 `*` → `/` (positional-only path, the options
    then positional too)."""
    path = _write(tmp_path, "ok.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= 2, DT= .01\n1 2\n")
    with pytest.raises(TypeError):
        read_record(path, "peer")
    assert read_record(path, format="peer").n == 2


@pytest.mark.parametrize(
    ("raw", "limit"), [("2.5", 2_500_000), (" 0.5 ", 500_000), ("1e-6", 1)], ids=repr
)
def test_the_record_size_limit_is_read_from_the_environment_in_megabytes(monkeypatch, raw, limit):
    """`ROCKING_MAX_RECORD_MB` is in MB (10⁶ bytes), any positive number, below 1 too. Kills
    records.py:625 `mb / 1_000_000`, `mb * 1000001`; records.py:623 `not` deleted, `not not`,
    `mb <= 0` (a positive value refused), `mb > 1` (0.5 MB refused)."""
    monkeypatch.setenv(RECORD_LIMIT_ENV, raw)
    assert record_size_limit() == limit


@pytest.mark.parametrize("raw", ["0", "-3", "lots", "nan", "inf"])
def test_a_record_size_limit_that_is_not_a_positive_number_is_refused(monkeypatch, raw):
    """Kills records.py:623 `mb >= 0` (0 accepted), `or` for `and` (−3 accepted; inf then
    overflows in `int`), records.py:621 `ValueError` not caught (a text gives float()'s own
    message, which names neither the variable nor the value)."""
    monkeypatch.setenv(RECORD_LIMIT_ENV, raw)
    message = f"ROCKING_MAX_RECORD_MB must be a positive number of MB, got {raw!r}"
    with pytest.raises(ValueError, match=re.escape(message)):
        record_size_limit()


def test_the_default_record_size_limit_is_50_mb(tmp_path, monkeypatch):
    """Without the environment variable the limit is 50 MB (10⁶ bytes each): one byte more is
    refused. Kills records.py:52 `MAX_RECORD_BYTES = 50000001`."""
    monkeypatch.delenv(RECORD_LIMIT_ENV, raising=False)
    assert record_size_limit() == 50_000_000
    with pytest.raises(RecordError, match="over the 50 MB limit"):
        read_record(_sparse(tmp_path, 50_000_001))


def test_a_record_exactly_at_the_size_limit_is_read(tmp_path):
    """Kills records.py:634 `size >= limit`."""
    path = _write(tmp_path, "ok.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= 2, DT= .01\n1 2\n")
    size = path.stat().st_size
    assert read_record(path, max_bytes=size).values.tolist() == [_G, 2 * _G]
    with pytest.raises(RecordError, match="over the"):
        read_record(path, max_bytes=size - 1)


@pytest.mark.parametrize(
    ("size", "limit", "said"),
    [
        (1_000_001, 1_000_000, "the file is 1 MB, over the 1 MB limit for a record (reading it "
         "would take about 10 MB of memory); use a shorter or decimated record, or raise the limit "
         "with the environment variable ROCKING_MAX_RECORD_MB=2 (max_bytes= in Python)"),
        (2_500_000, 2_000_000, "the file is 2.5 MB, over the 2 MB limit for a record (reading it "
         "would take about 25 MB of memory)"),
        (95_000_000, 50_000_000, "the file is 95 MB, over the 50 MB limit for a record (reading it "
         "would take about 950 MB of memory)"),
        (100_000_000, 50_000_000, "the file is 100 MB, over the 50 MB limit for a record (reading "
         "it would take about 1 GB of memory); use a shorter or decimated record, or raise the "
         "limit with the environment variable ROCKING_MAX_RECORD_MB=100 (max_bytes= in Python)"),
        (125_050_000, 50_000_000, "the file is 125 MB, over the 50 MB limit for a record (reading "
         "it would take about 1.3 GB of memory); use a shorter or decimated record, or raise the "
         "limit with the environment variable ROCKING_MAX_RECORD_MB=126 (max_bytes= in Python)"),
    ],
    ids=["1 MB", "2.5 MB", "95 MB", "100 MB", "125 MB"],
)
def test_a_record_over_the_size_limit_is_refused_saying_its_size_and_the_memory_it_needs(
        tmp_path, size, limit, said):
    """The size in MB (10⁶ bytes), the limit, ten times the size as the memory (in GB from 1 GB
    on), and the smallest whole-MB limit that would let the file through. Kills
    records.py:635 `size * 1_000_000`, `size / 1000001` (the ceiling of 1.000001 MB is 2);
    records.py:640 `limit * 1_000_000`, `limit / 1000001`; records.py:636: `10 / mb` in either
    unit or in the test, `* 1000`, `11 * mb` in either unit or in the test, `/ 1001` (1.2 GB),
    `>= 1001`, `> 1000` (100 MB), `<` and `not` (the units swapped)."""
    path = _sparse(tmp_path, size)
    with pytest.raises(RecordError) as info:
        read_record(path, max_bytes=limit)
    assert info.value.line is None and info.value.reason.startswith(said)
    assert str(info.value).startswith(f"{path}: ")


def test_a_forced_format_error_says_what_the_file_looks_like_only_when_it_is_another_format(
        tmp_path):
    """`format="esm"` on a PEER file: the ESM reader's error, plus a hint that the file looks
    like a PEER AT2 file; `format="peer"` on a PEER file with a bad header: the error alone.
    Kills records.py:598 `detected != forced` and `not detected == forced` (the hint given in
    the wrong case only)."""
    peer = _write(tmp_path, "rec.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= 2, DT= .01\n1 2\n")
    with pytest.raises(RecordError) as info:
        read_record(peer, format="esm")
    assert str(info.value).endswith(" (format 'esm' was asked for, but the file looks like a PEER "
                                    "AT2 file: omit the format to detect it)")
    bad = _write(tmp_path, "bad.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= many, DT= .01\n1 2\n")
    with pytest.raises(RecordError) as info:
        read_record(bad, format="peer")
    assert str(info.value) == f"{bad}: line 4: malformed header: NPTS = 'many' is not an integer"


def test_a_bundled_record_is_found_by_its_name_in_any_case():
    """Kills records.py:678 `!=` (every other record matches), records.py:679 `len(folded) == 2`,
    records.py:680 `folded[1]`."""
    assert resolve_record("KOBE1995_takatori_000") == bundled_records()["Kobe1995_Takatori_000"]


def test_an_unknown_record_name_suggests_at_most_three_close_names():
    """Kills records.py:682 `if not close` (no suggestion when there are some, an empty one
    when there are none), records.py:681 `n=4` (a fourth, Kocaeli, suggested)."""
    with pytest.raises(FileNotFoundError) as info:
        resolve_record("Northridge1994_Sta_000")
    assert ("Did you mean Northridge1994_SylmarConverterSta_052, Northridge1994_RinaldiReceivingSta_228, "
            "Northridge1994_CastaicOldRidgeRoute_090_2col? Bundled records: ") in str(info.value)
    with pytest.raises(FileNotFoundError) as info:
        resolve_record("zzz")
    assert "Did you mean" not in str(info.value)
    assert str(info.value).startswith("'zzz' is neither an existing file nor a bundled record. Bundled")


@pytest.mark.parametrize(
    ("name", "text", "line", "field"),
    [
        ("dt0.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= 3, DT= 0.0 SEC\n1 2 3\n", 4, "DT = '0.0'"),
        ("dt0.ASC", "EVENT_NAME: TEST\nNDATA: 3\nSAMPLING_INTERVAL_S: 0\nUNITS: g\n1\n2\n3\n", 3,
         "SAMPLING_INTERVAL_S = '0'"),
    ],
    ids=["peer", "esm"],
)
def test_a_zero_sampling_interval_is_refused_at_its_header_line(tmp_path, name, text, line, field):
    """Kills records.py:265 `dt >= 0.0` (DT = 0 accepted: every time is 0, and the error is
    GroundMotion's, about time[1] = 0.0, with no line)."""
    path = _write(tmp_path, name, text)
    with pytest.raises(RecordError) as info:
        read_record(path)
    assert str(info.value) == f"{path}: line {line}: malformed header: {field} must be positive"


def test_the_event_of_a_peer_file_is_its_second_header_line(tmp_path):
    """A PEER file's event is line 2 of its header; a header of the NPTS line alone has none.
    Kills records.py:313 `len(header) >= 1` (IndexError on a one-line header)."""
    standard = _write(tmp_path, "std.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= 2, DT= .01\n1 2\n")
    assert read_record(standard).meta["event"] == "Test, 1/1/2000, Nowhere, 0"
    bare = _write(tmp_path, "bare.AT2", "NPTS= 3, DT= .01 SEC, ACCELERATION IN UNITS OF G\n1 2 3\n")
    gm = read_record(bare)
    assert gm.meta["event"] == "" and gm.time.tolist() == [0.0, 0.01, 0.02]
    assert gm.values.tolist() == [_G, 2 * _G, 3 * _G]


def test_the_units_override_is_recorded_only_when_it_replaced_the_header_units(tmp_path):
    """A PEER file in g read as cm/s² with `units_override=True` says so in its meta; read with
    units that agree with the header, it does not. Kills records.py:562 `units is None` (the
    override not recorded) and `or` (recorded whenever units are given)."""
    path = _write(tmp_path, "g.AT2", _PEER_TOP + "ACCELERATION IN UNITS OF G\nNPTS= 2, DT= .01\n50 -20\n")
    overridden = read_record(path, units="cm/s2", units_override=True)
    assert overridden.meta["units_override"] is True and overridden.values.tolist() == [0.5, -0.2]
    agreeing = read_record(path, units="G")
    assert agreeing.meta["units_override"] is False
    assert agreeing.values.tolist() == [50 * _G, -20 * _G]


@pytest.mark.parametrize(
    ("name", "text", "line"),
    [
        ("v.AT2", _PEER_TOP + "VELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 2, DT= .01\n1 2\n", 4),
        ("d.AT2", _PEER_TOP + "DISPLACEMENT TIME SERIES IN UNITS OF CM\nNPTS= 2, DT= .01\n1 2\n", 4),
        ("v.ASC", "EVENT_NAME: TEST\nNDATA: 2\nSAMPLING_INTERVAL_S: 0.01\nUNITS: cm/s\n"
         "DATA_TYPE: VELOCITY\n1\n2\n", 5),
    ],
    ids=["peer velocity", "peer displacement", "esm velocity"],
)
def test_a_velocity_or_displacement_record_is_refused(tmp_path, name, text, line):
    """The message is compared whole: the file names here do not contain 'velocity' (the test of
    test_records.py matched it in its tmp_path's name, so a velocity file refused for its units
    'CM/S' passed). Kills records.py:271 `not` deleted and `not` added before the first search
    (a velocity record read as an acceleration)."""
    path = _write(tmp_path, name, text)
    assert _record_error(path) == (f"{path}: line {line}: this is a velocity or displacement record, "
                                   "not an acceleration")


@pytest.mark.parametrize(
    "title",
    ["PEER RECORD, SCALED IN UNITS OF G",
     "ACCELERATION IN UNITS OF G (VELOCITY AND DISPLACEMENT IN OTHER FILES)"],
    ids=["no kind named", "acceleration and velocity named"],
)
def test_a_peer_header_that_does_not_say_velocity_alone_is_an_acceleration(tmp_path, title):
    """Kills records.py:271 `or` for `and` (a header without the word ACCEL refused), `not`
    added (the same), `not` deleted (a header naming acceleration and velocity refused)."""
    path = _write(tmp_path, "acc.AT2", f"{title}\nTest\nNPTS= 2, DT= .01\n0.5 -0.25\n")
    assert read_record(path).values.tolist() == [0.5 * _G, -0.25 * _G]


def test_blank_lines_between_values_are_skipped(tmp_path):
    """Kills records.py:227 `continue` → `break` (reading stops at a blank line: 2 values of 4)."""
    path = _write(tmp_path, "gap.AT2", _PEER_TOP + "IN UNITS OF G\nNPTS= 4, DT= .01\n1 2\n\n  \n3 4\n")
    assert read_record(path).values.tolist() == [_G, 2 * _G, 3 * _G, 4 * _G]


def test_a_two_column_header_may_hold_blank_lines(tmp_path):
    """The data start at the first line that starts with a number, not at a blank line. Kills
    records.py:383 `return True` for a blank line (the header ends at the blank line and
    'Time[s] Accel[g]' is read as a row)."""
    path = _write(tmp_path, "blank.dat", "Castaic record\n\nTime[s] Accel[g]\n0.0 0.1\n0.01 -0.2\n")
    gm = read_record(path)
    assert gm.meta["header"] == ("Castaic record", "", "Time[s] Accel[g]")
    assert gm.values.tolist() == [0.1 * _G, -0.2 * _G] and gm.units == "g"


def test_the_npts_line_is_looked_for_in_the_first_ten_lines(tmp_path):
    """Line 10 is still read; on line 11 the error says where it was looked for. Kills
    records.py:93 `_PEER_HEADER_SEARCH = 11`."""
    ten = _write(tmp_path, "ten.AT2", "ACCELERATION IN UNITS OF G\n" + "note\n" * 8
                 + "NPTS= 2, DT= .01\n1 2\n")
    assert read_record(ten).n == 2
    eleven = _write(tmp_path, "eleven.AT2", "ACCELERATION IN UNITS OF G\n" + "note\n" * 9
                    + "NPTS= 2, DT= .01\n1 2\n")
    with pytest.raises(RecordError) as info:
        read_record(eleven)
    assert str(info.value) == (f"{eleven}: no 'NPTS= n, DT= x' line in the first 10 lines (PEER AT2 "
                               "files have it on line 4)")


def test_a_file_read_as_esm_without_a_key_line_names_line_1_and_quotes_60_characters(tmp_path):
    """Kills records.py:337 `first_data == 1` (the error is then about missing fields), records.py:341
    line 2, records.py:343 `[:61]`."""
    first = "Strong-motion record of the Northridge earthquake, station 24278, component 090"
    path = _write(tmp_path, "prose.txt", first + "\n0.0 0.1\n0.01 0.2\n")
    with pytest.raises(RecordError) as info:
        read_record(path, format="esm", units="g")
    assert info.value.line == 1
    assert info.value.reason.startswith(
        "not an ESM ASCII file: the header must start with 'KEY: value' lines (EVENT_NAME: ..., "
        f"NDATA: ...), got {first[:60]!r} (format 'esm' was asked for")


# ------------------------------------------------------------------------------------------------
# models/modes.py (seventh round): Painlevé's paradox at t = 0, dips inside one step, tan α = μs
# ------------------------------------------------------------------------------------------------

# A block 0.2555 × 0.7 m (tan α = 0.365) with μs = μk = 2 on the floor, set sliding at 0.5 m/s.
_PAINLEVE_BLOCK = rk.Statue(width=0.7 * 0.365, height=0.7, mass=1.0, friction=rk.Friction(static=2.0, kinetic=2.0))


def test_a_block_set_sliding_into_painleves_paradox_is_reported_singular_at_once():
    """A block sliding towards +x with μk = 2 > tan α on a floor at a = +1 m/s² has no consistent
    regime (derivation §3.1, §5): sliding upright needs |a + ü| = μk·g ≤ g·tan α; slide-rock about
    the leading corner (σ = s = +1) has D = M·I_O − (m R)²·cos α·(cos α + μk·sin α) < 0 (Painlevé),
    and about the trailing corner s·θ̈ ∝ −(μk·cos α + sin α)/D < 0. The run must not pretend
    otherwise: the block is reported sliding upright at t = 0 (fewest moving degrees of freedom,
    flagged), the rocking threshold is past at once, an uplift into slide-rock follows at t = 0
    (flagged too), and the run stops "singular" (a SimulationError by default). Kills modes.py:121
    (`n_sig = 2`: a moving pedestal "held" at once), modes.py:134 (`sig_list[1]`: the fallback's
    slip dropped), modes.py:135 (`or`: the fallback rocks at t = 0, no uplift), modes.py:136-137
    (the fallback's rocking direction from the slide-rock ü, from a − ü, or reversed: the
    trailing corner) and modes.py:174 (the fallback reported consistent)."""
    from rocking.models.regimes import EventKind, Regime

    m, b, h = 1.0, 0.5 * 0.7 * 0.365, 0.35
    alpha, big_r, i_o, mu = _PAINLEVE_BLOCK.slenderness, math.hypot(b, h), _PAINLEVE_BLOCK.inertia_about_corner, 2.0
    assert mu > math.tan(alpha)
    assert m * i_o - (m * big_r) ** 2 * math.cos(alpha) * (math.cos(alpha) + mu * math.sin(alpha)) < 0.0
    floor = rk.Harmonic(amplitude=1.0, frequency=1.0)  # cos form: a(0) = +1 m/s², between 0 and μk·g
    r = rk.simulate(rk.System(statue=_PAINLEVE_BLOCK), floor, initial_sliding_velocity=0.5, throw=False)
    assert r.status == "singular"
    assert r.events == [(0.0, EventKind.UPLIFT, Regime.SLIDE, Regime.SLIDE_ROCK)]
    assert Regime(int(r.regime[0])) == Regime.SLIDE
    assert "2 instant(s) where no regime was strictly consistent" in r.warnings
    with pytest.raises(rk.SimulationError, match="Painlevé"):
        rk.simulate(rk.System(statue=_PAINLEVE_BLOCK), floor, initial_sliding_velocity=0.5)


@dataclasses.dataclass(frozen=True, kw_only=True)
class _PushedWhileTheFloorDips(rk.RectanglePulse):
    """A constant horizontal push with a vertical Ricker dip: a user-defined motion whose
    vertical acceleration is not piecewise linear (AbstractMotion lets a subclass give one)."""

    dip: rk.RickerPulse

    def vertical_signal(self):
        return self.dip.signal()

    def vertical_acceleration(self, t):
        return self.dip.acceleration(np.asarray(t, dtype=float))


def test_a_dip_of_the_vertical_acceleration_inside_one_step_starts_the_rocking():
    """A statue (tan α = 1/6) at rest under a constant 0.9·g·tan α, while the floor drops briefly
    (a vertical Ricker dip, crest at 0.75 s) so that (g + a_v)·tan α falls 0.1 % below the push at
    its crest: the rocking must start where (g + a_v(t))·tan α = a_g first (closed form of the
    Ricker, found by root bracketing), about 9 ms before the crest, and the statue rocks
    (tiny, but not zero). Rest steps are long (0.1 s) and both their ends lie above the threshold:
    only the guard tracked at the step's stages sees the dip. Kills modes.py:87 (`g − a_v` in the
    tracked threshold: a dip of the floor looks like a rise, and the onset is missed)."""
    from scipy.optimize import brentq

    from rocking.models.regimes import EventKind, Regime

    tan_alpha = 0.2 / 1.2
    push = 0.9 * rk.g * tan_alpha
    dip = rk.RickerPulse(amplitude=-(rk.g - push * (1.0 - 1e-3) / tan_alpha), frequency=2.0)
    motion = _PushedWhileTheFloorDips(amplitude=push, width=2.0, dip=dip)
    r = rk.simulate(rk.System(statue=_SLENDER), motion)

    def threshold_margin(t):
        return (rk.g + dip.acceleration(np.array([t]))[0]) * tan_alpha - push

    onset = brentq(threshold_margin, 0.6, dip.t0, xtol=1e-14)
    assert 0.005 < dip.t0 - onset < 0.015
    assert r.events[0][:4] == (pytest.approx(onset, abs=1e-9), EventKind.UPLIFT, Regime.REST, Regime.ROCK)
    assert r.summary()["first_rocking_time"] == pytest.approx(onset, abs=1e-9)
    assert r.peak_rotation > 1e-7 and r.status == "completed"


def test_a_sliding_pedestal_whose_velocity_touches_zero_inside_one_step_stops_there():
    """In slide-rock the pedestal's acceleration does not depend on its own velocity (derivation
    §3.1: ü and θ̈ solve the 2×2 system with F = −σ·μk·N, in which u̇ does not appear), so a start
    slower by Δ shifts u̇(t) by −Δ and leaves θ(t) unchanged. A statue leaning at 0.05 rad on a
    pedestal sliding at 2 m/s (μs = μk = 0.2) under a 4 m/s², 3 Hz floor: u̇ has a local minimum
    v_min ≈ 1.44 m/s at t_min ≈ 0.145 s while the statue leans at 0.12 rad. Started slower by
    v_min + 1e-6 m/s, u̇ touches zero for a fraction of a millisecond: the slide must stop where
    the first run's u̇ equals v_min + 1e-6 (interpolated, to 1e-6 s), and with μs = μk the pedestal
    slides on at t_min, where the sliding acceleration changes sign (the held pedestal's friction
    demand reaches μs·N there). Both ends of that step see the pedestal sliding: only the guard
    σ·u̇ tracked at the step's stages finds the touch. Kills modes.py:85 (σ·θ tracked for σ·u̇)."""
    from rocking.models.regimes import EventKind, Regime

    pedestal = rk.Pedestal(mass=20.0, friction=rk.Friction(static=0.2, kinetic=0.2))
    system, floor = rk.System(statue=_SLENDER, pedestal=pedestal), rk.Harmonic(amplitude=4.0, frequency=3.0, cycles=2)
    kwargs = dict(initial_rotation=0.05, initial_angular_velocity=0.3, duration=0.19, options=rk.Options(save_dt=1e-5))
    fast = rk.simulate(system, floor, initial_sliding_velocity=2.0, **kwargs)
    assert fast.events == []
    window = (fast.t > 0.1) & (fast.t < 0.18)
    k = int(np.argmin(fast.u_dot[window]))
    t_min, v_min = fast.t[window][k], fast.u_dot[window][k]
    assert fast.theta[window][k] > 0.1

    slow = rk.simulate(system, floor, initial_sliding_velocity=2.0 - v_min - 1e-6, **kwargs)
    falling = window & (fast.t <= t_min)
    t_touch = np.interp(-(v_min + 1e-6), -fast.u_dot[falling], fast.t[falling])
    stop, slip = slow.events
    assert (stop.kind, stop.before, stop.after) == (EventKind.STOP, Regime.SLIDE_ROCK, Regime.ROCK)
    assert stop.time == pytest.approx(t_touch, abs=1e-6) and 1e-4 < t_min - stop.time < 1e-3
    assert (slip.kind, slip.after) == (EventKind.SLIP, Regime.SLIDE_ROCK)
    assert slip.time == pytest.approx(t_min, abs=2e-5)
    before = slow.t < stop.time
    np.testing.assert_allclose(slow.theta[before], fast.theta[: before.sum()], atol=1e-11)


def test_a_statue_whose_tan_alpha_equals_the_floor_friction_lifts_and_slips_at_the_same_instant():
    """A statue with b/h = 1/4 on a pedestal with μs = 1/4 (μk = 0.2) under a ramp a_g = 3·t m/s²
    (for 1 s): the rocking threshold g·tan α and the friction cone μs·g are reached together, at
    t₀ = g/4/3. The uplift is found first; the pedestal slips at the same instant, and then it
    slides with the statue upright (its base feels μk·g < g·tan α), so no rocking is entered and
    no instant is inconsistent: at the uplift, rocking starts with s·θ̈ = 0 to rounding, which the
    tolerance for a just-crossed threshold accepts. The slide stops where u̇ = ∫(−a_g + μk·g) dt
    returns to zero: t = 1 + |u̇(1)|/(μk·g) with u̇(1) = −1.5·(1 − t₀²) + μk·g·(1 − t₀). Kills
    modes.py:171 (`not forbid_rest`: the strict test applied right after the uplift, which flags
    this onset as inconsistent)."""
    from rocking.models.regimes import EventKind, Regime

    statue = rk.Statue(width=0.5, height=2.0, mass=50.0, restitution=0.8)
    pedestal = rk.Pedestal(mass=20.0, friction=rk.Friction(static=0.25, kinetic=0.2))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Ramp(rate=3.0, end=1.0), duration=1.5)
    t0 = rk.g * 0.25 / 3.0
    u_dot_1 = -1.5 * (1.0 - t0**2) + 0.2 * rk.g * (1.0 - t0)
    uplift, slip, stop = r.events
    assert (uplift.kind, uplift.before, uplift.after) == (EventKind.UPLIFT, Regime.REST, Regime.ROCK)
    assert (slip.kind, slip.before, slip.after) == (EventKind.SLIP, Regime.ROCK, Regime.SLIDE)
    assert uplift.time == slip.time == pytest.approx(t0, abs=1e-9)
    assert (stop.kind, stop.after) == (EventKind.STOP, Regime.REST)
    assert stop.time == pytest.approx(1.0 - u_dot_1 / (0.2 * rk.g), abs=1e-9)
    assert r.peak_rotation == 0.0 and r.summary()["first_rocking_time"] is None
    assert not [w for w in r.warnings if "strictly consistent" in w], r.warnings


def test_a_block_whose_tan_alpha_equals_its_friction_slides_upright_from_the_common_onset():
    """A block alone with b/h = 0.1 and μs = 0.1 (μk = 0.08) under a ramp a_g = −2·t m/s² (for
    1.5 s): the rocking threshold and the friction cone are reached together at t₀ = μs·g/2. The
    events say what happens there: the uplift is found first, and the base slips at the same
    instant, so the block slides without rocking (its base feels μk·g < g·tan α), until
    u̇ = ∫(−a_g − μk·g) dt returns to zero: u̇(1.5) = 1.5² − t₀² − μk·g·(1.5 − t₀), then
    t = 1.5 + u̇(1.5)/(μk·g). Kills modes.py:149 (`n_s = 2`: after the uplift the block is put back
    at rest, an "uplift" from rest to rest) and modes.py:171 (the tolerance after an uplift
    `−1.000000001·g/R`: slide-rock about to turn the wrong way, s·θ̈ ∝ μk·cos α − sin α < 0, is
    taken as the onset)."""
    from rocking.models.regimes import EventKind, Regime

    block = rk.Statue(width=0.2, height=2.0, mass=50.0, restitution=0.8, friction=rk.Friction(static=0.1, kinetic=0.08))
    r = rk.simulate(rk.System(statue=block), rk.Ramp(rate=-2.0, end=1.5), duration=4.0)
    t0, mu_k_g = rk.g * 0.1 / 2.0, 0.08 * rk.g
    u_dot = 1.5**2 - t0**2 - mu_k_g * (1.5 - t0)
    assert r.events == [
        (pytest.approx(t0, abs=1e-9), EventKind.UPLIFT, Regime.REST, Regime.ROCK),
        (pytest.approx(t0, abs=1e-9), EventKind.SLIP, Regime.ROCK, Regime.SLIDE),
        (pytest.approx(1.5 + u_dot / mu_k_g, abs=1e-9), EventKind.STOP, Regime.SLIDE, Regime.REST),
    ]
    assert r.peak_rotation == 0.0 and r.summary()["first_rocking_time"] is None


# ------------------------------------------------------------------------------------------------
# models/dynamics.py: the forces and the power of the floor along a run
# ------------------------------------------------------------------------------------------------

_TWO_COMPONENT_CASES = {
    # A slender statue that rocks on a held pedestal, then on a sliding one (REST, ROCK, SLIDE_ROCK).
    "rocks": (rk.Statue(width=0.4, height=2.0, mass=3.0, restitution=0.85),
              rk.Pedestal(mass=2.0, friction=rk.Friction(static=0.45, kinetic=0.35), width=0.6, height=0.8),
              (1.5, 5.5)),
    # A squat statue that never rocks: the stack slides as one body (REST, SLIDE).
    "slides": (rk.Statue(width=0.8, height=1.0, mass=3.0),
               rk.Pedestal(mass=2.0, friction=rk.Friction(static=0.3, kinetic=0.25), width=0.9, height=0.5),
               (1.5, 4.0)),
}


@functools.cache  # each case is read by two tests; the response is not modified
def _two_component_run(case):
    """A 3 kg statue on a 2 kg pedestal (masses ≠ 1, so that a `·M` written `/M` shows) under a
    record-like motion with a vertical component: 1.2 Hz horizontal, weaker then stronger, and a
    2 m/s², 3 Hz vertical, sampled every 0.01 s, for 4 s, then 2 s of stillness."""
    from rocking.excitation.record import GroundMotion

    statue, pedestal, (weak, strong) = _TWO_COMPONENT_CASES[case]
    t = np.round(np.arange(0.0, 6.0, 0.01), 10)
    horizontal = np.where(t < 2.5, weak, strong) * np.sin(2 * np.pi * 1.2 * t) * (t < 4.0)
    vertical = 2.0 * np.sin(2 * np.pi * 3.0 * t) * (t < 4.0)
    motion = GroundMotion(time=t, values=horizontal, vertical=vertical)
    system = rk.System(statue=statue, pedestal=pedestal)
    return rk.simulate(system, motion, options=rk.Options(gravity=9.81, save_dt=1e-3)), motion


def _signs_of_the_stretch(t, values, moving, tiny):
    """Per saved sample, the direction of a motion (a rotation θ, a sliding velocity u̇) read from
    the samples themselves: its sign where |value| > tiny; at a sample where it is ~0, the sign of
    the neighbour in the same stretch of motion: the previous sample for the one saved just
    before an event (its twin follows at the same time), else the next (the onset of the motion,
    or the sample just after an impact). 0 where the motion is off."""
    signs = np.where(np.abs(values) > tiny, np.sign(values), 0).astype(int)
    out = np.zeros(t.size, dtype=int)
    for i in np.flatnonzero(moving):
        if signs[i]:
            out[i] = signs[i]
            continue
        before_event = i + 1 < t.size and t[i + 1] == t[i]
        j = i - 1 if before_event else i + 1
        while 0 <= j < t.size and moving[j] and signs[j] == 0:
            j += -1 if before_event else 1
        assert 0 <= j < t.size and moving[j], f"no direction for the sample at t = {t[i]}"
        out[i] = signs[j]
    return out


@pytest.mark.parametrize(("case", "regimes"), [("rocks", {0, 1, 3}), ("slides", {0, 2})])
def test_contact_forces_along_a_run_match_the_sympy_derivation(case, regimes):
    """`Response.contact_forces()` (the floor's F and N, the force on the statue's base, the floor
    pressure centre x_N under the pedestal) at every saved sample, against the sympy derivation
    (`tests/oracles/lagrange.py`: the regime's accelerations and forces; x_N by the pedestal's
    moment balance), to 1e-9 relative: both evaluate closed forms at the same state, so they
    differ by rounding. Kills dynamics.py:71 (F = M(a − ü) for a sliding statue at rest) and the
    mutants of `pressure_centre` at dynamics.py:162 (`s/B`, `B/Py`, `·n`, `1.5·h1`, `0.5/h1`,
    `a − ü`). Every sample is checked, the onsets of rocking (θ = θ̇ = 0) and of sliding (u̇ = 0)
    and the samples where θ crossed zero by rounding before an impact included: the test reads
    the pivot and the sliding direction from the neighbouring samples of the same stretch
    (`_signs_of_the_stretch`). Before the solver saved them, `contact_forces()` guessed them from
    the signs at the sample and gave there the forces of rest or of the other pivot."""
    from oracles import lagrange
    from oracles.energy import lagrange_params

    r, motion = _two_component_run(case)
    assert set(np.unique(r.regime)) == regimes
    forces = r.contact_forces()
    params = lagrange_params(r.system, 9.81)
    a_g, a_v = motion.acceleration(r.t), motion.vertical_acceleration(r.t)
    names = {0: "stick-rest", 1: "stick-rock", 2: "slide-rest", 3: "slide-rock"}
    pivots = _signs_of_the_stretch(r.t, r.theta, (r.regime & 1) != 0, 1e-9)
    slips = _signs_of_the_stretch(r.t, r.u_dot, (r.regime & 2) != 0, 1e-12)
    scale = params["g"] * (params["m1"] + params["m2"])
    for i in range(r.t.size):
        code = int(r.regime[i])
        s = int(pivots[i]) if code & 1 else None
        sigma = int(slips[i]) if code & 2 else None
        udd, _, n, f, px, py = lagrange.accelerations(names[code], params, r.state[i], a_g[i], a_v[i], s=s, sigma=sigma)
        for key, value in (("F", f), ("N", n), ("Px", px), ("Py", py)):
            assert forces[key][i] == pytest.approx(value, rel=1e-9, abs=1e-12 * scale), (key, r.t[i])
        # (while the statue rests, s is None: its reaction acts where its own moment balance puts
        # it; until 2026-12-06 x_N was NaN there, and the formula read at s = 0 left that out)
        x_n = lagrange.pedestal_center_of_pressure(params, r.system.pedestal.height, s, px, py, n, a_g[i] + udd)
        assert forces["x_N"][i] == pytest.approx(x_n, rel=1e-9, abs=1e-12), r.t[i]


@pytest.mark.parametrize("case", ["rocks", "slides"])
def test_energy_ledger_under_vertical_motion_matches_the_one_computed_from_the_samples(case):
    """The solver's input work and friction dissipation against the ledger computed here from the
    saved samples with the sympy derivation's energy and power (`tests/oracles/energy.py`), under
    a floor that also moves vertically, with masses ≠ 1: to 1e-7 relative. The ledger's
    quadrature errs by ~1e-10 of the energies on 1 ms samples, but a stretch of fewer than four
    samples is integrated by a trapezoid: the last slide of "slides" ends 0.66 ms after a record
    sample, and that trapezoid errs by 1.6e-8 of the energies (measured). Kills dynamics.py:91
    (P_in = −a·u̇/M for a statue at rest) and dynamics.py:94 (the vertical power of a rocking
    statue with its sign flipped), and dynamics.py:169 below."""
    from oracles import energy

    r, motion = _two_component_run(case)
    led = energy.ledger(r.t, r.state, r.regime, energy.lagrange_params(r.system, 9.81), motion.acceleration,
                        motion.vertical_acceleration, motion.breakpoints)
    assert np.max(np.abs(led.residual)) <= 1e-7 * led.scale
    e = r.energy
    assert led.friction[-1] > 0.01 * led.scale
    np.testing.assert_allclose([e["input_work"], e["friction_dissipation"], e["impact_dissipation"]],
                               [led.input_work[-1], led.friction[-1], led.jumps[-1]], rtol=1e-7, atol=1e-12 * led.scale)
    # and the solver's own running balance closes (1e-11 measured): kills dynamics.py:169
    # (the kinetic energy 0.5·u̇²/M of a statue at rest on a sliding pedestal)
    assert e["relative_balance_error"] < 1e-9


def test_floor_pressure_centre_without_a_normal_force_is_undefined():
    """x_N = moment / N is undefined, NaN, where the floor's normal force is not positive; with
    N = 0 exactly, dynamics.py:159 `n < 0.0` divides by zero (and raises, under numba's
    Python error model). The uplift check and `contact_forces()` rely on the NaN."""
    from rocking.models.dynamics import pressure_centre
    from rocking.models.parameters import pack

    statue = rk.Statue(width=0.4, height=2.0, mass=3.0)
    pedestal = rk.Pedestal(mass=2.0, friction=rk.Friction(static=0.5), width=0.6, height=0.8)
    p = pack(rk.System(statue=statue, pedestal=pedestal), gravity=9.81, normal_force="full", impact="coulomb",
             rest_velocity=1e-6)
    assert math.isnan(pressure_centre(p, 1, 2.0, 0.0, 5.0, 20.0, 0.0))
    assert math.isnan(pressure_centre(p, -1, 2.0, 0.0, 5.0, 20.0, -3.0))
    assert pressure_centre(p, 1, 2.0, 0.0, 5.0, 20.0, 49.0) == pytest.approx(
        (0.2 * 20.0 - 0.8 * 5.0 - 0.5 * 0.8 * 2.0 * 2.0) / 49.0, rel=1e-14)


def test_energies_of_a_statue_at_rest_are_those_of_the_stack_sliding_as_one():
    """With the statue at rest (s = 0) the kinetic energy is ½·(m1 + m2)·u̇², and so is the
    mechanical energy (V = 0 upright). Kills dynamics.py:178 (`0.5 / M`; the solver itself
    never asks `kinetic_energy` for s = 0, so only a direct call sees it) and dynamics.py:169."""
    from rocking.models.dynamics import kinetic_energy, mechanical_energy
    from rocking.models.parameters import pack

    statue = rk.Statue(width=0.4, height=2.0, mass=3.0)
    pedestal = rk.Pedestal(mass=2.0, friction=rk.Friction(static=0.5))
    p = pack(rk.System(statue=statue, pedestal=pedestal), gravity=9.81, normal_force="full", impact="coulomb",
             rest_velocity=1e-6)
    assert kinetic_energy(p, 0, 0.7, 0.0, 0.0) == pytest.approx(0.5 * 5.0 * 0.49, rel=1e-15)
    assert mechanical_energy(p, 0, -0.7, 0.0, 0.0) == pytest.approx(0.5 * 5.0 * 0.49, rel=1e-15)


def test_floor_pressure_centre_under_a_light_pedestal_is_defined():
    """x_N is undefined only where the floor's normal force is not positive. A 50 g statue on a
    20 g pedestal has N ≈ 0.7 N: dynamics.py:159 (`n <= 1.0`) reports NaN there, and the uplift
    check goes blind. The same pressure centre as the sympy moment balance, to 1e-9."""
    from oracles import lagrange
    from oracles.energy import lagrange_params

    statue = rk.Statue(width=0.04, height=0.2, mass=0.05)
    pedestal = rk.Pedestal(mass=0.02, friction=rk.Friction(static=2.0, kinetic=2.0), width=0.06, height=0.05)
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2),
                    options=rk.Options(gravity=9.81))
    forces = r.contact_forces()
    rocking = np.flatnonzero(r.regime == 1)
    assert rocking.size > 10 and np.all(forces["N"][rocking] < 1.0)
    params = lagrange_params(r.system, 9.81)
    pivots = _signs_of_the_stretch(r.t, r.theta, r.regime == 1, 1e-9)
    for i in rocking[:: max(1, rocking.size // 20)]:
        s = int(pivots[i])
        udd, _, n, _, px, py = lagrange.accelerations("stick-rock", params, r.state[i], r.floor_acceleration[i], 0.0, s=s)
        x_n = lagrange.pedestal_center_of_pressure(params, 0.05, s, px, py, n, r.floor_acceleration[i] + udd)
        assert forces["x_N"][i] == pytest.approx(x_n, rel=1e-9, abs=1e-12)


# ------------------------------------------------------------------------------------------------
# excitation/signal.py: the compiled evaluator at the ends of its domain, and the band exits
# ------------------------------------------------------------------------------------------------

_ANALYTIC_MOTIONS = {
    "harmonic cos": rk.Harmonic(amplitude=2.0, frequency=1.5, cycles=2),
    "harmonic sin": rk.Harmonic(amplitude=2.0, frequency=1.5, cycles=1.25, form="sin"),
    "sine pulse": rk.SinePulse(amplitude=2.0, frequency=2.0, phase=0.4),
    "cosine pulse": rk.CosinePulse(amplitude=2.0, frequency=2.0),
    "rectangle": rk.RectanglePulse(amplitude=2.0, width=0.3),
    "Ricker": rk.RickerPulse(amplitude=2.0, frequency=2.0, center=0.1),  # cut off while still 0.28 m/s²
    "ramp": rk.Ramp(rate=1.5, end=0.8),
}


@pytest.mark.parametrize("name", list(_ANALYTIC_MOTIONS))
def test_the_local_form_of_an_analytic_signal_holds_at_both_ends_of_the_motion(name):
    """`localise` on the side of t = 0 and of t = t_end gives the formula `evaluate` gives there
    (a motion is on over its closed interval, as `acceleration` says: see the pulse tests above).
    Kills signal.py:78 `piece <= 0` and `piece >= params[3]` (zero at the start, or at the end),
    and `kind < 0 and piece < 0` (the formula before the motion starts)."""
    from rocking.excitation.signal import evaluate, local_value, localise

    motion = _ANALYTIC_MOTIONS[name]
    sig = motion.signal()
    t_end = float(sig.params[3])
    assert t_end == pytest.approx(motion.duration, rel=1e-15)
    for t in (0.0, t_end):
        expected = float(motion.acceleration(np.array([t]))[0])
        if name == "rectangle" and t == t_end:
            # The one motion that jumps at its end. `acceleration` is 0 from t_d on; the compiled
            # side with `piece = t_d` takes the pulse's side of the jump. The solver never asks
            # (its `piece` is strictly inside a step, and t_d is a breakpoint), so both hold.
            expected = 2.0
        assert evaluate(sig.kind, sig.params, sig.time, sig.values, t, t) == pytest.approx(expected, rel=1e-14, abs=1e-15)
        loc = localise(sig.kind, sig.params, sig.time, sig.values, t)
        assert local_value(loc, 0, t) == pytest.approx(expected, rel=1e-14, abs=1e-15), t
    # and nothing before the motion starts (signal.py:78 `kind < 0 and piece < 0.0 or …`)
    loc = localise(sig.kind, sig.params, sig.time, sig.values, -0.01)
    assert local_value(loc, 0, -0.01) == 0.0
    assert evaluate(sig.kind, sig.params, sig.time, sig.values, -0.01, -0.01) == 0.0
    # Not a vacuous check: each motion is clearly non-zero at one end at least.
    assert max(abs(float(v)) for v in motion.acceleration(np.array([0.0, t_end]))) > 0.1


def test_a_sampled_signal_at_its_last_sample_is_its_last_value():
    """At the last sample time, searchsorted lands past the last interval; both evaluators step
    back to it; at the first, they take the first interval. Kills signal.py:38 (`i = n + 2`), :74 (`i >= n + 1`, `i > n − 1`): each reads
    past the end of the arrays."""
    from rocking.excitation.signal import evaluate, local_value, localise

    t = np.array([0.0, 0.01, 0.02, 0.03])
    values = np.array([0.5, 1.0, -2.0, 3.0])
    from rocking.excitation.record import GroundMotion

    sig = GroundMotion(time=t, values=values).signal()
    assert evaluate(sig.kind, sig.params, sig.time, sig.values, 0.03, 0.03) == 3.0
    # the side of the last sample is the last interval, wherever t is (signal.py:37, where
    # `i >= n + 1` or `i > n − 1` take interval n − 1, past the end, and get t = 0.03 right only
    # because its weight is 0 there)
    assert evaluate(sig.kind, sig.params, sig.time, sig.values, 0.025, 0.03) == pytest.approx(0.5, rel=1e-14)
    # and nothing outside the record (signal.py:35, `return 1.0` there)
    assert evaluate(sig.kind, sig.params, sig.time, sig.values, 0.05, 0.05) == 0.0
    assert evaluate(sig.kind, sig.params, sig.time, sig.values, -0.01, -0.01) == 0.0
    loc = localise(sig.kind, sig.params, sig.time, sig.values, 0.03)
    assert loc[0] == 1.0 and loc[1] == -2.0 and loc[3] == 0.02
    assert loc[2] == pytest.approx(500.0, rel=1e-14)
    assert local_value(loc, 0, 0.03) == pytest.approx(3.0, rel=1e-15)
    # and at the first sample, the first interval (signal.py:71 `piece <= times[0]` gives 0)
    first = localise(sig.kind, sig.params, sig.time, sig.values, 0.0)
    assert local_value(first, 0, 0.0) == 0.5 and evaluate(sig.kind, sig.params, sig.time, sig.values, 0.0, 0.0) == 0.5


def test_cosine_band_exit_when_the_crest_only_touches_the_band_edge():
    """A·cos that reaches the edge of the band only at its crest (A = hi, or −A = lo) still
    leaves the band there (the band is open: strictly inside). The exit is the crest, short by
    the 1e-6 rad phase margin. Kills signal.py:124 (`A <= hi and …`, which says it never
    leaves) and :137 (`−A < lo`, which misses the trough)."""
    from rocking.excitation.signal import cosine_band_exit

    omega = 2.0 * math.pi
    # Phase π/2 at t = 0: the crest comes at ψ = 2π (t = 0.75 s), the trough at ψ = π (0.25 s).
    crest = cosine_band_exit(2.0, omega, 0.5 * math.pi, 0.0, 10.0, -5.0, 2.0)
    assert crest == pytest.approx(0.75 - 1e-6 / omega, abs=1e-12)
    trough = cosine_band_exit(2.0, omega, 0.5 * math.pi, 0.0, 10.0, -2.0, 5.0)
    assert trough == pytest.approx(0.25 - 1e-6 / omega, abs=1e-12)
    assert cosine_band_exit(2.0, omega, 0.5 * math.pi, 0.0, 10.0, -2.0 - 1e-9, 2.0 + 1e-9) == 10.0
    # and no frequency, no exit to compute: t (signal.py:118 `omega < 0.0` divides by it)
    assert cosine_band_exit(2.0, 0.0, 0.5 * math.pi, 0.0, 10.0, -5.0, 1.0) == 0.0


def test_cosine_band_exit_starting_on_the_band_edge_is_now():
    """A·cos starting exactly on the lower edge (rising through it) is not strictly inside the
    band: the exit is now. Kills signal.py:122 (`lo <= now`), which then waits for the next
    downward exit, a period later."""
    from rocking.excitation.signal import cosine_band_exit

    lo = 2.0 * math.cos(4.0)  # at ψ = 4 rad, 2·cos ψ is rising (sin 4 < 0)
    assert cosine_band_exit(2.0, 1.0, 4.0, 0.0, 100.0, lo, 5.0) == 0.0
    hi = 2.0 * math.cos(1.0)  # falling through the upper edge
    assert cosine_band_exit(2.0, 1.0, 1.0, 0.0, 100.0, -5.0, hi) == 0.0


def test_cosine_band_exit_exactly_on_the_exit_phase_is_now():
    """Started exactly on the phase where the band is left (upwards: ψ = 2π − β with
    β = arccos(hi/A); downwards: ψ = γ with γ = arccos(lo/A)) while A·cos ψ rounds to just inside
    the band: the exit is now, not a period later. Kills signal.py:140 (`while start <= r` in the
    downward branch), and its twin in the upward branch. β, γ and the cosine are computed by
    compiled code, as in the function, so that the tie is exact to the bit."""
    from numba import njit

    from rocking.excitation.signal import cosine_band_exit

    acos, cos = njit(lambda x: math.acos(x)), njit(lambda x: math.cos(x))
    up = down = 0
    for edge in np.linspace(0.1, 0.9, 2001):
        beta = acos(edge)
        if cos(-beta) < edge:  # upper edge hi = edge, at ψ = −β ≡ 2π − β
            up += 1
            assert cosine_band_exit(1.0, 1.0, -beta, 0.0, 100.0, -1.5, edge) == 0.0, edge
        gamma = acos(-edge)
        if cos(gamma) > -edge:  # lower edge lo = −edge, at ψ = γ
            down += 1
            assert cosine_band_exit(1.0, 1.0, gamma, 0.0, 100.0, -edge, 1.5) == 0.0, edge
    assert up > 10 and down > 10

# ------------------------------------------------------------------------------------------------
# excitation/signal.py, ninth round


def _harmonic_on_a_sinking_floor(amplitude, omega, sink, end):
    """a_h = A·sin(ω t) and a_v = −``sink`` (the floor accelerating downwards) for 0 ≤ t ≤ end: a
    motion of the user's own (rk.excitation.base.AbstractMotion), since none of the library's pairs
    a harmonic with a vertical component."""
    from rocking.excitation.base import KIND_HARMONIC, KIND_RECTANGLE, AbstractMotion, Signal

    class Motion(AbstractMotion):
        duration = end

        def acceleration(self, t):
            t = np.asarray(t, dtype=float)
            return np.where((t >= 0) & (t <= end), amplitude * np.sin(omega * t), 0.0)

        def signal(self):
            return Signal(KIND_HARMONIC, np.array([amplitude, omega, -0.5 * math.pi, end]), np.zeros(0), np.zeros(0))

        def vertical_signal(self):
            return Signal(KIND_RECTANGLE, np.array([-sink, end, 0.0, end]), np.zeros(0), np.zeros(0))

        def vertical_acceleration(self, t):
            t = np.asarray(t, dtype=float)
            return np.where((t >= 0) & (t < end), -sink, 0.0)

    return Motion()


def test_a_harmonic_on_a_sinking_floor_starts_the_rocking_at_the_lowered_threshold():
    """A block at rest under a_h = A sin ωt on a floor sinking at c = g/2: rocking starts where
    |a_h| = (g − c)·tan α (Housner's threshold under the apparent gravity), t* = asin((g − c) tan α /
    A)/ω, although A < g tan α. Kills signal.py:56 LOCAL_ZERO = 1.0 (the solver then takes a
    vertical that is linear in time for none, and crosses the rest under the harmonic with the
    band of the still floor, where the block never rocks)."""
    g = 9.81
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    A, omega, sink = 1.8, 2.0, 0.5 * g
    assert (g - sink) * 0.25 < A < g * 0.25
    r = rk.simulate(rk.System(statue=statue), _harmonic_on_a_sinking_floor(A, omega, sink, 2.0),
                    options=rk.Options(gravity=g), save=False).summary()
    t_star = math.asin((g - sink) * 0.25 / A) / omega
    assert r["first_rocking_time"] == pytest.approx(t_star, rel=1e-9)


def test_the_zero_signal_is_zero_at_every_time_including_its_start():
    """``evaluate`` of ``ZERO_SIGNAL`` (the vertical of every motion but a record with one): its
    parameters are zeros, so t = 0 lies inside its piece [0, 0] and runs past every kind's branch
    to the last return. Kills signal.py:50 `return 1.0`."""
    from rocking.excitation.base import ZERO_SIGNAL
    from rocking.excitation.signal import evaluate, local_value, localise

    z = ZERO_SIGNAL
    for t in (-1.0, 0.0, 1e-300, 0.5, 10.0):
        assert evaluate(z.kind, z.params, z.time, z.values, t, t) == 0.0
        assert local_value(localise(z.kind, z.params, z.time, z.values, t), 0, t) == 0.0


# ------------------------------------------------------------------------------------------------
# excitation/base.py


def test_a_motion_of_the_users_own_has_its_ends_as_breakpoints_and_its_sampled_peak_as_pga():
    """What ``AbstractMotion`` gives a subclass that defines only the four required members: the
    breakpoints are the motion's start and end, and ``pga`` is the largest |a_g| over 20 001
    samples of [0, duration]. a_h = A sin 2t on [0, 2] s peaks at t = π/4; the nearest sample is
    within 5e-5 s of it, so the sampled peak is A to 5e-9 (relative). Kills base.py:73 (the first
    breakpoint at 1 s) and base.py:78 (sampling from t = 1 s, where the peak is A sin 2 = 0.91 A)."""
    motion = _harmonic_on_a_sinking_floor(1.8, 2.0, 0.0, 2.0)
    np.testing.assert_array_equal(motion.breakpoints, [0.0, 2.0])
    assert motion.pga == pytest.approx(1.8, rel=5e-9)


# ------------------------------------------------------------------------------------------------
# solver/compiled.py


def test_a_light_rocking_stack_raises_no_warning_of_a_vanishing_normal_force():
    """A 20 g statue rocking on a 20 g pedestal that slides, under 3.5 m/s²: the floor pushes with
    about 0.4 N, never 0, and nothing warns. The check (made while the statue rocks) is N ≤ 0 in
    newtons; a threshold of 1 N (kills compiled.py:809 `n_full <= 1.0`) warned "the floor normal
    force reached zero" from the first rocking instant, 0.249 s."""
    statue = rk.Statue(width=0.3, height=1.2, mass=0.02)
    pedestal = rk.Pedestal(mass=0.02, friction=rk.Friction(static=0.3, kinetic=0.25))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=3.5, frequency=1.5, cycles=3))
    summary = r.summary()
    assert summary["first_sliding_time"] == 0.0 and summary["first_rocking_time"] == pytest.approx(0.249, abs=1e-3)
    assert r.warnings == []


def test_the_required_top_friction_covers_the_instant_after_an_impact():
    """A statue (0.3 × 1.2 m) rocking on a pedestal held by μs = 0.5 under 6 m/s²: right after its
    first impact (t = 0.3471 s) the statue's base needs |Px|/Py = 0.3380, the largest of the whole
    run, at an instant no integration stage sees (the next step starts from it). The summary's
    required_top_friction must be at least every saved rocking sample's ratio (Response.contact_forces,
    checked against the sympy derivation), the sample saved just before each event (θ crossed zero
    there by rounding, 8e-12 rad) and the onset (θ = θ̇ = 0) included: contact_forces reads the
    pivot the solver saved, not the sign of θ (it gave the other side's ratio at the first, and
    the forces of rest, |Px|/Py = a/g = 0.61, at the second). Kills compiled.py:805 `py <= 0.0`
    (the summary then said 0.3352)."""
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=0.5, kinetic=0.4))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=6.0, frequency=1.5, cycles=3),
                    options=rk.Options(save_dt=0.002))
    forces = r.contact_forces()
    theta = np.asarray(r.theta)
    assert np.any((theta == 0.0) & (np.asarray(r.theta_dot) == 0.0) & (r.regime == 1))  # the onset is in
    rocking = np.asarray(r.regime_codes) == 1
    ok = rocking & (np.abs(theta) <= r.alpha) & (forces["Py"] > 0)
    sampled = float(np.max(forces["top_friction_ratio"][ok]))
    assert sampled == pytest.approx(0.3380, abs=1e-4)
    assert r.summary()["required_top_friction"] >= sampled * (1 - 1e-12)


def test_the_required_top_friction_of_a_statue_that_overturns_stops_at_alpha():
    """The required top friction is a design quantity while the statue can still come back,
    |θ| ≤ α (README, summary keys); the statue toppling past α needs far more (|Px|/Py = 45 at
    the fall, θ = π/2, in this run). Under a record sampled every 0.01 s the steps are short
    and the fall is read off the dense output: the summary must still equal the largest ratio of
    the saved samples with |θ| ≤ α (contact_forces, every 1 ms; samples and integration stages
    see slightly different instants, hence 1e-5). Kills compiled.py:741 `py > 0.0 or |θ| ≤ α`
    at an event's instant (the summary then said 45.07 in place of 0.2607)."""
    from rocking.excitation.record import GroundMotion

    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=0.5, kinetic=0.4))
    t = np.round(np.arange(0.0, 4.0, 0.01), 10)
    record = GroundMotion(time=t, values=3.0 * np.sin(2 * np.pi * 0.5 * t))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), record, options=rk.Options(save_dt=1e-3))
    assert r.overturned
    forces = r.contact_forces()
    assert forces["top_friction_ratio"][-1] > 10.0  # the fall itself
    upright = ((r.regime & 1) != 0) & (np.abs(r.theta) <= r.alpha) & (forces["Py"] > 0)
    sampled = float(np.max(forces["top_friction_ratio"][upright]))
    assert sampled == pytest.approx(0.2607, abs=1e-4)
    assert r.summary()["required_top_friction"] == pytest.approx(sampled, rel=1e-5)


@pytest.mark.parametrize("case", ["alone, harmonic", "alone, high frequency", "on a pedestal, record"])
def test_the_peak_rotation_is_the_same_without_saved_samples_and_is_the_largest_sampled(case):
    """Batch runs (spectra, fragility, design) save no samples, and the solver then builds a
    step's dense output only where something needs it. The peak |θ| inside a step, where θ̇
    changes sign, must still be found: the summary's peak_rotation with save=False must equal
    the one with samples (the steps are the same: 1e-12), and both the largest |θ| of samples
    every 0.1 ms (a turning point is at most 50 µs from a sample: |θ̈|·(50 µs)²/2 < 1e-7 rad).
    Kills compiled.py:618 `y[3] > 1.0` (a turning point of a step that starts with
    0 < θ̇ ≤ 1 rad/s missed without samples: 0.020306 in place of 0.020458 rad)."""
    from rocking.excitation.record import GroundMotion

    g = 9.81
    statue = rk.Statue(width=0.4, height=2.0, mass=50.0, restitution=0.9)
    t = np.round(np.arange(0.0, 6.0, 0.01), 10)
    system, motion = {
        "alone, harmonic": (rk.System(statue=statue), rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4)),
        "alone, high frequency": (rk.System(statue=statue), rk.Harmonic(amplitude=0.25 * g, frequency=3.0, cycles=4)),
        "on a pedestal, record": (
            rk.System(statue=statue, pedestal=rk.Pedestal(mass=40.0, friction=rk.Friction(static=0.3, kinetic=0.25))),
            GroundMotion(time=t, values=2.5 * np.sin(2 * np.pi * 1.2 * t) * (t < 4.0))),
    }[case]
    sampled = rk.simulate(system, motion, options=rk.Options(save_dt=1e-4))
    bare = rk.simulate(system, motion, save=False)
    assert sampled.status == bare.status == "completed"
    peak = sampled.summary()["peak_rotation"]
    assert 0.01 < peak < sampled.alpha
    assert bare.summary()["peak_rotation"] == pytest.approx(peak, rel=1e-12)
    assert peak == pytest.approx(float(np.max(np.abs(sampled.theta))), abs=1e-7)


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_statue_released_exactly_at_alpha_turning_outwards_exceeds_it_at_once_and_falls_on_time(side):
    """A statue alone on a still floor, released at θ = ±α (its balance point) turning outwards
    at 0.05 rad/s, falls. Its summary must say it passed α at t = 0: the guard α − |θ| starts on
    zero and is never positive, so no crossing of it is ever found (before the fix the summary
    said it never exceeded α, for a statue that fell; so did it for one released at rest beyond
    α). Released turning inwards, it rocks back and never passes α. The fall time is checked against free rocking about the corner:
    with φ = |θ| − α, φ̈ = p² sin φ (Housner; p² = 3g/(4R), R the half-diagonal), so the time
    from φ = 0 at φ̇ = w to φ = π/2 − α is ∫ dφ / √(w² + 2p²(1 − cos φ)) (scipy.quad; the
    solver's events are located to 1e-9 s, and its integration error over 1.9 s is below 1e-7 s:
    1e-6 s is the tolerance)."""
    from scipy.integrate import quad

    b, h, w = 0.4, 2.0, 0.05
    statue = rk.Statue(width=b, height=h, mass=50.0)
    alpha = math.atan(b / h)
    floor = rk.Harmonic(amplitude=0.0, frequency=1.0, cycles=3)
    out = rk.simulate(rk.System(statue=statue), floor, initial_rotation=side * alpha,
                      initial_angular_velocity=side * w).summary()
    assert out["overturned"] and out["exceeded_alpha_time"] == 0.0
    p2 = 3.0 * 9.80665 / (4.0 * 0.5 * math.hypot(b, h))
    t_fall, _ = quad(lambda phi: 1.0 / math.sqrt(w * w + 2.0 * p2 * (1.0 - math.cos(phi))), 0.0,
                     0.5 * math.pi - alpha, epsabs=1e-13, epsrel=1e-13)
    assert t_fall == pytest.approx(1.8746, abs=1e-3)
    assert out["overturn_time"] == pytest.approx(t_fall, abs=1e-6)
    t_fall_outwards = t_fall
    back = rk.simulate(rk.System(statue=statue), floor, initial_rotation=side * alpha,
                       initial_angular_velocity=-side * w).summary()
    assert not back["overturned"] and back["exceeded_alpha_time"] is None
    assert back["peak_rotation"] == pytest.approx(alpha, rel=1e-12)
    # released at rest beyond α: the same, from φ0 = 0.1 α, ∫ dφ / √(2p²(cos φ0 − cos φ)),
    # with φ = φ0 + v² (dφ = 2v dv) to take away the start's 1/√ singularity, and the
    # difference of cosines as a product (no cancellation near the start)
    phi0 = 0.1 * alpha
    beyond = rk.simulate(rk.System(statue=statue), floor, initial_rotation=side * 1.1 * alpha).summary()
    t_fall, _ = quad(lambda v: 2.0 * v / math.sqrt(4.0 * p2 * math.sin(phi0 + 0.5 * v * v) * math.sin(0.5 * v * v)), 0.0,
                     math.sqrt(0.5 * math.pi - alpha - phi0), epsabs=1e-13, epsrel=1e-13)
    assert beyond["overturned"] and beyond["exceeded_alpha_time"] == 0.0
    assert beyond["overturn_time"] == pytest.approx(t_fall, abs=1e-6)
    # the SciPy integrator cross-check keeps the same books
    from rocking.solver.crosscheck import simulate_crosscheck

    cross = simulate_crosscheck(rk.System(statue=statue), floor, duration=3.0, initial_rotation=side * alpha,
                                initial_angular_velocity=side * w, save=False)
    assert cross["exceeded_alpha_time"] == 0.0 and cross["overturn_time"] == pytest.approx(t_fall_outwards, abs=1e-6)


@pytest.mark.parametrize("case", ["statue alone, rectangle pulse", "statue on its pedestal, the paper's harmonic"])
def test_a_floor_motion_that_jumps_at_the_start_starts_the_run_in_the_regime_after_the_jump(case):
    """Pulses and the cos-form harmonic jump at t = 0 (to A at 0⁺). The run starts in the regime
    consistent with the floor at 0⁺, as docs/paper-case-studies.md reads the paper's cases ("the
    pedestal slides at once"): the first saved sample carries that regime, the summary's first
    rocking or sliding time is 0, and the event log holds no transition at t = 0 (there is no
    earlier regime to leave: the motion and the run begin together). (Written for mutant
    d42f7435, `breakpoints[ib] < t` at the start, which it does not kill: the run starts at
    t = 0 and every breakpoint passed to the solver is > 0, so that mutant is equivalent. The
    claim stands on its own: a run that began at rest and left it by an event at t = 0 would
    fail here.)"""
    g = 9.80665
    if case == "statue alone, rectangle pulse":
        # b/h = 0.2 and a pulse of 0.25 g: beyond g·tan α at once, and no friction to slide
        system = rk.System(statue=rk.Statue(width=0.4, height=2.0, mass=50.0))
        motion, expected = rk.RectanglePulse(amplitude=-0.25 * g, width=0.3), rk.Regime.ROCK
    else:
        # 6.75 m/s² > μs·g = 3.92 m/s²: the pedestal slides at once, and the statue (b/h = 1/4)
        # rocks at once on it (paper case b)
        system = rk.System(statue=rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8),
                           pedestal=rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3)))
        motion, expected = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=1), rk.Regime.SLIDE_ROCK
    r = rk.simulate(system, motion, duration=1.0)
    assert r.t[0] == 0.0 and r.regime[0] == expected
    assert r.summary()["first_rocking_time"] == 0.0
    if expected == rk.Regime.SLIDE_ROCK:
        assert r.summary()["first_sliding_time"] == 0.0
    assert r.events and all(e.time > 0.0 for e in r.events)


def test_the_top_face_warning_comes_exactly_when_the_required_friction_passes_the_top_face_mu():
    """The statue's friction on its pedestal is only checked (the model holds it stuck): the
    warning "the statue would slip on the pedestal" must appear when, and only when, the largest
    required top friction (the summary's, over rocking and impacts) exceeds the top face's μs.
    Run with μs,top 0.1 % above and below that requirement, measured first with no top friction
    (which leaves the motion unchanged: the runs must agree to the bit). Kills compiled.py:785
    recording the warning at an impact that needs *less* than μs,top (`top <= μ`)."""
    def run(top):
        statue = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8, friction=top)
        system = rk.System(statue=statue, pedestal=rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3)))
        return rk.simulate(system, rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=3), save=False)

    free = run(None)
    need = free.summary()["required_top_friction"]
    assert free.summary()["impacts"] >= 2 and 0.3 < need < 2.0
    for factor, warned in ((1.001, False), (0.999, True)):
        r = run(rk.Friction(static=factor * need, kinetic=0.5 * need))
        assert r.summary()["peak_rotation"] == free.summary()["peak_rotation"]
        assert r.summary()["required_top_friction"] == need
        assert any("would slip on the pedestal" in w for w in r.warnings) == warned


@pytest.mark.parametrize("form", ["sin", "cos"])
def test_the_energy_scale_is_the_input_work_when_impacts_dissipate_it(form):
    """The relative balance error is |E − E0 − W + D + D_impact| over the run's largest |E − E0|,
    |W| or |D| (docs/verdicts.md). A block rocking through ten cycles of a harmonic loses at its
    ~45 impacts nearly all the work the floor puts in, so |W| (3.7–5.7 J) sets the scale, more
    than 5× the largest |E − E0|. The scale the summary implies (balance error / relative error)
    against the ledger computed here from the 1 ms samples with the sympy energy
    (`tests/oracles/energy.py`). Under the sine form |W| is largest at the end of the run, a step
    end: the two agree to 1e-9 (4e-11 measured). Under the cos form it is largest inside a step,
    and the solver reads its scale at step ends and events only: 3.7e-4 below the samples'
    (measured), which changes a relative error of ~1e-10 by as much; so there the scale must lie
    within 1e-3 below the ledger's and never above it. The cos form also ends with a jump of the
    floor acceleration from 4 m/s² to 0 at a saved sample, where the ledger takes each side's own
    limit (until 2026-12-01 it used one value for both, and its own balance was 1.6e-4 off).
    Kills compiled.py:805 (the scale reading |D| in place of |W|, bench/MUTATION.md f2167f0b)."""
    from oracles import energy

    block = rk.Statue(width=0.4, height=1.6, mass=3.0, restitution=0.6)
    motion = rk.Harmonic(amplitude=4.0, frequency=2.0, cycles=10, form=form)
    r = rk.simulate(rk.System(statue=block), motion, options=rk.Options(gravity=9.81, save_dt=1e-3))
    led = energy.ledger(r.t, r.state, r.regime, energy.lagrange_params(r.system, 9.81), motion.acceleration,
                        motion.vertical_acceleration, motion.breakpoints)
    assert r.status == "completed" and r.summary()["impacts"] > 40
    assert np.max(np.abs(led.input_work)) > 5.0 * np.max(np.abs(led.energy - led.energy[0]))
    assert np.max(np.abs(led.residual)) <= 1e-9 * led.scale
    e = r.energy
    scale = e["balance_error"] / e["relative_balance_error"]
    assert led.scale * (1.0 - (1e-9 if form == "sin" else 1e-3)) <= scale <= led.scale * (1.0 + 1e-9)


def test_a_statue_released_tilted_and_turning_dissipates_its_initial_energy_and_reports_a_closed_balance():
    """A statue alone on a still floor, released at θ = 0.05 rad turning at θ̇ = 0.3 rad/s, rocks
    down to rest: its impacts dissipate exactly the energy it started with (sympy energy of the
    initial state, `tests/oracles/lagrange.py`), and the balance the summary reports,
    |E − E0 − W + D| over the energy scale, stays at the integration's accuracy (1e-9; 8e-11
    measured over 59 impacts). Kills compiled.py:502 (E0 with θ̇ for θ: the balance error then
    reads 0.23)."""
    from oracles import lagrange
    from oracles.energy import lagrange_params

    from helpers import NO_MOTION

    r = rk.simulate(rk.System(statue=_SLENDER), NO_MOTION, duration=20.0, initial_rotation=0.05,
                    initial_angular_velocity=0.3, options=rk.Options(gravity=9.81))
    assert r.status == "completed" and r.summary()["impacts"] > 5
    params = lagrange_params(r.system, 9.81)
    e0 = lagrange.energy(params, (0.0, 0.0, 0.05, 0.3)) - lagrange.energy(params, (0.0, 0.0, 0.0, 0.0), s=1)
    assert r.energy["impact_dissipation"] == pytest.approx(e0, rel=1e-9)
    assert r.energy["input_work"] == 0.0
    assert r.energy["relative_balance_error"] < 1e-9


@pytest.mark.parametrize(("theta0", "theta_dot0"), [(0.05, 0.0), (0.0, 0.4), (0.03, -0.2)])
def test_a_statue_released_on_either_side_moves_as_the_mirror_image(theta0, theta_dot0):
    """Mirror symmetry of the initial state: released at (−θ0, −θ̇0) on a pedestal that slides,
    under the mirrored floor motion (−a), the statue's θ, θ̇ and the pedestal's u, u̇ are the
    negatives of the run from (θ0, θ̇0) under a, at every sample, and the events happen at the same
    instants (1e-12: the two runs take mirrored steps, and every formula is odd or even in the
    signs). Kills compiled.py:496 (the initial pivot −2 for a statue leaning to −x: the
    equations of motion then read s = −2)."""
    statue = rk.Statue(width=0.4, height=2.0, mass=50.0)
    system = rk.System(statue=statue, pedestal=rk.Pedestal(mass=30.0, friction=rk.Friction(static=0.25, kinetic=0.2)))
    runs = [rk.simulate(system, rk.Harmonic(amplitude=sign * 6.0, frequency=1.5, cycles=2), duration=2.5,
                        initial_rotation=sign * theta0, initial_angular_velocity=sign * theta_dot0)
            for sign in (1.0, -1.0)]
    plus, minus = runs
    assert plus.summary()["impacts"] >= 1 and plus.summary()["peak_sliding"] > 1e-3
    assert plus.t.size == minus.t.size
    for column in range(4):  # u, u̇, θ, θ̇, each to 1e-12 of its own range
        scale = float(np.max(np.abs(plus.state[:, column])))
        np.testing.assert_allclose(minus.state[:, column], -plus.state[:, column], rtol=0, atol=1e-12 * scale)
    assert [e.time for e in minus.events] == pytest.approx([e.time for e in plus.events], abs=1e-12)


def test_a_narrow_pedestal_that_uplifts_from_the_start_is_warned_from_the_start():
    """A 0.5 m wide, 0.8 m tall pedestal held by friction under a statue, floor at 4 m/s² (cos form:
    the crest at t = 0). The floor's inertial force on the pedestal itself, ½·h1·m1·a in its moment
    balance, puts the pressure centre outside the base from the start: the saved samples (every
    0.1 ms, `violations()`, from contact_forces) show uplift from t = 0 to 0.0378 s. The warning
    must start inside that interval. Kills compiled.py:816 (the step end's floor acceleration read
    from the vertical's column, 0 here: the first warning then came at 0.3074 s, the second
    interval)."""
    statue = rk.Statue(width=0.3, height=1.5, mass=100.0)
    pedestal = rk.Pedestal(mass=100.0, width=0.5, height=0.8, friction=rk.Friction(static=2.0, kinetic=2.0))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=3),
                    options=rk.Options(save_dt=1e-4), duration=1.0)
    spans = [(t0, t1) for name, t0, t1 in r.violations() if name == "pedestal uplift"]
    assert spans[0][0] == 0.0 and spans[0][1] == pytest.approx(0.0378, abs=2e-4)
    said = [w for w in r.warnings if "pedestal would uplift" in w]
    t_warn = float(re.search(r"from t = ([0-9.]+) s", said[0]).group(1))
    assert t_warn <= spans[0][1]


def test_a_floor_dropping_faster_than_gravity_under_a_rocking_statue_is_warned_while_it_drops():
    """A statue rocking on a pedestal under a record whose vertical component drops to −12 m/s²
    (faster than g) from 0.99 s to 1.1 s: the floor's normal force and the statue's base force
    vanish there, and the model (bodies in contact) no longer holds. The saved samples (every
    0.1 ms, `violations()`) show both from 0.9982 s to 1.0918 s; each warning must say a time
    inside that interval. Kills compiled.py:828 (`not isnan`: the first time never recorded,
    the floor warning never raised)."""
    from rocking.excitation.record import GroundMotion

    statue = rk.Statue(width=0.3, height=1.5, mass=100.0)
    pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=0.5, kinetic=0.4))
    t = np.round(np.arange(0.0, 3.0, 0.01), 10)
    record = GroundMotion(time=t, values=4.0 * np.sin(2 * np.pi * 1.5 * t),
                          vertical=np.where((t >= 1.0) & (t < 1.1), -12.0, 0.0))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), record, options=rk.Options(save_dt=1e-4))
    sampled = dict((name, (t0, t1)) for name, t0, t1 in r.violations())
    for check, words in (("floor normal force ≤ 0", "the floor normal force reached zero"),
                         ("statue lift-off (base force ≤ 0)", "the statue's base force reached zero")):
        t0, t1 = sampled[check]
        assert t0 == pytest.approx(0.9982, abs=2e-4) and t1 == pytest.approx(1.0918, abs=2e-4)
        said = [w for w in r.warnings if words in w]
        assert len(said) == 1, r.warnings
        t_warn = float(re.search(r"from t = ([0-9.]+) s", said[0]).group(1))
        # (the warning's first instant lies after the last sample that holds, t0 − 0.1 ms, and
        # the text rounds it to 0.1 ms: 0.9981 for 0.99814 s)
        assert t0 - 1.5e-4 <= t_warn <= t1, (check, t_warn)


def test_the_uplift_warning_falls_inside_the_uplift_seen_in_the_saved_samples():
    """A statue rocking on a 0.6 m × 0.8 m pedestal that slides, under 5 m/s². The saved samples
    (every 0.1 ms; Response.violations, from contact_forces) put the floor's pressure centre outside
    the pedestal's base from 2.2397 s to 2.2687 s only. The solver checks it at the end of each step,
    so its warning must fall inside that interval. It said 0.1775 s until 2026-11-24: the end-of-step
    checks read the floor acceleration and the forces of the last event, because the FSAL copy took
    only the derivatives (the warning mixed a = 5 m/s² from t = 0 with the state at 0.1775 s)."""
    statue = rk.Statue(width=0.3, height=1.5, mass=100.0)
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=0.3, kinetic=0.25), width=0.6, height=0.8)
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=5.0, frequency=1.5, cycles=3),
                    options=rk.Options(save_dt=1e-4))
    spans = [(t0, t1) for name, t0, t1 in r.violations() if name == "pedestal uplift"]
    assert spans and spans[0][0] == pytest.approx(2.2397, abs=1e-4)
    said = [w for w in r.warnings if "pedestal would uplift" in w]
    assert len(said) == 1
    t_warn = float(re.search(r"from t = ([0-9.]+) s", said[0]).group(1))
    assert any(t0 - 1e-4 <= t_warn <= t1 + 1e-4 for t0, t1 in spans), (t_warn, spans)


@pytest.mark.parametrize("amplitude", [0.5, 4.0])
def test_a_run_whose_duration_falls_a_rounding_short_of_a_grid_time_saves_its_end(amplitude):
    """A duration of 1 − 5e-12 s with samples every 0.01 s: the grid's last time, 1.0 s, lies
    past the run's end by less than the grid's 1e-9 tolerance, so it counts, and the run's last
    state is saved there at the run's end (the step loop stops at t_end and leaves it to the
    final hold). Both a run that ends at rest and one still rocking must end their samples with
    the state at t_end: the curves, animations and residual displacement read off the samples
    would otherwise stop a sample short. Kills compiled.py's final hold
    taken only for an overturn (`status == STATUS_OVERTURNED`: the last sample was 0.99 s)."""
    duration = 1.0 - 5e-12
    r = rk.simulate(rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=100.0)),
                    rk.Harmonic(amplitude=amplitude, frequency=2.0, cycles=3), duration=duration,
                    options=rk.Options(save_dt=0.01))
    assert r.t[-1] == duration
    assert np.count_nonzero(np.isclose(r.t, np.round(r.t, 2), rtol=0.0, atol=1e-11)) >= 101


@pytest.mark.parametrize("mu", [0.25, 0.5])
def test_a_friction_demand_tied_with_mus_for_a_whole_pulse_is_no_slip(mu):
    """A block (μs = μk = μ, squat: it cannot rock) under a rectangle pulse of exactly μ·g: the
    friction the floor must give, m·μ·g, equals μs·N to the bit for the whole second. Coulomb's
    law holds the block (|F| ≤ μs·N); with μk = μs a slide would have no acceleration either, so
    the only difference is what the run reports. It must report rest: no event, no sliding onset,
    no warning. Kills compiled.py's tie rule for a friction guard that starts at zero and stays
    there (`g1 < 1` for `g1 < 0`: a SLIP at t = 0, a "slide" through the pulse and a
    `first_sliding_time` of 0.0 s for a block that never moved)."""
    block = rk.Statue(width=1.0, height=1.0, mass=10.0, friction=rk.Friction(static=mu, kinetic=mu))
    r = rk.simulate(rk.System(statue=block), rk.RectanglePulse(amplitude=mu * rk.g, width=1.0), duration=2.0)
    assert r.events == []
    summary = r.summary()
    assert summary["first_sliding_time"] is None and summary["peak_sliding"] == 0.0
    assert not r.warnings


def test_a_slide_found_inside_a_step_starts_at_the_same_instant_without_saved_samples():
    """The brief excess of friction demand of
    `test_a_friction_demand_that_exceeds_mus_for_a_fraction_of_a_step_starts_the_slide` (μs a
    millionth below the demand's peak, 0.2062), run without saved samples as every study's batch
    runs are. With samples, a grid point inside nearly every step builds the dense output anyway;
    without them, the dip seen at the step's stages must build it. The slide must start at the
    same instant, to the event accuracy (1e-9 s). Kills compiled.py:620 (`g0 > 1` in the test
    that builds the dense output for a dip: the search then read the previous step's interpolant
    and put the slide at 0.1561 s, for 0.1633 s)."""
    from rocking.models.regimes import EventKind

    mu_s = 0.20620337647919162 * (1.0 - 1e-6)  # the peak demand, as that test measures it
    slips = [[e.time for e in _light_statue_rocking_on_a_pedestal(mu_s, save=save).events if e.kind == EventKind.SLIP]
             for save in (True, False)]
    assert slips[0] and slips[0][0] == pytest.approx(0.16326, abs=1e-4)
    assert slips[1] == pytest.approx(slips[0], abs=1e-9)


def test_the_required_top_friction_is_the_peak_of_the_base_force_ratio_between_step_ends():
    """A 0.2 × 1.2 m statue under 2.5 m/s² at 2 Hz rocks fast (|θ̇| up to several α per second)
    while |θ| stays below α. The summary's `required_top_friction` is the largest |Px|/Py while
    |θ| ≤ α; the solver tracks it at the integration stages, so it must match the largest ratio
    over samples every 10 µs (Response.contact_forces). Measured: 8.3e-7 above the grid's
    maximum, which lies below the true peak by the grid's second-order miss; 1e-5 is the
    tolerance. Kills compiled.py's stage sampling gated on |θ̇| ≤ α in place of |θ| ≤ α
    (b3636489: the stage maxima of fast rocking lost, 4.5e-5 below the grid's maximum)."""
    statue = rk.Statue(width=0.2, height=1.2, mass=100.0)
    r = rk.simulate(rk.System(statue=statue), rk.Harmonic(amplitude=2.5, frequency=2.0, cycles=3), duration=4.0,
                    options=rk.Options(save_dt=1e-5))
    assert r.summary()["first_rocking_time"] is not None and not r.summary()["overturned"]
    inside = np.abs(r.theta) <= r.alpha
    grid_peak = float(np.max(r.contact_forces()["top_friction_ratio"][inside]))
    assert r.summary()["required_top_friction"] == pytest.approx(grid_peak, rel=1e-5)


def test_the_required_top_friction_through_a_zeno_sequence_uses_the_state_at_each_event():
    """A 0.4 × 2 m statue rocks down to rest after a one-sine pulse through 218 impacts, most of
    them in a chattering sequence whose short steps read each impact off the 7th-order dense
    output; there the solver evaluates the base forces at the event's own state. The summary's
    required_top_friction must equal the largest |Px|/Py over saved samples every 0.1 ms with
    |θ| ≤ α (Response.contact_forces, checked against the sympy derivation elsewhere): 5.7e-6
    apart (measured; stages and samples see different instants), so 1e-5. The mass is chosen
    so that the floor's input work, which stays at 2.99 J after the pulse, would give a ratio of
    0.66 if read as θ̇ (rad/s) at those events: kills compiled.py:724 (θ̇ taken from the state's
    input-work entry, bench/MUTATION.md 868ff236)."""
    statue = rk.Statue(width=0.4, height=2.0, mass=26.5)
    r = rk.simulate(rk.System(statue=statue), rk.SinePulse(amplitude=3.0, frequency=2.0),
                    options=rk.Options(save_dt=1e-4))
    assert r.status == "completed" and r.summary()["impacts"] > 200
    assert r.energy["input_work"] == pytest.approx(2.99, abs=0.01)
    forces = r.contact_forces()
    inside = ((r.regime & 1) != 0) & (np.abs(r.theta) <= r.alpha) & (forces["Py"] > 0)
    grid_peak = float(np.max(forces["top_friction_ratio"][inside]))
    assert r.summary()["required_top_friction"] == pytest.approx(grid_peak, rel=1e-5)


def test_the_pedestal_uplift_warning_compares_the_floor_pressure_centre_with_the_half_width():
    """A 0.2 × 1.2 m statue rocks on a 500 kg, 1 m tall pedestal held by μ = 1 (it never slides)
    under 3 m/s² at 2 Hz. The floor's normal force acts at x_N (moment balance of the pedestal,
    derivation §3.5); the pedestal's width enters nothing but the check |x_N| ≤ b₁. Measured on
    a 100 µs grid: max |x_N| = X ≈ 0.178 m. A pedestal 2 % wider than 2X gives no uplift warning
    and the same motion to the bit; 5 % narrower gives the warning, no earlier than the grid's
    first |x_N| > b₁ (less 1 ms: the check runs at step ends and events). Kills compiled.py's
    check at FSAL step ends reading θ̇ for ü (f6121b70 of the fourteenth round: x_N then carries
    ½·h₁·m₁·θ̇/N, up to 6.7 % larger, and the wider pedestal is said to uplift)."""
    statue = rk.Statue(width=0.2, height=1.2, mass=100.0)
    held = rk.Friction(static=1.0, kinetic=1.0)
    motion = rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=3)

    def run(width, save_dt=None):
        pedestal = rk.Pedestal(mass=500.0, friction=held, width=width, height=1.0)
        options = rk.Options(save_dt=save_dt) if save_dt else rk.Options()
        return rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, duration=4.0, options=options)

    def uplift(r):
        return [w for w in r.warnings if "pedestal would uplift" in w]

    wide = run(3.0, 1e-4)
    x_n = np.abs(wide.contact_forces()["x_N"])
    big = float(np.nanmax(x_n))
    assert 0.15 < big < 0.2 and not uplift(wide) and wide.summary()["peak_sliding"] == 0.0
    above, below = run(2.0 * big * 1.02), run(2.0 * big * 0.95)
    assert not uplift(above), above.warnings
    assert above.peak_rotation == wide.peak_rotation
    (warning,) = uplift(below)
    t_warning = float(re.match(r"from t = ([0-9.]+) s", warning).group(1))
    first_over = float(wide.t[np.nonzero(x_n > big * 0.95)[0][0]])
    assert t_warning >= first_over - 1e-3


def test_a_run_one_event_short_of_its_limit_saves_every_sample():
    """The saved series holds every grid point and two rows per event (before and after it), and
    is reserved for that at the start: n_grid + 2·max_events + 4 rows. A 0.4 × 2 m statue rocking
    under 0.3 g at 2 Hz for a fixed 3 s makes 11 impacts, so 301 grid points + 22 rows. With
    max_events = 12 (one more than it needs, so the run completes its 3 s) it must save the very
    same 323 rows as with the default limit. Kills compiled.py:399 (the reservation
    n_grid + 2·max_events − 4: 321 rows, the last two grid points silently dropped)."""
    alone = rk.System(statue=rk.Statue(width=0.4, height=2.0, mass=50.0, restitution=0.9))
    motion = rk.Harmonic(amplitude=0.3 * 9.81, frequency=2.0, cycles=4)
    free = rk.simulate(alone, motion, duration=3.0)
    n = len(free.events)
    assert n == 11 and len(free.t) == 301 + 2 * n and free.t[-1] == 3.0
    tight = rk.simulate(alone, motion, duration=3.0, options=rk.Options(max_events=n + 1))
    assert tight.status == free.status == "still_moving"
    assert np.array_equal(tight.t, free.t) and np.array_equal(tight.state, free.state)


def test_a_run_the_solver_cannot_step_ends_step_failed_and_says_undetermined():
    """A floor acceleration of 1e150 m/s² makes every error estimate of the first step non-finite:
    the solver shrinks the step tenfold each time, and once it is below 1e-14 s it stops with
    status step_failed at t = 0, without a step taken. The verdict says the run is undetermined
    (not "did not overturn"), and by default the failure raises. The path a run takes when its
    step size underflows, checked on the solver itself (test_cli.py only fakes the error)."""
    alone = rk.System(statue=rk.Statue(width=0.4, height=2.0, mass=50.0))
    motion = rk.Harmonic(amplitude=1e150, frequency=2.0, cycles=2)
    r = rk.simulate(alone, motion, throw=False)
    assert r.status == "step_failed" and r.end_time == 0.0 and r.events == []
    assert r.verdict.startswith("undetermined") and "step_failed" in r.verdict
    assert not r.overturned
    with pytest.raises(rk.SimulationError, match="step size underflow"):
        rk.simulate(alone, motion)


def test_a_frictionless_top_face_is_flagged_as_soon_as_the_statue_rocks():
    """A top face with μs = 0 (given, not omitted) holds nothing: once the statue rocks its base
    pushes sideways, |P_x| > 0 = μs·P_y, and the run must warn that the statue would slip on the
    pedestal, from the first rocking instant on. Kills compiled.py:817 (the check made only for
    μ_top > 0: a frictionless top face never flagged)."""
    statue = rk.Statue(width=0.4, height=2.0, mass=50.0, friction=rk.Friction(static=0.0, kinetic=0.0))
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=0.8, kinetic=0.7))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2))
    first_rock = r.summary()["first_rocking_time"]
    assert first_rock is not None
    (slip,) = [w for w in r.warnings if "slip on the pedestal" in w]
    t_slip = float(re.match(r"from t = ([0-9.]+) s", slip).group(1))
    assert first_rock <= t_slip <= first_rock + 0.05


def test_the_right_hand_side_fills_every_slot_the_step_loop_reads_back():
    """``compiled.rhs`` writes dy/dt into ``out[:6]`` and (a_g, a_v, F, N, P_x, P_y, ok) into
    ``out[6:13]``; the step loop keeps them in its stage rows and reads P_x and P_y back at each
    step's ends (the friction the statue's base needs, the top-face check). Each slot against
    ``evaluate_all`` and the floor signals at the same state, in every regime, on a floor with both
    components moving; ``out`` starts as NaN so that a slot left unwritten shows. Kills
    compiled.py:159's 68b6c2cc (P_x written into P_y's slot, its own left as it was: every value
    it fed was found again by the stages' own evaluations, so no run differed)."""
    from rocking.excitation.record import GroundMotion
    from rocking.models.dynamics import evaluate_all
    from rocking.simulation import prepare
    from rocking.solver import compiled as C

    system = rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=80.0),
                       pedestal=rk.Pedestal(mass=120.0, friction=rk.Friction(static=0.4, kinetic=0.3)))
    time = np.linspace(0.0, 1.0, 101)
    motion = GroundMotion(time=time, values=3.0 * np.sin(7.0 * time), name="both",
                          vertical=-2.0 * np.cos(5.0 * time))
    p, args = prepare(system, motion, duration=1.0, options=rk.Options(gravity=9.81))
    sig_h, sig_v, breakpoints, t0, t_end = args[1:6]
    table = C._piece_table(sig_h, sig_v, breakpoints, t0, t_end)
    edges = np.concatenate(([t0], breakpoints, [t_end]))
    t = 0.4321
    loc = C._piece(table, int(np.searchsorted(edges, t)) - 1)
    a, av = 3.0 * math.sin(7.0 * t), -2.0 * math.cos(5.0 * t)  # linear between samples: to 1e-3
    y = np.array([0.01, 0.2, 0.05, -0.3, 0.0, 0.0])
    for sig, s in ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, -1), (1, -1)):
        out = np.full(C.N_STATE + C.N_DIAG, np.nan)
        C.rhs(t, y, p, sig, s, loc, out)
        udd, thdd, ok, f, n, px, py, p_in, p_fric = evaluate_all(p, sig, s, y[1], y[2], y[3], out[6], out[7])
        assert out[6] == pytest.approx(a, abs=1e-3) and out[7] == pytest.approx(av, abs=1e-3)
        np.testing.assert_array_equal(out[:13], [y[1], udd, y[3], thdd, p_in, p_fric, out[6], out[7], f, n, px, py,
                                                 1.0 if ok else 0.0], err_msg=f"regime sig={sig}, s={s}")
        assert px != 0.0 or s == 0  # a rocking statue's base pushes sideways: the slot is not trivially 0


def test_an_impact_excursion_narrower_than_the_guard_samples_is_found_at_its_turning_point():
    """After an event the impact guard S·θ starts a step on zero; if the statue rocks out and back
    within the step, ``_positive_inside`` must find a point where S·θ > 0 so that the impact can
    be located. Its 31 samples (k/32) miss an excursion narrower than 1/32 of the step; the
    turning point of θ, where S·θ peaks, does not. Here θ(x) = x·(0.02 − x) on the step's dense
    output (F0 = −0.98, F1 = 1 in DOP853's form y + x·(F0 + (1 − x)·F1)): positive on (0, 0.02)
    only, peak 1e-4 rad at x = 0.01. The turning point is returned; the samples alone (none
    lies inside (0, 0.02)) give −1, and the impact would be lost. Kills compiled.py:431's 4177a70e
    (the turning point tried for every guard but the impact's), which no whole run reached: the
    step after an event starts short enough for the samples to see the excursion."""
    from rocking.models.modes import IMPACT
    from rocking.simulation import prepare
    from rocking.solver import compiled as C

    p, args = prepare(rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=80.0)),
                      rk.Harmonic(amplitude=1.0, frequency=1.0, cycles=1), options=rk.Options(gravity=9.81))
    sig_h, sig_v, breakpoints, t0, t_end = args[1:6]
    loc = C._piece(C._piece_table(sig_h, sig_v, breakpoints, t0, t_end), 0)
    y0 = np.zeros(C.N_STATE)
    F = np.zeros((7, C.N_STATE))
    F[0, 2], F[1, 2] = -0.98, 1.0
    work, gbuf = np.empty(C.N_STATE), np.empty(C.N_GUARDS)
    for s, sign in ((1, 1.0), (-1, -1.0)):
        Fs = sign * F
        x = C._positive_inside(p, 0, s, y0, Fs, 0.1, loc, 0.3, False, work, gbuf, IMPACT, 0.01)
        assert x == 0.01
        assert max(s * (sign * (k / 32) * (0.02 - k / 32)) for k in range(1, 32)) < 0.0  # the samples miss it
    # with no turning point in the step, the samples are all there is
    assert C._positive_inside(p, 0, 1, y0, F, 0.1, loc, 0.3, False, work, gbuf, IMPACT, -1.0) == -1.0
