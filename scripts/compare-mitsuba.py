#!/usr/bin/env python3
"""Side-by-side path tracing time and noise: strahl against Mitsuba 3.

Each renderer draws its own Cornell box at 256x256, 64 samples per pixel, path length
unbounded with Russian roulette from bounce 5, on all cores. Timings are of the whole
process (start-up, scene build, render, image write), several runs, median reported.
Noise is the RMS difference of luminance to a high-sample reference of the same renderer,
relative to the reference's mean luminance (each renderer's own Cornell box). Since variance
falls as 1/samples, time × noise² compares the cost of reaching equal noise; the script prints
the seconds each renderer would need for a relative RMS noise of 0.05.

Needs: `pip install mitsuba` (and for `llvm_ad_rgb` Debian's libllvm19, found through
DRJIT_LIBLLVM_PATH), a release build of strahl (`cargo build --release`), numpy.

Usage: scripts/compare-mitsuba.py [--runs 5] [--strahl target/release/strahl]
           [--strahl-spp 64] [--variants llvm_ad_rgb,scalar_rgb] [--reference-spp 1024]
           [--out DIR]
"""

import argparse
import glob
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

SIZE = 256
SPP = 64

MITSUBA_RENDER = r"""
import sys, mitsuba as mi
mi.set_variant(sys.argv[1])
scene_dict = mi.cornell_box()
scene_dict["integrator"] = {"type": "path", "max_depth": -1, "rr_depth": 5}
scene_dict["sensor"]["film"]["width"] = int(sys.argv[3])
scene_dict["sensor"]["film"]["height"] = int(sys.argv[3])
scene_dict["sensor"]["sampler"]["sample_count"] = int(sys.argv[4])
scene = mi.load_dict(scene_dict)
image = mi.render(scene, spp=int(sys.argv[4]), seed=int(sys.argv[5]))
mi.util.write_bitmap(sys.argv[2], image)
"""


def find_libllvm():
    """The newest libLLVM shared library on the system (Dr.Jit needs LLVM 15 or newer)."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return os.environ["DRJIT_LIBLLVM_PATH"]
    candidates = []
    for path in glob.glob("/usr/lib/*/libLLVM*.so*") + glob.glob("/usr/lib/llvm-*/lib/libLLVM*.so*"):
        match = re.search(r"(?:llvm-|libLLVM-|libLLVM\.so\.)(\d+)", path)
        if match and int(match.group(1)) >= 15:
            candidates.append((int(match.group(1)), path))
    return max(candidates)[1] if candidates else None


def timed(command, env=None):
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def mitsuba_command(variant, path, spp, seed):
    return [sys.executable, "-c", MITSUBA_RENDER, variant, path, str(SIZE), str(spp), str(seed)]


def strahl_command(binary, path, spp, seed):
    return [
        binary, "render", "cornell", "--method", "pathtrace", "--width", str(SIZE),
        "--height", str(SIZE), "--spp", str(spp), "--seed", str(seed), "--quiet", "-o", path,
    ]


def load_linear(path):
    import mitsuba as mi
    import numpy as np

    if not mi.variant():
        mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def relative_rms(image, reference):
    import numpy as np

    luminance = lambda a: a @ np.array([0.2126, 0.7152, 0.0722])
    diff = luminance(image) - luminance(reference)
    return float(np.sqrt(np.mean(diff * diff)) / np.mean(luminance(reference)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--strahl", default="target/release/strahl")
    parser.add_argument("--variants", default="llvm_ad_rgb,scalar_rgb",
                        help="Mitsuba variants, comma-separated")
    parser.add_argument("--no-strahl", action="store_true", help="time Mitsuba only")
    parser.add_argument("--strahl-spp", type=int, default=SPP,
                        help="paths per pixel for strahl (fewer: compare at equal noise)")
    parser.add_argument("--reference-spp", type=int, default=1024)
    parser.add_argument("--out", default=None, help="keep images here")
    args = parser.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="compare-mitsuba-")
    os.makedirs(out, exist_ok=True)
    env = dict(os.environ)
    llvm = find_libllvm()
    if llvm:
        env["DRJIT_LIBLLVM_PATH"] = llvm

    renderers = []
    if not args.no_strahl:
        renderers.append(
            ("strahl", lambda path, spp, seed: strahl_command(
                args.strahl, path, args.strahl_spp if spp == SPP else spp, seed))
        )
    for variant in filter(None, args.variants.split(",")):
        renderers.append(
            (f"mitsuba {variant}", lambda path, spp, seed, v=variant: mitsuba_command(v, path, spp, seed))
        )

    # One untimed run each first warms file caches (and Mitsuba's kernel cache); the timed
    # runs then alternate between renderers so that other load on the machine hits all alike.
    images = {}
    for name, command in renderers:
        images[name] = os.path.join(out, f"{name.replace(' ', '_')}_{SPP}.exr")
        timed(command(images[name], SPP, 1), env)
    times = {name: [] for name, _ in renderers}
    for run in range(args.runs):
        for name, command in renderers:
            times[name].append(timed(command(images[name], SPP, 1 + run), env))
    results = {}
    for name, command in renderers:
        reference = os.path.join(out, f"{name.replace(' ', '_')}_{args.reference_spp}.exr")
        if not os.path.exists(reference):
            timed(command(reference, args.reference_spp, 1000), env)
        noise = relative_rms(load_linear(images[name]), load_linear(reference))
        median = statistics.median(times[name])
        results[name] = {
            "median_seconds": median,
            "seconds": [round(t, 3) for t in times[name]],
            "relative_rms_noise": noise,
        }
        print(f"{name:24} median {median:6.2f} s  runs {[round(t, 2) for t in times[name]]}  "
              f"relative RMS noise {noise:.4f}", flush=True)
    # Variance falls as 1/samples, so time × noise² is the cost of reaching a fixed noise
    # level (lower is better); scaled here to the seconds each would need for noise 0.05.
    for name, r in results.items():
        r["seconds_for_noise_0.05"] = r["median_seconds"] * (r["relative_rms_noise"] / 0.05) ** 2
        print(f"{name:24} would need {r['seconds_for_noise_0.05']:6.2f} s for relative RMS noise 0.05")
    print(json.dumps({"size": SIZE, "spp": SPP, "results": results}, indent=2))


if __name__ == "__main__":
    main()
