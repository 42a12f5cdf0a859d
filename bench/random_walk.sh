#!/usr/bin/env bash
# random_walk.sh: the random-walk method's throughput with sphere jumps on and off (paths/s, walk steps/s, steps per
# path, the pass times, medians of frames 2..F), and the time to a volpath reference of the same image on the GPU
# (`lucent reference --device gpu`) and on the CPU. Prints the device and markdown rows (docs/performance.md).
#   bash bench/random_walk.sh [SCENE] [WIDTH] [HEIGHT] [FRAMES] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${LUCENT:-build/lucent}
scene=${1:-scenes/bunny_marble.json}
width=${2:-160}
height=${3:-120}
frames=${4:-5}
spp=${5:-64}
mkdir -p out/bench
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "scene: $scene, ${width}x${height}, $frames frames of 1 path per pixel"
echo "| sphere jumps | sphere_walks ms | trace ms | paths/s | steps/s | steps/path |"
echo "|---|---|---|---|---|---|"
for jumps in true false; do
  json=out/bench/random_walk_$jumps.json
  log=$("$lucent" render "$scene" --set "method={\"name\": \"random-walk\", \"sphere_jumps\": $jumps}" \
    --set "render.width=$width" --set "render.height=$height" --frames "$frames" \
    -o "out/bench/random_walk_$jumps.png" --timings-json "$json" 2>&1)
  [[ $jumps == true ]] && echo "$log" | grep -m1 "GPU time per frame" | sed 's/.*, on /device: /; s/:$//'
  python3 - "$json" "$jumps" <<'PY'
import json, statistics, sys
frames = json.load(open(sys.argv[1]))["frames"][1:]
def median(key, where):
    return statistics.median(f[where].get(key, 0.0) for f in frames)
print(f"| {sys.argv[2]} | {median('sphere_walks', 'passes'):.1f} | {median('trace', 'passes'):.1f} | "
      f"{median('paths_per_second', 'stats'):.4g} | {median('steps_per_second', 'stats'):.4g} | "
      f"{median('steps_per_path', 'stats'):.2f} |")
PY
done
for device in gpu cpu; do
  "$lucent" reference "$scene" --device "$device" --spp "$spp" --set "render.width=$width" \
    --set "render.height=$height" -q -o "out/bench/random_walk_reference_$device.exr"
  python3 -c "import json,sys; m=json.load(open('out/bench/random_walk_reference_$device.meta.json')); print(f\"reference --device $device: {m['samples_per_pixel']} spp in {m['samples_per_pixel'] * m['width'] * m['height'] / m['camera_paths_per_second']:.1f} s ({m['camera_paths_per_second']:.4g} camera paths/s, {m['steps_per_path']:.2f} steps/path)\")"
done
"$lucent" compare out/bench/random_walk_reference_gpu.exr out/bench/random_walk_reference_cpu.exr | grep -E "linear|noise"
