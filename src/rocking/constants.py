"""Physical constants and numerical defaults (SI units)."""

#: Standard gravity, m/s² (the default; the paper and the oracles use 9.81).
STANDARD_GRAVITY = 9.80665
