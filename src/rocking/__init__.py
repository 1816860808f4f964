"""rocking — rigid blocks and statues rocking, sliding and overturning on a shaking floor.

Examples
--------
>>> import rocking as rk
>>> statue = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
>>> pedestal = rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3))
>>> floor = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=30)
>>> alone = rk.simulate(rk.System(statue=statue), floor)
>>> on_pedestal = rk.simulate(rk.System(statue=statue, pedestal=pedestal), floor)
>>> alone.overturned, on_pedestal.overturned
(True, False)
"""

from .constants import STANDARD_GRAVITY as g
from .contact.friction import Friction
from .excitation.harmonic import Harmonic
from .excitation.pulses import CosinePulse, Ramp, RectanglePulse, RickerPulse, SinePulse
from .models.bodies import Pedestal, Statue, System
from .models.regimes import EventKind, Regime
from .results.response import Response
from .simulation import Options, SimulationError, simulate
from .runner import run, run_response

__all__ = [
    "g", "Friction", "Harmonic", "CosinePulse", "Ramp", "RectanglePulse", "RickerPulse", "SinePulse",
    "Pedestal", "Statue", "System", "EventKind", "Regime", "Response", "Options", "SimulationError", "simulate", "run", "run_response",
]
__version__ = "0.1.0"
