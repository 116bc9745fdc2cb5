#!/usr/bin/env bash
# What ROMA_AO_START_SURFACES costs the public AO pass: roma-bench's dynamic AO frame of
# dragon_res2 (1920 x 1080, RES 128, A 4, the map and the surface grid rebuilt every frame),
# with the default walk of the rays' start and with the surface grid, alternating, two rounds
# (the machine's noise is about 5%). Usage, from the repository root after a build:
# bash docs/bench/ao_surface_start_cost.sh [BUILD_DIR]. About 3 minutes on 2 cores with lavapipe.
set -euo pipefail
build=${1:-build}
scene=${ROMA_SCENES_DIR:-scenes}/dragon_res2.glb
for round in 1 2; do
  for start in walk surfaces; do
    echo "round $round, --ray-start $start"
    "$build/apps/roma-bench" --scene "$scene" --rays 200000 --runs 3 --res 128 --angular 4 --ray-start "$start" |
      awk '/^Dynamic AO frame/ { on = 1 } on && /^\| (spp|1|4) / { print } /^hardware ray tracing frame/ { on = 0 }'
  done
done
