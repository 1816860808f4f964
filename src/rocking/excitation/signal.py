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
    KIND_ZERO,
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


@njit(cache=True)
def signal_end(kind, params, times):
    """The time (s) after which the signal is zero for good: a record's last sample (inf for a
    window cut from a longer record, ``params[3]``), the end of a parametric motion
    (``params[3]``, inf for one that never ends), −inf for no motion."""
    if kind == KIND_SAMPLED:
        return max(times[times.shape[0] - 1], params[3])
    if kind == KIND_ZERO:
        return -math.inf
    return params[3]


@njit(cache=True)
def floor_end(sig_h, sig_v):
    """When the floor motion ends for good, s: the later of its two components' :func:`signal_end`
    (each a (kind, params, times, values) tuple)."""
    return max(signal_end(sig_h[0], sig_h[1], sig_h[2]), signal_end(sig_v[0], sig_v[1], sig_v[2]))


# Local forms: inside one integration step a signal is one smooth formula, so its coefficients
# are worked out once per step ("localised") and the right-hand side evaluates only that
# formula — no array look-ups, no branches on the kind in the innermost loop.
LOCAL_ZERO, LOCAL_LINEAR, LOCAL_COSINE, LOCAL_RICKER = 0.0, 1.0, 2.0, 3.0
LOCAL_SIZE = 5


@njit(cache=True, inline="always")
def localise(kind, params, times, values, piece):
    """The formula valid on the piece containing time ``piece``, as a 5-tuple:
    (LOCAL_LINEAR, a0, slope, t0, 0) for a0 + slope·(t − t0); (LOCAL_COSINE, A, ω, φ, 0);
    (LOCAL_RICKER, a_p, f, t_0, 0); or (LOCAL_ZERO, 0, 0, 0, 0). A tuple, not an array: the
    innermost loop then passes it around without reference counting."""
    if kind == KIND_SAMPLED:
        n = times.shape[0]
        if piece < times[0] or piece > times[n - 1]:
            return (LOCAL_ZERO, 0.0, 0.0, 0.0, 0.0)
        i = np.searchsorted(times, piece, side="right") - 1
        if i >= n - 1:
            i = n - 2
        slope = (values[i + 1] - values[i]) / (times[i + 1] - times[i])
        return (LOCAL_LINEAR, values[i], slope, times[i], 0.0)
    if kind < 0 or piece < 0.0 or piece > params[3]:
        return (LOCAL_ZERO, 0.0, 0.0, 0.0, 0.0)
    if kind == KIND_HARMONIC or kind == KIND_SINE_PULSE:
        return (LOCAL_COSINE, params[0], params[1], params[2], 0.0)
    if kind == KIND_RECTANGLE:
        return (LOCAL_LINEAR, params[0], 0.0, 0.0, 0.0)
    if kind == KIND_RAMP:
        return (LOCAL_LINEAR, 0.0, params[0], 0.0, 0.0)
    if kind == KIND_RICKER:
        return (LOCAL_RICKER, params[0], params[1], params[2], 0.0)
    return (LOCAL_ZERO, 0.0, 0.0, 0.0, 0.0)


@njit(cache=True, inline="always")
def local_value(loc, k0, t):
    """Value at time t of the localised formula loc[k0:k0+5] (a tuple of localised signals)."""
    mode = loc[k0]
    if mode == LOCAL_LINEAR:
        return loc[k0 + 1] + loc[k0 + 2] * (t - loc[k0 + 3])
    if mode == LOCAL_COSINE:
        return loc[k0 + 1] * math.cos(loc[k0 + 2] * t + loc[k0 + 3])
    if mode == LOCAL_RICKER:
        x = (math.pi * loc[k0 + 2] * (t - loc[k0 + 3])) ** 2
        return loc[k0 + 1] * (1.0 - 2.0 * x) * math.exp(-x)
    return 0.0


# Phase margin (rad) kept before a cosine leaves a band: arccos loses about √ε ≈ 1e-8 rad near
# ±1, so stopping 1e-6 rad short can never overshoot the exit.
_PHASE_MARGIN = 1e-6


@njit(cache=True, inline="always")
def cosine_band_exit(amplitude, omega, phase, t, t_stop, lo, hi):
    """A time in [t, t_stop] up to which A·cos(ω τ + φ) stays strictly inside (lo, hi) for
    every τ from t: ``t_stop`` if it never leaves the band before then, otherwise a time just
    short of (within 1e-6 rad of phase of) the first exit. Returns t when the value is not
    inside the band at t. Units: s, rad/s, rad, and the signal's unit for lo, hi."""
    if amplitude < 0.0:
        amplitude, phase = -amplitude, phase + math.pi
    if omega <= 0.0 or t_stop <= t:
        return t
    psi0 = omega * t + phase
    now = amplitude * math.cos(psi0)
    if not (lo < now < hi):
        return t
    if amplitude < hi and -amplitude > lo:
        return t_stop
    two_pi = 2.0 * math.pi
    r = psi0 - two_pi * math.floor(psi0 / two_pi)  # phase in [0, 2π)
    # The band is left upwards on entering [2kπ − β, 2kπ + β] (A cos ψ ≥ hi), downwards on
    # entering [2kπ + γ, 2kπ + 2π − γ] (A cos ψ ≤ lo); r lies outside both.
    to_exit = math.inf
    if amplitude >= hi:
        beta = math.acos(max(-1.0, min(1.0, hi / amplitude)))
        start = two_pi - beta
        while start < r:
            start += two_pi
        to_exit = start - r
    if -amplitude <= lo:
        gamma = math.acos(max(-1.0, min(1.0, lo / amplitude)))
        start = gamma
        while start < r:
            start += two_pi
        to_exit = min(to_exit, start - r)
    to_exit -= _PHASE_MARGIN
    if to_exit <= 0.0:
        return t
    return min(t_stop, t + to_exit / omega)


@njit(cache=True, inline="always")
def next_crest_of(loc, k0, t):
    """next_crest of the localised formula loc[k0:k0+5] (k0 = LOCAL_SIZE: the vertical part)."""
    mode = loc[k0]
    if mode == LOCAL_COSINE and loc[k0 + 2] > 0.0:
        omega, phase = loc[k0 + 2], loc[k0 + 3]
        tau = ((math.floor((omega * t + phase) / math.pi) + 1.0) * math.pi - phase) / omega
        return tau if tau > t else tau + math.pi / omega
    if mode == LOCAL_RICKER and loc[k0 + 2] > 0.0:
        t0 = loc[k0 + 3]
        side = math.sqrt(1.5) / (math.pi * loc[k0 + 2])
        if t < t0 - side:
            return t0 - side
        if t < t0:
            return t0
        if t < t0 + side:
            return t0 + side
    return math.inf


@njit(cache=True, inline="always")
def next_crest(loc, t):
    """The first local maximum of |a_h| of ``loc`` strictly after time t (s), or inf if it has no
    more: a cosine's where ω t + φ is a multiple of π, a Ricker wavelet's at τ = −√(3/2)/(π f),
    0 and +√(3/2)/(π f). Between two crests |a_h| only falls, rises, or falls to zero and rises,
    so a level it passes there is passed at an end: what a search for a first crossing needs."""
    return next_crest_of(loc, 0, t)


@njit(cache=True, inline="always")
def crest_inside(loc, t_a, t_b):
    """A time strictly inside (t_a, t_b) (s) where the horizontal floor acceleration |a_h| of
    the localised motion ``loc`` has a local maximum of the largest height found there, or NaN
    when it has none inside (a linear piece is largest at an end).

    Why: at rest every face carries the mass above it times (a_h, g + a_v), so the friction it
    needs is |a_h|/(g + a_v); over a stretch where a_v is constant (every non-linear motion
    here has no vertical part) that peaks at an end or at this crest, and a solver that reads
    the forces only at its step ends or stages misses the crest. The first crest after t_a
    (next_crest) is the one, since a cosine's crests all have height |A|, but for a Ricker
    wavelet's centre, the highest (|a_p| against 2|a_p| e^(−3/2) at its sides), if it follows
    inside."""
    c = next_crest(loc, t_a)
    if not c < t_b:
        return math.nan
    if loc[0] == LOCAL_RICKER and c < loc[3] < t_b:
        return loc[3]
    return c
