// test_far_from_origin.cpp: an object far from the scene file's origin renders as it does at the origin. A 2 cm
// marble-like ball in a metre-unit scene at 100 m, 1 km and 10 km: in float, 10 km leaves 1 mm between
// representable coordinates (the ball is 20 of them across, its mean free path a fraction of one), and volpath
// went from 10% too dark at 100 m to black at 10 km. The loader moves the origin to the camera's target in double
// (Scene::origin); writers put it back. And a medium too dense for the ray offsets at its position is warned about.
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lucent/scene.h"
#include "lucent/scene_writer.h"
#include "reference/reference_renderer.h"

namespace lucent {
namespace {

std::string ball_at(double x, const std::string& sigma_s = "[2.2, 2.6, 3.0]") {
  return fmt::format(R"({{ "scale_mm": 1000,
    "camera": {{ "eye": [{0}, 0.01, 0.08], "target": [{0}, 0, 0], "fov_y_deg": 20 }},
    "lights": [{{ "direction": [-0.4, -0.5, -0.7], "radiance": [1, 1, 1] }},
               {{ "type": "point", "position": [{1}, 0.05, 0.05], "intensity": [1e-4, 1e-4, 1e-4] }}],
    "objects": [{{ "name": "ball", "shape": "sphere", "radius": 0.01, "segments": 32, "translate": [{0}, 0, 0],
                   "material": {{ "sigma_a": [0.003, 0.005, 0.01], "sigma_s": {2}, "g": 0, "eta": 1.5 }} }}],
    "render": {{ "width": 16, "height": 16, "background": [0, 0, 0] }} }})",
                     x, x + 0.03, sigma_s);
}

// The same image wherever the ball is (the moved scene is the scene at the origin, to the bit), which the file's
// coordinates in float could not give (volpath before: 0.81x at 100 m, 0.14x at 1 km, black at 10 km).
TEST(FarFromOrigin, ABallKilometresAwayRendersAsAtTheOrigin) {
  reference::ReferenceSettings settings;
  settings.samples_per_pixel = 8;
  const Scene at_origin = parse_scene(ball_at(0.0), "origin", "/");
  EXPECT_EQ(at_origin.origin, glm::dvec3(0.0));
  const reference::ReferenceImage expected = reference::render_reference(at_origin, settings);
  double sum = 0.0;
  for (float v : expected.mean.pixels) sum += v;
  ASSERT_GT(sum, 0.0);
  for (double x : {100.0, 1000.0, 10000.0}) {
    const Scene far = parse_scene(ball_at(x), "far", "/");
    EXPECT_EQ(far.origin, glm::dvec3(x, 0.0, 0.0));
    EXPECT_EQ(far.camera.target, glm::vec3(0.0f));
    EXPECT_EQ(far.point_lights[0].position, glm::vec3(0.03f, 0.05f, 0.05f));
    EXPECT_EQ(reference::render_reference(far, settings).mean.pixels, expected.mean.pixels) << x;
  }
}

// Writers give the file's coordinates back: the saved scene names the ball, the camera and the light where the file
// did, and loads to the same Scene.
TEST(FarFromOrigin, TheSavedSceneHasTheFilesCoordinates) {
  const Scene far = parse_scene(ball_at(10000.0), "far", "/");
  const nlohmann::json j = scene_to_json(far);
  EXPECT_EQ(j["camera"]["target"], nlohmann::json::array({10000.0, 0.0, 0.0}));
  EXPECT_EQ(j["camera"]["eye"][0], 10000.0);
  EXPECT_EQ(j["objects"][0]["translate"], nlohmann::json::array({10000.0, 0.0, 0.0}));
  EXPECT_NEAR(j["lights"][1]["position"][0].get<double>(), 10000.03, 1e-6);
}

// Near the origin nothing moves: a camera at 5 looking at the origin, or at a point 10 units away from 1 unit.
TEST(FarFromOrigin, ScenesAboutTheOriginKeepTheirCoordinates) {
  const Scene near = parse_scene(R"({ "camera": { "eye": [0, 0, 12], "target": [0, 0, 10] },
    "objects": [{ "shape": "sphere", "translate": [0, 0, 10], "material": "Skin1" }] })", "near", "/");
  EXPECT_EQ(near.origin, glm::dvec3(0.0));
  EXPECT_EQ(near.camera.target, glm::vec3(0, 0, 10));
}

// A medium whose mean free path is a few ray offsets long at its coordinates is named in one warning line.
TEST(FarFromOrigin, AMediumTooDenseForItsRayOffsetsIsWarnedAbout) {
  auto warnings = [](const std::string& text) {
    ::testing::internal::CaptureStderr();
    parse_scene(text, "dense", "/");
    return ::testing::internal::GetCapturedStderr();
  };
  EXPECT_EQ(warnings(ball_at(0.0)), "");
  const std::string dense = warnings(ball_at(0.0, "[1e5, 1e5, 1e5]"));
  EXPECT_NE(dense.find("dense: /objects/0: the shortest mean free path of its medium, 1e-05 mm, is only 0.5 ray "
                       "offsets long"),
            std::string::npos)
      << dense;
  EXPECT_EQ(std::count(dense.begin(), dense.end(), '\n'), 1) << dense;
}

}  // namespace
}  // namespace lucent
