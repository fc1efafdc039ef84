#!/usr/bin/env bash
# Installs what is missing, builds the release configuration and runs the main job, tressvk-demo, with no
# arguments (it renders the bundled sample). Extra arguments are passed to tressvk-demo.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
JOBS=${TRESSVK_JOBS:-$(nproc)}

./scripts/setup-deps.sh
cmake --preset release
cmake --build --preset release -j "$JOBS" --target tressvk-demo
# Without a GPU driver the Vulkan loader finds lavapipe by itself; with one, the demo picks the discrete GPU.
exec ./build/release/engine/tressvk-demo "$@"
