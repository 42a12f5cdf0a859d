#!/usr/bin/env bash
# texture_space_scale.sh: the shape of Chang et al. 2008, Figs. 13-14: texture-space-is against the hybrid as the
# object grows (bunny 10, 20, 30 mm wide): linear RMSE against the bssrdf reference of the same scene (standard
# dipole, no specular, 160 x 120) and GPU time of one frame, from `lucent render --timings-json`.
#   bash bench/texture_space_scale.sh [LUCENT] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
spp=${2:-1024}
out=out/bench/tsis_scale
mkdir -p "$out"
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "| bunny width | method | N | linear RMSE (noise-corrected) | mean error | frame ms |"
echo "|---|---|---|---|---|---|"
for width in 10 20 30; do
  scale=$(python3 -c "print($width / 2.0)")  # the bunny is 2 scene units wide
  S=(--set render.width=160 --set render.height=120 --set "scale_mm=$scale"
     --set 'objects.0.material={"preset": "Marble", "model": "standard"}')
  "$lucent" reference scenes/bunny_texture_space_is.json "${S[@]}" --integrator bssrdf --spp "$spp" -q \
    -o "$out/reference_$width.exr"
  for method in texture-space-is hybrid; do
    for n in 400 2500; do
      stem="$out/${method}_${width}_$n"
      "$lucent" render scenes/bunny_texture_space_is.json "${S[@]}" \
        --set "method={\"name\": \"$method\", \"N\": $n, \"specular\": false}" --frames 2 -q -o "$stem.png" \
        --exr "$stem.exr" --timings-json "$stem.json"
      "$lucent" compare "$stem.exr" "$out/reference_$width.exr" --json | python3 -c "
import json, sys
j = json.load(sys.stdin)['linear']
t = json.load(open('$stem.json'))['frames'][-1]['total_ms']
noise = j['reference_noise_rms'] * 3 ** 0.5
corrected = max(0.0, j['rmse_rgb'] ** 2 - noise ** 2) ** 0.5
print(f\"| $width mm | $method | $n | {j['rmse_rgb']:.4f} ({corrected:.4f}) | {j['mean_error']:+.4f} | {t:.0f} |\")"
    done
  done
done
