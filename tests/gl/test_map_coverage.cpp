// test_map_coverage.cpp: the coverage diagnostic (fraction of visible translucent pixels seen by at least one
// map) and the choice of map directions: automatic (Halton, Fibonacci) or given by the user.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"

namespace {

double coverage(const std::vector<std::string>& sets) {
  lucent::test::ensure_gl_context();
  std::vector<std::string> all = {"render.width=96", "render.height=64", "method.N=1", "method.map_size=64",
                                  "method.light_map_size=64", "method.vpls=0"};
  all.insert(all.end(), sets.begin(), sets.end());
  lucent::Scene scene = lucent::default_scene(all);
  lucent::OffscreenFramebuffer framebuffer(96, 64);
  lucent::Renderer renderer(scene);
  renderer.render(scene.camera, {framebuffer.id(), 96, 64});
  const lucent::FrameTimings& timings = renderer.last_frame_timings();
  EXPECT_GT(timings.stat("translucent_pixels"), 1000.0);
  return timings.stat("coverage", -1.0);
}

TEST(MapCoverage, GrowsWithKAndReachesTheWholeVisibleSurface) {
  double k1 = coverage({"method.K=1"}), k4 = coverage({"method.K=4"}), k16 = coverage({"method.K=16"});
  fmt::print("coverage K=1 {:.3f}, K=4 {:.3f}, K=16 {:.3f}\n", k1, k4, k16);
  EXPECT_LT(k1, 0.9) << "one view misses what faces away from it (the torus hole, the sides)";
  EXPECT_LT(k1, k4);
  EXPECT_LE(k4, k16);
  EXPECT_GT(k16, 0.99);
}

TEST(MapCoverage, UserDirectionsAreUsed) {
  // Only the back (-z, away from the camera): none of the visible surface is covered. The six axes: all of it.
  double back = coverage({"method.map_directions=[[0, 0, -1]]"});
  double axes = coverage({"method.map_directions=[[1,0,0],[-1,0,0],[0,1,0],[0,-1,0],[0,0,1],[0,0,-1]]"});
  double fibonacci = coverage({"method.K=6", "method.directions=\"fibonacci\""});
  fmt::print("coverage: back only {:.3f}, six axes {:.3f}, Fibonacci K=6 {:.3f}\n", back, axes, fibonacci);
  EXPECT_LT(back, 0.35);
  EXPECT_GT(axes, 0.99);
  EXPECT_GT(fibonacci, 0.95);
}

}  // namespace
