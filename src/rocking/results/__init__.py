"""Simulation results."""
