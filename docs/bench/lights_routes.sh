#!/usr/bin/env bash
# Many lights' visibility (roma-render --effects lights: how many of 256 random point lights
# each pixel sees) through the public light effect counting visible lights
# (ROMA_LIGHT_OUTPUT_VISIBLE_COUNT, --route api) and through the internal renderer's many-lights
# pass (--route internal), on the built-in room at 160x120, every light tested, one frame; the
# error against Embree's count and the pass's time (stats, GPU timestamps, which on lavapipe
# cover the pass), three alternating runs.
# Usage: docs/bench/lights_routes.sh [BUILD_DIR]   (from the repository root)
set -euo pipefail
build=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--scene builtin:cornell --effects lights --lights 256 --size 160x120 --quiet)
echo "# $(git log -1 --format=%h) on $(nproc) CPU threads; roma-render ${args[*]}"
"$build/apps/roma-render" "${args[@]}" --tracer embree --out "$tmp/ref" >/dev/null
for run in 1 2 3; do
  for route in api internal; do
    "$build/apps/roma-render" "${args[@]}" --tracer roma --route $route --out "$tmp/$route" \
      --stats "$tmp/$route.json" >/dev/null
    rel=$("$build/apps/roma-compare" "$tmp/$route/lights.pfm" "$tmp/ref/lights.pfm" --mask "$tmp/ref/coverage.pfm" |
          awk '$1 == "relative" { print $2 }')
    python3 - "$route" "$run" "$rel" "$tmp/$route.json" <<'PY'
import json, sys
route, run, rel, path = sys.argv[1:]
p = {x["name"]: x["ms"] for x in json.load(open(path))["passes"]}
print("%-8s %s  relative error %s  pass %.1f ms  whole render %.1f ms" % (
    route, run, rel, p.get("lights", p.get("many_lights", 0.0)), p["roma_total"]))
PY
  done
done
