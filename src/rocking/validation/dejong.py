"""Dimitrakopoulos & DeJong (2012): the similarity law and the closed-form (small-angle)
response."""

from __future__ import annotations

import math

import numpy as np

from rocking.analyses.spectra import overturning_spectrum

from . import exact as ex
from . import lib
from .rows import Row, Section

SRC = "Dimitrakopoulos & DeJong 2012"


def similarity_rows(quick: bool) -> list[Row]:
    """Blocks of the same α and sizes k = 1, 4, 16 under one-sine pulses with the same
    a_p/(g tan α) and ω_p/p: identical θ/α against p·t (impact times, peak), and identical
    spectra."""
    A, beta = 1.3, 3.0  # the block rocks through several impacts and survives
    sizes = (1.0, 4.0, 16.0)  # cheap: the quick manual computes the same rows
    runs = []
    for k in sizes:
        blk = ex.Block(0.25 * k, 1.0 * k)
        r = lib.simulate(lib.alone(blk), lib.sine_pulse(blk, A, beta), save=False)
        runs.append((blk, r))
    base_blk, base = runs[0]
    n = min(6, min(len(r.impacts) for _, r in runs))
    d_time = max(abs(imp.time * blk.p - ref.time * base_blk.p)
                 for blk, r in runs[1:] for imp, ref in zip(r.impacts[:n], base.impacts[:n]))
    d_peak = max(abs(r.peak_rotation / blk.alpha - base.peak_rotation / base_blk.alpha) for blk, r in runs[1:])
    label = ", ".join(f"{k:g}" for k in sizes)
    rows = [
        Row("DD1.1", SRC, f"similarity: p·t of the first {n} impacts, blocks b = 0.25k, h = k (k = {label}) under a "
                          f"one-sine pulse A = {A:g}, β = {beta:g}: largest difference between sizes", "exact",
            published=0.0, ours=d_time, tol=1e-7,
            note="published: identical response in τ = p·t (tolerance: the solver's, in dimensionless time)"),
        Row("DD1.2", SRC, "similarity: peak θ/α of the same runs, largest difference between sizes", "exact",
            published=0.0, ours=d_peak, tol=1e-8),
    ]
    if not quick:
        betas = (2.0, 4.0)
        spectra = []
        for k in (1.0, 10.0):
            blk = ex.Block(0.25 * k, 1.0 * k)
            spectra.append(overturning_spectrum(lib.alone(blk), ["sine", "cosine"], list(betas), rtol=1e-6,
                                                n_scan=60, amplitude_range=(1.01, 30.0), options=lib.OPTIONS,
                                                workers=1))
        a, b = (s.amplitude_ratio.values for s in spectra)
        rows.append(Row("DD1.3", SRC, "similarity: minimum overturning a_p/(g·tan α) of one-sine and one-cosine "
                                      "pulses at β = 2, 4 for k = 1 and 10: largest relative difference",
                        "exact", published=0.0, ours=float(np.max(np.abs(a / b - 1.0))), tol=2e-6,
                        note="tolerance: two bisection steps (rtol 1e-6)"))
    return rows


def closed_form_rows(quick: bool) -> list[Row]:
    """The small-angle closed-form response to a one-sine pulse (rocking from t = 0) up to the
    first impact: its peak |θ|/α and p·t of the impact."""
    A, beta = 2.5, 3.0
    blocks = [ex.slender(0.02)] if quick else [ex.slender(0.02), ex.Block(0.25, 1.0), ex.Block(0.5, 1.0)]
    peak_lin, tau_lin = ex.one_sine_linear_response(A, beta)
    rows = []
    for i, blk in enumerate(blocks, 1):
        pulse = lib.sine_pulse(blk, A, beta)
        first = lib.simulate(lib.alone(blk), pulse, save=False).impacts[0].time
        # stop just before the first impact: the peak of the run is then that of the first swing
        r = lib.simulate(lib.alone(blk), pulse, save=False, duration=first * (1 - 1e-9))
        o = ex.rock(blk, ex.sine_pulse(A * blk.g * blk.tan_alpha, beta * blk.p, math.asin(1.0 / A)),
                    stop_after_impacts=1, free_time=20.0 / blk.p)
        case = f"one-sine A = a_p/(g·tan α) = {A:g}, β = {beta:g}, α = {blk.alpha:.3g} rad:"
        rows.append(Row(f"DD2.{2 * i - 1}", SRC, f"{case} peak θ/α before the first impact", "approx",
                        published=peak_lin, exact=o.turns[0] / blk.alpha, ours=r.peak_rotation / blk.alpha,
                        tol=1e-8))
        rows.append(Row(f"DD2.{2 * i}", SRC, f"{case} p·t of the first impact", "approx", published=tau_lin,
                        exact=o.impact_times[0] * blk.p, ours=first * blk.p, tol=1e-8))
    return rows


INTRO = """\
Written in τ = p·t, Housner's equation contains only α, η and the floor acceleration in units of g;
for a pulse, only a_p/(g·tan α) (or a_p/g), ω_p/p and the pulse's shape. Dimitrakopoulos & DeJong
state the consequence: blocks of the same slenderness (hence the same Housner η) respond
identically in dimensionless time to pulses with the same dimensionless amplitude and frequency,
and their overturning spectra coincide. They also solve the small-angle equation in closed form,
pulse by pulse. The closed-form response used here (one-sine pulse starting rocking at t = 0, up to
the first impact) is that solution, derived and evaluated here; their printed expressions were not
compared symbol by symbol."""


def section(quick: bool, progress) -> Section:
    progress("Dimitrakopoulos & DeJong: similarity and closed forms")
    closed = closed_form_rows(quick)
    rows = similarity_rows(quick) + closed
    errs = {}
    for r in closed:
        a = float(r.case.split("α = ")[1].split(" rad")[0])
        errs[a] = max(errs.get(a, 0.0), abs(r.published / r.exact - 1.0))
    validity = ["The small-angle closed-form response (one-sine pulse, A = 2.5, β = 3, to the first impact) is "
                "within " + ", ".join(f"{100 * e:.2g} % at α = {a:g}" for a, e in errs.items()) + " of the exact one."]
    return Section("dejong", "3. Dimitrakopoulos & DeJong (2012): similarity and closed forms", INTRO, rows,
                   validity=validity)
