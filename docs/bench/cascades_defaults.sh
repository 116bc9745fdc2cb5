#!/usr/bin/env bash
# AO (radius 1.5 m) from roma-render's defaults (RES, cascade levels and finest cube picked by
# themselves) on the shared game levels at their first three cameras, against Embree at 1,024
# samples (ROMA: 32 samples x 32 frames, the same directions), 160x120: MAE and bias over the
# covered pixels and over those whose surface is within 6 m of the camera (the reference's
# distance.pfm as the mask, roma-compare --mask-max 6), with their counts.
# Usage, from the repository root after a build:
#     bash docs/bench/cascades_defaults.sh [BUILD_DIR] > docs/bench/cascades_defaults.txt
. "$(dirname "$0")/level_cameras.sh"
figures() { # MAE, bias and pixels of roma-compare's output
  awk '$1 == "mean_abs" { m = $2 } $1 == "bias" { b = $2 } $1 == "pixels" { n = $2 }
       END { printf "%.4f %+.4f %s", m, b, n }' "$1"
}
echo "level camera | picked | whole picture: MAE bias pixels | within 6 m: MAE bias pixels"
for level in "${level_names[@]}"; do
  for c in 1 2 3; do
    ao_args "$level" "$c"
    "$render" "${common[@]}" --tracer embree --spp 1024 --out "$tmp/ref" >/dev/null
    "$render" "${common[@]}" --tracer roma --spp 32 --frames 32 --out "$tmp/roma" --stats "$tmp/roma.json" >/dev/null
    picked=$(python3 -c "import json,sys; a=json.load(open(sys.argv[1]))['roma_arrays'][0]; \
print('RES %d, %d levels' % (a['resolution'], a['levels']))" "$tmp/roma.json")
    "$compare" "$tmp/roma/ao.pfm" "$tmp/ref/ao.pfm" --mask "$tmp/ref/coverage.pfm" >"$tmp/all.txt"
    "$compare" "$tmp/roma/ao.pfm" "$tmp/ref/ao.pfm" --mask "$tmp/ref/distance.pfm" --mask-max 6 >"$tmp/near.txt"
    echo "$level $c | $picked | $(figures "$tmp/all.txt") | $(figures "$tmp/near.txt")"
  done
done
