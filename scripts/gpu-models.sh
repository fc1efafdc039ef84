#!/usr/bin/env bash
# The three simulation models' GPU time against their model error (docs/accuracy.md, "Which model, at which rate"),
# in one command:
#
#   scripts/gpu-models.sh OUTDIR [BINDIR]
#
# BINDIR holds tressvk-bench and libtressvk.so.0 (default: build/portable/{engine,plugin}). On the first GPU,
# `tressvk-bench sweep` for follow-the-leader (the default), the compliant and the conservative model
# (TRESSVK_SIM_MODEL), each on the curly and the straight built-in grooms, over RATES (default 60,120,240) x
# ITERATIONS local iterations (default 1,2), 1 length sweep, N 32, the four scenes; GUIDES guides timed (default
# 32768: 1 M guide vertices), the first 8 tracked against the converged reference of the same model ->
# OUTDIR/sweep-MODEL-GROOM.csv (MODELS, GROOMS pick a subset). Each sweep first keeps the GPU busy for WARMUP_MS
# (default 5000), then each setting until its frame time has settled (the sweep's warm-up; a fixed one left some of
# follow-the-leader's 60 Hz rows 2.5x slow: docs/simulation.md, "Slow rows in the sweep"). Then, where Debian's
# python3-matplotlib is there, scripts/plot-models.py draws
# OUTDIR/models.png and writes OUTDIR/models.md.
set -euo pipefail
OUT=${1:?usage: gpu-models.sh OUTDIR [BINDIR]}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$ROOT/scripts/gpu-tools.sh"
gpu_tools "$ROOT" "${2:-}"
mkdir -p "$OUT"
for groom in ${GROOMS:-curly straight}; do
  for model in ${MODELS:-follow-the-leader compliant conservative}; do
    echo "== $model, $groom"
    env_model=$model
    [ "$model" = follow-the-leader ] && env_model=
    TRESSVK_SIM_MODEL=$env_model "$BENCH" sweep --builtin "$groom" --guides "${GUIDES:-32768}" --error-guides 8 \
      --rates "${RATES:-60,120,240}" --local-iterations "${ITERATIONS:-1,2}" --length-iterations 1 --vertices 32 \
      --scenes settle,shake,run,wind --warmup-ms "${WARMUP_MS:-5000}" --csv "$OUT/sweep-$model-$groom.csv" 2>&1 | tee "$OUT/sweep-$model-$groom.log"
  done
done
if /usr/bin/python3 -c "import matplotlib" 2> /dev/null; then
  /usr/bin/python3 "$ROOT/scripts/plot-models.py" "$OUT" "$OUT/models.png" "$OUT/models.md"
  cat "$OUT/models.md"
else
  echo "python3-matplotlib not installed: plot with scripts/plot-models.py $OUT $OUT/models.png $OUT/models.md"
fi
echo "done in $SECONDS s: $OUT"
