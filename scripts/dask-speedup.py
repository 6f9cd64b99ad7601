"""Two Dask worker processes against one on the light model (docs/PERFORMANCE.md, "The
Python package"): `canopy:3000`, 10⁷ photons (or PHOTONS) in 8 batches, one thread a batch, after a
warm-up, runs alternating; checks that every merged report equals the single process's but
for the seconds. Alternating with them, the same run in this process on one thread and on
two: what the machine's two cores give without Dask, the ceiling of the workers' ratio. Run
with the package installed (scripts/test builds it into target/python-venv):

    target/python-venv/bin/python scripts/dask-speedup.py [RUNS [BATCHES [PHOTONS]]]
"""

import json
import statistics
import sys
import time

from dask.distributed import Client, LocalCluster

import strahl
import strahl.distributed

SCENE = "canopy:3000"
BATCHES = int(sys.argv[2]) if len(sys.argv) > 2 else 8
PHOTONS = int(float(sys.argv[3])) if len(sys.argv) > 3 else 10**7


def without_seconds(report):
    report = json.loads(json.dumps(report))
    report["stats"].pop("seconds")
    return report


def main(runs):
    single = without_seconds(strahl.load(SCENE).solve("light-trace", photons=PHOTONS, threads=1).report)
    clusters = {w: LocalCluster(n_workers=w, threads_per_worker=1, processes=True, dashboard_address=None) for w in (1, 2)}
    clients = {w: Client(c) for w, c in clusters.items()}
    times = {1: [], 2: []}
    threaded = {1: [], 2: []}
    scene = strahl.load(SCENE)
    try:
        for run in range(runs + 1):
            for threads in (1, 2):
                start = time.perf_counter()
                scene.solve("light-trace", photons=PHOTONS, threads=threads)
                if run > 0:
                    threaded[threads].append(time.perf_counter() - start)
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
    one, two = statistics.median(threaded[1]), statistics.median(threaded[2])
    print("in this process, one thread:", " / ".join(f"{t:.2f}" for t in threaded[1]), "s")
    print("in this process, two threads:", " / ".join(f"{t:.2f}" for t in threaded[2]), "s")
    print(f"speed-up on medians: {one / two:.2f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
