// test_scene_writer_render.cpp: a saved scene renders like the scene it was saved from ("save scene as" in
// the viewer must let `lucent render` reproduce the view): the built-in scene and the spot-lit bunny (a mesh
// file, point and spot lights), rendered before and after load -> save -> load. Tolerance: max |difference|
// <= 2 8-bit steps, mean <= 0.05 (positions are bit-exact; normals may differ by the loader's renormalisation).
#include <filesystem>

#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "lucent/scene_writer.h"
#include "../test_paths.h"

namespace {

lucent::ImageRGBA8 render(const lucent::Scene& scene) {
  const int width = 96, height = 64;
  lucent::OffscreenFramebuffer framebuffer(width, height);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < 2; ++f) renderer.render(scene.camera, {framebuffer.id(), width, height});
  return renderer.read_display();
}

class SavedSceneRender : public ::testing::TestWithParam<const char*> {};

TEST_P(SavedSceneRender, RendersLikeTheOriginal) {
  lucent::test::ensure_gl_context();
  std::vector<std::string> fast = {"method.K=4", "method.N=4", "method.map_size=64", "method.light_map_size=128",
                                   "method.vpl_map_size=32"};
  std::string name = GetParam();
  lucent::Scene original = lucent::load_scene(std::string(LUCENT_SCENES_DIR) + "/" + name, fast);
  std::string saved = lucent::test::output_path("saved_" + name);
  lucent::save_scene(original, saved);
  lucent::Scene again = lucent::load_scene(saved);
  lucent::ImageRGBA8 a = render(original), b = render(again);
  lucent::test::ImageDifference d = lucent::test::compare(b, a);
  std::printf("%s: saved vs original: mean |d| %.4f, max %d (8-bit steps)\n", name.c_str(), d.mean_abs, d.max_abs);
  if (d.max_abs > 2 || d.mean_abs > 0.05) {
    lucent::write_png(lucent::test::output_path("saved_" + name + "_actual.png"), b);
    lucent::write_png(lucent::test::output_path("saved_" + name + "_diff.png"), lucent::test::difference_image(b, a));
  }
  EXPECT_LE(d.max_abs, 2);
  EXPECT_LE(d.mean_abs, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SavedSceneRender, ::testing::Values("default.json", "bunny_spot.json"),
                         [](const auto& test_param) { return std::filesystem::path(test_param.param).stem().string(); });

}  // namespace
