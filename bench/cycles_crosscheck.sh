#!/usr/bin/env bash
# cycles_crosscheck.sh: lucent's volpath reference against Blender Cycles on the bunnies of bench/cycles/: the
# index-matched grey medium, the opaque diffuse bunny and the dense high-albedo medium (docs/references.md,
# "Cross-check with Blender Cycles"). Needs Blender (Debian: apt-get install blender python3-numpy); not part of CI.
#   bash bench/cycles_crosscheck.sh [OUT_DIR] [LUCENT_SPP] [CYCLES_SPP] [THREADS]
# Environment: CASES (default "medium diffuse"; also "dense" and "box_dense": bench/cycles/bunny_<case>.json, else
# bench/cycles/<case>.json), JUMPS (empty: one lucent render with volpath's
# default, OUT_DIR/<case>_lucent.exr; "on off": one render per setting of --sphere-jumps,
# OUT_DIR/<case>_lucent_jumps<on|off>.exr), WIDTH and HEIGHT (both renderers at that size instead of the scene
# file's), BOUNCES (Cycles' bounce limit, default 1024), CYCLES_PATTERN (Cycles' sampling pattern: SOBOL or
# PROGRESSIVE_MULTI_JITTER, Blender 3.4's default; the dense case needs SOBOL, docs/references.md), LUCENT, BLENDER
# (the programs).
# Per case: the lucent render(s) (--jitter, with the standard-error image), two Cycles renders with seeds 1 and 2,
# and the comparison of every lucent render with the Cycles pair (OUT_DIR/<case>.json: means, the mean difference
# against the combined standard error, RMSE against noise, efficiencies; a PNG OUT_DIR/<case>.png with one row per
# lucent render: lucent | Cycles | difference in units of the combined noise).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/cycles}
lucent_spp=${2:-256}
cycles_spp=${3:-256}
threads=${4:-2}
lucent=${LUCENT:-build/lucent}
blender=${BLENDER:-blender}
size_lucent=() size_cycles=()
if [[ -n ${WIDTH:-} || -n ${HEIGHT:-} ]]; then
  [[ -n ${WIDTH:-} && -n ${HEIGHT:-} ]] || { echo "cycles_crosscheck.sh: give both WIDTH and HEIGHT" >&2; exit 2; }
  size_lucent=(--set "render.width=$WIDTH" --set "render.height=$HEIGHT")
  size_cycles=(--width "$WIDTH" --height "$HEIGHT")
fi
mkdir -p "$out"
for case in ${CASES:-medium diffuse}; do
  scene=bench/cycles/bunny_$case.json
  [[ -f $scene ]] || scene=bench/cycles/$case.json
  lucent_images=()
  for jumps in ${JUMPS:-default}; do
    if [[ $jumps == default ]]; then
      image=$out/${case}_lucent.exr jump_option=()
    else
      image=$out/${case}_lucent_jumps$jumps.exr jump_option=(--sphere-jumps "$jumps")
    fi
    nice "$lucent" reference "$scene" --integrator volpath --jitter --spp "$lucent_spp" --threads "$threads" \
      "${jump_option[@]}" "${size_lucent[@]}" -o "$image" 2>&1 | tr '\r' '\n' | tail -1
    lucent_images+=("$image")
  done
  for seed in 1 2; do
    nice "$blender" -b --python-exit-code 1 --python bench/cycles_crosscheck.py -- render "$scene" \
      "$out/${case}_cycles$seed.exr" --spp "$cycles_spp" --seed "$seed" --threads "$threads" "${size_cycles[@]}" \
      ${BOUNCES:+--bounces $BOUNCES} ${CYCLES_PATTERN:+--sampling-pattern $CYCLES_PATTERN} | grep '^cycles_crosscheck'
  done
  "$blender" -b --python-exit-code 1 --python bench/cycles_crosscheck.py -- compare "${lucent_images[@]}" \
    "$out/${case}_cycles1.exr" "$out/${case}_cycles2.exr" --json "$out/$case.json" --png "$out/$case.png" |
    sed -n '/^{/,/^}/p;/^cycles_crosscheck/p'
done
