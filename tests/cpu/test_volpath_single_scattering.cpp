// test_volpath_single_scattering.cpp: volpath restricted to one scattering event (ReferenceSettings::max_scatter =
// 1, `lucent reference --max-scatter 1`) against the closed-form single-scattered radiance of a homogeneous slab of
// thickness d over nothing, lit by a directional light of irradiance E at theta_i and seen at theta_o through a
// refractive boundary (isotropic phase function):
//
//   L = T(theta_o) / eta^2  sigma_s / (4 pi)  E T(theta_i) cos_i / cos_tl  (1 / cos_tv)  (1 - e^{-sigma_t d mu}) / (sigma_t mu),
//   mu = 1 / cos_tl + 1 / cos_tv.
//
// The slab's bottom face reflects a little of the view ray back (Fresnel, inside): paths that scatter after it are
// single scattering too, but not in the formula; with sigma_t d = 3 they add about 1e-3 of L. Measured: ratio 0.9992
// +- 0.0015 (200000 paths); counting one event too many (>= replaced by >) gives 1.53.
#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "lucent/scene.h"
#include "reference/embree_scene.h"
#include "transport/estimate.h"
#include "reference/integrators.h"

namespace {

using namespace lucent;
using namespace lucent::reference;

constexpr double kEta = 1.4, kSigmaS = 2.0, kSigmaT = 3.0, kDepth = 1.0, kIrradiance = 2.0;  // mm, mm^-1

double fresnel_reflectance(double eta, double cos_i) {
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5 * (parallel * parallel + perpendicular * perpendicular);
}

double refracted_cosine(double cos_i) { return std::sqrt(1.0 - (1.0 - cos_i * cos_i) / (kEta * kEta)); }

Estimate single_scattering(int max_scatter, int paths) {
  const Scene scene = parse_scene(fmt::format(R"({{
    "scale_mm": 1,
    "lights": [{{ "direction": [0.70710678, -0.70710678, 0], "radiance": [{0}, {0}, {0}] }}],
    "objects": [{{ "shape": "box", "size": [40, {1}, 40], "translate": [0, {2}, 0],
                  "material": {{ "sigma_a": [{3}, {3}, {3}], "sigma_s": [{4}, {4}, {4}], "g": 0, "eta": {5} }} }}] }})",
                                              kIrradiance, kDepth, -0.5 * kDepth, kSigmaT - kSigmaS, kSigmaS, kEta),
                                  "slab", ".");
  EmbreeScene rt(scene);
  const ReferenceScene rs{scene, rt, max_scatter};
  const glm::dvec3 to_camera(0.0, std::cos(M_PI / 6.0), std::sin(M_PI / 6.0));
  Accumulator acc;
  for (int i = 0; i < paths; ++i) {
    Rng rng(5, static_cast<std::uint64_t>(i));
    const glm::dvec3 target(rng.uniform() - 0.5, 0.0, rng.uniform() - 0.5);
    acc.add(volpath_radiance(rs, target + 10.0 * to_camera, -to_camera, rng).x);
  }
  return acc.estimate();
}

TEST(Volpath, MaxScatterOneMatchesTheSlabsClosedFormSingleScattering) {
  const double cos_i = std::sqrt(0.5), cos_o = std::cos(M_PI / 6.0);
  const double cos_tl = refracted_cosine(cos_i), cos_tv = refracted_cosine(cos_o), mu = 1.0 / cos_tl + 1.0 / cos_tv;
  const double expected = (1.0 - fresnel_reflectance(kEta, cos_o)) / (kEta * kEta) * kSigmaS / (4.0 * M_PI) *
                          kIrradiance * (1.0 - fresnel_reflectance(kEta, cos_i)) * cos_i / cos_tl / cos_tv *
                          (1.0 - std::exp(-kSigmaT * kDepth * mu)) / (kSigmaT * mu);
  const Estimate single = single_scattering(1, 200000);
  std::printf("volpath, one scattering event: %.6f +- %.6f, closed form %.6f (ratio %.4f)\n", single.mean,
              single.standard_error, expected, single.mean / expected);
  EXPECT_NEAR(single.mean, expected, 3.0 * single.standard_error + 3e-3 * expected);
  // More events add light: two scattering events, and no limit.
  const Estimate twice = single_scattering(2, 50000), all = single_scattering(0, 50000);
  EXPECT_GT(twice.mean, single.mean + 3.0 * (twice.standard_error + single.standard_error));
  EXPECT_GT(all.mean, twice.mean);
}

}  // namespace
