"""Equations of motion of the statue (θ) on a sliding pedestal (u), compiled.

One set of equations covers every regime of both the single block (pedestal mass m1 = 0: the
"pedestal" is the statue's own sliding base) and the statue on a pedestal (paper §3). The
derivation, with the corrections to the paper's Eqs. 18 and 21 (pitfalls P1–P4), is in
``docs/theory/derivation.md``. With c = cos φ, s_φ = sin φ, φ = α − S·θ, G = g + a_v:

    M(a_g + ü) + m2 R (c θ̈ + S s_φ θ̇²) = F                     (horizontal; paper Eq. 21b corrected)
    I_O θ̈ + m2 R c (a_g + ü) + S m2 R G s_φ = 0                  (rotation; paper Eqs. 5, 21a, 22)
    N = M G + m2 R (S s_φ θ̈ − c θ̇²)                              (floor normal force)

Regime codes: pedestal ``sig`` ∈ {0 stick, ±1 sliding towards ±x}; statue ``s`` ∈ {0 rest,
±1 rocking about its ±x corner}. State y = (u, u̇, θ, θ̇, W_in, D_friction).
"""

from __future__ import annotations

import math

from numba import njit

from .parameters import ALPHA, B, CAN_SLIDE, G, I_O, M, M1, M2, MU_K, NORMAL_PAPER, PED_HALF_WIDTH, PED_HEIGHT, R


@njit(cache=True)
def accelerations(p, sig, s, u_dot, theta, theta_dot, a, av):
    """(ü, θ̈, ok) in the regime (sig, s); ok is False when the sliding system is singular
    (a Painlevé-type indeterminacy, possible only for μk ≥ 2/3 with a light pedestal)."""
    grav = p[G] + av
    if s == 0:
        if sig == 0:
            return 0.0, 0.0, True
        # Paper Eq. 23 (and Eq. 14 for a single block): the stack slides as one body.
        return -a - sig * p[MU_K] * grav, 0.0, True
    phi = p[ALPHA] - s * theta
    c = math.cos(phi)
    sn = math.sin(phi)
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


@njit(cache=True)
def floor_forces(p, s, theta, theta_dot, a, av, udd, thdd):
    """(F, N): horizontal force the floor must exert on the sliding body, and the normal force
    (N), both N, from the momentum balance of the whole system (derivation §3.4)."""
    grav = p[G] + av
    if s == 0:
        return p[M] * (a + udd), p[M] * grav
    phi = p[ALPHA] - s * theta
    c = math.cos(phi)
    sn = math.sin(phi)
    m2r = p[M2] * p[R]
    f = p[M] * (a + udd) + m2r * (c * thdd + s * sn * theta_dot**2)
    n = p[M] * grav + m2r * (s * sn * thdd - c * theta_dot**2)
    return f, n


@njit(cache=True)
def friction_normal(p, n_full, av):
    """The normal force the friction law uses: the full N, or M(g + a_v) in the paper's model."""
    if p[NORMAL_PAPER] > 0.5:
        return p[M] * (p[G] + av)
    return n_full


@njit(cache=True)
def statue_contact(p, s, theta, theta_dot, a, av, udd, thdd):
    """(P_x, P_y): force of the pedestal (or floor) on the statue at its base, N."""
    grav = p[G] + av
    if s == 0:
        return p[M2] * (a + udd), p[M2] * grav
    phi = p[ALPHA] - s * theta
    c = math.cos(phi)
    sn = math.sin(phi)
    px = p[M2] * (a + udd + p[R] * (c * thdd + s * sn * theta_dot**2))
    py = p[M2] * (grav + p[R] * (s * sn * thdd - c * theta_dot**2))
    return px, py


@njit(cache=True)
def pressure_centre(p, s, a, udd, px, py, n):
    """x_N, m: where the floor's normal force acts under the pedestal (moment balance of the
    pedestal about its base centre); NaN when the pedestal height is not given."""
    if p[PED_HEIGHT] <= 0.0 or n <= 0.0:
        return math.nan
    h1 = p[PED_HEIGHT]
    return (s * p[B] * py - h1 * px - 0.5 * h1 * p[M1] * (a + udd)) / n


@njit(cache=True)
def mechanical_energy(p, s, u_dot, theta, theta_dot):
    """T + V relative to the floor, J; V = 0 with the statue upright (Eqs. 16–17)."""
    if s == 0:
        return 0.5 * p[M] * u_dot**2
    phi = p[ALPHA] - s * theta
    c = math.cos(phi)
    m2r = p[M2] * p[R]
    kinetic = 0.5 * p[M] * u_dot**2 + m2r * c * u_dot * theta_dot + 0.5 * p[I_O] * theta_dot**2
    return kinetic + m2r * p[G] * (c - math.cos(p[ALPHA]))


@njit(cache=True)
def kinetic_energy(p, s, u_dot, theta, theta_dot):
    """T relative to the floor, J."""
    if s == 0:
        return 0.5 * p[M] * u_dot**2
    c = math.cos(p[ALPHA] - s * theta)
    return 0.5 * p[M] * u_dot**2 + p[M2] * p[R] * c * u_dot * theta_dot + 0.5 * p[I_O] * theta_dot**2


@njit(cache=True)
def power(p, sig, s, u_dot, theta, theta_dot, a, av, udd, thdd):
    """(P_in, P_friction): power of the floor's inertial (d'Alembert) forces and the rate of
    energy dissipated by floor friction, W."""
    if s == 0:
        p_in = -a * p[M] * u_dot
    else:
        phi = p[ALPHA] - s * theta
        m2r = p[M2] * p[R]
        p_in = -a * (p[M] * u_dot + m2r * math.cos(phi) * theta_dot) - av * m2r * s * math.sin(phi) * theta_dot
    if sig == 0 or p[CAN_SLIDE] < 0.5:
        return p_in, 0.0
    _, n = floor_forces(p, s, theta, theta_dot, a, av, udd, thdd)
    return p_in, p[MU_K] * friction_normal(p, n, av) * abs(u_dot)


@njit(cache=True)
def pedestal_half_width(p):
    return p[PED_HALF_WIDTH]
