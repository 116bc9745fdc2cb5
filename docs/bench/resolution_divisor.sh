#!/usr/bin/env bash
# What tracing at a resolution divisor costs in accuracy and saves in time (roma_*_settings.
# resolution_divisor, roma-render --resolution-divisor): the built-in room from its camera at
# 320x240, AO (radius 0.5), direct light and GI through the public passes, 8 samples a frame
# over 16 frames (every block place visited 4 times at 2, once at 4), against Embree at 1,024
# samples; then the passes' time at 1280x720, 4 samples, 8 frames, medians of 3 runs (the stats'
# GPU timestamps, which on lavapipe cover the passes, summed over the frames).
# Usage: docs/bench/resolution_divisor.sh [BUILD_DIR]   (from the repository root)
set -euo pipefail
build=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
render=$build/apps/roma-render
scene=(--scene builtin:cornell --effects ao,direct,gi --ao-radius 0.5 --quiet)
echo "# $(git log -1 --format=%h) on $(nproc) CPU threads"
"$render" "${scene[@]}" --tracer embree --size 320x240 --spp 1024 --out "$tmp/ref" >/dev/null
echo "| divisor | AO MAE | direct relative | GI relative |"
echo "|---|---|---|---|"
for d in 1 2 4; do
  "$render" "${scene[@]}" --tracer roma --size 320x240 --spp 8 --frames 16 --resolution-divisor $d \
    --out "$tmp/d$d" >/dev/null
  row="| $d"
  for e in ao direct gi; do
    key=mean_abs
    [ "$e" = ao ] || key=relative
    v=$("$build/apps/roma-compare" "$tmp/d$d/$e.pfm" "$tmp/ref/$e.pfm" --mask "$tmp/ref/coverage.pfm" |
        awk -v k=$key '$1 == k { print $2 }')
    row="$row | $v"
  done
  echo "$row |"
done
echo
echo "| divisor | AO ms | direct ms | GI ms | whole render ms (host) |"
echo "|---|---|---|---|---|"
for d in 1 2 4; do
  for run in 1 2 3; do
    "$render" "${scene[@]}" --tracer roma --size 1280x720 --spp 4 --frames 8 --resolution-divisor $d \
      --out "$tmp/t" --stats "$tmp/t$run.json" >/dev/null
  done
  python3 - "$d" "$tmp"/t1.json "$tmp"/t2.json "$tmp"/t3.json <<'PY'
import json, statistics, sys
runs = [{p["name"]: p["ms"] for p in json.load(open(f))["passes"]} for f in sys.argv[2:]]
med = lambda k: statistics.median(r.get(k, 0.0) for r in runs)
print("| %s | %.1f | %.1f | %.1f | %.1f |" % (sys.argv[1], med("ao"), med("direct"), med("gi"), med("roma_total")))
PY
done
