#!/usr/bin/env bash
# roma-bench --cascades, small: the build of 3 cascade levels in the built-in room against one
# grid: a row for each case, every level rebuilt each frame when jittered, some when the camera
# moves unjittered, none when it stands still over the static room, each from its static part
# when an object moves or is skinned through its mesh's positions, every level from every
# triangle when the skinned positions are the whole scene's; the dynamic AO frame on it against
# Embree; bad arguments refused.
# Usage: test_bench_cascades.sh ROMA_BENCH SCRATCH_DIR
set -u
. "$(dirname "$0")/support/bench_script.sh"

"${bench_run[@]}" --cascades 3 --res 128 --ao-radius 0.5 --camera 0,1,1.9,0,0.9,0 --runs 1 --frames 4 \
  --csv "$dir/cascades.csv" >"$dir/out.txt" 2>&1 || { cat "$dir/out.txt" >&2; fail "roma-bench --cascades failed"; }
cat "$dir/out.txt"
grep -q "^camera: eye 0,1,1.9, target 0,0.9,0, fovy 45 degrees" "$dir/out.txt" || fail "the camera (six values: 45 degrees) is not the one given"
python3 - "$dir/out.txt" <<'ROWS' || fail "the cascades table does not have its seven rows as expected"
import sys
rows = {r[0]: r for r in ([c.strip() for c in l.strip().strip("|").split("|")] for l in open(sys.argv[1])
                          if l.startswith("| one grid") or l.startswith("| levels"))}
one, jittered = rows["one grid, jittered"], rows["levels along the path, jittered"]
moving, still = rows["levels along the path, unjittered"], rows["levels, camera still, unjittered"]
obj = rows["levels, camera still, unjittered, an object moving"]
skin = rows["levels, camera still, unjittered, the object skinned (its mesh's positions)"]
whole = rows["levels, camera still, unjittered, the object skinned (the whole scene's positions)"]
ok = len(rows) == 7 and one[1] == "1" and float(one[3]) == 1.0 and float(one[2]) > 0
ok = ok and all(r[1] == "3" for r in (jittered, moving, still, obj, skin, whole))
ok = ok and float(jittered[3]) == 3.0 and 0.0 < float(moving[3]) < 3.0 and float(still[3]) == 0.0
ok = ok and float(jittered[2]) > 0 and float(moving[2]) > 0
# triangles voxelized a build: the room (one chunk) in each level rebuilt, none while still
ok = ok and float(one[4]) > 0 and float(jittered[4]) == 3 * float(one[4]) and float(still[4]) == 0.0
# the object is in every level's cube: each redoes it, from its static part
ok = ok and float(obj[3]) == 3.0 and float(obj[2]) > 0
# skinned through its mesh: as the moving object (the static parts saved once in the first of
# the 4 frames, then kept); through the whole scene's positions: the room and the object (the
# room again) in every level, every frame
ok = ok and float(skin[3]) == 3.0 and float(skin[2]) > 0 and float(skin[4]) == float(obj[4])
ok = ok and float(whole[3]) == 3.0 and float(whole[4]) == 3 * 2 * float(one[4])
sys.exit(0 if ok else 1)
ROWS
[ "$(grep -c '^cascades,' "$dir/cascades.csv")" = "7" ] || fail "the CSV does not have a row a case"
# The level frame: a row for 1 and 4 samples, every time positive, ROMA's AO mean near Embree's
# at the same points (measured 0.652 against 0.771 at 1 sample, 0.648 against 0.774 at 4: the
# room's far wall lies in the coarsest level, 6.7 cm cells to a radius of 0.5, and darkens).
python3 - "$dir/out.txt" <<'FRAME' || fail "the level frame's table is not as expected"
import sys
rows = [[c.strip() for c in l.strip().strip("|").split("|")] for l in open(sys.argv[1])
        if l.startswith("| 1 |") or l.startswith("| 4 |")]
ok = len(rows) == 2 and all(all(float(c) > 0 for c in r[1:7]) for r in rows)
for r in rows:
    roma, embree = (float(x) for x in r[8].split("/"))
    ok = ok and abs(roma - embree) < 0.13
sys.exit(0 if ok else 1)
FRAME
[ "$(grep -c '^level_frame,' "$dir/cascades.csv")" = "10" ] || fail "the CSV does not have the level frame's rows"
"${bench_run[@]}" --cascades 3 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--cascades without --ao-radius should exit 2"
"${bench_run[@]}" --cascades 1 --ao-radius 0.1 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--cascades 1 should exit 2"
"${bench_run[@]}" --camera 0,1,1.9,0,0.9,0 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--camera without --cascades should exit 2"

finish test_bench_cascades
