"""Optional benchmark extra: the stack engine against MuJoCo and LMGC90 on the same stacks (issue 11 §7).

    .venv/bin/python bench/stack_peers.py            # MuJoCo at dt = 1e-3 and 1e-4, LMGC90 at 1e-3 and 2.5e-4
    .venv/bin/python bench/stack_peers.py --quick    # one step size per peer, 1 repeat (< 2 min)

Neither peer is a dependency of ``rocking``. MuJoCo goes into ``.venv`` (``.venv/bin/pip install
mujoco``). compas-lmgc90 pulls PySide6, so it lives in a venv of its own, which this script drives
through a subprocess (``--lmgc-python``, default ``/tmp/lmgc-venv/bin/python``)::

    python3 -m venv /tmp/lmgc-venv && /tmp/lmgc-venv/bin/pip install compas-lmgc90 numpy

A peer that is missing, or that cannot model a case, prints "not run: <reason>".

Cases (every engine runs the same window, s):

* ``b2``, ``r3``: ``bench/stack.py``'s statue on a pedestal (paper case b, 30 cycles of
  6.75 cos(2π·1.2 t) m/s², floor μs/μk = 0.4/0.3, a statue that never slips with r = 0.8) and its
  plinth + statue + vase under 30 s of the Loma Prieta Corralitos record (μ = 0.4/0.3, 0.6/0.5,
  0.5/0.4);
* ``h-fall``, ``h-safe``: a 0.3 × 1.5 m, 100 kg statue on a 1.0 × 0.4 m, 300 kg pedestal, μ = 0.7
  (static = kinetic) on both interfaces, no restitution coefficient (plastic impacts, which give
  Housner's value), under 2 cycles of 6 sin(2π·0.8 t) m/s² (the statue falls at about 1 s) and
  3 cycles of 2.5 sin(2π·2 t) m/s² (the statue rocks to a third of its slenderness angle and
  settles). These two are built so that every peer can model them exactly.

Models:

* ``rocking``: ``simulate_stack`` (event-driven, rigid, exact contact modes), default tolerances,
  ``save_dt`` = 0.01 s; its per-block summary gives the overturn time (|φ| = π/2) and the peak |φ|.
* MuJoCo (``mujoco_model``): each block a box (depth 0.2 m) on slide x, slide z and a hinge about y
  at its centre, with the block's mass and centroidal inertia; the floor a box on a slide-x joint
  (and slide z if the motion has a vertical component) of mass 1e5 × the stack's, pushed open-loop
  by a motor force M_p·a(t) at mid-step as in ``bench/mujoco_peer.py`` (its vertical force also
  carries the stack's weight); it settles 0.5 s before t = 0. Each interface is an explicit contact
  pair with that interface's friction; MuJoCo has one coefficient, so the pair gets μs (the one
  that decides whether a slip starts); a never-slip interface gets μ = 5 (the largest
  |tangential|/normal ratio that ``rocking`` needs at those interfaces is printed: well below).
  Contacts between blocks that are not neighbours keep MuJoCo's default (μ = 1). Stiff contacts
  ``solref = "2·dt 1"``, default ``solimp``, Euler, pyramidal cone, Newton solver. No restitution
  coefficient can be set: the rebound comes from the contact softness and the step.
* LMGC90 (compas-lmgc90 0.1.11, ``_lmgc90_worker``): non-smooth contact dynamics (Moreau–Jean
  θ-method, θ = 0.5, NLGS), the blocks as thin 3-D polyhedra (depth 0.2 m, density = m/(B·H·D):
  its inertia is the uniform block's, so a block with a given ``inertia`` is not run), on a floor
  block whose six velocities are imposed (ẋ_g(t) as a table at every step, the rest 0; ż_g(t)
  too with a vertical motion). What it cannot do: (1) in its installed ``solver.py``,
  ``Solver.contact_law`` registers its law under one fixed name ("iqsc0") and ``set_see_tables``
  takes only the alert distance, no pair of bodies; the Fortran wrapper in its repository makes
  the one see table POLYR–POLYR → "iqsc0". So every contact has the same friction; (2) the laws it offers (IQS_CLB: inelastic Coulomb) have one μ, no μs/μk pair;
  (3) a restitution law (RST_CLB) would also apply to every contact; (4) gravity is its fixed
  9.81 m/s² (``rocking`` uses 9.80665); (5) one simulation per process, so each repeat builds a
  new solver. Cases with different frictions per interface, μk ≠ μs, a never-slip interface or
  a restitution coefficient (``b2``, ``r3``) are therefore not run: LMGC90 would be solving a
  different problem.

Printed per case and engine: wall time per run (median of the repeats; MuJoCo ``rollout`` after
the model is compiled and settled; LMGC90 the stepping loop after ``preprocess``; ``rocking`` after
a warm-up run, so no JIT), the number of steps (``rocking``: of events), and per block: the verdict (the time |φ| first
reaches π/2 − 0.01 rad for the peers, π/2 for ``rocking``, or "no"), the peak |φ| (φ: rotation
relative to the block below) and, in brackets, the difference from ``rocking``'s overturn time and
peak. A ``rocking`` run stops when the first block falls: the peers' peaks are then taken up to
that instant, and a peer's fall after it is marked "after" (not compared). Where MuJoCo simplifies
the case (μk = μs, no restitution coefficient), ``rocking`` also runs on the simplified case (row
"rocking 1μ, r_H"), which separates what the model changes from what the engine does. The notes
under each case count the blocks whose verdict differs.

Measured (2026-11-24, ``bench/stack_peers.py`` without options, on the 2-core development machine
under load from other processes: load average 5.9, so the times move by tens of per cent between
runs; ``--quick`` took 7 s)::

    rocking 0.1.0 | MuJoCo 4.0.0 | Python 3.11.7 | numpy 2.4.6
    2 CPUs | load average 5.92, 4.42, 3.17 (other processes skew timings)

    [b2] statue on pedestal (paper case b), 30 cycles; window 25 s
    engine                dt    ms/run   steps  pedestal: overturn, peak|φ| rad (Δt, Δpeak)  statue: overturn, peak|φ| rad (Δt, Δpeak)
    -----------------------------------------------------------------------------------------------------------------------------------
    rocking            event      43.2     180        no 0.0000                           no 0.1024
    rocking 1μ, r_H    event      17.6      72        no 0.0000 (  same, +0.0000)  12.409 s 1.5708 (  DIFF, +1.4684)
    MuJoCo             0.001     271.6   25000        no 0.0006 (  same, +0.0006)   6.098 s 1.5620 (  DIFF, +1.4596)
    MuJoCo            0.0001    2342.1  250000        no 0.0006 (  same, +0.0006)   6.912 s 1.5609 (  DIFF, +1.4586)
    LMGC90           not run: frictions per interface (0.4/0.3, never slips) but compas-lmgc90 registers one contact law for every contact; μk ≠ μs but its IQS_CLB law has one μ; a restitution coefficient but its one law applies to every contact
      rocking dt=–: undetermined: still moving at t = 25.000 s; status still_moving
      rocking 1μ, r_H dt=–: statue overturned at t = 12.409 s; status overturned; verdicts differing from rocking: 1
      MuJoCo dt=0.001: platform |x_p − x_g| ≤ 0.46 mm; verdicts differing from rocking: 1, from rocking 1μ, r_H: 0
      MuJoCo dt=0.0001: platform |x_p − x_g| ≤ 0.061 mm; verdicts differing from rocking: 1, from rocking 1μ, r_H: 0
      rocking 1μ, r_H: rocking with MuJoCo's simplifications (μk = μs, no restitution coefficient)
      never-slip interfaces (MuJoCo μ = 5): rocking needs |T|/N up to pedestal–statue 0.30

    [r3] plinth + statue + vase, LomaPrieta1989_Corralitos_000 30 s; window 30 s
    engine                dt    ms/run   steps  plinth: overturn, peak|φ| rad (Δt, Δpeak)   statue: overturn, peak|φ| rad (Δt, Δpeak)    vase: overturn, peak|φ| rad (Δt, Δpeak)
    ------------------------------------------------------------------------------------------------------------------------------------------------------------------------------
    rocking            event      24.1      11        no 0.0000                           no 0.0602                      3.265 s 1.5708
    rocking 1μ, r_H    event      26.3      13        no 0.0000 (  same, +0.0000)        no 0.0779 (  same, +0.0177)   3.249 s 1.5708 (-0.016, +0.0000)
    MuJoCo             0.001     639.8   30000        no 0.0000 (  same, +0.0000)        no 0.0777 (  same, +0.0175)   3.249 s 1.5651 (-0.016, -0.0057)
    MuJoCo            0.0001    8419.6  300000        no 0.0000 (  same, +0.0000)        no 0.0776 (  same, +0.0174)   3.249 s 1.5608 (-0.015, -0.0100)
    LMGC90           not run: frictions per interface (0.4/0.3, 0.6/0.5, 0.5/0.4) but compas-lmgc90 registers one contact law for every contact; μk ≠ μs but its IQS_CLB law has one μ
      rocking dt=–: vase overturned at t = 3.265 s; status overturned
      rocking 1μ, r_H dt=–: vase overturned at t = 3.249 s; status overturned; verdicts differing from rocking: 0
      MuJoCo dt=0.001: platform |x_p − x_g| ≤ 0.28 mm; verdicts differing from rocking: 0, from rocking 1μ, r_H: 0
      MuJoCo dt=0.0001: platform |x_p − x_g| ≤ 0.029 mm; verdicts differing from rocking: 0, from rocking 1μ, r_H: 0
      rocking 1μ, r_H: rocking with MuJoCo's simplifications (μk = μs, no restitution coefficient)
      rocking stops at the first fall (3.265 s): the peers' peaks are taken up to then, their later falls marked 'after'

    [h-fall] statue 0.3×1.5 m on pedestal 1.0×0.4 m, μ 0.7, 2 cycles 6 sin(2π·0.8t); window 4 s
    engine                dt    ms/run   steps  pedestal: overturn, peak|φ| rad (Δt, Δpeak)  statue: overturn, peak|φ| rad (Δt, Δpeak)
    -----------------------------------------------------------------------------------------------------------------------------------
    rocking            event       1.1       4        no 0.0000                      1.051 s 1.5708
    MuJoCo             0.001      49.1    4000        no 0.0000 (  same, +0.0000)   1.049 s 1.5634 (-0.002, -0.0074)
    MuJoCo            0.0001     628.0   40000        no 0.0000 (  same, +0.0000)   1.049 s 1.5611 (-0.003, -0.0097)
    LMGC90 0.1.11      0.001     634.7    4000        no 0.0000 (  same, +0.0000)   1.053 s 1.5615 (+0.002, -0.0093)
    LMGC90 0.1.11    0.00025    2284.1   16000        no 0.0000 (  same, +0.0000)   1.053 s 1.5609 (+0.001, -0.0099)
      rocking dt=–: statue overturned at t = 1.051 s; status overturned
      MuJoCo dt=0.001: platform |x_p − x_g| ≤ 1.2 mm; verdicts differing from rocking: 0
      MuJoCo dt=0.0001: platform |x_p − x_g| ≤ 0.11 mm; verdicts differing from rocking: 0
      LMGC90 0.1.11 dt=0.001: floor |x − x_g| ≤ 0.00049 mm; verdicts differing from rocking: 0
      LMGC90 0.1.11 dt=0.00025: floor |x − x_g| ≤ 3.1e-05 mm; verdicts differing from rocking: 0
      rocking stops at the first fall (1.051 s): the peers' peaks are taken up to then, their later falls marked 'after'

    [h-safe] same stack, 3 cycles 2.5 sin(2π·2t); window 6 s
    engine                dt    ms/run   steps  pedestal: overturn, peak|φ| rad (Δt, Δpeak)  statue: overturn, peak|φ| rad (Δt, Δpeak)
    -----------------------------------------------------------------------------------------------------------------------------------
    rocking            event      41.7     215        no 0.0000                           no 0.0636
    MuJoCo             0.001      78.9    6000        no 0.0000 (  same, +0.0000)        no 0.0635 (  same, -0.0000)
    MuJoCo            0.0001     822.9   60000        no 0.0000 (  same, +0.0000)        no 0.0635 (  same, -0.0001)
    LMGC90 0.1.11      0.001     897.7    6000        no 0.0000 (  same, +0.0000)        no 0.0633 (  same, -0.0002)
    LMGC90 0.1.11    0.00025    2801.4   24000        no 0.0000 (  same, +0.0000)        no 0.0636 (  same, +0.0000)
      rocking dt=–: did not overturn; at rest at t = 6.000 s; status completed
      MuJoCo dt=0.001: platform |x_p − x_g| ≤ 0.2 mm; verdicts differing from rocking: 0
      MuJoCo dt=0.0001: platform |x_p − x_g| ≤ 0.019 mm; verdicts differing from rocking: 0
      LMGC90 0.1.11 dt=0.001: floor |x − x_g| ≤ 0.00021 mm; verdicts differing from rocking: 0
      LMGC90 0.1.11 dt=0.00025: floor |x − x_g| ≤ 1.3e-05 mm; verdicts differing from rocking: 0

What the differences come from (measured, nothing else):

* ``h-fall``, ``h-safe`` (every engine models the case exactly, plastic impacts everywhere): the
  three agree on every verdict; the statue falls within 3 ms of ``rocking``'s 1.051 s and rocks to
  within 2e-4 rad of its 0.0636 rad. A fallen block's peak is about 0.01 rad below π/2 because
  the peers' fall is read at |φ| ≥ π/2 − 0.01.
* ``r3``: MuJoCo's statue rocks 0.0175 rad more and the vase falls 16 ms earlier. ``rocking`` on
  MuJoCo's simplified case gives the same (0.0779 rad, 3.249 s): the difference is μk = μs (one
  MuJoCo coefficient), not the soft contacts or the step.
* ``b2``: MuJoCo's statue falls (6.10 s at dt = 1e-3, 6.91 s at 1e-4); ``rocking`` (floor
  μs/μk = 0.4/0.3, statue r = 0.8) keeps it standing for 25 s. ``rocking`` on MuJoCo's case
  (μ = 0.4, Housner's r) lets it fall too, at 12.41 s. Each simplification alone does not (peak
  0.140 rad with μk = μs and r = 0.8; 0.120 rad with μk = 0.3 and Housner's r, from two extra
  ``rocking`` runs not printed here). The fall time after a dozen impacts moves by 0.8 s between
  MuJoCo's two steps, so 6–7 s against 12.4 s says how sensitive the time is, not which is right.
  MuJoCo's light (1 kg) pedestal also tilts by up to 6e-4 rad where ``rocking``'s stays flat,
  either its soft contacts giving or a lift; these runs do not separate the two.
* Floor: LMGC90's imposed velocity puts its floor within 5e-4 mm of x_g; MuJoCo's pushed platform
  lags by about half a step of the floor's travel (max|ẋ_g|·dt/2: 1.2 mm at dt = 1e-3 in
  ``h-fall``), which the step change 1e-3 → 1e-4 shows to be harmless here (verdicts unchanged,
  ``h-fall``/``r3`` fall times within 1 ms).
* Time: ``rocking`` takes 1–43 ms per run (its cost grows with the events: 215 impacts and mode
  changes in ``h-safe`` make it only ~2× faster than MuJoCo at dt = 1e-3); MuJoCo 10–26 µs per step
  (50–640 ms per run at dt = 1e-3, about 10× that at 1e-4); LMGC90 about 0.15 ms per step
  (0.6–0.9 s per run at dt = 1e-3), its Python loop reading the poses included.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

WORKER_FLAG = "--lmgc90-worker"
DEPTH = 0.2  # m, out of plane, both peers
OVERTURN = 0.5 * math.pi - 0.01  # rad, peers: a block lying on its side sits at π/2 ± its contact's penetration
NEVER_SLIP_MU = 5.0
NON_NEIGHBOUR_MU = 1.0
PLATFORM_MASS_RATIO = 1e5  # platform mass / stack mass (MuJoCo): the blocks' reaction moves it by 1e-5 of theirs
SETTLE = 0.5  # s, MuJoCo's soft contacts sink before t = 0
FLOOR_HALF_LENGTH = 20.0  # m, room to slide
LMGC_THETA = 0.5
LMGC_DEFAULT_PYTHON = "/tmp/lmgc-venv/bin/python"
MUJOCO_VIEW = "rocking 1μ, r_H"  # rocking on the case as MuJoCo models it


# --- LMGC90 worker: runs in the LMGC90 venv (numpy + compas_lmgc90, no rocking) ------------------

def _box(cx: float, cz: float, width: float, depth: float, height: float) -> dict:
    """A box centred at (cx, 0, cz) as LMGC90's vertex/face dict (faces wound outwards)."""
    vertices = [[cx + sx * width / 2, sy * depth / 2, cz + sz * height / 2]
                for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)]
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return {"vertices": vertices, "faces": faces}


def _lmgc90_run_once(spec: dict) -> tuple[float, np.ndarray, np.ndarray]:
    """One simulation: (wall time of the stepping loop in s, θ of each block after each step (rad,
    > 0 leaning to +x), floor x after each step (m))."""
    from compas_lmgc90.solver import Solver

    blocks = spec["blocks"]
    solver = Solver(dt=spec["dt"], theta=LMGC_THETA)
    floor = _box(0.0, -0.05, 2 * FLOOR_HALF_LENGTH, 2.0, 0.1)
    meshes = [floor] + [_box(b["cx"], b["cz"], b["width"], DEPTH, b["height"]) for b in blocks]
    densities = [1000.0] + [b["mass"] / (b["width"] * b["height"] * DEPTH) for b in blocks]
    solver.geometry_from_v_f(meshes, density=densities)
    t = np.asarray(spec["t"])
    solver.apply_velocity(0, "Vx", np.vstack([t, np.asarray(spec["vx"])]))
    if spec["vz"] is not None:
        solver.apply_velocity(0, "Vz", np.vstack([t, np.asarray(spec["vz"])]))
    else:
        solver.apply_velocity(0, "Vz", 0.0)
    for component in ("Vy", "Rx", "Ry", "Rz"):
        solver.apply_velocity(0, component, 0.0)
    solver.contact_law("IQS_CLB", spec["mu"])
    solver.preprocess()
    n = spec["steps"]
    theta = np.empty((n, len(blocks)))
    floor_x = np.empty(n)
    step = solver.lmgc90.compute_one_step
    t0 = time.perf_counter()
    for i in range(n):
        state = step()
        floor_x[i] = state.bodies[0][0]
        for k in range(len(blocks)):
            frame = state.body_frames[k + 1]  # rows are the body's axes: row 3 is its own z axis
            theta[i, k] = math.atan2(frame[6], frame[8])
    elapsed = time.perf_counter() - t0
    solver.finalize()
    return elapsed, theta, floor_x


def _lmgc90_worker(spec_path: str, out_path: str) -> int:
    spec = json.loads(Path(spec_path).read_text())
    times = []
    for _ in range(spec["repeats"]):
        elapsed, theta, floor_x = _lmgc90_run_once(spec)
        times.append(elapsed)
    from importlib.metadata import version

    Path(out_path).write_text(json.dumps({
        "times": times, "theta": theta.tolist(), "floor_x": floor_x.tolist(),
        "version": version("compas-lmgc90"),
    }))
    return 0


if __name__ == "__main__" and len(sys.argv) == 4 and sys.argv[1] == WORKER_FLAG:
    # the worker's venv has no rocking: stop before importing it
    raise SystemExit(_lmgc90_worker(sys.argv[2], sys.argv[3]))

sys.path.insert(0, str(Path(__file__).resolve().parent))

import rocking as rk  # noqa: E402
import stack as stack_bench  # noqa: E402  (bench/stack.py)
from rocking.stack import Block, Interface, Stack, simulate_stack  # noqa: E402

try:
    import mujoco
    from mujoco import rollout as mj_rollout
except ImportError as exc:  # optional extra
    mujoco = None
    _MUJOCO_IMPORT_ERROR = exc

GRAVITY = rk.Options().gravity
ROCKING_OPTIONS = rk.Options(save_dt=0.01)


@dataclass(frozen=True)
class PeerCase:
    key: str
    label: str
    stack: Stack
    motion: object
    duration: float  # s


@dataclass(frozen=True)
class Outcome:
    """One engine on one case: wall time per run (s, median), steps per run, and per block the
    overturn time (s, None: did not) and peak |φ| (rad)."""

    engine: str
    dt: float | None
    seconds: float
    steps: int
    overturn: tuple[float | None, ...]
    peak: tuple[float, ...]
    note: str = ""
    end_time: float = math.inf  # s, where the run stopped (rocking: at the first fall)
    floor_error: float = 0.0  # m, largest |platform − prescribed floor| in x or z (peers)


def harmonic_statue(amplitude: float, frequency: float, cycles: float) -> tuple[Stack, rk.Harmonic]:
    mu = rk.Friction(static=0.7)
    stack = Stack(blocks=(Block(name="pedestal", width=1.0, height=0.4, mass=300.0),
                          Block(name="statue", width=0.3, height=1.5, mass=100.0)),
                  interfaces=(Interface(friction=mu), Interface(friction=mu)))
    return stack, rk.Harmonic(amplitude=amplitude, frequency=frequency, cycles=cycles, form="sin")


def peer_cases() -> list[PeerCase]:
    out = [PeerCase(key, label, stack, motion, float(duration))
           for key, label, stack, _system, motion, duration in stack_bench.cases() if key in ("b2", "r3")]
    fall, fall_motion = harmonic_statue(6.0, 0.8, 2)
    safe, safe_motion = harmonic_statue(2.5, 2.0, 3)
    out += [PeerCase("h-fall", "statue 0.3×1.5 m on pedestal 1.0×0.4 m, μ 0.7, 2 cycles 6 sin(2π·0.8t)",
                     fall, fall_motion, 4.0),
            PeerCase("h-safe", "same stack, 3 cycles 2.5 sin(2π·2t)", safe, safe_motion, 6.0)]
    return out


# --- the floor's motion on a peer's time grid -----------------------------------------------------

def floor_kinematics(motion, duration: float, dt: float, sub: int = 8) -> dict:
    """Velocities and displacements of the floor at t = k·dt (k = 0 … n) by the trapezoidal rule on
    dt/sub (exact for a record sampled at a multiple of dt/sub), and the accelerations at mid-step.
    m/s², m/s, m."""
    n = round(duration / dt)
    fine = np.linspace(0.0, n * dt, n * sub + 1)
    h = fine[1] - fine[0]

    def integrate(values):
        return np.concatenate([[0.0], np.cumsum(0.5 * h * (values[1:] + values[:-1]))])

    vx = integrate(motion.acceleration(fine))
    az = motion.vertical_acceleration(fine)
    vertical = bool(np.any(az != 0.0))
    vz = integrate(az) if vertical else None
    mid = (np.arange(n) + 0.5) * dt
    return {
        "n": n, "t": fine[::sub], "vx": vx[::sub], "x": integrate(vx)[::sub],
        "vz": None if vz is None else vz[::sub], "z": None if vz is None else integrate(vz)[::sub],
        "ax_mid": motion.acceleration(mid),
        "az_mid": motion.vertical_acceleration(mid) if vertical else None,
    }


def rest_centres(stack: Stack) -> list[tuple[float, float]]:
    """(x, z) of each block's centre at rest, m, floor surface at z = 0."""
    out, x, base = [], 0.0, 0.0
    for block in stack.blocks:
        x += block.offset
        out.append((x, base + 0.5 * block.height))
        base += block.height
    return out


def summarize(theta: np.ndarray, t: np.ndarray, until: float) -> tuple[tuple[float | None, ...], tuple[float, ...]]:
    """Per block: first time |φ| ≥ OVERTURN (s) and peak |φ| (rad) over t ≤ ``until`` (s), from
    absolute angles θ (n, N) at times t."""
    phi = np.diff(np.hstack([np.zeros((theta.shape[0], 1)), theta]), axis=1)
    overturn, peak = [], []
    for k in range(theta.shape[1]):
        over = np.flatnonzero(np.abs(phi[:, k]) >= OVERTURN)
        overturn.append(float(t[over[0]]) if over.size else None)
        # a fallen block tumbles on (off the pedestal, onto the floor): its peak is taken up to its fall
        last = over[0] + 1 if over.size else np.searchsorted(t, until, side="right")
        peak.append(float(np.max(np.abs(phi[:last, k]), initial=0.0)))
    return tuple(overturn), tuple(peak)


# --- rocking -------------------------------------------------------------------------------------

def as_mujoco_sees_it(case: PeerCase) -> PeerCase:
    """The case as the MuJoCo model has it: one friction coefficient (μk = μs) per interface and
    plastic impacts (no restitution coefficient, so Housner's value)."""
    interfaces = tuple(Interface(friction=None if iface.friction is None else rk.Friction(static=iface.friction.mu_s))
                       for iface in case.stack.interfaces)
    return dataclasses.replace(case, stack=Stack(blocks=case.stack.blocks, interfaces=interfaces))


def run_rocking(case: PeerCase, repeats: int, engine: str = "rocking"):
    def run():
        return simulate_stack(case.stack, case.motion, duration=case.duration, options=ROCKING_OPTIONS)

    response = run()  # JIT compilation or numba's disk cache
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        run()
        times.append(time.perf_counter() - t0)
    outcome = Outcome(engine, None, statistics.median(times), len(response.events),
                      tuple(b["overturn_time"] for b in response.blocks),
                      tuple(b["peak_rotation"] for b in response.blocks),
                      note=f"{response.verdict}; status {response.status}", end_time=response.end_time)
    return outcome, response


# --- MuJoCo --------------------------------------------------------------------------------------

def mujoco_friction(interface: Interface) -> float:
    return NEVER_SLIP_MU if interface.friction is None else interface.friction.mu_s


def mujoco_model(stack: Stack, dt: float, vertical: bool) -> str:
    """MJCF of the stack on a driven platform (see the module docstring)."""
    solref = f"{2 * dt:g} 1"
    mass = sum(b.mass for b in stack.blocks)
    bodies, pairs = [], []
    for k, ((x, z), block, iface) in enumerate(zip(rest_centres(stack), stack.blocks, stack.interfaces)):
        j = block.centroidal_inertia
        bodies.append(
            f'<body name="b{k}" pos="{x!r} 0 {z!r}">'
            f'<joint name="x{k}" type="slide" axis="1 0 0"/><joint name="z{k}" type="slide" axis="0 0 1"/>'
            f'<joint name="theta{k}" type="hinge" axis="0 1 0"/>'
            f'<inertial pos="0 0 0" mass="{block.mass!r}" diaginertia="{j!r} {j!r} {j!r}"/>'
            f'<geom name="g{k}" type="box" size="{block.width / 2!r} {DEPTH / 2!r} {block.height / 2!r}"/></body>')
        below, below_body = ("floor", "floor") if k == 0 else (f"g{k - 1}", f"b{k - 1}")
        mu = mujoco_friction(iface)
        pairs.append(f'<exclude body1="{below_body}" body2="b{k}"/>'
                     f'<pair geom1="{below}" geom2="g{k}" friction="{mu!r} {mu!r} 0.005 0.0001 0.0001" '
                     f'solref="{solref}"/>')
    z_joint = '<joint name="z_g" type="slide" axis="0 0 1"/>' if vertical else ""
    z_motor = '<motor name="drive_z" joint="z_g" ctrllimited="false"/>' if vertical else ""
    return f"""
<mujoco model="stack">
  <option timestep="{dt!r}" gravity="0 0 -{GRAVITY!r}"/>
  <default><geom friction="{NON_NEIGHBOUR_MU!r} 0.005 0.0001" solref="{solref}"/></default>
  <worldbody>
    <body name="floor"><joint name="x_g" type="slide" axis="1 0 0"/>{z_joint}
      <geom name="floor" type="box" pos="0 0 -0.05" size="{FLOOR_HALF_LENGTH!r} 1 0.05"
            mass="{PLATFORM_MASS_RATIO * mass!r}"/></body>
    {"".join(bodies)}
  </worldbody>
  <contact>{"".join(pairs)}</contact>
  <actuator><motor name="drive_x" joint="x_g" ctrllimited="false"/>{z_motor}</actuator>
</mujoco>"""


def _settled_state(model, data, dt: float) -> np.ndarray:
    mujoco.mj_step(model, data, nstep=round(SETTLE / dt))
    data.time = 0.0
    data.qpos[model.jnt_qposadr[model.joint("x_g").id]] = 0.0
    data.qvel[:] = 0.0
    data.qacc_warmstart[:] = 0.0
    mujoco.mj_forward(model, data)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    x0 = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, x0, spec)
    return x0


def run_mujoco(case: PeerCase, dt: float, repeats: int, peak_until: float) -> Outcome:
    floor = floor_kinematics(case.motion, case.duration, dt)
    vertical = floor["vz"] is not None
    model = mujoco.MjModel.from_xml_string(mujoco_model(case.stack, dt, vertical))
    data = mujoco.MjData(model)
    if vertical:  # hold the platform and the stack up before t = 0
        data.ctrl[1] = model.body_subtreemass[0] * GRAVITY
    x0 = _settled_state(model, data, dt)
    platform_mass = float(model.body_mass[model.body("floor").id])
    controls = [platform_mass * floor["ax_mid"]]
    if vertical:
        controls.append(platform_mass * floor["az_mid"] + model.body_subtreemass[0] * GRAVITY)
    control = np.stack(controls, axis=-1)[None, :, :]
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        state, _ = mj_rollout.rollout(model, data, x0[None, :], control)
        times.append(time.perf_counter() - t0)
    state = state[0]
    t = state[:, 0]
    qpos = state[:, 1:1 + model.nq]
    hinges = [model.jnt_qposadr[model.joint(f"theta{k}").id] for k in range(case.stack.n)]
    overturn, peak = summarize(qpos[:, hinges], t, peak_until)
    x_p = qpos[:, model.jnt_qposadr[model.joint("x_g").id]]
    errors = [float(np.max(np.abs(x_p - floor["x"][1:])))]
    note = f"platform |x_p − x_g| ≤ {1e3 * errors[0]:.2g} mm"
    if vertical:  # z_p from where the settled platform stood
        z0 = x0[1 + model.jnt_qposadr[model.joint("z_g").id]]
        z_p = qpos[:, model.jnt_qposadr[model.joint("z_g").id]] - z0
        errors.append(float(np.max(np.abs(z_p - floor["z"][1:]))))
        note += f", |z_p − z_g| ≤ {1e3 * errors[1]:.2g} mm"
    return Outcome("MuJoCo", dt, statistics.median(times), floor["n"], overturn, peak, note=note,
                   floor_error=max(errors))


# --- LMGC90 --------------------------------------------------------------------------------------

def lmgc90_obstacle(stack: Stack) -> str | None:
    """Why LMGC90 (compas-lmgc90) cannot model this stack, or None."""
    frictions = [iface.friction for iface in stack.interfaces]
    reasons = []
    if len({None if f is None else (f.mu_s, f.mu_k) for f in frictions}) > 1:
        listed = ", ".join("never slips" if f is None else f"{f.mu_s:g}/{f.mu_k:g}" for f in frictions)
        reasons.append(f"frictions per interface ({listed}) but compas-lmgc90 registers one contact law "
                       f"for every contact")
    elif frictions[0] is None:
        reasons.append("no friction given (never slips): a stand-in μ would be our choice, not the case")
    if any(f is not None and f.mu_s != f.mu_k for f in frictions):
        reasons.append("μk ≠ μs but its IQS_CLB law has one μ")
    if any(iface.restitution is not None for iface in stack.interfaces):
        reasons.append("a restitution coefficient but its one law applies to every contact")
    if any(block.inertia is not None for block in stack.blocks):
        reasons.append("a given inertia but LMGC90 takes it from the polyhedron")
    return "; ".join(reasons) or None


def run_lmgc90(case: PeerCase, dt: float, repeats: int, python: str, peak_until: float) -> Outcome | str:
    """An Outcome, or the reason it was not run."""
    reason = lmgc90_obstacle(case.stack)
    if reason:
        return reason
    if not Path(python).exists():
        return (f"no LMGC90 venv at {python} (python3 -m venv /tmp/lmgc-venv && "
                f"/tmp/lmgc-venv/bin/pip install compas-lmgc90 numpy)")
    floor = floor_kinematics(case.motion, case.duration, dt)
    spec = {
        "dt": dt, "steps": floor["n"], "repeats": repeats, "mu": case.stack.interfaces[0].friction.mu_s,
        "blocks": [{"cx": x, "cz": z, "width": b.width, "height": b.height, "mass": b.mass}
                   for (x, z), b in zip(rest_centres(case.stack), case.stack.blocks)],
        "t": floor["t"].tolist(), "vx": floor["vx"].tolist(),
        "vz": None if floor["vz"] is None else floor["vz"].tolist(),
    }
    with tempfile.TemporaryDirectory() as tmp:
        spec_path, out_path = Path(tmp, "spec.json"), Path(tmp, "out.json")
        spec_path.write_text(json.dumps(spec))
        # cwd: LMGC90 may write diagnostics next to itself
        proc = subprocess.run([python, str(Path(__file__).resolve()), WORKER_FLAG, str(spec_path), str(out_path)],
                              cwd=tmp, capture_output=True, text=True)
        if proc.returncode != 0 or not out_path.exists():
            last = (proc.stderr.strip() or proc.stdout.strip() or "no output").splitlines()[-1]
            return f"LMGC90 stopped (exit {proc.returncode}): {last}"
        out = json.loads(out_path.read_text())
    theta = np.asarray(out["theta"])
    t = floor["t"][1:]
    overturn, peak = summarize(theta, t, peak_until)
    tracking = float(np.max(np.abs(np.asarray(out["floor_x"]) - floor["x"][1:])))
    return Outcome(f"LMGC90 {out['version']}", dt, statistics.median(out["times"]), floor["n"], overturn, peak,
                   note=f"floor |x − x_g| ≤ {1e3 * tracking:.2g} mm", floor_error=tracking)


# --- report --------------------------------------------------------------------------------------

def _verdict(t: float | None) -> str:
    return "no" if t is None else f"{t:.3f} s"


def verdict_delta(t: float | None, t_ref: float | None, ref_end: float) -> str:
    """The overturn-time difference (s), "same" (neither fell), "DIFF", or "after" (a fall after
    the reference run stopped at another block's fall: not compared)."""
    if t is not None and t_ref is not None:
        return f"{t - t_ref:+.3f}"
    if t is None and t_ref is None:
        return "same"
    if t_ref is None and t > ref_end:
        return "after"
    return "DIFF"


def block_cell(outcome: Outcome, ref: Outcome, k: int) -> str:
    cell = f"{_verdict(outcome.overturn[k]):>8s} {outcome.peak[k]:6.4f}"
    if outcome is ref:
        return cell + " " * 19
    delta = verdict_delta(outcome.overturn[k], ref.overturn[k], ref.end_time)
    return cell + f" ({delta:>6s}, {outcome.peak[k] - ref.peak[k]:+.4f})"


def verdict_differences(outcome: Outcome, ref: Outcome) -> int:
    return sum(verdict_delta(t, t_ref, ref.end_time) == "DIFF" for t, t_ref in zip(outcome.overturn, ref.overturn))


def print_case(case: PeerCase, rows: list, response) -> None:
    names = case.stack.names
    print(f"\n[{case.key}] {case.label}; window {case.duration:g} s")
    head = f"{'engine':16s} {'dt':>7s} {'ms/run':>9s} {'steps':>7s}  " + "  ".join(
        f"{name + ': overturn, peak|φ| rad (Δt, Δpeak)':^42s}" for name in names)
    print(head.rstrip())
    print("-" * len(head.rstrip()))
    ref = rows[0]
    for row in rows:
        if isinstance(row, tuple):  # (engine, reason)
            print(f"{row[0]:16s} not run: {row[1]}")
            continue
        dt = "event" if row.dt is None else f"{row.dt:g}"
        cells = "  ".join(block_cell(row, ref, k) for k in range(len(names)))
        print(f"{row.engine:16s} {dt:>7s} {1e3 * row.seconds:9.1f} {row.steps:7d}  {cells}".rstrip())
    view = next((row for row in rows if not isinstance(row, tuple) and row.engine == MUJOCO_VIEW), None)
    for row in rows:
        if not isinstance(row, tuple):
            extra = "" if row is ref else f"; verdicts differing from rocking: {verdict_differences(row, ref)}"
            if view is not None and row.engine == "MuJoCo":
                extra += f", from {MUJOCO_VIEW}: {verdict_differences(row, view)}"
            print(f"  {row.engine} dt={row.dt if row.dt else '–'}: {row.note}{extra}")
    if view is not None:
        print(f"  {MUJOCO_VIEW}: rocking with MuJoCo's simplifications (μk = μs, no restitution coefficient)")
    needed = ", ".join(f"{f['name']} {f['required_friction']:.2f}" for f, iface in
                       zip(response.interfaces, case.stack.interfaces) if iface.friction is None)
    if needed:
        print(f"  never-slip interfaces (MuJoCo μ = {NEVER_SLIP_MU:g}): rocking needs |T|/N up to {needed}")
    if ref.end_time < case.duration:
        print(f"  rocking stops at the first fall ({ref.end_time:.3f} s): the peers' peaks are taken up to then, "
              f"their later falls marked 'after'")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one step size per peer, 1 repeat")
    ap.add_argument("--repeats", type=int, default=3, help="timed repeats per peer run (rocking: 5)")
    ap.add_argument("--cases", default="b2,r3,h-fall,h-safe", help="comma-separated case keys")
    ap.add_argument("--lmgc-python", default=LMGC_DEFAULT_PYTHON, help="python of the venv with compas-lmgc90")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error(f"--repeats must be ≥ 1, got {args.repeats}")
    known = {c.key: c for c in peer_cases()}
    keys = [k.strip() for k in args.cases.split(",") if k.strip()]
    for key in keys:
        if key not in known:
            ap.error(f"--cases: unknown case {key!r} (known: {', '.join(known)})")
    repeats = 1 if args.quick else args.repeats
    mujoco_dts = (1e-3,) if args.quick else (1e-3, 1e-4)
    lmgc_dts = (1e-3,) if args.quick else (1e-3, 2.5e-4)

    print(f"rocking {rk.__version__} | MuJoCo {mujoco.__version__ if mujoco else 'not installed'} | "
          f"Python {platform.python_version()} | numpy {np.__version__}")
    print(f"{os.cpu_count()} CPUs | load average {', '.join(f'{x:.2f}' for x in os.getloadavg())} "
          f"(other processes skew timings)")
    for key in keys:
        case = known[key]
        ref, response = run_rocking(case, 3 if args.quick else 5)
        rows = [ref]
        simplified = as_mujoco_sees_it(case)
        if simplified.stack != case.stack:
            rows.append(run_rocking(simplified, 3 if args.quick else 5, MUJOCO_VIEW)[0])
        for dt in mujoco_dts:
            rows.append(run_mujoco(case, dt, repeats, ref.end_time) if mujoco else
                        ("MuJoCo", f"not installed ({_MUJOCO_IMPORT_ERROR}); .venv/bin/pip install mujoco"))
        for dt in lmgc_dts:
            got = run_lmgc90(case, dt, repeats, args.lmgc_python, ref.end_time)
            rows.append(got if isinstance(got, Outcome) else ("LMGC90", got))
            if not isinstance(got, Outcome):
                break  # the reason does not depend on the step
        print_case(case, rows, response)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
