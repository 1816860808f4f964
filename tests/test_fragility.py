"""Fragility: the lognormal maximum-likelihood fit recovers known parameters, its bands, and the
incremental dynamic analysis over bundled records."""

import math

import numpy as np
import pytest
from scipy.special import ndtr

import rocking as rk
from rocking.analyses.fragility import (
    fit_lognormal,
    fragility_curves,
    ida,
    load_record_set,
    lognormal_probability,
    plot_fragility_curves,
)

G = 9.81


# ------------------------------------------------------------------------------- the fit
def test_fit_recovers_known_parameters_from_binomial_counts():
    rng = np.random.default_rng(12)
    median, beta = 3.2, 0.45
    levels = np.geomspace(1.0, 9.0, 12)
    n = np.full(levels.size, 4000)
    k = rng.binomial(n, ndtr(np.log(levels / median) / beta))
    fit = fit_lognormal(levels, n, k)
    assert fit.converged and not fit.at_bound
    assert fit.median == pytest.approx(median, rel=0.01)
    assert fit.beta == pytest.approx(beta, rel=0.03)
    # the Fisher standard errors are of the size of the actual errors
    assert abs(math.log(fit.median / median)) < 4 * fit.se_ln_median
    assert abs(fit.beta - beta) < 4 * fit.se_beta
    assert fit.n_runs == n.sum() and fit.n_failed == k.sum()


def test_fit_is_the_maximum_of_the_binomial_likelihood():
    levels, n, k = np.array([1.0, 2.0, 4.0, 8.0]), np.array([20, 20, 20, 20]), np.array([1, 6, 13, 19])
    fit = fit_lognormal(levels, n, k)

    def loglik(m, b):
        p = np.clip(ndtr(np.log(levels / m) / b), 1e-300, 1 - 1e-16)
        return float(np.sum(k * np.log(p) + (n - k) * np.log1p(-p)))

    best = loglik(fit.median, fit.beta)
    assert best == pytest.approx(fit.log_likelihood, rel=1e-9)
    for dm in (0.97, 1.03):
        assert loglik(fit.median * dm, fit.beta) < best
    for db in (0.97, 1.03):
        assert loglik(fit.median, fit.beta * db) < best
    # observed information = inverse covariance: compare with a finite-difference Hessian
    h = 1e-4
    mu, b = math.log(fit.median), fit.beta
    f = lambda x, y: loglik(math.exp(x), y)
    hess = np.array([
        [(f(mu + h, b) - 2 * f(mu, b) + f(mu - h, b)) / h**2,
         (f(mu + h, b + h) - f(mu + h, b - h) - f(mu - h, b + h) + f(mu - h, b - h)) / (4 * h * h)],
        [0.0, (f(mu, b + h) - 2 * f(mu, b) + f(mu, b - h)) / h**2],
    ])
    hess[1, 0] = hess[0, 1]
    np.testing.assert_allclose(np.linalg.inv(fit.covariance), -hess, rtol=1e-4)


def test_fit_recovers_parameters_of_synthetic_ida_and_the_band_covers_them():
    """Records with lognormal capacities (an IDA with monotone outcomes): fit and bootstrap."""
    import xarray as xr

    rng = np.random.default_rng(5)
    median, beta, n_rec = 4.0, 0.5, 300
    capacity = median * np.exp(beta * rng.standard_normal(n_rec))
    levels = np.geomspace(1.0, 12.0, 10)
    fails = capacity[:, None] <= levels[None, :]
    ds = xr.Dataset(
        {"fall": (("system", "record", "level"), fails[None]), "exceed": (("system", "record", "level"), fails[None])},
        coords={"system": ["synthetic"], "record": np.arange(n_rec), "level": levels},
        attrs={"im": "pga", "im_units": "m/s²"},
    )
    curves = fragility_curves(ds, n_boot=200, confidence=0.95, seed=3)
    c = curves.sel(system="synthetic", mode="fall")
    assert float(c["im_median"]) == pytest.approx(median, rel=0.06)
    assert float(c["beta"]) == pytest.approx(beta, rel=0.15)
    assert float(c.im_median_lower) < median < float(c.im_median_upper)
    truth = lognormal_probability(curves.im.values, median, beta)
    inside = (c.band_lower.values - 0.01 <= truth) & (truth <= c.band_upper.values + 0.01)
    assert inside.mean() > 0.95
    # same seed, same band; the Fisher band is of a similar width
    again = fragility_curves(ds, n_boot=200, confidence=0.95, seed=3)
    np.testing.assert_array_equal(again.band_lower.values, curves.band_lower.values)
    fisher = fragility_curves(ds, band="fisher", confidence=0.95).sel(system="synthetic", mode="fall")
    w_boot = float(np.max(c.band_upper - c.band_lower))
    w_fish = float(np.max(fisher.band_upper - fisher.band_lower))
    assert 0.3 < w_fish / w_boot < 3.0


def test_fit_without_information_is_flagged():
    none = fit_lognormal([1.0, 2.0], [10, 10], [0, 0])
    assert none.at_bound and not math.isfinite(none.beta)
    every = fit_lognormal([1.0, 2.0], [10, 10], [10, 10])
    assert every.at_bound and not math.isfinite(every.beta)
    with pytest.raises(ValueError):
        fit_lognormal([1.0, -2.0], [10, 10], [1, 2])
    with pytest.raises(ValueError):
        fit_lognormal([1.0, 2.0], [10, 10], [11, 2])


# ------------------------------------------------------------------------------------ IDA
RECORDS = ("Northridge1994_RinaldiReceivingSta_228", "Kobe1995_Takatori_000", "Northridge1994_CastaicOldRidgeRoute_090_2col")
STATUE = rk.Statue(width=0.4, height=1.6, mass=200.0, friction=rk.Friction(static=0.5))
PEDESTAL = rk.Pedestal(mass=300.0, friction=rk.Friction(static=0.15, kinetic=0.12))
SYSTEMS = {"alone": rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=200.0)),
           "on pedestal": rk.System(statue=STATUE, pedestal=PEDESTAL)}


@pytest.fixture(scope="module")
def records():
    return load_record_set(list(RECORDS))


@pytest.fixture(scope="module")
def runs(records):
    return ida(SYSTEMS, records, [1.0, 3.0, 6.0, 10.0], free_time=3.0, options=rk.Options(gravity=G), workers=2)


def test_ida_runs_each_record_scaled_to_each_level(records, runs):
    assert runs.overturned.dims == ("system", "record", "level")
    assert runs.record.values.tolist() == list(RECORDS)
    rec = records["Kobe1995_Takatori_000"]
    for level in (3.0, 10.0):
        factor = float(runs.scale_factor.sel(record=rec.name, level=level))
        assert rec.scaled(factor).pga == pytest.approx(level, rel=1e-12)
        single = rk.simulate(SYSTEMS["on pedestal"], rec.scaled(factor), duration=rec.duration + 3.0,
                             options=rk.Options(gravity=G), save=False).summary()
        got = runs.sel(system="on pedestal", record=rec.name, level=level)
        assert bool(got.overturned) == single["overturned"]
        assert float(got.peak_rotation) == single["peak_rotation"]
        assert float(got.peak_sliding) == single["peak_sliding"]
    # falling implies exceeding θ/α = 1; nothing happens at the lowest level (1 m/s² < g tan α)
    assert not np.any(runs.fall.values & ~runs.exceed.values)
    assert not runs.exceed.sel(level=1.0).values.any()
    assert runs.exceed.values.any()


def test_ida_scales_in_pgv_too(records):
    ds = ida(SYSTEMS["alone"], {k: records[k] for k in RECORDS[:1]}, [0.2, 0.5], im="pgv", options=rk.Options(gravity=G),
             workers=1)
    rec = records[RECORDS[0]]
    np.testing.assert_allclose(ds.scale_factor.values[0], np.array([0.2, 0.5]) / rec.pgv)
    assert ds.attrs["im"] == "pgv" and ds.level.attrs["units"] == "m/s"


def test_fragility_curves_of_an_ida_and_the_chart(runs):
    import matplotlib

    matplotlib.use("Agg")
    curves = fragility_curves(runs, n_boot=50, seed=1)
    assert curves["im_median"].dims == ("system", "mode")
    assert curves.n_runs.values.max() == len(RECORDS)
    np.testing.assert_array_equal(curves.n_failed.sel(mode="fall").values, runs.fall.sum("record").values)
    ax = plot_fragility_curves(curves, "exceed", title="IDA")
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(lab.startswith("alone") for lab in labels) and any(lab.startswith("on pedestal") for lab in labels)
    assert "θ/α" in ax.get_ylabel()


def test_a_run_the_solver_stops_before_a_verdict_counts_as_a_fall_and_is_reported(records):
    """max_events = 3 stops every run with more than three events (status "max_events") long
    before its record ends: nothing is known about whether the statue stands, so the run may not
    count as a survival (it did until 2026-11-24, when a stopped run simply had no fall)."""
    from rocking.analyses.fragility import fragility_report_lines

    rec = {RECORDS[1]: records[RECORDS[1]]}
    ds = ida(SYSTEMS["alone"], rec, [1.0, 4.0], free_time=3.0, options=rk.Options(gravity=G, max_events=3), workers=1)
    status = ds.status.values[0, 0]
    # 1 m/s² < g tan α: at rest throughout; at 4 m/s² it rocks, and the run stops at its 4th event
    assert status.tolist() == ["completed", "max_events"]
    assert ds.fall.values[0, 0].tolist() == [False, True] and ds.exceed.values[0, 0].tolist() == [False, True]
    assert int(ds.solver_stopped.values[0]) == 1 and int(ds.undetermined.values[0]) == 1
    lines = fragility_report_lines(fragility_curves(ds, n_boot=10, seed=1), ds, free_time=3.0)
    text = "\n".join(lines)
    assert "1 run(s) were stopped by the solver before a verdict" in text and "still moving" not in text


def test_a_run_still_moving_with_too_little_energy_to_overturn_counts_as_a_survival():
    """A 0.4 × 1.6 m statue under one sine of 1 s (a record), its free motion cut after 0.2 s. At a
    PGA of 2 m/s² it never rocks; at 3 m/s² it still rocks at the cut, inside α with less energy
    than the barrier m·g·R·(1 − cos α) (``settled_by_energy``): no fall, counted in ``settled``;
    at 5 m/s² it still rocks with more (undetermined: a fall, conservatively). Given 30 s of free
    motion, the 3 m/s² run does come to rest, and the 5 m/s² one falls. Until 2026-12-07 the
    study counted the settled run as a fall too."""
    from rocking.analyses.fragility import fragility_report_lines
    from rocking.excitation.record import GroundMotion

    t = np.linspace(0.0, 1.0, 201)
    rec = {"one sine": GroundMotion(time=t, values=np.sin(2 * np.pi * t), name="one sine")}
    system = rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=200.0))
    ds = ida(system, rec, [2.0, 3.0, 5.0], free_time=0.2, options=rk.Options(gravity=G), workers=1)
    assert ds.status.values[0, 0].tolist() == ["completed", "still_moving", "still_moving"]
    assert ds.settled_by_energy.values[0, 0].tolist() == [False, True, False]
    assert ds.fall.values[0, 0].tolist() == [False, False, True]
    assert ds.exceed.values[0, 0].tolist() == [False, False, True]
    assert int(ds.settled.values[0]) == 1 and int(ds.undetermined.values[0]) == 1
    text = "\n".join(fragility_report_lines(fragility_curves(ds, n_boot=10, seed=1), ds, free_time=0.2))
    assert "1 run(s) were still moving 0.2 s after their record ended, with less energy" in text
    assert "**1 run(s) were still moving 0.2 s after their record ended: undetermined" in text
    longer = ida(system, rec, [3.0, 5.0], free_time=30.0, options=rk.Options(gravity=G), workers=1)
    assert longer.status.values[0, 0].tolist() == ["completed", "overturned"]


def test_a_statue_on_a_pedestal_that_would_tip_counts_as_a_fall_and_is_reported(records):
    """A squat statue (never rocks: tan α = 0.83) on a pedestal 0.3 m wide and 1 m tall that
    friction (μs = 0.8) holds, under Takatori scaled to 1 and 4 m/s² PGA: the pedestal passes the
    floor's acceleration on, and its floor reaction leaves its base once |a_g|/g > 0.2 (derivation
    §3.5), so at 4 m/s² (0.41 g) the pedestal would tip, which the two-body model does not follow:
    that run may not count as a survival (until 2026-12-02 it did: the statue "stood"). At
    1 m/s² (0.10 g) it stays flat and survives."""
    from rocking.analyses.fragility import fragility_report_lines

    statue = rk.Statue(width=1.0, height=1.2, mass=50.0)
    pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=0.8, kinetic=0.7), width=0.3, height=1.0)
    rec = {RECORDS[1]: records[RECORDS[1]]}
    ds = ida(rk.System(statue=statue, pedestal=pedestal), rec, [1.0, 4.0], free_time=3.0,
             options=rk.Options(gravity=G), workers=1)
    assert not ds.overturned.values.any()
    assert np.isnan(ds.pedestal_uplift_time.values[0, 0, 0]) and ds.pedestal_uplift_time.values[0, 0, 1] > 0
    assert ds.fall.values[0, 0].tolist() == [False, True] and int(ds.pedestal_tips.values[0]) == 1
    text = "\n".join(fragility_report_lines(fragility_curves(ds, n_boot=10, seed=1), ds, free_time=3.0))
    assert "1 run(s): the statue stood, but its pedestal would tip" in text


def test_a_median_beyond_the_levels_run_is_flagged_and_the_levels_are_counted(runs):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from rocking.analyses.fragility import extrapolated, fragility_report_lines

    curves = fragility_curves(runs, n_boot=50, seed=1)
    beyond = extrapolated(curves)
    np.testing.assert_array_equal(beyond, curves.im_median.values > 10.0)
    # the fit can put a median beyond the highest level; here the pedestal's, as in the example
    curves["im_median"].loc[{"system": "on pedestal", "mode": "fall"}] = 19.3
    curves["beta"].loc[{"system": "on pedestal", "mode": "fall"}] = 0.85
    lines = fragility_report_lines(curves, runs, free_time=3.0, charts=["f.png"])
    row = next(line for line in lines if line.startswith("| on pedestal | falls |"))
    assert "| 19.3 m/s² ⚠ extrapolated (above the highest level run, 10 m/s²) |" in row
    assert lines[0] == "## PGA (every value in m/s²)" and not any(" g " in line or "(g)" in line for line in lines)
    # every level with its counts, per system and failure mode
    head = lines.index("| PGA (m/s²) | alone: θ/α ≥ 1 | alone: falls | on pedestal: θ/α ≥ 1 | on pedestal: falls |")
    rows = lines[head + 2: head + 6]
    assert [r.split(" | ")[0] for r in rows] == ["| 1", "| 3", "| 6", "| 10"]
    fails = runs.fall.sel(system="on pedestal").sum("record").values
    assert [r.split(" | ")[-1] for r in rows] == [f"{int(k)}/3 |" for k in fails]
    ax = plot_fragility_curves(curves, "fall")
    fit = [line.get_label() for line in ax.get_lines() if "median" in str(line.get_label())]
    assert "on pedestal: median = 19.3 m/s² (extrapolated), β = 0.85" in fit
    assert ax.get_xlim()[1] > 19.3  # the extrapolated median is on the chart, marked
    assert any(line.get_marker() == "D" for line in ax.get_lines())
    canvas = FigureCanvasAgg(ax.figure)
    canvas.draw()
    legend = ax.get_legend().get_window_extent(canvas.get_renderer())
    assert legend.y0 >= ax.get_window_extent(canvas.get_renderer()).y1  # above the data, not on it


def test_record_set_reads_folders_files_and_names(tmp_path, records):
    from rocking.io.records import resolve_record

    src = resolve_record(RECORDS[0])
    (tmp_path / "set").mkdir()
    (tmp_path / "set" / src.name).write_bytes(src.read_bytes())
    (tmp_path / "set" / "README.md").write_text("not a record")
    got = load_record_set(["set", RECORDS[1], str(src)], base_dir=tmp_path)
    assert list(got) == [RECORDS[0], RECORDS[1], f"{RECORDS[0]}-2"]
    np.testing.assert_array_equal(got[RECORDS[0]].values, records[RECORDS[0]].values)
    with pytest.raises(FileNotFoundError):
        load_record_set(["no_such_record_anywhere"], base_dir=tmp_path)


def test_separated_outcomes_are_flagged():
    fit = fit_lognormal([1.0, 2.0, 4.0, 8.0], [10, 10, 10, 10], [0, 0, 10, 10])
    assert fit.at_bound and fit.beta == 0.02 and fit.median == pytest.approx(math.sqrt(8.0))


# ------------------------------------------------------------------------- the command
FRAGILITY_TOML = """
[statue]
width = 0.4
height = 1.6
mass = 200.0
friction = {{ static = 0.5 }}

[pedestal]
mass = 300.0
friction = {{ static = 0.15, kinetic = 0.12 }}

[fragility]
records = {records}
pga_levels = [1.0, 4.0, 8.0]
pgv_levels = {{ start = 0.2, stop = 1.0, num = 3 }}
bootstrap = 20
free_time = 2.0

[simulation]
gravity = 9.81
"""


@pytest.fixture(scope="module")
def cli():
    import importlib

    from rocking.cli import studies

    cli_main = importlib.import_module("rocking.cli.main")
    if "fragility" not in {c.name for c in cli_main.app.registered_commands}:
        studies.register(cli_main.app)  # until rocking.cli.main registers the studies itself
        cli_main._command.cache_clear()
    return cli_main.main


def test_fragility_command(cli, tmp_path, capsys):
    cfg = tmp_path / "frag.toml"
    cfg.write_text(FRAGILITY_TOML.format(records=repr(list(RECORDS[:2])).replace("'", '"')))
    out = tmp_path / "out"
    assert cli(["fragility", str(cfg), "--out", str(out), "--workers", "2"]) == 0
    printed = capsys.readouterr().out
    assert "## PGA (every value in m/s²)" in printed and "## PGV (every value in m/s)" in printed
    assert "statue alone" in printed
    for im in ("pga", "pgv"):
        for name in (f"ida_{im}.nc", f"fragility_{im}.nc", f"fragility_{im}.csv", f"fragility_{im}_fall.png",
                     f"fragility_{im}_exceed.png"):
            assert (out / name).stat().st_size > 0, name
    import xarray as xr

    with xr.open_dataset(out / "ida_pga.nc", engine="h5netcdf") as ds:
        assert ds.system.values.tolist() == ["statue alone", "on pedestal"]
        assert ds.level.values.tolist() == [1.0, 4.0, 8.0]
    assert (out / "fragility_report.md").read_text().startswith("# Fragility")
    cfg.write_text(FRAGILITY_TOML.format(records='["nowhere/none.AT2"]'))
    assert cli(["fragility", str(cfg), "--out", str(out)]) == 2
    assert "fragility.records" in capsys.readouterr().err
