"""The general stack engine (rocking.stack, issue 11) against today's special-purpose solver and
against closed forms.

Tolerances: both solvers run at rtol 1e-10; their event times agree to ~1e-10 s and their angles
to ~1e-9 rad on these runs (measured), so 1e-8 rad / 1e-9 s (the issue's standard) leave a
margin of ~10 while any modelling difference (a wrong impact law, a missing term) shows up at
1e-3 or more.
"""

import dataclasses
import math

import numpy as np
import pytest

import rocking
from rocking.analyses.paper import case_named, paper_motion, variant_setup
from rocking.contact.friction import Friction
from rocking.excitation.base import KIND_HARMONIC, KIND_RAMP, KIND_RECTANGLE, ZERO_SIGNAL, AbstractMotion, Signal
from rocking.excitation.record import GroundMotion
from rocking.report.stack import build_stack_content, stack_verdict, stack_verdict_class
from rocking.stack import Block, Interface, Stack, engine, simulate_stack

G = 9.80665


def _stack_of(system, ped_width=4.0, ped_height=0.2):
    """The stack that matches a System under the seed's assumptions: a pedestal so wide it cannot
    rock, and a top face that never slips."""
    st = system.statue
    top = Block(width=st.width, height=st.height, mass=st.mass, name="statue")
    if system.pedestal is None:
        return Stack(blocks=(top,), interfaces=(Interface(friction=st.friction, restitution=st.restitution),))
    p = system.pedestal
    return Stack(blocks=(Block(width=ped_width, height=ped_height, mass=p.mass, name="pedestal"), top),
                 interfaces=(Interface(friction=p.friction), Interface(restitution=st.restitution)))


def _compare(system, motion, **kw):
    r = simulate_stack(_stack_of(system), motion, **kw)
    ref = rocking.simulate(system, motion, **kw)
    t_stop = min(r.end_time, ref.end_time) - 1e-6
    m = ref.t < t_stop
    on = np.isin(np.round(ref.t[m], 9), np.round(r.t, 9))
    assert on.sum() > 50
    th = np.interp(ref.t[m], r.t, r.rotation[:, -1])[on]
    u = np.interp(ref.t[m], r.t, r.sliding[:, 0])[on]
    return r, ref, np.max(np.abs(th - ref.theta[m][on])), np.max(np.abs(u - ref.u[m][on]))


STATUE = dict(width=0.3, height=1.2, mass=100.0)


def _pedestal_and_statue(floor_friction, top=None):
    """The 0.3 × 1.2 m, 100 kg statue on a 0.8 × 0.5 m, 300 kg pedestal (``top``: the friction
    of the face between them; None: it never slips)."""
    return Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(**STATUE)),
                 interfaces=(Interface(friction=floor_friction), Interface(friction=top)))


@pytest.mark.parametrize("amplitude, overturns", [(6.0, True), (3.0, True), (1.5, False)])
def test_single_block_matches_todays_solver(amplitude, overturns):
    motion = rocking.SinePulse(amplitude=amplitude, frequency=1.0)
    r, ref, dth, du = _compare(rocking.System(statue=rocking.Statue(**STATUE)), motion)
    assert r.overturned == ref.overturned == overturns
    assert dth < 1e-8 and du < 1e-12
    assert abs(r.end_time - ref.end_time) < 1e-9


def _floor_displacement(time, accel, t):
    """The displacement (m) at times t of a floor at rest at time[0] whose acceleration (m/s²) is
    linear between the samples (time, accel): exact, each piece's cubic."""
    dt = np.diff(time)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (accel[:-1] + accel[1:]) * dt)])
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * dt + accel[:-1] * dt**2 / 3 + accel[1:] * dt**2 / 6)])
    i = np.clip(np.searchsorted(time, t, side="right") - 1, 0, len(time) - 2)
    tau = t - time[i]
    return x[i] + v[i] * tau + accel[i] * tau**2 / 2 + (accel[i + 1] - accel[i]) / dt[i] * tau**3 / 6


@pytest.mark.parametrize("on_pedestal", [False, True], ids=["on the floor", "on a held pedestal"])
@pytest.mark.parametrize("floor", ["harmonic", "record"])
def test_a_frictionless_face_slides_from_the_first_instant_the_floor_pushes(floor, on_pedestal):
    """A face of μs = μk = 0 holds nothing: the block above it stays where it is in space and
    slides by minus the displacement of what it stands on, u(t) = −x_g(t), from t = 0, however
    the push starts. Under a floor whose acceleration rises from zero at t = 0 (a sine, here as a
    harmonic and as a record sampled every 0.02 s) its stick bound, −|F|, starts at zero and
    only falls. Until 2026-12-07 that face stayed stuck to the end of the first step (1 ms:
    3 µm of slide lost) or to the record's first sample (0.02 s: 1.2 mm, 0.8 %), where
    rocking.simulate slides from 0. Tolerance: 1e-9 m on a slide of 0.16 m (measured 5e-13)."""
    fr = Friction(static=0.0, kinetic=0.0)
    if on_pedestal:  # a pedestal that never slips, a frictionless top face
        stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.6, height=0.3, mass=50.0)),
                      interfaces=(Interface(), Interface(friction=fr)))
    else:
        stack = Stack(blocks=(Block(width=1.0, height=0.5, mass=100.0),), interfaces=(Interface(friction=fr),))
    k = stack.n - 1
    w = 2 * np.pi
    if floor == "harmonic":
        motion = rocking.Harmonic(amplitude=1.0, frequency=1.0, cycles=1, form="sin")
    else:
        time = np.arange(51) * 0.02
        motion = GroundMotion(time=time, values=np.sin(w * time), name="sine")
    r = simulate_stack(stack, motion, duration=1.0)
    x_g = (r.t / w - np.sin(w * r.t) / w**2) if floor == "harmonic" else _floor_displacement(time, np.sin(w * time), r.t)
    assert r.blocks[k]["first_sliding_time"] == 0.0
    assert np.max(np.abs(r.sliding[:, k] + x_g)) < 1e-9
    assert r.blocks[k]["peak_sliding"] == pytest.approx(np.max(np.abs(x_g)), abs=1e-9)


def test_a_run_that_fills_its_event_budget_stops_at_that_event_undetermined():
    """``max_events``: a run stops at the event that fills its budget, with status "max_events"
    and an undetermined verdict, its events those of the run without a budget up to there and its
    last saved instant that event's. A budget of exactly the run's own count stops at its last
    event (the run cannot know that nothing follows); one more lets it end at rest. (The block
    rocks under a one-sine pulse 14 % above its uplift value and lands, 135 events in all.)"""
    stack = Stack(blocks=(Block(**STATUE),), interfaces=(Interface(),))
    motion = rocking.SinePulse(amplitude=2.8, frequency=2.0)
    free = simulate_stack(stack, motion, options={"max_events": 5000})
    count = len(free.events)
    assert free.status == "completed" and count == 135
    for budget in (1, 2, 5, count):
        r = simulate_stack(stack, motion, options={"max_events": budget})
        assert r.status == "max_events" and r.verdict.startswith("undetermined")
        assert len(r.events) == budget
        np.testing.assert_array_equal(r.events, free.events[:budget])
        assert r.end_time == r.t[-1] == free.events[budget - 1, 0]
    assert simulate_stack(stack, motion, options={"max_events": count + 1}).status == "completed"


def test_sliding_block_matches_todays_solver():
    fr = Friction(static=0.2, kinetic=0.15)
    motion = rocking.SinePulse(amplitude=3.0, frequency=1.0)
    r, ref, dth, du = _compare(rocking.System(statue=rocking.Statue(width=1.0, height=0.5, mass=100.0, friction=fr)),
                               motion)
    assert du < 1e-9 and r.status == ref.status == "completed"
    assert abs(r.end_time - ref.end_time) < 1e-9


# Two random pedestals under records (statue never rocking): the pedestal's slip stops while the
# floor's acceleration is a hair above μs·g, so it slips back for less than a step's first sample
SLIPS_BACK = {
    "L'Aquila": ("LAquila2009_AQV_HNE_ESM", 7.288682879096391, (0.6951878216631013, 0.6187995658387064, 666.598649790987),
                 (0.39104643505637027, 0.7826039815545317, 169.4354699309871), (0.21443457975679134, 0.2090790547125613)),
    "Landers": ("Landers1992_Lucerne_260", 7.640519103250328, (1.4803891247234477, 0.6475283349410403, 441.7938998759589),
                (0.5672558080035673, 0.7701146588576463, 66.18974582653154), (0.12923029448359896, 0.126670136621393)),
}


@pytest.mark.parametrize("case", SLIPS_BACK)
def test_a_slip_that_stops_above_mu_s_and_runs_back_within_a_sample_is_followed(case):
    """A pedestal (the statue on it never rocks) slides under a record; one of its slips stops
    while the floor's acceleration is a hair above μs·g and falling (L'Aquila: 0.21488 g for
    μs = 0.21443, μk = 0.20908, at 4.73573 s). Held it cannot be: it slips back, and stops again
    when that acceleration has fallen below μk·g, 0.435 ms later, before the first sample of
    the 4 ms step. That sample saw the slip already reversed, which the engine took for a slip
    running against its own direction from the start: it stopped it at once, the mode selection
    set it slipping again at the same instant, 50 times, and the run stopped `inconsistent`
    (both cases, found by a scan of 2000 random statues on pedestals under the bundled records).
    The slip is now probed at closer points, as a gap that starts at zero. Against
    ``rocking.simulate`` (the seed's model holds: nothing rocks): every slip and stop at the
    same instants to 1e-9 s (measured 1e-13) and the same sliding to 1e-9 m."""
    from rocking.io.records import read_record

    name, pga, (pw, ph, pm), (sw, sh, sm), (mu_s, mu_k) = SLIPS_BACK[case]
    friction = Friction(static=mu_s, kinetic=mu_k)
    motion = read_record(name).trimmed(20.0).scaled(pga=pga)
    system = rocking.System(statue=rocking.Statue(width=sw, height=sh, mass=sm),
                            pedestal=rocking.Pedestal(mass=pm, friction=friction, width=pw, height=ph))
    stack = Stack(blocks=(Block(width=pw, height=ph, mass=pm), Block(width=sw, height=sh, mass=sm)),
                  interfaces=(Interface(friction=friction), Interface()))
    r, ref = simulate_stack(stack, motion), rocking.simulate(system, motion)
    assert r.status == ref.status == "completed", r.verdict
    assert r.summary()["blocks"][1]["peak_rotation"] == 0.0 and ref.peak_rotation == 0.0
    kinds = [e.kind.name for e in ref.events]
    assert set(kinds) == {"SLIP", "STOP"} and len(kinds) > 300
    np.testing.assert_allclose(r.events[:, 0], [e.time for e in ref.events], rtol=0, atol=1e-9)
    s, sr = r.summary()["blocks"][0], ref.summary()
    assert abs(s["residual_sliding"] - sr["residual_sliding"]) < 1e-9
    assert abs(s["peak_sliding"] - sr["peak_sliding"]) < 1e-9
    if case == "L'Aquila":
        stops = [e.time for e in ref.events if e.kind.name == "STOP" and 4.73 < e.time < 4.74]
        assert len(stops) == 2 and 4.3e-4 < stops[1] - stops[0] < 4.4e-4


def test_a_floor_face_at_its_bound_under_a_statue_rocking_to_its_fall_lets_the_statue_fall():
    """A 0.26 × 1.40 m, 404 kg statue (r = 0.725) rocks to its fall on a 0.63 × 0.34 m, 784 kg
    pedestal (μs = 0.5913, μk = 0.5902) under Rinaldi at a PGA of 4.18 m/s² (bench/verdict_scan.py
    --seed 3, run 259). A stick guard that starts a step at its bound and stays beyond it is an
    event from the step's start only while everything is at rest (the `rest_step` condition of
    the step loop). Applied while the statue rocks, the floor face left stuck at its bound by the
    event before came back to the same event 50 times, and the run stopped `inconsistent` at
    3.699 s (19 of those 800 runs did; a mutant of the forty-fourth round that dropped the
    condition). The statue falls at 3.741 s, as in the two-body model (3.740 s)."""
    from rocking.io.records import read_record

    motion = read_record("Northridge1994_RinaldiReceivingSta_228").trimmed(20.0).scaled(pga=4.179394075546052)
    friction = Friction(static=0.5913231690154952, kinetic=0.5901792146893219)
    pw, ph, pm = 0.6342878817328715, 0.3441384699883265, 783.8927810544168
    sw, sh, sm, rest = 0.26294798789766616, 1.3969196510584043, 403.6999918749701, 0.7250341501740163
    stack = Stack(blocks=(Block(width=pw, height=ph, mass=pm), Block(width=sw, height=sh, mass=sm)),
                  interfaces=(Interface(friction=friction), Interface(restitution=rest)))
    r = simulate_stack(stack, motion)
    assert r.status == "overturned", r.verdict
    two = rocking.simulate(rocking.System(statue=rocking.Statue(width=sw, height=sh, mass=sm, restitution=rest),
                                          pedestal=rocking.Pedestal(mass=pm, friction=friction, width=pw, height=ph)),
                           motion)
    assert two.status == "overturned"
    assert r.blocks[1]["overturn_time"] == pytest.approx(two.overturn_time, abs=3e-3)
    assert r.blocks[1]["overturn_time"] == pytest.approx(3.7406, abs=1e-3)


@pytest.mark.parametrize("amplitude", [2.0, 3.0, 5.0])
def test_statue_on_sliding_pedestal_matches_todays_solver(amplitude):
    fr = Friction(static=0.2, kinetic=0.15)
    system = rocking.System(statue=rocking.Statue(**STATUE),
                            pedestal=rocking.Pedestal(mass=300.0, friction=fr, width=0.8, height=0.5))
    r, ref, dth, du = _compare(system, rocking.SinePulse(amplitude=amplitude, frequency=1.0))
    assert dth < 1e-8 and du < 1e-9
    assert abs(r.end_time - ref.end_time) < 1e-9


PAPER_RUNS = [(name, variant, 1e-12, 1e-8) for name in ("9a", "9b", "10a", "10b", "11a", "11b", "12a", "12b")
              for variant in ("pedestal", "alone_floor_friction")]
PAPER_RUNS += [(name, "alone_infinite_friction", 1e-12, 1e-8) for name in ("9a", "9b", "10b")]
# Slender blocks rocking for 20 s at r = 0.8: an error grows by orders of magnitude over the
# impacts, so the two solvers meet at 1e-8 rad only from rtol 1e-13 (measured: 1.2e-8–2e-8 rad at
# 1e-12, 2e-10–3e-9 at 1e-13, and the event times converge to ours: at rtol 1e-10 ours are
# within 1e-10 s of the converged values, today's within 2e-8 s).
PAPER_RUNS += [(name, "alone_infinite_friction", 1e-13, 1e-8) for name in ("11a", "11b", "12a", "12b")]


@pytest.mark.parametrize("name, variant, rtol, tol", PAPER_RUNS)
def test_paper_cases_match_todays_solver(name, variant, rtol, tol):
    """The paper's runs (25 s / 20 s of harmonic motion, tens of impacts, Coulomb impact law with
    r = 0.8) on the general engine: the same rocking, sliding and impacts. 9b with floor friction
    (alone or on the pedestal) ends a long sequence of impacts while sliding (today's rule sets θ̇ = 0 and keeps u̇;
    ours lands the block with a plastic, Coulomb-bounded impulse), which moves u by 3e-7 m: it is
    held to 1e-6. 10a alone is left out: today's solver restarts its steps at the instant |θ|
    passes α (a marker event), and the runs drift apart to 2e-6 rad after it (2.7e-7 at 1e-13)."""
    if name == "9b" and variant != "alone_infinite_friction":
        tol = 1e-6
    case = case_named(name)
    motion = paper_motion(case)
    system, options = variant_setup(case, variant)
    options = dataclasses.replace(options, rtol=rtol, atol=rtol * 1e-2)
    r, ref, dth, du = _compare(system, motion, duration=motion.duration, options=options)
    assert r.status == ref.status
    assert dth < tol and du < tol
    # the impacts, counted per interface: the statue's are today's. (The pedestal may land too:
    # in 10b a statue's impact lifts a corner of the pedestal for 0.24 ms, 20 times, which the
    # seed's model, with a pedestal that never rocks, does not have.)
    impacts = [f["impacts"] for f in r.interfaces]
    assert impacts[-1] == len(ref.impacts) and sum(impacts) == r.summary()["impacts"]
    # the peaks: today's solver locates the turning points of θ, and so does the engine now (read
    # at the step ends and the saved samples alone, they came out up to 4e-5 rad low here); the
    # peak slide is the lowest block's (the pedestal, or the statue alone)
    assert abs(r.blocks[-1]["peak_rotation"] - ref.summary()["peak_rotation"]) < tol
    assert abs(r.blocks[0]["peak_sliding"] - ref.summary()["peak_sliding"]) < tol
    # the friction the statue's base needed, its impacts' impulses included (measured: 3e-13; in
    # 11 of these 23 runs an impact needs the most, 4/9 = (h/b)(1 − r)/(1 + r) in 11a alone; the
    # engine read up to 48 % low there until 2026-12-03, when it left impacts out)
    assert r.interfaces[-1]["required_friction"] == pytest.approx(ref.summary()["required_top_friction"], rel=1e-9)


def _ramp_onset(stack, rate=0.05):
    """Slow ramp a = rate·t from rest: the first rocking / sliding time of each block."""
    r = simulate_stack(stack, rocking.Ramp(rate=rate, end=60.0), duration=60.0)
    return r


def _rel(a, b):
    return abs(a - b) / abs(b)


def test_onset_upper_block_rocks_first():
    # a wide heavy pedestal that neither rocks (its threshold is g·B1/H1 = 6.7 g) nor slides
    stack = Stack(blocks=(Block(width=2.0, height=0.3, mass=500.0), Block(width=0.3, height=1.2, mass=50.0)),
                  interfaces=(Interface(), Interface()))
    r = _ramp_onset(stack)
    t = r.blocks[1]["first_rocking_time"]
    assert _rel(0.05 * t, G * 0.3 / 1.2) < 1e-6
    assert r.blocks[0]["first_rocking_time"] is None or r.blocks[0]["first_rocking_time"] > t


def test_onset_stack_rocks_as_one():
    m1, m2, b1, h1, h2 = 40.0, 60.0, 0.3, 1.0, 0.5
    stack = Stack(blocks=(Block(width=b1, height=h1, mass=m1), Block(width=0.5, height=h2, mass=m2)),
                  interfaces=(Interface(), Interface()))
    r = _ramp_onset(stack)
    a_star = G * (m1 + m2) * b1 / 2 / (m1 * h1 / 2 + m2 * (h1 + h2 / 2))
    t0 = r.blocks[0]["first_rocking_time"]
    assert _rel(0.05 * t0, a_star) < 1e-6
    # the top (wider than the block under it: its ends are the lower block's corners) rides on
    t1 = r.blocks[1]["first_rocking_time"]
    assert t1 is None or t1 > t0


def test_onset_upper_block_slides_first():
    stack = Stack(blocks=(Block(width=2.0, height=0.3, mass=500.0), Block(width=0.6, height=0.6, mass=50.0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.15, kinetic=0.1))))
    r = _ramp_onset(stack)
    assert _rel(0.05 * r.blocks[1]["first_sliding_time"], 0.15 * G) < 1e-6


def test_onset_stack_slides_on_floor():
    stack = Stack(blocks=(Block(width=2.0, height=0.3, mass=500.0), Block(width=0.6, height=0.6, mass=50.0)),
                  interfaces=(Interface(friction=Friction(static=0.12, kinetic=0.1)),
                              Interface(friction=Friction(static=0.3, kinetic=0.25))))
    r = _ramp_onset(stack)
    assert _rel(0.05 * r.blocks[0]["first_sliding_time"], 0.12 * G) < 1e-6
    assert r.blocks[1]["first_sliding_time"] is None


def _two_drums(restitution):
    """Two 0.4 × 1.0 m, 100 kg drums that never slip, the lower one's restitution given: while the
    joint between them stays closed they are one uniform 0.4 × 2.0 m, 200 kg block."""
    drum = Block(width=0.4, height=1.0, mass=100.0)
    return Stack(blocks=(drum, drum), interfaces=(Interface(restitution=restitution), Interface()))


@pytest.mark.parametrize("r", [0.93, 0.7])
def test_a_column_of_drums_rocking_as_one_restitutes_as_the_one_block(r):
    """The restitution impulse of a landing turns the lower drum *and the drum it carries* as one
    body, by (r − r_H)·φ̇⁻ with r_H and I_O of that body (docs/theory/stack.md §6), so the joint
    never opens and the column is today's single 0.4 × 2 m block with the same r: the angles
    agree to 1e-8 rad and the first ten impacts to 1e-9 s (measured: 1.1e-10 rad, 6e-10 s at
    r = 0.93). Until 2026-12-06 r_H and I_O were the lower drum's alone (0.793, against the
    column's 0.942): the column landed at 0.942 + (r − 0.793)·I_drum/I_column, 0.961 for r = 0.93
    and 0.929 for r = 0.7, and under the second pulse rocked to 0.174 rad where the block with
    r = 0.7 rocks to 0.091."""
    motion = rocking.SinePulse(amplitude=2.5 if r > 0.9 else 3.0, frequency=1.5)
    column = simulate_stack(_two_drums(r), motion, options={"save_dt": 0.01})
    block = rocking.simulate(rocking.System(statue=rocking.Statue(width=0.4, height=2.0, mass=200.0, restitution=r)),
                             motion, options={"save_dt": 0.01})
    assert column.status == block.status == "completed"
    assert not np.any(column.events[:, 1] == 1)  # the joint never opens
    on, i, j = np.intersect1d(np.round(column.t, 9), np.round(block.t, 9), return_indices=True)
    assert len(on) > 300
    assert np.max(np.abs(column.rotation[i, 0] - block.theta[j])) < 1e-8
    assert np.max(np.abs(column.rotation[:, 0])) > 0.04  # it rocks: a quarter of α or more
    hits = column.events[column.events[:, 2] == -1, 0][:10]
    assert len(hits) == 10
    np.testing.assert_allclose(hits, [e.time for e in block.impacts[:10]], rtol=0, atol=1e-9)


def test_energy_balance_and_dissipation():
    """E(t) − E(0) = W_in − D_friction − D_impact to the solver's accuracy, and no impact adds energy."""
    fr = Friction(static=0.3, kinetic=0.25)
    stack = _pedestal_and_statue(fr)
    r = simulate_stack(stack, rocking.SinePulse(amplitude=3.5, frequency=1.0))
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    assert np.max(np.abs(r.balance_error())) < 1e-9 * scale
    # the summary reports the same ratio: the ledger's worst imbalance over that scale (the work
    # put in, 81 J, is 3.3 times the largest change of energy here, so a scale of their difference
    # would read 1.85 times larger)
    worst = np.max(np.abs(r.energy - r.initial_energy - r.input_work + r.friction_loss + r.impact_loss))
    assert r.summary()["energy_balance_error"] == pytest.approx(worst / scale, rel=1e-12)
    impacts = r.events[r.events[:, 2] == -1]
    assert len(impacts) > 0 and np.all(impacts[:, 5] >= -1e-12 * scale)
    assert np.all(np.diff(r.friction_loss) >= -1e-9 * scale)  # friction never does positive work


def test_the_relative_energy_error_of_a_light_stack_is_reported():
    """The same stack 1000 times lighter (0.3 and 0.1 kg): the same motion, and a ledger whose
    scale is 0.08 J, below 1 J. The summary still reports its worst imbalance over that scale
    (a rule that took a scale below 1 J for no motion read 0 here: mutant 4db44063)."""
    fr = Friction(static=0.3, kinetic=0.25)
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=0.3), Block(width=0.3, height=1.2, mass=0.1)),
                  interfaces=(Interface(friction=fr), Interface()))
    r = simulate_stack(stack, rocking.SinePulse(amplitude=3.5, frequency=1.0))
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    worst = np.max(np.abs(r.energy - r.initial_energy - r.input_work + r.friction_loss + r.impact_loss))
    assert 0.01 < scale < 1.0 and worst > 0.0
    assert r.summary()["energy_balance_error"] == pytest.approx(worst / scale, rel=1e-12)


def test_mirror_symmetry():
    stack = _pedestal_and_statue(Friction(static=0.3, kinetic=0.25))
    a = simulate_stack(stack, rocking.SinePulse(amplitude=3.5, frequency=1.0))
    b = simulate_stack(stack, rocking.SinePulse(amplitude=-3.5, frequency=1.0))
    assert np.max(np.abs(a.rotation + b.rotation)) < 1e-10
    assert np.max(np.abs(a.sliding + b.sliding)) < 1e-10


def test_bad_stack_inputs_name_the_field():
    with pytest.raises(ValueError, match="interfaces"):
        Stack(blocks=(Block(width=1, height=1, mass=1),), interfaces=())
    with pytest.raises(ValueError, match="offset"):
        Stack(blocks=(Block(width=1, height=1, mass=1), Block(width=1, height=1, mass=1, offset=2.0)),
              interfaces=(Interface(), Interface()))
    with pytest.raises(ValueError, match="inertia"):
        Block(width=1, height=1, mass=1, inertia=-1.0)
    with pytest.raises(ValueError, match="restitution"):
        Interface(restitution=1.5)


@pytest.mark.parametrize("duration", [0.0, -1.0, math.nan, math.inf])
def test_a_run_of_no_positive_finite_duration_is_refused(duration):
    stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),))
    with pytest.raises(ValueError, match=r"simulation\.duration must be a positive number \(s\), got"):
        simulate_stack(stack, rocking.SinePulse(amplitude=3.0, frequency=1.0), duration=duration)


def test_the_run_is_called_as_documented_and_its_result_is_read_only():
    """``simulate_stack(stack, motion, *, duration, options)``: stack and motion by position or by
    name, the rest by name only (a bare number in third place is refused, not taken for a
    duration); the response cannot be changed after the run (a summary, a report and a plot of
    one response must tell the same story)."""
    stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),))
    motion = rocking.SinePulse(amplitude=1.0, frequency=1.0)
    r = simulate_stack(stack=stack, motion=motion, duration=0.5)
    assert r.status == "completed" and r.end_time == 0.5
    with pytest.raises(TypeError):
        simulate_stack(stack, motion, 0.5)
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.status = "overturned"


def test_the_contact_states_are_saved_in_their_own_columns():
    """A statue rocking on a pedestal that slides (μs = 0.35 under a 4 m/s² sine pulse: it falls
    at 1.54 s), its saved states read against the geometry of the saved samples, not against the
    engine: where the statue is turned it rocks (normal state 1), before it first rocks it stands
    flat (2); the pedestal stays flat on the floor; the pedestal slips (tangential state ±1) the
    way it moves; the statue's face, without friction, never slips (0)."""
    fr = Friction(static=0.35, kinetic=0.3)
    stack = _pedestal_and_statue(fr)
    r = simulate_stack(stack, rocking.SinePulse(amplitude=4.0, frequency=1.0), options={"save_dt": 0.005})
    assert r.blocks[1]["overturned"]
    turned = np.abs(r.rotation[:, 1]) > 1e-6
    before = r.t < r.blocks[1]["first_rocking_time"]
    assert turned.sum() > 200 and before.sum() > 20
    assert np.all(r.normal_state[turned, 1] == 1) and np.all(r.normal_state[before, 1] == 2)
    assert np.all(r.normal_state[:, 0] == 2)
    moving = np.abs(r.velocity[:, 0, 0]) > 1e-6
    assert moving.sum() > 50 and np.any(r.velocity[moving, 0, 0] < 0) and np.any(r.velocity[moving, 0, 0] > 0)
    assert np.all(r.tangential_state[moving, 0] == np.sign(r.velocity[moving, 0, 0]))
    assert np.all(r.tangential_state[:, 1] == 0)


def test_a_record_is_saved_at_its_own_sample_interval_unless_asked_otherwise():
    """Without ``save_dt`` the response is saved at the record's dt (0.005 s for Corralitos), as
    rocking.simulate does: every sample instant of the record is on the grid."""
    from rocking.io.records import read_record

    record = read_record("LomaPrieta1989_Corralitos_000").trimmed(2.0).scaled(0.05)
    stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),))
    assert record.dt == 0.005
    r = simulate_stack(stack, record, duration=2.0)
    grid = np.arange(401) * record.dt
    assert np.all(np.isin(np.round(grid, 12), np.round(r.t, 12)))
    coarse = simulate_stack(stack, record, duration=2.0, options={"save_dt": 0.02})
    # (the end is saved twice: as the last grid point and as the final state)
    grid = np.unique(coarse.t)
    assert len(grid) == 101 and np.allclose(np.diff(grid), 0.02, rtol=0, atol=1e-12)


def test_a_stack_that_never_moves_reports_no_energy_balance_error():
    """Below every threshold nothing moves: no work, no change of energy, so the ledger's scale
    is zero and the relative balance error is 0 (not undefined, not 1)."""
    stack = _pedestal_and_statue(Friction(static=0.5, kinetic=0.4))
    r = simulate_stack(stack, rocking.SinePulse(amplitude=0.5, frequency=1.0))
    assert r.status == "completed" and np.all(r.velocity == 0.0)
    assert np.all(r.input_work == 0.0) and np.all(r.energy == r.initial_energy)
    assert r.summary()["energy_balance_error"] == 0.0
    assert r.summary()["impacts"] == 0 and [f["impacts"] for f in r.interfaces] == [0, 0]


class _VerticalOnly(AbstractMotion):
    """A floor that moves only vertically, up to ``end`` (s); subclasses give the vertical part."""

    def __init__(self, end):
        self.end = end

    @property
    def duration(self):
        return self.end

    def acceleration(self, t):
        return np.zeros_like(np.asarray(t, dtype=float))

    def signal(self):
        return ZERO_SIGNAL


class _VerticalRamp(_VerticalOnly):
    """No horizontal motion; the floor accelerates downwards, a_v = −k·t (m/s²), for t ≤ end."""

    def __init__(self, rate, end):
        super().__init__(end)
        self.rate = rate

    def vertical_signal(self):
        return Signal(KIND_RAMP, np.array([-self.rate, 0.0, 0.0, self.end]), np.zeros(0), np.zeros(0))

    def vertical_acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t <= self.end), -self.rate * t, 0.0)


def test_flight_when_the_floor_falls_faster_than_gravity():
    """a_v = −k t: every contact opens when a_v = −g, at t* = g/k, and from then on each block
    moves relative to the floor with acceleration −(g + a_v) = k (t − t*): Y = Y₀ + k (t − t*)³/6."""
    k = 20.0
    stack = _pedestal_and_statue(Friction(static=0.3, kinetic=0.25))
    r = simulate_stack(stack, _VerticalRamp(k, 1.0), duration=0.8, options={"gravity": G})
    t_star = G / k
    assert abs(r.blocks[0]["lifted_off_time"] - t_star) < 1e-9
    after = r.t > t_star
    for i, y0 in enumerate((0.25, 0.5 + 0.6)):
        expected = y0 + k * (r.t[after] - t_star) ** 3 / 6
        assert np.max(np.abs(r.pose[after, i, 1] - expected)) < 1e-9
        assert np.max(np.abs(r.pose[:, i, 2])) < 1e-12  # nothing turns


class _VerticalSine(_VerticalOnly):
    """No horizontal motion; a_v = −B sin(ωt) (m/s²) for t ≤ end: a floor whose vertical
    acceleration is not linear in time, so a stack at rest on it is not at rest between samples."""

    def __init__(self, amplitude, omega, end):
        super().__init__(end)
        self.amplitude, self.omega = amplitude, omega

    def vertical_signal(self):
        # −B sin ωt = B cos(ωt + π/2)
        return Signal(KIND_HARMONIC, np.array([self.amplitude, self.omega, 0.5 * math.pi, self.end]), np.zeros(0),
                      np.zeros(0))

    def vertical_acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t <= self.end), -self.amplitude * np.sin(self.omega * t), 0.0)


@pytest.mark.parametrize("amplitude", [1.5, 1.01])
def test_flight_when_a_vertical_harmonic_first_reaches_minus_g(amplitude):
    """a_v = −B sin ωt with B = 1.5 g or 1.01 g (2 Hz): the stack leaves the floor where a_v
    first reaches −g, t* = arcsin(g/B)/ω, to 1e-9 s. The stack is at rest before, on a floor whose
    acceleration is not linear in time: its guards are not either, and the rest jump that
    holds between a record's samples does not apply (mutant fba704f8 took it over the whole
    harmonic, whose two ends leave the floor's force positive, and the stack never left it)."""
    omega = 4.0 * math.pi
    stack = _pedestal_and_statue(Friction(static=0.3, kinetic=0.25))
    r = simulate_stack(stack, _VerticalSine(amplitude * G, omega, 0.5), duration=0.5, options={"gravity": G})
    assert abs(r.blocks[0]["lifted_off_time"] - math.asin(1.0 / amplitude) / omega) < 1e-9


@pytest.mark.parametrize("ramp", [1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-3])
def test_flight_when_a_record_drops_the_floor_through_minus_g_along_a_steep_ramp(ramp):
    """A record whose vertical part falls from 0 to −1.5 g between its samples at t₀ = 0.5 s and
    t₀ + ramp: a_v = −k (t − t₀), k = 1.5 g/ramp, so every contact opens at t* = t₀ + ramp·2/3.
    Relative to the floor each block then rises as k τ³/6 (τ = t − t*) up to the ramp's end,
    t_r, and with the constant 0.5 g after it. With ramp = 1e-7 s the gap is 1e-17 m a quarter
    of the first step in: below the rounding of the positions, it was taken for a corner that
    closes again at once, reopened by the mode selection at the same instant 50 times, and the
    run stopped `inconsistent` at t*. With ramp = 1e-9 s the far corner's gap is 1e-19 m even at
    the end of the whole first step (3e-10 s): it stopped so until the opening was judged to
    first order from the interface's coordinates (2026-12-04)."""
    t0, a_end = 0.5, 1.5 * G
    motion = GroundMotion(time=np.array([0.0, t0, t0 + ramp, 0.8]), values=np.zeros(4),
                          vertical=np.array([0.0, 0.0, -a_end, -a_end]), name="drop")
    stack = _pedestal_and_statue(Friction(static=0.3, kinetic=0.25))
    r = simulate_stack(stack, motion, duration=0.8, options={"gravity": G})
    assert r.status == "still_moving"
    k, t_star, t_r = a_end / ramp, t0 + ramp * 2 / 3, t0 + ramp
    assert abs(r.blocks[0]["lifted_off_time"] - t_star) < 1e-12
    tau_r = t_r - t_star
    after = r.t > t_r
    s = r.t[after] - t_r
    rise = k * tau_r ** 3 / 6 + k * tau_r ** 2 / 2 * s + (a_end - G) / 2 * s ** 2
    for i, y0 in enumerate((0.25, 0.5 + 0.6)):
        assert np.max(np.abs(r.pose[after, i, 1] - (y0 + rise))) < 1e-9
        assert np.max(np.abs(r.pose[:, i, 2])) < 1e-12  # nothing turns


class _RampUnderAFallingLift(AbstractMotion):
    """a_h = c·t for t ≤ t2 (m/s²), and an upward a_v = A for t ≤ t1 < t2 that then drops to 0:
    at t1 the floor's grip μs·(g + a_v) falls by a jump while a_h goes on rising smoothly."""

    def __init__(self, c, t2, lift, t1, listed=True):
        self.c, self.t2, self.lift, self.t1, self.listed = c, t2, lift, t1, listed

    @property
    def duration(self):
        return self.t2

    @property
    def breakpoints(self):
        # unlisted, the lift's end is a jump of the vertical signal only (a user's motion that
        # lists the horizontal one's breakpoints): the solvers must find it there
        return np.array([0.0, self.t1, self.t2] if self.listed else [0.0, self.t2])

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t <= self.t2), self.c * t, 0.0)

    def signal(self):
        return Signal(KIND_RAMP, np.array([self.c, 0.0, 0.0, self.t2]), np.zeros(0), np.zeros(0))

    def vertical_signal(self):
        return Signal(KIND_RECTANGLE, np.array([self.lift, self.t1, 0.0, self.t1]), np.zeros(0), np.zeros(0))

    def vertical_acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t <= self.t1), self.lift, 0.0)


@pytest.mark.parametrize("listed", [True, False], ids=["listed", "not listed"])
@pytest.mark.parametrize("engine", ["stack", "two-body"])
def test_a_jump_of_the_floor_motion_that_breaks_the_grip_starts_the_slip_at_the_jump(engine, listed):
    """A squat block at rest under a_h = c t while the floor also accelerates upwards by A: its
    grip μs (g + A) holds up to t1 = 1 s (c t1 = 6 < 0.5·1.5 g), and at t1 the lift stops, so
    the grip μs g = 4.9 m/s² falls below c t1 at once. The slip starts at the jump, exactly, and
    then follows s̈ = μk g − c t from rest: s = μk g τ²/2 − c (t³ − t1³)/6 + c t1² τ/2, τ = t − t1.
    A block left stuck through the jump (its mode not decided again when the floor's formula
    changes) only starts to slip at the ramp's end, or never. The jump must be found whether or
    not the motion's ``breakpoints`` lists it (until 2026-12-03 an unlisted one was straddled by
    the steps, and the block never slipped). With μs = 2 it never slips and needs, at most, the
    ratio c t1/(g + A) just before the jump or c t2/g at the ramp's end (to 1e-12: the forces
    are those of a block at rest)."""
    c, t1, t2, mu_s, mu_k = 6.0, 1.0, 1.4, 0.5, 0.4
    motion = _RampUnderAFallingLift(c, t2, 0.5 * G, t1, listed)
    if engine == "stack":
        held = simulate_stack(Stack(blocks=(Block(width=1.0, height=0.2, mass=50.0),),
                                    interfaces=(Interface(friction=Friction(static=2.0, kinetic=2.0)),)),
                              motion, duration=t2, options={"gravity": G})
        need = held.summary()["interfaces"][0]["required_friction"]
    else:
        held = rocking.simulate(rocking.System(statue=rocking.Statue(
            width=1.0, height=0.2, mass=50.0, friction=Friction(static=2.0, kinetic=2.0))), motion, duration=t2,
            options={"gravity": G})
        need = held.summary()["required_top_friction"]
    assert need == pytest.approx(max(c * t1 / (1.5 * G), c * t2 / G), rel=1e-12)
    fr = Friction(static=mu_s, kinetic=mu_k)
    if engine == "stack":
        r = simulate_stack(Stack(blocks=(Block(width=1.0, height=0.2, mass=50.0),), interfaces=(Interface(friction=fr),)),
                           motion, duration=t2, options={"gravity": G})
        t, s, first = r.t, r.sliding[:, 0], r.blocks[0]["first_sliding_time"]
    else:
        r = rocking.simulate(rocking.System(statue=rocking.Statue(width=1.0, height=0.2, mass=50.0, friction=fr)),
                             motion, duration=t2, options={"gravity": G})
        t, s, first = r.t, r.u, r.summary()["first_sliding_time"]
    assert first is not None and abs(first - t1) < 1e-12
    assert np.all(s[t <= t1] == 0.0)
    after = t > t1
    tau = t[after] - t1
    expected = mu_k * G * tau**2 / 2 - c * (t[after] ** 3 - t1**3) / 6 + c * t1**2 * tau / 2
    assert np.max(np.abs(s[after] - expected)) < 1e-9 and expected.min() < -0.05


def test_statue_slipping_on_a_held_pedestal_moves_as_todays_sliding_block():
    """A squat statue that cannot rock, on a pedestal the floor holds (no floor slip, too wide to
    rock): its slip on the pedestal is today's single sliding block."""
    fr = Friction(static=0.25, kinetic=0.2)
    stack = Stack(blocks=(Block(width=3.0, height=0.3, mass=500.0), Block(width=1.0, height=0.5, mass=80.0)),
                  interfaces=(Interface(), Interface(friction=fr)))
    motion = rocking.SinePulse(amplitude=4.0, frequency=1.5)
    r = simulate_stack(stack, motion)
    ref = rocking.simulate(rocking.System(statue=rocking.Statue(width=1.0, height=0.5, mass=80.0, friction=fr)), motion)
    on = np.isin(np.round(ref.t, 9), np.round(r.t, 9))
    u = np.interp(ref.t, r.t, r.sliding[:, 1])
    assert np.max(np.abs(u - ref.u)[on]) < 1e-9
    assert abs(r.blocks[1]["residual_sliding"] - ref.summary()["residual_sliding"]) < 1e-9
    assert np.max(np.abs(r.sliding[:, 0])) == 0.0 and r.blocks[0]["first_rocking_time"] is None


def test_stack_rocks_as_one_composite_body():
    """While the upper interface sticks, the stack rocks about the floor corner as one rigid
    body: I_O θ̈ = m g r_x − m a_h r_y (r: centre of mass from the pivot, turned by θ), solved
    here with SciPy from the composite's own mass properties."""
    from scipy.integrate import solve_ivp

    m1, m2, b1, h1, b2, h2 = 40.0, 60.0, 0.3, 1.0, 0.5, 0.5
    stack = Stack(blocks=(Block(width=b1, height=h1, mass=m1), Block(width=b2, height=h2, mass=m2)),
                  interfaces=(Interface(), Interface()))
    amp, width = -0.3 * G, 0.25
    r = simulate_stack(stack, rocking.RectanglePulse(amplitude=amp, width=width), duration=4.0)
    assert r.blocks[0]["first_rocking_time"] == 0.0
    assert r.blocks[1]["first_rocking_time"] is None
    # composite about the right floor corner (the pulse pushes the stack towards +x)
    m = m1 + m2
    parts = [(m1, b1, h1, 0.5 * h1), (m2, b2, h2, h1 + 0.5 * h2)]
    pivot = np.array([0.5 * b1, 0.0])
    i_o = sum(mi * (bi**2 + hi**2) / 12 + mi * ((0 - pivot[0]) ** 2 + yi**2) for mi, bi, hi, yi in parts)
    rc = np.array([-pivot[0], sum(mi * yi for mi, _, _, yi in parts) / m])

    def rhs(t, s):
        th, w = s
        c, sn = np.cos(th), np.sin(th)
        rx, ry = c * rc[0] + sn * rc[1], -sn * rc[0] + c * rc[1]
        a_h = amp if t < width else 0.0
        return [w, (m * G * rx - m * a_h * ry) / i_o]

    impact = r.events[r.events[:, 2] == -1][0, 0]
    sel = (r.t > 0) & (r.t < impact - 1e-6)
    sol = solve_ivp(rhs, (0.0, impact), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True,
                    max_step=width / 4, t_eval=None)
    # (the pulse's end is a kink: integrate the two pieces separately for full accuracy)
    s1 = solve_ivp(rhs, (0.0, width), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    s2 = solve_ivp(rhs, (width, impact + 0.05), s1.y[:, -1], method="DOP853", rtol=1e-12, atol=1e-14,
                   dense_output=True, events=lambda t, s: s[0])
    th = np.where(r.t[sel] <= width, s1.sol(np.minimum(r.t[sel], width))[0], s2.sol(np.maximum(r.t[sel], width))[0])
    assert np.max(np.abs(r.pose[sel, 0, 2] - th)) < 1e-8
    assert np.max(np.abs(r.pose[sel, 1, 2] - th)) < 1e-8  # the top turns with it
    t_back = [t for t in s2.t_events[0] if t > width + 1e-6][0]
    assert abs(impact - t_back) < 1e-9
    # its largest tilt, where θ̇ = 0 between the pulse's end and the impact: the lower block's own
    # rotation and the upper block's absolute one (it does not turn on the lower)
    from scipy.optimize import brentq

    peak = s2.sol(brentq(lambda t: s2.sol(t)[1], width, t_back, xtol=1e-14))[0]
    assert abs(r.blocks[0]["peak_rotation"] - peak) < 1e-9
    assert abs(r.blocks[1]["peak_absolute_rotation"] - peak) < 1e-9
    assert r.blocks[1]["peak_rotation"] < 1e-12
    del sol


def test_similarity_law():
    """Lengths × λ, the pulse's period × √λ, the same acceleration: the same rotation history on
    the time axis scaled by √λ (Dimitrakopoulos & DeJong's similarity, for a stack)."""
    lam = 4.0

    def make(s):
        return Stack(blocks=(Block(width=0.8 * s, height=0.5 * s, mass=300.0),
                             Block(width=0.3 * s, height=1.2 * s, mass=100.0)),
                     interfaces=(Interface(friction=Friction(static=0.3, kinetic=0.25)), Interface()))

    a = simulate_stack(make(1.0), rocking.SinePulse(amplitude=3.0, frequency=1.0), duration=2.0,
                       options={"save_dt": 0.01})
    b = simulate_stack(make(lam), rocking.SinePulse(amplitude=3.0, frequency=1.0 / math.sqrt(lam)),
                       duration=2.0 * math.sqrt(lam), options={"save_dt": 0.01 * math.sqrt(lam)})
    n = min(len(a.t), len(b.t))
    grid_a = np.isclose(a.t[:n] / 0.01, np.round(a.t[:n] / 0.01), atol=1e-9)
    ta = a.t[grid_a]
    rot_b = np.interp(ta * math.sqrt(lam), b.t, b.rotation[:, 1])
    assert np.max(np.abs(a.rotation[grid_a, 1] - rot_b)) < 1e-8
    slide_b = np.interp(ta * math.sqrt(lam), b.t, b.sliding[:, 0])
    assert np.max(np.abs(lam * a.sliding[grid_a, 0] - slide_b)) < 1e-8 * lam


def _impact_times(r, ref):
    a = r.events[r.events[:, 2] == -1][:, 0]
    b = np.array([e.time for e in ref.impacts])
    assert len(a) == len(b) > 0
    return np.abs(a - b)


def test_single_block_under_a_record_matches_todays_solver():
    """A 0.3 × 1.2 m block under the first 15 s of Loma Prieta (Corralitos), rtol 1e-12: 168
    impacts in both solvers, the rotation within 1e-8 rad throughout (measured 2.6e-9), the first
    20 impacts within 1e-9 s (measured 4e-10 s). Later impacts drift apart to 7e-8 s: each
    solver is that far from its own run at rtol 1e-13 too (2e-8 s and 5e-8 s), so the sequence of
    168 impacts amplifies the tolerance, not a difference of model; the bound 2e-7 s holds that."""
    from rocking.io.records import read_record

    record = read_record("LomaPrieta1989_Corralitos_000").trimmed(15.0)
    system = rocking.System(statue=rocking.Statue(**STATUE))
    r, ref, dth, du = _compare(system, record, options=rocking.Options(rtol=1e-12, atol=1e-14))
    assert r.status == ref.status == "completed"
    dt = _impact_times(r, ref)
    assert len(dt) == 168
    assert dth < 1e-8 and du == 0.0
    assert np.max(dt[:20]) < 1e-9 and np.max(dt) < 2e-7


def test_statue_on_sliding_pedestal_under_a_record_matches_todays_solver():
    """The statue on a 300 kg pedestal (μs 0.3, μk 0.25) under Corralitos × 1.5: the pedestal
    slides 113 mm, the statue rocks (15 impacts) and overturns. Both solvers give the same
    impacts to 1e-9 s (measured 1.3e-13 s), the rotation to 1e-8 rad (3e-12), the sliding to
    1e-9 m (5e-15) and the fall to 1e-9 s."""
    from rocking.io.records import read_record

    record = read_record("LomaPrieta1989_Corralitos_000").trimmed(15.0).scaled(1.5)
    fr = Friction(static=0.3, kinetic=0.25)
    system = rocking.System(statue=rocking.Statue(**STATUE),
                            pedestal=rocking.Pedestal(mass=300.0, friction=fr, width=0.8, height=0.5))
    r, ref, dth, du = _compare(system, record, options=rocking.Options(rtol=1e-12, atol=1e-14))
    assert r.overturned and ref.overturned
    assert np.max(_impact_times(r, ref)) < 1e-9 and len(ref.impacts) == 15
    assert dth < 1e-8 and du < 1e-9
    assert abs(r.end_time - ref.end_time) < 1e-9


@pytest.mark.parametrize("name", ["10a", "10b", "11a", "11b", "12a"])
def test_paper_impact_law_matches_todays_solver(name):
    """impact = "paper" (the paper's Eq. 1, θ̇⁺ = r θ̇⁻ with the pedestal's velocity unchanged) on
    the statue on its pedestal, with the full normal force: today's results."""
    case = case_named(name)
    motion = paper_motion(case)
    system, options = variant_setup(case, "pedestal")
    options = dataclasses.replace(options, impact="paper", rtol=1e-12, atol=1e-14)
    r, ref, dth, du = _compare(system, motion, duration=motion.duration, options=options)
    assert r.status == ref.status
    assert dth < 1e-8 and du < 1e-8
    assert len(r.events[r.events[:, 2] == -1]) == len(ref.impacts) > 0


def test_paper_normal_force_is_refused_for_stacks():
    stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),))
    with pytest.raises(ValueError, match="normal_force"):
        simulate_stack(stack, rocking.SinePulse(amplitude=3.0, frequency=1.0), options={"normal_force": "paper"})


@pytest.mark.parametrize("mu", [0.5, 1.0])
def test_enough_top_friction_changes_nothing(mu):
    """A top face whose friction exceeds what the statue needs (0.26 here) gives the response of a
    top face that never slips: the same rocking, the same sequence of impacts to rest, no slip.
    (A rest rule that let the landing statue slip made it chatter for 60 s and gain energy.)"""
    def run(top):
        stack = _pedestal_and_statue(Friction(static=0.3, kinetic=0.25), top=top)
        return simulate_stack(stack, rocking.SinePulse(amplitude=2.8, frequency=1.0))

    never, frictional = run(None), run(Friction(static=mu, kinetic=0.8 * mu))
    assert never.status == frictional.status == "completed"
    assert frictional.summary()["impacts"] == never.summary()["impacts"] > 100
    assert np.max(np.abs(frictional.rotation - never.rotation)) < 1e-12
    assert frictional.blocks[1]["peak_sliding"] < 1e-12
    assert frictional.summary()["energy_balance_error"] < 1e-8
    assert np.all(np.diff(frictional.friction_loss) >= -1e-9)


def test_friction_never_creates_energy_in_a_three_block_stack():
    """Plinth, statue and vase, all three interfaces with friction: the friction loss never
    decreases, impacts never add energy, the ledger balances. (A slip that started against its own
    direction at a rounding-error rate was pushed along by its own friction: −200 J of 'loss'.)"""
    stack = Stack(blocks=(Block(width=1.0, height=0.6, mass=800.0), Block(width=0.4, height=1.4, mass=250.0),
                          Block(width=0.2, height=0.45, mass=8.0, offset=0.05)),
                  interfaces=(Interface(friction=Friction(static=0.6, kinetic=0.5)), Interface(friction=Friction(static=0.6)),
                              Interface(friction=Friction(static=0.4))))
    r = simulate_stack(stack, rocking.SinePulse(amplitude=4.0, frequency=1.5))
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    assert np.all(np.diff(r.friction_loss) >= -1e-9 * scale)
    assert np.all(r.events[r.events[:, 2] == -1][:, 5] >= -1e-12 * scale)
    assert np.max(np.abs(r.balance_error())) < 1e-8 * scale


def test_a_run_in_which_friction_gives_energy_is_not_a_result():
    """A slender light base (0.36 × 1.41 m, 14 kg) under a heavy squat block (154 kg) and a
    slender one, every face with friction, under Northridge (Rinaldi) × 0.394. From 2.2708 s no
    contact mode holds and the contacts are held (Painlevé's paradox, docs/theory/stack.md §5);
    a held slip keeps its friction −μk·σ·λn, which the tension turns round (−967 N at the floor by
    3.40 s, where every face slips and the base rocks past its tipping angle), so the friction
    "loss" falls: by 8e8 J within 30 ms, and the run ended `step_failed` with "block 2 went past the
    edge of block 1" in its verdict. The run checks itself: status `friction_gained`, from the
    hold's instant, and an undetermined verdict; the spectra count it as a solver failure."""
    from rocking.analyses.spectra import _STACK_SOLVER_FAILURES
    from rocking.io.records import read_record
    from rocking.stack.simulate import friction_gain_time

    stack = Stack(
        blocks=(Block(width=0.3593359169987903, height=1.4149052061073573, mass=13.654830043099937),
                Block(width=0.2642345055457874, height=0.3159680575759881, mass=153.80110813948698,
                      offset=0.05435585263933704),
                Block(width=0.2100146177908609, height=1.389662562614304, mass=12.575651032770635,
                      offset=0.043871471292464964)),
        interfaces=(Interface(friction=Friction(static=0.7186129614264132, kinetic=0.6967364822560813)),
                    Interface(friction=Friction(static=0.713292888053944, kinetic=0.707437733605769),
                              restitution=0.653490803412236),
                    Interface(friction=Friction(static=0.5930029891875824, kinetic=0.5063938746069581),
                              restitution=0.8898180869542534)))
    motion = read_record("Northridge1994_RinaldiReceivingSta_228").trimmed(15.0).scaled(0.39427486131494277)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    held = r.blocks[0]["tension_held_time"]
    assert held == pytest.approx(2.27082146, abs=1e-7)
    assert r.status == "friction_gained" and friction_gain_time(r) == pytest.approx(held, abs=1e-12)
    assert r.verdict.startswith("undetermined: from t = 2.271 s friction fed the motion"), r.verdict
    assert r.summary()["verdict"] == r.verdict
    assert any(w.startswith("From t = 2.271 s friction gave the stack energy") for w in build_stack_content(r).warnings)
    assert stack_verdict(r).startswith("Undetermined: from t = 2.271 s friction fed the motion")
    assert stack_verdict_class(r) == "stopped"
    assert np.min(np.diff(r.friction_loss)) < -1.0  # (J: what the check saw)
    assert "friction_gained" in _STACK_SOLVER_FAILURES


def test_friction_that_gives_energy_is_found_from_the_peak_its_loss_falls_from():
    """``friction_gain_time`` on a run's own arrays with a friction loss made up: rising, then
    falling from its peak at the 5th sample by 0.9e-6 and by 1.1e-6 of the energy scale
    (max |W_in| + max |E − E₀|, 1.0 J here): the first is the ledger's rounding (None), the second
    a gain, dated at the peak. A loss that only rises, or a run with no energy scale, gains nothing."""
    from rocking.stack.simulate import friction_gain_time

    stack = _pedestal_and_statue(Friction(static=0.3))
    r = simulate_stack(stack, rocking.SinePulse(amplitude=1.0, frequency=1.0), duration=0.1)
    n = len(r.t)
    assert n >= 8
    work = np.zeros(n)
    work[-1] = 1.0  # the energy scale: 1 J
    energy = np.full(n, r.initial_energy)
    rising = np.linspace(0.0, 0.1, n)
    base = dataclasses.replace(r, input_work=work, energy=energy, friction_loss=rising)
    assert friction_gain_time(base) is None
    for fall, want in ((0.9e-6, None), (1.1e-6, r.t[4])):
        loss = rising.copy()
        loss[5:] = loss[4] - fall
        got = friction_gain_time(dataclasses.replace(base, friction_loss=loss))
        assert got == want, (fall, got)
    still = dataclasses.replace(base, input_work=np.zeros(n), friction_loss=-rising)
    assert friction_gain_time(still) is None


@pytest.mark.parametrize("record, status", [
    ("Friuli1976_Tolmezzo_000", "completed"), ("ImperialValley1940_ElCentroArray9_180", "completed"),
    ("LomaPrieta1989_Corralitos_000", "completed"), ("Kobe1995_Takatori_000", "overturned"),
    ("Northridge1994_RinaldiReceivingSta_228", "overturned")])
def test_three_block_stack_under_a_full_scale_record_reaches_a_verdict(record, status):
    """Plinth, statue and off-centre vase under a whole record at full scale: the run reaches rest
    or a fall (Kobe: the vase slides past the statue's edge at 4.44 s and back at 5.19 s, then the
    statue falls at 6.19 s), with no endless switching at the statue's rocking threshold (the rest
    rule for slips) and no dead end at a record sample (the mode there is chosen as after an
    event); the ledger balances, friction and impacts only take energy."""
    from rocking.io.records import read_record

    stack = Stack(blocks=(Block(width=1.0, height=0.6, mass=800.0), Block(width=0.4, height=1.4, mass=250.0),
                          Block(width=0.2, height=0.45, mass=8.0, offset=0.05)),
                  interfaces=(Interface(friction=Friction(static=0.6, kinetic=0.5)), Interface(friction=Friction(static=0.6)),
                              Interface(friction=Friction(static=0.4, kinetic=0.32), restitution=0.7)))
    r = simulate_stack(stack, read_record(record))
    assert r.status == status, r.verdict
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    assert np.max(np.abs(r.balance_error())) < 1e-8 * scale
    assert np.all(np.diff(r.friction_loss) >= -1e-9 * scale) and np.all(np.diff(r.impact_loss) >= -1e-9 * scale)


def _deepest_sink(r) -> float:
    """The deepest any block's bottom corner goes below the top face of the block under it (or the
    floor), over the saved samples, m (negative: it sinks). Plain geometry of the saved poses and
    the block sizes: nothing of the engine."""
    deepest = math.inf
    blocks = r.stack.blocks
    for k, block in enumerate(blocks):
        x, y, th = (r.pose[:, k, c] for c in range(3))
        for xc in (-0.5 * block.width, 0.5 * block.width):
            # the corner (xc, −h/2) of a block turned by Θ clockwise about its centre
            px = x + xc * np.cos(th) - 0.5 * block.height * np.sin(th)
            py = y - xc * np.sin(th) - 0.5 * block.height * np.cos(th)
            if k == 0:
                gap = py
            else:
                below = blocks[k - 1]
                xb, yb, tb = (r.pose[:, k - 1, c] for c in range(3))
                u = (px - xb) * np.cos(tb) - (py - yb) * np.sin(tb)  # along the face below
                # (not a block turned to ±π/2 on the one below: its overturn, where it may lie
                # along that block's side, its corner at the face's end and far below it)
                gap = np.where((np.abs(u) <= 0.5 * below.width) & (np.abs(th - tb) < 0.5 * np.pi - 1e-9),
                               (px - xb) * np.sin(tb) + (py - yb) * np.cos(tb) - 0.5 * below.height, np.inf)
            deepest = min(deepest, float(np.min(gap)))
    return deepest


def test_a_corner_that_rebounds_by_less_than_rounding_lands_instead_of_sinking():
    """Plinth, statue and vase under Corralitos × 0.6. At 6.9125 s, after a run of ever smaller
    impacts, the vase's impact on the statue left the statue rocking at 3e-8 rad/s: its lifted
    corner rises by ~1e-16 m, below the rounding of the positions, so no sample of the gap was ever
    positive and the engine missed the corner's return. The statue then rocked on through the plinth
    (its corner 6 cm deep by 7.2 s, 33 cm at the end), and the vase 'fell' at 7.59 s. Such a gap
    now closes at once: the impact's rest rule lands the statue. Moreau–Jean time stepping finds no
    fall either."""
    from rocking.io.records import read_record
    from rocking.stack.timestepping import moreau_jean

    record = read_record("LomaPrieta1989_Corralitos_000").trimmed(30.0).scaled(0.6)
    stack = Stack(blocks=(Block(name="plinth", width=1.2, height=0.4, mass=400.0),
                          Block(name="statue", width=0.4, height=1.4, mass=150.0),
                          Block(name="vase", width=0.2, height=0.45, mass=8.0)),
                  interfaces=(Interface(friction=Friction(static=0.4, kinetic=0.3)),
                              Interface(friction=Friction(static=0.6, kinetic=0.5)),
                              Interface(friction=Friction(static=0.5, kinetic=0.4))))
    r = simulate_stack(stack, record, duration=record.duration, options={"save_dt": 0.01})
    # 1e-9 m: the positions carry rounding of ~1e-16 m; the sinking was 1e-5 m within 10 ms
    assert _deepest_sink(r) > -1e-9
    assert r.status == "completed", r.verdict
    # the independent solver, to 8.5 s (the statue is at rest from 7.2 s in both): no fall, and
    # peaks within 15 % (first order in dt: 0.0212/0.266 rad at 2e-4 s, 0.0215/0.269 at 1e-4 s)
    m = moreau_jean(stack, lambda t: float(record.acceleration(np.array([t]))[0]), t_end=8.5, dt=2e-4,
                    save_every=50)
    assert m.status == "completed"
    peak = np.max(np.abs(r.pose[:, :, 2]), axis=0)
    peak_m = np.max(np.abs(m.pose[:, :, 2]), axis=0)
    assert peak_m[1] == pytest.approx(peak[1], rel=0.15) and peak_m[2] == pytest.approx(peak[2], rel=0.15)


@pytest.mark.parametrize("record", ["Friuli1976_Tolmezzo_000", "Kobe1995_Takatori_000"])
def test_no_corner_sinks_into_the_face_below_under_a_record(record):
    """The same invariant over the whole of two full-scale runs of the plinth, statue and vase
    (one at rest, one where the statue falls; the samples up to the fall)."""
    from rocking.io.records import read_record

    stack = Stack(blocks=(Block(width=1.0, height=0.6, mass=800.0), Block(width=0.4, height=1.4, mass=250.0),
                          Block(width=0.2, height=0.45, mass=8.0, offset=0.05)),
                  interfaces=(Interface(friction=Friction(static=0.6, kinetic=0.5)), Interface(friction=Friction(static=0.6)),
                              Interface(friction=Friction(static=0.4, kinetic=0.32), restitution=0.7)))
    r = simulate_stack(stack, read_record(record))
    assert _deepest_sink(r) > -1e-9


def _random_stacks(seed: int, count: int):
    """``count`` random stacks of one to three blocks (sizes 0.15–1.6 m, masses 3–1000 kg, offsets,
    friction on four interfaces in five, some restitutions), each under a random sine pulse, harmonic
    or 15 s of a record scaled by 0.3–1.2."""
    from rocking.io.records import read_record

    names = ("LomaPrieta1989_Corralitos_000", "Friuli1976_Tolmezzo_000", "Kobe1995_Takatori_000",
             "Northridge1994_RinaldiReceivingSta_228", "ImperialValley1940_ElCentroArray9_180")
    records = [read_record(name).trimmed(15.0) for name in names]
    rng = np.random.default_rng(seed)
    for _ in range(count):
        blocks, interfaces = [], []
        for k in range(int(rng.integers(1, 4))):
            width, height, mass = rng.uniform(0.15, 1.2), rng.uniform(0.2, 1.6), 10 ** rng.uniform(0.5, 3)
            offset = rng.uniform(-0.1, 0.1) if k else 0.0
            blocks.append(Block(width=float(width), height=float(height), mass=float(mass), offset=float(offset)))
            mu_s = float(rng.uniform(0.2, 0.8))
            friction = Friction(static=mu_s, kinetic=mu_s * float(rng.uniform(0.7, 1.0))) if rng.random() < 0.8 else None
            restitution = float(rng.uniform(0.5, 0.95)) if rng.random() < 0.3 else None
            interfaces.append(Interface(friction=friction, restitution=restitution))
        try:
            stack = Stack(blocks=tuple(blocks), interfaces=tuple(interfaces))
        except ValueError:  # a block that does not rest on the one below
            stack = None
        kind = rng.integers(0, 3)
        if kind == 0:
            motion = rocking.SinePulse(amplitude=float(rng.uniform(1, 8)), frequency=float(rng.uniform(0.5, 3)))
        elif kind == 1:
            motion = rocking.Harmonic(amplitude=float(rng.uniform(1, 6)), frequency=float(rng.uniform(0.5, 3)),
                                      cycles=int(rng.integers(2, 6)))
        else:
            motion = records[int(rng.integers(0, 5))].scaled(float(rng.uniform(0.3, 1.2)))
        if stack is not None:
            yield stack, motion


def _assert_the_engines_invariants(stack, motion, r):
    """What every run of the engine must keep: no corner sunk into the face below (1e-5 m), the
    ledger balanced where the run reached a verdict (3e-7 of its energy scale), no impact and no
    friction giving energy."""
    assert _deepest_sink(r) > -1e-5, (stack, motion, r.verdict)
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    if r.status in ("completed", "overturned"):
        assert np.max(np.abs(r.balance_error())) <= 3e-7 * scale, (stack, motion)
    # no impact creates energy: the worst is 5e-10 of the scale (the impulse solve's accuracy,
    # 1e-9 of the energy before the impact); before 2026-11-27, 4e-5 (a restitution couple)
    # and 4e-6 (a slow slip stopped, or a block landed, by the rest rules)
    impacts = r.events[r.events[:, 2] == -1]
    assert len(impacts) == 0 or impacts[:, 5].min() >= -1e-8 * scale, (stack, motion)
    # nor does friction, but where a slip held in tension is pushed on by its own (seed 4's
    # 64th stack, 1e-4 of its scale): that run is no result (test_a_run_in_which_friction_…)
    if r.status != "friction_gained":
        assert np.all(np.diff(r.friction_loss) >= -1e-9 * scale), (stack, motion)


def _jumping_floor(rng: np.random.Generator):
    """A floor motion whose acceleration jumps, which ``_random_stacks``'s never does: a rectangle
    pulse, a one-cosine pulse, a cos harmonic (each jumps at its start, the pulses at their end
    too) or a sine pulse with a phase; amplitudes 1–8 m/s² of either sign."""
    kind = int(rng.integers(0, 4))
    a = float(rng.uniform(1, 8)) * (1 if rng.random() < 0.5 else -1)
    if kind == 0:
        return rocking.RectanglePulse(amplitude=a, width=float(rng.uniform(0.1, 1.5)))
    if kind == 1:
        return rocking.CosinePulse(amplitude=a, frequency=float(rng.uniform(0.5, 3)))
    if kind == 2:
        return rocking.Harmonic(amplitude=a, frequency=float(rng.uniform(0.5, 3)), cycles=int(rng.integers(2, 5)),
                                form="cos")
    return rocking.SinePulse(amplitude=abs(a), frequency=float(rng.uniform(0.5, 3)), phase=float(rng.uniform(0.3, 3.0)))


def test_a_vase_set_rocking_by_the_block_under_it_rocks_on_from_its_onset():
    """Seed 6's 57th random stack (a 118 kg squat base, a 6 kg block 0.77 m wide on it, a 21 kg
    vase on top) under a cos harmonic of 1.96 m/s²: the floor's jump at t = 0 sets the middle
    block and the vase rocking on the base as one (their threshold is 1.91 m/s²), and at
    3.7042 ms the vase's far corner unloads: it rocks on the middle block from rest. Its force
    there crossed zero at a finite rate, so its rotation grows from the onset as (t − t₀)³: at the
    samples 5 and 10 ms, |φ| ≈ 1.4e-9 and 2.0e-7 rad, a ratio within a factor 2 of
    ((5 − 3.7042)/(10 − 3.7042))³ = 0.0087 (0.0067). Mutant 90474d2e (the window of a dip search
    begun a sample early, at the step's start where the onset had just put the guard at zero) found
    a landing 57 ns after the onset and kept the vase flat for 10 ms (seen, compiled copy)."""
    for stack, motion in _random_stacks(6, 57):
        pass
    assert isinstance(motion, rocking.Harmonic) and motion.form == "cos"
    r = simulate_stack(stack, motion, duration=0.015, options={"save_dt": 0.005})
    onset = r.events[0, 0]
    assert r.events[:, :4].tolist() == [[onset, 2, engine.G_OTHER, 1]] and onset == pytest.approx(3.7042e-3, abs=1e-7)
    after = r.t > onset
    assert np.all(r.normal_state[after, 2] == 1)
    phi = {round(float(t), 6): abs(p) for t, p in zip(r.t, r.rotation[:, 2])}
    assert 0 < phi[0.005] < phi[0.01] < 1e-5
    cubic = ((0.005 - onset) / (0.01 - onset)) ** 3
    assert 0.5 * cubic < phi[0.005] / phi[0.01] < 2.0 * cubic


@pytest.mark.parametrize("seed", [2, 11])
def test_random_stacks_under_floors_that_jump_keep_the_engines_invariants(seed):
    """The random stacks of seeds 2 and 11 under floors that jump (``_jumping_floor``, drawn with
    seed 1000 + seed): the mode is decided again at every jump, and a contact held in tension can
    be released between events (5 of 1800 runs of seeds 1–12 do, 2 here each). Every run keeps
    the invariants of the test below: no corner sunk, the ledger balanced, no impact and no
    friction giving energy, no face needing more than its μs (bench/stack_invariants.py
    ``--floors jumping`` runs all twelve seeds: none broke one beyond a run already undetermined).
    A ratchet on the undetermined runs: seed 2 has 2 still moving (slow towers), 1 max_events."""
    floors = np.random.default_rng(1000 + seed)
    statuses = []
    for stack, _ in _random_stacks(seed, 150):
        motion = _jumping_floor(floors)
        r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
        statuses.append(r.status)
        _assert_the_engines_invariants(stack, motion, r)
        for summary, interface in zip(r.interfaces, stack.interfaces):
            if interface.friction is not None:
                assert summary["required_friction"] <= interface.friction.mu_s * (1 + 1e-6), (stack, motion)
    assert statuses.count("completed") > 90 and statuses.count("overturned") > 30
    assert len(statuses) - statuses.count("completed") - statuses.count("overturned") <= {2: 3, 11: 0}[seed]


@pytest.mark.parametrize("seed", [1, 4])
def test_no_corner_sinks_into_the_face_below_in_random_stacks(seed):
    """150 random stacks per seed. Before the fix above, 11 of the 150 of seed 1 had a block
    rocking through the one below (0.2 to 1 m deep) and reported it "overturned". The deepest was
    1.8e-6 m until 2026-11-27 (a chattering sequence of micro-impacts), 7e-9 m since (seed 1), so
    1e-5 m; the old failures were 1e4 times deeper. A run may end undetermined (one in 300 today:
    max_events), never with an exception. Where a run reaches a verdict its ledger balances to
    3e-7 of its energy scale: the worst today is 6.1e-8 (seed 1, 314 events), the next 7e-9; until
    the energy of an impact's exact pose was booked (2026-11-27) it was 2.7e-6 (seed 4, 949 events)
    (docs/theory/stack.md §9)."""
    statuses = set()
    undetermined = 0
    for stack, motion in _random_stacks(seed, 150):
        r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
        statuses.add(r.status)
        undetermined += r.status not in ("completed", "overturned")
        _assert_the_engines_invariants(stack, motion, r)
    assert {"completed", "overturned"} <= statuses
    # a ratchet: 7 and 10 until the impact rules of 2026-11-24 (the tests below), 4 and 6 until
    # impacts were kept from creating energy and the rest landing given a fallback (2026-11-27),
    # 1 and 4 until every pulling contact was held and the rest rules kept a slow corner closed and
    # landed any slow rocking interface (2026-11-27, later), 0 and 1 since; seed 4's 64th run is
    # `friction_gained` since 2026-12-07 (it gave a verdict, its friction having fed the motion)
    assert undetermined <= {1: 0, 4: 2}[seed]


def test_the_state_after_each_event_is_the_mode_the_run_goes_on_in():
    """The event table (``events``, the report's "state after" column) gives for each event the
    state of its interface after it; an interface's last row at an instant must be the state the
    run goes on in, the saved sample at that instant (saved after the event), over 30 random
    stacks (6963 such rows). Until 2026-12-07 an impact's row kept the impact's own outcome, which
    the choice of the mode after it may change: seed 1's 16th stack read "rocking, stuck" of a
    floor face that went on slipping, its 26th "flat" of a base that rocked on (570 of 77690
    impacts of seeds 1 and 2). The run's last event (an overturn) ends it before any choice."""
    rows = 0
    for stack, motion in _random_stacks(1, 30):
        r = simulate_stack(stack, motion)
        last = {}
        for row in r.events:
            if int(row[2]) not in (engine.G_OVERTURN, engine.G_OVERLAP):
                last[row[0], int(row[1])] = row[3:5].astype(int)
        for (t, k), (normal, tangential) in last.items():
            after = np.nonzero(r.t == t)[0][-1]
            assert (r.normal_state[after, k], r.tangential_state[after, k]) == (normal, tangential), (stack, t, k)
        rows += len(last)
    assert rows > 6000


@pytest.mark.parametrize("seed", [1, 4, 7, 9])
def test_no_interface_that_can_slip_reports_needing_more_than_its_mu_s(seed):
    """An interface that can slip slips once its forces, or an impact's impulse, would need more
    than μs: the friction it needed while it stuck (``required_friction``, impacts included) is
    at most μs, to the 1e-6 the report's check allows, on the 975 slippable interfaces of 600
    random stacks. (The report fails an interface whose need exceeds μs as a contradiction of the
    model: it never happens here.) Seeds 7 and 9 each had a micro-impact stuck within the impulse
    solve's slack booked at its solved ratio, 0.2 % and 0.07 % above μs, until 2026-12-07."""
    checked = 0
    for stack, motion in _random_stacks(seed, 150):
        r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
        for summary, interface in zip(r.interfaces, stack.interfaces):
            if interface.friction is not None:
                checked += 1
                assert summary["required_friction"] <= interface.friction.mu_s * (1 + 1e-6), (stack, motion)
    assert checked == {1: 246, 4: 241, 7: 242, 9: 246}[seed]


def test_the_library_measures_a_sinking_corner_as_the_independent_geometry_does():
    """rocking.stack.simulate.deepest_sink (the check every run now makes on itself) against
    ``_deepest_sink`` here, on random stacks and on the same poses with a block turned into the one
    below: equal to rounding (1e-15 m), and 0 where nothing sinks."""
    from rocking.stack.simulate import deepest_sink

    sunk_depths = []
    for stack, motion in list(_random_stacks(2, 40))[::4]:
        r = simulate_stack(stack, motion, options={"save_dt": 0.01, "max_events": 2000})
        assert deepest_sink(stack, r.pose) == pytest.approx(max(0.0, -_deepest_sink(r)), abs=1e-15)
        if stack.n >= 2:
            turned = r.pose.copy()
            turned[:, -1, 2] += 0.05  # the top block tilted about its centre: one corner dips
            sunk = dataclasses.replace(r, pose=turned)
            depth = deepest_sink(stack, turned)
            assert depth == pytest.approx(max(0.0, -_deepest_sink(sunk)), rel=1e-12, abs=1e-15)
            sunk_depths.append(depth)
    # (a corner that dips beyond the end of the face below is not on it: some give 0)
    assert sum(d > 1e-3 for d in sunk_depths) >= 2


def test_the_sink_check_sees_the_corners_of_drums_of_equal_width():
    """A column of drums of one width: level, the upper drum's corners stand exactly on the ends of
    the face below (|u| = b to the bit), so they are on it and a sink there counts: 1 mm down gives
    1 mm (to the rounding of 0.75 m, 1e-15 m). Moved 1e-9 m sideways, one corner is off the face
    and the other still on it; a drum 2e-9 m wider has both off (nothing is counted). Tilted either
    way, the corner on that side dips (each corner is looked at, not one twice)."""
    from rocking.stack.simulate import deepest_sink

    def column(upper_width):
        return Stack(blocks=(Block(width=0.4, height=0.5, mass=100.0),
                             Block(width=upper_width, height=0.5, mass=100.0)),
                     interfaces=(Interface(), Interface()))

    sunk = np.array([[[0.0, 0.25, 0.0], [0.0, 0.75 - 1e-3, 0.0]]])
    assert deepest_sink(column(0.4), sunk) == pytest.approx(1e-3, abs=1e-15)
    moved = sunk.copy()
    moved[0, 1, 0] = 1e-9
    assert deepest_sink(column(0.4), moved) == pytest.approx(1e-3, abs=1e-15)
    assert deepest_sink(column(0.4 + 2e-9), sunk) == 0.0
    # turned either way about its centre, level with the face below: the corner on the side it
    # turns to dips by b·sin|θ| − (h/2)(1 − cos θ), the other rises
    for theta in (0.01, -0.01):
        tilted = np.array([[[0.0, 0.25, 0.0], [0.0, 0.75, theta]]])
        dip = 0.2 * math.sin(abs(theta)) - 0.25 * (1.0 - math.cos(theta))
        assert deepest_sink(column(0.4), tilted) == pytest.approx(dip, rel=1e-12)


@pytest.mark.parametrize("theta", [0.4, -0.4, 1.2, -1.2, 0.5 * math.pi - 1e-8])
def test_the_sink_check_sees_a_block_tilted_far_on_the_one_below(theta):
    """A 0.4 × 1 m block rocking on a 2 m wide plinth, tilted by θ relative to it (up to a hair
    short of its overturn, π/2 − 1e-8), with its low corner put 1 mm below the plinth's top face
    at x = 0.1 m: the check counts 1 mm (to 1e-12 m). Only a block turned to π/2 on the one below
    (to 1e-9 rad: its overturn, where it may lie along that block's side) is skipped. Kills
    bench/MUTATION.md's 58d4caef and 5c8cb107 (thirty-fourth round), which skipped every tilt
    beyond 0.16 and 0.57 rad."""
    from rocking.stack.simulate import deepest_sink

    stack = Stack(blocks=(Block(width=2.0, height=0.5, mass=500.0), Block(width=0.4, height=1.0, mass=100.0)),
                  interfaces=(Interface(), Interface()))
    b, h = 0.2, 0.5
    side = math.copysign(1.0, theta)  # the corner (side·b, −h) dips, Θ clockwise
    x = 0.1 - side * b * math.cos(theta) + h * math.sin(theta)
    y = 0.5 - 1e-3 + side * b * math.sin(theta) + h * math.cos(theta)
    pose = np.array([[[0.0, 0.25, 0.0], [x, y, theta]]])
    assert deepest_sink(stack, pose) == pytest.approx(1e-3, abs=1e-12)
    overturned = pose.copy()
    overturned[0, 1, 2] = side * 0.5 * math.pi
    overturned[0, 1, 0] = 0.1 + side * h  # the same corner, 1 mm down, at the overturn
    overturned[0, 1, 1] = 0.5 - 1e-3 + b
    assert deepest_sink(stack, overturned) == 0.0


def test_a_run_whose_blocks_overlap_gives_no_verdict(monkeypatch):
    """Should the engine lose a contact again (a corner going on through the face below, as before
    the fix of 2026-11-24), the run is not believed: status "lost_contact", an undetermined
    verdict, and the spectra count it as a solver failure (``failed_runs``, warned; counted as
    safe, as every solver failure is there)."""
    from rocking.stack import simulate as sim

    stack = _pedestal_and_statue(Friction(static=0.3))
    motion = rocking.SinePulse(amplitude=1.0, frequency=1.0)  # nothing moves: 1 < 0.25 g
    honest = simulate_stack(stack, motion)
    assert honest.status == "completed" and sim.deepest_sink(stack, honest.pose) == 0.0
    integrate = engine.integrate

    def sinking(*args):
        out = list(integrate(*args))
        samples = out[2].copy()
        # the statue's Θ in the last saved rows: turned by 0.01 rad about its centre (its corner
        # 1.5 mm deep; 0.1 mm is the limit)
        samples[-3:, 1 + engine.N_BLOCK_COLS + 2] += 0.01
        out[2] = samples
        return tuple(out)

    monkeypatch.setattr(engine, "integrate", sinking)
    r = simulate_stack(stack, motion)
    assert r.status == "lost_contact"
    assert r.verdict.startswith("undetermined: a block went into the one below it")
    assert r.summary()["verdict"] == r.verdict
    from rocking.analyses.spectra import _STACK_SOLVER_FAILURES

    assert "lost_contact" in _STACK_SOLVER_FAILURES


SQUAT_ON_PLINTH_MU = 0.1


def _squat_on_plinth(mu=SQUAT_ON_PLINTH_MU, offset=0.0):
    """A squat block (0.4 × 0.2 m, 20 kg) on a held plinth 0.6 m wide, friction μ between them."""
    return Stack(blocks=(Block(width=0.6, height=0.3, mass=500.0), Block(width=0.4, height=0.2, mass=20.0, offset=offset)),
                 interfaces=(Interface(), Interface(friction=Friction(static=mu, kinetic=mu))))


def test_a_block_sliding_to_the_edge_stops_the_run_undetermined_when_asked():
    """The squat block slides on its plinth under a constant 0.5 g, μ = 0.1: its corner reaches the
    plinth's edge when ½(A − μg)t² = 0.1 m. With ``stop_at_edge`` (the conservative criterion) the
    run stops there, exactly, and says undetermined rather than safe."""
    a, mu = 0.5 * G, SQUAT_ON_PLINTH_MU
    stack = _squat_on_plinth()
    r = simulate_stack(stack, rocking.RectanglePulse(amplitude=a, width=2.0), duration=2.0,
                       options={"gravity": G, "stop_at_edge": True})
    assert r.status == "slid_past_edge"
    assert abs(r.end_time - math.sqrt(2 * 0.1 / (a - mu * G))) < 1e-9
    assert r.verdict == (f"undetermined: {stack.names[1]} slid to the edge of {stack.names[0]} at t = {r.end_time:.3f} s; "
                         "the model stops there (treat it as falling off)")
    assert abs(r.blocks[1]["residual_sliding"] + 0.1) < 1e-9


def test_a_block_slides_past_the_edge_tips_over_it_and_falls_off():
    """The same block, followed past the edge (the default). Its corner passes the plinth's edge at
    ½(A − μg)t² = 0.1 m; it then slides flat on the plinth's corner by the same law (the normal
    force is still its weight), until the resultant of the normal forces, which the friction at
    its base holds μ·h/2 = 0.01 m behind the centre, reaches that corner: at a slide of
    b_plinth − μh/2 = 0.29 m it starts to rock about the corner (to 1e-9 s), tips and falls off.
    The independent Moreau–Jean solver (Δt = 1e-4 s, first order; at 5e-5 s the differences
    halve) gives the same slide to 1e-7 m and rotation to 1e-6 rad at 0.30–0.48 s (measured
    8e-9 m and 3e-7 rad); the energy ledger balances."""
    from rocking.stack.timestepping import moreau_jean

    a, mu, h = 0.5 * G, SQUAT_ON_PLINTH_MU, 0.2
    stack = _squat_on_plinth()
    r = simulate_stack(stack, rocking.RectanglePulse(amplitude=a, width=2.0), duration=1.0,
                       options={"gravity": G, "save_dt": 0.01})
    edge, rock, fall = r.events[:, :3]
    assert edge[1:].tolist() == [1, 5] and abs(edge[0] - math.sqrt(2 * 0.1 / (a - mu * G))) < 1e-9
    assert rock[1:].tolist() == [1, 1] and abs(rock[0] - math.sqrt(2 * (0.3 - mu * h / 2) / (a - mu * G))) < 1e-9
    before = r.t <= rock[0]
    slide = r.pose[:, 1, 0] - r.pose[:, 0, 0]
    np.testing.assert_allclose(slide[before], -0.5 * (a - mu * G) * r.t[before] ** 2, rtol=0, atol=1e-9)
    assert not np.any(r.rotation[before, 1])
    assert r.status == "overturned" and r.blocks[1]["overturned"] and r.blocks[1]["overturn_time"] == fall[0]
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    assert np.max(np.abs(r.balance_error())) < 1e-9 * scale

    ts = np.array([0.30, 0.40, 0.44, 0.48])
    m = moreau_jean(stack, lambda t: a, t_end=0.49, dt=1e-4, gravity=G)
    slide_mj = np.interp(ts, m.t, m.pose[:, 1, 0] - m.pose[:, 0, 0])
    rotation_mj = np.interp(ts, m.t, m.pose[:, 1, 2] - m.pose[:, 0, 2])
    assert np.max(np.abs(slide_mj - np.interp(ts, r.t, slide))) < 1e-7
    assert np.max(np.abs(rotation_mj - np.interp(ts, r.t, r.rotation[:, 1]))) < 1e-6
    assert np.interp(0.48, r.t, r.rotation[:, 1]) < -0.07  # it is tipping over the edge


def test_a_block_pushed_partly_past_the_edge_stops_there_overhanging():
    """A push of 0.5 g for 0.35 s with μ = 0.3: the block slides ½(A − μg)w² while pushed, then
    v²/(2μg) more, 0.2003 m in all: its corner passes the plinth's edge (at 0.1 m), and it stops,
    overhanging by 0.1 m, at w + v/(μg), short of tipping (which would start at 0.3 − μh/2 =
    0.27 m). Both to 1e-9, and it ends at rest, upright."""
    a, mu, w = 0.5 * G, 0.3, 0.35
    r = simulate_stack(_squat_on_plinth(mu), rocking.RectanglePulse(amplitude=a, width=w), duration=1.5,
                       options={"gravity": G})
    v = (a - mu * G) * w
    travel = 0.5 * (a - mu * G) * w**2 + v**2 / (2 * mu * G)
    assert r.status == "completed" and not r.overturned
    assert abs(r.blocks[1]["residual_sliding"] + travel) < 1e-9
    assert r.events[:, 2].tolist() == [5, 2] and abs(r.events[-1, 0] - (w + v / (mu * G))) < 1e-9
    assert r.blocks[1]["peak_rotation"] == 0.0
    # what the user is told: it stayed on, but went past the edge (rocking run, the web page)
    from rocking.io.stack_output import fall_text

    assert r.blocks[1]["past_edge_time"] == r.events[0, 0] and r.blocks[0]["past_edge_time"] is None
    assert fall_text(r.summary(), 1) == f"no (past the edge below at {r.events[0, 0]:.3f} s)"
    assert fall_text(r.summary(), 0) == "no"
    names = r.stack.names
    assert r.verdict == (f"did not overturn; at rest at t = {r.end_time:.3f} s; "
                         f"{names[1]} went past the edge of {names[0]} at t = {r.events[0, 0]:.3f} s")


@pytest.mark.parametrize("delta", [3e-5, 1e-4, 1e-2])
def test_a_block_a_hair_wider_than_its_plinth_slides_over_both_edges_tips_and_falls_off(delta):
    """A squat block 2δ wider than its held plinth (0.6 m), placed 0.05 m right of centre so that
    it overhangs the right edge, pushed by a constant 0.5 g with μ = 0.1: relative to the plinth it
    slides left by ½(A − μg)t². Its left corner passes the plinth's left edge at a slide of
    0.05 − δ, its right corner comes back over the right edge at 0.05 + δ (both ends are then the
    block's own corners), and it starts to rock about the left edge at 0.05 + b_plinth − μh/2
    (the law of the test above), each to 1e-9 s. It falls off when its far corner slides onto
    that edge (the overlap of the faces ends): there the fall's row puts that corner on the
    edge to 1e-9 m. (Until 2026-12-04 the corner's gap was found closing at that instant with
    δ = 30 µm and 1 cm, the rounding's choice between two guards that vanish together, and an
    impact followed: repeated at one instant until the run stopped `inconsistent`, or a fall
    one impact late; with δ = 1e-8 m or 0.3 mm the overlap came first.)"""
    a, mu, h, o0, bl = 0.5 * G, 0.1, 0.2, 0.05, 0.3
    stack = Stack(blocks=(Block(width=2 * bl, height=0.3, mass=500.0),
                          Block(width=2 * (bl + delta), height=h, mass=20.0, offset=o0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=mu, kinetic=mu))))
    r = simulate_stack(stack, rocking.RectanglePulse(amplitude=a, width=2.0), duration=1.0,
                       options={"gravity": G, "save_dt": 0.01})
    assert r.status == "overturned" and r.blocks[1]["overturned"], r.verdict
    assert r.events[:, 1:3].tolist() == [[1, 5], [1, 5], [1, 1], [1, 6]]
    assert r.events[3, 3:].tolist() == [1, 1, 0.0]  # it falls rocking and slipping; no impact loss
    c = a - mu * G
    expected = [math.sqrt(2 * s / c) for s in (o0 - delta, o0 + delta, o0 + bl - mu * h / 2)]
    np.testing.assert_allclose(r.events[:3, 0], expected, rtol=0, atol=1e-9)
    fall = np.nonzero(r.t == r.events[3, 0])[0][-1]
    x, y, theta = r.pose[fall, 1] - r.pose[fall, 0]
    x_right = x + (bl + delta) * math.cos(theta) - 0.5 * h * math.sin(theta)
    assert abs(x_right + bl) < 1e-9 and theta < -0.1
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    assert np.max(np.abs(r.balance_error())) < 1e-9 * scale


def _with_reversed_vertical(name, scale, cv):
    """15 s of record ``name`` scaled by ``scale``, with a vertical part cv × its horizontal one
    reversed in time (the vertical motion of the random scans that found the cases below)."""
    from rocking.io.records import read_record

    base = read_record(name).trimmed(15.0).scaled(scale)
    return dataclasses.replace(base, vertical=cv * base.values[::-1].copy())


def _stack_from(blocks, interfaces):
    """A Stack from rows (width, height, mass, offset) and (μs, μk, restitution); μs None: the
    interface never slips."""
    return Stack(blocks=tuple(Block(width=w, height=h, mass=m, offset=o) for w, h, m, o in blocks),
                 interfaces=tuple(Interface(friction=None if mu_s is None else Friction(static=mu_s, kinetic=mu_k),
                                            restitution=r) for mu_s, mu_k, r in interfaces))


def test_a_corner_at_one_edge_is_not_taken_for_one_passing_it_when_the_other_corner_passes_the_other_edge_first():
    """A random stack (seed 7's 48th of the tests' random stacks) whose middle block is 0.11 mm
    wider than the one below, under 15 s of Kobe with a vertical part (0.34 × the horizontal one
    reversed). Sliding at 0.6 m/s it passes the left edge below with its left corner, and 0.19 ms
    later its right corner comes back over the right edge. The step after the first event was
    0.9 ms long: the edge guard (the nearer of the two ends) started at zero and was negative at
    the step's first sample, which the rule for a block placed flush with an edge read as a
    corner passing the edge at once. The same event repeated at one instant until the run
    stopped `inconsistent` at 6.106 s. Now the run reaches a verdict, and each edge event puts its
    corner on its edge to 1e-12 m (the blocks are flat there)."""
    motion = _with_reversed_vertical("Kobe1995_Takatori_000", 0.7851322717636504, 0.33944210843360667)
    stack = _stack_from(
        [(0.6791974372606197, 0.33512173685356983, 4.118251142691979, 0.0),
         (0.6793097281409662, 0.809542978538724, 755.4417735509004, 0.08975440614676766),
         (0.8049402248900218, 1.221762179059261, 87.12563490620727, -0.05798861272083977)],
        [(0.7942553144972426, 0.5689631202166588, None), (0.27498060696427784, 0.2261018641195579, None),
         (0.6906592572685667, 0.6281858657195952, 0.7119911659251734)])
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 100000})
    assert r.status == "completed", r.verdict
    edges = r.events[r.events[:, 2] == 5]
    assert edges[:, 1].tolist() == [1, 1] and 6.1 < edges[0, 0] < edges[1, 0] < 6.11
    bu, bl = 0.5 * stack.blocks[1].width, 0.5 * stack.blocks[0].width
    for t_edge, side in zip(edges[:, 0], (-1, 1)):
        row = np.nonzero(r.t == t_edge)[0][0]
        x, _, theta = r.pose[row, 1] - r.pose[row, 0]
        assert theta == 0.0 and r.rotation[row, 1] == 0.0
        assert abs(x + side * bu - side * bl) < 1e-12


@pytest.mark.parametrize("held_pedestal", [False, True], ids=["on the floor", "on a held pedestal"])
def test_a_slender_base_under_heavy_blocks_starts_to_rock_though_its_tilt_is_below_the_rounding_of_its_corner(
        held_pedestal):
    """A random stack (seed 2's 111th of the tests' random stacks): a base 0.2 m wide and 1.36 m
    tall under 350 kg, at rest under El Centro × 0.38 with a vertical part (0.84 × the horizontal
    one reversed) until its rocking starts at 1.72 s with zero acceleration. Its tilt grows as τ³:
    1.6e-16 rad after the first 1.6 µs step, where its far corner's height, a difference of
    positions of 1 m, read 0.0 m. The corner was taken for one that never opened and landed, the
    mode selection set the base rocking again at the same instant, 50 times, and the run stopped
    `inconsistent`. Now the opening is judged to first order from the interface's own
    coordinates, and the base rocks and falls.

    The same stack on a pedestal 2 m wide, 0.5 m tall and 2000 kg that never slips and never
    rocks: the base now starts to rock on the pedestal's face, and the rule must hold above the
    floor's interface too (the slot test of `_opened_below_rounding`): with it turned off there,
    the run stops `inconsistent` at 1.720 s (mutant c08d715d, seen on a copy of the source, and so
    with the pedestal 0.2, 0.25 and 1.0 m tall).

    Against the independent Moreau–Jean solver, which shares no physics code with the engine
    (Δt = 2e-4 s; at 1e-4 s its rotation moves by 1.1e-5 rad at 3 s, the engine's differs by 1e-5
    from the one and 1e-6 from the other, on the floor and on the pedestal alike): the base's
    rotation to 5e-5 rad at 2 to 3 s, while every other block stays flat."""
    from rocking.stack.timestepping import moreau_jean

    motion = _with_reversed_vertical("ImperialValley1940_ElCentroArray9_180", 0.38121624252951664, 0.8422139441780945)
    blocks = [(0.1954897880328545, 1.357399061491634, 16.68342425076199, 0.0),
              (0.9910469127824942, 1.5934172772440331, 169.66429773766885, 0.03510097173614132),
              (0.5170206648631608, 0.44935973713181826, 182.42482171314688, -0.06393138846540475)]
    interfaces = [(0.4165691170035012, 0.40380799331504386, None), (0.6065625443353023, 0.42835932214343414, None),
                  (0.31335873842541506, 0.25138511292387095, None)]
    if held_pedestal:
        blocks.insert(0, (2.0, 0.5, 2000.0, 0.0))
        interfaces.insert(0, (None, None, None))
    base = 1 if held_pedestal else 0
    stack = _stack_from(blocks, interfaces)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 100000})
    assert r.status == "overturned" and r.blocks[base]["overturned"], r.verdict
    assert 1.7199 < r.blocks[base]["first_rocking_time"] < 1.72
    if held_pedestal:
        assert r.blocks[0]["first_rocking_time"] is None and r.blocks[0]["first_sliding_time"] is None
    m = moreau_jean(stack, lambda t: float(motion.acceleration(np.array([t]))[0]),
                    lambda t: float(motion.vertical_acceleration(np.array([t]))[0]), t_end=3.0, dt=2e-4, save_every=10)
    assert m.status == "completed"
    ts = np.array([2.0, 2.5, 3.0])
    phi_mj = np.interp(ts, m.t, m.pose[:, base, 2])
    assert np.max(np.abs(phi_mj)) > 0.01  # it rocks
    np.testing.assert_allclose(np.interp(ts, r.t, r.rotation[:, base]), phi_mj, rtol=0, atol=5e-5)
    others = [k for k in range(len(blocks)) if k != base]
    assert np.all(r.rotation[r.t <= 3.0][:, others] == 0.0)


@pytest.mark.parametrize("on_pedestal", [False, True], ids=["on the floor", "on a held pedestal"])
@pytest.mark.parametrize("side", [1.0, -1.0], ids=["pushed left", "pushed right"])
@pytest.mark.parametrize("lead", [0.3e-6, 0.9e-6, 3e-6, 3e-5])
def test_a_block_set_rocking_just_before_a_sample_where_the_floor_turns_back_lands_when_its_closed_form_says(
        lead, side, on_pedestal):
    """A block 0.3 × 1.2 m under a record whose acceleration crosses the rocking threshold
    g·b/h a time ``lead`` before a sample and falls back steeply after it. It rocks by 1e-17 to
    1e-12 rad and lands. While |φ| is this small the rocking is linear, I₀φ̈ = m·h·(a − g·b/h)
    with I₀ = 4/3·m(b² + h²) (b, h the half sizes), and a − g·b/h = S₁τ + (S₂ − S₁)(τ − τ₁)₊
    (τ from the onset, τ₁ = lead, S₁ and S₂ the record's slopes before and after the sample). So
    φ ∝ S₁τ³ + (S₂ − S₁)(τ − τ₁)³: it lands at τ = τ₁q/(q − 1) with q = ((S₁ − S₂)/S₁)^⅓, and
    peaks at τ₁p/(p − 1) with p = ((S₁ − S₂)/S₁)^½.

    At a lead of 0.3 and 0.9 µs the tilt stays below the rounding of the far corner's height (a
    difference of positions of the block's size): the corner read −1e-16 m throughout, no probe
    saw it open, so it was closed again at once, the mode selection set the block rocking again at
    the same instant, 50 times, and the run stopped `inconsistent`, where the closed form has it
    land 1.1 µs after the sample (a statue on a pedestal under Landers, seed 1's run 1316 of
    bench/verdict_scan.py, did this). At 3 µs it landed 0.19 µs early, and at 30 µs 1.7 ns early.
    Now a far gap that reads zero to the rounding is read from its lift-off, to first order, and
    every landing is within 1e-12 s of the closed form (measured 5e-14 s); the peak rotation is
    within 1e-8 of it, relatively (measured 2.5e-9: the turning point's location; the neglected
    terms of the rocking equation are of relative order φ/α, below 1e-11). The same on a pedestal
    1 m wide, 0.5 m tall and 1000 kg that never slips (its own rocking would need 2 g), where the
    statue's corner is read on the pedestal's face."""
    g, b, h, dt, below = 9.80665, 0.15, 0.6, 0.005, 0.5
    a_thr = g * b / h
    excess = below * lead / (dt - lead)  # above the threshold at the sample: the crossing is `lead` before it
    motion = GroundMotion.from_arrays([0.0, dt, 2 * dt, 3 * dt], side * np.array([0.0, a_thr - below, a_thr + excess, 0.0]))
    blocks = (Block(width=2 * b, height=2 * h, mass=100.0),)
    if on_pedestal:
        blocks = (Block(width=1.0, height=0.5, mass=1000.0),) + blocks
    r = simulate_stack(Stack(blocks=blocks, interfaces=(Interface(),) * len(blocks)), motion, duration=0.05)
    assert r.status == "completed", r.verdict
    s1, s2 = (excess + below) / dt, -(a_thr + excess) / dt
    q, p = ((s1 - s2) / s1) ** (1 / 3), ((s1 - s2) / s1) ** 0.5
    onset = 2 * dt - lead
    assert len(r.events) == 2
    assert abs(r.events[0, 0] - onset) < 1e-12 and r.events[0, 2] in (0, 1)  # a corner's force vanishes
    assert abs(r.events[1, 0] - (onset + lead * q / (q - 1))) < 1e-12 and r.events[1, 2] == -1  # the landing
    tp = lead * p / (p - 1)
    peak = 3 * h / (4 * (b * b + h * h)) * (s1 * tp ** 3 + (s2 - s1) * (tp - lead) ** 3) / 6
    assert abs(r.summary()["blocks"][-1]["peak_rotation"] / peak - 1) < 1e-8
    if on_pedestal:
        assert r.summary()["blocks"][0]["peak_rotation"] == 0.0 and r.events[0, 1] == r.events[1, 1] == 1


@pytest.mark.parametrize("excess", [1e-7, 1e-6, 1e-5])
def test_a_block_at_a_harmonic_crest_just_above_its_threshold_rocks_lands_and_peaks_as_its_closed_form_says(
        excess):
    """A block 0.3 × 1.2 m under a sine whose crest exceeds the rocking threshold g·b/h by 1e-7
    to 1e-5 m/s². Near the crest a − g·b/h = ε − kτ² (τ from the crest, k = Aω²/2), so the
    linear rocking I₀φ̈ = m·h·(a − g·b/h) gives, with s the time since the onset at τ = −τ_h
    (τ_h = √(ε/k)): φ ∝ −s⁴/12 + τ_h·s³/3, which peaks at s = 3τ_h at 2.25·c·k·τ_h⁴
    (c = 3h/(4(b² + h²))) and lands at s = 4τ_h: 1.4e-16 to 1.4e-12 rad for 91 to 910 µs. The
    floor motion is not linear, so the onset is a step's event, not the rest's jump to a
    guard's root, and the whole rock fits in one step. Until 2026-12-06 the turning point of a
    rotation whose rate starts at exactly zero was never searched: the peak read as the step's
    ends, 1.5e-17 rad for 1.4e-12. Tolerances: the onset to 1e-12 s; the landing to 3e-8 s and
    the peak to 2e-17 rad, the integrator's absolute accuracy at these amplitudes (measured:
    2e-8, 6e-9 and 4e-10 s; 2e-19, 2e-18 and 1e-17 rad; the parabola's neglected quartic term
    moves the landing by less than 1e-6 of 4τ_h). The trough, half a period later, mirrors it."""
    g, b, h, f = 9.80665, 0.15, 0.6, 2.0
    w, a_thr = 2 * math.pi * f, g * b / h
    amplitude = a_thr + excess
    motion = rocking.Harmonic(amplitude=amplitude, frequency=f, cycles=1, form="sin")
    r = simulate_stack(Stack(blocks=(Block(width=2 * b, height=2 * h, mass=100.0),), interfaces=(Interface(),)),
                       motion, duration=0.5)
    assert r.status == "completed", r.verdict
    t1 = math.asin(a_thr / amplitude) / w
    th = 0.25 / f - t1
    k, c = amplitude * w * w / 2, 3 * h / (4 * (b * b + h * h))
    assert len(r.events) == 4 and list(r.events[:, 2]) in ([0, -1, 0, -1], [1, -1, 1, -1], [0, -1, 1, -1],
                                                             [1, -1, 0, -1])
    for half in (0, 1):
        onset, landing = r.events[2 * half, 0] - half / (2 * f), r.events[2 * half + 1, 0] - half / (2 * f)
        assert abs(onset - t1) < 1e-12
        assert abs(landing - (t1 + 4 * th)) < 3e-8
    assert abs(r.summary()["blocks"][0]["peak_rotation"] - 2.25 * c * k * th ** 4) < 2e-17


def test_a_block_overturning_about_the_corner_of_a_narrower_one_below_lies_along_its_side_not_in_it():
    """A random stack (seed 3's 131st of the tests' random stacks): a block 0.71 m wide rocks about
    the corner of the 0.35 m base under it (Northridge × 0.97 with a vertical part, 0.22 × the
    horizontal one reversed) and overturns at 3.49 s. At φ = −π/2 its face is vertical through the
    base's corner, and the part that overhung hangs along the base's side: its own corner lies at
    the end of the base's face (to the bit) and 0.245 m below it. The run's self-check counted that
    corner as sunk 0.245 m into the base and reported `lost_contact`; a block turned to ±π/2 is
    its overturn, and its corners are not on the face below. The rows before it: no corner sinks
    (the independent geometry here, to 1e-9 m)."""
    motion = _with_reversed_vertical("Northridge1994_RinaldiReceivingSta_228", 0.9669064609944824, 0.2198886117898482)
    stack = _stack_from(
        [(0.3485797216437727, 1.413017385334587, 721.0201559645694, 0.0),
         (0.7139832230646742, 0.38797893681087214, 76.64101415253954, -0.06267489379426824),
         (0.8778364152733206, 1.1227543873466599, 135.58145345484925, -0.04526105731699588)],
        [(0.3215445153253485, 0.2800613834717034, 0.5266614703553223), (None, None, 0.9191175752121079),
         (0.24064228981374763, 0.19589432020016098, None)])
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 100000})
    assert r.status == "overturned" and r.blocks[1]["overturned"], r.verdict
    t_fall = r.blocks[1]["overturn_time"]
    assert 3.49 < t_fall < 3.491
    row = np.nonzero(r.t == t_fall)[0][0]
    assert abs(r.rotation[row, 1] + 0.5 * math.pi) < 1e-12
    (x1, y1, t1), (x2, y2, t2) = r.pose[row, 0], r.pose[row, 1]
    bu, hu = 0.5 * stack.blocks[1].width, 0.5 * stack.blocks[1].height
    # its left bottom corner (−b, −h/2), Θ clockwise, relative to the base's centre
    dx = x2 - bu * math.cos(t2) - hu * math.sin(t2) - x1
    dy = y2 + bu * math.sin(t2) - hu * math.cos(t2) - y1
    along = dx * math.cos(t1) - dy * math.sin(t1)
    up = dx * math.sin(t1) + dy * math.cos(t1) - 0.5 * stack.blocks[0].height
    assert abs(abs(along) - 0.5 * stack.blocks[0].width) < 1e-12 and up < -0.2
    assert _deepest_sink(dataclasses.replace(r, pose=r.pose[r.t < t_fall])) > -1e-9


def test_a_mode_solve_satisfies_the_equations_of_that_mode():
    """solve_mode_in solves only the free coordinates' rows (docs/theory/stack.md): check the full
    equations M z̈ = f + Λ at random M (symmetric positive definite), f and every mode of a
    three-block stack — z̈ = 0 where frozen, Λ = 0 on free coordinates except a slipping a, where
    Λ_a = −μk σ Λ_d — to rounding."""
    from rocking.stack import modes
    from rocking.stack.kinematics import P_CAN_SLIP, P_MU_K
    from rocking.stack.simulate import pack

    stack = Stack(blocks=(Block(width=1.2, height=0.4, mass=400.0), Block(width=0.4, height=1.4, mass=150.0),
                          Block(width=0.2, height=0.45, mass=8.0)),
                  interfaces=tuple(Interface(friction=Friction(static=0.5, kinetic=0.4)) for _ in range(3)))
    P = pack(stack)[0]
    rng = np.random.default_rng(7)
    n, nz = 3, 9
    checked = 0
    for _ in range(3):
        R = rng.standard_normal((nz, nz))
        M = R @ R.T + nz * np.eye(nz)
        f = rng.standard_normal(nz)
        for states in np.ndindex(3, 3, 3, 3, 3, 3):
            nstate = np.array(states[:3], dtype=np.int64)
            tstate = np.array(states[3:], dtype=np.int64) - 1
            if np.any((nstate == modes.OPEN) & (tstate != 0)):
                continue
            x, lam = np.full(nz, np.nan), np.full(nz, np.nan)
            scratch = (np.zeros(nz, dtype=bool), np.empty(nz, dtype=np.int64), np.empty(nz, dtype=np.int64),
                       np.empty((nz, nz)), np.empty(nz))
            assert modes.solve_mode_in(M, f, P, nstate, tstate, x, lam, *scratch)
            frozen = np.zeros(nz, dtype=bool)
            modes.frozen_set(nstate, tstate, P, frozen)
            assert np.all(x[frozen] == 0.0)
            expected = np.where(frozen, lam, 0.0)
            for k in range(n):
                if nstate[k] >= modes.ROCK and tstate[k] != 0 and P[k, P_CAN_SLIP] > 0.5:
                    expected[3 * k] = -P[k, P_MU_K] * tstate[k] * lam[3 * k + 2]
            np.testing.assert_allclose(lam, expected, rtol=0, atol=1e-13 * np.abs(lam).max(initial=1.0))
            np.testing.assert_allclose(M @ x, f + lam, rtol=0, atol=1e-12 * (np.abs(f).max() + np.abs(lam).max()))
            checked += 1
    assert checked == 3 * 7**3  # per interface: open (stuck only), or rock or flat, each stuck or slipping ±


@pytest.mark.parametrize("offset", [0.1, -0.1], ids=["flush right, slides inwards", "flush left, slides outwards"])
def test_a_block_flush_with_the_edge_below(offset):
    """The squat block, placed with a corner flush with the plinth's edge (offset ±0.1 m: 0.1 +
    0.2 = 0.3 m, in floating point a hair past it), run with ``stop_at_edge``. Sliding away from
    that edge it crosses the plinth, 0.2 m, and stops at the far edge at ½(A − μg)t² = 0.2 m;
    sliding over that edge it is past it at once. (Before, the rounding of o ± b made the flush corner the
    plinth's: the first case stopped at 2e-9 s, the second slid off unnoticed.)"""
    a, mu = 0.5 * G, 0.1
    stack = _squat_on_plinth(mu, offset)
    r = simulate_stack(stack, rocking.RectanglePulse(amplitude=a, width=2.0), duration=2.0,
                       options={"gravity": G, "stop_at_edge": True})
    assert r.status == "slid_past_edge"
    if offset > 0:
        assert abs(r.end_time - math.sqrt(2 * 0.2 / (a - mu * G))) < 1e-9
        assert abs(r.blocks[1]["residual_sliding"] + 0.2) < 1e-9
    else:
        assert r.end_time == 0.0 and r.blocks[1]["peak_sliding"] < 1e-12


# -- three contact configurations of the random stacks that used to stop the run (2026-11-24) --
def _independent_energy(stack, r, gravity=9.80665):
    """Kinetic + potential energy of every saved row from the poses and velocities alone, J
    (uniform rectangles: J = m(w² + h²)/12 about the centre)."""
    e = np.zeros(len(r.t))
    for k, b in enumerate(stack.blocks):
        inertia = b.mass * (b.width ** 2 + b.height ** 2) / 12.0
        v = r.velocity[:, k]
        e += 0.5 * b.mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * inertia * v[:, 2] ** 2
        e += b.mass * gravity * r.pose[:, k, 1]
    return e


def _ledger_error(stack, r) -> float:
    """The run's energy ledger with the energy computed here (:func:`_independent_energy`):
    max |E − E0 − W_in + D_friction + D_impact| over its scale (the largest input work plus the
    largest energy change)."""
    e = _independent_energy(stack, r)
    balance = e - e[0] - r.input_work + r.friction_loss + r.impact_loss
    return float(np.max(np.abs(balance)) / (np.max(np.abs(r.input_work)) + np.max(np.abs(e - e[0]))))


def _impact_budget_drop(stack, r) -> float:
    """How far the energy the impacts took, by the ledger with the energy computed here from the
    poses (D = W_in − D_friction − (E − E0), J), ever falls below its running maximum, over the
    ledger's scale. Impacts only ever add to D, so a fall is energy an impact created; the engine's
    own impact bookkeeping is not read."""
    e = _independent_energy(stack, r)
    d = r.input_work - r.friction_loss - (e - e[0])
    return float(np.max(np.maximum.accumulate(d) - d) / (np.max(np.abs(r.input_work)) + np.max(np.abs(e - e[0]))))


def _squat_on_rocking_blocks():
    """Three blocks of the random stacks (seed 1): a squat top block (0.91 × 0.38 m, 21 kg,
    restitution 0.87, above its own Housner value, which is negative) on a block that rocks and
    slips, on one that rocks on the floor (restitution 0.69)."""
    return Stack(
        blocks=(Block(width=0.9200334315907671, height=0.7710862395509412, mass=51.555356641389366),
                Block(width=0.7116576603553549, height=0.8107119651341745, mass=98.87151070441959,
                      offset=-0.00023138091603017164),
                Block(width=0.9149862647005681, height=0.38290529011143615, mass=20.70762319469544,
                      offset=0.08894091111972105)),
        interfaces=(Interface(restitution=0.6909035055928314),
                    Interface(friction=Friction(static=0.44821744559718046, kinetic=0.35803463422531057)),
                    Interface(restitution=0.8719289460103321)))


def test_a_slipping_interface_that_rocks_onto_the_lower_blocks_corner_keeps_its_slip():
    """A squat block slipping flat on a narrower one rocks onto the lower block's corner at
    t = 2.9600 s. There ȧ is measured along the upper block's face, so its sign flips: the slip
    direction was checked before the re-anchoring and kept the old sign, the stick guard fired at
    once and zeroed a 0.19 m/s slip: 21 J left the stack outside the ledger (computed here from
    the poses alone: off by 5.6 % of its scale, 379 J). Now it balances to the solver's accuracy;
    1e-6 of the scale is 5e4 times below the old error."""
    from rocking.io.records import read_record

    stack = _squat_on_rocking_blocks()
    motion = read_record("Northridge1994_RinaldiReceivingSta_228").trimmed(15.0).scaled(1.1117499960497195)
    r = simulate_stack(stack, motion, duration=3.0, options={"save_dt": 0.005})
    assert r.status == "still_moving"  # (stopped at 3 s, past the event)
    assert np.any(np.abs(r.events[:, 0] - 2.96003) < 1e-5)  # the re-anchoring still happens
    assert _ledger_error(stack, r) <= 1e-6


def test_a_restitution_couple_that_would_create_energy_restitutes_less():
    """The same stack through the whole record. At t = 3.44075 s its squat top block lands on the
    rocking block below with the couple (r − r_H)·I_O·φ̇⁻, r = 0.87 above its negative Housner
    value: imposed from outside the contact problem, it gave the impact 0.0157 J more than it had,
    and each landing of the sequence that followed more again, until the run stopped at 4.59 s
    (max_events). An impact never creates energy: the couple is now scaled down to the boundary
    of the fractions that create none (docs/theory/stack.md §6), said in the block summary, and
    the stack comes to rest. The energy the impacts took, computed from the poses and the
    ledger's work and friction alone, never falls by more than the ledger's own balance (both
    about 1e-8 of the 379 J scale here); the old gain was 4e-5 of it."""
    from rocking.io.records import read_record

    stack = _squat_on_rocking_blocks()
    motion = read_record("Northridge1994_RinaldiReceivingSta_228").trimmed(15.0).scaled(1.1117499960497195)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert r.blocks[2]["restitution_reduced_time"] == pytest.approx(3.44075456, abs=1e-7)
    at = r.events[(np.abs(r.events[:, 0] - 3.44075456) < 1e-7) & (r.events[:, 2] == -1)]
    # at the bisection's boundary the impact conserves energy to the solve's accuracy (1e-9 of
    # the energy before it): 7e-9 J where it created 0.0157 J
    assert len(at) == 1 and abs(at[0, 5]) <= 2e-8
    assert _impact_budget_drop(stack, r) <= 1e-7
    assert _ledger_error(stack, r) <= 1e-7
    warnings = build_stack_content(r).warnings
    assert any("t = 3.441 s an impact under block 3 did not restitute" in w and "created energy" in w
               for w in warnings), warnings


def test_an_impact_that_stops_a_slow_slip_creates_no_energy():
    """Three blocks of the random stacks (seed 1), no restitution given. A sequence of floor
    impacts ends at t = 0.3753867 s with the plinth landing flat; the same impact leaves a slip
    slower than rest_velocity × the block's size, which the rest rule stops. It used to set that
    slip rate to zero alone: in the interface coordinates the blocks' momenta are coupled, so the
    others' velocities kept momenta that no longer matched, and the impact created 2.6e-5 J (the
    energy the impacts took, computed from the poses, fell by 5.1e-7 of the 50 J scale). The slip
    is now stopped by a plastic impulse (the velocity projected onto the mode in the kinetic-energy
    metric, docs/theory/stack.md §6), which cannot add energy: the fall is 7e-10, the size of the
    ledger's own balance (6e-10) here."""
    stack = Stack(
        blocks=(Block(width=0.5560671018304546, height=0.674872849892243, mass=485.4036119028105),
                Block(width=0.27254534962005234, height=0.3584438240649913, mass=46.22033649386566,
                      offset=-0.08158220686217676),
                Block(width=0.9761344989864735, height=1.4814315760614318, mass=149.8879144512885,
                      offset=0.03857244646704466)),
        interfaces=(Interface(friction=Friction(static=0.45125181038842405, kinetic=0.44134302490441335)),
                    Interface(friction=Friction(static=0.5790513153216552, kinetic=0.410908944859549)),
                    Interface(friction=Friction(static=0.29824499267190074, kinetic=0.21463765944410404))))
    r = simulate_stack(stack, rocking.SinePulse(amplitude=5.520049558917435, frequency=2.8672666662335184),
                       options={"save_dt": 0.005})
    assert r.status == "overturned"
    at = r.events[(np.abs(r.events[:, 0] - 0.37538667) < 1e-7) & (r.events[:, 2] == -1)]
    assert len(at) == 1 and at[0, 5] > 0.0
    assert _impact_budget_drop(stack, r) <= 1e-8
    assert _ledger_error(stack, r) <= 1e-8


def test_a_rest_landing_with_no_consistent_mode_lands_the_impacts_own_outcome():
    """Three blocks of the random stacks (seed 1): a heavy narrow block (240 kg) on a light one
    (17 kg), a light wide one (12 kg) on top, under Loma Prieta × 0.49. At t = 2.7333 s an impact
    leaves the heavy block rocking slower than rest_velocity, and the rest rule's landing (a plastic
    impulse with both ends closed, its signs unchecked) left the others no consistent mode: the run
    stopped "inconsistent". The impact's own outcome is now landed instead, by its velocities
    projected onto its mode with that interface flat (docs/theory/stack.md §6). The stack comes to
    rest; its ledger, computed here from the poses, balances to 1e-9 of its scale (6e-11 measured;
    2.1e-6 after the long sequence of micro-impacts until the energy of an impact's exact pose was
    booked, docs/theory/stack.md §6)."""
    from rocking.io.records import read_record

    stack = Stack(
        blocks=(Block(width=0.9768438674442071, height=1.359155114570687, mass=16.753544247147744),
                Block(width=0.37534566411425646, height=0.646073779431561, mass=239.95673908305957,
                      offset=-0.028335348558892415),
                Block(width=1.1169295158938224, height=0.5548715556939778, mass=11.707406053503496,
                      offset=0.09712814118647137)),
        interfaces=(Interface(friction=Friction(static=0.3429835632788545, kinetic=0.29433484127513415)),
                    Interface(friction=Friction(static=0.6544913303698594, kinetic=0.6448440325464665),
                              restitution=0.7151934348728851),
                    Interface(friction=Friction(static=0.7426581003324055, kinetic=0.5334562027715086))))
    motion = read_record("LomaPrieta1989_Corralitos_000").trimmed(15.0).scaled(0.49260942831448395)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert _ledger_error(stack, r) <= 1e-9
    assert _deepest_sink(r) > -1e-8


def test_an_impact_whose_restitution_has_no_consistent_mode_restitutes_less():
    """A light wide block (4.7 kg) rocks on a heavy slender one (100 kg, restitution 0.52) that
    lands at t = 0.28855 s. With the restitution couple, every contact mode breaks a condition:
    the upper block's corner would have to pull, and released it would sink. The run stopped
    "inconsistent". The couple is now scaled down, by bisection, to the boundary of the fractions
    that leave a consistent mode (docs/theory/stack.md §6), said in the block summary; the run
    reaches a verdict, the impact loses energy, and the ledger balances to 1e-8 of its scale."""
    stack = Stack(
        blocks=(Block(width=0.26007028406663035, height=0.9016335890884895, mass=100.1425696337417),
                Block(width=1.1019054673202364, height=0.5644802266627765, mass=4.7490804296984725,
                      offset=-0.09751811452286807)),
        interfaces=(Interface(friction=Friction(static=0.49818360889138025, kinetic=0.42634535867136003),
                              restitution=0.5197764079279189),
                    Interface()))
    motion = rocking.Harmonic(amplitude=2.3907747227686778, frequency=1.9570915796337518, cycles=5)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005})
    assert r.status in ("completed", "overturned")
    assert r.blocks[0]["restitution_reduced_time"] == pytest.approx(0.28855257, abs=1e-7)
    assert r.blocks[1]["restitution_reduced_time"] is None
    at = r.events[(np.abs(r.events[:, 0] - 0.28855257) < 1e-7) & (r.events[:, 2] == -1)]
    assert len(at) == 1 and at[0, 5] > 0.0
    assert _ledger_error(stack, r) <= 1e-8
    assert _deepest_sink(r) > -1e-9
    warnings = build_stack_content(r).warnings
    assert any("t = 0.289 s an impact under block 1 did not restitute" in w for w in warnings), warnings


def test_an_impact_whose_restitution_holds_only_below_one_half_restitutes_that_little():
    """Seed 5's 52nd random stack: a heavy wide block (634 kg, restitution 0.61 on its 30 kg
    plinth) lands at t = 0.44683 s with a slender block (166 kg) that never slips rocking on it.
    Half of the restitution couple leaves no consistent mode, so the bisection of
    ``_impact_with_less_restitution`` must start from the plastic impact (s = 0), which holds, and
    find the boundary below one half: block 2's summary notes the cut, and the impact leaves its
    interface rocking, slipping forward. (Tried at s = 0.5 first, the bisection gave up at once:
    the impact landed the block flat, holding its contacts, and the run went another way: 111
    events by 0.6 s where it makes 298; forty-second mutation round, cdb9e659.)"""
    stack = Stack(
        blocks=(Block(width=0.3717372154468587, height=0.5648150257040017, mass=29.840667958615043),
                Block(width=0.8476512157656304, height=0.9585679105675731, mass=634.4206021148693,
                      offset=-0.06259391581475385),
                Block(width=0.2704834939373004, height=0.8366997474788826, mass=166.36907398096272,
                      offset=-0.04164718324180808)),
        interfaces=(Interface(friction=Friction(static=0.3186348385526252, kinetic=0.293029640630052)),
                    Interface(friction=Friction(static=0.6180933283650607, kinetic=0.6062589114645254),
                              restitution=0.6147100149876976),
                    Interface(restitution=0.7716083435881677)))
    motion = rocking.Harmonic(amplitude=1.6830355432253576, frequency=2.1219191225793486, cycles=4)
    r = simulate_stack(stack, motion, duration=0.6, options={"save_dt": 0.005})
    cut = [b["restitution_reduced_time"] for b in r.blocks]
    assert cut[0] is None and cut[2] is None and cut[1] == pytest.approx(0.44682724, abs=1e-7)
    at = r.events[(np.abs(r.events[:, 0] - cut[1]) < 1e-9) & (r.events[:, 1] == 1) & (r.events[:, 2] == -1)]
    assert len(at) == 1 and (at[0, 3], at[0, 4]) == (1, 1) and at[0, 5] > 0.0  # rocking, slipping; loses energy
    assert _ledger_error(stack, r) <= 1e-8
    assert _deepest_sink(r) > -1e-9


def test_an_impact_that_would_make_a_corner_pull_holds_it():
    """A heavy statue (300 kg) lands on a small plinth while a light vase that never slips rocks
    on it: with the statue's interface slipping, the vase's corner would have to pull, and
    released it would sink (Painlevé's paradox at the impulse level; no restitution couple here).
    The run stopped "inconsistent" at t = 0.51593 s. The contacts are now held, as at the
    acceleration level, and the instant is reported as ``tension_held_time``; the impact loses
    energy and the ledger balances to 1e-8."""
    stack = Stack(
        blocks=(Block(width=0.41161026205673856, height=0.27219809802625505, mass=20.634437136930057),
                Block(width=0.9162121449412373, height=1.4951181658882087, mass=299.61879296965503,
                      offset=0.07326801546552494),
                Block(width=0.88608334073155, height=1.5341376989607238, mass=12.689318668760938,
                      offset=-0.08558795447225663)),
        interfaces=(Interface(), Interface(friction=Friction(static=0.5363894790280657, kinetic=0.5292902329141796)),
                    Interface()))
    motion = rocking.SinePulse(amplitude=7.895100409482686, frequency=1.6783673356715663)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005})
    assert r.status in ("completed", "overturned")
    assert r.blocks[2]["tension_held_time"] == pytest.approx(0.51592601, abs=1e-7)
    warnings = build_stack_content(r).warnings
    assert any("From t = 0.516 s the contact under block 3 carried a small tension" in w for w in warnings), warnings
    at = r.events[(np.abs(r.events[:, 0] - 0.51592601) < 1e-7) & (r.events[:, 2] == -1)]
    assert len(at) == 1 and at[0, 5] > 0.0
    assert _ledger_error(stack, r) <= 1e-8
    assert _deepest_sink(r) > -1e-9


def test_an_impact_that_leaves_a_block_lifting_slower_than_rest_lands_it_flat():
    """A slender block (restitution 0.73) under a wide light one settles after the record with
    micro-impacts. At t = 5.99972 s one of them left it lifting flat off the floor at 5e-9 m/s:
    the gap of its other corner cannot open that slowly as far as the positions resolve, so the
    same impact came again at the same instant, 53 times, and the run stopped "inconsistent".
    The rest rule of impacts now covers it: a lift slower than rest_velocity × the block's size
    lands the block flat (docs/theory/stack.md §6). The stack comes to rest, and the ledger,
    computed here from the poses, balances to 1e-8 of its scale."""
    from rocking.io.records import read_record

    stack = Stack(
        blocks=(Block(width=0.3087034124741205, height=1.2593459751579352, mass=89.7458514333603),
                Block(width=1.1322820547559966, height=0.4868139921045829, mass=6.958786058694237,
                      offset=-0.01789593109620298)),
        interfaces=(Interface(friction=Friction(static=0.5249476748842593, kinetic=0.4718581802264159),
                              restitution=0.7267251031146879),
                    Interface(friction=Friction(static=0.5117062651666293, kinetic=0.43248508265664026))))
    motion = read_record("Northridge1994_RinaldiReceivingSta_228").trimmed(15.0).scaled(0.3464323381962823)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert _ledger_error(stack, r) <= 1e-8
    assert _deepest_sink(r) > -1e-9


def test_an_impact_that_leaves_the_corner_hit_too_slow_to_open_keeps_it_closed():
    """A slender block (66 kg) slips on the floor under two wider blocks that never slip. At
    t = 8.7007658 s it lands, and the impulse leaves the block above it in flight, its corner
    approaching the face at 7e-13 m/s, within the impulse tolerance. That gap cannot open as far as
    the positions resolve, so the same impact came again at the same instant, 50 times, and the run
    stopped "inconsistent". The impact now keeps a corner hit that leaves slower than rest_velocity ×
    its block's size closed, the block rocking on it, by a plastic impulse (docs/theory/stack.md
    §6). The stack comes to rest; the ledger, computed here from the poses, balances to 1e-7 of its
    scale (1.4e-8 measured, after 2400 events) and no impact gains energy."""
    stack = Stack(
        blocks=(Block(width=0.3137916541533648, height=1.2075890715517976, mass=65.96960447659656),
                Block(width=0.6579122697749773, height=0.9585027775212518, mass=20.30769921393382,
                      offset=0.07792764781156789),
                Block(width=0.6638391991791343, height=0.9849980107420451, mass=4.750957072340555,
                      offset=-0.001412503797340925)),
        interfaces=(Interface(friction=Friction(static=0.2222531383433379, kinetic=0.16320041733225119),
                              restitution=0.6446381062056264),
                    Interface(), Interface()))
    motion = rocking.Harmonic(amplitude=3.888376856510073, frequency=2.272771103076093, cycles=3)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert r.end_time > 8.9
    assert _ledger_error(stack, r) <= 1e-7
    assert _deepest_sink(r) > -1e-9
    impacts = r.events[r.events[:, 2] == -1]
    assert impacts[:, 5].min() >= -1e-9  # J, of a 31 J scale


def test_a_contact_held_in_tension_holds_every_contact_that_pulls():
    """Three blocks under Kobe × 0.50: a 62 kg block rocks and slips on the floor with a heavy one
    (591 kg) slipping flat on it. Both normal forces turn negative at one instant, and no contact
    mode holds (Painlevé's paradox), so the contacts are held. Only the interface whose event it
    was used to be held: the other's force then fired at once, the two took turns at one instant,
    and the run stopped "inconsistent" at 4.544 s. Every contact that pulls is now held until it
    pushes again, and each is reported (docs/theory/stack.md §5). The run reaches a verdict, the
    ledger balances to 1e-8 of its scale, nothing sinks.

    The path has moved twice since, by changes at the rounding level that chaos then grew: the
    rest rules of 2026-11-27 (both contacts held from 5.203 s; without this rule the run still
    stopped there), and on 2026-12-06 the far gaps read from their lift-off (the first event
    time moves by 2e-15 s at 4.544 s, the verdict stays: block 1 overturns at 8.199 s; all three
    contacts pulled at 7.175 s). The restitution of 2026-12-07, which turns a block and what it
    carries as one body, moved it a fourth time: the contacts under blocks 1 and 2 pull together
    at 5.099 s, the one under block 3 at 7.165 s, and block 1 overturns at 8.428 s. But from
    5.099 s the held slips, their friction turned round by the tension, feed the motion (1e-4 of
    the run's energy scale by 8 s), so since 2026-12-07 the run is no result: `friction_gained`
    (docs/theory/stack.md §7), its verdict undetermined."""
    from rocking.io.records import read_record

    stack = Stack(
        blocks=(Block(width=0.446672738500028, height=0.8145819593512544, mass=62.389823914998296),
                Block(width=0.4024497310336428, height=0.38101423462201367, mass=591.431638563434,
                      offset=-0.014002165771610467),
                Block(width=1.141392229365473, height=0.7636369644731469, mass=48.083242783679864,
                      offset=-0.09294306430957583)),
        interfaces=(Interface(friction=Friction(static=0.6836485181922491, kinetic=0.6777303583170982),
                              restitution=0.8603069719346857),
                    Interface(friction=Friction(static=0.7104048244664822, kinetic=0.5392626819332554),
                              restitution=0.7497737740788035),
                    Interface(friction=Friction(static=0.49758505207927267, kinetic=0.40512311637276227))))
    motion = read_record("Kobe1995_Takatori_000").trimmed(15.0).scaled(0.5028922190004976)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "friction_gained" and r.verdict.startswith("undetermined: from t = 5.099 s friction fed")
    held = [b["tension_held_time"] for b in r.blocks]
    assert held[0] == pytest.approx(5.0992412, abs=1e-7) and held[1] == held[0]
    assert held[2] == pytest.approx(7.1653604, abs=1e-7)
    assert r.blocks[0]["overturn_time"] == pytest.approx(8.428, abs=1e-3)  # "block 1"
    # the report claims nothing either, though block 1 fell in the run: "stopped", not "fails"
    assert stack_verdict(r).startswith("Undetermined: from t = 5.099 s friction fed the motion")
    assert stack_verdict_class(r) == "stopped"
    warnings = build_stack_content(r).warnings
    for k, when in ((1, "5.099"), (2, "5.099"), (3, "7.165")):
        assert any(w.startswith(f"From t = {when} s the contact under block {k} carried a small tension")
                   for w in warnings), warnings
    assert _ledger_error(stack, r) <= 1e-8
    assert _deepest_sink(r) > -1e-9


def test_a_slipping_contact_held_in_tension_carries_no_friction():
    """Three blocks of the random stacks (seed 1, run 41) under Friuli × 1.07: a 578 kg block
    slipping on a 4.8 kg one that carries a restitution, on a 318 kg plinth. A floor landing had no
    consistent mode, so the contacts were held (Painlevé's paradox at an impact, docs/theory/stack.md
    §5); one of them slipped, and its sliding friction −μk·λn, turned round by the tension, pushed
    the slip on: the impact gained 3.9e-6 J, 1e-7 of the 37 J it had. Coulomb's bound on a contact
    that pulls is zero: where the held outcome gains energy the held slipping contacts now carry no
    friction (a plastic projection with their slips free, which can only take energy). Every
    impact then loses energy or keeps it to 1e-9 of the run's scale (127 J), the ledger balances
    to 1e-9, nothing sinks, and the slipping interface never needed more than its μs while it
    stuck (made to stick instead, it needed 0.305 against μs = 0.206)."""
    from rocking.io.records import read_record

    stack = Stack(
        blocks=(Block(width=1.0118657631385468, height=0.5316924338820408, mass=318.260528644107),
                Block(width=0.6227268498881925, height=1.494016255242408, mass=4.7652342162936945,
                      offset=-0.06875985463948248),
                Block(width=0.4287282030947166, height=1.448949612777023, mass=578.0136159134013,
                      offset=-0.095250841271066)),
        interfaces=(Interface(), Interface(restitution=0.9380566476553509),
                    Interface(friction=Friction(static=0.20582698098088667, kinetic=0.2015773831111605))))
    motion = read_record("Friuli1976_Tolmezzo_000").trimmed(15.0).scaled(1.0722097324390858)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert [b["tension_held_time"] for b in r.blocks][1:] == pytest.approx([3.8510236] * 2, abs=1e-7)
    scale = np.max(np.abs(r.input_work)) + np.max(np.abs(r.energy - r.initial_energy))
    impacts = r.events[r.events[:, 2] == -1]
    assert len(impacts) > 100 and impacts[:, 5].min() >= -1e-9 * scale
    assert r.interfaces[2]["required_friction"] <= stack.interfaces[2].friction.mu_s
    assert _ledger_error(stack, r) <= 1e-9
    assert _deepest_sink(r) > -1e-9


def test_a_body_on_a_rocking_block_falls_back_to_the_block_alone_and_runs_to_a_verdict():
    """Three blocks of the random stacks (seed 1, run 47): a 684 kg block flat and stuck on a
    10.7 kg one (restitution 0.94) that rocks on a slender 12.6 kg block, itself rocking on the
    floor. The 695 kg body the two upper blocks make lands on the slender block at t = 0.00495 s;
    its restitution impulse (docs/theory/stack.md §6) would create energy there, as the block
    below rocks, so it acts on the 10.7 kg block alone, and the summary says so. Allowed the
    energy allowance of the rest rules, the body's impulse took 2e-10 J at each landing, and
    rebounded, the landings 0.3 µs apart, until the run stopped at max_events at 0.008 s. Now the
    sequence ends and the slender block overturns at 2.521 s."""
    stack = Stack(
        blocks=(Block(width=0.19084542369825022, height=1.2754683810769132, mass=12.590146460529281),
                Block(width=0.808823427006238, height=1.1567213308196314, mass=10.725448419536143,
                      offset=0.01906434950045159),
                Block(width=1.0123666427726423, height=1.3585802411336998, mass=684.3228163256878,
                      offset=0.09212955200358283)),
        interfaces=(Interface(friction=Friction(static=0.399296624347251, kinetic=0.3991624219761108),
                              restitution=0.7108353513157976),
                    Interface(friction=Friction(static=0.5264638657438979, kinetic=0.3866872316281862),
                              restitution=0.9389873706871807),
                    Interface(friction=Friction(static=0.43609251925995945, kinetic=0.389206480253075))))
    motion = rocking.SinePulse(amplitude=5.755438683250736, frequency=1.298583627811307)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    # (2.521031 s before the dip rule of 2026-12-07 moved its path by rounding: 2.521008 s now)
    assert r.status == "overturned" and r.blocks[0]["overturn_time"] == pytest.approx(2.52101, abs=1e-4)
    assert len(r.events) < 500
    assert r.blocks[1]["restitution_reduced_time"] == pytest.approx(0.0049491183, abs=1e-9)
    assert [b["restitution_reduced_time"] for b in r.blocks][::2] == [None, None]
    warnings = build_stack_content(r).warnings
    assert any(w.startswith("At t = 0.005 s an impact under block 2 did not restitute as its coefficient asks")
               and "acted on block 2 alone" in w for w in warnings), warnings
    assert _ledger_error(stack, r) <= 1e-9
    assert _deepest_sink(r) > -1e-9


def test_a_gap_that_closes_and_opens_again_before_the_first_sample_is_an_impact():
    """Two blocks of the random stacks (seed 7, run 42): a 151 kg block on a slender 47.6 kg plinth
    (restitution 0.53 on the floor) under three cycles of a 4.8 m/s², 1.44 Hz harmonic. At
    t = 3.12902 s a slip stops while the plinth rocks on its right corner 6e-8 rad up, turning back
    at 4.4 mrad/s: its left corner reaches the floor 1.3e-5 s later. The step after the event was
    16 ms long, and its first sample, 2 ms on, saw the corner open again (8.8e-7 m), after the
    plinth had turned 3.3e-6 rad past flat about the wrong corner, its left corner 1.8 µm into the
    floor for 1 ms, until another event. Such a dip, seen from the gap's rate at the step's start,
    is now located at its minimum: nothing sinks (the saved poses, plain geometry), and the run
    ends at rest."""
    stack = Stack(
        blocks=(Block(width=0.5435044039240733, height=1.2592671533824051, mass=47.646343220030374),
                Block(width=0.9416928019197202, height=0.9902999294132917, mass=151.26087902671756,
                      offset=0.06046709042853193)),
        interfaces=(Interface(friction=Friction(static=0.4689190737081215, kinetic=0.38912835724988704),
                              restitution=0.5274667163537408),
                    Interface(friction=Friction(static=0.3380636974946389, kinetic=0.26482983424553164))))
    motion = rocking.Harmonic(amplitude=4.803454589242003, frequency=1.435453965612819, cycles=3)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert _deepest_sink(r) > -1e-9
    assert _ledger_error(stack, r) <= 1e-9


def test_an_impact_that_leaves_another_interface_rocking_slower_than_rest_lands_it():
    """A slender heavy block (991 kg) rocks on a lighter one (121 kg) that sits flat on a rocking,
    slipping base (521 kg). At t = 0.6408 s an impact elsewhere left the middle interface rocking
    at 8e-10 rad/s on a face it was pressed onto: 4 ns later it turned into the face, landed, lifted
    the others, and the three interfaces took turns landing every 4 ns until the run stopped at
    max_events (5000 events by 0.641 s). The rest rule of impacts now covers every interface: one
    left rocking slower than rest_velocity with its other end closed lands flat (docs/theory/stack.md
    §6). The top block then overturns at 1.416 s, as it does in the Moreau–Jean time stepping of the
    same stack without restitution coefficients (which that method cannot impose; checked by hand,
    2026-11-27). The ledger balances to 1e-8 and no impact gains energy."""
    stack = Stack(
        blocks=(Block(width=0.9734898233278767, height=1.0796410615078789, mass=520.606798084185),
                Block(width=0.9452709289970899, height=1.4243916979061926, mass=120.74747125472761,
                      offset=0.05715076984875431),
                Block(width=0.17081377598152928, height=1.1487343732158632, mass=990.90637090467,
                      offset=-0.002281679847634721)),
        interfaces=(Interface(friction=Friction(static=0.449214204896461, kinetic=0.3644412486030059),
                              restitution=0.7155821275042332),
                    Interface(friction=Friction(static=0.7820426241330571, kinetic=0.5672857332487266)),
                    Interface(friction=Friction(static=0.759811088224442, kinetic=0.751865168745564),
                              restitution=0.8777852592767661)))
    motion = rocking.Harmonic(amplitude=2.966256232886408, frequency=0.8314165526185459, cycles=3)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "overturned" and [b["overturned"] for b in r.blocks] == [False, False, True]
    assert len(r.events) < 200
    assert _ledger_error(stack, r) <= 1e-8
    assert _deepest_sink(r) > -1e-9
    impacts = r.events[r.events[:, 2] == -1]
    assert impacts[:, 5].min() >= 0.0


def test_the_exact_pose_of_a_landing_is_booked_in_the_ledger():
    """A heavy block (98 kg) on a tall light one (26 kg) on a squat base that never slips, after a sine
    pulse: the two upper blocks chatter to rest (949 events). At each impact the pose is made exact
    (the corner hit on the face; a landing whose other corner is within 1e-9 of the block's size,
    flat), which moves the blocks' weight: 5e-7 J at one landing. That energy was not booked, and
    summed to the whole of this run's ledger error, 2.7e-6 of its scale, the worst of the random
    stacks. It is now booked with the impact's (docs/theory/stack.md §6). The ledger, computed
    here from the poses, balances to 1e-8 of the scale (3e-9 measured, at a saved sample between
    events, not at a landing)."""
    stack = Stack(
        blocks=(Block(width=0.7298308016672939, height=0.3857238088819671, mass=381.1675382068276),
                Block(width=0.6046428449307083, height=1.5493253450550246, mass=25.718325545828687,
                      offset=0.01825683249419499),
                Block(width=0.43710031101680247, height=0.3876363440099099, mass=98.28030430613755,
                      offset=0.06524495969353683)),
        interfaces=(Interface(restitution=0.7652131330009031),
                    Interface(friction=Friction(static=0.7375850338922632, kinetic=0.6278463280354877)),
                    Interface(friction=Friction(static=0.7366780710401681, kinetic=0.5611273326989515),
                              restitution=0.6793010542456134)))
    motion = rocking.SinePulse(amplitude=1.9955473952493201, frequency=2.0028930239570597)
    r = simulate_stack(stack, motion, options={"save_dt": 0.005, "max_events": 5000})
    assert r.status == "completed" and not r.overturned
    assert len(r.events) > 500  # the long chatter this is about
    assert _ledger_error(stack, r) <= 1e-8


def test_the_friction_a_stack_at_rest_needs_under_a_record_is_the_floor_s():
    """A squat statue on a pedestal held by μs = 0.8, under a 4 s filtered-noise record of peak
    0.34 g: nothing slides, rocks or lifts, so the engine jumps from sample to sample at rest
    without a step. Each interface still needs |F|/N = |a_g|/g (the whole stack moves with the
    floor), largest at a sample: the summary's required friction of both interfaces must be
    max |a_i|/g, to 1e-12. Until 2026-12-01 the jumps skipped the tracking and it said 0.026,
    the ratio at the run's few tracked instants."""
    stack = Stack(blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=100.0),
                          Block(name="statue", width=0.5, height=0.6, mass=50.0)),
                  interfaces=(Interface(friction=Friction(static=0.8, kinetic=0.7)), Interface()))
    t = np.round(np.arange(0.0, 4.0, 0.01), 10)
    rng = np.random.default_rng(0)
    a = 2.0 * np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same")
    options = rocking.Options()
    r = simulate_stack(stack, GroundMotion(time=t, values=a), options=options)
    s = r.summary()
    need = float(np.max(np.abs(a))) / options.gravity
    assert 0.3 < need < 0.35
    assert all(b["first_sliding_time"] is None and b["first_rocking_time"] is None for b in s["blocks"])
    for interface in s["interfaces"]:
        assert interface["required_friction"] == pytest.approx(need, rel=1e-12)


def test_the_friction_a_stack_at_rest_needs_at_its_first_instant_counts():
    """The same stack under a record whose floor acceleration is largest at t = 0 (2.5 m/s², then
    down to ±1 m/s²): it stays at rest, and each interface needs 2.5/g, at the run's first
    instant, which only the tracking of the starting mode sees (the rest jumps track their ends;
    the start of the first is t = 0). Mutant 43c24a96 read the forces there as known, before any
    were made (zeros: no need), and booked 1/g."""
    stack = Stack(blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=100.0),
                          Block(name="statue", width=0.5, height=0.6, mass=50.0)),
                  interfaces=(Interface(friction=Friction(static=0.8, kinetic=0.7)), Interface()))
    motion = GroundMotion(time=np.array([0.0, 0.1, 0.5, 1.0, 1.5]), values=np.array([2.5, 0.0, 1.0, -1.0, 0.0]))
    options = rocking.Options()
    s = simulate_stack(stack, motion, options=options).summary()
    assert all(b["first_sliding_time"] is None and b["first_rocking_time"] is None for b in s["blocks"])
    for interface in s["interfaces"]:
        assert interface["required_friction"] == pytest.approx(2.5 / options.gravity, rel=1e-14)


@pytest.mark.parametrize("motion", [
    rocking.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form="sin"),
    rocking.Harmonic(amplitude=-3.0, frequency=1.3, cycles=2.5),
    rocking.SinePulse(amplitude=3.0, frequency=2.0, phase=0.4),
    rocking.RickerPulse(amplitude=3.0, frequency=2.0),
    rocking.RickerPulse(amplitude=-3.0, frequency=0.9, center=2.5),
], ids=["sine", "cosine", "sine-pulse", "ricker", "ricker-negative"])
def test_the_friction_a_stack_at_rest_needs_under_a_harmonic_or_a_pulse_is_its_peak_over_g(motion):
    """The stack of the record test above under 3 m/s² harmonics and pulses: it stays at rest
    and integrates steps (the floor motion is not linear between breakpoints), so the friction
    its interfaces need, |a_h|/g, peaks at a crest of the floor acceleration that falls between
    the steps' ends: each interface must need 3/g, to 1e-12. Until 2026-12-02 the engine read it
    at the steps' ends only (0.3012 for the sine in place of 0.3059)."""
    stack = Stack(blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=100.0),
                          Block(name="statue", width=0.5, height=0.6, mass=50.0)),
                  interfaces=(Interface(friction=Friction(static=0.8, kinetic=0.7)), Interface()))
    options = rocking.Options()
    s = simulate_stack(stack, motion, options=options).summary()
    assert all(b["first_sliding_time"] is None and b["first_rocking_time"] is None for b in s["blocks"])
    for interface in s["interfaces"]:
        assert interface["required_friction"] == pytest.approx(3.0 / options.gravity, rel=1e-12)


@pytest.mark.parametrize("frequency, excess", [(f, 1e-4) for f in np.linspace(1.2, 2.3, 12)] + [(13.0, 1e-2), (20.0, 1e-2)])
def test_a_block_at_rest_slips_at_the_first_crest_above_its_friction_wherever_it_falls_in_a_step(frequency, excess):
    """A squat block at rest under a sine a_h = A sin ωt whose crest exceeds μs·g by a fraction
    ``excess`` starts to slip where A sin ωt first reaches μs·g: t = arcsin(1/(1 + excess))/ω.
    The frequencies move the crest across the steps, which grow to max_step at rest. Until
    2026-12-02 a crest near a step's end (1.2, 2.1, 2.2 and 2.3 Hz here) or between the
    step's samples (13 and 20 Hz) was missed: the slip came a cycle late, or never."""
    mu = 0.5
    stack = Stack(blocks=(Block(width=3.0, height=0.3, mass=50.0),),
                  interfaces=(Interface(friction=Friction(static=mu, kinetic=0.45)),))
    motion = rocking.Harmonic(amplitude=mu * G * (1.0 + excess), frequency=frequency, form="sin", cycles=1.0)
    first = simulate_stack(stack, motion).summary()["blocks"][0]["first_sliding_time"]
    assert first is not None
    assert abs(first - math.asin(1.0 / (1.0 + excess)) / (2.0 * math.pi * frequency)) < 1e-9


def _ricker(amplitude, frequency, center, t):
    """The Ricker wavelet a_p (1 − 2x) e^(−x), x = (πf(t − t₀))², written here from its formula."""
    x = (math.pi * frequency * (t - center)) ** 2
    return amplitude * (1.0 - 2.0 * x) * math.exp(-x)


@pytest.mark.parametrize("frequency, center, excess", [(2.0, 1.0, 1e-2), (6.0, 2.11, 1e-3), (10.0, 1.0, 1e-3),
                                                      (15.0, 1.37, 1e-2), (20.0, 2.11, 1e-2), (30.0, 1.0, 1e-3)])
def test_a_block_at_rest_slips_where_a_ricker_pulse_first_exceeds_its_friction(frequency, center, excess):
    """A squat block at rest (μs = 0.5) under a Ricker pulse whose peak exceeds μs·g by a fraction
    ``excess`` starts to slip where the pulse first reaches μs·g, the root before its centre
    (brentq on the formula, to 1e-14 s), to 1e-9 s. At rest the steps grow to max_step, 0.1 s,
    with samples 25 ms apart, and the main lobe (1/f wide) passes between them: the crest search
    of a step at rest finds it (with the crest search's result dropped, mutant bcdb22d7, 21 of 48
    such pulses never slipped)."""
    from scipy.optimize import brentq

    mu = 0.5
    stack = Stack(blocks=(Block(width=3.0, height=0.3, mass=50.0),),
                  interfaces=(Interface(friction=Friction(static=mu, kinetic=0.45)),))
    amplitude = mu * G * (1.0 + excess)
    motion = rocking.RickerPulse(amplitude=amplitude, frequency=frequency, center=center)
    first = simulate_stack(stack, motion).summary()["blocks"][0]["first_sliding_time"]
    want = brentq(lambda t: _ricker(amplitude, frequency, center, t) - mu * G, center - 0.3 / frequency, center,
                  xtol=1e-14)
    assert first is not None and abs(first - want) < 1e-9


@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("frequency, center", [(10.0, 1.0), (20.0, 2.11)])
def test_a_block_at_rest_starts_to_rock_where_a_ricker_pulse_first_exceeds_its_uplift(frequency, center, sign):
    """A 0.4 × 1.6 m block that never slips under a Ricker pulse whose peak exceeds its uplift
    acceleration g·b/h by 1e-3, pushing either way: it starts to rock where the pulse first
    reaches g·b/h (brentq on the formula), to 1e-9 s. Its main lobe passes between the samples of
    a step at rest, so the crest search finds the corner force that fails: the left corner's
    (the interface's first guard) under a push towards −x, the right one's under +x. (Mutant
    d1fe3b4b, ``first >= 1``, dropped a failure of the first guard: under the −x pushes the block
    never rocked.)"""
    from scipy.optimize import brentq

    width, height = 0.4, 1.6
    stack = Stack(blocks=(Block(width=width, height=height, mass=50.0),), interfaces=(Interface(),))
    uplift = G * width / height
    amplitude = sign * uplift * (1.0 + 1e-3)
    motion = rocking.RickerPulse(amplitude=amplitude, frequency=frequency, center=center)
    first = simulate_stack(stack, motion, duration=center + 1.0).summary()["blocks"][0]["first_rocking_time"]
    want = brentq(lambda t: sign * _ricker(amplitude, frequency, center, t) - uplift, center - 0.3 / frequency,
                  center, xtol=1e-14)
    assert first is not None and abs(first - want) < 1e-9


# Rocking blocks (width, height, sine amplitude m/s², frequency Hz; 100 kg, two cycles) whose
# floor friction need peaks inside a step: random cases in which a585e4a's engine missed the slip
# of a floor face just weaker than the need.
_NEAR_SLIP = [
    (0.21102364529722736, 1.0840909036443807, 3.449815836308134, 1.855141492797095),
    (0.5922948799204955, 3.4742834119614447, 3.4894287716131784, 2.5319259377517893),
    (0.49011757523049554, 2.346943221622911, 3.37263861572432, 3.5754256180550374),
    (0.5052514130176213, 2.497269527076443, 2.367046625004897, 2.0039632045699016),
    (0.45010459376604267, 2.21797136925793, 3.5469575514272704, 1.7886982370418918),
    (0.5763736750647607, 1.846822986489538, 7.597291124944444, 3.226578758412219),
    (0.49637778129526355, 2.3713721325795136, 3.920239278195061, 0.9089458632888814),
]


def _near_slip_pair(width, height, mu):
    friction = Friction(static=mu, kinetic=0.9 * mu)
    return (Stack(blocks=(Block(width=width, height=height, mass=100.0),), interfaces=(Interface(friction=friction),)),
            rocking.System(statue=rocking.Statue(width=width, height=height, mass=100.0, friction=friction)))


@pytest.mark.parametrize("case", range(len(_NEAR_SLIP)))
def test_a_rocking_block_whose_friction_need_peaks_just_above_mu_s_slips_when_todays_solver_says(case):
    """The floor face 1e-4 and 1e-6 below the friction the rocking block needs (the two-body
    solver's, checked against sympy): the block slips, when the two-body solver says, to 1e-8 s
    (the two solvers' event location: they agree to 5e-9 s here). The slip lasts a fraction of a
    millisecond at first; a585e4a's engine missed it in all seven cases: a dip between a step's
    last two samples, or just after an impact before the second."""
    width, height, amp, f = _NEAR_SLIP[case]
    motion = rocking.Harmonic(amplitude=amp, frequency=f, form="sin", cycles=2.0)
    need = rocking.simulate(_near_slip_pair(width, height, 5.0)[1], motion).summary()["required_top_friction"]
    for below in (1e-4, 1e-6):
        stack, system = _near_slip_pair(width, height, need * (1.0 - below))
        ours = simulate_stack(stack, motion).summary()["blocks"][0]["first_sliding_time"]
        ref = rocking.simulate(system, motion).summary()["first_sliding_time"]
        assert ref is not None and ours is not None, below
        assert abs(ours - ref) < 1e-8, (below, ours, ref)


@pytest.mark.parametrize("case", range(len(_NEAR_SLIP)))
def test_the_friction_a_rocking_block_needs_is_its_peak_between_the_samples(case):
    """The largest |T|/N the floor face of a rocking block needs, against the two-body solver's
    (checked against sympy), to 1e-9: measured 3e-11. a585e4a's engine read it at step ends and
    events only, up to 1e-3 low (0.263010 for 0.263252 on a 0.4 × 1.6 m block). In case 1 the
    need peaks 3 ms before an impact, and there the two-body solver read 9e-5 low until
    2026-12-02 (its search in a step cut by an event never ran)."""
    width, height, amp, f = _NEAR_SLIP[case]
    motion = rocking.Harmonic(amplitude=amp, frequency=f, form="sin", cycles=2.0)
    stack, system = _near_slip_pair(width, height, 5.0)
    ours = simulate_stack(stack, motion).summary()["interfaces"][0]["required_friction"]
    ref = rocking.simulate(system, motion).summary()["required_top_friction"]
    assert ours == pytest.approx(ref, rel=1e-9)


def test_the_friction_a_rocking_block_needs_peaks_just_before_an_impact_as_its_saved_forces_show():
    """``rocking.simulate``'s required_top_friction for a single rocking block is the largest
    |P_x|/P_y of its own saved forces (every 20 µs), which can only read lower: at most by the
    curvature of the need over 10 µs, 1e-9 of it here. Its peak falls 3 ms before an impact, in
    the step cut by the event; until 2026-12-02 that step's search never ran (0.215422 against
    the saved forces' 0.215442)."""
    width, height, amp, f = _NEAR_SLIP[1]
    motion = rocking.Harmonic(amplitude=amp, frequency=f, form="sin", cycles=2.0)
    r = rocking.simulate(_near_slip_pair(width, height, 5.0)[1], motion, options=dict(save_dt=2e-5))
    forces = r.contact_forces()
    saved = np.nanmax(np.abs(forces["Px"]) / forces["Py"])
    need = r.summary()["required_top_friction"]
    assert saved * (1.0 - 1e-12) <= need <= saved * (1.0 + 1e-9), (need, saved)


def test_the_friction_a_face_needs_stops_counting_once_the_block_under_it_topples():
    """A 0.30 × 0.64 m statue (208 kg) that never slips, on a 0.52 × 0.66 m plinth (55 kg) that
    rocks and topples under two cycles of a 14 m/s² sine: once the plinth is past its tipping
    angle atan(B/H) the two fall together, the force between them tends to zero, and |T|/N up
    there is no design quantity (as for a block past its own angle). So the statue's face needs
    over the whole run what it needed up to the first saved sample past that angle (the run
    stopped there: rel 1e-6, the clipped last step's dense output differing by ~1e-10), a
    plain coefficient. Before 2026-12-03 the need went on counting: 5.1e11 (its normal force
    at the located overturn, 1e-12 of the weight)."""
    stack = Stack(blocks=(Block(width=0.5248767321494551, height=0.6596542686448617, mass=54.7993174198779),
                          Block(width=0.29761319857503443, height=0.6396475396036482, mass=207.7748361142165)),
                  interfaces=(Interface(friction=Friction(static=0.7307695780368777, kinetic=0.3)), Interface()))
    motion = rocking.Harmonic(amplitude=13.946795264748074, frequency=2.776607466937357, cycles=2.0, form="sin")
    full = simulate_stack(stack, motion, duration=3.0, options={"save_dt": 1e-3})
    assert full.blocks[0]["overturned"] and not full.blocks[1]["overturned"]
    tipped = np.abs(full.rotation[:, 0]) >= math.atan2(0.5248767321494551, 0.6596542686448617)
    first = int(np.argmax(tipped))
    assert tipped[first:].all() and np.all(full.normal_state[:first, 1] > 0)  # it never comes back
    cut = simulate_stack(stack, motion, duration=float(full.t[first]), options={"save_dt": 1e-3})
    need = full.interfaces[1]["required_friction"]
    assert need == pytest.approx(cut.interfaces[1]["required_friction"], rel=1e-6)
    assert 0.5 < need < 1.0


@pytest.mark.parametrize("r", [0.6, 0.3])
@pytest.mark.parametrize("grip", [None, 5.0])
@pytest.mark.parametrize("law", ["coulomb", "paper"])
def test_the_friction_an_impact_needs_counts_in_the_interfaces_need(r, grip, law):
    """A 0.2 × 1.2 m block rocking on a floor face that never slips, with θ̇⁺ = r·θ̇⁻ at its
    impacts. The impulse of an impact is the change of the block's momentum: m·(h/2)·Δθ̇ along
    the floor and m·(b/2)·(|θ̇⁺| + |θ̇⁻|) across it, so each impact needs the friction
    (h/b)·(1 − r)/(1 + r) (1.5 and 3.23 here) whatever its speed, far more than the forces
    between impacts (0.217). Until 2026-12-03 the stack engine left impacts out of an interface's
    need and reported that 0.217; the two-body solver counts them (its required_top_friction).
    ``grip``: the face's μs = μk (None: it never slips); at 5 every impact sticks. Both impact
    laws give a block alone the same θ̇⁺ = r·θ̇⁻ with its base held, so the same need."""
    width, height = 0.2, 1.2
    friction = None if grip is None else Friction(static=grip, kinetic=grip)
    stack = Stack(blocks=(Block(width=width, height=height, mass=50.0),),
                  interfaces=(Interface(friction=friction, restitution=r),))
    motion = rocking.SinePulse(amplitude=0.4 * G, frequency=1.5)
    res = simulate_stack(stack, motion, duration=3.0, options={"gravity": G, "impact": law})
    assert res.summary()["impacts"] >= 3 and not res.blocks[0]["overturned"]
    expected = height / width * (1.0 - r) / (1.0 + r)
    assert res.interfaces[0]["required_friction"] == pytest.approx(expected, rel=1e-9)
    two_body = rocking.simulate(rocking.System(statue=rocking.Statue(width=width, height=height, mass=50.0,
                                                                     friction=friction, restitution=r)),
                                motion, duration=3.0, options={"gravity": G, "impact": law})
    assert two_body.summary()["required_top_friction"] == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("slipping", [False, True])
def test_an_impulse_is_split_along_the_face_of_the_block_it_crosses_onto(slipping):
    """The need of an impact (``engine._impact_needs``) at a given outcome: a statue flat on a
    pedestal tilted by Θ = 0.1 rad (clockwise, towards +x: the frame turns by
    R(Θ) = [[cos Θ, sin Θ], [−sin Θ, cos Θ]], so the pedestal's top face runs along
    (cos Θ, −sin Θ) with its normal (sin Θ, cos Θ)), both brought to rest from given centre
    velocities. The impulse into the statue is m₂·(0 − v₂), split along that face and across it;
    the one through the floor is everything's change of momentum, split along the floor. A face
    that slips through the impact needs nothing (its friction is μk·N, not a need)."""
    from rocking.stack.modes import FLAT, ROCK
    from rocking.stack.simulate import pack

    m1, m2, tilt = 300.0, 100.0, 0.1
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=m1), Block(width=0.3, height=1.2, mass=m2)),
                  interfaces=(Interface(), Interface(friction=Friction(static=5.0, kinetic=5.0))))
    P, ends, anchor, z = pack(stack)
    z = z.copy()
    z[1] = tilt  # the pedestal rocks on its corner; the statue sits flat on it
    v1, v2 = np.array([0.3, -0.05]), np.array([0.8, -0.6])
    summ = np.zeros((2, engine.N_BLOCK_SUMMARY))
    engine._impact_needs(P, ends, anchor, np.array([ROCK, FLAT], dtype=np.int64),
                         np.array([0, 1 if slipping else 0], dtype=np.int64), z, np.zeros_like(z),
                         np.array([v1, v2]), summ, 0.0)
    impulse = -m2 * v2
    along = impulse @ [math.cos(tilt), -math.sin(tilt)]
    across = impulse @ [math.sin(tilt), math.cos(tilt)]
    assert across > 0.0
    assert summ[1, engine.B_MU_REQ] == (0.0 if slipping else pytest.approx(abs(along) / across, rel=1e-12))
    floor = -m1 * v1 - m2 * v2
    assert summ[0, engine.B_MU_REQ] == pytest.approx(abs(floor[0]) / floor[1], rel=1e-12)


def test_the_friction_a_rocking_block_needs_just_before_an_impact_is_found_in_the_step_the_impact_cuts():
    """A block whose floor face's need peaks 0.1 ms before an impact (θ = 2e-4 rad there): the
    stack engine's need must be the largest |P_x|/P_y of the two-body solver's saved forces
    (every 10 µs; a lower bound, 1e-10 below the peak here), to 1e-9. Until 2026-12-02 the
    stretch between the last sample of the step and the impact was not searched: 0.2583853
    for 0.2584108."""
    width, height, amp, f = 0.5583895281255041, 2.9137754037140655, 4.605614512199354, 2.6922176267460576
    motion = rocking.Harmonic(amplitude=amp, frequency=f, form="sin", cycles=2.0)
    stack, system = _near_slip_pair(width, height, 5.0)
    r = rocking.simulate(system, motion, duration=4.0, options=dict(save_dt=1e-5))
    forces = r.contact_forces()
    alpha = math.atan2(width, height)
    saved = np.nanmax(np.where(np.abs(r.theta) <= alpha, np.abs(forces["Px"]) / forces["Py"], -1.0))
    ours = simulate_stack(stack, motion, duration=4.0).summary()["interfaces"][0]["required_friction"]
    assert saved * (1.0 - 1e-12) <= ours <= saved * (1.0 + 1e-9), (ours, saved)
    # and the two-body solver's own, whose step cut by the impact is searched up to it
    need = r.summary()["required_top_friction"]
    assert saved * (1.0 - 1e-12) <= need <= saved * (1.0 + 1e-9), (need, saved)


def test_a_light_block_at_rest_needs_the_floors_peak_over_g():
    """A 50 g block (0.1 × 0.4 m, its weight 0.49 N) at rest on a face that never slips, under a
    1 m/s² sine at 2 Hz, below its uplift (g·b/h = 2.45 m/s²): the friction its face needs is the
    floor's peak over g, 1/9.80665, to 1e-12, however small its normal force (a mutant that
    counted only normal forces above 1 N read 0)."""
    stack = Stack(blocks=(Block(width=0.1, height=0.4, mass=0.05),), interfaces=(Interface(),))
    r = simulate_stack(stack, rocking.Harmonic(amplitude=1.0, frequency=2.0, cycles=2.0, form="sin"), duration=1.5)
    assert r.blocks[0]["first_rocking_time"] is None
    assert r.interfaces[0]["required_friction"] == pytest.approx(1.0 / 9.80665, rel=1e-12)


@pytest.mark.parametrize("masses", [(300.0, 100.0), (40.0, 7.0), (1.0, 1.0), (250.0, 60.0), (500.0, 80.0),
                                    (120.0, 45.0)])
def test_faces_of_equal_friction_at_their_limit_together_slip_at_the_top_whatever_the_rounding(masses):
    """A statue (0.6 × 0.8 m) at rest on a pedestal (0.8 × 0.5 m), both faces μs = 0.3, μk = 0.2,
    under 1.02 μs g sin ωt (5 Hz): both faces need sin ωt /0.98 · μs and reach their limit together
    at t* = asin(1/1.02)/ω, where Coulomb's law lets either slip. The rule (docs/theory/stack.md
    §5): the highest face gives way, as the mode order has it from rest. So the statue slides on
    its pedestal from t* (to the 1e-9 s of event location), the floor face holds for the two
    cycles, for every pair of masses. (Before the rule, the rounding of the two located roots
    chose: the floor face slid first for five of these pairs, the top face for 500/80 kg.)"""
    pedestal, statue = masses
    stack = Stack(blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=pedestal),
                          Block(name="statue", width=0.6, height=0.8, mass=statue)),
                  interfaces=(Interface(friction=Friction(static=0.3, kinetic=0.2)),
                              Interface(friction=Friction(static=0.3, kinetic=0.2))))
    motion = rocking.Harmonic(amplitude=1.02 * 0.3 * G, frequency=5.0, cycles=2, form="sin")
    r = simulate_stack(stack, motion, options=rocking.Options(save_dt=0.01))
    onset = math.asin(1.0 / 1.02) / (2.0 * math.pi * 5.0)
    floor, top = r.blocks
    assert top["first_sliding_time"] == pytest.approx(onset, abs=1e-9) and top["peak_sliding"] > 1e-4
    assert floor["first_sliding_time"] is None and floor["peak_sliding"] == 0.0
