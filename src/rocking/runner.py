"""Run a configuration end to end: ``run(config) -> summary dict``.

    >>> import rocking as rk
    >>> rk.run("examples/paper_fig10a.toml")["overturned"]  # doctest: +SKIP
    False

The configuration layer (pydantic) and the stack engine are imported on the first call, not
with ``import rocking``: a script that only calls :func:`rocking.simulate` never pays for them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .simulation import simulate

if TYPE_CHECKING:
    import os
    from collections.abc import Mapping

    from .io.config import Config, StackConfig
    from .results.response import Response
    from .stack import StackResponse

    ConfigLike = str | os.PathLike[str] | Mapping[str, Any] | Config | StackConfig

__all__ = ["run", "run_response"]


def run_response(
    config: ConfigLike, *, save: bool = True
) -> tuple[Config, Response] | tuple[StackConfig, StackResponse]:
    """Load a configuration and simulate it.

    Parameters
    ----------
    config : path-like, str, mapping, Config or StackConfig
        A TOML file, a dict of the same shape (relative record paths against the
        current directory), or an already loaded configuration.
    save : bool
        Keep the time series (default). False keeps only the summary and the events, which is
        all :func:`run` returns, and skips storing every sample; a stack always keeps its series.

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
    from .io.config import StackConfig, load_config_and_specs

    cfg, (system, motion, options, duration) = load_config_and_specs(config)
    if isinstance(cfg, StackConfig):
        from .stack import simulate_stack

        return cfg, simulate_stack(system, motion, duration=duration, options=options)
    return cfg, simulate(system, motion, duration=duration, options=options, save=save)


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
    # the summary is computed in the solver: the time series would be built and thrown away
    return run_response(config, save=False)[1].summary()
