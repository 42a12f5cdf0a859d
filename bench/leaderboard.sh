#!/usr/bin/env bash
# The leaderboard: every registered method at its quality settings on the scene suite of bench/leaderboard.json,
# against the volpath and bssrdf references, then docs/leaderboard.md and its plots from the results.
#   bash bench/leaderboard.sh [extra `lucent bench` options, e.g. --set render.width=64 --run candle]
# Environment: LUCENT (the binary, default build/lucent), OUT (the bench's folder, default out/leaderboard; its
# references/ cache makes a stopped run resume), DOC (default docs/leaderboard.md), PLOTS (default
# docs/images/leaderboard). Prints the total runtime, which also goes into the page.
set -euo pipefail
cd "$(dirname "$0")/.."
LUCENT=${LUCENT:-build/lucent}
OUT=${OUT:-out/leaderboard}
DOC=${DOC:-docs/leaderboard.md}
PLOTS=${PLOTS:-docs/images/leaderboard}
start=$(date +%s)
"$LUCENT" bench bench/leaderboard.json -o "$OUT" "$@"
runtime=$(( $(date +%s) - start ))
python3 bench/leaderboard_report.py "$OUT/results.json" "$DOC" "$PLOTS" --runtime "$runtime" \
  --command "bash bench/leaderboard.sh $*" --notes bench/leaderboard_notes.md
echo "leaderboard: ${runtime} s in all -> $DOC"
