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


def style_axes(ax: Axes) -> None:
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
    """Active pivot S at each saved state (+1, −1; 0 when not rocking), as the solver had it."""
    return np.asarray(response.pivot, dtype=int)


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
    style_axes(ax)
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
        style_axes(ax)
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
    style_axes(ax)
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
    scan_top: float | None = None,
    legend: bool = True,
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
    scan_top : float, optional
        The highest a_p/(g tan α) scanned: where the boundary is NaN (nothing overturned up to
        it), the band is drawn grey and says "no overturning in the scanned range".
    legend : bool
        Draw the legend in a strip above the axes, off the islands (off: gather the handles,
        ``ax.spectrum_handles``, into a figure legend).
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
        if scan_top is not None and np.isnan(ar).any():
            handles.append(_no_overturning(ax, fr, ar, scan_top))

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
    if handles and legend:
        ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=2, fontsize=_LEGEND_SIZE,
                  frameon=False, borderaxespad=0.0)
    ax.spectrum_handles = handles  # type: ignore[attr-defined]
    style_axes(ax)
    return ax


def _no_overturning(ax: Axes, fr: np.ndarray, ar: np.ndarray, scan_top: float) -> Patch:
    """Grey the frequencies where nothing overturned up to ``scan_top`` (the boundary's NaN gap),
    from the neighbouring frequencies that overturn (where the shaded region ends), and say so in
    the widest such span."""
    gap = np.isnan(ar)
    spans, start = [], None
    for k, g in enumerate(np.append(gap, False)):
        if g and start is None:
            start = k
        elif not g and start is not None:
            spans.append((fr[max(start - 1, 0)], fr[min(k, fr.size - 1)]))
            start = None
    style = dict(facecolor="0.93", edgecolor="0.75", hatch="..", lw=0.0, zorder=0)
    for lo, hi in spans:
        ax.fill_between([lo, hi], 0.0, scan_top, **style)
    lo, hi = max(spans, key=lambda span: span[1] - span[0])
    wide = hi - lo > 0.3 * (fr[-1] - fr[0])  # else written upright along the band
    ax.text(0.5 * (lo + hi), 0.5 * scan_top, f"no overturning in the scanned range (up to {scan_top:.3g})"
            .replace(" in", "\nin" if wide else " in").replace(" (", "\n(" if wide else " ("),
            rotation=0 if wide else 90, ha="center", va="center", fontsize=7, color="0.3", zorder=4)
    return Patch(**style, label=f"no overturning up to {scan_top:.3g}")


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
    tested_max: float | None = None,
    units: str = "",
    legend: bool = True,
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
    tested_max : float, optional
        The highest level run (default: the largest ``im``). A median above it is extrapolated:
        marked with an open diamond and "(extrapolated)" in its label, and the range beyond the
        highest level is greyed.
    units : str
        The unit of the intensity measure in the labels (e.g. "m/s²").
    legend : bool
        Draw the legend in a strip above the axes, off the data.
    """
    ax = _new_axes(ax)
    color = color or COLORS["fit"]
    im = np.asarray(im, dtype=float)
    pe = np.asarray(p_exceed, dtype=float)
    hi = float(np.nanmax(im)) if im.size else 1.0
    tested = float(tested_max) if tested_max is not None else hi
    if median is not None and math.isfinite(median):
        hi = max(hi, 2.0 * median)
    if band is not None:
        bx, lo, up = (np.asarray(v, dtype=float) for v in band)
        ax.fill_between(bx, lo, up, color=COLORS["band"], alpha=0.45, lw=0, label="confidence band", zorder=0)
    if median is not None and beta is not None:
        x = np.linspace(0.0, hi * 1.05, 400)
        beyond = median > tested
        unit = f" {units}" if units else ""
        text = f"median = {median:.3g}{unit}{' (extrapolated)' if beyond else ''}, β = {beta:.2f}"
        ax.plot(x, lognormal_cdf(x, median, beta), color=color, lw=1.4, zorder=2,
                label=f"{label}: {text}" if label else f"lognormal fit: {text}")
        ax.plot([median, median], [0.0, 0.5], color=color, lw=0.7, ls=":", zorder=1)
        ax.plot([0.0, median], [0.5, 0.5], color=color, lw=0.7, ls=":", zorder=1)
        if beyond:
            ax.plot([median], [0.5], "D", ms=6, mfc="white", mec=color, mew=1.3, zorder=4)
            ax.axvspan(tested, max(hi * 1.05, median * 1.1), color="0.9", lw=0, zorder=-1)
            ax.annotate(f"beyond the highest\nlevel run ({tested:.3g}{unit})", (tested, 0.0), xytext=(4, 3),
                        textcoords="offset points", ha="left", va="bottom", fontsize=6.5, color="0.35")
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
    if legend:
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=2, fontsize=_LEGEND_SIZE, frameon=False,
                  borderaxespad=0.0)
    style_axes(ax)
    return ax


#: Colour and line style of the limit on the statue's slide on the top face (the design chart).
TOP_LIMIT_COLOR = "#7a3b8f"
_TOP_LIMIT_STYLE = (0, (5, 2, 1, 2, 1, 2))


def _mm_text(value_mm: float) -> str:
    """A length in mm for reading: '0 mm', '< 0.01 mm', '0.05 mm', '12 mm', '303.7 mm'."""
    x = float(value_mm)
    if not math.isfinite(x):
        return "–"
    if x == 0:
        return "0 mm"
    if abs(x) < 0.005:
        return "< 0.01 mm"
    if abs(x) < 1:
        return f"{x:.2f}".rstrip("0").rstrip(".") + " mm"
    return f"{x:.1f}".removesuffix(".0") + " mm"


def _design_axes(ax: Axes | None) -> tuple[Axes, Axes, Axes]:
    """Three axes sharing μs: peak θ/α, the rate of falls, the sliding; in place of ``ax`` if given."""
    ratios = (1.5, 0.75, 1.75)
    if ax is None:
        fig = Figure(figsize=(6.4, 5.6), layout="constrained")
        return tuple(fig.subplots(3, 1, sharex=True, height_ratios=ratios))  # type: ignore[return-value]
    spec = ax.get_subplotspec().subgridspec(3, 1, height_ratios=ratios, hspace=0.08)
    fig = ax.figure
    ax.remove()
    top = fig.add_subplot(spec[0])
    return top, fig.add_subplot(spec[1], sharex=top), fig.add_subplot(spec[2], sharex=top)


def _limit_labels(ax: Axes, limits: Sequence[tuple[float, str, str, Any]]) -> None:
    """Horizontal limit lines (value, label, colour, line style), each labelled just right of the
    axes (never on the data); of two labels closer than a fifth of the axis, the higher one is
    lifted above its line and the lower one put under its own."""
    lo, hi = ax.get_ylim()
    close = len(limits) == 2 and abs(limits[0][0] - limits[1][0]) < 0.2 * (hi - lo)
    top_value = max(v for v, *_ in limits) if limits else 0.0
    for value, text, color, style in limits:
        ax.axhline(value, color=color, lw=1.0, ls=style, zorder=2)
        va = ("bottom" if value == top_value else "top") if close else "center"
        ax.annotate(text, (1.0, value), xycoords=ax.get_yaxis_transform(), xytext=(4, 0), textcoords="offset points",
                    ha="left", va=va, fontsize=_LEGEND_SIZE, color=color, annotation_clip=False)


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
    rotation_label: str = "peak |θ|/α (–)",
    sliding_limit: float | None = None,
    top_sliding_limit: float | None = None,
    sliding_max: float | None = None,
    axes: Sequence[Axes] | None = None,
    legend: bool = True,
) -> Axes:
    """Design chart against the floor friction under the pedestal, on three axes sharing μs.

    Top: peak θ/α (values above 2 are clipped, marked ▲ and labelled with their value). Middle:
    the overturn rate (fraction of runs that overturn, bars). Bottom: peak sliding (mm) with the
    limits, each labelled at the right. The legend sits in a strip above the top axes.

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
        Peak sliding of the statue on the pedestal's top face, m (shown in mm, dotted, next to
        the pedestal's sliding on the floor).
    rate_label, rotation_label : str
        The y labels of the bars' and the rotation's axes.
    sliding_limit, top_sliding_limit : float, optional
        The limits on the sliding on the floor and on the top face, m (``inf``: none drawn).
    sliding_max : float, optional
        Top of the sliding axis, mm (to share it between panels).
    axes : three Axes, optional
        Draw into these (rotation, rate, sliding) instead of ``ax``'s place.
    legend : bool
        Draw the legend above the top axes (off to gather the legends of several panels).

    Returns
    -------
    Axes
        The top (rotation) axes; ``.rate_ax`` and ``.sliding_ax`` are the others (``.right_ax``
        is the sliding axes too, its name when it was a twin axis).
    """
    rot_ax, rate_ax, slide_ax = tuple(axes) if axes is not None else _design_axes(ax)
    mu = np.asarray(mu_s, dtype=float)
    rot = np.asarray(peak_rotation_ratio, dtype=float)
    slide = 1e3 * np.asarray(peak_sliding, dtype=float)
    order = np.argsort(mu)
    mu, rot, slide = mu[order], rot[order], slide[order]
    clip = 2.0
    handles: list[Any] = []

    shown = np.where(np.isfinite(rot), np.minimum(rot, clip), clip)
    (line,) = rot_ax.plot(mu, shown, "-o", color=COLORS["theta"], ms=4, lw=1.3, zorder=3, label="peak |θ|/α")
    handles.append(line)
    clipped = ~(np.isfinite(rot) & (rot <= clip))
    if clipped.any():
        marks = rot_ax.plot(mu[clipped], np.full(clipped.sum(), clip), "^", color=COLORS["overturn"], ms=6, zorder=4,
                            label="clipped at 2 (its value)")
        handles.append(marks[0])
        for x, value in zip(mu[clipped], rot[clipped]):
            rot_ax.annotate(f"{value:.3g}" if np.isfinite(value) else "∞", (x, clip), xytext=(0, 5),
                            textcoords="offset points", ha="center", va="bottom", fontsize=7, color=COLORS["overturn"])
    rot_ax.axhline(1.0, color="0.35", lw=0.8, ls="--", zorder=2)
    rot_ax.annotate("θ = α", (0.0, 1.0), xycoords=rot_ax.get_yaxis_transform(), xytext=(3, 2),
                    textcoords="offset points", fontsize=7, color="0.35", va="bottom")
    rot_ax.set_ylim(0.0, clip * 1.25)
    rot_ax.set_ylabel(rotation_label)

    if overturn_rate is not None:
        rate = np.asarray(overturn_rate, dtype=float)[order]
        width = 0.6 * float(np.min(np.diff(mu))) if mu.size > 1 else 0.05
        bars = rate_ax.bar(mu, rate, width=width, color="#f6c9c4", edgecolor=COLORS["overturn"], lw=0.6, zorder=1,
                           label=rate_label)
        handles.append(bars)
    rate_ax.set_ylim(0.0, 1.05)
    rate_ax.set_yticks([0.0, 0.5, 1.0])
    rate_ax.set_ylabel(f"{rate_label.replace(' ', chr(10), 1)} (–)")  # two short lines: its axes is short

    floor_label = "peak sliding" if top_sliding is None else "pedestal on the floor"
    (sl,) = slide_ax.plot(mu, slide, "--s", color=COLORS["secondary"], ms=3.5, lw=1.2, zorder=3, label=floor_label)
    handles.append(sl)
    shown_slides = slide
    if top_sliding is not None:
        top_mm = 1e3 * np.asarray(top_sliding, dtype=float)[order]
        (tl,) = slide_ax.plot(mu, top_mm, ":D", color=COLORS["secondary"], ms=3.0, lw=1.4, zorder=3, mfc="white",
                              label="statue on the top face")
        handles.append(tl)
        shown_slides = np.concatenate((slide, top_mm))
    limits = [(1e3 * float(v), f"{name}\n{_mm_text(1e3 * float(v))}", color, style)
              for v, name, color, style in ((sliding_limit, "sliding limit", "0.2", "-."),
                                            (top_sliding_limit, "top-face limit", TOP_LIMIT_COLOR, _TOP_LIMIT_STYLE))
              if v is not None and math.isfinite(v)]
    finite = np.concatenate((shown_slides[np.isfinite(shown_slides)], [v for v, *_ in limits]))
    top = sliding_max if sliding_max is not None else (1.1 * float(finite.max()) if finite.size else 0.0)
    slide_ax.set_ylim(0.0, top if top > 0 else 1.0)
    _limit_labels(slide_ax, limits)
    slide_ax.set_ylabel("peak sliding (mm)")
    slide_ax.set_xlabel(xlabel)

    for a in (rot_ax, rate_ax, slide_ax):
        if tan_alpha is not None:
            a.axvline(tan_alpha, color="0.5", lw=0.8, ls=":", zorder=2)
        style_axes(a)
    if tan_alpha is not None:
        handles.append(Line2D([], [], color="0.5", lw=0.8, ls=":", label=f"μs = tan α = {tan_alpha:.3g}"))
    if recommended is not None:
        rec = float(recommended)
        for a in (rot_ax, rate_ax, slide_ax):
            if friction_scatter > 0:
                a.axvspan(rec * (1.0 - friction_scatter), rec * (1.0 + friction_scatter), color=COLORS["energy"],
                          alpha=0.12, lw=0, zorder=0, label=f"μs·(1 ± {friction_scatter:g})" if a is rot_ax else None)
            a.axvline(rec, color=COLORS["energy"], lw=1.6, alpha=0.7, zorder=2)
        handles.append(Line2D([], [], color=COLORS["energy"], lw=1.6, alpha=0.7, label=f"recommended μs = {rec:.3g}"))
        if friction_scatter > 0:
            handles.append(Patch(color=COLORS["energy"], alpha=0.12, lw=0,
                                 label=f"its scatter μs·(1 ± {friction_scatter:g})"))
    for a in (rot_ax, rate_ax):
        a.tick_params(labelbottom=False)
    if legend:
        rot_ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=3, fontsize=_LEGEND_SIZE,
                      frameon=False, borderaxespad=0.0, handlelength=1.8)
    rot_ax.rate_ax = rate_ax  # type: ignore[attr-defined]
    rot_ax.sliding_ax = slide_ax  # type: ignore[attr-defined]
    rot_ax.right_ax = slide_ax  # type: ignore[attr-defined]
    rot_ax.design_handles = handles  # type: ignore[attr-defined]
    return rot_ax
