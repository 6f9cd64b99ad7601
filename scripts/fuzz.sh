#!/usr/bin/env bash
# Fuzzes strahl's readers of untrusted input with libFuzzer (cargo-fuzz, nightly Rust):
#   scene_toml  the TOML scene loader and the world built from it
#   obj_mtl     the OBJ importer with its MTL library
#   mgf         the MGF reader with an included file
#   gltf        the glTF importer (JSON and binary)
#   texture     the PPM/PGM/PNG/JPEG texture reader
#   cli_args    the command line's arguments-to-options step
#
# Usage: scripts/fuzz.sh SECONDS [TARGET...]   (default: every target, SECONDS each)
#
# Each target starts from the seeds in fuzz/corpus/TARGET and keeps what it learns in
# fuzz/work/TARGET (not committed). A crash, a hang (an input taking over 10 s) or an
# allocation over 2 GB stops the target and leaves the input in fuzz/artifacts/TARGET;
# the script then exits non-zero. Install once: `cargo install cargo-fuzz` and
# `rustup toolchain install nightly`.
set -euo pipefail

if [[ $# -lt 1 || ! $1 =~ ^[0-9]+$ ]]; then
    echo "usage: $0 SECONDS [TARGET...]" >&2
    exit 2
fi
seconds=$1
shift
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
    targets=(scene_toml obj_mtl mgf gltf texture cli_args)
fi

cd "$(dirname "$0")/../fuzz"
failed=0
for target in "${targets[@]}"; do
    # The targets that read files write them to a scratch folder under the system's
    # temporary folder: here that is fuzz/work/tmp-TARGET, removed when the target ends.
    scratch="$PWD/work/tmp-$target"
    mkdir -p "work/$target" "corpus/$target" "$scratch"
    echo "== $target: $seconds s"
    if ! TMPDIR="$scratch" cargo +nightly fuzz run "$target" "work/$target" "corpus/$target" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
        -print_final_stats=1; then
        echo "== $target: FAILED (input in fuzz/artifacts/$target)" >&2
        failed=1
    fi
    rm -rf "$scratch"
done
exit $failed
