"""The web app at the server level (Flask's test client): forms, uploads, runs, limits, sweeps.

The browser tests (tests/test_browser.py) drive the same app in headless Chromium.
"""

from __future__ import annotations

import io
import json
import math
import re
import threading
import time
import zipfile
from html import unescape

import pytest

import flask  # noqa: E402, F401 - a declared dependency: missing, these tests must fail, not skip

import rocking as rk  # noqa: E402
from rocking.io.records import bundled_records  # noqa: E402
from rocking.report import verdict  # noqa: E402
from rocking.runner import run_response  # noqa: E402
from rocking.web.app import create_app  # noqa: E402

RECORD = "Northridge1994_RinaldiReceivingSta_228"

#: The inputs of examples/statue_alone_record.toml as the form sends them.
FORM = {
    "record": RECORD,
    "scale_kind": "factor",
    "scale_value": "0.4",
    "statue_width": "0.3",
    "statue_height": "1.2",
    "statue_mass": "100",
    "statue_restitution": "0.85",
    "statue_mu_s": "0.5",
    "statue_mu_k": "0.4",
}
CONFIG = {
    "statue": {"width": 0.3, "height": 1.2, "mass": 100.0, "restitution": 0.85,
               "friction": {"static": 0.5, "kinetic": 0.4}},
    "motion": {"kind": "record", "path": RECORD, "scale": 0.4},
}
PEDESTAL = {"pedestal": "on", "pedestal_mass": "50", "pedestal_mu_s": "0.3", "pedestal_mu_k": "0.22"}

FAST = {"ANIMATION": {"fps": 4, "longest_video": 4.0, "dpi": 40}, "FIGURE_DPI": 40}


def short_record(units_header: bool = True, seconds: float = 3.0) -> bytes:
    """A two-column record: one sine cycle of 0.5 g at 1 Hz, then rest, sampled at 100 Hz."""
    import math

    lines = ["synthetic test record", "Time[s] Accel[g]" if units_header else "time accel"]
    n = int(seconds * 100) + 1
    for i in range(n):
        t = i / 100
        a = 0.5 * math.sin(2 * math.pi * t) if t <= 1.0 else 0.0
        lines.append(f"{t:.2f} {a:.6f}")
    return ("\n".join(lines) + "\n").encode()


def malformed_peer() -> bytes:
    """A PEER AT2 file whose second data line (line 6) holds a word that is not a number."""
    return (
        "PEER NGA STRONG MOTION DATABASE RECORD\n"
        "TEST, 01/01/2000, Nowhere, 000\n"
        "ACCELERATION TIME HISTORY IN UNITS OF G\n"
        "NPTS=   10, DT=   .0100 SEC,\n"
        "  .1  .2  .3  .4  .5\n"
        "  .1  <b>oops</b>  .3  .4  .5\n"
    ).encode()


@pytest.fixture(scope="module")
def app(tmp_path_factory):
    app = create_app({**FAST, "RUN_TIMEOUT": 120, "MAX_UPLOAD": 64 * 1024,
                      "WORK_DIR": str(tmp_path_factory.mktemp("web"))})
    yield app
    app.extensions["rocking"].shutdown()


@pytest.fixture()
def client(app):
    return app.test_client()


def text_of(html: str, element_id: str) -> str:
    m = re.search(rf'<(\w+)[^>]*\bid="{element_id}"[^>]*>(.*?)</\1>', html, re.S)
    assert m, f"no element #{element_id} in the page"
    return " ".join(unescape(re.sub(r"<[^>]+>", "", m.group(2))).split())


def values_of(html: str) -> dict:
    return {k: json.loads(unescape(v)) for k, v in re.findall(r'<td id="(\w+)" data-value="([^"]*)"', html)}


def upload(data: bytes, name: str, **fields):
    form = {**FORM, **fields}
    form["upload"] = (io.BytesIO(data), name)
    return form


# -------------------------------------------------------------------------------- the page
def test_index_offers_the_bundled_records(client):
    r = client.get("/")
    assert r.status_code == 200
    html = r.get_data(as_text=True)
    for name in bundled_records():
        assert f'<option value="{name}"' in html
    for field in ("statue_width", "statue_height", "statue_mass", "pedestal_mass", "pedestal_mu_s", "upload",
                  "scale_value", "sweep_points"):
        assert f'name="{field}"' in html
    assert 'id="error"' not in html


def test_health(client):
    assert client.get("/healthz").get_json()["status"] == "ok"


# ------------------------------------------------------------------------------------ runs
def test_bundled_record_run_shows_the_api_verdict_and_summary(client):
    r = client.post("/run", data=FORM)
    html = r.get_data(as_text=True)
    assert r.status_code == 200, text_of(html, "error")
    _, response = run_response(CONFIG)
    expected = response.summary()
    assert text_of(html, "verdict") == verdict(response)
    shown = values_of(html)
    for key in ("overturned", "impacts", "status", "overturn_time", "first_sliding_time"):
        assert shown[key] == expected[key], key
    for key in ("peak_rotation", "peak_rotation_over_alpha", "peak_sliding", "first_rocking_time",
                "required_top_friction", "end_time"):
        assert shown[key] == pytest.approx(expected[key], rel=1e-9, abs=1e-12), key
    assert "0.563" in text_of(html, "peak_rotation_over_alpha")
    # the pictures are served
    for element, kind in (("animation", "image/gif"), ("response-plot", "image/png"), ("energy-plot", "image/png")):
        src = re.search(rf'id="{element}"[^>]*src="([^"]+)"', html).group(1)
        pic = client.get(src)
        assert pic.status_code == 200 and pic.mimetype == kind and len(pic.data) > 1000
    # the form keeps the inputs, and the permalink shows the same verdict
    assert 'name="scale_value" type="text" inputmode="decimal" value="0.4"' in html
    assert 'name="pedestal_mass" type="text" inputmode="decimal" value="50"' in html  # not sent: default
    link = re.search(r'id="permalink" href="([^"]+)"', html).group(1)
    again = client.get(link)
    assert again.status_code == 200 and text_of(again.get_data(as_text=True), "verdict") == verdict(response)


def test_pedestal_and_pga_scaling(client):
    form = {**FORM, **PEDESTAL, "scale_kind": "pga_g", "scale_value": "0.3", "duration": "8"}
    r = client.post("/run", data=form)
    html = r.get_data(as_text=True)
    assert r.status_code == 200, text_of(html, "error")
    assert "= 0.300 g" in html  # PGA after scaling
    assert "pedestal" in text_of(html, "verdict") or "overturns" in text_of(html, "verdict")
    assert values_of(html)["end_time"] == pytest.approx(8.0)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"statue_width": ""}, "statue width B: required"),
        ({"statue_height": "tall"}, "statue height H: enter a number, got 'tall'"),
        ({"statue_width": "-1"}, "statue width B: must be > 0"),
        ({"statue_mu_s": "", "statue_mu_k": "0.3"}, "statue friction μk: give μs too"),
        ({"statue_mu_s": "0.3", "statue_mu_k": "0.5"}, "statue friction μk: must be <= static"),
        ({"scale_value": "nan"}, "scale value: must be a finite number"),
        ({"scale_value": "0"}, "scale factor: must be > 0"),
        ({"record": "NoSuchRecord"}, "record: 'NoSuchRecord' is not a bundled record"),
        ({"pedestal": "on", "pedestal_mass": "50"}, "pedestal floor friction μs: required"),
    ],
)
def test_form_errors_name_the_field(client, change, message):
    r = client.post("/run", data={**FORM, **change})
    html = r.get_data(as_text=True)
    assert r.status_code == 400
    assert message in text_of(html, "error")
    assert "Traceback" not in html and 'id="verdict"' not in html


def test_malformed_upload_shows_the_readers_error(client):
    r = client.post("/run", data=upload(malformed_peer(), "bad.AT2"), content_type="multipart/form-data")
    html = r.get_data(as_text=True)
    assert r.status_code == 400
    error = text_of(html, "error")
    assert "Cannot read the record" in error
    assert "bad.AT2: line 6: cannot parse '<b>oops</b>' as a number" in error
    assert "<b>oops</b>" not in html  # escaped, not markup
    assert "Traceback" not in html and "/upload/" not in html  # no server paths either


def test_upload_without_units_then_with_units(client):
    r = client.post("/run", data=upload(short_record(units_header=False), "pulse.txt"),
                    content_type="multipart/form-data")
    assert r.status_code == 400
    assert "pulse.txt: the file does not state its units" in text_of(r.get_data(as_text=True), "error")
    r = client.post("/run", data=upload(short_record(units_header=False), "pulse.txt", units="g", scale_value="2"),
                    content_type="multipart/form-data")
    html = r.get_data(as_text=True)
    assert r.status_code == 200, text_of(html, "error")
    assert "= 1.000 g" in html  # a 0.5 g pulse scaled by 2


def test_uploaded_record_runs(client):
    form = upload(short_record(), "pulse.dat", scale_value="1")
    r = client.post("/run", data=form, content_type="multipart/form-data")
    html = r.get_data(as_text=True)
    assert r.status_code == 200, text_of(html, "error")
    assert "= 0.500 g" in html and "3.00 s" in html  # PGA and length of the uploaded record
    # The run goes on after the record until everything is at rest (at most free_time_limit more).
    end = values_of(html)["end_time"]
    assert end <= 3.0 + rk.Options().free_time_limit
    assert values_of(html)["overturned"] or end >= 3.0
    assert f"{end:.2f} s" in html  # "simulated until"
    assert text_of(html, "verdict").startswith("The statue ")


def test_empty_upload(client):
    r = client.post("/run", data=upload(b"", "empty.AT2"), content_type="multipart/form-data")
    assert r.status_code == 400
    assert "the uploaded file empty.AT2 is empty" in text_of(r.get_data(as_text=True), "error")


def test_upload_too_large(client):
    big = short_record() * 40  # > 64 kB
    r = client.post("/run", data=upload(big, "big.dat"), content_type="multipart/form-data")
    assert r.status_code == 413
    assert "the upload is larger than the limit of 64 kB" in text_of(r.get_data(as_text=True), "error")


def test_a_run_over_the_time_limit_is_stopped(tmp_path):
    app = create_app({**FAST, "RUN_TIMEOUT": 0.05, "WORK_DIR": str(tmp_path)})
    try:
        r = app.test_client().post("/run", data=FORM)
        html = r.get_data(as_text=True)
        assert r.status_code == 504
        assert "the run took longer than 0.05 s and was stopped" in text_of(html, "error")
        assert "Traceback" not in html
        assert app.extensions["rocking"].runner.active() == 0  # the worker was terminated
    finally:
        app.extensions["rocking"].shutdown()


def test_requests_do_not_block_each_other(app):
    runner = app.extensions["rocking"].runner
    results: dict[str, object] = {}

    def run(key: str) -> None:
        results[key] = app.test_client().post("/run", data=FORM)

    threads = [threading.Thread(target=run, args=(k,)) for k in ("a", "b")]
    for t in threads:
        t.start()
    end = time.monotonic() + 30
    peak = 0
    while time.monotonic() < end and peak < 2 and any(t.is_alive() for t in threads):
        peak = max(peak, runner.active())
        time.sleep(0.005)
    # while both runs compute, other requests are answered at once
    t0 = time.monotonic()
    page = app.test_client().get("/")
    bad = app.test_client().post("/run", data={**FORM, "statue_width": "x"})
    quick = time.monotonic() - t0
    busy = any(t.is_alive() for t in threads)
    for t in threads:
        t.join(60)
    assert peak == 2, "the two runs did not compute at the same time"
    assert page.status_code == 200 and bad.status_code == 400
    assert busy and quick < 2.0
    ids = set()
    for key in ("a", "b"):
        html = results[key].get_data(as_text=True)
        assert results[key].status_code == 200, text_of(html, "error")
        ids.add(re.search(r'id="permalink" href="/runs/(\w+)"', html).group(1))
    assert len(ids) == 2


# ----------------------------------------------------------------------------------- sweep
def test_design_sweep_reports_progress_and_its_report(client):
    form = {**FORM, **PEDESTAL, "duration": "6", "sweep_from": "0.1", "sweep_to": "0.4", "sweep_points": "4"}
    r = client.post("/sweep", data=form)
    assert r.status_code == 303
    page = r.headers["Location"]
    seen = []
    end = time.monotonic() + 120
    while time.monotonic() < end:
        s = client.get(page + "/status").get_json()
        seen.append((s["done"], s["total"]))
        if s["state"] not in ("queued", "running"):
            break
        time.sleep(0.1)
    assert s["state"] == "done", s
    assert s["total"] == 13 and s["done"] == 13  # 4 values × 3 friction levels, then the report
    dones = [d for d, _ in seen]
    assert dones == sorted(dones)
    html = client.get(page).get_data(as_text=True)
    assert "Recommended pedestal floor friction" in text_of(html, "verdict")
    # the record (19.9 s) was cut at the 6 s entered: the page says what the verdicts judge
    assert ("Warning: the record was cut at 6 s, the duration entered (it lasts 19.9 s): these verdicts judge the "
            "first 6 s only, and the rest of the record may yet make the statue fall.") in text_of(html, "sweep-verdict-lines")
    assert html.count("<tr") >= 5  # header + 4 values
    report = client.get(re.search(r'id="download-report" href="([^"]+)"', html).group(1))
    assert report.status_code == 200 and b"Friction design sweep" in report.data
    csv_text = client.get(page + "/files/sweep.csv").get_data(as_text=True)
    lines = csv_text.strip().splitlines()
    assert lines[0].startswith("static_friction,kinetic_friction,overturned")
    assert [float(line.split(",")[0]) for line in lines[1:]] == pytest.approx([0.1, 0.2, 0.3, 0.4])
    back = client.get(page + "/inputs").get_data(as_text=True)  # the form as it was sent
    assert 'name="sweep_points" type="text" inputmode="numeric" value="4"' in back
    assert 'id="pedestal" name="pedestal" type="checkbox" value="on" checked' in back
    zipped = client.get(page + "/files/sweep-report.zip")
    names = zipfile.ZipFile(io.BytesIO(zipped.data)).namelist()
    assert {"report.html", "report.pdf", "sweep.csv", "sweep.png"} <= set(names)


def _finished_sweep(client, form):
    r = client.post("/sweep", data=form)
    assert r.status_code == 303
    page = r.headers["Location"]
    end = time.monotonic() + 120
    while time.monotonic() < end:
        s = client.get(page + "/status").get_json()
        if s["state"] not in ("queued", "running"):
            break
        time.sleep(0.1)
    assert s["state"] == "done", s
    return client.get(page).get_data(as_text=True)


def test_sweep_verdict_says_first_that_no_value_met_every_requirement(client):
    """The page shows the design's own verdict (rocking.analyses.design.choose_design): with a 1 mm
    sliding limit no value both keeps the statue standing within μs·(1 ± 0.2) and slides so
    little. μs = 0.1 is safe (its band stays below tan α = 0.25), so it is recommended with the
    free space it needs; μs = 0.6, above the statue's own 0.5, is warned about."""
    form = {**FORM, **PEDESTAL, "duration": "6", "sweep_from": "0.1", "sweep_to": "0.6", "sweep_points": "3",
            "sweep_sliding_limit": "1"}
    html = _finished_sweep(client, form)
    assert text_of(html, "verdict") == (
        "No candidate met every requirement: none keeps the statue standing under every motion at μs and "
        "μs·(1 ± 0.2) (μk alike) and also meets the limits (peak sliding ≤ 1 mm, required statue–pedestal friction "
        "≤ 0.5).")
    assert 'class="verdict stopped"' in html
    lines = text_of(html, "sweep-verdict-lines")
    assert ("Recommended, because not falling comes first: μs = 0.1 (μk = 0.0733), pedestal mass 50 kg, the safe "
            "candidate that needs the least free space:") in lines
    assert ("Warning: a floor-face μs (μs·(1 + 0.2) within the scatter) at or above the statue–pedestal face's "
            "friction (0.5) inverts the concept: the statue, not the pedestal, would slide first. Candidates "
            "concerned: μs = 0.6.") in lines
    assert text_of(html, "sweep-run-verdict").startswith("The report's run, at μs = 0.1 (μk = 0.07333):")
    row = re.search(r'<tr class="best">(.*?)</tr>', html, re.S).group(1)
    assert "<td>safe</td>" in row and "<td>missed</td>" in row


def test_sweep_task_names_no_value_when_none_is_safe(tmp_path):
    """Only values whose scatter band reaches above tan α = 0.25: none is proven safe, nothing is
    recommended, and the report shows the value within the limits the design names instead."""
    from rocking.web.tasks import sweep_task

    config = {**CONFIG, "pedestal": {"mass": 50.0, "friction": {"static": 0.3, "kinetic": 0.22}},
              "simulation": {"duration": 6.0}}
    result = sweep_task(config=config, frictions=[0.3, 0.45], out_dir=str(tmp_path), sliding_limit=0.2, dpi=40)
    assert not result["recommended"] and not result["meets_limits"]
    assert not any(r["safe"] for r in result["rows"]) and all(r["meets_limits"] for r in result["rows"])
    assert result["design_verdict"].startswith("No candidate met every requirement: with every candidate the statue "
                                               "falls, or is left undetermined, under some motion")
    assert result["design_verdict"].endswith("Nothing is recommended.")
    assert result["design_lines"][0].startswith("Within the limits, ")
    hint = "Every μs swept reaches tan α = 0.25 within the scatter"
    assert any(line.startswith(hint) for line in result["design_lines"])
    assert result["best"]["static_friction"] in (0.3, 0.45)
    csv_lines = (tmp_path / "sweep.csv").read_text().splitlines()
    assert csv_lines[0].endswith(",status,safe,falls,undetermined,clearance,meets_limits,inverted,recommended")
    assert all(line.split(",")[-7] == "false" and line.split(",")[-1] == "false" for line in csv_lines[1:])


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"sweep_sliding_limit": "0"}, "sweep sliding limit: must be > 0 mm, got 0"),
        ({"pedestal": ""}, "the design sweep varies the pedestal's floor friction"),
        ({"sweep_from": "0.5", "sweep_to": "0.2"}, "sweep μs to: must be greater than μs from (0.5), got 0.2"),
        ({"sweep_points": "1000"}, "sweep values: must be between 2 and 41, got 1000"),
        ({"sweep_points": "two"}, "sweep values: enter a whole number, got 'two'"),
        ({"sweep_scatter": "1.5"}, "friction scatter: must be >= 0 and < 1 (relative to μs), got 1.5"),
    ],
)
def test_sweep_form_errors(client, change, message):
    form = {**FORM, **PEDESTAL, "sweep_from": "0.1", "sweep_to": "0.4", "sweep_points": "4", **change}
    r = client.post("/sweep", data=form)
    assert r.status_code == 400
    assert message in text_of(r.get_data(as_text=True), "error")


def test_sweep_status_of_unknown_job(client):
    assert client.get("/sweeps/" + "0" * 32 + "/status").status_code == 404
    assert client.get("/sweeps/nonsense").status_code == 404


# -------------------------------------------------------------------------------- safety
def test_only_known_files_are_served(client):
    assert client.get("/runs/" + "0" * 32 + "/response.png").status_code == 404
    assert client.get("/runs/../../etc/passwd").status_code == 404
    assert client.get("/runs/" + "0" * 32 + "/upload").status_code == 404


def test_cross_site_posts_are_refused(client):
    r = client.post("/run", data=FORM, headers={"Origin": "http://evil.example"})
    assert r.status_code == 403
    assert "cross-site" in text_of(r.get_data(as_text=True), "error")


def test_unexpected_host_is_refused(tmp_path):
    app = create_app({"ALLOWED_HOSTS": ["localhost", "127.0.0.1"], "WORK_DIR": str(tmp_path)})
    try:
        c = app.test_client()
        assert c.get("/", headers={"Host": "127.0.0.1:8000"}).status_code == 200
        assert c.get("/", headers={"Host": "rebind.example:8000"}).status_code == 400
    finally:
        app.extensions["rocking"].shutdown()


# --------------------------------------------------------------------------- serve, CLI
def test_serve_command_registers_with_its_options():
    import typer
    from typer.testing import CliRunner

    from rocking.cli import serve

    cli = typer.Typer()
    serve.register(cli)
    cli.command("other")(lambda: None)  # two commands: typer keeps the sub-command names
    result = CliRunner().invoke(cli, ["serve", "--help"])
    assert result.exit_code == 0
    for option in ("--host", "--port", "127.0.0.1", "8000", "--timeout", "--max-upload-mb"):
        assert option in result.output
    bad = CliRunner().invoke(cli, ["serve", "--timeout", "0"])
    assert bad.exit_code == 2 and "must be positive" in bad.output


def test_server_listens_on_loopback_and_answers(tmp_path):
    import urllib.request

    from rocking.web.server import make_server

    server, app = make_server("127.0.0.1", 0, {"WORK_DIR": str(tmp_path)})
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        assert server.server_address[0] == "127.0.0.1" and server.port > 0
        with urllib.request.urlopen(f"http://127.0.0.1:{server.port}/healthz", timeout=10) as resp:
            assert json.load(resp)["status"] == "ok"
    finally:
        server.shutdown()
        server.server_close()
        app.extensions["rocking"].shutdown()


# ------------------------------------------------------------- what the page says (issue 13 §4)
def test_record_dropdown_names_event_station_year_and_pga(client):
    html = client.get("/").get_data(as_text=True)
    option = re.search(rf'<option value="{RECORD}" data-pga-g="([^"]+)"[^>]*>([^<]+)</option>', html)
    assert option, "the Rinaldi record is not offered"
    assert float(option.group(1)) == pytest.approx(0.8740596, rel=1e-6)  # the file's PGA in g (README: 0.874)
    assert unescape(option.group(2)) == "Northridge-01 1994 · Rinaldi Receiving Sta 228 · PGA 0.87 g"
    # the station's name, not the network's code before it (README: "CDMG 24278, Castaic - Old Ridge Route")
    assert "Northridge 1994 · Castaic - Old Ridge Route 090 · PGA 0.57 g" in unescape(html)
    assert 'id="pga-preview"' in html


def test_a_bundled_record_is_named_by_event_in_the_motion_table(client):
    html = client.post("/run", data={**FORM, "duration": "3"}).get_data(as_text=True)
    assert "Northridge-01 1994 · Rinaldi Receiving Sta 228" in text_of(html, "motion")
    assert RECORD not in text_of(html, "motion")


def test_binary_upload_is_not_a_text_record_file(client):
    data = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + bytes(range(256)) * 8
    r = client.post("/run", data=upload(data, "photo.png"), content_type="multipart/form-data")
    assert r.status_code == 400
    assert "photo.png: not a text record file" in text_of(r.get_data(as_text=True), "error")


def test_looks_binary(tmp_path):
    from rocking.web.app import looks_binary

    text = tmp_path / "a.txt"
    text.write_bytes(short_record())
    latin = tmp_path / "b.txt"
    latin.write_bytes("Station Montréal\n0.0 0.1\n".encode("latin-1"))  # not UTF-8, still text
    zipped = tmp_path / "c.zip"
    zipped.write_bytes(b"PK\x03\x04" + b"\x14\x00" * 40)
    assert not looks_binary(text) and not looks_binary(latin) and looks_binary(zipped)


def test_missing_units_point_to_the_units_selector(client):
    r = client.post("/run", data=upload(short_record(units_header=False), "pulse.txt"),
                    content_type="multipart/form-data")
    error = text_of(r.get_data(as_text=True), "error")
    assert "choose them in the form's “units of the file” selector" in error
    assert "units=" not in error and "pass" not in error  # no Python keyword syntax


def test_residual_sliding_after_an_overturn_is_at_the_fall(client):
    r = client.post("/run", data={**FORM, "scale_value": "1.0"})  # the statue alone falls at 3.20 s
    html = r.get_data(as_text=True)
    assert r.status_code == 200, text_of(html, "error")
    assert values_of(html)["overturned"] is True
    row = re.search(r'<td class="name">([^<]*)</td><td id="residual_sliding"[^>]*>([^<]*)</td>', html)
    assert row.group(1) == "sliding at the fall"
    assert "(at the fall, 3.203 s)" in unescape(row.group(2))


def test_plots_have_a_phone_version_and_the_energy_zero_is_explained(client):
    html = client.post("/run", data={**FORM, "duration": "3"}).get_data(as_text=True)
    for name in ("response-narrow.png", "energy-narrow.png"):
        src = re.search(rf'<source media="\(max-width: 640px\)" srcset="([^"]*{name})">', html).group(1)
        pic = client.get(src)
        assert pic.status_code == 200 and pic.mimetype == "image/png"
    assert "Zero is the statue standing upright" in unescape(html)
    assert "below zero only when the statue leans more than 2α" in unescape(html)


def test_energy_axis_says_what_zero_is(tmp_path, monkeypatch):
    """The energy plots the page shows carry the meaning of zero on their axis."""
    from matplotlib.figure import Figure

    from rocking.web import tasks

    labels = []
    save = Figure.savefig

    def spy(fig, *args, **kw):
        labels.extend(ax.get_ylabel() for ax in fig.axes)
        return save(fig, *args, **kw)

    monkeypatch.setattr(Figure, "savefig", spy)
    tasks.run_task(config={**CONFIG, "simulation": {"duration": 2.0}}, out_dir=str(tmp_path),
                   animation=FAST["ANIMATION"], dpi=40)
    assert labels.count(tasks.ENERGY_AXIS_LABEL) == 2  # energy.png and energy-narrow.png
    assert "0 = upright" in tasks.ENERGY_AXIS_LABEL


# ------------------------------------------------------------------- the animation the page shows
def test_the_page_animation_is_real_time_at_20_fps(tmp_path):
    from PIL import Image

    from rocking.web.app import DEFAULTS
    from rocking.web.tasks import run_task

    result = run_task(config={**CONFIG, "simulation": {"duration": 2.0}}, out_dir=str(tmp_path),
                      animation=DEFAULTS["ANIMATION"], dpi=40)
    assert result["animation_speed"] == 1.0
    with Image.open(tmp_path / "animation.gif") as im:
        assert im.info["duration"] == 50  # ms per frame: 20 fps
        assert im.n_frames == 40  # 2 s of motion in 2 s of animation


def test_a_fallen_statue_rests_on_its_pedestal_or_the_floor():
    from rocking.viz.animation import resting_outline

    b, h = 0.15, 0.6  # a 0.3 × 1.2 m statue
    # on a 0.6 × 0.4 m pedestal centred at x = 1: its centre of mass is beyond the edge, so it
    # tips over the edge (x = 1.3, y = 0.4) until its far end touches the floor
    pts = resting_outline(1.0, 0.4, 0.6, b, h, +1.0)
    assert pts[:, 1].min() == pytest.approx(0.0, abs=1e-12)  # touches the floor, no lower
    bottom = pts[1] - pts[2]  # the face it lies on, from the far end to the pivot side
    cross = (1.3 - pts[2, 0]) * bottom[1] - (0.4 - pts[2, 1]) * bottom[0]
    assert cross == pytest.approx(0.0, abs=1e-12)  # that face leans on the pedestal's edge
    assert pts[:, 0].min() > 1.0  # fell towards +x
    # on a pedestal wider than the statue is tall: lies flat on its top
    flat = resting_outline(0.0, 0.4, 3.0, b, h, -1.0)
    assert flat[:, 1].min() == pytest.approx(0.4) and flat[:, 0].min() >= -1.5 - 1e-12
    # without a pedestal: flat on the floor
    assert resting_outline(0.0, 0.0, 0.0, b, h, 1.0)[:, 1].min() == pytest.approx(0.0, abs=1e-12)


def test_the_floor_ruler_is_labelled_in_metres_and_moves_with_the_floor():
    from matplotlib.figure import Figure

    from rocking.viz.animation import floor_ruler

    fig = Figure()
    ax = fig.add_subplot()
    ax.set_xlim(-1.5, 1.5)
    move = floor_ruler(ax, -1.5, 1.5, 0.1)
    shown = {t.get_text(): t.get_position()[0] for t in ax.texts if t.get_visible()}
    assert {"-1", "0", "1", "m"} <= set(shown) and shown["0"] == 0.0
    move(0.25)
    assert {t.get_text(): t.get_position()[0] for t in ax.texts}["0"] == 0.25


def test_sweep_report_has_the_chart_and_table_and_no_server_details(tmp_path):
    """The downloadable report: the sweep's chart and a row per μs, and nothing of the server (the
    uploaded file's temporary path) or of the code (class names, configuration keys)."""
    import shutil

    from rocking.web.tasks import sweep_task

    upload_dir = tmp_path / "work" / "upload"
    upload_dir.mkdir(parents=True)
    shutil.copy(bundled_records()[RECORD], upload_dir / "my_record.AT2")
    config = {**CONFIG, "motion": {"kind": "record", "path": str(upload_dir / "my_record.AT2"), "scale": 0.4},
              "pedestal": {"mass": 50.0, "friction": {"static": 0.3, "kinetic": 0.22}},
              "simulation": {"duration": 4.0}}
    sweep_task(config=config, frictions=[0.1, 0.4], out_dir=str(tmp_path / "out"), dpi=40)
    page = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert page.count("data:image/png;base64,") == 3  # response, energy and the sweep chart
    text = " ".join(unescape(re.sub(r"<[^>]+>", " ", re.sub(r"data:image/png;base64,[^\"']+", "", page))).split())
    assert "Figure 3 : Peak rotation of the statue" in text.replace("Figure 3:", "Figure 3 :")
    assert "μs = 0.1" in text and "μs = 0.4" in text and "Every value of μs swept" in text
    for leak in (str(tmp_path), "/upload/", "GroundMotion", "simulation.duration", "friction design sweep.",
                 "static_friction"):
        assert leak not in text, leak
    assert "my_record" in text  # the record is still named
    assert (tmp_path / "out" / "report.pdf").stat().st_size > 10_000


# ------------------------------------------------------------------- a stack of blocks (issue 11 §5)
#: examples/stack_three_blocks.toml under the Rinaldi record at full scale, as the form sends it.
STACK_FORM = {
    "mode": "stack", "stack_blocks": "3", "record": RECORD, "scale_kind": "factor", "scale_value": "1", "duration": "8",
    "block1_name": "plinth", "block1_width": "1.0", "block1_height": "0.6", "block1_mass": "800",
    "block1_mu_s": "0.6", "block1_mu_k": "0.5",
    "block2_name": "statue", "block2_width": "0.4", "block2_height": "1.4", "block2_mass": "250", "block2_mu_s": "0.6",
    "block3_name": "vase", "block3_width": "0.2", "block3_height": "0.45", "block3_mass": "8", "block3_offset": "0.05",
    "block3_mu_s": "0.4", "block3_mu_k": "0.32", "block3_restitution": "0.7",
}


def _same_stack_by_the_api():
    from rocking.stack import Block, Interface, Stack, simulate_stack

    stack = Stack(
        blocks=(Block(name="plinth", width=1.0, height=0.6, mass=800.0),
                Block(name="statue", width=0.4, height=1.4, mass=250.0),
                Block(name="vase", width=0.2, height=0.45, mass=8.0, offset=0.05)),
        interfaces=(Interface(friction=rk.Friction(static=0.6, kinetic=0.5)),
                    Interface(friction=rk.Friction(static=0.6)),
                    Interface(friction=rk.Friction(static=0.4, kinetic=0.32), restitution=0.7)))
    from rocking.io.records import read_record

    return simulate_stack(stack, read_record(RECORD).scaled(1.0), duration=8.0)


def _rows(html: str, table_id: str) -> list[tuple[list[str], dict]]:
    """(cell texts, data-values) of each body row of a table of the page."""
    table = re.search(rf'<table id="{table_id}"[^>]*>(.*?)</table>', html, re.S).group(1)
    out = []
    for attrs, body in re.findall(r"<tr([^>]*)>(.*?)</tr>", table, re.S):
        values = re.search(r'data-values="([^"]*)"', attrs)
        if values:
            cells = [" ".join(unescape(re.sub(r"<[^>]+>", "", c)).split()) for c in re.findall(r"<td[^>]*>(.*?)</td>",
                                                                                               body, re.S)]
            out.append((cells, json.loads(unescape(values.group(1)))))
    return out


def test_the_page_offers_a_stack_mode_and_keeps_the_statue_as_default(client):
    html = client.get("/").get_data(as_text=True)
    assert re.search(r'id="mode-statue" name="mode" type="radio" value="statue" checked', html)
    assert 'id="mode-stack" name="mode" type="radio" value="stack">' in html
    assert re.search(r'<fieldset id="stack-fields" hidden>', html) and '<fieldset id="statue-fields">' in html
    for k in range(1, 7):  # up to MAX_BLOCKS = 6 blocks, the first two shown
        assert f'name="block{k}_width"' in html and f'name="block{k}_restitution"' in html
    assert '<fieldset class="block" id="block2">' in html and '<fieldset class="block" id="block3" hidden>' in html
    assert 'name="block7_width"' not in html


def test_a_stack_run_shows_the_verdict_of_simulate_stack_and_a_row_per_block(client):
    r = client.post("/run", data=STACK_FORM)
    html = r.get_data(as_text=True)
    assert r.status_code == 200, text_of(html, "error")
    expected = _same_stack_by_the_api()
    fell = expected.blocks[1]["overturn_time"]
    assert text_of(html, "verdict") == expected.verdict == f"statue overturned at t = {fell:.3f} s"
    assert 'class="verdict stack fails"' in html
    blocks = _rows(html, "blocks")
    assert [cells[0] for cells, _ in blocks] == ["plinth", "statue", "vase"]
    for (cells, shown), b in zip(blocks, expected.blocks):
        assert shown["overturned"] is b["overturned"]
        for key in ("peak_rotation", "peak_sliding", "residual_sliding"):
            assert shown[key] == pytest.approx(b[key], rel=1e-9, abs=1e-12), key
        assert cells[2] == f"{round(math.degrees(b['peak_rotation']), 2) + 0.0:.2f}"
    interfaces = _rows(html, "interfaces")
    assert [cells[0] for cells, _ in interfaces] == ["floor–plinth", "plinth–statue", "statue–vase"]
    assert [cells[2] for cells, _ in interfaces] == ["0.6", "0.6", "0.4"]
    for (_, shown), f in zip(interfaces, expected.interfaces):
        assert shown["required_friction"] == pytest.approx(f["required_friction"], rel=1e-9)
        assert shown["impacts"] == f["impacts"]
    assert values_of(html)["impacts"] == expected.summary()["impacts"]
    for element, kind in (("animation", "image/gif"), ("response-plot", "image/png"), ("energy-plot", "image/png")):
        src = re.search(rf'id="{element}"[^>]*src="([^"]+)"', html).group(1)
        pic = client.get(src)
        assert pic.status_code == 200 and pic.mimetype == kind and len(pic.data) > 1000
    # the form stays in stack mode with the blocks typed, and the permalink shows the same
    assert 'id="mode-stack" name="mode" type="radio" value="stack" checked' in html
    assert 'name="block3_offset" type="text" inputmode="decimal" value="0.05"' in html
    link = re.search(r'id="permalink" href="([^"]+)"', html).group(1)
    again = client.get(link).get_data(as_text=True)
    assert text_of(again, "verdict") == expected.verdict and len(_rows(again, "blocks")) == 3


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"block2_width": "-1"}, "block 2 width: must be > 0, got -1.0"),
        ({"block2_width": "wide"}, "block 2 width: enter a number, got 'wide'"),
        ({"block1_mass": ""}, "block 1 mass: required"),
        ({"block3_mu_s": "0.3", "block3_mu_k": "0.5"}, "block 3 friction μk: must be <= static (0.3), got 0.5"),
        ({"block3_restitution": "1.5"}, "block 3 restitution r: must be <= 1, got 1.5"),
        ({"block2_offset": "2"}, "block 2 offset: leaves no overlap with block 1 (plinth) below"),
        ({"block3_name": "statue"}, "block 3 name: 'statue' is already the name of block 2"),
        ({"stack_blocks": "4"}, "block 4 width: required"),
        ({"stack_blocks": "7"}, "number of blocks: must be a whole number from 1 to 6, got '7'"),
    ],
)
def test_stack_form_errors_name_the_block_and_field(client, change, message):
    r = client.post("/run", data={**STACK_FORM, **change})
    html = r.get_data(as_text=True)
    assert r.status_code == 400
    assert message in text_of(html, "error")
    assert "blocks[" not in text_of(html, "error") and 'id="verdict"' not in html
    assert 'id="mode-stack" name="mode" type="radio" value="stack" checked' in html  # still in stack mode


def test_the_design_sweep_is_for_a_statue_on_its_pedestal(client):
    r = client.post("/sweep", data={**STACK_FORM, "sweep_from": "0.1", "sweep_to": "0.4", "sweep_points": "4"})
    assert r.status_code == 400
    assert "the design sweep varies the floor friction of a statue's pedestal" in text_of(r.get_data(as_text=True),
                                                                                          "error")
