// test_slab.cpp: the random walk and Fresnel code of the references against exact transport results
// (shared/spec/validation-values.md): each Monte Carlo estimate must lie within 3 of its own standard errors
// (plus the table's rounding) of the exact value. Deterministic seeds: a pass is reproducible.
#include <gtest/gtest.h>

#include "transport/slab.h"

namespace {

using lucent::reference::Estimate;
using lucent::reference::Incidence;
using lucent::reference::SlabConfig;
using lucent::reference::simulate_slab;

void expect_within_3_se(const Estimate& e, double exact, double table_rounding, const std::string& what) {
  EXPECT_NEAR(e.mean, exact, 3.0 * e.standard_error + table_rounding)
      << what << ": " << e.mean << " +- " << e.standard_error << " vs exact " << exact;
  EXPECT_LT(e.standard_error, 0.004) << what << ": too few photons for a meaningful test";
}

SlabConfig half_space(double albedo, double eta, std::uint64_t photons = 300000) {
  SlabConfig c;
  c.albedo = albedo, c.eta = eta, c.photons = photons;
  return c;
}

TEST(Slab, HalfSpaceIndexMatchedNormalIncidence) {
  // Chandrasekhar H-function values (validation-values.md Section 1).
  const std::pair<double, double> rows[] = {{0.3, 0.057214}, {0.5, 0.115226}, {0.8, 0.285255}, {0.9, 0.414948},
                                            {0.99, 0.752721}};
  for (auto [albedo, exact] : rows)
    expect_within_3_se(simulate_slab(half_space(albedo, 1.0)).diffuse_reflectance, exact, 1e-6,
                       "albedo " + std::to_string(albedo));
}

TEST(Slab, HalfSpaceIndexMatchedObliqueAndDiffuseIncidence) {
  SlabConfig oblique = half_space(0.8, 1.0);
  oblique.incidence_deg = 60.0;
  expect_within_3_se(simulate_slab(oblique).diffuse_reflectance, 0.367970, 1e-6, "60 degrees, albedo 0.8");
  SlabConfig diffuse = half_space(0.9, 1.0);
  diffuse.incidence = Incidence::Diffuse;
  expect_within_3_se(simulate_slab(diffuse).diffuse_reflectance, 0.478025, 1e-6, "diffuse, albedo 0.9");
}

TEST(Slab, HalfSpaceWithFresnelBoundaryPerRefractedPower) {
  // Adding-doubling, n = 1.3, +-1e-4 (validation-values.md Section 2). These fail with a wrong internal
  // Fresnel term or without total internal reflection (critical angle 50.3 degrees inside).
  const std::pair<double, double> rows[] = {{0.5, 0.06349}, {0.8, 0.18132}, {0.9, 0.29074}, {0.99, 0.65657}};
  for (auto [albedo, exact] : rows) {
    auto r = simulate_slab(half_space(albedo, 1.3));
    expect_within_3_se(r.diffuse_reflectance_per_refracted, exact, 1e-4, "n 1.3, albedo " + std::to_string(albedo));
    EXPECT_NEAR(r.specular_reflectance.mean, 0.017013, 1e-6);  // ((1.3 - 1) / 2.3)^2
  }
}

TEST(Slab, VanDeHulstFiniteSlab) {
  // a = 1, b = 1, g = 0, n = 1: R = 0.34133, T = 0.65867 including the unscattered e^-1.
  SlabConfig c = half_space(1.0, 1.0, 400000);
  c.thickness = 1.0;
  auto r = simulate_slab(c);
  expect_within_3_se(r.diffuse_reflectance, 0.34133, 5e-6, "R");
  expect_within_3_se(r.transmittance, 0.65867, 5e-6, "T");
  expect_within_3_se(r.unscattered_transmittance, std::exp(-1.0), 0.0, "unscattered T");
}

TEST(Slab, FurnaceNothingIsLost) {
  // Albedo 1, index-matched: every photon leaves, so R + T = 1 for each photon, exactly.
  SlabConfig c = half_space(1.0, 1.0, 50000);
  c.thickness = 3.0;
  c.g = 0.7;
  auto r = simulate_slab(c);
  EXPECT_NEAR(r.diffuse_reflectance.mean + r.transmittance.mean, 1.0, 1e-9);  // double rounding of 5e4 sums
  // With a Fresnel boundary energy is still conserved: specular + diffuse + transmitted = 1 within noise.
  c.eta = 1.4;
  r = simulate_slab(c);
  double total = r.specular_reflectance.mean + r.diffuse_reflectance.mean + r.transmittance.mean;
  double se = std::hypot(r.diffuse_reflectance.standard_error, r.transmittance.standard_error);
  EXPECT_NEAR(total, 1.0, 3.0 * se + 1e-9);
}

TEST(Slab, AggressiveRussianRouletteStaysUnbiased) {
  // Roulette at every weight below 0.5 (so most photons play it many times) must not move the estimate: a
  // roulette that forgets to divide surviving weights by the survival probability fails here.
  SlabConfig c = half_space(0.9, 1.3, 300000);
  c.roulette_threshold = 0.5;
  expect_within_3_se(simulate_slab(c).diffuse_reflectance_per_refracted, 0.29074, 1e-4, "roulette below 0.5");
}

TEST(Slab, DeterministicForAnyThreadCount) {
  SlabConfig c = half_space(0.9, 1.3, 20000);
  c.threads = 1;
  auto one = simulate_slab(c);
  c.threads = 2;
  auto two = simulate_slab(c);
  EXPECT_EQ(one.diffuse_reflectance.mean, two.diffuse_reflectance.mean);
}

TEST(Slab, RejectsOutOfRangeParameters) {
  SlabConfig c;
  c.albedo = 1.5;
  try {
    simulate_slab(c);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "--albedo 1.5 is out of range; allowed range [0, 1]");
  }
}

}  // namespace
