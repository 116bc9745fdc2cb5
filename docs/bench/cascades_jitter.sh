#!/usr/bin/env bash
# What keeping the grid costs in accumulated AO: roma-render's defaults on the shared game
# levels at their first three cameras (RES 128, the cascade levels it picks), AO of radius
# 1.5 m accumulated over 16 frames of 16 samples with a new grid placement and new candidate
# directions each frame (--jitter on, the default) and with the first frame's in every frame
# (--jitter off: what lets a still camera keep its maps), against Embree at 256 samples (the
# same directions), MAE and bias over the covered pixels, 160x120.
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_jitter.sh [BUILD_DIR] > docs/bench/cascades_jitter.txt
set -euo pipefail
build=${1:-build}
render=$build/apps/roma-render
compare=$build/apps/roma-compare
levels=${ROMA_LEVELS_DIR:-../shared/scenes/levels}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "level camera | --jitter on: MAE bias | --jitter off: MAE bias"
for level in oa_dm4 aggressor ctf_compromise; do
  for c in 1 2 3; do
    camera=$(sed -n "${c}p" "$levels/$level.cameras")
    common=(--scene "$levels/$level.glb" --camera "$camera" --effects ao --ao-radius 1.5 --size 160x120 --quiet)
    "$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
    line="$level $c"
    for jitter in on off; do
      "$render" "${common[@]}" --tracer roma --spp 16 --frames 16 --jitter "$jitter" --out "$tmp/roma" >/dev/null
      line="$line | $("$compare" "$tmp/roma/ao.pfm" "$tmp/ref/ao.pfm" --mask "$tmp/ref/coverage.pfm" |
        awk '$1 == "mean_abs" { m = $2 } $1 == "bias" { b = $2 } END { printf "%.4f %+.4f", m, b }')"
    done
    echo "$line"
  done
done
