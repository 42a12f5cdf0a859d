#!/usr/bin/env bash
# Per-pass GPU timings of the flagship features (point lights and their cube maps, VPLs, environment lights,
# animated geometry, the per-pixel baseline) on whatever OpenGL 4.5 device the headless context finds. Results go
# into docs/performance.md by hand, with the device and date printed here.
#   bash bench/flagship_features.sh [build/lucent]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
source bench/render_timings.sh
S="--set render.width=640 --set render.height=400"
common="--frames 3 $S --set method.K=16 --set method.N=32 --set method.map_size=256 --set method.light_map_size=512"
run shell_point_inside scenes/shell_point_light.json $common --set method.vpls=0
run candle_no_vpls scenes/candle.json $common --set method.vpls=0
run candle_vpls80 scenes/candle.json $common --set method.vpls=80
run candle_vpls256 scenes/candle.json $common --set method.vpls=256
run lamp_shade scenes/lamp_shade.json $common --set method.vpls=128
run bunny_env8 scenes/bunny_environment.json $common --set method.vpls=0
run bunny_env8_photon_beam scenes/bunny_environment.json $common --set method.vpls=0 --set 'objects.0.material={"preset": "Potato", "model": "photon-beam"}'
run blobs64 scenes/blobs.json $common --set method.vpls=0
run blobs128 scenes/blobs.json $common --set method.vpls=0 --set objects.0.segments=128
run candle_melting scenes/candle_melting.json --animate --frames 3 $S --set method.K=16 --set method.N=32 --set method.map_size=256 --set method.light_map_size=512
