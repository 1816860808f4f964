"""Property-based tests of every record reader and of the configuration loaders (hypothesis).

The property, for any input: either a valid result, or the documented error, one line of text
(:class:`~rocking.io.records.RecordError` for a record file, :class:`~rocking.io.config.ConfigError`
for a configuration), never another exception, a hang or a crash. Inputs: random bytes, the
bundled records cut at a random byte, random numbers (huge, tiny, negative, NaN, words) in every
header field, and random values in every field of a valid configuration and of the study files.
Nothing here simulates: loading a configuration reads its record and builds the specs only.
"""

from __future__ import annotations

import atexit
import copy
import math
import os
import shutil
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from rocking.excitation.record import GroundMotion
from rocking.io.config import Config, ConfigError, load_config
from rocking.io.records import RecordError, bundled_records, read_record

# Each test stays within a few seconds; no deadline per example (the machine may be shared).
# ROCKING_FUZZ_EXAMPLES=2000 searches harder (minutes), e.g. after changing a reader.
_N = int(os.environ.get("ROCKING_FUZZ_EXAMPLES", "120"))
FUZZ = settings(deadline=None, max_examples=_N, suppress_health_check=[HealthCheck.too_slow])
FUZZ_SMALL = settings(deadline=None, max_examples=max(1, _N // 2), suppress_health_check=[HealthCheck.too_slow])

FORMATS = [None, "peer", "esm", "two-column"]
_DIR = Path(tempfile.mkdtemp(prefix="rocking-fuzz-"))
atexit.register(shutil.rmtree, _DIR, ignore_errors=True)


def _file(data: bytes | str, name: str = "record.txt") -> Path:
    """Write one example's file (the same path every time: the examples run one by one)."""
    path = _DIR / name
    if isinstance(data, str):
        path.write_text(data, encoding="utf-8", errors="surrogatepass")
    else:
        path.write_bytes(data)
    return path


def _one_line(exc: BaseException) -> None:
    text = str(exc)
    assert len(text.splitlines()) == 1, repr(text)  # any line break: \n, \r, \u2028...


def _check_record(path: Path, **kwargs: Any) -> GroundMotion | None:
    """read_record gives a valid motion or a one-line RecordError naming the file."""
    try:
        motion = read_record(path, **kwargs)
    except RecordError as exc:
        _one_line(exc)
        assert str(exc).startswith(str(path)), str(exc)
        event(f"RecordError: {exc.reason[:40]}")
        return None
    event("valid")
    assert isinstance(motion, GroundMotion)
    assert motion.time.size == motion.values.size >= 2
    assert np.all(np.isfinite(motion.time)) and np.all(np.isfinite(motion.values))
    assert np.all(np.diff(motion.time) > 0)
    assert math.isfinite(motion.dt) and motion.dt > 0
    return motion


# --------------------------------------------------------------------------- strategies
_NUMBERS = st.one_of(
    st.integers(min_value=-(10**30), max_value=10**30).map(str),
    st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True).map(repr),
    st.floats(min_value=-1e3, max_value=1e3).map(lambda x: f"{x:.6E}"),
    st.floats(min_value=1e-320, max_value=1e-300).map(repr),
    st.sampled_from(["", "0", "-0", "1", "2", ".005", "1e308", "1e-323", "nan", "inf", "-inf", "1_000", "1.0D-03",
                     "0x10", "١٢", "NPTS", "=", ",", "1,2", "+", "-", ".", "e5", "9" * 400]),
    st.text(alphabet="0123456789+-.eEdD_ ,x", max_size=12),
    st.text(max_size=8),
)
# any finite double, written as a record would hold it: 1e308 in g overflows in m/s²
_VALUE = st.one_of(
    st.floats(-2.0, 2.0).map(lambda x: f"{x:.7E}"),
    st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=True).map(repr),
)


def _broken(draw, fields: list[str]) -> set[str]:
    """The fields an example corrupts: none, one or two, so that many files get past the
    header and the values (and the success path) are fuzzed too."""
    return draw(st.sets(st.sampled_from(fields), max_size=2))


def _values(draw, n: int, broken: set[str]) -> list[str]:
    values = [draw(_VALUE) for _ in range(n)]
    if "values" in broken and values:
        values[draw(st.integers(0, n - 1))] = draw(_NUMBERS)
    return values


_UNITS = st.one_of(
    st.sampled_from(["G", "g", "cm/s^2", "CM/SEC/SEC", "gal", "m/s2", "mm/s2", "m/s²", "in/s2", "", "furlongs"]),
    st.text(max_size=6),
)


@st.composite
def _peer_file(draw) -> str:
    """A PEER AT2 layout with random header numbers, units and values."""
    broken = _broken(draw, ["npts", "dt", "units", "kind", "values", "layout"])
    n_values = draw(st.integers(0, 12))
    values = _values(draw, n_values, broken)
    npts = draw(_NUMBERS) if "npts" in broken else str(n_values)
    dt = draw(_NUMBERS) if "dt" in broken else draw(st.sampled_from([".0050", "0.01", "1e-300", "1e300", "5e-324"]))
    units = draw(_UNITS) if "units" in broken else draw(st.sampled_from(["G", "g", "CM/SEC/SEC", "gal"]))
    kind = draw(st.sampled_from(["VELOCITY", "DISPLACEMENT", "ACCEL"])) if "kind" in broken else "ACCELERATION"
    old_layout = draw(st.booleans())
    npts_line = f"  {npts}   {dt}   NPTS, DT" if old_layout else f"NPTS= {npts}, DT= {dt} SEC,"
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "FUZZ, 01/01/2000, Nowhere, 000",
             f"{kind} TIME HISTORY IN UNITS OF {units}", npts_line]
    if "layout" in broken:
        del lines[draw(st.integers(0, len(lines) - 1))]
    per_line = draw(st.integers(1, 6))
    for i in range(0, n_values, per_line):
        lines.append("  ".join(values[i:i + per_line]))
    return "\n".join(lines) + draw(st.sampled_from(["\n", "", "\r\n", "\n\n"]))


@st.composite
def _esm_file(draw) -> str:
    """An ESM ASCII layout with random NDATA, SAMPLING_INTERVAL_S, UNITS, DATA_TYPE and values."""
    broken = _broken(draw, ["NDATA", "SAMPLING_INTERVAL_S", "UNITS", "DATA_TYPE", "values", "missing"])
    n_values = draw(st.integers(0, 12))
    values = _values(draw, n_values, broken)
    fields = {
        "EVENT_NAME": draw(st.text(max_size=10).map(lambda s: " ".join(s.splitlines()))),
        "SAMPLING_INTERVAL_S": draw(st.sampled_from(["0.005000", "1e-300", "1e300", "5e-324"])),
        "NDATA": str(n_values),
        "UNITS": draw(st.sampled_from(["cm/s^2", "m/s^2", "g", "gal"])),
        "DATA_TYPE": "ACCELERATION",
    }
    for key in broken & set(fields):
        fields[key] = draw(st.sampled_from(["VELOCITY", "DISPLACEMENT", ""])) if key == "DATA_TYPE" else draw(_NUMBERS)
    keys = draw(st.permutations(list(fields)))
    if "missing" in broken:
        keys.remove(draw(st.sampled_from(keys)))
    lines = [f"{k}: {fields[k]}" for k in keys] + values
    return "\n".join(lines) + "\n"


@st.composite
def _two_column_file(draw) -> str:
    """Header lines with a units spelling, then rows of random (time, acceleration) text."""
    header = draw(st.sampled_from(["Time[s] Accel[{u}]", "time acc ({u})", "units: {u}", "# t a", ""]))
    units = draw(_UNITS).replace("]", "").replace(")", "")
    n = draw(st.integers(0, 10))
    t = 0.0
    rows = []
    for _ in range(n):
        if draw(st.booleans()):
            t += draw(st.floats(min_value=1e-6, max_value=1.0))
            rows.append(f"{t!r} {draw(st.floats(-3, 3))!r}")
        else:
            sep = draw(st.sampled_from([" ", ",", ";", "\t", "  "]))
            rows.append(sep.join(draw(st.lists(_NUMBERS, min_size=0, max_size=3))))
    return "\n".join([header.format(u=units), *rows]) + "\n"


# ------------------------------------------------------------------------------- readers
@FUZZ
@given(data=st.binary(max_size=600), fmt=st.sampled_from(FORMATS))
def test_random_bytes_give_a_motion_or_a_record_error(data, fmt):
    _check_record(_file(data), format=fmt)


@FUZZ
@given(text=st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=400),
       fmt=st.sampled_from(FORMATS))
def test_random_text_gives_a_motion_or_a_record_error(text, fmt):
    _check_record(_file(text), format=fmt)


# the bundled records of each format that are small enough to reread for every example
_TRUNCATABLE = [name for name, p in bundled_records().items() if p.stat().st_size < 200_000]
_BYTES = {name: bundled_records()[name].read_bytes() for name in _TRUNCATABLE}


def test_the_truncated_records_cover_every_format():
    formats = {read_record(name).meta["format"] for name in _TRUNCATABLE}
    assert formats == {"peer", "esm", "two-column"}


@FUZZ_SMALL
@given(name=st.sampled_from(_TRUNCATABLE), cut=st.floats(0.0, 1.0))
def test_truncated_bundled_records_fail_cleanly(name, cut):
    data = _BYTES[name]
    k = int(cut * len(data))
    suffix = bundled_records()[name].suffix  # keep the extension: .AT2 selects the PEER reader
    motion = _check_record(_file(data[:k], "cut" + suffix))
    if motion is not None:
        # only a cut in the trailing blank space (or within the last value of a two-column
        # file, which still parses) leaves a record; it must then be the whole record or
        # a two-column record that lost its last rows
        full = read_record(name)
        assert motion.meta["format"] == full.meta["format"]
        if motion.meta["format"] != "two-column":
            assert motion.time.size == full.time.size


@FUZZ
@given(text=_peer_file(), fmt=st.sampled_from([None, "peer"]), units=st.one_of(st.none(), _UNITS))
def test_peer_headers_with_random_numbers(text, fmt, units):
    # units= that is not a unit is a RecordError naming the file too
    _check_record(_file(text, "fuzz.AT2"), format=fmt, units=units)


@FUZZ
@given(text=_esm_file(), fmt=st.sampled_from([None, "esm"]), override=st.booleans())
def test_esm_headers_with_random_numbers(text, fmt, override):
    units = "g" if override else None
    _check_record(_file(text, "fuzz.ASC"), format=fmt, units=units, units_override=override)


@FUZZ
@given(text=_two_column_file(), fmt=st.sampled_from([None, "two-column"]), units=st.sampled_from([None, "g"]))
def test_two_column_files_with_random_numbers(text, fmt, units):
    _check_record(_file(text, "fuzz.dat"), format=fmt, units=units, units_override=units is not None)


@FUZZ_SMALL
@given(text=st.one_of(_peer_file(), _esm_file(), _two_column_file()), fmt=st.sampled_from(["peer", "esm", "two-column"]))
def test_a_forced_format_on_another_layout_fails_cleanly(text, fmt):
    _check_record(_file(text, "other.txt"), format=fmt)


# ------------------------------------------------------------------------------ configs
VALID = {
    "statue": {"width": 0.3, "height": 1.2, "mass": 100.0, "restitution": 0.8,
               "friction": {"static": 0.5, "kinetic": 0.4}},
    "pedestal": {"mass": 50.0, "friction": {"static": 0.2, "kinetic": 0.15}, "width": 0.5, "height": 0.3},
    "motion": {"kind": "harmonic", "amplitude": 3.0, "frequency": 1.5, "cycles": 2, "form": "cos"},
    "simulation": {"duration": 1.5, "gravity": 9.81, "normal_force": "full", "impact": "coulomb",
                   "rtol": 1e-8, "atol": 1e-10, "max_step": 0.01, "save_dt": 0.01, "rest_velocity": 1e-6,
                   "max_events": 1000},
}
RINALDI = "Northridge1994_RinaldiReceivingSta_228"
MOTIONS = [
    {"kind": "harmonic", "amplitude": 3.0, "frequency": 1.5, "cycles": 2, "form": "sin", "angular_frequency": 9.0},
    {"kind": "record", "path": RINALDI, "pga": 3.0, "units": "g", "format": "peer"},
    {"kind": "record", "path": "LAquila2009_AQV_HNE_ESM", "scale": 0.5, "units": "cm/s2",
     "vertical_path": "LAquila2009_AQV_HNE_ESM", "vertical_units": "gal", "units_override": False},
    {"kind": "pulse", "shape": "sine", "amplitude": 3.0, "frequency": 2.0, "phase": 0.5},
    {"kind": "pulse", "shape": "cosine", "amplitude": 3.0, "frequency": 2.0},
    {"kind": "pulse", "shape": "rectangle", "amplitude": 3.0, "width": 0.2},
    {"kind": "pulse", "shape": "ricker", "amplitude": 3.0, "frequency": 2.0, "center": 0.5},
]

# anything a TOML file or a dict can hold, with the awkward numbers first
_VALUES = st.one_of(
    st.sampled_from([0, -1, 1, 0.0, -0.0, 1e-300, 1e300, 10**400, -(10**400), float("nan"), float("inf"),
                     float("-inf"), True, False, None, "", "nan", "1.2", "g", "cm/s^2", "harmonic", "record",
                     "pulse", "sine", RINALDI, "/", ".", [], {}, [1.0, 2.0], {"start": 0.1, "stop": 0.2, "num": 3}]),
    st.integers(),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=3),
    st.dictionaries(st.text(max_size=6), st.integers(), max_size=2),
)


def _leaves(d: dict, prefix: tuple = ()) -> list[tuple]:
    out = []
    for k, v in d.items():
        out.append((*prefix, k))
        if isinstance(v, dict):
            out += _leaves(v, (*prefix, k))
    return out


def _set(d: dict, path: tuple, value: Any) -> None:
    for k in path[:-1]:
        d = d[k]
    # a copy: sampled_from hands out the same {} / [] / dict object at every draw, and a later
    # draw could set a key of that very object to itself (a cycle the walk never leaves)
    d[path[-1]] = copy.deepcopy(value)


def _check_config(config: Any, **kwargs: Any) -> Config | None:
    try:
        cfg = load_config(config, **kwargs)
    except ConfigError as exc:
        _one_line(exc)
        event(f"ConfigError: {exc.field}")
        return None
    event("valid")
    assert isinstance(cfg, Config)
    return cfg


@FUZZ
@given(data=st.data(), motion=st.sampled_from(MOTIONS))
def test_random_values_in_every_config_field(data, motion):
    config = copy.deepcopy(VALID)
    config["motion"] = copy.deepcopy(motion)
    # one to three fields replaced, or deleted, or an unknown key added
    for _ in range(data.draw(st.integers(1, 3))):
        path = data.draw(st.sampled_from(_leaves(config)))
        action = data.draw(st.sampled_from(["replace", "replace", "replace", "delete", "add"]))
        if action == "delete":
            parent = config
            for k in path[:-1]:
                parent = parent[k]
            parent.pop(path[-1], None)
        elif action == "add":
            _set(config, (*path[:-1], data.draw(st.text(min_size=1, max_size=8))), data.draw(_VALUES))
        else:
            _set(config, path, data.draw(_VALUES))
        if not config:
            break
    _check_config(config)


@FUZZ
@given(text=st.text(max_size=300))
def test_random_toml_text(text):
    _check_config(_file(text, "fuzz.toml"))


_TOML = """\
[statue]
width = 0.3
height = 1.2
mass = 100.0
friction = { static = 0.5, kinetic = 0.4 }

[pedestal]
mass = 50.0
friction = { static = 0.2, kinetic = 0.15 }

[motion]
kind = "record"
path = "Northridge1994_RinaldiReceivingSta_228"
pga = 3.0

[simulation]
duration = 1.5
"""
_TOML_VALUES = [line.split("=", 1)[1].strip() for line in _TOML.splitlines() if "=" in line and "{" not in line]


@FUZZ
@given(data=st.data())
def test_random_values_in_a_toml_file(data):
    text = _TOML
    for _ in range(data.draw(st.integers(1, 2))):
        old = data.draw(st.sampled_from(_TOML_VALUES))
        new = data.draw(st.one_of(_NUMBERS, st.sampled_from(["nan", "inf", "-inf", "1e400", "true", '"x"', "[]",
                                                             "{}", '"g"', "1979-05-27", "0x10"])))
        text = text.replace(f"= {old}\n", f"= {new}\n", 1)
    _check_config(_file(text, "fuzz.toml"))


@FUZZ_SMALL
@given(data=st.binary(max_size=300))
def test_random_bytes_as_toml(data):
    _check_config(_file(data, "fuzz.toml"))


# ------------------------------------------------------------------------------- studies
STUDIES = {
    "design": {
        "statue": {"width": 0.4, "height": 1.6, "mass": 200.0, "friction": {"static": 0.5}},
        "pedestal": {"mass": 300.0, "friction": {"static": 0.3, "kinetic": 0.25}},
        "motions": {"records": [RINALDI], "pga": 4.0},
        "design": {"mu_s": {"start": 0.05, "stop": 0.45, "num": 3}, "mu_k_ratio": 0.8, "pedestal_mass": [150.0],
                   "sliding_limit": 0.1, "objective": "mean", "free_time": 5.0},
    },
    "design-family": {
        "statue": {"width": 0.4, "height": 1.6, "mass": 200.0},
        "pedestal": {"mass": 300.0, "friction": {"static": 0.3}},
        "motions": {"family": "harmonic", "amplitude": [2.0, 4.0], "frequency": {"start": 0.5, "stop": 3.0, "num": 2},
                    "cycles": 3},
        "design": {"mu_s": [0.1, 0.2], "mu_k": 0.1},
    },
    "fragility": {
        "statue": {"width": 0.4, "height": 1.6, "mass": 200.0},
        "pedestal": {"mass": 300.0, "friction": {"static": 0.3}},
        "fragility": {"records": [RINALDI], "pga_levels": [1.0, 2.0], "pgv_levels": {"start": 0.1, "stop": 1.0, "num": 3},
                      "band": "fisher", "bootstrap": 50, "confidence": 0.9, "seed": 1, "free_time": 2.0},
    },
    "spectrum": {
        "statue": {"width": 0.4, "height": 1.6, "mass": 200.0},
        "spectrum": {"motions": ["sine", "cosine"], "frequency_ratio": [1.0, 2.0], "amplitude_ratio": [1.01, 30.0],
                     "n_scan": 8, "rtol": 1e-3, "criterion": "overturn", "phase": "onset", "cycles": 3.0,
                     "free_time": 25.0},
    },
}


@FUZZ
@given(data=st.data(), name=st.sampled_from(sorted(STUDIES)))
def test_random_values_in_every_study_field(data, name):
    from rocking.cli import studies

    kind = name.split("-")[0]
    config = copy.deepcopy(STUDIES[name])
    for _ in range(data.draw(st.integers(1, 2))):
        path = data.draw(st.sampled_from(_leaves(config)))
        _set(config, path, data.draw(_VALUES))
    try:
        study, base = studies.load_study(kind, config)
        getattr(studies, f"{kind}_inputs")(study, base)  # the specs and records, no run
    except ConfigError as exc:
        _one_line(exc)
        assert exc.field, str(exc)  # every study problem names its field
        event(f"ConfigError: {exc.field}")
    else:
        event("valid")
