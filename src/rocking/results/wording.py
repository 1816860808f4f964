"""How a result is worded for people (the terminal, the report, the web page), where the number
alone would mislead."""

from __future__ import annotations

import math

#: A friction ratio |T|/N above this is no coefficient a material has (dry friction stays below
#: about 1.5, and an impact of a block 20 times as tall as it is wide, with r = 0.3, needs
#: (h/b)(1 − r)/(1 + r) ≈ 11). A need that large comes from a contact whose normal force falls
#: to zero while it still carries a tangential force, as before a lift-off: the need then grows
#: without bound, and the number is only what the solver saw at its last state before it.
UNBOUNDED_NEED = 100.0


def need_text(need: float | None, fmt: str = ".3f", *, short: bool = False) -> str:
    """A required friction coefficient for people: formatted with ``fmt`` (``"0.412"``), ``"—"``
    if None or NaN, and ``"> 100 (unbounded)"`` above :data:`UNBOUNDED_NEED` (``"unbounded"``
    with ``short``, for a narrow table column)."""
    if need is None or (isinstance(need, float) and math.isnan(need)):
        return "—"
    if need > UNBOUNDED_NEED:
        return "unbounded" if short else f"> {UNBOUNDED_NEED:.0f} (unbounded)"
    return format(need, fmt)
