#!/usr/bin/env bash
# atlas_quality.sh: does the atlas's distortion change texture-space-is' error? The same UV sphere (30 mm, marble,
# standard dipole, 160 x 120, 4 frames) with its own latitude-longitude coordinates (area stretch L2 1.19, angle
# distortion up to 7.7) and without any (lucent's atlas: L2 1.002), against the bssrdf reference of each.
#   bash bench/atlas_quality.sh [LUCENT]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=$(realpath "${1:-build/lucent}")
out=out/bench/uvsphere
python3 bench/make_uv_sphere.py "$out"
cat > "$out/scene.json" <<'JSON'
{
  "scale_mm": 15.0,
  "camera": { "eye": [0.0, 0.6, 4.2], "target": [0.0, 0.0, 0.0], "fov_y_deg": 34 },
  "lights": [ { "direction": [0.75, -0.35, -0.55], "radiance": [3.0, 3.0, 3.0] } ],
  "objects": [ { "name": "sphere", "mesh": "sphere_plain.obj", "material": { "preset": "Marble", "model": "standard" } } ],
  "method": { "name": "texture-space-is", "N": 1600, "specular": false },
  "render": { "width": 160, "height": 120, "frames": 4, "background": [0, 0, 0] }
}
JSON
cd "$out"
for m in plain latlong; do
  "$lucent" atlas "sphere_$m.obj" --no-cache | grep -E "charts|stretch"
  "$lucent" reference scene.json --set "objects.0.mesh=sphere_$m.obj" --integrator bssrdf --spp 2048 -q -o "ref_$m.exr"
  for n in 400 1600; do
    "$lucent" render scene.json --set "objects.0.mesh=sphere_$m.obj" --set "method.N=$n" -q -o "tsis_${m}_$n.png" \
      --exr "tsis_${m}_$n.exr"
    "$lucent" compare "tsis_${m}_$n.exr" "ref_$m.exr" --json | python3 -c "
import json, sys
j = json.load(sys.stdin)['linear']
noise = j['reference_noise_rms'] * 3 ** 0.5
print(f\"$m N $n: linear RMSE {j['rmse_rgb']:.4f} (noise-corrected {max(0, j['rmse_rgb']**2 - noise**2) ** 0.5:.4f}), mean error {j['mean_error']:+.4f}\")"
  done
done
