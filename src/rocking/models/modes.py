"""Which regime holds, and when it stops holding: the guards and the regime selection.

Guards (event functions) are positive while the current regime is consistent and cross zero
when it ends (derivation §3.5; paper Eqs. 4, 14, 24–29 corrected, P10–P12):

* pedestal held:   μs·N ∓ F_req              (paper Eq. 4 / Eq. 29 with |·| and N, P11)
* pedestal slides: σ·u̇                        (slide ends when the velocity vanishes, P12)
* statue at rest:  (g + a_v)·tan α ∓ (a_g + ü) (rocking onset, Eq. 5's |ẍg| > g b/h, P10)
* statue rocks:    S·θ (impact), α − |θ| (statically unstable), π/2 − |θ| (fallen)

Selection rule, used at t = 0, after every event and at every jump of the floor motion:
candidates are tried with the fewest moving degrees of freedom first — pedestal held before
sliding, statue at rest before rocking — and the first one whose forces are consistent is
kept (held: |F| ≤ μs·N; starting to slide: σ·ü > 0; at rest: |a_base| ≤ G tan α; starting to
rock: S·θ̈ > 0). Rigid bodies with Coulomb friction can admit more than one consistent
regime; this rule makes the choice unique and is tested.
"""

from __future__ import annotations

import math

from numba import njit

from .dynamics import accelerations, floor_forces, friction_normal
from .parameters import ALPHA, CAN_SLIDE, G, MU_S, R

SLIP_TO_NEGATIVE, SLIP_TO_POSITIVE, STOP, ROCK_TO_NEGATIVE, ROCK_TO_POSITIVE, IMPACT, EXCEED, FALL = range(8)
N_GUARDS = 8


@njit(cache=True, _nrt=False)
def evaluate_guards(p, sig, s, y, a, av, exceeded, out):
    """Fill ``out`` (length N_GUARDS) with the guard values; inactive guards are +1."""
    udd, thdd, _ = accelerations(p, sig, s, y[1], y[2], y[3], a, av)
    f, n = floor_forces(p, s, y[2], y[3], a, av, udd, thdd)
    guards_from_forces(p, sig, s, y, a, av, udd, f, n, exceeded, out)


@njit(cache=True, inline="always")
def guards_from_forces(p, sig, s, y, a, av, udd, f, n, exceeded, out):
    """:func:`evaluate_guards` when ü and the floor forces (F, N) at y are already known."""
    for i in range(N_GUARDS):
        out[i] = 1.0
    if sig == 0:
        if p[CAN_SLIDE] > 0.5:
            cap = p[MU_S] * friction_normal(p, n, av)
            out[SLIP_TO_NEGATIVE] = cap - f
            out[SLIP_TO_POSITIVE] = cap + f
    else:
        out[STOP] = sig * y[1]
    if s == 0:
        threshold = (p[G] + av) * math.tan(p[ALPHA])
        base = a + udd
        out[ROCK_TO_NEGATIVE] = threshold - base
        out[ROCK_TO_POSITIVE] = threshold + base
    else:
        for i in range(IMPACT, N_GUARDS):
            out[i] = angle_guard(p, s, i, y[2], exceeded)


@njit(cache=True, inline="always")
def angle_guard(p, s, index, theta, exceeded):
    """The guards of a rocking statue that depend on θ alone (index IMPACT, EXCEED or FALL):
    S·θ (impact), α − |θ| (statically unstable, until first exceeded), π/2 − |θ| (fallen)."""
    if index == IMPACT:
        return s * theta
    if index == EXCEED:
        return 1.0 if exceeded else p[ALPHA] - abs(theta)
    return 0.5 * math.pi - abs(theta)


@njit(cache=True, inline="always")
def track_threshold_guards(p, sig, s, y, a, av, udd, f, n, gmin):
    """Lower ``gmin`` to the values of the guards that follow the floor motion (friction cone,
    rocking threshold, sliding velocity) at an interior state of a step, given its horizontal
    acceleration ü and the floor forces (F, N) already computed there. Such a guard can dip below
    zero and come back within one step; the end points alone would miss it (scipy#9228)."""
    if sig == 0:
        if p[CAN_SLIDE] > 0.5:
            cap = p[MU_S] * friction_normal(p, n, av)
            gmin[SLIP_TO_NEGATIVE] = min(gmin[SLIP_TO_NEGATIVE], cap - f)
            gmin[SLIP_TO_POSITIVE] = min(gmin[SLIP_TO_POSITIVE], cap + f)
    else:
        gmin[STOP] = min(gmin[STOP], sig * y[1])
    if s == 0:
        threshold = (p[G] + av) * math.tan(p[ALPHA])
        gmin[ROCK_TO_NEGATIVE] = min(gmin[ROCK_TO_NEGATIVE], threshold - (a + udd))
        gmin[ROCK_TO_POSITIVE] = min(gmin[ROCK_TO_POSITIVE], threshold + (a + udd))


@njit(cache=True)
def _sign(x):
    return 1 if x > 0.0 else -1


@njit(cache=True, _nrt=False)
def select_regime(p, y, s_now, a, av, forbid_stick, forbid_rest):
    """Return (sig, s, consistent) for the state y at an instant with floor accelerations a, av.

    ``s_now`` is the statue's pivot if it is rocking (needed when θ = 0 right after an impact).
    ``forbid_stick``/``forbid_rest``: a guard has just fired, so the held/rest regime is known
    to be left even though its test is exactly tied at this instant.
    """
    u_dot, theta, theta_dot = y[1], y[2], y[3]
    moving = u_dot != 0.0
    rocking = s_now != 0 and (theta != 0.0 or theta_dot != 0.0)
    grav = p[G] + av
    threshold = grav * math.tan(p[ALPHA])

    # Preferred slip direction: opposite to the force the floor would need to hold the base.
    s_guess = s_now if rocking else 0
    udd0, thdd0, _ = accelerations(p, 0, s_guess, u_dot, theta, theta_dot, a, av)
    f0, _ = floor_forces(p, s_guess, theta, theta_dot, a, av, udd0, thdd0)
    sig_pref = -_sign(f0)

    # Candidate lists are tuples, not arrays: this runs at every event, and allocating there
    # costs more than the physics.
    if moving:
        sig_list = (1 if u_dot > 0.0 else -1, 0, 0)
        n_sig = 1
    elif p[CAN_SLIDE] < 0.5:
        sig_list = (0, 0, 0)
        n_sig = 1
    elif forbid_stick:
        # The friction cone was just left: the slip direction is the preferred one, even if
        # the tie at this instant makes σ·ü vanish to rounding.
        sig_list = (sig_pref, 0, 0)
        n_sig = 1
    else:
        sig_list = (0, sig_pref, -sig_pref)
        n_sig = 3

    first_sig, first_s = sig_list[0], s_guess
    if forbid_rest and not rocking:
        udd_r, _, _ = accelerations(p, first_sig, 0, u_dot, theta, theta_dot, a, av)
        first_s = -_sign(a + udd_r)
    for i in range(n_sig):
        sig = sig_list[i]
        # Statue candidates, preferred rocking direction opposite to the base acceleration.
        if rocking:
            s_list = (s_now, 0, 0)
            n_s = 1
        else:
            udd_r, _, _ = accelerations(p, sig, 0, u_dot, theta, theta_dot, a, av)
            s_pref = -_sign(a + udd_r)
            if forbid_rest:
                s_list = (s_pref, 0, 0)
                n_s = 1
            else:
                s_list = (0, s_pref, -s_pref)
                n_s = 3
        for j in range(n_s):
            s = s_list[j]
            udd, thdd, ok = accelerations(p, sig, s, u_dot, theta, theta_dot, a, av)
            if not ok:
                continue
            if sig == 0:
                if p[CAN_SLIDE] > 0.5:
                    f, n = floor_forces(p, s, theta, theta_dot, a, av, udd, thdd)
                    if abs(f) > p[MU_S] * friction_normal(p, n, av):
                        continue
            elif not moving:
                # Right after the cone was left the test is tied to rounding: tolerate that.
                if sig * udd <= (-1e-9 * grav if forbid_stick else 0.0):
                    continue
            if s == 0:
                if abs(a + udd) > threshold:
                    continue
            elif not rocking:
                if s * thdd <= (-1e-9 * grav / p[R] if forbid_rest else 0.0):
                    continue
            return sig, s, True
    return first_sig, first_s, False


@njit(cache=True, _nrt=False)
def rest_band(p, y, av, work):
    """(a_lo, a_hi), m/s²: the horizontal floor accelerations between which everything stays
    at rest (pedestal held, statue not rocking) in the state ``y`` under vertical acceleration
    ``av``. At rest the floor forces are F = M·a_g and N = M·(g + a_v), so every guard is affine
    in a_g (``models.modes`` docstring); the band is read off the guards at a_g = 0 and 1.
    ``work`` is scratch space of length 2·N_GUARDS."""
    evaluate_guards(p, 0, 0, y, 0.0, av, False, work[:N_GUARDS])
    evaluate_guards(p, 0, 0, y, 1.0, av, False, work[N_GUARDS:])
    lo, hi = -math.inf, math.inf
    for i in range(N_GUARDS):
        c = work[i]
        d = work[N_GUARDS + i] - c
        if d < 0.0:
            hi = min(hi, c / -d)
        elif d > 0.0:
            lo = max(lo, -c / d)
    return lo, hi
