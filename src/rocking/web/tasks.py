"""What the web app's worker processes do: one run, or a friction design sweep.

These functions only call the public API (:func:`rocking.runner.run_response`,
:func:`rocking.analyses.batch.sweep`, :mod:`rocking.viz`, :func:`rocking.report.write_report`);
they compute no physics. They run in a worker process (see :mod:`rocking.web.jobs`), write their
pictures and files into ``out_dir`` and return a small, picklable dict for the page.
"""

from __future__ import annotations

import base64
import csv
import dataclasses
import io
import json
import math
import time
import zipfile
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["SWEEP_COLUMNS", "run_task", "sweep_task"]

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
    # the design's judgement of the value over the friction scatter μs·(1 ± s), μk alike:
    "safe",  # the statue stands at every friction level
    "falls",  # it overturns at some level
    "undetermined",  # no fall, but still moving at the end (or the run stopped) at some level
    "clearance",  # m: the largest peak sliding over the levels, the free space the pedestal needs
    "meets_limits",
    "inverted",  # μs at or above the statue-pedestal face's friction
    "recommended",
)


def _no_progress(done: int, total: int, label: str = "") -> None:
    pass


def _jsonable(summary: Mapping[str, Any]) -> dict[str, Any]:
    from ..io.output import summary_json

    return json.loads(summary_json(summary))


def _motion_rows(motion: Any, end_time: float, gravity: float) -> list[tuple[str, str]]:
    """Rows describing the floor motion and how long the run lasted (``end_time``, s)."""
    rows = [("record", str(getattr(motion, "name", "") or type(motion).__name__))]
    if hasattr(motion, "dt"):
        rows.append(("samples", f"{motion.n} at Δt = {motion.dt:g} s"))
    rows.append(("PGA (after scaling)", f"{motion.pga:.3f} m/s² = {motion.pga / gravity:.3f} g"))
    rows.append(("length of the motion", f"{motion.duration:.2f} s"))
    rows.append(("simulated until", f"{end_time:.2f} s"))
    return rows


def _animation_speed(duration: float, longest_video: float) -> float:
    """Playback speed: real time (1) up to ``longest_video`` seconds of animation, faster for a
    longer run so that the animation lasts ``longest_video`` seconds."""
    return max(1.0, duration / longest_video)


#: What zero means on the energy plot (T + V relative to the floor, V = 0 upright).
ENERGY_AXIS_LABEL = "T + V (J);  0 = upright, at rest on the floor"

#: The size of the plots shown on a phone (in): narrow, so that their text stays readable.
NARROW_RESPONSE_SIZE = (3.4, 5.6)
NARROW_ENERGY_SIZE = (3.4, 4.2)


def _legend_rows(ax: Any, *, ncol: int, below: bool = False) -> None:
    """Lay out the legend of ``ax`` again in ``ncol`` columns (above the axes, or below them)."""
    legend = ax.get_legend()
    if legend is None:
        return
    handles, labels = legend.legend_handles, [t.get_text() for t in legend.get_texts()]
    size = legend.get_texts()[0].get_fontsize() if labels else 7.5
    legend.remove()
    if below:
        ax.figure.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=size, frameon=False,
                         handlelength=1.5)
    else:
        ax.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=ncol, fontsize=size,
                  frameon=False, borderaxespad=0.0, handlelength=1.5)


def _save_plots(response: Any, out: Path, dpi: int) -> None:
    """``response.png`` and ``energy.png`` for a wide screen, ``*-narrow.png`` for a phone."""
    from matplotlib.figure import Figure

    from ..viz.plots import plot_energy, plot_response

    fig = plot_response(response)
    fig.savefig(out / "response.png", dpi=dpi, metadata={"Software": None})
    ax = plot_energy(response)
    ax.set_ylabel(ENERGY_AXIS_LABEL)
    ax.figure.savefig(out / "energy.png", dpi=dpi, metadata={"Software": None})

    # a phone shows about 350 CSS pixels: drawn that wide, the text keeps its size
    narrow = Figure(figsize=NARROW_RESPONSE_SIZE, layout="constrained")
    axes = narrow.subplots(3, 1, sharex=True)
    plot_response(response, axes=axes)
    _legend_rows(axes[0], ncol=3)
    narrow.savefig(out / "response-narrow.png", dpi=int(1.6 * dpi), metadata={"Software": None})
    narrow = Figure(figsize=NARROW_ENERGY_SIZE, layout="constrained")
    ax = plot_energy(response, ax=narrow.add_subplot())
    ax.set_ylabel(ENERGY_AXIS_LABEL)
    _legend_rows(ax, ncol=1, below=True)
    narrow.savefig(out / "energy-narrow.png", dpi=int(1.6 * dpi), metadata={"Software": None})


#: The pictures of a run, by their role on the page.
_RUN_PICTURES = {"response": "response.png", "energy": "energy.png", "animation": "animation.gif",
                 "response_narrow": "response-narrow.png", "energy_narrow": "energy-narrow.png"}


def _save_stack_plots(response: Any, motion: Any, out: Path, dpi: int) -> None:
    """The stack's ``response.png`` (every block, and the floor) and ``energy.png``, each also
    narrow for a phone."""
    from matplotlib.figure import Figure

    from ..viz.stack_plots import plot_stack_energy, plot_stack_response

    plot_stack_response(response, motion=motion).savefig(out / "response.png", dpi=dpi, metadata={"Software": None})
    plot_stack_energy(response).figure.savefig(out / "energy.png", dpi=dpi, metadata={"Software": None})
    from ..report.pdf import fit_ylabels

    narrow = Figure(figsize=(NARROW_RESPONSE_SIZE[0], NARROW_RESPONSE_SIZE[1] + 0.4), layout="constrained")
    plot_stack_response(response, narrow.subplots(3, 1, sharex=True), motion=motion, legend_columns=2)
    fit_ylabels(narrow)  # the panels of a phone's figure are shorter than their labels
    narrow.savefig(out / "response-narrow.png", dpi=int(1.6 * dpi), metadata={"Software": None})
    narrow = Figure(figsize=NARROW_ENERGY_SIZE, layout="constrained")
    ax = plot_stack_energy(response, narrow.add_subplot())
    _legend_rows(ax, ncol=1, below=True)
    fit_ylabels(narrow)
    narrow.savefig(out / "energy-narrow.png", dpi=int(1.6 * dpi), metadata={"Software": None})


def _run_stack(cfg: Any, response: Any, out: Path, anim: Mapping[str, Any], dpi: int, seconds: float,
               progress: Progress) -> dict[str, Any]:
    """The pictures and the result of a stack run (:func:`run_task` with ``[[blocks]]``)."""
    from ..viz.stack_animation import animate_stack

    _, motion, options, _ = cfg.to_specs()
    progress(1, 4, "plotting")
    _save_stack_plots(response, motion, out, dpi)
    progress(2, 4, "animating")
    speed = _animation_speed(response.end_time, float(anim["longest_video"]))
    animate_stack(response, out / "animation.gif", speed=speed, fps=float(anim["fps"]), dpi=int(anim["dpi"]))
    return {
        "kind": "stack",
        "verdict": page_words(response.verdict),
        "summary": _jsonable(response.summary()),
        "frictions": [None if f.friction is None else f.friction.mu_s for f in response.stack.interfaces],
        "motion": _motion_rows(motion, response.end_time, options.gravity),
        "files": dict(_RUN_PICTURES),
        "animation_speed": speed,
        "seconds": seconds,
    }


def run_task(
    *,
    config: Mapping[str, Any],
    out_dir: str,
    animation: Mapping[str, Any] | None = None,
    dpi: int = 90,
    progress: Progress = _no_progress,
) -> dict[str, Any]:
    """Simulate ``config`` (a config dict, see :mod:`rocking.io.config`; a statue, or a stack of
    blocks with ``blocks`` and ``interfaces``) and write ``response.png``, ``energy.png`` (and
    their ``-narrow`` versions for a phone), ``animation.gif`` and ``result.json`` into ``out_dir``.

    Returns
    -------
    dict
        ``verdict`` (sentence), ``summary`` (JSON-ready :meth:`Response.summary`), ``motion``
        (rows of label, value), ``files`` (picture names), ``animation_speed``, ``seconds``.
        A stack's also has ``kind = "stack"`` and ``frictions`` (each interface's μs, or None
        when it never slips); its verdict is :attr:`rocking.stack.StackResponse.verdict`, which
        names the block that fell or slid to an edge.
    """
    from ..report import verdict
    from ..runner import run_response
    from ..viz.animation import animate

    anim = {"fps": 20, "longest_video": 60.0, "dpi": 80, **(animation or {})}
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    progress(0, 4, "simulating")
    cfg, response = run_response(dict(config))
    seconds = time.perf_counter() - t0
    if "blocks" in config:
        result = _run_stack(cfg, response, out, anim, dpi, seconds, progress)
        (out / "result.json").write_text(json.dumps(result, indent=2, ensure_ascii=False), encoding="utf-8")
        progress(4, 4, "done")
        return result
    summary = response.summary()
    progress(1, 4, "plotting")
    _save_plots(response, out, dpi)
    progress(2, 4, "animating")
    speed = _animation_speed(response.end_time, float(anim["longest_video"]))
    animate(response, out / "animation.gif", speed=speed, fps=float(anim["fps"]), dpi=int(anim["dpi"]))
    result = {
        "verdict": page_words(verdict(response)),
        "summary": _jsonable(summary),
        "motion": _motion_rows(response.motion, response.end_time, response.options.gravity),
        "files": dict(_RUN_PICTURES),
        "animation_speed": speed,
        "seconds": seconds,
    }
    (out / "result.json").write_text(json.dumps(result, indent=2, ensure_ascii=False), encoding="utf-8")
    progress(4, 4, "done")
    return result


# ------------------------------------------------------------------------------- design sweep
def _value(v: Any) -> Any:
    v = v.item() if hasattr(v, "item") else v
    if isinstance(v, float) and math.isnan(v):
        return None
    return v


def _row(mu: float, mu_k: float, point: Any) -> dict[str, Any]:
    """One sweep row from a dataset point (every summary field is a scalar there)."""
    row: dict[str, Any] = {"static_friction": float(mu), "kinetic_friction": float(mu_k)}
    for key in SWEEP_COLUMNS[2:]:
        if key in point:
            row[key] = _value(point[key].values.reshape(-1)[0])
    row["overturned"] = bool(row["overturned"])
    return row


def _rows_by_design(friction_design: Callable[..., Any], system: Any, motion: Any, frictions: list[float],
                    ratio: float, options: Any, free_time: float, sliding_limit: float | None,
                    friction_scatter: float, progress: Progress, total: int):
    """Rows (one per μs: the run at the nominal friction, and the design's judgement over the
    scatter band) and the Dataset of :func:`rocking.analyses.design.friction_design`, which
    ranks the values and writes the verdict: the page keeps no rule of its own."""

    def tick(done: int, n: int) -> None:
        progress(done, total, f"{done} of {n} runs")

    name = str(getattr(motion, "name", "") or "record")
    ds = friction_design(
        system, {name: motion}, mu_s=frictions, mu_k_ratio=ratio, sliding_limit=sliding_limit,
        friction_scatter=friction_scatter, free_time=free_time, options=options, workers=1, chunk_size=1,
        progress=tick,
    )
    rows = []
    for i, mu in enumerate(ds.mu_s.values):
        point = ds.isel(mu_s=i, pedestal_mass=0, motion=0)
        row = _row(float(mu), float(ds.mu_k.values[i]), point)
        row["safe"] = bool(ds.safe.values[i, 0])
        row["falls"] = bool(ds.falls.values[i, 0, 0])
        row["undetermined"] = bool(ds.undetermined.values[i, 0, 0])
        row["clearance"] = float(ds.clearance.values[i, 0, 0])
        row["meets_limits"] = bool(ds.feasible.values[i, 0])
        row["inverted"] = bool(ds.inverted.values[i])
        row["recommended"] = bool(ds.recommended.values[i, 0])
        rows.append(row)
    return rows, ds


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


def _plot_sweep(rows: list[Mapping[str, Any]], best: Mapping[str, Any], path: Path, dpi: int, *,
                recommended: bool, friction_scatter: float, tan_alpha: float, sliding_limit: float | None) -> None:
    from matplotlib.figure import Figure

    mu = [r["static_friction"] for r in rows]
    fig = Figure(figsize=(7.0, 5.2), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    top = 2.0
    ax1.plot(mu, [min(r["peak_rotation_over_alpha"], top) for r in rows], "-o", ms=3, lw=1.2, color="C0")
    fell = [(r["static_friction"], top * 0.97) for r in rows if r["falls"] or r["undetermined"]]
    if fell:
        ax1.plot(*zip(*fell), "v", color="C3", ms=6, ls="none", label="falls (or undetermined) within the scatter")
        ax1.legend(fontsize=8, loc="upper left")
    ax1.axhline(1.0, color="0.5", lw=0.8, ls=":")
    mu_best = best["static_friction"]
    shown = "recommended μs" if recommended else "no safe value: the fewest falls"
    for ax in (ax1, ax2):
        ax.axvline(tan_alpha, color="0.4", lw=0.8, ls=":")
        if recommended and friction_scatter > 0:  # the range over which the value's safety was checked
            ax.axvspan(mu_best * (1 - friction_scatter), mu_best * (1 + friction_scatter), color="C2", alpha=0.12,
                       lw=0, label=f"μs·(1 ± {friction_scatter:g})")
        ax.axvline(mu_best, color="C2" if recommended else "C3", lw=1.0, ls="--", label=shown)
    ax1.annotate("tan α", (tan_alpha, top * 0.97), xytext=(3, 0), textcoords="offset points", fontsize=8,
                 color="0.35", va="top")
    ax1.set_ylim(0.0, top)
    ax1.set_ylabel("peak |θ|/α")
    ax1.set_title("peak rotation of the statue at μs", loc="left", fontsize=9)
    ax2.plot(mu, [1e3 * r["clearance"] for r in rows], "-o", ms=3, lw=1.2, color="C1")
    if sliding_limit is not None:
        ax2.axhline(1e3 * sliding_limit, color="0.2", lw=0.9, ls="-.", label="sliding limit")
    ax2.legend(fontsize=8, loc="upper right")
    ax2.set_ylabel("free space needed (mm)")
    ax2.set_xlabel("pedestal floor friction μs")
    ax2.set_title("largest peak sliding of the pedestal over the friction scatter", loc="left", fontsize=9)
    for ax in (ax1, ax2):
        ax.grid(True, lw=0.3, alpha=0.6)
    fig.savefig(path, dpi=dpi, metadata={"Software": None})


def _describe(row: Mapping[str, Any]) -> str:
    if row["overturned"]:
        at = f"overturns at {row['overturn_time']:.2f} s"
    else:
        at = f"peak {row['peak_rotation_over_alpha']:.3f} α, pedestal slides at most {1e3 * row['peak_sliding']:.1f} mm"
    judged = ("safe" if row["safe"] else "falls within the scatter" if row["falls"]
              else "undetermined within the scatter")
    return (f"{at}; {judged}, needs {1e3 * row['clearance']:.1f} mm of free space"
            + ("" if row["meets_limits"] else ", misses a limit")
            + ("; μs inverts the concept" if row["inverted"] else ""))


#: Configuration keys the library's messages name, in the words of the web page's form.
_FORM_WORDS = (
    ("raise simulation.free_time_limit or simulation.duration", "enter a longer duration"),
    ("simulation.free_time_limit", "the free-motion limit"),
    ("simulation.duration", "the duration"),
)


def page_words(text: str) -> str:
    """A library message with the configuration keys it names replaced by the form's words."""
    for key, words in _FORM_WORDS:
        text = text.replace(key, words)
    return text


def _public_rows(rows: list[tuple[str, str]], duration: float | None) -> list[tuple[str, str]]:
    """Input rows as a museum engineer reads them: no file path of this server, no class or
    configuration key names."""
    out = []
    for name, value in rows:
        if name in ("source", "configuration file"):
            continue  # a path on this server (a bundled record's, or an upload's temporary folder)
        if name == "kind":
            value = {"GroundMotion": "recorded floor acceleration"}.get(value, "floor motion")
        if name == "simulated" and duration is not None:
            value = value.split(" (")[0] + f" (the duration entered, {duration:g} s)"
        out.append((name, value))
    return out


def _sweep_figure_text(number: int, recommended: bool, scatter: float) -> Any:
    from ..report.content import FigureText

    chosen = "the recommended μs" if recommended else "the value with the fewest falls (none is safe)"
    return FigureText(
        number=number,
        heading="Friction design sweep",
        discussion=(f"Figure {number} shows the friction design sweep: each value of the pedestal's floor friction μs "
                    f"was run at μs and μs·(1 ± {scatter:g}); the dashed line marks {chosen}, the run this report "
                    "describes. The table below gives every value."),
        caption=("Peak rotation of the statue (top, capped at 2 α; triangles: falls or undetermined within the "
                 "scatter) and the free space the pedestal needs (bottom) against the pedestal's floor friction μs."),
    )


def _write_sweep_report(cfg_best: Any, response: Any, out: Path, *, title: str, sweep_rows: list[tuple[str, str]],
                        table: list[tuple[str, str]], duration: float | None, sweep_png: Path, recommended: bool,
                        scatter: float, dpi: int) -> None:
    """``report.html`` and ``report.pdf`` of the report's run, with the sweep (its chart and a row
    per μs) added to the report :func:`rocking.report.write_report` would write."""
    from ..report.content import build_content, verdict_class
    from ..report.html import png_base64, write_html
    from ..report.pdf import write_pdf
    from ..viz.plots import plot_energy, plot_response

    content = build_content(response, cfg_best, title=title)
    content.verdict = page_words(content.verdict)
    content.warnings = [page_words(w) for w in content.warnings]
    content.checks = [dataclasses.replace(c, value=page_words(c.value), limit=page_words(c.limit),
                                          warning=c.warning and page_words(c.warning)) for c in content.checks]
    content.inputs = {k: _public_rows(v, duration) for k, v in content.inputs.items()}
    content.inputs["Friction design sweep"] = sweep_rows
    content.inputs["Every value of μs swept"] = table
    content.provenance = None if content.provenance is None else type(content.provenance)(
        content.provenance.version, content.provenance.date, "the web page's inputs", content.provenance.input_hash)
    content.source = None
    figures = [plot_response(response), plot_energy(response).figure]
    content.figures = [*content.figures, _sweep_figure_text(len(content.figures) + 1, recommended, scatter)]
    images = [png_base64(fig, dpi) for fig in figures]
    images.append(base64.b64encode(sweep_png.read_bytes()).decode("ascii"))
    klass = verdict_class(response, content.checks)
    write_html(content, images, out / "report.html", verdict_class=klass)
    write_pdf(content, [*figures, _sweep_chart_figure(sweep_png)], out / "report.pdf", verdict_class=klass)


def _sweep_chart_figure(png: Path) -> Any:
    """The sweep chart as a matplotlib figure (the PDF draws figures, not files)."""
    from matplotlib.figure import Figure
    from PIL import Image

    image = np.asarray(Image.open(png).convert("RGB"))
    h, w = image.shape[:2]
    fig = Figure(figsize=(7.0, 7.0 * h / w))
    ax = fig.add_axes((0, 0, 1, 1))
    ax.imshow(image)
    ax.set_axis_off()
    return fig


def sweep_task(
    *,
    config: Mapping[str, Any],
    frictions: list[float],
    out_dir: str,
    sliding_limit: float | None = None,
    friction_scatter: float | None = None,
    dpi: int = 90,
    progress: Progress = _no_progress,
) -> dict[str, Any]:
    """Sweep the pedestal's floor friction μs over ``frictions`` (μk/μs kept as in ``config``) under
    the configured record with :func:`rocking.analyses.design.friction_design` (its ranking and
    verdict, the same as ``rocking design``), and write ``sweep.csv``, ``sweep.png``, the report
    of the value it recommends (``report.html`` and ``report.pdf`` from
    :func:`rocking.report.write_report`; with no safe value, of the one with the fewest falls) and
    ``sweep-report.zip`` with all of them.

    Parameters
    ----------
    sliding_limit : float, optional
        Largest acceptable peak sliding of the pedestal, m (the free space around it).
    friction_scatter : float, optional
        Relative scatter s of the floor friction (default that of ``friction_design``, 0.2).

    Returns
    -------
    dict
        ``rows`` (one per μs), ``best`` (the row the report shows), ``recommended`` (whether it is
        a recommendation), ``meets_limits`` (whether it meets every requirement), ``design_verdict``
        (the first line) and ``design_lines`` (the ways out and warnings), ``verdict`` (of the
        report's single run), ``rule``, ``friction_scatter``, ``tan_alpha``, ``ratio`` (μk/μs),
        ``duration``, ``method``, ``files``.
    """
    from ..io.config import load_config
    from ..report import verdict
    from ..runner import run_response

    if not config.get("pedestal"):
        raise ValueError("the friction design sweep varies the pedestal's floor friction: add a pedestal")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    cfg = load_config(dict(config))
    system, motion, options, duration = cfg.to_specs()
    fr = system.pedestal.friction
    ratio = fr.mu_k / fr.mu_s if fr.mu_s > 0 else 1.0
    from ..analyses.design import DEFAULT_FRICTION_SCATTER, friction_design, friction_factors, ranking_rule

    scatter = DEFAULT_FRICTION_SCATTER if friction_scatter is None else float(friction_scatter)
    n = len(frictions)
    n_runs = n * len(friction_factors(scatter))
    total = n_runs + 1
    progress(0, total, "starting")
    method = "friction design"
    end = float(motion.duration)
    if duration is None:  # the motion, then free motion until at rest (capped)
        shaken, free = motion, options.free_time_limit
    else:
        shaken = motion.trimmed(duration) if duration < end else motion
        free = max(0.0, duration - end)
    rows, ds = _rows_by_design(friction_design, system, shaken, frictions, ratio, options,
                               free, sliding_limit, scatter, progress, total)
    progress(n_runs, total, "writing the report")
    a = ds.attrs
    lines = str(a["verdict_lines"]).split("\n")
    if shaken is not motion:
        # the design saw the record cut at the duration: say that its verdicts judge that window
        lines.append(f"Warning: the record was cut at {duration:g} s, the duration entered (it lasts {end:g} s): "
                     f"these verdicts judge the first {duration:g} s only, and the rest of the record may yet make the statue fall.")
    recommended = math.isfinite(a["recommended_mu_s"])
    meets = bool(a["meets_every_requirement"])
    # the single run the report shows: the recommendation; with none (no value is safe), the
    # value the design names as the one with the fewest falls
    shown = a["recommended_mu_s"] if recommended else a["fewest_overturns_mu_s"]
    best = next(r for r in rows if r["static_friction"] == shown)
    rule = ranking_rule(scatter, a["objective"])
    chosen = json.loads(json.dumps(config))
    chosen["pedestal"]["friction"] = {"static": best["static_friction"], "kinetic": best["kinetic_friction"]}
    if duration is not None:
        chosen.setdefault("simulation", {})["duration"] = duration
    cfg_best, response = run_response(chosen)
    _write_csv(rows, out / "sweep.csv")
    _plot_sweep(rows, best, out / "sweep.png", dpi, recommended=recommended, friction_scatter=scatter,
                tan_alpha=float(a["tan_alpha"]), sliding_limit=sliding_limit)
    sweep_rows = [
        ("values of the pedestal's floor friction μs", f"{n}, from {frictions[0]:g} to {frictions[-1]:g}"),
        ("μk/μs", f"{ratio:g}"),
        ("friction scatter s", f"{scatter:g} (each value also runs at μs·(1 ± s), μk alike)"),
        ("verdict", " ".join(lines)),
        ("recommended μs", f"{best['static_friction']:g}" if recommended else "none: no value is safe"),
        ("rule", rule),
    ]
    table = [(f"μs = {r['static_friction']:.4g}", _describe(r)) for r in rows]
    if recommended and meets:
        which = "the recommended"
    elif recommended:
        which = "the recommended (safe, but not within every limit)"
    else:
        which = "no safe value; the fewest falls with"
    title = f"Friction design sweep — {which} pedestal floor friction μs = {best['static_friction']:.4g}"
    _write_sweep_report(cfg_best, response, out, title=title, sweep_rows=sweep_rows, table=table, duration=duration,
                        sweep_png=out / "sweep.png", recommended=recommended, scatter=scatter, dpi=dpi)
    files = ["report.html", "report.pdf", "sweep.csv", "sweep.png"]
    with zipfile.ZipFile(out / "sweep-report.zip", "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name in files:
            if (out / name).exists():
                zf.write(out / name, arcname=name)
    progress(total, total, "done")
    return {
        "rows": rows,
        "best": best,
        "recommended": recommended,
        "meets_limits": meets,
        "design_verdict": lines[0],
        "design_lines": lines[1:],
        "rule": rule,
        "friction_scatter": scatter,
        "tan_alpha": float(a["tan_alpha"]),
        "ratio": ratio,
        "duration": response.end_time,
        "method": method,
        "verdict": page_words(verdict(response)),
        "files": [name for name in files if (out / name).exists()] + ["sweep-report.zip"],
    }
