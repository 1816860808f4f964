"""Studies on the stack engine: batch runs of stacks equal single simulate_stack runs, a resumable
stack study, the design of both faces of the pedestal (which face does the work; a statue that
slides to the pedestal's edge is not safe), and fragility and spectra of stacks."""

import dataclasses
import math

import numpy as np
import pytest

import rocking as rk
from rocking.analyses.batch import run_cases, stack_summary_values, sweep
from rocking.analyses.design import design_report, friction_design, motion_family, plot_design
from rocking.analyses.store import Run, StudyInterrupted, run_stored
from rocking.stack import Block, Interface, Stack, simulate_stack
from rocking.viz.plots import TOP_LIMIT_COLOR, _mm_text

G = 9.81
OPTS = rk.Options(gravity=G)
# the conservative criterion: a run stops, undetermined, when a block slides to the edge below
OPTS_EDGE = rk.Options(gravity=G, stop_at_edge=True)
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
    ds = sweep(base, MOTION, {"interfaces[1].friction.static": tops}, options=OPTS_EDGE, workers=2)
    assert ds.block_peak_sliding.dims == ("interfaces[1].friction.static", "block")
    assert ds.block.values.tolist() == ["pedestal", "statue"]
    for k, mu in enumerate(tops):
        stack = Stack(blocks=base.blocks, interfaces=(base.interfaces[0], Interface(friction=rk.Friction(static=mu))))
        single = simulate_stack(stack, MOTION, options=OPTS_EDGE).summary()
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
    # at μs = 0.1 on top the statue slips on the pedestal (to its edge: the run stops there, as asked);
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
                        f"levels): the top face isolates: the statue slides {_mm_text(1e3 * top)} on the "
                        "pedestal's top face, the pedestal slides 0 mm on the floor; the statue does not rock.")
    report = design_report(ds)
    assert "the top face isolates" in report and "| floor face (mm) | top face (mm, limit 400 mm) |" in report
    # a run of the sweep is the single stack run, at a scattered friction level too
    name = list(motions)[0]
    stack = Stack(blocks=(Block(name="pedestal", width=2.0, height=0.4, mass=300.0),
                          Block(name="statue", width=0.4, height=1.6, mass=200.0)),
                  interfaces=(Interface(friction=rk.Friction(static=0.6 * 1.2, kinetic=0.5 * 1.2)),
                              Interface(friction=rk.Friction(static=0.15 * 1.2, kinetic=0.12 * 1.2))))
    single = simulate_stack(stack, motions[name], options=rk.Options(gravity=G, free_time_limit=5.0)).summary()
    run = ds.sel(mu_s=0.6, mu_s_top=0.15, motion=name, friction_level="both faces μs·1.2").squeeze()
    assert float(run.scatter_top_sliding) == single["blocks"][1]["peak_sliding"]
    assert float(run.scatter_floor_sliding) == single["blocks"][0]["peak_sliding"]
    assert float(run.scatter_required_top_friction) == single["interfaces"][1]["required_friction"]


def test_sliding_to_the_pedestal_edge_is_not_safe_and_is_named():
    """On a 1.2 m pedestal the slippery top face lets the statue slide 0.4 m to the edge under the
    slower motion: with ``stop_at_edge`` the run stops there, and the design counts it as a fall risk."""
    narrow = rk.System(statue=SYSTEM.statue, pedestal=rk.Pedestal(mass=300.0, friction=SYSTEM.pedestal.friction,
                                                                   width=1.2, height=0.4))
    motions = motion_family("harmonic", [4.0], [0.8, 1.6], cycles=3)
    ds = friction_design(narrow, motions, mu_s=[0.6], mu_s_top=[0.15], mu_k_top_ratio=0.8, free_time=5.0,
                         options=OPTS_EDGE, workers=1)
    slow = "harmonic A=4 m/s² f=0.8 Hz"
    assert bool(ds.slid_off.sel(motion=slow).item()) and not bool(ds.falls.sel(motion=slow).item())
    assert not bool(ds.safe.item()) and int(ds.slid_off_count.item()) == 1
    assert math.isnan(ds.attrs["recommended_mu_s"])
    text = ds.attrs["verdict_lines"]
    assert "the statue slides to the edge of the pedestal (a fall risk) under 1 of 2 motions: " + slow in text
    assert "slides to the edge of the pedestal at every friction level (a fall risk)" in design_report(ds)


# ------------------------------------------------- the two faces' friction drifting apart
LEVELS = {"nominal μs": (1.0, 1.0), "both faces μs·0.8": (0.8, 0.8), "both faces μs·1.2": (1.2, 1.2),
          "floor μs·1.2 with top μs·0.8": (1.2, 0.8), "floor μs·0.8 with top μs·1.2": (0.8, 1.2)}


def _stored_runs(monkeypatch):
    """The runs a design hands to the store, as they are stored."""
    from rocking.analyses import design

    seen = []

    def keep(runs, *args, **kw):
        seen.extend(runs)
        return run_stored(runs, *args, **kw)

    monkeypatch.setattr(design, "run_stored", keep)
    return seen


def _faces(run):
    floor, top = (face.friction for face in run.system.interfaces)
    return floor, top


def test_both_faces_run_together_and_in_opposite_directions(monkeypatch):
    runs = _stored_runs(monkeypatch)
    ds = friction_design(SYSTEM, {"m": MOTION}, mu_s=[0.3], mu_k_ratio=0.8, mu_s_top=[0.2], mu_k_top_ratio=0.5,
                         free_time=2.0, options=OPTS, workers=1)
    assert ds.friction_level.values.tolist() == list(LEVELS)
    assert list(zip(ds.floor_factor.values.tolist(), ds.top_factor.values.tolist())) == list(LEVELS.values())
    assert len(runs) == 5
    for run, (f_floor, f_top) in zip(runs, LEVELS.values()):
        floor, top = _faces(run)
        assert (floor.static, floor.kinetic) == (0.3 * f_floor, 0.8 * 0.3 * f_floor)
        assert (top.static, top.kinetic) == (0.2 * f_top, 0.5 * 0.2 * f_top)
    report = design_report(ds)
    assert ("every candidate also runs with both faces at μs·(1 ± s) together and in opposite directions (μk "
            "alike): both faces μs·0.8, both faces μs·1.2, floor μs·1.2 with top μs·0.8, floor μs·0.8 with "
            "top μs·1.2; every result below is the worst of the five levels.") in report
    assert ("under every motion with both faces at μs and at μs·(1 ± 0.2) together and in opposite directions"
            in report)
    # without scatter, the nominal friction only
    runs.clear()
    exact = friction_design(SYSTEM, {"m": MOTION}, mu_s=[0.3], mu_s_top=[0.2], friction_scatter=0.0, free_time=2.0,
                            options=OPTS, workers=1)
    assert len(runs) == 1 and exact.friction_level.values.tolist() == ["nominal μs"]


def test_a_top_face_that_never_slips_runs_three_levels(monkeypatch):
    runs = _stored_runs(monkeypatch)
    ds = friction_design(_stack(None), {"m": MOTION}, mu_s=[0.3], mu_k_ratio=0.8, free_time=2.0, options=OPTS,
                         workers=1)
    assert ds.attrs["engine"] == "stack" and math.isinf(ds.mu_s_top.item())
    assert len(runs) == 3 and ds.sizes["friction_level"] == 3
    assert [_faces(run)[0].static for run in runs] == [0.3, 0.3 * 0.8, 0.3 * 1.2]
    assert all(_faces(run)[1] is None for run in runs)
    assert ds.friction_level.values.tolist() == ["nominal μs", "floor μs·0.8", "floor μs·1.2"]
    report = design_report(ds)
    assert "the top face never slips, so every candidate also runs with the floor face's μs and μk" in report
    assert "with the floor face at μs and μs·(1 ± 0.2) (μk alike; the top face never slips)" in report


@pytest.fixture(scope="module")
def drifting_apart():
    """A statue on a 1.2 m pedestal (default top-face limit 200 mm) whose top face (μs = 0.2) is
    slipperier than its floor face (μs = 0.2 or 0.3), under one harmonic motion."""
    stack = _stack(0.2, width=1.2)
    motions = motion_family("harmonic", [4.0], [1.2], cycles=3)
    return friction_design(stack, motions, mu_s=[0.2, 0.3], free_time=5.0, options=OPTS, workers=1)


def test_only_the_faces_drifting_apart_exceed_the_top_limit_and_move_the_recommendation(drifting_apart):
    from rocking.analyses.design import choose_design

    ds = drifting_apart
    room = float(ds.top_sliding_limit.item())
    assert room == pytest.approx(0.2)
    gripping = ds.sel(mu_s=0.3).squeeze()
    top = gripping.scatter_top_sliding.sel(friction_level=list(LEVELS))
    together, apart = top.values[:3], top.sel(friction_level="floor μs·1.2 with top μs·0.8").item()
    # the floor face gripping harder under a slipperier top face: only that drift exceeds the room
    assert together.max() < room < apart and float(gripping.top_sliding_max) == apart
    # the reverse drift is the floor face's worst: it sets the free space
    floor = gripping.scatter_floor_sliding
    reverse = floor.sel(friction_level="floor μs·0.8 with top μs·1.2").item()
    assert floor.values[:3].max() < reverse == float(gripping.peak_sliding_max)

    def recommended(levels):
        """choose_design over these levels only (the worst of them per candidate)."""
        part = ds.isel(friction_level=levels)
        worst = lambda name: part[name].max("friction_level").values  # noqa: E731
        choice = choose_design(
            mu_s=ds.mu_s.values, mu_k=ds.mu_k.values, pedestal_mass=ds.pedestal_mass.values,
            motions=ds.motion.values, falls=part.scatter_overturned.any("friction_level").values,
            undetermined=part.scatter_undetermined.any("friction_level").values,
            clearance=worst("scatter_floor_sliding"), residual=ds.residual_sliding_max.values,
            top_friction=ds.required_top_friction_max.values, score=ds.score.values,
            extra_axes=(("mu_s_top", ds.mu_s_top.values), ("pedestal_width", ds.pedestal_width.values)),
            top_sliding=worst("scatter_top_sliding").max(-1), top_sliding_limit=room)
        return float(ds.mu_s.values[choice.recommended[0]])

    # the faces drifting together only would have recommended the gripping floor face; apart, it fails
    assert recommended([0, 1, 2]) == 0.3 and recommended([0, 1, 2, 3, 4]) == 0.2
    assert ds.attrs["recommended_mu_s"] == 0.2 and ds.attrs["excluded_by_top_sliding_mu_s"] == 0.3
    assert not bool(ds.feasible.sel(mu_s=0.3).item()) and bool(ds.feasible.sel(mu_s=0.2).item())
    assert (f"excludes floor μs = 0.3 (μk = 0.24), top μs = 0.2 (μk = 0.16), pedestal mass 300 kg, width 1.2 m, "
            f"which would otherwise be recommended: the statue slides {_mm_text(1e3 * apart)} on the pedestal's top "
            "face, more than the 200 mm limit there.") in ds.attrs["verdict_lines"]


def test_a_folder_of_a_design_run_before_the_levels_apart_is_refused_not_mixed(drifting_apart, tmp_path):
    """The levels of earlier versions (both faces ·0.8, ·1, ·1.2 together only) are other runs: the
    store's fingerprint differs, so a rerun into that folder refuses, and --fresh recomputes."""
    import dataclasses

    from rocking.analyses.store import StoreMismatchError

    motions = motion_family("harmonic", [4.0], [1.2], cycles=3)
    old = [Run(_stack(0.2 * f, floor_mu=mu * f, width=1.2), name) for name in motions for mu in (0.2, 0.3)
           for f in (0.8, 1.0, 1.2)]
    folder = tmp_path / "chunks"
    # one chunk each: only the runs tell the two studies apart
    run_stored(old, motions, options=dataclasses.replace(OPTS, free_time_limit=5.0), study="design", folder=folder,
               workers=1, chunk_size=100, meta={"friction_factor": [0.8, 1.0, 1.2]})
    kw = dict(mu_s=[0.2, 0.3], free_time=5.0, options=OPTS, workers=1, folder=folder, chunk_size=100)
    with pytest.raises(StoreMismatchError, match="holds the chunks of another design"):
        friction_design(_stack(0.2, width=1.2), motions, **kw)
    again = friction_design(_stack(0.2, width=1.2), motions, fresh=True, **kw)
    assert again.sizes["friction_level"] == 5
    np.testing.assert_array_equal(again.scatter_top_sliding.values, drifting_apart.scatter_top_sliding.values)


def _panels(fig):
    """(title, rotation axes) of each panel of a design chart, row by row."""
    cells = [cell for row in fig.subfigs[1].subfigs for cell in np.ravel(row)]
    rot = [ax for ax in fig.axes if hasattr(ax, "sliding_ax")]
    return [(cell.texts[0].get_text(), ax) for cell, ax in zip(cells, rot)]


def test_two_face_chart_has_a_row_per_top_face_and_numbers_what_it_clips(top_face_design, tmp_path):
    _, ds = top_face_design
    fig = plot_design(ds)
    panels = _panels(fig)
    assert [t for t, _ in panels] == ["top face μs 0.15, width 2 m", "top face μs 0.6, width 2 m"]
    assert len(fig.axes) == 6  # θ/α, fall/edge rate, sliding: each on its own axes
    ax = panels[0][1]
    assert [line.get_label() for line in ax.sliding_ax.get_lines()][:2] == ["pedestal on the floor",
                                                                             "statue on the top face"]
    assert ax.rate_ax.get_ylabel() == "fall/edge\nrate (–)" and ax.get_ylabel() == "mean peak\n|θ|/α (–)"
    # both motions topple the statue on the gripping top face: θ/α = π/(2α) = 6.41, clipped and numbered
    clipped = panels[1][1]
    assert float(ds.peak_rotation_ratio_mean.sel(mu_s_top=0.6).item()) == pytest.approx(6.41, abs=0.005)
    assert "6.41" in [t.get_text() for t in clipped.texts]
    assert max(clipped.get_lines()[0].get_ydata()) == 2.0
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    fig.savefig(tmp_path / "chart.png")
    # the legend sits in the strip above the panels, clear of every axes
    renderer = canvas.get_renderer()
    legend = fig.subfigs[0].legends[0].get_window_extent(renderer)
    assert all(not legend.overlaps(a.get_window_extent(renderer)) for a in fig.axes)
    assert "recommended μs = 0.6" in [t.get_text() for t in fig.subfigs[0].legends[0].get_texts()]


def test_the_chart_draws_each_width_s_top_face_limit(top_limit_designs):
    fig = plot_design(top_limit_designs[None])
    panels = _panels(fig)
    assert [t for t, _ in panels] == ["top face μs 0.15, width 1.2 m", "top face μs 0.15, width 2 m"]
    for (_, ax), room in zip(panels, ("200 mm", "400 mm")):
        labels = [t.get_text() for t in ax.sliding_ax.texts]
        assert labels == [f"top-face limit\n{room}"]  # no sliding_limit was given
        limit = [line for line in ax.sliding_ax.get_lines() if line.get_color() == TOP_LIMIT_COLOR]
        assert [float(line.get_ydata()[0]) for line in limit] == pytest.approx([float(room.split()[0])])
    # the rows share their axes, so the 400 mm limit fits both panels
    assert panels[0][1].sliding_ax.get_ylim() == panels[1][1].sliding_ax.get_ylim()
    assert panels[0][1].sliding_ax.get_ylim()[1] > 400


# ------------------------------------------------------- the statue's slide on the top face
def test_the_default_top_limit_is_half_the_room_on_each_pedestal_width():
    from rocking.analyses.design import default_top_sliding_limit

    # 0.5·((W − 0.4)/2 − |offset|): the offset's sign does not matter, the nearer edge does
    np.testing.assert_allclose(default_top_sliding_limit([0.8, 1.2], 0.4, -0.05), [0.075, 0.175], rtol=1e-12)
    with pytest.raises(ValueError, match="top_sliding_limit: its default, half the room"):
        default_top_sliding_limit([0.5], 0.4, 0.1)
    off_centre = Stack(blocks=(Block(name="pedestal", width=1.0, height=0.4, mass=300.0),
                               Block(name="statue", width=0.4, height=1.6, mass=200.0, offset=0.05)),
                       interfaces=(Interface(friction=rk.Friction(static=0.6)),
                                   Interface(friction=rk.Friction(static=0.6))))
    ds = friction_design(off_centre, {"m": rk.SinePulse(amplitude=1.0, frequency=2.0)}, mu_s=[0.6],
                         pedestal_width=[0.8, 1.2], friction_scatter=0.0, free_time=2.0, options=OPTS, workers=1)
    np.testing.assert_allclose(ds.top_sliding_limit.values, [0.075, 0.175], rtol=1e-12)
    assert ("statue's slide on the top face ≤ half the room there, 0.5 × ((pedestal width − statue width)/2 − "
            "|offset|): 75 mm on the 0.8 m pedestal, 175 mm on the 1.2 m pedestal (the default: "
            "design.top_sliding_limit not given)") in design_report(ds)


@pytest.fixture(scope="module")
def top_limit_designs():
    """A gripping floor face under a slippery top face (the statue slides 0.33 m on its pedestal), or
    a slippery floor face (the pedestal slides instead), on a 1.2 m and a 2 m pedestal."""
    motions = motion_family("harmonic", [4.0], [1.2, 1.6], cycles=3)
    return {limit: friction_design(SYSTEM, motions, mu_s=[0.15, 0.6], mu_s_top=[0.15], mu_k_top_ratio=0.8,
                                   pedestal_width=[1.2, 2.0], free_time=5.0, options=OPTS, workers=1,
                                   top_sliding_limit=limit)
            for limit in (None, 0.1, 0.2, math.inf)}


def _recommended(ds):
    a = ds.attrs
    return a["recommended_mu_s"], a["recommended_pedestal_width"]


def test_the_top_limit_moves_the_recommendation_and_the_verdict_says_why(top_limit_designs):
    loose, default, tight, tighter = (top_limit_designs[k] for k in (math.inf, None, 0.2, 0.1))
    slide = float(loose.top_sliding_max.sel(mu_s=0.6, pedestal_width=1.2).item())
    assert 0.2 < slide < 0.4  # over the default 200 mm on the 1.2 m pedestal, within the 400 mm on the 2 m one
    # no limit: the gripping floor face on the narrower pedestal, as before the limit existed
    assert _recommended(loose) == (0.6, 1.2) and "The limit on the statue's slide" not in loose.attrs["verdict_lines"]
    # the default limit: the statue may not slide that far on the 1.2 m pedestal, the 2 m one takes it
    assert _recommended(default) == (0.6, 2.0)
    assert not bool(default.feasible.sel(mu_s=0.6, pedestal_width=1.2).item())
    lines = default.attrs["verdict_lines"].split("\n")
    assert lines[1] == ("The limit on the statue's slide on the pedestal's top face excludes floor μs = 0.6 "
                        "(μk = 0.5), top μs = 0.15 (μk = 0.12), pedestal mass 300 kg, width 1.2 m, which would "
                        f"otherwise be recommended: the statue slides {_mm_text(1e3 * slide)} on the pedestal's "
                        "top face, more than the 200 mm limit there.")
    assert default.attrs["excluded_by_top_sliding_pedestal_width"] == 1.2
    # 200 mm on both: neither pedestal takes the top face's slide; the slippery floor face isolates instead
    assert _recommended(tight) == (0.15, 2.0) and tight.attrs["excluded_by_top_sliding_mu_s"] == 0.6
    assert float(tight.top_sliding_max.sel(mu_s=0.15, pedestal_width=2.0).item()) <= 0.2
    assert "statue's slide on the top face ≤ 200 mm" in tight.attrs["verdict"]
    # 100 mm: the slippery floor face keeps the statue within it while the faces drift together,
    # not when the floor grips harder under a slipperier top: then no candidate meets the limit
    slippery = tighter.scatter_top_sliding.sel(mu_s=0.15, pedestal_width=2.0).squeeze()
    apart = slippery.sel(friction_level="floor μs·1.2 with top μs·0.8").max().item()
    assert slippery.isel(friction_level=[0, 1, 2]).max().item() <= 0.1 < apart
    assert not tighter.feasible.any() and not tighter.attrs["meets_every_requirement"]
    assert "statue's slide on the top face ≤ 100 mm" in tighter.attrs["verdict"]


def test_the_report_shows_the_top_slide_against_its_limit(top_limit_designs):
    default = top_limit_designs[None]
    report = design_report(default)
    assert "| motion | floor face (mm) | top face (mm, limit 400 mm) |" in report
    assert "| top slide (mm) | top limit (mm) |" in report
    row = next(line for line in report.splitlines() if line.startswith("| 0.6 | 0.5 | 0.15 | 0.12 | 300 | 1.2 |"))
    slide = _mm_text(1e3 * float(default.top_sliding_max.sel(mu_s=0.6, pedestal_width=1.2).item()))
    assert f"| {slide.removesuffix(' mm')} | 200 |" in row
    assert row.endswith("| no |")  # does not meet the limits
    assert "Limits: statue's slide on the top face ≤ half the room there" in report
    assert ("Limits: no limit on the statue's slide on the top face (top_sliding_limit = inf)."
            in design_report(top_limit_designs[math.inf]))


def test_bad_top_limits_are_refused_naming_the_field(cli, tmp_path, capsys):
    for bad in (0.0, -0.1, math.nan, "0.2", True):
        with pytest.raises(ValueError, match=r"^top_sliding_limit must be a number > 0 \(m\), or inf for no limit"):
            friction_design(SYSTEM, {"m": MOTION}, mu_s=[0.3], mu_s_top=[0.2], top_sliding_limit=bad, workers=1)
    with pytest.raises(ValueError, match="top_sliding_limit needs the stack engine"):
        friction_design(SYSTEM, {"m": MOTION}, mu_s=[0.3], top_sliding_limit=0.1, workers=1)
    cfg = tmp_path / "bad.toml"
    for text, said in (("0", "must be a number > 0 (m), or inf for no limit, got 0.0"),
                       ("-0.05", "must be a number > 0 (m), or inf for no limit, got -0.05"),
                       ("nan", "must be a number > 0 (m), or inf for no limit, got nan"),
                       ('"wide"', "must be a number, got 'wide'")):
        cfg.write_text(STACK_CONFIG.format(design=f"top_sliding_limit = {text}"))
        assert cli(["design", str(cfg)]) == 2
        err = capsys.readouterr().err
        assert f"design.top_sliding_limit: {said}" in err and len(err.strip().splitlines()) == 1
    # the seed's model: the statue never slips on its pedestal, so there is nothing to limit
    cfg.write_text("[statue]\nwidth = 0.4\nheight = 1.6\nmass = 200.0\n[pedestal]\nmass = 300.0\n"
                   "friction = { static = 0.3 }\n[motions]\nfamily = \"sine\"\namplitude = [4.0]\nfrequency = [1.0]\n"
                   "[design]\nmu_s = [0.3]\ntop_sliding_limit = 0.1\n")
    assert cli(["design", str(cfg)]) == 2
    assert "design.top_sliding_limit: applies on the stack engine" in capsys.readouterr().err


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
    ds = ida(stacks, {"r": rec}, [4.0, 10.0], free_time=10.0, options=OPTS_EDGE, workers=1)
    for label, stack in stacks.items():
        for j, level in enumerate((4.0, 10.0)):
            single = simulate_stack(stack, rec.scaled(level / rec.pga),
                                    options=rk.Options(gravity=G, free_time_limit=10.0, stop_at_edge=True)).summary()
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
    # runs still rocking at the cap with too little energy to fall: settled alike (3 and 6 of them
    # at β = 1 and 3); undetermined, counted as failing by default, they would lower the boundary
    np.testing.assert_array_equal(ours.settling_runs.values, ref.settling_runs.values)
    assert int(ours.settling_runs.sum()) > 0 and int(ours.undetermined_runs.sum()) == 0


def test_a_one_block_stack_left_rocking_is_settled_only_inside_its_barrier():
    """A one-block stack cut while it rocks gently after its pulse is settled (E − E₀ below
    m·g·(R − H/2), inside α), and says so in its summary, verdict and report; cut at the same
    instant while the floor still moves, it is not (the floor may still give it energy). One cut
    as it falls, past α, is not, although its energy is below the barrier (E − E₀ < 0: past α its
    weight works for it); a two-block stack never is (no bound is known for it)."""
    from rocking.analyses.spectra import spectrum_motion
    from rocking.report.stack import stack_checks, stack_verdict

    block = Stack(blocks=(Block(width=0.3, height=1.5, mass=1.0),), interfaces=(Interface(),))
    alpha, barrier = math.atan(0.2), G * (math.hypot(0.15, 0.75) - 0.75)
    gentle = simulate_stack(block, rk.SinePulse(amplitude=4.0, frequency=3.0), duration=0.5, options=OPTS)
    assert gentle.status == "still_moving" and 1e-3 < abs(gentle.rotation[-1, 0]) < alpha
    assert 0 < gentle.energy[-1] - gentle.initial_energy < barrier
    assert gentle.settled_by_energy and gentle.summary()["settled_by_energy"]
    assert gentle.verdict.startswith("did not overturn; still moving at t = 0.500 s, with less energy")
    assert stack_verdict(gentle).startswith("No block overturns: the block is still moving")
    rest = [c for c in stack_checks(gentle) if c.name.startswith("run ends at rest")]
    assert [c.result for c in rest] == ["pass"]
    during = simulate_stack(block, rk.SinePulse(amplitude=4.0, frequency=1.5), duration=0.5, options=OPTS)
    assert during.status == "still_moving" and 0 < during.energy[-1] - during.initial_energy < barrier
    assert not during.settled_by_energy and during.verdict.startswith("undetermined: still moving")
    statue = rk.Statue(width=0.3, height=1.5, mass=1.0)
    pulse = spectrum_motion("sine", 1.479, 1.0, g_tan_alpha=G * 0.2, p=statue.frequency_parameter(G))
    falling = simulate_stack(block, pulse, duration=pulse.duration + 0.01, options=OPTS)
    assert falling.status == "still_moving" and abs(falling.rotation[-1, 0]) > 2 * alpha
    assert falling.energy[-1] - falling.initial_energy < 0
    assert not falling.settled_by_energy
    assert simulate_stack(block, pulse, options=OPTS).status == "overturned"  # (it does fall)
    # the same saved at the start, its events and its end only: the sample before the end is
    # inside α, the end is not, and the rule reads the end's rotation
    sparse = simulate_stack(block, pulse, duration=pulse.duration + 0.01,
                            options=dataclasses.replace(OPTS, save_dt=10.0))
    assert abs(sparse.rotation[-2, 0]) < alpha < abs(sparse.rotation[-1, 0]) and not sparse.settled_by_energy
    # cut exactly as the pulse ends: the floor has stopped, and the block rocks gently on
    pulse3 = rk.SinePulse(amplitude=4.0, frequency=3.0)
    at_end = simulate_stack(block, pulse3, duration=pulse3.duration, options=OPTS)
    assert at_end.status == "still_moving" and at_end.end_time == pulse3.duration
    assert at_end.settled_by_energy
    two = Stack(blocks=(Block(width=1.0, height=0.3, mass=50.0), Block(width=0.3, height=1.5, mass=1.0)),
                interfaces=(Interface(), Interface()))
    rocking_on_top = simulate_stack(two, rk.SinePulse(amplitude=4.0, frequency=3.0), duration=0.5, options=OPTS)
    assert rocking_on_top.status == "still_moving"
    assert not rocking_on_top.settled_by_energy


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
