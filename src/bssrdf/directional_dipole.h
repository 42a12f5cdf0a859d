// directional_dipole.h: the directional dipole diffusion BSSRDF.
//
// Source: Frisvad, Hachisuka, Kjeldsen, "Directional Dipole Model for Subsurface Scattering", ACM TOG 34(1),
// Art. 5 (2014): ray source along the refracted direction w_12, modified tangent plane (eq. 23), corrected
// real-source distance for the front-lit case and 1/(3 sigma_t)^2 for the back-lit case (eqs. 24-25, note
// the unreduced sigma_t), extrapolation distance d_e = 2.131 D / sqrt(alpha') (eq. 21), A (eq. 22), the
// profile S'_d (eqs. 20 and 26) and C_phi, C_E (eqs. 30-31); equations as listed in
// shared/spec/bssrdf-models.md Section 1.
// Parameterisation: per colour band; w_i points toward the light (w_i . n_i > 0); lengths and coefficients in
// one consistent unit, S_d in 1/length^2; Fresnel transmittance T12 and T21 are applied by the caller.
// Degenerate case: when x_o - x_i is parallel to n_i (or x_o = x_i) the modified tangent plane is undefined and
// the authors' code returns NaN; here the true normal n_i is used, which keeps S_d finite and continuous.
// Known limits: not reciprocal (S(i->o) != S(o->i)); negative values of the dipole difference are clamped to 0.
#ifndef LUCENT_BSSRDF_DIRECTIONAL_DIPOLE_H
#define LUCENT_BSSRDF_DIRECTIONAL_DIPOLE_H
#include "shared/bridge.h"
#include "bssrdf/constants.h"
#include "bssrdf/fresnel.h"
#include "bssrdf/medium.h"

LUCENT_SHADER_BEGIN

// Direction of the refracted ray source, pointing into the medium (Section 1.2 of the spec).
LUCENT_INLINE vec3 refracted_direction(vec3 w_i, vec3 n_i, float eta) {
  float cos_i = dot(w_i, n_i);
  float inv_eta = 1.0f / eta;
  float sin2_t = inv_eta * inv_eta * max(0.0f, 1.0f - cos_i * cos_i);
  return -inv_eta * (w_i - cos_i * n_i) - n_i * sqrt(max(0.0f, 1.0f - sin2_t));
}

// Normal of the modified tangent plane: n_i projected onto the plane perpendicular to x_o - x_i (eq. 23).
LUCENT_INLINE vec3 modified_tangent_normal(vec3 n_i, vec3 x) {
  float r2 = dot(x, x);
  if (r2 < 1e-12f) return n_i;
  vec3 x_hat = x / sqrt(r2);
  vec3 projected = n_i - dot(n_i, x_hat) * x_hat;
  float len2 = dot(projected, projected);
  if (len2 < 1e-12f) return n_i;
  return projected / sqrt(len2);
}

// One source term S'_d(x, w, r) (eq. 26): x from the source origin to x_o, w the source direction,
// r the (corrected) distance.
LUCENT_INLINE float directional_dipole_source(BandMedium m, float eta, vec3 x, vec3 w, float r, vec3 n_o) {
  float c_phi = fresnel_c_phi(eta);
  float c_e = fresnel_c_e(eta);
  float normalization = 1.0f / (4.0f * fresnel_c_phi(1.0f / eta));
  float sigma_tr_r = m.sigma_tr * r;
  float one_plus = 1.0f + sigma_tr_r;
  float x_dot_w = dot(x, w);
  float r2 = r * r;
  float fluence_term = c_phi * (r2 / m.D + 3.0f * one_plus * x_dot_w);
  float flux_term = c_e * (3.0f * m.D * one_plus * dot(w, n_o) -
                           (one_plus + 3.0f * m.D * (3.0f * one_plus + sigma_tr_r * sigma_tr_r) / r2 * x_dot_w) *
                               dot(x, n_o));
  return normalization * kInvFourPiSquared * exp(-sigma_tr_r) / (r2 * r) * (fluence_term - flux_term);
}

// S_d(x_i, w_i; x_o) [1/length^2] for one band; w_i toward the light, n_i and n_o outward unit normals.
LUCENT_INLINE float directional_dipole_Sd(BandMedium m, float eta, vec3 x_i, vec3 w_i, vec3 n_i, vec3 x_o,
                                          vec3 n_o) {
  vec3 x = x_o - x_i;
  float r2 = dot(x, x);
  vec3 w_12 = refracted_direction(w_i, n_i, eta);
  float d_e = 2.131f * m.D / sqrt(m.alpha_prime);
  float A = (1.0f - fresnel_c_e(eta)) / (2.0f * fresnel_c_phi(eta));

  // Real source: corrected distance, front-lit or back-lit (eqs. 24-25).
  float mu_0 = -dot(n_o, w_12);
  float w_dot_x = dot(w_12, x);
  float cos_beta = -sqrt(max(0.0f, r2 - w_dot_x * w_dot_x) / (r2 + d_e * d_e));
  float d_r2 = r2 + 1.0f / (9.0f * m.sigma_t * m.sigma_t);
  if (mu_0 > 0.0f) d_r2 = r2 + m.D * mu_0 * (m.D * mu_0 - 2.0f * d_e * cos_beta);
  float d_r = sqrt(d_r2);

  // Virtual source mirrored in the modified tangent plane.
  vec3 n_star = modified_tangent_normal(n_i, x);
  vec3 x_v = x_i + 2.0f * A * d_e * n_star;
  vec3 w_v = w_12 - 2.0f * dot(w_12, n_star) * n_star;
  vec3 x_from_virtual = x_o - x_v;
  float d_v = length(x_from_virtual);

  float s_d = directional_dipole_source(m, eta, x, w_12, d_r, n_o) -
              directional_dipole_source(m, eta, x_from_virtual, w_v, d_v, n_o);
  return max(s_d, 0.0f);
}

LUCENT_SHADER_END

#endif
