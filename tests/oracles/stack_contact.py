"""An independent contact problem of a stack of blocks, for the tests of ``rocking.stack``.

Every block's pose is written from the definition of the interface coordinates (a, φ, d) at an
anchor (docs/theory/stack.md §3) and differentiated by complex step (exact to rounding) for the
Jacobians and by central differences of those for the velocity terms. Each contact is stated as
physics does: a closed end is a constraint on that corner's gap, with a normal force along the
gap's gradient; a stuck interface a constraint on the slip at its contact, with a friction force
along the slip's gradient; a slipping one a friction force −μk·σ·N. Nothing here imports the
library's kinematics or mode selection: only its data layout (the packed parameters P, the ends
and the state constants).
"""

import itertools

import numpy as np

from rocking.contact.friction import Friction
from rocking.stack import Block, Interface, Stack
from rocking.stack.kinematics import (END_U, P_CAN_SLIP, P_HL, P_HU, P_INERTIA, P_MASS, P_MU_K, P_MU_S,
                                      P_OFFSET)
from rocking.stack.modes import ACCELERATION, FLAT, OPEN, ROCK, VELOCITY
from rocking.stack.simulate import pack

G = 9.80665
# the branches of one interface in the documented order: (normal state, on the other end?, slip sign)
BRANCHES = [(FLAT, 0, 0), (ROCK, 0, 0), (ROCK, 1, 0), (FLAT, 0, 1), (FLAT, 0, -1),
            (ROCK, 0, 1), (ROCK, 0, -1), (ROCK, 1, 1), (ROCK, 1, -1), (OPEN, 0, 0)]


# ---- the geometry, from the definition of (a, φ, d) at an anchor --------------------------------
def rot(phi, vx, vy):
    """R(φ) v, R = [[cos, sin], [−sin, cos]] (clockwise positive)."""
    c, s = np.cos(phi), np.sin(phi)
    return c * vx + s * vy, -s * vx + c * vy


def rot_t(phi, vx, vy):
    c, s = np.cos(phi), np.sin(phi)
    return c * vx - s * vy, s * vx + c * vy


def relative(P, ends, anchor, k, a, phi, d):
    """Centre of block k in the frame of the block below, from its anchor's corner."""
    hu, hl = P[k, P_HU], P[k, P_HL]
    kind, x_e = ends[k, anchor[k]]
    if kind == END_U:  # its corner (x_e, −h_u) at (a, h_l + d)
        qx, qy = rot(phi, x_e, -hu)
        return a - qx, hl + d - qy
    wx, wy = rot(phi, a, -hu - d)  # the lower corner (x_e, h_l) at (a, −h_u − d) in its frame
    return x_e - wx, hl - wy


def contact(P, ends, anchor, k, z, e):
    """(gap, slip) of end e of interface k: the corner's distance from the face it touches (> 0
    open) and its position along that face, signed so that its rate is the upper block's
    tangential velocity relative to the lower one."""
    a, phi, d = z[3 * k], z[3 * k + 1], z[3 * k + 2]
    rx, ry = relative(P, ends, anchor, k, a, phi, d)
    hu, hl = P[k, P_HU], P[k, P_HL]
    kind, x_e = ends[k, e]
    if kind == END_U:
        px, py = rot(phi, x_e, -hu)
        return ry + py - hl, rx + px
    qx, qy = rot_t(phi, x_e - rx, hl - ry)
    return -hu - qy, -qx


def poses(P, ends, anchor, z):
    """(X, Y, Θ) of every block's centre in the floor's frame, stacked (3N)."""
    out = []
    X, Y, TH = 0.0, 0.0, 0.0
    for k in range(P.shape[0]):
        rx, ry = relative(P, ends, anchor, k, z[3 * k], z[3 * k + 1], z[3 * k + 2])
        dx, dy = rot(TH, rx, ry)
        X, Y, TH = X + dx, Y + dy, TH + z[3 * k + 1]
        out += [X, Y, TH]
    return np.array(out)


def jacobian(fun, z):
    """∂fun/∂z by complex step (fun is analytic in z: sums, products, sin and cos)."""
    h = 1e-30
    cols = []
    for j in range(len(z)):
        zc = z.astype(complex)
        zc[j] += 1j * h
        cols.append(np.imag(fun(zc)) / h)
    return np.array(cols).T


def curvature(fun, z, zd):
    """d²/ds² fun(z + s ż) at s = 0: the velocity term of fun's acceleration (central differences of
    the complex-step rate, error ~1e-10 on these sizes)."""
    h = 1e-5
    return (jacobian(fun, z + h * zd) @ zd - jacobian(fun, z - h * zd) @ zd) / (2 * h)


# ---- the oracle ---------------------------------------------------------------------------------
class Oracle:
    """The contact problem of one state, in the state's own coordinates (anchors never move)."""

    def __init__(self, P, ends, anchor, geo, z, zd, ah, av, level, extra):
        self.P, self.geo, self.level, self.n = P, geo, level, P.shape[0]
        nz = 3 * self.n
        self.ends, self.anchor = ends.copy(), anchor.copy()
        pose = lambda q: poses(P, self.ends, self.anchor, q)  # noqa: E731
        self.J = jacobian(pose, z)
        self.beta = curvature(pose, z, zd)
        W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(self.n)])
        F = np.concatenate([[-P[k, P_MASS] * ah, -P[k, P_MASS] * (G + av), 0.0] for k in range(self.n)])
        self.M = self.J.T @ (W[:, None] * self.J)
        if level == ACCELERATION:
            self.rhs = self.J.T @ (F - W * self.beta)
        else:
            self.rhs = self.M @ zd + extra
        # per interface and end: gradients and velocity terms of the gap and slip, and the slip rate
        self.dg, self.gg, self.ds, self.gs, self.sdot = {}, {}, {}, {}, {}
        for k in range(self.n):
            for e in range(2):
                g = lambda q, k=k, e=e: np.array(contact(P, self.ends, self.anchor, k, q, e))  # noqa: E731
                jac = jacobian(g, z)
                curv = curvature(g, z, zd) if level == ACCELERATION else np.zeros(2)
                self.dg[k, e], self.ds[k, e] = jac[0], jac[1]
                self.gg[k, e], self.gs[k, e] = curv[0], curv[1]
                # (states slip at ≥ 1e-3 m/s or not at all: rounding in the complex step is ~1e-17)
                sdot = jac[1] @ zd
                self.sdot[k, e] = sdot if abs(sdot) > 1e-9 else 0.0
        self.scale_force = float(np.sum(P[:, P_MASS]) * G)
        self.nz = nz

    def sigma(self, k, other, tst):
        """Physical slip direction of a branch's sign: ȧ's sign at the end it rocks on (flat: the
        anchor), reversed on a lower block's corner (there a runs along the upper face)."""
        e = self.anchor[k] if not other else 1 - self.anchor[k]
        return tst * (1 if self.ends[k, e, 0] == END_U else -1)

    def allowed(self, k, branch, veto, hold, force_flat):
        nst, other, tst = branch
        P, geo = self.P, self.geo[k]
        if nst > geo or (other and geo != FLAT) or (nst == OPEN and tst != 0):
            return False
        if tst != 0 and P[k, P_CAN_SLIP] < 0.5:
            return False
        if k == force_flat:
            # the rest rule: lands flat, keeping its tangential state
            sd = self.sdot[k, self.anchor[k]]
            keep = 0 if sd == 0.0 or P[k, P_CAN_SLIP] < 0.5 else int(np.sign(sd))
            return nst == FLAT and self.sigma(k, 0, tst) == keep
        if (hold or force_flat >= 0) and (nst != geo or other):
            return False
        if self.level == ACCELERATION and nst >= ROCK:
            e = self.anchor[k] if not other else 1 - self.anchor[k]
            sd = self.sdot[k, e]
            if sd != 0.0 and (tst == 0 or self.sigma(k, other, tst) != np.sign(sd)):
                return False  # a slipping interface slips on, its way; it cannot stick without an impulse
        if veto is not None and veto[0] == k:
            kind = veto[1]
            if kind == 0 and (nst == FLAT or (nst == ROCK and not other)):
                return False
            if kind == 1 and (nst == FLAT or (nst == ROCK and other)):
                return False
            if kind == 2 and nst >= ROCK and tst == 0:
                return False
        return True

    def solve(self, combo):
        """Accelerations (velocities) and the forces (impulses) of one branch per interface:
        (z̈, {(k, e): N}, {k: T}), or None if singular."""
        nz = self.nz
        cols, names = [], []
        rows, rhs_c = [], []
        for k, (nst, other, tst) in enumerate(combo):
            if nst == OPEN:
                continue
            e_rock = self.anchor[k] if not other else 1 - self.anchor[k]
            closed = [0, 1] if nst == FLAT else [e_rock]
            slip_end = self.anchor[k] if nst == FLAT else e_rock
            for e in closed:
                col = self.dg[k, e].copy()
                if tst != 0:  # sliding friction −μk σ N along the slip's gradient
                    col -= self.P[k, P_MU_K] * self.sigma(k, other, tst) * self.ds[k, slip_end]
                cols.append(col)
                names.append(("N", k, e))
                rows.append(self.dg[k, e])
                rhs_c.append(-self.gg[k, e])
            if tst == 0:  # stuck (or never slips): no slip at the contact
                cols.append(self.ds[k, slip_end])
                names.append(("T", k, slip_end))
                rows.append(self.ds[k, slip_end])
                rhs_c.append(-self.gs[k, slip_end])
        m = len(cols)
        A = np.zeros((nz + m, nz + m))
        b = np.zeros(nz + m)
        A[:nz, :nz] = self.M
        b[:nz] = self.rhs
        for j in range(m):
            A[:nz, nz + j] = -cols[j]
            A[nz + j, :nz] = rows[j]
            b[nz + j] = rhs_c[j]
        if np.linalg.cond(A) > 1e9:
            return None
        x = np.linalg.solve(A, b)
        forces = {names[j]: x[nz + j] for j in range(m)}
        return x[:nz], forces

    def holds(self, combo, sol, hold, force_flat, margins):
        """The complementarity conditions (docs/theory/stack.md §5); appends each condition's
        distance from its threshold to ``margins``."""
        zdd, forces = sol
        acc = self.level == ACCELERATION
        check_normal = force_flat < 0 and not hold
        tol_f = 1e-10 * self.scale_force
        for k, (nst, other, tst) in enumerate(combo):
            if k == force_flat:
                continue
            geo = self.geo[k]
            e_rock = self.anchor[k] if not other else 1 - self.anchor[k]
            rate = lambda e: self.dg[k, e] @ zdd + (self.gg[k, e] if acc else 0.0)  # noqa: E731
            tests = []  # (value, threshold, strict)
            if check_normal:
                if nst == FLAT:
                    tests += [(forces["N", k, 0], -tol_f, False), (forces["N", k, 1], -tol_f, False)]
                elif nst == ROCK:
                    tests.append((forces["N", k, e_rock], -tol_f, False))
                elif geo >= ROCK:
                    tests.append((rate(self.anchor[k]) / G, -1e-12 / G, False))
                if nst <= ROCK and geo == FLAT:
                    released = 1 - e_rock if nst == ROCK else 1 - self.anchor[k]
                    tests.append((rate(released) / G, 0.0 if acc else -1e-12 / G, acc))
            if nst >= ROCK and self.P[k, P_CAN_SLIP] > 0.5:
                slip_end = self.anchor[k] if nst == FLAT else e_rock
                n_tot = sum(v for (kind, kk, _), v in forces.items() if kind == "N" and kk == k)
                if tst == 0:
                    t = forces["T", k, slip_end]
                    tests.append(((self.P[k, P_MU_S] * n_tot + tol_f - abs(t)) / self.scale_force, 0.0, False))
                elif not acc or self.sdot[k, slip_end] == 0.0:
                    s_rate = self.ds[k, slip_end] @ zdd + (self.gs[k, slip_end] if acc else 0.0)
                    tests.append((self.sigma(k, other, tst) * s_rate / G, 0.0, acc))
            for value, threshold, strict in tests:
                margins.append(abs(value - threshold))
                if (value <= threshold) if strict else (value < threshold):
                    return False
        return True

    def select(self, veto=None, hold=False, force_flat=-1):
        """The first branch combination that holds: (combo, solution, smallest margin met on the
        way) or (None, None, margin)."""
        margins = []
        for attempt in range(2):
            v = veto if attempt == 0 else None
            per = [[b for b in BRANCHES if self.allowed(k, b, v, hold, force_flat)] for k in range(self.n)]
            for combo in itertools.product(*per):
                sol = self.solve(combo)
                if sol is None:
                    return "singular", None, 0.0
                if self.holds(combo, sol, hold, force_flat, margins):
                    return combo, sol, min(margins, default=np.inf)
            if veto is None:
                break
        return None, None, min(margins, default=np.inf)


# ---- random stacks in random states -------------------------------------------------------------
def random_states(rng, count, level):
    """``count`` states drawn by :func:`random_state`, those it rejects skipped."""
    drawn = 0
    while drawn < count:
        state = random_state(rng, level)
        if state is not None:
            drawn += 1
            yield state


def random_state(rng, level, kinetic=(0.6, 1.0)):
    """``kinetic``: the range of μk/μs."""
    n = int(rng.integers(1, 4))
    blocks, interfaces = [], []
    for k in range(n):
        width = rng.uniform(0.2, 1.2)
        # an offset that leaves the faces overlapping by a fair width
        offset = 0.0 if k == 0 else rng.uniform(-0.3, 0.3) * min(width, blocks[-1].width)
        blocks.append(Block(width=width, height=rng.uniform(0.2, 1.5), mass=rng.uniform(5.0, 400.0), offset=offset))
        mu_s = rng.uniform(0.2, 0.8)
        friction = Friction(static=mu_s, kinetic=mu_s * rng.uniform(*kinetic)) if rng.random() < 0.7 else None
        interfaces.append(Interface(friction=friction))
    P, ends, anchor, z = pack(Stack(blocks=tuple(blocks), interfaces=tuple(interfaces)))
    zd = np.zeros(3 * n)
    geo = np.zeros(n, dtype=np.int64)
    for k in range(n):
        i = 3 * k
        can_slip = P[k, P_CAN_SLIP] > 0.5
        geo[k] = rng.choice([FLAT, ROCK, OPEN], p=[0.5, 0.35, 0.15])
        e = int(rng.integers(0, 2))
        if e == 1:  # move the anchor to the right end (pack puts it on the left)
            anchor[k] = 1
            z[i] = ends[k, 1, 1] + (P[k, P_OFFSET] if ends[k, 1, 0] == END_U else -P[k, P_OFFSET])
        if geo[k] == FLAT:
            if can_slip and rng.random() < 0.4:
                zd[i] = rng.choice([-1, 1]) * rng.uniform(1e-3, 0.5)
            if level == VELOCITY:
                zd[i + 1], zd[i + 2] = rng.uniform(-1.0, 1.0), rng.uniform(-0.5, 0.0)
        elif geo[k] == ROCK:
            z[i + 1] = (1 if e == 1 else -1) * rng.uniform(0.01, 0.3)  # tilted away from the other end
            zd[i + 1] = rng.uniform(-1.0, 1.0)
            if can_slip and rng.random() < 0.4:
                zd[i] = rng.choice([-1, 1]) * rng.uniform(1e-3, 0.5)
            if level == VELOCITY:
                zd[i + 2] = rng.uniform(-0.5, 0.0)
        else:
            z[i + 1], z[i + 2] = rng.uniform(-0.1, 0.1), rng.uniform(0.001, 0.05)
            zd[i:i + 3] = rng.uniform(-0.5, 0.5, 3)
    # each state must be what its geometric state says: a rocking interface's other end open
    for k in range(n):
        if geo[k] == ROCK and contact(P, ends, anchor, k, z, 1 - anchor[k])[0] <= 1e-4:
            return None
    extra = np.zeros(3 * n)
    if level == VELOCITY:
        extra[1::3] = rng.uniform(-20.0, 20.0, n) * (rng.random(n) < 0.5)  # couples, on the φ's only
    return P, ends, anchor, geo, z, zd, extra
