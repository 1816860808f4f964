"""An outside solver on the manual's cases: MuJoCo, a general rigid-body engine with soft
(penalty-like) contacts. Optional: the section is written only when ``mujoco`` imports.

The block is a box on a heavy platform; the platform slides along x under a prescribed force
(its mass, 1e6 kg, makes its acceleration the floor's to 1e-6); the block has free x, z and
rotation about y (θ > 0 leans it towards +x, as in the library). MuJoCo has no restitution
parameter and no Housner impact map: an impact is a short contact transient whose outcome
depends on the contact's stiffness and damping (``solref``) and the time step.
"""

from __future__ import annotations

import math

import numpy as np

import rocking as rk

from . import exact as ex
from . import lib
from .housner import velocity_step_ours
from .makris import mode1_pair, spectrum
from .rows import Row, Section

try:  # optional: not a dependency of the package
    import mujoco
except ImportError:  # pragma: no cover - depends on the environment
    mujoco = None

PLATFORM_MASS = 1e6  # kg
DEPTH = 0.2  # m, the box's extent along y (the model is planar)
XML = """
<mujoco model="validation peer">
  <option timestep="{dt}" gravity="0 0 -{g}"/>
  <default>
    <geom friction="{mu} 0.005 0.0001" solref="{timeconst} 1" solimp="0.9 0.95 0.001"/>
  </default>
  <worldbody>
    <body name="platform">
      <joint name="floor_x" type="slide" axis="1 0 0"/>
      <geom type="box" pos="0 0 -0.05" size="10 1 0.05" mass="{platform}"/>
    </body>
    <body name="block" pos="0 0 {h}">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="z" type="slide" axis="0 0 1"/>
      <joint name="theta" type="hinge" axis="0 1 0"/>
      <geom type="box" size="{b} {d} {h}" mass="1"/>
    </body>
  </worldbody>
  <actuator>
    <motor joint="floor_x" ctrllimited="false"/>
  </actuator>
</mujoco>
"""


def available() -> bool:
    return mujoco is not None


class Box:
    """A block of half-width b and half-height h (m) with friction ``mu`` on the platform,
    stepped with ``dt`` (s) and a contact time constant of 2·dt (MuJoCo's advice)."""

    def __init__(self, block: ex.Block, *, mu: float = 2.0, dt: float = 1e-4):
        self.block, self.dt = block, dt
        xml = XML.format(dt=dt, g=block.g, mu=mu, timeconst=2 * dt, platform=PLATFORM_MASS, b=block.b,
                         d=DEPTH / 2, h=block.h)
        self.model = mujoco.MjModel.from_xml_string(xml)
        self.data = mujoco.MjData(self.model)
        # the block settles into its contacts (a soft contact holds the weight with a small overlap)
        mujoco.mj_step(self.model, self.data, nstep=round(0.5 / dt))
        self.rest_z = float(self.data.qpos[2])

    def start(self, *, theta: float = 0.0, vx: float = 0.0) -> None:
        """Reset: platform at rest at x = 0; the block tilted by θ (rad) about its +x corner, or
        upright and sliding at vx (m/s) relative to the platform."""
        d = self.data
        mujoco.mj_resetData(self.model, d)
        b, h = self.block.b, self.block.h
        d.qpos[:] = 0.0
        d.qpos[1] = b - b * math.cos(theta) + h * math.sin(theta)
        d.qpos[2] = self.rest_z + b * math.sin(theta) + h * math.cos(theta) - h
        d.qpos[3] = theta
        d.qvel[:] = 0.0
        d.qvel[1] = vx
        mujoco.mj_forward(self.model, d)

    def run(self, duration: float, floor=None, stop=None) -> dict[str, np.ndarray]:
        """Step for ``duration`` s with the floor acceleration ``floor(t)`` (m/s², or None), or
        until ``stop(theta, theta_dot)`` is true. Returns t, θ, θ̇ and the sliding u (m)."""
        d, n = self.data, round(duration / self.dt)
        out = np.empty((n + 1, 4))
        out[0] = (d.time, d.qpos[3], d.qvel[3], d.qpos[1] - d.qpos[0])
        k = n
        for i in range(1, n + 1):
            if floor is not None:
                d.ctrl[0] = PLATFORM_MASS * floor(d.time + 0.5 * self.dt)
            mujoco.mj_step(self.model, d)
            out[i] = (d.time, d.qpos[3], d.qvel[3], d.qpos[1] - d.qpos[0])
            if stop is not None and stop(out[i, 1], out[i, 2]):
                k = i
                break
        out = out[: k + 1]
        return {"t": out[:, 0], "theta": out[:, 1], "theta_dot": out[:, 2], "u": out[:, 3]}


def free_rocking(block: ex.Block, dt: float) -> tuple[float, float]:
    """Release from rest at θ0 = α/2: (time of the first impact, s; the ratio η implied by the
    next peak through the exact energy recursion)."""
    box = Box(block, dt=dt)
    th0 = 0.5 * block.alpha
    box.start(theta=th0)
    r = box.run(3.0 * ex.quarter_period_exact(block, th0))
    th, t = r["theta"], r["t"]
    i = int(np.flatnonzero((th[:-1] > 0) & (th[1:] <= 0))[0])
    t1 = float(t[i] + th[i] / (th[i] - th[i + 1]) * (t[i + 1] - t[i]))
    peak = float(np.max(-th[i + 1:]))
    ca = math.cos(block.alpha)
    eta = math.sqrt((math.cos(block.alpha - peak) - ca) / (math.cos(block.alpha - th0) - ca))
    return t1, eta


def _falls(theta: float, _thd: float) -> bool:
    return abs(theta) > 1.2  # rad: far past α, nothing brings the block back


def velocity_step(block: ex.Block, dt: float) -> float:
    """Smallest relative sliding velocity V (m/s) given to the upright block that overturns it:
    in the floor's frame, the floor velocity step +V."""
    box = Box(block, dt=dt)

    def fails(v):
        box.start(vx=-v)
        seen = {"away": False}

        def stop(theta, thd):
            if abs(theta) > 1e-3:
                seen["away"] = True
            return _falls(theta, thd) or (seen["away"] and theta > 0.0)  # back at θ = 0: an impact

        r = box.run(6.0, stop=stop)
        return abs(r["theta"][-1]) > 1.2

    return ex.find(fails, ex.velocity_step_exact(block), rtol=1e-4, step=1.01)


def sine_mode1(block: ex.Block, beta: float, dt: float) -> float:
    """Smallest one-sine a_p/(g tan α) (rocking from t = 0) that overturns before any impact."""
    box = Box(block, dt=dt)
    gt = block.g * block.tan_alpha

    def fails(A):
        m = ex.sine_pulse(A * gt, beta * block.p, math.asin(1.0 / A))
        box.start()
        seen = {"away": False}

        def stop(theta, thd):
            if abs(theta) > 1e-3:
                seen["away"] = True
            return _falls(theta, thd) or (seen["away"] and theta > 0.0)

        r = box.run(m.end + 10.0 / block.p, floor=lambda t: m.accel(t) if t <= m.end else 0.0, stop=stop)
        return abs(r["theta"][-1]) > 1.2

    return ex.find(fails, ex.one_sine_mode1_linear(beta), rtol=1e-4, step=1.01)


def newmark(A: float, N: float, t0: float, dt: float) -> float:
    """Residual sliding |u| (m) of a squat box (B = 1 m, H = 0.1 m, friction N) under A·g for t0 s."""
    box = Box(ex.Block(0.5, 0.05), mu=N, dt=dt)
    box.start()
    r = box.run(t0 + A * t0 / N + 1.0, floor=lambda t: A * ex.G if t < t0 else 0.0)
    return abs(float(r["u"][-1] - r["u"][0]))


def harmonic(dt: float) -> tuple[list[float], float | None]:
    """The benchmark case of ``bench/``: B = 1 m, H = 4 m under 6.75·cos(2π·1.2 t) m/s² for 30
    cycles. Returns the first four impact times (s) and the overturning time (s, or None)."""
    blk = ex.Block(0.5, 2.0)
    box = Box(blk, dt=dt)
    box.start()
    w = 2 * math.pi * 1.2
    r = box.run(25.0, floor=lambda t: 6.75 * math.cos(w * t) if t <= 25.0 else 0.0,
                stop=lambda th, _thd: abs(th) > 1.2)
    th, t = r["theta"], r["t"]
    crossings = []
    last = 0
    for i in np.flatnonzero(np.sign(th[:-1]) * np.sign(th[1:]) < 0):
        # a rocking half-cycle, not the contact's chatter around θ = 0
        if np.max(np.abs(th[last:i + 1])) > 1e-3:
            crossings.append(float(t[i] + th[i] / (th[i] - th[i + 1]) * (t[i + 1] - t[i])))
        last = i
    fell = abs(th[-1]) > 1.2
    return crossings[:4], (float(t[-1]) if fell else None)


BAND = 0.01  # relative: a general engine is expected within 1 % of the rigid-body model here


def rows(progress) -> list[Row]:
    blk = ex.Block(0.25, 1.0)
    th0 = 0.5 * blk.alpha
    lib_free = lib.simulate(lib.alone(blk), lib.STILL, duration=3.0, save=False, initial_rotation=th0).impacts[0]
    v_ours = velocity_step_ours(blk)
    ours_sine = float(spectrum(blk, ["sine"], [2.0], criterion="no_impact", rtol=1e-7).amplitude_ratio.values[0, 0])
    exact_sine = mode1_pair(blk, "sine", 2.0, ours_sine, 1e-8)
    squat = ex.Block(5.0, 0.5)
    slide = lib.simulate(lib.alone(squat, friction=rk.Friction(static=0.2, kinetic=0.2)),
                         rk.RectanglePulse(amplitude=0.5 * ex.G, width=0.5), save=False)
    bench_motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30)
    bench = lib.simulate(lib.alone(ex.Block(0.5, 2.0)), bench_motion, save=False)
    # the same run with the standard gravity 9.80665 m/s² instead of 9.81: how sensitive it is
    bench_g0 = lib.simulate(lib.alone(ex.Block(0.5, 2.0)), bench_motion, save=False, options=rk.Options())
    out = []
    for dt in (1e-3, 1e-4):
        tag = "a" if dt == 1e-3 else "b"
        src = f"MuJoCo, dt = {dt:g} s"
        progress(f"MuJoCo (dt = {dt:g} s): free rocking, velocity step, one-sine, sliding, harmonic")
        t1, eta = free_rocking(blk, dt)
        out.append(Row(f"M1.{tag}", src, "free rocking from θ0 = α/2, B = 0.5 m, H = 2 m: time to the first impact "
                                         "(reference: exact quadrature, §1)", "peer",
                       published=ex.quarter_period_exact(blk, th0), ours=lib_free.time, exact=t1, unit="s",
                       tol=BAND))
        out.append(Row(f"M2.{tag}", src, "same run: η implied by the first rebound through the exact energy recursion "
                                         "(reference: Housner's η)", "peer", published=blk.eta,
                       ours=lib_free.theta_dot_after / lib_free.theta_dot_before, exact=eta, tol=BAND))
        out.append(Row(f"M3.{tag}", src, "velocity step that overturns, B = 0.5 m, H = 2 m (reference: exact closed "
                                         "form, §1)", "peer", published=ex.velocity_step_exact(blk), ours=v_ours,
                       exact=velocity_step(blk, dt), unit="m/s", tol=BAND))
        out.append(Row(f"M4.{tag}", src, "one-sine β = 2, B = 0.5 m, H = 2 m: smallest a_p/(g·tan α) overturning "
                                         "without impact (reference: exact integration, §2)", "peer",
                       published=exact_sine, ours=ours_sine, exact=sine_mode1(blk, 2.0, dt), tol=BAND))
        out.append(Row(f"M5.{tag}", src, "Newmark: pulse 0.5g for 0.5 s, μ = 0.2 (reference: Newmark's formula, §6)",
                       "peer", published=ex.newmark_rectangle(0.5, 0.2, 0.5),
                       ours=abs(slide.summary()["residual_sliding"]), exact=newmark(0.5, 0.2, 0.5, dt), unit="m",
                       tol=BAND))
        times, fell = harmonic(dt)
        out.append(Row(f"M6.{tag}", src, "bench case (a): B = 1 m, H = 4 m, 6.75·cos(2π·1.2 t) m/s², Housner η: "
                                         "time of the 4th impact", "peer", ours=bench.impacts[3].time,
                       exact=times[3] if len(times) > 3 else math.nan, unit="s", tol=BAND))
        out.append(Row(f"M7.{tag}", src, "bench case (a): time of overturning", "peer",
                       ours=bench.overturn_time, exact=fell if fell is not None else math.nan, unit="s", tol=BAND,
                       note="after some ten impacts the response depends sensitively on small differences: the "
                            "library itself overturns at "
                            f"{bench_g0.overturn_time:.2f} s instead of {bench.overturn_time:.2f} s when g is "
                            "9.80665 instead of 9.81 m/s², and MuJoCo's time moves with dt. The time of a late "
                            "overturning is not a measure of accuracy; the early impacts (M6) are."))
    return out


INTRO = """MuJoCo is a general rigid-body engine: contacts are soft constraints (a stiffness and damping set by
`solref`, here a time constant of 2·dt, critically damped), friction is a regularised cone, and an
impact is a short contact transient rather than Housner's impact map. It has no restitution parameter.
The model is a box 0.2 m deep on a 10⁶ kg platform driven by a force, with free x, z and rotation about y
(`rocking.validation.peer`, written for this manual; `bench/mujoco_peer.py` runs the benchmark case
with timings). Friction 2 keeps the rocking cases from sliding. Each case is run at dt = 1e-3 s and
1e-4 s. Columns: the reference (published or exact) value, ours, MuJoCo, and ours against the
reference; the verdict compares MuJoCo with ours."""


def section(quick: bool, progress) -> Section:
    if not available():
        return Section("peer", "9. An outside solver: MuJoCo",
                       "MuJoCo is not installed here (`pip install mujoco` adds it; the package does not depend on "
                       "it), so this section was not computed.", [])
    version = getattr(mujoco, "__version__", "?")
    return Section("peer", "9. An outside solver: MuJoCo", INTRO + f"\n\nMuJoCo {version}.", rows(progress),
                   exact_label="MuJoCo")
