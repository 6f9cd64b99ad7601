"""The light model on a Dask cluster: a run's photons split into batches that run on the
cluster's workers and merge into the report one process gives with the same seed, bit for
bit (the light model tallies power in integers, so the sums do not depend on the split).

    from dask.distributed import Client, LocalCluster
    import strahl.distributed

    with Client(LocalCluster(n_workers=2, threads_per_worker=1)) as client:
        result = strahl.distributed.solve_light(client, "canopy:3000", photons=10**8, batches=16)

The same on Slurm (PBS, HTCondor alike) through dask-jobqueue:

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(cores=16, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=8)
    with Client(cluster) as client:
        result = strahl.distributed.solve_light(client, "field.toml", photons=10**10, batches=64)

Each worker opens the scene itself, by built-in name or file path (the file must be where
the workers can read it), so scenes built from arrays do not travel yet.
"""

from __future__ import annotations

from . import Result, _result, _strahl

__all__ = ["solve_light", "trace_batch", "merge"]


def trace_batch(scene: str, photons: int, seed: int, index: int, count: int, threads: int = 0) -> str:
    """Batch ``index`` of ``count`` of the light model's run of ``photons`` photons on
    ``scene`` (a built-in name or a file path), as JSON for :func:`merge`. Runs anywhere:
    a Dask task, a job of an array, another process."""
    return _strahl.light_trace_batch(scene, photons, seed, index, count, threads)


def merge(scene: str, partials: list) -> Result:
    """The result of the whole run from every batch's JSON (each once, any order)."""
    return _result(_strahl.merge_batches(scene, list(partials)))


def solve_light(client, scene: str, photons: int, batches: int, seed: int = 0, threads: int = 1) -> Result:
    """The light model's run of ``photons`` photons on ``scene`` split into ``batches``
    tasks on the Dask ``client``'s cluster (``threads`` threads each), merged here."""
    futures = [
        client.submit(trace_batch, scene, photons, seed, k, batches, threads, pure=False)
        for k in range(batches)
    ]
    return merge(scene, client.gather(futures))
