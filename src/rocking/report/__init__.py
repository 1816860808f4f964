"""Reports of one simulation: a self-contained ``report.html`` and a ``report.pdf``.

    >>> from rocking.report import write_report
    >>> write_report("examples/statue_on_pedestal.toml", "results/pedestal")   # doctest: +SKIP
    PosixPath('results/pedestal/report.html')

A stack of blocks (:mod:`rocking.stack`) gets the same report with a check per block and per
interface, a table of each, and every block in the figures (:mod:`rocking.report.stack`).

The HTML page has its CSS inline and its figures embedded as base64 PNG (no external URL); the
PDF is made with matplotlib's PdfPages on A4 pages, each with a footer (library version, date,
input file and its short SHA-256, page number). Both say the same: a one-sentence verdict, the
table of pass/fail checks, the key figures, the response and energy plots as numbered figures
with the text that discusses them, the warnings, the inputs, the model's assumptions and the
symbols.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .content import Check, ReportContent, build_content, check_clearance, checks, verdict, verdict_class

__all__ = [
    "Check", "ReportContent", "build_content", "check_clearance", "checks", "verdict", "verdict_class", "write_report",
]


def _resolve(source: Any) -> tuple[Any, Any]:
    """(config or None, response) from a Response or StackResponse, a (config, response) pair, or
    a config (simulated here)."""
    from ..results.response import Response
    from ..stack import StackResponse

    responses = (Response, StackResponse)
    if isinstance(source, responses):
        return None, source
    if isinstance(source, tuple) and len(source) == 2 and isinstance(source[1], responses):
        return source
    if isinstance(source, (str, os.PathLike, Mapping)) or type(source).__name__ in ("Config", "StackConfig"):
        from ..runner import run_response

        return run_response(source)
    raise TypeError(
        "write_report needs a Response (or a stack's StackResponse), a (config, response) pair, a config "
        f"file path, a config dict or a Config; got {type(source).__name__}"
    )


def _content_and_figures(response: Any, config: Any, *, title: str | None, inputs: Mapping[str, Any] | None,
                         clearance: float | None) -> tuple[ReportContent, list[Any], str]:
    """What the report says, its figures (in the order of ``content.figures``) and the verdict's
    colour, for one statue or for a stack of blocks."""
    from ..stack import StackResponse

    if isinstance(response, StackResponse):
        from .stack import build_stack_content, stack_figures, stack_verdict_class

        content = build_stack_content(response, config, title=title, inputs=inputs, clearance=clearance)
        return content, stack_figures(response, config), stack_verdict_class(response, content.checks)
    from ..viz.plots import plot_energy, plot_response

    content = build_content(response, config, title=title, inputs=inputs, clearance=clearance)
    figures = [plot_response(response), plot_energy(response).figure]
    return content, figures, verdict_class(response, content.checks)


def write_report(
    config_or_response: Any,
    out_dir: str | os.PathLike[str],
    *,
    title: str | None = None,
    inputs: Mapping[str, Any] | None = None,
    pdf: bool = True,
    dpi: int = 110,
    clearance: float | None = None,
) -> Path:
    """Write ``report.html`` (and ``report.pdf``) into ``out_dir``.

    Parameters
    ----------
    config_or_response : Response, StackResponse, (config, response), path, dict, Config or StackConfig
        What to report. A configuration (TOML path, dict of the same tables, or a loaded
        :class:`~rocking.io.config.Config` or :class:`~rocking.io.config.StackConfig`) is
        simulated first with :func:`rocking.runner.run_response`. A stack of blocks
        (``[[blocks]]``) gets the stack's report: a check per block and per interface, a table
        of each, and every block in the figures (the motion and options are shown when its
        config is given).
    out_dir : path-like
        Folder, created if needed.
    title : str, optional
        Page title (default: the statue's size, pedestal or not, and the config file name).
    inputs : mapping, optional
        Extra inputs shown as a "Configuration" table (e.g. the raw TOML tables), for callers
        that only hold a Response.
    pdf : bool
        Also write ``report.pdf``.
    dpi : int
        Resolution of the figures embedded in the HTML page.
    clearance : float, optional
        Free space around the sliding body (the pedestal, the statue alone, or a stack's block
        on the floor), m: the checks compare its peak sliding with it.

    Returns
    -------
    pathlib.Path
        The HTML file.

    Raises
    ------
    ConfigError
        For an invalid configuration (from :func:`rocking.runner.run_response`).
    TypeError
        For anything else that is not a Response or a configuration.
    ValueError
        For a clearance that is not a positive length.
    """
    from .html import png_base64, write_html
    from .pdf import write_pdf

    clearance = check_clearance(clearance)  # before simulating: bad input fails fast
    config, response = _resolve(config_or_response)
    content, figures, klass = _content_and_figures(response, config, title=title, inputs=inputs,
                                                   clearance=clearance)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    # the HTML first: the PDF redraws the figures at its own size
    html_path = write_html(content, [png_base64(fig, dpi) for fig in figures], out / "report.html",
                           verdict_class=klass)
    if pdf:
        write_pdf(content, figures, out / "report.pdf", verdict_class=klass)
    return html_path
