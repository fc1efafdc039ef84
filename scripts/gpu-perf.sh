#!/usr/bin/env bash
# The simulation speed tables and scaling sweep of docs/simulation.md ("Speed: which kernel runs"), with
# `tressvk-bench perf` (frames in flight, no readback between timed frames, no plugin timestamps, a copy kernel moving
# the frame's bytes timed in the same run, the step error measured after the timed frames), for both simulation paths:
#
#   scripts/gpu-perf.sh OUTDIR [BINDIR [DATADIR]]
#   python3 scripts/plot-sim-perf.py OUTDIR docs/images/sim-perf.png
#
# BINDIR holds tressvk-bench, tressvk-bake and libtressvk.so.0 (default: build/portable). DATADIR holds
# tressfx/ratboy/Ratboy_mohawk.tfx (+ .tfxbone) for the Ratboy row (default: data/ beside the repository).
# Writes one JSON file per run, table.md (the issue's table) and sweep.md. Single tables instead: MODELS=1, SLEEP=1,
# CROWD=1, CROWD_RULE=1, CHOICE=1, SPLIT=1, WAVES=1, REFINE=1, TERMS=1, FRAME_WG=1, RUNS=1 (each described where it runs). BUDGET (seconds, default 400) stops
# starting new sweep runs once spent, so that the whole script fits a bounded GPU session; rows not run are absent.
set -euo pipefail
OUT=${1:?usage: gpu-perf.sh OUTDIR [BINDIR [DATADIR]]}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${2:-}
DATA=${3:-$ROOT/../data}
mkdir -p "$OUT"
. "$ROOT/scripts/gpu-tools.sh"
gpu_tools "$ROOT" "$BIN"
BUDGET=${BUDGET:-400}
MOHAWK=${MOHAWK:-$OUT/mohawk.tvkhair}  # a baked Ratboy mohawk with 2 follows; baked from DATADIR when absent
RATBOY="$DATA/tressfx/ratboy/Ratboy_mohawk.tfx"
if [ ! -f "$MOHAWK" ] && [ -f "$RATBOY" ]; then
  BONES=()
  [ -f "${RATBOY%.tfx}.tfxbone" ] && BONES=(--bones "${RATBOY%.tfx}.tfxbone")
  "$BAKE" "$RATBOY" "${BONES[@]}" --follow 2 -o "$MOHAWK" > "$OUT/bake.log" 2>&1
fi

# The header of the Markdown table that `perf --table-row` rows fill (the path column names the kernel that ran).
table_header() {
  echo "| groom | guide vertices | step rate | path (kernel) | µs/frame (median) | p99 | GB/s achieved (copy) | dispatches/frame | step error |"
  echo "|---|---|---|---|---|---|---|---|---|"
}

perf() {  # json name, path (TRESSVK_SIM_PATH: default = unset, runs, fused, passes), then bench arguments; path
          # "compliant" = the compliant model's lane kernel, "conservative" its conservative local shape
  local name=$1 path=$2 model= run=; shift 2
  [ "$path" = compliant ] && { model=compliant; path=; }
  [ "$path" = conservative ] && { model=conservative; path=; }
  [ "$path" = default ] && path=
  case "$path" in runs4) path=runs run=4 ;; runs8) path=runs run=8 ;; esac
  TRESSVK_SIM_MODEL=$model TRESSVK_SIM_PATH=$path TRESSVK_SIM_RUN=$run timeout "${RUN_TIMEOUT:-150}" "$BENCH" perf "$@" --json "$OUT/$name.json" --table-row 2> "$OUT/$name.err" ||
    echo "| $name | failed: $(tail -1 "$OUT/$name.err") |"
}

# The issue's table for the given paths (prefix of the JSON names, then paths): Ratboy mohawk + 2 follows, curly
# 32,768 x 32 (1M) and 131,072 x 32 (4M guide vertices), at 60 and 240 Hz.
T="--scene shake --frames 300 --warmup 60 --error-frames 2"
table() {
  local prefix=$1 rate path; shift
  table_header
  for rate in 60 240; do
    for path in "$@"; do
      [ -f "$MOHAWK" ] && perf "$prefix-ratboy-$path-$rate" "$path" --asset "$MOHAWK" --step-rate "$rate" $T
      perf "$prefix-curly1M-$path-$rate" "$path" --builtin curly --guides 32768 --step-rate "$rate" $T
      perf "$prefix-curly4M-$path-$rate" "$path" --builtin curly --guides 131072 --step-rate "$rate" $T
    done
  done
}

# BY_MODEL=1: each model at its own rate and iterations (no --step-rate or --local-iterations: what the settings leave
# to the model, docs/integration.md "Each model at its own rate"): Ratboy, curly 1 M and 4 M on follow-the-leader and
# the conservative model, then the conservative model's hard cases at its own settings. Then stop.
if [ "${BY_MODEL:-0}" = 1 ]; then
  {
    table_header
    for path in default conservative; do
      [ -f "$MOHAWK" ] && perf "bymodel-ratboy-$path" "$path" --asset "$MOHAWK" $T
      perf "bymodel-curly1M-$path" "$path" --builtin curly --guides 32768 $T
      perf "bymodel-curly4M-$path" "$path" --builtin curly --guides 131072 $T
    done
  } | tee "$OUT/bymodel.md"
  "$BENCH" hardcases --model conservative --converged-rate 960 --json "$OUT/bymodel-hardcases.json" |
    tee "$OUT/bymodel-hardcases.md" || true
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# MODELS=1: only the kernel table (PATHS, default: follow-the-leader's default choice, its one-thread kernel, the
# compliant model's lane kernel, each with its step error against the reference of its own model), then stop.
if [ "${MODELS:-0}" = 1 ]; then
  table models ${PATHS:-default fused compliant} | tee "$OUT/models.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# SLEEP=1: only the sleeping table (docs/simulation.md, "Sleeping"): each groom moving (`shake`) and at rest under a
# still head (`settle`, 900 warm-up frames to come to rest) with the default sleep_below and with sleeping off, at
# 240 Hz on the default path; the JSON's guides_asleep counts the sleeping guides after the timed frames. Then the
# idle-instance rows ("Idle instances"): Sintel (baked --scale 0.0046) and TestHair1 (--units cm) from DATADIR and
# the conservative model's Ratboy, `settle` after 1,500 warm-up frames. Then stop.
if [ "${SLEEP:-0}" = 1 ]; then
  Z="--step-rate 240 --frames 300 --warmup 900 --error-frames 2"
  {
    table_header
    for g in ratboy straight1M curly1M curly4M; do
      case $g in
        ratboy) [ -f "$MOHAWK" ] || continue; G=(--asset "$MOHAWK") ;;
        straight1M) G=(--builtin straight --guides 32768) ;;
        curly1M) G=(--builtin curly --guides 32768) ;;
        curly4M) G=(--builtin curly --guides 131072) ;;
      esac
      perf "sleep-$g-shake" default "${G[@]}" --scene shake $Z
      perf "sleep-$g-settle" default "${G[@]}" --scene settle $Z
      perf "sleep-$g-settle-off" default "${G[@]}" --scene settle --sleep-below 0 $Z
    done
    I="--step-rate 240 --frames 300 --warmup 1500 --error-frames 2"
    SINTEL_SRC="$DATA/sintel/sintel_hair.tfx" TESTHAIR1_SRC="$DATA/tressfx/testhair1/TestHair1.tfx"
    [ -f "$SINTEL_SRC" ] && "$BAKE" "$SINTEL_SRC" --scale 0.0046 -o "$OUT/sintel.tvkhair" > "$OUT/bake_sintel.log" 2>&1 &&
      perf "idle-sintel-settle" default --asset "$OUT/sintel.tvkhair" --scene settle $I
    [ -f "$TESTHAIR1_SRC" ] && "$BAKE" "$TESTHAIR1_SRC" --units cm -o "$OUT/testhair1.tvkhair" > "$OUT/bake_testhair1.log" 2>&1 &&
      perf "idle-testhair1-settle" default --asset "$OUT/testhair1.tvkhair" --scene settle $I
    [ -f "$MOHAWK" ] && perf "idle-ratboy-conservative-settle" conservative --asset "$MOHAWK" --scene settle $I
  } | tee "$OUT/sleep.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# CROWD=1: only the crowd table (docs/simulation.md, "A crowd"): K = 1, 2, 4, ..., 64 instances of the Ratboy mohawk in
# one tressvk_cmd_simulate (perf --instances), in runs of 4, runs of 8 and the one-thread kernel, at 240 and 60 Hz;
# then /usr/bin/python3 scripts/plot-crowd.py OUTDIR docs/images/sim-crowd.png.
if [ "${CROWD:-0}" = 1 ]; then
  C="--scene shake --frames 200 --warmup 60 --error-frames 1"
  {
    table_header
    for rate in 240 60; do
      for k in 1 2 4 8 16 32 64; do
        for path in runs4 runs8 fused; do
          [ -f "$MOHAWK" ] && perf "crowd-$k-$path-$rate" "$path" --asset "$MOHAWK" --instances "$k" --step-rate "$rate" $C
        done
      done
    done
  } | tee "$OUT/crowd.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# CROWD_RULE=1: only the crowd rule's table (docs/simulation.md, "A crowd": the default, which picks the kernel by the
# whole call, against each instance's own run kernel forced with TRESSVK_SIM_PATH=runs).
if [ "${CROWD_RULE:-0}" = 1 ]; then
  C="--scene shake --frames 200 --warmup 60 --error-frames 1"
  both() { local name=$1; shift; perf "$name-default" default "$@" $C; perf "$name-own" runs "$@" $C; }
  {
    table_header
    if [ -f "$MOHAWK" ]; then
      for k in 1 4 6 8 16 64; do both "rule-ratboy-$k-240" --asset "$MOHAWK" --instances "$k"; done
      for k in 6 8 64; do both "rule-ratboy-$k-120" --asset "$MOHAWK" --instances "$k" --step-rate 120; done
      both "rule-ratboy-8-60" --asset "$MOHAWK" --instances 8 --step-rate 60
    fi
    both "rule-curly4096x4-240" --builtin curly --guides 4096 --instances 4
    both "rule-curly8192x2-240" --builtin curly --guides 8192 --instances 2
    both "rule-curly8192x4-240" --builtin curly --guides 8192 --instances 4
    both "rule-curly2221x32-120" --builtin curly --guides 2221 --instances 32 --step-rate 120
  } | tee "$OUT/crowd-rule.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# CHOICE=1: only the model choice's cost (docs/accuracy.md, "The settled look against the settings"): the default
# (follow-the-leader, 240 Hz, 2 local iterations) against the conservative model through the setting (--model), at
# the defaults and at its recommended 120 Hz with 1 iteration, on Ratboy, 1 M and 4 M guide vertices; Ratboy at rest.
if [ "${CHOICE:-0}" = 1 ]; then
  REC="--model conservative --step-rate 120 --local-iterations 1"
  {
    table_header
    if [ -f "$MOHAWK" ]; then
      perf "choice-ratboy-default" default --asset "$MOHAWK" $T
      perf "choice-ratboy-conservative" default --asset "$MOHAWK" --model conservative $T
      perf "choice-ratboy-conservative120" default --asset "$MOHAWK" $REC $T
      perf "choice-ratboy-ftl120" default --asset "$MOHAWK" --step-rate 120 --local-iterations 1 $T
      perf "choice-ratboy-default-rest" default --asset "$MOHAWK" --scene settle --warmup 1500
      perf "choice-ratboy-conservative120-rest" default --asset "$MOHAWK" --scene settle --warmup 1500 $REC
    fi
    perf "choice-curly1M-default" default --builtin curly --guides 32768 $T
    perf "choice-curly1M-conservative120" default --builtin curly --guides 32768 $REC $T
    perf "choice-curly4M-default" default --builtin curly --guides 131072 $T
    perf "choice-curly4M-conservative120" default --builtin curly --guides 131072 $REC $T
  } | tee "$OUT/choice.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# SPLIT=1: only "Where its frame goes at scale" (docs/accuracy.md, "A conservative local shape"): the conservative
# model at its recommended 120 Hz with 0, 1 and 2 local iterations on Ratboy, 1 M and 4 M guide vertices; beside it at
# 1 M follow-the-leader with 1 iteration and the compliant model with 0.
if [ "${SPLIT:-0}" = 1 ]; then
  C="--scene shake --frames 200 --warmup 60 --error-frames 1 --step-rate 120"
  {
    table_header
    for li in 0 1 2; do
      [ -f "$MOHAWK" ] && perf "split-ratboy-conservative-li$li" default --asset "$MOHAWK" --model conservative \
        --local-iterations "$li" $C
      perf "split-curly1M-conservative-li$li" default --builtin curly --guides 32768 --model conservative \
        --local-iterations "$li" $C
      perf "split-curly4M-conservative-li$li" default --builtin curly --guides 131072 --model conservative \
        --local-iterations "$li" $C
    done
    perf "split-curly1M-ftl-li1" default --builtin curly --guides 32768 --local-iterations 1 $C
    perf "split-curly1M-compliant-li0" default --builtin curly --guides 32768 --model compliant --local-iterations 0 $C
  } | tee "$OUT/split.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# WAVES=1: only "A small groom's frame is whole waves of workgroups" (docs/accuracy.md): the conservative model at
# 120 Hz with 1 local iteration (and with local shape off) on curly grooms of 660 to 6,600 guides (0.5 to 5 waves of
# its workgroups of ten strands on a 132-SM GPU), follow-the-leader's default beside it, then stop.
if [ "${WAVES:-0}" = 1 ]; then
  C="--scene shake --frames 200 --warmup 60 --error-frames 1"
  {
    table_header
    for g in 660 1320 1330 1980 2640 3960 6600; do
      perf "waves-conservative-li1-$g" default --builtin curly --guides "$g" --model conservative --step-rate 120 \
        --local-iterations 1 $C
    done
    for g in 1320 1330 2640; do
      perf "waves-conservative-li0-$g" default --builtin curly --guides "$g" --model conservative --step-rate 120 \
        --local-iterations 0 $C
    done
    for g in 660 1320 2640 6600; do perf "waves-ftl-$g" default --builtin curly --guides "$g" $C; done
  } | tee "$OUT/waves.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# REFINE=1: only "The shape solve refined below 120 Hz" (docs/accuracy.md): the conservative model with 1 local
# iteration at 30 Hz (its solve refined three times; then once, TRESSVK_SIM_REFINE=1, as before), 60 Hz (once) and
# 120 Hz (not) on Ratboy + 2 follows, curly 1 M and 4 M guide vertices and 1,320 curly guides (one wave on a 132-SM
# GPU), then its hard cases at 60 and 30 Hz, then stop. The table's "before" column is the same rows on a build before
# the refinement.
if [ "${REFINE:-0}" = 1 ]; then
  # (two error frames: at 30 Hz one frame in two of `shake`'s 60 steps)
  C="--scene shake --frames 200 --warmup 60 --error-frames 2 --model conservative --local-iterations 1"
  refine_rows() {  # name suffix, step rate
    [ -f "$MOHAWK" ] && perf "refine-ratboy-$1" default --asset "$MOHAWK" --step-rate "$2" $C
    perf "refine-curly1M-$1" default --builtin curly --guides 32768 --step-rate "$2" $C
    perf "refine-curly4M-$1" default --builtin curly --guides 131072 --step-rate "$2" $C
    perf "refine-curly1320-$1" default --builtin curly --guides 1320 --step-rate "$2" $C
  }
  {
    table_header
    for rate in 30 60 120; do refine_rows "$rate" "$rate"; done
    TRESSVK_SIM_REFINE=1 refine_rows 30-once 30
  } | tee "$OUT/refine.md"
  for rate in 60 30; do
    "$BENCH" hardcases --model conservative --converged-rate 960 --step-rate "$rate" --local-iterations 1 \
      --json "$OUT/refine-hardcases-$rate.json" | tee "$OUT/refine-hardcases-$rate.md" || true
  done
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# TERMS=1: only "Where a frame's time goes" (docs/simulation.md): each term switched off in turn (parameter files
# written to OUTDIR) on curly 1 M guide vertices and on Ratboy at 240 Hz, the 60 Hz frame with every term and bare,
# and 4 M with every term and bare.
if [ "${TERMS:-0}" = 1 ]; then
  echo '{"simulation":{"vsp_coefficient":0}}' > "$OUT/novsp.json"
  echo '{"simulation":{"global_stiffness":0}}' > "$OUT/noglobal.json"
  echo '{"simulation":{"max_speed":0}}' > "$OUT/noclamp.json"
  echo '{"simulation":{"vsp_coefficient":0,"global_stiffness":0,"max_speed":0,"local_iterations":0}}' > "$OUT/bare.json"
  P="--frames 200 --warmup 60 --error-frames 1"
  {
    table_header
    for g in curly1M ratboy; do
      case $g in
        ratboy) [ -f "$MOHAWK" ] || continue; G=(--asset "$MOHAWK") ;;
        curly1M) G=(--builtin curly --guides 32768) ;;
      esac
      perf "terms-$g-all" default "${G[@]}" --scene shake $P
      perf "terms-$g-lit0" default "${G[@]}" --scene shake --local-iterations 0 $P
      perf "terms-$g-lit1" default "${G[@]}" --scene shake --local-iterations 1 $P
      perf "terms-$g-lit4" default "${G[@]}" --scene shake --local-iterations 4 $P
      perf "terms-$g-len2" default "${G[@]}" --scene shake --length-iterations 2 $P
      for p in novsp noglobal noclamp bare; do
        perf "terms-$g-$p" default "${G[@]}" --scene shake --params "$OUT/$p.json" $P
      done
      perf "terms-$g-settle" default "${G[@]}" --scene settle --sleep-below 0 $P
      perf "terms-$g-60" default "${G[@]}" --scene shake --step-rate 60 $P
      perf "terms-$g-60bare" default "${G[@]}" --scene shake --step-rate 60 --params "$OUT/bare.json" $P
    done
    perf "terms-curly4M-all" default --builtin curly --guides 131072 --scene shake $P
    perf "terms-curly4M-bare" default --builtin curly --guides 131072 --scene shake --params "$OUT/bare.json" $P
  } | tee "$OUT/terms.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# FRAME_WG=1: only the one-thread kernel's workgroup table (docs/simulation.md, "The one-thread kernel's workgroup"):
# curly 1, 2, 3 and 4 M guide vertices at 240 Hz with workgroups of 32 and of 512 (TRESSVK_SIM_FRAME_WG), every term
# and VSP off; at 4 M also global shape off and bare.
if [ "${FRAME_WG:-0}" = 1 ]; then
  echo '{"simulation":{"vsp_coefficient":0}}' > "$OUT/novsp.json"
  echo '{"simulation":{"global_stiffness":0}}' > "$OUT/noglobal.json"
  echo '{"simulation":{"vsp_coefficient":0,"global_stiffness":0,"max_speed":0,"local_iterations":0}}' > "$OUT/bare.json"
  P="--scene shake --frames 200 --warmup 60 --error-frames 1"
  {
    table_header
    for wg in 32 512; do
      for guides in 32768 65536 98304 131072; do
        for p in all novsp noglobal bare; do
          [ $guides != 131072 ] && { [ $p = noglobal ] || [ $p = bare ]; } && continue
          A=(); [ $p != all ] && A=(--params "$OUT/$p.json")
          TRESSVK_SIM_FRAME_WG=$wg perf "wg$wg-curly$guides-$p" default --builtin curly --guides $guides "${A[@]}" $P
        done
      done
    done
  } | tee "$OUT/frame_wg.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# RUNS=1: only the run kernel's crossover table (runs of 4, of 8 and the one-thread kernel on curly 4,096, 8,192 and
# 16,384 x 32, and the default on Ratboy, at 240 and 60 Hz; docs/simulation.md, "The run kernel"), then stop.
if [ "${RUNS:-0}" = 1 ]; then
  R="--scene shake --frames 120 --warmup 30 --error-frames 1"
  {
    table_header
    for rate in 240 60; do
      [ -f "$MOHAWK" ] && perf "runs-ratboy-default-$rate" default --asset "$MOHAWK" --step-rate "$rate" $R
      for guides in 4096 8192 16384; do
        for path in runs4 runs8 fused; do
          perf "runs-$path-$guides-$rate" "$path" --builtin curly --guides "$guides" --step-rate "$rate" $R
        done
      done
    done
  } | tee "$OUT/runs.md"
  echo "done in $SECONDS s: $OUT"
  exit 0
fi

# SWEEP_ONLY=1: skip this table. Every path (and the shared-memory variant of the one-thread kernel at 240 Hz).
[ "${SWEEP_ONLY:-0}" = 1 ] || {
  table table default fused passes
  [ -f "$MOHAWK" ] && perf "table-ratboy-fused-shared-240" fused-shared --asset "$MOHAWK" --step-rate 240 $T
  perf "table-curly1M-fused-shared-240" fused-shared --builtin curly --guides 32768 --step-rate 240 $T
  perf "table-curly4M-fused-shared-240" fused-shared --builtin curly --guides 131072 --step-rate 240 $T
} | tee "$OUT/table.md"

# Scaling sweep: 10k .. 16M guide vertices (curly, 32 vertices per strand) at SWEEP_RATES (default 60 120 240) on
# SWEEP_PATHS (default: default fused passes); the step error of each row from one frame after its timed frames. The
# default path runs the one-thread kernel above 768 k guide vertices: its rows there are skipped when fused runs too.
S="--scene shake --frames 120 --warmup 30 --error-frames 1"
{
  table_header
  for guides in 320 1024 3200 10240 32768 131072 524288; do
    for rate in ${SWEEP_RATES:-60 120 240}; do
      for path in ${SWEEP_PATHS:-default fused passes}; do
        if [ "$path" = default ] && [ "$guides" -gt 24576 ] && [[ " ${SWEEP_PATHS:-default fused passes} " == *" fused "* ]]; then
          continue
        fi
        # SWEEP_PASSES_MIN: the pass-per-dispatch rows from that many guides only (the plot of docs/simulation.md).
        if [ "$path" = passes ] && [ "$guides" -lt "${SWEEP_PASSES_MIN:-0}" ]; then continue; fi
        if [ "$SECONDS" -gt "$BUDGET" ]; then echo "| budget of ${BUDGET} s spent: curly $guides x 32 at $rate Hz ($path) not run |"; continue; fi
        perf "sweep-$path-$guides-$rate" "$path" --builtin curly --guides "$guides" --step-rate "$rate" $S
      done
    done
  done
} | tee "$OUT/sweep.md"
echo "done in $SECONDS s: $OUT"
