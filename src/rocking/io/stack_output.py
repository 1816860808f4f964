"""Write a stack run's results to a folder: a CSV time series, the JSON summary, a figure.

The counterpart of :func:`rocking.io.output.write_outputs` for :class:`rocking.stack.StackResponse`,
with the same guarantees (all files or none, see :func:`rocking.io.output.write_files`).

``timeseries.csv`` has one row per saved instant (at an event the rows before and after share
the time): ``time_s``, then for each block from the floor up ``<name>_x_m``, ``<name>_y_m``,
``<name>_theta_rad`` (X, Y, Θ of its centre in the floor's frame, Θ positive clockwise),
``<name>_phi_rad`` (φ, its rotation relative to the block below) and ``<name>_sliding_m``
(its slide along the face below). ``<name>`` is the block's name with every character other
than a letter, digit, ``-`` or ``_`` replaced by ``_`` (``block1``, ``block2``... if that
leaves two blocks with one name).
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from .output import OutputSpaceError, _existing_folder, human_bytes, summary_json, write_files

__all__ = ["STACK_OUTPUT_FILES", "check_stack_output_space", "csv_header", "estimate_stack_output_bytes",
           "plot_stack_response", "write_stack_outputs"]

#: The files :func:`write_stack_outputs` creates, in order.
STACK_OUTPUT_FILES = ("timeseries.csv", "summary.json", "response.png")

#: Columns of the CSV per block: (suffix, what it holds).
_BLOCK_COLUMNS = ("x_m", "y_m", "theta_rad", "phi_rad", "sliding_m")
# A "%.10g" number takes at most 16 characters (-1.234567891e-05), plus its comma or newline.
_NUMBER_BYTES = 17
# The figure and the summary do not grow with the run (measured: < 200 kB).
_FIXED_BYTES = 1_000_000
_CSV_BLOCK_ROWS = 50_000


def fall_text(summary: dict, k: int) -> str:
    """Whether block k of a stack's summary fell, in words: "at 2.125 s", "no", or, when the run
    stopped at another block's fall (or slide to an edge) first, that its fate is not known: a
    vase on a statue that falls has not been seen to stay up. A block that went past the edge of
    the one below and stayed on says so: "no (past the edge below at 2.978 s)"."""
    block = summary["blocks"][k]
    if block["overturned"]:
        return f"at {block['overturn_time']:.3f} s"
    fallen = [b for b in summary["blocks"] if b["overturned"]]
    if fallen:
        first = min(fallen, key=lambda b: b["overturn_time"])
        return f"not known (run stopped at {first['name']}'s fall)"
    if summary.get("status") == "slid_past_edge":
        return "not known (run stopped at a slide to an edge)"
    if block.get("past_edge_time") is not None:
        return f"no (past the edge below at {block['past_edge_time']:.3f} s)"
    return "no"


def _labels(names: tuple[str, ...]) -> list[str]:
    slugs = [re.sub(r"[^A-Za-z0-9_-]", "_", name) for name in names]
    if len(set(slugs)) < len(slugs):
        slugs = [f"block{k + 1}" for k in range(len(names))]
    return slugs


def csv_header(names: tuple[str, ...]) -> list[str]:
    """The CSV's column names for blocks called ``names`` (from the floor up)."""
    return ["time_s"] + [f"{label}_{col}" for label in _labels(names) for col in _BLOCK_COLUMNS]


def _write_csv(response: Any, path: Path) -> None:
    pose = np.asarray(response.pose)  # (n, N, 3): X, Y, Θ
    per_block = np.concatenate((pose, np.asarray(response.rotation)[:, :, None],
                                np.asarray(response.sliding)[:, :, None]), axis=2)  # (n, N, 5)
    t = np.asarray(response.t)
    with open(path, "w", encoding="utf-8", newline="") as f:
        f.write(",".join(csv_header(response.stack.names)) + "\n")
        for start in range(0, t.size, _CSV_BLOCK_ROWS):
            stop = start + _CSV_BLOCK_ROWS
            rows = np.column_stack((t[start:stop], per_block[start:stop].reshape(len(t[start:stop]), -1)))
            np.savetxt(f, rows, fmt="%.10g", delimiter=",")


def plot_stack_response(response: Any, path: str | os.PathLike[str], *, title: str | None = None) -> None:
    """Save :func:`rocking.viz.stack_plots.plot_stack_response` (each block's rotation φ on the
    block below, in degrees, and its slide along that block's face, in mm, versus t in s; a dashed
    line where a block overturned) to ``path``, headed by ``title`` (default: the verdict)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from ..viz.stack_plots import plot_stack_response as draw

    fig = draw(response, title=title or response.verdict)
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=120)


def estimate_stack_output_bytes(n_samples: int, n_blocks: int) -> int:
    """An upper bound of the bytes :func:`write_stack_outputs` writes for ``n_samples`` rows."""
    return 200 + max(0, int(n_samples)) * (1 + 5 * n_blocks) * _NUMBER_BYTES + _FIXED_BYTES


def check_stack_output_space(n_samples: int, n_blocks: int, out_dir: str | os.PathLike[str], *,
                             hint: str = "") -> int:
    """Refuse, before anything is written, outputs larger than the free space where they go.

    Returns
    -------
    int
        :func:`estimate_stack_output_bytes`.

    Raises
    ------
    OutputSpaceError
        Naming the sizes, the free space and ``hint`` (what the user can change).
    """
    need = estimate_stack_output_bytes(n_samples, n_blocks)
    where = _existing_folder(Path(out_dir))
    try:
        free = shutil.disk_usage(where).free
    except OSError:
        return need  # no answer from the file system: the writer reports any real failure
    if need > free:
        raise OutputSpaceError(
            f"--out: {n_samples:.3g} saved samples of {n_blocks} blocks would write up to {human_bytes(need)}, "
            f"but only {human_bytes(free)} is free on {where}" + (f"; {hint}" if hint else "")
        )
    return need


def write_stack_outputs(response: Any, out_dir: str | os.PathLike[str], *, config: Any = None) -> dict[str, Path]:
    """Write ``timeseries.csv``, ``summary.json`` and ``response.png`` of a stack run into ``out_dir``.

    Parameters
    ----------
    response : rocking.stack.StackResponse
    out_dir : path-like
        Target folder, created if missing; files of the same names are replaced, others kept.
    config : StackConfig, optional
        Its file's name heads the figure.

    Returns
    -------
    dict
        ``{file name: path}``.
    """
    if np.asarray(response.t).size == 0:
        raise ValueError("the response has no time series")
    title = response.verdict
    if config is not None and getattr(config, "source", None):
        title = f"{Path(config.source).name}: {title}"
    return write_files(out_dir, {
        "timeseries.csv": lambda path: _write_csv(response, path),
        "summary.json": lambda path: path.write_text(summary_json(response.summary()) + "\n", encoding="utf-8"),
        "response.png": lambda path: plot_stack_response(response, path, title=title),
    })
