#!/usr/bin/env bash
# The denoising stage as a user meets it: 16 still frames, then a 5-degree orbit (bench/tools/denoise_orbit.cpp),
# and the first frame after the orbit against the new view's volpath reference: with the reprojected history, denoised
# from nothing, and the method's raw restart. Also the flicker over the still frames and the stage's cost.
#   bash bench/denoise.sh [SCENE] [key=value ...]   (default: the marble bunny by random-walk at 96x72)
# Environment: OUT (default out/denoise), SPP (the reference's samples per pixel, default 256).
set -euo pipefail
cd "$(dirname "$0")/.."
SCENE=${1:-scenes/bunny_random_walk.json}
shift || true
OUT=${OUT:-out/denoise}
SPP=${SPP:-256}
SETS=("render.width=96" "render.height=72" "$@")
build/examples/denoise_orbit "$SCENE" "$OUT" 16 5 "${SETS[@]}"
if [ ! -f "$OUT/orbit_reference.exr" ]; then
  build/lucent reference "$OUT/orbit.json" --spp "$SPP" -o "$OUT/orbit_reference.exr" -q
fi
for image in orbit_denoised orbit_denoised_restart orbit_raw; do
  build/lucent compare "$OUT/$image.exr" "$OUT/orbit_reference.exr" --json | python3 -c '
import json, sys
d = json.load(sys.stdin)["linear"]
print("%s: RMSE against volpath (%s spp) %.5f, mean error %+.5f +- %.5f, reference noise %.5f"
      % (sys.argv[1], sys.argv[2], d["rmse_rgb"], d["mean_error"], d["mean_error_se"], d["reference_noise_rms"]))' "$image" "$SPP"
done
