"""Batch runs: the same summaries in-process and on local processes, labelled sweeps."""

import math

import numpy as np
import pytest
import xarray as xr

import rocking as rk
from rocking.analyses.batch import replace_at, run_cases, sweep

STATUE = rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)
MOTION = rk.Harmonic(amplitude=6.75, frequency=1.2, cycles=6)


def test_sweep_matches_individual_runs_and_is_labelled():
    amplitudes, heights = [2.0, 5.0, 9.0], [3.0, 4.0]
    ds = sweep(rk.System(statue=STATUE), MOTION, {"motion.amplitude": amplitudes, "statue.height": heights}, workers=1)
    assert ds.overturned.dims == ("motion.amplitude", "statue.height")
    for i, a in enumerate(amplitudes):
        for j, h in enumerate(heights):
            st = rk.Statue(width=1.0, height=h, mass=1.0, restitution=0.8)
            single = rk.simulate(rk.System(statue=st), rk.Harmonic(amplitude=a, frequency=1.2, cycles=6)).summary()
            assert bool(ds.overturned[i, j]) == single["overturned"]
            assert float(ds.peak_rotation[i, j]) == single["peak_rotation"]
            assert int(ds.impacts[i, j]) == single["impacts"]


def test_processes_give_identical_results():
    ped = rk.Pedestal(mass=1.0, friction=rk.Friction(static=0.4, kinetic=0.3))
    cases = [(rk.System(statue=STATUE, pedestal=ped), rk.Harmonic(amplitude=a, frequency=f, cycles=4))
             for a in np.linspace(3, 9, 6) for f in (0.8, 1.2, 2.0)]
    serial = run_cases(cases, workers=1)
    parallel = run_cases(cases, workers=2, chunk_size=3)
    xr.testing.assert_identical(serial, parallel)


def test_replace_at_names_unknown_axes():
    sysm = rk.System(statue=STATUE)
    assert replace_at(sysm, "statue.mass", 3.0).statue.mass == 3.0
    with pytest.raises(ValueError, match="statue.colour"):
        replace_at(sysm, "statue.colour", 1.0)


def test_summary_memory_is_small():
    ds = run_cases([(rk.System(statue=STATUE), MOTION)] * 20, workers=1)
    per_run = sum(v.values.nbytes for v in ds.data_vars.values()) / 20
    # 100 000 runs must stay well below 500 MB.
    assert per_run * 100_000 < 100e6


def test_series_on_request_match_single_runs():
    cases = [(rk.System(statue=STATUE), rk.Harmonic(amplitude=a, frequency=1.2, cycles=6)) for a in (2.0, 6.75, 10.0)]
    ds = run_cases(cases, workers=1, series=True)
    assert ds.theta.dims == ("case", "time") and ds.time.attrs["units"] == "s"
    assert float(ds.time[1]) == pytest.approx(0.01, abs=1e-15)
    # Summaries are those of the runs without series.
    plain = run_cases(cases, workers=1)
    xr.testing.assert_identical(plain, ds[list(plain.data_vars)])
    for i, (system, motion) in enumerate(cases):
        r = rk.simulate(system, motion)
        on_grid = np.isclose(r.t / 0.01, np.rint(r.t / 0.01), rtol=0, atol=1e-9)
        t, first = np.unique(np.rint(r.t[on_grid] / 0.01), return_index=True)
        theta = r.theta[on_grid][first]
        n = theta.size
        np.testing.assert_array_equal(ds.theta[i, :n].values, theta)
        np.testing.assert_array_equal(ds.u[i, :n].values, r.u[on_grid][first])
        # After the run ended (overturned) the histories are NaN.
        assert np.all(np.isnan(ds.theta[i, n:].values))
    assert bool(ds.overturned[2]) and np.isnan(ds.theta[2, -1])


def test_sweep_series_keep_the_time_axis():
    ds = sweep(rk.System(statue=STATUE), MOTION, {"motion.amplitude": [2.0, 9.0], "statue.height": [3.0, 4.0]},
               workers=1, series=True)
    assert ds.theta.dims == ("motion.amplitude", "statue.height", "time")
    assert ds.overturned.dims == ("motion.amplitude", "statue.height")
    # The axis runs to the end of the longest run: the motion, then free motion until at rest.
    longest = float(ds.end_time.max())
    assert longest > MOTION.duration
    assert ds.theta.sizes["time"] == int(math.floor(longest / 0.01 + 1e-9)) + 1
