"""Nabeshima, Taniguchi, Kojima & Takewaki (2016): the double impulse that just overturns a
block, and the timing of its second impulse."""

from __future__ import annotations

from . import exact as ex
from . import lib
from .rows import Row, Section, fmt_pct

SRC = "Nabeshima et al. 2016"
WIDTH = 1e-5  # s, each impulse is a rectangular acceleration pulse this wide


def _first_impact(block: ex.Block, v: float) -> float:
    """Time (s) of the first impact after a single floor velocity step v (m/s)."""
    r = lib.simulate(lib.alone(block), lib.two_pulses(v, 0.0, 1.0, WIDTH), save=False)
    return r.impacts[0].time


def critical_double(block: ex.Block, delay: float, *, rtol: float = 1e-7) -> float:
    """Smallest V (m/s) of the double impulse +V at t = 0, −V at (first impact + ``delay`` s)
    that overturns the library's block (the first impact depends on V: it is found for each
    trial V)."""
    def fails(v):
        t2 = _first_impact(block, v) + delay
        r = lib.simulate(lib.alone(block), lib.two_pulses(v, -v, t2, WIDTH), save=False)
        return lib.model_overturned(r)

    return ex.find(fails, ex.double_impulse_exact(block), rtol=rtol, step=1.002)


def rows(quick: bool) -> tuple[list[Row], str]:
    blocks = [ex.Block(0.25, 1.0)] if quick else [ex.Block(0.25, 1.0), ex.Block(0.5, 2.0), ex.Block(0.5, 1.0)]
    out = []
    for i, blk in enumerate(blocks, 1):
        published = ex.double_impulse_exact(blk)
        ours = critical_double(blk, 0.0)
        out.append(Row(f"N1.{i}", SRC, f"double impulse (+V, then −V at the first impact) that just overturns, "
                                       f"B = {2 * blk.b:g} m, H = {2 * blk.h:g} m (α = {blk.alpha:.4f} rad, "
                                       f"η = {blk.eta:.4f}); impulses {WIDTH:g} s wide", "exact",
                       published=published, ours=ours, unit="m/s", tol=1e-4,
                       note="published: V_step/(1 + η), conservation of angular momentum and energy"))
    blk = blocks[0]
    delays = (-0.2, -0.05, -0.01, 0.01, 0.05, 0.2)  # in units of 1/p (cheap: also in the quick manual)
    at_impact = out[0].ours
    ratios = {d: critical_double(blk, d / blk.p, rtol=1e-6) / at_impact for d in delays}
    worst_neighbour = min(ratios.values())
    out.append(Row(
        "N2.1", SRC, "critical timing: the second impulse right after the first impact needs the smallest V "
                     f"(B = 0.5 m, H = 2 m; delays p·Δt = {', '.join(f'{d:+g}' for d in delays)})",
        "crosscheck", ours=worst_neighbour, published_label="just after the impact (qualitative)",
        passed=worst_neighbour > 1.0,
        note=f"smallest V at the other delays / V at the impact = {worst_neighbour:.4f}"))
    extra = ("**Timing of the second impulse** (B = 0.5 m, H = 2 m): V needed to overturn, relative to the "
             "second impulse at the first impact.\n\n"
             "| p·Δt | " + " | ".join(f"{d:+g}" for d in delays) + " |\n|---|" + "---|" * len(delays) + "\n"
             "| V/V(Δt = 0) | " + " | ".join(f"{ratios[d]:.4f}" for d in delays) + " |\n\n"
             "An impulse before the impact has its effect cut by the impact (×η); after it, the block has "
             "already slowed down: the impact is the worst instant, as the paper states. Just before the "
             f"impact the needed V is about (1 + η)/(2η) = {(1 + blk.eta) / (2 * blk.eta):.4f} times larger "
             f"({fmt_pct((1 + blk.eta) / (2 * blk.eta) - 1)}).")
    return out, extra


INTRO = """\
The double impulse stands for the main pulse of a near-fault record: a floor velocity step +V, then −V.
Nabeshima et al. obtain the limit in closed form from conservation of angular momentum (at each
impulse and at the impact) and of energy (between them), and find that the worst instant for the
second impulse is just after the impact. The closed form evaluated here is V = V_step/(1 + η), with
V_step the single-step limit of section 1 and Housner's η, as derived in the closed-form oracles of the test suite (`tests/oracles/closed_forms.py`)
(O7) from those two conservation laws; the paper's printed expression was not compared symbol by
symbol. "ours" drives the library with two rectangular acceleration pulses 1e-5 s wide (a recorded
motion built with `GroundMotion.from_arrays`), the second starting at the first impact of the
library's own run, and bisects V."""


def section(quick: bool, progress) -> tuple:
    progress("Nabeshima et al.: double impulse")
    rws, extra = rows(quick)
    return Section("nabeshima", "4. Nabeshima et al. (2016): double impulse and its critical timing", INTRO, rws,
                   extra)
