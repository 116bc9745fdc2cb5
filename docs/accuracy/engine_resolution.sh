#!/usr/bin/env bash
# 2CylinderEngine's unbounded AO (issue: MAE <= 0.05) against the voxels' own limit: ROMA (its
# start walked through the BOM, and through the surface grid too: --ray-start surfaces) and
# the exact traversal of the same voxels (--ao-method voxel-dda) at RES 128 and 256, the blind
# start at both, and cascade levels around the camera, each against Embree at 1024 samples
# (160 x 120; ROMA 32 samples x 32 frames), as in docs/accuracy.md. Usage, from the repository
# root after a build: bash docs/accuracy/engine_resolution.sh [BUILD_DIR] [OUT_DIR]. About a
# minute on 2 cores with lavapipe.
set -euo pipefail
build=${1:-build}
out=${2:-out/engine_resolution}
scene=${ROMA_SCENES_DIR:-scenes}/2CylinderEngine.glb
mkdir -p "$out"
"$build/apps/roma-render" --scene "$scene" --tracer embree --effects ao --ao-radius inf --size 160x120 --spp 1024 \
  --quiet --out "$out/ref" >/dev/null
echo "| setting | MAE | mean ROMA | mean Embree | relative bias |"
echo "|---|---|---|---|---|"
for spec in "RES 128|--res 128" "RES 128, start through the surface grid|--res 128 --ray-start surfaces" \
            "RES 256, start through the surface grid|--res 256 --ray-start surfaces" \
            "RES 128, exact voxel traversal|--res 128 --ao-method voxel-dda" \
            "RES 128, blind start|--res 128 --ray-start blind" "RES 256|--res 256" \
            "RES 256, exact voxel traversal|--res 256 --ao-method voxel-dda" \
            "RES 256, blind start|--res 256 --ray-start blind" "RES 128, 3 cascade levels|--res 128 --cascades 3"; do
  IFS='|' read -r name args <<<"$spec"
  dir=$out/$(echo "$name" | tr -c 'a-zA-Z0-9\n' '_')
  # shellcheck disable=SC2086
  "$build/apps/roma-render" --scene "$scene" --tracer roma --effects ao --ao-radius inf --size 160x120 --spp 32 \
    --frames 32 --quiet --out "$dir" $args >/dev/null
  "$build/apps/roma-compare" "$dir/ao.pfm" "$out/ref/ao.pfm" --mask "$out/ref/coverage.pfm" >"$out/cmp.txt"
  awk -v name="$name" '$1 == "mean_abs" { m = $2 } $1 == "mean_a" { a = $2 } $1 == "mean_b" { b = $2 }
    END { printf "| %s | %.4f | %.4f | %.4f | %+.1f%% |\n", name, m, a, b, 100 * (a - b) / b }' "$out/cmp.txt"
done
