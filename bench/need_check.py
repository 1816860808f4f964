"""On-demand check: the friction a rocking block's base needs, by both engines, against the
largest of its own saved forces and its impacts' impulse ratios (docs/theory/stack.md §9).

    .venv/bin/python bench/need_check.py            # seed 0, 200 random blocks (about 5 minutes)
    .venv/bin/python bench/need_check.py --seed 1 --runs 50

Random blocks (0.1–0.5 m wide, 0.6–2 m tall) rock under two cycles of a sine or cosine of 1.1–3
times their uplift acceleration, on a floor face of μs = 5 (they never slide), with Housner's
restitution or a chosen one (0.6–0.95). Runs that slide or pass α are left out. For each, the
reference is the largest |P_x|/P_y of the two-body solver's saved forces every 10 µs while
|θ| ≤ α (a lower bound: it reads the peak low by its curvature over 5 µs) and the impulse ratio
of each of its impacts. Printed: how many runs, in how many an impact needs the most, and each
engine's need minus that reference (lowest and highest; a negative value beyond rounding is a
peak the engine missed). Not collected by pytest.
"""

from __future__ import annotations

import argparse

import numpy as np

import rocking as rk
from rocking.stack import Block, Interface, Stack, simulate_stack

G = 9.80665


def blocks(seed: int, runs: int):
    rng = np.random.default_rng(seed)
    for i in range(runs):
        width, height, mass = rng.uniform(0.1, 0.5), rng.uniform(0.6, 2.0), rng.uniform(20, 200)
        amplitude, frequency = rng.uniform(1.1, 3.0) * G * width / height, rng.uniform(0.8, 4.0)
        form = "sin" if rng.random() < 0.5 else "cos"
        restitution = rng.uniform(0.6, 0.95) if rng.random() < 0.5 else None
        yield i, width, height, mass, rk.Harmonic(amplitude=amplitude, frequency=frequency, cycles=2.0, form=form), \
            restitution


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--runs", type=int, default=200)
    args = ap.parse_args()
    friction = rk.Friction(static=5.0, kinetic=5.0)
    rows = []
    for i, width, height, mass, motion, restitution in blocks(args.seed, args.runs):
        statue = rk.Statue(width=width, height=height, mass=mass, friction=friction, restitution=restitution)
        two = rk.simulate(rk.System(statue=statue), motion, duration=4.0, options={"save_dt": 1e-5})
        if np.any(two.u_dot != 0.0) or two.exceeded_alpha_time is not None:
            continue
        forces = two.contact_forces()
        saved = float(np.nanmax(np.where(np.abs(two.theta) <= two.alpha, np.abs(forces["Px"]) / forces["Py"], -1.0)))
        impacts = max([imp.friction_needed for imp in two.impacts], default=0.0)
        reference = max(saved, impacts)
        stack = Stack(blocks=(Block(width=width, height=height, mass=mass),),
                      interfaces=(Interface(friction=friction, restitution=restitution),))
        ours = simulate_stack(stack, motion, duration=4.0).interfaces[0]["required_friction"]
        rows.append((i, two.summary()["required_top_friction"] - reference, ours - reference, impacts >= saved))
    d = np.array([r[1] for r in rows])
    e = np.array([r[2] for r in rows])
    print(f"seed {args.seed}: {len(rows)} of {args.runs} runs neither slide nor pass alpha; "
          f"an impact needs the most in {sum(r[3] for r in rows)}")
    for name, v in (("two-body required_top_friction", d), ("stack engine required_friction", e)):
        worst = rows[int(np.argmin(v))][0], rows[int(np.argmax(v))][0]
        print(f"{name} - reference: lowest {v.min():.3g} (run {worst[0]}), highest {v.max():.3g} (run {worst[1]}); "
              f"beyond 1e-9 in {int(np.sum(np.abs(v) > 1e-9))}")


if __name__ == "__main__":
    main()
