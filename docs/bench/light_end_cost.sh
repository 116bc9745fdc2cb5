#!/usr/bin/env bash
# What the checks of a shadow segment's end at its light cost (roma_light_end_blocked,
# roma_emitter_end_blocked: the BOM's walks, and the surface grid's where the light shares a
# wall's cells): roma-render's public direct-light and GI passes on the default room (its lamp,
# 2 cm under the ceiling, and its spot) at 640x360, 16 samples, 4 frames, with this build and
# with a build of the commit before a change (BASE_BUILD), three alternating runs; per run the
# pass's time summed over the frames, in ms, from the stats file.
# Usage: docs/bench/light_end_cost.sh BASE_BUILD [BUILD_DIR [ROMA_RENDER_ARGS...]]   (from the
# repository root; e.g. `--res 256` for the walk back's reach at RES 256)
set -euo pipefail
base=$1
build=${2:-build}
shift $(( $# < 2 ? $# : 2 ))
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--tracer roma --effects direct,gi --size 640x360 --spp 16 --frames 4 --quiet "$@")
echo "# $(git log -1 --format=%h) against $(git -C "$base/.." log -1 --format=%h 2>/dev/null || echo base) on $(nproc) CPU threads; roma-render ${args[*]}"
for run in 1 2 3; do
  for which in base new; do
    dir=$build
    [ "$which" = base ] && dir=$base
    "$dir/apps/roma-render" "${args[@]}" --out "$tmp/out_$which" --stats "$tmp/s.json" >/dev/null
    python3 - "$which" "$run" "$tmp/s.json" <<'PY'
import json, sys
which, run, path = sys.argv[1:]
s = json.load(open(path))
p = {x["name"]: x["ms"] for x in s["passes"]}
print("%-4s %s  total %7.1f  direct %7.1f  gi %7.1f" % (which, run, p.get("roma_total", 0), p.get("direct", 0), p.get("gi", 0)))
PY
  done
done
