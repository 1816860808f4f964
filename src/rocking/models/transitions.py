"""What happens when a guard fires: the transition (reset) of the hybrid system.

Shared by the compiled solver and the SciPy integrator cross-check (``solver.crosscheck``), so both
apply exactly the same rules; only *when* the guard fires is found by each solver's own event
location.
"""

from __future__ import annotations

from numba import njit

from ..contact.impact import friction_ratio, impact_coulomb, impact_paper
from .dynamics import kinetic_energy
from .modes import EXCEED, FALL, IMPACT, STOP, select_regime
from .parameters import B, CAN_SLIDE, ETA, H, I_O, IMPACT_COULOMB, M, M2, MU_K, MU_S, REST_VEL

# Event kinds (the values of models.regimes.EventKind).
EV_IMPACT, EV_SLIP, EV_STOP, EV_UPLIFT, EV_EXCEED, EV_FALL, EV_SETTLE, EV_BREAKPOINT = 1, 2, 3, 4, 5, 6, 7, 8


@njit(cache=True, _nrt=False)
def apply_transition(p, guard, at_step_start, y, sig, s, a, av):
    """Apply the transition of ``guard`` (an index of models.modes) to the state ``y`` (changed in
    place) with the floor accelerations (a, av) at that instant.

    Returns (sig, s, kind, consistent, impact, energy_lost, floor_ratio, top_ratio, floor_short):
    the new regime, the event kind, whether the new regime is strictly consistent, whether an
    impact law was applied, the kinetic
    energy lost (J), the friction ratio |Fx|/Fy an impact needs from the floor and at the
    statue's base, and whether the impact left the body on the floor held by more floor friction
    than μs.
    """
    lost, floor_ratio, top_ratio, floor_short, ok = 0.0, 0.0, 0.0, False, True
    if guard == FALL:
        return sig, s, EV_FALL, ok, False, lost, floor_ratio, top_ratio, floor_short
    if guard == EXCEED:
        return sig, s, EV_EXCEED, ok, False, lost, floor_ratio, top_ratio, floor_short
    if guard == IMPACT and at_step_start and abs(y[3]) < p[REST_VEL]:
        # Rocking began at a tangency of the threshold and θ went the wrong way at once:
        # there was no uplift, the statue stays at rest.
        y[2] = 0.0
        y[3] = 0.0
        sig2, s2, ok = select_regime(p, y, 0, a, av, False, False)
        if s2 != 0:
            # The rest test is tied to rounding here (the floor is at g·tan α to within an ulp)
            # and choosing rocking again at the same instant would repeat this event without
            # end. Rest it is: if the floor truly exceeds the threshold, the rest regime's
            # rocking guard is negative at the end of the next step and fires at its start.
            s2 = 0
        return sig2, s2, EV_SETTLE, ok, False, lost, floor_ratio, top_ratio, floor_short
    if guard == IMPACT:
        kind = EV_IMPACT
        y[2] = 0.0
        t_before = kinetic_energy(p, s, y[1], 0.0, y[3])
        if p[IMPACT_COULOMB] > 0.5:
            ud1, thd1, fx, fy, ok = impact_coulomb(
                p[I_O], p[M], p[M2], p[B], p[H], p[ETA], p[MU_S], p[MU_K], p[CAN_SLIDE], y[1], y[3]
            )
        else:
            ud1, thd1, fx, fy = impact_paper(p[M], p[M2], p[B], p[H], p[ETA], y[1], y[3])
        # The floor must supply this ratio; the paper's law does not check it (P15, O19). The body
        # ends the impact held with more than μs where the paper's law keeps a held body held, or
        # where the Coulomb law found no consistent outcome and kept its held one (a slide takes
        # μk·Fy): a body sliding before the impact can end it so, under the Coulomb law only.
        floor_ratio = friction_ratio(fx, fy)
        floor_short = p[CAN_SLIDE] > 0.5 and ud1 == 0.0 and floor_ratio > p[MU_S]
        # Impulse on the statue's base: it must not slip on the pedestal either.
        lx = p[M2] * ((ud1 - y[1]) + p[H] * (thd1 - y[3]))
        ly = p[M2] * p[B] * (abs(thd1) + abs(y[3]))
        top_ratio = friction_ratio(lx, ly)
        s = -s
        if abs(thd1) < p[REST_VEL]:
            # The settle closes a Zeno sequence of ever smaller impacts at its accumulation
            # point (θ̇ := 0). The impact's u̇⁺ is kept (an impact that ends the rocking of a
            # block sliding fast changes its slide for real), but a slide slower than the rest
            # velocity × the statue's size (b + h) stops with the rocking: the kick is then O(θ̇⁻),
            # like the rest of the sequence (the stack engine's rule, docs/theory/stack.md §6).
            # Kept, it restarts the sequence when μk > tan α: a statue on a sliding base must
            # rock, the slide stops, the statue falls back and settles with a new kick, and
            # again; under a record the events accumulated at one instant until max_events.
            kind = EV_SETTLE
            thd1 = 0.0
            s = 0
            if abs(ud1) < p[REST_VEL] * (p[B] + p[H]):
                ud1 = 0.0
        y[1] = ud1
        y[3] = thd1
        lost = t_before - kinetic_energy(p, s, y[1], 0.0, y[3])
        sig2, s2, ok2 = select_regime(p, y, s, a, av, False, False)
        return sig2, s2, kind, ok and ok2, True, lost, floor_ratio, top_ratio, floor_short
    if guard == STOP:
        y[1] = 0.0
        sig2, s2, ok = select_regime(p, y, s, a, av, False, False)
        return sig2, s2, EV_STOP, ok, False, lost, floor_ratio, top_ratio, floor_short
    if guard <= 1:  # the friction cone was left
        sig2, s2, ok = select_regime(p, y, s, a, av, True, False)
        return sig2, s2, EV_SLIP, ok, False, lost, floor_ratio, top_ratio, floor_short
    # the rocking threshold was crossed
    sig2, s2, ok = select_regime(p, y, s, a, av, False, True)
    return sig2, s2, EV_UPLIFT, ok, False, lost, floor_ratio, top_ratio, floor_short
