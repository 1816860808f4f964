"""Immutable descriptions of what is simulated: the statue, the pedestal, the system.

All lengths in m, masses in kg, angles in rad. Symbols follow the paper (§2.1, §3.1):
B = 2b, H = 2h, R = √(b² + h²), α = atan(b/h), I_O = (4/3)·m·R² (uniform rectangle).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..contact.friction import Friction


def _positive(name: str, value) -> None:
    if not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")


@dataclass(frozen=True, kw_only=True, slots=True)
class Statue:
    """The slender rigid block that rocks (block 2 of the paper).

    Parameters
    ----------
    width, height : float
        B and H, m.
    mass : float
        m, kg.
    restitution : float, optional
        r = θ̇⁺/θ̇⁻ at an impact (paper Eq. 1), in [0, 1]. ``None`` uses Housner's value
        1 − 1.5 sin²α (paper Eq. 3), i.e. conservation of angular momentum about the new pivot.
    friction : Friction, optional
        Friction of the face it stands on (the floor, or the pedestal's top face). ``None``
        means it never slides there.
    """

    width: float
    height: float
    mass: float
    restitution: float | None = None
    friction: Friction | None = None

    def __post_init__(self):
        _positive("statue.width", self.width)
        _positive("statue.height", self.height)
        _positive("statue.mass", self.mass)
        r = self.restitution
        if r is not None and (not isinstance(r, (int, float)) or not 0.0 <= r <= 1.0):
            raise ValueError(f"statue.restitution must lie in [0, 1], got {r!r}")

    @property
    def b(self) -> float:
        return 0.5 * self.width

    @property
    def h(self) -> float:
        return 0.5 * self.height

    @property
    def slenderness(self) -> float:
        """α = atan(b/h), rad."""
        return math.atan2(self.width, self.height)

    @property
    def semi_diagonal(self) -> float:
        """R = √(b² + h²), m."""
        return math.hypot(self.b, self.h)

    @property
    def inertia_about_corner(self) -> float:
        """I_O = (4/3)·m·R², kg·m² (J_G + m R², not the J_G of the paper's Eq. 21; P4)."""
        return 4.0 / 3.0 * self.mass * self.semi_diagonal**2

    def frequency_parameter(self, gravity: float) -> float:
        """p = √(m g R / I_O) = √(3g/4R), s⁻¹."""
        return math.sqrt(3.0 * gravity / (4.0 * self.semi_diagonal))

    @property
    def housner_restitution(self) -> float:
        """η = 1 − 1.5·sin²α (paper Eq. 3), clamped at 0.

        The formula turns negative for α > asin√(2/3) = 0.9553 rad (b/h > √2): θ̇ would reverse,
        which would drive the old corner into the floor. Such a squat block lands flat instead: a
        plastic impact, η = 0."""
        return max(0.0, 1.0 - 1.5 * math.sin(self.slenderness) ** 2)

    @property
    def effective_restitution(self) -> float:
        return self.housner_restitution if self.restitution is None else float(self.restitution)


@dataclass(frozen=True, kw_only=True, slots=True)
class Pedestal:
    """The squat block under the statue that only slides (block 1 of the paper).

    Parameters
    ----------
    mass : float
        m1, kg (≥ 0; 0 reduces the model to a single block that can slide and rock).
    friction : Friction
        Friction of its bottom face on the floor.
    width, height : float, optional
        B1 and H1, m: used for drawings and for the pedestal-uplift check.
    """

    mass: float
    friction: Friction
    width: float | None = None
    height: float | None = None

    def __post_init__(self):
        m = self.mass
        if not isinstance(m, (int, float)) or not math.isfinite(m) or m < 0:
            raise ValueError(f"pedestal.mass must be a finite number ≥ 0, got {m!r}")
        if not isinstance(self.friction, Friction):
            raise ValueError(f"pedestal.friction must be a Friction, got {self.friction!r}")
        for name in ("width", "height"):
            if getattr(self, name) is not None:
                _positive(f"pedestal.{name}", getattr(self, name))

    @property
    def uplift_checked(self) -> bool:
        """Whether the solver checks that the pedestal stays flat: it needs both its width and
        its height (derivation §3.5)."""
        return self.width is not None and self.height is not None


@dataclass(frozen=True, kw_only=True, slots=True)
class System:
    """A statue standing on the floor, or on a pedestal that stands on the floor.

    Examples
    --------
    >>> s = System(statue=Statue(width=1.0, height=4.0, mass=1.0))
    >>> round(s.statue.slenderness, 6)
    0.244979
    """

    statue: Statue
    pedestal: Pedestal | None = None

    def __post_init__(self):
        if not isinstance(self.statue, Statue):
            raise ValueError(f"statue must be a Statue, got {self.statue!r}")
        if self.pedestal is not None and not isinstance(self.pedestal, Pedestal):
            raise ValueError(f"pedestal must be a Pedestal, got {self.pedestal!r}")

    @property
    def floor_friction(self) -> Friction | None:
        """Friction under the body that slides on the floor (pedestal, or the statue itself)."""
        return self.pedestal.friction if self.pedestal is not None else self.statue.friction

    @property
    def top_friction(self) -> Friction | None:
        """Friction between statue and pedestal, if given (only checked, never simulated)."""
        return self.statue.friction if self.pedestal is not None else None
