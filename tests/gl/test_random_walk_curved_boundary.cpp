// test_random_walk_curved_boundary.cpp: the random-walk method (volpath's estimator on the GPU, in float) against the
// independent estimate of an exact sphere (analytic_sphere_transport.h: every refracted path of the light enumerated
// in closed form), per pixel, where the boundary's curvature matters most: spheres of 1 and 10 mean free paths'
// radius (sigma_s 1, sigma_a 0.01 mm^-1, g 0) lit from the side and from behind, on a 256 x 512 quad mesh. The image
// means within 3 combined standard errors (the walk's from the spread of independent frames), the RMS difference per
// pixel within 1.2 times the combined noise, and no path cut by llvmpipe's loop cap. The small sphere at eta 1.4 runs
// with every test (lit from the side, and from behind 100 radii from the origin, where float rounding leaves a solve
// loose near the surface); all twelve cases (eta 1.3, 1.4, 1.5) at more samples under the `accuracy` label
// (docs/references.md has their numbers).
#include <cmath>
#include <cstdio>
#include <ostream>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "analytic_sphere_transport.h"
#include "image_compare.h"
#include "lucent/lucent.h"
#include "reference/reference_renderer.h"
#include "transport/estimate.h"

namespace {

struct SphereCase {
  double radius;  // [mm]
  bool back_lit;
  double eta;
  int frames = 16, samples_per_frame = 4, independent_samples = 64;
  double offset = 0.0;  // the sphere and the camera moved along x by this many radii (float rounding grows with it)
};

void PrintTo(const SphereCase& c, std::ostream* os) {
  *os << "radius " << c.radius << " mm, " << (c.back_lit ? "back-lit" : "side-lit") << ", eta " << c.eta;
  if (c.offset != 0.0) *os << ", " << c.offset << " radii from the origin";
}

std::string case_name(const ::testing::TestParamInfo<SphereCase>& case_info) {
  return fmt::format("Radius{}{}Eta{}{}", static_cast<int>(case_info.param.radius),
                     case_info.param.back_lit ? "Back" : "Side",
                     static_cast<int>(std::lround(10.0 * case_info.param.eta)),
                     case_info.param.offset != 0.0 ? "FarFromTheOrigin" : "");
}

constexpr int kSize = 16;

lucent::Scene sphere_scene(const SphereCase& c) {
  const glm::dvec3 l = c.back_lit ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
  const double fov_y = 2.0 * glm::degrees(std::atan(1.05 * std::tan(std::asin(0.25))));
  lucent::Scene scene = lucent::parse_scene(fmt::format(R"({{
    "scale_mm": 1,
    "camera": {{ "eye": [{}, 0, {}], "target": [{}, 0, 0], "fov_y_deg": {} }},
    "lights": [{{ "direction": [{}, {}, {}], "radiance": [1, 1, 1] }}],
    "objects": [{{ "shape": "sphere", "radius": {}, "segments": 512, "translate": [{}, 0, 0],
                  "material": {{ "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [1, 1, 1], "g": 0, "eta": {} }} }}],
    "method": {{ "name": "random-walk", "samples_per_frame": {} }},
    "render": {{ "width": {}, "height": {}, "frames": 1, "background": [0, 0, 0] }} }})",
                                         c.offset * c.radius, 4.0 * c.radius, c.offset * c.radius, fov_y, l.x, l.y,
                                         l.z, c.radius, c.offset * c.radius, c.eta, c.samples_per_frame,
                                         kSize, kSize),
                             "random-walk curved boundary", ".");
  // The loader would move the origin to the camera's target (Scene::origin); put the scene back where the file
  // has it, so that the walk works at these coordinates in float.
  const glm::vec3 shift(scene.origin);
  scene.camera.eye += shift, scene.camera.target += shift;
  for (lucent::SceneObject& object : scene.objects) object.world_from_object[3] += glm::vec4(shift, 0.0f);
  scene.origin = glm::dvec3(0.0);
  return scene;
}

void expect_agreement(const SphereCase& c) {
  lucent::test::ensure_gl_context();
  const lucent::Scene scene = sphere_scene(c);
  // The walk: per pixel the mean and standard error over frames of fresh random numbers (the running mean before
  // and after each frame gives the frame's own), and the image mean's error from the frames' spread.
  const std::size_t pixels = kSize * kSize;
  std::vector<double> sum(pixels, 0.0), sum2(pixels, 0.0), previous(pixels, 0.0), frame_means;
  lucent::OffscreenFramebuffer framebuffer(kSize, kSize);
  lucent::Renderer renderer(scene);
  // The interior pixels: rays at least 5% of the radius inside the sphere's silhouette, and the independent estimate
  // along each, through the references' camera (the walk's image rows are the references').
  std::vector<std::size_t> interior;
  std::vector<lucent::reference::Estimate> independent;
  lucent::test::AnalyticSphere sphere;
  sphere.radius = c.radius;
  sphere.eta = c.eta;
  sphere.light_direction = c.back_lit ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
  for (std::size_t p = 0; p < pixels; ++p) {
    glm::dvec3 origin, direction;
    lucent::reference::camera_ray(scene.camera, kSize, kSize, static_cast<double>(p % kSize) + 0.5,
                                  static_cast<double>(p / kSize) + 0.5, origin, direction);
    origin.x -= c.offset * c.radius;  // the exact sphere is centred at the origin
    const double miss = glm::length(origin - glm::dot(origin, direction) * direction);
    if (miss >= 0.95 * c.radius) continue;
    lucent::reference::Accumulator a;
    for (int k = 0; k < c.independent_samples; ++k) {
      lucent::reference::Rng rng = lucent::reference::Rng::for_path(12, p, static_cast<std::uint64_t>(k));
      a.add(lucent::test::analytic_sphere_radiance(sphere, origin, direction, rng));
    }
    interior.push_back(p);
    independent.push_back(a.estimate());
  }
  double loop_limited = 0.0, replayed = 0.0;  // paths llvmpipe's loop cap ended (dropped); events it cut (replayed)
  for (int f = 0; f < c.frames; ++f) {
    renderer.render(scene.camera, {framebuffer.id(), kSize, kSize});
    for (const lucent::FrameTimings& t : renderer.finished_frames(true))
      loop_limited += t.stat("loop_limited_paths"), replayed += t.stat("replayed_events");
    const lucent::ImageRGBA32F image = renderer.read_radiance();
    double frame_sum = 0.0;
    for (std::size_t i : interior) {
      const double running = image.pixels[4 * i];
      const double v = running * (f + 1) - previous[i] * f;
      previous[i] = running;
      sum[i] += v, sum2[i] += v * v, frame_sum += v;
    }
    frame_means.push_back(frame_sum / static_cast<double>(interior.size()));
  }
  const double frames = c.frames, n = static_cast<double>(interior.size());
  double difference = 0.0, squared = 0.0, noise = 0.0, walk_mean = 0.0, independent_mean = 0.0, independent_var = 0.0;
  for (std::size_t k = 0; k < interior.size(); ++k) {
    const std::size_t i = interior[k];
    const double mean = sum[i] / frames;
    const double variance = std::max(0.0, (sum2[i] - frames * mean * mean) / (frames - 1.0)) / frames;
    const lucent::reference::Estimate& e = independent[k];
    difference += mean - e.mean, squared += (mean - e.mean) * (mean - e.mean);
    noise += variance + e.standard_error * e.standard_error;
    walk_mean += mean / n, independent_mean += e.mean / n, independent_var += e.standard_error * e.standard_error;
  }
  double m = 0.0, m2 = 0.0;
  for (double b : frame_means) m += b, m2 += b * b;
  const double frame_mean = m / frames;
  const double walk_mean_error =
      std::sqrt(std::max(0.0, (m2 - frames * frame_mean * frame_mean) / (frames - 1.0)) / frames);
  const double mean_error = std::sqrt(walk_mean_error * walk_mean_error + independent_var / (n * n));
  const double rmse = std::sqrt(squared / n), combined_noise = std::sqrt(noise / n);
  std::printf("random-walk, radius %4.1f mm %-4s eta %.1f: %.5f, independent %.5f, ratio %.4f +- %.4f (walk %.4f, "
              "independent %.4f), z %+.2f, RMSE / noise %.2f (%d pixels, %.0f paths cut, %.0f events replayed)\n",
              c.radius, c.back_lit ? "back" : "side", c.eta, walk_mean, independent_mean, walk_mean / independent_mean,
              mean_error / independent_mean, walk_mean_error / independent_mean,
              std::sqrt(independent_var) / n / independent_mean, (difference / n) / mean_error, rmse / combined_noise,
              static_cast<int>(n), loop_limited, replayed);
  EXPECT_EQ(loop_limited, 0.0);
  EXPECT_LE(std::fabs(difference / n), 3.0 * mean_error);
  EXPECT_LE(rmse, 1.2 * combined_noise);
}

class RandomWalkCurvedBoundary : public ::testing::TestWithParam<SphereCase> {};

TEST_P(RandomWalkCurvedBoundary, AgreesWithEveryRefractedPathOfTheExactSphere) { expect_agreement(GetParam()); }

INSTANTIATE_TEST_SUITE_P(RandomWalk, RandomWalkCurvedBoundary,
                         ::testing::Values(SphereCase{1.0, false, 1.4}, SphereCase{1.0, true, 1.4, 16, 8, 64, 100.0}),
                         case_name);

// The `accuracy` label: all twelve cases at more samples.
class RandomWalkCurvedBoundaryAccuracy : public ::testing::TestWithParam<SphereCase> {};

TEST_P(RandomWalkCurvedBoundaryAccuracy, AgreesWithEveryRefractedPathOfTheExactSphere) {
  expect_agreement(GetParam());
}

std::vector<SphereCase> every_case() {
  std::vector<SphereCase> cases;
  for (double eta : {1.3, 1.4, 1.5})
    for (double radius : {1.0, 10.0})
      for (bool back : {false, true}) cases.push_back({radius, back, eta, 16, radius > 1.0 ? 64 : 32, 256});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(RandomWalk, RandomWalkCurvedBoundaryAccuracy, ::testing::ValuesIn(every_case()), case_name);

}  // namespace
