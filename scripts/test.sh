#!/usr/bin/env bash
# Quick start, step 2 (and CI): install what is missing, build, run every test (CPU tests and GL tests on
# llvmpipe or a GPU), then the cpu-labelled tests again under AddressSanitizer + UndefinedBehaviorSanitizer, then
# the file loaders under libFuzzer for a minute (scripts/fuzz.sh). The sanitizer tests and the fuzz targets share
# one clang tree, build-sanitize/ (scripts/sanitize_build.sh). Each stage prints its wall time; docs/design.md
# ("Build and test time") has the measured budget.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
stage_start=$SECONDS
stage() {  # stage NAME: the time since the previous stage ended
  echo "test.sh: $1 took $((SECONDS - stage_start)) s"
  stage_start=$SECONDS
}

bash scripts/install-deps.sh
stage "install-deps"
bash scripts/build.sh
stage "release build"
(cd build && ctest --output-on-failure --parallel "$(nproc)" -LE accuracy)
stage "tests"

# Sanitizer run: CPU tests only (GL drivers are not sanitizer-clean).
bash scripts/sanitize_build.sh lucent_cpu_tests lucent_cli fuzz_mesh fuzz_image fuzz_scene fuzz_vdb fuzz_material_map fuzz_gltf
stage "sanitizer build"
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure --parallel "$(nproc)" -L cpu)
stage "sanitizer tests"

# Fuzzing: mutated mesh, image and scene files through the loaders, 60 s in all (clang, ASan + UBSan).
bash scripts/fuzz.sh 60
stage "fuzzing"
echo "test.sh: all stages passed in $((SECONDS - started)) s"
