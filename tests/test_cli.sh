#!/usr/bin/env bash
# End-to-end test of the command-line tools: roma-render on builtin:cornell
# (outputs, "wrote" lines, stats JSON, AO with and without a radius), roma-compare
# (identical images, mismatched channels) and the exit codes of bad input.
# Usage: test_cli.sh ROMA_RENDER ROMA_COMPARE SCRATCH_DIR
set -u

if [ $# -ne 3 ]; then
  echo "usage: $0 ROMA_RENDER ROMA_COMPARE SCRATCH_DIR" >&2
  exit 2
fi
render=$1
compare=$2
dir=$3
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# expect_status WANT GOT WHAT
expect_status() {
  if [ "$2" -ne "$1" ]; then
    fail "$3: exit status $2, expected $1"
    return 1
  fi
  return 0
}

# metric FILE NAME: value of a "name value" line printed by roma-compare.
metric() {
  awk -v k="$2" '$1 == k { print $2; found = 1 } END { exit !found }' "$1"
}

# has_stat FILE KEY [VALUE]: some object of the JSON file has KEY (with VALUE, compared as
# text, a string's start matching VALUE...).
has_stat() {
  python3 - "$@" <<'PY' 2>/dev/null
import json, sys
path, key = sys.argv[1], sys.argv[2]
want = sys.argv[3] if len(sys.argv) > 3 else None
def values(node):
    if isinstance(node, dict):
        for k, v in node.items():
            if k == key:
                yield v
            yield from values(v)
    elif isinstance(node, list):
        for v in node:
            yield from values(v)
def text(v):
    return v if isinstance(v, str) else json.dumps(v)
found = any(want is None or text(v) == want or (want.endswith("...") and text(v).startswith(want[:-3]))
            for v in values(json.load(open(path))))
sys.exit(0 if found else 1)
PY
}

for tool in "$render" "$compare"; do
  if [ ! -x "$tool" ]; then
    echo "FAIL: $tool is not an executable" >&2
    exit 1
  fi
done
if ! command -v python3 >/dev/null 2>&1; then
  echo "FAIL: python3 is needed to parse the stats JSON" >&2
  exit 1
fi

rm -rf "$dir"
mkdir -p "$dir" || exit 1
# Sanitizer builds: the Vulkan tools get the preload the test programs get
# (tests/CMakeLists.txt), through a wrapper so that bash and python3 do not.
if [ -n "${ROMA_TOOL_PRELOAD:-}" ]; then
  printf '#!/bin/sh\nLD_PRELOAD="%s" exec "%s" "$@"\n' "$ROMA_TOOL_PRELOAD" "$render" >"$dir/roma-render-preloaded"
  chmod +x "$dir/roma-render-preloaded"
  render=$dir/roma-render-preloaded
fi
out="$dir/cornell"
common=(--scene builtin:cornell --size 32x24 --spp 2 --quiet)

# --- A full render: four effects and stats ---
"$render" "${common[@]}" --effects ao,direct,gi,lights --out "$out" --stats "$out/stats.json" \
  >"$dir/render.out" 2>"$dir/render.err"
expect_status 0 $? "roma-render (all effects)" || cat "$dir/render.err" >&2

expected_files=()
for e in ao direct gi lights coverage composed distance; do
  expected_files+=("$out/$e.pfm" "$out/$e.png")
done
for f in "${expected_files[@]}" "$out/stats.json"; do
  [ -s "$f" ] || fail "missing or empty output $f"
  grep -qxF "wrote $f" "$dir/render.out" || fail "no 'wrote $f' line in the output"
done
wrote_count=$(grep -c '^wrote ' "$dir/render.out")
[ "$wrote_count" -eq 15 ] || fail "expected 15 'wrote' lines, got $wrote_count"

if [ -f "$out/stats.json" ]; then
  python3 - "$out/stats.json" <<'EOF' || fail "stats JSON does not parse or lacks the expected keys"
import json, sys
def strict(name):  # Infinity/NaN are not JSON
    raise ValueError("non-JSON constant " + name)
s = json.load(open(sys.argv[1]), parse_constant=strict)
assert s["tool"] == "roma-render", s.get("tool")
assert s["scene"]["triangles"] > 0, s["scene"]
assert s["settings"]["width"] == 32 and s["settings"]["height"] == 24, s["settings"]
assert s["settings"]["spp"] == 2, s["settings"]
assert len(s["passes"]) > 0, s["passes"]
for p in s["passes"]:
    assert p["name"] and p["ms"] >= 0, p
EOF
else
  fail "roma-render wrote no stats file ($out/stats.json)"
fi

# --- roma-compare ---
"$compare" "$out/ao.pfm" "$out/ao.pfm" >"$dir/same.out" 2>"$dir/same.err"
if expect_status 0 $? "roma-compare ao.pfm ao.pfm"; then
  v=$(metric "$dir/same.out" mean_abs) || fail "roma-compare printed no mean_abs"
  [ "${v:-x}" = "0" ] || fail "mean_abs of an image with itself is '${v:-}', expected 0"
  v=$(metric "$dir/same.out" flip) || fail "roma-compare printed no flip"
  [ "${v:-x}" = "0" ] || fail "FLIP of an image with itself is '${v:-}', expected 0"
fi

"$compare" "$out/ao.pfm" "$out/direct.pfm" >"$dir/mismatch.out" 2>"$dir/mismatch.err"
expect_status 1 $? "roma-compare ao.pfm direct.pfm (channel mismatch)"
[ -s "$dir/mismatch.err" ] || fail "roma-compare channel mismatch: no message on stderr"

"$compare" "$out/ao.pfm" >/dev/null 2>"$dir/compare_usage.err"
expect_status 2 $? "roma-compare with one image"

# distance.pfm: the distance from the eye where a surface is seen; as a mask with --mask-max,
# the pixels within that distance (the room's walls are 1 to 5 m from its camera).
count_pixels() { awk '$1 == "pixels" { print $2 }' "$1"; }
"$compare" "$out/ao.pfm" "$out/ao.pfm" --mask "$out/coverage.pfm" >"$dir/covered.cmp"
"$compare" "$out/ao.pfm" "$out/ao.pfm" --mask "$out/distance.pfm" >"$dir/distance_all.cmp"
"$compare" "$out/ao.pfm" "$out/ao.pfm" --mask "$out/distance.pfm" --mask-max 3 >"$dir/distance_near.cmp"
"$compare" "$out/ao.pfm" "$out/ao.pfm" --mask "$out/distance.pfm" --mask-max 0.5 >"$dir/distance_none.cmp"
covered=$(count_pixels "$dir/covered.cmp") all=$(count_pixels "$dir/distance_all.cmp")
near=$(count_pixels "$dir/distance_near.cmp") none=$(count_pixels "$dir/distance_none.cmp")
[ -n "$covered" ] && [ "$covered" = "$all" ] ||
  fail "distance.pfm is not > 0 exactly where coverage.pfm is ($all against $covered pixels)"
[ -n "$near" ] && [ "$near" -gt 0 ] && [ "$near" -lt "$covered" ] && [ "$none" = 0 ] ||
  fail "--mask-max on distance.pfm: within 3 m $near, within 0.5 m $none of $covered pixels"
grep -q "where the mask is > 0 and <= 3)" "$dir/distance_near.cmp" || fail "roma-compare does not say --mask-max's bound"
"$compare" "$out/ao.pfm" "$out/ao.pfm" --mask-max 3 >/dev/null 2>"$dir/mask_max.err"
expect_status 2 $? "roma-compare --mask-max without --mask"

# roma-compare for people: labelled figures, relative error and bias, the heat map's
# scale and legend, a pass/fail threshold, JSON, and the mask's own errors.
"$compare" "$out/direct.pfm" "$out/composed.pfm" --mask "$out/coverage.pfm" --heatmap "$dir/heat.png" \
  --json "$dir/compare.json" --threshold 1000 >"$dir/people.cmp" 2>&1
expect_status 0 $? "roma-compare with --threshold 1000" || cat "$dir/people.cmp" >&2
for key in "^A  " "^B  " "^relative .*mean_abs / mean_b" "^bias .*mean_a - mean_b" "^flip .*LDR-FLIP" "^heat_scale " \
  "^pass: "; do
  grep -q "$key" "$dir/people.cmp" || fail "roma-compare does not print '$key'"
done
python3 - "$dir/compare.json" <<'PY' || fail "roma-compare --json is not the figures as JSON"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["result"] == "pass" and j["pixels"] > 0 and abs(j["bias"] - (j["mean_a"] - j["mean_b"])) < 1e-6, j
assert 0.0 < j["flip"] < 1.0, j
PY
"$compare" "$out/direct.pfm" "$out/composed.pfm" --threshold 0 >"$dir/threshold.cmp" 2>&1
expect_status 3 $? "roma-compare --threshold 0 on images that differ"
grep -q "^FAIL: mean_abs .* is above the threshold 0" "$dir/threshold.cmp" || fail "roma-compare --threshold: no FAIL line"
"$compare" "$out/ao.pfm" "$out/ao.pfm" --mask "$out/direct.pfm" >/dev/null 2>"$dir/mask3.err"
expect_status 1 $? "roma-compare with a 3-channel mask"
grep -q "the mask .* has 3 channels; a mask has 1" "$dir/mask3.err" || fail "a 3-channel mask is not named as the cause"

# --- AO of the closed room: unbounded is exactly 0, a short radius is not ---
# ao_mean LABEL ARGS...: renders AO into $dir/LABEL and prints its mean.
ao_mean() {
  local label=$1
  shift
  "$render" "${common[@]}" --effects ao --out "$dir/$label" "$@" >/dev/null 2>"$dir/$label.err"
  expect_status 0 $? "roma-render --effects ao $*" || return 1
  "$compare" "$dir/$label/ao.pfm" "$dir/$label/ao.pfm" >"$dir/$label.cmp" 2>&1 || return 1
  metric "$dir/$label.cmp" mean_a
}
if m=$(ao_mean ao_unbounded --ao-radius inf); then
  python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) == 0.0 else 1)' "$m" ||
    fail "unbounded AO mean of the closed cornell room is $m, expected 0"
else
  fail "unbounded AO render/compare failed"
fi
if m=$(ao_mean ao_r03 --ao-radius 0.3); then
  python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) > 0.0 else 1)' "$m" ||
    fail "AO mean with --ao-radius 0.3 is $m, expected > 0"
else
  fail "AO render/compare with --ao-radius 0.3 failed"
fi

# --- ROMA: every effect, and only the passes the scene calls for (stats "passes") ---
# roma_passes SCENE: the passes of the effect plan in the stats file, sorted, and the arrays, one line.
roma_passes() {
  local scene=$1 label=$2
  "$render" --scene "$scene" --tracer roma --effects ao,direct,gi,lights --size 16x12 --spp 1 --frames 2 \
    --lights 16 --quiet --out "$dir/$label" --stats "$dir/$label/stats.json" >/dev/null \
    2>"$dir/$label.err"
  expect_status 0 $? "roma-render --tracer roma --scene $scene (all effects)" || { cat "$dir/$label.err" >&2; return 1; }
  for e in ao direct gi lights; do
    [ -s "$dir/$label/$e.pfm" ] || fail "roma-render --tracer roma --scene $scene: no $e.pfm"
  done
  python3 - "$dir/$label/stats.json" <<'EOF2'
import json, sys
s = json.load(open(sys.argv[1]))
names = sorted(s["plan"])
arrays = sorted((a["resolution"], a["angular"]) for a in s["roma_arrays"])
print(" ".join(names), "|", " ".join("%dx%d" % a for a in arrays))
EOF2
}
# cornell: area light + spot light: every pass (GI from the spot by shadow rays: no RSM), arrays
# for A = 4 and A = 8.
got=$(roma_passes builtin:cornell roma_cornell) || fail "ROMA render of cornell failed"
want="ao gbuffer gi many_lights punctual_lights soft_shadows | 128x4 128x8"
[ "$got" = "$want" ] || fail "cornell passes: got '$got', want '$want'"
# plates: one area light, no punctual light: no punctual-light pass, no RSM; GI by shadow rays.
got=$(roma_passes builtin:plates roma_plates) || fail "ROMA render of plates failed"
want="ao gbuffer gi many_lights soft_shadows | 128x4 128x8"
[ "$got" = "$want" ] || fail "plates passes: got '$got', want '$want'"

# --- ROMA through the public effect passes: every effect, and the study's methods plugged into them ---
route_args=(--scene builtin:cornell --tracer roma --effects ao,direct,gi --size 47x35 --spp 2 --frames 2
            --ao-radius 0.5 --quiet)
"$render" "${route_args[@]}" --out "$dir/route_api" --stats "$dir/route_api/stats.json" >/dev/null \
  2>"$dir/route_api.err"
expect_status 0 $? "roma-render --tracer roma (public effect passes)" || cat "$dir/route_api.err" >&2
# The study's shadow method, ray start and GI through reflective shadow maps (src/study/) change
# the images they should change, and only those: the exact traversal and the blind start leave
# AO's and (the exact one) nothing else alike; RSMs change GI alone.
for variant in "exact:--shadow-method voxel-dda" "blind:--ray-start blind" "rsm:--gi-punctual rsm"; do
  tag=${variant%%:*}
  args=${variant#*:}
  # shellcheck disable=SC2086 # the variant's arguments, split
  "$render" "${route_args[@]}" $args --out "$dir/variant_$tag" --stats "$dir/variant_$tag.json" >/dev/null \
    2>"$dir/variant_$tag.err"
  expect_status 0 $? "roma-render $args" || cat "$dir/variant_$tag.err" >&2
  for e in ao direct gi; do
    same=1
    cmp -s "$dir/variant_$tag/$e.pfm" "$dir/route_api/$e.pfm" || same=0
    case "$tag-$e" in
      exact-ao|rsm-ao|rsm-direct) want=1 ;;
      *) want=0 ;;
    esac
    [ $same = $want ] || fail "$args: $e $([ $want = 1 ] && echo changed || echo "did not change")"
  done
done
has_stat "$dir/variant_rsm.json" name rsm || fail "--gi-punctual rsm: the stats lack the RSMs' rasterization"
# Many lights' visibility: the light effect counting visible lights (ROMA_LIGHT_OUTPUT_VISIBLE_COUNT).
"$render" "${route_args[@]}" --effects lights --lights 64 --out "$dir/lights_api" --stats "$dir/lights_api.json" \
  >/dev/null 2>"$dir/lights_api.err"
expect_status 0 $? "roma-render --effects lights" || cat "$dir/lights_api.err" >&2
has_stat "$dir/lights_api.json" name lights || fail "the stats lack the lights pass"
# The study's AO methods take the public AO pass (study/study_ao.h): NAADF traverses the exact
# traversal's voxels, so both give the same image.
for method in voxel-dda naadf; do
  "$render" "${route_args[@]}" --effects ao --ao-method "$method" --cascades 1 --out "$dir/method_$method" \
    --stats "$dir/method_$method.json" >/dev/null 2>&1 || fail "roma-render --ao-method $method failed"
done
cmp -s "$dir/method_voxel-dda/ao.pfm" "$dir/method_naadf/ao.pfm" || fail "NAADF's AO differs from the exact traversal's"
has_stat "$dir/method_naadf.json" name naadf_build || fail "the stats lack the NAADF hierarchy's build"
# The public passes over every pixel (a GPU's default) write the same bits as over the list of
# covered pixels each effect makes and as over one list for every effect and frame (a CPU
# device's default: roma_pixel_list).
for pd in list every shared; do
  "$render" "${route_args[@]}" --pixel-dispatch $pd --out "$dir/route_$pd" \
    --stats "$dir/route_$pd/stats.json" >/dev/null 2>"$dir/route_$pd.err"
  expect_status 0 $? "roma-render --pixel-dispatch $pd" || cat "$dir/route_$pd.err" >&2
  has_stat "$dir/route_$pd/stats.json" pixel_dispatch "$pd" || fail "the stats do not say --pixel-dispatch $pd"
done
for e in ao direct gi; do
  cmp -s "$dir/route_every/$e.pfm" "$dir/route_list/$e.pfm" || fail "$e over every pixel differs from the list's"
  cmp -s "$dir/route_shared/$e.pfm" "$dir/route_list/$e.pfm" || fail "$e over the shared list differs from the list's"
done
has_stat "$dir/route_api/stats.json" pixel_dispatch shared || fail "roma-render's default on lavapipe is not one shared list"
has_stat "$dir/route_shared/stats.json" name pixel_list || fail "the stats lack the shared list's record"
# --resolution-divisor: the public passes trace one pixel a block (the stats say so); 3 is refused.
"$render" "${route_args[@]}" --resolution-divisor 2 --out "$dir/divisor2" --stats "$dir/divisor2/stats.json" \
  >/dev/null 2>"$dir/divisor2.err"
expect_status 0 $? "roma-render --resolution-divisor 2" || cat "$dir/divisor2.err" >&2
has_stat "$dir/divisor2/stats.json" resolution_divisor 2 || fail "the stats do not say --resolution-divisor 2"
"$render" "${route_args[@]}" --resolution-divisor 3 --out "$dir/divisor3" >/dev/null 2>"$dir/divisor3.err"
expect_status 2 $? "roma-render --resolution-divisor 3"
grep -q "bad value for --resolution-divisor: '3' (valid: 1, 2, 4)" "$dir/divisor3.err" ||
  fail "a bad --resolution-divisor does not list the choices"
"$render" "${route_args[@]}" --pixel-dispatch some --out "$dir/route_some" >/dev/null 2>"$dir/route_some.err"
expect_status 2 $? "roma-render --pixel-dispatch some"
grep -q "unknown pixel dispatch 'some' (valid: auto, list, every, shared)" "$dir/route_some.err" ||
  fail "a bad --pixel-dispatch does not list the choices"
"$render" "${route_args[@]}" --route internal --out "$dir/route_gone" >/dev/null 2>"$dir/route_gone.err"
expect_status 2 $? "roma-render --route internal (the internal renderer is gone)"
grep -q "unknown option --route" "$dir/route_gone.err" || fail "--route is not refused as an unknown option"

# Cascade levels: AO far shorter than the scene (cornell, 3 wide, radius 0.05) makes roma-render
# pick levels around the camera and say so (the finest 30 cells to the radius, the coarsest as
# wide as the scene: 5); --finest-extent alone picks them for that edge (4); --cascades 1 keeps
# one grid.
for c in auto:5: finest:4:--finest-extent=0.5 one:1:--cascades=1; do
  IFS=: read -r name want arg <<<"$c"
  # shellcheck disable=SC2086
  "$render" --tracer roma --scene builtin:cornell --effects ao --ao-radius 0.05 --spp 1 --size 32x24 \
    ${arg/=/ } --out "$dir/cascades_$name" --stats "$dir/cascades_$name/stats.json" >/dev/null \
    2>"$dir/cascades_$name.err"
  expect_status 0 $? "roma-render with cascades ($name)" || cat "$dir/cascades_$name.err" >&2
  got=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["roma_arrays"][0]["levels"])' \
    "$dir/cascades_$name/stats.json" 2>/dev/null)
  [ "$got" = "$want" ] || fail "roma-render ($name): $got cascade levels, expected $want"
done
grep -q "note: cascades: 5 grids around the camera, the finest 0.213 wide (30 cells to the AO radius 0.05)" \
  "$dir/cascades_auto.err" || fail "roma-render does not say which cascade levels it picked"
# The room's far wall lies beyond the coarsest of those levels: said.
grep -q "note: cascades: the coarsest grid reaches 1.71 from the camera and the scene 2.9: geometry farther away is not traced" \
  "$dir/cascades_auto.err" || fail "roma-render does not say that part of the scene lies beyond its levels"
grep -q "the finest 0.5 wide (--finest-extent)" "$dir/cascades_finest.err" ||
  fail "roma-render does not say the finest level's edge came from --finest-extent"
! grep -q "note: cascades" "$dir/cascades_one.err" || fail "roma-render --cascades 1 still notes cascades"
# More levels than one storage buffer of the device holds (RES 256, A 4, 7 levels for a 1 cm
# radius: 224 MiB of maps; lavapipe holds 128 MiB in one): roma-render renders with the levels
# that fit and says how many (where the device holds them all, with all 7 and no note).
"$render" --tracer roma --scene builtin:cornell --effects ao --ao-radius 0.01 --res 256 --spp 1 --size 16x12 \
  --out "$dir/cascades_fit" --stats "$dir/cascades_fit/stats.json" >/dev/null 2>"$dir/cascades_fit.err"
expect_status 0 $? "roma-render with more levels than a storage buffer holds" || cat "$dir/cascades_fit.err" >&2
got=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["roma_arrays"][0]["levels"])' \
  "$dir/cascades_fit/stats.json" 2>/dev/null)
fit=$(sed -n 's/.*RES 256, A 4: \([0-9]*\) of the 7 cascade levels fit in one storage buffer.*/\1/p' "$dir/cascades_fit.err")
[ "$got" = "${fit:-7}" ] || fail "roma-render with 7 levels wanted: $got levels made, the note says ${fit:-none}"

# --jitter off: every frame's grid and directions the first's (the stats say so); a bad value is
# refused.
"$render" --tracer roma --scene builtin:cornell --effects ao --spp 1 --frames 2 --size 32x24 --jitter off \
  --out "$dir/jitter_off" --stats "$dir/jitter_off/stats.json" >/dev/null 2>"$dir/jitter_off.err"
expect_status 0 $? "roma-render --jitter off" || cat "$dir/jitter_off.err" >&2
got=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["settings"]["jitter"])' \
  "$dir/jitter_off/stats.json" 2>/dev/null)
[ "$got" = "off" ] || fail "roma-render --jitter off: the stats say jitter '$got'"
"$render" --tracer roma --scene builtin:cornell --effects ao --size 32x24 --jitter maybe --out "$dir/jitter_bad" \
  >/dev/null 2>"$dir/jitter_bad.err"
expect_status 2 $? "roma-render --jitter maybe"

# --- Usage and bad input ---
"$render" --help >"$dir/help.out" 2>&1
expect_status 0 $? "roma-render --help"
grep -q '^usage: roma-render' "$dir/help.out" || fail "roma-render --help prints no usage"

# bad_args NAME ARGS...: roma-render must exit 2 with a message on stderr.
bad_args() {
  local what=$1
  shift
  "$render" "$@" --out "$dir/bad" >"$dir/bad.out" 2>"$dir/bad.err"
  expect_status 2 $? "roma-render $what"
  [ -s "$dir/bad.err" ] || fail "roma-render $what: no message on stderr"
}
bad_args "--size 0x0" --size 0x0
bad_args "--size 100000x100000" --size 100000x100000
bad_args "--effects bogus" --effects bogus
bad_args "--tracer bogus" --tracer bogus
bad_args "--shadow-angular 17" --tracer roma --shadow-angular 17
bad_args "--max-steps 0" --tracer roma --max-steps 0
bad_args "unknown option" --no-such-option
bad_args "--camera with eye == target" --camera 1,2,3,1,2,3,45
bad_args "--preset bogus" --tracer roma --preset bogus
bad_args "--budget-ms 0" --tracer roma --budget-ms 0
bad_args "--budget-ms with --res" --tracer roma --budget-ms 50 --res 64
[ -e "$dir/bad" ] && fail "roma-render created its output folder despite bad arguments"

# The largest size accepted: lavapipe can neither hold its G-buffer (17 GB) nor read it as
# a texel buffer (2^30 texels, its limit 2^27), so it must end with a clear error, exit
# status 1 and no output folder; a device that can must render it.
"$render" --tracer roma --effects ao --size 16384x16384 --spp 1 --quiet --out "$dir/huge" >/dev/null 2>"$dir/huge.err"
status=$?
if [ $status -eq 0 ]; then
  [ -s "$dir/huge/ao.pfm" ] || fail "roma-render --size 16384x16384 succeeded without writing ao.pfm"
else
  expect_status 1 $status "roma-render --size 16384x16384"
  grep -qE "out of device memory|maxTexelBufferElements" "$dir/huge.err" \
    || fail "roma-render --size 16384x16384 does not say why (device memory or texel buffer limit)"
  [ -e "$dir/huge" ] && fail "roma-render left an output folder after failing"
fi
rm -rf "$dir/huge"

missing="$dir/no_such_scene.glb"
"$render" --scene "$missing" --size 8x8 --spp 1 --out "$dir/missing" >/dev/null 2>"$dir/missing.err"
expect_status 1 $? "roma-render with a missing scene file"
grep -qF "$missing" "$dir/missing.err" || fail "the error for a missing scene does not name $missing"
grep -q "No such file or directory" "$dir/missing.err" || fail "the error for a missing scene does not give the system's reason"

# Errors that name the cause; choices list their valid values; near misses are suggested.
# says WHAT PATTERN ARGS...: roma-render exits non-zero and stderr matches PATTERN.
says() {
  local what=$1 pattern=$2
  shift 2
  "$render" --size 8x8 --spp 1 --quiet "$@" >"$dir/says.out" 2>"$dir/says.err"
  [ $? -ne 0 ] || fail "roma-render $what succeeded"
  grep -q -- "$pattern" "$dir/says.err" || { fail "roma-render $what does not say '$pattern'"; cat "$dir/says.err" >&2; }
}
mkdir -p "$dir/a_folder"
printf 'o cube\n' >"$dir/model.obj"
says "--scene DIRECTORY" "is a directory" --scene "$dir/a_folder" --out "$dir/x1"
says "--scene MODEL.obj" "only glTF 2.0 files (.gltf, .glb)" --scene "$dir/model.obj" --out "$dir/x2"
says "--scene builtin:cornel" "did you mean builtin:cornell?" --scene builtin:cornel --out "$dir/x3"
says "--out under a file" "cannot create output folder .*: Not a directory" --out "$dir/model.obj/out"
says "--res 100" "valid: 32, 64, 128, 256" --tracer roma --res 100 --out "$dir/x4"
says "--effects occlusion" "valid: ao, direct, gi, lights" --effects occlusion --out "$dir/x5"
says "--effects directt" "did you mean direct?" --effects directt --out "$dir/x6"
says "--effcts" "did you mean --effects?" --effcts ao --out "$dir/x7"
says "--tracer optix" "valid: embree, roma" --tracer optix --out "$dir/x8"
says "--light bogus" "bad light 'bogus'" --light bogus --out "$dir/x9"
says "--stats in a missing folder" "cannot write .*stats.json: No such file or directory" \
  --out "$dir/x10" --stats "$dir/no/such/stats.json"

# Say when nothing happens (stderr and the stats' notes), and the defaults chosen.
"$render" --scene "$ROMA_SCENES_DIR/spot.glb" --effects ao,direct,gi --size 16x12 --spp 1 --frames 2 --res 64 \
  --out "$dir/notes" --stats "$dir/notes/stats.json" >/dev/null 2>"$dir/notes.err"
expect_status 0 $? "roma-render on spot.glb with direct and gi" || cat "$dir/notes.err" >&2
for pattern in "direct: the scene has no light" "gi: the scene has no light" "--frames is a ROMA setting" \
               "--res is a ROMA setting" "AO radius .*10% of the scene's diagonal"; do
  grep -q -- "$pattern" "$dir/notes.err" || fail "roma-render does not say '$pattern'"
  grep -q -- "$pattern" "$dir/notes/stats.json" || fail "the stats' notes lack '$pattern'"
done
has_stat "$dir/notes/stats.json" ao_radius_from "10% of the scene..." || fail "the stats do not say where the AO radius came from"
"$render" --tracer roma --effects gi --threads 2 --size 16x12 --spp 1 --out "$dir/notes2" >/dev/null 2>"$dir/notes2.err"
"$render" --tracer embree --effects gi --gi-punctual rays --size 16x12 --spp 1 --out "$dir/notes3" >/dev/null \
  2>"$dir/notes3.err"
grep -q -- "--gi-punctual is a ROMA setting" "$dir/notes3.err" || fail "--gi-punctual with the reference: no note"
"$render" --tracer roma --effects gi --gi-punctual bogus --size 16x12 --out "$dir/notes4" >/dev/null 2>"$dir/notes4.err"
expect_status 2 $? "roma-render --gi-punctual bogus"
grep -q "unknown gi route 'bogus'" "$dir/notes4.err" || fail "a bad --gi-punctual does not say why"
# The AO baselines of the accuracy study render; a bad method lists the valid ones.
for method in voxel-dda distance-field naadf screen-space; do
  "$render" --tracer roma --effects ao --ao-method "$method" --size 16x12 --spp 1 --res 32 --out "$dir/$method" \
    --stats "$dir/$method/stats.json" >/dev/null 2>&1 || fail "roma-render --ao-method $method failed"
done
has_stat "$dir/distance-field/stats.json" name distance_field_build || fail "the stats lack the distance field's build"
has_stat "$dir/naadf/stats.json" name naadf_build || fail "the stats lack the NAADF hierarchy's build"
# Screen-space AO against a stochastic depth map too; its layers only with that method.
"$render" --tracer roma --effects ao --ao-method screen-space --ssao-layers 2 --ao-radius 0.5 --size 16x12 --spp 1 \
  --out "$dir/sdmap" --stats "$dir/sdmap/stats.json" >/dev/null 2>&1 || fail "roma-render --ssao-layers 2 failed"
has_stat "$dir/sdmap/stats.json" name depth_layers || fail "the stats lack the depth layers' rasterization"
"$render" --tracer roma --effects ao --ssao-layers 2 --size 16x12 --out "$dir/sdmap2" >/dev/null 2>"$dir/sdmap2.err"
expect_status 2 $? "roma-render --ssao-layers without screen space"
grep -q -- "--ssao-layers is for --ao-method screen-space" "$dir/sdmap2.err" || fail "--ssao-layers alone: no reason"
"$render" --tracer roma --effects ao --ao-method bogus --size 16x12 --out "$dir/aom" >/dev/null 2>"$dir/aom.err"
expect_status 2 $? "roma-render --ao-method bogus"
grep -q "valid: roma, voxel-dda, distance-field, naadf, screen-space" "$dir/aom.err" || fail "a bad --ao-method does not list the methods"
grep -q -- "--threads sets the CPU threads of the G-buffer's primary rays" "$dir/notes2.err" ||
  fail "--threads with ROMA: no note"
grep -q "frames 100%" "$dir/notes2.err" || fail "a ROMA render prints no progress"
grep -q "done in" "$dir/notes2.err" || fail "roma-render does not say how long it took"
"$render" --tracer roma --effects ao --size 16x12 --spp 1 --quiet --out "$dir/quiet" >/dev/null 2>"$dir/quiet.err"
[ ! -s "$dir/quiet.err" ] || fail "roma-render --quiet printed: $(head -2 "$dir/quiet.err")"

# --light adds lights to any scene: the spot model is lit (direct no longer black), by
# a point light and by a sun, on both tracers.
for tracer in embree roma; do
  "$render" --scene "$ROMA_SCENES_DIR/spot.glb" --tracer "$tracer" --effects direct --size 24x18 --spp 1 --quiet \
    --light point:0,1.5,1.5:1,1,1:5 --light sun:0,-1,-1:1,0.9,0.8:2 --res 64 \
    --out "$dir/lit_$tracer" --stats "$dir/lit_$tracer/stats.json" >/dev/null 2>"$dir/lit_$tracer.err"
  expect_status 0 $? "roma-render --light ($tracer)" || cat "$dir/lit_$tracer.err" >&2
  "$compare" "$dir/lit_$tracer/direct.pfm" "$dir/lit_$tracer/direct.pfm" >"$dir/lit_$tracer.cmp" 2>&1
  m=$(metric "$dir/lit_$tracer.cmp" mean_a)
  awk -v m="${m:-0}" 'BEGIN { exit !(m > 0) }' || fail "--light ($tracer): direct.pfm is still black (mean ${m:-none})"
  has_stat "$dir/lit_$tracer/stats.json" added_lights 2 || fail "--light ($tracer): the stats do not count 2 added lights"
  has_stat "$dir/lit_$tracer/stats.json" punctual_lights 2 || fail "--light ($tracer): the scene has not 2 lights"
done

# --time poses an animated glTF (both tracers); a scene without animation says so.
"$render" --scene builtin:cornell --time 0.5 --size 8x8 --spp 1 --quiet --out "$dir/posed" >/dev/null 2>"$dir/posed.err"
expect_status 1 $? "roma-render --time on a scene without animation"
grep -q "no animation data" "$dir/posed.err" || fail "roma-render --time on a static scene does not say it has no animation data"
"$render" --scene "$ROMA_SCENES_DIR/CesiumMan.glb" --time 0.5 --size 16x12 --spp 1 --quiet \
  --out "$dir/cesium" --stats "$dir/cesium.json" >/dev/null 2>"$dir/cesium.err"
expect_status 0 $? "roma-render --time 0.5 on CesiumMan" || cat "$dir/cesium.err" >&2
has_stat "$dir/cesium.json" pose_time || fail "the stats of a posed render do not give the pose"

# --format: OpenEXR beside PFM holds the same floats (1 and 3 channels), read back by
# roma-compare; PNG is not written when not asked for; an unknown format lists the valid ones.
"$render" --scene builtin:cornell --effects ao,direct --tracer roma --size 24x16 --spp 2 --ao-radius 0.5 \
  --quiet --format pfm,exr --out "$dir/exr" >/dev/null 2>"$dir/exr.err"
expect_status 0 $? "roma-render --format pfm,exr" || cat "$dir/exr.err" >&2
for e in ao direct; do
  [ -f "$dir/exr/$e.exr" ] || fail "--format pfm,exr wrote no $e.exr"
  [ ! -e "$dir/exr/$e.png" ] || fail "--format pfm,exr wrote $e.png"
  "$compare" "$dir/exr/$e.exr" "$dir/exr/$e.pfm" >"$dir/exr_$e.cmp" 2>&1
  expect_status 0 $? "roma-compare $e.exr $e.pfm" || cat "$dir/exr_$e.cmp" >&2
  [ "$(metric "$dir/exr_$e.cmp" max_abs)" = "0" ] || fail "$e.exr differs from $e.pfm"
  [ "$(metric "$dir/exr_$e.cmp" pixels)" = "384" ] || fail "$e.exr: not 24x16 pixels"
done
"$render" --size 8x8 --spp 1 --quiet --format tiff --out "$dir/tiff" >/dev/null 2>"$dir/tiff.err"
expect_status 2 $? "roma-render --format tiff"
grep -q "valid: pfm, png, exr" "$dir/tiff.err" || fail "an unknown --format does not list the valid formats"

# --up turns a scene authored with another up axis: tabletop.gltf is y-down; turned, its
# bounds in y are the negated bounds of the file (a rotation by 180 degrees about x).
for up in +y -y; do
  "$render" --scene "$ROMA_SCENES_DIR/tabletop.gltf" --up "$up" --size 8x6 --spp 1 --quiet --ao-radius 1 \
    --out "$dir/up$up" --stats "$dir/up$up.json" >/dev/null 2>"$dir/up$up.err"
  expect_status 0 $? "roma-render --up $up" || cat "$dir/up$up.err" >&2
done
python3 - "$dir/up+y.json" "$dir/up-y.json" <<'PY' || fail "--up -y did not turn tabletop.gltf upside up"
import json, sys
a, b = (json.load(open(p))["scene"] for p in sys.argv[1:])
assert abs(a["bounds_min"][1] + b["bounds_max"][1]) < 1e-4 and abs(a["bounds_max"][1] + b["bounds_min"][1]) < 1e-4, (a, b)
assert abs(a["bounds_min"][0] - b["bounds_min"][0]) < 1e-4, (a, b)
PY
says "--up sideways" "valid: +y, -y, +z" --up sideways --out "$dir/x11"

# --animation by name (or index) and --gltf-camera; a wrong name lists the animations.
"$render" --scene "$ROMA_SCENES_DIR/Fox.glb" --animation Walk --time 0.3 --size 8x6 --spp 1 --quiet \
  --out "$dir/fox" --stats "$dir/fox.json" >/dev/null 2>"$dir/fox.err"
expect_status 0 $? "roma-render --animation Walk" || cat "$dir/fox.err" >&2
has_stat "$dir/fox.json" pose_clip 1 || fail "--animation Walk did not pose clip 1"
says "--animation Wallk" "did you mean Walk?" --scene "$ROMA_SCENES_DIR/Fox.glb" --animation Wallk --out "$dir/x12"
grep -q "the scene has 3: 0 (Survey) 1 (Walk) 2 (Run)" "$dir/says.err" || fail "a wrong --animation does not list the animations"
says "--gltf-camera 1" "the file has 1 perspective camera" --scene "$ROMA_SCENES_DIR/2CylinderEngine.glb" \
  --gltf-camera 1 --out "$dir/x13"

# PNG pictures: --background paints the pixels that see nothing, --exposure scales, and
# --tonemap reinhard maps c to c / (1 + c); the PFM keeps the exact values.
"$render" --scene "$ROMA_SCENES_DIR/spot.glb" --effects ao --size 32x24 --spp 4 --quiet --background 0,0,1 \
  --exposure 0.5 --tonemap reinhard --out "$dir/png" >/dev/null 2>"$dir/png.err"
expect_status 0 $? "roma-render --background --exposure --tonemap" || cat "$dir/png.err" >&2
python3 "$(dirname "$0")/check_png_tone.py" "$dir/png/ao.png" "$dir/png/ao.pfm" "$dir/png/coverage.pfm" \
  || fail "the PNG does not show the background, exposure and tone map asked for"
says "--tonemap filmic" "valid: clamp, reinhard" --tonemap filmic --out "$dir/x14"

# The default camera of a scene without one fills the picture: the bunny covers 29% of it
# (libroma's bounding-sphere framing: 14%).
"$render" --scene "$ROMA_SCENES_DIR/bunny.glb" --effects ao --size 64x48 --spp 1 --quiet --out "$dir/framed" \
  >/dev/null 2>"$dir/framed.err"
"$compare" "$dir/framed/coverage.pfm" "$dir/framed/coverage.pfm" >"$dir/framed.cmp" 2>&1
covered=$(metric "$dir/framed.cmp" mean_a)
awk -v c="${covered:-0}" 'BEGIN { exit !(c >= 0.28 && c <= 0.9) }' \
  || fail "the default camera frames the bunny at ${covered:-none} of the picture, expected 0.28 to 0.9"

# roma-bench --accuracy --small times one run: it must not claim medians of 3.
bench=$(dirname "$compare")/roma-bench
if [ -x "$bench" ]; then
  bench_run=("$bench")
  [ -n "${ROMA_TOOL_PRELOAD:-}" ] && bench_run=(env "LD_PRELOAD=$ROMA_TOOL_PRELOAD" "$bench")
  "${bench_run[@]}" --accuracy --small --ao-radius 0.5 >"$dir/bench.out" 2>&1 || fail "roma-bench --accuracy --small failed"
  grep -q "runs: 1 (one run: no median)" "$dir/bench.out" || fail "roma-bench --accuracy --small does not say it ran once"
  grep -q "median of 1 runs\|runs: 3" "$dir/bench.out" && fail "roma-bench --accuracy --small still speaks of medians"
fi

# An unwritable stats file or a malformed number is an error, not a silent success.
"$render" --size 8x8 --spp 1 --quiet --out "$dir/nostats" --stats "$dir/no/such/dir/stats.json" >/dev/null 2>"$dir/nostats.err"
expect_status 1 $? "roma-render with an unwritable --stats path"
"$compare" "$dir/nostats/ao.pfm" "$dir/nostats/ao.pfm" --tolerance abc >/dev/null 2>"$dir/tolerance.err"
expect_status 2 $? "roma-compare --tolerance abc"

# --- Presets and --budget-ms (roma/presets.h): the preset's RES and A in the stats; a
#     budget measures each preset once per device, scene, size and effects (fastest first,
#     stopping at the first over the budget) and reads them back from its cache ---
"$render" "${common[@]}" --tracer roma --effects ao --preset high --angular 2 --out "$dir/preset" \
  --stats "$dir/preset/stats.json" >/dev/null 2>"$dir/preset.err"
expect_status 0 $? "roma-render --preset high" || cat "$dir/preset.err" >&2
python3 - "$dir/preset/stats.json" <<'PY' || fail "--preset high --angular 2 is not RES 256, A 2 in the stats"
import json, sys
s = json.load(open(sys.argv[1]))["settings"]
assert s["preset"] == "high" and s["resolution"] == 256 and s["angular"] == 2, s
PY
budget=(--scene builtin:cornell --size 32x24 --spp 1 --tracer roma --effects ao --budget-cache "$dir/budget.tsv")
# A budget below the fastest preset's time: low, said to be over the budget, and nothing
# slower measured.
"$render" "${budget[@]}" --budget-ms 1e-6 --out "$dir/budget" --stats "$dir/budget/low.json" \
  >/dev/null 2>"$dir/budget1.err"
expect_status 0 $? "roma-render --budget-ms 1e-6" || cat "$dir/budget1.err" >&2
grep -q 'low (RES 128, A 2), the fastest preset, over the budget' "$dir/budget1.err" ||
  fail "a budget nothing fits does not fall back to low: $(grep budget "$dir/budget1.err")"
[ "$(wc -l <"$dir/budget.tsv")" -eq 1 ] || fail "a budget below low's time measured more than low"
# No bound: ultra, the three others measured now, low read from the cache; then all cached.
"$render" "${budget[@]}" --budget-ms 1e9 --out "$dir/budget" --stats "$dir/budget/stats.json" \
  >/dev/null 2>"$dir/budget2.err"
expect_status 0 $? "roma-render --budget-ms 1e9" || cat "$dir/budget2.err" >&2
grep -q -- '--budget-ms 1e+09: ultra (RES 256, A 8)' "$dir/budget2.err" ||
  fail "an unbounded budget does not choose ultra: $(grep budget "$dir/budget2.err")"
[ "$(wc -l <"$dir/budget.tsv")" -eq 4 ] || fail "the budget cache does not hold the four presets' times"
[ "$(grep -o '(cached)' "$dir/budget2.err" | wc -l)" -eq 1 ] || fail "low's time was not read from the cache"
"$render" "${budget[@]}" --budget-ms 1e9 --out "$dir/budget" >/dev/null 2>"$dir/budget3.err"
expect_status 0 $? "roma-render --budget-ms 1e9 (cached)"
[ "$(grep -o '(cached)' "$dir/budget3.err" | wc -l)" -eq 4 ] || fail "a second run measures again"
python3 - "$dir/budget/stats.json" "$dir/budget/low.json" <<'PY' || fail "the stats do not record the budget's choice"
import json, sys
a = json.load(open(sys.argv[1]))["settings"]
b = json.load(open(sys.argv[2]))["settings"]
assert a["preset"] == "ultra" and a["budget"]["fits"] == 1 and len(a["budget"]["ms_per_frame"]) == 4, a
assert b["preset"] == "low" and b["budget"]["fits"] == 0 and b["resolution"] == 128 and b["angular"] == 2, b
PY

# Sanitizer builds: a report fails the test even where the expected exit status
# (1) is the one ASan exits with.
if reports=$(grep -l -E 'ERROR: (Address|Leak)Sanitizer|runtime error:' "$dir"/*.err "$dir"/*.cmp); then
  fail "sanitizer reports in: $(echo $reports)"
fi

if [ "$failures" -ne 0 ]; then
  echo "test_cli: $failures check(s) failed (outputs in $dir)" >&2
  exit 1
fi
echo "test_cli: all checks passed"
