// test_viewer_camera.cpp: the viewer's pure parts without GL: orbit/pan/zoom keep what they must keep, the
// camera readout pastes back into a scene file as the same camera, the file watcher notices saves.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "../test_support.h"
#include "viewer/file_watcher.h"
#include "viewer/orbit_camera.h"

namespace lucent::viewer {
namespace {

Camera example_camera() {
  Camera c;
  c.eye = {0.0f, 1.6f, 5.2f};
  c.target = {0.0f, 0.55f, 0.0f};
  c.fov_y_deg = 38.0f;
  return c;
}

TEST(OrbitCamera, OrbitKeepsTargetAndDistance) {
  OrbitCamera camera(example_camera());
  float distance = camera.distance();
  for (int i = 0; i < 50; ++i) camera.orbit(37.0f, -23.0f);
  EXPECT_EQ(camera.camera().target, example_camera().target);
  EXPECT_NEAR(camera.distance(), distance, 1e-4f * distance);
  EXPECT_TRUE(camera.moved());
}

TEST(OrbitCamera, HorizontalDragYawsAboutUp) {
  OrbitCamera camera(example_camera());
  float height = camera.camera().eye.y;
  camera.orbit(300.0f, 0.0f);  // 90 degrees
  EXPECT_NEAR(camera.camera().eye.y, height, 1e-5f);
  glm::vec3 before = example_camera().eye - example_camera().target, after = camera.camera().eye - camera.camera().target;
  EXPECT_NEAR(glm::dot(glm::vec2(before.x, before.z), glm::vec2(after.x, after.z)), 0.0f, 1e-4f);
}

TEST(OrbitCamera, PitchStopsShortOfThePoles) {
  OrbitCamera camera(example_camera());
  camera.orbit(0.0f, 100000.0f);
  glm::vec3 dir = glm::normalize(camera.camera().eye - camera.camera().target);
  EXPECT_LT(std::abs(glm::dot(dir, glm::vec3(0, 1, 0))), 0.99999f);
  EXPECT_GT(glm::length(glm::cross(dir, glm::vec3(0, 1, 0))), 1e-3f);  // the look-at matrix stays defined
  camera.orbit(0.0f, -200000.0f);
  dir = glm::normalize(camera.camera().eye - camera.camera().target);
  EXPECT_GT(glm::length(glm::cross(dir, glm::vec3(0, 1, 0))), 1e-3f);
}

TEST(OrbitCamera, PanMovesEyeAndTargetTogetherByThePixelsAtTheTarget) {
  OrbitCamera camera(example_camera());
  float view_height = 400.0f;
  camera.pan(-view_height, 0.0f, view_height);  // a whole view height to the left: the scene moves right
  glm::vec3 shift = camera.camera().target - example_camera().target;
  EXPECT_EQ(camera.camera().eye - example_camera().eye, shift);
  float expected = 2.0f * glm::length(example_camera().eye - example_camera().target) * std::tan(glm::radians(19.0f));
  EXPECT_NEAR(glm::length(shift), expected, 1e-4f * expected);
  EXPECT_NEAR(shift.y, 0.0f, 1e-5f);  // horizontal drag: along the camera's right axis
}

TEST(OrbitCamera, ZoomScalesDistanceAndResetRestoresTheExactCamera) {
  OrbitCamera camera(example_camera());
  float distance = camera.distance();
  camera.zoom(1.0f);
  EXPECT_NEAR(camera.distance(), 0.9f * distance, 1e-5f);
  camera.zoom(-2.0f);
  EXPECT_NEAR(camera.distance(), distance / 0.9f, 1e-4f);
  camera.orbit(10.0f, 5.0f);
  camera.reset();
  EXPECT_FALSE(camera.moved());
  EXPECT_EQ(camera.camera().eye, example_camera().eye);
}

// The readout pasted into a scene file gives the same floats (the loader renormalises up; it is unit already).
TEST(CameraReadout, PastesBackIntoASceneAsTheSameCamera) {
  OrbitCamera camera(example_camera());
  camera.orbit(123.0f, -45.0f);
  camera.pan(17.0f, 9.0f, 300.0f);
  camera.zoom(0.7f);
  std::string readout = camera_readout(camera.camera());
  EXPECT_EQ(readout.rfind("\"camera\": {", 0), 0u) << readout;
  std::string text = "{ " + readout + R"(, "objects": [{"shape": "sphere"}] })";
  Scene scene = parse_scene(text, "readout.json", ".");
  EXPECT_EQ(scene.camera.eye, camera.camera().eye);
  EXPECT_EQ(scene.camera.target, camera.camera().target);
  EXPECT_EQ(scene.camera.fov_y_deg, camera.camera().fov_y_deg);
  EXPECT_NEAR(glm::length(scene.camera.up - camera.camera().up), 0.0f, 1e-6f);
}

TEST(FileWatcher, NoticesEachChangeOnce) {
  test::TempFile file(".json");
  { std::ofstream(file.path()) << "{}"; }
  FileWatcher watcher(file.path());
  EXPECT_FALSE(watcher.changed());
  { std::ofstream(file.path()) << "{ \"scale_mm\": 2 }"; }  // a different size: seen even within one mtime tick
  EXPECT_TRUE(watcher.changed());
  EXPECT_FALSE(watcher.changed());
  std::filesystem::last_write_time(file.path(), std::filesystem::last_write_time(file.path()) + std::chrono::seconds(2));
  EXPECT_TRUE(watcher.changed());
  std::filesystem::remove(file.path());  // an editor replacing the file: gone for a moment, not a change
  EXPECT_FALSE(watcher.changed());
  { std::ofstream(file.path()) << "{ \"scale_mm\": 3 }"; }
  EXPECT_TRUE(watcher.changed());
}

TEST(FileWatcher, WithoutAPathNothingChanges) {
  FileWatcher none;
  EXPECT_FALSE(none.active());
  EXPECT_FALSE(none.changed());
}

}  // namespace
}  // namespace lucent::viewer
