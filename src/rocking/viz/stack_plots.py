"""Plots of a stack of blocks (:class:`rocking.stack.StackResponse`): every block's motion, and
the energy ledger.

    >>> from rocking.viz.stack_plots import plot_stack_energy, plot_stack_response
    >>> fig = plot_stack_response(response, motion=motion)      # doctest: +SKIP
    >>> ax = plot_stack_energy(response)                         # doctest: +SKIP

Both return matplotlib objects (a Figure, an Axes) that the caller saves or composes, like
:func:`rocking.viz.plot_response` and :func:`rocking.viz.plot_energy` for one statue.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..io.output import _envelope
from .plots import style_axes

__all__ = ["ENERGY_LABEL", "block_color", "plot_stack_energy", "plot_stack_response"]

#: Line colours of the blocks, from the floor up: darker shades of the animation's fills (repeated).
LINE_COLORS = ("#7a6440", "#1f4e9c", "#b5512a", "#2d7d46", "#8a8a2a", "#7b3f98")
_LEGEND_SIZE = 7.5

#: The energy axis: what zero means there.
ENERGY_LABEL = "E − E₀ (J);  0 = the stack as it started"


def block_color(k: int) -> str:
    """The line colour of block ``k`` (0 = the one on the floor)."""
    return LINE_COLORS[k % len(LINE_COLORS)]


def _legend_above(ax: Axes, handles: list[Any], ncol: int) -> None:
    """The legend above the axes: inside, it would cover a curve whatever its place."""
    ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=ncol, fontsize=_LEGEND_SIZE,
              frameon=False, borderaxespad=0.0, handlelength=1.5)


def _edge_time(response: Any) -> tuple[int, float] | None:
    """(block index, t) when a block slid to the edge of the one below (the run stops there)."""
    if response.status != "slid_past_edge" or not len(response.events):
        return None
    return int(response.events[-1, 1]), float(response.end_time)


def plot_stack_response(response: Any, axes: Sequence[Axes] | None = None, *, motion: Any = None,
                        title: str | None = None, legend_columns: int | None = None) -> Figure:
    """Stacked panels against time t (s): each block's rotation φ on what it stands on (°), its
    sliding along that face (mm) and, given ``motion``, the floor acceleration (m/s²). A dashed
    line marks a block's overturn, a dotted one a block that slid to the edge of the one below.

    Parameters
    ----------
    response : rocking.stack.StackResponse
    axes : two or three Axes, optional
        Where to draw, top to bottom (three with ``motion``); default a new figure.
    motion : floor motion, optional
        The motion the stack was run with (its ``acceleration(t)`` in m/s²) for the third panel.
    title : str, optional
        Figure title (only when the figure is created here).
    legend_columns : int, optional
        Columns of the legend above the top panel (default: every entry on one row, at most 6).

    Returns
    -------
    matplotlib.figure.Figure
    """
    panels = 3 if motion is not None else 2
    if axes is None:
        fig = Figure(figsize=(8.0, 7.0 if panels == 3 else 6.0), layout="constrained")
        axes = fig.subplots(panels, 1, sharex=True)
        if title:
            fig.suptitle(title, fontsize=10)
    fig = axes[0].figure
    ax_phi, ax_u = axes[0], axes[1]
    t = np.asarray(response.t, dtype=float)
    rotation = np.asarray(response.rotation, dtype=float)
    sliding = np.asarray(response.sliding, dtype=float)
    handles = []
    for k, (name, block) in enumerate(zip(response.stack.names, response.blocks)):
        color = block_color(k)
        ax_phi.plot(*_envelope(t, np.degrees(rotation[:, k])), color=color, lw=1.0, zorder=2)
        ax_u.plot(*_envelope(t, 1e3 * sliding[:, k]), color=color, lw=1.0, zorder=2)
        handles.append(Line2D([], [], color=color, lw=1.4, label=name))
        if block.get("overturned") and block.get("overturn_time") is not None:
            for ax in axes:
                ax.axvline(block["overturn_time"], color=color, ls="--", lw=1.0, zorder=3)
    if any(b.get("overturned") for b in response.blocks):
        handles.append(Line2D([], [], color="0.3", ls="--", lw=1.0, label="overturn"))
    edge = _edge_time(response)
    if edge is not None:
        for ax in axes:
            ax.axvline(edge[1], color=block_color(edge[0]), ls=":", lw=1.2, zorder=3)
        handles.append(Line2D([], [], color="0.3", ls=":", lw=1.2, label="slid to the edge"))
    for ax in axes:
        ax.axhline(0.0, color="0.7", lw=0.5, zorder=1)
    ax_phi.set_ylabel("rotation φ on what is below (°)")
    ax_u.set_ylabel("sliding on what is below (mm)")
    if motion is not None:
        ax_a = axes[2]
        grid = np.linspace(float(t[0]), float(t[-1]), 4000) if t.size else t
        ax_a.plot(grid, np.asarray(motion.acceleration(grid), dtype=float), color="#4d4d4d", lw=0.8, zorder=2)
        ax_a.set_ylabel("floor acceleration (m/s²)")
    axes[-1].set_xlabel("t (s)")
    for ax in axes:
        if t.size:
            ax.set_xlim(float(t[0]), max(float(t[-1]), float(t[0]) + 1e-9))
        style_axes(ax)
    _legend_above(ax_phi, handles, legend_columns or min(len(handles), 6))
    return fig


def plot_stack_energy(response: Any, ax: Axes | None = None) -> Axes:
    """The change of mechanical energy E − E₀ of the whole stack (J) against t (s), with the
    ledger W − D (the floor's work less what friction and impacts dissipated) drawn over it: the
    two coincide when the energy balance closes. The legend gives the final values.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        ax = Figure(figsize=(6.4, 3.6), layout="constrained").add_subplot()
    t = np.asarray(response.t, dtype=float)
    change = np.asarray(response.energy, dtype=float) - float(response.initial_energy)
    work = np.asarray(response.input_work, dtype=float)
    friction = np.asarray(response.friction_loss, dtype=float)
    impact = np.asarray(response.impact_loss, dtype=float)
    ax.plot(t, change, color="#2d7d46", lw=1.2, zorder=2, label="E − E₀ (kinetic + potential)")
    ax.plot(t, work - friction - impact, color="k", lw=0.9, ls=(0, (4, 3)), zorder=3,
            label="ledger W − D (should lie on it)")
    ax.axhline(0.0, color="0.7", lw=0.5, zorder=1)
    handles, _ = ax.get_legend_handles_labels()
    blank = {"color": "none", "ls": "none"}
    last = (lambda x: float(x[-1]) if x.size else math.nan)
    error = float(response.summary()["energy_balance_error"])
    handles += [
        Line2D([], [], **blank, label=f"input work W = {last(work):.4g} J"),
        Line2D([], [], **blank, label=f"friction dissipation = {last(friction):.4g} J"),
        Line2D([], [], **blank, label=f"impact dissipation = {last(impact):.4g} J"),
        Line2D([], [], **blank, label=f"balance error = {error:.1e} (relative)"),
    ]
    _legend_above(ax, handles, 2)
    if t.size:
        ax.set_xlim(float(t[0]), max(float(t[-1]), float(t[0]) + 1e-9))
    ax.set_xlabel("t (s)")
    ax.set_ylabel(ENERGY_LABEL)
    style_axes(ax)
    return ax
