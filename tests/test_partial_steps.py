"""The Runge–Kutta steps on part of the state (``*_on`` in rocking.integrators.dop853 and
dopri5), which the stack engine uses to skip the coordinates its contact mode holds still.

Their promise is exactness, not accuracy: where the skipped components' rows of K are zero,
they give what the full functions give, bit for bit, including the sign of a zero (a −0.0 in
y comes out +0.0 from the full sums). So every comparison here is ``array_equal`` on the
values and on their sign bits, on random states in which a random subset of components has
zero (or −0.0) rows of K, and some y entries are ±0.0.
"""

import itertools

import numpy as np
import pytest

from rocking.integrators import dop853, dopri5


def _same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b))


def _sorted(act, m):
    """``act`` with its moving part sorted, as the error norms want it (the still part after it:
    a permutation of the whole state, so that the norms take their partial path, not the full one
    they take when every component moves)."""
    return np.concatenate([np.sort(act[:m]), act[m:]])


def _case(rng, n_rows, n):
    y = rng.normal(size=n)
    K = rng.normal(size=(n_rows, n))
    still = rng.random(n) < 0.5
    still[rng.integers(n)] = False  # at least one moving component
    if rng.random() < 0.2:
        still[:] = False  # all moving: the functions' shortcut to the full sums
    # the still components: zero rows of K (some −0.0), and some zero y of either sign
    K[:, still] = np.where(rng.random((n_rows, still.sum())) < 0.5, 0.0, -0.0)
    zeros = still & (rng.random(n) < 0.5)
    y[zeros] = np.where(rng.random(zeros.sum()) < 0.5, 0.0, -0.0)
    moving = np.flatnonzero(~still)
    act = np.concatenate([moving, rng.permutation(np.flatnonzero(still))]).astype(np.int64)
    return y, K, act, len(moving)


@pytest.mark.parametrize("seed", range(20))
def test_dop853_steps_on_the_moving_components_are_the_full_steps(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 14))
    y, K, act, m = _case(rng, dop853.N_K, n)
    h = float(rng.uniform(1e-4, 0.1))
    for stage in range(1, dop853.N_STAGES):
        full, part = np.full(n, np.nan), np.full(n, np.nan)
        dop853.stage_input(y, K, h, stage, full)
        dop853.stage_input_on(y, K, h, stage, part, act, m)
        assert _same(full, part), stage
    full, part = np.full(n, np.nan), np.full(n, np.nan)
    dop853.advance(y, K, h, full)
    dop853.advance_on(y, K, h, part, act, m)
    assert _same(full, part)
    y_new = full
    # (tolerances of 1: with 1e-9 the squared sums are ~1e18, and a sum started at 1.0 instead of
    # 0.0 would round to the same value)
    for (rtol, atol), n_ctrl in itertools.product(((1e-9, 1e-12), (1.0, 1.0)), (n, n - 1)):
        e_full = dop853.error_norm(y, y_new, K, h, rtol, atol, n_ctrl)
        e_part = dop853.error_norm_on(y, y_new, K, h, rtol, atol, n_ctrl, _sorted(act, m), m)
        assert e_full == e_part and (e_full > 0.0 or n_ctrl < n)
    for j in range(dop853.N_EXTRA):
        full, part = np.full(n, np.nan), np.full(n, np.nan)
        dop853.extra_stage_input(y, K, h, j, full)
        dop853.extra_stage_input_on(y, K, h, j, part, act, m)
        assert _same(full, part), j
    F_full = np.full((dop853.INTERPOLATOR_POWER, n), np.nan)
    F_part = np.full((dop853.INTERPOLATOR_POWER, n), np.nan)  # stale values must not survive
    dop853.prepare_dense(y, y_new, K, h, F_full)
    dop853.prepare_dense_on(y, y_new, K, h, F_part, act, m)
    assert _same(F_full[:, act[:m]], F_part[:, act[:m]])
    for x in (0.0, 0.25, 0.5, 0.9, 1.0):
        full, part, on = np.empty(n), np.empty(n), np.full(n, np.nan)
        dop853.dense(y, F_full, x, full)
        dop853.dense(y, F_part, x, part)
        dop853.dense_on(y, F_part, x, on, act, m)
        assert _same(full, part) and _same(full, on), x


@pytest.mark.parametrize("seed", range(20))
def test_dopri5_steps_on_the_moving_components_are_the_full_steps(seed):
    rng = np.random.default_rng(100 + seed)
    n = int(rng.integers(2, 14))
    y, K, act, m = _case(rng, 7, n)
    h = float(rng.uniform(1e-4, 0.1))
    for stage in range(1, 6):
        full, part = np.full(n, np.nan), np.full(n, np.nan)
        dopri5.stage_input(y, K, h, stage, full)
        dopri5.stage_input_on(y, K, h, stage, part, act, m)
        assert _same(full, part), stage
    full, part = np.full(n, np.nan), np.full(n, np.nan)
    dopri5.advance(y, K, h, full)
    dopri5.advance_on(y, K, h, part, act, m)
    assert _same(full, part)
    y_new = full
    for (rtol, atol), n_ctrl in itertools.product(((1e-9, 1e-12), (1.0, 1.0)), (n, n - 1)):
        e_full = dopri5.error_norm(y, y_new, K, h, rtol, atol, n_ctrl)
        e_part = dopri5.error_norm_on(y, y_new, K, h, rtol, atol, n_ctrl, _sorted(act, m), m)
        assert e_full == e_part and (e_full > 0.0 or n_ctrl < n)
    F_full = np.full((7, n), np.nan)
    F_part = np.full((7, n), np.nan)
    dopri5.prepare_dense_nested(y, K, h, F_full)
    dopri5.prepare_dense_nested_on(y, K, h, F_part, act, m)
    assert _same(F_full[:, act[:m]], F_part[:, act[:m]])
    for x in (0.0, 0.3, 0.7, 1.0):
        full, part = np.empty(n), np.empty(n)
        dop853.dense(y, F_full, x, full)
        dop853.dense(y, F_part, x, part)
        assert _same(full, part), x
