"""Pulse-type floor motions used for overturning spectra and closed-form checks.

Conventions follow the oracles (Housner 1963; Zhang & Makris 2001; Dimitrakopoulos & DeJong 2012):
a positive amplitude accelerates the floor towards +x, which starts rocking with θ < 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._checks import finite, positive
from .base import (
    KIND_HARMONIC,
    KIND_RAMP,
    KIND_RECTANGLE,
    KIND_RICKER,
    KIND_SINE_PULSE,
    AbstractMotion,
    Signal,
)

_EMPTY = np.zeros(0)


@dataclass(frozen=True, kw_only=True, slots=True)
class SinePulse(AbstractMotion):
    """One-sine pulse a_p·sin(ω_p t + ψ) for 0 ≤ t ≤ (2π − ψ)/ω_p (oracle O9).

    Parameters
    ----------
    amplitude : float
        a_p, m/s².
    frequency : float
        f_p, Hz (ω_p = 2π f_p).
    phase : float
        ψ, rad, in [0, 2π). With ψ = asin(g tan α / a_p) rocking starts at t = 0 (type-A pulse).
    """

    amplitude: float
    frequency: float
    phase: float = 0.0

    def __post_init__(self):
        finite("amplitude", self.amplitude)
        positive("frequency", self.frequency)
        finite("phase", self.phase)
        if not 0.0 <= self.phase < 2.0 * math.pi:
            raise ValueError(f"phase must lie in [0, 2π) rad, got {self.phase!r}")

    @property
    def omega(self) -> float:
        return 2.0 * math.pi * self.frequency

    @property
    def duration(self) -> float:
        return (2.0 * math.pi - self.phase) / self.omega

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        on = (t >= 0.0) & (t <= self.duration)
        return np.where(on, self.amplitude * np.sin(self.omega * t + self.phase), 0.0)

    def signal(self) -> Signal:
        # sin(x) = cos(x − π/2): the compiled evaluator shares the harmonic formula.
        p = np.array([self.amplitude, self.omega, self.phase - 0.5 * math.pi, self.duration])
        return Signal(KIND_SINE_PULSE, p, _EMPTY, _EMPTY)

    @property
    def pga(self) -> float:
        return abs(self.amplitude)


@dataclass(frozen=True, kw_only=True, slots=True)
class CosinePulse(AbstractMotion):
    """One-cosine pulse a_p·cos(ω_p t) for 0 ≤ t ≤ 2π/ω_p (oracle O9b)."""

    amplitude: float
    frequency: float

    def __post_init__(self):
        finite("amplitude", self.amplitude)
        positive("frequency", self.frequency)

    @property
    def omega(self) -> float:
        return 2.0 * math.pi * self.frequency

    @property
    def duration(self) -> float:
        return 1.0 / self.frequency

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        on = (t >= 0.0) & (t <= self.duration)
        return np.where(on, self.amplitude * np.cos(self.omega * t), 0.0)

    def signal(self) -> Signal:
        p = np.array([self.amplitude, self.omega, 0.0, self.duration])
        return Signal(KIND_HARMONIC, p, _EMPTY, _EMPTY)

    @property
    def pga(self) -> float:
        return abs(self.amplitude)


@dataclass(frozen=True, kw_only=True, slots=True)
class RectanglePulse(AbstractMotion):
    """Constant acceleration a for 0 ≤ t < t_d (oracles O8, O12; a short one is a velocity step, O6)."""

    amplitude: float
    width: float

    def __post_init__(self):
        finite("amplitude", self.amplitude)
        positive("width", self.width)

    @property
    def duration(self) -> float:
        return self.width

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0.0) & (t < self.width), self.amplitude, 0.0)

    def signal(self) -> Signal:
        p = np.array([self.amplitude, self.width, 0.0, self.width])
        return Signal(KIND_RECTANGLE, p, _EMPTY, _EMPTY)

    @property
    def pga(self) -> float:
        return abs(self.amplitude)


@dataclass(frozen=True, kw_only=True, slots=True)
class RickerPulse(AbstractMotion):
    """Ricker wavelet a_p·(1 − 2π²f²τ²)·exp(−π²f²τ²), τ = t − t_0, on 0 ≤ t ≤ 2 t_0.

    ``center`` t_0 defaults to 1.5/f so the wavelet starts from (practically) zero.
    """

    amplitude: float
    frequency: float
    center: float | None = None

    def __post_init__(self):
        finite("amplitude", self.amplitude)
        positive("frequency", self.frequency)
        if self.center is not None:
            positive("center", self.center)

    @property
    def t0(self) -> float:
        return self.center if self.center is not None else 1.5 / self.frequency

    @property
    def duration(self) -> float:
        return 2.0 * self.t0

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        x = (np.pi * self.frequency * (t - self.t0)) ** 2
        on = (t >= 0.0) & (t <= self.duration)
        return np.where(on, self.amplitude * (1.0 - 2.0 * x) * np.exp(-x), 0.0)

    def signal(self) -> Signal:
        p = np.array([self.amplitude, self.frequency, self.t0, self.duration])
        return Signal(KIND_RICKER, p, _EMPTY, _EMPTY)

    @property
    def pga(self) -> float:
        return abs(self.amplitude)


@dataclass(frozen=True, kw_only=True, slots=True)
class Ramp(AbstractMotion):
    """a_g = k·t for 0 ≤ t ≤ t_end (oracle O1: locating the rocking onset)."""

    rate: float
    end: float

    def __post_init__(self):
        finite("rate", self.rate)
        positive("end", self.end)

    @property
    def duration(self) -> float:
        return self.end

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0.0) & (t <= self.end), self.rate * t, 0.0)

    def signal(self) -> Signal:
        return Signal(KIND_RAMP, np.array([self.rate, 0.0, 0.0, self.end]), _EMPTY, _EMPTY)
