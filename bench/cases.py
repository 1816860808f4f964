"""Benchmark cases shared by ``bench/run.py`` (no ``test_`` names: pytest does not collect them).

Each case is a (system, motion, duration) triple; the batch is a grid of harmonic motions on the
single block of case (a).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import rocking as rk
from rocking.io.records import read_record

#: The paper's statue (Table 1: B = 1 m, H = 4 m, r = 0.8, m2 = 1 kg) and pedestal (m1 = 1 kg,
#: μs = 0.4, μk = 0.3), excited by 30 cycles of 6.75 cos(2π·1.2 t) m/s².
STATUE = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
PEDESTAL = rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3))
PAPER_AMPLITUDE, PAPER_FREQUENCY, PAPER_CYCLES = 6.75, 1.2, 30

#: The ~30 s record of case (c), used at its own sample rate.
RECORD = "LomaPrieta1989_Corralitos_000"
RECORD_LENGTH = 30.0  # s


@dataclass(frozen=True)
class Case:
    key: str
    label: str
    system: rk.System
    motion: object
    duration: float | None = None

    @property
    def save_dt(self) -> float:
        """Output spacing for the accuracy runs: the record's step, else 0.01 s."""
        return float(getattr(self.motion, "dt", None) or 0.01)


def paper_motion(amplitude: float = PAPER_AMPLITUDE, frequency: float = PAPER_FREQUENCY) -> rk.Harmonic:
    return rk.Harmonic(amplitude=amplitude, frequency=frequency, cycles=PAPER_CYCLES)


def cases() -> list[Case]:
    record = read_record(RECORD).trimmed(RECORD_LENGTH)
    window = paper_motion().duration
    # (a)-(c) keep the fixed windows of issue 4 (the motion's length), so that their figures
    # compare across sessions; (d) runs as users do, on until rest after the motion.
    return [
        Case("a", "single block H=4 B=1 r=0.8, 30 cycles 6.75 cos(2π·1.2t)", rk.System(statue=STATUE),
             paper_motion(), window),
        Case("b", "statue on pedestal m1=m2=1, μs=0.4 μk=0.3, same motion",
             rk.System(statue=STATUE, pedestal=PEDESTAL), paper_motion(), window),
        Case("c", f"0.3×1.2 m block, {RECORD} first {RECORD_LENGTH:g} s (dt={record.dt:g} s)",
             rk.System(statue=rk.Statue(width=0.3, height=1.2, mass=1.0)), record, record.duration),
    ]


def batch_grid(n: int) -> list[tuple[float, float]]:
    """About ``n`` (amplitude m/s², frequency Hz) pairs on a regular grid for case (a):
    amplitudes 2–10 m/s² (the block's rocking threshold g·tanα is 2.45 m/s²) × 0.5–3 Hz."""
    n_a = max(1, int(round(np.sqrt(n * 0.8))))
    n_f = max(1, int(np.ceil(n / n_a)))
    amplitudes = np.linspace(2.0, 10.0, n_a)
    frequencies = np.linspace(0.5, 3.0, n_f)
    grid = [(float(a), float(f)) for a in amplitudes for f in frequencies]
    return grid[:n]
