#!/bin/sh
# Regenerates the pictures under lessons/methods/img/ from the demo scene (Res/scenes/demo.toml).
# Run from anywhere: sh lessons/methods/make-images.sh
# Needs cargo (builds and runs the engine headless) and python3 (lessons/figures.py, no extra modules).
# Figures with words on them are drawn twice: img/NAME.png in English, img/ja/NAME.png in Japanese.
# OPENGL3D=path/to/opengl3d uses an already-built binary instead of `cargo run --release --`.
# With TIMINGS=1 it also prints the AO passes of `render --stats` at 1280x720 (3 runs per method).
set -eu

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
IMG="$HERE/img"
mkdir -p "$IMG/ja"
. "$ROOT/lessons/engine.sh"
# The renders' own messages are not wanted here: only the script's summary lines.
run() { engine "$@" >/dev/null; }
# Every picture keeps the settings' own values (the course's configuration), not the recommended
# configuration `--method NAME` alone runs (docs/bench/defaults.md): the pages' figures describe these.
# `--samples 11` (the demo's count) keeps gtao and vbao off their presets; vbao's slabs are R/2 = 0.5 m.
SMALL="--width 640 --height 360 --ao-resolution half --normals depth --guard-band 0 --layers 1"
METHODS="sao-lesson sao crytek hemisphere hbao angle-based gtao vbao"
fig() { python3 "$ROOT/lessons/figures.py" "$@"; }
fig_ja() { python3 "$ROOT/lessons/figures.py" --lang ja "$@"; }

# Raw and blurred AO of every method (visibility: white = open), and two composites.
for m in $METHODS; do
  run render --method "$m" --view ao-raw $SMALL --samples 11 --out "$IMG/$m-ao-raw.png"
  run render --method "$m" --view ao $SMALL --samples 11 --out "$IMG/$m-ao.png"
done
run render --method sao --view composite $SMALL --out "$IMG/sao-composite.png"
run render --method gtao --view composite $SMALL --samples 11 --out "$IMG/gtao-composite.png"
run render --method vbao --view composite $SMALL --samples 11 --out "$IMG/vbao-composite.png"

# Crytek without the rescale of the occluded fraction (an edited copy of its shader via --res;
# #include is resolved next to the including file, so common.glsl goes along).
V="$TMP/crytek-norescale"
mkdir -p "$V/ao"
cp Res/ao/common.glsl "$V/ao/"
sed 's/clamp(2\.0 \* fraction - 1\.0, 0\.0, 1\.0)/fraction/' Res/ao/crytek.frag > "$V/ao/crytek.frag"
cmp -s "$V/ao/crytek.frag" Res/ao/crytek.frag && { echo "sed did not change crytek.frag" >&2; exit 1; }
run render --method crytek --view ao-raw $SMALL --out "$TMP/crytek.pfm"
run --res "$V" render --method crytek --view ao-raw $SMALL --out "$TMP/crytek-norescale.pfm"
fig grid "$IMG/crytek-rescale.png" 320 180 \
  "rescaled=$TMP/crytek.pfm@320,60" "fraction as is=$TMP/crytek-norescale.pfm@320,60"
fig_ja grid "$IMG/ja/crytek-rescale.png" 320 180 \
  "再スケールあり=$TMP/crytek.pfm@320,60" "割合のまま=$TMP/crytek-norescale.pfm@320,60"

# GTAO: 2 slices always; --samples only adds steps (N/4 per side).
run render --method gtao --samples 11 --view ao-raw $SMALL --out "$TMP/gtao-11.pfm"
run render --method gtao --samples 44 --view ao-raw $SMALL --out "$TMP/gtao-44.pfm"
fig grid "$IMG/gtao-samples.png" 320 180 \
  "--samples 11=$TMP/gtao-11.pfm@120,150" "--samples 44=$TMP/gtao-44.pfm@120,150"

# HBAO before and after the fix of its tangent (commits 6e47616, 4fbc477), on the near floor at the old
# default of 8 taps: the shader before it comes from git history (skipped outside a git checkout).
if git cat-file -e 2711d1e:Res/ao/hbao.frag 2>/dev/null; then
  V="$TMP/hbao-old"
  mkdir -p "$V/ao"
  cp Res/ao/common.glsl "$V/ao/"
  git show 2711d1e:Res/ao/hbao.frag > "$V/ao/hbao.frag"
  run --res "$V" render --method hbao --samples 8 --view ao-raw $SMALL --out "$TMP/hbao-old.pfm"
  run render --method hbao --samples 8 --view ao-raw $SMALL --out "$TMP/hbao-new.pfm"
  fig grid "$IMG/hbao-tangent-fix.png" 320 180 \
    "before (old tangent)=$TMP/hbao-old.pfm@0,180" "now (tangent plane)=$TMP/hbao-new.pfm@0,180"
  fig_ja grid "$IMG/ja/hbao-tangent-fix.png" 320 180 \
    "修正前(古い接線)=$TMP/hbao-old.pfm@0,180" "修正後(接平面)=$TMP/hbao-new.pfm@0,180"
else
  echo "no git history: hbao-tangent-fix.png left as it is" >&2
fi

# VBAO: what lies behind each depth sample (raw buffer; the demo's radius is 1 m, so R/2 is 0.5 m).
for t in 0.1 0.5 3 backface; do
  run render --method vbao --thickness "$t" --view ao-raw $SMALL --samples 11 --out "$TMP/vbao-$t.pfm"
done
fig grid "$IMG/vbao-thickness.png" 320 180 \
  "--thickness 0.1=$TMP/vbao-0.1.pfm@140,140" "--thickness 0.5=$TMP/vbao-0.5.pfm@140,140" \
  "--thickness 3=$TMP/vbao-3.pfm@140,140" "--thickness backface=$TMP/vbao-backface.pfm@140,140"
fig_ja grid "$IMG/ja/vbao-thickness.png" 320 180 \
  "--thickness 0.1=$TMP/vbao-0.1.pfm@140,140" "--thickness 0.5=$TMP/vbao-0.5.pfm@140,140" \
  "--thickness 3=$TMP/vbao-3.pfm@140,140" "--thickness backface=$TMP/vbao-backface.pfm@140,140"

# The two blurs on the same wall: the lesson's 9x9 (taps 2 texels apart) and the separable 2 x 9.
run render --method sao-lesson --view ao $SMALL --out "$TMP/lesson-blur.pfm"
run render --method sao --view ao $SMALL --out "$TMP/sao-blur.pfm"
fig grid "$IMG/sao-blurs.png" 320 180 \
  "sao-lesson: 9x9=$TMP/lesson-blur.pfm@320,60" "sao: separable=$TMP/sao-blur.pfm@320,60"
fig_ja grid "$IMG/ja/sao-blurs.png" 320 180 \
  "sao-lesson: 9×9=$TMP/lesson-blur.pfm@320,60" "sao: 分離可能=$TMP/sao-blur.pfm@320,60"

echo "pictures written to $IMG"

if [ "${TIMINGS:-0}" = 1 ]; then
  for m in $METHODS; do
    for i in 1 2 3; do
      if [ -n "${OPENGL3D:-}" ]; then
        "$OPENGL3D" render --method "$m" --stats --width 1280 --height 720 --out "$TMP/t.png" 2>/dev/null
      else
        cargo run --release --quiet -- render --method "$m" --stats --width 1280 --height 720 --out "$TMP/t.png" 2>/dev/null
      fi
    done | python3 -c '
import json, statistics, sys
runs = [[p for p in json.loads(l)["passes"] if p["group"] == "ao"] for l in sys.stdin if l.strip()]
names = [p["name"] for p in runs[0]]
med = {n: statistics.median(r[i]["ms"] for r in runs) for i, n in enumerate(names)}
tot = statistics.median(sum(p["ms"] for p in r) for r in runs)
print(sys.argv[1], " ".join(f"{n}={v:.1f}" for n, v in med.items()), f"total={tot:.1f}")
' "$m"
  done
fi
