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
    "stack": {"analyses", "io", "cli", "viz", "web", "report", "runner"},
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


def _module_imports(path: Path) -> set[Path]:
    """The rocking modules (files) a module imports from, relative or absolute, including
    submodules imported by name (``from ..integrators import dop853``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = set()
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level > 0:
            base = path.parent
            for _ in range(node.level - 1):
                base = base.parent
            parts = node.module.split(".") if node.module else []
        elif node.module and node.module.startswith("rocking."):
            base, parts = PKG, node.module.split(".")[1:]
        else:
            continue
        target = base.joinpath(*parts)
        candidates = [target.with_suffix(".py"), target / "__init__.py"]
        candidates += [target / f"{alias.name}.py" for alias in node.names]
        out.update(c for c in candidates if c.exists())
    return out


@pytest.mark.parametrize("name, root", [("SOLVER_CORE", "solver/compiled.py"), ("STACK_CORE", "stack/engine.py")])
def test_numba_cache_fingerprint_covers_every_compiled_module(name, root):
    """Numba's disk cache checks only a function's own file, not its callees', so each compiled
    core's list in rocking._numba_cache must hold every module with compiled code that it reaches through its imports:
    an edit to one left out (models/transitions.py was; stack/modes.py was, and a fixed rule
    kept running in its stale compiled caller) would leave a stale solver running."""
    from rocking import _numba_cache

    core = getattr(_numba_cache, name)
    seen, todo = set(), [PKG / root]
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        todo.extend(_module_imports(path) - seen)
    compiled = {str(p.relative_to(PKG)) for p in seen if "njit" in p.read_text(encoding="utf-8")
                and p.name != "__init__.py"}
    missing = sorted(compiled - set(core))
    assert not missing, f"compiled modules missing from _numba_cache.{name}: {missing}"
