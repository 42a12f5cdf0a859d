#!/usr/bin/env bash
# The diffusion models on the bunny against volpath: marble, potato, skim milk, white grapefruit juice and
# strawberry shampoo (or the marble bunny at 10 mm, 100 mm and 1 m with --scales), radiosity-maps at 16 frames with
# the settings of bench/accuracy.json, each model against one volpath reference per scene. Prints a markdown table:
# RMSE (noise-corrected), the reference's noise, mean error and the median frame time.
# Usage: bench/model_bunny_table.sh [LUCENT] [SPP] [--scales]   (docs/models/tabulated.md)
set -euo pipefail
lucent=${1:-build/lucent}
spp=${2:-384}
mode=${3:-materials}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
S=(--set render.width=160 --set render.height=120 --set method.specular=false --set 'objects.1.albedo=[0,0,0]'
   --set 'render.background=[0,0,0]' --set method.map_size=256 --set method.light_map_size=1024)
if [ "$mode" = "--scales" ]; then
  cases=("10mm:Marble:5" "100mm:Marble:50" "1m:Marble:500")
else
  cases=("marble:Marble:25" "potato:Potato:25" "skimmilk:Skimmilk:25" "grapefruit:White Grapefruit Juice:25"
         "shampoo:Strawberry Shampoo:25")
fi
echo "| case | model | RMSE vs volpath (noise-corrected) | volpath noise | mean error vs volpath | frame ms |"
echo "|---|---|---|---|---|---|"
for spec in "${cases[@]}"; do
  IFS=: read -r name material scale <<< "$spec"
  M=(--set "scale_mm=$scale")
  "$lucent" reference scenes/bunny_marble.json "${S[@]}" "${M[@]}" --set "objects.0.material={\"preset\": \"$material\"}" \
    --integrator volpath --spp "$spp" -q -o "$out/volpath.exr"
  for model in tabulated standard better-dipole directional; do
    "$lucent" render scenes/bunny_marble.json "${S[@]}" "${M[@]}" \
      --set "objects.0.material={\"preset\": \"$material\", \"model\": \"$model\"}" --frames 16 -q \
      -o "$out/$name.png" --exr "$out/o.exr" --timings-json "$out/o.json"
    "$lucent" compare "$out/o.exr" "$out/volpath.exr" --json | python3 -c "
import json, sys
j = json.load(sys.stdin)['linear']; n = j['reference_noise_rms'] * 3 ** 0.5
t = sorted(f['total_ms'] for f in json.load(open('$out/o.json'))['frames'])
print('| $name | $model | %.4f (%.4f) | %.4f | %+.4f +- %.4f | %.2f |' % (j['rmse_rgb'], max(0, j['rmse_rgb'] ** 2 - n ** 2) ** 0.5,
      n, j['mean_error'], j['mean_error_se'], t[len(t) // 2]))"
  done
done
