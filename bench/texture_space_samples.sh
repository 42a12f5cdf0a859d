#!/usr/bin/env bash
# texture_space_samples.sh: the shape of Chang et al. 2008, Tables 2 and 3: GPU time of stage 3 (the `shade`
# pass) and of the whole frame against the number of samples N, for texture-space-is, from
# `lucent render --timings-json` (median of frames 2-3; frame 1 is a warm-up).
#   bash bench/texture_space_samples.sh [LUCENT] [WIDTH] [HEIGHT]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
width=${2:-320}
height=${3:-240}
mkdir -p out/bench
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "| scene | N | shade (stage 3) ms | frame ms | frames/s |"
echo "|---|---|---|---|---|"
for scene in scenes/bunny_texture_space_is.json scenes/horse_texture_space_is.json sphere; do
  args=("$scene")
  name=$(basename "$scene" .json)
  if [[ $scene == sphere ]]; then
    args=(docs/images/atlas/scenes/sphere.json --set 'method={"name": "texture-space-is"}'
          --set 'lights=[{"direction": [0.75, -0.35, -0.55], "radiance": [3, 3, 3]}]' --set scale_mm=25)
  fi
  for n in 49 100 400 900 1600 2500; do
    json=out/bench/tsis_${name}_$n.json
    "$lucent" render "${args[@]}" --set "method.N=$n" --set method.atlas_size=512 --set "render.width=$width" \
      --set "render.height=$height" --frames 3 -q -o "out/bench/tsis_${name}_$n.png" --timings-json "$json"
    python3 - "$json" "$name" "$n" <<'PY'
import json, statistics, sys
frames = json.load(open(sys.argv[1]))["frames"][1:]
shade = statistics.median(f["passes"].get("shade", 0.0) for f in frames)
total = statistics.median(f["total_ms"] for f in frames)
print(f"| {sys.argv[2]} | {sys.argv[3]} | {shade:.1f} | {total:.1f} | {1000.0 / total:.2f} |")
PY
  done
done
