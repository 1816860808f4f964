"""Solvers of the hybrid (regime-switching) equations: compiled event-driven, scipy reference."""
