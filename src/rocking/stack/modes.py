"""Which way every interface moves: the contact problem solved exactly, by enumeration, compiled.

At every event the solver asks which mode each interface takes. Normal state: ``OPEN`` (no
contact), ``ROCK`` (on its anchor corner; the other end open) or ``FLAT`` (both ends closed).
Tangential state of a closed interface: ``STICK`` or slipping towards ±x (``tstate`` ±1).
A mode freezes coordinates (kinematics.py): d when closed, φ when flat, a when stuck.

For a candidate mode, Kane's equations with the frozen accelerations set to zero,

    Σ_{j free} M_ij z̈_j − Λ_i + [i = a of a slipping interface] μk·σ·Λ_d = f_i,

are linear in the free accelerations and the frozen coordinates' forces Λ; one solve gives both.
The candidate holds if its forces and accelerations satisfy the complementarity conditions
(docs/theory/stack.md §4): closed normals push (Λ ≥ 0), opening ends accelerate apart, stuck
interfaces need no more than μs·N, slipping ones start in the direction their acceleration
takes. This is the linear complementarity problem on the contact accelerations, solved by
trying its finitely many branches; the first that holds in the order of ``_CANDIDATES`` (stick
before slip, flat before rocking, open last: the most constrained first) is taken. The same
routine, with velocities for accelerations and impulses for forces, decides an impact
(``level = VELOCITY``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kinematics import (
    END_L,
    END_U,
    P_BL,
    P_BU,
    P_CAN_SLIP,
    P_HU,
    P_MU_K,
    P_MU_S,
    anchor_at,
    end_gap_gradient,
    forward,
    new_frame,
    mass_and_forces,
    relative_pose,
)

OPEN, ROCK, FLAT = 0, 1, 2
ACCELERATION, VELOCITY = 0, 1

# Candidate order for one interface: (normal state, rock on the other end?, tangential state).
# Stick before slip, then rest before rock: the order of rocking.simulate (derivation.md §5,
# "stick-rest, stick-rock, slide-rest, slide-rock"), which decides where Coulomb friction leaves
# the motion not unique (a block that may either start to rock or slide back).
_CANDIDATES = np.array(
    [
        [FLAT, 0, 0], [ROCK, 0, 0], [ROCK, 1, 0],
        [FLAT, 0, 1], [FLAT, 0, -1],
        [ROCK, 0, 1], [ROCK, 0, -1], [ROCK, 1, 1], [ROCK, 1, -1],
        [OPEN, 0, 0],
    ],
    dtype=np.int64,
)
N_CANDIDATES = 10

# Result codes of select_mode.
SELECT_OK, SELECT_NONE, SELECT_HELD = 0, 1, 2


@njit(cache=True, _nrt=False, inline="always")  # (inlined: see kinematics.forward)
def frozen_set(nstate, tstate, P, frozen):
    """frozen[i] = True for the coordinates a mode holds fixed."""
    n = nstate.shape[0]
    for k in range(n):
        i = 3 * k
        closed = nstate[k] >= ROCK
        frozen[i] = closed and (tstate[k] == 0 or P[k, P_CAN_SLIP] < 0.5)
        frozen[i + 1] = nstate[k] == FLAT
        frozen[i + 2] = closed


@njit(cache=True, _nrt=False, inline="always")  # (inlined: see kinematics.forward)
def solve_mode_in(M, f, P, nstate, tstate, x_out, lam_out, frozen, free, row_of, K, b):
    """Solve the mode's equations M z̈ = f + Λ: x_out = z̈ (or ż⁺), lam_out = Λ on frozen
    coordinates (and the friction force −μk σ Λ_d on a slipping a). Returns False if the system
    is singular. Only the columns of M of the free coordinates are read.

    The frozen coordinates have z̈ = 0, so only the rows of the free ones are solved, for their
    accelerations; each frozen row then gives its Λ = (M z̈ − f). A slipping a's row carries
    −μk σ Λ_d, with Λ_d the same expression of its interface's d, which folds into that row:
    (M_a + μk σ M_d) z̈ = f_a + μk σ f_d. The reduced system has one unknown per free coordinate
    (1 to 3 in most modes, of 3N), which is what makes a mode's right-hand side cheap.

    frozen, free, row_of (3N), K (3N × 3N) and b (3N) are scratch arrays, overwritten."""
    nz = f.shape[0]
    n = nstate.shape[0]
    frozen_set(nstate, tstate, P, frozen)
    nf = 0
    for i in range(nz):
        row_of[i] = -1
        if not frozen[i]:
            free[nf] = i
            row_of[i] = nf
            nf += 1
    for r in range(nf):
        i = free[r]
        for c in range(nf):
            K[r, c] = M[i, free[c]]
        b[r] = f[i]
    for k in range(n):
        i = 3 * k
        if nstate[k] >= ROCK and tstate[k] != 0 and P[k, P_CAN_SLIP] > 0.5:
            r = row_of[i]
            mu = P[k, P_MU_K] * tstate[k]
            for c in range(nf):
                K[r, c] += mu * M[i + 2, free[c]]
            b[r] += mu * f[i + 2]
    # Gaussian elimination with partial pivoting (nf ≤ 3N, mostly 1–3)
    for c in range(nf):
        p = c
        best = abs(K[c, c])
        for r in range(c + 1, nf):
            if abs(K[r, c]) > best:
                best = abs(K[r, c])
                p = r
        if best == 0.0 or not math.isfinite(best):
            return False
        if p != c:
            for j in range(nf):
                K[c, j], K[p, j] = K[p, j], K[c, j]
            b[c], b[p] = b[p], b[c]
        for r in range(c + 1, nf):
            fac = K[r, c] / K[c, c]
            if fac != 0.0:
                for j in range(c, nf):
                    K[r, j] -= fac * K[c, j]
                b[r] -= fac * b[c]
    for r in range(nf - 1, -1, -1):
        acc = b[r]
        for j in range(r + 1, nf):
            acc -= K[r, j] * x_out[free[j]]
        x_out[free[r]] = acc / K[r, r]
    for i in range(nz):
        if frozen[i]:
            x_out[i] = 0.0
    for i in range(nz):
        if frozen[i]:
            acc = -f[i]
            for c in range(nf):
                acc += M[i, free[c]] * x_out[free[c]]
            lam_out[i] = acc
        else:
            lam_out[i] = 0.0
    for k in range(n):
        i = 3 * k
        if nstate[k] >= ROCK and tstate[k] != 0 and P[k, P_CAN_SLIP] > 0.5:
            lam_out[i] = -P[k, P_MU_K] * tstate[k] * lam_out[i + 2]
    return True


@njit(cache=True, _nrt=False)
def flat_forces(P, ends, anchor, k, z, lam):
    """(N_anchor, N_other): the normal forces (or impulses) at the two ends of a flat interface,
    from Λ_d (the total) and Λ_φ (their moment about the anchor)."""
    grad = end_gap_gradient(P, ends, anchor, k, z, 1 - anchor[k])
    i = 3 * k
    if grad[1] == 0.0:
        return lam[i + 2], 0.0
    n_other = lam[i + 1] / grad[1]
    return lam[i + 2] - n_other * grad[2], n_other


@njit(cache=True, _nrt=False)
def corner_x(P, ends, anchor, k, z):
    """x of the upper block's two bottom corners in the lower block's frame (m), for end
    identification and the slide-off check."""
    i = 3 * k
    rx, ry, _, _ = relative_pose(P, ends, anchor, k, z[i], z[i + 1], z[i + 2], 0.0, 0.0, 0.0)
    c, s = math.cos(z[i + 1]), math.sin(z[i + 1])
    bu, hu = P[k, P_BU], P[k, P_HU]
    xl = rx + c * (-bu) + s * (-hu)
    xr = rx + c * bu + s * (-hu)
    return xl, xr


@njit(cache=True)
def identify_ends(P, ends, anchor, k, z, direction, tol, out):
    """Which corner makes each end of interface k at the current pose (out[e] = (type, x)):
    the inner of the upper and lower corners; a tie goes to the one that stays inner when the
    upper block moves in ``direction`` (±1, 0 for none)."""
    xl, xr = corner_x(P, ends, anchor, k, z)
    bu, bl = P[k, P_BU], P[k, P_BL]
    # left end
    if xl > -bl + tol or (abs(xl + bl) <= tol and direction >= 0):
        out[0, 0], out[0, 1] = END_U, -bu
    else:
        out[0, 0], out[0, 1] = END_L, -bl
    if xr < bl - tol or (abs(xr - bl) <= tol and direction <= 0):
        out[1, 0], out[1, 1] = END_U, bu
    else:
        out[1, 0], out[1, 1] = END_L, bl


@njit(cache=True)
def refresh_ends(P, ends, anchor, k, z, zd, direction):
    """Set interface k's end descriptors to the corners that make its ends now (identify_ends),
    re-anchoring if the anchor's corner changed."""
    ends_new = np.empty((2, 2))
    identify_ends(P, ends, anchor, k, z, direction, 1e-12, ends_new)
    for e in range(2):
        if ends_new[e, 0] != ends[k, e, 0]:
            if e == anchor[k]:
                reanchor(P, ends, anchor, k, z, zd, e, ends_new[e, 0], ends_new[e, 1])
            else:
                ends[k, e, 0] = ends_new[e, 0]
                ends[k, e, 1] = ends_new[e, 1]


@njit(cache=True)
def reanchor(P, ends, anchor, k, z, zd, e_new, type_new, x_new):
    """Move interface k's anchor to end ``e_new`` (corner ``type_new`` at ``x_new``), keeping
    the pose; updates z, ż, ends and anchor in place."""
    i = 3 * k
    a, d, ad, dd = anchor_at(P, ends, anchor, k, z, zd, e_new, type_new, x_new)
    z[i], z[i + 2], zd[i], zd[i + 2] = a, d, ad, dd
    ends[k, e_new, 0] = type_new
    ends[k, e_new, 1] = x_new
    anchor[k] = e_new


@njit(cache=True)
def _candidate_ok(level, P, ends, anchor, geo, k, nst, tst, z, zd, x, lam, tol_force, tol_rate, check_normal):
    """Complementarity conditions of interface k for one candidate (see the module docstring)."""
    i = 3 * k
    if not check_normal:
        pass
    elif nst == FLAT:
        n_a, n_o = flat_forces(P, ends, anchor, k, z, lam)
        if n_a < -tol_force or n_o < -tol_force:
            return False
    elif nst == ROCK:
        if lam[i + 2] < -tol_force:
            return False
    else:
        if geo[k] >= ROCK and x[i + 2] < -tol_rate:
            return False
    if check_normal and nst <= ROCK and geo[k] == FLAT:
        # The other end must open: its gap rate ≥ 0 after an impulse; its gap acceleration > 0,
        # strictly, from rest (flat, tried first, holds where it is zero; a rounding-error
        # tolerance here let a block rock the wrong way round and land again 1e-8 s later, for
        # ever).
        grad = end_gap_gradient(P, ends, anchor, k, z, 1 - anchor[k])
        opening = grad[0] * x[i] + grad[1] * x[i + 1] + grad[2] * x[i + 2]
        if level == ACCELERATION:
            if not opening > 0.0:
                return False
        elif opening < -tol_rate:
            return False
    if nst >= ROCK and P[k, P_CAN_SLIP] > 0.5:
        if tst == 0:
            if abs(lam[i]) > P[k, P_MU_S] * lam[i + 2] + tol_force:
                return False
        else:
            # already slipping (ȧ ≠ 0): the direction is ȧ's (filtered by select_mode). From rest
            # the slip must start the way friction assumes, strictly (ä·σ > 0): a slip that goes
            # the other way at a rounding-error rate would be pushed along by its own friction
            # and create energy. After an impulse, σ·ȧ⁺ ≥ 0 (ȧ⁺ = 0 is a stick, tried first).
            if level == ACCELERATION:
                if zd[i] == 0.0 and not tst * x[i] > 0.0:
                    return False
            elif tst * x[i] < 0.0:
                return False
    return True


@njit(cache=True)
def select_mode(level, P, ends, anchor, geo, z, zd, ah, av, gravity, rhs_extra,
                nstate, tstate, veto_k, veto_kind, tol_force, tol_rate, x_out, lam_out, force_flat=-1, hold=False):
    """Choose the mode of every interface (fills nstate, tstate; may move anchors: ends, anchor,
    z, ż change in place). ``geo[k]`` is the geometric state (OPEN, ROCK, FLAT: which ends are
    closed now). At ``level`` ACCELERATION the solve is for z̈ and forces; at VELOCITY for ż⁺
    and impulses, with ``rhs_extra`` added (the restitution couples). ``veto_k``/``veto_kind``
    exclude the branch whose guard just fired (0: the anchor's normal force, 1: the other
    end's, 2: sticking), unless no other branch holds. ``force_flat`` (an interface, or −1)
    lands that interface flat whatever its impulses (the rest rule after an impact). ``hold``
    keeps every interface's normal state and skips the normal-force signs (the paradox rule,
    docs/theory/stack.md §5).
    Returns SELECT_OK or SELECT_NONE."""
    n = P.shape[0]
    nz = 3 * n
    A, beta, C, X, Xd, th, thd = new_frame(n)
    M = np.zeros((nz, nz))
    f = np.zeros(nz)
    # scratch of the solves, made once for all the candidates tried
    frozen, free, row_of = np.zeros(nz, dtype=np.bool_), np.empty(nz, dtype=np.int64), np.empty(nz, dtype=np.int64)
    k_red, b_red = np.empty((nz, nz)), np.empty(nz)
    # the branches each interface may take
    allowed = np.zeros((n, N_CANDIDATES), dtype=np.bool_)
    for k in range(n):
        for c in range(N_CANDIDATES):
            nst, other, tst = _CANDIDATES[c, 0], _CANDIDATES[c, 1], _CANDIDATES[c, 2]
            ok = nst <= geo[k]
            if other == 1 and geo[k] != FLAT:
                ok = False
            # (on the other end, ȧ is that corner's: its sign is checked once re-anchored, below)
            if other == 0 and nst >= ROCK and tst == 0 and level == ACCELERATION and zd[3 * k] != 0.0:
                ok = False  # a slipping interface cannot stick without an impulse
            if nst >= ROCK and tst != 0:
                if P[k, P_CAN_SLIP] < 0.5:
                    ok = False
                elif other == 0 and level == ACCELERATION and zd[3 * k] != 0.0 and tst * zd[3 * k] < 0.0:
                    ok = False
            if nst == OPEN and tst != 0:
                ok = False
            if k == force_flat:
                # the rest rule lands the interface flat and keeps its tangential state: sliding on
                # in its direction, or stuck (its tiny landing impulse decides nothing)
                a_dot = zd[3 * k]
                keep = 0 if a_dot == 0.0 or P[k, P_CAN_SLIP] < 0.5 else (1 if a_dot > 0.0 else -1)
                if nst != FLAT or tst != keep:
                    ok = False
            if (hold or (force_flat >= 0 and k != force_flat)) and (nst != geo[k] or other == 1):
                ok = False  # the rest rule lands one interface and lifts nothing else
            allowed[k, c] = ok
    z0 = z.copy()
    zd0 = zd.copy()
    ends0 = ends.copy()
    anchor0 = anchor.copy()
    built = -1  # which ends (as a bit set of re-anchored interfaces) M and f were built for
    for attempt in range(2):
        counter = np.zeros(n, dtype=np.int64)
        done = False
        while not done:
            valid = True
            for k in range(n):
                if not allowed[k, counter[k]]:
                    valid = False
                    break
                if attempt == 0 and k == veto_k:
                    c = counter[k]
                    nst, other = _CANDIDATES[c, 0], _CANDIDATES[c, 1]
                    if veto_kind == 0 and (nst == FLAT or (nst == ROCK and other == 0)):
                        valid = False
                    if veto_kind == 1 and (nst == FLAT or (nst == ROCK and other == 1)):
                        valid = False
                    if veto_kind == 2 and nst >= ROCK and _CANDIDATES[c, 2] == 0:
                        valid = False
            if valid:
                # the pose with the anchors this candidate needs (M and f depend on nothing
                # else, so candidates on the same anchors share them)
                flips = 0
                for k in range(n):
                    if _CANDIDATES[counter[k], 1] == 1:
                        flips |= 1 << k
                if flips != built:
                    z[:] = z0
                    zd[:] = zd0
                    ends[:, :, :] = ends0
                    anchor[:] = anchor0
                    for k in range(n):
                        if _CANDIDATES[counter[k], 1] == 1:
                            e = 1 - anchor[k]
                            reanchor(P, ends, anchor, k, z, zd, e, ends[k, e, 0], ends[k, e, 1])
                    forward(P, ends, anchor, z, zd, A, beta, C, X, Xd, th, thd)
                    mass_and_forces(P, A, beta, C, ah, av, gravity, M, f)
                    built = flips
                if level == VELOCITY:
                    # impulse problem: M ż⁺ = M ż⁻ + extra + Λ
                    for i in range(nz):
                        acc = rhs_extra[i]
                        for j in range(nz):
                            acc += M[i, j] * zd[j]
                        f[i] = acc
                for k in range(n):
                    c = counter[k]
                    nstate[k] = _CANDIDATES[c, 0]
                    tstate[k] = _CANDIDATES[c, 2]
                    if level == ACCELERATION and _CANDIDATES[c, 1] == 1 and zd[3 * k] != 0.0 and (
                            tstate[k] * zd[3 * k] <= 0.0):
                        # Rocking onto the other end of a slipping interface: its ȧ is now that
                        # corner's, reversed where the corner is the lower block's (the slip is
                        # measured along the other face). The slip keeps its way, in the sign of
                        # the new ȧ; a stick would need an impulse. (Checked before the
                        # re-anchoring, the old sign kept a slip that ran against its own ȧ: the
                        # stick guard fired at once and zeroed a real slip velocity, energy the
                        # ledger never saw: 21 J in a random stack whose ledger scale was 379 J.)
                        valid = False
                if valid and solve_mode_in(M, f, P, nstate, tstate, x_out, lam_out, frozen, free, row_of, k_red, b_red):
                    good = True
                    for k in range(n):
                        c = counter[k]
                        if k == force_flat:
                            continue
                        if not _candidate_ok(level, P, ends, anchor, geo, k, nstate[k], tstate[k], z, zd,
                                             x_out, lam_out, tol_force, tol_rate, force_flat < 0 and not hold):
                            good = False
                            break
                    if good:
                        return SELECT_OK
            # next candidate (mixed radix, the floor interface most significant)
            k = n - 1
            while k >= 0:
                counter[k] += 1
                if counter[k] < N_CANDIDATES:
                    break
                counter[k] = 0
                k -= 1
            if k < 0:
                done = True
        if veto_k < 0:
            break
    z[:] = z0
    zd[:] = zd0
    ends[:, :, :] = ends0
    anchor[:] = anchor0
    return SELECT_NONE
