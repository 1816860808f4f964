"""What a report says about a stack of blocks (:class:`rocking.stack.StackResponse`): the verdict
naming the block that fell or slid to an edge, the checks (every block upright, none slid to the
edge, each interface's friction, at rest, energy balance), a table per block and per interface,
the two figures' texts, the inputs, the model's assumptions and the symbols.

It fills the same :class:`~rocking.report.content.ReportContent` as a single statue's report, so
the HTML page and the A4 PDF are drawn by the same code.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..results.wording import need_text
from .content import (
    FAIL,
    NOT_APPLICABLE,
    NOT_CHECKED,
    PASS,
    UNDETERMINED,
    Check,
    DataTable,
    FigureText,
    ReportContent,
    Rows,
    _energy_check,
    _g,
    _mm,
    _motion_rows,
    _time,
    check_clearance,
    sliding_check,
    inputs_from_mapping,
    provenance,
)

__all__ = ["block_label", "build_stack_content", "stack_checks", "stack_verdict", "stack_verdict_class"]

#: A slippable interface reaches its μs, then slips: its need may pass μs by the event's tolerance.
_FRICTION_TOLERANCE = 1e-6
#: Statuses of a run that broke the engine's own invariants (a corner sunk, friction that gave
#: energy): its verdict is undetermined whatever fell in it.
_NOT_A_RESULT = ("lost_contact", "friction_gained")


# ------------------------------------------------------------------------------------ naming
def block_label(stack: Any, k: int) -> str:
    """"block 2 (statue)" for block index ``k`` (0 = on the floor), "block 2" if it has no name."""
    name = stack.blocks[k].name
    return f"block {k + 1} ({name})" if name else f"block {k + 1}"


def _below(stack: Any, k: int) -> str:
    return "the floor" if k == 0 else block_label(stack, k - 1)


def _capital(text: str) -> str:
    return text[:1].upper() + text[1:]


def _fallen(response: Any) -> list[tuple[float, int]]:
    """(overturn time, block index) of every block that overturned, earliest first."""
    return sorted((b["overturn_time"], k) for k, b in enumerate(response.blocks) if b["overturned"])


def _edge_block(response: Any) -> int | None:
    """The block whose corner reached the edge of the one below (the run stopped there)."""
    if response.status != "slid_past_edge" or not len(response.events):
        return None
    return int(response.events[-1, 1])  # the engine's last event names it


def _undetermined(response: Any) -> bool:
    return not _fallen(response) and response.status != "completed" and not response.settled_by_energy


# ----------------------------------------------------------------------------------- verdict
def _motion_words(response: Any) -> str:
    """Which block rocked and which slid the most, in a few words."""
    stack, blocks = response.stack, response.blocks
    rocked = [k for k, b in enumerate(blocks) if b["first_rocking_time"] is not None]
    slid = [k for k, b in enumerate(blocks) if b["first_sliding_time"] is not None and b["peak_sliding"] > 0]
    if rocked:
        k = max(rocked, key=lambda i: blocks[i]["peak_rotation"])
        rock = (f"{block_label(stack, k)} rocks the most, up to {math.degrees(blocks[k]['peak_rotation']):.2f}° "
                f"on {_below(stack, k)}")
    else:
        rock = "no block rocks"
    if slid:
        k = max(slid, key=lambda i: blocks[i]["peak_sliding"])
        slide = (f"{block_label(stack, k)} slides the most, {_mm(blocks[k]['peak_sliding'])} on {_below(stack, k)} "
                 f"(residual {_mm(blocks[k]['residual_sliding'])})")
    else:
        slide = "no block slides"
    return f"{rock}; {slide}"


def stack_verdict(response: Any) -> str:
    """One sentence naming the block that overturned first, or the block that slid to the edge of
    the one below, or saying that no block overturned (and which rocked and slid the most).

    >>> stack_verdict(response)  # doctest: +SKIP
    'Block 2 (statue) overturns at t = 2.12 s; the run ends there.'
    """
    stack, end = response.stack, float(response.end_time)
    if response.status in _NOT_A_RESULT:
        # the run broke its own invariants: whatever fell in it, nothing is claimed
        return f"Undetermined: {response.verdict.removeprefix('undetermined: ')}."
    fallen = _fallen(response)
    if fallen:
        t, k = fallen[0]
        others = [block_label(stack, i) for _, i in fallen[1:]]
        also = f" ({', '.join(others)} too)" if others else ""
        return f"{_capital(block_label(stack, k))} overturns at t = {t:.2f} s{also}; the run ends there."
    edge = _edge_block(response)
    if edge is not None:
        return (f"Undetermined: {block_label(stack, edge)} slid to the edge of {_below(stack, edge)} at "
                f"t = {end:.2f} s, where the model stops (treat it as falling off); until then no block overturned.")
    body = _motion_words(response)
    if response.status == "still_moving" and response.settled_by_energy:
        return (f"No block overturns: the block is still moving at t = {end:.2f} s, when the run ended, but with "
                f"less energy than it needs to overturn, on a floor that has stopped, so it cannot fall any more; "
                f"{body}.")
    if response.status == "still_moving":
        return (f"Undetermined: the stack is still moving at t = {end:.2f} s, when the run ended (raise "
                f"simulation.free_time_limit or simulation.duration for a verdict); until then no block "
                f"overturned: {body}.")
    if response.status != "completed":
        return (f"Undetermined: the simulation stopped early at t = {end:.2f} s ({response.status}); until then "
                f"no block overturned: {body}.")
    return f"No block overturns; {body}; everything is at rest at t = {end:.2f} s."


def stack_verdict_class(response: Any, report_checks: list[Check] | None = None) -> str:
    """"fails" (a block overturns), "stopped" (undetermined, or standing while a check fails) or
    "safe"."""
    if response.status in _NOT_A_RESULT:
        return "stopped"
    if _fallen(response):
        return "fails"
    if _undetermined(response) or any(c.result == FAIL for c in report_checks or []):
        return "stopped"
    return "safe"


# ------------------------------------------------------------------------------------ checks
def _upright_check(response: Any, k: int) -> Check:
    stack, b = response.stack, response.blocks[k]
    name = f"{block_label(stack, k)} stays upright (no overturn)"
    limit = "|φ| < 90° on what is below"
    peak = f"peak |φ| = {math.degrees(b['peak_rotation']):.2f}°"
    if b["overturned"]:
        return Check(name, f"overturns at t = {b['overturn_time']:.2f} s", limit, FAIL)
    fallen = _fallen(response)
    if fallen:  # the model stops at the first fall: what this block does next is not computed
        t, j = fallen[0]
        return Check(name, f"{peak} until the run ended at the fall of {block_label(stack, j)} at t = {t:.2f} s",
                     limit, UNDETERMINED)
    if _undetermined(response):
        return Check(name, f"{peak} until t = {response.end_time:.2f} s, when the run ended", limit, UNDETERMINED)
    return Check(name, peak, limit, PASS)


def _edge_check(response: Any) -> Check:
    stack = response.stack
    name, limit = "no block slid to the edge of the one below", "every corner stays on the face below"
    edge = _edge_block(response)
    if edge is not None:
        return Check(name, f"{block_label(stack, edge)} reached the edge of {_below(stack, edge)} at "
                     f"t = {response.end_time:.2f} s", limit, FAIL, warning=(
                         f"{_capital(block_label(stack, edge))} slid to the edge of {_below(stack, edge)}: the run "
                         "stops there (stop_at_edge); treat it as falling off."))
    if response.first_past_edge is not None:
        t, k = response.first_past_edge
        return Check(name, f"{block_label(stack, k)} went past the edge of {_below(stack, k)} at t = {t:.2f} s",
                     limit, FAIL, warning=(
                         f"{_capital(block_label(stack, k))} slid past the edge of {_below(stack, k)} at t = {t:.2f} s "
                         "and hung over it: give it more room or more friction on that face."))
    fallen = _fallen(response)
    if fallen:
        return Check(name, f"none before the fall at t = {fallen[0][0]:.2f} s", limit, PASS)
    if _undetermined(response):
        return Check(name, f"none until t = {response.end_time:.2f} s, when the run ended", limit, UNDETERMINED)
    return Check(name, "none", limit, PASS)


def _friction_check(response: Any, k: int, summary_interface: Mapping[str, Any]) -> Check:
    """The friction interface ``k`` needed while it stuck, against its μs (a slippable interface
    slips once it needs μs, and that slip is simulated)."""
    stack = response.stack
    need = float(summary_interface["required_friction"])
    name = f"friction {summary_interface['name']} needs while it sticks ≤ its μs"
    fr = stack.interfaces[k].friction
    if fr is None:
        return Check(name, need_text(need), "no μs given (assumed never to slip)", NOT_CHECKED)
    limit = f"μs = {fr.mu_s:g}"
    if need <= fr.mu_s * (1 + _FRICTION_TOLERANCE):
        slip = float(summary_interface["slip_path"])
        value = need_text(need) + (f" (it slipped {_mm(slip)}: simulated)" if slip > 0 else "")
        return Check(name, value, limit, PASS)
    return Check(name, need_text(need), limit, FAIL, warning=(
        f"Interface {summary_interface['name']} needed a friction coefficient of {need_text(need)}, more than its "
        f"μs = {fr.mu_s:g}, without slipping."))


def _rest_check(response: Any) -> Check:
    name, limit = "run ends at rest (a verdict, not undetermined)", ("at rest after the floor motion, or too little "
                                                                    "energy left to overturn")
    fallen = _fallen(response)
    if fallen:
        return Check(name, f"ended by the overturn at t = {fallen[0][0]:.2f} s", limit, NOT_APPLICABLE)
    verdict = response.verdict
    return Check(name, verdict, limit, FAIL if verdict.startswith("undetermined") else PASS)


def _clearance_check(response: Any, clearance: float | None) -> Check | None:
    """Block 1's peak sliding on the floor against the free space around it."""
    stack = response.stack
    if clearance is None and stack.interfaces[0].friction is None:
        return None  # nothing slides on the floor and no free space was given
    label = block_label(stack, 0)
    return sliding_check(label, f"peak sliding of {label} on the floor", float(response.blocks[0]["peak_sliding"]),
                         clearance, _undetermined(response))


def stack_checks(response: Any, clearance: float | None = None) -> list[Check]:
    """The pass/fail checks of a stack run: every block upright, no block slid to the edge of the
    one below, each interface's friction against its μs, (block 1's sliding against
    ``clearance``, m), ended at rest, energy balance."""
    s = response.summary()
    found = [_upright_check(response, k) for k in range(response.stack.n)]
    found.append(_edge_check(response))
    found += [_friction_check(response, k, f) for k, f in enumerate(s["interfaces"])]
    found += [_clearance_check(response, clearance), _rest_check(response), _energy_check(s)]
    return [c for c in found if c is not None]


def _warnings(response: Any, found: list[Check]) -> list[str]:
    out = []
    if response.status == "still_moving" and not response.settled_by_energy:
        out.append(f"The run ended at t = {response.end_time:.2f} s while the stack still moved: the verdict is "
                   "undetermined (raise simulation.free_time_limit or simulation.duration).")
    elif response.status == "friction_gained":
        from ..stack.simulate import friction_gain_time

        out.append(f"From t = {friction_gain_time(response):.3f} s friction gave the stack energy, which Coulomb "
                   "friction cannot: a contact held in tension slipped (Painlevé's paradox), so the run is not a "
                   "result (docs/theory/stack.md §5).")
    elif response.status not in ("completed", "overturned", "slid_past_edge"):
        out.append(f"The simulation stopped early at t = {response.end_time:.2f} s (status {response.status}).")
    for k, b in enumerate(response.blocks):
        if b.get("tension_held_time") is not None:
            out.append(f"From t = {b['tension_held_time']:.3f} s the contact under {block_label(response.stack, k)} "
                       "carried a small tension (Painlevé's paradox of Coulomb friction: released, the contact "
                       "would sink; the model holds it until it pushes again).")
        if b.get("restitution_reduced_time") is not None:
            label = block_label(response.stack, k)
            out.append(f"At t = {b['restitution_reduced_time']:.3f} s an impact under {label} did not restitute "
                       f"as its coefficient asks: the full rebound of {label} and the blocks standing on it "
                       "would have left no consistent contact mode (a block resting on it pulling on its corner) "
                       "or would have created energy (a rebound pushing the block below faster than it slows "
                       f"the block above), so it acted on {label} alone or was scaled down "
                       "(docs/theory/stack.md §6).")
    return out + [c.warning for c in found if c.result == FAIL and c.warning]


# ------------------------------------------------------------------------------------ tables
def _two_decimals(x: float) -> str:
    """x with two decimals, never "-0.00" (a residual of −1 µm is no sliding back)."""
    return f"{round(x, 2) + 0.0:.2f}"


def _block_table(response: Any) -> DataTable:
    rows = []
    for k, b in enumerate(response.blocks):
        rows.append((
            block_label(response.stack, k),
            f"at {b['overturn_time']:.3f} s" if b["overturned"] else "no",
            _two_decimals(math.degrees(b["peak_rotation"])),
            _two_decimals(1e3 * b["peak_sliding"]),
            _two_decimals(1e3 * b["residual_sliding"]),
            _time(b["first_rocking_time"]),
            _time(b["first_sliding_time"]),
        ))
    return DataTable("Blocks, from the floor up (rotation φ and sliding on what is below)",
                     ("block", "overturned", "peak |φ| (°)", "peak sliding (mm)", "residual sliding (mm)",
                      "rocking from", "sliding from"),
                     tuple(rows), (0.2, 0.14, 0.11, 0.13, 0.14, 0.14, 0.14))


def _interface_table(response: Any, summary: Mapping[str, Any]) -> DataTable:
    rows = []
    for k, f in enumerate(summary["interfaces"]):
        fr = response.stack.interfaces[k].friction
        rows.append((f["name"], need_text(f["required_friction"]), "never slips" if fr is None else f"{fr.mu_s:g}",
                     _two_decimals(1e3 * f["slip_path"]), str(f["impacts"])))
    return DataTable("Interfaces, from the floor up", ("interface", "friction needed", "μs given",
                                                       "slip path (mm)", "impacts"),
                     tuple(rows), (0.3, 0.18, 0.18, 0.18, 0.16))


def _block_inputs(stack: Any) -> DataTable:
    rows = []
    for k, b in enumerate(stack.blocks):
        inertia = f"{b.centroidal_inertia:.4g}" + ("" if b.inertia is not None else " (uniform)")
        rows.append((block_label(stack, k), f"{b.width:g}", f"{b.height:g}", f"{b.mass:g}", inertia, f"{b.offset:g}",
                     f"{math.degrees(math.atan2(b.width, b.height)):.2f}°"))
    return DataTable("Inputs: blocks, from the floor up", ("block", "width B (m)", "height H (m)", "mass m (kg)",
                                                            "inertia J_G (kg·m²)", "offset (m)", "α = atan(B/H)"),
                     tuple(rows), (0.22, 0.11, 0.11, 0.12, 0.18, 0.11, 0.15), place="inputs")


def _interface_inputs(stack: Any) -> DataTable:
    rows = []
    for k, f in enumerate(stack.interfaces):
        friction = ("none given (never slips)" if f.friction is None
                    else f"μs = {f.friction.mu_s:g}, μk = {f.friction.mu_k:g}")
        r = "Housner's rule (plastic landing)" if f.restitution is None else f"{f.restitution:g} (given)"
        rows.append((f"{_below(stack, k)} – {block_label(stack, k)}", friction, r))
    return DataTable("Inputs: interfaces, from the floor up", ("interface", "friction", "restitution r"),
                     tuple(rows), (0.4, 0.32, 0.28), place="inputs")


def _options_rows(response: Any, options: Any, duration: float | None, source: str | None) -> Rows:
    rows: Rows = []
    if source:
        rows.append(("configuration file", str(source)))
    if options is None:
        return rows + [("simulated", f"until t = {response.end_time:.3f} s")]
    how = (f"simulation.duration = {duration:g} s" if duration is not None
           else f"the motion, then free motion until at rest, at most {options.free_time_limit:g} s more")
    return rows + [
        ("simulated", f"until t = {response.end_time:.3f} s ({how})"),
        ("gravity g", f"{options.gravity:g} m/s²"),
        ("impact rule", options.impact),
        ("tolerances rtol / atol", f"{options.rtol:g} / {options.atol:g}"),
        ("largest step", f"{options.max_step:g} s"),
        ("output spacing", "default" if options.save_dt is None else f"{options.save_dt:g} s"),
    ]


_EVENT_NAMES = {-1: "impact", -2: "mode change (with another interface's)", 0: "contact change at an end",
                1: "contact change at the other end", 2: "stick or slip begins", 3: "stick or slip begins",
                4: "overturn", 5: "edge reached", 6: "overlap ends"}
_NORMAL_STATES = {0: "open", 1: "rocking", 2: "flat"}
_TANGENTIAL_STATES = {0: "stuck", 1: "slipping towards +x", -1: "slipping towards −x"}


def _event_rows(response: Any, limit: int = 500) -> list[tuple[str, str, str, str]]:
    """(t, interface, event, state after) of the engine's events."""
    stack = response.stack
    rows = []
    for t, k, slot, normal, tangential, _ in response.events[:limit]:
        k = int(k)
        rows.append((f"{t:.4f}", f"{_below(stack, k)} – {block_label(stack, k)}",
                     _EVENT_NAMES.get(int(slot), str(int(slot))),
                     "—" if int(normal) not in _NORMAL_STATES else
                     f"{_NORMAL_STATES[int(normal)]}, {_TANGENTIAL_STATES.get(int(tangential), '?')}"))
    return rows


# ----------------------------------------------------------------------------------- figures
def _figure_texts(response: Any, summary: Mapping[str, Any], with_motion: bool) -> list[FigureText]:
    fallen = _fallen(response)
    stack = response.stack
    if fallen:
        end = f"{_capital(block_label(stack, fallen[0][1]))} overturns at t = {fallen[0][0]:.2f} s (dashed line)."
    elif _edge_block(response) is not None:
        end = (f"{_capital(block_label(stack, _edge_block(response)))} reaches the edge of the block below at "
               f"t = {response.end_time:.2f} s (dotted line), where the run stops.")
    else:
        end = f"The run ends at t = {response.end_time:.2f} s."
    floor = " and the floor acceleration a_g" if with_motion else ""
    response_fig = FigureText(
        1, "Response",
        f"Figure 1 shows every block's motion against time: {_motion_words(response)}, with {summary['impacts']} "
        f"impact{'' if summary['impacts'] == 1 else 's'} in all. {end}",
        f"Rotation φ of each block on what it stands on (°), its sliding along that face (mm){floor} against time "
        "t; one colour per block, from the floor up; dashed lines: overturns; dotted: a block that slid to an edge.",
    )
    work = float(response.input_work[-1]) if len(response.t) else math.nan
    friction = float(response.friction_loss[-1]) if len(response.t) else math.nan
    impact = float(response.impact_loss[-1]) if len(response.t) else math.nan
    energy_fig = FigureText(
        2, "Energy",
        f"Figure 2 follows the change of the stack's mechanical energy. The floor puts in the work W = "
        f"{_g(work, 4, 'J')}; friction dissipates {_g(friction, 4, 'J')} and impacts {_g(impact, 4, 'J')}. The "
        f"ledger W − D (dashed) lies on E − E₀ to a relative error of {summary['energy_balance_error']:.1e}, the "
        "energy balance check.",
        "Change of the mechanical energy E − E₀ (kinetic plus potential) of all the blocks against time t, with the "
        "ledger W − D: input work of the floor less the dissipation by friction and impacts.",
    )
    return [response_fig, energy_fig]


def _assumptions(response: Any, options: Any) -> list[str]:
    stack = response.stack
    given = [f.restitution for f in stack.interfaces if f.restitution is not None]
    out = [
        f"{stack.n} rigid rectangular blocks in a vertical plane, listed from the floor up, each standing on the one "
        "below (block 1 on the floor); contacts only between neighbours.",
        "Every interface may stick, slip with Coulomb friction (μs to start, μk while slipping), rock on either end "
        "of its overlap and lift off; an interface without friction given never slips.",
    ]
    if options is None or options.impact == "coulomb":
        rule = ("with the restitution r given (the relative angular velocity after over before, the block below "
                "held)" if given else "plastic on the new corner, which gives Housner's value")
        if given and len(given) < stack.n:
            rule += " where it is given, plastic on the new corner (Housner's value) elsewhere"
        out.append(f"Impact when an interface lands on its other end: {rule}; the impulses are bounded by Coulomb "
                   "friction.")
    else:
        out.append("Impact when an interface lands on its other end: the paper's rule φ̇⁺ = r·φ̇⁻, every other "
                   "relative velocity unchanged.")
    out.append("A block overturns when its rotation on what is below reaches |φ| = 90°, and the run stops at the "
               "first overturn. Sliding past the edge of the block below is not modelled: the run stops when a "
               "corner reaches it.")
    if options is not None:
        out.append(f"Event-driven integration (DOP853, rtol = {options.rtol:g}, atol = {options.atol:g}); "
                   f"g = {options.gravity:g} m/s²; the stack starts at rest.")
    return out


SYMBOLS: Rows = [
    ("B, H", "width and height of a block, m"),
    ("m, J_G", "mass of a block, kg; its moment of inertia about its centre of mass, kg·m²"),
    ("offset", "horizontal position of a block's centre relative to the centre of the block below, m"),
    ("α", "α = atan(B/H) of a block, rad"),
    ("φ", "rotation of a block on what is below (rad, > 0 clockwise, towards +x); it overturns at |φ| = 90°"),
    ("μs, μk", "static and kinetic friction coefficients of an interface"),
    ("r", "coefficient of restitution of an interface: relative angular velocity after an impact over before"),
    ("a_g", "horizontal acceleration of the floor, m/s²"),
    ("g", "acceleration of gravity, m/s²"),
    ("E, E₀", "mechanical energy (kinetic plus potential) of all the blocks, and at the start, J"),
    ("W, D", "work put in by the floor; energy dissipated by friction and impacts, J"),
    ("t", "time, s"),
]


# ----------------------------------------------------------------------------------- content
def _title(response: Any, config: Any) -> str:
    names = ", ".join(response.stack.names)
    text = f"Rocking analysis: a stack of {response.stack.n} blocks ({names})"
    source = getattr(config, "source", None)
    if source:
        from pathlib import Path

        text += f" ({Path(source).name})"
    return text


def build_stack_content(response: Any, config: Any = None, *, title: str | None = None,
                        inputs: Mapping[str, Any] | None = None, clearance: float | None = None) -> ReportContent:
    """Everything the report of a stack run says.

    Parameters
    ----------
    response : rocking.stack.StackResponse
    config : rocking.io.config.StackConfig, optional
        Where the motion and the options are read from (without it the inputs show the blocks
        and interfaces only).
    title : str, optional
    inputs : mapping, optional
        Extra inputs shown as a "Configuration" table.
    clearance : float, optional
        Free space around block 1 on the floor, m: its peak sliding is checked against it.
    """
    s = response.summary()
    motion = options = duration = None
    if config is not None:
        _, motion, options, duration = config.to_specs()
    found = stack_checks(response, check_clearance(clearance))
    tables: dict[str, Rows] = {}
    if motion is not None:
        tables["Motion"] = _motion_rows(motion, options.gravity)
    tables["Options"] = _options_rows(response, options, duration, getattr(config, "source", None))
    if inputs:
        tables["Configuration"] = inputs_from_mapping(inputs)
    fallen = _fallen(response)
    key_figures: Rows = [
        ("blocks, from the floor up", ", ".join(response.stack.names)),
        ("first block to overturn", f"{block_label(response.stack, fallen[0][1])} at t = {fallen[0][0]:.3f} s"
         if fallen else "none"),
        ("impacts, all interfaces", str(s["impacts"])),
        ("simulated until", f"{response.end_time:.3f} s ({response.status.replace('_', ' ')})"),
        ("energy balance error", f"{s['energy_balance_error']:.1e}"),
    ]
    return ReportContent(
        title=title or _title(response, config),
        verdict=stack_verdict(response),
        inputs=tables,
        key_figures=key_figures,
        assumptions=_assumptions(response, options),
        warnings=_warnings(response, found),
        source=getattr(config, "source", None),
        checks=found,
        figures=_figure_texts(response, s, motion is not None),
        symbols=list(SYMBOLS),
        provenance=provenance(config),
        events=_event_rows(response),
        event_header=("t (s)", "interface", "event", "after"),
        tables=[_block_table(response), _interface_table(response, s), _block_inputs(response.stack),
                _interface_inputs(response.stack)],
    )


def stack_figures(response: Any, config: Any = None) -> list[Any]:
    """The report's two figures (matplotlib Figures), in the order of its figure texts."""
    from ..viz.stack_plots import plot_stack_energy, plot_stack_response

    motion = config.to_specs()[1] if config is not None else None
    return [plot_stack_response(response, motion=motion), plot_stack_energy(response).figure]
