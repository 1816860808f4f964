"""``rocking report`` and ``rocking animate``: the views, one command each."""

from __future__ import annotations

import os
import shutil
import tempfile
import uuid
from pathlib import Path
from typing import Annotated

import typer

from .limits import MAX_FRAMES, MAX_SAMPLES_OPTION, check_frames, preflight, with_max_samples


def register(app: typer.Typer) -> None:
    @app.command("report")
    def report_command(
        config: Annotated[Path, typer.Argument(metavar="CONFIG", help="TOML configuration file.")],
        out: Annotated[Path, typer.Option("--out", "-o", help="Folder for report.html and report.pdf.")] = Path(
            "report"
        ),
        max_samples: Annotated[int | None, MAX_SAMPLES_OPTION] = None,
        clearance: Annotated[float | None, typer.Option(
            help="Free space around the sliding pedestal (or statue, or a stack's block on the floor), m: the "
                 "report checks its peak sliding against it.")] = None,
    ) -> None:
        """Simulate CONFIG (one statue, or a stack of blocks) and write a self-contained HTML report
        and its PDF."""
        from ..io.config import StackConfig, load_config
        from ..report import check_clearance, write_report
        from ..runner import run_response
        from ..solver.warmup import ensure_compiled, ensure_stack_compiled

        clearance = check_clearance(clearance)  # before the run: a bad value must not cost a simulation
        cfg = with_max_samples(load_config(config), max_samples)
        _check_out_folder(out)  # before simulating: a run must not end in FileExistsError
        preflight(cfg)  # the saved series within simulation.max_samples, before compiling
        # each says so on stderr when the first run on this machine must compile
        if isinstance(cfg, StackConfig):
            ensure_stack_compiled()
        else:
            ensure_compiled()
        result = run_response(cfg)
        _write_atomically(out, lambda tmp: write_report(result, tmp, clearance=clearance))
        typer.echo(f"wrote {out / 'report.html'} and {out / 'report.pdf'}")

    @app.command("animate")
    def animate_command(
        config: Annotated[Path, typer.Argument(metavar="CONFIG", help="TOML configuration file.")],
        out: Annotated[Path, typer.Option("--out", "-o", help="Animation file (.gif, or .mp4 with ffmpeg).")] = Path(
            "animation.gif"
        ),
        speed: Annotated[float, typer.Option(help="Playback speed: 1 = real time, 0.25 = four times slower.")] = 1.0,
        fps: Annotated[int, typer.Option(help="Frames per second.")] = 25,
        max_frames: Annotated[int, typer.Option(
            "--max-frames", min=1,
            help="Most frames to draw (a GIF holds them all in memory, about 0.35 MB each); more is refused.",
        )] = MAX_FRAMES,
        max_samples: Annotated[int | None, MAX_SAMPLES_OPTION] = None,
    ) -> None:
        """Simulate CONFIG and draw the floor, pedestal and statue (or every block of a stack) moving,
        to scale."""
        from ..io.config import StackConfig, load_config
        from ..runner import run_response
        from ..solver.warmup import ensure_compiled
        from ..viz import animate
        from ..viz.animation import check_animation_path
        from .main import InputError

        if speed <= 0 or fps <= 0:
            raise ValueError(f"--speed and --fps must be positive, got {speed} and {fps}")
        cfg = with_max_samples(load_config(config), max_samples)
        stack = isinstance(cfg, StackConfig)
        hint = "raise --speed to {speed} or more, lower --fps, or raise --max-frames"
        # everything that would stop the writing, found before the simulation
        if out.is_dir():
            raise InputError(f"--out: {out} is a directory; give a file name such as {out / 'animation.gif'}")
        _check_parent(out)
        try:
            check_animation_path(out)
        except (ValueError, RuntimeError) as exc:
            raise InputError(f"--out: {exc}") from None
        preflight(cfg)  # the saved series within simulation.max_samples
        if cfg.simulation.duration is not None:  # the run lasts this long (unless it falls): refuse now
            check_frames(cfg.simulation.duration, speed=speed, fps=fps, max_frames=max_frames, hint=hint)
        if not stack:
            ensure_compiled()
        _, response = run_response(cfg)
        check_frames(float(response.t[-1] - response.t[0]), speed=speed, fps=fps, max_frames=max_frames, hint=hint)
        out.parent.mkdir(parents=True, exist_ok=True)
        # a name, not mkstemp's 0600 file: the writer creates it with the user's umask, like any
        # file they write; hidden, beside the target (the final move is a rename)
        tmp = str(out.parent / f".{out.stem}-{uuid.uuid4().hex[:12]}.tmp{out.suffix}")
        try:
            if stack:
                from ..viz.stack_animation import animate_stack

                animate_stack(response, tmp, speed=speed, fps=fps, title=config.name)
            else:
                animate(response, tmp, speed=speed, fps=fps)
            os.replace(tmp, out)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
        typer.echo(f"wrote {out}")


def _check_out_folder(out: Path) -> None:
    """Refuse an --out folder that cannot be made (an existing file, or a file on its path)."""
    from .main import InputError

    if out.exists() and not out.is_dir():
        raise InputError(f"--out: {out} exists and is not a directory")
    _check_parent(out)


def _check_parent(out: Path) -> None:
    """Refuse an --out whose nearest existing ancestor is a file (``--out afile/report``)."""
    from .main import InputError

    p = out.parent
    while not p.exists() and p != p.parent:
        p = p.parent
    if p.exists() and not p.is_dir():
        raise InputError(f"--out: {p} is a file, so {out} cannot be created")


def _write_atomically(out: Path, write) -> None:
    """Write into a fresh folder beside ``out``; move the files in only when all succeeded."""
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    try:
        write(tmp)
        out.mkdir(exist_ok=True)
        for f in tmp.iterdir():
            os.replace(f, out / f.name)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
