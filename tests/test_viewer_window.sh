#!/usr/bin/env bash
# roma-viewer in a window under Xvfb (GLFW, swapchain, Dear ImGui; validation on): a few
# frames, the scripted windows of tests/viewer/*.script (an orbit, effects turned off, the
# reprojected history, resilience, quitting while the reference renders, the scene's cameras),
# and bad input (an unknown view lists the valid ones; a missing scene names the file).
# Usage: test_viewer_window.sh ROMA_VIEWER ROMA_RENDER ROMA_COMPARE SCENES_DIR SCRATCH_DIR
source "$(dirname "$0")/test_viewer_common.sh" "$@"

# 3. The window: swapchain, interface, two frames in flight.
if ! command -v xvfb-run >/dev/null; then
  fail "xvfb-run is missing (./install-deps.sh installs xvfb): the window was not tested"
else
  xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --frames 12 --size 320x200 \
    --view map --screenshot "$dir/window.png" >"$dir/window.out" 2>&1 \
    || { cat "$dir/window.out" >&2; fail "roma-viewer in a window (Xvfb) failed"; }
  [ -s "$dir/window.png" ] || fail "no picture from the window run"
fi

# 3b. Scripted windows (tests/viewer/*.script): an orbit of 60 frames ends with a finite
#     picture; turning an effect off drops its pass and changes the picture; a 1x1 window,
#     minimising and a malformed file dropped in leave the viewer running.
scripts=$(cd "$(dirname "$0")/viewer" && pwd)
printf '{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]' >"$dir/malformed.gltf"
windowed() { # NAME SCRIPT: run it in a window under Xvfb, stats in $dir/NAME.json
  local name=$1 script=$2
  (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 160x120 --script "$script" \
     --stats "$dir/$name.json" --linear "$dir/$name.pfm") >"$dir/$name.out" 2>&1
}
if command -v xvfb-run >/dev/null; then
  windowed orbit "$scripts/orbit.script" || { cat "$dir/orbit.out" >&2; fail "the scripted orbit failed"; }
  frames=$(json "$dir/orbit.json" frames)
  [ "${frames:-0}" -ge 64 ] || fail "the orbit ran ${frames:-no} frames, expected at least 64"
  compare_checked "$dir/orbit.pfm" "$dir/orbit.pfm" >"$dir/orbit.cmp" 2>&1
  grep -q "^non_finite" "$dir/orbit.cmp" && fail "the picture after the orbit has NaN or infinite pixels"
  grep -q "^pixels  *19200" "$dir/orbit.cmp" || fail "the picture after the orbit is not 160x120"

  windowed all "$scripts/still.script" || { cat "$dir/all.out" >&2; fail "the still script failed"; }
  for effect in ao direct gi; do
    windowed "${effect}_off" "$scripts/${effect}_off.script" || { cat "$dir/${effect}_off.out" >&2; fail "$effect off failed"; }
  done
  passes_all=$(json "$dir/all.json" passes)
  passes_ao=$(json "$dir/ao_off.json" passes)
  passes_direct=$(json "$dir/direct_off.json" passes)
  passes_gi=$(json "$dir/gi_off.json" passes)
  case " $passes_all " in *" ao "*) ;; *) fail "the composed view ran no ao pass ($passes_all)" ;; esac
  case " $passes_all " in *" direct_light "*) ;; *) fail "the composed view ran no direct_light pass ($passes_all)" ;; esac
  case " $passes_ao " in *" ao "*) fail "ao off still ran the ao pass ($passes_ao)" ;; esac
  case " $passes_all " in *" gi "*) ;; *) fail "the composed view ran no gi pass ($passes_all)" ;; esac
  case " $passes_direct " in *" direct_light "*) fail "direct off still ran the direct_light pass ($passes_direct)" ;; esac
  case " $passes_gi " in *" gi "*) fail "gi off still ran the gi pass ($passes_gi)" ;; esac
  for effect in ao direct gi; do
    compare_checked "$dir/all.pfm" "$dir/${effect}_off.pfm" >"$dir/${effect}_off.cmp" 2>&1
    d=$(metric "$dir/${effect}_off.cmp" mean_abs)
    awk -v d="${d:-0}" 'BEGIN { exit !(d > 0.001) }' || fail "turning $effect off did not change the picture (MAE ${d:-none})"
  done

  # Moving: the history is reprojected (not thrown away), so after a 30-frame orbit the AO
  # is far closer to the reference at the final camera than a picture of one frame; the
  # a-trous filter alone, on single frames, does most of that too.
  for variant in orbit_ao orbit_ao_fresh orbit_ao_filtered; do
    (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 160x120 --ao-radius 0.5 \
       --script "$scripts/$variant.script" --stats "$dir/$variant.json" --linear "$dir/$variant.pfm") \
       >"$dir/$variant.out" 2>&1 || { cat "$dir/$variant.out" >&2; fail "$variant failed"; }
  done
  final=$(json "$dir/orbit_ao.json" camera)
  "$render" --tracer embree --effects ao --spp 256 --ao-radius 0.5 --camera "$final" --size 160x120 --quiet \
    --out "$dir/orbit_reference" >/dev/null 2>&1 || fail "the reference at the orbit's end failed"
  for variant in orbit_ao orbit_ao_fresh orbit_ao_filtered; do
    compare_checked "$dir/$variant.pfm" "$dir/orbit_reference/ao.pfm" --mask "$dir/orbit_reference/coverage.pfm" \
      >"$dir/$variant.cmp" 2>&1
  done
  kept=$(metric "$dir/orbit_ao.cmp" mean_abs)
  fresh=$(metric "$dir/orbit_ao_fresh.cmp" mean_abs)
  filtered=$(metric "$dir/orbit_ao_filtered.cmp" mean_abs)
  echo "AO after an orbit, MAE against Embree: reprojected history $kept, one frame $fresh, one frame filtered $filtered"
  # Measured: 0.0573, 0.1439 and 0.0678 (a still camera converges to 0.0449); before the viewer
  # used libroma's temporal effect (its own shader then): 0.0578, 0.1439, 0.0678.
  below "${filtered:-1}" 0.073 || fail "the filtered single frame is further than 0.073 from the reference ($filtered)"
  below "${kept:-1}" 0.063 || fail "after the orbit the reprojected AO is further than 0.063 from the reference ($kept)"
  awk -v k="${kept:-1}" -v f="${fresh:-0}" 'BEGIN { exit !(k < 0.5 * f) }' \
    || fail "the reprojected history does not halve the error of a single frame ($kept against $fresh)"

  windowed resilience "$scripts/resilience.script" || { cat "$dir/resilience.out" >&2; fail "the resilience script failed"; }
  [ "$(json "$dir/resilience.json" scene_failures)" = "1" ] || fail "the malformed file was not refused once"
  grep -q "cannot open malformed.gltf" "$dir/resilience.out" || fail "the malformed file is not named in a message"
  [ "$(json "$dir/resilience.json" validation_messages)" = "0" ] || fail "validation messages in the resilience script"
  [ "$(json "$dir/resilience.json" resolution) $(json "$dir/resilience.json" angular)" = "64 2" ] \
    || fail "RES 64 and A 2, set by the script, did not reach the map"

  # Quitting while the Embree reference renders (640x480 at 4,096 samples a pixel: about 150 s
  # here) stops it: measured 4.9 s to quit with it stopped (23 s with a build beside it), and
  # at 1,024 samples 41 s when the viewer waited for it.
  started=$(date +%s)
  (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 640x480 --reference-spp 4096 \
     --script "$scripts/quit_while_reference.script" --stats "$dir/quit_reference.json") \
    >"$dir/quit_reference.out" 2>&1 || { cat "$dir/quit_reference.out" >&2; fail "the quit-while-reference script failed"; }
  took=$(( $(date +%s) - started ))
  grep -q "quitting stopped the reference render" "$dir/quit_reference.out" \
    || fail "quitting did not stop the reference render"
  [ "$took" -le 60 ] || fail "quitting waited ${took} s for the reference instead of stopping it"
  pgrep -f "roma-viewer-reference-" >/dev/null && fail "a reference render outlived the viewer"

  # The scene's cameras: a glTF file with two, the second picked as the interface's button picks
  # it (script verb camera); a camera the scene lacks is refused with a message.
  (cd "$dir" && xvfb-run -a -s "-screen 0 800x600x24" "$viewer" --validation --size 160x120 \
     --scene "$scripts/two_cameras.gltf" --script "$scripts/cameras.script" --stats "$dir/cameras.json") \
    >"$dir/cameras.out" 2>&1 || { cat "$dir/cameras.out" >&2; fail "the cameras script failed"; }
  grep -q "the scene has no camera 5 (it has 2)" "$dir/cameras.out" || fail "camera 5 of 2 was not refused with a message"
  python3 - "$(json "$dir/cameras.json" camera)" <<'EOF' || fail "the viewer's camera is not the file's second camera"
import sys
got = [float(x) for x in sys.argv[1].split(",")]
want = [3, 1, 0, 2, 1, 0, 57.29578]  # translation (3, 1, 0), turned to look along -x, yfov 1 rad
sys.exit(0 if all(abs(a - b) < 1e-3 for a, b in zip(got, want)) and len(got) == 7 else 1)
EOF
fi

# 4. Bad input.
"$viewer" --headless --view occlusion >/dev/null 2>"$dir/view.err"
[ $? -eq 2 ] || fail "an unknown --view does not exit with status 2"
grep -q "valid: composed, ao, direct" "$dir/view.err" || fail "an unknown --view does not list the valid views"
"$viewer" --headless --scene "$dir/no-such.glb" >/dev/null 2>"$dir/scene.err"
[ $? -eq 1 ] || fail "a missing scene does not exit with status 1"
grep -q "no-such.glb" "$dir/scene.err" || fail "the error for a missing scene does not name the file"

finish window
