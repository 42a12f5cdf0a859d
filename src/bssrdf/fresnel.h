// fresnel.h: Fresnel reflectance and transmittance of a smooth dielectric boundary, and the Fresnel moments.
//
// Sources: exact unpolarized Fresnel equations (e.g. pbrt-v4 FrDielectric); Fresnel moment polynomials of
// d'Eon & Irving 2011 as used by Frisvad et al. 2014 (shared/spec/bssrdf-models.md Section 1.4); the diffuse
// Fresnel reflectance fit of Groenhuis et al. 1983 used by the standard dipole (Jensen et al. 2001).
// eta = n_transmitted / n_incident. Valid for 0.5 < eta < 3; the polynomials are fits over 1 <= eta <= 2 and
// their mirror below 1.
#ifndef LUCENT_BSSRDF_FRESNEL_H
#define LUCENT_BSSRDF_FRESNEL_H
#include "shared/bridge.h"

LUCENT_SHADER_BEGIN

// Reflectance for light arriving at cos_theta_i (measured on the incident side, >= 0); 1 under total
// internal reflection.
LUCENT_INLINE float fresnel_reflectance(float eta, float cos_theta_i) {
  float cos_i = clamp(cos_theta_i, 0.0f, 1.0f);
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = sqrt(1.0f - sin2_t);
  float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

// T12 = 1 - F_r: the fraction transmitted through the boundary.
LUCENT_INLINE float fresnel_transmittance(float eta, float cos_theta_i) {
  return 1.0f - fresnel_reflectance(eta, cos_theta_i);
}

// 2 C1(eta): first Fresnel moment times two (hemispherical diffuse reflectance, F_dr), polynomial fit.
LUCENT_INLINE float fresnel_moment_2c1(float eta) {
  float e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
  if (eta < 1.0f)
    return 0.919317f - 3.4793f * eta + 6.75335f * e2 - 7.80989f * e3 + 4.98554f * e4 - 1.36881f * e5;
  return -9.23372f + 22.2272f * eta - 20.9292f * e2 + 10.2291f * e3 - 2.54396f * e4 + 0.254913f * e5;
}

// 3 C2(eta): second Fresnel moment times three, polynomial fit.
LUCENT_INLINE float fresnel_moment_3c2(float eta) {
  float e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
  if (eta < 1.0f)
    return 0.828421f - 2.62051f * eta + 3.36231f * e2 - 1.95284f * e3 + 0.236494f * e4 + 0.145787f * e5;
  return -1641.1f + 135.926f / e3 - 656.175f / e2 + 1376.53f / eta + 1213.67f * eta - 568.556f * e2 +
         164.798f * e3 - 27.0181f * e4 + 1.91826f * e5;
}

// C_phi(eta) = (1 - 2 C1) / 4 (Frisvad et al. 2014, eq. 30).
LUCENT_INLINE float fresnel_c_phi(float eta) { return 0.25f * (1.0f - fresnel_moment_2c1(eta)); }

// C_E(eta) = (1 - 3 C2) / 2 (Frisvad et al. 2014, eq. 31).
LUCENT_INLINE float fresnel_c_e(float eta) { return 0.5f * (1.0f - fresnel_moment_3c2(eta)); }

// F_dr, diffuse Fresnel reflectance, Groenhuis et al. 1983 fit (used by the standard dipole).
LUCENT_INLINE float fresnel_diffuse_reflectance_groenhuis(float eta) {
  return -1.440f / (eta * eta) + 0.710f / eta + 0.668f + 0.0636f * eta;
}

LUCENT_SHADER_END

#endif
