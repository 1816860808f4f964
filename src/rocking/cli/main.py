"""The ``rocking`` command line.

Commands::

    rocking run CONFIG.toml [--json] [--out DIR]   simulate a configuration
    rocking records [--json]                       list the bundled accelerograms
    rocking info RECORD [--json]                   properties of one record

Exit codes: 0 success; 2 bad input (invalid config, unreadable record, wrong
arguments), reported as one ``error: ...`` line on stderr without a traceback and
without any output file; 1 a failed simulation or an output that cannot be written;
130 interrupted. Set ``ROCKING_DEBUG=1`` to see the traceback of an unexpected error.
"""

from __future__ import annotations

import json
import os
import sys
import warnings
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from typer._click import exceptions as click_exceptions  # typer vendors click

from .. import __version__
from ..io.config import ConfigError, load_config
from ..io.output import OUTPUT_FILES, summary_json, write_outputs
from ..io.records import RecordError, bundled_records, read_record
from ..runner import run_response
from ..simulation import SimulationError
from .progress import delayed_spinner
from .render import g_units, record_info, record_table, summary_table

__all__ = ["InputError", "app", "main"]


class InputError(ValueError):
    """Bad input found by a command (exit code 2); the message is shown as is."""


class OutputError(OSError):
    """The outputs could not be written (exit code 1)."""


app = typer.Typer(
    name="rocking",
    help="Rocking, sliding and overturning of statues on pedestals under floor shaking.",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,  # main() reports errors itself, in one line
)


def _stdout() -> Console:
    # built per call: tests swap sys.stdout, and a console made at import would miss it
    console = Console(highlight=False)
    if not console.is_terminal:
        # a pipe or file has no width: rich's 80 columns would cut the record names
        console = Console(highlight=False, width=120)
    return console


def _stderr() -> Console:
    return Console(stderr=True, highlight=False)


def _version(value: bool) -> None:
    if value:
        print(f"rocking {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=_version, is_eager=True, help="Show the version and exit."
        ),
    ] = False,
) -> None:
    """Rocking, sliding and overturning of statues on pedestals under floor shaking."""


# ---------------------------------------------------------------------------- run
@app.command("run")
def run_command(
    config: Annotated[Path, typer.Argument(metavar="CONFIG", help="TOML configuration file.", show_default=False)],
    as_json: Annotated[
        bool, typer.Option("--json", help="Print the summary as JSON (nothing else on stdout).")
    ] = False,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out",
            "-o",
            help="Folder for timeseries.csv, timeseries.nc, summary.json and response.png.",
            show_default=False,
        ),
    ] = None,
    animate: Annotated[
        bool, typer.Option("--animate", help="Also write animation.gif (needs --out).")
    ] = False,
) -> None:
    """Simulate CONFIG and print the summary (SI units, radians)."""
    cfg = load_config(config)  # every input error surfaces here, before any output
    if out is not None and out.exists() and not out.is_dir():
        raise InputError(f"--out: {out} exists and is not a directory")
    if animate and out is None:
        raise InputError("--animate needs --out DIR to write animation.gif into")
    with delayed_spinner(f"simulating {config.name}", console=_stderr()):
        cfg, response = run_response(cfg)
    summary = response.summary()
    if out is not None:
        with delayed_spinner(f"writing {out}", console=_stderr()):
            try:
                write_outputs(response, out, config=cfg)
            except OSError as exc:
                raise OutputError(f"cannot write the outputs to {out}: {exc}") from None
        if animate:
            from ..viz import animate as write_animation

            with delayed_spinner("drawing the animation", console=_stderr()):
                write_animation(response, out / "animation.gif")
    if as_json:
        sys.stdout.write(summary_json(summary) + "\n")
        if out is not None:
            _stderr().print(f"wrote {', '.join(OUTPUT_FILES)} to {out}", markup=False)
        return
    console = _stdout()
    console.print(summary_table(summary, title=str(config)))
    if out is not None:
        console.print(f"wrote {', '.join(OUTPUT_FILES)} to {out}", markup=False)


# ------------------------------------------------------------------------ records
def _record_row(name: str, motion: Any) -> dict[str, Any]:
    return {
        "name": name,
        "format": str(motion.meta.get("format", "")),
        "dt": motion.dt,
        "points": motion.n,
        "duration": motion.duration,
        "pga": motion.pga,
        "pga_g": g_units(motion.pga),
    }


@app.command("records")
def records_command(
    as_json: Annotated[bool, typer.Option("--json", help="Print the list as JSON.")] = False,
) -> None:
    """List the bundled accelerograms (name, dt, points, PGA in g)."""
    rows = [_record_row(name, read_record(path)) for name, path in bundled_records().items()]
    if as_json:
        sys.stdout.write(json.dumps(rows, indent=2) + "\n")
    else:
        _stdout().print(record_table(rows))


# --------------------------------------------------------------------------- info
@app.command("info")
def info_command(
    record: Annotated[
        str,
        typer.Argument(metavar="RECORD", help="A record file, or the name of a bundled record.", show_default=False),
    ],
    format: Annotated[
        str | None, typer.Option("--format", help="peer, esm or two-column (default: detect).")
    ] = None,
    units: Annotated[
        str | None,
        typer.Option("--units", help="Units of the stored values if the file lacks them (g, cm/s2, m/s2)."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the properties as JSON.")] = False,
) -> None:
    """Show a record's format, dt, points, duration, PGA and PGV."""
    try:
        motion = read_record(record, format=format, units=units)
    except FileNotFoundError as exc:
        raise InputError(str(exc).replace("\n", " ")) from None
    info = _record_row(motion.name, motion)
    info.update(
        file=motion.source,
        units=motion.units,
        pgv=motion.pgv,
        event=str(motion.meta.get("event", "")),
    )
    if as_json:
        sys.stdout.write(json.dumps(info, indent=2) + "\n")
    else:
        _stdout().print(record_info(info))


# ----------------------------------------------------------------- extra commands
def _register_optional_commands() -> None:
    """Add the commands that live in their own modules (each has ``register(app)``)."""
    import importlib

    for name in ("paper", "views", "studies", "serve"):
        try:
            module = importlib.import_module(f"{__package__}.{name}")
        except ImportError as exc:
            if getattr(exc, "name", None) == f"{__package__}.{name}":
                continue  # the module is not there: the CLI simply has no such command
            # present but broken: keep the other commands working, and say why
            warnings.warn(f"'rocking {name}' commands are unavailable: {exc}", stacklevel=2)
            continue
        module.register(app)


_register_optional_commands()


# --------------------------------------------------------------------------- main
def _error(message: str) -> None:
    """The one line a user sees for a failure (plain text: no markup, no traceback)."""
    text = " ".join(str(message).split())
    sys.stderr.write(f"error: {text}\n")
    sys.stderr.flush()


@lru_cache(maxsize=1)
def _command() -> Any:
    return typer.main.get_command(app)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line and return the exit code (the ``rocking`` console script).

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.

    Returns
    -------
    int
        0 success, 1 failed simulation or output, 2 bad input, 130 interrupted.
    """
    args = list(argv) if argv is not None else sys.argv[1:]
    try:
        rv = _command().main(args=args, prog_name="rocking", standalone_mode=False)
    except click_exceptions.UsageError as exc:
        if type(exc).__name__ == "NoArgsIsHelpError":  # bare `rocking`: show the help
            sys.stderr.write(exc.format_message() + "\n")
            return 2
        hint = f" (see '{exc.ctx.command_path} --help')" if exc.ctx is not None else ""
        _error(exc.format_message() + hint)
        return 2
    except click_exceptions.ClickException as exc:
        _error(exc.format_message())
        return exc.exit_code
    except (typer.Abort, KeyboardInterrupt):
        _error("interrupted")
        return 130
    except (ConfigError, RecordError, InputError) as exc:
        _error(str(exc))
        return 2
    except SimulationError as exc:
        _error(f"the simulation failed: {exc}")
        return 1
    except OutputError as exc:
        _error(str(exc))
        return 1
    except ValueError as exc:  # any other value the API refused: still the user's input
        if os.environ.get("ROCKING_DEBUG"):
            raise
        _error(str(exc))
        return 2
    except Exception as exc:
        if os.environ.get("ROCKING_DEBUG"):
            raise
        _error(f"unexpected {type(exc).__name__}: {exc} (set ROCKING_DEBUG=1 for the traceback)")
        return 1
    return rv if isinstance(rv, int) else 0
