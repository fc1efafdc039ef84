#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (the `fuzz` preset: clang 14, ASan + UBSan) and runs every one of them
# for a share of SECONDS (the whole run's fuzzing time, default 60), then prints executions and coverage per
# target. Exits non-zero when any target found a crash, a leak, undefined behaviour, a timeout or a memory blow-up;
# the input that did it is under build/fuzz/findings/<target>/ -- fix the bug and move the input to
# fuzz/regressions/<target>/, which ./scripts/test.sh replays in the ordinary build.
#
#   scripts/fuzz.sh [SECONDS]
#
# Environment: TRESSVK_FUZZ_TARGETS (a subset, e.g. "obj tfx"), TRESSVK_FUZZ_JOBS (targets run at once, default
# 2; each target is one libFuzzer process), TRESSVK_FUZZ_RSS_MB (per process, default 2048 for the plugin target,
# 512 for the rest), TRESSVK_FUZZ_TIMEOUT (seconds per input, default 10; 60 for the plugin target, whose first
# input of each vertex count builds pipelines with lavapipe's LLVM under ASan). The corpus
# grows across runs in build/fuzz/corpus/<target>/ (delete it to start from the seeds again).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
SECONDS_TOTAL=${1:-60}
JOBS=${TRESSVK_FUZZ_JOBS:-2}
TARGETS=(${TRESSVK_FUZZ_TARGETS:-obj tfx tfxbone tvkhair bake plugin_load})
DATA=${TRESSVK_DATA_DIR:-$ROOT/../shared/data}
OUT=$ROOT/build/fuzz

say() { printf 'fuzz: %s\n' "$*"; }

[ "${TRESSVK_FUZZ_SKIP_DEPS:-0}" = 1 ] || ./scripts/setup-deps.sh >/dev/null
# shellcheck source=scripts/lavapipe-env.sh
. ./scripts/lavapipe-env.sh
cmake --preset fuzz >/dev/null
build_targets=(tressvk-bake)
for t in "${TARGETS[@]}"; do build_targets+=("fuzz_$t"); done
cmake --build --preset fuzz -j "${TRESSVK_JOBS:-$(nproc)}" --target "${build_targets[@]}"

rm -rf "$OUT/seeds"
python3 fuzz/make_seeds.py "$OUT/seeds" "$DATA" "$OUT/baker/tressvk-bake" | sed 's/^/fuzz: /'

per_target=$(( SECONDS_TOTAL * JOBS / ${#TARGETS[@]} ))
[ "$per_target" -ge 5 ] || per_target=5
say "${#TARGETS[@]} target(s), $per_target s each, $JOBS at a time"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$ROOT/fuzz/lsan.supp:print_suppressions=0}

run_target() {
  local t=$1 rss=512 timeout=${TRESSVK_FUZZ_TIMEOUT:-10} max_len=4100 dict=()
  case $t in
    plugin_load) rss=2048; timeout=${TRESSVK_FUZZ_TIMEOUT:-60}; max_len=16384 ;;
    tvkhair) max_len=16384 ;;
    obj|bake) dict=(-dict=fuzz/dict/obj.dict) ;;
    tfxbone) max_len=8192 ;;
  esac
  rss=${TRESSVK_FUZZ_RSS_MB:-$rss}
  mkdir -p "$OUT/corpus/$t" "$OUT/findings/$t" "$OUT/seeds/$t"
  "$OUT/fuzz/fuzz_$t" -max_total_time="$per_target" -rss_limit_mb="$rss" -malloc_limit_mb="$rss" \
    -timeout="$timeout" -max_len="$max_len" "${dict[@]}" -print_final_stats=1 \
    -artifact_prefix="$OUT/findings/$t/" "$OUT/corpus/$t" "$OUT/seeds/$t" "fuzz/regressions/$t" \
    >"$OUT/$t.log" 2>&1
}

status=0
pids=()
names=()
for t in "${TARGETS[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do sleep 1; done
  run_target "$t" &
  pids+=($!)
  names+=("$t")
done
failed=()
for i in "${!pids[@]}"; do
  if ! wait "${pids[$i]}"; then failed+=("${names[$i]}"); status=1; fi
done

printf '%-12s %12s %8s %8s %10s %s\n' target executions cov ft peak_rss result | tee "$OUT/summary.txt"
for t in "${TARGETS[@]}"; do
  log=$OUT/$t.log
  execs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || echo "?")
  rss=$(grep -oE 'stat::peak_rss_mb: *[0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || echo "?")
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || echo "?")
  ft=$(grep -oE 'ft: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || echo "?")
  result=ok
  [[ " ${failed[*]} " == *" $t "* ]] && result="FINDING (see $log, $OUT/findings/$t/)"
  printf '%-12s %12s %8s %8s %8sMB %s\n' "$t" "$execs" "$cov" "$ft" "$rss" "$result" | tee -a "$OUT/summary.txt"
done
if [ $status -ne 0 ]; then
  for t in "${failed[@]}"; do say "--- $t ---"; grep -E 'ERROR|FUZZ FINDING|SUMMARY|runtime error' "$OUT/$t.log" | head -20; done
fi
exit $status
