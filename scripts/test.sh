#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test on Mesa lavapipe with the Vulkan validation layers
# (synchronization validation included) watching, then a one-minute fuzzing smoke (TRESSVK_SKIP_FUZZ=1 skips it,
# TRESSVK_FUZZ_SECONDS sets its length). Exits non-zero on any failure.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
JOBS=${TRESSVK_JOBS:-$(nproc)}

./scripts/setup-deps.sh
# shellcheck source=scripts/lavapipe-env.sh
. ./scripts/lavapipe-env.sh
echo "test: Vulkan driver ${VK_DRIVER_FILES:-<loader default>}"
vulkaninfo --summary 2>/dev/null | grep -E 'deviceName|driverInfo|apiVersion' | head -3 || true

start=$(date +%s)
cmake --preset ci
cmake --build --preset ci -j "$JOBS"
echo "test: build took $(( $(date +%s) - start )) s"

# The baker's robustness tests run again under AddressSanitizer + UBSan (only the targets they need).
if [ "${TRESSVK_SKIP_SANITIZE:-0}" != 1 ]; then
  cmake --preset sanitize >/dev/null
  cmake --build --preset sanitize -j "$JOBS" --target tressvk_sanitize_tests
fi

status=0
ctest --preset ci -j "$JOBS" || status=$?
if [ "${TRESSVK_SKIP_SANITIZE:-0}" != 1 ]; then
  ctest --preset sanitize -j "$JOBS" || status=$?
fi

# A short coverage-guided fuzzing smoke of every reader, the bake and the plugin's asset load (clang, ASan +
# UBSan; scripts/fuzz.sh, docs/reliability.md). The regression inputs of fuzz/regressions/ were replayed above by
# ctest in the ci and sanitize builds.
if [ "${TRESSVK_SKIP_FUZZ:-0}" != 1 ]; then
  TRESSVK_FUZZ_SKIP_DEPS=1 TRESSVK_JOBS=$JOBS ./scripts/fuzz.sh "${TRESSVK_FUZZ_SECONDS:-60}" || status=$?
fi
exit $status
