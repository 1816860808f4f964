"""``rocking paper``: rerun the seed paper's case studies (Figs. 9–12) and write the outcome table.

``register(app)`` adds the command to the typer application of :mod:`rocking.cli.main`.
"""

from __future__ import annotations

import os
import shutil
import uuid
from pathlib import Path
from typing import Annotated

import typer

__all__ = ["register", "paper"]


def _publish(tmp: Path, out: Path) -> None:
    """Move the finished files of ``tmp`` into ``out`` (a rename if ``out`` does not exist yet)."""
    if not out.exists():
        os.replace(tmp, out)
        return
    for item in sorted(tmp.iterdir()):
        os.replace(item, out / item.name)
    tmp.rmdir()


def paper(
    out: Annotated[Path, typer.Option("--out", "-o", help="Directory for the figures and tables.")] = Path("paper-out"),
    omega: Annotated[
        float | None,
        typer.Option(
            "--omega",
            help="Angular frequency ω of A·cos ωt, 1/s (default 2π·1.2 = 7.5398; the paper prints 7.53).",
        ),
    ] = None,
) -> None:
    """Rerun the paper's eight case studies (Table 2) in four variants each, write one figure per
    case (paper_fig_<case>.png, all on one vertical scale), paper_outcomes.csv (every column) and
    paper_outcomes.md (a summary, the tables and their key) into --out, and print the Markdown."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from ..analyses.paper import outcome_table_markdown, run_paper_cases, write_outcome_table
    from ..viz.paper_figures import write_paper_figures

    if omega is not None and not omega > 0:
        raise typer.BadParameter("must be a positive number", param_hint="--omega")
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise typer.BadParameter(f"{out} exists and is not a directory", param_hint="--out")
    from ..solver.warmup import ensure_compiled

    ensure_compiled()  # before the progress bar: the message must not fight with it
    parent = out.resolve().parent
    parent.mkdir(parents=True, exist_ok=True)
    # A hidden sibling directory (same file system, so the final move is a rename), created with
    # the user's umask, unlike mkdtemp's 0700.
    tmp = parent / f".{out.name}-{uuid.uuid4().hex[:12]}.tmp"
    tmp.mkdir()
    try:
        responses: dict = {}
        console = Console(stderr=True)
        with Progress(
            TextColumn("{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            console=console,
            disable=not console.is_terminal,  # no bar in pipes, CI logs and tests
        ) as bar:
            task = bar.add_task("simulating (the first run compiles)", total=None)

            def progress(done: int, total: int, label: str) -> None:
                bar.update(task, completed=done, total=total, description=f"simulating {label:<34}")

            rows = run_paper_cases(omega=omega, progress=progress, responses=responses)
            bar.update(task, description="writing figures")
            write_paper_figures(responses, tmp)
            write_outcome_table(rows, tmp)
        _publish(tmp, out)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    typer.echo(outcome_table_markdown(rows), nl=False)
    typer.echo(f"\nwrote {out}/paper_outcomes.csv, paper_outcomes.md and {len(responses) // 4} figures", err=True)


def register(app: typer.Typer) -> None:
    """Add the ``paper`` command to ``app``."""
    app.command("paper")(paper)
