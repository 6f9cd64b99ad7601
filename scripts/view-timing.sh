#!/usr/bin/env bash
# Times `strahl view` in headless Chromium (Debian's, or STRAHL_CHROMIUM) on the real clock:
# frame times while orbiting and the time from a move to the preview and the final solution
# on screen. Installs playwright-core into a temporary folder (npm registry).
#   [MOVES=N] scripts/view-timing.sh [SCENE] [FRAMES] [NAME:X,Y,Z] [-- VIEW OPTIONS...]
# e.g. scripts/view-timing.sh cornell 300 light:0,0,0.1 (MOVES: the moves made, 3 unless set)
set -euo pipefail
scene=${1:-cornell}
frames=${2:-300}
move=${3:-light:0,0,0.1}
shift $(( $# < 3 ? $# : 3 )); [[ ${1:-} == -- ]] && shift
root=$(cd "$(dirname "$0")/.." && pwd)
cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p strahl-cli
work=$(mktemp -d)
trap 'kill "$viewer" 2>/dev/null || true; rm -rf "$work"' EXIT
(cd "$work" && npm init -y >/dev/null && npm install --silent playwright-core@1 >/dev/null)
cp "$root/scripts/view-timing.mjs" "$work/"
"$root/target/release/strahl" view "$scene" --port 0 -q "$@" >"$work/address" &
viewer=$!
until grep -q http "$work/address" 2>/dev/null; do sleep 0.1; done
address=$(sed -e 's|.*http://||' -e 's|/.*||' "$work/address")
node "$work/view-timing.mjs" "$address" "$frames" "$move"
