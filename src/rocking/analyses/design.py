"""Friction design of a pedestal: which floor-face friction (and pedestal mass) keeps the statue
standing, and quietest, without letting the pedestal slide too far?

Every candidate (μs of the pedestal's floor face, with μk given or as a ratio of μs, and
optionally the pedestal mass) is run under every motion of a set (records scaled to a target
intensity, or a harmonic/pulse family), at its nominal friction and, because measured friction
scatters with the surfaces, humidity and age, at μs·(1 − s) and μs·(1 + s) with μk scaled alike
(``friction_scatter`` s, default 0.2; designing both faces, :func:`two_face_design` also runs the
faces drifting in opposite directions: five levels). For each candidate the study reports, over
the motions and those friction levels (the worst of them):

* the statue's peak θ/α (mean, median and maximum over the motions; an overturn counts as π/(2α));
* the motions under which the statue falls, and those whose runs prove nothing (still moving at
  the end, or stopped early): "undetermined";
* the pedestal's peak sliding, which is the free space (clearance) it needs, per motion and
  overall, and its residual sliding (m);
* ``required_top_friction``: the largest |F|/N the statue–pedestal face must supply (over the
  runs the statue survives), to compare with that face's friction.

The ranking (:func:`choose_design`; the rules are in ``docs/studies.md``) puts safety above every
limit: a candidate is *safe* if the statue neither falls nor is left undetermined under any motion
at any of the friction levels. The recommendation is the best safe candidate that meets
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
from ..results.wording import need_text
from ..simulation import Options
from ..stack.model import Block, Interface, Stack
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
    "default_top_sliding_limit",
    "stack_of_system",
    "two_face_design",
    "two_face_levels",
]

OBJECTIVES = ("mean", "median", "max")

#: How the verdict's line opens when the limit on the statue's slide on the top face moves the
#: recommendation.
TOP_LIMIT_EXCLUDES = "The limit on the statue's slide on the pedestal's top face excludes"


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


def two_face_levels(scatter: float, *, top_slips: bool = True) -> tuple[tuple[float, float], ...]:
    """The friction levels of a two-face design, as (floor factor, top factor) on each face's
    (μs, μk): the nominal (1, 1); both faces together (1 − s, 1 − s) and (1 + s, 1 + s); and in
    opposite directions (1 + s, 1 − s) and (1 − s, 1 + s), since the two surfaces age apart.
    A top face that never slips (``top_slips`` False) makes the top factor moot: the first three
    only. Without scatter, the nominal only."""
    s = _check_scatter(scatter)
    if s == 0.0:
        return ((1.0, 1.0),)
    low, high = 1.0 - s, 1.0 + s
    together = ((1.0, 1.0), (low, low), (high, high))
    return together + ((high, low), (low, high)) if top_slips else together


def _two_face_level_name(floor: float, top: float, *, top_slips: bool) -> str:
    """A level of :func:`two_face_levels` in words: 'nominal μs', 'both faces μs·0.8',
    'floor μs·1.2 with top μs·0.8' (or 'floor μs·0.8' when the top face never slips)."""
    if floor == 1.0 and top == 1.0:
        return "nominal μs"
    if not top_slips:
        return f"floor μs·{floor:g}"
    if floor == top:
        return f"both faces μs·{floor:g}"
    return f"floor μs·{floor:g} with top μs·{top:g}"


def _two_face_band(s: float, *, top_slips: bool = True) -> str:
    """The friction levels of a two-face design in one phrase, for verdicts and rules."""
    if s == 0:
        return "at the nominal friction (no scatter)"
    if not top_slips:
        return f"with the floor face at μs and μs·(1 ± {s:g}) (μk alike; the top face never slips)"
    return f"with both faces at μs and at μs·(1 ± {s:g}) together and in opposite directions (μk alike)"


# why a run that did not overturn may still not prove that the statue stands
_UNDETERMINED_WHY = ("still moving at the end with energy enough to overturn, a body lifting off, or the run "
                     "stopped")


def run_undetermined(ds) -> np.ndarray:
    """Per run of a summaries Dataset: True where the statue did not overturn, yet the run does not
    prove that it stands: the statue is still moving at the end (``still_moving``, when the
    summaries carry it), the run stopped early, or a body would have left its support while the
    statue stood (``"lifted_off"``): any status but ``"completed"``. A run still moving whose
    statue can no longer overturn (``settled_by_energy``: too little energy left on a floor that
    has stopped) proves it as a run at rest does."""
    over = np.asarray(ds.overturned.values, dtype=bool)
    unproven = np.asarray(ds.status.values).astype(str) != "completed"
    moving = ds.get("still_moving")
    if moving is not None:
        m = np.asarray(moving.values)
        unproven = unproven | (np.nan_to_num(m.astype(float)) != 0)
    return ~over & unproven & ~_settled(ds)


def _settled(ds) -> np.ndarray:
    """``settled_by_energy`` of a summaries Dataset as booleans (False where it is missing: the
    summaries of an older study)."""
    settled = ds.get("settled_by_energy")
    if settled is None:
        return np.zeros(np.shape(ds.overturned.values), dtype=bool)
    return np.nan_to_num(np.asarray(settled.values).astype(float)) != 0


def _mm(x: float) -> str:
    """A length given in m, in mm for reading: '0.05 mm', '12 mm', '303.7 mm' (never 5.17e-05)."""
    from ..viz.plots import _mm_text

    return _mm_text(1e3 * float(x))


def _mm_cell(x: float) -> str:
    """The same, without the unit, for a table column headed '(mm)'."""
    return _mm(x).removesuffix(" mm")


_mm_limit = _mm


def _names(names: Sequence[str], most: int = 6) -> str:
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


def ranking_rule(friction_scatter: float, objective: str = "mean", *, two_face: bool = False,
                 top_slips: bool = True) -> str:
    """The ranking of :func:`choose_design` in one sentence, for reports and the web page
    (``two_face``: of :func:`two_face_design`; ``top_slips`` False: its top face never slips)."""
    s = _check_scatter(friction_scatter)
    band = f"at μs and μs·(1 ± {s:g}), μk alike" if s > 0 else "at the nominal friction"
    if two_face:
        band = _two_face_band(s, top_slips=top_slips) if s > 0 else "at the nominal friction"
        return (f"safety first: a candidate is safe if, under every motion {band}, no block falls, none slides to "
                f"the edge of the block below and every run ends at rest (or with too little energy left to "
                f"overturn); among the safe candidates that meet the "
                f"limits, the smallest {objective} peak θ/α, the least free space on the floor, then the smaller "
                f"floor μs, the lighter pedestal, the smaller top μs, the narrower pedestal; if no safe candidate "
                f"meets the limits, the safe one needing the least free space (among those within the limit on the "
                f"statue's slide on the top face, if any), and nothing if none is safe")
    return (f"safety first: a value is safe if the statue neither falls nor is left moving, and its pedestal (where "
            f"its width and height are given) would not tip, under any motion {band}; "
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
    #: (μs, mass, *extra, motion): a block slid to the edge of the one below (stack runs), or None
    slid_off: np.ndarray | None = None
    #: the candidate axes after (μs, mass): ((name, values), …), e.g. mu_s_top, pedestal_width
    extra_axes: tuple[tuple[str, np.ndarray], ...] = ()
    #: the candidate that would be recommended without the limit on the statue's slide on the top
    #: face, when that limit is what excludes it (else None)
    excluded_by_top_sliding: tuple[int, ...] | None = None

    @property
    def verdict(self) -> str:
        """The first line: the recommendation, or that no candidate met every requirement."""
        return self.lines[0]

    def falling_motions(self, ij: tuple[int, int]) -> list[str]:
        return [m for m, f in zip(self.motions, self.falls[ij]) if f]

    def undetermined_motions(self, ij: tuple[int, int]) -> list[str]:
        return [m for m, u in zip(self.motions, self.undetermined[ij]) if u]

    def slid_off_motions(self, ij: tuple[int, ...]) -> list[str]:
        if self.slid_off is None:
            return []
        return [m for m, u in zip(self.motions, self.slid_off[ij]) if u]

    def attrs(self) -> dict[str, Any]:
        """Dataset attributes (numbers and strings only, so that they survive NetCDF)."""
        out: dict[str, Any] = {
            "verdict": self.verdict,
            "verdict_lines": "\n".join(self.lines),
            "meets_every_requirement": int(self.meets_every_requirement),
            "fewest_overturns_within_limits": int(self.fewest_overturns_within_limits),
        }
        for prefix, ij in (("recommended", self.recommended), ("nearest_safe", self.nearest_safe),
                           ("fewest_overturns", self.fewest_overturns),
                           ("excluded_by_top_sliding", self.excluded_by_top_sliding)):
            out[f"{prefix}_mu_s"] = float(self.mu_s[ij[0]]) if ij else np.nan
            out[f"{prefix}_mu_k"] = float(_clean(self.mu_k[ij[0]])) if ij else np.nan
            out[f"{prefix}_pedestal_mass"] = float(self.pedestal_mass[ij[1]]) if ij else np.nan
            out[f"{prefix}_clearance"] = float(self.clearance[ij].max()) if ij else np.nan
            for q, (axis, values) in enumerate(self.extra_axes):
                out[f"{prefix}_{axis}"] = float(values[ij[2 + q]]) if ij else np.nan
        ij = self.fewest_overturns
        out["fewest_overturns_count"] = int(self.falls[ij].sum()) if ij else -1
        out["fewest_overturns_motions"] = "\n".join(self.falling_motions(ij)) if ij else ""
        out["fewest_overturns_undetermined"] = "\n".join(self.undetermined_motions(ij)) if ij else ""
        if self.slid_off is not None:
            out["fewest_overturns_slid_off"] = "\n".join(self.slid_off_motions(ij)) if ij else ""
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
    extra_axes: Sequence[tuple[str, Sequence[float]]] = (),
    describe: Callable[[tuple[int, ...]], str] | None = None,
    slid_off: Any = None,
    slid_off_text: str = "a block slides to the edge of the one below",
    slid_off_how: str = "slides to an edge",
    subject: str = "pedestal floor friction",
    top_sliding: Any = None,
    top_sliding_limit: Any = None,
    top_sliding_limit_text: str | None = None,
    scatter_text: str | None = None,
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
        some level leaves it still moving at the end with energy enough to overturn (or the run
        stopped early).
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
    extra_axes : sequence of (name, values), optional
        Candidate axes after (μs, mass), e.g. ``("mu_s_top", …)`` and ``("pedestal_width", …)``
        of the two-face design: every candidate array then has these dimensions after the
        mass (``falls`` is (μs, mass, *extra, motion)); they break the last ties, smaller first.
    describe : callable, optional
        ``describe(index)`` → the text naming a candidate (default: its μs, μk and mass).
    slid_off : bool array like ``falls``, optional
        Stack runs: a block slid to the edge of the one below at some friction level (the engine
        stops there); or, in the two-body model, the pedestal would tip (its uplift check). Not
        safe, like a fall, and named as ``slid_off_text`` (and ``slid_off_how`` where the verdict
        lists how every candidate fails).
    subject : str
        What the first line recommends ("Recommended <subject>: …").
    top_sliding : array like ``score``, optional
        Two-face design: the statue's largest peak slide on the pedestal's top face over the
        motions and levels, m.
    top_sliding_limit : float or array broadcasting to ``score``, optional
        The largest such slide a candidate may need, m (per candidate: it depends on the
        pedestal's width); ``inf``: no limit. A limit like ``sliding_limit``.
    top_sliding_limit_text : str, optional
        The limit in words for the verdict (default: "statue's slide on the top face ≤ … mm").
    scatter_text : str, optional
        The friction levels the runs covered, in words (default: "at μs and μs·(1 ± s) (μk
        alike)"); the two-face design names its levels in opposite directions too.

    Notes
    -----
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
    slid = np.zeros(falls.shape, bool) if slid_off is None else np.asarray(slid_off, dtype=bool) & ~falls
    unsure = np.asarray(undetermined, dtype=bool) & ~falls & ~slid
    extra = tuple((str(axis), np.asarray(values, dtype=float)) for axis, values in extra_axes)
    clearance = np.asarray(clearance, dtype=float)
    residual = np.asarray(residual, dtype=float)
    top = np.asarray(top_friction, dtype=float)
    score = np.asarray(score, dtype=float)
    n_mot = len(names)
    s = _check_scatter(friction_scatter)
    band = f"at μs and μs·(1 ± {s:g}) (μk alike)" if s > 0 else "at the nominal friction (no scatter)"
    if scatter_text is not None:
        band = scatter_text

    clear_max = clearance.max(axis=-1)
    miss_sliding = clear_max > sliding_limit if sliding_limit is not None else np.zeros(clear_max.shape, bool)
    miss_residual = residual > residual_limit if residual_limit is not None else np.zeros(clear_max.shape, bool)
    miss_top = top > top_friction_limit if top_friction_limit is not None else np.zeros(clear_max.shape, bool)
    top_slide = np.zeros(clear_max.shape) if top_sliding is None else np.asarray(top_sliding, dtype=float)
    top_room = np.broadcast_to(np.asarray(np.inf if top_sliding_limit is None else top_sliding_limit, dtype=float),
                               clear_max.shape)
    miss_top_slide = top_slide > top_room
    feasible = ~(miss_sliding | miss_residual | miss_top | miss_top_slide)
    n_unsafe = falls.sum(axis=-1) + slid.sum(axis=-1) + unsure.sum(axis=-1)
    safe = n_unsafe == 0
    # the floor face's friction may turn out s higher: the concept is inverted as soon as the top
    # of its scatter band reaches the statue-pedestal face's friction
    inverted = (mus * (1.0 + s) >= top_friction_limit) if top_friction_limit is not None else np.zeros(mus.shape, bool)
    cands = list(np.ndindex(*falls.shape[:-1]))  # (μs, mass, *extra), μs outermost

    def best(pool: list[tuple[int, int]], key: Callable[[tuple[int, int]], tuple]) -> tuple[int, int] | None:
        return min(pool, key=key) if pool else None

    def tail(ij: tuple[int, ...]) -> tuple:
        i, j = ij[:2]
        rest = tuple(float(values[k]) for (_, values), k in zip(extra, ij[2:]))
        return (bool(inverted[i]), float(score[ij]), float(clear_max[ij]), float(mus[i]), float(masses[j]), *rest)

    safe_pool = [c for c in cands if safe[c]]
    good = best([c for c in safe_pool if feasible[c]], tail)
    # the free space on the floor is what the fallback gives up; a statue sliding towards the edge
    # of its plinth is given up last of the limits
    nearest = best(safe_pool, lambda c: (bool(miss_top_slide[c]), bool(miss_residual[c] or miss_top[c]),
                                         float(clear_max[c]), *tail(c)))
    # what would be recommended without the top-face limit, to say so when that limit moves it
    within_others = ~(miss_sliding | miss_residual | miss_top)
    loose = best([c for c in safe_pool if within_others[c]], tail)
    if loose is None:
        loose = best(safe_pool, lambda c: (bool(miss_residual[c] or miss_top[c]), float(clear_max[c]), *tail(c)))
    limited = [c for c in cands if feasible[c]]
    within = bool(limited)
    by_falls = (lambda c: (int(n_unsafe[c]), int(falls[c].sum() + slid[c].sum()), *tail(c)))
    fewest = best(limited, by_falls)
    if fewest is None and not safe_pool:  # nothing to build either way: the least bad candidate, named
        fewest = best(cands, lambda c: (int(n_unsafe[c]), int(miss_sliding[c] + miss_residual[c] + miss_top[c]
                                                              + miss_top_slide[c]), *by_falls(c)[1:]))
    recommended = good if good is not None else nearest
    excluded = loose if loose is not None and loose != recommended and miss_top_slide[loose] else None

    def name(ij: tuple[int, ...]) -> str:
        if describe is not None:
            return describe(ij)
        i, j = ij[:2]
        return f"μs = {mus[i]:.3g} (μk = {kin[i]:.3g}), pedestal mass {masses[j]:g} kg"

    def misses(ij: tuple[int, int]) -> list[str]:
        out = []
        if miss_sliding[ij]:
            out.append(f"the pedestal needs {_mm(clear_max[ij])} of free space, more than the "
                       f"{_mm_limit(sliding_limit)} limit")
        if miss_residual[ij]:
            out.append(f"its residual sliding {_mm(residual[ij])} exceeds the {_mm_limit(residual_limit)} limit")
        if miss_top[ij]:
            out.append(f"the statue–pedestal face must supply μ = {need_text(top[ij], '.3g')}, more than "
                       f"{top_friction_limit:.3g}")
        if miss_top_slide[ij]:
            out.append(top_slide_miss(ij))
        return out

    def top_slide_miss(ij: tuple[int, ...]) -> str:
        return (f"the statue slides {_mm(top_slide[ij])} on the pedestal's top face, more than the "
                f"{_mm_limit(top_room[ij])} limit there")

    def outcome(ij: tuple[int, int]) -> str:
        fell = [m for m, f in zip(names, falls[ij]) if f]
        moving = [m for m, u in zip(names, unsure[ij]) if u]
        edge = [m for m, u in zip(names, slid[ij]) if u]
        parts = []
        if fell and n_mot == 1:
            parts.append(f"the statue falls under the motion ({fell[0]})")
        elif fell:
            parts.append(f"the statue falls under {len(fell)} of {n_mot} motions: {_names(fell)}")
        if edge:
            risk = "" if "fall risk" in slid_off_text else " (a fall risk)"  # (a text may say it itself)
            parts.append(f"{slid_off_text}{risk} under {len(edge)} of {n_mot} motions: {_names(edge)}")
        if moving:
            parts.append(f"undetermined ({_UNDETERMINED_WHY}) under {len(moving)}: {_names(moving)}")
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
    if top_sliding_limit_text is not None:
        limits.append(top_sliding_limit_text)
    elif np.isfinite(top_room).any():
        limits.append(f"statue's slide on the top face ≤ {_mm_limit(float(np.min(top_room)))}")
    limit_text = ", ".join(limits) if limits else "no limits"
    excluded_line = (f"{TOP_LIMIT_EXCLUDES} {name(excluded)}, which "
                     f"would otherwise be recommended: {top_slide_miss(excluded)}." if excluded is not None else None)

    lines: list[str] = []
    if good is not None:
        lines.append(f"Recommended {subject}: {name(good)}. The statue stands under {every} {band}, "
                     f"and the limits are met ({limit_text}).")
        if excluded_line:
            lines.append(excluded_line)
        lines.append(f"Free space the pedestal needs: {space(good)}.")
    else:
        if safe_pool:
            lines.append(f"No candidate met every requirement: none keeps the statue standing under every motion "
                         f"{band} and also meets the limits ({limit_text}).")
            if excluded_line:
                lines.append(excluded_line)
            other = [m for m in misses(nearest) if not m.startswith("the pedestal needs")]
            beyond = f", more than the {_mm_limit(sliding_limit)} limit" if miss_sliding[nearest] else ""
            kept = (" among those that keep the statue's slide on the top face within its limit"
                    if not miss_top_slide[nearest] and any(miss_top_slide[c] for c in safe_pool) else "")
            lines.append(f"Recommended, because not falling comes first: {name(nearest)}, the safe candidate that "
                         f"needs the least free space{kept}: {space(nearest)}{beyond}"
                         + "".join(f"; {m}" for m in other) + ".")
        else:
            how = "falls, or is left undetermined" if slid_off is None else \
                f"falls, {slid_off_how}, or is left undetermined"
            lines.append(f"No candidate met every requirement: with every candidate the statue {how}, under some "
                         f"motion {band}. Nothing is recommended.")
        # "fewest falls" unless the candidate's only failures are undetermined runs
        least = ("the fewest falls" if fewest is None or falls[fewest].any() or slid[fewest].any()
                 else "no fall, but not proven safe")
        if fewest is not None and within:
            lines.append(f"Within the limits, {least}: {name(fewest)}: {outcome(fewest)}.")
        elif fewest is not None:
            lines.append(f"No candidate meets the limits ({limit_text}) either; {least} regardless of them: "
                         f"{name(fewest)}: {outcome(fewest)}; {'; '.join(misses(fewest))}.")
        else:
            lines.append(f"No candidate meets the limits ({limit_text}).")
        # (the floor face's argument: with a top face that may slip the statue has other ways out)
        if not safe_pool and not extra and tan_alpha is not None and float(mus.min()) * (1.0 + s) >= tan_alpha:
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
        slid_off=None if slid_off is None else slid, extra_axes=extra, excluded_by_top_sliding=excluded,
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
    mu_s_top: Sequence[float] | None = None,
    mu_k_top: float | None = None,
    mu_k_top_ratio: float | None = None,
    pedestal_width: Sequence[float] | None = None,
    top_sliding_limit: float | None = None,
):
    """Sweep the pedestal's floor friction (and mass) over a set of motions and recommend one.

    With a :class:`rocking.stack.Stack`, or with ``mu_s_top`` or ``pedestal_width``, both faces
    of the pedestal are designed on the stack engine: see :func:`two_face_design`, which takes
    the same arguments and returns the same Dataset with two more candidate dimensions, and five
    friction levels along ``friction_level`` (the faces also drifting in opposite directions)
    instead of ``friction_factor``.

    Parameters
    ----------
    system : System or Stack
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

    mu_s_top, mu_k_top, mu_k_top_ratio, pedestal_width, top_sliding_limit : optional
        The statue–pedestal face and the pedestal's width (m), swept on the stack engine, and the
        limit on the statue's slide on that face (m; :func:`two_face_design`).

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

    if isinstance(system, Stack) or mu_s_top is not None or pedestal_width is not None:
        return two_face_design(
            system, motions, mu_s=mu_s, mu_k=mu_k, mu_k_ratio=mu_k_ratio, pedestal_mass=pedestal_mass,
            mu_s_top=mu_s_top, mu_k_top=mu_k_top, mu_k_top_ratio=mu_k_top_ratio, pedestal_width=pedestal_width,
            top_sliding_limit=top_sliding_limit,
            sliding_limit=sliding_limit, residual_limit=residual_limit, top_friction_limit=top_friction_limit,
            objective=objective, friction_scatter=friction_scatter, free_time=free_time, options=options,
            workers=workers, folder=folder, fresh=fresh, chunk_size=chunk_size, progress=progress)
    if mu_k_top is not None or mu_k_top_ratio is not None:
        raise ValueError("mu_k_top and mu_k_top_ratio need mu_s_top (the statue–pedestal face's μs)")
    if top_sliding_limit is not None:
        raise ValueError("top_sliding_limit needs the stack engine, where the statue may slip on the pedestal: "
                         "give mu_s_top or pedestal_width too, or a Stack")
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
    # The pedestal would tip (the floor's reaction leaves its base: derivation §3.5), which this
    # model does not follow: not proven safe, and named. Checked only for a pedestal whose width
    # and height are given.
    tips = np.isfinite(every.pedestal_uplift_time.values) & ~over
    ds["scatter_overturned"] = (run_dims, over)
    ds["scatter_undetermined"] = (run_dims, undetermined, {
        "long_name": f"statue neither overturned nor proven safe ({_UNDETERMINED_WHY})"})
    ds["scatter_peak_rotation_over_alpha"] = (run_dims, rot)
    ds["scatter_peak_sliding"] = (run_dims, slide, {"units": "m"})
    ds["scatter_residual_sliding"] = (run_dims, every.residual_sliding.values, {"units": "m"})
    ds["scatter_required_top_friction"] = (run_dims, every.required_top_friction.values)
    ds["scatter_pedestal_uplift_time"] = (run_dims, every.pedestal_uplift_time.values, {
        "units": "s", "long_name": "first instant the pedestal would tip (NaN: never, or not checked)"})

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
    pedestal_tips = tips.any(axis=-1) & ~falls
    ds["pedestal_tips"] = (cand + ("motion",), pedestal_tips, {
        "long_name": "no fall, but the pedestal would tip at some friction level (this model does not follow it)"})
    ds["pedestal_tips_count"] = (cand, pedestal_tips.sum(axis=-1).astype(np.int64))
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
        slid_off=pedestal_tips if pedestal_tips.any() else None, slid_off_how="tips its pedestal",
        slid_off_text=("the pedestal would tip, a fall risk (the floor's reaction leaves its base, which this model "
                       "does not follow: a pedestal_width axis designs it on the stack engine),"),
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


# ============================================================== both faces, on the stack engine
def stack_of_system(system: System, *, pedestal_width: float | None = None) -> Stack:
    """The statue on its pedestal as a two-block :class:`~rocking.stack.Stack`: the pedestal
    (block 1, ``"pedestal"``) on the floor with its floor friction, the statue (``"statue"``) on
    it with ``statue.friction`` (None: it never slips) and ``statue.restitution`` on that face.
    The pedestal needs a width (or ``pedestal_width``, m) and a height: it may rock."""
    p, st = system.pedestal, system.statue
    if p is None:
        raise ValueError("pedestal: missing (required): the design sweeps the pedestal's faces")
    width = pedestal_width if pedestal_width is not None else p.width
    for field, value in (("pedestal.width", width), ("pedestal.height", p.height)):
        if value is None:
            raise ValueError(f"{field}: needed by the stack engine, which designs both faces (the pedestal may "
                             "rock and the statue slip on it)")
    return Stack(blocks=(Block(name="pedestal", width=float(width), height=float(p.height), mass=float(p.mass)),
                         Block(name="statue", width=st.width, height=st.height, mass=st.mass)),
                 interfaces=(Interface(friction=p.friction),
                             Interface(friction=st.friction, restitution=st.restitution)))


def _kinetic(mus: np.ndarray, mu_k: float | None, ratio: float | None, base: Friction | None,
             names: tuple[str, str]) -> np.ndarray:
    """μk of each μs: fixed (capped at μs), a ratio of μs, or by default the ratio of ``base``."""
    if mu_k is not None and ratio is not None:
        raise ValueError(f"give {names[0]} or {names[1]}, not both")
    if mu_k is not None:
        if not mu_k >= 0:
            raise ValueError(f"{names[0]} must be >= 0, got {mu_k!r}")
        return np.minimum(float(mu_k), mus)
    if ratio is None:
        ratio = (base.kinetic / base.static) if base is not None and base.static > 0 and base.kinetic is not None else 1.0
    if not 0 <= ratio <= 1:
        raise ValueError(f"{names[1]} must lie in [0, 1], got {ratio!r}")
    return float(ratio) * mus


def _clean(values: Any) -> Any:
    """Products like 0.8 × 0.3 as written for reading (0.24, not 0.24000000000000002); the runs
    keep the exact products, so that a run equals the single simulation with ratio × μs."""
    return np.round(values, 12)


def _grid_values(values: Sequence[float], name: str, *, positive: bool) -> np.ndarray:
    arr = np.asarray(values, dtype=float)
    bad = arr.ndim != 1 or arr.size == 0 or np.any(~np.isfinite(arr)) or np.any(arr <= 0 if positive else arr < 0)
    if bad:
        raise ValueError(f"{name} must be {'positive' if positive else 'non-negative'} numbers, got {values!r}")
    return arr


def _check_top_sliding_limit(value: Any) -> float | None:
    """A given limit on the statue's slide on the top face (m): > 0, or inf for none."""
    if value is None:
        return None
    ok = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))
    if not ok or not float(value) > 0:
        raise ValueError(f"top_sliding_limit must be a number > 0 (m), or inf for no limit, got {value!r}")
    return float(value)


def default_top_sliding_limit(pedestal_width: Any, statue_width: float, statue_offset: float = 0.0) -> np.ndarray:
    """Half the room on the pedestal's top face, m: 0.5·((pedestal width − statue width)/2 − |offset|),
    per pedestal width (m). The statue's edge may travel half way to the pedestal's edge, on the
    side where it stands nearer the edge (``statue_offset``, m, from the pedestal's centre)."""
    room = 0.5 * (np.asarray(pedestal_width, dtype=float) - float(statue_width)) - abs(float(statue_offset))
    if np.any(room <= 0):
        w = float(np.asarray(pedestal_width, dtype=float).ravel()[np.argmin(np.ravel(room))])
        raise ValueError(f"top_sliding_limit: its default, half the room on the pedestal's top face, needs room "
                         f"there; a {w:g} m pedestal under a {statue_width:g} m statue (offset {statue_offset:g} m) "
                         "leaves none: give top_sliding_limit (m)")
    return 0.5 * room


def top_sliding_limit_text(widths: Sequence[float], limits: Sequence[float], *, default: bool) -> str:
    """The limit on the statue's slide on the top face in words (reports and verdicts)."""
    limits = [float(v) for v in limits]
    if not np.isfinite(limits).any():
        return "no limit on the statue's slide on the top face (top_sliding_limit = inf)"
    values = sorted({(float(w), v) for w, v in zip(widths, limits)})
    if not default:
        return f"statue's slide on the top face ≤ {_mm_limit(limits[0])}"
    per = ", ".join(f"{_mm_limit(v)} on the {w:g} m pedestal" for w, v in values)
    return (f"statue's slide on the top face ≤ half the room there, 0.5 × ((pedestal width − statue width)/2 − "
            f"|offset|): {per}")


#: The candidate dimensions of a two-face design, in order.
TWO_FACE_CANDIDATE = ("mu_s", "pedestal_mass", "mu_s_top", "pedestal_width")


def face_work(floor_slide: float, top_slide: float, statue_rotation: float, pedestal_rotation: float) -> str:
    """Which face of the pedestal does the work, in one clause: the face that slides more isolates
    (slides in m, rotations as peak θ/α of the statue and the pedestal's peak rotation in rad)."""
    if floor_slide <= 0 and top_slide <= 0:
        text = "neither face slides"
    elif floor_slide >= top_slide:
        text = (f"the floor face isolates: the pedestal slides {_mm(floor_slide)}, the statue slides "
                f"{_mm(top_slide)} on the top face")
    else:
        text = (f"the top face isolates: the statue slides {_mm(top_slide)} on the pedestal's top face, the "
                f"pedestal slides {_mm(floor_slide)} on the floor")
    text += (f"; the statue rocks (peak θ/α = {statue_rotation:.2f})" if statue_rotation > 0
             else "; the statue does not rock")
    if pedestal_rotation > 0:
        text += f"; the pedestal rocks (peak {math.degrees(pedestal_rotation):.2f}°)"
    return text


def _after_recommendation(lines: Sequence[str]) -> int:
    """Where the verdict's line on the working face goes: after the line that recommends (and the
    top-face limit's line that follows it), or second when nothing is recommended."""
    at = next((k for k, line in enumerate(lines) if line.startswith("Recommended")), 0) + 1
    while at < len(lines) and lines[at].startswith(TOP_LIMIT_EXCLUDES):
        at += 1
    return at


def two_face_design(
    system: System | Stack,
    motions: Mapping[str, Any],
    *,
    mu_s: Sequence[float],
    mu_k: float | None = None,
    mu_k_ratio: float | None = None,
    pedestal_mass: Sequence[float] | None = None,
    mu_s_top: Sequence[float] | None = None,
    mu_k_top: float | None = None,
    mu_k_top_ratio: float | None = None,
    pedestal_width: Sequence[float] | None = None,
    sliding_limit: float | None = None,
    residual_limit: float | None = None,
    top_friction_limit: float | None = None,
    top_sliding_limit: float | None = None,
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
    """Design both faces of the pedestal on the stack engine: the statue may slip on the pedestal,
    the pedestal may slide, rock and lift.

    The pedestal is the stack's block 1 (on the floor), the *floor face* interface 1 and the *top
    face* interface 2 (under block 2, the statue); the statue's rotation statistics are the top
    block's (the statue itself in a two-block stack). A :class:`System` is first turned into a
    two-block stack (:func:`stack_of_system`). Candidates are every floor μs × pedestal mass × top
    μs × pedestal width. The two faces are different surfaces that age apart, so the friction
    scatter s is run as five levels (floor factor, top factor) on each face's μs and μk
    (:func:`two_face_levels`): (1, 1), both together (1 − s, 1 − s) and (1 + s, 1 + s), and in
    opposite directions (1 + s, 1 − s), the worst for the statue's slide on the top face, and
    (1 − s, 1 + s), the worst for the free space on the floor. A top face that never slips runs the
    first three only; s = 0 the nominal only. Every result is the worst over the levels.

    Safety (:func:`choose_design`): a candidate is safe if, under every motion at every level, no
    block overturns (sliding off counts), no block reaches the edge of the one below when
    ``options.stop_at_edge`` asks the runs to stop there (status ``slid_past_edge``: a fall risk,
    named as such) and every run ends at rest (or still moving with too little energy left for any
    block to overturn, ``settled_by_energy``). Then the
    limits: ``sliding_limit`` and ``residual_limit`` on the pedestal's sliding on the floor (the
    free space it needs), ``top_friction_limit`` (if given) on the friction the top face must
    supply, and ``top_sliding_limit`` on the statue's peak slide on the top face (by default half
    the room there, per pedestal width: :func:`default_top_sliding_limit`). When that last limit
    is what moves the recommendation, the verdict's second line says so and names the candidate
    it excludes. The next line says which face does the work for the recommended candidate
    (:func:`face_work`). The parameters not listed below are those of :func:`friction_design`.

    Parameters
    ----------
    mu_s_top : sequence of float, optional
        μs of the top face; default the given top face's (a top face that never slips stays so:
        ``mu_s_top`` is then ∞).
    mu_k_top, mu_k_top_ratio : float, optional
        Its μk, fixed (capped at μs) or as a ratio of μs; default the given top face's ratio.
    pedestal_width : sequence of float, optional
        m; default the pedestal's.
    top_sliding_limit : float, optional
        The largest peak slide of the statue on the pedestal's top face a candidate may need, m
        (> 0; ``inf``: no limit). Default: half the room on the top face, 0.5·((pedestal width −
        statue width)/2 − |offset|), for each candidate's own width.

    Returns
    -------
    xarray.Dataset
        As :func:`friction_design`, with candidate dimensions ``mu_s``, ``pedestal_mass``,
        ``mu_s_top`` and ``pedestal_width`` (and ``mu_k_top`` along ``mu_s_top``), and the
        levels along ``friction_level`` instead of ``friction_factor``: named ("nominal μs",
        "both faces μs·0.8", "floor μs·1.2 with top μs·0.8", …), with coordinates
        ``floor_factor`` and ``top_factor``. Per run and level also ``scatter_slid_off``,
        ``scatter_floor_sliding``, ``scatter_top_sliding`` (m, the pedestal on the floor and the
        statue on the pedestal) and
        ``scatter_pedestal_rotation`` (rad); per candidate and motion ``slid_off`` and
        ``top_sliding`` (m, worst over the levels); per candidate ``slid_off_count``,
        ``top_sliding_max`` and ``pedestal_rotation_max``; per width ``top_sliding_limit`` (m).
        ``clearance`` is the floor face's sliding. Attributes as in :func:`friction_design`, plus ``engine = "stack"``,
        ``recommended_mu_s_top``, ``recommended_pedestal_width`` (and for ``nearest_safe_``,
        ``fewest_overturns_``, ``excluded_by_top_sliding_``), ``face_work`` (the clause of
        :func:`face_work`), ``top_sliding_limit`` (the given limit, m; NaN: the default) and
        ``top_sliding_limit_text``.
    """
    from .batch import specs_dataset

    stack = system if isinstance(system, Stack) else stack_of_system(
        system, pedestal_width=None if pedestal_width is None else float(np.asarray(pedestal_width, float).ravel()[0]))
    if stack.n < 2:
        raise ValueError("blocks: the two-face design needs a pedestal and a statue (at least two blocks)")
    motions = dict(motions)
    if not motions:
        raise ValueError("friction_design needs at least one motion")
    floor_face, top_face = stack.interfaces[0].friction, stack.interfaces[1].friction
    if floor_face is None:
        raise ValueError("interfaces[0].friction: the floor face must be able to slip (its friction is designed)")
    mus = _grid_values(mu_s, "mu_s", positive=False)
    kin = _kinetic(mus, mu_k, mu_k_ratio, floor_face, ("mu_k", "mu_k_ratio"))
    if mu_s_top is None:
        if mu_k_top is not None or mu_k_top_ratio is not None:
            raise ValueError("mu_k_top and mu_k_top_ratio need mu_s_top (the statue–pedestal face's μs)")
        mus_top = np.array([math.inf if top_face is None else top_face.static])
        kin_top = np.array([math.inf if top_face is None else (top_face.kinetic if top_face.kinetic is not None
                                                              else top_face.static)])
    else:
        mus_top = _grid_values(mu_s_top, "mu_s_top", positive=False)
        kin_top = _kinetic(mus_top, mu_k_top, mu_k_top_ratio, top_face, ("mu_k_top", "mu_k_top_ratio"))
    pedestal = stack.blocks[0]
    masses = _grid_values(pedestal_mass if pedestal_mass is not None else [pedestal.mass], "pedestal_mass",
                          positive=True)
    widths = _grid_values(pedestal_width if pedestal_width is not None else [pedestal.width], "pedestal_width",
                          positive=True)
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}")
    scatter = _check_scatter(friction_scatter)
    for name, v in (("sliding_limit", sliding_limit), ("residual_limit", residual_limit),
                    ("top_friction_limit", top_friction_limit)):
        if v is not None and not (math.isfinite(v) and v >= 0):
            raise ValueError(f"{name} must be a number >= 0, got {v!r}")
    if not free_time >= 0:
        raise ValueError(f"free_time must be >= 0, got {free_time!r}")
    given_top_limit = _check_top_sliding_limit(top_sliding_limit)
    on_top = stack.blocks[1]
    top_limits = (default_top_sliding_limit(widths, on_top.width, on_top.offset) if given_top_limit is None
                  else np.full(widths.shape, given_top_limit))
    top_limit_text = top_sliding_limit_text(widths, top_limits, default=given_top_limit is None)

    # The faces are different surfaces and age apart: the levels where they drift in opposite
    # directions are the worst for the statue's slide on top (top slipperier, floor gripping
    # harder) and for the free space on the floor (the reverse). Without a top face that slips
    # those levels would repeat the others, so they are not run.
    top_slips = bool(np.isfinite(mus_top).all())
    levels = two_face_levels(scatter, top_slips=top_slips)
    shape_c = (mus.size, masses.size, mus_top.size, widths.size)
    candidates = {}
    for (i, j, k, w) in np.ndindex(*shape_c):
        for q, (f_floor, f_top) in enumerate(levels):
            floor = Friction(static=float(mus[i]) * f_floor, kinetic=float(kin[i]) * f_floor)
            top = None if math.isinf(mus_top[k]) else Friction(static=float(mus_top[k]) * f_top,
                                                                kinetic=float(kin_top[k]) * f_top)
            blocks = (dataclasses.replace(pedestal, mass=float(masses[j]), width=float(widths[w])),) + stack.blocks[1:]
            faces = (dataclasses.replace(stack.interfaces[0], friction=floor),
                     dataclasses.replace(stack.interfaces[1], friction=top)) + stack.interfaces[2:]
            candidates[i, j, k, w, q] = Stack(blocks=blocks, interfaces=faces)
    runs = [Run(candidates[key], name) for name in motions for key in np.ndindex(*shape_c, len(levels))]
    options = dataclasses.replace(options, free_time_limit=float(free_time))
    floor_factors = [f for f, _ in levels]
    top_factors = [f for _, f in levels]
    meta = {"mu_s": mus.tolist(), "mu_k": kin.tolist(), "pedestal_mass": masses.tolist(),
            "mu_s_top": mus_top.tolist(), "mu_k_top": kin_top.tolist(), "pedestal_width": widths.tolist(),
            "motions": list(motions), "floor_factor": floor_factors, "top_factor": top_factors, "engine": "stack"}
    # A folder of an earlier study (its levels were other runs) is refused by the store, whose
    # fingerprint covers every run: never mixed with these levels.
    raw = run_stored(runs, motions, options=options, study="design", folder=folder, fresh=fresh, workers=workers,
                     chunk_size=chunk_size, progress=progress, meta=meta)
    statue = stack.blocks[-1]
    alpha = math.atan2(statue.width, statue.height)
    cand = TWO_FACE_CANDIDATE
    run_dims = cand + ("motion", "friction_level")
    every = specs_dataset(raw, [r.system for r in runs], dims=("motion",) + cand + ("friction_level",),
                          shape=(len(motions),) + shape_c + (len(levels),))
    every = every.transpose(*run_dims, ...)
    ds = every.isel(friction_level=levels.index((1.0, 1.0)), drop=True)
    names = [_two_face_level_name(f, g, top_slips=top_slips) for f, g in levels]
    ds = ds.assign_coords(mu_s=mus, pedestal_mass=masses, mu_s_top=mus_top, pedestal_width=widths,
                          motion=list(motions), friction_level=names,
                          floor_factor=("friction_level", floor_factors), top_factor=("friction_level", top_factors))
    ds["mu_s"].attrs["long_name"] = "static friction of the pedestal on the floor"
    ds["mu_s_top"].attrs["long_name"] = "static friction of the statue on the pedestal (inf: never slips)"
    ds["pedestal_mass"].attrs["units"] = "kg"
    ds["pedestal_width"].attrs["units"] = "m"
    ds["friction_level"].attrs["long_name"] = "friction level of the two faces (the scatter, together and apart)"
    ds["floor_factor"].attrs["long_name"] = "floor-face friction (μs and μk) over its nominal value"
    ds["top_factor"].attrs["long_name"] = ("top-face friction (μs and μk) over its nominal value (moot where the "
                                           "top face never slips)")

    status = every.status.values.astype(str)
    over = every.block_overturned.any("block").values | (status == "overturned")
    slid = (status == "slid_past_edge") & ~over
    unproven = ((status != "completed") | every.still_moving.values) & ~_settled(every)
    undetermined = ~over & ~slid & unproven
    rot = np.where(over, math.pi / (2.0 * alpha), every.peak_rotation_over_alpha.values)
    floor_slide = every.block_peak_sliding.isel(block=0).values
    top_slide = every.block_peak_sliding.isel(block=1).values
    ped_rot = every.block_peak_rotation.isel(block=0).values
    resid = np.abs(every.block_residual_sliding.isel(block=0).values)
    top_needed = every.interface_required_friction.isel(interface=1).values
    top = np.where(over, np.nan, top_needed)
    ds["scatter_overturned"] = (run_dims, over, {"long_name": "a block overturned"})
    ds["scatter_slid_off"] = (run_dims, slid, {"long_name": "a block slid to the edge of the one below (stopped)"})
    ds["scatter_undetermined"] = (run_dims, undetermined, {
        "long_name": ("nothing fell nor slid off, but the run did not end at rest (still moving with energy enough "
                      "to overturn, or it stopped)")})
    ds["scatter_peak_rotation_over_alpha"] = (run_dims, rot)
    ds["scatter_peak_sliding"] = (run_dims, floor_slide, {"units": "m"})
    ds["scatter_floor_sliding"] = (run_dims, floor_slide, {"units": "m", "long_name": "pedestal on the floor"})
    ds["scatter_top_sliding"] = (run_dims, top_slide, {"units": "m", "long_name": "statue on the pedestal"})
    ds["scatter_pedestal_rotation"] = (run_dims, ped_rot, {"units": "rad"})
    ds["scatter_residual_sliding"] = (run_dims, every.block_residual_sliding.isel(block=0).values, {"units": "m"})
    ds["scatter_required_top_friction"] = (run_dims, top_needed)

    falls = over.any(axis=-1)
    slid_off = slid.any(axis=-1) & ~falls
    unsure = undetermined.any(axis=-1) & ~falls & ~slid_off
    rot_env = rot.max(axis=-1)
    clearance = floor_slide.max(axis=-1)
    top_env = top_slide.max(axis=-1)
    n_c = len(cand)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN: every run overturns the statue
        top_max = np.nanmax(top.reshape(*top.shape[:n_c], -1), axis=-1)
    resid_max = resid.reshape(*resid.shape[:n_c], -1).max(axis=-1)
    ds["mu_k"] = (("mu_s",), kin)
    ds["mu_k_top"] = (("mu_s_top",), kin_top)
    ds["falls"] = (cand + ("motion",), falls, {"long_name": "a block overturns at some friction level"})
    ds["slid_off"] = (cand + ("motion",), slid_off, {
        "long_name": "a block slides to the edge of the one below at some friction level (a fall risk)"})
    ds["undetermined"] = (cand + ("motion",), unsure, {
        "long_name": "no fall, but some friction level leaves the stack moving at the end (or the run stopped)"})
    ds["clearance"] = (cand + ("motion",), clearance, {
        "units": "m", "long_name": "free space the pedestal needs: largest peak sliding on the floor over the levels"})
    ds["top_sliding"] = (cand + ("motion",), top_env, {
        "units": "m", "long_name": "largest peak sliding of the statue on the pedestal over the levels"})
    ds["overturn_count"] = (cand, falls.sum(axis=-1).astype(np.int64))
    ds["slid_off_count"] = (cand, slid_off.sum(axis=-1).astype(np.int64))
    ds["undetermined_count"] = (cand, unsure.sum(axis=-1).astype(np.int64))
    ds["overturn_rate"] = (cand, falls.mean(axis=-1))
    ds["peak_rotation_ratio_mean"] = (cand, rot_env.mean(axis=-1))
    ds["peak_rotation_ratio_median"] = (cand, np.median(rot_env, axis=-1))
    ds["peak_rotation_ratio_max"] = (cand, rot_env.max(axis=-1))
    ds["peak_sliding_max"] = (cand, clearance.max(axis=-1), {"units": "m"})
    ds["top_sliding_max"] = (cand, top_env.max(axis=-1), {"units": "m"})
    ds["top_sliding_limit"] = (("pedestal_width",), top_limits, {
        "units": "m", "long_name": "largest peak slide of the statue on the pedestal's top face a candidate may need"})
    ds["pedestal_rotation_max"] = (cand, ped_rot.reshape(*shape_c, -1).max(axis=-1), {"units": "rad"})
    ds["residual_sliding_max"] = (cand, resid_max, {"units": "m"})
    ds["required_top_friction_max"] = (cand, top_max, {
        "long_name": "largest friction the statue-pedestal face needed (runs without overturning)"})
    score = _stat(rot_env, objective)

    def describe(ij: tuple[int, ...]) -> str:
        i, j, k, w = ij
        top_text = ("top face never slips" if math.isinf(mus_top[k])
                    else f"top μs = {mus_top[k]:.3g} (μk = {kin_top[k]:.3g})")
        return (f"floor μs = {mus[i]:.3g} (μk = {kin[i]:.3g}), {top_text}, pedestal mass {masses[j]:g} kg, "
                f"width {widths[w]:g} m")

    below = stack.names[0]
    choice = choose_design(
        mu_s=mus, mu_k=kin, pedestal_mass=masses, motions=list(motions), falls=falls, undetermined=unsure,
        clearance=clearance, residual=resid_max, top_friction=top_max, score=score, objective=objective,
        sliding_limit=sliding_limit, residual_limit=residual_limit, top_friction_limit=top_friction_limit,
        friction_scatter=scatter, tan_alpha=math.tan(alpha),
        extra_axes=(("mu_s_top", mus_top), ("pedestal_width", widths)), describe=describe, slid_off=slid_off,
        slid_off_text=(f"the {stack.names[1]} slides to the edge of the {below}" if stack.n == 2
                       else "a block slides to the edge of the one below"),
        subject="pedestal faces",
        top_sliding=top_env.max(axis=-1), top_sliding_limit=top_limits,
        top_sliding_limit_text=top_limit_text if np.isfinite(top_limits).any() else None,
        scatter_text=_two_face_band(scatter, top_slips=top_slips),
    )
    work = ""
    shown = choice.recommended if choice.recommended is not None else choice.fewest_overturns
    if shown is not None:
        stands = ~over[shown]
        work = face_work(float(floor_slide[shown].max()), float(top_slide[shown].max()),
                         float(rot[shown][stands].max()) if stands.any() else 0.0, float(ped_rot[shown].max()))
        which = "the recommended design" if choice.recommended is not None else "the candidate with the fewest falls"
        over_what = "motions and friction levels" if len(levels) > 1 else "motions"
        lines = list(choice.lines)
        lines.insert(_after_recommendation(lines),
                     f"Which face does the work, for {which} (largest over the {over_what}): {work}.")
        choice = dataclasses.replace(choice, lines=tuple(lines))
    ds["safe"] = (cand, choice.safe, {
        "long_name": ("nothing falls or slides off, and every run ends at rest (or with too little energy left to "
                      "overturn), under every motion at every level")})
    ds["feasible"] = (cand, choice.feasible, {
        "long_name": "meets the sliding, residual, top-friction and top-sliding limits"})
    ds["inverted"] = (("mu_s",), choice.inverted, {
        "long_name": "floor-face μs·(1 + s) at or above top_friction_limit"})
    ds["score"] = (cand, score, {"long_name": f"{objective} peak θ/α over the motions"})
    rec = np.zeros(choice.safe.shape, dtype=bool)
    if choice.recommended is not None:
        rec[choice.recommended] = True
    ds["recommended"] = (cand, rec)
    ds.attrs.update(
        study="friction design",
        engine="stack",
        alpha=alpha,
        tan_alpha=math.tan(alpha),
        objective=objective,
        sliding_limit=np.nan if sliding_limit is None else float(sliding_limit),
        residual_limit=np.nan if residual_limit is None else float(residual_limit),
        top_friction_limit=np.nan if top_friction_limit is None else float(top_friction_limit),
        top_sliding_limit=np.nan if given_top_limit is None else given_top_limit,
        top_sliding_limit_text=top_limit_text,
        friction_scatter=scatter,
        free_time=float(free_time),
        gravity=float(options.gravity),
        statue_width=statue.width,
        statue_height=statue.height,
        statue_mass=statue.mass,
        pedestal_height=pedestal.height,
        blocks="\n".join(stack.names),
        face_work=work,
        **choice.attrs(),
    )
    return ds



CANDIDATE_COLUMNS = (
    "mu_k", "safe", "overturn_count", "undetermined_count", "overturn_rate", "peak_rotation_ratio_mean",
    "peak_rotation_ratio_median", "peak_rotation_ratio_max", "peak_sliding_max", "residual_sliding_max",
    "required_top_friction_max", "feasible", "inverted", "score", "recommended",
)


#: The columns a two-face design (:func:`two_face_design`) adds.
TWO_FACE_COLUMNS = ("mu_k_top", "slid_off_count", "top_sliding_max", "top_sliding_limit", "pedestal_rotation_max")


def _candidate_dims(ds) -> tuple[str, ...]:
    return tuple(d for d in TWO_FACE_CANDIDATE if d in ds.dims)


def candidate_table(ds):
    """One row per candidate (μs, pedestal mass; and top μs, pedestal width for a two-face design)
    with the aggregated results (a pandas DataFrame).

    The results are the worst over the friction levels μs·(1 − s), μs, μs·(1 + s) (a two-face
    design: over its ``friction_level``, both faces together and apart);
    ``peak_sliding_max`` is the free space the pedestal needs (m)."""
    columns = list(CANDIDATE_COLUMNS) + (list(TWO_FACE_COLUMNS) if "mu_s_top" in ds.dims else [])
    table = ds[columns].to_dataframe().reset_index()
    for column in ("mu_k", "mu_k_top"):
        if column in table:
            table[column] = _clean(table[column])
    return table[[*_candidate_dims(ds), *columns]]


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
            at = {d: a[f"{prefix}_{d}"] for d in _candidate_dims(ds)}
            break
    if shown is not None and "mu_s_top" in ds.dims:
        lines += _faces_per_motion(ds, at, shown[2])
    elif shown is not None:
        sel = ds.sel(mu_s=shown[0], pedestal_mass=shown[1])
        factors = [float(f) for f in ds.friction_factor.values]
        lines += [f"## Free space per motion, for {shown[2]} (μs = {shown[0]:.3g}, pedestal mass {shown[1]:g} kg)", "",
                  "The largest peak sliding of the pedestal under each motion, "
                  + (f"over the friction levels {_levels_text(factors, [True] * len(factors))}" if len(factors) > 1
                     else "at the nominal friction")
                  + f". Overall: **{_mm(float(sel.clearance.max()))}**.",
                  "", "| motion | free space (mm) | statue |", "|---|---|---|"]
        for k, motion in enumerate(ds.motion.values):
            over = sel.scatter_overturned.values[k]
            unsure = sel.scatter_undetermined.values[k]
            tips = (np.isfinite(sel.scatter_pedestal_uplift_time.values[k]) if "scatter_pedestal_uplift_time" in sel
                    else np.zeros(over.shape, bool))
            if over.any():
                state = f"falls at {_levels_text(factors, over)}"
            elif tips.any():
                state = (f"stands, but the pedestal would tip at {_levels_text(factors, tips)} (a fall risk this "
                         "model does not follow)")
            elif unsure.any():
                state = f"undetermined at {_levels_text(factors, unsure)} ({_UNDETERMINED_WHY})"
            else:
                state = "stands"
            lines.append(f"| {motion} | {_mm_cell(float(sel.clearance.values[k]))} | {state} |")
        lines.append("")
    lines += ["## Inputs and rules", ""]
    if "mu_s_top" in ds.dims:
        lines += _two_face_inputs(ds)
    else:
        lines.append(
            f"Statue {a['statue_width']:g} m × {a['statue_height']:g} m, {a['statue_mass']:g} kg "
            f"(α = {a['alpha']:.4f} rad, tan α = {a['tan_alpha']:.3f}); {n_mot} motion(s); "
            f"{ds.sizes['mu_s']} × {ds.sizes['pedestal_mass']} candidate(s) (μs × pedestal mass)."
        )
    if s > 0 and "mu_s_top" in ds.dims:
        lines.append(_two_face_scatter_line(ds, s))
    elif s > 0:
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
    if "top_sliding_limit_text" in a:
        rule = "" if math.isfinite(a["top_sliding_limit"]) or "inf" in a["top_sliding_limit_text"] else \
            " (the default: design.top_sliding_limit not given)"
        limits.append(a["top_sliding_limit_text"] + rule)
    lines.append(f"Limits: {', '.join(limits) if limits else 'none'}.")
    two = "mu_s_top" in ds.dims
    top_slips = not two or _top_slips(ds)
    lines.append(f"Ranking: {ranking_rule(s, a['objective'], two_face=two, top_slips=top_slips)} (docs/studies.md).")
    if "mu_s_top" in ds.dims:
        lines += _two_face_candidates(ds, n_mot)
        if chart:
            lines += ["", f"![design chart]({chart})"]
        return "\n".join(lines) + "\n"
    lines += ["", "## Candidates", "",
              "| μs | μk | pedestal mass (kg) | safe | falls | undetermined | peak θ/α mean | peak θ/α max | "
              "free space (mm) | residual (mm) | required top μ | meets limits |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for _, row in candidate_table(ds).iterrows():
        mark = " ⟵" if row["recommended"] else ""
        warn = " ⚠" if row["inverted"] else ""
        tipping = int(ds.pedestal_tips_count.sel(mu_s=row["mu_s"], pedestal_mass=row["pedestal_mass"])) \
            if "pedestal_tips_count" in ds else 0
        safe_text = _fmt(bool(row["safe"])) + (f" (the pedestal tips under {tipping}/{n_mot})" if tipping else "")
        lines.append(
            f"| {_fmt(row['mu_s'])}{mark}{warn} | {_fmt(row['mu_k'])} | {_fmt(row['pedestal_mass'])} | "
            f"{safe_text} | {int(row['overturn_count'])}/{n_mot} | "
            f"{int(row['undetermined_count'])}/{n_mot} | {_fmt(row['peak_rotation_ratio_mean'])} | "
            f"{_fmt(row['peak_rotation_ratio_max'])} | {_mm_cell(row['peak_sliding_max'])} | "
            f"{_mm_cell(row['residual_sliding_max'])} | {_fmt(row['required_top_friction_max'])} | "
            f"{_fmt(bool(row['feasible']))} |"
        )
    lines += ["", "⟵ recommended; ⚠ μs·(1 + s) at or above the statue–pedestal face's friction (inverts the concept). "
              "An overturn counts as θ/α = π/(2α) in the statistics of the peak rotation. The free space is the "
              "largest peak sliding of the pedestal; the required top friction is the largest |F|/N at the statue–pedestal "
              "face over the runs the statue survives."]
    if chart:
        lines += ["", f"![design chart]({chart})"]
    return "\n".join(lines) + "\n"


def _top_text(mu: float) -> str:
    return "never slips" if math.isinf(mu) else f"{mu:.3g}"


def _faces_per_motion(ds, at: Mapping[str, float], what: str) -> list[str]:
    """The report's table of a two-face design: per motion, the slide on each face, the statue's
    rotation and its fate, for the candidate ``at`` (its coordinates)."""
    sel = ds.sel(**at)
    n_levels = ds.sizes["friction_level"]
    levels = f"over the {n_levels} friction levels" if n_levels > 1 else "at the nominal friction"
    below, above = (ds.attrs.get("blocks", "pedestal\nstatue").split("\n") + ["statue"])[:2]
    room = float(sel.top_sliding_limit) if "top_sliding_limit" in sel else math.inf
    room_text = f", limit {_mm_limit(room)}" if math.isfinite(room) else ""
    out = [f"## Which face does the work, per motion, for {what} (floor μs = {at['mu_s']:.3g}, top μs = "
           f"{_top_text(at['mu_s_top'])}, pedestal {at['pedestal_mass']:g} kg, {at['pedestal_width']:g} m wide)", "",
           f"The largest peak sliding of the {below} on the floor (the free space it needs) and of the {above} on "
           f"the {below}'s top face under each motion, {levels}; the statue's peak θ/α where it stands. Overall: "
           f"**{_mm(float(sel.clearance.max()))}** on the floor, **{_mm(float(sel.top_sliding.max()))}** "
           "on the top face.", "",
           f"| motion | floor face (mm) | top face (mm{room_text}) | statue peak θ/α | pedestal rocks | statue |",
           "|---|---|---|---|---|---|"]
    for k, motion in enumerate(ds.motion.values):
        over = sel.scatter_overturned.values[k]
        slid = sel.scatter_slid_off.values[k]
        unsure = sel.scatter_undetermined.values[k]
        if over.any():
            state = f"falls at {_named_levels(ds, over)}"
        elif slid.any():
            state = f"slides to the edge of the {below} at {_named_levels(ds, slid)} (a fall risk)"
        elif unsure.any():
            state = f"undetermined at {_named_levels(ds, unsure)} ({_UNDETERMINED_WHY})"
        else:
            state = "stands"
        rot = sel.scatter_peak_rotation_over_alpha.values[k]
        rocks = "yes" if float(sel.scatter_pedestal_rotation.values[k].max()) > 0 else "no"
        on_top = float(sel.top_sliding.values[k])
        over_room = " ⚠ over the limit" if on_top > room else ""
        out.append(f"| {motion} | {_mm_cell(float(sel.clearance.values[k]))} | "
                   f"{_mm_cell(on_top)}{over_room} | "
                   f"{_fmt(float(rot[~over].max())) if (~over).any() else '–'} | {rocks} | {state} |")
    return out + [""]


def _named_levels(ds, hit: Sequence[bool]) -> str:
    """The friction levels of a two-face design where ``hit`` holds, by name ('every friction
    level' when that is all of several)."""
    hit = np.asarray(hit, dtype=bool)
    if hit.size > 1 and hit.all():
        return "every friction level"
    return ", ".join(str(name) for name, h in zip(ds.friction_level.values, hit) if h)


def _top_slips(ds) -> bool:
    """Whether the top face of a two-face design may slip (its μs is finite)."""
    return bool(np.isfinite(ds.mu_s_top.values).all())


def _two_face_scatter_line(ds, s: float) -> str:
    """The report's line on the friction levels a two-face design ran."""
    if not _top_slips(ds):
        return (f"Friction scatter s = {s:g}: the top face never slips, so every candidate also runs with the "
                "floor face's μs and μk times (1 − s) and (1 + s), and every result below is the worst of the three "
                "levels.")
    return (f"Friction scatter s = {s:g}: the two faces are different surfaces and age apart, so every candidate "
            f"also runs with both faces at μs·(1 ± s) together and in opposite directions (μk alike): "
            f"{', '.join(str(v) for v in ds.friction_level.values[1:])}; every result below is the worst of the "
            f"five levels.")


def _two_face_inputs(ds) -> list[str]:
    a = ds.attrs
    n = [ds.sizes[d] for d in TWO_FACE_CANDIDATE]
    return [f"Stack engine (the statue may slip on the pedestal, the pedestal may slide, rock and lift): blocks "
            f"{', '.join(str(a.get('blocks', '')).split(chr(10)))} from the floor up; statue {a['statue_width']:g} m × "
            f"{a['statue_height']:g} m, {a['statue_mass']:g} kg (α = {a['alpha']:.4f} rad, tan α = "
            f"{a['tan_alpha']:.3f}); pedestal {a['pedestal_height']:g} m high; {ds.sizes['motion']} motion(s); "
            f"{' × '.join(str(k) for k in n)} candidate(s) (floor μs × pedestal mass × top μs × pedestal width)."]


def _two_face_candidates(ds, n_mot: int) -> list[str]:
    out = ["", "## Candidates", "",
           "| floor μs | μk | top μs | top μk | pedestal mass (kg) | width (m) | safe | falls | slides off | "
           "undetermined | peak θ/α mean | peak θ/α max | floor slide (mm) | top slide (mm) | top limit (mm) | "
           "residual (mm) | required top μ | meets limits |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for _, row in candidate_table(ds).iterrows():
        mark = " ⟵" if row["recommended"] else ""
        out.append(
            f"| {_fmt(row['mu_s'])}{mark} | {_fmt(row['mu_k'])} | {_top_text(row['mu_s_top'])} | "
            f"{_top_text(row['mu_k_top'])} | {_fmt(row['pedestal_mass'])} | {_fmt(row['pedestal_width'])} | "
            f"{_fmt(bool(row['safe']))} | {int(row['overturn_count'])}/{n_mot} | {int(row['slid_off_count'])}/{n_mot} | "
            f"{int(row['undetermined_count'])}/{n_mot} | {_fmt(row['peak_rotation_ratio_mean'])} | "
            f"{_fmt(row['peak_rotation_ratio_max'])} | {_mm_cell(row['peak_sliding_max'])} | "
            f"{_mm_cell(row['top_sliding_max'])} | {_mm_cell(row['top_sliding_limit'])} | "
            f"{_mm_cell(row['residual_sliding_max'])} | "
            f"{_fmt(row['required_top_friction_max'])} | {_fmt(bool(row['feasible']))} |")
    return out + ["", "⟵ recommended. Safe: under every motion at every friction level no block falls, none slides to "
                  "the edge of the block below (where the stack engine stops: a fall risk), and every run ends at "
                  "rest. An overturn counts as θ/α = π/(2α) in the statistics of the peak rotation. The floor slide "
                  "is the free space the pedestal needs; the top slide is the statue's on the pedestal, within the top "
                  "limit for the candidate to meet the limits; the required "
                  "top friction is the largest |F|/N the top face needed over the runs nothing fell."]


def plot_design(ds, *, panel_size: tuple[float, float] = (5.0, 4.4)):
    """The design chart: per candidate panel, three axes against the floor μs (peak θ/α, the rate
    of falls, the peak sliding in mm; the worst over the friction levels of the scatter), with
    tan α, the limits, the recommended candidate and its scatter band [μs·(1 − s), μs·(1 + s)]
    marked, and one legend in a strip above the panels.

    A floor-face design has a panel per pedestal mass. A two-face design has a row per top-face
    μs (and mass) and a column per pedestal width, on shared axes; it also draws the statue's
    slide on the top face with its limit (per width) and counts slides to the edge with the falls.
    Returns the Figure."""
    from matplotlib.figure import Figure

    from ..viz.plots import plot_design_chart

    two = "mu_s_top" in ds.dims
    masses = ds.pedestal_mass.values
    rows = [{"pedestal_mass": m} for m in masses]
    cols = [{}]
    if two:
        rows = [{"pedestal_mass": m, "mu_s_top": t} for m in masses for t in ds.mu_s_top.values]
        cols = [{"pedestal_width": w} for w in ds.pedestal_width.values]
    fig = Figure(figsize=(panel_size[0] * len(cols) + 0.8, panel_size[1] * len(rows) + 1.4), layout="constrained")
    strip, grid = fig.subfigures(2, 1, height_ratios=(1.4, panel_size[1] * len(rows)))
    cells = np.atleast_2d(grid.subfigures(len(rows), len(cols), squeeze=False))
    stat = ds.attrs.get("objective", "mean")
    limit = ds.attrs.get("sliding_limit", np.nan)
    slides = [ds.peak_sliding_max.values, [limit]] + ([ds.top_sliding_max.values, ds.top_sliding_limit.values]
                                                     if two else [])
    finite = np.concatenate([np.ravel(np.asarray(v, dtype=float)) for v in slides])
    finite = finite[np.isfinite(finite)]
    sliding_max = 1.1e3 * float(finite.max()) if finite.size and finite.max() > 0 else 1.0
    rot_axes, handles = [], {}
    for r, row in enumerate(rows):
        for c, col in enumerate(cols):
            at = {**row, **col}
            sub = ds.sel(**at)
            rec = sub.recommended.values
            rate = (sub.falls | sub.slid_off).mean("motion").values if two else sub.overturn_rate.values
            axes = cells[r, c].subplots(3, 1, sharex=True, height_ratios=(1.5, 0.75, 1.75))
            ax = plot_design_chart(
                sub.mu_s.values, sub[f"peak_rotation_ratio_{stat}"].values, sub.peak_sliding_max.values, rate,
                axes=axes, legend=False, tan_alpha=ds.attrs.get("tan_alpha"),
                recommended=float(sub.mu_s.values[rec][0]) if rec.any() else None,
                friction_scatter=float(ds.attrs.get("friction_scatter", 0.0)),
                top_sliding=sub.top_sliding_max.values if two else None,
                rate_label="fall/edge rate" if two else "overturn rate", rotation_label=f"{stat} peak\n|θ|/α (–)",
                sliding_limit=limit if np.isfinite(limit) else None,
                top_sliding_limit=float(sub.top_sliding_limit) if two else None, sliding_max=sliding_max)
            rot_axes.append(ax)
            for handle in ax.design_handles:  # every entry of every panel, once
                handles.setdefault(handle.get_label(), handle)
            if c > 0:  # the rows share their y axes: one set of labels, on the left
                for a in (ax, ax.rate_ax, ax.sliding_ax):
                    a.set_ylabel("")
            if r < len(rows) - 1:
                ax.sliding_ax.set_xlabel("")
            head = f"pedestal mass {at['pedestal_mass']:g} kg" if len(masses) > 1 or not two else ""
            if two:
                head = ", ".join(filter(None, (f"top face μs {_top_text(float(at['mu_s_top']))}",
                                               f"width {at['pedestal_width']:g} m", head)))
            cells[r, c].suptitle(head, fontsize=9)
            cells[r, c].align_ylabels([ax, ax.rate_ax, ax.sliding_ax])
    for ax in rot_axes[1:]:
        first = rot_axes[0]
        for mine, theirs in ((ax, first), (ax.rate_ax, first.rate_ax), (ax.sliding_ax, first.sliding_ax)):
            mine.sharey(theirs)
    note = "" if ds.attrs.get("meets_every_requirement", 1) else "no candidate met every requirement\n"
    what = "both faces of the pedestal" if two else "the pedestal's floor friction"
    levels = "the friction levels of the scatter"
    if two and ds.sizes["friction_level"] > 1:
        levels = (f"the {ds.sizes['friction_level']} friction levels (both faces at μs·(1 ± s) together and in "
                  "opposite directions)" if _top_slips(ds) else
                  f"the {ds.sizes['friction_level']} friction levels (the floor face at μs·(1 ± s))")
    strip.suptitle(f"Friction design of {what}\n{note}each point: the worst over {levels}", fontsize=9.5)
    strip.legend(handles=list(handles.values()), loc="lower center", ncol=min(len(handles), 5 if len(cols) > 1 else 3),
                 fontsize=7.5, frameon=False)
    return fig
