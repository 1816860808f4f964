"""Immutable description of a stack of rigid blocks on the floor (issue 11; docs/theory/stack.md).

Blocks are listed from the floor up: block 1 stands on the floor, block k on block k − 1.
Interface k is the contact between block k and what it stands on (interface 1: the floor).
All lengths in m, masses in kg, inertias in kg·m².

Example
-------
>>> from rocking.stack import Block, Interface, Stack
>>> from rocking.contact.friction import Friction
>>> stack = Stack(
...     blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=300.0),
...             Block(name="statue", width=0.3, height=1.2, mass=100.0)),
...     interfaces=(Interface(friction=Friction(static=0.3, kinetic=0.25)), Interface()),
... )
>>> round(stack.overlap(2), 3)
(-0.15, 0.15)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..contact.friction import Friction
from ..models.bodies import _positive


@dataclass(frozen=True, kw_only=True, slots=True)
class Block:
    """One rigid rectangular block.

    Parameters
    ----------
    width, height : float
        B and H, m.
    mass : float
        m, kg.
    inertia : float, optional
        Moment of inertia about the centre of mass, kg·m². Default: uniform rectangle,
        m (B² + H²)/12.
    offset : float
        Horizontal position of its centre relative to the centre of the block below (or to the
        origin of the floor), m, positive towards +x.
    name : str
        Used in summaries and plots.
    """

    width: float
    height: float
    mass: float
    inertia: float | None = None
    offset: float = 0.0
    name: str = ""

    def __post_init__(self):
        label = f"blocks[{self.name or '?'}]"
        _positive(f"{label}.width", self.width)
        _positive(f"{label}.height", self.height)
        _positive(f"{label}.mass", self.mass)
        if self.inertia is not None:
            _positive(f"{label}.inertia", self.inertia)
        o = self.offset
        if isinstance(o, bool) or not isinstance(o, (int, float)) or not math.isfinite(o):
            raise ValueError(f"{label}.offset must be a finite number (m), got {o!r}")

    @property
    def centroidal_inertia(self) -> float:
        """J_G, kg·m²."""
        if self.inertia is not None:
            return float(self.inertia)
        return self.mass * (self.width**2 + self.height**2) / 12.0


@dataclass(frozen=True, kw_only=True, slots=True)
class Interface:
    """The contact under a block.

    Parameters
    ----------
    friction : Friction, optional
        Coulomb friction (μs ≥ μk). ``None``: the interface never slips.
    restitution : float, optional
        r in [0, 1]: the ratio of the relative angular velocities after and before an impact of
        the block on its other corner, when what lies below is held (the single block's
        θ̇⁺ = r θ̇⁻). With blocks standing on it flat and stuck, it is the ratio of the body they
        make with it (docs/theory/stack.md §6). ``None``: a
        plastic impact on the new corner with the old one free to lift, which gives Housner's
        value for whatever rocks (the block and anything stuck on it).
    """

    friction: Friction | None = None
    restitution: float | None = None

    def __post_init__(self):
        if self.friction is not None and not isinstance(self.friction, Friction):
            raise ValueError(f"interface.friction must be a Friction, got {self.friction!r}")
        r = self.restitution
        if r is not None and (isinstance(r, bool) or not isinstance(r, (int, float)) or not 0.0 <= r <= 1.0):
            raise ValueError(f"interface.restitution must lie in [0, 1], got {r!r}")


@dataclass(frozen=True, kw_only=True, slots=True)
class Stack:
    """N ≥ 1 blocks from the floor up, with one interface under each."""

    blocks: tuple[Block, ...]
    interfaces: tuple[Interface, ...]

    def __post_init__(self):
        blocks = tuple(self.blocks)
        interfaces = tuple(self.interfaces)
        object.__setattr__(self, "blocks", blocks)
        object.__setattr__(self, "interfaces", interfaces)
        if not blocks:
            raise ValueError("blocks: a stack needs at least one block")
        for i, b in enumerate(blocks):
            if not isinstance(b, Block):
                raise ValueError(f"blocks[{i}] must be a Block, got {b!r}")
        for i, f in enumerate(interfaces):
            if not isinstance(f, Interface):
                raise ValueError(f"interfaces[{i}] must be an Interface, got {f!r}")
        if len(interfaces) != len(blocks):
            raise ValueError(
                f"interfaces: {len(blocks)} blocks need {len(blocks)} interfaces (floor–block 1 first), "
                f"got {len(interfaces)}"
            )
        for k in range(2, len(blocks) + 1):
            lo, hi = self.overlap(k)
            if hi - lo <= 0.0:
                raise ValueError(
                    f"blocks[{k - 1}].offset = {blocks[k - 1].offset!r} m leaves no overlap with the block below "
                    f"(overlap width {hi - lo:.6g} m)"
                )

    @property
    def n(self) -> int:
        return len(self.blocks)

    def overlap(self, k: int) -> tuple[float, float]:
        """Ends of interface k's contact (k = 1 … N) along the face of the block below, relative to
        that block's centre (the floor: to block 1's rest position), m."""
        upper = self.blocks[k - 1]
        lo_u, hi_u = upper.offset - 0.5 * upper.width, upper.offset + 0.5 * upper.width
        if k == 1:
            return lo_u, hi_u
        lower = self.blocks[k - 2]
        return max(lo_u, -0.5 * lower.width), min(hi_u, 0.5 * lower.width)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(b.name or f"block {i + 1}" for i, b in enumerate(self.blocks))
