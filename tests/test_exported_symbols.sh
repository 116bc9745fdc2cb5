#!/usr/bin/env bash
# The symbols a shared library of libroma exports equal the functions its public headers
# declare with ROMA_API: no internal function leaks out, no public one is missing.
# Usage: test_exported_symbols.sh LIBRARY HEADER...
set -euo pipefail
lib=$1
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Declared: the identifier before the first "(" of every ROMA_API declaration (one
# declaration may span lines; its name is always on the ROMA_API line).
grep -h '^ROMA_API ' "$@" | sed -E 's/\(.*//; s/.*[^A-Za-z0-9_]([A-Za-z_][A-Za-z0-9_]*)$/\1/' | sort -u >"$tmp/declared"
# Exported: defined, global, dynamic symbols (functions and data).
nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBRVWGS]$/ { print $3 }' | sed 's/@.*//' | sort -u >"$tmp/exported"

status=0
if ! [ -s "$tmp/declared" ]; then
  echo "no ROMA_API declaration found in: $*" >&2
  exit 1
fi
extra=$(comm -13 "$tmp/declared" "$tmp/exported")
missing=$(comm -23 "$tmp/declared" "$tmp/exported")
if [ -n "$extra" ]; then
  echo "$(basename "$lib") exports symbols no public header declares:" >&2
  echo "$extra" | sed 's/^/  /' >&2
  status=1
fi
if [ -n "$missing" ]; then
  echo "$(basename "$lib") lacks functions its public headers declare:" >&2
  echo "$missing" | sed 's/^/  /' >&2
  status=1
fi
echo "$(basename "$lib"): $(wc -l <"$tmp/exported") exported symbols, $(wc -l <"$tmp/declared") declared"
exit $status
