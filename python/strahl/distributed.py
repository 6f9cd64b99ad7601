"""strahl on a Dask cluster: a run split into batches that run on the cluster's workers and
merge into what one process gives with the same seed, bit for bit — the light model's photons
(it tallies power in integers, so the sums do not depend on the split) and the path tracer's
samples per pixel (each pixel's samples summed in fixed point).

    from dask.distributed import Client, LocalCluster
    import strahl.distributed

    with Client(LocalCluster(n_workers=2, threads_per_worker=1)) as client:
        result = strahl.distributed.solve_light(client, "canopy:3000", photons=10**8, batches=16)
        image = strahl.distributed.render(client, "cornell", batches=8, samples_per_pixel=1024)

The same on Slurm (PBS, HTCondor alike) through dask-jobqueue:

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(cores=16, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=8)
    with Client(cluster) as client:
        result = strahl.distributed.solve_light(client, "field.toml", photons=10**10, batches=64)

A scene is named (a built-in name, or a file path the workers can read) or a
:class:`strahl.Scene` — one built by :func:`strahl.from_arrays` travels as its arrays, sent to
every worker once; each worker compiles a scene once for all its tasks.
"""

from __future__ import annotations

from typing import Optional, Union

import numpy as np

from . import Result, Scene, _image, _named, _rebuilt, _result

__all__ = ["solve_light", "trace_batch", "merge", "render", "render_batch", "merge_render"]

SceneLike = Union[str, Scene]


def _open(scene: SceneLike) -> Scene:
    """`scene` compiled in this process (once per process for a name)."""
    return scene if isinstance(scene, Scene) else _rebuilt(("load", scene), "load:" + scene)


def trace_batch(
    scene: SceneLike,
    index: int,
    count: int,
    *,
    seed: int = 0,
    threads: int = 0,
    per_face: bool = False,
    diffuse_only: bool = False,
    **settings,
) -> str:
    """Batch ``index`` of ``count`` of the light model's run on ``scene`` with ``settings``
    (``photons=…``, ``max_bounces=…``, as :meth:`strahl.Scene.solve` takes them), as JSON for
    :func:`merge`. Runs anywhere: a Dask task, a job of an array, another process."""
    return _open(scene)._scene.batch(
        "light-trace",
        index,
        count,
        seed=seed,
        threads=threads,
        settings=_named(settings),
        per_face=per_face,
        diffuse_only=diffuse_only,
    )


def merge(scene: SceneLike, partials: list, *, per_face: bool = False, diffuse_only: bool = False) -> Result:
    """The result of the whole run from every batch's JSON (each once, any order); refuses
    batches of another scene, settings, seed or split."""
    merged = _open(scene)._scene.merge_light(list(partials), per_face=per_face, diffuse_only=diffuse_only)
    return _result(merged)


def solve_light(
    client,
    scene: SceneLike,
    photons: int,
    batches: int,
    *,
    seed: int = 0,
    threads: int = 1,
    per_face: bool = False,
    diffuse_only: bool = False,
    **settings,
) -> Result:
    """The light model's run of ``photons`` photons on ``scene`` split into ``batches`` tasks
    on the Dask ``client``'s cluster (``threads`` threads each), merged here: the result
    :meth:`strahl.Scene.solve` gives with the same seed and settings."""
    sent = client.scatter(scene, broadcast=True) if isinstance(scene, Scene) else scene
    options = dict(seed=seed, threads=threads, per_face=per_face, diffuse_only=diffuse_only)
    futures = [
        client.submit(trace_batch, sent, k, batches, photons=photons, **options, **settings, pure=False)
        for k in range(batches)
    ]
    return merge(scene, client.gather(futures), per_face=per_face, diffuse_only=diffuse_only)


def render_batch(
    scene: SceneLike,
    index: int,
    count: int,
    *,
    width: Optional[int] = None,
    height: Optional[int] = None,
    samples_per_pixel: Optional[int] = None,
    seed: int = 0,
    threads: int = 0,
    **settings,
) -> str:
    """Batch ``index`` of ``count`` of the path tracer's render of ``scene`` (samples
    ``index·spp/count ..`` of every pixel) with the settings :meth:`strahl.Scene.render` takes,
    as JSON for :func:`merge_render`."""
    named = dict(width=width, height=height, spp=samples_per_pixel, **settings)
    return _open(scene)._scene.batch("pathtrace", index, count, seed=seed, threads=threads, settings=_named(named))


def merge_render(scene: SceneLike, partials: list) -> np.ndarray:
    """The image of the whole render from every batch's JSON (each once, any order): the
    array :meth:`strahl.Scene.render` gives with the same settings, bit for bit."""
    return _image(*_open(scene)._scene.merge_render(list(partials)))


def render(
    client,
    scene: SceneLike,
    batches: int,
    *,
    width: Optional[int] = None,
    height: Optional[int] = None,
    samples_per_pixel: Optional[int] = None,
    seed: int = 0,
    threads: int = 1,
    **settings,
) -> np.ndarray:
    """The path tracer's render of ``scene`` split into ``batches`` tasks on the Dask
    ``client``'s cluster (``threads`` threads each), merged here: the linear radiance,
    W/(sr·m²), as a float32 array of shape (height, width, 3), equal to what
    :meth:`strahl.Scene.render` gives with the same seed and settings."""
    sent = client.scatter(scene, broadcast=True) if isinstance(scene, Scene) else scene
    options = dict(width=width, height=height, samples_per_pixel=samples_per_pixel, seed=seed, threads=threads)
    futures = [
        client.submit(render_batch, sent, k, batches, **options, **settings, pure=False)
        for k in range(batches)
    ]
    return merge_render(scene, client.gather(futures))
