// test_multipole_slab.cpp: light through a thin slab lit from behind, by the per-pixel integration of eq. 9 (shared
// with radiosity-maps) with the multipole model, against exact transport; the half-space model on the same slab
// shows what the test tells apart.
//
// A slab 2 reduced mean free paths thick (sigma_t' = 10 mm^-1, 0.2 mm; 4 mm wide, g = 0, eta 1.3; reduced albedo
// 0.99, 0.97, 0.95 per band), lit by one directional light from straight below and seen straight down at its centre,
// where it is an infinite flat slab under uniform irradiance E. There the diffusely transmitted exitance is
// M = T12(0) E T with T the slab's diffuse transmittance per refracted power (unscattered light excluded: it leaves
// along the light's direction, which no camera ray follows), and L = T21(0) M / (pi (1 - 2 C1(1/eta))). T comes from
// the slab transport of `lucent slab` (photon Monte Carlo, 2e5 photons per band: standard errors under 0.5%), nothing
// from the model or a rendering.
//
// Tolerance 5% per band (the model's diffusion error on transmittance at these albedos is 1-4%, docs/models/
// multipole.md). Measured on llvmpipe (N 1024, 512^2 light map, 4 frames): 0.992, 1.010, 1.030. The standard dipole,
// which reads the light that crossed as reflectance at the slab's thickness: 0.954, 0.695, 0.583 (asserted further
// off in every band, and by more than 25% in one).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "bssrdf/fresnel.h"
#include "image_compare.h"
#include "lucent/lucent.h"
#include "lucent/scene_writer.h"
#include "transport/slab.h"

namespace {

constexpr int kSize = 8;
constexpr double kSigmaT = 10.0;  // [mm^-1], g = 0
constexpr double kAlbedo[3] = {0.99, 0.97, 0.95};
constexpr double kEta = 1.3;
constexpr double kIrradiance = 2.0;

lucent::ImageRGBA32F render_slab(const char* model) {
  const std::string json = fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [0, 3.01, 0], "target": [0, 0.01, 0], "up": [0, 0, -1], "fov_y_deg": 1.91 }},
    "lights": [{{ "direction": [0, 1, 0], "radiance": [{4}, {4}, {4}] }}],
    "objects": [{{ "shape": "box", "size": [0.4, 0.02, 0.4],
                  "material": {{ "sigma_a": [{0}, {1}, {2}], "sigma_s": [{5}, {6}, {7}], "g": 0, "eta": {3},
                                "model": "{8}", "thickness_mm": 0.2 }} }}],
    "method": {{ "name": "per-pixel", "N": 1024, "light_map_size": 512, "specular": false }},
    "render": {{ "width": {9}, "height": {9}, "frames": 4, "seed": 1 }} }})",
                                       kSigmaT * (1.0 - kAlbedo[0]), kSigmaT * (1.0 - kAlbedo[1]),
                                       kSigmaT * (1.0 - kAlbedo[2]), kEta, kIrradiance, kSigmaT * kAlbedo[0],
                                       kSigmaT * kAlbedo[1], kSigmaT * kAlbedo[2], model, kSize);
  const lucent::Scene scene = lucent::parse_scene(json, "multipole slab scene", ".");
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < 4; ++f) renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
  return renderer.read_radiance();
}

// Rendered radiance over exact transport's, per band.
std::array<double, 3> ratios(const char* model) {
  lucent::test::ensure_gl_context();
  const lucent::ImageRGBA32F image = render_slab(model);
  const float eta = static_cast<float>(kEta);
  const double exit = lucent::shader::fresnel_transmittance(eta, 1.0f) /
                      (M_PI * 4.0 * static_cast<double>(lucent::shader::fresnel_c_phi(1.0f / eta)));
  std::array<double, 3> out{};
  for (std::size_t b = 0; b < 3; ++b) {
    lucent::reference::SlabConfig config;
    config.albedo = kAlbedo[b], config.eta = kEta, config.thickness = 2.0;
    config.photons = 200000, config.seed = 4343;
    const lucent::reference::SlabResult exact = lucent::reference::simulate_slab(config);
    const double T = (exact.transmittance.mean - exact.unscattered_transmittance.mean) /
                     (1.0 - exact.specular_reflectance.mean);
    const double expected = lucent::shader::fresnel_transmittance(eta, 1.0f) * kIrradiance * T * exit;
    double sum = 0.0;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) sum += image.pixels[i + b];
    out[b] = sum / static_cast<double>(image.pixels.size() / 4) / expected;
    std::printf("%s, band %zu: transmitted radiance / exact = %.4f (T = %.4f)\n", model, b, out[b], T);
  }
  return out;
}

TEST(MultipoleSlab, LightThroughAThinSlabIsExactTransport) {
  const std::array<double, 3> multipole = ratios("multipole");
  for (std::size_t b = 0; b < 3; ++b) EXPECT_NEAR(multipole[b], 1.0, 0.05) << "band " << b;
  const std::array<double, 3> standard = ratios("standard");
  double worst = 0.0;
  for (std::size_t b = 0; b < 3; ++b) {
    EXPECT_LT(std::abs(multipole[b] - 1.0), std::abs(standard[b] - 1.0)) << "band " << b;
    worst = std::max(worst, std::abs(standard[b] - 1.0));
  }
  EXPECT_GT(worst, 0.25);
}

// A glTF thin-walled material (KHR_materials_diffuse_transmission, no volume) says what its surface reflects and
// transmits diffusely: R = (1 - f) B and T = f D. lucent renders it as a multipole sheet (docs/materials.md); a 40 mm
// square sheet of it, 0.5 mm thick, seen at its centre under one light from above and then one from below, must show
// them: L = T12(0) E X T21(0) / (pi 4 C_phi(1 / eta)) for X = R, T (the model's totals are per refracted power, as
// in the slab test above). Tolerance 6% per band. Measured on llvmpipe: see the printed ratios.
lucent::ImageRGBA32F render_sheet(const std::string& gltf, float light_y) {
  const std::string json = fmt::format(R"({{
    "scale_mm": 10,
    "camera": {{ "eye": [0, 3.01, 0], "target": [0, 0.01, 0], "up": [0, 0, -1], "fov_y_deg": 1.91 }},
    "lights": [{{ "direction": [0, {1}, 0], "radiance": [{2}, {2}, {2}] }}],
    "objects": [{{ "mesh": "{0}", "material": "from_mesh" }}],
    "method": {{ "name": "per-pixel", "N": 1024, "light_map_size": 512, "specular": false }},
    "render": {{ "width": {3}, "height": {3}, "frames": 4, "seed": 1 }} }})",
                                       gltf, light_y, kIrradiance, kSize);
  const lucent::Scene scene = lucent::parse_scene(json, "sheet scene", ".");
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  for (int f = 0; f < 4; ++f) renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
  return renderer.read_radiance();
}

TEST(MultipoleSlab, AThinWalledGltfSheetReflectsAndTransmitsWhatTheFileSays) {
  lucent::test::ensure_gl_context();
  lucent::TriangleMesh quad;  // 4 x 4 scene units in the xz plane, facing +y
  quad.positions = {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}};
  quad.normals.assign(4, glm::vec3(0, 1, 0));
  quad.indices = {0, 1, 2, 0, 2, 3};
  const nlohmann::json material = nlohmann::json::parse(R"({"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.5, 0.4, 1]},
    "extensions": {"KHR_materials_ior": {"ior": 1.5},
      "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.3, "diffuseTransmissionColorFactor": [0.8, 0.6, 0.4]}},
    "extras": {"lucent": {"thickness_mm": 0.5}}})");
  const std::string path = lucent::test::output_path("thin_walled_sheet.gltf");
  lucent::write_gltf(path, quad, material);
  const float eta = 1.5f;
  const double factor = lucent::shader::fresnel_transmittance(eta, 1.0f) * kIrradiance *
                        lucent::shader::fresnel_transmittance(eta, 1.0f) /
                        (M_PI * 4.0 * static_cast<double>(lucent::shader::fresnel_c_phi(1.0f / eta)));
  const std::array<double, 3> R{0.42, 0.35, 0.28}, T{0.24, 0.18, 0.12};  // (1 - 0.3) B and 0.3 D
  for (const auto& [light_y, expected, what] : {std::tuple{-1.0f, R, "reflected"}, std::tuple{1.0f, T, "transmitted"}}) {
    const lucent::ImageRGBA32F image = render_sheet(path, light_y);
    for (std::size_t b = 0; b < 3; ++b) {
      double sum = 0.0;
      for (std::size_t i = 0; i < image.pixels.size(); i += 4) sum += image.pixels[i + b];
      const double ratio = sum / static_cast<double>(image.pixels.size() / 4) / (factor * expected[b]);
      std::printf("thin-walled sheet, %s, band %zu: radiance / the file's = %.4f\n", what, b, ratio);
      EXPECT_NEAR(ratio, 1.0, 0.06) << what << " band " << b;
    }
  }
}

}  // namespace
