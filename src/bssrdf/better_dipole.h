// better_dipole.h: d'Eon's "better dipole" BSSRDF.
//
// Source: d'Eon, "A Better Dipole", 2012 (and d'Eon & Irving 2011): one point source at depth z_r = 1/sigma_t' as
// the standard dipole, with the improved diffusion of photon beam diffusion: Grosjean's D_G, sigma_tr =
// sqrt(sigma_a / D_G), the extrapolated boundary z_b = 2 A D_G with A = (1 + 3 C2) / (1 - 2 C1), and the exitance
// C_phi fluence + C_E flux of the dipole, source strength rho'^2 (the same kernel as photon_beam_integrand in
// photon_beam_diffusion.h, at the single depth and without the beam's kappa correction). Selected as
// "better-dipole"; the fourth column of docs/models/total-reflectance.md.
// Parameterisation: per colour band, S_d = R(|x_o - x_i|) / (pi (1 - 2 C1(1/eta))) in 1/length^2 with the
// exit normalisation of the other models, so S = T12(w_i) S_d T21(w_o) (Fresnel applied by the caller).
// Known limits: depends on distance only; flat semi-infinite medium; no single-scattering term.
#ifndef LUCENT_BSSRDF_BETTER_DIPOLE_H
#define LUCENT_BSSRDF_BETTER_DIPOLE_H
#include "shared/bridge.h"
#include "bssrdf/photon_beam_diffusion.h"

LUCENT_SHADER_BEGIN

// Radial exitance profile R(r) [1/length^2] per unit refracted flux.
LUCENT_INLINE float better_dipole_R(BandMedium m, float eta, float r) {
  PhotonBeamMedium p = make_photon_beam_medium(m, eta);
  float z_r = 1.0f / p.sigma_t_prime;
  float z_v = z_r + 2.0f * p.z_b;
  float d_r = sqrt(r * r + z_r * z_r);
  float d_v = sqrt(r * r + z_v * z_v);
  float e_r = exp(-p.sigma_tr * d_r);
  float e_v = exp(-p.sigma_tr * d_v);
  float fluence = (e_r / d_r - e_v / d_v) / (4.0f * kPi * p.D_G);
  float flux = (z_r * (1.0f + p.sigma_tr * d_r) * e_r / (d_r * d_r * d_r) +
                z_v * (1.0f + p.sigma_tr * d_v) * e_v / (d_v * d_v * d_v)) /
               (4.0f * kPi);
  return p.rho_prime * p.rho_prime * (p.c_phi * fluence + p.c_e * flux);
}

// S_d(x_i; x_o) [1/length^2] for one band.
LUCENT_INLINE float better_dipole_Sd(BandMedium m, float eta, vec3 x_i, vec3 x_o) {
  return better_dipole_R(m, eta, length(x_o - x_i)) * kInvPi / (4.0f * fresnel_c_phi(1.0f / eta));
}

LUCENT_SHADER_END

#endif
