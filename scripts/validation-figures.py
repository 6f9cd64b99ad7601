#!/usr/bin/env python3
"""The figures of docs/VALIDATION.md, as SVG, from runs of the strahl binary.

- validation-light-trace.svg: RMS and largest relative error of the light model over the
  quick suite's sensor checks, and its mean reported standard error, against the photons;
- validation-pathtrace.svg: the same for the path tracer against the samples per sensor;
- validation-hierarchical.svg: the Cornell box per object, hierarchical radiosity against a
  light-model reference (--reference-photons), largest and RMS error against --error, with
  the seconds of each run;
- validation-links.svg: links against leaves of those hierarchical runs, with leaves² (what
  linking every pair would cost) for scale;
- validation-cornell-line.svg: illuminance along a line across the Cornell box's floor by
  the path tracer, the light model and hierarchical radiosity (`examples/cornell_sensors.rs`).

Needs a release build (`cargo build --release`). Prints the numbers as Markdown tables too.

Usage: scripts/validation-figures.py [--strahl target/release/strahl] [--out docs/images]
           [--reference-photons 20000000] [--part all|convergence|hierarchical|line]
"""

import argparse
import json
import math
import os
import subprocess
import tempfile
import time


def run_json(cmd, path):
    subprocess.run(cmd, check=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(path) as f:
        return json.load(f)


def suite_errors(strahl, method, option, value, tmp):
    """RMS and largest |relative error| and mean 1σ (relative) over the sensor rows."""
    path = os.path.join(tmp, "suite.json")
    rows = run_json(
        [strahl, "validate", "--quick", "--method", method, option, str(value), "--report", path],
        path,
    )
    rows = [r for r in rows if r["quantity"].startswith("E(")]
    errors = [abs(r["relative_error"]) for r in rows]
    sigmas = [r["standard_error"] / r["expected"] for r in rows if r["standard_error"]]
    rms = math.sqrt(sum(e * e for e in errors) / len(errors))
    return rms, max(errors), sum(sigmas) / max(len(sigmas), 1)


def solve(strahl, args, tmp):
    path = os.path.join(tmp, "report.json")
    start = time.time()
    report = run_json([strahl, "solve", "cornell", "-q", "--report", path] + args, path)
    return report, time.time() - start


def per_object(report):
    return {o["name"]: o["irradiance"][1] for o in report["objects"] if o["irradiance"]}


class Plot:
    """A line plot, log-log or linear, written as SVG by hand (no plotting library needed)."""

    W, H, L, R, T, B = 560, 380, 70, 20, 30, 50

    def __init__(self, title, xlabel, ylabel, log=True):
        self.title, self.xlabel, self.ylabel, self.log = title, xlabel, ylabel, log
        self.series = []

    def add(self, name, points, colour, dashed=False):
        keep = [(x, y) for x, y in points if not self.log or (x > 0 and y > 0)]
        self.series.append((name, keep, colour, dashed))

    def axis(self, values):
        """(to axis units, first tick, last tick, tick step, tick label) for `values`."""
        if self.log:
            lo, hi = math.floor(math.log10(min(values))), math.ceil(math.log10(max(values)))
            return math.log10, lo, hi, 1, lambda k: f"1e{k}"
        step = 10 ** math.floor(math.log10((max(values) - min(values)) / 4))
        for factor in (1, 2, 5, 10):
            if (max(values) - min(values)) / (step * factor) <= 6:
                step *= factor
                break
        lo, hi = math.floor(min(values) / step), math.ceil(max(values) / step)
        return (lambda v: v / step), lo, hi, 1, lambda k: f"{k * step:g}"

    def write(self, path):
        xs = [x for _, p, _, _ in self.series for x, _ in p]
        ys = [y for _, p, _, _ in self.series for _, y in p]
        fx, x0, x1, _, xlabel = self.axis(xs)
        fy, y0, y1, _, ylabel = self.axis(ys)
        pw, ph = self.W - self.L - self.R, self.H - self.T - self.B

        def sx(x):
            return self.L + (fx(x) - x0) / max(x1 - x0, 1) * pw

        def sy(y):
            return self.T + ph - (fy(y) - y0) / max(y1 - y0, 1) * ph

        out = [
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.W}" height="{self.H}" '
            'font-family="sans-serif" font-size="12">',
            f'<rect width="{self.W}" height="{self.H}" fill="white"/>',
            f'<text x="{self.W / 2}" y="18" text-anchor="middle" font-size="14">{self.title}</text>',
        ]
        for k in range(x0, x1 + 1):
            x = self.L + (k - x0) / max(x1 - x0, 1) * pw
            out.append(f'<line x1="{x}" y1="{self.T}" x2="{x}" y2="{self.T + ph}" stroke="#ddd"/>')
            out.append(f'<text x="{x}" y="{self.T + ph + 16}" text-anchor="middle">{xlabel(k)}</text>')
        for k in range(y0, y1 + 1):
            y = self.T + ph - (k - y0) / max(y1 - y0, 1) * ph
            out.append(f'<line x1="{self.L}" y1="{y}" x2="{self.L + pw}" y2="{y}" stroke="#ddd"/>')
            out.append(f'<text x="{self.L - 6}" y="{y + 4}" text-anchor="end">{ylabel(k)}</text>')
        out.append(
            f'<rect x="{self.L}" y="{self.T}" width="{pw}" height="{ph}" fill="none" stroke="black"/>'
        )
        out.append(
            f'<text x="{self.L + pw / 2}" y="{self.H - 12}" text-anchor="middle">{self.xlabel}</text>'
        )
        out.append(
            f'<text x="16" y="{self.T + ph / 2}" text-anchor="middle" '
            f'transform="rotate(-90 16 {self.T + ph / 2})">{self.ylabel}</text>'
        )
        for i, (name, points, colour, dashed) in enumerate(self.series):
            dash = ' stroke-dasharray="5,4"' if dashed else ""
            line = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in points)
            out.append(f'<polyline points="{line}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>')
            for x, y in points:
                out.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="3" fill="{colour}"/>')
            ly = self.T + 14 + 16 * i
            out.append(f'<line x1="{self.L + pw - 170}" y1="{ly - 4}" x2="{self.L + pw - 150}" '
                       f'y2="{ly - 4}" stroke="{colour}" stroke-width="2"{dash}/>')
            out.append(f'<text x="{self.L + pw - 145}" y="{ly}">{name}</text>')
        out.append("</svg>")
        with open(path, "w") as f:
            f.write("\n".join(out) + "\n")


def convergence(strahl, method, option, values, label, out, tmp):
    rows = [(v,) + suite_errors(strahl, method, option, v, tmp) for v in values]
    print(f"\n| {label} | RMS error | largest error | mean 1σ |\n|---|---|---|---|")
    for v, rms, worst, sigma in rows:
        print(f"| {v:,} | {100 * rms:.3f} % | {100 * worst:.3f} % | {100 * sigma:.3f} % |")
    plot = Plot(f"{method}: quick suite, sensor checks", label, "relative error")
    plot.add("RMS error", [(v, r) for v, r, _, _ in rows], "#1f77b4")
    plot.add("largest error", [(v, w) for v, _, w, _ in rows], "#d62728")
    plot.add("mean 1σ reported", [(v, s) for v, _, _, s in rows], "#2ca02c", dashed=True)
    plot.write(os.path.join(out, f"validation-{method}.svg"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--strahl", default="target/release/strahl")
    parser.add_argument("--out", default="docs/images")
    parser.add_argument("--reference-photons", type=int, default=20_000_000)
    parser.add_argument("--part", choices=["all", "convergence", "hierarchical", "line"],
                        default="all", help="which figures to make (default: all)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        if args.part in ("all", "convergence"):
            convergence(args.strahl, "light-trace", "--photons",
                        [10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000],
                        "photons", args.out, tmp)
            convergence(args.strahl, "pathtrace", "--samples",
                        [256, 1024, 4096, 16_384, 65_536, 262_144],
                        "samples per sensor", args.out, tmp)
        if args.part in ("all", "hierarchical"):
            hierarchical(args, tmp)
    if args.part in ("all", "line"):
        cornell_line(args.out)


def hierarchical(args, tmp):
    """Hierarchical radiosity on the Cornell box against the light model, and its links."""
    reference, seconds = solve(
        args.strahl, ["--solver", "light-trace", "--photons", str(args.reference_photons)], tmp)
    ref = per_object(reference)
    print(f"\nReference: light model, {args.reference_photons:,} photons, {seconds:.1f} s")
    print("\n| --error | largest error | RMS error | links | leaves | seconds |")
    print("|---|---|---|---|---|---|")
    rows = []
    for error in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5]:
        report, seconds = solve(
            args.strahl,
            ["--solver", "hierarchical", "--error", str(error), "--threads", "1"], tmp)
        got = per_object(report)
        errs = [abs(got[k] / ref[k] - 1) for k in ref if k in got and ref[k] > 0]
        worst = max(errs)
        rms = math.sqrt(sum(e * e for e in errs) / len(errs))
        links, leaves = report["stats"]["links"], report["stats"]["patches"]
        rows.append((error, worst, rms, links, leaves, seconds))
        print(f"| {error:g} | {100 * worst:.2f} % | {100 * rms:.2f} % | {links:,} | "
              f"{leaves:,} | {seconds:.2f} |")
    plot = Plot("Cornell box: hierarchical radiosity vs light model", "--error",
                "relative error per object")
    plot.add("largest error", [(e, w) for e, w, _, _, _, _ in rows], "#d62728")
    plot.add("RMS error", [(e, r) for e, _, r, _, _, _ in rows], "#1f77b4")
    plot.add("seconds (one thread)", [(e, s) for e, _, _, _, _, s in rows], "#7f7f7f",
             dashed=True)
    plot.write(os.path.join(args.out, "validation-hierarchical.svg"))
    plot = Plot("Cornell box: links against leaves", "leaves", "count")
    plot.add("links", [(l, k) for _, _, _, k, l, _ in rows], "#1f77b4")
    plot.add("leaves²", [(l, l * l) for _, _, _, _, l, _ in rows], "#7f7f7f", dashed=True)
    plot.write(os.path.join(args.out, "validation-links.svg"))


def cornell_line(out):
    """Illuminance along the Cornell box's floor line by three methods."""
    text = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--example", "cornell_sensors"],
        check=True, capture_output=True, text=True,
    ).stdout
    rows = [list(map(float, line.split(","))) for line in text.strip().splitlines()[1:]]
    print("\n| x (m) | path tracer | light model | hierarchical | largest difference |")
    print("|---|---|---|---|---|")
    for x, p, _, l, _, h in rows:
        spread = (max(p, l, h) - min(p, l, h)) / l
        print(f"| {x:.3f} | {p:.1f} | {l:.1f} | {h:.1f} | {100 * spread:.2f} % |")
    plot = Plot("Cornell box floor, z = 0.5 m: illuminance by three methods", "x (m)",
                "illuminance (683 × Y of W/m²)", log=False)
    plot.add("path tracer", [(r[0], r[1]) for r in rows], "#1f77b4")
    plot.add("light model", [(r[0], r[3]) for r in rows], "#2ca02c", dashed=True)
    plot.add("hierarchical radiosity", [(r[0], r[5]) for r in rows], "#d62728")
    plot.write(os.path.join(out, "validation-cornell-line.svg"))


if __name__ == "__main__":
    main()
