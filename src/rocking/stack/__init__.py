"""Stacks of rigid blocks: the general planar contact engine (issue 11; docs/theory/stack.md)."""

from .model import Block, Interface, Stack
from .simulate import StackResponse, simulate_stack

__all__ = ["Block", "Interface", "Stack", "StackResponse", "simulate_stack"]
