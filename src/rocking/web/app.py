"""The Flask application: the input form, the run and sweep pages, the files they show.

Build it with :func:`create_app`; serve it with :func:`rocking.web.server.serve` (``rocking serve``).
Every computation runs in a worker process with a time limit (:mod:`rocking.web.jobs`); the request
thread only validates the form, reads an uploaded record to check it, and renders the page.
"""

from __future__ import annotations

import json
import logging
import math
import re
import shutil
import tempfile
import threading
import uuid
import weakref
from collections.abc import Mapping
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from flask import Flask, abort, g, jsonify, redirect, render_template, request, send_from_directory, url_for
from jinja2 import DictLoader
from werkzeug.exceptions import HTTPException, RequestEntityTooLarge
from werkzeug.utils import secure_filename

from .. import __version__
from ..constants import STANDARD_GRAVITY
from ..io.config import ConfigError, load_config
from ..io.records import RecordError, UnitsConflictError, bundled_records, read_record
from ..io.stack_output import fall_text
from ..results.wording import need_text
from . import tasks
from .jobs import DONE, JobRunner
from .templates import TEMPLATES

__all__ = ["DEFAULTS", "FormError", "block_field_names", "create_app", "parse_form", "stack_form_defaults"]

log = logging.getLogger("rocking.web")

#: Settings of :func:`create_app` (override any of them with its ``settings`` argument).
DEFAULTS: dict[str, Any] = {
    "RUN_TIMEOUT": 120.0,  # s, one run (simulation, plots and animation)
    "SWEEP_TIMEOUT": 600.0,  # s, one design sweep with its report
    "MAX_UPLOAD": 5 * 1024 * 1024,  # bytes of an uploaded record
    "MAX_SWEEP_POINTS": 41,  # values of μs in one design sweep (the grid)
    "MAX_BLOCKS": 6,  # blocks of a stack the form offers
    "MAX_DURATION": 600.0,  # s, the longest a run may last (the record and the free motion after it)
    "MAX_SAMPLES": 1_000_000,  # saved samples of one run (simulation.max_samples): ~40 MB, plots included < 0.5 GB
    "MAX_JOBS_PER_CLIENT": 2,  # runs and sweeps at once from one address (at most MAX_WORKERS - 1)
    "MAX_WORKERS": None,  # worker processes at once (default max(4, CPUs))
    "QUEUE_TIMEOUT": 60.0,  # s a job waits for a free worker
    "KEEP_RUNS": 200,  # run and sweep folders kept on disk (oldest removed first)
    "WORK_DIR": None,  # where runs are written (default: a temporary folder, removed at exit)
    "ANIMATION": {"fps": 20, "longest_video": 60.0, "dpi": 80},  # real time up to a minute of motion
    "FIGURE_DPI": 90,
    "ALLOWED_HOSTS": None,  # Host names accepted (None: any); serve() sets the loopback names
    "MP_CONTEXT": "forkserver",
}

_FORM_DEFAULTS = {
    "mode": "statue",
    "stack_blocks": "2",
    "record": "Northridge1994_RinaldiReceivingSta_228",
    "format": "",
    "units": "",
    "scale_kind": "factor",
    "scale_value": "0.4",
    "duration": "",
    "statue_width": "0.3",
    "statue_height": "1.2",
    "statue_mass": "100",
    "statue_restitution": "0.85",
    "statue_mu_s": "0.5",
    "statue_mu_k": "0.4",
    "pedestal": "",
    "pedestal_mass": "50",
    "pedestal_mu_s": "0.3",
    "pedestal_mu_k": "0.22",
    "pedestal_width": "0.6",
    "pedestal_height": "0.4",
    "sweep_from": "0.05",
    "sweep_to": "0.6",
    "sweep_points": "12",
    "sweep_sliding_limit": "",
    "sweep_scatter": "0.2",
}

#: What stands on the floor: the form's two modes.
_MODES = [("statue", "a statue, alone or on a pedestal"), ("stack", "a stack of blocks")]

#: The fields of each block of a stack (block<k>_<field>); friction and restitution are those of
#: the interface under the block.
_BLOCK_FIELDS = ("name", "width", "height", "mass", "offset", "mu_s", "mu_k", "restitution")

#: The stack the form starts with (examples/stack_statue_on_pedestal.toml, and a vase to add, centred:
#: this statue is 0.3 m wide, so the example's 5 cm offset would put the vase flush with its edge).
_STACK_DEFAULTS = (
    {"name": "pedestal", "width": "0.8", "height": "0.5", "mass": "300", "mu_s": "0.3", "mu_k": "0.25"},
    {"name": "statue", "width": "0.3", "height": "1.2", "mass": "100", "mu_s": "0.5", "mu_k": "0.4"},
    {"name": "vase", "width": "0.2", "height": "0.45", "mass": "8", "mu_s": "0.4", "mu_k": "0.32",
     "restitution": "0.7"},
)

#: The longest name of a block the form takes (it heads table rows and the animation's header).
_MAX_NAME = 40


def block_field_names(max_blocks: int) -> list[str]:
    """The form's names of every block field, block1_name … block<max_blocks>_restitution."""
    return [f"block{k}_{f}" for k in range(1, max_blocks + 1) for f in _BLOCK_FIELDS]


def stack_form_defaults(max_blocks: int) -> dict[str, str]:
    """The block fields as the form first shows them."""
    out = dict.fromkeys(block_field_names(max_blocks), "")
    for k, block in enumerate(_STACK_DEFAULTS[:max_blocks], start=1):
        out.update({f"block{k}_{f}": v for f, v in block.items()})
    return out


_FORMATS = [("", "detect"), ("peer", "PEER AT2"), ("esm", "ESM ASCII"), ("two-column", "two-column text")]
_UNITS = [("", "from the file"), ("g", "g"), ("cm/s2", "cm/s² (gal)"), ("m/s2", "m/s²"), ("mm/s2", "mm/s²")]
_SCALE_KINDS = [("factor", "factor ×"), ("pga_g", "target PGA (g)"), ("pga", "target PGA (m/s²)")]

#: Form labels of the configuration fields, for error messages.
_LABELS = {
    "statue.width": "statue width B",
    "statue.height": "statue height H",
    "statue.mass": "statue mass",
    "statue.restitution": "statue restitution r",
    "statue.friction.static": "statue friction μs",
    "statue.friction.kinetic": "statue friction μk",
    "statue.friction": "statue friction",
    "statue": "statue",
    "pedestal.mass": "pedestal mass",
    "pedestal.friction.static": "pedestal floor friction μs",
    "pedestal.friction.kinetic": "pedestal floor friction μk",
    "pedestal.friction": "pedestal floor friction",
    "pedestal.width": "pedestal width",
    "pedestal.height": "pedestal height",
    "pedestal": "pedestal",
    "motion.scale": "scale factor",
    "motion.pga": "target PGA",
    "motion.path": "record",
    "motion.units": "units of the file",
    "motion.format": "file format",
    "motion": "floor motion",
    "simulation.duration": "duration",
}

_RUN_FILES = {"response.png", "response-narrow.png", "energy.png", "energy-narrow.png", "animation.gif", "result.json"}
_SWEEP_FILES = {"report.html", "report.pdf", "sweep.csv", "sweep.png", "sweep-report.zip"}
_ID_RE = re.compile(r"^[0-9a-f]{32}$")


# ------------------------------------------------------------------------- bundled records
def _provenance_table() -> dict[str, dict[str, str]]:
    """Rows of the provenance table of the bundled records' README, by file stem: event, year,
    station and component as the README spells them (empty if the README is missing)."""
    from importlib.resources import files

    try:
        text = files("rocking").joinpath("data/records/README.md").read_text(encoding="utf-8")
    except (FileNotFoundError, OSError):
        return {}
    rows: dict[str, dict[str, str]] = {}
    header: list[str] | None = None
    for line in text.splitlines():
        if not line.startswith("|"):
            header = None if not line.strip() else header
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if header is None:
            header = [c.lower() for c in cells]
            continue
        if set(cells[0]) <= set("-: ") or "file" not in header:
            continue
        row = dict(zip(header, cells))
        rows[Path(row["file"]).stem] = row
    return rows


def _event(text: str) -> str:
    """The event of a README cell, without the magnitude or country after a comma."""
    return re.sub(r"\s*\[[a-z]\]", "", text).split(",")[0].strip()


def _station(text: str) -> str:
    """The station of a README cell: its name, not the network code or the footnote mark."""
    parts = [p.strip() for p in re.sub(r"\s*\[[a-z]\]", "", text).split(",")]
    named = [p for p in parts if p and not p.startswith("network")]
    return named[-1] if named else ""


def record_choices(records: Mapping[str, Path]) -> list[dict[str, Any]]:
    """The bundled records as the form's dropdown shows them: ``name`` (the value sent),
    ``label`` ("Northridge-01 1994 · Rinaldi Receiving Sta 228 · PGA 0.87 g") and ``pga_g``
    (the record's PGA, g), sorted by label. A record the README does not describe shows its
    name; one that cannot be read shows no PGA."""
    table = _provenance_table()
    choices = []
    for name, path in records.items():
        try:
            pga_g = float(read_record(path).pga) / STANDARD_GRAVITY
        except (RecordError, ValueError, OSError):
            pga_g = None
        row = table.get(name)
        if row:
            station = " ".join(filter(None, (_station(row.get("station", "")), row.get("comp.", "").split(" ")[0])))
            text = f"{_event(row.get('event', name))} {row.get('year', '')} · {station}".strip()
        else:
            text = name
        label = f"{text} · PGA {pga_g:.2f} g" if pga_g is not None else text
        choices.append({"name": name, "label": label, "pga_g": pga_g, "short": text})
    return sorted(choices, key=lambda c: c["label"].lower())


class FormError(ValueError):
    """A problem with the form's values; the message is shown on the page as is."""


class LimitError(FormError):
    """A request over this server's limits (duration, saved samples); shown on the page as is."""


def check_limits(config: Any, max_duration: float, max_samples: int) -> None:
    """Refuse a run longer than ``max_duration`` (s) or saving more than ``max_samples`` samples,
    before any worker starts.

    Parameters
    ----------
    config : rocking.io.config.Config
        The validated run.

    Raises
    ------
    LimitError
        Naming the form's field (duration, or the record) and the limit.
    """
    from ..io.output import planned_samples

    _, motion, options, duration = config.to_specs()
    if duration is not None:
        t_end, what = float(duration), "duration"
        if t_end > max_duration:
            raise LimitError(f"duration: at most {max_duration:g} s on this server, got {t_end:g} s")
    else:
        t_end = float(motion.duration) + float(options.free_time_limit)
        if t_end > max_duration:
            raise LimitError(
                f"record: {getattr(motion, 'name', 'the motion')} lasts {float(motion.duration):g} s, and with up to "
                f"{float(options.free_time_limit):g} s of motion after it the run could last {t_end:g} s, over this "
                f"server's limit of {max_duration:g} s; enter a duration of at most {max_duration:g} s"
            )
        what = "the record's length"
    n = planned_samples(motion, options, duration)
    save_dt = options.save_dt or getattr(motion, "dt", None) or 0.01
    if n > max_samples:
        raise LimitError(
            f"duration: the run would save {n:.3g} samples (one every {save_dt:g} s over "
            f"{what}, {t_end:g} s), over this server's limit of {max_samples:.3g}; enter a shorter duration"
        )


class _Clients:
    """Runs and sweeps in progress per client address, so that one client cannot take every worker.

    Behind a reverse proxy every request comes from the proxy's address: all its users then
    share one quota (the app does not trust ``X-Forwarded-For``, which any client can forge).
    """

    def __init__(self, limit: int):
        self.limit = max(1, int(limit))
        self._lock = threading.Lock()
        self._active: dict[str, int] = {}

    def claim(self, client: str) -> bool:
        """Count one more job for ``client``; False (and nothing counted) if it is at its limit."""
        with self._lock:
            n = self._active.get(client, 0)
            if n >= self.limit:
                return False
            self._active[client] = n + 1
            return True

    def release(self, client: str) -> None:
        with self._lock:
            n = self._active.get(client, 0) - 1
            if n > 0:
                self._active[client] = n
            else:
                self._active.pop(client, None)

    def active(self, client: str) -> int:
        with self._lock:
            return self._active.get(client, 0)


# ----------------------------------------------------------------------------------- the form
def _text(form: Mapping[str, Any], name: str) -> str:
    return str(form.get(name, "") or "").strip()


def _number(form: Mapping[str, Any], name: str, label: str, problems: list[str], *, required: bool) -> float | None:
    raw = _text(form, name)
    if not raw:
        if required:
            problems.append(f"{label}: required")
        return None
    try:
        value = float(raw.replace(",", ".")) if raw.count(",") == 1 and "." not in raw else float(raw)
    except ValueError:
        problems.append(f"{label}: enter a number, got {raw!r}")
        return None
    if not math.isfinite(value):
        problems.append(f"{label}: must be a finite number, got {raw!r}")
        return None
    return value


def _friction(form: Mapping[str, Any], prefix: str, label: str, problems: list[str], *, required: bool):
    mu_s = _number(form, f"{prefix}_mu_s", f"{label} μs", problems, required=required)
    mu_k = _number(form, f"{prefix}_mu_k", f"{label} μk", problems, required=False)
    if mu_s is None:
        if mu_k is not None:
            problems.append(f"{label} μk: give μs too")
        return None
    out: dict[str, float] = {"static": mu_s}
    if mu_k is not None:
        out["kinetic"] = mu_k
    return out


def parse_form(form: Mapping[str, Any], record_path: str | None = None, *, max_blocks: int = 6) -> dict[str, Any]:
    """The run configuration (a dict for :func:`rocking.io.config.load_config`) of the form: a
    statue (alone or on a pedestal), or with ``mode = "stack"`` a stack of blocks.

    Parameters
    ----------
    form : mapping
        The submitted fields (see ``_FORM_DEFAULTS`` and :func:`block_field_names` for the names).
    record_path : str, optional
        An uploaded record saved on disk; replaces the bundled record of the form.
    max_blocks : int
        The most blocks a stack may have.

    Raises
    ------
    FormError
        One line naming every field that is missing or not a number.
    """
    problems: list[str] = []
    mode = _text(form, "mode") or "statue"
    if mode not in {m for m, _ in _MODES}:
        problems.append(f"mode: unknown choice {mode!r}")
        cfg: dict[str, Any] = {}
    elif mode == "stack":
        cfg = _parse_stack(form, problems, max_blocks)
    else:
        cfg = _parse_statue(form, problems)
    cfg.update(_parse_motion(form, record_path, problems))
    if problems:
        raise FormError("; ".join(problems))
    return cfg


def _parse_stack(form: Mapping[str, Any], problems: list[str], max_blocks: int) -> dict[str, Any]:
    """``blocks`` and ``interfaces`` of the form's stack (the interface under each block)."""
    raw = _text(form, "stack_blocks")
    if not raw.isdigit() or not 1 <= int(raw) <= max_blocks:
        problems.append(f"number of blocks: must be a whole number from 1 to {max_blocks}, got {raw!r}")
        return {}
    blocks, interfaces = [], []
    for k in range(1, int(raw) + 1):
        prefix, label = f"block{k}", f"block {k}"
        block: dict[str, Any] = {}
        name = _text(form, f"{prefix}_name")
        if len(name) > _MAX_NAME:
            problems.append(f"{label} name: at most {_MAX_NAME} characters, got {len(name)}")
        elif name:
            block["name"] = name
        for key in ("width", "height", "mass"):
            block[key] = _number(form, f"{prefix}_{key}", f"{label} {key}", problems, required=True)
        offset = _number(form, f"{prefix}_offset", f"{label} offset", problems, required=False)
        if offset is not None:
            block["offset"] = offset
        interface: dict[str, Any] = {}
        friction = _friction(form, prefix, f"{label} friction", problems, required=False)
        if friction is not None:
            interface["friction"] = friction
        r = _number(form, f"{prefix}_restitution", f"{label} restitution r", problems, required=False)
        if r is not None:
            interface["restitution"] = r
        blocks.append(block)
        interfaces.append(interface)
    return {"blocks": blocks, "interfaces": interfaces}


def _parse_statue(form: Mapping[str, Any], problems: list[str]) -> dict[str, Any]:
    """``statue`` (and ``pedestal`` when its box is ticked) of the form."""
    statue: dict[str, Any] = {}
    for key, label in (("width", "statue width B"), ("height", "statue height H"), ("mass", "statue mass")):
        statue[key] = _number(form, f"statue_{key}", label, problems, required=True)
    r = _number(form, "statue_restitution", "statue restitution r", problems, required=False)
    if r is not None:
        statue["restitution"] = r
    fr = _friction(form, "statue", "statue friction", problems, required=False)
    if fr is not None:
        statue["friction"] = fr
    cfg: dict[str, Any] = {"statue": statue}

    if _text(form, "pedestal"):
        ped: dict[str, Any] = {"mass": _number(form, "pedestal_mass", "pedestal mass", problems, required=True)}
        ped["friction"] = _friction(form, "pedestal", "pedestal floor friction", problems, required=True)
        for key in ("width", "height"):
            v = _number(form, f"pedestal_{key}", f"pedestal {key}", problems, required=False)
            if v is not None:
                ped[key] = v
        cfg["pedestal"] = ped
    return cfg


def _parse_motion(form: Mapping[str, Any], record_path: str | None, problems: list[str]) -> dict[str, Any]:
    """``motion`` (and ``simulation`` with a duration) of the form."""
    cfg: dict[str, Any] = {}
    motion: dict[str, Any] = {"kind": "record"}
    if record_path is not None:
        motion["path"] = record_path
    else:
        name = _text(form, "record")
        if not name:
            problems.append("record: choose a bundled record or upload a file")
        elif name not in bundled_records():
            problems.append(f"record: {name!r} is not a bundled record")
        motion["path"] = name
    kind = _text(form, "scale_kind") or "factor"
    value = _number(form, "scale_value", "scale value", problems, required=False)
    if kind not in {k for k, _ in _SCALE_KINDS}:
        problems.append(f"scale by: unknown choice {kind!r}")
    elif value is not None:
        if kind == "factor":
            motion["scale"] = value
        elif kind == "pga_g":
            motion["pga"] = value * STANDARD_GRAVITY  # the unit g, as the record readers use it
        else:
            motion["pga"] = value
    for key, choices in (("units", _UNITS), ("format", _FORMATS)):
        v = _text(form, key)
        if v and v not in {c for c, _ in choices}:
            problems.append(f"{key}: unknown choice {v!r}")
        elif v:
            motion[key] = v
    cfg["motion"] = motion
    duration = _number(form, "duration", "duration", problems, required=False)
    if duration is not None:
        cfg["simulation"] = {"duration": duration}
    return cfg


def parse_sweep(form: Mapping[str, Any], max_points: int) -> tuple[list[float], float | None]:
    """The pedestal frictions μs of the design sweep (evenly spaced, both ends included) and the
    largest acceptable sliding of the pedestal (m, or None)."""
    problems: list[str] = []
    limit_mm = _number(form, "sweep_sliding_limit", "sweep sliding limit", problems, required=False)
    if limit_mm is not None and not limit_mm > 0:
        problems.append(f"sweep sliding limit: must be > 0 mm, got {limit_mm:g}")
    lo = _number(form, "sweep_from", "sweep μs from", problems, required=True)
    hi = _number(form, "sweep_to", "sweep μs to", problems, required=True)
    raw = _text(form, "sweep_points")
    n = None
    if not raw:
        problems.append("sweep values: required")
    elif not raw.isdigit():
        problems.append(f"sweep values: enter a whole number, got {raw!r}")
    else:
        n = int(raw)
        if not 2 <= n <= max_points:
            problems.append(f"sweep values: must be between 2 and {max_points}, got {n}")
    if lo is not None and lo < 0:
        problems.append(f"sweep μs from: must be >= 0, got {lo:g}")
    if lo is not None and hi is not None and not hi > lo:
        problems.append(f"sweep μs to: must be greater than μs from ({lo:g}), got {hi:g}")
    if problems:
        raise FormError("; ".join(problems))
    return [lo + (hi - lo) * i / (n - 1) for i in range(n)], (None if limit_mm is None else limit_mm / 1000.0)


def _units_conflict_message(exc: UnitsConflictError) -> str:
    """The units selector contradicts the file's header. The page offers no override: the
    selector is for files that do not state their units, and a wrong header is fixed in the file."""
    chosen = dict(_UNITS).get(exc.given_units, exc.given_units)
    line = f" (line {exc.line})" if exc.line is not None else ""
    uploaded = exc.path not in set(bundled_records().values())
    fix = " (if the header is wrong, correct it and upload the file again)" if uploaded else ""
    return (
        f"units of the file: {exc.path.name} states its units as {exc.header_units!r}{line}, not {chosen}; "
        f"choose \u201cfrom the file\u201d{fix}"
    )


def parse_scatter(form: Mapping[str, Any]) -> float | None:
    """The relative scatter s of the pedestal's floor friction for the design sweep (each value also
    runs at μs·(1 ± s)); None (the design's default) if the field is empty."""
    problems: list[str] = []
    s = _number(form, "sweep_scatter", "friction scatter", problems, required=False)
    if s is not None and not 0 <= s < 1:
        problems.append(f"friction scatter: must be >= 0 and < 1 (relative to μs), got {s:g}")
    if problems:
        raise FormError("; ".join(problems))
    return s


def _missing_units_message(exc: RecordError) -> str:
    """The reader asks for a keyword argument; the page has a selector for it."""
    return (f"{exc.path.name}: the file does not state its units; choose them in the form's "
            "\u201cunits of the file\u201d selector (g, cm/s\u00b2 (gal), m/s\u00b2 or mm/s\u00b2) and run again")


#: Bytes other than tab, line feed, form feed and carriage return below 0x20: none in a text record.
_CONTROL_BYTES = bytes(set(range(32)) - {9, 10, 12, 13}) + b"\x7f"


def looks_binary(path: Path, probe: int = 65536) -> bool:
    """True for a file that is not text: a NUL byte, or more than 1 % control characters, in its
    first ``probe`` bytes (a spreadsheet, a picture, a compressed archive...)."""
    with open(path, "rb") as fh:
        head = fh.read(probe)
    if b"\x00" in head:
        return True
    return len(head) > 0 and sum(head.count(bytes([c])) for c in _CONTROL_BYTES) > 0.01 * len(head)


#: The words of a stack's interface fields on the form (the friction under block k is block k's).
_INTERFACE_WORDS = {"friction.static": "friction μs", "friction.kinetic": "friction μk", "friction": "friction",
                    "restitution": "restitution r"}


def _stack_label(field: str) -> str | None:
    """The form's label of a stack's configuration field: blocks[1].width → "block 2 width",
    interfaces[0].friction.static → "block 1 friction μs"; None for another field."""
    m = re.fullmatch(r"(blocks|interfaces)\[(\d+)\](?:\.(.+))?", field)
    if m is None:
        return None
    k = int(m.group(2)) + 1
    rest = m.group(3) or ""
    if m.group(1) == "blocks":
        return f"block {k} {rest}".strip()
    return f"block {k} {_INTERFACE_WORDS.get(rest, rest)}".strip()


def _block_words(message: str) -> str:
    """A configuration message's blocks[i] in the form's words, block i+1."""
    return re.sub(r"\bblocks\[(\d+)\]", lambda m: f"block {int(m.group(1)) + 1}", message)


def _config_message(exc: ConfigError, hide: str | None) -> str:
    parts = []
    for fld, msg in exc.problems:
        label = _stack_label(fld or "") or _LABELS.get(fld or "", fld)
        msg = _block_words(msg)
        parts.append(f"{label}: {msg}" if label else msg)
    return _hide_path(" ".join("; ".join(parts).split()), hide)


def _hide_path(message: str, folder: str | None) -> str:
    """Show an uploaded file by its name, not by the server's temporary folder."""
    if folder:
        message = message.replace(folder.rstrip("/") + "/", "")
    return message


# ---------------------------------------------------------------------------- the summary
def _t(x: Any) -> str:
    return "—" if x is None else f"{x:.3f} s"


def _num(x: Any, fmt: str = ".4g") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    return format(x, fmt)


def summary_rows(s: Mapping[str, Any]) -> list[tuple[str, str, str, str]]:
    """(id, label, text, JSON value) of each summary number shown on the result page."""
    ratio = s.get("peak_rotation_over_alpha")
    rows = [
        ("overturned", "overturned", f"yes, at {_t(s['overturn_time'])}" if s["overturned"] else "no"),
        ("overturn_time", "overturn time", _t(s["overturn_time"])),
        ("exceeded_alpha_time", "|θ| first exceeded α", _t(s["exceeded_alpha_time"])),
        ("peak_rotation", "peak rotation", f"{_num(s['peak_rotation'])} rad"),
        ("peak_rotation_over_alpha", "peak rotation / α", _num(ratio, ".3f")),
        ("peak_sliding", "peak sliding", f"{_num(1e3 * s['peak_sliding'], '.2f')} mm"),
        _residual_row(s),
        ("impacts", "impacts", str(s["impacts"])),
        ("first_rocking_time", "rocking started", _t(s["first_rocking_time"])),
        ("first_sliding_time", "sliding started", _t(s["first_sliding_time"])),
        ("required_top_friction", "friction needed under the statue", need_text(s["required_top_friction"])),
        ("impact_floor_friction_needed", "friction needed at impacts", _num(s.get("impact_floor_friction_needed"), ".3f")),
        ("end_time", "simulated until", _t(s.get("end_time"))),
        ("status", "status", str(s.get("status"))),
        ("energy_balance_error", "energy balance error", _num(s.get("energy_balance_error"), ".1e")),
    ]
    return [(k, label, text, json.dumps(s.get(k))) for k, label, text in rows]


def _residual_row(s: Mapping[str, Any]) -> tuple[str, str, str]:
    """The sliding left at the end; after an overturn the run ends at the fall, so the sliding
    is the sliding at that instant, not where the statue comes to rest."""
    mm = f"{_num(1e3 * s['residual_sliding'], '.2f')} mm"
    if s["overturned"]:
        return ("residual_sliding", "sliding at the fall", f"{mm} (at the fall, {_t(s['overturn_time'])})")
    return ("residual_sliding", "residual sliding", mm)


def _two_decimals(x: Any) -> str:
    """x with two decimals, never "-0.00" (a residual of −1 µm is no sliding back)."""
    if x is None or not math.isfinite(x):
        return "—"
    return f"{round(x, 2) + 0.0:.2f}"


def _mm(x: Any) -> str:
    return _two_decimals(None if x is None else 1e3 * x)


def _degrees(x: Any) -> str:
    return _two_decimals(None if x is None else math.degrees(x))


def stack_summary_rows(s: Mapping[str, Any]) -> list[tuple[str, str, str, str]]:
    """(id, label, text, JSON value) of a stack run's overall numbers (as ``rocking run`` prints them)."""
    rows = [
        ("impacts", "impacts, all interfaces", str(s["impacts"])),
        ("end_time", "simulated until", _t(s.get("end_time"))),
        ("status", "status", str(s.get("status"))),
        ("energy_balance_error", "energy balance error", _num(s.get("energy_balance_error"), ".1e")),
    ]
    return [(k, label, text, json.dumps(s.get(k))) for k, label, text in rows]


def block_rows(s: Mapping[str, Any]) -> list[dict[str, Any]]:
    """One row per block, from the floor up: name, whether and when it overturned, peak rotation
    on what is below (°), peak and residual sliding on it (mm); ``values`` holds the SI numbers."""
    rows = []
    for k, b in enumerate(s["blocks"]):
        rows.append({
            "name": b["name"],
            "overturned": fall_text(s, k),
            "peak_rotation": _degrees(b["peak_rotation"]),
            "peak_sliding": _mm(b["peak_sliding"]),
            "residual_sliding": _mm(b["residual_sliding"]),
            "values": json.dumps({k: b[k] for k in ("overturned", "overturn_time", "peak_rotation", "peak_sliding",
                                                    "residual_sliding")}),
        })
    return rows


def interface_rows(s: Mapping[str, Any], frictions: list[float | None]) -> list[dict[str, Any]]:
    """One row per interface, from the floor up: the friction it needed, the μs given (or "never
    slips"), its slip path (mm) and impacts."""
    rows = []
    for f, mu in zip(s["interfaces"], frictions):
        rows.append({
            "name": f["name"],
            "required_friction": need_text(f["required_friction"], short=True),  # (a phone's column)
            "given": "never slips" if mu is None else _num(mu, ".3g"),
            "slip_path": _mm(f["slip_path"]),
            "impacts": str(f.get("impacts", "—")),
            "values": json.dumps({"required_friction": f["required_friction"], "slip_path": f["slip_path"],
                                  "impacts": f.get("impacts")}),
        })
    return rows


def _page_result(run_id: str, result: Mapping[str, Any], labels: Mapping[str, str] | None = None) -> dict[str, Any]:
    """The run's result as the templates use it; ``labels`` name bundled records by event and
    station instead of their file stem."""
    s = result["summary"]
    motion = [(k, (labels or {}).get(v, v) if k == "record" else v) for k, v in result["motion"]]
    if result.get("kind") == "stack":
        fell = any(b["overturned"] for b in s["blocks"])  # the top-level keys describe the top block only
        klass = "fails" if fell else ("stopped" if s["verdict"].startswith("undetermined") else "safe")
        return {**result, "id": run_id, "rows": stack_summary_rows(s), "verdict_class": klass, "motion": motion,
                "block_rows": block_rows(s), "interface_rows": interface_rows(s, result["frictions"])}
    klass = "fails" if s["overturned"] else ("safe" if s.get("status") == "completed" else "stopped")
    return {**result, "id": run_id, "rows": summary_rows(s), "verdict_class": klass, "motion": motion}


# ------------------------------------------------------------------------------- the state
class _State:
    """What the app keeps between requests: settings, the job runner, the work folder."""

    def __init__(self, settings: Mapping[str, Any]):
        self.settings = dict(settings)
        work = settings["WORK_DIR"]
        if work is None:
            self.work_dir = Path(tempfile.mkdtemp(prefix="rocking-web-"))
            self._cleanup = weakref.finalize(self, shutil.rmtree, str(self.work_dir), True)
        else:
            self.work_dir = Path(work)
            self.work_dir.mkdir(parents=True, exist_ok=True)
            self._cleanup = None
        (self.work_dir / "runs").mkdir(exist_ok=True)
        (self.work_dir / "sweeps").mkdir(exist_ok=True)
        self.runner = JobRunner(
            settings["MAX_WORKERS"], queue_timeout=float(settings["QUEUE_TIMEOUT"]), context=settings["MP_CONTEXT"]
        )
        self._lock = threading.Lock()
        # one client may hold at most all workers but one: another user can always start a run
        self.clients = _Clients(min(int(settings["MAX_JOBS_PER_CLIENT"]), max(1, self.runner.max_workers - 1)))
        self.records = record_choices(bundled_records())
        self.record_labels = {c["name"]: c["short"] for c in self.records}
        self.forms: dict[str, dict[str, str]] = {}  # the inputs of each sweep, to go back to them

    def new_dir(self, kind: str) -> tuple[str, Path]:
        run_id = uuid.uuid4().hex
        path = self.work_dir / kind / run_id
        path.mkdir(parents=True)
        self._prune(kind)
        return run_id, path

    def _prune(self, kind: str) -> None:
        keep = int(self.settings["KEEP_RUNS"])
        def age(path: Path) -> float | None:
            try:
                return path.stat().st_mtime
            except FileNotFoundError:  # removed meanwhile by a request that was refused
                return None

        with self._lock:
            stamped = [(t, p) for p in (self.work_dir / kind).iterdir() if (t := age(p)) is not None]
            dirs = [p for _, p in sorted(stamped, key=lambda tp: tp[0])]
            for old in dirs[:-keep] if len(dirs) > keep else []:
                job = self.runner.get(old.name)
                if job is None or job.finished_flag:
                    shutil.rmtree(old, ignore_errors=True)
                    self.forms.pop(old.name, None)

    def shutdown(self) -> None:
        self.runner.shutdown()
        if self._cleanup is not None:
            self._cleanup()


def _state(app: Flask) -> _State:
    return app.extensions["rocking"]


def _megabytes(n: int) -> str:
    return f"{n / 1024 / 1024:g} MB" if n >= 1024 * 1024 else f"{n / 1024:g} kB"


# -------------------------------------------------------------------------------- the app
def create_app(settings: Mapping[str, Any] | None = None) -> Flask:
    """Build the web app.

    Parameters
    ----------
    settings : mapping, optional
        Overrides of :data:`DEFAULTS`: ``RUN_TIMEOUT`` and ``SWEEP_TIMEOUT`` (s), ``MAX_UPLOAD``
        (bytes), ``MAX_SWEEP_POINTS``, ``MAX_WORKERS``, ``WORK_DIR``, ``ANIMATION``,
        ``ALLOWED_HOSTS`` ...

    Returns
    -------
    flask.Flask
        ``app.extensions["rocking"].shutdown()`` stops its workers and removes its files.
    """
    cfg = {**DEFAULTS, **(settings or {})}
    app = Flask("rocking.web")
    app.jinja_loader = DictLoader(TEMPLATES)
    # the whole request: the record plus the other fields
    app.config["MAX_CONTENT_LENGTH"] = int(cfg["MAX_UPLOAD"]) + 256 * 1024
    state = _State(cfg)
    app.extensions["rocking"] = state

    max_blocks = int(cfg["MAX_BLOCKS"])
    block_fields = block_field_names(max_blocks)

    def page(status: int = 200, *, form: Mapping[str, Any] | None = None, **kw: Any):
        values = {**_FORM_DEFAULTS, **stack_form_defaults(max_blocks)}
        if form is not None:
            values.update({k: _text(form, k) for k in (*_FORM_DEFAULTS, *block_fields) if k in form})
            values["pedestal"] = _text(form, "pedestal")  # an unticked box is not sent
        try:
            shown = min(max(int(values["stack_blocks"]), 1), max_blocks)
        except ValueError:
            shown = min(2, max_blocks)
        html = render_template(
            "index.html",
            form=values,
            modes=_MODES,
            max_blocks=max_blocks,
            shown_blocks=shown,
            records=state.records,
            formats=_FORMATS,
            units=_UNITS,
            scale_kinds=_SCALE_KINDS,
            max_upload=_megabytes(int(cfg["MAX_UPLOAD"])),
            max_upload_bytes=int(cfg["MAX_UPLOAD"]),
            max_sweep_points=int(cfg["MAX_SWEEP_POINTS"]),
            max_duration=f"{float(cfg['MAX_DURATION']):g}",
            timeout=f"{float(cfg['RUN_TIMEOUT']):g}",
            **kw,
        )
        return html, status

    @app.context_processor
    def _version() -> dict[str, Any]:
        return {"version": __version__}

    @app.before_request
    def _guard():
        allowed = cfg["ALLOWED_HOSTS"]
        if allowed:
            host = request.headers.get("Host", "")
            name = host[1 : host.find("]")] if host.startswith("[") else host.rsplit(":", 1)[0]
            if name.lower() not in {h.lower() for h in allowed}:
                abort(400, description=f"unexpected Host header {host!r}")
        if request.method == "POST":
            origin = request.headers.get("Origin")
            if origin and origin != "null" and urlsplit(origin).netloc != request.host:
                abort(403, description="cross-site form submissions are refused")

    # ------------------------------------------------------------ one client's share of the workers
    def claim_quota(folder: Path):
        """Count this request's run or sweep against its client's quota (until the job ends);
        None, or the 429 page if the client is at its limit (``folder`` is then removed).
        Called after the form is validated: a mistake in it is shown whatever the quota."""
        client = request.remote_addr or "unknown"
        if not state.clients.claim(client):
            shutil.rmtree(folder, ignore_errors=True)
            limit = state.clients.limit
            html, status = page(
                429, form=request.form, error_title="Too many runs at once",
                error=f"{client} already has {limit} run{'s' if limit > 1 else ''} or design sweep"
                      f"{'s' if limit > 1 else ''} in progress, the most one address may have at once on this "
                      "server; wait until one has finished, then try again",
            )
            return html, status, {"Retry-After": "10"}
        g.quota_client = client
        return None

    @app.teardown_request
    def _release_quota(exc):
        client = g.pop("quota_client", None)  # a started sweep has taken it over
        if client is not None:
            state.clients.release(client)

    @app.errorhandler(RequestEntityTooLarge)
    def _too_large(exc):
        return page(
            413, error_title="Upload refused",
            error=f"the upload is larger than the limit of {_megabytes(int(cfg['MAX_UPLOAD']))}",
        )

    @app.errorhandler(HTTPException)
    def _http_error(exc):
        if request.method == "GET" and exc.code == 404:
            return page(404, error_title="Not found", error="there is no such page (old runs are removed)")
        return page(exc.code or 500, error_title=exc.name, error=exc.description or exc.name)

    @app.errorhandler(Exception)
    def _unexpected(exc):
        log.exception("unexpected error in %s %s", request.method, request.path)
        return page(500, error_title="Unexpected error",
                    error=f"unexpected {type(exc).__name__}: {exc} (the server log has the details)")

    # ---------------------------------------------------------------- validation helpers
    def prepare(kind: str, folder: Path) -> tuple[dict[str, Any], str | None]:
        """Read the form and the upload (saved in ``folder``) into a config dict; raises FormError,
        RecordError or ConfigError with messages for the page."""
        upload = request.files.get("upload")
        record_path = None
        if upload is not None and upload.filename:
            upload_dir = folder / "upload"
            upload_dir.mkdir()
            name = secure_filename(upload.filename) or "record.txt"
            path = upload_dir / name
            upload.save(path)
            size = path.stat().st_size
            if size == 0:
                raise FormError(f"the uploaded file {name} is empty")
            if size > int(cfg["MAX_UPLOAD"]):
                raise RequestEntityTooLarge()
            if looks_binary(path):
                raise FormError(f"{name}: not a text record file; upload a PEER AT2, ESM ASCII or two-column text file")
            record_path = str(path)
        config = parse_form(request.form, record_path, max_blocks=max_blocks)
        # the worker refuses a longer series too (ResourceLimitError), should a record's time step be finer
        config.setdefault("simulation", {})["max_samples"] = int(cfg["MAX_SAMPLES"])
        motion = config["motion"]
        if record_path is not None or motion.get("units"):
            # the reader's own checks, with its message naming the file and the line; also a
            # units choice that contradicts the header of a bundled record (the config's own
            # message for that would point at a TOML key the page does not have)
            read_record(record_path or motion["path"], format=motion.get("format"), units=motion.get("units"))
        checked = load_config(config)  # every other problem, named by field, before a worker starts
        check_limits(checked, float(cfg["MAX_DURATION"]), int(cfg["MAX_SAMPLES"]))
        return config, record_path

    def validated(kind: str):
        """((id, folder, config, upload folder or None), None), or (None, (title, message))."""
        run_id, folder = state.new_dir(kind)
        upload_dir = str(folder / "upload")
        try:
            config, record_path = prepare(kind, folder)
        except BaseException as exc:
            shutil.rmtree(folder, ignore_errors=True)
            if isinstance(exc, UnitsConflictError):
                return None, ("Invalid input", _units_conflict_message(exc))
            if isinstance(exc, LimitError):
                return None, ("Over this server's limits", str(exc))
            if isinstance(exc, RecordError) and exc.reason.startswith("the file does not state its units"):
                return None, ("Choose the units", _missing_units_message(exc))
            if isinstance(exc, RecordError):
                return None, ("Cannot read the record", _hide_path(" ".join(str(exc).split()), upload_dir))
            if isinstance(exc, ConfigError):
                return None, ("Invalid input", _config_message(exc, upload_dir))
            if isinstance(exc, ValueError):  # FormError, or e.g. an unknown format from the reader
                return None, ("Invalid input", _hide_path(" ".join(str(exc).split()), upload_dir))
            raise
        return (run_id, folder, config, upload_dir if record_path else None), None

    # ------------------------------------------------------------------------- routes
    @app.get("/")
    def index():
        return page()

    @app.get("/healthz")
    def healthz():
        return {"status": "ok", "version": __version__, "active_workers": state.runner.active()}

    @app.post("/run")
    def run():
        prepared, problem = validated("runs")
        if problem is not None:
            return page(400, form=request.form, error_title=problem[0], error=problem[1])
        run_id, folder, config, upload_dir = prepared
        refused = claim_quota(folder)
        if refused is not None:
            return refused
        job = state.runner.run(
            tasks.run_task,
            {"config": config, "out_dir": str(folder), "animation": cfg["ANIMATION"], "dpi": int(cfg["FIGURE_DPI"])},
            timeout=float(cfg["RUN_TIMEOUT"]),
            kind="run",
            job_id=run_id,
        )
        if upload_dir:
            shutil.rmtree(upload_dir, ignore_errors=True)
        if job.state != DONE:
            status = {"timeout": 504, "busy": 503, "internal": 500}.get(job.error_kind or "", 400)
            title = {"timeout": "Run stopped", "busy": "Server busy"}.get(job.error_kind or "", "The run failed")
            return page(status, form=request.form, error_title=title, error=_hide_path(job.error or "", upload_dir))
        return page(form=request.form, result=_page_result(run_id, job.result, state.record_labels))

    @app.get("/runs/<run_id>")
    def show_run(run_id: str):
        path = _folder("runs", run_id) / "result.json"
        if not path.is_file():
            abort(404)
        result = json.loads(path.read_text(encoding="utf-8"))
        return render_template("run.html", result=_page_result(run_id, result, state.record_labels))

    @app.get("/runs/<run_id>/<name>")
    def run_file(run_id: str, name: str):
        if name not in _RUN_FILES:
            abort(404)
        return send_from_directory(_folder("runs", run_id), name, max_age=3600)

    @app.post("/sweep")
    def start_sweep():
        prepared, problem = validated("sweeps")
        frictions, sliding_limit, scatter = None, None, None
        if problem is None:
            try:
                if "blocks" in prepared[2]:
                    raise FormError(
                        "the design sweep varies the floor friction of a statue's pedestal: choose "
                        "'a statue, alone or on a pedestal' and describe the pedestal"
                    )
                if "pedestal" not in prepared[2]:
                    raise FormError(
                        "the design sweep varies the pedestal's floor friction: tick "
                        "'the statue stands on a pedestal' and describe the pedestal"
                    )
                frictions, sliding_limit = parse_sweep(request.form, int(cfg["MAX_SWEEP_POINTS"]))
                scatter = parse_scatter(request.form)
            except FormError as exc:
                problem = ("Invalid input", str(exc))
        if problem is not None:
            if prepared is not None:
                shutil.rmtree(prepared[1], ignore_errors=True)
            return page(400, form=request.form, error_title=problem[0], error=problem[1])
        job_id, folder, config, upload_dir = prepared
        refused = claim_quota(folder)
        if refused is not None:
            return refused
        state.forms[job_id] = {k: _text(request.form, k) for k in (*_FORM_DEFAULTS, *block_fields)
                               if k in request.form}
        state.forms[job_id]["pedestal"] = "on"
        client = g.pop("quota_client", None)  # the sweep holds its client's share until it ends

        def finished(job) -> None:
            if upload_dir:
                shutil.rmtree(upload_dir, ignore_errors=True)
            if client is not None:
                state.clients.release(client)

        try:
            state.runner.start(
                tasks.sweep_task,
                {"config": config, "frictions": frictions, "sliding_limit": sliding_limit, "friction_scatter": scatter,
                 "out_dir": str(folder),
                 "dpi": int(cfg["FIGURE_DPI"])},
                timeout=float(cfg["SWEEP_TIMEOUT"]),
                kind="sweep",
                job_id=job_id,
                on_done=finished,
            )
        except BaseException:
            if client is not None:
                state.clients.release(client)
            raise
        return redirect(url_for("show_sweep", job_id=job_id), code=303)

    def _job(job_id: str):
        job = state.runner.get(job_id) if _ID_RE.match(job_id) else None
        if job is None or job.kind != "sweep":
            abort(404)
        return job

    @app.get("/sweeps/<job_id>")
    def show_sweep(job_id: str):
        job = _job(job_id)
        return render_template("sweep.html", job=job, finished=job.finished_flag)

    @app.get("/sweeps/<job_id>/inputs")
    def sweep_inputs(job_id: str):
        _job(job_id)
        return page(form=state.forms.get(job_id, {}))

    @app.get("/sweeps/<job_id>/status")
    def sweep_status(job_id: str):
        resp = jsonify(_job(job_id).status())
        resp.headers["Cache-Control"] = "no-store"
        return resp

    @app.get("/sweeps/<job_id>/files/<name>")
    def sweep_file(job_id: str, name: str):
        job = _job(job_id)
        if name not in _SWEEP_FILES or job.state != DONE:
            abort(404)
        return send_from_directory(_folder("sweeps", job_id), name, as_attachment=name != "report.html")

    def _folder(kind: str, run_id: str) -> Path:
        if not _ID_RE.match(run_id):
            abort(404)
        path = state.work_dir / kind / run_id
        if not path.is_dir():
            abort(404)
        return path

    return app

