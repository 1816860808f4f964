"""Friction design of a pedestal: which floor-face friction (and pedestal mass) keeps the statue
standing, and quietest, without letting the pedestal slide too far?

Every candidate (μs of the pedestal's floor face, with μk given or as a ratio of μs, and
optionally the pedestal mass) is run under every motion of a set (records scaled to a target
intensity, or a harmonic/pulse family), at its nominal friction and, because measured friction
scatters with the surfaces, humidity and age, at μs·(1 − s) and μs·(1 + s) with μk scaled alike
(``friction_scatter`` s, default 0.2). For each candidate the study reports, over the motions and
those three friction levels (the worst of them):

* the statue's peak θ/α (mean, median and maximum over the motions; an overturn counts as π/(2α));
* the motions under which the statue falls, and those whose runs prove nothing (still moving at
  the end, or stopped early): "undetermined";
* the pedestal's peak sliding, which is the free space (clearance) it needs, per motion and
  overall, and its residual sliding (m);
* ``required_top_friction``: the largest |F|/N the statue–pedestal face must supply (over the
  runs the statue survives), to compare with that face's friction.

The ranking (:func:`choose_design`; the rules are in ``docs/studies.md``) puts safety above every
limit: a candidate is *safe* if the statue neither falls nor is left undetermined under any motion
at any of the three friction levels. The recommendation is the best safe candidate that meets
the limits (peak sliding ≤ ``sliding_limit``, residual sliding ≤ ``residual_limit``, required top
friction ≤ ``top_friction_limit``). If there is none, the verdict's first line says so, and the
two nearest ways out are named: the safe candidate that needs the least free space (then the
recommendation, since not falling comes first) and the candidate within the limits with the
fewest falls, with the motions that make it fall. If no candidate is safe, nothing is recommended.

    >>> ds = friction_design(system, motions, mu_s=[0.1, 0.2, 0.3], sliding_limit=0.05)   # doctest: +SKIP
    >>> ds.attrs["recommended_mu_s"], ds.attrs["verdict"]                                   # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses
import math
import os
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from ..contact.friction import Friction
from ..models.bodies import System
from ..simulation import Options
from .batch import replace_at
from .store import Run, run_stored

__all__ = [
    "DEFAULT_FRICTION_SCATTER",
    "OBJECTIVES",
    "DesignChoice",
    "candidate_table",
    "choose_design",
    "design_report",
    "friction_design",
    "friction_factors",
    "motion_family",
    "plot_design",
    "ranking_rule",
    "run_undetermined",
]

OBJECTIVES = ("mean", "median", "max")


def motion_family(kind: str, amplitudes: Sequence[float], frequencies: Sequence[float], **kw: Any) -> dict[str, Any]:
    """Every amplitude × frequency of a harmonic or pulse shape, as ``{name: motion}``.

    Parameters
    ----------
    kind : {"harmonic", "sine", "cosine", "ricker"}
    amplitudes : sequence of float
        m/s².
    frequencies : sequence of float
        Hz.
    **kw
        ``cycles`` and ``form`` for a harmonic motion.
    """
    from ..excitation.harmonic import Harmonic
    from ..excitation.pulses import CosinePulse, RickerPulse, SinePulse

    makers = {
        "harmonic": lambda a, f: Harmonic(amplitude=a, frequency=f, cycles=kw.get("cycles", 3.0), form=kw.get("form", "sin")),
        "sine": lambda a, f: SinePulse(amplitude=a, frequency=f),
        "cosine": lambda a, f: CosinePulse(amplitude=a, frequency=f),
        "ricker": lambda a, f: RickerPulse(amplitude=a, frequency=f),
    }
    if kind not in makers:
        raise ValueError(f"unknown motion family {kind!r}; use one of {', '.join(makers)}")
    out = {}
    for a in amplitudes:
        for f in frequencies:
            out[f"{kind} A={float(a):g} m/s² f={float(f):g} Hz"] = makers[kind](float(a), float(f))
    if not out:
        raise ValueError("the motion family is empty")
    return out


def _stat(values: np.ndarray, how: str, axis: int = -1) -> np.ndarray:
    if how == "mean":
        return values.mean(axis=axis)
    if how == "median":
        return np.median(values, axis=axis)
    return values.max(axis=axis)


#: Default relative scatter of the floor-face friction (surface, humidity, age).
DEFAULT_FRICTION_SCATTER = 0.2


def _check_scatter(scatter: Any) -> float:
    try:
        s = float(scatter)
    except (TypeError, ValueError):
        raise ValueError(f"friction_scatter must be a number in [0, 1), got {scatter!r}") from None
    if not 0.0 <= s < 1.0:
        raise ValueError(f"friction_scatter must lie in [0, 1) (relative to μs), got {scatter!r}")
    return s


def friction_factors(scatter: float) -> tuple[float, ...]:
    """The friction levels run for each candidate, as factors on (μs, μk): (1 − s, 1, 1 + s), or
    (1,) without scatter."""
    s = _check_scatter(scatter)
    return (1.0,) if s == 0.0 else (1.0 - s, 1.0, 1.0 + s)


def run_undetermined(ds) -> np.ndarray:
    """Per run of a summaries Dataset: True where the statue did not overturn, yet the run does not
    prove that it stands: the statue is still moving at the end (``still_moving``, when the
    summaries carry it) or the run stopped early (any status but ``"completed"``)."""
    over = np.asarray(ds.overturned.values, dtype=bool)
    unproven = np.asarray(ds.status.values).astype(str) != "completed"
    moving = ds.get("still_moving")
    if moving is not None:
        m = np.asarray(moving.values)
        unproven = unproven | (np.nan_to_num(m.astype(float)) != 0)
    return ~over & unproven


def _mm(x: float) -> str:
    return f"{1e3 * float(x):.1f} mm"


def _mm_limit(x: float) -> str:
    return f"{1e3 * float(x):g} mm"


def _names(names: Sequence[str], most: int = 6) -> str:
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


def ranking_rule(friction_scatter: float, objective: str = "mean") -> str:
    """The ranking of :func:`choose_design` in one sentence, for reports and the web page."""
    s = _check_scatter(friction_scatter)
    band = f"at μs and μs·(1 ± {s:g}), μk alike" if s > 0 else "at the nominal friction"
    return (f"safety first: a value is safe if the statue neither falls nor is left moving under any motion {band}; "
            f"among the safe values that meet the limits, μs·(1 + s) below the statue–pedestal face's friction, "
            f"then the smallest {objective} peak θ/α, the least free space, the smaller μs, the lighter pedestal; if no safe "
            f"value meets the limits, the safe one needing the least free space, and nothing if no value is safe")


@dataclasses.dataclass(frozen=True)
class DesignChoice:
    """The outcome of :func:`choose_design`. Candidates are (i, j) = (μs index, mass index)."""

    mu_s: np.ndarray
    mu_k: np.ndarray
    pedestal_mass: np.ndarray
    clearance: np.ndarray  # m, (μs, mass, motion)
    falls: np.ndarray  # (μs, mass, motion)
    undetermined: np.ndarray  # (μs, mass, motion)
    motions: tuple[str, ...]
    safe: np.ndarray  # (μs, mass)
    feasible: np.ndarray  # (μs, mass): meets the limits
    inverted: np.ndarray  # (μs,)
    recommended: tuple[int, int] | None
    meets_every_requirement: bool
    nearest_safe: tuple[int, int] | None
    fewest_overturns: tuple[int, int] | None
    fewest_overturns_within_limits: bool
    lines: tuple[str, ...]

    @property
    def verdict(self) -> str:
        """The first line: the recommendation, or that no candidate met every requirement."""
        return self.lines[0]

    def falling_motions(self, ij: tuple[int, int]) -> list[str]:
        return [m for m, f in zip(self.motions, self.falls[ij]) if f]

    def undetermined_motions(self, ij: tuple[int, int]) -> list[str]:
        return [m for m, u in zip(self.motions, self.undetermined[ij]) if u]

    def attrs(self) -> dict[str, Any]:
        """Dataset attributes (numbers and strings only, so that they survive NetCDF)."""
        out: dict[str, Any] = {
            "verdict": self.verdict,
            "verdict_lines": "\n".join(self.lines),
            "meets_every_requirement": int(self.meets_every_requirement),
            "fewest_overturns_within_limits": int(self.fewest_overturns_within_limits),
        }
        for prefix, ij in (("recommended", self.recommended), ("nearest_safe", self.nearest_safe),
                           ("fewest_overturns", self.fewest_overturns)):
            out[f"{prefix}_mu_s"] = float(self.mu_s[ij[0]]) if ij else np.nan
            out[f"{prefix}_mu_k"] = float(self.mu_k[ij[0]]) if ij else np.nan
            out[f"{prefix}_pedestal_mass"] = float(self.pedestal_mass[ij[1]]) if ij else np.nan
            out[f"{prefix}_clearance"] = float(self.clearance[ij].max()) if ij else np.nan
        ij = self.fewest_overturns
        out["fewest_overturns_count"] = int(self.falls[ij].sum()) if ij else -1
        out["fewest_overturns_motions"] = "\n".join(self.falling_motions(ij)) if ij else ""
        out["fewest_overturns_undetermined"] = "\n".join(self.undetermined_motions(ij)) if ij else ""
        return out


def choose_design(
    *,
    mu_s: Sequence[float],
    mu_k: Sequence[float],
    pedestal_mass: Sequence[float],
    motions: Sequence[str],
    falls: Any,
    undetermined: Any,
    clearance: Any,
    residual: Any,
    top_friction: Any,
    score: Any,
    objective: str = "mean",
    sliding_limit: float | None = None,
    residual_limit: float | None = None,
    top_friction_limit: float | None = None,
    friction_scatter: float = DEFAULT_FRICTION_SCATTER,
    tan_alpha: float | None = None,
) -> DesignChoice:
    """Rank the candidates of a friction design and write its verdict: the one place where the
    rules live (``rocking design``, :func:`friction_design` and the web page's sweep use it).

    Parameters
    ----------
    mu_s, mu_k : sequence of float
        The candidates' nominal floor-face friction (one per μs).
    pedestal_mass : sequence of float
        kg.
    motions : sequence of str
        Motion names.
    falls, undetermined : bool arrays (μs, mass, motion)
        The statue overturns at some friction level of the scatter band; or, without a fall,
        some level leaves it still moving at the end (or the run stopped early).
    clearance : array (μs, mass, motion)
        Largest peak sliding of the pedestal over the friction levels, m.
    residual, top_friction, score : arrays (μs, mass)
        Largest |residual sliding| (m) and required statue–pedestal friction (NaN when every run
        overturns: not a violation) over the motions and levels; the ``objective`` statistic of
        the peak θ/α over the motions.
    sliding_limit, residual_limit, top_friction_limit : float, optional
        The limits (m, m, –); ``top_friction_limit`` is also the statue–pedestal face's friction,
        which a floor-face μs must stay below.
    friction_scatter : float
        The relative scatter the runs covered, for the text.
    tan_alpha : float, optional
        The statue's tan α, for the hint when no candidate is safe.

    Rules, in order (see ``docs/studies.md``):

    1. *Safe* (no fall, nothing undetermined, under any motion at any friction level) comes
       before every limit.
    2. Among the safe candidates that meet the limits, the recommendation is the one with
       μs·(1 + s) below the statue–pedestal face's friction, then the smallest ``objective`` peak
       θ/α, the least free space, the smaller μs and the lighter pedestal.
    3. If there is none, the first line says that no candidate met every requirement, and the
       nearest ways out follow: the safe candidate needing the least free space (preferring those
       that meet the residual and top-friction limits), which is then recommended; and the
       candidate within the limits with the fewest falls (then undetermined motions), naming the
       motions that make it fall.
    4. If no candidate is safe, nothing is recommended.
    """
    mus = np.asarray(mu_s, dtype=float)
    kin = np.asarray(mu_k, dtype=float)
    masses = np.asarray(pedestal_mass, dtype=float)
    names = tuple(str(m) for m in motions)
    falls = np.asarray(falls, dtype=bool)
    unsure = np.asarray(undetermined, dtype=bool) & ~falls
    clearance = np.asarray(clearance, dtype=float)
    residual = np.asarray(residual, dtype=float)
    top = np.asarray(top_friction, dtype=float)
    score = np.asarray(score, dtype=float)
    n_mot = len(names)
    s = _check_scatter(friction_scatter)
    band = f"at μs and μs·(1 ± {s:g}) (μk alike)" if s > 0 else "at the nominal friction (no scatter)"

    clear_max = clearance.max(axis=-1)
    miss_sliding = clear_max > sliding_limit if sliding_limit is not None else np.zeros(clear_max.shape, bool)
    miss_residual = residual > residual_limit if residual_limit is not None else np.zeros(clear_max.shape, bool)
    miss_top = top > top_friction_limit if top_friction_limit is not None else np.zeros(clear_max.shape, bool)
    feasible = ~(miss_sliding | miss_residual | miss_top)
    n_unsafe = falls.sum(axis=-1) + unsure.sum(axis=-1)
    safe = n_unsafe == 0
    # the floor face's friction may turn out s higher: the concept is inverted as soon as the top
    # of its scatter band reaches the statue-pedestal face's friction
    inverted = (mus * (1.0 + s) >= top_friction_limit) if top_friction_limit is not None else np.zeros(mus.shape, bool)
    cands = [(i, j) for i in range(mus.size) for j in range(masses.size)]

    def best(pool: list[tuple[int, int]], key: Callable[[tuple[int, int]], tuple]) -> tuple[int, int] | None:
        return min(pool, key=key) if pool else None

    def tail(ij: tuple[int, int]) -> tuple:
        i, j = ij
        return (bool(inverted[i]), float(score[ij]), float(clear_max[ij]), float(mus[i]), float(masses[j]))

    safe_pool = [c for c in cands if safe[c]]
    good = best([c for c in safe_pool if feasible[c]], tail)
    nearest = best(safe_pool, lambda c: (bool(miss_residual[c] or miss_top[c]), float(clear_max[c]), *tail(c)))
    limited = [c for c in cands if feasible[c]]
    within = bool(limited)
    by_falls = (lambda c: (int(n_unsafe[c]), int(falls[c].sum()), *tail(c)))
    fewest = best(limited, by_falls)
    if fewest is None and not safe_pool:  # nothing to build either way: the least bad candidate, named
        fewest = best(cands, lambda c: (int(n_unsafe[c]), int(miss_sliding[c] + miss_residual[c] + miss_top[c]),
                                        *by_falls(c)[1:]))
    recommended = good if good is not None else nearest

    def name(ij: tuple[int, int]) -> str:
        i, j = ij
        return f"μs = {mus[i]:.3g} (μk = {kin[i]:.3g}), pedestal mass {masses[j]:g} kg"

    def misses(ij: tuple[int, int]) -> list[str]:
        out = []
        if miss_sliding[ij]:
            out.append(f"the pedestal needs {_mm(clear_max[ij])} of free space, more than the "
                       f"{_mm_limit(sliding_limit)} limit")
        if miss_residual[ij]:
            out.append(f"its residual sliding {_mm(residual[ij])} exceeds the {_mm_limit(residual_limit)} limit")
        if miss_top[ij]:
            out.append(f"the statue–pedestal face must supply μ = {top[ij]:.3g}, more than {top_friction_limit:.3g}")
        return out

    def outcome(ij: tuple[int, int]) -> str:
        fell = [m for m, f in zip(names, falls[ij]) if f]
        moving = [m for m, u in zip(names, unsure[ij]) if u]
        parts = []
        if fell and n_mot == 1:
            parts.append(f"the statue falls under the motion ({fell[0]})")
        elif fell:
            parts.append(f"the statue falls under {len(fell)} of {n_mot} motions: {_names(fell)}")
        if moving:
            parts.append(f"undetermined (still moving at the end, or the run stopped) under {len(moving)}: "
                         f"{_names(moving)}")
        return "; ".join(parts) if parts else f"the statue stands under {every}"

    def space(ij: tuple[int, int]) -> str:
        k = int(np.argmax(clearance[ij]))
        return (f"{_mm(clear_max[ij])}, the largest peak sliding over the motions {band}, under {names[k]}")

    every = "the motion" if n_mot == 1 else f"all {n_mot} motions"
    limits = []
    if sliding_limit is not None:
        limits.append(f"peak sliding ≤ {_mm_limit(sliding_limit)}")
    if residual_limit is not None:
        limits.append(f"residual sliding ≤ {_mm_limit(residual_limit)}")
    if top_friction_limit is not None:
        limits.append(f"required statue–pedestal friction ≤ {top_friction_limit:.3g}")
    limit_text = ", ".join(limits) if limits else "no limits"

    lines: list[str] = []
    if good is not None:
        lines.append(f"Recommended pedestal floor friction: {name(good)}. The statue stands under {every} {band}, "
                     f"and the limits are met ({limit_text}).")
        lines.append(f"Free space the pedestal needs: {space(good)}.")
    else:
        if safe_pool:
            lines.append(f"No candidate met every requirement: none keeps the statue standing under every motion "
                         f"{band} and also meets the limits ({limit_text}).")
            other = [m for m in misses(nearest) if not m.startswith("the pedestal needs")]
            beyond = f", more than the {_mm_limit(sliding_limit)} limit" if miss_sliding[nearest] else ""
            lines.append(f"Recommended, because not falling comes first: {name(nearest)}, the safe candidate that "
                         f"needs the least free space: {space(nearest)}{beyond}"
                         + "".join(f"; {m}" for m in other) + ".")
        else:
            lines.append(f"No candidate met every requirement: with every candidate the statue falls, or is left "
                         f"undetermined, under some motion {band}. Nothing is recommended.")
        # "fewest falls" unless the candidate's only failures are undetermined runs
        least = "the fewest falls" if fewest is None or falls[fewest].any() else "no fall, but not proven safe"
        if fewest is not None and within:
            lines.append(f"Within the limits, {least}: {name(fewest)}: {outcome(fewest)}.")
        elif fewest is not None:
            lines.append(f"No candidate meets the limits ({limit_text}) either; {least} regardless of them: "
                         f"{name(fewest)}: {outcome(fewest)}; {'; '.join(misses(fewest))}.")
        else:
            lines.append(f"No candidate meets the limits ({limit_text}).")
        if not safe_pool and tan_alpha is not None and float(mus.min()) * (1.0 + s) >= tan_alpha:
            lines.append(f"Every μs swept reaches tan α = {tan_alpha:.3g} within the scatter. While μs·(1 + s) stays "
                         f"below tan α, the pedestal cannot pass on enough acceleration to start the statue rocking "
                         f"under horizontal shaking: sweep lower values (they need more free space).")
    if top_friction_limit is not None and inverted.any():
        at = ", ".join(f"{m:.3g}" for m in mus[inverted])
        note = f" (μs·(1 + {s:g}) within the scatter)" if s > 0 else ""
        if recommended is not None and inverted[recommended[0]]:
            mu = mus[recommended[0]]
            reach = "" if mu >= top_friction_limit else f" within its scatter, up to {mu * (1.0 + s):.3g},"
            lines.append(f"Warning: the recommended μs = {mu:.3g} is{reach} at or above the friction of the "
                         f"statue–pedestal face ({top_friction_limit:.3g}): that inverts the concept (the statue, not "
                         f"the pedestal, would slide first).")
        lines.append(f"Warning: a floor-face μs{note} at or above the statue–pedestal face's friction "
                     f"({top_friction_limit:.3g}) inverts the concept: the statue, not the pedestal, would slide "
                     f"first. Candidates concerned: μs = {at}.")
    return DesignChoice(
        mu_s=mus, mu_k=kin, pedestal_mass=masses, clearance=clearance, falls=falls, undetermined=unsure,
        motions=names, safe=safe, feasible=feasible, inverted=inverted, recommended=recommended,
        meets_every_requirement=good is not None, nearest_safe=nearest, fewest_overturns=fewest,
        fewest_overturns_within_limits=fewest is not None and within, lines=tuple(lines),
    )


def friction_design(
    system: System,
    motions: Mapping[str, Any],
    *,
    mu_s: Sequence[float],
    mu_k: float | None = None,
    mu_k_ratio: float | None = None,
    pedestal_mass: Sequence[float] | None = None,
    sliding_limit: float | None = None,
    residual_limit: float | None = None,
    top_friction_limit: float | None = None,
    objective: str = "mean",
    friction_scatter: float = DEFAULT_FRICTION_SCATTER,
    free_time: float = 60.0,
    options: Options = Options(),
    workers: int | Any | None = None,
    folder: str | os.PathLike[str] | None = None,
    fresh: bool = False,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
):
    """Sweep the pedestal's floor friction (and mass) over a set of motions and recommend one.

    Parameters
    ----------
    system : System
        The statue on its pedestal; the pedestal's friction and mass are the ones swept.
    motions : mapping of name to motion
        Already scaled (see :func:`rocking.analyses.fragility.load_record_set` and
        ``GroundMotion.scaled``, or :func:`motion_family`).
    mu_s : sequence of float
        Static friction coefficients of the pedestal's floor face.
    mu_k, mu_k_ratio : float, optional
        The kinetic coefficient: fixed (capped at each μs), or μk = ratio·μs. Default: the
        ratio of the system's pedestal friction.
    pedestal_mass : sequence of float, optional
        Pedestal masses (kg) to sweep as well (default: the system's).
    sliding_limit, residual_limit : float, optional
        Largest acceptable peak and residual sliding of the pedestal over the motions (m).
    top_friction_limit : float, optional
        Largest friction the statue–pedestal face can supply; default the statue's static
        friction if the system gives one (with a pedestal, ``statue.friction`` is that face).
        A floor-face μs whose scatter band reaches it inverts the concept and is warned about.
    objective : {"mean", "median", "max"}
        Statistic of the statue's peak θ/α over the motions that is minimised.
    friction_scatter : float
        Relative scatter s of the floor-face friction, 0 ≤ s < 1 (default 0.2): every candidate
        is also run at μs·(1 − s) and μs·(1 + s) (μk scaled alike), and counts as safe only if
        the statue survives every motion at all three. 0 runs the nominal friction only.
    free_time : float
        Longest free motion after each motion ends, s: each run goes on with the floor still
        until everything is at rest or the statue falls, for at most this long; a run still
        moving then is undetermined (not safe).
    options, workers, folder, fresh, chunk_size, progress
        As in :func:`rocking.analyses.store.run_stored`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``mu_s``, ``pedestal_mass``, ``motion`` and ``friction_factor`` (1 − s, 1,
        1 + s). Every summary field per run at the nominal friction; ``scatter_overturned``,
        ``scatter_undetermined``, ``scatter_peak_rotation_over_alpha``, ``scatter_peak_sliding``,
        ``scatter_residual_sliding`` and ``scatter_required_top_friction`` per run at each
        friction level; per candidate and motion, over the levels, ``falls``, ``undetermined``
        and ``clearance`` (m, the largest peak sliding); per candidate ``mu_k``,
        ``overturn_count`` (motions under which the statue falls at some level),
        ``undetermined_count``, ``overturn_rate``, ``peak_rotation_ratio_mean``, ``_median``,
        ``_max``, ``peak_sliding_max`` (m, the overall clearance), ``residual_sliding_max``,
        ``required_top_friction_max``, ``safe``, ``feasible`` (meets the limits), ``inverted``
        (μs at or above the statue–pedestal face's friction), ``score`` and ``recommended``.
        The attributes hold the inputs and the outcome of :func:`choose_design`: ``verdict`` (the
        first line), ``verdict_lines`` (all lines, newline-separated), ``meets_every_requirement``
        (1 or 0), ``recommended_mu_s``, ``recommended_mu_k``, ``recommended_pedestal_mass`` and
        ``recommended_clearance`` (m; all NaN if no candidate is safe), and likewise
        ``nearest_safe_*`` and ``fewest_overturns_*`` (with ``fewest_overturns_count``,
        ``fewest_overturns_motions`` and ``fewest_overturns_within_limits``).
    """
    from .batch import summaries_dataset

    if system.pedestal is None:
        raise ValueError("friction_design needs a system with a pedestal")
    motions = dict(motions)
    if not motions:
        raise ValueError("friction_design needs at least one motion")
    mus = np.asarray(mu_s, dtype=float)
    if mus.ndim != 1 or mus.size == 0 or np.any(~np.isfinite(mus)) or np.any(mus < 0):
        raise ValueError(f"mu_s must be non-negative numbers, got {mu_s!r}")
    if mu_k is not None and mu_k_ratio is not None:
        raise ValueError("give mu_k or mu_k_ratio, not both")
    base = system.pedestal.friction
    if mu_k is not None:
        if not mu_k >= 0:
            raise ValueError(f"mu_k must be >= 0, got {mu_k!r}")
        kin = np.minimum(float(mu_k), mus)
    else:
        if mu_k_ratio is None:
            mu_k_ratio = (base.kinetic / base.static) if base.static > 0 and base.kinetic is not None else 1.0
        if not 0 <= mu_k_ratio <= 1:
            raise ValueError(f"mu_k_ratio must lie in [0, 1], got {mu_k_ratio!r}")
        kin = float(mu_k_ratio) * mus
    masses = np.asarray(pedestal_mass if pedestal_mass is not None else [system.pedestal.mass], dtype=float)
    if masses.ndim != 1 or masses.size == 0 or np.any(~np.isfinite(masses)) or np.any(masses < 0):
        raise ValueError(f"pedestal_mass must be non-negative numbers, got {pedestal_mass!r}")
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}")
    scatter = _check_scatter(friction_scatter)
    if top_friction_limit is None and system.statue.friction is not None:
        top_friction_limit = system.statue.friction.static
    for name, v in (("sliding_limit", sliding_limit), ("residual_limit", residual_limit),
                    ("top_friction_limit", top_friction_limit)):
        if v is not None and not (math.isfinite(v) and v >= 0):
            raise ValueError(f"{name} must be a number >= 0, got {v!r}")
    if not free_time >= 0:
        raise ValueError(f"free_time must be >= 0, got {free_time!r}")

    # The scattered frictions are extra runs of the same batch, so a study that stops resumes
    # them like any other run; without scatter the runs are exactly those of the nominal sweep.
    factors = friction_factors(scatter)
    nominal = factors.index(1.0)
    candidates = {}
    for i, mu in enumerate(mus):
        for j, m1 in enumerate(masses):
            for k, f in enumerate(factors):
                s = replace_at(system, "pedestal.friction", Friction(static=float(mu) * f, kinetic=float(kin[i]) * f))
                candidates[i, j, k] = replace_at(s, "pedestal.mass", float(m1))
    runs = []
    for name in motions:  # motion outermost: a chunk ships one or two records
        for i in range(mus.size):
            for j in range(masses.size):
                for k in range(len(factors)):
                    runs.append(Run(candidates[i, j, k], name))  # the motion, then free motion until at rest
    options = dataclasses.replace(options, free_time_limit=float(free_time))
    meta = {"mu_s": mus.tolist(), "mu_k": kin.tolist(), "pedestal_mass": masses.tolist(), "motions": list(motions),
            "friction_factor": list(factors)}
    raw = run_stored(runs, motions, options=options, study="design", folder=folder, fresh=fresh, workers=workers,
                     chunk_size=chunk_size, progress=progress, meta=meta)
    alpha = system.statue.slenderness
    dims = ("motion", "mu_s", "pedestal_mass", "friction_factor")
    shape = (len(motions), mus.size, masses.size, len(factors))
    every = summaries_dataset(raw, np.full(len(runs), alpha), dims=dims, shape=shape)
    every = every.transpose("mu_s", "pedestal_mass", "motion", "friction_factor")
    ds = every.isel(friction_factor=nominal, drop=True)
    ds = ds.assign_coords(mu_s=mus, pedestal_mass=masses, motion=list(motions), friction_factor=list(factors))
    ds["mu_s"].attrs["long_name"] = "static friction of the pedestal on the floor"
    ds["pedestal_mass"].attrs["units"] = "kg"
    ds["friction_factor"].attrs["long_name"] = "floor-face friction (μs and μk) over its nominal value"

    run_dims = ("mu_s", "pedestal_mass", "motion", "friction_factor")
    over = every.overturned.values  # (mu, mass, motion, level)
    undetermined = run_undetermined(every)
    rot = every.peak_rotation_over_alpha.values  # an overturn gives π/(2α)
    slide = every.peak_sliding.values
    resid = np.abs(every.residual_sliding.values)
    top = np.where(over, np.nan, every.required_top_friction.values)  # what the face needs while the statue stands
    ds["scatter_overturned"] = (run_dims, over)
    ds["scatter_undetermined"] = (run_dims, undetermined, {
        "long_name": "statue neither overturned nor proven at rest (still moving at the end, or the run stopped)"})
    ds["scatter_peak_rotation_over_alpha"] = (run_dims, rot)
    ds["scatter_peak_sliding"] = (run_dims, slide, {"units": "m"})
    ds["scatter_residual_sliding"] = (run_dims, every.residual_sliding.values, {"units": "m"})
    ds["scatter_required_top_friction"] = (run_dims, every.required_top_friction.values)

    # Per candidate and motion, the worst of the friction levels: the design must hold whatever
    # the friction turns out to be within the scatter.
    falls = over.any(axis=-1)
    unsure = undetermined.any(axis=-1) & ~falls
    rot_env = rot.max(axis=-1)
    clearance = slide.max(axis=-1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN: every run overturns the statue
        top_max = np.nanmax(top.reshape(*top.shape[:2], -1), axis=-1)
    resid_max = resid.reshape(*resid.shape[:2], -1).max(axis=-1)
    cand = ("mu_s", "pedestal_mass")
    ds["mu_k"] = (("mu_s",), kin)
    ds["falls"] = (cand + ("motion",), falls, {"long_name": "the statue overturns at some friction level"})
    ds["undetermined"] = (cand + ("motion",), unsure, {
        "long_name": "no fall, but some friction level leaves the statue moving at the end (or the run stopped)"})
    ds["clearance"] = (cand + ("motion",), clearance, {
        "units": "m", "long_name": "free space the pedestal needs: largest peak sliding over the friction levels"})
    ds["overturn_count"] = (cand, falls.sum(axis=-1).astype(np.int64))
    ds["undetermined_count"] = (cand, unsure.sum(axis=-1).astype(np.int64))
    ds["overturn_rate"] = (cand, falls.mean(axis=-1))
    ds["peak_rotation_ratio_mean"] = (cand, rot_env.mean(axis=-1))
    ds["peak_rotation_ratio_median"] = (cand, np.median(rot_env, axis=-1))
    ds["peak_rotation_ratio_max"] = (cand, rot_env.max(axis=-1))
    ds["peak_sliding_max"] = (cand, clearance.max(axis=-1), {"units": "m"})
    ds["residual_sliding_max"] = (cand, resid_max, {"units": "m"})
    ds["required_top_friction_max"] = (cand, top_max, {
        "long_name": "largest friction the statue-pedestal face must supply (runs without overturning)"})
    score = _stat(rot_env, objective)
    choice = choose_design(
        mu_s=mus, mu_k=kin, pedestal_mass=masses, motions=list(motions), falls=falls, undetermined=unsure,
        clearance=clearance, residual=resid_max, top_friction=top_max, score=score, objective=objective,
        sliding_limit=sliding_limit, residual_limit=residual_limit, top_friction_limit=top_friction_limit,
        friction_scatter=scatter, tan_alpha=math.tan(alpha),
    )
    ds["safe"] = (cand, choice.safe, {"long_name": "the statue stands under every motion at every friction level"})
    ds["feasible"] = (cand, choice.feasible, {"long_name": "meets the sliding, residual and top-friction limits"})
    ds["inverted"] = (("mu_s",), choice.inverted, {
        "long_name": "floor-face μs·(1 + s) at or above the statue-pedestal face's friction (the concept is inverted)"})
    ds["score"] = (cand, score, {"long_name": f"{objective} peak θ/α over the motions"})
    rec = np.zeros(choice.safe.shape, dtype=bool)
    if choice.recommended is not None:
        rec[choice.recommended] = True
    ds["recommended"] = (cand, rec)
    ds.attrs.update(
        study="friction design",
        alpha=alpha,
        tan_alpha=math.tan(alpha),
        objective=objective,
        sliding_limit=np.nan if sliding_limit is None else float(sliding_limit),
        residual_limit=np.nan if residual_limit is None else float(residual_limit),
        top_friction_limit=np.nan if top_friction_limit is None else float(top_friction_limit),
        friction_scatter=scatter,
        free_time=float(free_time),
        gravity=float(options.gravity),
        statue_width=system.statue.width,
        statue_height=system.statue.height,
        statue_mass=system.statue.mass,
        **choice.attrs(),
    )
    return ds

CANDIDATE_COLUMNS = (
    "mu_k", "safe", "overturn_count", "undetermined_count", "overturn_rate", "peak_rotation_ratio_mean",
    "peak_rotation_ratio_median", "peak_rotation_ratio_max", "peak_sliding_max", "residual_sliding_max",
    "required_top_friction_max", "feasible", "inverted", "score", "recommended",
)


def candidate_table(ds):
    """One row per candidate (μs, pedestal mass) with the aggregated results (a pandas DataFrame).

    The results are the worst over the friction levels μs·(1 − s), μs, μs·(1 + s);
    ``peak_sliding_max`` is the free space the pedestal needs (m)."""
    table = ds[list(CANDIDATE_COLUMNS)].to_dataframe().reset_index()
    return table[["mu_s", "pedestal_mass", *CANDIDATE_COLUMNS]]


def _fmt(x: Any, digits: int = 3) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    x = float(x)
    return "–" if not math.isfinite(x) else f"{x:.{digits}g}"


def _levels_text(factors: Sequence[float], hit: Sequence[bool]) -> str:
    """'μs·0.8, μs' for the friction levels where ``hit`` holds."""
    return ", ".join("μs" if f == 1.0 else f"μs·{f:g}" for f, h in zip(factors, hit) if h)


def design_report(ds, *, title: str = "Friction design", chart: str | None = "design_chart.png") -> str:
    """A short Markdown report. Its first line after the title is the verdict (the recommendation,
    or that no candidate met every requirement); then the ways out and warnings, the free space
    per motion, the inputs, the ranking rules and the candidate table."""
    a = ds.attrs
    n_mot = ds.sizes["motion"]
    s = float(a.get("friction_scatter", 0.0))
    verdict = str(a["verdict_lines"]).split("\n")
    lines = [f"# {title}", "", f"**{verdict[0]}**", ""]
    lines += [f"* {line}" for line in verdict[1:]]
    if len(verdict) > 1:
        lines.append("")
    # the free space per motion, for the design the report stands on
    shown = None
    for prefix, what in (("recommended", "the recommended design"),
                         ("fewest_overturns", "the candidate with the fewest falls")):
        if math.isfinite(a.get(f"{prefix}_mu_s", np.nan)):
            shown = (a[f"{prefix}_mu_s"], a[f"{prefix}_pedestal_mass"], what)
            break
    if shown is not None:
        sel = ds.sel(mu_s=shown[0], pedestal_mass=shown[1])
        factors = [float(f) for f in ds.friction_factor.values]
        lines += [f"## Free space per motion, for {shown[2]} (μs = {shown[0]:.3g}, pedestal mass {shown[1]:g} kg)", "",
                  f"The largest peak sliding of the pedestal under each motion, "
                  + (f"over the friction levels {_levels_text(factors, [True] * len(factors))}" if len(factors) > 1
                     else "at the nominal friction")
                  + f". Overall: **{1e3 * float(sel.clearance.max()):.1f} mm**.",
                  "", "| motion | free space (mm) | statue |", "|---|---|---|"]
        for k, motion in enumerate(ds.motion.values):
            over = sel.scatter_overturned.values[k]
            unsure = sel.scatter_undetermined.values[k]
            if over.any():
                state = f"falls at {_levels_text(factors, over)}"
            elif unsure.any():
                state = f"undetermined at {_levels_text(factors, unsure)} (still moving at the end, or the run stopped)"
            else:
                state = "stands"
            lines.append(f"| {motion} | {1e3 * float(sel.clearance.values[k]):.1f} | {state} |")
        lines.append("")
    lines += ["## Inputs and rules", ""]
    lines.append(
        f"Statue {a['statue_width']:g} m × {a['statue_height']:g} m, {a['statue_mass']:g} kg "
        f"(α = {a['alpha']:.4f} rad, tan α = {a['tan_alpha']:.3f}); {n_mot} motion(s); "
        f"{ds.sizes['mu_s']} × {ds.sizes['pedestal_mass']} candidate(s) (μs × pedestal mass)."
    )
    if s > 0:
        lines.append(f"Friction scatter s = {s:g}: every candidate also runs at μs·(1 − s) and μs·(1 + s), with μk "
                     "scaled alike, and every result below is the worst of the three levels.")
    else:
        lines.append("Friction scatter: none (each candidate runs at its nominal friction only).")
    limits = []
    if math.isfinite(a["sliding_limit"]):
        limits.append(f"peak sliding ≤ {1e3 * a['sliding_limit']:.0f} mm")
    if math.isfinite(a["residual_limit"]):
        limits.append(f"residual sliding ≤ {1e3 * a['residual_limit']:.0f} mm")
    if math.isfinite(a["top_friction_limit"]):
        limits.append(f"required statue–pedestal friction ≤ {a['top_friction_limit']:.3g}")
    lines.append(f"Limits: {', '.join(limits) if limits else 'none'}.")
    lines.append(f"Ranking: {ranking_rule(s, a['objective'])} (docs/studies.md).")
    lines += ["", "## Candidates", "",
              "| μs | μk | pedestal mass (kg) | safe | falls | undetermined | peak θ/α mean | peak θ/α max | "
              "free space (mm) | residual (mm) | required top μ | meets limits |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for _, row in candidate_table(ds).iterrows():
        mark = " ⟵" if row["recommended"] else ""
        warn = " ⚠" if row["inverted"] else ""
        lines.append(
            f"| {_fmt(row['mu_s'])}{mark}{warn} | {_fmt(row['mu_k'])} | {_fmt(row['pedestal_mass'])} | "
            f"{_fmt(bool(row['safe']))} | {int(row['overturn_count'])}/{n_mot} | "
            f"{int(row['undetermined_count'])}/{n_mot} | {_fmt(row['peak_rotation_ratio_mean'])} | "
            f"{_fmt(row['peak_rotation_ratio_max'])} | {_fmt(1e3 * row['peak_sliding_max'], 4)} | "
            f"{_fmt(1e3 * row['residual_sliding_max'], 4)} | {_fmt(row['required_top_friction_max'])} | "
            f"{_fmt(bool(row['feasible']))} |"
        )
    lines += ["", "⟵ recommended; ⚠ μs·(1 + s) at or above the statue–pedestal face's friction (inverts the concept). "
              "An overturn counts as θ/α = π/(2α) in the statistics of the peak rotation. The free space is the "
              "largest peak sliding of the pedestal; the required top friction is the largest |F|/N at the statue–pedestal "
              "face over the runs the statue survives."]
    if chart:
        lines += ["", f"![design chart]({chart})"]
    return "\n".join(lines) + "\n"


def plot_design(ds, *, figsize_per_panel: tuple[float, float] = (6.4, 3.6)):
    """The design chart (one panel per pedestal mass): peak θ/α, overturn rate and peak sliding
    (the worst over the friction levels of the scatter) against μs, with tan α, the sliding limit,
    the recommended candidate and its scatter band [μs·(1 − s), μs·(1 + s)] marked. Returns the
    Figure."""
    from matplotlib.figure import Figure

    from ..viz.plots import plot_design_chart

    masses = ds.pedestal_mass.values
    fig = Figure(figsize=(figsize_per_panel[0], figsize_per_panel[1] * masses.size), layout="constrained")
    axes = fig.subplots(masses.size, 1, squeeze=False)[:, 0]
    stat = ds.attrs.get("objective", "mean")
    for ax, m1 in zip(axes, masses):
        sub = ds.sel(pedestal_mass=m1)
        rec = sub.recommended.values
        plot_design_chart(sub.mu_s.values, sub[f"peak_rotation_ratio_{stat}"].values, sub.peak_sliding_max.values,
                          sub.overturn_rate.values, ax=ax, tan_alpha=ds.attrs.get("tan_alpha"),
                          recommended=float(sub.mu_s.values[rec][0]) if rec.any() else None,
                          friction_scatter=float(ds.attrs.get("friction_scatter", 0.0)))
        limit = ds.attrs.get("sliding_limit", np.nan)
        if np.isfinite(limit):
            ax.right_ax.axhline(1e3 * limit, color="0.2", lw=0.9, ls="-.")
            ax.right_ax.annotate("sliding limit", (float(sub.mu_s.values.max()), 1e3 * limit), xytext=(-3, 3),
                                 textcoords="offset points", ha="right", fontsize=7, color="0.2")
            top = max(ax.right_ax.get_ylim()[1], 1.15e3 * limit)
            ax.right_ax.set_ylim(0.0, top)
        ax.set_ylabel(f"{stat} peak |θ|/α, overturn rate (–)")
        note = "" if ds.attrs.get("meets_every_requirement", 1) else " (no candidate met every requirement)"
        ax.set_title(f"pedestal mass {m1:g} kg{note}", fontsize=9)
    return fig
