"""Figures of the seed paper's case studies (its Figs. 9–12) and of the pedestal design study.

Every function returns a :class:`matplotlib.figure.Figure` built on the Agg backend (no display
needed); nothing here computes physics: the data come from :mod:`rocking.analyses.paper`.

Layout of a case figure, as in the paper:

* (a.1) displacement u(t) of the pedestal relative to the floor;
* (a.2) rotation θ/α of the statue on the pedestal, with the lines θ = ±α;
* (a.3) rotation θ/α of the same statue alone: with infinite friction (the paper's baseline,
  solid) and on the same floor friction as the pedestal (dashed).

In (a.1) and (a.2) the solid line is this library's default model (full normal force, Coulomb
impact); the dashed line uses the paper's options (N = M·g, θ̇⁺ = r·θ̇⁻).

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

from ..analyses import paper as _paper  # noqa: E402
from ..results.response import Response  # noqa: E402

__all__ = [
    "plot_comparison",
    "plot_paper_case",
    "write_paper_figures",
    "plot_friction_sweep",
    "write_design_insight",
]

_SOLID = {"lw": 1.1}
_DASHED = {"lw": 1.0, "ls": "--"}


def _theta_limit(responses: Sequence[Response]) -> float:
    """Common vertical scale for θ/α panels (the paper keeps scales homogeneous)."""
    peak = max((r.peak_rotation / r.alpha for r in responses), default=0.0)
    return 1.3 if peak <= 1.2 else 2.0


def _draw_theta(ax, response: Response, label: str, style: dict, color: str, limit: float) -> None:
    ax.plot(response.t, response.theta / response.alpha, color=color, label=label, **style)
    if response.overturned and response.overturn_time is not None:
        side = math.copysign(1.0, response.theta[-1]) if response.theta.size else 1.0
        y = 0.92 * limit * side
        ax.plot([response.overturn_time], [y], marker="x", ms=9, mew=2, color=color, ls="none")
        ax.annotate(
            f"falls at {response.overturn_time:.2f} s",
            (response.overturn_time, y),
            xytext=(6, -12 if side > 0 else 6),
            textcoords="offset points",
            color=color,
            fontsize=8,
        )


def _alpha_lines(ax, limit: float) -> None:
    for y in (1.0, -1.0):
        ax.axhline(y, color="0.45", lw=0.8, ls=":")
    ax.axhline(0.0, color="0.8", lw=0.6)
    ax.set_ylim(-limit, limit)
    ax.set_ylabel("θ/α")


def plot_comparison(
    pedestal: Mapping[str, Response],
    alone: Mapping[str, Response],
    title: str,
    *,
    figsize: tuple[float, float] = (9.0, 7.5),
) -> Figure:
    """Three stacked panels: pedestal u(t), θ/α on the pedestal, θ/α of the statue alone.

    Parameters
    ----------
    pedestal, alone : mapping of label → Response
        Runs with a pedestal (panels a.1, a.2) and without (panel a.3). The first of each is drawn
        solid, the second dashed (more are drawn dotted).
    title : str
        Figure title (say the case and the model options).
    """
    fig = Figure(figsize=figsize, layout="constrained")
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    styles = [_SOLID, _DASHED, {"lw": 1.0, "ls": ":"}]
    limit = _theta_limit(list(pedestal.values()) + list(alone.values()))

    for i, (label, r) in enumerate(pedestal.items()):
        color = f"C{i}"
        ax1.plot(r.t, r.u, color=color, label=label, **styles[min(i, 2)])
        _draw_theta(ax2, r, label, styles[min(i, 2)], color, limit)
    for i, (label, r) in enumerate(alone.items()):
        _draw_theta(ax3, r, label, styles[min(i, 2)], f"C{i + 2}", limit)

    ax1.axhline(0.0, color="0.8", lw=0.6)
    ax1.set_ylabel("u (m)")
    ax1.set_title("(a.1) pedestal displacement relative to the floor", loc="left", fontsize=9)
    _alpha_lines(ax2, limit)
    ax2.set_title("(a.2) statue on the pedestal", loc="left", fontsize=9)
    _alpha_lines(ax3, limit)
    ax3.set_title("(a.3) statue alone on the floor", loc="left", fontsize=9)
    ax3.set_xlabel("t (s)")
    for ax in (ax1, ax2, ax3):
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
        ax.grid(True, lw=0.3, alpha=0.5)
    end = max((r.duration for r in (*pedestal.values(), *alone.values())), default=1.0)
    ax3.set_xlim(0.0, end)
    fig.suptitle(title, fontsize=9.5)
    return fig


def _case_title(case: _paper.PaperCase, response: Response) -> str:
    motion, t1 = response.motion, _paper.TABLE_1
    return (
        f"{case.figure}: statue B × H = {t1.width:g} × {case.height:g} m (B/H = {case.aspect_ratio:.2f}), "
        f"m2 = {case.statue_mass:g} kg, r = {t1.restitution}; pedestal m1 = {t1.pedestal_mass:g} kg on "
        f"μs = {t1.static_friction}, μk = {t1.kinetic_friction}\n"
        f"ẍg = {motion.amplitude} {motion.form}(ωt) m/s², ω = {motion.omega:.4f} s⁻¹, {case.cycles} cycles, "
        f"g = {response.options.gravity} m/s².  Paper: alone {case.alone_claim}; on pedestal {case.pedestal_claim}.\n"
        "solid: normal_force='full', impact='coulomb' (default);  dashed: normal_force='paper', impact='paper'"
    )


def plot_paper_case(case: _paper.PaperCase | str, responses: Mapping[str, Response]) -> Figure:
    """One of the paper's Figs. 9–12 redrawn from :func:`rocking.analyses.paper.run_case`.

    Parameters
    ----------
    case : PaperCase or str
        The case (or its name, "9a" … "12b").
    responses : mapping variant → Response
        Must hold the four :data:`rocking.analyses.paper.VARIANTS`.
    """
    if isinstance(case, str):
        case = _paper.case_named(case)
    labels = _paper.VARIANT_LABELS
    pedestal = {labels[v]: responses[v] for v in ("pedestal", "pedestal_paper_options")}
    alone = {labels[v]: responses[v] for v in ("alone_infinite_friction", "alone_floor_friction")}
    return plot_comparison(pedestal, alone, _case_title(case, responses["pedestal"]))


def write_paper_figures(
    responses: Mapping[tuple[str, str], Response], out_dir: str | Path, *, dpi: int = 110
) -> list[Path]:
    """Write ``paper_fig_<case>.png`` for every case present in ``responses``
    (``{(case, variant): Response}``, as filled by :func:`run_paper_cases`)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    names = list(dict.fromkeys(name for name, _ in responses))
    for name in names:
        per_case = {v: r for (c, v), r in responses.items() if c == name}
        fig = plot_paper_case(name, per_case)
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
