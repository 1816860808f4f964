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
    "simulation": {"duration": 3.0},
}


def _friction(static, kinetic):
    return rk.Friction(static=static, kinetic=kinetic)


@pytest.fixture(scope="module")
def pedestal_response():
    statue = rk.Statue(width=0.3, height=1.2, mass=100.0, friction=_friction(0.6, 0.5))
    system = rk.System(statue=statue, pedestal=rk.Pedestal(mass=50.0, friction=_friction(0.3, 0.22), width=0.6, height=0.4))
    return rk.simulate(system, rk.Harmonic(amplitude=4.0, frequency=1.5, cycles=3), duration=3.0)


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
        r"[\d.]+ mm \(residual [\d.]+ mm\)\.",
        sentence,
    )
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
    r = rk.simulate(system, rk.Harmonic(amplitude=0.5, frequency=1.5, cycles=2))
    assert verdict(r) == "The statue does not overturn; it does not rock and the pedestal does not slide."
    alone = rk.simulate(rk.System(statue=statue), rk.Harmonic(amplitude=0.5, frequency=1.5, cycles=2))
    assert verdict(alone) == "The statue does not overturn; it neither rocks nor slides."


def test_content_is_deterministic(pedestal_response):
    a = build_content(pedestal_response)
    b = build_content(pedestal_response)
    assert a == b
    assert set(a.inputs) == {"Statue", "Pedestal", "Motion", "Options"}


def test_report_rejects_other_inputs(tmp_path):
    with pytest.raises(TypeError, match="Response"):
        write_report(42, tmp_path)
