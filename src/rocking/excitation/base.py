"""The contract every floor motion satisfies.

A floor motion is an immutable object that gives the horizontal floor acceleration
a_g(t) (m/s², +x) and optionally the vertical one a_v(t) (m/s², upwards) at any time t (s).

The compiled core cannot call Python objects, so every motion also describes itself as a
*signal*: an integer kind, a small parameter vector and (for recorded motions) sample arrays.
`rocking.excitation.signal.evaluate` evaluates that description inside compiled code; the
``acceleration`` method of each class is the vectorised NumPy version of the same formula.
"""

from __future__ import annotations

import abc
from typing import NamedTuple

import numpy as np

# Signal kinds understood by the compiled evaluator (rocking.excitation.signal).
KIND_ZERO = -1  #: no motion
KIND_SAMPLED = 0  #: piecewise linear through samples (t_i, a_i); zero outside [t_0, t_n];
#: params[3] = inf for a window cut from a longer record (its floor goes on after t_n), else 0
KIND_HARMONIC = 1  #: A·cos(ω t + φ) for 0 ≤ t ≤ t_end, else 0;   params = (A, ω, φ, t_end)
KIND_SINE_PULSE = 2  #: a_p·sin(ω t + ψ) for 0 ≤ t ≤ (2π − ψ)/ω; params = (a_p, ω, ψ, t_end)
KIND_RECTANGLE = 3  #: a for 0 ≤ t < t_d;                        params = (a, t_d, 0, t_d)
KIND_RICKER = 4  #: a_p (1 − 2π²f²τ²) exp(−π²f²τ²), τ = t − t_0;  params = (a_p, f, t_0, t_end)
KIND_RAMP = 5  #: k·t for 0 ≤ t ≤ t_end;                        params = (k, 0, 0, t_end)

N_PARAMS = 4


class Signal(NamedTuple):
    """Description of a scalar acceleration history for the compiled evaluator."""

    kind: int
    params: np.ndarray  # float64[N_PARAMS]
    time: np.ndarray  # float64[n] sample times (s); empty for analytic kinds
    values: np.ndarray  # float64[n] sample values (m/s²); empty for analytic kinds


ZERO_SIGNAL = Signal(KIND_ZERO, np.zeros(N_PARAMS), np.zeros(0), np.zeros(0))


def signal_breakpoints(signal: Signal) -> np.ndarray:
    """Times (s) where ``signal`` may jump or kink: a sampled signal's sample times, the two ends
    [0, t_end] of an analytic one's support, nothing for no motion. The solvers stop at these
    whatever a motion's ``breakpoints`` lists, so that a vertical component's jump (a user's
    motion whose list names the horizontal one's only) is never straddled by a step."""
    if signal.kind == KIND_ZERO:
        return np.zeros(0)
    if signal.kind == KIND_SAMPLED:
        return np.asarray(signal.time, dtype=float)
    return np.array([0.0, float(signal.params[3])])


class AbstractMotion(abc.ABC):
    """A floor motion. Subclasses are frozen dataclasses.

    To implement one you must provide:

    1. ``duration`` (s): the time after which the floor no longer accelerates;
    2. ``acceleration(t)`` returning the horizontal acceleration (m/s²) for an array ``t``;
    3. ``signal()`` returning the :class:`Signal` of the horizontal acceleration;
    4. optionally ``vertical_signal()`` (default: no vertical motion) and
       ``breakpoints`` (times where a_g is not smooth; the integrators stop exactly there, and at
       every jump and kink of the two signals too, see :func:`signal_breakpoints`).
    """

    @property
    @abc.abstractmethod
    def duration(self) -> float: ...

    @abc.abstractmethod
    def acceleration(self, t: np.ndarray) -> np.ndarray: ...

    @abc.abstractmethod
    def signal(self) -> Signal: ...

    def vertical_signal(self) -> Signal:
        return ZERO_SIGNAL

    def vertical_acceleration(self, t: np.ndarray) -> np.ndarray:
        return np.zeros_like(np.asarray(t, dtype=float))

    @property
    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.duration])

    @property
    def pga(self) -> float:
        """Peak |a_g| (m/s²)."""
        t = np.linspace(0.0, self.duration, 20001)
        return float(np.max(np.abs(self.acceleration(t))))
