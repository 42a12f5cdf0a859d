// test_animation.cpp: animated geometry through the renderer: a new time reshapes deforming meshes and blob
// surfaces on the GPU and restarts accumulation; the same time renders the same image.
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "../test_paths.h"

namespace {

lucent::Scene small_blobs() {
  return lucent::load_scene(std::string(LUCENT_SCENES_DIR) + "/blobs.json",
                            {"render.width=64", "render.height=40", "method.K=4", "method.N=4", "method.map_size=64",
                             "method.light_map_size=128", "method.vpls=0", "objects.0.segments=32"});
}

TEST(Animation, NewTimeReshapesBlobsAndRestartsAccumulation) {
  lucent::test::ensure_gl_context();
  lucent::Scene scene = small_blobs();
  lucent::OffscreenFramebuffer framebuffer(64, 40);
  lucent::Renderer renderer(scene);
  auto frame = [&] {
    renderer.render(scene.camera, {framebuffer.id(), 64, 40});
    return renderer.read_radiance();
  };
  lucent::ImageRGBA32F at_zero = frame();
  frame();
  EXPECT_EQ(renderer.accumulated_frames(), 2);
  renderer.set_time(0.5);
  lucent::ImageRGBA32F at_half = frame();
  EXPECT_EQ(renderer.accumulated_frames(), 1) << "new geometry restarts accumulation";
  // The blobs moved: the translucent coverage (alpha marks surfaces) changed.
  int changed = 0;
  for (std::size_t i = 3; i < at_zero.pixels.size(); i += 4) changed += at_zero.pixels[i] != at_half.pixels[i];
  EXPECT_GT(changed, 10);
  // Back to t = 0 with a fresh renderer (same seed, same first frame): the same image.
  lucent::Renderer again(scene);
  again.render(scene.camera, {framebuffer.id(), 64, 40});
  EXPECT_EQ(again.read_radiance().pixels, at_zero.pixels);
}

TEST(Animation, StaticSceneIgnoresTime) {
  lucent::test::ensure_gl_context();
  lucent::Scene scene = lucent::default_scene({"render.width=32", "render.height=24", "method.K=2", "method.N=2",
                                               "method.map_size=32", "method.light_map_size=64"});
  lucent::OffscreenFramebuffer framebuffer(32, 24);
  lucent::Renderer renderer(scene);
  renderer.render(scene.camera, {framebuffer.id(), 32, 24});
  renderer.set_time(3.0);
  renderer.render(scene.camera, {framebuffer.id(), 32, 24});
  EXPECT_EQ(renderer.accumulated_frames(), 2) << "nothing moves, nothing restarts";
}

}  // namespace
