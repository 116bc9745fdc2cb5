#!/usr/bin/env bash
# Where ROMA's AO is darker than Embree's (issue: mean AO within 2% on the room and the dragon):
# the same rays with the start walked through the BOM (the default), through the surface grid
# too (--ray-start surfaces), skipped blind, and every ray walked exactly through the same voxels
# (--ao-method voxel-dda, the voxelization's own share), at RES 128 and 256, each against Embree
# at 1024 samples (160 x 120; ROMA 32 samples x 32 frames). The room with radius 0.5, the dragon
# unbounded. Usage, from the repository root after a build:
# bash docs/accuracy/ao_darkening.sh [BUILD_DIR] [OUT_DIR]. About 2 minutes on 2 cores with lavapipe.
set -euo pipefail
build=${1:-build}
out=${2:-out/ao_darkening}
mkdir -p "$out"
echo "| scene | setting | MAE | mean ROMA | mean Embree | relative bias |"
echo "|---|---|---|---|---|---|"
for scene_spec in "room|builtin:cornell|0.5" "dragon|${ROMA_SCENES_DIR:-scenes}/dragon_res2.glb|inf"; do
  IFS='|' read -r sname scene radius <<<"$scene_spec"
  "$build/apps/roma-render" --scene "$scene" --tracer embree --effects ao --ao-radius "$radius" --size 160x120 \
    --spp 1024 --quiet --out "$out/$sname-ref" >/dev/null
  for spec in "RES 128|--res 128" "RES 128, start through the surface grid|--res 128 --ray-start surfaces" \
              "RES 128, blind start|--res 128 --ray-start blind" \
              "RES 128, exact voxel traversal|--res 128 --ao-method voxel-dda" "RES 256|--res 256" \
              "RES 256, start through the surface grid|--res 256 --ray-start surfaces" \
              "RES 256, exact voxel traversal|--res 256 --ao-method voxel-dda"; do
    IFS='|' read -r name args <<<"$spec"
    dir=$out/$sname-$(echo "$name" | tr -c 'a-zA-Z0-9\n' '_')
    # shellcheck disable=SC2086
    "$build/apps/roma-render" --scene "$scene" --tracer roma --effects ao --ao-radius "$radius" --size 160x120 \
      --spp 32 --frames 32 --quiet --out "$dir" $args >/dev/null
    "$build/apps/roma-compare" "$dir/ao.pfm" "$out/$sname-ref/ao.pfm" --mask "$out/$sname-ref/coverage.pfm" \
      >"$out/cmp.txt"
    awk -v s="$sname" -v name="$name" '$1 == "mean_abs" { m = $2 } $1 == "mean_a" { a = $2 } $1 == "mean_b" { b = $2 }
      END { printf "| %s | %s | %.4f | %.4f | %.4f | %+.1f%% |\n", s, name, m, a, b, 100 * (a - b) / b }' "$out/cmp.txt"
  done
done
