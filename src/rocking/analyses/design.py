"""Friction design of a pedestal: which floor-face friction (and pedestal mass) keeps the statue
quietest without letting the pedestal slide too far?

Every candidate (μs of the pedestal's floor face, with μk given or as a ratio of μs, and
optionally the pedestal mass) is run under every motion of a set (records scaled to a target
intensity, or a harmonic/pulse family). For each candidate the study reports, over the motions:

* the statue's peak θ/α (mean, median and maximum; an overturn counts as π/(2α));
* the number and rate of overturns;
* the pedestal's peak and residual sliding (maximum over the motions, m);
* ``required_top_friction``: the largest |F|/N the statue–pedestal face must supply (over the
  motions the statue survives), to compare with that face's friction.

The recommended candidate satisfies the limits (peak sliding ≤ ``sliding_limit``, e.g. the
free space around the pedestal; residual sliding ≤ ``residual_limit``; required top friction ≤
``top_friction_limit``) and, among those, has the fewest overturns and then the smallest
``objective`` statistic of the peak θ/α (ties: the smaller peak sliding, then the smaller μs).

    >>> ds = friction_design(system, motions, mu_s=[0.1, 0.2, 0.3], sliding_limit=0.05)   # doctest: +SKIP
    >>> ds.attrs["recommended_mu_s"]                                                         # doctest: +SKIP
"""

from __future__ import annotations

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

__all__ = ["OBJECTIVES", "candidate_table", "design_report", "friction_design", "motion_family", "plot_design"]

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
    free_time: float = 5.0,
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
    objective : {"mean", "median", "max"}
        Statistic of the statue's peak θ/α over the motions that is minimised.
    free_time : float
        Seconds simulated after each motion ends.
    options, workers, folder, fresh, chunk_size, progress
        As in :func:`rocking.analyses.store.run_stored`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``mu_s``, ``pedestal_mass``, ``motion``: every summary field per run, and per
        candidate ``mu_k``, ``overturn_count``, ``overturn_rate``, ``peak_rotation_ratio_mean``,
        ``_median``, ``_max``, ``peak_sliding_max``, ``residual_sliding_max``,
        ``required_top_friction_max``, ``feasible``, ``score`` and ``recommended``. The
        attributes hold the limits and ``recommended_mu_s``, ``recommended_mu_k`` and
        ``recommended_pedestal_mass`` (NaN if no candidate meets the limits).
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
    if top_friction_limit is None and system.statue.friction is not None:
        top_friction_limit = system.statue.friction.static
    for name, v in (("sliding_limit", sliding_limit), ("residual_limit", residual_limit),
                    ("top_friction_limit", top_friction_limit)):
        if v is not None and not (math.isfinite(v) and v >= 0):
            raise ValueError(f"{name} must be a number >= 0, got {v!r}")
    if not free_time >= 0:
        raise ValueError(f"free_time must be >= 0, got {free_time!r}")

    candidates = {}
    for i, mu in enumerate(mus):
        for j, m1 in enumerate(masses):
            s = replace_at(system, "pedestal.friction", Friction(static=float(mu), kinetic=float(kin[i])))
            candidates[i, j] = replace_at(s, "pedestal.mass", float(m1))
    runs = []
    for name, motion in motions.items():  # motion outermost: a chunk ships one or two records
        duration = float(motion.duration) + float(free_time)
        for i in range(mus.size):
            for j in range(masses.size):
                runs.append(Run(candidates[i, j], name, 1.0, duration))
    meta = {"mu_s": mus.tolist(), "mu_k": kin.tolist(), "pedestal_mass": masses.tolist(), "motions": list(motions)}
    raw = run_stored(runs, motions, options=options, study="design", folder=folder, fresh=fresh, workers=workers,
                     chunk_size=chunk_size, progress=progress, meta=meta)
    alpha = system.statue.slenderness
    shape = (len(motions), mus.size, masses.size)
    flat = summaries_dataset(raw, np.full(len(runs), alpha), dims=("motion", "mu_s", "pedestal_mass"), shape=shape)
    ds = flat.transpose("mu_s", "pedestal_mass", "motion")
    ds = ds.assign_coords(mu_s=mus, pedestal_mass=masses, motion=list(motions))
    ds["mu_s"].attrs["long_name"] = "static friction of the pedestal on the floor"
    ds["pedestal_mass"].attrs["units"] = "kg"

    rot = ds.peak_rotation_over_alpha.values  # (mu, mass, motion); an overturn gives π/(2α)
    over = ds.overturned.values
    survived_top = np.where(over, np.nan, ds.required_top_friction.values)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN: every motion overturns the statue
        top_max = np.nanmax(survived_top, axis=-1)
    cand = ("mu_s", "pedestal_mass")
    ds["mu_k"] = (("mu_s",), kin)
    ds["overturn_count"] = (cand, over.sum(axis=-1).astype(np.int64))
    ds["overturn_rate"] = (cand, over.mean(axis=-1))
    ds["peak_rotation_ratio_mean"] = (cand, rot.mean(axis=-1))
    ds["peak_rotation_ratio_median"] = (cand, np.median(rot, axis=-1))
    ds["peak_rotation_ratio_max"] = (cand, rot.max(axis=-1))
    ds["peak_sliding_max"] = (cand, ds.peak_sliding.values.max(axis=-1), {"units": "m"})
    ds["residual_sliding_max"] = (cand, np.abs(ds.residual_sliding.values).max(axis=-1), {"units": "m"})
    ds["required_top_friction_max"] = (cand, top_max, {
        "long_name": "largest friction the statue-pedestal face must supply (runs without overturning)"})
    feasible = np.ones(over.shape[:2], dtype=bool)
    if sliding_limit is not None:
        feasible &= ds.peak_sliding_max.values <= sliding_limit
    if residual_limit is not None:
        feasible &= ds.residual_sliding_max.values <= residual_limit
    if top_friction_limit is not None:
        feasible &= ~(top_max > top_friction_limit)  # NaN (everything overturned) is not a violation
    score = _stat(rot, objective)
    ds["feasible"] = (cand, feasible)
    ds["score"] = (cand, score, {"long_name": f"{objective} peak θ/α over the motions"})
    rec = np.zeros_like(feasible)
    best = None
    for i in range(mus.size):
        for j in range(masses.size):
            if feasible[i, j]:
                key = (int(ds.overturn_count.values[i, j]), float(score[i, j]),
                       float(ds.peak_sliding_max.values[i, j]), float(mus[i]), float(masses[j]))
                if best is None or key < best[0]:
                    best = (key, i, j)
    if best is not None:
        rec[best[1], best[2]] = True
    ds["recommended"] = (cand, rec)
    ds.attrs.update(
        study="friction design",
        alpha=alpha,
        tan_alpha=math.tan(alpha),
        objective=objective,
        sliding_limit=np.nan if sliding_limit is None else float(sliding_limit),
        residual_limit=np.nan if residual_limit is None else float(residual_limit),
        top_friction_limit=np.nan if top_friction_limit is None else float(top_friction_limit),
        free_time=float(free_time),
        gravity=float(options.gravity),
        recommended_mu_s=float(mus[best[1]]) if best else np.nan,
        recommended_mu_k=float(kin[best[1]]) if best else np.nan,
        recommended_pedestal_mass=float(masses[best[2]]) if best else np.nan,
        statue_width=system.statue.width,
        statue_height=system.statue.height,
        statue_mass=system.statue.mass,
    )
    return ds


CANDIDATE_COLUMNS = (
    "mu_k", "overturn_count", "overturn_rate", "peak_rotation_ratio_mean", "peak_rotation_ratio_median",
    "peak_rotation_ratio_max", "peak_sliding_max", "residual_sliding_max", "required_top_friction_max",
    "feasible", "score", "recommended",
)


def candidate_table(ds):
    """One row per candidate (μs, pedestal mass) with the aggregated results (a pandas DataFrame)."""
    table = ds[list(CANDIDATE_COLUMNS)].to_dataframe().reset_index()
    return table[["mu_s", "pedestal_mass", *CANDIDATE_COLUMNS]]


def _fmt(x: Any, digits: int = 3) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    x = float(x)
    return "–" if not math.isfinite(x) else f"{x:.{digits}g}"


def design_report(ds, *, title: str = "Friction design", chart: str | None = "design_chart.png") -> str:
    """A short Markdown report: inputs, the recommendation and the candidate table."""
    a = ds.attrs
    n_mot = ds.sizes["motion"]
    lines = [f"# {title}", ""]
    lines.append(
        f"Statue {a['statue_width']:g} m × {a['statue_height']:g} m, {a['statue_mass']:g} kg "
        f"(α = {a['alpha']:.4f} rad, tan α = {a['tan_alpha']:.3f}); {n_mot} motion(s); "
        f"{ds.sizes['mu_s']} × {ds.sizes['pedestal_mass']} candidate(s) (μs × pedestal mass)."
    )
    limits = []
    if math.isfinite(a["sliding_limit"]):
        limits.append(f"peak sliding ≤ {1e3 * a['sliding_limit']:.0f} mm")
    if math.isfinite(a["residual_limit"]):
        limits.append(f"residual sliding ≤ {1e3 * a['residual_limit']:.0f} mm")
    if math.isfinite(a["top_friction_limit"]):
        limits.append(f"required statue–pedestal friction ≤ {a['top_friction_limit']:.3g}")
    lines.append(f"Limits: {', '.join(limits) if limits else 'none'}. Objective: fewest overturns, then the "
                 f"smallest {a['objective']} peak θ/α over the motions.")
    lines.append("")
    if math.isfinite(a["recommended_mu_s"]):
        sel = ds.sel(mu_s=a["recommended_mu_s"], pedestal_mass=a["recommended_pedestal_mass"])
        lines.append(
            f"**Recommended: μs = {a['recommended_mu_s']:.3g}, μk = {a['recommended_mu_k']:.3g}, pedestal mass = "
            f"{a['recommended_pedestal_mass']:g} kg.** Overturns: {int(sel.overturn_count)} of {n_mot}; "
            f"peak θ/α {a['objective']} {_fmt(sel.score)}, max {_fmt(sel.peak_rotation_ratio_max)}; peak sliding "
            f"{1e3 * float(sel.peak_sliding_max):.1f} mm, residual {1e3 * float(sel.residual_sliding_max):.1f} mm; "
            f"the statue–pedestal face must supply μ ≥ {_fmt(sel.required_top_friction_max)}."
        )
    else:
        lines.append("**No candidate satisfies the limits.** Relax them or widen the sweep; the table shows "
                     "how far each candidate is.")
    lines += ["", "| μs | μk | pedestal mass (kg) | overturns | peak θ/α mean | peak θ/α max | peak sliding (mm) | "
              "residual (mm) | required top μ | meets limits |", "|---|---|---|---|---|---|---|---|---|---|"]
    for _, row in candidate_table(ds).iterrows():
        mark = " ⟵" if row["recommended"] else ""
        lines.append(
            f"| {_fmt(row['mu_s'])}{mark} | {_fmt(row['mu_k'])} | {_fmt(row['pedestal_mass'])} | "
            f"{int(row['overturn_count'])}/{n_mot} | {_fmt(row['peak_rotation_ratio_mean'])} | "
            f"{_fmt(row['peak_rotation_ratio_max'])} | {_fmt(1e3 * row['peak_sliding_max'], 4)} | "
            f"{_fmt(1e3 * row['residual_sliding_max'], 4)} | {_fmt(row['required_top_friction_max'])} | "
            f"{_fmt(bool(row['feasible']))} |"
        )
    lines += ["", "An overturn counts as θ/α = π/(2α) in the statistics of the peak rotation. The required top "
              "friction is the largest |F|/N at the statue–pedestal face over the motions the statue survives."]
    if chart:
        lines += ["", f"![design chart]({chart})"]
    return "\n".join(lines) + "\n"


def plot_design(ds, *, figsize_per_panel: tuple[float, float] = (6.4, 3.6)):
    """The design chart (one panel per pedestal mass): peak θ/α, overturn rate and peak sliding
    against μs, with the sliding limit and the recommended candidate marked. Returns the Figure."""
    from matplotlib.figure import Figure

    from ..viz.plots import plot_design_chart

    masses = ds.pedestal_mass.values
    fig = Figure(figsize=(figsize_per_panel[0], figsize_per_panel[1] * masses.size), layout="constrained")
    axes = fig.subplots(masses.size, 1, squeeze=False)[:, 0]
    stat = ds.attrs.get("objective", "mean")
    for ax, m1 in zip(axes, masses):
        sub = ds.sel(pedestal_mass=m1)
        plot_design_chart(sub.mu_s.values, sub[f"peak_rotation_ratio_{stat}"].values, sub.peak_sliding_max.values,
                          sub.overturn_rate.values, ax=ax, tan_alpha=ds.attrs.get("tan_alpha"))
        limit = ds.attrs.get("sliding_limit", np.nan)
        if np.isfinite(limit):
            ax.right_ax.axhline(1e3 * limit, color="0.2", lw=0.9, ls="-.")
            ax.right_ax.annotate("sliding limit", (float(sub.mu_s.values.max()), 1e3 * limit), xytext=(-3, 3),
                                 textcoords="offset points", ha="right", fontsize=7, color="0.2")
            top = max(ax.right_ax.get_ylim()[1], 1.15e3 * limit)
            ax.right_ax.set_ylim(0.0, top)
        rec = sub.recommended.values
        if rec.any():
            mu = float(sub.mu_s.values[rec][0])
            ax.axvline(mu, color="#2ca02c", lw=1.6, alpha=0.6, zorder=0)
            ax.annotate("recommended", (mu, 0.02), xytext=(3, 2), textcoords="offset points", fontsize=7,
                        color="#2ca02c")
        ax.set_ylabel(f"{stat} peak |θ|/α, overturn rate (–)")
        ax.set_title(f"pedestal mass {m1:g} kg", fontsize=9)
    return fig
