#!/usr/bin/env bash
# AO (radius 1.5 m) on the shared game levels at their first three cameras: one grid over the
# level against cascade levels around the camera (roma-render --cascades), against Embree at
# 256 samples (ROMA: 16 samples x 16 frames, the same directions), MAE and bias over the
# covered pixels, 160x120, and roma-render's wall time (start-up included).
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_levels.sh [BUILD_DIR] > docs/bench/cascades_levels.txt
. "$(dirname "$0")/level_cameras.sh"
configs=("--res 128 --cascades 1" "--res 256 --cascades 1" "--res 128 --cascades 4" "--res 256 --cascades 3")
echo "level camera | one grid RES 128 | one grid RES 256 | RES 128, 4 levels | RES 256, 3 levels   (MAE bias seconds)"
for level in "${level_names[@]}"; do
  for c in 1 2 3; do
    ao_args "$level" "$c"
    "$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
    line="$level $c"
    for cfg in "${configs[@]}"; do
      start=$(date +%s.%N)
      # shellcheck disable=SC2086
      "$render" "${common[@]}" --tracer roma --spp 16 --frames 16 $cfg --out "$tmp/roma" >/dev/null
      end=$(date +%s.%N)
      line="$line | $(ao_error "$tmp/roma" "$tmp/ref") $(python3 -c "print('%.1f' % ($end - $start))")"
    done
    echo "$line"
  done
done
