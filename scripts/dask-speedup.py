"""Two Dask worker processes against one on the light model (docs/PERFORMANCE.md, "The
Python package"): `canopy:3000`, 10⁷ photons in 8 batches, one thread a batch, after a
warm-up, runs alternating; checks that every merged report equals the single process's but
for the seconds. Run with the package installed (scripts/test builds it into
target/python-venv):

    target/python-venv/bin/python scripts/dask-speedup.py [RUNS]
"""

import json
import statistics
import sys
import time

from dask.distributed import Client, LocalCluster

import strahl
import strahl.distributed

SCENE, PHOTONS, BATCHES = "canopy:3000", 10**7, 8


def without_seconds(report):
    report = json.loads(json.dumps(report))
    report["stats"].pop("seconds")
    return report


def main(runs):
    single = without_seconds(strahl.load(SCENE).solve("light-trace", photons=PHOTONS, threads=1).report)
    clusters = {w: LocalCluster(n_workers=w, threads_per_worker=1, processes=True, dashboard_address=None) for w in (1, 2)}
    clients = {w: Client(c) for w, c in clusters.items()}
    times = {1: [], 2: []}
    try:
        for run in range(runs + 1):
            for workers, client in clients.items():
                start = time.perf_counter()
                merged = strahl.distributed.solve_light(client, SCENE, photons=PHOTONS, batches=BATCHES)
                seconds = time.perf_counter() - start
                assert without_seconds(merged.report) == single, "merged report differs"
                if run > 0:  # the first run of each is the warm-up
                    times[workers].append(seconds)
    finally:
        for c in clients.values():
            c.close()
        for c in clusters.values():
            c.close()
    one, two = statistics.median(times[1]), statistics.median(times[2])
    print("one worker:", " / ".join(f"{t:.2f}" for t in times[1]), "s")
    print("two workers:", " / ".join(f"{t:.2f}" for t in times[2]), "s")
    print(f"speed-up on medians: {one / two:.2f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
