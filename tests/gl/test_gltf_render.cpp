// test_gltf_render.cpp: the Blender-made glTF (tests/data/gltf/translucent_textured.glb: base colour texture,
// transmission, KHR_materials_volume) rendered by per-pixel as "material": "from_mesh" (llvmpipe, 96 x 64): the
// ball is translucent with the attenuation's hue (A = B c^2 with c^2 = 0.81, 0.36, 0.09: red over green over blue),
// and its texture shows: against the same material without maps (its texels' mean), pixels differ.
#include <algorithm>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "../test_paths.h"

namespace {

using nlohmann::json;

lucent::ImageRGBA8 render_ball(const lucent::Scene& scene) {
  const int width = 96, height = 64;
  lucent::OffscreenFramebuffer framebuffer(width, height);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < 2; ++f) renderer.render(scene.camera, {framebuffer.id(), width, height});
  return renderer.read_display();
}

json ball_scene(const json& material) {
  return {{"scale_mm", 1000},
          {"camera", {{"eye", {0.0, 0.02, 0.12}}, {"target", {0.0, 0.0, 0.0}}, {"fov_y_deg", 30}}},
          {"lights", json::array({{{"direction", {-0.4, -0.6, -0.7}}, {"radiance", {3.0, 3.0, 3.0}}}})},
          {"objects", json::array({{{"mesh", std::string(LUCENT_TEST_DATA) + "/gltf/translucent_textured.glb"},
                                    {"material", material}}})},
          {"method", {{"name", "per-pixel"}}},
          {"render", {{"background", {0.0, 0.0, 0.0}}}}};
}

TEST(GltfRender, BlenderAssetRendersTranslucentWithItsTexture) {
  lucent::test::ensure_gl_context();
  const lucent::Scene textured = lucent::parse_scene(ball_scene("from_mesh").dump(), "gltf.json", ".");
  const lucent::Material& m = *textured.objects[0].material;
  json flat = {{"sigma_a", {m.sigma_a.x, m.sigma_a.y, m.sigma_a.z}}, {"sigma_s", {m.sigma_s.x, m.sigma_s.y, m.sigma_s.z}},
               {"eta", m.eta}};
  const lucent::Scene untextured = lucent::parse_scene(ball_scene(flat).dump(), "flat.json", ".");
  const lucent::ImageRGBA8 a = render_ball(textured), b = render_ball(untextured);
  lucent::write_png(lucent::test::output_path("gltf_blender_asset.png"), a);
  double sum[3] = {0, 0, 0};
  int covered = 0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
    if (a.pixels[i] + a.pixels[i + 1] + a.pixels[i + 2] == 0) continue;  // the black background
    ++covered;
    for (int c = 0; c < 3; ++c) sum[c] += a.pixels[i + static_cast<std::size_t>(c)];
  }
  std::printf("ball: %d pixels, mean 8-bit colour (%.1f, %.1f, %.1f)\n", covered, sum[0] / covered, sum[1] / covered,
              sum[2] / covered);
  EXPECT_GT(covered, 500);
  EXPECT_GT(sum[0], 1.2 * sum[1]);
  EXPECT_GT(sum[1], 1.2 * sum[2]);
  const lucent::test::ImageDifference d = lucent::test::compare(a, b);
  std::printf("textured vs the texels' mean: mean |d| %.3f, max %d (8-bit steps)\n", d.mean_abs, d.max_abs);
  EXPECT_GE(d.max_abs, 8);
}

}  // namespace
