# Sourced by the roma-bench test scripts (test_bench_*.sh ROMA_BENCH SCRATCH_DIR): checks the
# arguments, empties the scratch folder, defines fail() (counted in $failures) and finish, and
# bench_run, the command that runs roma-bench. Under the sanitizers the tool runs with the ASan
# runtime preloaded; gnuplot, which it starts, gets a clean environment (a shim first on PATH).
if [ $# -ne 2 ]; then
  echo "usage: $0 ROMA_BENCH SCRATCH_DIR" >&2
  exit 2
fi
bench=$1
dir=$2
failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
finish() { # NAME: the verdict and the exit status
  if [ "$failures" -ne 0 ]; then
    echo "$1: $failures failure(s)" >&2
    exit 1
  fi
  echo "$1: passed"
}
check_png() { # FILE MIN_BYTES: a PNG's signature, and more bytes than a plot with nothing drawn
  if [ ! -f "$1" ]; then
    fail "no $(basename "$1")"
    return
  fi
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "$(basename "$1") is not a PNG"
  local size
  size=$(stat -c %s "$1")
  [ "$size" -gt "$2" ] || fail "$(basename "$1") has $size bytes: nothing drawn?"
}
rm -rf "$dir" && mkdir -p "$dir"
bench_run=("$bench")
if [ -n "${ROMA_TOOL_PRELOAD:-}" ]; then
  bench_run=(env "LD_PRELOAD=$ROMA_TOOL_PRELOAD" "$bench")
  mkdir -p "$dir/bin"
  printf '#!/bin/sh\nexec env -u LD_PRELOAD "%s" "$@"\n' "$(command -v gnuplot)" >"$dir/bin/gnuplot"
  chmod +x "$dir/bin/gnuplot"
  export PATH="$dir/bin:$PATH"
fi
