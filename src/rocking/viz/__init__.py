"""Pictures of simulations and studies (matplotlib; nothing here computes physics).

* :mod:`rocking.viz.plots` — ``plot_response``, ``plot_regimes``, ``plot_energy``,
  ``plot_spectrum``, ``plot_fragility``, ``plot_design_chart``;
* :mod:`rocking.viz.animation` — ``animate(response, path)`` (GIF, or MP4 with ffmpeg);
* :mod:`rocking.viz.paper_figures` — the seed paper's case-study figures.

Names load on first use, so ``import rocking.viz`` stays cheap.
"""

from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "plot_response": "plots",
    "plot_regimes": "plots",
    "plot_energy": "plots",
    "plot_spectrum": "plots",
    "plot_fragility": "plots",
    "plot_design_chart": "plots",
    "energy_series": "plots",
    "floor_motion": "plots",
    "lognormal_cdf": "plots",
    "REGIME_COLORS": "plots",
    "REGIME_NAMES": "plots",
    "animate": "animation",
    "frame_times": "animation",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'rocking.viz' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
