# Sourced by the docs/bench/cascades_*.sh scripts (BUILD_DIR as their first argument, default
# build): the tools, the shared game levels (ROMA_LEVELS_DIR, default ../shared/scenes/levels),
# a scratch folder removed on exit, and
#   ao_args LEVEL C          sets `common`: AO of radius 1.5 m at LEVEL's camera C, 160x120
#   ao_error ROMA REF [ARG]  "MAE bias" of ROMA/ao.pfm against REF/ao.pfm over REF's covered
#                            pixels (ARG: more roma-compare options)
set -euo pipefail
build=${1:-build}
render=$build/apps/roma-render
compare=$build/apps/roma-compare
levels=${ROMA_LEVELS_DIR:-../shared/scenes/levels}
level_names=(oa_dm4 aggressor ctf_compromise)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ao_args() {
  common=(--scene "$levels/$1.glb" --camera "$(sed -n "${2}p" "$levels/$1.cameras")" --effects ao --ao-radius 1.5
          --size 160x120 --quiet)
}
ao_error() {
  local roma=$1 ref=$2
  shift 2
  "$compare" "$roma/ao.pfm" "$ref/ao.pfm" --mask "$ref/coverage.pfm" "$@" |
    awk '$1 == "mean_abs" { m = $2 } $1 == "bias" { b = $2 } END { printf "%.4f %+.4f", m, b }'
}
