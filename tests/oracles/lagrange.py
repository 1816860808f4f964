"""Independent sympy derivation of the statue-on-pedestal equations (oracle for the solver).

Never imports ``rocking``.  Everything below is derived here from positions, kinetic and
potential energy and momentum balances; nothing is retyped from docs/theory/derivation.md
(the self-check tests compare the results with the formulas printed there).

Model
-----
* Floor position (x_g(t), y_g(t)); a_g = x_g'', a_v = y_g''.
* Pedestal (mass m1) slides horizontally: centre of mass (x_g + u, y_g + c1).
* Statue (mass m2, uniform rectangle, half-width b, half-height h, R = sqrt(b^2+h^2),
  alpha = atan(b/h), J_G = m2 R^2/3) rocks on the pivot s = +1 (its +x base corner, theta >= 0)
  or s = -1 (its -x corner, theta <= 0).  Pivot at (x_g + u + s b, y_g + H1); statue centre of
  mass at pivot + (-s R sin(phi), R cos(phi)) with phi = alpha - s theta.
* theta > 0 tilts the statue towards +x (clockwise rotation): body angular velocity about +z is
  -theta_dot (checked symbolically below).
* Floor friction F acts on the pedestal along +x; its virtual work is F du, so the generalised
  forces are Q_u = F, Q_theta = 0 (the pivot does not slip).

Public API
----------
accelerations(regime, params, state, a_g, a_v=0.0, *, s=None, sigma=None)
    -> (u_ddot, theta_ddot, N, F, Px, Py)
energy(params, state, *, s=None) -> float
impact_coulomb(params, state, *, r=None, s_before=None) -> ImpactResult
impact_paper(params, state, *, r=None, s_before=None) -> ImpactResult

statue_velocity_rel(params, state, *, s=None) -> (vx, vy)
consistent_regimes(params, a_g, a_v=0.0) -> [(regime, s, sigma), ...]   (at u_dot = theta = theta_dot = 0)
select_regime(params, a_g, a_v=0.0) -> (regime, s, sigma)              (preference rule)
pedestal_center_of_pressure(params, H1, s, Px, Py, N, a_abs) -> x_N
symbolic(regime, s, normal_force) / symbolic_equations(s): the sympy expressions themselves.

params: dict with b, h, m1, m2 and optionally g (default 9.81), mu_s, mu_k,
normal_force ("full" default | "paper").  state: (u, u_dot, theta, theta_dot).
"paper" means N = M (g + a_v) (the seed's Eq. 18 normal force, without the stray a_g factor),
i.e. N = M g without vertical floor motion; "full" is the N of the vertical momentum balance.

The symbolic work (about 1 s) is done lazily on first use and cached in the module-level
dict _CACHE, one lambdified function per (regime, pivot, normal-force model).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import sympy as sp

G_DEFAULT = 9.81
REGIMES = ("stick-rest", "stick-rock", "slide-rest", "slide-rock")

# ---------------------------------------------------------------------------------------------
# Symbolic derivation
# ---------------------------------------------------------------------------------------------
_t = sp.Symbol("t", real=True)
b, h, m1, m2, g = sp.symbols("b h m1 m2 g", positive=True)
c1, H1 = sp.symbols("c1 H1", positive=True)  # pedestal centre-of-mass height, pedestal height
mu_k, sigma, F = sp.symbols("mu_k sigma F", real=True)
u_s, ud_s, udd_s, th_s, thd_s, thdd_s = sp.symbols("u u_dot u_ddot theta theta_dot theta_ddot", real=True)
ag_s, av_s, vg_s, vgy_s = sp.symbols("a_g a_v v_g v_gy", real=True)

_u = sp.Function("u", real=True)(_t)
_th = sp.Function("theta", real=True)(_t)
_xg = sp.Function("x_g", real=True)(_t)
_yg = sp.Function("y_g", real=True)(_t)

# R and alpha are kept as symbols (R = sqrt(b^2+h^2), alpha = atan(b/h) are passed numerically);
# this keeps the expressions short and the derivation fast.
R, alpha = sp.symbols("R alpha", positive=True)
M = m1 + m2
J_G = m2 * R ** 2 / 3


def _to_symbols(expr):
    """Replace time derivatives by plain symbols (highest order first)."""
    reps = [
        (_u.diff(_t, 2), udd_s), (_th.diff(_t, 2), thdd_s), (_xg.diff(_t, 2), ag_s), (_yg.diff(_t, 2), av_s),
        (_u.diff(_t), ud_s), (_th.diff(_t), thd_s), (_xg.diff(_t), vg_s), (_yg.diff(_t), vgy_s),
        (_u, u_s), (_th, th_s),
    ]
    for a, z in reps:
        expr = expr.subs(a, z)
    return expr


def _tidy(expr, wrt=()):
    """Cheap tidy-up: expand, collect in the given symbols and trigsimp each coefficient."""
    expr = sp.expand(expr)
    if not wrt:
        return sp.trigsimp(expr)
    coll = sp.collect(expr, wrt, evaluate=False)
    return sp.Add(*[sp.trigsimp(c) * k for k, c in coll.items()])


def _at_theta0(expr):
    """Evaluate at theta = 0 and write sin(alpha), cos(alpha) as b/R, h/R."""
    expr = sp.expand_trig(sp.expand(expr.subs(th_s, 0)))
    return sp.expand(expr.subs({sp.sin(alpha): b / R, sp.cos(alpha): h / R}))


def _kinematics(s: int):
    """Absolute positions of the two centres of mass and the pivot, for pivot s."""
    phi = alpha - s * _th
    x1 = sp.Matrix([_xg + _u, _yg + c1])
    pivot = sp.Matrix([_xg + _u + s * b, _yg + H1])
    x2 = pivot + sp.Matrix([-s * R * sp.sin(phi), R * sp.cos(phi)])
    return x1, x2, pivot


def _derive(s: int):
    x1, x2, pivot = _kinematics(s)
    v1, v2 = x1.diff(_t), x2.diff(_t)
    a2 = v2.diff(_t)
    T = sp.Rational(1, 2) * m1 * v1.dot(v1) + sp.Rational(1, 2) * m2 * v2.dot(v2) \
        + sp.Rational(1, 2) * J_G * _th.diff(_t) ** 2
    V = m1 * g * x1[1] + m2 * g * x2[1]
    L = T - V
    eqs = {}
    for q, Q in ((_u, F), (_th, 0)):
        el = sp.diff(sp.diff(L, q.diff(_t)), _t) - sp.diff(L, q) - Q
        eqs[q] = _to_symbols(el)
    W = (udd_s, thdd_s, ag_s, av_s, thd_s ** 2, F, g)
    E_u = _tidy(eqs[_u], W)  # = 0
    E_th = _tidy(eqs[_th], W)  # = 0
    # floor normal force from the vertical momentum balance of the whole system:
    # N - M g = m1 y1'' + m2 y2''
    N_full = _tidy(_to_symbols(M * g + m1 * x1[1].diff(_t, 2) + m2 * a2[1]), W)
    # contact force on the statue at its pivot from the statue's own Newton equations:
    # m2 a_G = P + m2 g (0, -1)
    Px = _tidy(_to_symbols(m2 * a2[0]), W)
    Py = _tidy(_to_symbols(m2 * a2[1] + m2 * g), W)
    # horizontal momentum balance of the whole system must equal the u Euler-Lagrange equation
    Fx_balance = _to_symbols(m1 * x1[0].diff(_t, 2) + m2 * a2[0])
    assert sp.expand(E_u - (Fx_balance - F)) == 0, "u-equation != horizontal momentum balance"
    # body angular velocity about +z from the rotation of (G - pivot)
    r = x2 - pivot
    omega_z = _to_symbols((r[0] * r[1].diff(_t) - r[1] * r[0].diff(_t)) / (r[0] ** 2 + r[1] ** 2))
    assert sp.trigsimp(sp.factor(omega_z)) == -thd_s
    # energy relative to the floor (velocities relative to the floor, potential from pedestal top)
    x2_rel = x2 - sp.Matrix([_xg, _yg + H1])
    v2_rel = _to_symbols(x2_rel.diff(_t))
    T_rel = sp.Rational(1, 2) * m1 * ud_s ** 2 + sp.Rational(1, 2) * m2 * v2_rel.dot(v2_rel) \
        + sp.Rational(1, 2) * J_G * thd_s ** 2
    E_rel = _tidy(T_rel + m2 * g * _to_symbols(x2_rel[1]), (thd_s ** 2, ud_s * thd_s, ud_s ** 2, g))
    return dict(E_u=E_u, E_th=E_th, N=N_full, Px=Px, Py=Py, E_rel=E_rel, v2_rel=v2_rel,
                x2=_to_symbols(x2), v2=_to_symbols(v2), pivot=_to_symbols(pivot))


def _linear_solve(eqs, unknowns):
    """Solve a small linear system symbolically by Cramer's rule; also return the determinant."""
    A, rhs = sp.linear_eq_to_matrix([sp.expand(e) for e in eqs], list(unknowns))
    det = sp.expand(A.det())
    sols = []
    for j in range(len(unknowns)):
        Aj = A.copy()
        Aj[:, j] = rhs
        sols.append(sp.expand(Aj.det()) / det)
    return sols, det


def _solve_regime(d, regime: str, normal_force: str):
    """Return symbolic (u_ddot, theta_ddot, N, F, det) for a regime (det: determinant of the
    linear system solved for the accelerations, 1 when none is solved)."""
    E_u, E_th, N = d["E_u"], d["E_th"], d["N"]
    rest = {th_s: 0, thd_s: 0, thdd_s: 0}
    N_paper = M * (g + av_s)
    one = sp.Integer(1)
    if regime == "stick-rest":
        sub = {**rest, udd_s: 0}
        (Fv,), _ = _linear_solve([E_u.subs(sub)], [F])
        return sp.Integer(0), sp.Integer(0), (N.subs(sub) if normal_force == "full" else N_paper), Fv, one
    if regime == "stick-rock":
        (thdd,), det = _linear_solve([E_th.subs(udd_s, 0)], [thdd_s])
        sub = {udd_s: 0, thdd_s: thdd}
        (Fv,), _ = _linear_solve([E_u.subs(sub)], [F])
        Nv = N.subs(sub) if normal_force == "full" else N_paper
        return sp.Integer(0), thdd, Nv, Fv, det
    if regime == "slide-rest":
        Nv = N.subs(rest) if normal_force == "full" else N_paper
        Fv = -sigma * mu_k * Nv
        (udd,), det = _linear_solve([E_u.subs(rest).subs(F, Fv)], [udd_s])
        return udd, sp.Integer(0), Nv, Fv, det
    if regime == "slide-rock":
        Nsym = N if normal_force == "full" else N_paper
        (udd, thdd), det = _linear_solve([E_u.subs(F, -sigma * mu_k * Nsym), E_th], [udd_s, thdd_s])
        Nv = Nsym.subs({udd_s: udd, thdd_s: thdd})
        return udd, thdd, Nv, -sigma * mu_k * Nv, det
    raise ValueError(f"unknown regime {regime!r}; expected one of {REGIMES}")


_ARGS = (b, h, R, alpha, m1, m2, g, mu_k, sigma, u_s, ud_s, th_s, thd_s, ag_s, av_s)
_CACHE: dict = {}


def _derived(s: int):
    key = ("derive", s)
    if key not in _CACHE:
        _CACHE[key] = _derive(s)
    return _CACHE[key]


def _acc_function(regime: str, s: int, normal_force: str):
    key = ("acc", regime, s, normal_force)
    if key not in _CACHE:
        d = _derived(s)
        udd, thdd, Nv, Fv, det = _solve_regime(d, regime, normal_force)
        sub = {udd_s: udd, thdd_s: thdd}
        Px = d["Px"].subs(sub)
        Py = d["Py"].subs(sub)
        if regime.endswith("rest"):
            Px, Py = Px.subs({th_s: 0, thd_s: 0}), Py.subs({th_s: 0, thd_s: 0})
        fn = sp.lambdify(_ARGS, [udd, thdd, Nv, Fv, Px, Py], modules="math", cse=True)
        # slide-rock: det = M I_O - m2^2 R^2 cos(phi) (cos(phi) + sigma mu_k s sin(phi)) must be > 0
        # (Painleve-type indeterminacy otherwise)
        detf = sp.lambdify(_ARGS, det, modules="math") if regime == "slide-rock" else None
        _CACHE[key] = (fn, detf)
    return _CACHE[key]


def symbolic(regime: str, s: int, normal_force: str = "full"):
    """Symbolic (u_ddot, theta_ddot, N, F) for a regime and pivot s (for inspection/docs)."""
    return _solve_regime(_derived(s), regime, normal_force)[:4]


def symbolic_equations(s: int):
    """Symbolic Euler-Lagrange residuals and force expressions for pivot s (dict)."""
    return dict(_derived(s))


# ---------------------------------------------------------------------------------------------
# Numerical API
# ---------------------------------------------------------------------------------------------
def _sign(x: float) -> int:
    return 1 if x > 0 else (-1 if x < 0 else 0)


def _params(params: dict):
    p = dict(params)
    return (float(p["b"]), float(p["h"]), float(p["m1"]), float(p["m2"]), float(p.get("g", G_DEFAULT)),
            p.get("normal_force", "full"))


def accelerations(regime: str, params: dict, state, a_g: float, a_v: float = 0.0, *,
                  s: int | None = None, sigma: int | None = None):
    """Accelerations and forces of the statue-on-pedestal system in a given regime.

    regime: "stick-rest" | "stick-rock" | "slide-rest" | "slide-rock".
    params: {b, h, m1, m2, g=9.81, mu_s, mu_k, normal_force="full"|"paper"} (SI units).
    state: (u, u_dot, theta, theta_dot) - u, u_dot relative to the floor (m, m/s), theta in rad.
    a_g, a_v: horizontal and vertical floor accelerations (m/s^2, +x and +y).
    s: pivot (+1 or -1); default sign(theta); required for rock regimes when theta == 0.
    sigma: slide direction (+1 or -1); default sign(u_dot); required for slide regimes when
        u_dot == 0.  Friction while sliding is F = -sigma mu_k N.

    "rest" regimes use theta = theta_dot = theta_ddot = 0; "stick" regimes use u_ddot = 0 and
    return in F the friction force the floor must supply (to be compared with mu_s N).  With
    normal_force="paper", N = M (g + a_v) (the paper's Eq. 18 normal force) everywhere.

    Returns (u_ddot, theta_ddot, N, F, Px, Py): pedestal acceleration relative to the floor
    (m/s^2), statue angular acceleration (rad/s^2), floor normal force on the pedestal (N),
    floor friction force on the pedestal along +x (N), force of the pedestal on the statue at
    the pivot (N, +x and +y).  Raises ValueError for a Painleve-singular slide-rock system.
    """
    bb, hh, mm1, mm2, gg, nf = _params(params)
    if nf not in ("full", "paper"):
        raise ValueError("normal_force must be 'full' or 'paper'")
    u, ud, th, thd = (float(x) for x in state)
    if regime.endswith("rock"):
        if s is None:
            s = _sign(th)
        if s not in (1, -1):
            raise ValueError("pivot s must be +1 or -1 (theta == 0 needs an explicit s)")
    else:
        s = 1 if s is None else s  # irrelevant at rest
    if regime.startswith("slide"):
        if sigma is None:
            sigma = _sign(ud)
        if sigma not in (1, -1):
            raise ValueError("slide sign sigma must be +1 or -1 (u_dot == 0 needs an explicit sigma)")
        muk = float(params["mu_k"])
    else:
        sigma, muk = 0, float(params.get("mu_k", 0.0))
    fn, det = _acc_function(regime, s, nf)
    args = (bb, hh, math.hypot(bb, hh), math.atan2(bb, hh), mm1, mm2, gg, muk, sigma, u, ud, th, thd, a_g, a_v)
    if det is not None and det(*args) <= 0.0:
        raise ValueError("Painleve-type indeterminacy: slide-rock mass matrix determinant <= 0")
    return tuple(float(x) for x in fn(*args))


def energy(params: dict, state, *, s: int | None = None) -> float:
    """Mechanical energy (J) relative to the floor: kinetic energy of both bodies with velocities
    relative to the floor plus m2 g (height of the statue's centre of mass above the pedestal
    top).  state = (u, u_dot, theta, theta_dot); s defaults to sign(theta) (either pivot gives the
    same value at theta = 0)."""
    bb, hh, mm1, mm2, gg, _ = _params(params)
    u, ud, th, thd = (float(x) for x in state)
    if s is None:
        s = _sign(th) or 1
    key = ("energy", s)
    if key not in _CACHE:
        _CACHE[key] = sp.lambdify(_ARGS, _derived(s)["E_rel"], modules="math")
    return float(_CACHE[key](bb, hh, math.hypot(bb, hh), math.atan2(bb, hh), mm1, mm2, gg, 0.0, 0, u, ud, th, thd, 0.0, 0.0))


def statue_velocity_rel(params: dict, state, *, s: int | None = None) -> tuple[float, float]:
    """Velocity (m/s) of the statue's centre of mass relative to the floor, (x, y)."""
    bb, hh, mm1, mm2, gg, _ = _params(params)
    u, ud, th, thd = (float(x) for x in state)
    if s is None:
        s = _sign(th) or 1
    key = ("v2rel", s)
    if key not in _CACHE:
        _CACHE[key] = sp.lambdify(_ARGS, list(_derived(s)["v2_rel"]), modules="math")
    vx, vy = _CACHE[key](bb, hh, math.hypot(bb, hh), math.atan2(bb, hh), mm1, mm2, gg, 0.0, 0, u, ud, th, thd, 0.0, 0.0)
    return float(vx), float(vy)


# ---------------------------------------------------------------------------------------------
# Impact at theta = 0 (derivation.md section 3.6), derived from momentum balances
# ---------------------------------------------------------------------------------------------
Vm, Vp, thdm, thdp, Fx_s, Fy_s, r_s, mu_s_sym = sp.symbols(
    "V_minus V_plus thetadot_minus thetadot_plus F_x F_y r mu_s", real=True)


def _impact_equations(s_before: int):
    """Momentum equations of an impact at theta = 0 where the pivot switches s_before -> -s_before.

    Returns (eq_L, eq_Lr, eq_x, eq_y, Lam_x, Lam_y), all expressions that vanish:
      eq_L  : statue angular momentum about the new pivot is conserved (the only impulse on the
              statue acts there; the old corner releases without impulse),
      eq_Lr : same with the theta_dot- coefficient replaced by r times the theta_dot+ one (a
              user-prescribed restitution r; with the pedestal held it gives theta_dot+ = r theta_dot-),
      eq_x  : horizontal momentum change of the whole system - Fx,
      eq_y  : vertical momentum change of the whole system - Fy,
    and Lam_x, Lam_y: the impulse on the statue at the new pivot (its momentum change).
    Positions are frozen during the impact; the floor velocity (v_g, v_gy) is continuous and
    cancels (asserted).
    """
    key = ("impact", s_before)
    if key in _CACHE:
        return _CACHE[key]
    s_after = -s_before
    d_m, d_p = _derived(s_before), _derived(s_after)

    def vel(d, V, thd):
        return sp.Matrix([_at_theta0(c.subs({ud_s: V, thd_s: thd})) for c in d["v2"]])

    v2m, v2p = vel(d_m, Vm, thdm), vel(d_p, Vp, thdp)
    # both kinematic descriptions place G at the same point when theta = 0
    assert all(sp.expand(_at_theta0(a - c)) == 0 for a, c in zip(d_m["x2"], d_p["x2"]))
    rG = sp.Matrix([_at_theta0(c) for c in (d_m["x2"] - d_p["pivot"])])  # G - new pivot
    # angular momentum about the spatial point at the new pivot; body omega_z = -theta_dot
    Hm = -J_G * thdm + m2 * (rG[0] * v2m[1] - rG[1] * v2m[0])
    Hp = -J_G * thdp + m2 * (rG[0] * v2p[1] - rG[1] * v2p[0])
    eq_L = sp.expand(Hp - Hm)
    cm = sp.diff(Hm, thdm)  # coefficient of theta_dot- in H-: -(I_O - 2 m2 b^2)
    cp = sp.diff(Hp, thdp)  # coefficient of theta_dot+ in H+: -I_O
    eq_Lr = sp.expand(Hp - (Hm - cm * thdm + r_s * cp * thdm))
    px = lambda V, v2: m1 * (vg_s + V) + m2 * v2[0]
    py = lambda v2: m1 * vgy_s + m2 * v2[1]
    eq_x = sp.expand(px(Vp, v2p) - px(Vm, v2m) - Fx_s)
    eq_y = sp.expand(py(v2p) - py(v2m) - Fy_s)
    Lam = (m2 * (v2p - v2m)).applyfunc(sp.expand)
    for e in (eq_L, eq_Lr, eq_x, eq_y, Lam[0], Lam[1]):
        assert not e.has(vg_s) and not e.has(vgy_s)
    out = (eq_L, eq_Lr, eq_x, eq_y, Lam[0], Lam[1])
    _CACHE[key] = out
    return out


_IMP_ARGS = (b, h, R, m1, m2, r_s, mu_k, sigma, Vm, thdm)


def _impact_solvers(s_before: int, use_r: bool):
    key = ("impact_solvers", s_before, use_r)
    if key in _CACHE:
        return _CACHE[key]
    eq_L, eq_Lr, eq_x, eq_y, Lx, Ly = _impact_equations(s_before)
    eqL = eq_Lr if use_r else eq_L
    # stick: V+ = 0; unknowns theta_dot+, Fx, Fy
    (thp, fx, fy), _ = _linear_solve([eqL.subs(Vp, 0), eq_x.subs(Vp, 0), eq_y], [thdp, Fx_s, Fy_s])
    st_sub = {Vp: 0, thdp: thp}
    stick = sp.lambdify(_IMP_ARGS, [sp.Integer(0), thp, fx, fy, Lx.subs(st_sub), Ly.subs(st_sub)],
                        modules="math", cse=True)
    # slide: Fx = -sigma mu_k Fy; unknowns V+, theta_dot+, Fy
    (vp, thp2, fy2), _ = _linear_solve([eqL, eq_x.subs(Fx_s, -sigma * mu_k * Fy_s), eq_y], [Vp, thdp, Fy_s])
    sl_sub = {Vp: vp, thdp: thp2}
    slide = sp.lambdify(_IMP_ARGS, [vp, thp2, -sigma * mu_k * fy2, fy2, Lx.subs(sl_sub), Ly.subs(sl_sub)],
                        modules="math", cse=True)
    # paper: V+ = V-, theta_dot+ = r theta_dot- (impulses implied by the momentum balances)
    pa_sub = {Vp: Vm, thdp: r_s * thdm}
    (fx3, fy3), _ = _linear_solve([eq_x.subs(pa_sub), eq_y.subs(pa_sub)], [Fx_s, Fy_s])
    paper = sp.lambdify(_IMP_ARGS, [Vm, r_s * thdm, fx3, fy3, Lx.subs(pa_sub), Ly.subs(pa_sub)],
                        modules="math", cse=True)
    _CACHE[key] = (stick, slide, paper)
    return _CACHE[key]


class ImpactResult(NamedTuple):
    """Post-impact state and impulses (SI: m/s, rad/s, N s)."""

    u_dot: float  #: pedestal velocity relative to the floor after the impact
    theta_dot: float  #: statue angular velocity after the impact
    Fx: float  #: horizontal floor impulse on the pedestal (+x)
    Fy: float  #: vertical floor impulse (+y)
    Lx: float  #: horizontal impulse on the statue at the new pivot
    Ly: float  #: vertical impulse on the statue at the new pivot
    mode: str  #: "stick" | "slide" | "paper"
    s_after: int  #: new pivot
    consistent: bool  #: Fy >= 0, Ly >= 0 and theta_dot+ moves the statue onto the new pivot side


def _impact_prepare(params, state, r, s_before):
    bb, hh, mm1, mm2, gg, _ = _params(params)
    u, ud, th, thd = (float(x) for x in state)
    if s_before is None:
        s_before = _sign(th) or -_sign(thd)
    if s_before not in (1, -1):
        raise ValueError("cannot infer the pivot before the impact; pass s_before")
    use_r = r is not None
    return (bb, hh, math.hypot(bb, hh), mm1, mm2), ud, thd, s_before, use_r, (float(r) if use_r else 0.0)


def _consistent(res_thd, Fy, Ly, s_after):
    return Fy >= 0.0 and Ly >= 0.0 and s_after * res_thd >= 0.0


def impact_coulomb(params: dict, state, *, r: float | None = None, s_before: int | None = None) -> ImpactResult:
    """Impact map with Coulomb friction at the impulse level (derivation.md section 3.6).

    state = (u, u_dot, theta, theta_dot) just before the impact (theta ~ 0); s_before defaults
    to sign(theta), or -sign(theta_dot) if theta == 0.  Equations (derived with sympy above):
      1. statue angular momentum about the new pivot conserved
         (with r: the theta_dot- coefficient I_O - 2 m2 b^2 is replaced by r I_O);
      2. horizontal momentum of the system changes by the floor impulse Fx;
      3. vertical momentum of the system changes by the floor impulse Fy;
      4. try u_dot+ = 0 and accept if |Fx| <= mu_s Fy; otherwise Fx = -sigma mu_k Fy with
         sigma = sign(u_dot+), trying sigma = -sign(Fx_stick) first, then the other sign.
    params needs mu_s and mu_k.  Raises ValueError if no sliding solution is consistent.
    """
    geo, ud, thd, s_b, use_r, rr = _impact_prepare(params, state, r, s_before)
    mus, muk = float(params["mu_s"]), float(params["mu_k"])
    stick, slide, _ = _impact_solvers(s_b, use_r)
    s_a = -s_b
    V, th_p, Fx, Fy, Lx, Ly = (float(x) for x in stick(*geo, rr, muk, 0, ud, thd))
    if abs(Fx) <= mus * Fy:
        return ImpactResult(0.0, th_p, Fx, Fy, Lx, Ly, "stick", s_a, _consistent(th_p, Fy, Ly, s_a))
    first = -_sign(Fx) or 1
    for sg in (first, -first):
        V, th_p, Fx2, Fy2, Lx2, Ly2 = (float(x) for x in slide(*geo, rr, muk, sg, ud, thd))
        if _sign(V) == sg:
            return ImpactResult(V, th_p, Fx2, Fy2, Lx2, Ly2, "slide", s_a, _consistent(th_p, Fy2, Ly2, s_a))
    raise ValueError("no consistent sliding impact solution")


def impact_paper(params: dict, state, *, r: float | None = None, s_before: int | None = None) -> ImpactResult:
    """The seed paper's impact rule: theta_dot+ = r theta_dot-, u_dot unchanged (r defaults to
    Housner's eta = 1 - 1.5 sin^2 alpha).  The returned Fx, Fy are the floor impulses this rule
    implies (from the momentum balances), with no friction check; 'consistent' only checks the
    signs of Fy, Ly and theta_dot+ (use |Fx|/Fy against mu_s yourself, O19)."""
    geo, ud, thd, s_b, use_r, rr = _impact_prepare(params, state, r, s_before)
    if not use_r:
        bb, hh = geo[0], geo[1]
        rr = 1.0 - 1.5 * bb * bb / (bb * bb + hh * hh)
    _, _, paper = _impact_solvers(s_b, True)
    V, th_p, Fx, Fy, Lx, Ly = (float(x) for x in paper(*geo, rr, 0.0, 0, ud, thd))
    s_a = -s_b
    return ImpactResult(V, th_p, Fx, Fy, Lx, Ly, "paper", s_a, _consistent(th_p, Fy, Ly, s_a))


# ---------------------------------------------------------------------------------------------
# Mode selection at a state where several regimes are candidates (derivation.md section 3.5)
# ---------------------------------------------------------------------------------------------
#: preference order: fewest moving degrees of freedom, stick before slide, rest before rock
REGIME_PREFERENCE = ("stick-rest", "stick-rock", "slide-rest", "slide-rock")


def consistent_regimes(params: dict, a_g: float, a_v: float = 0.0, state=(0.0, 0.0, 0.0, 0.0)):
    """All regimes consistent at a state with u_dot = 0 and theta = theta_dot = 0 (e.g. t = 0+),
    as a list of (regime, s, sigma) in preference order (s, sigma = 0 where irrelevant).

    Consistency tests:
      stick: |F| <= mu_s N;            slip: sigma u_ddot > 0;
      rest:  |a_g + u_ddot| <= (g + a_v) tan(alpha);   rock: s theta_ddot > 0.
    Also N > 0 is required.  params needs mu_s and mu_k.
    """
    u, ud, th, thd = (float(x) for x in state)
    if ud != 0.0 or th != 0.0 or thd != 0.0:
        raise ValueError("consistent_regimes expects u_dot = theta = theta_dot = 0")
    bb, hh = float(params["b"]), float(params["h"])
    gg = float(params.get("g", G_DEFAULT))
    mus = float(params["mu_s"])
    tan_a = bb / hh
    out = []
    for regime in REGIME_PREFERENCE:
        for s in ((0,) if regime.endswith("rest") else (1, -1)):
            for sg in ((0,) if regime.startswith("stick") else (1, -1)):
                kw = {}
                if s:
                    kw["s"] = s
                if sg:
                    kw["sigma"] = sg
                try:
                    udd, thdd, N, Fv, _px, _py = accelerations(regime, params, state, a_g, a_v, **kw)
                except ValueError:
                    continue
                ok = N > 0.0
                if regime.startswith("stick"):
                    ok &= abs(Fv) <= mus * N
                else:
                    ok &= sg * udd > 0.0
                if regime.endswith("rest"):
                    ok &= abs(a_g + udd) <= (gg + a_v) * tan_a
                else:
                    ok &= s * thdd > 0.0
                if ok:
                    out.append((regime, s, sg))
    return out


def select_regime(params: dict, a_g: float, a_v: float = 0.0):
    """First consistent regime in REGIME_PREFERENCE order at u_dot = theta = theta_dot = 0:
    (regime, s, sigma).  Raises ValueError if none is consistent."""
    c = consistent_regimes(params, a_g, a_v)
    if not c:
        raise ValueError("no consistent regime")
    return c[0]


# ---------------------------------------------------------------------------------------------
# Centre of pressure under the pedestal (pedestal-uplift check), derived by a moment balance
# ---------------------------------------------------------------------------------------------
def _x_n_expression():
    """x_N from the moment balance of the (non-rotating) pedestal about the floor point below its
    centre of mass: x_N N + (moment of the statue's reaction -P at (s b, H1)) = moment of
    m1 a_G1 with r_G1 = (0, H1/2).  Returns x_N(s, Px, Py, N, a_abs) with a_abs = a_g + u_ddot."""
    key = ("xN",)
    if key not in _CACHE:
        s_, Px_, Py_, N_, a_, xN = sp.symbols("s P_x P_y N a_abs x_N", real=True)
        r_P = (s_ * b, H1)
        mom_P = r_P[0] * (-Py_) - r_P[1] * (-Px_)
        r_G = (0, H1 / 2)
        mom_inertia = r_G[0] * (m1 * av_s) - r_G[1] * (m1 * a_)
        sol = sp.solve(sp.Eq(xN * N_ + mom_P, mom_inertia), xN)[0]
        _CACHE[key] = (sp.lambdify((s_, b, H1, m1, Px_, Py_, N_, a_, av_s), sol, modules="math"), sol)
    return _CACHE[key]


def _x_n_rest_expression():
    """x_N while the statue rests on the pedestal (no rocking): its reaction acts at x_p, which
    the statue's own moment balance about its centre of mass (0, H1 + h) fixes, since it does
    not rotate: (x_p, -h) x P = 0; then the pedestal's balance as above, with -P at (x_p, H1).
    Returns x_N(h, Px, Py, N, a_abs)."""
    key = ("xN rest",)
    if key not in _CACHE:
        Px_, Py_, N_, a_, xN, xp = sp.symbols("P_x P_y N a_abs x_N x_p", real=True)
        x_p = sp.solve(sp.Eq(xp * Py_ - (-h) * Px_, 0), xp)[0]
        mom_P = x_p * (-Py_) - H1 * (-Px_)
        mom_inertia = -(H1 / 2) * (m1 * a_)
        sol = sp.solve(sp.Eq(xN * N_ + mom_P, mom_inertia), xN)[0]
        _CACHE[key] = (sp.lambdify((h, H1, m1, Px_, Py_, N_, a_), sol, modules="math"), sol)
    return _CACHE[key]


def pedestal_center_of_pressure(params: dict, H1: float, s: int | None, Px: float, Py: float, N: float,
                                a_abs: float) -> float:
    """Horizontal position (m) of the floor's resultant normal force relative to the pedestal's
    centre line, for a pedestal of height H1 with its centre of mass at H1/2; a_abs is the
    pedestal's absolute horizontal acceleration a_g + u_ddot.  The pedestal uplifts if |x_N|
    exceeds its half-width.  While the statue rocks (s = ±1) this is derivation.md 3.5's
    x_N = [s b Py - H1 Px - (H1/2) m1 a_abs] / N; while it rests (s None or 0) the statue's
    reaction acts where its own moment balance puts it (_x_n_rest_expression), which that
    formula, read at s = 0, leaves out."""
    if not s:
        fn, _ = _x_n_rest_expression()
        return float(fn(float(params["h"]), H1, float(params["m1"]), Px, Py, N, a_abs))
    fn, _ = _x_n_expression()
    return float(fn(s, float(params["b"]), H1, float(params["m1"]), Px, Py, N, a_abs, 0.0))
