"""The statue-on-pedestal model reduced to the validated single-block cases, and two-block stacks
on the general stack engine."""

from __future__ import annotations

import rocking as rk
from rocking.analyses.spectra import overturning_spectrum

from . import exact as ex
from . import lib
from .rows import Row, Section


def reduction_rows(quick: bool) -> list[Row]:
    blk = ex.Block(0.25, 1.0)
    rows = []
    # 1. a pedestal the floor holds (μ = 10): the statue is Housner's block of section 2
    held = rk.System(statue=lib.statue(blk), pedestal=rk.Pedestal(mass=1.0, friction=rk.Friction(static=10.0)))
    betas = [2.0] if quick else [2.0, 4.0]
    kw = dict(criterion="overturn", rtol=1e-7, n_scan=60, amplitude_range=(1.01, 30.0), options=lib.OPTIONS,
              workers=1)
    on_pedestal = overturning_spectrum(held, ["sine"], betas, **kw).amplitude_ratio.values.ravel()
    single = overturning_spectrum(lib.alone(blk), ["sine"], betas, **kw).amplitude_ratio.values.ravel()
    for i, (a, b) in enumerate(zip(on_pedestal, single), 1):
        rows.append(Row(f"P1.{i}", "this model, limit μ → ∞",
                        f"statue B = 0.5 m, H = 2 m on a pedestal held by friction μ = 10: smallest overturning "
                        f"one-sine a_p/(g·tan α) at β = {betas[i - 1]:g} (published = the single block's, §2)",
                        "exact", published=float(b), ours=float(a), tol=2e-7,
                        note="the pedestal never slides: the statue must be the Housner block"))
    # 2. a statue too squat to rock on a sliding pedestal: Newmark's block of mass m1 + m2
    squat = rk.Statue(width=2.0, height=1.0, mass=3.0)  # tan α = 1 > μ: it never rocks (O17)
    for i, (A, N, t0) in enumerate([(0.5, 0.2, 0.5)] if quick else [(0.5, 0.2, 0.5), (1.0, 0.1, 0.2)], 1):
        system = rk.System(statue=squat, pedestal=rk.Pedestal(mass=2.0, friction=rk.Friction(static=N, kinetic=N)))
        r = lib.simulate(system, rk.RectanglePulse(amplitude=A * ex.G, width=t0), save=False)
        rows.append(Row(f"P2.{i}", "Newmark 1965, through this model",
                        f"squat statue (tan α = 1) on a pedestal sliding on μ = {N:g}: pulse {A:g}g for {t0:g} s",
                        "exact", published=ex.newmark_rectangle(A, N, t0), ours=abs(r.summary()["residual_sliding"]),
                        unit="m", tol=1e-8))
    # 3. μs ≤ tan α: a sliding pedestal passes on at most μk·g < g·tan α, the statue never rocks
    slender = rk.System(statue=lib.statue(blk), pedestal=rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.2)))
    peaks = [lib.simulate(slender, lib.sine_pulse(blk, A, beta), save=False).peak_rotation
             for A in (2.0, 10.0) for beta in (0.5, 2.0, 8.0)]
    rows.append(Row("P3.1", "Shenton 1996, through this model",
                    "statue B = 0.5 m, H = 2 m (tan α = 0.25) on a pedestal with μ = 0.2: largest |θ| (rad) "
                    "over one-sine pulses A = 2, 10 × β = 0.5, 2, 8", "exact", published=0.0, ours=max(peaks),
                    unit="rad", tol=0.0, note="slide before rock: the statue never rocks"))
    return rows


def _ramp_onset(stack, block: int, rate: float = 0.05, what: str = "first_rocking_time") -> float:
    """Floor acceleration (m/s²) at which ``block`` (0 = the lowest) first rocks (or, with
    ``what="first_sliding_time"``, slides) under a slow ramp a = rate·t from rest, through the
    general stack engine."""
    from rocking.stack import simulate_stack

    r = simulate_stack(stack, rk.Ramp(rate=rate, end=60.0), duration=60.0, options={"gravity": ex.G})
    return rate * r.blocks[block][what]


def _composite_rows() -> list[Row]:
    """A two-block stack that rocks as one body (its top block squat, the interface stuck) against
    Housner's equation for that body, integrated with SciPy (:func:`exact.composite_rocking`)."""
    from rocking.stack import Block, Interface, Stack, simulate_stack

    (m1, w1, h1), (m2, w2, h2) = (40.0, 0.3, 1.0), (60.0, 0.5, 0.5)
    stack = Stack(blocks=(Block(width=w1, height=h1, mass=m1), Block(width=w2, height=h2, mass=m2)),
                  interfaces=(Interface(), Interface()))
    a, width = 0.3 * ex.G, 0.25
    r = simulate_stack(stack, rk.RectanglePulse(amplitude=a, width=width), duration=4.0, options={"gravity": ex.G})
    impacts = r.events[r.events[:, 2] == -1]
    # the composite body about the floor corner it tips on: each block's own inertia about its
    # centre plus its mass times its squared distance from the corner (both centred on the corner's
    # vertical at b1 = w1/2)
    parts = [(m1, w1, h1, 0.5 * h1), (m2, w2, h2, h1 + 0.5 * h2)]
    mass = m1 + m2
    io = sum(m * (w * w + h * h) / 12.0 + m * ((0.5 * w1) ** 2 + y * y) for m, w, h, y in parts)
    h_c = sum(m * y for m, _, _, y in parts) / mass
    t_back, peak = ex.composite_rocking(mass, io, 0.5 * w1, h_c, a, width)
    case = (f"two-block stack that rocks as one (0.3 × 1 m, 40 kg, under a squat 0.5 × 0.5 m, 60 kg): rectangular "
            f"pulse 0.3 g for {width:g} s")
    whole = "the top block, squat (tan α2 = 1), never rocks on the plinth: the stack is one body"
    return [
        Row("ST1.6", "Psycharis 1990 (the stack as one body)", f"{case}; largest rotation", "crosscheck", exact=peak,
            ours=r.blocks[0]["peak_rotation"], unit="rad", tol=1e-8, note=whole,
            published_label="Housner's equation of the composite body",
            passed=r.blocks[1]["first_rocking_time"] is None),
        Row("ST1.7", "Psycharis 1990 (the stack as one body)", f"{case}; time of the first impact", "crosscheck",
            exact=t_back, ours=float(impacts[0, 0]) if len(impacts) else None, unit="s", tol=1e-9,
            published_label="Housner's equation of the composite body"),
    ]


def stack_rows() -> list[Row]:
    from rocking.stack import Block, Interface, Stack

    rows = []
    # the whole stack rocks first: two centred blocks of one width, the top one squat
    m1, m2, b1, h1, h2 = 40.0, 60.0, 0.15, 1.0, 0.5
    whole = Stack(blocks=(Block(width=2 * b1, height=h1, mass=m1), Block(width=2 * b1, height=h2, mass=m2)),
                  interfaces=(Interface(), Interface()))
    h_c = (m1 * h1 / 2 + m2 * (h1 + h2 / 2)) / (m1 + m2)
    rows.append(Row("ST1.1", "Psycharis 1990", "two-block stack, both blocks centred (B = 0.3 m; H1 = 1 m, 40 kg; "
                                               "H2 = 0.5 m, 60 kg): uplift of the whole stack at a_g = g·b1/h_c "
                                               "(h_c: height of the combined centre of mass), slow ramp from rest",
                    "exact", published=ex.G * b1 / h_c, ours=_ramp_onset(whole, 0), unit="m/s²", tol=1e-6,
                    note="the top block's own threshold, g·b2/h2 = 0.6 g, is higher: the stack rocks as one"))
    # the top block rocks first: a slender statue on a wide heavy plinth
    top = Stack(blocks=(Block(width=2.0, height=0.3, mass=500.0), Block(width=0.3, height=1.2, mass=50.0)),
                interfaces=(Interface(), Interface()))
    rows.append(Row("ST1.2", "Psycharis 1990", "two-block stack: uplift of the top block alone (0.3 × 1.2 m on a "
                                               "2 × 0.3 m plinth) at a_g = g·b2/h2; the smaller threshold starts the "
                                               "motion", "exact", published=ex.G * 0.15 / 0.6, ours=_ramp_onset(top, 1),
                    unit="m/s²", tol=1e-6))
    # the top block slides first: friction on its face below both rocking thresholds and the floor's
    slides = Stack(blocks=(Block(width=2.0, height=0.3, mass=500.0), Block(width=0.6, height=0.6, mass=50.0)),
                   interfaces=(Interface(), Interface(friction=rk.Friction(static=0.15, kinetic=0.1))))
    rows.append(Row("ST1.4", "Coulomb; Shenton 1996's slide-first branch, on the top face",
                    "two-block stack (0.6 × 0.6 m on a 2 × 0.3 m plinth, held by the floor), top face μs = 0.15: the "
                    "top block slides at a_g = μs·g, below its rocking threshold g·b2/h2 = g", "exact",
                    published=0.15 * ex.G, ours=_ramp_onset(slides, 1, what="first_sliding_time"), unit="m/s²",
                    tol=1e-6))
    # the whole stack slides first: the floor face is the weaker one
    floor = Stack(blocks=(Block(width=2.0, height=0.3, mass=500.0), Block(width=0.6, height=0.6, mass=50.0)),
                  interfaces=(Interface(friction=rk.Friction(static=0.12, kinetic=0.1)),
                              Interface(friction=rk.Friction(static=0.3, kinetic=0.25))))
    rows.append(Row("ST1.5", "Coulomb; Shenton 1996's slide-first branch, on the floor",
                    "the same stack with floor μs = 0.12 under a top face μs = 0.3: the stack slides as one at "
                    "a_g = μs,floor·g; the top block does not slide", "exact", published=0.12 * ex.G,
                    ours=_ramp_onset(floor, 0, what="first_sliding_time"), unit="m/s²", tol=1e-6))
    rows.extend(_composite_rows())
    rows.append(Row("ST1.3", "Makris & Vassiliou 2013",
                    "rocking frame (columns and a free cap beam): p̂ = p·√((1+2γ)/(1+3γ)), "
                    "η̂ = (1 − 1.5 sin²α + 3γ cos 2α)/(1 + 3γ)", "pending",
                    note="a frame stands on several columns side by side; the stack engine takes one block on another"))
    return rows


INTRO_REDUCTION = """\
The statue on a sliding pedestal, the library's main model, has no published closed form of its own.
What can be checked is that it reduces to the validated cases: with a pedestal the floor holds it is
Housner's block (§1–2), with a statue that cannot rock it is Newmark's sliding block (§6), and with
μs ≤ tan α the statue never rocks (the slide-before-rock branch of Shenton's criterion, §5). The
paper's own case studies are compared in `docs/paper-case-studies.md`."""

INTRO_STACKS = """\
Stacks of blocks (a statue on a plinth that can itself rock) run on the general stack engine
(`rocking.stack`, `docs/theory/stack.md`). Under a slow ramp from rest, which motion starts first
and at what floor acceleration: the top block rocking, the stack rocking as one, the top block
sliding, the stack sliding (the smallest of the four thresholds wins). Once the stack rocks as one
body, its motion is that of Housner's equation for the composite body (its mass, its centre of mass
and its inertia about the floor corner), integrated here with SciPy. A rocking frame (columns with
a free cap beam) is not a stack of one block on another and waits for a multi-contact model."""


def sections(quick: bool, progress) -> list[Section]:
    progress("pedestal model: reductions")
    return [Section("pedestal", "7. The statue-on-pedestal model: reduction to the validated cases", INTRO_REDUCTION,
                    reduction_rows(quick)),
            Section("stacks", "8. Two-block stacks", INTRO_STACKS, stack_rows())]
