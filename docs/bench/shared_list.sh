#!/usr/bin/env bash
# roma-render's public AO pass with one covered-pixel list for every effect and frame
# (roma_pixel_list, --pixel-dispatch shared: the default on CPU devices) against each effect's
# own list per record (list) and against the internal renderer, on dragon_res2 at 1920x1080,
# AO, 1 sample, 8 frames; three alternating runs. From each stats file, in ms: the whole render
# (roma_total, host clock), the G-buffer, the list (shared only, once per render) and the AO
# pass summed over the 8 frames.
# Usage: docs/bench/shared_list.sh [BUILD_DIR]   (from the repository root)
set -euo pipefail
build=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--scene scenes/dragon_res2.glb --tracer roma --effects ao --size 1920x1080 --spp 1 --frames 8 --quiet)
echo "# $(git log -1 --format=%h) on $(nproc) CPU threads; roma-render ${args[*]}"
for run in 1 2 3; do
  for mode in shared list internal; do
    case $mode in
      internal) extra=(--route internal) ;;
      *) extra=(--route api --pixel-dispatch "$mode") ;;
    esac
    "$build/apps/roma-render" "${args[@]}" "${extra[@]}" --out "$tmp/out" --stats "$tmp/s.json" >/dev/null
    python3 - "$mode" "$run" "$tmp/s.json" <<'PY'
import json, sys
mode, run, path = sys.argv[1:]
s = json.load(open(path))
p = {x["name"]: x["ms"] for x in s["passes"]}
print("%-8s %s  total %7.1f  gbuffer %6.1f  list %5.1f  ao %6.1f" % (
    mode, run, p.get("roma_total", 0), p.get("gbuffer", 0), p.get("pixel_list", 0), p.get("ao", 0)))
PY
  done
done
