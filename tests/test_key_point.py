"""``Response.key_point`` (paper Eqs. 7–13) against geometry written out here.

Positions: the four corners and the top centre of the statue at given θ, about both pivots, on
a pedestal displaced by u, from elementary geometry (the corner on the floor stays put, the far
base corner rises by 2b·sin|θ|, the side above the pivot leans by θ), not from a rotation matrix
about a pivot as the library does. Velocities and the absolute acceleration: finite differences
of those positions along a simulated slide-rock run.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from helpers import G

import rocking as rk
from rocking.models.regimes import Regime

STATUE = rk.Statue(width=1.0, height=4.0, mass=2.0, restitution=0.8)
PEDESTAL = rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3))


def corners_and_top(b, h, u, theta):
    """Positions (m, relative to the floor; y up from the statue's base) of the statue's
    points named below when its base centre sat at x = u upright and it now leans by θ
    (θ > 0: about its +x corner, towards +x)."""
    s = 1.0 if theta > 0 else -1.0
    lean = abs(theta)
    pivot = (u + s * b, 0.0)  # the corner it rocks on does not move
    # The base runs from the pivot back towards the other corner, tilted up by |θ|.
    far_base = (pivot[0] - s * 2 * b * math.cos(lean), 2 * b * math.sin(lean))
    # The side above the pivot is tilted by |θ| from the vertical, towards the lean.
    up = (s * 2 * h * math.sin(lean), 2 * h * math.cos(lean))
    above_pivot = (pivot[0] + up[0], up[1])
    above_far = (far_base[0] + up[0], far_base[1] + up[1])
    top_centre = (0.5 * (above_pivot[0] + above_far[0]), 0.5 * (above_pivot[1] + above_far[1]))
    base_plus, base_minus = (pivot, far_base) if s > 0 else (far_base, pivot)
    top_plus, top_minus = (above_pivot, above_far) if s > 0 else (above_far, above_pivot)
    return {(b, 0.0): base_plus, (-b, 0.0): base_minus, (b, 2 * h): top_plus, (-b, 2 * h): top_minus,
            (0.0, 2 * h): top_centre}


def _response_with(states, regimes):
    """A Response whose saved samples are the given (u, u̇, θ, θ̇) rows: key_point reads only
    those, the system, the motion and the parameters."""
    system = rk.System(statue=STATUE, pedestal=PEDESTAL)
    motion = rk.Harmonic(amplitude=2.0, frequency=1.0, cycles=1)
    base = rk.simulate(system, motion, duration=0.05, options=rk.Options(gravity=G))
    states = np.asarray(states, dtype=float)
    regimes = np.asarray(regimes, dtype=np.int8)
    # the rows' own signs: none of them is at θ = 0 or, while sliding, at u̇ = 0
    pivot = np.where(regimes & 1, np.sign(states[:, 2]), 0).astype(np.int8)
    slip = np.where(regimes & 2, np.sign(states[:, 1]), 0).astype(np.int8)
    return dataclasses.replace(base, t=np.linspace(0.0, 0.5, len(states)), state=states,
                               regime_codes=regimes, pivot=pivot, slip_direction=slip)


def test_positions_of_the_corners_and_top_centre_at_given_angles():
    b, h, alpha = STATUE.b, STATUE.h, STATUE.slenderness
    states, regimes, expected = [], [], []
    for s in (1, -1):
        for lean in (1e-3, 0.1, 0.5 * alpha, alpha, 1.0, 1.5):
            theta = s * lean
            for u, u_dot in ((0.0, 0.0), (0.37, 0.4), (-1.2, -0.3)):  # held, then sliding both ways
                states.append((u, u_dot, theta, -0.7 * s))
                regimes.append(Regime.SLIDE_ROCK if u_dot else Regime.ROCK)
                expected.append(corners_and_top(b, h, u, theta))
    r = _response_with(states, regimes)
    for point in expected[0]:
        kp = r.key_point(*point)
        x_want = np.array([e[point][0] for e in expected]) - point[0]
        y_want = np.array([e[point][1] for e in expected]) - point[1]
        np.testing.assert_allclose(kp["x"], x_want, rtol=0, atol=1e-14, err_msg=f"x of {point}")
        np.testing.assert_allclose(kp["y"], y_want, rtol=0, atol=1e-14, err_msg=f"y of {point}")


def test_the_statue_moves_as_a_rigid_body_about_the_right_corner():
    """Invariants that need no formula: the pivot corner stays on the floor at u ± b, the far
    base corner is the one that rises, and every distance between the corners is kept."""
    b, h = STATUE.b, STATUE.h
    thetas = np.array([-1.2, -0.3, -0.01, 0.01, 0.3, 1.2])
    u = np.linspace(-0.5, 0.5, thetas.size)
    states = [(ui, 0.2, th, 0.5) for ui, th in zip(u, thetas)]
    r = _response_with(states, [Regime.SLIDE_ROCK] * len(states))
    pts = {}
    for x0, y0 in ((b, 0.0), (-b, 0.0), (b, 2 * h), (-b, 2 * h)):
        kp = r.key_point(x0, y0)
        pts[(x0, y0)] = np.stack([x0 + kp["x"], y0 + kp["y"]])
    s = np.sign(thetas)
    pivot = np.where(s > 0, pts[(b, 0.0)], pts[(-b, 0.0)])
    other = np.where(s > 0, pts[(-b, 0.0)], pts[(b, 0.0)])
    np.testing.assert_allclose(pivot[0], u + s * b, atol=1e-15)
    np.testing.assert_allclose(pivot[1], 0.0, atol=1e-15)
    np.testing.assert_allclose(other[1], 2 * b * np.sin(np.abs(thetas)), rtol=1e-14)
    dist = lambda p, q: np.hypot(*(pts[p] - pts[q]))  # noqa: E731
    np.testing.assert_allclose(dist((b, 0.0), (-b, 0.0)), 2 * b, rtol=1e-14)
    np.testing.assert_allclose(dist((b, 0.0), (b, 2 * h)), 2 * h, rtol=1e-14)
    np.testing.assert_allclose(dist((-b, 0.0), (b, 2 * h)), 2 * math.hypot(b, h), rtol=1e-14)


# -- velocities and accelerations: finite differences of the positions above ------------------------------
DT = 2e-3  # s, the saved grid


def _five_point(z, i, dt):
    """First and second derivatives at samples i by the 5-point central stencils."""
    d1 = (z[i - 2] - 8 * z[i - 1] + 8 * z[i + 1] - z[i + 2]) / (12 * dt)
    d2 = (-z[i - 2] + 16 * z[i - 1] - 30 * z[i] + 16 * z[i + 1] - z[i + 2]) / (12 * dt**2)
    return d1, d2


def _smooth_points(r, dt):
    """Samples i with i ± 1, i ± 2 on the uniform grid in the same regime and about the same
    pivot, with no event and no jump of the floor motion inside the stencil."""
    t, th, reg = r.t, r.theta, r.regime
    i = np.arange(2, t.size - 2)
    ok = np.ones(i.size, dtype=bool)
    for k in (-2, -1, 0, 1):
        ok &= np.abs(t[i + k + 1] - t[i + k] - dt) < 1e-9
    for k in (-2, -1, 1, 2):
        ok &= (reg[i + k] == reg[i]) & (np.sign(th[i + k]) == np.sign(th[i]))
    for jump in r.motion.breakpoints:
        ok &= (t[i + 2] < jump) | (t[i - 2] > jump)
    return i[ok]


def test_velocities_and_acceleration_match_finite_differences_on_a_sliding_pedestal():
    system = rk.System(statue=STATUE, pedestal=PEDESTAL)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=4)
    # Tight tolerances: the second difference amplifies the position error by ~5/dt².
    r = rk.simulate(system, motion, duration=motion.duration,
                    options=rk.Options(gravity=G, save_dt=DT, rtol=1e-12, atol=1e-14))
    i = _smooth_points(r, DT)
    # Both pivots, the pedestal held and sliding: every branch of Eqs. 8–13.
    assert set(np.unique(r.regime[i])) == {Regime.ROCK, Regime.SLIDE_ROCK}
    assert set(np.sign(r.theta[i])) == {-1.0, 1.0}
    assert i.size > 1500
    b, h = STATUE.b, STATUE.h
    for point in ((0.0, 2 * h), (b, 2 * h), (-b, 0.0), (b, 0.0)):
        pos = np.array([corners_and_top(b, h, u, th)[point] for u, th in zip(r.u, r.theta)]).T
        vx, ax = _five_point(pos[0], i, DT)
        vy, _ = _five_point(pos[1], i, DT)
        kp = r.key_point(*point)
        # Stencil errors: dt⁴/30·x⁽⁵⁾ ≈ 2e-9 m/s for the velocity; for the acceleration the
        # solver's position error (~1e-13 m) times 5/dt² ≈ 1.5e-7 m/s² dominates dt⁴/90·x⁽⁶⁾.
        np.testing.assert_allclose(kp["x_dot"][i], vx, rtol=0, atol=1e-8, err_msg=f"x_dot of {point}")
        np.testing.assert_allclose(kp["y_dot"][i], vy, rtol=0, atol=1e-8, err_msg=f"y_dot of {point}")
        np.testing.assert_allclose(kp["absolute_acceleration"][i], ax + motion.acceleration(r.t[i]),
                                   rtol=0, atol=1e-6, err_msg=f"absolute acceleration of {point}")


def test_a_statue_at_rest_moves_with_its_sliding_pedestal():
    """Case 9a's statue never rocks: each of its points moves as the pedestal does, x = u,
    ẋ = u̇, and its absolute acceleration is a_g + ü."""
    system = rk.System(statue=rk.Statue(width=1.0, height=2.0, mass=1.0), pedestal=PEDESTAL)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=1)
    r = rk.simulate(system, motion, options=rk.Options(gravity=G, save_dt=DT, rtol=1e-12, atol=1e-14))
    assert r.peak_rotation == 0.0 and np.any(r.u != 0)
    kp = r.key_point(0.3, 1.7)
    np.testing.assert_array_equal(kp["x"], r.u)
    np.testing.assert_array_equal(kp["y"], 0.0)
    np.testing.assert_array_equal(kp["x_dot"], r.u_dot)
    np.testing.assert_array_equal(kp["y_dot"], 0.0)
    i = _smooth_points(r, DT)
    sliding = i[r.regime[i] == Regime.SLIDE]
    assert sliding.size > 100
    _, a = _five_point(r.u, sliding, DT)
    np.testing.assert_allclose(kp["absolute_acceleration"][sliding], a + motion.acceleration(r.t[sliding]),
                               rtol=0, atol=1e-6)
