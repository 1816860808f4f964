"""What the web app's worker processes do: one run, or a friction design sweep.

These functions only call the public API (:func:`rocking.runner.run_response`,
:func:`rocking.analyses.batch.sweep`, :mod:`rocking.viz`, :func:`rocking.report.write_report`);
they compute no physics. They run in a worker process (see :mod:`rocking.web.jobs`), write their
pictures and files into ``out_dir`` and return a small, picklable dict for the page.
"""

from __future__ import annotations

import csv
import io
import json
import math
import time
import zipfile
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

__all__ = ["SWEEP_COLUMNS", "best_row", "run_task", "sweep_task"]

Progress = Callable[[int, int, str], None]

#: Columns of sweep.csv (the pedestal's floor friction, then the summary of each run).
SWEEP_COLUMNS = (
    "static_friction",
    "kinetic_friction",
    "overturned",
    "overturn_time",
    "peak_rotation",
    "peak_rotation_over_alpha",
    "peak_sliding",
    "residual_sliding",
    "impacts",
    "first_rocking_time",
    "first_sliding_time",
    "required_top_friction",
    "status",
)


def _no_progress(done: int, total: int, label: str = "") -> None:
    pass


def _jsonable(summary: Mapping[str, Any]) -> dict[str, Any]:
    from ..io.output import summary_json

    return json.loads(summary_json(summary))


def _motion_rows(motion: Any, duration: float, gravity: float) -> list[tuple[str, str]]:
    rows = [("record", str(getattr(motion, "name", "") or type(motion).__name__))]
    if hasattr(motion, "dt"):
        rows.append(("samples", f"{motion.n} at Δt = {motion.dt:g} s"))
    rows.append(("PGA (after scaling)", f"{motion.pga:.3f} m/s² = {motion.pga / gravity:.3f} g"))
    rows.append(("simulated duration", f"{duration:.2f} s"))
    return rows


def _animation_speed(duration: float, longest_video: float) -> float:
    """Playback speed so that the animation lasts at most ``longest_video`` seconds."""
    return max(1.0, duration / longest_video)


def run_task(
    *,
    config: Mapping[str, Any],
    out_dir: str,
    animation: Mapping[str, Any] | None = None,
    dpi: int = 90,
    progress: Progress = _no_progress,
) -> dict[str, Any]:
    """Simulate ``config`` (a config dict, see :mod:`rocking.io.config`) and write
    ``response.png``, ``energy.png``, ``animation.gif`` and ``result.json`` into ``out_dir``.

    Returns
    -------
    dict
        ``verdict`` (sentence), ``summary`` (JSON-ready :meth:`Response.summary`), ``motion``
        (rows of label, value), ``files`` (picture names), ``animation_speed``, ``seconds``.
    """
    from ..report import verdict
    from ..runner import run_response
    from ..viz.animation import animate
    from ..viz.plots import plot_energy, plot_response

    anim = {"fps": 10, "longest_video": 20.0, "dpi": 60, **(animation or {})}
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    progress(0, 4, "simulating")
    cfg, response = run_response(dict(config))
    seconds = time.perf_counter() - t0
    summary = response.summary()
    progress(1, 4, "plotting")
    fig = plot_response(response)
    fig.savefig(out / "response.png", dpi=dpi, metadata={"Software": None})
    ax = plot_energy(response)
    ax.figure.savefig(out / "energy.png", dpi=dpi, metadata={"Software": None})
    progress(2, 4, "animating")
    speed = _animation_speed(response.duration, float(anim["longest_video"]))
    animate(response, out / "animation.gif", speed=speed, fps=float(anim["fps"]), dpi=int(anim["dpi"]))
    _, motion, options, duration = cfg.to_specs()
    result = {
        "verdict": verdict(response),
        "summary": _jsonable(summary),
        "motion": _motion_rows(motion, duration, options.gravity),
        "files": {"response": "response.png", "energy": "energy.png", "animation": "animation.gif"},
        "animation_speed": speed,
        "seconds": seconds,
    }
    (out / "result.json").write_text(json.dumps(result, indent=2, ensure_ascii=False), encoding="utf-8")
    progress(4, 4, "done")
    return result


# ------------------------------------------------------------------------------- design sweep
RULE = ("among the values that meet the limits, the one where the statue does not overturn (or falls last), "
        "then the smallest peak rotation, then the least sliding, then the smaller μs")


def best_row(rows: list[Mapping[str, Any]], sliding_limit: float | None = None,
             top_friction_limit: float | None = None) -> tuple[Mapping[str, Any], bool]:
    """The recommended row of a one-motion sweep and whether it meets the limits.

    The rule of :func:`rocking.analyses.design.friction_design` for one motion: among the rows
    whose peak sliding is within ``sliding_limit`` (m) and whose statue–pedestal face needs no more
    than ``top_friction_limit``, no overturn first, then the smallest peak θ/α, the smaller peak
    sliding, the smaller μs. If no row meets the limits, the best row regardless of them.
    """

    def ok(r: Mapping[str, Any]) -> bool:
        if sliding_limit is not None and r["peak_sliding"] > sliding_limit:
            return False
        need = r["required_top_friction"]
        return not (top_friction_limit is not None and not r["overturned"] and need is not None
                    and need > top_friction_limit)

    def key(r: Mapping[str, Any]) -> tuple:
        return (bool(r["overturned"]), -(r["overturn_time"] or 0.0) if r["overturned"] else 0.0,
                r["peak_rotation_over_alpha"], r["peak_sliding"], r["static_friction"])

    feasible = [r for r in rows if ok(r)]
    return (min(feasible, key=key), True) if feasible else (min(rows, key=key), False)


def _value(v: Any) -> Any:
    v = v.item() if hasattr(v, "item") else v
    if isinstance(v, float) and math.isnan(v):
        return None
    return v


def _row(mu: float, mu_k: float, point: Any) -> dict[str, Any]:
    """One sweep row from a dataset point (every summary field is a scalar there)."""
    row: dict[str, Any] = {"static_friction": float(mu), "kinetic_friction": float(mu_k)}
    for key in SWEEP_COLUMNS[2:]:
        row[key] = _value(point[key].values.reshape(-1)[0])
    row["overturned"] = bool(row["overturned"])
    return row


def _rows_by_design(friction_design: Callable[..., Any], system: Any, motion: Any, frictions: list[float],
                    ratio: float, options: Any, free_time: float, sliding_limit: float | None, progress: Progress,
                    total: int):
    """Rows and the recommended μs from :func:`rocking.analyses.design.friction_design`."""

    def tick(done: int, n: int) -> None:
        progress(done, total, f"{done} of {n} runs")

    ds = friction_design(
        system, {"record": motion}, mu_s=frictions, mu_k_ratio=ratio, sliding_limit=sliding_limit,
        free_time=free_time, options=options, workers=1, chunk_size=1, progress=tick,
    )
    rows = []
    for i, mu in enumerate(ds.mu_s.values):
        point = ds.isel(mu_s=i, pedestal_mass=0, motion=0)
        row = _row(float(mu), float(ds.mu_k.values[i]), point)
        row["feasible"] = bool(ds.feasible.values[i, 0])
        rows.append(row)
    recommended = ds.attrs.get("recommended_mu_s", float("nan"))
    return rows, (None if not math.isfinite(recommended) else float(recommended))


def _rows_by_sweep(system: Any, motion: Any, frictions: list[float], ratio: float, options: Any,
                   duration: float, progress: Progress, total: int):
    """Rows from :func:`rocking.analyses.batch.sweep`, one μs at a time (for the progress bar)."""
    from dataclasses import replace

    from ..analyses.batch import sweep
    from ..contact.friction import Friction

    # μk = None on the base: the sweep sets μs first, then μk = ratio·μs (never μk > μs midway)
    base = replace(system, pedestal=replace(system.pedestal, friction=Friction(static=max(frictions))))
    rows = []
    for i, mu in enumerate(frictions):
        progress(i, total, f"{i} of {len(frictions)} runs")
        ds = sweep(base, motion, {"pedestal.friction.static": [mu], "pedestal.friction.ratio": [ratio]},
                   options=options, duration=duration, workers=1)
        rows.append(_row(mu, ratio * mu, ds))
    return rows, None


def _csv_value(v: Any) -> Any:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    return v


def _write_csv(rows: list[Mapping[str, Any]], path: Path) -> None:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(SWEEP_COLUMNS)
    for r in rows:
        w.writerow([_csv_value(r[c]) for c in SWEEP_COLUMNS])
    path.write_text(buf.getvalue(), encoding="utf-8")


def _plot_sweep(rows: list[Mapping[str, Any]], best: Mapping[str, Any], path: Path, dpi: int) -> None:
    from matplotlib.figure import Figure

    mu = [r["static_friction"] for r in rows]
    fig = Figure(figsize=(7.0, 5.2), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    top = 2.0
    ax1.plot(mu, [min(r["peak_rotation_over_alpha"], top) for r in rows], "-o", ms=3, lw=1.2, color="C0")
    fell = [(r["static_friction"], top * 0.97) for r in rows if r["overturned"]]
    if fell:
        ax1.plot(*zip(*fell), "v", color="C3", ms=6, ls="none", label="overturns")
        ax1.legend(fontsize=8, loc="upper left")
    ax1.axhline(1.0, color="0.5", lw=0.8, ls=":")
    ax1.axvline(best["static_friction"], color="C2", lw=1.0, ls="--")
    ax1.set_ylim(0.0, top)
    ax1.set_ylabel("peak |θ|/α")
    ax1.set_title("peak rotation of the statue (▼ overturned; dashed: best value)", loc="left", fontsize=9)
    ax2.plot(mu, [1e3 * r["peak_sliding"] for r in rows], "-o", ms=3, lw=1.2, color="C1")
    ax2.axvline(best["static_friction"], color="C2", lw=1.0, ls="--")
    ax2.set_ylabel("peak sliding (mm)")
    ax2.set_xlabel("pedestal floor friction μs")
    ax2.set_title("peak sliding of the pedestal on the floor", loc="left", fontsize=9)
    for ax in (ax1, ax2):
        ax.grid(True, lw=0.3, alpha=0.6)
    fig.savefig(path, dpi=dpi, metadata={"Software": None})


def _describe(row: Mapping[str, Any]) -> str:
    if row["overturned"]:
        return f"overturns at {row['overturn_time']:.2f} s"
    return f"peak {row['peak_rotation_over_alpha']:.3f} α, pedestal slides at most {1e3 * row['peak_sliding']:.1f} mm"


def sweep_task(
    *,
    config: Mapping[str, Any],
    frictions: list[float],
    out_dir: str,
    sliding_limit: float | None = None,
    dpi: int = 90,
    progress: Progress = _no_progress,
) -> dict[str, Any]:
    """Sweep the pedestal's floor friction μs over ``frictions`` (μk/μs kept as in ``config``) under
    the configured record, recommend one value, and write ``sweep.csv``, ``sweep.png``, the report
    of the recommended value (``report.html`` and ``report.pdf`` from
    :func:`rocking.report.write_report`) and ``sweep-report.zip`` with all of them.

    Uses :func:`rocking.analyses.design.friction_design` when that module is there, else
    :func:`rocking.analyses.batch.sweep` with the same rule (:func:`best_row`).

    Parameters
    ----------
    sliding_limit : float, optional
        Largest acceptable peak sliding of the pedestal, m (the free space around it).

    Returns
    -------
    dict
        ``rows`` (one per μs), ``best`` (the recommended row), ``meets_limits``, ``verdict`` (of the
        recommended value), ``rule``, ``ratio`` (μk/μs), ``duration``, ``method``, ``files``.
    """
    from ..io.config import load_config
    from ..report import verdict, write_report
    from ..runner import run_response

    if not config.get("pedestal"):
        raise ValueError("the friction design sweep varies the pedestal's floor friction: add a pedestal")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    cfg = load_config(dict(config))
    system, motion, options, duration = cfg.to_specs()
    fr = system.pedestal.friction
    ratio = fr.mu_k / fr.mu_s if fr.mu_s > 0 else 1.0
    top_limit = system.statue.friction.mu_s if system.statue.friction is not None else None
    n = len(frictions)
    total = n + 1
    progress(0, total, "starting")
    try:
        from ..analyses.design import friction_design
    except ImportError:
        friction_design = None
    if friction_design is not None:
        method = "friction design"
        end = float(motion.duration)
        shaken = motion.trimmed(duration) if duration < end else motion
        rows, recommended = _rows_by_design(friction_design, system, shaken, frictions, ratio, options,
                                            max(0.0, duration - end), sliding_limit, progress, total)
    else:
        method = "batch sweep"
        rows, recommended = _rows_by_sweep(system, motion, frictions, ratio, options, duration, progress, total)
    progress(n, total, "writing the report")
    best, meets = best_row(rows, sliding_limit, top_limit)
    if recommended is not None:  # the design module's choice (the same rule)
        best = min(rows, key=lambda r: abs(r["static_friction"] - recommended))
        meets = True
    limits = []
    if sliding_limit is not None:
        limits.append(f"peak sliding ≤ {1e3 * sliding_limit:g} mm")
    if top_limit is not None:
        limits.append(f"friction needed under the statue ≤ its μs = {top_limit:g}")
    rule = RULE + (f" (limits: {', '.join(limits)})" if limits else " (no limits given)")
    if not meets:
        rule = "no value meets the limits (" + ", ".join(limits) + "): the best value regardless of them"
    chosen = json.loads(json.dumps(config))
    chosen["pedestal"]["friction"] = {"static": best["static_friction"], "kinetic": best["kinetic_friction"]}
    chosen.setdefault("simulation", {})["duration"] = duration
    cfg_best, response = run_response(chosen)
    _write_csv(rows, out / "sweep.csv")
    _plot_sweep(rows, best, out / "sweep.png", dpi)
    sweep_inputs = {
        "friction design sweep": {
            "values of the pedestal's floor friction μs": f"{n}, from {frictions[0]:g} to {frictions[-1]:g}",
            "μk/μs": f"{ratio:g}",
            "recommended μs": f"{best['static_friction']:g}",
            "rule": rule,
            "computed with": method,
            **{f"μs = {r['static_friction']:.4g}": _describe(r) for r in rows},
        }
    }
    title = f"Friction design sweep — report for the pedestal's floor friction μs = {best['static_friction']:.4g}"
    write_report((cfg_best, response), out, title=title, inputs=sweep_inputs, dpi=dpi)
    files = ["report.html", "report.pdf", "sweep.csv", "sweep.png"]
    with zipfile.ZipFile(out / "sweep-report.zip", "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name in files:
            if (out / name).exists():
                zf.write(out / name, arcname=name)
    progress(total, total, "done")
    return {
        "rows": rows,
        "best": best,
        "meets_limits": meets,
        "rule": rule,
        "ratio": ratio,
        "duration": duration,
        "method": method,
        "verdict": verdict(response),
        "files": [name for name in files if (out / name).exists()] + ["sweep-report.zip"],
    }
