#!/usr/bin/env bash
# Every GPU check in one command, for a machine with a GPU lent for minutes (start-up included):
# the C test programs with validation on (test_hw_ray_tracing among them), roma-bench on dragon_res2
# (generation, the trace ladder with the hardware ray-tracing rows,
# the frame), the cascade levels' build and dynamic frame on ctf_compromise, the accuracy study
# on aggressor (one grid against cascade levels, 640 x 480) and on the room (AO: every method, the
# hardware's rows and the ray-traced stochastic depth map among them; direct light with the
# hardware's rows), and the issue-41 passes through
# roma-render (AO at 1920 x 1080 on dragon_res2, also with the rays' start through the surface
# grid, many lights on the room) with GPU timestamps.
# Each step has its own timeout and a failing step does not stop the others; the timeouts add up
# to 480 s, within the 8 minutes a lent GPU leaves for the checks.
#
# The GPU machine may have no compiler: the binaries are built here and carried.
#   bash docs/bench/gpu_checks.sh bundle [BUILD_DIR]   # here: out/gpu-bundle (stripped tools and
#                                                      # test programs, the shared levels; ~55 MiB)
#   bash docs/bench/gpu_checks.sh run [OUT_DIR]        # there, from the repository root with
#                                                      # out/gpu-bundle carried; writes OUT_DIR
#                                                      # (default out/gpu), then copy it to docs/bench
set -uo pipefail
mode=${1:-}
bundle=out/gpu-bundle
case "$mode" in
bundle)
  build=${2:-build}
  levels=${ROMA_LEVELS_DIR:-../shared/scenes/levels}
  rm -rf "$bundle" && mkdir -p "$bundle/tests" "$bundle/levels" || exit 1
  for tool in roma-bench roma-render roma-compare; do
    strip -o "$bundle/$tool" "$build/apps/$tool" || exit 1
  done
  # The C test programs (the shell-script tests drive the tools, which run below on their own).
  find "$build/tests" -maxdepth 1 -type f -executable -name 'test_*' | while read -r t; do
    strip -o "$bundle/tests/$(basename "$t")" "$t" || exit 1
  done
  [ -x "$build/tests/fuzz_trace" ] && strip -o "$bundle/tests/fuzz_trace" "$build/tests/fuzz_trace"
  cp "$levels"/*.glb "$levels"/*.cameras "$bundle/levels/" || exit 1
  git log -1 --format='commit %h' > "$bundle/commit.txt"
  du -sh "$bundle"
  ;;
run)
  out=${2:-out/gpu}
  [ -x "$bundle/roma-bench" ] || { echo "gpu_checks: no $bundle (make it with: $0 bundle)" >&2; exit 1; }
  mkdir -p "$out" "$out/tmp" || exit 1
  lv=$bundle/levels
  step() { # step NAME SECONDS COMMAND...: output in OUT/NAME.txt, its status and time in OUT/summary.txt
    local name=$1 limit=$2 start rc
    shift 2
    start=$(date +%s%N)
    timeout "$limit" "$@" > "$out/$name.txt" 2>&1
    rc=$?
    printf '%-28s rc %3d  %6d ms  (limit %s s)\n' "$name" "$rc" $((($(date +%s%N) - start) / 1000000)) "$limit" |
      tee -a "$out/summary.txt"
  }
  : > "$out/summary.txt"
  cat "$bundle/commit.txt" | tee -a "$out/summary.txt"
  { nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv 2>&1
    command -v vulkaninfo >/dev/null && vulkaninfo --summary 2>&1 | sed -n '/Devices:/,$p'; } > "$out/device.txt"
  step tests 130 bash "$0" tests "$out"
  echo "tests: $(grep -c ' rc 0$' "$out/tests.txt") of $(grep -c ' rc ' "$out/tests.txt") passed" | tee -a "$out/summary.txt"
  step fuzz_trace 30 env ROMA_VALIDATION=1 "$bundle/tests/fuzz_trace" --seconds 20
  step dragon_res2 70 "$bundle/roma-bench" --scene scenes/dragon_res2.glb --runs 5 --res 128 --angular 4 \
    --csv "$out/dragon_res2.csv"
  step cascades_ctf_compromise 50 "$bundle/roma-bench" --scene "$lv/ctf_compromise.glb" \
    --camera "$(sed -n 1p "$lv/ctf_compromise.cameras")" --cascades 6 --ao-radius 1.5 --runs 5 --frames 16
  step aggressor_accuracy_640x480 70 "$bundle/roma-bench" --accuracy --scene "$lv/aggressor.glb" \
    --camera "$(sed -n 1p "$lv/aggressor.cameras")" --ao-radius 1.5 --cascades auto --no-baselines --runs 3 \
    --size 640x480 --csv "$out/aggressor_accuracy_640x480.csv"
  step room_accuracy 30 "$bundle/roma-bench" --accuracy --scene builtin:cornell --ao-radius 0.5 --runs 3 \
    --csv "$out/room_accuracy.csv"
  step room_direct_accuracy 30 "$bundle/roma-bench" --accuracy --effect direct --scene builtin:cornell --runs 3 \
    --csv "$out/room_direct_accuracy.csv"
  step dragon_ao_1080p 30 "$bundle/roma-render" --scene scenes/dragon_res2.glb --tracer roma --effects ao \
    --size 1920x1080 --spp 1 --frames 8 --out "$out/tmp/dragon_ao" --stats "$out/dragon_ao_1080p.json"
  step dragon_ao_1080p_surfaces 10 "$bundle/roma-render" --scene scenes/dragon_res2.glb --tracer roma --effects ao \
    --size 1920x1080 --spp 1 --frames 8 --ray-start surfaces --out "$out/tmp/dragon_ao_surfaces" \
    --stats "$out/dragon_ao_1080p_surfaces.json"
  step room_lights 30 "$bundle/roma-render" --scene builtin:cornell --tracer roma --effects lights \
    --size 1280x720 --frames 4 --out "$out/tmp/room_lights" --stats "$out/room_lights.json"
  # The failing tests' logs beside the summary (the rest of tmp is left out of what comes back).
  grep -v ' rc 0$' "$out/tests.txt" | while read -r t _; do cp "$out/tmp/$t.log" "$out/failed_$t.log" 2>/dev/null; done
  rm -rf "$out/tmp"
  ;;
tests) # (inside run) the C tests, 8 at a time, each at most 100 s, validation on as in ctest
  # (a program that ctest runs in parts runs whole here)
  out=$2
  export ROMA_VALIDATION=1 ROMA_SCENES_DIR=$PWD/scenes ROMA_LEVELS_DIR=$PWD/$bundle/levels
  ls "$bundle/tests" | grep -v '^fuzz_trace$' | xargs -P 8 -I{} sh -c \
    'mkdir -p "$1/tmp/$2" && ROMA_TEST_TMPDIR="$1/tmp/$2" timeout 100 "$0/tests/$2" > "$1/tmp/$2.log" 2>&1;
     echo "$2 rc $?"' "$bundle" "$out" {} | sort
  ;;
*)
  sed -n '2,15p' "$0" >&2
  exit 2
  ;;
esac
