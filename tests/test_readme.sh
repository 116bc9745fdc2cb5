#!/usr/bin/env bash
# Every tool command of the README and of the guides it links (docs/tools.md, viewer.md,
# using.md) runs as written, so they cannot drift from the tools: each indented line that
# starts with build/apps/ is run in a scratch folder where
# build/ is this build and scenes/ the repository's, made small by options appended after
# it (a later option wins): roma-render 24x18 pixels, 1 sample; roma-viewer headless, one
# frame. `make` lines (the set-up commands) are what CI runs anyway. The README itself stays
# an entry page: at most 150 lines, its two set-up commands `make run` and `make test`.
# Usage: test_readme.sh BUILD_DIR SCENES_DIR SCRATCH_DIR README [GUIDE...]
set -u
build=$(realpath "$1")
scenes=$(realpath "$2")
dir=$3
shift 3
documents=()
for f in "$@"; do documents+=("$(realpath "$f")"); done
readme=${documents[0]}
rm -rf "$dir"
mkdir -p "$dir"
ln -s "$build" "$dir/build"
ln -s "$scenes" "$dir/scenes"
cd "$dir" || exit 1

failures=0
count=0
lines=$(wc -l <"$readme")
if [ "$lines" -gt 150 ]; then
  echo "FAIL: $readme has $lines lines; the entry page keeps to 150 (details go to docs/)" >&2
  failures=$((failures + 1))
fi
for command in "make run" "make test"; do
  if ! grep -qx "    $command" "$readme"; then
    echo "FAIL: $readme does not give the set-up command '$command'" >&2
    failures=$((failures + 1))
  fi
done
while IFS= read -r line; do
  count=$((count + 1))
  read -r -a words <<<"$line"
  tool=$(basename "${words[0]}")
  case "$tool" in
    roma-render) extra=(--size 24x18 --spp 1 --quiet) ;;
    roma-viewer) extra=(--headless --frames 1 --size 32x24) ;;
    example-engine) extra=(--frames 2) ;;
    *) extra=() ;;
  esac
  [ "${words[1]:-}" = "--help" ] && extra=()
  # Sanitizer builds: the driver preloaded, as test_cli does (tests/CMakeLists.txt says why).
  preload=()
  [ -n "${ROMA_TOOL_PRELOAD:-}" ] && preload=(env "LD_PRELOAD=$ROMA_TOOL_PRELOAD")
  if ! "${preload[@]}" "${words[@]}" "${extra[@]}" >"cmd$count.out" 2>&1; then
    echo "FAIL: README command failed: $line" >&2
    tail -5 "cmd$count.out" >&2
    failures=$((failures + 1))
  fi
done < <(sed -n 's/^    \(build\/apps\/[^#]*\).*/\1/p' "${documents[@]}" | sed 's/[[:space:]]*$//')

if [ "$count" -lt 8 ]; then
  echo "FAIL: only $count tool commands found in ${documents[*]}" >&2
  failures=$((failures + 1))
fi
if [ "$failures" -ne 0 ]; then
  echo "test_readme: $failures failures, $count commands (outputs in $dir)" >&2
  exit 1
fi
echo "test_readme: all $count commands of ${#documents[@]} documents ran"
