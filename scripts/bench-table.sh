#!/usr/bin/env bash
# The simulation table of docs/simulation.md: every scene with every built-in groom (and the Ratboy mohawk baked
# with 2 follow hairs when the shared data is present), as Markdown rows from tressvk-bench, on whatever Vulkan
# device is selected (lavapipe when run after `. scripts/lavapipe-env.sh`).
#
#   scripts/bench-table.sh [BUILD_DIR] [GUIDES] [FRAMES]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build/ci}
GUIDES=${2:-256}
FRAMES=${3:-120}
BENCH="$BUILD/engine/tressvk-bench"
DATA=${TRESSVK_DATA_DIR:-$ROOT/../shared/data}
echo "| groom | guides x N (+follows) | scene | steps/frame | GPU ms/frame | step error max | trajectory rms | stretch max | NaN/exploded |"
echo "|---|---|---|---|---|---|---|---|---|"
for groom in straight curly long128; do
  g=$GUIDES; [ "$groom" = long128 ] && g=$((GUIDES / 4))
  for scene in settle shake run teleport wind hitch far; do
    "$BENCH" compare --builtin "$groom" --guides "$g" --scene "$scene" --frames "$FRAMES" --warmup 10 --table-row
  done
done
if [ -f "$DATA/tressfx/ratboy/Ratboy_mohawk.tfx" ]; then
  tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
  "$BUILD/baker/tressvk-bake" "$DATA/tressfx/ratboy/Ratboy_mohawk.tfx" --bones "$DATA/tressfx/ratboy/Ratboy_mohawk.tfxbone" \
    --follow 2 -o "$tmp/mohawk.tvkhair" --quiet
  for scene in settle shake run teleport wind hitch far; do
    "$BENCH" compare --asset "$tmp/mohawk.tvkhair" --scene "$scene" --frames "$FRAMES" --warmup 10 --table-row
  done
fi
