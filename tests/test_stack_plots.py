"""Pictures of a stack of blocks: the response and energy plots draw every block, and the
animation's header keeps every block's rotation on the picture however many blocks and however
long their names."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import rocking as rk  # noqa: E402
from rocking.stack import Block, Interface, Stack, simulate_stack  # noqa: E402
from rocking.viz.stack_animation import header_lines, short_name  # noqa: E402
from rocking.viz.stack_plots import block_color, plot_stack_energy, plot_stack_response  # noqa: E402

NAMES = ("granite plinth base", "marble pedestal top", "bronze statue figure", "box", "ceramic vase body", "glass")


@pytest.fixture(scope="module")
def six_blocks():
    sizes = [(1.0, 0.5, 800.0), (0.8, 0.4, 400.0), (0.4, 1.0, 200.0), (0.3, 0.2, 20.0), (0.2, 0.4, 8.0),
             (0.1, 0.3, 1.0)]
    blocks = tuple(Block(name=n, width=w, height=h, mass=m) for n, (w, h, m) in zip(NAMES, sizes))
    stack = Stack(blocks=blocks, interfaces=tuple(Interface(friction=rk.Friction(static=0.5)) for _ in blocks))
    return simulate_stack(stack, rk.SinePulse(amplitude=4.0, frequency=1.5))


def test_the_header_wraps_the_rotations_within_its_width():
    lines = header_lines(NAMES, width=60)
    assert sorted(k for line in lines for k in line) == list(range(6))  # every block, once, in order
    assert [k for line in lines for k in line] == list(range(6))
    for line in lines:
        text = "   ".join(f"{short_name(NAMES[k])}: {-12.3:+5.1f}°" for k in line)
        assert len(text) <= 60, text
    assert len(lines) > 1
    assert header_lines(("a", "b"), width=60) == [[0, 1]]
    assert short_name("granite plinth base") == "granite plinth …" and short_name("box") == "box"


def test_the_response_draws_every_block_in_its_colour(six_blocks):
    fig = plot_stack_response(six_blocks)
    phi, sliding = fig.axes
    for ax, series in ((phi, np.degrees(six_blocks.rotation)), (sliding, 1e3 * six_blocks.sliding)):
        curves = [line for line in ax.get_lines() if len(line.get_xdata()) > 2]
        assert [line.get_color() for line in curves] == [block_color(k) for k in range(6)]
        for k, line in enumerate(curves):  # each block's own series (decimated, peaks kept)
            assert np.max(np.abs(line.get_ydata())) == pytest.approx(np.max(np.abs(series[:, k])), rel=1e-12)
    labels = [t.get_text() for t in phi.get_legend().get_texts()]
    assert labels[:6] == list(NAMES)


def test_the_legends_stay_off_the_data(six_blocks):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    for fig in (plot_stack_response(six_blocks, motion=rk.SinePulse(amplitude=4.0, frequency=1.5)),
                plot_stack_energy(six_blocks).figure):
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw_without_rendering()
        legend = fig.axes[0].get_legend().get_window_extent(renderer)
        for ax in fig.axes:
            box = ax.get_window_extent(renderer)
            assert not (legend.x0 < box.x1 and box.x0 < legend.x1 and legend.y0 < box.y1 and box.y0 < legend.y1)


def test_the_energy_ledger_lies_on_the_energy(six_blocks):
    ax = plot_stack_energy(six_blocks)
    energy, ledger = ax.get_lines()[:2]
    assert np.allclose(energy.get_ydata(), six_blocks.energy - six_blocks.initial_energy)
    scale = np.max(np.abs(six_blocks.input_work))
    assert np.max(np.abs(energy.get_ydata() - ledger.get_ydata())) <= 1e-6 * scale
