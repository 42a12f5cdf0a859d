// test_model_total_reflectance.cpp: the flat half-space total of a model (materials/model_total_reflectance.h)
// against independent values: the standard dipole's closed-form R_total (Jensen et al. 2001), the exit
// transmittance against the spec's exactly integrated Fresnel moments (4 C_phi(1/eta)), the directional dipole's
// normal-incidence symmetry, and the models' disagreement with exact transport (Monte Carlo slab,
// validated against Chandrasekhar's tables in test_slab.cpp) that docs/models/total-reflectance.md reports.
#include <gtest/gtest.h>

#include <cmath>

#include "bssrdf/fresnel.h"
#include "bssrdf/standard_dipole.h"
#include "lucent/material.h"
#include "materials/model_total_reflectance.h"
#include "transport/slab.h"

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

// The better dipole's plane integral in closed form: with e_r = exp(-sigma_tr z_r), e_v = exp(-sigma_tr z_v), the
// fluence integrates to 2 pi e / sigma_tr and the flux z (1 + sigma_tr d) e^{-sigma_tr d} / d^3 to 2 pi e, so
// R_total = rho'^2 (C_phi (e_r - e_v) / (2 D_G sigma_tr) + C_E (e_r + e_v) / 2). Improved-diffusion constants
// recomputed here in double precision from their definitions.
TEST(ModelTotalReflectance, BetterDipoleMatchesItsClosedFormTotal) {
  for (float albedo : {0.5f, 0.9f, 0.999f})
    for (float eta : {1.0f, 1.3f, 1.5f}) {
      const auto t = lucent::model_total_reflectance(material(lucent::BssrdfModel::BetterDipole, albedo, eta), 0.0);
      const double sigma_a = 1.0 - albedo, sigma_s = albedo, sigma_t = 1.0;
      const double D = (2.0 * sigma_a + sigma_s) / (3.0 * sigma_t * sigma_t), sigma_tr = std::sqrt(sigma_a / D);
      const double c_phi = lucent::shader::fresnel_c_phi(eta), c_e = lucent::shader::fresnel_c_e(eta);
      const double z_r = 1.0 / sigma_t, z_v = z_r + 2.0 * 2.0 * D * (1.0 - c_e) / (2.0 * c_phi);
      const double e_r = std::exp(-sigma_tr * z_r), e_v = std::exp(-sigma_tr * z_v);
      const double closed = albedo * albedo * (c_phi * (e_r - e_v) / (2.0 * D * sigma_tr) + c_e * (e_r + e_v) / 2.0);
      EXPECT_NEAR(t.radiosity.x * 4.0 * lucent::shader::fresnel_c_phi(1.0f / eta), closed, 2e-3 * closed)
          << "albedo " << albedo << " eta " << eta;
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

// The total depends on the albedo, g and eta, not on the length unit: a mean free path of 1e-30 mm or 1e30 mm gives
// the total of 1 mm in every model (they were NaN: the rings' radii and S_d's values left float's range).
TEST(ModelTotalReflectance, IsTheSameAtAnyMeanFreePath) {
  for (lucent::BssrdfModel model : {lucent::BssrdfModel::StandardDipole, lucent::BssrdfModel::DirectionalDipole,
                                    lucent::BssrdfModel::PhotonBeamDiffusion, lucent::BssrdfModel::BetterDipole}) {
    const lucent::Material unit = material(model, 0.9f, 1.3f);
    const double expected = lucent::model_total_reflectance(unit, 0.0).total.x;
    for (float scale : {1e-30f, 1e30f}) {
      lucent::Material m = unit;
      m.sigma_a *= scale, m.sigma_s *= scale;
      const double total = lucent::model_total_reflectance(m, 0.0).total.x;
      EXPECT_NEAR(total, expected, 1e-5 * expected) << lucent::to_string(model) << " sigma x " << scale;
    }
  }
}

}  // namespace
