"""Figures of the seed paper's case studies (its Figs. 9–12) and of the pedestal design study.

Every function returns a :class:`matplotlib.figure.Figure` built on the Agg backend (no display
needed); nothing here computes physics: the data come from :mod:`rocking.analyses.paper`.

Layout of a case figure, as in the paper (panels (a.1)–(a.3) for the "a" cases, (b.1)–(b.3) for
the "b" cases):

* (a.1) sliding u(t) on the floor: of the pedestal, and of the statue standing alone on the same
  floor friction;
* (a.2) rotation θ/α of the statue on the pedestal, with the lines θ = ±α;
* (a.3) rotation θ/α of the same statue alone: with infinite friction (the paper's baseline) and
  on the same floor friction as the pedestal.

Each run keeps its colour and line in every panel; one legend below the panels names the runs
(with the model options) and the markers: ○ where |θ| first exceeds α, ▲/▼ on the edge of the
plot where a statue falls (|θ| = π/2 lies far beyond the common scale). The parameters go in a
caption under the legend, the title is one short line. :func:`write_paper_figures` draws the
eight figures on one vertical scale (the paper's "homogeneous scale").

Regenerate the design-study images of ``docs/design-insight.md`` with
``python -m rocking.viz.paper_figures docs/img``.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")

from matplotlib.figure import Figure  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from ..analyses import paper as _paper  # noqa: E402
from ..results.response import Response  # noqa: E402

__all__ = [
    "plot_comparison",
    "plot_paper_case",
    "paper_case_figures",
    "shared_limits",
    "write_paper_figures",
    "plot_friction_sweep",
    "write_design_insight",
]

_PEDESTAL_STYLES = ({"lw": 1.1}, {"lw": 1.0, "ls": "--"}, {"lw": 1.0, "ls": ":"})
_ALONE_STYLES = ({"lw": 1.1}, {"lw": 1.0, "ls": "-."}, {"lw": 1.0, "ls": ":"})
_ALPHA_MARKER = {"marker": "o", "ms": 6, "mfc": "white", "mew": 1.4, "ls": "none", "zorder": 5}
_FALL_MARKER = {"ms": 9, "ls": "none", "clip_on": False, "zorder": 6}

_LEGEND_ROW = 0.19  # in, one row of the legend at fontsize 7.5
_CAPTION_LINE = 0.16  # in, one line of the caption


def _key_height(entries: int, caption: str | None) -> float:
    """Height (in) of the strip under the panels: a two-column legend and the caption."""
    lines = caption.count("\n") + 1 if caption else 0
    return 0.08 + _LEGEND_ROW * math.ceil(entries / 2) + _CAPTION_LINE * lines


#: Smallest half-range of the θ/α panels: the lines θ = ±α always show, with a margin.
MIN_THETA_LIMIT = 1.25


def _nice_ceil(value: float, step: float) -> float:
    return step * math.ceil(value / step - 1e-9)


def _theta_limit(responses: Sequence[Response]) -> float:
    """Half-range of the θ/α panels: the largest peak of the runs that did not fall, with a margin.

    A statue that falls reaches |θ| = π/2 (8α for H = 5 m); scaling to it would flatten every
    other curve, so falls leave the plot and are marked on its edge."""
    standing = [r.peak_rotation / r.alpha for r in responses if not r.overturned]
    return max(MIN_THETA_LIMIT, _nice_ceil(1.08 * max(standing, default=0.0), 0.25))


def _u_limit(responses: Sequence[Response]) -> float:
    """Half-range of the sliding panel, m (at least 1 cm, so a run that never slides reads as 0)."""
    peak = max((float(abs(r.u).max()) for r in responses if r.u.size), default=0.0)
    return max(0.01, _nice_ceil(1.08 * peak, 0.01))


def shared_limits(responses: Mapping[Any, Response]) -> tuple[float, float]:
    """``(theta_limit, u_limit)``: one vertical scale (θ/α and m) for every figure drawn from
    ``responses``, as the paper keeps its scales homogeneous."""
    runs = list(responses.values())
    return _theta_limit(runs), _u_limit(runs)


def _side(response: Response, time: float) -> float:
    """Sign of θ at the first saved sample at or after ``time`` (which way the statue leans)."""
    after = response.theta[response.t >= time]
    lean = after[0] if after.size else (response.theta[-1] if response.theta.size else 1.0)
    return math.copysign(1.0, lean)


def _run_label(label: str, response: Response) -> str:
    """The legend entry of a run: its name and, when they happen, when it passes α and falls."""
    notes = []
    if response.exceeded_alpha_time is not None:
        notes.append(f"|θ| > α at {response.exceeded_alpha_time:.2f} s")
    if response.overturned and response.overturn_time is not None:
        notes.append(f"falls at {response.overturn_time:.2f} s")
    return f"{label}: {', '.join(notes)}" if notes else label


def _draw_theta(ax, response: Response, label: str, style: Mapping[str, Any], color: str, limit: float) -> None:
    ax.plot(response.t, response.theta / response.alpha, color=color, label=label, **style)
    crossing = response.exceeded_alpha_time
    if crossing is not None:
        ax.plot([crossing], [_side(response, crossing)], color=color, gid="exceeds_alpha", **_ALPHA_MARKER)
    if response.overturned and response.overturn_time is not None:
        side = _side(response, response.overturn_time)
        ax.plot([response.overturn_time], [side * limit], marker="^" if side > 0 else "v", color=color,
                gid="falls", **_FALL_MARKER)


def _alpha_lines(ax, limit: float) -> None:
    for y in (1.0, -1.0):
        ax.axhline(y, color="0.45", lw=0.8, ls=":")
    ax.axhline(0.0, color="0.8", lw=0.6)
    ax.set_ylim(-limit, limit)
    ax.set_ylabel("θ/α")


def _marker_keys(responses: Sequence[Response]) -> list[tuple[Line2D, str]]:
    """Legend entries for the markers that appear in the figure."""
    keys = []
    if any(r.exceeded_alpha_time is not None for r in responses):
        keys.append((Line2D([], [], color="0.2", **_ALPHA_MARKER), "first |θ| > α"))
    if any(r.overturned for r in responses):
        fall = {k: v for k, v in _FALL_MARKER.items() if k != "clip_on"}
        keys.append((Line2D([], [], color="0.2", marker="^", **fall), "falls (|θ| = π/2, off the scale)"))
    return keys


def _figure_legend(key: Figure, axes, responses: Sequence[Response]) -> None:
    """One legend for the panels, each run once (a run drawn in two panels has one entry)."""
    entries: dict[str, Any] = {}
    for ax in axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    for handle, label in _marker_keys(responses):
        entries.setdefault(label, handle)
    key.legend(list(entries.values()), list(entries.keys()), loc="upper center", ncols=2, fontsize=7.5,
               frameon=False, borderaxespad=0.2)


def plot_comparison(
    pedestal: Mapping[str, Response],
    alone: Mapping[str, Response],
    title: str,
    *,
    caption: str | None = None,
    panel: str = "a",
    theta_limit: float | None = None,
    u_limit: float | None = None,
    figsize: tuple[float, float] = (9.0, 8.2),
) -> Figure:
    """Three stacked panels: sliding on the floor, θ/α on the pedestal, θ/α of the statue alone.

    Parameters
    ----------
    pedestal, alone : mapping of label → Response
        Runs with a pedestal (panels 1 and 2) and without (panel 3; a statue alone that can slide
        also appears in panel 1). The first of each is drawn solid, the second dashed (pedestal)
        or dash-dotted (alone), more dotted.
    title : str
        Figure title, one short line.
    caption : str, optional
        Text under the legend (the parameters of the runs).
    panel : str
        Letter of the panel labels: "a" gives (a.1)–(a.3), "b" gives (b.1)–(b.3).
    theta_limit, u_limit : float, optional
        Half-range of the θ/α panels and of the sliding panel (m); by default fitted to these runs.
    """
    runs = [*pedestal.values(), *alone.values()]
    fig = Figure(figsize=figsize, layout="constrained")
    # The panels above, the legend and the caption below, apart: no legend covers a curve.
    key_height = _key_height(len(runs) + len(_marker_keys(runs)), caption)
    plots, key = fig.subfigures(2, 1, height_ratios=(figsize[1] - key_height, key_height))
    ax1, ax2, ax3 = plots.subplots(3, 1, sharex=True)
    limit = theta_limit if theta_limit is not None else _theta_limit(runs)
    u_half = u_limit if u_limit is not None else _u_limit(runs)

    for i, (label, r) in enumerate(pedestal.items()):
        color, style, name = f"C{i}", _PEDESTAL_STYLES[min(i, 2)], _run_label(label, r)
        ax1.plot(r.t, r.u, color=color, label=name, **style)
        _draw_theta(ax2, r, name, style, color, limit)
    for i, (label, r) in enumerate(alone.items()):
        color, style, name = f"C{i + 2}", _ALONE_STYLES[min(i, 2)], _run_label(label, r)
        if r.system.statue.friction is not None:
            ax1.plot(r.t, r.u, color=color, label=name, **style)
        _draw_theta(ax3, r, name, style, color, limit)

    ax1.axhline(0.0, color="0.8", lw=0.6)
    ax1.set_ylabel("u (m)")
    ax1.set_ylim(-u_half, u_half)
    ax1.set_title(f"({panel}.1) sliding on the floor", loc="left", fontsize=9)
    _alpha_lines(ax2, limit)
    ax2.set_title(f"({panel}.2) statue on the pedestal", loc="left", fontsize=9)
    _alpha_lines(ax3, limit)
    ax3.set_title(f"({panel}.3) statue alone on the floor", loc="left", fontsize=9)
    ax3.set_xlabel("t (s)")
    for ax in (ax1, ax2, ax3):
        ax.grid(True, lw=0.3, alpha=0.5)
    end = max((r.duration for r in runs), default=1.0)
    ax3.set_xlim(0.0, end)
    _figure_legend(key, (ax2, ax3, ax1), runs)  # the runs in their order: on the pedestal, then alone
    fig.suptitle(title, fontsize=10.5)
    if caption:
        key.text(0.5, 0.04, caption, ha="center", va="bottom", fontsize=7.5, color="0.25")
    return fig


#: Legend names of the four runs in a case figure (the model options spelled as in the API).
CASE_RUN_LABELS = {
    "pedestal": "on pedestal, default model (normal_force='full', impact='coulomb')",
    "pedestal_paper_options": "on pedestal, paper's options (normal_force='paper', impact='paper')",
    "alone_infinite_friction": "alone, μ = ∞ (the paper's baseline)",
    "alone_floor_friction": (
        f"alone, on the pedestal's floor "
        f"(μs = {_paper.TABLE_1.static_friction}, μk = {_paper.TABLE_1.kinetic_friction})"
    ),
}


def _case_title(case: _paper.PaperCase) -> str:
    width = _paper.TABLE_1.width
    return f"{case.figure} rerun: statue {width:g} × {case.height:g} m, m2 = {case.statue_mass:g} kg"


def _case_caption(case: _paper.PaperCase, response: Response) -> str:
    motion, t1 = response.motion, _paper.TABLE_1
    return (
        f"Statue B × H = {t1.width:g} × {case.height:g} m (B/H = {case.aspect_ratio:.2f}), "
        f"m2 = {case.statue_mass:g} kg, r = {t1.restitution}; pedestal m1 = {t1.pedestal_mass:g} kg; "
        f"floor μs = {t1.static_friction}, μk = {t1.kinetic_friction}.\n"
        f"ẍg = {motion.amplitude} {motion.form}(ωt) m/s², ω = {motion.omega:.4f} s⁻¹, {case.cycles} cycles, "
        f"g = {response.options.gravity} m/s².  The paper says: alone, {case.alone_claim}; "
        f"on the pedestal, {case.pedestal_claim}."
    )


def plot_paper_case(
    case: _paper.PaperCase | str,
    responses: Mapping[str, Response],
    *,
    theta_limit: float | None = None,
    u_limit: float | None = None,
) -> Figure:
    """One of the paper's Figs. 9–12 redrawn from :func:`rocking.analyses.paper.run_case`.

    Parameters
    ----------
    case : PaperCase or str
        The case (or its name, "9a" … "12b"); a "b" case gets the panel labels (b.1)–(b.3).
    responses : mapping variant → Response
        Must hold the four :data:`rocking.analyses.paper.VARIANTS`.
    theta_limit, u_limit : float, optional
        Half-range of the θ/α panels and of the sliding panel (m), to share one scale between
        figures (:func:`shared_limits`); by default fitted to this case.
    """
    if isinstance(case, str):
        case = _paper.case_named(case)
    pedestal = {CASE_RUN_LABELS[v]: responses[v] for v in ("pedestal", "pedestal_paper_options")}
    alone = {CASE_RUN_LABELS[v]: responses[v] for v in ("alone_infinite_friction", "alone_floor_friction")}
    return plot_comparison(
        pedestal,
        alone,
        _case_title(case),
        caption=_case_caption(case, responses["pedestal"]),
        panel=case.name[-1],
        theta_limit=theta_limit,
        u_limit=u_limit,
    )


def paper_case_figures(responses: Mapping[tuple[str, str], Response]) -> dict[str, Figure]:
    """``{case: Figure}`` for every case in ``responses`` (``{(case, variant): Response}``, as
    filled by :func:`rocking.analyses.paper.run_paper_cases`), all on one vertical scale."""
    theta_limit, u_limit = shared_limits(responses)
    names = list(dict.fromkeys(name for name, _ in responses))
    return {
        name: plot_paper_case(
            name,
            {v: r for (c, v), r in responses.items() if c == name},
            theta_limit=theta_limit,
            u_limit=u_limit,
        )
        for name in names
    }


def write_paper_figures(
    responses: Mapping[tuple[str, str], Response], out_dir: str | Path, *, dpi: int = 110
) -> list[Path]:
    """Write ``paper_fig_<case>.png`` for every case present in ``responses``
    (``{(case, variant): Response}``, as filled by :func:`run_paper_cases`), on one scale."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, fig in paper_case_figures(responses).items():
        path = out / f"paper_fig_{name}.png"
        fig.savefig(path, dpi=dpi)
        paths.append(path)
    return paths


# ---------------------------------------------------------------------------------------------
# Design study
# ---------------------------------------------------------------------------------------------
def plot_friction_sweep(sweeps: Mapping[str, Sequence[Mapping[str, Any]]], *, title: str | None = None) -> Figure:
    """Peak θ/α, peak sliding and overturning time versus the pedestal's floor friction μs.

    Parameters
    ----------
    sweeps : mapping of label → rows of :func:`rocking.analyses.paper.friction_sweep`
        One curve per sweep (same statue in all, for the tan α marks).
    """
    fig = Figure(figsize=(8.5, 8.0), layout="constrained")
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    first = next(iter(sweeps.values()))
    tan_alpha, ratio = first[0]["tan_alpha"], first[0]["kinetic_friction"] / first[0]["static_friction"]
    top = 2.0
    for i, (label, rows) in enumerate(sweeps.items()):
        color = f"C{i}"
        mu = [r["static_friction"] for r in rows]
        peak = [min(r["peak_rotation_over_alpha"], top) for r in rows]
        ax1.plot(mu, peak, "-", color=color, lw=1.2, label=label)
        fell = [(r["static_friction"], top * 0.97) for r in rows if r["overturned"]]
        if fell:
            ax1.plot(*zip(*fell), "v", color=color, ms=5, ls="none", label=f"{label}: overturns")
        ax1.axhline(
            min(rows[0]["alone_peak_rotation_over_alpha"], top),
            color=color,
            lw=0.8,
            ls="--",
            label=f"{label}: statue alone (μ = ∞)" + (" overturns" if rows[0]["alone_overturned"] else ""),
        )
        ax2.plot(mu, [r["peak_sliding"] for r in rows], "-", color=color, lw=1.2, label=label)
        times = [(r["static_friction"], r["overturn_time"]) for r in rows if r["overturned"]]
        if times:
            ax3.plot(*zip(*times), "o", color=color, ms=4, ls="none", label=f"{label}: on pedestal")
        if rows[0]["alone_overturned"]:
            ax3.axhline(rows[0]["alone_overturn_time"], color=color, lw=0.8, ls="--", label=f"{label}: statue alone")
    for ax in (ax1, ax2, ax3):
        ax.axvline(tan_alpha, color="k", lw=0.9)
        ax.axvline(tan_alpha / ratio, color="k", lw=0.9, ls=":")
        ax.grid(True, lw=0.3, alpha=0.5)
    ax1.axhline(1.0, color="0.45", lw=0.8, ls=":")
    ax1.set_ylim(0.0, top)
    ax1.set_ylabel("peak |θ|/α")
    ax1.text(tan_alpha, top * 0.3, " μs = tan α\n (O17: no rocking\n  to the left)", fontsize=8, va="center")
    ax1.text(tan_alpha / ratio, top * 0.72, f" μk = tan α\n (μs = {tan_alpha / ratio:.3f})", fontsize=8, va="center")
    ax1.set_title("(a) peak rotation of the statue on the pedestal (▼: overturned)", loc="left", fontsize=9)
    ax1.legend(fontsize=7, loc="upper left")
    ax2.set_ylabel("peak |u| (m)")
    ax2.set_title("(b) peak sliding of the pedestal", loc="left", fontsize=9)
    ax2.legend(fontsize=7)
    ax3.set_ylabel("overturning time (s)")
    ax3.set_xlabel(f"pedestal floor friction μs (μk = {ratio:g} μs)")
    ax3.set_title("(c) when the statue falls: on the pedestal vs alone", loc="left", fontsize=9)
    if ax3.get_legend_handles_labels()[0]:
        ax3.legend(fontsize=7)
    r0 = first[0]
    fig.suptitle(
        title
        or (
            f"Statue B × H = 1 × {r0['height']:g} m (tan α = {tan_alpha:g}), m2 = {r0['statue_mass']:g} kg, r = 0.8, "
            f"on a pedestal m1 = {r0['pedestal_mass']:g} kg; ẍg = A cos ωt, ω = {r0['omega']:.4f} s⁻¹\n"
            "model: normal_force='full', impact='coulomb' (default); vertical lines: μs = tan α and μk = tan α"
        ),
        fontsize=9,
    )
    return fig


#: The "only delayed" example of docs/design-insight.md: A = 10 m/s², H = 4 m, m1 = m2 = 1 kg.
DELAY_AMPLITUDE = 10.0
DELAY_FRICTION = 0.64


def write_design_insight(out_dir: str | Path, *, dpi: int = 110) -> list[Path]:
    """Run the design study and write ``design_insight.png`` (μs sweep at the paper's A = 6.75 m/s²
    and at A = 10 m/s²) and ``design_delay.png`` (a pedestal that only delays overturning)."""
    from ..contact.friction import Friction
    from ..excitation.harmonic import Harmonic
    from ..models.bodies import Pedestal, Statue, System
    from ..simulation import Options, simulate

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    sweeps = {
        f"A = {_paper.TABLE_1.amplitude} m/s² (paper)": _paper.friction_sweep(),
        f"A = {DELAY_AMPLITUDE:g} m/s²": _paper.friction_sweep(amplitude=DELAY_AMPLITUDE),
    }
    paths = [out / "design_insight.png", out / "design_delay.png"]
    plot_friction_sweep(sweeps).savefig(paths[0], dpi=dpi)

    # One μs inside the narrow band where the pedestal only delays the fall.
    t1 = _paper.TABLE_1
    options = Options(gravity=t1.gravity)
    motion = Harmonic(amplitude=DELAY_AMPLITUDE, frequency=t1.frequency, cycles=30)
    statue = Statue(width=1.0, height=4.0, mass=1.0, restitution=t1.restitution)
    runs = {}
    for mu in (DELAY_FRICTION, 0.60):
        ped = Pedestal(mass=1.0, friction=Friction(static=mu, kinetic=0.75 * mu))
        runs[f"on pedestal μs = {mu:g}, μk = {0.75 * mu:g}"] = simulate(
            System(statue=statue, pedestal=ped), motion, options=options
        )
    alone = {"alone, μ = ∞": simulate(System(statue=statue), motion, options=options)}
    title = (
        f"Statue 1 × 4 m, m2 = 1 kg, r = 0.8, pedestal m1 = 1 kg; ẍg = {DELAY_AMPLITUDE:g} cos(ωt) m/s², "
        f"ω = {motion.omega:.4f} s⁻¹, 30 cycles, g = {t1.gravity} m/s²\n"
        "model: normal_force='full', impact='coulomb' (default)\n"
        f"μs = {DELAY_FRICTION:g}: the pedestal only delays the fall;  μs = 0.6: it avoids it"
    )
    plot_comparison(runs, alone, title).savefig(paths[1], dpi=dpi)
    return paths


if __name__ == "__main__":  # pragma: no cover
    for p in write_design_insight(sys.argv[1] if len(sys.argv) > 1 else "."):
        print(p)
