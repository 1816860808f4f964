"""PDF report with matplotlib's PdfPages (no extra dependency): text pages, then the figures."""

from __future__ import annotations

import textwrap
from pathlib import Path

from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure

from .content import ReportContent

_A4 = (8.27, 11.69)
_WRAP = 100  # characters per line at 8.5 pt on A4 with 0.7 in margins


def _lines(content: ReportContent) -> list[tuple[str, str]]:
    """(style, text) lines: styles title, h, body, row, gap."""
    out: list[tuple[str, str]] = [("title", line) for line in textwrap.wrap(content.title, 75)]
    out.append(("gap", ""))
    for line in textwrap.wrap(content.verdict, 80):
        out.append(("verdict", line))
    out += [("gap", ""), ("h", "Key figures")]
    for k, v in content.key_figures:
        out.append(("row", f"{k}\t{v}"))
    out += [("gap", ""), ("h", "Warnings")]
    for w in content.warnings or ["None."]:
        wrapped = textwrap.wrap(w, _WRAP - 2)
        out += [("body", ("• " if i == 0 else "  ") + line) for i, line in enumerate(wrapped)]
    for section, rows in content.inputs.items():
        out += [("gap", ""), ("h", f"Inputs: {section}")]
        out += [("row", f"{k}\t{v}") for k, v in rows]
    out += [("gap", ""), ("h", "Model assumptions")]
    for a in content.assumptions:
        wrapped = textwrap.wrap(a, _WRAP - 2)
        out += [("body", ("• " if i == 0 else "  ") + line) for i, line in enumerate(wrapped)]
    return out


def _text_pages(content: ReportContent) -> list[Figure]:
    sizes = {"title": 13.0, "h": 10.5, "verdict": 11.0, "body": 8.5, "row": 8.5, "gap": 6.0}
    pages: list[Figure] = []
    fig = None
    y = 0.0
    top, bottom, left = 0.94, 0.05, 0.085
    for style, text in _lines(content):
        step = sizes[style] * 1.45 / 72 / _A4[1]
        if fig is None or y - step < bottom:
            fig = Figure(figsize=_A4)
            pages.append(fig)
            y = top
            if style == "gap":
                continue
        y -= step
        if style == "row":
            name, value = text.split("\t", 1)
            fig.text(left, y, name, fontsize=sizes[style], color="0.35", va="baseline")
            vals = textwrap.wrap(value, 60) or [""]
            for i, v in enumerate(vals):
                if i:
                    y -= step
                fig.text(left + 0.42, y, v, fontsize=sizes[style], va="baseline")
        elif style != "gap":
            weight = "bold" if style in ("title", "h", "verdict") else "normal"
            color = {"verdict": "#8b1a10" if "overturns" in content.verdict else "#1f5c30"}.get(style, "black")
            fig.text(left, y, text, fontsize=sizes[style], fontweight=weight, color=color, va="baseline")
    return pages


def write_pdf(content: ReportContent, figures: list[Figure], path: str | Path) -> Path:
    """Write the text pages then one page per figure; returns the path."""
    path = Path(path)
    with PdfPages(path, metadata={"Title": content.title, "Creator": "rocking", "CreationDate": None}) as pdf:
        for page in _text_pages(content):
            pdf.savefig(page)
        for fig in figures:
            pdf.savefig(fig)
    return path
