#!/usr/bin/env bash
# Geometry beyond the coarsest cascade level (docs/accuracy.md, "Geometry beyond the coarsest
# level"): AO with the levels roma-render picks against one more level (which reaches farther,
# with coarser cells) and one grid, against Embree at 256 samples (ROMA: 32 samples x 8 frames),
# MAE and bias over the covered pixels, 160x120: the built-in room at radius 0.05 (5 levels
# picked), then the shared levels' first three cameras at radius 1.5 m (4 picked on oa_dm4 and
# aggressor, 6 on ctf_compromise) against 6 and 7 levels.
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_beyond.sh [BUILD_DIR] > docs/bench/cascades_beyond.txt
. "$(dirname "$0")/level_cameras.sh"
run() { # run LABEL ROMA-ARGS...: one ROMA row against $tmp/ref
  local label=$1
  shift
  "$render" "${common[@]}" --tracer roma --spp 32 --frames 8 "$@" --out "$tmp/roma" >/dev/null
  echo "$label $(ao_error "$tmp/roma" "$tmp/ref")"
}
echo "(MAE bias)"
common=(--scene builtin:cornell --effects ao --ao-radius 0.05 --size 160x120 --quiet)
"$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
run "cornell, the 5 levels picked:" 
run "cornell, 6 levels:" --cascades 6
run "cornell, one grid:" --cascades 1
for level in "${level_names[@]}"; do
  for c in 1 2 3; do
    ao_args "$level" "$c"
    "$render" "${common[@]}" --tracer embree --spp 256 --out "$tmp/ref" >/dev/null
    run "$level $c, the levels picked:"
    run "$level $c, 6 levels:" --cascades 6
    run "$level $c, 7 levels:" --cascades 7
  done
done
