"""Small builders shared by the solver tests (g = 9.81 m/s², as in the oracles)."""

import math

import numpy as np

import rocking as rk

G = 9.81
OPTS = rk.Options(gravity=G)
NO_MOTION = rk.Harmonic(amplitude=0.0, frequency=1.0, cycles=1.0)


def block(b, h, *, mass=1.0, restitution=None, friction=None):
    """A statue of half-width b and half-height h (m)."""
    return rk.Statue(width=2 * b, height=2 * h, mass=mass, restitution=restitution, friction=friction)


def alone(statue):
    return rk.System(statue=statue)


def slender(alpha, h=1.0, **kw):
    """A block of slenderness α (rad) and half-height h."""
    return block(h * math.tan(alpha), h, **kw)


def p_of(statue):
    return statue.frequency_parameter(G)


def first_event(response, kind):
    for e in response.events:
        if e.kind == kind:
            return e
    return None


def on_grid(response, dt):
    """(t, θ, u) of a response on the uniform grid k·dt: the extra rows saved at event instants
    are dropped, and of two rows at one grid time the first (the state before the event) is kept."""
    k = np.rint(response.t / dt)
    on = response.t == k * dt
    _, first = np.unique(k[on], return_index=True)
    rows = np.flatnonzero(on)[first]
    return response.t[rows], response.theta[rows], response.u[rows]


def free_rocking(system, energy_over_barrier, theta0, cut=0.06, options=None, duration=None, motion=None):
    """A statue set rocking at θ0 (rad) away from upright, with the angular velocity that gives it
    ``energy_over_barrier`` × the overturning barrier (T + V by the closed forms of a block on a
    fixed corner: V = m·g·(R·cos(α − θ) − h), T = ½·(4/3)·m·R²·θ̇²), on a floor that never moves
    (a rectangle pulse of zero amplitude, 0.01 s long), cut ``cut`` s later while it still
    rocks outwards."""
    st = system.statue
    g = 9.5
    m, R, alpha, h = st.mass, math.hypot(st.b, st.h), math.atan2(st.b, st.h), st.h
    barrier = m * g * (R - h)
    v0 = m * g * (R * math.cos(alpha - theta0) - h)
    rate = math.sqrt(max(energy_over_barrier * barrier - v0, 0.0) / (0.5 * 4.0 / 3.0 * m * R * R))
    opts = options or rk.Options(gravity=g, free_time_limit=cut - 0.01)
    return rk.simulate(system, motion or rk.RectanglePulse(amplitude=0.0, width=0.01), options=opts,
                       duration=duration, initial_rotation=theta0, initial_angular_velocity=rate)
