// test_layered_stm.cpp: subsurface texture mapping (layered-stm) against physics derived here.
//
// A one-layer stack of thickness d over nothing, lit by a directional light of irradiance E at incidence theta_i,
// seen at theta_o, is a homogeneous slab; its single-scattered radiance, with the refraction and Fresnel factors the
// method applies (beam compression cos_i / cos_t on the way in, T / eta^2 on the way out) and the Schlick phase
// function with k = 1.55 g - 0.55 g^3, is
//
//   L = T(theta_o) / eta^2  sigma_s p(cos_s) E T(theta_i) cos_i / cos_tl  (1 / cos_tv)  (1 - e^{-sigma_t d mu}) / (sigma_t mu),
//   mu = 1 / cos_tl + 1 / cos_tv,
//
// cos_tl and cos_tv the cosines of the refracted light and view directions, cos_s the cosine between the light's
// direction of travel inside and the direction from the scattering point back toward P. The test computes it in
// double precision from Snell's law and the Fresnel equations written out below, not from the shader's headers.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "../cli_runner.h"
#include "image_compare.h"
#include "lucent/lucent.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = 16;
constexpr double kEta = 1.4;
constexpr double kDepthMm = 1.0;  // the stack's depth: the slab's thickness
constexpr double kIrradiance = 2.0;
constexpr std::array<double, 3> kSigmaS = {0.5, 1.0, 2.0}, kSigmaT = {1.0, 1.5, 4.0};  // [mm^-1]
constexpr double kG = 0.3;
// Light from 45 degrees in the x-y plane, camera at 30 degrees in the z-y plane (another azimuth, so the phase
// function's angle is not a mirror one).
const glm::dvec3 kLightTravel = glm::normalize(glm::dvec3(1.0, -1.0, 0.0));
const glm::dvec3 kToCamera = glm::dvec3(0.0, std::cos(kPi / 6.0), std::sin(kPi / 6.0));

double fresnel_reflectance(double eta, double cos_i) {
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5 * (parallel * parallel + perpendicular * perpendicular);
}

// Direction of travel d refracted into the medium below the plane y = 0 (normal +y), relative index eta.
glm::dvec3 refract_down(glm::dvec3 d, double eta) {
  const glm::dvec3 n(0.0, 1.0, 0.0);
  const double cos_i = -glm::dot(d, n);
  const double cos_t = std::sqrt(1.0 - (1.0 - cos_i * cos_i) / (eta * eta));
  return d / eta + (cos_i / eta - cos_t) * n;
}

std::array<double, 3> expected_radiance(double depth_mm) {
  const glm::dvec3 light_in = refract_down(kLightTravel, kEta), view_in = refract_down(-kToCamera, kEta);
  const double cos_i = -kLightTravel.y, cos_o = kToCamera.y, cos_tl = -light_in.y, cos_tv = -view_in.y;
  const double k = 1.55 * kG - 0.55 * kG * kG * kG;
  const double cos_s = glm::dot(light_in, -view_in);
  const double phase = (1.0 - k * k) / (4.0 * kPi * (1.0 - k * cos_s) * (1.0 - k * cos_s));
  const double E_in = kIrradiance * (1.0 - fresnel_reflectance(kEta, cos_i)) * cos_i / cos_tl;
  const double out = (1.0 - fresnel_reflectance(kEta, cos_o)) / (kEta * kEta);
  const double mu = 1.0 / cos_tl + 1.0 / cos_tv;
  std::array<double, 3> L{};
  for (std::size_t b = 0; b < 3; ++b)
    L[b] = out * kSigmaS[b] * phase * E_in / cos_tv * (1.0 - std::exp(-kSigmaT[b] * depth_mm * mu)) / (kSigmaT[b] * mu);
  return L;
}

// A 4 x 1 x 4 cm box (scale_mm 10: coefficients become per centimetre on the GPU), its top face at y = 0.5, seen
// from 40 cm away at 30 degrees over a 1 degree field: every pixel sees the top face's centre region. The box is
// thicker than the least-squares planes' radius (3 / sigma_t = 3 mm), which then lie in the top face.
lucent::ImageRGBA32F render_slab(const std::string& method_keys, int frames) {
  const glm::dvec3 eye = glm::dvec3(0.0, 0.5, 0.0) + 40.0 * kToCamera;
  const std::string json = fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [{}, {}, {}], "target": [0, 0.5, 0], "fov_y_deg": 1.0 }},
    "lights": [{{ "direction": [{}, {}, {}], "radiance": [{}, {}, {}] }}],
    "objects": [{{ "shape": "box", "size": [4, 1, 4],
                  "material": {{ "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "g": 0, "eta": {} }} }}],
    "method": {{ "name": "layered-stm", "depth": {}, "light_map_size": 256, "specular": false, {} }},
    "render": {{ "width": {}, "height": {}, "frames": {}, "seed": 3 }} }})",
                                       eye.x, eye.y, eye.z, kLightTravel.x, kLightTravel.y, kLightTravel.z, kIrradiance,
                                       kIrradiance, kIrradiance, kEta, kDepthMm, method_keys, kSize, kSize, frames);
  const lucent::Scene scene = lucent::parse_scene(json, "layered slab scene", lucent::test::output_path(""));
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < frames; ++f) renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
  return renderer.read_radiance();
}

std::array<double, 3> mean_radiance(const lucent::ImageRGBA32F& image) {
  std::array<double, 3> sum{};
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    EXPECT_GT(image.pixels[i + 3], 0.5f) << "pixel " << i / 4 << " does not show the slab";
    for (std::size_t b = 0; b < 3; ++b) sum[b] += image.pixels[i + b];
  }
  for (double& s : sum) s /= static_cast<double>(image.pixels.size() / 4);
  return sum;
}

std::string one_layer(double sigma_s_scale = 1.0) {
  return fmt::format(R"("maps": "uniform", "sigma_s": [[{}, {}, {}]], "sigma_t": [[{}, {}, {}]], "g": [[{}, {}, {}]])",
                     kSigmaS[0] * sigma_s_scale, kSigmaS[1] * sigma_s_scale, kSigmaS[2] * sigma_s_scale, kSigmaT[0],
                     kSigmaT[1], kSigmaT[2], kG, kG, kG);
}

// Jittered samples average to the integral: 16 samples, 32 frames. Measured on llvmpipe: ratios 0.9995, 0.9993, 0.9980 (the
// viewing direction varies by +-0.5 degrees over the image; the jitter's noise averages over 256 pixels x 32 frames).
// Tolerance 1%: dropping the exit's 1 / eta^2 (0.51), either Fresnel factor (0.97, 0.96) or the beam compression
// (cos_i / cos_tl = 0.83) fails it.
TEST(LayeredStm, OneLayerMatchesTheSlabsClosedFormSingleScattering) {
  lucent::test::ensure_gl_context();
  const std::array<double, 3> expected = expected_radiance(kDepthMm);
  const std::array<double, 3> L = mean_radiance(render_slab(one_layer() + R"(, "samples": 16, "jitter": true)", 32));
  for (std::size_t b = 0; b < 3; ++b) {
    std::printf("band %zu: layered-stm %.6f, closed form %.6f, ratio %.5f\n", b, L[b], expected[b], L[b] / expected[b]);
    EXPECT_NEAR(L[b] / expected[b], 1.0, 0.01) << "band " << b;
  }
}

// Two flat layers (a PNG map: layer 0 holds 0.4 of the depth, layer 1 the remaining 0.6): with flat layers Eqs.
// 11-14 are exact, so the march must reproduce the single-scattering integral over depth z,
//   L = T_o / eta^2 (1 / cos_tv) int sigma_s(z) p E_in e^{-tau(z) / cos_tl} e^{-tau(z) / cos_tv} dz,
// tau(z) the optical depth from the surface to z, evaluated here by a 200000-step midpoint rule. Isotropic layers.
// Measured on llvmpipe (128 midpoint samples): ratios 0.9982, 0.9996, 1.0001 (the layer boundary costs the midpoint
// rule its second order); a light path that ignored the upper layers
// (Eq. 14 without the sum over the layers above) gives 0.45, 0.85, 0.84.
TEST(LayeredStm, TwoFlatLayersMatchTheIntegralOverDepth) {
  lucent::test::ensure_gl_context();
  lucent::ImageRGBA8 map;
  map.width = map.height = 2;
  map.pixels.assign(4 * 4, 0);
  for (std::size_t i = 0; i < 4; ++i) map.pixels[4 * i] = 102, map.pixels[4 * i + 1] = 153;  // 0.4, 0.6
  const std::string map_path = lucent::test::output_path("layered_stm_flat_layers.png");
  lucent::write_png(map_path, map);
  const std::array<std::array<double, 3>, 2> sigma_s = {{{0.5, 1.0, 2.0}, {2.0, 0.4, 1.0}}};
  const std::array<std::array<double, 3>, 2> sigma_t = {{{1.0, 1.5, 4.0}, {3.0, 0.8, 1.5}}};
  const double split = kDepthMm * 102.0 / 255.0, bottom = kDepthMm * (102.0 + 153.0) / 255.0;
  const glm::dvec3 light_in = refract_down(kLightTravel, kEta), view_in = refract_down(-kToCamera, kEta);
  const double cos_i = -kLightTravel.y, cos_o = kToCamera.y, cos_tl = -light_in.y, cos_tv = -view_in.y;
  const double E_in = kIrradiance * (1.0 - fresnel_reflectance(kEta, cos_i)) * cos_i / cos_tl;
  const double out = (1.0 - fresnel_reflectance(kEta, cos_o)) / (kEta * kEta);
  std::array<double, 3> expected{};
  const int steps = 200000;
  for (std::size_t b = 0; b < 3; ++b) {
    double tau = 0.0, sum = 0.0;
    const double dz = bottom / steps;
    for (int i = 0; i < steps; ++i) {
      const double z = (i + 0.5) * dz;
      const int layer = z < split ? 0 : 1;
      const double tau_mid = tau + 0.5 * dz * sigma_t[layer][b];
      sum += sigma_s[layer][b] / (4.0 * kPi) * E_in * std::exp(-tau_mid * (1.0 / cos_tl + 1.0 / cos_tv)) * dz;
      tau += dz * sigma_t[layer][b];
    }
    expected[b] = out * sum / cos_tv;
  }
  const std::string keys = fmt::format(
      R"("maps": "{}", "samples": 128, "jitter": false, "sigma_s": [[{}, {}, {}], [{}, {}, {}]],
         "sigma_t": [[{}, {}, {}], [{}, {}, {}]])",
      map_path, sigma_s[0][0], sigma_s[0][1], sigma_s[0][2], sigma_s[1][0], sigma_s[1][1], sigma_s[1][2],
      sigma_t[0][0], sigma_t[0][1], sigma_t[0][2], sigma_t[1][0], sigma_t[1][1], sigma_t[1][2]);
  const std::array<double, 3> L = mean_radiance(render_slab(keys, 1));
  for (std::size_t b = 0; b < 3; ++b) {
    std::printf("band %zu: two layers %.6f, integral %.6f, ratio %.5f\n", b, L[b], expected[b], L[b] / expected[b]);
    EXPECT_NEAR(L[b] / expected[b], 1.0, 0.005) << "band " << b;
  }
}

// Midpoint sampling (no jitter) is the midpoint rule of the integral: its error falls as 1 / N^2.
TEST(LayeredStm, TheRayMarchConvergesAsSamplesGrow) {
  lucent::test::ensure_gl_context();
  const std::array<double, 3> expected = expected_radiance(kDepthMm);
  double previous = 1e30;
  for (int samples : {2, 8, 32, 128}) {
    const std::array<double, 3> L =
        mean_radiance(render_slab(one_layer() + fmt::format(R"(, "samples": {}, "jitter": false)", samples), 1));
    const double error = std::fabs(L[2] / expected[2] - 1.0);  // the optically thickest band
    std::printf("%d samples: relative error %.5f\n", samples, error);
    EXPECT_LT(error, previous) << samples << " samples";
    previous = error;
  }
  EXPECT_LT(previous, 0.002);
}

// Two uniform layers of half the depth each, and a third of zero thickness (a PNG map whose blue channel is 0).
std::string three_layers(const std::string& map, double layer1_green_sigma_s, double layer2_sigma_s) {
  return fmt::format(R"("maps": "{}", "samples": 16, "jitter": false,
      "sigma_s": [[0.5, 1.0, 2.0], [1.0, {}, 0.5], [{}, {}, {}]],
      "sigma_t": [[1.0, 1.5, 4.0], [2.0, 3.0, 3.0], [5.0, 5.0, 5.0]])",
                     map, layer1_green_sigma_s, layer2_sigma_s, layer2_sigma_s, layer2_sigma_s);
}

TEST(LayeredStm, ChangingOneLayerChangesOnlyWhatItShould) {
  lucent::test::ensure_gl_context();
  lucent::ImageRGBA8 map;
  map.width = map.height = 4;
  map.pixels.assign(16 * 4, 0);
  for (std::size_t i = 0; i < 16; ++i) map.pixels[4 * i] = map.pixels[4 * i + 1] = 128;
  const std::string map_path = lucent::test::output_path("layered_stm_two_layers.png");
  lucent::write_png(map_path, map);
  const auto base = mean_radiance(render_slab(three_layers(map_path, 1.0, 1.0), 1));
  // Layer 1's green scattering: green changes, red and blue not at all.
  const auto green = mean_radiance(render_slab(three_layers(map_path, 2.0, 1.0), 1));
  EXPECT_EQ(green[0], base[0]);
  EXPECT_EQ(green[2], base[2]);
  EXPECT_GT(green[1], base[1] * 1.05);
  // Layer 2 is nowhere: its coefficients change nothing.
  const auto absent = mean_radiance(render_slab(three_layers(map_path, 1.0, 4.0), 1));
  for (std::size_t b = 0; b < 3; ++b) EXPECT_EQ(absent[b], base[b]) << "band " << b;
  // Half the depth in layer 0 of the one-layer slab's coefficients: the radiance of a slab half as thick plus
  // what layer 1 adds below it, so more than the thinner slab alone.
  const auto thin = expected_radiance(0.5 * kDepthMm);
  EXPECT_GT(base[0], thin[0]);
}

TEST(LayeredStm, ABadLayerIsOneClearErrorNamingIt) {
  lucent::test::ensure_gl_context();
  std::string message;
  try {
    render_slab(R"("maps": "uniform", "sigma_s": [[1, 1, 1], [1, 1, 1], [2, 2, 2]],
                   "sigma_t": [[2, 2, 2], [2, 2, 2], [3, 1.5, 3]])", 1);
  } catch (const lucent::Error& e) {
    message = e.what();
  }
  EXPECT_EQ(message,
            "layered slab scene: /method/sigma_t/2: layer 2: sigma_t[1] = 1.5 mm^-1 is below sigma_s[1] = 2 mm^-1; "
            "extinction includes scattering (sigma_t = sigma_a + sigma_s)");
  message.clear();
  try {
    render_slab(R"("sigma_s": [[1, 1, 1], [1, 1, 1]], "sigma_t": [[2, 2, 2]])", 1);
  } catch (const lucent::Error& e) {
    message = e.what();
  }
  EXPECT_EQ(message, "layered slab scene: /method/sigma_t: 1 layers, but sigma_s has 2; give both for every layer");
  message.clear();
  try {
    render_slab(R"("maps": "no_such_maps.png")", 1);
  } catch (const lucent::Error& e) {
    message = e.what();
  }
  // Relative paths resolve against the scene file's folder (this scene has none).
  EXPECT_EQ(message, "layered slab scene: /method/maps: no_such_maps.png: cannot read PNG: No such file or directory");
  // From the command line: "lucent: <scene>: <where>: <problem>" on one line, exit status 1.
  const std::string scene = lucent::test::output_path("layered_bad_layer.json");
  std::ofstream(scene) << R"({"lights": [{"direction": [0, -1, 0], "radiance": [1, 1, 1]}],
    "objects": [{"shape": "sphere", "material": "Marble"}],
    "method": {"name": "layered-stm", "sigma_s": [[1, 1, 1], [4, 1, 1]], "sigma_t": [[2, 2, 2], [3, 2, 2]]}})";
  const lucent::test::CliResult r = lucent::test::run_cli("render -q -o " + lucent::test::output_path("bad.png") + " " + scene);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "lucent: " + scene + ": /method/sigma_t/1: layer 1: sigma_t[0] = 3 mm^-1 is below sigma_s[0] = 4 "
                      "mm^-1; extinction includes scattering (sigma_t = sigma_a + sigma_s)\n");
}

}  // namespace

namespace {

// The least-squares planes are refitted to the deformed mesh every frame: a bending lobe rendered at a quarter of
// its period matches the same lobe built already bent (scene_at_time: a static mesh, planes fitted to it once).
// Measured on llvmpipe: mean |difference| 0.42% of the mean radiance (the neighbour lists come from the pose at
// creation); fitting the planes only in the first frame (the rest pose, as the thesis precomputes them) gives 18%.
TEST(LayeredStm, PlanesFollowADeformingMesh) {
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = lucent::parse_scene(R"({
    "scale_mm": 10,
    "camera": { "eye": [0, 2, 8], "target": [0, 1.7, 0], "fov_y_deg": 32 },
    "lights": [{ "direction": [0.6, -0.35, -0.7], "radiance": [3, 3, 3] }],
    "objects": [{ "shape": "lathe", "segments": 48,
                  "profile": [[0, 0], [0.55, 0.05], [0.9, 0.5], [0.95, 1.6], [0.8, 2.7], [0.45, 3.3], [0, 3.4]],
                  "deform": { "type": "bend", "amplitude": 0.9, "period_s": 4.0 },
                  "material": { "sigma_a": [0.03, 0.1, 0.12], "sigma_s": [1.4, 1.0, 0.9], "g": 0, "eta": 1.4 } }],
    "method": { "name": "layered-stm", "samples": 16, "jitter": false, "depth": 3, "maps": "uniform",
                "fit_radius": 6, "light_map_size": 256, "specular": false },
    "render": { "width": 48, "height": 48, "frames": 1, "seed": 1 } })",
                                                  "bending lobe", ".");
  constexpr double kTime = 1.0;  // a quarter period: the largest bend
  const lucent::Scene bent = lucent::scene_at_time(scene, kTime);
  auto render = [](const lucent::Scene& s, bool animate) {
    lucent::OffscreenFramebuffer framebuffer(48, 48);
    lucent::Renderer renderer(s);
    renderer.render(s.camera, {framebuffer.id(), 48, 48});  // the rest pose (time 0)
    if (animate) renderer.set_time(kTime);
    renderer.render(s.camera, {framebuffer.id(), 48, 48});
    return renderer.read_radiance();
  };
  const lucent::ImageRGBA32F animated = render(scene, true), reference = render(bent, false);
  double difference = 0.0, total = 0.0;
  for (std::size_t i = 0; i < animated.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    difference += std::fabs(animated.pixels[i] - reference.pixels[i]);
    total += reference.pixels[i];
  }
  std::printf("bending lobe: mean |difference| / mean radiance = %.4f\n", difference / total);
  EXPECT_GT(total, 0.0);
  EXPECT_LT(difference / total, 0.01);
}

}  // namespace
