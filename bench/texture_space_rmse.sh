#!/usr/bin/env bash
# texture_space_rmse.sh: the shape of Chang et al. 2008, Fig. 7: RMSE against the number of samples for
# texture-space-is and the hybrid, one frame each, against the bssrdf reference of the same model (the standard
# dipole, whose radial profile both methods use exactly), on the bunny at 160 x 120 without specular.
#   bash bench/texture_space_rmse.sh [LUCENT] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
spp=${2:-256}
out=out/bench/tsis_rmse
mkdir -p "$out"
S=(--set render.width=160 --set render.height=120 --set 'objects.0.material={"preset": "Marble", "model": "standard"}')
date -u +"date: %Y-%m-%d %H:%M UTC"
"$lucent" reference scenes/bunny_texture_space_is.json "${S[@]}" --integrator bssrdf --spp "$spp" -q \
  -o "$out/reference.exr"
echo "| method | N | frames | linear RMSE vs bssrdf (reference noise; noise-corrected) | mean error |"
echo "|---|---|---|---|---|"
for method in texture-space-is hybrid; do
  for n in 49 400 1600 2500; do
    exr="$out/${method}_$n.exr"
    "$lucent" render scenes/bunny_texture_space_is.json "${S[@]}" --set "method={\"name\": \"$method\", \"N\": $n, \"specular\": false}" \
      --frames 1 -q -o "$out/${method}_$n.png" --exr "$exr"
    "$lucent" compare "$exr" "$out/reference.exr" --json | python3 -c "
import json, sys
j = json.load(sys.stdin)['linear']
noise = j['reference_noise_rms'] * 3 ** 0.5
corrected = max(0.0, j['rmse_rgb'] ** 2 - noise ** 2) ** 0.5
print(f\"| $method | $n | 1 | {j['rmse_rgb']:.4f} ({noise:.4f}; corrected {corrected:.4f}) | {j['mean_error']:+.4f} +- {j['mean_error_se']:.4f} |\")"
  done
done
