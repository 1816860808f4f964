"""Fragility curves by incremental dynamic analysis (IDA).

Every record of a set is scaled to a ladder of intensity levels (PGA in m/s², or PGV in m/s)
and run on each system (e.g. the statue alone and the statue on its pedestal). At each level
the fraction of records that make the statue exceed θ/α = 1 and the fraction that make it fall
are counted, and a lognormal curve P(IM) = Φ(ln(IM/median)/β) is fitted to the counts by
maximum likelihood (binomial likelihood over the levels; Baker 2015, Earthquake Spectra 31(1)).
Its confidence band comes from a bootstrap over the records (default) or from the observed
Fisher information (delta method).

    >>> from rocking.io.records import read_record
    >>> records = {n: read_record(n) for n in ("Kobe1995_Takatori_000", "Northridge1994_RinaldiReceivingSta_228")}
    >>> ds = ida({"alone": alone, "on pedestal": on_pedestal}, records, [1, 2, 4, 8])   # doctest: +SKIP
    >>> curves = fragility_curves(ds)                                                  # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..models.bodies import System
from ..simulation import Options
from ..stack.model import Stack
from .store import Run, run_stored

__all__ = [
    "IM_UNITS",
    "LognormalFit",
    "fit_lognormal",
    "fragility_curves",
    "ida",
    "load_record_set",
    "lognormal_probability",
    "extrapolated",
    "fragility_report_lines",
    "plot_fragility_curves",
]

IM_UNITS = {"pga": "m/s²", "pgv": "m/s"}
MODES = ("exceed", "fall")
_MODE_TEXT = {"exceed": "θ/α ≥ 1", "fall": "falling"}


# --------------------------------------------------------------------------------- records
def load_record_set(items: Sequence[str | os.PathLike[str]], *, base_dir: str | os.PathLike[str] | None = None) -> dict[str, Any]:
    """Read a set of records: files, folders (every readable record file in them, sorted by
    name) and names of bundled records, in the given order.

    Returns
    -------
    dict
        ``{name: GroundMotion}``; names are the file stems, made unique with a suffix.

    Raises
    ------
    FileNotFoundError, rocking.io.records.RecordError
    """
    from ..io.records import read_record

    base = Path(base_dir) if base_dir is not None else Path.cwd()
    files: list[Any] = []
    for item in items:
        p = Path(item).expanduser()
        p = p if p.is_absolute() else base / p
        if p.is_dir():
            found = sorted(q for q in p.iterdir() if q.is_file() and not q.name.startswith(".")
                           and q.suffix.lower() not in (".md", ".txt", ".toml", ".json", ".csv", ".py"))
            if not found:
                raise FileNotFoundError(f"no record files in the folder {p}")
            files.extend(found)
        elif p.is_file():
            files.append(p)
        else:
            files.append(str(item))  # a bundled record's name (read_record says if it is not one)
    out: dict[str, Any] = {}
    for f in files:
        motion = read_record(f)
        name, k = motion.name, 2
        while name in out:
            name, k = f"{motion.name}-{k}", k + 1
        out[name] = motion
    if not out:
        raise ValueError("the record set is empty")
    return out


def _intensity(motion: Any, im: str) -> float:
    if im == "pga":
        return float(motion.pga)
    if im == "pgv":
        return float(motion.pgv)
    raise ValueError(f"im must be 'pga' or 'pgv', got {im!r}")


# ------------------------------------------------------------------------------------ IDA
def ida(
    systems: System | Stack | Mapping[str, System | Stack],
    records: Mapping[str, Any] | Sequence[Any],
    levels: Sequence[float],
    *,
    im: str = "pga",
    free_time: float = 60.0,
    options: Options = Options(),
    workers: int | Any | None = None,
    folder: str | os.PathLike[str] | None = None,
    fresh: bool = False,
    chunk_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
):
    """Run every record scaled to every intensity level on every system.

    Parameters
    ----------
    systems : System, Stack, or mapping of label to either
        A :class:`rocking.stack.Stack` runs on the stack engine (every interface may slip,
        rock and lift); the statue is its top block.
    records : mapping of name to GroundMotion, or a sequence of GroundMotion
    levels : sequence of float
        Intensity levels: PGA (m/s²) or PGV (m/s), see ``im``.
    im : {"pga", "pgv"}
        The intensity measure the records are scaled to (PGV of the trapezoid-integrated,
        uncorrected record).
    free_time : float
        Longest free motion after the end of each record, s: each run goes on with the floor
        still until everything is at rest or the statue falls, for at most this long.
    options, workers, folder, fresh, chunk_size, progress
        As in :func:`rocking.analyses.store.run_stored`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``system``, ``record``, ``level``; every summary field of the runs plus
        ``exceed`` (θ/α reached 1, or fell) and ``fall`` (overturned), and ``scale_factor``.
        A run still moving at the free-motion cap (``still_moving``), or stopped by the solver
        before a verdict (``max_events``, ``inconsistent``, …), is not shown to survive: it counts
        as a fall and an exceedance (conservative); ``undetermined`` counts both kinds and
        ``solver_stopped`` the second. A run still moving whose statue can no longer overturn
        (``settled_by_energy``: less energy left than it needs to reach α, on a floor that has
        stopped) is no fall, counted in ``settled``.
        For a stack, any block that overturns (or slides off the one below) is a fall, and so,
        with ``options.stop_at_edge``, is a block that reaches the edge of the one below (status
        ``slid_past_edge``: the run stops there), counted in ``slid_off``. A statue that stands on
        a pedestal that would tip (``pedestal_uplift_time``: checked where the pedestal's width
        and height are given; the two-body model does not follow it) counts as a fall too, in
        ``pedestal_tips``.
    """
    from .batch import specs_dataset

    if isinstance(systems, (System, Stack)):
        systems = {"statue": systems}
    systems = dict(systems)
    if not systems:
        raise ValueError("ida needs at least one system")
    if not isinstance(records, Mapping):
        records = {(getattr(r, "name", "") or f"record{i}"): r for i, r in enumerate(records)}
    records = dict(records)
    if not records:
        raise ValueError("ida needs at least one record")
    lv = np.asarray(levels, dtype=float)
    if lv.ndim != 1 or lv.size == 0 or np.any(~np.isfinite(lv)) or np.any(lv <= 0):
        raise ValueError(f"levels must be positive numbers, got {levels!r}")
    if im not in IM_UNITS:
        raise ValueError(f"im must be 'pga' or 'pgv', got {im!r}")
    if not free_time >= 0:
        raise ValueError(f"free_time must be >= 0, got {free_time!r}")
    factors = np.empty((len(records), lv.size))
    for i, (name, rec) in enumerate(records.items()):
        base = _intensity(rec, im)
        if not base > 0:
            raise ValueError(f"record {name!r} has {im.upper()} = 0: it cannot be scaled")
        factors[i] = lv / base
    runs = []
    for i, (name, rec) in enumerate(records.items()):  # record outermost: a chunk ships 1-2 records
        for label, system in systems.items():
            for j in range(lv.size):
                runs.append(Run(system, name, float(factors[i, j])))  # the record, then free motion
    options = dataclasses.replace(options, free_time_limit=float(free_time))
    meta = {"systems": list(systems), "records": list(records), "levels": lv.tolist(), "im": im}
    raw = run_stored(runs, records, options=options, study="fragility", folder=folder, fresh=fresh,
                     workers=workers, chunk_size=chunk_size, progress=progress, meta=meta)
    shape = (len(records), len(systems), lv.size)
    flat = specs_dataset(raw, [run.system for run in runs], dims=("record", "system", "level"), shape=shape)
    ds = flat.transpose("system", "record", "level", ...)
    ds = ds.assign_coords(system=list(systems), record=list(records), level=lv)
    ds["level"].attrs.update(units=IM_UNITS[im], long_name=im.upper())
    ds["scale_factor"] = (("record", "level"), factors)
    slid_off = ds["status"] == "slid_past_edge"
    # A run the solver stopped before a verdict (max_events, inconsistent, singular, step_failed)
    # says nothing about survival: like a run still moving, it must not count as one.
    stopped = ~ds["status"].isin(["completed", "overturned", "still_moving", "slid_past_edge"])
    # A pedestal that would tip (the floor's reaction leaves its base, derivation §3.5; checked
    # where its width and height are given) is a fall risk the two-body model does not follow.
    tips = ds["pedestal_uplift_time"].notnull() & ~ds["overturned"]
    # a stack stops when any of its blocks overturns (status "overturned"), the statue or not
    # still moving at the cap, unless the statue can no longer overturn (too little energy left on
    # a floor that has stopped: results.response.settled_by_energy)
    moving = ds["still_moving"] & ~ds["settled_by_energy"]
    ds["fall"] = ds["overturned"] | (ds["status"] == "overturned") | moving | slid_off | stopped | tips
    ds["exceed"] = ds["fall"] | (ds["peak_rotation_over_alpha"] >= 1.0)
    ds["undetermined"] = (moving | stopped).sum(dim=("record", "level"))
    ds["undetermined"].attrs["long_name"] = ("runs still moving at the free-motion cap or stopped by the solver "
                                             "(counted as falls)")
    ds["settled"] = (ds["still_moving"] & ds["settled_by_energy"]).sum(dim=("record", "level"))
    ds["settled"].attrs["long_name"] = ("runs still moving at the free-motion cap whose statue can no longer "
                                        "overturn (too little energy left; counted as survivals)")
    ds["solver_stopped"] = stopped.sum(dim=("record", "level"))
    ds["solver_stopped"].attrs["long_name"] = "runs the solver stopped before a verdict (counted as falls)"
    ds["slid_off"] = slid_off.sum(dim=("record", "level"))
    ds["slid_off"].attrs["long_name"] = "runs where a block slid to the edge of the one below (counted as falls)"
    ds["pedestal_tips"] = tips.sum(dim=("record", "level"))
    ds["pedestal_tips"].attrs["long_name"] = ("runs where the statue stood but its pedestal would tip, which the "
                                              "two-body model does not follow (counted as falls)")
    ds.attrs.update(study="ida", im=im, im_units=IM_UNITS[im], free_time=float(free_time),
                    gravity=float(options.gravity))
    return ds


# ---------------------------------------------------------------------------- the fit
def lognormal_probability(x: Any, median: float, beta: float) -> np.ndarray:
    """Φ(ln(x/median)/β); 0 for x ≤ 0."""
    from scipy.special import ndtr

    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.log(np.where(x > 0, x, np.nan) / median) / beta
    return np.where(x > 0, ndtr(z), 0.0)


@dataclass(frozen=True)
class LognormalFit:
    """Maximum-likelihood lognormal fragility P(IM) = Φ(ln(IM/median)/β).

    ``covariance`` is the inverse observed Fisher information of (ln median, β) at the
    estimate (NaN if singular); ``se_ln_median`` and ``se_beta`` are its square-rooted
    diagonal. ``at_bound`` says that the optimum lies on the search bounds (the data do not
    pin the curve down: e.g. no failure, all failures, or failures that jump from 0 to 1 between
    two levels, for which β → 0).
    """

    median: float
    beta: float
    log_likelihood: float
    covariance: np.ndarray = field(repr=False)
    converged: bool
    at_bound: bool
    n_levels: int
    n_runs: int
    n_failed: int

    @property
    def se_ln_median(self) -> float:
        return float(math.sqrt(self.covariance[0, 0])) if np.isfinite(self.covariance[0, 0]) else math.nan

    @property
    def se_beta(self) -> float:
        return float(math.sqrt(self.covariance[1, 1])) if np.isfinite(self.covariance[1, 1]) else math.nan

    def probability(self, x: Any) -> np.ndarray:
        return lognormal_probability(x, self.median, self.beta)

    def fisher_band(self, x: Any, confidence: float = 0.9) -> tuple[np.ndarray, np.ndarray]:
        """Pointwise band of P(x) by the delta method on z = (ln x − ln median)/β."""
        from scipy.special import ndtr, ndtri

        x = np.asarray(x, dtype=float)
        q = float(ndtri(0.5 + 0.5 * confidence))
        with np.errstate(divide="ignore", invalid="ignore"):
            z = (np.log(x) - math.log(self.median)) / self.beta
            g0, g1 = -1.0 / self.beta, -z / self.beta
            c = self.covariance
            sd = np.sqrt(g0 * g0 * c[0, 0] + 2 * g0 * g1 * c[0, 1] + g1 * g1 * c[1, 1])
        lo, hi = ndtr(z - q * sd), ndtr(z + q * sd)
        zero = ~(x > 0)
        return np.where(zero, 0.0, lo), np.where(zero, 0.0, hi)


def _nll_terms(theta: np.ndarray, lx: np.ndarray, n: np.ndarray, k: np.ndarray) -> tuple[float, np.ndarray]:
    """Negative binomial log-likelihood of (mu = ln median, beta) and its gradient."""
    from scipy.special import log_ndtr

    mu, beta = theta
    z = (lx - mu) / beta
    lp, lq = log_ndtr(z), log_ndtr(-z)
    log_phi = -0.5 * z * z - 0.5 * math.log(2 * math.pi)
    a = k * np.exp(log_phi - lp) - (n - k) * np.exp(log_phi - lq)  # dℓ/dz
    grad = np.array([np.sum(a) / beta, np.sum(a * z) / beta])  # of −ℓ: ∂z/∂mu = −1/β, ∂z/∂β = −z/β
    return -float(np.sum(k * lp + (n - k) * lq)), grad


def _observed_information(mu: float, beta: float, lx: np.ndarray, n: np.ndarray, k: np.ndarray) -> np.ndarray:
    """−∇²ℓ at (mu = ln median, beta), analytic."""
    from scipy.special import log_ndtr

    z = (lx - mu) / beta
    log_phi = -0.5 * z * z - 0.5 * math.log(2 * math.pi)
    # ratios φ/Φ and φ/(1−Φ) computed in logs: stable far in the tails
    r1 = np.exp(log_phi - log_ndtr(z))
    r0 = np.exp(log_phi - log_ndtr(-z))
    a = k * r1 - (n - k) * r0  # dℓ/dz
    b = -z * a - k * r1 * r1 - (n - k) * r0 * r0  # d²ℓ/dz²
    dz = np.stack([-np.ones_like(z) / beta, -z / beta])  # ∂z/∂(mu, beta)
    h = np.einsum("j,aj,bj->ab", b, dz, dz)
    h[0, 1] += np.sum(a / beta**2)  # ∂²z/∂mu∂beta = 1/β²
    h[1, 0] += np.sum(a / beta**2)
    h[1, 1] += np.sum(a * 2 * z / beta**2)  # ∂²z/∂β² = 2z/β²
    return -h


def fit_lognormal(
    im: Any,
    n_runs: Any,
    n_failed: Any,
    *,
    beta_bounds: tuple[float, float] = (0.02, 5.0),
    start: tuple[float, float] | None = None,
) -> LognormalFit:
    """Fit Φ(ln(im/median)/β) to ``n_failed`` of ``n_runs`` at each level by maximum likelihood.

    Parameters
    ----------
    im : array
        Intensity levels (> 0).
    n_runs, n_failed : array
        Runs and failures at each level (levels without runs are ignored).
    beta_bounds : (float, float)
        Search interval of β. The median is searched between 1/100 of the smallest and 100
        times the largest level.
    start : (median, beta), optional
        A starting point (e.g. the full-data fit when refitting bootstrap samples); default:
        the best of three generic starts.

    Examples
    --------
    >>> fit = fit_lognormal([1, 2, 4, 8], [100, 100, 100, 100], [3, 25, 70, 96])
    >>> round(fit.median, 2), round(fit.beta, 2)
    (2.95, 0.57)
    """
    from scipy.optimize import minimize

    x = np.asarray(im, dtype=float)
    n = np.asarray(n_runs, dtype=float)
    k = np.asarray(n_failed, dtype=float)
    if not (x.shape == n.shape == k.shape) or x.ndim != 1:
        raise ValueError("im, n_runs and n_failed must be 1-D arrays of one length")
    keep = n > 0
    x, n, k = x[keep], n[keep], k[keep]
    if x.size == 0 or np.any(x <= 0) or np.any(k < 0) or np.any(k > n):
        raise ValueError("fit_lognormal needs positive levels and 0 <= n_failed <= n_runs")
    lx = np.log(x)
    lo_mu, hi_mu = float(lx.min()) - math.log(100.0), float(lx.max()) + math.log(100.0)
    lo_b, hi_b = (math.log(float(b)) for b in beta_bounds)
    bounds = [(lo_mu, hi_mu), (lo_b, hi_b)]  # on (ln median, ln β)
    total, failed = int(n.sum()), int(k.sum())
    nan_cov = np.full((2, 2), np.nan)
    if failed == 0 or failed == total:
        # no information on the curve: the likelihood is maximal at a bound
        mu = hi_mu if failed == 0 else lo_mu
        return LognormalFit(math.exp(mu), math.nan, 0.0, nan_cov, False, True, int(x.size), total, failed)

    frac = k / n
    order = np.argsort(lx)
    if np.all((frac == 0) | (frac == 1)) and np.all(np.diff(frac[order]) >= 0):
        # complete separation (0 below some level, 1 above): the likelihood grows as β → 0
        j = int(np.argmax(frac[order] == 1))
        mu = 0.5 * (lx[order][j - 1] + lx[order][j])
        return LognormalFit(math.exp(mu), float(beta_bounds[0]), 0.0, nan_cov, False, True, int(x.size), total,
                            failed)

    def objective(t: np.ndarray) -> tuple[float, np.ndarray]:
        b = math.exp(t[1])
        value, grad = _nll_terms(np.array([t[0], b]), lx, n, k)
        return value, np.array([grad[0], grad[1] * b])

    # start: median where the observed fraction crosses 1/2, β from the spread of the levels
    mu0 = float(np.interp(0.5, np.maximum.accumulate(frac[order]), lx[order])) if frac.max() >= 0.5 else float(lx.max())
    starts = [(mu0, 0.4), (mu0, 1.0), (float(lx.mean()), 0.6)]
    if start is not None:
        starts = [(math.log(start[0]), start[1])]
    best = None
    for s in starts:
        t0 = np.array([min(max(s[0], lo_mu), hi_mu), min(max(math.log(s[1]), lo_b), hi_b)])
        # TNC: bounded, and far faster than L-BFGS-B on this 2-parameter problem
        res = minimize(objective, t0, jac=True, method="TNC", bounds=bounds, options={"maxfun": 400})
        if best is None or res.fun < best.fun:
            best = res
    mu, beta = float(best.x[0]), math.exp(float(best.x[1]))
    at_bound = any(min(abs(v - b0), abs(v - b1)) < 1e-5 for v, (b0, b1) in zip(best.x, bounds))
    info = _observed_information(mu, beta, lx, n, k)
    try:
        cov = np.linalg.inv(info)
        if not np.all(np.isfinite(cov)) or np.any(np.diag(cov) < 0):
            cov = nan_cov
    except np.linalg.LinAlgError:
        cov = nan_cov
    return LognormalFit(math.exp(mu), beta, -float(best.fun), cov, bool(best.success), bool(at_bound),
                        int(x.size), total, failed)


def fragility_curves(
    ds,
    *,
    band: str = "bootstrap",
    n_boot: int = 400,
    confidence: float = 0.9,
    seed: int = 0,
    grid: Sequence[float] | None = None,
):
    """Lognormal fits (and their confidence bands) of every system and failure mode of an IDA.

    Parameters
    ----------
    ds : xarray.Dataset
        The result of :func:`ida`.
    band : {"bootstrap", "fisher", "none"}
        ``"bootstrap"``: resample the records with replacement ``n_boot`` times, refit, and take
        the pointwise percentiles of the curves; ``"fisher"``: delta method with the observed
        Fisher information.
    confidence : float
        Two-sided level of the band and of the median's interval.
    seed : int
        Of the bootstrap's random generator (the result is reproducible).
    grid : sequence of float, optional
        IM values of the curves (default: 200 points from 0 to 1.5 × the highest level).

    Returns
    -------
    xarray.Dataset
        Dimensions ``system``, ``mode`` ("exceed", "fall"), ``level``, ``im``:
        ``n_runs``, ``n_failed``, ``fraction`` (observed), ``im_median`` (the IM at which
        P = 1/2), ``beta``, ``se_ln_median``, ``se_beta``, ``im_median_lower``/``_upper`` (its
        interval), ``log_likelihood``, ``at_bound``, ``probability`` (the fitted curve on
        ``im``) and ``band_lower``/``band_upper``.
    """
    import xarray as xr
    from scipy.special import ndtri

    if band not in ("bootstrap", "fisher", "none"):
        raise ValueError(f"band must be 'bootstrap', 'fisher' or 'none', got {band!r}")
    if not 0 < confidence < 1:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    levels = ds.level.values
    x = np.asarray(grid, dtype=float) if grid is not None else np.linspace(0.0, 1.5 * float(levels.max()), 201)[1:]
    systems, n_rec = ds.system.values.tolist(), ds.sizes["record"]
    shape = (len(systems), len(MODES))
    out = {name: np.full(shape, np.nan) for name in
           ("im_median", "beta", "se_ln_median", "se_beta", "im_median_lower", "im_median_upper", "log_likelihood")}
    at_bound = np.zeros(shape, dtype=bool)
    n_runs = np.zeros(shape + (levels.size,), dtype=np.int64)
    n_failed = np.zeros(shape + (levels.size,), dtype=np.int64)
    prob = np.full(shape + (x.size,), np.nan)
    lower = np.full(shape + (x.size,), np.nan)
    upper = np.full(shape + (x.size,), np.nan)
    rng = np.random.default_rng(seed)
    picks = rng.integers(0, n_rec, size=(int(n_boot), n_rec)) if band == "bootstrap" else None
    q = float(ndtri(0.5 + 0.5 * confidence))
    for i, label in enumerate(systems):
        for m, mode in enumerate(MODES):
            fails = ds[mode].sel(system=label).values.astype(np.int64)  # (record, level)
            n = np.full(levels.size, n_rec, dtype=np.int64)
            k = fails.sum(axis=0)
            n_runs[i, m], n_failed[i, m] = n, k
            fit = fit_lognormal(levels, n, k)
            at_bound[i, m] = fit.at_bound
            if not np.isfinite(fit.beta):
                continue
            out["im_median"][i, m], out["beta"][i, m] = fit.median, fit.beta
            out["se_ln_median"][i, m], out["se_beta"][i, m] = fit.se_ln_median, fit.se_beta
            out["log_likelihood"][i, m] = fit.log_likelihood
            prob[i, m] = fit.probability(x)
            if band == "fisher":
                lower[i, m], upper[i, m] = fit.fisher_band(x, confidence)
                se = fit.se_ln_median
                out["im_median_lower"][i, m] = fit.median * math.exp(-q * se)
                out["im_median_upper"][i, m] = fit.median * math.exp(q * se)
            elif band == "bootstrap":
                curves, medians = [], []
                for pick in picks:  # type: ignore[union-attr]
                    kb = fails[pick].sum(axis=0)
                    fb = fit_lognormal(levels, n, kb, start=(fit.median, fit.beta))
                    if np.isfinite(fb.beta):
                        curves.append(fb.probability(x))
                        medians.append(fb.median)
                if curves:
                    tail = 50.0 * (1.0 - confidence)
                    lower[i, m], upper[i, m] = np.percentile(np.array(curves), [tail, 100 - tail], axis=0)
                    out["im_median_lower"][i, m], out["im_median_upper"][i, m] = np.percentile(medians, [tail, 100 - tail])
    dims = ("system", "mode")
    res = xr.Dataset(
        {
            "n_runs": (dims + ("level",), n_runs),
            "n_failed": (dims + ("level",), n_failed),
            "fraction": (dims + ("level",), n_failed / np.maximum(n_runs, 1)),
            **{name: (dims, arr) for name, arr in out.items()},
            "at_bound": (dims, at_bound),
            "probability": (dims + ("im",), prob),
            "band_lower": (dims + ("im",), lower),
            "band_upper": (dims + ("im",), upper),
        },
        coords={"system": systems, "mode": list(MODES), "level": levels, "im": x},
        attrs={"study": "fragility", "im_name": ds.attrs.get("im", "pga"), "im_units": ds.attrs.get("im_units", ""),
               "band": band, "confidence": float(confidence), "n_boot": int(n_boot) if band == "bootstrap" else 0,
               "seed": int(seed), "n_records": int(n_rec)},
    )
    for name in ("im_median", "im_median_lower", "im_median_upper"):
        res[name].attrs["units"] = res.attrs["im_units"]
    return res


def plot_fragility_curves(curves, mode: str = "fall", ax=None, *, title: str | None = None):
    """Every system's observed fractions, fitted curve and band for one failure mode on one chart,
    with the legend in a strip above the axes; a median beyond the highest level run is marked
    as extrapolated and the range beyond that level greyed."""
    from ..viz.plots import plot_fragility

    colors = ["#c0392b", "#1f77b4", "#2ca02c", "#8e44ad", "#ff7f0e"]
    im_name = curves.attrs.get("im_name", "pga").upper()
    units = curves.attrs.get("im_units", "")
    level = int(round(100 * float(curves.attrs.get("confidence", 0.9))))
    tested = float(curves.level.values.max())
    medians = curves.im_median.sel(mode=mode).values
    medians = medians[np.isfinite(medians)]
    # the extrapolated medians on the chart, unless absurdly far out (then the label says where)
    x_max = max(float(curves.im.values.max()), min(1.15 * float(medians.max()), 3.0 * tested) if medians.size else 0.0)
    x = np.linspace(0.0, x_max, 400)
    if ax is None:  # wide enough for a legend column per system above the axes
        from matplotlib.figure import Figure

        ax = Figure(figsize=(7.6, 4.6), layout="constrained").add_subplot()
    for i, label in enumerate(curves.system.values.tolist()):
        c = curves.sel(system=label, mode=mode)
        color = colors[i % len(colors)]
        median = float(c["im_median"]) if np.isfinite(c["im_median"]) else None
        beta = float(c["beta"]) if np.isfinite(c["beta"]) else None
        band = None
        if np.any(np.isfinite(c.band_lower.values)):
            band = (curves.im.values, c.band_lower.values, c.band_upper.values)
        before = set(map(id, ax.collections)) if ax is not None else set()
        lines_before = set(map(id, ax.get_lines())) if ax is not None else set()
        ax = plot_fragility(curves.level.values, c.fraction.values, median, beta, ax=ax, label=label, band=band,
                            im_label=f"{im_name} ({units})", color=color, tested_max=tested, units=units,
                            legend=False)
        for coll in ax.collections:  # the band just drawn: in the system's colour
            if id(coll) not in before and coll.get_label() == "confidence band":
                coll.set_facecolor(color)
                coll.set_alpha(0.15)
                coll.set_label(f"{label}: {level}% band")
        for line in ax.get_lines():
            if id(line) in lines_before:
                continue
            if median is None and line.get_label() == "observed fraction":  # plot_fragility's name for it
                line.set_label(f"{label}: observed (no fit)")
            elif median is not None and "median =" in str(line.get_label()):
                # every system's curve over the same range
                line.set_data(x, lognormal_probability(x, median, beta))
    ax.set_ylabel(f"probability of {_MODE_TEXT.get(mode, mode)} (–)")
    ax.set_xlim(0.0, x_max)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=2, fontsize=7.5, frameon=False, borderaxespad=0.0)
    if title:
        ax.figure.suptitle(title, fontsize=9)
    return ax


def extrapolated(curves) -> np.ndarray:
    """(system, mode): the fitted median lies above the highest level run (an extrapolation)."""
    return np.asarray(curves.im_median.values > float(curves.level.values.max()))


def fragility_report_lines(curves, runs, *, free_time: float, charts: Sequence[str] = ()) -> list[str]:
    """The report's section of one intensity measure: the fits (every number with its unit, the
    medians beyond the highest level run flagged), the levels run with the failures counted at
    each, the warnings, and the charts."""
    im = str(curves.attrs.get("im_name", "pga"))
    unit = curves.attrs["im_units"]
    top = float(curves.level.values.max())
    beyond = extrapolated(curves)
    systems = curves.system.values.tolist()
    lines = [f"## {im.upper()} (every value in {unit})", "",
             f"| system | failure | median {im.upper()} | interval | β |", "|---|---|---|---|---|"]
    for s, label in enumerate(systems):
        for m, mode in enumerate(MODES):
            c = curves.sel(system=label, mode=mode)
            med, lo, hi, beta = (float(c[k]) for k in ("im_median", "im_median_lower", "im_median_upper", "beta"))
            fit = f"{med:.3g} {unit}" if math.isfinite(med) else "no fit (no failure at any level)"
            if beyond[s, m]:
                fit += f" ⚠ extrapolated (above the highest level run, {top:.3g} {unit})"
            interval = f"{lo:.3g} – {hi:.3g} {unit}" if math.isfinite(lo) else "–"
            lines.append(f"| {label} | {_REPORT_MODE[mode]} | {fit} | {interval} | "
                         f"{f'{beta:.3g}' if math.isfinite(beta) else '–'} |")
    lines.append("")
    if beyond.any():
        lines += [f"⚠ An extrapolated median lies beyond every level run: the fit reaches it from the failures "
                  f"below {top:.3g} {unit}, so it (and its interval) rests on the lognormal shape, not on runs. "
                  f"Run higher levels to check it.", ""]
    heads = [f"{label}: {_REPORT_MODE[mode]}" for label in systems for mode in MODES]
    lines += [f"Failures per level ({curves.attrs.get('n_records', '')} records at each):", "",
              f"| {im.upper()} ({unit}) | " + " | ".join(heads) + " |", "|---|" + "---|" * len(heads)]
    for k, level in enumerate(curves.level.values):
        cells = [f"{int(curves.n_failed.values[s, m, k])}/{int(curves.n_runs.values[s, m, k])}"
                 for s in range(len(systems)) for m in range(len(MODES))]
        lines.append(f"| {level:.3g} | " + " | ".join(cells) + " |")
    lines.append("")
    stopped = int(runs.solver_stopped.sum()) if "solver_stopped" in runs else 0
    moving = int(runs.undetermined.sum()) - stopped
    if moving:
        lines += [f"**{moving} run(s) were still moving {free_time:g} s after their record ended: "
                  "undetermined, counted as falls.** Raise fragility.free_time to decide them.", ""]
    settled = int(runs.settled.sum()) if "settled" in runs else 0
    if settled:
        lines += [f"{settled} run(s) were still moving {free_time:g} s after their record ended, with less energy "
                  "than the statue needs to overturn on a floor that has stopped: it cannot fall any more, so "
                  "they count as survivals.", ""]
    if stopped:
        lines += [f"**{stopped} run(s) were stopped by the solver before a verdict (too many events, or no "
                  "consistent contact mode): undetermined, counted as falls.** Their statuses are in the "
                  "runs' `status`.", ""]
    slid = int(runs.slid_off.sum()) if "slid_off" in runs else 0
    if slid:
        lines += [f"**{slid} run(s): a block slid to the edge of the one below, where the stack engine stops: "
                  "counted as falls (a fall risk).**", ""]
    tipping = int(runs.pedestal_tips.sum()) if "pedestal_tips" in runs else 0
    if tipping:
        lines += [f"**{tipping} run(s): the statue stood, but its pedestal would tip (the floor's reaction left its "
                  "base), which this model does not follow: counted as falls (a fall risk).** A stack of blocks "
                  "(the stack engine) follows the pedestal's rocking.", ""]
    lines += [f"![{im} {name.split('_')[-1].removesuffix('.png')}]({name})" for name in charts]
    return lines + [""]


_REPORT_MODE = {"exceed": "θ/α ≥ 1", "fall": "falls"}
