"""Shenton (1996): which motion starts from rest under a constant floor acceleration; Newmark
(1965): the sliding of a block under a rectangular pulse."""

from __future__ import annotations

import itertools

import rocking as rk

from . import exact as ex
from . import lib
from .rows import Row, Section

REGIME = {rk.Regime.REST: "rest", rk.Regime.SLIDE: "slide", rk.Regime.ROCK: "rock",
          rk.Regime.SLIDE_ROCK: "slide-rock"}
OPTIONS = rk.Options(gravity=ex.G, save_dt=1e-4)


def start_mode(b: float, h: float, mu: float, lam: float) -> str:
    """The library's motion just after t = 0 under a constant floor acceleration λ·g (m/s²),
    for a block of half-width b and half-height h (m) with μs = μk = μ."""
    blk = ex.Block(b, h)
    system = lib.alone(blk, friction=rk.Friction(static=mu, kinetic=mu))
    r = lib.simulate(system, rk.RectanglePulse(amplitude=lam * ex.G, width=0.01), duration=0.001, options=OPTIONS)
    return REGIME[rk.Regime(int(r.regime[1]))]


def shenton_rows(quick: bool) -> list[Row]:
    rows = []
    for i, t in enumerate((0.2, 0.25, 1 / 3, 0.5), 1):
        if quick and i not in (2, 4):
            continue
        b, h = t, 1.0
        lam = 1.5 * t
        published = ex.shenton_mu_rock(b, h, lam)

        def fails(mu, b=b, h=h, lam=lam):  # "fails" = pure rocking starts (μ at or above the boundary)
            return start_mode(b, h, mu, lam) == "rock"

        ours = ex.find(fails, published, rtol=1e-9, step=1.0 + 1e-6)
        rows.append(Row(f"S1.{i}", "Shenton 1996", f"friction above which pure rocking (not slide-rock) starts, "
                                                   f"b/h = {t:.4g}, λ = a_g/g = 1.5·b/h", "exact",
                        published=published, ours=ours, tol=1e-8,
                        note="published: Shenton's criterion, written as derived in the test suite's closed-form oracle O15"))
    # the four regions of Shenton's map, sampled around their boundaries
    t = 0.25
    points = list(itertools.product((0.5, 0.95, 1.05, 1.2, 2.0, 6.0), (0.5, 0.95, 1.05, 1.5, 3.0, 8.0)))
    agree = sum(start_mode(t, 1.0, fm * t, fl * t) == ex.shenton_mode(t, 1.0, fm * t, fl * t) for fm, fl in points)
    rows.append(Row("S2.1", "Shenton 1996", f"initiation map (rest, slide, rock, slide-rock) at b/h = {t:g}: "
                                            f"{len(points)} points μ/(b/h) × λ/(b/h) around the boundaries",
                    "exact", published=float(len(points)), ours=float(agree), tol=0.0,
                    note="values: points where the library's first motion is Shenton's"))
    return rows


def newmark_rows(quick: bool) -> list[Row]:
    cases = [(0.5, 0.2, 0.5)] if quick else [(0.5, 0.2, 0.5), (1.0, 0.1, 0.2), (0.3, 0.1, 1.0), (2.0, 0.5, 0.1)]
    squat = ex.Block(5.0, 0.5)  # b/h = 10: far too squat to rock at these accelerations
    rows = []
    for i, (A, N, t0) in enumerate(cases, 1):
        system = lib.alone(squat, friction=rk.Friction(static=N, kinetic=N))
        r = lib.simulate(system, rk.RectanglePulse(amplitude=A * ex.G, width=t0), save=False)
        rows.append(Row(f"NM1.{i}", "Newmark 1965", f"sliding under a rectangular pulse A = {A:g}g for "
                                                    f"t0 = {t0:g} s, resistance N = {N:g}g", "exact",
                        published=ex.newmark_rectangle(A, N, t0), ours=abs(r.summary()["residual_sliding"]),
                        unit="m", tol=1e-8))
    return rows


INTRO_SHENTON = """\
Shenton classifies the motion that starts from rest under a floor acceleration λ·g with friction μ:
rest, slide, rock or slide-rock. A block slides first if μ < b/h and λ > μ (and then cannot also start
to rock); it rocks if μ and λ exceed b/h and the friction can hold the corner, μ ≥ μ_rock(λ); it
slide-rocks otherwise. μ_rock(λ) = [λ(4b² + h²) + 3bh]/[(b² + 4h²) + 3λbh] for a uniform rectangle,
the ratio of the corner's reactions at the onset of rocking, as derived in the closed-form oracles of the test suite (`tests/oracles/closed_forms.py`)
(O15); Shenton's printed form was not compared symbol by symbol. "ours" is the library's regime
just after t = 0 under a constant floor acceleration (`RectanglePulse`); the boundary is bisected
on μ."""

INTRO_NEWMARK = """\
Newmark's sliding block: under a rectangular floor pulse A·g lasting t0, a block with friction
resistance N·g slides u = V²/(2gN)·(1 − N/A), V = A·g·t0 (exact for rigid-plastic Coulomb friction
with μs = μk). "ours" is the residual sliding of a squat block (b/h = 10) that cannot rock."""


def sections(quick: bool, progress) -> list[Section]:
    progress("Shenton: initiation modes")
    s = Section("shenton", "5. Shenton (1996): initiation of slide, rock and slide-rock", INTRO_SHENTON,
                shenton_rows(quick))
    progress("Newmark: rectangular pulse")
    n = Section("newmark", "6. Newmark (1965): sliding under a rectangular pulse", INTRO_NEWMARK, newmark_rows(quick))
    return [s, n]
