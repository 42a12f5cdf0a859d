// test_sphere_jumps.cpp: volpath's sphere jumps (shared/sphere_walk.h, docs/references.md "Sphere jumps").
//  - EmbreeScene::closest_surface_distance against a brute-force loop over every triangle of a sphere mesh and a
//    cube, and closest_point_on_triangle against a fine search over the triangle.
//  - The canonical walk against independent values: exits on the sphere, the mean number of collisions and the
//    mean of n L_v (the stored vertex's estimate of the sum of the collisions' path lengths) against a
//    brute-force walk in double written here, and P(n = 0) = e^{-tau}.
//  - The reflectance of a half-space (albedo 0.99) with jumps against Chandrasekhar's exact value (measured 0.7545
//    +- 0.0025 against 0.7527; without the n-fold next-event estimate at the stored vertex 0.658: fails).
//  - Images with and without jumps agree within their noise (isotropic and forward scattering, grey and coloured),
//    while the steps per path fall at least tenfold in a dense medium. Measured (16x16, 8 batches of 8 spp each
//    way): the image means within 2 standard errors per band; without the n-fold next-event estimate at the stored
//    vertex the means fall by 4 to 7.6 standard errors, and without the coloured bands' e^{-(sigma_t - sigma_t,hero)
//    l} in the throughput red and blue move by 5 to 8 in opposite directions: both fail.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "lucent/scene.h"
#include "geometry/closest_point.h"
#include "reference/embree_scene.h"
#include "reference/integrators.h"
#include "reference/reference_renderer.h"
#include "shared/sphere_walk.h"
#include "transport/estimate.h"
#include "transport/sphere_jump_bank.h"

namespace {

using namespace lucent;
using namespace lucent::reference;

// The point of triangle (a, b, c) nearest to p by a search over a barycentric grid of `steps` cells per edge: an
// upper bound on the distance within the grid's spacing of the exact one.
double sj_grid_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                        int steps) {
  double best = 1e300;
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; i + j <= steps; ++j) {
      const double u = double(i) / steps, v = double(j) / steps;
      best = std::min(best, glm::length(a + u * (b - a) + v * (c - a) - p));
    }
  return best;
}

TEST(SphereJumps, ClosestPointOnTriangleMatchesAFineSearch) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  auto point = [&] { return glm::dvec3(coordinate(gen), coordinate(gen), coordinate(gen)); };
  for (int trial = 0; trial < 300; ++trial) {
    const glm::dvec3 a = point(), b = point(), c = trial % 10 == 0 ? a + 0.5 * (b - a) : point();  // some degenerate
    const glm::dvec3 p = 2.0 * point();
    const double exact = glm::length(closest_point_on_triangle(p, a, b, c) - p);
    const double searched = sj_grid_distance(p, a, b, c, 200);
    const double spacing = std::max({glm::length(b - a), glm::length(c - a), glm::length(c - b)}) / 200.0;
    EXPECT_LE(exact, searched + 1e-12) << "trial " << trial;
    EXPECT_GE(exact, searched - spacing) << "trial " << trial;
  }
}

TEST(SphereJumps, ClosestSurfaceDistanceMatchesBruteForce) {
  const Scene scene = parse_scene(R"({
    "objects": [{ "shape": "sphere", "radius": 1, "segments": 24 },
                { "shape": "box", "size": [1, 1.5, 2], "translate": [3, 0.5, 0] }] })",
                                  "distance", ".");
  EmbreeScene rt(scene);
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> x(-2.0, 5.0), yz(-2.0, 2.0);
  for (int trial = 0; trial < 400; ++trial) {
    const glm::dvec3 p(x(gen), yz(gen), yz(gen));
    double brute = 1e300;
    for (int o = 0; o < rt.object_count(); ++o)
      for (const ObjectData::Corners& c : rt.object(o).corners)
        brute = std::min(brute, glm::length(closest_point_on_triangle(p, c.position[0], c.position[1], c.position[2]) - p));
    const double found = rt.closest_surface_distance(p, 10.0);
    EXPECT_LE(found, brute) << "trial " << trial;  // a lower bound
    EXPECT_NEAR(found, brute, 1e-4) << "trial " << trial;
    // Clamped to the query's radius.
    EXPECT_NEAR(rt.closest_surface_distance(p, 0.25), std::min(brute, 0.25), 1e-4) << "trial " << trial;
  }
}

// A canonical walk in double: the statistics sphere_walk() must reproduce.
struct SjWalk {
  int n = 0;
  double sum_length_at_collisions = 0.0;  // the sum over collisions of the optical length from the centre
  double exit_radius = 0.0;
};

glm::dvec3 sj_sample_hg(std::mt19937_64& gen, const glm::dvec3& w, double g) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double cos_theta;
  if (g == 0.0) {
    cos_theta = 1.0 - 2.0 * u(gen);
  } else {  // inverting the HG distribution of cos theta
    const double s = (1.0 - g * g) / (1.0 + g - 2.0 * g * u(gen));
    cos_theta = (1.0 + g * g - s * s) / (2.0 * g);
  }
  const double phi = 2.0 * M_PI * u(gen), sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const glm::dvec3 t = std::abs(w.z) < 0.9 ? glm::normalize(glm::cross(w, glm::dvec3(0, 0, 1)))
                                            : glm::normalize(glm::cross(w, glm::dvec3(1, 0, 0)));
  const glm::dvec3 s = glm::cross(w, t);
  return glm::normalize(sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * s + cos_theta * w);
}

SjWalk sj_brute_walk(std::mt19937_64& gen, double tau, double g) {
  std::exponential_distribution<double> flight(1.0);
  SjWalk w;
  glm::dvec3 p(0.0), d(0.0, 0.0, 1.0);
  double length = 0.0;
  for (;;) {
    const double t = flight(gen);
    // A segment from inside the (convex) ball leaves it exactly when its end is outside.
    const glm::dvec3 q = p + t * d;
    if (glm::length(q) >= tau) {
      const double b = glm::dot(p, d), c = glm::dot(p, p) - tau * tau;
      const double s = -b + std::sqrt(b * b - c);
      w.exit_radius = glm::length(p + s * d) / tau;
      return w;
    }
    p = q;
    length += t;
    ++w.n;
    w.sum_length_at_collisions += length;
    d = sj_sample_hg(gen, d, g);
  }
}

void sj_check_walk_statistics(float tau, float g) {
  constexpr int kWalks = 20000;
  Accumulator n_fast, n_brute, sum_fast, sum_brute;
  for (int i = 0; i < kWalks; ++i) {
    const shader::SphereWalkGPU r = shader::sphere_walk(tau, g, shader::seed_from(3u, 5u, static_cast<std::uint32_t>(i), 0u));
    const double n = r.exit_dir.w;
    n_fast.add(n);
    sum_fast.add(n * r.vertex.w);
    ASSERT_LT(n, shader::kSphereWalkMaxSteps);
    EXPECT_NEAR(glm::length(glm::vec3(r.exit)), 1.0f, 1e-4f);
    EXPECT_NEAR(glm::length(glm::vec3(r.exit_dir)), 1.0f, 1e-4f);
    EXPECT_GE(r.exit.w, tau * (1.0f - 1e-4f));  // at least the straight line out
    if (n >= 1.0) {
      EXPECT_GE(r.vertex_dir.w, 1.0f);
      EXPECT_LE(r.vertex_dir.w, r.exit_dir.w);
      EXPECT_LE(glm::length(glm::vec3(r.vertex)), 1.0f);
      EXPECT_LE(r.vertex.w, r.exit.w);
    }
  }
  std::mt19937_64 gen(99);
  for (int i = 0; i < kWalks; ++i) {
    const SjWalk w = sj_brute_walk(gen, tau, g);
    n_brute.add(w.n);
    sum_brute.add(w.sum_length_at_collisions);
  }
  const Estimate a = n_fast.estimate(), b = n_brute.estimate(), c = sum_fast.estimate(), d = sum_brute.estimate();
  std::printf("tau %.1f g %.1f: mean n %.3f +- %.3f (brute force %.3f +- %.3f); mean n L_v %.2f +- %.2f (sum of L %.2f "
              "+- %.2f)\n", tau, g, a.mean, a.standard_error, b.mean, b.standard_error, c.mean, c.standard_error,
              d.mean, d.standard_error);
  EXPECT_NEAR(a.mean, b.mean, 4.0 * std::hypot(a.standard_error, b.standard_error));
  EXPECT_NEAR(c.mean, d.mean, 4.0 * std::hypot(c.standard_error, d.standard_error));
}

TEST(SphereJumps, CanonicalWalkMatchesABruteForceWalk) {
  sj_check_walk_statistics(4.0f, 0.0f);
  sj_check_walk_statistics(8.0f, 0.8f);
}

TEST(SphereJumps, CanonicalWalkLeavesWithoutCollisionWithProbabilityExpMinusTau) {
  constexpr int kWalks = 200000;
  const double tau = 0.5;
  int none = 0;
  for (int i = 0; i < kWalks; ++i) {
    const shader::SphereWalkGPU r = shader::sphere_walk(static_cast<float>(tau), 0.0f, shader::seed_from(8u, static_cast<std::uint32_t>(i), 1u, 2u));
    if (r.exit_dir.w == 0.0f) {
      ++none;
      EXPECT_EQ(r.vertex, glm::vec4(0.0f));
      EXPECT_NEAR(r.exit.z, 1.0f, 1e-5f);  // straight along +z
    }
  }
  const double p = std::exp(-tau), se = std::sqrt(p * (1.0 - p) / kWalks);
  EXPECT_NEAR(static_cast<double>(none) / kWalks, p, 4.0 * se);
}

TEST(SphereJumps, BankRecordsAreReproducibleAndDifferPerSample) {
  const SphereJumpBank bank(5, 64);
  const auto a = bank.records(3, 0.5f, 2), again = bank.records(3, 0.5f, 2), other = bank.records(4, 0.5f, 2);
  ASSERT_EQ(a.size(), 64u);
  EXPECT_EQ(a.data(), again.data());  // generated once, then shared
  const auto fresh = SphereJumpBank::generate(5, 3, 0.5f, 2, 64);
  int equal_to_other = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].exit, fresh[i].exit);
    equal_to_other += a[i].exit == other[i].exit;
  }
  EXPECT_EQ(equal_to_other, 0);
}

// Threads asking for the same bank at once get the one generated copy; released banks are generated again alike.
TEST(SphereJumps, BankIsGeneratedOnceForConcurrentThreads) {
  SphereJumpBank bank(9, 128);
  std::vector<const shader::SphereWalkGPU*> seen(8, nullptr);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t)
    threads.emplace_back([&bank, &seen, t] { seen[t] = bank.records(t % 2 == 0 ? 0 : 1, 0.0f, 3).data(); });
  for (std::thread& thread : threads) thread.join();
  for (std::size_t t = 2; t < seen.size(); ++t) EXPECT_EQ(seen[t], seen[t % 2]) << "thread " << t;
  EXPECT_NE(seen[0], seen[1]);
  const shader::SphereWalkGPU first = bank.records(1, 0.0f, 3)[5];
  bank.release_samples_before(2);
  EXPECT_EQ(bank.records(1, 0.0f, 3)[5].exit, first.exit);
}

// A sphere of radius 1 scene unit (scale_mm 10: 10 mm) of a dense, high-albedo medium, lit from the side.
Scene sj_marble_scene(double sigma_s_mm, glm::dvec3 albedo, double g, int size) {
  const glm::dvec3 sigma_a = sigma_s_mm * (1.0 - albedo) / albedo;
  return parse_scene(fmt::format(R"({{
    "scale_mm": 10, "camera": {{ "eye": [0, 0, 4], "target": [0, 0, 0], "fov_y_deg": 32 }},
    "lights": [{{ "direction": [0.6, -0.5, -0.62], "radiance": [3, 3, 3] }}],
    "objects": [{{ "shape": "sphere", "radius": 1, "segments": 48,
                  "material": {{ "sigma_a": [{}, {}, {}], "sigma_s": [{}, {}, {}], "g": {}, "eta": 1.4 }} }}],
    "render": {{ "width": {}, "height": {}, "background": [0, 0, 0] }} }})",
                                 sigma_a.x, sigma_a.y, sigma_a.z, sigma_s_mm, sigma_s_mm, sigma_s_mm, g, size, size),
                     "marble", ".");
}

struct SjComparison {
  glm::dvec3 mean_difference, mean_error;  // per band, over the image; the error from the batches' spread
  double grey_difference, grey_error;      // the same for the mean of the bands
  double claimed_ratio;  // band 0: the batch means' spread over what the per-pixel standard errors imply
  double rms_z;          // per pixel and band: the RMS of difference / combined standard error
  double steps_on, steps_off, seconds_on, seconds_off;
};

// Renders `batches` independent batches (distinct seeds) of `spp` samples with jumps and as many without. The
// image means are compared through the spread of the batches' image means: pixels of one batch share the bank of
// each sample index, so their errors are correlated and the sum of per-pixel variances understates the error of
// an image mean. Each pixel is compared through its own standard error (the pixel's samples are independent).
SjComparison sj_compare(const Scene& scene, int spp, int batches) {
  const std::uint64_t first_seed = 21;
  SjComparison r{};
  std::vector<glm::dvec3> means[2];
  std::vector<double> grey[2];
  std::vector<glm::dvec3> pixel_sum[2], pixel_var[2];
  double claimed_var = 0.0, observed_var = 0.0;
  for (int jumps = 0; jumps < 2; ++jumps)
    for (int b = 0; b < batches; ++b) {
      ReferenceSettings settings;
      settings.samples_per_pixel = spp;
      settings.sphere_jumps = jumps == 1;
      settings.seed = first_seed + static_cast<std::uint64_t>(1000 * jumps + b);
      const ReferenceImage image = render_reference(scene, settings);
      (jumps ? r.steps_on : r.steps_off) += image.steps_per_path / batches;
      (jumps ? r.seconds_on : r.seconds_off) += image.seconds;
      const std::size_t pixels = image.mean.pixels.size() / 4;
      pixel_sum[jumps].resize(pixels), pixel_var[jumps].resize(pixels);
      glm::dvec3 mean(0.0), var(0.0);
      for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) {
          const double m = image.mean.pixels[4 * i + static_cast<std::size_t>(c)];
          const double e = image.standard_error.pixels[4 * i + static_cast<std::size_t>(c)];
          mean[c] += m / static_cast<double>(pixels), var[c] += e * e / static_cast<double>(pixels * pixels);
          pixel_sum[jumps][i][c] += m, pixel_var[jumps][i][c] += e * e;
        }
      means[jumps].push_back(mean);
      grey[jumps].push_back((mean.x + mean.y + mean.z) / 3.0);
      claimed_var += var.x / (2.0 * batches);
    }
  glm::dvec3 average[2], spread[2];
  double grey_average[2], grey_spread[2];
  for (int jumps = 0; jumps < 2; ++jumps) {
    average[jumps] = glm::dvec3(0.0), spread[jumps] = glm::dvec3(0.0);
    grey_average[jumps] = 0.0, grey_spread[jumps] = 0.0;
    for (int b = 0; b < batches; ++b) {
      average[jumps] += means[jumps][static_cast<std::size_t>(b)] / double(batches);
      grey_average[jumps] += grey[jumps][static_cast<std::size_t>(b)] / double(batches);
    }
    for (int b = 0; b < batches; ++b) {
      const glm::dvec3 d = means[jumps][static_cast<std::size_t>(b)] - average[jumps];
      const double e = grey[jumps][static_cast<std::size_t>(b)] - grey_average[jumps];
      spread[jumps] += d * d / double(batches - 1), grey_spread[jumps] += e * e / double(batches - 1);
    }
    observed_var += spread[jumps].x / 2.0;
  }
  r.mean_difference = average[1] - average[0];
  r.mean_error = glm::sqrt((spread[0] + spread[1]) / double(batches));
  r.grey_difference = grey_average[1] - grey_average[0];
  r.grey_error = std::sqrt((grey_spread[0] + grey_spread[1]) / batches);
  r.claimed_ratio = std::sqrt(observed_var / claimed_var);
  double z2 = 0.0;
  int counted = 0;
  for (std::size_t i = 0; i < pixel_sum[0].size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double difference = (pixel_sum[1][i][c] - pixel_sum[0][i][c]) / batches;
      const double variance = (pixel_var[1][i][c] + pixel_var[0][i][c]) / (double(batches) * batches);
      if (variance > 0.0) z2 += difference * difference / variance, ++counted;
    }
  r.rms_z = std::sqrt(z2 / std::max(1, counted));
  return r;
}

void sj_expect_agreement(double g, glm::dvec3 albedo, const char* what) {
  const int spp = 8, batches = 8;
  const SjComparison r = sj_compare(sj_marble_scene(5.0, albedo, g, 16), spp, batches);
  const glm::dvec3 z = r.mean_difference / r.mean_error;
  const double total_z = r.grey_difference / r.grey_error;
  std::printf("%s, g %.1f: image mean difference per band in standard errors %.2f %.2f %.2f (all bands %.2f; batch "
              "spread %.2fx the per-pixel errors'), per-pixel RMS z %.3f; steps per path %.1f with jumps, %.1f "
              "without; %.2f s and %.2f s\n", what, g, z.x, z.y, z.z, total_z, r.claimed_ratio, r.rms_z, r.steps_on,
              r.steps_off, r.seconds_on, r.seconds_off);
  // Student's t with 2 (batches - 1) = 14 degrees of freedom: |t| > 3 has probability 0.01, |t| > 4 0.0013.
  EXPECT_LE(std::abs(total_z), 3.0) << what << " g " << g;
  for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs(z[c]), 4.0) << what << " g " << g << " band " << c;
  EXPECT_LE(r.rms_z, 1.25) << what << " g " << g;
  EXPECT_GT(r.rms_z, 0.75) << what << " g " << g;  // the standard errors are not overestimated either
  EXPECT_LT(r.steps_on, 0.5 * r.steps_off) << what << " g " << g;  // the jumps do happen
}

TEST(SphereJumps, ImagesWithAndWithoutJumpsAgreeGrey) {
  sj_expect_agreement(0.0, glm::dvec3(0.999), "grey");
  sj_expect_agreement(0.8, glm::dvec3(0.999), "grey");
}

TEST(SphereJumps, ImagesWithAndWithoutJumpsAgreeColoured) {
  sj_expect_agreement(0.0, glm::dvec3(0.9995, 0.995, 0.98), "coloured");
  sj_expect_agreement(0.8, glm::dvec3(0.9995, 0.995, 0.98), "coloured");
}

// Against an exact value: the diffuse reflectance of a half-space (albedo 0.99, g = 0, index-matched, light at
// normal incidence; Chandrasekhar's H-function value 0.752721, as in test_slab.cpp), through volpath with jumps, by
// reciprocity R = pi E[L(w_o)] / E for views cosine-weighted over the hemisphere. 64 sample indices (banks of 256
// records); the standard error comes from the spread of the 64 groups' means, since paths that share a bank are
// not independent of each other.
TEST(SphereJumps, HalfSpaceReflectanceWithJumpsMatchesTheExactValue) {
  const Scene scene = parse_scene(R"({
    "scale_mm": 1, "lights": [{ "direction": [0, -1, 0], "radiance": [1, 1, 1] }],
    "objects": [{ "shape": "box", "size": [300, 300, 300], "translate": [0, -150, 0],
                  "material": { "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [0.99, 0.99, 0.99], "g": 0, "eta": 1 } }] })",
                                  "half-space", ".");
  EmbreeScene rt(scene);
  const SphereJumpBank bank(3, 256);
  ReferenceScene rs{scene, rt};
  rs.jump_bank = &bank;
  constexpr int kGroups = 64, kPathsPerGroup = 1600;
  Accumulator groups;
  std::int64_t steps = 0;
  for (int group = 0; group < kGroups; ++group) {
    double sum = 0.0;
    for (int i = 0; i < kPathsPerGroup; ++i) {
      Rng rng(17, static_cast<std::uint64_t>(group * kPathsPerGroup + i));
      const double r = std::sqrt(rng.uniform()), phi = 2.0 * M_PI * rng.uniform();
      const glm::dvec3 w_o(r * std::cos(phi), std::sqrt(std::max(0.0, 1.0 - r * r)), r * std::sin(phi));
      const glm::dvec3 target(rng.uniform() - 0.5, 0.0, rng.uniform() - 0.5);
      PathRecord record;
      record.sample = group;
      sum += M_PI * volpath_radiance(rs, target + 10.0 * w_o, -w_o, rng, nullptr, &record).x;
      steps += record.steps;
    }
    groups.add(sum / kPathsPerGroup);
  }
  const Estimate e = groups.estimate();
  std::printf("half-space, albedo 0.99, with jumps: R = %.5f +- %.5f (exact 0.752721), %.1f steps per path\n", e.mean,
              e.standard_error, static_cast<double>(steps) / (kGroups * kPathsPerGroup));
  EXPECT_NEAR(e.mean, 0.752721, 3.0 * e.standard_error + 1e-6);
  EXPECT_LT(e.standard_error, 0.01);
}

TEST(SphereJumps, StepsPerPathFallTenfoldInADenseMedium) {
  constexpr double kAlbedo = 0.99995;
  const Scene scene = sj_marble_scene(20.0, glm::dvec3(kAlbedo), 0.0, 8);
  ReferenceSettings settings;
  settings.samples_per_pixel = 16;
  const ReferenceImage on = render_reference(scene, settings);
  settings.sphere_jumps = false;
  const ReferenceImage off = render_reference(scene, settings);
  std::printf("dense sphere (200 mean free paths in radius, albedo %g): %.1f steps per path with jumps, %.1f "
              "without: %.1fx fewer; %.2f s and %.2f s\n", kAlbedo, on.steps_per_path, off.steps_per_path,
              off.steps_per_path / on.steps_per_path, on.seconds, off.seconds);
  EXPECT_GE(off.steps_per_path, 10.0 * on.steps_per_path);
}

}  // namespace
