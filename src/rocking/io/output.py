"""Write a run's results to a folder: CSV and NetCDF time series, JSON summary, a figure.

Everything is first written into a temporary folder next to the target and moved in
only when all four files succeeded, so a failed run never leaves half a result; an interrupt
(Ctrl-C, or SIGTERM through :mod:`rocking.cli.interrupts`) removes the temporary folder too.

The files grow with the number of saved samples (:func:`estimate_output_bytes`: up to about
150 bytes a sample on disk); writing them needs little memory beyond the series itself (the CSV
is written in blocks, and the figure draws at most a few thousand points a curve).
"""

from __future__ import annotations

import json
import math
import os
import shutil
import uuid
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..models.regimes import Regime

__all__ = [
    "OUTPUT_FILES", "OutputSpaceError", "check_output_space", "estimate_output_bytes", "human_bytes", "jsonable",
    "planned_samples", "plot_response", "summary_json", "write_files", "write_outputs",
]

#: The files :func:`write_outputs` creates, in order.
OUTPUT_FILES = ("timeseries.csv", "timeseries.nc", "summary.json", "response.png")

_CSV_COLUMNS = (
    ("time_s", "t", "%.10g"),
    ("u_m", "u", "%.10g"),
    ("u_dot_m_per_s", "u_dot", "%.10g"),
    ("theta_rad", "theta", "%.10g"),
    ("theta_dot_rad_per_s", "theta_dot", "%.10g"),
    ("regime", "regime", "%d"),
    ("floor_acceleration_m_per_s2", "floor_acceleration", "%.10g"),
)

# Upper bounds of the bytes per saved sample in each file. A CSV row holds six "%.10g" numbers of
# at most 16 characters (-1.234567891e-05), a one-digit regime, six commas and a newline. The NetCDF
# file stores t and five float64 series plus the int8 regime, uncompressed.
CSV_ROW_BYTES = 6 * 16 + 1 + 6 + 1
NETCDF_SAMPLE_BYTES = 6 * 8 + 1
# HDF5 structures and the attributes (the config and the summary as JSON): measured ~20 kB.
NETCDF_HEADER_BYTES = 100_000
# The figure, the summary and the NetCDF header do not grow with the run (measured: < 200 kB).
FIXED_OUTPUT_BYTES = 1_000_000
# Rows formatted at a time by the CSV writer: its memory stays a few MB however long the run.
_CSV_BLOCK_ROWS = 50_000
# Points drawn per curve at most (min and max of each of half as many slices): more than the
# figure's 960 pixel columns can show, and a few MB whatever the length of the run.
_PLOT_POINTS = 8_000

# Light shading of the regimes in the figure (REST is left blank).
_REGIME_STYLE = (
    (Regime.ROCK, "tab:orange", "rocking"),
    (Regime.SLIDE, "tab:blue", "sliding"),
    (Regime.SLIDE_ROCK, "tab:purple", "sliding + rocking"),
)


# ----------------------------------------------------------------------------- JSON
def jsonable(obj: Any) -> Any:
    """A copy of ``obj`` that :func:`json.dumps` writes as strict JSON.

    NaN and ±inf become ``null`` (JSON has no such numbers), NumPy scalars become
    Python numbers and tuples become lists.
    """
    if isinstance(obj, Mapping):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, Path):
        return str(obj)
    return obj


def summary_json(summary: Mapping[str, Any]) -> str:
    """The summary as indented strict JSON text (what ``rocking run --json`` prints)."""
    return json.dumps(jsonable(summary), indent=2, ensure_ascii=False, allow_nan=False)


# ------------------------------------------------------------------------ estimates
class OutputSpaceError(OSError):
    """The outputs would not fit on the target's file system (found before anything is written)."""


def human_bytes(n: float) -> str:
    """``4.1e10`` → ``"41 GB"`` (decimal units, three digits)."""
    for unit in ("bytes", "kB", "MB", "GB", "TB"):
        if abs(n) < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    raise AssertionError  # pragma: no cover


def planned_samples(motion: Any, options: Any, duration: float | None) -> int:
    """Samples of a run's saved series at most, counted as :func:`rocking.simulation.prepare`
    counts them: one every ``options.save_dt`` s (default the record's time step, or 0.01 s)
    over ``duration`` s, or over the motion plus ``options.free_time_limit`` s when ``duration``
    is None. Events add a row each (a few at most, next to the grid)."""
    t_end = float(duration) if duration is not None else float(motion.duration) + float(options.free_time_limit)
    save_dt = options.save_dt
    if save_dt is None:
        save_dt = float(getattr(motion, "dt", None) or 0.01)
    return math.floor(t_end / save_dt + 1e-9) + 1


def estimate_output_bytes(n_samples: int) -> dict[str, int]:
    """Upper bounds of the sizes of the files :func:`write_outputs` writes for ``n_samples`` rows.

    Parameters
    ----------
    n_samples : int
        Saved samples (rows of the time series; an event adds one).

    Returns
    -------
    dict
        ``{"timeseries.csv": bytes, "timeseries.nc": bytes, "other": bytes, "total": bytes}``.
    """
    n = max(0, int(n_samples))
    sizes = {"timeseries.csv": 200 + n * CSV_ROW_BYTES, "timeseries.nc": NETCDF_HEADER_BYTES + n * NETCDF_SAMPLE_BYTES,
             "other": FIXED_OUTPUT_BYTES}
    sizes["total"] = sum(sizes.values())
    return sizes


def _existing_folder(path: Path) -> Path:
    p = path.resolve()
    while not p.exists() and p.parent != p:
        p = p.parent
    return p


def check_output_space(n_samples: int, out_dir: str | os.PathLike[str], *, hint: str = "") -> dict[str, int]:
    """Refuse, before anything is written, outputs larger than the free space where they go.

    Parameters
    ----------
    n_samples : int
        Saved samples of the run (an estimate before it, the exact count after).
    out_dir : path-like
        The target folder (it need not exist yet).
    hint : str
        What the user can change, appended to the message (e.g. which config fields).

    Returns
    -------
    dict
        :func:`estimate_output_bytes` of ``n_samples``.

    Raises
    ------
    OutputSpaceError
        If the estimate exceeds the free space of the file system that will hold ``out_dir``.
    """
    sizes = estimate_output_bytes(n_samples)
    where = _existing_folder(Path(out_dir))
    try:
        free = shutil.disk_usage(where).free
    except OSError:
        return sizes  # no answer from the file system: the writer reports any real failure
    if sizes["total"] > free:
        raise OutputSpaceError(
            f"--out: {n_samples:.3g} saved samples would write up to {human_bytes(sizes['total'])} "
            f"(timeseries.csv {human_bytes(sizes['timeseries.csv'])}, timeseries.nc "
            f"{human_bytes(sizes['timeseries.nc'])}), but only {human_bytes(free)} is free on {where}"
            + (f"; {hint}" if hint else "")
        )
    return sizes


# ------------------------------------------------------------------------- writers
def _write_csv(response: Any, path: Path) -> None:
    """One row per saved instant; at an event the row before and after share the time.

    Written in blocks of rows, so that formatting a long run does not hold a text copy of it.
    """
    columns = [np.asarray(getattr(response, attr)) for _, attr, _ in _CSV_COLUMNS]
    header = ",".join(name for name, _, _ in _CSV_COLUMNS)
    fmt = [f for _, _, f in _CSV_COLUMNS]
    n = columns[0].shape[0]
    with open(path, "w", encoding="ascii", newline="") as f:
        f.write(header + "\n")
        for start in range(0, n, _CSV_BLOCK_ROWS):
            block = np.column_stack([c[start:start + _CSV_BLOCK_ROWS].astype(float) for c in columns])
            np.savetxt(f, block, fmt=fmt, delimiter=",")


def _write_netcdf(response: Any, path: Path, config: Any = None) -> None:
    ds = response.to_xarray()
    if config is not None:
        # the full input next to the result, so a .nc file explains itself
        data = config.model_dump(mode="json") if hasattr(config, "model_dump") else config
        ds.attrs["config"] = json.dumps(jsonable(data))
        if getattr(config, "source", None):
            ds.attrs["config_file"] = str(config.source)
    ds.to_netcdf(path, engine="h5netcdf")


def _regime_intervals(t: np.ndarray, regime: np.ndarray, code: int, *, resolution: float = 0.0) -> np.ndarray:
    """Time intervals [t_start, t_end] (s) during which ``regime == code``, as an (m, 2) array.

    Intervals separated by less than ``resolution`` (s) are merged: a figure cannot show the gap,
    and a long run that switches regime millions of times must not draw millions of patches.
    """
    on = regime == code
    if not on.any():
        return np.empty((0, 2))
    edges = np.diff(on.astype(np.int8))
    starts = np.flatnonzero(edges == 1) + 1
    ends = np.flatnonzero(edges == -1) + 1  # first sample after the interval
    if on[0]:
        starts = np.concatenate(([0], starts))
    if on[-1]:
        ends = np.concatenate((ends, [len(on) - 1]))
    a, b = t[starts], t[ends]
    if resolution > 0 and a.size > 1:
        apart = a[1:] - b[:-1] >= resolution  # this interval starts a new patch
        a = a[np.concatenate(([True], apart))]
        b = b[np.concatenate((apart, [True]))]
    return np.column_stack((a, b)).astype(float)


def _envelope(t: np.ndarray, y: np.ndarray, points: int = _PLOT_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """At most about ``points`` samples of (t, y) that draw the same curve at figure resolution:
    the first, the last, and the smallest and largest value of each of ``points/2`` slices, in
    time order (peaks are kept exactly)."""
    n = y.size
    slices = points // 2
    if n <= points or slices < 1:
        return t, y
    k = n // slices
    body = y[: k * slices].reshape(slices, k)
    base = np.arange(slices) * k
    idx = np.concatenate((base + np.argmin(body, axis=1), base + np.argmax(body, axis=1),
                          np.arange(k * slices, n), [0, n - 1]))
    idx = np.unique(idx)
    return t[idx], y[idx]


def plot_response(response: Any, path: str | os.PathLike[str], *, title: str | None = None) -> None:
    """Save a three-panel figure: θ/α, u (mm) and floor acceleration (m/s²) versus t (s).

    The regimes are shaded lightly on every panel, impacts are marked on the θ/α
    panel, and the overturning instant (if any) is drawn as a dashed line.

    Parameters
    ----------
    response : Response
    path : path-like
        PNG file to write.
    title : str, optional
        Figure title; default: the outcome.
    """
    # Figure + Agg canvas, not pyplot: no global state, no GUI backend, thread safe.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import PolyCollection
    from matplotlib.figure import Figure

    t = np.asarray(response.t, dtype=float)
    regime = np.asarray(response.regime_codes)
    span = float(t[-1] - t[0]) if t.size else 0.0
    fig = Figure(figsize=(8.0, 7.5), layout="constrained")
    FigureCanvasAgg(fig)
    ax_th, ax_u, ax_a = fig.subplots(3, 1, sharex=True)

    for code, color, label in _REGIME_STYLE:
        # gaps below a pixel's worth of time are not drawn (the figure is under 1000 pixels wide)
        intervals = _regime_intervals(t, regime, int(code), resolution=span / 2000.0)
        if not len(intervals):
            continue
        # one collection per regime and panel: a record can switch regime thousands
        # of times, and thousands of axvspan artists make saving slow
        a, b = intervals[:, 0], intervals[:, 1]
        zero, one = np.zeros_like(a), np.ones_like(a)
        verts = np.stack((np.column_stack((a, zero)), np.column_stack((b, zero)),
                          np.column_stack((b, one)), np.column_stack((a, one))), axis=1)
        for ax in (ax_th, ax_u, ax_a):
            ax.add_collection(
                PolyCollection(verts, transform=ax.get_xaxis_transform(), facecolor=color,
                               alpha=0.12, linewidth=0, label=label if ax is ax_th else None),
                autolim=False,
            )

    alpha = float(response.alpha)
    ax_th.plot(*_envelope(t, np.asarray(response.theta) / alpha), color="k", lw=0.9)
    for y in (-1.0, 1.0):  # |θ| = α: static instability of the statue
        ax_th.axhline(y, color="0.5", lw=0.6, ls=":")
    impacts = [imp.time for imp in response.impacts]
    if impacts:
        shown = np.unique(np.asarray(impacts, dtype=float))
        if shown.size > _PLOT_POINTS:  # marks closer than a pixel draw the same picture
            shown = np.unique(np.round(shown / (span / _PLOT_POINTS)) * (span / _PLOT_POINTS))
        ax_th.plot(shown, np.zeros(shown.size), ls="none", marker="|", ms=9, color="tab:red",
                   label=f"impacts ({len(impacts)})")
    if response.overturned and response.overturn_time is not None:
        for ax in (ax_th, ax_u, ax_a):
            ax.axvline(response.overturn_time, color="tab:red", ls="--", lw=1.0,
                       label="overturned" if ax is ax_th else None)
    ax_th.set_ylabel("θ/α")
    if ax_th.get_legend_handles_labels()[0]:  # at rest all along: nothing to explain
        ax_th.legend(loc="upper right", fontsize="small", ncol=3, framealpha=0.8)

    ax_u.plot(*_envelope(t, 1e3 * np.asarray(response.u)), color="k", lw=0.9)
    ax_u.set_ylabel("u (mm)")
    ax_a.plot(*_envelope(t, np.asarray(response.floor_acceleration)), color="k", lw=0.7)
    ax_a.set_ylabel("floor acceleration (m/s²)")
    ax_a.set_xlabel("t (s)")
    if t.size:
        ax_a.set_xlim(t[0], t[-1])
    if title is None:
        if response.overturned:
            title = f"overturned at t = {response.overturn_time:.3f} s"
        else:
            title = f"peak θ/α = {response.peak_rotation / alpha:.3f}, no overturning"
    fig.suptitle(title, fontsize="medium")
    fig.savefig(path, dpi=120)


def _write_summary(response: Any, path: Path) -> None:
    path.write_text(summary_json(response.summary()) + "\n", encoding="utf-8")


# --------------------------------------------------------------------------- public
def write_outputs(
    response: Any, out_dir: str | os.PathLike[str], *, config: Any = None
) -> dict[str, Path]:
    """Write ``timeseries.csv``, ``timeseries.nc``, ``summary.json`` and ``response.png``.

    Parameters
    ----------
    response : Response
        A result with its time series (``simulate(..., save=True)``).
    out_dir : path-like
        Target folder; created (with its parents) if missing. Files of the same names
        are replaced, other files are left alone.
    config : Config or mapping, optional
        Stored as JSON in the NetCDF attributes (``config``, ``config_file``) and
        used for the figure title.

    Returns
    -------
    dict
        ``{file name: path}`` of the four files.

    Raises
    ------
    ValueError
        If the response was simulated with ``save=False`` (no time series).
    NotADirectoryError
        If ``out_dir`` exists and is not a folder.
    OSError, ValueError
        If any file cannot be written; then no new file is left in ``out_dir``, and
        any folder this call created is removed again.

    Notes
    -----
    All files are written into a temporary folder inside ``out_dir``'s parent (the
    same file system, so the final moves are ``os.replace`` renames) and moved in
    only after all of them succeeded.
    """
    if np.asarray(response.t).size == 0:
        raise ValueError("the response has no time series: simulate with save=True")
    title = None
    if config is not None and getattr(config, "source", None):
        outcome = (f"overturned at t = {response.overturn_time:.3f} s" if response.overturned
                   else f"peak θ/α = {response.peak_rotation / response.alpha:.3f}")
        title = f"{Path(config.source).name}: {outcome}"
    # looked up when called (tests replace the writers of this module)
    return write_files(out_dir, {
        "timeseries.csv": lambda path: _write_csv(response, path),
        "timeseries.nc": lambda path: _write_netcdf(response, path, config),
        "summary.json": lambda path: _write_summary(response, path),
        "response.png": lambda path: plot_response(response, path, title=title),
    })


def write_files(out_dir: str | os.PathLike[str], writers: Mapping[str, Any]) -> dict[str, Path]:
    """Write files into ``out_dir`` all at once, or not at all.

    Parameters
    ----------
    out_dir : path-like
        Target folder; created (with its parents) if missing. Files of the same names are
        replaced, other files are left alone.
    writers : mapping
        ``{file name: function(path)}``, called in order, each writing its file at ``path``
        (in a temporary folder).

    Returns
    -------
    dict
        ``{file name: path in out_dir}``.

    Raises
    ------
    NotADirectoryError
        If ``out_dir`` exists and is not a folder.
    OSError, ValueError
        What a writer raised; then no new file is left in ``out_dir``, and any folder this
        call created is removed again (see :func:`write_outputs`).
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise NotADirectoryError(f"{out}: exists and is not a directory")
    names = list(writers)
    created: list[Path] = []
    # the name before the folder, and the folder inside the try: an interrupt at any moment
    # (Ctrl-C, or SIGTERM through rocking.cli.interrupts) leaves no temporary folder behind
    tmp = out.parent / f".{out.name}.tmp-{uuid.uuid4().hex[:12]}"
    try:
        created = _make_parents(out.parent)
        tmp.mkdir(mode=0o700)  # private while it fills, like mkdtemp's
        for name, write in writers.items():
            write(tmp / name)
        if not out.exists():
            out.mkdir()
            created.append(out)
        _move_in(tmp, out, names)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)  # first: it sits in a folder we may remove
        _remove_empty(created)
        raise
    shutil.rmtree(tmp, ignore_errors=True)
    return {name: out / name for name in names}


def _move_in(tmp: Path, out: Path, names: list[str]) -> None:
    """Move the finished files into ``out``; on failure put back what was there."""
    backup = tmp / ".previous"
    backup.mkdir()
    moved: list[str] = []
    saved: list[str] = []
    try:
        for name in names:
            target = out / name
            if target.exists():
                os.replace(target, backup / name)
                saved.append(name)
            os.replace(tmp / name, target)
            moved.append(name)
    except BaseException:
        for name in moved:
            (out / name).unlink(missing_ok=True)
        for name in saved:
            os.replace(backup / name, out / name)
        raise


def _make_parents(folder: Path) -> list[Path]:
    """Create ``folder`` and missing parents; return those created, outermost first."""
    missing = []
    p = folder
    while not p.exists():
        missing.append(p)
        if p.parent == p:
            break
        p = p.parent
    missing.reverse()
    made: list[Path] = []
    try:
        for p in missing:
            p.mkdir()
            made.append(p)
    except BaseException:
        _remove_empty(made)
        raise
    return made


def _remove_empty(folders: list[Path]) -> None:
    """Remove folders created by this call (innermost first), if they are still empty."""
    for p in reversed(folders):
        try:
            p.rmdir()
        except OSError:
            pass
