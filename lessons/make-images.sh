#!/bin/sh
# Regenerates every picture under lessons/img/ from the demo scene (Res/scenes/demo.toml).
# Run from anywhere: sh lessons/make-images.sh
# Needs: cargo (builds and runs the engine headless) and python3 (lessons/figures.py, no extra modules).
# OPENGL3D=path/to/opengl3d uses an already-built binary instead of `cargo run --release --`.
# Figures with words on them are drawn twice: img/NAME.png in English, img/ja/NAME.png in Japanese.
# "Mistake" pictures are rendered with a broken copy of one lesson shader in a temporary --res folder.
set -eu

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(dirname "$HERE")
IMG="$HERE/img"
mkdir -p "$IMG/ja"
. "$ROOT/lessons/engine.sh"
SMALL="--width 640 --height 360"
M="--method sao-lesson"   # the lesson's shaders (the default method, pinned here)
fig() { python3 "$HERE/figures.py" "$@"; }
fig_ja() { python3 "$HERE/figures.py" --lang ja "$@"; }

# Engine views, straight to PNG.
run render $M --view composite $SMALL --out "$IMG/composite.png"
run render $M --view composite --ao off $SMALL --out "$IMG/composite-ao-off.png"
run render $M --view linear-depth $SMALL --out "$IMG/linear-depth.png"
run render $M --view ao-raw $SMALL --out "$IMG/ao-raw.png"
run render $M --view ao $SMALL --out "$IMG/ao.png"

# Diagrams.
fig depth-curve "$IMG/depth-curve.png"
fig spiral "$IMG/spiral.png"
fig_ja depth-curve "$IMG/ja/depth-curve.png"
fig_ja spiral "$IMG/ja/spiral.png"

# Figures computed from the linear depth (1280x720 view = one value per level-0 texel of 640x360).
run render $M --view linear-depth --out "$TMP/linear-depth.pfm"
fig mip-chain "$TMP/linear-depth.pfm" "$IMG/mip-chain.png"
fig_ja mip-chain "$TMP/linear-depth.pfm" "$IMG/ja/mip-chain.png"
fig course-depth "$TMP/linear-depth.pfm" "$IMG/course-depth.png"
fig normals "$TMP/linear-depth.pfm" "$IMG/normals.png"

# Typical mistakes: one edited shader each, everything else from Res/.
V="$TMP/var"
mkdir -p "$V/noguard" "$V/nomipbias" "$V/noedge"
sed 's/bool hasNormal = len2 > 1e-30 \&\& !onEdge;/bool hasNormal = len2 > 1e-30;/' Res/sao.frag > "$V/noguard/sao.frag"
sed 's/(vn - BIAS - mipBias)/(vn - BIAS)/' Res/sao.frag > "$V/nomipbias/sao.frag"
sed 's/weight \*= max(0.0, 1.0 - edgeSharpness \* abs(sampleDepth - depth));/\/\/ edge weight removed/' \
    Res/sao_blur.frag > "$V/noedge/sao_blur.frag"
for f in "$V"/*/*; do cmp -s "$f" "Res/$(basename "$f")" && { echo "sed did not change $f" >&2; exit 1; }; done

run render $M --view ao-raw $SMALL --out "$TMP/ok.pfm"
run --res "$V/noguard" render $M --view ao-raw $SMALL --out "$TMP/noguard.pfm"
# A low camera looking across the floor shows what the mip bias is for.
LOW="--eye 1.5,0.5,5 --target -1,0.2,-1"
run render $M --view ao-raw $LOW $SMALL --out "$TMP/low-ok.pfm"
run --res "$V/nomipbias" render $M --view ao-raw $LOW $SMALL --out "$TMP/low-nomipbias.pfm"
run render $M --view ao $SMALL --out "$TMP/ok-blur.pfm"
run --res "$V/noedge" render $M --view ao $SMALL --out "$TMP/noedge.pfm"

# 320x180 crops of the 640x360 views, correct on the left.
fig grid "$IMG/mistakes-sao.png" 320 180 \
  "correct=$TMP/ok.pfm@100,80" "no depth-edge guard=$TMP/noguard.pfm@100,80" \
  "correct, low camera=$TMP/low-ok.pfm@320,180" "no mip bias=$TMP/low-nomipbias.pfm@320,180"
fig grid "$IMG/blur-edges.png" 320 180 \
  "edge weight=$TMP/ok-blur.pfm@100,120" "no edge weight=$TMP/noedge.pfm@100,120"
fig_ja grid "$IMG/ja/mistakes-sao.png" 320 180 \
  "正しい結果=$TMP/ok.pfm@100,80" "深度の境界判定なし=$TMP/noguard.pfm@100,80" \
  "正しい結果、低いカメラ=$TMP/low-ok.pfm@320,180" "ミップバイアスなし=$TMP/low-nomipbias.pfm@320,180"
fig_ja grid "$IMG/ja/blur-edges.png" 320 180 \
  "境界のウェイトあり=$TMP/ok-blur.pfm@100,120" "境界のウェイトなし=$TMP/noedge.pfm@100,120"

echo "pictures written to $IMG"
