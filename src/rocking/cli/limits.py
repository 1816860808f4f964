"""Resource checks of the commands that simulate, done before the simulation starts.

* The saved series: :func:`rocking.simulation.prepare` refuses a run that would store more than
  ``simulation.max_samples`` samples (``--max-samples`` overrides the config);
  :func:`preflight` calls it before the solver is compiled or run, so a refusal is immediate.
* ``--out``: the files grow with the samples (:func:`rocking.io.output.estimate_output_bytes`,
  up to about 150 bytes a sample); they are refused when they would not fit in the free space of
  the target's file system, before the run and again, with the exact count, after it.
* Animations: a GIF holds every frame in memory while it is written (about 0.35 MB a frame at
  the default size) and draws about 100 frames a second, so at most :data:`MAX_FRAMES` frames are
  drawn unless ``--max-frames`` says otherwise.

Every refusal is a :class:`ResourceRefused` (a ``ValueError``: exit code 2) whose message names
what to change.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import typer

__all__ = ["MAX_FRAMES", "MAX_SAMPLES_OPTION", "ResourceRefused", "check_frames", "preflight", "with_max_samples"]

#: Frames an animation may have by default: 2 minutes at 25 frames a second, about 1 GB of
#: memory and half a minute of drawing for a GIF (measured: 0.35 MB and 11 ms a frame).
MAX_FRAMES = 3000
#: Memory of one GIF frame while the file is written, bytes (480 × 360 pixels at 80 dpi).
FRAME_BYTES = 350_000

#: ``--max-samples`` of the commands that keep the time series (run, report, animate).
MAX_SAMPLES_OPTION = typer.Option(
    "--max-samples",
    min=1,
    help="Largest saved time series, in samples (overrides simulation.max_samples of CONFIG; default "
    "5 000 000, about 200 MB). A run that needs more is refused before it starts.",
    show_default=False,
)

#: What the user can change to shorten the saved series (for the messages).
_SERIES_HINT = "raise simulation.save_dt, shorten simulation.duration, or choose another --out"


class ResourceRefused(ValueError):
    """A command would need more memory, disk or time than its limits allow (exit code 2)."""


def with_max_samples(cfg: Any, max_samples: int | None) -> Any:
    """``cfg`` (a :class:`rocking.io.config.Config`) with ``simulation.max_samples`` replaced,
    or unchanged when ``max_samples`` is None."""
    if max_samples is None:
        return cfg
    if isinstance(max_samples, bool) or int(max_samples) < 1:
        raise ResourceRefused(f"--max-samples must be an integer >= 1, got {max_samples!r}")
    sim = cfg.simulation.model_copy(update={"max_samples": int(max_samples)})
    return cfg.model_copy(update={"simulation": sim})


def preflight(cfg: Any, *, out: Path | None = None) -> int:
    """Refuse, before anything is compiled or simulated, a run over its limits.

    Parameters
    ----------
    cfg : rocking.io.config.Config or StackConfig
    out : path, optional
        The ``--out`` folder, whose file system must hold the outputs.

    Returns
    -------
    int
        The planned number of saved samples.

    Raises
    ------
    rocking.simulation.ResourceLimitError
        Over ``simulation.max_samples`` (the message names the fields).
    rocking.io.output.OutputSpaceError
        Outputs larger than the free space where they go.
    """
    from ..io.config import StackConfig
    from ..io.output import check_output_space, planned_samples
    from ..simulation import ResourceLimitError, prepare

    system, motion, options, duration = cfg.to_specs()
    n = planned_samples(motion, options, duration)
    if isinstance(cfg, StackConfig):
        if n > options.max_samples:  # the check prepare() makes for one statue
            raise ResourceLimitError(
                f"simulation.save_dt: the run would store {n:.3g} samples, over simulation.max_samples = "
                f"{options.max_samples:.3g}; raise simulation.save_dt, shorten simulation.duration, or raise "
                "simulation.max_samples (--max-samples on the command line)")
        if out is not None:
            from ..io.stack_output import check_stack_output_space

            check_stack_output_space(n, len(cfg.blocks), out, hint=_SERIES_HINT)
        return n
    prepare(system, motion, duration=duration, options=options)  # the memory check of simulate()
    if out is not None:
        check_output_space(n, out, hint=_SERIES_HINT)
    return n


def check_frames(duration: float, *, speed: float, fps: float, max_frames: int, hint: str) -> int:
    """The frames of an animation of ``duration`` seconds (s of motion), refused past ``max_frames``.

    Parameters
    ----------
    duration : float
        Simulated time shown, s.
    speed, fps : float
        Playback speed (1 = real time) and frames per second.
    max_frames : int
        The limit.
    hint : str
        What to change, for the message (the options of the command).

    Raises
    ------
    ResourceRefused
    """
    frames = max(1, int(round(fps * duration / speed)))
    if frames > max_frames:
        from ..io.output import human_bytes

        need = fps * duration / max_frames  # the speed that fits
        raise ResourceRefused(
            f"the animation of {duration:.6g} s at speed {speed:g} and {fps:g} frames/s would draw {frames:.3g} "
            f"frames (about {human_bytes(frames * FRAME_BYTES)} of memory), over the limit of {max_frames} frames; "
            + hint.format(speed=_round_up(need))
        )
    return frames


def _round_up(x: float) -> str:
    """A speed to suggest: ``x`` rounded up to two significant digits."""
    if x <= 0:
        return "1"
    scale = 10 ** (math.floor(math.log10(x)) - 1)
    return f"{math.ceil(x / scale) * scale:.3g}"


def gif_speed(span: float, fps: float) -> float:
    """Playback speed of ``run --animate``'s GIF for a run of ``span`` seconds: real time, or
    faster so that it stays within MAX_FRAMES frames (a GIF holds them all in memory)."""
    return max(1.0, fps * span / MAX_FRAMES)


def gif_speed_note(speed: float) -> str | None:
    """What to tell the user when the GIF plays faster than real time."""
    if speed <= 1.0:
        return None
    return (f"animation.gif plays {speed:.3g} times faster than real time (at most {MAX_FRAMES} frames); "
            "`rocking animate --speed` chooses the speed")
