"""The event-driven stack engine against the independent Moreau–Jean time stepping
(rocking.stack.timestepping, which shares no physics code with it), on five stacks.

The two converge to each other as Δt → 0. Up to the first impact the time stepping is first
order or better, which these tests assert: the error at Δt = 1e-4 s must be at most 1/2.5 of the
one at 4e-4 s (first order gives 1/4), and below 1e-6 (rad, m). The comparison uses the instants
both solvers saved, with no interpolation (a kink in a linear interpolation would cost 1e-4 rad).
Past an impact the time stepping's error stays within C·Δt but depends on where the impact falls
inside a step (measured: 1e-4 rad at Δt = 1e-4 s on the single block), so it is not asserted to
fall monotonically; test_stack_timestepping.py checks that the impact law converges at first order.
"""

import numpy as np
import pytest

import rocking as rk
from rocking.stack import Block, Interface, Stack, simulate_stack
from rocking.stack.timestepping import moreau_jean

F = rk.Friction
CASES = {
    "rocking block": (
        Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),)),
        rk.SinePulse(amplitude=3.0, frequency=1.0), 1.0),
    # the pedestal slips, the statue rocks on it while it slides, the slip stops
    "statue on a sliding pedestal": (
        Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=100.0)),
              interfaces=(Interface(friction=F(static=0.3, kinetic=0.3)), Interface())),
        rk.SinePulse(amplitude=3.5, frequency=1.0), 1.2),
    # the statue rocks on its plinth and the vase rocks on the statue
    "plinth, statue and vase": (
        Stack(blocks=(Block(width=1.2, height=0.4, mass=400.0), Block(width=0.4, height=1.4, mass=150.0),
                      Block(width=0.2, height=0.45, mass=8.0)),
              interfaces=(Interface(friction=F(static=0.4, kinetic=0.4)), Interface(friction=F(static=0.6, kinetic=0.6)),
                          Interface(friction=F(static=0.5, kinetic=0.5)))),
        rk.SinePulse(amplitude=3.0, frequency=1.5), 0.8),
    # a box wider than its plinth rocks on the plinth's top corners (from 0.152 s), and the
    # plinth on the floor (from 0.172 s): the contacts of the upper interface are the lower
    # block's corners under the box's bottom face
    "wide box on a narrow plinth": (
        Stack(blocks=(Block(width=0.4, height=0.5, mass=200.0), Block(width=0.8, height=0.8, mass=50.0)),
              interfaces=(Interface(), Interface())),
        rk.SinePulse(amplitude=6.0, frequency=1.0), 0.3),
    # a squat box (μ = 0.15) slips on its slender plinth from 0.060 s, and goes on slipping on
    # the plinth's turned face once the plinth rocks (from 0.131 s); the box rocks only at 0.563 s
    "box slipping on a rocking plinth": (
        Stack(blocks=(Block(width=0.3, height=1.0, mass=100.0), Block(width=0.25, height=0.1, mass=5.0)),
              interfaces=(Interface(), Interface(friction=F(static=0.15, kinetic=0.15)))),
        rk.SinePulse(amplitude=4.0, frequency=1.0), 0.5),
}


def _errors(stack, motion, t_end, dt, ref):
    impacts = ref.events[ref.events[:, 2] == -1]
    t_first = impacts[0, 0] if len(impacts) else t_end
    m = moreau_jean(stack, lambda t: float(motion.acceleration(np.array([t]))[0]), t_end=t_end, dt=dt)
    assert m.status == "completed"
    key_ref, key_m = np.round(ref.t, 9), np.round(m.t, 9)
    i = np.searchsorted(key_ref, key_m)
    shared = (i < len(ref.t)) & (key_ref[np.minimum(i, len(ref.t) - 1)] == key_m) & (m.t < t_first)
    assert shared.sum() > 100
    d = m.pose[shared] - ref.pose[i[shared]]
    return np.max(np.abs(d[:, :, [0, 2]]))  # x and Θ of every block


@pytest.mark.parametrize("name", list(CASES))
def test_time_stepping_converges_to_the_event_driven_engine(name):
    stack, motion, t_end = CASES[name]
    ref = simulate_stack(stack, motion, duration=t_end, options={"save_dt": 1e-3})
    assert any(b["first_rocking_time"] is not None for b in ref.blocks)  # something happens
    coarse = _errors(stack, motion, t_end, 4e-4, ref)
    fine = _errors(stack, motion, t_end, 1e-4, ref)
    assert fine < coarse / 2.5
    assert fine < 1e-6
