"""Lemke's method (rocking.stack.lcp) against an independent solution of the same LCPs.

The oracle enumerates complementary bases: for every set S of indices, solve M_SS z_S = −q_S
with numpy and keep the z that has z ≥ 0 and w = Mz + q ≥ 0. It shares nothing with the pivoting
but numpy's linear algebra, and it is exhaustive, so it is affordable for n ≤ 7 only.

``lemke`` checks its own answer (residual within ``check``) and falls back on regularised
problems, so a broken pivoting mostly shows as an answer that is right to 1e-6 instead of
1e-12, or as an LCPError. The tests below therefore hold the answers to round-off, and run the
plain pivoting on its own where its soundness on degenerate problems is the claim.
"""

import itertools

import numpy as np
import pytest

from rocking.stack import lcp
from rocking.stack.lcp import LCPError, lemke


def enumerate_solutions(m, q, tol=1e-12):
    """Every solution of the LCP (m, q) found among the complementary bases (nondegenerate ones)."""
    n = q.size
    found = []
    for size in range(n + 1):
        for support in itertools.combinations(range(n), size):
            s = list(support)
            z = np.zeros(n)
            if s:
                block = m[np.ix_(s, s)]
                if abs(np.linalg.det(block)) < 1e-12:
                    continue
                z[s] = np.linalg.solve(block, -q[s])
            w = m @ z + q
            if z.min() >= -tol and w.min() >= -tol:
                found.append(z)
    return found


def p_matrix(rng, n):
    """AAᵀ + I plus a skew part: positive definite (xᵀMx ≥ |x|²), hence a P-matrix."""
    a = rng.normal(size=(n, n))
    skew = rng.normal(size=(n, n))
    return a @ a.T + np.eye(n) + (skew - skew.T)


def p_matrix_problems(seed, count, q_size=1.0):
    """``count`` random P-matrix problems (n = 1…7) with their one solution by enumeration."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        n = int(rng.integers(1, 8))
        m = p_matrix(rng, n)
        q = rng.normal(size=n) * q_size
        (expected,) = enumerate_solutions(m, q)
        yield m, q, expected


def assert_round_off(z, expected):
    assert z == pytest.approx(expected, abs=1e-12 * max(1.0, np.abs(expected).max()))


def test_p_matrix_problems_match_the_enumeration_to_round_off():
    """A P-matrix LCP has one solution for every q. Lemke's must be that one to 1e-12 of its
    size: the data are O(1) and M is well conditioned (eigenvalues of the symmetric part ≥ 1),
    so round-off is ~1e-15; the regularised fallbacks (M + 1e-10·s·I) would be off by ~1e-10."""
    for m, q, expected in p_matrix_problems(seed=11, count=400, q_size=2.0):
        assert_round_off(lemke(m, q), expected)


def test_the_exact_ratio_test_without_slack_solves_p_matrix_problems():
    """slack = 0 turns Harris's test into the textbook one (the rows at the exact minimum ratio)."""
    for m, q, expected in p_matrix_problems(seed=13, count=100):
        assert_round_off(lemke(m, q, slack=0.0), expected)


def test_the_plain_pivoting_solves_p_matrix_problems_without_fallback(monkeypatch):
    """The regularisations are a fallback: on a P-matrix (no degeneracy in exact arithmetic) the
    first, unregularised attempt must already succeed."""
    monkeypatch.setattr(lcp, "_REGULARISATIONS", (0.0,))
    for m, q, expected in p_matrix_problems(seed=12, count=200):
        assert_round_off(lemke(m, q), expected)


def _stack_lcps():
    """The contact LCPs of short Moreau–Jean runs: a block at rest on two corners (two parallel
    tangent rows, a statically indeterminate normal pair), a block sliding, a statue rocking on
    a pedestal, and a block whose face never slips (μ = 10⁴ in the LCP)."""
    from rocking.contact.friction import Friction
    from rocking.stack import timestepping as ts
    from rocking.stack.model import Block, Interface, Stack

    def one(width, height, mass, friction):
        return Stack(blocks=(Block(width=width, height=height, mass=mass),), interfaces=(Interface(friction=friction),))

    cases = [
        (one(0.4, 2.0, 100.0, Friction(static=0.5, kinetic=0.4)), lambda t: 0.0, 0.02),
        (one(1.0, 0.3, 100.0, Friction(static=0.2, kinetic=0.15)), lambda t: 4.0, 0.03),
        (Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=100.0)),
               interfaces=(Interface(friction=Friction(static=0.3, kinetic=0.25)),
                           Interface(friction=Friction(static=0.5, kinetic=0.4)))),
         lambda t: 5.0 * np.sin(4 * np.pi * t), 0.3),
        (one(0.4, 2.0, 100.0, None), lambda t: 3.0, 0.3),
    ]
    found = []
    solve = ts.lemke

    def recording(m, q, **kwargs):
        found.append((m.copy(), q.copy()))
        return solve(m, q, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(ts, "lemke", recording)
        for stack, a_h, t_end in cases:
            ts.moreau_jean(stack, a_h, t_end=t_end, dt=1e-3)
    return [(m, q) for m, q in found if q.min() < -1e-10 * max(1.0, np.abs(m).max(), np.abs(q).max())]


def test_the_plain_pivoting_solves_the_degenerate_lcps_of_contact(monkeypatch):
    """The claim of the module's docstring: Harris's ratio test, the largest pivot and the
    lexicographic tie-break keep the pivoting sound on the contact LCPs, which are degenerate.
    Without the regularised fallbacks every one of them must still be solved, to round-off
    (measured worst: 2e-15 of the data's size; 1e-12 allowed)."""
    problems = _stack_lcps()
    assert len(problems) > 200
    monkeypatch.setattr(lcp, "_REGULARISATIONS", (0.0,))
    for m, q in problems:
        z = lemke(m, q)
        w = m @ z + q
        scale = max(1.0, np.abs(m).max(), np.abs(q).max())
        assert z.min() >= 0.0
        assert w.min() >= -1e-12 * scale
        assert np.abs(np.minimum(w, z)).max() <= 1e-12 * scale


def test_a_block_on_two_corners_gets_a_valid_split_of_its_weight():
    """The simplest degenerate contact LCP, by hand: two equal normal columns (a block on both
    corners, no friction) that must carry a total impulse of 1. Any split is a solution; the
    sum must be exact."""
    m = np.ones((2, 2))
    for q in ([-1.0, -1.0], [-3.0, -3.0]):
        z = lemke(m, np.array(q))
        assert z.min() >= 0.0 and z.sum() == pytest.approx(-q[0], rel=1e-14)


def test_trivial_and_bad_problems():
    assert lemke(np.zeros((0, 0)), np.zeros(0)).shape == (0,)
    assert lemke(np.array([[1.0, 0.0], [0.0, 1.0]]), np.array([0.0, 2.0])).tolist() == [0.0, 0.0]
    # q slightly negative within round-off of its size: z = 0
    assert lemke(np.eye(2), np.array([-1e-12, 5.0])).tolist() == [0.0, 0.0]
    assert lemke(np.eye(2), np.array([-1e-8, 5.0])) == pytest.approx([1e-8, 0.0], abs=1e-20)
    with pytest.raises(ValueError, match=r"lemke: M must be \(2, 2\) for q of length 2, got \(2, 3\)"):
        lemke(np.ones((2, 3)), np.ones(2))
    with pytest.raises(LCPError, match="must be finite"):
        lemke(np.array([[np.nan]]), np.array([-1.0]))
    with pytest.raises(LCPError, match="must be finite"):
        lemke(np.array([[1.0]]), np.array([-np.inf]))


def test_failures_name_every_attempt():
    """No solution (w = −z − 1 ≥ 0 is impossible): the plain attempt and the three regularised
    ones are each reported; an exhausted pivot budget is named as such."""
    with pytest.raises(LCPError) as info:
        lemke(np.array([[-1.0]]), np.array([-1.0]))
    message = str(info.value)
    assert message.startswith("lemke: no solution found (n = 1); ε = 0: ray termination; ε = 1e-10: ")
    assert message.count("ε = ") == 4 and "ε = 1e-08" in message and "ε = 1e-06" in message
    with pytest.raises(LCPError, match=r"ε = 0: no solution within 0 pivots"):
        lemke(np.array([[2.0, 1.0], [1.0, 2.0]]), np.array([-5.0, -6.0]), max_pivots=0)


def test_a_problem_the_plain_pivoting_cannot_solve_is_solved_by_a_regularised_attempt():
    """M below is not copositive, and the plain pivoting ray-terminates on it (checked here),
    although z = (0, 0, 2) solves it: w = Mz + q = (2 − 2, 0, 0) = 0. M + εI (ε = 1e-10 of the
    data's size) leads the pivoting to that solution; the answer is checked on the original
    problem. (M − εI, a perturbation of the wrong sign, ray-terminates at every ε.)"""
    m = np.array([[-1.0, 0.0, 1.0], [-1.0, 1.0, 0.0], [-1.0, -1.0, 0.0]])
    q = np.array([-2.0, 0.0, 0.0])
    with pytest.raises(LCPError, match="ray termination"):
        lcp._pivoting(m, q, 200, 1e-10, 1e-9)
    assert lemke(m, q) == pytest.approx([0.0, 0.0, 2.0], abs=1e-8)


def test_the_regularisation_is_relative_to_the_size_of_the_data():
    """The problem above scaled by 10⁶ (z is unchanged): ε·s·I must be 1e-10 of the entries, not
    of 1; an absolute 1e-10 would be lost in their round-off and every attempt would
    ray-terminate."""
    m = 1e6 * np.array([[-1.0, 0.0, 1.0], [-1.0, 1.0, 0.0], [-1.0, -1.0, 0.0]])
    q = 1e6 * np.array([-2.0, 0.0, 0.0])
    assert lemke(m, q) == pytest.approx([0.0, 0.0, 2.0], abs=1e-8)


@pytest.mark.parametrize("tol", [1e-10, 0.0])
def test_a_tie_in_the_ratio_test_is_broken_lexicographically(tol):
    """M = [[3, 1, 1], [1, 1, 1], [1, 1, 3]] is positive definite (leading minors 3, 2, 4), so with
    q = (−2, −2, −2) the solution is unique: by symmetry z₁ = z₃ = a, z₂ = b with 4a + b = 2 and
    2a + b = 2, so z = (0, 2, 0), w = 0: degenerate. The ratio test meets rows that tie exactly,
    which the lexicographic rule must order, also with no tolerance at all (tol = 0)."""
    m = np.array([[3.0, 1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 1.0, 3.0]])
    assert lemke(m, np.array([-2.0, -2.0, -2.0]), tol=tol) == pytest.approx([0.0, 2.0, 0.0], abs=1e-14)


def test_the_options_are_keyword_only_and_q_at_the_tolerance_is_zero():
    m = np.eye(2)
    with pytest.raises(TypeError):
        lemke(m, np.array([-1.0, 0.5]), 10)  # max_pivots only by name
    assert lemke(M=m, q=np.array([-1.0, 0.5])).tolist() == [1.0, 0.0]
    # |q| ≤ 1 and |M| = 1: scale 1, and q.min() = −tol·scale exactly counts as non-negative;
    # beyond it, the pivoting runs
    assert lemke(m, np.array([-1e-10, 0.5])).tolist() == [0.0, 0.0]
    assert lemke(m, np.array([-1.5e-10, 0.5])).tolist() == [1.5e-10, 0.0]


def test_q_within_round_off_of_large_data_is_zero():
    """With |M| = 10⁶, q = −10⁻⁵ is round-off (below 1e-10 of the data's size): z = 0, no pivot."""
    assert lemke(1e6 * np.eye(2), np.array([-1e-5, 5e5])).tolist() == [0.0, 0.0]


@pytest.mark.parametrize("size", [1.0, 1e3, 1e6])
def test_a_problem_without_solution_is_refused_at_any_scale(size):
    """M is positive semidefinite and singular; with y = (0, 1, 1, 1), yᵀM = 0 and yᵀq = −2, so
    yᵀw = −2 for every z: no z gives w ≥ 0 (Farkas), and there is no solution. At 10⁶ the
    pivoting returned z ≈ 3e15 with w = −2e6, which the round-off allowance 1e-12·max z, left
    uncapped, accepted: a wrong answer where an LCPError is due."""
    m = np.array([[3.0, 1.0, -1.0, 0.0], [1.0, 2.0, -1.0, -1.0], [-1.0, -1.0, 3.0, -2.0], [0.0, -1.0, -2.0, 3.0]])
    q = np.array([-2.0, 0.0, 0.0, -2.0])
    y = np.array([0.0, 1.0, 1.0, 1.0])
    assert (y @ m).tolist() == [0.0, 0.0, 0.0, 0.0] and y @ q == -2.0  # the certificate, exactly
    with pytest.raises(LCPError, match="no solution found"):
        lemke(size * m, size * q)


# A contact LCP with the Moreau–Jean structure (normal rows; β⁺, β⁻ and λ rows; λ rows of a
# never-slipping contact scaled by 1/μ = 1e-4), built by the time stepping's assembly from
# random integer contact rows with a duplicated contact. Found by a search of 20 000 such
# problems: without the lexicographic tie-break Lemke's method cycles on it.
CYCLING_M = np.array([
    [2.0, 0.0, 2.0, -1.5, 0.0, 1.5, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.5, 1.0, -0.5, -1.0, 0.0, 0.0],
    [2.0, 0.0, 2.0, -1.5, 0.0, 1.5, 0.0, 0.0, 0.0],
    [-1.5, 0.5, -1.5, 1.5, 0.5, -1.5, -0.5, 1.0, 0.0],
    [0.0, 1.0, 0.0, 0.5, 1.0, -0.5, -1.0, 0.0, 1.0],
    [1.5, -0.5, 1.5, -1.5, -0.5, 1.5, 0.5, 1.0, 0.0],
    [0.0, -1.0, 0.0, -0.5, -1.0, 0.5, 1.0, 0.0, 1.0],
    [0.0, 1.0, 0.0, -1e-4, 0.0, -1e-4, 0.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0, -1e-4, 0.0, -1e-4, 0.0, 0.0],
])
CYCLING_Q = np.array([-2.0, 3.0, -2.0, 3.0, 3.0, -3.0, -3.0, 0.0, 0.0])


@pytest.mark.parametrize("fallbacks", [True, False])
def test_the_tie_break_keeps_the_pivoting_from_cycling(monkeypatch, fallbacks):
    """On the problem above the plain pivoting must end, with an exact answer (w ≥ 0, z ≥ 0,
    min(w, z) = 0 to 1e-12 of the data). Without the tie-break it runs out of pivots (cycling),
    and the regularised fallback then returns an answer off by 9e-8: inside `check`, outside
    round-off."""
    if not fallbacks:
        monkeypatch.setattr(lcp, "_REGULARISATIONS", (0.0,))
    z = lemke(CYCLING_M, CYCLING_Q)
    w = CYCLING_M @ z + CYCLING_Q
    assert z.min() >= 0.0 and w.min() >= -1e-12 and np.abs(np.minimum(w, z)).max() <= 1e-12


def test_the_largest_pivot_is_taken_among_rows_that_tie():
    """Entries of 1e-5 and 1e-4 beside entries of order 1. By hand, z = (0, 100001, 0, 200001, 0)
    solves it: w₁ = 2·100001 − 200001 − 1 = 0, w₃ = 1e-5·(200001 − 100001) − 1 = 0, and
    w₀ = 1, w₂ = 200001, w₄ = 29.0002 are positive. Round-off in w is at most n·ε·|M||z| ≈ 5e-10,
    so 1e-9 is allowed. Pivoting on a tiny entry of a tied row instead of the largest one leaves
    w₁ = 3.4e-6 at z₁ = 100001 (and `check` lets that through)."""
    m = np.array([
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0, 2.0, -1.0, 1.0],
        [0.0, 2.0, 4.0, 0.0, 4.0],
        [0.0, -1e-5, 0.0, 1e-5, 1e-5],
        [0.0, 1e-4, 4e-4, 1e-4, 5e-4],
    ])
    q = np.array([1.0, -1.0, -1.0, -1.0, -1.0])
    z = lemke(m, q)
    w = m @ z + q
    assert z == pytest.approx([0.0, 100001.0, 0.0, 200001.0, 0.0], rel=1e-9)
    assert z.min() >= 0.0 and w.min() >= -1e-9 and np.abs(np.minimum(w, z)).max() <= 1e-9
