#!/usr/bin/env bash
# method_timings.sh: every registered method on one scene, every frame recomputed (`--restart-every-frame`, as when
# the scene changes), per-pass GPU time as the median of frames 2..F (frame 1 is a warm-up), from
# `lucent render --timings-json`. Prints the device, then one markdown row per method and pass.
#   bash bench/method_timings.sh [LUCENT] [SCENE] [WIDTH] [HEIGHT] [FRAMES] [-- extra render arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
scene=${2:-scenes/bunny_marble.json}
width=${3:-640}
height=${4:-480}
frames=${5:-5}
shift $(( $# < 5 ? $# : 5 ))
[[ ${1:-} == -- ]] && shift
mkdir -p out/bench
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "scene: $scene, ${width}x${height}, $frames frames, every frame recomputed"
methods=$("$lucent" methods --json | python3 -c 'import json, sys; print(" ".join(m["name"] for m in json.load(sys.stdin)))')
first=1
for method in $methods; do
  json=out/bench/method_timings_$method.json
  log=$("$lucent" render "$scene" --set "method={\"name\": \"$method\"}" --set "render.width=$width" \
    --set "render.height=$height" --frames "$frames" --restart-every-frame -o "out/bench/method_timings_$method.png" \
    --timings-json "$json" "$@" 2>&1) || { echo "$method: failed: $log" | tail -3; continue; }
  if [[ $first == 1 ]]; then echo "$log" | grep -m1 "GPU time per frame" | sed 's/.*, on /device: /; s/:$//'; first=0; fi
  python3 - "$json" "$method" <<'PY'
import json, statistics, sys
frames = json.load(open(sys.argv[1]))["frames"]
timed = frames[1:] or frames
passes = {}
for f in timed:
    for name, ms in f["passes"].items():
        passes.setdefault(name, []).append(ms)
total = statistics.median(f["total_ms"] for f in timed)
cells = ", ".join(f"{name} {statistics.median(v):.2f}" for name, v in passes.items())
stats = timed[-1]["stats"]
extra = ""
if "bssrdf_samples_per_second" in stats:
    extra = f" ({stats['bssrdf_samples_per_second']:.3g} BSSRDF samples/s)"
print(f"| {sys.argv[2]} | {total:.2f} | {1000.0 / total:.1f} | {cells}{extra} |")
PY
done
