// diffuse_albedo.h: the albedo a diffuse shading baseline (diffuse-wrap, screen-space) gives a translucent material:
// the emergent flux per unit of transmitted flux on a flat, uniformly lit surface, for one band.
//
// It is the standard dipole's closed-form total diffuse reflectance R_total(alpha', eta) (standard_dipole.h, Jensen
// et al. 2001) times its exit normalisation 1 / (1 - 2 C1(1/eta)), so that with the boundary's Fresnel factors
//   L = F_t(w_i) E R_total F_t(w_o) / (pi (1 - 2 C1(1/eta)))
// is what the standard dipole's S_d gives on a semi-infinite flat slab under uniform irradiance E (the expectation
// of tests/flat_slab_expectation.h). Used for every material whatever its model (the other models have no closed
// form; their R_total differs from this by the few percent of docs/models/total-reflectance.md).
#ifndef LUCENT_BSSRDF_DIFFUSE_ALBEDO_H
#define LUCENT_BSSRDF_DIFFUSE_ALBEDO_H
#include "shared/bridge.h"
#include "bssrdf/medium.h"
#include "bssrdf/standard_dipole.h"

LUCENT_SHADER_BEGIN

// R_total of one band, from the material's coefficients (any length unit: alpha' is unitless).
LUCENT_INLINE float diffuse_total_reflectance(float sigma_a, float sigma_s, float g, float eta) {
  BandMedium m = make_band_medium(sigma_a, sigma_s, g);
  return standard_dipole_total_Rd(m.alpha_prime, eta);
}

// R_total / (1 - 2 C1(1/eta)) per band: the diffuse albedo such that L = F_t(w_i) E albedo F_t(w_o) / pi.
LUCENT_INLINE vec3 diffuse_albedo(vec3 sigma_a, vec3 sigma_s, vec3 g, float eta) {
  float k = standard_dipole_exit_normalization(eta);
  return vec3(diffuse_total_reflectance(sigma_a.x, sigma_s.x, g.x, eta) * k,
              diffuse_total_reflectance(sigma_a.y, sigma_s.y, g.y, eta) * k,
              diffuse_total_reflectance(sigma_a.z, sigma_s.z, g.z, eta) * k);
}

LUCENT_SHADER_END

#endif
