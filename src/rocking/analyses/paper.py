"""The seed paper's case studies (its §3.2, Tables 1–2, Figs. 9–12), rerun with correct mechanics.

The paper ("Rocking of a rigid block freestanding on a flat pedestal") studies a statue standing
on a squat pedestal that slides on the floor, under ẍg = A·cos ωt (Table 1), for eight
statue geometries and masses (Table 2). For each case it compares the statue on the pedestal with
the statue alone and states an outcome ("does not change significantly", "overturning avoided",
"overturning only delayed").

:func:`run_paper_cases` reruns every case in four variants:

``pedestal``
    statue on the pedestal, this library's default model: full floor normal force
    (``normal_force="full"``) and a Coulomb-bounded impact impulse (``impact="coulomb"``).
``pedestal_paper_options``
    the same with the paper's simplifications: N = M·g (P1) and θ̇⁺ = r·θ̇⁻ with the pedestal
    velocity unchanged at an impact (the paper's Eq. 1, O19).
``alone_infinite_friction``
    the statue alone on the floor, never sliding: the paper's baseline (its Figs. a.3).
``alone_floor_friction``
    the statue alone on the same floor friction as the pedestal (μs = 0.4, μk = 0.3; P17).

Each run gives one row of a tidy table (a list of dicts, one per case and variant). The row also
carries the paper's stated outcome and whether our result agrees, judged twice because the
paper never defines "overturning" (P14): once with |θ| = π/2 (the statue falls) and once with
|θ| > α (the statue passes its static stability limit).

:func:`friction_sweep` is the design study of ``docs/design-insight.md``: peak rotation and
sliding versus the pedestal's floor friction.

Examples
--------
>>> from rocking.analyses.paper import PAPER_CASES, case_named
>>> [c.name for c in PAPER_CASES]
['9a', '9b', '10a', '10b', '11a', '11b', '12a', '12b']
>>> case_named("10a").height, case_named("10a").duration
(4.0, 25.0)
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..contact.friction import Friction
from ..excitation.harmonic import Harmonic
from ..models.bodies import Pedestal, Statue, System
from ..models.regimes import Regime
from ..results.response import Response
from ..simulation import Options, simulate

__all__ = [
    "TABLE_1",
    "PAPER_CASES",
    "VARIANTS",
    "PaperCase",
    "Table1",
    "case_named",
    "paper_motion",
    "variant_setup",
    "run_case",
    "outcome_rows",
    "run_paper_cases",
    "outcome_table_markdown",
    "write_outcome_table",
    "outcome_dataset",
    "friction_sweep",
    "verdict_sensitivity",
    "sensitivity_table_markdown",
]

#: Relative change of the peak rotation below which the pedestal "does not change significantly"
#: the statue's response (the paper's words for Fig. 9; it gives no number).
SIGNIFICANT_CHANGE = 0.25

#: Peak θ/α below which a statue is not counted as "rocking" in the comparison with the paper
#: (a few impacts at 0.3° would be invisible in its figures).
VISIBLE_ROCKING = 0.05

Progress = Callable[[int, int, str], None]


# ---------------------------------------------------------------------------------------------
# Table 1 and Table 2 as data
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Table1:
    """Parameters common to all the paper's analyses (its Table 1), SI units."""

    static_friction: float = 0.40  #: μs of the pedestal–floor interface
    kinetic_friction: float = 0.30  #: μk of the pedestal–floor interface
    width: float = 1.0  #: statue width B, m
    pedestal_mass: float = 1.0  #: m1, kg
    restitution: float = 0.8  #: r = θ̇⁺/θ̇⁻ (the paper's Eq. 1), for every slenderness (P6)
    frequency: float = 1.2  #: f, Hz (sets the duration: cycles/f)
    amplitude: float = 6.75  #: A, m/s²
    paper_angular_frequency: float = 7.53  #: ω as printed, s⁻¹ (2π·1.2 = 7.5398; P13)
    gravity: float = 9.81  #: g used by the paper, m/s²

    @property
    def friction(self) -> Friction:
        return Friction(static=self.static_friction, kinetic=self.kinetic_friction)


TABLE_1 = Table1()


@dataclass(frozen=True, slots=True)
class PaperCase:
    """One line of the paper's Table 2, with the outcome the paper states for it.

    ``alone_claim`` is what the paper says of the statue alone ("rocks" or "overturns"),
    ``pedestal_claim`` what it says of the statue on the pedestal ("does not change
    significantly", "overturning avoided" or "overturning only delayed"), from derivation.md's
    table of claims. For 10a/10b the overturning of the statue alone is implied, not stated.
    """

    name: str  #: "9a" … "12b" (the figure)
    statue_mass: float  #: m2, kg
    height: float  #: H, m
    cycles: int  #: number of forcing cycles
    alone_claim: str
    pedestal_claim: str

    @property
    def figure(self) -> str:
        return f"Fig. {self.name}"

    @property
    def duration(self) -> float:
        """cycles/f, s (30 cycles → 25 s, 24 cycles → 20 s)."""
        return self.cycles / TABLE_1.frequency

    @property
    def aspect_ratio(self) -> float:
        """B/H."""
        return TABLE_1.width / self.height

    def statue(self, friction: Friction | None = None, restitution: float | None = TABLE_1.restitution) -> Statue:
        return Statue(
            width=TABLE_1.width, height=self.height, mass=self.statue_mass, restitution=restitution, friction=friction
        )


ROCKS, OVERTURNS = "rocks", "overturns"
NO_CHANGE, AVOIDED, DELAYED = "does not change significantly", "overturning avoided", "overturning only delayed"

PAPER_CASES: tuple[PaperCase, ...] = (
    PaperCase("9a", 1.0, 2.0, 30, ROCKS, NO_CHANGE),
    PaperCase("9b", 1.0, 3.0, 30, ROCKS, NO_CHANGE),
    PaperCase("10a", 1.0, 4.0, 30, OVERTURNS, AVOIDED),
    PaperCase("10b", 1.0, 5.0, 30, OVERTURNS, AVOIDED),
    PaperCase("11a", 2.0, 4.0, 24, OVERTURNS, DELAYED),
    PaperCase("11b", 3.0, 4.0, 24, OVERTURNS, DELAYED),
    PaperCase("12a", 4.0, 4.0, 24, OVERTURNS, AVOIDED),
    PaperCase("12b", 6.0, 4.0, 24, OVERTURNS, AVOIDED),
)

#: The four runs per case, in the order of the table.
VARIANTS: tuple[str, ...] = ("pedestal", "pedestal_paper_options", "alone_infinite_friction", "alone_floor_friction")

VARIANT_LABELS = {
    "pedestal": "on pedestal (full N, Coulomb impact)",
    "pedestal_paper_options": "on pedestal (paper: N = Mg, θ̇⁺ = rθ̇⁻)",
    "alone_infinite_friction": "alone, μ = ∞ (paper's baseline)",
    "alone_floor_friction": "alone, μs 0.4 / μk 0.3",
}


def case_named(name: str) -> PaperCase:
    """The case of Table 2 for figure ``name`` ("9a" … "12b")."""
    for case in PAPER_CASES:
        if case.name == name:
            return case
    raise KeyError(f"no paper case {name!r}; choose from {[c.name for c in PAPER_CASES]}")


def paper_motion(case: PaperCase, omega: float | None = None, form: str = "cos") -> Harmonic:
    """ẍg = A·cos ωt for the case's number of cycles.

    ``omega=None`` uses ω = 2π·f = 7.5398 s⁻¹; ``omega=7.53`` reproduces the paper's rounded value
    (P13). The duration is cycles/f either way. ``form="sin"`` starts from zero instead of jumping
    to A at t = 0⁺ (a sensitivity check, not the paper's forcing).
    """
    return Harmonic(
        amplitude=TABLE_1.amplitude,
        frequency=TABLE_1.frequency,
        cycles=case.cycles,
        form=form,
        angular_frequency=omega,
    )


def variant_setup(case: PaperCase, variant: str, restitution: float | None = TABLE_1.restitution) -> tuple[System, Options]:
    """The system and model options of one variant (see the module docstring)."""
    g = TABLE_1.gravity
    pedestal = Pedestal(mass=TABLE_1.pedestal_mass, friction=TABLE_1.friction)
    if variant == "pedestal":
        return System(statue=case.statue(restitution=restitution), pedestal=pedestal), Options(gravity=g)
    if variant == "pedestal_paper_options":
        options = Options(gravity=g, normal_force="paper", impact="paper")
        return System(statue=case.statue(restitution=restitution), pedestal=pedestal), options
    if variant == "alone_infinite_friction":
        return System(statue=case.statue(restitution=restitution)), Options(gravity=g)
    if variant == "alone_floor_friction":
        return System(statue=case.statue(friction=TABLE_1.friction, restitution=restitution)), Options(gravity=g)
    raise ValueError(f"unknown variant {variant!r}; choose from {VARIANTS}")


def run_case(
    case: PaperCase,
    omega: float | None = None,
    *,
    variants: Sequence[str] = VARIANTS,
    form: str = "cos",
    restitution: float | None = TABLE_1.restitution,
    save: bool = True,
    progress: Callable[[str], None] | None = None,
) -> dict[str, Response]:
    """Simulate one case in the given variants; returns ``{variant: Response}``.

    Each run lasts exactly the paper's window (its number of cycles), as the paper's runs do; a
    run still moving at its end says so (``still_moving``) rather than being followed further."""
    motion = paper_motion(case, omega, form)
    out = {}
    for variant in variants:
        system, options = variant_setup(case, variant, restitution)
        out[variant] = simulate(system, motion, duration=motion.duration, options=options, save=save)
        if progress is not None:
            progress(variant)
    return out


# ---------------------------------------------------------------------------------------------
# One row per (case, variant), and the comparison with the paper
# ---------------------------------------------------------------------------------------------
def _initial_regime(response: Response) -> str:
    """Regime at t = 0⁺: the first saved sample, or the state before the first event."""
    if response.regime.size:
        return Regime(int(response.regime[0])).name
    events = response.events
    return events[0].before.name if events else "REST"


def _row(case: PaperCase, variant: str, response: Response) -> dict[str, Any]:
    s = response.summary()
    system, options = response.system, response.options
    friction = system.floor_friction
    return {
        "case": case.name,
        "figure": case.figure,
        "variant": variant,
        "variant_label": VARIANT_LABELS[variant],
        "statue_mass": case.statue_mass,
        "height": case.height,
        "aspect_ratio": case.aspect_ratio,
        "pedestal_mass": system.pedestal.mass if system.pedestal is not None else None,
        "floor_static_friction": friction.mu_s if friction is not None else math.inf,
        "floor_kinetic_friction": friction.mu_k if friction is not None else math.inf,
        "restitution": system.statue.effective_restitution,
        "normal_force": options.normal_force,
        "impact": options.impact,
        "amplitude": response.motion.amplitude,
        "omega": response.motion.omega,
        "form": response.motion.form,
        "gravity": options.gravity,
        "duration": response.duration,
        "alpha": response.alpha,
        "initial_regime": _initial_regime(response),
        "overturned": s["overturned"],
        "overturn_time": s["overturn_time"],
        "exceeded_alpha": s["exceeded_alpha_time"] is not None,
        "exceeded_alpha_time": s["exceeded_alpha_time"],
        "peak_rotation": s["peak_rotation"],
        "peak_rotation_over_alpha": s["peak_rotation_over_alpha"],
        "peak_sliding": s["peak_sliding"],
        "residual_sliding": s["residual_sliding"],
        "impacts": s["impacts"],
        "first_rocking_time": s["first_rocking_time"],
        "first_sliding_time": s["first_sliding_time"],
        "required_top_friction": s["required_top_friction"],
        "impact_floor_friction_needed": s["impact_floor_friction_needed"],
        "warnings": len(s["warnings"]),
        "warning_text": "; ".join(s["warnings"]),
        "status": s["status"],
        "still_moving": s["still_moving"],
    }


def _judge(row: dict[str, Any], baseline: dict[str, Any], claim: str) -> tuple[bool, bool]:
    """Does the row agree with the paper's claim? (|θ| = π/2 criterion, |θ| > α criterion)."""
    rocked = row["peak_rotation_over_alpha"] >= VISIBLE_ROCKING
    if claim == ROCKS:
        return rocked and not row["overturned"], rocked and not row["exceeded_alpha"]
    if claim == OVERTURNS:
        return row["overturned"], row["exceeded_alpha"]
    if claim == AVOIDED:
        return not row["overturned"], not row["exceeded_alpha"]
    if claim == DELAYED:
        # Falls, but later than the statue alone (the paper's baseline).
        def later(flag: str, time: str) -> bool:
            return bool(row[flag] and baseline[flag] and row[time] > baseline[time])

        return later("overturned", "overturn_time"), later("exceeded_alpha", "exceeded_alpha_time")
    if claim == NO_CHANGE:
        ref = baseline["peak_rotation_over_alpha"]
        close = abs(row["peak_rotation_over_alpha"] - ref) <= SIGNIFICANT_CHANGE * ref
        return (
            close and row["overturned"] == baseline["overturned"],
            close and row["exceeded_alpha"] == baseline["exceeded_alpha"],
        )
    raise ValueError(f"unknown claim {claim!r}")


def outcome_rows(case: PaperCase, responses: Mapping[str, Response]) -> list[dict[str, Any]]:
    """Rows of the outcome table for one case, from :func:`run_case`'s responses.

    The statue-on-pedestal rows are judged against the paper's baseline, the statue alone with
    infinite friction (``responses`` must contain ``"alone_infinite_friction"`` for them).
    """
    rows = {v: _row(case, v, r) for v, r in responses.items()}
    out = []
    for variant, row in rows.items():
        claim = case.alone_claim if variant.startswith("alone") else case.pedestal_claim
        baseline = rows.get("alone_infinite_friction")
        if baseline is None and claim in (NO_CHANGE, DELAYED):
            raise ValueError("judging a pedestal row needs the 'alone_infinite_friction' run")
        row["paper_outcome"] = claim
        row["agrees"], row["agrees_alpha_criterion"] = _judge(row, baseline, claim)
        out.append(row)
    return out


def run_paper_cases(
    omega: float | None = None,
    progress: Progress | None = None,
    *,
    cases: Iterable[PaperCase] = PAPER_CASES,
    form: str = "cos",
    restitution: float | None = TABLE_1.restitution,
    responses: dict[tuple[str, str], Response] | None = None,
) -> list[dict[str, Any]]:
    """Run the paper's eight cases in the four variants; return the tidy outcome table.

    Parameters
    ----------
    omega : float, optional
        Angular frequency of ẍg = A·cos ωt, s⁻¹. ``None``: 2π·1.2 = 7.5398; the paper prints 7.53.
    progress : callable, optional
        Called as ``progress(done, total, label)`` after each simulation.
    cases : iterable of PaperCase
        Subset of :data:`PAPER_CASES` (default: all eight).
    form : {"cos", "sin"}
        Forcing kind (the paper: cos, which jumps to A at t = 0⁺; P13).
    restitution : float or None
        r of every statue (the paper: 0.8; ``None``: Housner's 1 − 1.5 sin²α; P6).
    responses : dict, optional
        If given, filled with ``{(case, variant): Response}`` (for the figures).

    Returns
    -------
    list of dict
        One row per case and variant (keys: see ``docs/paper-case-studies.md``), with the paper's
        stated outcome (``paper_outcome``) and whether we agree with it (``agrees`` with
        overturning meaning |θ| = π/2, ``agrees_alpha_criterion`` meaning |θ| > α).
    """
    cases = list(cases)
    total = len(cases) * len(VARIANTS)
    done = 0
    rows: list[dict[str, Any]] = []
    for case in cases:

        def tick(variant: str, case=case) -> None:
            nonlocal done
            done += 1
            if progress is not None:
                progress(done, total, f"{case.figure} {variant}")

        result = run_case(case, omega, form=form, restitution=restitution, progress=tick)
        if responses is not None:
            responses.update({(case.name, v): r for v, r in result.items()})
        rows.extend(outcome_rows(case, result))
    return rows


# ---------------------------------------------------------------------------------------------
# Output: Markdown, CSV, xarray
# ---------------------------------------------------------------------------------------------
def _t(flag: bool, time: float | None) -> str:
    return f"yes ({time:.2f} s)" if flag and time is not None else "no"


def _opt_time(time: float | None) -> str:
    return "–" if time is None else f"{time:.3f}"


def _yes(flag: bool) -> str:
    return "yes" if flag else "**no**"


def outcome_table_markdown(rows: Sequence[Mapping[str, Any]]) -> str:
    """The outcome table as GitHub Markdown (one line per case and variant)."""
    header = (
        "| Fig. | run | t = 0⁺ | overturned (\\|θ\\| = π/2) | \\|θ\\| > α | peak θ/α | peak u (m) "
        "| residual u (m) | impacts | first rock / slide (s) | μ top | warn. | paper says "
        "| agrees (π/2) | agrees (α) |"
    )
    lines = [header, "|" + "---|" * header.count(" | ") + "---|"]
    for r in rows:
        first = f"{_opt_time(r['first_rocking_time'])} / {_opt_time(r['first_sliding_time'])}"
        fell = _t(r["overturned"], r["overturn_time"]) + (" (still moving at the end)" if r.get("still_moving") else "")
        lines.append(
            f"| {r['case']} | {r['variant_label']} | {r['initial_regime'].lower().replace('_', '+')} "
            f"| {fell} | {_t(r['exceeded_alpha'], r['exceeded_alpha_time'])} "
            f"| {r['peak_rotation_over_alpha']:.3f} | {r['peak_sliding']:.3f} | {r['residual_sliding']:+.3f} "
            f"| {r['impacts']} | {first} | {r['required_top_friction']:.3f} | {r['warnings']} "
            f"| {r['paper_outcome']} | {_yes(r['agrees'])} | {_yes(r['agrees_alpha_criterion'])} |"
        )
    first = rows[0] if rows else None
    if first is not None:
        lines.append("")
        lines.append(
            f"A = {first['amplitude']} m/s², ω = {first['omega']:.4f} s⁻¹, ẍg = A·{first['form']} ωt, "
            f"g = {first['gravity']} m/s², r = {first['restitution']}, pedestal m1 = {TABLE_1.pedestal_mass} kg "
            f"on μs = {TABLE_1.static_friction}, μk = {TABLE_1.kinetic_friction}. "
            "u: sliding of the body on the floor (pedestal, or the statue alone). "
            "μ top: largest friction ratio |Px|/Py needed under the statue (sampled at every solver stage and at impacts, while |θ| ≤ α). "
            "Each run lasts the paper's window; \"still moving at the end\" marks a run whose statue or pedestal had "
            "not come to rest when the window closed: whether it would still fall is not decided by that window."
        )
    return "\n".join(lines) + "\n"


def _csv_value(v: Any) -> Any:
    if v is None:
        return ""
    if isinstance(v, float) and math.isinf(v):
        return "inf"
    return v


def write_outcome_table(rows: Sequence[Mapping[str, Any]], out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``paper_outcomes.csv`` (every column) and ``paper_outcomes.md`` into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    csv_path, md_path = out / "paper_outcomes.csv", out / "paper_outcomes.md"
    fields = list(rows[0].keys()) if rows else []
    with csv_path.open("w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: _csv_value(v) for k, v in row.items()})
    md_path.write_text(outcome_table_markdown(rows), encoding="utf-8")
    return csv_path, md_path


def outcome_dataset(rows: Sequence[Mapping[str, Any]]):
    """The outcome table as an ``xarray.Dataset`` with dimensions (case, variant)."""
    import xarray as xr

    cases = list(dict.fromkeys(r["case"] for r in rows))
    variants = list(dict.fromkeys(r["variant"] for r in rows))
    index = {(r["case"], r["variant"]): r for r in rows}
    skip = {"case", "variant"}
    data = {}
    for key in rows[0]:
        if key in skip:
            continue
        values = [[index[(c, v)][key] if (c, v) in index else None for v in variants] for c in cases]
        sample = rows[0][key]
        if isinstance(sample, bool):
            arr = np.array(values, dtype=bool)
        elif isinstance(sample, (int, float)) or sample is None:
            arr = np.array([[np.nan if x is None else x for x in line] for line in values], dtype=float)
        else:
            arr = np.array(values, dtype=object).astype(str)
        data[key] = (("case", "variant"), arr)
    return xr.Dataset(data, coords={"case": cases, "variant": variants})


# ---------------------------------------------------------------------------------------------
# Design study: peak response versus the pedestal's floor friction
# ---------------------------------------------------------------------------------------------
def friction_sweep(
    static_friction: Sequence[float] | None = None,
    *,
    kinetic_ratio: float = 0.75,
    height: float = 4.0,
    width: float = TABLE_1.width,
    statue_mass: float = 1.0,
    pedestal_mass: float = TABLE_1.pedestal_mass,
    restitution: float | None = TABLE_1.restitution,
    amplitude: float = TABLE_1.amplitude,
    frequency: float = TABLE_1.frequency,
    cycles: int = 30,
    omega: float | None = None,
    options: Options | None = None,
    progress: Progress | None = None,
) -> list[dict[str, Any]]:
    """Statue on pedestal under ẍg = A·cos ωt for a range of pedestal floor frictions μs.

    μk = ``kinetic_ratio``·μs. Defaults: the paper's case 10a (H = 4 m, tan α = 0.25,
    m1 = m2 = 1 kg, r = 0.8, A = 6.75 m/s², f = 1.2 Hz, 30 cycles) with the default model and
    g = 9.81. If μs ≤ tan α the statue cannot start to rock (O17): a stuck pedestal transmits at
    most μs·g and a sliding one μk·g.

    Returns
    -------
    list of dict
        One row per μs with the pedestal run (``peak_rotation_over_alpha``, ``peak_sliding``,
        ``overturned``, ``overturn_time``, ``exceeded_alpha_time``, ``first_rocking_time``, ...)
        and the statue alone with infinite friction as reference (``alone_*`` keys, the same in
        every row).

    Examples
    --------
    >>> rows = friction_sweep([0.2], cycles=2)
    >>> rows[0]["rocked"], rows[0]["tan_alpha"]
    (False, 0.25)
    """
    if static_friction is None:
        static_friction = np.round(np.arange(0.05, 0.8001, 0.01), 4)
    mus = [float(m) for m in static_friction]
    options = options if options is not None else Options(gravity=TABLE_1.gravity)
    motion = Harmonic(amplitude=amplitude, frequency=frequency, cycles=cycles, angular_frequency=omega)
    statue = Statue(width=width, height=height, mass=statue_mass, restitution=restitution)
    # The paper's fixed window (its number of cycles), as in run_case.
    alone = simulate(System(statue=statue), motion, duration=motion.duration, options=options, save=False).summary()
    rows = []
    for i, mu in enumerate(mus):
        pedestal = Pedestal(mass=pedestal_mass, friction=Friction(static=mu, kinetic=kinetic_ratio * mu))
        s = simulate(System(statue=statue, pedestal=pedestal), motion, duration=motion.duration, options=options,
                     save=False).summary()
        rows.append(
            {
                "static_friction": mu,
                "kinetic_friction": kinetic_ratio * mu,
                "tan_alpha": width / height,
                "height": height,
                "statue_mass": statue_mass,
                "pedestal_mass": pedestal_mass,
                "amplitude": amplitude,
                "omega": motion.omega,
                "rocked": s["first_rocking_time"] is not None,
                "first_rocking_time": s["first_rocking_time"],
                "peak_rotation_over_alpha": s["peak_rotation_over_alpha"],
                "peak_sliding": s["peak_sliding"],
                "overturned": s["overturned"],
                "overturn_time": s["overturn_time"],
                "exceeded_alpha_time": s["exceeded_alpha_time"],
                "still_moving": s["still_moving"],
                "warnings": len(s["warnings"]),
                "alone_overturned": alone["overturned"],
                "alone_overturn_time": alone["overturn_time"],
                "alone_exceeded_alpha_time": alone["exceeded_alpha_time"],
                "alone_peak_rotation_over_alpha": alone["peak_rotation_over_alpha"],
            }
        )
        if progress is not None:
            progress(i + 1, len(mus), f"μs = {mu:.3f}")
    return rows


# ---------------------------------------------------------------------------------------------
# How fragile are the overturning verdicts? (P6, P13)
# ---------------------------------------------------------------------------------------------
SENSITIVITY_SETTINGS: tuple[tuple[str, float | None, str, float | None], ...] = (
    ("paper (ω = 2π·1.2, cos, r = 0.8)", None, "cos", 0.8),
    ("ω = 7.53", TABLE_1.paper_angular_frequency, "cos", 0.8),
    ("Housner r", None, "cos", None),
    ("ω = 7.53, Housner r", TABLE_1.paper_angular_frequency, "cos", None),
    ("sin ωt", None, "sin", 0.8),
)


def verdict_sensitivity(
    settings: Sequence[tuple[str, float | None, str, float | None]] = SENSITIVITY_SETTINGS,
    progress: Progress | None = None,
) -> list[dict[str, Any]]:
    """Rerun the statue alone (μ = ∞) and on the pedestal (default model) for each setting
    ``(label, omega, form, restitution)``; one row per case and setting."""
    variants = ("pedestal", "alone_infinite_friction")
    total = len(settings) * len(PAPER_CASES) * len(variants)
    done = 0
    rows = []
    for label, omega, form, restitution in settings:
        for case in PAPER_CASES:
            res = run_case(case, omega, variants=variants, form=form, restitution=restitution, save=False)
            ped, alone = res["pedestal"].summary(), res["alone_infinite_friction"].summary()
            rows.append(
                {
                    "setting": label,
                    "case": case.name,
                    "alone_overturn_time": alone["overturn_time"],
                    "alone_exceeded_alpha_time": alone["exceeded_alpha_time"],
                    "alone_peak_rotation_over_alpha": alone["peak_rotation_over_alpha"],
                    "pedestal_overturn_time": ped["overturn_time"],
                    "pedestal_exceeded_alpha_time": ped["exceeded_alpha_time"],
                    "pedestal_peak_rotation_over_alpha": ped["peak_rotation_over_alpha"],
                    "pedestal_first_rocking_time": ped["first_rocking_time"],
                    "pedestal_first_sliding_time": ped["first_sliding_time"],
                }
            )
            done += len(variants)
            if progress is not None:
                progress(done, total, f"{label} {case.name}")
    return rows


def sensitivity_table_markdown(rows: Sequence[Mapping[str, Any]]) -> str:
    """Cases × settings: statue alone / on pedestal, as "falls at t" or peak θ/α."""

    def cell(t_fall: float | None, peak: float) -> str:
        return f"falls {t_fall:.1f} s" if t_fall is not None else f"{peak:.2f}α"

    settings = list(dict.fromkeys(r["setting"] for r in rows))
    cases = list(dict.fromkeys(r["case"] for r in rows))
    index = {(r["setting"], r["case"]): r for r in rows}
    lines = ["| Fig. | " + " | ".join(settings) + " |", "|---|" + "---|" * len(settings)]
    for c in cases:
        cells = []
        for s in settings:
            r = index[(s, c)]
            cells.append(
                cell(r["alone_overturn_time"], r["alone_peak_rotation_over_alpha"])
                + " / "
                + cell(r["pedestal_overturn_time"], r["pedestal_peak_rotation_over_alpha"])
            )
        lines.append(f"| {c} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
