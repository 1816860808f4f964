"""Plots of one simulation and of the studies built from many (matplotlib, no display needed).

Every function draws into the ``ax`` (or ``axes``) it is given, or into a new
:class:`matplotlib.figure.Figure` (not a pyplot figure: safe in a web server or a worker), and
returns the Axes, or the Figure for multi-panel plots. Nothing here computes physics: the data
come from a :class:`~rocking.results.response.Response` or from arrays the analyses produced; the
only formula evaluated is the mechanical energy of the saved states (:func:`energy_series`).

Conventions: SI units in every label except sliding, shown in mm; rotations as θ/α
(dimensionless), degrees only in text meant for reading.

    >>> import rocking as rk
    >>> from rocking.viz import plot_response
    >>> fig = plot_response(response)            # doctest: +SKIP
    >>> fig.savefig("response.png", dpi=120)     # doctest: +SKIP
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..models.regimes import Regime

__all__ = [
    "REGIME_COLORS",
    "REGIME_NAMES",
    "energy_series",
    "floor_motion",
    "lognormal_cdf",
    "pivot_signs",
    "plot_design_chart",
    "plot_energy",
    "plot_fragility",
    "plot_regimes",
    "plot_response",
    "plot_spectrum",
]

#: Background colour of each regime on time axes.
REGIME_COLORS: dict[Regime, str] = {
    Regime.REST: "#ffffff",
    Regime.ROCK: "#ffd9a8",  # light orange
    Regime.SLIDE: "#c4e0f9",  # light blue
    Regime.SLIDE_ROCK: "#dccbf0",  # light purple
}
#: Display names of the regimes.
REGIME_NAMES: dict[Regime, str] = {
    Regime.REST: "rest",
    Regime.ROCK: "rock",
    Regime.SLIDE: "slide",
    Regime.SLIDE_ROCK: "slide-rock",
}

# One colour per quantity, used by every plot and the animation.
COLORS = {
    "theta": "#1f4e9c",
    "sliding": "#b5512a",
    "floor": "#4d4d4d",
    "energy": "#2d7d46",
    "impact": "#000000",
    "overturn": "#c0392b",
    "fit": "#1f4e9c",
    "band": "#9fbbe6",
    "secondary": "#b5512a",
    "statue": "#d9cdb3",
    "pedestal": "#9a9a9a",
}
_LABEL_SIZE = 9.0
_TICK_SIZE = 8.0
_LEGEND_SIZE = 7.5


# --------------------------------------------------------------------------------- helpers
def _new_axes(ax: Axes | None, figsize: tuple[float, float] = (6.4, 3.6)) -> Axes:
    if ax is not None:
        return ax
    fig = Figure(figsize=figsize, layout="constrained")
    return fig.add_subplot()


def _style(ax: Axes) -> None:
    """Explicit styling (no rcParams changes: the caller's settings are left alone)."""
    ax.tick_params(labelsize=_TICK_SIZE)
    ax.grid(True, lw=0.4, color="0.85")
    ax.set_axisbelow(True)
    ax.xaxis.label.set_size(_LABEL_SIZE)
    ax.yaxis.label.set_size(_LABEL_SIZE)


def _regime_runs(t: np.ndarray, regime: np.ndarray) -> dict[int, list[tuple[float, float]]]:
    """Time intervals of each regime: sample i's regime holds on [t_i, t_{i+1}] (at an event both
    the state before and after are saved with the same time, so this is exact)."""
    runs: dict[int, list[tuple[float, float]]] = {int(r): [] for r in Regime}
    if t.size < 2:
        return runs
    codes = regime[:-1]
    change = np.flatnonzero(np.diff(codes)) + 1
    starts = np.concatenate(([0], change))
    ends = np.concatenate((change, [codes.size]))
    for a, b in zip(starts, ends):
        t0, t1 = float(t[a]), float(t[b])
        if t1 > t0:
            runs[int(codes[a])].append((t0, t1))
    return runs


def _shade_regimes(ax: Axes, t: np.ndarray, regime: np.ndarray, *, alpha: float = 1.0) -> None:
    """Regime background: one PolyCollection per regime spanning the axes' height."""
    for code, spans in _regime_runs(t, regime).items():
        if code == Regime.REST or not spans:
            continue
        verts = [[(a, 0.0), (b, 0.0), (b, 1.0), (a, 1.0)] for a, b in spans]
        coll = PolyCollection(
            verts,
            facecolors=REGIME_COLORS[Regime(code)],
            edgecolors="none",
            alpha=alpha,
            transform=ax.get_xaxis_transform(),
            zorder=0,
        )
        ax.add_collection(coll, autolim=False)


def _regime_handles() -> list[Patch]:
    return [
        Patch(facecolor=REGIME_COLORS[r], edgecolor="0.6", lw=0.5, label=REGIME_NAMES[r]) for r in Regime
    ]


def _impact_times(response) -> np.ndarray:
    return np.array([imp.time for imp in response.impacts], dtype=float)


def _t_end(response) -> float:
    t = np.asarray(response.t)
    return float(t[-1]) if t.size else float(response.duration)


def _overturn_line(ax: Axes, response) -> None:
    if response.overturned and response.overturn_time is not None:
        ax.axvline(response.overturn_time, color=COLORS["overturn"], lw=1.0, ls="-", zorder=3)


# ---------------------------------------------------------------------------- derived series
def floor_motion(response) -> tuple[np.ndarray, np.ndarray]:
    """Floor velocity (m/s) and displacement (m) at ``response.t``, integrating
    ``response.floor_acceleration`` twice with the trapezoid rule from rest at t[0].

    For drawings only: a record's displacement drifts without baseline correction.
    """
    t = np.asarray(response.t, dtype=float)
    a = np.asarray(response.floor_acceleration, dtype=float)
    if t.size == 0:
        return np.zeros(0), np.zeros(0)
    dt = np.diff(t)
    v = np.concatenate(([0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)))
    x = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)))
    return v, x


def pivot_signs(response) -> np.ndarray:
    """Active pivot S at each saved state: sign θ while rocking (sign θ̇ at θ = 0), else 0."""
    th = np.asarray(response.theta)
    thd = np.asarray(response.theta_dot)
    rocking = np.isin(response.regime, (Regime.ROCK, Regime.SLIDE_ROCK))
    s = np.where(th != 0.0, np.sign(th), np.sign(thd))
    return np.where(rocking, s, 0.0).astype(int)


def energy_series(response) -> np.ndarray:
    """Mechanical energy T + V relative to the floor (J) at each saved state, from
    :func:`rocking.models.dynamics.mechanical_energy` (V = 0 with the statue upright)."""
    from ..models.dynamics import mechanical_energy

    p = np.asarray(response.parameters, dtype=float)
    s = pivot_signs(response)
    ud, th, thd = (np.asarray(x, dtype=float) for x in (response.u_dot, response.theta, response.theta_dot))
    return np.array([mechanical_energy(p, int(s[i]), ud[i], th[i], thd[i]) for i in range(th.size)])


# ------------------------------------------------------------------------------- response
def plot_regimes(response, ax: Axes | None = None, *, legend: bool = True) -> Axes:
    """Regime timeline: a strip coloured by regime (rest white, rock light orange, slide light
    blue, slide-rock light purple), impacts as ticks, the overturn instant as a red line."""
    ax = _new_axes(ax, figsize=(6.4, 1.2))
    t = np.asarray(response.t)
    _shade_regimes(ax, t, np.asarray(response.regime))
    imp = _impact_times(response)
    if imp.size:
        ax.plot(imp, np.full(imp.size, 0.5), "|", color=COLORS["impact"], ms=7, mew=0.8)
    _overturn_line(ax, response)
    ax.set_xlim(float(t[0]) if t.size else 0.0, max(_t_end(response), 1e-9))
    ax.set_ylim(0.0, 1.0)
    ax.set_yticks([])
    ax.set_xlabel("t (s)")
    _style(ax)
    ax.grid(False)
    for spine in ax.spines.values():
        spine.set_color("0.6")
    if legend:
        handles = _regime_handles()
        if imp.size:
            handles.append(Line2D([], [], ls="none", marker="|", color=COLORS["impact"], label="impact"))
        ax.legend(
            handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=len(handles),
            fontsize=_LEGEND_SIZE, frameon=False, borderaxespad=0.0, handlelength=1.5,
        )
    return ax


def plot_response(response, axes: Sequence[Axes] | None = None, *, title: str | None = None) -> Figure:
    """Three stacked panels against time: θ/α of the statue (dashed lines at ±1), the sliding
    u of the body on the floor (mm) and the floor acceleration (m/s²); the regime timeline
    shaded behind all three, impacts marked as ticks on the θ panel, the overturn instant as a
    red line.

    Parameters
    ----------
    response : Response
    axes : three Axes, optional
        Where to draw (top to bottom); default a new 8 × 7 in figure.
    title : str, optional
        Figure title (only when the figure is created here).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if axes is None:
        fig = Figure(figsize=(8.0, 7.0), layout="constrained")
        ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
        if title:
            fig.suptitle(title, fontsize=10)
    else:
        ax1, ax2, ax3 = axes
        fig = ax1.figure
    t = np.asarray(response.t)
    regime = np.asarray(response.regime)
    alpha = response.alpha
    t_end = max(_t_end(response), 1e-9)
    t0 = float(t[0]) if t.size else 0.0

    for ax in (ax1, ax2, ax3):
        _shade_regimes(ax, t, regime)
        _overturn_line(ax, response)

    # θ/α
    ratio = np.asarray(response.theta) / alpha
    ax1.plot(t, ratio, color=COLORS["theta"], lw=1.1, zorder=2)
    for y in (1.0, -1.0):
        ax1.axhline(y, color="0.35", lw=0.8, ls="--", zorder=1)
    ax1.axhline(0.0, color="0.7", lw=0.5, zorder=1)
    peak = float(np.max(np.abs(ratio))) if ratio.size else 0.0
    lim = max(1.25, 1.1 * peak)
    ax1.set_ylim(-lim, lim)
    imp = _impact_times(response)
    if imp.size:
        ax1.plot(imp, np.zeros(imp.size), "|", color=COLORS["impact"], ms=6, mew=0.8, zorder=4)
    if response.overturned and response.overturn_time is not None:
        ax1.annotate(
            f"overturns at {response.overturn_time:.2f} s",
            (response.overturn_time, 0.85 * lim * (1 if ratio.size == 0 or ratio[-1] >= 0 else -1)),
            xytext=(-6, 0), textcoords="offset points", ha="right", va="center",
            fontsize=_LEGEND_SIZE, color=COLORS["overturn"],
        )
    ax1.set_ylabel("rotation θ/α (–)")

    # sliding
    ax2.plot(t, 1e3 * np.asarray(response.u), color=COLORS["sliding"], lw=1.1, zorder=2)
    ax2.axhline(0.0, color="0.7", lw=0.5, zorder=1)
    who = "pedestal" if getattr(response.system, "pedestal", None) is not None else "statue"
    ax2.set_ylabel(f"{who} sliding u (mm)")
    if getattr(response.system, "floor_friction", True) is None:
        ax2.text(0.5, 0.62, "no floor friction given: the statue cannot slide", transform=ax2.transAxes,
                 ha="center", va="center", fontsize=_LEGEND_SIZE, color="0.35")

    # floor acceleration
    ax3.plot(t, np.asarray(response.floor_acceleration), color=COLORS["floor"], lw=0.9, zorder=2)
    ax3.axhline(0.0, color="0.7", lw=0.5, zorder=1)
    ax3.set_ylabel("floor acceleration (m/s²)")
    ax3.set_xlabel("t (s)")

    for ax in (ax1, ax2, ax3):
        ax.set_xlim(t0, t_end)
        _style(ax)
    handles = _regime_handles()
    if imp.size:
        handles.append(Line2D([], [], ls="none", marker="|", color=COLORS["impact"], label="impact"))
    handles.append(Line2D([], [], color="0.35", lw=0.8, ls="--", label="θ = ±α"))
    if response.overturned:
        handles.append(Line2D([], [], color=COLORS["overturn"], lw=1.0, label="overturn"))
    ax1.legend(
        handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=len(handles),
        fontsize=_LEGEND_SIZE, frameon=False, borderaxespad=0.0, handlelength=1.5,
    )
    return fig


def plot_energy(response, ax: Axes | None = None) -> Axes:
    """Mechanical energy relative to the floor (J) against time, with the final energy ledger
    of ``response.energy`` in the legend and the energy the ledger predicts at the end
    (E(t0) + input work − dissipation) as a marker, which should sit on the curve."""
    ax = _new_axes(ax)
    t = np.asarray(response.t)
    e = energy_series(response)
    _shade_regimes(ax, t, np.asarray(response.regime), alpha=0.6)
    ax.plot(t, e, color=COLORS["energy"], lw=1.1, label="T + V (relative to the floor)", zorder=2)
    led = response.energy
    handles, _ = ax.get_legend_handles_labels()
    if e.size:
        predicted = e[0] + led["input_work"] - led["friction_dissipation"] - led["impact_dissipation"]
        (mark,) = ax.plot(
            [t[-1]], [predicted], marker="o", ms=5, mfc="none", mec="k", ls="none", zorder=4,
            label="ledger: E(t₀) + W − D at the end",
        )
        handles.append(mark)
    blank = {"color": "none", "ls": "none"}
    handles += [
        Line2D([], [], **blank, label=f"input work W = {led['input_work']:.4g} J"),
        Line2D([], [], **blank, label=f"friction dissipation = {led['friction_dissipation']:.4g} J"),
        Line2D([], [], **blank, label=f"impact dissipation = {led['impact_dissipation']:.4g} J"),
        Line2D([], [], **blank, label=f"balance error = {led['relative_balance_error']:.1e} (relative)"),
    ]
    # above the axes, as in plot_response: inside, "best" still lands on the curve or the marker
    ax.legend(
        handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=2, fontsize=_LEGEND_SIZE,
        frameon=False, borderaxespad=0.0, handlelength=1.5,
    )
    ax.set_xlim(float(t[0]) if t.size else 0.0, max(_t_end(response), 1e-9))
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mechanical energy (J)")
    _style(ax)
    return ax


# --------------------------------------------------------------------------------- studies
def _get(data: Any, name: str) -> Any:
    if data is None:
        return None
    if isinstance(data, Mapping) or hasattr(data, "data_vars"):
        try:
            v = data[name]
        except KeyError:
            return None
        return np.asarray(getattr(v, "values", v))
    return getattr(data, name, None)


def plot_spectrum(
    data: Any = None,
    ax: Axes | None = None,
    *,
    frequency_ratio: Any = None,
    amplitude_ratio: Any = None,
    safe_islands: Sequence[Any] | None = None,
    overturned: Any = None,
    label: str | None = "overturning boundary",
    color: str | None = None,
    shade: bool = True,
    ymax: float | None = None,
) -> Axes:
    """Overturning spectrum: x = ω_p/p, y = a_p/(g tan α); the overturn region shaded.

    Parameters
    ----------
    data : xarray.Dataset, mapping or tuple, optional
        Holds ``frequency_ratio`` and ``amplitude_ratio`` (and optionally ``safe_islands`` and
        ``overturned``); a ``(frequency_ratio, amplitude_ratio)`` tuple also works. Keywords
        override it.
    frequency_ratio, amplitude_ratio : array
        The boundary: smallest a_p/(g tan α) that overturns at each ω_p/p (NaN where none does).
        The region above it is shaded as "overturns".
    safe_islands : sequence, optional
        Regions above the boundary where the block survives, drawn unshaded. Each is an (N, 2)
        array of polygon vertices (ω_p/p, a_p/(g tan α)), or a triple
        ``(frequency_ratio, lower, upper)`` of 1-D arrays bounding a band.
    overturned : 2-D bool array, optional
        Outcome on the grid ``amplitude_ratio × frequency_ratio`` (shape (n_amp, n_freq));
        with it both coordinates are grid axes, the overturned cells are shaded and no
        boundary line is drawn.
    label, color : str
        Legend label and colour of the boundary line.
    shade : bool
        Shade the overturn region (turn off when overlaying several boundaries).
    ymax : float, optional
        Top of the plot (default: 1.15 × the largest finite amplitude ratio).
    """
    ax = _new_axes(ax)
    if isinstance(data, tuple) and len(data) == 2:
        data = {"frequency_ratio": data[0], "amplitude_ratio": data[1]}
    fr = np.asarray(frequency_ratio if frequency_ratio is not None else _get(data, "frequency_ratio"), dtype=float)
    ar = np.asarray(amplitude_ratio if amplitude_ratio is not None else _get(data, "amplitude_ratio"), dtype=float)
    if fr.ndim == 0 or ar.ndim == 0:
        raise ValueError("plot_spectrum needs the arrays frequency_ratio and amplitude_ratio")
    if safe_islands is None:
        safe_islands = _get(data, "safe_islands")
    if overturned is None:
        overturned = _get(data, "overturned")
    color = color or COLORS["overturn"]
    fill = "#f6c9c4"
    handles = []
    finite = ar[np.isfinite(ar)]
    top = ymax if ymax is not None else (1.15 * float(finite.max()) if finite.size else 1.0)

    if overturned is not None:
        grid = np.asarray(overturned, dtype=bool)
        if grid.shape != (ar.size, fr.size):
            raise ValueError(f"overturned must have shape (amplitude, frequency) = {(ar.size, fr.size)}, got {grid.shape}")
        from matplotlib.colors import ListedColormap

        ax.pcolormesh(fr, ar, grid.astype(float), cmap=ListedColormap(["#ffffff", fill]), vmin=0, vmax=1,
                      shading="nearest", zorder=0)
        handles.append(Patch(facecolor=fill, edgecolor="none", label="overturns"))
        top = ymax if ymax is not None else float(ar.max())
    else:
        if ar.shape != fr.shape:
            raise ValueError(f"frequency_ratio and amplitude_ratio differ in shape: {fr.shape} vs {ar.shape}")
        order = np.argsort(fr)
        fr, ar = fr[order], ar[order]
        if shade:
            ax.fill_between(fr, np.where(np.isfinite(ar), ar, top), top, where=np.isfinite(ar),
                            color=fill, lw=0, zorder=0)
            handles.append(Patch(facecolor=fill, edgecolor="none", label="overturns"))
        (line,) = ax.plot(fr, ar, color=color, lw=1.4, label=label, zorder=3)
        if label:
            handles.insert(0, line)

    if safe_islands is not None and len(safe_islands):
        for island in safe_islands:
            if isinstance(island, tuple) and len(island) == 3:
                f, lo, hi = (np.asarray(x, dtype=float) for x in island)
                ax.fill_between(f, lo, hi, facecolor="white", edgecolor=color, lw=0.8, hatch="///", zorder=1)
            else:
                poly = np.asarray(island, dtype=float)
                ax.fill(poly[:, 0], poly[:, 1], facecolor="white", edgecolor=color, lw=0.8, hatch="///", zorder=1)
        handles.append(Patch(facecolor="white", edgecolor=color, hatch="///", label="safe island"))

    ax.set_xlim(float(np.nanmin(fr)), float(np.nanmax(fr)))
    ax.set_ylim(0.0, top)
    ax.set_xlabel("frequency ratio ω_p/p (–)")
    ax.set_ylabel("amplitude ratio a_p/(g tan α) (–)")
    if handles:
        ax.legend(handles=handles, loc="upper left", fontsize=_LEGEND_SIZE, framealpha=0.9)
    _style(ax)
    return ax


def lognormal_cdf(x: Any, median: float, beta: float) -> np.ndarray:
    """Φ(ln(x/median)/β), the lognormal fragility curve (0 for x ≤ 0)."""
    from scipy.special import ndtr

    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.log(np.where(x > 0, x, np.nan) / median) / beta
    return np.where(x > 0, ndtr(z), 0.0)


def plot_fragility(
    im: Any,
    p_exceed: Any,
    median: float | None = None,
    beta: float | None = None,
    ax: Axes | None = None,
    *,
    label: str | None = None,
    band: tuple[Any, Any, Any] | None = None,
    im_label: str = "PGA (m/s²)",
    counts: Any = None,
    color: str | None = None,
) -> Axes:
    """Fragility: observed fractions of failure (points) and the fitted lognormal CDF.

    Parameters
    ----------
    im : array
        Intensity measure of each point (e.g. PGA, m/s²).
    p_exceed : array
        Observed probability of failure (exceedance) at each ``im``.
    median, beta : float, optional
        The fitted lognormal curve Φ(ln(im/median)/β); omitted: points only.
    label : str, optional
        Legend label of the curve (median and β are appended).
    band : (x, lower, upper), optional
        A confidence band (probabilities ``lower`` and ``upper`` at ``x``), shaded.
    im_label : str
        x-axis label, with its unit.
    counts : array, optional
        Runs behind each point, shown as ``k/n`` annotations.
    """
    ax = _new_axes(ax)
    color = color or COLORS["fit"]
    im = np.asarray(im, dtype=float)
    pe = np.asarray(p_exceed, dtype=float)
    hi = float(np.nanmax(im)) if im.size else 1.0
    if median is not None and math.isfinite(median):
        hi = max(hi, 2.0 * median)
    if band is not None:
        bx, lo, up = (np.asarray(v, dtype=float) for v in band)
        ax.fill_between(bx, lo, up, color=COLORS["band"], alpha=0.45, lw=0, label="confidence band", zorder=0)
    if median is not None and beta is not None:
        x = np.linspace(0.0, hi * 1.05, 400)
        text = f"median = {median:.3g}, β = {beta:.2f}"
        ax.plot(x, lognormal_cdf(x, median, beta), color=color, lw=1.4, zorder=2,
                label=f"{label}: {text}" if label else f"lognormal fit: {text}")
        ax.plot([median, median], [0.0, 0.5], color=color, lw=0.7, ls=":", zorder=1)
        ax.plot([0.0, median], [0.5, 0.5], color=color, lw=0.7, ls=":", zorder=1)
    ax.plot(im, pe, "o", ms=4.5, mfc="white", mec=color, mew=1.1, ls="none", zorder=3,
            label="observed fraction" if label is None or median is None else f"{label}: observed")
    if counts is not None:
        for xi, pi, ni in zip(im, pe, np.asarray(counts)):
            ax.annotate(f"{round(pi * ni):d}/{int(ni)}", (xi, pi), xytext=(3, -9), textcoords="offset points",
                        fontsize=6.5, color="0.3")
    ax.set_xlim(0.0, hi * 1.05)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(im_label)
    ax.set_ylabel("probability of overturning (–)")
    ax.legend(loc="lower right", fontsize=_LEGEND_SIZE, framealpha=0.9)
    _style(ax)
    return ax


def plot_design_chart(
    mu_s: Any,
    peak_rotation_ratio: Any,
    peak_sliding: Any,
    overturn_rate: Any = None,
    ax: Axes | None = None,
    *,
    xlabel: str = "pedestal friction on the floor μs (–)",
    tan_alpha: float | None = None,
    recommended: float | None = None,
    friction_scatter: float = 0.0,
    top_sliding: Any = None,
    rate_label: str = "overturn rate",
) -> Axes:
    """Design chart against the floor friction under the pedestal, on two y-axes.

    Left: peak θ/α (line, circles; values above 2 are clipped and marked ▲) and the overturn
    rate (fraction of runs that overturn, bars). Right: peak sliding (mm, dashed).

    Parameters
    ----------
    mu_s : array
        Static friction coefficients (x).
    peak_rotation_ratio : array
        Peak |θ|/α at each μs (e.g. median over records).
    peak_sliding : array
        Peak sliding, m (shown in mm).
    overturn_rate : array, optional
        Fraction of runs that overturned, in [0, 1].
    tan_alpha : float, optional
        Mark μs = tan α (the statue alone rocks before sliding above it).
    recommended : float, optional
        Mark the recommended μs.
    friction_scatter : float
        Relative scatter s of the friction: shade [μs·(1 − s), μs·(1 + s)] around the
        recommended μs, the range its safety was checked over.
    top_sliding : array, optional
        Peak sliding of the statue on the pedestal's top face, m (shown in mm, dotted, on the
        right axis next to the pedestal's sliding on the floor).
    rate_label : str
        Legend text of the bars.

    Returns
    -------
    Axes
        The left axes; the right one is ``ax.right_ax``.
    """
    ax = _new_axes(ax)
    mu = np.asarray(mu_s, dtype=float)
    rot = np.asarray(peak_rotation_ratio, dtype=float)
    slide = 1e3 * np.asarray(peak_sliding, dtype=float)
    order = np.argsort(mu)
    mu, rot, slide = mu[order], rot[order], slide[order]
    top = 2.0
    handles = []
    if overturn_rate is not None:
        rate = np.asarray(overturn_rate, dtype=float)[order]
        width = 0.6 * float(np.min(np.diff(mu))) if mu.size > 1 else 0.05
        bars = ax.bar(mu, rate, width=width, color="#f6c9c4", edgecolor=COLORS["overturn"], lw=0.6,
                      zorder=1, label=rate_label)
        handles.append(bars)
    shown = np.where(np.isfinite(rot), np.minimum(rot, top), top)
    (line,) = ax.plot(mu, shown, "-o", color=COLORS["theta"], ms=4, lw=1.3, zorder=3, label="peak |θ|/α")
    handles.append(line)
    clipped = ~(np.isfinite(rot) & (rot <= top))
    if clipped.any():
        ax.plot(mu[clipped], np.full(clipped.sum(), top), "^", color=COLORS["overturn"], ms=6, zorder=4)
    ax.axhline(1.0, color="0.35", lw=0.8, ls="--", zorder=2)
    if tan_alpha is not None:
        ax.axvline(tan_alpha, color="0.5", lw=0.8, ls=":", zorder=2)
        ax.annotate("μs = tan α", (tan_alpha, top * 0.97), xytext=(3, 0), textcoords="offset points",
                    fontsize=_LEGEND_SIZE, color="0.35", va="top")
    if recommended is not None:
        rec = float(recommended)
        if friction_scatter > 0:
            span = ax.axvspan(rec * (1.0 - friction_scatter), rec * (1.0 + friction_scatter), color=COLORS["energy"],
                              alpha=0.12, lw=0, zorder=0, label=f"μs·(1 ± {friction_scatter:g})")
            handles.append(span)
        ax.axvline(rec, color=COLORS["energy"], lw=1.6, alpha=0.7, zorder=2)
        ax.annotate("recommended", (rec, 0.02), xytext=(3, 2), textcoords="offset points", fontsize=_LEGEND_SIZE,
                    color=COLORS["energy"])
    ax.set_ylim(0.0, top * 1.05)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("peak |θ|/α, overturn rate (–)")
    right = ax.twinx()
    floor_label = "peak sliding (mm)" if top_sliding is None else "pedestal on the floor (mm)"
    (sl,) = right.plot(mu, slide, "--s", color=COLORS["secondary"], ms=3.5, lw=1.2, zorder=3,
                       label=floor_label)
    handles.append(sl)
    shown_slides = slide
    if top_sliding is not None:
        top_mm = 1e3 * np.asarray(top_sliding, dtype=float)[order]
        (tl,) = right.plot(mu, top_mm, ":D", color=COLORS["secondary"], ms=3.0, lw=1.4, zorder=3,
                           mfc="white", label="statue on the top face (mm)")
        handles.append(tl)
        shown_slides = np.concatenate((slide, top_mm))
    right.set_ylabel("peak sliding (mm)", color=COLORS["secondary"])
    right.tick_params(axis="y", colors=COLORS["secondary"], labelsize=_TICK_SIZE)
    right.yaxis.label.set_size(_LABEL_SIZE)
    finite = shown_slides[np.isfinite(shown_slides)]
    right.set_ylim(0.0, 1.1 * float(finite.max()) if finite.size and finite.max() > 0 else 1.0)
    _style(ax)
    ax.legend(handles=handles, loc="upper right", fontsize=_LEGEND_SIZE, framealpha=0.9)
    ax.right_ax = right  # type: ignore[attr-defined]
    return ax
