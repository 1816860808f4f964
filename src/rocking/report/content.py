"""What a report says, independent of its format: inputs, verdict, key figures, assumptions,
warnings. Built from a :class:`~rocking.results.response.Response` (which carries the system,
the motion and the options it was run with), optionally with the :class:`Config` it came from.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..models.regimes import Regime
from ..results.response import IMPACT_BEYOND_FRICTION, LIFTED_OFF, SETTLED_TEXT
from ..results.wording import need_text

Rows = list[tuple[str, str]]


#: Results of a check.
PASS, FAIL, UNDETERMINED, NOT_CHECKED, NOT_APPLICABLE = "pass", "fail", "undetermined", "not checked", "n/a"

#: Largest relative energy balance error |E − E₀ − W + D| / energy scale a run may have.
ENERGY_BALANCE_LIMIT = 1e-6


@dataclass(frozen=True)
class Check:
    """One row of the checks table: what was checked, the value found, the limit, the result
    (:data:`PASS`, :data:`FAIL`, :data:`UNDETERMINED`, :data:`NOT_CHECKED`, :data:`NOT_APPLICABLE`).
    ``warning`` says what a failure means when the model's own warnings do not say it."""

    name: str
    value: str
    limit: str
    result: str
    warning: str | None = None


@dataclass(frozen=True)
class FigureText:
    """What the report says about one figure: ``number`` (1, 2, … in reading order), the
    heading of its section, the paragraph that discusses it and its caption (without the
    "Figure n:" label)."""

    number: int
    heading: str
    discussion: str
    caption: str

    @property
    def label(self) -> str:
        return f"Figure {self.number}: {self.caption}"


@dataclass(frozen=True)
class Provenance:
    """Where a report comes from: library version, date (ISO), input name and the first 12 hex
    digits of its SHA-256 (None when there is no input to hash)."""

    version: str
    date: str
    input_name: str
    input_hash: str | None

    @property
    def footer(self) -> str:
        digest = f"SHA-256 {self.input_hash}" if self.input_hash else "no input file"
        return f"rocking {self.version} · {self.date} · {self.input_name} · {digest}"


@dataclass(frozen=True)
class DataTable:
    """A table with a header row and several columns (a row per block of a stack, say):
    ``heading``, ``header`` (column names), ``rows`` (strings), ``widths`` (relative widths of
    the columns in the PDF) and ``place``: "results" (after the key figures) or "inputs" (first
    in the inputs)."""

    heading: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    widths: tuple[float, ...]
    place: str = "results"


@dataclass
class ReportContent:
    """Everything a report shows, as plain strings (format-independent)."""

    title: str
    verdict: str
    inputs: dict[str, Rows]
    key_figures: Rows
    assumptions: list[str]
    warnings: list[str]
    events: list[tuple[str, str, str, str]] = field(default_factory=list)
    source: str | None = None
    checks: list[Check] = field(default_factory=list)
    figures: list[FigureText] = field(default_factory=list)
    symbols: Rows = field(default_factory=list)
    provenance: Provenance | None = None
    tables: list[DataTable] = field(default_factory=list)
    event_header: tuple[str, ...] = ("t (s)", "event", "before", "after")

    def tables_at(self, place: str) -> list[DataTable]:
        """The tables shown at ``place`` ("results" or "inputs"), in order."""
        return [t for t in self.tables if t.place == place]


# --------------------------------------------------------------------------------- numbers
def _g(x: float | None, digits: int = 4, unit: str = "") -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    text = f"{x:.{digits}g}"
    return f"{text} {unit}".strip()


def _mm(x_m: float) -> str:
    mm = abs(x_m) * 1e3
    if mm >= 10:
        return f"{mm:.0f} mm"
    if mm >= 1:
        return f"{mm:.1f} mm"
    return f"{mm:.2f} mm"


def _time(t: float | None) -> str:
    return "—" if t is None else f"{t:.2f} s"


def _deg(rad: float) -> str:
    return f"{math.degrees(rad):.2f}°"


# --------------------------------------------------------------------------------- verdict
def verdict(response) -> str:
    """One sentence: does the statue overturn, how far it rocks, how far the sliding body slides.

    >>> verdict(response)  # doctest: +SKIP
    'The statue does not overturn; it rocks up to 0.45 α and the pedestal slides at most 38 mm (residual 6 mm).'
    """
    s = response.summary()
    if s["overturned"]:
        return f"The statue overturns at t = {s['overturn_time']:.2f} s."
    pedestal = getattr(response.system, "pedestal", None) is not None
    rocks = s["first_rocking_time"] is not None
    slides = s["first_sliding_time"] is not None
    if rocks:
        rock = f"it rocks up to {s['peak_rotation_over_alpha']:.2f} α"
        if s["exceeded_alpha_time"] is not None:
            rock += " (beyond its static stability limit θ = α)"
    else:
        rock = "it does not rock"
    amount = f"slides at most {_mm(s['peak_sliding'])} (residual {_mm(s['residual_sliding'])})"
    if pedestal:
        body = f"{rock} and the pedestal " + (amount if slides else "does not slide")
    elif not rocks and not slides:
        body = "it neither rocks nor slides"
    elif not slides:
        body = f"{rock} and does not slide"
    else:
        body = f"{rock} and " + amount if rocks else f"it does not rock but {amount}"
    if s["still_moving"] and s["settled_by_energy"]:
        return (f"The statue does not overturn: it is still moving at t = {s['end_time']:.2f} s, when the run "
                f"ended, but {SETTLED_TEXT}, so it cannot fall any more; {body}.")
    if s["still_moving"]:
        return (
            f"Undetermined: the statue is still moving at t = {s['end_time']:.2f} s, when the run ended "
            f"(raise simulation.free_time_limit or simulation.duration for a verdict); until then it did not "
            f"overturn: {body}."
        )
    if s["status"] == LIFTED_OFF:
        return (f"{s['verdict'][0].upper()}{s['verdict'][1:]} (the warnings say which body): what follows is not a "
                f"result; model it as a stack of blocks ([[blocks]]), whose engine follows the flight. Over the "
                f"whole run, in the two-body model, {body}.")
    if s["status"] == IMPACT_BEYOND_FRICTION:
        return (f"{s['verdict'][0].upper()}{s['verdict'][1:]}: the model held the body on the floor anyway, so what "
                f"follows is not a result; model it as a stack of blocks ([[blocks]]), whose engine solves each "
                f"impact with friction at both corners. Over the whole run, in the two-body model, {body}.")
    if s["status"] != "completed":
        return (
            f"Undetermined: the simulation stopped early at t = {s['end_time']:.2f} s ({response.status_message}); "
            f"until then the statue did not overturn: {body}."
        )
    if s["verdict"].startswith("undetermined"):  # the run ended before the floor motion did
        return f"{s['verdict'][0].upper()}{s['verdict'][1:]}; until then the statue did not overturn: {body}."
    return f"The statue does not overturn; {body}; everything is at rest at t = {s['end_time']:.2f} s."


def verdict_class(response, report_checks: list[Check] | None = None) -> str:
    """The colour of the verdict: "fails" (overturns), "stopped" (undetermined, or standing while
    a check of ``report_checks`` fails) or "safe"."""
    s = response.summary()
    if s["overturned"]:
        return "fails"
    if s["verdict"].startswith("undetermined") or any(c.result == FAIL for c in report_checks or []):
        return "stopped"
    return "safe"


# ----------------------------------------------------------------------------------- inputs
def _friction(fr) -> str:
    if fr is None:
        return "none given (never slides)"
    return f"μs = {fr.mu_s:g}, μk = {fr.mu_k:g}"


def _motion_rows(motion, gravity: float) -> Rows:
    name = type(motion).__name__
    rows: Rows = [("kind", name)]
    if name == "GroundMotion":
        rows += [
            ("record", motion.name or "(unnamed)"),
            ("source", str(getattr(motion, "source", "") or "—")),
            ("samples", f"{motion.n} at Δt = {motion.dt:g} s"),
            ("record duration", f"{motion.duration:.2f} s"),
            ("PGA", f"{motion.pga:.3f} m/s² ({motion.pga / gravity:.3f} g)"),
            ("PGV", f"{motion.pgv:.3f} m/s"),
        ]
        if getattr(motion, "vertical", None) is not None:
            rows.append(("vertical component", "yes"))
        return rows
    units = {"amplitude": "m/s²", "frequency": "Hz", "angular_frequency": "rad/s", "width": "s",
             "center": "s", "phase": "rad", "rate": "m/s³", "end": "s"}
    if dataclasses.is_dataclass(motion):
        for f in dataclasses.fields(motion):
            v = getattr(motion, f.name)
            if v is None:
                continue
            rows.append((f.name.replace("_", " "), f"{v:g} {units.get(f.name, '')}".strip()
                         if isinstance(v, (int, float)) else str(v)))
    try:
        rows.append(("PGA", f"{motion.pga:.3f} m/s² ({motion.pga / gravity:.3f} g)"))
    except Exception:  # pragma: no cover - a motion without pga
        pass
    rows.append(("motion duration", f"{motion.duration:.2f} s"))
    return rows


def describe_inputs(response, config: Any = None) -> dict[str, Rows]:
    """Input tables (section → rows of (name, value with unit))."""
    system, options = response.system, response.options
    st = system.statue
    g = options.gravity
    r_text = (f"{st.restitution:g} (given)" if st.restitution is not None
              else f"{st.housner_restitution:.4f} (Housner, 1 − 1.5 sin²α)")
    statue: Rows = [
        ("width B × height H", f"{st.width:g} m × {st.height:g} m"),
        ("mass m₂", f"{st.mass:g} kg"),
        ("slenderness α = atan(B/H)", f"{st.slenderness:.4f} rad ({_deg(st.slenderness)})"),
        ("semi-diagonal R", f"{st.semi_diagonal:.4g} m"),
        ("frequency parameter p = √(3g/4R)", f"{st.frequency_parameter(g):.4g} s⁻¹"),
        ("g·tan α (uplift threshold at rest)", f"{g * math.tan(st.slenderness):.3f} m/s²"),
        ("restitution r", r_text),
    ]
    ped = system.pedestal
    if ped is not None:
        statue.append(("friction on the pedestal (checked only)", _friction(st.friction)))
    else:
        statue.append(("friction on the floor", _friction(st.friction)))
    out: dict[str, Rows] = {"Statue": statue}
    if ped is not None:
        rows: Rows = [
            ("mass m₁", f"{ped.mass:g} kg"),
            ("friction on the floor", _friction(ped.friction)),
            ("width × height", f"{ped.width:g} m × {ped.height:g} m"
             if ped.width is not None and ped.height is not None else
             ", ".join(f"{k} {v:g} m" for k, v in (("width", ped.width), ("height", ped.height)) if v is not None)
             or "not given"),
        ]
        out["Pedestal"] = rows
    else:
        out["Pedestal"] = [("pedestal", "none: the statue stands on the floor")]
    out["Motion"] = _motion_rows(response.motion, g)
    out["Options"] = [
        ("simulated", f"until t = {response.end_time:.3f} s (" + (
            f"simulation.duration = {response.duration:g} s" if response.duration_given
            else f"the motion, then free motion until at rest, at most {options.free_time_limit:g} s more") + ")"),
        ("gravity g", f"{g:g} m/s²"),
        ("normal force in the friction law", options.normal_force),
        ("impact rule", options.impact),
        ("tolerances rtol / atol", f"{options.rtol:g} / {options.atol:g}"),
        ("largest step", f"{options.max_step:g} s"),
        ("output spacing", "default" if options.save_dt is None else f"{options.save_dt:g} s"),
    ]
    source = getattr(config, "source", None)
    if source:
        out["Options"].insert(0, ("configuration file", str(source)))
    return out


def _flatten(prefix: str, value: Any, rows: Rows) -> None:
    if isinstance(value, Mapping):
        for k, v in value.items():
            _flatten(f"{prefix}.{k}" if prefix else str(k), v, rows)
    else:
        rows.append((prefix, str(value)))


def inputs_from_mapping(inputs: Mapping[str, Any]) -> Rows:
    """A nested mapping (e.g. the TOML tables) as dotted rows."""
    rows: Rows = []
    _flatten("", inputs, rows)
    return rows


# ------------------------------------------------------------------------------ key figures
def regime_durations(response) -> dict[Regime, float]:
    """Time spent in each regime, s."""
    t = np.asarray(response.t, dtype=float)
    reg = np.asarray(response.regime)
    out = {r: 0.0 for r in Regime}
    if t.size >= 2:
        dt = np.diff(t)
        for r in Regime:
            out[r] = float(dt[reg[:-1] == r].sum())
    return out


def key_figures(response) -> Rows:
    s = response.summary()
    led = response.energy
    pedestal = getattr(response.system, "pedestal", None) is not None
    body = "pedestal" if pedestal else "statue"
    # whether it overturned, the end of the run and the energy balance are in the checks table
    rows: Rows = [
        ("first time |θ| ≥ α", _time(s["exceeded_alpha_time"])),
        ("peak rotation |θ|", f"{s['peak_rotation']:.4g} rad ({_deg(s['peak_rotation'])}) = "
                              f"{s['peak_rotation_over_alpha']:.3f} α"),
        (f"peak sliding of the {body}", _mm(s["peak_sliding"])),
        (f"residual sliding of the {body}",
         f"{s['residual_sliding'] * 1e3:+.3g} mm" if s["residual_sliding"] != 0 else "0 mm"),
        ("impacts", str(s["impacts"])),
        ("first rocking", _time(s["first_rocking_time"])),
        ("first sliding", _time(s["first_sliding_time"])),
    ]
    shares = regime_durations(response)
    total = sum(shares.values())
    if total > 0:
        rows.append(("time at rest / rocking / sliding / sliding and rocking",
                     " / ".join(f"{shares[r]:.2f} s" for r in Regime)))
    rows += [
        ("friction the statue's base needs, max |Fx|/Fy", need_text(s["required_top_friction"], ".4g")),
        ("floor friction needed at impacts, max |Fx|/Fy", _g(s["impact_floor_friction_needed"], 4)),
        ("input work of the floor", _g(led["input_work"], 4, "J")),
        ("energy dissipated by friction", _g(led["friction_dissipation"], 4, "J")),
        ("energy dissipated by impacts", _g(led["impact_dissipation"], 4, "J")),
    ]
    return rows


# ------------------------------------------------------------------------ assumptions, warnings
def assumptions(response) -> list[str]:
    system, options = response.system, response.options
    st = system.statue
    ped = system.pedestal
    out = [
        "Rigid blocks in plane motion: the statue is a uniform rigid rectangle B × H that rocks about "
        "its base corners; nothing deforms, the blocks never fly (contact is kept).",
        "The floor moves horizontally only"
        + (" (plus the record's vertical component)" if getattr(response.motion, "vertical", None) is not None
           else "") + "; the motion is the given floor acceleration.",
    ]
    if ped is not None:
        out.append(
            "The pedestal only slides: it never rocks or lifts off (checked: a warning says when it would). The "
            "statue does not slide on the pedestal; the friction its base needs is compared with the top face's "
            "μs in the checks."
        )
        fr = ped.friction
    else:
        fr = st.friction
        if fr is None:
            out.append("The statue does not slide on the floor (infinite friction); the friction it needs is in "
                       "the checks.")
    if fr is not None:
        out.append(
            f"Coulomb friction under the sliding body: sticking while |F| ≤ μs·N (μs = {fr.mu_s:g}), "
            f"sliding with F = μk·N opposing the motion (μk = {fr.mu_k:g})."
        )
    r = st.effective_restitution
    r_origin = "given" if st.restitution is not None else "Housner's value 1 − 1.5 sin²α"
    if options.impact == "coulomb":
        out.append(
            "Impact when θ crosses zero (the statue changes corner): the statue's angular momentum about the new "
            f"corner is conserved (Housner's rule), with the coefficient of restitution r = {r:.4f} ({r_origin}); "
            "the floor's horizontal impulse is bounded by Coulomb friction, so an impact can set the sliding "
            "body in motion."
        )
    else:
        out.append(
            "Impact when θ crosses zero: the paper's rule θ̇⁺ = r·θ̇⁻ with the sliding velocity unchanged "
            f"(r = {r:.4f}, {r_origin}); the floor friction this needs is only checked."
        )
    if options.normal_force == "full":
        out.append(
            "The friction force uses the full floor normal force N = M(g + a_v) + m₂R(S sin φ θ̈ − cos φ θ̇²), "
            "which includes the statue's rocking inertia."
        )
    else:
        out.append("The friction force uses the paper's normal force N = M·g (rocking inertia neglected).")
    th0 = float(response.theta[0]) if len(response.t) else 0.0
    thd0 = float(response.theta_dot[0]) if len(response.t) else 0.0
    ud0 = float(response.u_dot[0]) if len(response.t) else 0.0
    start = ("the system starts at rest with the statue upright" if th0 == thd0 == ud0 == 0.0 else
             f"initial state θ = {th0:.4g} rad, θ̇ = {thd0:.4g} rad/s, u̇ = {ud0:.4g} m/s")
    out.append(
        f"Event-driven integration (Runge–Kutta, rtol = {options.rtol:g}, atol = {options.atol:g}); "
        f"g = {options.gravity:g} m/s²; {start}."
    )
    return out


def _overturn_check(s: Mapping[str, Any]) -> Check:
    name, limit = "statue stays upright (no overturn)", "|θ| < π/2 (90°)"
    peak = f"peak |θ| = {s['peak_rotation_over_alpha']:.2f} α ({_deg(s['peak_rotation'])})"
    if s["overturned"]:
        return Check(name, f"overturns at t = {s['overturn_time']:.2f} s", limit, FAIL)
    if s["verdict"].startswith("undetermined"):
        return Check(name, f"{peak} until t = {s['end_time']:.2f} s, when the run ended", limit, UNDETERMINED)
    return Check(name, peak, limit, PASS)


def _top_friction_check(response, s: Mapping[str, Any]) -> Check | None:
    """The friction the statue's base needs, against the face it stands on when that face is
    not simulated (the pedestal's top, or a floor without friction)."""
    need = s["required_top_friction"]
    system = response.system
    if system.pedestal is None:
        if system.statue.friction is not None:
            return None  # the statue slides on the floor when it must: simulated, nothing to check
        return Check("friction the statue's base needs on the floor, |Fx|/Fy", need_text(need),
                     "none given (assumed never to slide)", NOT_CHECKED)
    name = "friction the statue's base needs ≤ μs of the pedestal's top face"
    top = system.top_friction
    if top is None:
        return Check(name, need_text(need), "no μs given for the top face", NOT_CHECKED)
    if need <= top.mu_s:
        return Check(name, need_text(need), f"μs = {top.mu_s:g}", PASS)
    return Check(name, need_text(need), f"μs = {top.mu_s:g}", FAIL, warning=(
        f"The statue's base needs a friction coefficient of {need_text(need)}, more than the top face's "
        f"μs = {top.mu_s:g}: the statue would slip on the pedestal, which this model does not simulate."))


def _uplift_check(response, s: Mapping[str, Any]) -> Check | None:
    """The floor's reaction under the pedestal stays within its base (derivation §3.5): else the
    pedestal would tip, which this model does not simulate (the stack engine does). The run's
    warnings say from when; a failed check keeps the verdict from showing as safe."""
    pedestal = response.system.pedestal
    if pedestal is None:
        return None
    name = "pedestal stays flat (the floor's reaction within its base)"
    if not pedestal.uplift_checked:
        return Check(name, "–", "the pedestal's width and height not given", NOT_CHECKED)
    limit = f"|x_N| ≤ {pedestal.width / 2:g} m, half its width"
    t = s.get("pedestal_uplift_time")
    if t is None:
        # an impact's impulse outside the base lifts a corner for an instant at most: a warning,
        # named here so that the pass does not read as denying it
        lifts = response.impact_uplifts()
        if lifts.size:
            return Check(name, f"within its base; at {lifts.size} impact(s) from t = {lifts[0]:.2f} s the "
                         "impulse is not (see the warnings)", limit, PASS)
        return Check(name, "within its base", limit, PASS)
    return Check(name, f"leaves its base at t = {t:.2f} s", limit, FAIL)


def _clearance_check(response, s: Mapping[str, Any], clearance: float | None) -> Check | None:
    system = response.system
    body = "pedestal" if system.pedestal is not None else "statue"
    if clearance is None and system.floor_friction is None:
        return None  # nothing slides and no free space was given: nothing to compare
    undetermined = s["verdict"].startswith("undetermined") and not s["overturned"]
    return sliding_check(f"the {body}", f"peak sliding of the {body}", s["peak_sliding"], clearance, undetermined)


def sliding_check(subject: str, what: str, peak: float, clearance: float | None, undetermined: bool) -> Check:
    """``what`` (peak sliding of ``subject``, m) against the free space around it; ``undetermined``:
    the run ended before the motion did, so it may slide further."""
    name = f"{what} ≤ the free space around it (clearance)"
    if clearance is None:
        return Check(name, _mm(peak), "no clearance given", NOT_CHECKED)
    limit = _mm(clearance)
    if peak > clearance:
        return Check(name, _mm(peak), limit, FAIL, warning=(
            f"{subject[:1].upper()}{subject[1:]} slides up to {_mm(peak)}, beyond the {limit} of free space around "
            "it: it would hit what surrounds it, which this model does not simulate."))
    if undetermined:
        return Check(name, _mm(peak), limit, UNDETERMINED)
    return Check(name, _mm(peak), limit, PASS)


def _rest_check(s: Mapping[str, Any]) -> Check:
    name, limit = "run ends at rest (a verdict, not undetermined)", ("at rest after the floor motion, or too little "
                                                                    "energy left to overturn")
    if s["overturned"]:
        return Check(name, f"ended by the overturn at t = {s['overturn_time']:.2f} s", limit, NOT_APPLICABLE)
    # the model's warnings already say why a run is undetermined: no second warning here
    return Check(name, s["verdict"], limit, FAIL if s["verdict"].startswith("undetermined") else PASS)


def _impact_floor_check(response, s: Mapping[str, Any]) -> Check | None:
    """The paper's impact rule takes whatever floor friction an impact needs. The Coulomb rule
    bounds the impulse by friction, except at an impact where no outcome within it was consistent
    and the body was held anyway (``Response.impact_friction_shortfalls``): a failed check, so
    that a verdict resting on such impacts does not show as safe."""
    floor = response.system.floor_friction
    if floor is None:
        return None
    if response.options.impact == "paper":
        need = s["impact_floor_friction_needed"]
        return Check("floor friction the impacts need ≤ the floor's μs (paper's impact rule)", f"{need:.3f}",
                     f"μs = {floor.mu_s:g}", PASS if need <= floor.mu_s else FAIL)
    held = response.impact_friction_shortfalls()
    if not held.size:
        return None
    return Check("every impact within the floor's friction (Coulomb impact rule)",
                 f"{held.size} held beyond it from t = {held[0]:.2f} s (see the warnings)", f"μs = {floor.mu_s:g}", FAIL)


def _energy_check(s: Mapping[str, Any]) -> Check:
    err = s["energy_balance_error"]
    name, limit = "energy balance error |E − E₀ − W + D| / energy scale", f"≤ {ENERGY_BALANCE_LIMIT:.0e}"
    if err <= ENERGY_BALANCE_LIMIT:
        return Check(name, f"{err:.1e}", limit, PASS)
    return Check(name, f"{err:.1e}", limit, FAIL, warning=(
        f"The energy ledger does not close (relative error {err:.1e} > {ENERGY_BALANCE_LIMIT:.0e}): tighten "
        "simulation.rtol and simulation.atol and run again."))


def checks(response, clearance: float | None = None) -> list[Check]:
    """The pass/fail checks of one run, most important first.

    Parameters
    ----------
    response : Response
    clearance : float, optional
        Free space around the sliding body, m: its peak sliding must stay within it.
    """
    s = response.summary()
    found = [
        _overturn_check(s),
        _top_friction_check(response, s),
        _uplift_check(response, s),
        _clearance_check(response, s, clearance),
        _rest_check(s),
        _impact_floor_check(response, s),
        _energy_check(s),
    ]
    return [c for c in found if c is not None]


def warnings(response, report_checks: list[Check] | None = None) -> list[str]:
    """Real warnings only: the model's own (instants where its assumptions fail, an undetermined
    end) and what each failed check means. A passing check is not a warning."""
    found = checks(response) if report_checks is None else report_checks
    return list(response.warnings) + [c.warning for c in found if c.result == FAIL and c.warning]


def check_clearance(clearance: float | None) -> float | None:
    """``clearance`` as a float (m), or a one-line ValueError naming it."""
    if clearance is None:
        return None
    try:
        value = float(clearance)
    except (TypeError, ValueError):
        raise ValueError(f"clearance: must be a length in m, got {clearance!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"clearance: must be a positive length in m, got {clearance!r}")
    return value


# ----------------------------------------------------------------------------------- figures
def figure_texts(response) -> list[FigureText]:
    """The two figures of a report, numbered, with the paragraph that discusses each."""
    s = response.summary()
    led = response.energy
    body = "pedestal" if response.system.pedestal is not None else "statue"
    if s["first_rocking_time"] is None:
        rock = "The statue never rocks"
    else:
        rock = (f"The statue starts rocking at t = {s['first_rocking_time']:.2f} s and rocks up to "
                f"{s['peak_rotation_over_alpha']:.2f} α ({_deg(s['peak_rotation'])}), with {s['impacts']} impacts")
    if s["first_sliding_time"] is None:
        slide = f"the {body} never slides"
    else:
        slide = (f"the {body} starts sliding at t = {s['first_sliding_time']:.2f} s, slides at most "
                 f"{_mm(s['peak_sliding'])} and ends {_mm(s['residual_sliding'])} from where it started")
    end = (f"The statue overturns at t = {s['overturn_time']:.2f} s (red line)." if s["overturned"]
           else f"The run ends at t = {s['end_time']:.2f} s.")
    response_fig = FigureText(
        1,
        "Response",
        f"Figure 1 shows the motion against time. {rock}; {slide}. {end}",
        f"Rotation θ/α of the statue, sliding u of the {body} relative to the floor and floor acceleration "
        "a_g against time t. Background: the regime (rest white, rock orange, slide blue, slide-rock purple); "
        "ticks: impacts; dashed lines: θ = ±α, the static stability limit.",
    )
    energy_fig = FigureText(
        2,
        "Energy",
        f"Figure 2 follows the mechanical energy E. The floor puts in the work W = {_g(led['input_work'], 4, 'J')}; "
        f"friction dissipates {_g(led['friction_dissipation'], 4, 'J')} and impacts "
        f"{_g(led['impact_dissipation'], 4, 'J')}. The ledger E(t₀) + W − D (circle) closes on the curve to a "
        f"relative error of {s['energy_balance_error']:.1e}, the energy balance check.",
        "Mechanical energy E = T + V (kinetic plus potential) of the statue"
        + (" and the pedestal" if response.system.pedestal is not None else "")
        + " relative to the floor against time t, with the final energy ledger: input work W of the floor, "
        "dissipation D by friction and impacts.",
    )
    return [response_fig, energy_fig]


# ----------------------------------------------------------------------------------- symbols
SYMBOLS: Rows = [
    ("B, H", "width and height of the statue, m"),
    ("m₁, m₂, M", "mass of the pedestal, of the statue, and M = m₁ + m₂ (M = m₂ alone), kg"),
    ("α", "slenderness α = atan(B/H), rad: beyond |θ| = α gravity no longer rights the statue"),
    ("R", "semi-diagonal R = ½√(B² + H²): base corner to centre of mass, m"),
    ("p", "frequency parameter p = √(3g/4R), s⁻¹"),
    ("g", "acceleration of gravity, m/s²"),
    ("r", "coefficient of restitution: θ̇ after an impact over θ̇ before"),
    ("μs, μk", "static and kinetic friction coefficients"),
    ("θ, θ̇, θ̈", "rotation of the statue (rad, > 0 towards +x), its rate (rad/s) and acceleration (rad/s²)"),
    ("u, u̇", "sliding of the pedestal (or of the statue alone) relative to the floor, m and m/s"),
    ("a_g, a_v", "horizontal and vertical acceleration of the floor, m/s²"),
    ("S", "the corner the statue rocks about: S = +1 for θ > 0, −1 for θ < 0"),
    ("φ", "φ = α − S·θ = α − |θ|: angle between the corner-to-centre line and the vertical, rad"),
    ("N, F", "normal and friction force of the floor on the body that slides, N"),
    ("Fx, Fy", "horizontal and vertical force on the statue's base, N; |Fx|/Fy is the friction it needs"),
    ("E, T, V", "mechanical energy E = T + V (kinetic plus potential) relative to the floor, J"),
    ("W, D", "work put in by the floor; energy dissipated by friction and impacts, J"),
    ("t, t₀", "time and the start of the run, s"),
]


# -------------------------------------------------------------------------------- provenance
def _report_date() -> str:
    """Today (UTC), or SOURCE_DATE_EPOCH's day for a reproducible build."""
    import datetime as dt
    import os

    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch and epoch.strip().isdigit():
        return dt.datetime.fromtimestamp(int(epoch), dt.timezone.utc).date().isoformat()
    return dt.datetime.now(dt.timezone.utc).date().isoformat()


def _sha256_short(data: bytes) -> str:
    import hashlib

    return hashlib.sha256(data).hexdigest()[:12]


def provenance(config: Any = None) -> Provenance:
    """Version, date and the input (file name and short SHA-256 of its bytes; a configuration
    given as a dict is hashed as canonical JSON)."""
    import json
    from pathlib import Path

    from .. import __version__

    date = _report_date()
    source = getattr(config, "source", None)
    if source:
        path = Path(source)
        try:
            digest = _sha256_short(path.read_bytes())
        except OSError:
            digest = None  # moved or deleted since it was read: say so rather than guess
        return Provenance(__version__, date, path.name, digest)
    if config is not None and hasattr(config, "model_dump"):
        text = json.dumps(config.model_dump(mode="json"), sort_keys=True, ensure_ascii=False)
        return Provenance(__version__, date, "configuration dict", _sha256_short(text.encode("utf-8")))
    return Provenance(__version__, date, "a Response (no input file)", None)


def event_rows(response, limit: int = 500) -> list[tuple[str, str, str, str]]:
    from ..viz.plots import REGIME_NAMES

    rows = []
    for ev in response.events[:limit]:
        rows.append((f"{ev.time:.4f}", ev.kind.name.lower().replace("_", " "),
                     REGIME_NAMES[ev.before], REGIME_NAMES[ev.after]))
    return rows


def default_title(response, config: Any = None) -> str:
    source = getattr(config, "source", None)
    st = response.system.statue
    where = "on a pedestal" if response.system.pedestal is not None else "on the floor"
    text = f"Rocking analysis: statue {st.width:g} m × {st.height:g} m {where}"
    if source:
        from pathlib import Path

        text += f" ({Path(source).name})"
    return text


def build_content(response, config: Any = None, *, title: str | None = None,
                  inputs: Mapping[str, Any] | None = None, clearance: float | None = None) -> ReportContent:
    """Everything the report says about ``response``; ``clearance`` (m) is the free space
    around the sliding body, checked against its peak sliding."""
    tables = describe_inputs(response, config)
    if inputs:
        tables["Configuration"] = inputs_from_mapping(inputs)
    found = checks(response, check_clearance(clearance))
    return ReportContent(
        title=title or default_title(response, config),
        verdict=verdict(response),
        inputs=tables,
        key_figures=key_figures(response),
        assumptions=assumptions(response),
        warnings=warnings(response, found),
        events=event_rows(response),
        source=getattr(config, "source", None),
        checks=found,
        figures=figure_texts(response),
        symbols=list(SYMBOLS),
        provenance=provenance(config),
    )
