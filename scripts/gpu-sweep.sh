#!/usr/bin/env bash
# The accuracy fronts and the hard-case table of docs/accuracy.md, in one command:
#
#   scripts/gpu-sweep.sh OUTDIR [BINDIR]
#
# BINDIR holds tressvk-bench and libtressvk.so.0 (default: build/portable/{engine,plugin}). Runs, on the first GPU:
#   1. `tressvk-bench hardcases` -> OUTDIR/hardcases.md (the table) and hardcases.json;
#   2. `tressvk-bench sweep` over step rate x local iterations x length iterations x vertices per strand on settle,
#      shake, run and wind -> OUTDIR/sweep.csv, sweep.json (SWEEP_ARGS replaces the grid options, e.g.
#      SWEEP_ARGS=--around-default for the default setting and one axis changed at a time);
#   3. when Debian's python3-matplotlib is there, the fronts and the budget table: OUTDIR/pareto.png, pareto.md
#      (otherwise run scripts/plot-pareto.py OUTDIR/sweep.json OUTDIR/pareto.png OUTDIR/pareto.md elsewhere).
# GROOM (default curly), GUIDES (timed groom, default 1024), ERROR_GUIDES (default 8), FRAMES (default 120) size it.
set -euo pipefail
OUT=${1:?usage: gpu-sweep.sh OUTDIR [BINDIR]}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$ROOT/scripts/gpu-tools.sh"
gpu_tools "$ROOT" "${2:-}"
mkdir -p "$OUT"

echo "== hard cases"
"$BENCH" hardcases --json "$OUT/hardcases.json" > "$OUT/hardcases.md" 2> "$OUT/hardcases.err" || echo "hardcases exited $? (see $OUT/hardcases.md)"
cat "$OUT/hardcases.md"

echo "== sweep"
# shellcheck disable=SC2086
"$BENCH" sweep --builtin "${GROOM:-curly}" --guides "${GUIDES:-1024}" --error-guides "${ERROR_GUIDES:-8}" \
  --frames "${FRAMES:-120}" ${SWEEP_ARGS:-} --csv "$OUT/sweep.csv" --json "$OUT/sweep.json" 2>&1 | tee "$OUT/sweep.log"

if /usr/bin/python3 -c "import matplotlib" 2> /dev/null; then
  /usr/bin/python3 "$ROOT/scripts/plot-pareto.py" "$OUT/sweep.json" "$OUT/pareto.png" "$OUT/pareto.md"
  cat "$OUT/pareto.md"
else
  echo "python3-matplotlib not installed: plot with scripts/plot-pareto.py $OUT/sweep.json $OUT/pareto.png $OUT/pareto.md"
fi
echo "done in $SECONDS s: $OUT"
