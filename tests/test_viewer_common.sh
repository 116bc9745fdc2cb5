#!/usr/bin/env bash
# What every part of test_viewer shares (sourced: test_viewer_PART.sh VIEWER RENDER COMPARE
# SCENES_DIR SCRATCH_DIR): the tools (LD_PRELOADed under the sanitizers), the checks that fail
# on a missing or non-numeric value, the room's camera, and the ending that fails the part on
# any failed check or sanitizer report. The parts run as separate tests (ctest -R test_viewer),
# each in its own scratch folder, so that ctest -j runs them side by side and a slow day does
# not push one test past its timeout.
set -u
viewer=$1
render=$2
compare=$3
scenes=$4
dir=$5
failures=0
rm -rf "$dir"
mkdir -p "$dir"

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
# outputs FILE...: true when every file is there; each missing one is a failure, so that a tool
# that exits 0 without writing its output cannot skip the checks that read it.
outputs() {
  local missing=0 f
  for f in "$@"; do
    [ -f "$f" ] || { fail "missing output $f"; missing=1; }
  done
  return $missing
}
metric() {
  awk -v k="$2" '$1 == k { print $2; found = 1 } END { exit !found }' "$1"
}
json() { # FILE KEY: a top-level value of a stats file
  python3 -c 'import json, sys; v = json.load(open(sys.argv[1]))[sys.argv[2]]; print(" ".join(v) if isinstance(v, list) else v)' "$1" "$2"
}
# headless NAME WHAT ARGS...: a headless run with validation, its output in $dir/NAME.out,
# shown and counted as a failure ("roma-viewer WHAT failed") when it exits non-zero.
headless() {
  local name=$1 what=$2
  shift 2
  "$viewer" --headless --validation "$@" >"$dir/$name.out" 2>&1 || { cat "$dir/$name.out" >&2; fail "roma-viewer $what failed"; }
}
# numbers VALUE...: every value a decimal number (a missing or empty metric is not: awk would
# compare it as a string, and "" <= 0.037 holds).
numbers() {
  local v
  for v in "$@"; do
    [[ $v =~ ^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] || return 1
  done
}
# below VALUE BOUND: VALUE <= BOUND, both numbers
below() {
  numbers "$1" "$2" && awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'
}
# The checks themselves: a missing, empty or non-numeric value fails them.
below "" 0.5 && fail "below passes an empty value"
below "none" 0.5 && fail "below passes a word"
below 0.4 "" && fail "below passes an empty bound"
numbers 0.1 "" && fail "numbers passes an empty value"
(outputs "$dir/no such file" 2>/dev/null) && fail "outputs passes a missing file"
# compare_checked ARGS...: roma-compare, a failure when it does not exit 0
compare_checked() {
  "$compare" "$@" || fail "roma-compare $* exited $?"
}
if [ -n "${ROMA_TOOL_PRELOAD:-}" ]; then
  for tool in viewer render compare; do
    printf '#!/bin/sh\nLD_PRELOAD="%s" exec "%s" "$@"\n' "$ROMA_TOOL_PRELOAD" "${!tool}" >"$dir/$tool-preloaded"
    chmod +x "$dir/$tool-preloaded"
    eval "$tool=\$dir/\$tool-preloaded"
  done
fi

# The room's camera of the AO, direct-light, GI and view checks.
cam="0,1,1.9,0,0.9,0,60"

# finish NAME: sanitizer reports in the outputs fail the part; the count of failed checks decides.
finish() {
  if reports=$(grep -l -E 'ERROR: (Address|Leak)Sanitizer|runtime error:' "$dir"/*.out "$dir"/*.err 2>/dev/null); then
    fail "sanitizer reports in: $(echo $reports)"
  fi
  if [ "$failures" -ne 0 ]; then
    echo "test_viewer $1: $failures check(s) failed (outputs in $dir)" >&2
    exit 1
  fi
  echo "test_viewer $1: all checks passed"
}
