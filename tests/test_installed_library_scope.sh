#!/usr/bin/env bash
# The installed library holds libroma and nothing of the accuracy study's methods (src/study/):
# none of their shaders among its embedded SPIR-V (their names are the table's keys) and none of
# their functions among its symbols, hidden ones included; one of its own shaders is there, so
# that the search itself is shown to work.
# Usage: test_installed_library_scope.sh LIBRARY STUDY_SHADER...   (e.g. study/ao_naadf.comp)
set -euo pipefail
lib=$1
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A module's name may follow other bytes in the string table: take the name at a string's end.
strings "$lib" | grep -oE '[a-z0-9_]+\.(comp|vert|frag)$' | sort -u >"$tmp/modules"
nm "$lib" 2>/dev/null | awk '{ print $NF }' | sort -u >"$tmp/symbols"
status=0
grep -qx 'ao_images.comp' "$tmp/modules" || { echo "FAIL: libroma's own ao_images.comp not found in $lib" >&2; status=1; }
for src in "$@"; do
  name=$(basename "$src")
  if grep -qx "$name" "$tmp/modules"; then
    echo "FAIL: $lib embeds the study's $name" >&2
    status=1
  fi
done
found=$(grep -E '^roma_(naadf|distance_field|effect_render|ao_pass|gbuffer|denoiser|pixel_pass|rsm_views|gbuffer_list|study)_' \
        "$tmp/symbols" || true)
if [ -n "$found" ]; then
  echo "FAIL: $lib holds functions of the study:" >&2
  echo "$found" | sed 's/^/  /' >&2
  status=1
fi
echo "$(basename "$lib"): $(wc -l <"$tmp/modules") embedded shaders, none of the $# study shaders"
exit $status
