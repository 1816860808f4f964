"""Run a configuration end to end: ``run(config) -> summary dict``.

    >>> import rocking as rk
    >>> rk.run("examples/paper_fig10a.toml")["overturned"]  # doctest: +SKIP
    False
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

from .io.config import Config, StackConfig, load_config
from .results.response import Response
from .simulation import simulate
from .stack import StackResponse, simulate_stack

__all__ = ["run", "run_response"]

ConfigLike = str | os.PathLike[str] | Mapping[str, Any] | Config | StackConfig


def run_response(config: ConfigLike) -> tuple[Config, Response] | tuple[StackConfig, StackResponse]:
    """Load a configuration and simulate it.

    Parameters
    ----------
    config : path-like, str, mapping, Config or StackConfig
        A TOML file, a dict of the same shape (relative record paths against the
        current directory), or an already loaded configuration.

    Returns
    -------
    config : Config or StackConfig
        The validated configuration.
    response : Response or rocking.stack.StackResponse
        The full result (time series, events, summary); a stack's (``[[blocks]]``) comes from
        :func:`rocking.stack.simulate_stack`.

    Raises
    ------
    ConfigError
        If the configuration is invalid (a ``ValueError``; names file and field).
    SimulationError
        If the solver cannot finish.
    """
    cfg = load_config(config)
    system, motion, options, duration = cfg.to_specs()
    if isinstance(cfg, StackConfig):
        return cfg, simulate_stack(system, motion, duration=duration, options=options)
    return cfg, simulate(system, motion, duration=duration, options=options)


def run(config: ConfigLike) -> dict[str, Any]:
    """Simulate a configuration and return its summary.

    Parameters
    ----------
    config : path-like, str, mapping or Config
        See :func:`run_response`.

    Returns
    -------
    dict
        :meth:`Response.summary`: ``overturned``, ``overturn_time`` (s),
        ``exceeded_alpha_time`` (s), ``peak_rotation`` (rad), ``peak_sliding`` and
        ``residual_sliding`` (m, of the body sliding on the floor), ``impacts``,
        ``first_rocking_time`` and ``first_sliding_time`` (s),
        ``required_top_friction`` and more; times are None when the event did not
        happen. A stack's summary (:meth:`rocking.stack.StackResponse.summary`) describes the
        top block at the top level, and every block and interface in ``blocks`` and
        ``interfaces``.
    """
    return run_response(config)[1].summary()
