#!/usr/bin/env bash
# Installs what TressVK needs to build and test on Debian 12 (bookworm), and only what is missing.
#
#   - bookworm packages: compiler, CMake, Ninja, Vulkan headers/loader/tools/validation layers, glslang,
#     SPIRV-Tools, volk, glm, tinyobjloader, stb, CLI11, nlohmann-json, ffmpeg (tressvk-demo --video), GLFW and
#     Dear ImGui (tressvk-viewer), xvfb + xauth (xvfb-run: the viewer's test without a screen); clang 14 with
#     libFuzzer and the LLVM tools (llvm-symbolizer for readable sanitizer reports) for the fuzz targets
#     (scripts/fuzz.sh);
#   - bookworm-backports, selected per package: catch2 (v3) and mesa-vulkan-drivers (lavapipe);
#   - the VulkanMemoryAllocator header package from trixie, unpacked with `dpkg -x` into a project-local,
#     git-ignored prefix (default: .deps/ at the repository root) that the CMake presets search.
#
# Idempotent: a second run finds everything present, installs nothing and says so. Runs as root, or through
# sudo when it is available. Nothing under /etc/apt is changed: the extra suites use private apt state.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PREFIX=$(realpath -m "${TRESSVK_DEPS_PREFIX:-$ROOT/.deps}")

say() { printf 'setup-deps: %s\n' "$*"; }

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=(sudo); else
    say "error: not root and no sudo; run this script as root"; exit 1; fi
fi
export DEBIAN_FRONTEND=noninteractive

BOOKWORM_PKGS=(build-essential cmake ninja-build pkg-config libvulkan-dev vulkan-tools vulkan-validationlayers
  glslang-tools spirv-tools libvulkan-volk-dev libglm-dev libtinyobjloader-dev libstb-dev libcli11-dev
  nlohmann-json3-dev ca-certificates ffmpeg libglfw3-dev libimgui-dev xvfb xauth
  clang-14 libclang-rt-14-dev libfuzzer-14-dev llvm-14)
BACKPORT_PKGS=(catch2 mesa-vulkan-drivers)

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q '^install ok installed$'; }
version_of() { dpkg-query -W -f='${Version}' "$1" 2>/dev/null || true; }

missing=()
for p in "${BOOKWORM_PKGS[@]}"; do installed "$p" || missing+=("$p"); done
for p in "${BACKPORT_PKGS[@]}"; do
  # catch2 must be v3 and lavapipe the pinned Mesa: both come from bookworm-backports (~bpo12).
  if ! installed "$p" || [[ "$(version_of "$p")" != *bpo12* ]]; then missing+=("$p/bookworm-backports"); fi
done
need_vma=0
[ -f "$PREFIX/usr/include/vk_mem_alloc.h" ] && [ -f "$PREFIX/usr/share/cmake/VulkanMemoryAllocator/VulkanMemoryAllocatorConfig.cmake" ] || need_vma=1

if [ ${#missing[@]} -eq 0 ] && [ $need_vma -eq 0 ]; then
  say "everything is already installed (VMA in $PREFIX); nothing to do"
  exit 0
fi

APTDIR=$(mktemp -d)
trap 'rm -rf "$APTDIR"' EXIT
chmod 755 "$APTDIR"
mkdir -p "$APTDIR/bp/lists/partial" "$APTDIR/tx/lists/partial" "$APTDIR/deb"

# The machine's own Debian mirror (deb822 'URIs:' or one-line 'deb' entries).
MIRROR=$(grep -rhE '^(URIs:|deb) ' /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null \
  | grep -oE 'https?://[^ ]+/debian/?( |$)' | grep -v security | head -1 | tr -d ' ' || true)
MIRROR=${MIRROR:-http://deb.debian.org/debian}
# Overriding Dir::Etc::SourceList replaces /etc/apt/sources.list, so carry its entries over (a minimal system
# keeps its bookworm source there; others use sources.list.d/, which stays active).
{ [ -f /etc/apt/sources.list ] && grep -E '^deb ' /etc/apt/sources.list || true
  echo "deb $MIRROR bookworm-backports main"; } > "$APTDIR/bp/sources.list"
echo "deb $MIRROR trixie main" > "$APTDIR/tx/sources.list"
# Bookworm sources stay active; backports are added; all indexes go to a private lists directory.
BP=(-o "Dir::Etc::SourceList=$APTDIR/bp/sources.list" -o "Dir::State::Lists=$APTDIR/bp/lists")
TX=(-o "Dir::Etc::SourceList=$APTDIR/tx/sources.list" -o Dir::Etc::SourceParts=/dev/null
    -o "Dir::State::Lists=$APTDIR/tx/lists"
    -o Acquire::IndexTargets::deb::DEP-11::DefaultEnabled=false
    -o Acquire::IndexTargets::deb::DEP-11-icons::DefaultEnabled=false
    -o Acquire::IndexTargets::deb::DEP-11-icons-small::DefaultEnabled=false)

if [ ${#missing[@]} -gt 0 ]; then
  say "installing: ${missing[*]}"
  "${SUDO[@]}" apt-get "${BP[@]}" update -q
  "${SUDO[@]}" apt-get "${BP[@]}" install -y -q --no-install-recommends "${missing[@]}"
  say "installed ${#missing[@]} package(s)"
fi

if [ $need_vma -eq 1 ]; then
  say "fetching the VulkanMemoryAllocator header package from trixie into $PREFIX"
  "${SUDO[@]}" chown _apt "$APTDIR/deb" 2>/dev/null || true
  "${SUDO[@]}" apt-get "${TX[@]}" update -q
  (cd "$APTDIR/deb" && "${SUDO[@]}" apt-get "${TX[@]}" download libvulkan-memory-allocator-dev)
  mkdir -p "$PREFIX"
  dpkg -x "$APTDIR"/deb/libvulkan-memory-allocator-dev_*_all.deb "$PREFIX"
  say "VMA $(ls "$APTDIR"/deb | sed -E 's/.*_([^_]+)_all.deb/\1/') unpacked into $PREFIX"
fi
say "done"
