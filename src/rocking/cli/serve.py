"""``rocking serve``: the local web app (:mod:`rocking.web`).

``register(app)`` adds the command to the typer application of :mod:`rocking.cli.main`.
"""

from __future__ import annotations

from typing import Annotated

import typer

__all__ = ["register", "serve"]


def serve(
    host: Annotated[
        str, typer.Option("--host", help="Address to listen on; 0.0.0.0 opens the app to the network (no accounts).")
    ] = "127.0.0.1",
    port: Annotated[int, typer.Option("--port", help="TCP port (0: any free port).", min=0, max=65535)] = 8000,
    timeout: Annotated[
        float, typer.Option("--timeout", help="Longest run (simulation, plots, animation), s.")
    ] = 120.0,
    sweep_timeout: Annotated[float, typer.Option("--sweep-timeout", help="Longest friction design sweep, s.")] = 600.0,
    max_upload_mb: Annotated[float, typer.Option("--max-upload-mb", help="Largest uploaded record, MB.")] = 5.0,
    max_duration: Annotated[
        float, typer.Option("--max-duration", help="Longest simulated time of one run (record and free motion), s.")
    ] = 600.0,
    max_jobs_per_client: Annotated[
        int, typer.Option("--max-jobs-per-client", help="Runs and sweeps one address may have in progress at once.")
    ] = 2,
) -> None:
    """Serve the web page: choose or upload a record, describe the statue and pedestal, run, and see
    the verdict, animation and plots; run a friction design sweep and download its report.
    Stop with Ctrl+C."""
    from ..web.server import serve as run_server
    from ..web.server import settings_from

    try:
        settings = settings_from(timeout, sweep_timeout, max_upload_mb, max_duration=max_duration,
                                 max_jobs_per_client=max_jobs_per_client)
    except ValueError as exc:
        name, _, message = str(exc).partition(" ")
        raise typer.BadParameter(message, param_hint=name) from None
    from ..solver.warmup import TYPICAL_SECONDS, cache_is_warm

    if cache_is_warm() is False:
        # the worker processes compile it in the background (web/_preload.py): say why the
        # first run on the page waits
        typer.echo(f"rocking: compiling the solver in the background (first run on this machine, about "
                   f"{TYPICAL_SECONDS} s; cached afterwards); the first run on the page waits for it", err=True)
    try:
        run_server(host, port, settings)
    except OSError as exc:
        raise typer.BadParameter(f"cannot listen on {host}:{port}: {exc.strerror or exc}", param_hint="--port") from None


def register(app: typer.Typer) -> None:
    """Add the ``serve`` command to ``app``."""
    app.command("serve")(serve)
