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

Rows = list[tuple[str, str]]


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
    if s["still_moving"]:
        return (
            f"Undetermined: the statue is still moving at t = {s['end_time']:.2f} s, when the run ended "
            f"(raise simulation.free_time_limit or simulation.duration for a verdict); until then it did not "
            f"overturn: {body}."
        )
    if s["status"] != "completed":
        return (
            f"Undetermined: the simulation stopped early at t = {s['end_time']:.2f} s ({response.status_message}); "
            f"until then the statue did not overturn: {body}."
        )
    if s["verdict"].startswith("undetermined"):  # the run ended before the floor motion did
        return f"{s['verdict'][0].upper()}{s['verdict'][1:]}; until then the statue did not overturn: {body}."
    return f"The statue does not overturn; {body}; everything is at rest at t = {s['end_time']:.2f} s."


# ----------------------------------------------------------------------------------- inputs
def _friction(fr) -> str:
    if fr is None:
        return "none given (never slides)"
    return f"μs = {fr.mu_s:g}, μk = {fr.mu_k:g}"


def _motion_rows(motion, response) -> Rows:
    name = type(motion).__name__
    rows: Rows = [("kind", name)]
    if name == "GroundMotion":
        rows += [
            ("record", motion.name or "(unnamed)"),
            ("source", str(getattr(motion, "source", "") or "—")),
            ("samples", f"{motion.n} at Δt = {motion.dt:g} s"),
            ("record duration", f"{motion.duration:.2f} s"),
            ("PGA", f"{motion.pga:.3f} m/s² ({motion.pga / response.options.gravity:.3f} g)"),
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
        rows.append(("PGA", f"{motion.pga:.3f} m/s² ({motion.pga / response.options.gravity:.3f} g)"))
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
    out["Motion"] = _motion_rows(response.motion, response)
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
    rows: Rows = [
        ("overturned", "yes" if s["overturned"] else "no"),
        ("overturn time", _time(s["overturn_time"])),
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
        ("friction the statue's base needs, max |Fx|/Fy", _g(s["required_top_friction"], 4)),
        ("floor friction needed at impacts, max |Fx|/Fy", _g(s["impact_floor_friction_needed"], 4)),
        ("input work of the floor", _g(led["input_work"], 4, "J")),
        ("energy dissipated by friction", _g(led["friction_dissipation"], 4, "J")),
        ("energy dissipated by impacts", _g(led["impact_dissipation"], 4, "J")),
        ("energy balance error (relative)", f"{s['energy_balance_error']:.2e}"),
        ("status", f"{s['status']} (end at t = {s['end_time']:.3f} s)"),
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
            "The pedestal only slides: it never rocks or lifts off (checked, see warnings). The statue does not "
            "slide on the pedestal; the friction its base needs is reported and compared with the given value."
        )
        fr = ped.friction
    else:
        fr = st.friction
        if fr is None:
            out.append("The statue does not slide on the floor (infinite friction); the friction it needs is reported.")
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


def warnings(response) -> list[str]:
    """The model's own warnings plus the friction the statue's base face must supply."""
    s = response.summary()
    out = list(response.warnings)
    need = s["required_top_friction"]
    st = response.system.statue
    if response.system.pedestal is not None:
        text = (f"The statue/pedestal face must supply a friction coefficient of at least {need:.3f} "
                "(largest |Fx|/Fy at the statue's base, impacts included) for the statue not to slide on the pedestal")
        if st.friction is not None:
            ok = need <= st.friction.mu_s
            text += (f"; the given μs = {st.friction.mu_s:g} is " + ("enough." if ok else "NOT enough: the statue "
                     "would slip on the pedestal, which this model does not simulate."))
        else:
            text += "; no friction was given for that face, so this was not checked."
        out.append(text)
    elif st.friction is None:
        out.append(f"The floor must supply a friction coefficient of at least {need:.3f} under the statue "
                   "(largest |Fx|/Fy at its base, impacts included); it was assumed never to slide.")
    return out


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
                  inputs: Mapping[str, Any] | None = None) -> ReportContent:
    tables = describe_inputs(response, config)
    if inputs:
        tables["Configuration"] = inputs_from_mapping(inputs)
    return ReportContent(
        title=title or default_title(response, config),
        verdict=verdict(response),
        inputs=tables,
        key_figures=key_figures(response),
        assumptions=assumptions(response),
        warnings=warnings(response),
        events=event_rows(response),
        source=getattr(config, "source", None),
    )
