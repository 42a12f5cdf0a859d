// test_volpath_index_matched.cpp: light that reaches a medium vertex or an opaque surface through an index-matched
// (eta = 1) medium. Nothing bends the ray there, so the light arrives along the straight line, attenuated by the
// medium's transmittance between the points where the line enters and leaves it. (volpath used to stop the
// shadow ray at the first surface of any object: an index-matched bunny came out 1.5% darker than Blender Cycles,
// the light through its front ear to the back one, through the head to the neck and back, lost;
// docs/references.md, "Cross-check with Blender Cycles".)
//
// The scenes: a directional light straight down (irradiance E) through an absorbing index-matched plate B
// (sigma_a = 0.7 mm^-1, 1 mm thick; a trace of scattering, 1e-4 mm^-1, as materials need sigma_s > 0) onto
//  - a scattering slab A, seen from below: every light path into A crosses B once, vertically, so the radiance
//    with B is the radiance without it times e^{-sigma_t d} (the same camera paths: with B, a path that leaves A
//    upward enters B, where it only scatters with probability 1e-4);
//  - an opaque Lambertian floor (albedo 0.5), seen from below B: radiance albedo / pi E e^{-sigma_t d}.
// Before the fix both came out 0.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "lucent/scene.h"
#include "reference/embree_scene.h"
#include "transport/estimate.h"
#include "reference/integrators.h"

namespace {

using namespace lucent;
using namespace lucent::reference;

constexpr double kSunIrradiance = 2.0, kPlateSigmaA = 0.7, kPlateSigmaS = 1e-4, kPlateThickness = 1.0;  // mm^-1, mm

std::string plate(bool with_plate) {
  if (!with_plate) return "";
  return fmt::format(R"(, {{ "shape": "box", "size": [60, {0}, 60], "translate": [0, 3, 0],
      "material": {{ "sigma_a": [{1}, {1}, {1}], "sigma_s": [{2}, {2}, {2}], "g": 0, "eta": 1 }} }})",
                     kPlateThickness, kPlateSigmaA, kPlateSigmaS);
}

Scene scene_with(const std::string& receiver, bool with_plate) {
  return parse_scene(fmt::format(R"({{
    "scale_mm": 1,
    "lights": [{{ "direction": [0, -1, 0], "radiance": [{0}, {0}, {0}] }}],
    "objects": [{1}{2}] }})",
                                 kSunIrradiance, receiver, plate(with_plate)),
                     "index-matched", ".");
}

// Mean radiance of `paths` camera paths from below toward random points of the plane y = y_target.
Estimate radiance_from_below(const Scene& scene, double y_target, int paths) {
  EmbreeScene rt(scene);
  const ReferenceScene rs{scene, rt};
  const glm::dvec3 up = glm::normalize(glm::dvec3(0.3, 1.0, 0.1));
  Accumulator acc;
  for (int i = 0; i < paths; ++i) {
    Rng rng(17, static_cast<std::uint64_t>(i));
    const glm::dvec3 target(10.0 * rng.uniform() - 5.0, y_target, 10.0 * rng.uniform() - 5.0);
    acc.add(volpath_radiance(rs, target - 10.0 * up, up, rng).x);
  }
  return acc.estimate();
}

TEST(Volpath, IndexMatchedMediumInTheLightsWayAttenuatesTheLightToAMedium) {
  const std::string slab = R"({ "shape": "box", "size": [40, 2, 40], "translate": [0, -1, 0],
      "material": { "sigma_a": [0.05, 0.05, 0.05], "sigma_s": [1, 1, 1], "g": 0.5, "eta": 1 } })";
  const Estimate open = radiance_from_below(scene_with(slab, false), -2.0, 20000);
  const Estimate shaded = radiance_from_below(scene_with(slab, true), -2.0, 20000);
  const double expected = std::exp(-(kPlateSigmaA + kPlateSigmaS) * kPlateThickness);
  std::printf("slab under an index-matched plate: %.6f +- %.6f, without %.6f +- %.6f: ratio %.6f, e^-sigma_t d %.6f\n",
              shaded.mean, shaded.standard_error, open.mean, open.standard_error, shaded.mean / open.mean, expected);
  ASSERT_GT(open.mean, 0.0);
  EXPECT_NEAR(shaded.mean / open.mean, expected, 1e-3 * expected);
}

TEST(Volpath, IndexMatchedMediumInTheLightsWayAttenuatesTheLightToAnOpaqueSurface) {
  const std::string floor = R"({ "shape": "plane", "extent": [40, 40], "albedo": [0.5, 0.5, 0.5] })";
  // Seen from above, through the gap between the floor (y = 0) and the plate (y = 2.5 ... 3.5).
  const Scene scene = scene_with(floor, true);
  EmbreeScene rt(scene);
  const ReferenceScene rs{scene, rt};
  const glm::dvec3 down = glm::normalize(glm::dvec3(1.0, -0.2, 0.3));
  Accumulator acc;
  for (int i = 0; i < 2000; ++i) {
    Rng rng(19, static_cast<std::uint64_t>(i));
    const glm::dvec3 target(4.0 * rng.uniform() - 2.0, 0.0, 4.0 * rng.uniform() - 2.0);
    acc.add(volpath_radiance(rs, target - 5.0 * down, down, rng).x);
  }
  const Estimate e = acc.estimate();
  const double expected = 0.5 / M_PI * kSunIrradiance * std::exp(-(kPlateSigmaA + kPlateSigmaS) * kPlateThickness);
  std::printf("floor under an index-matched plate: %.6f +- %.6f, expected %.6f\n", e.mean, e.standard_error, expected);
  EXPECT_NEAR(e.mean, expected, 3.0 * e.standard_error + 1e-3 * expected);
}

}  // namespace
