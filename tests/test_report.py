"""HTML and PDF reports: self-contained, with the verdict, the figures and the warnings."""

from __future__ import annotations

import base64
import re
from html import escape

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402

import rocking as rk  # noqa: E402
from rocking.report import build_content, verdict, write_report  # noqa: E402

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
    for needle in ("Key figures", "Inputs", "Model assumptions", "Warnings", "Coulomb friction",
                   "Housner", "normal force", "must supply a friction coefficient of at least"):
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
    # alone on a floor it cannot slide on: the friction it needs is reported
    assert "The floor must supply a friction coefficient of at least" in html


def test_a_run_cut_short_while_rocking_is_undetermined(pedestal_response, tmp_path):
    """With an explicit duration that ends while the statue still rocks, the report must not say
    that the statue does not overturn (issue 10: a run is not over when the floor stops)."""
    cut = 0.5 * (pedestal_response.motion.duration + pedestal_response.end_time)
    r = rk.simulate(_pedestal_system(), rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=3), duration=cut)
    assert r.status == "still_moving" and r.still_moving
    s = r.summary()
    assert s["still_moving"] is True and s["verdict"] == f"undetermined: still moving at t = {cut:.3f} s"
    sentence = verdict(r)
    assert sentence.startswith(f"Undetermined: the statue is still moving at t = {cut:.2f} s")
    html = write_report(r, tmp_path, pdf=False).read_text(encoding="utf-8")
    assert "does not overturn" not in html and escape(sentence) in html


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
