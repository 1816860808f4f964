"""The compiled cores never index an array out of its bounds.

Numba does not check indices by default: a write past the end of an array (a scratch vector one
entry too short, a table filled past its capacity) corrupts whatever lies next in memory, and a
run may still look right. A mutant of `solver/compiled.py` did exactly that and survived the
whole suite (bench/MUTATION.md, a4335bac: the scratch vector `gmin` two entries short, written
and read past its end). Here the cores are compiled afresh with
``NUMBA_BOUNDSCHECK=1`` (into a cache of their own, so that no unchecked machine code is
reused) and run on cases that reach the ends of their tables: every event slot filled
(max_events), runs with and without saved samples, an overturn, a sliding pedestal under a
record with a vertical component, stacks of one to three blocks. An out-of-bounds index then
raises ``IndexError`` and the script fails.

Each case compiles the core it runs (40–90 s), in a subprocess. The cold start is also where
the compilation notices of `rocking.solver.warmup` show: they are checked there too.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
import time


# The first lines prove that the flag took effect: an unchecked read past the end returns garbage
# and raises nothing, and the test would then pass whatever the cores do.
_PROBE = """
import numpy as np
from numba import njit

@njit
def _past_the_end(a):
    return a[a.size]

try:
    _past_the_end(np.zeros(3))
except IndexError:
    pass
else:
    raise SystemExit("NUMBA_BOUNDSCHECK did not take effect")
"""

_SOLVER_CASES = """
import numpy as np
import rocking as rk
from rocking.excitation.record import GroundMotion

g = 9.81
slender = rk.Statue(width=0.4, height=2.0, mass=50.0, restitution=0.9)
alone = rk.System(statue=slender)
for motion, options, kwargs, verdict in (
    (rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4), rk.Options(), {}, "did not overturn"),
    (rk.Harmonic(amplitude=0.5 * g, frequency=0.8, cycles=4), rk.Options(), {}, "overturned"),
    # every event slot filled: the run stops at max_events, the tables at their capacity
    (rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4), rk.Options(max_events=5), {}, "max_events"),
    (rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4), rk.Options(max_events=5), {"save": False},
     "max_events"),
    (rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4), rk.Options(), {"save": False}, "did not overturn"),
    (rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4), rk.Options(save_dt=1.0), {}, "did not overturn"),
    # still rocking at the run's end, past the motion's last breakpoint (2 s): the loop ends on
    # t_end there, with no piece of the motion left to move to
    (rk.Harmonic(amplitude=0.3 * g, frequency=2.0, cycles=4), rk.Options(), {"duration": 2.5}, "still_moving"),
):
    r = rk.simulate(alone, motion, options=options, throw=False, **kwargs)
    assert verdict in r.verdict + r.status, (verdict, r.verdict)
    print(r.verdict)

# a statue on a pedestal that slides, under a record-like motion with a vertical component
t = np.round(np.arange(0.0, 6.0, 0.01), 10)
motion = GroundMotion(time=t, values=4.0 * np.sin(2 * np.pi * 1.2 * t) * (t < 4.0),
                      vertical=2.0 * np.sin(2 * np.pi * 3.0 * t) * (t < 4.0))
pedestal = rk.Pedestal(mass=40.0, friction=rk.Friction(static=0.3, kinetic=0.25), width=0.6, height=0.5)
for statue in (slender, rk.Statue(width=0.8, height=1.0, mass=30.0)):
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, throw=False)
    assert r.status in ("completed", "overturned"), r.status
    print(r.verdict)
# a block that slides and rocks at once
r = rk.simulate(rk.System(statue=rk.Statue(width=0.6, height=1.2, mass=20.0,
                                           friction=rk.Friction(static=0.55, kinetic=0.5))),
                rk.Harmonic(amplitude=8.0, frequency=2.0, cycles=3), throw=False)
assert 3 in r.regime, np.unique(r.regime)
print(r.verdict)
# a block released tilted; at 0.3 s the floor jumps to -4 m/s², more than its friction carries:
# rocking turns into slide-rock at that breakpoint, whose event row is written in full
slippy = rk.Statue(width=0.4, height=2.0, mass=1.0, friction=rk.Friction(static=0.12, kinetic=0.1))
r = rk.simulate(rk.System(statue=slippy), GroundMotion(time=np.array([0.3, 0.5, 0.7]), values=np.array([-4.0, -4.0, 0.0])),
                duration=1.0, initial_rotation=0.1, throw=False)
assert r.events[0].kind == rk.EventKind.BREAKPOINT and r.event_table[0, 9] == 0.0, r.event_table[:2]
print(r.verdict)
"""

_STACK_CASES = """
import rocking as rk
from rocking.solver.warmup import ensure_stack_compiled
from rocking.stack import Block, Interface, Stack, simulate_stack

ensure_stack_compiled()  # as the command line does before a stack run: the notice, then the work

g = 9.81
pedestal = Block(name="pedestal", width=0.8, height=0.5, mass=300.0)
statue = Block(name="statue", width=0.3, height=1.2, mass=100.0)
vase = Block(name="vase", width=0.15, height=0.4, mass=10.0)
slides = Interface(friction=rk.Friction(static=0.3, kinetic=0.25))
grips = Interface(friction=rk.Friction(static=0.6, kinetic=0.5))
for stack, motion, options in (
    (Stack(blocks=[statue], interfaces=[grips]), rk.Harmonic(amplitude=0.3 * g, frequency=1.5, cycles=3), rk.Options()),
    (Stack(blocks=[pedestal, statue], interfaces=[slides, grips]),
     rk.Harmonic(amplitude=0.35 * g, frequency=1.5, cycles=3), rk.Options()),
    (Stack(blocks=[pedestal, statue, vase], interfaces=[slides, grips, grips]),
     rk.Harmonic(amplitude=0.4 * g, frequency=2.0, cycles=3), rk.Options()),
    (Stack(blocks=[pedestal, statue, vase], interfaces=[slides, grips, grips]),
     rk.Harmonic(amplitude=0.4 * g, frequency=2.0, cycles=3), rk.Options(max_events=4)),
):
    r = simulate_stack(stack, motion, options=options)
    print(r.status, r.verdict)
"""


def _run_with_bounds_checked(script: str, tmp_path, what: str) -> str:
    """Run ``script`` on a cold cache of its own; return its stdout. The cold start is also where
    the compilation notice shows (`rocking.solver.warmup`): said once before and once after,
    with a time no longer than the whole process took. A second process on the now warm cache
    must compile nothing and say nothing."""
    env = dict(os.environ, NUMBA_BOUNDSCHECK="1", NUMBA_CACHE_DIR=str(tmp_path / "numba-cache"))
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", textwrap.dedent(_PROBE + script)], env=env,
                          capture_output=True, text=True, timeout=1200)
    wall = time.perf_counter() - start
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-4000:]
    assert proc.stderr.count(f"rocking: compiling the {what} (first run on this machine") == 1, proc.stderr
    said = re.findall(rf"rocking: {what} compiled in (\d+) s", proc.stderr)
    assert len(said) == 1 and int(said[0]) <= wall + 0.5, (said, wall)
    ensure = "ensure_compiled" if what == "solver" else "ensure_stack_compiled"
    warm = subprocess.run([sys.executable, "-c", f"from rocking.solver.warmup import {ensure}; assert {ensure}() is None"],
                          env=env, capture_output=True, text=True, timeout=300)
    assert warm.returncode == 0 and "compil" not in warm.stderr, warm.stderr
    return proc.stdout


def test_the_solver_core_stays_inside_its_arrays(tmp_path):
    out = _run_with_bounds_checked(_SOLVER_CASES, tmp_path, "solver")
    assert out.count("\n") == 11


def test_the_stack_engine_stays_inside_its_arrays(tmp_path):
    out = _run_with_bounds_checked(_STACK_CASES, tmp_path, "stack engine")
    assert out.count("\n") == 4
    assert "max_events" in out.splitlines()[-1]


def test_the_warm_up_command_compiles_both_cores_and_exits_0(monkeypatch):
    """`scripts/env.sh` runs `raise SystemExit(main())` under `set -e`: main must ask for both cores
    and return 0."""
    from rocking.solver import warmup

    asked = []
    monkeypatch.setattr(warmup, "ensure_compiled", lambda **_: asked.append("solver"))
    monkeypatch.setattr(warmup, "ensure_stack_compiled", lambda **_: asked.append("stack"))
    assert warmup.main() == 0
    assert asked == ["solver", "stack"]
