#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test on Mesa lavapipe with the Vulkan validation layers
# (synchronization validation included) watching. Ends with ctest's summary; exits non-zero on any failure.
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
exit $status
