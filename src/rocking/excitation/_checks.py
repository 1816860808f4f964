"""Validation helpers shared by the motion classes: errors name the field and the value."""

import math


def positive(name: str, value) -> None:
    if value is None or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")


def finite(name: str, value) -> None:
    if value is None or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
