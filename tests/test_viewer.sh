#!/usr/bin/env bash
# roma-viewer, as a person and a script use it (validation on in every run):
#  - headless, the AO view accumulated over 32 frames on the built-in room, compared with
#    the Embree reference (roma-render --tracer embree) on the same camera and radius, and
#    with roma-render's own ROMA AO: the viewer (public API, its own rasterized G-buffer)
#    must be as accurate as roma-render (the same public passes on the reference's primary
#    rays, accumulated offline), and nearly equal to it;
#  - its own reference comparison, one-bounce GI against roma-render's and the reference,
#    and the occupancy-slice view (no surface point in an empty cell);
#  - an animated glTF played headless (the animator, the map following the skinned
#    positions, the G-buffer drawing them);
#  - the window (GLFW, swapchain, Dear ImGui) for a few frames under Xvfb;
#  - bad input: an unknown view lists the valid ones; a missing scene names the file.
# Usage: test_viewer.sh ROMA_VIEWER ROMA_RENDER ROMA_COMPARE SCENES_DIR SCRATCH_DIR
set -u
viewer=$1
render=$2
compare=$3
scenes=$4
dir=$5
failures=0
rm -rf "$dir"
mkdir -p "$dir"

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
metric() {
  awk -v k="$2" '$1 == k { print $2; found = 1 } END { exit !found }' "$1"
}
json() { # FILE KEY: a top-level value of a stats file
  python3 -c 'import json, sys; v = json.load(open(sys.argv[1]))[sys.argv[2]]; print(" ".join(v) if isinstance(v, list) else v)' "$1" "$2"
}
# headless NAME WHAT ARGS...: a headless run with validation, its output in $dir/NAME.out,
# shown and counted as a failure ("roma-viewer WHAT failed") when it exits non-zero.
headless() {
  local name=$1 what=$2
  shift 2
  "$viewer" --headless --validation "$@" >"$dir/$name.out" 2>&1 || { cat "$dir/$name.out" >&2; fail "roma-viewer $what failed"; }
}
# numbers VALUE...: every value a decimal number (a missing or empty metric is not: awk would
# compare it as a string, and "" <= 0.037 holds).
numbers() {
  local v
  for v in "$@"; do
    [[ $v =~ ^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] || return 1
  done
}
# below VALUE BOUND: VALUE <= BOUND, both numbers
below() {
  numbers "$1" "$2" && awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'
}
# The checks themselves: a missing, empty or non-numeric value fails them.
below "" 0.5 && fail "below passes an empty value"
below "none" 0.5 && fail "below passes a word"
below 0.4 "" && fail "below passes an empty bound"
numbers 0.1 "" && fail "numbers passes an empty value"
# compare_checked ARGS...: roma-compare, a failure when it does not exit 0
compare_checked() {
  "$compare" "$@" || fail "roma-compare $* exited $?"
}
if [ -n "${ROMA_TOOL_PRELOAD:-}" ]; then
  for tool in viewer render compare; do
    printf '#!/bin/sh\nLD_PRELOAD="%s" exec "%s" "$@"\n' "$ROMA_TOOL_PRELOAD" "${!tool}" >"$dir/$tool-preloaded"
    chmod +x "$dir/$tool-preloaded"
    eval "$tool=\$dir/\$tool-preloaded"
  done
fi

# 1. AO against the reference and against roma-render's ROMA (same samples: the AO
#    effect draws the reference's sequences; frame f uses samples f*8 .. f*8+7).
cam="0,1,1.9,0,0.9,0,60"
"$viewer" --headless --validation --view ao --frames 32 --ao-samples 8 --ao-radius 0.5 --camera "$cam" \
  --size 160x120 --linear "$dir/viewer_ao.pfm" --screenshot "$dir/viewer_ao.png" >"$dir/viewer.out" 2>&1 \
  || { cat "$dir/viewer.out" >&2; fail "roma-viewer --headless (AO view) failed"; }
"$render" --tracer embree --effects ao --spp 256 --ao-radius 0.5 --camera "$cam" --size 160x120 --quiet \
  --out "$dir/reference" >/dev/null 2>&1 || fail "roma-render --tracer embree failed"
"$render" --tracer roma --effects ao --spp 8 --frames 32 --ao-radius 0.5 --camera "$cam" \
  --size 160x120 --quiet --out "$dir/roma" >/dev/null 2>&1 || fail "roma-render --tracer roma failed"
if [ -f "$dir/viewer_ao.pfm" ] && [ -f "$dir/reference/ao.pfm" ] && [ -f "$dir/roma/ao.pfm" ]; then
  compare_checked "$dir/viewer_ao.pfm" "$dir/reference/ao.pfm" --mask "$dir/reference/coverage.pfm" >"$dir/vs_reference.txt"
  compare_checked "$dir/viewer_ao.pfm" "$dir/roma/ao.pfm" --mask "$dir/reference/coverage.pfm" >"$dir/vs_roma.txt"
  compare_checked "$dir/roma/ao.pfm" "$dir/reference/ao.pfm" --mask "$dir/reference/coverage.pfm" >"$dir/roma_vs_reference.txt"
  vr=$(metric "$dir/vs_reference.txt" mean_abs)
  vo=$(metric "$dir/vs_roma.txt" mean_abs)
  rr=$(metric "$dir/roma_vs_reference.txt" mean_abs)
  echo "AO MAE over 19,200 pixels: viewer vs Embree $vr (roma-render's ROMA vs Embree $rr), viewer vs roma-render $vo"
  # Measured: 0.0449 (roma-render 0.0447) and 0.0011.
  below "$vr" 0.050 || fail "the viewer's AO is further from the reference than 0.050 (MAE $vr)"
  below "$vo" 0.0015 || fail "the viewer's AO differs from roma-render's ROMA AO by more than 0.0015 (MAE $vo)"
fi

# 1b. The viewer's own comparison (--compare-reference runs roma-render beside it) gives
#     the MAE roma-compare gives.
"$viewer" --headless --validation --view ao --frames 32 --ao-samples 8 --ao-radius 0.5 --camera "$cam" \
  --size 160x120 --compare-reference --reference-spp 256 >"$dir/compare.out" 2>&1 \
  || { cat "$dir/compare.out" >&2; fail "roma-viewer --compare-reference failed"; }
own=$(sed -n 's/.*AO against the Embree reference.*MAE \([0-9.]*\) over 19200 covered pixels.*/\1/p' "$dir/compare.out")
if [ -z "$own" ]; then
  fail "roma-viewer --compare-reference printed no MAE over 19200 pixels"
elif [ -n "${vr:-}" ]; then
  numbers "$own" "$vr" && awk -v a="$own" -v b="$vr" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 0.00006) }' \
    || fail "the viewer's own MAE ($own) is not roma-compare's ($vr)"
fi

# 1c. Traced at a resolution divisor (one pixel of each 2x2 or 4x4 block a frame, upsampled),
#     the 32 frames' AO stays as close to Embree's: measured 0.0445 and 0.0455 (every pixel:
#     0.0449).
for d in 2:0.047 4:0.048; do
  "$viewer" --headless --validation --view ao --frames 32 --ao-samples 8 --ao-radius 0.5 --camera "$cam" \
    --size 160x120 --compare-reference --reference-spp 256 --resolution-divisor "${d%%:*}" \
    >"$dir/divisor_${d%%:*}.out" 2>&1 || { cat "$dir/divisor_${d%%:*}.out" >&2; fail "--resolution-divisor ${d%%:*} failed"; }
  got=$(sed -n 's/.*AO against the Embree reference.*MAE \([0-9.]*\) over 19200 covered pixels.*/\1/p' \
    "$dir/divisor_${d%%:*}.out")
  below "$got" "${d##*:}" || fail "AO at --resolution-divisor ${d%%:*}: MAE ${got:-?} against Embree, above ${d##*:}"
done

# 1b'. Direct light (the room's spot and its ceiling area light) against the reference.
"$viewer" --headless --validation --view direct --frames 32 --area-samples 8 --camera "$cam" --size 160x120 \
  --compare-reference --reference-spp 256 >"$dir/direct.out" 2>&1 \
  || { cat "$dir/direct.out" >&2; fail "roma-viewer --view direct --compare-reference failed"; }
direct=$(sed -n 's/.*direct light against the Embree reference.*MAE \([0-9.]*\) over.*/\1/p' "$dir/direct.out")
echo "direct light MAE (viewer vs Embree): ${direct:-none}"
# Measured: 0.0027 (the mean reflected radiance is about 0.09).
[ -n "$direct" ] && below "$direct" 0.0032 ||
  fail "the viewer's direct light is further from the reference than 0.0032 ($direct)"

# 1b''. One-bounce GI through the public effect (roma_gi_effect, 1 bounce ray a frame) against
#      roma-render's offline accumulation of it with the same route for the spot (shadow rays) and the
#      same samples, and against the reference.
"$viewer" --headless --validation --view gi --frames 32 --camera "$cam" --size 160x120 \
  --linear "$dir/viewer_gi.pfm" >"$dir/gi.out" 2>&1 || { cat "$dir/gi.out" >&2; fail "roma-viewer --view gi failed"; }
"$render" --tracer roma --effects gi --gi-punctual rays --spp 1 --frames 32 --camera "$cam" \
  --size 160x120 --quiet --out "$dir/roma_gi" >/dev/null 2>&1 || fail "roma-render --effects gi failed"
"$render" --tracer embree --effects gi --spp 256 --camera "$cam" --size 160x120 --quiet \
  --out "$dir/reference_gi" >/dev/null 2>&1 || fail "roma-render --tracer embree --effects gi failed"
if [ -f "$dir/viewer_gi.pfm" ] && [ -f "$dir/roma_gi/gi.pfm" ] && [ -f "$dir/reference_gi/gi.pfm" ]; then
  compare_checked "$dir/viewer_gi.pfm" "$dir/roma_gi/gi.pfm" --mask "$dir/reference_gi/coverage.pfm" >"$dir/gi_vs_roma.txt"
  compare_checked "$dir/viewer_gi.pfm" "$dir/reference_gi/gi.pfm" --mask "$dir/reference_gi/coverage.pfm" \
    >"$dir/gi_vs_reference.txt"
  go=$(metric "$dir/gi_vs_roma.txt" mean_abs)
  gr=$(metric "$dir/gi_vs_reference.txt" mean_abs)
  echo "GI MAE over 19,200 pixels: viewer vs roma-render $go, viewer vs Embree $gr"
  gb=$(metric "$dir/gi_vs_reference.txt" bias)
  echo "GI bias against Embree: $gb"
  # Measured: 0.00057 (1.4% of the mean 0.040), 0.0189 and +0.00107 (+2.7%; +0.00062 while
  # area-light segments across the lamp's 2 cm gap were taken as free only up to two origin
  # offsets, docs/accuracy.md). Most of the MAE is the rare bright samples of bounce rays that
  # reach the ceiling the lamp lights from 2 cm, on both sides, on different pixels.
  below "$go" 0.0007 || fail "the viewer's GI differs from roma-render's by more than 0.0007 (MAE $go)"
  below "$gr" 0.020 || fail "the viewer's GI is further from the reference than 0.020 (MAE $gr)"
  [ -n "$gb" ] && below "${gb#-}" 0.0012 || fail "the viewer's GI is biased by more than 0.0012 against Embree ($gb)"
fi

# 1b''''. GI while a surface moves: tests/viewer/moving_wall.gltf slides a red wall over a
#       floor under a point light (a node animation). At --time 0.9 the viewer's GI matches
#       roma-render's of the scene posed at that time, so the bounce hits find the wall where
#       it is now (the GI effect rebuilds its surface grid from the map's animated positions;
#       the viewer poses nothing on the host for it).
wall="$(cd "$(dirname "$0")/viewer" && pwd)/moving_wall.gltf"
wall_cam="0,3,4,0,0.3,0,50"
"$viewer" --headless --validation --scene "$wall" --time 0.9 --view gi --frames 32 --camera "$wall_cam" \
  --size 160x120 --linear "$dir/wall_gi.pfm" >"$dir/wall_gi.out" 2>&1 \
  || { cat "$dir/wall_gi.out" >&2; fail "roma-viewer --view gi on the moving wall failed"; }
"$render" --scene "$wall" --time 0.9 --tracer roma --effects gi --gi-punctual rays --spp 1 \
  --frames 32 --camera "$wall_cam" --size 160x120 --quiet --out "$dir/wall_roma" >/dev/null 2>&1 \
  || fail "roma-render --effects gi on the moving wall failed"
if [ -f "$dir/wall_gi.pfm" ] && [ -f "$dir/wall_roma/gi.pfm" ]; then
  compare_checked "$dir/wall_gi.pfm" "$dir/wall_roma/gi.pfm" --mask "$dir/wall_roma/coverage.pfm" >"$dir/wall_gi.txt"
  wg=$(metric "$dir/wall_gi.txt" mean_abs)
  echo "GI with the wall moved (time 0.9): viewer vs roma-render of the posed scene, MAE $wg"
  # Measured: 0.00029 (1.2% of the mean); with the surfaces left at the rest pose 0.0195 (82%).
  below "$wg" 0.00035 || fail "the viewer's GI on the moving wall differs from the posed scene's (MAE $wg)"
fi

# 1b'''. The steps view: the un-snapped shadow rays to the spot that walk every step without a
#       hit and without reaching the light or leaving the map (magenta: they gave up and count
#       as lit) are many with the paper's 8 steps and few with 64.
magenta() { # PFM: the share of pure magenta pixels
  python3 -c '
import struct, sys
f = open(sys.argv[1], "rb"); kind = f.readline().strip(); w, h = map(int, f.readline().split()); f.readline()
v = struct.unpack("<%df" % (3 * w * h), f.read(12 * w * h))
print(sum(1 for i in range(w * h) if v[3*i] > 0.99 and v[3*i+1] < 0.01 and v[3*i+2] > 0.99) / (w * h))' "$1"
}
for steps in 8 64; do
  headless "steps_$steps" "--view steps" --view steps --max-steps $steps --frames 1 --camera "$cam" --size 160x120 \
    --linear "$dir/steps_$steps.pfm"
done
if [ -f "$dir/steps_8.pfm" ] && [ -f "$dir/steps_64.pfm" ]; then
  g8=$(magenta "$dir/steps_8.pfm"); g64=$(magenta "$dir/steps_64.pfm")
  echo "steps view: shadow rays to the spot that gave up: $g8 of the pixels with 8 steps, $g64 with 64"
  # Measured: 0.859 with 8 steps, 0.0013 with 64 (19,200 pixels).
  numbers "$g8" "$g64" && awk -v a="$g8" -v b="$g64" 'BEGIN { exit !(a > 0.85 && b < 0.002) }' || fail "the steps view: gave up $g8 (8), $g64 (64)"
fi

# 1b4. The rotated-map view: map 0 and map 9 of the 16 seen along their directions; the
#      closed room covers part of each map's square (the rest: empty columns), a different
#      part along each direction.
occupied_share() { # PFM: the share of the centred square's texels whose column holds a cell
  python3 -c '
import struct, sys
f = open(sys.argv[1], "rb"); kind = f.readline().strip(); w, h = map(int, f.readline().split()); f.readline()
v = struct.unpack("<%df" % (3 * w * h), f.read(12 * w * h))
side = min(w, h); x0 = (w - side) // 2; y0 = (h - side) // 2
empty = sum(1 for y in range(y0, y0 + side) for x in range(x0, x0 + side)
            if max(abs(v[3*(y*w+x)] - 0.02), abs(v[3*(y*w+x)+1] - 0.04), abs(v[3*(y*w+x)+2] - 0.2)) < 1e-3)
print(1.0 - empty / float(side * side))' "$1"
}
for k in 0 9; do
  headless "rotated_$k" "--view rotated-map --map $k" --view rotated-map --map $k --frames 1 --size 160x120 \
    --linear "$dir/rotated_$k.pfm"
done
if [ -f "$dir/rotated_0.pfm" ] && [ -f "$dir/rotated_9.pfm" ]; then
  r0=$(occupied_share "$dir/rotated_0.pfm"); r9=$(occupied_share "$dir/rotated_9.pfm")
  echo "rotated-map view: occupied columns: $r0 of map 0's texels, $r9 of map 9's"
  # Measured: 0.348 (map 0) and 0.490 (map 9) of 14,400 texels.
  numbers "$r0" "$r9" && awk -v a="$r0" -v b="$r9" 'BEGIN { exit !(a > 0.33 && a < 0.37 && b > 0.47 && b < 0.51) }' \
    || fail "the rotated-map view: occupied shares $r0 (map 0), $r9 (map 9)"
fi

# 1b5. The ray-start view: AO rays whose start (offset + skip, walked through the BOM) meets
#      another surface light up where surfaces meet (the room's edges), and more of them with
#      a longer skip.
blocked_share() { # PFM: the share of pixels with at least one of the 16 starts blocked
  python3 -c '
import struct, sys
f = open(sys.argv[1], "rb"); kind = f.readline().strip(); w, h = map(int, f.readline().split()); f.readline()
v = struct.unpack("<%df" % (3 * w * h), f.read(12 * w * h))
print(sum(1 for i in range(w * h) if v[3*i] > 0.0) / float(w * h))' "$1"
}
for skip in 1.6 3.2; do
  headless "ray_start_$skip" "--view ray-start" --view ray-start --ao-skip $skip --frames 1 --camera "$cam" \
    --size 160x120 --linear "$dir/ray_start_$skip.pfm"
done
if [ -f "$dir/ray_start_1.6.pfm" ] && [ -f "$dir/ray_start_3.2.pfm" ]; then
  s1=$(blocked_share "$dir/ray_start_1.6.pfm"); s2=$(blocked_share "$dir/ray_start_3.2.pfm")
  echo "ray-start view: pixels with a blocked start: $s1 with the default skip (1.6 cells), $s2 with 3.2"
  # Measured: 0.0918 and 0.169 of 19,200 pixels.
  numbers "$s1" "$s2" && awk -v a="$s1" -v b="$s2" 'BEGIN { exit !(a > 0.085 && a < 0.1 && b > 0.16 && b < 0.18) }' || fail "the ray-start view: $s1 (1.6), $s2 (3.2)"
fi

# 1b6. Many lights: 256 point lights added to the room's spot, 8 of them traced per pixel and
#      frame (roma_light_settings.lights_per_frame): the accumulated direct light converges to
#      the image with every light traced (its noise halves from 16 to 64 frames), unbiased.
for run in "8 16" "8 64" "256 16"; do
  set -- $run
  headless "many_$1_$2" "--many-lights" --scene builtin:cornell_spot --view direct --many-lights 256 \
    --lights-per-frame "$1" --frames "$2" --camera "$cam" --size 80x60 --linear "$dir/many_$1_$2.pfm" \
    --stats "$dir/many_$1_$2.json"
done
headless many_none "(spot only)" --scene builtin:cornell_spot --view direct --frames 16 --camera "$cam" --size 80x60 \
  --linear "$dir/many_none.pfm"
if [ -f "$dir/many_8_16.pfm" ] && [ -f "$dir/many_8_64.pfm" ] && [ -f "$dir/many_256_16.pfm" ] && [ -f "$dir/many_none.pfm" ]; then
  for a in 8_16 8_64 none; do compare_checked "$dir/many_$a.pfm" "$dir/many_256_16.pfm" >"$dir/many_$a.txt"; done
  r16=$(metric "$dir/many_8_16.txt" relative); r64=$(metric "$dir/many_8_64.txt" relative)
  b16=$(metric "$dir/many_8_16.txt" bias); b64=$(metric "$dir/many_8_64.txt" bias)
  mean=$(metric "$dir/many_8_16.txt" mean_b); spot=$(metric "$dir/many_none.txt" mean_a)
  echo "many lights: 8 of 256 per pixel and frame, from every light traced: $r16 after 16 frames, $r64 after 64" \
    "(bias $b16, $b64 on a mean of $mean; the spot alone: $spot)"
  # Measured (4,800 pixels): 0.169 and 0.0832 (bias -0.0007 and +0.0004 on 0.148; the spot alone 0.0061).
  # The bias is the mean of 4,800 pixels' errors: within three of its standard errors (a
  # pixel's error spreads about 1.25 times its mean absolute error; 1.6 and 1.8 of them
  # measured). A bound of 0.4% of the mean, set on one lucky run (0.25%), failed when the
  # shadow rays' end walk (roma_light_end_blocked) changed which lights some pixels see.
  numbers "$r16" "$r64" "$b16" "$b64" "$mean" "$spot" && awk -v a="$r16" -v b="$r64" -v c="$b16" -v d="$b64" -v m="$mean" -v s="$spot" 'BEGIN {
    se16 = 1.25 * a * m / sqrt(4800); se64 = 1.25 * b * m / sqrt(4800)
    exit !(a < 0.175 && b < 0.087 && b < 0.6 * a && c * c < (3 * se16) ^ 2 && d * d < (3 * se64) ^ 2 && s < 0.1 * m) }' \
    || fail "many lights: $r16 (16 frames), $r64 (64 frames), bias $b16, $b64, mean $mean, spot alone $spot"
  case " $(json "$dir/many_8_16.json" passes) " in *" many_lights "*) ;; *) fail "no many_lights pass in the stats" ;; esac
fi

# 1c. The occupancy slice: every surface point the rasterizer draws lies in a cell the
#     voxelization marked (conservative), at three layers of the room.
for layer in "y 22" "y 60" "x 64"; do
  set -- $layer
  "$viewer" --headless --validation --view bom-slice --slice-axis "$1" --slice-depth "$2" --frames 2 \
    --size 320x240 >"$dir/slice_$1$2.out" 2>&1 || { cat "$dir/slice_$1$2.out" >&2; fail "bom-slice $1 = $2 failed"; }
  line=$(grep "occupancy slice" "$dir/slice_$1$2.out")
  occupied=$(echo "$line" | sed -n 's/.*: \([0-9]*\) pixels on occupied cells, \([0-9]*\) on empty.*/\1/p')
  empty=$(echo "$line" | sed -n 's/.*: \([0-9]*\) pixels on occupied cells, \([0-9]*\) on empty.*/\2/p')
  # Measured: 4862 / 849 / 504 pixels on occupied cells, 0 on empty ones.
  [ -n "$occupied" ] && [ "$occupied" -ge 400 ] || fail "slice $1 = $2: only '$occupied' pixels on occupied cells"
  [ "${empty:-1}" -eq 0 ] || fail "slice $1 = $2: $empty surface pixels lie in cells the voxelization left empty"
done

# 1d. A glTF file's camera by index: one the file lacks is refused with the count; the
#     stats give libroma's device memory.
"$viewer" --headless --scene "$scenes/2CylinderEngine.glb" --gltf-camera 1 --frames 1 --size 32x24 \
  >"$dir/gltf_camera.out" 2>&1
[ $? -eq 1 ] || fail "--gltf-camera 1 on a file with one camera did not fail"
grep -q "the file has 1 perspective camera" "$dir/gltf_camera.out" || fail "--gltf-camera 1: the count is not named"
"$viewer" --headless --validation --frames 2 --size 32x24 --stats "$dir/memory.json" >/dev/null 2>&1 \
  || fail "roma-viewer --stats failed"
python3 -c 'import json, sys; assert json.load(open(sys.argv[1]))["libroma_device_memory_bytes"] > 1000000' \
  "$dir/memory.json" || fail "the stats do not give libroma's device memory"
# A preset sets the array's RES and A (roma/presets.h); a later --angular overrides its A.
"$viewer" --headless --validation --frames 1 --size 32x24 --preset low --stats "$dir/preset_low.json" \
  >/dev/null 2>&1 || fail "roma-viewer --preset low failed"
"$viewer" --headless --validation --frames 1 --size 32x24 --preset high --angular 3 --stats "$dir/preset_high.json" \
  >/dev/null 2>&1 || fail "roma-viewer --preset high --angular 3 failed"
[ "$(json "$dir/preset_low.json" resolution) $(json "$dir/preset_low.json" angular)" = "128 2" ] &&
  [ "$(json "$dir/preset_high.json" resolution) $(json "$dir/preset_high.json" angular)" = "256 3" ] ||
  fail "--preset does not set the array's RES and A"

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
  if [ -f "$dir/level_auto.pfm" ] && [ -f "$dir/level_one.pfm" ] && [ -f "$dir/level_reference/ao.pfm" ] &&
    [ -f "$dir/level_roma/ao.pfm" ]; then
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

# 3. The window: swapchain, interface, two frames in flight.
if ! command -v xvfb-run >/dev/null; then
  fail "xvfb-run is missing (./install-deps.sh installs xvfb): the window was not tested"
else
  xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --frames 12 --size 320x200 \
    --view map --screenshot "$dir/window.png" >"$dir/window.out" 2>&1 \
    || { cat "$dir/window.out" >&2; fail "roma-viewer in a window (Xvfb) failed"; }
  [ -s "$dir/window.png" ] || fail "no picture from the window run"
fi

# 3b. Scripted windows (tests/viewer/*.script): an orbit of 60 frames ends with a finite
#     picture; turning an effect off drops its pass and changes the picture; a 1x1 window,
#     minimising and a malformed file dropped in leave the viewer running.
scripts=$(cd "$(dirname "$0")/viewer" && pwd)
printf '{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]' >"$dir/malformed.gltf"
windowed() { # NAME SCRIPT: run it in a window under Xvfb, stats in $dir/NAME.json
  local name=$1 script=$2
  (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 160x120 --script "$script" \
     --stats "$dir/$name.json" --linear "$dir/$name.pfm") >"$dir/$name.out" 2>&1
}
if command -v xvfb-run >/dev/null; then
  windowed orbit "$scripts/orbit.script" || { cat "$dir/orbit.out" >&2; fail "the scripted orbit failed"; }
  frames=$(json "$dir/orbit.json" frames)
  [ "${frames:-0}" -ge 64 ] || fail "the orbit ran ${frames:-no} frames, expected at least 64"
  compare_checked "$dir/orbit.pfm" "$dir/orbit.pfm" >"$dir/orbit.cmp" 2>&1
  grep -q "^non_finite" "$dir/orbit.cmp" && fail "the picture after the orbit has NaN or infinite pixels"
  grep -q "^pixels  *19200" "$dir/orbit.cmp" || fail "the picture after the orbit is not 160x120"

  windowed all "$scripts/still.script" || { cat "$dir/all.out" >&2; fail "the still script failed"; }
  for effect in ao direct gi; do
    windowed "${effect}_off" "$scripts/${effect}_off.script" || { cat "$dir/${effect}_off.out" >&2; fail "$effect off failed"; }
  done
  passes_all=$(json "$dir/all.json" passes)
  passes_ao=$(json "$dir/ao_off.json" passes)
  passes_direct=$(json "$dir/direct_off.json" passes)
  passes_gi=$(json "$dir/gi_off.json" passes)
  case " $passes_all " in *" ao "*) ;; *) fail "the composed view ran no ao pass ($passes_all)" ;; esac
  case " $passes_all " in *" direct_light "*) ;; *) fail "the composed view ran no direct_light pass ($passes_all)" ;; esac
  case " $passes_ao " in *" ao "*) fail "ao off still ran the ao pass ($passes_ao)" ;; esac
  case " $passes_all " in *" gi "*) ;; *) fail "the composed view ran no gi pass ($passes_all)" ;; esac
  case " $passes_direct " in *" direct_light "*) fail "direct off still ran the direct_light pass ($passes_direct)" ;; esac
  case " $passes_gi " in *" gi "*) fail "gi off still ran the gi pass ($passes_gi)" ;; esac
  for effect in ao direct gi; do
    compare_checked "$dir/all.pfm" "$dir/${effect}_off.pfm" >"$dir/${effect}_off.cmp" 2>&1
    d=$(metric "$dir/${effect}_off.cmp" mean_abs)
    awk -v d="${d:-0}" 'BEGIN { exit !(d > 0.001) }' || fail "turning $effect off did not change the picture (MAE ${d:-none})"
  done

  # Moving: the history is reprojected (not thrown away), so after a 30-frame orbit the AO
  # is far closer to the reference at the final camera than a picture of one frame; the
  # a-trous filter alone, on single frames, does most of that too.
  for variant in orbit_ao orbit_ao_fresh orbit_ao_filtered; do
    (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 160x120 --ao-radius 0.5 \
       --script "$scripts/$variant.script" --stats "$dir/$variant.json" --linear "$dir/$variant.pfm") \
       >"$dir/$variant.out" 2>&1 || { cat "$dir/$variant.out" >&2; fail "$variant failed"; }
  done
  final=$(json "$dir/orbit_ao.json" camera)
  "$render" --tracer embree --effects ao --spp 256 --ao-radius 0.5 --camera "$final" --size 160x120 --quiet \
    --out "$dir/orbit_reference" >/dev/null 2>&1 || fail "the reference at the orbit's end failed"
  for variant in orbit_ao orbit_ao_fresh orbit_ao_filtered; do
    compare_checked "$dir/$variant.pfm" "$dir/orbit_reference/ao.pfm" --mask "$dir/orbit_reference/coverage.pfm" \
      >"$dir/$variant.cmp" 2>&1
  done
  kept=$(metric "$dir/orbit_ao.cmp" mean_abs)
  fresh=$(metric "$dir/orbit_ao_fresh.cmp" mean_abs)
  filtered=$(metric "$dir/orbit_ao_filtered.cmp" mean_abs)
  echo "AO after an orbit, MAE against Embree: reprojected history $kept, one frame $fresh, one frame filtered $filtered"
  # Measured: 0.0573, 0.1439 and 0.0678 (a still camera converges to 0.0449); before the viewer
  # used libroma's temporal effect (its own shader then): 0.0578, 0.1439, 0.0678.
  below "${filtered:-1}" 0.073 || fail "the filtered single frame is further than 0.073 from the reference ($filtered)"
  below "${kept:-1}" 0.063 || fail "after the orbit the reprojected AO is further than 0.063 from the reference ($kept)"
  awk -v k="${kept:-1}" -v f="${fresh:-0}" 'BEGIN { exit !(k < 0.5 * f) }' \
    || fail "the reprojected history does not halve the error of a single frame ($kept against $fresh)"

  windowed resilience "$scripts/resilience.script" || { cat "$dir/resilience.out" >&2; fail "the resilience script failed"; }
  [ "$(json "$dir/resilience.json" scene_failures)" = "1" ] || fail "the malformed file was not refused once"
  grep -q "cannot open malformed.gltf" "$dir/resilience.out" || fail "the malformed file is not named in a message"
  [ "$(json "$dir/resilience.json" validation_messages)" = "0" ] || fail "validation messages in the resilience script"
  [ "$(json "$dir/resilience.json" resolution) $(json "$dir/resilience.json" angular)" = "64 2" ] \
    || fail "RES 64 and A 2, set by the script, did not reach the map"

  # Quitting while the Embree reference renders (640x480 at 4,096 samples a pixel: about 150 s
  # here) stops it: measured 4.9 s to quit with it stopped (23 s with a build beside it), and
  # at 1,024 samples 41 s when the viewer waited for it.
  started=$(date +%s)
  (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 640x480 --reference-spp 4096 \
     --script "$scripts/quit_while_reference.script" --stats "$dir/quit_reference.json") \
    >"$dir/quit_reference.out" 2>&1 || { cat "$dir/quit_reference.out" >&2; fail "the quit-while-reference script failed"; }
  took=$(( $(date +%s) - started ))
  grep -q "quitting stopped the reference render" "$dir/quit_reference.out" \
    || fail "quitting did not stop the reference render"
  [ "$took" -le 60 ] || fail "quitting waited ${took} s for the reference instead of stopping it"
  pgrep -f "roma-viewer-reference-" >/dev/null && fail "a reference render outlived the viewer"

  # The scene's cameras: a glTF file with two, the second picked as the interface's button picks
  # it (script verb camera); a camera the scene lacks is refused with a message.
  (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 160x120 \
     --scene "$scripts/two_cameras.gltf" --script "$scripts/cameras.script" --stats "$dir/cameras.json") \
    >"$dir/cameras.out" 2>&1 || { cat "$dir/cameras.out" >&2; fail "the cameras script failed"; }
  grep -q "the scene has no camera 5 (it has 2)" "$dir/cameras.out" || fail "camera 5 of 2 was not refused with a message"
  python3 - "$(json "$dir/cameras.json" camera)" <<'EOF' || fail "the viewer's camera is not the file's second camera"
import sys
got = [float(x) for x in sys.argv[1].split(",")]
want = [3, 1, 0, 2, 1, 0, 57.29578]  # translation (3, 1, 0), turned to look along -x, yfov 1 rad
sys.exit(0 if all(abs(a - b) < 1e-3 for a, b in zip(got, want)) and len(got) == 7 else 1)
EOF
fi

# 4. Bad input.
"$viewer" --headless --view occlusion >/dev/null 2>"$dir/view.err"
[ $? -eq 2 ] || fail "an unknown --view does not exit with status 2"
grep -q "valid: composed, ao, direct" "$dir/view.err" || fail "an unknown --view does not list the valid views"
"$viewer" --headless --scene "$dir/no-such.glb" >/dev/null 2>"$dir/scene.err"
[ $? -eq 1 ] || fail "a missing scene does not exit with status 1"
grep -q "no-such.glb" "$dir/scene.err" || fail "the error for a missing scene does not name the file"

if reports=$(grep -l -E 'ERROR: (Address|Leak)Sanitizer|runtime error:' "$dir"/*.out "$dir"/*.err 2>/dev/null); then
  fail "sanitizer reports in: $(echo $reports)"
fi
if [ "$failures" -ne 0 ]; then
  echo "test_viewer: $failures check(s) failed (outputs in $dir)" >&2
  exit 1
fi
echo "test_viewer: all checks passed"
