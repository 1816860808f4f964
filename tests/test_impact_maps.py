"""The impact laws of ``rocking.contact.impact`` against the maps that ``tests/oracles/lagrange.py``
derives with sympy from momentum balances (statue's angular momentum about the new pivot,
the system's horizontal and vertical momentum, Coulomb's law on the floor impulse).

Random states, both pivots, a held and a sliding pedestal (stick and slip at the impact), with
Housner's restitution and with a prescribed r. rtol 1e-10: both sides solve the same 2×2 or 3×3
linear system in float64, differently arranged.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import G
from oracles import lagrange

from rocking.contact.impact import impact_coulomb, impact_paper

RTOL = 1e-10


def _random_impacts(n, seed):
    """(params for lagrange, r or None, s_before, u̇⁻, θ̇⁻) for n random impacts."""
    rng = np.random.default_rng(seed)
    for k in range(n):
        b, h = rng.uniform(0.1, 0.6), rng.uniform(0.6, 3.0)
        m1 = 0.0 if k % 7 == 0 else rng.uniform(0.1, 5.0)  # m1 = 0: the single block
        m2 = rng.uniform(0.2, 6.0)
        mu_s = rng.uniform(0.05, 0.7)
        params = dict(b=b, h=h, m1=m1, m2=m2, g=G, mu_s=mu_s, mu_k=mu_s * rng.uniform(0.4, 1.0))
        r = (None, 0.5, 0.8, 0.95, 1.0)[k % 5]
        s_before = int(rng.choice([-1, 1]))
        theta_dot = -s_before * rng.uniform(0.05, 2.0)  # falling back onto θ = 0
        u_dot = 0.0 if k % 3 == 0 else rng.normal(0.0, 0.3)  # a held or a sliding pedestal
        yield params, r, s_before, u_dot, theta_dot


def _library_coulomb(params, r, u_dot, theta_dot, can_slide=1.0):
    b, h, m1, m2 = params["b"], params["h"], params["m1"], params["m2"]
    i_o = 4.0 / 3.0 * m2 * (b * b + h * h)
    eta = 1.0 - 1.5 * b * b / (b * b + h * h) if r is None else r  # Housner's, for a held pedestal
    return impact_coulomb(i_o, m1 + m2, m2, b, h, eta, params["mu_s"], params["mu_k"], can_slide, u_dot, theta_dot)


def _assert_close(got, want, scale, what):
    np.testing.assert_allclose(got, want, rtol=RTOL, atol=RTOL * scale, err_msg=what)


def test_coulomb_impact_law_matches_the_sympy_momentum_balances():
    modes = {"stick": 0, "slide": 0, "inconsistent": 0}
    pivots, laws = set(), set()
    for params, r, s_before, u_dot, theta_dot in _random_impacts(600, seed=20240612):
        v, w, fx, fy, ok = _library_coulomb(params, r, u_dot, theta_dot)
        try:
            ref = lagrange.impact_coulomb(params, (0.0, u_dot, 0.0, theta_dot), r=r, s_before=s_before)
        except ValueError:  # no sliding direction solves the balances: the library must say so
            assert not ok
            continue
        what = f"{params}, r={r}, s={s_before}, u̇⁻={u_dot}, θ̇⁻={theta_dot}, {ref.mode}"
        if not ref.consistent:  # θ̇ would reverse (a squat statue): flagged, not compared
            assert not ok, what
            modes["inconsistent"] += 1
            continue
        assert ok, what
        _assert_close(v, ref.u_dot, abs(u_dot) + abs(theta_dot) * params["h"], "u̇⁺: " + what)
        _assert_close(w, ref.theta_dot, abs(theta_dot), "θ̇⁺: " + what)
        momentum = (params["m1"] + params["m2"]) * (abs(u_dot) + abs(theta_dot) * params["h"])
        _assert_close(fx, ref.Fx, momentum, "Fx: " + what)
        _assert_close(fy, ref.Fy, momentum, "Fy: " + what)
        if ref.mode == "stick":
            assert v == 0.0 and abs(fx) <= params["mu_s"] * fy, what
        else:
            assert v != 0.0 and abs(fx) == pytest.approx(params["mu_k"] * fy, rel=1e-12), what
        modes[ref.mode] += 1
        pivots.add(s_before)
        laws.add(r)
    # Enough of every branch: held and sliding through the impact, both corners, every r.
    assert modes["stick"] > 100 and modes["slide"] > 100, modes
    assert pivots == {-1, 1} and laws == {None, 0.5, 0.8, 0.95, 1.0}


def test_coulomb_sliding_branch_with_kinetic_below_static_friction():
    """μk well below μs: using μs for μk in the sliding branch (or flipping the sign of its μk
    term) moves u̇⁺ and θ̇⁺ by far more than the tolerance."""
    params = dict(b=0.5, h=2.0, m1=1.0, m2=6.0, g=G, mu_s=0.1, mu_k=0.05)
    for s_before in (1, -1):
        for u_dot in (0.0, 0.5, -0.5):  # held, and sliding either way, before the impact
            theta_dot = -0.8 * s_before
            for r in (None, 0.8):
                ref = lagrange.impact_coulomb(params, (0.0, u_dot, 0.0, theta_dot), r=r, s_before=s_before)
                assert ref.mode == "slide" and ref.consistent
                v, w, fx, fy, ok = _library_coulomb(params, r, u_dot, theta_dot)
                assert ok
                np.testing.assert_allclose([v, w, fx, fy], [ref.u_dot, ref.theta_dot, ref.Fx, ref.Fy],
                                           rtol=RTOL, atol=RTOL)


def test_coulomb_impact_without_floor_friction_limit_is_the_held_pedestal():
    """A body that cannot slide (no floor friction given): the stick solution, whatever Fx."""
    for params, r, s_before, _, theta_dot in _random_impacts(60, seed=7):
        ref = lagrange.impact_coulomb({**params, "mu_s": math.inf}, (0.0, 0.0, 0.0, theta_dot), r=r,
                                      s_before=s_before)
        got = _library_coulomb(params, r, 0.0, theta_dot, can_slide=0.0)
        assert ref.mode == "stick" and got[4]
        np.testing.assert_allclose(got[:4], [ref.u_dot, ref.theta_dot, ref.Fx, ref.Fy], rtol=RTOL,
                                   atol=RTOL * abs(theta_dot) * (params["m1"] + params["m2"]) * params["h"])


def test_paper_impact_law_matches_the_sympy_momentum_balances():
    n = 0
    for params, r, s_before, u_dot, theta_dot in _random_impacts(200, seed=99):
        b, h, m1, m2 = params["b"], params["h"], params["m1"], params["m2"]
        eta = 1.0 - 1.5 * b * b / (b * b + h * h) if r is None else r
        ref = lagrange.impact_paper(params, (0.0, u_dot, 0.0, theta_dot), r=r, s_before=s_before)
        v, w, fx, fy = impact_paper(m1 + m2, m2, b, h, eta, u_dot, theta_dot)
        scale = (m1 + m2) * (abs(u_dot) + abs(theta_dot) * h)
        np.testing.assert_allclose([v, w], [ref.u_dot, ref.theta_dot], rtol=RTOL, atol=RTOL * (abs(u_dot) + 1e-300))
        np.testing.assert_allclose([fx, fy], [ref.Fx, ref.Fy], rtol=RTOL, atol=RTOL * scale)
        n += 1
    assert n == 200
