"""The ``rocking`` command line.

Commands::

    rocking run CONFIG.toml [--json] [--out DIR]   simulate a configuration (a statue, or a stack)
    rocking records [--json]                       list the bundled accelerograms
    rocking info RECORD [--json]                   properties of one record

Exit codes: 0 success; 2 bad input (invalid config, unreadable record, wrong
arguments) or a run over a resource limit (``simulation.max_samples``, the free space for
``--out``, see ``docs/limits.md``), reported as one ``error: ...`` line on stderr without a
traceback and without any output file; 1 a failed simulation or an output that cannot be
written; 130 interrupted by Ctrl-C, 143 by SIGTERM (129 SIGHUP), with the temporary outputs
removed. Set ``ROCKING_DEBUG=1`` to see the traceback of an unexpected error.
"""

from __future__ import annotations

import errno
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
from rich.markup import escape as rich_escape
from typer._click import exceptions as click_exceptions  # typer vendors click
from typer._click import utils as click_utils

from .. import __version__
from ..io.config import ConfigError, StackConfig, load_config
from ..io.output import OUTPUT_FILES, OutputSpaceError, check_output_space, summary_json, write_outputs
from ..io.records import RecordError, UnitsConflictError, bundled_records, read_record
from ..runner import run_response
from ..simulation import ResourceLimitError, SimulationError
from ..solver.warmup import ensure_compiled, ensure_stack_compiled
from .interrupts import exit_code, signal_name, stop_signals
from .limits import MAX_SAMPLES_OPTION, ResourceRefused, gif_speed, gif_speed_note, preflight, with_max_samples
from .progress import delayed_spinner
from .render import g_units, record_info, record_table, summary_table

__all__ = ["InputError", "app", "main"]


class InputError(ValueError):
    """Bad input found by a command (exit code 2); the message is shown as is."""


class OutputError(OSError):
    """The outputs could not be written (exit code 1)."""


# typer 0.29 prints a flag's value type ("<bool>") in --help as if the flag took a value; a flag
# takes none, so it shows none.
_display_type_rich = typer.core.TyperOption.display_type_rich


def _flag_without_type(self, ctx):
    return None if self.is_flag and not self.count else _display_type_rich(self, ctx)


typer.core.TyperOption.display_type_rich = _flag_without_type

app = typer.Typer(
    name="rocking",
    help="Rocking, sliding and overturning of statues on pedestals under floor shaking.",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,  # main() reports errors itself, in one line
)


def write_run_files(out: Path, response, write, draw=None) -> None:
    """Write a run's files into ``out`` with ``write()`` and, if ``draw`` is given, its
    animation.gif with ``draw(response, path, speed=…, fps=…)``: a long run plays faster, so that
    the GIF stays within MAX_FRAMES frames (memory). An OSError becomes OutputError (exit 1)."""
    with delayed_spinner(f"writing {out}", console=_stderr()):
        try:
            write()
        except OSError as exc:
            raise OutputError(f"cannot write the outputs to {out}: {exc}") from None
    if draw is not None:
        speed = gif_speed(float(response.t[-1] - response.t[0]), ANIMATION_FPS)
        note = gif_speed_note(speed)
        if note:
            _stderr().print(note, markup=False)
        with delayed_spinner("drawing the animation", console=_stderr()):
            draw(response, out / "animation.gif", speed=speed, fps=ANIMATION_FPS)


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
#: Frames per second of ``run --animate``.
ANIMATION_FPS = 25


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
            help="Folder for timeseries.csv, timeseries.nc, summary.json and response.png (a stack: "
            "timeseries.csv, summary.json and response.png).",
            show_default=False,
        ),
    ] = None,
    animate: Annotated[
        bool, typer.Option("--animate", help="Also write animation.gif (needs --out).")
    ] = False,
    max_samples: Annotated[int | None, MAX_SAMPLES_OPTION] = None,
) -> None:
    """Simulate CONFIG and print the summary (SI units, radians; a stack's per block and interface)."""
    cfg = with_max_samples(load_config(config), max_samples)  # every input error surfaces here
    if out is not None and out.exists() and not out.is_dir():
        raise InputError(f"--out: {out} exists and is not a directory")
    if out is not None:
        from .views import _check_parent

        _check_parent(out)  # `--out afile/sub`: refused now, not after the run
    if animate and out is None:
        raise InputError("--animate needs --out DIR to write animation.gif into")
    stack = isinstance(cfg, StackConfig)
    preflight(cfg, out=out)  # memory and disk limits, before the solver is compiled or run
    # each says so on stderr when the first run on this machine must compile
    if stack:
        ensure_stack_compiled()
    else:
        ensure_compiled()
    with delayed_spinner(f"simulating {config.name}", console=_stderr()):
        # without --out only the summary is shown: the time series would be stored for nothing
        cfg, response = run_response(cfg, save=out is not None)
    if stack:
        from .stack_run import show_stack_run

        return show_stack_run(cfg, response, config, out=out, as_json=as_json, animate=animate)
    summary = response.summary()
    if out is not None:
        # the exact count now (events add rows): still nothing written if it does not fit
        check_output_space(len(response.t), out, hint="raise simulation.save_dt or shorten simulation.duration")
        draw = None
        if animate:  # the animation module (and its imports) only when asked for
            from ..viz import animate as draw

        write_run_files(out, response, lambda: write_outputs(response, out, config=cfg), draw)
    # every file written, by name
    wrote = f"wrote {', '.join(OUTPUT_FILES + (('animation.gif',) if animate else ()))} to {out}"
    if as_json:
        sys.stdout.write(summary_json(summary) + "\n")
        if out is not None:
            _stderr().print(wrote, markup=False)
        return
    console = _stdout()
    console.print(summary_table(summary, title=str(config)))
    if out is not None:
        console.print(wrote, markup=False)


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
    units_override: Annotated[
        bool,
        typer.Option("--units-override", help="Use --units even where the file's header states other units."),
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help="Print the properties as JSON.")] = False,
) -> None:
    """Show a record's format, dt, points, duration, PGA and PGV."""
    if units_override and units is None:
        raise InputError("--units-override needs --units (the units that replace the header's)")
    try:
        motion = read_record(record, format=format, units=units, units_override=units_override)
    except FileNotFoundError as exc:
        raise InputError(str(exc).replace("\n", " ")) from None
    except UnitsConflictError as exc:
        # the reader's way out names the API argument; say it with the options of this command
        where = f"{exc.path}: line {exc.line}" if exc.line is not None else str(exc.path)
        raise InputError(
            f"{where}: the header states the units {exc.header_units!r}, but --units says {exc.given_units!r}; "
            "omit --units to use the header's, or add --units-override if the header is wrong"
        ) from None
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


def _interrupted(exc: BaseException) -> int:
    """Say how the command was stopped; return 128 + the signal's number (130 Ctrl-C, 143 SIGTERM).

    A study's interrupt carries how many of its runs are saved
    (:class:`rocking.analyses.store.StudyInterrupted`); a ``typer.Abort`` raised by a command
    counts as Ctrl-C (or as its cause, if it has one).
    """
    cause = exc.__cause__ if isinstance(exc, typer.Abort) and exc.__cause__ is not None else exc
    if hasattr(cause, "saved") and hasattr(cause, "total"):
        text = str(cause)
    elif signal_name(cause) == "Ctrl-C":
        text = "interrupted"
    else:
        text = f"interrupted by {signal_name(cause)}"
    sys.stderr.write(text + "\n")
    sys.stderr.flush()
    return exit_code(cause)


def _as_help(text: str | None) -> str | None:
    """A docstring or help string as rich shows it right: each paragraph on one line (rich wraps
    it to the terminal; a line break kept from the source shows mid-sentence) and square brackets
    escaped (``[[blocks]]`` is a TOML table, not rich markup: unescaped, it showed as "[]")."""
    if not text:
        return text
    paragraphs = (" ".join(p.split()) for p in text.split("\n\n"))
    return rich_escape("\n\n".join(p for p in paragraphs if p))


@lru_cache(maxsize=1)
def _command() -> Any:
    command = typer.main.get_command(app)
    for sub in [command, *getattr(command, "commands", {}).values()]:
        sub.help = _as_help(sub.help)
        for param in sub.params:
            if getattr(param, "help", None):
                param.help = _as_help(param.help)
    return command


def _invoke(args: list[str]) -> Any:
    """Parse ``args`` and run the command: what click's ``main(standalone_mode=False)`` does, except
    that a ``KeyboardInterrupt`` propagates. Typer's ``main`` turns it into the bare exit code 130,
    which would lose the signal (SIGTERM is 143) and what a study saved before it stopped."""
    command = _command()
    try:
        with command.make_context("rocking", args) as ctx:
            return command.invoke(ctx)
    except typer.Exit as exc:  # --version, --help
        return exc.exit_code
    except OSError as exc:
        if exc.errno != errno.EPIPE:
            raise
        # the reader of a pipe went away (`rocking records | head`): no error, as click does
        sys.stdout = click_utils.PacifyFlushWrapper(sys.stdout)
        sys.stderr = click_utils.PacifyFlushWrapper(sys.stderr)
        return 1


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line and return the exit code (the ``rocking`` console script).

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.

    Returns
    -------
    int
        0 success, 1 failed simulation or output, 2 bad input or over a resource limit,
        130 interrupted (Ctrl-C), 143 terminated (SIGTERM; 129 for SIGHUP).
    """
    args = list(argv) if argv is not None else sys.argv[1:]
    try:
        with stop_signals():  # SIGTERM/SIGHUP unwind like Ctrl-C: temporary outputs are removed
            rv = _invoke(args)
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
    except (typer.Abort, KeyboardInterrupt) as exc:
        return _interrupted(exc)
    except (ResourceLimitError, ResourceRefused, OutputSpaceError) as exc:  # over a limit: change the input
        _error(str(exc))
        return 2
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
