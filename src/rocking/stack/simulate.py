"""Run a stack: validation, packing for the compiled engine, and the response (issue 11).

Example
-------
>>> import rocking
>>> from rocking.stack import Block, Interface, Stack, simulate_stack
>>> stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),))
>>> r = simulate_stack(stack, rocking.SinePulse(amplitude=6.0, frequency=1.0))
>>> r.blocks[0]["overturned"]
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..excitation.base import AbstractMotion
from ..excitation.signal import floor_end
from ..results.response import verdict_text
from ..simulation import Options, _as_options, _breakpoints
from ..solver.compiled import _piece_table
from . import engine
from .kinematics import (
    END_L,
    END_U,
    N_P,
    P_BL,
    P_BU,
    P_CAN_SLIP,
    P_HL,
    P_HU,
    P_IMPACT_PAPER,
    P_INERTIA,
    P_MASS,
    P_MU_K,
    P_MU_S,
    P_OFFSET,
    P_RESTITUTION,
)
from .model import Stack

STATUS_NAMES = ("completed", "overturned", "max_events", "inconsistent", "step_failed", "still_moving",
                "slid_past_edge", "lost_contact", "friction_gained")
#: How far (a fraction of the run's energy scale, max |W_in| + max |E − E₀|) the friction loss may
#: fall below its largest value so far before a run is not believed. Friction only takes energy:
#: the loss falls only by the ledger's rounding, less than 1e-9 of the scale between samples in
#: 1793 of 1800 random stacks; in the other 7 a slip held in tension and pushed on by its own
#: friction (Painlevé's paradox, docs/theory/stack.md §5) fed 1e-5 to 1.2 times the scale, and 6
#: of them gave a verdict.
FRICTION_GAIN_LIMIT = 1e-6
#: How deep (m) a corner may go into the face below it before a run is not believed. The deepest
#: seen in 300 random stacks is 1.8e-6 m (chattering micro-impacts); a contact the engine lost
#: (docs/theory/stack.md §7, fixed 2026-11-24) sank 3e-4 m within 30 ms and 0.3 m by the end.
SINK_LIMIT = 1e-4
_FLOOR_HALF_WIDTH = 1e300  # the floor's face has no end


def pack(stack: Stack, impact: str = "coulomb") -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(P, ends, anchor, z0): the parameter table, the corners that make each interface's ends,
    the anchors (left ends) and the interface coordinates at rest. ``impact``: "coulomb" (the
    impact routine of docs/theory/stack.md §6) or "paper" (φ̇⁺ = r·φ̇⁻, every other relative
    velocity unchanged: the paper's Eq. 1)."""
    n = stack.n
    P = np.zeros((n, N_P))
    ends = np.zeros((n, 2, 2))
    anchor = np.zeros(n, dtype=np.int64)
    z0 = np.zeros(3 * n)
    for k, (block, iface) in enumerate(zip(stack.blocks, stack.interfaces)):
        lower = stack.blocks[k - 1] if k > 0 else None
        P[k, P_MASS] = block.mass
        P[k, P_INERTIA] = block.centroidal_inertia
        P[k, P_HU] = 0.5 * block.height
        P[k, P_HL] = 0.5 * lower.height if lower is not None else 0.0
        P[k, P_BU] = 0.5 * block.width
        P[k, P_BL] = 0.5 * lower.width if lower is not None else _FLOOR_HALF_WIDTH
        P[k, P_OFFSET] = block.offset
        P[k, P_IMPACT_PAPER] = 1.0 if impact == "paper" else 0.0
        if iface.friction is not None:
            P[k, P_MU_S] = iface.friction.mu_s
            P[k, P_MU_K] = iface.friction.mu_k
            P[k, P_CAN_SLIP] = 1.0
        P[k, P_RESTITUTION] = math.nan if iface.restitution is None else float(iface.restitution)
        bu, bl, o = P[k, P_BU], P[k, P_BL], block.offset
        # each end of the overlap is the inner of the two corners (a tie: the upper one); a block
        # placed flush with the edge below is a tie, whatever the rounding of o ± bu says
        tie = 1e-12 * max(bu, bl)
        ends[k, 0] = (END_U, -bu) if o - bu >= -bl - tie else (END_L, -bl)
        ends[k, 1] = (END_U, bu) if o + bu <= bl + tie else (END_L, bl)
        # anchor at the left end: a is that corner's position along the face it touches
        z0[3 * k] = o - bu if ends[k, 0, 0] == END_U else -bl - o
    return P, ends, anchor, z0


@dataclass(frozen=True)
class StackResponse:
    """What a stack run gives. Time series on the saved grid (plus event instants):

    * ``t`` (s); ``pose`` (n, N, 3): X, Y, Θ of each block's centre in the floor's frame
      (m, m, rad; Θ positive clockwise, tilting towards +x); ``velocity`` (n, N, 3);
    * ``rotation`` (n, N): φ, each block's rotation relative to the block below, rad;
      ``sliding`` (n, N): its centre's displacement along the face below from where it
      started, m; ``normal_state``/``tangential_state`` (n, N): 0 open, 1 rocking, 2 flat;
      0 stuck, ±1 slipping towards ±x;
    * ``energy``, ``input_work``, ``friction_loss``, ``impact_loss`` (n,), J;
    * ``events`` (m, 6), one row per event: t (s), the interface k, what happened (the guard
      that fired: 0/1 a contact force or gap at the anchor/other end, 2/3 the stick bounds,
      4 overturn, 5 an edge reached, 6 the overlap ended; −1 an impact; −2 a change that follows
      another interface's event), k's normal and tangential state after it (as in the samples:
      an interface's last row at an instant is the state the run goes on in), and the kinetic
      energy an impact took (J, else 0).
    """

    stack: Stack
    status: str
    end_time: float
    t: np.ndarray
    pose: np.ndarray
    velocity: np.ndarray
    rotation: np.ndarray
    sliding: np.ndarray
    normal_state: np.ndarray
    tangential_state: np.ndarray
    energy: np.ndarray
    input_work: np.ndarray
    friction_loss: np.ndarray
    impact_loss: np.ndarray
    events: np.ndarray
    blocks: tuple[dict, ...]
    initial_energy: float

    interfaces: tuple[dict, ...] = ()
    #: still moving at the end, yet it can no longer overturn (:func:`cannot_overturn`)
    settled_by_energy: bool = False

    @property
    def overturned(self) -> bool:
        return any(b["overturned"] for b in self.blocks)

    @property
    def still_moving(self) -> bool:
        return self.status == "still_moving"

    @property
    def verdict(self) -> str:
        """One line, as for a single statue; names the block that fell first."""
        if self.status == "lost_contact":
            return ("undetermined: a block went into the one below it (the solver lost a contact), so the run "
                    "is not a result")
        if self.status == "friction_gained":
            t = friction_gain_time(self)
            return (f"undetermined: from t = {t:.3f} s friction fed the motion (a slip under a contact held in "
                    "tension, Painlevé's paradox of Coulomb friction), so the run is not a result")
        fallen = [b for b in self.blocks if b["overturned"]]
        if fallen:
            first = min(fallen, key=lambda b: b["overturn_time"])
            return f"{first['name']} overturned at t = {first['overturn_time']:.3f} s"
        if self.status == "slid_past_edge" and len(self.events):
            # the engine's last event names the block whose corner reached the edge
            k = int(self.events[-1, 1])
            below = self.stack.names[k - 1] if k > 0 else "the floor"
            return (f"undetermined: {self.stack.names[k]} slid to the edge of {below} at t = {self.end_time:.3f} s; "
                    "the model stops there (treat it as falling off)")
        text = verdict_text(self.status, None, self.end_time, settled=self.settled_by_energy)
        near_miss = first_past_edge(self.blocks)
        if near_miss is not None:
            # no fall, but a block's corner went past the edge of what it stands on
            t, k = near_miss
            text += f"; {self.stack.names[k]} went past the edge of {self.stack.names[k - 1]} at t = {t:.3f} s"
        return text

    @property
    def first_past_edge(self) -> tuple[float, int] | None:
        """:func:`first_past_edge` of this run's blocks."""
        return first_past_edge(self.blocks)

    def summary(self) -> dict:
        """``blocks`` (from the floor up) and ``interfaces`` (floor first); the top-level keys
        describe the top block, the statue, as ``rocking run`` does for a single statue. SI units,
        radians, null when it did not happen. ``energy_balance_error`` is the largest
        |:meth:`balance_error`| over the run divided by its energy scale, max |W_in| + max |E − E₀|
        (0 when nothing moved). An interface's ``required_friction`` is the largest |T|/N it needed
        while it stuck: its contact forces between impacts and, at each impact it came out of
        stuck, the ratio of the impulse that crossed it."""
        top = self.blocks[-1]
        scale = self.energy_scale
        out = {key: top[key] for key in (
            "overturned", "overturn_time", "peak_rotation", "peak_sliding", "residual_sliding",
            "first_rocking_time", "first_sliding_time", "lifted_off_time")}
        out.update(
            impacts=int(np.sum(self.events[:, 2] == engine.EVENT_IMPACT)) if len(self.events) else 0,
            energy_balance_error=float(np.max(np.abs(self.balance_error())) / scale) if scale > 0 else 0.0,
            status=self.status, end_time=self.end_time, still_moving=self.still_moving,
            settled_by_energy=self.settled_by_energy, verdict=self.verdict,
            blocks=[dict(b) for b in self.blocks], interfaces=[dict(f) for f in self.interfaces],
        )
        return out

    @property
    def energy_scale(self) -> float:
        """max |W_in| + max |E − E₀| over the run, J: what the ledger's checks are relative to."""
        return float(np.max(np.abs(self.input_work)) + np.max(np.abs(self.energy - self.initial_energy)))

    def balance_error(self) -> np.ndarray:
        """E(t) − E(0) − W_in + D_friction + D_impact, J (zero up to the solver's accuracy)."""
        return self.energy - self.initial_energy - self.input_work + self.friction_loss + self.impact_loss


def simulate_stack(
    stack: Stack,
    motion: AbstractMotion,
    *,
    duration: float | None = None,
    options: Options | Mapping = Options(),
) -> StackResponse:
    """Simulate a stack of blocks on a floor moving with ``motion`` (see :class:`StackResponse`).

    Without ``duration`` the run lasts the motion and then, with the floor still, until every
    interface is flat and stuck, for at most ``options.free_time_limit`` more seconds."""
    if not isinstance(stack, Stack):
        raise TypeError(f"stack must be a rocking.stack.Stack, got {type(stack).__name__}")
    if not isinstance(motion, AbstractMotion):
        raise TypeError(f"motion must be a floor motion, got {type(motion).__name__}")
    options = _as_options(options)
    motion_end = float(motion.duration)
    if duration is None:
        t_end, t_settle = motion_end + float(options.free_time_limit), motion_end
    else:
        t_end, t_settle = float(duration), math.inf
        if not (math.isfinite(t_end) and t_end > 0):
            raise ValueError(f"simulation.duration must be a positive number (s), got {duration!r}")
    save_dt = options.save_dt or (float(getattr(motion, "dt", 0.0) or 0.0) or 0.01)
    if options.normal_force != "full":
        raise ValueError(
            "simulation.normal_force = 'paper' (N = M g) belongs to the two-body model of rocking.simulate; "
            "a stack always uses the contact forces it computes"
        )
    P, ends, anchor, z0 = pack(stack, options.impact)
    n = stack.n
    y0 = np.zeros(6 * n + 2)
    y0[: 3 * n] = z0
    sig_h, sig_v = motion.signal(), motion.vertical_signal()
    bp = _breakpoints(motion, t_end, (sig_h, sig_v))
    h = (sig_h.kind, sig_h.params, sig_h.time, sig_h.values)
    v = (sig_v.kind, sig_v.params, sig_v.time, sig_v.values)
    pieces = _piece_table(h, v, bp, 0.0, t_end)
    status, t_stop, samples, events, summ, e0, *_ = engine.integrate(
        P, ends, anchor, pieces, bp, t_end, t_settle, y0, options.gravity, options.rtol, options.atol,
        options.max_step, save_dt, int(options.max_events), options.rest_velocity, bool(options.stop_at_edge),
    )
    response = _response(stack, STATUS_NAMES[status], t_stop, samples, events, summ, e0)
    if response.status == "still_moving" and cannot_overturn(response, floor_end(h, v), options):
        response = replace(response, settled_by_energy=True)
    return response


def cannot_overturn(response: StackResponse, t_floor_end: float, options: Options) -> bool:
    """Whether a one-block stack still moving where its run ended can no longer overturn, by the
    rule of :func:`rocking.solver.compiled._cannot_overturn` for the two-body model. Once the floor
    has stopped for good (the run ended at or after ``t_floor_end``, s), friction and
    impacts only take energy (the engine's impacts to their allowance for the rest velocity, §6
    of docs/theory/stack.md), so a block inside ±α with less energy above its rest, E − E₀ plus
    the ledger's largest error, than m·g·(R − h) never reaches ±α again. Not under the paper's
    impact law on a face that slips (it keeps the slip rate and can add energy). A taller stack
    has no such simple bound (which block falls, over which corner, how high the others ride):
    it stays undetermined."""
    stack = response.stack
    if stack.n != 1:
        return False
    if response.end_time < t_floor_end:
        return False
    if options.impact == "paper" and stack.interfaces[0].friction is not None:
        return False
    block = stack.blocks[0]
    alpha = math.atan2(block.width, block.height)
    barrier = block.mass * options.gravity * (0.5 * math.hypot(block.width, block.height) - 0.5 * block.height)
    energy = float(response.energy[-1] - response.initial_energy) + float(np.max(np.abs(response.balance_error())))
    return bool(abs(response.rotation[-1, 0]) < alpha and energy < barrier)


def first_past_edge(blocks: Sequence[Mapping[str, Any]]) -> tuple[float, int] | None:
    """(t, block index) of the first time a corner of a block reached the edge of the block below
    (it went past it, or the run stopped there with ``stop_at_edge``), or None; ``blocks`` as in
    :attr:`StackResponse.blocks`. (A function, so that the studies' unpacked summaries get the same
    verdict.)"""
    past = [(b["past_edge_time"], k) for k, b in enumerate(blocks) if b["past_edge_time"] is not None]
    return min(past) if past else None


def deepest_sink(stack: Stack, pose: np.ndarray) -> float:
    """How deep (m, ≥ 0) any block's bottom corner went below the top face of the block under it
    (or the floor), over the poses ``pose`` (n, N, 3) as in :attr:`StackResponse.pose`. A corner
    beyond the end of the face below is not on it and is skipped, and so are the corners of a
    block turned to ±π/2 on the one below (to 1e-9 rad): that is its overturn, where the run
    ends, and one that overturns about the lower block's corner lies along that block's side, its
    own corner at the face's end (to rounding) and up to its width below."""
    deepest = 0.0
    cos, sin = np.cos(pose[:, :, 2]), np.sin(pose[:, :, 2])  # once: each block's Θ serves twice
    for k, block in enumerate(stack.blocks):
        x, y, c, s = pose[:, k, 0], pose[:, k, 1], cos[:, k], sin[:, k]
        for xc in (-0.5 * block.width, 0.5 * block.width):
            px = x + xc * c - 0.5 * block.height * s  # the corner (xc, −h/2), Θ clockwise
            py = y - xc * s - 0.5 * block.height * c
            if k == 0:
                gap = py
            else:
                below = stack.blocks[k - 1]
                dx, dy, cb, sb = px - pose[:, k - 1, 0], py - pose[:, k - 1, 1], cos[:, k - 1], sin[:, k - 1]
                up = dx * sb + dy * cb - 0.5 * below.height
                on = (np.abs(dx * cb - dy * sb) <= 0.5 * below.width) & (
                    np.abs(pose[:, k, 2] - pose[:, k - 1, 2]) < 0.5 * np.pi - 1e-9)
                gap = np.where(on, up, np.inf)
            deepest = max(deepest, float(-np.min(gap, initial=0.0)))
    return deepest


def _response(stack, status, t_stop, samples, events, summ, e0) -> StackResponse:
    n = stack.n
    t = samples[:, 0]
    order = np.argsort(t, kind="stable")
    samples = samples[order]
    t = samples[:, 0]
    blk = samples[:, 1 : 1 + engine.N_BLOCK_COLS * n].reshape(len(t), n, engine.N_BLOCK_COLS)
    c0 = 1 + engine.N_BLOCK_COLS * n
    ifc = samples[:, c0 : c0 + engine.N_IFACE_COLS * n].reshape(len(t), n, engine.N_IFACE_COLS)
    tail = samples[:, c0 + engine.N_IFACE_COLS * n :]
    blocks = []
    interfaces = []
    below = ("floor",) + stack.names[:-1]
    impacts = events[events[:, 2] == engine.EVENT_IMPACT] if len(events) else events
    edges = events[events[:, 2] == engine.G_EDGE] if len(events) else events
    for k, name in enumerate(stack.names):
        s = summ[k]
        # peaks between the tracking points are caught by the saved samples
        s[engine.B_PEAK_PHI] = max(s[engine.B_PEAK_PHI], float(np.max(np.abs(ifc[:, k, 0]), initial=0.0)))
        s[engine.B_PEAK_SLIP] = max(s[engine.B_PEAK_SLIP], float(np.max(np.abs(ifc[:, k, 1]), initial=0.0)))
        interfaces.append({
            "name": f"{below[k]}–{name}",
            "required_friction": float(s[engine.B_MU_REQ]),
            "slip_path": float(s[engine.B_SLIP_PATH]),
            "impacts": int(np.sum(impacts[:, 1] == k)) if len(impacts) else 0,
        })
        overturned = bool(np.isfinite(s[engine.B_OVERTURN]))
        blocks.append({
            "name": name,
            "overturned": overturned,
            "overturn_time": float(s[engine.B_OVERTURN]) if overturned else None,
            "peak_rotation": float(s[engine.B_PEAK_PHI]),
            "peak_absolute_rotation": float(s[engine.B_PEAK_ABS_THETA]),
            "peak_sliding": float(s[engine.B_PEAK_SLIP]),
            "residual_sliding": float(s[engine.B_FINAL_SLIP]),
            "lifted_off_time": _opt(s[engine.B_LIFTOFF]),
            "first_rocking_time": _opt(s[engine.B_FIRST_ROCK]),
            "first_sliding_time": _opt(s[engine.B_FIRST_SLIDE]),
            "tension_held_time": _opt(s[engine.B_HELD]),
            # the first impact on this block's interface whose restitution had to be reduced for a
            # consistent contact mode to exist (docs/theory/stack.md §6)
            "restitution_reduced_time": _opt(s[engine.B_RESTITUTION_CUT]),
            # the first time a corner of this block reached the edge of the one below (it went
            # past it, or the run stopped there with stop_at_edge)
            "past_edge_time": float(edges[edges[:, 1] == k][0, 0]) if np.any(edges[:, 1] == k) else None,
        })
    response = StackResponse(
        stack=stack, status=status, end_time=float(t_stop), t=t, pose=blk[:, :, :3].copy(),
        velocity=blk[:, :, 3:].copy(), rotation=ifc[:, :, 0].copy(), sliding=ifc[:, :, 1].copy(),
        normal_state=ifc[:, :, 2].astype(int), tangential_state=ifc[:, :, 3].astype(int),
        energy=tail[:, 0].copy(), input_work=tail[:, 1].copy(), friction_loss=tail[:, 2].copy(),
        impact_loss=tail[:, 3].copy(), events=events, blocks=tuple(blocks), initial_energy=float(e0),
        interfaces=tuple(interfaces),
    )
    if friction_gain_time(response) is not None:
        # friction gave energy: the engine's own invariant broken, the run is not a result
        status = "friction_gained"
    if deepest_sink(stack, blk[:, :, :3]) > SINK_LIMIT:
        # the engine's own invariant broken: whatever the run says after that is not a result
        status = "lost_contact"
    return replace(response, status=status)


def friction_gain_time(response: StackResponse) -> float | None:
    """Where friction first gave energy: the saved instant (s) from which the friction loss fell,
    the first time it falls below its largest value so far by more than FRICTION_GAIN_LIMIT of the
    run's energy scale; None if it never does. Coulomb friction only takes energy; a fall beyond the
    ledger's rounding is the engine's own invariant broken."""
    loss = response.friction_loss
    if len(loss) == 0:
        return None
    scale = response.energy_scale
    peak = np.maximum.accumulate(loss)
    over = np.nonzero(peak - loss > FRICTION_GAIN_LIMIT * scale)[0]
    if not len(over) or not scale > 0:
        return None
    # the fall began after the last sample at the peak it falls from
    start = np.nonzero(loss[:over[0]] == peak[over[0]])[0][-1]
    return float(response.t[start])


def _opt(v: float) -> float | None:
    return None if not np.isfinite(v) else float(v)
