#!/usr/bin/env bash
# roma-bench --cascades, small: the build of 3 cascade levels in the built-in room against one
# grid: a row for each case, every level rebuilt each frame when jittered, some when the camera
# moves unjittered, none when it stands still over the static room; bad arguments refused.
# Usage: test_bench_cascades.sh ROMA_BENCH SCRATCH_DIR
set -u
. "$(dirname "$0")/support/bench_script.sh"

"${bench_run[@]}" --cascades 3 --res 64 --ao-radius 0.1 --camera 0,1,1.9,0,0.9,0 --runs 1 --frames 4 \
  --csv "$dir/cascades.csv" >"$dir/out.txt" 2>&1 || { cat "$dir/out.txt" >&2; fail "roma-bench --cascades failed"; }
cat "$dir/out.txt"
python3 - "$dir/out.txt" <<'ROWS' || fail "the cascades table does not have its four rows as expected"
import sys
rows = {r[0]: r for r in ([c.strip() for c in l.strip().strip("|").split("|")] for l in open(sys.argv[1])
                          if l.startswith("| one grid") or l.startswith("| levels"))}
one, jittered = rows["one grid, jittered"], rows["levels along the path, jittered"]
moving, still = rows["levels along the path, unjittered"], rows["levels, camera still, unjittered"]
ok = len(rows) == 4 and one[1] == "1" and float(one[3]) == 1.0 and float(one[2]) > 0
ok = ok and all(r[1] == "3" for r in (jittered, moving, still))
ok = ok and float(jittered[3]) == 3.0 and 0.0 < float(moving[3]) < 3.0 and float(still[3]) == 0.0
ok = ok and float(jittered[2]) > 0 and float(moving[2]) > 0
sys.exit(0 if ok else 1)
ROWS
[ "$(grep -c '^cascades,' "$dir/cascades.csv")" = "4" ] || fail "the CSV does not have a row a case"
"${bench_run[@]}" --cascades 3 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--cascades without --ao-radius should exit 2"
"${bench_run[@]}" --cascades 1 --ao-radius 0.1 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--cascades 1 should exit 2"
"${bench_run[@]}" --camera 0,1,1.9,0,0.9,0 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--camera without --cascades should exit 2"

finish test_bench_cascades
