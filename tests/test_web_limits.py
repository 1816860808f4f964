"""The web app's limits (issue 10, section 3): per-request caps on the simulated duration, the saved
samples and the sweep grid, and a per-client cap on the runs and sweeps in progress, so that one
client cannot take every worker.

The caps are checked with Flask's test client. The per-client cap is checked against a real
server on 127.0.0.1 with concurrent HTTP clients, each client bound to its own loopback address
(127.0.0.2, 127.0.0.3, …: all of 127.0.0.0/8 reaches the server). Their jobs wait on a gate (a
file the test creates), so the test decides when they end; the jobs run in forked workers that
inherit the gated task functions.
"""

from __future__ import annotations

import http.client
import re
import threading
import time
from html import unescape
from pathlib import Path
from urllib.parse import urlencode

import pytest

import flask  # noqa: E402, F401 - a declared dependency: missing, these tests must fail, not skip

from rocking.web import tasks  # noqa: E402
from rocking.web.app import create_app  # noqa: E402
from rocking.web.server import make_server  # noqa: E402

from test_web import FORM, PEDESTAL, RECORD  # noqa: E402  (the statue of examples/statue_alone_record.toml)

FAST = {"ANIMATION": {"fps": 4, "longest_video": 4.0, "dpi": 40}, "FIGURE_DPI": 40}


def error_of(html: str) -> str:
    m = re.search(r'<div id="error"[^>]*>(.*?)</div>', html, re.S)
    assert m, "no error on the page"
    return " ".join(unescape(re.sub(r"<[^>]+>", "", m.group(1))).split())


@pytest.fixture()
def app(tmp_path):
    app = create_app({**FAST, "WORK_DIR": str(tmp_path / "work"), "MAX_DURATION": 100.0, "MAX_SAMPLES": 5000})
    yield app
    app.extensions["rocking"].shutdown()


# --------------------------------------------------------------------------- per request
def test_a_duration_over_the_cap_is_refused_before_any_worker(app):
    r = app.test_client().post("/run", data={**FORM, "duration": "1e6"})
    assert r.status_code == 400
    html = r.get_data(as_text=True)
    assert error_of(html) == "Over this server's limits: duration: at most 100 s on this server, got 1e+06 s"
    assert app.extensions["rocking"].runner.active() == 0
    assert 'value="1e6"' in html  # the form keeps what was typed
    assert not list((Path(app.extensions["rocking"].work_dir) / "runs").iterdir())


def test_a_record_longer_than_the_cap_names_the_record(tmp_path):
    app = create_app({**FAST, "WORK_DIR": str(tmp_path), "MAX_DURATION": 50.0})
    try:
        r = app.test_client().post("/run", data=FORM)  # 19.9 s + 60 s of free motion > 50 s
        assert r.status_code == 400
        msg = error_of(r.get_data(as_text=True))
        assert f"record: {RECORD} lasts 19.9 s" in msg and "limit of 50 s" in msg
        assert "enter a duration of at most 50 s" in msg
    finally:
        app.extensions["rocking"].shutdown()


def test_too_many_samples_are_refused(app):
    r = app.test_client().post("/run", data={**FORM, "duration": "80"})  # 8001 samples at 0.01 s
    assert r.status_code == 400
    msg = error_of(r.get_data(as_text=True))
    assert "the run would save 8e+03 samples" in msg and "limit of 5e+03" in msg


def test_the_sweep_grid_and_duration_are_capped(app):
    client = app.test_client()
    r = client.post("/sweep", data={**FORM, **PEDESTAL, "duration": "20", "sweep_from": "0.1", "sweep_to": "0.5",
                                     "sweep_points": "42"})
    assert r.status_code == 400
    assert "sweep values: must be between 2 and 41, got 42" in error_of(r.get_data(as_text=True))
    r = client.post("/sweep", data={**FORM, **PEDESTAL, "duration": "500", "sweep_points": "4"})
    assert r.status_code == 400
    assert "duration: at most 100 s on this server, got 500 s" in error_of(r.get_data(as_text=True))
    assert not list((Path(app.extensions["rocking"].work_dir) / "sweeps").iterdir())


def test_one_client_can_never_hold_every_worker(tmp_path):
    app = create_app({**FAST, "WORK_DIR": str(tmp_path), "MAX_WORKERS": 2, "MAX_JOBS_PER_CLIENT": 5})
    try:
        assert app.extensions["rocking"].clients.limit == 1
    finally:
        app.extensions["rocking"].shutdown()


# -------------------------------------------------------------- concurrent clients, real server
GATE = {"path": None}
CANNED: dict = {}


def _wait_for_gate() -> None:
    end = time.monotonic() + 60  # bounded: a forgotten gate must not hang the suite
    while GATE["path"] is not None and not Path(GATE["path"]).exists() and time.monotonic() < end:
        time.sleep(0.01)


def gated_run(*, progress, **kwargs):
    """Runs in a forked worker: wait for the gate, then answer with a real run's result."""
    progress(0, 1, "waiting for the test")
    _wait_for_gate()
    return CANNED["result"]


def gated_sweep(*, progress, **kwargs):
    progress(0, 1, "waiting for the test")
    _wait_for_gate()
    raise ValueError("stopped by the test")


def post(port: int, path: str, form: dict, source: str) -> tuple[int, dict, str]:
    """POST ``form`` from the loopback address ``source``; (status, headers, body)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=90, source_address=(source, 0))
    try:
        conn.request("POST", path, body=urlencode(form),
                     headers={"Content-Type": "application/x-www-form-urlencoded"})
        resp = conn.getresponse()
        return resp.status, dict(resp.getheaders()), resp.read().decode()
    finally:
        conn.close()


def get_json(port: int, path: str) -> dict:
    import json

    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    try:
        conn.request("GET", path)
        return json.loads(conn.getresponse().read())
    finally:
        conn.close()


@pytest.fixture()
def server(tmp_path, monkeypatch):
    """A real server on 127.0.0.1 whose runs and sweeps wait on a gate file."""
    CANNED["result"] = tasks.run_task(config={"statue": {"width": 0.3, "height": 1.2, "mass": 100.0},
                                              "motion": {"kind": "record", "path": RECORD, "scale": 0.4},
                                              "simulation": {"duration": 2.0}},
                                      out_dir=str(tmp_path / "canned"), animation=FAST["ANIMATION"], dpi=30)
    GATE["path"] = str(tmp_path / "gate")
    monkeypatch.setattr(tasks, "run_task", gated_run)
    monkeypatch.setattr(tasks, "sweep_task", gated_sweep)
    settings = {**FAST, "WORK_DIR": str(tmp_path / "work"), "MP_CONTEXT": "fork", "MAX_WORKERS": 6,
                "MAX_JOBS_PER_CLIENT": 1, "QUEUE_TIMEOUT": 5.0}
    srv, app = make_server("127.0.0.1", 0, settings)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    try:
        yield srv.port, app, Path(GATE["path"])
    finally:
        Path(GATE["path"]).touch()  # release anything still waiting
        srv.shutdown()
        srv.server_close()
        app.extensions["rocking"].shutdown()
        GATE["path"] = None


def test_one_client_cannot_take_every_worker(server):
    port, app, gate = server
    runner = app.extensions["rocking"].runner

    # client A starts a sweep: it runs in the background and holds A's one slot
    sweep = {**FORM, **PEDESTAL, "duration": "5", "sweep_from": "0.1", "sweep_to": "0.5", "sweep_points": "3"}
    status, headers, body = post(port, "/sweep", sweep, "127.0.0.1")
    assert status == 303, error_of(body)
    sweep_page = headers["Location"]
    status, headers, body = post(port, "/run", FORM, "127.0.0.1")
    assert status == 429
    assert headers["Retry-After"] == "10"
    assert error_of(body) == ("Too many runs at once: 127.0.0.1 already has 1 run or design sweep in progress, "
                              "the most one address may have at once on this server; wait until one has finished, "
                              "then try again")
    assert re.search(r'id="statue_height"[^>]*value="1.2"', body)  # the form keeps what was typed

    # three other clients each start a run at the same time: none is refused, none waits for A
    results: dict[str, tuple] = {}

    def run_from(source: str) -> None:
        results[source] = post(port, "/run", FORM, source)

    others = ["127.0.0.2", "127.0.0.3", "127.0.0.4"]
    threads = [threading.Thread(target=run_from, args=(s,)) for s in others]
    for t in threads:
        t.start()
    end = time.monotonic() + 30
    while runner.active() < 4 and time.monotonic() < end:  # A's sweep + three runs
        time.sleep(0.01)
    assert runner.active() == 4, "the other clients' runs did not all start"
    # each of them is now at its own limit, and A still is
    for source in others[:1] + ["127.0.0.1"]:
        status, _, body = post(port, "/run", FORM, source)
        assert status == 429 and f"{source} already has 1 run" in error_of(body)
    # a mistake in the form is still shown as such, quota or not
    status, _, body = post(port, "/run", {**FORM, "statue_width": "x"}, "127.0.0.2")
    assert status == 400 and "statue width B: enter a number" in error_of(body)
    assert not results, "the runs must wait for the gate"

    gate.touch()
    for t in threads:
        t.join(60)
    for source in others:
        status, _, body = results[source]
        assert status == 200, error_of(body)
        assert 'id="verdict"' in body
    end = time.monotonic() + 30
    while time.monotonic() < end:
        if get_json(port, sweep_page + "/status")["state"] not in ("queued", "running"):
            break
        time.sleep(0.05)
    assert get_json(port, sweep_page + "/status")["error"] == "stopped by the test"
    # every slot was given back: A may run again
    status, _, body = post(port, "/run", FORM, "127.0.0.1")
    assert status == 200, error_of(body)
    assert app.extensions["rocking"].clients.active("127.0.0.1") == 0


def test_a_flood_from_one_client_gets_one_run(server):
    port, app, gate = server
    outcomes: list[int] = []
    lock = threading.Lock()

    def one() -> None:
        status, _, _ = post(port, "/run", FORM, "127.0.0.5")
        with lock:
            outcomes.append(status)

    threads = [threading.Thread(target=one) for _ in range(6)]
    for t in threads:
        t.start()
    end = time.monotonic() + 30
    while len(outcomes) < 5 and time.monotonic() < end:  # five are refused at once
        time.sleep(0.01)
    assert sorted(outcomes) == [429] * 5
    # meanwhile another client is served
    gate.touch()
    status, _, _ = post(port, "/run", FORM, "127.0.0.6")
    assert status == 200
    for t in threads:
        t.join(60)
    assert sorted(outcomes) == [200] + [429] * 5
