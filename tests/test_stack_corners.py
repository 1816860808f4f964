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


def test_the_upper_blocks_corners_in_the_lower_blocks_frame():
    rng = np.random.default_rng(7)
    n = 3
    worst = 0.0
    for _ in range(300):
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
        z = rng.uniform(-0.3, 0.3, 3 * n)  # every a, φ and d nonzero: gaps open, blocks below turned
        for k in range(n):
            e = anchor[k]
            got = corner_x(P, ends, anchor, k, z)
            want = _expected(P[k, P_HU], P[k, P_BU], ends[k, e, 0], ends[k, e, 1], z[3 * k], z[3 * k + 1], z[3 * k + 2])
            worst = max(worst, abs(got[0] - want[0]), abs(got[1] - want[1]))
    assert worst <= 1e-13
