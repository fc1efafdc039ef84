#!/usr/bin/env bash
# The README's "Measured" tables on a real GPU, in one command (portable binaries, cmake --preset portable):
#
#   scripts/gpu-readme.sh OUTDIR [BINDIR [DATADIR]]
#
# BINDIR holds tressvk-bench, tressvk-bake and libtressvk.so.0 (default: build/portable). DATADIR holds
# tressfx/ratboy/Ratboy_mohawk.tfx (+ .tfxbone), baked here with 2 follow hairs for the simulation rows and 4 for the
# rendering row (default: ../shared/data). Runs the simulation rows as docs/simulation.md's kernel table does
# (scripts/gpu-perf.sh with MODELS=1 PATHS=default: `tressvk-bench perf --scene shake`, 240 and 60 Hz, the step error
# after the timed frames) into OUTDIR/sim, the two rendering rows as docs/rendering.md does (scripts/gpu-render-bench.sh,
# 1920x1080, no timestamps inside the calls, the error against the brute-force reference) into OUTDIR/render, the
# host's CPU time per frame (`tressvk-bench perf`, 1 and 64 instances of the simulation rows' Ratboy, moved by their
# transform and with their bones driven, --bones; HOST_ROUNDS rounds, 3 by default) into OUTDIR/host, then prints the
# three tables
# (scripts/readme-tables.py).
set -euo pipefail
OUT=${1:?usage: gpu-readme.sh OUTDIR [BINDIR [DATADIR]]}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${2:-}
DATA=${3:-$ROOT/../shared/data}
mkdir -p "$OUT/sim" "$OUT/render" "$OUT/host"
MODELS=1 PATHS=default "$ROOT/scripts/gpu-perf.sh" "$OUT/sim" "$BIN" "$DATA" > "$OUT/sim.log" 2>&1 ||
  echo "gpu-perf.sh exited $? (see $OUT/sim.log)"
ROWS='^(ratboy4|100k)-compute-1080p$' "$ROOT/scripts/gpu-render-bench.sh" "$OUT/render" "$BIN" "$DATA" \
  > "$OUT/render.log" 2>&1 || echo "gpu-render-bench.sh exited $? (see $OUT/render.log)"
. "$ROOT/scripts/gpu-tools.sh"
gpu_tools "$ROOT" "$BIN"
MOHAWK="$OUT/sim/mohawk.tvkhair"  # baked by gpu-perf.sh with 2 follows and the .tfxbone's bones
if [ -f "$MOHAWK" ]; then
  for r in $(seq "${HOST_ROUNDS:-3}"); do  # the CPU time wanders between runs: the table takes the median
    for n in 1 64; do
      for bones in "" --bones; do
        name="ratboy-$n${bones:+-bones}-r$r"
        timeout 200 "$BENCH" perf --asset "$MOHAWK" --instances "$n" $bones --scene shake --frames 300 --warmup 60 \
          --error-frames 1 --json "$OUT/host/$name.json" > "$OUT/host/$name.log" 2>&1 ||
          echo "host row $name failed (see $OUT/host)"
      done
    done
  done
fi
python3 "$ROOT/scripts/readme-tables.py" "$OUT" | tee "$OUT/readme-tables.md"
