#!/usr/bin/env bash
# roma-bench --growth, small: generation and trace time for two scenes at two RES, a row for
# each, every time positive, the plot a PNG with curves in it.
# Usage: test_bench_growth.sh ROMA_BENCH SCRATCH_DIR
set -u
. "$(dirname "$0")/support/bench_script.sh"

"${bench_run[@]}" --growth builtin:plates,builtin:cornell --res 32,64 --size 64x48 --runs 1 --ao-radius 0.5 \
  --csv "$dir/growth.csv" --plot "$dir/growth.png" >"$dir/out.txt" 2>&1 ||
  { cat "$dir/out.txt" >&2; fail "roma-bench --growth failed"; }
cat "$dir/out.txt"
python3 - "$dir/out.txt" <<'ROWS' || fail "the growth table does not have a row per scene and RES with positive times"
import sys
rows = [[c.strip() for c in l.strip().strip("|").split("|")] for l in open(sys.argv[1])
        if l.startswith("| builtin:")]
ok = len(rows) == 4 and {(r[0], r[3]) for r in rows} == {(s, res) for s in ("builtin:plates", "builtin:cornell")
                                                             for res in ("32", "64")}
ok = ok and all(float(v) > 0 for r in rows for v in r[4:])
triangles = {r[0]: int(r[1]) for r in rows}
ok = ok and triangles["builtin:plates"] < triangles["builtin:cornell"]  # 4 against the room's 38
sys.exit(0 if ok else 1)
ROWS
[ "$(grep -c '^growth,' "$dir/growth.csv")" = "20" ] || fail "the CSV does not have 5 rows a scene and RES"
# Measured: 45,206 bytes; the accuracy plot's two panels with axes and grid but no data: 9,199.
check_png "$dir/growth.png" 30000
"${bench_run[@]}" --growth builtin:cornell --accuracy >/dev/null 2>&1
[ $? -eq 2 ] || fail "--growth with --accuracy should exit 2"

finish test_bench_growth
