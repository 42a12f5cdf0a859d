#!/usr/bin/env bash
# Quick start, step 1: install the Debian 12 packages, build, and render the default scene to out/default.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/lucent render -o out/default.png
