"""Many simulations at once: a list of cases or a grid sweep, in-process or on workers.

Only summaries travel back (a few dozen numbers per run), so 100 000 runs fit in a few tens of
MB. A case is a :class:`~rocking.models.bodies.System` (the compiled two-body solver) or a
:class:`~rocking.stack.Stack` (the general stack engine, :func:`rocking.stack.simulate_stack`);
a stack's summary is packed into a flat vector (:func:`stack_raw`) so that it travels and is
saved like a system's, and unpacked into exactly :meth:`~rocking.stack.StackResponse.summary`
(:func:`stack_summary_values`). Workers follow SciPy's convention: ``workers=1`` runs in this process, an integer ``n > 1``
uses ``n`` local processes (the default is all cores), and any object with a ``map(fn, iterable)``
method (e.g. :class:`rocking.analyses.executors.DaskExecutor`) distributes the chunks. Results do
not depend on the workers: every run is the same deterministic computation.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import re
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..excitation.base import AbstractMotion
from ..models.bodies import System
from ..results.response import SUMMARY_FIELDS, summary_values
from ..simulation import Options, prepare, solve
from ..solver.compiled import N_SUMMARY
from ..stack.model import Stack
from .executors import as_executor, default_workers

Case = tuple[System | Stack, AbstractMotion]

# -- stacks: the summary as a flat vector -----------------------------------------------------
#: Layout of a stack's raw summary: these run-wide fields, then ``STACK_BLOCK_FIELDS`` of every
#: block from the floor up, then ``STACK_INTERFACE_FIELDS`` of every interface (floor first).
STACK_RUN_FIELDS = ("status", "end_time", "impacts", "energy_balance_error", "last_event_block", "settled_by_energy")
STACK_BLOCK_FIELDS = ("overturned", "overturn_time", "peak_rotation", "peak_absolute_rotation", "peak_sliding",
                      "residual_sliding", "lifted_off_time", "first_rocking_time", "first_sliding_time",
                      "tension_held_time", "past_edge_time", "restitution_reduced_time")
STACK_INTERFACE_FIELDS = ("required_friction", "slip_path", "impacts")
#: The top-level keys of a stack summary taken from its top block (StackResponse.summary).
_STACK_TOP_KEYS = ("overturned", "overturn_time", "peak_rotation", "peak_sliding", "residual_sliding",
                   "first_rocking_time", "first_sliding_time", "lifted_off_time")
_BLOCK_UNITS = {"overturn_time": "s", "peak_rotation": "rad", "peak_absolute_rotation": "rad", "peak_sliding": "m",
                "residual_sliding": "m", "lifted_off_time": "s", "first_rocking_time": "s", "first_sliding_time": "s",
                "tension_held_time": "s", "past_edge_time": "s", "restitution_reduced_time": "s"}


def stack_raw_size(n_blocks: int) -> int:
    """Length of the raw summary vector of a stack of ``n_blocks`` blocks."""
    return len(STACK_RUN_FIELDS) + n_blocks * (len(STACK_BLOCK_FIELDS) + len(STACK_INTERFACE_FIELDS))


def _number(v: Any) -> float:
    return math.nan if v is None else float(v)


def stack_raw(response: Any) -> np.ndarray:
    """The flat float vector of a :class:`StackResponse`'s summary (None → NaN, status → its
    code), with the block of its last event (which the verdict of a slide to an edge names)."""
    from ..stack.simulate import STATUS_NAMES

    summary = response.summary()
    last = float(response.events[-1, 1]) if len(response.events) else math.nan
    head = [float(STATUS_NAMES.index(summary["status"])), summary["end_time"], summary["impacts"],
            summary["energy_balance_error"], last, float(summary["settled_by_energy"])]
    blocks = [_number(b[k]) for b in summary["blocks"] for k in STACK_BLOCK_FIELDS]
    faces = [_number(f[k]) for f in summary["interfaces"] for k in STACK_INTERFACE_FIELDS]
    return np.array(head + blocks + faces, dtype=float)


def _opt_float(v: float) -> float | None:
    return None if math.isnan(v) else float(v)


def stack_summary_values(raw: np.ndarray, stack: Stack) -> dict[str, Any]:
    """The summary of one stack run (equal to :meth:`StackResponse.summary`) from its raw vector."""
    from types import SimpleNamespace

    from ..stack.simulate import STATUS_NAMES, StackResponse

    n = stack.n
    nb, nf = len(STACK_BLOCK_FIELDS), len(STACK_INTERFACE_FIELDS)
    head = len(STACK_RUN_FIELDS)
    status = STATUS_NAMES[int(raw[0])]
    below = ("floor",) + stack.names[:-1]
    blocks, faces = [], []
    for k, name in enumerate(stack.names):
        row = raw[head + k * nb : head + (k + 1) * nb]
        block: dict[str, Any] = {"name": name}
        for key, v in zip(STACK_BLOCK_FIELDS, row):
            block[key] = bool(v) if key == "overturned" else (_opt_float(v) if key.endswith("_time") else float(v))
        blocks.append(block)
        row = raw[head + n * nb + k * nf : head + n * nb + (k + 1) * nf]
        faces.append({"name": f"{below[k]}–{name}", "required_friction": float(row[0]), "slip_path": float(row[1]),
                      "impacts": int(row[2])})
    end_time = float(raw[1])
    # the verdict is the engine's own rule, applied to the unpacked blocks (and the last event's block)
    events = np.empty((0, 3)) if math.isnan(raw[4]) else np.array([[math.nan, raw[4], math.nan]])
    settled = bool(raw[5] == 1.0)
    verdict = StackResponse.verdict.fget(SimpleNamespace(blocks=blocks, status=status, end_time=end_time,
                                                         events=events, stack=stack, settled_by_energy=settled))
    out = {key: blocks[-1][key] for key in _STACK_TOP_KEYS}
    out.update(impacts=int(raw[2]), energy_balance_error=float(raw[3]), status=status, end_time=end_time,
               still_moving=status == "still_moving", settled_by_energy=settled, verdict=verdict, blocks=blocks,
               interfaces=faces)
    return out


def stack_alpha(stack: Stack) -> float:
    """α = atan(B/H) of the top block (the statue), rad: what its peak rotation is measured against."""
    top = stack.blocks[-1]
    return math.atan2(top.width, top.height)


def spec_alpha(spec: System | Stack) -> float:
    """The statue's α (rad): of a System's statue, or of a stack's top block."""
    return stack_alpha(spec) if isinstance(spec, Stack) else spec.statue.slenderness


def run_stack_raw(stack: Stack, motion: AbstractMotion, options: Options, duration: float | None = None) -> np.ndarray:
    """Raw summary vector of one stack run (see :func:`stack_raw`)."""
    from ..stack.simulate import simulate_stack

    return stack_raw(simulate_stack(stack, motion, duration=duration, options=options))


def run_spec_raw(spec: System | Stack, motion: AbstractMotion, options: Options,
                 duration: float | None = None) -> np.ndarray:
    """Raw summary vector of one run of a System (compiled solver) or a Stack (stack engine)."""
    if isinstance(spec, Stack):
        return run_stack_raw(spec, motion, options, duration)
    return run_raw(spec, motion, options, duration)


def spec_kind(spec: Any, where: str = "case") -> str:
    """"system" or "stack"; a ValueError naming ``where`` for anything else."""
    if isinstance(spec, Stack):
        return "stack"
    if isinstance(spec, System):
        return "system"
    raise ValueError(f"{where}: a run needs a rocking.System or a rocking.stack.Stack, got {type(spec).__name__}")


def pad_rows(rows: Sequence[np.ndarray]) -> np.ndarray:
    """Raw summary vectors (or blocks of them) of different lengths as one 2-D array, NaN-padded
    on the right: a system's and stacks of any size can share a batch."""
    arrays = [np.atleast_2d(np.asarray(r, dtype=float)) for r in rows]
    width = max(a.shape[1] for a in arrays)
    out = np.full((sum(a.shape[0] for a in arrays), width), np.nan)
    k = 0
    for a in arrays:
        out[k : k + a.shape[0], : a.shape[1]] = a
        k += a.shape[0]
    return out


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
    if any(isinstance(spec, Stack) for spec, _ in cases):
        return pad_rows([run_spec_raw(spec, motion, options, duration) for spec, motion in cases])
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
    cases : sequence of (System or Stack, motion)
        A :class:`rocking.stack.Stack` runs on the stack engine; its summaries describe the top
        block at the top level (as :meth:`StackResponse.summary`) and every block and interface
        along ``block`` and ``interface`` (see :func:`specs_dataset`).
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
    kinds = {spec_kind(spec, f"cases[{i}]") for i, (spec, _) in enumerate(cases)}
    if "stack" in kinds and series:
        raise ValueError("series=True records the two-body state (u, θ); a stack's histories come from "
                         "rocking.stack.simulate_stack")
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
    if "stack" in kinds:
        return specs_dataset(pad_rows(results), [c[0] for c in cases], dims=("case",), shape=(n,))
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
        data[key] = (dims, _column(key, [row[key] for row in rows]).reshape(shape))
    ds = xr.Dataset(data, coords=coords or {})
    units = {"overturn_time": "s", "exceeded_alpha_time": "s", "peak_rotation": "rad", "peak_sliding": "m",
             "residual_sliding": "m", "first_rocking_time": "s", "first_sliding_time": "s", "end_time": "s",
             "top_slip_time": "s", "pedestal_uplift_time": "s", "impact_beyond_friction_time": "s"}
    for key, unit in units.items():
        ds[key].attrs["units"] = unit
    return ds


def specs_dataset(raw: np.ndarray, specs: Sequence[System | Stack], *, dims: tuple[str, ...],
                  shape: tuple[int, ...], coords=None):
    """The summaries Dataset of a batch whose runs may be stacks (one row of ``raw`` per spec).

    Systems only: exactly :func:`summaries_dataset`. With stacks, every field of
    ``SUMMARY_FIELDS`` is there, for the top block (the statue) as in
    :meth:`StackResponse.summary` (``required_top_friction`` is the friction the interface under
    it needed; ``exceeded_alpha_time`` and ``impact_floor_friction_needed``, which the stack
    engine does not track, are NaN), plus ``lifted_off_time``; when every run is a stack with
    the same block names, also ``block_<field>`` along ``block`` (from the floor up: overturned,
    peak_rotation and peak_sliding relative to the block below, …) and ``interface_<field>``
    along ``interface`` (required_friction, slip_path in m, impacts).
    """
    import xarray as xr

    specs = list(specs)
    if not any(isinstance(s, Stack) for s in specs):
        return summaries_dataset(raw, np.array([s.statue.slenderness for s in specs]), dims=dims, shape=shape,
                                 coords=coords)
    rows = []
    for r, spec in zip(raw, specs):
        if isinstance(spec, Stack):
            rows.append(stack_summary_values(r, spec))
        else:
            rows.append(summary_values(r, spec.statue.slenderness))
    alphas = [spec_alpha(s) for s in specs]
    data = {}
    for key in SUMMARY_FIELDS + ("lifted_off_time",):
        values = []
        for row, spec, alpha in zip(rows, specs, alphas):
            if key == "peak_rotation_over_alpha" and isinstance(spec, Stack):
                values.append(row["peak_rotation"] / alpha)
            elif key == "required_top_friction" and isinstance(spec, Stack):
                values.append(row["interfaces"][-1]["required_friction"])
            else:
                values.append(row.get(key))
        data[key] = (dims, _column(key, values).reshape(shape))
    same = all(isinstance(s, Stack) and s.names == specs[0].names for s in specs)
    if same:
        stack0 = specs[0]
        for key in STACK_BLOCK_FIELDS:
            arr = _column(key, [[b[key] for b in row["blocks"]] for row in rows])
            data[f"block_{key}"] = (dims + ("block",), arr.reshape(shape + (stack0.n,)),
                                    {"units": _BLOCK_UNITS[key]} if key in _BLOCK_UNITS else {})
        for key in STACK_INTERFACE_FIELDS:
            arr = _column(key, [[f[key] for f in row["interfaces"]] for row in rows])
            data[f"interface_{key}"] = (dims + ("interface",), arr.reshape(shape + (stack0.n,)),
                                        {"units": "m"} if key == "slip_path" else {})
        coords = {**(coords or {}), "block": list(stack0.names),
                  "interface": [f["name"] for f in rows[0]["interfaces"]]}
    ds = xr.Dataset(data, coords=coords or {})
    units = {"overturn_time": "s", "exceeded_alpha_time": "s", "peak_rotation": "rad", "peak_sliding": "m",
             "residual_sliding": "m", "first_rocking_time": "s", "first_sliding_time": "s", "end_time": "s",
             "lifted_off_time": "s"}
    for key, unit in units.items():
        ds[key].attrs["units"] = unit
    return ds


def _column(key: str, values: list) -> np.ndarray:
    """One summary field of many runs as an array of its type (None → NaN for numbers)."""
    if key in ("overturned", "still_moving", "settled_by_energy"):
        return np.array(values, dtype=bool)
    if key == "impacts":
        return np.array(values, dtype=np.int64)
    if key in ("status", "verdict"):
        return np.array(values, dtype=str)
    arr = np.array(values, dtype=object)
    return np.where(arr == None, np.nan, arr).astype(float)  # noqa: E711 - elementwise test for None


# -- sweeps over named parameters --------------------------------------------------------------
_INDEXED = re.compile(r"^(\w+)\[(\d+)\]$")


def replace_at(obj: Any, path: str, value: Any, _full: str | None = None) -> Any:
    """A copy of a nested frozen dataclass with the field at dotted ``path`` replaced
    (e.g. ``"pedestal.friction.static"``). A tuple field takes an index (``"blocks[1].mass"``,
    ``"interfaces[0].friction.static"``), and in a :class:`~rocking.stack.Stack` a block's name
    stands for its entry in ``blocks`` (``"statue.height"``)."""
    full = path if _full is None else _full
    head, _, rest = path.partition(".")
    if isinstance(obj, Stack) and head in obj.names and head not in ("blocks", "interfaces"):
        head = f"blocks[{obj.names.index(head)}]"
    indexed = _INDEXED.match(head)
    field, index = (indexed.group(1), int(indexed.group(2))) if indexed else (head, None)
    if not dataclasses.is_dataclass(obj) or field not in {f.name for f in dataclasses.fields(obj)}:
        raise ValueError(f"unknown sweep axis {full!r}: {type(obj).__name__} has no field {field!r}")
    if index is None:
        if not rest:
            return dataclasses.replace(obj, **{field: value})
        return dataclasses.replace(obj, **{field: replace_at(getattr(obj, field), rest, value, full)})
    items = getattr(obj, field)
    if not isinstance(items, tuple) or not 0 <= index < len(items):
        raise ValueError(f"unknown sweep axis {full!r}: {type(obj).__name__}.{field} has no entry {index}")
    item = value if not rest else replace_at(items[index], rest, value, full)
    return dataclasses.replace(obj, **{field: items[:index] + (item,) + items[index + 1 :]})


def _apply(system: System | Stack, motion: AbstractMotion, axis: str, value: float) -> Case:
    if axis == "pga":
        if hasattr(motion, "scaled"):
            return system, motion.scaled(pga=value)
        return system, replace_at(motion, "amplitude", math.copysign(value, getattr(motion, "amplitude", 1.0) or 1.0))
    if axis == "scale":
        return system, motion.scaled(factor=value)
    if axis.startswith("motion."):
        return system, replace_at(motion, axis[len("motion."):], value)
    if axis.endswith("friction.ratio"):  # μk/μs of that friction
        where = axis[: -len(".ratio")]
        f = _get_at(system, where)
        return replace_at(system, f"{where}.kinetic", value * f.static), motion
    return replace_at(system, axis, value), motion


def _get_at(obj: Any, path: str) -> Any:
    """The value at a dotted ``path`` of :func:`replace_at`."""
    for head in path.split("."):
        if isinstance(obj, Stack) and head in obj.names:
            head = f"blocks[{obj.names.index(head)}]"
        indexed = _INDEXED.match(head)
        obj = getattr(obj, indexed.group(1))[int(indexed.group(2))] if indexed else getattr(obj, head)
    return obj


def sweep(
    system: System | Stack,
    motion: AbstractMotion,
    axes: dict[str, Sequence[float]],
    *,
    options: Options = Options(),
    duration: float | None = None,
    workers: int | Any | None = None,
    progress: Callable[[int, int], None] | None = None,
    series: bool = False,
):
    """Run the Cartesian product of ``axes`` and return a Dataset with one dimension per axis
    (plus ``time`` for the state histories when ``series`` is True; see :func:`run_cases`).

    An axis is a dotted path into the system or stack (see :func:`replace_at`, e.g.
    ``"statue.height"``, ``"interfaces[1].friction.static"``), ``<…>.friction.ratio`` (μk/μs of
    that friction), ``motion.<field>``, ``"pga"`` or ``"scale"``. A stack's summaries keep their
    ``block`` and ``interface`` dimensions after the axes.

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
        coords={**{k: g for k, g in zip(names, grids)},
                **{c: ds[c] for c in ds.coords if "case" not in ds[c].dims}},
    )
    return out
