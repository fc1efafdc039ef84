#!/usr/bin/env bash
# The plugin_load fuzz target on a machine with a real GPU and many cores: libFuzzer's fork mode runs JOBS
# processes at once (each input loaded, instanced and simulated on the GPU with the validation layer and
# synchronization validation on, as on lavapipe in scripts/fuzz.sh), for SECONDS, and prints the executions and
# coverage reached. Exits non-zero on a finding (crash, sanitizer report, validation message, leak, timeout).
#
#   scripts/gpu-fuzz.sh OUTDIR BINDIR [SECONDS [JOBS]]
#
# BINDIR holds fuzz_plugin_load and libtressvk.so.0 from the `fuzz` preset (build/fuzz/fuzz, build/fuzz/plugin),
# the validation layer (libVkLayer_khronos_validation.so and its VkLayer_khronos_validation.json) and any shared
# library the machine lacks; BINDIR/corpus holds the starting inputs (scripts/fuzz.sh's seeds and corpus of
# plugin_load). On a machine without a Vulkan loader, install it first and point VK_DRIVER_FILES at the driver's
# ICD JSON (see scripts/gpu-bench.sh).
set -euo pipefail
OUT=${1:?usage: gpu-fuzz.sh OUTDIR BINDIR [SECONDS [JOBS]]}
BIN=$(cd "${2:?usage: gpu-fuzz.sh OUTDIR BINDIR [SECONDS [JOBS]]}" && pwd)
SECS=${3:-480}
JOBS=${4:-$(( $(nproc) - 1 ))}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mkdir -p "$OUT/corpus" "$OUT/findings"
export LD_LIBRARY_PATH="$BIN:${LD_LIBRARY_PATH:-}"
export VK_LAYER_PATH="$BIN"
# protect_shadow_gap=0: GPU drivers map memory in the range ASan keeps as its shadow gap. detect_leaks=0:
# LeakSanitizer's stop-the-world scan crashes inside NVIDIA's driver threads ("Tracer caught signal 11") and the
# driver's JIT code has no module name to suppress; host leaks are checked by the lavapipe runs of scripts/fuzz.sh,
# and this harness still fails an input whose device allocations do not return to the baseline.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1:allocator_may_return_null=0:protect_shadow_gap=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$ROOT/fuzz/lsan.supp:print_suppressions=0}
status=0
"$BIN/fuzz_plugin_load" -fork="$JOBS" -max_total_time="$SECS" -rss_limit_mb=4096 -malloc_limit_mb=4096 \
  -timeout=60 -max_len=16384 -print_final_stats=1 -artifact_prefix="$OUT/findings/" \
  "$OUT/corpus" "$BIN/corpus" > "$OUT/plugin_load.log" 2>&1 || status=$?
last=$(grep -E '^#[0-9]+' "$OUT/plugin_load.log" | tail -1 || true)
{
  echo "device: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || echo unknown)"
  echo "jobs: $JOBS, seconds: $SECS, exit: $status"
  echo "last status line: $last"
  grep -E 'ERROR|FUZZ FINDING|SUMMARY|runtime error|validation' "$OUT/plugin_load.log" | head -20 || true
} | tee "$OUT/summary.txt"
exit $status
