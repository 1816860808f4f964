"""Names of the regimes (the paper's motion patterns, Fig. 7) and of the events."""

from enum import IntEnum


class Regime(IntEnum):
    """Motion regime of the system at an instant.

    REST: nothing moves relative to the floor. ROCK: the statue rocks, the body under it is held
    (pattern a). SLIDE: the body on the floor slides, the statue does not rock (pattern b).
    SLIDE_ROCK: both (pattern c).
    """

    REST = 0
    ROCK = 1
    SLIDE = 2
    SLIDE_ROCK = 3

    @classmethod
    def of(cls, sig: int, s: int) -> "Regime":
        return cls((1 if s != 0 else 0) + (2 if sig != 0 else 0))


class EventKind(IntEnum):
    """What happened at an event instant (``Response.events``)."""

    IMPACT = 1  #: θ crossed 0: the statue changed pivot (impact law applied)
    SLIP = 2  #: the body on the floor started to slide (friction cone left)
    STOP = 3  #: the sliding velocity reached zero
    UPLIFT = 4  #: the statue started to rock
    EXCEED_ALPHA = 5  #: |θ| reached α for the first time (statically unstable)
    FALL = 6  #: |θ| reached π/2: overturned
    SETTLE = 7  #: an impact left too little velocity: the statue is back at rest
    BREAKPOINT = 8  #: the regime changed at a jump of the floor motion
