"""Stacks of rigid blocks: the general planar contact engine (issue 11; docs/theory/stack.md).

Examples
--------
>>> import rocking
>>> from rocking.stack import Block, Interface, Stack, simulate_stack
>>> stack = Stack(blocks=(Block(name="pedestal", width=0.8, height=0.5, mass=300.0),
...                       Block(name="statue", width=0.3, height=1.2, mass=100.0)),
...               interfaces=(Interface(friction=rocking.Friction(static=0.3, kinetic=0.25)), Interface()))
>>> r = simulate_stack(stack, rocking.SinePulse(amplitude=3.5, frequency=1.0))
>>> [b["overturned"] for b in r.blocks]
[False, True]
"""

from .._numba_cache import refresh

refresh()  # drops stale compiled code before the engine's modules are imported

from .model import Block, Interface, Stack  # noqa: E402
from .simulate import StackResponse, simulate_stack  # noqa: E402

__all__ = ["Block", "Interface", "Stack", "StackResponse", "simulate_stack"]
