"""The library under test, reached through its public API only (``rocking.simulate``, the
bodies, the pulses, ``rocking.analyses.spectra``), so that the manual keeps working when the
internals are renamed."""

from __future__ import annotations

import math

import numpy as np

import rocking as rk
from rocking.excitation.record import GroundMotion

from .exact import G, Block

#: the library's options for every run of the manual: the oracle tables' g = 9.81 m/s²
OPTIONS = rk.Options(gravity=G)
#: a floor that never moves (free-rocking runs)
STILL = rk.Harmonic(amplitude=0.0, frequency=1.0, cycles=1.0)


def statue(block: Block, *, restitution: float | None = None, friction: rk.Friction | None = None,
           mass: float = 1.0) -> rk.Statue:
    """The library's statue for a block of half-width b and half-height h (m), mass in kg."""
    return rk.Statue(width=2.0 * block.b, height=2.0 * block.h, mass=mass, restitution=restitution,
                     friction=friction)


def alone(block: Block, **kw) -> rk.System:
    """The block standing on the floor."""
    return rk.System(statue=statue(block, **kw))


def simulate(system: rk.System, motion, **kw) -> rk.Response:
    """``rk.simulate`` with the manual's options unless given."""
    kw.setdefault("options", OPTIONS)
    return rk.simulate(system, motion, **kw)


def model_overturned(r: rk.Response) -> bool:
    """Whether the Housner model itself overturned the block: the solver's own status, whether or
    not the block's base force reached zero on the way. The manual compares the model with closed
    forms of the same model, which assume the block never leaves its pivot; a user's verdict, by
    contrast, is ``lifted_off`` there (docs/verdicts.md), as under the impulses that carry a
    velocity step here (10⁴ g for 1e-5 s, under which a real block would jump)."""
    from rocking.solver.compiled import S_STATUS, STATUS_OVERTURNED

    return int(r.raw_summary[S_STATUS]) == STATUS_OVERTURNED


def overturns_mode1(block: Block, motion) -> bool:
    """Does the library overturn the block before any impact (mode 1)?"""
    r = simulate(alone(block), motion, save=False)
    return bool(model_overturned(r) and r.summary()["impacts"] == 0)


def sine_pulse(block: Block, A: float, beta: float) -> rk.SinePulse:
    """The one-sine pulse of amplitude A·g·tan α and ω_p = β·p whose phase ψ = asin(1/A) makes
    rocking start at t = 0 (Zhang & Makris's pulse as defined in the manual)."""
    gt = block.g * block.tan_alpha
    return rk.SinePulse(amplitude=A * gt, frequency=beta * block.p / (2 * math.pi), phase=math.asin(1.0 / A))


def cosine_pulse(block: Block, A: float, beta: float) -> rk.CosinePulse:
    """a_p·cos(ω_p t) for one period, a_p = A·g·tan α, ω_p = β·p."""
    return rk.CosinePulse(amplitude=A * block.g * block.tan_alpha, frequency=beta * block.p / (2 * math.pi))


def two_pulses(v1: float, v2: float, t2: float, width: float) -> GroundMotion:
    """Two rectangular acceleration pulses of ``width`` s carrying floor velocity steps v1 at
    t = 0 and v2 at t = t2 (m/s). The floor motion is piecewise linear between samples, so each
    pulse ends (and the second begins) with a ramp of width/1000 whose area is counted."""
    ramp = width * 1e-3
    a1 = v1 / (width + 0.5 * ramp)
    a2 = v2 / (width + ramp)
    t = [0.0, width, width + ramp, t2, t2 + ramp, t2 + ramp + width, t2 + 2 * ramp + width]
    a = [a1, a1, 0.0, 0.0, a2, a2, 0.0]
    if not t2 > width + ramp:
        raise ValueError("the second pulse must start after the first ends")
    return GroundMotion.from_arrays(np.array(t), np.array(a), name="double impulse")
