"""Self-contained HTML report: inline CSS, figures embedded as base64 PNG, no external URL."""

from __future__ import annotations

import base64
import io
from html import escape
from pathlib import Path

from .content import FAIL, NOT_APPLICABLE, NOT_CHECKED, PASS, UNDETERMINED, DataTable, ReportContent

_RESULT_CLASSES = {PASS: ("pass", "pass"), FAIL: ("fail", "fail"), UNDETERMINED: ("undetermined", "undetermined"),
                   NOT_CHECKED: ("not-checked", "not checked"), NOT_APPLICABLE: ("na", "n/a")}

_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif;
       color: #222; max-width: 960px; margin: 2em auto; padding: 0 1em; line-height: 1.45; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; }
h2 { font-size: 1.15em; margin-top: 1.8em; border-bottom: 1px solid #ddd; padding-bottom: 0.2em; }
h3 { font-size: 1em; margin: 1em 0 0.3em; color: #444; }
p.verdict { font-size: 1.15em; padding: 0.7em 1em; border-radius: 6px; border-left: 6px solid; }
p.verdict.safe { background: #eef7ee; border-color: #2d7d46; }
p.verdict.fails { background: #fbeceb; border-color: #c0392b; }
p.verdict.stopped { background: #fff6e5; border-color: #d68910; }
table { border-collapse: collapse; margin: 0.3em 0 0.8em; font-size: 0.93em; max-width: 100%; }
td, th { border-bottom: 1px solid #e5e5e5; padding: 0.25em 0.8em 0.25em 0; text-align: left; vertical-align: top;
         overflow-wrap: break-word; }
td.value { overflow-wrap: anywhere; }  /* a long path breaks inside its cell instead of widening the page */
td.result, th.result { white-space: nowrap; }
th { color: #555; font-weight: 600; }
td.name { color: #555; min-width: 12em; }
td.pass { color: #1f7a3a; font-weight: 600; }
td.fail { color: #c0392b; font-weight: 700; text-transform: uppercase; }
td.undetermined { color: #b36b00; font-weight: 600; }
td.not-checked, td.na { color: #777; }
td.symbol { font-weight: 600; white-space: nowrap; }
.wide { max-width: 100%; overflow-x: auto; }
table.data td, table.data th { padding-right: 1.1em; }
.inputs { display: grid; grid-template-columns: repeat(auto-fit, minmax(min(420px, 100%), 1fr)); gap: 0 2em; }
@media (max-width: 600px) { td.name { min-width: 7em; } td, th { padding-right: 0.5em; }
  table.checks { font-size: 0.78em; } table.checks td, table.checks th { padding-right: 0.4em; } }
figure { margin: 1em 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #eee; }
figcaption { font-size: 0.9em; color: #555; }
ul.warnings li { color: #8a4b00; }
ul li { margin-bottom: 0.3em; }
details { margin: 0.5em 0; }
footer { margin-top: 3em; font-size: 0.8em; color: #888; overflow-wrap: anywhere; }
"""


def png_base64(fig, dpi: int = 110) -> str:
    """A matplotlib figure as a base64 PNG string (no metadata, so it is reproducible)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    return base64.b64encode(buf.getvalue()).decode("ascii")


def _rows(rows) -> str:
    return "\n".join(f'<tr><td class="name">{escape(k)}</td><td class="value">{escape(v)}</td></tr>'
                     for k, v in rows)


def _checks(content: ReportContent) -> str:
    rows = []
    for c in content.checks:
        klass, text = _RESULT_CLASSES[c.result]
        rows.append(f"<tr><td>{escape(c.name)}</td><td>{escape(c.value)}</td><td>{escape(c.limit)}</td>"
                    f'<td class="result {klass}">{escape(text)}</td></tr>')
    return ('<div class="wide"><table class="checks"><tr><th>check</th><th>value</th><th>limit</th>'
            '<th class="result">result</th></tr>\n' + "\n".join(rows) + "</table></div>")


def _data_table(table: DataTable, level: str = "h3") -> str:
    """A table with a header row; it scrolls inside the page on a narrow screen."""
    head = "".join(f"<th>{escape(h)}</th>" for h in table.header)
    body = "\n".join("<tr>" + "".join(f"<td>{escape(c)}</td>" for c in row) + "</tr>" for row in table.rows)
    return (f"<{level}>{escape(table.heading)}</{level}>\n"
            f'<div class="wide"><table class="data"><tr>{head}</tr>\n{body}</table></div>')


def _figures_and_key_figures(content: ReportContent, images: list[str]) -> str:
    """Each figure's section; the key figures (and the result tables) follow the first (the
    motion they sum up)."""
    key_figures = f"<h2>Key figures</h2>\n<table>\n{_rows(content.key_figures)}\n</table>"
    key_figures += "".join("\n" + _data_table(t) for t in content.tables_at("results"))
    parts = []
    for text, data in zip(content.figures, images):
        parts.append(
            f"<h2>{escape(text.heading)}</h2>\n<p>{escape(text.discussion)}</p>\n"
            f'<figure id="figure-{text.number}"><img alt="{escape(text.label)}" src="data:image/png;base64,{data}">'
            f"<figcaption><b>Figure {text.number}:</b> {escape(text.caption)}</figcaption></figure>"
        )
        if text.number == 1:
            parts.append(key_figures)
    if not parts:
        parts.append(key_figures)
    return "\n\n".join(parts)


def render_html(content: ReportContent, images: list[str], *, verdict_class: str) -> str:
    """The HTML page: ``images`` are the base64 PNGs of ``content.figures``, in order."""
    inputs = "\n".join(
        f"<div><h3>{escape(section)}</h3><table>{_rows(rows)}</table></div>"
        for section, rows in content.inputs.items()
    )
    input_tables = "\n".join(_data_table(t) for t in content.tables_at("inputs"))
    assumptions = "\n".join(f"<li>{escape(a)}</li>" for a in content.assumptions)
    warnings = (
        '<ul class="warnings">' + "\n".join(f"<li>{escape(w)}</li>" for w in content.warnings) + "</ul>"
        if content.warnings else "<p>None: every assumption of the model held during the run.</p>"
    )
    symbols = "\n".join(f'<tr><td class="symbol">{escape(k)}</td><td>{escape(v)}</td></tr>'
                         for k, v in content.symbols)
    if content.events:
        ev = "\n".join(
            "<tr>" + "".join(f"<td>{escape(c)}</td>" for c in row) + "</tr>" for row in content.events
        )
        events = (
            f"<details><summary>{len(content.events)} event(s)</summary>"
            "<table><tr>" + "".join(f"<th>{escape(h)}</th>" for h in content.event_header) + "</tr>"
            f"{ev}</table></details>"
        )
    else:
        events = "<p>No events.</p>"
    footer = escape(content.provenance.footer) if content.provenance is not None else "rocking"
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{escape(content.title)}</title>
<style>{_CSS}</style>
</head>
<body>
<h1>{escape(content.title)}</h1>
<p class="verdict {verdict_class}">{escape(content.verdict)}</p>

<h2>Checks</h2>
{_checks(content)}

<h2>Warnings</h2>
{warnings}

{_figures_and_key_figures(content, images)}

<h2>Inputs</h2>
{input_tables}
<div class="inputs">
{inputs}
</div>

<h2>Model assumptions</h2>
<ul>
{assumptions}
</ul>

<h2>Symbols</h2>
<table>
{symbols}
</table>

<h2>Events</h2>
{events}

<footer>{footer}</footer>
</body>
</html>
"""


def write_html(content: ReportContent, images: list[str], path: str | Path, *,
               verdict_class: str = "safe") -> Path:
    """Write the page; ``images`` are the base64 PNGs of ``content.figures``, in order."""
    path = Path(path)
    path.write_text(render_html(content, images, verdict_class=verdict_class), encoding="utf-8")
    return path
