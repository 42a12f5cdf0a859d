// test_radiosity_maps.cpp: image tests of the radiosity-maps method on llvmpipe (small resolutions):
// (a) light bleeds past the terminator, farther in red than in blue; (b) same seed, same image; (c) golden
// image; (d) converged scattered radiosity of a flat slab equals the model's total diffuse reflectance; (e) on
// llvmpipe, an N whose loops would pass the driver's loop budget is one clear error naming method.N.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "bssrdf/model.h"
#include "image_compare.h"
#include "lucent/error.h"
#include "lucent/lucent.h"
#include "platform/gl_capabilities.h"
#include "../test_paths.h"

namespace {

using lucent::ImageRGBA32F;
using lucent::ImageRGBA8;
using lucent::Scene;

struct Rendered {
  ImageRGBA32F radiance;
  ImageRGBA8 display;
};

Rendered render(const Scene& scene) {
  lucent::test::ensure_gl_context();
  lucent::OffscreenFramebuffer framebuffer(scene.render.width, scene.render.height);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < scene.render.frames; ++f)
    renderer.render(scene.camera, {framebuffer.id(), scene.render.width, scene.render.height});
  return {renderer.read_radiance(), renderer.read_display()};
}

// ---- (a) bleeding past the terminator ----------------------------------------------------------------------

Scene side_lit_sphere(const std::string& material) {
  return lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 22 }},
    "lights": [{{ "direction": [1, 0, 0], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 96, "material": "{}" }}],
    "method": {{ "K": 8, "N": 16, "map_size": 96, "light_map_size": 128, "specular": false }},
    "render": {{ "width": 96, "height": 96, "frames": 4 }} }})",
                                         material),
                             "side-lit sphere", ".");
}

// Distance past the terminator (in sphere radii) where a band falls below 10% of its terminator radiance.
double bleed_distance(const ImageRGBA32F& image, int band, std::ofstream& csv) {
  int row = image.height / 2;
  double world_per_pixel = 2.0 * 6.0 * std::tan(glm::radians(11.0)) / image.width;  // at the sphere's centre
  double x_terminator = (image.width - 1) / 2.0;
  double at_terminator = image.at(image.width / 2, row)[band];
  for (int x = image.width / 2; x < image.width; ++x) {
    double radius_fraction = (x - x_terminator) * world_per_pixel;
    double value = image.at(x, row)[band];
    csv << band << "," << radius_fraction << "," << value << "\n";
    if (image.at(x, row)[3] == 0.0f || value < 0.1 * at_terminator) return radius_fraction;
  }
  return 1.0;
}

TEST(RadiosityMaps, LightBleedsPastTerminatorFartherInRedThanBlue) {
  for (const char* material : {"Skimmilk", "Marble"}) {
    SCOPED_TRACE(material);
    Rendered r = render(side_lit_sphere(material));
    lucent::write_png(lucent::test::output_path(fmt::format("side_lit_{}.png", material)), r.display);
    std::ofstream csv(lucent::test::output_path(fmt::format("side_lit_{}_profile.csv", material)));
    csv << "band,distance_past_terminator_radii,radiance\n";
    double red = bleed_distance(r.radiance, 0, csv), blue = bleed_distance(r.radiance, 2, csv);
    RecordProperty("bleed_red", std::to_string(red));
    RecordProperty("bleed_blue", std::to_string(blue));
    EXPECT_GT(red, 0.05) << "no light in the shadowed half";
    EXPECT_GT(red, blue) << "red should bleed farther than blue (its sigma_tr is smaller)";
  }
}

// ---- (b) determinism -----------------------------------------------------------------------------------------

Scene small_default(unsigned seed, int samples = 8, int frames = 2) {
  return lucent::default_scene({"render.width=96", "render.height=64", fmt::format("render.frames={}", frames),
                                "method.K=6", fmt::format("method.N={}", samples), "method.map_size=64",
                                "method.light_map_size=128", fmt::format("render.seed={}", seed)});
}

TEST(RadiosityMaps, SameSeedGivesIdenticalImageAndOtherSeedDiffers) {
  ImageRGBA32F a = render(small_default(5)).radiance, b = render(small_default(5)).radiance;
  ImageRGBA32F c = render(small_default(6)).radiance;
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
}

// ---- progressive accumulation -----------------------------------------------------------------------------

// Relative standard deviation of red over the flat centre of the slab image (a noise measure).
double relative_noise(const ImageRGBA32F& image) {
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int y = image.height / 4; y < 3 * image.height / 4; ++y)
    for (int x = image.width / 4; x < 3 * image.width / 4; ++x, ++n) sum += image.at(x, y)[0], sum2 += double(image.at(x, y)[0]) * image.at(x, y)[0];
  double mean = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean;
}

TEST(RadiosityMaps, ProgressiveAccumulationConvergesAndRestartsOnSceneChange) {
  // A flat slab under normal incidence has a constant B: pixel-to-pixel spread is Monte Carlo noise, which must
  // fall as frames accumulate (ideally as 1/sqrt(frames): 16 frames -> 1/4; at least a factor 2.5 required).
  Scene scene = lucent::parse_scene(R"({
    "scale_mm": 10,
    "camera": { "eye": [0, 9, 0], "target": [0, 5, 0], "up": [0, 0, -1], "fov_y_deg": 8 },
    "lights": [{ "direction": [0, -1, 0], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "box", "size": [30, 10, 30], "material": "Marble" }],
    "method": { "K": 4, "N": 2, "map_size": 128, "light_map_size": 512, "specular": false },
    "render": { "width": 32, "height": 32, "tonemap": "linear" } })", "noise slab", ".");
  lucent::test::ensure_gl_context();
  lucent::OffscreenFramebuffer target(32, 32);
  lucent::Renderer renderer(scene);
  const lucent::RenderTarget framebuffer{target.id(), 32, 32};
  renderer.render(scene.camera, framebuffer);
  double noise_1 = relative_noise(renderer.read_radiance());
  lucent::Camera moved = scene.camera;
  for (int f = 1; f < 16; ++f) {
    moved.eye.x = 0.01f * static_cast<float>(f);  // only the camera moves: keep accumulating
    renderer.render(moved, framebuffer);
  }
  EXPECT_EQ(renderer.accumulated_frames(), 16);
  double noise_16 = relative_noise(renderer.read_radiance());
  RecordProperty("noise_1", std::to_string(noise_1));
  RecordProperty("noise_16", std::to_string(noise_16));
  EXPECT_LT(noise_16, noise_1 / 2.5) << noise_1 << " -> " << noise_16;

  renderer.scene().lights[0].radiance = glm::vec3(2.0f);  // a light change restarts accumulation
  renderer.scene_changed();
  renderer.render(scene.camera, framebuffer);
  EXPECT_EQ(renderer.accumulated_frames(), 1);
}

// ---- (c) golden image ----------------------------------------------------------------------------------------

TEST(RadiosityMaps, DefaultSceneMatchesGoldenImage) {
  // Tolerance (8-bit steps): mean |difference| <= 1.5, 99th percentile <= 12, and a mean signed difference
  // within +-0.5. The image is a Monte Carlo estimate with a fixed seed; another driver (or seed) moves the
  // noise: rendering seed 2 against the seed-1 golden stays within all three bounds. A systematic change does
  // not: 10% less translucent radiance moves the signed mean by about -1.5 and fails.
  std::string golden_path = std::string(LUCENT_TEST_DATA) + "/golden/default_96x64.png";
  ImageRGBA8 actual = render(small_default(1, 32, 4)).display;  // 128 samples per band and map: low noise
  if (std::getenv("LUCENT_UPDATE_GOLDEN")) {
    std::filesystem::create_directories(std::filesystem::path(golden_path).parent_path());
    lucent::write_png(golden_path, actual);
    GTEST_SKIP() << "golden image updated: " << golden_path;
  }
  ImageRGBA8 expected = lucent::read_png(golden_path);
  lucent::test::ImageDifference d = lucent::test::compare(actual, expected);
  bool ok = d.mean_abs <= 1.5 && d.percentile_99 <= 12.0 && std::abs(d.mean_signed) <= 0.5;
  if (!ok) {
    lucent::write_png(lucent::test::output_path("default_96x64.actual.png"), actual);
    lucent::write_png(lucent::test::output_path("default_96x64.diff.png"), lucent::test::difference_image(actual, expected));
  }
  EXPECT_TRUE(ok) << "mean " << d.mean_abs << " signed " << d.mean_signed << " p99 " << d.percentile_99 << " max " << d.max_abs
                  << "; actual and diff written to " << LUCENT_TEST_OUT;
}

// ---- (d) flat slab: converged radiosity = total diffuse reflectance ----------------------------------------

Scene slab(const std::string& model) {
  return lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [0, 9, 0], "target": [0, 5, 0], "up": [0, 0, -1], "fov_y_deg": 8 }},
    "lights": [{{ "direction": [0, -1, 0], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "box", "size": [30, 10, 30],
                  "material": {{ "preset": "Marble", "model": "{}" }} }}],
    "method": {{ "K": 8, "N": 32, "map_size": 128, "light_map_size": 2048, "specular": false }},
    "render": {{ "width": 32, "height": 32, "frames": 8, "tonemap": "linear" }} }})",
                                         model),
                             "slab", ".");
}

glm::dvec3 mean_radiance(const ImageRGBA32F& image) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += glm::dvec3(image.at(x, y)[0], image.at(x, y)[1], image.at(x, y)[2]);
  return sum / static_cast<double>(image.width * image.height);
}

// pi * integral over the plane of S_d (normal incidence, flat surface), per band: the model's total diffuse
// reflectance per unit transmitted irradiance. Integrated in mm with the same header code the shader runs.
double model_total_reflectance(int model, const lucent::Material& m, int band) {
  using namespace lucent::shader;
  BandMedium medium = make_band_medium(m.sigma_a[band], m.sigma_s[band], m.g[band]);
  const int n = 200000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    double u = (k + 0.5) / n, r = -std::log(1.0 - u) / medium.sigma_tr;
    double S = bssrdf_Sd(model, medium, m.eta, glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1),
                         glm::vec3(static_cast<float>(r), 0.0f, 0.0f), glm::vec3(0, 0, 1));
    sum += 2.0 * M_PI * r * S / (medium.sigma_tr * (1.0 - u)) / n;
  }
  return M_PI * sum;
}

TEST(RadiosityMaps, SlabRadiosityApproachesModelTotalReflectance) {
  // Tolerance 3% per band. Monte Carlo noise after 8 frames x 32 samples x the maps that see the top face is
  // ~0.5%. The larger part is a bias of the method: x_i snaps to light-map texel centres, and the directional
  // dipole peaks within d_r ~ D = 0.15 mm of x_i at normal incidence. Measured (red band, directional dipole):
  // -3.1% with 1024^2 texels of 0.43 mm, -1.2% with 2048^2 texels of 0.22 mm; so the test uses 2048.
  lucent::Material marble = lucent::material_from_preset(*lucent::find_material_preset("Marble"));
  float T = lucent::shader::fresnel_transmittance(marble.eta, 1.0f);
  for (int model : {LUCENT_MODEL_DIRECTIONAL_DIPOLE, LUCENT_MODEL_STANDARD_DIPOLE}) {
    SCOPED_TRACE(model == LUCENT_MODEL_STANDARD_DIPOLE ? "standard dipole" : "directional dipole");
    Scene scene = slab(model == LUCENT_MODEL_STANDARD_DIPOLE ? "standard" : "directional");
    glm::dvec3 L = mean_radiance(render(scene).radiance);
    for (int band = 0; band < 3; ++band) {
      // L_o = T(w_o) B / pi with B = L_light T(w_i) R_total and L_light = 1.
      double measured = M_PI * L[band] / (T * T);
      double expected = model_total_reflectance(model, marble, band);
      if (model == LUCENT_MODEL_STANDARD_DIPOLE) {
        float alpha_prime = marble.sigma_s[band] / (marble.sigma_s[band] + marble.sigma_a[band]);
        EXPECT_NEAR(expected,
                    lucent::shader::standard_dipole_total_Rd(alpha_prime, marble.eta) *
                        lucent::shader::standard_dipole_exit_normalization(marble.eta),
                    1e-3);
      }
      EXPECT_NEAR(measured, expected, 0.03 * expected) << "band " << band;
      RecordProperty(fmt::format("model{}_band{}_measured_over_expected", model, band), std::to_string(measured / expected));
    }
  }
}

// Three lights: a map texel's invocation runs 3 x (1 + 3 x (1 + N)) loop iterations, so N 4096 (the parameter's
// maximum) is refused and N 3554 is the largest within llvmpipe's loop budget of 32,000; it renders finite and as
// bright as N 256 in the mean (a cut loop drops the last light's samples: a third of the light or more).
TEST(RadiosityMaps, AnNPastTheDriverLoopBudgetIsOneErrorAndTheLargestUnderItRenders) {
  lucent::test::ensure_gl_context();
  if (!lucent::platform::current_capabilities().is_llvmpipe) GTEST_SKIP() << "only llvmpipe caps shader loops";
  auto render = [](int N) {
    lucent::Scene scene = lucent::parse_scene(fmt::format(R"({{
      "scale_mm": 10,
      "camera": {{ "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 22 }},
      "lights": [{{ "direction": [1, 0, -0.3], "radiance": [1, 1, 1] }},
                 {{ "direction": [-1, 0.2, -0.5], "radiance": [0.5, 0.5, 0.5] }},
                 {{ "direction": [0, -1, -0.4], "radiance": [0.5, 0.5, 0.5] }}],
      "objects": [{{ "shape": "sphere", "radius": 1, "segments": 48, "material": "Potato" }}],
      "method": {{ "name": "radiosity-maps", "K": 2, "N": {}, "map_size": 16, "light_map_size": 64, "vpls": 0,
                   "specular": false }},
      "render": {{ "width": 16, "height": 16, "frames": 1 }} }})",
                                                         N),
                                              "three-light sphere", ".");
    lucent::OffscreenFramebuffer framebuffer(16, 16);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {framebuffer.id(), 16, 16});
    return renderer.read_radiance();
  };
  try {
    render(4096);
    ADD_FAILURE() << "N 4096 with three lights rendered on llvmpipe";
  } catch (const lucent::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("radiosity-maps: N 4096 x 3 bands x 3 lights"), std::string::npos) << message;
    EXPECT_NE(message.find("lower method.N to 3554"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  const lucent::ImageRGBA32F largest = render(3554), reference = render(256);
  double sum[2] = {0.0, 0.0};
  int covered = 0;
  for (std::size_t i = 0; i < largest.pixels.size(); i += 4) {
    if (reference.pixels[i + 3] <= 0.0f) continue;  // background
    ++covered;
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(largest.pixels[i + c])) << "pixel " << i / 4;
      sum[0] += largest.pixels[i + c], sum[1] += reference.pixels[i + c];
    }
  }
  ASSERT_GT(covered, 20);
  fmt::print("N 3554 mean / N 256 mean = {:.4f} over {} pixels\n", sum[0] / sum[1], covered);
  EXPECT_NEAR(sum[0] / sum[1], 1.0, 0.05);
}

}  // namespace
