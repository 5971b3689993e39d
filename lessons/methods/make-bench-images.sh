#!/bin/sh
# Regenerates the bench pictures of the method pages (lessons/methods/img/bench-*.png): the demo scene
# (Res/scenes/demo.toml) at 480x270 with R = 1 m, as the bench's report.html shows a setting:
#   bench-truth.png        the ray-traced truth (`opengl3d reference`, 256 rays per pixel)
#   bench-METHOD-ao.png    the method's blurred AO view (`render --view ao`)
#   bench-METHOD-error.png its signed error against the truth (`render --view error --truth`)
# and img/ja/bench-METHOD-error.png, the same error map with the words of its scale in Japanese.
# Prints each method's PSNR against the truth (the pages' captions quote it).
# Run from anywhere: sh lessons/methods/make-bench-images.sh
# Needs cargo (builds and runs the engine headless) and python3 (lessons/figures.py, no extra modules).
# OPENGL3D=path/to/opengl3d uses an already-built binary instead of `cargo run --release --`.
set -eu

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
IMG="$HERE/img"
mkdir -p "$IMG/ja"
. "$ROOT/lessons/engine.sh"
SIZE="--width 480 --height 270 --radius 1"
METHODS="sao-lesson sao crytek hemisphere hbao angle-based gtao vbao rtao"

# The truth, once as raw floats for the error maps and once as the picture (the second run is cached).
run reference $SIZE --cache "$TMP/cache" --out "$TMP/truth.pfm" >/dev/null
run reference $SIZE --cache "$TMP/cache" --out "$IMG/bench-truth.png" >/dev/null

for m in $METHODS; do
  # rtao traces 2 rays per pixel and frame: 64 frames averaged, as it converges when the camera stands,
  # at half size as its page describes.
  extra=""
  [ "$m" = rtao ] && extra="--accumulate 64 --ao-resolution half"
  run render --method "$m" $SIZE $extra --view ao --out "$IMG/bench-$m-ao.png" >/dev/null
  run render --method "$m" $SIZE $extra --view error --truth "$TMP/truth.pfm" --out "$TMP/error.pfm" >/dev/null
  psnr=$(run render --method "$m" $SIZE $extra --view error --truth "$TMP/truth.pfm" \
    --out "$IMG/bench-$m-error.png" | sed -n 's/^PSNR \([0-9.]*\) dB.*/\1/p')
  python3 "$ROOT/lessons/figures.py" --lang ja error-legend \
    "$IMG/bench-$m-error.png" "$TMP/error.pfm" "$IMG/ja/bench-$m-error.png"
  echo "$m PSNR $psnr dB"
done
echo "pictures written to $IMG"
