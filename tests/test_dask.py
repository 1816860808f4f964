"""The same study on a dask.distributed LocalCluster and on local processes gives identical
results; DaskExecutor keeps the order of ``map`` and fits ``batch.map_chunks``."""

import numpy as np
import pytest
import xarray as xr

import rocking as rk
from rocking.analyses.batch import run_cases
from rocking.analyses.design import friction_design, motion_family
from rocking.analyses.executors import DaskExecutor, as_executor
from rocking.analyses.spectra import overturning_spectrum

# a declared test dependency (the `test` extra pulls in `rocking[dask]`): missing, the suite fails
import distributed  # noqa: E402

G = 9.81
OPTS = rk.Options(gravity=G)
STATUE = rk.Statue(width=0.4, height=1.6, mass=200.0, friction=rk.Friction(static=0.6))
SYSTEM = rk.System(statue=STATUE, pedestal=rk.Pedestal(mass=300.0, friction=rk.Friction(static=0.3, kinetic=0.24)))


def _negate(x):
    return -x


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_dask_executor_map_is_ordered_and_as_completed_is_complete(client):
    ex = DaskExecutor(client)
    assert ex.workers == 2
    assert list(ex.map(_negate, range(10))) == [-i for i in range(10)]
    got = dict(ex.as_completed(_negate, range(10)))
    assert got == {i: -i for i in range(10)}
    assert isinstance(as_executor(client), DaskExecutor)  # a bare Client is accepted as `workers`


def test_batch_run_cases_on_dask_equals_local_processes(client):
    cases = [(rk.System(statue=rk.Statue(width=1.0, height=4.0, mass=1.0, restitution=0.8)),
              rk.Harmonic(amplitude=a, frequency=f, cycles=4)) for a in (3.0, 6.0, 9.0) for f in (0.8, 1.6)]
    local = run_cases(cases, options=OPTS, workers=2, chunk_size=2)
    on_dask = run_cases(cases, options=OPTS, workers=DaskExecutor(client), chunk_size=2)
    xr.testing.assert_identical(local, on_dask)


def test_design_study_on_dask_equals_local_processes(client, tmp_path):
    motions = motion_family("harmonic", [3.5, 6.0], [0.8, 1.6], cycles=3)
    kw = dict(mu_s=[0.1, 0.25, 0.3, 0.45], pedestal_mass=[150.0, 600.0], sliding_limit=0.25, free_time=3.0,
              options=OPTS)
    local = friction_design(SYSTEM, motions, workers=2, folder=tmp_path / "local", **kw)
    on_dask = friction_design(SYSTEM, motions, workers=DaskExecutor(client), folder=tmp_path / "dask", **kw)
    xr.testing.assert_identical(local, on_dask)
    # the chunk files are interchangeable: a study begun on processes resumes on Dask
    saved = sorted((tmp_path / "local").glob("chunk-*.npz"))
    for p in saved[::2]:
        p.unlink()
    resumed = friction_design(SYSTEM, motions, workers=DaskExecutor(client), folder=tmp_path / "local", **kw)
    xr.testing.assert_identical(local, resumed)


def test_spectrum_on_dask_equals_local_processes(client):
    kw = dict(frequency_ratios=[1.0, 2.0, 3.0], amplitude_range=(1.01, 10.0), n_scan=20, options=OPTS, chunk_size=1)
    system = rk.System(statue=rk.Statue(width=0.4, height=2.0, mass=1.0))
    local = overturning_spectrum(system, ["sine", "cosine"], workers=2, **kw)
    on_dask = overturning_spectrum(system, ["sine", "cosine"], workers=client, **kw)
    xr.testing.assert_identical(local, on_dask)
    assert np.isfinite(local.amplitude_ratio.values).all()


def test_two_face_design_of_a_stack_on_dask_equals_local_processes(client, tmp_path):
    from rocking.stack import Block, Interface, Stack

    stack = Stack(blocks=(Block(name="pedestal", width=1.2, height=0.4, mass=300.0),
                          Block(name="statue", width=0.4, height=1.6, mass=200.0)),
                  interfaces=(Interface(friction=rk.Friction(static=0.3, kinetic=0.24)),
                              Interface(friction=rk.Friction(static=0.5, kinetic=0.4))))
    motions = motion_family("harmonic", [4.0], [0.8, 1.6], cycles=3)
    kw = dict(mu_s=[0.2, 0.45], mu_s_top=[0.15, 0.6], free_time=3.0, options=OPTS, chunk_size=3)
    local = friction_design(stack, motions, workers=2, folder=tmp_path / "local", **kw)
    on_dask = friction_design(stack, motions, workers=DaskExecutor(client), **kw)
    xr.testing.assert_identical(local, on_dask)
    assert local.attrs["engine"] == "stack" and local.block.values.tolist() == ["pedestal", "statue"]
