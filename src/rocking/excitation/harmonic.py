"""Harmonic floor motion: a_g(t) = A·cos(ω t + φ) for a whole number of cycles."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .base import KIND_HARMONIC, N_PARAMS, AbstractMotion, Signal
from ._checks import finite, positive


@dataclass(frozen=True, kw_only=True, slots=True)
class Harmonic(AbstractMotion):
    """Harmonic floor acceleration switched on at t = 0 and off after ``cycles`` cycles.

    Parameters
    ----------
    amplitude : float
        A, m/s² (may be negative to reverse the direction).
    frequency : float
        f, Hz; ω = 2πf.
    cycles : float
        Number of cycles; the motion lasts cycles/f seconds.
    form : {"cos", "sin"}
        ``"cos"``: A·cos ωt (the paper's Table 1; jumps to A at t = 0⁺).
        ``"sin"``: A·sin ωt (starts from zero).
    angular_frequency : float, optional
        ω in rad/s, to reproduce a rounded value such as the paper's 7.53 s⁻¹ (P13);
        overrides ``frequency`` for the waveform but not for the duration.

    Examples
    --------
    >>> Harmonic(amplitude=6.75, frequency=1.2, cycles=30).duration
    25.0
    """

    amplitude: float
    frequency: float
    cycles: float = 1.0
    form: str = "cos"
    angular_frequency: float | None = None

    def __post_init__(self):
        positive("frequency", self.frequency)
        positive("cycles", self.cycles)
        finite("amplitude", self.amplitude)
        if self.form not in ("cos", "sin"):
            raise ValueError(f"form must be 'cos' or 'sin', got {self.form!r}")
        if self.angular_frequency is not None:
            positive("angular_frequency", self.angular_frequency)

    @property
    def omega(self) -> float:
        """ω, rad/s."""
        if self.angular_frequency is not None:
            return float(self.angular_frequency)
        return 2.0 * math.pi * self.frequency

    @property
    def phase(self) -> float:
        return 0.0 if self.form == "cos" else -0.5 * math.pi

    @property
    def duration(self) -> float:
        return self.cycles / self.frequency

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        on = (t >= 0.0) & (t <= self.duration)
        return np.where(on, self.amplitude * np.cos(self.omega * t + self.phase), 0.0)

    def signal(self) -> Signal:
        params = np.array([self.amplitude, self.omega, self.phase, self.duration])
        assert params.size == N_PARAMS
        return Signal(KIND_HARMONIC, params, np.zeros(0), np.zeros(0))

    @property
    def pga(self) -> float:
        return abs(self.amplitude)
