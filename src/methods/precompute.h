// precompute.h: runs a method's precompute step (PrecomputeDecl, method_info.h) through the precompute cache:
// the cached bytes when the key matches, else computed and stored. CPU only, no GL (the renderer calls it before
// creating the method; tests call it with their own declarations).
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "cache/precompute_cache.h"
#include "methods/method_info.h"

namespace lucent::methods {

// The cache key of `decl` for `input` (see PrecomputeDecl for what it holds).
cache::Key precompute_key(const PrecomputeDecl& decl, const PrecomputeInput& input);

struct PrecomputeResult {
  std::vector<std::byte> bytes;
  bool from_cache = false;
};

// `progress` (may be empty) sees fractions in [0, 1], non-decreasing, starting with 0 and ending with exactly one
// 1, whatever decl.compute reports (a cache hit: 0 then 1). A disabled cache computes and stores nothing.
PrecomputeResult run_precompute(const PrecomputeDecl& decl, const PrecomputeInput& input,
                                const std::function<void(double)>& progress = {});

}  // namespace lucent::methods
