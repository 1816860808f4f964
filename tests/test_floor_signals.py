"""The compiled floor acceleration against each motion's own ``acceleration(t)``.

The solver never calls ``motion.acceleration``: it integrates with the piece table that
``rocking.solver.compiled._piece_table`` builds from the motion's signal and breakpoints, read by
``rocking.excitation.signal.local_value``. A wrong formula there (a Ricker pulse with 1 − x for
1 − 2x, a sine pulse off by its phase) changes every response and nothing else would notice, so
every motion kind is checked here at random times inside every piece, horizontal and vertical.

Tolerance: rtol 1e-14, plus an absolute 1e-14 of the signal's peak. Both sides evaluate the same
formula in float64, so they agree to a few ulps; only at a zero crossing is a pointwise relative
error meaningless (the sine pulse is evaluated as a cosine of a phase shifted by π/2, whose
rounding, ≤ 1e-15 of the peak, is then all there is).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import G, alone, block

import rocking as rk
from rocking.excitation.record import GroundMotion
from rocking.excitation.signal import LOCAL_SIZE, crest_inside, evaluate, local_value, next_crest
from rocking.io.records import read_record
from rocking.simulation import prepare
from rocking.solver.compiled import _piece_table

RTOL = 1e-14
SYSTEM = alone(block(0.5, 2.0))


def _rng(name: str) -> np.random.Generator:
    return np.random.default_rng(sum(map(ord, name)))


def _pieces(motion, t_end):
    """(table, edges) as the solver gets them: row i of the table holds the formulas valid on
    [edges[i], edges[i + 1]] (horizontal in columns 0–4, vertical in 5–9)."""
    _, args = prepare(SYSTEM, motion, duration=t_end, options=rk.Options(gravity=G))
    sig_h, sig_v, breakpoints, t0, t_end_solver = args[1:6]
    assert t0 == 0.0 and t_end_solver == t_end
    table = _piece_table(sig_h, sig_v, breakpoints, t0, t_end_solver)
    edges = np.concatenate(([t0], breakpoints, [t_end_solver]))
    assert table.shape == (edges.size - 1, 2 * LOCAL_SIZE)
    return table, edges


def _times_inside(rng, lo, hi, k):
    """k random times strictly inside (lo, hi), plus two within 1e-9 of its ends."""
    u = np.concatenate((rng.uniform(0.0, 1.0, k), [1e-9, 1.0 - 1e-9]))
    t = lo + u * (hi - lo)
    return t[(t > lo) & (t < hi)]


def _compare(motion, t_end, *, per_piece=3, max_pieces=None, seed="x"):
    """Check both components of the piece table at random times of (a sample of) its pieces.
    Returns the number of points checked."""
    rng = _rng(seed)
    table, edges = _pieces(motion, t_end)
    rows = np.arange(table.shape[0])
    if max_pieces is not None and rows.size > max_pieces:
        rows = np.sort(rng.choice(rows, max_pieces, replace=False))
    ts, got_h, got_v = [], [], []
    for i in rows:
        loc = tuple(float(v) for v in table[i])
        for t in _times_inside(rng, edges[i], edges[i + 1], per_piece):
            ts.append(t)
            got_h.append(local_value(loc, 0, t))
            got_v.append(local_value(loc, LOCAL_SIZE, t))
    ts = np.array(ts)
    want_h = motion.acceleration(ts)
    want_v = motion.vertical_acceleration(ts)
    peak_h = max(np.max(np.abs(want_h)), 1e-300)
    peak_v = max(np.max(np.abs(want_v)), 1e-300)
    np.testing.assert_allclose(got_h, want_h, rtol=RTOL, atol=RTOL * peak_h)
    np.testing.assert_allclose(got_v, want_v, rtol=RTOL, atol=RTOL * peak_v)
    # The motion must not be trivially zero where the solver sees it (a test of nothing).
    assert np.count_nonzero(want_h) > 0.5 * np.count_nonzero(ts < motion.duration)
    return ts.size


ANALYTIC = {
    "harmonic cos": rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=3),
    "harmonic sin": rk.Harmonic(amplitude=4.0, frequency=2.5, cycles=4.5, form="sin"),
    "harmonic reversed, rounded ω": rk.Harmonic(amplitude=-6.75, frequency=1.2, cycles=5, angular_frequency=7.53),
    "harmonic many cycles": rk.Harmonic(amplitude=3.0, frequency=1.7, cycles=30),
    "harmonic, slow (ω < 1 rad/s)": rk.Harmonic(amplitude=2.0, frequency=0.12, cycles=1.5, form="sin"),
    "sine pulse": rk.SinePulse(amplitude=5.0, frequency=1.5),
    "sine pulse with phase": rk.SinePulse(amplitude=-7.0, frequency=0.8, phase=0.37),
    "cosine pulse": rk.CosinePulse(amplitude=8.0, frequency=2.0),
    "rectangle pulse": rk.RectanglePulse(amplitude=-4.5, width=0.3),
    "ricker pulse": rk.RickerPulse(amplitude=9.0, frequency=1.3),
    "ricker pulse, given centre": rk.RickerPulse(amplitude=-3.0, frequency=0.7, center=3.1),
    "ramp": rk.Ramp(rate=2.5, end=1.7),
}


@pytest.mark.parametrize("name", list(ANALYTIC))
def test_piece_table_matches_every_analytic_motion(name):
    motion = ANALYTIC[name]
    # Past the end of the motion too: the last piece must read zero.
    n = _compare(motion, 1.25 * motion.duration + 0.5, per_piece=400, seed=name)
    assert n > 400


def _local_pieces(motion):
    """(loc, start, end) of every piece of the motion's table, as the solvers localise them."""
    table, edges = _pieces(motion, motion.duration)
    return [(tuple(float(v) for v in table[i]), edges[i], edges[i + 1]) for i in range(table.shape[0])]


def _is_crest(motion, t, gap):
    """Whether |a| of the motion's own ``acceleration`` at t is at least its value ``gap`` s either side."""
    here = abs(float(motion.acceleration(t)))
    return here >= abs(float(motion.acceleration(t - gap))) and here >= abs(float(motion.acceleration(t + gap)))


@pytest.mark.parametrize("name", list(ANALYTIC))
def test_crest_inside_gives_the_largest_acceleration_between_any_two_times(name):
    """crest_inside is how both solvers read the friction a face at rest needs between two
    instants (|a_h|/(g + a_v) is largest at an end or at the crest it returns). Checked at 60
    random stretches of every piece against the motion's own ``acceleration`` sampled at 20 001
    points: the largest of |a| at the two ends and at the crest must not fall below the
    sampled maximum (a missed crest falls short by up to the whole swing), and the crest must lie
    inside the stretch and be a local maximum of |a|. The sampling's own error is below
    ½·|a''|·Δt² ≤ 1e-7 of the peak here, so 1e-12 of the peak is the allowance."""
    motion = ANALYTIC[name]
    rng = _rng(name + " crest")
    found = 0
    for loc, lo, hi in _local_pieces(motion):
        for _ in range(60):
            t_a, t_b = np.sort(rng.uniform(lo, hi, 2))
            tau = crest_inside(loc, t_a, t_b)
            best = max(abs(motion.acceleration(t_a)), abs(motion.acceleration(t_b)))
            if not math.isnan(tau):
                found += 1
                assert t_a < tau < t_b
                assert _is_crest(motion, tau, 1e-5 * (t_b - t_a))
                best = max(best, abs(float(motion.acceleration(tau))))
            dense = float(np.max(np.abs(motion.acceleration(np.linspace(t_a, t_b, 20_001)))))
            assert best >= dense - 1e-12 * motion.pga
    if name in ("rectangle pulse", "ramp"):
        assert found == 0  # linear pieces: largest at an end
    else:
        assert found >= 10  # (a test of something: crests inside many stretches)


@pytest.mark.parametrize("name", list(ANALYTIC))
def test_next_crest_is_the_first_local_maximum_of_the_acceleration_after_any_time(name):
    """next_crest orders the search for the first instant a check at rest fails, so it must not
    skip a crest: from 60 random times in each piece, the returned time must be a local maximum
    of |a| (the motion's own ``acceleration``, 1e-5 of the gap either side), and |a| sampled at
    20 001 points from the start to it must have no interior local maximum higher than the
    sampling's own rounding (a skipped crest shows as one). inf for the linear pieces of the
    rectangle and the ramp, and past a pulse's last crest."""
    motion = ANALYTIC[name]
    rng = _rng(name + " next crest")
    found = 0
    for loc, lo, hi in _local_pieces(motion):
        for t in rng.uniform(lo, hi, 60):
            c = next_crest(loc, t)
            if math.isinf(c):
                continue
            found += 1
            assert c > t
            end = min(c, hi)  # (a crest past the piece's end is the formula's, clamped by its callers)
            if c < hi:
                assert _is_crest(motion, c, 1e-5 * (c - t))
            a = np.abs(motion.acceleration(np.linspace(t, end, 20_001)))
            inner = a[1:-1]
            peaks = (inner > a[:-2]) & (inner > a[2:]) & (inner > 1e-9 * motion.pga)
            assert not peaks[:-1].any()  # (the last sample's neighbour is the crest itself)
    if name in ("rectangle pulse", "ramp"):
        assert found == 0
    else:
        assert found >= 20


def test_next_crest_from_a_crest_is_the_next_one():
    """From a time at a cosine's crest, as computed in floating point ((kπ − φ)/ω), the next
    crest is π/ω later, whichever side of the crest the rounding put that time (the phase
    (ω t + φ)/π then falls just below or just above k; below, the formula gives t itself, and the
    next crest must be taken). 2000 random crests; rtol 1e-9 on π/ω covers the rounding of t."""
    rng = np.random.default_rng(12)
    for _ in range(2000):
        omega, phase, k = rng.uniform(0.5, 60.0), rng.uniform(-10.0, 10.0), int(rng.integers(5, 400))
        t = (k * math.pi - phase) / omega
        c = next_crest((2.0, 3.0, omega, phase, 0.0), t)
        assert c > t
        assert c - t == pytest.approx(math.pi / omega, rel=1e-9)


def test_ricker_pulse_values_at_known_points():
    """The wavelet itself, independently of both implementations: a_p at t0, zero where
    2π²f²τ² = 1, and a_p·(1 − 2·π²/4)·e^{−π²/4} at τ = 1/(2f)."""
    f, a_p = 1.3, 9.0
    motion = rk.RickerPulse(amplitude=a_p, frequency=f)
    table, edges = _pieces(motion, motion.duration)
    loc = tuple(float(v) for v in table[0])
    t0 = 1.5 / f
    assert local_value(loc, 0, t0) == pytest.approx(a_p, rel=1e-15)
    assert local_value(loc, 0, t0 + 1.0 / (math.sqrt(2.0) * math.pi * f)) == pytest.approx(0.0, abs=1e-14 * a_p)
    x = math.pi**2 / 4
    assert local_value(loc, 0, t0 + 0.5 / f) == pytest.approx(a_p * (1 - 2 * x) * math.exp(-x), rel=1e-14)


def test_piece_table_matches_a_record_with_a_vertical_component():
    rng = np.random.default_rng(12)
    # Uneven sampling, a first sample after t = 0 and a vertical history: every branch of the
    # sampled kind, on both columns of the table.
    t = 0.2 + np.cumsum(rng.uniform(0.003, 0.02, 400))
    motion = GroundMotion.from_arrays(t, rng.normal(0.0, 2.0, t.size), vertical=rng.normal(0.0, 1.0, t.size))
    n = _compare(motion, motion.duration + 0.7, per_piece=5, seed="vertical")
    assert n > 2000
    # The vertical column really carries the vertical history (it is not all zero).
    table, _ = _pieces(motion, motion.duration)
    assert np.count_nonzero(table[:, LOCAL_SIZE + 1]) > 300


@pytest.mark.parametrize("stem", ["Northridge1994_RinaldiReceivingSta_228", "LAquila2009_AQV_HNE_ESM",
                                  "Northridge1994_CastaicOldRidgeRoute_090_2col"])
def test_piece_table_matches_bundled_records(stem):
    """One record of each format; its breakpoints are its sample times, so a piece that spans a
    sample (a breakpoint lost) would show as a kink missed between two samples."""
    motion = read_record(stem)
    n = _compare(motion, motion.duration + 1.0, per_piece=3, max_pieces=3000, seed=stem)
    assert n > 9000


def test_piece_table_of_a_trimmed_and_scaled_record():
    motion = read_record("Kobe1995_Takatori_000").scaled(pga=3.0).trimmed(7.3456)
    assert motion.time[-1] == 7.3456  # an interpolated last sample
    _compare(motion, 9.0, per_piece=3, max_pieces=1500, seed="trimmed")


@pytest.mark.parametrize("name", list(ANALYTIC))
def test_direct_evaluator_matches_every_analytic_motion(name):
    """``signal.evaluate``, the other compiled evaluator (one formula per call, no table)."""
    motion = ANALYTIC[name]
    rng = _rng(name)
    sig = motion.signal()
    bps = np.unique(np.concatenate(([0.0], np.asarray(motion.breakpoints, float), [1.2 * motion.duration])))
    ts = np.concatenate([_times_inside(rng, lo, hi, 200) for lo, hi in zip(bps[:-1], bps[1:])])
    got = np.array([evaluate(sig.kind, sig.params, sig.time, sig.values, t, t) for t in ts])
    want = motion.acceleration(ts)
    np.testing.assert_allclose(got, want, rtol=RTOL, atol=RTOL * np.max(np.abs(want)))


def test_direct_evaluator_matches_a_record():
    rng = np.random.default_rng(5)
    t = np.cumsum(rng.uniform(0.004, 0.015, 300))
    motion = GroundMotion.from_arrays(t, rng.normal(0.0, 2.0, t.size), vertical=rng.normal(0.0, 1.0, t.size))
    for sig, reference in ((motion.signal(), motion.acceleration), (motion.vertical_signal(), motion.vertical_acceleration)):
        ts = np.concatenate([_times_inside(rng, lo, hi, 2) for lo, hi in zip(t[:-1], t[1:])])
        got = np.array([evaluate(sig.kind, sig.params, sig.time, sig.values, x, x) for x in ts])
        want = reference(ts)
        np.testing.assert_allclose(got, want, rtol=RTOL, atol=RTOL * np.max(np.abs(want)))

