#!/usr/bin/env bash
# The textured example (scenes/marble_textured.json: albedo and mean free path from textures) against both
# references: volpath (the physics) and the bssrdf integrator (the model, with the same exit-point convention),
# with the two methods that read material maps. Prints `lucent compare` for each pair, the pass timings of a
# textured and an untextured render (what the texture-coordinate attachment and the lookup cost), and writes
# docs/images/marble_textured.png (volpath | bssrdf | radiosity-maps | per-pixel). About 5 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
L=build/lucent
OUT=${OUT:-out/material_maps}
mkdir -p "$OUT"
SCENE=scenes/marble_textured.json
S=(--set render.width=240 --set render.height=150)
$L reference $SCENE "${S[@]}" --integrator volpath --spp 256 -o "$OUT/volpath.exr"
$L reference $SCENE "${S[@]}" --integrator bssrdf --spp 1024 -o "$OUT/bssrdf.exr"
$L render $SCENE "${S[@]}" --set method.specular=false --exr "$OUT/radiosity_maps.exr" -o "$OUT/radiosity_maps.png"
$L render $SCENE "${S[@]}" --set 'method={"name": "per-pixel", "N": 32, "specular": false}' \
   --exr "$OUT/per_pixel.exr" -o "$OUT/per_pixel.png"
for r in volpath bssrdf; do $L tonemap "$OUT/$r.exr" -o "$OUT/$r.png"; done
for m in radiosity_maps per_pixel bssrdf; do
  for r in volpath bssrdf; do
    [ "$m" = "$r" ] && continue
    echo "== $m against $r"
    $L compare "$OUT/$m.exr" "$OUT/$r.exr" --diff "$OUT/${m}_vs_$r.png"
  done
done
# The same ball untextured (the maps' mean albedo and mean free path): the cost of the maps.
echo "== textured"
$L render $SCENE "${S[@]}" -o "$OUT/timing_textured.png" | grep -E "gbuffer|integrate|total"
echo "== untextured"
$L render $SCENE "${S[@]}" --set 'objects.0.material={"albedo": [0.816, 0.795, 0.748], "mfp_mm": [1.125, 0.750, 0.516], "eta": 1.5}' \
   -o "$OUT/timing_untextured.png" | grep -E "gbuffer|integrate|total"
python3 - "$OUT" <<'PY'
import os, sys
sys.path.insert(0, "bench")
from leaderboard_report import write_strip
out = sys.argv[1]
write_strip([os.path.join(out, n + ".png") for n in ("volpath", "bssrdf", "radiosity_maps", "per_pixel")],
            "docs/images/marble_textured.png")
print("wrote docs/images/marble_textured.png")
PY
