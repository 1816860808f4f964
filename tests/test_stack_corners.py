"""Where the upper block's bottom corners are, in the frame of the block below
(``rocking.stack.modes.corner_x``: the x of those corners decides which corner makes each end
of an interface and when a block slides past an edge or off the block below).

The expected values come from the definition of an interface's coordinates (a, φ, d) at its
anchor (docs/theory/stack.md §3, the module docstring of ``rocking.stack.kinematics``), written
here again: an upper corner (x_e, −h_u) at (a, h_l + d) in the lower block's frame, or a lower
corner (x_e, h_l) at (a, −h_u − d) in the upper block's frame, the upper block turned by φ,
R(φ) = [[cos φ, sin φ], [−sin φ, cos φ]]. Random poses with open gaps (d ≠ 0) and turned blocks
below; tolerance 1e-13 m, rounding on sizes of order 1 m.
"""

import numpy as np

from rocking.stack.kinematics import END_L, END_U, P_BL, P_BU, P_HL, P_HU
from rocking.stack.modes import corner_x


def _rotate(phi, vx, vy):
    c, s = np.cos(phi), np.sin(phi)
    return c * vx + s * vy, -s * vx + c * vy


def _expected(hu, bu, kind, x_e, a, phi, d):
    """x of the upper block's bottom corners (left, right) in the lower block's frame, m."""
    if kind == END_U:
        qx, qy = _rotate(phi, x_e, -hu)
        rx = a - qx  # centre of the upper block: (a, h_l + d) − R(φ)(x_e, −h_u)
    else:
        wx, wy = _rotate(phi, a, -hu - d)
        rx = x_e - wx  # (x_e, h_l) = r + R(φ)(a, −h_u − d)
    left, _ = _rotate(phi, -bu, -hu)
    right, _ = _rotate(phi, bu, -hu)
    return rx + left, rx + right


def _random_poses(seed, count):
    """Three-block stacks in random poses: (rng, P, ends, anchor, z), every a, φ and d nonzero (gaps
    open, blocks below turned)."""
    rng = np.random.default_rng(seed)
    n = 3
    for _ in range(count):
        P = np.zeros((n, 12))
        P[:, P_HU] = rng.uniform(0.1, 1.0, n)
        P[:, P_BU] = rng.uniform(0.05, 0.6, n)
        P[1:, P_HL] = P[:-1, P_HU]
        P[1:, P_BL] = P[:-1, P_BU]
        P[0, P_BL] = 1e3  # the floor
        ends = np.zeros((n, 2, 2))
        anchor = rng.integers(0, 2, n).astype(np.int64)
        for k in range(n):
            for e, sign in ((0, -1.0), (1, 1.0)):
                kind = END_L if (k > 0 and rng.random() < 0.5) else END_U
                ends[k, e] = kind, sign * (P[k, P_BL] if kind == END_L else P[k, P_BU])
        yield rng, P, ends, anchor, rng.uniform(-0.3, 0.3, 3 * n)


def test_the_upper_blocks_corners_in_the_lower_blocks_frame():
    worst = 0.0
    for _, P, ends, anchor, z in _random_poses(7, 300):
        for k in range(3):
            e = anchor[k]
            got = corner_x(P, ends, anchor, k, z)
            want = _expected(P[k, P_HU], P[k, P_BU], ends[k, e, 0], ends[k, e, 1], z[3 * k], z[3 * k + 1], z[3 * k + 2])
            worst = max(worst, abs(got[0] - want[0]), abs(got[1] - want[1]))
    assert worst <= 1e-13


def _inner_ends(bu, bl, xl, xr, direction, tol):
    """The corner that makes each end of the overlap (type, x): the inner of the upper block's
    bottom corner (at xl or xr in the lower block's frame) and the lower block's top corner (at
    ∓bl); within ``tol`` of a tie, the one that stays inner when the upper block moves in
    ``direction`` (moving right, its left corner moves in; at rest, the upper one)."""
    if abs(xl + bl) <= tol:
        left = (END_U, -bu) if direction >= 0 else (END_L, -bl)
    else:
        left = (END_U, -bu) if xl > -bl else (END_L, -bl)
    if abs(xr - bl) <= tol:
        right = (END_U, bu) if direction <= 0 else (END_L, bl)
    else:
        right = (END_U, bu) if xr < bl else (END_L, bl)
    return left, right


def test_each_end_is_made_by_the_inner_corner():
    """identify_ends against the overlap's definition, on random poses, half of them moved so that
    a corner of the upper block lies within 2 mm of the lower block's (ties at tol = 1 mm, in each
    direction of motion)."""
    from rocking.stack.modes import identify_ends

    ties = 0
    for rng, P, ends, anchor, z in _random_poses(11, 400):
        k = int(rng.integers(1, 3))
        i = 3 * k
        hu, bu, bl = P[k, P_HU], P[k, P_BU], P[k, P_BL]
        kind, x_e = ends[k, anchor[k]]
        xl, xr = _expected(hu, bu, kind, x_e, z[i], z[i + 1], z[i + 2])
        if rng.random() < 0.5:
            # move a so that one corner of the upper block comes within 2 mm of the lower one's
            # (x is linear in a: slope 1 on an upper anchor, −cos φ on a lower one)
            slope = 1.0 if kind == END_U else -np.cos(z[i + 1])
            target = (-bl - xl) if rng.random() < 0.5 else (bl - xr)
            z[i] += (target + rng.uniform(-2e-3, 2e-3)) / slope
            xl, xr = _expected(hu, bu, kind, x_e, z[i], z[i + 1], z[i + 2])
        direction = int(rng.integers(-1, 2))
        out = np.zeros((2, 2))
        identify_ends(P, ends, anchor, k, z, direction, 1e-3, out)
        want = _inner_ends(bu, bl, xl, xr, direction, 1e-3)
        assert tuple(out[0]) == want[0] and tuple(out[1]) == want[1], (xl, xr, bl, direction, out)
        ties += abs(xl + bl) <= 1e-3 or abs(xr - bl) <= 1e-3
    assert ties >= 50


def _pose_and_rate(P, ends, anchor, k, z, zd):
    """Block k's centre and rotation in the lower block's frame and their rates, from the anchor's
    definition (central differences in time for the rates: the pose is smooth, error ~1e-10)."""
    def pose(zz):
        i = 3 * k
        kind, x_e = ends[k, anchor[k]]
        hu, hl = P[k, P_HU], P[k, P_HL]
        a, phi, d = zz[i], zz[i + 1], zz[i + 2]
        if kind == END_U:
            qx, qy = _rotate(phi, x_e, -hu)
            return np.array([a - qx, hl + d - qy, phi])
        wx, wy = _rotate(phi, a, -hu - d)
        return np.array([x_e - wx, hl - wy, phi])

    h = 1e-6
    return pose(z), (pose(z + h * zd) - pose(z - h * zd)) / (2 * h)


def test_refreshing_the_ends_keeps_every_block_where_it_is():
    """refresh_ends sets each end to the corner that makes it now; where that moves the anchor, the
    interface's coordinates are re-expressed at the new one: every block keeps its pose (to
    1e-12 m) and its velocity (to 1e-8 m/s, the finite differences' error)."""
    from rocking.stack.modes import identify_ends, refresh_ends

    moved = 0
    for rng, P, ends, anchor, z in _random_poses(12, 300):
        k = int(rng.integers(1, 3))
        zd = rng.uniform(-1.0, 1.0, 9)
        direction = int(rng.integers(-1, 2))
        before, rate_before = _pose_and_rate(P, ends, anchor, k, z, zd)
        ends1, anchor1, z1, zd1 = ends.copy(), anchor.copy(), z.copy(), zd.copy()
        refresh_ends(P, ends1, anchor1, k, z1, zd1, direction)
        want = np.zeros((2, 2))
        identify_ends(P, ends, anchor, k, z, direction, 1e-12, want)
        assert np.array_equal(ends1[k], want)
        others = [j for j in range(3) if j != k]
        assert np.array_equal(ends1[others], ends[others]) and np.array_equal(anchor1[others], anchor[others])
        assert np.array_equal(z1[np.r_[0:3 * k, 3 * k + 3:9]], z[np.r_[0:3 * k, 3 * k + 3:9]])
        after, rate_after = _pose_and_rate(P, ends1, anchor1, k, z1, zd1)
        np.testing.assert_allclose(after, before, rtol=0, atol=1e-12)
        np.testing.assert_allclose(rate_after, rate_before, rtol=0, atol=1e-8)
        moved += anchor1[k] == anchor[k] and ends1[k, anchor[k], 0] != ends[k, anchor[k], 0]
    assert moved >= 20  # the anchor's own corner changed (re-anchored in place): 25 of the 300
