#!/usr/bin/env bash
# What keeping the grid costs in accumulated AO: roma-render's defaults on the shared game
# levels at their first three cameras (RES 128, the cascade levels it picks), AO of radius
# 1.5 m accumulated over 16 frames of 16 samples with a new grid placement and new candidate
# directions each frame (--jitter on, the default) and with the first frame's in every frame
# (--jitter off: what lets a still camera keep its maps), against Embree at 256 samples (the
# same directions), MAE and bias over the covered pixels, 160x120.
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_jitter.sh [BUILD_DIR] > docs/bench/cascades_jitter.txt
. "$(dirname "$0")/level_cameras.sh"
echo "level camera | --jitter on: MAE bias | --jitter off: MAE bias"
for level in "${level_names[@]}"; do
  for c in 1 2 3; do
    ao_args "$level" "$c"
    "$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
    line="$level $c"
    for jitter in on off; do
      "$render" "${common[@]}" --tracer roma --spp 16 --frames 16 --jitter "$jitter" --out "$tmp/roma" >/dev/null
      line="$line | $(ao_error "$tmp/roma" "$tmp/ref")"
    done
    echo "$line"
  done
done
