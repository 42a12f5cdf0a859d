// test_view_screenshot.cpp: `lucent view SCENE --frames N --screenshot` under Xvfb (llvmpipe, small window)
// against `lucent render` of the same scene, size and frames: the viewer renders through the library's passes,
// not a second renderer. Tolerance: mean |difference| <= 0.5 and 99th percentile <= 2 8-bit steps (the same
// passes on the same driver are expected to agree exactly; the slack is for driver-side nondeterminism). The
// comparison is shown able to fail: the image is not black, and a render with the light from the other side
// exceeds the tolerance. Failing comparisons write the images and a difference image to test-output/.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "gl/image_compare.h"
#include "../test_paths.h"

namespace lucent::test {
namespace {

constexpr double kMeanTolerance = 0.5;        // [8-bit steps]
constexpr double kPercentile99Tolerance = 2;  // [8-bit steps]
constexpr int kWidth = 160, kHeight = 120, kFrames = 4, kPanelWidth = 240;

// Small method settings so that llvmpipe on two cores renders each image in about a second.
const std::string kFast =
    " --set method.K=4 --set method.N=8 --set method.map_size=128 --set method.light_map_size=128"
    " --set method.vpl_map_size=64";
const std::string kScene = std::string(LUCENT_SCENES_DIR) + "/default.json";

std::string xvfb(const std::string& arguments) {
  return std::string(XVFB_RUN) + " -a -s \"-screen 0 1024x768x24\" " + LUCENT_CLI + " " + arguments;
}

CliResult run_shell(const std::string& command) {
  std::string full = command + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer;
  while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

bool within_tolerance(const ImageDifference& d) {
  return d.mean_abs <= kMeanTolerance && d.percentile_99 <= kPercentile99Tolerance;
}

void write_failure_images(const std::string& name, const ImageRGBA8& actual, const ImageRGBA8& expected) {
  write_png(output_path(name + "_actual.png"), actual);
  write_png(output_path(name + "_expected.png"), expected);
  write_png(output_path(name + "_diff.png"), difference_image(actual, expected));
}

class ViewScreenshot : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string size = " --width " + std::to_string(kWidth) + " --height " + std::to_string(kHeight);
    view_png_ = output_path("view_screenshot.png");
    window_png_ = output_path("view_window.png");
    render_png_ = output_path("view_render.png");
    other_png_ = output_path("view_render_other_light.png");
    saved_scene_ = output_path("view_saved_scene.json");
    view_ = run_shell(xvfb("view " + kScene + kFast + size + " --frames " + std::to_string(kFrames) + " --screenshot " +
                           view_png_ + " --screenshot-window " + window_png_ + " --save-scene " + saved_scene_ + " --panel-width " +
                           std::to_string(kPanelWidth)));
    std::string render_size = " --set render.width=" + std::to_string(kWidth) + " --set render.height=" + std::to_string(kHeight);
    render_ = run_cli("render " + kScene + kFast + render_size + " --frames " + std::to_string(kFrames) + " -q -o " + render_png_);
    other_ = run_cli("render " + kScene + kFast + render_size + " --frames " + std::to_string(kFrames) + " -q -o " + other_png_ +
                     " --set 'lights.0.direction=[-0.8,-0.45,-0.25]'");
  }
  static inline CliResult view_, render_, other_;
  static inline std::string view_png_, window_png_, render_png_, other_png_, saved_scene_;
};

TEST_F(ViewScreenshot, MatchesTheHeadlessRenderOfTheSameScene) {
  ASSERT_EQ(view_.exit_code, 0) << view_.output;
  ASSERT_EQ(render_.exit_code, 0) << render_.output;
  ImageRGBA8 view = read_png(view_png_), render = read_png(render_png_);
  ASSERT_EQ(view.width, kWidth);
  ASSERT_EQ(view.height, kHeight);
  ImageDifference d = compare(view, render);
  std::printf("view vs render: mean |d| %.3f, 99th percentile %.1f, max %d (8-bit steps)\n", d.mean_abs, d.percentile_99, d.max_abs);
  if (!within_tolerance(d)) write_failure_images("view_vs_render", view, render);
  EXPECT_LE(d.mean_abs, kMeanTolerance);
  EXPECT_LE(d.percentile_99, kPercentile99Tolerance);
}

TEST_F(ViewScreenshot, IsNotBlack) {
  ASSERT_EQ(view_.exit_code, 0) << view_.output;
  ImageRGBA8 view = read_png(view_png_);
  double sum = 0.0;
  for (std::size_t i = 0; i < view.pixels.size(); i += 4) sum += view.pixels[i] + view.pixels[i + 1] + view.pixels[i + 2];
  double mean = sum / (3.0 * kWidth * kHeight);
  EXPECT_GT(mean, 40.0) << "mean 8-bit value of the screenshot";
}

// The check can fail: the same scene lit from the other side is far outside the tolerance.
TEST_F(ViewScreenshot, ADifferentLightFailsTheTolerance) {
  ASSERT_EQ(view_.exit_code, 0) << view_.output;
  ASSERT_EQ(other_.exit_code, 0) << other_.output;
  ImageDifference d = compare(read_png(view_png_), read_png(other_png_));
  std::printf("view vs other light: mean |d| %.3f, 99th percentile %.1f\n", d.mean_abs, d.percentile_99);
  EXPECT_FALSE(within_tolerance(d));
  EXPECT_GT(d.mean_abs, 10.0 * kMeanTolerance);
}

// The window opens at the smallest integer scale of the view that gives the panel 480 rows (4 x 120) and shows the
// rendered view right of the panel, filling the window, each rendered pixel a 4x4 block (and the panel is drawn).
TEST_F(ViewScreenshot, TheWindowShowsTheViewBesideThePanel) {
  ASSERT_EQ(view_.exit_code, 0) << view_.output;
  ImageRGBA8 window = read_png(window_png_), view = read_png(view_png_);
  constexpr int kScale = 4;
  ASSERT_EQ(window.width, kPanelWidth + kScale * kWidth);
  ASSERT_EQ(window.height, kScale * kHeight);
  ImageRGBA8 region{kWidth, kHeight, std::vector<std::uint8_t>(static_cast<std::size_t>(kWidth) * kHeight * 4)};
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 4; ++c)
        region.at(x, y)[c] = c == 3 ? 255 : window.at(kPanelWidth + kScale * x + kScale - 1, kScale * y + kScale - 1)[c];
  ImageDifference d = compare(region, view);
  if (d.max_abs != 0) write_failure_images("view_window_region", region, view);
  EXPECT_EQ(d.max_abs, 0);
  int panel_pixels_lit = 0;  // ImGui text and frames
  for (int y = 0; y < window.height; ++y)
    for (int x = 0; x < kPanelWidth; ++x) panel_pixels_lit += window.at(x, y)[0] > 128;
  EXPECT_GT(panel_pixels_lit, 200);
}

// "Save scene as" writes the view's camera, size, method settings and frame count: `lucent render` of the saved
// file, with no options, reproduces the screenshot.
TEST_F(ViewScreenshot, TheSavedSceneRendersTheSameImage) {
  ASSERT_EQ(view_.exit_code, 0) << view_.output;
  std::string png = output_path("view_saved_scene_render.png");
  CliResult render = run_cli("render " + saved_scene_ + " -q -o " + png);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  ImageRGBA8 view = read_png(view_png_), again = read_png(png);
  ASSERT_EQ(again.width, kWidth);
  ASSERT_EQ(again.height, kHeight);
  ImageDifference d = compare(again, view);
  std::printf("saved scene render vs view: mean |d| %.3f, 99th percentile %.1f\n", d.mean_abs, d.percentile_99);
  if (!within_tolerance(d)) write_failure_images("view_saved_scene", again, view);
  EXPECT_LE(d.mean_abs, kMeanTolerance);
  EXPECT_LE(d.percentile_99, kPercentile99Tolerance);
}

// A window of another shape (400x300, a 240-pixel panel asked): the panel takes at most half the window (200), the
// 160x120 view is scaled by 1.25 into the 200x300 beside it and centred, background above and below; the view
// is still rendered at 160x120 (the screenshot). The same run saves the scene as a binary glTF.
TEST(ViewLayout, AViewInAWindowOfAnotherShapeIsScaledToFitAndCentred) {
  const std::string view_png = output_path("view_fit_view.png"), window_png = output_path("view_fit_window.png");
  const std::string glb = output_path("view_fit_scene.glb");
  std::filesystem::remove(glb);
  CliResult view = run_shell(xvfb("view " + kScene + kFast + " --width 160 --height 120 --window-width 400 "
                                  "--window-height 300 --panel-width 240 --frames 1 --screenshot " + view_png +
                                  " --screenshot-window " + window_png + " --save-scene " + glb));
  ASSERT_EQ(view.exit_code, 0) << view.output;
  {
    std::ifstream in(glb, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(bytes.substr(0, 4), "glTF") << glb;
    EXPECT_NE(bytes.find("KHR_lights_punctual"), std::string::npos) << glb;
    EXPECT_NE(bytes.find("\"cameras\""), std::string::npos) << glb;
  }
  const ImageRGBA8 window = read_png(window_png), rendered = read_png(view_png);
  ASSERT_EQ(window.width, 400);
  ASSERT_EQ(window.height, 300);
  EXPECT_EQ(rendered.width, 160);
  EXPECT_EQ(rendered.height, 120);
  // The view spans rows 75..224 of columns 200..399: the rows just outside it are the dark background (15, 15, 18
  // in 8 bits), every row inside it holds the image (the default scene has no pixel that dark).
  auto row_is_background = [&](int y) {
    for (int x = 200; x < 400; ++x)
      if (window.at(x, y)[0] > 20 || window.at(x, y)[1] > 20 || window.at(x, y)[2] > 24) return false;
    return true;
  };
  EXPECT_TRUE(row_is_background(0));
  EXPECT_TRUE(row_is_background(73));
  EXPECT_FALSE(row_is_background(76));
  EXPECT_FALSE(row_is_background(150));
  EXPECT_FALSE(row_is_background(223));
  EXPECT_TRUE(row_is_background(226));
  EXPECT_TRUE(row_is_background(299));
}

// A bad scene in --frames mode: exit 1 with the one line `lucent render` prints, no window left behind.
TEST(ViewErrors, BadSceneExitsWithTheRenderCommandsMessage) {
  std::string path = output_path("view_bad_scene.json");
  std::ofstream(path) << R"({"objects": [{"shape": "sphere", "material": {"sigma_a": [-1, 0, 0], "sigma_s": [1, 1, 1]}}]})";
  CliResult view = run_shell(xvfb("view " + path + " --frames 1 --screenshot " + output_path("view_bad.png")));
  CliResult render = run_cli("render " + path + " -q -o " + output_path("render_bad.png"));
  EXPECT_EQ(view.exit_code, 1) << view.output;
  EXPECT_EQ(render.exit_code, 1) << render.output;
  EXPECT_EQ(view.output, render.output);
  EXPECT_NE(view.output.find("/objects/0/material: sigma_a[0] = -1 is negative"), std::string::npos) << view.output;
}

}  // namespace
}  // namespace lucent::test
