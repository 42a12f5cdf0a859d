#!/usr/bin/env bash
# Per-step GPU timings of the radiosity-maps method (medians over the frames after the first), on whatever
# OpenGL 4.5 device the headless context finds (llvmpipe without a GPU). Results go into docs/performance.md
# by hand, with the device and date printed here.
#   bash bench/radiosity_maps.sh [build/lucent]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
source bench/render_timings.sh
run default_small --frames 5 --set render.width=320 --set render.height=200 --set method.map_size=256 --set method.light_map_size=256
run default --frames 5
run bunny_target scenes/bunny_potato.json --frames 3 --set render.width=1920 --set render.height=1080 \
    --set method.K=16 --set method.N=32 --set method.map_size=512 --set method.light_map_size=512
