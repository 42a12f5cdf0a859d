// test_image_metrics.cpp: the comparison metrics of `lucent compare` and `lucent bench` on images with known
// differences, and the reference renderer's resume (2 + 2 samples equal 4 samples).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image/image_metrics.h"
#include "lucent/error.h"
#include "lucent/scene.h"
#include "reference/embree_scene.h"
#include "reference/integrators.h"
#include "reference/reference_renderer.h"
#include "transport/rng.h"

namespace {

using lucent::ImageRGBA32F;

ImageRGBA32F constant(int w, int h, float r, float g, float b) {
  ImageRGBA32F image{w, h, std::vector<float>(static_cast<std::size_t>(w * h) * 4, 1.0f)};
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) image.pixels[i] = r, image.pixels[i + 1] = g, image.pixels[i + 2] = b;
  return image;
}

TEST(ImageMetrics, KnownDifferences) {
  ImageRGBA32F reference = constant(8, 4, 0.5f, 0.25f, 1.0f);
  ImageRGBA32F shifted = constant(8, 4, 0.5f + 0.1f, 0.25f, 1.0f - 0.2f);
  lucent::ImageError e = lucent::image_error(shifted, reference);
  EXPECT_NEAR(e.rmse[0], 0.1, 1e-6);
  EXPECT_NEAR(e.rmse[1], 0.0, 1e-9);
  EXPECT_NEAR(e.rmse[2], 0.2, 1e-6);
  EXPECT_NEAR(e.rmse_rgb, std::sqrt(0.01 + 0.04), 1e-6);  // Dal Corso et al.'s sqrt(dr^2 + dg^2 + db^2)
  EXPECT_NEAR(e.mean_error, (0.1 - 0.2) / 3.0, 1e-6);
  EXPECT_NEAR(e.psnr_db, 10.0 * std::log10(1.0 / ((0.01 + 0.04) / 3.0)), 1e-4);  // peak 1 (the reference's max)
  EXPECT_EQ(lucent::image_error(reference, reference).rmse_rgb, 0.0);
}

TEST(ImageMetrics, ReferenceNoiseAndMeanErrorStandardError) {
  ImageRGBA32F a = constant(10, 10, 1.0f, 1.0f, 1.0f), b = a, se = constant(10, 10, 0.3f, 0.3f, 0.3f);
  lucent::ImageError e = lucent::image_error(a, b, &se);
  EXPECT_NEAR(e.reference_noise_rms, 0.3, 1e-6);
  EXPECT_NEAR(e.mean_error_se, 0.3 / std::sqrt(300.0), 1e-6);  // 300 independent channel values
}

TEST(ImageMetrics, SizeMismatchIsAnError) {
  EXPECT_THROW(lucent::image_error(constant(2, 2, 0, 0, 0), constant(3, 2, 0, 0, 0)), std::exception);
}

// A NaN compared as no error at all (RMSE nan, PSNR 1e9 and a noise-corrected RMSE of 0 in bench): every metric
// refuses non-finite values, naming the image, the pixel and the band.
TEST(ImageMetrics, NonFiniteValuesAreErrorsNamingThePixel) {
  const ImageRGBA32F good = constant(4, 3, 0.5f, 0.5f, 0.5f), se = constant(4, 3, 0.01f, 0.01f, 0.01f);
  auto message = [&](const ImageRGBA32F& a, const ImageRGBA32F& b, const ImageRGBA32F* s) {
    try {
      lucent::image_error(a, b, s);
    } catch (const lucent::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ImageRGBA32F nan_image = good;
  nan_image.pixels[4 * (2 * 4 + 1) + 1] = std::nanf("");  // pixel (1, 2), green
  EXPECT_EQ(message(nan_image, good, nullptr),
            "the image has a non-finite value nan at pixel (1, 2), green; no error metric is computed over it");
  ImageRGBA32F inf_reference = good;
  inf_reference.pixels[2] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(message(good, inf_reference, nullptr),
            "the reference has a non-finite value inf at pixel (0, 0), blue; no error metric is computed over it");
  ImageRGBA32F bad_se = se;
  bad_se.pixels[4 * 3] = -0.5f;
  EXPECT_EQ(message(good, good, &bad_se), "the reference's standard error has a negative value -0.5 at pixel (3, 0), "
                                          "red; no error metric is computed over it");
  bad_se.pixels[4 * 3] = std::nanf("");
  EXPECT_NE(message(good, good, &bad_se).find("non-finite value nan at pixel (3, 0), red"), std::string::npos);
  EXPECT_THROW(lucent::display_error(nan_image, good, 0.0f), lucent::Error);
  EXPECT_EQ(message(good, good, &se), "no error");
}

// Values too large for the tone curve's float arithmetic display as white, not as NaN.
TEST(ImageMetrics, HugeValuesDisplayAsWhite) {
  const ImageRGBA32F huge = constant(2, 2, 1e38f, 3e30f, 1e7f), white = constant(2, 2, 1.0f, 1.0f, 1.0f);
  const ImageRGBA32F shown = lucent::tonemapped(huge, 0.0f);
  for (float v : shown.pixels) EXPECT_TRUE(std::isfinite(v));
  EXPECT_NEAR(shown.pixels[0], lucent::tonemapped(constant(1, 1, 1e6f, 1e6f, 1e6f), 0.0f).pixels[0], 1e-6f);
  const lucent::ImageError e = lucent::display_error(huge, white, 0.0f);
  EXPECT_TRUE(std::isfinite(e.rmse_rgb));
}

TEST(ReferenceRenderer, ResumingAddsSamplesExactly) {
  lucent::Scene scene = lucent::parse_scene(R"({
    "scale_mm": 10, "camera": { "eye": [0, 0, 5], "target": [0, 0, 0], "fov_y_deg": 30 },
    "lights": [{ "direction": [0.6, -0.8, 0], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "sphere", "radius": 1, "segments": 24, "material": "Potato" }],
    "render": { "width": 8, "height": 6 } })", "resume", ".");
  for (auto integrator : {lucent::reference::Integrator::Bssrdf, lucent::reference::Integrator::Volpath}) {
    lucent::reference::ReferenceSettings settings;
    settings.integrator = integrator;
    settings.samples_per_pixel = 4;
    auto whole = lucent::reference::render_reference(scene, settings);
    settings.samples_per_pixel = 2;
    auto half = lucent::reference::render_reference(scene, settings);
    auto resumed = lucent::reference::render_reference(scene, settings, &half);
    ASSERT_EQ(resumed.samples_per_pixel, 4);
    for (std::size_t i = 0; i < whole.mean.pixels.size(); ++i)
      EXPECT_NEAR(resumed.mean.pixels[i], whole.mean.pixels[i], 1e-5 * std::abs(whole.mean.pixels[i]) + 1e-7)
          << "value " << i;
  }
}

// A stop must not wait for a pass: at thousands of samples per pixel a pass of a few rows runs for seconds. With
// 8000 samples already done the first pass holds 1000; its first chunk (where stop and progress are next polled)
// must hold a small part of it, and a stop there keeps the previous samples only.
TEST(ReferenceRenderer, StopIsPolledWithinLargePasses) {
  lucent::Scene scene = lucent::parse_scene(R"({
    "scale_mm": 10, "camera": { "eye": [0, 0, 5], "target": [0, 0, 0], "fov_y_deg": 30 },
    "lights": [{ "direction": [0.6, -0.8, 0], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "sphere", "radius": 1, "segments": 24, "material": "Potato" }],
    "render": { "width": 8, "height": 6 } })", "stop", ".");
  lucent::reference::ReferenceImage previous;
  previous.samples_per_pixel = 8000;
  previous.mean = {8, 6, std::vector<float>(8 * 6 * 4, 0.25f)};
  for (std::size_t i = 3; i < previous.mean.pixels.size(); i += 4) previous.mean.pixels[i] = 1.0f;  // alpha
  previous.standard_error = {8, 6, std::vector<float>(8 * 6 * 4, 0.0f)};
  lucent::reference::ReferenceSettings settings;
  settings.integrator = lucent::reference::Integrator::Bssrdf;
  settings.samples_per_pixel = 1000;
  std::vector<double> fractions;
  int polls = 0;
  settings.progress = [&](double fraction) { fractions.push_back(fraction); };
  settings.stop_requested = [&] { return ++polls == 2; };
  const auto image = lucent::reference::render_reference(scene, settings, &previous);
  EXPECT_EQ(polls, 2);
  ASSERT_EQ(fractions.size(), 1u);
  EXPECT_GT(fractions[0], 0.0);
  EXPECT_LT(fractions[0], 0.01) << "the first chunk held " << fractions[0] * 1000 << " of the pass's 1000 samples";
  EXPECT_EQ(image.samples_per_pixel, 8000);
  EXPECT_EQ(image.mean.pixels, previous.mean.pixels);
}

// Without jitter the renderer traces each pixel's centre ray once and hands the hit to the integrator; pixels whose
// ray misses get the background without sampling. Both must give what the integrators give when they trace the
// camera ray themselves, sample by sample with the same random streams.
TEST(ReferenceRenderer, SharedCentreHitAndBackgroundPixelsEqualPerSampleTracing) {
  lucent::Scene scene = lucent::parse_scene(R"({
    "scale_mm": 10, "camera": { "eye": [0, 0, 5], "target": [0, 0, 0], "fov_y_deg": 30 },
    "lights": [{ "direction": [0.6, -0.8, 0], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "sphere", "radius": 1, "segments": 24, "material": "Potato" }],
    "render": { "width": 8, "height": 6, "background": [0.2, 0.3, 0.4] } })", "centre", ".");
  lucent::reference::EmbreeScene rt(scene);
  lucent::reference::ReferenceScene rs{scene, rt};
  const lucent::reference::SphereJumpBank jump_bank(lucent::reference::ReferenceSettings{}.seed);
  rs.jump_bank = &jump_bank;  // the renderer's sphere jumps draw from the same banks
  for (auto integrator : {lucent::reference::Integrator::Bssrdf, lucent::reference::Integrator::Volpath}) {
    lucent::reference::ReferenceSettings settings;
    settings.integrator = integrator;
    settings.samples_per_pixel = 3;
    auto image = lucent::reference::render_reference(scene, settings);
    auto radiance = integrator == lucent::reference::Integrator::Volpath ? lucent::reference::volpath_radiance
                                                                         : lucent::reference::bssrdf_radiance;
    int background_pixels = 0;
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x) {
        const std::size_t pixel = static_cast<std::size_t>(y * 8 + x);
        glm::dvec3 origin, direction, sum(0.0);
        lucent::reference::camera_ray(scene.camera, 8, 6, x + 0.5, y + 0.5, origin, direction);
        for (int sample = 0; sample < 3; ++sample) {
          lucent::reference::Rng rng = lucent::reference::Rng::for_path(settings.seed, pixel, static_cast<std::uint64_t>(sample));
          lucent::reference::PathRecord record;
          record.sample = sample;
          sum += radiance(rs, origin, direction, rng, nullptr, &record);
        }
        if (!rt.intersect(origin, direction).hit()) ++background_pixels;
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(image.mean.pixels[4 * pixel + static_cast<std::size_t>(c)], sum[c] / 3.0, 1e-6 * std::abs(sum[c]) + 1e-9)
              << "pixel " << x << "," << y << " band " << c;
      }
    EXPECT_GT(background_pixels, 0);
    EXPECT_LT(background_pixels, 48);
    EXPECT_EQ(image.mean.pixels[2], 0.4f);  // corner pixel: the background, exactly, with no noise
    EXPECT_EQ(image.standard_error.pixels[2], 0.0f);
  }
}

}  // namespace
