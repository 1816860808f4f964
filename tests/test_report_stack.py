"""Reports of a stack of blocks (issue 11 §5): `rocking report stack.toml` writes the same A4
report as for one statue, with a check per block and per interface computed from the
StackResponse's summary, a table of each, and every block in the figures."""

from __future__ import annotations

import copy
import math
import re
import tomllib
from html import escape, unescape
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402

from rocking.report import write_report  # noqa: E402
from rocking.report import pdf as report_pdf  # noqa: E402
from rocking.report.content import (  # noqa: E402
    ENERGY_BALANCE_LIMIT,
    _mm,
    FAIL,
    NOT_APPLICABLE,
    NOT_CHECKED,
    PASS,
    UNDETERMINED,
)
from rocking.report.stack import build_stack_content, stack_figures, stack_verdict, stack_verdict_class  # noqa: E402
from rocking.runner import run_response  # noqa: E402
from test_report import A4, _pdf_pages  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
THREE = ROOT / "examples" / "stack_three_blocks.toml"  # the statue falls at 2.12 s
PAIR = tomllib.loads((ROOT / "examples" / "stack_statue_on_pedestal.toml").read_text(encoding="utf-8"))


def _standing_config() -> dict:
    """The statue on its pedestal with a slippery floor face (the pedestal slides 96 mm) and a
    statue–pedestal face without friction (never slips): every block stands, at rest at 1.18 s."""
    config = copy.deepcopy(PAIR)
    config["interfaces"] = [{"friction": {"static": 0.2, "kinetic": 0.15}}, {}]
    config["motion"]["amplitude"] = 3.0
    return config


def _edge_config() -> dict:
    """The three blocks under a scaled record: the vase slides to the statue's edge at 5.07 s, where
    the run stops (``stop_at_edge``, the conservative criterion)."""
    config = tomllib.loads(THREE.read_text(encoding="utf-8"))
    config["blocks"][0]["width"], config["blocks"][0]["height"], config["blocks"][0]["mass"] = 0.8, 0.5, 300.0
    config["blocks"][0]["name"] = "pedestal"
    config["blocks"][1].update(width=0.3, height=1.2, mass=100.0)
    del config["blocks"][1]["inertia"]
    config["interfaces"][0]["friction"] = {"static": 0.3, "kinetic": 0.25}
    config["interfaces"][1]["friction"] = {"static": 0.5, "kinetic": 0.4}
    config["motion"] = {"kind": "record", "path": "Northridge1994_RinaldiReceivingSta_228", "scale": 0.4}
    config["simulation"] = {"stop_at_edge": True}
    return config


@pytest.fixture(scope="module")
def falling():
    return run_response(THREE)


@pytest.fixture(scope="module")
def standing():
    return run_response(_standing_config())


@pytest.fixture(scope="module")
def at_the_edge():
    return run_response(_edge_config())


def _expected_checks(response) -> dict[str, str]:
    """What every check must say, from the StackResponse's summary (and each interface's μs) alone."""
    s = response.summary()
    fell = [b for b in s["blocks"] if b["overturned"]]
    undetermined = not fell and s["status"] != "completed"
    names = [f"block {k + 1} ({b['name']})" for k, b in enumerate(s["blocks"])]
    out = {}
    for name, b in zip(names, s["blocks"]):
        out[f"{name} stays upright (no overturn)"] = (
            FAIL if b["overturned"] else UNDETERMINED if (fell or undetermined) else PASS)
    past_edge = s["status"] == "slid_past_edge" or any(b["past_edge_time"] is not None for b in s["blocks"])
    out["no block slid to the edge of the one below"] = (
        FAIL if past_edge else UNDETERMINED if undetermined else PASS)
    for f, interface in zip(s["interfaces"], response.stack.interfaces):
        given = interface.friction
        out[f"friction {f['name']} needs while it sticks ≤ its μs"] = (
            NOT_CHECKED if given is None else PASS if f["required_friction"] <= given.mu_s * (1 + 1e-6) else FAIL)
    out["run ends at rest (a verdict, not undetermined)"] = NOT_APPLICABLE if fell else (
        FAIL if undetermined else PASS)
    out["energy balance error |E − E₀ − W + D| / energy scale"] = (
        PASS if s["energy_balance_error"] <= ENERGY_BALANCE_LIMIT else FAIL)
    return out


@pytest.mark.parametrize("case", ["falling", "standing", "at_the_edge"])
def test_checks_say_pass_or_fail_from_the_stack_summary(case, request):
    config, response = request.getfixturevalue(case)
    found = {c.name: c.result for c in build_stack_content(response, config).checks}
    expected = _expected_checks(response)
    assert {k: found.get(k) for k in expected} == expected
    # nothing slides on the floor's face in the example without a clearance: only the checks above
    extra = set(found) - set(expected)
    assert extra <= {"peak sliding of block 1 (plinth) on the floor ≤ the free space around it (clearance)",
                     "peak sliding of block 1 (pedestal) on the floor ≤ the free space around it (clearance)"}


def test_a_falling_stack_fails_and_names_the_block(falling):
    config, response = falling
    statue = response.blocks[1]
    assert statue["overturned"] and not response.blocks[2]["overturned"]
    sentence = stack_verdict(response)
    assert sentence == f"Block 2 (statue) overturns at t = {statue['overturn_time']:.2f} s; the run ends there."
    content = build_stack_content(response, config)
    checks = {c.name: c for c in content.checks}
    assert checks["block 2 (statue) stays upright (no overturn)"].value == (
        f"overturns at t = {statue['overturn_time']:.2f} s")
    assert stack_verdict_class(response, content.checks) == "fails"


def test_a_standing_stack_passes_and_says_which_face_is_unchecked(standing):
    config, response = standing
    s = response.summary()
    assert s["status"] == "completed" and not any(b["overturned"] for b in s["blocks"])
    content = build_stack_content(response, config)
    pedestal = s["blocks"][0]
    assert pedestal["peak_sliding"] == pytest.approx(0.0962, abs=1e-4)
    assert content.verdict == (
        f"No block overturns; no block rocks; block 1 (pedestal) slides the most, {_mm(pedestal['peak_sliding'])} on "
        f"the floor (residual {_mm(pedestal['residual_sliding'])}); everything is at rest at "
        f"t = {s['end_time']:.2f} s.")
    checks = {c.name: c for c in content.checks}
    unchecked = checks["friction pedestal–statue needs while it sticks ≤ its μs"]
    assert (unchecked.value, unchecked.limit) == (f"{s['interfaces'][1]['required_friction']:.3f}",
                                                  "no μs given (assumed never to slip)")
    assert not any(c.result == FAIL for c in content.checks) and content.warnings == []
    assert stack_verdict_class(response, content.checks) == "safe"


def test_a_block_at_the_edge_fails_its_check_with_a_warning(at_the_edge):
    config, response = at_the_edge
    assert response.status == "slid_past_edge"
    content = build_stack_content(response, config)
    edge = {c.name: c for c in content.checks}["no block slid to the edge of the one below"]
    assert edge.result == FAIL and edge.value.startswith("block 3 (vase) reached the edge of block 2 (statue) at t =")
    assert content.verdict.startswith("Undetermined: block 3 (vase) slid to the edge of block 2 (statue) at t = ")
    assert edge.warning in content.warnings
    assert stack_verdict_class(response, content.checks) == "stopped"


def test_a_block_followed_past_the_edge_fails_the_edge_check():
    """The same stack and record without ``stop_at_edge``: the vase, flush with the statue's edge,
    slides past it at 2.98 s and hangs over it; the run goes on to rest. The check of the edge
    fails and names the block, the edge and the time (from the engine's edge event), with a
    warning; the verdict class is not "safe"."""
    from rocking.stack.engine import G_EDGE

    config = _edge_config()
    config["simulation"] = {}
    config, response = run_response(config)
    assert response.status == "completed" and not response.overturned
    first = response.events[response.events[:, 2] == G_EDGE][0]
    assert int(first[1]) == 2
    content = build_stack_content(response, config)
    edge = {c.name: c for c in content.checks}["no block slid to the edge of the one below"]
    assert edge.result == FAIL
    assert edge.value == f"block 3 (vase) went past the edge of block 2 (statue) at t = {first[0]:.2f} s"
    assert edge.warning in content.warnings and "hung over it" in edge.warning
    assert stack_verdict_class(response, content.checks) == "stopped"


def test_tables_have_a_row_per_block_and_per_interface(falling):
    config, response = falling
    s = response.summary()
    content = build_stack_content(response, config)
    results = content.tables_at("results")
    blocks, interfaces = results
    assert [row[0] for row in blocks.rows] == ["block 1 (plinth)", "block 2 (statue)", "block 3 (vase)"]
    assert [row[3] for row in blocks.rows] == [f"{1e3 * b['peak_sliding']:.2f}" for b in s["blocks"]]
    assert [row[1] for row in blocks.rows] == ["no", f"at {s['blocks'][1]['overturn_time']:.3f} s", "no"]
    assert [row[:3] for row in interfaces.rows] == [
        (f["name"], f"{f['required_friction']:.3f}", mu) for f, mu in zip(s["interfaces"], ("0.6", "0.6", "0.4"))]
    inputs = content.tables_at("inputs")
    assert [len(t.rows) for t in inputs] == [3, 3]
    assert inputs[1].rows[2] == ("block 2 (statue) – block 3 (vase)", "μs = 0.4, μk = 0.32", "0.7 (given)")
    assert set(content.inputs) == {"Motion", "Options"}


def test_the_response_figure_draws_every_block(falling):
    config, response = falling
    fig, energy = stack_figures(response, config)
    phi, sliding, floor = fig.axes
    assert len(phi.get_lines()) >= 3 and len(sliding.get_lines()) >= 3  # one curve per block (plus lines at 0)
    labels = [t.get_text() for t in phi.get_legend().get_texts()]
    assert labels[:3] == ["plinth", "statue", "vase"] and "overturn" in labels
    assert floor.get_ylabel() == "floor acceleration (m/s²)"
    assert "balance error" in " ".join(t.get_text() for t in energy.axes[0].get_legend().get_texts())


@pytest.fixture(scope="module")
def cli_report(tmp_path_factory):
    """`rocking report examples/stack_three_blocks.toml`."""
    from rocking.cli import main

    out = tmp_path_factory.mktemp("stack-report") / "report"
    assert main(["report", str(THREE), "--out", str(out)]) == 0
    return out


def test_rocking_report_of_a_stack_writes_a4_pages(cli_report, falling):
    _, response = falling
    pages = _pdf_pages(cli_report / "report.pdf")
    assert len(pages) >= 2
    for number, (box, text) in enumerate(pages, start=1):
        assert box[:2] == (0.0, 0.0) and box[2:] == pytest.approx(A4, abs=0.01)
        assert "stack_three_blocks.toml · SHA-256 " in text and f"page {number} of {len(pages)}" in text
    whole = "\n".join(text for _, text in pages)
    # (the PDF sets "fl" as one glyph: the needles avoid it)
    for needle in ("Checks", "Blocks, from the", "Interfaces, from the", "Figure 1:", "Figure 2:",
                   "Inputs: blocks, from the", "Inputs: interfaces", "Model assumptions"):
        assert needle in whole, needle
    html = (cli_report / "report.html").read_text(encoding="utf-8")
    assert escape(stack_verdict(response)) in html
    assert html.count("data:image/png;base64,") == 2
    assert len(re.findall(r'<td class="result fail">', html)) == 1  # the statue's fall, nothing else


def test_stack_report_pages_are_well_filled_and_tables_whole(falling):
    config, response = falling
    content = build_stack_content(response, config)
    figures = stack_figures(response, config)
    pages = report_pdf.layout(content, figures, stack_verdict_class(response, content.checks))
    fills = [report_pdf.page_fill(p) for p in pages]
    assert min(fills) >= 0.3 and max(fills) <= 1.0 + 1e-9, fills
    placed = [p for page in pages for p in page if isinstance(p.block, report_pdf.Table)]
    made = [b for b in report_pdf.blocks(content, figures) if isinstance(b, report_pdf.Table)]
    assert len(placed) == len(made)  # no table split across pages


def test_a_stack_response_alone_still_gets_its_report(standing, tmp_path):
    _, response = standing
    html = write_report(response, tmp_path, pdf=False).read_text(encoding="utf-8")
    text = unescape(re.sub(r"<[^>]+>", " ", html))
    assert stack_verdict(response) in " ".join(text.split())
    assert "Inputs: blocks, from the floor up" in text and "Motion" not in re.findall(r"<h3>([^<]*)</h3>", html)


def test_clearance_checks_the_block_on_the_floor(standing, tmp_path):
    config, response = standing
    peak = response.blocks[0]["peak_sliding"]
    name = "peak sliding of block 1 (pedestal) on the floor ≤ the free space around it (clearance)"
    tight = {c.name: c for c in build_stack_content(response, config, clearance=0.5 * peak).checks}[name]
    roomy = {c.name: c for c in build_stack_content(response, config, clearance=2 * peak).checks}[name]
    assert (tight.result, roomy.result) == (FAIL, PASS)


def test_an_unbounded_need_is_worded_as_such_not_as_a_coefficient():
    """A slender statue (0.42 × 1.70 m, 226 kg) that never slips, on a plinth that rocks until
    it topples: the statue's base unloads to a lift-off at 0.708 s while it still carries a
    tangential force, so the friction it needs grows without bound, and the solver's last state
    before the lift-off read |T|/N ≈ 5e11. That number is no coefficient anyone can specify:
    the report's check and its interface table say "> 100 (unbounded)" (as the terminal does,
    and the web page's narrow column "unbounded", through rocking.results.wording.need_text);
    the JSON keeps the number."""
    from rocking.results.wording import UNBOUNDED_NEED, need_text

    config = {
        "blocks": [{"name": "plinth", "width": 0.6546373071849749, "height": 0.8969072345851428,
                    "mass": 136.10363781958782},
                   {"name": "statue", "width": 0.42353994220485064, "height": 1.7000999809993305,
                    "mass": 225.65540010084422}],
        "interfaces": [{"friction": {"static": 0.9524417806293648, "kinetic": 0.3}}, {}],
        "motion": {"kind": "harmonic", "amplitude": 9.537306982161581, "frequency": 0.5514720673787925,
                   "cycles": 1, "form": "sin"},
        "simulation": {},
    }
    config, response = run_response(config)
    s = response.summary()
    assert s["blocks"][1]["lifted_off_time"] == pytest.approx(0.708, abs=1e-3)
    assert s["interfaces"][1]["required_friction"] > UNBOUNDED_NEED
    content = build_stack_content(response, config)
    check = {c.name: c for c in content.checks}["friction plinth–statue needs while it sticks ≤ its μs"]
    assert (check.value, check.result) == ("> 100 (unbounded)", NOT_CHECKED)
    table = next(t for t in content.tables if t.heading.startswith("Interfaces"))
    assert table.rows[1][1] == "> 100 (unbounded)"
    assert table.rows[0][1] == f"{s['interfaces'][0]['required_friction']:.3f}"
    assert [need_text(x) for x in (0.41234, UNBOUNDED_NEED, 100.0001, None, math.nan)] == [
        "0.412", "100.000", "> 100 (unbounded)", "—", "—"]
    assert need_text(5e11, short=True) == "unbounded"  # (the web page's interface column, 390 px wide)
    from rocking.web.app import interface_rows

    assert [row["required_friction"] for row in interface_rows(s, [0.9524417806293648, None])] == [
        f"{s['interfaces'][0]['required_friction']:.3f}", "unbounded"]
