"""The cost of wavelength bands in the light model (docs/PERFORMANCE.md, "Wavelength bands"):
the plant example (`examples/plant-bands/plant.toml`) with its four bands replaced by 1 or 10
bands of equal width over 400–1100 nm, under the ASTM G173 sun and sky (two spectra) or the
direct spectrum for both (one spectrum); `strahl solve` with the light model, 2·10⁶ photons,
one thread, and the light model's own seconds (`stats.seconds` of the report). Each binary
given is run on every variant in turn, ROUNDS times, so that the machine's drift falls on all
alike; prints the medians and minima and the ratio of 10 bands to 1. Usage:

    python3 scripts/bands-cost.py [ROUNDS] STRAHL [STRAHL ...]
"""

import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "examples", "plant-bands")
ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].isdigit() else 7
BINARIES = [a for a in sys.argv[1:] if not a.isdigit()] or [
    os.path.join(ROOT, "target", "release", "strahl")
]


def bands(n):
    """`n` bands of equal width over 400–1100 nm, as TOML."""
    width = 700.0 / n
    return "".join(
        f'[[bands]]\nname = "b{i}"\nfrom_nm = {400 + i * width:g}\nto_nm = {400 + (i + 1) * width:g}\n\n'
        for i in range(n)
    )


def variants(folder):
    """The scene files of every variant, by name, written into `folder`."""
    with open(os.path.join(EXAMPLE, "plant.toml")) as f:
        text = f.read()
    text = re.sub(r'\[\[bands\]\]\nname = "[^"]*"\nfrom_nm = \d+\nto_nm = \d+\n\n', "", text)
    for csv in ("leaf_reflectance.csv", "leaf_transmittance.csv"):
        shutil.copy(os.path.join(EXAMPLE, csv), folder)
    files = {}
    for spectra in ("one", "two"):
        for n in (1, 10):
            scene = text.replace("[materials.leaf]", bands(n) + "[materials.leaf]")
            if spectra == "one":
                scene = scene.replace("astm-g173-diffuse", "astm-g173-direct")
            path = os.path.join(folder, f"plant-{n}-{spectra}.toml")
            with open(path, "w") as f:
                f.write(scene)
            files[(spectra, n)] = path
    return files


def seconds(strahl, scene, report):
    """The light model's own seconds on `scene`."""
    subprocess.run(
        [strahl, "solve", scene, "--photons", "2000000", "--threads", "1", "-q", "--report", report],
        check=True,
    )
    with open(report) as f:
        return json.load(f)["stats"]["seconds"]


def main():
    with tempfile.TemporaryDirectory() as folder:
        files = variants(folder)
        times = {}
        report = os.path.join(folder, "report.json")
        for _ in range(ROUNDS):
            for key, scene in files.items():
                for strahl in BINARIES:
                    times.setdefault((strahl, key), []).append(seconds(strahl, scene, report))
    for strahl in BINARIES:
        print(strahl)
        for spectra, label in (("one", "one spectrum"), ("two", "two spectra")):
            one, ten = times[(strahl, (spectra, 1))], times[(strahl, (spectra, 10))]
            print(
                f"  {label}: 1 band {statistics.median(one):.3f} s ({min(one):.3f}), "
                f"10 bands {statistics.median(ten):.3f} s ({min(ten):.3f}), "
                f"10 against 1 {statistics.median(ten) / statistics.median(one):.2f}× "
                f"({min(ten) / min(one):.2f}×)"
            )


if __name__ == "__main__":
    main()
