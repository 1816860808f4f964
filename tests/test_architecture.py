"""Imports flow one way: physics and numerics never import the layers built on them."""

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parent.parent / "src" / "rocking"

# layer -> the rocking subpackages it must never import
FORBIDDEN = {
    "integrators": {"models", "contact", "excitation", "solver", "simulation", "results", "analyses", "io", "cli",
                    "viz", "web", "report", "runner"},
    "contact": {"models", "solver", "simulation", "results", "analyses", "io", "cli", "viz", "web", "report", "runner"},
    "excitation": {"models", "solver", "simulation", "results", "analyses", "io", "cli", "viz", "web", "report",
                   "runner"},
    "models": {"solver", "simulation", "results", "analyses", "io", "cli", "viz", "web", "report", "runner"},
    "solver": {"analyses", "io", "cli", "viz", "web", "report", "runner"},
    "analyses": {"cli", "web"},
    "viz": {"cli", "web"},
}


def _rocking_imports(path: Path) -> set[str]:
    """The first-level rocking subpackages a module imports (absolute or relative)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    depth = len(path.relative_to(PKG).parts) - 1  # folders below rocking/
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 0 and node.module and node.module.startswith("rocking."):
                found.add(node.module.split(".")[1])
            elif node.level > 0:
                up = node.level - 1
                if up == depth and node.module:  # relative to rocking/
                    found.add(node.module.split(".")[0])
                elif up == depth and not node.module:
                    found.update(alias.name for alias in node.names)
                elif up < depth:
                    found.add(path.relative_to(PKG).parts[0])
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("rocking."):
                    found.add(alias.name.split(".")[1])
    return found


@pytest.mark.parametrize("layer", sorted(FORBIDDEN))
def test_layer_imports_flow_one_way(layer):
    offenders = {}
    for path in (PKG / layer).rglob("*.py"):
        bad = _rocking_imports(path) & FORBIDDEN[layer]
        if bad:
            offenders[str(path.relative_to(PKG))] = sorted(bad)
    assert not offenders, f"{layer} imports layers above it: {offenders}"
