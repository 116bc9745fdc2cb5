#!/usr/bin/env bash
# The finest cascade level's edge, in cells of RES 128 to the AO radius (1.5 m): AO on the
# shared game levels at their first three cameras against Embree at 256 samples (ROMA: 16
# samples x 16 frames), MAE and bias over the covered pixels, 160x120; the levels as
# roma-render picks them for that edge (enough to cover the level).
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_finest.sh [BUILD_DIR] > docs/bench/cascades_finest.txt
set -euo pipefail
build=${1:-build}
render=$build/apps/roma-render
compare=$build/apps/roma-compare
levels=${ROMA_LEVELS_DIR:-../shared/scenes/levels}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cells=(25 30 32 35 40)
echo "level camera | $(printf '%s cells | ' "${cells[@]}")  (MAE bias, RES 128, finest edge = 128 x 1.5 / cells)"
for level in oa_dm4 aggressor ctf_compromise; do
  for c in 1 2 3; do
    camera=$(sed -n "${c}p" "$levels/$level.cameras")
    common=(--scene "$levels/$level.glb" --camera "$camera" --effects ao --ao-radius 1.5 --size 160x120 --quiet)
    "$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
    line="$level $c"
    for n in "${cells[@]}"; do
      edge=$(python3 -c "print(128 * 1.5 / $n)")
      "$render" "${common[@]}" --tracer roma --res 128 --spp 16 --frames 16 --finest-extent "$edge" \
        --out "$tmp/roma" >/dev/null
      line="$line | $("$compare" "$tmp/roma/ao.pfm" "$tmp/ref/ao.pfm" --mask "$tmp/ref/coverage.pfm" |
        awk '$1 == "mean_abs" { m = $2 } $1 == "bias" { b = $2 } END { printf "%.4f %+.4f", m, b }')"
    done
    echo "$line"
  done
done
