"""Housner (1963): uplift, restitution, free rocking, the velocity step and the rectangular
pulse."""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

import rocking as rk
from rocking.excitation.record import GroundMotion

from . import exact as ex
from . import lib
from .rows import Row, Section, fmt_pct

SRC = "Housner 1963"
REF_BLOCK = ex.Block(0.25, 1.0)  # B = 0.5 m, H = 2 m: α = 0.2450 rad, p = 2.6717 1/s
ALPHAS = (0.02, 0.05, 0.1, 0.2, 0.3, 0.4)  # rad, the grids of the range of validity
VALIDITY: list[str] = []  # the range-of-validity findings of the current build, in order


def _name(block: ex.Block) -> str:
    return f"B = {2 * block.b:.4g} m, H = {2 * block.h:.4g} m (α = {block.alpha:.4f} rad)"


def uplift(quick: bool) -> list[Row]:
    """Rocking starts at a_g = g·tan α: a ramp a_g = k·t, the onset time t_u gives k·t_u."""
    blocks = [ex.slender(0.02), REF_BLOCK] + ([] if quick else [ex.Block(0.5, 1.0), ex.Block(0.5, 0.5)])
    rows = []
    for i, blk in enumerate(blocks, 1):
        thr = ex.uplift_acceleration(blk)
        rate = thr  # onset near t = 1 s
        r = lib.simulate(lib.alone(blk), rk.Ramp(rate=rate, end=2.0), duration=1.5, save=False)
        ours = rate * r.summary()["first_rocking_time"]
        rows.append(Row(f"H1.{i}", SRC, f"uplift threshold g·tan α, {_name(blk)}; ramp a_g = k·t", "exact",
                        published=thr, ours=ours, unit="m/s²", tol=1e-8))
    if not quick:
        blk, a_v = REF_BLOCK, 2.0
        thr = ex.uplift_acceleration(blk, a_v)
        t = np.linspace(0.0, 2.0, 201)
        motion = GroundMotion.from_arrays(t, thr * t, vertical=np.full_like(t, a_v))
        r = lib.simulate(lib.alone(blk), motion, duration=1.5, save=False)
        rows.append(Row(f"H1.{len(blocks) + 1}", "Housner 1963, with vertical motion",
                        f"uplift at (g + a_v)·tan α with a_v = {a_v:g} m/s², {_name(blk)}", "exact",
                        published=thr, ours=thr * r.summary()["first_rocking_time"], unit="m/s²", tol=1e-8,
                        note="the extension to vertical floor motion is derived in docs/theory/derivation.md"))
    return rows


def restitution(quick: bool) -> list[Row]:
    """θ̇⁺/θ̇⁻ at the first impact of free rocking from α/2, with the library's default
    (Housner) restitution."""
    blocks = [ex.Block(0.5, 1.0), ex.Block(0.5, 1.5), REF_BLOCK, ex.Block(0.5, 2.5), ex.slender(0.02)]
    rows = []
    for i, blk in enumerate(blocks, 1):
        if quick and i not in (1, 3, 5):
            continue
        r = lib.simulate(lib.alone(blk), lib.STILL, duration=12.0 / blk.p, save=False,
                         initial_rotation=0.5 * blk.alpha)
        imp = r.impacts[0]
        rows.append(Row(f"H2.{i}", SRC, f"restitution η = 1 − 1.5 sin²α (θ̇⁺/θ̇⁻), {_name(blk)}", "exact",
                        published=blk.eta, ours=imp.theta_dot_after / imp.theta_dot_before, tol=1e-12))
    if not quick:
        blk = ex.Block(1.5, 0.5)
        r = lib.simulate(lib.alone(blk), lib.STILL, duration=5.0, save=False, initial_rotation=0.5 * blk.alpha)
        imp = r.impacts[0]
        ratio = imp.theta_dot_after / imp.theta_dot_before
        same_instant = sum(1 for x in r.impacts if abs(x.time - imp.time) < 1e-9)
        rows.append(Row(
            f"H2.{len(blocks) + 1}", SRC, f"restitution outside the formula's range: {_name(blk)}", "exact",
            published=max(0.0, blk.eta), ours=ratio + 0.0, tol=1e-12,  # (+ 0.0: no "-0")
            note=(f"η = 1 − 1.5 sin²α = {blk.eta:.3f} is negative for α > asin√(2/3) = "
                  f"{math.asin(math.sqrt(2 / 3)):.4f} rad (b/h > √2): the block cannot go on pivoting about the new "
                  f"corner (its θ̇ would reverse and the old corner enter the floor); a squat block lands flat. "
                  f"The library clamps η at 0 (a plastic landing): {same_instant} impact at t = {imp.time:.4f} s, "
                  f"then rest")))
    return rows


def free_rocking(quick: bool) -> tuple[list[Row], list[Row], str]:
    """The quarter period (release at rest at θ0 to the first impact): exact quadrature against
    ours, and Housner's small-angle formula against both; then its range of validity."""
    cases = [(REF_BLOCK, 0.1), (REF_BLOCK, 0.5), (REF_BLOCK, 0.9)]
    if not quick:
        cases += [(ex.Block(0.5, 1.0), 0.5), (ex.Block(0.5, 0.5), 0.5), (ex.slender(0.02), 0.5)]
    exact_rows, approx_rows = [], []
    for i, (blk, frac) in enumerate(cases, 1):
        th0 = frac * blk.alpha
        r = lib.simulate(lib.alone(blk), lib.STILL, duration=4.0 * ex.quarter_period_exact(blk, th0) + 1.0,
                         save=False, initial_rotation=th0)
        ours = r.impacts[0].time
        t_exact = ex.quarter_period_exact(blk, th0)
        case = f"time from release at θ0 = {frac:g}α to the first impact, {_name(blk)}"
        exact_rows.append(Row(f"H3.{i}", SRC + " (exact equation)", case, "exact", published=t_exact,
                              ours=ours, unit="s", tol=1e-8,
                              note="published: the energy integral of the nonlinear equation, by quadrature"))
        approx_rows.append(Row(f"H4.{i}", SRC, "small-angle " + case, "approx",
                               published=ex.quarter_period_linear(blk, th0), exact=t_exact, ours=ours, unit="s",
                               tol=1e-8))
    grid = "" if quick else _period_grid()
    return exact_rows, approx_rows, grid


def _period_error(alpha: float, frac: float) -> float:
    blk = ex.slender(alpha)
    th0 = frac * alpha
    return ex.quarter_period_linear(blk, th0) / ex.quarter_period_exact(blk, th0) - 1.0


def _period_grid() -> str:
    fracs = (0.1, 0.5, 0.9)
    alphas = ALPHAS + (0.5, 0.6, 0.785)
    lines = ["**Range of validity of Housner's small-angle period** (error of (1/p)·arccosh(1/(1 − θ0/α)) "
             "against the exact quadrature; negative: the formula is short).", "",
             "| θ0/α | " + " | ".join(f"α = {a:g}" for a in alphas) + " | α where the error reaches 1 % |",
             "|---|" + "---|" * (len(alphas) + 1)]
    limits = []
    for frac in fracs:
        errs = [_period_error(a, frac) for a in alphas]
        limit = _crossing(lambda a: abs(_period_error(a, frac)) - 0.01, 0.01, 1.2)
        limits.append(f"θ0/α = {frac:g}: α ≤ {_fmt_limit(limit)}")
        lines.append(f"| {frac:g} | " + " | ".join(_signed_pct(e) for e in errs) + f" | {_fmt_limit(limit)} |")
    VALIDITY.append("Housner's small-angle quarter period (1/p)·arccosh(1/(1 − θ0/α)) is within 1 % of the exact "
                    "one for " + "; ".join(limits) + " (it is always short).")
    return "\n".join(lines)


def _signed_pct(e: float) -> str:
    return ("−" if e < 0 else "") + fmt_pct(abs(e))


def _crossing(f, lo: float, hi: float) -> float | None:
    """Smallest root of f on [lo, hi] found on a grid of 200 points, refined by brentq."""
    xs = np.linspace(lo, hi, 201)
    vals = [f(x) for x in xs]
    for i in range(len(xs) - 1):
        if vals[i] <= 0 < vals[i + 1]:
            return optimize.brentq(f, xs[i], xs[i + 1], xtol=1e-10)
    return None


def _fmt_limit(x: float | None) -> str:
    return "beyond the range" if x is None else f"{x:.3f} rad"


def amplitude_decay(quick: bool) -> list[Row]:
    """Peak after six impacts of free rocking from α/2: the exact recursion (energy conserved in
    flight, η² of the kinetic energy kept at each impact) and Housner's small-angle decay."""
    if quick:
        return []
    blk, n = REF_BLOCK, 6
    th0 = 0.5 * blk.alpha
    r = lib.simulate(lib.alone(blk), lib.STILL, duration=6.0, save=True, initial_rotation=th0,
                     options=rk.Options(gravity=ex.G, save_dt=1e-4))
    times = [imp.time for imp in r.impacts]
    window = (r.t > times[n - 1]) & (r.t < times[n])
    # the sampled maximum lies within ½·θ̈·(Δt/2)² ≈ 1e-10 rad of the true peak
    ours = float(np.max(np.abs(r.theta[window]))) / blk.alpha
    exact = ex.peaks_exact(blk, th0, n)[-1] / blk.alpha
    lin = ex.peaks_linear(blk, th0, n)[-1] / blk.alpha
    case = f"peak θ/α after {n} impacts of free rocking from θ0 = α/2, {_name(blk)}"
    return [
        Row("H5.1", SRC + " (exact recursion)", case, "exact", published=exact, ours=ours, tol=1e-7,
            note="published: energy conserved between impacts, η² of it kept at each impact"),
        Row("H5.2", SRC, "small-angle " + case, "approx", published=lin, exact=exact, ours=ours, tol=1e-7),
    ]


STEP_WIDTH = 1e-6  # s, the rectangular pulse that carries a velocity step


def velocity_step_ours(block: ex.Block) -> float:
    """The library's smallest overturning velocity step V (m/s), bisected to 1e-8."""
    def fails(v):
        pulse = rk.RectanglePulse(amplitude=v / STEP_WIDTH, width=STEP_WIDTH)
        return lib.model_overturned(lib.simulate(lib.alone(block), pulse, save=False))

    return ex.find(fails, ex.velocity_step_exact(block), rtol=1e-8, step=1.001)


def velocity_step(quick: bool) -> tuple[list[Row], str]:
    """The floor velocity step that just overturns: a rectangular pulse 1e-6 s wide carrying
    the step V, bisected on V."""
    blocks = [REF_BLOCK] if quick else [REF_BLOCK, ex.Block(0.5, 2.0), ex.Block(0.5, 1.0)]
    rows = []
    for i, blk in enumerate(blocks, 1):
        v_exact = ex.velocity_step_exact(blk)
        ours = velocity_step_ours(blk)
        case = f"velocity step that overturns, {_name(blk)}; pulse {STEP_WIDTH:g} s wide"
        rows.append(Row(f"H6.{2 * i - 1}", SRC + " (impulse, exact)", case, "exact", published=v_exact, ours=ours,
                        unit="m/s", tol=1e-5,
                        note="published: angular momentum about the corner and energy; a pulse of width t_d "
                             "adds about p·t_d/2 to V"))
        rows.append(Row(f"H6.{2 * i}", SRC, "small-angle g·α/p: " + case, "approx",
                        published=ex.velocity_step_linear(blk), exact=v_exact, ours=ours, unit="m/s", tol=1e-5,
                        note="exact: the closed form above"))
    extra = ""
    if not quick:
        lim1 = _crossing(lambda a: abs(_vstep_error(a)) - 0.01, 0.005, 1.2)
        lim5 = _crossing(lambda a: abs(_vstep_error(a)) - 0.05, 0.005, 1.2)
        cells = " | ".join(_signed_pct(_vstep_error(a)) for a in ALPHAS + (0.5, 0.785))
        VALIDITY.append(f"The small-angle velocity step g·α/p is within 1 % of the exact limit for "
                        f"α ≤ {_fmt_limit(lim1)}, 5 % for α ≤ {_fmt_limit(lim5)}; it is always low, which errs on "
                        "the safe side (it predicts overturning below the true limit).")
        extra = ("**Range of validity of the small-angle velocity step g·α/p** (error against the exact "
                 "closed form; it depends on α only).\n\n"
                 "| " + " | ".join(f"α = {a:g}" for a in ALPHAS + (0.5, 0.785)) + " |\n"
                 "|" + "---|" * (len(ALPHAS) + 2) + "\n| " + cells + " |\n\n"
                 f"The error reaches 1 % at α = {_fmt_limit(lim1)} and 5 % at α = {_fmt_limit(lim5)}.")
    return rows, extra


def _vstep_error(alpha: float) -> float:
    blk = ex.slender(alpha)
    return ex.velocity_step_linear(blk) / ex.velocity_step_exact(blk) - 1.0


def rectangle_threshold(block: ex.Block, p_td: float, *, rtol: float = 1e-7) -> tuple[float, float]:
    """Mode-1 threshold a/(g tan α) of the rectangular pulse for (ours, exact integration)."""
    gt = block.g * block.tan_alpha
    width = p_td / block.p

    def ours_fails(A):
        return lib.overturns_mode1(block, rk.RectanglePulse(amplitude=A * gt, width=width))

    def exact_fails(A):
        o = ex.rock(block, ex.rectangle(A * gt, width), stop_after_impacts=1)
        return o.overturned and o.impacts == 0

    guess = ex.rectangle_threshold_linear(p_td)
    ours = ex.find(ours_fails, guess, rtol=rtol)
    # seeded from ours (a bracket only: both ends are decided by the exact integration)
    exact = ex.find(exact_fails, ours, fallback=guess, rtol=rtol, step=1.0 + 10 * rtol)
    return ours, exact


def rectangle(quick: bool) -> tuple[list[Row], str]:
    """Housner's rectangular pulse: the small-angle mode-1 threshold 1/(1 − e^(−p t_d))."""
    blk = ex.slender(0.02)
    rows = []
    for i, ptd in enumerate((0.5, 1.0, 2.0, 4.0), 1):
        if quick and i not in (2, 3):
            continue
        ours, exact = rectangle_threshold(blk, ptd)
        rows.append(Row(f"H7.{i}", SRC, f"rectangular pulse, p·t_d = {ptd:g}: smallest a/(g·tan α) that "
                                        f"overturns without impact, α = {blk.alpha:g} rad", "approx",
                        published=ex.rectangle_threshold_linear(ptd), exact=exact, ours=ours, tol=1e-5))
    if quick:
        return rows, ""
    lines = ["**Range of validity of the rectangular-pulse formula** (closed form against the exact "
             "integration, a/(g·tan α); the largest |ours/exact − 1| over the grid is given below).", "",
             "| p·t_d | " + " | ".join(f"α = {a:g}" for a in ALPHAS) + " |", "|---|" + "---|" * len(ALPHAS)]
    worst = worst_formula = 0.0
    for ptd in (0.5, 1.0, 2.0, 4.0):
        cells = []
        for a in ALPHAS:
            ours, exact = rectangle_threshold(ex.slender(a), ptd, rtol=1e-6)
            worst = max(worst, abs(ours / exact - 1.0))
            err = ex.rectangle_threshold_linear(ptd) / exact - 1.0
            worst_formula = max(worst_formula, abs(err))
            cells.append(_signed_pct(err))
        lines.append(f"| {ptd:g} | " + " | ".join(cells) + " |")
    lines += ["", f"Largest |ours/exact − 1| on this grid: {worst:.1e} (bisections to 1e-6)."]
    VALIDITY.append(f"The rectangular-pulse threshold 1/(1 − e^(−p·t_d)) stays within {fmt_pct(worst_formula)} "
                    f"of the exact one for α ≤ {max(ALPHAS):g} and p·t_d from 0.5 to 4 (read in a/(g·tan α)).")
    return rows, "\n".join(lines)


INTRO = """\
Housner's model: a rigid block rocking about its base corners without sliding or bouncing, an
impact that conserves angular momentum about the new corner, and free flight in between. Its
published results used here are the uplift condition, the ratio η = θ̇⁺/θ̇⁻ of the impact (Housner
gives the energy ratio η²), the free-rocking period and amplitude decay for slender blocks, and the
response to a rectangular pulse. The exact forms (the energy integral of the quarter period, the
exact decay recursion, the impulse limit from angular momentum and energy) follow from the same
equations without the small-angle step; they are evaluated here, not transcribed, and the
small-angle forms are compared with them. The velocity-step limit and the rectangular-pulse
threshold are written as derived in the closed-form oracles of the test suite (`tests/oracles/closed_forms.py`) (O6, O8); Housner's printed
expressions were not compared symbol by symbol.

Blocks: B = 2b, H = 2h. "ours" is `rocking.simulate` with g = 9.81 m/s² and the default
(Housner) restitution; thresholds are bisected on the library's outcome."""


def section(quick: bool, progress) -> Section:
    VALIDITY.clear()
    rows = []
    progress("Housner: uplift, restitution")
    rows += uplift(quick)
    rows += restitution(quick)
    progress("Housner: free rocking")
    exact_rows, approx_rows, period_grid = free_rocking(quick)
    rows += exact_rows + approx_rows
    rows += amplitude_decay(quick)
    progress("Housner: velocity step")
    v_rows, v_extra = velocity_step(quick)
    rows += v_rows
    progress("Housner: rectangular pulse (exact integration on a grid of α)")
    r_rows, r_extra = rectangle(quick)
    rows += r_rows
    extra = "\n\n".join(x for x in (period_grid, v_extra, r_extra) if x)
    return Section("housner", "1. Housner (1963): uplift, restitution, free rocking, velocity step, "
                              "rectangular pulse", INTRO, rows, extra, validity=list(VALIDITY))
