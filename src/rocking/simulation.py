"""The one entry point: ``simulate(system, motion, ...) -> Response``."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields

import numpy as np

from .constants import STANDARD_GRAVITY
from .excitation.base import AbstractMotion, Signal, signal_breakpoints
from .models.bodies import System
from .models.parameters import pack
from .results.response import Response, split_saved_codes
from .solver.compiled import N_STATE, integrate
from .solver.signals import deferred_signals
from .solver.warmup import ensure_compiled


DEFAULT_MAX_SAMPLES = 5_000_000  # saved samples a run may hold by default (about 200 MB)


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
    free_time_limit : float
        When no duration is given, the run goes on after the floor motion ends, with the floor
        still, until every body is at rest or the statue falls, but for at most this long, s.
        A run cut short by this limit (or by an explicit duration) while anything still moves
        ends with status "still_moving": its verdict is undetermined, unless the floor motion
        is over and the statue has less energy left than it needs to overturn
        (``settled_by_energy``, docs/verdicts.md).
    stop_at_edge : bool
        Stacks only: stop a run, with status "slid_past_edge" and an undetermined verdict, when
        a sliding block's corner reaches the edge of the block below (a conservative criterion:
        a vase at its shelf's edge counts as lost). Default False: the motion is followed past
        the edge (sliding on the lower block's corner, tipping over it, falling off).
    max_samples : int
        Largest number of saved samples a run may hold (about 41 bytes each in memory, more in
        output files); a run that would need more is refused before it starts
        (:class:`ResourceLimitError`). The default, 5 million, is about 200 MB.
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
    free_time_limit: float = 60.0
    stop_at_edge: bool = False
    max_samples: int = DEFAULT_MAX_SAMPLES

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
        for name in ("max_events", "max_samples"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
                raise ValueError(f"simulation.{name} must be an integer ≥ 1, got {v!r}")
        v = self.free_time_limit
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
            raise ValueError(f"simulation.free_time_limit must be a number ≥ 0 (s), got {v!r}")
        if not isinstance(self.stop_at_edge, (bool, np.bool_)):
            raise ValueError(f"simulation.stop_at_edge must be true or false, got {self.stop_at_edge!r}")


class SimulationError(RuntimeError):
    """The solver could not finish (singular slide-rock system, step-size underflow)."""


class ResourceLimitError(ValueError):
    """A run would need more memory than ``simulation.max_samples`` allows; the message names
    the fields to change."""


# Bytes a saved sample takes in the solver's arrays: t, (u, u̇, θ, θ̇) as float64, regime int8.
SAMPLE_BYTES = 8 + 4 * 8 + 1
EVENT_BYTES = 10 * 8  # one row of the event table


def human_bytes(n: float) -> str:
    """``4.1e10`` → ``"41 GB"`` (decimal units)."""
    for unit in ("bytes", "kB", "MB", "GB", "TB", "PB"):
        if n < 1000 or unit == "PB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    raise AssertionError  # pragma: no cover


def _as_options(options: Options | Mapping) -> Options:
    if isinstance(options, Options):
        return options
    if isinstance(options, Mapping):
        known = {f.name for f in fields(Options)}
        unknown = sorted(set(map(str, options)) - known)
        if unknown:
            raise ValueError(f"options: unknown key {unknown[0]!r}; known keys: {', '.join(sorted(known))}")
        return Options(**options)
    raise TypeError(f"options must be rocking.Options or a dict of its fields, got {type(options).__name__}")


def _finite(name: str, value, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number ({unit}), got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number ({unit}), got {value!r}")
    return value


def _check_memory(t_end: float, save_dt: float, save: bool, options: Options, duration: float | None,
                  motion_duration: float) -> None:
    """Refuse, before anything is allocated, a run whose saved series or event table would not
    fit in ``options.max_samples`` samples."""
    limit = options.max_samples
    span = (f"{t_end:.6g} s" if duration is not None else
            f"{t_end:.6g} s (the motion's {motion_duration:.6g} s + simulation.free_time_limit "
            f"{options.free_time_limit:.6g} s)")
    if save:
        n = math.floor(t_end / save_dt + 1e-9) + 1
        if n > limit:
            raise ResourceLimitError(
                f"simulation.save_dt: {save_dt:.6g} s over {span} would store {n:.3g} samples "
                f"({human_bytes(n * SAMPLE_BYTES)} in memory, more in output files), over simulation.max_samples "
                f"= {limit:.3g}; raise save_dt, shorten the run, or raise simulation.max_samples (--max-samples on the "
                "command line; or simulate(..., save=False) for the summary alone)"
            )
    # The event table is reserved whole (max_events rows) whatever the series: it may take as
    # much memory as the default series would, or as the raised limit allows.
    budget = max(limit, DEFAULT_MAX_SAMPLES) * SAMPLE_BYTES
    if options.max_events * EVENT_BYTES > budget:
        raise ResourceLimitError(
            f"simulation.max_events: {options.max_events:.3g} would reserve {human_bytes(options.max_events * EVENT_BYTES)} "
            f"for the event table, more than {human_bytes(budget)} (simulation.max_samples = {limit:.3g}); lower "
            "max_events or raise max_samples"
        )


def _breakpoints(motion: AbstractMotion, t_end: float, signals: tuple[Signal, ...] = ()) -> np.ndarray:
    """The times inside (0, t_end) where a step must end (s, increasing): the motion's own list
    and every jump or kink of ``signals`` (its horizontal and vertical signals). A vertical pulse
    left out of a user's list had its end straddled by the steps: a block that a vertical lift had
    kept stuck then never slipped when it ended (2026-12-03)."""
    bp = np.asarray(motion.breakpoints, dtype=float)
    parts = [bp]
    for sig in signals:
        own = signal_breakpoints(sig)
        # a record's samples are its list already: skip the merge (a sort of 10⁴ samples)
        if own.size and not (own.shape == bp.shape and np.array_equal(own, bp)):
            parts.append(own)
    if len(parts) > 1:
        bp = np.concatenate(parts)
    bp = bp[(bp > 0.0) & (bp < t_end)]
    if bp.size > 1 and not np.all(bp[1:] > bp[:-1]):  # a record's sample times already are
        bp = np.unique(bp)
    return bp


def prepare(
    system: System,
    motion: AbstractMotion,
    *,
    duration: float | None = None,
    options: Options | Mapping = Options(),
    initial_rotation: float = 0.0,
    initial_angular_velocity: float = 0.0,
    initial_sliding_velocity: float = 0.0,
    save: bool = True,
) -> tuple[np.ndarray, tuple]:
    """Validate the inputs and pack them for the compiled solver: (parameter vector, arguments
    of :func:`rocking.solver.compiled.integrate` but the last, the stop flag). Batch runs call
    this and the solver directly.

    Without ``duration`` the run lasts the motion and then at most ``options.free_time_limit``
    more seconds, ending as soon as everything is at rest; with it, exactly ``duration``."""
    if not isinstance(system, System):
        raise TypeError(f"system must be a rocking.System, got {type(system).__name__}")
    if not isinstance(motion, AbstractMotion):
        raise TypeError(f"motion must be a floor motion, got {type(motion).__name__}")
    options = _as_options(options)
    initial_rotation = _finite("initial_rotation", initial_rotation, "rad")
    initial_angular_velocity = _finite("initial_angular_velocity", initial_angular_velocity, "rad/s")
    initial_sliding_velocity = _finite("initial_sliding_velocity", initial_sliding_velocity, "m/s")
    motion_end = float(motion.duration)
    if duration is None:
        t_end, t_settle = motion_end + float(options.free_time_limit), motion_end
    else:
        t_end = _finite("simulation.duration", duration, "s")
        t_settle = math.inf  # the user asked for this length: keep it, at rest or not
    if not t_end > 0:
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
    _check_memory(t_end, save_dt, save, options, duration, motion_end)
    y0 = np.zeros(N_STATE)
    y0[1], y0[2], y0[3] = initial_sliding_velocity, initial_rotation, initial_angular_velocity
    sig_h, sig_v = motion.signal(), motion.vertical_signal()
    args = (
        p,
        (sig_h.kind, sig_h.params, sig_h.time, sig_h.values),
        (sig_v.kind, sig_v.params, sig_v.time, sig_v.values),
        _breakpoints(motion, t_end, (sig_h, sig_v)),
        0.0,
        t_end,
        y0,
        options.rtol,
        options.atol,
        options.max_step,
        save_dt,
        save,
        int(options.max_events),
        t_settle,
    )
    return p, args


def solve(args: tuple) -> tuple:
    """Run the compiled solver on :func:`prepare`'s arguments with Ctrl-C and SIGTERM deferred
    (see :mod:`rocking.solver.signals`): an interrupt stops the run within milliseconds and is
    raised (``KeyboardInterrupt``) once the solver has returned."""
    with deferred_signals() as flag:
        return integrate(*args, flag)


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
        Simulated time, s. Default: the motion's duration, then free motion on a still floor
        until everything is at rest or the statue falls, for at most
        ``options.free_time_limit`` s. The summary's ``verdict`` says "undetermined" when the
        run ends while anything still moves, unless the statue can no longer overturn
        (``settled_by_energy``).
    options : Options or dict
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
    options = _as_options(options)
    ensure_compiled()  # a cold cache compiles for half a minute: say so (once per process)
    p, args = prepare(
        system, motion, duration=duration, options=options, initial_rotation=initial_rotation,
        initial_angular_velocity=initial_angular_velocity, initial_sliding_velocity=initial_sliding_velocity,
        save=save,
    )
    summary, t, y, saved_codes, events = solve(args)
    regime, pivot, slip = split_saved_codes(saved_codes)
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
        pivot=pivot,
        slip_direction=slip,
        event_table=events,
        duration_given=duration is not None,
    )
    if throw and response.status in ("singular", "step_failed"):
        raise SimulationError(response.status_message)
    return response
