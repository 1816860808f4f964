"""Compiled evaluation of a floor-motion :class:`~rocking.excitation.base.Signal`.

Every formula here is the compiled twin of an ``acceleration`` method in
``harmonic.py``/``pulses.py``/``record.py``; tests check that both agree.

Why two times: a motion may jump (a cosine switched on at t = 0, a rectangular pulse switched
off at t_d). An integration step never straddles a jump (the jumps are breakpoints), but its
first and last stages sit *on* the jump. ``piece`` is a time strictly inside the current step:
it decides which side of a jump applies, and ``t`` is where the formula is evaluated.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .base import (
    KIND_HARMONIC,
    KIND_RAMP,
    KIND_RECTANGLE,
    KIND_RICKER,
    KIND_SAMPLED,
    KIND_SINE_PULSE,
)


@njit(cache=True)
def evaluate(kind, params, times, values, t, piece):
    """Acceleration (m/s²) of the signal at time ``t`` (s), on the side of ``piece``."""
    if kind == KIND_SAMPLED:
        n = times.shape[0]
        if piece < times[0] or piece > times[n - 1]:
            return 0.0
        i = np.searchsorted(times, piece, side="right") - 1
        if i >= n - 1:
            i = n - 2
        w = (t - times[i]) / (times[i + 1] - times[i])
        return values[i] + w * (values[i + 1] - values[i])
    if piece < 0.0 or piece > params[3]:
        return 0.0
    if kind == KIND_HARMONIC or kind == KIND_SINE_PULSE:
        # A·cos(ω t + φ); the sine pulse is stored with φ = ψ − π/2.
        return params[0] * math.cos(params[1] * t + params[2])
    if kind == KIND_RECTANGLE:
        return params[0]
    if kind == KIND_RICKER:
        x = (math.pi * params[1] * (t - params[2])) ** 2
        return params[0] * (1.0 - 2.0 * x) * math.exp(-x)
    if kind == KIND_RAMP:
        return params[0] * t
    return 0.0
