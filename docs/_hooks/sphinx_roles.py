"""MkDocs hook: the docstrings use Sphinx roles (``:func:`name```), which Markdown does not know.

mkdocstrings renders them as ``:func:<code>name</code>``; this drops the role so the API pages
show just the name in code. The docstrings stay as they are (the command line's help and
``help()`` read them too).
"""

from __future__ import annotations

import re

SPHINX_ROLE = re.compile(r":(?:py:)?(?:func|class|meth|mod|attr|data|exc|obj|const):(?=<code>)")


def strip_sphinx_roles(html: str) -> str:
    """The page's HTML without the role prefixes in front of inline code."""
    return SPHINX_ROLE.sub("", html)


def on_page_content(html: str, **_: object) -> str:
    return strip_sphinx_roles(html)
