"""Lemke's complementary pivoting for small dense linear complementarity problems.

Find z with  w = M z + q,  w ≥ 0,  z ≥ 0,  wᵀz = 0.

Used by the Moreau–Jean time stepping of a block stack (``rocking.stack.timestepping``), where
M has at most a few tens of rows, is copositive (the 2-D Coulomb friction LCP) and is often
degenerate: a block resting on two corners is statically indeterminate, and the tangential rows
of the two corners of one interface are parallel or nearly so. What keeps the pivoting sound on
such problems:

* the ratio test is Harris's two-pass test (``_ratio_test``): among the rows that block within a
  step overshooting the minimum ratio by at most a tiny slack, it takes the largest pivot, and
  breaks remaining ties lexicographically (rows of B⁻¹ over the pivot column). The textbook
  test takes a tiny pivot (1e-7) when its row has a zero ratio and blows the tableau up;
* basic values that round-off leaves slightly negative are reset to 0 after each pivot;
* if the pivoting still fails (ray termination, pivot budget, inaccurate answer), it is run
  again on M + εI for ε = 1e-10, 1e-8, 1e-6 (relative to the size of M and q): a strictly
  copositive perturbation that removes the degeneracy. Whatever comes out is accepted only if it
  solves the *original* LCP within the tolerance ``check``.

A pivot budget guards against cycling; every failure raises LCPError rather than returning a
wrong answer.

Example
-------
>>> import numpy as np
>>> z = lemke(np.array([[2.0, 1.0], [1.0, 2.0]]), np.array([-5.0, -6.0]))
>>> np.round(z, 12).tolist()
[1.333333333333, 2.333333333333]
"""

from __future__ import annotations

import numpy as np

__all__ = ["LCPError", "lemke"]

# Regularisations tried in turn, relative to max(1, |M|, |q|): 0 first (the plain problem).
_REGULARISATIONS = (0.0, 1e-10, 1e-8, 1e-6)


class LCPError(RuntimeError):
    """Lemke's method did not find a solution (ray termination, pivot budget, bad residual)."""


def lemke(M, q, *, max_pivots: int | None = None, tol: float = 1e-10, slack: float = 1e-9,
          check: float = 1e-6) -> np.ndarray:
    """Solve the LCP (M, q) by Lemke's method with the covering vector d = (1, …, 1).

    M and q should be scaled so that their entries are O(1) at most (the tolerances are
    relative to s = max(1, |M|, |q|)).

    Parameters
    ----------
    M : (n, n) array_like
    q : (n,) array_like
    max_pivots : int, optional
        Budget of pivots per attempt (default 50 n + 50).
    tol : float
        Relative size below which a column entry is not a pivot, and below which q counts as
        non-negative (z = 0 returned without pivoting).
    slack : float
        Harris's tolerance: a pivot may leave a basic value at −slack·max(1, |q|) (reset to 0).
    check : float
        Accepted residual of the answer: min(w) ≥ −r and |min(w_i, z_i)| ≤ r for every i,
        with r = s·(check + min(1e-12·max z, check)).

    Returns
    -------
    z : (n,) ndarray, z ≥ 0.

    Raises
    ------
    LCPError
        If no attempt (plain, then regularised) gives an answer that passes ``check``: for
        copositive M, Lemke's method ray-terminates when the LCP has no solution.
    """
    M = np.asarray(M, dtype=float)
    q = np.asarray(q, dtype=float).ravel()
    n = q.size
    if M.shape != (n, n):
        raise ValueError(f"lemke: M must be ({n}, {n}) for q of length {n}, got {M.shape}")
    if not (np.all(np.isfinite(M)) and np.all(np.isfinite(q))):
        raise LCPError("lemke: M and q must be finite")
    scale = max(1.0, float(np.abs(M).max(initial=0.0)), float(np.abs(q).max(initial=0.0)))
    if n == 0 or q.min() >= -tol * scale:  # z = 0 solves it (up to round-off in q)
        return np.zeros(n)
    if max_pivots is None:
        max_pivots = 50 * n + 50
    slack_abs = slack * max(1.0, float(np.abs(q).max()))
    failures = []
    for eps in _REGULARISATIONS:
        try:
            z = _pivoting(M + eps * scale * np.eye(n), q, max_pivots, tol, slack_abs)
        except LCPError as exc:
            failures.append(f"ε = {eps:g}: {exc}")
            continue
        residual = _residual(M, q, z)
        # Round-off in w grows with |z|, hence the second term (far below check·s for |z| ≲ 10⁵).
        # It is capped at check·s: a blown-up z (10¹⁵ from a tableau gone singular) would
        # otherwise excuse any residual, and a problem without solution would return garbage.
        if residual <= scale * (check + min(1e-12 * float(z.max(initial=0.0)), check)):
            return z
        failures.append(f"ε = {eps:g}: inaccurate answer (residual {residual:.3g})")
    raise LCPError("lemke: no solution found (n = %d); %s" % (n, "; ".join(failures)))


def _pivoting(M: np.ndarray, q: np.ndarray, max_pivots: int, tol: float, slack: float) -> np.ndarray:
    """One run of Lemke's method; raises LCPError on ray termination or an exhausted budget."""
    n = q.size
    # Tableau of  I w − M z − d z0 = q  in the current basis: its first n columns are B⁻¹
    # (they start as the identity), which the lexicographic tie-break reads.
    z0 = 2 * n
    tableau = np.hstack([np.eye(n), -M, -np.ones((n, 1))])
    rhs = q.copy()
    basis = np.arange(n)  # basic variable of each row: 0…n−1 = w_i, n…2n−1 = z_i, 2n = z0

    # First pivot: z0 enters at the value that makes every w ≥ 0, i.e. it replaces the row
    # with the most negative q (ties: the last such row, the lexicographic choice for B = I).
    row = int(np.flatnonzero(rhs <= rhs.min() + tol * max(1.0, abs(rhs.min())))[-1])
    leaving = _pivot(tableau, rhs, basis, row, z0)
    for _ in range(max_pivots):
        entering = leaving + n if leaving < n else leaving - n  # the complement of what left
        row = _ratio_test(tableau, rhs, basis, entering, z0, tol, slack)
        leaving = _pivot(tableau, rhs, basis, row, entering)
        if leaving == z0:
            z = np.zeros(n)
            is_z = (basis >= n) & (basis < 2 * n)
            z[basis[is_z] - n] = rhs[is_z]
            return z
    raise LCPError(f"no solution within {max_pivots} pivots (cycling?)")


def _pivot(tableau: np.ndarray, rhs: np.ndarray, basis: np.ndarray, row: int, col: int) -> int:
    """Gauss–Jordan pivot on (row, col) in place; returns the variable that leaves the basis."""
    pivot = tableau[row, col]
    tableau[row] /= pivot
    rhs[row] /= pivot
    factor = tableau[:, col].copy()
    factor[row] = 0.0
    tableau -= np.outer(factor, tableau[row])
    rhs -= factor * rhs[row]
    # Basic values are ≥ 0 in exact arithmetic; a negative one (round-off, or Harris's slack)
    # would give a negative ratio that wins the next ratio test and derails the method.
    np.maximum(rhs, 0.0, out=rhs)
    leaving = int(basis[row])
    basis[row] = col
    return leaving


def _ratio_test(tableau: np.ndarray, rhs: np.ndarray, basis: np.ndarray, entering: int, z0: int,
                tol: float, slack: float) -> int:
    """Row that leaves when ``entering`` enters.

    Harris's two-pass ratio test: the step may overshoot the exact minimum ratio as long as no
    basic value goes below −``slack``; among the rows that block within that step, take z0 if
    it is one (it ends the method), else the largest pivot, else (equal pivots) the
    lexicographic minimum of the rows of B⁻¹ over the column.
    """
    column = tableau[:, entering]
    rows = np.flatnonzero(column > tol * max(1.0, float(np.abs(column).max())))
    if rows.size == 0:
        raise LCPError("ray termination")
    bound = ((rhs[rows] + slack) / column[rows]).min()
    rows = rows[rhs[rows] / column[rows] <= bound]
    if np.any(basis[rows] == z0):
        return int(rows[basis[rows] == z0][0])
    pivots = column[rows]
    rows = rows[pivots >= (1.0 - 1e-9) * pivots.max()]
    for j in range(tableau.shape[0]):  # column j of B⁻¹ is tableau column j (the w_j column)
        if rows.size == 1:
            break
        values = tableau[rows, j] / column[rows]
        rows = rows[values <= values.min() + tol * max(1.0, abs(values.min()))]
    return int(rows[0])


def _residual(M: np.ndarray, q: np.ndarray, z: np.ndarray) -> float:
    """max(−min w, max |min(w_i, z_i)|) with w = Mz + q: zero exactly for a solution."""
    w = M @ z + q
    return max(0.0, -float(w.min()), float(np.abs(np.minimum(w, z)).max()), -float(z.min()))
