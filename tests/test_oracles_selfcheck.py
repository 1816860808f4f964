"""Self-check of the independent oracles (tests/oracles) against the numbers tabulated in
shared/design/oracles.md and shared/design/derivation.md, plus internal consistency checks of the
sympy derivation.  Nothing here imports ``rocking``.

Tolerances: a tabulated number printed with d decimals is asserted to within 0.51e-d (half a unit
in its last printed digit, with a hair of slack for ties).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles import closed_forms as cf  # noqa: E402
from oracles import lagrange as lg  # noqa: E402

G = 9.81
OMEGA_SEED = 2 * math.pi * 1.2  # P13: pin omega = 2 pi f, f = 1.2 Hz
A_SEED = 6.75


def assert_table(value: float, printed: str) -> None:
    """|value - printed| <= half a unit of the printed number's last digit."""
    dec = len(printed.split(".")[1]) if "." in printed else 0
    tol = 0.51 * 10.0 ** (-dec) + 1e-15
    assert abs(value - float(printed)) <= tol, f"{value!r} vs tabulated {printed} (tol {tol:g})"


# ------------------------------------------------------------------------------------------------
# O2
# ------------------------------------------------------------------------------------------------
O2_TABLE = [
    # H, R, alpha, tan a, g tan a, p, eta, eta^2
    (2, "1.11803", "0.463648", "0.5000", "4.9050", "2.56530", "0.700000", "0.490000"),
    (3, "1.58114", "0.321751", "0.3333", "3.2700", "2.15715", "0.850000", "0.722500"),
    (4, "2.06155", "0.244979", "0.2500", "2.4525", "1.88916", "0.911765", "0.831315"),
    (5, "2.54951", "0.197396", "0.2000", "1.9620", "1.69878", "0.942308", "0.887944"),
]


@pytest.mark.parametrize("row", O2_TABLE, ids=lambda r: f"H={r[0]}")
def test_o2_block_constants(row):
    H, *printed = row
    c = cf.block_constants(0.5, H / 2)
    for v, p in zip((c.R, c.alpha, c.tan_alpha, c.g_tan_alpha, c.p, c.eta, c.eta2), printed):
        assert_table(v, p)
    assert c.I_O(2.0) == pytest.approx(2.0 * 4 / 3 * c.R ** 2, rel=1e-14)
    assert c.eta == pytest.approx(cf.housner_eta(0.5, H / 2), rel=1e-14)
    # eta from angular momentum about the new corner: (I_O - 2 m b^2)/I_O
    assert c.eta == pytest.approx((c.I_O_per_mass - 2 * 0.25) / c.I_O_per_mass, rel=1e-14)
    assert cf.rocking_onset_acceleration(0.5, H / 2) == pytest.approx(c.g_tan_alpha, rel=1e-14)


# ------------------------------------------------------------------------------------------------
# O3, O4
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("frac, lin, exact", [
    (0.1, "0.1748513906", "0.1755894159"),
    (0.5, "0.4929342447", "0.4938032151"),
    (0.9, "1.1203562743", "1.1208643787"),
])
def test_o3_free_rocking_t1(frac, lin, exact):
    c = cf.block_constants(0.25, 1.0)
    assert_table(c.p, "2.671671")
    assert_table(c.eta, "0.911765")
    assert_table(cf.free_rocking_t1_linearised(0.25, 1.0, frac * c.alpha), lin)
    assert_table(cf.free_rocking_t1_exact(0.25, 1.0, frac * c.alpha), exact)


def test_o3_quadrature_against_ode():
    """The quadrature agrees with a direct integration of the nonlinear Housner equation."""
    c = cf.block_constants(0.25, 1.0)
    th0 = 0.5 * c.alpha
    ev = lambda t, y: y[0]
    ev.terminal, ev.direction = True, -1
    sol = solve_ivp(lambda t, y: [y[1], -c.p ** 2 * math.sin(c.alpha - y[0])], (0, 5), [th0, 0.0],
                    events=ev, rtol=1e-12, atol=1e-14, method="DOP853")
    assert sol.t_events[0][0] == pytest.approx(cf.free_rocking_t1_exact(0.25, 1.0, th0), abs=1e-9)
    assert -sol.y_events[0][0][1] == pytest.approx(cf.free_rocking_impact_velocity(0.25, 1.0, th0), rel=1e-9)


def test_o4_amplitude_sequences():
    c = cf.block_constants(0.25, 1.0)
    ex = cf.amplitude_sequence_exact(c.alpha, c.eta, c.alpha / 2, 6) / c.alpha
    li = cf.amplitude_sequence_linearised(c.alpha, c.eta, c.alpha / 2, 6) / c.alpha
    for v, p in zip(ex, "0.38671447 0.30639688 0.24605747 0.19931405 0.16241485 0.13291840".split()):
        assert_table(v, p)
    for v, p in zip(li, "0.38639276 0.30596349 0.24560062 0.19887471 0.16201166 0.13255850".split()):
        assert_table(v, p)


# ------------------------------------------------------------------------------------------------
# O6, O7, O8, O9, O9b
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("b, h, ex, lin", [
    (0.25, 1.0, "0.924895", "0.899527"),
    (0.5, 2.0, "1.307999", "1.272124"),
    (0.5, 1.0, "1.964615", "1.773044"),
])
def test_o6_vcrit(b, h, ex, lin):
    assert_table(cf.vcrit_exact(b, h), ex)
    assert_table(cf.vcrit_linearised(b, h), lin)
    # energy check of the definition: (1/2) I_O w0^2 = m g R (1 - cos a), I_O w0 = m V h
    c = cf.block_constants(b, h)
    w0 = cf.vcrit_exact(b, h) * h / c.I_O_per_mass
    assert 0.5 * c.I_O_per_mass * w0 ** 2 == pytest.approx(G * c.R * (1 - math.cos(c.alpha)), rel=1e-13)


def test_o7_double_impulse():
    assert_table(cf.vcrit_double(0.25, 1.0), "0.483791")


@pytest.mark.parametrize("ptd, printed", [(0.5, "2.541494"), (1.0, "1.581977"), (2.0, "1.156518"), (4.0, "1.018657")])
def test_o8_rect_pulse(ptd, printed):
    assert_table(cf.rect_pulse_threshold(ptd), printed)


def test_o8_short_pulse_limit():
    c = cf.block_constants(0.25, 1.0)
    td = 1e-7
    a = cf.rect_pulse_threshold(c.p * td) * G * c.alpha
    assert a * td == pytest.approx(cf.vcrit_linearised(0.25, 1.0), rel=1e-6)


@pytest.mark.parametrize("beta, printed", [
    (0.5, "1.118050"), (1, "1.418315"), (2, "2.349903"), (3, "3.631150"),
    (4, "5.238964"), (6, "9.416966"), (8, "14.871352"),
])
def test_o9_one_sine(beta, printed):
    assert_table(cf.one_sine_threshold(beta), printed)
    psi = cf.one_sine_psi(beta)
    assert 0 < psi < math.atan(1 / beta)
    assert (math.cos(psi) - beta * math.sin(psi)) * math.exp((2 * math.pi - psi) / beta) == pytest.approx(1, abs=1e-12)


def test_o9_one_sine_linear_ode():
    """Mode-1 threshold re-derived by integrating the linearised equation phi'' = p^2 (phi - 1 +
    A sin(w t + psi)) (phi = -theta/alpha for a +x pulse): at threshold the block ends the pulse
    exactly on the separatrix phi_dot/p = 1 - phi."""
    beta = 2.0
    psi = cf.one_sine_psi(beta)
    A = 1 / math.sin(psi)
    sol = solve_ivp(lambda t, y: [y[1], y[0] - 1 + A * math.sin(beta * t + psi)],
                    (0, (2 * math.pi - psi) / beta), [0.0, 0.0], rtol=1e-12, atol=1e-14, method="DOP853")
    phi, phid = sol.y[:, -1]
    assert phid == pytest.approx(1 - phi, abs=1e-9)


@pytest.mark.parametrize("beta, printed", [(0.5, "1.250004"), (1, "2.003742"), (2, "5.225829"), (4, "21.461383")])
def test_o9b_one_cosine(beta, printed):
    assert_table(cf.one_cosine_threshold(beta), printed)


# ------------------------------------------------------------------------------------------------
# O11
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("beta, eta, printed", [(2, 0.9, "0.112907"), (4, 0.9, "0.124556"), (2, 0.8, "0.236428")])
def test_o11_amin(beta, eta, printed):
    a = cf.harmonic_11_amin(beta, eta)
    assert_table(a, printed)
    assert cf.harmonic_11_orbits(beta, eta, a * (1 - 1e-9)) == []
    assert len(cf.harmonic_11_orbits(beta, eta, a * (1 + 1e-6))) == 2


def test_o11_example_and_periodicity():
    beta, eta, A = 2.0, 0.9, 0.5
    orbits = cf.harmonic_11_orbits(beta, eta, A)
    assert len(orbits) == 2
    (t1, v1), (t2, v2) = orbits
    assert_table(t1, "3.30044869")
    assert_table(v1, "0.43419072")
    assert_table(t2, "5.98648601")
    assert_table(v2, "0.80247367")
    # linearised equation in phi = theta/alpha (theta > 0 side), tau = p t:
    # phi'' = phi - 1 - A sin(beta tau + tau0); half a forcing period returns phi = 0 with
    # phi' = -phi'(0+)/eta, which the impact maps to the mirror image of the start.
    for tau0, v0 in orbits:
        sol = solve_ivp(lambda t, y: [y[1], y[0] - 1 - A * math.sin(beta * t + tau0)],
                        (0, math.pi / beta), [0.0, v0], rtol=1e-13, atol=1e-15, method="DOP853")
        assert sol.y[0, -1] == pytest.approx(0.0, abs=1e-10)
        assert sol.y[1, -1] == pytest.approx(-v0 / eta, abs=1e-10)


# ------------------------------------------------------------------------------------------------
# O12, O13, O14
# ------------------------------------------------------------------------------------------------
def test_o12_newmark():
    assert_table(0.5 * G * 0.5, "2.4525")
    assert_table(cf.newmark_rect_pulse(0.5, 0.2, 0.5), "0.919687")  # exact value 0.9196875
    assert_table(cf.newmark_rect_pulse(1.0, 0.1, 0.2), "1.765800")


def test_o13_half_sine():
    r = cf.half_sine_sliding(0.5 * G, 0.2, 0.5)
    assert_table(r.t1, "0.065495")
    assert_table(r.t2, "0.828052")
    assert_table(r.u, "0.280945")
    r2 = cf.half_sine_sliding(0.4 * G, 0.1, 1.0)
    assert_table(r2.u, "2.031287")


def test_o13_against_ode():
    """Integrate the sliding equation u'' = -a_g + mu g (slipping backwards) from t1 to the stop."""
    Ap, mu, Tp = 0.5 * G, 0.2, 0.5
    r = cf.half_sine_sliding(Ap, mu, Tp)
    ag = lambda t: Ap * math.sin(math.pi * t / Tp) if t <= Tp else 0.0
    ev = lambda t, y: y[1]
    ev.terminal, ev.direction = True, 1
    rhs = lambda t, y: [y[1], -ag(t) + mu * G]
    s1 = solve_ivp(rhs, (r.t1, Tp), [0.0, 0.0], rtol=1e-12, atol=1e-14, method="DOP853")
    s2 = solve_ivp(rhs, (Tp, 5.0), s1.y[:, -1], events=ev, rtol=1e-12, atol=1e-14, method="DOP853")
    assert s2.t_events[0][0] == pytest.approx(r.t2, abs=1e-9)
    assert -s2.y_events[0][0][0] == pytest.approx(r.u, rel=1e-9)


def test_o14_harmonic_sliding():
    mu = 0.3
    assert_table(cf.harmonic_nonstop_threshold(mu) / (mu * G), "1.86210")
    assert cf.harmonic_nonstop_threshold(mu) == pytest.approx(mu * G * math.sqrt(1 + math.pi ** 2 / 4), rel=1e-14)
    assert_table(cf.harmonic_sliding_peak_to_peak(A_SEED, OMEGA_SEED, 0.3), "0.173038")


# ------------------------------------------------------------------------------------------------
# O15, O17, P17
# ------------------------------------------------------------------------------------------------
O15_TABLE = [
    (0.2, ["0.2000", "0.2246", "0.2486", "0.3793", "1.9333"]),
    (0.25, ["0.2500", "0.2806", "0.3099", "0.4156", "1.6667"]),
    (1 / 3, ["0.3333", "0.3735", "0.4109", "0.4783", "1.4444"]),
    (0.5, ["0.5000", "0.5581", "0.6087", "0.6087", "1.3333"]),
]


@pytest.mark.parametrize("bh, printed", O15_TABLE)
def test_o15_mu_req(bh, printed):
    h = 1.0
    b = bh * h
    for lam, p in zip((bh, 1.5 * bh, 2 * bh, 1.0, math.inf), printed):
        assert_table(cf.shenton_mu_req(b, h, lam), p)
    assert cf.shenton_mu_req(b, h, 1e12) == pytest.approx(cf.shenton_mu_req(b, h, math.inf), rel=1e-9)


def test_o15_mu_req_matches_sympy_stick_rock():
    """mu_req is |F|/N of a single block (m1 = 0) that starts rocking on a stuck base."""
    for b, h, lam in [(0.25, 1.0, 0.4), (0.5, 1.5, 1.2), (0.2, 1.0, 3.0)]:
        P = dict(b=b, h=h, m1=0.0, m2=2.0, g=G, mu_s=10.0, mu_k=0.3)
        udd, thdd, N, F, *_ = lg.accelerations("stick-rock", P, (0, 0, 0, 0), lam * G, s=-1)
        assert abs(F) / N == pytest.approx(cf.shenton_mu_req(b, h, lam), rel=1e-12)


def test_o15_regimes():
    b, h = 0.25, 1.0  # b/h = 0.25
    assert cf.shenton_regime(b, h, 0.2, 0.15) == "rest"
    assert cf.shenton_regime(b, h, 0.2, 0.3) == "slide"
    assert cf.shenton_regime(b, h, 0.5, 0.2) == "rest"
    assert cf.shenton_regime(b, h, 0.5, 1.0) == "rock"  # mu_req(1) = 0.4156
    assert cf.shenton_regime(b, h, 0.4, 1.0) == "slide-rock"
    assert cf.shenton_regime(b, h, 0.26, 0.4) == "slide-rock"  # mu_req(0.4) > 0.26 > b/h


def test_o15_regime_edge():
    b, h = 0.25, 1.0
    assert cf.shenton_mu_req(b, h, 0.3) < 0.3
    assert cf.shenton_regime(b, h, 0.3, 0.3) == "rock"


def test_o15_regimes_agree_with_sympy_mode_selection():
    """shenton_regime == lagrange.select_regime for a single block (m1 = 0) over a grid."""
    names = {"stick-rest": "rest", "stick-rock": "rock", "slide-rest": "slide", "slide-rock": "slide-rock"}
    for bh in (0.2, 0.25, 0.5):
        for mus in (0.15, 0.3, 0.45, 0.7):
            for muk in (mus, 0.8 * mus):
                for lam in (0.1, 0.22, 0.35, 0.6, 1.0, 2.5):
                    P = dict(b=bh, h=1.0, m1=0.0, m2=1.0, g=G, mu_s=mus, mu_k=muk)
                    reg = names[lg.select_regime(P, lam * G)[0]]
                    assert reg == cf.shenton_regime(bh, 1.0, mus, lam, mu_k=muk), (bh, mus, muk, lam)


def test_p17_statue_alone_at_t0():
    lam = A_SEED / G
    for H, p in [(3, "0.4155"), (4, "0.3517"), (5, "0.3140")]:
        assert_table(cf.shenton_mu_req(0.5, H / 2, lam), p)
    # with mu_k = mu_s = 0.4 (the O15 rule) ...
    assert [cf.shenton_regime(0.5, H / 2, 0.4, lam) for H in (2, 3, 4, 5)] == ["slide", "slide-rock", "rock", "rock"]
    # ... but with the paper's mu_k = 0.3 < tan(alpha) = 1/3, H = 3 starts in plain sliding
    assert [cf.shenton_regime(0.5, H / 2, 0.4, lam, mu_k=0.3) for H in (2, 3, 4, 5)] == ["slide", "slide", "rock", "rock"]


def test_o17_never_rocks():
    assert cf.statue_never_rocks(0.5, 1.0, 0.4, 0.3)  # 9a
    assert not cf.statue_never_rocks(0.5, 1.5, 0.4, 0.3)  # 9b: tan a = 1/3 < mu_s


# ------------------------------------------------------------------------------------------------
# O18, O19
# ------------------------------------------------------------------------------------------------
O18_TABLE = [
    # b, h, m1, m2, t1, thetadot, u, udot, eta_stack, eta
    (0.5, 2.0, 1, 1, "0.55652972", "-0.49670213", "0.12405637", "0.49670213", "0.86363636", "0.91176471"),
    (0.5, 2.0, 1, 4, "0.45049012", "-0.60558694", "0.19849020", "0.96893911", "0.79729730", "0.91176471"),
    (0.5, 1.0, 1, 1, "0.41974610", "-1.21738173", "0.12156421", "0.60869087", "0.57142857", "0.70000000"),
]


@pytest.mark.parametrize("row", O18_TABLE, ids=lambda r: f"h={r[1]},m2={r[3]}")
def test_o18_closed_form(row):
    b, h, m1, m2, *printed = row
    r = cf.frictionless_release(b, h, m1, m2, math.atan2(b, h) / 2)
    for v, p in zip((r.t1, r.theta_dot, r.u, r.u_dot, r.eta_stack, r.eta_housner), printed):
        assert_table(v, p)


@pytest.mark.parametrize("row", O18_TABLE, ids=lambda r: f"h={r[1]},m2={r[3]}")
def test_o18_sympy_ode_and_impact(row):
    """Integrate the sympy slide-rock equations with mu_k = 0 and apply the sympy impact map."""
    b, h, m1, m2, *_ = row
    P = dict(b=b, h=h, m1=m1, m2=m2, g=G, mu_s=0.0, mu_k=0.0)
    th0 = math.atan2(b, h) / 2

    def rhs(t, y):
        udd, thdd, *_ = lg.accelerations("slide-rock", P, y, 0.0, s=1, sigma=1)
        return [y[1], udd, y[3], thdd]

    ev = lambda t, y: y[2]
    ev.terminal, ev.direction = True, -1
    sol = solve_ivp(rhs, (0, 3), [0.0, 0.0, th0, 0.0], events=ev, rtol=1e-11, atol=1e-13, method="DOP853")
    ref = cf.frictionless_release(b, h, m1, m2, th0)
    u, ud, th, thd = sol.y_events[0][0]
    assert sol.t_events[0][0] == pytest.approx(ref.t1, abs=1e-8)
    assert (u, ud, thd) == pytest.approx((ref.u, ref.u_dot, ref.theta_dot), abs=1e-8)
    # energy conserved along the way (frictionless, no base motion)
    E = [lg.energy(P, y, s=1) for y in sol.y.T]
    assert np.ptp(E) < 1e-9 * abs(E[0])
    imp = lg.impact_coulomb(P, (u, ud, 0.0, thd), s_before=1)
    assert imp.theta_dot / thd == pytest.approx(ref.eta_stack, rel=1e-12)
    assert imp.Fx == pytest.approx(0.0, abs=1e-14)
    M = m1 + m2
    assert M * imp.u_dot + m2 * h * imp.theta_dot == pytest.approx(M * ud + m2 * h * thd, rel=1e-12)


O19_MU = [(2, "0.3529", "0.2222"), (3, "0.2432", "0.3333"), (4, "0.1846", "0.4444"), (5, "0.1485", "0.5556")]


@pytest.mark.parametrize("H, housner, r08", O19_MU)
def test_o19_friction_needed(H, housner, r08):
    b, h = 0.5, H / 2
    assert_table(cf.impact_friction_needed(b, h), housner)
    assert_table(cf.impact_friction_needed(b, h, 0.8), r08)
    a = math.atan2(b, h)
    assert cf.impact_friction_needed(b, h) == pytest.approx(
        1.5 * math.sin(a) * math.cos(a) / (2 - 1.5 * math.sin(a) ** 2), rel=1e-13)
    # the sympy impact map with the pedestal held: theta_dot+ = eta theta_dot-, |Fx|/Fy as above
    for s_before, thd in ((1, -0.7), (-1, 0.7)):
        P = dict(b=b, h=h, m1=1.0, m2=1.0, g=G, mu_s=10.0, mu_k=10.0)
        imp = lg.impact_coulomb(P, (0.0, 0.0, 0.0, thd), s_before=s_before)
        assert imp.mode == "stick" and imp.consistent
        assert imp.theta_dot == pytest.approx(cf.housner_eta(b, h) * thd, rel=1e-13)
        assert abs(imp.Fx) / imp.Fy == pytest.approx(cf.impact_friction_needed(b, h), rel=1e-12)
        # statue-pedestal interface needs the same ratio (O19)
        assert abs(imp.Lx) / imp.Ly == pytest.approx(cf.impact_friction_needed(b, h), rel=1e-12)
        imp8 = lg.impact_coulomb(P, (0.0, 0.0, 0.0, thd), s_before=s_before, r=0.8)
        assert imp8.theta_dot == pytest.approx(0.8 * thd, rel=1e-13)
        assert abs(imp8.Fx) / imp8.Fy == pytest.approx(cf.impact_friction_needed(b, h, 0.8), rel=1e-12)
        pap = lg.impact_paper(P, (0.0, 0.0, 0.0, thd), s_before=s_before, r=0.8)
        assert (pap.u_dot, pap.theta_dot, pap.Fx, pap.Fy) == pytest.approx(
            (0.0, imp8.theta_dot, imp8.Fx, imp8.Fy), rel=1e-12, abs=1e-15)


def test_o19_paper_rule_inconsistent_for_slender_statues():
    """With r = 0.8 and mu_s = 0.4 the held-pedestal impact needs 0.444 (H = 4): Coulomb slips."""
    for H, mode in ((3, "stick"), (4, "slide"), (5, "slide")):
        P = dict(b=0.5, h=H / 2, m1=1.0, m2=1.0, g=G, mu_s=0.4, mu_k=0.3)
        imp = lg.impact_coulomb(P, (0.0, 0.0, 0.0, -0.5), s_before=1, r=0.8)
        assert imp.mode == mode
        if mode == "slide":
            assert abs(imp.Fx) == pytest.approx(0.3 * imp.Fy, rel=1e-12)
            assert np.sign(imp.u_dot) == -np.sign(imp.Fx)


@pytest.mark.parametrize("H, values", [(4, ["0.8636", "0.8333", "0.7973", "0.7766"]),
                                       (2, ["0.5714", "0.5000", "0.4231", "0.3824"])])
def test_o19_eta_stack_table(H, values):
    for m2, p in zip((1, 2, 4, 6), values):
        assert_table(cf.eta_stack_frictionless(0.5, H / 2, 1.0, m2), p)
        P = dict(b=0.5, h=H / 2, m1=1.0, m2=m2, g=G, mu_s=0.0, mu_k=0.0)
        imp = lg.impact_coulomb(P, (0.0, 0.0, 0.0, -1.0), s_before=1)
        assert imp.theta_dot / -1.0 == pytest.approx(cf.eta_stack_frictionless(0.5, H / 2, 1.0, m2), rel=1e-12)
        assert imp.theta_dot / -1.0 < cf.housner_eta(0.5, H / 2)


def test_o20_rocking_frame():
    for gam, pr, er in [(0, "1", "0.911765"), (0.5, "0.894427", "0.894118"),
                        (1, "0.866025", "0.889706"), (2, "0.845154", "0.886555")]:
        p, e = cf.rocking_frame(0.25, 1.0, gam)
        assert_table(p, pr if "." in pr else pr + ".000000")
        assert_table(e, er)


# ------------------------------------------------------------------------------------------------
# Seed cases 9a / 9b (derivation.md "What a test may assert", items 1-2) and t = 0+ regimes
# ------------------------------------------------------------------------------------------------
def test_seed_9a_9b_event_times():
    x = cf.seed_first_stop_phase(A_SEED, 0.3)
    assert_table(x, "2.04279805")
    assert_table(x / OMEGA_SEED, "0.27093451")
    assert_table(abs(A_SEED * math.cos(x)), "3.069")
    assert abs(A_SEED * math.cos(x)) < 0.4 * G  # sticks at the first stop
    y = cf.seed_reslip_phase(A_SEED, 0.4)
    assert_table(y, "2.19116274")
    assert_table(y / OMEGA_SEED, "0.29061198")
    z = cf.seed_rock_onset_phase(A_SEED, 0.5, 1.5)
    assert_table(z, "2.07652433")
    assert_table(z / OMEGA_SEED, "0.27540759")
    assert x < z < y  # 9b: rocking starts before the pedestal slips again


def test_seed_9a_first_stop_by_sympy_integration():
    """Integrate the sympy slide-rest equation (sigma = -1) under A cos(w t) to the first stop."""
    P = dict(b=0.5, h=1.0, m1=1.0, m2=1.0, g=G, mu_s=0.4, mu_k=0.3)
    rhs = lambda t, y: [y[1], lg.accelerations("slide-rest", P, (y[0], y[1], 0, 0),
                                               A_SEED * math.cos(OMEGA_SEED * t), sigma=-1)[0]]
    ev = lambda t, y: y[1]
    ev.terminal, ev.direction = True, 1
    sol = solve_ivp(rhs, (0, 1), [0.0, 0.0], events=ev, rtol=1e-12, atol=1e-14, method="DOP853",
                    first_step=1e-6)
    assert sol.t_events[0][0] == pytest.approx(0.27093451, abs=1e-8)


CASES = [  # fig, m2, H, regime at t = 0+ (derivation.md "What a test may assert", item 4)
    ("9a", 1, 2, "slide-rest"), ("9b", 1, 3, "slide-rest"), ("10a", 1, 4, "slide-rock"),
    ("10b", 1, 5, "slide-rock"), ("11a", 2, 4, "slide-rock"), ("11b", 3, 4, "slide-rock"),
    ("12a", 4, 4, "slide-rock"), ("12b", 6, 4, "stick-rock"),
]


@pytest.mark.parametrize("fig, m2, H, regime", CASES, ids=[c[0] for c in CASES])
def test_seed_t0_regimes(fig, m2, H, regime):
    P = dict(b=0.5, h=H / 2, m1=1.0, m2=m2, g=G, mu_s=0.4, mu_k=0.3, normal_force="full")
    reg, s, sg = lg.select_regime(P, A_SEED)
    assert reg == regime
    if reg.endswith("rock"):
        assert s == -1  # +x floor acceleration rocks the statue towards -x
    if reg.startswith("slide"):
        assert sg == -1


def test_seed_12b_margin_and_paper_normal_force():
    P = dict(b=0.5, h=2.0, m1=1.0, m2=6.0, g=G, mu_s=0.4, mu_k=0.3)
    _, _, N, F, *_ = lg.accelerations("stick-rock", P, (0, 0, 0, 0), A_SEED, s=-1)
    margin = 0.4 * N / abs(F) - 1
    assert 0.007 < margin < 0.009  # "0.8% margin"
    # with the paper's N = M g the stuck pedestal cannot hold: 12b starts in slide-rock
    assert lg.select_regime(dict(P, normal_force="paper"), A_SEED)[0] == "slide-rock"


def test_worked_check_case_10a():
    """derivation.md 3.5: case 10a at t = 0+."""
    P = dict(b=0.5, h=2.0, m1=1.0, m2=1.0, g=G, mu_s=0.4, mu_k=0.3)
    udd, thdd, N, F, Px, Py = lg.accelerations("stick-rock", P, (0, 0, 0, 0), A_SEED, s=-1)
    assert_table(F, "10.47")
    assert_table(0.4 * N, "8.15")
    assert abs(F) > 0.4 * N  # a stuck pedestal cannot hold a rocking statue
    assert -1 * thdd > 0  # rock consistent on a stuck base
    # pedestal sliding with the statue at rest: base acceleration mu_k g = 2.94 > g tan a = 2.45
    udd_r, _, N_r, F_r, *_ = lg.accelerations("slide-rest", P, (0, 0, 0, 0), A_SEED, sigma=-1)
    assert_table(A_SEED + udd_r, "2.94")
    assert_table(G * 0.25, "2.45")
    assert abs(A_SEED + udd_r) > G * 0.25
    # so slide + rock, consistent: sigma u_ddot > 0 and s theta_ddot > 0
    udd2, thdd2, N2, F2, *_ = lg.accelerations("slide-rock", P, (0, 0, 0, 0), A_SEED, s=-1, sigma=-1)
    assert -udd2 > 0 and -thdd2 > 0
    assert F2 == pytest.approx(0.3 * N2, rel=1e-14)
    assert lg.consistent_regimes(P, A_SEED) == [("slide-rock", -1, -1)]


# ------------------------------------------------------------------------------------------------
# The sympy derivation against the formulas printed in derivation.md 3.2-3.4 (typed here)
# ------------------------------------------------------------------------------------------------
def _derivation_md(regime, P, state, ag, av, s, sigma):
    """derivation.md 3.4 formulas, retyped, for comparison with the sympy result."""
    b, h, m1, m2, g, muk = P["b"], P["h"], P["m1"], P["m2"], P["g"], P["mu_k"]
    M = m1 + m2
    R = math.hypot(b, h)
    a = math.atan2(b, h)
    I_O = m2 * R * R / 3 + m2 * R * R
    u, ud, th, thd = state
    if regime.endswith("rest"):
        th = thd = 0.0
    phi = a - s * th
    c, sn = math.cos(phi), math.sin(phi)
    if regime == "stick-rest":
        udd = thdd = 0.0
    elif regime == "stick-rock":
        udd = 0.0
        thdd = -m2 * R * (c * ag + s * sn * (g + av)) / I_O
    elif regime == "slide-rest":
        thdd = 0.0
        udd = -ag - sigma * muk * (g + av)  # seed Eq. (23), correct (same in both N models)
    else:
        if P.get("normal_force", "full") == "full":
            A = np.array([[M, m2 * R * (c + sigma * muk * s * sn)], [m2 * R * c, I_O]])
            rhs = np.array([-M * ag - s * m2 * R * sn * thd ** 2 - sigma * muk * (M * (g + av) - m2 * R * c * thd ** 2),
                            -m2 * R * (c * ag + s * sn * (g + av))])
            D = M * I_O - m2 ** 2 * R ** 2 * c * (c + sigma * muk * s * sn)
            assert np.linalg.det(A) == pytest.approx(D, rel=1e-12)
        else:  # paper: F = -sigma mu_k M (g + a_v), symmetric mass matrix
            A = np.array([[M, m2 * R * c], [m2 * R * c, I_O]])
            rhs = np.array([-sigma * muk * M * (g + av) - M * ag - s * m2 * R * sn * thd ** 2,
                            -m2 * R * (c * ag + s * sn * (g + av))])
        udd, thdd = np.linalg.solve(A, rhs)
    N = M * (g + av) + m2 * R * (s * sn * thdd - c * thd ** 2)
    if P.get("normal_force") == "paper":
        N = M * (g + av)
    if regime.startswith("stick"):
        F = M * ag + m2 * R * (c * thdd + s * sn * thd ** 2)  # F_req: (u) equation with u_ddot = 0
    else:
        F = -sigma * muk * N
    Px = m2 * (ag + udd + R * c * thdd + s * R * sn * thd ** 2)
    Py = m2 * (g + av + s * R * sn * thdd - R * c * thd ** 2)
    # residual of the (u) equation must vanish
    assert M * (ag + udd) + m2 * R * (c * thdd + s * sn * thd ** 2) == pytest.approx(F, rel=1e-10, abs=1e-10)
    return udd, thdd, N, F, Px, Py


def _random_cases(n, seed=12345):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        b = rng.uniform(0.1, 0.6)
        h = rng.uniform(0.6, 3.0)
        P = dict(b=b, h=h, m1=rng.uniform(0.0, 5.0), m2=rng.uniform(0.2, 6.0), g=G,
                 mu_s=rng.uniform(0.2, 0.6), mu_k=rng.uniform(0.1, 0.5))
        s = int(rng.choice([-1, 1]))
        sigma = int(rng.choice([-1, 1]))
        th = s * rng.uniform(0.0, 0.9) * math.atan2(b, h)
        state = (rng.normal(), sigma * rng.uniform(0.01, 1.0), th, rng.normal())
        yield P, state, rng.normal(0, 5), rng.normal(0, 2), s, sigma


@pytest.mark.parametrize("nf", ["full", "paper"])
@pytest.mark.parametrize("regime", lg.REGIMES)
def test_sympy_matches_derivation_md(regime, nf):
    for P, state, ag, av, s, sigma in _random_cases(40):
        P["normal_force"] = nf
        got = lg.accelerations(regime, P, state, ag, av, s=s, sigma=sigma)
        want = _derivation_md(regime, P, state, ag, av, s, sigma)
        assert got == pytest.approx(want, rel=1e-10, abs=1e-10), (regime, nf, P, state)


def test_single_block_housner_form():
    """derivation.md 3.2: theta_ddot = -p^2 [(1 + a_v/g) sin(s a - theta) + (a_g/g) cos(s a - theta)]
    (mechanics.md prints (a_g/G) with G = g + a_v and no (1 + a_v/g): wrong for a_v != 0)."""
    for P, state, ag, av, s, sigma in _random_cases(30, seed=7):
        c = cf.block_constants(P["b"], P["h"], G)
        th = state[2]
        _, thdd, *_ = lg.accelerations("stick-rock", P, state, ag, av, s=s)
        want = -c.p ** 2 * ((1 + av / G) * math.sin(s * c.alpha - th) + ag / G * math.cos(s * c.alpha - th))
        assert thdd == pytest.approx(want, rel=1e-11, abs=1e-12)
        # contact force of a single block (m1 = 0, stuck): derivation.md 3.2 f_x, f_y
        P1 = dict(P, m1=0.0)
        _, thdd1, N1, F1, Px1, Py1 = lg.accelerations("stick-rock", P1, state, ag, av, s=s)
        phi = c.alpha - s * th
        m, R = P["m2"], c.R
        fx = m * (ag + R * math.cos(phi) * thdd1 + s * R * math.sin(phi) * state[3] ** 2)
        fy = m * (G + av + s * R * math.sin(phi) * thdd1 - R * math.cos(phi) * state[3] ** 2)
        assert (F1, N1, Px1, Py1) == pytest.approx((fx, fy, fx, fy), rel=1e-11, abs=1e-11)


def test_pedestal_center_of_pressure_matches_derivation_md():
    P = dict(b=0.5, h=2.0, m1=1.5, m2=2.0, g=G, mu_s=0.4, mu_k=0.3)
    udd, thdd, N, F, Px, Py = lg.accelerations("slide-rock", P, (0, 0.2, -0.05, 0.3), 3.0, s=-1)
    H1 = 0.4
    xN = lg.pedestal_center_of_pressure(P, H1, -1, Px, Py, N, 3.0 + udd)
    assert xN == pytest.approx((-1 * 0.5 * Py - H1 * Px - H1 / 2 * 1.5 * (3.0 + udd)) / N, rel=1e-13)


def test_painleve_detected():
    # single squat block (m1 = 0), high friction: D = m2^2 R^2 [4/3 - cos(phi)(cos(phi) + mu sin(phi))]
    P = dict(b=1.0, h=1.0, m1=0.0, m2=1.0, g=G, mu_s=2.0, mu_k=2.0)
    with pytest.raises(ValueError, match="Painleve"):
        lg.accelerations("slide-rock", P, (0, 1.0, 0.0, 0.1), 0.0, s=1, sigma=1)


# ------------------------------------------------------------------------------------------------
# Energy balance: d/dt (T + V) = floor inertial power + friction power  (finite differences)
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("nf", ["full", "paper"])
@pytest.mark.parametrize("regime", ["slide-rock", "stick-rock", "slide-rest"])
def test_energy_rate_equals_power(regime, nf):
    dt = 1e-5
    for P, state, ag, av, s, sigma in _random_cases(25, seed=99):
        P["normal_force"] = nf
        u, ud, th, thd = state
        if regime.startswith("stick"):
            ud = 0.0
        if regime.endswith("rest"):
            th = thd = 0.0
        y = np.array([u, ud, th, thd])
        udd, thdd, N, F, Px, Py = lg.accelerations(regime, P, y, ag, av, s=s, sigma=sigma)
        ydot = np.array([ud, udd, thd, thdd])
        dE = (lg.energy(P, y + dt * ydot, s=s) - lg.energy(P, y - dt * ydot, s=s)) / (2 * dt)
        vx, vy = lg.statue_velocity_rel(P, y, s=s)
        M = P["m1"] + P["m2"]
        power = -ag * (P["m1"] * ud + P["m2"] * vx) - av * P["m2"] * vy + F * ud
        scale = abs(power) + abs(F * ud) + abs(ag * M * ud) + 1.0
        assert dE == pytest.approx(power, abs=1e-7 * scale), (regime, P, y)


def test_energy_function_closed_form():
    P = dict(b=0.5, h=2.0, m1=1.0, m2=1.0, g=G)
    R, a = math.hypot(0.5, 2.0), math.atan2(0.5, 2.0)
    u, ud, th, thd = 0.1, 0.3, -0.05, 0.7
    phi = a + th  # s = -1
    T = 0.5 * 2 * ud ** 2 + 0.5 * (4 / 3) * R * R * thd ** 2 + R * math.cos(phi) * ud * thd
    assert lg.energy(P, (u, ud, th, thd)) == pytest.approx(T + G * R * math.cos(phi), rel=1e-13)
    # continuous across the pivot switch
    assert lg.energy(P, (0, ud, 0.0, thd), s=1) == pytest.approx(lg.energy(P, (0, ud, 0.0, thd), s=-1), rel=1e-14)


# ------------------------------------------------------------------------------------------------
# Impact map: derivation.md 3.6 equations (typed) hold for the sympy-derived map
# ------------------------------------------------------------------------------------------------
def test_impact_coulomb_satisfies_derivation_md_equations():
    rng = np.random.default_rng(2024)
    n_slide = n_stick = 0
    for _ in range(200):
        b, h = rng.uniform(0.1, 0.6), rng.uniform(0.6, 3.0)
        m1, m2 = rng.uniform(0.0, 4.0), rng.uniform(0.2, 6.0)
        mus = rng.uniform(0.05, 0.6)
        P = dict(b=b, h=h, m1=m1, m2=m2, g=G, mu_s=mus, mu_k=mus * rng.uniform(0.5, 1.0))
        s_b = int(rng.choice([-1, 1]))
        thm = -s_b * rng.uniform(0.05, 1.0)
        Vm = rng.normal(0, 0.2)
        r = None if rng.uniform() < 0.5 else rng.uniform(0.5, 1.0)
        try:
            imp = lg.impact_coulomb(P, (0.0, Vm, 0.0, thm), s_before=s_b, r=r)
        except ValueError:
            continue
        M = m1 + m2
        I_O = 4 / 3 * m2 * (b * b + h * h)
        coef = (I_O - 2 * m2 * b * b) if r is None else r * I_O
        Vp, thp = imp.u_dot, imp.theta_dot
        # 1. statue angular momentum about the new pivot (the same form for both pivots)
        assert I_O * thp + m2 * h * Vp == pytest.approx(coef * thm + m2 * h * Vm, rel=1e-10, abs=1e-12)
        # 2. horizontal momentum
        assert M * Vp + m2 * h * thp == pytest.approx(M * Vm + m2 * h * thm + imp.Fx, rel=1e-10, abs=1e-12)
        # 3. vertical impulse
        if imp.consistent:
            assert imp.Fy == pytest.approx(m2 * b * (abs(thp) + abs(thm)), rel=1e-10)
        # 6. statue impulse
        assert imp.Lx == pytest.approx(m2 * (Vp - Vm + h * (thp - thm)), rel=1e-10, abs=1e-12)
        # 4. Coulomb
        if imp.mode == "stick":
            n_stick += 1
            assert Vp == 0.0 and abs(imp.Fx) <= mus * imp.Fy
        else:
            n_slide += 1
            assert abs(imp.Fx) == pytest.approx(P["mu_k"] * imp.Fy, rel=1e-12)
            assert np.sign(imp.Fx) == -np.sign(Vp)
        # the impact never creates kinetic energy (relative to the floor)
        if imp.consistent:
            E0 = lg.energy(P, (0, Vm, 0.0, thm), s=s_b)
            E1 = lg.energy(P, (0, Vp, 0.0, thp), s=-s_b)
            assert E1 <= E0 + 1e-12
    assert n_slide > 20 and n_stick > 20


def test_impact_mirror_symmetry():
    P = dict(b=0.4, h=1.7, m1=1.3, m2=2.1, g=G, mu_s=0.3, mu_k=0.25)
    for Vm in (-0.3, 0.0, 0.2):
        a = lg.impact_coulomb(P, (0, Vm, 0.0, -0.8), s_before=1)
        m = lg.impact_coulomb(P, (0, -Vm, 0.0, 0.8), s_before=-1)
        assert (m.u_dot, m.theta_dot, m.Fx, m.Fy) == pytest.approx((-a.u_dot, -a.theta_dot, -a.Fx, a.Fy), rel=1e-12, abs=1e-15)
        assert a.mode == m.mode and a.s_after == -1 and m.s_after == 1


def test_accelerations_mirror_symmetry():
    for P, (u, ud, th, thd), ag, av, s, sigma in _random_cases(20, seed=3):
        for regime in lg.REGIMES:
            a = lg.accelerations(regime, P, (u, ud, th, thd), ag, av, s=s, sigma=sigma)
            m = lg.accelerations(regime, P, (-u, -ud, -th, -thd), -ag, av, s=-s, sigma=-sigma)
            assert m == pytest.approx((-a[0], -a[1], a[2], -a[3], -a[4], a[5]), rel=1e-11, abs=1e-11)


def test_p7_corrected_eq12_and_p8_vectors():
    """derivation.md P7 (Eq. 12 with theta_dot^2) and P8 (G2 - O = (-b, h)) checked with sympy."""
    import sympy as sp

    t = sp.Symbol("t")
    th = sp.Function("theta")(t)
    xp, yp = sp.symbols("x_p y_p")
    rot = sp.Matrix([[sp.cos(th), sp.sin(th)], [-sp.sin(th), sp.cos(th)]])  # seed Eq. (9)
    x = (rot * sp.Matrix([xp, yp]))[0]
    want = -(xp * sp.cos(th) + yp * sp.sin(th)) * th.diff(t) ** 2 + (-xp * sp.sin(th) + yp * sp.cos(th)) * th.diff(t, 2)
    assert sp.simplify(x.diff(t, 2) - want) == 0
    # P8: with the pivot on the +x corner (s = +1) the statue's G2 - pivot at theta = 0 is (-b, h)
    d = lg.symbolic_equations(1)
    G_minus_pivot = (d["x2"] - d["pivot"]).subs(lg.th_s, 0)
    vals = {lg.b: 0.5, lg.h: 2.0, lg.R: math.hypot(0.5, 2.0), lg.alpha: math.atan2(0.5, 2.0)}
    assert [float(c.subs(vals)) for c in G_minus_pivot] == pytest.approx([-0.5, 2.0], rel=1e-14)


def test_impact_consistency_flag():
    """Slender statues, pedestal at rest before the impact: always consistent.  A squat heavy
    statue on a light pedestal over a slippery floor is flagged (theta_dot+ changes sign)."""
    for H in (2, 3, 4, 5):
        for m2 in (0.5, 1, 4, 10):
            for mu in (0.0, 0.1, 0.4, 1.0):
                P = dict(b=0.5, h=H / 2, m1=1.0, m2=m2, g=G, mu_s=mu, mu_k=0.75 * mu)
                for r in (None, 0.8):
                    imp = lg.impact_coulomb(P, (0.0, 0.0, 0.0, -0.5), s_before=1, r=r)
                    assert imp.consistent and imp.theta_dot < 0
    P = dict(b=0.5, h=0.5, m1=0.01, m2=5.0, g=G, mu_s=0.01, mu_k=0.01)
    assert cf.eta_stack_frictionless(0.5, 0.5, 0.01, 5.0) < 0
    imp = lg.impact_coulomb(P, (0.0, 0.0, 0.0, -0.5), s_before=1)
    assert not imp.consistent and imp.theta_dot > 0
