"""The validation manual: the library against published results, case by case.

``python -m rocking.validation --out docs/validation.md`` regenerates ``docs/validation.md``.
Each module holds the cases of one source (``housner``, ``makris``, ``dejong``, ``impulses``,
``sliding``, ``pedestal``, ``peer`` for MuJoCo); ``exact`` holds the independent references
(the published closed forms evaluated, and a SciPy integration of Housner's nonlinear equation
that shares no code with the library's solver); ``rows`` the verdict rule; ``manual`` the
Markdown. The library is reached through its public API only.
"""

from .manual import all_rows, build, parse, render
from .rows import ACCEPTED, Row, Section

__all__ = ["ACCEPTED", "Row", "Section", "all_rows", "build", "parse", "render"]
