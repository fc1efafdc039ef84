#!/usr/bin/env bash
# The bundled sample on follow-the-leader (left) and on the conservative model (right), each at its own settings:
# frame 60 (the head turn) above, the poster frame 126 (the gust) below, as one PNG (docs/accuracy.md, "Not done yet").
#
#   scripts/demo-models.sh OUT.png [DEMO]
#
# DEMO: a built tressvk-demo (default build/ci/engine/tressvk-demo). Renders demo.sh's sample (480x270, 1,000 guides,
# 6 follows) for 150 frames per model into a temporary folder; needs ffmpeg to stack the frames.
set -euo pipefail
OUT=${1:?usage: demo-models.sh OUT.png [DEMO]}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
DEMO=${2:-$ROOT/build/ci/engine/tressvk-demo}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
for m in follow-the-leader conservative; do
  echo "{\"settings\": {\"model\": \"$m\"}}" > "$TMP/$m.json"
  "$DEMO" --frames 150 --width 480 --height 270 --guides 1000 --follows 6 --params "$TMP/$m.json" --out "$TMP/$m" \
    | grep -E '^(simulation|GPU time)'
done
ffmpeg -loglevel error -y -i "$TMP/follow-the-leader/frame_0060.png" -i "$TMP/conservative/frame_0060.png" \
  -i "$TMP/follow-the-leader/frame_0126.png" -i "$TMP/conservative/frame_0126.png" \
  -filter_complex "[0][1]hstack[top];[2][3]hstack[bottom];[top][bottom]vstack" "$OUT"
echo "wrote $OUT"
