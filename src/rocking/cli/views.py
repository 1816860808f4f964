"""``rocking report`` and ``rocking animate``: the views, one command each."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path
from typing import Annotated

import typer


def register(app: typer.Typer) -> None:
    @app.command("report")
    def report_command(
        config: Annotated[Path, typer.Argument(metavar="CONFIG", help="TOML configuration file.")],
        out: Annotated[Path, typer.Option("--out", "-o", help="Folder for report.html and report.pdf.")] = Path(
            "report"
        ),
    ) -> None:
        """Simulate CONFIG and write a self-contained HTML report and its PDF."""
        from ..io.config import load_config
        from ..report import write_report
        from ..runner import run_response

        cfg = load_config(config)
        result = run_response(cfg)
        _write_atomically(out, lambda tmp: write_report(result, tmp))
        typer.echo(f"wrote {out / 'report.html'} and {out / 'report.pdf'}")

    @app.command("animate")
    def animate_command(
        config: Annotated[Path, typer.Argument(metavar="CONFIG", help="TOML configuration file.")],
        out: Annotated[Path, typer.Option("--out", "-o", help="Animation file (.gif, or .mp4 with ffmpeg).")] = Path(
            "animation.gif"
        ),
        speed: Annotated[float, typer.Option(help="Playback speed: 1 = real time, 0.25 = four times slower.")] = 1.0,
        fps: Annotated[int, typer.Option(help="Frames per second.")] = 25,
    ) -> None:
        """Simulate CONFIG and draw the floor, pedestal and statue moving, to scale."""
        from ..io.config import load_config
        from ..runner import run_response
        from ..viz import animate

        if speed <= 0 or fps <= 0:
            raise ValueError(f"--speed and --fps must be positive, got {speed} and {fps}")
        cfg = load_config(config)
        _, response = run_response(cfg)
        out.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(suffix=out.suffix, dir=out.parent)
        os.close(fd)
        try:
            animate(response, tmp, speed=speed, fps=fps)
            os.replace(tmp, out)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
        typer.echo(f"wrote {out}")


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
