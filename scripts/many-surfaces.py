#!/usr/bin/env python3
"""Hierarchical radiosity on many surfaces: time, links, leaves and peak memory as the number
of surfaces and the error change, with and without clustering.

Runs `strahl solve SCENE --solver hierarchical` on the built-in `blocks:N` (N cubes in a
closed room under a lamp) and `canopy:N` (N leaves under sky and sun) scenes and prints one
Markdown table row per run: the scene, the error, clustering on or off, seconds (the whole
process), links (of which cluster links), leaves, peak resident memory, and the exponent k
of links ~ N^k between successive sizes N of one scene at one setting (2 would be every pair
of surfaces linked).

Needs a release build of strahl (`cargo build --release`).

Usage: scripts/many-surfaces.py [--strahl target/release/strahl] [--threads 2]
           [--blocks 125,1000] [--canopy 300,1000,3000] [--errors 4e-4,1e-4,2.5e-5]
           [--pairwise-limit 300]
Runs without clustering are made only up to --pairwise-limit surfaces (objects), as they
grow with the square of the faces.
"""

import argparse
import json
import math
import os
import subprocess
import tempfile
import time


def run(strahl, scene, error, clustering, threads):
    """One solve; returns (seconds, report statistics of the last round)."""
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report.json")
        args = [strahl, "solve", scene, "--solver", "hierarchical", "--error", str(error),
                "--threads", str(threads), "--quiet", "--report", report]
        if not clustering:
            args.append("--no-clustering")
        start = time.perf_counter()
        subprocess.run(args, check=True)
        seconds = time.perf_counter() - start
        with open(report) as f:
            stats = json.load(f)["stats"]
    return seconds, stats["rounds"][-1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--strahl", default="target/release/strahl")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--blocks", default="125,1000")
    parser.add_argument("--canopy", default="300,1000,3000")
    parser.add_argument("--errors", default="4e-4,1e-4,2.5e-5")
    parser.add_argument("--pairwise-limit", type=int, default=300)
    args = parser.parse_args()
    errors = [float(e) for e in args.errors.split(",")]
    print("| scene | error | clustering | s | links (cluster) | leaves | peak MB | links ~ N^k |")
    print("|---|---|---|---|---|---|---|---|")
    for name, sizes in [("blocks", args.blocks), ("canopy", args.canopy)]:
        counts = [int(n) for n in sizes.split(",") if n]
        for error in errors:
            for clustering in [True, False]:
                previous = None
                for n in counts:
                    if not clustering and n > args.pairwise_limit:
                        continue
                    seconds, last = run(args.strahl, f"{name}:{n}", error, clustering,
                                        args.threads)
                    links, leaves = last["links"], last["leaves"]
                    exponent = ""
                    if previous:
                        k = math.log(links / previous[0]) / math.log(n / previous[1])
                        exponent = f"{k:.2f}"
                    previous = (links, n)
                    memory = last.get("peak_memory_bytes")
                    memory = f"{memory / 1e6:.0f}" if memory else "—"
                    print(f"| {name}:{n} | {error:g} | {'on' if clustering else 'off'} "
                          f"| {seconds:.2f} | {links:,} ({last['cluster_links']:,}) "
                          f"| {leaves:,} | {memory} | {exponent} |", flush=True)


if __name__ == "__main__":
    main()
