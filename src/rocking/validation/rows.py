"""Rows of the validation manual and the rule that turns each into a verdict.

A row compares the library ("ours") with a reference value. The reference is one of:

* ``exact``: a published closed form that holds without approximation under the model's
  assumptions (or a published statement that can be counted, such as a regime map). The row
  agrees when ours is within ``tol`` (relative) of it.
* ``approx``: a published small-angle / slender-block approximation. The row also carries an
  independent exact integration written in :mod:`rocking.validation.exact`. It passes when ours
  agrees with that integration within ``tol``; the approximation's own error (published against
  exact) is reported and classed as holding (within ``band``) or not, which is the formula's
  range of validity, not a fault of the library.
* ``crosscheck``: the published result is qualitative (a safe region exists, the critical timing
  is at the impact); ours is checked against the independent integration or the stated property.
* ``peer``: an outside solver (MuJoCo) on the same case; ``exact`` holds its value. It agrees
  within ``tol`` of ours, or differs for the modelling reason given in ``note``.
* ``limitation``: a case outside a published formula's range that the library still accepts;
  explained in the row and listed in the manual's findings.
* ``pending``: needs a part of the library that does not exist yet.

Anything else that does not meet its tolerance is ``DIFFERS``: the test suite fails on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

#: statuses a row may end with that do not fail the manual's test
ACCEPTED = ("agrees", "approximation holds", "approximation fails (explained)", "differs (explained)", "limitation",
            "pending")


@dataclass
class Row:
    """One comparison. Values are floats in ``unit`` (or None when not applicable)."""

    id: str  #: stable identifier, e.g. "H3.2"; the test matches rows by it
    source: str  #: short citation, e.g. "Housner 1963"
    case: str  #: what is computed, with its parameters
    kind: str  #: "exact", "approx", "crosscheck", "limitation" or "pending"
    published: float | None = None  #: the published value (closed form evaluated, or a number)
    ours: float | None = None  #: the library's value, through its public API
    exact: float | None = None  #: independent exact integration (approx/crosscheck rows)
    unit: str = ""
    tol: float = 1e-6  #: relative tolerance of ours against the reference that decides the row
    band: float = 0.01  #: approx rows: relative error up to which the approximation "holds"
    passed: bool | None = None  #: crosscheck/qualitative rows: outcome of the stated check
    note: str = ""  #: explanation shown in the verdict (limitations, qualitative checks)
    published_label: str = ""  #: replaces the number in the published column (qualitative rows)
    status: str = field(default="", init=False)
    detail: str = field(default="", init=False)

    def __post_init__(self):
        self.status, self.detail = judge(self)

    @property
    def verdict(self) -> str:
        """The verdict as printed: the status, then why."""
        return f"{self.status}: {self.detail}" if self.detail else self.status

    @property
    def rel_diff(self) -> float | None:
        """|ours − published| / |published| (None when either is missing)."""
        return rel(self.ours, self.published)


def rel(a: float | None, b: float | None) -> float | None:
    """Relative difference |a − b| / |b| (absolute when b = 0); None when either is missing."""
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
        return None
    return abs(a - b) / abs(b) if b != 0 else abs(a - b)


def fmt_rel(x: float | None) -> str:
    """A relative difference as shown in the tables: "3.1e-10", "0" or "—"."""
    if x is None:
        return "—"
    if x == 0:
        return "0"
    return f"{x:.1e}"


def fmt_pct(x: float) -> str:
    """A relative error as a percentage with two significant digits (0.0012 → "0.12 %")."""
    pct = 100.0 * x
    if pct == 0:
        return "0 %"
    return f"{pct:.2g} %" if pct >= 0.01 else f"{pct:.1e} %"


def judge(row: Row) -> tuple[str, str]:
    """(status, detail) of a row; see the module docstring. The manual prints
    "**status**: detail"."""
    if row.kind == "pending":
        return "pending", row.note
    if row.kind == "limitation":
        return "limitation", row.note
    if row.kind == "exact":
        d = rel(row.ours, row.published)
        detail = f"rel. diff {fmt_rel(d)}, tolerance {row.tol:.0e}" + _tail(row.note)
        return ("agrees" if d is not None and d <= row.tol else "DIFFERS"), detail
    if row.kind == "crosscheck":
        d = rel(row.ours, row.exact)
        ok = (row.passed is not False) and (row.exact is None or (d is not None and d <= row.tol))
        parts = [f"exact integration agrees with ours to {fmt_rel(d)} (tolerance {row.tol:.0e})"
                 if row.exact is not None else "", row.note]
        return ("agrees" if ok else "DIFFERS"), "; ".join(x for x in parts if x)
    if row.kind == "approx":
        d_exact = rel(row.ours, row.exact)
        if d_exact is None or d_exact > row.tol:
            return "DIFFERS", f"ours and the exact integration differ by {fmt_rel(d_exact)} (tolerance {row.tol:.0e})"
        err = rel(row.published, row.exact)
        backing = f"exact integration agrees with ours to {fmt_rel(d_exact)}"
        if err is not None and err <= row.band:
            return "approximation holds", (f"within {fmt_pct(err)} of the exact value (band {fmt_pct(row.band)}); "
                                           f"{backing}" + _tail(row.note))
        return "approximation fails (explained)", (f"off by {fmt_pct(err)}: the small-angle formula is outside its "
                                                   f"range here; {backing}" + _tail(row.note))
    if row.kind == "peer":
        # exact = the outside solver's value, compared with ours; ours must match the reference
        d_ref = rel(row.ours, row.published)
        if row.published is not None and (d_ref is None or d_ref > 1e-4):
            return "DIFFERS", f"ours is {fmt_rel(d_ref)} from the reference"
        d = rel(row.exact, row.ours)
        if d is not None and d <= row.tol:
            return "agrees", f"MuJoCo within {fmt_pct(d)} of ours (band {fmt_pct(row.tol)})"
        if row.note and d is not None:
            return "differs (explained)", f"MuJoCo {fmt_pct(d)} from ours; {row.note}"
        return "DIFFERS", f"MuJoCo {fmt_rel(d)} from ours"
    raise ValueError(f"unknown row kind {row.kind!r}")


def _tail(note: str) -> str:
    return f"; {note}" if note else ""


@dataclass
class Section:
    """A titled group of rows with its explanatory text (Markdown) and optional extra tables."""

    key: str
    title: str
    intro: str
    rows: list[Row]
    extra: str = ""  #: Markdown after the rows (grids of the range of validity, notes)
    exact_label: str = "exact integration"  #: heading of the column that holds ``Row.exact``
    validity: list[str] = field(default_factory=list)  #: one line per range-of-validity finding


def fmt_value(x: float | None, unit: str = "") -> str:
    """Values in the tables: 10 significant digits, so the test can compare them closely."""
    if x is None:
        return "—"
    if isinstance(x, float) and math.isnan(x):
        return "n/a"
    s = f"{x:.10g}"
    return f"{s} {unit}".strip() if unit else s
