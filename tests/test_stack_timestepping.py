"""Moreau–Jean time stepping of a block stack (rocking.stack.timestepping) against closed forms.

The method is first order: an impact, the start or end of a slip, or a jump of the floor's
acceleration falls inside a step, and contacts are enforced on velocities only, so errors are
O(Δt) in general. Each tolerance below says where its size comes from. Nothing here compares
with another rocking module: the point of this solver is to be independent of them.
"""

import math

import numpy as np
import pytest

from rocking.contact.friction import Friction
from rocking.stack.lcp import LCPError, lemke
from rocking.stack.model import Block, Interface, Stack
from rocking.stack.timestepping import moreau_jean, relative_pose, rest_pose

G = 9.80665

# The slender block of the rocking tests: B/H = 0.2, α = atan(0.2).
B, H, M = 0.4, 2.0, 100.0
ALPHA = math.atan(B / H)
R = 0.5 * math.hypot(B, H)  # centre to corner, m
J_O = M * (B**2 + H**2) / 12 + M * R**2  # inertia about a corner, kg·m²


def single(width=B, height=H, mass=M, friction=None):
    return Stack(blocks=(Block(width=width, height=height, mass=mass),), interfaces=(Interface(friction=friction),))


def statue_on_pedestal(top_friction=None):
    return Stack(
        blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=100.0, offset=0.1)),
        interfaces=(Interface(friction=Friction(static=0.3, kinetic=0.25)), Interface(friction=top_friction)),
    )


def on_right_corner(theta0, width=B, height=H):
    """Pose (1, 3) of a block tilted by θ0 > 0 (clockwise) about its right bottom corner at x = B/2."""
    c, s = math.cos(theta0), math.sin(theta0)
    return np.array([[0.5 * width - 0.5 * width * c + 0.5 * height * s, 0.5 * width * s + 0.5 * height * c, theta0]])


def zero(t):
    return 0.0


# 1. free flight -------------------------------------------------------------------------------


@pytest.mark.parametrize("stack", [single(), statue_on_pedestal()], ids=["one block", "two blocks"])
def test_free_flight_parabola(stack):
    """a_v = −2g: the net vertical load is +m g, every contact opens at t = 0⁺ and each block
    rises on Y = Y0 + ½ g t² with Θ = 0. The velocity is linear in t, which the θ = ½ position
    update integrates exactly: round-off only (1e-12 m on ~1 m over 500 steps)."""
    dt = 1e-3
    res = moreau_jean(stack, zero, lambda t: -2 * G, t_end=0.5, dt=dt)
    y0 = rest_pose(stack)[:, 1]
    expected = y0[None, :] + 0.5 * G * res.t[:, None] ** 2
    assert res.status == "completed"
    assert np.abs(res.pose[..., 1] - expected).max() < 1e-12
    assert np.abs(res.velocity[..., 1] - G * res.t[:, None]).max() < 1e-12
    assert np.abs(res.pose[..., 2]).max() == 0.0  # nothing can turn a block: no moment at all
    assert np.abs(res.pose[..., 0] - rest_pose(stack)[:, 0]).max() == 0.0


def test_free_flight_implicit_euler_error_is_first_order():
    """θ = 1 updates positions with v_{n+1} only: Y_n = Y0 + ½ g t_n (t_n + Δt), an error of
    exactly ½ g Δt t_n (first order), here 2.45e-3 m at t = 0.5 s; checked to round-off."""
    dt = 1e-3
    res = moreau_jean(single(), zero, lambda t: -2 * G, t_end=0.5, dt=dt, theta=1.0)
    error = res.pose[:, 0, 1] - (0.5 * H + 0.5 * G * res.t**2)
    assert error == pytest.approx(0.5 * G * dt * res.t, abs=1e-12)


# 2. sliding -----------------------------------------------------------------------------------


def test_sliding_block_velocity_and_stop_time():
    """A squat block (B/H = 5, cannot rock for A < 5 g) with μs = μk = μ under a_h = A > μ g for
    t < t1, then 0. Relative velocity −(A − μ g) t, then −(A − μ g) t1 + μ g (t − t1) until it
    stops at t_stop = t1 A/(μ g); displacement u = −(A − μ g) A t1²/(2 μ g).

    t1 is off the grid: the step that straddles it applies A for all of the step or none of it,
    so the velocity error is at most A·Δt (the jump, once); the stop time is then off by at most
    Δt + A Δt/(μ g) and the displacement by at most A Δt · (t_stop − t1)."""
    mu, a, t1 = 0.3, 0.5 * G, 0.2345678
    stack = single(width=2.0, height=0.4, friction=Friction(static=mu))
    t_stop = t1 * a / (mu * G)
    u_end = -(a - mu * G) * a * t1**2 / (2 * mu * G)
    for dt in (5e-4, 2.5e-4):
        res = moreau_jean(stack, lambda t: a if t < t1 else 0.0, t_end=0.6, dt=dt)
        t = res.t
        v_exact = np.where(t < t1, -(a - mu * G) * t, np.minimum(0.0, -(a - mu * G) * t1 + mu * G * (t - t1)))
        v = res.velocity[:, 0, 0]
        assert np.abs(v - v_exact).max() <= a * dt * (1 + 1e-9)
        stopped = t[np.flatnonzero(np.abs(v) > 1e-12)[-1] + 1]
        assert abs(stopped - t_stop) <= dt * (1 + a / (mu * G))
        assert abs(res.pose[-1, 0, 0] - u_end) <= a * dt * (t_stop - t1)
        assert np.abs(res.pose[:, 0, 2]).max() < 1e-12  # slides flat: no rotation
        assert np.abs(res.pose[:, 0, 1] - 0.2).max() < 1e-12


def test_a_block_on_a_frictionless_face_keeps_its_place_in_space():
    """μ = 0 between a squat block and a pedestal that never slips on the floor: no horizontal
    force reaches the block, which stays where it was in space, so on the pedestal (the floor
    frame) it moves at −A t under a_h = A (½ A t² back after t). The frictionless contacts have
    no tangential unknowns while the floor's have: the LCP mixes the two. The θ = ½ positions of
    a uniform acceleration are exact: round-off only (1e-12 m and m/s over 500 steps)."""
    stack = Stack(blocks=(Block(width=1.0, height=0.3, mass=500.0), Block(width=0.6, height=0.1, mass=20.0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.0))))
    a = 0.2 * G
    res = moreau_jean(stack, lambda t: a, t_end=0.5, dt=1e-3)
    assert res.status == "completed"
    assert np.abs(res.velocity[:, 1, 0] + a * res.t).max() < 1e-12
    assert np.abs(res.pose[:, 1, 0] + 0.5 * a * res.t**2).max() < 1e-12
    assert np.abs(res.pose[:, 0, :] - rest_pose(stack)[0]).max() < 1e-12  # the pedestal holds
    assert np.abs(res.pose[:, 1, 1:] - rest_pose(stack)[1, 1:]).max() < 1e-12  # flat, on its face


def test_the_floor_acceleration_is_read_at_the_steps_theta_point():
    """The same frictionless box under a ramp a_h = c·t. Its velocity on the pedestal changes by
    −c·t_{n+θ}·Δt per step, with t_{n+θ} = t_n + θΔt: for θ = ½ (the midpoint rule, exact for a
    linear a_h) v(t_n) = −c t_n²/2, and for θ = 1 v(t_n) = −c Δt² n(n+1)/2. Sums of n terms of
    size ≤ c·t·Δt: round-off only. Read at t_n − θΔt, both would be off by c·t·θΔt (2e-4 m/s)."""
    stack = Stack(blocks=(Block(width=1.0, height=0.3, mass=500.0), Block(width=0.6, height=0.1, mass=20.0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.0))))
    c, dt = 4.0, 1e-3
    mid = moreau_jean(stack, lambda t: c * t, t_end=0.1, dt=dt)
    assert np.abs(mid.velocity[:, 1, 0] + 0.5 * c * mid.t**2).max() < 1e-14
    end = moreau_jean(stack, lambda t: c * t, t_end=0.1, dt=dt, theta=1.0)
    n = np.rint(end.t / dt)
    assert np.abs(end.velocity[:, 1, 0] + 0.5 * c * dt**2 * n * (n + 1)).max() < 1e-14


def test_static_then_kinetic_friction():
    """μs = 0.4, μk = 0.3, constant a_h = A. Between μk g and μs g the block never starts (static
    friction holds it: round-off only). Above μs g it slides at −(A − μk g): the first step uses μs
    (the block was at rest), so the velocity is off by (μs − μk) g Δt at most (first order)."""
    stack = single(width=2.0, height=0.4, friction=Friction(static=0.4, kinetic=0.3))
    dt = 1e-3
    held = moreau_jean(stack, lambda t: 0.35 * G, t_end=0.5, dt=dt)
    assert np.abs(held.velocity).max() < 1e-12
    a = 0.5 * G
    slides = moreau_jean(stack, lambda t: a, t_end=0.5, dt=dt)
    v = slides.velocity[:, 0, 0]
    assert np.abs(v - (-(a - 0.3 * G) * slides.t)).max() <= (0.4 - 0.3) * G * dt * (1 + 1e-9)


def test_a_block_launched_sliding_uses_kinetic_friction_from_the_first_step():
    """A squat block set sliding at v0 = 1 m/s (μs = 0.5, μk = 0.3): its contacts are new, and their
    tangential speed (1 m/s) is far above g Δt (1e-2 m/s), so they take μk at once. It slows at
    μk g exactly (θ = ½ integrates the uniform deceleration exactly: round-off), stopping at
    v0/(μk g) = 0.340 s."""
    stack = single(width=2.0, height=0.4, friction=Friction(static=0.5, kinetic=0.3))
    velocity0 = np.array([[1.0, 0.0, 0.0]])
    res = moreau_jean(stack, zero, t_end=0.3, dt=1e-3, velocity0=velocity0)
    assert np.abs(res.velocity[:, 0, 0] - (1.0 - 0.3 * G * res.t)).max() < 1e-12


# 3. rocking onset -----------------------------------------------------------------------------


def test_rocking_onset_threshold():
    """Under a constant a_h = A a block with infinite friction rocks iff A > g B/H. Just below
    (0.95 g B/H) it must stay exactly at rest (round-off: < 1e-12). Just above (1.05 g B/H)
    it tips towards −x (Θ < 0, about its left corner) as φ = −Θ = C (cosh λt − 1), the
    linearisation of J_O φ̈ = m R (A cos(α − φ) − g sin(α − φ)) with
    λ² = m R (A sin α + g cos α)/J_O, C = (A cos α − g sin α)/(A sin α + g cos α).
    The neglected term is ½ φ² (A cos α − g sin α) m R, relative size < 1e-4 at φ ≈ 0.02;
    the time stepping adds O(Δt) from the pivot drift: 1e-3 relative covers both
    (measured: 8e-6 at t = 0.6 s)."""
    stack = single()
    below = moreau_jean(stack, lambda t: 0.95 * G * B / H, t_end=0.6, dt=2e-4)
    assert np.abs(below.pose[:, 0, :] - rest_pose(stack)[0]).max() < 1e-12
    assert np.abs(below.velocity).max() < 1e-12

    a = 1.05 * G * B / H
    above = moreau_jean(stack, lambda t: a, t_end=0.6, dt=2e-4)
    lam = math.sqrt(M * R * (a * math.sin(ALPHA) + G * math.cos(ALPHA)) / J_O)
    c = (a * math.cos(ALPHA) - G * math.sin(ALPHA)) / (a * math.sin(ALPHA) + G * math.cos(ALPHA))
    phi = -above.pose[:, 0, 2]
    assert above.status == "completed"
    assert phi[-1] > 0.01  # it rocks, towards −x
    assert phi[-1] == pytest.approx(c * (math.cosh(lam * 0.6) - 1), rel=1e-3)
    # The pivot (left corner) neither slips nor lifts: only the velocity-level drift moves it
    # (measured 8e-8 m along x, 4e-7 m along y).
    x, y, th = above.pose[:, 0, 0], above.pose[:, 0, 1], above.pose[:, 0, 2]
    assert np.abs(x - 0.5 * B * np.cos(th) - 0.5 * H * np.sin(th) + 0.5 * B).max() < 1e-6
    assert np.abs(y + 0.5 * B * np.sin(th) - 0.5 * H * np.cos(th)).max() < 1e-6


def test_interface_without_friction_never_slips():
    """Interface.friction = None: a squat block (rocks only above 5 g) under a_h = 3 g stays put
    (round-off); any slip would show at once as a velocity of order g Δt = 1e-2 m/s."""
    res = moreau_jean(single(width=2.0, height=0.4), lambda t: 3 * G, t_end=0.5, dt=1e-3)
    assert np.abs(res.velocity).max() < 1e-12


# 4. Housner's impact --------------------------------------------------------------------------


def _tilted_statue(theta0):
    """The statue on pedestal with the statue tilted by θ0 about its right corner (on the pedestal)."""
    stack = statue_on_pedestal()
    pose = rest_pose(stack)
    pose[1] = on_right_corner(theta0, 0.3, 1.2)[0] + [0.1, 0.5, 0.0]  # its corner at (0.25, 0.5)
    return stack, pose


def _energy(stack, res):
    """Kinetic + gravitational energy of the stack at each saved time, J."""
    m = np.array([b.mass for b in stack.blocks])
    j = np.array([b.centroidal_inertia for b in stack.blocks])
    v = res.velocity
    return (0.5 * m * (v[..., 0] ** 2 + v[..., 1] ** 2) + 0.5 * j * v[..., 2] ** 2 + m * G * res.pose[..., 1]).sum(1)


@pytest.mark.parametrize("case", ["block on floor", "statue on pedestal"])
def test_housner_impact_ratio_converges(case):
    """Released from Θ0 = 0.1 rad at rest, with infinite friction under the rocking block, it
    rocks back on its right corner and lands on its left one: Θ̇⁺/Θ̇⁻ → 1 − 1.5 sin²α (Housner;
    0.94231 for the block, B/H = 0.2, and 0.91176 for the statue, B/H = 0.25) as Δt → 0. The
    statue lands on the pedestal, which its floor contacts hold still.

    The impact happens at Θ = O(Δt) and gravity acts during the impact step, so the error is
    O(Δt): measured −1.17e-3, −5.9e-4, −2.9e-4 (block) and −1.60e-3, −8.0e-4, −4.0e-4 (statue) at
    Δt = 4e-4, 2e-4, 1e-4 s. Asserted: the error halves with Δt (ratio 2 ± 0.3) and is below 5e-4
    at 1e-4 s. The energy may only fall (plastic impact), up to the O(Δt) that velocity-level
    contacts let drift in: the sum of its step-to-step increases (measured 8.4e-3, 4.2e-3,
    2.1e-3 J on 1826 J for the statue) must halve with Δt as well."""
    if case == "block on floor":
        stack, pose0, k, alpha = single(), on_right_corner(0.1), 0, ALPHA
    else:
        (stack, pose0), k, alpha = _tilted_statue(0.1), 1, math.atan(0.3 / 1.2)
    housner = 1 - 1.5 * math.sin(alpha) ** 2
    errors, gains = [], []
    for dt in (4e-4, 2e-4, 1e-4):
        res = moreau_jean(stack, zero, t_end=0.55, dt=dt, pose0=pose0)
        w = res.velocity[:, k, 2]
        j = int(np.argmax(np.abs(np.diff(w))))  # the step with the impulse
        assert 0.3 < res.t[j] < 0.55 and w[j] < 0  # the first impact, falling back towards −x
        errors.append(abs(w[j + 1] / w[j] - housner))
        energy = _energy(stack, res)
        assert energy[-1] < energy[0]
        gains.append(np.maximum(np.diff(energy), 0.0).sum())
    assert errors[0] / errors[1] == pytest.approx(2.0, abs=0.3)
    assert errors[1] / errors[2] == pytest.approx(2.0, abs=0.3)
    assert errors[2] < 5e-4
    assert gains[0] / gains[1] == pytest.approx(2.0, abs=0.3) and gains[1] / gains[2] == pytest.approx(2.0, abs=0.3)


def test_a_wide_box_rocks_on_the_corners_of_a_narrow_plinth():
    """A box wider than its plinth (0.8 × 0.8 m, 50 kg, on 0.4 × 0.3 m, 20 t, neither slipping)
    touches the plinth at the plinth's top corners, which lie under the box's bottom face. Released
    at rest, tilted by φ0 = 0.05 rad about the plinth's right corner, it rocks back and lands on the
    left one.

    About a plinth corner the box is a rocking body with b = 0.2 m (half the plinth's width),
    h = 0.4 m (half its own height), R = √(b² + h²), tan α = b/h, J_O = J_G + m R². Energy gives the
    rate at landing, ω⁻ = √(2 m g R (cos(α − φ0) − cos α)/J_O) = 0.7789 rad/s, and angular momentum
    about the new corner the ratio ω⁺/ω⁻ = (J_G + m(h² − b²))/(J_G + m(h² + b²)) = 0.73913
    (Housner's law for this geometry) if the plinth holds still. It must be heavy for that: the
    impulse on its top corner would lift its far floor corner, and a 2 t plinth does lift (the
    ratio then tends to 0.7359, not 0.7391); at 20 t the lift is below round-off.

    The step that holds the impact starts up to one Δt before it (ω̇ ≈ 6 rad/s²): ω⁻ measured
    1.7e-4 relative off at Δt = 1e-4 s, asserted 1e-3. The ratio's error is O(Δt) as in
    test_housner_impact_ratio_converges (measured −3.05e-3, −1.56e-3, −7.7e-4 at Δt = 4e-4, 2e-4,
    1e-4 s): asserted to halve with Δt (2 ± 0.3) and to be below 1e-3 at 1e-4 s."""
    m, b, h = 50.0, 0.2, 0.4
    stack = Stack(blocks=(Block(width=0.4, height=0.3, mass=2e4), Block(width=0.8, height=0.8, mass=m)),
                  interfaces=(Interface(), Interface()))
    j_g = stack.blocks[1].centroidal_inertia
    r, alpha, phi0 = math.hypot(b, h), math.atan(b / h), 0.05
    j_o = j_g + m * r**2
    omega_minus = math.sqrt(2 * m * G * r * (math.cos(alpha - phi0) - math.cos(alpha)) / j_o)
    ratio = (j_g + m * (h**2 - b**2)) / (j_g + m * (h**2 + b**2))
    pose = rest_pose(stack)
    c, s = math.cos(phi0), math.sin(phi0)
    # the box's local point (b, −h) pinned at the plinth's right corner (0.2, 0.3); Θ clockwise
    pose[1] = [b - b * c + h * s, 0.3 + b * s + h * c, phi0]
    errors = []
    for dt in (4e-4, 2e-4, 1e-4):
        res = moreau_jean(stack, zero, t_end=0.2, dt=dt, pose0=pose)
        w = res.velocity[:, 1, 2]
        k = int(np.argmax(np.abs(np.diff(w))))
        assert 0.1 < res.t[k] < 0.2 and w[k] < 0
        errors.append(abs(w[k + 1] / w[k] - ratio))
        assert np.abs(res.pose[:, 0, :] - rest_pose(stack)[0]).max() < 1e-12  # the plinth stays put
    assert -w[k] == pytest.approx(omega_minus, rel=1e-3)  # at the last, finest step
    assert errors[0] / errors[1] == pytest.approx(2.0, abs=0.3)
    assert errors[1] / errors[2] == pytest.approx(2.0, abs=0.3)
    assert errors[2] < 1e-3


def test_body_frame_round_trip():
    """The time stepper's own geometry: a body point's floor position, brought back into the
    body's frame, is the point, for 200 random poses (round-off, ~1e-15 on values up to ~4;
    asserted 1e-13)."""
    from rocking.stack.timestepping import _body_point, _to_body

    rng = np.random.default_rng(3)
    for _ in range(200):
        pose = (rng.normal(), rng.normal(), rng.uniform(-3.0, 3.0))
        xi, eta = rng.normal(size=2)
        assert _to_body(pose, *_body_point(pose, xi, eta)) == pytest.approx((xi, eta), abs=1e-13)


# 5. convergence -------------------------------------------------------------------------------


def _rate_at(phi_star, dt, theta):
    """φ̇ = −Θ̇ when φ = −Θ first reaches φ* under a_h = 1.5 g B/H (linear interpolation in t)."""
    res = moreau_jean(single(), lambda t: 1.5 * G * B / H, t_end=0.4, dt=dt, theta=theta)
    phi, rate = -res.pose[:, 0, 2], -res.velocity[:, 0, 2]
    i = int(np.flatnonzero(phi >= phi_star)[0])
    f = (phi_star - phi[i - 1]) / (phi[i] - phi[i - 1])
    return rate[i - 1] + f * (rate[i] - rate[i - 1])


def test_rocking_rate_converges_first_order():
    """While the block rocks on its left corner under a constant a_h = A = 1.5 g B/H, energy gives
    ½ J_O φ̇² = m R [A (sin α − sin(α − φ)) + g (cos α − cos(α − φ))] exactly. φ̇ at φ* = 0.05 rad:
    with θ = 1 the error is first order (measured −2.43e-4, −1.21e-4, −6.06e-5 at Δt = 8e-4, 4e-4,
    2e-4 s: observed order 1.00); asserted: order in [0.9, 1.1]. θ = ½ is far more accurate on
    this smooth motion (measured 3e-7 at 2e-4 s, round-off and interpolation); asserted < 5e-6."""
    a, phi_star = 1.5 * G * B / H, 0.05
    drop = math.cos(ALPHA) - math.cos(ALPHA - phi_star)  # fall of the centre over R (< 0: it rises)
    work = M * R * (a * (math.sin(ALPHA) - math.sin(ALPHA - phi_star)) + G * drop)
    exact = math.sqrt(2 * work / J_O)
    errors = [abs(_rate_at(phi_star, dt, 1.0) - exact) for dt in (8e-4, 4e-4, 2e-4)]
    orders = [math.log2(errors[i] / errors[i + 1]) for i in range(2)]
    assert all(0.9 <= p <= 1.1 for p in orders), (errors, orders)
    assert abs(_rate_at(phi_star, 2e-4, 0.5) - exact) < 5e-6


# 6. a stack at rest ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "stack",
    [
        statue_on_pedestal(),
        statue_on_pedestal(top_friction=Friction(static=0.5, kinetic=0.4)),
        Stack(blocks=(Block(width=0.3, height=0.6, mass=100.0), Block(width=0.3, height=0.6, mass=100.0)),
              interfaces=(Interface(), Interface(friction=Friction(static=0.6)))),
        Stack(blocks=(Block(width=1.2, height=0.4, mass=400.0), Block(width=0.4, height=1.4, mass=150.0),
                      Block(width=0.2, height=0.45, mass=8.0, offset=0.05)),
              interfaces=(Interface(friction=Friction(static=0.4)), Interface(), Interface(friction=Friction(static=0.5)))),
    ],
    ids=["statue on pedestal", "with friction on top", "equal widths (coincident corners)", "three blocks"],
)
def test_blocks_at_rest_stay_at_rest(stack):
    """Gravity alone: the LCP must balance it exactly each step (the resting contacts are
    statically indeterminate). Any drift would be round-off: < 1e-12 m and rad over 2 s (2000
    steps); measured ~1e-15."""
    res = moreau_jean(stack, zero, t_end=2.0, dt=1e-3, save_every=50)
    assert res.status == "completed" and res.t[-1] == pytest.approx(2.0)
    assert np.abs(res.pose - rest_pose(stack)[None]).max() < 1e-12
    assert np.abs(res.velocity).max() < 1e-12


def test_relative_pose_of_a_moved_and_turned_lower_block():
    """relative_pose reads block 2 in block 1's body frame: with block 1 at (X1, Y1, Θ1) and block 2
    placed at block 1's body point (ξ, η) = (0.12, 0.9) turned by φ = 0.07 rad more, it returns
    (ξ, η, φ), and block 3 likewise in block 2's frame. The placement is written here from the
    module's convention (a body point (ξ, η) lies at (X + ξ cos Θ + η sin Θ, Y − ξ sin Θ + η cos Θ));
    round-off only."""
    from rocking.stack.timestepping import StackTimeSteppingResult

    def placed(x, y, th, xi, eta, phi):  # block k + 1's pose from block k's and the relative one
        c, s = math.cos(th), math.sin(th)
        return [x + xi * c + eta * s, y - xi * s + eta * c, th + phi]

    first = [0.31, 0.27, -0.2]
    second = placed(*first, 0.12, 0.9, 0.07)
    third = placed(*second, -0.05, 0.6, -0.3)  # a third block: each is read against the one under it
    pose = np.array([[first, second, third]])
    res = StackTimeSteppingResult(t=np.zeros(1), pose=pose, velocity=np.zeros_like(pose), overturned=(False,) * 3,
                                  overturn_time=(math.nan,) * 3, status="completed", dt=1e-3, theta=0.5)
    rel = relative_pose(res)
    assert rel[0, 0] == pytest.approx(first, abs=1e-15)
    assert rel[0, 1] == pytest.approx([0.12, 0.9, 0.07], abs=1e-14)
    assert rel[0, 2] == pytest.approx([-0.05, 0.6, -0.3], abs=1e-14)


@pytest.mark.parametrize(
    "beyond, turn, falls",
    [(1e-3, 0.0, True), (-1e-3, 0.0, False), (-0.3, 0.5 * math.pi + 1e-3, True), (-0.3, 0.5 * math.pi - 1e-3, False)],
)
def test_falling_off_is_judged_relative_to_the_turned_block_below(beyond, turn, falls):
    """A 1.0 × 0.3 m plinth in the air, turned by 0.3 rad, with a 0.2 m cube on its top face whose
    centre is 0.6 m + ``beyond`` from the plinth's centre along that face (the two faces overlap
    by −``beyond``), turned by ``turn`` more than the plinth (a square turned by π/2 has the same
    footprint). Both fall freely for one step of 1e-4 s, which moves nothing relative to the
    other, so the run stops with the cube fallen exactly when the overlap is gone or the turn is
    past π/2. The placement uses the module's convention (see the test above). Judged in the
    floor frame, with the wrong coordinate or against the sum of the two turns, the answer
    would change."""
    plinth = [0.0, 2.0, 0.3]
    xi, eta = 0.5 + 0.1 + beyond, 0.15 + 0.1
    c, s = math.cos(plinth[2]), math.sin(plinth[2])
    cube = [plinth[0] + xi * c + eta * s, plinth[1] - xi * s + eta * c, plinth[2] + turn]
    stack = Stack(blocks=(Block(width=1.0, height=0.3, mass=100.0), Block(width=0.2, height=0.2, mass=10.0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.5))))
    res = moreau_jean(stack, zero, t_end=1e-3, dt=1e-4, pose0=np.array([plinth, cube]))
    assert res.overturned == (False, falls)
    assert res.t[-1] == pytest.approx(1e-4 if falls else 1e-3)


def test_at_coincident_corners_the_contact_lies_on_the_lower_face():
    """Two blocks of one width (0.4 m); the upper one is turned by 0.05 rad about its right corner,
    placed on the lower one's right corner. Where two corners coincide the contact is the upper
    block's corner on the lower block's face (the module's rule for aligned edges, as in the
    engine), so its normal is the lower face's, vertical. With a frictionless face the first
    step's impulse on the upper block is then vertical: Ẋ stays 0 to round-off while Ẏ and Θ̇
    change. (Read as the lower corner on the upper face, the normal would lean by 0.05 rad:
    Ẋ = 3e-4 m/s after the step.)"""
    width, height, th = 0.4, 0.8, 0.05
    stack = Stack(blocks=(Block(width=width, height=0.4, mass=100.0), Block(width=width, height=height, mass=50.0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.0))))
    c, s = math.cos(th), math.sin(th)
    corner = (0.5 * width, -0.5 * height)  # the upper block's right bottom corner, body frame
    upper = [0.5 * width - (corner[0] * c + corner[1] * s), 0.4 - (-corner[0] * s + corner[1] * c), th]
    res = moreau_jean(stack, zero, t_end=1e-3, dt=1e-3, pose0=np.array([[0.0, 0.2, 0.0], upper]))
    x_dot, y_dot, th_dot = res.velocity[-1, 1]
    assert abs(x_dot) < 1e-15
    assert y_dot < -1e-3 and th_dot < -1e-2  # the corner carried it: it turns back towards flat


def test_relative_pose_at_rest():
    """Block 2 of the statue on pedestal sits 0.1 m right of the pedestal's centre, (0.5 + 1.2)/2
    above it, unrotated; block 1 is given in the floor frame."""
    res = moreau_jean(statue_on_pedestal(), zero, t_end=0.01, dt=1e-3)
    rel = relative_pose(res)
    assert rel.shape == res.pose.shape
    assert rel[-1, 0] == pytest.approx([0.0, 0.25, 0.0], abs=1e-12)
    assert rel[-1, 1] == pytest.approx([0.1, 0.85, 0.0], abs=1e-12)


# overturning -----------------------------------------------------------------------------------


def test_overturn_is_detected_and_stops_the_run():
    """A strong constant push (3 g B/H) topples the slender block towards −x: the run stops at the
    first step with |Θ| > π/2."""
    res = moreau_jean(single(), lambda t: 3 * G * B / H, t_end=5.0, dt=1e-3)
    assert res.status == "overturned" and res.overturned == (True,)
    assert res.pose[-1, 0, 2] < -math.pi / 2 < res.pose[-2, 0, 2]
    assert res.t[-1] == pytest.approx(res.overturn_time[0]) and res.t[-1] < 5.0


def test_a_statue_falling_off_a_held_pedestal_stops_the_run_past_a_right_angle():
    """A statue on a wide pedestal (both never slip) under a strong push, 3 g B/H of the statue:
    it topples; the run stops at the first step where its rotation relative to the pedestal
    passes π/2. (On a pedestal narrower than 1.5 m the other rule stops it first: its centre,
    0.75 m out from its middle when it lies flat, leaves the face.) Only block 2 is flagged."""
    stack = Stack(blocks=(Block(width=2.4, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=100.0)),
                  interfaces=(Interface(), Interface()))
    res = moreau_jean(stack, lambda t: 3 * G * 0.3 / 1.2, t_end=5.0, dt=1e-3)
    assert res.status == "overturned" and res.overturned == (False, True)
    phi = res.pose[:, 1, 2] - res.pose[:, 0, 2]
    assert phi[-1] < -math.pi / 2 < phi[-2]
    assert res.t[-1] == pytest.approx(res.overturn_time[1])


def test_two_blocks_that_cannot_slip_on_each_other_slide_as_one():
    """A squat block on a squat pedestal, never slipping between them, μ = 0.2 on the floor, under
    a_h = 0.5 g: neither can rock (B/H = 4 and more), so the pair slides as one body at
    −(0.5 − 0.2) g t from the first step (μs = μk; the total weight presses the floor), with no
    relative motion at the interface; θ = ½ positions of a uniform acceleration are exact:
    round-off only."""
    stack = Stack(blocks=(Block(width=1.2, height=0.3, mass=300.0), Block(width=0.8, height=0.2, mass=100.0)),
                  interfaces=(Interface(friction=Friction(static=0.2)), Interface()))
    a = 0.5 * G
    res = moreau_jean(stack, lambda t: a, t_end=0.3, dt=1e-3)
    v_exact = -(a - 0.2 * G) * res.t
    assert np.abs(res.velocity[:, :, 0] - v_exact[:, None]).max() < 1e-11
    assert np.abs(res.velocity[:, :, 1:]).max() < 1e-11
    assert np.abs(res.pose[:, 1, 0] - res.pose[:, 0, 0]).max() < 1e-12


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_pedestal_stops_in_one_step_while_its_box_slides_the_other_way(sign):
    """Both 100 kg, μ = 0.5 on both faces, no floor motion. The pedestal drifts at +2μgΔt, the
    box slides back at −3 m/s, so in the first step the box's friction gives it +μ m g Δt and
    the pedestal −μ m g Δt. To stop, the pedestal needs a floor impulse of
    −(m v₀ − μ m g Δt) = −μ m g Δt, within the floor's μ (2m) g Δt: it sticks at the end of the
    first step, and the box is at −3 + μ g Δt. By hand, so round-off only.

    The one case here where friction pushes one contact in +x (the box's) and the coupled one in
    −x (the floor's) while that one sticks: the LCP's β⁻ rows must couple to β⁺ with −Wᵀ (with
    +Wᵀ the pedestal overshoots to −1.7e-3 m/s). Mirrored (sign −1), the same holds for the β⁺
    rows' coupling to β⁻."""
    mu = 0.5
    stack = Stack(blocks=(Block(width=1.0, height=0.3, mass=100.0), Block(width=0.5, height=0.2, mass=100.0)),
                  interfaces=(Interface(friction=Friction(static=mu)), Interface(friction=Friction(static=mu))))
    dt = 1e-3
    velocity0 = sign * np.array([[2 * mu * G * dt, 0.0, 0.0], [-3.0, 0.0, 0.0]])
    res = moreau_jean(stack, zero, t_end=dt, dt=dt, velocity0=velocity0)
    assert res.t[-1] == pytest.approx(dt)
    assert np.abs(res.velocity[-1, 0]).max() < 1e-12
    assert res.velocity[-1, 1, 0] == pytest.approx(sign * (-3.0 + mu * G * dt), abs=1e-12)
    assert np.abs(res.velocity[-1, 1, 1:]).max() < 1e-12


def test_top_block_slides_off():
    """A squat top block (cannot rock) on a pedestal that never slips, with μ = 0.1 between them,
    under a_h = 0.6 g: the top block slides off the pedestal towards −x; only block 2 is flagged.

    It slides at −(0.6 − 0.1) g from rest, so its centre is at ξ = −¼ g t² on the pedestal, and
    the faces stop overlapping when |ξ| = 0.3 + 0.6 m (the two half-widths): at t = √(0.9/(¼ g))
    = 0.6058 s. The step's θ = ½ positions of a uniform acceleration are exact; the run stops at
    the end of the step that crosses, so within one Δt after it. (Half-widths read as 0.5/B
    would give 0.5406 s.)"""
    stack = Stack(
        blocks=(Block(width=1.2, height=0.3, mass=500.0), Block(width=0.6, height=0.1, mass=20.0)),
        interfaces=(Interface(), Interface(friction=Friction(static=0.1))),
    )
    dt = 1e-3
    res = moreau_jean(stack, lambda t: 0.6 * G, t_end=3.0, dt=dt)
    assert res.status == "overturned" and res.overturned == (False, True)
    t_off = math.sqrt((0.3 + 0.6) / (0.25 * G))
    assert math.isnan(res.overturn_time[0]) and t_off <= res.overturn_time[1] < t_off + dt
    assert relative_pose(res)[-1, 1, 0] < -0.9  # block 2's centre, seen from block 1


# 7. bad input --------------------------------------------------------------------------------


def test_restitution_is_not_implemented():
    stack = Stack(blocks=(Block(width=B, height=H, mass=M),), interfaces=(Interface(restitution=0.5),))
    with pytest.raises(NotImplementedError, match="restitution"):
        moreau_jean(stack, zero)
    two = Stack(blocks=(Block(width=1.0, height=0.3, mass=500.0), Block(width=B, height=H, mass=M)),
                interfaces=(Interface(), Interface(restitution=0.5)))
    with pytest.raises(NotImplementedError, match=r"^interface 2: restitution = 0\.5 "):
        moreau_jean(two, zero)


def test_a_run_shorter_than_a_step_is_one_short_step():
    """t_end < Δt: one step, of length t_end (the last step is shortened to end at t_end)."""
    res = moreau_jean(single(), zero, lambda t: -2 * G, t_end=4e-4, dt=1e-3)
    assert res.t.tolist() == [0.0, 4e-4]
    assert res.velocity[-1, 0, 1] == pytest.approx(G * 4e-4, rel=1e-12)  # free flight for 0.4 ms
    assert len(moreau_jean(single(), zero, t_end=1e-3).t) == 11  # the default step: 1e-4 s
    assert moreau_jean(single(), zero, dt=0.5).t.tolist() == [0.0, 0.5, 1.0, 1.5, 2.0]  # the default t_end: 2 s
    # save_every keeps every n-th step, and the last one whatever n
    kept = moreau_jean(single(), zero, t_end=1e-2, dt=1e-3, save_every=3)
    assert kept.t == pytest.approx([0.0, 3e-3, 6e-3, 9e-3, 1e-2], abs=1e-15)


def test_a_failed_contact_lcp_says_at_which_step(monkeypatch):
    """An LCP that Lemke's method cannot solve stops the run with the step's start time."""
    import rocking.stack.timestepping as ts

    def failing(m, q):
        raise LCPError("ray termination")

    monkeypatch.setattr(ts, "lemke", failing)
    with pytest.raises(LCPError, match=r"^moreau_jean: the contact LCP of the step from t = 0 s failed: ray termination"):
        moreau_jean(single(), zero, t_end=1e-2, dt=1e-3)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"dt": 0.0}, "dt"),
        ({"dt": -1e-4}, "dt"),
        ({"dt": math.nan}, "dt"),
        ({"theta": 0.49}, "theta"),
        ({"theta": 1.01}, "theta"),
        ({"t_end": 0.0}, "t_end"),
        ({"save_every": 0}, "save_every"),
        ({"pose0": np.zeros((2, 3))}, "pose0"),
        ({"dt": True}, "dt"),
        ({"t_end": "1"}, "t_end"),
        ({"gravity": math.nan}, "gravity"),
        ({"gravity": "9.81"}, "gravity"),
        ({"save_every": True}, "save_every"),
        ({"save_every": 2.0}, "save_every"),
        ({"theta": True}, r"theta must lie in \[0.5, 1\], got True"),
        ({"theta": "0.5"}, r"theta must lie in \[0.5, 1\], got '0.5'"),
    ],
)
def test_bad_arguments(kwargs, match):
    with pytest.raises(ValueError, match=match):
        moreau_jean(single(), zero, **kwargs)


@pytest.mark.parametrize("a_h, a_v", [(3.0, None), (zero, 3.0), ("zero", zero)])
def test_floor_motions_must_be_callables(a_h, a_v):
    with pytest.raises(ValueError, match=r"a_h \(and a_v if given\) must be callables"):
        moreau_jean(single(), a_h, a_v)


# the LCP solver ------------------------------------------------------------------------------


def test_lemke_small_problems():
    """A positive definite problem (solution by hand: z = M⁻¹(−q) > 0), a degenerate one (a
    block on two corners: two equal columns, the sum of the impulses fixed), and one without a
    solution (w = −z − 1 ≥ 0 impossible)."""
    z = lemke(np.array([[2.0, 1.0], [1.0, 2.0]]), np.array([-5.0, -6.0]))
    assert z == pytest.approx([4 / 3, 7 / 3], abs=1e-12)
    degenerate = np.array([[1.0, 1.0], [1.0, 1.0]])
    z = lemke(degenerate, np.array([-1.0, -1.0]))
    assert z.min() >= 0 and z.sum() == pytest.approx(1.0, abs=1e-12)
    assert lemke(degenerate, np.array([1.0, 2.0])).tolist() == [0.0, 0.0]
    with pytest.raises(LCPError):
        lemke(np.array([[-1.0]]), np.array([-1.0]))


def test_lemke_random_feasible_problems():
    """Random monotone LCPs (M = AAᵀ, singular when A has fewer columns than rows) with
    q = −M y + s, y, s ≥ 0, so that z = y is feasible and a solution exists; and random positive
    definite non-symmetric ones (AAᵀ + 0.1 I plus a skew part: P-matrices, a unique solution for
    any q). Every one is solved, with w ≥ 0, z ≥ 0, min(w, z) = 0 to 1e-9 (round-off on O(1)
    data; the measured worst is 2e-11)."""
    rng = np.random.default_rng(7)
    for trial in range(300):
        n = int(rng.integers(1, 9))
        a = rng.normal(size=(n, n))
        if trial % 2 == 0:
            a = a[:, : max(1, n - 2)]
            m = a @ a.T
        else:
            skew = rng.normal(size=(n, n))
            m = a @ a.T + 0.1 * np.eye(n) + (skew - skew.T)
        q = -m @ np.abs(rng.normal(size=n)) + np.abs(rng.normal(size=n)) * (rng.random(n) < 0.5)
        z = lemke(m, q)
        w = m @ z + q
        assert z.min() >= 0 and w.min() >= -1e-9 and np.abs(np.minimum(w, z)).max() <= 1e-9
