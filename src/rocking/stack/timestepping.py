"""Moreau–Jean time stepping for a planar stack of rigid blocks: the independent, first-order method.

This solver exists to cross-check the event-driven stack engine: it shares none of its code,
only the data classes of ``rocking.stack.model``. It writes its own geometry, kinematics and
contact LCP, and as Δt → 0 it converges (to first order) to the same non-smooth dynamics.

Model (SI units, angles in rad)
-------------------------------
* Frame attached to the floor (x right, y up, floor surface y = 0). Block k = 1…N from the floor
  up; generalised coordinates of each block: its centre (X, Y) and its rotation Θ, **positive
  clockwise**: a body point at local (ξ, η) lies at (X + ξ cos Θ + η sin Θ, Y − ξ sin Θ + η cos Θ).
  The mass matrix is diag(m, m, J) per block (J: centroidal inertia), constant.
* Loads: gravity and the floor acceleration as d'Alembert forces, (−m a_h(t), −m (g + a_v(t)))
  at each centre.
* Contacts at interface k (block k on block k − 1, or on the floor): on each side (left,
  right) the bottom corner of block k on the top face of block k − 1 if its projection lies on
  that face (the floor's face is infinite), otherwise the top corner of block k − 1 on the
  bottom face of block k if that corner lies under it. So each interface has at most two
  contact points, the ends of the overlap of the two faces, and coincident corners (equal
  widths, aligned edges) count once. Gap: signed distance of the corner from the face along
  the face's normal, ≥ 0 when apart.
* Impacts: Newton restitution 0 at every contact (plastic).
* Friction per interface: ``Interface.friction`` (Coulomb, 2-D cone as an LCP with the edges
  ±t and a slack λ), or ``None`` = never slips. "Never slips" is the cone with μ = 10⁴: u_t = 0
  at every contact that carries a normal impulse, while a corner that lifts (P_n = 0) carries no
  tangential impulse. A bilateral u_t = 0 at every active contact is not used: at an impact both
  corners of a block are active while Θ ≠ 0 (Θ = O(Δt)), and u_t = 0 at both locks the rotation
  (the LCP asks for tangential impulses of order ω/Θ and Lemke ray-terminates), instead of
  letting the old corner lift as in Housner's impact.
  With μs > μk: a contact uses μs if it was sticking at the end of the
  previous step (|u_t| ≤ 1e-8 m/s in that step's solution) and μk if it was sliding; a contact
  that was not active in the previous step uses μs if its tangential relative velocity before the
  step is at most g Δt (so the criterion tends to "u_t = 0" as Δt → 0) and μk otherwise.

Method (Moreau–Jean, θ-method)
------------------------------
Per step of length Δt:  q_{n+θ} = q_n + θ Δt v_n;  contacts with gap(q_{n+θ}) ≤ a small
threshold are active;  M (v_{n+1} − v_n) = Δt f(t_{n+θ}) + Wᵀ P  with, per active contact,
0 ≤ P_n ⟂ u_n(v_{n+1}) ≥ 0 and the friction complementarity, W evaluated at q_{n+θ};  then
q_{n+1} = q_n + Δt ((1 − θ) v_n + θ v_{n+1}).  One LCP per step (``rocking.stack.lcp.lemke``).
The method is first order: impacts fall inside a step, and a contact is enforced at the velocity
level only, so a rocking pivot drifts off (or into) its face by O(Δt) over a unit of time.

Stopping: a block overturns when its rotation relative to the block below (the floor for
block 1) exceeds π/2 in magnitude, or when it has slid off (its centre, seen from the block below,
leaves no overlap of the two faces); the run stops at the end of that step.

Limitations: only the corner-on-face contacts above (no side faces, no contact between
non-adjacent blocks); no restitution other than 0; plain Python and numpy: about 2–5·10³ steps
per second for one or two blocks, 1–2·10³ for three.

Example
-------
>>> from rocking.stack.model import Block, Interface, Stack
>>> stack = Stack(blocks=(Block(width=0.4, height=2.0, mass=100.0),), interfaces=(Interface(),))
>>> res = moreau_jean(stack, lambda t: 0.0, t_end=0.01, dt=1e-3)
>>> res.status, res.pose.shape
('completed', (11, 1, 3))
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .lcp import LCPError, lemke
from .model import Stack

__all__ = ["LCPError", "StackTimeSteppingResult", "moreau_jean", "relative_pose", "rest_pose"]

# A contact is active when its gap at q_{n+θ} is below this fraction of the smallest block
# height: enough to absorb round-off in the gap of a stack at rest (~1e-16 m), far too small
# to matter otherwise.
_GAP_TOL = 1e-9
# A corner's projection still counts as on a face within this fraction of the face's width, so
# that corners exactly at the end of a face (aligned edges) are kept by the first test.
_EDGE_TOL = 1e-9
# |u_t| (m/s) below which a contact's LCP solution is a stick.
_STICK_TOL = 1e-8
# The friction coefficient of an interface that never slips (Interface.friction = None): a
# contact slips only if it needs a tangential impulse 10⁴ times its normal one.
_NEVER_SLIPS_MU = 1e4


@dataclass(frozen=True)
class StackTimeSteppingResult:
    """Output of :func:`moreau_jean`.

    Attributes
    ----------
    t : (n,) ndarray, s.
    pose : (n, N, 3) ndarray
        X, Y (m) and Θ (rad, clockwise) of each block's centre, in the floor frame.
    velocity : (n, N, 3) ndarray
        Ẋ, Ẏ (m/s) and Θ̇ (rad/s), floor frame.
    overturned : tuple of bool, per block (the block that triggered the stop).
    overturn_time : tuple of float, s (nan where the block did not overturn).
    status : "completed" or "overturned".
    dt, theta : the step (s) and the θ of the run.
    """

    t: np.ndarray
    pose: np.ndarray
    velocity: np.ndarray
    overturned: tuple[bool, ...]
    overturn_time: tuple[float, ...]
    status: str
    dt: float
    theta: float


@dataclass(frozen=True, slots=True)
class _Blocks:
    """Per-block constants as arrays (index 0 = block 1) and per-interface friction."""

    width: np.ndarray  # m
    height: np.ndarray  # m
    mass: np.ndarray  # kg
    inertia: np.ndarray  # kg·m²
    mu_s: tuple[float, ...]  # per interface
    mu_k: tuple[float, ...]
    inverse_mass: np.ndarray  # diagonal of M⁻¹ for v = (Ẋ1, Ẏ1, Θ̇1, Ẋ2, …), 1/kg and 1/(kg·m²)

    @property
    def n(self) -> int:
        return self.width.size


@dataclass(frozen=True, slots=True)
class _Contact:
    """A candidate contact point at interface k, at q_{n+θ}."""

    key: tuple[int, int, str]  # (interface k ≥ 1, side −1 left / +1 right, "A" upper corner | "B" lower corner)
    upper: int  # 0-based index of block k
    lower: int  # 0-based index of block k − 1; −1 for the floor
    point: tuple[float, float]  # the corner, m (floor frame)
    normal: tuple[float, float]  # unit normal of the face: the direction of the force on the upper block
    gap: float  # m, ≥ 0 when apart


def moreau_jean(
    stack: Stack,
    a_h: Callable[[float], float],
    a_v: Callable[[float], float] | None = None,
    t_end: float = 2.0,
    dt: float = 1e-4,
    gravity: float = 9.80665,
    theta: float = 0.5,
    save_every: int = 1,
    *,
    pose0=None,
    velocity0=None,
) -> StackTimeSteppingResult:
    """Integrate the stack from t = 0 to ``t_end`` with Moreau–Jean time stepping.

    Parameters
    ----------
    stack : Stack
    a_h, a_v : callable t (s) → m/s²
        Horizontal and vertical floor acceleration; ``a_v=None`` means 0.
    t_end : float
        Duration, s (the last step is shortened if t_end is not a multiple of dt).
    dt : float
        Step, s.
    gravity : float
        g, m/s².
    theta : float
        θ of the θ-method, in [0.5, 1] (0.5: trapezoidal positions; 1: implicit Euler).
    save_every : int
        Keep one step in ``save_every`` (the first and the last are always kept).
    pose0, velocity0 : (N, 3) array_like, optional
        Initial X, Y, Θ (m, m, rad) and their rates; default: the rest pose of the stack
        (Θ = 0, blocks stacked on their offsets) and zero velocity.

    Returns
    -------
    StackTimeSteppingResult

    Notes
    -----
    Friction with μs > μk: a contact uses μs if it was sticking at the end of the previous step
    and μk if it was sliding; a contact that has just closed uses μs if its tangential relative
    velocity is at most g Δt, μk otherwise. ``Interface.friction = None`` is a cone with
    μ = 10⁴ (see the module docstring for why not a bilateral constraint).

    Raises
    ------
    NotImplementedError
        If an interface has a restitution (only the plastic impact, e = 0, is implemented).
    ValueError
        On a bad step, θ, duration or initial state.
    LCPError
        If the contact LCP of a step cannot be solved.
    """
    blocks = _check_inputs(stack, a_h, a_v, t_end, dt, gravity, theta, save_every)
    a_v = a_v if a_v is not None else (lambda t: 0.0)
    q = _initial(pose0, rest_pose(stack), "pose0")
    v = _initial(velocity0, np.zeros_like(q), "velocity0")

    n_steps = max(1, math.ceil(t_end / dt - 1e-9))  # the last step is shortened to end at t_end
    slip_threshold = max(abs(gravity), 1.0) * dt  # m/s, μs or μk for a new contact (module docstring)
    stick: dict[tuple, bool] = {}  # contact key → was sticking at the end of the previous step
    times, poses, velocities = [0.0], [q.copy()], [v.copy()]
    overturn_time = [math.nan] * blocks.n
    for step in range(1, n_steps + 1):
        t0, t1 = (step - 1) * dt, (step * dt if step < n_steps else t_end)
        t_mid = t0 + theta * (t1 - t0)
        loads = _loads(blocks, float(a_h(t_mid)), float(a_v(t_mid)), gravity)
        try:
            q, v, stick = _step(q, v, t1 - t0, theta, loads, blocks, stick, slip_threshold)
        except LCPError as exc:
            raise LCPError(f"moreau_jean: the contact LCP of the step from t = {t0:.9g} s failed: {exc}") from exc
        fallen = _overturned(q, blocks)
        if step % save_every == 0 or step == n_steps or any(fallen):
            times.append(t1)
            poses.append(q.copy())
            velocities.append(v.copy())
        if any(fallen):
            overturn_time = [t1 if f else math.nan for f in fallen]
            break
    overturned = tuple(not math.isnan(x) for x in overturn_time)
    return StackTimeSteppingResult(
        t=np.array(times),
        pose=np.array(poses),
        velocity=np.array(velocities),
        overturned=overturned,
        overturn_time=tuple(overturn_time),
        status="overturned" if any(overturned) else "completed",
        dt=float(dt),
        theta=float(theta),
    )


def _step(q, v, h, theta, loads, blocks: _Blocks, stick: dict, slip_threshold: float):
    """One Moreau–Jean step of length h (s) from (q, v) ((N, 3) arrays) under the generalised
    ``loads`` (N, N, N·m, flat) evaluated at t_{n+θ}. Returns (q_{n+1}, v_{n+1}, stick state)."""
    q_mid = q + theta * h * v
    v_free = v.ravel() + h * blocks.inverse_mass * loads
    # Contacts are chosen at q_{n+θ}: a contact whose gap closes during the step is caught there.
    active = [c for c in _contacts(q_mid, blocks) if c.gap <= _GAP_TOL * blocks.height.min()]
    if active:
        v_new, stick = _contact_step(active, q_mid, v, v_free, blocks, stick, slip_threshold)
    else:
        v_new, stick = v_free, {}
    v_new = v_new.reshape(v.shape)
    return q + h * ((1.0 - theta) * v + theta * v_new), v_new, stick


def relative_pose(res: StackTimeSteppingResult) -> np.ndarray:
    """Pose of each block relative to the block below, (n, N, 3).

    Block k: (ξ, η, φ) with φ = Θ_k − Θ_{k−1} (rad, clockwise) and (ξ, η) the position of its
    centre in block k − 1's body frame (m; origin at that block's centre, ξ along its bottom
    face). Block 1 is given relative to the floor, i.e. its own (X, Y, Θ).
    """
    pose = np.asarray(res.pose, dtype=float)
    out = pose.copy()
    below, above = pose[:, :-1, :], pose[:, 1:, :]
    c, s = np.cos(below[..., 2]), np.sin(below[..., 2])
    dx, dy = above[..., 0] - below[..., 0], above[..., 1] - below[..., 1]
    out[:, 1:, 0] = c * dx - s * dy
    out[:, 1:, 1] = s * dx + c * dy
    out[:, 1:, 2] = above[..., 2] - below[..., 2]
    return out


def rest_pose(stack: Stack) -> np.ndarray:
    """(N, 3) rest pose: Θ = 0, each block centred on its offsets and standing on the one below, m."""
    pose = np.zeros((stack.n, 3))
    x = y = 0.0
    for k, b in enumerate(stack.blocks):
        x += b.offset
        pose[k] = (x, y + 0.5 * b.height, 0.0)
        y += b.height
    return pose


# --------------------------------------------------------------------------------------------
# input checks


def _check_inputs(stack, a_h, a_v, t_end, dt, gravity, theta, save_every) -> _Blocks:
    if not isinstance(stack, Stack):
        raise ValueError(f"stack must be a rocking.stack.model.Stack, got {type(stack).__name__}")
    for k, interface in enumerate(stack.interfaces, start=1):
        if interface.restitution is not None:
            raise NotImplementedError(
                f"interface {k}: restitution = {interface.restitution!r} is not implemented by the "
                "Moreau–Jean solver, which uses a plastic impact (Newton e = 0) at every contact; "
                "leave Interface.restitution = None"
            )
    if not callable(a_h) or (a_v is not None and not callable(a_v)):
        raise ValueError("a_h (and a_v if given) must be callables t (s) → acceleration (m/s²)")
    _finite_positive("dt", dt)
    _finite_positive("t_end", t_end)
    if isinstance(theta, bool) or not isinstance(theta, (int, float)) or not 0.5 <= theta <= 1.0:
        raise ValueError(f"theta must lie in [0.5, 1], got {theta!r}")
    if isinstance(gravity, bool) or not isinstance(gravity, (int, float)) or not math.isfinite(gravity):
        raise ValueError(f"gravity must be a finite number (m/s²), got {gravity!r}")
    if isinstance(save_every, bool) or not isinstance(save_every, int) or save_every < 1:
        raise ValueError(f"save_every must be a positive integer, got {save_every!r}")
    mu_s = tuple(_NEVER_SLIPS_MU if i.friction is None else i.friction.mu_s for i in stack.interfaces)
    mu_k = tuple(_NEVER_SLIPS_MU if i.friction is None else i.friction.mu_k for i in stack.interfaces)
    mass = np.array([b.mass for b in stack.blocks])
    inertia = np.array([b.centroidal_inertia for b in stack.blocks])
    return _Blocks(
        width=np.array([b.width for b in stack.blocks]),
        height=np.array([b.height for b in stack.blocks]),
        mass=mass,
        inertia=inertia,
        mu_s=mu_s,
        mu_k=mu_k,
        inverse_mass=1.0 / np.column_stack([mass, mass, inertia]).ravel(),
    )


def _finite_positive(name: str, value) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a positive finite number (s), got {value!r}")


def _initial(value, default: np.ndarray, name: str) -> np.ndarray:
    if value is None:
        return default.copy()
    arr = np.array(value, dtype=float)
    if arr.shape != default.shape or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a finite array of shape {default.shape}, got shape {arr.shape}")
    return arr


# --------------------------------------------------------------------------------------------
# geometry and kinematics


def _body_point(pose, xi: float, eta: float) -> tuple[float, float]:
    """Floor-frame position (m) of the body point at local (ξ, η) of a block at ``pose``."""
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    return x + xi * c + eta * s, y - xi * s + eta * c


def _to_body(pose, px: float, py: float) -> tuple[float, float]:
    """Local (ξ, η) (m) of the floor-frame point (px, py) in the frame of a block at ``pose``."""
    x, y, th = pose
    c, s = math.cos(th), math.sin(th)
    dx, dy = px - x, py - y
    return c * dx - s * dy, s * dx + c * dy


def _up(th: float) -> tuple[float, float]:
    """Unit vector of a block's local +η axis (its 'up') in the floor frame."""
    return math.sin(th), math.cos(th)


def _contacts(q: np.ndarray, blocks: _Blocks) -> list[_Contact]:
    """Candidate contacts of every interface at configuration q (N, 3)."""
    out = []
    for u in range(blocks.n):
        hw_u, hh_u = 0.5 * blocks.width[u], 0.5 * blocks.height[u]
        k = u + 1
        for side in (-1, 1):
            corner = _body_point(q[u], side * hw_u, -hh_u)
            if u == 0:  # the floor: an infinite face y = 0
                out.append(_Contact((k, side, "A"), u, -1, corner, (0.0, 1.0), corner[1]))
                continue
            lo = u - 1
            hw_l, hh_l = 0.5 * blocks.width[lo], 0.5 * blocks.height[lo]
            xi, eta = _to_body(q[lo], *corner)
            if abs(xi) <= hw_l * (1.0 + _EDGE_TOL):  # block k's corner over block k−1's top face
                out.append(_Contact((k, side, "A"), u, lo, corner, _up(q[lo, 2]), eta - hh_l))
                continue
            corner = _body_point(q[lo], side * hw_l, hh_l)
            xi, eta = _to_body(q[u], *corner)
            if abs(xi) <= hw_u * (1.0 + _EDGE_TOL):  # block k−1's corner under block k's bottom face
                out.append(_Contact((k, side, "B"), u, lo, corner, _up(q[u, 2]), -hh_u - eta))
    return out


def _jacobian_row(q: np.ndarray, contact: _Contact, direction: tuple[float, float]) -> np.ndarray:
    """Row w with w·v = the relative velocity, along ``direction``, of the upper block's material
    point at the contact point with respect to the lower block's (m/s per unit of v).

    A body point at r from the centre moves at (Ẋ + Θ̇ r_y, Ẏ − Θ̇ r_x) (Θ clockwise); the same
    row, transposed, maps a force along ``direction`` to generalised forces (N, N, N·m)."""
    row = np.zeros(q.size)
    dx, dy = direction
    px, py = contact.point
    for body, sign in ((contact.upper, 1.0), (contact.lower, -1.0)):
        if body < 0:
            continue
        rx, ry = px - q[body, 0], py - q[body, 1]
        row[3 * body: 3 * body + 3] = sign * dx, sign * dy, sign * (dx * ry - dy * rx)
    return row


def _loads(blocks: _Blocks, a_h: float, a_v: float, gravity: float) -> np.ndarray:
    """Generalised forces (N, N, N·m per block): gravity and the floor's d'Alembert forces."""
    f = np.zeros((blocks.n, 3))
    f[:, 0] = -blocks.mass * a_h
    f[:, 1] = -blocks.mass * (gravity + a_v)
    return f.ravel()


def _overturned(q: np.ndarray, blocks: _Blocks) -> list[bool]:
    """Per block: rotated by more than π/2 relative to the block below, or slid off it."""
    out = []
    for k in range(blocks.n):
        if k == 0:
            out.append(abs(q[0, 2]) > 0.5 * math.pi)
            continue
        phi = q[k, 2] - q[k - 1, 2]
        xi, _ = _to_body(q[k - 1], q[k, 0], q[k, 1])
        hw_u, hw_l = 0.5 * blocks.width[k], 0.5 * blocks.width[k - 1]
        overlap = min(xi + hw_u, hw_l) - max(xi - hw_u, -hw_l)
        out.append(abs(phi) > 0.5 * math.pi or overlap <= 0.0)
    return out


# --------------------------------------------------------------------------------------------
# the contact LCP of one step


def _contact_step(active, q_mid, v, v_free, blocks: _Blocks, stick: dict, slip_threshold: float):
    """Velocities after one step with the active contacts, and the stick state of each.

    ``stick`` holds the previous step's stick state; a contact not in it uses μs if its
    tangential relative velocity |u_t(v_n)| is at most ``slip_threshold`` (m/s).
    Returns (v_{n+1} as a flat array, {contact key: sticking}).
    """
    normals = np.array([_jacobian_row(q_mid, c, c.normal) for c in active])
    tangents = np.array([_jacobian_row(q_mid, c, (c.normal[1], -c.normal[0])) for c in active])
    mus = []
    for c, w_t in zip(active, tangents):
        k = c.key[0] - 1
        was_sticking = stick[c.key] if c.key in stick else abs(w_t @ v.ravel()) <= slip_threshold
        mus.append(blocks.mu_s[k] if was_sticking else blocks.mu_k[k])
    impulse_n, impulse_t = _solve_lcp(normals, tangents, np.array(mus), blocks.inverse_mass, v_free,
                                      float(blocks.mass.min()))
    v_new = v_free + blocks.inverse_mass * (normals.T @ impulse_n + tangents.T @ impulse_t)
    u_t = tangents @ v_new
    return v_new, {c.key: abs(u) <= _STICK_TOL for c, u in zip(active, u_t)}


def _solve_lcp(normals, tangents, mus, inv_mass, v_free, mass_scale):
    """Normal and tangential impulses (N·s) of the active contacts.

    Unknowns (impulses divided by ``mass_scale``, kg, so that every entry of the LCP is a
    velocity or a number): p_n per contact; β⁺, β⁻ and λ per contact with μ > 0
    (P_t = β⁺ − β⁻; frictionless contacts have no tangential unknowns). Pairs:
        p_n  ⟂ u_n ≥ 0
        β⁺   ⟂ u_t + λ ≥ 0
        β⁻   ⟂ −u_t + λ ≥ 0
        λ    ⟂ μ p_n − β⁺ − β⁻ ≥ 0
    with u = W v_{n+1}, v_{n+1} = v_free + M⁻¹ Wᵀ P: stick (λ = 0, |P_t| ≤ μ P_n) or slip
    against the motion (λ = |u_t|, |P_t| = μ P_n).
    """
    m = len(mus)
    fric = np.flatnonzero(mus > 0.0)  # contacts with a tangential impulse
    nf = fric.size
    rows = np.vstack([normals, tangents[fric]])  # directions of the impulses
    a = (rows * inv_mass) @ rows.T * mass_scale  # Delassus operator W M⁻¹ Wᵀ, scaled
    free = rows @ v_free
    a_n, a_t = a[:m], a[m:]
    eye = np.eye(nf)

    size = m + 3 * nf
    n_, p_, m_, l_ = slice(0, m), slice(m, m + nf), slice(m + nf, m + 2 * nf), slice(m + 2 * nf, size)
    lcp = np.zeros((size, size))
    lcp[n_, n_], lcp[n_, p_], lcp[n_, m_] = a_n[:, :m], a_n[:, m:], -a_n[:, m:]
    lcp[p_, n_], lcp[p_, p_], lcp[p_, m_], lcp[p_, l_] = a_t[:, :m], a_t[:, m:], -a_t[:, m:], eye
    lcp[m_, n_], lcp[m_, p_], lcp[m_, m_], lcp[m_, l_] = -a_t[:, :m], -a_t[:, m:], a_t[:, m:], eye
    # λ rows divided by max(μ, 1) (same complementarity): μ = 10⁴ would dwarf the other entries
    lcp[m + 2 * nf + np.arange(nf), fric] = mus[fric] / np.maximum(mus[fric], 1.0)
    lcp[l_, p_] = lcp[l_, m_] = -np.diag(1.0 / np.maximum(mus[fric], 1.0))
    rhs = np.concatenate([free[:m], free[m:], -free[m:], np.zeros(nf)])

    z = lemke(lcp, rhs) * mass_scale
    impulse_n = z[:m]
    impulse_t = np.zeros(m)
    impulse_t[fric] = z[p_] - z[m_]
    return impulse_n, impulse_t
