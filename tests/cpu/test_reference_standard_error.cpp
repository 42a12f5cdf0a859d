// test_reference_standard_error.cpp: the standard error a reference reports is the spread its mean really has.
// Independent renders with different seeds are draws of the mean: per band, the variance of the per-pixel mean
// over the seeds must agree with the mean of the claimed variances (standard error squared). Everything built on
// the standard error depends on it: compare's noise correction, reference merge, the refinement criterion.
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "lucent/scene.h"
#include "reference/reference_renderer.h"

namespace {

using namespace lucent;
using namespace lucent::reference;

// A chromatic, forward-scattering sphere on a grey floor, lit from the side: paths of every length, three bands
// of different noise, no fireflies (a heavy tail would make 16 seeds too few for any estimator).
// With `interior_light`, a point light inside the sphere instead: next-event estimation at the scattering vertices
// had infinite variance there (1/r^2 near the light); the flights' equiangular samples do not.
Scene seeds_scene(bool interior_light = false) {
  const std::string lights = interior_light
                                 ? R"({ "type": "point", "position": [0.15, 0.7, 0.1], "intensity": [2e-4, 2e-4, 2e-4] })"
                                 : R"({ "direction": [0.6, -0.6, -0.5], "radiance": [2, 2, 2] })";
  return parse_scene(R"({
    "scale_mm": 10,
    "camera": { "eye": [0, 1.0, 4.0], "target": [0, 0.6, 0], "fov_y_deg": 30 },
    "lights": [)" + lights + R"(],
    "objects": [{ "shape": "sphere", "radius": 0.6, "segments": 32, "translate": [0, 0.6, 0],
                  "material": { "sigma_a": [0.02, 0.05, 0.2], "sigma_s": [1.0, 0.8, 0.6], "g": [0.3, 0.3, 0.3],
                                "eta": 1.3 } },
                { "shape": "plane", "extent": [6, 6], "albedo": [0.5, 0.5, 0.5] }],
    "render": { "width": 32, "height": 32, "background": [0, 0, 0] } })",
                     "seeds", "/");
}

// LUCENT_SEED_BASE offsets the 16 seeds, to see the test's spread over independent sets of seeds.
int seed_base() {
  const char* base = std::getenv("LUCENT_SEED_BASE");
  return base ? std::atoi(base) : 0;
}

void expect_honest_standard_error(Integrator integrator, int spp, bool interior_light = false) {
  const Scene scene = seeds_scene(interior_light);
  constexpr int kSeeds = 16;
  std::vector<ReferenceImage> renders;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    ReferenceSettings settings;
    settings.integrator = integrator;
    settings.samples_per_pixel = spp;
    settings.seed = static_cast<std::uint64_t>(seed + seed_base());
    renders.push_back(render_reference(scene, settings));
  }
  const std::size_t pixels = renders[0].mean.pixels.size() / 4;
  for (int band = 0; band < 3; ++band) {
    double observed = 0.0, claimed = 0.0;  // summed over pixels: variance of the mean over seeds, mean of se^2
    for (std::size_t p = 0; p < pixels; ++p) {
      const std::size_t i = 4 * p + static_cast<std::size_t>(band);
      double sum = 0.0, sum2 = 0.0, se2 = 0.0;
      for (const ReferenceImage& r : renders) {
        sum += r.mean.pixels[i], sum2 += double(r.mean.pixels[i]) * r.mean.pixels[i];
        se2 += double(r.standard_error.pixels[i]) * r.standard_error.pixels[i];
      }
      const double mean = sum / kSeeds;
      observed += std::max(0.0, (sum2 - kSeeds * mean * mean) / (kSeeds - 1));
      claimed += se2 / kSeeds;
    }
    ASSERT_GT(claimed, 0.0);
    std::printf("%s %d spp, band %d: variance of the mean over seeds / claimed %.3f\n",
                std::string(to_string(integrator)).c_str(), spp, band, observed / claimed);
    // The ratio's own spread: the variance over 16 seeds is within sqrt(2 / 15) = 37% per pixel, and the claimed
    // variances are random too, which biases a ratio of sums upward where samples are few and heavy-tailed
    // (bssrdf at 16 spp: 1.00-1.09 over five sets of seeds, up to 1.09 at 64 spp). Over eight sets of seeds
    // (LUCENT_SEED_BASE 0 to 700) at these sample counts: volpath 0.95-1.07, bssrdf 0.96-1.03, every band; 10% is
    // the acceptance bound.
    EXPECT_NEAR(observed / claimed, 1.0, 0.10)
        << fmt::format("{} {} spp, band {}: variance of the mean over {} seeds {:.4g}, claimed {:.4g}",
                       to_string(integrator), spp, band, kSeeds, observed, claimed);
  }
}

TEST(ReferenceStandardError, VolpathClaimsTheSpreadOfItsMeanOverSeeds) {
  expect_honest_standard_error(Integrator::Volpath, 32);
}

TEST(ReferenceStandardError, VolpathClaimsTheSpreadOfItsMeanOverSeedsWithALightInsideTheMedium) {
  expect_honest_standard_error(Integrator::Volpath, 32, true);
}

TEST(ReferenceStandardError, BssrdfClaimsTheSpreadOfItsMeanOverSeeds) {
  expect_honest_standard_error(Integrator::Bssrdf, 256);
}

}  // namespace
