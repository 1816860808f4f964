"""Stack files (``[[blocks]]``, ``[[interfaces]]``): parsing, one clear error per bad input, and
``rocking run`` of a stack (issue 11 §5).

The commands run in-process through ``rocking.cli.main(argv)``, as in test_cli.py; the runs are
short (half a second of a sine pulse), so once the stack engine is compiled each takes milliseconds.
"""

from __future__ import annotations

import copy
import json
import math
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest
from rich.console import Console

import rocking as rk
from rocking import runner
from rocking.cli import main
from rocking.cli.render import outcome_markup
from rocking.cli.stack_run import stack_tables
from rocking.io.config import Config, ConfigError, StackConfig, load_config
from rocking.io.stack_output import STACK_OUTPUT_FILES, csv_header
from rocking.stack import Stack

ROOT = Path(__file__).resolve().parents[1]
PEDESTAL = ROOT / "examples" / "stack_statue_on_pedestal.toml"
THREE = ROOT / "examples" / "stack_three_blocks.toml"

TOML = """\
[[blocks]]
name = "pedestal"
width = 0.8
height = 0.5
mass = 300.0

[[blocks]]
name = "statue"
width = 0.3
height = 1.2
mass = 100.0

[[interfaces]]
friction = { static = 0.3, kinetic = 0.25 }

[[interfaces]]
friction = { static = 0.5, kinetic = 0.4 }
restitution = 0.8

[motion]
kind = "pulse"
shape = "sine"
amplitude = 3.5
frequency = 1.0

[simulation]
duration = 0.5
"""

BASE = tomllib.loads(TOML)


def _mutated(change) -> dict:
    d = copy.deepcopy(BASE)
    change(d)
    return d


def _run_cli(capsys, *args) -> tuple[int, str, str]:
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def stack_toml(tmp_path) -> Path:
    f = tmp_path / "stack.toml"
    f.write_text(TOML, encoding="utf-8")
    return f


# ------------------------------------------------------------------------ examples
def test_statue_on_pedestal_example_gives_the_stack():
    cfg = load_config(PEDESTAL)
    assert isinstance(cfg, StackConfig) and cfg.source == str(PEDESTAL)
    stack, motion, options, duration = cfg.to_specs()
    assert isinstance(stack, Stack) and stack.names == ("pedestal", "statue")
    pedestal, statue = stack.blocks
    assert (pedestal.width, pedestal.height, pedestal.mass, pedestal.inertia) == (0.8, 0.5, 300.0, None)
    assert (statue.width, statue.height, statue.mass, statue.offset) == (0.3, 1.2, 100.0, 0.0)
    floor, top = stack.interfaces
    assert (floor.friction.static, floor.friction.kinetic) == (0.3, 0.25)
    assert (top.friction.static, top.friction.kinetic) == (0.5, 0.4) and top.restitution is None
    assert isinstance(motion, rk.SinePulse) and isinstance(options, rk.Options) and duration is None


def test_three_blocks_example_gives_the_stack():
    stack, motion, options, duration = load_config(THREE).to_specs()
    assert stack.names == ("plinth", "statue", "vase")
    assert stack.blocks[1].inertia == 45.0 and stack.blocks[2].offset == 0.05
    assert stack.interfaces[1].friction.mu_k == stack.interfaces[1].friction.mu_s == 0.6  # kinetic = static
    assert stack.interfaces[2].restitution == 0.7
    assert options.free_time_limit == 10.0


def test_dict_and_toml_give_the_same_stack(stack_toml):
    assert load_config(stack_toml).to_specs() == load_config(BASE).to_specs()


def test_defaults_an_interface_without_friction_never_slips_and_names_are_optional():
    d = _mutated(lambda d: (d["interfaces"][1].pop("friction"), d["blocks"][0].pop("name")))
    stack, *_ = load_config(d).to_specs()
    assert stack.interfaces[1].friction is None
    assert stack.names == ("block 1", "statue")
    assert stack.blocks[0].centroidal_inertia == pytest.approx(300.0 * (0.8**2 + 0.5**2) / 12)


def test_a_single_statue_file_still_gives_a_config():
    single = {"statue": {"width": 0.3, "height": 1.2, "mass": 100.0},
              "motion": {"kind": "pulse", "shape": "sine", "amplitude": 3.0, "frequency": 1.0}}
    assert type(load_config(single)) is Config


# ------------------------------------------------------------------------ bad input
# (id, change to the dict, the field the message names, words it must contain)
BAD = [
    ("too-few-interfaces", lambda d: d["interfaces"].pop(), "interfaces",
     ["2 blocks need 2 interfaces", "floor–pedestal, pedestal–statue", "got 1"]),
    ("too-many-interfaces", lambda d: d["interfaces"].append({}), "interfaces", ["2 blocks need 2", "got 3"]),
    ("no-overlap", lambda d: d["blocks"][1].update(offset=0.55), "blocks[1].offset",
     ["no overlap", "pedestal", "< (width + width below)/2 = 0.55 m", "got 0.55"]),
    ("no-overlap-left", lambda d: d["blocks"][1].update(offset=-0.7), "blocks[1].offset", ["got -0.7"]),
    ("negative-inertia", lambda d: d["blocks"][1].update(inertia=-2.0), "blocks[1].inertia",
     ["must be > 0", "got -2.0"]),
    ("zero-width", lambda d: d["blocks"][0].update(width=0), "blocks[0].width", ["must be > 0", "got 0"]),
    ("missing-mass", lambda d: d["blocks"][1].pop("mass"), "blocks[1].mass", ["missing"]),
    ("string-offset", lambda d: d["blocks"][1].update(offset="left"), "blocks[1].offset", ["a number", "'left'"]),
    ("unknown-block-key", lambda d: d["blocks"][1].update(widht=0.3), "blocks[1].widht",
     ["unknown key", "did you mean 'width'"]),
    ("unknown-interface-key", lambda d: d["interfaces"][0].update(frction=0.3), "interfaces[0].frction",
     ["unknown key", "did you mean 'friction'"]),
    ("unknown-top-level-key", lambda d: d.update(blokcs=[]), "blokcs", ["unknown key", "did you mean 'blocks'"]),
    ("restitution-above-1", lambda d: d["interfaces"][1].update(restitution=1.5), "interfaces[1].restitution",
     ["must be <= 1", "got 1.5"]),
    ("kinetic-above-static", lambda d: d["interfaces"][0].update(friction={"static": 0.3, "kinetic": 0.4}),
     "interfaces[0].friction.kinetic", ["must be <= static (0.3)", "got 0.4"]),
    ("repeated-name", lambda d: d["blocks"][1].update(name="pedestal"), "blocks[1].name",
     ["'pedestal'", "already the name of blocks[0]"]),
    ("empty-name", lambda d: d["blocks"][1].update(name=""), "blocks[1].name", ["must not be empty"]),
    ("no-blocks", lambda d: d.update(blocks=[]), "blocks", ["must not be empty"]),
    ("blocks-as-a-table", lambda d: d.update(blocks={"width": 1.0}), "blocks", ["array of tables", "[[blocks]]"]),
    ("interfaces-without-blocks", lambda d: d.pop("blocks"), "blocks", ["missing"]),
    ("statue-and-blocks", lambda d: d.update(statue={"width": 0.3, "height": 1.2, "mass": 100.0}), "blocks",
     ["[statue]", "[[blocks]]", "either"]),
    ("pedestal-and-blocks", lambda d: d.update(pedestal={"mass": 50.0}), "blocks", ["[pedestal]"]),
    ("paper-normal-force", lambda d: d["simulation"].update(normal_force="paper"), "simulation.normal_force",
     ["'paper'", "single-statue solver"]),
]


@pytest.mark.parametrize(("change", "field", "words"), [c[1:] for c in BAD], ids=[c[0] for c in BAD])
def test_bad_stack_input_is_one_error_naming_the_field(change, field, words):
    with pytest.raises(ConfigError) as info:
        load_config(_mutated(change))
    message = str(info.value)
    assert info.value.field == field, message
    assert message.startswith(f"{field}: ") and "\n" not in message, message
    for w in words:
        assert w in message, (w, message)


def test_a_stack_built_in_python_names_the_block_that_has_no_overlap():
    """The same rule without a file: blocks are counted from the floor, from 0 as in a file's
    [[blocks]], so the vase (the third block) is blocks[2]; its overlap with the statue,
    [0.4, 0.6] ∩ [−0.2, 0.2], is empty."""
    from rocking.stack import Block, Interface

    blocks = (Block(width=1.0, height=0.4, mass=300.0), Block(width=0.4, height=1.2, mass=100.0),
              Block(width=0.2, height=0.3, mass=5.0, offset=0.5))
    with pytest.raises(ValueError, match=r"^blocks\[2\]\.offset = 0\.5 m leaves no overlap .*width -0\.2 m"):
        Stack(blocks=blocks, interfaces=(Interface(),) * 3)
    with pytest.raises(ValueError, match=r"^interfaces: 3 blocks need 3 interfaces .*got 2$"):
        Stack(blocks=blocks, interfaces=(Interface(),) * 2)
    # faces that only touch at a point: an overlap of zero width is no support either
    # (binary-exact sizes: the right end of one face is the left end of the other to the bit)
    with pytest.raises(ValueError, match=r"^blocks\[1\]\.offset = 0\.375 m leaves no overlap .*width 0 m"):
        Stack(blocks=(Block(width=0.5, height=0.4, mass=300.0), Block(width=0.25, height=0.5, mass=10.0, offset=0.375)),
              interfaces=(Interface(),) * 2)
    # a block's own errors name it by its name, or by "?" without one
    with pytest.raises(ValueError, match=r"^blocks\[vase\]\.width"):
        Block(name="vase", width=-0.2, height=0.3, mass=5.0)
    with pytest.raises(ValueError, match=r"^blocks\[\?\]\.mass"):
        Block(width=0.2, height=0.3, mass=0.0)
    for offset in ("left", True, math.nan, math.inf):
        with pytest.raises(ValueError, match=r"^blocks\[\?\]\.offset must be a finite number \(m\)"):
            Block(width=0.2, height=0.3, mass=5.0, offset=offset)
    # not blocks nor interfaces: named by their place
    with pytest.raises(ValueError, match=r"^blocks\[1\] must be a Block, got 'statue'$"):
        Stack(blocks=(blocks[0], "statue"), interfaces=(Interface(),) * 2)
    with pytest.raises(ValueError, match=r"^interfaces\[0\] must be an Interface, got 0\.3$"):
        Stack(blocks=blocks[:1], interfaces=(0.3,))


def test_the_overlap_is_the_narrower_face_relative_to_the_block_below():
    """Ends of each interface's contact, relative to the centre of the block below (the floor:
    block 1's rest position): a narrower block's own face, a wider one's the face below."""
    from rocking.stack import Block, Interface

    stack = Stack(blocks=(Block(width=0.8, height=0.4, mass=300.0, offset=0.1),
                          Block(width=0.3, height=1.2, mass=100.0, offset=-0.1),
                          Block(width=0.6, height=0.3, mass=5.0)), interfaces=(Interface(),) * 3)
    assert stack.overlap(1) == pytest.approx((-0.3, 0.5), abs=1e-15)
    assert stack.overlap(2) == pytest.approx((-0.25, 0.05), abs=1e-15)
    assert stack.overlap(3) == pytest.approx((-0.15, 0.15), abs=1e-15)


def test_an_interface_takes_restitution_from_0_to_1_inclusive():
    from rocking.stack import Interface

    assert [Interface(restitution=r).restitution for r in (0.0, 0.5, 1.0)] == [0.0, 0.5, 1.0]
    for bad in (-1e-12, 1.0 + 1e-12, True):
        with pytest.raises(ValueError, match=r"^interface\.restitution must lie in \[0, 1\]"):
            Interface(restitution=bad)


def test_blocks_interfaces_and_stacks_are_immutable():
    """A stack is a value (rocking.stack.model: "immutable description"): nothing may change a
    block's size under a run that has read it. And its parts are built by keyword only."""
    import dataclasses

    from rocking.stack import Block, Interface

    block = Block(width=0.3, height=1.2, mass=100.0)
    stack = Stack(blocks=(block,), interfaces=(Interface(),))
    # and each is built by keyword only: a width and a height are too easy to swap
    for build in (lambda: Block(0.3, 1.2, 100.0), lambda: Interface(None, 0.5), lambda: Stack((block,), (Interface(),))):
        with pytest.raises(TypeError):
            build()
    for obj, field, value in ((block, "width", 0.5), (stack.interfaces[0], "restitution", 0.5),
                              (stack, "blocks", ())):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, field, value)


def test_a_file_without_statue_nor_blocks_says_both():
    with pytest.raises(ConfigError, match=r"^statue: missing \(required\); or describe a stack .*\[\[blocks\]\]"):
        load_config({"motion": BASE["motion"]})


def test_cli_bad_stack_file_exits_2_with_one_line_and_no_output(capsys, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text(TOML.replace("[[interfaces]]\nfriction = { static = 0.5, kinetic = 0.4 }\nrestitution = 0.8\n", ""),
                 encoding="utf-8")
    code, out, err = _run_cli(capsys, "run", f, "--out", tmp_path / "out")
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {f}: interfaces: 2 blocks need 2 interfaces"), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


# ------------------------------------------------------------------------ rocking run
def test_rocking_run_prints_the_verdict_and_tables_and_writes_the_files(capsys, stack_toml, tmp_path):
    out_dir = tmp_path / "results" / "stack"
    code, out, err = _run_cli(capsys, "run", stack_toml, "--out", out_dir)
    assert code == 0, err
    expected = runner.run(stack_toml)
    verdict = next(line for line in out.splitlines() if "outcome" in line)
    assert expected["verdict"] in verdict
    for words in ("peak rotation (°)", "peak sliding (mm)", "residual sliding (mm)", "friction needed",
                  "slip path (mm)", "floor–pedestal", "pedestal–statue"):
        assert words in out, words
    assert len([line for line in out.splitlines() if re.match(r"^\s+(pedestal|statue)\s", line)]) == 2

    wrote = re.search(r"^wrote (.+) to (.+)$", out, re.M)
    assert wrote is not None, out
    names = wrote.group(1).split(", ")
    assert names == list(STACK_OUTPUT_FILES) and Path(wrote.group(2)) == out_dir
    assert sorted(p.name for p in out_dir.iterdir()) == sorted(names)  # every file named, and only those
    assert not [p for p in out_dir.parent.iterdir() if p.name.startswith(".")]  # no temporary folder left

    summary = json.loads((out_dir / "summary.json").read_text(encoding="utf-8"))
    assert [b["name"] for b in summary["blocks"]] == ["pedestal", "statue"]
    assert [f["name"] for f in summary["interfaces"]] == ["floor–pedestal", "pedestal–statue"]
    assert summary["verdict"] == expected["verdict"]
    assert (out_dir / "response.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

    _, response = runner.run_response(stack_toml)
    csv = np.genfromtxt(out_dir / "timeseries.csv", delimiter=",", names=True)
    assert list(csv.dtype.names) == csv_header(("pedestal", "statue"))
    assert csv.dtype.names[:6] == ("time_s", "pedestal_x_m", "pedestal_y_m", "pedestal_theta_rad",
                                   "pedestal_phi_rad", "pedestal_sliding_m")
    np.testing.assert_allclose(csv["time_s"], response.t, rtol=1e-9)
    np.testing.assert_allclose(csv["statue_theta_rad"], response.pose[:, 1, 2], rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(csv["statue_sliding_m"], response.sliding[:, 1], rtol=1e-9, atol=1e-15)


def test_rocking_run_json_prints_only_the_summary(capsys, stack_toml, tmp_path):
    code, out, err = _run_cli(capsys, "run", stack_toml, "--json", "--out", tmp_path / "o")
    assert code == 0, err
    summary = json.loads(out)  # nothing but JSON on stdout
    assert {"blocks", "interfaces", "verdict", "overturned"} <= summary.keys()
    assert len(summary["blocks"]) == len(summary["interfaces"]) == 2
    assert err.strip() == f"wrote {', '.join(STACK_OUTPUT_FILES)} to {tmp_path / 'o'}"


def test_rocking_run_of_a_stack_keeps_the_sample_limit(capsys, stack_toml, tmp_path):
    code, out, err = _run_cli(capsys, "run", stack_toml, "--max-samples", "10", "--out", tmp_path / "o")
    assert code == 2 and out == ""
    assert err.startswith("error: simulation.save_dt:") and "simulation.max_samples = 10" in err
    assert len(err.strip().splitlines()) == 1 and not (tmp_path / "o").exists()


def test_the_verdict_is_coloured_as_for_one_statue():
    summary = {"overturned": True, "verdict": "statue overturned at t = 2.000 s", "impacts": 1, "end_time": 2.0,
               "energy_balance_error": 1e-10,
               "blocks": [{"name": "statue", "overturned": True, "overturn_time": 2.0, "peak_rotation": 1.5708,
                           "peak_sliding": 0.01, "residual_sliding": 0.01}],
               "interfaces": [{"name": "floor–statue", "required_friction": 0.3, "slip_path": 0.02, "impacts": 1}]}
    assert outcome_markup(summary).startswith("[bold red]")
    standing = [{**summary["blocks"][0], "overturned": False, "overturn_time": None}]
    assert outcome_markup({**summary, "overturned": False, "blocks": standing,
                           "verdict": "undetermined: x"}).startswith("[bold yellow]")
    assert outcome_markup({**summary, "overturned": False, "blocks": standing,
                           "verdict": "did not overturn"}).startswith("[bold green]")
    console = Console(record=True, width=120)
    console.print(stack_tables(summary, frictions=[None]))
    text = console.export_text()
    assert "statue overturned at t = 2.000 s" in text and "90.00" in text and "10.00" in text
    assert "never slips" in text and "20.00" in text


def test_the_paper_impact_law_is_accepted_for_stacks():
    """impact = "paper" runs on the stack engine (docs/theory/stack.md §6)."""
    stack, _, options, _ = load_config(_mutated(lambda d: d["simulation"].update(impact="paper"))).to_specs()
    assert options.impact == "paper"


def test_rocking_run_animates_a_stack(capsys, stack_toml, tmp_path):
    """--animate draws every block of the stack; the "wrote" line names animation.gif."""
    from PIL import Image

    code, out, err = _run_cli(capsys, "run", stack_toml, "--out", tmp_path / "o", "--animate")
    assert code == 0, err
    gif = tmp_path / "o" / "animation.gif"
    with Image.open(gif) as im:
        assert im.n_frames >= 12  # 0.5 s at 25 frames per second
    assert "animation.gif" in out.splitlines()[-1]


def test_rocking_animate_draws_a_stack(capsys, stack_toml, tmp_path):
    code, out, err = _run_cli(capsys, "animate", stack_toml, "-o", tmp_path / "stack.gif", "--fps", "10")
    assert code == 0, err
    assert (tmp_path / "stack.gif").stat().st_size > 0


def test_block_outline_turns_clockwise_about_the_centre():
    """A block 2 × 4 m centred at (1, 3), turned by θ: corner (b, −h) goes to
    (1 + b cos θ − h sin θ, 3 − b sin θ − h cos θ) (clockwise positive, as θ everywhere)."""
    from rocking.viz.stack_animation import block_outline

    theta = 0.3
    pts = block_outline(1.0, 3.0, theta, 1.0, 2.0)
    assert pts[1] == pytest.approx([1 + np.cos(theta) - 2 * np.sin(theta), 3 - np.sin(theta) - 2 * np.cos(theta)],
                                   abs=1e-15)
    assert np.mean(pts, axis=0) == pytest.approx([1.0, 3.0], abs=1e-15)


def test_the_verdict_of_a_stack_whose_middle_block_fell_is_red():
    """The top-level keys of a stack's summary describe the top block; a block below that fell
    must still colour the verdict red, not green."""
    from rocking.cli.render import outcome_markup

    summary = {"overturned": False, "verdict": "statue overturned at t = 2.120 s",
               "blocks": [{"name": "plinth", "overturned": False}, {"name": "statue", "overturned": True},
                          {"name": "vase", "overturned": False}]}
    assert outcome_markup(summary).startswith("[bold red]")
    summary["blocks"][1]["overturned"] = False
    summary["verdict"] = "did not overturn; at rest at t = 9.000 s"
    assert outcome_markup(summary).startswith("[bold green]")


def test_a_block_that_did_not_fall_before_the_run_stopped_is_not_said_to_stand():
    """The run stops at the first fall: the vase on a statue that fell was not seen to stay up,
    so its row says so instead of "no"; with no fall and no stop, "no"."""
    from rocking.io.stack_output import fall_text

    blocks = [{"name": "plinth", "overturned": False, "overturn_time": None},
              {"name": "statue", "overturned": True, "overturn_time": 2.125},
              {"name": "vase", "overturned": False, "overturn_time": None}]
    summary = {"status": "overturned", "blocks": blocks}
    assert [fall_text(summary, k) for k in range(3)] == [
        "not known (run stopped at statue's fall)", "at 2.125 s", "not known (run stopped at statue's fall)"]
    edge = {"status": "slid_past_edge", "blocks": [dict(b, overturned=False, overturn_time=None) for b in blocks]}
    assert fall_text(edge, 2) == "not known (run stopped at a slide to an edge)"
    calm = {"status": "completed", "blocks": edge["blocks"]}
    assert [fall_text(calm, k) for k in range(3)] == ["no", "no", "no"]
