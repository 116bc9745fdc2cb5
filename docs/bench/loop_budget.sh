#!/usr/bin/env bash
# The loop budget's figures in docs/robustness.md ("The loop budget of a shader
# invocation"): results that grow with lights and samples, against Embree and against the
# same samples spread over frames, on the device the context picks (lavapipe here).
# Usage, from the repository root after a build:
#     bash docs/bench/loop_budget.sh [BUILD_DIR] > docs/bench/loop_budget.txt
# ROMA_LOOP_PLAN=N in the environment plans each dispatch for N loop iterations instead
# (4000000000: one dispatch, as before the split). About 15 minutes on 2 cores.
set -euo pipefail
build=${1:-build}
render=$build/apps/roma-render
compare=$build/apps/roma-compare
levels=${ROMA_LEVELS_DIR:-../shared/scenes/levels}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# means A B: "mean_a mean_b ratio" over the pixels B's coverage marks
means() {
  "$compare" "$1" "$2" --mask "$(dirname "$2")/coverage.pfm" |
    awk '$1 == "mean_a" { a = $2 } $1 == "mean_b" { b = $2 } END { printf "%.4f %.4f %.4f", a, b, a / b }'
}
# timed NAME ARGS...: roma-render into $tmp/NAME, its wall time in $tmp/NAME.s
timed() {
  local name=$1
  shift
  local start end
  start=$(date +%s.%N)
  "$render" --quiet --out "$tmp/$name" "$@" >/dev/null
  end=$(date +%s.%N)
  echo "$end - $start" | bc > "$tmp/$name.s"
}

"$render" --tracer roma --effects ao --size 8x8 --spp 1 --quiet --out "$tmp/probe" --stats "$tmp/probe.json" >/dev/null
echo "# device: $(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["device"]["name"])' "$tmp/probe.json"),"\
  "ROMA_LOOP_PLAN=${ROMA_LOOP_PLAN:-default}; ROMA_s: roma-render's wall time (start-up included)"
echo
echo "## Many lights: builtin:cornell, 160x120, every light tested in one frame"
echo "lights  ROMA_visible  Embree_visible  ratio  ROMA_s"
for n in 256 512 768 1024 2048 8192; do
  timed roma_$n --tracer roma --effects lights --lights $n --size 160x120
  timed ref_$n --tracer embree --effects lights --lights $n --size 160x120
  echo "$n $(means "$tmp/roma_$n/lights.pfm" "$tmp/ref_$n/lights.pfm") $(cat "$tmp/roma_$n.s")"
done
echo
echo "## GI in one record against the same samples over frames: builtin:cornell, 160x120"
echo "samples  mean_one_record  mean_64x8_frames  ratio  ROMA_s"
timed gi_64x8 --tracer roma --effects gi --size 160x120 --spp 64 --frames 8
for s in 512 1024; do
  timed gi_$s --tracer roma --effects gi --size 160x120 --spp $s
  echo "$s $(means "$tmp/gi_$s/gi.pfm" "$tmp/gi_64x8/gi.pfm") $(cat "$tmp/gi_$s.s")"
done
echo
camera=$(head -1 "$levels/aggressor.cameras")
echo "## aggressor (84 point lights), camera 1 of aggressor.cameras, 160x120, roma-render's defaults"
echo "what  ROMA_mean  other_mean  ratio  ROMA_s"
timed agg_ref --scene "$levels/aggressor.glb" --camera "$camera" --tracer embree --effects direct,gi --size 160x120
timed agg_one --scene "$levels/aggressor.glb" --camera "$camera" --tracer roma --effects direct,gi --size 160x120
timed agg_frames --scene "$levels/aggressor.glb" --camera "$camera" --tracer roma --effects gi --size 160x120 \
  --spp 4 --frames 16
echo "gi_64_samples_vs_embree $(means "$tmp/agg_one/gi.pfm" "$tmp/agg_ref/gi.pfm") $(cat "$tmp/agg_one.s")"
echo "gi_4x16_frames_vs_embree $(means "$tmp/agg_frames/gi.pfm" "$tmp/agg_ref/gi.pfm") $(cat "$tmp/agg_frames.s")"
echo "gi_64_samples_vs_4x16_frames $(means "$tmp/agg_one/gi.pfm" "$tmp/agg_frames/gi.pfm")"
echo "direct_vs_embree $(means "$tmp/agg_one/direct.pfm" "$tmp/agg_ref/direct.pfm")"
