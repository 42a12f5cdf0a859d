// test_model_total_reflectance.cpp: the flat half-space total of a model (materials/model_total_reflectance.h)
// against independent values: the standard dipole's closed-form R_total (Jensen et al. 2001), the exit
// transmittance against the spec's exactly integrated Fresnel moments (4 C_phi(1/eta)), the directional dipole's
// normal-incidence symmetry, and the models' disagreement with exact transport (Monte Carlo slab,
// validated against Chandrasekhar's tables in test_slab.cpp) that docs/models/total-reflectance.md reports.
#include <gtest/gtest.h>

#include "bssrdf/standard_dipole.h"
#include "lucent/material.h"
#include "materials/model_total_reflectance.h"
#include "reference/slab.h"

namespace {

lucent::Material material(lucent::BssrdfModel model, float albedo, float eta) {
  lucent::Material m;
  m.sigma_a = glm::vec3(1.0f - albedo);
  m.sigma_s = glm::vec3(albedo);
  m.g = glm::vec3(0.0f);
  m.eta = eta;
  m.model = model;
  return m;
}

// The integrator reproduces the standard dipole's closed form (relative 2e-4) at low and high albedo, and with the
// exit normalisation the emergent total is R_total itself: 1 - 2 C1(1/eta) integrated numerically against its
// polynomial fit, within 2e-3.
TEST(ModelTotalReflectance, StandardDipoleEmergentTotalIsTheClosedFormTotal) {
  for (float albedo : {0.3f, 0.8f, 0.99f, 0.999f})
    for (float eta : {1.0f, 1.3f, 1.5f}) {
      const auto t = lucent::model_total_reflectance(material(lucent::BssrdfModel::StandardDipole, albedo, eta), 0.0);
      const double closed = lucent::shader::standard_dipole_total_Rd(albedo, eta);
      EXPECT_NEAR(t.radiosity.x, closed * lucent::shader::standard_dipole_exit_normalization(eta), 2e-4 * closed)
          << "albedo " << albedo << " eta " << eta;
      EXPECT_NEAR(t.total.x, closed, 2e-3 * closed) << "albedo " << albedo << " eta " << eta;
    }
}

// integral of T21 cos / pi = 1 - 2 C1(1/eta) = 4 C_phi(1/eta): the spec's exact values 0.938868 (1.3), 0.908224 (1.5).
TEST(ModelTotalReflectance, ExitTransmittanceIsTheFresnelMoment) {
  EXPECT_NEAR(lucent::model_total_reflectance(material(lucent::BssrdfModel::StandardDipole, 0.9f, 1.0f), 0).exit_transmittance,
              1.0, 1e-6);
  EXPECT_NEAR(lucent::model_total_reflectance(material(lucent::BssrdfModel::StandardDipole, 0.9f, 1.3f), 0).exit_transmittance,
              4.0 * 0.234717, 2e-5);
  EXPECT_NEAR(lucent::model_total_reflectance(material(lucent::BssrdfModel::StandardDipole, 0.9f, 1.5f), 0).exit_transmittance,
              4.0 * 0.227056, 2e-5);
}

// What the models promise against exact transport on the flat half-space at normal incidence, n = 1.3, albedo
// 0.999 (exact 0.872 per refracted power; the spec's adding-doubling value at n = 1.33 is 0.86641): the standard
// dipole within 2%, the directional dipole above exact by more than 20% (docs/models/total-reflectance.md).
TEST(ModelTotalReflectance, AgainstExactTransportAtHighAlbedo) {
  lucent::reference::SlabConfig o;
  o.albedo = 0.999;
  o.eta = 1.3;
  o.photons = 20000;  // standard error about 0.3%
  const double exact = lucent::reference::simulate_slab(o).diffuse_reflectance_per_refracted.mean;
  const auto standard = lucent::model_total_reflectance(material(lucent::BssrdfModel::StandardDipole, 0.999f, 1.3f), 0);
  const auto directional = lucent::model_total_reflectance(material(lucent::BssrdfModel::DirectionalDipole, 0.999f, 1.3f), 0);
  EXPECT_NEAR(standard.total.x / exact, 1.0, 0.02);
  EXPECT_GT(directional.total.x / exact, 1.2);
}

}  // namespace
