"""An energy ledger computed from a run's saved samples, independently of the solver's own.

The compiled solver integrates its input work and friction dissipation alongside the motion and
reports how well E − E0 − W + D + D_impact vanishes; a test that reads that number checks the
solver against itself (its energy, its power, its floor acceleration). Here every term comes
from elsewhere:

* E, the mechanical energy relative to the floor, and the statue's velocity: the sympy
  derivation ``oracles.lagrange`` (positions → kinetic and potential energy);
* the floor's friction force F and normal force N while sliding: ``lagrange.accelerations``;
* the floor accelerations: the motion's own NumPy formulas (``acceleration(t)``), not the
  compiled piece table;
* W and D: quadrature of their power over the saved samples (a cubic spline on each smooth
  stretch, error O(dt⁴)); D_impact: the drops of E at the instants saved twice (before and after
  an event).

Power balance in the floor's frame (the floor is not inertial): the bodies feel the inertial
forces −m·a_g (horizontal) and −m·a_v (vertical) besides gravity and the floor's reactions, so

    dE/dt = −a_g·(m1·u̇ + m2·ẋ2) − a_v·m2·ẏ2 + F·u̇,

with (ẋ2, ẏ2) the statue's centre-of-mass velocity relative to the floor and F·u̇ = −μk·N·|u̇|
while sliding. Units: J, W, s.

Never imports ``rocking``: the samples come in as arrays, the regime as the Response's codes
(bit 1: the statue rocks; bit 2: the body on the floor slides).
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numpy as np
from scipy.interpolate import CubicSpline

from . import lagrange

ROCKS, SLIDES = 1, 2  # bits of the regime code


class Ledger(NamedTuple):
    """Every array has one value per saved sample (J)."""

    energy: np.ndarray  #: E, mechanical energy relative to the floor
    input_work: np.ndarray  #: W, work of the floor's inertial forces since the start
    friction: np.ndarray  #: D, energy dissipated by floor friction since the start
    jumps: np.ndarray  #: D_impact, energy lost at events (impacts) since the start
    losses: list  #: (time, E before − E after) at every instant saved twice

    @property
    def residual(self) -> np.ndarray:
        """E − E0 − W + D + D_impact: zero for an exact solution."""
        return self.energy - self.energy[0] - self.input_work + self.friction + self.jumps

    @property
    def scale(self) -> float:
        """The largest energy of the run, to make the residual relative."""
        return float(max(np.max(np.abs(self.energy - self.energy[0])), np.max(np.abs(self.input_work)),
                         np.max(self.friction), np.max(self.jumps), 1e-300))


def _majority_sign(x: np.ndarray) -> int:
    """The sign most samples of a smooth stretch have (its first sample may sit on θ = 0)."""
    total = np.sum(np.sign(x))
    return 1 if total > 0 else (-1 if total < 0 else 0)


def _pivot(theta: np.ndarray, theta_dot: np.ndarray) -> int:
    """The corner (±1) a statue rocks on during one flight (a stretch between events).

    A flight that starts on θ = 0 (just after an impact) leaves it towards its pivot. Otherwise
    the pivot is the side of the largest |θ|: the sample just before an impact sits on θ ≈ 0
    within the event tolerance, on either side, and must not decide. A lone sample on
    θ = θ̇ = 0 (an uplift and nothing after it) adds nothing, whatever the answer."""
    if theta[0] == 0.0 and theta_dot[0] != 0.0:
        return 1 if theta_dot[0] > 0 else -1
    k = int(np.argmax(np.abs(theta)))
    if theta[k] != 0.0:
        return 1 if theta[k] > 0 else -1
    if theta_dot[-1] != 0.0:  # arriving at θ = 0 moves away from the pivot
        return -1 if theta_dot[-1] > 0 else 1
    return 1


def _segments(t, regimes, breaks):
    """[(i0, i1)]: stretches of samples (inclusive) without an event, a regime change or a
    jump/kink of the floor motion inside them."""
    cut = np.zeros(t.size, dtype=bool)  # cut[i]: a stretch ends at i, the next starts at i + 1
    twice = t[1:] == t[:-1]  # an instant saved twice: before and after an event
    changed = regimes[1:] != regimes[:-1]
    if np.any(changed & ~twice):
        i = int(np.flatnonzero(changed & ~twice)[0])
        raise ValueError(f"the regime changes between the samples at t = {t[i]} and {t[i + 1]} s (at a jump "
                         "of the floor motion): end the run before it, or save on a grid that contains it")
    cut[:-1] |= twice
    starts_at_sample = np.zeros(t.size, dtype=bool)  # a stretch also ends *at* a floor break
    for tb in breaks:
        if not t[0] < tb < t[-1]:
            continue
        j = int(np.argmin(np.abs(t - tb)))
        if abs(t[j] - tb) > 1e-9 * max(1.0, abs(tb)):
            raise ValueError(f"the floor motion breaks at t = {tb} s between two samples: "
                             "save on a grid that contains its breakpoints")
        starts_at_sample[j] = True
    out, i0 = [], 0
    for i in range(t.size):
        if i == t.size - 1 or cut[i]:
            out.append((i0, i))
            i0 = i + 1
        elif starts_at_sample[i] and i > i0:
            out.append((i0, i))
            i0 = i  # the break sample belongs to both sides (the state is continuous there)
    return out


def _cumulative(t, f):
    """∫ f dt from t[0] to every t[i] (cubic spline; trapezoids for fewer than 4 samples)."""
    if t.size < 2:
        return np.zeros(t.size)
    if t.size < 4:
        return np.concatenate(([0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(t))))
    anti = CubicSpline(t, f).antiderivative()
    return anti(t) - anti(t[0])


def ledger(t, state, regimes, params: dict, a_g: Callable, a_v: Callable, breaks=()) -> Ledger:
    """The energy ledger of a run from its saved samples.

    t (s), state rows (u, u̇, θ, θ̇) in m, m/s, rad, rad/s, regime codes per sample;
    params as for ``lagrange`` (b, h, m1, m2, g, mu_k, normal_force); a_g, a_v: the floor's
    horizontal and vertical acceleration (m/s²) as functions of an array of times; breaks: the
    times (s) where those are not smooth (each must be a saved sample).
    """
    t = np.asarray(t, dtype=float)
    state = np.asarray(state, dtype=float)
    regimes = np.asarray(regimes, dtype=int)
    m1, m2 = float(params["m1"]), float(params["m2"])
    n = t.size
    energy = np.empty(n)
    work, fric, jumps = np.zeros(n), np.zeros(n), np.zeros(n)
    losses = []
    segments = _segments(t, regimes, breaks)
    # Integrate stretch by stretch, carrying the totals over events and breaks.
    w_total = d_total = j_total = 0.0
    previous_end = None
    for i0, i1 in segments:
        sl = slice(i0, i1 + 1)
        # The floor's acceleration at a stretch's end samples is its limit from inside the
        # stretch: at a jump (a pulse's or a cos harmonic's end) the sample shared by two
        # stretches has one value on each side, and the power there must use its own side's.
        ts = t[sl].copy()
        if ts.size > 1:
            # (never past a quarter of the stretch, which may be a sliver between two events)
            inward = min(1e-12 * max(1.0, abs(ts[0]), abs(ts[-1])), 0.25 * (ts[-1] - ts[0]))
            ts[0] += inward
            ts[-1] -= inward
        ag, av = np.asarray(a_g(ts), dtype=float), np.asarray(a_v(ts), dtype=float)
        code = int(regimes[i0])
        s = _pivot(state[sl, 2], state[sl, 3]) if code & ROCKS else 0
        sigma = _majority_sign(state[sl, 1]) if code & SLIDES else 0
        name = ("slide-" if code & SLIDES else "stick-") + ("rock" if code & ROCKS else "rest")
        power_in = np.zeros(ts.size)
        power_fric = np.zeros(ts.size)
        for k, i in enumerate(range(i0, i1 + 1)):
            y = tuple(state[i])
            pivot = s or 1  # at rest θ = θ̇ = 0 and either pivot describes the same state
            energy[i] = lagrange.energy(params, y, s=pivot)
            vx, vy = lagrange.statue_velocity_rel(params, y, s=pivot)
            power_in[k] = -ag[k] * (m1 * y[1] + m2 * vx) - av[k] * m2 * vy
            if sigma:
                kw = {"sigma": sigma, **({"s": s} if s else {})}
                force = lagrange.accelerations(name, params, y, ag[k], av[k], **kw)[3]
                power_fric[k] = -force * y[1]
        if previous_end is not None and previous_end != i0:  # an instant saved twice
            loss = energy[previous_end] - energy[i0]
            losses.append((float(t[i0]), float(loss)))
            j_total += loss
        if previous_end == i0:  # continuing through a break sample
            w_start, d_start = work[i0], fric[i0]
        else:
            w_start, d_start = w_total, d_total
        work[sl] = w_start + _cumulative(t[sl], power_in)
        fric[sl] = d_start + _cumulative(t[sl], power_fric)
        jumps[sl] = j_total
        w_total, d_total = work[i1], fric[i1]
        previous_end = i1
    return Ledger(energy, work, fric, jumps, losses)


def lagrange_params(system, gravity: float, normal_force: str = "full") -> dict:
    """lagrange's parameter dict read off a ``rocking.System`` by attribute (SI units)."""
    st, ped = system.statue, system.pedestal
    friction = ped.friction if ped is not None else st.friction
    return dict(b=0.5 * st.width, h=0.5 * st.height, m1=ped.mass if ped is not None else 0.0, m2=st.mass,
                g=gravity, mu_s=math.inf if friction is None else friction.mu_s,
                mu_k=math.inf if friction is None else friction.mu_k, normal_force=normal_force)
