#!/usr/bin/env bash
# compare-embree.sh: strahl's BVH against Embree's single-ray API, side by side.
#
# What it does
#   Compiles scripts/compare-embree.c (gcc -O3 -march=native -ffp-contract=off, against the
#   system's Embree 3) into a temporary folder, then runs `strahl bench SCENE --rays SET
#   --threads 1` and the Embree program (one thread, build quality HIGH, and MEDIUM unless
#   MEDIUM=0) alternately, RUNS repetitions each (default 5) for both ray sets (primary and
#   random), flipping the order within each repetition so that load from elsewhere hits both
#   alike. One untimed run of each comes first (it reads the scene into the page cache). Both
#   programs trace the same triangles (strahl's, zero-area ones dropped) and the same rays
#   (regenerated bit for bit in C; see the header of compare-embree.c), one ray at a time on one
#   thread, and report the fastest of REPEAT passes (default 3) per process. It prints a
#   Markdown table of medians, ranges (min–max over the runs) and the ratio strahl/Embree
#   (of the medians, with the range of the run-by-run ratios of one repetition), then every run.
#   Build: seconds, ratio < 1 means strahl builds faster. Closest and any hit: Mrays/s, ratio > 1
#   means strahl traces faster. The hit counts of both are checked to agree.
#
# How to run (from anywhere; needs a release build of strahl and Embree 3's headers):
#   apt-get install libembree-dev          # Debian: Embree 3 and its headers
#   cargo build --release
#   scripts/compare-embree.sh path/to/conference.obj [RUNS]
#   Environment: STRAHL (default: target/release/strahl of this repository), REPEAT (passes per
#   process, default 3), MEDIUM=0 (skip Embree's MEDIUM build quality), CC (default gcc).
#   Nothing outside this repository is used at run time except the scene file given, the
#   system's Embree and standard tools (gcc, awk, sed, sort, git for the commit).
#
# Scene
#   The Grynberg & Ward conference room, conference.obj (331,179 triangles, of which strahl keeps
#   277,552 with area): Anat Grynberg and Greg Ward (LBL, c. 1991), re-modelled by Kenzie Lamar,
#   distributed by Morgan McGuire's Computer Graphics Archive (https://casual-effects.com/data/,
#   "License: Public Domain"); not kept in this repository. The copy measured in
#   docs/PERFORMANCE.md is geometry only (positions and triangles, 194,399 vertices), converted
#   to OBJ from the C-array dump conference.zip in github.com/taqu/BoundingVolumeHierarchy at
#   62fa086 (Unlicense); it has McGuire's triangle count. Any OBJ whose faces are triangles or
#   convex planar polygons works.
set -euo pipefail

usage() {
    echo "usage: $0 SCENE.obj [RUNS]   (env: STRAHL, REPEAT, MEDIUM=0, CC)" >&2
    exit 2
}
[ $# -ge 1 ] && [ $# -le 2 ] || usage
scene=$1
runs=${2:-5}
repeat=${REPEAT:-3}
medium=${MEDIUM:-1}
cc=${CC:-gcc}
[ -f "$scene" ] || { echo "$0: no such scene file: $scene" >&2; exit 1; }
case $runs in '' | *[!0-9]* | 0) usage ;; esac

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
strahl=${STRAHL:-$repo/target/release/strahl}
[ -x "$strahl" ] || { echo "$0: $strahl is missing: run 'cargo build --release' first" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A copy, so that a rebuild during the runs cannot mix two binaries in one table.
cp "$strahl" "$tmp/strahl"
strahl_built=$(date -u -r "$strahl" '+%Y-%m-%d %H:%M UTC')
strahl=$tmp/strahl
embree=$tmp/compare-embree
"$cc" -O3 -march=native -ffp-contract=off -o "$embree" "$repo/scripts/compare-embree.c" \
    -lembree3 -lm

qualities=(high)
[ "$medium" = 0 ] || qualities+=(medium)

# One record per run: program set repetition build closest_mrays any_mrays closest_hits any_hits
results=$tmp/results.tsv
: > "$results"
field() { # field JSON KEY: the number after "KEY": (first occurrence)
    sed -n "s/.*\"$2\":\([-0-9.eE+]*\).*/\1/p" <<< "$1"
}
query() { # query JSON closest_hit|any_hit KEY
    sed -n "s/.*\"$2\":{[^}]*\"$3\":\([-0-9.eE+]*\).*/\1/p" <<< "$1"
}
run_one() { # run_one PROGRAM SET REPETITION
    local prog=$1 set=$2 rep=$3 json
    if [ "$prog" = strahl ]; then
        json=$("$strahl" bench "$scene" --rays "$set" --threads 1 --repeat "$repeat")
    else
        json=$("$embree" "$scene" --rays "$set" --quality "${prog#embree-}" --repeat "$repeat")
        embree_version=$(sed -n 's/.*"embree_version":"\([^"]*\)".*/\1/p' <<< "$json")
    fi
    [ "$rep" = 0 ] && return 0
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$prog" "$set" "$rep" \
        "$(field "$json" build_seconds)" \
        "$(query "$json" closest_hit mrays_per_second)" "$(query "$json" any_hit mrays_per_second)" \
        "$(query "$json" closest_hit hits)" "$(query "$json" any_hit hits)" >> "$results"
}

programs=(strahl)
for q in "${qualities[@]}"; do programs+=("embree-$q"); done

commit=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [ "$commit" != unknown ] && ! git -C "$repo" diff --quiet HEAD -- src Cargo.toml Cargo.lock; then
    commit="$commit (with uncommitted changes to src/ or Cargo files)"
fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
load_before=$(cut -d ' ' -f 1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M UTC')

echo "warm-up (untimed) ..." >&2
for prog in "${programs[@]}"; do run_one "$prog" primary 0; done
for rep in $(seq 1 "$runs"); do
    echo "repetition $rep of $runs ..." >&2
    for set in primary random; do
        order=("${programs[@]}")
        if [ $((rep % 2)) = 0 ]; then # reversed order on even repetitions
            order=()
            for ((i = ${#programs[@]} - 1; i >= 0; i--)); do order+=("${programs[i]}"); done
        fi
        for prog in "${order[@]}"; do run_one "$prog" "$set" "$rep"; done
    done
done
load_after=$(cut -d ' ' -f 1-3 /proc/loadavg)

# stats PROGRAM SET COLUMN: "median min max" (SET "all" pools both ray sets)
stats() {
    awk -F '\t' -v p="$1" -v s="$2" -v c="$3" '$1 == p && (s == "all" || $2 == s) { print $c }' \
        "$results" | sort -g | awk '{ v[NR] = $1 } END {
            m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
            print m, v[1], v[NR] }'
}
# ratio_range PROGRAM SET COLUMN: min and max over repetitions of strahl / PROGRAM
ratio_range() {
    awk -F '\t' -v p="$1" -v s="$2" -v c="$3" '
        (s == "all" || $2 == s) && $1 == "strahl" { a[$2 " " $3] = $c }
        (s == "all" || $2 == s) && $1 == p { b[$2 " " $3] = $c }
        END { lo = 1e30; hi = -1e30
              for (k in a) if (k in b) { r = a[k] / b[k]; if (r < lo) lo = r; if (r > hi) hi = r }
              printf "%.2f–%.2f", lo, hi }' "$results"
}
cell() { # cell "median min max" DECIMALS
    awk -v d="$2" '{ printf "%.*f (%.*f–%.*f)", d, $1, d, $2, d, $3 }' <<< "$1"
}
row() { # row LABEL SET COLUMN DECIMALS
    local label=$1 set=$2 col=$3 dec=$4 s line
    s=$(stats strahl "$set" "$col")
    line="| $label | $(cell "$s" "$dec")"
    for q in "${qualities[@]}"; do
        local e
        e=$(stats "embree-$q" "$set" "$col")
        line+=" | $(cell "$e" "$dec") | $(awk -v a="${s%% *}" -v b="${e%% *}" \
            'BEGIN { printf "%.2f", a / b }') ($(ratio_range "embree-$q" "$set" "$col"))"
    done
    echo "$line |"
}

echo
echo "strahl $commit (binary built $strahl_built) against Embree ${embree_version:-?} (${qualities[*]}); $started"
echo "scene: $scene; $runs runs per program and ray set, each the fastest of $repeat passes; one thread"
echo "machine: $cpu, $(nproc) CPUs; load average before $load_before, after $load_after"
echo
header="| figure | strahl median (range)"
rule="|---|---"
for q in "${qualities[@]}"; do
    Q=$(tr '[:lower:]' '[:upper:]' <<< "$q")
    header+=" | Embree $Q median (range) | strahl / Embree $Q (run-by-run range)"
    rule+="|---|---"
done
echo "$header |"
echo "$rule|"
row "build, s (both ray sets' runs)" all 4 3
row "closest hit, primary, Mrays/s" primary 5 2
row "any hit, primary, Mrays/s" primary 6 2
row "closest hit, random, Mrays/s" random 5 2
row "any hit, random, Mrays/s" random 6 2
echo
echo "Build: ratio < 1 means strahl builds faster. Rays: ratio > 1 means strahl traces faster."

# The hit counts must agree (same rays, same triangles; a ray grazing an edge could in principle
# be decided differently by the two triangle tests).
for set in primary random; do
    counts=$(awk -F '\t' -v s="$set" '$2 == s { print $1 ": closest " $7 ", any " $8 }' \
        "$results" | sort -u)
    echo "hits, $set rays: $(paste -sd ';' <<< "$counts" | sed 's/;/; /g')"
    if [ "$(sed 's/^[^:]*: //' <<< "$counts" | sort -u | wc -l)" != 1 ]; then
        echo "WARNING: the hit counts of the $set rays differ between the programs or runs"
    fi
done

echo
echo "Every run (program, ray set, repetition, build s, closest Mrays/s, any Mrays/s):"
awk -F '\t' '{ printf "  %-13s %-7s %2d  %.3f  %6.2f  %6.2f\n", $1, $2, $3, $4, $5, $6 }' "$results"
