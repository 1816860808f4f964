"""Input that contradicts itself is refused, and the errors that used to escape as "unexpected"
are one line naming the field or the file, found before anything is simulated or written.

* units given by the user that contradict a record's header (API, config, ``rocking info``, web);
* ``rocking report --out FILE``, ``rocking animate --out X.mp4`` without ffmpeg (and other outputs
  that cannot be written), ``design.mu_s`` in a study file, ``info --format esm`` on an AT2 file.

The commands run in-process through ``rocking.cli.main(argv)``; the simulation entry point is
replaced by one that fails the test, so "before any simulation" is checked, not assumed.
"""

from __future__ import annotations

import importlib
from pathlib import Path

import matplotlib
import pytest

from rocking import runner
from rocking.cli import main
from rocking.io.config import ConfigError, load_config
from rocking.io.records import RecordError, UnitsConflictError, bundled_records, read_record

from test_config import TOML

ROOT = Path(__file__).resolve().parents[1]
ESM = "LAquila2009_AQV_HNE_ESM"  # header: UNITS: cm/s^2 (line 33), PGA 644.2 cm/s²
AT2 = "Northridge1994_RinaldiReceivingSta_228"  # header: ... IN UNITS OF G (line 3)
TWO_COL = "Northridge1994_CastaicOldRidgeRoute_090_2col"  # header: Time[s] Accel[g]
G = 9.80665


def _run_cli(capsys, *args) -> tuple[int, str, str]:
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def _one_error_line(err: str, *fragments: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("error: ") and "unexpected" not in lines[0] and "Traceback" not in err, err
    for frag in fragments:
        assert frag in lines[0], (frag, err)
    return lines[0]


@pytest.fixture
def no_simulation(monkeypatch):
    """Fail the test if a command gets as far as simulating."""

    def refuse(*args, **kwargs):
        raise AssertionError("the command simulated before refusing its input")

    monkeypatch.setattr(runner, "run_response", refuse)
    monkeypatch.setattr(importlib.import_module("rocking.cli.main"), "run_response", refuse)


@pytest.fixture
def short_toml(tmp_path) -> Path:
    f = tmp_path / "short.toml"
    f.write_text(TOML, encoding="utf-8")
    return f


# ============================================================ 5. units against the header
@pytest.mark.parametrize(
    ("name", "given", "header", "line"),
    [(ESM, "g", "cm/s^2", 33), (AT2, "cm/s2", "G", 3), (AT2, "m/s^2", "G", 3), (TWO_COL, "gal", "g", 5)],
)
def test_units_that_contradict_the_header_are_refused(name, given, header, line):
    with pytest.raises(UnitsConflictError) as info:
        read_record(name, units=given)
    exc = info.value
    assert isinstance(exc, RecordError) and isinstance(exc, ValueError)
    text = str(exc)
    assert len(text.splitlines()) == 1
    assert text.startswith(f"{bundled_records()[name]}: line {line}: ")
    assert f"the header states the units {header!r}, but units={given!r}" in text
    assert "units_override=True" in text
    assert (exc.header_units, exc.given_units) == (header, given)


@pytest.mark.parametrize(("name", "same"), [(ESM, "cm/s2"), (ESM, "gal"), (ESM, "CM/S²"), (AT2, "g"), (AT2, "G")])
def test_units_that_agree_with_the_header_in_any_spelling_are_accepted(name, same):
    assert read_record(name, units=same).pga == read_record(name).pga


def test_units_override_reads_the_file_in_the_given_units():
    header = read_record(ESM)
    forced = read_record(ESM, units="g", units_override=True)
    assert header.pga == pytest.approx(644.246826 * 0.01)  # m/s²: the header's cm/s²
    assert forced.pga == pytest.approx(644.246826 * G)  # the "PGA of 644 g" the override asks for
    assert forced.units == "g" and forced.meta["units_override"] is True
    assert forced.meta["header_units"] == "cm/s^2"
    assert header.meta["units_override"] is False


def test_units_override_without_units_is_an_argument_error():
    with pytest.raises(ValueError, match="units_override=True needs units"):
        read_record(ESM, units_override=True)


def test_a_header_without_units_still_takes_the_given_units(tmp_path):
    f = tmp_path / "plain.txt"
    f.write_text("time accel\n0 0.1\n0.01 0.2\n0.02 0\n")
    assert read_record(f, units="g").pga == pytest.approx(0.2 * G)
    with pytest.raises(RecordError, match="does not state its units"):
        read_record(f)


def _record_config(**motion) -> dict:
    return {"statue": {"width": 0.3, "height": 1.2, "mass": 100.0},
            "motion": {"kind": "record", "path": ESM, **motion}}


def test_config_units_that_contradict_the_header(tmp_path):
    f = tmp_path / "esm.toml"
    f.write_text(f'[statue]\nwidth = 0.3\nheight = 1.2\nmass = 100.0\n[motion]\nkind = "record"\n'
                 f'path = "{ESM}"\nunits = "g"\n', encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        load_config(f)
    text = str(info.value)
    assert len(text.splitlines()) == 1 and info.value.field == "motion.units"
    assert text.startswith(f"{f}: motion.units: {bundled_records()[ESM]}: line 33: ")
    assert "the header states the units 'cm/s^2', but units = 'g'" in text
    assert "units_override = true in [motion]" in text


def test_config_units_override():
    cfg = load_config(_record_config(units="g", units_override=True))
    _, motion, _, _ = cfg.to_specs()
    assert motion.pga == pytest.approx(644.246826 * G)
    with pytest.raises(ConfigError, match="motion: units_override = true needs units"):
        load_config(_record_config(units_override=True))
    with pytest.raises(ConfigError, match="motion.units_override: must be true or false"):
        load_config(_record_config(units="g", units_override="yes"))


def test_config_vertical_units_are_checked_too():
    with pytest.raises(ConfigError) as info:
        load_config(_record_config(vertical_path=ESM, vertical_units="m/s2"))
    assert info.value.field == "motion.vertical_units"
    assert "but vertical_units = 'm/s2'" in str(info.value)
    load_config(_record_config(vertical_path=ESM, vertical_units="m/s2", units_override=True))


def test_info_units_against_the_header(capsys):
    code, out, err = _run_cli(capsys, "info", ESM, "--units", "g")
    assert code == 2 and out == ""
    _one_error_line(err, f"{bundled_records()[ESM]}: line 33", "'cm/s^2'", "--units says 'g'", "--units-override")
    code, out, err = _run_cli(capsys, "info", ESM, "--units", "g", "--units-override", "--json")
    assert code == 0, err
    assert '"units": "g"' in out
    code, out, err = _run_cli(capsys, "info", ESM, "--units-override")
    assert code == 2
    _one_error_line(err, "--units-override needs --units")


# ================================================================ 6. errors before a run
def test_report_out_that_is_a_file(capsys, short_toml, tmp_path, no_simulation):
    taken = tmp_path / "afile"
    taken.write_text("keep me")
    code, out, err = _run_cli(capsys, "report", short_toml, "--out", taken)
    assert code == 2 and out == ""
    _one_error_line(err, f"--out: {taken} exists and is not a directory")
    assert taken.read_text() == "keep me"
    code, out, err = _run_cli(capsys, "report", short_toml, "--out", taken / "report")
    assert code == 2
    _one_error_line(err, f"--out: {taken} is a file")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "short.toml"]  # no temporary folder


def test_run_out_below_a_file(capsys, short_toml, tmp_path, no_simulation):
    taken = tmp_path / "afile"
    taken.write_text("keep me")
    code, out, err = _run_cli(capsys, "run", short_toml, "--out", taken / "sub")
    assert code == 2 and out == ""
    _one_error_line(err, f"--out: {taken} is a file")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "short.toml"]


def test_animate_mp4_without_ffmpeg(capsys, short_toml, tmp_path, monkeypatch, no_simulation):
    # where matplotlib looks for ffmpeg: a path that does not exist stands for "not installed"
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", str(tmp_path / "no-ffmpeg"))
    target = tmp_path / "movie.mp4"
    code, out, err = _run_cli(capsys, "animate", short_toml, "--out", target)
    assert code == 2 and out == ""
    line = _one_error_line(err, "--out: cannot write movie.mp4", "ffmpeg", ".gif")
    assert ".tmp" not in line  # the user's file name, not a temporary one
    assert sorted(p.name for p in tmp_path.iterdir()) == ["short.toml"]


@pytest.mark.parametrize(
    ("target", "fragment"),
    [("movie.avi", "must end in .gif or .mp4"), ("folder", "is a directory"), ("afile/x.gif", "is a file")],
)
def test_animate_outputs_that_cannot_be_written(capsys, short_toml, tmp_path, no_simulation, target, fragment):
    (tmp_path / "folder").mkdir()
    (tmp_path / "afile").write_text("x")
    code, out, err = _run_cli(capsys, "animate", short_toml, "--out", tmp_path / target)
    assert code == 2 and out == ""
    _one_error_line(err, "--out: ", fragment)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "folder", "short.toml"]


DESIGN = (ROOT / "examples" / "studies" / "design.toml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("line", "field", "words"),
    [
        ("mu_s = [-0.1, 0.2]", "design.mu_s", "every value must be >= 0, got -0.1"),
        ("mu_s = []", "design.mu_s", "must hold at least one value"),
        ("mu_s = { start = -0.1, stop = 0.3, num = 5 }", "design.mu_s", "every value must be >= 0, got -0.1"),
        ("mu_s = { start = 0.1, stop = 0.3, num = 0 }", "design.mu_s.num", "must be >= 1, got 0"),
        ("mu_s = [0.1]\npedestal_mass = [0.0, 300.0]", "design.pedestal_mass", "every value must be > 0, got 0"),
    ],
)
def test_design_grid_errors_name_the_file_and_the_field(capsys, tmp_path, monkeypatch, line, field, words):
    from rocking.analyses import design as design_module

    def refuse(*args, **kwargs):
        raise AssertionError("friction_design ran")

    monkeypatch.setattr(design_module, "friction_design", refuse)
    text = "\n".join(ln for ln in DESIGN.splitlines() if not ln.startswith(("mu_s =", "pedestal_mass =")))
    f = tmp_path / "d.toml"
    f.write_text(text.replace("[design]", f"[design]\n{line}"), encoding="utf-8")
    code, out, err = _run_cli(capsys, "design", f, "--out", tmp_path / "out")
    assert code == 2 and out == ""
    _one_error_line(err, f"error: {f}: {field}: {words}")
    assert not (tmp_path / "out").exists()


def test_info_with_the_wrong_format_says_what_the_file_is(capsys):
    code, out, err = _run_cli(capsys, "info", AT2, "--format", "esm")
    assert code == 2 and out == ""
    line = _one_error_line(err, f"{bundled_records()[AT2]}: line 1: not an ESM ASCII file",
                           "looks like a PEER AT2 file")
    assert "lines 1-0" not in line
    code, out, err = _run_cli(capsys, "info", ESM, "--format", "peer")
    assert code == 2
    _one_error_line(err, "no 'NPTS= n, DT= x' line", "looks like an ESM ASCII file")


def test_an_empty_record_file(tmp_path):
    f = tmp_path / "empty.ASC"
    f.write_text("\n  \n")
    for fmt in (None, "esm", "peer", "two-column"):
        with pytest.raises(RecordError, match=r"empty\.ASC: the file is empty$"):
            read_record(f, format=fmt)


def test_values_that_overflow_in_si_units(tmp_path):
    f = tmp_path / "huge.AT2"
    f.write_text("PEER\nX\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= 2, DT= .01 SEC\n 1e308 0.0\n")
    with pytest.raises(RecordError, match=r"value #1 \(1e\+308 g\) overflows when converted to m/s²"):
        read_record(f)


# ====================================================================== the web page
def test_web_units_selector_against_the_header(tmp_path):
    from rocking.web.app import create_app

    from test_web import FORM, text_of

    app = create_app({"WORK_DIR": str(tmp_path)})
    try:
        client = app.test_client()
        r = client.post("/run", data={**FORM, "record": ESM, "units": "g"})
        assert r.status_code == 400
        error = text_of(r.get_data(as_text=True), "error")
        assert "units of the file: LAquila2009_AQV_HNE_ESM.ASC states its units as 'cm/s^2' (line 33), not g" in error
        assert "from the file" in error and "units_override" not in error and "upload" not in error
        r = client.post("/run", data={**FORM, "record": ESM, "units": "cm/s2", "statue_width": "x"})
        assert "units of the file" not in text_of(r.get_data(as_text=True), "error")  # agreeing units pass
    finally:
        app.extensions["rocking"].shutdown()
