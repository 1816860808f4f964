"""Animation of a simulation: the floor, the pedestal and the statue drawn to scale.

The floor moves by its displacement (the floor acceleration integrated twice with the trapezoid
rule, for the drawing only), the pedestal slides on it by u, and the statue rotates by θ about
its active corner (+b for θ > 0, −b for θ < 0, from the centre of its base; θ > 0 tilts it
towards +x). Without a pedestal u moves the statue itself.

    >>> from rocking.viz import animate
    >>> animate(response, "statue.gif")                  # doctest: +SKIP
    >>> animate(response, "statue.mp4", speed=0.5)       # doctest: +SKIP  (needs ffmpeg)
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Polygon, Rectangle

from ..models.regimes import Regime
from .plots import COLORS, REGIME_COLORS, REGIME_NAMES, floor_motion

__all__ = ["animate", "check_animation_path", "frame_times"]


def frame_times(response, *, speed: float = 1.0, fps: float = 25, max_seconds: float | None = None) -> np.ndarray:
    """Simulated times shown by the frames of :func:`animate`.

    ``n = max(1, round(fps · D / speed))`` frames, D the simulated duration (``t[-1] − t[0]``),
    cut to ``fps · max_seconds`` frames of video; frame k shows t0 + k·speed/fps, except that
    the last frame of an uncut animation shows the final state.
    """
    if not (speed > 0 and math.isfinite(speed)):
        raise ValueError(f"speed must be a positive number, got {speed!r}")
    if not (fps > 0 and math.isfinite(fps)):
        raise ValueError(f"fps must be a positive number, got {fps!r}")
    if max_seconds is not None and not max_seconds > 0:
        raise ValueError(f"max_seconds must be positive, got {max_seconds!r}")
    t = np.asarray(response.t, dtype=float)
    if t.size == 0:
        raise ValueError("the response holds no saved states (simulate with save=True)")
    t0, t1 = float(t[0]), float(t[-1])
    video = (t1 - t0) / speed
    n = max(1, int(round(fps * video)))
    cut = False
    if max_seconds is not None and n > int(round(fps * max_seconds)):
        n, cut = max(1, int(round(fps * max_seconds))), True
    times = t0 + np.arange(n) * speed / fps
    if not cut and n > 1:
        times[-1] = t1
    return np.minimum(times, t1)


def _state_at(response, times: np.ndarray) -> dict[str, np.ndarray]:
    """Saved states at the frame times: positions interpolated linearly, the regime of the last
    saved state at or before each time (after an event: the new regime)."""
    t = np.asarray(response.t, dtype=float)
    _, xg = floor_motion(response)
    idx = np.clip(np.searchsorted(t, times, side="right") - 1, 0, t.size - 1)
    return {
        "xg": np.interp(times, t, xg),
        "u": np.interp(times, t, np.asarray(response.u)),
        "theta": np.interp(times, t, np.asarray(response.theta)),
        "regime": np.asarray(response.regime)[idx],
    }


def floor_scene(lo: float, hi: float, top: float, ground: float, *, axes_height: float):
    """A 6 × 4.5 in figure whose axes show x in [lo, hi] and y in [−ground, top] (m) at equal
    scales (the narrower range is widened to the axes' shape), with the floor drawn as a strip
    below y = 0. Returns (fig, ax, lo, hi, top) with the widened ranges."""
    box_w, box_h = 0.96 * 6.0, axes_height * 4.5  # axes size, in
    if (hi - lo) / (top + ground) < box_w / box_h:
        extra = 0.5 * ((top + ground) * box_w / box_h - (hi - lo))
        lo, hi = lo - extra, hi + extra
    else:
        top = (hi - lo) * box_h / box_w - ground
    fig = Figure(figsize=(6.0, 4.5))
    ax = fig.add_axes((0.02, 0.02, box_w / 6.0, box_h / 4.5))
    ax.set_xlim(lo, hi)
    ax.set_ylim(-ground, top)
    ax.set_axis_off()
    span = hi - lo
    ax.add_patch(Rectangle((lo - span, -ground), 3 * span, ground, facecolor="#e4e0d8", edgecolor="none", zorder=1))
    ax.plot([lo - span, hi + span], [0, 0], color="0.3", lw=1.2, zorder=2)
    return fig, ax, lo, hi, top


def write_frames(fig, path: Path, ext: str, *, fps: float, dpi: int, n_frames: int, draw, swatch: list[str]) -> None:
    """Draw frame k with ``draw(k)`` for k < n_frames and write them to ``path`` (a GIF with one
    palette for all frames, or an MP4 through ffmpeg)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if ext == ".gif":
        writer = _PalettePillowWriter.make(fps, swatch)
    else:
        from matplotlib.animation import FFMpegWriter

        writer = FFMpegWriter(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])
    with writer.saving(fig, str(path), dpi):
        for k in range(n_frames):
            draw(k)
            writer.grab_frame()


def _statue_outline(xc: float, yb: float, b: float, h: float, theta: float) -> np.ndarray:
    """Corners of the statue whose base centre rests at (xc, yb), rotated clockwise by θ about
    the corner (S·b, 0), S = sign θ (the key-point formula of the Response, Eqs. 8–9)."""
    pts = np.array([[-b, 0.0], [b, 0.0], [b, 2.0 * h], [-b, 2.0 * h]])
    if theta != 0.0:
        s = math.copysign(1.0, theta)
        c, sn = math.cos(theta), math.sin(theta)
        rx = pts[:, 0] - s * b
        ry = pts[:, 1]
        pts = np.column_stack((s * b + c * rx + sn * ry, -sn * rx + c * ry))
    return pts + np.array([xc, yb])


def resting_outline(x_ped: float, ph: float, pw: float, b: float, h: float, sign: float) -> np.ndarray:
    """Corners of a statue that has overturned towards ``sign`` (±1), drawn where it comes to rest:
    lying on the pedestal's top if its centre of mass is over the pedestal, else tipped over the
    pedestal's edge until its far end touches the floor (on the floor itself without a pedestal,
    ``ph = 0``). The model stops at the overturn; this is a drawing, not a simulation. m."""
    lying = _statue_outline(x_ped, ph, b, h, sign * 0.5 * math.pi)
    edge = 0.5 * pw
    if ph <= 0.0 or h <= edge - b:  # on the floor, or its centre of mass over the pedestal's top
        return lying
    reach = b + 2.0 * h - edge  # from the pedestal's edge to the far end
    if reach <= ph:  # shorter than the drop: it falls beside the pedestal and lies on the floor
        return lying + np.array([sign * (edge - b), -ph])
    tilt = math.asin(ph / reach)
    c, s = math.cos(tilt), math.sin(tilt)
    pivot = np.array([x_ped + sign * edge, ph])
    rel = lying - pivot
    turned = np.column_stack((c * rel[:, 0] + sign * s * rel[:, 1], -sign * s * rel[:, 0] + c * rel[:, 1]))
    return turned + pivot


def _sliding_trace(fig, response):
    """A small plot at the top left of the frame: the sliding u (mm) up to the frame's time, so
    that a few millimetres, invisible at the statue's scale, show. Returns ``show(t)``."""
    t = np.asarray(response.t, dtype=float)
    u_mm = 1e3 * np.asarray(response.u, dtype=float)
    lim = max(1.0, 1.15 * float(np.max(np.abs(u_mm)))) if u_mm.size else 1.0
    ax = fig.add_axes((0.09, 0.60, 0.30, 0.19))
    ax.set_xlim(float(t[0]), max(float(t[-1]), float(t[0]) + 1e-9))
    ax.set_ylim(-lim, lim)
    ax.axhline(0.0, color="0.7", lw=0.6)
    ax.tick_params(labelsize=10, length=2, pad=1)
    ax.set_xticks([])
    ax.locator_params(axis="y", nbins=3)
    ax.patch.set_alpha(0.85)
    who = "pedestal" if getattr(response.system, "pedestal", None) is not None else "statue"
    ax.set_title(f"{who} sliding u (mm)", fontsize=11, loc="left", pad=2)
    (line,) = ax.plot([], [], color=COLORS["sliding"], lw=1.3)

    def show(time: float) -> None:
        n = int(np.searchsorted(t, time, side="right"))
        line.set_data(t[:n], u_mm[:n])

    return show


def floor_ruler(ax, lo: float, hi: float, ground: float, *, fontsize: float = 9):
    """A ruler on the floor strip: labelled ticks in metres (1, 2 or 5 × 10^k apart, about six
    across the view) and unlabelled ones between. Returns ``move(shift)``, which redraws it
    shifted by ``shift`` (m; the floor's displacement), so the ruler moves with the floor."""
    span = hi - lo
    rough = span / 6
    base = 10 ** math.floor(math.log10(max(rough, 1e-9)))
    step = next(m * base for m in (1.0, 2.0, 5.0, 10.0) if m * base >= rough)
    minor = step / 5
    (major_ticks,) = ax.plot([], [], color="0.3", lw=1.0, zorder=2)
    (minor_ticks,) = ax.plot([], [], color="0.5", lw=0.6, zorder=2)
    first = math.floor((lo - span) / step) * step
    values = np.arange(first, hi + span, step)
    labels = [ax.text(0.0, -0.66 * ground, f"{v:g}", fontsize=fontsize, ha="center", va="center", color="0.25",
                      zorder=2, clip_on=True) for v in values]
    ax.text(hi - 0.01 * span, -0.66 * ground, "m", fontsize=fontsize, ha="right", va="center", color="0.25",
            zorder=3, bbox={"boxstyle": "square,pad=0.15", "facecolor": "#e4e0d8", "edgecolor": "none"})
    minors = np.arange(first, hi + span, minor)

    def move(shift: float) -> None:
        xs = values + shift
        major_ticks.set_data(np.repeat(xs, 3), np.tile([0.0, -0.32 * ground, np.nan], xs.size))
        ms = minors + shift
        minor_ticks.set_data(np.repeat(ms, 3), np.tile([0.0, -0.16 * ground, np.nan], ms.size))
        for text, x in zip(labels, xs):
            text.set_x(x)
            text.set_visible(lo < x < hi)

    move(0.0)
    return move


class _PalettePillowWriter:
    """Factory for a PillowWriter that stores frames as 8-bit palette images (a quarter of the
    memory of RGBA) with one palette for the whole GIF (no colour flicker)."""

    @staticmethod
    def make(fps: float, swatch: list[str]):
        from matplotlib.animation import PillowWriter
        from matplotlib.colors import to_rgb
        from PIL import Image

        class Writer(PillowWriter):
            def setup(self, fig, outfile, dpi=None):
                super().setup(fig, outfile, dpi=dpi)
                self._palette = None

            def grab_frame(self, **savefig_kwargs):
                from io import BytesIO

                buf = BytesIO()
                self.fig.savefig(buf, **{**savefig_kwargs, "format": "rgba", "dpi": self.dpi})
                w, h = self.frame_size
                im = Image.frombuffer("RGBA", (w, h), buf.getbuffer(), "raw", "RGBA", 0, 1).convert("RGB")
                if self._palette is None:
                    # palette from the first frame plus every colour (and its blends with white
                    # and black, for antialiasing) that later frames may show
                    rows = []
                    for c in swatch:
                        rgb = np.array(to_rgb(c))
                        for f in np.linspace(0.0, 1.0, 6):
                            rows.append(rgb * (1 - f) + f)
                            rows.append(rgb * (1 - f))
                    sw = (np.array(rows)[None, :, :] * 255).round().astype(np.uint8)
                    sw = np.repeat(sw, 4, axis=0)
                    src = Image.new("RGB", (max(w, sw.shape[1]), h + sw.shape[0]), "white")
                    src.paste(im, (0, 0))
                    src.paste(Image.fromarray(sw, "RGB"), (0, h))
                    self._palette = src.quantize(colors=255, method=Image.Quantize.MEDIANCUT)
                self._frames.append(im.quantize(palette=self._palette, dither=Image.Dither.NONE))

        return Writer(fps=fps)


def check_animation_path(path: str | os.PathLike[str]) -> str:
    """Check that an animation can be written to ``path`` before anything is simulated.

    Parameters
    ----------
    path : path-like
        ``*.gif`` or ``*.mp4``.

    Returns
    -------
    str
        The extension, lower case (``".gif"`` or ``".mp4"``).

    Raises
    ------
    ValueError
        Another extension.
    RuntimeError
        ``.mp4`` and matplotlib finds no ffmpeg (on PATH, or at ``rcParams["animation.ffmpeg_path"]``).
    """
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in (".gif", ".mp4"):
        raise ValueError(f"animation file must end in .gif or .mp4, got {path.name!r}")
    if ext == ".mp4":
        from matplotlib.animation import writers

        # the registry animate() writes through: it looks where matplotlib will look
        if not writers.is_available("ffmpeg"):
            raise RuntimeError(
                f"cannot write {path.name}: MP4 needs ffmpeg, which matplotlib does not find "
                "(on PATH, or at rcParams['animation.ffmpeg_path']); install ffmpeg or write a .gif instead"
            )
    return ext


def animate(
    response,
    path: str | os.PathLike[str],
    *,
    speed: float = 1.0,
    fps: float = 25,
    max_seconds: float | None = None,
    dpi: int = 80,
    title: str | None = None,
) -> Path:
    """Write an animation of ``response`` to ``path`` (a GIF, or an MP4 with ffmpeg).

    Parameters
    ----------
    response : Response
        Simulated with ``save=True``.
    path : path-like
        ``*.gif`` (Pillow, always available) or ``*.mp4`` (needs ``ffmpeg`` on PATH).
    speed : float
        Playback speed: 1 is real time, 0.5 half speed.
    fps : float
        Frames per second of the video.
    max_seconds : float, optional
        Longest video, s: the animation stops there (the frames are ``fps · duration / speed``,
        at most ``fps · max_seconds``; see :func:`frame_times`).
    dpi : int
        Resolution (the figure is 6 × 4.5 in: 480 × 360 pixels at 80 dpi).
    title : str, optional
        Text at the top of every frame.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        Unknown extension, or bad speed/fps/max_seconds.
    RuntimeError
        ``.mp4`` without ffmpeg (write a ``.gif`` instead); see :func:`check_animation_path`.
    """
    path = Path(path)
    ext = check_animation_path(path)
    times = frame_times(response, speed=speed, fps=fps, max_seconds=max_seconds)
    st = _state_at(response, times)

    statue = response.system.statue
    b, h = statue.b, statue.h
    ped = getattr(response.system, "pedestal", None)
    if ped is not None:
        pw = ped.width if ped.width is not None else 1.5 * statue.width
        ph = ped.height if ped.height is not None else 0.15 * statue.height
    else:
        pw = ph = 0.0
    alpha = response.alpha

    # fixed view wide enough for the whole motion (the world frame: the floor moves in it),
    # with equal scales on both axes
    x_body = st["xg"] + st["u"]
    margin = max(0.5 * pw, b + 2.0 * h) + 0.1 * (2.0 * h + ph)  # room for a fallen statue
    lo = float(np.min(x_body)) - margin
    hi = float(np.max(x_body)) + margin
    top = ph + 1.25 * math.hypot(2 * b, 2 * h)
    ground = 0.08 * top
    fig, ax, lo, hi, top = floor_scene(lo, hi, top, ground, axes_height=0.86)
    # a ruler that moves with the floor (the statue's sliding reads off it); a fixed reference
    # triangle at x = 0
    move_ruler = floor_ruler(ax, lo, hi, ground)
    ax.plot([0.0], [-ground], marker="^", color="0.2", ms=7, zorder=3, clip_on=False)
    ped_patch = Rectangle((0, 0), pw, ph, facecolor=COLORS["pedestal"], edgecolor="0.2", lw=1.0, zorder=3)
    if ped is not None:
        ax.add_patch(ped_patch)
    stat_patch = Polygon(_statue_outline(0.0, ph, b, h, 0.0), closed=True, facecolor=COLORS["statue"],
                         edgecolor="0.2", lw=1.0, zorder=4)
    ax.add_patch(stat_patch)
    (pivot,) = ax.plot([], [], "o", color="k", ms=3, zorder=5)
    # large enough to read when the picture is shrunk to a phone's width
    txt_t = fig.text(0.03, 0.95, "", fontsize=14, family="monospace", va="center")
    txt_th = fig.text(0.33, 0.95, "", fontsize=14, family="monospace", va="center")
    txt_reg = fig.text(0.97, 0.95, "", fontsize=14, va="center", ha="right",
                       bbox={"boxstyle": "round,pad=0.3", "facecolor": "white", "edgecolor": "0.5"})
    if title:
        fig.text(0.5, 0.885, title, fontsize=9, ha="center", va="center", color="0.3")
    t_fall = response.overturn_time if response.overturned else None
    trace = _sliding_trace(fig, response)

    def draw(k: int) -> None:
        xg, u, th = float(st["xg"][k]), float(st["u"][k]), float(st["theta"][k])
        reg = Regime(int(st["regime"][k]))
        x_ped = xg + u  # centre of the sliding body's base
        move_ruler(xg)
        ped_patch.set_xy((x_ped - 0.5 * pw, 0.0))
        fallen = t_fall is not None and times[k] >= t_fall - 1e-12
        if fallen and k == times.size - 1:  # the last frame: where the statue comes to rest
            stat_patch.set_xy(resting_outline(x_ped, ph, pw, b, h, math.copysign(1.0, th)))
            pivot.set_data([], [])
        else:
            stat_patch.set_xy(_statue_outline(x_ped, ph, b, h, th))
            pivot.set_data(([x_ped + math.copysign(b, th)], [ph]) if th != 0.0 else ([], []))
        trace(times[k])
        txt_t.set_text(f"t = {times[k]:6.2f} s")
        txt_th.set_text("fallen" if fallen else f"θ/α = {th / alpha:+.2f}")
        txt_reg.set_text("overturned" if fallen else REGIME_NAMES[reg])
        txt_reg.get_bbox_patch().set_facecolor("#f6c9c4" if fallen else REGIME_COLORS[reg])

    swatch = [*REGIME_COLORS.values(), COLORS["statue"], COLORS["pedestal"], "#e4e0d8", "#f6c9c4", "#000000"]
    write_frames(fig, path, ext, fps=fps, dpi=dpi, n_frames=times.size, draw=draw, swatch=swatch)
    return path
