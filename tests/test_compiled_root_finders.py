"""The two searches of the compiled solver's event location, tested on their own.

``_locate`` finds the first zero of a guard inside a bracket; ``_minimum`` finds a dip of a guard
below zero between two positive ends (a grazing touch, scipy#9228). In a run both read the guard
off the step's dense output. Here the dense output is built so that the impact guard of a
statue rocking on its +x corner, S·θ(x) = θ(x), is a polynomial chosen in the test: the searches
are checked against roots and minima known in closed form, with no physics involved.

The dense output of the 8th-order step is a nested product in x and 1 − x
(``dop853.dense_component``); it is linear in the rows of ``F``, so the rows that give a wanted
polynomial are solved for from its values at as many points as there are rows used.
"""

from __future__ import annotations

import numpy as np
import pytest

from rocking.integrators import dop853
from rocking.models.modes import IMPACT, N_GUARDS
from rocking.models.parameters import N_PARAMS
from rocking.excitation.signal import LOCAL_SIZE
from rocking.solver.compiled import N_STATE, _guard_at, _locate, _minimum, _piece

THETA = 2  # the state's column of θ


def _dense_rows(poly, n_rows):
    """The state at the step's start and ``F`` (INTERPOLATOR_POWER × N_STATE) whose θ column
    interpolates the polynomial ``poly`` (a callable of the step fraction x, degree ≤ n_rows).
    Every row of ``F`` adds a multiple of x (the output starts at the state), so θ at the start
    is ``poly(0)`` and the rows fit the rest."""
    F = np.zeros((dop853.INTERPOLATOR_POWER, N_STATE))
    y0 = np.zeros(N_STATE)
    y0[THETA] = poly(0.0)
    xs = np.linspace(0.05, 0.95, n_rows)
    basis = np.empty((n_rows, n_rows))
    for k in range(n_rows):
        unit = np.zeros_like(F)
        unit[k, THETA] = 1.0
        basis[:, k] = [dop853.dense_component(np.zeros(N_STATE), unit, x, THETA) for x in xs]
    F[:n_rows, THETA] = np.linalg.solve(basis, [poly(x) - y0[THETA] for x in xs])
    return y0, F


def _search_args(y0, F):
    """The arguments the two searches share, for the impact guard of a statue on its +x corner
    (``s = 1``, not sliding): only θ is read, so the parameters and the floor (a piece of the
    motion, in the tuple form the solver passes) are left empty."""
    p = np.zeros(N_PARAMS)
    loc = _piece(np.zeros((1, 2 * LOCAL_SIZE)), 0)
    work = np.empty(N_STATE)
    gbuf = np.empty(N_GUARDS)
    return p, 0, 1, y0, F, 1e-2, loc, 0.0, False, work, gbuf, IMPACT


def _guard(args, x):
    return _guard_at(*args[:6], x, *args[6:])


def test_the_dense_output_built_here_is_the_polynomial_asked_for():
    poly = lambda x: (x - 0.3) * (0.8 - x)  # noqa: E731
    y0, F = _dense_rows(poly, 3)
    args = _search_args(y0, F)
    for x in np.linspace(0.0, 1.0, 11):
        assert _guard(args, x) == pytest.approx(poly(x), abs=1e-15)


def test_locate_finds_the_first_zero_when_the_bracket_ends_on_a_zero():
    # A guard that starts tied after an event (zero at x = 0), is positive inside and is zero to
    # the bit at the step's end: the secant point then falls on the bracket's end, and the search
    # must bisect inside the bracket. The zero it must find is the end, x = 1.
    y0, F = _dense_rows(lambda x: x * (1.0 - x), 3)
    args = _search_args(y0, F)
    g_hi = _guard(args, 1.0)
    assert g_hi == 0.0  # the case under test: the secant's end point is the root itself
    x0 = 0.25
    x = _locate(*args, _guard(args, x0), g_hi, x0, 1.0)
    assert x0 <= x <= 1.0
    assert x == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("root", [0.1, 0.5, 0.93])
def test_locate_finds_a_simple_zero_to_the_event_tolerance(root):
    # (x − root)·(x + 1)·(−1): positive before the root, negative after. The search stops when
    # the bracket is 1e-15 s wide: at h = 1e-2 s that is 1e-13 of the step.
    y0, F = _dense_rows(lambda x: (root - x) * (x + 1.0), 3)
    args = _search_args(y0, F)
    x = _locate(*args, _guard(args, 0.0), _guard(args, 1.0), 0.0, 1.0)
    assert x == pytest.approx(root, abs=1e-12)
    assert _guard(args, x) <= 0.0  # the located point is on or past the crossing


@pytest.mark.parametrize("centre", [0.2, 0.55, 0.8])
def test_minimum_finds_a_narrow_dip_below_zero_anywhere_in_the_step(centre):
    # (x − c)² − w²: positive at both ends of the step, below zero only within ±w of c. With
    # w = 0.01 the golden-section search must narrow the bracket several times before one of
    # its points falls inside the dip (its first two points, 0.382 and 0.618, are outside).
    w = 0.01
    y0, F = _dense_rows(lambda x: (x - centre) ** 2 - w * w, 3)
    args = _search_args(y0, F)
    assert _guard(args, 0.0) > 0.0 and _guard(args, 1.0) > 0.0
    x = _minimum(*args)
    assert abs(x - centre) <= w
    assert _guard(args, x) <= 0.0


def test_minimum_reports_no_dip_for_a_guard_that_stays_positive():
    y0, F = _dense_rows(lambda x: (x - 0.4) ** 2 + 1e-4, 3)
    assert _minimum(*_search_args(y0, F)) == -1.0


def _dense_columns(polys, n_cols, n_rows=5):
    """The state at the step's start and ``F`` whose column j interpolates ``polys[j]`` (a callable
    of x, degree ≤ n_rows), as :func:`_dense_rows` does for one column."""
    F = np.zeros((dop853.INTERPOLATOR_POWER, n_cols))
    y0 = np.zeros(n_cols)
    xs = np.linspace(0.05, 0.95, n_rows)
    basis = np.empty((n_rows, n_rows))
    for k in range(n_rows):
        unit = np.zeros((dop853.INTERPOLATOR_POWER, 1))
        unit[k, 0] = 1.0
        basis[:, k] = [dop853.dense_component(np.zeros(1), unit, x, 0) for x in xs]
    for j, poly in polys.items():
        y0[j] = poly(0.0)
        F[:n_rows, j] = np.linalg.solve(basis, [poly(x) - y0[j] for x in xs])
    return y0, F


@pytest.mark.parametrize("root", [0.07, 0.5, 0.9])
@pytest.mark.parametrize("bend", ["convex", "concave"])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_dense_sum_root_finds_the_zero_of_a_sum_to_its_tolerance(root, bend, sign):
    # The turning point of a block's absolute rotation θ = Σ φ is the zero of a sum of dense
    # components (the stack engine; the two-body solver's θ̇ is a sum of one). On a convex or
    # concave function plain regula falsi keeps one end of the bracket for good and, after its 100
    # iterations, would return the middle of a bracket still ~0.5 wide; the Illinois rule halves
    # the stuck end's value. Both orientations of the sign change and both bends are asked for, so
    # that each end gets stuck in one of the cases. Tolerance: the documented 1e-10 of the step.
    if bend == "convex":
        total = lambda x: sign * ((1.2 - x) ** 4 - (1.2 - root) ** 4)  # noqa: E731
    else:
        total = lambda x: sign * ((root + 0.2) ** 4 - (x + 0.2) ** 4)  # noqa: E731
    # split over two components, 3 apart (first = 1, stride = 3, count = 2), with a polynomial
    # that cancels in the sum
    part = lambda x: 0.3 * x**3 - x  # noqa: E731
    y0, F = _dense_columns({1: lambda x: 0.4 * total(x) + part(x), 4: lambda x: 0.6 * total(x) - part(x)}, 6)
    f = lambda x: dop853.dense_sum(y0, F, x, 1, 3, 2)  # noqa: E731
    assert f(root) == pytest.approx(0.0, abs=1e-12)
    x = dop853.dense_sum_root(y0, F, 1, 3, 2, f(0.0), f(1.0), 1.0)
    assert x == pytest.approx(root, abs=1e-10)


def test_dense_sum_root_takes_the_secant_step():
    # Regula falsi lands on a straight line's zero at its first step: on y = −0.3 + x (one
    # component, every higher coefficient zero) the chord from (0, −0.3) to (1, 0.7) meets zero at
    # 0.3/1.0, and the dense output there is −0.3 + 0.3 = 0 exactly, so the search stops at once.
    # Bisection alone (a broken secant falls back on it) ends 1e-11 off, at a dyadic midpoint.
    # Tolerance 1e-15: a few ulps of 0.3. The same on y = −1.5 + 5x, whose values at the ends
    # differ by 5, not 1: a chord that multiplied by that difference instead of dividing by it
    # met the first line's zero all the same (and, after one bisection, that of y = −0.6 + 2x).
    F = np.zeros((dop853.INTERPOLATOR_POWER, 1))
    for y_start, slope in ((-0.3, 1.0), (-1.5, 5.0)):
        F[0, 0] = slope
        y0 = np.array([y_start])
        f_lo, f_hi = dop853.dense_sum(y0, F, 0.0, 0, 1, 1), dop853.dense_sum(y0, F, 1.0, 0, 1, 1)
        assert (f_lo, f_hi) == (y_start, y_start + slope)
        assert dop853.dense_sum_root(y0, F, 0, 1, 1, f_lo, f_hi, 1.0) == pytest.approx(0.3, abs=1e-15)


def test_dense_sum_root_halves_the_bracket_where_the_chord_rounds_onto_its_end():
    # On y = s·(x − r)(1 + c·x), 3000 random parabolas with one zero r in [0, x_hi]: the chord
    # lands within a few ulps of r, and about one search in seventy then finds its next chord
    # rounded onto an end of the tiny bracket left (43 of these 3000). The search must halve
    # that bracket there, not leave it: a midpoint written 0.5/(lo + hi) sent two of them out of
    # [0, x_hi] (to 1.05 and 1.93), one written 1.5·(lo + hi) two others (to 1.76 and 1.2e16).
    # Tolerance: the documented 1e-10 of the step (the worst here is 5.0e-11, a bisection's last
    # halving), and the answer must lie in [0, x_hi].
    rng = np.random.default_rng(2)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 1))
    worst = 0.0
    for _ in range(3000):
        r = float(rng.uniform(0.05, 0.9))
        x_hi = float(rng.uniform(r + 1e-3, 1.0))
        s = float(rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-3, 3))
        c = float(rng.uniform(-0.9, 0.9))
        # s(x − r)(1 + cx) = −sr + s(1 − cr + c)·x − sc·x(1 − x), the dense output's own form
        F[0, 0], F[1, 0] = s * (1 - c * r + c), -s * c
        y0 = np.array([-s * r])
        f_lo, f_hi = dop853.dense_sum(y0, F, 0.0, 0, 1, 1), dop853.dense_sum(y0, F, x_hi, 0, 1, 1)
        assert f_lo * f_hi < 0.0
        x = dop853.dense_sum_root(y0, F, 0, 1, 1, f_lo, f_hi, x_hi)
        assert 0.0 <= x <= x_hi, (r, s, c, x_hi, x)
        worst = max(worst, abs(x - r))
    assert worst <= 1e-10
