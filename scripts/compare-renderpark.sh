#!/usr/bin/env bash
# compare-renderpark.sh: strahl's hierarchical radiosity against RenderPark's Galerkin radiosity
# on the measured Cornell box, side by side.
#
# What it does
#   Writes strahl's built-in `cornell` scene as MGF (scripts/cornell-mgf.py: same geometry, same
#   linear-RGB reflectances and emitted radiance as RenderPark reads them) into a temporary
#   folder, then runs RenderPark and strahl alternately, RUNS times each (default 5), flipping
#   the order on even runs, after one untimed run of each:
#     RPK_BINARY cornell.mgf -radiance-method Galerkin -raytracing-method none
#         -gr-link-error-threshold RPK_ERROR -iterations 20 -timings   (RPK_ERROR: 1e-5)
#     strahl solve cornell --solver hierarchical --threads 1 --report run.json -q
#   RenderPark's Galerkin radiosity runs hierarchical, clustered, Jacobi iterations, one thread
#   (it has no threads); -timings only makes it print its own time. Each whole process is
#   timed (wall clock, bash `time`). The table gives per run: wall seconds, and each program's
#   own figure: RenderPark's "Radiance total time" (processor time, clock(), of its 20
#   iterations; reading the scene is not in it) and strahl's solver seconds (report
#   stats.seconds: setup + form factors + iterations, wall clock), plus the element and link
#   counts. Medians and ranges follow.
#
#   Per object (unless OBJECTS=0): RenderPark runs once more, untimed, with the same options
#   and a VRML export of its solution (-radiance-model-savefile; Ward's tone mapping with
#   -ldmax 100 -brightness-adjust -16, which is linear: display value = radiance x 2^-16 x
#   183.07 x comp / 100, where comp follows from the adaptation luminance the run prints, so
#   that no value clips). Every leaf element is matched to the MGF face it lies on; an
#   element's mean radiance is the mean of its corner values (its corner values come from
#   its constant + linear basis, whose mean over the corners is the constant term); the
#   object's mean is area-weighted over its elements; radiosity = pi x radiance. The export
#   prints 3 significant digits per corner; over an object's elements the rounding averages
#   out (another display scale moves the means by at most 0.02 %), but the light's reflected
#   part (under 1 % of its emitted radiance, on a few elements) cannot be recovered: n/a.
#   The run's statistics (average reflectance, emitted power, largest emitted radiance, in
#   RenderPark's grey = its Y) are checked against the values the MGF was made for.
#   Printed per object: luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the reflected
#   (non-emitted) radiosity, W/m^2, of RenderPark, of strahl's hierarchical radiosity (last
#   timed run: reflected_power / area) and of strahl's light model as the reference
#   (`strahl solve cornell --solver light-trace --photons PHOTONS`, all cores, run once
#   unless REFERENCE names such a report), and both radiosity results' deviation from it.
#
#   Per face (with the per-object table): the same elements of RenderPark matched to each MGF
#   face (the faces of an object in the order strahl numbers them, checked by their areas);
#   strahl once more, untimed, with the same options and `--per-face` (every face reported on
#   its own, its final gather then held to each face); the reference is the light model at
#   2e8 photons recorded per face in src/validate/cornell_per_face_light_model.json (unless
#   FACE_REFERENCE names another such file), with its standard error per face. The lamp's
#   face is left out (see above). Printed: each face's Y of the reflected radiosity, both
#   programs' deviations, and their worst and RMS deviation over the faces.
#
# How to run (from anywhere; needs a release build of strahl and a RenderPark build):
#   cargo build --release
#   scripts/compare-renderpark.sh /path/to/rpk [RUNS]
#   RenderPark: the C++ rewrite github.com/OscarChavarro/rpkCpp (measured at 37e5ff4), built with
#   cmake in Release (Debian: cmake build-essential freeglut3-dev libglu1-mesa-dev).
#   Environment: STRAHL (default: target/release/strahl of this repository), OBJECTS=0 (skip the
#   per-object and per-face tables), RPK_ERROR (RenderPark's link error threshold, default
#   1e-5, its own default), FACE_REFERENCE (see above), REFERENCE (a light-trace JSON
#   report of the `cornell` scene to use as the per-object reference instead of computing one),
#   PHOTONS (its photons, default 20000000).
#   Needs bash, python3 (standard library only) and standard tools.
set -euo pipefail

usage() {
    echo "usage: $0 RPK_BINARY [RUNS]   (env: STRAHL, OBJECTS=0, RPK_ERROR, REFERENCE, FACE_REFERENCE, PHOTONS)" >&2
    exit 2
}
[ $# -ge 1 ] && [ $# -le 2 ] || usage
rpk=$1
runs=${2:-5}
objects=${OBJECTS:-1}
photons=${PHOTONS:-20000000}
rpk_error=${RPK_ERROR:-1e-5}
case $runs in '' | *[!0-9]* | 0) usage ;; esac
[ -x "$rpk" ] || { echo "$0: $rpk is not an executable" >&2; exit 1; }

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
strahl=${STRAHL:-$repo/target/release/strahl}
[ -x "$strahl" ] || { echo "$0: $strahl is missing: run 'cargo build --release' first" >&2; exit 1; }
if [ -n "${REFERENCE:-}" ]; then
    [ -f "$REFERENCE" ] || { echo "$0: no such reference report: $REFERENCE" >&2; exit 1; }
    REFERENCE=$(cd "$(dirname "$REFERENCE")" && pwd)/$(basename "$REFERENCE")
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Copies, so that a rebuild during the runs cannot mix two binaries in one table.
cp "$strahl" "$tmp/strahl"
cp "$rpk" "$tmp/rpk"
strahl_built=$(date -u -r "$strahl" '+%Y-%m-%d %H:%M UTC')
rpk_built=$(date -u -r "$rpk" '+%Y-%m-%d %H:%M UTC')
rpk_path=$(cd "$(dirname "$rpk")" && pwd)/$(basename "$rpk")
strahl=$tmp/strahl
rpk=$tmp/rpk
mgf=$tmp/cornell.mgf
python3 "$repo/scripts/cornell-mgf.py" "$mgf"

rpk_args=(-radiance-method Galerkin -raytracing-method none -gr-link-error-threshold "$rpk_error"
    -iterations 20 -timings)
strahl_args=(solve cornell --solver hierarchical --threads 1 -q)

# One record per run: program repetition wall_s own_s elements links
results=$tmp/results.tsv
: > "$results"
TIMEFORMAT=%3R
run_one() { # run_one PROGRAM REPETITION (0: untimed)
    local prog=$1 rep=$2 wall own elements links
    cd "$tmp"
    if [ "$prog" = renderpark ]; then
        { time "$rpk" "$mgf" "${rpk_args[@]}" > rpk.out 2> rpk.err; } 2> time.txt \
            || { echo "$0: RenderPark failed, see its output:" >&2; tail -n 20 rpk.out rpk.err >&2; exit 1; }
        own=$(sed -n 's/^Radiance total time \([-0-9.eE+]*\) secs.*/\1/p' rpk.out | tail -n 1)
        elements=$(sed -n 's/^Nr\. elements: \([0-9]*\).*/\1/p' rpk.out | tail -n 1)
        links=$(sed -n 's/^Nr\. interactions: \([0-9]*\).*/\1/p' rpk.out | tail -n 1)
    else
        { time "$strahl" "${strahl_args[@]}" --report run.json > strahl.out 2> strahl.err; } \
            2> time.txt \
            || { echo "$0: strahl failed:" >&2; tail -n 20 strahl.err >&2; exit 1; }
        read -r own elements links < <(python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))["stats"]
print(s["seconds"], s.get("elements", "?"), s.get("links", "?"))' run.json)
    fi
    wall=$(tail -n 1 time.txt)
    [ "$rep" = 0 ] && return 0
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$prog" "$rep" "$wall" "${own:-?}" "${elements:-?}" \
        "${links:-?}" >> "$results"
}

commit=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [ "$commit" != unknown ] && ! git -C "$repo" diff --quiet HEAD -- src Cargo.toml Cargo.lock; then
    commit="$commit (with uncommitted changes to src/ or Cargo files)"
fi
# RenderPark's commit: of the folder the binary is in, or of the source folder of its cmake build.
rpk_dir=$(dirname "$rpk_path")
rpk_source=$(sed -n 's/^rpk_SOURCE_DIR:STATIC=//p' "$rpk_dir/CMakeCache.txt" 2>/dev/null || true)
rpk_commit=$(git -C "$rpk_dir" rev-parse --short HEAD 2>/dev/null \
    || { [ -n "$rpk_source" ] && git -C "$rpk_source" rev-parse --short HEAD 2>/dev/null; } \
    || echo unknown)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
load_before=$(cut -d ' ' -f 1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M UTC')

programs=(renderpark strahl)
echo "warm-up (untimed) ..." >&2
for prog in "${programs[@]}"; do run_one "$prog" 0; done
for rep in $(seq 1 "$runs"); do
    echo "run $rep of $runs ..." >&2
    order=("${programs[@]}")
    [ $((rep % 2)) = 0 ] && order=(strahl renderpark)
    for prog in "${order[@]}"; do run_one "$prog" "$rep"; done
done
load_after=$(cut -d ' ' -f 1-3 /proc/loadavg)
cp "$tmp/run.json" "$tmp/hierarchical.json"

echo
echo "strahl $commit (binary built $strahl_built) against RenderPark rpkCpp $rpk_commit"
echo "  ($rpk_path, built $rpk_built); $started"
echo "scene: strahl's cornell (RenderPark: the same box as MGF); $runs runs per program, one thread"
echo "machine: $cpu, $(nproc) CPUs; load average before $load_before, after $load_after"
echo "RenderPark: rpk cornell.mgf ${rpk_args[*]}"
echo "strahl:     strahl ${strahl_args[*]} --report run.json"
echo
python3 - "$results" <<'EOF'
import statistics, sys

rows = [line.rstrip("\n").split("\t") for line in open(sys.argv[1]) if line.strip()]
print("| run | RenderPark wall s | RenderPark own s (CPU, iterations) | strahl wall s "
      "| strahl own s (solver) |")
print("|---|---|---|---|---|")
reps = sorted({int(r[1]) for r in rows})
by = {(r[0], int(r[1])): r for r in rows}
for rep in reps:
    a, b = by[("renderpark", rep)], by[("strahl", rep)]
    first = "RenderPark first" if rep % 2 else "strahl first"
    print(f"| {rep} ({first}) | {float(a[2]):.3f} | {a[3]} | {float(b[2]):.3f} | "
          f"{float(b[3]):.4f} |")


def column(prog, i):
    out = []
    for r in rows:
        if r[0] == prog:
            try:
                out.append(float(r[i]))
            except ValueError:
                pass
    return out


def cell(values, decimals):
    if not values:
        return "?"
    return (f"{statistics.median(values):.{decimals}f} "
            f"({min(values):.{decimals}f}–{max(values):.{decimals}f})")


rw, ro = column("renderpark", 2), column("renderpark", 3)
sw, so = column("strahl", 2), column("strahl", 3)
print(f"| median (range) | {cell(rw, 3)} | {cell(ro, 3)} | {cell(sw, 3)} | {cell(so, 4)} |")
if rw and sw:
    print(f"\nwall-clock ratio strahl / RenderPark (medians): {statistics.median(sw) / statistics.median(rw):.2f}")
if ro and so:
    print(f"own-time ratio strahl / RenderPark (medians): {statistics.median(so) / statistics.median(ro):.2f}")
for prog, name, what in (("renderpark", "RenderPark", "elements (incl. clusters), interactions"),
                         ("strahl", "strahl", "elements (patch sides), links")):
    counts = sorted({(r[4], r[5]) for r in rows if r[0] == prog})
    print(f"{name} {what}: " + "; ".join(f"{e}, {l}" for e, l in counts))
EOF

[ "$objects" = 0 ] && exit 0

echo
echo "per-object export run of RenderPark (untimed) ..." >&2
cd "$tmp"
"$rpk" "$mgf" "${rpk_args[@]}" -radiance-model-savefile "$tmp/solution.wrl" \
    -tonemapping Ward -ldmax 100 -brightness-adjust -16 > export.out 2> export.err \
    || { echo "$0: RenderPark's export run failed" >&2; tail -n 20 export.out export.err >&2; exit 1; }
lwa=$(sed -n 's/.*adaptationLuminance) *\.*: *\([-0-9.eE+]*\) cd.*/\1/p' export.out | tail -n 1)
[ -n "$lwa" ] || { echo "$0: no adaptation luminance in RenderPark's output" >&2; exit 1; }

echo "per-face run of strahl (untimed) ..." >&2
"$strahl" "${strahl_args[@]}" --per-face --report "$tmp/faces.json"
face_reference=${FACE_REFERENCE:-$repo/src/validate/cornell_per_face_light_model.json}

reference=${REFERENCE:-}
if [ -z "$reference" ]; then
    echo "reference: strahl light model, $photons photons, all cores ..." >&2
    reference=$tmp/reference.json
    "$strahl" solve cornell --solver light-trace --photons "$photons" --report "$reference" -q
    reference_what="strahl solve cornell --solver light-trace --photons $photons (seed 0, this run)"
else
    reference_what="$reference"
fi

python3 - "$repo/scripts/cornell-mgf.py" "$tmp/solution.wrl" "$lwa" "$tmp/hierarchical.json" \
    "$reference" "$reference_what" "$tmp/export.out" "$tmp/faces.json" "$face_reference" <<'EOF'
import importlib.util, json, math, os, re, sys

mgf_script, wrl, lwa, hr_path, ref_path, ref_what, rpk_out, faces_path, face_ref_path = sys.argv[1:10]
sys.path.insert(0, os.path.dirname(mgf_script))
from renderpark_export import cross, display_scale, dot, elements, newell, read_export, sub

spec = importlib.util.spec_from_file_location("cornell_mgf", mgf_script)
cm = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cm)


def norm(v):
    return math.sqrt(dot(v, v))


def unit(v):
    length = norm(v)
    return tuple(x / length for x in v)


def luminance(rgb):
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]


# The MGF faces in metres, with their unit normals and areas.
# The faces of each object come in the order strahl numbers them (`object#face`).
faces, face_index = [], []
for name, _, polys in cm.OBJECTS:
    for k, poly in enumerate(polys):
        pm = [tuple(x / 1000 for x in v) for v in poly]
        faces.append((name, pm, unit(newell(pm)), norm(newell(pm))))
        face_index.append(k)

# What RenderPark read: its scene statistics against the values the MGF was made for (its
# "gray" is Y in its own RGB space).
y_row = cm.rgb_to_xyz_matrix()[1]


def grey(rgb):
    return sum(w * c for w, c in zip(y_row, rgb))


reflectance = {"white": cm.WHITE, "red": cm.RED, "green": cm.GREEN,
               "light": (cm.LIGHT_REFLECTANCE,) * 3}
material = {name: m for name, m, _ in cm.OBJECTS}
total_area = sum(f[3] for f in faces)
light_area = sum(f[3] for f in faces if f[0] == "light")
expected = {
    "averageReflectivity": sum(f[3] * grey(reflectance[material[f[0]]]) for f in faces) / total_area,
    "totalEmittedPower": grey([math.pi * c for c in cm.LIGHT]) * light_area,
    "maxSelfEmittedRadiance": grey(cm.LIGHT),
    "totalArea": total_area,
}
stats = {}
for line in open(rpk_out, errors="replace"):
    m = re.search(r"GLOBAL_statistics[._](\w+) \.*: ([-0-9.eE+]+)", line)
    if m:
        stats[m.group(1)] = float(m.group(2))
print("RenderPark's scene statistics (its Y; in brackets: expected from strahl's colours):")
print("  " + "; ".join(f"{k} {stats.get(k, float('nan')):.6g} ({v:.6g})" for k, v in expected.items()))

scale = display_scale(float(lwa))
try:
    P, C, index = read_export(wrl)
except ValueError as e:
    sys.exit(str(e))
clipped = sum(1 for c in C for v in c if v >= 0.999)


def inside(face, point):
    _, poly, n, _ = face
    if abs(dot(n, sub(point, poly[0]))) > 2e-4:
        return False
    return all(dot(n, cross(sub(poly[(i + 1) % len(poly)], poly[i]), sub(point, poly[i]))) >= -1e-9
               for i in range(len(poly)))


# Per object and per face: [area, area-weighted sum of the elements' mean radiance]
sums = {name: [0.0, [0.0, 0.0, 0.0]] for name, _, _ in cm.OBJECTS}
face_sums = {(f[0], k): [0.0, [0.0, 0.0, 0.0]] for f, k in zip(faces, face_index)}
unmatched = elements_read = 0
for element in elements(index):
    elements_read += 1
    poly = [P[k] for k in element]
    area_vector = newell(poly)
    area, n = norm(area_vector), unit(area_vector)
    centre = tuple(sum(p[k] for p in poly) / len(poly) for k in range(3))
    mean = [sum(C[k][c] for k in element) / len(element) / scale for c in range(3)]
    match = [i for i, f in enumerate(faces) if dot(f[2], n) > 0.99 and inside(f, centre)]
    if len(match) != 1:
        unmatched += 1
    else:
        name = faces[match[0]][0]
        for s in (sums[name], face_sums[(name, face_index[match[0]])]):
            s[0] += area
            s[1] = [s[1][c] + area * mean[c] for c in range(3)]


def reflected(report):
    out = {}
    for o in json.load(open(report))["objects"]:
        out[o["name"]] = (o["area"], [p / o["area"] for p in o["reflected_power"]])
    return out


hr, ref = reflected(hr_path), reflected(ref_path)
print(f"RenderPark's solution: {elements_read} leaf elements in its VRML export, {unmatched} not matched "
      f"to a face, {clipped} clipped colour values; display scale {scale:.6g} "
      f"(adaptation luminance {lwa} cd/m^2)")
print(f"reference: {ref_what}")
print()
print("Luminance Y of the reflected radiosity, W/m^2 (Y = 0.2126 R + 0.7152 G + 0.0722 B):")
print()
print("| object | area m² (RenderPark / strahl) | RenderPark Galerkin | strahl hierarchical "
      "| reference (light model) | RenderPark / ref − 1 | strahl HR / ref − 1 |")
print("|---|---|---|---|---|---|---|")
emitted = [math.pi * c for c in cm.LIGHT]
check = None
for name, _, _ in cm.OBJECTS:
    area, weighted = sums[name]
    rpk_rgb = [w / area * math.pi for w in weighted] if area > 0 else None
    hr_area, hr_rgb = hr[name]
    _, ref_rgb = ref[name]
    y_ref, y_hr = luminance(ref_rgb), luminance(hr_rgb)
    if name == "light" and rpk_rgb is not None:
        # Its total radiosity; the reflected part is below the export's precision.
        check = luminance(rpk_rgb) / luminance(emitted)
        rpk_cell, rpk_dev = "n/a", "n/a"
    elif rpk_rgb is None:
        rpk_cell, rpk_dev = "?", "?"
    else:
        y = luminance(rpk_rgb)
        rpk_cell, rpk_dev = f"{y:.4f}", f"{y / y_ref - 1:+.2%}"
    print(f"| {name} | {area:.5f} / {hr_area:.5f} | {rpk_cell} | {y_hr:.4f} | {y_ref:.4f} "
          f"| {rpk_dev} | {y_hr / y_ref - 1:+.2%} |")
if check is not None:
    print(f"\nCheck of the export's scale: RenderPark's light, total radiosity / emitted radiosity "
          f"= {check:.4f} (expected 1 + reflected/emitted ≈ "
          f"{1 + luminance(ref['light'][1]) / luminance(emitted):.4f}, to about ±0.5 %)")

# Per face: strahl's per-face run against the recorded per-face light model.
per_face_run = json.load(open(faces_path))
hr_faces = {(o["name"], o["face"]): o for o in per_face_run["objects"]}
ref_faces = {(f["object"], f["face"]): f for f in json.load(open(face_ref_path))["faces"]}
ref_source = json.load(open(face_ref_path)).get("photons", "?")
for (name, k), face in zip(((f[0], k) for f, k in zip(faces, face_index)), faces):
    got = hr_faces[(name, k)]["area"]
    if abs(got / face[3] - 1) > 1e-3:
        sys.exit(f"{name}#{k}: strahl's face has {got} m², the MGF's {face[3]}: "
                 "the faces are not numbered alike")
print()
print(f"Per face (strahl `--per-face`, the same options, solver "
      f"{per_face_run['stats']['seconds']:.3f} s; reference: the light model at "
      f"{ref_source} photons, {face_ref_path.split('/')[-1]}, 1σ per face):")
print()
print("| face | area m² | RenderPark Galerkin | strahl hierarchical | reference ± 1σ "
      "| RenderPark / ref − 1 | strahl HR / ref − 1 |")
print("|---|---|---|---|---|---|---|")
worst = {"RenderPark": [], "strahl": []}
for face, k in zip(faces, face_index):
    name, area = face[0], face[3]
    if name == "light":
        continue
    r = ref_faces[(name, k)]
    reflected_ref = [i - a for i, a in zip(r["incident_power"], r["absorbed_power"])]
    rho = [(i - a) / i for i, a in zip(r["incident_power"], r["absorbed_power"])]
    y_ref = luminance(reflected_ref) / area
    sigma = luminance([p * e for p, e in zip(rho, r["incident_power_standard_error"])]) / area
    y_hr = luminance(hr_faces[(name, k)]["reflected_power"]) / area
    rpk_area, weighted = face_sums[(name, k)]
    if rpk_area > 0:
        y_rpk = luminance([w / rpk_area * math.pi for w in weighted])
        rpk_cell, rpk_dev = f"{y_rpk:.4f}", f"{y_rpk / y_ref - 1:+.2%}"
        worst["RenderPark"].append(y_rpk / y_ref - 1)
    else:
        rpk_cell, rpk_dev = "?", "?"
    worst["strahl"].append(y_hr / y_ref - 1)
    print(f"| {name}#{k} | {area:.5f} | {rpk_cell} | {y_hr:.4f} | {y_ref:.4f} ± {sigma / y_ref:.2%} "
          f"| {rpk_dev} | {y_hr / y_ref - 1:+.2%} |")
print()
for prog, devs in worst.items():
    if devs:
        rms = math.sqrt(sum(d * d for d in devs) / len(devs))
        print(f"{prog}: {len(devs)} faces, worst {max(devs, key=abs):+.2%}, RMS {rms:.2%}")
EOF
