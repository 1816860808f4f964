"""Shared pytest configuration: put tests/ on sys.path so `from oracles import ...` works."""

import sys
from pathlib import Path

_TESTS = str(Path(__file__).resolve().parent)
if _TESTS not in sys.path:
    sys.path.insert(0, _TESTS)


import pytest  # noqa: E402


@pytest.fixture(autouse=True, scope="session")
def _quiet_first_compile():
    """Tests are not users: the command line's "compiling the solver" message (rocking.solver.warmup)
    would appear in the stderr of whichever CLI test first meets a cold cache. tests/test_install.py
    turns it back on where it is the subject."""
    from rocking.solver import warmup

    warmup._done = True
    warmup._stack_done = True  # the same for "compiling the stack engine"
    yield
