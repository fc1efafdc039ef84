# Sourced by the scripts/gpu-*.sh runs: `gpu_tools ROOT [BINDIR]` sets BENCH and BAKE to tressvk-bench and
# tressvk-bake in BINDIR (empty or absent: ROOT's build/portable tree) and puts the directory holding
# libtressvk.so.0 first on LD_LIBRARY_PATH.
gpu_tools() {
  local root=$1 bin=${2:-}
  if [ -z "$bin" ]; then
    BENCH="$root/build/portable/engine/tressvk-bench"
    BAKE="$root/build/portable/baker/tressvk-bake"
    export LD_LIBRARY_PATH="$root/build/portable/plugin:${LD_LIBRARY_PATH:-}"
  else
    BENCH="$bin/tressvk-bench"
    BAKE="$bin/tressvk-bake"
    export LD_LIBRARY_PATH="$bin:${LD_LIBRARY_PATH:-}"
  fi
}
