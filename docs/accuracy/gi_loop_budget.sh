#!/usr/bin/env bash
# Why test_ao_effect's GI bias differed between lavapipe and an H100 at 256 samples (+3.0%
# against +6.2%): the public GI effect of the default room at 64 x 48 (roma-render's default
# route, RES 128), N bounce rays per pixel in one record, against Embree at 1024 samples. Each
# N twice: with the passes' split across dispatches (the default on lavapipe; a GPU runs one
# dispatch and needs none) and with the split turned off (ROMA_LOOP_PLAN=4294967294: one
# dispatch, as before the split), so that llvmpipe's 65,535 loop iterations per invocation
# cut the loop short. Last column: the pixels whose GI differs between the two. Usage, from
# the repository root after a build: bash docs/accuracy/gi_loop_budget.sh [BUILD_DIR] [OUT_DIR].
# About a minute on 2 cores with lavapipe.
set -euo pipefail
build=${1:-build}
out=${2:-out/gi_loop_budget}
mkdir -p "$out"
stats() { "$build/apps/roma-compare" "$1" "$out/ref/gi.pfm" --mask "$out/ref/coverage.pfm"; }
"$build/apps/roma-render" --scene builtin:cornell --effects gi --size 64x48 --quiet --tracer embree --spp 1024 \
  --out "$out/ref" >/dev/null
echo "| samples in one record | dispatches | MAE | mean ROMA | mean Embree | relative bias | pixels that differ |"
echo "|---|---|---|---|---|---|---|"
for spp in 64 128 256 512 1024; do
  env -u ROMA_LOOP_PLAN "$build/apps/roma-render" --scene builtin:cornell --effects gi --size 64x48 --quiet \
    --tracer roma --spp "$spp" --frames 1 --res 128 --out "$out/split-$spp" >/dev/null
  ROMA_LOOP_PLAN=4294967294 "$build/apps/roma-render" --scene builtin:cornell --effects gi --size 64x48 --quiet \
    --tracer roma --spp "$spp" --frames 1 --res 128 --out "$out/one-$spp" >/dev/null 2>&1
  differ=$("$build/apps/roma-compare" "$out/split-$spp/gi.pfm" "$out/one-$spp/gi.pfm" --mask "$out/ref/coverage.pfm" \
    --tolerance 0.000001 | awk '$1 == "pixels" { n = $2 } $1 ~ /^above_/ { f = $2 } END { printf "%d of %d", f * n + 0.5, n }')
  for kind in split one; do
    stats "$out/$kind-$spp/gi.pfm" | awk -v s="$spp" -v k="$kind" -v d="$differ" '$1 == "mean_abs" { m = $2 }
      $1 == "mean_a" { a = $2 } $1 == "mean_b" { b = $2 }
      END { printf "| %s | %s | %.4f | %.4f | %.4f | %+.1f%% | %s |\n", s,
            k == "split" ? "split (the default)" : "one (ROMA_LOOP_PLAN=4294967294)", m, a, b, 100 * (a - b) / b, d }'
  done
done
