#!/usr/bin/env bash
# converged_mode.sh: radiosity-maps' converged mode (Dal Corso et al. 2015, Section 3.2): GPU time of a full frame
# (steps 1-3) against a converged frame (step 3 alone) for the default scene and the bunny, from
# `lucent render --timings-json`. Frames 1..C accumulate the maps, frames C+1.. are converged.
#   bash bench/converged_mode.sh [LUCENT] [FRAMES] [CONVERGED_AFTER]
set -euo pipefail
cd "$(dirname "$0")/.."
lucent=${1:-build/lucent}
frames=${2:-10}
after=${3:-4}
mkdir -p out/bench
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
for scene in default scenes/bunny_marble.json; do
  name=$(basename "$scene" .json)
  args=()
  [[ $scene != default ]] && args+=("$scene")
  json=out/bench/converged_$name.json
  "$lucent" render "${args[@]}" --frames "$frames" --set "method.converged_after=$after" -q \
    -o "out/bench/converged_$name.png" --timings-json "$json"
  python3 - "$json" "$name" "$after" <<'PY'
import json, statistics, sys
frames = json.load(open(sys.argv[1]))["frames"]
after = int(sys.argv[3])
full = [f for f in frames[1:after]]            # frame 1 is a warm-up (driver compiles, first-use costs)
converged = [f for f in frames if f["stats"].get("converged") == 1]
med = lambda fs, key=None: statistics.median([f["total_ms"] if key is None else f["passes"].get(key, 0.0) for f in fs])
print(f"{sys.argv[2]}: full frame {med(full):.1f} ms (median of {len(full)}), converged frame {med(converged):.1f} ms "
      f"(median of {len(converged)}), ratio {med(full) / med(converged):.1f}x; "
      f"converged = camera_gbuffer {med(converged, 'camera_gbuffer'):.1f} + combine {med(converged, 'combine'):.1f} "
      f"+ tonemap {med(converged, 'tonemap'):.1f} ms; full-frame combine {med(full, 'combine'):.1f} ms")
PY
done
