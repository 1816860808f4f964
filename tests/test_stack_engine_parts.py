"""The parts of the stack engine (``rocking.stack.engine``) one at a time, against the independent
contact problem of tests/oracles/stack_contact.py and against SciPy's integrators.

The engine's own tests (tests/test_stack_engine.py) run whole simulations: a wrong guard, a
wrong ledger term or a wrong index into the state shows there only as a changed trajectory, and
only if a case happens to reach it. Here each compiled helper is called directly on random
stacks of one to three blocks in random states:

* the right-hand side of a mode: accelerations, contact forces and the energy ledger's rates;
* the guards: contact forces, gaps, friction margins, slip rates, overturning, overlap and the
  edge of the block below; the rest band that makes them affine in the floor's acceleration;
* the components a step integrates, one DOP853 and one Dormand–Prince 5(4) step and the dense
  output (against SciPy's ``DOP853`` and ``RK45``, which share no code with the engine);
* Housner's ratio and the restitution couple, the projection of an impact onto a mode, the
  energies and the energy allowance of an impact, the slip and slide direction, the saved rows,
  the peaks found inside a step, and the classification of the guards.

Tolerances: quantities the oracle gets exactly (complex step) to 1e-12 of their scale; those
that need its velocity terms (central differences, error ~1e-10) to 1e-7, as in
tests/test_stack_modes.py; the integrators to 1e-12 of the state's scale (both sum the same
tableau in a different order).

These tests compile only the helpers they call, so each takes seconds: they also make
bench/mutation.py's run of ``stack/engine.py`` fast (a mutant they kill costs no compilation of
the whole engine).
"""

import math

import numpy as np
import pytest
from oracles.stack_contact import G, Oracle, contact, jacobian, poses, random_state, random_states, relative, rot
from scipy.integrate import DOP853, RK45

from rocking.contact.friction import Friction
from rocking.excitation.signal import LOCAL_COSINE, LOCAL_LINEAR
from rocking.integrators import dop853
from rocking.stack import Block, Interface, Stack
from rocking.stack import engine as E
from rocking.stack.kinematics import (END_U, P_BL, P_BU, P_CAN_SLIP, P_HL, P_HU, P_IMPACT_PAPER, P_INERTIA, P_MASS,
                                      P_MU_K, P_MU_S, P_OFFSET, P_RESTITUTION, anchor_at)
from rocking.stack.modes import (ACCELERATION, FLAT, OPEN, ROCK, SELECT_OK, VELOCITY, corner_x, flat_forces,
                                 select_mode)
from rocking.stack.simulate import pack


def _friction(mu_s, mu_k):
    return Friction(static=mu_s, kinetic=mu_k)


# ---- random states in a mode --------------------------------------------------------------------
def _state_in_a_mode(rng):
    """A random stack in a random consistent state and the mode of that state: each interface in
    the normal state of its geometry; a closed one that slips has tstate = the sign of ȧ, one at
    rest any tstate (stuck, or starting to slip either way)."""
    while True:
        state = random_state(rng, ACCELERATION)
        if state is not None:
            break
    P, ends, anchor, geo, z, zd, _ = state
    n = P.shape[0]
    nstate = geo.copy()
    tstate = np.zeros(n, dtype=np.int64)
    for k in range(n):
        if nstate[k] >= ROCK and P[k, P_CAN_SLIP] > 0.5:
            v = zd[3 * k]
            tstate[k] = int(np.sign(v)) if v != 0.0 else int(rng.integers(-1, 2))
    return P, ends, anchor, geo, nstate, tstate, z, zd


def _combo(nstate, tstate):
    return tuple((int(nstate[k]), 0, int(tstate[k])) for k in range(nstate.shape[0]))


def _y(z, zd, ledger=(0.0, 0.0)):
    return np.concatenate([z, zd, ledger])


def _floor(ah, av):
    """A piece table row of a floor moving at constant accelerations ah, av (m/s²)."""
    return np.array([LOCAL_LINEAR, ah, 0.0, 0.0, 0.0, LOCAL_LINEAR, av, 0.0, 0.0, 0.0])


def _harmonic_floor(a_h, w_h, p_h, a_v, w_v, p_v):
    return np.array([LOCAL_COSINE, a_h, w_h, p_h, 0.0, LOCAL_COSINE, a_v, w_v, p_v, 0.0])


def _evaluate(P, ends, anchor, nstate, tstate, z, zd, ah, av):
    n = P.shape[0]
    ws = E.new_workspace(n)
    dy, lam = np.full(6 * n + 2, np.nan), np.full(3 * n, np.nan)
    ok = E.evaluate_at(P, ends, anchor, nstate, tstate, ah, av, _y(z, zd), G, dy, lam, ws)
    return ok, dy, lam


def _solved_states(rng, samples, ah_range, av_range):
    """``samples`` random states in their modes (``_state_in_a_mode``) under random floor
    accelerations (ranges in g), each with the oracle's solve of its mode: (P, ends, anchor,
    nstate, tstate, z, zd, ah, av, oracle, combo, solution). States whose contact problem is
    nearly singular are skipped (they count towards ``samples``)."""
    for _ in range(samples):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        ah, av = rng.uniform(*ah_range) * G, rng.uniform(*av_range) * G
        oracle = Oracle(P, ends, anchor, geo, z, zd, ah, av, ACCELERATION, np.zeros(3 * P.shape[0]))
        combo = _combo(nstate, tstate)
        solution = oracle.solve(combo)
        if solution is not None:
            yield P, ends, anchor, nstate, tstate, z, zd, ah, av, oracle, combo, solution


def _oracle_forces(oracle, solution, combo, k):
    """(N per closed end, total N, friction along the lower face) of interface k in the oracle's
    ``solution`` of ``combo``."""
    zdd, forces = solution
    normal = {e: v for (kind, kk, e), v in forces.items() if kind == "N" and kk == k}
    nst, _, tst = combo[k]
    total = sum(normal.values())
    if nst >= ROCK and tst == 0:
        friction = forces["T", k, oracle.anchor[k]]
    elif nst >= ROCK:
        friction = -oracle.P[k, P_MU_K] * oracle.sigma(k, 0, tst) * total
    else:
        friction = None
    return normal, total, friction


# ---- the right-hand side -------------------------------------------------------------------------
def test_the_right_hand_side_of_a_mode_is_its_contact_problem():
    """``evaluate_at``: ż, the mode's accelerations (as every block's absolute acceleration), its
    contact forces (the normal force of each closed end, the friction along the face), the power
    of the floor's d'Alembert forces −Σ m (a_h Ẋ + a_v Ẏ) and the power friction dissipates,
    μk·N·|slip rate|, all against the oracle's solve of the same mode."""
    rng = np.random.default_rng(31)
    kinds = set()
    for P, ends, anchor, nstate, tstate, z, zd, ah, av, oracle, combo, solution in _solved_states(
            rng, 80, (-1.2, 1.2), (-0.5, 0.5)):
        n = P.shape[0]
        ok, dy, lam = _evaluate(P, ends, anchor, nstate, tstate, z, zd, ah, av)
        assert ok
        nz = 3 * n
        assert np.array_equal(dy[:nz], zd)
        zdd, _ = solution
        want = oracle.J @ zdd + oracle.beta
        got = oracle.J @ dy[nz:2 * nz] + oracle.beta
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * (G + np.abs(want).max()))
        scale = np.sum(P[:, P_MASS]) * G
        p_in = -sum(P[k, P_MASS] * (ah * (oracle.J @ zd)[3 * k] + av * (oracle.J @ zd)[3 * k + 1]) for k in range(n))
        assert abs(dy[2 * nz] - p_in) <= 1e-12 * (abs(p_in) + scale * np.abs(zd).max())
        p_fric = 0.0
        for k in range(n):
            i = 3 * k
            normal, total, friction = _oracle_forces(oracle, solution, combo, k)
            if nstate[k] == FLAT:
                n_anchor, n_other = flat_forces(P, ends, anchor, k, z, lam)
                assert abs(n_anchor - normal[anchor[k]]) <= 1e-7 * scale
                assert abs(n_other - normal[1 - anchor[k]]) <= 1e-7 * scale
            elif nstate[k] == ROCK:
                assert abs(lam[i + 2] - normal[anchor[k]]) <= 1e-7 * scale
            if friction is not None:
                along = 1.0 if ends[k, anchor[k], 0] == END_U else -1.0
                assert abs(lam[i] - along * friction) <= 1e-7 * scale, (k, lam[i], friction)
                if tstate[k] != 0:
                    slip_rate = oracle.ds[k, anchor[k]] @ zd
                    p_fric += P[k, P_MU_K] * total * oracle.sigma(k, 0, int(tstate[k])) * slip_rate
            kinds.add((int(nstate[k]), int(tstate[k] != 0), int(ends[k, anchor[k], 0])))
        assert abs(dy[2 * nz + 1] - p_fric) <= 1e-7 * scale * (np.abs(zd).max() + 1e-3)
    # every normal state, stuck and slipping, on both kinds of anchor
    for kind in [(FLAT, 0, 0), (FLAT, 1, 0), (ROCK, 0, 0), (ROCK, 1, 0), (OPEN, 0, 0), (FLAT, 0, 1), (ROCK, 0, 1)]:
        assert kind in kinds, kind


def test_a_slipping_interface_dissipates_what_its_friction_force_does_work():
    """The ledger's friction rate is the power of the friction force on the slip: positive, and
    μk·N·|ȧ| for a flat block sliding on the floor (here with a_h = 0, N = m g, ȧ = 0.3 m/s)."""
    stack = Stack(blocks=(Block(width=0.4, height=0.6, mass=20.0),),
                  interfaces=(Interface(friction=_friction(0.5, 0.3)),))
    P, ends, anchor, z = pack(stack)
    for v in (0.3, -0.3):
        zd = np.array([v, 0.0, 0.0])
        tstate = np.array([int(np.sign(v))])
        ok, dy, lam = _evaluate(P, ends, anchor, np.array([FLAT]), tstate, z, zd, 0.0, 0.0)
        assert ok
        assert dy[7] == pytest.approx(0.3 * 20.0 * G * 0.3, rel=1e-14)
        assert dy[3] == pytest.approx(-np.sign(v) * 0.3 * G, rel=1e-14)  # decelerating at μk g
        assert dy[6] == 0.0  # no floor motion, no work done by it


def test_evaluate_reads_the_floor_acceleration_at_its_time():
    """``evaluate``/``guards`` at a time t are ``evaluate_at``/``guards_at`` at the floor's
    accelerations there, read from the piece table (horizontal first, vertical second), to the
    bit."""
    rng = np.random.default_rng(32)
    for _ in range(20):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        a_h, w_h, p_h, a_v, w_v, p_v = rng.uniform(0.5, 5.0), rng.uniform(1, 20), rng.uniform(0, 6), \
            rng.uniform(0.5, 3.0), rng.uniform(1, 20), rng.uniform(0, 6)
        loc = _harmonic_floor(a_h, w_h, p_h, a_v, w_v, p_v)
        t = rng.uniform(0.0, 10.0)
        ah, av = a_h * math.cos(w_h * t + p_h), a_v * math.cos(w_v * t + p_v)
        y = _y(z, zd)
        ws = E.new_workspace(n)
        dy1, lam1, dy2, lam2 = (np.zeros(6 * n + 2), np.zeros(3 * n), np.zeros(6 * n + 2), np.zeros(3 * n))
        E.evaluate(P, ends, anchor, nstate, tstate, t, y, loc, G, dy1, lam1, ws)
        E.evaluate_at(P, ends, anchor, nstate, tstate, ah, av, y, G, dy2, lam2, ws)
        assert np.array_equal(dy1, dy2) and np.array_equal(lam1, lam2)
        held = np.zeros(n, dtype=np.bool_)
        g1, g2 = np.zeros(n * E.N_GUARD_SLOTS), np.zeros(n * E.N_GUARD_SLOTS)
        E.guards(P, ends, anchor, nstate, tstate, t, y, loc, G, g1, held, ws)
        E.guards_at(P, ends, anchor, nstate, tstate, ah, av, y, G, g2, held, ws)
        assert np.array_equal(g1, g2)
        out = np.zeros(6 * n + 2)
        E._rhs(P, ends, anchor, nstate, tstate, t, y, loc, G, out, ws)
        assert np.array_equal(out, dy1)


# ---- the guards -----------------------------------------------------------------------------------
def _expected_guards(P, ends, anchor, nstate, tstate, z, zd, oracle, solution, held):
    """Each guard from its definition (docs/theory/stack.md §7), with the oracle's forces and
    geometry."""
    n = P.shape[0]
    want = np.ones(n * E.N_GUARD_SLOTS)
    combo = _combo(nstate, tstate)
    for k in range(n):
        b = k * E.N_GUARD_SLOTS
        i = 3 * k
        normal, total, friction = _oracle_forces(oracle, solution, combo, k)
        gap_other = contact(P, ends, anchor, k, z, 1 - anchor[k])[0]
        if nstate[k] == FLAT:
            want[b + E.G_ANCHOR], want[b + E.G_OTHER] = normal[anchor[k]], normal[1 - anchor[k]]
        elif nstate[k] == ROCK:
            want[b + E.G_ANCHOR], want[b + E.G_OTHER] = normal[anchor[k]], gap_other
        else:
            want[b + E.G_ANCHOR] = contact(P, ends, anchor, k, z, anchor[k])[0]
            want[b + E.G_OTHER] = gap_other
        if held[k]:
            want[b + E.G_ANCHOR] = 1.0
            if nstate[k] == FLAT:
                want[b + E.G_OTHER] = 1.0
        if nstate[k] >= ROCK and P[k, P_CAN_SLIP] > 0.5:
            along = 1.0 if ends[k, anchor[k], 0] == END_U else -1.0
            if tstate[k] == 0:
                want[b + E.G_STICK_POS] = P[k, P_MU_S] * total - along * friction
                want[b + E.G_STICK_NEG] = P[k, P_MU_S] * total + along * friction
            else:
                want[b + E.G_STICK_POS] = tstate[k] * zd[i]
        want[b + E.G_OVERTURN] = 0.5 * math.pi - abs(z[i + 1])
        if k >= 1:
            rx, _ = relative(P, ends, anchor, k, z[i], z[i + 1], z[i + 2])
            bu, hu, bl = P[k, P_BU], P[k, P_HU], P[k, P_BL]
            xl = rx + rot(z[i + 1], -bu, -hu)[0]
            xr = rx + rot(z[i + 1], bu, -hu)[0]
            want[b + E.G_OVERLAP] = min(xr, bl) - max(xl, -bl)
            if nstate[k] == FLAT and tstate[k] != 0:
                # how far each end's corner is from the lower block's edge it would pass
                want[b + E.G_EDGE] = min(abs(xl + bl), abs(bl - xr))
    return want


@pytest.mark.parametrize("with_held", [False, True], ids=["free", "held"])
def test_the_guards_are_the_modes_forces_gaps_and_margins(with_held):
    """``guards_at``: per interface, the anchor's normal force (an open interface: its gap d), the
    other end's force (flat) or gap, μs·N ∓ T of a stuck interface or σ·ȧ of a slipping one, the
    margin π/2 − |φ| to overturning, the overlap of the faces and, for a block sliding flat, its
    distance from the lower block's edge. A contact held in tension does not watch its forces."""
    rng = np.random.default_rng(33 + with_held)
    seen_edge = seen_overhang = 0
    for P, ends, anchor, nstate, tstate, z, zd, ah, av, oracle, _, solution in _solved_states(
            rng, 80, (-1.2, 1.2), (-0.5, 0.5)):
        n = P.shape[0]
        held = (rng.random(n) < 0.5) if with_held else np.zeros(n, dtype=np.bool_)
        g = np.full(n * E.N_GUARD_SLOTS, np.nan)
        E.guards_at(P, ends, anchor, nstate, tstate, ah, av, _y(z, zd), G, g, held, E.new_workspace(n))
        want = _expected_guards(P, ends, anchor, nstate, tstate, z, zd, oracle, solution, held)
        scale = np.sum(P[:, P_MASS]) * G
        force = np.array([E._is_force(j, nstate, tstate) for j in range(g.shape[0])])
        tol = np.where(force, 1e-7 * scale, 1e-12)
        assert np.all(np.abs(g - want) <= tol), np.nonzero(np.abs(g - want) > tol)
        for k in range(1, n):
            if nstate[k] == FLAT and tstate[k] != 0:
                seen_edge += 1
                seen_overhang += int(ends[k, 0, 0] != END_U or ends[k, 1, 0] != END_U)
    assert seen_edge >= 5 and seen_overhang >= 2


def test_the_guard_kinds_are_forces_gaps_and_slip_rates():
    """``_is_force``, ``_is_gap`` and ``_is_slip`` (which decide how an event is located and
    which tolerance applies) classify each guard by what it is: a force changes with the contact
    forces alone, a gap is a corner's distance from the face (the oracle's), a slip rate is σ·ȧ."""
    rng = np.random.default_rng(35)
    for _ in range(40):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        nz = 3 * n
        lam = rng.uniform(-100.0, 100.0, nz)
        held = np.zeros(n, dtype=np.bool_)
        y = _y(z, zd)
        g1, g2, g3 = (np.zeros(n * E.N_GUARD_SLOTS) for _ in range(3))
        E.guards_from(P, ends, anchor, nstate, tstate, y, lam, g1, held)
        E.guards_from(P, ends, anchor, nstate, tstate, y, 2.0 * lam + 1.0, g2, held)
        y3 = y.copy()
        y3[nz:2 * nz] = 2.0 * zd + 1.0
        E.guards_from(P, ends, anchor, nstate, tstate, y3, lam, g3, held)
        gaps = [contact(P, ends, anchor, k, z, e)[0] for k in range(n) for e in range(2)]
        for j in range(n * E.N_GUARD_SLOTS):
            k = j // E.N_GUARD_SLOTS
            if g1[j] == g2[j] == g3[j] == 1.0:
                continue  # a guard this mode does not watch (its kind is never asked)
            assert E._is_force(j, nstate, tstate) == (g1[j] != g2[j]), j
            assert E._is_slip(j, nstate, tstate) == (g1[j] != g3[j] and g1[j] == g2[j]), j
            is_gap = g1[j] == g2[j] and g1[j] == g3[j] and any(abs(g1[j] - v) < 1e-12 for v in gaps) \
                and j % E.N_GUARD_SLOTS in (E.G_ANCHOR, E.G_OTHER)
            assert E._is_gap(j, nstate) == is_gap, (j, nstate[k], g1[j])
        assert E._all_stuck(nstate, tstate) == all(nstate[k] == FLAT and tstate[k] == 0 for k in range(n))


def test_a_stack_at_rest_has_guards_affine_in_the_floor_acceleration():
    """``_rest_band``/``_band_guards``: at rest (ż = 0, every interface flat and stuck) each guard
    is affine in (a_h, a_v); the band gives the guards of any floor acceleration to rounding."""
    rng = np.random.default_rng(36)
    for _ in range(15):
        n = int(rng.integers(1, 4))
        blocks = tuple(Block(width=rng.uniform(0.2, 1.0), height=rng.uniform(0.2, 1.5), mass=rng.uniform(5, 300))
                       for _ in range(n))
        interfaces = tuple(Interface(friction=_friction(0.5, 0.4) if rng.random() < 0.7 else None) for _ in range(n))
        P, ends, anchor, z = pack(Stack(blocks=blocks, interfaces=interfaces))
        nstate, tstate = np.full(n, FLAT, dtype=np.int64), np.zeros(n, dtype=np.int64)
        held = np.zeros(n, dtype=np.bool_)
        y = _y(z, np.zeros(3 * n))
        ws = E.new_workspace(n)
        m = n * E.N_GUARD_SLOTS
        band0, band_h, band_v, g, want = (np.zeros(m) for _ in range(5))
        E._rest_band(P, ends, anchor, nstate, tstate, y, G, held, band0, band_h, band_v, ws)
        for _ in range(5):
            ah, av = rng.uniform(-8.0, 8.0), rng.uniform(-5.0, 5.0)
            E._band_guards(band0, band_h, band_v, _floor(ah, av), 0.0, g)
            E.guards_at(P, ends, anchor, nstate, tstate, ah, av, y, G, want, held, ws)
            scale = np.sum(P[:, P_MASS]) * G
            np.testing.assert_allclose(g, want, rtol=0, atol=1e-12 * scale)


# ---- the step ---------------------------------------------------------------------------------------
def _frozen(P, nstate, tstate):
    """The coordinates a mode holds still (docs/theory/stack.md §4): d of a closed interface, φ
    of a flat one, a of a closed one that sticks or never slips."""
    out = []
    for k in range(P.shape[0]):
        closed = nstate[k] >= ROCK
        out += [closed and (tstate[k] == 0 or P[k, P_CAN_SLIP] < 0.5), nstate[k] == FLAT, closed]
    return np.array(out)


def test_a_step_integrates_the_free_coordinates_and_whatever_still_moves():
    """``_moving``: first, in increasing order, the free coordinates and any held one whose rate
    is not zero, then the free coordinates' rates, then the two ledger entries; then the rest.
    A single block integrates everything."""
    rng = np.random.default_rng(37)
    for _ in range(60):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        nz = 3 * n
        if rng.random() < 0.3:
            zd = zd + (rng.random(nz) < 0.3) * rng.uniform(-1, 1, nz)  # held coordinates still moving
        y = _y(z, zd)
        ws = E.new_workspace(n)
        E._moving(P, nstate, tstate, y, ws)
        act, m = ws[E.WS_ACT], ws[E.WS_N_ACT][0]
        if n == 1:
            assert m == 2 * nz + 2 and np.array_equal(act, np.arange(2 * nz + 2))
            continue
        frozen = _frozen(P, nstate, tstate)
        moving = [i for i in range(nz) if not frozen[i] or zd[i] != 0.0]
        rates = [nz + i for i in range(nz) if not frozen[i]]
        first = moving + rates + [2 * nz, 2 * nz + 1]
        rest = [i for i in range(nz) if i not in moving] + [nz + i for i in range(nz) if frozen[i]]
        assert m == len(first)
        assert list(act) == first + rest


def _one_scipy_step(method, fun, t, y, h):
    solver = method(fun, t, y, t + 2 * h, first_step=h, max_step=h, rtol=1e3, atol=1e3)
    solver.step()
    assert solver.status == "running" and solver.t == t + h
    return solver


@pytest.mark.parametrize("kind", ["dop853", "dopri5"])
def test_one_step_is_scipys_step_of_the_same_right_hand_side(kind):
    """``_step`` (DOP853) and ``_step5`` (Dormand–Prince 5(4)) on the moving components give
    SciPy's DOP853 and RK45 step of the full state, ledger included; the frozen components stay
    put to the bit; the step's end holds the right-hand side and contact forces there; DOP853's
    dense output (``_dense_prepare``) is SciPy's at interior points."""
    rng = np.random.default_rng(38 + (kind == "dopri5"))
    for _ in range(12):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        nz = 3 * n
        ny = 2 * nz + 2
        loc = _harmonic_floor(3.0, 9.0, 0.4, 1.0, 14.0, 1.1)
        t, h = rng.uniform(0.0, 5.0), 2e-3
        y = _y(z, zd, ledger=(rng.uniform(-1, 1), rng.uniform(0, 1)))
        ws = E.new_workspace(n)

        def fun(tt, yy):
            out = np.zeros(ny)
            E._rhs(P, ends, anchor, nstate, tstate, tt, np.ascontiguousarray(yy), loc, G, out, E.new_workspace(n))
            return out

        E._moving(P, nstate, tstate, y, ws)
        K = np.zeros((dop853.N_K, ny))
        K[0] = fun(t, y)
        y_new = np.zeros(ny)
        if kind == "dop853":
            err = E._step(P, ends, anchor, nstate, tstate, t, y, h, loc, G, K, y_new, 1e-10, 1e-10, ny, ws)
            solver = _one_scipy_step(DOP853, fun, t, y, h)
            end = K[dop853.FSAL]
        else:
            err = E._step5(P, ends, anchor, nstate, tstate, t, y, h, loc, G, K, y_new, 1e-10, 1e-10, ny, ws)
            solver = _one_scipy_step(RK45, fun, t, y, h)
            end = K[E.FSAL5]
        scale = np.abs(y).max() + h * np.abs(K[0]).max()
        np.testing.assert_allclose(y_new, solver.y, rtol=0, atol=1e-12 * scale)
        assert math.isfinite(err) and err >= 0.0
        frozen = _frozen(P, nstate, tstate)
        still = [i for i in range(nz) if frozen[i] and zd[i] == 0.0] + [nz + i for i in range(nz) if frozen[i]]
        assert np.array_equal(y_new[still], y[still])
        lam_end = np.zeros(nz)
        want_end = np.zeros(ny)
        E.evaluate(P, ends, anchor, nstate, tstate, t + h, y_new, loc, G, want_end, lam_end, E.new_workspace(n))
        assert np.array_equal(end, want_end) and np.array_equal(ws[E.WS_LAM_END], lam_end)
        if kind == "dop853":
            F = np.zeros((dop853.INTERPOLATOR_POWER, ny))
            E._dense_prepare(P, ends, anchor, nstate, tstate, t, y, y_new, h, loc, G, K, F, ws)
            dense = solver.dense_output()
            out = np.zeros(ny)
            for x in (0.1, 0.37, 0.5, 0.83):
                dop853.dense_on(y, F, x, out, ws[E.WS_ACT], ws[E.WS_N_ACT][0])
                np.testing.assert_allclose(out, dense(t + x * h), rtol=0, atol=1e-12 * scale)


def test_a_rejected_step_reports_its_error_above_one():
    """The error norm a step returns is what decides acceptance: a step 100 times too long for
    the tolerance reports more than 1, a short one less."""
    stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=100.0),), interfaces=(Interface(),))
    P, ends, anchor, z = pack(stack)
    z = z.copy()
    z[1] = -0.05
    zd = np.array([0.0, 0.8, 0.0])
    nstate, tstate = np.array([ROCK]), np.array([0])
    loc = _harmonic_floor(3.0, 9.0, 0.4, 0.0, 1.0, 0.0)
    errors = []
    for h in (1e-3, 0.3):
        y = _y(z, zd)
        ws = E.new_workspace(1)
        E._moving(P, nstate, tstate, y, ws)
        K = np.zeros((dop853.N_K, 8))
        E._rhs(P, ends, anchor, nstate, tstate, 0.0, y, loc, G, K[0], ws)
        errors.append(E._step(P, ends, anchor, nstate, tstate, 0.0, y, h, loc, G, K, np.zeros(8), 1e-10, 1e-10, 8,
                              ws))
    assert errors[0] < 1.0 < errors[1]


# ---- impacts ----------------------------------------------------------------------------------------
def _contact_point(P, ends, anchor, k, z, e):
    """End e's contact point in the lower block's frame."""
    i = 3 * k
    kind, x_e = ends[k, e]
    if kind == END_U:
        cx, cy = relative(P, ends, anchor, k, z[i], z[i + 1], z[i + 2])
        px, py = rot(z[i + 1], x_e, -P[k, P_HU])
        return np.array([cx + px, cy + py])
    return np.array([x_e, P[k, P_HL]])


def test_housners_ratio_is_the_angular_momentum_about_the_new_corner():
    """``_housner_ratio``: blocks k … top as one rigid body (as they stand) turning at ω about
    block k's old corner p₀ land on p₁ and go on about p₁ alone. The angular momentum about p₁ is
    kept: Σ_j J_j ω + m_j (c_j − p₁) × (ω × (c_j − p₀)) = I₁ ω⁺, I₁ = Σ_j J_j + m_j |c_j − p₁|²,
    k ≤ j ≤ top, the centres c_j from the oracle's poses. For a uniform block on its own corners
    that is Housner's 1 − (3/2) sin² α."""
    rng = np.random.default_rng(39)
    checked = above = 0
    while checked < 60:
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        k = int(rng.integers(0, n))
        i = 3 * k
        z = z.copy()
        z[i + 1] = z[i + 2] = 0.0  # flat, at the instant of the landing
        world = poses(P, ends, anchor, z).reshape(n, 3)
        below = world[k - 1] if k > 0 else np.zeros(3)  # the frame the contact points are given in
        p1, p0 = (below[:2] + np.array(rot(below[2], *_contact_point(P, ends, anchor, k, z, e)))
                  for e in (anchor[k], 1 - anchor[k]))
        top = int(rng.integers(k, n))
        num = i_1 = 0.0
        for j in range(k, top + 1):
            m, J = P[j, P_MASS], P[j, P_INERTIA]
            r1, r0 = world[j, :2] - p1, world[j, :2] - p0
            v = np.array([-r0[1], r0[0]])  # ω ẑ × (c − p₀), ω = 1
            num += J + m * (r1[0] * v[1] - r1[1] * v[0])
            i_1 += J + m * (r1 @ r1)
        got_ratio, got_i = E._housner_ratio(P, ends, anchor, k, z, top)
        assert got_i == pytest.approx(i_1, rel=1e-13)
        assert got_ratio == pytest.approx(num / i_1, rel=1e-12, abs=1e-13)
        checked += 1
        above += top > k
    assert above >= 12  # the blocks above, tilted as they stand, are counted (15 of the 60)
    # Housner's uniform block on its own corners
    b, h = 0.15, 0.6
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=2 * b, height=2 * h, mass=7.0),), interfaces=(Interface(),)))
    alpha = math.atan2(b, h)
    assert E._housner_ratio(P, ends, anchor, 0, z, 0)[0] == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-14)


def test_the_restitution_couple_gives_the_chosen_restitution():
    """``_housner_couple``: a single block landing on its other corner, given the couple of its
    interface's restitution r, leaves that corner turning at r times its rate before (the impact
    solved by ``select_mode`` at the velocity level): the seed's impact law. With no r (NaN) the
    couple is zero: the plastic impact, Housner's ratio."""
    for r in (0.3, 0.75, float("nan")):
        interface = Interface(restitution=None if math.isnan(r) else r)
        stack = Stack(blocks=(Block(width=0.4, height=1.4, mass=80.0),), interfaces=(interface,))
        P, ends, anchor, z = pack(stack)
        assert math.isnan(P[0, P_RESTITUTION]) == math.isnan(r)
        # rocking about the left corner (anchor 0, φ < 0), φ reaching 0 with φ̇ > 0: lands on the right
        z, zd = z.copy(), np.array([0.0, 0.9, 0.0])
        a, d, ad, dd = anchor_at(P, ends, anchor, 0, z, zd, 1, ends[0, 1, 0], ends[0, 1, 1])
        anchor = np.array([1])
        z[0], z[2], zd[0], zd[2] = a, d, ad, dd
        assert dd < 0.0  # the right corner comes down
        extra = np.full(3, 7.0)  # stale values, cleared
        E._housner_couple(P, ends, anchor, 0, z, zd, 0, extra)
        r_h, i_o = E._housner_ratio(P, ends, anchor, 0, z, 0)
        want = 0.0 if math.isnan(r) else (r - r_h) * i_o * zd[1]
        assert extra[0] == 0.0 and extra[2] == 0.0 and extra[1] == pytest.approx(want, rel=1e-14, abs=0.0)
        nstate, tstate = np.zeros(1, dtype=np.int64), np.zeros(1, dtype=np.int64)
        x, lam = np.zeros(3), np.zeros(3)
        code = select_mode(VELOCITY, P, ends, anchor, np.array([FLAT]), z, zd, 0.0, 0.0, G, extra, nstate, tstate,
                           -1, 0, 1e-10 * 80 * G, 1e-12, x, lam)
        assert code == SELECT_OK and nstate[0] == ROCK and anchor[0] == 1
        want_rate = (r_h if math.isnan(r) else r) * 0.9
        assert x[1] == pytest.approx(want_rate, rel=1e-12)
        assert x[0] == 0.0 and x[2] == 0.0


def test_the_body_that_lands_is_the_blocks_held_flat_and_stuck_on_the_one_that_lands():
    """``_held_on``: block k and every block above it standing flat and stuck on the one below (or
    on a face that never slips), up to the first that rocks, slides or flies."""
    drum = Block(width=0.4, height=1.0, mass=100.0)
    slips = Interface(friction=Friction(static=0.5, kinetic=0.4))
    P, *_ = pack(Stack(blocks=(drum,) * 4, interfaces=(Interface(), slips, Interface(), slips)))
    stuck, sliding = np.zeros(4, dtype=np.int64), np.array([0, 0, 0, 1])
    assert E._held_on(P, np.full(4, FLAT), stuck, 0) == 3
    assert E._held_on(P, np.full(4, FLAT), sliding, 0) == 2  # the top block slides
    assert E._held_on(P, np.full(4, FLAT), np.array([0, 0, 1, 0]), 1) == 3  # a face that never slips
    assert E._held_on(P, np.array([ROCK, FLAT, ROCK, FLAT]), stuck, 0) == 1  # block 3 rocks on block 2
    assert E._held_on(P, np.array([ROCK, OPEN, FLAT, FLAT]), stuck, 0) == 0  # block 2 flies
    assert E._held_on(P, np.full(4, FLAT), stuck, 3) == 3


def test_the_restitution_impulse_turns_the_body_that_lands_as_one():
    """``_housner_couple`` on a column of three drums landing as one on the floor: its parts on the
    coordinates above the floor interface are M e_φ·Δω of the column's own mass matrix (the
    oracle's, from its poses), none on a_0 and d_0 (no net force on the column: momentum is kept),
    and the impact solved at the velocity level (``select_mode``) leaves the column turning at
    r times its rate before, as one body (the joints' relative rates zero). With the top drum
    sliding it is not part of the body: the impulse stops at the middle drum."""
    drum = Block(width=0.4, height=1.0, mass=100.0)
    r = 0.6
    for top_slides in (False, True):
        top = Interface(friction=Friction(static=0.5, kinetic=0.4)) if top_slides else Interface()
        P, ends, anchor, z = pack(Stack(blocks=(drum,) * 3, interfaces=(Interface(restitution=r), Interface(), top)))
        zd = np.zeros(9)
        zd[1] = 0.9
        a, d, ad, dd = anchor_at(P, ends, anchor, 0, z, zd, 1, ends[0, 1, 0], ends[0, 1, 1])
        anchor = anchor.copy()
        anchor[0] = 1
        z, zd = z.copy(), zd.copy()
        z[0], z[2], zd[0], zd[2] = a, d, ad, dd
        nstate = np.array([ROCK, FLAT, FLAT])
        tstate = np.array([0, 0, 1 if top_slides else 0])
        held = E._held_on(P, nstate, tstate, 0)
        assert held == (1 if top_slides else 2)
        extra = np.zeros(9)
        dw = E._housner_couple(P, ends, anchor, 0, z, zd, held, extra)
        r_h, i_o = E._housner_ratio(P, ends, anchor, 0, z, held)
        assert dw == pytest.approx((r - r_h) * 0.9, rel=1e-14)
        # the mass matrix of the landing body alone, from the oracle's poses
        W = np.concatenate([[P[j, P_MASS], P[j, P_MASS], P[j, P_INERTIA]] if j <= held else [0.0, 0.0, 0.0]
                            for j in range(3)])
        Jp = jacobian(lambda q: poses(P, ends, anchor, q), z)
        M = Jp.T @ (W[:, None] * Jp)
        assert M[1, 1] == pytest.approx(i_o, rel=1e-12)
        want = np.zeros(9)
        want[1] = i_o * dw
        want[3:3 * held + 3] = M[3:3 * held + 3, 1] * dw
        np.testing.assert_allclose(extra, want, rtol=0, atol=1e-12 * i_o * abs(dw))
        assert extra[0] == extra[2] == 0.0 and not np.any(extra[3 * held + 3:])
        if top_slides:
            continue
        x, lam = np.zeros(9), np.zeros(9)
        code = select_mode(VELOCITY, P, ends, anchor, np.array([FLAT, FLAT, FLAT]), z, zd, 0.0, 0.0, G, extra,
                           nstate, tstate, -1, 0, 1e-10 * 300 * G, 1e-12, x, lam)
        assert code == SELECT_OK and list(nstate) == [ROCK, FLAT, FLAT] and anchor[0] == 1
        assert x[1] == pytest.approx(r * 0.9, rel=1e-12)
        np.testing.assert_allclose(x[3:], 0.0, atol=1e-12)
        # the column's own Housner value: I_O and r_H of the uniform 0.4 × 3 m block it is
        alpha = math.atan2(0.2, 1.5)
        assert r_h == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-13)
        assert i_o == pytest.approx(300.0 * (0.2 ** 2 + 1.5 ** 2) * 4 / 3, rel=1e-13)


def test_the_friction_an_impact_needs_leaves_out_the_restitution_impulse_on_the_blocks_above():
    """``_momentum_before_less_kick``: the part of the restitution impulse that acts on blocks
    k+1 … top (each the momentum of a rigid turn about the new corner, m_j Δω × (c_j − O), from
    the oracle's poses) is added to their velocities before, and its opposite to block k's, so
    that it does not count as crossing the interfaces: summed over the body it is zero."""
    drum = Block(width=0.4, height=1.0, mass=100.0)
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.8, height=0.3, mass=300.0), drum, Block(width=0.3, height=0.5, mass=20.0)),
                                    interfaces=(Interface(), Interface(restitution=0.5), Interface())))
    rng = np.random.default_rng(7)
    before = rng.uniform(-1, 1, (3, 2))
    dw, scale = 0.37, 0.6
    out = E._momentum_before_less_kick(P, ends, anchor, 1, z, dw, scale, 2, before)
    world = poses(P, ends, anchor, z).reshape(3, 3)
    corner = world[0, :2] + np.array(rot(world[0, 2], *_contact_point(P, ends, anchor, 1, z, anchor[1])))
    rel = world[2, :2] - corner
    w = scale * dw
    # φ turns clockwise positive (R = [[cos, sin], [−sin, cos]]): v = w (rel_y, −rel_x)
    kick = w * np.array([rel[1], -rel[0]])
    np.testing.assert_allclose(out[2], before[2] + kick, rtol=0, atol=1e-14)
    np.testing.assert_allclose(out[1], before[1] - P[2, P_MASS] * kick / P[1, P_MASS], rtol=0, atol=1e-14)
    np.testing.assert_array_equal(out[0], before[0])
    np.testing.assert_array_equal(E._momentum_before_less_kick(P, ends, anchor, 1, z, dw, scale, 1, before), before)
    np.testing.assert_array_equal(E._momentum_before_less_kick(P, ends, anchor, 1, z, 0.0, scale, 2, before), before)


def test_the_friction_an_impact_needs_is_the_impulse_across_each_face_over_its_normal_part():
    """``_impact_needs``: the impulse across interface j is the change of momentum of blocks j …
    top, Σ m_i (V_i⁺ − V_i⁻), with V⁺ from the oracle's poses differentiated along ż⁺. Split along
    the face the anchor touches (the lower block's top for an upper corner, the block's own base
    for a lower corner: the unit vectors rot(Θ, 1, 0) and rot(Θ, 0, 1)), it needs |J_t|/J_n,
    booked where the interface sticks (or cannot slip) under a stack that stands (each block up
    to it closed and within atan(b/h)), and where J_n exceeds 1e-6 of the momentum scale Σ m|V⁻|.
    Random stacks and velocities; both kinds of anchor, slipping and tipped interfaces among
    them. 1e-9 relative: the complex-step Jacobian is exact to rounding, the ratios are of order 1."""
    rng = np.random.default_rng(20261209)
    kinds = set()
    for P, ends, anchor, geo, z, zd, _ in random_states(rng, 120, VELOCITY):
        n = P.shape[0]
        tstate = np.array([int(rng.integers(-1, 2)) if geo[k] >= ROCK and P[k, P_CAN_SLIP] > 0.5 else 0
                           for k in range(n)])
        before = rng.uniform(-1.0, 1.0, (n, 2))
        summ = np.zeros((n, E.N_BLOCK_SUMMARY))
        summ[:, E.B_MU_REQ] = rng.uniform(0.0, 0.5, n) * (rng.random(n) < 0.3)
        booked_before = summ[:, E.B_MU_REQ].copy()
        E._impact_needs(P, ends, anchor, geo, tstate, z, zd, before, summ, 0.0)
        velocity = (jacobian(lambda zz: poses(P, ends, anchor, zz), z) @ zd).reshape(n, 3)
        theta = poses(P, ends, anchor, z)[2::3]
        scale = sum(P[i, P_MASS] * math.hypot(*before[i]) for i in range(n))
        for j in range(n):
            impulse = sum(P[i, P_MASS] * (velocity[i, :2] - before[i]) for i in range(j, n))
            own = ends[j, anchor[j], 0] != END_U
            face = theta[j] if own else (theta[j - 1] if j > 0 else 0.0)
            j_t = impulse @ np.array(rot(face, 1.0, 0.0))
            j_n = impulse @ np.array(rot(face, 0.0, 1.0))
            sticks = tstate[j] == 0 or P[j, P_CAN_SLIP] < 0.5
            stands = all(geo[i] >= ROCK and abs(z[3 * i + 1]) < math.atan2(P[i, P_BU], P[i, P_HU])
                         for i in range(j + 1))
            want = booked_before[j]
            if sticks and stands and j_n > 1e-6 * scale:
                want = max(want, abs(j_t) / j_n)
                kinds.add(("booked", own))
            else:
                kinds.add("slips" if not sticks else ("falls or flies" if not stands else "pulls"))
            assert summ[j, E.B_MU_REQ] == pytest.approx(want, rel=1e-9, abs=1e-15), (j, want)
    assert {("booked", True), ("booked", False), "slips", "falls or flies", "pulls"} <= kinds
    # the threshold: a block at rest after an impulse m(1, ε) (from V⁻ = −(1, ε)), booked at
    # 1/ε for ε = 2e-6 of the scale m·|V⁻| and not for 5e-7
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.4, height=0.8, mass=30.0),), interfaces=(Interface(),)))
    for eps, want in ((2e-6, 5e5), (5e-7, 0.0)):
        summ = np.zeros((1, E.N_BLOCK_SUMMARY))
        E._impact_needs(P, ends, anchor, np.array([FLAT]), np.array([0]), z, np.zeros(3), np.array([[-1.0, -eps]]),
                        summ, 0.0)
        assert summ[0, E.B_MU_REQ] == pytest.approx(want, rel=1e-12), eps


def test_an_impact_stuck_within_the_solves_slack_needs_its_mu_s_at_most():
    """The impulse solve accepts a stick with |J_t| ≤ μs·J_n + tol (``tol_impulse``): the exact
    impulse is then inside the friction cone, and the need booked is μs, not the solved ratio. A
    block (30 kg, μs = 0.5) brought to rest from V⁻ = −(0.5 + δ, 1) m/s takes J = m(0.5 + δ, 1):
    with the slack just above m·δ its need is μs, just below it 0.5 + δ; a face that cannot slip
    has no μs to stop at; a zero slack books the ratio. Until 2026-12-07 the ratio was booked, and
    micro-impacts in 3 of 1500 random stacks read up to 0.2 % above μs: the report failed those
    faces as needing more than μs without slipping."""
    delta, m = 1e-4, 30.0
    for friction, tol, want in ((Friction(static=0.5, kinetic=0.4), 1.01 * m * delta, 0.5),
                                (Friction(static=0.5, kinetic=0.4), 0.99 * m * delta, 0.5 + delta),
                                (Friction(static=0.5, kinetic=0.4), 0.0, 0.5 + delta),
                                (None, 1.01 * m * delta, 0.5 + delta)):
        P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.4, height=0.8, mass=m),),
                                        interfaces=(Interface(friction=friction),)))
        summ = np.zeros((1, E.N_BLOCK_SUMMARY))
        E._impact_needs(P, ends, anchor, np.array([FLAT]), np.array([0]), z, np.zeros(3),
                        np.array([[-(0.5 + delta), -1.0]]), summ, tol)
        assert summ[0, E.B_MU_REQ] == pytest.approx(want, rel=1e-12), (friction, tol)


def test_projecting_onto_a_mode_is_the_nearest_velocity_in_kinetic_energy():
    """``_project_onto_mode``: the velocity with the mode's frozen coordinates at zero that is
    nearest to ż in the kinetic-energy metric (oracle mass matrix), so the kinetic energy falls by
    ½ (ż − ż⁺)ᵀ M (ż − ż⁺) ≥ 0."""
    rng = np.random.default_rng(40)
    for _ in range(30):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        nz = 3 * n
        zd = rng.uniform(-1.0, 1.0, nz)
        pose = lambda q: poses(P, ends, anchor, q)  # noqa: E731
        Jp = jacobian(pose, z)
        W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(n)])
        M = Jp.T @ (W[:, None] * Jp)
        free = ~_frozen(P, nstate, tstate)
        want = np.zeros(nz)
        if free.any():
            want[free] = np.linalg.solve(M[np.ix_(free, free)], (M @ zd)[free])
        got = zd.copy()
        E._project_onto_mode(P, ends, anchor, nstate, tstate, z, got, 0.0, 0.0, G)
        assert np.array_equal(got[~free], np.zeros(int((~free).sum())))
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * (1 + np.abs(want).max()))
        loss = 0.5 * zd @ M @ zd - 0.5 * got @ M @ got
        assert loss == pytest.approx(0.5 * (zd - got) @ M @ (zd - got), rel=1e-9, abs=1e-12)


def test_the_energy_an_impact_may_add_is_its_rounding_and_the_rest_motion():
    """``_energy_allowance`` is 1e-9 of the kinetic energy before the impact plus the kinetic
    energy of every block moving at the rest velocity × its size (half-width + half-height);
    ``_creates_energy`` compares the outcome's kinetic energy (the oracle's) with that."""
    rng = np.random.default_rng(41)
    for _ in range(20):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        t_before, rest = rng.uniform(0.0, 50.0), rng.uniform(1e-6, 1e-3)
        e_rest = sum(0.5 * P[k, P_MASS] * (rest * (P[k, P_BU] + P[k, P_HU])) ** 2 for k in range(n))
        allowance = E._energy_allowance(P, t_before, rest)
        assert allowance == pytest.approx(1e-9 * t_before + e_rest, rel=1e-14)
        zd = rng.uniform(-1.0, 1.0, 3 * n)
        qd = jacobian(lambda q: poses(P, ends, anchor, q), z) @ zd  # noqa: E731
        W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(n)])
        kinetic = 0.5 * np.sum(W * qd ** 2)
        assert E._kinetic_of(P, ends, anchor, z, zd) == pytest.approx(kinetic, rel=1e-12)
        after = np.concatenate([zd, np.zeros(3 * n)])  # (it reads the first 3N entries only)
        assert E._creates_energy(P, ends, anchor, z, after, kinetic * (1 - 1e-6) - allowance, allowance)
        assert not E._creates_energy(P, ends, anchor, z, after, kinetic * (1 + 1e-6) - allowance, allowance)


# ---- what the run saves and tracks ---------------------------------------------------------------------
def test_the_slip_is_the_blocks_displacement_on_the_block_below():
    """``slip_of``: with the interface flat, how far block k's centre has moved along the block
    below from where it was placed (its offset), whichever corner anchors it."""
    rng = np.random.default_rng(42)
    kinds = set()
    for _ in range(60):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        k = int(rng.integers(0, P.shape[0]))
        i = 3 * k
        z = z.copy()
        z[i] += rng.uniform(-0.1, 0.1)
        z[i + 1] = z[i + 2] = 0.0
        rx, _ = relative(P, ends, anchor, k, z[i], 0.0, 0.0)
        assert E.slip_of(P, ends, anchor, k, z) == pytest.approx(rx - P[k, P_OFFSET], abs=1e-14)
        kinds.add(int(ends[k, anchor[k], 0]))
    assert kinds == {0, 1}


def test_the_slide_direction_is_the_way_the_block_moves_on_the_one_below():
    """``_slide_direction``: the sign of the block's velocity relative to the block below (the
    oracle's slip rate), or at the start of a slip (ȧ = 0) the way its slip state points."""
    rng = np.random.default_rng(43)
    kinds = set()
    for _ in range(60):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        k = int(rng.integers(0, n))
        zd = zd.copy()
        moving = rng.random() < 0.5
        zd[3 * k] = rng.choice([-1.0, 1.0]) * rng.uniform(0.01, 0.5) if moving else 0.0
        oracle = Oracle(P, ends, anchor, geo, z, zd, 0.0, 0.0, ACCELERATION, np.zeros(3 * n))
        for sigma in (-1, 0, 1):
            got = E._slide_direction(ends, anchor, k, zd, sigma)
            if moving:
                assert got == np.sign(oracle.ds[k, anchor[k]] @ zd)
            else:
                assert got == oracle.sigma(k, 0, sigma)
        kinds.add((moving, int(ends[k, anchor[k], 0])))
    assert len(kinds) == 4


def test_a_saved_row_holds_the_poses_the_interfaces_and_the_ledger():
    """``_save_row``: t; per block X, Y, Θ, Ẋ, Ẏ, Θ̇ (the oracle's poses and their rates); per
    interface φ, the slip, the normal and tangential states; then the energy (kinetic +
    potential), the work of the floor, the friction loss and the impact loss."""
    rng = np.random.default_rng(44)
    for _ in range(20):
        P, ends, anchor, geo, nstate, tstate, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        ledger = rng.uniform(-5.0, 5.0, 2)
        samples = np.full((3, 1 + E.N_BLOCK_COLS * n + E.N_IFACE_COLS * n + E.N_TAIL), np.nan)
        t, d_impact = rng.uniform(0, 10), rng.uniform(0, 3)
        E._save_row(P, ends, anchor, nstate, tstate, t, _y(z, zd, ledger), G, np.zeros(n), d_impact, samples, 1,
                    E.new_workspace(n))
        row = samples[1]
        assert np.isnan(samples[0]).all() and np.isnan(samples[2]).all()
        q = poses(P, ends, anchor, z)
        qd = jacobian(lambda qq: poses(P, ends, anchor, qq), z) @ zd  # noqa: E731
        assert row[0] == t
        blocks = row[1:1 + E.N_BLOCK_COLS * n].reshape(n, E.N_BLOCK_COLS)
        np.testing.assert_allclose(blocks[:, :3], q.reshape(n, 3), rtol=0, atol=1e-12)
        np.testing.assert_allclose(blocks[:, 3:], qd.reshape(n, 3), rtol=0, atol=1e-12)
        ifaces = row[1 + E.N_BLOCK_COLS * n:1 + (E.N_BLOCK_COLS + E.N_IFACE_COLS) * n].reshape(n, E.N_IFACE_COLS)
        for k in range(n):
            assert ifaces[k, 0] == z[3 * k + 1]
            assert ifaces[k, 1] == E.slip_of(P, ends, anchor, k, z)
            assert (ifaces[k, 2], ifaces[k, 3]) == (nstate[k], tstate[k])
        W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(n)])
        e = 0.5 * np.sum(W * qd ** 2) + G * np.sum(P[:, P_MASS] * q[1::3])
        tail = row[-E.N_TAIL:]
        assert tail[0] == pytest.approx(e, rel=1e-12, abs=1e-12)
        assert list(tail[1:]) == [ledger[0], ledger[1], d_impact]
        assert E._energy_of(P, ends, anchor, _y(z, zd), G) == tail[0]


def test_a_turning_point_inside_a_step_counts_for_the_peaks():
    """``_peaks_inside``: where a block's rate of rotation changes sign inside the step, its angle
    there counts for the peak of φ (its own interface) and of θ (the sum up to it), read from the
    dense output; a turning point beyond the step's used fraction does not."""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0),
                                            Block(width=0.3, height=1.2, mass=100.0)),
                                    interfaces=(Interface(), Interface())))
    n, nz = 2, 6
    y = np.zeros(2 * nz + 2)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 2 * nz + 2))
    # In the dense form y + x(F0 + (1 − x) F1): φ₁ (component 4) = 0.01 + 0.08 x(1 − x), turning
    # at x = 1/2 where φ₁ = 0.03, its rate (component nz + 4) 0.08 (1 − 2x); φ₀ (component 1)
    # = −0.02 + 0.04 x, never turning, its rate 0.04. θ₁ = φ₀ + φ₁ has the rate 0.12 − 0.16 x,
    # turning at x = 3/4.
    y[4], F[1, 4] = 0.01, 0.08
    y[nz + 4], F[0, nz + 4] = 0.08, -0.16
    y[1], F[0, 1] = -0.02, 0.04
    y[nz + 1] = 0.04
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_PHI] == pytest.approx(0.03, rel=1e-12)
    theta_1 = (-0.02 + 0.04 * 0.75) + (0.01 + 0.08 * 0.75 * 0.25)
    assert summ[1, E.B_PEAK_ABS_THETA] == pytest.approx(theta_1, rel=1e-12)
    assert summ[0, E.B_PEAK_PHI] == 0.0 and summ[0, E.B_PEAK_ABS_THETA] == 0.0
    # up to x = 0.6 the θ turning point is not reached; the φ one is
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 0.6, summ)
    assert summ[1, E.B_PEAK_PHI] == pytest.approx(0.03, rel=1e-12)
    assert summ[1, E.B_PEAK_ABS_THETA] == 0.0
    # θ₁'s rate sums the blocks' own rates, one state component in three, also at the step's
    # start: with block 1 in flight, its gap d₁ closing at 0.1 m/s beside its rate (mutant
    # c391c7d2 summed φ̇₀ + ḋ₁ = −0.06 there, of the end's sign, and saw no turn)
    y[5], y[nz + 5] = 0.02, -0.1
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_ABS_THETA] == pytest.approx(theta_1, rel=1e-12)
    y[5] = y[nz + 5] = 0.0
    # a larger peak already booked stays
    summ[1, E.B_PEAK_PHI] = 0.5
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_PHI] == 0.5
    # a rate that starts at exactly zero (a rocking that starts from rest in this step):
    # φ̇₁ = 0.04 x − 0.08 x² turns at x = 1/2, where φ₁ = 0.03; the zero at the start is not a
    # change of sign, and the sign the rate takes inside is read back from the middle (the angle
    # there is insensitive to the position found, 1e-10 of the step: 1e-14 relative is rounding)
    y[nz + 4], F[0, nz + 4], F[1, nz + 4] = 0.0, -0.04, 0.08
    y[1] = F[0, 1] = y[nz + 1] = 0.0
    for x_end, want in ((1.0, 0.03), (0.45, 0.0)):
        summ = np.zeros((n, E.N_BLOCK_SUMMARY))
        E._peaks_inside(P, y, F, x_end, summ)
        assert summ[1, E.B_PEAK_PHI] == pytest.approx(want, rel=1e-14, abs=0.0), x_end
        assert summ[1, E.B_PEAK_ABS_THETA] == pytest.approx(want, rel=1e-14, abs=0.0), x_end
    # the same with the rate exactly zero in the middle too: φ̇₁ = 0.08 x (x − 1/2), negative in
    # between, so φ₁ = 0.01 − 0.08 x(1 − x) turns at x = 1/2 (−0.01); the zero read there is no
    # sign either, and the search reads on back towards the start (mutant 7d589742 took it for one)
    y[4], F[0, 4], F[1, 4] = 0.01, 0.0, -0.08
    F[0, nz + 4], F[1, nz + 4] = 0.04, -0.08
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_PHI] == pytest.approx(0.01, rel=1e-14, abs=0.0)
    # and with the turn before the middle (φ̇₁ = 0.08 x (1/4 − x)): the middle's rate has the
    # end's sign, so the search reads on back to 1/8, where it has the other (mutant 4d6697c0
    # stopped at the middle, on the end's sign, and saw no turn); φ₁ = 0.01 + 0.08 x(1 − x)
    # turns at 1/4, at 0.025
    y[4], F[0, 4], F[1, 4] = 0.01, 0.0, 0.08
    F[0, nz + 4], F[1, nz + 4] = -0.06, 0.08
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_PHI] == pytest.approx(0.025, rel=1e-14, abs=0.0)
    # and a rate that starts at zero and turns twice: φ̇₁ = 0.08 x² − 0.024 x, negative up to
    # x = 0.3 and positive after, small (0.008) at the middle: the search reads back past the
    # middle, whose sign is the end's, to 0.25, and finds the turn at 0.3, where
    # φ₁ = −0.01 − 0.012 x² + (0.08/3) x³ = −0.01036 (mutant 1726f12c read a rate below 1 rad/s
    # as negative, stopped at the middle and saw no turn)
    F[:] = 0.0
    y[4], F[1, 4], F[2, 4] = -0.01, 0.012 - 0.08 / 3, -0.08 / 3
    F[0, 4] = -F[1, 4]
    y[nz + 4], F[0, nz + 4], F[1, nz + 4] = 0.0, 0.056, -0.08
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_PHI] == pytest.approx(0.01 + 0.012 * 0.09 - 0.08 / 3 * 0.027, rel=1e-12, abs=0.0)
    # a turning point of a negative angle (φ₁ = −0.01 − 0.08 x(1 − x), its rate from −0.08 to
    # +0.08) with the pedestal in flight, its gap d₀ = 0.05 m: the rate, not the state beside it,
    # is read at the start (mutant 00aa07c0 read component nz − 4, the gap, and saw no turn)
    y[:] = 0.0
    F[:] = 0.0
    y[2] = 0.05
    y[4], F[1, 4] = -0.01, -0.08
    y[nz + 4], F[0, nz + 4] = -0.08, 0.16
    summ = np.zeros((n, E.N_BLOCK_SUMMARY))
    E._peaks_inside(P, y, F, 1.0, summ)
    assert summ[1, E.B_PEAK_PHI] == pytest.approx(0.03, rel=1e-14, abs=0.0)


def test_an_event_record_holds_its_fields_and_counts_past_the_capacity():
    events = np.full((2, E.N_EVENT_FIELDS), np.nan)
    n = E._record(events, 0, 1.25, 1, E.G_STICK_POS, ROCK, -1, 0.5)
    assert n == 1 and list(events[0]) == [1.25, 1, E.G_STICK_POS, ROCK, -1, 0.5]
    n = E._record(events, 2, 2.0, 0, 0, FLAT, 0, 0.0)
    assert n == 3 and np.isnan(events[1]).all()


def test_a_contact_pulls_when_its_force_is_below_minus_the_tolerance():
    """``_pulls`` and ``_mark_pulling``: a flat interface pulls if either end's normal force (the
    oracle's) is below −tol, a rocking one if its corner's is, an open one never; the first such
    time is noted and kept."""
    rng = np.random.default_rng(45)
    seen = set()
    for P, ends, anchor, nstate, tstate, z, zd, ah, av, oracle, combo, solution in _solved_states(
            rng, 60, (-1.5, 1.5), (-1.2, 0.5)):
        n = P.shape[0]
        ok, dy, lam = _evaluate(P, ends, anchor, nstate, tstate, z, zd, ah, av)
        tol = 1e-3 * np.sum(P[:, P_MASS]) * G
        summ = np.full((n, E.N_BLOCK_SUMMARY), np.nan)
        summ[0, E.B_HELD] = 0.5
        E._mark_pulling(P, ends, anchor, nstate, z, lam, tol, 2.0, summ)
        for k in range(n):
            normal, _, _ = _oracle_forces(oracle, solution, combo, k)
            lowest = min(normal.values(), default=np.inf)
            if abs(lowest + tol) < 1e-5 * np.sum(P[:, P_MASS]) * G:  # (both solve to ~1e-7 of it)
                continue
            pulls = lowest < -tol
            assert E._pulls(P, ends, anchor, nstate, k, z, lam, tol) == pulls
            if k == 0:
                assert summ[0, E.B_HELD] == 0.5
            else:
                assert (summ[k, E.B_HELD] == 2.0) == pulls and (np.isnan(summ[k, E.B_HELD]) != pulls)
            seen.add((int(nstate[k]), pulls))
    assert {(FLAT, True), (FLAT, False), (ROCK, True), (ROCK, False), (OPEN, False)} <= seen


def test_tracking_books_the_peaks_the_first_times_and_the_friction_needed():
    """``_track``: the peaks of |φ| (per interface) and |θ| (absolute, the oracle's Θ), of the
    slip and its path, the first time each interface is open, rocks or slides, and the friction
    ratio |T|/N a closed interface that does not slip needs (the oracle's forces), unless its
    block is turned past its tipping angle atan(b/h), where N vanishes as it falls."""
    rng = np.random.default_rng(46)
    kinds = set()
    for P, ends, anchor, nstate, tstate, z, zd, ah, av, oracle, combo, solution in _solved_states(
            rng, 40, (-0.8, 0.8), (-0.3, 0.3)):
        n = P.shape[0]
        summ = np.full((n, E.N_BLOCK_SUMMARY), np.nan)
        for slot in (E.B_PEAK_PHI, E.B_PEAK_SLIP, E.B_MU_REQ, E.B_SLIP_PATH, E.B_PEAK_ABS_THETA):
            summ[:, slot] = 0.0
        slip0 = rng.uniform(-0.01, 0.01, n)
        before = slip0.copy()
        lam = np.full(3 * n, np.nan)
        E._track(P, ends, anchor, nstate, tstate, _y(z, zd), 1.5, slip0, summ, lam, _floor(ah, av), G,
                 E.new_workspace(n), False)
        theta = poses(P, ends, anchor, z)[2::3]
        for k in range(n):
            i = 3 * k
            s = E.slip_of(P, ends, anchor, k, z)
            assert summ[k, E.B_PEAK_PHI] == abs(z[i + 1]) and summ[k, E.B_PEAK_ABS_THETA] == pytest.approx(
                abs(theta[k]), abs=1e-15)
            assert summ[k, E.B_PEAK_SLIP] == abs(s) and slip0[k] == s
            assert summ[k, E.B_SLIP_PATH] == abs(s - before[k])
            assert (summ[k, E.B_LIFTOFF] == 1.5) == (nstate[k] == OPEN)
            assert (summ[k, E.B_FIRST_ROCK] == 1.5) == (nstate[k] == ROCK)
            assert (summ[k, E.B_FIRST_SLIDE] == 1.5) == (nstate[k] >= ROCK and tstate[k] != 0)
            _, total, friction = _oracle_forces(oracle, solution, combo, k)
            tipped = abs(z[i + 1]) >= math.atan2(P[k, P_BU], P[k, P_HU])
            sticks = nstate[k] >= ROCK and (tstate[k] == 0 or P[k, P_CAN_SLIP] < 0.5)
            scale = np.sum(P[:, P_MASS]) * G
            if sticks and not tipped and total > 1e-6 * scale:
                assert summ[k, E.B_MU_REQ] == pytest.approx(abs(friction) / total, rel=1e-6, abs=1e-9)
                kinds.add("booked")
            elif not (sticks and not tipped and abs(total) <= 1e-6 * scale):
                assert summ[k, E.B_MU_REQ] == 0.0
                kinds.add("not booked")
        # a second call later: the first times stay, the peaks only grow, the path adds up;
        # with the forces given (forces_known), they are not computed again
        lam2 = lam.copy()
        lam2[0::3] *= 3.0
        summ2 = summ.copy()
        z2 = z * 0.5
        E._track(P, ends, anchor, nstate, tstate, _y(z2, zd), 2.5, slip0, summ2, lam2, _floor(ah, av), G,
                 E.new_workspace(n), True)
        for slot in (E.B_LIFTOFF, E.B_FIRST_ROCK, E.B_FIRST_SLIDE):
            np.testing.assert_array_equal(summ2[:, slot], summ[:, slot])
        np.testing.assert_array_equal(summ2[:, E.B_PEAK_PHI], summ[:, E.B_PEAK_PHI])
        for k in range(n):
            s2 = E.slip_of(P, ends, anchor, k, z2)
            step = abs(s2 - E.slip_of(P, ends, anchor, k, z))
            assert summ2[k, E.B_SLIP_PATH] == pytest.approx(summ[k, E.B_SLIP_PATH] + step, abs=1e-15)
            if summ[k, E.B_MU_REQ] > 0.0 and lam2[3 * k + 2] > 0.0 and abs(z2[3 * k + 1]) < math.atan2(
                    P[k, P_BU], P[k, P_HU]):
                assert summ2[k, E.B_MU_REQ] == pytest.approx(3.0 * summ[k, E.B_MU_REQ], rel=1e-12)
    assert {"booked", "not booked"} <= kinds
    # a block rocking on a stuck corner books its friction ratio until it passes its tipping angle
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.3, height=1.2, mass=50.0),),
                                    interfaces=(Interface(friction=_friction(0.8, 0.6)),)))
    alpha = math.atan2(0.15, 0.6)
    anchor = np.array([1])
    booked, ratios = [], []
    for phi in (alpha - 0.02, alpha + 0.02):
        z1 = np.array([ends[0, 1, 1], phi, 0.0])
        summ = np.zeros((1, E.N_BLOCK_SUMMARY))
        lam = np.zeros(3)
        E._track(P, ends, anchor, np.array([ROCK]), np.array([0]), _y(z1, np.array([0.0, 0.5, 0.0])), 0.1,
                 np.zeros(1), summ, lam, _floor(-3.0, 0.0), G, E.new_workspace(1), False)
        assert lam[2] > 0.0
        booked.append(summ[0, E.B_MU_REQ])
        ratios.append(abs(lam[0]) / lam[2])
    assert booked[0] == ratios[0] and ratios[0] > 0.05 and booked[1] == 0.0 and ratios[1] > 0.05



def test_a_stack_stands_while_each_block_up_to_the_interface_touches_and_is_within_its_angle():
    """``_stands(P, nstate, y, k)``, the rule under which interface k's need counts: blocks 1 …
    k+1 each in contact with what they stand on (not OPEN) and turned less than atan(b/h), read
    from φ_j = y[3j + 1] alone. Every other component of the state (slides, lifts, the rates, the
    ledger) is random and large here, and so are the angles of the blocks above k, which must
    not matter. Exact: comparisons only (the angle is compared at 0.99, 1 and 1.01 of atan(b/h),
    computed here from the blocks' sizes)."""
    sizes = ((1.2, 0.4), (0.4, 1.4), (0.2, 0.45))
    stack = Stack(blocks=tuple(Block(width=w, height=h, mass=10.0) for w, h in sizes),
                  interfaces=(Interface(), Interface(), Interface()))
    P, *_ = pack(stack)
    alpha = [math.atan2(w / 2, h / 2) for w, h in sizes]
    rng = np.random.default_rng(12)
    seen = set()
    for _ in range(300):
        y = rng.uniform(-10.0, 10.0, 6 * 3 + 2)
        nstate = rng.choice([OPEN, ROCK, FLAT], size=3, p=[0.15, 0.6, 0.25])
        for j in range(3):
            y[3 * j + 1] = 0.0 if nstate[j] == FLAT else rng.choice([-1, 1]) * alpha[j] * rng.choice(
                [rng.uniform(0.0, 0.99), 0.99, 1.0, 1.01, rng.uniform(1.01, 5.0)])
        for k in range(3):
            want = all(nstate[j] != OPEN and abs(y[3 * j + 1]) < alpha[j] for j in range(k + 1))
            assert E._stands(P, nstate, y, k) == want, (k, nstate, y[1::3][:3])
            seen.add((k, want))
    assert seen == {(k, w) for k in range(3) for w in (True, False)}



def test_an_interfaces_need_is_its_friction_ratio_where_it_sticks_pushes_and_stands():
    """``_need_of``: |T|/N from the contact forces (T at lam[3k], N at lam[3k + 2]) for an
    interface that sticks (or cannot slip), pushes (N > 0, however small: a 1 mN force on a
    50 g block is a real one) and stands (:func:`_stands`); −1 (not counted) where N ≤ 0, where
    it slips, or where a block up to it does not stand. Exact: one division."""
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=0.05)),
                  interfaces=(Interface(friction=_friction(0.3, 0.3)), Interface()))
    P, *_ = pack(stack)  # interface 0 can slip, interface 1 cannot
    y = np.zeros(6 * 2 + 2)
    stuck, slipping = np.array([0, 0]), np.array([1, -1])
    standing = np.array([FLAT, ROCK])
    for T, N in ((0.2, 1e-3), (-3.0, 10.0), (5.0, 0.0), (1.0, -2.0), (0.0, 4.0)):
        lam = np.array([T, 0.0, N, T, 0.0, N])
        for k in (0, 1):
            want = abs(T) / N if N > 0.0 else -1.0
            assert E._need_of(P, standing, stuck, y, lam, k) == want
            # the floor interface slips: not counted; the upper one cannot slip: counted
            assert E._need_of(P, standing, slipping, y, lam, k) == (-1.0 if k == 0 else want)
            assert E._need_of(P, np.array([OPEN, ROCK]), stuck, y, lam, k) == -1.0


def _block_in_flight():
    """A single block in flight (OPEN): its anchor's guard is its gap d, the state's component 2."""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.4, height=0.8, mass=30.0),), interfaces=(Interface(),)))
    nstate, tstate = np.array([OPEN]), np.array([0])
    ws = E.new_workspace(1)
    y = np.zeros(8)
    E._moving(P, nstate, tstate, y, ws)
    return P, ends, anchor, nstate, tstate, ws


def test_an_event_is_located_where_its_guard_reaches_zero_on_the_dense_output():
    """``_locate``: the gap d(x) = 0.01 − 0.04 x + 0.02 x² of a block in flight (written in the
    dense form y + x(F0 + (1 − x) F1)) reaches zero at x* = 1 − 1/√2. The fraction returned is
    the end of the last bracket: at or just past x*, within the 1e-13 s the search stops at."""
    P, ends, anchor, nstate, tstate, ws = _block_in_flight()
    y = np.zeros(8)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    y[2], F[0, 2], F[1, 2] = 0.01, -0.02, -0.02
    root = 1.0 - 1.0 / math.sqrt(2.0)
    held = np.zeros(1, dtype=np.bool_)
    ym, gm = np.zeros(8), np.zeros(E.N_GUARD_SLOTS)
    for hs in (1e-3, 0.05):
        for lo, hi in ((0.0, 1.0), (0.2, 0.5)):
            glo = 0.01 - 0.04 * lo + 0.02 * lo * lo
            ghi = 0.01 - 0.04 * hi + 0.02 * hi * hi
            x = E._locate(P, ends, anchor, nstate, tstate, 2.0, y, hs, F, _floor(0.0, -12.0), G, E.G_ANCHOR, lo, hi,
                          glo, ghi, ym, gm, held, ws)
            assert 0.0 <= (x - root) * hs <= 2e-13, (hs, lo, hi, x - root)


def test_a_grazing_guard_is_searched_for_its_minimum():
    """``_minimum`` (golden section): the gap 0.011 − 0.04 x + 0.04 x² has its minimum 0.001 at
    x = 1/2; with 0.009 in place of 0.011 it dips below zero, and the search stops at a point
    where it is ≤ 0."""
    P, ends, anchor, nstate, tstate, ws = _block_in_flight()
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    F[1, 2] = -0.04
    held = np.zeros(1, dtype=np.bool_)
    ym, gm = np.zeros(8), np.zeros(E.N_GUARD_SLOTS)
    hs = 1e-3
    for y2, lo, hi in ((0.011, 0.0, 1.0), (0.011, 0.3, 0.9), (0.009, 0.0, 1.0)):
        y = np.zeros(8)
        y[2] = y2
        x, g = E._minimum(P, ends, anchor, nstate, tstate, 1.0, y, hs, F, _floor(0.0, -12.0), G, E.G_ANCHOR, lo, hi,
                          ym, gm, held, ws)
        assert lo <= x <= hi
        assert g == pytest.approx(y2 - 0.04 * x + 0.04 * x * x, abs=1e-17)
        if y2 > 0.01:
            assert abs(x - 0.5) < 1e-8 and g == pytest.approx(0.001, abs=1e-16)
        else:
            assert g <= 0.0
    # 0.04 (x − 0.7)² − 0.0005 dips below zero near 0.7 only: the search's first two points are
    # 0.382 (above zero) and 0.618 (below), and it stops at the second
    y = np.zeros(8)
    y[2], F[0, 2], F[1, 2] = 0.0191, -0.016, -0.04
    x, g = E._minimum(P, ends, anchor, nstate, tstate, 1.0, y, hs, F, _floor(0.0, -12.0), G, E.G_ANCHOR, 0.0, 1.0,
                      ym, gm, held, ws)
    assert x == pytest.approx(0.6180339887498949, abs=1e-15) and g == pytest.approx(
        0.04 * (x - 0.7) ** 2 - 0.0005, abs=1e-17) and g <= 0.0


def test_a_graze_is_located_where_its_dip_first_reaches_zero():
    """``_graze``: the gap 0.009 − 0.04 x + 0.04 x² of a block in flight dips below zero and first
    reaches it at x* = (0.04 − √(0.04² − 4·0.04·0.009)) / 0.08 ≈ 0.342; with 0.011 its minimum
    0.001 stays above zero and the answer is 2 (no event). x is returned at or just past x*,
    within the 1e-13 s the search stops at."""
    P, ends, anchor, nstate, tstate, ws = _block_in_flight()
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    F[1, 2] = -0.04
    held = np.zeros(1, dtype=np.bool_)
    ym, gm = np.zeros(8), np.zeros(E.N_GUARD_SLOTS)
    root = (0.04 - math.sqrt(0.04 ** 2 - 4 * 0.04 * 0.009)) / 0.08
    for hs in (1e-3, 0.05):
        for y2, want in ((0.011, None), (0.009, root)):
            y = np.zeros(8)
            y[2] = y2
            x = E._graze(P, ends, anchor, nstate, tstate, 1.0, y, hs, F, _floor(0.0, -12.0), G, E.G_ANCHOR, 0.0, 1.0,
                         y2, ym, gm, held, ws)
            if want is None:
                assert x == 2.0
            else:
                assert 0.0 <= (x - want) * hs <= 2e-13, (hs, x - want)


def test_a_gaps_rate_is_the_rate_of_its_corners_distance_from_the_face():
    """``_gap_rate`` (the dip rule's test, docs/theory/stack.md §7): the anchor's gap d has rate ḋ;
    the other end's gap has the rate of the oracle's corner distance, differentiated by complex
    step, at random poses and velocities of every coordinate (exact to rounding: 1e-12 m/s on
    rates of order 1 m/s)."""
    rng = np.random.default_rng(20261207)
    for P, ends, anchor, geo, z, _, _ in random_states(rng, 40, ACCELERATION):
        n = P.shape[0]
        zd = rng.uniform(-1.0, 1.0, 3 * n)
        y = _y(z, zd)
        for k in range(n):
            for slot in (E.G_ANCHOR, E.G_OTHER):
                e = anchor[k] if slot == E.G_ANCHOR else 1 - anchor[k]
                want = jacobian(lambda zz, k=k, e=e: np.array([contact(P, ends, anchor, k, zz, e)[0]]), z)[0] @ zd
                got = E._gap_rate(P, ends, anchor, geo, y, k * E.N_GUARD_SLOTS + slot)
                assert got == pytest.approx(want, abs=1e-12), (k, slot)


def _standing_block(mu_s, mass=30.0):
    """A 0.4 × 0.8 m block (30 kg) standing flat and stuck on the floor with friction μs (μk =
    0.8 μs), at rest: (P, ends, anchor, nstate, tstate, y, ws), the step's moving components
    listed in ws (``_moving``)."""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.4, height=0.8, mass=mass),),
                                    interfaces=(Interface(friction=_friction(mu_s, 0.8 * mu_s)),)))
    nstate, tstate = np.array([FLAT]), np.array([0])
    ws = E.new_workspace(1)
    y = _y(z, np.zeros(3))
    E._moving(P, nstate, tstate, y, ws)
    return P, ends, anchor, nstate, tstate, y, ws


def _sampled_needs(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, x_stop, ws):
    """The need of every interface at the step's samples i/N_SUB up to x_stop, as the step loop
    hands them to ``_need_inside`` (−1 past x_stop): (q, the number of samples n_q)."""
    n_q = int(x_stop * E.N_SUB) + 1
    q = np.full((P.shape[0], E.N_SUB + 1), -1.0)
    for k in range(P.shape[0]):
        for i in range(n_q):
            q[k, i] = E._need_at(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, i / E.N_SUB, k,
                                 np.zeros(y.shape[0]), ws)
    return q, n_q


def _booked_need(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, q, n_q, x_stop, best, ws):
    """The need ``_need_inside`` books for the first interface over a step (its samples q, n_q,
    up to x_stop), with ``best`` booked before."""
    summ = np.zeros((P.shape[0], E.N_BLOCK_SUMMARY))
    summ[0, E.B_MU_REQ] = best
    E._need_inside(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, q, n_q, x_stop, summ, np.zeros(y.shape[0]),
                   np.zeros(E.N_GUARD_SLOTS * P.shape[0]), np.zeros(P.shape[0], dtype=np.bool_), ws)
    return summ[0, E.B_MU_REQ]


def _need_in_a_step(crest, x_stop=None, best=0.0):
    """``_need_inside`` on a step of 0.4 s from t = 2 s of a block standing stuck on a floor whose
    acceleration 3 cos(2 (t − t_c)) m/s² crests at ``crest`` (a fraction of the step): the need
    is |a_h|/g, sampled at the step's quarters (up to x_stop), the largest need booked before the
    step ``best``. Returns the need booked and its samples."""
    P, ends, anchor, nstate, tstate, y, ws = _standing_block(0.9)
    t, hs = 2.0, 0.4
    loc = _harmonic_floor(3.0, 2.0, -2.0 * (t + crest * hs), 0.0, 0.0, 0.0)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    x_stop = 1.0 if x_stop is None else x_stop
    q, n_q = _sampled_needs(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, x_stop, ws)
    return _booked_need(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, q, n_q, x_stop, best, ws), q[0, :n_q]


def test_the_friction_needed_inside_a_step_is_its_peak_whether_inside_or_at_an_end():
    """The need 3 cos(2 (t − t_c))/g of a block standing under a floor cresting at t_c: where
    the crest lies between the last two samples (x = 0.95, the largest sample the step's end),
    the first two (x = 0.05) or two inside (0.3, 0.55, 0.7), the peak is 3/g, which no sample reads (3/g·cos 0.04
    at the nearest); where it lies past the step (x = 1.3, or before it, x = −0.3) the need
    rises to an end and is the sample there, to the bit (``_need_peak`` then skips the
    search). The same with the step stopped by an event at x = 0.7, the crest just before it
    (0.65) or after (0.9). Tolerance: 1e-14 relative, the rounding of a golden search that
    stops 1e-12 of the step from the crest (the need's change there is (f''/2)·x², 1e-24)."""
    peak = 3.0 / G
    for crest, best in ((0.95, 4), (0.05, 0), (0.3, 1), (0.55, 2), (0.7, 3)):
        booked, q = _need_in_a_step(crest)
        assert q.max() < peak * (1.0 - 1e-4) and int(np.argmax(q)) == best
        assert booked == pytest.approx(peak, rel=1e-14), crest
    for crest, end in ((1.3, 4), (-0.3, 0)):
        booked, q = _need_in_a_step(crest)
        assert booked == q[end] and int(np.argmax(q)) == end, crest
    booked, q = _need_in_a_step(0.65, x_stop=0.7)
    assert len(q) == 3 and booked == pytest.approx(peak, rel=1e-14)
    booked, q = _need_in_a_step(0.9, x_stop=0.7)
    want = 3.0 * math.cos(2.0 * 0.2 * 0.4) / G  # at the event, 0.2 of the step before the crest
    assert booked == pytest.approx(want, rel=1e-14) and booked > q.max()
    # The crest just past the last sample before an event at x = 0.7 (0.52): the last sample
    # reads 0.99987 of the peak, the one before it and the event 0.977 and 0.990, with 0.998 of
    # it booked before. The last sample alone calls for the search up to the event (mutant
    # d17b0e94 asked the sample before it, skipped the search, and booked 0.99987).
    booked, q = _need_in_a_step(0.52, x_stop=0.7, best=0.998 * peak)
    assert len(q) == 3 and q[-2] < 0.997 * peak < q[-1]
    assert booked == pytest.approx(peak, rel=1e-14)
    # A crest midway between two samples (x = 0.375) reads 3/g·cos 0.1 there, 0.5 % low: with a
    # need of 0.998 · 3/g booked before, the samples alone are more than 1e-3 below it, and the
    # parabola through the best sample and its neighbours, which peaks near 3/g, sends the
    # search; with 1.001 · 3/g booked, nothing is searched. (Mutant afb6d919, (q₀ − q₂)·2 for
    # (q₀ − q₂)², put that parabola's peak below the best sample.)
    booked, q = _need_in_a_step(0.375, best=0.998 * peak)
    assert q.max() < 0.999 * 0.998 * peak and booked == pytest.approx(peak, rel=1e-14)
    booked, q = _need_in_a_step(0.375, best=1.001 * peak)
    assert booked == 1.001 * peak
    # The same with the best sample the last but one (a crest at 0.64, nearest the sample at 0.75):
    # its parabola is formed as any other inside one's (mutant 371549ff, b < n_q − 2, formed none
    # there, estimated the sample itself and skipped the search)
    booked, q = _need_in_a_step(0.64, best=0.998 * peak)
    assert int(np.argmax(q)) == 3 and q.max() < 0.999 * 0.998 * peak and booked == pytest.approx(peak, rel=1e-14)
    # The same where the best so far lies just below the top of that parabola (numpy's fit
    # through the three samples): 95 % of the way up from the best sample. The estimate must
    # reach it (mutant bd40b234, 9 for 8 in the vertex's formula, stopped at 8/9 of the way).
    _, q = _need_in_a_step(0.375)
    b = int(np.argmax(q))
    c2, c1, c0 = np.polyfit([-1.0, 0.0, 1.0], q[b - 1:b + 2], 2)
    top = c0 - c1 * c1 / (4.0 * c2)
    best = q[b] + 0.95 * (top - q[b])
    assert q[b] < 0.999 * best < best < top < peak
    booked, _ = _need_in_a_step(0.375, best=best)
    assert booked == pytest.approx(peak, rel=1e-14)
    # A crest at 0.43, off the middle between two samples: the best sample (0.5) reads 0.99843
    # of the peak, the parabola through it and both neighbours 0.999986, and 0.9997 of it is
    # booked. The parabola's curvature takes both neighbours (mutant 4bacc3d5, the one after the
    # best twice, estimated 0.99943 and skipped the search).
    booked, q = _need_in_a_step(0.43, best=0.9997 * peak)
    assert int(np.argmax(q)) == 2 and q.max() < 0.999 * 0.9997 * peak
    assert booked == pytest.approx(peak, rel=1e-14)


def test_the_need_is_searched_between_the_best_samples_neighbours_only():
    """A block standing stuck under a floor whose push 3 cos(ω (t − t_c)) crests twice in a step
    of 0.4 s (|a_h| every 0.16 s: at 0.28 and 0.68 of the step), with its vertical acceleration
    −4 + 10 (t − 2) m/s² rising, so that the first crest needs more: the need |a_h|/(g + a_v)
    peaks at 0.4343 (the formula, maximised here by scipy), the second crest at 0.3525. The
    best sample (0.25) reads 0.4286; the search between its neighbours (0 to 0.5, one crest)
    finds the peak to 1e-9. (Mutant 259762c2, b/dx for b·dx, searched up to the step's end:
    the golden section, which assumes one peak, went to the second crest, and the sample stayed.)"""
    from scipy.optimize import minimize_scalar

    P, ends, anchor, nstate, tstate, y, ws = _standing_block(0.9)
    t, hs, x_c = 2.0, 0.4, 0.28
    omega = math.pi / (0.4 * hs)
    loc = np.array([LOCAL_COSINE, 3.0, omega, -omega * (t + x_c * hs), 0.0, LOCAL_LINEAR, -4.0, 10.0, t, 0.0])
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    q, n_q = _sampled_needs(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, 1.0, ws)

    def need(x):
        tt = t + x * hs
        return abs(3.0 * math.cos(omega * (tt - t - x_c * hs))) / (G - 4.0 + 10.0 * (tt - t))

    np.testing.assert_allclose(q[0], [need(i / 4) for i in range(5)], rtol=1e-14)
    peak = -minimize_scalar(lambda x: -need(x), bounds=(0.0, 0.5), method="bounded", options={"xatol": 1e-12}).fun
    second = -minimize_scalar(lambda x: -need(x), bounds=(0.5, 1.0), method="bounded", options={"xatol": 1e-12}).fun
    assert int(np.argmax(q[0])) == 1 and q[0, 1] < peak * (1.0 - 1e-2) and second < q[0, 1]
    booked = _booked_need(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, q, n_q, 1.0, 0.0, ws)
    assert booked == pytest.approx(peak, rel=1e-9)


def _need_across_a_tip(phi0, phi_dot0, a_h, a_v0, a_v_rate, best, x_stop=1.0):
    """``_need_inside`` on one accepted DOP853 step of 0.02 s of a 0.4 × 0.8 m block rocking,
    stuck, on its left corner from φ0 (rad) at φ̇0 (rad/s), under a floor at a_h (m/s²) with its
    vertical acceleration a_v0 + a_v_rate·t (m/s², m/s³): the block passes its tipping angle
    α = atan(0.2/0.4) inside the step. Returns (the need booked, with ``best`` booked before;
    the samples; the fraction of the step where |φ| = α, by brentq on the dense output; the need
    there, on the side where the block stands). ``x_stop``: the step cut there by an event."""
    from scipy.optimize import brentq

    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.4, height=0.8, mass=30.0),), interfaces=(Interface(),)))
    assert anchor[0] == 0 and ends[0, 0, 1] == -0.2  # the left corner: the block tips towards −x, φ < 0
    z = z.copy()
    z[1] = phi0
    y = _y(z, np.array([0.0, phi_dot0, 0.0]))
    nstate, tstate, t, hs = np.array([ROCK]), np.array([0]), 0.0, 0.02
    ws = E.new_workspace(1)
    E._moving(P, nstate, tstate, y, ws)
    loc = np.array([LOCAL_LINEAR, a_h, 0.0, 0.0, 0.0, LOCAL_LINEAR, a_v0, a_v_rate, t, 0.0])
    K = np.zeros((dop853.N_K, 8))
    E._rhs(P, ends, anchor, nstate, tstate, t, y, loc, G, K[0], ws)
    y_new = np.zeros(8)
    assert E._step(P, ends, anchor, nstate, tstate, t, y, hs, loc, G, K, y_new, 1e-10, 1e-10, 8, ws) < 1.0
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    E._dense_prepare(P, ends, anchor, nstate, tstate, t, y, y_new, hs, loc, G, K, F, ws)
    q, n_q = _sampled_needs(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, x_stop, ws)
    alpha = math.atan2(0.2, 0.4)

    def past_tip(x):
        out = np.zeros(8)
        dop853.dense_on(y, F, x, out, ws[E.WS_ACT], ws[E.WS_N_ACT][0])
        return abs(out[1]) - alpha

    x_tip = brentq(past_tip, 0.0, 1.0, xtol=1e-15)
    side = -1e-12 if past_tip(0.0) < 0.0 else 1e-12
    at_tip = E._need_at(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, x_tip + side, 0, np.zeros(8), ws)
    booked = _booked_need(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, q, n_q, x_stop, best, ws)
    return booked, q[0], x_tip, at_tip


@pytest.mark.parametrize("leaving", [True, False])
def test_the_friction_needed_up_to_a_tipping_angle_inside_a_step_is_searched_for(leaving):
    """A block stuck to the floor passes its tipping angle inside a step (tipping out, or
    rocking back in), as its floor's vertical acceleration falls towards −g (or rises from it):
    its normal force fails towards the tip and the need |T|/N rises steeply to it, 1.95 (2.05)
    where the sample a quarter of a step away reads 1.38 (1.24). The need counts while the block
    stands (|φ| < α), so the need booked is the one at the tip, to 1e-9 (the golden search stops
    1e-12 of the step from it, where the need changes by ~1e-11), above the 1.7 booked before.
    Until 2026-12-07 a sample beside the tip (no need there, −1) made no parabola, the best
    sample was below 0.999 of 1.7, and the stretch was not searched: 1.7 stayed. (Mutants that
    formed the parabola through the −1, f2bd9a26 and a5335280, estimated 1.57 and 1.41, below
    1.7, and skipped the search too.) The same where an event cuts the step past the tip and the
    tip lies beyond the last sample: the stretch to the event was searched only where its ends
    came within 1e-3 of the need booked."""
    alpha = math.atan2(0.2, 0.4)
    case = ((-(alpha - 0.01), -1.0, 10.0, -7.0, -100.0) if leaving else (-(alpha + 0.005), 1.0, 10.0, -9.0, 150.0))
    booked, q, x_tip, at_tip = _need_across_a_tip(*case, best=1.7)
    no_need = [2, 3, 4] if leaving else [0, 1]
    assert np.all(q[no_need] == -1.0) and np.all(np.delete(q, no_need) >= 0.0) and 0.25 < x_tip < 0.5
    assert np.all(q < 0.999 * 1.7) and at_tip > 1.9
    assert booked == pytest.approx(at_tip, rel=1e-9)
    # With nothing booked before, the best sample alone sends the search, as it always did.
    assert _need_across_a_tip(*case, best=0.0)[0] == pytest.approx(booked, rel=1e-12)
    # The same with the step cut by an event past the tip (at 0.49, or 0.45 rocking back in), the
    # tip beyond the last sample (0.25): the stretch from that sample to the event is searched.
    x_stop = 0.49 if leaving else 0.45
    booked, q, x_tip, at_tip = _need_across_a_tip(*case, best=1.7, x_stop=x_stop)
    n_q = int(x_stop * E.N_SUB) + 1
    assert (n_q - 1) / E.N_SUB < x_tip < x_stop and np.all(q[:n_q] < 0.999 * 1.7)
    assert booked == pytest.approx(at_tip, rel=1e-9)
    # The tip moved across the step (the block started nearer to or farther from it): wherever
    # the golden section's last two points fall, the one it books is the standing one (mutant
    # 302f0957, which returned the worse of the two, booked the −1 beyond the tip: 1.7 stayed in
    # five of these, and the sample's 2.1158 for 2.1293 in the first rocking back).
    for offset in ((0.0095, 0.0101) if leaving else (0.00475, 0.00555, 0.00575, 0.00595)):
        moved = (-(alpha - offset),) + case[1:] if leaving else (-(alpha + offset),) + case[1:]
        booked, q, x_tip, at_tip = _need_across_a_tip(*moved, best=1.7)
        assert at_tip > max(1.75, q.max())
        assert booked == pytest.approx(at_tip, rel=1e-9), offset
    if leaving:
        # The tip between the last two samples (the block 0.02 rad inside it): the best sample is
        # the last but one, its right neighbour the last, −1. The parabola through that −1
        # estimates 4.17, far below the need at the tip, 7.94: with 5.0 booked the stretch must
        # still be searched (mutant e1dc36a8, which skipped the right neighbour's check at the
        # last but one sample, left 5.0).
        booked, q, x_tip, at_tip = _need_across_a_tip(-(alpha - 0.02), *case[1:], best=5.0)
        assert int(np.argmax(q)) == E.N_SUB - 1 and q[-1] == -1.0 and 0.75 < x_tip < 1.0
        d2 = q[-3] - 2.0 * q[-2] + q[-1]
        assert q[-2] - (q[-3] - q[-1]) ** 2 / (8.0 * d2) < 0.999 * 5.0 and q[-2] < 0.999 * 5.0
        assert at_tip > 7.0 and booked == pytest.approx(at_tip, rel=1e-9)


def _statue_on_pedestal_at_rest(statue_width, statue_height, floor_friction, top_friction):
    """A statue (mass 100 kg) standing stuck on a 0.8 × 0.5 m pedestal of 300 kg, at rest:
    (P, ends, anchor, nstate, tstate, y, ws), the step's moving components listed in ws."""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0),
                                            Block(width=statue_width, height=statue_height, mass=100.0)),
                                    interfaces=(Interface(friction=floor_friction),
                                                Interface(friction=top_friction))))
    nstate, tstate = np.array([FLAT, FLAT]), np.array([0, 0])
    ws = E.new_workspace(2)
    y = _y(z, np.zeros(6))
    E._moving(P, nstate, tstate, y, ws)
    return P, ends, anchor, nstate, tstate, y, ws


def test_each_interface_books_its_own_need_whatever_the_one_below_did():
    """``_need_inside`` on a statue standing on a pedestal at rest, both faces stuck, under a floor
    2 cos(2 (t − t_c)) m/s² cresting inside a 0.4 s step: both faces then need |a_h|/g, peaking
    at 2/g. The floor face is passed over in three ways (its best so far already above every
    sample; its samples all −1, as for a face that does not stand; its best above the need at
    an event that stops the step) and the top face must still book its own peak, to 1e-14 as
    in the test above. (Mutants that left the loop over the faces, `break` for `continue`,
    survived the tests of a single face: 7aef256d and bdd6af2d on an earlier form of this
    loop.)"""
    P, ends, anchor, nstate, tstate, y, ws = _statue_on_pedestal_at_rest(0.3, 1.2, _friction(0.9, 0.7),
                                                                         _friction(0.9, 0.7))
    t, hs, peak = 2.0, 0.4, 2.0 / G
    F = np.zeros((dop853.INTERPOLATOR_POWER, 14))
    ym, gm, held = np.zeros(14), np.zeros(2 * E.N_GUARD_SLOTS), np.zeros(2, dtype=np.bool_)
    for crest, x_stop in ((0.3, 1.0), (0.65, 0.7)):
        loc = _harmonic_floor(2.0, 2.0, -2.0 * (t + crest * hs), 0.0, 0.0, 0.0)
        q, n_q = _sampled_needs(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, x_stop, ws)
        assert q[0, :n_q] == pytest.approx(q[1, :n_q], rel=1e-14) and q[1, :n_q].max() < peak * (1.0 - 1e-4)
        summ = np.zeros((2, E.N_BLOCK_SUMMARY))
        summ[0, E.B_MU_REQ] = 1.0
        E._need_inside(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, q, n_q, x_stop, summ, ym, gm, held, ws)
        assert summ[0, E.B_MU_REQ] == 1.0
        assert summ[1, E.B_MU_REQ] == pytest.approx(peak, rel=1e-14), crest
        summ = np.zeros((2, E.N_BLOCK_SUMMARY))
        q[0] = -1.0
        E._need_inside(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, q, n_q, x_stop, summ, ym, gm, held, ws)
        # (the stretch up to an event reads the need there afresh, whatever the samples said)
        assert summ[0, E.B_MU_REQ] == (0.0 if x_stop == 1.0 else pytest.approx(peak, rel=1e-14))
        assert summ[1, E.B_MU_REQ] == pytest.approx(peak, rel=1e-14), crest


def test_a_dip_is_near_where_the_parabola_through_three_samples_bottoms_out_low():
    """``_dips_near``: the parabola through (−1, ga), (0, gb), (1, gc) has d2 = ga − 2gb + gc, its
    vertex at xv = (ga − gc)/(2 d2) and its bottom gb − (ga − gc)²/(8 d2). A dip is near when the
    parabola opens upwards, lo < xv < hi strictly, and the bottom is below GRAZING × the largest
    sample. Exact cases on each bound (values exact in binary, or rounded alike on both sides),
    then 2000 random triples against numpy's fit of the same parabola (those within 1e-9 of a
    bound skipped: the two computations round differently there)."""
    assert E.GRAZING == 0.2
    # d2 = 1.25, xv = 0.5/2.5 = 0.2, bottom 0.125 − 0.25/10 = 0.1 < 0.2
    assert E._dips_near(1.0, 0.125, 0.5, -1.0, 1.0)
    assert E._dips_near(1.0, 0.125, 0.5, 0.1999, 0.2001)
    assert not E._dips_near(1.0, 0.125, 0.5, 0.2, 1.0)  # the vertex on lo
    assert not E._dips_near(1.0, 0.125, 0.5, -1.0, 0.2)  # on hi
    assert not E._dips_near(1.0, 0.125, 0.5, 0.25, 1.0)  # outside
    assert not E._dips_near(1.0, 0.25, 0.5, -1.0, 1.0)  # bottom 0.21875 above 0.2
    assert not E._dips_near(1.0, 0.2, 1.0, -1.0, 1.0)  # bottom exactly 0.2 × the largest
    assert E._dips_near(1.0, 0.1875, 1.0, -1.0, 1.0)  # bottom 0.1875, the vertex at 0
    assert not E._dips_near(1.0, 0.5, 0.0, -1.0, 1.0)  # a straight line (d2 = 0)
    assert not E._dips_near(0.5, 1.0, 0.5, -1.0, 1.0)  # a crest (d2 < 0)
    rng = np.random.default_rng(20261208)
    seen = set()
    for _ in range(2000):
        ga, gb, gc = rng.uniform(0.0, 1.0, 3)
        lo, hi = np.sort(rng.uniform(-1.5, 1.5, 2))
        c2, c1, c0 = np.polyfit([-1.0, 0.0, 1.0], [ga, gb, gc], 2)
        if c2 <= 1e-9:
            want = False
        else:
            xv, bottom = -c1 / (2.0 * c2), c0 - c1 * c1 / (4.0 * c2)
            margin = min(abs(xv - lo), abs(xv - hi), abs(bottom - 0.2 * max(ga, gb, gc)))
            if margin < 1e-9:
                continue
            want = lo < xv < hi and bottom < 0.2 * max(ga, gb, gc)
        assert E._dips_near(ga, gb, gc, lo, hi) == want, (ga, gb, gc, lo, hi)
        seen.add(want)
    assert seen == {True, False}


@pytest.mark.parametrize("mass", [30.0, 0.05], ids=["30 kg", "50 g"])
def test_a_step_at_rest_fails_at_the_first_crest_of_the_floor_beyond_its_friction(mass):
    """``_first_crest_failure``: a block standing stuck (μs = 0.3) under a floor whose
    acceleration A cos(ω(t − t₀)) crests every π/ω = 0.1 s, at 0.035, 0.135 and 0.235 s into a
    step of 0.25 s, 0.01 s or more from its five samples, which all hold. At rest the stick guard is
    m(μs(g + a_v) − |a_h|): it first fails where A cos ω(τ − t₀) = μs g before the first crest,
    τ = t₀ − acos(μs g/A)/ω. With a vertical part B cos ω(t − t₀), B = g/20 and A = μs g, the
    first crest (+A, g + B under the block) needs μs/1.05 and holds; the second (−A, g − B)
    needs μs/0.95 and fails where −A cos θ = μs (g + B cos θ), θ = ω(τ − t₀):
    τ = t₀ + acos(−μs g/(A + μs B))/ω, on the other stick guard. A step that ends before the
    first crest has no failure, nor one whose crests need less than μs. The fraction is returned
    at or just past the root, within the 1e-13 s the location stops at. For a block of 30 kg
    and one of 50 g, whose stick guards (forces, N) are below 1 N (mutant 42a722cc searched
    only guards above 1)."""
    mu, hs, t = 0.3, 0.25, 2.0
    omega = 10.0 * math.pi
    t0 = t + 0.035
    P, ends, anchor, nstate, tstate, y, ws = _standing_block(mu, mass)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    held = np.zeros(1, dtype=np.bool_)

    def crest_failure(a_h, a_v, x_end):
        loc = _harmonic_floor(a_h, omega, -omega * t0, a_v, omega if a_v else 0.0, -omega * t0 if a_v else 0.0)
        gq, gc, gm = (np.zeros(E.N_GUARD_SLOTS) for _ in range(3))
        E.guards(P, ends, anchor, nstate, tstate, t, y, loc, G, gq, held, ws)
        for x in np.linspace(0.0, 1.0, E.N_SUB + 1):  # the step's samples hold
            E.guards(P, ends, anchor, nstate, tstate, t + x * hs, y, loc, G, gm, held, ws)
            assert gm.min() > 0.0
        return E._first_crest_failure(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, x_end, gq, gc,
                                      np.zeros(8), gm, held, ws)

    a_h = 1.02 * mu * G
    j1, x1 = crest_failure(a_h, 0.0, 1.0)
    want = (t0 - math.acos(mu * G / a_h) / omega - t) / hs
    assert j1 in (E.G_STICK_POS, E.G_STICK_NEG) and 0.0 <= (x1 - want) * hs <= 2e-13, (j1, (x1 - want) * hs)
    assert crest_failure(a_h, 0.0, 0.1) == (-1, 2.0)  # the step ends before the first crest (0.14)
    assert crest_failure(0.98 * mu * G, 0.0, 1.0) == (-1, 2.0)
    a_h, a_v = mu * G, 0.05 * G
    j2, x2 = crest_failure(a_h, a_v, 1.0)
    want = (t0 + math.acos(-mu * G / (a_h + mu * a_v)) / omega - t) / hs
    assert {j1, j2} == {E.G_STICK_POS, E.G_STICK_NEG} and 0.0 <= (x2 - want) * hs <= 2e-13, (j2, (x2 - want) * hs)
    assert crest_failure(a_h, a_v, 0.5) == (-1, 2.0)  # only the first crest (0.14) is inside


def test_a_frictionless_face_at_rest_under_a_vertical_motion_does_not_fail_at_its_crests():
    """``_first_crest_failure``: a block standing on a face of μs = 0 under a floor that moves
    only vertically (g/5 at 5 Hz): no horizontal force acts, so its stick bounds, μs·N ∓ F, are
    zero at the step's start and at every crest, a tie that holds and not a failure. (Mutant
    668d567b searched a root from a guard at zero and reported a failure at the step's start.)"""
    P, ends, anchor, nstate, tstate, y, ws = _standing_block(0.0)
    t, hs, omega = 2.0, 0.25, 10.0 * math.pi
    loc = _harmonic_floor(0.0, 0.0, 0.0, 0.2 * G, omega, -omega * (t + 0.035))
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    held = np.zeros(1, dtype=np.bool_)
    gq, gc, gm = (np.zeros(E.N_GUARD_SLOTS) for _ in range(3))
    E.guards(P, ends, anchor, nstate, tstate, t, y, loc, G, gq, held, ws)
    assert gq[E.G_STICK_POS] == gq[E.G_STICK_NEG] == 0.0 and gq.min() == 0.0
    assert E._first_crest_failure(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, 1.0, gq, gc, np.zeros(8), gm,
                                  held, ws) == (-1, 2.0)


def test_of_two_faces_failing_at_the_same_fraction_the_first_in_order_is_reported():
    """``_first_crest_failure`` with two faces at rest that reach their friction at the same
    instant: a 100 kg block on a 300 kg pedestal, both faces μs = 0.3, under the crest of
    1.02 μs g cos ω(t − t₀). Both stick guards are m_above (μs g − |a_h|), proportional, and
    located at the same fraction to the bit; the first in order, the floor's, is reported (the
    rule of every location in the step: a later guard replaces the first only if strictly
    earlier). Mutant 36e431fc (`<=`) reported the top face's. Where the two locations differ by
    rounding, the earlier is reported, whichever face it is (a 7 kg block on a 40 kg pedestal:
    the top face's, 2.6e-16 of the step earlier). Which face then gives way no longer follows
    that choice (``_face_that_gives_way``, docs/theory/stack.md §5)."""
    P, ends, anchor, nstate, tstate, y, ws = _statue_on_pedestal_at_rest(0.6, 0.8, _friction(0.3, 0.2),
                                                                         _friction(0.3, 0.2))
    t, hs, omega = 2.0, 0.25, 10.0 * math.pi
    t0 = t + 0.035
    loc = _harmonic_floor(1.02 * 0.3 * G, omega, -omega * t0, 0.0, 0.0, 0.0)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 14))
    held = np.zeros(2, dtype=np.bool_)
    gq, gc, gm = (np.zeros(2 * E.N_GUARD_SLOTS) for _ in range(3))
    E.guards(P, ends, anchor, nstate, tstate, t, y, loc, G, gq, held, ws)
    E.guards(P, ends, anchor, nstate, tstate, t0, y, loc, G, gc, held, ws)
    failing = [j for j in range(2 * E.N_GUARD_SLOTS) if gq[j] > 0.0 and gc[j] <= 0.0]
    assert len(failing) == 2 and [j // E.N_GUARD_SLOTS for j in failing] == [0, 1]
    roots = [E._locate(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, j, 0.0, (t0 - t) / hs, gq[j], gc[j],
                       np.zeros(14), gm, held, ws) for j in failing]
    # equal to the bit on the development machine (x86-64, AVX-512); another libm or fused
    # multiply-adds may round them apart, and then the earlier is the one
    want = failing[0] if roots[0] <= roots[1] else failing[1]
    j, x = E._first_crest_failure(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, 1.0, gq, gc, np.zeros(14), gm,
                                  held, ws)
    assert (j, x) == (want, min(roots))


def test_the_stick_a_stick_event_forbids_is_the_highest_face_at_its_limit():
    """``_face_that_gives_way``: under a floor accelerating at exactly μs·g, a statue and its
    pedestal at rest, both faces μs = 0.3, have both stick guards at zero (to rounding, far
    within the force tolerance 1e-10 of the weight): whichever face's event it is, the top face's
    stick is the one forbidden. With the top face at μs = 0.35 its guard is 0.05 g × its mass
    above zero and the event's own face is returned; so it is for a top face that already slips
    or cannot slip."""
    def stack(mu_top, top_friction=True):
        P, ends, anchor, _, _, y, _ = _statue_on_pedestal_at_rest(
            0.6, 0.8, _friction(0.3, 0.2), _friction(mu_top, 0.2) if top_friction else None)
        return P, ends, anchor, y

    loc = _floor(0.3 * G, 0.0)
    held = np.zeros(2, dtype=np.bool_)
    tol = 1e-10 * 400.0 * G
    flat, stuck = np.array([FLAT, FLAT]), np.array([0, 0])
    P, ends, anchor, y = stack(0.3)
    for k in (0, 1):
        assert E._face_that_gives_way(P, ends, anchor, flat, stuck, 1.0, y, loc, G, k, tol, held,
                                      E.new_workspace(2)) == 1
    P, ends, anchor, y = stack(0.35)
    assert E._face_that_gives_way(P, ends, anchor, flat, stuck, 1.0, y, loc, G, 0, tol, held, E.new_workspace(2)) == 0
    P, ends, anchor, y = stack(0.3)
    assert E._face_that_gives_way(P, ends, anchor, flat, np.array([0, 1]), 1.0, y, loc, G, 0, tol, held,
                                  E.new_workspace(2)) == 0
    P, ends, anchor, y = stack(0.3, top_friction=False)
    assert E._face_that_gives_way(P, ends, anchor, flat, stuck, 1.0, y, loc, G, 0, tol, held, E.new_workspace(2)) == 0


def test_a_step_at_rest_books_the_friction_needed_at_the_floors_crest_inside_it():
    """``_track_crest``: a block standing stuck under a floor 3 cos(2(t − t_c)) m/s² needs 3/g at
    the crest t_c; a step at rest over (t_a, t_b) books it there when the crest lies inside,
    nothing when it does not, and nothing for a block that rocks (the state of a step that is
    not at rest changes over it; its need is tracked elsewhere). 1e-14 relative: the rounding of
    the forces' ratio."""
    P, ends, anchor, nstate, tstate, y, ws = _standing_block(0.9)
    loc = _harmonic_floor(3.0, 2.0, -2.0 * 2.3, 0.0, 0.0, 0.0)

    def booked(t_a, t_b, nst=nstate):
        summ = np.zeros((1, E.N_BLOCK_SUMMARY))
        E._track_crest(P, ends, anchor, nst, tstate, y, t_a, t_b, np.zeros(1), summ, np.zeros(3), loc, G, ws)
        return summ[0, E.B_MU_REQ]

    assert booked(2.0, 2.4) == pytest.approx(3.0 / G, rel=1e-14)
    assert booked(2.0, 2.25) == 0.0 and booked(2.35, 2.4) == 0.0
    assert booked(2.0, 2.4, np.array([ROCK])) == 0.0


def test_a_guard_that_starts_at_zero_is_probed_back_towards_the_start():
    """``_probe_from_zero``: the gap d(x) = c₁x + c₂x² of a block in flight starts at zero and is
    negative at x_hi = 0.8. Probed at x_hi/2, x_hi/4, …: with c₁ = 0.04, c₂ = −0.08 it is
    positive at the first probe, 0.4, and comes back to zero at x = 1/2; with c₁ = 0.001 it is
    positive only below x = 0.0125, which the sixth probe lands on exactly (d = 0 there, not
    positive), so the seventh finds it and the zero is 0.0125; with c₁ = −0.04 it never comes
    back (−1). The zero is returned at or just past the root, within 1e-13 s."""
    P, ends, anchor, nstate, tstate, ws = _block_in_flight()
    held = np.zeros(1, dtype=np.bool_)
    hs, x_hi = 0.05, 0.8
    for c1, root in ((0.04, 0.5), (0.001, 0.0125), (-0.04, None)):
        c2 = -0.08
        y = np.zeros(8)
        F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
        F[0, 2], F[1, 2] = c1 + c2, -c2  # y + x(F0 + (1 − x) F1) = (F0 + F1) x − F1 x²
        g_hi = c1 * x_hi + c2 * x_hi * x_hi
        x = E._probe_from_zero(P, ends, anchor, nstate, tstate, 1.0, y, hs, F, _floor(0.0, -12.0), G, E.G_ANCHOR,
                               x_hi, g_hi, np.zeros(8), np.zeros(E.N_GUARD_SLOTS), held, ws, ws[E.WS_ACT],
                               ws[E.WS_N_ACT][0])
        if root is None:
            assert x == -1.0
        else:
            assert 0.0 <= (x - root) * hs <= 2e-13, (c1, x - root)


def test_a_stick_bound_that_starts_at_zero_is_probed_at_the_floors_own_instants():
    """``_probe_from_zero`` on a force, which depends on the time through the floor: a block
    standing stuck (μs = 0.3) at t = 2 s under a_h = μs·g and a_v = B sin(ω(τ − t)): its stick
    bound on the side a_h pushes, m·μs·a_v, is zero at t. With B = g/10 and ω = π/1.5 ms it is
    positive until T = 1.5 ms and negative at the first sample (x_hi = 1/4 of a step of 10 ms):
    the probe at x_hi/2 (1.25 ms) finds it positive and the zero found is T, 0.15 of the step,
    within the 1e-13 s the location stops at (and the rounding of the floor's phase). With B = −g/10 and ω = π/1 s it falls for a second:
    no probe finds it positive (−1). (Mutant 10032247 read the floor at t + x/hs, seconds away,
    and found the second one positive at 3.1 s.)"""
    mu, t, hs, x_hi = 0.3, 2.0, 0.01, 0.25
    P, ends, anchor, nstate, tstate, y, ws = _standing_block(mu)
    F = np.zeros((dop853.INTERPOLATOR_POWER, 8))
    held = np.zeros(1, dtype=np.bool_)
    for b, omega, want in ((0.1 * G, math.pi / 1.5e-3, 0.15), (-0.1 * G, math.pi, None)):
        loc = _harmonic_floor(mu * G, 0.0, 0.0, b, omega, -omega * t - 0.5 * math.pi)
        g_start, g_hi = np.zeros(E.N_GUARD_SLOTS), np.zeros(E.N_GUARD_SLOTS)
        E.guards(P, ends, anchor, nstate, tstate, t, y, loc, G, g_start, held, ws)
        E.guards(P, ends, anchor, nstate, tstate, t + x_hi * hs, y, loc, G, g_hi, held, ws)
        j = E.G_STICK_POS if abs(g_start[E.G_STICK_POS]) < abs(g_start[E.G_STICK_NEG]) else E.G_STICK_NEG
        assert abs(g_start[j]) < 1e-9 and g_hi[j] < 0.0  # (N: the rounding of the floor's phase at t)
        x = E._probe_from_zero(P, ends, anchor, nstate, tstate, t, y, hs, F, loc, G, j, x_hi, g_hi[j], np.zeros(8),
                               np.zeros(E.N_GUARD_SLOTS), held, ws, ws[E.WS_ACT], ws[E.WS_N_ACT][0])
        if want is None:
            assert x == -1.0
        else:
            # (from 1e-15 s before: the rounding of the floor's phase, ωt = 4189 rad, is 4e-16 s)
            assert -1e-15 <= (x - want) * hs <= 2e-13, (x - want) * hs


def test_the_grid_points_inside_a_step_are_saved_from_its_dense_output():
    """``_save_grid``: every multiple of save_dt in [t, t_stop] not saved yet, each the row of the
    dense state there; none past the capacity."""
    P, ends, anchor, nstate, tstate, ws = _block_in_flight()
    rng = np.random.default_rng(47)
    y = rng.uniform(-0.1, 0.1, 8)
    F = rng.uniform(-0.1, 0.1, (dop853.INTERPOLATOR_POWER, 8))
    t, h, save_dt = 0.1003, 0.0125, 0.002
    ncol = 1 + E.N_BLOCK_COLS + E.N_IFACE_COLS + E.N_TAIL
    for t_stop, cap in ((t + h, 100), (0.108, 100), (t + h, 4)):
        samples = np.full((cap, ncol), np.nan)
        samples[:2] = 0.0  # two rows already saved
        n_out, next_grid = E._save_grid(P, ends, anchor, nstate, tstate, t, y, h, F, G, save_dt, 50, 10_000, samples,
                                        2, cap, np.zeros(1), 0.25, t_stop, ws)
        grid = [j * save_dt for j in range(50, 100) if t <= j * save_dt <= t_stop]
        grid = grid[:cap - 2]
        assert n_out == 2 + len(grid) and next_grid == 50 + (t > 50 * save_dt) + len(grid)
        assert np.isnan(samples[n_out:]).all()
        for r, tg in enumerate(grid):
            x = (tg - t) / h
            state = np.zeros(8)
            dop853.dense(y, F, x, state)
            want = np.full((1, ncol), np.nan)
            E._save_row(P, ends, anchor, nstate, tstate, tg, state, G, np.zeros(1), 0.25, want, 0, E.new_workspace(1))
            np.testing.assert_allclose(samples[2 + r], want[0], rtol=0, atol=1e-15)


@pytest.mark.parametrize("rising", [True, False], ids=["passing the threshold", "turning back"])
def test_the_mode_after_an_event_is_the_one_the_motion_goes_on_in(rising):
    """``_select_ahead``: at a threshold every branch ties (a normal force of zero holds closed as
    well as open), so the mode is decided a moment later, where the floor's motion breaks the tie.
    A block at rest whose floor acceleration reaches its uplift value g·b/h and goes on past it
    rocks on the corner behind (and the state at the event is re-expressed at that corner, the
    block's pose unchanged); one whose floor turns back there stays flat. A floor that reaches
    −g vertically and falls on faster lifts the block off; one that turns back keeps it down."""
    b, h = 0.2, 0.6
    stack = Stack(blocks=(Block(width=2 * b, height=2 * h, mass=40.0),), interfaces=(Interface(),))
    slope = 50.0 if rising else -50.0
    t = 0.7
    for direction in (1, -1):
        P, ends, anchor, z = pack(stack)
        zd = np.zeros(3)
        # start anchored on the corner the block will not rock on, so that a move is visible
        start = 1 if direction > 0 else 0
        a, d, ad, dd = anchor_at(P, ends, anchor, 0, z, zd, start, ends[0, start, 0], ends[0, start, 1])
        anchor = np.array([start])
        z = np.array([a, 0.0, d])
        pose = poses(P, ends, anchor, z)
        # a_h(t) = direction·g·b/h at the event, then on past it (or back)
        loc = np.array([LOCAL_LINEAR, direction * G * b / h, direction * slope, t, 0.0,
                        LOCAL_LINEAR, 0.0, 0.0, 0.0, 0.0])
        nstate, tstate = np.array([FLAT]), np.array([0])
        x_sel, lam_sel = np.zeros(3), np.zeros(3)
        code = E._select_ahead(P, ends, anchor, np.array([FLAT]), t, z, zd, loc, G, np.zeros(3), nstate, tstate,
                               -1, 0, 1e-10 * 40 * G, 1e-12, x_sel, lam_sel, E.new_workspace(1))
        assert code == SELECT_OK
        if rising:
            # a floor pushing +x throws the block back onto its left corner (end 0)
            assert nstate[0] == ROCK and anchor[0] == (0 if direction > 0 else 1)
        else:
            assert nstate[0] == FLAT and anchor[0] == start
        np.testing.assert_allclose(poses(P, ends, anchor, z), pose, rtol=0, atol=1e-15)
    # vertically: the floor at −g, falling on faster or turning back
    P, ends, anchor, z = pack(stack)
    loc = np.array([LOCAL_LINEAR, 0.0, 0.0, 0.0, 0.0, LOCAL_LINEAR, -G, -slope, t, 0.0])
    nstate, tstate = np.array([FLAT]), np.array([0])
    code = E._select_ahead(P, ends, anchor, np.array([FLAT]), t, z, np.zeros(3), loc, G, np.zeros(3), nstate,
                           tstate, -1, 0, 1e-10 * 40 * G, 1e-12, np.zeros(3), np.zeros(3), E.new_workspace(1))
    assert code == SELECT_OK and nstate[0] == (OPEN if rising else FLAT)
    # The moment grows with t beyond 1 s (LOOKAHEAD·t), as the rounding of t does: 40 s into a
    # run, a floor passing −g at 2 m/s³ (a record's slope between samples 0.05 s and 0.01 g
    # apart) changes the normal force by 8e-9 of the weight in 4e-8 s, past the force tolerance
    # (1e-10 of it); in a moment that shrank with t (1e-9/t = 2.5e-11 s) it would change by 5e-12
    # of it, and the tie would stay in contact.
    loc = np.array([LOCAL_LINEAR, 0.0, 0.0, 0.0, 0.0, LOCAL_LINEAR, -G, -slope / 25.0, 40.0, 0.0])
    nstate, tstate = np.array([FLAT]), np.array([0])
    code = E._select_ahead(P, ends, anchor, np.array([FLAT]), 40.0, z, np.zeros(3), loc, G, np.zeros(3), nstate,
                           tstate, -1, 0, 1e-10 * 40 * G, 1e-12, np.zeros(3), np.zeros(3), E.new_workspace(1))
    assert code == SELECT_OK and nstate[0] == (OPEN if rising else FLAT)


def test_an_impact_that_would_gain_energy_restitutes_the_largest_fraction_that_does_not():
    """``_impact_with_less_restitution``: the restitution couple is scaled by the largest s in
    [0, 1] whose outcome is consistent and has no more kinetic energy than allowed. A slender
    block landing with r above its Housner ratio r_H leaves at (r_H + s(r − r_H))·φ̇⁻; given an
    energy budget equal to what s* = 0.6 leaves, the bisection finds s* (to 2⁻³⁰), leaves the
    couple scaled by it and the block rocking on the corner it landed on."""
    stack = Stack(blocks=(Block(width=0.3, height=1.2, mass=60.0),), interfaces=(Interface(restitution=0.97),))
    P, ends, anchor, z = pack(stack)
    zd = np.array([0.0, 0.9, 0.0])
    a, d, ad, dd = anchor_at(P, ends, anchor, 0, z, zd, 1, ends[0, 1, 0], ends[0, 1, 1])
    anchor = np.array([1])
    z, zd = np.array([a, 0.0, d]), np.array([ad, 0.9, dd])
    extra = np.zeros(3)
    E._housner_couple(P, ends, anchor, 0, z, zd, 0, extra)
    r_h, i_o = E._housner_ratio(P, ends, anchor, 0, z, 0)
    assert 0.0 < r_h < 0.97
    for s_star in (0.6, 0.05):
        rate = (r_h + s_star * (0.97 - r_h)) * 0.9
        budget = 0.5 * i_o * rate ** 2  # the block turning about its corner at that rate
        zz, zzd, ee, aa, ex = z.copy(), zd.copy(), ends.copy(), anchor.copy(), extra.copy()
        nstate, tstate = np.zeros(1, dtype=np.int64), np.zeros(1, dtype=np.int64)
        x_sel, lam_sel = np.zeros(3), np.zeros(3)
        code = E._impact_with_less_restitution(P, ee, aa, np.array([FLAT]), zz, zzd, 0.0, 0.0, G, ex, nstate,
                                               tstate, 1e-10, 1e-12, x_sel, lam_sel, budget, 0.0)
        assert code == SELECT_OK and nstate[0] == ROCK and aa[0] == 1
        s = ex[1] / extra[1]
        assert abs(s - s_star) < 2e-9 and s <= s_star * (1 + 1e-12)
        assert x_sel[1] == pytest.approx(rate, rel=1e-8)
        assert E._kinetic_of(P, ee, aa, zz, x_sel) <= budget * (1 + 1e-12)


# ---- events ------------------------------------------------------------------------------------------
def _event(P, ends, anchor, nstate, tstate, y, loc, k, slot, rest_velocity=1e-7, stop_at_edge=False, t=0.8):
    n = P.shape[0]
    events = np.full((4, E.N_EVENT_FIELDS), np.nan)
    summ = np.full((n, E.N_BLOCK_SUMMARY), np.nan)
    held = np.zeros(n, dtype=np.bool_)
    geo = nstate.copy()
    status, d_impact, n_ev = E._handle_event(
        P, ends, anchor, nstate, tstate, geo, t, y, loc, G, k, slot, 1e-10 * np.sum(P[:, P_MASS]) * G, 1e-12,
        rest_velocity, np.zeros(3 * n), np.zeros(3 * n), np.zeros(3 * n), events, 0, 0.1, summ, held, stop_at_edge,
        E.new_workspace(n))
    return status, d_impact - 0.1, events[:n_ev], summ


def _landing(width, height, mass, rate, restitution=None, paper=False):
    """A block rocking on its left corner (φ < 0) back to φ = 0 at φ̇ = rate, its right corner
    touching the floor: the event of that corner's gap."""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=width, height=height, mass=mass),),
                                    interfaces=(Interface(restitution=restitution),)))
    if paper:
        P = P.copy()
        P[0, P_IMPACT_PAPER] = 1.0
    y = _y(z, np.array([0.0, rate, 0.0]))
    return P, ends, anchor, np.array([ROCK]), np.array([0]), y


@pytest.mark.parametrize("restitution, paper", [(None, False), (0.5, False), (None, True), (0.5, True)],
                         ids=["Housner", "r = 0.5", "paper, Housner", "paper, r = 0.5"])
def test_a_landing_turns_the_block_onto_the_corner_it_hits(restitution, paper):
    """``_handle_event`` at a corner's impact: the block goes on rocking about the corner it hit
    at r·φ̇⁻ (Housner's 1 − 3/2 sin²α for a uniform block, or the interface's r; the coupled
    impulse solve and the paper's Eq. 1 agree on a single block), the anchor moves there, the
    impact loss ½ I_O φ̇⁻² (1 − r²) is booked and recorded with the event."""
    b, h, m, rate = 0.15, 0.6, 60.0, 0.9
    P, ends, anchor, nstate, tstate, y = _landing(2 * b, 2 * h, m, rate, restitution, paper)
    status, d_impact, events, summ = _event(P, ends, anchor, nstate, tstate, y, _floor(0.0, 0.0), 0, E.G_OTHER)
    r = 1.0 - 1.5 * math.sin(math.atan2(b, h)) ** 2 if restitution is None else restitution
    i_o = m * (4.0 / 3.0) * (b * b + h * h)
    loss = 0.5 * i_o * rate ** 2 * (1.0 - r * r)
    assert status == 0 and nstate[0] == ROCK and tstate[0] == 0 and anchor[0] == 1
    assert y[4] == pytest.approx(r * rate, rel=1e-12) and y[3] == 0.0 and y[5] == 0.0
    assert y[1] == 0.0 and y[2] == 0.0
    assert d_impact == pytest.approx(loss, rel=1e-10)
    assert len(events) == 1 and list(events[0, :5]) == [0.8, 0, E.EVENT_IMPACT, ROCK, 0]
    assert events[0, 5] == pytest.approx(loss, rel=1e-10)


def test_a_landing_slower_than_the_rest_velocity_lands_flat():
    """An impact that leaves the block turning slower than ``rest_velocity`` lands it flat: all
    its kinetic energy goes to the impact loss, and it rests."""
    P, ends, anchor, nstate, tstate, y = _landing(0.3, 1.2, 60.0, 2e-6)
    status, d_impact, events, summ = _event(P, ends, anchor, nstate, tstate, y, _floor(0.0, 0.0), 0, E.G_OTHER,
                                            rest_velocity=1e-5)
    i_o = 60.0 * (4.0 / 3.0) * (0.15 ** 2 + 0.6 ** 2)
    assert status == 0 and nstate[0] == FLAT and np.all(y[3:6] == 0.0)
    assert d_impact == pytest.approx(0.5 * i_o * 4e-12, rel=1e-9)
    assert list(events[0, :5]) == [0.8, 0, E.EVENT_IMPACT, FLAT, 0]


def test_an_overturn_and_a_slide_past_the_edge_stop_the_run():
    """A block past π/2, or off the face below, ends the run as overturned at that time; a corner
    at the edge below ends it as slid past the edge when asked (``stop_at_edge``) and otherwise
    goes on."""
    P, ends, anchor, nstate, tstate, y = _landing(0.3, 1.2, 60.0, 0.5)
    for slot in (E.G_OVERTURN, E.G_OVERLAP):
        status, _, events, summ = _event(P, ends, anchor, nstate.copy(), tstate.copy(), y.copy(), _floor(0, 0), 0,
                                         slot, t=1.25)
        assert status == E.STATUS_OVERTURNED and summ[0, E.B_OVERTURN] == 1.25
        assert list(events[0]) == [1.25, 0, slot, ROCK, 0, 0.0]
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=0.4, mass=20.0)),
                  interfaces=(Interface(), Interface(friction=_friction(0.3, 0.2))))
    P, ends, anchor, z = pack(stack)
    zd = np.array([0.0, 0.0, 0.0, 0.2, 0.0, 0.0])
    for stop in (True, False):
        nstate, tstate = np.array([FLAT, FLAT]), np.array([0, 1])
        status, _, events, _ = _event(P, ends, anchor.copy(), nstate, tstate, _y(z, zd), _floor(0, 0), 1, E.G_EDGE,
                                      stop_at_edge=stop)
        if stop:
            assert status == E.STATUS_PAST_EDGE and list(events[0]) == [0.8, 1, E.G_EDGE, FLAT, 1, 0.0]
        else:
            assert status == 0 and list(events[0, :3]) == [0.8, 1, E.G_EDGE]


@pytest.mark.parametrize("overlap, falls", [(1e-9, True), (2.5e-9, True), (5e-9, False)])
def test_a_corner_landing_where_the_faces_barely_overlap_is_the_fall_off_the_edge(overlap, falls):
    """A 2 × 4 m block (size h/2 + b/2 = 3 m) overhanging a 1 m block by all but ``overlap`` of
    its base, rocking back about the lower block's corner (−0.3 rad/s): its own far corner lands
    where the faces overlap by ``overlap``. Within 1e-9 of the block's size (3e-9 m) that is the
    instant it slides off the edge: the run ends with it overturned (the fall, ``G_OVERLAP``),
    not with an impact that the next instant repeats (docs/theory/stack.md §9); at 5e-9 m it is
    an impact. (Mutant 63fa490d, 1e-9 / size, took 1e-9 m for an impact.)"""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=1.0, height=0.5, mass=100.0),
                                            Block(width=2.0, height=4.0, mass=10.0, offset=1.5 - overlap)),
                                    interfaces=(Interface(), Interface())))
    zd = np.zeros(6)
    a, d, ad, dd = anchor_at(P, ends, anchor, 1, z, zd, 1, ends[1, 1, 0], ends[1, 1, 1])
    anchor = np.array([0, 1])
    z[3], z[5], zd[4] = a, d, -0.3
    xl, xr = corner_x(P, ends, anchor, 1, z)
    assert E._overlap(xl, xr, P[1, P_BL]) == pytest.approx(overlap, rel=1e-6)
    nstate, tstate = np.array([FLAT, ROCK]), np.array([0, 0])
    status, _, events, summ = _event(P, ends, anchor, nstate, tstate, _y(z, zd), _floor(0.0, 0.0), 1, E.G_OTHER)
    if falls:
        assert status == E.STATUS_OVERTURNED and summ[1, E.B_OVERTURN] == 0.8
        assert list(events[0, :3]) == [0.8, 1, E.G_OVERLAP]
    else:
        assert status == 0 and np.isnan(summ[1, E.B_OVERTURN]) and list(events[0, :3]) == [0.8, 1, E.EVENT_IMPACT]


@pytest.mark.parametrize("ah_over_g, tstate_after", [(0.0, 0), (0.45, 0), (0.7, -1)])
def test_a_slip_that_stops_sticks_if_static_friction_can_hold_it(ah_over_g, tstate_after):
    """The slip guard of a block sliding on the floor (ȧ reaching 0): the slip stops, exactly,
    and it sticks if the floor's acceleration needs less than μs·g (μs = 0.5) to carry it, or
    slips on the other way (relative to the floor, against the floor's acceleration)."""
    P, ends, anchor, z = pack(Stack(blocks=(Block(width=1.0, height=0.4, mass=50.0),),
                                    interfaces=(Interface(friction=_friction(0.5, 0.4)),)))
    y = _y(z, np.array([1e-18, 0.0, 0.0]))
    nstate, tstate = np.array([FLAT]), np.array([1])
    status, d_impact, events, _ = _event(P, ends, anchor, nstate, tstate, y, _floor(ah_over_g * G, 0.0), 0,
                                         E.G_STICK_POS)
    assert status == 0 and nstate[0] == FLAT and tstate[0] == tstate_after and y[3] == 0.0
    assert d_impact == 0.0 and list(events[0]) == [0.8, 0, E.G_STICK_POS, FLAT, tstate_after, 0.0]


def test_a_slip_that_stops_under_a_rocking_block_stops_by_a_plastic_impulse():
    """The slip guard of a pedestal sliding on the floor (5 cm/s, far above the ~1e-12 m/s a located
    guard leaves: an impact at the same instant may leave that much) while a statue rocks on it:
    the slip stops by a plastic impulse, the velocity projected in the kinetic-energy metric onto
    the mode with the floor stuck (the oracle's mass matrix, only the statue's φ free), and the
    kinetic energy it takes is booked with the impacts'. Zeroing the slip rate alone would leave
    the statue's φ̇ as it was, momenta that no longer match, and book nothing."""
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=100.0)),
                  interfaces=(Interface(friction=_friction(0.3, 0.25)), Interface()))
    P, ends, anchor, z = pack(stack)
    assert anchor[1] == 0
    z = z.copy()
    z[4] = -0.02  # the statue rocking on its left corner, the right one up
    zd = np.array([0.05, 0.0, 0.0, 0.0, -0.3, 0.0])
    nstate, tstate = np.array([FLAT, ROCK]), np.array([1, 0])
    W = np.concatenate([[P[k, P_MASS], P[k, P_MASS], P[k, P_INERTIA]] for k in range(2)])
    Jp = jacobian(lambda q: poses(P, ends, anchor, q), z)
    M = Jp.T @ (W[:, None] * Jp)
    want = np.zeros(6)
    want[4] = (M @ zd)[4] / M[4, 4]  # only the statue's φ stays free
    assert abs(want[4] - zd[4]) > 1e-3  # the impulse turns the statue too
    kinetic = 0.5 * zd @ M @ zd - 0.5 * want @ M @ want
    y = _y(z, zd)
    status, d_impact, events, _ = _event(P, ends, anchor, nstate, tstate, y, _floor(0.0, 0.0), 0, E.G_STICK_POS)
    assert status == 0 and tstate[0] == 0 and nstate[1] == ROCK
    np.testing.assert_allclose(y[6:12], want, rtol=0, atol=1e-12)
    assert d_impact == pytest.approx(kinetic, rel=1e-9) and kinetic > 0.0


@pytest.mark.parametrize("slot", ["anchor", "stick"])
def test_a_guard_that_fires_at_a_tie_vetoes_the_branch_it_ends(slot):
    """At the instant a stuck block's friction need reaches μs·g, or a flat block's floor
    acceleration reaches its uplift value (here 1e-11 past it, inside the force tolerance, so
    flat still holds as well), both branches tie; the guard's veto, with the floor's acceleration
    held there, takes the branch the guard opens: slip, or rocking on the other corner."""
    if slot == "stick":
        P, ends, anchor, z = pack(Stack(blocks=(Block(width=1.0, height=0.4, mass=50.0),),
                                        interfaces=(Interface(friction=_friction(0.5, 0.4)),)))
        nstate, tstate = np.array([FLAT]), np.array([0])
        status, _, events, _ = _event(P, ends, anchor, nstate, tstate, _y(z, np.zeros(3)), _floor(0.5 * G, 0.0), 0,
                                      E.G_STICK_POS)
        assert status == 0 and nstate[0] == FLAT and tstate[0] == -1
    else:
        P, ends, anchor, z = pack(Stack(blocks=(Block(width=0.3, height=1.2, mass=50.0),), interfaces=(Interface(),)))
        nstate, tstate = np.array([FLAT]), np.array([0])
        assert anchor[0] == 0
        ah = -G * 0.15 / 0.6 * (1.0 + 1e-11)  # throws the block onto its right corner, lifting the left
        status, _, events, _ = _event(P, ends, anchor, nstate, tstate, _y(z, np.zeros(3)), _floor(ah, 0.0), 0,
                                      E.G_ANCHOR)
        assert status == 0 and nstate[0] == ROCK and anchor[0] == 1
    assert list(events[0, :3]) == [0.8, 0, E.G_STICK_POS if slot == "stick" else E.G_ANCHOR]


def test_the_papers_impact_law_keeps_the_pedestals_sliding_velocity():
    """The paper's Eq. 1 at a statue's landing on a sliding pedestal: φ̇⁺ = r·φ̇⁻ about the new
    corner, every other interface's velocity unchanged (the pedestal's u̇), and the kinetic
    energy the change takes booked as the impact loss (against the oracle's kinetic energy)."""
    stack = Stack(blocks=(Block(width=0.8, height=0.5, mass=300.0), Block(width=0.3, height=1.2, mass=100.0)),
                  interfaces=(Interface(friction=_friction(0.2, 0.15)), Interface(restitution=0.6)))
    P, ends, anchor, z = pack(stack)
    P = P.copy()
    P[:, P_IMPACT_PAPER] = 1.0
    zd = np.array([0.25, 0.0, 0.0, 0.0, 0.7, 0.0])  # pedestal sliding, statue landing on its right corner
    y = _y(z, zd)
    nstate, tstate = np.array([FLAT, ROCK]), np.array([1, 0])
    before = zd.copy()
    status, d_impact, events, _ = _event(P, ends, anchor, nstate, tstate, y, _floor(0.0, 0.0), 1, E.G_OTHER)
    assert status == 0 and (nstate[1], anchor[1]) == (ROCK, 1) and y[6] == 0.25 and y[7] == 0.0 and y[8] == 0.0
    assert y[10] == pytest.approx(0.6 * 0.7, rel=1e-14) and y[9] == 0.0 and y[11] == 0.0

    def kinetic(anchor_, z_, zd_):
        qd = jacobian(lambda q: poses(P, ends, anchor_, q), z_) @ zd_  # noqa: E731
        W = np.array([300.0, 300.0, P[0, P_INERTIA], 100.0, 100.0, P[1, P_INERTIA]])
        return 0.5 * np.sum(W * qd ** 2)

    loss = kinetic(np.array([0, 0]), z, before) - kinetic(anchor, y[:6], y[6:12])
    assert loss > 0.0 and d_impact == pytest.approx(loss, rel=1e-9)


def test_a_far_corner_within_the_rounding_opens_as_its_first_order_change_says():
    """``_opened_below_rounding``: a rocking interface's far corner whose gap reads zero to the
    rounding of the positions at a step's end has opened if the first-order change of that gap
    over the step, ∇gap · Δ(a, φ, d), is positive. Checked on random stacks rocking about either
    end against the oracle's complex-step gradient of the far end's gap (end 1 − anchor), for a
    step of 1e-12 in a random direction; the bound of the rounding, 64 ε (h_u + h_l + 2 b_u), is
    held at 0.99 and 1.01 of it (above it the gap is resolved as it reads: False), and an anchor's
    own gap (its coordinate d) is never judged this way. Kills 786c8323 (the far end read as
    1 + anchor, past the end of the table for anchor 1), 17671e4c, 0452ef08 and e9a99568 (the
    bound's terms and factor) in bench/MUTATION.md's thirty-fourth round. ``_gap_opened`` adds the
    gaps open at the step's end (b26d1dee of the fortieth round asked both at once)."""
    rng = np.random.default_rng(12)
    checked = [0, 0]
    while min(checked) < 25:
        state = random_state(rng, ACCELERATION)
        if state is None:
            continue
        P, ends, anchor, geo, z, zd, _ = state
        for k in range(P.shape[0]):
            if geo[k] != ROCK:
                continue
            far = 1 - int(anchor[k])
            # the anchor a hair off the face, as rounding leaves it (−1.1e-16 m in a random statue
            # on a pedestal; larger here so that a d read in place of Δd shows)
            z = z.copy()
            z[3 * k + 2] = rng.uniform(-1e-3, 1e-3)
            grad = jacobian(lambda zz, k=k, far=far: np.array([contact(P, ends, anchor, k, zz, far)[0]]), z)[0]
            dz = rng.normal(size=z.size) * 1e-12
            rate = grad @ dz
            if abs(rate) < 1e-3 * np.linalg.norm(grad) * np.linalg.norm(dz):
                continue  # a step along the gap's level line: the sign is the rounding's
            y, y_new = _y(z, zd), _y(z + dz, zd)
            j = k * E.N_GUARD_SLOTS + E.G_OTHER
            bound = 64.0 * np.finfo(float).eps * (P[k, P_HU] + P[k, P_HL] + 2.0 * P[k, P_BU])
            ws = E.new_workspace(P.shape[0])
            for gap_end in (0.0, 0.99 * bound, -0.99 * bound):
                assert E._opened_below_rounding(P, ends, anchor, j, y, y_new, gap_end, ws) == (rate > 0.0)
            for gap_end in (1.01 * bound, -1.01 * bound):
                assert not E._opened_below_rounding(P, ends, anchor, j, y, y_new, gap_end, ws)
            assert not E._opened_below_rounding(P, ends, anchor, k * E.N_GUARD_SLOTS + E.G_ANCHOR, y, y_new, 0.0, ws)
            # ``_gap_opened``, what the step loop asks: a gap open at the step's end opened, whatever
            # its first-order change says; one at or below zero as the rule above says
            for gap_end in (0.99 * bound, 1.01 * bound, 1e-3):
                assert E._gap_opened(P, ends, anchor, j, y, y_new, gap_end, ws)
            for gap_end in (0.0, -0.99 * bound):
                assert E._gap_opened(P, ends, anchor, j, y, y_new, gap_end, ws) == (rate > 0.0)
            assert not E._gap_opened(P, ends, anchor, j, y, y_new, -1.01 * bound, ws)
            # a gap read from its lift-off is not judged again from the step's start
            ws[E.WS_LIFT][k, E.LIFT_MARK] = 1.0
            assert not E._opened_below_rounding(P, ends, anchor, j, y, y_new, 0.0, ws)
            checked[int(anchor[k])] += 1


def test_a_far_corner_that_lifts_within_the_rounding_is_read_from_its_lift_off():
    """``mark_lift_offs`` and ``resolve_gaps``: an interface that starts to rock (it was flat)
    with its far corner at the face (φ = 0 here, so the gap reads zero to the rounding) keeps its
    coordinates and the far gap's gradient there, which must be the oracle's complex-step
    gradient; a guard of that gap that reads within the rounding bound, 64 ε (h_u + h_l + 2 b_u),
    is then replaced by the gradient times the change of (a, φ, d) since the lift-off (the
    oracle's, to 1e-9), and one beyond it is left as it reads. The mark stays through decisions
    that do not concern the interface, is taken again at its impact (unmarked if its far gap is
    then open), and is dropped once it is flat. A corner lifted beyond the rounding is not
    marked. (The engine test of the same rule: a block set rocking just before a record's
    sample, tests/test_stack_engine.py.)"""
    rng = np.random.default_rng(36)
    checked = 0
    while checked < 30:
        P, ends, anchor, geo, _, _, z, zd = _state_in_a_mode(rng)
        n = P.shape[0]
        for k in range(n):
            if geo[k] != ROCK:
                continue
            i, j, far = 3 * k, k * E.N_GUARD_SLOTS + E.G_OTHER, 1 - int(anchor[k])
            bound = 64.0 * np.finfo(float).eps * (P[k, P_HU] + P[k, P_HL] + 2.0 * P[k, P_BU])
            tilted = z.copy()
            z = z.copy()
            z[i + 1] = z[i + 2] = 0.0
            nstate, was = geo.copy(), geo.copy()
            was[k] = FLAT
            ws = E.new_workspace(n)
            lift = ws[E.WS_LIFT]
            E.mark_lift_offs(P, ends, anchor, nstate, was, anchor.copy(), -1, _y(z, zd), ws)
            assert lift[k, E.LIFT_MARK] == 1.0
            np.testing.assert_array_equal(lift[k, E.LIFT_AT:E.LIFT_AT + 3], z[i:i + 3])
            grad = jacobian(lambda zz, k=k, far=far: np.array([contact(P, ends, anchor, k, zz, far)[0]]), z)[0]
            np.testing.assert_allclose(lift[k, E.LIFT_GRAD:E.LIFT_GRAD + 3], grad[i:i + 3], rtol=1e-12, atol=1e-15)
            dz = np.zeros_like(z)
            dz[i:i + 3] = rng.normal(size=3) * 1e-15
            y1 = _y(z + dz, zd)
            for reads in (0.0, 0.99 * bound, -0.99 * bound, 1.01 * bound, -1.01 * bound):
                g = np.full(n * E.N_GUARD_SLOTS, 7.0)
                g[j] = reads
                E.resolve_gaps(P, ends, anchor, nstate, y1, g, ws)
                if abs(reads) < bound:
                    assert g[j] == pytest.approx(grad @ dz, rel=1e-9, abs=1e-30)
                else:
                    assert g[j] == reads
                assert np.all(np.delete(g, j) == 7.0)
            # another interface's event: the mark and its reference stay
            before = lift[k].copy()
            E.mark_lift_offs(P, ends, anchor, nstate, nstate.copy(), anchor.copy(), -1, _y(tilted, zd), ws)
            np.testing.assert_array_equal(lift[k], before)
            # its own impact, leaving the far corner open beyond the rounding: unmarked
            E.mark_lift_offs(P, ends, anchor, nstate, nstate.copy(), anchor.copy(), k, _y(tilted, zd), ws)
            assert lift[k, E.LIFT_MARK] == 0.0
            # lifted beyond the rounding from flat: not marked
            E.mark_lift_offs(P, ends, anchor, nstate, was, anchor.copy(), -1, _y(tilted, zd), ws)
            assert lift[k, E.LIFT_MARK] == 0.0
            # marked again, then flat: unmarked, and a flat interface's guard is never replaced
            E.mark_lift_offs(P, ends, anchor, nstate, was, anchor.copy(), -1, _y(z, zd), ws)
            assert lift[k, E.LIFT_MARK] == 1.0
            flat = nstate.copy()
            flat[k] = FLAT
            g = np.zeros(n * E.N_GUARD_SLOTS)
            E.resolve_gaps(P, ends, anchor, flat, y1, g, ws)
            assert g[j] == 0.0
            E.mark_lift_offs(P, ends, anchor, flat, nstate, anchor.copy(), -1, _y(z, zd), ws)
            assert lift[k, E.LIFT_MARK] == 0.0
            checked += 1
