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
import os
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
    "outcome_summary",
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
        "settled_by_energy": s["settled_by_energy"],
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
#: The page that explains every verdict of the table (linked from paper_outcomes.md).
DOCS_PAGE = "docs/paper-case-studies.md"

#: The columns of the Markdown table and what each means (the key under the table).
MD_COLUMNS: tuple[tuple[str, str], ...] = (
    ("Fig.", "the paper's figure, i.e. the case of its Table 2. A row naming several figures "
             "(\"11a–12b\") stands for cases whose rows read the same: the statue alone does not depend "
             "on its mass (the paper's C4)."),
    ("run", "which model: the statue on the pedestal with this library's default model (full floor normal "
            "force, Coulomb-bounded impact) or with the paper's simplifications (N = M·g, θ̇⁺ = r·θ̇⁻); or "
            "the statue alone, on a floor it can never slide on (μ = ∞, the paper's baseline) or on the "
            "pedestal's floor friction."),
    ("t = 0⁺", "the motion just after the start: *slide* (the body on the floor slides, the statue stands "
               "on it), *rock* (the statue rocks, the body under it holds), *slide+rock* (both), *rest*."),
    ("overturned (\\|θ\\| = π/2)", "*yes (t)* if the statue fell, |θ| reaching π/2 at time t; *no* otherwise."),
    ("\\|θ\\| > α", "*yes (t)* if the statue passed its static stability limit α = atan(B/H), first at time t."),
    ("peak θ/α", "the largest |θ| divided by α: 1 is the stability limit; a fall reaches π/2 ÷ α."),
    ("peak u (m)", "the largest sliding on the floor, relative to the floor, of the pedestal (or of the "
                   "statue alone)."),
    ("residual u (m)", "that sliding at the end of the run."),
    ("impacts", "how many times the statue struck its base on landing from a rock."),
    ("first rock / slide (s)", "when the statue first rocked / the body on the floor first slid; – never."),
    ("μ top", "the largest friction ratio |Px|/Py needed under the statue (on the pedestal's top face, or on "
              "the floor for the statue alone), while |θ| ≤ α: above the available μs the statue would slip."),
    ("warn.", "how many of the model's warnings the run raised (their texts are in paper_outcomes.csv, column "
              "warning_text); \"still moving when the run ended\" is one of them."),
    ("at the end", "*moving* if the statue or the pedestal had not come to rest when the paper's window "
                   "closed (whether it would still fall later is not decided); *moving, cannot fall* if, as the "
                   "floor stops there, the statue has less energy left than it needs to overturn "
                   "(docs/verdicts.md); *at rest*; or *fallen*."),
    ("paper says", "the paper's statement for this statue: alone it *rocks* or *overturns*; on the pedestal "
                   "its response *does not change significantly*, *overturning avoided* or *overturning only "
                   "delayed*."),
    ("agrees (π/2)", "whether this run bears the statement out when \"overturning\" means |θ| = π/2 (the "
                     "paper never defines it). *rocks*: peak θ/α ≥ {visible} and no fall; *overturns*: falls; "
                     "*overturning avoided*: no fall; *overturning only delayed*: falls later than the statue "
                     "alone with μ = ∞; *does not change significantly*: peak θ/α within ±{change:.0%} of the "
                     "statue alone with μ = ∞ and the same verdict. **no** marks a disagreement."),
    ("agrees (α)", "the same judgement when \"overturning\" means passing α (|θ| > α)."),
)


def _t(flag: bool, time: float | None) -> str:
    return f"yes ({time:.2f} s)" if flag and time is not None else "no"


def _opt_time(time: float | None) -> str:
    return "–" if time is None else f"{time:.3f}"


def _yes(flag: bool) -> str:
    return "yes" if flag else "**no**"


def _end_state(row: Mapping[str, Any]) -> str:
    if row["overturned"]:
        return "fallen"
    if row["still_moving"]:
        return "moving, cannot fall" if row.get("settled_by_energy") else "moving"
    return "at rest" if row["status"] == "completed" else str(row["status"])


def _cells(row: Mapping[str, Any]) -> list[str]:
    """The table cells of one row after its Fig. cell."""
    first = f"{_opt_time(row['first_rocking_time'])} / {_opt_time(row['first_sliding_time'])}"
    return [
        row["variant_label"],
        row["initial_regime"].lower().replace("_", "+"),
        _t(row["overturned"], row["overturn_time"]),
        _t(row["exceeded_alpha"], row["exceeded_alpha_time"]),
        f"{row['peak_rotation_over_alpha']:.3f}",
        f"{row['peak_sliding']:.3f}",
        f"{row['residual_sliding']:+.3f}",
        str(row["impacts"]),
        first,
        f"{row['required_top_friction']:.3f}",
        str(row["warnings"]),
        _end_state(row),
        row["paper_outcome"],
        _yes(row["agrees"]),
        _yes(row["agrees_alpha_criterion"]),
    ]


def _case_span(names: Sequence[str], order: Sequence[str]) -> str:
    """"11a–12b" for consecutive cases (three or more, in ``order``), else "9a, 10a"."""
    positions = [order.index(n) for n in names]
    if len(names) >= 3 and positions == list(range(positions[0], positions[0] + len(names))):
        return f"{names[0]}–{names[-1]}"
    return ", ".join(names)


def _table(rows: Sequence[Mapping[str, Any]], order: Sequence[str]) -> list[str]:
    """Markdown lines of one table; rows of one run that read the same in every cell but Fig. are
    folded into one."""
    folded: dict[tuple[str, ...], list[str]] = {}
    for row in rows:
        folded.setdefault((row["variant"], *_cells(row)), []).append(row["case"])
    header = "| " + " | ".join(name for name, _ in MD_COLUMNS) + " |"
    lines = [header, "|" + "---|" * len(MD_COLUMNS)]
    for (_, *cells), names in folded.items():
        lines.append(f"| {_case_span(names, order)} | " + " | ".join(cells) + " |")
    return lines


def _counts(rows: Sequence[Mapping[str, Any]], variant: str) -> dict[str, Any]:
    mine = [r for r in rows if r["variant"] == variant]
    return {
        "cases": len(mine),
        "fell": [r["case"] for r in mine if r["overturned"]],
        "passed_alpha": [r["case"] for r in mine if r["exceeded_alpha"]],
        "peak": max((r["peak_rotation_over_alpha"] for r in mine if not r["overturned"]), default=0.0),
    }


def _failed_claims(rows: Sequence[Mapping[str, Any]], key: str) -> str:
    """The paper's statements the rows contradict, in words: "on the pedestal, “x” (9a, 9b) and
    “y” (11a); alone, “z” (10a)"."""
    groups: dict[str, dict[str, list[str]]] = {"on the pedestal": {}, "alone": {}}
    for r in rows:
        if not r[key]:
            where = "alone" if r["variant"].startswith("alone") else "on the pedestal"
            groups[where].setdefault(r["paper_outcome"], []).append(r["case"])
    return "; ".join(
        f"{where}, " + " and ".join(f"“{claim}” ({', '.join(cases)})" for claim, cases in claims.items())
        for where, claims in groups.items()
        if claims
    )


def outcome_summary(rows: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """The numbers the summary of ``paper_outcomes.md`` states, computed from the table's rows.

    The paper's claims are judged as the paper compares: the statue on the pedestal with the
    default model (``pedestal`` rows) and the statue alone with μ = ∞ (its baseline), one
    statement each per case.
    """
    judged = [r for r in rows if r["variant"] in ("pedestal", "alone_infinite_friction")]
    return {
        "pedestal": _counts(rows, "pedestal"),
        "pedestal_paper_options": _counts(rows, "pedestal_paper_options"),
        "alone_infinite_friction": _counts(rows, "alone_infinite_friction"),
        "alone_floor_friction": _counts(rows, "alone_floor_friction"),
        "claims": len(judged),
        "claims_hold": sum(bool(r["agrees"]) for r in judged),
        "claims_hold_alpha": sum(bool(r["agrees_alpha_criterion"]) for r in judged),
        "failed": _failed_claims(judged, "agrees"),
        "failed_alpha": _failed_claims(judged, "agrees_alpha_criterion"),
        "runs": len(rows),
        "still_moving": sum(bool(r["still_moving"]) for r in rows),
        "settled": sum(bool(r["still_moving"]) and bool(r.get("settled_by_energy")) for r in rows),
    }


def _listed(cases: Sequence[str]) -> str:
    return f" ({', '.join(cases)})" if cases else ""


def _summary_lines(rows: Sequence[Mapping[str, Any]]) -> list[str]:
    s = outcome_summary(rows)
    ped, opt = s["pedestal"], s["pedestal_paper_options"]
    alone, floor = s["alone_infinite_friction"], s["alone_floor_friction"]

    def survives(c: dict[str, Any]) -> str:
        return (f"survives in {c['cases'] - len(c['fell'])} of {c['cases']} cases{_listed(c['fell'])}"
                if c["fell"] else f"survives in {c['cases']} of {c['cases']} cases")

    lines = [
        f"- **On the pedestal**, the statue {survives(ped)} and passes its stability limit α in "
        f"{len(ped['passed_alpha'])} of {ped['cases']}{_listed(ped['passed_alpha'])}; its largest peak is "
        f"{ped['peak']:.3f}α. With the paper's simplifications (N = M·g, θ̇⁺ = r·θ̇⁻) it {survives(opt)} "
        "and "
        f"passes α in {len(opt['passed_alpha'])} of {opt['cases']}{_listed(opt['passed_alpha'])}; largest peak "
        f"{opt['peak']:.3f}α.",
        f"- **Alone, on a floor it cannot slide on** (the paper's baseline), the statue falls in "
        f"{len(alone['fell'])} of {alone['cases']} cases{_listed(alone['fell'])} and passes α in "
        f"{len(alone['passed_alpha'])} of {alone['cases']}{_listed(alone['passed_alpha'])}.",
        f"- **Alone, on the pedestal's floor friction**, it falls in {len(floor['fell'])} of {floor['cases']} "
        f"cases{_listed(floor['fell'])} and passes α in {len(floor['passed_alpha'])} of "
        f"{floor['cases']}{_listed(floor['passed_alpha'])}.",
        f"- **The paper's claims** (one on the statue alone and one on the pedestal per case, judged with "
        f"the default model against the baseline) hold in {s['claims_hold']} of {s['claims']} if "
        f"\"overturning\" means falling (|θ| = π/2), and in {s['claims_hold_alpha']} of {s['claims']} if it "
        f"means passing α.",
    ]
    if s["failed"]:
        lines.append(f"  - Not borne out with |θ| = π/2: {s['failed']}.")
    if s["failed_alpha"]:
        lines.append(f"  - Not borne out with |θ| > α: {s['failed_alpha']}.")
    if s["still_moving"]:
        open_ = s["still_moving"] - s["settled"]
        lines.append(
            f"- {s['still_moving']} of {s['runs']} runs were still moving when the paper's window closed, where its "
            f"floor motion ends. In {s['settled']} of them the statue has less energy left than it needs to "
            f"overturn, so it cannot fall afterwards; the verdict of the other {open_} covers that window only."
        )
    return lines


def outcome_table_markdown(rows: Sequence[Mapping[str, Any]], *, docs_link: str = DOCS_PAGE) -> str:
    """The outcome table as a GitHub Markdown document: a title, a summary computed from ``rows``,
    one table for the statue on the pedestal and one for the statue alone (rows that read the same
    folded into one), the key of the columns and a link (``docs_link``) to the page that explains
    every verdict."""
    if not rows:
        return "# The paper's case studies, rerun\n\nNo case was run.\n"
    first = rows[0]
    order = list(dict.fromkeys(r["case"] for r in rows))
    durations = sorted({r["duration"] for r in rows})
    window = f"{durations[0]:g} s" if len(durations) == 1 else f"{durations[0]:g}–{durations[-1]:g} s"
    lines = [
        "# The paper's case studies (Figs. 9–12), rerun",
        "",
        f"{len(order)} statues of the paper's Table 2, each alone and on a pedestal of "
        f"m1 = {TABLE_1.pedestal_mass:g} kg that slides on the floor (μs = {TABLE_1.static_friction}, "
        f"μk = {TABLE_1.kinetic_friction}), under ẍg = A·{first['form']} ωt with A = {first['amplitude']} m/s², "
        f"ω = {first['omega']:.4f} s⁻¹, "
        f"for the paper's window of {window}; g = {first['gravity']} m/s², r = {first['restitution']}.",
        "",
        "## Summary",
        "",
        *_summary_lines(rows),
        "",
        f"Why each statement holds or fails, case by case: [{DOCS_PAGE}]({docs_link}).",
        "",
        "## The statue on the pedestal",
        "",
        *_table([r for r in rows if not r["variant"].startswith("alone")], order),
        "",
        "## The statue alone on the floor",
        "",
        *_table([r for r in rows if r["variant"].startswith("alone")], order),
        "",
        "## Key",
        "",
    ]
    for name, meaning in MD_COLUMNS:
        text = meaning.format(visible=VISIBLE_ROCKING, change=SIGNIFICANT_CHANGE) if "{" in meaning else meaning
        lines.append(f"- **{name}**: {text}")
    return "\n".join(lines) + "\n"


def _csv_value(v: Any) -> Any:
    if v is None:
        return ""
    if isinstance(v, float) and math.isinf(v):
        return "inf"
    return v


def _docs_link(md_dir: Path) -> str:
    """Where :data:`DOCS_PAGE` lies seen from ``md_dir``: a relative path when this library runs
    from its source tree (the page exists on disk), else the page's path in that tree."""
    page = Path(__file__).resolve().parents[3] / DOCS_PAGE
    if not page.is_file():
        return DOCS_PAGE
    try:
        return Path(os.path.relpath(page, md_dir.resolve())).as_posix()
    except ValueError:  # another drive (Windows): no relative path exists
        return page.as_uri()


def write_outcome_table(rows: Sequence[Mapping[str, Any]], out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``paper_outcomes.csv`` (every column) and ``paper_outcomes.md`` (title, summary,
    tables, key and a link to the explanations, see :func:`outcome_table_markdown`) into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    csv_path, md_path = out / "paper_outcomes.csv", out / "paper_outcomes.md"
    fields = list(rows[0].keys()) if rows else []
    with csv_path.open("w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: _csv_value(v) for k, v in row.items()})
    md_path.write_text(outcome_table_markdown(rows, docs_link=_docs_link(out)), encoding="utf-8")
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
