"""The two-block model (paper §3): limits O16, never-rocks O17, frictionless invariants O18,
impact friction O19, the equations against an independent sympy derivation, energy and symmetry."""


import dataclasses
import math

import numpy as np
import pytest
from helpers import G, NO_MOTION, OPTS, alone, block
from oracles import closed_forms as cf
from oracles import energy, lagrange

import rocking as rk
from rocking.excitation.record import GroundMotion
from rocking.models import dynamics
from rocking.models.parameters import MU_TOP, pack
from rocking.models.regimes import Regime

FLOOR = rk.Friction(static=0.4, kinetic=0.3)
PAPER_MOTION = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30)


def on_pedestal(statue, m1=1.0, friction=FLOOR, **kw):
    return rk.System(statue=statue, pedestal=rk.Pedestal(mass=m1, friction=friction, **kw))


# -- equations of motion against sympy --------------------------------------------------------
@pytest.mark.parametrize("normal_force", ["full", "paper"])
def test_accelerations_match_the_sympy_lagrangian(normal_force):
    rng = np.random.default_rng(7)
    for _ in range(200):
        b, h = rng.uniform(0.1, 0.6), rng.uniform(0.6, 3.0)
        m1, m2 = rng.uniform(0.0, 5.0), rng.uniform(0.2, 5.0)
        mu_s = rng.uniform(0.05, 0.6)
        mu_k = mu_s * rng.uniform(0.5, 1.0)
        st = block(b, h, mass=m2)
        sysm = on_pedestal(st, m1=m1, friction=rk.Friction(static=mu_s, kinetic=mu_k))
        p = pack(sysm, gravity=G, normal_force=normal_force, impact="coulomb", rest_velocity=1e-6)
        params = dict(b=b, h=h, m1=m1, m2=m2, g=G, mu_s=mu_s, mu_k=mu_k, normal_force=normal_force)
        s, sig = int(rng.choice([-1, 1])), int(rng.choice([-1, 1]))
        theta = s * rng.uniform(0.0, 0.9) * st.slenderness
        ud, thd = sig * rng.uniform(0.01, 1.0), rng.uniform(-2, 2)
        a, av = rng.uniform(-8, 8), rng.uniform(-2, 2)
        for regime, (rsig, rs) in {"stick-rock": (0, s), "slide-rock": (sig, s), "slide-rest": (sig, 0)}.items():
            udd, thdd, ok = dynamics.accelerations(p, rsig, rs, ud, theta if rs else 0.0, thd if rs else 0.0, a, av)
            state = (0.0, ud, theta if rs else 0.0, thd if rs else 0.0)
            ref = lagrange.accelerations(regime, params, state, a, av, s=s, sigma=sig)
            assert ok
            np.testing.assert_allclose([udd, thdd], ref[:2], rtol=1e-10, atol=1e-10)
            if rs:
                f, n = dynamics.floor_forces(p, rs, theta, thd, a, av, udd, thdd)
                px, py = dynamics.statue_contact(p, rs, theta, thd, a, av, udd, thdd)
                np.testing.assert_allclose([px, py], ref[4:6], rtol=1e-10, atol=1e-10)
                if normal_force == "full":
                    np.testing.assert_allclose([f, n], [ref[3], ref[2]], rtol=1e-10, atol=1e-10)


def test_worked_check_case_10a_at_t0():
    """derivation §3.5: held pedestal would need 10.47 N against μs N = 8.15 N → slide + rock."""
    st = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
    p = pack(on_pedestal(st), gravity=G, normal_force="full", impact="coulomb", rest_velocity=1e-6)
    udd, thdd, _ = dynamics.accelerations(p, 0, -1, 0.0, 0.0, 0.0, 6.75, 0.0)
    f, n = dynamics.floor_forces(p, -1, 0.0, 0.0, 6.75, 0.0, udd, thdd)
    assert f == pytest.approx(10.47, abs=5e-3) and 0.4 * n == pytest.approx(8.15, abs=5e-3)
    r = rk.simulate(on_pedestal(st), PAPER_MOTION, duration=0.1, options=OPTS)
    assert Regime(int(r.regime[0])) == Regime.SLIDE_ROCK


# -- O16 limits ---------------------------------------------------------------------------------
def test_o16_infinite_floor_friction_is_the_statue_alone():
    st = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
    a = rk.simulate(alone(st), PAPER_MOTION, options=OPTS)
    b = rk.simulate(on_pedestal(st, friction=rk.Friction(static=1e6, kinetic=1e6)), PAPER_MOTION, options=OPTS)
    np.testing.assert_allclose(b.theta, a.theta, atol=1e-9)
    assert b.summary()["peak_sliding"] == 0.0


def test_o16_massless_statue_leaves_a_coulomb_block():
    pedestal_only = rk.simulate(alone(block(5.0, 0.5, friction=FLOOR)), PAPER_MOTION, options=OPTS)
    st = rk.Statue(width=1.0, height=4.0, mass=1e-9)
    with_statue = rk.simulate(on_pedestal(st), PAPER_MOTION, options=OPTS)
    # Event instants differ (the weightless statue still rocks), so compare on a common grid.
    grid = np.linspace(0.0, 25.0, 2501)
    np.testing.assert_allclose(np.interp(grid, with_statue.t, with_statue.u),
                               np.interp(grid, pedestal_only.t, pedestal_only.u), atol=1e-7)


def _sympy_flight(regime, params, y0, t0, t1, a_g, *, s, sigma=0):
    """Integrate lagrange's equations of one regime from (t0, y0) until the statue lands
    (θ = 0), the sliding stops (u̇ = 0) or t1: (solution, end time, end state)."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        udd, thdd, *_ = lagrange.accelerations(regime, params, y, float(a_g(t)), s=s, **({"sigma": sigma} if sigma else {}))
        return [y[1], udd, y[3], thdd]

    lands = lambda t, y: s * y[2]  # noqa: E731
    stops = lambda t, y: sigma * y[1] if sigma else 1.0  # noqa: E731
    for event in (lands, stops):
        event.terminal, event.direction = True, -1
    sol = solve_ivp(rhs, (t0, t1), y0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True, events=(lands, stops))
    return sol, sol.t[-1], sol.y[:, -1]


def test_o16_massless_pedestal_is_the_single_block_slide_rock_model():
    """m1 = 0: a statue on a massless pedestal and the single block with the same floor friction
    both follow the sympy slide-rock equations (solved here by SciPy), then, once the sliding
    stops, the stick-rock ones up to the first impact."""
    friction = rk.Friction(static=0.45, kinetic=0.40)  # μk > tan α = 1/3: the braking tips it over
    motion = rk.Harmonic(amplitude=2.0, frequency=1.2, cycles=3, form="sin")
    st = rk.Statue(width=1.0, height=3.0, mass=2.0, restitution=0.85)
    kw = dict(duration=1.5, options=rk.Options(gravity=G, save_dt=0.005), initial_sliding_velocity=2.0)
    single = rk.simulate(alone(rk.Statue(width=1.0, height=3.0, mass=2.0, restitution=0.85, friction=friction)),
                         motion, **kw)
    stacked = rk.simulate(on_pedestal(st, m1=0.0, friction=friction), motion, **kw)
    params = dict(b=0.5, h=1.5, m1=0.0, m2=2.0, g=G, mu_s=0.45, mu_k=0.40)
    # Sliding towards +x and braked by friction, the statue tips forward about its +x corner.
    slide, t_stop, y_stop = _sympy_flight("slide-rock", params, [0.0, 2.0, 0.0, 0.0], 0.0, 1.5, motion.acceleration,
                                          s=1, sigma=1)
    assert slide.t_events[1].size == 1 and 0.2 < t_stop < 0.3  # the sliding stops first, the statue still up
    y_stop[1] = 0.0
    # Held from then on (the friction the held block needs is within μs·N), it rocks back to θ = 0.
    _, _, n, f, _, _ = lagrange.accelerations("stick-rock", params, y_stop, float(motion.acceleration(t_stop)), s=1)
    assert abs(f) < 0.45 * n
    rock, t_land, _ = _sympy_flight("stick-rock", params, y_stop, t_stop, 1.5, motion.acceleration, s=1)
    assert rock.t_events[0].size == 1 and t_land > 1.0
    for r in (single, stacked):
        stop, land = r.events[0], r.events[1]
        assert (stop.kind, stop.before, stop.after) == (rk.EventKind.STOP, Regime.SLIDE_ROCK, Regime.ROCK)
        assert land.kind == rk.EventKind.IMPACT
        assert stop.time == pytest.approx(t_stop, abs=1e-9)
        assert land.time == pytest.approx(t_land, abs=1e-9)
        for sol, t0, t1 in ((slide, 0.0, t_stop), (rock, t_stop, t_land)):
            inside = (r.t > t0) & (r.t < t1)
            assert inside.sum() > 40
            np.testing.assert_allclose(r.state[inside].T, sol.sol(r.t[inside]), rtol=0, atol=1e-9)
    np.testing.assert_allclose(stacked.state, single.state, rtol=0, atol=1e-12)


# -- O17 ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("motion", [PAPER_MOTION, rk.Harmonic(amplitude=12.0, frequency=2.5, cycles=10, form="sin"),
                                    rk.RickerPulse(amplitude=15.0, frequency=1.0)])
def test_o17_statue_never_rocks_when_mu_s_at_most_tan_alpha(motion):
    st = rk.Statue(width=1.0, height=2.0, mass=3.0)  # tan α = 0.5
    for mu_s in (0.5, 0.4, 0.2):
        r = rk.simulate(on_pedestal(st, m1=2.0, friction=rk.Friction(static=mu_s, kinetic=0.8 * mu_s)), motion, options=OPTS)
        assert r.summary()["first_rocking_time"] is None
        assert r.summary()["peak_sliding"] > 0


# -- O18 frictionless floor ---------------------------------------------------------------------
@pytest.mark.parametrize("H,m2", [(4.0, 1.0), (4.0, 4.0), (2.0, 1.0)])
def test_o18_frictionless_floor_release(H, m2):
    st = rk.Statue(width=1.0, height=H, mass=m2)
    theta0 = 0.5 * st.slenderness
    sysm = on_pedestal(st, friction=rk.Friction(static=0.0, kinetic=0.0))
    r = rk.simulate(sysm, NO_MOTION, duration=1.0, options=OPTS, initial_rotation=theta0)
    ref = cf.frictionless_release(0.5, H / 2, 1.0, m2, theta0, g=G)
    imp = r.impacts[0]
    assert imp.time == pytest.approx(ref.t1, abs=1e-8)
    assert imp.theta_dot_before == pytest.approx(ref.theta_dot, abs=1e-8)
    assert imp.u_dot_before == pytest.approx(ref.u_dot, abs=1e-8)
    i = np.flatnonzero(r.t == imp.time)[0]
    assert r.u[i] == pytest.approx(ref.u, abs=1e-8)
    # With no floor impulse the system's momentum is conserved: η_stack (O18, O19 table).
    eta = cf.eta_stack_frictionless(0.5, H / 2, 1.0, m2)
    assert imp.theta_dot_after / imp.theta_dot_before == pytest.approx(eta, rel=1e-12)
    assert (1.0 + m2) * imp.u_dot_after + m2 * H / 2 * imp.theta_dot_after == pytest.approx(
        (1.0 + m2) * imp.u_dot_before + m2 * H / 2 * imp.theta_dot_before, abs=1e-12)
    # Energy from the saved samples with the sympy derivation's formula: constant up to the
    # impact (no friction, no floor motion), then lower by what the impact took.
    led = energy.ledger(r.t, r.state, r.regime, energy.lagrange_params(sysm, G), NO_MOTION.acceleration,
                        NO_MOTION.vertical_acceleration, NO_MOTION.breakpoints)
    assert np.max(led.input_work) == 0.0 and np.max(led.friction) == 0.0
    assert np.max(np.abs(led.residual)) <= 1e-8 * led.scale
    assert led.losses[0][0] == imp.time and led.losses[0][1] == pytest.approx(imp.energy_lost, rel=1e-9)


def test_o18_table_values():
    rows = {(4.0, 1.0): (0.55652972, -0.49670213, 0.12405637, 0.49670213, 0.86363636),
            (4.0, 4.0): (0.45049012, -0.60558694, 0.19849020, 0.96893911, 0.79729730),
            (2.0, 1.0): (0.41974610, -1.21738173, 0.12156421, 0.60869087, 0.57142857)}
    for (H, m2), (t1, thd, u, ud, eta) in rows.items():
        st = rk.Statue(width=1.0, height=H, mass=m2)
        r = rk.simulate(on_pedestal(st, friction=rk.Friction(static=0.0)), NO_MOTION, duration=1.0, options=OPTS,
                        initial_rotation=0.5 * st.slenderness)
        imp = r.impacts[0]
        np.testing.assert_allclose([imp.time, imp.theta_dot_before, imp.u_dot_before, imp.theta_dot_after / imp.theta_dot_before],
                                   [t1, thd, ud, eta], atol=5e-8)


# -- O19 ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("H,housner,r08", [(2, 0.3529, 0.2222), (3, 0.2432, 0.3333), (4, 0.1846, 0.4444), (5, 0.1485, 0.5556)])
def test_o19_friction_needed_by_an_impact_on_a_held_pedestal(H, housner, r08):
    for restitution, expected in ((None, housner), (0.8, r08)):
        st = rk.Statue(width=1.0, height=H, mass=1.0, restitution=restitution)
        held = on_pedestal(st, friction=rk.Friction(static=10.0, kinetic=10.0))
        r = rk.simulate(held, NO_MOTION, duration=1.5, options=OPTS, initial_rotation=0.5 * st.slenderness)
        eta = st.effective_restitution
        assert r.impacts[0].friction_needed == pytest.approx(H / 2 / 0.5 * (1 - eta) / (1 + eta), rel=1e-10)
        assert r.impacts[0].friction_needed == pytest.approx(expected, abs=5e-5)
        assert r.impacts[0].theta_dot_after / r.impacts[0].theta_dot_before == pytest.approx(eta, rel=1e-12)


def test_o19_paper_rule_flags_missing_floor_friction_and_coulomb_rule_slips():
    """12b (m2 = 6, H = 4, r = 0.8): the paper's rule needs 0.444 > μs = 0.4 at impacts."""
    st = rk.Statue(width=1.0, height=4.0, mass=6.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=24)
    paper = rk.simulate(on_pedestal(st), motion, options=rk.Options(gravity=G, impact="paper"))
    coulomb = rk.simulate(on_pedestal(st), motion, options=OPTS)
    assert paper.summary()["first_sliding_time"] is None
    assert any("more floor friction" in w for w in paper.warnings)
    slip = coulomb.summary()["first_sliding_time"]
    assert slip == pytest.approx(coulomb.impacts[0].time, abs=1e-12)


# -- energy, symmetry -----------------------------------------------------------------------------
@pytest.mark.parametrize("impact,normal_force", [("coulomb", "full"), ("paper", "full"), ("coulomb", "paper")])
def test_energy_ledger_balances_with_friction_and_impacts(impact, normal_force):
    st = rk.Statue(width=1.0, height=4.0, mass=2.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=24)
    # Saved every 2 ms, to the end of the motion (where a_g jumps to 0 and the regime may change).
    r = rk.simulate(on_pedestal(st), motion, duration=motion.duration,
                    options=rk.Options(gravity=G, impact=impact, normal_force=normal_force, save_dt=2e-3))
    assert r.summary()["impacts"] > 10
    # The ledger computed here: E, the power of the floor's inertial forces and of friction from
    # the sympy derivation and the motion's own a_g(t), integrated over the samples.
    led = energy.ledger(r.t, r.state, r.regime, energy.lagrange_params(r.system, G, normal_force),
                        motion.acceleration, motion.vertical_acceleration, motion.breakpoints)
    assert led.friction[-1] > 0.02 * led.scale and led.jumps[-1] > 0.5 * led.scale
    # Quadrature of the 2 ms samples errs by ~1e-10 of the energies (cubic splines, O(dt⁴)).
    assert np.max(np.abs(led.residual)) <= 1e-9 * led.scale
    # Every impact loses energy, the amount the solver reports.
    lost = {imp.time: imp.energy_lost for imp in r.impacts}
    assert len(lost) == r.summary()["impacts"]
    for t, loss in led.losses:
        assert loss >= -1e-12 * led.scale
        if t in lost:
            assert loss == pytest.approx(lost[t], rel=1e-9, abs=1e-12 * led.scale)
    # The solver's own ledger (its summary's balance error) agrees with this one.
    e = r.energy
    np.testing.assert_allclose([e["input_work"], e["friction_dissipation"], e["impact_dissipation"]],
                               [led.input_work[-1], led.friction[-1], led.jumps[-1]], rtol=1e-8)
    assert e["relative_balance_error"] < 1e-8


def test_mirror_symmetry_two_blocks():
    st = rk.Statue(width=1.0, height=4.0, mass=3.0, restitution=0.8)
    a = rk.simulate(on_pedestal(st), rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=10), options=OPTS)
    b = rk.simulate(on_pedestal(st), rk.Harmonic(amplitude=-6.75, frequency=1.2, cycles=10), options=OPTS)
    np.testing.assert_allclose(b.theta, -a.theta, atol=1e-12)
    np.testing.assert_allclose(b.u, -a.u, atol=1e-12)


def test_assumption_checks_report_pedestal_uplift_and_top_slip():
    st = rk.Statue(width=0.4, height=2.0, mass=50.0, friction=rk.Friction(static=0.2, kinetic=0.2))
    ped = rk.Pedestal(mass=5.0, friction=rk.Friction(static=0.6, kinetic=0.5), width=0.5, height=0.8)
    r = rk.simulate(rk.System(statue=st, pedestal=ped), rk.Harmonic(amplitude=6.0, frequency=1.0, cycles=4), options=OPTS)
    text = " ".join(r.warnings)
    assert "slip on the pedestal" in text and "uplift" in text
    assert r.summary()["required_top_friction"] > 0.2


def test_convergence_as_tolerances_tighten():
    st = rk.Statue(width=1.0, height=4.0, mass=2.0, restitution=0.8)
    motion = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=6)
    ref = rk.simulate(on_pedestal(st), motion, options=rk.Options(gravity=G, rtol=1e-13, atol=1e-15))
    errors = []
    for rtol in (1e-5, 1e-7, 1e-9):
        # A large max_step so that the tolerance, not the step cap, sets the accuracy.
        r = rk.simulate(on_pedestal(st), motion, options=rk.Options(gravity=G, rtol=rtol, atol=rtol * 1e-2, max_step=1.0))
        t_ref = np.array([i.time for i in ref.impacts])
        t_run = np.array([i.time for i in r.impacts])
        assert t_run.size == t_ref.size
        errors.append(max(np.max(np.abs(t_run - t_ref)), abs(r.peak_rotation - ref.peak_rotation)))
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 1e-8
    assert errors[0] > 10 * errors[2]


def test_required_top_friction_of_a_statue_at_rest_is_the_largest_transmitted_acceleration():
    """9a's statue never rocks: its base needs |a_base|/g, which peaks at μs just before the
    pedestal slips again (0.29061198 s); while sliding the pedestal transmits μk g < μs g."""
    st = rk.Statue(width=1.0, height=2.0, mass=1.0, restitution=0.8)
    r = rk.simulate(on_pedestal(st), rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=1), options=OPTS)
    assert r.summary()["first_rocking_time"] is None
    assert r.summary()["required_top_friction"] == pytest.approx(0.4, abs=1e-9)


@pytest.mark.parametrize("kind", ["cos", "sin", "ricker", "record", "record-with-vertical"])
def test_required_top_friction_of_a_pedestal_that_never_slides(kind):
    """A squat statue (tan α = 0.83) on a pedestal held by μs = 0.8 moves with the floor for the
    whole run: nothing slides or rocks, so the solver crosses every stretch at rest without a
    step. Its base still needs |P_x|/P_y = |a_g|/(g + a_v), the floor's: the summary's
    required_top_friction must be the largest of that, A/g under a 3 m/s² harmonic (its peak at
    t = 0 for cos, inside the run for sin), max |a_i|/(g + a_v,i) over the samples of a
    record (piecewise linear: the ratio peaks at a sample), |a_p|/g at the centre of a Ricker
    pulse. Until 2026-12-01 it was 0.0 but for the Ricker pulse (the rest crossing skipped the
    check), and the report's top-face check passed a statue whose top face (μs = 0.1) cannot
    hold it. Under the Ricker pulse, where the solver steps at rest, it read the forces at the
    steps' stages only and fell 0.4 % short until 2026-12-02. Closed forms, to 1e-12."""
    statue = rk.Statue(width=1.0, height=1.2, mass=50.0, friction=rk.Friction(static=0.1, kinetic=0.1))
    system = on_pedestal(statue, m1=100.0, friction=rk.Friction(static=0.8, kinetic=0.7))
    if kind in ("cos", "sin"):
        motion = rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form=kind)
        need = 3.0 / G
    elif kind == "ricker":
        motion = rk.RickerPulse(amplitude=3.0, frequency=2.0)
        need = 3.0 / G
    else:
        t = np.round(np.arange(0.0, 4.0, 0.01), 10)
        rng = np.random.default_rng(0)
        a = 2.0 * np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same")
        av = np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same") if kind == "record-with-vertical" else None
        motion = GroundMotion(time=t, values=a, vertical=av)
        need = float(np.max(np.abs(a) / (G + (av if av is not None else 0.0))))
    r = rk.simulate(system, motion, options=OPTS)
    s = r.summary()
    assert r.events == [] and s["first_sliding_time"] is None and s["first_rocking_time"] is None
    assert 0.3 < need < 0.35
    assert s["required_top_friction"] == pytest.approx(need, rel=1e-12)
    # what the saved samples say (Response.contact_forces, from the saved states)
    assert np.nanmax(r.contact_forces()["top_friction_ratio"]) <= need * (1 + 1e-12)


def _first_rest_excess(motion, mu):
    """The first time |a_h(t)| > μ·(g + a_v(t)), from the motion's own formulas (at rest: when a
    statue moving with the floor needs more than μ from its base): bracketed on a grid of 1e-4 s
    (shorter than a quarter of any swing here) and solved by brentq to 1e-15 s."""
    from scipy.optimize import brentq

    def excess(t):
        return abs(float(motion.acceleration(t))) - mu * (G + float(motion.vertical_acceleration(t)))

    grid = np.arange(0.0, motion.duration, 1e-4)
    if isinstance(motion, GroundMotion):
        grid = np.union1d(grid, motion.time)  # (its kinks)
    above = np.nonzero([excess(t) > 0.0 for t in grid])[0]
    assert above.size and above[0] > 0
    k = above[0]
    return brentq(excess, grid[k - 1], grid[k], xtol=1e-15, rtol=4 * np.finfo(float).eps)


def _slip_warning_time(r):
    """The time of the top-slip warning, to the bit (the summary's raw value)."""
    from rocking.solver import compiled as C
    assert sum("would slip on the pedestal" in w for w in r.warnings) == (0 if np.isnan(r.raw_summary[C.S_TOP_SLIP]) else 1)
    return float(r.raw_summary[C.S_TOP_SLIP])


@pytest.mark.parametrize("kind", ["sin", "ricker", "sine-pulse", "record-with-vertical"])
def test_the_top_slip_warning_of_a_statue_at_rest_comes_when_its_base_first_needs_more_than_the_top_mu(kind):
    """The statue and held pedestal of the test above, whose top face has μs = 0.2: the statue
    never rocks, and its base needs |a_h|/(g + a_v), which passes 0.2 inside a stretch the
    solver crosses at rest (or steps at rest, under the Ricker pulse). The run must warn that
    the statue would slip, from the first instant that happens (solved here from the motion's
    formulas by brentq): to 1e-12 s, as the solver bisects the crossing to the last bit and the
    ratio's rounding (1e-16) over its slope (> 0.1 /s) is far below that. With μs 0.1 % above
    the largest need there must be no warning, 0.1 % below one. Until 2026-12-02 no warning came
    at rest at all: the check was made only while the statue rocked or at impacts."""
    if kind == "sin":
        motion = rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form="sin")
    elif kind == "ricker":
        motion = rk.RickerPulse(amplitude=3.0, frequency=2.0)
    elif kind == "sine-pulse":
        motion = rk.SinePulse(amplitude=-3.0, frequency=1.5, phase=0.4)
    else:
        t = np.round(np.arange(0.0, 4.0, 0.01), 10)
        rng = np.random.default_rng(3)
        a = 2.0 * np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same")
        av = np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same")
        motion = GroundMotion(time=t, values=a, vertical=av)

    def run(mu):
        statue = rk.Statue(width=1.0, height=1.2, mass=50.0, friction=rk.Friction(static=mu, kinetic=mu))
        return rk.simulate(on_pedestal(statue, m1=100.0, friction=rk.Friction(static=0.8, kinetic=0.7)), motion,
                           options=OPTS)

    r = run(0.2)
    assert r.events == [] and r.summary()["first_rocking_time"] is None
    want = _first_rest_excess(motion, 0.2)
    assert want > 0.01
    assert _slip_warning_time(r) == pytest.approx(want, abs=1e-12)
    need = r.summary()["required_top_friction"]
    assert np.isnan(_slip_warning_time(run(1.001 * need)))
    assert _slip_warning_time(run(0.999 * need)) > want


def test_a_frictionless_top_face_is_flagged_at_rest_as_soon_as_the_floor_moves():
    """A top face given μs = 0 holds nothing: a statue at rest on a held pedestal needs
    |a_g|/g > 0 from the first instant the floor accelerates. Under a sine from t = 0 (a_g(0) = 0)
    the warning must start at once (the bisection ends within 1e-12 s of 0), though nothing ever
    rocks or slides. Kills compiled.py's rest check made only for μs,top > 0 (a frictionless face
    never flagged at rest: the run crosses its rest without a step, so no other check sees it)."""
    from rocking.solver import compiled as C

    statue = rk.Statue(width=1.0, height=1.2, mass=50.0, friction=rk.Friction(static=0.0, kinetic=0.0))
    r = rk.simulate(on_pedestal(statue, m1=100.0, friction=rk.Friction(static=0.8, kinetic=0.7)),
                    rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form="sin"), options=OPTS)
    assert r.events == [] and r.summary()["first_rocking_time"] is None
    assert 0.0 <= r.raw_summary[C.S_TOP_SLIP] < 1e-12
    assert r.summary()["top_slip_time"] == r.raw_summary[C.S_TOP_SLIP]


def test_a_figurine_of_50_grams_at_rest_needs_the_floors_ratio_too():
    """The friction a statue at rest needs, |P_x|/P_y = |a_g|/g, does not depend on its mass: a
    50 g figurine (P_y = 0.49 N) on a held pedestal under a 3 m/s² sine needs 3/g as a 50 kg
    statue does, to 1e-12. Kills compiled.py's rest ratio read only where P_y > 1 N (a force
    compared with a number of newtons: the ratio of a light object read as 0)."""
    statue = rk.Statue(width=0.02, height=0.024, mass=0.05)
    r = rk.simulate(on_pedestal(statue, m1=2.0, friction=rk.Friction(static=0.8, kinetic=0.7)),
                    rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form="sin"), options=OPTS)
    assert r.events == [] and r.summary()["first_rocking_time"] is None
    assert r.summary()["required_top_friction"] == pytest.approx(3.0 / G, rel=1e-12)


def _rest_motion(kind):
    if kind == "sin":
        return rk.Harmonic(amplitude=3.0, frequency=2.0, cycles=2, form="sin")
    if kind == "ricker":
        return rk.RickerPulse(amplitude=3.0, frequency=2.0)
    t = np.round(np.arange(0.0, 4.0, 0.01), 10)
    rng = np.random.default_rng(3)
    a = 2.0 * np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same")
    av = np.convolve(rng.normal(size=t.size), np.ones(5) / 5, mode="same")
    return GroundMotion(time=t, values=a, vertical=av)


@pytest.mark.parametrize("kind", ["sin", "ricker", "record-with-vertical"])
def test_the_uplift_warning_of_a_tall_narrow_pedestal_under_a_resting_statue(kind):
    """A squat statue (1.0 × 1.2 m, 50 kg) on a pedestal 0.3 m wide and 1 m tall (50 kg) that
    μs = 0.8 holds: nothing slides or rocks, but the floor's normal force moves off the
    pedestal's base. At rest the two move as one body, and moments about the base centre give
    |x_N| = |a_h|·(m₁H₁/2 + m₂(H₁ + h₂)) / ((m₁ + m₂)(g + a_v)) (h₂ = 0.6 m, the statue's centre
    above its base), so it leaves the half-width b₁ = 0.15 m when |a_h|/(g + a_v) >
    b₁(m₁ + m₂)/(m₁H₁/2 + m₂(H₁ + h₂)) = 1/7. The run must warn that the pedestal would uplift,
    from that first instant (brentq on the motion's formulas; 1e-12 s as for the top slip above),
    and not at all on a pedestal 0.9 m wide (3/7 > 0.4 > every |a_h|/(g + a_v) here). Until
    2026-12-02 the check was made only while the statue rocked: the verdict "did not overturn; at
    rest" came with no warning, for a pedestal that tips. Until 2026-12-06 it left out the
    statue's own couple on the pedestal (m₂h₂ of the moment arm; the threshold read 0.2) and
    warned late or not at all."""
    motion = _rest_motion(kind)

    def run(width):
        statue = rk.Statue(width=1.0, height=1.2, mass=50.0)
        pedestal = rk.Pedestal(mass=50.0, friction=rk.Friction(static=0.8, kinetic=0.7), width=width, height=1.0)
        return rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, options=OPTS)

    from rocking.solver import compiled as C
    r = run(0.3)
    assert r.events == [] and r.summary()["first_rocking_time"] is None
    want = _first_rest_excess(motion, 0.15 * 100.0 / (50.0 * 1.0 / 2 + 50.0 * (1.0 + 0.6)))
    assert want > 0.01
    (up,) = [w for w in r.warnings if "uplift" in w]
    assert up.startswith(f"from t = {want:.4f} s")
    assert r.raw_summary[C.S_UPLIFT] == pytest.approx(want, abs=1e-12)
    wide = run(0.9)
    assert wide.summary()["required_top_friction"] < 0.4
    assert np.isnan(wide.raw_summary[C.S_UPLIFT]) and not any("uplift" in w for w in wide.warnings)


def test_a_pedestal_and_a_resting_statue_tip_as_one_when_the_stack_engine_lifts_the_pedestal():
    """A 0.47 × 0.86 m statue (259 kg) on a 0.80 × 0.94 m pedestal (345 kg, μs = 0.52) under Kobe
    at 6.9 m/s² (seed 3's run 213 of bench/verdict_scan.py). The statue would rock at
    g·b/h = 5.35 m/s² and the pedestal slide at μs·g = 5.13, but the two tip as one body about
    the pedestal's corner first, when |a_h| reaches g·b₁(m₁ + m₂)/(m₁H₁/2 + m₂(H₁ + h₂)) =
    4.584 m/s² (issue 11's onset formula), at 2.736 s: the general engine (rocking.stack, which
    shares no physics code with the two-body solver) rocks the pedestal there, and its statue
    later falls. The two-body model, whose pedestal cannot rock, must warn of the uplift at that
    instant (to 1e-9 s; measured 1e-13). Until 2026-12-06 its moment balance at rest left out the
    statue's own couple on the pedestal, its threshold read 5.85 m/s², which the pedestal's
    slips kept it below, and the run said "did not overturn" with no warning at all."""
    from rocking.io.records import read_record
    from rocking.stack import Block, Interface, Stack, simulate_stack

    (w1, h1, m1), (w2, h2, m2) = (0.8023499127013874, 0.9418190859594764, 344.83202135531354), \
        (0.47036109298562767, 0.8627652197572526, 259.3580231095145)
    friction = rk.Friction(static=0.5232158975772888, kinetic=0.508028597928443)
    motion = read_record("Kobe1995_Takatori_000").trimmed(20.0).scaled(pga=6.923437609423012)
    system = rk.System(statue=rk.Statue(width=w2, height=h2, mass=m2),
                       pedestal=rk.Pedestal(mass=m1, friction=friction, width=w1, height=h1))
    two = rk.simulate(system, motion)
    stack = simulate_stack(Stack(blocks=(Block(width=w1, height=h1, mass=m1), Block(width=w2, height=h2, mass=m2)),
                                 interfaces=(Interface(friction=friction), Interface())), motion)
    onset = stack.blocks[0]["first_rocking_time"]
    assert 2.73 < onset < 2.74 and stack.blocks[0]["first_sliding_time"] > onset
    a_up = 9.80665 * (w1 / 2) * (m1 + m2) / (m1 * h1 / 2 + m2 * (h1 + h2 / 2))  # (the default gravity)
    assert abs(float(motion.acceleration(np.array([onset]))[0])) == pytest.approx(a_up, rel=1e-9)
    assert two.summary()["pedestal_uplift_time"] == pytest.approx(onset, abs=1e-9)
    assert any("uplift" in w for w in two.warnings)


def _moving_case(case):
    """(system, motion, the summary slots the case's warnings fill) of the test below."""
    from rocking.solver import compiled as C

    held = rk.Friction(static=0.8, kinetic=0.7)
    sine = rk.Harmonic(amplitude=3.5, frequency=1.5, cycles=3, form="sin")
    if case.startswith("top slip"):
        mu = float(case.split()[-1])
        statue = rk.Statue(width=0.4, height=1.6, mass=100.0, friction=rk.Friction(static=mu, kinetic=mu))
        return rk.System(statue=statue, pedestal=rk.Pedestal(mass=100.0, friction=held)), sine, (C.S_TOP_SLIP,)
    statue = rk.Statue(width=0.4, height=1.6, mass=100.0)
    if case.startswith("uplift"):
        width, height = (float(v) for v in case.split()[1:])
        pedestal = rk.Pedestal(mass=100.0, friction=held, width=width, height=height)
        return rk.System(statue=statue, pedestal=pedestal), sine, (C.S_UPLIFT,)
    # a vertical floor acceleration that dips to −1.2 g at 1.5 s, while the statue rocks
    t = np.round(np.arange(0.0, 3.0, 0.01), 10)
    motion = GroundMotion(time=t, values=3.5 * np.sin(3.0 * np.pi * t), vertical=-1.2 * G * np.exp(-((t - 1.5) / 0.1) ** 2))
    return rk.System(statue=statue, pedestal=rk.Pedestal(mass=100.0, friction=held)), motion, (C.S_N_NONPOSITIVE,
                                                                                             C.S_PY_NONPOSITIVE)


def _first_failing_sample(r, motion, slot):
    """Index of the first saved sample at which the warning's check fails, judged from the sympy
    derivation's forces (tests/oracles/lagrange.py) at the saved state, and the regime's own
    formula for each check (derivation §3.5), not from the solver's forces."""
    from rocking.solver import compiled as C

    params = energy.lagrange_params(r.system, G)
    names = {0: "stick-rest", 1: "stick-rock", 2: "slide-rest", 3: "slide-rock"}
    a_g, a_v = motion.acceleration(r.t), motion.vertical_acceleration(r.t)
    for i in range(r.t.size):
        code = int(r.regime[i])
        s = int(np.sign(r.theta[i])) if code & 1 else 0
        sigma = int(np.sign(r.u_dot[i])) if code & 2 else None
        if (code & 1 and s == 0) or (code & 2 and sigma == 0):
            continue  # an onset sample: no pivot or direction yet (the check holds there in every case here)
        udd, _, n, _, px, py = lagrange.accelerations(names[code], params, r.state[i], a_g[i], a_v[i], s=s or None,
                                                      sigma=sigma)
        if slot == C.S_TOP_SLIP:
            fails = abs(px) > r.system.statue.friction.mu_s * py
        elif slot == C.S_UPLIFT:
            x_n = lagrange.pedestal_center_of_pressure(params, r.system.pedestal.height, s, px, py, n, a_g[i] + udd)
            fails = n > 0.0 and abs(x_n) > 0.5 * r.system.pedestal.width
        elif slot == C.S_N_NONPOSITIVE:
            fails = n <= 0.0
        else:
            fails = py <= 0.0
        if fails:
            return i
    raise AssertionError("the check never fails on the samples")


@pytest.mark.parametrize("case", ["top slip 0.26", "top slip 0.27", "uplift 0.6 1.0", "uplift 0.65 1.0",
                                  "uplift 0.8 1.5", "lift-off"])
def test_a_warning_while_the_statue_rocks_comes_when_its_check_first_fails(case):
    """A statue 0.4 × 1.6 m rocking on a pedestal that μs = 0.8 holds, under a sine of 3.5 m/s²
    at 1.5 Hz: its base needs more than μs,top = 0.26 or 0.27 from the pedestal's top (peak 0.275);
    the pedestal's base (0.6–0.8 m wide, 1–1.5 m tall) has the floor's normal force move past its
    edge; or, under a vertical floor acceleration dipping to −1.2 g, the floor's normal force and
    the statue's base force reach zero. Each first failure comes while the statue rocks, between
    step ends. The warning's time must lie between the last saved sample (every 0.1 ms) where the
    check holds and the first where it fails, judged from the sympy derivation's forces at those
    states. Until 2026-12-02 a warning took the first step end that failed the check: the top
    slip at 0.26 came at 0.1409 s for 0.1009 (40 ms late), the uplift at 0.6 m at 0.1409 s for
    0.0968, that at 0.65 m not at all (the normal force left the base and came back inside one
    step), the lift-off at the record's sample 1.46 s for 1.4570 s."""
    system, motion, slots = _moving_case(case)
    r = rk.simulate(system, motion, options=rk.Options(gravity=G, save_dt=1e-4))
    assert r.summary()["first_rocking_time"] < 0.1
    for slot in slots:
        t_warn = float(r.raw_summary[slot])
        i = _first_failing_sample(r, motion, slot)
        assert r.regime[i] & 1 and r.t[i] > r.summary()["first_rocking_time"] + 1e-3
        assert r.t[i - 1] < t_warn <= r.t[i] + 1e-12, (slot, r.t[i - 1], t_warn, r.t[i])


def _largest_need(r, motion):
    """max |P_x|/P_y of a statue rocking on a held pedestal (|θ| ≤ α), from the sympy forces at
    the saved samples, then on a 1 µs grid around the best one, integrated there from its sample
    by SciPy (DOP853, rtol 1e-12) on the sympy stick-rock equation."""
    from scipy.integrate import solve_ivp

    params = energy.lagrange_params(r.system, G)
    alpha = math.atan2(r.system.statue.width, r.system.statue.height)

    def ratio(state, t, s):
        _, _, _, _, px, py = lagrange.accelerations("stick-rock", params, state, float(motion.acceleration(t)), 0.0, s=s)
        return abs(px) / py if py > 0.0 else 0.0

    def pivot(i):  # at θ = 0 (an impact's or an onset's sample), that of the same stretch's neighbour
        if abs(r.theta[i]) > 1e-12:
            return int(np.sign(r.theta[i]))
        before_event = i + 1 < r.t.size and r.t[i + 1] == r.t[i]
        return int(np.sign(r.theta[i - 1] if before_event else r.theta[i + 1]))

    best, i_best = -1.0, -1
    for i in np.flatnonzero((r.regime == 1) & (np.abs(r.theta) <= alpha)):
        if pivot(i) == 0:
            continue  # (a neighbour at θ = 0 too: the instant of an impact, seen from its other sample)
        v = ratio(r.state[i], r.t[i], pivot(i))
        if v > best:
            best, i_best = v, i
    s = pivot(i_best)

    def rhs(t, y):
        _, thdd, *_ = lagrange.accelerations("stick-rock", params, (0.0, 0.0, y[0], y[1]), float(motion.acceleration(t)), 0.0, s=s)
        return [y[1], thdd]

    t0 = r.t[i_best]
    for direction in (1.0, -1.0):  # 0.1 ms either side, unless an event or the stretch ends first
        t1 = t0 + direction * 1e-4
        j = i_best + int(direction)
        if not (0 <= j < r.t.size and r.regime[j] == 1 and np.sign(r.theta[j]) == s and r.t[j] != t0):
            continue
        grid = np.linspace(t0, t1, 101)
        sol = solve_ivp(rhs, (t0, t1), [r.theta[i_best], r.theta_dot[i_best]], method="DOP853", t_eval=grid,
                        rtol=1e-12, atol=1e-14)
        for k, tk in enumerate(sol.t):
            best = max(best, ratio((0.0, 0.0, sol.y[0, k], sol.y[1, k]), tk, s))
    return best


@pytest.mark.parametrize("amplitude", [3.5, 3.0])
def test_a_top_face_just_weaker_than_the_rocking_statue_needs_is_warned(amplitude):
    """The rocking statue of the test above, under its sine or one of 3.0 m/s², with the top face's
    μs 0.1 % below the friction its base needs (`required_top_friction`, above tan α = 0.25: the
    peak comes while it rocks, not at rest, where it needs |a_g|/g < tan α): the need passes μs
    only for a few milliseconds around its peak, inside one step. The run must warn, once, inside
    the 0.1 ms samples where the sympy forces exceed μs; with μs 0.1 % above the need, it must not.
    A summary that says the statue needs more than its top face gives, with no warning, contradicts
    itself: so it did until 2026-12-02 whenever the excess began and ended between two step ends
    (the check was made there only); the stages of each step now see it, and a near miss between
    them has the dense output searched."""
    held = rk.Friction(static=0.8, kinetic=0.7)
    motion = rk.Harmonic(amplitude=amplitude, frequency=1.5, cycles=3, form="sin")

    def run(mu):
        friction = None if mu is None else rk.Friction(static=mu, kinetic=mu)
        statue = rk.Statue(width=0.4, height=1.6, mass=100.0, friction=friction)
        return rk.simulate(rk.System(statue=statue, pedestal=rk.Pedestal(mass=100.0, friction=held)), motion,
                           options=rk.Options(gravity=G, save_dt=1e-4))

    free = run(None)
    need = free.summary()["required_top_friction"]
    assert need > 0.2501
    # The need itself is the peak of |P_x|/P_y, found between the solver's stages: against the
    # sympy forces at the 0.1 ms samples, refined at 1 µs around the best one (a peak's samples
    # read it low by (Δt)²·|r''|/8r ≈ 1e-10 at 1 µs). Until 2026-12-02 the stages alone read it
    # 7e-5 low (0.274986 for 0.275007 at 3.5 m/s²).
    assert need == pytest.approx(_largest_need(free, motion), rel=1e-8)
    r = run(0.999 * need)
    assert r.summary()["required_top_friction"] == pytest.approx(need, rel=1e-9)  # (μs,top only checks)
    from rocking.solver import compiled as C

    t_warn = _slip_warning_time(r)
    i = _first_failing_sample(r, motion, C.S_TOP_SLIP)
    assert r.regime[i] & 1 and r.t[i - 1] < t_warn <= r.t[i] + 1e-12
    assert np.isnan(_slip_warning_time(run(1.001 * need)))
    # And the summary never contradicts itself, however close μs,top is to the need: 1e-7 below
    # it the excess lasts well under a millisecond, between two stages, and must be warned (found by the
    # near-miss search of derivation §3.5: until 2026-12-02 a need 1e-5 above μs,top went
    # unwarned); 1e-7 above it, the run must not warn.
    assert _slip_warning_time(run((1.0 - 1e-7) * need)) > 0.1
    assert np.isnan(_slip_warning_time(run((1.0 + 1e-7) * need)))


def test_a_frictionless_top_face_under_a_statue_that_rocks_from_the_start_is_flagged_at_once():
    """μs,top = 0 given for the statue's base, under a cosine whose first value (3.5 m/s²) rocks
    the statue at t = 0: there is no rest stretch to check, and the base needs |P_x| > 0 from
    the first instant. The warning must say t = 0 exactly (it said the first step's end before
    the stage checks; a stage check that skipped μs = 0, mutant 29dbac14, said so again)."""
    statue = rk.Statue(width=0.4, height=1.6, mass=100.0, friction=rk.Friction(static=0.0, kinetic=0.0))
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=0.8, kinetic=0.7))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), rk.Harmonic(amplitude=3.5, frequency=1.5, cycles=1),
                    options=OPTS)
    assert r.summary()["first_rocking_time"] == 0.0
    assert _slip_warning_time(r) == 0.0


@pytest.mark.parametrize("floor_mu", [0.8, 0.1])
def test_the_lift_off_warnings_at_rest_or_sliding_come_when_the_floor_falls_faster_than_g(floor_mu):
    """A squat statue (1 × 1 m) on a pedestal (μs = 0.8 or 0.1), under a weak sine (0.35 m/s²)
    and a vertical floor acceleration that dips to −1.2 g at 1.5 s: the pedestal slides (from
    0.06 s, or once μs·(g + a_v) falls below |a_h| near 1.45 s) and the statue rests on it. Until
    the statue rocks, N and P_y are the weights times g + a_v: both reach zero where a_v = −g first
    (brentq on the record's linear pieces, to 1e-15 s). Both warnings must come then, to 1e-12 s.
    Until 2026-12-02 neither was checked unless the statue rocked (here that instant is also an
    event, the rocking onset at zero threshold, whose post-event check caught it: this guards the
    checks in every regime, not a time that was wrong)."""
    from scipy.optimize import brentq

    from rocking.solver import compiled as C

    t = np.round(np.arange(0.0, 3.0, 0.01), 10)
    motion = GroundMotion(time=t, values=0.35 * np.sin(3.0 * np.pi * t), vertical=-1.2 * G * np.exp(-((t - 1.5) / 0.1) ** 2))
    statue = rk.Statue(width=1.0, height=1.0, mass=100.0)
    pedestal = rk.Pedestal(mass=100.0, friction=rk.Friction(static=floor_mu, kinetic=0.75 * floor_mu))
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, options=OPTS)
    first = np.flatnonzero(G + motion.vertical <= 0.0)[0]
    want = brentq(lambda x: G + float(motion.vertical_acceleration(x)), t[first - 1], t[first], xtol=1e-15)
    assert r.summary()["first_rocking_time"] == pytest.approx(want, abs=1e-9)  # not before
    assert r.summary()["first_sliding_time"] < want  # (μs·(g + a_v) falls below |a_h| first)
    assert r.raw_summary[C.S_N_NONPOSITIVE] == pytest.approx(want, abs=1e-12)
    assert r.raw_summary[C.S_PY_NONPOSITIVE] == pytest.approx(want, abs=1e-12)
    assert sum("would jump" in w for w in r.warnings) == 1 and sum("would lift off" in w for w in r.warnings) == 1


@dataclasses.dataclass(frozen=True, kw_only=True, slots=True)
class _SineWithVerticalSine(rk.Harmonic):
    """A user's own motion (AbstractMotion's extension point, vertical_signal): the harmonic
    horizontal floor of rk.Harmonic, and a vertical floor acceleration B·sin(2π f_v t), m/s², for
    as long."""

    vertical_amplitude: float = 0.0
    vertical_frequency: float = 1.0

    def _vertical(self):
        return rk.Harmonic(amplitude=self.vertical_amplitude, frequency=self.vertical_frequency,
                           cycles=self.duration * self.vertical_frequency, form="sin")

    def vertical_signal(self):
        return self._vertical().signal()

    def vertical_acceleration(self, t):
        return self._vertical().acceleration(t)


@pytest.mark.parametrize("check, fv, depth", [("N", 2.0, 0.977), ("N", 2.0, 0.9775), ("P_y", 2.5, 0.9881),
                                              ("P_y", 3.0, 0.9997), ("N", 2.0, 0.97652), ("P_y", 2.2, 0.9701),
                                              ("P_y", 2.0, 0.9547)])
def test_a_lift_off_that_starts_and_ends_inside_one_step_is_warned_when_it_starts(check, fv, depth):
    """A statue 0.4 × 1.6 m rocking on a held pedestal under one cycle of a 3.5 m/s² sine at
    1.5 Hz, and a vertical floor acceleration −depth·g·sin(2π f_v t) whose trough, with the
    statue's own rocking, takes the floor's normal force N (or the statue's base force P_y) just
    below zero for 0.8–7 ms, between two ends of one of the solver's steps (about 16 ms long
    here). The dip is judged from the sympy forces (tests/oracles/lagrange.py) at samples 0.1 ms
    apart: it must be short (its first and last failing samples within 10 ms) and the warning
    must come between the last sample before it and its first. The first four dips are wide
    enough for a stage of the step to fall in them: with the checks at the stages removed, none
    was warned. The last three (0.8–2 ms, to −0.03 … −0.12 N) fall between the stages, and were
    not warned until 2026-12-02: the margin the stages see near zero now has the dense output
    searched (derivation §3.5)."""
    from rocking.solver import compiled as C

    held = rk.Friction(static=0.8, kinetic=0.7)
    system = rk.System(statue=rk.Statue(width=0.4, height=1.6, mass=100.0), pedestal=rk.Pedestal(mass=100.0, friction=held))
    motion = _SineWithVerticalSine(amplitude=3.5, frequency=1.5, cycles=1, form="sin", vertical_amplitude=-depth * G,
                                   vertical_frequency=fv)
    r = rk.simulate(system, motion, options=rk.Options(gravity=G, save_dt=1e-4))
    slot = C.S_N_NONPOSITIVE if check == "N" else C.S_PY_NONPOSITIVE
    params = energy.lagrange_params(r.system, G)
    names = {0: "stick-rest", 1: "stick-rock", 2: "slide-rest", 3: "slide-rock"}
    failing = []
    for i in np.flatnonzero(r.t < 1.0):
        code = int(r.regime[i])
        s = int(np.sign(r.theta[i])) if code & 1 else None
        sigma = int(np.sign(r.u_dot[i])) if code & 2 else None
        if s == 0 or sigma == 0:
            continue  # an event's sample: no pivot or direction (none falls in the dip here)
        _, _, n, _, _, py = lagrange.accelerations(names[code], params, r.state[i], float(motion.acceleration(r.t[i])),
                                                   float(motion.vertical_acceleration(r.t[i])), s=s, sigma=sigma)
        if (n if check == "N" else py) <= 0.0:
            failing.append(i)
    assert failing, "the dip does not reach zero"
    first, last = failing[0], failing[-1]
    assert r.t[last] - r.t[first] < 0.01 and last - first == len(failing) - 1  # one short dip
    assert r.t[first - 1] < float(r.raw_summary[slot]) <= r.t[first] + 1e-12
    word = "would jump" if check == "N" else "would lift off"
    assert sum(word in w for w in r.warnings) == 1


def test_no_lift_off_is_warned_where_the_statues_base_stays_pressed():
    """A 0.49 × 1.93 m statue (151 kg) on a 149 kg pedestal sliding on the floor, under a
    7.1 m/s² sine at 1.40 Hz with a vertical 7.2 m/s² sine at 6.8 Hz: it passes α at 1.18 s
    and falls at 2.13 s, its top face slipping from 1.9877 s (μs 0.616). Its base force P_y
    stays positive at every sample 10 µs apart from 1.95 s to the fall, by the sympy forces
    (tests/oracles/lagrange.py): no lift-off may be warned. The mutant 9c67faeb of the
    thirtieth round (the near-miss search of an accepted step run over twice the step, half of
    it extrapolated) warned one at 2.08 s. The top-face slip is warned at the saved forces'
    first failure (to the 10 µs grid)."""
    from rocking.solver import compiled as C

    statue = rk.Statue(width=0.487680039156713, height=1.9324409135614022, mass=151.41014904597316,
                       friction=rk.Friction(static=0.6160617256323125, kinetic=0.5149742034108533))
    pedestal = rk.Pedestal(mass=149.15388079025325, width=0.7405542397054135, height=0.17199412148118165,
                           friction=rk.Friction(static=0.5173433852746537, kinetic=0.47510870364512237))
    motion = _SineWithVerticalSine(amplitude=7.10681455501137, frequency=1.3977521523812648, cycles=1, form="sin",
                                   vertical_amplitude=7.156358398838781, vertical_frequency=6.791903118693617)
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, duration=3.715434419683319,
                    options=rk.Options(save_dt=1e-5))
    assert r.summary()["overturned"]
    params = energy.lagrange_params(r.system, 9.80665)
    names = {0: "stick-rest", 1: "stick-rock", 2: "slide-rest", 3: "slide-rock"}
    pressed = 0
    for i in np.flatnonzero((r.t > 1.95) & (np.abs(r.theta) < 1.5)):
        code = int(r.regime[i])
        s = int(np.sign(r.theta[i])) if code & 1 else None
        sigma = int(np.sign(r.u_dot[i])) if code & 2 else None
        if s == 0 or sigma == 0:
            continue
        *_, py = lagrange.accelerations(names[code], params, r.state[i], float(motion.acceleration(r.t[i])),
                                        float(motion.vertical_acceleration(r.t[i])), s=s, sigma=sigma)
        assert py > 0.0, r.t[i]
        pressed += 1
    assert pressed > 15000
    assert math.isnan(r.raw_summary[C.S_PY_NONPOSITIVE])
    assert not any("would lift off" in w for w in r.warnings)
    forces = r.contact_forces()
    slips = np.flatnonzero(forces["top_friction_ratio"] > statue.friction.mu_s)
    assert r.t[slips[0] - 1] < r.summary()["top_slip_time"] <= r.t[slips[0]]


def test_an_uplift_just_before_the_pedestal_jumps_is_warned_when_it_happens():
    """A 0.16 × 1.08 m statue (188 kg) rocking on a light 36 kg pedestal 0.46 × 0.30 m, under a
    3.3 m/s² sine at 0.72 Hz with a vertical 8.9 m/s² sine at 3.7 Hz. As the floor's normal
    force N falls to zero at 0.7286 s the pressure centre x_N = (s·b·P_y − h₁P_x −
    ½h₁m₁(a + ü))/N (the pedestal's moment balance about its base centre, derivation §3.5)
    runs off the base: 0.3 ms before N = 0 the pedestal uplifts. Judged here from the sympy
    forces (tests/oracles/lagrange.py) every 10 µs, the uplift warning must come between the
    last sample inside the base and the first outside it (or past N = 0 with a moment). Until
    2026-12-03 the check read x_N as undefined where N ≤ 0, so a step that ended past the jump
    saw nothing, and the uplift was warned at 0.9659 s."""
    statue = rk.Statue(width=0.1602306940562029, height=1.0840003042417525, mass=187.59906755482473,
                       friction=rk.Friction(static=1.1727550216908469, kinetic=0.984751003909859))
    pedestal = rk.Pedestal(mass=36.05375407384685, width=0.45553087005102344, height=0.2998643197923171,
                           friction=rk.Friction(static=0.5361111213104793, kinetic=0.3507974730333762))
    motion = _SineWithVerticalSine(amplitude=3.3330909598123837, frequency=0.7217948025130159, cycles=2,
                                   form="sin", vertical_amplitude=8.89076670043662,
                                   vertical_frequency=3.6828139989051816)
    r = rk.simulate(rk.System(statue=statue, pedestal=pedestal), motion, duration=0.8,
                    options=rk.Options(save_dt=1e-5))
    params = energy.lagrange_params(r.system, 9.80665)
    b, h1, m1 = 0.5 * statue.width, pedestal.height, pedestal.mass
    names = {0: "stick-rest", 1: "stick-rock", 2: "slide-rest", 3: "slide-rock"}
    first = None
    for i in np.flatnonzero(r.t <= 0.8):
        code = int(r.regime[i])
        if not code & 1:
            continue  # (uplift is watched while the statue rocks)
        s = int(np.sign(r.theta[i]))
        sigma = int(np.sign(r.u_dot[i])) if code & 2 else None
        if s == 0 or sigma == 0:
            continue
        a = float(motion.acceleration(r.t[i]))
        udd, _, n, _, px, py = lagrange.accelerations(names[code], params, r.state[i], a,
                                                      float(motion.vertical_acceleration(r.t[i])), s=s, sigma=sigma)
        moment = s * b * py - h1 * px - 0.5 * h1 * m1 * (a + udd)
        if (n > 0 and abs(moment / n) > 0.5 * pedestal.width) or (n <= 0 and moment != 0):
            first = i
            break
    assert first is not None and 0.7280 < r.t[first] < 0.7286
    warned = r.summary()["pedestal_uplift_time"]
    assert r.t[first - 1] < warned <= r.t[first] + 1e-12
    # Response.violations() judges the saved samples by the same rule
    assert min(t0 for name, t0, _ in r.violations() if name == "pedestal uplift") == r.t[first]


@pytest.mark.parametrize("kind", ["cosine", "ricker", "ricker-fast", "linear-with-vertical"])
def test_the_first_failure_at_rest_is_the_first_crossing_on_any_stretch(kind):
    """The search behind both warnings at rest (compiled._first_failure), on 400 random stretches
    of one floor-motion piece each and random top-face μs: the statue's base fails the check
    where |a_h| > μs·(g + a_v). Against the motion's formulas written here, sampled at 20 001
    points of the stretch: the returned instant must hold the check until it (no sample before it
    fails, to 1e-12 of the level), fail just after it (within 1e-12 s: the bisection ends at the
    last bit), and lie no later than the first failing sample (a later crossing of a wavelet's
    three crests is not the first). NaN only where no sample fails. "ricker-fast" is a 6 Hz
    wavelet, whose crests and zeros crowd into a few tens of milliseconds."""
    from rocking.solver.compiled import _first_failure

    rng = np.random.default_rng(sum(map(ord, kind)))
    statue = rk.Statue(width=1.0, height=1.2, mass=50.0, friction=rk.Friction(static=0.2, kinetic=0.2))
    base = pack(on_pedestal(statue, m1=100.0, friction=rk.Friction(static=0.8, kinetic=0.7)), gravity=G,
                normal_force="full", impact="coulomb", rest_velocity=1e-6)
    y = np.zeros(6)
    found = 0
    for _ in range(400):
        if kind == "cosine":
            amp, omega, phase = rng.uniform(-6, 6), rng.uniform(2, 30), rng.uniform(-7, 7)
            loc = (2.0, amp, omega, phase, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            t_a, t_b = np.sort(rng.uniform(0.0, 3.0, 2))

            def a_h(t, amp=amp, omega=omega, phase=phase):
                return amp * np.cos(omega * t + phase)

            def a_v(t):
                return 0.0 * t
        elif kind.startswith("ricker"):
            amp = rng.uniform(-6, 6)
            f = 6.0 if kind == "ricker-fast" else rng.uniform(0.5, 3.0)
            t0 = 1.5 / f
            loc = (3.0, amp, f, t0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            t_a = rng.uniform(0.0, t0)
            t_b = rng.uniform(t_a, 2.0 * t0)

            def a_h(t, amp=amp, f=f, t0=t0):
                x = (np.pi * f * (t - t0)) ** 2
                return amp * (1.0 - 2.0 * x) * np.exp(-x)

            def a_v(t):
                return 0.0 * t
        else:
            a0, slope, v0, vslope, tl = rng.uniform(-4, 4), rng.uniform(-80, 80), rng.uniform(-3, 3), rng.uniform(-60, 60), rng.uniform(0, 2)
            t_a = tl + rng.uniform(0.0, 0.01)
            t_b = t_a + rng.uniform(0.0, 0.02)
            loc = (1.0, a0, slope, tl, 0.0, 1.0, v0, vslope, tl, 0.0)

            def a_h(t, a0=a0, slope=slope, tl=tl):
                return a0 + slope * (t - tl)

            def a_v(t, v0=v0, vslope=vslope, tl=tl):
                return v0 + vslope * (t - tl)
        mu = rng.uniform(0.02, 0.6)
        p = list(base)
        p[MU_TOP] = mu
        p = tuple(p)

        def excess(t):
            return np.abs(a_h(t)) - mu * (G + a_v(t))

        grid = np.linspace(t_a, t_b, 20_001)
        ex = excess(grid)
        if np.any(G + a_v(grid) <= 0.0):
            continue  # (a floor falling faster than g: the statue flies, another check)
        got = _first_failure(p, y, loc, t_a, t_b, 1)
        level = 1e-12 * (abs(a_h(t_a)) + mu * G + 1.0)
        bad = np.nonzero(ex > 0.0)[0]
        if np.isnan(got):
            assert bad.size == 0
            continue
        found += 1
        assert t_a <= got <= t_b
        assert np.all(ex[grid < got] <= level)
        assert got == t_a or excess(min(got + 1e-12, t_b)) > -level
        if bad.size:
            assert got <= grid[bad[0]]
    assert found >= 40


def test_violation_intervals_agree_with_the_first_times_in_the_summary():
    st = rk.Statue(width=0.4, height=2.0, mass=50.0, friction=rk.Friction(static=0.2, kinetic=0.2))
    ped = rk.Pedestal(mass=5.0, friction=rk.Friction(static=0.6, kinetic=0.5), width=0.5, height=0.8)
    r = rk.simulate(rk.System(statue=st, pedestal=ped), rk.Harmonic(amplitude=6.0, frequency=1.0, cycles=4),
                    options=rk.Options(gravity=G, save_dt=1e-3))
    found = {name for name, _, _ in r.violations()}
    assert {"statue slips on the pedestal", "pedestal uplift"} <= found
    first_slip = min(t0 for name, t0, _ in r.violations() if name == "statue slips on the pedestal")
    from rocking.solver import compiled as C
    # The solver checks at its steps and stages, the intervals use the 1 ms samples.
    assert first_slip == pytest.approx(r.raw_summary[C.S_TOP_SLIP], abs=0.05)
    forces = r.contact_forces()
    # Vertical balance of the whole stack at rest instants: N = M g.
    rest = r.regime == Regime.REST
    if rest.any():
        np.testing.assert_allclose(forces["N"][rest], 55.0 * G, rtol=1e-12)


@pytest.mark.parametrize("restitution", [None, 0.6, 0.85])
def test_an_impact_whose_floor_impulse_leaves_the_pedestals_base_is_warned(restitution):
    """``Response.impact_uplifts``: on a pedestal that cannot slide (μs = 5), every impact of the
    statue has θ̇⁺ = r·θ̇⁻ and Δu̇ = 0, so the floor's impulse acts at

        |x| = (1 − r)·(I_c + m2·h·(H1 + h)) / (m2·b·(1 + r))

    from the pedestal's base centre, whatever the speed (the statue's change of angular momentum
    about that centre over its normal impulse; I_c = m2·(b² + h²)/3, b, h half the statue's width
    and height). With the pedestal's half width 1 % below |x| every impact is flagged and warned;
    1 % above it none is. The report's check of the pedestal (its forces) still passes, and names
    the impacts."""
    from rocking.report.content import build_content

    width, height, mass, h1, m1 = 0.3, 1.2, 100.0, 0.8, 300.0
    st = rk.Statue(width=width, height=height, mass=mass, restitution=restitution)
    r = st.restitution if restitution is not None else 1.0 - 1.5 * math.sin(st.slenderness) ** 2
    b, h = width / 2, height / 2
    i_c = mass * (b * b + h * h) / 3.0
    x = (1.0 - r) * (i_c + mass * h * (h1 + h)) / (mass * b * (1.0 + r))
    motion = rk.Harmonic(amplitude=3.0, frequency=1.5, cycles=3)
    for factor, flagged in ((0.99, True), (1.01, False)):
        ped = rk.Pedestal(mass=m1, friction=rk.Friction(static=5.0, kinetic=5.0), width=2 * factor * x, height=h1)
        resp = rk.simulate(rk.System(statue=st, pedestal=ped), motion, options=OPTS)
        impacts = resp.event_table[resp.event_table[:, 1] == 1]
        assert len(impacts) >= 3 and np.all(impacts[:, 4] == 0.0) and np.all(impacts[:, 5] == 0.0)
        np.testing.assert_allclose(impacts[:, 7], r * impacts[:, 6], rtol=1e-12)
        lifts = resp.impact_uplifts()
        warned = [w for w in resp.warnings if "a corner of the pedestal would lift" in w]
        check = [c for c in build_content(resp).checks if c.name.startswith("pedestal stays flat")][0]
        assert check.result == "pass"  # the forces stay within the base; the impulses are warned
        if flagged:
            np.testing.assert_array_equal(lifts, impacts[:, 0])
            assert warned and f"at {len(impacts)} impact(s)" in warned[0]
            assert f"at {len(impacts)} impact(s)" in check.value
        else:
            assert lifts.size == 0 and not warned and check.value == "within its base"


def test_the_impacts_the_two_body_model_flags_are_where_the_stack_engine_lifts_the_pedestal():
    """A statue (0.18 × 1.91 m, r = 0.87) on a pedestal 1.36 m wide and 0.95 m tall under
    L'Aquila AQV at a PGA of 4.0 m/s²: its first impact that the two-body model flags (the floor's
    impulse outside the pedestal's base) is where the stack engine, which lets the pedestal rock,
    lifts it (1e-7 rad for 0.7 µs), to 1e-9 s. (In a scan of 1548 random statues on pedestals
    under the bundled records, both engines flag 273 runs, 270 of them first at the same instant to
    1e-6 s; neither flags 1266; in 5 only the two-body model does, where the stack engine's impact
    keeps the pedestal flat, and in 4 only the stack engine.)"""
    from rocking.io.records import read_record
    from rocking.stack import Block, Interface, Stack, simulate_stack

    friction = rk.Friction(static=0.38486186788789445, kinetic=0.3508857752581768)
    pw, ph, pm = 1.363630070433226, 0.9462049050888628, 1348.5504701497894
    sw, sh, sm, r = 0.1764062155299424, 1.907309839471273, 139.04551683127016, 0.872720747581669
    motion = read_record("LAquila2009_AQV_HNE_ESM").trimmed(20.0).scaled(pga=4.014687574543548)
    system = rk.System(statue=rk.Statue(width=sw, height=sh, mass=sm, restitution=r),
                       pedestal=rk.Pedestal(mass=pm, friction=friction, width=pw, height=ph))
    two = rk.simulate(system, motion)
    stack = Stack(blocks=(Block(width=pw, height=ph, mass=pm), Block(width=sw, height=sh, mass=sm)),
                  interfaces=(Interface(friction=friction), Interface(restitution=r)))
    general = simulate_stack(stack, motion).summary()["blocks"][0]
    lifts = two.impact_uplifts()
    assert lifts.size > 10 and two.summary()["pedestal_uplift_time"] is None
    assert lifts[0] == pytest.approx(general["first_rocking_time"], abs=1e-9)
    assert general["peak_rotation"] < 1e-5
