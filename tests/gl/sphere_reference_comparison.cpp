// sphere_reference_comparison.cpp: see sphere_reference_comparison.h.
#include "sphere_reference_comparison.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "image_compare.h"
#include "lucent/lucent.h"
#include "reference/reference_renderer.h"

namespace lucent::test {
namespace {

constexpr int kSphereSize = 48;
constexpr int kBlock = 4;

double band_mean(const ImageRGBA32F& image, std::size_t i) {
  return (static_cast<double>(image.pixels[i]) + image.pixels[i + 1] + image.pixels[i + 2]) / 3.0;
}

}  // namespace

std::string sphere_scene_json(const std::string& method_object, const std::string& model, int size, int frames,
                              int seed) {
  return fmt::format(R"({{
    "scale_mm": 1,
    "camera": {{ "eye": [0, 0, 6], "target": [0, 0, 0], "fov_y_deg": 24 }},
    "lights": [{{ "direction": [-0.8, -0.3, -0.5], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 64,
                  "material": {{ "sigma_a": [0.05, 0.08, 0.12], "sigma_s": [2.0, 2.2, 2.5], "g": 0, "eta": 1.3,
                                 "model": "{}" }} }}],
    "method": {{ {} }},
    "render": {{ "width": {}, "height": {}, "frames": {}, "seed": {} }} }})",
                     model, method_object, size, size, frames, seed);
}

SphereComparison compare_sphere_with_reference(const std::string& method, const std::string& method_keys,
                                               const std::string& model, int frames, int reference_spp) {
  ensure_gl_context();
  const std::string json =
      sphere_scene_json(fmt::format(R"("name": "{}", {})", method, method_keys), model, kSphereSize, frames, 7);
  const Scene scene = parse_scene(json, "sphere comparison scene", ".");
  OffscreenFramebuffer framebuffer(kSphereSize, kSphereSize);
  Renderer renderer(scene);
  for (int f = 0; f < frames; ++f) renderer.render(scene.camera, {framebuffer.id(), kSphereSize, kSphereSize});
  const ImageRGBA32F ours = renderer.read_radiance();
  reference::ReferenceSettings settings;
  settings.integrator = reference::Integrator::Bssrdf;
  settings.samples_per_pixel = reference_spp;
  const ImageRGBA32F theirs = reference::render_reference(scene, settings).mean;

  SphereComparison out;
  int n = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); i += 4) {
    if (ours.pixels[i + 3] <= 0.5f) continue;
    out.mean += band_mean(ours, i), out.reference_mean += band_mean(theirs, i);
    ++n;
  }
  if (n == 0 || out.reference_mean <= 0.0) return out;
  out.mean /= n, out.reference_mean /= n;
  out.relative_mean_error = (out.mean - out.reference_mean) / out.reference_mean;
  // Per block of kBlock x kBlock pixels wholly on the sphere: the reference's per-pixel noise (about 26% at 64 spp)
  // averages down by the block's pixel count.
  double lit_reference = 0.0, squared = 0.0;
  for (int by = 0; by + kBlock <= kSphereSize; by += kBlock)
    for (int bx = 0; bx + kBlock <= kSphereSize; bx += kBlock) {
      double a = 0.0, b = 0.0;
      bool inside = true;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x) {
          const std::size_t i = 4 * (static_cast<std::size_t>(y) * kSphereSize + static_cast<std::size_t>(x));
          inside = inside && ours.pixels[i + 3] > 0.5f;
          a += band_mean(ours, i), b += band_mean(theirs, i);
        }
      a /= kBlock * kBlock, b /= kBlock * kBlock;
      if (!inside || b < 0.2 * out.reference_mean) continue;
      squared += (a - b) * (a - b), lit_reference += b;
      out.max_relative = std::max(out.max_relative, std::fabs(a - b) / b);
      ++out.lit_blocks;
    }
  if (out.lit_blocks > 0) out.relative_rmse = std::sqrt(squared / out.lit_blocks) / (lit_reference / out.lit_blocks);
  return out;
}

void expect_sphere_agrees(const std::string& method, const std::string& method_keys, const std::string& model,
                          double mean_tolerance, double rmse_tolerance, double max_tolerance) {
  const SphereComparison c = compare_sphere_with_reference(method, method_keys, model, 8, 1024);
  fmt::print("{}, {} dipole: mean {:.5f}, bssrdf reference {:.5f}, relative error {:+.4f}; lit region ({} 4x4 blocks): "
             "relative RMSE {:.4f}, max relative {:.4f}\n",
             method, model, c.mean, c.reference_mean, c.relative_mean_error, c.lit_blocks, c.relative_rmse,
             c.max_relative);
  ASSERT_GT(c.lit_blocks, 40);
  EXPECT_LE(std::fabs(c.relative_mean_error), mean_tolerance) << method << ", " << model;
  EXPECT_LE(c.relative_rmse, rmse_tolerance) << method << ", " << model;
  EXPECT_LE(c.max_relative, max_tolerance) << method << ", " << model;
}

}  // namespace lucent::test
