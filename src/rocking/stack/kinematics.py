"""Geometry and equations of motion of a planar stack in interface coordinates, compiled.

docs/theory/stack.md derives everything here. In short: the pose of block k relative to the
block below (the floor for k = 1) is described by three coordinates z_k = (a, φ, d) measured at
the interface's *anchor*, one end of the contact:

* the anchor is an upper corner on the lower face (``U``): that corner sits at (a, h_l + d) in
  the lower block's frame, and the upper block is turned by φ;
* or a lower corner on the upper face (``L``): that corner sits at (a, −h_u − d) in the upper
  block's frame.

a slides along the face, d is the gap at the anchor, φ is the relative rotation, positive
clockwise (tilting towards +x), as θ in the rest of the library. A contact force at the anchor
does work only through a (tangential) and d (normal); rotating about the anchor (φ) moves it
not at all. So closing the anchor is freezing d, sticking it is freezing a, and a flat
interface freezes φ as well: every mode is a set of frozen coordinates, which stay exactly
constant while the mode lasts (no drift, no stabilisation).

Absolute poses follow from the floor up, X_k = X_{k−1} + R(Θ_{k−1}) r_k, Θ_k = Θ_{k−1} + φ_k,
with R(θ) = [[cos θ, sin θ], [−sin θ, cos θ]] (clockwise). Kane's equations give

    M(z) z̈ = f(z, ż, t) + Λ,    M = Σ_k m_k A_kᵀA_k + J_k C_kᵀC_k,   f = Σ_k A_kᵀ(F_k − m_k β_k),

with Ẍ_k = A_k z̈ + β_k, Θ̈_k = C_k z̈, F_k = (−m_k a_h, −m_k (g + a_v)) the weight and the
floor's d'Alembert force, and Λ the generalised contact forces (nonzero on frozen coordinates
and, through friction, on the a of a slipping interface).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# Columns of the parameter table P (one row per block / interface k = 0 … N−1).
(P_MASS, P_INERTIA, P_HU, P_HL, P_BU, P_BL, P_OFFSET, P_MU_S, P_MU_K, P_CAN_SLIP, P_RESTITUTION,
 P_IMPACT_PAPER) = range(12)
N_P = 12

END_U, END_L = 0, 1  # an upper corner on the lower face / a lower corner on the upper face


@njit(cache=True, inline="always")
def _rot(phi):
    return math.cos(phi), math.sin(phi)


@njit(cache=True, _nrt=False)
def relative_pose(P, ends, anchor, k, zk0, zk1, zk2, zd0, zd1, zd2):
    """Pose of block k in the frame of the block below, and its rate:
    (r_x, r_y, ṙ_x, ṙ_y), m and m/s, from z_k = (a, φ, d) and ż_k at the anchor."""
    a, phi, d = zk0, zk1, zk2
    c, s = _rot(phi)
    hu, hl = P[k, P_HU], P[k, P_HL]
    e = anchor[k]
    x = ends[k, e, 1]
    if ends[k, e, 0] == END_U:
        # corner (x, −hu) of the upper block at (a, hl + d): r = (a, hl + d) − R(φ)(x, −hu)
        cx, cy = x, -hu
        rx = a - (c * cx + s * cy)
        ry = hl + d - (-s * cx + c * cy)
        # ṙ = (ȧ, ḋ) − R E c φ̇ ;  R E = [[−s, c], [−c, −s]]
        rdx = zd0 - (-s * cx + c * cy) * zd1
        rdy = zd2 - (-c * cx - s * cy) * zd1
    else:
        # corner (x, hl) of the lower block at (a, −hu − d) in the upper frame: r = p − R w
        wx, wy = a, -hu - d
        rx = x - (c * wx + s * wy)
        ry = hl - (-s * wx + c * wy)
        wdx, wdy = zd0, -zd2
        # ṙ = −R E w φ̇ − R ẇ
        rdx = -(-s * wx + c * wy) * zd1 - (c * wdx + s * wdy)
        rdy = -(-c * wx - s * wy) * zd1 - (-s * wdx + c * wdy)
    return rx, ry, rdx, rdy


@njit(cache=True, _nrt=False)
def end_gap(P, ends, anchor, k, z, zd, e):
    """(gap, gap rate) of end ``e`` (0 left, 1 right) of interface k, m and m/s: the distance
    of its corner from the face it touches, along that face's normal (> 0 open)."""
    i = 3 * k
    return _end_gap(P, ends, anchor, k, z[i], z[i + 1], z[i + 2], zd[i], zd[i + 1], zd[i + 2], e)


@njit(cache=True, _nrt=False)
def _end_gap(P, ends, anchor, k, a, phi, d, ad, phid, dd, e):
    """:func:`end_gap` from interface k's coordinates (a, φ, d) and their rates."""
    rx, ry, rdx, rdy = relative_pose(P, ends, anchor, k, a, phi, d, ad, phid, dd)
    c, s = _rot(phi)
    w = phid
    hu, hl = P[k, P_HU], P[k, P_HL]
    x = ends[k, e, 1]
    if ends[k, e, 0] == END_U:
        # p = r + R (x, −hu);  ṗ = ṙ + R E (x, −hu) φ̇
        py = ry + (-s * x + c * (-hu))
        pdy = rdy + (-c * x - s * (-hu)) * w
        return py - hl, pdy
    # q = Rᵀ (p − r), p = (x, hl);  q̇ = −E q φ̇ − Rᵀ ṙ  (E q = (q_y, −q_x))
    dx, dy = x - rx, hl - ry
    qx = c * dx - s * dy
    qy = s * dx + c * dy
    qdy = qx * w - (s * rdx + c * rdy)
    return -hu - qy, -qdy


@njit(cache=True, _nrt=False)
def end_gap_gradient(P, ends, anchor, k, z, e):
    """∂(gap of end e)/∂(a, φ, d) of interface k at z, a 3-tuple: the rate of :func:`end_gap`
    along the three unit velocities (the gap rate is linear in ż)."""
    i = 3 * k
    a, phi, d = z[i], z[i + 1], z[i + 2]
    return (_end_gap(P, ends, anchor, k, a, phi, d, 1.0, 0.0, 0.0, e)[1],
            _end_gap(P, ends, anchor, k, a, phi, d, 0.0, 1.0, 0.0, e)[1],
            _end_gap(P, ends, anchor, k, a, phi, d, 0.0, 0.0, 1.0, e)[1])


@njit(cache=True)
def anchor_at(P, ends, anchor, k, z, zd, e_new, type_new, x_new):
    """Coordinates (a, φ, d) and rates of interface k re-expressed at another anchor (end
    ``e_new`` with corner type and position): the same relative pose, so every block stays put.
    Returns (a, d, ȧ, ḋ); φ and φ̇ do not change."""
    i = 3 * k
    rx, ry, rdx, rdy = relative_pose(P, ends, anchor, k, z[i], z[i + 1], z[i + 2], zd[i], zd[i + 1], zd[i + 2])
    c, s = _rot(z[i + 1])
    w = zd[i + 1]
    hu, hl = P[k, P_HU], P[k, P_HL]
    x = x_new
    if type_new == END_U:
        px = rx + (c * x + s * (-hu))
        py = ry + (-s * x + c * (-hu))
        pdx = rdx + (-s * x + c * (-hu)) * w
        pdy = rdy + (-c * x - s * (-hu)) * w
        return px, py - hl, pdx, pdy
    dx, dy = x - rx, hl - ry
    qx = c * dx - s * dy
    qy = s * dx + c * dy
    qdx = -qy * w - (c * rdx - s * rdy)
    qdy = qx * w - (s * rdx + c * rdy)
    return qx, -hu - qy, qdx, -qdy


# Inlined into its callers (Numba IR level): a call that passes a dozen arrays costs ~40 ns,
# as much as the kinematics of one block; inlining this, mass_and_forces_on and the mode solve
# made one evaluation of a block 143 → 100 ns (docs/theory/stack.md §9).
@njit(cache=True, _nrt=False, inline="always")
def forward(P, ends, anchor, z, zd, A, beta, C, X, Xd, theta, theta_d):
    """Absolute poses and their acceleration maps, from the floor up (fills the arrays):
    X[k], Θ[k] (centre, m; rotation, rad), Ẋ[k], Θ̇[k], and A[k] (2 × 3N), β[k], C[k] (3N)
    such that Ẍ_k = A_k z̈ + β_k and Θ̈_k = C_k z̈."""
    n = P.shape[0]
    nz = 3 * n
    px, py, pdx, pdy, pth, pthd = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    for k in range(n):
        i = 3 * k
        a, phi, d = z[i], z[i + 1], z[i + 2]
        ad, phid, dd = zd[i], zd[i + 1], zd[i + 2]
        rx, ry, rdx, rdy = relative_pose(P, ends, anchor, k, a, phi, d, ad, phid, dd)
        c, s = _rot(phi)
        hu = P[k, P_HU]
        # ∂r/∂z_k (columns a, φ, d) and the part of r̈ without z̈ (bias)
        e = anchor[k]
        x = ends[k, e, 1]
        if ends[k, e, 0] == END_U:
            cx, cy = x, -hu
            da = (1.0, 0.0)
            # −R E c
            dphi = (-(-s * cx + c * cy), -(-c * cx - s * cy))
            dd_ = (0.0, 1.0)
            # r̈ bias: + R c φ̇²
            bx = (c * cx + s * cy) * phid * phid
            by = (-s * cx + c * cy) * phid * phid
        else:
            wx, wy = a, -hu - d
            da = (-c, s)  # −R (1, 0)
            dphi = (-(-s * wx + c * wy), -(-c * wx - s * wy))
            dd_ = (s, c)  # −R (0, −1)
            wdx, wdy = ad, -dd
            # r̈ bias: R w φ̇² − 2 R E ẇ φ̇
            bx = (c * wx + s * wy) * phid * phid - 2.0 * (-s * wdx + c * wdy) * phid
            by = (-s * wx + c * wy) * phid * phid - 2.0 * (-c * wdx - s * wdy) * phid
        # rotate by the lower block's absolute angle
        cl, sl = _rot(pth)
        # R_l r, R_l E r, R_l ṙ, R_l E ṙ
        Rr = (cl * rx + sl * ry, -sl * rx + cl * ry)
        Er = (ry, -rx)
        REr = (cl * Er[0] + sl * Er[1], -sl * Er[0] + cl * Er[1])
        Rrd = (cl * rdx + sl * rdy, -sl * rdx + cl * rdy)
        Erd = (rdy, -rdx)
        RErd = (cl * Erd[0] + sl * Erd[1], -sl * Erd[0] + cl * Erd[1])
        X[k, 0] = px + Rr[0]
        X[k, 1] = py + Rr[1]
        Xd[k, 0] = pdx + REr[0] * pthd + Rrd[0]
        Xd[k, 1] = pdy + REr[1] * pthd + Rrd[1]
        theta[k] = pth + phi
        theta_d[k] = pthd + phid
        for j in range(nz):
            A[k, 0, j] = A[k - 1, 0, j] if k > 0 else 0.0
            A[k, 1, j] = A[k - 1, 1, j] if k > 0 else 0.0
            C[k, j] = C[k - 1, j] if k > 0 else 0.0
        # Θ̈_{k−1} contributes R_l E r_k to Ẍ_k
        if k > 0:
            for j in range(nz):
                cj = C[k - 1, j]
                if cj != 0.0:
                    A[k, 0, j] += REr[0] * cj
                    A[k, 1, j] += REr[1] * cj
        for col, v in ((i, da), (i + 1, dphi), (i + 2, dd_)):
            A[k, 0, col] += cl * v[0] + sl * v[1]
            A[k, 1, col] += -sl * v[0] + cl * v[1]
        C[k, i + 1] += 1.0
        bRx = cl * bx + sl * by
        bRy = -sl * bx + cl * by
        b0 = beta[k - 1, 0] if k > 0 else 0.0
        b1 = beta[k - 1, 1] if k > 0 else 0.0
        beta[k, 0] = b0 - Rr[0] * pthd * pthd + 2.0 * RErd[0] * pthd + bRx
        beta[k, 1] = b1 - Rr[1] * pthd * pthd + 2.0 * RErd[1] * pthd + bRy
        px, py, pdx, pdy, pth, pthd = X[k, 0], X[k, 1], Xd[k, 0], Xd[k, 1], theta[k], theta_d[k]


@njit(cache=True)
def new_frame(n):
    """Arrays for :func:`forward` of n blocks: (A, β, C, X, Ẋ, Θ, Θ̇)."""
    nz = 3 * n
    return (np.zeros((n, 2, nz)), np.zeros((n, 2)), np.zeros((n, nz)), np.zeros((n, 2)), np.zeros((n, 2)),
            np.zeros(n), np.zeros(n))


@njit(cache=True)
def mass_and_forces(P, A, beta, C, ah, av, gravity, M, f):
    """M = Σ m AᵀA + J CᵀC and f = Σ Aᵀ(F − m β), F = (−m a_h, −m (g + a_v)) (fills M, f)."""
    mass_and_forces_on(P, A, beta, C, ah, av, gravity, M, f, 3 * P.shape[0], np.arange(3 * P.shape[0]))


@njit(cache=True, _nrt=False, inline="always")  # (inlined: see forward)
def mass_and_forces_on(P, A, beta, C, ah, av, gravity, M, f, n_cols, cols):
    """:func:`mass_and_forces` on the columns cols[:n_cols] of M only (the others are left as
    they were): a mode's equations read only the columns of its free coordinates, one to three
    of 3N in most modes."""
    n = P.shape[0]
    nz = 3 * n
    for i in range(nz):
        f[i] = 0.0
        for c in range(n_cols):
            M[i, cols[c]] = 0.0
    for k in range(n):
        m = P[k, P_MASS]
        J = P[k, P_INERTIA]
        fx = -m * ah - m * beta[k, 0]
        fy = -m * (gravity + av) - m * beta[k, 1]
        for i in range(nz):
            a0, a1, ci = A[k, 0, i], A[k, 1, i], C[k, i]
            f[i] += a0 * fx + a1 * fy
            if a0 == 0.0 and a1 == 0.0 and ci == 0.0:
                continue
            for c in range(n_cols):
                j = cols[c]
                M[i, j] += m * (a0 * A[k, 0, j] + a1 * A[k, 1, j]) + J * ci * C[k, j]


@njit(cache=True, _nrt=False)
def energy(P, X, Xd, theta_d, gravity):
    """Kinetic + potential energy relative to the floor, J (potential zero at y = 0)."""
    e = 0.0
    for k in range(P.shape[0]):
        m = P[k, P_MASS]
        e += 0.5 * m * (Xd[k, 0] ** 2 + Xd[k, 1] ** 2) + 0.5 * P[k, P_INERTIA] * theta_d[k] ** 2 + m * gravity * X[k, 1]
    return e


@njit(cache=True, _nrt=False)
def kinetic_energy(P, Xd, theta_d):
    e = 0.0
    for k in range(P.shape[0]):
        e += 0.5 * P[k, P_MASS] * (Xd[k, 0] ** 2 + Xd[k, 1] ** 2) + 0.5 * P[k, P_INERTIA] * theta_d[k] ** 2
    return e


def corner_positions(P, ends, anchor, z, zd=None):
    """Python helper for plots and tests: absolute centre poses (N, 3) = (X, Y, Θ)."""
    n = P.shape[0]
    nz = 3 * n
    A, beta, C, X, Xd, th, thd = new_frame(n)
    forward(P, ends, anchor, np.asarray(z, float), np.zeros(nz) if zd is None else np.asarray(zd, float),
            A, beta, C, X, Xd, th, thd)
    return np.column_stack([X, th])
