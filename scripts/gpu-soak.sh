#!/usr/bin/env bash
# The GPU soak of docs/reliability.md with portable binaries (cmake --preset portable): tressvk-bench soak on the
# Ratboy mohawk with 4 follow hairs per guide (baked here from the TressFX files) and on the bundled built-in
# groom, each for SOAK_SECONDS (default 3600), with 4 instances churning. Writes a JSON file and the report per
# groom into OUTDIR; exits non-zero if either run failed (NaN strands, resets, stretch, memory growth).
#
#   scripts/gpu-soak.sh OUTDIR [BINDIR]
#   SOAK_SECONDS=600 scripts/gpu-soak.sh /tmp/soak
#
# BINDIR holds tressvk-bench, tressvk-bake and libtressvk.so.0 (default: build/portable/{engine,baker,plugin}).
# RATBOY_DIR is the folder with Ratboy_mohawk.tfx and .tfxbone (default ../shared/data/tressfx/ratboy); without
# it only the built-in groom runs. On a machine without a Vulkan loader, install one first (see gpu-bench.sh).
set -euo pipefail
OUT=${1:?usage: gpu-soak.sh OUTDIR [BINDIR]}
BIN=${2:-}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mkdir -p "$OUT"
. "$ROOT/scripts/gpu-tools.sh"
gpu_tools "$ROOT" "$BIN"
SECS=${SOAK_SECONDS:-3600}
RATBOY=${RATBOY_DIR:-$ROOT/../shared/data/tressfx/ratboy}
status=0

if [ -f "$RATBOY/Ratboy_mohawk.tfx" ]; then
  "$BAKE" "$RATBOY/Ratboy_mohawk.tfx" --bones "$RATBOY/Ratboy_mohawk.tfxbone" --follow 4 -o "$OUT/ratboy_4follows.tvkhair"
  echo "== ratboy + 4 follows, $SECS s" | tee "$OUT/ratboy.txt"
  "$BENCH" soak --asset "$OUT/ratboy_4follows.tvkhair" --seconds "$SECS" --instances 4 \
    --json "$OUT/ratboy.json" 2>&1 | tee -a "$OUT/ratboy.txt" || status=1
else
  echo "gpu-soak: $RATBOY/Ratboy_mohawk.tfx not found; skipping the Ratboy soak" >&2
fi
echo "== built-in curly, 4096 guides, $SECS s" | tee "$OUT/curly.txt"
"$BENCH" soak --builtin curly --guides 4096 --seconds "$SECS" --instances 4 \
  --json "$OUT/curly.json" 2>&1 | tee -a "$OUT/curly.txt" || status=1
exit $status
