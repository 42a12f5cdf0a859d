// precompute.cpp: see precompute.h.
#include "methods/precompute.h"

#include <algorithm>
#include <cmath>

#include "texture_space/scene_atlas.h"

namespace lucent::methods {
namespace {

// Passes on what a computation reports as a clamped, non-decreasing fraction below 1 (1 is the runner's own).
class MonotonicProgress {
 public:
  explicit MonotonicProgress(const std::function<void(double)>& out) : out_(out) {}
  void report(double fraction) {
    if (!out_ || !(fraction > last_)) return;  // also drops NaN
    last_ = std::min(fraction, kBelowOne);
    if (last_ > reported_) out_(reported_ = last_);
  }
  void start() {
    if (out_) out_(0.0);
  }
  void finish() {
    if (out_) out_(1.0);
  }

 private:
  static constexpr double kBelowOne = 0.999;
  const std::function<void(double)>& out_;
  double last_ = 0.0, reported_ = 0.0;
};

}  // namespace

cache::Key precompute_key(const PrecomputeDecl& decl, const PrecomputeInput& input) {
  const Scene& scene = input.scene;
  cache::Key key(decl.kind, decl.version);
  key.text(scene.method).params(scene.method_params).number(scene.scale_mm);
  key.integer(static_cast<std::int64_t>(scene.objects.size()));
  for (const SceneObject& object : scene.objects) {
    key.mesh(object.mesh);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) key.number(object.world_from_object[c][r]);
    if (object.material) key.integer(1).material(*object.material);
    else key.integer(0).vec3(object.albedo);
  }
  if (input.atlas) {
    key.integer(input.atlas->atlas.size);
    for (const texture_space::AtlasObject& object : input.atlas->atlas.objects)
      key.bytes(std::as_bytes(std::span(object.chart)));
  } else {
    key.integer(-1);
  }
  return key;
}

PrecomputeResult run_precompute(const PrecomputeDecl& decl, const PrecomputeInput& input,
                                const std::function<void(double)>& progress) {
  MonotonicProgress monotonic(progress);
  monotonic.start();
  const cache::Key key = precompute_key(decl, input);
  PrecomputeResult out;
  if (std::optional<std::vector<std::byte>> bytes = cache::load(key)) {
    out.bytes = std::move(*bytes);
    out.from_cache = true;
  } else {
    out.bytes = decl.compute(input, [&monotonic](double fraction) { monotonic.report(fraction); });
    cache::store(key, out.bytes);
  }
  monotonic.finish();
  return out;
}

}  // namespace lucent::methods
