"""Bundled accelerograms, the record readers and GroundMotion."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from rocking.excitation.base import KIND_SAMPLED, KIND_ZERO, N_PARAMS
from rocking.excitation.record import GroundMotion
from rocking.io.records import (
    RecordError,
    bundled_records,
    read_record,
    resolve_record,
    units_to_si,
)

# Standard gravity, m/s², by definition (3rd CGPM, 1901): typed here, not read from the package
# under test, so that a wrong conversion constant there cannot cancel out of these checks.
G = 9.80665

# From rocking/data/records/README.md: file stem -> (points, dt in s, PGA in g, units).
TABLE = {
    "ImperialValley1940_ElCentroArray9_180": (5372, 0.01, 0.281, "g"),
    "ImperialValley1979_ElCentroArray6_230": (7818, 0.005, 0.449, "g"),
    "Northridge1994_RinaldiReceivingSta_228": (1991, 0.01, 0.874, "g"),
    "Northridge1994_SylmarConverterSta_052": (8773, 0.005, 0.623, "g"),
    "Northridge1994_CastaicOldRidgeRoute_090_2col": (3989, 0.01, 0.568, "g"),
    "Kobe1995_Takatori_000": (4096, 0.01, 0.618, "g"),
    "ChiChi1999_TCU052_N": (18000, 0.005, 0.419, "g"),
    "LomaPrieta1989_Corralitos_000": (7995, 0.005, 0.645, "g"),
    "LomaPrieta1989_TreasureIsland_000": (7999, 0.005, 0.100, "g"),
    "Landers1992_Lucerne_260": (9625, 0.005, 0.725, "g"),
    "Kocaeli1999_Fatih_000": (30598, 0.005, 0.188, "g"),
    "LAquila2009_AQV_HNE_ESM": (20001, 0.005, 0.657, "cm/s2"),
    "LAquila2009_AVZ_HNN_ESM": (24000, 0.005, 0.069, "cm/s2"),
    "Friuli1976_Tolmezzo_000": (7277, 0.005, 0.357, "g"),
    "Irpinia1980_Brienza_000": (12064, 0.0029, 0.220, "g"),
}

README = Path(__file__).resolve().parents[1] / "src/rocking/data/records/README.md"


@pytest.fixture(scope="module")
def motions() -> dict[str, GroundMotion]:
    return {stem: read_record(path) for stem, path in bundled_records().items()}


# ---------------------------------------------------------------- bundled records
def test_every_table_entry_is_bundled_and_nothing_else():
    assert set(bundled_records()) == set(TABLE)


def test_readme_table_matches_this_test():
    """The numbers hard-coded above are the ones in the packaged README."""
    rows = [ln for ln in README.read_text(encoding="utf-8").splitlines() if ln.startswith("| ")]
    seen = {}
    for row in rows[1:]:  # skip the column titles
        cells = [c.strip() for c in row.strip("|").split("|")]
        stem = Path(cells[0]).stem
        seen[stem] = (int(cells[6]), float(cells[7].split()[0]), float(cells[9]))
    assert seen == {k: v[:3] for k, v in TABLE.items()}


@pytest.mark.parametrize("stem", sorted(TABLE))
def test_bundled_record_against_readme(motions, stem):
    npts, dt, pga_g, units = TABLE[stem]
    gm = motions[stem]
    assert gm.n == npts
    assert gm.meta["npts"] == npts
    assert gm.dt == dt  # exactly, see GroundMotion.dt
    assert gm.meta["dt"] == dt
    assert gm.duration == pytest.approx((npts - 1) * dt, rel=1e-12)
    assert gm.time[0] == 0.0
    assert abs(gm.pga / G - pga_g) <= 0.0005 + 1e-12  # table gives 3 decimals
    assert gm.units == units
    assert gm.name == stem
    assert Path(gm.source) == bundled_records()[stem]
    assert np.all(np.isfinite(gm.values))


def test_kobe_file_really_has_crlf_and_parses(motions):
    raw = bundled_records()["Kobe1995_Takatori_000"].read_bytes()
    assert raw.count(b"\r\n") == raw.count(b"\n") > 800  # every line ends with CRLF
    gm = motions["Kobe1995_Takatori_000"]
    assert gm.n == 4096
    assert gm.values[0] == pytest.approx(-0.1259993e-02 * G, rel=1e-15)
    assert gm.values[-1] == pytest.approx(0.4044295e-03 * G, rel=1e-15)
    assert gm.meta["event"] == "KOBE, 01/16/1995, Takatori, 000"  # trailing blanks gone


def test_brienza_odd_dt(motions):
    gm = motions["Irpinia1980_Brienza_000"]
    assert gm.meta["dt"] == 0.0029
    assert gm.dt == 0.0029
    assert gm.time[-1] == pytest.approx(12063 * 0.0029)
    assert gm.duration == pytest.approx(34.98, abs=0.01)


def test_old_pacific_engineering_header(motions):
    gm = motions["ChiChi1999_TCU052_N"]
    assert gm.meta["header"][0].startswith("PEER STRONG MOTION DATABASE RECORD. PROCESSING")
    assert gm.meta["header_units"] == "G"  # from "IN UNITS OF G. FILTER POINTS ..."


def test_esm_cm_per_s2_converted_to_si(motions):
    gm = motions["LAquila2009_AQV_HNE_ESM"]
    assert gm.units == "cm/s2"
    assert gm.meta["header_units"] == "cm/s^2"
    # the header's own PGA (cm/s², signed for AVZ) agrees with the data after conversion
    assert gm.pga == pytest.approx(644.246826 / 100, rel=1e-12)
    assert gm.values[1] == pytest.approx(-0.000116 / 100, rel=1e-12)
    avz = motions["LAquila2009_AVZ_HNN_ESM"]
    assert avz.pga == pytest.approx(abs(float(avz.meta["header"]["PGA_CM/S^2"])) / 100)
    for m in (gm, avz):  # and the time axis is right: the peak is where the header says
        t_peak = m.time[np.argmax(np.abs(m.values))]
        assert t_peak == pytest.approx(float(m.meta["header"]["TIME_PGA_S"]), abs=1e-9)
    assert gm.meta["license"].startswith("CC-BY3_0-IT")
    assert "10.13127/itaca.3.1" in gm.meta["citation"]
    assert gm.meta["station"] == "AQV" and gm.meta["component"] == "HNE"


def test_two_column_file(motions):
    gm = motions["Northridge1994_CastaicOldRidgeRoute_090_2col"]
    raw = bundled_records()[gm.name].read_bytes()
    assert not raw.endswith(b"\n")  # last row has no newline and must still be read
    assert gm.meta["format"] == "two-column"
    assert gm.meta["header_units"] == "g"  # from "Time[s] Accel[g]"
    assert gm.time[0] == 0.0 and gm.time[-1] == 39.88
    assert gm.values[:3] == pytest.approx(np.array([-0.0012, -0.0007, -0.0003]) * G)
    assert gm.values[-1] == pytest.approx(-0.0001 * G)


def test_resolve_record_by_stem_name_and_path(tmp_path):
    path = bundled_records()["Kobe1995_Takatori_000"]
    assert resolve_record("Kobe1995_Takatori_000") == path
    assert resolve_record("Kobe1995_Takatori_000.AT2") == path
    assert resolve_record(path) == path
    assert resolve_record(str(path)) == path
    with pytest.raises(FileNotFoundError, match="Kobe1995_Takatori_000"):
        resolve_record("Kobe1995_Takatori")  # suggests the close name
    with pytest.raises(FileNotFoundError):
        resolve_record(tmp_path / "missing.AT2")


def test_units_argument_overrides_header():
    # units that contradict the header are refused unless asked for (tests/test_input_errors.py)
    with pytest.raises(RecordError, match="the header states the units 'G', but units='cm/s2'"):
        read_record("Kobe1995_Takatori_000", units="cm/s2")
    gm = read_record("Kobe1995_Takatori_000", units="cm/s2", units_override=True)
    ref = read_record("Kobe1995_Takatori_000")
    np.testing.assert_allclose(gm.values, ref.values / G / 100, rtol=1e-15)
    assert gm.units == "cm/s2" and gm.meta["header_units"] == "G"


@pytest.mark.parametrize(
    ("units", "factor"),
    [
        ("g", G), ("G", G),
        ("cm/s2", 0.01), ("cm/s^2", 0.01), ("cm/s²", 0.01), ("gal", 0.01), ("GAL", 0.01),
        ("m/s2", 1.0), ("m/s^2", 1.0), ("M/S²", 1.0),
        ("mm/s2", 0.001),
    ],
)
def test_unit_spellings(units, factor):
    assert units_to_si(units) == factor


# ------------------------------------------------------------------- bad input
AT2_HEADER = (
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "Test, 1/1/2000, Nowhere, 0\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n"
)


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def check(exc: pytest.ExceptionInfo, path: Path, line: int | None) -> None:
    msg = str(exc.value)
    assert path.name in msg
    assert isinstance(exc.value, ValueError)
    if line is not None:
        assert re.search(rf"\bline {line}\b", msg), msg
        assert exc.value.line == line


def test_at2_roundtrip_small(tmp_path):
    path = write(tmp_path, "ok.AT2", AT2_HEADER + "NPTS=  7, DT= .0100 SEC,\n"
                 " .1E-01 -.2E-01 .3E-01 .4E-01 .5E-01\n .6E-01 -.7E-01\n")
    gm = read_record(path)
    np.testing.assert_allclose(gm.values / G, [0.01, -0.02, 0.03, 0.04, 0.05, 0.06, -0.07])
    assert gm.duration == pytest.approx(0.06)


def test_at2_nan_value(tmp_path):
    path = write(tmp_path, "nan.AT2", AT2_HEADER + "NPTS= 6, DT= .01 SEC\n"
                 "1.0 2.0 3.0\n4.0 NaN 6.0\n")
    with pytest.raises(RecordError, match="not finite") as exc:
        read_record(path)
    check(exc, path, 6)


def test_at2_inf_value(tmp_path):
    path = write(tmp_path, "inf.AT2", AT2_HEADER + "NPTS= 3, DT= .01 SEC\n1.0 inf 2.0\n")
    with pytest.raises(RecordError, match="not finite") as exc:
        read_record(path)
    check(exc, path, 5)


def test_at2_too_few_points(tmp_path):
    path = write(tmp_path, "short.AT2", AT2_HEADER + "NPTS= 6, DT= .01 SEC\n"
                 "1.0 2.0 3.0\n4.0 5.0\n\n")
    with pytest.raises(RecordError, match=r"5 values.*NPTS=6 \(line 4\)") as exc:
        read_record(path)
    check(exc, path, 6)


def test_at2_too_many_points(tmp_path):
    path = write(tmp_path, "long.AT2", AT2_HEADER + "NPTS= 4, DT= .01 SEC\n"
                 "1.0 2.0 3.0\n4.0 5.0\n")
    with pytest.raises(RecordError, match=r"value #5.*NPTS=4") as exc:
        read_record(path)
    check(exc, path, 6)


def test_at2_garbage_number(tmp_path):
    path = write(tmp_path, "garbage.AT2", AT2_HEADER + "NPTS= 4, DT= .01 SEC\n"
                 "1.0 2.0\n3.0 4.O\n")
    with pytest.raises(RecordError, match="'4.O'") as exc:
        read_record(path)
    check(exc, path, 6)


def test_at2_fortran_d_exponent_is_accepted(tmp_path):
    path = write(tmp_path, "d.AT2", AT2_HEADER + "NPTS= 2, DT= .01 SEC\n1.0D-02 -2.0d-02\n")
    np.testing.assert_allclose(read_record(path).values / G, [0.01, -0.02])


@pytest.mark.parametrize(
    ("line4", "what"),
    [
        ("NPTS= abc, DT= .01 SEC", "NPTS = 'abc'"),
        ("NPTS= 4, DT= fast SEC", "DT = 'fast'"),
        ("NPTS= 4, DT= -.01 SEC", "must be positive"),
        ("NPTS 4 DT .01", "expected 'NPTS= n, DT= x'"),
    ],
)
def test_at2_malformed_header(tmp_path, line4, what):
    path = write(tmp_path, "hdr.AT2", AT2_HEADER + line4 + "\n1.0 2.0 3.0 4.0\n")
    with pytest.raises(RecordError, match="malformed header") as exc:
        read_record(path)
    assert what in str(exc.value)
    check(exc, path, 4)


def test_at2_without_npts_line(tmp_path):
    path = write(tmp_path, "nonpts.AT2", AT2_HEADER + "1.0 2.0\n")
    with pytest.raises(RecordError, match="NPTS") as exc:
        read_record(path)
    check(exc, path, None)


def test_at2_units_missing_asks_for_units_argument(tmp_path):
    text = "PEER RECORD\nTest\nACCELERATION\nNPTS= 2, DT= .01 SEC\n1.0 2.0\n"
    path = write(tmp_path, "nounits.AT2", text)
    with pytest.raises(RecordError, match="units=") as exc:
        read_record(path)
    check(exc, path, None)
    assert read_record(path, units="m/s2").values.tolist() == [1.0, 2.0]


def test_unknown_units_in_header(tmp_path):
    text = AT2_HEADER.replace("UNITS OF G", "UNITS OF FT/S2") + "NPTS= 2, DT= .01\n1 2\n"
    path = write(tmp_path, "ft.AT2", text)
    with pytest.raises(RecordError, match="'FT/S2'") as exc:
        read_record(path)
    check(exc, path, 3)


def test_unknown_units_argument(tmp_path):
    path = write(tmp_path, "ok.AT2", AT2_HEADER + "NPTS= 2, DT= .01\n1 2\n")
    with pytest.raises(ValueError, match="'furlong/fortnight2'") as exc:
        read_record(path, units="furlong/fortnight2")
    check(exc, path, None)


def test_velocity_file_is_refused(tmp_path):
    text = AT2_HEADER.replace("ACCELERATION TIME SERIES IN UNITS OF G",
                              "VELOCITY TIME SERIES IN UNITS OF CM/S")
    path = write(tmp_path, "vel.VT2", text + "NPTS= 2, DT= .01\n1 2\n")
    # the whole message: "velocity" alone also matched the test's own folder name
    with pytest.raises(RecordError) as info:
        read_record(path, format="peer")
    assert str(info.value) == f"{path}: line 4: this is a velocity or displacement record, not an acceleration"


@pytest.mark.parametrize("npts, dt, row, line, bad", [
    ("3", ".01", "1_000 2 3", 5, "cannot parse '1_000' as a number"),
    ("1_0", ".01", "1 2 3", 4, "malformed header: NPTS = '1_0' is not an integer"),
    ("3", "0.0_1", "1 2 3", 4, "malformed header: DT = '0.0_1' is not a number"),
])
def test_underscores_in_numbers_are_refused(tmp_path, npts, dt, row, line, bad):
    """Python reads "1_000" as 1000; no record format writes numbers so. A value of 1_000 was read
    as 1000 g, and NPTS= 1_0 as 10 points: refused now, naming the line and the token."""
    path = write(tmp_path, "us.AT2", f"PEER\nEV\nACCELERATION IN UNITS OF G\nNPTS= {npts}, DT= {dt}\n{row}\n")
    with pytest.raises(RecordError) as info:
        read_record(path)
    assert str(info.value) == f"{path}: line {line}: {bad}"


def test_two_column_rows_with_underscores_are_refused(tmp_path):
    path = write(tmp_path, "us.dat", "Time[s] Accel[g]\n0 0.1\n0.01 1_0\n")
    with pytest.raises(RecordError, match=re.escape("line 3: cannot parse '1_0' as a number")):
        read_record(path)


def test_a_peer_header_of_a_title_and_the_npts_line_names_no_event(tmp_path):
    """The event is the header's second line only when the NPTS line is not that line."""
    path = write(tmp_path, "two.AT2", "ACCELERATION IN UNITS OF G\nNPTS= 3, DT= .01\n1 2 3\n")
    assert read_record(path).meta["event"] == ""
    full = write(tmp_path, "full.AT2", "PEER\nKobe 1995, Takatori\nACCELERATION IN UNITS OF G\nNPTS= 3, DT= .01\n1 2 3\n")
    assert read_record(full).meta["event"] == "Kobe 1995, Takatori"


def esm_text(ndata: str = "3", dt: str = "0.010000", units: str = "cm/s^2",
             data: str = "0.0\n1.5\n-2.0\n") -> str:
    header = [
        "EVENT_NAME: TEST",
        "STATION_CODE: XYZ",
        f"SAMPLING_INTERVAL_S: {dt}",
        f"NDATA: {ndata}",
        f"UNITS: {units}",
        "DATA_TYPE: ACCELERATION",
        "USER1: ",
    ]
    return "\n".join(header) + "\n" + data


def test_esm_small(tmp_path):
    path = write(tmp_path, "x.ASC", esm_text())
    gm = read_record(path)
    np.testing.assert_allclose(gm.values, [0.0, 0.015, -0.02])
    assert gm.dt == 0.01 and gm.meta["format"] == "esm"


def test_esm_wrong_ndata(tmp_path):
    path = write(tmp_path, "n.ASC", esm_text(ndata="4"))
    with pytest.raises(RecordError, match=r"NDATA=4 \(line 4\)") as exc:
        read_record(path)
    check(exc, path, 10)


def test_esm_missing_fields(tmp_path):
    text = esm_text().replace("NDATA: 3\n", "").replace("SAMPLING_INTERVAL_S: 0.010000\n", "")
    path = write(tmp_path, "m.ASC", text)
    with pytest.raises(RecordError, match="NDATA, SAMPLING_INTERVAL_S") as exc:
        read_record(path)
    check(exc, path, 6)  # the first line after the 5-line header


def test_esm_malformed_dt(tmp_path):
    path = write(tmp_path, "dt.ASC", esm_text(dt="0,01"))
    with pytest.raises(RecordError, match="SAMPLING_INTERVAL_S = '0,01'") as exc:
        read_record(path)
    check(exc, path, 3)


def test_esm_unknown_units(tmp_path):
    path = write(tmp_path, "u.ASC", esm_text(units="cm/s"))
    with pytest.raises(RecordError, match="'cm/s'") as exc:
        read_record(path)
    check(exc, path, 5)


def test_esm_nan(tmp_path):
    path = write(tmp_path, "nan.ASC", esm_text(data="0.0\nnan\n1.0\n"))
    with pytest.raises(RecordError, match="not finite") as exc:
        read_record(path)
    check(exc, path, 9)


TWO_COL = "Some record\nTime[s]\tAccel[g]\n"


def test_two_column_parsing_variants(tmp_path):
    path = write(tmp_path, "a.txt", TWO_COL + "0.0\t0.1\n0.02\t-0.2\n# comment\n\n0.04 0.3")
    gm = read_record(path)
    assert gm.time.tolist() == [0.0, 0.02, 0.04]
    np.testing.assert_allclose(gm.values, np.array([0.1, -0.2, 0.3]) * G)
    assert gm.dt == 0.02
    csv = write(tmp_path, "b.csv", "time, acc (m/s^2)\n1.0, 2.0\n1.5, 3.0\n")
    gm = read_record(csv)
    assert gm.time.tolist() == [1.0, 1.5] and gm.values.tolist() == [2.0, 3.0]
    assert gm.units == "m/s2"
    assert gm.acceleration(np.array([0.5])).tolist() == [0.0]  # before the first sample


def test_two_column_non_increasing_time(tmp_path):
    path = write(tmp_path, "t.dat", TWO_COL + "0.00 0.1\n0.01 0.2\n0.01 0.3\n0.02 0.4\n")
    with pytest.raises(RecordError, match=r"not greater.*\(line 4\)") as exc:
        read_record(path)
    check(exc, path, 5)


def test_two_column_garbage_and_wrong_columns(tmp_path):
    path = write(tmp_path, "g.dat", TWO_COL + "0.00 0.1\n0.01 x0.2\n")
    with pytest.raises(RecordError, match="'x0.2'") as exc:
        read_record(path)
    check(exc, path, 4)
    path = write(tmp_path, "c.dat", TWO_COL + "0.00 0.1\n0.01 0.2 0.3\n")
    with pytest.raises(RecordError, match="found 3") as exc:
        read_record(path)
    check(exc, path, 4)


def test_two_column_without_units(tmp_path):
    path = write(tmp_path, "nu.dat", "time accel\n0 1\n1 2\n")
    with pytest.raises(RecordError, match="units=") as exc:
        read_record(path)
    check(exc, path, None)
    assert read_record(path, units="gal").values.tolist() == [0.01, 0.02]


def test_unrecognised_format(tmp_path):
    path = write(tmp_path, "prose.txt", "hello\nworld\n")
    with pytest.raises(RecordError, match="format=") as exc:
        read_record(path)
    check(exc, path, None)
    with pytest.raises(ValueError, match="'xml'"):
        read_record(path, format="xml")


# ----------------------------------------------------------------- GroundMotion
def simple() -> GroundMotion:
    return GroundMotion.from_arrays([0.0, 0.1, 0.2, 0.3], [0.0, 2.0, -4.0, 1.0], name="s")


def test_linear_between_samples_and_zero_outside():
    gm = simple()
    assert gm.acceleration(np.array([0.05]))[0] == pytest.approx(1.0)
    assert gm.acceleration(np.array([0.15]))[0] == pytest.approx(-1.0)
    assert gm.acceleration(np.array([0.175]))[0] == pytest.approx(-2.5)
    np.testing.assert_array_equal(gm.acceleration(gm.time), gm.values)
    np.testing.assert_array_equal(gm.acceleration(np.array([-0.1, 0.3000001, 5.0])), 0.0)
    np.testing.assert_array_equal(gm.vertical_acceleration(np.array([0.1, 0.2])), 0.0)


def test_midpoint_of_a_real_record(motions):
    gm = motions["Kobe1995_Takatori_000"]
    t = 0.5 * (gm.time[100] + gm.time[101])
    mid = 0.5 * (gm.values[100] + gm.values[101])
    assert gm.acceleration(np.array([t]))[0] == pytest.approx(mid, rel=1e-12)
    assert gm.acceleration(np.array([gm.duration + 1e-9]))[0] == 0.0


def test_properties():
    gm = simple()
    assert gm.dt == 0.1 and gm.duration == 0.3 and gm.pga == 4.0
    # trapezoid velocity: 0, 0.1, 0.0, -0.15 -> peak 0.15
    assert gm.pgv == pytest.approx(0.15)
    np.testing.assert_array_equal(gm.breakpoints, gm.time)


def test_signal_is_sampled_float64_contiguous():
    gm = simple()
    sig = gm.signal()
    assert sig.kind == KIND_SAMPLED
    assert sig.params.shape == (N_PARAMS,) and not sig.params.any()
    for arr, ref in ((sig.time, gm.time), (sig.values, gm.values)):
        assert arr.dtype == np.float64 and arr.flags.c_contiguous and arr.flags.writeable
        np.testing.assert_array_equal(arr, ref)
    assert gm.vertical_signal().kind == KIND_ZERO


def test_vertical_component():
    gm = GroundMotion.from_arrays([0.0, 1.0], [1.0, 1.0], vertical=[0.0, -2.0])
    assert gm.vertical_acceleration(np.array([0.5, 2.0])).tolist() == [-1.0, 0.0]
    sig = gm.vertical_signal()
    assert sig.kind == KIND_SAMPLED and sig.values.tolist() == [0.0, -2.0]
    assert gm.scaled(3.0).vertical.tolist() == [0.0, -6.0]


def test_scaled_by_factor():
    gm = simple()
    s = gm.scaled(2.5)
    np.testing.assert_array_equal(s.values, gm.values * 2.5)
    np.testing.assert_array_equal(s.time, gm.time)
    assert s.meta["scale_factor"] == 2.5 and s.scaled(2.0).meta["scale_factor"] == 5.0
    assert gm.values[1] == 2.0  # original untouched


@pytest.mark.parametrize("target", [0.1, 0.3 * G, 1.0, 2.718281828, 7.3])
def test_scaled_to_pga_is_exact(motions, target):
    for gm in (simple(), motions["Irpinia1980_Brienza_000"], motions["LAquila2009_AVZ_HNN_ESM"]):
        s = gm.scaled(pga=target)
        assert s.pga == target
        k = int(np.argmax(np.abs(gm.values)))
        assert np.sign(s.values[k]) == np.sign(gm.values[k])
        np.testing.assert_allclose(s.values, gm.values * (target / gm.pga), rtol=1e-15)


@pytest.mark.parametrize(
    "kwargs",
    [{}, {"factor": 2.0, "pga": 1.0}, {"factor": 0.0}, {"factor": -1.0},
     {"factor": float("nan")}, {"pga": float("inf")}, {"pga": "big"}],
)
def test_scaled_rejects_bad_arguments(kwargs):
    with pytest.raises(ValueError, match="GroundMotion.scaled"):
        simple().scaled(**kwargs)


def test_scaled_zero_record_to_pga():
    with pytest.raises(ValueError, match="identically zero"):
        GroundMotion.from_arrays([0, 1], [0, 0]).scaled(pga=1.0)


def test_trimmed():
    gm = simple()
    t = gm.trimmed(0.15)
    assert t.time.tolist() == [0.0, 0.1, 0.15] and t.values.tolist() == pytest.approx([0, 2, -1])
    assert t.duration == 0.15
    assert gm.trimmed(0.2).time.tolist() == [0.0, 0.1, 0.2]  # on a sample: nothing added
    assert gm.trimmed(10.0) is gm
    with pytest.raises(ValueError, match="t_end"):
        gm.trimmed(0.0)


def test_frozen_and_read_only():
    gm = simple()
    with pytest.raises(AttributeError):
        gm.name = "other"  # type: ignore[misc]
    with pytest.raises(ValueError):
        gm.values[0] = 1.0
    src = np.array([0.0, 1.0])
    gm = GroundMotion.from_arrays(src, [1.0, 2.0], meta=(("a", 1),))
    src[1] = 5.0  # the motion holds a copy
    assert gm.time[1] == 1.0 and gm.meta["a"] == 1


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        ({"time": [0.0, np.nan, 2.0], "values": [0, 0, 0]}, r"GroundMotion\.time\[1\] is nan"),
        ({"time": [0, 1, 2], "values": [0, np.inf, 0]}, r"GroundMotion\.values\[1\] is inf"),
        ({"time": [0, 1, 1, 2], "values": [0, 0, 0, 0]},
         r"GroundMotion\.time must be strictly increasing: time\[2\] = 1\.0"),
        ({"time": [0, 2, 1], "values": [0, 0, 0]}, r"time\[2\] = 1\.0 <= time\[1\] = 2\.0"),
        ({"time": [0, 1, 2], "values": [0, 0]},
         r"GroundMotion\.values has 2 samples but time has 3"),
        ({"time": [0.0], "values": [0.0]}, r"GroundMotion\.time needs at least 2 samples, got 1"),
        ({"time": [[0, 1]], "values": [0, 1]}, r"GroundMotion\.time must be 1-D"),
        ({"time": ["a", "b"], "values": [0, 1]}, r"GroundMotion\.time: cannot convert"),
        ({"time": [0, 1], "values": [0, 1], "vertical": [0.0]},
         r"GroundMotion\.vertical has 1 samples"),
        ({"time": [0, 1], "values": [0, 1], "vertical": [0.0, np.nan]},
         r"GroundMotion\.vertical\[1\] is nan"),
    ],
)
def test_validation_names_the_field(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        GroundMotion.from_arrays(**kwargs)
