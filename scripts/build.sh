#!/usr/bin/env bash
# Configures and builds lucent in build/ (Release, warnings as errors), as CI does.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DLUCENT_WERROR=ON > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build --parallel "$(nproc)"
