// standard_dipole.h: the standard dipole diffusion BSSRDF.
//
// Source: Jensen, Marschner, Levoy, Hanrahan, "A Practical Model for Subsurface Light Transport",
// SIGGRAPH 2001, eqs. 4-6 (R_d, z_r, z_v, A with the Groenhuis F_dr) and the closed-form total diffuse
// reflectance. See shared/spec/bssrdf-models.md Section 2.
// Parameterisation: per colour band; S_d(x_i, w_i; x_o) = R_d(|x_o - x_i|) / (pi (1 - 2 C1(1/eta))), the Fresnel
// terms of S = F_t(w_o) S_d F_t(w_i) (Dal Corso et al. 2015, eq. 2) being applied by the caller.
// Exit normalisation: R_d is the dipole's radiant exitance, the flux that has already crossed the boundary (its
// boundary condition, through A, accounts for the light reflected back in). Jensen et al.'s S_d = R_d / pi,
// multiplied by F_t(w_o), lets only 1 - 2 C1(1/eta) of it out (0.939 at eta 1.3, 0.908 at 1.5): the exit Fresnel
// counted twice. Dividing by that integral, as the directional dipole (its 1 / (4 C_phi(1/eta))), photon beam
// diffusion and pbrt's separable BSSRDF do, makes the emergent flux R_total. Measured against exact transport
// (lucent slab, flat half-space, docs/models/total-reflectance.md): within 1-3% of exact for a' >= 0.95 with the
// normalisation, 6-10% dark without it at eta 1.3-1.5.
// Known limits: depends on distance only (no incident direction); assumes a flat semi-infinite medium;
// underestimates reflectance at low albedo (diffusion bias). eta = 1 uses A = 1 exactly (index-matched).
#ifndef LUCENT_BSSRDF_STANDARD_DIPOLE_H
#define LUCENT_BSSRDF_STANDARD_DIPOLE_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"
#include "bssrdf/medium.h"

LUCENT_SHADER_BEGIN

// Boundary mismatch A = (1 + F_dr) / (1 - F_dr); exactly 1 when index-matched.
LUCENT_INLINE float standard_dipole_A(float eta) {
  if (abs(eta - 1.0f) < 1e-6f) return 1.0f;
  float f_dr = fresnel_diffuse_reflectance_groenhuis(eta);
  return (1.0f + f_dr) / (1.0f - f_dr);
}

// Radial diffuse reflectance profile R_d(r) [1/length^2] for one band.
LUCENT_INLINE float standard_dipole_Rd(BandMedium m, float eta, float r) {
  float z_r = 1.0f / m.sigma_t_prime;
  float z_v = z_r + 4.0f * standard_dipole_A(eta) * m.D;
  float d_r = sqrt(r * r + z_r * z_r);
  float d_v = sqrt(r * r + z_v * z_v);
  float real_term = z_r * (1.0f + m.sigma_tr * d_r) * exp(-m.sigma_tr * d_r) / (d_r * d_r * d_r);
  float virtual_term = z_v * (1.0f + m.sigma_tr * d_v) * exp(-m.sigma_tr * d_v) / (d_v * d_v * d_v);
  return m.alpha_prime / (4.0f * kPi) * (real_term + virtual_term);
}

// 1 / (1 - 2 C1(1/eta)) = 1 / (4 C_phi(1/eta)): the exit normalisation (see the top of this file); exactly 1 when
// index-matched, as A (the moment polynomials are 0.4% off there).
LUCENT_INLINE float standard_dipole_exit_normalization(float eta) {
  if (abs(eta - 1.0f) < 1e-6f) return 1.0f;
  return 1.0f / (4.0f * fresnel_c_phi(1.0f / eta));
}

// S_d = R_d(r) / (pi (1 - 2 C1(1/eta))) [1/length^2] between entry x_i and exit x_o.
LUCENT_INLINE float standard_dipole_Sd(BandMedium m, float eta, vec3 x_i, vec3 x_o) {
  return standard_dipole_Rd(m, eta, length(x_o - x_i)) * kInvPi * standard_dipole_exit_normalization(eta);
}

// Total diffuse reflectance, the closed form of the integral of 2 pi r R_d(r) over r.
LUCENT_INLINE float standard_dipole_total_Rd(float alpha_prime, float eta) {
  float s = sqrt(3.0f * (1.0f - alpha_prime));
  float A = standard_dipole_A(eta);
  return 0.5f * alpha_prime * (1.0f + exp(-(4.0f / 3.0f) * A * s)) * exp(-s);
}

LUCENT_SHADER_END

#endif
