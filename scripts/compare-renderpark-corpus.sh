#!/usr/bin/env bash
# compare-renderpark-corpus.sh: strahl's hierarchical radiosity against RenderPark's Galerkin
# radiosity on RenderPark's own MGF scenes, side by side, object by object.
#
# What it does
#   For each scene (an MGF file; by default the nine of RenderPark's `etc/` folder), one run
#   of each program at its defaults, one thread, each under a time limit (LIMIT seconds,
#   default 300), whole process timed with its peak resident memory (GNU time):
#     RPK_BINARY SCENE.mgf -radiance-method Galerkin -raytracing-method none -iterations 20
#         -radiance-model-savefile solution.wrl -tonemapping Ward -ldmax 100
#         -brightness-adjust -16
#     strahl solve SCENE.mgf --solver hierarchical --threads 1 -q --report hr.json
#         --export hr.ply
#   and strahl's light model as the reference (`--solver light-trace --diffuse-only --photons
#   PHOTONS`, all cores; default 10^7 photons): with the lobes radiosity does not model
#   dropped (several of these scenes have specular materials, which both radiosity programs
#   count as absorbing), so that it solves what they solve.
#   Per object (the MGF objects, as strahl names them): the luminance Y of the power each
#   program's solution reflects, against the light model's. strahl's comes from its report;
#   RenderPark's from its VRML export: every leaf element is matched to the strahl polygon
#   (from hr.ply, whose faces name their object) that holds its centre and faces its way,
#   and the object's reflected power is the sum over its elements of area x pi x mean
#   radiance (Ward's linear tone mapping undone as in compare-renderpark.sh). RenderPark's
#   watts are lumens / 183.07 where strahl's are lumens / 683: its figures are scaled by
#   183.07 / 683. Objects that emit are left out (RenderPark exports emitted and reflected
#   light together), and so are objects below 10^-4 of the reflected power or whose
#   reference has a standard error above 1 %. Printed per scene: time, memory, elements and links of
#   both, the worst and the RMS deviation over the objects compared, and where a program
#   did not finish within the limit, that.
#
# How to run
#   cargo build --release
#   scripts/compare-renderpark-corpus.sh /path/to/rpk /path/to/rpkCpp/etc [SCENE.mgf ...]
#   (SCENE paths relative to the etc folder; RenderPark: see compare-renderpark.sh.)
#   Environment: STRAHL (default: target/release/strahl of this repository), LIMIT (seconds
#   per program and scene, default 300), PHOTONS (default 10000000).
#   Needs bash, GNU time (/usr/bin/time), python3 (standard library only), timeout.
set -euo pipefail

usage() {
    echo "usage: $0 RPK_BINARY RPK_ETC_DIR [SCENE.mgf ...]   (env: STRAHL, LIMIT, PHOTONS)" >&2
    exit 2
}
[ $# -ge 2 ] || usage
rpk=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
etc=$(cd "$2" && pwd)
shift 2
[ -x "$rpk" ] || { echo "$0: $rpk is not an executable" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "$0: needs GNU time (/usr/bin/time)" >&2; exit 1; }
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(cube.mgf corridor.mgf examp1.mgf office2/office2.mgf
    office3/office.mgf hospital/main.mgf salon/classroom.mgf office1/graz.mgf soda.mgf)
limit=${LIMIT:-300}
photons=${PHOTONS:-10000000}
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
strahl=${STRAHL:-$repo/target/release/strahl}
[ -x "$strahl" ] || { echo "$0: $strahl is missing: run 'cargo build --release' first" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$strahl" "$tmp/strahl"
strahl=$tmp/strahl

commit=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)
echo "strahl $commit against RenderPark ($rpk); $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1), $(nproc) CPUs;" \
    "limit ${limit} s per program and scene; reference: light model, $photons photons"
echo
echo "| scene | triangles | RenderPark s / MB | elements, links | strahl s / MB | leaves, links | objects | RenderPark worst, RMS | strahl worst, RMS |"
echo "|---|---|---|---|---|---|---|---|---|"

for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .mgf)
    dir=$etc/$(dirname "$scene")
    out=$tmp/$name
    mkdir -p "$out"
    echo "$scene ..." >&2
    triangles=$("$strahl" info "$etc/$scene" 2>/dev/null | sed -n 's/^primitives *\([0-9]*\) triangles.*/\1/p')
    # RenderPark reads includes relative to its working folder.
    rpk_status=0
    (cd "$dir" && /usr/bin/time -f "%e %M" -o "$out/rpk.time" timeout "$limit" "$rpk" \
        "$(basename "$scene")" -radiance-method Galerkin -raytracing-method none -iterations 20 \
        -radiance-model-savefile "$out/solution.wrl" -tonemapping Ward -ldmax 100 \
        -brightness-adjust -16 > "$out/rpk.out" 2>&1) || rpk_status=$?
    hr_status=0
    /usr/bin/time -f "%e %M" -o "$out/hr.time" timeout "$limit" "$strahl" solve "$etc/$scene" \
        --solver hierarchical --threads 1 -q --report "$out/hr.json" --export "$out/hr.ply" \
        2> "$out/hr.err" || hr_status=$?
    "$strahl" solve "$etc/$scene" --solver light-trace --diffuse-only --photons "$photons" -q \
        --report "$out/lt.json" 2> /dev/null
    python3 - "$out" "$scene" "$triangles" "$rpk_status" "$hr_status" "$repo/scripts" <<'EOF'
import json, math, re, sys

out, scene, triangles, rpk_status, hr_status, scripts = sys.argv[1:7]
sys.path.insert(0, scripts)
from renderpark_export import (adaptation_luminance, cross, display_scale, dot, elements,
                               newell, read_export, sub)

# Y of the MGF RGB space both programs read colours into (primaries of the MGF notes, white E;
# the middle row of scripts/cornell-mgf.py's rgb_to_xyz_matrix).
Y = (0.265105820, 0.670105820, 0.064788360)


def luminance(rgb):
    return sum(w * c for w, c in zip(Y, rgb))


def timing(path):
    try:
        seconds, kb = open(path).read().split()[-2:]
        return float(seconds), float(kb) / 1024
    except (OSError, ValueError):
        return None


def cell_time(t, status):
    if status == "124":
        return "not finished"
    if status != "0" or t is None:
        return f"failed ({status})"
    return f"{t[0]:.2f} / {t[1]:.0f}"


lt = json.load(open(f"{out}/lt.json"))
reference = {o["name"]: o for o in lt["objects"]}
total = sum(luminance(o["reflected_power"]) for o in lt["objects"])


def compared(name):
    o = reference[name]
    if luminance(o["emitted_power"]) > 0:
        return False
    share = luminance(o["reflected_power"]) / total
    sigma = luminance(o["incident_power_standard_error"]) / max(luminance(o["incident_power"]), 1e-300)
    return share >= 1e-4 and sigma <= 0.01


def deviations(values):
    d = [values[n] / luminance(reference[n]["reflected_power"]) - 1
         for n in values if n in reference and compared(n)]
    if not d:
        return "–", 0
    worst = max(d, key=abs)
    return f"{worst:+.1%}, {math.sqrt(sum(x * x for x in d) / len(d)):.1%}", len(d)


rpk_cell, hr_cell, objects = "–", "–", 0
rpk_counts, hr_counts = "?", "?"
if hr_status == "0":
    hr = json.load(open(f"{out}/hr.json"))
    s = hr["stats"]
    hr_counts = f"{s.get('patches', '?')}, {s.get('links', '?')}"
    hr_values = {o["name"]: luminance(o["reflected_power"]) for o in hr["objects"]}
    hr_cell, objects = deviations(hr_values)
    names = [o["name"] for o in hr["objects"]]
if rpk_status == "0":
    text = open(f"{out}/rpk.out", errors="replace").read()
    m = re.findall(r"Nr\. elements: (\d+)", text)
    k = re.findall(r"Nr\. interactions: (\d+)", text)
    rpk_counts = f"{m[-1] if m else '?'}, {k[-1] if k else '?'}"
if rpk_status == "0" and hr_status == "0":
    scale = display_scale(adaptation_luminance(text))
    P, C, index = read_export(f"{out}/solution.wrl")

    # strahl's polygons (both sides of every leaf) with their object, in a grid of cells.
    lines = open(f"{out}/hr.ply").read().split("end_header\n", 1)[1].splitlines()
    vertices = int(re.search(r"element vertex (\d+)", open(f"{out}/hr.ply").read(2000)).group(1))
    V = [tuple(map(float, l.split()[:3])) for l in lines[:vertices]]
    polys = []
    for l in lines[vertices:]:
        w = l.split()
        n = int(w[0])
        corners = [V[int(i)] for i in w[1:1 + n]]
        a = newell(corners)
        length = math.sqrt(dot(a, a))
        if length > 0:
            polys.append((corners, tuple(x / length for x in a), int(w[1 + n])))
    xs = [c for p in polys for c in p[0]]
    lo = [min(c[i] for c in xs) for i in range(3)]
    hi = [max(c[i] for c in xs) for i in range(3)]
    cell = max(hi[i] - lo[i] for i in range(3)) / 128 or 1.0
    grid = {}
    for k, (corners, _, _) in enumerate(polys):
        b0 = [int((min(c[i] for c in corners) - lo[i]) / cell) for i in range(3)]
        b1 = [int((max(c[i] for c in corners) - lo[i]) / cell) for i in range(3)]
        if (b1[0] - b0[0] + 1) * (b1[1] - b0[1] + 1) * (b1[2] - b0[2] + 1) > 4096:
            b1 = [min(b1[i], b0[i] + 15) for i in range(3)]
        for x in range(b0[0], b1[0] + 1):
            for y in range(b0[1], b1[1] + 1):
                for z in range(b0[2], b1[2] + 1):
                    grid.setdefault((x, y, z), []).append(k)

    def holds(k, point, normal, size):
        corners, n, _ = polys[k]
        if dot(n, normal) < 0.99 or abs(dot(n, sub(point, corners[0]))) > 1e-3 * size + 1e-6:
            return False
        return all(dot(n, cross(sub(corners[(i + 1) % len(corners)], corners[i]),
                                sub(point, corners[i]))) >= -1e-9 * size * size
                   for i in range(len(corners)))

    rpk_values = {}
    unmatched = read = 0
    for element in elements(index):
        poly = [P[j] for j in element]
        a = newell(poly)
        area = math.sqrt(dot(a, a))
        read += 1
        if area > 0:
            n = tuple(x / area for x in a)
            centre = tuple(sum(p[j] for p in poly) / len(poly) for j in range(3))
            size = math.sqrt(area)
            key = tuple(int((centre[j] - lo[j]) / cell) for j in range(3))
            match = [k for k in grid.get(key, []) if holds(k, centre, n, size)]
            if match:
                mean = [sum(C[j][c] for j in element) / len(element) / scale for c in range(3)]
                obj = names[polys[match[0]][2]]
                rpk_values[obj] = rpk_values.get(obj, 0.0) + area * math.pi * luminance(mean) * 183.07 / 683
            else:
                unmatched += 1
    rpk_cell, _ = deviations(rpk_values)
    if unmatched:
        rpk_cell += f" ({unmatched} of {read} elements unmatched)"
print(f"| {scene} | {triangles} | {cell_time(timing(f'{out}/rpk.time'), rpk_status)} | {rpk_counts} "
      f"| {cell_time(timing(f'{out}/hr.time'), hr_status)} | {hr_counts} | {objects} | {rpk_cell} | {hr_cell} |")
EOF
done
