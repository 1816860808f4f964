"""Overturning spectra: the smallest pulse (or harmonic) amplitude that overturns a block, against
the frequency, in the dimensionless form of Zhang & Makris (2001) and Dimitrakopoulos & DeJong
(2012): y = a_p/(g·tan α) against x = β = ω_p/p.

Overturning is not monotonic in the amplitude: above the first overturning amplitude there can
be *safe islands* (amplitudes at which the block survives again, e.g. because the stronger
pulse makes it impact earlier). At every frequency the amplitude axis is therefore scanned on a
geometric grid, and every change of outcome between two neighbouring grid points is bisected to
the relative tolerance ``rtol``. Islands narrower than one grid step can be missed; refine with
``n_scan``.

The motions, for an amplitude a_p = A·g·tan α and a circular frequency ω_p = β·p:

* ``"sine"``: one-sine pulse a_p·sin(ω_p t + ψ) on 0 ≤ t ≤ (2π − ψ)/ω_p; by default
  ψ = asin(1/A) so that rocking starts at t = 0 (oracle O9, Zhang & Makris's pulse);
  ``phase=0.0`` gives the plain one-sine;
* ``"cosine"``: one-cosine pulse a_p·cos(ω_p t) on 0 ≤ t ≤ 2π/ω_p (O9b);
* ``"ricker"``: Ricker wavelet with peak a_p and f = ω_p/2π, centred at 1.5/f;
* ``"harmonic"``: a_p·sin(ω_p t) (``form="sin"``) for ``cycles`` cycles.

Every run lasts the motion, then goes on with the floor still until the block is at rest or
falls, for at most ``free_time``/p (25 by default). A statue still rocking at that cap with less
energy than it needs to overturn (T + V < m₂·g·R·(1 − cos α) on the still floor, where the energy
can only fall) cannot fall: it counts as safe, in ``settling_runs`` (under ``"exceed"`` only if
it never passed α; the solver decides it, ``results.response.settled_by_energy``; a slender block rocking down
from near its overturn takes ~50/p and ~220 impacts to come to rest under Housner's
restitution). The same holds for a one-block stack; a taller stack has no such bound here. Any
other run still moving at the cap is undetermined, counted in
``undetermined_runs``; so is a run the solver stops before a verdict (too many events, a singular
or inconsistent contact mode, for stacks a lost contact or friction that gave energy), counted in
``failed_runs``. By default (``undetermined="fail"``) such a run counts as failing, as the design
and fragility studies count it: the boundary is then the smallest amplitude at which the block is
not shown to survive, never above the true one on the scanned grid. With ``undetermined="safe"``
it counts as safe, as before 2026-12-07: the boundary of the falls seen, which may lie above the
true one. Where what the run did settles the criterion anyway (an impact before the solver
stopped, under ``"no_impact"``; α passed, under ``"exceed"``), the run counts as it did. The
report and the command warn of both counts and say which way the boundary may move.

    >>> import rocking as rk
    >>> from rocking.analyses.spectra import overturning_spectrum
    >>> st = rk.Statue(width=0.3, height=1.5, mass=1.0)
    >>> ds = overturning_spectrum(rk.System(statue=st), "sine", [1.0, 2.0], workers=1)   # doctest: +SKIP
    >>> ds.amplitude_ratio.sel(pulse="sine").values                                      # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..excitation.harmonic import Harmonic
from ..excitation.pulses import CosinePulse, RickerPulse, SinePulse
from ..models.bodies import System
from ..results.response import IMPACT_BEYOND_FRICTION, LIFTED_OFF, status_of
from ..simulation import Options
from ..solver import compiled as C
from ..stack.model import Stack
from .store import ChunkStore, _version, chunk_ranges, fingerprint, run_chunks

__all__ = [
    "SHAPES",
    "CRITERIA",
    "SpectrumTask",
    "overturning_spectrum",
    "spectrum_motion",
    "island_bands",
    "block_text",
    "plot_spectra",
    "plot_spectra_overlay",
    "spectrum_report",
    "counted_as",
]

SHAPES = ("sine", "cosine", "ricker", "harmonic")
#: "overturn": any overturning counts; "no_impact": only overturning before the first impact
#: (mode 1 of Zhang & Makris); "exceed": |θ| reaching α (a quick, monotone-ish proxy).
CRITERIA = ("overturn", "no_impact", "exceed")
#: How a run without an outcome (still moving at the cap, or stopped by the solver) counts:
#: "fail" (conservative, the default), or "safe" (the falls seen only).
UNDETERMINED = ("fail", "safe")
_COUNTED = {"fail": "failing", "safe": "safe"}
MAX_ISLANDS = 16
MAX_EDGES = 2 * MAX_ISLANDS + 1


def spectrum_motion(
    shape: str,
    amplitude_ratio: float,
    frequency_ratio: float,
    *,
    g_tan_alpha: float,
    p: float,
    phase: float | str = "onset",
    cycles: float = 3.0,
) -> Any:
    """The floor motion of one point (A, β) of a spectrum (see the module docstring)."""
    a = float(amplitude_ratio) * g_tan_alpha
    omega = float(frequency_ratio) * p
    f = omega / (2.0 * math.pi)
    if shape == "sine":
        if phase == "onset":
            psi = math.asin(min(1.0, 1.0 / amplitude_ratio)) if amplitude_ratio > 0 else 0.0
        else:
            psi = float(phase)
        return SinePulse(amplitude=a, frequency=f, phase=psi)
    if shape == "cosine":
        return CosinePulse(amplitude=a, frequency=f)
    if shape == "ricker":
        return RickerPulse(amplitude=a, frequency=f)
    if shape == "harmonic":
        return Harmonic(amplitude=a, frequency=f, cycles=cycles, form="sin")
    raise ValueError(f"unknown spectrum motion {shape!r}; use one of {', '.join(SHAPES)}")


@dataclass(frozen=True)
class SpectrumTask:
    """Everything one worker needs to find the boundary at a few frequencies of one motion."""

    system: System | Stack
    shape: str
    frequency_ratios: tuple[float, ...]
    scan: tuple[float, ...]
    rtol: float
    criterion: str
    phase: float | str
    cycles: float
    free_time: float
    options: Options
    undetermined: str = "fail"


def _undecided(task: SpectrumTask, settled: bool) -> bool:
    """How a run without an outcome counts: failing under ``undetermined="fail"``, unless what it
    did before it stopped already settles the criterion (``settled``: it cannot fail any more)."""
    return task.undetermined == "fail" and not settled


def _fails(task: SpectrumTask, A: float, beta: float, g_tan_alpha: float, p: float, counter: list[int],
           options: Options) -> bool:
    """Does the block fail under amplitude ratio ``A`` at β? ``counter`` counts the runs, the
    solver failures and the undetermined (still moving) runs; ``options`` carry the free-motion
    cap."""
    from .batch import run_raw

    two_body = not isinstance(task.system, Stack)
    may_tip = two_body and task.system.pedestal is not None and task.system.pedestal.uplift_checked
    if A <= 1.0 and two_body and not may_tip:
        # |a_g| never exceeds g·tan α: nothing can start rocking (alone, or on a pedestal that
        # passes on at most μk·g < |a_g|), so there is nothing to simulate; a pedestal of given
        # width and height may tip below that, so it runs
        return task.criterion not in ("overturn", "no_impact", "exceed")
    motion = spectrum_motion(task.shape, A, beta, g_tan_alpha=g_tan_alpha, p=p, phase=task.phase, cycles=task.cycles)
    if isinstance(task.system, Stack):
        return _stack_fails(task, motion, counter, options)
    raw = run_raw(task.system, motion, options)
    counter[0] += 1
    status = int(raw[C.S_STATUS])
    if status == C.STATUS_INTERRUPTED:
        # cut short by a signal: not a result, and never to be saved in a chunk (see store._run_runs)
        raise KeyboardInterrupt("a run of the spectrum was interrupted")
    # a body that would leave its support while the statue stands ends what the two-body model
    # can tell (results.response.lift_off_time), an overturn after it too: as a pedestal that
    # would tip (below), a fall risk this model does not follow, failing under every criterion
    model_status = status_of(raw)[0]
    if model_status == LIFTED_OFF:
        counter[4 if not math.isnan(raw[C.S_UPLIFT]) else 5] += 1
        return True
    if model_status == IMPACT_BEYOND_FRICTION:
        # an impact held the block by more floor friction than there is (results.response.
        # held_impact_time): what follows is not a result, so, as a lift-off, not shown to stand
        counter[6] += 1
        return True
    impacted = int(raw[C.S_IMPACTS]) > 0
    if status in (C.STATUS_SINGULAR, C.STATUS_STEP_FAILED, C.STATUS_MAX_EVENTS):
        if task.criterion == "exceed" and not math.isnan(raw[C.S_EXCEED_TIME]):
            return True  # it had passed α before the solver stopped: that much is known
        counter[1] += 1
        return _undecided(task, task.criterion == "no_impact" and impacted)
    moving = status == C.STATUS_STILL_MOVING
    if moving and math.isnan(raw[C.S_UPLIFT]) and raw[C.S_SETTLED] == 1.0:
        # it rocks on, but cannot fall (nor reach α again): decided, safe, unless α was passed
        # before, which fails "exceed" whatever follows (a pedestal that would have tipped is a
        # fall risk whatever the energy: below)
        counter[7] += 1
        return task.criterion == "exceed" and not math.isnan(raw[C.S_EXCEED_TIME])
    if moving:
        counter[2] += 1
    if status != C.STATUS_OVERTURNED and not math.isnan(raw[C.S_UPLIFT]):
        # the pedestal would tip (derivation §3.5), which the two-body model does not follow:
        # a fall risk, failing under every criterion, as a stack block at the edge
        counter[4] += 1
        return True
    if task.criterion == "exceed":
        return not math.isnan(raw[C.S_EXCEED_TIME]) or (moving and _undecided(task, False))
    if moving:
        return _undecided(task, task.criterion == "no_impact" and impacted)
    overturned = status == C.STATUS_OVERTURNED
    if task.criterion == "no_impact":
        return overturned and not impacted
    return overturned


_STACK_SOLVER_FAILURES = ("inconsistent", "step_failed", "max_events", "lost_contact", "friction_gained")


def _stack_fails(task: SpectrumTask, motion: Any, counter: list[int], options: Options) -> bool:
    """:func:`_fails` for a stack: any block overturning (or sliding off) is an overturn, and, with
    ``options.stop_at_edge``, a block reaching the edge of the one below (``slid_past_edge``,
    where the run stops) a failure under every criterion (a fall risk), counted in ``counter[3]``."""
    from ..stack.simulate import simulate_stack
    from .batch import stack_alpha

    response = simulate_stack(task.system, motion, options=options)
    summary = response.summary()
    counter[0] += 1
    status = summary["status"]
    # an impact before the run stopped settles "no_impact" (no mode-1 fall any more), unless the
    # run went wrong before it ended (a lost contact, friction that gave energy): its late
    # impacts are not known to have happened
    impacted = summary["impacts"] > 0 and status not in ("lost_contact", "friction_gained")
    if status in _STACK_SOLVER_FAILURES:
        counter[1] += 1
        return _undecided(task, task.criterion == "no_impact" and impacted)
    moving = status == "still_moving"
    if moving and response.settled_by_energy:
        counter[7] += 1  # as in _fails: α passed before still fails "exceed"
        return task.criterion == "exceed" and summary["peak_rotation"] >= stack_alpha(task.system)
    if moving:
        counter[2] += 1
    if status == "slid_past_edge":
        counter[3] += 1
        return True
    overturned = status == "overturned"
    if task.criterion == "exceed":
        return (overturned or summary["peak_rotation"] >= stack_alpha(task.system)
                or (moving and _undecided(task, False)))
    if moving:
        return _undecided(task, task.criterion == "no_impact" and impacted)
    if task.criterion == "no_impact":
        return overturned and summary["impacts"] == 0
    return overturned


def statue_scales(system: System | Stack, gravity: float) -> tuple[float, float]:
    """(α in rad, p in 1/s) of the statue: a System's, or a stack's top block (p = √(m g R / I_O),
    I_O about a corner, from its inertia)."""
    if not isinstance(system, Stack):
        return system.statue.slenderness, system.statue.frequency_parameter(gravity)
    top = system.blocks[-1]
    radius = 0.5 * math.hypot(top.width, top.height)
    corner_inertia = top.centroidal_inertia + top.mass * radius**2
    return math.atan2(top.width, top.height), math.sqrt(top.mass * gravity * radius / corner_inertia)


def _bisect(fails: Callable[[float], bool], lo: float, hi: float, f_lo: bool, rtol: float) -> tuple[float, float]:
    """Narrow [lo, hi] (outcomes differ at the ends) to hi − lo ≤ rtol·hi."""
    while hi - lo > rtol * hi:
        mid = math.sqrt(lo * hi) if lo > 0 else 0.5 * (lo + hi)
        if fails(mid) == f_lo:
            lo = mid
        else:
            hi = mid
    return lo, hi


def _spectrum_chunk(task: SpectrumTask) -> dict[str, np.ndarray]:
    """Worker task: boundary, islands and scan at each frequency of ``task``."""
    g = task.options.gravity
    alpha, p = statue_scales(task.system, g)
    g_tan_alpha = g * math.tan(alpha)
    options = dataclasses.replace(task.options, free_time_limit=task.free_time / p)
    nf, ns = len(task.frequency_ratios), len(task.scan)
    out = {
        "lower": np.full(nf, np.nan),
        "upper": np.full(nf, np.nan),
        "island_lower": np.full((nf, MAX_ISLANDS), np.nan),
        "island_upper": np.full((nf, MAX_ISLANDS), np.nan),
        "n_islands": np.zeros(nf, dtype=np.int64),
        "edge_lower": np.full((nf, MAX_EDGES), np.nan),
        "edge_upper": np.full((nf, MAX_EDGES), np.nan),
        "edge_to_failure": np.zeros((nf, MAX_EDGES), dtype=bool),
        "truncated": np.zeros(nf, dtype=bool),
        "scan_fails": np.zeros((nf, ns), dtype=bool),
        "runs": np.zeros(nf, dtype=np.int64),
        "failed_runs": np.zeros(nf, dtype=np.int64),
        "undetermined_runs": np.zeros(nf, dtype=np.int64),
        "slid_off_runs": np.zeros(nf, dtype=np.int64),
        "pedestal_tips_runs": np.zeros(nf, dtype=np.int64),
        "lifted_off_runs": np.zeros(nf, dtype=np.int64),
        "impact_beyond_friction_runs": np.zeros(nf, dtype=np.int64),
        "settling_runs": np.zeros(nf, dtype=np.int64),
    }
    for k, beta in enumerate(task.frequency_ratios):
        counter = [0, 0, 0, 0, 0, 0, 0, 0]

        def fails(A: float, beta: float = beta) -> bool:
            return _fails(task, A, beta, g_tan_alpha, p, counter, options)

        scan = np.array([fails(A) for A in task.scan], dtype=bool)
        out["scan_fails"][k] = scan
        edges = []  # (boundary lo, boundary hi, becomes_failing)
        for j in np.flatnonzero(scan[1:] != scan[:-1]):
            lo, hi = _bisect(fails, task.scan[j], task.scan[j + 1], bool(scan[j]), task.rtol)
            edges.append((lo, hi, not scan[j]))
        for e, (lo, hi, to_failure) in enumerate(edges[:MAX_EDGES]):
            out["edge_lower"][k, e], out["edge_upper"][k, e], out["edge_to_failure"][k, e] = lo, hi, to_failure
        if scan[0]:  # fails already at the bottom of the scan: the boundary is below it
            out["upper"][k] = task.scan[0]
            out["truncated"][k] = True
            tail = edges
        else:
            first = next((i for i, e in enumerate(edges) if e[2]), None)
            if first is not None:
                out["lower"][k], out["upper"][k] = edges[first][0], edges[first][1]
            tail = edges[first + 1 :] if first is not None else []
        # after the first overturn, edges alternate: safe again (island starts), fails again (ends)
        n_isl = 0
        for i in range(0, len(tail), 2):
            start = tail[i]
            end = tail[i + 1] if i + 1 < len(tail) else None
            if n_isl < MAX_ISLANDS:
                out["island_lower"][k, n_isl] = 0.5 * (start[0] + start[1])
                out["island_upper"][k, n_isl] = 0.5 * (end[0] + end[1]) if end is not None else np.inf
            n_isl += 1
        out["n_islands"][k] = n_isl
        (out["runs"][k], out["failed_runs"][k], out["undetermined_runs"][k], out["slid_off_runs"][k],
         out["pedestal_tips_runs"][k], out["lifted_off_runs"][k], out["impact_beyond_friction_runs"][k],
         out["settling_runs"][k]) = counter
    return out


def _as_grid(values: Sequence[float] | np.ndarray, name: str) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values, dtype=float))
    if arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError(f"{name} must be positive finite numbers, got {values!r}")
    return arr


def overturning_spectrum(
    system: System,
    shapes: str | Sequence[str] = "sine",
    frequency_ratios: Sequence[float] | np.ndarray = tuple(np.round(np.geomspace(0.5, 8.0, 25), 6)),
    *,
    amplitude_range: tuple[float, float] = (1.01, 30.0),
    n_scan: int = 48,
    rtol: float = 1e-3,
    criterion: str = "overturn",
    phase: float | str = "onset",
    cycles: float = 3.0,
    free_time: float = 25.0,
    undetermined: str = "fail",
    options: Options = Options(),
    workers: int | Any | None = None,
    folder: str | os.PathLike[str] | None = None,
    fresh: bool = False,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
):
    """Minimum overturning amplitude a_p/(g tan α) against ω_p/p, with the safe islands above it.

    Parameters
    ----------
    system : System or Stack
        The statue, alone or on a pedestal; α and p = √(3g/4R) are the statue's. A
        :class:`rocking.stack.Stack` runs on the stack engine, its top block being the statue;
        any block overturning counts as an overturn, and (with ``options.stop_at_edge``) a block
        reaching the edge of the one below (``slid_past_edge``) as a failure under every
        criterion, counted in ``slid_off_runs``.
    shapes : str or sequence of str
        ``"sine"``, ``"cosine"``, ``"ricker"``, ``"harmonic"`` (see the module docstring).
    frequency_ratios : sequence of float
        β = ω_p/p.
    amplitude_range : (float, float)
        The scanned a_p/(g tan α). At or below 1 nothing can rock (no run is made there); just
        above 1 slender blocks chatter through thousands of tiny impacts, which is slow, hence
        the default lower end 1.01. A boundary below the range is flagged ``truncated``.
    n_scan : int
        Points of the geometric coarse scan (the islands it can see are wider than one step).
    rtol : float
        Relative width to which every change of outcome is bisected.
    criterion : {"overturn", "no_impact", "exceed"}
        What counts as failure (``"no_impact"``: overturning before any impact, mode 1).
    phase : "onset" or float
        Sine pulse phase ψ: ``"onset"`` = asin(1/A) (rocking starts at t = 0), or a fixed angle.
    cycles : float
        Cycles of the harmonic motion.
    free_time : float
        Longest free motion after the motion ends, in units of 1/p: the run ends earlier when the
        block is at rest or falls.
    undetermined : {"fail", "safe"}
        How a run without an outcome counts (still moving at the cap, or stopped by the solver):
        ``"fail"`` (the default, conservative: the boundary is the smallest amplitude at which
        the block is not shown to survive) or ``"safe"`` (the falls seen only: the boundary may
        lie above the true one). Either way the runs are counted in ``undetermined_runs`` and
        ``failed_runs``.
    options : Options
    workers : int, executor or Dask client
        As in :mod:`rocking.analyses.batch` (tasks are groups of frequencies).
    folder : path-like, optional
        Save every finished chunk there and resume from it (see :mod:`rocking.analyses.store`).
    fresh : bool
        Start afresh in a folder that holds other results.
    chunk_size : int, optional
        Frequencies per task (default: about 48 tasks in all).
    progress : callable, optional
        ``progress(done, total)`` in frequencies.

    Returns
    -------
    xarray.Dataset
        Dimensions ``pulse``, ``frequency_ratio``, ``island`` and ``scan``. Variables:
        ``amplitude_ratio`` (midpoint of the final bracket; NaN if nothing in range fails),
        ``amplitude_ratio_lower``/``_upper`` (the bracket), ``truncated`` (it already fails at
        the bottom of the range), ``island_lower``/``island_upper`` (safe islands above the
        boundary; ``inf`` = still safe at the top of the scan), ``n_islands``, every change of
        outcome found (``edge_lower``/``edge_upper`` brackets, ``edge_to_failure`` True where
        the block fails above it), ``scan_fails`` (the coarse scan), ``runs``,
        ``failed_runs`` (solver failures: max_events, singular, step_failed; for stacks also
        inconsistent, lost_contact and friction_gained), ``undetermined_runs`` (still moving at
        the free-motion cap; both counted as ``undetermined`` says), ``slid_off_runs`` (stacks only) and
        ``pedestal_tips_runs`` (a pedestal of given width and height would tip, which the
        two-body model does not follow: counted as failing under every criterion) and
        ``lifted_off_runs`` (a body would leave its support while the statue stands, status
        ``lifted_off``: counted as failing too) and ``impact_beyond_friction_runs`` (an impact
        needed more floor friction than μs and the two-body model held the block anyway, status
        ``impact_beyond_friction``: counted as failing too) and ``settling_runs`` (the two-body
        model or a one-block stack: still moving at the cap with less energy than the statue
        needs to overturn, so it cannot fall: counted as safe, and not as undetermined).

    Notes
    -----
    The boundary is the first change from safe to failing *that the scan sees*. Under harmonic
    motion (several cycles) the overturning region of a rocking block is ragged, with
    overturning slivers narrower than any practical scan step; refine ``n_scan`` to resolve
    more of them. Every reported bracket is exact: the block survives at its lower end and
    fails at its upper end (or the reverse for the end of an overturning region).
        Attributes: α, p, g, tan α and the settings.
    """
    import xarray as xr

    shapes = [shapes] if isinstance(shapes, str) else list(shapes)
    for s in shapes:
        if s not in SHAPES:
            raise ValueError(f"unknown spectrum motion {s!r}; use one of {', '.join(SHAPES)}")
    if len(set(shapes)) != len(shapes):
        raise ValueError(f"repeated motion in {shapes!r}")
    if criterion not in CRITERIA:
        raise ValueError(f"criterion must be one of {', '.join(CRITERIA)}, got {criterion!r}")
    if undetermined not in UNDETERMINED:
        raise ValueError(f"undetermined must be one of {', '.join(UNDETERMINED)}, got {undetermined!r}")
    betas = _as_grid(frequency_ratios, "frequency_ratios")
    lo, hi = (float(x) for x in amplitude_range)
    if not (0 < lo < hi and math.isfinite(hi)):
        raise ValueError(f"amplitude_range must be 0 < low < high, got {amplitude_range!r}")
    if int(n_scan) < 2:
        raise ValueError(f"n_scan must be >= 2, got {n_scan!r}")
    if not 0 < rtol < 1:
        raise ValueError(f"rtol must lie in (0, 1), got {rtol!r}")
    if not free_time >= 0:
        raise ValueError(f"free_time must be >= 0, got {free_time!r}")
    if phase != "onset" and not isinstance(phase, (int, float)):
        raise ValueError(f"phase must be 'onset' or a number, got {phase!r}")
    scan = tuple(float(x) for x in np.geomspace(lo, hi, int(n_scan)))
    size = int(chunk_size) if chunk_size else max(1, math.ceil(len(shapes) * betas.size / 48))

    tasks: list[SpectrumTask] = []
    index: list[tuple[int, range]] = []
    for si, shape in enumerate(shapes):
        for r in chunk_ranges(betas.size, size):
            tasks.append(
                SpectrumTask(system, shape, tuple(float(b) for b in betas[r.start : r.stop]), scan, float(rtol),
                             criterion, phase if phase == "onset" else float(phase), float(cycles),
                             float(free_time), options, undetermined)
            )
            index.append((si, r))
    store = None
    if folder is not None:
        fp = fingerprint({"study": "spectrum", "tasks": tasks, "version": _version()})
        meta = {"shapes": shapes, "frequency_ratios": betas.tolist(), "amplitude_range": [lo, hi],
                "n_scan": int(n_scan), "rtol": rtol, "criterion": criterion, "undetermined": undetermined}
        store = ChunkStore(folder, study="spectrum", fingerprint=fp, n_chunks=len(tasks), meta=meta, fresh=fresh)
    parts = run_chunks(_spectrum_chunk, tasks, store=store, workers=workers,
                       sizes=[len(t.frequency_ratios) for t in tasks], progress=progress)

    ns, nb = len(shapes), betas.size
    full: dict[str, np.ndarray] = {
        "lower": np.full((ns, nb), np.nan),
        "upper": np.full((ns, nb), np.nan),
        "island_lower": np.full((ns, nb, MAX_ISLANDS), np.nan),
        "island_upper": np.full((ns, nb, MAX_ISLANDS), np.nan),
        "n_islands": np.zeros((ns, nb), dtype=np.int64),
        "edge_lower": np.full((ns, nb, MAX_EDGES), np.nan),
        "edge_upper": np.full((ns, nb, MAX_EDGES), np.nan),
        "edge_to_failure": np.zeros((ns, nb, MAX_EDGES), dtype=bool),
        "truncated": np.zeros((ns, nb), dtype=bool),
        "scan_fails": np.zeros((ns, nb, len(scan)), dtype=bool),
        "runs": np.zeros((ns, nb), dtype=np.int64),
        "failed_runs": np.zeros((ns, nb), dtype=np.int64),
        "undetermined_runs": np.zeros((ns, nb), dtype=np.int64),
        "slid_off_runs": np.zeros((ns, nb), dtype=np.int64),
        "pedestal_tips_runs": np.zeros((ns, nb), dtype=np.int64),
        "lifted_off_runs": np.zeros((ns, nb), dtype=np.int64),
        "impact_beyond_friction_runs": np.zeros((ns, nb), dtype=np.int64),
        "settling_runs": np.zeros((ns, nb), dtype=np.int64),
    }
    for (si, r), part in zip(index, parts):
        for key, arr in full.items():
            if key in part:  # (a chunk saved before a counter existed has none of it: zeros)
                arr[si, r.start : r.stop] = part[key]
    used = int(max(1, full["n_islands"].max()))
    n_edges = int(max(1, np.isfinite(full["edge_lower"]).sum(axis=-1).max()))
    g = options.gravity
    alpha, p = statue_scales(system, g)
    mid = np.where(np.isnan(full["lower"]), full["upper"], 0.5 * (full["lower"] + full["upper"]))
    mid = np.where(full["truncated"], full["upper"], mid)
    dims = ("pulse", "frequency_ratio")
    ds = xr.Dataset(
        {
            "amplitude_ratio": (dims, mid, {"long_name": "minimum overturning a_p/(g tan α)"}),
            "amplitude_ratio_lower": (dims, full["lower"]),
            "amplitude_ratio_upper": (dims, full["upper"]),
            "truncated": (dims, full["truncated"]),
            "island_lower": (dims + ("island",), full["island_lower"][:, :, :used]),
            "island_upper": (dims + ("island",), full["island_upper"][:, :, :used]),
            "n_islands": (dims, full["n_islands"]),
            "edge_lower": (dims + ("edge",), full["edge_lower"][:, :, :n_edges]),
            "edge_upper": (dims + ("edge",), full["edge_upper"][:, :, :n_edges]),
            "edge_to_failure": (dims + ("edge",), full["edge_to_failure"][:, :, :n_edges]),
            "scan_fails": (dims + ("scan",), full["scan_fails"]),
            "runs": (dims, full["runs"]),
            "failed_runs": (dims, full["failed_runs"]),
            "undetermined_runs": (dims, full["undetermined_runs"], {
                "long_name": f"runs still moving at the free-motion cap (counted as {_COUNTED[undetermined]})"}),
            "slid_off_runs": (dims, full["slid_off_runs"], {
                "long_name": "stack runs where a block slid to the edge of the one below (counted as failing)"}),
            "pedestal_tips_runs": (dims, full["pedestal_tips_runs"], {
                "long_name": "runs where the pedestal would tip, which the two-body model does not follow "
                             "(counted as failing)"}),
            "lifted_off_runs": (dims, full["lifted_off_runs"], {
                "long_name": "runs where a body would leave its support while the statue stands, which the "
                             "two-body model does not follow (counted as failing)"}),
            "impact_beyond_friction_runs": (dims, full["impact_beyond_friction_runs"], {
                "long_name": "runs where an impact needed more floor friction than μs, which the two-body model's "
                             "impact law cannot give (counted as failing)"}),
            "settling_runs": (dims, full["settling_runs"], {
                "long_name": "runs still moving at the free-motion cap with less energy than the statue needs to "
                             "overturn (counted as safe: they cannot fall)"}),
        },
        coords={
            "pulse": np.array(shapes, dtype=str),
            "frequency_ratio": betas,
            "scan_amplitude_ratio": ("scan", np.array(scan)),
        },
        attrs={
            "study": "overturning spectrum",
            "alpha": alpha,
            "tan_alpha": math.tan(alpha),
            "p": p,
            "gravity": g,
            "restitution": _restitution(system),
            **_block_size(system),
            "pedestal": int(system.n > 1) if isinstance(system, Stack) else int(system.pedestal is not None),
            "engine": "stack" if isinstance(system, Stack) else "system",
            "criterion": criterion,
            "undetermined": undetermined,
            "rtol": float(rtol),
            "free_time": float(free_time),
            "cycles": float(cycles),
            "phase": str(phase),
        },
    )
    return ds


def _block_size(system: System | Stack) -> dict[str, float]:
    """The width and height (m) of the block whose spectrum this is: the statue, or the top block."""
    block = system.blocks[-1] if isinstance(system, Stack) else system.statue
    return {"block_width": float(block.width), "block_height": float(block.height)}


def _restitution(system: System | Stack) -> float:
    """The statue's r (NaN for a stack interface left to the plastic rule, which gives Housner's value)."""
    if isinstance(system, Stack):
        r = system.interfaces[-1].restitution
        return math.nan if r is None else float(r)
    return system.statue.effective_restitution


def island_bands(ds, pulse: str) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The safe islands of one motion as ``(frequency_ratio, lower, upper)`` bands for
    :func:`rocking.viz.plots.plot_spectrum` (NaN where an island is absent; an island open at
    the top is cut at the top of the scan)."""
    sub = ds.sel(pulse=pulse)
    top = float(ds.scan_amplitude_ratio.max())
    bands = []
    for j in range(ds.sizes.get("island", 0)):
        lo = sub.island_lower.isel(island=j).values
        hi = np.minimum(sub.island_upper.isel(island=j).values, top)
        if np.any(np.isfinite(lo)):
            bands.append((ds.frequency_ratio.values, lo, hi))
    return bands


_COLORS = {"sine": "#c0392b", "cosine": "#1f77b4", "ricker": "#2ca02c", "harmonic": "#8e44ad"}


def block_text(ds) -> str:
    """The block of a spectrum in words: its size, α, p and r (from the Dataset's attributes)."""
    a = ds.attrs
    size = (f"block {a['block_width']:g} m × {a['block_height']:g} m, " if "block_width" in a else "")
    r = a.get("restitution", math.nan)
    r_text = f"r = {r:.3g}" if math.isfinite(r) else "r by Housner's rule"
    where = " on a pedestal" if a.get("pedestal") else ""
    return f"{size}α = {a['alpha']:.3f} rad, p = {a['p']:.3f} 1/s, {r_text}{where}"


def plot_spectra(ds, *, title: str | None = None, panel_size: tuple[float, float] = (4.6, 3.4)):
    """One panel per motion (as in Zhang & Makris 2001), all on one y-range (the scanned
    a_p/(g tan α)): the boundary, the overturn region shaded, the safe islands hatched, and the
    frequencies where nothing overturned in the scanned range greyed and said so. One legend, in a
    strip above the panels. Returns the matplotlib Figure."""
    from matplotlib.figure import Figure

    from ..viz.plots import plot_spectrum

    pulses = ds.pulse.values.tolist()
    cols = 1 if len(pulses) == 1 else 2
    rows = math.ceil(len(pulses) / cols)
    fig = Figure(figsize=(panel_size[0] * cols, panel_size[1] * rows + 0.9), layout="constrained")
    strip, grid = fig.subfigures(2, 1, height_ratios=(0.9, panel_size[1] * rows))
    axes = grid.subplots(rows, cols, squeeze=False, sharex=True, sharey=True).ravel()
    top = float(ds.scan_amplitude_ratio.max())
    handles: dict[str, Any] = {}
    for ax, pulse in zip(axes, pulses):
        plot_spectrum(
            frequency_ratio=ds.frequency_ratio.values,
            amplitude_ratio=ds.amplitude_ratio.sel(pulse=pulse).values,
            safe_islands=island_bands(ds, pulse) or None,
            label="smallest overturning amplitude",
            ymax=top,
            scan_top=top,
            legend=False,
            ax=ax,
        )
        for handle in ax.spectrum_handles:
            handles.setdefault(handle.get_label(), handle)
        ax.set_title(_MOTION_TITLES.get(pulse, pulse), fontsize=9)
        ax.label_outer()
    for ax in axes[len(pulses):]:
        ax.set_visible(False)
    strip.suptitle(title or f"Overturning spectra: {block_text(ds)}", fontsize=10)
    strip.legend(handles=list(handles.values()), loc="lower center", ncol=min(len(handles), 3), fontsize=7.5,
                 frameon=False)
    return fig


_MOTION_TITLES = {"sine": "one-sine pulse", "cosine": "one-cosine pulse", "ricker": "Ricker wavelet",
                  "harmonic": "harmonic motion"}


def counted_as(ds) -> str:
    """How a spectrum counted its runs without an outcome, and where that may put its boundary
    (a dataset made before the ``undetermined`` option counted them as safe)."""
    if ds.attrs.get("undetermined", "safe") == "fail":
        return "counted as failing, so a boundary may lie higher than shown"
    return "counted as safe, so a boundary may lie lower than shown"


def spectrum_report(ds, *, title: str = "Overturning spectra", chart: str | None = "spectrum.png") -> str:
    """A Markdown report of a spectrum: the block and the inputs, the boundary a_p/(g tan α) per
    motion and frequency ratio (with its safe islands, and "no overturning in the scanned range"
    where nothing fell), the warnings, and the chart."""
    a = ds.attrs
    top = float(ds.scan_amplitude_ratio.max())
    low = float(ds.scan_amplitude_ratio.min())
    pulses = ds.pulse.values.tolist()
    what = {"overturn": "overturns", "no_impact": "overturns before its first impact (mode 1)",
            "exceed": "rotates past α"}.get(str(a["criterion"]), str(a["criterion"]))
    lines = [f"# {title}", "", f"**The smallest floor amplitude a_p/(g tan α) at which the block {what}, against "
             f"the frequency ratio β = ω_p/p, for {', '.join(_MOTION_TITLES.get(m, m) for m in pulses)}.**", "",
             f"{block_text(ds)[:1].upper()}{block_text(ds)[1:]}; engine: {a.get('engine', 'system')}. "
             f"Scanned a_p/(g tan α) from {low:.3g} to "
             f"{top:.3g}, bisected to a relative {a['rtol']:g}; each run goes on {a['free_time']:g}/p after the motion"
             + (f"; harmonic motion of {a['cycles']:g} cycles" if "harmonic" in pulses else "") + ".", ""]
    runs = int(ds.runs.sum())
    counted = counted_as(ds)
    unsure = int(ds.undetermined_runs.sum())
    if unsure:
        lines += [f"**{unsure} of {runs} runs were still moving at the end of their free motion: undetermined, "
                  f"{counted}.** Raise spectrum.free_time to decide them.", ""]
    settling = int(ds.settling_runs.sum()) if "settling_runs" in ds else 0
    if settling:
        lines += [f"{settling} of {runs} runs were still rocking at the end of their free motion with less energy than "
                  "the block needs to overturn (on the still floor it can only lose energy): safe, decided.", ""]
    failed = int(ds.failed_runs.sum()) if "failed_runs" in ds else 0
    if failed:
        lines += [f"**{failed} of {runs} runs were stopped by the solver before a verdict (too many events, or no "
                  f"consistent contact mode): {counted}.**", ""]
    slid = int(ds.slid_off_runs.sum())
    if slid:
        lines += [f"**In {slid} of {runs} runs a block slid to the edge of the one below, where the stack engine "
                  "stops: counted as failing (a fall risk).**", ""]
    tipping = int(ds.pedestal_tips_runs.sum()) if "pedestal_tips_runs" in ds else 0
    if tipping:
        lines += [f"**In {tipping} of {runs} runs the pedestal would tip (the floor's reaction left its base), which "
                  "this model does not follow: counted as failing (a fall risk).** A stack of blocks (the stack "
                  "engine) follows the pedestal's rocking.", ""]
    lifting = int(ds.lifted_off_runs.sum()) if "lifted_off_runs" in ds else 0
    if lifting:
        lines += [f"**In {lifting} of {runs} runs a body would leave its support while the statue stood (the "
                  "floor's or the statue's base force reached zero), which this model does not follow: counted as "
                  "failing (a fall risk).** A stack of blocks (the stack engine) follows the flight.", ""]
    held = int(ds.impact_beyond_friction_runs.sum()) if "impact_beyond_friction_runs" in ds else 0
    if held:
        lines += [f"**In {held} of {runs} runs an impact needed more floor friction than μs, which the two-body "
                  "model's impact law cannot give (it held the block anyway): counted as failing.** A restitution "
                  "well below Housner's does this on a low friction; a stack of blocks (the stack engine) solves "
                  "such impacts with friction at both corners.", ""]
    lines += ["## Boundary", "", "a_p/(g tan α) of the smallest amplitude that fails; \"none up to "
              f"{top:.3g}\": no overturning in the scanned range; ⁺: safe islands above the boundary (listed below).",
              "", "| β = ω_p/p | " + " | ".join(_MOTION_TITLES.get(m, m) for m in pulses) + " |",
              "|---|" + "---|" * len(pulses)]
    for k, beta in enumerate(ds.frequency_ratio.values):
        cells = []
        for pulse in pulses:
            value = float(ds.amplitude_ratio.sel(pulse=pulse).values[k])
            islands = int(ds.n_islands.sel(pulse=pulse).values[k])
            cells.append(f"none up to {top:.3g}" if not math.isfinite(value)
                         else f"{value:.3g}" + ("⁺" if islands else ""))
        lines.append(f"| {beta:.3g} | " + " | ".join(cells) + " |")
    island_rows = []
    for pulse in pulses:
        sub = ds.sel(pulse=pulse)
        for k, beta in enumerate(ds.frequency_ratio.values):
            spans = [f"{lo:.3g} – {min(hi, top):.3g}" + (" (open above the scan)" if not hi <= top else "")
                     for lo, hi in zip(sub.island_lower.values[k], sub.island_upper.values[k]) if math.isfinite(lo)]
            if spans:
                island_rows.append(f"| {_MOTION_TITLES.get(pulse, pulse)} | {beta:.3g} | {'; '.join(spans)} |")
    if island_rows:
        lines += ["", "## Safe islands", "", "Amplitudes above the boundary where the block survives again.", "",
                  "| motion | β | a_p/(g tan α) |", "|---|---|---|", *island_rows]
    if chart:
        lines += ["", f"![overturning spectra]({chart})"]
    return "\n".join(lines) + "\n"


def plot_spectra_overlay(ds, ax=None, *, title: str | None = None):
    """The boundaries of all motions of a spectrum dataset on one chart (islands hatched)."""
    from matplotlib.patches import Patch

    from ..viz.plots import plot_spectrum

    finite = ds.amplitude_ratio.values[np.isfinite(ds.amplitude_ratio.values)]
    top = 1.15 * float(finite.max()) if finite.size else float(ds.scan_amplitude_ratio.max())
    for pulse in ds.pulse.values.tolist():
        ax = plot_spectrum(
            frequency_ratio=ds.frequency_ratio.values,
            amplitude_ratio=ds.amplitude_ratio.sel(pulse=pulse).values,
            safe_islands=island_bands(ds, pulse) or None,
            label=f"{pulse}",
            color=_COLORS.get(pulse),
            shade=(len(ds.pulse) == 1),
            ymax=top,
            ax=ax,
        )
    handles = [ln for ln in ax.get_lines() if not ln.get_label().startswith("_")]
    if np.any(ds.n_islands.values > 0):
        handles.append(Patch(facecolor="white", edgecolor="0.3", hatch="///", label="safe island"))
    if len(ds.pulse) == 1:
        handles.append(Patch(facecolor="#f6c9c4", edgecolor="none", label="overturns"))
    ax.legend(handles=handles, loc="upper left", fontsize=7.5, framealpha=0.9)
    if title:
        ax.set_title(title, fontsize=9)
    return ax
