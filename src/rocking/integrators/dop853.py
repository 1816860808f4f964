"""Dormand–Prince 8(5,3) Runge–Kutta step with its 7th-order dense output, compiled.

Generic numerics, in the style of :mod:`rocking.integrators.dopri5`: nothing here evaluates a
right-hand side. The caller loops over the stages, evaluating its own right-hand side where this
module says (numba cannot cache a function that receives another compiled function as an
argument, so keeping the right-hand side outside lets everything be cached on disk).

The method is Hairer's DOP853 (Hairer, Nørsett & Wanner, *Solving Ordinary Differential
Equations I*, §II.10; the Fortran code ``dop853.f``), with the coefficients used by
``scipy.integrate.DOP853``: 12 stages plus the FSAL stage f(t + h, y_new), an 8th-order
solution, the combined 5th/3rd-order error estimate, and a 7th-order dense output that needs
three extra stages.

Stage storage: ``K`` has shape (N_K, n) = (16, n) —

* K[0 … 11]  the stages (K[0] = f(t, y) on entry),
* K[12]      f(t + h, y_new) (FSAL: it is K[0] of the next step),
* K[13 … 15] the extra stages of the dense output (only when dense output is wanted).

One step (``f(t, y, out)`` stands for the caller's right-hand side)::

    for stage in range(1, dop853.N_STAGES):
        dop853.stage_input(y, K, h, stage, work)
        f(t + dop853.C[stage] * h, work, K[stage])
    dop853.advance(y, K, h, y_new)
    f(t + h, y_new, K[dop853.FSAL])
    err = dop853.error_norm(y, y_new, K, h, rtol, atol, n)
    # accepted and dense output wanted:
    for j in range(dop853.N_EXTRA):
        dop853.extra_stage_input(y, K, h, j, work)
        f(t + dop853.C_EXTRA[j] * h, work, K[dop853.FSAL + 1 + j])
    dop853.prepare_dense(y, y_new, K, h, F)      # F: (INTERPOLATOR_POWER, n)
    dop853.dense(y, F, x, out)                   # state at t + x·h, 0 ≤ x ≤ 1
"""

from __future__ import annotations

import numpy as np
from numba import njit

ORDER = 8
# Step-size control: h_new = h · SAFETY · err^(−ERROR_EXPONENT), as scipy's
# −1/(error_estimator_order + 1) with error_estimator_order = 7.
ERROR_EXPONENT = 1 / 8
N_STAGES = 12
FSAL = N_STAGES  # row of K holding f(t + h, y_new)
N_EXTRA = 3  # extra stages of the dense output
N_K = N_STAGES + 1 + N_EXTRA  # rows of K
INTERPOLATOR_POWER = 7  # rows of the dense-output coefficient array F

# Nodes of the 12 stages.
C = np.array(
    [
        0.0,
        0.526001519587677318785587544488e-01,
        0.789002279381515978178381316732e-01,
        0.118350341907227396726757197510,
        0.281649658092772603273242802490,
        0.333333333333333333333333333333,
        0.25,
        0.307692307692307692307692307692,
        0.651282051282051282051282051282,
        0.6,
        0.857142857142857142857142857142,
        1.0,
    ]
)

# Stage coupling coefficients, A[s, k] for k < s (strictly lower triangular, sparse).
A = np.zeros((N_STAGES, N_STAGES))
A[1, [0]] = [5.26001519587677318785587544488e-2]
A[2, [0, 1]] = [1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2]
A[3, [0, 2]] = [2.95875854768068491816892993775e-2, 8.87627564304205475450678981324e-2]
A[4, [0, 2, 3]] = [
    2.41365134159266685502369798665e-1,
    -8.84549479328286085344864962717e-1,
    9.24834003261792003115737966543e-1,
]
A[5, [0, 3, 4]] = [
    3.7037037037037037037037037037e-2,
    1.70828608729473871279604482173e-1,
    1.25467687566822425016691814123e-1,
]
A[6, [0, 3, 4, 5]] = [
    3.7109375e-2,
    1.70252211019544039314978060272e-1,
    6.02165389804559606850219397283e-2,
    -1.7578125e-2,
]
A[7, [0, 3, 4, 5, 6]] = [
    3.70920001185047927108779319836e-2,
    1.70383925712239993810214054705e-1,
    1.07262030446373284651809199168e-1,
    -1.53194377486244017527936158236e-2,
    8.27378916381402288758473766002e-3,
]
A[8, [0, 3, 4, 5, 6, 7]] = [
    6.24110958716075717114429577812e-1,
    -3.36089262944694129406857109825,
    -8.68219346841726006818189891453e-1,
    2.75920996994467083049415600797e1,
    2.01540675504778934086186788979e1,
    -4.34898841810699588477366255144e1,
]
A[9, [0, 3, 4, 5, 6, 7, 8]] = [
    4.77662536438264365890433908527e-1,
    -2.48811461997166764192642586468,
    -5.90290826836842996371446475743e-1,
    2.12300514481811942347288949897e1,
    1.52792336328824235832596922938e1,
    -3.32882109689848629194453265587e1,
    -2.03312017085086261358222928593e-2,
]
A[10, [0, 3, 4, 5, 6, 7, 8, 9]] = [
    -9.3714243008598732571704021658e-1,
    5.18637242884406370830023853209,
    1.09143734899672957818500254654,
    -8.14978701074692612513997267357,
    -1.85200656599969598641566180701e1,
    2.27394870993505042818970056734e1,
    2.49360555267965238987089396762,
    -3.0467644718982195003823669022,
]
A[11, [0, 3, 4, 5, 6, 7, 8, 9, 10]] = [
    2.27331014751653820792359768449,
    -1.05344954667372501984066689879e1,
    -2.00087205822486249909675718444,
    -1.79589318631187989172765950534e1,
    2.79488845294199600508499808837e1,
    -2.85899827713502369474065508674,
    -8.87285693353062954433549289258,
    1.23605671757943030647266201528e1,
    6.43392746015763530355970484046e-1,
]

# Weights of the 8th-order solution (stages 1–4 have zero weight).
B = np.zeros(N_STAGES)
B[[0, 5, 6, 7, 8, 9, 10, 11]] = [
    5.42937341165687622380535766363e-2,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
]

# Error estimators over K[0 … 12] (the FSAL entry is zero in both): E3 = B − b̂ of the embedded
# 3rd-order weights b̂ (bhh1, bhh2, bhh3 of dop853.f), E5 the 5th-order error weights.
E3 = np.zeros(N_STAGES + 1)
E3[:N_STAGES] = B
E3[0] -= 0.244094488188976377952755905512
E3[8] -= 0.733846688281611857341361741547
E3[11] -= 0.220588235294117647058823529412e-1

E5 = np.zeros(N_STAGES + 1)
E5[[0, 5, 6, 7, 8, 9, 10, 11]] = [
    0.1312004499419488073250102996e-1,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
]

# Extra stages of the dense output: nodes, and couplings over K[0 … 15] (row j feeds K[13 + j]).
C_EXTRA = np.array([0.1, 0.2, 0.777777777777777777777777777778])
A_EXTRA = np.zeros((N_EXTRA, N_K))
A_EXTRA[0, [0, 6, 7, 8, 9, 10, 11, 12]] = [
    5.61675022830479523392909219681e-2,
    2.53500210216624811088794765333e-1,
    -2.46239037470802489917441475441e-1,
    -1.24191423263816360469010140626e-1,
    1.5329179827876569731206322685e-1,
    8.20105229563468988491666602057e-3,
    7.56789766054569976138603589584e-3,
    -8.298e-3,
]
A_EXTRA[1, [0, 5, 6, 7, 10, 11, 12, 13]] = [
    3.18346481635021405060768473261e-2,
    2.83009096723667755288322961402e-2,
    5.35419883074385676223797384372e-2,
    -5.49237485713909884646569340306e-2,
    -1.08347328697249322858509316994e-4,
    3.82571090835658412954920192323e-4,
    -3.40465008687404560802977114492e-4,
    1.41312443674632500278074618366e-1,
]
A_EXTRA[2, [0, 5, 6, 7, 8, 12, 13, 14]] = [
    -4.28896301583791923408573538692e-1,
    -4.69762141536116384314449447206,
    7.68342119606259904184240953878,
    4.06898981839711007970213554331,
    3.56727187455281109270669543021e-1,
    -1.39902416515901462129418009734e-3,
    2.9475147891527723389556272149,
    -9.15095847217987001081870187138,
]

# Coefficients of F[3 … 6] of the dense output over K[0 … 15] (F[0 … 2] come from y, y_new,
# K[0] and K[12] directly; see `prepare_dense`).
_D_COLUMNS = [0, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15]
D = np.zeros((INTERPOLATOR_POWER - 3, N_K))
D[0, _D_COLUMNS] = [
    -0.84289382761090128651353491142e1,
    0.56671495351937776962531783590,
    -0.30689499459498916912797304727e1,
    0.23846676565120698287728149680e1,
    0.21170345824450282767155149946e1,
    -0.87139158377797299206789907490,
    0.22404374302607882758541771650e1,
    0.63157877876946881815570249290,
    -0.88990336451333310820698117400e-1,
    0.18148505520854727256656404962e2,
    -0.91946323924783554000451984436e1,
    -0.44360363875948939664310572000e1,
]
D[1, _D_COLUMNS] = [
    0.10427508642579134603413151009e2,
    0.24228349177525818288430175319e3,
    0.16520045171727028198505394887e3,
    -0.37454675472269020279518312152e3,
    -0.22113666853125306036270938578e2,
    0.77334326684722638389603898808e1,
    -0.30674084731089398182061213626e2,
    -0.93321305264302278729567221706e1,
    0.15697238121770843886131091075e2,
    -0.31139403219565177677282850411e2,
    -0.93529243588444783865713862664e1,
    0.35816841486394083752465898540e2,
]
D[2, _D_COLUMNS] = [
    0.19985053242002433820987653617e2,
    -0.38703730874935176555105901742e3,
    -0.18917813819516756882830838328e3,
    0.52780815920542364900561016686e3,
    -0.11573902539959630126141871134e2,
    0.68812326946963000169666922661e1,
    -0.10006050966910838403183860980e1,
    0.77771377980534432092869265740,
    -0.27782057523535084065932004339e1,
    -0.60196695231264120758267380846e2,
    0.84320405506677161018159903784e2,
    0.11992291136182789328035130030e2,
]
D[3, _D_COLUMNS] = [
    -0.25693933462703749003312586129e2,
    -0.15418974869023643374053993627e3,
    -0.23152937917604549567536039109e3,
    0.35763911791061412378285349910e3,
    0.93405324183624310003907691704e2,
    -0.37458323136451633156875139351e2,
    0.10409964950896230045147246184e3,
    0.29840293426660503123344363579e2,
    -0.43533456590011143754432175058e2,
    0.96324553959188282948394950600e2,
    -0.39177261675615439165231486172e2,
    -0.14972683625798562581422125276e3,
]
del _D_COLUMNS

for _arr in (C, A, B, E3, E5, C_EXTRA, A_EXTRA, D):
    _arr.flags.writeable = False
del _arr


# The same couplings as (column, value) lists of their non-zeros, in increasing column order: the
# dense-output loops then skip the zeros and still sum in the order of a dense loop.
_EXTRA_NNZ = 8
EXTRA_COLS = np.array([np.flatnonzero(row) for row in A_EXTRA])
EXTRA_VALS = np.array([row[np.flatnonzero(row)] for row in A_EXTRA])
D_COLS = np.flatnonzero(np.any(D != 0.0, axis=0))
D_VALS = D[:, D_COLS].copy()
assert EXTRA_COLS.shape == (N_EXTRA, _EXTRA_NNZ)
for _arr in (EXTRA_COLS, EXTRA_VALS, D_COLS, D_VALS):
    _arr.flags.writeable = False
del _arr


# Each step operation is a loop over the components of one per-component kernel, so that the
# variants on part of the state (at the end of this module) do the same arithmetic in the same order.


@njit(cache=True, inline="always")
def _stage_input_at(y, K, h, stage, out, j):
    acc = 0.0
    for k in range(stage):
        a = A[stage, k]
        if a != 0.0:
            acc += a * K[k, j]
    out[j] = y[j] + h * acc


@njit(cache=True, inline="always")
def stage_input(y, K, h, stage, out):
    """State at which stage ``stage`` (1…11) is evaluated: y + h·Σ_{k<stage} A[stage, k]·K[k].

    The caller evaluates its right-hand side at (t + C[stage]·h, out) into K[stage]; after
    stage 11 it calls :func:`advance` and evaluates K[12] at (t + h, y_new).
    """
    for j in range(y.shape[0]):
        _stage_input_at(y, K, h, stage, out, j)


@njit(cache=True, inline="always")
def _advance_at(y, K, h, y_new, j):
    acc = 0.0
    for k in range(N_STAGES):
        b = B[k]
        if b != 0.0:
            acc += b * K[k, j]
    y_new[j] = y[j] + h * acc


@njit(cache=True, inline="always")
def advance(y, K, h, y_new):
    """8th-order solution y + h·Σ_k B[k]·K[k] (k = 0…11) into ``y_new``."""
    for j in range(y.shape[0]):
        _advance_at(y, K, h, y_new, j)


@njit(cache=True, inline="always")
def _error_terms_at(y, y_new, K, rtol, atol, j):
    """Component ``j``'s scaled 5th- and 3rd-order error estimates (e5, e3) of :func:`error_norm`."""
    e5 = 0.0
    e3 = 0.0
    for k in range(N_STAGES):
        e5 += E5[k] * K[k, j]
        e3 += E3[k] * K[k, j]
    scale = atol + rtol * max(abs(y[j]), abs(y_new[j]))
    return e5 / scale, e3 / scale


@njit(cache=True, inline="always")
def _combined_norm(s5, s3, h, n_controlled):
    if s5 == 0.0 and s3 == 0.0:
        return 0.0
    return abs(h) * s5 / np.sqrt((s5 + 0.01 * s3) * n_controlled)


@njit(cache=True, inline="always")
def error_norm(y, y_new, K, h, rtol, atol, n_controlled):
    """Hairer's combined error estimate, the RMS over the first ``n_controlled`` components.

    With e5 = Σ E5[k]·K[k]/scale and e3 = Σ E3[k]·K[k]/scale, scale = atol + rtol·max(|y|, |y_new|),
    the norm is |h|·‖e5‖² / sqrt((‖e5‖² + 0.01·‖e3‖²)·n_controlled) — scipy's
    ``DOP853._estimate_error_norm``. Uses K[0 … 11] only (E3 and E5 vanish on K[12]).
    """
    s5 = 0.0
    s3 = 0.0
    for j in range(n_controlled):
        e5, e3 = _error_terms_at(y, y_new, K, rtol, atol, j)
        s5 += e5 * e5
        s3 += e3 * e3
    return _combined_norm(s5, s3, h, n_controlled)


@njit(cache=True, inline="always")
def _extra_stage_input_at(y, K, h, j, out, i):
    acc = 0.0
    for q in range(_EXTRA_NNZ):
        acc += EXTRA_VALS[j, q] * K[EXTRA_COLS[j, q], i]
    out[i] = y[i] + h * acc


@njit(cache=True, _nrt=False)
def extra_stage_input(y, K, h, j, out):
    """State at which extra stage ``j`` (0…2) of the dense output is evaluated:
    y + h·Σ_k A_EXTRA[j, k]·K[k] over k < 13 + j.

    Needs K[0 … 12] (K[12] = f(t + h, y_new)) and the previous extra stages; the caller
    evaluates its right-hand side at (t + C_EXTRA[j]·h, out) into K[13 + j].
    """
    for i in range(y.shape[0]):
        _extra_stage_input_at(y, K, h, j, out, i)


@njit(cache=True, inline="always")
def _prepare_dense_at(y, y_new, K, h, F, j):
    dy = y_new[j] - y[j]
    f0 = K[0, j]
    F[0, j] = dy
    F[1, j] = h * f0 - dy
    F[2, j] = 2.0 * dy - h * (K[FSAL, j] + f0)
    for i in range(INTERPOLATOR_POWER - 3):
        acc = 0.0
        for q in range(D_COLS.shape[0]):
            acc += D_VALS[i, q] * K[D_COLS[q], j]
        F[3 + i, j] = h * acc


@njit(cache=True, _nrt=False)
def prepare_dense(y, y_new, K, h, F):
    """Coefficients F (INTERPOLATOR_POWER × n) of the 7th-order interpolant of the step.

    Needs all 16 rows of K (the three extra stages included). As scipy's
    ``DOP853._dense_output_impl``: F[0] = Δy, F[1] = h·f₀ − Δy, F[2] = 2Δy − h·(f₁ + f₀),
    F[3 + i] = h·Σ_k D[i, k]·K[k], with Δy = y_new − y, f₀ = K[0], f₁ = K[12].
    """
    for j in range(y.shape[0]):
        _prepare_dense_at(y, y_new, K, h, F, j)


@njit(cache=True, _nrt=False)
def dense(y, F, x, out):
    """Interpolated state at t + x·h, 0 ≤ x ≤ 1, into ``out`` (F from :func:`prepare_dense`).

    The interpolant alternates the factors x and 1 − x (scipy's ``Dop853DenseOutput``):
    y + x·(F0 + (1−x)·(F1 + x·(F2 + (1−x)·(F3 + x·(F4 + (1−x)·(F5 + x·F6)))))).
    """
    # Row by row across the components (not component by component through the rows): the
    # components' Horner chains are independent, so the processor overlaps them.
    xm = 1.0 - x
    m = F.shape[0]
    n = y.shape[0]
    for j in range(n):
        out[j] = F[m - 1, j] * x
    for i in range(1, m):
        factor = x if i % 2 == 0 else xm
        row = m - 1 - i
        for j in range(n):
            out[j] = (out[j] + F[row, j]) * factor
    for j in range(n):
        out[j] += y[j]


@njit(cache=True, inline="always")
def dense_component(y, F, x, j):
    """Component ``j`` of :func:`dense` alone (event functions often need one state variable)."""
    xm = 1.0 - x
    m = F.shape[0]
    acc = F[m - 1, j] * x
    for i in range(1, m):
        acc = (acc + F[m - 1 - i, j]) * (x if i % 2 == 0 else xm)
    return y[j] + acc


@njit(cache=True, inline="always")
def dense_sum(y, F, x, first, stride, count):
    """The sum of ``count`` components of :func:`dense`, ``first``, ``first + stride``, … (a block's
    absolute rotation is the sum of the rotations at the interfaces below it)."""
    acc = 0.0
    for i in range(count):
        acc += dense_component(y, F, x, first + i * stride)
    return acc


@njit(cache=True, _nrt=False)
def dense_sum_root(y, F, first, stride, count, f_lo, f_hi, x_hi, x_lo=0.0):
    """Fraction of the step in [x_lo, x_hi] where :func:`dense_sum` changes sign, given its values
    f_lo at x_lo and f_hi at x_hi of opposite signs: the Illinois method, to 1e-10 of the step.
    (Used for the turning points of a rotation, where the angle is insensitive to the position to
    first order.)"""
    lo, hi = x_lo, x_hi
    side = 0
    for _ in range(100):
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        fx = dense_sum(y, F, x, first, stride, count)
        if fx == 0.0:
            return x
        if (fx > 0.0) == (f_lo > 0.0):
            lo, f_lo = x, fx
            if side == 1:
                f_hi *= 0.5
            side = 1
        else:
            hi, f_hi = x, fx
            if side == -1:
                f_lo *= 0.5
            side = -1
        if hi - lo < 1e-10:
            break
    return 0.5 * (lo + hi)


# --- The same steps on part of the state -----------------------------------------------------
# A contact mode holds some coordinates still: their rows of K are zero at every stage (zero
# velocity, zero acceleration), so the sums above give y + 0.0 for them. The variants below
# take the components in a permutation ``act`` of the state whose first ``m`` entries are the
# moving ones; they do the arithmetic on those alone and write what the full sums give for the
# rest (y + 0.0, which turns a −0.0 into +0.0 as the sums do). Same results, bit for bit, when
# the rows of the others really are zero; the caller must make sure of that.


@njit(cache=True, inline="always")
def hold_still(y, out, act, m):
    """out = y + 0.0 on the components act[m:], those a mode holds still: what the full sums give
    them, their rows of K being zero."""
    for q in range(m, act.shape[0]):
        j = act[q]
        out[j] = y[j] + 0.0


@njit(cache=True, inline="always")
def interpolate_still(F, act, m):
    """Zero interpolant coefficients (columns of F) for the components act[m:], which a mode holds
    still: :func:`dense` then gives them y + 0.0, as it would from the full coefficients."""
    for q in range(m, act.shape[0]):
        j = act[q]
        for i in range(F.shape[0]):
            F[i, j] = 0.0


@njit(cache=True, inline="always")
def stage_input_on(y, K, h, stage, out, act, m):
    """:func:`stage_input` computed on the components act[:m] only (see above)."""
    if m == act.shape[0]:  # every component moves: no indirection
        stage_input(y, K, h, stage, out)
        return
    for q in range(m):
        _stage_input_at(y, K, h, stage, out, act[q])
    hold_still(y, out, act, m)


@njit(cache=True, inline="always")
def advance_on(y, K, h, y_new, act, m):
    """:func:`advance` computed on the components act[:m] only."""
    if m == act.shape[0]:  # every component moves: no indirection
        advance(y, K, h, y_new)
        return
    for q in range(m):
        _advance_at(y, K, h, y_new, act[q])
    hold_still(y, y_new, act, m)


@njit(cache=True, inline="always")
def error_norm_on(y, y_new, K, h, rtol, atol, n_controlled, act, m):
    """:func:`error_norm` summed over the components act[:m] (those below ``n_controlled``), in
    increasing order of index as there: the others add exact zeros. ``act[:m]`` must be sorted."""
    if m == act.shape[0]:  # every component moves: no indirection
        return error_norm(y, y_new, K, h, rtol, atol, n_controlled)
    s5 = 0.0
    s3 = 0.0
    for q in range(m):
        j = act[q]
        if j >= n_controlled:
            continue
        e5, e3 = _error_terms_at(y, y_new, K, rtol, atol, j)
        s5 += e5 * e5
        s3 += e3 * e3
    return _combined_norm(s5, s3, h, n_controlled)


@njit(cache=True, _nrt=False)
def extra_stage_input_on(y, K, h, j, out, act, m):
    """:func:`extra_stage_input` computed on the components act[:m] only."""
    if m == act.shape[0]:  # every component moves: no indirection
        extra_stage_input(y, K, h, j, out)
        return
    for q in range(m):
        _extra_stage_input_at(y, K, h, j, out, act[q])
    hold_still(y, out, act, m)


@njit(cache=True, _nrt=False)
def prepare_dense_on(y, y_new, K, h, F, act, m):
    """:func:`prepare_dense` computed on the components act[:m] only; the others get an
    interpolant of zeros (:func:`dense` then gives y + 0.0 for them, as it would from the full
    coefficients, whose first row is +0.0)."""
    if m == act.shape[0]:  # every component moves: no indirection
        prepare_dense(y, y_new, K, h, F)
        return
    for q in range(m):
        _prepare_dense_at(y, y_new, K, h, F, act[q])
    interpolate_still(F, act, m)


@njit(cache=True, _nrt=False)
def dense_on(y, F, x, out, act, m):
    """:func:`dense` computed on the components act[:m] only; the others get y + 0.0, which is
    what :func:`dense` gives them from the zero coefficients of :func:`prepare_dense_on`.

    Row by row across the moving components, as :func:`dense` and for the same reason."""
    if m == act.shape[0]:  # every component moves: no indirection
        dense(y, F, x, out)
        return
    xm = 1.0 - x
    rows = F.shape[0]
    for q in range(m):
        j = act[q]
        out[j] = F[rows - 1, j] * x
    for i in range(1, rows):
        factor = x if i % 2 == 0 else xm
        row = rows - 1 - i
        for q in range(m):
            j = act[q]
            out[j] = (out[j] + F[row, j]) * factor
    for q in range(m):
        j = act[q]
        out[j] += y[j]
    hold_still(y, out, act, m)
