#!/usr/bin/env bash
# Quick start, step 2 (and CI): install what is missing, build, run every test (CPU tests and GL tests on
# llvmpipe or a GPU), then the cpu-labelled tests again under AddressSanitizer + UndefinedBehaviorSanitizer, then
# the file loaders under libFuzzer for a minute (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure --parallel "$(nproc)")

# Sanitizer run: CPU tests only (GL drivers are not sanitizer-clean).
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DLUCENT_SANITIZE=ON -DLUCENT_WERROR=ON \
      -DLUCENT_BUILD_EXAMPLES=OFF > build-sanitize.log 2>&1 || { cat build-sanitize.log; exit 1; }
cmake --build build-sanitize --parallel "$(nproc)" --target lucent_cpu_tests lucent_cli
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure --parallel "$(nproc)" -L cpu)

# Fuzzing: mutated mesh, image and scene files through the loaders, 60 s in all (clang, ASan + UBSan).
bash scripts/fuzz.sh 60
