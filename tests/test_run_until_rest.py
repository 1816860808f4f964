"""A run is not over when the floor stops (issue 10 §1).

Without ``duration`` a run goes on after the motion, on a still floor, until every body is at
rest or the statue falls (at most ``free_time_limit`` s). A run cut short while anything moves
says "undetermined", never "did not overturn". The verdicts are checked against longer runs
and, for the free slide after the motion, against its closed form.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import rocking as rk
from rocking.cli import main
from rocking.solver.crosscheck import simulate_crosscheck
from rocking.simulation import ResourceLimitError

from helpers import alone, block, free_rocking

G = 9.81
OPTS = rk.Options(gravity=G)

# The issue's example: a 0.3 m × 1.2 m statue under one 6 m/s², 1 Hz sine pulse. The pulse is
# over at 1 s, the statue falls at 1.334 s.
ISSUE_STATUE = rk.Statue(width=0.3, height=1.2, mass=100.0)
ISSUE_PULSE = rk.SinePulse(amplitude=6.0, frequency=1.0)
ISSUE_TOML = """
[statue]
width = 0.3
height = 1.2
mass = 100.0
[motion]
kind = "pulse"
shape = "sine"
amplitude = 6.0
frequency = 1.0
"""


def test_a_statue_falling_after_the_pulse_is_reported_as_falling():
    r = rk.simulate(rk.System(statue=ISSUE_STATUE), ISSUE_PULSE)
    longer = rk.simulate(rk.System(statue=ISSUE_STATUE), ISSUE_PULSE, duration=20.0)
    assert ISSUE_PULSE.duration == pytest.approx(1.0)
    assert r.overturned and longer.overturned
    # The same run as the explicit 20 s one, up to the fall (same solver steps: same numbers).
    assert r.overturn_time == pytest.approx(longer.overturn_time, abs=1e-12)
    assert r.overturn_time == pytest.approx(1.334, abs=5e-4) and r.overturn_time > ISSUE_PULSE.duration
    assert r.summary()["verdict"] == f"overturned at t = {r.overturn_time:.3f} s"
    # Cut at the end of the pulse, the run must not claim that the statue survives.
    cut = rk.simulate(rk.System(statue=ISSUE_STATUE), ISSUE_PULSE, duration=ISSUE_PULSE.duration)
    s = cut.summary()
    assert s["status"] == "still_moving" and s["still_moving"] and not s["overturned"]
    assert s["verdict"] == "undetermined: still moving at t = 1.000 s"
    assert any("still moving" in w for w in s["warnings"])


def test_cli_says_overturned_and_undetermined(capsys, tmp_path):
    f = tmp_path / "issue.toml"
    f.write_text(ISSUE_TOML, encoding="utf-8")
    assert main(["run", str(f), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["overturned"] and s["verdict"].startswith("overturned at t = 1.33")
    f.write_text(ISSUE_TOML + "[simulation]\nduration = 1.0\n", encoding="utf-8")
    assert main(["run", str(f)]) == 0
    out = capsys.readouterr().out
    assert "undetermined: still moving at t = 1.000 s" in out
    assert "did not overturn" not in out
    assert main(["run", str(f), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["still_moving"] is True and s["status"] == "still_moving"


def test_free_slide_after_the_motion_stops_as_its_closed_form():
    """A squat block still sliding when the floor stops decelerates at μk·g: it stops after
    |v|/(μk g) and slides v²/(2 μk g) further (independent of the solver's equations)."""
    mu_s, mu_k = 0.3, 0.2
    squat = block(0.5, 0.25, friction=rk.Friction(static=mu_s, kinetic=mu_k))  # tan α = 2: never rocks
    motion = rk.Harmonic(amplitude=5.0, frequency=1.0, cycles=2.25, form="sin")  # ends at a crest of the velocity
    at_end = rk.simulate(alone(squat), motion, duration=motion.duration, options=OPTS)
    assert at_end.status == "still_moving"
    u_m, v_m = float(at_end.u[-1]), float(at_end.u_dot[-1])
    assert abs(v_m) > 0.05  # sliding when the floor stops
    r = rk.simulate(alone(squat), motion, options=OPTS)
    s = r.summary()
    assert s["status"] == "completed" and not s["still_moving"]
    assert s["end_time"] == pytest.approx(motion.duration + abs(v_m) / (mu_k * G), abs=1e-9)
    assert s["residual_sliding"] == pytest.approx(u_m + math.copysign(v_m**2 / (2 * mu_k * G), v_m), abs=1e-9)
    assert s["verdict"] == f"did not overturn; at rest at t = {s['end_time']:.3f} s"
    # At rest means stuck with zero velocity (the last saved state).
    assert r.u_dot[-1] == 0.0 and r.theta[-1] == 0.0 and r.theta_dot[-1] == 0.0


def test_free_rocking_after_the_motion_ends_at_rest_and_agrees_with_the_integrator_crosscheck():
    statue = block(0.25, 1.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=4.0, frequency=1.2, cycles=3)  # rocks, does not fall
    r = rk.simulate(alone(statue), motion, options=OPTS)
    ref = simulate_crosscheck(alone(statue), motion, options=OPTS)
    assert r.status == ref["status"] == "completed"
    assert r.end_time > motion.duration + 0.5  # the statue rocked on after the floor stopped
    # Both end at the impact that the rest rule closes (|θ̇⁺| below rest_velocity).
    assert r.end_time == pytest.approx(ref["end_time"], abs=1e-8)
    assert r.theta[-1] == 0.0 and r.theta_dot[-1] == 0.0
    # The end does not depend on the cap, as long as the cap is longer.
    capped = rk.simulate(alone(statue), motion, options=rk.Options(gravity=G, free_time_limit=30.0), save=False)
    assert capped.end_time == r.end_time
    short = rk.simulate(alone(statue), motion, options=rk.Options(gravity=G, free_time_limit=0.2))
    assert short.status == "still_moving"
    assert short.end_time == pytest.approx(motion.duration + 0.2, abs=1e-12)
    # still rocking when cut, but (as the full run shows) it cannot fall any more: its energy decides it
    assert short.settled_by_energy and short.summary()["verdict"].startswith("did not overturn; still moving")


def test_a_run_ending_before_the_motion_is_undetermined_even_at_rest():
    statue = block(0.15, 0.6)
    quiet = rk.Harmonic(amplitude=0.5, frequency=1.0, cycles=10)  # below the rocking threshold
    r = rk.simulate(alone(statue), quiet, duration=3.0)
    assert r.status == "completed" and not r.still_moving
    assert r.verdict.startswith("undetermined: the run ended at t = 3.000 s, before the floor motion")
    assert r.summary()["verdict"] == r.verdict
    assert any("before the floor motion did" in w for w in r.warnings)


def test_a_quiet_statue_ends_with_the_motion():
    statue = block(0.15, 0.6)
    quiet = rk.Harmonic(amplitude=0.5, frequency=1.0, cycles=2)
    r = rk.simulate(alone(statue), quiet)
    assert r.status == "completed" and r.end_time == pytest.approx(quiet.duration, abs=1e-12)
    assert r.t[-1] == pytest.approx(quiet.duration, abs=1e-12)


def test_batch_summaries_carry_still_moving():
    from rocking.analyses.batch import run_cases

    statue = block(0.25, 1.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=4.0, frequency=1.2, cycles=3)
    ds = run_cases([(alone(statue), motion)] * 2, options=OPTS, workers=1)
    assert not ds.still_moving.values.any() and ds.verdict.values[0].startswith("did not overturn")
    ds = run_cases([(alone(statue), motion)], options=OPTS, duration=0.9 * motion.duration, workers=1)
    assert ds.still_moving.values.all() and ds.verdict.values[0].startswith("undetermined")
    assert not ds.settled_by_energy.values.any()
    # cut as the floor stops, it rocks on with too little energy to overturn (as the full run shows)
    ds = run_cases([(alone(statue), motion)], options=OPTS, duration=motion.duration, workers=1)
    assert ds.still_moving.values.all() and ds.settled_by_energy.values.all()
    assert ds.verdict.values[0].startswith("did not overturn; still moving")


# ------------------------------------------------------------------------ bounded resources
def test_a_run_that_would_not_fit_in_memory_is_refused_before_it_starts():
    statue = block(0.15, 0.6)
    motion = rk.Harmonic(amplitude=0.5, frequency=1.0, cycles=2)
    with pytest.raises(ResourceLimitError, match=r"^simulation\.save_dt: 1e-09 s over 1e\+06 s would store 1e\+15 "
                                                 r"samples \(4\.1e\+04 TB|^simulation\.save_dt: 1e-09 s over 1e\+06 s "
                                                 r"would store 1e\+15 samples \(41 PB"):
        rk.simulate(alone(statue), motion, duration=1e6, options=rk.Options(save_dt=1e-9))
    with pytest.raises(ResourceLimitError, match=r"simulation\.max_samples"):
        rk.simulate(alone(statue), motion, duration=1e6)  # 1e8 samples at 0.01 s
    # Without saving, the series costs nothing and the run is allowed.
    assert rk.simulate(alone(statue), motion, duration=1e3, save=False).status == "completed"
    # The limit can be raised.
    r = rk.simulate(alone(statue), motion, duration=10.0, options=rk.Options(save_dt=1e-3, max_samples=20_000))
    assert r.t.size >= 10_001
    with pytest.raises(ResourceLimitError, match=r"^simulation\.max_events"):
        rk.simulate(alone(statue), motion, options=rk.Options(max_events=10**8))


# ------------------------------------------------------------------------------ bad input
@pytest.mark.parametrize(
    ("kwargs", "error", "words"),
    [
        ({"initial_rotation": "0.1"}, TypeError, "initial_rotation must be a number (rad), got '0.1'"),
        ({"initial_rotation": math.nan}, ValueError, "initial_rotation must be a finite number (rad), got nan"),
        ({"initial_angular_velocity": math.inf}, ValueError, "initial_angular_velocity must be a finite number"),
        ({"options": {"rtol": 1e-8, "tolerance": 1}}, ValueError, "options: unknown key 'tolerance'"),
        ({"options": 3}, TypeError, "options must be rocking.Options or a dict"),
        ({"options": {"free_time_limit": -1.0}}, ValueError, "simulation.free_time_limit must be a number ≥ 0"),
    ],
)
def test_bad_arguments_get_a_one_line_error(kwargs, error, words):
    with pytest.raises(error) as info:
        rk.simulate(alone(block(0.15, 0.6)), rk.Harmonic(amplitude=0.5, frequency=1.0), **kwargs)
    assert words in str(info.value) and "\n" not in str(info.value)


def test_options_may_be_a_dict():
    motion = rk.Harmonic(amplitude=0.5, frequency=1.0)
    a = rk.simulate(alone(block(0.15, 0.6)), motion, options={"gravity": 9.81, "save_dt": 0.05})
    assert a.options == rk.Options(gravity=9.81, save_dt=0.05)
    assert np.allclose(np.diff(a.t), 0.05)


def test_an_implausible_pga_is_flagged():
    statue = block(0.5, 0.5)  # squat: survives anything briefly
    motion = rk.Harmonic(amplitude=6.0 * 9.80665, frequency=5.0, cycles=1)
    assert any("above 5 g" in w for w in rk.simulate(alone(statue), motion).warnings)
    calm = rk.Harmonic(amplitude=4.0 * 9.80665, frequency=5.0, cycles=1)
    assert not any("above 5 g" in w for w in rk.simulate(alone(statue), calm).warnings)


# ------------------------------------------------------------------------------ interrupts
_LONG_RUN = """
import signal, sys, time
# Ctrl-C as in a terminal: a test runner started in the background (nohup, `cmd &` in a script)
# hands its children SIGINT ignored, and an ignored signal rightly stays ignored (solver/signals.py).
signal.signal(signal.SIGINT, signal.default_int_handler)
import rocking as rk
system = rk.System(statue=rk.Statue(width=1.0, height=4.0, mass=1.0),
                   pedestal=rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.1, kinetic=0.08)))
floor = rk.Harmonic(amplitude=2.0, frequency=1.2, cycles=1e8)  # slides for ever: hours of solver time
rk.simulate(system, floor, duration=0.5, save=False)  # compiled (or loaded from the cache) first
print("busy", flush=True)
t0 = time.perf_counter()
try:
    rk.simulate(system, floor, duration=1e8, save=False, options=rk.Options(max_events=2_000_000))
except KeyboardInterrupt:
    print(f"KeyboardInterrupt after {time.perf_counter() - t0:.3f} s", flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


@pytest.mark.parametrize("signum", ["SIGINT", "SIGTERM"])
def test_a_signal_during_a_compiled_run_stops_it_cleanly(signum, tmp_path):
    """Ctrl-C raises KeyboardInterrupt within the solver's polling interval; SIGTERM ends the
    process as SIGTERM does. Before issue 10 both crashed it with a segmentation fault."""
    import signal
    import subprocess
    import sys
    import time

    script = tmp_path / "long_run.py"
    script.write_text(_LONG_RUN, encoding="utf-8")
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "busy"
        time.sleep(0.5)  # well inside the long run
        sent = time.perf_counter()
        proc.send_signal(getattr(signal, signum))
        out, err = proc.communicate(timeout=20)
        latency = time.perf_counter() - sent
    finally:
        proc.kill()
    assert "finished" not in out
    if signum == "SIGINT":
        assert proc.returncode == 3, err
        assert "KeyboardInterrupt after" in out
    else:
        assert proc.returncode == -signal.SIGTERM, err
    assert "Segmentation fault" not in err and "Fatal Python error" not in err
    assert latency < 5.0  # the solver polls every few thousand steps: milliseconds, with a wide margin


def test_an_ignored_sigint_stays_ignored(tmp_path):
    """A background job of a shell script (or nohup) ignores Ctrl-C: the solver must not stop."""
    import signal
    import subprocess
    import sys
    import time

    script = tmp_path / "ignored.py"
    script.write_text(
        "import signal\n"
        "import rocking as rk\n"
        "signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
        "system = rk.System(statue=rk.Statue(width=1.0, height=4.0, mass=1.0),\n"
        "                   pedestal=rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.1, kinetic=0.08)))\n"
        "floor = rk.Harmonic(amplitude=2.0, frequency=1.2, cycles=1e8)\n"
        "rk.simulate(system, floor, duration=0.5, save=False)\n"
        "print('busy', flush=True)\n"
        "r = rk.simulate(system, floor, duration=1e8, save=False, options=rk.Options(max_events=150_000))\n"
        "print(r.status, flush=True)\n",
        encoding="utf-8",
    )
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "busy"
        time.sleep(0.3)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 0, err
    assert out.strip() == "max_events"  # ran to its own end, not "interrupted"


# ----------------------------------------------------------------------- studies: the same rule
def _abrupt_record(amplitude: float) -> "rk.GroundMotion":
    """A 1.25-cycle sine sampled at 5 ms that stops at its crest: the statue is still rocking
    when the record ends."""
    from rocking.excitation.record import GroundMotion

    t = np.arange(0.0, 1.25 + 1e-9, 0.005)
    return GroundMotion(time=t, values=amplitude * np.sin(2 * np.pi * t), name="abrupt")


def test_fragility_counts_a_run_still_moving_at_the_cap_with_too_little_energy_to_fall_as_a_survival():
    from rocking.analyses.fragility import ida

    statue = block(0.25, 1.0, restitution=0.8)  # g·tan α = 2.45 m/s²
    record = _abrupt_record(1.0)
    levels = [2.8, 3.0]  # PGA, m/s²: rocks, does not fall
    settled = ida({"statue": alone(statue)}, {"abrupt": record}, levels, options=OPTS, workers=1)
    assert not settled.still_moving.any() and not settled.fall.any()
    assert int(settled.undetermined.sum()) == 0
    cut = ida({"statue": alone(statue)}, {"abrupt": record}, levels, free_time=0.0, options=OPTS, workers=1)
    assert cut.still_moving.all()  # rocking when the record ends, and no free time to settle
    # but with too little energy left to overturn: shown to survive, as the full runs confirm (a run
    # still moving with more energy counts as a fall: tests/test_fragility.py)
    assert cut.settled_by_energy.all() and not cut.fall.any() and not cut.overturned.any()
    assert int(cut.undetermined.sum()) == 0 and int(cut.settled.sum()) == len(levels)


def test_spectrum_counts_runs_still_moving_at_the_cap():
    from rocking.analyses.spectra import overturning_spectrum

    statue = rk.Statue(width=0.3, height=1.5, mass=1.0)
    kw = dict(frequency_ratios=[2.0], amplitude_range=(1.5, 3.0), n_scan=3, rtol=0.05, options=OPTS, workers=1)
    full = overturning_spectrum(rk.System(statue=statue), "sine", **kw)
    cut = overturning_spectrum(rk.System(statue=statue), "sine", free_time=0.0, **kw)
    assert int(full.undetermined_runs.sum()) == 0
    assert int(cut.undetermined_runs.sum()) > 0
    assert int(cut.undetermined_runs.sum()) <= int(cut.runs.sum())


@pytest.mark.parametrize("criterion", ["overturn", "no_impact", "exceed"])
def test_a_spectrum_never_shows_safe_what_a_longer_run_shows_failing(criterion):
    """Cut every run at the end of its pulse (``free_time = 0``): a block that rocks is then still
    moving. If its energy is below the overturning barrier it cannot fall (``settling_runs``,
    safe); otherwise its outcome is unknown. Counted as failing (the default), the cut spectrum
    fails wherever the full one does, so its boundary is never above the true one; counted as safe
    it fails only where the full one does. Until 2026-12-07 the spectrum counted such runs as safe
    only. A settling run that fell later, or an unknown one counted safe, breaks the first; an
    unknown one counted failing that the full run shows safe is what the second rule avoids."""
    from rocking.analyses.spectra import overturning_spectrum

    system = rk.System(statue=rk.Statue(width=0.3, height=1.5, mass=1.0))
    kw = dict(frequency_ratios=[1.0, 3.0], amplitude_range=(1.2, 12.0), n_scan=12, rtol=1e-2, criterion=criterion,
              options=OPTS, workers=1)
    full = overturning_spectrum(system, "sine", free_time=400.0, **kw)
    strict = overturning_spectrum(system, "sine", free_time=0.0, **kw)
    lenient = overturning_spectrum(system, "sine", free_time=0.0, undetermined="safe", **kw)
    assert int(full.undetermined_runs.sum()) == 0, "the full runs all reach an outcome"
    assert strict.attrs["undetermined"] == "fail" and lenient.attrs["undetermined"] == "safe"
    f, s, ln = (ds.scan_fails.values for ds in (full, strict, lenient))
    assert np.all(s >= f) and np.all(ln <= f)
    assert int(strict.undetermined_runs.sum()) > 0 and int(strict.settling_runs.sum()) > 0
    assert np.any(s != ln), "some scanned runs are unknown at the cut, and the two rules count them apart"
    b_full, b_strict = full.amplitude_ratio_upper.values, strict.amplitude_ratio_upper.values
    assert np.all(b_strict <= b_full * (1 + 1e-12))


def test_a_statue_still_rocking_with_less_energy_than_its_barrier_is_settled_and_one_above_is_not():
    """The solver's rule (``settled_by_energy``, slot ``S_SETTLED``) against the barrier
    m·g·R·(1 − cos α) written here. A 0.3 × 1.5 m, 2 kg statue rocks freely (g = 9.5) with
    energy 1e-7 below or above its barrier, cut 0.06 s later, far inside α: settled just below,
    not just above (the run's ledger error, ~1e-12 of the energy, is far inside 1e-7). Past α
    (θ0 = 1.001 α, at rest: E is below the barrier, but its weight now works for it) it is not;
    nor is it while the floor motion has not ended (a zero rectangle pulse 1 s long, cut at
    0.06 s: the floor may yet give it energy; a record cut from a longer one by ``trimmed``,
    whose floor goes on in the real record), nor under the paper's impact law (Eq. 1) on a
    pedestal that slides, which can add energy at an impact; on a statue that cannot slide,
    Eq. 1 only takes energy, and the rule holds."""
    from rocking.solver import compiled as C

    statue = rk.Statue(width=0.3, height=1.5, mass=2.0)
    alpha = math.atan(0.2)
    below = free_rocking(rk.System(statue=statue), 1 - 1e-7, 0.3 * alpha)
    above = free_rocking(rk.System(statue=statue), 1 + 1e-7, 0.3 * alpha)
    for r, settled in ((below, True), (above, False)):
        assert r.status == "still_moving" and 0.3 * alpha < r.theta[-1] < 0.5 * alpha
        assert r.t[-1] == pytest.approx(0.06, abs=1e-12)
        assert r.settled_by_energy is settled and r.summary()["settled_by_energy"] is settled
        assert r.raw_summary[C.S_SETTLED] == float(settled)
    assert below.verdict == ("did not overturn; still moving at t = 0.060 s, with less energy than the statue "
                             "needs to overturn, on a floor that has stopped")
    assert not any("still moving" in w for w in below.warnings)
    assert above.verdict == "undetermined: still moving at t = 0.060 s"
    past = free_rocking(rk.System(statue=statue), 0.0, 1.001 * alpha)
    assert past.status == "still_moving" and past.theta[-1] > alpha and not past.settled_by_energy
    moving_floor = free_rocking(rk.System(statue=statue), 0.5, 0.3 * alpha, duration=0.06,
                                 motion=rk.RectanglePulse(amplitude=0.0, width=1.0))
    assert moving_floor.status == "still_moving" and not moving_floor.settled_by_energy
    stopped_floor = free_rocking(rk.System(statue=statue), 0.5, 0.3 * alpha, duration=0.06)
    assert stopped_floor.status == "still_moving" and stopped_floor.settled_by_energy
    # a record whose floor stops after 0.01 s, and the same samples cut from a longer record by
    # ``trimmed``: a window, whose floor goes on in the real record
    from rocking.excitation.record import GroundMotion

    window = GroundMotion(time=np.linspace(0.0, 1.0, 101), values=np.zeros(101), name="still").trimmed(0.01)
    whole = GroundMotion(time=window.time, values=window.values, name="still")
    for motion, settled in ((whole, True), (window, False)):
        r = free_rocking(rk.System(statue=statue), 0.5, 0.3 * alpha, motion=motion)
        assert r.status == "still_moving" and r.settled_by_energy is settled
    sliding = rk.System(statue=statue, pedestal=rk.Pedestal(mass=5.0, friction=rk.Friction(static=0.3, kinetic=0.2)))
    held = rk.System(statue=statue)  # on the floor, which it never slides on (no friction given)
    for system, impact, settled in ((sliding, "coulomb", True), (sliding, "paper", False), (held, "paper", True)):
        r = free_rocking(system, 0.5, 0.3 * alpha, options=rk.Options(gravity=9.5, free_time_limit=0.05,
                                                                      impact=impact))
        assert r.status == "still_moving" and r.settled_by_energy is settled, (impact, system.floor_friction)


def _falling_floor(ah, t_drop=1.0, ramp=0.01, depth=1.5, end=2.0):
    """A record: a_h = ah throughout, and a_v ramped from 0 at t_drop down to −depth·g over ramp s,
    then held: the floor falls faster than gravity from t_drop + ramp/depth on."""
    from rocking.excitation.record import GroundMotion

    t = np.array([0.0, 0.5, t_drop, t_drop + ramp, end])
    return GroundMotion(time=t, values=np.array([0.0, ah, ah, ah, ah]), name="falling floor",
                        vertical=np.array([0.0, 0.0, 0.0, -depth * G, -depth * G]))


@pytest.mark.parametrize("ah", [0.0, 0.02 * G])
def test_a_block_that_would_jump_while_it_stands_is_never_shown_safe(ah):
    """A squat block on a floor that falls faster than gravity: N = M (g + a_v) reaches zero at
    t₀ = t_drop + ramp/depth exactly (at rest, to the record's bit), the block would jump, and
    the two-body model, which keeps it on the floor, has no result after that. Until 2026-12-03
    such a run went on to say "did not overturn; at rest" (35 of 3000 random runs with a vertical
    floor motion), or "overturned" when the model's statue then toppled under the reversed weight
    (the floor still falling, no horizontal motion at all: ah = 0 here). Now its status is
    ``lifted_off`` and its verdict undetermined, at t₀ to 1e-9 s (the solver's event accuracy),
    and the fragility study counts it as a fall."""
    from rocking.analyses.fragility import ida
    from rocking.results.response import lift_off_time

    statue = block(1.0, 0.5, mass=80.0, friction=rk.Friction(static=0.6, kinetic=0.5))
    r = rk.simulate(alone(statue), _falling_floor(ah), options=OPTS)
    t0 = 1.0 + 0.01 / 1.5
    assert r.status == "lifted_off" and not r.summary()["overturned"]
    assert lift_off_time(r.raw_summary) == pytest.approx(t0, abs=1e-9)
    assert r.verdict == (f"undetermined: a body would leave its support at t = {t0:.3f} s, which the two-body model "
                         "does not follow")
    assert any("stack of blocks" in w for w in r.warnings)
    from rocking.report import content  # the report says it too, and does not colour it safe

    assert content.verdict(r).startswith("Undetermined: a body would leave its support at t = ")
    assert content.verdict_class(r) == "stopped"
    if ah:
        runs = ida({"block": alone(statue)}, {"falling": _falling_floor(ah)}, [ah, 2 * ah], options=OPTS, workers=1)
        assert runs.fall.all() and not runs.overturned.any() and int(runs.undetermined.sum()) == 2


def test_a_lift_off_counts_only_while_the_statue_stands():
    """``lift_off_time`` reads the first of the two lift-off instants (the floor's normal force,
    the statue's base force) and drops it at or after the first |θ| > α (a falling statue's
    lift-off is part of its fall); ``status_of`` overrides only a run that went on (completed,
    still moving, out of events, or overturned after it), never a solver failure or an interrupt."""
    from rocking.results.response import lift_off_time, status_of
    from rocking.solver import compiled as C

    def raw(status, n=math.nan, py=math.nan, exceed=math.nan):
        out = np.full(C.N_SUMMARY, math.nan)
        out[C.S_STATUS], out[C.S_N_NONPOSITIVE], out[C.S_PY_NONPOSITIVE], out[C.S_EXCEED_TIME] = status, n, py, exceed
        return out

    assert lift_off_time(raw(C.STATUS_COMPLETED)) is None
    assert lift_off_time(raw(C.STATUS_COMPLETED, n=0.8, py=0.7)) == 0.7
    assert lift_off_time(raw(C.STATUS_COMPLETED, n=0.8, exceed=0.9)) == 0.8
    assert lift_off_time(raw(C.STATUS_COMPLETED, n=0.9, exceed=0.9)) is None
    assert lift_off_time(raw(C.STATUS_COMPLETED, py=1.2, exceed=1.0)) is None
    for code, own, lifted in ((C.STATUS_COMPLETED, "completed", True), (C.STATUS_STILL_MOVING, "still_moving", True),
                              (C.STATUS_MAX_EVENTS, "max_events", True), (C.STATUS_OVERTURNED, "overturned", True),
                              (C.STATUS_SINGULAR, "singular", False), (C.STATUS_STEP_FAILED, "step_failed", False),
                              (C.STATUS_INTERRUPTED, "interrupted", False)):
        assert status_of(raw(code, n=0.5))[0] == ("lifted_off" if lifted else own)
        assert status_of(raw(code, n=0.5, exceed=0.4))[0] == own  # lifted after α: the solver's own


def test_a_pedestal_of_unknown_height_is_never_judged_for_uplift_even_as_it_jumps():
    """The uplift check needs the pedestal's width and height (x_N = moment/N, the moment from
    the height): with the width alone it is off, also where N ≤ 0 (the rule that counts a jump
    under a moment as an uplift has no moment to go by). Under the falling floor above, a
    statue on a 0.6 m pedestal of unknown height lifts off with no uplift warned; given a
    height of 0.4 m, the uplift is warned by the lift-off at the latest (to 1e-9 s: x_N runs off
    the base as N falls)."""
    from rocking.results.response import lift_off_time

    statue = block(0.3, 0.6, mass=50.0, friction=rk.Friction(static=0.8, kinetic=0.8))
    for height in (None, 0.4):
        pedestal = rk.Pedestal(mass=100.0, width=0.6, height=height, friction=rk.Friction(static=0.7, kinetic=0.7))
        r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), _falling_floor(0.02 * G), options=OPTS)
        uplift, lift = r.summary()["pedestal_uplift_time"], lift_off_time(r.raw_summary)
        assert r.status == "lifted_off" and lift is not None
        if height is None:
            assert uplift is None and not any("uplift" in w for w in r.warnings)
        else:
            assert uplift is not None and uplift <= lift + 1e-9


def test_the_saved_series_ends_with_the_state_the_verdict_judges():
    """A run cut while the statue still moves ends between two saved grid points; its last row is
    the state at ``end_time``, the one the verdict (and the energy rule) judged, not the grid
    point before it. The same run saved on a grid that lands on its end holds the same state
    there, to its rounding (the steps are the same; that grid point is read off the last step's
    interpolant, 1 ulp from the step's end)."""
    statue = block(0.25, 1.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=4.0, frequency=1.2, cycles=3)
    opts = rk.Options(gravity=G, free_time_limit=0.123)
    r = rk.simulate(alone(statue), motion, options=opts)
    t_end = motion.duration + 0.123
    assert r.status == "still_moving" and r.end_time == pytest.approx(t_end, abs=1e-12)
    assert r.t[-1] == r.end_time and r.t[-2] < r.end_time - 1e-3  # the grid (0.01 s) misses the end
    on_grid = rk.simulate(alone(statue), motion, options=rk.Options(gravity=G, free_time_limit=0.123,
                                                                    save_dt=t_end / 100))
    assert on_grid.t[-1] == r.end_time
    np.testing.assert_allclose(on_grid.state[-1], r.state[-1], rtol=1e-14, atol=1e-16)
    assert abs(r.theta[-1] - r.theta[-2]) > 1e-6  # it moved since the last grid point
