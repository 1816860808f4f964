"""The compiled Dormand–Prince 8(5,3) toolkit (rocking.integrators.dop853).

A tiny compiled driver (fixed step and scipy's adaptive controller) runs the stage loop a caller
writes; it is checked for the one-step and global orders on y' = −y, the harmonic oscillator
and a nonlinear pendulum, and against scipy's DOP853 (step, error norm, dense output).
"""

import math

import numpy as np
import pytest
from numba import njit
from scipy.integrate import DOP853, solve_ivp
from scipy.integrate._ivp import dop853_coefficients as sc
from scipy.integrate._ivp.rk import rk_step

from rocking.integrators import dop853 as d

# --- right-hand sides -----------------------------------------------------------------------
# One compiled right-hand side chosen by an integer, like the solver's single `rhs`: the drivers
# below are then compiled once (a compiled function passed as an argument would compile them
# once per right-hand side, and could not be cached anyway).

DECAY, OSCILLATOR, PENDULUM = 0, 1, 2


@njit
def rhs(kind, t, y, out):
    if kind == DECAY:
        out[0] = -y[0]
    elif kind == OSCILLATOR:
        out[0] = y[1]
        out[1] = -y[0]
    else:
        out[0] = y[1]
        out[1] = -math.sin(y[0])


def py_pend(t, y):
    return np.array([y[1], -math.sin(y[0])])


# --- the driver a caller writes ------------------------------------------------------------


@njit
def step(kind, t, y, h, K, work, y_new):
    """One DOP853 step; K[0] = f(t, y) on entry, K[FSAL] = f(t + h, y_new) on exit."""
    for stage in range(1, d.N_STAGES):
        d.stage_input(y, K, h, stage, work)
        rhs(kind, t + d.C[stage] * h, work, K[stage])
    d.advance(y, K, h, y_new)
    rhs(kind, t + h, y_new, K[d.FSAL])


@njit
def with_dense(kind, t, y, y_new, h, K, work, F):
    """The three extra stages, then the interpolant's coefficients F."""
    for j in range(d.N_EXTRA):
        d.extra_stage_input(y, K, h, j, work)
        rhs(kind, t + d.C_EXTRA[j] * h, work, K[d.FSAL + 1 + j])
    d.prepare_dense(y, y_new, K, h, F)


@njit
def fixed(kind, t0, y0, h, n):
    y = y0.copy()
    y_new = np.empty_like(y)
    work = np.empty_like(y)
    K = np.empty((d.N_K, y.shape[0]))
    rhs(kind, t0, y, K[0])
    for i in range(n):
        step(kind, t0 + i * h, y, h, K, work, y_new)
        y[:] = y_new
        K[0] = K[d.FSAL]
    return y


@njit
def one_step(kind, t, y, h):
    """y_new, K (all 16 rows), F of a single step."""
    n = y.shape[0]
    K = np.empty((d.N_K, n))
    work = np.empty(n)
    y_new = np.empty(n)
    F = np.empty((d.INTERPOLATOR_POWER, n))
    rhs(kind, t, y, K[0])
    step(kind, t, y, h, K, work, y_new)
    with_dense(kind, t, y, y_new, h, K, work, F)
    return y_new, K, F


@njit
def adaptive(kind, t0, y0, t_end, h0, rtol, atol, max_steps):
    """scipy's RungeKutta step-size control (SAFETY 0.9, factors in [0.2, 10]); returns the
    accepted times, the final state, the number of rejections and the largest interpolation
    error of y at the step midpoints against the fine fixed-step solution."""
    n = y0.shape[0]
    y = y0.copy()
    y_new = np.empty(n)
    work = np.empty(n)
    K = np.empty((d.N_K, n))
    ts = np.empty(max_steps + 1)
    ts[0] = t0
    t = t0
    h_abs = h0
    rhs(kind, t, y, K[0])
    n_acc = 0
    n_rej = 0
    while t < t_end and n_acc < max_steps:
        rejected = False
        while True:
            t_new = t + h_abs
            if t_new > t_end:
                t_new = t_end
            h = t_new - t
            h_abs = abs(h)
            step(kind, t, y, h, K, work, y_new)
            err = d.error_norm(y, y_new, K, h, rtol, atol, n)
            if err < 1.0:
                factor = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-d.ERROR_EXPONENT))
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(0.2, 0.9 * err ** (-d.ERROR_EXPONENT))
            rejected = True
            n_rej += 1
        t = t_new
        y[:] = y_new
        K[0] = K[d.FSAL]
        n_acc += 1
        ts[n_acc] = t
    return ts[: n_acc + 1], y, n_rej


PROBLEMS = {
    "decay": (DECAY, np.array([1.0]), lambda t: np.array([math.exp(-t)])),
    "oscillator": (OSCILLATOR, np.array([1.0, 0.0]), lambda t: np.array([math.cos(t), -math.sin(t)])),
    "pendulum": (PENDULUM, np.array([0.5, 1.0]), None),
}


def reference(kind, y0, t, exact, n=256):
    """Exact solution, or the fixed-step solution with a tiny step (error ≪ 1e-16)."""
    return exact(t) if exact is not None else fixed(kind, 0.0, y0, t / n, n)


# --- tableau ---------------------------------------------------------------------------------


def test_tableau_matches_scipy_and_is_consistent():
    n = d.N_STAGES
    assert n == 12 and d.ORDER == 8 and d.ERROR_EXPONENT == 1 / 8
    assert d.N_K == 16 and d.FSAL == 12 and d.N_EXTRA == 3 and d.INTERPOLATOR_POWER == 7
    assert np.array_equal(d.C, sc.C[:n])
    assert np.array_equal(d.A, sc.A[:n, :n])
    assert np.array_equal(d.B, sc.B)
    assert np.array_equal(d.E3, sc.E3) and np.array_equal(d.E5, sc.E5)
    assert np.array_equal(d.C_EXTRA, sc.C[n + 1 :])
    assert np.array_equal(d.A_EXTRA, sc.A[n + 1 :])
    assert np.array_equal(d.D, sc.D)
    # Row sums are the nodes; the weights integrate polynomials up to degree 7 exactly.
    assert np.allclose(d.A.sum(axis=1), d.C, atol=1e-14)
    assert np.allclose(d.A_EXTRA.sum(axis=1), d.C_EXTRA, atol=1e-14)
    for q in range(8):
        assert d.B @ d.C**q == pytest.approx(1 / (q + 1), abs=1e-14)
    assert np.tril(d.A, -1).tolist() == d.A.tolist()
    assert abs(d.E3.sum()) < 1e-14 and abs(d.E5.sum()) < 1e-14


def test_tables_are_read_only():
    # Numba compiles the module's arrays into the machine code as constants; a write from Python
    # would change what Python sees and not what the compiled steps use. So none can be written.
    for name in ("C", "A", "B", "E3", "E5", "C_EXTRA", "A_EXTRA", "D", "EXTRA_COLS", "EXTRA_VALS", "D_COLS",
                 "D_VALS"):
        table = getattr(d, name)
        with pytest.raises(ValueError, match="read-only"):
            table.flat[0] = table.flat[0]


# The same step, dense output and error norms, as a script run both compiled (here) and in the
# interpreter (a subprocess with NUMBA_DISABLE_JIT=1), on the pendulum, on all components and on
# part of them (act = [1], the partial functions' indirection).
_STEP_SCRIPT = """
import math
import numpy as np
from rocking.integrators import dop853 as d


def f(t, y, out):
    out[0] = y[1]
    out[1] = -math.sin(y[0])


def run():
    n, t, h = 2, 0.0, 0.1
    y, y_new, work = np.array([1.0, 0.3]), np.zeros(n), np.zeros(n)
    K = np.zeros((d.FSAL + 1 + d.N_EXTRA, n))
    F = np.zeros((d.INTERPOLATOR_POWER, n))
    f(t, y, K[0])
    for stage in range(1, d.N_STAGES):
        d.stage_input(y, K, h, stage, work)
        f(t + d.C[stage] * h, work, K[stage])
    d.advance(y, K, h, y_new)
    f(t + h, y_new, K[d.FSAL])
    for j in range(d.N_EXTRA):
        d.extra_stage_input(y, K, h, j, work)
        f(t + d.C_EXTRA[j] * h, work, K[d.FSAL + 1 + j])
    d.prepare_dense(y, y_new, K, h, F)
    out = {"y_new": y_new.copy(), "F": F.copy(), "norm": [d.error_norm(y, y_new, K, h, 1e-6, 1e-8, n)]}
    for x in (0.3, 0.7):
        d.dense(y, F, x, work)
        out[f"dense {x}"] = work.copy()
    act = np.array([1, 0])
    part, F_part = np.zeros(n), np.zeros((d.INTERPOLATOR_POWER, n))
    for stage in range(1, d.N_STAGES):
        d.stage_input_on(y, K, h, stage, part, act, 1)
        out[f"stage {stage} on"] = part.copy()
    d.advance_on(y, K, h, part, act, 1)
    out["advance on"] = part.copy()
    out["norm on"] = [d.error_norm_on(y, y_new, K, h, 1e-6, 1e-8, n, act, 1)]
    for j in range(d.N_EXTRA):
        d.extra_stage_input_on(y, K, h, j, part, act, 1)
        out[f"extra {j} on"] = part.copy()
    d.prepare_dense_on(y, y_new, K, h, F_part, act, 1)
    out["F on"] = F_part.copy()
    d.dense_on(y, F_part, 0.3, part, act, 1)
    out["dense on"] = part.copy()
    return {key: np.asarray(v, dtype=float).tolist() for key, v in out.items()}
"""


def test_the_step_runs_uncompiled_with_every_index_checked():
    """Compiled code checks no index: a loop one row too long (the interpolant's D rows run to
    ``INTERPOLATOR_POWER + 3``) writes past the end of F, where nothing may notice. The
    interpreter checks every one. So the same step runs both ways, and must agree to rounding
    (the interpreter may round a sum differently from the compiled code: 1e-14 of the scale)."""
    import json
    import os
    import subprocess
    import sys

    namespace = {}
    exec(_STEP_SCRIPT, namespace)
    compiled = namespace["run"]()
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    proc = subprocess.run([sys.executable, "-c", _STEP_SCRIPT + "\nimport json\nprint(json.dumps(run()))"],
                          env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    interpreted = json.loads(proc.stdout.strip().splitlines()[-1])
    assert interpreted.keys() == compiled.keys()
    for key in compiled:
        np.testing.assert_allclose(interpreted[key], compiled[key], rtol=1e-14, atol=1e-15, err_msg=key)


# --- orders ----------------------------------------------------------------------------------


@pytest.mark.parametrize("name", PROBLEMS)
def test_local_error_order_nine(name):
    """Halving h divides the one-step error by ≈ 2⁹ (local error O(h⁹)). The pendulum starts at
    (0.5, 1): from other states its error constant is small enough that h¹⁰ terms still show."""
    kind, y0, exact = PROBLEMS[name]
    hs = [0.5, 0.25] if exact is not None else [0.8, 0.4, 0.2]
    errs = [np.abs(fixed(kind, 0.0, y0, h, 1) - reference(kind, y0, h, exact, 64)).max() for h in hs]
    for e_big, e_small in zip(errs, errs[1:]):
        assert 1e-15 < e_small < e_big
        assert 8.5 < math.log2(e_big / e_small) < 9.8, errs


@pytest.mark.parametrize("name", PROBLEMS)
def test_global_convergence_order_eight(name):
    """Halving h divides the error at a fixed end time by ≈ 2⁸ (errors kept above roundoff)."""
    kind, y0, exact = PROBLEMS[name]
    cases = {"decay": (4.0, [4, 8, 16]), "oscillator": (10.0, [10, 20, 40]), "pendulum": (10.0, [20, 40, 80])}
    T, ns = cases[name]
    if name == "pendulum":
        y0 = np.array([1.0, 0.5])  # (0.5, 1) is still pre-asymptotic (ratios ≈ 2^7.7) at these h
    ref = reference(kind, y0, T, exact, 4000)
    errs = [np.abs(fixed(kind, 0.0, y0, T / n, n) - ref).max() for n in ns]
    for e_big, e_small in zip(errs, errs[1:]):
        assert 1e-14 < e_small < e_big
        assert 7.6 < math.log2(e_big / e_small) < 8.5, errs


def test_fine_pendulum_reference_agrees_with_scipy():
    """The fine fixed-step pendulum reference agrees with scipy at a tight tolerance."""
    y0 = np.array([1.0, 0.5])
    ours = fixed(PENDULUM, 0.0, y0, 10.0 / 4000, 4000)
    sol = solve_ivp(py_pend, (0.0, 10.0), y0, method="DOP853", rtol=1e-13, atol=1e-13)
    assert np.allclose(ours, sol.y[:, -1], rtol=0, atol=1e-11)


# --- one step against scipy ------------------------------------------------------------------


@pytest.mark.parametrize("h", [0.3, 0.05, -0.2])
def test_step_matches_scipy_rk_step(h):
    y0 = np.array([0.9, -0.4])
    t0 = 0.7
    y_new, K, _ = one_step(PENDULUM, t0, y0, h)
    K_sp = np.empty((d.N_STAGES + 1, 2))
    y_sp, f_sp = rk_step(py_pend, t0, y0, py_pend(t0, y0), h, DOP853.A, DOP853.B, DOP853.C, K_sp)
    assert np.allclose(y_new, y_sp, rtol=1e-13, atol=1e-15)
    assert np.allclose(K[: d.N_STAGES + 1], K_sp, rtol=1e-13, atol=1e-15)
    assert np.allclose(K[d.FSAL], f_sp, rtol=1e-13, atol=1e-15)


def _forced_scipy_step(fun, t0, y0, h):
    """One step of scipy's DOP853 forced to size h (huge tolerances: the step is accepted)."""
    solver = DOP853(fun, t0, y0, t_bound=t0 + 100 * h, first_step=h, rtol=1e3, atol=1e3)
    solver.step()
    assert solver.status == "running" and solver.t == pytest.approx(t0 + h, rel=1e-15)
    return solver


def test_step_dense_output_and_error_norm_match_scipy_solver():
    y0 = np.array([1.2, 0.3])
    t0, h = 0.25, 0.4
    solver = _forced_scipy_step(py_pend, t0, y0, h)
    y_new, K, F = one_step(PENDULUM, t0, y0, h)
    assert np.allclose(y_new, solver.y, rtol=1e-13, atol=1e-15)

    # The dense output: same coefficients, same values (scipy's alternating x, 1 − x form).
    # F[3:] = h·D·K sums terms of size ~500·h·|K| down to ~1e-6: both sides carry roundoff of
    # that cancellation (≈ 1e-9 relative, ours no worse than scipy's), hence the absolute bound.
    dense_sp = solver.dense_output()
    assert np.allclose(F, dense_sp.F, rtol=0, atol=1e-13 * h * np.abs(K).max())
    out = np.empty(2)
    for x in np.linspace(0.0, 1.0, 17):
        d.dense(y0, F, x, out)
        assert np.allclose(out, dense_sp(t0 + x * h), rtol=1e-13, atol=1e-15)
    d.dense(y0, F, 0.0, out)
    assert np.array_equal(out, y0)
    d.dense(y0, F, 1.0, out)
    assert np.allclose(out, y_new, rtol=1e-15, atol=1e-16)

    # The error norm of the same stages (scipy's K), at tolerances that make it of order one.
    # Σ E5·K cancels ~8 digits here (terms ~1, sum ~1e-7), so the order of summation (ours vs
    # numpy's dot) shows at ~1e-10 relative, and our own K (equal to scipy's to ~1e-15) at ~1e-8;
    # without cancellation (test_error_norm_equals_scipy_formula) the agreement is ~1e-15.
    K_sp = np.zeros((d.N_K, 2))
    K_sp[: d.N_STAGES + 1] = solver.K
    for rtol, atol in [(1e-10, 1e-12), (1e-6, 1e-9), (0.0, 1e-8)]:
        scale = atol + rtol * np.maximum(np.abs(y0), np.abs(solver.y))
        ours = d.error_norm(y0, solver.y, K_sp, h, rtol, atol, 2)
        theirs = solver._estimate_error_norm(solver.K, h, scale)
        assert ours == pytest.approx(theirs, rel=1e-9)
        assert d.error_norm(y0, y_new, K, h, rtol, atol, 2) == pytest.approx(theirs, rel=1e-6)


def test_error_norm_equals_scipy_formula():
    rng = np.random.default_rng(7)
    solver = DOP853(lambda t, y: -y, 0.0, np.ones(5), 1.0)
    for _ in range(20):
        n = 5
        K = rng.normal(size=(d.N_K, n))
        y = rng.normal(size=n)
        y_new = y + 0.1 * rng.normal(size=n)
        h = rng.uniform(-0.5, 0.5)
        rtol, atol = 10 ** rng.uniform(-10, -3), 10 ** rng.uniform(-12, -6)
        scale = atol + rtol * np.maximum(np.abs(y), np.abs(y_new))
        for m in (n, 3):  # only the first m components are controlled
            theirs = solver._estimate_error_norm(K[: d.N_STAGES + 1, :m], h, scale[:m])
            assert d.error_norm(y, y_new, K, h, rtol, atol, m) == pytest.approx(theirs, rel=1e-13)
    zero = np.zeros((d.N_K, 2))
    assert d.error_norm(np.ones(2), np.ones(2), zero, 0.1, 1e-6, 1e-9, 2) == 0.0
    # The 3rd-order estimate exactly zero, the 5th-order one not (K on two stages whose E3 terms
    # cancel to the bit): the norm is |h|·‖e5‖/√n, as scipy's, not the 0 of two vanishing estimates.
    K = np.zeros((d.N_K, 2))
    K[5, :], K[7, :] = d.E3[7], -d.E3[5]
    y = np.ones(2)
    theirs = solver._estimate_error_norm(K[: d.N_STAGES + 1], 0.1, 1e-9 + 1e-6 * y)
    assert theirs > 0.0 and d.error_norm(y, y, K, 0.1, 1e-6, 1e-9, 2) == pytest.approx(theirs, rel=1e-13)


# --- dense output accuracy -------------------------------------------------------------------


def test_one_dense_component_and_sums_of_them_are_the_dense_output():
    # dense_component does dense's arithmetic for one component, in the same order (y + the
    # nested product), so the bits agree; dense_sum adds the components it names. Random
    # coefficients of both signs over several scales, x across and at the ends of the step.
    rng = np.random.default_rng(7)
    y = rng.normal(size=9) * 10.0 ** rng.integers(-3, 3, size=9)
    F = rng.normal(size=(d.INTERPOLATOR_POWER, 9)) * 10.0 ** rng.integers(-6, 1, size=(d.INTERPOLATOR_POWER, 9))
    out = np.empty(9)
    for x in [0.0, 1.0, *rng.uniform(0.0, 1.0, size=20)]:
        d.dense(y, F, x, out)
        for j in range(9):
            assert d.dense_component(y, F, x, j) == out[j]
        assert d.dense_sum(y, F, x, 2, 3, 3) == out[2] + out[5] + out[8]


@pytest.mark.parametrize("name", PROBLEMS)
def test_dense_output_interpolates_within_a_step(name):
    kind, y0, exact = PROBLEMS[name]
    t0, h = 0.0, 0.1
    _, _, F = one_step(kind, t0, y0, h)
    out = np.empty_like(y0)
    worst = 0.0
    for x in np.linspace(0.0, 1.0, 21)[1:]:
        d.dense(y0, F, x, out)
        ref = reference(kind, y0, x * h, exact, 16)
        worst = max(worst, np.abs(out - ref).max() / np.abs(ref).max())
    assert worst < 1e-12


def test_dense_output_order_seven():
    """The interpolant's error at mid-step falls as h⁸ (7th-order dense output)."""
    kind, y0, _ = PROBLEMS["oscillator"]
    errs = []
    out = np.empty(2)
    for h in (1.0, 0.5):
        _, _, F = one_step(kind, 0.0, y0, h)
        d.dense(y0, F, 0.5, out)
        errs.append(np.abs(out - np.array([math.cos(h / 2), -math.sin(h / 2)])).max())
    assert 7.5 < math.log2(errs[0] / errs[1]) < 9.0, errs


# --- adaptive driver -------------------------------------------------------------------------


@pytest.mark.parametrize("rtol, atol", [(1e-6, 1e-9), (1e-9, 1e-12), (1e-12, 1e-14)])
def test_adaptive_driver_follows_scipy(rtol, atol):
    """scipy's controller on our step: the same accepted and rejected steps as solve_ivp's DOP853.

    The error estimate cancels ~8 digits, so its roundoff differs in the 8th digit between the
    two implementations: the step sizes agree to that level, not to the last bit."""
    y0 = np.array([1.0, 0.5])
    h0 = 0.01
    ts, y_end, n_rej = adaptive(PENDULUM, 0.0, y0, 20.0, h0, rtol, atol, 10_000)
    sol = solve_ivp(py_pend, (0.0, 20.0), y0, method="DOP853", rtol=rtol, atol=atol, first_step=h0)
    assert len(ts) == len(sol.t)
    assert sol.nfev == 1 + d.N_STAGES * (len(ts) - 1 + n_rej)
    assert n_rej > 0
    assert np.allclose(ts, sol.t, rtol=0, atol=1e-6)
    assert np.allclose(y_end, sol.y[:, -1], rtol=0, atol=1e-12)


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_adaptive_driver_meets_tolerance(rtol):
    kind, y0, exact = PROBLEMS["oscillator"]
    ts, y_end, _ = adaptive(kind, 0.0, y0, 10.0, 1e-3, rtol, 1e-14, 10_000)
    assert ts[-1] == 10.0
    assert np.abs(y_end - exact(10.0)).max() < 100 * rtol
