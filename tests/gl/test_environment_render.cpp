// test_environment_render.cpp: a scene's environment map on the GPU: camera rays that miss see it the right
// way up and in the right azimuth (the mapping of lights/equirect.h), and its lights carry no GGX highlight.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"

namespace {

TEST(EnvironmentRender, BackgroundShowsTheMapUpright) {
  lucent::test::ensure_gl_context();
  // Upper hemisphere red, lower blue, and a green quarter of azimuths around +x (u in [0.625, 0.875)).
  lucent::ImageRGBA32F image{64, 32, {}};
  image.pixels.resize(64 * 32 * 4);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      float* p = &image.pixels[4 * (y * 64 + x)];
      bool plus_x = x >= 40 && x < 56;
      p[0] = y < 16 && !plus_x ? 1.0f : 0.0f, p[1] = plus_x ? 1.0f : 0.0f, p[2] = y >= 16 && !plus_x ? 1.0f : 0.0f;
      p[3] = 1.0f;
    }
  std::string map = lucent::test::output_path("updown.hdr");
  lucent::write_hdr(map, image);
  lucent::Scene scene = lucent::parse_scene(fmt::format(R"({{
    "camera": {{ "eye": [0, 0, 0], "target": [0, 0, -1], "fov_y_deg": 60 }},
    "environment": {{ "file": "{}", "lights": 4 }},
    "objects": [{{ "shape": "sphere", "radius": 0.01, "translate": [0, 0, 50], "material": "Marble" }}],
    "method": {{ "K": 2, "N": 1, "map_size": 16, "light_map_size": 16, "vpls": 0 }},
    "render": {{ "width": 32, "height": 32 }} }})",
                                                        map),
                                            "environment scene", ".");
  ASSERT_TRUE(scene.environment.has_value());
  ASSERT_EQ(scene.lights.size(), 4u);
  for (const auto& light : scene.lights) EXPECT_FALSE(light.specular);
  lucent::OffscreenFramebuffer framebuffer(32, 32);
  lucent::Renderer renderer(scene);
  renderer.render(scene.camera, {framebuffer.id(), 32, 32});
  lucent::ImageRGBA32F out = renderer.read_radiance();
  // Looking along -z (u = 0.5): red above the horizon, blue below (image rows top first).
  EXPECT_GT(out.at(16, 4)[0], 0.9f);
  EXPECT_LT(out.at(16, 4)[2], 0.1f);
  EXPECT_GT(out.at(16, 28)[2], 0.9f);
  EXPECT_LT(out.at(16, 28)[0], 0.1f);
  // Turned toward +x (u = 0.75): green.
  lucent::Camera east = scene.camera;
  east.target = {1, 0, 0};
  renderer.render(east, {framebuffer.id(), 32, 32});
  out = renderer.read_radiance();
  EXPECT_GT(out.at(16, 16)[1], 0.9f);
}

}  // namespace
