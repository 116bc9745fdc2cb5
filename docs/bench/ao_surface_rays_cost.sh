#!/usr/bin/env bash
# What ROMA_AO_TRACE_SURFACES costs the public AO pass: roma-bench's dynamic AO frame (1920 x
# 1080, RES 128, A 4, the map rebuilt every frame; the surface grid built once: the scenes do
# not move) of dragon_res2 (unbounded rays) and of the built-in room (radius 0.5), with the
# default snapped query after the walk of the start (maps), the surface grid's start
# (--ray-start surfaces) and the rays walked through the grid (--ao-trace surfaces),
# alternating, two rounds (the machine's noise is 5-25%). Usage, from the repository root after
# a build: bash docs/bench/ao_surface_rays_cost.sh [BUILD_DIR]. About 6 minutes on 2 cores with
# lavapipe.
set -euo pipefail
build=${1:-build}
for spec in "dragon|${ROMA_SCENES_DIR:-scenes}/dragon_res2.glb|0" "room|builtin:cornell|0.5"; do
  IFS='|' read -r name scene radius <<<"$spec"
  for round in 1 2; do
    for mode in "maps|" "start through the grid|--ray-start surfaces" "rays through the grid|--ao-trace surfaces"; do
      IFS='|' read -r label args <<<"$mode"
      echo "$name, round $round, $label"
      # shellcheck disable=SC2086
      "$build/apps/roma-bench" --scene "$scene" --rays 200000 --runs 3 --res 128 --angular 4 --ao-radius "$radius" \
        $args | awk '/^Dynamic AO frame/ { on = 1 } on && /^\| (spp|1|4) / { print } /^hardware ray tracing frame/ { on = 0 }'
    done
  done
done
