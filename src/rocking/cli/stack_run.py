"""``rocking run`` of a stack (a file with ``[[blocks]]``): the tables it prints and the files it writes.

:func:`rocking.cli.main.run_command` simulates the stack (:func:`rocking.runner.run_response`) and
hands the result to :func:`show_stack_run`, which prints, as for one statue, the verdict coloured
by outcome, then one row per block (from the floor up) and one per interface (the floor's first),
and with ``--out`` writes ``timeseries.csv``, ``summary.json`` and ``response.png``
(:mod:`rocking.io.stack_output`).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rich import box
from rich.console import Group
from rich.markup import escape
from rich.table import Table

from ..io.output import summary_json
from ..results.wording import need_text
from ..io.stack_output import STACK_OUTPUT_FILES, check_stack_output_space, fall_text, write_stack_outputs
from .render import _num, _time, outcome_markup

__all__ = ["show_stack_run", "stack_tables"]


def _mm(x: float | None) -> str:
    return _num(None if x is None else 1e3 * x, ".2f")


def _degrees(x: float | None) -> str:
    return _num(None if x is None else math.degrees(x), ".2f")


def stack_tables(summary: Mapping[str, Any], *, frictions: list[float | None] | None = None,
                 title: str | None = None) -> Group:
    """A stack run's summary for the terminal: the verdict, then a table of the blocks and one of
    the interfaces.

    Parameters
    ----------
    summary : mapping
        :meth:`rocking.stack.StackResponse.summary` (SI units, radians).
    frictions : list of float or None, optional
        The static friction of each interface (None: it never slips), shown next to the
        friction the run needed.
    title : str, optional
        E.g. the config file.
    """
    s = summary
    head = Table(title=escape(title) if title else None, show_header=False, title_justify="left")
    head.add_column("quantity", style="bold")
    head.add_column("value")
    head.add_row("outcome", outcome_markup(s))
    head.add_row("impacts", str(s["impacts"]))
    head.add_row("simulated until", _time(s["end_time"]))
    head.add_row("energy balance error", _num(s["energy_balance_error"], ".1e"))

    blocks = Table(title="blocks, from the floor up (rotation and sliding relative to the block or floor below)",
                   title_justify="left", box=box.SIMPLE_HEAD)
    for name in ("block", "overturned", "peak rotation (°)", "peak sliding (mm)", "residual sliding (mm)"):
        blocks.add_column(name, justify="left" if name in ("block", "overturned") else "right")
    for k, b in enumerate(s["blocks"]):
        fell = f"[red]{fall_text(s, k)}[/]" if b["overturned"] else escape(fall_text(s, k))
        blocks.add_row(escape(b["name"]), fell, _degrees(b["peak_rotation"]), _mm(b["peak_sliding"]),
                       _mm(b["residual_sliding"]))

    interfaces = Table(title="interfaces, from the floor up", title_justify="left", box=box.SIMPLE_HEAD)
    for name in ("interface", "friction needed", "μs given", "slip path (mm)", "impacts"):
        interfaces.add_column(name, justify="left" if name == "interface" else "right")
    for k, f in enumerate(s["interfaces"]):
        given = "—"
        if frictions is not None:
            given = "never slips" if frictions[k] is None else _num(frictions[k], ".3g")
        interfaces.add_row(escape(f["name"]), need_text(f["required_friction"]), given, _mm(f["slip_path"]),
                           str(f.get("impacts", "—")))
    return Group(head, blocks, interfaces)


def show_stack_run(cfg: Any, response: Any, config: Path, *, out: Path | None, as_json: bool,
                   animate: bool = False) -> None:
    """Write the outputs of a stack run (with ``--out``) and print its summary.

    Parameters
    ----------
    cfg : rocking.io.config.StackConfig
    response : rocking.stack.StackResponse
    config : Path
        The file as the user named it (the title of the tables).
    out : Path or None
        ``--out``.
    as_json : bool
        ``--json``: the summary as JSON on stdout, the "wrote" line on stderr.
    animate : bool
        ``--animate``: also animation.gif in ``out``.
    """
    from .main import _stderr, _stdout

    summary = response.summary()
    if out is not None:
        # the exact count now (events add rows): still nothing written if it does not fit
        check_stack_output_space(len(response.t), response.stack.n, out,
                                 hint="raise simulation.save_dt or shorten simulation.duration")
        from .main import write_run_files

        draw = None
        if animate:  # the animation module (and its imports) only when asked for
            from ..viz.stack_animation import animate_stack

            draw = (lambda r, path, speed, fps: animate_stack(r, path, speed=speed, fps=fps, title=config.name))
        write_run_files(out, response, lambda: write_stack_outputs(response, out, config=cfg), draw)
    wrote = f"wrote {', '.join(STACK_OUTPUT_FILES + (('animation.gif',) if animate else ()))} to {out}"
    if as_json:
        sys.stdout.write(summary_json(summary) + "\n")
        if out is not None:
            _stderr().print(wrote, markup=False, soft_wrap=True)  # a path is not broken
        return
    frictions = [f.friction.static if f.friction is not None else None for f in response.stack.interfaces]
    console = _stdout()
    console.print(stack_tables(summary, frictions=frictions, title=str(config)))
    if out is not None:
        console.print(wrote, markup=False, soft_wrap=True)
