"""Batches of the light model on a Dask cluster of two worker processes, and through the
command line's --batch and merge: the merged report is the single process's, bit for bit
(but for the seconds)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

import strahl
import strahl.distributed

ROOT = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("STRAHL_BIN", ROOT / "target" / "release" / "strahl"))


def without_seconds(report: dict) -> dict:
    report = json.loads(json.dumps(report))
    report["stats"].pop("seconds")
    return report


def test_batches_on_two_dask_workers_give_the_single_process_report():
    distributed = pytest.importorskip("dask.distributed")
    single = strahl.load("canopy:300").solve("light-trace", photons=300_000, seed=11)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        merged = strahl.distributed.solve_light(
            client, "canopy:300", photons=300_000, batches=5, seed=11
        )
    assert without_seconds(merged.report) == without_seconds(single.report)
    assert (merged.absorbed_w == single.absorbed_w).all()


def test_a_scene_from_arrays_travels_to_the_workers():
    distributed = pytest.importorskip("dask.distributed")
    import numpy as np

    rng = np.random.default_rng(2)
    # 40 small leaves at random heights and tilts under a sun and a sky.
    centres = rng.uniform([0, 0, 0], [2, 1, 2], size=(40, 3))
    corners = np.array([[-0.1, 0, -0.1], [0.1, 0, -0.1], [0.1, 0, 0.1], [-0.1, 0, 0.1]])
    tilt = rng.uniform(-0.08, 0.08, size=(40, 4, 1)) * np.array([0, 1, 0])
    vertices = (centres[:, None, :] + corners[None] + tilt).reshape(-1, 3)
    triangles = np.array([[[4 * k, 4 * k + 2, 4 * k + 1], [4 * k, 4 * k + 3, 4 * k + 2]] for k in range(40)]).reshape(-1, 3)
    leaves = np.repeat(np.arange(40), 2)
    scene = strahl.from_arrays(
        vertices, triangles, leaves, [f"leaf{k}" for k in range(40)], 0.1,
        translucency=0.1, sun=([0.2, -1, 0.1], 500.0), sky=30.0,
    )
    single = scene.solve("light-trace", photons=100_000, seed=7, per_face=True, max_bounces=50)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        merged = strahl.distributed.solve_light(
            client, scene, photons=100_000, batches=4, seed=7, per_face=True, max_bounces=50
        )
    assert without_seconds(merged.report) == without_seconds(single.report)
    assert len(merged.names) == 80


def test_batches_merge_in_any_order_and_refuse_strangers():
    parts = [strahl.distributed.trace_batch("cornell", k, 3, photons=50_000, seed=3) for k in range(3)]
    single = strahl.load("cornell").solve("light-trace", photons=50_000, seed=3)
    merged = strahl.distributed.merge("cornell", parts[::-1])
    assert without_seconds(merged.report) == without_seconds(single.report)
    with pytest.raises(ValueError, match="batch 1/3 is missing"):
        strahl.distributed.merge("cornell", [parts[0], parts[2]])
    with pytest.raises(ValueError, match="another scene"):
        strahl.distributed.merge("canopy:10", parts)
    with pytest.raises(ValueError, match="another scene"):
        strahl.distributed.merge("cornell", parts, per_face=True)


def test_the_command_lines_batches_merge_into_its_single_report(tmp_path):
    if not CLI.exists():
        pytest.skip(f"no command line at {CLI}")
    common = ["solve", "canopy:300", "--photons", "200000", "--seed", "5", "-q"]
    subprocess.run([CLI, *common, "--report", tmp_path / "single.json"], check=True)
    parts = []
    for k in range(4):
        part = tmp_path / f"part{k}.json"
        subprocess.run([CLI, *common, "--batch", f"{k}/4", "--partial", part], check=True)
        parts.append(part)
    subprocess.run([CLI, "merge", *parts[::-1], "-q", "--report", tmp_path / "merged.json"], check=True)
    single = json.loads((tmp_path / "single.json").read_text())
    merged = json.loads((tmp_path / "merged.json").read_text())
    assert without_seconds(merged) == without_seconds(single)
    # A batch left out, or one of another seed: refused with the reason.
    refused = subprocess.run([CLI, "merge", *parts[:3]], capture_output=True, text=True)
    assert refused.returncode != 0 and "batch 3/4 is missing" in refused.stderr
    other = tmp_path / "other.json"
    subprocess.run(
        [CLI, "solve", "canopy:300", "--photons", "200000", "--seed", "6", "-q", "--batch", "3/4", "--partial", other],
        check=True,
    )
    refused = subprocess.run([CLI, "merge", *parts[:3], other], capture_output=True, text=True)
    assert refused.returncode != 0 and "other settings" in refused.stderr


def test_a_render_in_batches_on_dask_is_the_single_render():
    distributed = pytest.importorskip("dask.distributed")
    import numpy as np

    settings = dict(width=40, height=30, samples_per_pixel=12, seed=5, depth=6)
    single = strahl.load("cornell").render("pathtrace", **settings)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        merged = strahl.distributed.render(client, "cornell", batches=5, **settings)
    assert merged.dtype == np.float32 and merged.shape == (30, 40, 3)
    assert np.array_equal(merged, single)
    # Batches merge in any order; a missing one or one of another seed is refused.
    parts = [strahl.distributed.render_batch("cornell", k, 3, **settings) for k in range(3)]
    assert np.array_equal(strahl.distributed.merge_render("cornell", parts[::-1]), single)
    with pytest.raises(ValueError, match="batch 1/3 is missing"):
        strahl.distributed.merge_render("cornell", [parts[0], parts[2]])
    other = strahl.distributed.render_batch("cornell", 1, 3, **dict(settings, seed=6))
    with pytest.raises(ValueError, match="other settings"):
        strahl.distributed.merge_render("cornell", [parts[0], other, parts[2]])
