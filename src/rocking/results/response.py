"""What a simulation returns: time series, regime timeline, events, outcome, energy ledger."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from ..models import parameters as P
from ..models.regimes import EventKind, Regime
from ..models.transitions import EV_IMPACT, EV_SETTLE
from ..solver import compiled as C

_STATUS = {
    C.STATUS_COMPLETED: ("completed", "simulated until everything was at rest (or to the requested duration)"),
    C.STATUS_OVERTURNED: ("overturned", "the statue overturned (|θ| reached π/2)"),
    C.STATUS_MAX_EVENTS: ("max_events", "stopped: too many events (raise simulation.max_events)"),
    C.STATUS_SINGULAR: ("singular", "slide-rock equations singular (Painlevé indeterminacy, μk ≥ 2/3?)"),
    C.STATUS_STEP_FAILED: ("step_failed", "step size underflow"),
    C.STATUS_STILL_MOVING: ("still_moving", "still moving when the run ended: raise simulation.free_time_limit "
                                            "(or simulation.duration) for a verdict"),
    C.STATUS_INTERRUPTED: ("interrupted", "interrupted (Ctrl-C or SIGTERM)"),
}

#: A run in which a body would have left its support while the statue stood (see lift_off_time).
LIFTED_OFF = "lifted_off"
_LIFTED_OFF_MESSAGE = ("a body would leave its support while the statue stood (the warning above says which), "
                       "which the two-body model does not follow (it keeps every body on its support): what "
                       "follows is not a result; model it as a stack of blocks ([[blocks]]), whose engine follows "
                       "the flight")
#: A run in which an impact needed more floor friction than μs and the Coulomb impact law held
#: the body on the floor anyway (see held_impact_time).
IMPACT_BEYOND_FRICTION = "impact_beyond_friction"
_IMPACT_BEYOND_FRICTION_MESSAGE = (
    "an impact needed more floor friction than μs and no outcome of the impact law within friction was consistent "
    "(the warning above says when and how much); the two-body model held the body on the floor anyway, so what "
    "follows is not a result; model it as a stack of blocks ([[blocks]]), whose engine solves each impact with "
    "friction at both corners")
# the solver's statuses a lift-off while standing, or an impact held beyond friction, overrides:
# the run went on after the model's result had ended (to rest, to an overturn, or round a loop of
# events under a floor falling faster than gravity, where the model's statue topples under the
# reversed weight)
_OVERRIDDEN_BY_LIFT_OFF = (C.STATUS_COMPLETED, C.STATUS_STILL_MOVING, C.STATUS_MAX_EVENTS, C.STATUS_OVERTURNED)


def lift_off_time(raw: np.ndarray) -> float | None:
    """The first instant (s) the floor's normal force or the statue's base force reached zero
    while the statue stood (before |θ| first passed α), or None. From then on a body would leave
    its support: the pedestal (or a statue alone) would jump off the floor, or the statue off its
    pedestal. The two-body model keeps them in contact, so the rest of the run is not a result,
    and a run with such an instant says so: status ``lifted_off``, an undetermined verdict, never
    safe, and no overturn either (one that follows is the model's, not the statue's). A lift-off
    after α is part of a fall and changes nothing."""
    times = [float(raw[i]) for i in (C.S_N_NONPOSITIVE, C.S_PY_NONPOSITIVE) if not math.isnan(raw[i])]
    if not times:
        return None
    t = min(times)
    exceeded = float(raw[C.S_EXCEED_TIME])
    return None if exceeded == exceeded and t >= exceeded else t


def held_impact_time(raw: np.ndarray) -> float | None:
    """The first instant (s) of an impact that needed more floor friction than μs, at which the
    Coulomb impact law (docs/theory/derivation.md §6) found no consistent outcome within friction and held the
    body on the floor anyway, or None (never, or under the paper's law, which holds such bodies by
    design and says so in a warning). The rest of the run follows a floor impulse friction cannot
    give, so it is not a result: status ``impact_beyond_friction``, an undetermined verdict, never
    safe, and no overturn either. Seen with a restitution well below Housner's on a low floor
    friction (:meth:`Response.impact_friction_shortfalls`)."""
    return _opt(raw[C.S_HELD_IMPACT])


def model_end_time(raw: np.ndarray) -> float | None:
    """The first instant (s) the two-body model's result ends (:func:`lift_off_time`,
    :func:`held_impact_time`), or None."""
    times = [t for t in (lift_off_time(raw), held_impact_time(raw)) if t is not None]
    return min(times) if times else None


def status_of(raw: np.ndarray) -> tuple[str, str]:
    """(status, message) of a run from the solver's raw summary: the solver's own, or
    ``lifted_off`` (see :func:`lift_off_time`), or ``impact_beyond_friction`` (see
    :func:`held_impact_time`), whichever came first."""
    code = int(raw[C.S_STATUS])
    if code in _OVERRIDDEN_BY_LIFT_OFF:
        lift, held = lift_off_time(raw), held_impact_time(raw)
        if lift is not None and (held is None or lift <= held):
            return LIFTED_OFF, _LIFTED_OFF_MESSAGE
        if held is not None:
            return IMPACT_BEYOND_FRICTION, _IMPACT_BEYOND_FRICTION_MESSAGE
    return _STATUS[code]


# A floor acceleration above this many g is almost surely a units or scaling mistake.
PGA_WARNING_G = 5.0


class Impact(NamedTuple):
    """One impact of the statue (θ = 0, pivot switch). Velocities in m/s and rad/s, energy in J."""

    time: float
    u_dot_before: float
    u_dot_after: float
    theta_dot_before: float
    theta_dot_after: float
    energy_lost: float
    friction_needed: float  # |Fx|/Fy of the floor impulse


class Event(NamedTuple):
    time: float
    kind: EventKind
    before: Regime
    after: Regime


def split_saved_codes(codes: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The solver's saved codes → (regime codes 0–3, pivot, slip direction), per sample. The pivot
    is the sign of the rotation the statue rocks towards (0: it does not rock); the slip
    direction is the sign of the sliding velocity of the body on the floor (0: it does not slide).
    """
    codes = np.asarray(codes, dtype=np.int8)
    regime = (codes & 3).astype(np.int8)
    pivot = np.where(regime & 1, np.where(codes & C.SAVED_NEGATIVE_PIVOT, -1, 1), 0).astype(np.int8)
    slip = np.where(regime & 2, np.where(codes & C.SAVED_NEGATIVE_SLIP, -1, 1), 0).astype(np.int8)
    return regime, pivot, slip


def _opt(x: float) -> float | None:
    return None if math.isnan(x) else float(x)


SUMMARY_FIELDS = (
    "overturned", "overturn_time", "exceeded_alpha_time", "peak_rotation", "peak_rotation_over_alpha",
    "peak_sliding", "residual_sliding", "impacts", "first_rocking_time", "first_sliding_time",
    "required_top_friction", "impact_floor_friction_needed", "top_slip_time", "pedestal_uplift_time",
    "impact_beyond_friction_time", "energy_balance_error", "status", "end_time", "still_moving", "settled_by_energy",
    "verdict",
)

#: How a run still moving at its end, yet settled by its energy, is described (verdicts, reports).
SETTLED_TEXT = "with less energy than the statue needs to overturn, on a floor that has stopped"


def settled_by_energy(raw: np.ndarray) -> bool:
    """Whether a run still moving at its end can no longer overturn: the floor has stopped for
    good, the statue is inside ±α and has less energy than it needs to reach ±α, and no impact
    law that adds energy is in use (:func:`rocking.solver.compiled._cannot_overturn`). Such a run
    did not overturn, and never will: its verdict is decided. False for any other status (a
    lift-off or an impact held beyond friction overrides it: what follows them is not a result)."""
    return status_of(raw)[0] == "still_moving" and float(raw[C.S_SETTLED]) == 1.0


def verdict_text(status: str, overturn_time: float | None, end_time: float, model_end: float | None = None,
                 settled: bool = False) -> str:
    """The one-line verdict: "overturned at t = …", "did not overturn; at rest at t = …", "did not
    overturn; still moving at t = … with less energy than …" (``settled``: see
    :func:`settled_by_energy`), or "undetermined: …" whenever the run could not tell (still
    moving, the solver stopped, or the two-body model's result ended at ``model_end``, s: a body
    would have left its support, or an impact needed more floor friction than there is)."""
    if status == LIFTED_OFF:
        return (f"undetermined: a body would leave its support at t = {model_end:.3f} s, which the two-body model "
                "does not follow")
    if status == IMPACT_BEYOND_FRICTION:
        return (f"undetermined: an impact at t = {model_end:.3f} s needed more floor friction than μs, which the "
                "two-body model's impact law cannot give")
    if status == "overturned":
        return f"overturned at t = {overturn_time:.3f} s"
    if status == "completed":
        return f"did not overturn; at rest at t = {end_time:.3f} s"
    if status == "still_moving" and settled:
        return f"did not overturn; still moving at t = {end_time:.3f} s, {SETTLED_TEXT}"
    if status == "still_moving":
        return f"undetermined: still moving at t = {end_time:.3f} s"
    return f"undetermined: the solver stopped at t = {end_time:.3f} s ({status})"


def summary_values(raw: np.ndarray, alpha: float) -> dict[str, Any]:
    """The summary dictionary (keys ``SUMMARY_FIELDS``) from the solver's raw summary vector."""
    status = status_of(raw)[0]
    end_time = float(raw[C.S_T_END])
    settled = settled_by_energy(raw)
    return {
        "overturned": status == "overturned",
        "overturn_time": _opt(raw[C.S_OVERTURN_TIME]),
        "exceeded_alpha_time": _opt(raw[C.S_EXCEED_TIME]),
        "peak_rotation": float(raw[C.S_PEAK_ROTATION]),
        "peak_rotation_over_alpha": float(raw[C.S_PEAK_ROTATION] / alpha),
        "peak_sliding": float(raw[C.S_PEAK_SLIDING]),
        "residual_sliding": float(raw[C.S_RESIDUAL_SLIDING]),
        "impacts": int(raw[C.S_IMPACTS]),
        "first_rocking_time": _opt(raw[C.S_FIRST_ROCK]),
        "first_sliding_time": _opt(raw[C.S_FIRST_SLIDE]),
        "required_top_friction": float(raw[C.S_TOP_RATIO]),
        "impact_floor_friction_needed": float(raw[C.S_IMPACT_FLOOR_RATIO]),
        # the first instants the model's assumptions fail (derivation §3.5; the warnings say it in words)
        "top_slip_time": _opt(raw[C.S_TOP_SLIP]),
        "pedestal_uplift_time": _opt(raw[C.S_UPLIFT]),
        "impact_beyond_friction_time": held_impact_time(raw),
        "energy_balance_error": float(raw[C.S_BALANCE] / raw[C.S_ENERGY_SCALE]),
        "status": status,
        "end_time": end_time,
        "still_moving": status == "still_moving",
        "settled_by_energy": settled,
        "verdict": verdict_text(status, _opt(raw[C.S_OVERTURN_TIME]), end_time, model_end_time(raw), settled),
    }


@dataclass(frozen=True, kw_only=True, eq=False)
class Response:
    """The result of :func:`rocking.simulate`.

    Time series (sampled on a uniform grid merged with the event instants, and ending at
    ``end_time``, the state the verdict judges; at an event both the state before and after
    appear with the same time): ``t`` (s), ``u`` and ``u_dot`` (sliding of
    the body on the floor relative to the floor, m and m/s), ``theta`` and ``theta_dot`` (statue,
    rad and rad/s), ``regime`` (:class:`Regime` codes), ``pivot`` (+1: the statue rocks on its +x
    corner, −1: on its −x corner, 0: it does not rock) and ``slip_direction`` (the sign of the
    sliding velocity, 0: no sliding), the last two as the solver had them (at the onset of
    rocking θ = θ̇ = 0 and of sliding u̇ = 0: the state alone does not say). ``duration`` is the
    longest the run could last (s): the requested duration, or the motion plus
    ``free_time_limit``; ``end_time`` is when it ended.
    """

    system: Any
    motion: Any
    options: Any
    duration: float
    parameters: np.ndarray = field(repr=False)
    raw_summary: np.ndarray = field(repr=False)
    t: np.ndarray = field(repr=False)
    state: np.ndarray = field(repr=False)
    regime_codes: np.ndarray = field(repr=False)
    event_table: np.ndarray = field(repr=False)
    duration_given: bool = False  # True: ``duration`` was asked for; False: it is the free-motion cap
    #: Per sample, the signs of the regime as the solver had them: ``pivot``, the sign of the
    #: rotation the statue rocks towards (0: not rocking), and ``slip_direction``, that of the
    #: sliding velocity (0: not sliding). Not inferable from the state: at the onset of rocking
    #: θ = θ̇ = 0, at that of sliding u̇ = 0, and just before an impact θ may have crossed 0 by
    #: rounding.
    pivot: np.ndarray = field(repr=False)
    slip_direction: np.ndarray = field(repr=False)

    # -- time series -----------------------------------------------------------------------
    @property
    def u(self) -> np.ndarray:
        return self.state[:, 0]

    @property
    def u_dot(self) -> np.ndarray:
        return self.state[:, 1]

    @property
    def theta(self) -> np.ndarray:
        return self.state[:, 2]

    @property
    def theta_dot(self) -> np.ndarray:
        return self.state[:, 3]

    @property
    def regime(self) -> np.ndarray:
        return self.regime_codes.astype(int)

    @property
    def floor_acceleration(self) -> np.ndarray:
        return self.motion.acceleration(self.t)

    # -- outcome ---------------------------------------------------------------------------
    @property
    def status(self) -> str:
        return status_of(self.raw_summary)[0]

    @property
    def status_message(self) -> str:
        return status_of(self.raw_summary)[1]

    @property
    def alpha(self) -> float:
        return self.system.statue.slenderness

    @property
    def overturned(self) -> bool:
        return self.status == "overturned"

    @property
    def overturn_time(self) -> float | None:
        return _opt(self.raw_summary[C.S_OVERTURN_TIME])

    @property
    def exceeded_alpha_time(self) -> float | None:
        """First time (s) |θ| passed α, beyond which gravity tips the statue further; the start
        time for one released at or beyond α and turning outwards; None if it never did."""
        return _opt(self.raw_summary[C.S_EXCEED_TIME])

    @property
    def peak_rotation(self) -> float:
        return float(self.raw_summary[C.S_PEAK_ROTATION])

    @property
    def events(self) -> list[Event]:
        return [Event(float(r[0]), EventKind(int(r[1])), Regime(int(r[2])), Regime(int(r[3]))) for r in self.event_table]

    @property
    def impacts(self) -> list[Impact]:
        rows = self.event_table[np.isin(self.event_table[:, 1], (EV_IMPACT, EV_SETTLE))]
        return [Impact(*(float(v) for v in (r[0], r[4], r[5], r[6], r[7], r[8], r[9]))) for r in rows]

    @property
    def energy(self) -> dict[str, float]:
        """Energy ledger at the end, J: input work of the floor's inertial forces, friction and
        impact dissipation, and the largest balance error |E − E0 − W + D| over the run."""
        s = self.raw_summary
        return {
            "input_work": float(s[C.S_W_INPUT]),
            "friction_dissipation": float(s[C.S_D_FRICTION]),
            "impact_dissipation": float(s[C.S_D_IMPACT]),
            "balance_error": float(s[C.S_BALANCE]),
            "relative_balance_error": float(s[C.S_BALANCE] / s[C.S_ENERGY_SCALE]),
        }

    @property
    def warnings(self) -> list[str]:
        """Instants where the model's assumptions fail (derivation §3.5), in words."""
        s = self.raw_summary
        out = []
        body = "pedestal" if self.system.pedestal is not None else "block"
        checks = [
            (C.S_N_NONPOSITIVE, f"the floor normal force reached zero (the {body} would jump)"),
            (C.S_PY_NONPOSITIVE, "the statue's base force reached zero (the statue would lift off)"),
            (C.S_TOP_SLIP, "the statue would slip on the pedestal (top-face friction exceeded)"),
            (C.S_UPLIFT, "the pedestal would uplift (normal force outside its base)"),
        ]
        for index, text in checks:
            if not math.isnan(s[index]):
                out.append(f"from t = {s[index]:.4f} s {text}")
        if s[C.S_IMPACT_FLOOR_SHORT] > 0 and self.options.impact == "paper":
            out.append(
                f"{int(s[C.S_IMPACT_FLOOR_SHORT])} impact(s) needed more floor friction than μs "
                f"(up to {s[C.S_IMPACT_FLOOR_RATIO]:.3f}); the paper's impact law ignores this"
            )
        elif s[C.S_IMPACT_FLOOR_SHORT] > 0:
            out.append(self._shortfall_text())
        lifts = self.impact_uplifts()
        if lifts.size:
            out.append(f"from t = {lifts[0]:.4f} s, at {lifts.size} impact(s), the floor's impulse under the pedestal "
                       "falls outside its base: a corner of the pedestal would lift for an instant (or the impact "
                       "restitute less), which the two-body model does not follow; a stack of blocks ([[blocks]]) does")
        if s[C.S_INDETERMINATE] > 0:
            out.append(f"{int(s[C.S_INDETERMINATE])} instant(s) where no regime was strictly consistent")
        if self.status not in ("completed", "overturned") and not self.settled_by_energy:
            out.append(self.status_message)
        if self._ended_before_motion():
            out.append(f"the run ended at t = {self.end_time:.3f} s, before the floor motion did "
                       f"({self.motion.duration:.3f} s): the verdict covers only the simulated part")
        g = self.options.gravity
        pga = float(self.motion.pga)
        if pga > PGA_WARNING_G * g:
            out.append(f"the floor's peak acceleration is {pga / g:.1f} g (above {PGA_WARNING_G:g} g): check the "
                       "record's units and scaling")
        return out

    @property
    def end_time(self) -> float:
        """Time at which the run ended, s."""
        return float(self.raw_summary[C.S_T_END])

    @property
    def still_moving(self) -> bool:
        """True if the run ended while something still moved: its verdict is undetermined."""
        return self.status == "still_moving"

    @property
    def settled_by_energy(self) -> bool:
        """True if the run ended still moving, yet the statue can no longer overturn
        (:func:`settled_by_energy`): the verdict is "did not overturn"."""
        return settled_by_energy(self.raw_summary)

    def _ended_before_motion(self) -> bool:
        return self.status == "completed" and self.end_time < float(self.motion.duration) - 1e-9

    @property
    def verdict(self) -> str:
        """One line: "overturned at t = … s", "did not overturn; at rest at t = … s", or
        "undetermined: …" (still moving at the end, the run stopped before the floor motion did,
        or the solver stopped)."""
        if self._ended_before_motion():
            return (f"undetermined: the run ended at t = {self.end_time:.3f} s, before the floor motion "
                    f"({float(self.motion.duration):.3f} s)")
        return verdict_text(self.status, self.overturn_time, self.end_time, model_end_time(self.raw_summary),
                            self.settled_by_energy)

    def summary(self) -> dict[str, Any]:
        """The summary contract of ``rocking run`` (SI units, radians, null when it did not happen)."""
        out = summary_values(self.raw_summary, self.alpha)
        out["verdict"] = self.verdict
        out["warnings"] = self.warnings
        return out

    # -- the model's assumptions along the run (derivation §3.5) ---------------------------
    def _regime_signs(self):
        return np.asarray(self.slip_direction, dtype=int), np.asarray(self.pivot, dtype=int)

    def contact_forces(self) -> dict[str, np.ndarray]:
        """Forces at the saved times, N: the floor's normal force ``N`` and friction ``F`` on the
        body that slides, the force ``Px``, ``Py`` on the statue's base, the friction ratio
        |Px|/Py the statue's base needs, and the floor pressure centre ``x_N`` under the pedestal
        (m, NaN without pedestal height or where N ≤ 0) with ``N_x_N``, the moment about the
        pedestal's base centre that N balances (N·m, 0 without pedestal height)."""
        from ..models.dynamics import evaluate_all, pressure_centre, pressure_moment

        p = self.parameters
        sig, s = self._regime_signs()
        a_g = self.floor_acceleration
        a_v = self.motion.vertical_acceleration(self.t)
        n = self.t.size
        out = {k: np.empty(n) for k in ("F", "N", "Px", "Py", "x_N", "N_x_N")}
        for i in range(n):
            udd, _, _, f, nn, px, py, _, _ = evaluate_all(
                p, int(sig[i]), int(s[i]), self.u_dot[i], self.theta[i], self.theta_dot[i], a_g[i], a_v[i]
            )
            out["F"][i], out["N"][i], out["Px"][i], out["Py"][i] = f, nn, px, py
            out["x_N"][i] = pressure_centre(p, int(s[i]), a_g[i], udd, px, py, nn)
            out["N_x_N"][i] = pressure_moment(p, int(s[i]), a_g[i], udd, px, py)
        with np.errstate(divide="ignore", invalid="ignore"):
            out["top_friction_ratio"] = np.where(out["Py"] > 0, np.abs(out["Px"]) / out["Py"], np.inf)
        return out

    def violations(self) -> list[tuple[str, float, float]]:
        """Intervals (check, t_start, t_end) of the saved time series where an assumption of the
        model fails while the statue rocks: the floor normal force ≤ 0, the statue's base force
        ≤ 0 (lift-off), the statue slipping on the pedestal (when the top face's friction is
        given), the pedestal uplifting (when its width and height are given)."""
        forces = self.contact_forces()
        rocking = np.isin(self.regime, (Regime.ROCK, Regime.SLIDE_ROCK))
        checks = {
            "floor normal force ≤ 0": forces["N"] <= 0,
            "statue lift-off (base force ≤ 0)": forces["Py"] <= 0,
        }
        top = self.system.top_friction
        if top is not None:
            checks["statue slips on the pedestal"] = forces["top_friction_ratio"] > top.mu_s
        ped = self.system.pedestal
        if ped is not None and ped.width is not None and ped.height is not None:
            # where N ≤ 0 the pressure centre has left the base if the pedestal carries a moment:
            # x_N = moment/N grows without bound as N falls to zero (as the solver's check)
            left = np.abs(np.nan_to_num(forces["x_N"])) > 0.5 * ped.width
            checks["pedestal uplift"] = left | ((forces["N"] <= 0) & (forces["N_x_N"] != 0.0))
        out = []
        for name, flag in checks.items():
            flag = flag & rocking
            edges = np.flatnonzero(np.diff(np.concatenate([[0], flag.astype(np.int8), [0]])))
            for start, stop in zip(edges[::2], edges[1::2]):
                out.append((name, float(self.t[start]), float(self.t[stop - 1])))
        return sorted(out, key=lambda v: v[1])

    def impact_friction_shortfalls(self) -> np.ndarray:
        """Times (s) of the impacts of the Coulomb law (``options.impact = "coulomb"``) that found
        no outcome within the floor's friction and held the body on the floor anyway.

        The law (docs/theory/derivation.md §6) first holds the body on the floor: the statue's angular momentum
        about the new corner gives θ̇⁺ and the floor must supply |Fx|/Fy (O19 with u̇ = 0). If that
        exceeds μs, it lets the body slide with Fx = −μk·Fy·sgn(u̇⁺); that outcome is consistent
        only if the statue still rolls onto the new corner (θ̇⁺ of the sign of θ̇⁻). With a
        restitution well below Housner's (a lone 0.3 × 1.5 m block on μs = 0.25: Housner's
        r = 0.942 needs 0.149 of the floor, r = 0.6 needs 1.25) the sliding outcome turns the
        statue back, no outcome is consistent, and the law keeps the held one, whose floor impulse
        friction cannot give. What follows is not a motion the floor's friction allows. Empty
        under the paper's law (its warning counts those impacts) or without floor friction."""
        return self._held_beyond_friction()[:, 0]

    def _held_beyond_friction(self) -> np.ndarray:
        """The event rows of :meth:`impact_friction_shortfalls`. The law's held outcome ends with
        u̇⁺ = 0, and only its fallback needs more than μs (a slide takes μk·Fy), whatever the body
        did before the impact."""
        floor = self.system.floor_friction
        if floor is None or self.options.impact == "paper":
            return np.empty((0, self.event_table.shape[1]))
        rows = self.event_table[np.isin(self.event_table[:, 1], (EV_IMPACT, EV_SETTLE))]
        return rows[(rows[:, 5] == 0.0) & (rows[:, 9] > floor.mu_s)]

    def _shortfall_text(self) -> str:
        """The warning of the Coulomb law's impacts held beyond friction, from the solver's count
        and first instant of them. Its largest floor ratio is theirs: every other impact of the
        law needs at most μs (held) or takes μk (a slide)."""
        s = self.raw_summary
        body = "pedestal" if self.system.pedestal is not None else "block"
        st = self.system.statue
        r = st.effective_restitution
        why = (f"; a restitution below Housner's ({r:.3f} against {st.housner_restitution:.3f}) takes that impulse"
               if r < st.housner_restitution else "")
        return (f"from t = {s[C.S_HELD_IMPACT]:.4f} s, {int(s[C.S_IMPACT_FLOOR_SHORT])} impact(s) needed more floor "
                f"friction than μs = {self.system.floor_friction.mu_s:g} (up to {s[C.S_IMPACT_FLOOR_RATIO]:.3f}) and "
                f"no sliding outcome of the impact was consistent: the {body} was held as if the floor could give "
                f"it{why}")

    def impact_uplifts(self) -> np.ndarray:
        """Times (s) of the impacts after which a corner of the pedestal would lift for an instant:
        the impulses the two-body model gives them need the floor's normal impulse to act outside
        the pedestal's base. Empty without a pedestal of known width and height.

        At an impact the finite forces (weight, the floor's motion) give no impulse. The pedestal,
        which the model keeps from rotating, takes the statue's change of angular momentum about
        its base centre O, ΔL = −I_c·Δθ̇ − (H1 + h)·Λx (the couple of a restitution other than
        Housner's included, as the stack engine has it), and its own momentum change m1·Δu̇ at its
        centre; the floor's impulse (Fx, Λy) acts at x from O with

            x·Λy = ΔL − ½·H1·m1·Δu̇,

        the impulse form of the pressure centre's moment (derivation §3.5). Here Λx = m2·(Δu̇ +
        h·Δθ̇), Λy = m2·b·(|θ̇⁺| + |θ̇⁻|) (derivation §6) and I_c = I_O − m2·R². With Housner's
        restitution ΔL is the moment of the impulse at the new corner, s⁺·b·Λy − H1·Λx. It lifts
        if |x| > B1/2. The two-body model keeps the pedestal flat through such an impact. A
        settling impact's row holds the state after the rest rule, not the map's, and is not
        judged."""
        ped = self.system.pedestal
        if ped is None or ped.width is None or ped.height is None:
            return np.empty(0)
        rows = self.event_table[self.event_table[:, 1] == EV_IMPACT]
        if rows.size == 0:
            return np.empty(0)
        p = self.parameters
        b, h, m2, m1, h1 = p[P.B], p[P.H], p[P.M2], p[P.M1], ped.height
        i_c = p[P.I_O] - m2 * p[P.R] ** 2
        du, dth = rows[:, 5] - rows[:, 4], rows[:, 7] - rows[:, 6]
        lx = m2 * (du + h * dth)
        ly = m2 * b * (np.abs(rows[:, 7]) + np.abs(rows[:, 6]))
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (-i_c * dth - (h1 + h) * lx - 0.5 * h1 * m1 * du) / ly
        return rows[(ly > 0) & (np.abs(x) > 0.5 * ped.width), 0]

    # -- key point kinematics (paper Eqs. 7–13) --------------------------------------------
    def key_point(self, x: float, y: float) -> dict[str, np.ndarray]:
        """Motion of a point P of the statue, given at rest by (x, y) in m from the centre of
        its base (y up). Returns, at the saved times, its horizontal and vertical displacement
        relative to the floor (``x``, ``y``, m), its velocity relative to the floor (``x_dot``,
        ``y_dot``, m/s) and its absolute horizontal acceleration (``absolute_acceleration``,
        m/s², Eq. 13).

        Eq. 12 is used with θ̇² in the centripetal term (the paper prints θ̇; P7).
        """
        from ..models.dynamics import accelerations

        b = self.system.statue.b
        p = self.parameters
        th, thd, ud = self.theta, self.theta_dot, self.u_dot
        a_g = self.floor_acceleration
        a_v = self.motion.vertical_acceleration(self.t)
        sig, s = self._regime_signs()
        udd = np.zeros_like(th)
        thdd = np.zeros_like(th)
        for i in range(th.size):
            udd[i], thdd[i], _ = accelerations(p, int(sig[i]), int(s[i]), ud[i], th[i], thd[i], a_g[i], a_v[i])
        rx = x - s * b  # P relative to the active pivot (S·b, 0)
        c, sn = np.cos(th), np.sin(th)
        dx = c * rx + sn * y - rx  # Eqs. 8–9: rotation (clockwise positive) about the pivot
        dy = -sn * rx + c * y - y
        acc_rel = (-sn * rx + c * y) * thdd - (c * rx + sn * y) * thd**2  # Eq. 12 (P7)
        return {
            "x": self.u + dx,
            "y": dy,
            "x_dot": ud + (-sn * rx + c * y) * thd,  # time derivatives of Eqs. 8–9
            "y_dot": -(c * rx + sn * y) * thd,
            "absolute_acceleration": a_g + udd + acc_rel,  # Eq. 13
        }

    # -- export ----------------------------------------------------------------------------
    def to_xarray(self):
        """The time series as an ``xarray.Dataset`` (units in attributes; summary in attrs)."""
        import json

        import xarray as xr

        time = np.asarray(self.t)
        ds = xr.Dataset(
            {
                "u": ("time", self.u, {"units": "m", "long_name": "sliding displacement relative to the floor"}),
                "u_dot": ("time", self.u_dot, {"units": "m/s"}),
                "theta": ("time", self.theta, {"units": "rad", "long_name": "statue rotation"}),
                "theta_dot": ("time", self.theta_dot, {"units": "rad/s"}),
                "regime": ("time", self.regime_codes.astype(np.int8), {"flag_values": "0 rest, 1 rock, 2 slide, 3 slide-rock"}),
                "floor_acceleration": ("time", self.floor_acceleration, {"units": "m/s2"}),
            },
            coords={"time": ("time", time, {"units": "s"})},
        )
        ds.attrs["summary"] = json.dumps(self.summary())
        ds.attrs["slenderness_rad"] = self.alpha
        return ds
