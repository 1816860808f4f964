"""Animation of a stack of blocks (rocking.stack), drawn to scale in the floor's frame.

Every block is drawn from its saved pose (centre X, Y and rotation Θ, clockwise positive), so
whatever the interfaces do — slip, rock, lift off — the picture is the solver's state itself. The
floor is drawn still (the frame moves with it); the header gives the time, each block's rotation
on what it stands on (on as many lines as the names need, a long name cut to 16 characters), and
the verdict once a block has fallen.

    >>> from rocking.viz.stack_animation import animate_stack
    >>> animate_stack(response, "stack.gif")          # doctest: +SKIP
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
from matplotlib.patches import Polygon

from .animation import check_animation_path, floor_scene, frame_times, write_frames

__all__ = ["animate_stack", "block_outline", "header_lines", "short_name"]

#: Fill colours of the blocks, from the floor up (repeated beyond six); the plots draw each block's
#: lines in a darker shade of its fill (rocking.viz.stack_plots.LINE_COLORS).
BLOCK_COLORS = ("#b9a98c", "#8fa7c4", "#c49a8f", "#9cbf95", "#c4b98f", "#b7a3c9")


def block_outline(x: float, y: float, theta: float, half_width: float, half_height: float) -> np.ndarray:
    """Corners (4 × 2, m) of a block with its centre at (x, y), turned clockwise by θ (rad)."""
    local = np.array([[-half_width, -half_height], [half_width, -half_height], [half_width, half_height],
                      [-half_width, half_height]])
    c, s = math.cos(theta), math.sin(theta)
    return np.column_stack((x + local[:, 0] * c + local[:, 1] * s, y - local[:, 0] * s + local[:, 1] * c))


#: Characters of the header's monospace lines (8 pt on the 6 in wide figure, within its margins).
_HEADER_CHARS = 80
#: The longest name the header shows whole.
_NAME_CHARS = 16


def short_name(name: str, limit: int = _NAME_CHARS) -> str:
    """``name`` cut to ``limit`` characters, its end replaced by "…" when cut."""
    return name if len(name) <= limit else name[: limit - 1] + "…"


def header_lines(names: tuple[str, ...], width: int = _HEADER_CHARS) -> list[list[int]]:
    """The blocks (indices) on each line of the header's rotations, so that no line holds more
    than ``width`` characters ("name: +12.3°" each, three spaces apart)."""
    lines: list[list[int]] = [[]]
    used = 0
    for k, name in enumerate(names):
        need = len(short_name(name)) + 9 + (3 if lines[-1] else 0)
        if lines[-1] and used + need > width:
            lines.append([])
            used, need = 0, need - 3
        lines[-1].append(k)
        used += need
    return lines


def _nice_step(rough: float) -> float:
    """1, 2 or 5 × 10^k, the first at least ``rough`` (m)."""
    base = 10 ** math.floor(math.log10(max(rough, 1e-9)))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * base >= rough:
            return m * base
    return 10.0 * base


def animate_stack(response, path: str | os.PathLike[str], *, speed: float = 1.0, fps: float = 25,
                  max_seconds: float | None = None, dpi: int = 80, title: str | None = None) -> Path:
    """Write an animation of a :class:`rocking.stack.StackResponse` to ``path`` (GIF, or MP4 with
    ffmpeg); the arguments are those of :func:`rocking.viz.animate`."""
    path = Path(path)
    ext = check_animation_path(path)
    times = frame_times(response, speed=speed, fps=fps, max_seconds=max_seconds)
    t = np.asarray(response.t, dtype=float)
    n = response.stack.n
    pose = np.stack([np.stack([np.interp(times, t, response.pose[:, k, j]) for j in range(3)], axis=1)
                     for k in range(n)], axis=1)  # (frames, N, 3)
    rotation = np.stack([np.interp(times, t, response.rotation[:, k]) for k in range(n)], axis=1)
    halves = [(0.5 * b.width, 0.5 * b.height) for b in response.stack.blocks]

    # a fixed view holding every corner at every frame, equal scales on both axes
    corners = np.concatenate([block_outline(*pose[f, k], *halves[k]) for f in range(times.size) for k in range(n)])
    height = sum(b.height for b in response.stack.blocks)
    margin = 0.15 * height
    lo, hi = float(corners[:, 0].min()) - margin, float(corners[:, 0].max()) + margin
    top = max(float(corners[:, 1].max()), height) + 0.3 * height
    ground = 0.08 * top
    fig, ax, lo, hi, top = floor_scene(lo, hi, top, ground, axes_height=0.80)
    span = hi - lo
    # a ruler on the floor: ticks every `step` m, labelled, so that the scale reads off the picture
    step = _nice_step(span / 6)
    for x in np.arange(math.ceil(lo / step) * step, hi, step):
        ax.plot([x, x], [0, -0.3 * ground], color="0.35", lw=0.8, zorder=2)
        ax.text(x, -0.62 * ground, f"{x:g}", fontsize=7, ha="center", va="center", color="0.3", zorder=2)
    ax.text(hi - 0.01 * span, -0.62 * ground, "m", fontsize=7, ha="right", va="center", color="0.3")
    patches = []
    for k in range(n):
        patch = Polygon(block_outline(*pose[0, k], *halves[k]), closed=True,
                        facecolor=BLOCK_COLORS[k % len(BLOCK_COLORS)],
                        edgecolor="0.2", lw=1.0, zorder=3 + k)
        ax.add_patch(patch)
        patches.append(patch)
    names = response.stack.names
    lines = header_lines(names)
    txt_t = fig.text(0.03, 0.95, "", fontsize=10, family="monospace", va="center")
    # the rotations under the time, in as many lines as the names need
    txt_rot = fig.text(0.03, 0.915, "", fontsize=8, family="monospace", va="top", color="0.25", linespacing=1.25)
    txt_verdict = fig.text(0.97, 0.95, "", fontsize=9, va="center", ha="right",
                           bbox={"boxstyle": "round,pad=0.3", "facecolor": "white", "edgecolor": "0.5"})
    if title:  # between the time and the verdict, where nothing else is written
        fig.text(0.5, 0.95, short_name(title, 40), fontsize=8, ha="center", va="center", color="0.3")
    falls = [(b["overturn_time"], short_name(b["name"])) for b in response.blocks if b["overturned"]]
    first_fall = min(falls) if falls else None

    def draw(f: int) -> None:
        for k in range(n):
            patches[k].set_xy(block_outline(*pose[f, k], *halves[k]))
        txt_t.set_text(f"t = {times[f]:6.2f} s")
        txt_rot.set_text("\n".join("   ".join(f"{short_name(names[k])}: {math.degrees(rotation[f, k]):+5.1f}°"
                                              for k in line) for line in lines))
        fallen = first_fall is not None and times[f] >= first_fall[0] - 1e-12
        txt_verdict.set_text(f"{first_fall[1]} overturned" if fallen else "standing")
        txt_verdict.get_bbox_patch().set_facecolor("#f6c9c4" if fallen else "#dff0d8")

    write_frames(fig, path, ext, fps=fps, dpi=dpi, n_frames=times.size, draw=draw,
                 swatch=[*BLOCK_COLORS, "#e4e0d8", "#f6c9c4", "#dff0d8", "#000000"])
    return path
