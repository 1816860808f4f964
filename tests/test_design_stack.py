"""Studies on the stack engine: batch runs of stacks equal single simulate_stack runs, a resumable
stack study, the design of both faces of the pedestal (which face does the work; a statue that
slides to the pedestal's edge is not safe), and fragility and spectra of stacks."""

import math

import numpy as np
import pytest

import rocking as rk
from rocking.analyses.batch import run_cases, stack_summary_values, sweep
from rocking.analyses.design import design_report, friction_design, motion_family, plot_design
from rocking.analyses.store import Run, StudyInterrupted, run_stored
from rocking.stack import Block, Interface, Stack, simulate_stack

G = 9.81
OPTS = rk.Options(gravity=G)
STATUE = Block(name="statue", width=0.4, height=1.6, mass=200.0)  # tan α = 0.25


def _stack(top_mu: float | None, *, floor_mu: float = 0.3, width: float = 0.8) -> Stack:
    top = None if top_mu is None else rk.Friction(static=top_mu, kinetic=0.8 * top_mu)
    return Stack(blocks=(Block(name="pedestal", width=width, height=0.4, mass=300.0), STATUE),
                 interfaces=(Interface(friction=rk.Friction(static=floor_mu, kinetic=0.8 * floor_mu)),
                             Interface(friction=top)))


MOTION = rk.Harmonic(amplitude=4.0, frequency=1.0, cycles=3, form="sin")


def _value(x):
    """A Dataset value as the summary writes it (NaN → None)."""
    x = x.item() if hasattr(x, "item") else x
    return None if isinstance(x, float) and math.isnan(x) else x


# ------------------------------------------------------------------------------- batch runs
def test_sweep_over_the_top_friction_equals_single_stack_runs_and_reports_the_slip():
    tops = [0.1, 0.2, 0.6]
    base = _stack(0.3)
    base = Stack(blocks=base.blocks, interfaces=(base.interfaces[0], Interface(friction=rk.Friction(static=0.3))))
    ds = sweep(base, MOTION, {"interfaces[1].friction.static": tops}, options=OPTS, workers=2)
    assert ds.block_peak_sliding.dims == ("interfaces[1].friction.static", "block")
    assert ds.block.values.tolist() == ["pedestal", "statue"]
    for k, mu in enumerate(tops):
        stack = Stack(blocks=base.blocks, interfaces=(base.interfaces[0], Interface(friction=rk.Friction(static=mu))))
        single = simulate_stack(stack, MOTION, options=OPTS).summary()
        run = ds.isel({"interfaces[1].friction.static": k})
        for key in ("overturned", "overturn_time", "peak_rotation", "peak_sliding", "residual_sliding",
                    "first_rocking_time", "first_sliding_time", "impacts", "energy_balance_error", "status",
                    "end_time", "still_moving", "verdict"):
            assert _value(run[key]) == single[key], (mu, key)
        assert float(run.required_top_friction) == single["interfaces"][1]["required_friction"]
        for b, block in enumerate(single["blocks"]):
            for key in ("overturned", "peak_rotation", "peak_sliding", "residual_sliding", "first_sliding_time"):
                assert _value(run[f"block_{key}"][b]) == block[key], (mu, b, key)
        for f, face in enumerate(single["interfaces"]):
            assert float(run.interface_slip_path[f]) == face["slip_path"]
    # at μs = 0.1 on top the statue slips on the pedestal (to its edge: the engine stops there);
    # at 0.6 it grips: it never slides on the pedestal, and rocks instead
    low, high = ds.isel({"interfaces[1].friction.static": 0}), ds.isel({"interfaces[1].friction.static": 2})
    assert float(low.block_peak_sliding.sel(block="statue")) > 0.1 and np.isfinite(float(low.first_sliding_time))
    assert str(low.status.values) == "slid_past_edge" and "slid to the edge" in str(low.verdict.values)
    assert float(high.block_peak_sliding.sel(block="statue")) == 0.0 and float(high.peak_rotation) > 0.01


def test_raw_stack_summaries_unpack_to_exactly_the_summary():
    """Every field, the lists of blocks and interfaces included, through the store's raw rows."""
    stacks = [_stack(0.1), _stack(0.3), _stack(None, floor_mu=0.6)]
    raw = run_stored([Run(s, "m") for s in stacks], {"m": MOTION}, options=OPTS, workers=1)
    for row, stack in zip(raw, stacks):
        assert stack_summary_values(row, stack) == simulate_stack(stack, MOTION, options=OPTS).summary()


def test_systems_and_stacks_share_a_batch():
    system = rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=200.0))
    alone = Stack(blocks=(STATUE,), interfaces=(Interface(),))
    ds = run_cases([(system, MOTION), (_stack(0.3), MOTION), (alone, MOTION)], options=OPTS, workers=1)
    assert bool(ds.overturned[0]) == rk.simulate(system, MOTION, options=OPTS).summary()["overturned"]
    assert str(ds.verdict[2].values) == simulate_stack(alone, MOTION, options=OPTS).summary()["verdict"]
    assert "block" not in ds.dims  # blocks differ between the runs: top-level fields only
    with pytest.raises(ValueError, match=r"cases\[0\]: a run needs a rocking.System or a rocking.stack.Stack"):
        run_cases([("statue", MOTION)], workers=1)


def test_an_interrupted_stack_study_resumes_to_identical_results(tmp_path):
    runs = [Run(_stack(mu), "m") for mu in (0.1, 0.15, 0.2, 0.3, 0.45, 0.6)]
    whole = run_stored(runs, {"m": MOTION}, options=OPTS, workers=1, chunk_size=1)
    calls = []

    def stop_after_two(done, total):
        calls.append(done)
        if done >= 2:
            raise KeyboardInterrupt

    folder = tmp_path / "chunks"
    with pytest.raises(StudyInterrupted) as stopped:
        run_stored(runs, {"m": MOTION}, options=OPTS, workers=1, chunk_size=1, folder=folder, progress=stop_after_two)
    assert stopped.value.saved == 2 and stopped.value.total == 6
    seen = []
    again = run_stored(runs, {"m": MOTION}, options=OPTS, workers=2, chunk_size=1, folder=folder,
                       progress=lambda d, t: seen.append(d))
    assert seen[0] == 2  # the saved chunks are loaded, not rerun
    np.testing.assert_array_equal(again, whole)


# ------------------------------------------------------------------------- both faces
SYSTEM = rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=200.0, friction=rk.Friction(static=0.6, kinetic=0.5)),
                   pedestal=rk.Pedestal(mass=300.0, friction=rk.Friction(static=0.6, kinetic=0.5), width=2.0,
                                        height=0.4))


@pytest.fixture(scope="module")
def top_face_design():
    """The floor face grips (μs = 0.6): only a slippery top face keeps the statue standing."""
    motions = motion_family("harmonic", [4.0], [1.2, 1.6], cycles=3)
    ds = friction_design(SYSTEM, motions, mu_s=[0.6], mu_s_top=[0.15, 0.6], mu_k_top_ratio=0.8, free_time=5.0,
                         options=OPTS, workers=2)
    return motions, ds


def test_only_the_top_face_saves_the_statue_and_the_report_names_it(top_face_design):
    motions, ds = top_face_design
    assert ds.attrs["engine"] == "stack"
    assert ds.safe.sel(mu_s_top=0.15).all() and not ds.safe.sel(mu_s_top=0.6).any()
    assert int(ds.overturn_count.sel(mu_s_top=0.6).item()) == 2
    assert ds.attrs["recommended_mu_s_top"] == 0.15 and ds.attrs["recommended_mu_s"] == 0.6
    top = float(ds.top_sliding_max.sel(mu_s_top=0.15).item())
    assert top > 0.1 and float(ds.peak_sliding_max.sel(mu_s_top=0.15).item()) == 0.0
    lines = ds.attrs["verdict_lines"].split("\n")
    assert lines[0].startswith("Recommended pedestal faces: floor μs = 0.6 (μk = 0.5), top μs = 0.15 (μk = 0.12)")
    assert lines[1] == ("Which face does the work, for the recommended design (largest over the motions and friction "
                        f"levels): the top face isolates: the statue slides {1e3 * top:.1f} mm on the pedestal's top "
                        "face, the pedestal slides 0.0 mm on the floor; the statue does not rock.")
    report = design_report(ds)
    assert "the top face isolates" in report and "| floor face (mm) | top face (mm) |" in report
    # a run of the sweep is the single stack run, at a scattered friction level too
    name = list(motions)[0]
    stack = Stack(blocks=(Block(name="pedestal", width=2.0, height=0.4, mass=300.0),
                          Block(name="statue", width=0.4, height=1.6, mass=200.0)),
                  interfaces=(Interface(friction=rk.Friction(static=0.6 * 1.2, kinetic=0.5 * 1.2)),
                              Interface(friction=rk.Friction(static=0.15 * 1.2, kinetic=0.12 * 1.2))))
    single = simulate_stack(stack, motions[name], options=rk.Options(gravity=G, free_time_limit=5.0)).summary()
    run = ds.sel(mu_s=0.6, mu_s_top=0.15, motion=name, friction_factor=1.2).squeeze()
    assert float(run.scatter_top_sliding) == single["blocks"][1]["peak_sliding"]
    assert float(run.scatter_floor_sliding) == single["blocks"][0]["peak_sliding"]
    assert float(run.scatter_required_top_friction) == single["interfaces"][1]["required_friction"]


def test_sliding_to_the_pedestal_edge_is_not_safe_and_is_named():
    """On a 1.2 m pedestal the slippery top face lets the statue slide 0.4 m to the edge under the
    slower motion: the engine stops there, and the design counts it as a fall risk."""
    narrow = rk.System(statue=SYSTEM.statue, pedestal=rk.Pedestal(mass=300.0, friction=SYSTEM.pedestal.friction,
                                                                   width=1.2, height=0.4))
    motions = motion_family("harmonic", [4.0], [0.8, 1.6], cycles=3)
    ds = friction_design(narrow, motions, mu_s=[0.6], mu_s_top=[0.15], mu_k_top_ratio=0.8, free_time=5.0,
                         options=OPTS, workers=1)
    slow = "harmonic A=4 m/s² f=0.8 Hz"
    assert bool(ds.slid_off.sel(motion=slow).item()) and not bool(ds.falls.sel(motion=slow).item())
    assert not bool(ds.safe.item()) and int(ds.slid_off_count.item()) == 1
    assert math.isnan(ds.attrs["recommended_mu_s"])
    text = ds.attrs["verdict_lines"]
    assert "the statue slides to the edge of the pedestal (a fall risk) under 1 of 2 motions: " + slow in text
    assert "slides to the edge of the pedestal at μs·0.8, μs, μs·1.2 (a fall risk)" in design_report(ds)


def test_two_face_chart(top_face_design, tmp_path):
    _, ds = top_face_design
    fig = plot_design(ds)
    axes = [ax for ax in fig.axes if hasattr(ax, "right_ax")]
    assert len(axes) == 2  # one panel per top-face μs
    assert "top face μs 0.15" in axes[0].get_title()
    labels = [line.get_label() for line in axes[0].right_ax.get_lines()]
    assert "statue on the top face (mm)" in labels
    fig.savefig(tmp_path / "chart.png")


def test_design_refuses_a_pedestal_the_stack_engine_cannot_draw():
    no_height = rk.System(statue=SYSTEM.statue, pedestal=rk.Pedestal(mass=300.0, friction=SYSTEM.pedestal.friction))
    with pytest.raises(ValueError, match=r"pedestal.width: needed by the stack engine"):
        friction_design(no_height, {"m": MOTION}, mu_s=[0.3], mu_s_top=[0.2], workers=1)
    with pytest.raises(ValueError, match="mu_k_top and mu_k_top_ratio need mu_s_top"):
        friction_design(SYSTEM, {"m": MOTION}, mu_s=[0.3], mu_k_top=0.1, workers=1)


# ------------------------------------------------------------------- fragility, spectrum
def test_fragility_of_a_stack_counts_slides_to_the_edge_as_falls():
    from rocking.analyses.fragility import ida
    from rocking.io.records import read_record

    rec = read_record("LomaPrieta1989_Corralitos_000")
    stacks = {"slippery top": _stack(0.1, floor_mu=0.6), "gripping top": _stack(0.6, floor_mu=0.6)}
    ds = ida(stacks, {"r": rec}, [4.0, 10.0], free_time=10.0, options=OPTS, workers=1)
    for label, stack in stacks.items():
        for j, level in enumerate((4.0, 10.0)):
            single = simulate_stack(stack, rec.scaled(level / rec.pga),
                                    options=rk.Options(gravity=G, free_time_limit=10.0)).summary()
            run = ds.sel(system=label, record="r").isel(level=j)
            assert str(run.status.values) == single["status"]
            assert float(run.peak_rotation) == single["peak_rotation"]
            fell = single["status"] in ("overturned", "slid_past_edge", "still_moving")
            assert bool(run.fall) == fell
    # at PGA 10 m/s² the slippery top lets the statue slide to the edge; the gripping one makes it fall
    assert ds.status.sel(system="slippery top").values.ravel().tolist() == ["completed", "slid_past_edge"]
    assert ds.status.sel(system="gripping top").values.ravel().tolist() == ["completed", "overturned"]
    assert ds.fall.values[:, 0, 1].all() and int(ds.slid_off.sel(system="slippery top")) == 1


def test_spectrum_of_a_one_block_stack_is_the_statue_spectrum():
    from rocking.analyses.spectra import overturning_spectrum

    statue = rk.Statue(width=0.3, height=1.5, mass=1.0)
    block = Stack(blocks=(Block(width=0.3, height=1.5, mass=1.0),), interfaces=(Interface(),))
    kw = dict(shapes="sine", frequency_ratios=[1.0, 3.0], n_scan=10, rtol=1e-3, workers=1, options=OPTS)
    ours = overturning_spectrum(block, **kw)
    ref = overturning_spectrum(rk.System(statue=statue), **kw)
    assert ours.attrs["engine"] == "stack" and ours.attrs["p"] == pytest.approx(ref.attrs["p"], rel=1e-12)
    np.testing.assert_allclose(ours.amplitude_ratio.values, ref.amplitude_ratio.values, rtol=2e-3)
    assert int(ours.slid_off_runs.sum()) == 0


# ------------------------------------------------------------------------------ the command
@pytest.fixture(scope="module")
def cli():
    import importlib

    from rocking.cli import studies

    cli_main = importlib.import_module("rocking.cli.main")
    if "design" not in {c.name for c in cli_main.app.registered_commands}:
        studies.register(cli_main.app)
        cli_main._command.cache_clear()
    return cli_main.main


STACK_CONFIG = """
[[blocks]]
name = "pedestal"
width = 2.0
height = 0.4
mass = 300.0
[[blocks]]
name = "statue"
width = 0.4
height = 1.6
mass = 200.0
[[interfaces]]
friction = {{ static = 0.6, kinetic = 0.5 }}
[[interfaces]]
friction = {{ static = 0.6, kinetic = 0.5 }}
[motions]
family = "harmonic"
amplitude = [4.0]
frequency = [1.2, 1.6]
cycles = 3
[design]
mu_s = [0.6]
{design}
free_time = 5.0
[simulation]
gravity = 9.81
"""


def test_design_command_on_a_stack_file_names_the_working_face_and_resumes(cli, tmp_path, capsys):
    cfg = tmp_path / "faces.toml"
    cfg.write_text(STACK_CONFIG.format(design="mu_s_top = [0.15, 0.6]\nmu_k_top_ratio = 0.8"))
    out = tmp_path / "out"
    assert cli(["design", str(cfg), "--out", str(out), "--workers", "1"]) == 0
    printed = capsys.readouterr().out
    assert "Recommended pedestal faces: floor μs = 0.6" in printed and "the top face isolates" in printed
    header = (out / "design_table.csv").read_text().splitlines()[0]
    assert header.startswith("mu_s,pedestal_mass,mu_s_top,pedestal_width,mu_k,") and "top_sliding_max" in header
    stamps = {p.name: p.stat().st_mtime_ns for p in (out / "chunks").glob("chunk-*.npz")}
    assert stamps and cli(["design", str(cfg), "--out", str(out), "--workers", "1"]) == 0
    assert {p.name: p.stat().st_mtime_ns for p in (out / "chunks").glob("chunk-*.npz")} == stamps


def test_design_files_name_the_bad_field(cli, tmp_path, capsys):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(STACK_CONFIG.format(design="mu_k_top = 0.1"))
    assert cli(["design", str(cfg)]) == 2
    assert "design: mu_k_top and mu_k_top_ratio go with mu_s_top" in capsys.readouterr().err
    cfg.write_text(STACK_CONFIG.format(design="mu_s_top = [0.2, -0.1]"))
    assert cli(["design", str(cfg)]) == 2
    assert "design.mu_s_top: every value must be >= 0, got -0.1" in capsys.readouterr().err
    cfg.write_text(STACK_CONFIG.format(design="pedestal_width = [0.0]"))
    assert cli(["design", str(cfg)]) == 2
    assert "design.pedestal_width: every value must be > 0, got 0" in capsys.readouterr().err
    cfg.write_text("[statue]\nwidth = 0.4\nheight = 1.6\nmass = 200.0\n" + STACK_CONFIG.format(design=""))
    assert cli(["design", str(cfg)]) == 2
    assert "blocks: [[blocks]] describes a stack, which cannot also have [statue]" in capsys.readouterr().err
    system_file = """
[statue]
width = 0.4
height = 1.6
mass = 200.0
[pedestal]
mass = 300.0
width = 1.0
friction = { static = 0.3 }
[motions]
family = "sine"
amplitude = [4.0]
frequency = [1.0]
[design]
mu_s = [0.3]
mu_s_top = [0.2]
"""
    cfg.write_text(system_file)
    assert cli(["design", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert "pedestal.height: missing: design.mu_s_top runs the stack engine" in err and len(err.splitlines()) == 1


def test_fragility_and_spectrum_files_of_a_stack(tmp_path):
    from rocking.cli.studies import fragility_inputs, load_study, spectrum_inputs

    head = STACK_CONFIG.split("[motions]")[0].format()
    frag, base = load_study("fragility", _toml(tmp_path, head + '[fragility]\nrecords = ["Kobe1995_Takatori_000"]\n'
                                               "pga_levels = [2.0]\nalone_friction = { static = 0.4 }\n"))
    inputs = fragility_inputs(frag, base)
    alone, stack = inputs["systems"]["statue alone"], inputs["systems"]["stack"]
    assert isinstance(stack, Stack) and stack.names == ("pedestal", "statue")
    assert alone.n == 1 and alone.blocks[0].height == 1.6 and alone.interfaces[0].friction.static == 0.4
    spec, base = load_study("spectrum", _toml(tmp_path, head + "[spectrum]\nmotions = [\"sine\"]\n"))
    assert spectrum_inputs(spec, base)["system"] == stack
    bad = head.replace('name = "statue"', 'name = "pedestal"')
    with pytest.raises(Exception, match=r"blocks\[1\].name: 'pedestal' is already the name of blocks\[0\]"):
        spectrum_inputs(*load_study("spectrum", _toml(tmp_path, bad + "[spectrum]\n")))


def _toml(tmp_path, text):
    path = tmp_path / "study.toml"
    path.write_text(text)
    return path
