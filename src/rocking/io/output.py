"""Write a run's results to a folder: CSV and NetCDF time series, JSON summary, a figure.

Everything is first written into a temporary folder next to the target and moved in
only when all four files succeeded, so a failed run never leaves half a result.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..models.regimes import Regime

__all__ = ["OUTPUT_FILES", "jsonable", "plot_response", "summary_json", "write_outputs"]

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


# ------------------------------------------------------------------------- writers
def _write_csv(response: Any, path: Path) -> None:
    """One row per saved instant; at an event the row before and after share the time."""
    data = np.column_stack([np.asarray(getattr(response, attr), dtype=float) for _, attr, _ in _CSV_COLUMNS])
    header = ",".join(name for name, _, _ in _CSV_COLUMNS)
    np.savetxt(path, data, fmt=[f for _, _, f in _CSV_COLUMNS], delimiter=",", header=header, comments="")


def _write_netcdf(response: Any, path: Path, config: Any = None) -> None:
    ds = response.to_xarray()
    if config is not None:
        # the full input next to the result, so a .nc file explains itself
        data = config.model_dump(mode="json") if hasattr(config, "model_dump") else config
        ds.attrs["config"] = json.dumps(jsonable(data))
        if getattr(config, "source", None):
            ds.attrs["config_file"] = str(config.source)
    ds.to_netcdf(path, engine="h5netcdf")


def _regime_intervals(t: np.ndarray, regime: np.ndarray, code: int) -> list[tuple[float, float]]:
    """Time intervals [t_start, t_end] during which ``regime == code``."""
    on = regime == code
    if not on.any():
        return []
    edges = np.diff(on.astype(np.int8))
    starts = list(np.flatnonzero(edges == 1) + 1)
    ends = list(np.flatnonzero(edges == -1) + 1)  # first sample after the interval
    if on[0]:
        starts.insert(0, 0)
    if on[-1]:
        ends.append(len(on) - 1)
    return [(float(t[a]), float(t[b])) for a, b in zip(starts, ends, strict=True)]


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
    regime = np.asarray(response.regime)
    fig = Figure(figsize=(8.0, 7.5), layout="constrained")
    FigureCanvasAgg(fig)
    ax_th, ax_u, ax_a = fig.subplots(3, 1, sharex=True)

    for code, color, label in _REGIME_STYLE:
        intervals = _regime_intervals(t, regime, int(code))
        if not intervals:
            continue
        # one collection per regime and panel: a record can switch regime thousands
        # of times, and thousands of axvspan artists make saving slow
        verts = [[(a, 0.0), (b, 0.0), (b, 1.0), (a, 1.0)] for a, b in intervals]
        for ax in (ax_th, ax_u, ax_a):
            ax.add_collection(
                PolyCollection(verts, transform=ax.get_xaxis_transform(), facecolor=color,
                               alpha=0.12, linewidth=0, label=label if ax is ax_th else None),
                autolim=False,
            )

    alpha = float(response.alpha)
    ax_th.plot(t, np.asarray(response.theta) / alpha, color="k", lw=0.9)
    for y in (-1.0, 1.0):  # |θ| = α: static instability of the statue
        ax_th.axhline(y, color="0.5", lw=0.6, ls=":")
    impacts = [imp.time for imp in response.impacts]
    if impacts:
        ax_th.plot(impacts, np.zeros(len(impacts)), ls="none", marker="|", ms=9, color="tab:red",
                   label=f"impacts ({len(impacts)})")
    if response.overturned and response.overturn_time is not None:
        for ax in (ax_th, ax_u, ax_a):
            ax.axvline(response.overturn_time, color="tab:red", ls="--", lw=1.0,
                       label="overturned" if ax is ax_th else None)
    ax_th.set_ylabel("θ/α")
    if ax_th.get_legend_handles_labels()[0]:  # at rest all along: nothing to explain
        ax_th.legend(loc="upper right", fontsize="small", ncol=3, framealpha=0.8)

    ax_u.plot(t, 1e3 * np.asarray(response.u), color="k", lw=0.9)
    ax_u.set_ylabel("u (mm)")
    ax_a.plot(t, np.asarray(response.floor_acceleration), color="k", lw=0.7)
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
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise NotADirectoryError(f"{out}: exists and is not a directory")
    created = _make_parents(out.parent)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.tmp-", dir=out.parent))
    except BaseException:
        _remove_empty(created)
        raise
    try:
        title = None
        if config is not None and getattr(config, "source", None):
            title = Path(config.source).name
            outcome = (f"overturned at t = {response.overturn_time:.3f} s" if response.overturned
                       else f"peak θ/α = {response.peak_rotation / response.alpha:.3f}")
            title = f"{title}: {outcome}"
        _write_csv(response, tmp / "timeseries.csv")
        _write_netcdf(response, tmp / "timeseries.nc", config)
        _write_summary(response, tmp / "summary.json")
        plot_response(response, tmp / "response.png", title=title)
        if not out.exists():
            out.mkdir()
            created.append(out)
        _move_in(tmp, out)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)  # first: it sits in a folder we may remove
        _remove_empty(created)
        raise
    shutil.rmtree(tmp, ignore_errors=True)
    return {name: out / name for name in OUTPUT_FILES}


def _move_in(tmp: Path, out: Path) -> None:
    """Move the finished files into ``out``; on failure put back what was there."""
    backup = tmp / ".previous"
    backup.mkdir()
    moved: list[str] = []
    saved: list[str] = []
    try:
        for name in OUTPUT_FILES:
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
