"""An impact the floor's friction cannot hold ends what the two-body model can say.

The Coulomb impact law (derivation §3.6) conserves the statue's angular momentum about the new
corner with r·I_O in place of I_O − 2 m b² when the user fixes r, and bounds the floor's impulse
by friction. With r well below Housner's and a low floor friction, the held outcome needs more
than μs and the sliding one turns the statue back (θ̇⁺ against θ̇⁻): no outcome is consistent.
The law keeps the held one. Until 2026-12-06 the run went on to a verdict, with a warning that
blamed "the paper's impact law": a lone 0.24 × 1.59 m block of r = 0.66 on μs = 0.22 under
Castaic "overturned at t = 9.541 s", where the stack engine, which solves the impact with
friction at both corners, has it at rest (bench/verdict_scan.py --seed 9, run 487). Now the
run's status is ``impact_beyond_friction`` and its verdict undetermined, from the first such impact.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import rocking as rk
from rocking.report import content
from rocking.results.response import held_impact_time, status_of
from rocking.solver import compiled as C
from rocking.stack import Block, Interface, Stack, simulate_stack

G = 9.81
OPTS = rk.Options(gravity=G)
WIDTH, HEIGHT, MASS, R = 0.3, 1.5, 100.0, 0.6
LOW = rk.Friction(static=0.25, kinetic=0.2)
PULSE = rk.SinePulse(amplitude=2.2, frequency=1.5)  # above g·tan α = 1.96, below μs·g = 2.45 m/s²


def _block(restitution=R, friction=LOW):
    return rk.System(statue=rk.Statue(width=WIDTH, height=HEIGHT, mass=MASS, restitution=restitution,
                                      friction=friction))


def _outcomes(theta_dot, r=R, mu_k=LOW.mu_k, b=WIDTH / 2, h=HEIGHT / 2, m=MASS):
    """The impact of a lone block landing on its other corner from rest on the floor (u̇⁻ = 0),
    written out here from momentum balances alone (no code of the library): the held outcome's
    |Fx|/Fy, and for each sliding direction σ whether the slide goes that way and whether it
    turns the block back (θ̇⁺ against θ̇⁻).

    About the new corner: I_O·θ̇⁺ + m·h·u̇⁺ = r·I_O·θ̇⁻. Horizontally: m·u̇⁺ + m·h·θ̇⁺ = m·h·θ̇⁻ + Fx,
    vertically Fy = m·b·(|θ̇⁺| + |θ̇⁻|), and a slide has Fx = −σ·μk·Fy."""
    i_o = m * (b * b + h * h) * 4.0 / 3.0
    held_fx = m * h * (r - 1.0) * theta_dot
    held_fy = m * b * (1.0 + r) * abs(theta_dot)
    turned = []
    for sigma in (1.0, -1.0):
        # unknowns (u̇⁺, θ̇⁺), with |θ̇⁺| taken of the sign of θ̇⁻ as a roll-over onto the new corner has it
        zeta = math.copysign(1.0, theta_dot)
        a = np.array([[m * h, i_o], [m, m * h + sigma * mu_k * m * b * zeta]])
        rhs = np.array([r * i_o * theta_dot, m * h * theta_dot - sigma * mu_k * m * b * abs(theta_dot)])
        u_after, w_after = np.linalg.solve(a, rhs)
        turned.append((sigma * u_after > 0, w_after * theta_dot < 0))  # (slides that way, turns back)
    return abs(held_fx) / held_fy, turned


def test_the_case_has_no_impact_outcome_within_friction():
    """The premise, by hand: the held outcome needs (h/b)(1 − r)/(1 + r) = 5·0.4/1.6 = 1.25 (O19)
    of a floor of μs = 0.25; a slide against the held impulse (the one friction would give) turns
    the block back onto its old corner, and a slide the other way goes the wrong way. With
    Housner's r = 1 − 1.5 sin²α = 0.942 the held outcome needs 0.149 < 0.25."""
    for theta_dot in (-1.0, 1.0):
        ratio, slides = _outcomes(theta_dot)
        assert ratio == pytest.approx(1.25, rel=1e-12)
        assert not any(way and not back for way, back in slides)  # no consistent slide
        assert any(way and back for way, back in slides)  # the one that slides turns back
    r_housner = 1.0 - 1.5 * (WIDTH / 2) ** 2 / ((WIDTH / 2) ** 2 + (HEIGHT / 2) ** 2)
    assert _outcomes(-1.0, r=r_housner)[0] < LOW.mu_s


def test_an_impact_that_friction_cannot_hold_ends_the_two_body_result():
    """Status ``impact_beyond_friction`` from the first impact, whose floor impulse ratio is the
    closed form above (1.25, to 1e-12: it is the held outcome) and whose time is the verdict's; the
    warning counts the impacts held beyond μs, names Housner's r, and the status message sends the
    user to the stack engine; the report does not show it safe and fails the impact check."""
    r = rk.simulate(_block(), PULSE, options=OPTS)
    first = r.impacts[0]
    assert first.u_dot_before == first.u_dot_after == 0.0
    assert first.friction_needed == pytest.approx(1.25, rel=1e-12)
    assert r.status == "impact_beyond_friction" and not r.overturned
    assert held_impact_time(r.raw_summary) == first.time
    assert r.summary()["impact_beyond_friction_time"] == first.time
    assert r.verdict == (f"undetermined: an impact at t = {first.time:.3f} s needed more floor friction than μs, "
                         "which the two-body model's impact law cannot give")
    held = [i for i in r.impacts if i.u_dot_after == 0.0 and i.friction_needed > LOW.mu_s]
    # the block never slides: every impact of the run is one of them, each needing the closed form
    assert len(held) == len(r.impacts) > 10 and r.summary()["peak_sliding"] == 0.0
    np.testing.assert_allclose([i.friction_needed for i in held], 1.25, rtol=1e-12)
    np.testing.assert_array_equal(r.impact_friction_shortfalls(), [i.time for i in held])
    assert [w for w in r.warnings if "no sliding outcome" in w] == [
        f"from t = {first.time:.4f} s, {len(held)} impact(s) needed more floor friction than μs = 0.25 (up to "
        "1.250) and no sliding outcome of the impact was consistent: the block was held as if the floor could "
        "give it; a restitution below Housner's (0.600 against 0.942) takes that impulse"]
    assert not any("the paper's impact law ignores this" in w for w in r.warnings)
    assert any("whose engine solves each impact with friction at both corners" in w for w in r.warnings)
    assert content.verdict(r).startswith(f"Undetermined: an impact at t = {first.time:.3f} s needed more floor")
    assert content.verdict_class(r, content.checks(r)) == "stopped"
    (check,) = [c for c in content.checks(r) if "impact" in c.name]
    assert check.result == content.FAIL and check.value.startswith(f"{len(held)} held beyond it")


@pytest.mark.parametrize(("restitution", "friction"), [(None, LOW), (R, rk.Friction(static=1.3, kinetic=1.2))],
                         ids=["Housner's restitution", "friction enough for r"])
def test_an_impact_within_friction_leaves_the_verdict_alone(restitution, friction):
    """The same pulse with Housner's restitution (the held outcome needs 0.149), or with
    r = 0.6 on μs = 1.3 > 1.25: every impact is within friction, the run ends at rest, and
    neither the status, the warning nor the report's impact check appears."""
    r = rk.simulate(_block(restitution, friction), PULSE, options=OPTS)
    assert r.impacts and r.status == "completed"
    assert held_impact_time(r.raw_summary) is None and r.impact_friction_shortfalls().size == 0
    assert not any("no sliding outcome" in w for w in r.warnings)
    assert not [c for c in content.checks(r) if "impact" in c.name]


def test_the_paper_law_keeps_its_own_warning_and_its_verdict():
    """The paper's law holds a held body by design (θ̇⁺ = r·θ̇⁻, u̇ unchanged, P15): the run keeps
    its verdict, warned that the law ignores the friction, and its report check fails."""
    r = rk.simulate(_block(), PULSE, options=rk.Options(gravity=G, impact="paper"))
    assert r.status in ("completed", "overturned") and held_impact_time(r.raw_summary) is None
    held = [i for i in r.impacts if i.u_dot_before == i.u_dot_after == 0.0 and i.friction_needed > LOW.mu_s]
    assert [w for w in r.warnings if "needed more floor friction" in w] == [
        f"{len(held)} impact(s) needed more floor friction than μs (up to 1.250); the paper's impact law ignores this"]
    (check,) = [c for c in content.checks(r) if "impact" in c.name]
    assert check.result == content.FAIL


def test_the_stack_engine_decides_the_same_block_within_friction():
    """What the status message promises: the stack engine runs the same block to rest, its first
    impact at the two-body model's first held one (to 1e-9 s: both locate θ = 0 on the same
    motion from the same rest), the friction its interface needed within μs."""
    stack = Stack(blocks=(Block(width=WIDTH, height=HEIGHT, mass=MASS),),
                  interfaces=(Interface(friction=LOW, restitution=R),))
    s = simulate_stack(stack, PULSE, options=OPTS).summary()
    two_body = rk.simulate(_block(), PULSE, options=OPTS)
    assert s["status"] == "completed" and not s["overturned"]
    assert s["interfaces"][0]["required_friction"] <= LOW.mu_s
    assert s["blocks"][0]["restitution_reduced_time"] is None
    assert s["first_sliding_time"] == pytest.approx(two_body.impacts[0].time, abs=1e-9)


def test_a_body_sliding_into_an_impact_it_cannot_slide_out_of_counts_too():
    """The Coulomb law's fallback ends the impact held (u̇⁺ = 0) whatever the body did before: a
    block sliding at 0.05 m/s into the same landing needs 1.20 of the floor. Until 2026-12-06 the
    count asked for u̇⁻ = 0 as well (the paper's law's held body), and missed it."""
    from rocking.models.modes import IMPACT
    from rocking.models.parameters import pack
    from rocking.models.transitions import apply_transition

    p = pack(_block(), gravity=G, normal_force="full", impact="coulomb", rest_velocity=1e-6)
    y = np.array([0.0, 0.05, 0.0, -1.0, 0.0, 0.0])
    *_, ratio, _, short = apply_transition(p, IMPACT, False, y, 1, 1, 0.0, 0.0)
    assert y[1] == 0.0 and ratio > LOW.mu_s and short


def test_the_first_end_of_the_model_names_the_status():
    """``status_of`` overrides a run that went on (completed, still moving, out of events,
    overturned) with whichever came first, a lift-off or an impact held beyond friction; never a
    solver failure or an interrupt."""
    def raw(status, n=math.nan, held=math.nan):
        out = np.full(C.N_SUMMARY, math.nan)
        out[C.S_STATUS], out[C.S_N_NONPOSITIVE], out[C.S_HELD_IMPACT] = status, n, held
        return out

    for code, own, overridden in ((C.STATUS_COMPLETED, "completed", True),
                                  (C.STATUS_STILL_MOVING, "still_moving", True),
                                  (C.STATUS_MAX_EVENTS, "max_events", True), (C.STATUS_OVERTURNED, "overturned", True),
                                  (C.STATUS_SINGULAR, "singular", False), (C.STATUS_STEP_FAILED, "step_failed", False),
                                  (C.STATUS_INTERRUPTED, "interrupted", False)):
        assert status_of(raw(code))[0] == own
        assert status_of(raw(code, held=0.5))[0] == ("impact_beyond_friction" if overridden else own)
        assert status_of(raw(code, n=0.4, held=0.5))[0] == ("lifted_off" if overridden else own)
        assert status_of(raw(code, n=0.6, held=0.5))[0] == ("impact_beyond_friction" if overridden else own)


def test_studies_do_not_count_such_a_run_as_standing():
    """The fragility study counts it as a fall (not proven to stand, as a lift-off); the
    overturning spectrum as failing, in its own counter."""
    from rocking.analyses.fragility import ida
    from rocking.analyses.spectra import overturning_spectrum

    runs = ida({"block": _block()}, {"pulse": PULSE}, [2.2, 2.3], options=OPTS, workers=1)
    assert runs.fall.all() and not runs.overturned.any()
    assert (runs.status == "impact_beyond_friction").all()
    ds = overturning_spectrum(_block(), "sine", [2.0], amplitude_range=(1.01, 1.3), n_scan=3, rtol=1e-2,
                              options=OPTS, workers=1)
    assert int(ds.impact_beyond_friction_runs.sum()) > 0
