"""Friction design of the pedestal: per-run results, aggregation, the recommendation, and the
``rocking design`` command."""

import json
import math

import numpy as np
import pytest

import rocking as rk
from rocking.analyses.design import candidate_table, design_report, friction_design, motion_family, plot_design

G = 9.81
OPTS = rk.Options(gravity=G)
STATUE = rk.Statue(width=0.4, height=1.6, mass=200.0, friction=rk.Friction(static=0.6))  # tan α = 0.25
PEDESTAL = rk.Pedestal(mass=300.0, friction=rk.Friction(static=0.3, kinetic=0.24))
SYSTEM = rk.System(statue=STATUE, pedestal=PEDESTAL)
MU_S = [0.1, 0.2, 0.3, 0.45]


@pytest.fixture(scope="module")
def motions():
    return motion_family("harmonic", [3.5, 6.0], [0.8, 1.6], cycles=3)


@pytest.fixture(scope="module")
def design(motions):
    return friction_design(SYSTEM, motions, mu_s=MU_S, pedestal_mass=[150.0, 600.0], sliding_limit=0.25,
                           free_time=3.0, options=OPTS, workers=2)


def test_runs_are_the_single_simulations(design, motions):
    name = list(motions)[3]
    run = design.sel(mu_s=0.2, pedestal_mass=600.0, motion=name)
    ped = rk.Pedestal(mass=600.0, friction=rk.Friction(static=0.2, kinetic=0.2 * 0.8))
    single = rk.simulate(rk.System(statue=STATUE, pedestal=ped), motions[name],
                         duration=motions[name].duration + 3.0, options=OPTS, save=False).summary()
    for key in ("peak_rotation", "peak_sliding", "residual_sliding", "required_top_friction"):
        assert float(run[key]) == single[key], key
    assert bool(run.overturned) == single["overturned"]
    assert float(design.mu_k.sel(mu_s=0.2)) == pytest.approx(0.16)


def test_aggregates_and_the_physics_of_the_sweep(design):
    rot = design.peak_rotation_over_alpha
    np.testing.assert_array_equal(design.overturn_count.values, design.overturned.sum("motion").values)
    np.testing.assert_allclose(design.peak_rotation_ratio_max.values, rot.max("motion").values)
    np.testing.assert_allclose(design.peak_sliding_max.values, design.peak_sliding.max("motion").values)
    # O17: with μk ≤ μs ≤ tan α the floor can pass on at most μs·g ≤ g tan α, so the statue never rocks
    low = design.sel(mu_s=[0.1, 0.2])
    assert float(low.peak_rotation.max()) == 0.0 and not low.overturned.any()
    # a pedestal that grips better slides less
    assert float(design.peak_sliding_max.sel(mu_s=0.1).max()) > float(design.peak_sliding_max.sel(mu_s=0.45).max())
    # the friction the statue-pedestal face must supply never exceeds what the floor passes on
    # while the statue stays on the pedestal without rocking: μs of the floor face
    quiet = design.required_top_friction.where(design.peak_rotation == 0)
    assert float((quiet - design.mu_s).max()) <= 1e-9


def test_recommendation_is_the_best_feasible_candidate(design):
    table = candidate_table(design)
    feasible = table[table.feasible]
    assert len(feasible) and (feasible.peak_sliding_max <= 0.25).all()
    assert (table[~table.feasible].peak_sliding_max > 0.25).all()
    best = feasible.sort_values(["overturn_count", "score", "peak_sliding_max", "mu_s", "pedestal_mass"]).iloc[0]
    assert table.recommended.sum() == 1
    rec = table[table.recommended].iloc[0]
    assert (rec.mu_s, rec.pedestal_mass) == (best.mu_s, best.pedestal_mass)
    assert design.attrs["recommended_mu_s"] == best.mu_s
    assert design.attrs["recommended_pedestal_mass"] == best.pedestal_mass
    report = design_report(design)
    assert "**Recommended: μs = " in report and report.count("⟵") == 1


def test_no_feasible_candidate_and_fixed_kinetic_friction(motions):
    few = dict(list(motions.items())[:1])
    ds = friction_design(SYSTEM, few, mu_s=[0.1, 0.3], mu_k=0.2, sliding_limit=0.0, residual_limit=0.0,
                         options=OPTS, workers=1)
    np.testing.assert_allclose(ds.mu_k.values, [0.1, 0.2])  # capped at μs
    assert math.isnan(ds.attrs["recommended_mu_s"]) and not ds.recommended.any()
    assert "No candidate satisfies the limits" in design_report(ds)
    with pytest.raises(ValueError, match="pedestal"):
        friction_design(rk.System(statue=STATUE), few, mu_s=[0.1])
    with pytest.raises(ValueError, match="not both"):
        friction_design(SYSTEM, few, mu_s=[0.1], mu_k=0.1, mu_k_ratio=0.5)


def test_design_chart(design):
    fig = plot_design(design)
    assert len(fig.axes) >= 2
    titles = [ax.get_title() for ax in fig.axes]
    assert "pedestal mass 150 kg" in titles and "pedestal mass 600 kg" in titles


# ------------------------------------------------------------------------- the command
CONFIG = """
[statue]
width = 0.4
height = 1.6
mass = 200.0
friction = {{ static = 0.6 }}

[pedestal]
mass = 300.0
friction = {{ static = 0.3, kinetic = 0.24 }}

[motions]
family = "harmonic"
amplitude = [3.5, 6.0]
frequency = {{ start = 0.8, stop = 1.6, num = 2 }}
cycles = 3

[design]
mu_s = {mu_s}
sliding_limit = 0.25
free_time = 3.0

[simulation]
gravity = 9.81
"""


@pytest.fixture(scope="module")
def cli():
    import importlib

    from rocking.cli import studies

    cli_main = importlib.import_module("rocking.cli.main")  # the package re-exports `main`, the function

    if "design" not in {c.name for c in cli_main.app.registered_commands}:
        studies.register(cli_main.app)  # until rocking.cli.main registers the studies itself
        cli_main._command.cache_clear()
    return cli_main.main


def test_design_command_writes_everything_and_resumes(cli, tmp_path, capsys):
    cfg = tmp_path / "pedestal.toml"
    cfg.write_text(CONFIG.format(mu_s="[0.1, 0.2, 0.3, 0.45]"))
    out = tmp_path / "out"
    assert cli(["design", str(cfg), "--out", str(out), "--workers", "1"]) == 0
    printed = capsys.readouterr().out
    assert "Recommended" in printed
    for name in ("design_table.csv", "design.nc", "design_chart.png", "design_report.md"):
        assert (out / name).stat().st_size > 0
    lines = (out / "design_table.csv").read_text().splitlines()
    assert len(lines) == 1 + 4 and lines[0].startswith("mu_s,pedestal_mass,mu_k,")
    chunks = sorted((out / "chunks").glob("chunk-*.npz"))
    manifest = json.loads((out / "chunks" / "manifest.json").read_text())
    assert manifest["complete"] and manifest["n_chunks"] == len(chunks) > 0
    stamps = {p.name: p.stat().st_mtime_ns for p in chunks}
    # the same command again: every chunk is loaded, none is rerun, same table
    assert cli(["design", str(cfg), "--out", str(out), "--workers", "1"]) == 0
    assert {p.name: p.stat().st_mtime_ns for p in (out / "chunks").glob("chunk-*.npz")} == stamps
    assert (out / "design_table.csv").read_text().splitlines() == lines
    # other inputs in the same folder are refused, unless --fresh
    cfg.write_text(CONFIG.format(mu_s="[0.1, 0.2]"))
    capsys.readouterr()
    assert cli(["design", str(cfg), "--out", str(out), "--workers", "1"]) == 2
    assert "--fresh" in capsys.readouterr().err
    assert cli(["design", str(cfg), "--out", str(out), "--workers", "1", "--fresh"]) == 0
    assert len((out / "design_table.csv").read_text().splitlines()) == 1 + 2


def test_design_command_names_the_bad_field(cli, tmp_path, capsys):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(CONFIG.format(mu_s="[0.1]").replace("sliding_limit", "slide_limit"))
    assert cli(["design", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "design.slide_limit: unknown key; did you mean 'sliding_limit'?" in err
    cfg.write_text(CONFIG.format(mu_s="[0.1]").replace('family = "harmonic"', 'records = ["no_such_record"]')
                   .replace("amplitude = [3.5, 6.0]\n", "").replace("frequency = { start = 0.8, stop = 1.6, num = 2 }\n", "")
                   .replace("cycles = 3\n", ""))
    assert cli(["design", str(cfg)]) == 2
    assert "motions.records" in capsys.readouterr().err
