"""Pack a :class:`System` and the model options into the flat float64 vector the compiled
kernels read. Index names are module constants so the kernels stay readable."""

from __future__ import annotations

import math

import numpy as np

from .bodies import System

B, H, R, ALPHA, M2, I_O, M1, M, MU_S, MU_K, G, ETA = range(12)
NORMAL_PAPER, IMPACT_COULOMB, CAN_SLIDE, REST_VEL, MU_TOP, PED_HALF_WIDTH, PED_HEIGHT = range(12, 19)
N_PARAMS = 19


def pack(system: System, *, gravity: float, normal_force: str, impact: str, rest_velocity: float) -> tuple:
    """Return the parameter vector (see the index constants above) for the kernels, as a tuple
    of floats: compiled code passes tuples by value, without reference counting."""
    st = system.statue
    p = np.zeros(N_PARAMS)
    p[B], p[H] = st.b, st.h
    p[R], p[ALPHA] = st.semi_diagonal, st.slenderness
    p[M2], p[I_O] = st.mass, st.inertia_about_corner
    m1 = system.pedestal.mass if system.pedestal is not None else 0.0
    p[M1], p[M] = m1, m1 + st.mass
    friction = system.floor_friction
    p[CAN_SLIDE] = 0.0 if friction is None else 1.0
    p[MU_S] = math.inf if friction is None else friction.mu_s
    p[MU_K] = math.inf if friction is None else friction.mu_k
    p[G] = gravity
    p[ETA] = st.effective_restitution
    p[NORMAL_PAPER] = {"full": 0.0, "paper": 1.0}[normal_force]
    p[IMPACT_COULOMB] = {"paper": 0.0, "coulomb": 1.0}[impact]
    p[REST_VEL] = rest_velocity
    top = system.top_friction
    p[MU_TOP] = -1.0 if top is None else top.mu_s
    ped = system.pedestal
    p[PED_HALF_WIDTH] = 0.5 * ped.width if ped is not None and ped.width is not None else -1.0
    p[PED_HEIGHT] = ped.height if ped is not None and ped.height is not None else -1.0
    return tuple(float(v) for v in p)
