"""Readable tables for the terminal: a run's summary, the bundled records, one record."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from rich import box
from rich.markup import escape
from rich.table import Table

from ..constants import STANDARD_GRAVITY
from ..results.wording import need_text

__all__ = ["outcome_markup", "record_info", "record_table", "summary_table"]


def _time(x: float | None) -> str:
    return "—" if x is None else f"{x:.3f} s"


def _num(x: float | None, fmt: str = ".4g") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    return format(x, fmt)


def outcome_markup(summary: Mapping[str, Any]) -> str:
    """The verdict of a run as rich markup: red if it overturned, yellow if undetermined, else green.
    For a stack, red if any block fell: the top-level keys describe the top block only."""
    text = summary.get("verdict") or ("overturned" if summary["overturned"] else "did not overturn")
    if summary["overturned"] or any(b.get("overturned") for b in summary.get("blocks", ())):
        return f"[bold red]{escape(text)}[/]"
    if text.startswith("undetermined"):
        return f"[bold yellow]{escape(text)}[/]"
    return f"[bold green]{escape(text)}[/]"


def summary_table(summary: Mapping[str, Any], *, title: str | None = None) -> Table:
    """The summary of a run as a two-column table (values with units).

    Parameters
    ----------
    summary : mapping
        :meth:`rocking.Response.summary` (SI units, radians).
    title : str, optional
        Table title, e.g. the config file.
    """
    s = summary
    table = Table(title=escape(title) if title else None, show_header=False, title_justify="left")
    table.add_column("quantity", style="bold")
    table.add_column("value")
    table.add_row("outcome", outcome_markup(s))
    table.add_row("|θ| first exceeded α", _time(s["exceeded_alpha_time"]))
    ratio = s.get("peak_rotation_over_alpha")
    ratio_text = f" = {_num(ratio, '.3f')} α" if ratio is not None else ""
    table.add_row("peak rotation", f"{_num(s['peak_rotation'])} rad{ratio_text}")
    table.add_row("peak sliding", f"{_num(1e3 * s['peak_sliding'], '.2f')} mm")
    table.add_row("residual sliding", f"{_num(1e3 * s['residual_sliding'], '.2f')} mm")
    table.add_row("impacts", str(s["impacts"]))
    table.add_row("rocking started", _time(s["first_rocking_time"]))
    table.add_row("sliding started", _time(s["first_sliding_time"]))
    table.add_row("friction needed under statue", need_text(s["required_top_friction"]))
    if "impact_floor_friction_needed" in s:
        table.add_row("friction needed at impacts", _num(s["impact_floor_friction_needed"], ".3f"))
    if "end_time" in s:
        table.add_row("simulated until", _time(s["end_time"]))
    if "energy_balance_error" in s:
        table.add_row("energy balance error", _num(s["energy_balance_error"], ".1e"))
    for w in s.get("warnings") or []:
        table.add_row("[yellow]warning[/]", escape(str(w)))
    return table


def record_table(rows: list[Mapping[str, Any]]) -> Table:
    """The bundled records: name, format, dt (s), points, duration (s), PGA (g)."""
    table = Table(title="Bundled records", title_justify="left", box=box.SIMPLE_HEAD)
    table.add_column("name", no_wrap=True)
    table.add_column("format")
    table.add_column("dt (s)", justify="right")
    table.add_column("points", justify="right")
    table.add_column("duration (s)", justify="right")
    table.add_column("PGA (g)", justify="right")
    for r in rows:
        table.add_row(
            escape(r["name"]),
            escape(r["format"]),
            f"{r['dt']:g}",
            str(r["points"]),
            f"{r['duration']:.2f}",
            f"{r['pga_g']:.3f}",
        )
    return table


def record_info(info: Mapping[str, Any]) -> Table:
    """One record's properties as a two-column table."""
    table = Table(title=escape(info["name"]), show_header=False, title_justify="left")
    table.add_column("quantity", style="bold", no_wrap=True)
    table.add_column("value", overflow="fold")
    table.add_row("file", escape(info["file"]))
    table.add_row("format", escape(info["format"]))
    if info.get("event"):
        table.add_row("event", escape(info["event"]))
    table.add_row("units in file", escape(str(info["units"])))
    table.add_row("dt", f"{info['dt']:g} s")
    table.add_row("points", str(info["points"]))
    table.add_row("duration", f"{info['duration']:.3f} s")
    table.add_row("PGA", f"{info['pga_g']:.4f} g = {info['pga']:.4f} m/s²")
    table.add_row("PGV", f"{info['pgv']:.4f} m/s (trapezoid integral, no baseline correction)")
    return table


def g_units(acceleration: float) -> float:
    """m/s² -> g (standard gravity 9.80665 m/s², as the record reader uses)."""
    return acceleration / STANDARD_GRAVITY
