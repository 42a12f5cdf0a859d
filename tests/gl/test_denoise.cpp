// test_denoise.cpp: the denoising stage after the method (src/denoise/), on what it must not change and on what it
// must improve, each against values independent of the filter:
//   - a region of constant radiance stays constant to float (any weighting of equal values returns them);
//   - nothing crosses an object's edge: a black opaque slab beside a glowing back-lit translucent one, coplanar and
//     facing the same way (so that only the object id separates them), stays exactly black;
//   - after a camera translation the first frame reuses the reprojected history: closer to the new view's converged
//     image than a restart, and without ghosts (a noise-free render: every pixel its own surface's value, also where
//     the move uncovers the floor);
//   - still frames flicker less (the mean frame-to-frame change), and a converged image is left as it is, within its
//     noise, per pixel (the filter's weight fades as frames accumulate).
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "../test_support.h"
#include "lucent/lucent.h"

namespace {

using lucent::ImageRGBA32F;

lucent::Scene make_scene(const std::string& json) {
  lucent::test::ensure_gl_context();
  return lucent::parse_scene(json, "denoise test", ".");
}

// `frames` frames of the scene from `camera`, the radiance after the last one.
ImageRGBA32F render(const lucent::Scene& scene, int frames) {
  lucent::OffscreenFramebuffer framebuffer(scene.render.width, scene.render.height);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < frames; ++f) renderer.render(scene.camera, {framebuffer.id(), scene.render.width, scene.render.height});
  return renderer.read_radiance();
}

lucent::Scene with_denoise(lucent::Scene scene, bool enabled, int iterations = 5) {
  scene.denoise.set("enabled", enabled);
  scene.denoise.set("iterations", static_cast<double>(iterations));
  return scene;
}

double luminance(const ImageRGBA32F& image, std::size_t pixel) {
  const float* p = &image.pixels[4 * pixel];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// A marble-like sphere on an opaque floor under a slanted light, rendered by the walk (one path per pixel a frame).
constexpr const char* kSphereOnFloor = R"({
  "scale_mm": 10,
  "camera": { "eye": [0.3, 1.0, 3.2], "target": [0, -0.1, 0], "fov_y_deg": 36 },
  "lights": [{ "direction": [0.5, -1, -0.6], "radiance": [2, 2, 2] }],
  "objects": [{ "shape": "sphere", "radius": 0.8, "segments": 32,
                "material": { "sigma_a": [0.003, 0.006, 0.012], "sigma_s": [2.2, 2.4, 2.6], "g": 0, "eta": 1.4 } },
              { "shape": "plane", "extent": [6, 6], "translate": [0, -0.8, 0], "albedo": [0.6, 0.55, 0.5] }],
  "method": { "name": "random-walk", "samples_per_frame": 1 },
  "render": { "width": 40, "height": 30, "background": [0, 0, 0] } })";

double rms_difference(const ImageRGBA32F& a, const ImageRGBA32F& b, const std::vector<std::size_t>& pixels) {
  double sum = 0.0;
  for (std::size_t p : pixels)
    for (int c = 0; c < 3; ++c) {
      const double d = a.pixels[4 * p + c] - b.pixels[4 * p + c];
      sum += d * d;
    }
  return std::sqrt(sum / (3.0 * static_cast<double>(pixels.size())));
}

// A tilted opaque plane under a directional light has one radiance everywhere (Lambert); a sphere in front of it
// is another object with other values. The filter must return the plane's value to float in every plane pixel,
// including those beside the sphere.
TEST(Denoise, ConstantRadianceStaysConstant) {
  const lucent::Scene scene = make_scene(R"({
    "camera": { "eye": [0, 1.5, 4], "target": [0, 0, 0], "fov_y_deg": 40 },
    "lights": [{ "direction": [0.2, -1, -0.3], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "plane", "extent": [10, 10], "albedo": [0.7, 0.5, 0.3] },
                { "shape": "sphere", "radius": 0.5, "translate": [0, 0.5, 0], "albedo": [0.1, 0.2, 0.9] }],
    "method": { "name": "diffuse-wrap" },
    "render": { "width": 48, "height": 36, "background": [0, 0, 0] } })");
  // Five frames: from the fourth the noise level comes from the frames' spread (none here), not the neighbours'.
  const ImageRGBA32F raw = render(with_denoise(scene, false), 5);
  const ImageRGBA32F denoised = render(with_denoise(scene, true), 5);
  // The plane's radiance: the most common value of the image.
  const float* plane = nullptr;
  int best = 0;
  for (std::size_t p = 0; p < raw.pixels.size() / 4; p += 7) {
    int same = 0;
    for (std::size_t q = 0; q < raw.pixels.size() / 4; ++q) same += raw.pixels[4 * q] == raw.pixels[4 * p] ? 1 : 0;
    if (same > best) best = same, plane = &raw.pixels[4 * p];
  }
  ASSERT_TRUE(plane != nullptr);
  ASSERT_GT(plane[0], 0.0f);
  int plane_pixels = 0, changed = 0;
  for (std::size_t p = 0; p < raw.pixels.size() / 4; ++p) {
    bool on_plane = true;
    for (int c = 0; c < 3; ++c) on_plane = on_plane && raw.pixels[4 * p + c] == plane[c];
    if (!on_plane) continue;
    ++plane_pixels;
    for (int c = 0; c < 3; ++c)
      if (std::fabs(denoised.pixels[4 * p + c] - plane[c]) > 1e-4f * plane[c]) ++changed;  // float rounding: 1e-5
  }
  EXPECT_GT(plane_pixels, 600);
  EXPECT_EQ(changed, 0) << "of " << plane_pixels << " plane pixels";
}

// A thin translucent slab lit from behind glows; an opaque slab beside it in the same plane, facing the camera
// away from the light, is black. Same normal, same plane: only the object id keeps the glow off the black slab.
TEST(Denoise, NothingCrossesAnObjectsEdge) {
  const lucent::Scene scene = make_scene(R"({
    "scale_mm": 10,
    "camera": { "eye": [0, 0, 4], "target": [0, 0, 0], "fov_y_deg": 30 },
    "lights": [{ "direction": [0, 0, 1], "radiance": [3, 3, 3] }],
    "objects": [{ "shape": "box", "size": [1, 1.4, 0.1], "translate": [-0.5, 0, 0],
                  "material": { "sigma_a": [0.01, 0.02, 0.04], "sigma_s": [1.5, 1.5, 1.5], "g": 0, "eta": 1.3 } },
                { "shape": "box", "size": [1, 1.4, 0.1], "translate": [0.5, 0, 0], "albedo": [0.8, 0.8, 0.8] }],
    "method": { "name": "random-walk", "samples_per_frame": 1 },
    "render": { "width": 40, "height": 30, "background": [0, 0, 0] } })");
  const ImageRGBA32F raw = render(with_denoise(scene, false), 1);
  const ImageRGBA32F denoised = render(with_denoise(scene, true), 1);
  const int width = scene.render.width, height = scene.render.height;
  double glow = 0.0, black_raw = 0.0, black_denoised = 0.0;
  int black_pixels = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y * width + x);
      if (raw.pixels[4 * p + 3] <= 0.0f) continue;  // not on an object
      if (x < width / 2 - 1) glow += luminance(raw, p);
      if (x > width / 2 + 1) {
        ++black_pixels;
        black_raw += luminance(raw, p);
        black_denoised += luminance(denoised, p);
      }
    }
  ASSERT_GT(glow, 1.0) << "the translucent slab should glow";
  ASSERT_GT(black_pixels, 100);
  EXPECT_EQ(black_raw, 0.0);
  EXPECT_EQ(black_denoised, 0.0) << "light crossed from the glowing slab onto the black one";
}

// 16 still frames, then the camera moves sideways; the first frame after the move (history reprojected, no spatial
// filter) against a restart's first frame, both against the new view's 32-frame average, over every pixel.
TEST(Denoise, ReprojectedHistoryAfterACameraTranslation) {
  lucent::Scene scene = make_scene(kSphereOnFloor);
  scene.render.seed = 7;
  const int width = scene.render.width, height = scene.render.height;
  lucent::Camera moved = scene.camera;
  moved.eye += glm::vec3(0.25f, 0.0f, 0.0f);
  moved.target += glm::vec3(0.25f, 0.0f, 0.0f);

  lucent::Scene at_new_view = scene;
  at_new_view.camera = moved;
  at_new_view.render.seed = 99;
  const ImageRGBA32F converged = render(with_denoise(at_new_view, false), 32);
  at_new_view.render.seed = 8;
  const ImageRGBA32F restart = render(with_denoise(at_new_view, false), 1);

  lucent::OffscreenFramebuffer framebuffer(width, height);
  lucent::Renderer renderer(with_denoise(scene, true, /*iterations=*/0));
  for (int f = 0; f < 16; ++f) renderer.render(scene.camera, {framebuffer.id(), width, height});
  renderer.render(moved, {framebuffer.id(), width, height});
  const ImageRGBA32F reused = renderer.read_radiance();
  EXPECT_EQ(renderer.last_frame_timings().stat("denoise_history", 0.0), 17.0);

  std::vector<std::size_t> covered;
  for (std::size_t p = 0; p < converged.pixels.size() / 4; ++p)
    if (converged.pixels[4 * p + 3] > 0.0f) covered.push_back(p);
  ASSERT_GT(covered.size(), 600u);
  const double error_restart = rms_difference(restart, converged, covered);
  const double error_reused = rms_difference(reused, converged, covered);
  fmt::print("RMSE against 32 frames: restart {:.4f}, reprojected history {:.4f} ({:.2f}x)\n", error_restart,
             error_reused, error_restart / error_reused);
  EXPECT_LT(error_reused, 0.5 * error_restart);
}

// No ghosts: a blue sphere on a red floor, both opaque and Lambertian under white light (diffuse-wrap, no noise), so
// that each surface has one chromaticity whatever its shading. After a sideways move every pixel must keep its own
// surface's chromaticity (the history of another surface, say the sphere's on the floor the move uncovers, would
// change it), to float. Its brightness is the reprojection's bilinear interpolation of the shading, which smooths
// steep gradients (the sphere's dark rim, the contact shadow): most pixels within 2%.
TEST(Denoise, NoGhostsWhereAMoveUncoversTheFloor) {
  lucent::Scene scene = make_scene(R"({
    "camera": { "eye": [0, 1.0, 4], "target": [0, 0, 0], "fov_y_deg": 30 },
    "lights": [{ "direction": [0, -0.25, -1], "radiance": [2, 2, 2] }],
    "objects": [{ "shape": "sphere", "radius": 0.6, "albedo": [0.05, 0.1, 0.9] },
                { "shape": "plane", "extent": [20, 20], "translate": [0, -0.6, 0], "albedo": [0.9, 0.3, 0.1] }],
    "method": { "name": "diffuse-wrap", "specular": false },
    "render": { "width": 48, "height": 36, "background": [0, 0, 0] } })");
  const int width = scene.render.width, height = scene.render.height;
  lucent::Camera moved = scene.camera;
  moved.eye += glm::vec3(0.4f, 0.0f, 0.0f);
  moved.target += glm::vec3(0.4f, 0.0f, 0.0f);
  lucent::Scene at_new_view = scene;
  at_new_view.camera = moved;
  const ImageRGBA32F expected = render(with_denoise(at_new_view, false), 1);

  lucent::OffscreenFramebuffer framebuffer(width, height);
  lucent::Renderer renderer(with_denoise(scene, true, /*iterations=*/0));
  for (int f = 0; f < 4; ++f) renderer.render(scene.camera, {framebuffer.id(), width, height});
  renderer.render(moved, {framebuffer.id(), width, height});
  const ImageRGBA32F reused = renderer.read_radiance();
  EXPECT_EQ(renderer.last_frame_timings().stat("denoise_history", 0.0), 5.0);
  int covered = 0, ghosts = 0, within = 0;
  for (std::size_t p = 0; p < expected.pixels.size() / 4; ++p) {
    const float* e = &expected.pixels[4 * p];
    const float* r = &reused.pixels[4 * p];
    const float e_sum = e[0] + e[1] + e[2], r_sum = r[0] + r[1] + r[2];
    if (e[3] <= 0.0f || e_sum < 1e-4f) continue;
    ++covered;
    bool ghost = false;
    for (int c = 0; c < 3; ++c) ghost = ghost || std::fabs(r[c] / r_sum - e[c] / e_sum) > 1e-4f;
    ghosts += ghost ? 1 : 0;
    within += std::fabs(r_sum - e_sum) <= 0.02f * e_sum ? 1 : 0;
  }
  fmt::print("after the move: {} of {} pixels with another surface's colour; {} within 2% in brightness\n", ghosts,
             covered, within);
  EXPECT_GT(covered, 1000);
  EXPECT_EQ(ghosts, 0);
  EXPECT_GT(within, covered * 9 / 10);
}

// Flicker (the mean change between successive still frames, 1 to 31) and a converged image (32 frames, the fade
// at 2 frames: the filter's weight there is 2^2 / (2^2 + 32^2) = 0.4%): raw and denoised from one seed, so that
// all see the same paths.
TEST(Denoise, FlickersLessAndLeavesAConvergedImage) {
  lucent::Scene scene = make_scene(kSphereOnFloor);
  scene.render.seed = 21;
  const int width = scene.render.width, height = scene.render.height, frames = 32;
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  lucent::OffscreenFramebuffer framebuffer(width, height);
  lucent::Scene fading = with_denoise(scene, true);
  fading.denoise.set("fade_frames", 2.0);
  lucent::Renderer raw(with_denoise(scene, false)), denoised(with_denoise(scene, true)), faded(fading);
  ImageRGBA32F raw_previous, denoised_previous, faded_last;
  double raw_change = 0.0, denoised_change = 0.0;
  std::vector<double> sum(pixels * 3, 0.0), sum2(pixels * 3, 0.0), previous_average(pixels * 3, 0.0);
  for (int f = 0; f < frames; ++f) {
    raw.render(scene.camera, {framebuffer.id(), width, height});
    faded.render(scene.camera, {framebuffer.id(), width, height});
    const ImageRGBA32F r = raw.read_radiance();
    faded_last = faded.read_radiance();
    for (std::size_t i = 0; i < pixels * 3; ++i) {  // each frame's own estimate, for the per-pixel noise
      const std::size_t p = i / 3, c = i % 3;
      const double running = r.pixels[4 * p + c], v = running * (f + 1) - previous_average[i] * f;
      previous_average[i] = running;
      sum[i] += v, sum2[i] += v * v;
    }
    if (f < 32) {
      denoised.render(scene.camera, {framebuffer.id(), width, height});
      const ImageRGBA32F d = denoised.read_radiance();
      if (f > 0)
        for (std::size_t p = 0; p < pixels; ++p)
          for (int c = 0; c < 3; ++c) {
            raw_change += std::fabs(r.pixels[4 * p + c] - raw_previous.pixels[4 * p + c]);
            denoised_change += std::fabs(d.pixels[4 * p + c] - denoised_previous.pixels[4 * p + c]);
          }
      denoised_previous = d;
    }
    raw_previous = r;
  }
  fmt::print("mean frame-to-frame change over frames 1-31: raw {:.3g}, denoised {:.3g} ({:.1f}x less)\n", raw_change,
             denoised_change, raw_change / denoised_change);
  EXPECT_LT(denoised_change, raw_change / 5.0);

  // Converged: per pixel within 3 standard errors of the raw average but for what chance allows, image mean 0.5%.
  int outside = 0, compared = 0;
  double mean_raw = 0.0, mean_faded = 0.0;
  for (std::size_t i = 0; i < pixels * 3; ++i) {
    const std::size_t p = i / 3, c = i % 3;
    const double mean = sum[i] / frames;
    const double se = std::sqrt(std::max(0.0, (sum2[i] / frames - mean * mean) / (frames - 1)));
    mean_raw += raw_previous.pixels[4 * p + c], mean_faded += faded_last.pixels[4 * p + c];
    if (se <= 0.0) continue;
    ++compared;
    if (std::fabs(faded_last.pixels[4 * p + c] - raw_previous.pixels[4 * p + c]) > 3.0 * se + 1e-3 * mean) ++outside;
  }
  fmt::print("after {} frames: {} of {} pixel values beyond 3 standard errors of the raw average; image mean "
             "raw {:.5f}, denoised {:.5f}\n", frames, outside, compared, mean_raw / static_cast<double>(pixels * 3),
             mean_faded / static_cast<double>(pixels * 3));
  EXPECT_GT(compared, 1000);
  EXPECT_LT(outside, compared / 100);
  EXPECT_NEAR(mean_faded / mean_raw, 1.0, 0.005);
}

}  // namespace
