#!/usr/bin/env bash
# ROMA_AO_TRACE_SURFACES (roma-render --ao-trace surfaces: each AO ray walked through the
# surface grid, the rotated map over runs of cells with more triangles than the grid keeps)
# against the default snapped query and the surface grid's start alone (--ray-start surfaces):
# the room (radius 0.5), the dragon, 2CylinderEngine and the bunny (unbounded) at RES 128 and
# 256, each against Embree at 1024 samples (160 x 120; ROMA 32 samples x 32 frames); then the
# closed default room (unbounded AO, 0 everywhere in Embree) at 320 x 240, 256 samples: the
# pixels above 0.05. Usage, from the repository root after a build:
# bash docs/accuracy/ao_surface_rays.sh [BUILD_DIR] [OUT_DIR]. About 15 minutes on 2 cores with lavapipe.
set -euo pipefail
build=${1:-build}
out=${2:-out/ao_surface_rays}
scenes=${ROMA_SCENES_DIR:-scenes}
mkdir -p "$out"
modes=("maps (default)|" "start through the grid|--ray-start surfaces" "rays through the grid|--ao-trace surfaces")
echo "| scene | RES | AO trace | MAE | mean ROMA | mean Embree | relative bias |"
echo "|---|---|---|---|---|---|---|"
for scene_spec in "room|builtin:cornell|0.5" "dragon|$scenes/dragon_res2.glb|inf" \
                  "2CylinderEngine|$scenes/2CylinderEngine.glb|inf" "bunny|$scenes/bunny.glb|inf"; do
  IFS='|' read -r sname scene radius <<<"$scene_spec"
  "$build/apps/roma-render" --scene "$scene" --tracer embree --effects ao --ao-radius "$radius" --size 160x120 \
    --spp 1024 --quiet --out "$out/$sname-ref" >/dev/null
  for res in 128 256; do
    for mode in "${modes[@]}"; do
      IFS='|' read -r name args <<<"$mode"
      dir=$out/$sname-$res-$(echo "$name" | tr -c 'a-zA-Z0-9\n' '_')
      # shellcheck disable=SC2086
      "$build/apps/roma-render" --scene "$scene" --tracer roma --effects ao --ao-radius "$radius" --size 160x120 \
        --spp 32 --frames 32 --res "$res" --quiet --out "$dir" $args >/dev/null
      "$build/apps/roma-compare" "$dir/ao.pfm" "$out/$sname-ref/ao.pfm" --mask "$out/$sname-ref/coverage.pfm" \
        >"$out/cmp.txt"
      awk -v s="$sname" -v r="$res" -v name="$name" '$1 == "mean_abs" { m = $2 } $1 == "mean_a" { a = $2 }
        $1 == "mean_b" { b = $2 }
        END { printf "| %s | %s | %s | %.4f | %.4f | %.4f | %+.1f%% |\n", s, r, name, m, a, b, 100 * (a - b) / b }' \
        "$out/cmp.txt"
    done
  done
done
echo
echo "Closed default room, unbounded AO, 320 x 240, 16 x 16 samples, RES 128: the share of the pixels above 0.05 and the largest value (Embree: 0)"
"$build/apps/roma-render" --scene builtin:cornell --tracer embree --effects ao --ao-radius inf --size 320x240 \
  --spp 16 --quiet --out "$out/closed-ref" >/dev/null
for mode in "${modes[@]}"; do
  IFS='|' read -r name args <<<"$mode"
  dir=$out/closed-$(echo "$name" | tr -c 'a-zA-Z0-9\n' '_')
  # shellcheck disable=SC2086
  "$build/apps/roma-render" --scene builtin:cornell --tracer roma --effects ao --ao-radius inf --size 320x240 \
    --spp 16 --frames 16 --quiet --out "$dir" $args >/dev/null
  "$build/apps/roma-compare" "$dir/ao.pfm" "$out/closed-ref/ao.pfm" --tolerance 0.05 >"$out/cmp.txt"
  echo "$name: $(grep -E '^(above_|max_abs)' "$out/cmp.txt" | tr '\n' ' ')"
done
