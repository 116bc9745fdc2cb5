#!/usr/bin/env bash
# roma-bench --accuracy, small: it runs end to end on the CI device; its Pareto fronts are
# the settings no other setting beats in both time and error (recomputed here from the
# printed tables); --plot draws a PNG through gnuplot; Embree's rows carry FLIP.
# Usage: test_bench_accuracy.sh ROMA_BENCH SCRATCH_DIR
set -u
. "$(dirname "$0")/support/bench_script.sh"

"${bench_run[@]}" --small --accuracy --ao-radius 0.5 --csv "$dir/accuracy.csv" --plot "$dir/accuracy.png" \
  --cache "$dir/points.cache" >"$dir/out.txt" 2>"$dir/progress.txt" ||
  { cat "$dir/out.txt" "$dir/progress.txt" >&2; fail "roma-bench --accuracy --plot failed"; }
cat "$dir/out.txt"

# The same run again with its cache: every point but the first (whose render makes the
# G-buffer and the reference) comes from the cache, and its row is the same.
"${bench_run[@]}" --small --accuracy --ao-radius 0.5 --cache "$dir/points.cache" >"$dir/again.txt" \
  2>"$dir/again_progress.txt" || { cat "$dir/again_progress.txt" >&2; fail "roma-bench --cache (again) failed"; }
python3 - "$dir/out.txt" "$dir/again.txt" "$dir/progress.txt" "$dir/again_progress.txt" <<'CACHE' ||
import sys
def rows(path):  # the method rows of the first table
    lines = open(path).read().split("\n\n")[2].splitlines()
    return [l for l in lines if l.startswith("| ") and not l.startswith("| method") and not l.startswith("|---")]
first, again = rows(sys.argv[1]), rows(sys.argv[2])
progress = [l for l in open(sys.argv[3]) if l.startswith("roma-bench: [")]
cached = [l for l in open(sys.argv[4]) if "(from the cache)" in l]
print("points:", len(first), "measured the first time:", len(progress), "from the cache again:", len(cached))
sys.exit(0 if len(first) >= 10 and len(progress) == len(first) and len(cached) == len(first) - 1
         and first[1:] == again[1:] else 1)
CACHE
  fail "a second run with the cache did not take its points from it"

# The PNG: its signature and a size no empty plot has (measured: 49,895 bytes; the same
# two panels with axes and grid but no data: 9,199).
check_png "$dir/accuracy.png" 40000
grep -q "^accuracy,embree ao flip," "$dir/accuracy.csv" || fail "no FLIP rows for Embree in the CSV"
# Error against frames: its plot beside the first, and more frames never worse for ROMA here
# (2 frames in the small run; measured 0.1245 -> 0.1161).
[ "$(head -c 4 "$dir/accuracy_frames.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = "89504e47" ] ||
  fail "no accuracy_frames.png"
e1=$(sed -n 's/^frames,ao mae after 1 frames,[0-9]*,[0-9]*,\([0-9.]*\),$/\1/p' "$dir/accuracy.csv")
e2=$(sed -n 's/^frames,ao mae after 2 frames,[0-9]*,[0-9]*,\([0-9.]*\),$/\1/p' "$dir/accuracy.csv")
awk -v a="$e1" -v b="$e2" 'BEGIN { exit !(a > 0 && b > 0 && b < a) }' || fail "ROMA's error after 1 and 2 frames: $e1, $e2"

# The fronts, recomputed from the CSV: ROMA and the baselines cost frames x ms per frame
# (the screen-space rows: steps in the CSV's res column),
# Embree (and hardware ray tracing, where it runs) its ms for the image; Embree's row at the
# reference's own sample count has error 0.
python3 - "$dir/out.txt" "$dir/accuracy.csv" <<'EOF' || fail "the printed Pareto fronts are not the fronts of the measured points"
import csv, re, sys
text = open(sys.argv[1]).read()
frames = int(re.search(r"per frame over (\d+) frames", text).group(1))
values = {}
for row in csv.DictReader(open(sys.argv[2])):
    values[(row["name"], row["res"], row["angular"])] = float(row["value"])
points = []
for (name, res, angular), v in values.items():
    if name.endswith(" ms per frame"):
        tag = name[: -len(" ms per frame")]
        series = {"voxel-dda": "voxel traversal", "distance-field": "distance field", "naadf": "NAADF",
                  "sd-map": "stochastic depth map (layers)",
                  "sd-map-traced": "stochastic depth map, ray traced (layers)",
                  "screen-space": "screen space (steps)"}.get(tag, "ROMA A " + angular)
        points.append((series, res, v * frames, values[(tag + " mae", res, angular)], values[(tag + " flip", res, angular)]))
    elif name == "embree ao ms":
        points.append(("Embree (spp)", res, v, values[("embree ao mae", res, angular)], values[("embree ao flip", res, angular)]))
    elif name == "hardware ao ms":  # where a device has hardware ray tracing: its ms for the image
        points.append(("hardware ray tracing (spp)", res, v, values[("hardware ao mae", res, angular)],
                       values[("hardware ao flip", res, angular)]))
printed = {"MAE": [], "FLIP": [], "MAE, GPU": [], "FLIP, GPU": []}
for line in text.splitlines():
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if cells[0] == "front" and cells[1] in printed:
        printed[cells[1]].append((cells[2], cells[3]))
ok = len(points) >= 8
for k, name in ((3, "MAE"), (4, "FLIP"), (3, "MAE, GPU"), (4, "FLIP, GPU")):
    usable = [p for p in points if p[k] > 0 and not (name.endswith("GPU") and p[0].startswith("Embree"))]
    front = [p for p in usable if not any(
        (q[2] <= p[2] and q[k] < p[k]) or (q[2] < p[2] and q[k] <= p[k]) for q in usable)]
    front.sort(key=lambda p: p[2])
    want = [(p[0], p[1]) for p in front]
    print(name, "front:", want)
    # One point may be the whole front: in a run this small, timing noise can let one
    # setting be both the fastest and the most accurate.
    ok = ok and want == printed[name] and len(want) >= 1
    errors = [p[k] for p in front]
    ok = ok and all(a > b for a, b in zip(errors, errors[1:]))
# Equal time and equal error against ROMA A 4 (at RES 64 in the small run).
anchor = [p for p in points if p[0] == "ROMA A 4"][0]
rows = {}
for line in text.splitlines():
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if len(cells) == 9 and cells[0] in {p[0] for p in points}:
        rows[cells[0]] = cells
for series in {p[0] for p in points}:
    mine = [p for p in points if p[0] == series]
    want = []
    for k in (3, 4):
        fit = [p for p in mine if p[2] <= anchor[2] and p[k] > 0]
        want.append(min(fit, key=lambda p: p[k])[1] if fit else "-")
    for k in (3, 4):
        fit = [p for p in mine if p[k] <= anchor[k] and p[k] > 0]
        want.append(min(fit, key=lambda p: p[2])[1] if fit else "-")
    got = [rows.get(series, [""] * 9)[c] for c in (2, 4, 6, 8)]
    print(series, "equal time and error settings:", got)
    ok = ok and got == want
ok = ok and rows["ROMA A 4"][6] == anchor[1]  # ROMA itself reaches its own error in its own time
sys.exit(0 if ok else 1)
EOF

# Direct light (--effect direct): ROMA at every RES x A of the shadow array and with more
# steps, the exact traversal of the BOM, Embree. Embree at the reference's own sample count is
# the reference (MAE 0: the same samples); the GPU methods' error is their shadow rays'
# (measured through the public passes 0.0022-0.0071 on a mean radiance of about 0.09; RES 64
# at A 2 and 4 0.0071 and 0.0070, 0.0061 at most before the walk searched back as far as a
# wall's step is long).
"${bench_run[@]}" --small --accuracy --effect direct --csv "$dir/direct.csv" >"$dir/direct.txt" \
  2>"$dir/direct_progress.txt" ||
  { cat "$dir/direct.txt" "$dir/direct_progress.txt" >&2; fail "roma-bench --accuracy --effect direct failed"; }
cat "$dir/direct.txt"
python3 - "$dir/direct.csv" <<'DIRECT' || fail "the direct-light sweep's rows"
import csv, sys
v = {(r["name"], r["res"], r["angular"]): float(r["value"]) for r in csv.DictReader(open(sys.argv[1]))}
gpu = {t: [k for k in v if k[0] == t + " mae"] for t in ("direct", "direct-voxel-dda", "direct-steps")}
embree = sorted((int(k[1]), x) for k, x in v.items() if k[0] == "embree direct mae")
print({t: len(k) for t, k in gpu.items()}, "Embree:", embree)
ok = [len(gpu[t]) for t in gpu] == [2, 1, 2] and all(0 < v[k] < 0.0075 for t in gpu for k in gpu[t])
ok = ok and embree[-1][1] == 0.0 and all(a[1] > b[1] for a, b in zip(embree, embree[1:]))
sys.exit(0 if ok else 1)
DIRECT
# Direct light through the hardware: skipped with the device's reason, or a row a sample count
# (1 to 64), the last on the reference's own segments (not yet measured on a GPU: within 0.005,
# what rays that graze an edge may differ by).
if grep -q "^Hardware ray tracing: skipped: " "$dir/direct.txt"; then
  grep -q "^Hardware ray tracing: skipped: .*\(offers no VK_KHR_\|lacks\)" "$dir/direct.txt" ||
    fail "the direct light's hardware rows were skipped without the device's reason"
else
  rows=$(sed -n '/^| hardware spp |/,/^$/p' "$dir/direct.txt" | grep -cE '^\| (1|2|4|8|16|32|64) \| [0-9]+ \|')
  [ "$rows" -eq 7 ] || fail "expected 7 direct-light hardware rows (1 to 64 samples), found $rows"
  sed -n '/^| hardware spp |/,/^$/p' "$dir/direct.txt" | grep -qE '^\| 64 \| [0-9]+ \| [0-9.]+ \| 0\.00[0-4][0-9] \|' ||
    fail "the direct light's hardware row at the reference's samples is not within 0.005 of it"
fi

# Unbounded AO (no --ao-radius): screen space marches a bounded radius, so its rows are left
# out with a note, and the run still succeeds.
"${bench_run[@]}" --small --accuracy >"$dir/unbounded.txt" 2>"$dir/unbounded_progress.txt" ||
  { cat "$dir/unbounded.txt" "$dir/unbounded_progress.txt" >&2; fail "roma-bench --accuracy (unbounded) failed"; }
grep -q "no rows for unbounded AO" "$dir/unbounded.txt" && ! grep -q "^| screen space" "$dir/unbounded.txt" ||
  fail "unbounded AO: screen-space rows should be left out with a note"

# GI (--effect gi) and many lights (--effect lights): ROMA at every RES x A of their arrays,
# the exact traversal of the BOM, GI with shadow rays for the spot instead of its RSM, the
# lights with other step counts; Embree. Measured here: GI MAE 0.016-0.091 (32 x 24 pixels,
# 64 samples: mostly the noise of both sides), the lights' share 0.022-0.100 (A 2 at RES 64:
# 0.087 before the walk searched back as far as a wall's step is long, 0.097 before the end at
# the light was walked too (roma_light_end_blocked), each blocking more segments next to two
# surfaces); Embree's exact count of the lights is the reference (MAE 0).
for effect in gi lights; do
  "${bench_run[@]}" --small --accuracy --effect $effect --csv "$dir/$effect.csv" >"$dir/$effect.txt" \
    2>"$dir/${effect}_progress.txt" ||
    { cat "$dir/$effect.txt" "$dir/${effect}_progress.txt" >&2; fail "roma-bench --accuracy --effect $effect failed"; }
  cat "$dir/$effect.txt"
done
# Many lights through the hardware: skipped with the device's reason, or one row, the same
# segments as Embree's count (MAE below 0.01: rays that graze an edge may differ).
if grep -q "^Hardware ray tracing: skipped: " "$dir/lights.txt"; then
  grep -q "^Hardware ray tracing: skipped: .*\(offers no VK_KHR_\|lacks\)" "$dir/lights.txt" ||
    fail "the many-lights hardware row was skipped without the device's reason"
else
  awk -F'|' '$2 ~ /every segment/ && $5 + 0 < 0.01 { found = 1 } END { exit !found }' \
    <(sed -n '/^| hardware  | rays |/,/^$/p' "$dir/lights.txt") || fail "no many-lights hardware row within 0.01"
fi
python3 - "$dir/gi.csv" "$dir/lights.csv" <<'LIGHTS' || fail "the GI and many-lights sweeps' rows"
import csv, sys
def load(path):
    return {(r["name"], r["res"], r["angular"]): float(r["value"]) for r in csv.DictReader(open(path))}
ok = True
for path, tags, counts, bound in ((sys.argv[1], ("gi", "gi-voxel-dda", "gi-punctual-rays"), [2, 1, 1], 0.10),
                                  (sys.argv[2], ("lights", "lights-voxel-dda", "lights-steps"), [2, 1, 3], 0.105)):
    v = load(path)
    gpu = {t: [k for k in v if k[0] == t + " mae"] for t in tags}
    effect = tags[0]
    embree = sorted((int(k[1]), x) for k, x in v.items() if k[0] == "embree %s mae" % effect)
    print(effect, {t: len(k) for t, k in gpu.items()}, "Embree:", embree)
    ok = ok and [len(gpu[t]) for t in tags] == counts and all(0 < v[k] < bound for t in tags for k in gpu[t])
    ok = ok and embree[-1][1] == 0.0 and all(a[1] > b[1] for a, b in zip(embree, embree[1:]))
ok = ok and len(embree) == 1  # the lights: no samples, one Embree row
sys.exit(0 if ok else 1)
LIGHTS
"${bench_run[@]}" --small --effect direct >/dev/null 2>&1
[ $? -eq 2 ] || fail "--effect without --accuracy should exit 2"

# Cascade levels (--cascades auto): the built-in room with an AO radius of 5 cm, so small beside
# the room that roma-render would pick levels: beside the one grid, ROMA with its levels for
# each A (K >= 2), the equal-time and equal-error tables anchored on A 4 with its levels, and
# the levels closer to Embree than the one grid, whose cells (3 cm at RES 64) are as wide as
# the radius; --no-baselines leaves out the voxel baselines over one grid; --camera keeps its
# field of view. Refused: another effect, no radius, auto without --accuracy, --no-baselines
# without --accuracy, a camera of 180 degrees or with its eye on its target.
"${bench_run[@]}" --small --accuracy --ao-radius 0.05 --cascades auto --no-baselines --camera 0,1,1.9,0,0.8,-1,50 \
  --csv "$dir/levels.csv" \
  >"$dir/levels.txt" \
  2>"$dir/levels_progress.txt" ||
  { cat "$dir/levels.txt" "$dir/levels_progress.txt" >&2; fail "roma-bench --accuracy --cascades auto failed"; }
cat "$dir/levels.txt"
python3 - "$dir/levels.txt" "$dir/levels.csv" <<'LEVELS' || fail "the cascade levels' rows"
import csv, re, sys
text = open(sys.argv[1]).read()
v = {(r["name"], r["res"], r["angular"]): float(r["value"]) for r in csv.DictReader(open(sys.argv[2]))}
rows = re.findall(r"^\| ROMA, (\d+) levels \| 64 \| (\d) \|", text, re.M)
levels = {a: float(x) for (n, _, a), x in v.items() if re.fullmatch(r"ao-levels-\d+ mae", n)}
grid = {a: x for (n, _, a), x in v.items() if n == "ao mae"}
print("level rows:", rows, "MAE with levels:", levels, "one grid:", grid)
ok = [a for _, a in rows] == ["2", "4"] and all(int(k) >= 2 for k, _ in rows)
ok = ok and sorted(levels) == ["2", "4"] and all(0 < levels[a] < grid[a] for a in levels)
ok = ok and "Against ROMA A 4, levels at 64" in text
ok = ok and "camera: eye 0,1,1.9, target 0,0.8,-1, fovy 50 degrees" in text  # the field of view is kept
ok = ok and not re.search(r"^\| (voxel traversal|distance field|NAADF) \|", text, re.M)
sys.exit(0 if ok else 1)
LEVELS
for bad in "--accuracy --effect direct --ao-radius 0.05 --cascades auto" "--accuracy --cascades auto" \
           "--cascades auto --ao-radius 0.05" "--no-baselines --ao-radius 0.05" \
           "--accuracy --camera 0,1,1.9,0,0.8,-1,180" "--accuracy --camera 0,1,1.9,0,1,1.9" \
           "--accuracy --ao-trace surfaces" "--accuracy --ray-start surfaces" \
           "--cascades 2 --ao-radius 0.05 --ao-trace surfaces" "--growth builtin:cornell --ao-trace surfaces"; do
  # shellcheck disable=SC2086
  "${bench_run[@]}" --small $bad >/dev/null 2>&1
  [ $? -eq 2 ] || fail "$bad: should exit 2"
done

# The hardware ray-tracing rows: skipped with the device's reason (lavapipe), or a row a
# sample count, doubling to the run's 64, each with its rays, time and error.
if grep -q "^Hardware ray tracing: skipped: " "$dir/out.txt"; then
  grep -q "^Hardware ray tracing: skipped: .*\(offers no VK_KHR_\|lacks\)" "$dir/out.txt" ||
    fail "the hardware rows were skipped without the device's reason"
else
  rows=$(grep -cE '^\| (1|2|4|8|16|32|64) \| [0-9]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \|$' \
    <(sed -n '/^| hardware spp |/,/^$/p' "$dir/out.txt"))
  [ "$rows" -eq 7 ] || fail "expected 7 hardware rows (1 to 64 samples), found $rows"
fi
# The stochastic depth map ray traced (the seed paper's acquisition): skipped with the same
# reason, or a row for each of its layer counts.
if grep -q "^paper's ray-traced acquisition: skipped: " "$dir/out.txt"; then
  grep -q "^paper's ray-traced acquisition: skipped: .*\(offers no VK_KHR_\|lacks\)" "$dir/out.txt" ||
    fail "the ray-traced depth map was skipped without the device's reason"
else
  rows=$(grep -c '^| stochastic depth map ray traced, [24] layers |' "$dir/out.txt")
  [ "$rows" -eq 2 ] || fail "expected 2 ray-traced depth map rows, found $rows"
fi

# Bad use: --plot without --accuracy; a PNG or CSV that cannot be written (refused before
# anything is measured, with a message, and no crash).
"${bench_run[@]}" --small --plot "$dir/x.png" >/dev/null 2>&1
[ $? -eq 2 ] || fail "--plot without --accuracy should exit 2"
"${bench_run[@]}" --small --cache "$dir/x.cache" >/dev/null 2>&1
[ $? -eq 2 ] || fail "--cache without --accuracy should exit 2"
for bad in "--plot $dir/missing/x.png" "--csv $dir/missing/x.csv"; do
  # shellcheck disable=SC2086
  "${bench_run[@]}" --small --accuracy $bad >"$dir/bad.txt" 2>&1
  rc=$?
  [ $rc -eq 1 ] && grep -q "cannot write there" "$dir/bad.txt" ||
    { cat "$dir/bad.txt" >&2; fail "$bad: expected exit 1 and a message, got $rc"; }
done

finish test_bench_accuracy
