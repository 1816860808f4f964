"""Dormand–Prince 5(4) Runge–Kutta step with its 4th-order dense output, compiled.

Generic numerics: nothing here knows about blocks; the caller evaluates its own right-hand side
between the stages. The tableau is the one of
Dormand & Prince (1980) as used by ``scipy.integrate.RK45`` (Shampine's dense output).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .dop853 import hold_still, interpolate_still

C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1 / 5, 0.0, 0.0, 0.0, 0.0],
        [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
        [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    ]
)
BW = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
# Difference between the 5th- and embedded 4th-order weights (the error estimator).
E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
# Dense output polynomial coefficients (Shampine 1986), columns multiply x, x², x³, x⁴.
P = np.array(
    [
        [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
        [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
        [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
        [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
        [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
    ]
)


# As in dop853.py: each step operation loops over one per-component kernel, which the variants on
# part of the state share.


@njit(cache=True, inline="always")
def _stage_input_at(y, K, h, stage, out, j):
    acc = 0.0
    for k in range(stage):
        acc += A[stage, k] * K[k, j]
    out[j] = y[j] + h * acc


@njit(cache=True, _nrt=False)
def stage_input(y, K, h, stage, out):
    """State at which stage ``stage`` (1…5) is evaluated: y + h·Σ_k A[stage, k]·K[k].

    The caller evaluates its right-hand side there into K[stage]; after stage 5 it calls
    :func:`advance` and evaluates K[6] at (t + h, y_new). (Keeping the right-hand side out of
    this module lets the compiled solver be cached on disk: numba cannot cache a function that
    receives another compiled function as an argument.)
    """
    for j in range(y.shape[0]):
        _stage_input_at(y, K, h, stage, out, j)


@njit(cache=True, inline="always")
def _advance_at(y, K, h, y_new, j):
    acc = 0.0
    for k in range(6):
        acc += BW[k] * K[k, j]
    y_new[j] = y[j] + h * acc


@njit(cache=True, inline="always")
def advance(y, K, h, y_new):
    """5th-order solution y + h·Σ b_k K[k] into ``y_new``."""
    for j in range(y.shape[0]):
        _advance_at(y, K, h, y_new, j)


@njit(cache=True, inline="always")
def _error_term_at(y, y_new, K, h, rtol, atol, j):
    """Component ``j``'s squared scaled error (h·e/scale)² of :func:`error_norm`."""
    e = 0.0
    for k in range(7):
        e += E[k] * K[k, j]
    scale = atol + rtol * max(abs(y[j]), abs(y_new[j]))
    return (h * e / scale) ** 2


@njit(cache=True, inline="always")
def error_norm(y, y_new, K, h, rtol, atol, n_controlled):
    """RMS of the local error estimate scaled by atol + rtol·max(|y|, |y_new|)."""
    total = 0.0
    for j in range(n_controlled):
        total += _error_term_at(y, y_new, K, h, rtol, atol, j)
    return np.sqrt(total / n_controlled)


@njit(cache=True, inline="always")
def _prepare_dense_nested_at(K, h, F, j):
    c1 = 0.0
    c2 = 0.0
    c3 = 0.0
    c4 = 0.0
    for k in range(7):
        c1 += K[k, j] * P[k, 0]
        c2 += K[k, j] * P[k, 1]
        c3 += K[k, j] * P[k, 2]
        c4 += K[k, j] * P[k, 3]
    c1 *= h
    c2 *= h
    c3 *= h
    c4 *= h
    F[0, j] = c1 + c2 + c3 + c4
    F[1, j] = -c2 - c3 - c4
    F[2, j] = -c3 - 2.0 * c4
    F[3, j] = c4
    for k in range(4, F.shape[0]):
        F[k, j] = 0.0


@njit(cache=True, _nrt=False)
def prepare_dense_nested(y, K, h, F):
    """The dense output of the step written in DOP853's nested form (see ``dop853.dense``), so one
    evaluator serves both methods: y + x(F0 + (1−x)(F1 + x(F2 + (1−x)F3))), F4…F6 = 0.

    With the quartic y + c1 x + c2 x² + c3 x³ + c4 x⁴ of this method, F3 = c4,
    F2 = −c3 − 2c4, F1 = −c2 − c3 − c4 and F0 = c1 + c2 + c3 + c4.
    """
    for j in range(y.shape[0]):
        _prepare_dense_nested_at(K, h, F, j)


# --- The same steps on part of the state (see the note in dop853.py) -------------------------


@njit(cache=True, _nrt=False)
def stage_input_on(y, K, h, stage, out, act, m):
    """:func:`stage_input` computed on the components act[:m] only; the others get y + 0.0."""
    if m == act.shape[0]:  # every component moves: no indirection
        stage_input(y, K, h, stage, out)
        return
    for q in range(m):
        _stage_input_at(y, K, h, stage, out, act[q])
    hold_still(y, out, act, m)


@njit(cache=True, inline="always")
def advance_on(y, K, h, y_new, act, m):
    """:func:`advance` computed on the components act[:m] only; the others get y + 0.0."""
    if m == act.shape[0]:  # every component moves: no indirection
        advance(y, K, h, y_new)
        return
    for q in range(m):
        _advance_at(y, K, h, y_new, act[q])
    hold_still(y, y_new, act, m)


@njit(cache=True, inline="always")
def error_norm_on(y, y_new, K, h, rtol, atol, n_controlled, act, m):
    """:func:`error_norm` summed over act[:m] (sorted; those below ``n_controlled``)."""
    if m == act.shape[0]:  # every component moves: no indirection
        return error_norm(y, y_new, K, h, rtol, atol, n_controlled)
    total = 0.0
    for q in range(m):
        j = act[q]
        if j < n_controlled:
            total += _error_term_at(y, y_new, K, h, rtol, atol, j)
    return np.sqrt(total / n_controlled)


@njit(cache=True, _nrt=False)
def prepare_dense_nested_on(y, K, h, F, act, m):
    """:func:`prepare_dense_nested` computed on act[:m] only; the others get zeros."""
    if m == act.shape[0]:  # every component moves: no indirection
        prepare_dense_nested(y, K, h, F)
        return
    for q in range(m):
        _prepare_dense_nested_at(K, h, F, act[q])
    interpolate_still(F, act, m)
