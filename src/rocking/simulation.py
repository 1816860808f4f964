"""The one entry point: ``simulate(system, motion, ...) -> Response``."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .constants import STANDARD_GRAVITY
from .excitation.base import AbstractMotion
from .models.bodies import System
from .models.parameters import pack
from .results.response import Response
from .solver.compiled import N_STATE, integrate


@dataclass(frozen=True, kw_only=True, slots=True)
class Options:
    """Model and solver options (the config's ``[simulation]`` table).

    Parameters
    ----------
    gravity : float
        g, m/s².
    normal_force : {"full", "paper"}
        Floor normal force used by the friction law: the full N = M(g + a_v) + m2 R(S sin φ θ̈ − cos φ θ̇²)
        (default) or the paper's N = M g (its Eq. 18 without the stray factor, P1).
    impact : {"coulomb", "paper"}
        Impact law at θ = 0 (see :mod:`rocking.contact.impact`): angular momentum about the new
        pivot with a Coulomb-bounded floor impulse (default), or the paper's θ̇⁺ = r θ̇⁻ with the
        pedestal velocity unchanged (Eq. 1).
    rtol, atol : float
        Tolerances of the Runge–Kutta error control (relative; absolute in m, rad, m/s, rad/s).
    max_step : float
        Largest step, s.
    rest_velocity : float
        |θ̇⁺| below which an impact leaves the statue at rest, rad/s (stops Zeno sequences).
    save_dt : float, optional
        Spacing of the saved time series, s (default: the record's time step, or 0.01 s).
    max_events : int
        Stop with status "max_events" after this many events.
    """

    gravity: float = STANDARD_GRAVITY
    normal_force: str = "full"
    impact: str = "coulomb"
    rtol: float = 1e-10
    atol: float = 1e-12
    max_step: float = 0.1
    rest_velocity: float = 1e-6
    save_dt: float | None = None
    max_events: int = 100_000

    def __post_init__(self):
        if self.normal_force not in ("full", "paper"):
            raise ValueError(f"simulation.normal_force must be 'full' or 'paper', got {self.normal_force!r}")
        if self.impact not in ("coulomb", "paper"):
            raise ValueError(f"simulation.impact must be 'coulomb' or 'paper', got {self.impact!r}")
        for name in ("gravity", "rtol", "atol", "max_step", "rest_velocity"):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"simulation.{name} must be a positive number, got {v!r}")
        if self.save_dt is not None and (not math.isfinite(self.save_dt) or self.save_dt <= 0):
            raise ValueError(f"simulation.save_dt must be a positive number, got {self.save_dt!r}")
        if int(self.max_events) < 1:
            raise ValueError(f"simulation.max_events must be ≥ 1, got {self.max_events!r}")


class SimulationError(RuntimeError):
    """The solver could not finish (singular slide-rock system, step-size underflow)."""


def _breakpoints(motion: AbstractMotion, t_end: float) -> np.ndarray:
    bp = np.asarray(motion.breakpoints, dtype=float)
    bp = bp[(bp > 0.0) & (bp < t_end)]
    if bp.size > 1 and not np.all(bp[1:] > bp[:-1]):  # a record's sample times already are
        bp = np.unique(bp)
    return bp


def prepare(
    system: System,
    motion: AbstractMotion,
    *,
    duration: float | None = None,
    options: Options = Options(),
    initial_rotation: float = 0.0,
    initial_angular_velocity: float = 0.0,
    initial_sliding_velocity: float = 0.0,
    save: bool = True,
) -> tuple[np.ndarray, tuple]:
    """Validate the inputs and pack them for the compiled solver: (parameter vector, arguments
    of :func:`rocking.solver.compiled.integrate`). Batch runs call this and the solver directly."""
    if not isinstance(system, System):
        raise TypeError(f"system must be a rocking.System, got {type(system).__name__}")
    if not isinstance(motion, AbstractMotion):
        raise TypeError(f"motion must be a floor motion, got {type(motion).__name__}")
    t_end = motion.duration if duration is None else float(duration)
    if not math.isfinite(t_end) or t_end <= 0:
        raise ValueError(f"simulation.duration must be a positive number, got {duration!r}")
    if abs(initial_rotation) >= 0.5 * math.pi:
        raise ValueError(f"initial_rotation must satisfy |θ0| < π/2, got {initial_rotation!r}")
    p = pack(
        system,
        gravity=options.gravity,
        normal_force=options.normal_force,
        impact=options.impact,
        rest_velocity=options.rest_velocity,
    )
    save_dt = options.save_dt
    if save_dt is None:
        dt = getattr(motion, "dt", None)
        save_dt = float(dt) if dt else 0.01
    y0 = np.zeros(N_STATE)
    y0[1], y0[2], y0[3] = initial_sliding_velocity, initial_rotation, initial_angular_velocity
    sig_h, sig_v = motion.signal(), motion.vertical_signal()
    args = (
        p,
        (sig_h.kind, sig_h.params, sig_h.time, sig_h.values),
        (sig_v.kind, sig_v.params, sig_v.time, sig_v.values),
        _breakpoints(motion, t_end),
        0.0,
        t_end,
        y0,
        options.rtol,
        options.atol,
        options.max_step,
        save_dt,
        save,
        int(options.max_events),
    )
    return p, args


def simulate(
    system: System,
    motion: AbstractMotion,
    *,
    duration: float | None = None,
    options: Options = Options(),
    initial_rotation: float = 0.0,
    initial_angular_velocity: float = 0.0,
    initial_sliding_velocity: float = 0.0,
    save: bool = True,
    throw: bool = True,
) -> Response:
    """Simulate a statue (alone or on a pedestal) on a shaking floor.

    Parameters
    ----------
    system : System
        What stands on the floor.
    motion : AbstractMotion
        The floor motion (Harmonic, a pulse, or a recorded GroundMotion).
    duration : float, optional
        Simulated time, s; default: the motion's duration.
    options : Options
        Model options and solver tolerances.
    initial_rotation, initial_angular_velocity : float
        θ(0), rad, and θ̇(0), rad/s (free-rocking studies).
    initial_sliding_velocity : float
        u̇(0) of the sliding body relative to the floor, m/s.
    save : bool
        Keep the time series (False: only the summary and events, for batch runs).
    throw : bool
        Raise :class:`SimulationError` if the solver fails (else return with ``status`` set).

    Returns
    -------
    Response

    Examples
    --------
    >>> import rocking as rk
    >>> statue = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
    >>> r = rk.simulate(rk.System(statue=statue), rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30))
    >>> r.summary()["overturned"]
    True
    """
    p, args = prepare(
        system, motion, duration=duration, options=options, initial_rotation=initial_rotation,
        initial_angular_velocity=initial_angular_velocity, initial_sliding_velocity=initial_sliding_velocity,
        save=save,
    )
    summary, t, y, regime, events = integrate(*args)
    t_end = args[5]
    response = Response(
        system=system,
        motion=motion,
        options=options,
        duration=t_end,
        parameters=p,
        raw_summary=summary,
        t=t,
        state=y,
        regime_codes=regime,
        event_table=events,
    )
    if throw and response.status in ("singular", "step_failed"):
        raise SimulationError(response.status_message)
    return response
