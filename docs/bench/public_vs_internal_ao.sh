#!/usr/bin/env bash
# Issue 40's bound: the public AO pass at 1920x1080 on dragon_res2's view against the internal
# renderer's AO pass, the last commit that had it (8567a0b) built beside this one. roma-render,
# AO, 1 sample, 8 frames; the public passes with one shared list of the covered pixels (the
# default on CPU devices), the internal renderer with its own list; RUNS (default 3) alternating
# runs. From each stats file, in ms: the whole render (host clock), the G-buffer, the shared list
# (once per render) and the AO pass summed over the 8 frames.
# Usage: docs/bench/public_vs_internal_ao.sh BUILD_DIR OLD_BUILD_DIR   (from the repository root)
#   e.g. git worktree add /tmp/old 8567a0b && cmake -S /tmp/old -B /tmp/old/build \
#        -DCMAKE_BUILD_TYPE=RelWithDebInfo && cmake --build /tmp/old/build --target roma-render
set -euo pipefail
build=${1:?build dir}
old=${2:?build dir of 8567a0b}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--scene scenes/dragon_res2.glb --tracer roma --effects ao --size 1920x1080 --spp 1 --frames 8 --quiet)
echo "# $(git log -1 --format=%h) against 8567a0b on $(nproc) CPU threads; roma-render ${args[*]}"
for run in $(seq 1 "${RUNS:-3}"); do
  for mode in public internal; do
    case $mode in
      public) "$build/apps/roma-render" "${args[@]}" --out "$tmp/out" --stats "$tmp/s.json" >/dev/null ;;
      internal) "$old/apps/roma-render" "${args[@]}" --route internal --out "$tmp/out" --stats "$tmp/s.json" >/dev/null ;;
    esac
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
