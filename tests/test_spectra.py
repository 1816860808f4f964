"""Overturning spectra: mode-1 branches against O9/O9b, similarity (O10), the harmonic (1,1)
orbit (O11), and the safe islands found by scan + bisection."""

import math
import re
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

import rocking as rk
from rocking.analyses.spectra import (
    island_bands,
    overturning_spectrum,
    plot_spectra,
    plot_spectra_overlay,
    spectrum_motion,
)
from rocking.excitation.base import KIND_HARMONIC, AbstractMotion, Signal

G = 9.81
OPTS = rk.Options(gravity=G)


def slender(alpha, h=1.0, **kw):
    """A statue of slenderness α and half-height h."""
    return rk.Statue(width=2 * h * math.tan(alpha), height=2 * h, mass=1.0, **kw)


# ------------------------------------------------------------------------- closed forms
def one_sine_mode1(beta):
    """O9: a_p/(gα) = 1/sin ψ with (cos ψ − β sin ψ)·exp((2π − ψ)/β) = 1 on 0 < ψ < atan(1/β)."""
    f = lambda psi: (math.cos(psi) - beta * math.sin(psi)) * math.exp((2 * math.pi - psi) / beta) - 1.0
    psi = brentq(f, 1e-12, math.atan(1.0 / beta) - 1e-12, xtol=1e-15)
    return 1.0 / math.sin(psi)


def one_cosine_mode1(beta):
    """O9b: a_p/(gα) = (1 + β²)/(1 − exp(−2π/β))."""
    return (1 + beta**2) / (1 - math.exp(-2 * math.pi / beta))


def test_closed_forms_reproduce_the_oracle_tables():
    for beta, value in ((0.5, 1.118050), (1, 1.418315), (2, 2.349903), (4, 5.238964), (8, 14.871352)):
        assert one_sine_mode1(beta) == pytest.approx(value, abs=2e-6)
    for beta, value in ((0.5, 1.250004), (1, 2.003742), (2, 5.225829), (4, 21.461383)):
        assert one_cosine_mode1(beta) == pytest.approx(value, abs=2e-6)


# --------------------------------------------------------------------- O9 / O9b, mode 1
BETAS = (0.5, 1.0, 2.0, 4.0)


@pytest.fixture(scope="module")
def mode1():
    # α = 0.02 makes the nonlinear block close to the linearised one; mode 1 (overturning
    # before any impact) does not depend on the restitution.
    system = rk.System(statue=slender(0.02))
    return overturning_spectrum(system, ["sine", "cosine"], BETAS, criterion="no_impact", rtol=2e-4,
                                amplitude_range=(1.01, 30.0), n_scan=40, options=OPTS, workers=1)


def test_one_sine_mode1_matches_O9(mode1):
    got = mode1.amplitude_ratio.sel(pulse="sine").values
    want = [one_sine_mode1(b) for b in BETAS]
    # a_p/(g tan α) against a_p/(g α): 1.3e-4 apart at α = 0.02, inside the tolerance
    np.testing.assert_allclose(got, want, rtol=1e-3)
    assert not mode1.truncated.values.any()


def test_one_cosine_mode1_matches_O9b(mode1):
    got = mode1.amplitude_ratio.sel(pulse="cosine").values
    want = np.array([one_cosine_mode1(b) for b in BETAS])
    np.testing.assert_allclose(got[:3], want[:3], rtol=1e-3)
    # β = 4 needs a_p ≈ 0.43 g: the nonlinear block is 1.3e-3 below the linearised value
    # (oracle O9b lists the solver at 21.433903)
    assert got[3] == pytest.approx(want[3], rel=2e-3)
    assert got[3] == pytest.approx(21.433903, rel=2e-4)


def test_mode1_boundary_is_bracketed_by_direct_runs(mode1):
    statue = slender(0.02)
    system = rk.System(statue=statue)
    p, gta = statue.frequency_parameter(G), G * math.tan(statue.slenderness)
    for shape in ("sine", "cosine"):
        lo = float(mode1.amplitude_ratio_lower.sel(pulse=shape, frequency_ratio=2.0))
        hi = float(mode1.amplitude_ratio_upper.sel(pulse=shape, frequency_ratio=2.0))
        assert hi - lo <= 2e-4 * hi
        outcome = []
        for A in (lo, hi):
            m = spectrum_motion(shape, A, 2.0, g_tan_alpha=gta, p=p)
            s = rk.simulate(system, m, duration=m.duration + 25 / p, options=OPTS, save=False).summary()
            outcome.append(s["overturned"] and s["impacts"] == 0)
        assert outcome == [False, True]


def test_one_sine_pulse_starts_rocking_at_t0():
    statue = slender(0.02)
    p, gta = statue.frequency_parameter(G), G * math.tan(statue.slenderness)
    m = spectrum_motion("sine", 1.7, 1.0, g_tan_alpha=gta, p=p)
    assert m.phase == pytest.approx(math.asin(1 / 1.7))
    assert float(m.acceleration(np.array([0.0]))[0]) == pytest.approx(gta)


# -------------------------------------------------------------------------- O10 similarity
def test_similarity_law_O10_spectra_identical_for_two_sizes():
    """Blocks with the same α and η but sizes 1 and 4: identical dimensionless spectra."""
    kw = dict(frequency_ratios=[1.0, 2.5, 5.0], amplitude_range=(1.01, 40.0), n_scan=30, rtol=1e-3,
              options=OPTS, workers=1)
    small = overturning_spectrum(rk.System(statue=rk.Statue(width=0.5, height=2.0, mass=1.0)), ["sine", "cosine"], **kw)
    large = overturning_spectrum(rk.System(statue=rk.Statue(width=2.0, height=8.0, mass=7.0)), ["sine", "cosine"], **kw)
    assert large.attrs["p"] == pytest.approx(small.attrs["p"] / 2)
    np.testing.assert_array_equal(small.scan_fails.values, large.scan_fails.values)
    for name in ("amplitude_ratio", "amplitude_ratio_lower", "amplitude_ratio_upper", "island_lower", "island_upper"):
        np.testing.assert_allclose(small[name].values, large[name].values, rtol=1e-9, equal_nan=True, err_msg=name)
    assert np.all(np.isfinite(small.amplitude_ratio.values))


# --------------------------------------------------------------------------- safe islands
@pytest.fixture(scope="module")
def with_islands():
    statue = rk.Statue(width=0.4, height=2.0, mass=1.0)  # α ≈ 0.197, Housner η ≈ 0.94
    ds = overturning_spectrum(rk.System(statue=statue), ["cosine", "harmonic"], [1.0, 2.0, 4.0],
                              amplitude_range=(1.01, 10.0), n_scan=36, rtol=1e-3, cycles=3, options=OPTS, workers=2)
    return statue, ds


def test_every_reported_change_of_outcome_is_verified_by_direct_runs(with_islands):
    statue, ds = with_islands
    assert int(ds.n_islands.sel(pulse="cosine").sum()) >= 1, "the cosine pulse has safe islands"
    p, gta = statue.frequency_parameter(G), G * math.tan(statue.slenderness)
    system = rk.System(statue=statue)

    def falls(shape, A, beta):
        m = spectrum_motion(shape, A, beta, g_tan_alpha=gta, p=p, cycles=3)
        return rk.simulate(system, m, duration=m.duration + 25 / p, options=OPTS, save=False).overturned

    for shape in ds.pulse.values.tolist():
        for k, beta in enumerate(ds.frequency_ratio.values):
            sub = ds.sel(pulse=shape).isel(frequency_ratio=k)
            lo, hi = float(sub.amplitude_ratio_lower), float(sub.amplitude_ratio_upper)
            assert hi - lo <= 1e-3 * hi
            assert not falls(shape, lo, beta) and falls(shape, hi, beta)
            edges = [(a, b, up) for a, b, up in zip(sub.edge_lower.values, sub.edge_upper.values,
                                                    sub.edge_to_failure.values) if np.isfinite(a)]
            assert edges[0][:2] == (lo, hi) and edges[0][2]
            assert [e[2] for e in edges] == [i % 2 == 0 for i in range(len(edges))]  # alternate
            for a, b, up in edges:
                assert falls(shape, a, beta) != up and falls(shape, b, beta) == up
            # islands are the safe stretches between the edges above the first overturn
            n = int(sub.n_islands)
            assert n == len(edges) // 2
            mids = [0.5 * (a + b) for a, b, _ in edges]
            np.testing.assert_allclose(sub.island_lower.values[:n], mids[1::2])


def test_cosine_islands_are_safe_inside(with_islands):
    """The one-cosine pulse's islands (Zhang & Makris's safe region above the minimum) are
    plain bands: the block survives throughout them."""
    statue, ds = with_islands
    p, gta = statue.frequency_parameter(G), G * math.tan(statue.slenderness)
    system = rk.System(statue=statue)
    sub = ds.sel(pulse="cosine")
    top = float(ds.scan_amplitude_ratio.max())
    checked = 0
    for k, beta in enumerate(ds.frequency_ratio.values):
        for lo, hi in zip(sub.island_lower.values[k], sub.island_upper.values[k]):
            if not np.isfinite(lo):
                continue
            hi = min(hi, top)
            for A in np.geomspace(1.003 * lo, 0.997 * hi, 5):
                m = spectrum_motion("cosine", A, beta, g_tan_alpha=gta, p=p)
                assert not rk.simulate(system, m, duration=m.duration + 25 / p, options=OPTS, save=False).overturned
            checked += 1
    assert checked >= 1


def test_spectrum_chart_and_island_bands(with_islands):
    import matplotlib

    matplotlib.use("Agg")
    _, ds = with_islands
    bands = island_bands(ds, "cosine")
    assert all(len(b) == 3 and b[0].shape == b[1].shape == b[2].shape for b in bands)
    fig = plot_spectra(ds, title="test")
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert [ax.get_title() for ax in visible] == ["one-cosine pulse", "harmonic motion"]
    assert visible[0].get_xlabel().startswith("frequency ratio")
    # one y-range for every panel: the scanned amplitudes
    assert {ax.get_ylim() for ax in visible} == {(0.0, float(ds.scan_amplitude_ratio.max()))}
    # the legend in the strip above the panels, clear of the islands (of every axes)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    legend = fig.subfigs[0].legends[0]
    assert "safe island" in [t.get_text() for t in legend.get_texts()]
    box = legend.get_window_extent(canvas.get_renderer())
    assert not any(box.overlaps(ax.get_window_extent(canvas.get_renderer())) for ax in visible)
    ax = plot_spectra_overlay(ds)
    assert {t.get_text() for t in ax.get_legend().get_texts()} >= {"cosine", "harmonic", "safe island"}


def test_a_gap_in_the_boundary_says_nothing_overturned_in_the_scanned_range(with_islands):
    from rocking.analyses.spectra import spectrum_report
    from rocking.viz.plots import plot_spectrum

    _, ds = with_islands
    gap = ds.copy(deep=True)
    gap["amplitude_ratio"].loc[{"pulse": "cosine", "frequency_ratio": 4.0}] = np.nan
    report = spectrum_report(gap, title="gap")
    assert report.splitlines()[0] == "# gap"
    assert "Block 0.4 m × 2 m, α = 0.197 rad, p = " in report and ", r = 0.942; engine: system." in report
    row = next(line for line in report.splitlines() if line.startswith("| 4 |"))
    assert row.split(" | ")[1] == "none up to 10"
    assert "nan" not in report
    ax = plot_spectrum(frequency_ratio=[1.0, 2.0, 4.0], amplitude_ratio=[1.2, 1.5, np.nan], scan_top=10.0)
    grey = [p for p in ax.get_legend().get_patches() if p.get_label() == "no overturning up to 10"]
    assert len(grey) == 1
    assert [t.get_text() for t in ax.texts] == ["no overturning\nin the scanned range\n(up to 10)"]
    assert ax.get_legend().get_bbox_to_anchor().y0 > ax.get_window_extent().y1 - 1  # above the axes


def test_runs_the_solver_stopped_are_reported_as_they_were_counted(with_islands):
    """A run the solver stops before a verdict counts as failing by default, which can only lower
    the boundary; counted as safe (``undetermined="safe"``, or a dataset made before the option),
    it can only raise it. The report must say which (it said nothing until 2026-11-24)."""
    from rocking.analyses.spectra import spectrum_report

    _, ds = with_islands
    runs = int(ds.runs.sum())
    assert int(ds.failed_runs.sum()) == 0 and int(ds.undetermined_runs.sum()) == 0
    assert "stopped by the solver" not in spectrum_report(ds)
    stopped = ds.copy(deep=True)
    stopped["failed_runs"].values[0, 0] = 2
    stopped["undetermined_runs"].values[:] = 0
    stopped["undetermined_runs"].values[0, 0] = 3
    settled = int(ds.settling_runs.sum())
    assert settled > 0  # (71 with free_time 25: the islands' runs rock on for up to ~50/p)
    assert (f"{settled} of {runs} runs were still rocking at the end of their free motion with less energy than the "
            "block needs to overturn (on the still floor it can only lose energy): safe, decided.") in spectrum_report(ds)
    said = {"fail": "counted as failing, so a boundary may lie higher than shown",
            "safe": "counted as safe, so a boundary may lie lower than shown"}
    for rule in ("fail", "safe", None):
        if rule is None:
            del stopped.attrs["undetermined"]
        else:
            stopped.attrs["undetermined"] = rule
        report = spectrum_report(stopped)
        text = said[rule or "safe"]
        assert (f"**2 of {runs} runs were stopped by the solver before a verdict (too many events, or no "
                f"consistent contact mode): {text}.**") in report
        assert (f"**3 of {runs} runs were still moving at the end of their free motion: undetermined, "
                f"{text}.** Raise spectrum.free_time to decide them.") in report


def test_bad_inputs_are_refused():
    system = rk.System(statue=slender(0.1))
    with pytest.raises(ValueError, match="unknown spectrum motion"):
        overturning_spectrum(system, "square", [1.0], workers=1)
    with pytest.raises(ValueError, match="criterion"):
        overturning_spectrum(system, "sine", [1.0], criterion="maybe", workers=1)
    with pytest.raises(ValueError, match="undetermined must be one of fail, safe, got 'unsafe'"):
        overturning_spectrum(system, "sine", [1.0], undetermined="unsafe", workers=1)
    with pytest.raises(ValueError, match="amplitude_range"):
        overturning_spectrum(system, "sine", [1.0], amplitude_range=(3.0, 2.0), workers=1)


# ------------------------------------------------------------------- O11: harmonic orbits
@dataclass(frozen=True)
class PhasedSine(AbstractMotion):
    """a·sin(ωt + τ) for 0 ≤ t ≤ end: a harmonic motion with any phase (the compiled harmonic
    kind evaluates A·cos(ωt + φ), so φ = τ − π/2)."""

    amplitude: float
    omega: float
    tau: float
    end: float

    @property
    def duration(self):
        return self.end

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t <= self.end), self.amplitude * np.sin(self.omega * t + self.tau), 0.0)

    def signal(self):
        params = np.array([self.amplitude, self.omega, self.tau - 0.5 * math.pi, self.end])
        return Signal(KIND_HARMONIC, params, np.zeros(0), np.zeros(0))


ALPHA, ETA, BETA = 0.01, 0.9, 2.0


def _linear_orbits(A):
    """O11 (linearised): the phases τ and post-impact velocities φ̇(0⁺)/p of both (1,1) orbits."""
    lam = math.pi / BETA
    P = math.tanh(lam / 2)
    Q = 1 / P
    K = A / (1 + BETA**2)
    R = math.hypot(Q * (1 + ETA), BETA * (1 - ETA))
    phase = math.atan2(BETA * (1 - ETA), Q * (1 + ETA))
    s = -P * (1 - ETA) / (K * R)
    orbits = []
    for x in (math.asin(s), math.pi - math.asin(s)):
        tau = (x - phase) % (2 * math.pi)
        orbits.append((tau, P + Q * K * math.sin(tau) + BETA * K * math.cos(tau)))
    return orbits


def _a_min_linear():
    lam = math.pi / BETA
    P, Q = math.tanh(lam / 2), 1 / math.tanh(lam / 2)
    return (1 + BETA**2) * P * (1 - ETA) / math.sqrt(Q**2 * (1 + ETA) ** 2 + BETA**2 * (1 - ETA) ** 2)


@pytest.fixture(scope="module")
def orbit_block():
    statue = slender(ALPHA, restitution=ETA)  # small α: the nonlinear block is nearly linear
    p = statue.frequency_parameter(G)
    return rk.System(statue=statue), p, 2 * math.pi / (BETA * p)


def _start_on_orbit(orbit_block, A, tau, v, periods=1.0):
    """Start at θ = 0 just after an impact with θ̇ = v·p·α under a·sin(ωt + τ)."""
    system, p, T = orbit_block
    motion = PhasedSine(amplitude=A * G * ALPHA, omega=BETA * p, tau=tau % (2 * math.pi), end=2 * periods * T)
    r = rk.simulate(system, motion, duration=(periods + 0.2) * T, options=OPTS,
                    initial_angular_velocity=v * p * ALPHA, save=False)
    return r


def test_O11_orbits_are_periodic_in_the_solver(orbit_block):
    _, p, T = orbit_block
    orbits = _linear_orbits(0.5)
    assert orbits[0] == pytest.approx((5.98648601, 0.80247367), abs=1e-7)
    assert orbits[1] == pytest.approx((3.30044869, 0.43419072), abs=1e-7)
    for tau, v in orbits:
        r = _start_on_orbit(orbit_block, 0.5, tau, v)
        impacts = [i for i in r.impacts if i.time < 1.1 * T]
        assert len(impacts) == 2 and not r.overturned
        # one impact per half period, and after a full forcing period the state repeats
        assert impacts[0].time / T == pytest.approx(0.5, abs=5e-5)
        assert impacts[1].time / T == pytest.approx(1.0, abs=5e-5)
        assert impacts[0].theta_dot_after / (p * ALPHA) == pytest.approx(-v, rel=1e-4)
        assert impacts[1].theta_dot_after / (p * ALPHA) == pytest.approx(v, rel=1e-4)
        assert impacts[0].theta_dot_after / impacts[0].theta_dot_before == pytest.approx(ETA, rel=1e-9)


def test_O11_threshold_from_the_solver_by_shooting(orbit_block):
    """Find both orbits with the solver (shooting on phase and velocity) just above the
    linearised A_min; they merge at the fold, where (τ1 − τ2)² → 0. Extrapolating that to zero
    gives the solver's A_min, which must be the linearised 0.112907 (α = 0.01)."""
    _, p, T = orbit_block
    a_min = _a_min_linear()
    assert a_min == pytest.approx(0.112907, abs=1e-6)

    def residual(x, A):
        tau, v = x
        first = _start_on_orbit(orbit_block, A, tau, v, periods=0.5).impacts[0]
        return [first.time / T - 0.5, first.theta_dot_after / (p * ALPHA) + v]

    amplitudes, gaps = [], []
    for factor in (1.02, 1.05, 1.10):
        A = factor * a_min
        taus = []
        for tau0, v0 in _linear_orbits(A):
            x, info, ier, _ = fsolve(residual, [tau0, v0], args=(A,), full_output=True, xtol=1e-12)
            assert ier == 1 and np.max(np.abs(info["fvec"])) < 1e-9
            taus.append(x[0])
        amplitudes.append(A)
        gaps.append((taus[0] - taus[1]) ** 2)
    fold = np.polyfit(gaps, amplitudes, 2)[-1]
    assert fold == pytest.approx(0.112907, rel=2e-3)


SPECTRUM_TOML = """
[statue]
width = 0.4
height = 2.0
mass = 1.0

[spectrum]
motions = ["sine", "cosine"]
frequency_ratio = [1.0, 2.0, 3.0]
amplitude_ratio = [1.01, 10.0]
n_scan = 20

[simulation]
gravity = 9.81
"""


def test_spectrum_command(tmp_path, capsys):
    import importlib

    import xarray as xr

    from rocking.cli import studies

    cli_main = importlib.import_module("rocking.cli.main")
    if "spectrum" not in {c.name for c in cli_main.app.registered_commands}:
        studies.register(cli_main.app)  # until rocking.cli.main registers the studies itself
        cli_main._command.cache_clear()
    cfg = tmp_path / "block.toml"
    cfg.write_text(SPECTRUM_TOML)
    out = tmp_path / "out"
    assert cli_main.main(["spectrum", str(cfg), "--out", str(out), "--workers", "1"]) == 0
    assert "minimum overturning a_p/(g tan α)" in capsys.readouterr().out
    rows = (out / "spectrum.csv").read_text().splitlines()
    assert rows[0].startswith("motion,frequency_ratio,amplitude_ratio") and len(rows) == 1 + 6
    assert (out / "spectrum.png").stat().st_size > 0
    report = (out / "spectrum_report.md").read_text()
    assert report.startswith("# Overturning spectra: block.toml") and "![overturning spectra](spectrum.png)" in report
    with xr.open_dataset(out / "spectrum.nc", engine="h5netcdf") as ds:
        api = overturning_spectrum(rk.System(statue=rk.Statue(width=0.4, height=2.0, mass=1.0)), ["sine", "cosine"],
                                   [1.0, 2.0, 3.0], amplitude_range=(1.01, 10.0), n_scan=20, options=OPTS, workers=1)
        np.testing.assert_array_equal(ds.amplitude_ratio.values, api.amplitude_ratio.values)
    # a run the solver stops (here after its second event) counts as failing, and the command says
    # so; with undetermined = "safe", as safe
    stopped = SPECTRUM_TOML.replace("gravity = 9.81", "gravity = 9.81\nmax_events = 2")
    boundary = {}
    for rule in ("fail", "safe"):
        cfg.write_text(stopped.replace("[spectrum]", f'[spectrum]\nundetermined = "{rule}"'))
        assert cli_main.main(["spectrum", str(cfg), "--out", str(tmp_path / rule), "--workers", "1"]) == 0
        said = capsys.readouterr().out
        counted = {"fail": "failing, so a boundary may lie higher", "safe": "safe, so a boundary may lie lower"}[rule]
        assert re.search(r"warning: \d+ of \d+ runs were stopped by the solver before a verdict: counted as "
                         + counted, said)
        with xr.open_dataset(tmp_path / rule / "spectrum.nc", engine="h5netcdf") as got:
            assert got.attrs["undetermined"] == rule and int(got.failed_runs.sum()) > 0
            boundary[rule] = np.nan_to_num(got.amplitude_ratio_upper.values, nan=np.inf)
    assert np.all(boundary["fail"] <= boundary["safe"]) and np.any(boundary["fail"] < boundary["safe"])
    cfg.write_text(SPECTRUM_TOML.replace("[spectrum]", '[spectrum]\nundetermined = "maybe"'))
    assert cli_main.main(["spectrum", str(cfg), "--out", str(out)]) == 2
    assert "spectrum.undetermined" in capsys.readouterr().err
    cfg.write_text(SPECTRUM_TOML.replace('"cosine"]', '"square"]'))
    assert cli_main.main(["spectrum", str(cfg), "--out", str(out)]) == 2
    assert "spectrum.motions" in capsys.readouterr().err


def test_a_pedestal_that_would_tip_fails_the_scan_where_it_first_would():
    """A squat statue (tan α = 0.833) on a pedestal 0.3 m wide and 1 m tall (50 kg each) that
    friction (μs = 0.8) holds, under one-sine pulses. The statue moves with the floor; the floor's
    reaction leaves the pedestal's base once |a_g|/g > b₁(m₁ + m₂)/(m₁H₁/2 + m₂(H₁ + h₂)) = 1/7
    (derivation §3.5, h₂ = 0.6 m the statue's centre above its base), so the pedestal would tip
    from a_p/(g tan α) = (1/7)/0.833 = 0.1714 on, at every β (the pulse reaches its peak), far
    below where the statue could rock (1). That fails the scan (a fall risk the two-body model
    does not follow), and the report says so. Until 2026-12-02 runs below a_p = g tan α were
    skipped as "nothing can happen" and the spectrum said "none up to 1"; until 2026-12-06 the
    check left out the statue's own couple and the boundary read 0.24."""
    from rocking.analyses.spectra import spectrum_report

    statue = rk.Statue(width=1.0, height=1.2, mass=50.0)
    pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=0.8, kinetic=0.7), width=0.3, height=1.0)
    ds = overturning_spectrum(rk.System(statue=statue, pedestal=pedestal), "sine", [1.0, 3.0],
                              amplitude_range=(0.1, 1.0), n_scan=10, rtol=1e-4, free_time=2.0, options=OPTS, workers=1)
    np.testing.assert_allclose(ds.amplitude_ratio.values[0], 1.2 / 7.0, rtol=2e-4)
    assert int(ds.pedestal_tips_runs.sum()) > 0
    assert "runs the pedestal would tip" in spectrum_report(ds)


def test_a_pedestal_that_would_tip_fails_even_where_the_statue_cannot_fall_any_more(monkeypatch):
    """A run still moving at its cap with too little energy for the statue to fall is decided
    safe (``settling_runs``), but not where the pedestal would have tipped on the way: that is a
    fall risk the two-body model does not follow, failing under every criterion whatever the
    statue's energy (a solver summary made up here: still moving, the uplift at 0.5 s, settled by
    the solver's energy rule). Without the uplift the same summary is settled. Under "exceed" a
    settled run that had passed α before (``S_EXCEED_TIME``) still fails: the energy rule says
    only that it cannot reach α again."""
    import dataclasses as dc

    from rocking.analyses import batch
    from rocking.analyses.spectra import SpectrumTask, _fails
    from rocking.solver import compiled as C

    statue = rk.Statue(width=0.4, height=2.0, mass=10.0)
    pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=0.8, kinetic=0.7), width=0.3, height=1.0)
    raw = np.full(C.N_SUMMARY, np.nan)
    raw[[C.S_STATUS, C.S_IMPACTS, C.S_SETTLED]] = C.STATUS_STILL_MOVING, 3, 1.0
    # counted: the run (0), still moving (2) and the pedestal tipping (4); or the run and settled (7)
    tipping, settled = [1, 0, 1, 0, 1, 0, 0, 0], [1, 0, 0, 0, 0, 0, 0, 1]
    for uplift, exceeded, criterion, fails, counted in (
            (0.5, math.nan, "overturn", True, tipping), (math.nan, math.nan, "overturn", False, settled),
            (math.nan, 0.7, "overturn", False, settled), (math.nan, 0.7, "exceed", True, settled),
            (math.nan, math.nan, "exceed", False, settled), (math.nan, 0.7, "no_impact", False, settled)):
        raw[C.S_UPLIFT], raw[C.S_EXCEED_TIME] = uplift, exceeded
        monkeypatch.setattr(batch, "run_raw", lambda *a, raw=raw.copy(): raw)
        task = SpectrumTask(rk.System(statue=statue, pedestal=pedestal), "sine", (2.0,), (2.0,), 1e-3, criterion,
                            "onset", 3.0, 25.0, OPTS)
        counter = [0] * 8
        assert _fails(task, 2.0, 2.0, G * 0.2, 2.0, counter, dc.replace(OPTS, free_time_limit=10.0)) is fails
        assert counter == counted


def test_a_run_in_which_the_block_would_jump_counts_as_failing():
    """A 0.5 × 2 m block under one-cosine pulses at ω_p/p = 5, from 20 to 30 g tan α: the Housner
    model overturns it only near 31 g tan α, but from about 25.9 g tan α the block's base force
    reaches zero while it stands (status ``lifted_off``): it would jump, which the model does not
    follow. Such a run is a fall risk, failing like a pedestal that would tip, so the boundary is
    the first amplitude whose run lifts off: the run at the bracket's lower end does not
    (completed, at rest), the one at its upper end does. Until 2026-12-03 the scan said "none up
    to 30"."""
    from rocking.analyses.spectra import spectrum_report

    statue = rk.Statue(width=0.5, height=2.0, mass=1.0)
    ds = overturning_spectrum(rk.System(statue=statue), "cosine", [5.0], amplitude_range=(20.0, 30.0), n_scan=6,
                              rtol=1e-3, options=OPTS, workers=1)
    lo, hi = float(ds.amplitude_ratio_lower.values[0, 0]), float(ds.amplitude_ratio_upper.values[0, 0])
    assert 20.0 < lo < hi <= lo * (1 + 2e-3) and int(ds.lifted_off_runs.sum()) > 0
    p, gta = statue.frequency_parameter(G), G * math.tan(statue.slenderness)
    status = [rk.simulate(rk.System(statue=statue), spectrum_motion("cosine", a, 5.0, g_tan_alpha=gta, p=p),
                          options=OPTS).status for a in (lo, hi)]
    assert status == ["completed", "lifted_off"]
    assert "would leave its support" in spectrum_report(ds, chart=None)
