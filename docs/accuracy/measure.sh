#!/usr/bin/env bash
# Converged accuracy of ROMA against the Embree reference, as reported in
# docs/accuracy.md. Both sides trace the same 1024 samples per pixel (ROMA:
# 32 per frame over 32 frames, each frame with new grid and direction jitter;
# the reference: 1024 at once) at 160x120; errors are over the pixels that see
# geometry. Usage, from the repository root after a build:
#     bash docs/accuracy/measure.sh [BUILD_DIR] [OUT_DIR]
# Writes OUT_DIR (default out/accuracy) and prints the tables. About 5 minutes
# on 2 cores with lavapipe.
set -euo pipefail
build=${1:-build}
out=${2:-out/accuracy}
scenes_dir=${ROMA_SCENES_DIR:-scenes}
render=$build/apps/roma-render
compare=$build/apps/roma-compare
mkdir -p "$out"
size=160x120

# metric FILE NAME
metric() { awk -v n="$2" '$1 == n { print $2 }' "$1"; }

# ref NAME SCENE EFFECTS [ARGS...]: the reference at 1024 samples, once per scene.
ref() {
  local name=$1 scene=$2 effects=$3
  shift 3
  [ -f "$out/ref_$name/coverage.pfm" ] && [ -f "$out/ref_$name/.effects_$effects" ] && return 0
  "$render" --scene "$scene" --tracer embree --effects "$effects" --size $size --spp 1024 --quiet \
    --out "$out/ref_$name" "$@" >/dev/null
  touch "$out/ref_$name/.effects_$effects"
}

# roma NAME LABEL SCENE EFFECTS [ARGS...]: the internal renderer, whose passes docs/accuracy.md
# measures (roma-render's public-pass route gives the same images within 1e-6: test_cli).
roma() {
  local name=$1 label=$2 scene=$3 effects=$4
  shift 4
  "$render" --scene "$scene" --tracer roma --route internal --effects "$effects" --size $size --spp 32 --frames 32 \
    --quiet \
    --out "$out/roma_${name}_$label" "$@" >/dev/null
}

# row NAME LABEL EFFECT: "mean_abs mean_roma mean_ref relative_bias relative_mae"
row() {
  local name=$1 label=$2 effect=$3
  "$compare" "$out/roma_${name}_$label/$effect.pfm" "$out/ref_$name/$effect.pfm" \
    --mask "$out/ref_$name/coverage.pfm" --heatmap "$out/${name}_${label}_${effect}_error.png" \
    --side-by-side "$out/${name}_${label}_${effect}.png" >"$out/cmp.txt"
  local mae a b
  mae=$(metric "$out/cmp.txt" mean_abs)
  a=$(metric "$out/cmp.txt" mean_a)
  b=$(metric "$out/cmp.txt" mean_b)
  awk -v m="$mae" -v a="$a" -v b="$b" 'BEGIN { printf "%.4f  %.4f  %.4f  %+.3f  %.3f\n", m, a, b, (a - b) / b, m / b }'
}

echo "== Ambient occlusion, RES 128, A = 4 (MAE target <= 0.05), rays' start walked (default) or blind: MAE, mean ROMA, mean reference, relative bias, relative MAE"
for spec in "cornell|builtin:cornell|--ao-radius 0.5" "bunny|$scenes_dir/bunny.glb|--ao-radius inf --camera 0.172454447,0.265031695,0.239383832,-0.0168405008,0.110154003,-0.0015369989,45" \
            "engine|$scenes_dir/2CylinderEngine.glb|--ao-radius inf"; do
  IFS='|' read -r name scene extra <<<"$spec"
  # shellcheck disable=SC2086
  ref "$name" "$scene" ao $extra
  for skip in 0 1 1.6 2; do
    # shellcheck disable=SC2086
    roma "$name" "skip$skip" "$scene" ao --ao-skip $skip $extra
    printf "%-8s walk  ao-skip %-4s " "$name" "$skip"
    row "$name" "skip$skip" ao
  done
  # The rule before the walk: the skipped start not looked at.
  # shellcheck disable=SC2086
  roma "$name" "blind" "$scene" ao --ray-start blind $extra
  printf "%-8s blind ao-skip %-4s " "$name" 1.6
  row "$name" "blind" ao
  # The baseline: every ray walked exactly through the BOM (no ROMA maps).
  # shellcheck disable=SC2086
  roma "$name" "voxel-dda" "$scene" ao --ao-method voxel-dda $extra
  printf "%-8s voxel-dda     %-4s " "$name" "-"
  row "$name" "voxel-dda" ao
  # The origin offset at the default skip.
  # shellcheck disable=SC2086
  roma "$name" "offset1.75" "$scene" ao --offset 1.75 $extra
  printf "%-8s walk  offset  %-4s " "$name" 1.75
  row "$name" "offset1.75" ao
done

echo "== Direct light (area + punctual), RES 128, A = 8, 8 steps, skip 1: same columns"
for spec in "cornell|builtin:cornell" "blinds|builtin:blinds" "plates|builtin:plates"; do
  IFS='|' read -r name scene <<<"$spec"
  ref "${name}_direct" "$scene" direct
  roma "${name}_direct" default "$scene" direct
  printf "%-8s %-12s " "$name" direct
  row "${name}_direct" default direct
done

echo "== One-bounce GI, RES 128, A = 4: same columns"
for spec in "cornell|builtin:cornell" "cornell_spot|builtin:cornell_spot" "blinds|builtin:blinds"; do
  IFS='|' read -r name scene <<<"$spec"
  ref "${name}_gi" "$scene" gi
  roma "${name}_gi" default "$scene" gi
  printf "%-12s %-8s " "$name" gi
  row "${name}_gi" default gi
done
