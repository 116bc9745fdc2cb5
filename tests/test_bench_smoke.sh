#!/usr/bin/env bash
# roma-bench --small, end to end on the CI device, checked for what it prints: the generation
# table (a row for RES 64 with A 2 and A 4, every time positive; roma-bench itself fails when a
# timed build kept its grid), the record-cost table, the rays table (Embree's two rows and
# ROMA's three, rays a second positive; the hardware ray-tracing rows or the reason they were
# skipped; the trace ladder's five rungs) and the dynamic AO frame (1 and 4 samples; the closed
# room's unbounded AO is 0 on both sides).
# Usage: test_bench_smoke.sh ROMA_BENCH SCRATCH_DIR
set -u
. "$(dirname "$0")/support/bench_script.sh"

"${bench_run[@]}" --small --rays 20000 >"$dir/out.txt" 2>&1 || { cat "$dir/out.txt" >&2; fail "roma-bench --small failed"; }
cat "$dir/out.txt"
tables() { # FILE: the tables as expected
python3 - "$1" <<'CHECK'

import sys
lines = open(sys.argv[1]).read().splitlines()
def rows(first):
    return [[c.strip() for c in l.strip().strip("|").split("|")] for l in lines if l.startswith(first)]
def positive(cells):
    return all(float(c) > 0 for c in cells)
gen = rows("| 64 |")
ok = [r[1] for r in gen] == ["2", "4"] and all(positive(r[3:7]) for r in gen)
cost = rows("| static geometry |") + rows("| host positions |") + rows("| GPU positions |")
ok = ok and len(cost) == 3 and all(positive(r[1:2]) for r in cost)
embree = rows("| Embree rtc")
roma = rows("| roma ")
ok = ok and len(embree) == 2 and len(roma) == 3 and all(float(r[4]) > 0 for r in embree + roma)
# The hardware ray-tracing rows: skipped with the reason where the device lacks the extensions
# (lavapipe), else any hit and closest hit, agreeing with Embree on the same rays.
hw = rows("| hardware ray tracing")
if len(hw) == 1:
    ok = ok and hw[0][1].startswith("skipped: ") and ("offers no VK_KHR_" in hw[0][1] or "lacks" in hw[0][1])
else:
    agree = [l for l in lines if l.startswith("hardware ray tracing: both acceleration structures")]
    pct = [float(w.rstrip("%")) for l in agree for w in l.split() if w.endswith("%")]
    ok = ok and len(hw) == 2 and all(float(r[4]) > 0 for r in hw) and len(pct) == 2 and min(pct) >= 99.9
# The same AO frame through the hardware: skipped with its reason, or 1 and 4 samples with
# times positive and the mean AO within 0.01 of Embree's (the same rays).
hw_frame = rows("| 1 (hardware) |") + rows("| 4 (hardware) |")
if len(hw) == 1:
    ok = ok and any(l.startswith("hardware ray tracing frame: skipped: ") for l in lines) and not hw_frame
else:
    embree_means = [float(r[8].split("/")[1]) for r in rows("| 1 |") + rows("| 4 |")]
    ok = ok and len(hw_frame) == 2 and all(positive(r[2:5]) for r in hw_frame) and \
        all(abs(float(r[5]) - m) <= 0.01 for r, m in zip(hw_frame, embree_means))
# The trace ladder: five rungs, host-observed times positive (lavapipe's timestamps may not cover a dispatch).
ladder = [r for r in rows("| ") if len(r) == 5 and (r[0].startswith("+ ") or r[0] in
          ("empty dispatch (launch only)", "whole snapped any-hit trace"))]
ok = ok and len(ladder) == 5 and all(positive(r[2:4]) for r in ladder)
frame = rows("| 1 |") + rows("| 4 |")
ok = ok and len(frame) == 2 and all(positive(r[1:7]) for r in frame)
ok = ok and all(r[8].replace(" ", "") == "0.000/0.000" for r in frame)
sys.exit(0 if ok else 1)
CHECK
}
tables "$dir/out.txt" || fail "roma-bench --small did not print its tables as expected"
# The check itself fails on an output without its last table, or with an empty cell.
grep -v '^| [14] |' "$dir/out.txt" >"$dir/no_frame.txt"
tables "$dir/no_frame.txt" && fail "the check passes an output without the frame table"
sed 's/^| 64 | 2 | 4 | [0-9.]* |/| 64 | 2 | 4 |  |/' "$dir/out.txt" >"$dir/empty_cell.txt"
tables "$dir/empty_cell.txt" 2>/dev/null && fail "the check passes an empty cell"
grep -v '^| hardware ray tracing' "$dir/out.txt" >"$dir/no_hardware.txt"
tables "$dir/no_hardware.txt" && fail "the check passes an output without the hardware ray-tracing rows"
grep -v '^| + map the origin' "$dir/out.txt" >"$dir/no_rung.txt"
tables "$dir/no_rung.txt" && fail "the check passes an output without a rung of the ladder"
finish test_bench_smoke
