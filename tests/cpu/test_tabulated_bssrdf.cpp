// test_tabulated_bssrdf.cpp: the tabulated model (bssrdf/tabulated.h, materials/tabulated_bssrdf.h) against
// independent values: its flat total against a separate run of the slab transport (different random streams) at
// normal and oblique incidence; the scale invariance of reduced units; the symmetry of normal incidence; the
// forward bias of oblique incidence that exact transport shows and the radial dipoles cannot; determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "bssrdf/model.h"
#include "bssrdf/tabulated.h"
#include "lucent/material.h"
#include "materials/model_total_reflectance.h"
#include "materials/tabulated_bssrdf.h"
#include "transport/slab.h"

namespace {

using lucent::BssrdfModel;
namespace sh = lucent::shader;

constexpr std::uint64_t kPhotons = 40000;

lucent::Material tabulated(float albedo, float g, float eta, float sigma_t = 1.0f) {
  lucent::set_bssrdf_table_photons(kPhotons);
  lucent::Material m;
  m.sigma_a = glm::vec3((1.0f - albedo) * sigma_t);
  m.sigma_s = glm::vec3(albedo * sigma_t);
  m.g = glm::vec3(g);
  m.eta = eta;
  m.model = BssrdfModel::Tabulated;
  return m;
}

// The model's plane integral, with its exit normalisation, returns what exact transport reflects per refracted
// power: within 3 combined standard errors of an independent slab run plus 0.5% for the table's interpolation.
// Fails without the exit normalisation 1 / (1 - 2 C1(1/eta)) (6-9% at eta 1.3-1.5).
TEST(TabulatedBssrdf, FlatTotalIsExactTransport) {
  struct Case {
    float albedo, g, eta;
    double incidence_deg;
  };
  for (const Case& c : {Case{0.9f, 0.0f, 1.3f, 0.0}, Case{0.99f, 0.0f, 1.5f, 0.0}, Case{0.95f, 0.5f, 1.33f, 0.0},
                        Case{0.99f, 0.0f, 1.5f, 45.0}, Case{0.9f, 0.0f, 1.0f, 75.0}}) {
    const auto model = lucent::model_total_reflectance(tabulated(c.albedo, c.g, c.eta), c.incidence_deg);
    lucent::reference::SlabConfig config;
    config.albedo = c.albedo, config.g = c.g, config.eta = c.eta, config.incidence_deg = c.incidence_deg;
    config.photons = kPhotons, config.seed = 99;
    const auto exact = lucent::reference::simulate_slab(config).diffuse_reflectance_per_refracted;
    // The table's own estimate has about the same standard error as the independent run.
    const double tolerance = 3.0 * std::sqrt(2.0) * exact.standard_error + 0.005 * exact.mean;
    EXPECT_NEAR(model.total.x, exact.mean, tolerance)
        << "albedo " << c.albedo << " g " << c.g << " eta " << c.eta << " incidence " << c.incidence_deg;
  }
}

// One table serves every scale: S_d of a medium k times denser at distance r / k is k^2 times larger.
TEST(TabulatedBssrdf, ReducedUnitsMakeTheProfileScaleInvariant) {
  const lucent::Material thin = tabulated(0.95f, 0.0f, 1.3f, 1.0f), dense = tabulated(0.95f, 0.0f, 1.3f, 10.0f);
  const sh::BandMedium a = sh::make_band_medium(thin.sigma_a.x, thin.sigma_s.x, 0.0f);
  const sh::BandMedium b = sh::make_band_medium(dense.sigma_a.x, dense.sigma_s.x, 0.0f);
  const glm::vec3 n(0, 0, 1), w(0.5f, 0.0f, 0.8660254f);
  for (float r : {0.01f, 0.3f, 1.0f, 4.0f, 20.0f}) {
    const float s_thin = sh::tabulated_Sd(a, 1.3f, glm::vec3(0.0f), w, n, glm::vec3(r, 0.0f, 0.0f));
    const float s_dense = sh::tabulated_Sd(b, 1.3f, glm::vec3(0.0f), w, n, glm::vec3(r / 10.0f, 0.0f, 0.0f));
    EXPECT_NEAR(s_dense, 100.0f * s_thin, 1e-4f * s_dense + 1e-12f) << "r " << r;
  }
}

// Normal incidence: no preferred azimuth. Oblique incidence (60 degrees): exact transport puts more light ahead of
// the entry point, in the refracted beam's direction of travel, than behind it, near the entry point.
TEST(TabulatedBssrdf, AzimuthFollowsTheRefractedBeam) {
  const lucent::Material m = tabulated(0.99f, 0.0f, 1.0f);
  const sh::BandMedium b = sh::make_band_medium(m.sigma_a.x, m.sigma_s.x, 0.0f);
  const glm::vec3 n(0, 0, 1), normal_w = n;
  const glm::vec3 oblique_w(-std::sin(1.0471976f), 0.0f, std::cos(1.0471976f));  // light from -x: travels toward +x
  const float r = 1.0f;
  const float ahead_0 = sh::tabulated_Sd(b, 1.0f, glm::vec3(0.0f), normal_w, n, glm::vec3(r, 0, 0));
  const float behind_0 = sh::tabulated_Sd(b, 1.0f, glm::vec3(0.0f), normal_w, n, glm::vec3(-r, 0, 0));
  EXPECT_EQ(ahead_0, behind_0);
  const float ahead = sh::tabulated_Sd(b, 1.0f, glm::vec3(0.0f), oblique_w, n, glm::vec3(r, 0, 0));
  const float behind = sh::tabulated_Sd(b, 1.0f, glm::vec3(0.0f), oblique_w, n, glm::vec3(-r, 0, 0));
  EXPECT_GT(ahead, 1.3f * behind);
}

TEST(TabulatedBssrdf, TablesAreDeterministic) {
  const auto first = lucent::build_bssrdf_table(0.9f, 0.3f, 1.3f, 5000);
  const auto second = lucent::build_bssrdf_table(0.9f, 0.3f, 1.3f, 5000);
  ASSERT_EQ(first.size(), static_cast<std::size_t>(sh::kBssrdfTableFloats));
  EXPECT_EQ(first, second);
}

}  // namespace
