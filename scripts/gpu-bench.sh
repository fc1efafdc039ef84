#!/usr/bin/env bash
# Runs the simulation benchmark matrix on a real GPU with portable binaries (cmake --preset portable), and writes
# one JSON file per configuration plus a summary table into OUTDIR.
#
#   scripts/gpu-bench.sh OUTDIR [BINDIR]
#   WARM=1 scripts/gpu-bench.sh OUTDIR [BINDIR]   # the H200 table of docs/simulation.md, as Markdown rows
#
# WARM=1 times 300 frames after 60 warm-up frames with the step error every 30th frame and no free-running
# reference, so the GPU stays busy and at full clock between frames. MOHAWK=FILE adds the baked Ratboy mohawk.
# BINDIR holds tressvk-bench and libtressvk.so.0 (default build/portable/engine and build/portable/plugin).
# On a machine without a Vulkan loader, install the loader first (scripts/gpu-bench.sh does not), e.g. by
# unpacking Debian's libvulkan1 and the glvnd libraries, and point VK_DRIVER_FILES at the driver's ICD JSON.
set -euo pipefail
OUT=${1:?usage: gpu-bench.sh OUTDIR [BINDIR]}
BIN=${2:-}
mkdir -p "$OUT"
if [ -z "$BIN" ]; then
  ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  BIN="$ROOT/build/portable/engine"
  export LD_LIBRARY_PATH="$ROOT/build/portable/plugin:${LD_LIBRARY_PATH:-}"
else
  export LD_LIBRARY_PATH="$BIN:${LD_LIBRARY_PATH:-}"
fi
BENCH="$BIN/tressvk-bench"
FRAMES=${FRAMES:-120}

if [ "${WARM:-0}" = 1 ]; then
  W="--frames 300 --warmup 60 --step-error-every 30 --no-trajectory --table-row"
  {
    for scene in settle shake run hitch; do "$BENCH" compare --builtin curly --guides 4096 --scene "$scene" $W; done
    "$BENCH" compare --builtin straight --guides 4096 --scene shake $W
    "$BENCH" compare --builtin long128 --guides 1024 --scene shake $W
    if [ -f "${MOHAWK:-}" ]; then
      for scene in settle shake run; do "$BENCH" compare --asset "$MOHAWK" --scene "$scene" $W; done
    fi
    for g in 1024 16384 65536; do "$BENCH" compare --builtin curly --guides "$g" --scene shake $W; done
    for rate in 120 480; do "$BENCH" compare --builtin curly --guides 4096 --scene shake --step-rate "$rate" $W; done
  } | tee "$OUT/warm-table.md"
  exit 0
fi

run() {  # name, then bench arguments
  local name=$1; shift
  echo "== $name: $*" | tee -a "$OUT/summary.txt"
  "$BENCH" compare "$@" --frames "$FRAMES" --json "$OUT/$name.json" 2>&1 | tee -a "$OUT/summary.txt"
}

# Every scene with the default groom size (4096 guides x 32 vertices).
for scene in settle shake run teleport wind hitch far; do
  run "curly-4096-$scene" --builtin curly --guides 4096 --scene "$scene"
done
run "straight-4096-shake" --builtin straight --guides 4096 --scene shake
run "long128-1024-shake" --builtin long128 --guides 1024 --scene shake
if [ -f "${MOHAWK:-}" ]; then
  for scene in settle shake run; do run "ratboy-2follows-$scene" --asset "$MOHAWK" --scene "$scene"; done
fi
# Scaling with the guide count: the step error is sampled and the free-running reference skipped, so the CPU
# reference stays affordable.
for g in 1024 16384 65536; do
  run "curly-$g-shake" --builtin curly --guides "$g" --scene shake --step-error-every 25 --no-trajectory
done
# Cost versus accuracy: length iterations and the simulation step rate.
for it in 1 2 8; do
  run "curly-4096-shake-len$it" --builtin curly --guides 4096 --scene shake --length-iterations "$it" --step-error-every 5
done
for rate in 120 480; do
  run "curly-4096-shake-rate$rate" --builtin curly --guides 4096 --scene shake --step-rate "$rate" --step-error-every 5
done
echo "done: $OUT"
