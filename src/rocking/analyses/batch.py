"""Many simulations at once: a list of cases or a grid sweep, in-process or on workers.

Only summaries travel back (a few dozen numbers per run), so 100 000 runs fit in a few tens of
MB. Workers follow SciPy's convention: ``workers=1`` runs in this process, an integer ``n > 1``
uses ``n`` local processes (the default is all cores), and any object with a ``map(fn, iterable)``
method (e.g. :class:`rocking.analyses.executors.DaskExecutor`) distributes the chunks. Results do
not depend on the workers: every run is the same deterministic computation.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..excitation.base import AbstractMotion
from ..models.bodies import System
from ..results.response import SUMMARY_FIELDS, summary_values
from ..simulation import Options, prepare, solve
from ..solver.compiled import N_SUMMARY
from .executors import as_executor, default_workers

Case = tuple[System, AbstractMotion]


def run_raw(system: System, motion: AbstractMotion, options: Options, duration: float | None = None) -> np.ndarray:
    """Raw summary vector of one run (no time series)."""
    _, args = prepare(system, motion, duration=duration, options=options, save=False)
    return solve(args)[0]


def run_series(
    system: System, motion: AbstractMotion, options: Options, duration: float | None, dt: float
) -> tuple[np.ndarray, np.ndarray]:
    """Raw summary vector and the state (u, u̇, θ, θ̇) at t = k·dt (rows k = 0, 1, …, up to the end
    of the run: an overturned run stops there)."""
    options = dataclasses.replace(options, save_dt=dt)
    _, args = prepare(system, motion, duration=duration, options=options, save=True)
    summary, t, y, _, _ = solve(args)
    k = np.rint(t / dt)
    on_grid = np.flatnonzero(t == k * dt)  # the rows at event instants are off the grid
    # An event exactly on a grid time adds rows there: keep the first (the state before it).
    _, first = np.unique(k[on_grid], return_index=True)
    return summary, y[on_grid[first]]


def _run_chunk(payload):
    cases, options, duration, series_dt = payload
    out = np.empty((len(cases), N_SUMMARY))
    if series_dt is None:
        for i, (system, motion) in enumerate(cases):
            out[i] = run_raw(system, motion, options, duration)
        return out
    states = []
    for i, (system, motion) in enumerate(cases):
        out[i], state = run_series(system, motion, options, duration, series_dt)
        states.append(state)
    return out, states


def _chunks(cases: Sequence[Case], size: int) -> list[Sequence[Case]]:
    return [cases[i : i + size] for i in range(0, len(cases), size)]


def map_chunks(
    fn: Callable[[Any], np.ndarray],
    payloads: list[Any],
    workers: int | Any | None,
    progress: Callable[[int], None] | None = None,
) -> list[np.ndarray]:
    """Apply ``fn`` to every payload on the chosen workers (see :func:`executors.as_executor`),
    in order; ``progress(n_done_payloads)`` after each."""
    results: list[np.ndarray] = []
    for r in as_executor(workers).map(fn, payloads):
        results.append(r)
        if progress is not None:
            progress(len(results))
    return results


def run_cases(
    cases: Sequence[Case],
    *,
    options: Options = Options(),
    duration: float | None = None,
    workers: int | Any | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    series: bool = False,
):
    """Run every (system, motion) case and return an ``xarray.Dataset`` of summaries along ``case``
    (and, with ``series=True``, the time histories too).

    Parameters
    ----------
    cases : sequence of (System, motion)
    options : Options
        Shared by all runs.
    duration : float, optional
        Simulated time (s); default each motion's duration.
    workers : int or executor, optional
        1: in this process; n > 1: local processes (default: all cores); or an object with ``map``.
    chunk_size : int, optional
        Runs per task (default: enough for ~4 tasks per worker).
    progress : callable, optional
        ``progress(done, total)`` after each chunk.
    series : bool
        Also return the state histories ``u`` (m), ``u_dot`` (m/s), ``theta`` (rad) and
        ``theta_dot`` (rad/s) along (``case``, ``time``), sampled every ``options.save_dt``
        (default 0.01 s) from 0 to the longest run; NaN after a run ends (overturned, or a
        shorter motion). Off by default: summaries alone keep 100 000 runs in a few tens of MB.

    Examples
    --------
    >>> import rocking as rk
    >>> from rocking.analyses.batch import run_cases
    >>> st = rk.Statue(width=1.0, height=4.0, mass=1.0)
    >>> ds = run_cases([(rk.System(statue=st), rk.Harmonic(amplitude=a, frequency=1.2, cycles=3)) for a in (2.0, 8.0)], workers=1)
    >>> ds.overturned.values.tolist(), int(ds.impacts[0])
    ([False, True], 0)
    """
    cases = list(cases)
    n = len(cases)
    if n == 0:
        raise ValueError("run_cases needs at least one case")
    nw = 1 if workers is None and n < 64 else workers
    if chunk_size is None:
        per = default_workers() if nw is None else (int(nw) if not hasattr(nw, "map") else 8)
        chunk_size = max(1, min(2000, math.ceil(n / (4 * max(1, per)))))
    chunks = _chunks(cases, chunk_size)
    series_dt = (options.save_dt or 0.01) if series else None
    payloads = [(c, options, duration, series_dt) for c in chunks]
    done_runs = np.cumsum([len(c) for c in chunks])
    report = (lambda k: progress(int(done_runs[k - 1]), n)) if progress else None
    results = map_chunks(_run_chunk, payloads, nw, report)
    alphas = np.array([system.statue.slenderness for system, _ in cases])
    if not series:
        return summaries_dataset(np.concatenate(results, axis=0), alphas, dims=("case",), shape=(n,))
    raw = np.concatenate([r[0] for r in results], axis=0)
    ds = summaries_dataset(raw, alphas, dims=("case",), shape=(n,))
    return ds.assign(_series_variables([state for r in results for state in r[1]], series_dt))


def _series_variables(states: list[np.ndarray], dt: float) -> dict:
    """The state histories padded with NaN to a common time axis, as Dataset variables."""
    import xarray as xr

    n_time = max(len(s) for s in states)
    padded = np.full((len(states), n_time, 4), np.nan)
    for i, s in enumerate(states):
        padded[i, : len(s)] = s
    time = xr.DataArray(np.arange(n_time) * dt, dims="time", attrs={"units": "s"})
    names = (("u", "m"), ("u_dot", "m/s"), ("theta", "rad"), ("theta_dot", "rad/s"))
    return {
        name: xr.DataArray(padded[:, :, j], dims=("case", "time"), coords={"time": time}, attrs={"units": unit})
        for j, (name, unit) in enumerate(names)
    }


def summaries_dataset(raw: np.ndarray, alphas: np.ndarray, *, dims: tuple[str, ...], shape: tuple[int, ...], coords=None):
    """An ``xarray.Dataset`` with one variable per summary field, shaped ``shape`` along ``dims``."""
    import xarray as xr

    rows = [summary_values(r, a) for r, a in zip(raw, alphas)]
    data = {}
    for key in SUMMARY_FIELDS:
        values = [row[key] for row in rows]
        if key in ("overturned", "still_moving"):
            arr = np.array(values, dtype=bool)
        elif key == "impacts":
            arr = np.array(values, dtype=np.int64)
        elif key in ("status", "verdict"):
            arr = np.array(values, dtype=str)
        else:
            arr = np.array([np.nan if v is None else v for v in values], dtype=float)
        data[key] = (dims, arr.reshape(shape))
    ds = xr.Dataset(data, coords=coords or {})
    units = {"overturn_time": "s", "exceeded_alpha_time": "s", "peak_rotation": "rad", "peak_sliding": "m",
             "residual_sliding": "m", "first_rocking_time": "s", "first_sliding_time": "s", "end_time": "s"}
    for key, unit in units.items():
        ds[key].attrs["units"] = unit
    return ds


# -- sweeps over named parameters --------------------------------------------------------------
def replace_at(obj: Any, path: str, value: Any, _full: str | None = None) -> Any:
    """A copy of a nested frozen dataclass with the field at dotted ``path`` replaced
    (e.g. ``"pedestal.friction.static"``)."""
    full = path if _full is None else _full
    head, _, rest = path.partition(".")
    if not dataclasses.is_dataclass(obj) or head not in {f.name for f in dataclasses.fields(obj)}:
        raise ValueError(f"unknown sweep axis {full!r}: {type(obj).__name__} has no field {head!r}")
    if not rest:
        return dataclasses.replace(obj, **{head: value})
    return dataclasses.replace(obj, **{head: replace_at(getattr(obj, head), rest, value, full)})


def _apply(system: System, motion: AbstractMotion, axis: str, value: float) -> Case:
    if axis == "pga":
        if hasattr(motion, "scaled"):
            return system, motion.scaled(pga=value)
        return system, replace_at(motion, "amplitude", math.copysign(value, getattr(motion, "amplitude", 1.0) or 1.0))
    if axis == "scale":
        return system, motion.scaled(factor=value)
    if axis.startswith("motion."):
        return system, replace_at(motion, axis[len("motion."):], value)
    if axis == "pedestal.friction.ratio":  # μk/μs
        f = system.pedestal.friction
        return replace_at(system, "pedestal.friction.kinetic", value * f.static), motion
    return replace_at(system, axis, value), motion


def sweep(
    system: System,
    motion: AbstractMotion,
    axes: dict[str, Sequence[float]],
    *,
    options: Options = Options(),
    duration: float | None = None,
    workers: int | Any | None = None,
    progress: Callable[[int, int], None] | None = None,
    series: bool = False,
):
    """Run the Cartesian product of ``axes`` (dotted paths into the system, ``motion.<field>``,
    ``"pga"`` or ``"scale"``) and return a Dataset with one dimension per axis (plus ``time``
    for the state histories when ``series`` is True; see :func:`run_cases`).

    Examples
    --------
    >>> import rocking as rk
    >>> from rocking.analyses.batch import sweep
    >>> st = rk.Statue(width=1.0, height=4.0, mass=1.0)
    >>> ds = sweep(rk.System(statue=st), rk.Harmonic(amplitude=1.0, frequency=1.2, cycles=3),
    ...            {"motion.amplitude": [2.0, 8.0], "statue.height": [4.0, 8.0]}, workers=1)
    >>> ds.overturned.dims
    ('motion.amplitude', 'statue.height')
    """
    names = list(axes)
    grids = [np.asarray(axes[k], dtype=float) for k in names]
    cases = []
    for values in itertools.product(*grids):
        sysm, mot = system, motion
        for axis, value in zip(names, values):
            sysm, mot = _apply(sysm, mot, axis, float(value))
        cases.append((sysm, mot))
    ds = run_cases(cases, options=options, duration=duration, workers=workers, progress=progress, series=series)
    shape = tuple(len(g) for g in grids)
    import xarray as xr

    # "case" unfolds into one dimension per axis; a trailing "time" (series) stays.
    out = xr.Dataset(
        {k: (tuple(names) + ds[k].dims[1:], ds[k].values.reshape(shape + ds[k].shape[1:]), ds[k].attrs)
         for k in ds.data_vars},
        coords={**{k: g for k, g in zip(names, grids)}, **({"time": ds.time} if series else {})},
    )
    return out
