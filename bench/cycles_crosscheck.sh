#!/usr/bin/env bash
# cycles_crosscheck.sh: lucent's volpath reference against Blender Cycles on the index-matched medium bunny and
# the opaque diffuse bunny of bench/cycles/ (docs/references.md, "Cross-check with Blender Cycles"). Needs
# Blender (Debian: apt-get install blender python3-numpy); not part of CI.
#   bash bench/cycles_crosscheck.sh [OUT_DIR] [LUCENT_SPP] [CYCLES_SPP] [THREADS]
# Per case: one lucent render (--jitter, with its standard-error image), two Cycles renders with seeds 1 and 2,
# and the comparison (OUT_DIR/<case>.json, a side-by-side PNG OUT_DIR/<case>.png: lucent | Cycles | difference in
# units of the combined noise).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/cycles}
lucent_spp=${2:-256}
cycles_spp=${3:-256}
threads=${4:-2}
lucent=${LUCENT:-build/lucent}
blender=${BLENDER:-blender}
mkdir -p "$out"
for case in ${CASES:-medium diffuse}; do
  scene=bench/cycles/bunny_$case.json
  nice "$lucent" reference "$scene" --integrator volpath --jitter --spp "$lucent_spp" --threads "$threads" \
    -o "$out/${case}_lucent.exr" 2>&1 | tr '\r' '\n' | tail -1
  for seed in 1 2; do
    nice "$blender" -b --python bench/cycles_crosscheck.py -- render "$scene" "$out/${case}_cycles$seed.exr" \
      --spp "$cycles_spp" --seed "$seed" --threads "$threads" ${BOUNCES:+--bounces $BOUNCES} | grep '^cycles_crosscheck'
  done
  "$blender" -b --python bench/cycles_crosscheck.py -- compare "$out/${case}_lucent.exr" "$out/${case}_cycles1.exr" \
    "$out/${case}_cycles2.exr" --json "$out/$case.json" --png "$out/$case.png" | sed -n '/^{/,/^}/p;/^cycles_crosscheck/p'
done
