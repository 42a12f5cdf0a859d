#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, ASan + UBSan) in build-sanitize/ (scripts/sanitize_build.sh, the
# tree the sanitizer tests use) and runs each one on a copy of
# its seed corpus (tests/fuzz/corpus/<target>/, which the run never changes) for its share of SECONDS (default 60).
# Exits non-zero when a target crashes, leaks, hangs or runs out of memory, after printing the reproducer, which
# is kept in build-sanitize/artifacts/<target>/. Reproduce: build-sanitize/tests/fuzz/fuzz_<target> <file>.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
targets=(mesh image scene vdb material_map gltf)

bash scripts/sanitize_build.sh "${targets[@]/#/fuzz_}"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for target in "${targets[@]}"; do
  mkdir -p "$work/$target/corpus" "$work/$target/artifacts"
  cp tests/fuzz/corpus/"$target"/* "$work/$target/corpus/"
  if build-sanitize/tests/fuzz/fuzz_"$target" "$work/$target/corpus" -max_total_time=$((seconds / ${#targets[@]})) \
       -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$work/$target/artifacts/" -print_final_stats=1 \
       > "$work/$target/log" 2>&1; then
    echo "fuzz_$target: $(grep -E '^stat::number_of_executed_units' "$work/$target/log" | awk '{print $2}') inputs, no failure"
  else
    status=1
    echo "fuzz_$target: FAILED"
    tail -n 60 "$work/$target/log"
    mkdir -p build-sanitize/artifacts/"$target"
    for artifact in "$work/$target/artifacts"/*; do
      [ -e "$artifact" ] || continue
      cp "$artifact" build-sanitize/artifacts/"$target"/
      kept=build-sanitize/artifacts/$target/$(basename "$artifact")
      echo "reproducer: $kept ($(stat -c %s "$kept") bytes); run: build-sanitize/tests/fuzz/fuzz_$target $kept"
      od -A d -c "$kept" | head -n 20
    done
  fi
done
exit $status
