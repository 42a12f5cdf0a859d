#!/usr/bin/env bash
# texture_space_equal_time.sh: the texture-space methods against radiosity-maps and per-pixel at equal GPU time on
# the five-material bunny of docs/accuracy.md (160 x 120, directional dipole, no specular, black floor and
# background), each method accumulating frames until its GPU time reaches the budget; linear RMSE against the
# bssrdf reference of the same scene (the method's own error).
#   bash bench/texture_space_equal_time.sh [LUCENT] [BUDGET_MS] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
budget=${2:-3000}
spp=${3:-4096}
out=out/bench/tsis_equal_time
mkdir -p "$out"
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "| material | method | frames | GPU ms | linear RMSE vs bssrdf (noise-corrected) | mean error |"
echo "|---|---|---|---|---|---|"
base=(--set render.width=160 --set render.height=120 --set 'objects.1.albedo=[0,0,0]' --set 'render.background=[0,0,0]')
declare -A method_sets=(
  [radiosity-maps]='{"name": "radiosity-maps", "specular": false, "map_size": 256, "light_map_size": 1024}'
  [per-pixel]='{"name": "per-pixel", "specular": false, "light_map_size": 1024}'
  [texture-space-is]='{"name": "texture-space-is", "specular": false, "N": 400, "atlas_size": 1024, "light_map_size": 1024}'
  [hybrid]='{"name": "hybrid", "specular": false, "N": 400, "atlas_size": 1024, "light_map_size": 1024}')
for material in Marble Potato Skimmilk "White Grapefruit Juice" "Strawberry Shampoo"; do
  stem=$(echo "$material" | tr -d ' ' | tr 'A-Z' 'a-z')
  S=("${base[@]}" --set "objects.0.material={\"preset\": \"$material\"}")
  "$lucent" reference scenes/bunny_marble.json "${S[@]}" --integrator bssrdf --spp "$spp" -q -o "$out/ref_$stem.exr"
  for method in radiosity-maps per-pixel texture-space-is hybrid; do
    # One frame to learn the method's cost (frame 1 pays for compiles), then as many frames as fit the budget.
    "$lucent" render scenes/bunny_marble.json "${S[@]}" --set "method=${method_sets[$method]}" --frames 2 -q \
      -o "$out/probe.png" --timings-json "$out/probe.json"
    frames=$(python3 -c "import json; f=json.load(open('$out/probe.json'))['frames'][-1]['total_ms']; print(max(1, int($budget / max(f, 1e-3))))")
    img="$out/${stem}_$method"
    "$lucent" render scenes/bunny_marble.json "${S[@]}" --set "method=${method_sets[$method]}" --frames "$frames" -q \
      -o "$img.png" --exr "$img.exr" --timings-json "$img.json"
    "$lucent" compare "$img.exr" "$out/ref_$stem.exr" --json | python3 -c "
import json, sys
j = json.load(sys.stdin)['linear']
ms = sum(f['total_ms'] for f in json.load(open('$img.json'))['frames'])
noise = j['reference_noise_rms'] * 3 ** 0.5
corrected = max(0.0, j['rmse_rgb'] ** 2 - noise ** 2) ** 0.5
print(f\"| $material | $method | $frames | {ms:.0f} | {j['rmse_rgb']:.4f} ({corrected:.4f}) | {j['mean_error']:+.4f} |\")"
  done
done
