"""The stack engine's mode selection (``rocking.stack.modes.select_mode``) against an independent
contact problem (tests/oracles/stack_contact.py).

``select_mode`` works in interface coordinates: a mode freezes some of them, and a branch on the
other end of an interface is solved after moving that interface's anchor. The oracle knows
none of that. It writes every block's pose from the definition of the coordinates
(docs/theory/stack.md §3), differentiates it by complex step (exact to rounding) for the
Jacobians and by central differences of those for the velocity terms, and states each contact as
physics does: a closed end is a constraint on that corner's gap, with a normal force along the
gap's gradient; a stuck interface a constraint on the slip at its contact, with a friction force
along the slip's gradient; a slipping one a friction force −μk·σ·N. One linear solve per branch
gives the accelerations (or, for an impact, the velocities after it) and the forces (impulses),
which are then judged by the complementarity conditions of docs/theory/stack.md §5, in the
documented order (floor interface most significant; per interface: flat-stick, rock-stick on the
anchor, then on the other end, flat-slip ±, rock-slip, open; the ± in the sign of ȧ at the end
the branch rocks on, so physically reversed on a lower block's corner).

The two are compared on random stacks of one to three blocks in random states: the branch taken,
the absolute accelerations of every block, every closed end's normal force and every closed
interface's friction force. Samples whose decision passes within 1e-6 (relative) of a condition's
threshold are skipped, as are nearly singular contact problems: there the finite differences
(~1e-10) could flip a decision. The tolerance on accelerations and forces, 1e-7 relative, is 1000
times the finite-difference error. Ties are checked apart, on a case where they are exact (a
floor falling at g). The same geometry checks the kinematics the selection builds on.
"""

import numpy as np
import pytest
from oracles.stack_contact import G, Oracle, contact, curvature, jacobian, poses, random_state

from rocking.contact.friction import Friction
from rocking.stack import Block, Interface, Stack
from rocking.stack.kinematics import END_U, P_BU, P_CAN_SLIP, P_HU, P_INERTIA, P_MASS, P_MU_K, P_MU_S
from rocking.stack.modes import (ACCELERATION, FLAT, OPEN, ROCK, SELECT_NONE, SELECT_OK, VELOCITY, flat_forces,
                                 select_mode)
from rocking.stack.simulate import pack


def _library_accelerations(P, ends, anchor, z, zd, x, level):
    pose = lambda q: poses(P, ends, anchor, q)  # noqa: E731
    J = jacobian(pose, z)
    return J @ x + (curvature(pose, z, zd) if level == ACCELERATION else 0.0)


def _compare(level, seed, samples, options, kinetic=(0.6, 1.0), slip_speed=None):
    """Run select_mode and the oracle on ``samples`` random states; returns the branches taken
    and how many of them the options (veto, hold, rest rule) changed. ``slip_speed``: every
    interface that slips does so at exactly this speed (m/s), its direction kept."""
    rng = np.random.default_rng(seed)
    taken = []
    changed = 0
    tried = 0
    while len(taken) < samples:
        tried += 1
        assert tried < 20 * samples
        state = random_state(rng, level, kinetic)
        if state is None:
            continue
        P, ends, anchor, geo, z, zd, extra = state
        n = P.shape[0]
        if slip_speed is not None:
            zd[0::3] = np.sign(zd[0::3]) * slip_speed
        ah, av = rng.uniform(-1.2, 1.2) * G, rng.uniform(-0.5, 0.5) * G
        oracle = Oracle(P, ends, anchor, geo, z, zd, ah, av, level, extra)
        veto, hold, force_flat = options(rng, oracle)
        combo, sol, margin = oracle.select(veto, hold, force_flat)
        if combo == "singular" or margin < 1e-6:
            continue
        changed += combo != oracle.select()[0]
        ends_l, anchor_l, z_l, zd_l = ends.copy(), anchor.copy(), z.copy(), zd.copy()
        nstate, tstate = np.zeros(n, dtype=np.int64), np.zeros(n, dtype=np.int64)
        x, lam = np.zeros(3 * n), np.zeros(3 * n)
        scale = np.sum(P[:, P_MASS]) * G
        tol_force = 1e-10 * scale  # the engine's tolerance (for impulses it scales with the energy instead)
        veto_k, veto_kind = veto if veto is not None else (-1, 0)
        code = select_mode(level, P, ends_l, anchor_l, geo, z_l, zd_l, ah, av, G, extra, nstate, tstate,
                           veto_k, veto_kind, tol_force, 1e-12, x, lam, force_flat, hold)
        if combo is None:
            assert code == SELECT_NONE
            assert np.array_equal(z_l, z) and np.array_equal(zd_l, zd) and np.array_equal(anchor_l, anchor)
            taken.append(None)
            continue
        assert code == SELECT_OK
        for k, (nst, other, tst) in enumerate(combo):
            assert (nstate[k], tstate[k]) == (nst, tst), (k, combo, nstate, tstate)
            assert anchor_l[k] == (1 - anchor[k] if other else anchor[k])
        # every block's absolute acceleration (velocity after an impact), in the oracle's
        # coordinates and in the library's (possibly re-anchored) ones
        zdd, forces = sol
        want = oracle.J @ zdd + (oracle.beta if level == ACCELERATION else 0.0)
        got = _library_accelerations(P, ends_l, anchor_l, z_l, zd_l, x, level)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * (G + np.abs(want).max()))
        # the normal force (impulse) of every closed end, where the normal problem was solved
        for k, (nst, other, tst) in enumerate(combo):
            i = 3 * k
            if nst == FLAT:
                n_anchor, n_other = flat_forces(P, ends_l, anchor_l, k, z_l, lam)
                got_n = {anchor_l[k]: n_anchor, 1 - anchor_l[k]: n_other}
            elif nst == ROCK:
                got_n = {anchor_l[k]: lam[i + 2]}
            else:
                got_n = {}
            for e, value in got_n.items():
                assert abs(value - forces["N", k, e]) <= 1e-7 * scale, (k, e, value, forces["N", k, e])
            # and its friction force (impulse), on a: the library's Λ_a is the force along the face
            # the anchor's corner runs on, the oracle's T along the lower face (reversed for a
            # lower block's corner, as σ)
            if nst >= ROCK and P[k, P_CAN_SLIP] > 0.5:
                contact = anchor[k] if nst == FLAT else (1 - anchor[k] if other else anchor[k])
                if tst == 0:
                    friction = forces["T", k, contact]
                else:
                    n_total = sum(v for (kind, kk, _), v in forces.items() if kind == "N" and kk == k)
                    friction = -P[k, P_MU_K] * oracle.sigma(k, other, tst) * n_total
                along = 1.0 if ends[k, contact, 0] == END_U else -1.0
                assert abs(lam[i] - along * friction) <= 1e-7 * scale, (k, lam[i], friction)
        taken.append(combo)
    return taken, changed


def _kinds(taken):
    """Which kinds of branch the samples took: flat/rock/open × stick/slip, on the anchor or not."""
    kinds = set()
    for combo in taken:
        if combo is None:
            kinds.add("none")
            continue
        for nst, other, tst in combo:
            kinds.add(({FLAT: "flat", ROCK: "rock", OPEN: "open"}[nst], "other" if other else "anchor",
                       "slip" if tst else "stick"))
    return kinds


def _plain(rng, oracle):
    return None, False, -1


def test_the_acceleration_branch_is_the_first_that_holds():
    taken, _ = _compare(ACCELERATION, seed=1, samples=150, options=_plain)
    kinds = _kinds(taken)
    # the samples reach every kind of branch (a test that never met one could not fail on it)
    for kind in [("flat", "anchor", "stick"), ("flat", "anchor", "slip"), ("rock", "anchor", "stick"),
                 ("rock", "anchor", "slip"), ("rock", "other", "stick"), ("open", "anchor", "stick")]:
        assert kind in kinds, kind


def test_a_slip_at_a_round_speed_is_judged_by_its_direction():
    """The rule that a slipping interface keeps its direction (a branch slipping against ȧ is
    excluded) at slip speeds of exactly ±1 m/s: random speeds never meet a constant the rule
    could be compared with by mistake (a mutant exempting ȧ = 1.0 passed every other test).
    Where the slip's own branches fail (friction pulling a corner off, Painlevé's paradox), the
    reversed one could hold and be taken."""
    taken, _ = _compare(ACCELERATION, seed=11, samples=150, options=_plain, slip_speed=1.0)
    assert ("flat", "anchor", "slip") in _kinds(taken) and ("rock", "anchor", "slip") in _kinds(taken)


def test_the_impact_branch_is_the_first_that_holds():
    taken, _ = _compare(VELOCITY, seed=2, samples=150, options=_plain)
    kinds = _kinds(taken)
    for kind in [("flat", "anchor", "stick"), ("flat", "anchor", "slip"), ("rock", "anchor", "stick"),
                 ("rock", "other", "stick"), ("open", "anchor", "stick")]:
        assert kind in kinds, kind


def _vetoed(rng, oracle):
    """A veto of the branch the interface would take without one (its guard just fired): the
    anchor's force (0) or the other end's (1) for a flat or rocking branch, the stick (2); now
    and then a veto of another guard, which moves where the enumeration starts."""
    combo, _, _ = oracle.select()
    if combo in (None, "singular"):
        return None, False, -1
    closed = [k for k in range(oracle.n) if combo[k][0] >= ROCK]
    if not closed:
        return None, False, -1
    k = int(rng.choice(closed))
    nst, other, tst = combo[k]
    kinds = [2] if tst == 0 and rng.random() < 0.6 else ([0, 1] if nst == FLAT else [1 if other else 0])
    if rng.random() < 0.3:
        kinds = [0, 1, 2]  # or any guard: one that excludes other branches, not the one taken
    return (k, int(rng.choice(kinds))), False, -1


def _held(rng, oracle):
    return None, True, -1


def _landed(rng, oracle):
    flat = [k for k in range(oracle.n) if oracle.geo[k] == FLAT]
    return None, False, (int(rng.choice(flat)) if flat else -1)


@pytest.mark.parametrize("level", [ACCELERATION, VELOCITY], ids=["acceleration", "impact"])
@pytest.mark.parametrize("options", [_vetoed, _held, _landed], ids=["veto", "hold", "rest rule"])
def test_the_rules_that_narrow_the_branches(level, options):
    """A veto excludes the branch whose guard just fired unless nothing else holds; ``hold`` keeps
    every normal state and skips the normal signs; the rest rule lands one interface flat
    (keeping its slip) and lifts nothing else."""
    # (a veto changes the outcome only where the contact problem has two solutions: a stick
    # that may also slip, μk < μs; a low μk/μs makes that common)
    samples = 150 if options is _vetoed else 60
    taken, changed = _compare(level, seed=3 + level, samples=samples, options=options, kinetic=(0.2, 0.6))
    assert changed >= 5 and sum(combo is not None for combo in taken) >= 0.8 * samples


def test_the_kinematics_against_the_poses_written_here():
    """rocking.stack.kinematics, which the selection builds on, against the same independent
    geometry: the absolute poses, their velocities and acceleration maps (``forward``), the
    mass matrix and forces, each end's gap and its rate and gradient, an anchor moved to the
    other end, and the energies. Exact quantities to 1e-12 of their scale (complex step); the
    velocity terms β to 1e-8 (central differences, error ~1e-10)."""
    from rocking.stack.kinematics import (anchor_at, corner_positions, end_gap, end_gap_gradient, energy, forward,
                                          kinetic_energy, mass_and_forces, new_frame)

    rng = np.random.default_rng(21)
    checked = 0
    while checked < 60:
        state = random_state(rng, ACCELERATION)
        if state is None:
            continue
        P, ends, anchor, _, z, zd, _ = state
        n = P.shape[0]
        z = z + rng.uniform(-0.05, 0.05, 3 * n)  # any pose: gaps open or shut, blocks turned
        zd = rng.uniform(-1.0, 1.0, 3 * n)
        ah, av = rng.uniform(-10.0, 10.0, 2)
        A, beta, C, X, Xd, th, thd = new_frame(n)
        forward(P, ends, anchor, z, zd, A, beta, C, X, Xd, th, thd)
        pose = lambda q: poses(P, ends, anchor, q)  # noqa: E731
        q, J, curv = pose(z), jacobian(pose, z), curvature(pose, z, zd)
        qd = J @ zd
        for k in range(n):
            np.testing.assert_allclose([*X[k], th[k]], q[3 * k:3 * k + 3], rtol=0, atol=1e-12)
            np.testing.assert_allclose([*Xd[k], thd[k]], qd[3 * k:3 * k + 3], rtol=0, atol=1e-12)
            np.testing.assert_allclose(A[k], J[3 * k:3 * k + 2], rtol=0, atol=1e-12)
            np.testing.assert_allclose(C[k], J[3 * k + 2], rtol=0, atol=1e-12)
            np.testing.assert_allclose(beta[k], curv[3 * k:3 * k + 2], rtol=0, atol=1e-8)
        np.testing.assert_allclose(corner_positions(P, ends, anchor, z), q.reshape(n, 3), rtol=0, atol=1e-12)
        M, f = np.zeros((3 * n, 3 * n)), np.zeros(3 * n)
        mass_and_forces(P, A, beta, C, ah, av, G, M, f)
        W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(n)])
        F = np.concatenate([[-P[k, P_MASS] * ah, -P[k, P_MASS] * (G + av), 0.0] for k in range(n)])
        M_want = J.T @ (W[:, None] * J)
        np.testing.assert_allclose(M, M_want, rtol=0, atol=1e-12 * np.abs(M_want).max())
        f_want = J.T @ (F - W * curv)
        np.testing.assert_allclose(f, f_want, rtol=0, atol=1e-8 * np.abs(f_want).max())
        kinetic = 0.5 * np.sum(W * qd ** 2)
        assert abs(kinetic_energy(P, Xd, thd) - kinetic) <= 1e-12 * kinetic
        potential = G * np.sum(P[:, P_MASS] * q[1::3])
        assert abs(energy(P, X, Xd, thd, G) - kinetic - potential) <= 1e-12 * (kinetic + abs(potential))
        for k in range(n):
            for e in range(2):
                gap = lambda qq, k=k, e=e: np.array([contact(P, ends, anchor, k, qq, e)[0]])  # noqa: E731
                grad = jacobian(gap, z)[0]
                g, g_rate = end_gap(P, ends, anchor, k, z, zd, e)
                assert abs(g - gap(z)[0]) <= 1e-12 and abs(g_rate - grad @ zd) <= 1e-12
                # (a gap depends on its own interface's coordinates only: the gradient is along those)
                assert not np.any(np.delete(grad, np.s_[3 * k:3 * k + 3]))
                np.testing.assert_allclose(end_gap_gradient(P, ends, anchor, k, z, e), grad[3 * k:3 * k + 3],
                                           rtol=0, atol=1e-12)
            # the other end as anchor: the same block pose and velocity in new coordinates
            e_new = 1 - anchor[k]
            a, d, ad, dd = anchor_at(P, ends, anchor, k, z, zd, e_new, ends[k, e_new, 0], ends[k, e_new, 1])
            anchor2, z2, zd2 = anchor.copy(), z.copy(), zd.copy()
            anchor2[k] = e_new
            z2[3 * k], z2[3 * k + 2], zd2[3 * k], zd2[3 * k + 2] = a, d, ad, dd
            np.testing.assert_allclose(poses(P, ends, anchor2, z2), q, rtol=0, atol=1e-12)
            np.testing.assert_allclose(jacobian(lambda qq: poses(P, ends, anchor2, qq), z2) @ zd2, qd,  # noqa: E731
                                       rtol=0, atol=1e-12)
        checked += 1


@pytest.mark.parametrize("n", [1, 2, 3])
def test_a_stack_on_a_floor_falling_at_g_carries_no_force_and_stays_flat_and_stuck(n):
    """With the floor falling at exactly g, every contact force of a stack at rest is zero, to the
    bit: a tie at which flat and stuck (the most constrained branch, first) holds, as well as open.
    The tolerances decide the tie in favour of contact (|T| = 0 ≤ μs·0 + tol)."""
    blocks = tuple(Block(width=0.6 - 0.1 * k, height=0.5 + 0.2 * k, mass=50.0 + 10 * k) for k in range(n))
    stack = Stack(blocks=blocks, interfaces=tuple(Interface(friction=Friction(static=0.5, kinetic=0.4))
                                                  for _ in range(n)))
    P, ends, anchor, z = pack(stack)
    zd = np.zeros(3 * n)
    geo = np.full(n, FLAT, dtype=np.int64)
    nstate, tstate = np.zeros(n, dtype=np.int64), np.ones(n, dtype=np.int64)
    x, lam = np.full(3 * n, np.nan), np.full(3 * n, np.nan)
    tol_force = 1e-10 * np.sum(P[:, P_MASS]) * G
    code = select_mode(ACCELERATION, P, ends, anchor, geo, z, zd, 0.0, -G, G, np.zeros(3 * n), nstate, tstate,
                       -1, 0, tol_force, 1e-12, x, lam)
    assert code == SELECT_OK
    assert np.all(nstate == FLAT) and np.all(tstate == 0)
    assert np.all(x == 0.0) and np.all(lam == 0.0)


def test_a_mode_solve_pivots_past_a_zero_diagonal():
    """solve_mode_in on a slipping rocking interface whose folded row a (M_a + μk·σ·M_d) has a zero
    diagonal entry (M_aa = 1, M_da = −2, μk = 0.5): the system is regular (det −0.165), and only a
    row exchange solves it. Checked against numpy's solve of the reduced system."""
    from rocking.stack.modes import solve_mode_in

    P = np.zeros((1, 12))
    P[0, P_CAN_SLIP], P[0, P_MU_K], P[0, P_MU_S] = 1.0, 0.5, 0.6
    M = np.array([[1.0, 0.3, -2.0], [0.3, 2.0, 0.5], [-2.0, 0.5, 10.0]])
    assert np.all(np.linalg.eigvalsh(M) > 0)
    f = np.array([0.7, -1.1, 3.0])
    x, lam = np.full(3, np.nan), np.full(3, np.nan)
    scratch = (np.zeros(3, dtype=np.bool_), np.empty(3, dtype=np.int64), np.empty(3, dtype=np.int64),
               np.empty((3, 3)), np.empty(3))
    assert solve_mode_in(M, f, P, np.array([ROCK]), np.array([1]), x, lam, *scratch)
    # free a and φ; the a row carries −μk·σ·Λ_d with Λ_d = (M z̈ − f)_d
    K = np.array([[M[0, 0] + 0.5 * M[2, 0], M[0, 1] + 0.5 * M[2, 1]], [M[1, 0], M[1, 1]]])
    assert K[0, 0] == 0.0
    want = np.linalg.solve(K, [f[0] + 0.5 * f[2], f[1]])
    np.testing.assert_allclose(x, [want[0], want[1], 0.0], rtol=1e-14, atol=1e-14)
    lam_d = M[2] @ x - f[2]
    np.testing.assert_allclose(lam, [-0.5 * lam_d, 0.0, lam_d], rtol=1e-13, atol=1e-13)


def test_a_mode_solve_refuses_a_singular_or_non_finite_system():
    """solve_mode_in returns False (the candidate fails) where the reduced system has no pivot:
    the folded row a (M_a + μk·σ·M_d) is zero (M_aa = 1, M_da = −2, M_aφ = 0.3, M_dφ = −0.6,
    μk = 0.5, a slip that friction locks, a positive definite M), and where M holds a NaN. The
    random states never meet either (the oracle comparison skips nearly singular ones), so
    mutant 9892b9a3 (``and`` for ``or``: never refused) survived them."""
    from rocking.stack.modes import solve_mode_in

    P = np.zeros((1, 12))
    P[0, P_CAN_SLIP], P[0, P_MU_K], P[0, P_MU_S] = 1.0, 0.5, 0.6
    M = np.array([[1.0, 0.3, -2.0], [0.3, 2.0, -0.6], [-2.0, -0.6, 10.0]])
    assert np.all(np.linalg.eigvalsh(M) > 0)
    assert M[0, 0] + 0.5 * M[2, 0] == 0.0 and M[0, 1] + 0.5 * M[2, 1] == 0.0
    f = np.array([0.7, -1.1, 3.0])

    def solves(M):
        x, lam = np.full(3, np.nan), np.full(3, np.nan)
        scratch = (np.zeros(3, dtype=np.bool_), np.empty(3, dtype=np.int64), np.empty(3, dtype=np.int64),
                   np.empty((3, 3)), np.empty(3))
        return solve_mode_in(M, f, P, np.array([ROCK]), np.array([1]), x, lam, *scratch)

    assert not solves(M)
    assert solves(np.diag([1.0, 2.0, 10.0]))  # (the same call solves a regular system)
    M_nan = np.diag([1.0, 2.0, 10.0])
    M_nan[1, 1] = np.nan
    assert not solves(M_nan)


def test_a_veto_of_the_anchors_force_decides_a_tie_for_the_other_corner():
    """A flat block on the floor pushed towards +x a hair above its uplift threshold g·b/h (by 1e-11
    relative): its anchor's (left end's) force is −1e-11 of the weight, within the tolerance, so
    flat still holds, as does rocking on the other corner. Without a veto the most constrained
    branch wins, flat; with the anchor's force vetoed (its guard has just fired), the block rocks
    onto its other corner. That branch is the first tried, and the first whose pose moves an
    anchor, so its equations are the first built (the selection builds them once per set of
    moved anchors)."""
    stack = Stack(blocks=(Block(width=0.4, height=1.2, mass=100.0),), interfaces=(Interface(),))
    P, ends, anchor, z = pack(stack)
    ah = -G * P[0, P_BU] / P[0, P_HU] * (1.0 + 1e-11)
    tol_force = 1e-10 * P[0, P_MASS] * G
    outcomes = []
    for veto_k in (-1, 0):
        ends_l, anchor_l, z_l, zd_l = ends.copy(), anchor.copy(), z.copy(), np.zeros(3)
        nstate, tstate, x, lam = np.zeros(1, dtype=np.int64), np.zeros(1, dtype=np.int64), np.zeros(3), np.zeros(3)
        code = select_mode(ACCELERATION, P, ends_l, anchor_l, np.array([FLAT]), z_l, zd_l, ah, 0.0, G, np.zeros(3),
                           nstate, tstate, veto_k, 0, tol_force, 1e-12, x, lam)
        assert code == SELECT_OK
        outcomes.append((int(nstate[0]), int(anchor_l[0]), x[1]))
    assert outcomes[0] == (FLAT, 0, 0.0)
    # rocking on the right corner (clockwise, φ̈ > 0) at ~1e-11 of g/h: the tie's own size
    assert outcomes[1][:2] == (ROCK, 1) and 0.0 < outcomes[1][2] < 1e-9


def test_the_rest_rule_lands_the_floor_interface_whatever_the_others_pull():
    """The rest rule after an impact (``force_flat``) lands one interface flat and keeps every other
    in its normal state without looking at the signs of their impulses. Here the bottom block
    lands on the floor (interface 0, ḋ = −0.1 m/s) while the top block, flat on it, is lifting
    off (ḋ = +0.3 m/s): keeping it down takes a pulling impulse, and the rule accepts it."""
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=200.0), Block(width=0.3, height=0.9, mass=50.0)),
                  interfaces=(Interface(), Interface()))
    P, ends, anchor, z = pack(stack)
    zd = np.array([0.0, 0.0, -0.1, 0.0, 0.0, 0.3])
    geo = np.array([FLAT, FLAT])
    oracle = Oracle(P, ends, anchor, geo, z, zd, 0.0, 0.0, VELOCITY, np.zeros(6))
    combo, sol, _ = oracle.select(force_flat=0)
    assert combo == ((FLAT, 0, 0), (FLAT, 0, 0))
    assert sol[1]["N", 1, 0] + sol[1]["N", 1, 1] < -1.0  # the top interface pulls (N·s)
    nstate, tstate, x, lam = np.zeros(2, dtype=np.int64), np.zeros(2, dtype=np.int64), np.zeros(6), np.zeros(6)
    code = select_mode(VELOCITY, P, ends, anchor, geo, z, zd, 0.0, 0.0, G, np.zeros(6), nstate, tstate, -1, 0,
                       1e-9, 1e-12, x, lam, 0)
    assert code == SELECT_OK and list(nstate) == [FLAT, FLAT]
    np.testing.assert_allclose(x, sol[0], rtol=0, atol=1e-9)


def test_the_other_end_must_open_strictly_from_rest_and_within_the_tolerance_after_an_impulse():
    """``_candidate_ok``'s opening check for a flat interface that would rock: the other end's
    gap acceleration must be > 0, strictly, at the acceleration level (flat, tried first, holds
    where it is zero; a tolerance there once let a block rock the wrong way round), and its gap
    rate ≥ −tol_rate after an impulse. Checked on both levels at openings of −2, −½, 0 and +½
    tol_rate, with the anchor pushing and nothing slipping, so only that check decides. (Swapping
    the two levels' checks, mutant 83a4595a, was reached by no run.)"""
    from rocking.stack.kinematics import end_gap_gradient
    from rocking.stack.modes import _candidate_ok

    stack = Stack(blocks=(Block(width=0.4, height=1.2, mass=100.0),), interfaces=(Interface(),))
    P, ends, anchor, z = pack(stack)
    tol_force, tol_rate = 1e-10 * P[0, P_MASS] * G, 1e-9
    grad = end_gap_gradient(P, ends, anchor, 0, z, 1 - anchor[0])
    assert grad[1] != 0.0
    lam = np.array([0.0, 0.0, P[0, P_MASS] * G])  # the anchor carries the weight
    geo = np.array([FLAT])
    outcomes = {}
    for level in (ACCELERATION, VELOCITY):
        for opening in (-2.0, -0.5, 0.0, 0.5):
            x = np.array([0.0, opening * tol_rate / grad[1], 0.0])
            assert grad[1] * x[1] == pytest.approx(opening * tol_rate, rel=1e-12, abs=0.0)
            outcomes[level, opening] = _candidate_ok(level, P, ends, anchor, geo, 0, ROCK, 0, z, np.zeros(3), x, lam,
                                                     tol_force, tol_rate, True)
    assert [outcomes[ACCELERATION, o] for o in (-2.0, -0.5, 0.0, 0.5)] == [False, False, False, True]
    assert [outcomes[VELOCITY, o] for o in (-2.0, -0.5, 0.0, 0.5)] == [False, True, True, True]


def test_the_checks_after_an_impulse_hold_at_their_bounds_and_a_slip_keeps_its_direction():
    """``_candidate_ok``'s other conditions at their bounds, each alone deciding:
    - after an impulse the other end's gap rate may be −tol_rate exactly (≥ −tol_rate), and an
      open candidate's anchor gap rate likewise (−2, −1, −½ and 0 tol_rate, the tolerance made
      exactly representable as the product the check computes);
    - a slip candidate keeps its direction: after an impulse σ·ȧ⁺ ≥ 0 (ȧ⁺ = 0 allowed); from
      rest σ·ä > 0 strictly; already slipping, nothing is checked here (select_mode filters by
      ȧ's sign).
    - a stick holds up to |λ_t| = μs·λ_n + tol_force, that bound included.
    Ties at exactly the bound and at zero were reached by no run, so mutants moving them (90c30b41,
    46d3d89e, fa21fe14, 5d53466f) survived the other tests."""
    from rocking.stack.kinematics import end_gap_gradient
    from rocking.stack.modes import _candidate_ok

    stack = Stack(blocks=(Block(width=0.4, height=1.2, mass=100.0),),
                  interfaces=(Interface(friction=Friction(static=0.5, kinetic=0.4)),))
    P, ends, anchor, z = pack(stack)
    tol_force = 1e-10 * P[0, P_MASS] * G
    grad = end_gap_gradient(P, ends, anchor, 0, z, 1 - anchor[0])
    x1 = -1e-9 / grad[1]
    tol_rate = -(grad[1] * x1)  # the opening the check computes from x = (0, x1, 0), exactly
    lam = np.array([0.0, 0.0, P[0, P_MASS] * G])
    flat, rocking = np.array([FLAT]), np.array([ROCK])

    def ok(level, geo, nst, tst, x, zd=np.zeros(3), check_normal=True):
        return _candidate_ok(level, P, ends, anchor, geo, 0, nst, tst, z, zd, np.asarray(x, dtype=float), lam,
                             tol_force, tol_rate, check_normal)

    # the other end opening after an impulse, for a flat interface that would rock
    got = [ok(VELOCITY, flat, ROCK, 0, [0.0, f * x1, 0.0]) for f in (2.0, 1.0, 0.5, 0.0)]
    assert got == [False, True, True, True]
    # an open candidate's anchor after an impulse: its gap rate ḋ⁺
    got = [ok(VELOCITY, rocking, OPEN, 0, [0.0, 0.0, -f * tol_rate]) for f in (2.0, 1.0, 0.5, 0.0)]
    assert got == [False, True, True, True]
    # the slip's direction, the normal conditions left out
    for tst in (1, -1):
        after = [ok(VELOCITY, rocking, ROCK, tst, [v, 0.0, 0.0], check_normal=False) for v in (-1e-3, 0.0, 1e-3)]
        assert after == [tst < 0, True, tst > 0], tst
        start = [ok(ACCELERATION, rocking, ROCK, tst, [v, 0.0, 0.0], check_normal=False) for v in (-1e-3, 0.0, 1e-3)]
        assert start == [tst < 0, False, tst > 0], tst
        going = [ok(ACCELERATION, rocking, ROCK, tst, [v, 0.0, 0.0], zd=np.array([tst * 0.1, 0.0, 0.0]),
                    check_normal=False) for v in (-1e-3, 0.0, 1e-3)]
        assert going == [True, True, True], tst
    # a stick holds while |λ_t| ≤ μs·λ_n + tol_force, the bound included (dyadic: 0.5·8 + 2⁻²⁰)
    lam_n, tol = 8.0, 2.0 ** -20
    P_half = P.copy()
    P_half[0, P_MU_S] = 0.5
    for lam_t, holds in ((4.0 + tol, True), (-(4.0 + tol), True), (4.0 + 2 * tol, False), (-(4.0 + 2 * tol), False)):
        got = _candidate_ok(ACCELERATION, P_half, ends, anchor, rocking, 0, ROCK, 0, z, np.zeros(3), np.zeros(3),
                            np.array([lam_t, 0.0, lam_n]), tol, tol_rate, False)
        assert got == holds, lam_t


def test_a_flat_contact_holds_while_each_ends_normal_force_is_at_least_minus_the_tolerance():
    """``_candidate_ok`` for a flat interface: each end's normal force (``flat_forces``, from Λ_d
    and Λ_φ) may be −tol_force exactly, not below (−2, −1, −½ and 0 tol_force at one end, 8 N at
    the other). A 0.5 m block, so that the other end's lever is ±0.5 and every value is dyadic:
    the forces the check reads are the ones set, exactly. Mutant d744bdd7 (`n_o <= −tol_force`)
    moved the tie; no run puts a force on it."""
    from rocking.stack.kinematics import end_gap_gradient
    from rocking.stack.modes import _candidate_ok

    stack = Stack(blocks=(Block(width=0.5, height=1.0, mass=100.0),),
                  interfaces=(Interface(friction=Friction(static=0.5, kinetic=0.4)),))
    P, ends, anchor, z = pack(stack)
    grad = end_gap_gradient(P, ends, anchor, 0, z, 1 - anchor[0])
    assert grad[2] == 1.0 and abs(grad[1]) == 0.5
    tol = 2.0 ** -20

    def ok(n_a, n_o):
        lam = np.array([0.0, n_o * grad[1], n_a + n_o])
        assert flat_forces(P, ends, anchor, 0, z, lam) == (n_a, n_o)
        return _candidate_ok(ACCELERATION, P, ends, anchor, np.array([FLAT]), 0, FLAT, 0, z, np.zeros(3),
                             np.zeros(3), lam, tol, 1e-12, True)

    factors = (2.0, 1.0, 0.5, 0.0)
    assert [ok(8.0, -f * tol) for f in factors] == [False, True, True, True]
    assert [ok(-f * tol, 8.0) for f in factors] == [False, True, True, True]


def test_an_end_that_slides_past_the_lower_blocks_edge_becomes_that_blocks_corner():
    """``refresh_ends`` on a block 2.0 m wide (its corners at x = ±1.0 in its own frame, the same
    numbers as the end types END_L = 1 and END_U = 0) sliding on one 2.5 m wide: while its right
    corner is inside the lower face that corner makes the right end; slid 0.1 m past the lower
    block's edge, the right end is the lower block's corner at +1.25, the left end stays its own
    corner; slid back, its own corner again. (Comparing a type with a stored x, mutant 42e9c46f,
    or an x with a stored type, b9772f54, took 1.0 for 1 and kept the old corner here.)"""
    from rocking.stack.kinematics import END_L
    from rocking.stack.modes import refresh_ends

    stack = Stack(blocks=(Block(width=2.5, height=0.5, mass=300.0), Block(width=2.0, height=0.4, mass=50.0, offset=0.2)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.3, kinetic=0.2))))
    P, ends, anchor, z = pack(stack)
    assert anchor[1] == 0 and list(ends[1, 0]) == [END_U, -1.0] and list(ends[1, 1]) == [END_U, 1.0]
    z, zd = z.copy(), np.zeros(6)
    z[3] += 0.1  # the right corner at 1.3, past the edge at 1.25
    refresh_ends(P, ends, anchor, 1, z, zd, 1)
    assert list(ends[1, 1]) == [END_L, 1.25] and list(ends[1, 0]) == [END_U, -1.0]
    z[3] -= 0.2  # and back, the right corner at 1.1: its own corner again
    refresh_ends(P, ends, anchor, 1, z, zd, -1)
    assert list(ends[1, 1]) == [END_U, 1.0] and list(ends[1, 0]) == [END_U, -1.0]


def test_an_end_within_the_tolerance_of_the_lower_edge_is_a_tie_the_motion_decides():
    """``identify_ends`` at the bounds of its tie band: the upper block's left corner at
    x_l = −b_l + f·tol (and its right corner at b_l − f·tol), f = 2, 1, 0, −1, −2, with the
    block moving left, not at all, right. Beyond the band (|f| > 1) the inner corner makes the
    end whatever the motion; within it, bounds included (|x_l + b_l| ≤ tol), the one that stays
    inner as the block moves: its own corner unless it moves outwards. The positions are dyadic,
    so the corners sit on the bounds exactly. (Mutants moving the bounds by a comparison's
    equality, 6f0b2330, cc4cbad9, dc0c70a8, ad9ae035, 51b04fe7, were called equivalent: no run
    puts a corner exactly there.)"""
    from rocking.stack.kinematics import END_L
    from rocking.stack.modes import corner_x, identify_ends

    stack = Stack(blocks=(Block(width=1.0, height=0.5, mass=300.0), Block(width=0.5, height=0.4, mass=50.0)),
                  interfaces=(Interface(), Interface(friction=Friction(static=0.3, kinetic=0.2))))
    P, ends, anchor, z = pack(stack)
    assert anchor[1] == 0 and list(ends[1, 0]) == [END_U, -0.25]
    tol = 2.0 ** -20
    out = np.zeros((2, 2))
    for f in (2, 1, 0, -1, -2):
        for direction in (-1, 0, 1):
            for end in (0, 1):
                z = z.copy()
                z[3] = -0.5 + f * tol if end == 0 else -f * tol  # the anchor's (left) corner at a
                xl, xr = corner_x(P, ends, anchor, 1, z)
                assert (xl, xr)[end] == (-0.5 + f * tol if end == 0 else 0.5 - f * tol)
                identify_ends(P, ends, anchor, 1, z, direction, tol, out)
                outwards = direction < 0 if end == 0 else direction > 0
                own = f > 1 or (abs(f) <= 1 and not outwards)
                want = [END_U, (-0.25, 0.25)[end]] if own else [END_L, (-0.5, 0.5)[end]]
                assert list(out[end]) == want, (f, direction, end)


def test_the_mass_matrix_of_a_column_taller_than_the_parameter_table_is_wide():
    """``mass_and_forces`` on a column of 13 drums, one more than the 12 columns of the packed
    parameters P (a mutant sized its list of columns by P's width, c3efe1a9, and the random stacks
    have 1–3 blocks): M = JᵀWJ and f = Jᵀ(F − Wβ) from the oracle's poses, as in the test above."""
    from rocking.stack.kinematics import N_P, forward, mass_and_forces, new_frame

    n = N_P + 1
    rng = np.random.default_rng(13)
    stack = Stack(blocks=tuple(Block(width=rng.uniform(0.5, 0.6), height=rng.uniform(0.2, 0.4), mass=rng.uniform(50, 90))
                               for _ in range(n)), interfaces=tuple(Interface() for _ in range(n)))
    P, ends, anchor, z = pack(stack)
    assert P.shape == (n, N_P)
    z = z + rng.uniform(-0.01, 0.01, 3 * n)
    zd = rng.uniform(-0.2, 0.2, 3 * n)
    A, beta, C, X, Xd, th, thd = new_frame(n)
    forward(P, ends, anchor, z, zd, A, beta, C, X, Xd, th, thd)
    M, f = np.zeros((3 * n, 3 * n)), np.zeros(3 * n)
    mass_and_forces(P, A, beta, C, 1.5, -0.5, G, M, f)
    pose = lambda q: poses(P, ends, anchor, q)  # noqa: E731
    J, curv = jacobian(pose, z), curvature(pose, z, zd)
    W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(n)])
    F = np.concatenate([[-P[k, P_MASS] * 1.5, -P[k, P_MASS] * (G - 0.5), 0.0] for k in range(n)])
    M_want = J.T @ (W[:, None] * J)
    np.testing.assert_allclose(M, M_want, rtol=0, atol=1e-12 * np.abs(M_want).max())
    f_want = J.T @ (F - W * curv)
    np.testing.assert_allclose(f, f_want, rtol=0, atol=1e-8 * np.abs(f_want).max())


def test_the_selections_result_codes_are_distinct():
    """The engine tells a contact held in tension (SELECT_HELD: run on, the contact watched) from
    no consistent mode at all (SELECT_NONE: the run stops `inconsistent`) by the code alone; with
    SELECT_NONE equal to SELECT_HELD (mutant 05c47fef, which no run reached) a failed selection
    would run on as a held contact."""
    from rocking.stack.modes import SELECT_HELD

    assert len({SELECT_OK, SELECT_NONE, SELECT_HELD}) == 3
