"""Equations of motion of the statue (θ) on a sliding pedestal (u), compiled.

One set of equations covers every regime of both the single block (pedestal mass m1 = 0: the
"pedestal" is the statue's own sliding base) and the statue on a pedestal (paper §3). The
derivation, with the corrections to the paper's Eqs. 18 and 21 (pitfalls P1–P4), is in
``docs/theory/derivation.md``. With c = cos φ, s_φ = sin φ, φ = α − S·θ, G = g + a_v:

    M(a_g + ü) + m2 R (c θ̈ + S s_φ θ̇²) = F                     (horizontal; paper Eq. 21b corrected)
    I_O θ̈ + m2 R c (a_g + ü) + S m2 R G s_φ = 0                  (rotation; paper Eqs. 5, 21a, 22)
    N = M G + m2 R (S s_φ θ̈ − c θ̇²)                              (floor normal force)
    P = m2 (a_g + ü + R(c θ̈ + S s_φ θ̇²),  G + R(S s_φ θ̈ − c θ̇²))   (force on the statue's base)

Regime codes: pedestal ``sig`` ∈ {0 stick, ±1 sliding towards ±x}; statue ``s`` ∈ {0 rest,
±1 rocking about its ±x corner}. State y = (u, u̇, θ, θ̇, W_in, D_friction).

Each quantity has a ``_cs`` kernel taking c and s_φ, so the solver's hot path
(:func:`evaluate_all`) computes the trigonometric functions once per evaluation.
"""

from __future__ import annotations

import math

from numba import njit

from .parameters import ALPHA, B, CAN_SLIDE, G, I_O, M, M1, M2, MU_K, NORMAL_PAPER, PED_HALF_WIDTH, PED_HEIGHT, R


@njit(cache=True, inline="always")
def _cs(p, s, theta):
    if s == 0:
        return 1.0, 0.0
    phi = p[ALPHA] - s * theta
    return math.cos(phi), math.sin(phi)


@njit(cache=True, inline="always")
def _accelerations_cs(p, sig, s, theta_dot, a, av, c, sn):
    grav = p[G] + av
    if s == 0:
        if sig == 0:
            return 0.0, 0.0, True
        # Paper Eq. 23 (and Eq. 14 for a single block): the stack slides as one body.
        return -a - sig * p[MU_K] * grav, 0.0, True
    m2r = p[M2] * p[R]
    rhs_theta = -m2r * (c * a + s * sn * grav)
    if sig == 0:
        # Paper Eq. 22 with I_O about the pivot (P4): the pedestal is held by friction.
        return 0.0, rhs_theta / p[I_O], True
    # Slide-rock: F = −σ μk N with N containing θ̈ → a 2×2 non-symmetric linear system.
    mu = p[MU_K]
    if p[NORMAL_PAPER] > 0.5:
        a12 = m2r * c
        rhs_u = -p[M] * a - s * m2r * sn * theta_dot**2 - sig * mu * p[M] * grav
    else:
        a12 = m2r * (c + sig * mu * s * sn)
        rhs_u = -p[M] * a - s * m2r * sn * theta_dot**2 - sig * mu * (p[M] * grav - m2r * c * theta_dot**2)
    a21 = m2r * c
    det = p[M] * p[I_O] - a12 * a21
    if det <= 1e-12 * p[M] * p[I_O]:
        return 0.0, 0.0, False
    udd = (rhs_u * p[I_O] - a12 * rhs_theta) / det
    thdd = (p[M] * rhs_theta - a21 * rhs_u) / det
    return udd, thdd, True


@njit(cache=True, inline="always")
def _floor_forces_cs(p, s, theta_dot, a, av, udd, thdd, c, sn):
    grav = p[G] + av
    if s == 0:
        return p[M] * (a + udd), p[M] * grav
    m2r = p[M2] * p[R]
    f = p[M] * (a + udd) + m2r * (c * thdd + s * sn * theta_dot**2)
    n = p[M] * grav + m2r * (s * sn * thdd - c * theta_dot**2)
    return f, n


@njit(cache=True, inline="always")
def _statue_contact_cs(p, s, theta_dot, a, av, udd, thdd, c, sn):
    grav = p[G] + av
    if s == 0:
        return p[M2] * (a + udd), p[M2] * grav
    px = p[M2] * (a + udd + p[R] * (c * thdd + s * sn * theta_dot**2))
    py = p[M2] * (grav + p[R] * (s * sn * thdd - c * theta_dot**2))
    return px, py


@njit(cache=True, inline="always")
def _power_cs(p, sig, s, u_dot, theta_dot, a, av, n, c, sn):
    if s == 0:
        p_in = -a * p[M] * u_dot
    else:
        m2r = p[M2] * p[R]
        p_in = -a * (p[M] * u_dot + m2r * c * theta_dot) - av * m2r * s * sn * theta_dot
    if sig == 0 or p[CAN_SLIDE] < 0.5:
        return p_in, 0.0
    # σ·u̇, not |u̇|: equal while the regime holds, but smooth where a step runs past the stop
    # (u̇ = 0), so the dissipation integrates to full order up to the event and its dense output
    # is accurate there.
    return p_in, p[MU_K] * friction_normal(p, n, av) * sig * u_dot


@njit(cache=True, inline="always")
def accelerations(p, sig, s, u_dot, theta, theta_dot, a, av):
    """(ü, θ̈, ok) in the regime (sig, s); ok is False when the sliding system is singular
    (a Painlevé-type indeterminacy, possible only for μk ≥ 2/3 with a light pedestal)."""
    c, sn = _cs(p, s, theta)
    return _accelerations_cs(p, sig, s, theta_dot, a, av, c, sn)


@njit(cache=True, inline="always")
def floor_forces(p, s, theta, theta_dot, a, av, udd, thdd):
    """(F, N): horizontal force the floor must exert on the sliding body, and the normal force
    (N), both N, from the momentum balance of the whole system (derivation §3.4)."""
    c, sn = _cs(p, s, theta)
    return _floor_forces_cs(p, s, theta_dot, a, av, udd, thdd, c, sn)


@njit(cache=True, inline="always")
def friction_normal(p, n_full, av):
    """The normal force the friction law uses: the full N, or M(g + a_v) in the paper's model."""
    if p[NORMAL_PAPER] > 0.5:
        return p[M] * (p[G] + av)
    return n_full


@njit(cache=True)
def statue_contact(p, s, theta, theta_dot, a, av, udd, thdd):
    """(P_x, P_y): force of the pedestal (or floor) on the statue at its base, N."""
    c, sn = _cs(p, s, theta)
    return _statue_contact_cs(p, s, theta_dot, a, av, udd, thdd, c, sn)


@njit(cache=True)
def power(p, sig, s, u_dot, theta, theta_dot, a, av, udd, thdd):
    """(P_in, P_friction): power of the floor's inertial (d'Alembert) forces and the rate of
    energy dissipated by floor friction, W."""
    c, sn = _cs(p, s, theta)
    _, n = _floor_forces_cs(p, s, theta_dot, a, av, udd, thdd, c, sn)
    return _power_cs(p, sig, s, u_dot, theta_dot, a, av, n, c, sn)


@njit(cache=True, inline="always")
def evaluate_all(p, sig, s, u_dot, theta, theta_dot, a, av):
    """Everything the solver needs at one state, with one cos/sin:
    (ü, θ̈, ok, F, N, P_x, P_y, P_in, P_friction)."""
    c, sn = _cs(p, s, theta)
    udd, thdd, ok = _accelerations_cs(p, sig, s, theta_dot, a, av, c, sn)
    f, n = _floor_forces_cs(p, s, theta_dot, a, av, udd, thdd, c, sn)
    px, py = _statue_contact_cs(p, s, theta_dot, a, av, udd, thdd, c, sn)
    p_in, p_fric = _power_cs(p, sig, s, u_dot, theta_dot, a, av, n, c, sn)
    return udd, thdd, ok, f, n, px, py, p_in, p_fric


@njit(cache=True)
def pressure_centre(p, s, a, udd, px, py, n):
    """x_N, m: where the floor's normal force acts under the pedestal (moment balance of the
    pedestal about its base centre); NaN when the pedestal height is not given or N ≤ 0."""
    if p[PED_HEIGHT] <= 0.0 or n <= 0.0:
        return math.nan
    return pressure_moment(p, s, a, udd, px, py) / n


@njit(cache=True)
def pressure_moment(p, s, a, udd, px, py):
    """N·x_N, N·m: the moment about the pedestal's base centre that the floor's normal force
    must balance (the numerator of :func:`pressure_centre`); 0 when the pedestal height is not
    given (no moment known).

    The statue's base force (−Px, −Py on the pedestal) acts at its pivot, x = s·b, while it
    rocks. While it rests on the pedestal (s = 0) it acts where the statue's own moment balance
    puts it, x_p·Py = −h·Px (h = R·cos α, the height of the statue's centre above its base), so
    that the pedestal and the statue tip as one body: at rest |x_N| = |a_g|·(m1·H1/2 +
    m2·(H1 + h))/((m1 + m2)·G). Until 2026-12-06 that couple was left out (the force taken at
    x = 0, as derivation.md §3.5 writes it for s = 0): the check at rest saw only m2·H1 of the
    statue's moment arm and missed uplifts (a 0.80 × 0.94 m pedestal under a 259 kg statue
    tips as one at 0.467 g, where the check said 0.596 g; docs/theory/derivation.md §3.5)."""
    h1 = p[PED_HEIGHT]
    if h1 <= 0.0:
        return 0.0
    if s == 0:
        return -(h1 + p[R] * math.cos(p[ALPHA])) * px - 0.5 * h1 * p[M1] * (a + udd)
    return s * p[B] * py - h1 * px - 0.5 * h1 * p[M1] * (a + udd)


@njit(cache=True)
def mechanical_energy(p, s, u_dot, theta, theta_dot):
    """T + V relative to the floor, J; V = 0 with the statue upright (Eqs. 16–17)."""
    if s == 0:
        return 0.5 * p[M] * u_dot**2
    c = math.cos(p[ALPHA] - s * theta)
    return kinetic_energy(p, s, u_dot, theta, theta_dot) + p[M2] * p[R] * p[G] * (c - math.cos(p[ALPHA]))


@njit(cache=True)
def overturning_barrier(p):
    """The least energy (J, relative to the system at rest with the statue upright) with which the
    statue can reach its tipping angle ±α: m2·g·R·(1 − cos α), Eqs. 16–17's V at θ = ±α. Turned to
    ±α, the statue has a corner R below its centre whatever else moves, so with less energy than
    this, and no energy coming in, it never gets there."""
    return p[M2] * p[R] * p[G] * (1.0 - math.cos(p[ALPHA]))


@njit(cache=True)
def kinetic_energy(p, s, u_dot, theta, theta_dot):
    """T relative to the floor, J."""
    if s == 0:
        return 0.5 * p[M] * u_dot**2
    c = math.cos(p[ALPHA] - s * theta)
    return 0.5 * p[M] * u_dot**2 + p[M2] * p[R] * c * u_dot * theta_dot + 0.5 * p[I_O] * theta_dot**2


@njit(cache=True)
def pedestal_half_width(p):
    return p[PED_HALF_WIDTH]
