"""The compiled Dormand–Prince 5(4) toolkit (rocking.integrators.dopri5), used by the solver on
steps cut short by a record sample: one step, its error norm and its dense output (in DOP853's
nested form, evaluated by ``dop853.dense``) against scipy's RK45 forced to the same step."""

import math

import numpy as np
import pytest
from numba import njit
from scipy.integrate import RK45

from rocking.integrators import dop853, dopri5

FSAL = 6  # row of K holding f(t + h, y_new)


@njit
def pendulum(t, y, out):
    out[0] = y[1]
    out[1] = -math.sin(y[0]) + 0.3 * math.cos(1.7 * t)  # forced: the nodes c_k matter


def py_pendulum(t, y):
    out = np.empty(2)
    pendulum(t, y, out)
    return out


@njit
def one_step(t, y, h):
    K = np.empty((7, 2))
    work = np.empty(2)
    y_new = np.empty(2)
    pendulum(t, y, K[0])
    for stage in range(1, 6):
        dopri5.stage_input(y, K, h, stage, work)
        pendulum(t + dopri5.C[stage] * h, work, K[stage])
    dopri5.advance(y, K, h, y_new)
    pendulum(t + h, y_new, K[FSAL])
    F = np.empty((dop853.INTERPOLATOR_POWER, 2))
    dopri5.prepare_dense_nested(y, K, h, F)
    return y_new, K, F


def test_tableau_is_scipy_rk45s_to_the_bit():
    """Every coefficient is Dormand & Prince's as scipy's RK45 holds it, the zeros that the stage
    loops never read included: the method is explicit (A strictly lower triangular, C[0] = 0), which
    is what lets ``stage_input`` sum over the earlier stages only."""
    assert np.array_equal(dopri5.C, RK45.C)
    assert np.array_equal(dopri5.A, RK45.A)
    assert np.array_equal(dopri5.BW, RK45.B)
    assert np.array_equal(dopri5.E, RK45.E)
    assert np.array_equal(dopri5.P, RK45.P)
    # Independently of scipy: explicit, consistent (row sums are the nodes), the weights sum to 1
    # and the error weights to 0 (1e-15: sums of a few O(1) fractions).
    assert dopri5.C[0] == 0.0 and np.array_equal(np.tril(dopri5.A, -1), dopri5.A)
    np.testing.assert_allclose(dopri5.A.sum(axis=1), dopri5.C, rtol=0, atol=1e-15)
    assert dopri5.BW.sum() == pytest.approx(1.0, abs=1e-15) and abs(dopri5.E.sum()) < 1e-15


@pytest.mark.parametrize("h", [0.4, 0.05])
def test_step_error_norm_and_dense_output_match_scipy_rk45(h):
    t0, y0 = 0.3, np.array([1.1, -0.2])
    solver = RK45(py_pendulum, t0, y0, t_bound=t0 + 100 * h, first_step=h, rtol=1e3, atol=1e3)
    solver.step()  # huge tolerances: the step of size h is accepted
    assert solver.t == pytest.approx(t0 + h, rel=1e-15)
    y_new, K, F = one_step(t0, y0, h)
    # Sums of a handful of O(1) terms: agreement to a few ulps.
    np.testing.assert_allclose(y_new, solver.y, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(K, solver.K, rtol=1e-14, atol=1e-15)

    for rtol, atol in [(1e-10, 1e-12), (1e-6, 1e-9)]:
        scale = atol + rtol * np.maximum(np.abs(y0), np.abs(solver.y))
        theirs = solver._estimate_error_norm(solver.K, h, scale)
        # Σ E·K cancels several digits (terms ~1, sum ~h⁴): the summation order shows at ~1e-10.
        assert dopri5.error_norm(y0, y_new, K, h, rtol, atol, 2) == pytest.approx(theirs, rel=1e-8)

    # Shampine's quartic interpolant, rewritten in the nested form, gives scipy's values.
    dense = solver.dense_output()
    out = np.empty(2)
    for x in np.linspace(0.0, 1.0, 17):
        dop853.dense(y0, F, x, out)
        np.testing.assert_allclose(out, dense(t0 + x * h), rtol=1e-13, atol=1e-15)
    dop853.dense(y0, F, 1.0, out)
    np.testing.assert_allclose(out, y_new, rtol=1e-15, atol=1e-16)
