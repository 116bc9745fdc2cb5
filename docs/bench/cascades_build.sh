#!/usr/bin/env bash
# The build of cascade levels around the camera against one grid over the level, on the shared
# game levels from their first camera (roma-bench --cascades: AO radius 1.5 m, RES 128, the
# levels roma-render picks for the level: 4, 4 and 6), 16 frames a run, medians of 5 runs.
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_build.sh [BUILD_DIR] > docs/bench/cascades_build.txt
set -euo pipefail
build=${1:-build}
levels=${ROMA_LEVELS_DIR:-../shared/scenes/levels}
for level in oa_dm4:4 aggressor:4 ctf_compromise:6; do
  name=${level%%:*}
  echo "## $name"
  "$build/apps/roma-bench" --scene "$levels/$name.glb" --camera "$(sed -n 1p "$levels/$name.cameras")" \
    --cascades "${level##*:}" --ao-radius 1.5 --runs 5 --frames 16
done
