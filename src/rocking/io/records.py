"""Readers for recorded accelerograms (PEER AT2, ESM/ITACA ASCII, two-column text).

Every reader returns a :class:`~rocking.excitation.record.GroundMotion` in m/s² and
refuses to guess: a value that does not parse, a point count that disagrees with the
header or units that cannot be found raise :class:`RecordError`, whose message starts
with ``<path>: line <n>:`` so the user can open the file at the faulty line.

Formats (see ``rocking/data/records/README.md`` for the bundled files):

``peer``
    PEER AT2: header lines ending with one that holds ``NPTS= n, DT= x`` (line 4 in
    practice; the old ``n x NPTS, DT`` layout is also read), units in the header text
    (``... IN UNITS OF G``), then whitespace-separated values.
``esm``
    ESM/ITACA ASCII: ``KEY: value`` header lines (``NDATA``, ``SAMPLING_INTERVAL_S``,
    ``UNITS``), then the values.
``two-column``
    Free-text header lines, then ``time accel`` rows (whitespace, comma or semicolon
    separated). Units from a header such as ``Accel[g]`` or from ``units=``.
"""

from __future__ import annotations

import difflib
import math
import os
import re
from pathlib import Path
from typing import Any

import numpy as np

from rocking.constants import STANDARD_GRAVITY
from rocking.excitation.record import GroundMotion

__all__ = [
    "MAX_RECORD_BYTES",
    "RecordError",
    "UnitsConflictError",
    "bundled_records",
    "read_record",
    "record_size_limit",
    "resolve_record",
    "units_to_si",
]

#: Largest record file read by default, bytes (50 MB: about 3 million samples of text). Reading
#: takes about ten times the file's size in memory while the text is parsed (measured: 45 MB
#: file, 460 MB), so the limit keeps a mistaken file (a whole day of data, a binary) from
#: exhausting a laptop. Raise it with ``max_bytes=`` or the environment variable
#: ``ROCKING_MAX_RECORD_MB``.
MAX_RECORD_BYTES = 50_000_000
#: Environment variable that replaces :data:`MAX_RECORD_BYTES`, in MB (10⁶ bytes).
RECORD_LIMIT_ENV = "ROCKING_MAX_RECORD_MB"

_RECORDS_DIR = Path(__file__).resolve().parent.parent / "data" / "records"

# Canonical unit name -> factor to m/s². Spellings are reduced by _canonical_units.
_UNIT_FACTORS = {
    "g": STANDARD_GRAVITY,
    "cm/s2": 0.01,
    "m/s2": 1.0,
    "mm/s2": 0.001,
}
_UNIT_ALIASES = {"gal": "cm/s2", "gals": "cm/s2"}

_FORMATS = {
    "peer": "peer",
    "at2": "peer",
    "peer-at2": "peer",
    "esm": "esm",
    "itaca": "esm",
    "asc": "esm",
    "two-column": "two-column",
    "two_column": "two-column",
    "2col": "two-column",
    "2-column": "two-column",
    "columns": "two-column",
}

# PEER AT2 header: "NPTS=   7995, DT=   .0050 SEC," (values captured raw so that a bad
# one can be reported verbatim), or the pre-NGA layout "  4000   .0050   NPTS, DT".
_NPTS_RE = re.compile(r"NPTS\s*=\s*([^\s,]*)\s*,?\s*DT\s*=\s*([^\s,]*)", re.IGNORECASE)
_NPTS_OLD_RE = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,\s*DT", re.IGNORECASE)
_UNITS_OF_RE = re.compile(r"UNITS\s+OF\s+([^\s,;]+)", re.IGNORECASE)
# Two-column headers: "Accel[g]", "acc (m/s^2)", "Acceleration [cm/s2]", "units: g".
_COLUMN_UNITS_RE = re.compile(r"acc\w*\s*[\[(]\s*([^\])]+?)\s*[\])]", re.IGNORECASE)
_UNITS_KEY_RE = re.compile(r"\bunits?\s*[:=]\s*([^\s,;]+)", re.IGNORECASE)
# ESM keys are upper case: EVENT_NAME, VS30_M/S, PGA_CM/S^2, LATE/NORMAL_TRIGGERED ...
_ESM_KEY_RE = re.compile(r"^([A-Z][A-Z0-9_/^.\-]*):\s?(.*)$")
_SPLIT_RE = re.compile(r"[\s,;]+")

_PEER_HEADER_SEARCH = 10  # lines scanned for NPTS; the standard puts it on line 4


class RecordError(ValueError):
    """A record file that cannot be read; the message names the file and the line.

    Attributes
    ----------
    path : pathlib.Path
        The file.
    line : int or None
        1-based line number of the problem, when there is one.
    reason : str
        The message without its ``<path>: line <n>:`` prefix.
    """

    def __init__(self, path: os.PathLike[str] | str, line: int | None, message: str):
        self.path = Path(path)
        self.line = line
        self.reason = message
        where = f"{path}: line {line}" if line is not None else f"{path}"
        super().__init__(f"{where}: {message}")


class UnitsConflictError(RecordError):
    """``units`` given by the caller contradict the units the file's header states.

    Raised unless ``units_override=True``: a header that says cm/s² read as g gives a
    PGA 981 times too large, so neither may win silently.

    Attributes
    ----------
    header_units : str
        The units as the header spells them (e.g. ``"cm/s^2"``).
    given_units : str
        The units the caller gave (e.g. ``"g"``).
    """

    def __init__(
        self,
        path: os.PathLike[str] | str,
        line: int | None,
        header_units: str,
        given_units: str,
        way_out: str = (
            "omit units to use the header's, or pass units_override=True if the header is wrong"
        ),
    ):
        self.header_units = header_units
        self.given_units = given_units
        super().__init__(
            path,
            line,
            f"the header states the units {header_units!r}, but units={given_units!r} was "
            f"given; {way_out}",
        )


# --------------------------------------------------------------------------- units
def _canonical_units(units: str) -> str | None:
    """Reduce a unit spelling ("CM/SEC/SEC", "m/s²", "Gal") to a key of _UNIT_FACTORS."""
    s = units.strip().lower().replace(" ", "").rstrip(".,;")
    s = s.replace("²", "2").replace("^2", "2").replace("**2", "2")
    s = s.replace("/sec/sec", "/s2").replace("/s/s", "/s2").replace("/sec2", "/s2")
    s = _UNIT_ALIASES.get(s, s)
    return s if s in _UNIT_FACTORS else None


def units_to_si(
    units: str, path: os.PathLike[str] | str = "<units>", line: int | None = None
) -> float:
    """Factor that converts acceleration in ``units`` to m/s².

    Parameters
    ----------
    units : str
        One of g, cm/s2 (cm/s^2, cm/s², gal), m/s2 (m/s^2, m/s²), mm/s2; any case.
    path, line
        Where the units came from, for the error message.

    Raises
    ------
    RecordError
        If the units are not recognised (a ``ValueError``).
    """
    canonical = _canonical_units(units)
    if canonical is None:
        raise RecordError(
            path,
            line,
            f"unknown acceleration units {units!r}; use one of g, cm/s2 (gal), m/s2, mm/s2",
        )
    return _UNIT_FACTORS[canonical]


# ------------------------------------------------------------------------- parsing
def _read_lines(path: Path) -> list[str]:
    """File lines without terminators; CRLF, CR and LF all end a line."""
    text = path.read_bytes().decode("utf-8", errors="replace")
    # str.splitlines would also split on \x0b, \x1c, \u2028…, shifting line numbers.
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return lines


def _to_float(token: str, path: Path, line: int) -> float:
    """Parse one number; Fortran ``D`` exponents are accepted, NaN/inf are not."""
    if "_" in token:  # Python's float() accepts "1_000"; no record format does
        raise RecordError(path, line, f"cannot parse {token!r} as a number")
    try:
        x = float(token)
    except ValueError:
        try:
            x = float(token.upper().replace("D", "E"))  # Fortran double: 1.0D-03
        except ValueError:
            raise RecordError(path, line, f"cannot parse {token!r} as a number") from None
    if not math.isfinite(x):
        raise RecordError(path, line, f"value {token!r} is not finite")
    return x


def _read_values(
    lines: list[str], first: int, path: Path, expected: int, key: str, key_line: int
) -> np.ndarray:
    """Read whitespace-separated values from ``lines[first:]`` and check their count.

    ``key``/``key_line`` name the header field that announced ``expected`` values.
    """
    out: list[float] = []
    last_line = first  # 1-based number of the last line holding a value
    for idx in range(first, len(lines)):
        tokens = lines[idx].split()
        if not tokens:
            continue
        for tok in tokens:
            out.append(_to_float(tok, path, idx + 1))
        last_line = idx + 1
        if len(out) > expected:
            raise RecordError(
                path,
                idx + 1,
                f"value #{expected + 1} found, but the header says {key}={expected} "
                f"(line {key_line})",
            )
    if len(out) != expected:
        raise RecordError(
            path,
            last_line,
            f"data end after {len(out)} values, but the header says {key}={expected} "
            f"(line {key_line})",
        )
    return np.asarray(out, dtype=float)


def _header_int(raw: str, path: Path, line: int, key: str) -> int:
    try:
        if "_" in raw:  # int() reads "1_0" as 10
            raise ValueError
        n = int(raw)
    except ValueError:
        msg = f"malformed header: {key} = {raw!r} is not an integer"
        raise RecordError(path, line, msg) from None
    if n < 2:
        raise RecordError(path, line, f"malformed header: {key} = {n}; a record needs >= 2 points")
    return n


def _header_dt(raw: str, path: Path, line: int, key: str) -> float:
    try:
        if "_" in raw:  # float() reads "0.0_1" as 0.01
            raise ValueError
        dt = float(raw)
    except ValueError:
        msg = f"malformed header: {key} = {raw!r} is not a number"
        raise RecordError(path, line, msg) from None
    if not (math.isfinite(dt) and dt > 0.0):
        raise RecordError(path, line, f"malformed header: {key} = {raw!r} must be positive")
    return dt


def _require_acceleration(text: str, path: Path, line: int) -> None:
    if re.search(r"VELOCITY|DISPLACEMENT", text, re.I) and not re.search(r"ACCEL", text, re.I):
        raise RecordError(
            path, line, "this is a velocity or displacement record, not an acceleration"
        )


def _parse_peer(lines: list[str], path: Path) -> dict[str, Any]:
    """PEER AT2 -> raw values, dt, header units (+ line) and metadata."""
    for idx, line in enumerate(lines[:_PEER_HEADER_SEARCH]):
        if "NPTS" in line.upper():
            break
    else:
        raise RecordError(
            path,
            None,
            f"no 'NPTS= n, DT= x' line in the first {_PEER_HEADER_SEARCH} lines "
            "(PEER AT2 files have it on line 4)",
        )
    npts_line = idx + 1
    m = _NPTS_RE.search(lines[idx]) or _NPTS_OLD_RE.search(lines[idx])
    if m is None:
        raise RecordError(
            path,
            npts_line,
            f"malformed header: expected 'NPTS= n, DT= x', got {lines[idx].strip()!r}",
        )
    npts = _header_int(m.group(1), path, npts_line, "NPTS")
    dt = _header_dt(m.group(2), path, npts_line, "DT")
    header = lines[:npts_line]
    _require_acceleration(" ".join(header), path, npts_line)

    header_units, units_line = None, None
    for j, line in enumerate(header):
        um = _UNITS_OF_RE.search(line)
        if um:
            header_units, units_line = um.group(1).rstrip(".,;"), j + 1
            break
    values = _read_values(lines, npts_line, path, npts, "NPTS", npts_line)
    meta = {
        "format": "peer",
        "npts": npts,
        "dt": dt,
        # the event is line 2 of a full header; a header of a title and the NPTS line has none
        "event": header[1].strip() if len(header) > 2 else "",
        "header": tuple(h.rstrip() for h in header),
    }
    return {
        "values": values,
        "dt": dt,
        "units": header_units,
        "units_line": units_line,
        "meta": meta,
    }


def _parse_esm(lines: list[str], path: Path) -> dict[str, Any]:
    """ESM/ITACA ASCII -> raw values, dt, header units (+ line) and metadata."""
    fields: dict[str, str] = {}
    where: dict[str, int] = {}
    first_data = len(lines)
    for idx, line in enumerate(lines):
        m = _ESM_KEY_RE.match(line)
        if m is None:
            first_data = idx
            break
        fields[m.group(1)] = m.group(2).strip()
        where[m.group(1)] = idx + 1
    if first_data == 0 and lines:
        # not one "KEY: value" line: say what line 1 is rather than "lines 1-0"
        raise RecordError(
            path,
            1,
            f"not an ESM ASCII file: the header must start with 'KEY: value' lines "
            f"(EVENT_NAME: ..., NDATA: ...), got {lines[0].strip()[:60]!r}",
        )
    end = first_data + 1  # the first line after the header, for "missing field" errors
    missing = [k for k in ("NDATA", "SAMPLING_INTERVAL_S") if not fields.get(k)]
    if missing:
        raise RecordError(
            path,
            end,
            f"missing header field(s) {', '.join(missing)} in the ESM header "
            f"(lines 1-{first_data})",
        )
    if "DATA_TYPE" in fields:
        _require_acceleration(fields["DATA_TYPE"], path, where["DATA_TYPE"])
    npts = _header_int(fields["NDATA"], path, where["NDATA"], "NDATA")
    key = "SAMPLING_INTERVAL_S"
    dt = _header_dt(fields[key], path, where[key], key)
    values = _read_values(lines, first_data, path, npts, "NDATA", where["NDATA"])
    meta = {
        "format": "esm",
        "npts": npts,
        "dt": dt,
        "event": fields.get("EVENT_NAME", ""),
        "station": fields.get("STATION_CODE", ""),
        "component": fields.get("STREAM", ""),
        "license": fields.get("DATA_LICENSE", ""),
        "citation": fields.get("DATA_CITATION", ""),
        "header": fields,
    }
    return {
        "values": values,
        "dt": dt,
        "units": fields.get("UNITS") or None,
        "units_line": where.get("UNITS"),
        "meta": meta,
    }


def _starts_with_number(line: str) -> bool:
    tokens = _SPLIT_RE.split(line.strip(), maxsplit=1)
    if not tokens or not tokens[0]:
        return False
    try:
        float(tokens[0])
    except ValueError:
        return False
    return True


def _parse_two_column(lines: list[str], path: Path) -> dict[str, Any]:
    """Header lines, then ``time accel`` rows -> time, raw values, header units."""
    # The header is every line before the first one that starts with a number; from
    # then on every non-blank, non-comment line must be a row, so a garbled row is
    # reported instead of being silently taken for header text.
    first = next((i for i, ln in enumerate(lines) if _starts_with_number(ln)), None)
    if first is None:
        raise RecordError(path, None, "no 'time accel' data rows found")
    header = lines[:first]
    times: list[float] = []
    accel: list[float] = []
    row_lines: list[int] = []
    for idx in range(first, len(lines)):
        stripped = lines[idx].strip()
        if not stripped or stripped[0] in "#%":
            continue
        tokens = _SPLIT_RE.split(stripped)
        if len(tokens) != 2:
            raise RecordError(
                path,
                idx + 1,
                f"expected 2 numbers (time, acceleration), found {len(tokens)}: {stripped!r}",
            )
        times.append(_to_float(tokens[0], path, idx + 1))
        accel.append(_to_float(tokens[1], path, idx + 1))
        row_lines.append(idx + 1)
    if len(times) < 2:
        line = row_lines[-1] if row_lines else first + 1
        raise RecordError(path, line, "need at least 2 data rows")
    time = np.asarray(times)
    bad = np.flatnonzero(np.diff(time) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise RecordError(
            path,
            row_lines[i],
            f"time {times[i]!r} is not greater than the previous time {times[i - 1]!r} "
            f"(line {row_lines[i - 1]}); times must be strictly increasing",
        )
    header_units, units_line = None, None
    for j, line in enumerate(header):
        um = (
            _COLUMN_UNITS_RE.search(line)
            or _UNITS_OF_RE.search(line)
            or _UNITS_KEY_RE.search(line)
        )
        if um:
            header_units, units_line = um.group(1), j + 1
            break
    dt = float(f"{np.median(np.diff(time)):.12g}")  # same convention as GroundMotion.dt
    meta = {"format": "two-column", "npts": time.size, "dt": dt, "header": tuple(header)}
    return {
        "time": time,
        "values": np.asarray(accel),
        "dt": dt,
        "units": header_units,
        "units_line": units_line,
        "meta": meta,
    }


def _detect_format(lines: list[str], path: Path) -> str:
    """Guess the format from the extension and the first lines."""
    if path.suffix.lower() == ".at2":
        return "peer"
    first = next((ln for ln in lines if ln.strip()), "")
    if _ESM_KEY_RE.match(first):
        return "esm"
    if any("NPTS" in ln.upper() for ln in lines[:_PEER_HEADER_SEARCH]):
        return "peer"
    if any(_starts_with_number(ln) for ln in lines):
        return "two-column"
    raise RecordError(
        path,
        None,
        "cannot recognise the format (PEER AT2, ESM ASCII or two-column text); pass format=",
    )


_PARSERS = {"peer": _parse_peer, "esm": _parse_esm, "two-column": _parse_two_column}


# ---------------------------------------------------------------------- public API
def read_record(
    path: os.PathLike[str] | str,
    *,
    format: str | None = None,
    units: str | None = None,
    units_override: bool = False,
    max_bytes: int | None = None,
) -> GroundMotion:
    """Read an accelerogram file into a :class:`GroundMotion` (m/s²).

    Parameters
    ----------
    path : path-like or str
        A file, or the stem of a bundled record (see :func:`bundled_records`).
    format : {"peer", "esm", "two-column"}, optional
        File format (aliases: "at2", "itaca", "2col"); detected when omitted.
    units : str, optional
        Units of the stored values: g, cm/s2 (cm/s^2, cm/s², gal), m/s2 (m/s^2, m/s²)
        or mm/s2, any case. Required when the file does not state its units; when it
        does, they must agree with the header's (same units, any spelling) unless
        ``units_override`` is set.
    units_override : bool
        Use ``units`` even though the header states other units (for a file whose
        header is known to be wrong). Needs ``units``.
    max_bytes : int, optional
        Largest file accepted, bytes; default :func:`record_size_limit` (50 MB, or
        ``ROCKING_MAX_RECORD_MB``). A larger file is refused before it is read.

    Returns
    -------
    GroundMotion
        Time from 0 (s) for PEER and ESM files, the file's time column otherwise;
        values converted with g = 9.80665 m/s². ``units`` holds the stored units and
        ``meta`` the header, the header ``dt`` (s) and point count, ``header_units``
        and ``units_override``.

    Raises
    ------
    UnitsConflictError
        ``units`` that contradict the header's, without ``units_override`` (a
        :class:`RecordError`).
    RecordError
        For any problem in the file, the message naming the file and the line; or a
        file larger than ``max_bytes``, the message naming its size and the limit.
    ValueError
        For an unknown ``format`` or ``units`` argument, or ``units_override``
        without ``units``.
    """
    if units_override and units is None:
        raise ValueError("units_override=True needs units= (the units that replace the header's)")
    file = resolve_record(path)
    _check_size(file, record_size_limit() if max_bytes is None else int(max_bytes))
    lines = _read_lines(file)
    if not any(line.strip() for line in lines):
        raise RecordError(file, None, "the file is empty")
    if format is None:
        fmt = _detect_format(lines, file)
        parsed = _PARSERS[fmt](lines, file)
    else:
        fmt = _FORMATS.get(format.strip().lower())
        if fmt is None:
            known = sorted(set(_FORMATS.values()))
            raise ValueError(f"unknown record format {format!r}; use one of {known}")
        try:
            parsed = _PARSERS[fmt](lines, file)
        except RecordError as exc:
            raise _with_format_hint(exc, fmt, lines, file) from None

    header_units, units_line = parsed["units"], parsed["units_line"]
    if units is not None:
        factor = units_to_si(units, file)  # ValueError naming the value and the file
        stored = _canonical_units(units)
        header = _canonical_units(header_units) if header_units is not None else None
        # a header whose units are not recognised cannot be contradicted: the caller's
        # units are then the only ones there are
        if header is not None and header != stored and not units_override:
            raise UnitsConflictError(file, units_line, header_units, units)
    elif header_units is not None:
        factor = units_to_si(header_units, file, units_line)
        stored = _canonical_units(header_units)
    else:
        raise RecordError(
            file,
            None,
            "the file does not state its units; pass units='g' (or 'cm/s2', 'm/s2', 'mm/s2')",
        )
    meta = dict(parsed["meta"])
    meta["header_units"] = header_units
    meta["units_override"] = bool(units_override and units is not None)

    with np.errstate(over="ignore", invalid="ignore"):  # overflow is reported below
        values = parsed["values"] * factor
        time = parsed.get("time")
        if time is None:
            # i*dt in one multiplication: no accumulated round-off over long records
            time = np.arange(values.size) * parsed["dt"]
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        raw = float(parsed["values"][bad[0]])
        raise RecordError(
            file, None, f"value #{bad[0] + 1} ({raw!r} {stored}) overflows when converted to m/s²"
        )
    if not np.all(np.isfinite(time)):
        raise RecordError(file, None, f"the times overflow: {values.size} points at dt = {parsed['dt']!r} s")
    try:
        return GroundMotion(
            time=time, values=values, name=file.stem, source=str(file), units=stored, meta=meta
        )
    except ValueError as exc:
        # GroundMotion's own checks; the ones above should already have caught anything a
        # file can hold, but whatever is left is still a problem of this file
        raise RecordError(file, None, " ".join(str(exc).split())) from None


_FORMAT_NAMES = {"peer": "a PEER AT2", "esm": "an ESM ASCII", "two-column": "a two-column text"}


def _with_format_hint(exc: RecordError, forced: str, lines: list[str], file: Path) -> RecordError:
    """``exc`` from the reader of a format the caller forced, plus what the file looks like
    when that is another format (``info --format esm`` on an AT2 file)."""
    try:
        detected = _detect_format(lines, file)
    except RecordError:
        return exc
    if detected == forced:
        return exc
    hint = (
        f" (format {forced!r} was asked for, but the file looks like {_FORMAT_NAMES[detected]} "
        "file: omit the format to detect it)"
    )
    return RecordError(file, exc.line, exc.reason + hint)


def record_size_limit() -> int:
    """The largest record file :func:`read_record` reads, bytes: ``ROCKING_MAX_RECORD_MB`` (MB) if
    set, else :data:`MAX_RECORD_BYTES`.

    Raises
    ------
    ValueError
        If the environment variable is not a positive number.
    """
    raw = os.environ.get(RECORD_LIMIT_ENV, "").strip()
    if not raw:
        return MAX_RECORD_BYTES
    try:
        mb = float(raw)
    except ValueError:
        mb = math.nan
    if not (math.isfinite(mb) and mb > 0):
        raise ValueError(f"{RECORD_LIMIT_ENV} must be a positive number of MB, got {raw!r}")
    return int(mb * 1_000_000)


def _check_size(file: Path, limit: int) -> None:
    """Refuse a file over ``limit`` bytes before reading it (reading takes ~10× its size)."""
    try:
        size = file.stat().st_size
    except OSError:
        return  # the read that follows reports it
    if size > limit:
        mb = size / 1_000_000
        memory = f"{10 * mb / 1000:.2g} GB" if 10 * mb >= 1000 else f"{10 * mb:.3g} MB"
        raise RecordError(
            file,
            None,
            f"the file is {mb:.3g} MB, over the {limit / 1_000_000:g} MB limit for a record (reading it would "
            f"take about {memory} of memory); use a shorter or decimated record, or raise the limit with "
            f"the environment variable {RECORD_LIMIT_ENV}={math.ceil(mb)} (max_bytes= in Python)",
        )


def bundled_records() -> dict[str, Path]:
    """The accelerograms shipped with rocking, as {file stem: path}.

    See ``rocking/data/records/README.md`` for provenance, units and licences.
    """
    if not _RECORDS_DIR.is_dir():
        return {}
    return {
        p.stem: p
        for p in sorted(_RECORDS_DIR.iterdir())
        if p.is_file() and p.name != "README.md" and not p.name.startswith(".")
    }


def resolve_record(name_or_path: os.PathLike[str] | str) -> Path:
    """Return the file for an existing path or the stem (or file name) of a bundled record.

    Raises
    ------
    FileNotFoundError
        If it is neither; the message lists close bundled names.
    """
    path = Path(name_or_path).expanduser()
    if path.is_file():
        return path
    records = bundled_records()
    key = str(name_or_path)
    if key in records:
        return records[key]
    by_name = {p.name: p for p in records.values()}
    if key in by_name:
        return by_name[key]
    folded = [stem for stem in records if stem.lower() == key.lower()]
    if len(folded) == 1:
        return records[folded[0]]
    close = difflib.get_close_matches(key, list(records), n=3, cutoff=0.5)
    hint = f" Did you mean {', '.join(close)}?" if close else ""
    raise FileNotFoundError(
        f"{key!r} is neither an existing file nor a bundled record.{hint} "
        f"Bundled records: {', '.join(records)}"
    )
