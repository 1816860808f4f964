"""HTML and PDF reports: self-contained, with the verdict, the checks, the numbered figures,
only real warnings, and (in the PDF) A4 pages with a footer on each."""

from __future__ import annotations

import base64
import math
import hashlib
import re
import zlib
from html import escape
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402

import rocking as rk  # noqa: E402
from rocking.report import build_content, verdict, write_report  # noqa: E402
from rocking.report import content as report_content  # noqa: E402
from rocking.report import pdf as report_pdf  # noqa: E402
from rocking.report.content import ENERGY_BALANCE_LIMIT, FAIL, NOT_APPLICABLE, NOT_CHECKED, PASS, UNDETERMINED  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PEDESTAL_TOML = ROOT / "examples" / "statue_on_pedestal.toml"
A4 = (595.276, 841.89)  # pt

CONFIG = {
    "statue": {"width": 0.3, "height": 1.2, "mass": 100.0, "friction": {"static": 0.6, "kinetic": 0.5}},
    "pedestal": {"mass": 50.0, "friction": {"static": 0.3, "kinetic": 0.22}, "width": 0.6, "height": 0.4},
    "motion": {"kind": "harmonic", "amplitude": 4.0, "frequency": 1.5, "cycles": 3},
}


def _friction(static, kinetic):
    return rk.Friction(static=static, kinetic=kinetic)


def _pedestal_system():
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0, friction=_friction(0.6, 0.5))
    return rk.System(statue=statue, pedestal=rk.Pedestal(mass=50.0, friction=_friction(0.3, 0.22), width=0.6, height=0.4))


@pytest.fixture(scope="module")
def pedestal_response():
    return rk.simulate(_pedestal_system(), rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=3))


@pytest.fixture(scope="module")
def overturn_response():
    statue = rk.Statue(width=1.0, height=5.0, mass=1.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=12)
    return rk.simulate(rk.System(statue=statue), motion, options=rk.Options(gravity=9.81))


def _check_self_contained(html: str) -> None:
    assert "://" not in html  # no http(s)/ftp/file URL anywhere (base64 never contains ':')
    for attr in re.findall(r'(?:href|src)\s*=\s*"([^"]*)"', html):
        assert attr.startswith("data:image/png;base64,")
    assert "<link" not in html and "<script" not in html and "@import" not in html


def _images(html: str) -> list[bytes]:
    return [base64.b64decode(m) for m in re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', html)]


def test_report_from_a_response(pedestal_response, tmp_path):
    path = write_report(pedestal_response, tmp_path / "out", title="Pedestal test")
    assert path == tmp_path / "out" / "report.html" and path.exists()
    html = path.read_text(encoding="utf-8")
    sentence = verdict(pedestal_response)
    assert re.fullmatch(
        r"The statue does not overturn; it rocks up to \d+\.\d\d α and the pedestal slides at most "
        r"[\d.]+ mm \(residual [\d.]+ mm\); everything is at rest at t = \d+\.\d\d s\.",
        sentence,
    )
    # The run went on after the motion (2 s) until everything was at rest.
    assert pedestal_response.end_time > pedestal_response.motion.duration
    assert f"at rest at t = {pedestal_response.end_time:.2f} s" in sentence
    assert escape(sentence) in html
    assert "Pedestal test" in html
    _check_self_contained(html)
    images = _images(html)
    assert len(images) == 2 and all(img.startswith(b"\x89PNG\r\n\x1a\n") for img in images)
    for needle in ("Checks", "Key figures", "Inputs", "Model assumptions", "Warnings", "Symbols",
                   "Coulomb friction", "Housner", "normal force", "friction the statue&#x27;s base needs"):
        assert needle in html
    pdf = tmp_path / "out" / "report.pdf"
    assert pdf.exists() and pdf.read_bytes().startswith(b"%PDF")


def test_report_of_an_overturn(overturn_response, tmp_path):
    r = overturn_response
    sentence = verdict(r)
    assert sentence == f"The statue overturns at t = {r.overturn_time:.2f} s."
    html = write_report(r, tmp_path).read_text(encoding="utf-8")
    assert sentence in html
    _check_self_contained(html)
    # alone on a floor it cannot slide on: the friction it needs is in the checks, unchecked
    need = r.summary()["required_top_friction"]
    assert re.search(r"<td>friction the statue&#x27;s base needs on the floor, \|Fx\|/Fy</td>"
                     rf"<td>{need:.3f}</td><td>none given \(assumed never to slide\)</td>"
                     r'<td class="result not-checked">not checked</td>', html)


def test_a_run_cut_short_while_rocking_is_undetermined_unless_it_cannot_fall_any_more(pedestal_response, tmp_path):
    """With an explicit duration that ends while the statue still rocks under the floor motion, the
    report must not say that the statue does not overturn (issue 10: a run is not over when the
    floor stops). Cut after the floor has stopped, halfway to its rest, the statue still rocks but
    with less energy than it needs to reach α: it cannot fall any more, and the report says so,
    with that reason (``settled_by_energy``)."""
    motion = rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=3)
    during = 0.95 * motion.duration
    r = rk.simulate(_pedestal_system(), motion, duration=during)
    assert r.status == "still_moving" and r.still_moving and not r.settled_by_energy
    s = r.summary()
    assert s["still_moving"] is True and s["verdict"] == f"undetermined: still moving at t = {during:.3f} s"
    sentence = verdict(r)
    assert sentence.startswith(f"Undetermined: the statue is still moving at t = {during:.2f} s")
    html = write_report(r, tmp_path / "during", pdf=False).read_text(encoding="utf-8")
    assert "does not overturn" not in html and escape(sentence) in html
    after = 0.5 * (pedestal_response.motion.duration + pedestal_response.end_time)
    r = rk.simulate(_pedestal_system(), motion, duration=after)
    assert r.status == "still_moving" and r.settled_by_energy and r.summary()["settled_by_energy"] is True
    sentence = verdict(r)
    assert sentence.startswith(f"The statue does not overturn: it is still moving at t = {after:.2f} s, when the "
                               "run ended, but with less energy than the statue needs to overturn")
    html = write_report(r, tmp_path / "after", pdf=False).read_text(encoding="utf-8")
    assert escape(sentence) in html and "Undetermined" not in html


def test_report_from_a_config_dict(tmp_path):
    path = write_report(CONFIG, tmp_path, pdf=False)
    html = path.read_text(encoding="utf-8")
    assert "The statue does not overturn" in html or "The statue overturns" in html
    assert not (tmp_path / "report.pdf").exists()
    _check_self_contained(html)


def test_report_from_config_and_response(tmp_path):
    from rocking.runner import run_response

    cfg, r = run_response(CONFIG)
    html = write_report((cfg, r), tmp_path, inputs=CONFIG).read_text(encoding="utf-8")
    assert escape(verdict(r)) in html
    assert "motion.amplitude" in html  # the extra inputs table


def test_verdict_at_rest():
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0)
    system = rk.System(statue=statue, pedestal=rk.Pedestal(mass=50.0, friction=_friction(0.3, 0.22)))
    motion = rk.Harmonic(amplitude=0.5, frequency=1.5, cycles=2)
    r = rk.simulate(system, motion)
    # Nothing moves: the run ends with the motion.
    assert verdict(r) == ("The statue does not overturn; it does not rock and the pedestal does not slide; "
                          f"everything is at rest at t = {motion.duration:.2f} s.")
    alone = rk.simulate(rk.System(statue=statue), motion)
    assert verdict(alone) == ("The statue does not overturn; it neither rocks nor slides; everything is at rest "
                              f"at t = {motion.duration:.2f} s.")


def test_content_is_deterministic(pedestal_response):
    a = build_content(pedestal_response)
    b = build_content(pedestal_response)
    assert a == b
    assert set(a.inputs) == {"Statue", "Pedestal", "Motion", "Options"}


def test_report_rejects_other_inputs(tmp_path):
    with pytest.raises(TypeError, match="Response"):
        write_report(42, tmp_path)


# ------------------------------------------------------------------------- reading the PDF back
def _literal_strings(stream: bytes) -> str:
    """The text of a content stream's string operands, joined per text object (BT … ET)."""
    escapes = {b"n": b"\n", b"r": b"\r", b"t": b"\t", b"b": b"\b", b"f": b"\f"}

    def unescape(raw: bytes) -> bytes:
        def one(m):
            c = m.group(1)
            if c[:1].isdigit():
                return bytes([int(c, 8)])
            return escapes.get(c, c)

        return re.sub(rb"\\([0-7]{1,3}|.)", one, raw, flags=re.S)

    texts = []
    for block in re.findall(rb"BT(.*?)ET", stream, re.S):
        parts = re.findall(rb"\(((?:\\.|[^\\)])*)\)", block, re.S)
        texts.append(b"".join(unescape(p) for p in parts).decode("cp1252", "replace"))
    return "\n".join(texts)


def _pdf_pages(path: Path) -> list[tuple[tuple[float, ...], str]]:
    """(MediaBox, text) of each page in order, read with the standard library only: the page
    tree's kids, each page's inflated content stream and the strings of its text objects."""
    data = path.read_bytes()
    objects = {int(m.group(1)): m.group(2) for m in re.finditer(rb"(\d+) 0 obj(.*?)endobj", data, re.S)}
    kids = next(re.search(rb"/Kids\s*\[([^\]]*)\]", body).group(1) for body in objects.values()
                if re.search(rb"/Type\s*/Pages\b", body))
    pages = []
    for ref in re.findall(rb"(\d+) 0 R", kids):
        page = objects[int(ref)]
        box = tuple(float(v) for v in re.search(rb"/MediaBox\s*\[([^\]]*)\]", page).group(1).split())
        content = objects[int(re.search(rb"/Contents\s+(\d+) 0 R", page).group(1))]
        raw = re.search(rb"stream\r?\n(.*)\r?\nendstream", content, re.S).group(1)
        pages.append((box, _literal_strings(zlib.decompress(raw) if b"/FlateDecode" in content else raw)))
    return pages


@pytest.fixture(scope="module")
def example_report(tmp_path_factory):
    """The report of examples/statue_on_pedestal.toml, as `rocking report` writes it."""
    out = tmp_path_factory.mktemp("example")
    html = write_report(str(PEDESTAL_TOML), out)
    return out / "report.pdf", html.read_text(encoding="utf-8")


def test_every_pdf_page_is_a4_with_the_footer(example_report):
    pdf, _ = example_report
    pages = _pdf_pages(pdf)
    assert len(pages) >= 2
    digest = hashlib.sha256(PEDESTAL_TOML.read_bytes()).hexdigest()[:12]
    for number, (box, text) in enumerate(pages, start=1):
        assert box[:2] == (0.0, 0.0) and box[2:] == pytest.approx(A4, abs=0.01)
        assert f"rocking {rk.__version__} · " in text
        assert f"statue_on_pedestal.toml · SHA-256 {digest}" in text
        assert f"page {number} of {len(pages)}" in text


def test_the_footer_date_follows_source_date_epoch(monkeypatch, pedestal_response):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")  # 2023-11-14 22:13 UTC
    prov = build_content(pedestal_response).provenance
    assert prov.date == "2023-11-14"
    assert prov.footer == f"rocking {rk.__version__} · 2023-11-14 · a Response (no input file) · no input file"


def test_a_config_dict_is_hashed_as_canonical_json(tmp_path):
    from rocking.runner import run_response

    cfg, r = run_response(CONFIG)
    prov = build_content(r, cfg).provenance
    assert prov.input_name == "configuration dict" and re.fullmatch(r"[0-9a-f]{12}", prov.input_hash)
    other = dict(CONFIG, statue=dict(CONFIG["statue"], mass=101.0))
    cfg2, r2 = run_response(other)
    assert build_content(r2, cfg2).provenance.input_hash != prov.input_hash


def test_figures_are_numbered_in_order_on_the_pages_that_discuss_them(example_report):
    pdf, html = example_report
    pages = [text for _, text in _pdf_pages(pdf)]
    whole = "\n".join(pages)
    assert whole.index("Figure 1:") < whole.index("Figure 2:") and "Figure 3" not in whole
    for n, verb in ((1, "shows"), (2, "follows")):
        captions = [i for i, text in enumerate(pages) if f"Figure {n}:" in text]
        assert len(captions) == 1
        assert f"Figure {n} {verb}" in pages[captions[0]]  # the paragraph that discusses it
    assert re.findall(r"<figcaption><b>Figure (\d):</b>", html) == ["1", "2"]


def _expected_results(s: dict) -> dict[str, str]:
    """What the checks must say, from the run's summary alone."""
    undetermined = s["verdict"].startswith("undetermined")
    return {
        "statue stays upright (no overturn)": FAIL if s["overturned"] else (UNDETERMINED if undetermined else PASS),
        "run ends at rest (a verdict, not undetermined)": NOT_APPLICABLE if s["overturned"] else (
            FAIL if undetermined else PASS),
        "energy balance error |E − E₀ − W + D| / energy scale":
            PASS if s["energy_balance_error"] <= ENERGY_BALANCE_LIMIT else FAIL,
    }


@pytest.mark.parametrize("case", ["overturn_response", "pedestal_response"])
def test_checks_say_pass_or_fail_from_the_summary(case, request, tmp_path):
    r = request.getfixturevalue(case)
    s = r.summary()
    found = {c.name: c for c in build_content(r).checks}
    for name, result in _expected_results(s).items():
        assert found[name].result == result, name
    upright = found["statue stays upright (no overturn)"]
    if s["overturned"]:
        assert upright.value == f"overturns at t = {s['overturn_time']:.2f} s"
    else:
        assert upright.value.startswith(f"peak |θ| = {s['peak_rotation_over_alpha']:.2f} α")
    html = write_report(r, tmp_path, pdf=False).read_text(encoding="utf-8")
    fails = sum(c.result == FAIL for c in found.values())
    assert html.count('<td class="result fail">') == fails
    assert (fails > 0) == bool(s["overturned"])  # the fall fails, the survivor passes every check


def test_top_friction_check_against_the_top_face(pedestal_response):
    s = pedestal_response.summary()
    need = s["required_top_friction"]
    name = "friction the statue's base needs ≤ μs of the pedestal's top face"
    ok = {c.name: c for c in build_content(pedestal_response).checks}[name]
    assert (ok.value, ok.limit, ok.result) == (f"{need:.3f}", "μs = 0.6", PASS if need <= 0.6 else FAIL)
    # the same run with a slippery top face: the statue would slip
    weak = rk.simulate(
        rk.System(statue=rk.Statue(width=0.3, height=1.2, mass=100.0, friction=_friction(0.15, 0.1)),
                  pedestal=_pedestal_system().pedestal),
        rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=3))
    content = build_content(weak)
    bad = {c.name: c for c in content.checks}[name]
    assert weak.summary()["required_top_friction"] > 0.15 and bad.result == FAIL
    assert bad.warning in content.warnings and "would slip on the pedestal" in bad.warning
    # standing, but a check fails: the verdict is not shown as safe
    assert report_content.verdict_class(weak, content.checks) == "stopped"
    assert report_content.verdict_class(pedestal_response, build_content(pedestal_response).checks) == "safe"


def test_warnings_hold_no_passing_check(pedestal_response):
    content = build_content(pedestal_response)
    passing = [c for c in content.checks if c.result == PASS]
    assert passing  # the run passes checks, and none of them shows up as a warning
    assert content.warnings == list(pedestal_response.warnings)
    for w in content.warnings:
        assert "friction coefficient" not in w and "enough" not in w
    for c in passing:
        assert all(c.name not in w and c.value not in w for w in content.warnings)


def test_clearance_check(pedestal_response, tmp_path):
    peak = pedestal_response.summary()["peak_sliding"]
    name = "peak sliding of the pedestal ≤ the free space around it (clearance)"
    tight = build_content(pedestal_response, clearance=0.5 * peak)
    check = {c.name: c for c in tight.checks}[name]
    assert check.result == FAIL and check.warning in tight.warnings
    roomy = {c.name: c for c in build_content(pedestal_response, clearance=2 * peak).checks}[name]
    assert roomy.result == PASS
    unknown = {c.name: c for c in build_content(pedestal_response).checks}[name]
    assert unknown.limit == "no clearance given"
    with pytest.raises(ValueError, match=r"^clearance: must be a positive length in m, got -0\.1$"):
        write_report(pedestal_response, tmp_path, clearance=-0.1)


def test_cli_report_checks_a_clearance(tmp_path, capsys):
    from rocking.cli import main

    assert main(["report", str(PEDESTAL_TOML), "--out", str(tmp_path / "bad"), "--clearance", "0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == "error: clearance: must be a positive length in m, got 0.0"
    assert not (tmp_path / "bad").exists()
    assert main(["report", str(PEDESTAL_TOML), "--out", str(tmp_path / "r"), "--clearance", "0.001"]) == 0
    html = (tmp_path / "r" / "report.html").read_text(encoding="utf-8")
    assert re.search(r"<td>peak sliding of the pedestal ≤ the free space around it \(clearance\)</td>"
                     r'<td>[\d.]+ mm</td><td>1.0 mm</td><td class="result fail">fail</td>', html)


def _layout(response, config=None, **kw):
    content = build_content(response, config, **kw)
    from rocking.viz.plots import plot_energy, plot_response

    figures = [plot_response(response), plot_energy(response).figure]
    return content, figures, report_pdf.layout(content, figures, report_content.verdict_class(response))


@pytest.mark.parametrize("case", ["overturn_response", "pedestal_response"])
def test_pages_are_well_filled_and_tables_whole(case, request):
    r = request.getfixturevalue(case)
    content, figures, pages = _layout(r)
    fills = [report_pdf.page_fill(p) for p in pages]
    assert min(fills) >= 0.3, fills  # no page left 70 % empty
    assert max(fills) <= 1.0 + 1e-9
    whole = (report_pdf.Table, report_pdf.Columns)
    placed = [p for page in pages for p in page if isinstance(p.block, whole)]
    made = [b for b in report_pdf.blocks(content, figures) if isinstance(b, whole)]
    assert len(placed) == len(made)  # a split table would be placed twice
    assert all(p.height == pytest.approx(p.block.height()) for p in placed)


class _Spacer(report_pdf.Block):
    def __init__(self, height: float):
        super().__init__()
        self._height = height

    def height(self) -> float:
        return self._height

    def draw(self, page, top, height) -> None:
        pass


def test_a_table_splits_only_when_taller_than_a_page():
    rows = [[report_pdf.Cell(f"row {i}"), report_pdf.Cell("value")] for i in range(200)]
    small = report_pdf.Table(rows=rows[:5], header=["name", "value"])
    big = report_pdf.Table(rows=rows, header=["name", "value"])
    # half of the small table would fit under the spacer: it must move to the next page whole
    pages = report_pdf.paginate([_Spacer(report_pdf.FRAME_HEIGHT - 0.5 * small.height()), small, big])
    tables = [(i, p.block) for i, page in enumerate(pages) for p in page if isinstance(p.block, report_pdf.Table)]
    assert tables[0] == (1, small)  # whole, on the second page
    assert sum(len(t.rows) for _, t in tables[1:]) == 200 and len(tables) > 2
    assert all(t.header == ["name", "value"] for _, t in tables)  # the header repeats


def test_the_layout_takes_the_fewest_pages_then_the_fullest(pedestal_response):
    """Of the figure sizes and the two places of the key figures, the layout keeps the one with the
    fewest pages, then with the fullest emptiest page."""
    content, figures, pages = _layout(pedestal_response)
    candidates = [report_pdf.paginate(report_pdf.blocks(content, figures, figure_scale=scale, key_figures_first=first))
                  for first in (False, True) for scale in report_pdf.FIGURE_SCALES]
    fewest = min(len(c) for c in candidates)
    fullest = max(min(map(report_pdf.page_fill, c)) for c in candidates if len(c) == fewest)
    assert len(pages) == fewest
    assert min(map(report_pdf.page_fill, pages)) == pytest.approx(fullest, abs=0.005)


def test_long_paths_wrap_inside_their_cell(tmp_path, pedestal_response):
    path = "/" + "/".join(f"folder_number_{i}_with_a_long_name" for i in range(8)) + "/record.AT2"
    width = 200.0  # a folder name and a half
    lines = report_pdf.wrap(path, width, 8.2)
    assert len(lines) > 3 and "".join(lines) == path
    assert all(report_pdf.text_width(line, 8.2) <= width for line in lines)
    assert all(line.endswith("/") for line in lines[:-1])  # broken after a separator, not mid-name
    assert len(report_pdf.wrap("x" * 300, 100.0, 8.2)) > 2  # no separator at all: still within the width
    content, _, pages = _layout(pedestal_response, inputs={"record": {"path": path}})
    tables = [p.block for page in pages for p in page if isinstance(p.block, report_pdf.Table)]
    tables += [b for page in pages for p in page if isinstance(p.block, report_pdf.Columns)
               for side in (p.block.left, p.block.right) for b in side if isinstance(b, report_pdf.Table)]
    for table in tables:
        for wrapped in table._cells:
            for (cell, cell_lines), w in zip(wrapped, table._column_widths()):
                assert all(report_pdf.text_width(x, table.size, cell.bold) <= w - 6.0 for x in cell_lines)
    assert any("record.AT2" in line for t in tables for row in t._cells for _, ls in row for line in ls)
    html = write_report(pedestal_response, tmp_path, inputs={"record": {"path": path}}, pdf=False)
    assert "overflow-wrap: anywhere" in html.read_text(encoding="utf-8")


def test_every_symbol_of_the_formulas_is_defined(pedestal_response):
    content = build_content(pedestal_response)
    defined = {name.strip() for names, _ in content.symbols for name in names.split(",")}
    formula = next(a for a in content.assumptions if "N = M(g + a_v)" in a)
    for symbol in ("N", "M", "g", "a_v", "m₂", "R", "S", "φ", "θ̈", "θ̇"):
        assert symbol in formula and symbol in defined, symbol
    for symbol in ("α", "p", "r", "μs", "μk", "B", "H", "Fx", "Fy", "W", "D", "E", "t₀"):
        assert symbol in defined, symbol


def _overlaps(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


@pytest.mark.parametrize("case", ["overturn_response", "pedestal_response"])
def test_legends_stay_off_the_data(case, request):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from rocking.viz.plots import plot_energy, plot_response

    r = request.getfixturevalue(case)
    for fig in (plot_response(r), plot_energy(r).figure):
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw_without_rendering()
        legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
        assert legends
        for legend in legends:
            box = legend.get_window_extent(renderer)
            assert not any(_overlaps(box, ax.get_window_extent(renderer)) for ax in fig.axes)


def test_a_pedestal_that_would_tip_fails_its_check_and_the_verdict_is_not_shown_safe():
    """A squat statue on a pedestal 0.3 m wide and 1 m tall (50 kg each) that friction holds,
    under a 3 m/s² sine: nothing slides or rocks ("did not overturn"), but the floor's reaction
    leaves the pedestal's base once |a_g| > g/7 (derivation §3.5: b₁(m₁ + m₂)/(m₁H₁/2 +
    m₂(H₁ + h₂)), the two tipping as one body; 0.2 g until 2026-12-06, when the statue's own
    couple was left out), at asin(g/(7·3))/(4π) s.
    The report's check must fail there, and its verdict must not be coloured safe; on a pedestal
    1 m wide it passes, and a pedestal without a height is not checked."""
    statue = rk.Statue(width=1.0, height=1.2, mass=50.0)
    motion = rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form="sin")
    name = "pedestal stays flat (the floor's reaction within its base)"

    def check(**size):
        pedestal = rk.Pedestal(mass=50.0, friction=_friction(0.8, 0.7), **size)
        r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, options=rk.Options(gravity=9.81))
        found = {c.name: c for c in build_content(r).checks}
        return r, found[name]

    narrow, c = check(width=0.3, height=1.0)
    t = math.asin(9.81 / 7.0 / 3.0) / (4 * math.pi)
    assert narrow.summary()["verdict"].startswith("did not overturn")
    assert (c.result, c.value, c.limit) == (FAIL, f"leaves its base at t = {t:.2f} s", "|x_N| ≤ 0.15 m, half its width")
    assert narrow.summary()["pedestal_uplift_time"] == pytest.approx(t, abs=1e-12)
    assert report_content.verdict_class(narrow, build_content(narrow).checks) == "stopped"
    wide, c = check(width=1.0, height=1.0)
    assert c.result == PASS and report_content.verdict_class(wide, build_content(wide).checks) == "safe"
    assert check(width=0.3)[1].result == NOT_CHECKED
