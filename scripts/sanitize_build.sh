#!/usr/bin/env bash
# Configures build-sanitize/ and builds the given targets in it: clang, AddressSanitizer + UndefinedBehaviorSanitizer,
# libFuzzer's coverage instrumentation, -O1 with line tables, warnings as errors. One tree serves both the sanitizer
# run of the cpu-labelled tests (scripts/test.sh) and the libFuzzer targets (scripts/fuzz.sh), so the library is
# compiled once for both. Usage: bash scripts/sanitize_build.sh TARGET...
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p build-sanitize
CC=clang CXX=clang++ cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DLUCENT_SANITIZE=ON \
      -DLUCENT_FUZZ=ON -DLUCENT_WERROR=ON -DLUCENT_BUILD_EXAMPLES=OFF > build-sanitize/configure.log 2>&1 ||
  { cat build-sanitize/configure.log; exit 1; }
cmake --build build-sanitize --parallel "$(nproc)" --target "$@"
