"""Coulomb friction of an interface: static and kinetic coefficients."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True, kw_only=True, slots=True)
class Friction:
    """Coulomb friction with a static (μs) and a kinetic (μk ≤ μs) coefficient.

    Stick holds while |F| ≤ μs·N; while sliding the force is −sgn(u̇)·μk·N (paper Eqs. 4, 14).

    Examples
    --------
    >>> Friction(static=0.4, kinetic=0.3).kinetic
    0.3
    """

    static: float
    kinetic: float | None = None

    def __post_init__(self):
        for name in ("static", "kinetic"):
            value = getattr(self, name)
            if value is None and name == "kinetic":  # omitted: μk = μs
                continue
            if not isinstance(value, (int, float)) or math.isnan(value) or value < 0:
                raise ValueError(f"friction.{name} must be a number ≥ 0, got {value!r}")
        if self.kinetic is not None and self.kinetic > self.static:
            raise ValueError(
                f"friction.kinetic ({self.kinetic}) must not exceed friction.static ({self.static})"
            )

    @property
    def mu_s(self) -> float:
        return float(self.static)

    @property
    def mu_k(self) -> float:
        return float(self.static if self.kinetic is None else self.kinetic)
