#!/usr/bin/env bash
# The hair rendering table of docs/rendering.md on a real GPU, with portable binaries (cmake --preset portable):
# every row is one `tressvk-bench render` run (speed of warm back-to-back frames, then the error of one more
# frame against the brute-force sorted reference, same run), one JSON file per row, plus a PNG per scene.
#
#   scripts/gpu-render-bench.sh OUTDIR [BINDIR [ASSETDIR]]
#
# BINDIR holds tressvk-bench, tressvk-bake and libtressvk.so.0 (default build/portable/{engine,baker,plugin}).
# ASSETDIR (default ../shared/data) holds tressfx/ratboy/Ratboy_mohawk.tfx and sintel/{sintel_hair.tfx,sintel.obj};
# rows whose data is absent are skipped. QUICK=1 runs only the target rows; ROWS=REGEX only the rows whose name matches. On a machine without a Vulkan
# loader, install it first and point VK_DRIVER_FILES at the driver's ICD JSON (see scripts/gpu-bench.sh).
set -euo pipefail
OUT=${1:?usage: gpu-render-bench.sh OUTDIR [BINDIR [ASSETDIR]]}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${2:-}
DATA=${3:-$ROOT/../shared/data}
mkdir -p "$OUT"
. "$ROOT/scripts/gpu-tools.sh"
gpu_tools "$ROOT" "$BIN"
HD="--width 1920 --height 1080"
TIMED="--frames ${FRAMES:-60} --warmup ${WARMUP:-30}"

row() {  # name, then bench arguments
  local name=$1; shift
  if [ -n "${ROWS:-}" ] && ! [[ $name =~ $ROWS ]]; then return 0; fi
  echo "== $name: $*" >> "$OUT/summary.txt"
  if "$BENCH" render "$@" --json "$OUT/$name.json" > "$OUT/$name.log" 2>&1; then
    grep -E '"(device|shading|gpu_ms_shadow|gpu_ms_shading|error_mean|error_p99|error_vs_full_mean|error_vs_full_p99|coverage_vs_full|strands_drawn)"' "$OUT/$name.json" |
      tr -d '\n' >> "$OUT/summary.txt"
    echo >> "$OUT/summary.txt"
    sed -n '/"gpu_ms_passes"/,/}/p' "$OUT/$name.json" | tr -d '\n ' >> "$OUT/summary.txt"
    echo >> "$OUT/summary.txt"
  else
    echo "FAILED ($?): $(tail -3 "$OUT/$name.log")" >> "$OUT/summary.txt"
  fi
}

RATBOY=""
if [ -f "$DATA/tressfx/ratboy/Ratboy_mohawk.tfx" ]; then
  RATBOY="$OUT/ratboy_mohawk_4follows.tvkhair"
  "$BAKE" "$DATA/tressfx/ratboy/Ratboy_mohawk.tfx" --follow 4 -o "$RATBOY" > "$OUT/bake_ratboy.log" 2>&1
fi
SINTEL=""
if [ -f "$DATA/sintel/sintel_hair.tfx" ]; then
  SINTEL="$OUT/sintel_6follows.tvkhair"
  "$BAKE" "$DATA/sintel/sintel_hair.tfx" --scale 0.0046 --follow 6 -o "$SINTEL" > "$OUT/bake_sintel.log" 2>&1
fi

# The targets: the sphere sample (9,600 x 48, the issue's "bundled sample" before the head sample), Ratboy mohawk + 4
# follows, 100,000 strands x 32 (compute path, 1080p). Each compute row runs as a host runs it (no timestamps inside
# the calls: each waits for the work before it); its -passes twin times every pass of the same frames.
NP=--no-pass-timestamps
twin() {  # name, then bench arguments: the row without and with per-pass timestamps
  local name=$1; shift
  row "$name" "$@" $NP
  row "$name-passes" "$@"
}
twin sample-compute-1080p --sample sphere $HD $TIMED --png "$OUT/sample-compute-1080p.png"
# The bundled head sample (the demo's default scene: face, straight groom, head turn).
twin head-compute-1080p --sample head $HD $TIMED --png "$OUT/head-compute-1080p.png"
[ -n "$RATBOY" ] && twin ratboy4-compute-1080p --asset "$RATBOY" $HD $TIMED --animate shake --png "$OUT/ratboy4-compute-1080p.png"
twin 100k-compute-1080p --sample sphere --guides 12500 --follows 7 --vertices 32 $HD $TIMED
[ "${QUICK:-0}" = 1 ] && exit 0

# The raster path on the same frames; its error: its displayed frame against the reference layer blended over the same
# frame drawn without hair (tressvk-bench builds both with the same options and frame count).
row sample-raster-1080p --sample sphere $HD --frames 10 --warmup 5 --path raster --png "$OUT/sample-raster-1080p.png"
[ -n "$RATBOY" ] && row ratboy4-raster-1080p --asset "$RATBOY" $HD --frames 10 --warmup 5 --animate shake --path raster
# Sintel with her mesh (hair in front of and behind an opaque mesh).
[ -n "$SINTEL" ] && twin sintel6-compute-1080p --asset "$SINTEL" --mesh "$DATA/sintel/sintel.obj" --mesh-scale 0.0046 \
  $HD $TIMED --png "$OUT/sintel6-compute-1080p.png"
# Kajiya-Kay per fragment instead of per vertex (time, and the error against the per-vertex-shaded reference).
row sample-compute-1080p-fragment --sample sphere $HD $TIMED --shade fragment --png "$OUT/sample-compute-1080p-fragment.png" $NP
[ -n "$RATBOY" ] && row ratboy4-compute-1080p-fragment --asset "$RATBOY" $HD $TIMED --animate shake --shade fragment $NP
row 100k-compute-1080p-fragment --sample sphere --guides 12500 --follows 7 --vertices 32 $HD $TIMED --shade fragment $NP
# Speed against error: resolution and LOD.
row sample-compute-540p --sample sphere --width 960 --height 540 $TIMED $NP
row sample-compute-2160p --sample sphere --width 3840 --height 2160 $TIMED $NP
row sample-compute-1080p-lod50 --sample sphere $HD $TIMED --lod-fraction 0.5 $NP
row sample-compute-1080p-lod25 --sample sphere $HD $TIMED --lod-fraction 0.25 $NP
twin 100k-compute-1080p-lod25 --sample sphere --guides 12500 --follows 7 --vertices 32 $HD $TIMED --lod-fraction 0.25
row 100k-compute-2160p --sample sphere --guides 12500 --follows 7 --vertices 32 --width 3840 --height 2160 $TIMED $NP

# LOD against ALL strands (--error-vs-full: the same frame rendered without LOD is captured and its sorted reference
# is what the LOD frame is compared with, error_vs_full_*): the fixed fractions above and the coverage-driven LOD
# (--lod-target-px LODPX, default 1: sub-pixel strands thinned until the drawn ones are about 1 px wide).
LODPX=${LODPX:-1}
FULL="--error-vs-full $NP"
row sample-compute-1080p-lod25-vsfull --sample sphere $HD $TIMED --lod-fraction 0.25 $FULL
row 100k-compute-1080p-lod25-vsfull --sample sphere --guides 12500 --follows 7 --vertices 32 $HD $TIMED --lod-fraction 0.25 $FULL
for res in 1080p 2160p; do
  if [ $res = 1080p ]; then VIEW=$HD; else VIEW="--width 3840 --height 2160"; fi
  row sample-compute-$res-lodauto --sample sphere $VIEW $TIMED --lod-target-px $LODPX $FULL
  row head-compute-$res-lodauto --sample head $VIEW $TIMED --lod-target-px $LODPX $FULL
  [ -n "$RATBOY" ] && row ratboy4-compute-$res-lodauto --asset "$RATBOY" $VIEW $TIMED --animate shake --lod-target-px $LODPX $FULL
  row 100k-compute-$res-lodauto --sample sphere --guides 12500 --follows 7 --vertices 32 $VIEW $TIMED --lod-target-px $LODPX $FULL
done
# Far views, where the strands are a fraction of a pixel (the camera 4x the framing distance: the sphere sample and
# 100,000 x 32, 2 px strands at 1080p, become 0.5 px): every strand, then the coverage LOD against all strands.
for scene in sample 100k; do
  if [ $scene = sample ]; then G="--sample sphere"; else G="--sample sphere --guides 12500 --follows 7 --vertices 32"; fi
  row $scene-compute-1080p-far4 $G $HD $TIMED --zoom 4 $NP
  row $scene-compute-1080p-far4-lodauto $G $HD $TIMED --zoom 4 --lod-target-px $LODPX $FULL
done
# The shadow call where the hair covers a small part of the map (the map 4x wider than the scene, as a cascade is):
# only the rectangle the hair can reach is copied out and back (compare the -passes rows' shadow_copy_* with the
# ratboy4-compute-1080p-passes row).
[ -n "$RATBOY" ] && twin ratboy4-compute-1080p-wideshadow --asset "$RATBOY" $HD $TIMED --animate shake --shadow-extent 6.4
