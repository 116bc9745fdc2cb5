#!/usr/bin/env bash
# What declaring RoundingModeRTE in libroma's pipelines costs (src/vulkan/spirv_rounding.c):
# roma-bench's trace table (2,000,000 AO rays on the built-in room: snapped any-hit and
# closest-hit at RES 128 A 4, un-snapped 8 steps at A 8; GPU timestamps where the device has
# them, else host-observed) and its dynamic AO frame at 640x360, 4 samples (the public AO pass),
# with the declaration (the default where the device supports it) and without it
# (ROMA_NO_ROUNDING_MODE=1), RUNS (default 5) alternating runs of 5 each; medians printed last.
# Usage: docs/bench/rounding_mode_cost.sh BUILD_DIR   (from the repository root)
set -euo pipefail
build=${1:?build dir}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--scene builtin:cornell --res 128 --angular 4 --runs 5 --size 640x360)
echo "# $(git log -1 --format=%h) on $(nproc) CPU threads; roma-bench ${args[*]}"
for run in $(seq 1 "${RUNS:-5}"); do
  for mode in rte default; do
    if [ "$mode" = rte ]; then
      "$build/apps/roma-bench" "${args[@]}" > "$tmp/out.txt" 2>/dev/null
    else
      ROMA_NO_ROUNDING_MODE=1 "$build/apps/roma-bench" "${args[@]}" > "$tmp/out.txt" 2>/dev/null
    fi
    python3 - "$mode" "$tmp/out.txt" >> "$tmp/rows.txt" <<'PY'
import sys
mode, path = sys.argv[1:]
rows = [l.split("|") for l in open(path) if l.startswith("| roma ") or l.startswith("| 4 |")]
vals = {}
for r in rows:
    cells = [c.strip() for c in r[1:-1]]
    if cells[0].startswith("roma"):
        vals[cells[0]] = float(cells[2])  # host-observed, bound
    else:
        vals["AO frame 4 spp (AO pass)"] = float(cells[2])
print(mode + "\t" + "\t".join("%s=%.2f" % kv for kv in vals.items()))
PY
    tail -1 "$tmp/rows.txt"
  done
done
python3 - "$tmp/rows.txt" <<'PY'
import sys, statistics
rows = {}
for line in open(sys.argv[1]):
    mode, *kv = line.rstrip("\n").split("\t")
    for item in kv:
        k, v = item.rsplit("=", 1)
        rows.setdefault(k, {}).setdefault(mode, []).append(float(v))
print("\nmedians, ms                                  RoundingModeRTE   none   ratio")
for k, m in rows.items():
    a, b = statistics.median(m["rte"]), statistics.median(m["default"])
    print("%-44s %8.2f %8.2f   %.3f" % (k, a, b, a / b))
PY
