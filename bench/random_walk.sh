#!/usr/bin/env bash
# random_walk.sh: the random-walk method's throughput, frame by frame in one run, with sphere jumps on and off,
# beside CPU volpath on the same image (one core and all cores). Per frame: the trace pass's time, dispatches (and
# those with under a tenth of the pool busy), read-backs, paths finished and their walk steps (every pixel's),
# traversals per step and per next-event estimate, node visits per step. Then the totals over frames 2..F (frame 1
# compiles the shaders) and the ratio of CPU volpath's paths per second per core to the walk's. Prints the device
# and markdown (docs/performance.md), and from a second run that waits for and times every dispatch, the share of
# the trace time spent in sparse dispatches.
#   bash bench/random_walk.sh [SCENE] [WIDTH] [HEIGHT] [FRAMES] [REFERENCE_SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${LUCENT:-build/lucent}
scene=${1:-scenes/bunny_marble.json}
width=${2:-64}
height=${3:-48}
frames=${4:-24}
spp=${5:-16}
mkdir -p out/bench
date -u +"date: %Y-%m-%d %H:%M UTC"
cores=$(nproc)
echo "machine: $cores cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "scene: $scene, ${width}x${height}, $frames frames of 1 path per pixel"
for jumps in on off; do
  flag=$([[ $jumps == on ]] && echo true || echo false)
  json=out/bench/random_walk_$jumps.json
  start=$(date +%s.%N)
  log=$("$lucent" render "$scene" --set "method={\"name\": \"random-walk\", \"sphere_jumps\": $flag}" \
    --set "render.width=$width" --set "render.height=$height" --frames "$frames" \
    -o "out/bench/random_walk_$jumps.png" --timings-json "$json" 2>&1)
  wall=$(echo "$(date +%s.%N) - $start" | bc)
  [[ $jumps == on ]] && echo "$log" | grep -m1 "GPU time per frame" | sed 's/.*, on /device: /; s/:$//'
  # The same frames again with every dispatch waited for and timed (slower: a read-back per dispatch): the share of
  # the trace time spent in dispatches with under a tenth of the pool busy.
  "$lucent" render "$scene" --set "method={\"name\": \"random-walk\", \"sphere_jumps\": $flag, \"time_dispatches\": true}" \
    --set "render.width=$width" --set "render.height=$height" --frames "$frames" \
    -o "out/bench/random_walk_${jumps}_timed.png" --timings-json "out/bench/random_walk_${jumps}_timed.json" >/dev/null 2>&1
  for threads in 1 0; do
    "$lucent" reference "$scene" --spp "$spp" --threads "$threads" --sphere-jumps "$jumps" \
      --set "render.width=$width" --set "render.height=$height" -q -o "out/bench/random_walk_volpath_${jumps}_$threads.exr"
  done
  python3 bench/random_walk_report.py "$json" "$jumps" "$wall" "$cores" out/bench/random_walk_volpath_${jumps}_1.meta.json \
    out/bench/random_walk_volpath_${jumps}_0.meta.json "out/bench/random_walk_${jumps}_timed.json"
done
