"""The outside peers of the stack engine (bench/stack_peers.py): how a Stack becomes a MuJoCo
model, how the floor is driven, how the peers' angles become verdicts, and why LMGC90 is not run
on a case. MuJoCo runs are skipped where it is not installed; the LMGC90 run where its separate
venv is missing."""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import rocking as rk
from rocking.excitation.record import GroundMotion
from rocking.stack import Block, Interface, Stack

BENCH = Path(__file__).resolve().parents[1] / "bench"


@pytest.fixture(scope="module")
def peers():
    saved = list(sys.path)
    try:
        spec = importlib.util.spec_from_file_location("bench_stack_peers", BENCH / "stack_peers.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # its dataclasses look their module up there
        spec.loader.exec_module(module)
    finally:
        sys.path[:] = saved
    return module


def _mujoco():
    return pytest.importorskip("mujoco")


def test_floor_kinematics_integrates_a_sine_exactly(peers):
    motion = rk.Harmonic(amplitude=2.0, frequency=1.5, cycles=2, form="sin")
    floor = peers.floor_kinematics(motion, 1.0, 1e-3)
    w = motion.omega
    t = floor["t"]
    assert floor["n"] == 1000 and t[-1] == pytest.approx(1.0)
    np.testing.assert_allclose(floor["vx"], 2.0 / w * (1 - np.cos(w * t)), atol=1e-7)
    np.testing.assert_allclose(floor["x"], 2.0 / w * t - 2.0 / w**2 * np.sin(w * t), atol=1e-7)
    np.testing.assert_allclose(floor["ax_mid"], 2.0 * np.sin(w * (np.arange(1000) + 0.5) * 1e-3))
    assert floor["vz"] is None and floor["az_mid"] is None


def test_summarize_reads_relative_rotations_and_stops_a_peak_at_the_fall(peers):
    t = np.arange(1, 6) * 1.0
    # block 1 tilts 0.1 rad; block 2 rides on it, then falls and tumbles on
    theta = np.array([[0.1, 0.1], [0.1, 0.3], [0.1, 1.7], [0.1, 3.1], [0.1, 3.5]])
    overturn, peak = peers.summarize(theta, t, until=math.inf)
    assert overturn == (None, 3.0)
    assert peak[0] == pytest.approx(0.1)
    assert peak[1] == pytest.approx(1.6)  # up to the fall, not the tumble after it
    _, peak_early = peers.summarize(theta[:, :1] * [[1], [1], [1], [4], [1]], t, until=3.0)
    assert peak_early[0] == pytest.approx(0.1)  # the 0.4 rad at t = 4 s is after `until`


def test_verdict_delta_separates_agreement_disagreement_and_falls_after_the_reference_run(peers):
    assert peers.verdict_delta(1.25, 1.0, math.inf) == "+0.250"
    assert peers.verdict_delta(None, None, 3.0) == "same"
    assert peers.verdict_delta(None, 1.0, 1.0) == "DIFF"
    assert peers.verdict_delta(2.0, None, 3.0) == "DIFF"
    assert peers.verdict_delta(4.0, None, 3.0) == "after"


def test_lmgc90_is_refused_exactly_what_it_cannot_model(peers):
    cases = {c.key: c for c in peers.peer_cases()}
    b2 = peers.lmgc90_obstacle(cases["b2"].stack)
    assert "frictions per interface (0.4/0.3, never slips)" in b2 and "restitution" in b2
    r3 = peers.lmgc90_obstacle(cases["r3"].stack)
    assert "0.4/0.3, 0.6/0.5, 0.5/0.4" in r3 and "restitution" not in r3
    assert peers.lmgc90_obstacle(cases["h-fall"].stack) is None
    assert peers.lmgc90_obstacle(cases["h-safe"].stack) is None
    odd = Stack(blocks=(Block(width=0.3, height=1.2, mass=10.0, inertia=2.0),),
                interfaces=(Interface(friction=rk.Friction(static=0.5)),))
    assert "inertia" in peers.lmgc90_obstacle(odd)


def test_mujoco_model_carries_the_stack(peers):
    mujoco = _mujoco()
    mu = rk.Friction(static=0.6, kinetic=0.5)
    stack = Stack(blocks=(Block(name="plinth", width=1.0, height=0.5, mass=200.0),
                          Block(name="statue", width=0.3, height=1.2, mass=50.0, offset=0.1, inertia=9.0)),
                  interfaces=(Interface(friction=mu), Interface()))
    model = mujoco.MjModel.from_xml_string(peers.mujoco_model(stack, 1e-3, vertical=False))
    b0, b1 = model.body("b0").id, model.body("b1").id
    assert model.body_mass[b0] == 200.0 and model.body_mass[b1] == 50.0
    assert model.body_inertia[b1][1] == 9.0
    assert model.body_inertia[b0][1] == pytest.approx(200.0 * (1.0 + 0.25) / 12)
    np.testing.assert_allclose(model.body_pos[b1], [0.1, 0.0, 0.5 + 0.6])
    np.testing.assert_allclose(model.geom_size[model.geom("g1").id], [0.15, 0.1, 0.6])
    assert model.body_mass[model.body("floor").id] == pytest.approx(peers.PLATFORM_MASS_RATIO * 250.0)
    frictions = sorted(float(model.pair_friction[i][0]) for i in range(model.npair))
    assert frictions == [0.6, peers.NEVER_SLIP_MU]  # μs of the floor interface; the never-slip one
    assert model.nexclude == 2  # no second, default contact on the neighbours


def test_mujoco_statue_falls_when_rocking_says_so(peers):
    _mujoco()
    case = {c.key: c for c in peers.peer_cases()}["h-fall"]
    out = peers.run_mujoco(case, 1e-3, repeats=1, peak_until=math.inf)
    assert out.overturn[0] is None
    assert out.overturn[1] == pytest.approx(1.051, abs=0.02)  # rocking: 1.051 s
    assert out.peak[0] < 0.01


def test_mujoco_platform_follows_a_vertical_motion(peers):
    mujoco = _mujoco()
    t = np.linspace(0.0, 2.0, 401)
    quake = GroundMotion(time=t, values=np.zeros_like(t), vertical=3.0 * np.sin(2 * np.pi * 2.0 * t))
    stack = Stack(blocks=(Block(width=0.5, height=1.0, mass=100.0),), interfaces=(Interface(),))
    case = peers.PeerCase("v", "vertical only", stack, quake, 2.0)
    out = peers.run_mujoco(case, 1e-3, repeats=1, peak_until=math.inf)
    assert out.overturn == (None,) and out.peak[0] < 1e-3
    model = mujoco.MjModel.from_xml_string(peers.mujoco_model(stack, 1e-3, vertical=True))
    assert model.nu == 2
    # the platform's z follows ∫∫a_v (amplitude 3/(2π·2)² ≈ 19 mm) up to the Euler step's lag, |v_z|·dt
    lag = 3.0 / (2 * np.pi * 2.0) * 2 * 1e-3
    assert "|z_p − z_g|" in out.note
    assert 0.1 * lag < out.floor_error < 1.2 * lag


@pytest.mark.skipif(not Path("/tmp/lmgc-venv/bin/python").exists(), reason="no LMGC90 venv")
def test_lmgc90_statue_falls_when_rocking_says_so(peers):
    case = {c.key: c for c in peers.peer_cases()}["h-fall"]
    out = peers.run_lmgc90(case, 1e-3, 1, "/tmp/lmgc-venv/bin/python", math.inf)
    assert not isinstance(out, str), out
    assert out.overturn[0] is None
    assert out.overturn[1] == pytest.approx(1.051, abs=0.02)


def test_rocking_on_mujocos_model_keeps_mu_s_and_drops_the_restitution(peers):
    cases = {c.key: c for c in peers.peer_cases()}
    simple = peers.as_mujoco_sees_it(cases["b2"]).stack
    floor, top = simple.interfaces
    assert (floor.friction.mu_s, floor.friction.mu_k) == (0.4, 0.4)
    assert top.friction is None and top.restitution is None and floor.restitution is None
    assert simple.blocks == cases["b2"].stack.blocks
    assert peers.as_mujoco_sees_it(cases["h-fall"]).stack == cases["h-fall"].stack  # nothing to simplify
