#!/usr/bin/env bash
# roma-viewer headless on game levels and an animated glTF (validation on): cascade levels
# around the camera on aggressor against Embree and one grid, the levels view, a level without
# lights opening readable, CesiumMan played (the animator, the map following the skinned
# positions, the G-buffer drawing them).
# Usage: test_viewer_levels.sh ROMA_VIEWER ROMA_RENDER ROMA_COMPARE SCENES_DIR SCRATCH_DIR
source "$(dirname "$0")/test_viewer_common.sh" "$@"

# 1e. A game level (aggressor, ROMA_LEVELS_DIR) with an AO radius of 1.5 m: the viewer picks
#     cascade levels around the camera as roma-render does (4 here), its AO is roma-render's,
#     and it is nearer Embree's than one grid over the level (--cascades 1).
level=${ROMA_LEVELS_DIR:-}/aggressor
if [ ! -f "$level.glb" ] || [ ! -f "$level.cameras" ]; then
  fail "no game level at $level.glb (set ROMA_LEVELS_DIR)"
else
  lcam=$(sed -n 1p "$level.cameras")
  lcommon=(--scene "$level.glb" --camera "$lcam" --ao-radius 1.5 --size 160x120)
  headless level_auto "on a game level" "${lcommon[@]}" --view ao --frames 16 --ao-samples 16 \
    --linear "$dir/level_auto.pfm" --stats "$dir/level_auto.json"
  headless level_one "on a game level with one grid" "${lcommon[@]}" --view ao --frames 16 --ao-samples 16 \
    --cascades 1 --linear "$dir/level_one.pfm" --stats "$dir/level_one.json"
  "$render" --tracer embree --effects ao --spp 256 "${lcommon[@]}" --quiet --out "$dir/level_reference" \
    >/dev/null 2>&1 || fail "roma-render --tracer embree on the level failed"
  "$render" --tracer roma --effects ao --spp 16 --frames 16 "${lcommon[@]}" --quiet --out "$dir/level_roma" \
    >/dev/null 2>&1 || fail "roma-render --tracer roma on the level failed"
  [ "$(json "$dir/level_auto.json" levels) $(json "$dir/level_one.json" levels)" = "4 1" ] ||
    fail "the viewer did not pick 4 cascade levels for the level (or 1 with --cascades 1)"
  if outputs "$dir/level_auto.pfm" "$dir/level_one.pfm" "$dir/level_reference/ao.pfm" "$dir/level_roma/ao.pfm"; then
    mask=(--mask "$dir/level_reference/coverage.pfm")
    compare_checked "$dir/level_auto.pfm" "$dir/level_reference/ao.pfm" "${mask[@]}" >"$dir/level_auto.txt"
    compare_checked "$dir/level_one.pfm" "$dir/level_reference/ao.pfm" "${mask[@]}" >"$dir/level_one.txt"
    compare_checked "$dir/level_auto.pfm" "$dir/level_roma/ao.pfm" "${mask[@]}" >"$dir/level_vs_roma.txt"
    la=$(metric "$dir/level_auto.txt" mean_abs)
    lo=$(metric "$dir/level_one.txt" mean_abs)
    lr=$(metric "$dir/level_vs_roma.txt" mean_abs)
    echo "aggressor AO (radius 1.5) MAE vs Embree: 4 cascade levels $la, one grid $lo; viewer vs roma-render $lr"
    # Measured: 0.0362, 0.0969 and 5.1e-6.
    below "$la" 0.037 || fail "the viewer's cascaded AO on the level is further from Embree than 0.037 (MAE $la)"
    numbers "$la" "$lo" && awk -v a="$la" -v b="$lo" 'BEGIN { exit !(a <= 0.40 * b) }' ||
      fail "cascade levels do not bring the level's AO error under 0.40 of one grid's ($la against $lo)"
    below "$lr" 0.00001 || fail "the viewer's cascaded AO differs from roma-render's (MAE $lr)"
  fi
  # The levels view colours each surface point by the level that holds it: from camera 1 the 4
  # levels' colours are all seen (measured: 3,124, 1,108, 267 and 202 of 4,800 pixels, the rest
  # their cubes' faces in black); one grid shows the first colour alone.
  for k in 0 1; do
    headless "levels_view_$k" "--view levels --cascades $k" "${lcommon[@]}" --size 80x60 --view levels --frames 1 \
      --cascades "$k" --linear "$dir/levels_view_$k.pfm"
  done
  levels_seen() { # PFM: the levels whose colour (compose.comp's level_colour) some pixel has
    python3 - "$1" <<'PY'
import struct, sys
f = open(sys.argv[1], "rb")
kind = f.readline().strip()
w, h = map(int, f.readline().split())
scale = float(f.readline())
v = struct.unpack(("<" if scale < 0 else ">") + "%df" % (w * h * 3), f.read(12 * w * h))
palette = [(1, .2, .2), (.2, 1, .2), (.25, .4, 1), (1, .9, .2), (1, .2, 1), (.2, 1, 1), (1, .55, .1), (1, 1, 1)]
seen = set()
for i in range(w * h):
    c = v[3 * i:3 * i + 3]
    m = max(c)
    if m > 0:
        d = [sum((c[k] / m - p[k]) ** 2 for k in range(3)) for p in palette]
        best = min(range(8), key=lambda j: d[j])
        if d[best] < 0.01:
            seen.add(best)
print(" ".join(str(l) for l in sorted(seen)))
PY
  }
  [ "$(levels_seen "$dir/levels_view_0.pfm")" = "0 1 2 3" ] ||
    fail "the levels view does not show the 4 levels (it shows: $(levels_seen "$dir/levels_view_0.pfm"))"
  [ "$(levels_seen "$dir/levels_view_1.pfm")" = "0" ] ||
    fail "the levels view of one grid shows more than its level (it shows: $(levels_seen "$dir/levels_view_1.pfm"))"
fi

# 1f. A level without lights (oa_dm4) opens readable: the sky that AO scales is 1 there (0.2
#     where the scene has lights, as aggressor), so the composed picture is not nearly black.
dm4=${ROMA_LEVELS_DIR:-}/oa_dm4
if [ -f "$dm4.glb" ] && [ -f "$dm4.cameras" ]; then
  headless unlit "on a level without lights" --scene "$dm4.glb" --camera "$(sed -n 1p "$dm4.cameras")" \
    --view composed --frames 2 --ao-radius 1.5 --size 80x60 --linear "$dir/unlit.pfm" --stats "$dir/unlit.json"
  near() { numbers "$1" "$2" && awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; exit !(d < 1e-6 && d > -1e-6) }'; }
  near "$(json "$dir/unlit.json" sky)" 1 || fail "the sky of a level without lights is not 1"
  [ ! -f "$dir/level_auto.json" ] || near "$(json "$dir/level_auto.json" sky)" 0.2 ||
    fail "the sky of a level with lights is not 0.2"
  # Measured: a mean of 0.523 (0.105 with the lit scenes' sky).
  unlit=$(python3 - "$dir/unlit.pfm" <<'PY'
import struct, sys
f = open(sys.argv[1], "rb")
kind = f.readline().strip()
w, h = map(int, f.readline().split())
scale = float(f.readline())
n = w * h * (3 if kind == b"PF" else 1)
print(sum(struct.unpack(("<" if scale < 0 else ">") + "%df" % n, f.read(4 * n))) / n)
PY
)
  awk -v m="${unlit:-0}" 'BEGIN { exit !(m >= 0.50) }' ||
    fail "the composed view of a level without lights is dark (mean ${unlit:-none}, expected >= 0.50)"
else
  fail "no game level at $dm4.glb (set ROMA_LEVELS_DIR)"
fi

# 2. An animated, skinned glTF played: validation clean, a picture written.
"$viewer" --headless --validation --scene "$scenes/CesiumMan.glb" --play --frames 6 --size 96x96 \
  --screenshot "$dir/cesium.png" >"$dir/cesium.out" 2>&1 \
  || { cat "$dir/cesium.out" >&2; fail "roma-viewer on CesiumMan (playing) failed"; }
[ -s "$dir/cesium.png" ] || fail "no picture of CesiumMan"

finish levels
