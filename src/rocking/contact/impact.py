"""Impact of the statue on its base when θ crosses zero and the pivot switches corner.

Two laws (derivation §3.6; docs/theory/derivation.md):

* ``paper`` — the paper's Eq. 1: θ̇⁺ = r·θ̇⁻ and the pedestal velocity is unchanged. It needs
  the floor to supply |Fx|/Fy = (h/b)(1 − r)/(1 + r) (oracle O19), which is returned so the
  caller can report when that exceeds the available friction.
* ``coulomb`` — the statue's angular momentum about the new pivot is conserved (Eq. 2 of the
  paper with its brackets mended, P5), with r·I_O replacing I_O − 2 m b² when the user fixes r;
  the floor's horizontal impulse is bounded by Coulomb friction on its vertical impulse
  (Moreau's impulse law): the pedestal is stopped if |Fx| ≤ μs·Fy, otherwise it slides with
  Fx = −μk·Fy·sgn(u̇⁺).

Velocities: u̇ of the sliding body relative to the floor (m/s), θ̇ of the statue (rad/s).
Impulses Fx, Fy in N·s.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def _impulses(m_tot, m2, b, h, u0, w0, u1, w1):
    """Floor impulses (Fx, Fy) from the system's horizontal momentum and the statue's
    vertical momentum (its centre goes from −b|θ̇⁻| to +b|θ̇⁺|)."""
    fx = m_tot * (u1 - u0) + m2 * h * (w1 - w0)
    fy = m2 * b * (abs(w1) + abs(w0))
    return fx, fy


@njit(cache=True)
def impact_paper(m_tot, m2, b, h, r, u_dot, theta_dot):
    """Paper Eq. 1. Returns (u̇⁺, θ̇⁺, Fx, Fy)."""
    w1 = r * theta_dot
    fx, fy = _impulses(m_tot, m2, b, h, u_dot, theta_dot, u_dot, w1)
    return u_dot, w1, fx, fy


@njit(cache=True)
def impact_coulomb(i_o, m_tot, m2, b, h, r, mu_s, mu_k, can_slide, u_dot, theta_dot):
    """Angular momentum about the new pivot + Coulomb floor impulse. Returns (u̇⁺, θ̇⁺, Fx, Fy, ok).

    ``r`` is θ̇⁺/θ̇⁻ for a pedestal held in place (Housner's 1 − 1.5 sin²α when the user has not
    set it), so that I_O·θ̇⁺ + m2·h·u̇⁺ = r·I_O·θ̇⁻ + m2·h·u̇⁻. ``ok`` is False when no outcome is
    consistent: a held one whose θ̇⁺ turns back (a squat statue), or no sliding direction whose
    θ̇⁺ keeps its sign (an r well below Housner's on a low friction: the held outcome is then
    returned though it needs more than μs, and the run's result ends there, results.response.
    held_impact_time; docs/theory/derivation.md §6).
    """
    mh = m2 * h
    lhs = r * i_o * theta_dot + mh * u_dot  # I_O θ̇⁺ + m h u̇⁺ equals this
    # Trial 1: the floor holds (or stops) the sliding body, u̇⁺ = 0.
    w_stick = lhs / i_o
    fx, fy = _impulses(m_tot, m2, b, h, u_dot, theta_dot, 0.0, w_stick)
    if can_slide < 0.5 or abs(fx) <= mu_s * fy:
        # A reversed θ̇ (a squat heavy statue, or a pedestal moving against it) breaks the
        # assumption that the statue rolls over onto the new corner: report it as inconsistent.
        return 0.0, w_stick, fx, fy, w_stick * theta_dot >= 0.0
    # Trial 2: it slides with σ = ±1 during the impulse; θ̇⁺ keeps the sign of θ̇⁻ (ζ).
    zeta = 1.0 if theta_dot > 0 else -1.0
    for sigma in (-1.0 if fx > 0 else 1.0, 1.0 if fx > 0 else -1.0):
        # I_O w + m h v = lhs ;  M v + (m h + μk σ m b ζ) w = M u̇⁻ + m h θ̇⁻ − μk σ m b |θ̇⁻|
        a11, a12 = mh, i_o
        a21, a22 = m_tot, mh + mu_k * sigma * m2 * b * zeta
        rhs2 = m_tot * u_dot + mh * theta_dot - mu_k * sigma * m2 * b * abs(theta_dot)
        det = a11 * a22 - a12 * a21
        if det == 0.0:
            continue
        v = (lhs * a22 - a12 * rhs2) / det
        w = (a11 * rhs2 - a21 * lhs) / det
        if sigma * v > 0.0 and zeta * w >= 0.0:
            fx, fy = _impulses(m_tot, m2, b, h, u_dot, theta_dot, v, w)
            return v, w, fx, fy, True
    fx, fy = _impulses(m_tot, m2, b, h, u_dot, theta_dot, 0.0, w_stick)
    return 0.0, w_stick, fx, fy, False


@njit(cache=True)
def friction_ratio(fx, fy):
    """|Fx|/Fy, the friction coefficient an impulse (or a force) needs; inf if Fy ≤ 0."""
    if fy <= 0.0:
        return math.inf
    return abs(fx) / fy
