#!/usr/bin/env bash
# The finest cascade level's edge, in cells of RES 128 to the AO radius (1.5 m): AO on the
# shared game levels at their first three cameras against Embree at 256 samples (ROMA: 16
# samples x 16 frames), MAE and bias over the covered pixels, 160x120; the levels as
# roma-render picks them for that edge (enough to cover the level).
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_finest.sh [BUILD_DIR] > docs/bench/cascades_finest.txt
. "$(dirname "$0")/level_cameras.sh"
cells=(25 30 32 35 40)
echo "level camera | $(printf '%s cells | ' "${cells[@]}")  (MAE bias, RES 128, finest edge = 128 x 1.5 / cells)"
for level in "${level_names[@]}"; do
  for c in 1 2 3; do
    ao_args "$level" "$c"
    "$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
    line="$level $c"
    for n in "${cells[@]}"; do
      edge=$(python3 -c "print(128 * 1.5 / $n)")
      "$render" "${common[@]}" --tracer roma --res 128 --spp 16 --frames 16 --finest-extent "$edge" \
        --out "$tmp/roma" >/dev/null
      line="$line | $(ao_error "$tmp/roma" "$tmp/ref")"
    done
    echo "$line"
  done
done
