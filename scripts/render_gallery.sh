#!/usr/bin/env bash
# Renders the README gallery of the flagship scenes into docs/images/ (llvmpipe: a few minutes on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
L=build/lucent
S="--set render.width=320 --set render.height=200 -q"
$L render scenes/candle.json $S --frames 4 --set method.map_size=256 -o docs/images/candle.png
$L render scenes/candle.json $S --frames 4 --set method.map_size=256 --set method.vpls=0 -o docs/images/candle_no_vpls.png
$L render scenes/lamp_shade.json $S --frames 4 --set method.map_size=256 -o docs/images/lamp_shade.png
$L render scenes/bunny_environment.json $S --frames 4 --set render.height=240 --set method.map_size=256 \
  --set method.light_map_size=512 -o docs/images/bunny_environment.png
$L render scenes/shell_point_light.json $S --frames 4 -o docs/images/shell_point_light.png
$L render scenes/blobs.json $S --animate --frames 3 --set render.fps=0.5 -o out/gallery/blobs.png
cp out/gallery/blobs_0000.png docs/images/blobs_t0.png && cp out/gallery/blobs_0002.png docs/images/blobs_t4.png
$L render scenes/candle_melting.json $S --animate --frames 2 --set render.fps=1.33 --set method.map_size=256 \
  -o out/gallery/candle_melting.png
cp out/gallery/candle_melting_0001.png docs/images/candle_melting.png
$L render scenes/bunny_spot.json $S --frames 4 --set render.height=240 --set method.map_size=256 \
  --set method.light_map_size=512 -o docs/images/bunny_spot.png
# voxel-paths: heterogeneous media (a material's "field")
$L render scenes/bunny_marble_veins.json $S --set render.height=240 -o docs/images/bunny_marble_veins.png
$L render scenes/bunny_marble_veins.json $S --set render.height=240 --set method.extinction='"sigma_t"' \
  -o docs/images/bunny_marble_veins_sigma_t.png
$L render scenes/deforming_inclusion.json $S --set render.height=240 --animate --frames 2 --set render.fps=1.33 \
  -o out/gallery/deforming_inclusion.png
cp out/gallery/deforming_inclusion_0000.png docs/images/deforming_inclusion_t0.png
cp out/gallery/deforming_inclusion_0001.png docs/images/deforming_inclusion_t075.png
# the bunny in the materials of Dal Corso et al. (Fig. 6, Fig. 13), 320 x 240, 4 frames
for m in marble grapefruit shampoo potato; do
  $L render scenes/bunny_$m.json $S --set render.height=240 --frames 4 -o docs/images/bunny_$m.png
done
# every method's example scene that has no picture above, 320 x 240
for s in bunny_per_pixel bunny_screen_space bunny_diffuse_wrap; do
  $L render scenes/$s.json $S --set render.height=240 -o docs/images/$s.png
done
$L render scenes/bunny_random_walk.json $S --set render.height=240 --frames 8 -o docs/images/bunny_random_walk.png
