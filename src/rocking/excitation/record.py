"""Recorded floor motions: a sampled horizontal accelerogram (and optional vertical one).

The motion is piecewise linear between samples and zero outside ``[time[0], time[-1]]``,
which is exactly what the compiled evaluator does for ``KIND_SAMPLED``, so the NumPy and
compiled versions agree sample for sample.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType
from typing import Any

import numpy as np

from rocking.excitation.base import (
    KIND_SAMPLED,
    N_PARAMS,
    ZERO_SIGNAL,
    AbstractMotion,
    Signal,
)

__all__ = ["GroundMotion"]


def _as_samples(name: str, x: Any) -> np.ndarray:
    """Return a read-only float64 copy of ``x`` after checking it is 1-D and finite."""
    try:
        arr = np.array(x, dtype=np.float64)  # a copy: later changes to x cannot leak in
    except (TypeError, ValueError) as exc:
        raise ValueError(f"GroundMotion.{name}: cannot convert to float array ({exc})") from None
    if arr.ndim != 1:
        raise ValueError(f"GroundMotion.{name} must be 1-D, got shape {arr.shape}")
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"GroundMotion.{name}[{i}] is {float(arr[i])!r}; every sample must be finite "
            f"({bad.size} non-finite sample(s) in total)"
        )
    arr.setflags(write=False)  # frozen dataclass: make the arrays immutable too
    return arr


@dataclass(frozen=True, eq=False)
class GroundMotion(AbstractMotion):
    """A recorded horizontal floor acceleration history.

    The acceleration is linear between samples and zero before ``time[0]`` and after
    ``time[-1]``.

    Parameters
    ----------
    time : numpy.ndarray
        Sample times (s), strictly increasing and finite, at least 2 samples.
    values : numpy.ndarray
        Horizontal acceleration (m/s², +x) at ``time``; finite.
    name : str, optional
        Human-readable label, e.g. the record file stem.
    source : str, optional
        Where the record came from (a file path), for provenance.
    units : str, optional
        Units the record was stored in *before* conversion to m/s² (provenance only:
        ``values`` are always m/s²).
    meta : mapping, optional
        Free-form metadata (header fields, scale factors…). Stored as a read-only
        mapping; not used in comparisons.
    vertical : numpy.ndarray or None, optional
        Vertical acceleration (m/s², upwards) on the same time base, or None.

    Notes
    -----
    Equality and hashing are by identity (``eq=False``): the generated value equality
    of a dataclass would compare NumPy arrays element-wise and fail, and arrays are
    not hashable.
    """

    time: np.ndarray
    values: np.ndarray
    name: str = ""
    source: str = ""
    units: str = "m/s2"
    meta: Mapping[str, Any] = field(default_factory=dict, compare=False, repr=False)
    vertical: np.ndarray | None = None

    def __post_init__(self) -> None:
        time = _as_samples("time", self.time)
        values = _as_samples("values", self.values)
        if time.size < 2:
            raise ValueError(f"GroundMotion.time needs at least 2 samples, got {time.size}")
        if values.size != time.size:
            raise ValueError(
                f"GroundMotion.values has {values.size} samples but time has {time.size}"
            )
        steps = np.diff(time)
        bad = np.flatnonzero(steps <= 0.0)
        if bad.size:
            i = int(bad[0]) + 1
            raise ValueError(
                f"GroundMotion.time must be strictly increasing: time[{i}] = {float(time[i])!r} "
                f"<= time[{i - 1}] = {float(time[i - 1])!r}"
            )
        vertical = None
        if self.vertical is not None:
            vertical = _as_samples("vertical", self.vertical)
            if vertical.size != time.size:
                raise ValueError(
                    f"GroundMotion.vertical has {vertical.size} samples but time has "
                    f"{time.size}"
                )
        meta = self.meta
        if not isinstance(meta, Mapping):
            try:
                meta = dict(meta)  # a tuple of (key, value) pairs
            except (TypeError, ValueError) as exc:
                raise ValueError(
                    f"GroundMotion.meta must be a mapping or (key, value) pairs, got "
                    f"{type(self.meta).__name__} ({exc})"
                ) from None
        # frozen dataclass: fields can only be replaced through object.__setattr__
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "vertical", vertical)
        object.__setattr__(self, "meta", MappingProxyType(dict(meta)))

    def __reduce__(self):
        # A read-only mapping does not pickle: rebuild from plain values, so motions can go to
        # worker processes and Dask clusters.
        return (
            _rebuild,
            (self.time, self.values, self.name, self.source, self.units, dict(self.meta), self.vertical),
        )

    # ----------------------------------------------------------------- construction
    @classmethod
    def from_arrays(
        cls, time: Iterable[float], values: Iterable[float], **kw: Any
    ) -> GroundMotion:
        """Build a motion from array-likes.

        Parameters
        ----------
        time : array_like
            Sample times (s).
        values : array_like
            Horizontal acceleration (m/s²).
        **kw
            Any other field (``name``, ``source``, ``units``, ``meta``, ``vertical``).
        """
        # __post_init__ converts and validates, with messages that name the field
        return cls(time=time, values=values, **kw)  # type: ignore[arg-type]

    # ------------------------------------------------------------------- properties
    @property
    def n(self) -> int:
        """Number of samples."""
        return int(self.time.size)

    @cached_property  # the arrays are read-only, so the median never changes
    def dt(self) -> float:
        """Median sampling interval (s), rounded to 12 significant digits.

        The median is robust to a few odd steps in the time column. Sample times are
        usually ``i*dt`` rounded to double precision, so their differences carry noise
        of order 1e-14·t (0.005 comes out as 0.004999999999999893); 12 digits remove it
        and still resolve any interval a real record states.
        """
        return float(f"{np.median(np.diff(self.time)):.12g}")

    @property
    def duration(self) -> float:
        """Time of the last sample (s); the floor is at rest afterwards."""
        return float(self.time[-1])

    @property
    def pga(self) -> float:
        """Peak ground acceleration max |a_g| over the samples (m/s²).

        Exact for a piecewise-linear signal: its extrema are at the samples.
        """
        return float(np.max(np.abs(self.values)))

    @property
    def pgv(self) -> float:
        """Peak |v_g| (m/s) of the trapezoid-integrated velocity, starting from rest.

        No baseline correction is applied, so for an unprocessed record this can be
        dominated by drift.
        """
        return float(np.max(np.abs(self._velocity())))

    @property
    def breakpoints(self) -> np.ndarray:
        """The sample times (s): a_g has a kink at each one."""
        return self.time

    def _velocity(self) -> np.ndarray:
        increments = 0.5 * (self.values[1:] + self.values[:-1]) * np.diff(self.time)
        return np.concatenate(([0.0], np.cumsum(increments)))

    # ------------------------------------------------------------------- evaluation
    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """Horizontal acceleration (m/s²) at times ``t`` (s); zero outside the record."""
        return np.interp(np.asarray(t, dtype=float), self.time, self.values, left=0.0, right=0.0)

    def vertical_acceleration(self, t: np.ndarray) -> np.ndarray:
        """Vertical acceleration (m/s², up) at times ``t`` (s); zero if there is none."""
        t = np.asarray(t, dtype=float)
        if self.vertical is None:
            return np.zeros_like(t)
        return np.interp(t, self.time, self.vertical, left=0.0, right=0.0)

    def signal(self) -> Signal:
        """The horizontal history as a ``KIND_SAMPLED`` signal.

        Returns fresh writable contiguous float64 copies: the stored arrays are
        read-only, and a compiled core would otherwise see (and compile for) a
        separate read-only array type.
        """
        return Signal(
            KIND_SAMPLED,
            self._window_params(),
            np.ascontiguousarray(self.time, dtype=np.float64).copy(),
            np.ascontiguousarray(self.values, dtype=np.float64).copy(),
        )

    def _window_params(self) -> np.ndarray:
        """A sampled signal's params: params[3] = inf for a record cut by :meth:`trimmed`, whose
        floor goes on after its last sample in the real record (no claim may rest on it stopping
        there: :func:`rocking.excitation.signal.signal_end`), else 0."""
        params = np.zeros(N_PARAMS)
        if "trimmed_at" in self.meta:
            params[3] = math.inf
        return params

    def vertical_signal(self) -> Signal:
        """The vertical history as a ``KIND_SAMPLED`` signal, or ``ZERO_SIGNAL``."""
        if self.vertical is None:
            return ZERO_SIGNAL
        return Signal(
            KIND_SAMPLED,
            self._window_params(),
            np.ascontiguousarray(self.time, dtype=np.float64).copy(),
            np.ascontiguousarray(self.vertical, dtype=np.float64).copy(),
        )

    # ------------------------------------------------------------------ derivations
    def scaled(self, factor: float | None = None, *, pga: float | None = None) -> GroundMotion:
        """Return a copy with both components multiplied by one factor.

        Parameters
        ----------
        factor : float, optional
            Positive multiplier (dimensionless).
        pga : float, optional
            Target horizontal PGA (m/s²); the factor is ``pga / self.pga``.
            Give exactly one of ``factor`` and ``pga``.

        Returns
        -------
        GroundMotion
            The scaled motion; with ``pga=`` its ``pga`` equals the target exactly.
        """
        if (factor is None) == (pga is None):
            raise ValueError("GroundMotion.scaled: give exactly one of factor= or pga=")
        label, given = ("factor", factor) if factor is not None else ("pga", pga)
        try:
            number = float(given) if not isinstance(given, bool) else math.nan
        except (TypeError, ValueError):
            number = math.nan
        if not (math.isfinite(number) and number > 0.0):
            raise ValueError(
                f"GroundMotion.scaled: {label} must be positive and finite, got {given!r}"
            )
        if pga is None:
            factor = number
        else:
            if self.pga == 0.0:
                raise ValueError(
                    f"GroundMotion.scaled: cannot scale {self.name or 'the record'!r} to a "
                    "target PGA because it is identically zero"
                )
            factor = number / self.pga
        values = self.values * factor
        if pga is not None:
            # The product can miss the target by an ulp. Scaling is monotone, so the
            # peak sample stays the peak: pin it (and any rounded-up ties) to ±pga.
            k = int(np.argmax(np.abs(values)))
            values = np.clip(values, -number, number)
            values[k] = math.copysign(number, values[k])
        vertical = None if self.vertical is None else self.vertical * factor
        meta = dict(self.meta)
        meta["scale_factor"] = meta.get("scale_factor", 1.0) * factor
        return GroundMotion(self.time, values, self.name, self.source, self.units, meta, vertical)

    def trimmed(self, t_end: float) -> GroundMotion:
        """Return the motion cut at ``t_end`` (s), unchanged on ``[time[0], t_end]``.

        If ``t_end`` falls between two samples, a sample interpolated at ``t_end`` is
        added so the history up to the cut is preserved exactly. The cut record is a window of
        this one (``meta["trimmed_at"]``): a run still moving after it is not decided by its
        energy, since in the real record the floor goes on (docs/verdicts.md).
        """
        t_end = float(t_end)
        if not math.isfinite(t_end) or t_end <= self.time[0]:
            raise ValueError(
                f"GroundMotion.trimmed: t_end must be finite and > time[0] = "
                f"{float(self.time[0])!r}, got {t_end!r}"
            )
        if t_end >= self.time[-1]:
            return self
        keep = int(np.searchsorted(self.time, t_end, side="right"))  # samples with time <= t_end
        time = self.time[:keep]
        values = self.values[:keep]
        vertical = None if self.vertical is None else self.vertical[:keep]
        if time[-1] < t_end:
            time = np.append(time, t_end)
            values = np.append(values, np.interp(t_end, self.time, self.values))
            if vertical is not None:
                vertical = np.append(vertical, np.interp(t_end, self.time, self.vertical))
        meta = dict(self.meta)
        meta["trimmed_at"] = t_end
        return GroundMotion(time, values, self.name, self.source, self.units, meta, vertical)

    def __repr__(self) -> str:
        # The generated repr would print up to 2x1000 samples and the whole header.
        return (
            f"GroundMotion(name={self.name!r}, n={self.n}, dt={self.dt:.6g} s, "
            f"duration={self.duration:.6g} s, pga={self.pga:.6g} m/s², "
            f"vertical={'yes' if self.vertical is not None else 'no'})"
        )


def _rebuild(time, values, name, source, units, meta, vertical):
    """Unpickle a :class:`GroundMotion` (see ``GroundMotion.__reduce__``)."""
    return GroundMotion(time=time, values=values, name=name, source=source, units=units, meta=meta, vertical=vertical)
