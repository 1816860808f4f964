"""Plots and animation: image regression against tests/baseline/, and the numbers behind them.

Baselines: a missing baseline fails the test unless ``ROCKING_UPDATE_BASELINES=1`` is set, in
which case it is written (delete a baseline and rerun with the variable to regenerate it).
"""

from __future__ import annotations

import math
import os
import shutil
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.testing import set_font_settings_for_testing, set_reproducibility_for_testing  # noqa: E402
from matplotlib.testing.compare import compare_images  # noqa: E402

import rocking as rk  # noqa: E402
from rocking.viz import animation as anim_mod  # noqa: E402
from rocking.viz import (  # noqa: E402
    animate,
    energy_series,
    floor_motion,
    frame_times,
    plot_design_chart,
    plot_energy,
    plot_fragility,
    plot_regimes,
    plot_response,
    plot_spectrum,
)

BASELINE = Path(__file__).resolve().parent / "baseline"
TOL = 5.0  # RMS of the pixel difference (0–255)
DPI = 72


# ----------------------------------------------------------------------------- fixtures
@pytest.fixture(autouse=True)
def _mpl_defaults():
    """Matplotlib's default rcParams with its test font settings, restored afterwards."""
    with matplotlib.rc_context():
        matplotlib.rcdefaults()
        set_font_settings_for_testing()
        set_reproducibility_for_testing()
        yield


def _friction(static, kinetic):
    return rk.Friction(static=static, kinetic=kinetic)


@pytest.fixture(scope="module")
def pedestal_response():
    """The paper's Table 1 statue (B = 1, H = 4, r = 0.8) on its pedestal, 3 cycles of
    6.75 cos(2π·1.2 t) m/s², then 1.5 s of free motion: rock, slide-rock and impacts."""
    statue = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8, friction=_friction(0.4, 0.3))
    system = rk.System(statue=statue, pedestal=rk.Pedestal(mass=1.0, friction=_friction(0.4, 0.3)))
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=3)
    return rk.simulate(system, motion, duration=4.0, options=rk.Options(gravity=9.81))


@pytest.fixture(scope="module")
def overturn_response():
    """The paper's case 10b statue alone (H = 5 m) on a floor it cannot slide on: it falls."""
    statue = rk.Statue(width=1.0, height=5.0, mass=1.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=12)
    return rk.simulate(rk.System(statue=statue), motion, options=rk.Options(gravity=9.81))


@pytest.fixture(scope="module")
def short_response():
    """A 1 s run for the animation."""
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    system = rk.System(statue=statue, pedestal=rk.Pedestal(mass=50.0, friction=_friction(0.3, 0.22), width=0.6, height=0.4))
    return rk.simulate(system, rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=1.5), duration=1.0)


# -------------------------------------------------------------------------- image helper
def assert_image_matches(fig: Figure, name: str, tmp_path: Path, tol: float = TOL) -> None:
    """Compare ``fig`` saved as PNG with ``tests/baseline/<name>.png`` (RMS ≤ tol)."""
    actual = tmp_path / f"{name}.png"
    fig.savefig(actual, dpi=DPI, metadata={"Software": None})
    expected = BASELINE / f"{name}.png"
    if not expected.exists():
        if os.environ.get("ROCKING_UPDATE_BASELINES") == "1":
            BASELINE.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(actual, expected)
        else:
            pytest.fail(f"missing baseline {expected}; rerun with ROCKING_UPDATE_BASELINES=1 to create it")
    result = compare_images(str(expected), str(actual), tol=tol)
    if result is not None:
        pytest.fail(f"{name}: image differs from the baseline: {result}")


# ------------------------------------------------------------------------- image tests
def test_plot_response_image(pedestal_response, tmp_path):
    fig = plot_response(pedestal_response)
    assert isinstance(fig, Figure) and len(fig.axes) == 3
    assert_image_matches(fig, "plot_response", tmp_path)


def test_plot_response_overturn_image(overturn_response, tmp_path):
    assert overturn_response.overturned
    assert_image_matches(plot_response(overturn_response), "plot_response_overturn", tmp_path)


def test_plot_regimes_image(pedestal_response, tmp_path):
    fig = Figure(figsize=(6.4, 1.3), layout="constrained")
    ax = fig.add_subplot()
    assert plot_regimes(pedestal_response, ax) is ax
    assert_image_matches(fig, "plot_regimes", tmp_path)


def test_plot_energy_image(pedestal_response, tmp_path):
    ax = plot_energy(pedestal_response)
    labels = ax.get_legend().get_texts()
    assert any("input work" in t.get_text() for t in labels)
    assert_image_matches(ax.figure, "plot_energy", tmp_path)


def _spectrum_arrays():
    fr = np.linspace(0.5, 10.0, 40)
    return fr, 1.0 + 0.15 * fr + 0.02 * fr**2


def test_plot_spectrum_image(tmp_path):
    fr, ar = _spectrum_arrays()
    band = np.linspace(3.0, 5.0, 20)
    ax = plot_spectrum(frequency_ratio=fr, amplitude_ratio=ar,
                       safe_islands=[(band, np.full(20, 1.9), np.full(20, 2.4)),
                                     np.array([[7.0, 4.0], [8.0, 4.0], [7.5, 4.6]])])
    assert_image_matches(ax.figure, "plot_spectrum", tmp_path)


def test_plot_fragility_image(tmp_path):
    im = np.linspace(1.0, 10.0, 10)
    p = np.clip((im - 2.0) / 6.0, 0.0, 1.0)
    x = np.linspace(0.1, 11.0, 50)
    ax = plot_fragility(im, p, 5.0, 0.4, label="statue", band=(x, np.clip(x / 11 - 0.1, 0, 1), np.clip(x / 11 + 0.1, 0, 1)),
                        counts=np.full(10, 20))
    assert_image_matches(ax.figure, "plot_fragility", tmp_path)


def test_plot_design_chart_image(tmp_path):
    mu = np.linspace(0.05, 0.6, 12)
    rot = 0.2 + 2.0 * mu
    rot[-1] = np.inf  # overturned: clipped and marked
    ax = plot_design_chart(mu, rot, 0.3 * np.exp(-5.0 * mu), np.clip(2.0 * mu - 0.6, 0.0, 1.0), tan_alpha=0.25)
    assert hasattr(ax, "right_ax") and ax.right_ax.get_ylabel() == "peak sliding (mm)"
    assert_image_matches(ax.figure, "plot_design_chart", tmp_path)


def test_plot_design_chart_scatter_band_image(tmp_path):
    """The recommended μs = 0.2 with its friction scatter band [0.16, 0.24] shaded, below tan α."""
    mu = np.linspace(0.05, 0.45, 9)
    rot = np.where(mu < 0.25, 0.0, 1.2 + mu)
    ax = plot_design_chart(mu, rot, 0.3 * np.exp(-5.0 * mu), np.where(mu < 0.25, 0.0, 1 / 6), tan_alpha=0.25,
                           recommended=0.2, friction_scatter=0.2)
    band = [p for p in ax.patches if p.get_label() == "μs·(1 ± 0.2)"]
    assert len(band) == 1
    patch = band[0]  # a Rectangle (matplotlib ≥ 3.9) or a Polygon
    xs = [patch.get_x(), patch.get_x() + patch.get_width()] if hasattr(patch, "get_width") else patch.get_xy()[:, 0]
    assert min(xs) == pytest.approx(0.16) and max(xs) == pytest.approx(0.24)
    assert_image_matches(ax.figure, "plot_design_chart_band", tmp_path)


# ----------------------------------------------------------------- behaviour of the plots
def test_plots_draw_into_given_axes(pedestal_response):
    fig = Figure()
    axes = fig.subplots(3, 1)
    assert plot_response(pedestal_response, axes=axes) is fig
    ax = Figure().add_subplot()
    assert plot_energy(pedestal_response, ax) is ax
    fr, ar = _spectrum_arrays()
    assert plot_spectrum((fr, ar), ax) is ax
    assert plot_fragility([1, 2], [0, 1], None, None, ax) is ax


def test_plot_spectrum_inputs():
    fr, ar = _spectrum_arrays()
    ax = plot_spectrum({"frequency_ratio": fr, "amplitude_ratio": ar})
    assert ax.get_xlabel().startswith("frequency ratio ω_p/p")
    grid = np.outer(np.linspace(0, 5, 6), np.ones(fr.size)) > 2.5
    plot_spectrum(frequency_ratio=fr, amplitude_ratio=np.linspace(0, 5, 6), overturned=grid)
    with pytest.raises(ValueError):
        plot_spectrum(frequency_ratio=fr, amplitude_ratio=ar[:-1])
    with pytest.raises(ValueError):
        plot_spectrum()


def test_energy_series_matches_the_ledger(pedestal_response):
    """E(t_end) = E(t0) + W − D_friction − D_impact: the viz evaluation of T + V agrees with the
    solver's ledger (and starts from 0 for a system at rest)."""
    r = pedestal_response
    e = energy_series(r)
    led = r.energy
    assert e.shape == r.t.shape
    assert e[0] == pytest.approx(0.0, abs=1e-12)
    predicted = e[0] + led["input_work"] - led["friction_dissipation"] - led["impact_dissipation"]
    assert e[-1] == pytest.approx(predicted, rel=1e-6, abs=1e-9 * max(1.0, led["input_work"]))


def test_floor_motion_is_the_double_integral(pedestal_response):
    """Cosine floor acceleration A cos ωt from rest: x = A(1 − cos ωt)/ω² while it lasts."""
    r = pedestal_response
    v, x = floor_motion(r)
    m = r.motion
    on = r.t <= m.duration
    expected = m.amplitude * (1.0 - np.cos(m.omega * r.t[on])) / m.omega**2
    assert np.allclose(x[on], expected, atol=2e-3 * np.max(np.abs(expected)))
    assert np.allclose(v[on], m.amplitude * np.sin(m.omega * r.t[on]) / m.omega, atol=1e-3 * m.amplitude / m.omega)


# ------------------------------------------------------------------------------ animation
def test_animation_gif_frames(short_response, tmp_path):
    from PIL import Image

    path = animate(short_response, tmp_path / "run.gif", fps=25)
    assert path == tmp_path / "run.gif" and path.exists()
    with Image.open(path) as im:
        assert im.n_frames == 25  # fps × duration / speed
        assert im.size == (480, 360)
        assert im.info.get("duration") == 40  # ms per frame: real time


def test_animation_speed_and_cut(short_response, tmp_path):
    from PIL import Image

    assert frame_times(short_response, speed=0.5, fps=10).size == 20
    path = animate(short_response, tmp_path / "cut.gif", fps=10, speed=0.5, max_seconds=0.5)
    with Image.open(path) as im:
        assert im.n_frames == 5
    times = frame_times(short_response, fps=10)
    assert times[0] == short_response.t[0] and times[-1] == short_response.t[-1]


def test_animation_rejects_bad_requests(short_response, tmp_path, monkeypatch):
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        animate(short_response, tmp_path / "run.avi")
    with pytest.raises(ValueError, match="speed"):
        animate(short_response, tmp_path / "run.gif", speed=0)
    # where matplotlib looks for ffmpeg: a path that does not exist stands for "not installed"
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", str(tmp_path / "no-ffmpeg"))
    with pytest.raises(RuntimeError, match=r"ffmpeg.*\.gif"):
        animate(short_response, tmp_path / "run.mp4")


def test_statue_outline_rotates_about_the_active_corner():
    b, h, th = 0.5, 2.0, 0.3
    pts = anim_mod._statue_outline(0.0, 1.0, b, h, th)
    assert np.allclose(pts[1], [b, 1.0])  # the +b corner is the pivot for θ > 0
    assert pts[2, 0] > b and pts[3, 0] > -b  # top moves towards +x
    assert np.allclose(np.linalg.norm(pts[2] - pts[1]), 2 * h)
    pts = anim_mod._statue_outline(0.0, 0.0, b, h, -th)
    assert np.allclose(pts[0], [-b, 0.0])  # the −b corner for θ < 0
    assert pts[3, 0] < -b
    assert np.allclose(anim_mod._statue_outline(1.0, 0.0, b, h, 0.0)[:, 0], [0.5, 1.5, 1.5, 0.5])


def test_animation_of_an_overturn(overturn_response, tmp_path):
    from PIL import Image

    path = animate(overturn_response, tmp_path / "fall.gif", fps=5)
    expected = max(1, round(5 * overturn_response.t[-1]))
    with Image.open(path) as im:
        assert im.n_frames == expected
    assert math.isclose(frame_times(overturn_response, fps=5)[-1], overturn_response.overturn_time, rel_tol=1e-9)
